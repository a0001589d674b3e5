//! The Bernstein basis `B_i^g(t) = C(g, i) (1 − t)^{g−i} tⁱ` (Farin, *Curves and Surfaces
//! for CAGD*, 5th ed., §4.1 "Bernstein Polynomials"; Piegl & Tiller, *The NURBS Book*, 2nd
//! ed., §1.3) and the binomial coefficients of Pascal's triangle.
//!
//! Values are computed with the triangle `B_i^r = (1 − t) B_i^{r−1} + t B_{i−1}^{r−1}` (the
//! de Casteljau scheme applied to the unit vectors): only convex combinations of numbers in
//! `[0, 1]`, so no binomial coefficient is ever formed in the scalar type and fixed-point
//! evaluation cannot overflow (the closed form multiplies large binomials by small powers,
//! which needs high precision for high degrees).

use super::int_scalar;
use crate::scalar::Scalar;

/// The binomial coefficient `C(n, k) = n! / (k! (n − k)!)`, exactly; `Some(0)` for `k > n`,
/// `None` when it exceeds `u64::MAX` (from `n = 68` on for the middle coefficients).
///
/// Computed with the exact integer recurrence `C(a, m) = C(a − 1, m − 1) · a / m`.
///
/// ```
/// use strak_curves::basis::binomial;
/// assert_eq!(binomial(4, 2), Some(6));
/// assert_eq!(binomial(3, 5), Some(0));
/// assert_eq!(binomial(100, 50), None);
/// ```
pub fn binomial(n: usize, k: usize) -> Option<u64> {
    if k > n {
        return Some(0);
    }
    let k = k.min(n - k);
    let mut r: u128 = 1;
    for m in 1..=k {
        // r = C(n − k + m − 1, m − 1); the product is divisible by m.
        r = r.checked_mul((n - k + m) as u128)? / (m as u128);
    }
    u64::try_from(r).ok()
}

/// Row `g = N − 1` of Pascal's triangle, `[C(g, 0), …, C(g, g)]`, built with the additive rule
/// `C(n, i) = C(n − 1, i − 1) + C(n − 1, i)` (Pascal's triangle);
/// `None` on `u64` overflow.
///
/// ```
/// use strak_curves::basis::pascal_row;
/// assert_eq!(pascal_row::<5>(), Some([1, 4, 6, 4, 1]));
/// assert_eq!(pascal_row::<0>(), Some([]));
/// ```
pub fn pascal_row<const N: usize>() -> Option<[u64; N]> {
    let mut row = [0_u64; N];
    if let Some(first) = row.first_mut() {
        *first = 1;
    }
    for level in 1..N {
        for j in (1..=level).rev() {
            row[j] = row[j].checked_add(row[j - 1])?;
        }
    }
    Some(row)
}

/// `C(n, k)` in `f64` (exact while the value stays below 2⁵³); 0 for `k > n`.
pub(crate) fn binomial_f64(n: usize, k: usize) -> f64 {
    if k > n {
        return 0.0;
    }
    let k = k.min(n - k);
    let mut r = 1.0_f64;
    for m in 1..=k {
        r = r * (n - k + m) as f64 / m as f64;
    }
    r
}

/// Fills `b[0..=level]` with the Bernstein values of degree `level` at `t` (`t` in `[0, 1]`)
/// and leaves the entries above `level` zero.
fn bernstein_row<S: Scalar>(t: S, level: usize, b: &mut [S]) {
    let s = S::ONE - t;
    for v in b.iter_mut() {
        *v = S::ZERO;
    }
    if let Some(first) = b.first_mut() {
        *first = S::ONE;
    }
    let top = level.min(b.len().saturating_sub(1));
    for r in 1..=top {
        for j in (1..=r).rev() {
            b[j] = b[j] * s + b[j - 1] * t;
        }
        b[0] *= s;
    }
}

/// All `N` Bernstein basis functions of degree `g = N − 1` at `t`:
/// `[B_0^g(t), …, B_g^g(t)]`. `t` is clamped to `[0, 1]`.
///
/// The values are non-negative and sum to one (partition of unity, which makes Bézier
/// curves affinely invariant; Farin §4.2).
///
/// ```
/// use strak_curves::basis::bernstein_all;
/// // B⃗²(t) = ((1−t)², 2(1−t)t, t²) at t = 1/4
/// assert_eq!(bernstein_all::<f64, 3>(0.25), [0.5625, 0.375, 0.0625]);
/// ```
pub fn bernstein_all<S: Scalar, const N: usize>(t: S) -> [S; N] {
    let t = t.clamp_to(S::ZERO, S::ONE);
    let mut b = [S::ZERO; N];
    bernstein_row(t, N.saturating_sub(1), &mut b);
    b
}

/// The single Bernstein basis function `B_i^g(t)` of degree `g = N − 1`; zero for `i ≥ N`.
/// `t` is clamped to `[0, 1]`.
///
/// ```
/// use strak_curves::basis::bernstein;
/// assert_eq!(bernstein::<f64, 4>(1, 0.5), 0.375);
/// assert_eq!(bernstein::<f64, 4>(7, 0.5), 0.0);
/// ```
pub fn bernstein<S: Scalar, const N: usize>(i: usize, t: S) -> S {
    bernstein_all::<S, N>(t).get(i).copied().unwrap_or(S::ZERO)
}

/// The derivatives `d/dt B_i^g(t)` of all `N` Bernstein functions of degree `g = N − 1`, by
/// `dB_{i,n}/dt = n (B_{i−1,n−1}(t) − B_{i,n−1}(t))` (Farin §4.3; with
/// `B_{−1,n−1} = B_{n,n−1} = 0`). Zero for `N ≤ 1`. `t` is clamped to `[0, 1]`.
///
/// Values are bounded by `g` in magnitude (fits every scalar type for `g ≤ 16 383`).
///
/// ```
/// use strak_curves::basis::bernstein_deriv_all;
/// assert_eq!(bernstein_deriv_all::<f64, 4>(0.5), [-0.75, -0.75, 0.75, 0.75]);
/// ```
pub fn bernstein_deriv_all<S: Scalar, const N: usize>(t: S) -> [S; N] {
    let mut out = [S::ZERO; N];
    let Some(g) = N.checked_sub(1) else {
        return out;
    };
    if g == 0 {
        return out;
    }
    let t = t.clamp_to(S::ZERO, S::ONE);
    let mut b = [S::ZERO; N];
    bernstein_row(t, g - 1, &mut b);
    let gs: S = int_scalar(g);
    let mut prev = S::ZERO;
    for (o, &cur) in out.iter_mut().zip(b.iter()) {
        *o = gs * (prev - cur);
        prev = cur;
    }
    out
}

/// The closed form `B_i^g(t) = C(g, i) (1 − t)^{g−i} tⁱ` in `f64`, for checks and
/// host-side tools; zero for `i > g`. `t` is clamped to `[0, 1]`.
///
/// ```
/// use strak_curves::basis::bernstein_f64;
/// assert_eq!(bernstein_f64(3, 2, 0.5), 0.375);
/// ```
pub fn bernstein_f64(g: usize, i: usize, t: f64) -> f64 {
    if i > g {
        return 0.0;
    }
    let t = t.clamp(0.0, 1.0);
    let mut r = binomial_f64(g, i);
    for _ in 0..i {
        r *= t;
    }
    for _ in 0..(g - i) {
        r *= 1.0 - t;
    }
    r
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)] // index loops mirror the matrix formulas
mod tests {
    use super::*;
    use crate::{I16F16, I32F32};

    #[test]
    fn pascal_triangle_rows() {
        assert_eq!(pascal_row::<1>(), Some([1]));
        assert_eq!(pascal_row::<2>(), Some([1, 1]));
        assert_eq!(pascal_row::<3>(), Some([1, 2, 1]));
        assert_eq!(pascal_row::<4>(), Some([1, 3, 3, 1]));
        assert_eq!(pascal_row::<5>(), Some([1, 4, 6, 4, 1]));
    }

    #[test]
    fn binomial_agrees_with_pascal_and_factorials() {
        let row = pascal_row::<61>().unwrap();
        for (k, &c) in row.iter().enumerate() {
            assert_eq!(binomial(60, k), Some(c));
        }
        // n!/(k!(n−k)!) for small n
        let fact = |n: u64| (1..=n).product::<u64>();
        for n in 0..=20_u64 {
            for k in 0..=n {
                let expect = fact(n) / (fact(k) * fact(n - k));
                assert_eq!(binomial(n as usize, k as usize), Some(expect));
                assert_eq!(binomial_f64(n as usize, k as usize), expect as f64);
            }
        }
        assert_eq!(binomial(67, 33), Some(14_226_520_737_620_288_370));
        assert_eq!(binomial(68, 34), None);
        assert_eq!(pascal_row::<69>(), None);
        assert_eq!(binomial(5, 6), Some(0));
    }

    #[test]
    fn cubic_values() {
        // B⃗³(t) = ((1−t)³, 3(1−t)²t, 3(1−t)t², t³) at t = 1/4.
        let b = bernstein_all::<f64, 4>(0.25);
        assert_eq!(b, [27.0 / 64.0, 27.0 / 64.0, 9.0 / 64.0, 1.0 / 64.0]);
        for i in 0..4 {
            assert_eq!(bernstein::<f64, 4>(i, 0.25), bernstein_f64(3, i, 0.25));
        }
        // clamped
        assert_eq!(bernstein_all::<f64, 4>(-1.0), [1.0, 0.0, 0.0, 0.0]);
        assert_eq!(bernstein_all::<f64, 4>(2.0), [0.0, 0.0, 0.0, 1.0]);
        assert_eq!(bernstein_all::<f64, 0>(0.5), [0.0_f64; 0]);
        assert_eq!(bernstein_all::<f64, 1>(0.5), [1.0]);
    }

    #[test]
    fn triangle_matches_closed_form() {
        for n in [2_usize, 5, 9] {
            for step in 0..=20 {
                let t = step as f64 / 20.0;
                for i in 0..=n {
                    let tri = match n {
                        2 => bernstein::<f64, 3>(i, t),
                        5 => bernstein::<f64, 6>(i, t),
                        _ => bernstein::<f64, 10>(i, t),
                    };
                    assert!(
                        (tri - bernstein_f64(n, i, t)).abs() < 1e-15,
                        "n={n} i={i} t={t}"
                    );
                }
            }
        }
    }

    #[test]
    fn symmetry_b_i_n_equals_b_n_minus_i_at_one_minus_t() {
        // Symmetry B_{i,n}(t) = B_{n−i,n}(1 − t); exact for dyadic t.
        for t in [0.0, 0.125, 0.25, 0.5, 0.875, 1.0] {
            let a = bernstein_all::<f64, 6>(t);
            let b = bernstein_all::<f64, 6>(1.0 - t);
            for i in 0..6 {
                assert_eq!(a[i], b[5 - i]);
            }
        }
        for t in [0.1, 0.3, 0.7] {
            let a = bernstein_all::<f64, 6>(t);
            let b = bernstein_all::<f64, 6>(1.0 - t);
            for i in 0..6 {
                assert!((a[i] - b[5 - i]).abs() < 1e-15);
            }
        }
    }

    #[test]
    fn partition_of_unity_and_positivity() {
        for step in 0..=50 {
            let t = step as f64 / 50.0;
            let b = bernstein_all::<f64, 8>(t);
            let sum: f64 = b.iter().sum();
            assert!((sum - 1.0).abs() < 1e-15);
            assert!(b.iter().all(|&v| v >= 0.0));
        }
        // fixed point: values are convex combinations, the sum loses at most a few ulps
        for step in 0..=16 {
            let t = I16F16::from_num(step) / I16F16::from_num(16);
            let b = bernstein_all::<I16F16, 4>(t);
            let sum: f64 = b.iter().map(|v| v.to_f64()).sum();
            assert!((sum - 1.0).abs() <= 8.0 * <I16F16 as Scalar>::EPSILON);
        }
    }

    #[test]
    fn derivative_formula() {
        // dB_{i,n}/dt = n (B_{i−1,n−1} − B_{i,n−1}), against the derivative of the closed form.
        for step in 1..20 {
            let t = step as f64 / 20.0;
            let d = bernstein_deriv_all::<f64, 5>(t);
            for (i, &di) in d.iter().enumerate() {
                let n = 4.0;
                let c = binomial_f64(4, i);
                let fi = i as f64;
                let exact = c
                    * (fi * t.powi(i as i32 - 1) * (1.0 - t).powi(4 - i as i32)
                        - (n - fi) * t.powi(i as i32) * (1.0 - t).powi(3 - i as i32));
                assert!((di - exact).abs() < 1e-14, "i={i} t={t}: {di} vs {exact}");
            }
        }
        // The maximum of B_{i,n} is at t = i/n.
        assert_eq!(bernstein_deriv_all::<f64, 5>(0.25)[1], 0.0);
        assert_eq!(bernstein_deriv_all::<f64, 5>(0.5)[2], 0.0);
        assert_eq!(bernstein_deriv_all::<f64, 5>(0.75)[3], 0.0);
        assert_eq!(bernstein_deriv_all::<f64, 1>(0.3), [0.0]);
        assert_eq!(bernstein_deriv_all::<f64, 2>(0.3), [-1.0, 1.0]);
        assert_eq!(bernstein_deriv_all::<f64, 0>(0.3), [0.0_f64; 0]);
    }

    #[test]
    fn f32_and_fixed_point_agree_with_f64() {
        for step in 0..=32 {
            let t = step as f64 / 32.0;
            let r = bernstein_all::<f64, 6>(t);
            let d = bernstein_deriv_all::<f64, 6>(t);
            let a = bernstein_all::<f32, 6>(t as f32);
            let da = bernstein_deriv_all::<f32, 6>(t as f32);
            let x = bernstein_all::<I16F16, 6>(I16F16::from_num(t));
            let dx = bernstein_deriv_all::<I16F16, 6>(I16F16::from_num(t));
            let y = bernstein_all::<I32F32, 6>(I32F32::from_num(t));
            let dy = bernstein_deriv_all::<I32F32, 6>(I32F32::from_num(t));
            for i in 0..6 {
                assert!((f64::from(a[i]) - r[i]).abs() < 1e-6);
                assert!((f64::from(da[i]) - d[i]).abs() < 1e-5);
                // five levels of truncating products: at most ~2 ulps per level
                assert!((x[i].to_f64() - r[i]).abs() <= 12.0 * <I16F16 as Scalar>::EPSILON);
                assert!((dx[i].to_f64() - d[i]).abs() <= 60.0 * <I16F16 as Scalar>::EPSILON);
                assert!((y[i].to_f64() - r[i]).abs() <= 12.0 * <I32F32 as Scalar>::EPSILON);
                assert!((dy[i].to_f64() - d[i]).abs() <= 60.0 * <I32F32 as Scalar>::EPSILON);
            }
        }
    }
}
