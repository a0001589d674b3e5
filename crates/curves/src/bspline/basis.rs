//! The B-spline basis functions `N_i^g` by the Cox–de Boor recursion (Cox, "The numerical
//! evaluation of B-splines", *J. Inst. Maths Applics* 10, 1972; de Boor, "On calculating
//! with B-splines", *J. Approx. Theory* 6, 1972; Piegl & Tiller, *The NURBS Book*, 2nd ed.,
//! §2.2, and §2.3 for the derivatives) and their derivatives.
//!
//! Cox–de Boor recursion, with the convention `0/0 := 0`:
//!
//! ```text
//! N_i^0(u) = 1  if u_i ≤ u < u_{i+1} and u_i < u_{i+1},   0 otherwise
//! N_i^g(u) = (u − u_i)/(u_{i+g} − u_i) · N_i^{g−1}(u) + (u_{i+g+1} − u)/(u_{i+g+1} − u_{i+1}) · N_{i+1}^{g−1}(u)
//! ```
//!
//! On the span `[u_s, u_{s+1})` only `N_{s−g}^g, …, N_s^g` are non-zero; they are computed
//! together with the triangular scheme (Piegl & Tiller §2.5, Algorithms A2.2 and A2.3). At
//! the right end `u = u_K` of the domain the last
//! non-empty span is taken as closed, so that the basis still sums to one there (the same
//! convention as the curve evaluation).

use super::knots::{BSPLINE_MAX_DEGREE, KnotVector, LOCAL, check_degree, check_values, ratio};
use crate::error::Error;
use crate::scalar::Scalar;

/// The triangular table of Cox–de Boor: row `p` (`0 ≤ p ≤ g`) holds
/// `N_{s−p}^p(u), …, N_s^p(u)` for the span `s` of `u`.
///
/// Each step is the convex split `N·(1 − α)`, `N·α` with `α = (u − u_i)/(u_{i+p} − u_i) ∈ [0, 1]`,
/// so no intermediate value exceeds 1 (safe in fixed-point).
#[allow(clippy::needless_range_loop)] // the indices are the textbook's
pub(crate) fn basis_table<S: Scalar, const M: usize>(
    kv: &KnotVector<S, M>,
    s: usize,
    u: S,
) -> [[S; LOCAL]; LOCAL] {
    let g = kv.degree().min(BSPLINE_MAX_DEGREE);
    let mut ndu = [[S::ZERO; LOCAL]; LOCAL];
    ndu[0][0] = S::ONE;
    for p in 1..=g {
        let mut saved = S::ZERO;
        for r in 0..p {
            // N_i^{p−1}, i = s − p + 1 + r, splits into N_{i−1}^p (right part) and N_i^p (left part).
            let i = (s + 1 + r).saturating_sub(p);
            let lo = kv.knot(i);
            let alpha = ratio(u - lo, kv.knot(i + p) - lo);
            let val = ndu[p - 1][r];
            ndu[p][r] = saved + (S::ONE - alpha) * val;
            saved = alpha * val;
        }
        ndu[p][p] = saved;
    }
    ndu
}

/// All non-zero basis functions at `u` (clamped to the domain `[u_g, u_K]`): returns the span
/// `s` and `[N_{s−g}^g(u), …, N_s^g(u), 0, …]` (entries above `g` are zero).
///
/// The values are non-negative and sum to one (partition of unity, Piegl & Tiller §2.2).
///
/// ```
/// use strak_curves::{KnotVector, bspline_basis};
///
/// // Clamped uniform quadratic, 5 de Boor points: T = (0,0,0,1,2,3,3,3)
/// let kv = KnotVector::<f64, 8>::new(2, &[0., 0., 0., 1., 2., 3., 3., 3.]).unwrap();
/// let (span, n) = bspline_basis(&kv, 1.5);
/// assert_eq!(span, 3);
/// assert_eq!(&n[..3], &[0.125, 0.75, 0.125]); // N_1, N_2, N_3
/// ```
pub fn bspline_basis<S: Scalar, const M: usize>(
    knots: &KnotVector<S, M>,
    u: S,
) -> (usize, [S; BSPLINE_MAX_DEGREE + 1]) {
    let (lo, hi) = knots.domain();
    let u = u.clamp_to(lo, hi);
    let s = knots.span(u);
    let g = knots.degree().min(BSPLINE_MAX_DEGREE);
    (s, basis_table(knots, s, u)[g])
}

/// The basis functions and their derivatives at `u` (clamped to the domain): row `k` of
/// `out` receives `[N_{s−g}^{g(k)}(u), …, N_s^{g(k)}(u), 0, …]`, the `k`-th derivative with
/// respect to `u`, for `k = 0 .. out.len()`. Returns `(s, valid)`: the span and the number of
/// leading rows that hold true values.
///
/// Rows above the degree are zero (and valid). Rows `k` with
/// [`KnotVector::max_basis_derivative`]` < k ≤ g` — only possible in fixed-point with very short
/// knot spans, where `N^{(k)} ~ (1/Δu)^k` exceeds the range — are set to zero and not counted
/// in `valid`.
///
/// The derivatives follow `N_i^{p(k)} = p·(N_i^{p−1(k−1)}/(u_{i+p} − u_i) − N_{i+1}^{p−1(k−1)}/(u_{i+p+1} − u_{i+1}))`.
///
/// ```
/// use strak_curves::{KnotVector, bspline_basis_derivs};
///
/// // Bernstein special case: knots 0,0,0,1,1,1 give B_i^2(u).
/// let kv = KnotVector::<f64, 8>::new(2, &[0., 0., 0., 1., 1., 1.]).unwrap();
/// let mut rows = [[0.0; 8]; 3];
/// let (span, valid) = bspline_basis_derivs(&kv, 0.5, &mut rows);
/// assert_eq!((span, valid), (2, 3));
/// assert_eq!(&rows[0][..3], &[0.25, 0.5, 0.25]); // (1−u)², 2u(1−u), u²
/// assert_eq!(&rows[1][..3], &[-1.0, 0.0, 1.0]); // −2(1−u), 2 − 4u, 2u
/// assert_eq!(&rows[2][..3], &[2.0, -4.0, 2.0]);
/// ```
pub fn bspline_basis_derivs<S: Scalar, const M: usize>(
    knots: &KnotVector<S, M>,
    u: S,
    out: &mut [[S; BSPLINE_MAX_DEGREE + 1]],
) -> (usize, usize) {
    let (lo, hi) = knots.domain();
    let u = u.clamp_to(lo, hi);
    let s = knots.span(u);
    let g = knots.degree().min(BSPLINE_MAX_DEGREE);
    let orders = knots.max_basis_derivative().min(g);
    let ndu = basis_table(knots, s, u);
    for (k, row) in out.iter_mut().enumerate() {
        *row = if k == 0 {
            ndu[g]
        } else if k <= orders {
            derivative_row(knots, s, &ndu, k)
        } else {
            [S::ZERO; LOCAL]
        };
    }
    let valid = if orders >= g {
        out.len()
    } else {
        out.len().min(orders + 1)
    };
    (s, valid)
}

/// `[N_{s−g}^{g(k)}(u), …, N_s^{g(k)}(u)]` for `1 ≤ k ≤ g`, from row `g − k` of the table by
/// `k` steps of the derivative recursion (multiply by the integer `p` first, then divide by
/// the knot difference: one rounding per step in fixed-point).
fn derivative_row<S: Scalar, const M: usize>(
    kv: &KnotVector<S, M>,
    s: usize,
    ndu: &[[S; LOCAL]; LOCAL],
    k: usize,
) -> [S; LOCAL] {
    let g = kv.degree().min(BSPLINE_MAX_DEGREE);
    let k = k.min(g);
    let p0 = g - k;
    let mut cur = ndu[p0];
    for q in 1..=k {
        let p = p0 + q;
        let f = S::from_i16(p as i16);
        let mut next = [S::ZERO; LOCAL];
        for j in 0..=p {
            // N_i^p with i = s − p + j; N_i^{p−1} is cur[j − 1], N_{i+1}^{p−1} is cur[j].
            let i = (s + j).saturating_sub(p);
            let mut v = S::ZERO;
            if j >= 1 {
                let t0 = kv.knot(i);
                v += ratio(cur[j - 1] * f, kv.knot(i + p) - t0);
            }
            if j < p {
                let t1 = kv.knot(i + 1);
                v -= ratio(cur[j] * f, kv.knot(i + p + 1) - t1);
            }
            next[j] = v;
        }
        cur = next;
    }
    cur
}

/// The highest derivative order `k ≤ g` whose f64 bound (every intermediate of
/// [`derivative_row`], over every non-empty span) fits the scalar's range.
pub(crate) fn basis_derivative_orders<S: Scalar, const M: usize>(kv: &KnotVector<S, M>) -> usize {
    let g = kv.degree().min(BSPLINE_MAX_DEGREE);
    let t = |i: usize| kv.knot(i).to_f64();
    let mut worst = [0.0_f64; LOCAL];
    for s in g..kv.control_point_count() {
        if t(s) >= t(s + 1) {
            continue;
        }
        for (k, w) in worst.iter_mut().enumerate().take(g + 1).skip(1) {
            let p0 = g - k;
            let mut cur = [0.0_f64; LOCAL];
            for c in cur.iter_mut().take(p0 + 1) {
                *c = 1.0; // |N^{p0}| ≤ 1
            }
            for q in 1..=k {
                let p = p0 + q;
                let f = p as f64;
                let mut next = [0.0_f64; LOCAL];
                for j in 0..=p {
                    let i = s + j - p;
                    let mut v = 0.0;
                    if j >= 1 {
                        let m = cur[j - 1] * f;
                        *w = w.max(m);
                        v += m / (t(i + p) - t(i));
                    }
                    if j < p {
                        let m = cur[j] * f;
                        *w = w.max(m);
                        v += m / (t(i + p + 1) - t(i + 1));
                    }
                    *w = w.max(v);
                    next[j] = v;
                }
                cur = next;
            }
        }
    }
    let mut orders = 0;
    for w in worst.iter().take(g + 1).skip(1) {
        if S::fits(*w) {
            orders += 1;
        } else {
            break;
        }
    }
    orders
}

/// A single basis function `N_i^g(u)` straight from the Cox–de Boor recursion (Piegl &
/// Tiller §2.5, Algorithm A2.4), for any knot slice `u_0 ≤ … ≤ u_{m−1}`.
///
/// `N_i^0` is 1 on the half-open `[u_i, u_{i+1})`, except at the right end `u = u_K`
/// (`K = m − g − 1`) of the domain, where only the last non-empty span of the domain is on —
/// the convention of [`bspline_basis`] and of the curve evaluation. `u` is not clamped: outside
/// `[u_i, u_{i+g+1}]` the result is 0.
///
/// # Errors
/// [`Error::DegreeTooHigh`], [`Error::KnotCount`] (fewer than `i + g + 2` knots),
/// [`Error::NonFinite`], [`Error::OutOfRange`], [`Error::KnotsUnsorted`].
///
/// ```
/// use strak_curves::basis_function;
/// let t = [0., 0., 0., 1., 2., 3., 3., 3.];
/// assert_eq!(basis_function(&t, 2, 2, 1.5).unwrap(), 0.75);
/// assert_eq!(basis_function(&t, 2, 2, 3.5).unwrap(), 0.0);
/// assert_eq!(basis_function(&t, 4, 2, 3.0).unwrap(), 1.0); // right end
/// ```
pub fn basis_function<S: Scalar>(knots: &[S], i: usize, degree: usize, u: S) -> Result<S, Error> {
    check_degree(degree)?;
    let m = knots.len();
    if i + degree + 2 > m {
        return Err(Error::KnotCount {
            expected: i + degree + 2,
            found: m,
        });
    }
    if !u.is_finite() {
        return Err(Error::NonFinite);
    }
    check_values(knots)?;
    let g = degree.min(BSPLINE_MAX_DEGREE);
    let t = |j: usize| knots.get(j).copied().unwrap_or(S::ZERO);
    // The last non-empty span of the domain [u_g, u_K], if the slice has a domain.
    let mut end_span = None;
    if m >= 2 * g + 2 {
        let count = m - g - 1;
        if t(g) < t(count) {
            end_span = (g..count)
                .rev()
                .find(|&s| t(s) < t(s + 1))
                .map(|s| (s, t(count)));
        }
    }
    let mut n = [S::ZERO; LOCAL];
    for (j, v) in n.iter_mut().enumerate().take(g + 1) {
        let idx = i + j;
        let (a, b) = (t(idx), t(idx + 1));
        let on = match end_span {
            // At the right end of the domain only the last non-empty span is "on".
            Some((s, e)) if u == e => s == idx,
            _ => a <= u && u < b,
        };
        if on {
            *v = S::ONE;
        }
    }
    for p in 1..=g {
        for j in 0..=(g - p) {
            let idx = i + j;
            let mut v = S::ZERO;
            if n[j] != S::ZERO {
                let a = t(idx);
                v += ratio(u - a, t(idx + p) - a) * n[j];
            }
            if n[j + 1] != S::ZERO {
                let b = t(idx + p + 1);
                v += ratio(b - u, b - t(idx + 1)) * n[j + 1];
            }
            n[j] = v;
        }
    }
    Ok(n[0])
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;
    use crate::scalar::{I16F16, I32F32};

    type Kv = KnotVector<f64, 32>;

    fn vectors() -> [(usize, &'static [f64]); 6] {
        [
            (0, &[0., 1., 2.5, 3.]),
            (1, &[0., 0., 1., 2., 2.]),
            (2, &[0., 0., 0., 1., 2., 3., 3., 3.]),
            (3, &[0., 0., 0., 0., 0.5, 0.5, 1.5, 2., 2., 2., 2.]),
            (3, &[-3., -2., -1., 0., 1., 2., 3., 4., 5.]),
            (
                4,
                &[0., 0., 0., 0., 0., 0.3, 0.3, 0.3, 0.3, 1., 1., 1., 1., 1.],
            ),
        ]
    }

    fn samples(kv: &Kv) -> impl Iterator<Item = f64> {
        let (lo, hi) = kv.domain();
        (0..=400).map(move |i| lo + (hi - lo) * f64::from(i) / 400.0)
    }

    #[test]
    fn partition_of_unity_and_non_negativity() {
        for (g, t) in vectors() {
            let kv = Kv::new(g, t).unwrap();
            for u in samples(&kv) {
                let (_, n) = bspline_basis(&kv, u);
                let sum: f64 = n.iter().sum();
                assert!((sum - 1.0).abs() < 1e-14, "g={g} u={u} sum={sum}");
                assert!(n.iter().all(|&x| x >= 0.0));
                assert!(n.iter().skip(g + 1).all(|&x| x == 0.0));
            }
        }
    }

    #[test]
    fn triangular_scheme_equals_single_functions_and_local_support() {
        for (g, t) in vectors() {
            let kv = Kv::new(g, t).unwrap();
            let count = kv.control_point_count();
            for u in samples(&kv) {
                let (s, n) = bspline_basis(&kv, u);
                for i in 0..count {
                    let single = basis_function(t, i, g, u).unwrap();
                    let expected = if i + g >= s && i <= s {
                        n[i + g - s]
                    } else {
                        0.0
                    };
                    assert!((single - expected).abs() < 1e-14, "g={g} i={i} u={u}");
                    // Local support: N_i^g vanishes outside [u_i, u_{i+g+1}].
                    if u < t[i] || u > t[i + g + 1] {
                        assert_eq!(single, 0.0);
                    }
                }
            }
        }
    }

    #[test]
    fn quadratic_example() {
        // T = (0,0,0,1,2,3,3,3), order 3: N_{2,3} = t/2·N_{2,2} + (3−t)/2·N_{3,2}
        let t = [0., 0., 0., 1., 2., 3., 3., 3.];
        for (u, v) in [
            (0.0, 0.0),
            (0.5, 0.125),
            (1.0, 0.5),
            (1.5, 0.75),
            (2.0, 0.5),
            (2.5, 0.125),
        ] {
            assert_eq!(basis_function(&t, 2, 2, u).unwrap(), v);
        }
        // N_0 = (1 − t)² on [0, 1)
        assert_eq!(basis_function(&t, 0, 2, 0.25).unwrap(), 0.5625);
    }

    fn binom(n: usize, k: usize) -> f64 {
        (0..k).fold(1.0, |acc, j| acc * (n - j) as f64 / (j + 1) as f64)
    }

    #[test]
    fn bernstein_special_case() {
        // Knots (0,…,0, 1,…,1), g + 1 times each, give the Bernstein polynomials.
        for g in 0..=BSPLINE_MAX_DEGREE {
            let mut t = [0.0; 16];
            for v in t.iter_mut().skip(g + 1).take(g + 1) {
                *v = 1.0;
            }
            let kv = Kv::new(g, &t[..2 * g + 2]).unwrap();
            for j in 0..=20 {
                let u = f64::from(j) / 20.0;
                let (s, n) = bspline_basis(&kv, u);
                assert_eq!(s, g);
                for i in 0..=g {
                    let b = binom(g, i) * u.powi(i as i32) * (1.0 - u).powi((g - i) as i32);
                    assert!((n[i] - b).abs() < 1e-14, "g={g} i={i} u={u}");
                }
            }
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        for (g, t) in vectors() {
            let kv = Kv::new(g, t).unwrap();
            let mut rows = [[0.0; LOCAL]; LOCAL];
            for u in samples(&kv) {
                let (s, valid) = bspline_basis_derivs(&kv, u, &mut rows);
                assert_eq!(valid, LOCAL);
                // Derivative of order k from finite differences of order k − 1 inside the span.
                let (a, b) = (kv.knot(s), kv.knot(s + 1));
                let h = 1e-6 * (b - a);
                if u - h <= a || u + h >= b {
                    continue;
                }
                let mut lo = [[0.0; LOCAL]; LOCAL];
                let mut hi = [[0.0; LOCAL]; LOCAL];
                bspline_basis_derivs(&kv, u - h, &mut lo);
                bspline_basis_derivs(&kv, u + h, &mut hi);
                for k in 1..=g {
                    for j in 0..=g {
                        let fd = (hi[k - 1][j] - lo[k - 1][j]) / (2.0 * h);
                        let scale = 1.0 + rows[k][j].abs();
                        assert!(
                            (fd - rows[k][j]).abs() < 1e-5 * scale,
                            "g={g} k={k} j={j} u={u}"
                        );
                    }
                }
                for row in rows.iter().skip(g + 1) {
                    assert!(row.iter().all(|&x| x == 0.0));
                }
                // Derivatives of a partition of unity sum to zero.
                for row in rows.iter().skip(1) {
                    assert!(row.iter().sum::<f64>().abs() < 1e-9);
                }
            }
        }
    }

    #[test]
    fn bernstein_derivatives_exact() {
        let kv = Kv::new(3, &[0., 0., 0., 0., 1., 1., 1., 1.]).unwrap();
        let mut rows = [[0.0; LOCAL]; 4];
        bspline_basis_derivs(&kv, 0.25, &mut rows);
        // B_0 = (1−u)³: −3(1−u)², 6(1−u), −6
        assert_eq!(rows[1][0], -3.0 * 0.75 * 0.75);
        assert_eq!(rows[2][0], 6.0 * 0.75);
        assert_eq!(rows[3][..4], [-6.0, 18.0, -18.0, 6.0]);
    }

    #[test]
    fn fixed_point_basis_and_derivative_limit() {
        let t: [f64; 8] = [0., 0., 0., 1., 2., 3., 3., 3.];
        let tf: [I32F32; 8] = t.map(I32F32::from_num);
        let kv = KnotVector::<I32F32, 8>::new(2, &tf).unwrap();
        let kd = Kv::new(2, &t).unwrap();
        assert_eq!(kv.max_basis_derivative(), 2);
        for i in 0..=60 {
            let u = f64::from(i) / 20.0;
            let (s, n) = bspline_basis(&kv, I32F32::from_num(u));
            let (sd, nd) = bspline_basis(&kd, u);
            assert_eq!(s, sd);
            for j in 0..3 {
                assert!((n[j].to_f64() - nd[j]).abs() < 1e-8);
            }
        }
        // Very short spans: the second derivative (~2/Δu²) does not fit I16F16.
        let e = 1.0 / 256.0;
        let short: [I16F16; 8] =
            [0., 0., 0., e, 2. * e, 3. * e, 3. * e, 3. * e].map(I16F16::from_num);
        let kv = KnotVector::<I16F16, 8>::new(2, &short).unwrap();
        assert_eq!(kv.max_basis_derivative(), 1);
        let mut rows = [[I16F16::ZERO; LOCAL]; 3];
        let (_, valid) = bspline_basis_derivs(&kv, I16F16::from_num(e * 1.5), &mut rows);
        assert_eq!(valid, 2);
        assert!(rows[2].iter().all(|&x| x == I16F16::ZERO));
        assert!((rows[1][1].to_f64()).abs() < 1e-3); // symmetric middle function: N' = 0
    }

    #[test]
    fn basis_function_errors() {
        let t = [0., 0., 1., 2., 2.];
        assert_eq!(
            basis_function(&t, 3, 1, 0.5).unwrap_err(),
            Error::KnotCount {
                expected: 6,
                found: 5
            }
        );
        assert_eq!(
            basis_function(&[0., 0., 2., 1., 2.], 0, 1, 0.5).unwrap_err(),
            Error::KnotsUnsorted { index: 3 }
        );
        assert_eq!(
            basis_function(&t, 0, 1, f64::NAN).unwrap_err(),
            Error::NonFinite
        );
        assert_eq!(
            basis_function(&[0.0; 20], 0, 8, 0.5).unwrap_err(),
            Error::DegreeTooHigh { max: 7, found: 8 }
        );
        let big = [0., 0., 1e6, 1e6].map(I16F16::saturating_from_num);
        assert_eq!(
            basis_function(&big, 0, 1, I16F16::ZERO).unwrap_err(),
            Error::OutOfRange
        );
    }
}
