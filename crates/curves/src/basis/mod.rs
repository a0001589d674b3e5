//! Polynomial bases and the matrices between them (Farin, *Curves and Surfaces for CAGD*,
//! 5th ed., §4.1 "Bernstein Polynomials", §4.8 "The Matrix Form of a Bézier Curve", §6.2
//! "Lagrange Polynomials", §6.5 "Cubic Hermite Interpolation"; Piegl & Tiller, *The NURBS
//! Book*, 2nd ed., §1.2 "Power Basis Form of a Curve", §1.3 "Bézier Curves").
//!
//! | basis      | functions                          | module items                               |
//! |------------|------------------------------------|--------------------------------------------|
//! | monomial   | `M_i^g(t) = tⁱ`                    | [`horner`], [`horner_points`], [`MonomialCurve`] |
//! | Bernstein  | `B_i^g(t) = C(g,i)(1−t)^{g−i} tⁱ`  | [`binomial`], [`pascal_row`], [`bernstein_all`], [`bernstein_deriv_all`] |
//! | Lagrange   | `L_i^g(t) = Π_{k≠i} (t−u_k)/(u_i−u_k)` | [`LagrangeBasis`]                    |
//! | Hermite    | `H_0 … H_3` (cubic)                | [`hermite`], [`hermite_deriv`], [`HERMITE_K_INV`] |
//!
//! Basis changes are matrices: [`monomial_to_bernstein_matrix`] is `T_{B←M}`,
//! [`bernstein_to_monomial_matrix`] is `T_{M←B} = (T_{B←M})⁻¹`, and
//! [`bernstein_to_monomial`] / [`monomial_to_bernstein`] convert control points.
//!
//! Everything here is `no_std`, allocation-free and generic over [`Scalar`]
//! (f32, f64, fixed-point); arrays are sized by a const generic `N = g + 1` (the number of
//! basis functions of degree `g`). Basis functions on `[0, 1]` clamp their parameter to
//! `[0, 1]`; the Lagrange basis clamps to its first and last node.
//!
//! ```
//! use strak_curves::basis;
//!
//! // The cubic Bernstein basis at t = 1/2: (1, 3, 3, 1) / 8.
//! let b: [f64; 4] = basis::bernstein_all(0.5);
//! assert_eq!(b, [0.125, 0.375, 0.375, 0.125]);
//! ```
//!
//! # Basis changes
//! A polynomial has the monomial coefficient vector `a⃗` (`f = Σ a_j tʲ`) and the Bernstein
//! coefficient vector `b⃗` (`f = Σ b_i B_i^g`); `b⃗ = T_{B←M} a⃗`,
//! `a⃗ = T_{M←B} b⃗ = (T_{B←M})⁻¹ b⃗`, and the bases themselves are related by
//! `B⃗^g(t) = A_{B←M} M⃗^g(t)` with `T_{M←B} = A_{B←M}ᵀ` (Farin §4.8 writes the cubic case as
//! a matrix product).
//!
//! ## Derivation of the entries
//! **`A_{B←M}` and `T_{M←B}`.** Expanding `(1 − t)^{g−i}` binomially,
//! `B_i^g(t) = C(g,i) tⁱ (1−t)^{g−i} = Σ_{j≥i} (−1)^{j−i} C(g,i) C(g−i, j−i) tʲ`, and
//! `C(g,i) C(g−i, j−i) = C(g,j) C(j,i)`. So row `i` of `A_{B←M}` is
//! `A[i][j] = (−1)^{j−i} C(g,j) C(j,i)` (`j ≥ i`, else 0), and
//! `T_{M←B}[j][i] = A[i][j]`: `a_j = C(g,j) Σ_{i≤j} (−1)^{j−i} C(j,i) b_i = C(g,j) Δʲ b_0`
//! (the `j`-th forward difference of the Bézier points). Lower triangular, integer entries.
//!
//! **`T_{B←M}`.** Multiplying `tʲ` by `1 = (t + (1 − t))^{g−j}`,
//! `tʲ = Σ_{i≥j} C(g−j, i−j) tⁱ (1−t)^{g−i} = Σ_{i≥j} [C(g−j, i−j) / C(g,i)] B_i^g(t)`, and
//! `C(g−j, i−j)/C(g,i) = C(i,j)/C(g,j)`. Hence `b_i = Σ_{j≤i} C(i,j)/C(g,j) · a_j`:
//! `T_{B←M}[i][j] = C(i,j) / C(g,j)` (`j ≤ i`, else 0), lower triangular with entries in
//! `[0, 1]`. For `g = 3`: `[[1,0,0,0],[1,1/3,0,0],[1,2/3,1/3,0],[1,1,1,1]]`.
//!
//! ## Worked example
//! The Bernstein coefficients `(2, −2, 5, 1)` have the monomial vector `(2, −12, 33, −22)`:
//! `f(t) = 2 − 12t + 33t² − 22t³`. The cubic terms are `−2 − 6 − 15 + 1 = −22`, and
//! `f(1) = b_3 = 1` checks it; [`bernstein_to_monomial`] returns exactly these values.
//!
//! ## Numbers
//! Entries are computed in `f64` (binomials exact while below 2⁵³, i.e. for `g ≤ 50`) and rounded
//! once to the scalar type; `T_{M←B}` grows like `3^g` and leaves the fixed-point range early
//! (`I16F16`: degree ≤ 11, `I32F32`: degree ≤ 21), which is reported as
//! [`Error::OutOfRange`](crate::Error::OutOfRange). The point conversions also work in `f64` and round each result once.
//!
//! # The Hermite basis matrix
//! A cubic segment on `[0, 1]` in matrix form is
//! `Q(t) = [t³ t² t 1] · M_H · [P_0, P_1, P'_0, P'_1]ᵀ` with the Hermite basis matrix
//! [`HERMITE_K_INV`] `= M_H = [[2,−2,1,1],[−3,3,−2,−1],[0,0,1,0],[1,0,0,0]]` (Foley, van Dam,
//! Feiner & Hughes, *Computer Graphics: Principles and Practice*, 2nd ed., §11.2.2 "Hermite
//! Curves"), the inverse of the matrix `K` of the four end conditions. Column `j` of `M_H`
//! holds the coefficients of the `j`-th blending function in *descending* powers, and the
//! geometry vector lists both points before both tangents. Hence the columns of `M_H` are
//! `H_0, H_3, H_1, H_2` in this crate's order (start point, start tangent, end tangent, end
//! point; Farin §6.5).
//!
//! Both forms weight the end tangent as a derivative vector pointing *forward*, in the
//! direction of motion: `t³ − t² = −t²(1 − t) = H_2(t)`. `H_2` is negative on `(0, 1)`
//! because a forward end tangent pulls the curve back before the end point; do not negate
//! it. [`HERMITE_MONOMIAL`] is the same matrix in this crate's order.

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
