//! The cubic Hermite basis (Farin, *Curves and Surfaces for CAGD*, 5th ed., §6.5 "Cubic
//! Hermite Interpolation"; Burden & Faires, *Numerical Analysis*, §3.4).
//!
//! In the order used throughout this crate:
//!
//! | function | product form     | monomial form     | role                       |
//! |----------|------------------|-------------------|----------------------------|
//! | `H_0`    | `(1−t)²(1+2t)`   | `1 − 3t² + 2t³`   | weight of the start point `q_i`     |
//! | `H_1`    | `t(1−t)²`        | `t − 2t² + t³`    | weight of the start tangent `m_i`   |
//! | `H_2`    | `−t²(1−t)`       | `−t² + t³`        | weight of the end tangent `m_{i+1}` |
//! | `H_3`    | `(3−2t)t²`       | `3t² − 2t³`       | weight of the end point `q_{i+1}`   |
//!
//! so that a segment over `[u_i, u_{i+1}]` with `Δ_i = u_{i+1} − u_i` and
//! `s = (t − u_i)/Δ_i` is `c(t) = H_0(s) q_i + Δ_i H_1(s) m_i + Δ_i H_2(s) m_{i+1} + H_3(s) q_{i+1}`
//! (the tangents are derivatives with respect to `t`, hence the factor `Δ_i`).
//!
//! The relation to the Hermite basis matrix `M_H` ([`HERMITE_K_INV`]) is documented in the
//! [`basis`](crate::basis) module docs.

use crate::scalar::Scalar;

/// The Hermite basis matrix `M_H = K⁻¹` (Foley, van Dam, Feiner & Hughes, *Computer
/// Graphics: Principles and Practice*, 2nd ed., §11.2.2), the inverse of the matrix `K` of
/// the four end conditions: `Q(t) = [t³ t² t 1] · K⁻¹ · [P_0, P_1, P'_0, P'_1]ᵀ`.
///
/// Rows: powers `t³, t², t, 1`; columns: start point, end point, start tangent, end tangent
/// (i.e. the monomial coefficients of `H_0, H_3, H_1, H_2`, see the [`basis`](crate::basis) module docs).
///
/// ```
/// use strak_curves::basis::{HERMITE_K_INV, hermite};
/// // [t³ t² t 1] · K⁻¹ at t = 1/2 gives (H_0, H_3, H_1, H_2)(1/2)
/// let t: f64 = 0.5;
/// let row = [t * t * t, t * t, t, 1.0];
/// let mut blend = [0.0; 4];
/// for (j, b) in blend.iter_mut().enumerate() {
///     *b = (0..4).map(|i| row[i] * f64::from(HERMITE_K_INV[i][j])).sum();
/// }
/// let h: [f64; 4] = hermite(t);
/// assert_eq!(blend, [h[0], h[3], h[1], h[2]]);
/// ```
pub const HERMITE_K_INV: [[i8; 4]; 4] =
    [[2, -2, 1, 1], [-3, 3, -2, -1], [0, 0, 1, 0], [1, 0, 0, 0]];

/// The Hermite basis in the monomial basis: row `i` holds the coefficients of
/// `H_i` in ascending powers `1, t, t², t³`, i.e. `H⃗(t) = HERMITE_MONOMIAL · (1, t, t², t³)ᵀ`.
///
/// ```
/// use strak_curves::basis::{HERMITE_MONOMIAL, horner, hermite};
/// let h: [f64; 4] = hermite(0.25);
/// for i in 0..4 {
///     let c = HERMITE_MONOMIAL[i].map(f64::from);
///     assert_eq!(horner(&c, 0.25), h[i]);
/// }
/// ```
pub const HERMITE_MONOMIAL: [[i8; 4]; 4] =
    [[1, 0, -3, 2], [0, 1, -2, 1], [0, 0, -1, 1], [0, 0, 3, -2]];

/// The matrix [`HERMITE_K_INV`] in the scalar type (all entries are small integers, exact in
/// every type).
///
/// ```
/// use strak_curves::basis::hermite_k_inv;
/// let k: [[f32; 4]; 4] = hermite_k_inv();
/// assert_eq!(k[1], [-3.0, 3.0, -2.0, -1.0]);
/// ```
pub fn hermite_k_inv<S: Scalar>() -> [[S; 4]; 4] {
    HERMITE_K_INV.map(|row| row.map(|v| S::from_i16(i16::from(v))))
}

/// The cubic Hermite basis `[H_0(t), H_1(t), H_2(t), H_3(t)]`,
/// `t` clamped to `[0, 1]`:
/// `H_0 = (1−t)²(1+2t)`, `H_1 = t(1−t)²`, `H_2 = −t²(1−t)`, `H_3 = (3−2t)t²`.
///
/// Evaluated in the product form (every intermediate is at most 3 in magnitude).
///
/// ```
/// use strak_curves::basis::hermite;
/// assert_eq!(hermite(0.5_f64), [0.5, 0.125, -0.125, 0.5]);
/// assert_eq!(hermite(0.0_f64), [1.0, 0.0, 0.0, 0.0]);
/// ```
pub fn hermite<S: Scalar>(t: S) -> [S; 4] {
    hermite_deriv(t, 0)
}

/// The `k`-th derivatives `[H_0^{(k)}(t), …, H_3^{(k)}(t)]` of the cubic Hermite basis,
/// `t` clamped to `[0, 1]`; `k = 0` gives the values, `k ≥ 4` gives zeros.
///
/// | k | `H_0`       | `H_1`          | `H_2`      | `H_3`      |
/// |---|-------------|----------------|------------|------------|
/// | 1 | `−6t(1−t)`  | `(1−t)(1−3t)`  | `t(3t−2)`  | `6t(1−t)`  |
/// | 2 | `12t − 6`   | `6t − 4`       | `6t − 2`   | `6 − 12t`  |
/// | 3 | `12`        | `6`            | `6`        | `−12`      |
///
/// ```
/// use strak_curves::basis::hermite_deriv;
/// // interpolation conditions: H_1'(0) = 1, H_2'(1) = 1, the others vanish there
/// assert_eq!(hermite_deriv(0.0_f64, 1), [0.0, 1.0, 0.0, 0.0]);
/// assert_eq!(hermite_deriv(1.0_f64, 1), [0.0, 0.0, 1.0, 0.0]);
/// assert_eq!(hermite_deriv(0.3_f64, 3), [12.0, 6.0, 6.0, -12.0]);
/// ```
pub fn hermite_deriv<S: Scalar>(t: S, k: usize) -> [S; 4] {
    let t = t.clamp_to(S::ZERO, S::ONE);
    let s = S::ONE - t;
    let n = |v: i16| S::from_i16(v);
    match k {
        0 => [
            s * s * (S::ONE + S::TWO * t),
            t * s * s,
            -(t * t * s),
            (n(3) - S::TWO * t) * t * t,
        ],
        1 => [
            -(n(6) * t * s),
            s * (S::ONE - n(3) * t),
            t * (n(3) * t - S::TWO),
            n(6) * t * s,
        ],
        2 => [
            n(12) * t - n(6),
            n(6) * t - n(4),
            n(6) * t - S::TWO,
            n(6) - n(12) * t,
        ],
        3 => [n(12), n(6), n(6), n(-12)],
        _ => [S::ZERO; 4],
    }
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)] // index loops mirror the matrix formulas
mod tests {
    use super::*;
    use crate::basis::horner;
    use crate::{I16F16, I32F32};

    fn closed_form(t: f64) -> [f64; 4] {
        [
            (1.0 - t) * (1.0 - t) * (1.0 + 2.0 * t),
            t * (1.0 - t) * (1.0 - t),
            -t * t * (1.0 - t),
            (3.0 - 2.0 * t) * t * t,
        ]
    }

    #[test]
    fn basis_values() {
        assert_eq!(hermite(0.0_f64), [1.0, 0.0, 0.0, 0.0]);
        assert_eq!(hermite(1.0_f64), [0.0, 0.0, 0.0, 1.0]);
        assert_eq!(hermite(0.5_f64), [0.5, 0.125, -0.125, 0.5]);
        // t = 1/4: (27/32, 9/64, −3/64, 5/32)
        assert_eq!(
            hermite(0.25_f64),
            [27.0 / 32.0, 9.0 / 64.0, -3.0 / 64.0, 5.0 / 32.0]
        );
        for step in 0..=20 {
            let t = step as f64 / 20.0;
            let h = hermite(t);
            let c = closed_form(t);
            for i in 0..4 {
                assert!((h[i] - c[i]).abs() < 1e-15);
            }
            // the point weights form a partition of unity
            assert!((h[0] + h[3] - 1.0).abs() < 1e-15);
        }
        // clamped
        assert_eq!(hermite(-1.0_f64), hermite(0.0_f64));
        assert_eq!(hermite(2.0_f64), hermite(1.0_f64));
    }

    #[test]
    fn interpolation_conditions() {
        // d^r/dt^r H_{i,k}(t_j) = δ_ij δ_kr, in the order (H_0, H_1, H_2, H_3)
        assert_eq!(hermite(0.0_f64), [1.0, 0.0, 0.0, 0.0]);
        assert_eq!(hermite(1.0_f64), [0.0, 0.0, 0.0, 1.0]);
        assert_eq!(hermite_deriv(0.0_f64, 1), [0.0, 1.0, 0.0, 0.0]);
        assert_eq!(hermite_deriv(1.0_f64, 1), [0.0, 0.0, 1.0, 0.0]);
    }

    #[test]
    fn derivatives_match_differentiated_monomials() {
        for step in 0..=10 {
            let t = step as f64 / 10.0;
            for k in 0..5 {
                let d = hermite_deriv(t, k);
                for i in 0..4 {
                    // differentiate the monomial coefficients k times
                    let mut c = HERMITE_MONOMIAL[i].map(f64::from);
                    for _ in 0..k {
                        c = [c[1], 2.0 * c[2], 3.0 * c[3], 0.0];
                    }
                    assert!((d[i] - horner(&c, t)).abs() < 1e-14, "i={i} k={k} t={t}");
                }
            }
        }
    }

    #[test]
    fn k_inverse_is_the_inverse_of_k_and_holds_the_basis() {
        // K: the end conditions c(0), c(1), c'(0), c'(1) on [t³ t² t 1]
        let k = [[0, 0, 0, 1], [1, 1, 1, 1], [0, 0, 1, 0], [3, 2, 1, 0]];
        for i in 0..4 {
            for j in 0..4 {
                let p: i32 = (0..4)
                    .map(|m| k[i][m] * i32::from(HERMITE_K_INV[m][j]))
                    .sum();
                assert_eq!(p, i32::from(i == j));
            }
        }
        // columns of K⁻¹ (descending powers) = H_0, H_3, H_1, H_2 (ascending in HERMITE_MONOMIAL)
        let order = [0, 3, 1, 2];
        for (col, &h) in order.iter().enumerate() {
            for power in 0..4 {
                assert_eq!(HERMITE_K_INV[3 - power][col], HERMITE_MONOMIAL[h][power]);
            }
        }
        // 003's H_{r+1,1} = t³ − t² has the same sign as 002's H_2 = −t²(1 − t)
        assert_eq!(HERMITE_MONOMIAL[2], [0, 0, -1, 1]);
        let kf: [[f64; 4]; 4] = hermite_k_inv();
        assert_eq!(kf[0], [2.0, -2.0, 1.0, 1.0]);
        let kx: [[I16F16; 4]; 4] = hermite_k_inv();
        assert_eq!(kx[3][0], I16F16::ONE);
    }

    #[test]
    fn f32_and_fixed_point_agree_with_f64() {
        for step in 0..=16 {
            let t = step as f64 / 16.0;
            for k in 0..4 {
                let r = hermite_deriv(t, k);
                let a = hermite_deriv(t as f32, k);
                let x = hermite_deriv(I16F16::from_num(t), k);
                let y = hermite_deriv(I32F32::from_num(t), k);
                for i in 0..4 {
                    assert!((f64::from(a[i]) - r[i]).abs() < 1e-6);
                    assert!((x[i].to_f64() - r[i]).abs() <= 4.0 * <I16F16 as Scalar>::EPSILON);
                    assert!((y[i].to_f64() - r[i]).abs() <= 4.0 * <I32F32 as Scalar>::EPSILON);
                }
            }
        }
    }
}
