//! Polynomial bases (seeds/000 and 002 "Polynombasen", seeds/003 "Hermite-Matrix",
//! seeds/004 "Bernstein-Polynome") and the matrices between them.
//!
//! | basis      | functions                          | module items                               |
//! |------------|------------------------------------|--------------------------------------------|
//! | monomial   | `M_i^g(t) = tⁱ`                    | [`horner`], [`horner_points`], [`MonomialCurve`] |
//! | Bernstein  | `B_i^g(t) = C(g,i)(1−t)^{g−i} tⁱ`  | [`binomial`], [`pascal_row`], [`bernstein_all`], [`bernstein_deriv_all`] |
//! | Lagrange   | `L_i^g(t) = Π_{k≠i} (t−u_k)/(u_i−u_k)` | [`LagrangeBasis`]                    |
//! | Hermite    | `H_0 … H_3` (cubic)                | [`hermite`], [`hermite_deriv`], [`HERMITE_K_INV`] |
//!
//! Basis changes are matrices (seeds/000 "Basistransformation"): [`monomial_to_bernstein_matrix`]
//! is `T_{B←M}`, [`bernstein_to_monomial_matrix`] is `T_{M←B} = (T_{B←M})⁻¹`, and
//! [`bernstein_to_monomial`] / [`monomial_to_bernstein`] convert control points.
//!
//! Everything here is `no_std`, allocation-free and generic over [`Scalar`](crate::Scalar)
//! (f32, f64, fixed-point); arrays are sized by a const generic `N = g + 1` (the number of
//! basis functions of degree `g`). Basis functions on `[0, 1]` clamp their parameter to
//! `[0, 1]`; the Lagrange basis clamps to its first and last node.
//!
//! ```
//! use strak_curves::basis;
//!
//! // The cubic Bernstein basis at t = 1/2 (seeds/000): (1, 3, 3, 1) / 8.
//! let b: [f64; 4] = basis::bernstein_all(0.5);
//! assert_eq!(b, [0.125, 0.375, 0.375, 0.125]);
//! ```

mod bernstein;
mod hermite;
mod lagrange;
mod monomial;
mod transform;

pub use bernstein::*;
pub use hermite::*;
pub use lagrange::*;
pub use monomial::*;
pub use transform::*;

use crate::scalar::Scalar;

/// The largest degree the polynomial types of this crate accept: degrees enter evaluation as
/// small integers ([`Scalar::from_i16`]), so they must fit an `i16`.
pub const MAX_DEGREE: usize = i16::MAX as usize;

/// The integer `n` as a scalar, saturating at [`MAX_DEGREE`] (callers validate the degree).
#[inline]
pub(crate) fn int_scalar<S: Scalar>(n: usize) -> S {
    S::from_i16(i16::try_from(n).unwrap_or(i16::MAX))
}

/// `n · (n − 1) ⋯ (n − k + 1) = n!/(n − k)!` in `f64` (the falling factorial; 0 for `k > n`).
pub(crate) fn falling_factorial_f64(n: usize, k: usize) -> f64 {
    if k > n {
        return 0.0;
    }
    let mut r = 1.0_f64;
    for m in 0..k {
        r *= (n - m) as f64;
    }
    r
}
