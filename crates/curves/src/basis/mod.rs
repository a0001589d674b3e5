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
//! Everything here is `no_std`, allocation-free and generic over [`Scalar`]
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
//!
//! # Basis changes
//! Notation of seeds/000: a polynomial has the monomial coefficient vector `a⃗`
//! (`f = Σ a_j tʲ`) and the Bernstein coefficient vector `b⃗` (`f = Σ b_i B_i^g`);
//! `b⃗ = T_{B←M} a⃗`, `a⃗ = T_{M←B} b⃗ = (T_{B←M})⁻¹ b⃗`, and the bases themselves are related by
//! `B⃗^g(t) = A_{B←M} M⃗^g(t)` with `T_{M←B} = A_{B←M}ᵀ`.
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
//! `[0, 1]`. For `g = 3` this is the matrix of seeds/000:
//! `[[1,0,0,0],[1,1/3,0,0],[1,2/3,1/3,0],[1,1,1,1]]`.
//!
//! ## Erratum in seeds/000
//! The worked example converts the Bernstein coefficients `(2, −2, 5, 1)` and prints the result
//! `2 − 12t + 33t² − 23t³`. Its own intermediate lines sum the cubic terms to
//! `−2 − 6 − 15 + 1 = −22`, and `f(1)` must equal `b_3 = 1`: the correct monomial vector is
//! `(2, −12, 33, −22)`, which is what [`bernstein_to_monomial`] returns.
//!
//! ## Numbers
//! Entries are computed in `f64` (binomials exact while below 2⁵³, i.e. for `g ≤ 50`) and rounded
//! once to the scalar type; `T_{M←B}` grows like `3^g` and leaves the fixed-point range early
//! (`I16F16`: degree ≤ 11, `I32F32`: degree ≤ 21), which is reported as
//! [`Error::OutOfRange`](crate::Error::OutOfRange). The point conversions also work in `f64` and round each result once.
//!
//! # The Hermite basis and the matrix K⁻¹ of seeds/003
//! seeds/003 writes a cubic segment on `[0, 1]` as
//! `Q(t) = [t³ t² t 1] · K⁻¹ · [P_r, P_{r+1}, P'_r, P'_{r+1}]ᵀ` with
//! [`HERMITE_K_INV`] `= [[2,−2,1,1],[−3,3,−2,−1],[0,0,1,0],[1,0,0,0]]`. Column `j` of `K⁻¹`
//! holds the coefficients of the `j`-th blending function in *descending* powers, and the
//! geometry vector lists both points before both tangents. Hence the columns of `K⁻¹` are
//! `H_0, H_3, H_1, H_2` of seeds/002 (003 calls them `H_{r,0}, H_{r+1,0}, H_{r,1}, H_{r+1,1}`).
//!
//! The formulas agree, including the sign of the end-tangent function:
//! 003's `H_{r+1,1}(t) = t³ − t²` is 002's `H_2(t) = −t²(1 − t)`; both weight the end
//! tangent as a derivative vector pointing *forward* (in the direction of motion). The
//! difference is only in the drawings: seeds/002 warns ("Vorsicht") that its figure draws the
//! arrow at the end point *against* the vector `m` used in the formula. `H_2` is negative on
//! `(0, 1)` because a forward end tangent pulls the curve back before the end point; do not
//! negate it. [`HERMITE_MONOMIAL`] is the same matrix in the order of seeds/002.

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
