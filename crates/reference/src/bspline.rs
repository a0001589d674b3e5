//! B-splines: the Cox–de Boor recursion (seeds/002 "Cox De Boor-Rekursion", seeds/004
//! "Konstruktion von B-Splines"), its derivative, open B-spline curves `Σ d_i N_i^g(t)`, and
//! knot vector helpers.
//!
//! Notation: degree `g` (seeds/004 uses the order `k = g + 1`), `K` de Boor points
//! `d_0..d_{K−1}`, knot vector `u_0..u_{m−1}` with `m = K + g + 1` (open splines), domain
//! `[u_g, u_K]`.
//!
//! **End of the domain.** The recursion starts from the half-open indicator
//! `N_j^0(t) = 1` iff `u_j ≤ t < u_{j+1}` (and `u_j < u_{j+1}`), so at the right end `b = u_K`
//! every basis function would vanish. At exactly `t = b` the indicators are instead taken on
//! the half-open intervals `(u_j, u_{j+1}]`, i.e. `N_j^0(b) = 1` iff `u_j < b ≤ u_{j+1}`. Since
//! every `N_i^g` is one polynomial on the last non-degenerate interval `(u_j, b]`, this gives
//! exactly the **limit from the left**, and the domain becomes the closed interval `[u_g, u_K]`
//! (partition of unity holds at `b` too). The flag is decided once from the top-level degree
//! `g` and used throughout the recursion.

use crate::piece::find_piece;
use crate::vecops::weighted_sum;

/// The domain `[u_g, u_{m−g−1}] = [u_g, u_K]` of an open B-spline of degree `g` on `knots`.
///
/// # Panics
/// If `knots.len() < 2g + 2` (fewer than `g + 1` de Boor points).
///
/// ```
/// let k = [0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0];
/// assert_eq!(strak_ref::bspline_domain(&k, 2), (0.0, 3.0));
/// ```
pub fn bspline_domain(knots: &[f64], g: usize) -> (f64, f64) {
    assert!(
        knots.len() >= 2 * g + 2,
        "bspline_domain: need at least 2g + 2 knots"
    );
    (knots[g], knots[knots.len() - g - 1])
}

fn right_end_flag(knots: &[f64], g: usize, t: f64) -> bool {
    knots.len() >= 2 * g + 2 && t == knots[knots.len() - g - 1]
}

/// Cox–de Boor recursion with the 0/0 = 0 convention; `right_closed` selects `(u_j, u_{j+1}]`.
fn n_rec(knots: &[f64], i: usize, p: usize, t: f64, right_closed: bool) -> f64 {
    if p == 0 {
        let (a, b) = (knots[i], knots[i + 1]);
        let inside = if right_closed {
            a < t && t <= b
        } else {
            a <= t && t < b
        };
        return if a < b && inside { 1.0 } else { 0.0 };
    }
    let mut v = 0.0;
    let d1 = knots[i + p] - knots[i];
    if d1 != 0.0 {
        v += (t - knots[i]) / d1 * n_rec(knots, i, p - 1, t, right_closed);
    }
    let d2 = knots[i + p + 1] - knots[i + 1];
    if d2 != 0.0 {
        v += (knots[i + p + 1] - t) / d2 * n_rec(knots, i + 1, p - 1, t, right_closed);
    }
    v
}

/// Derivative recursion `N' = p/(u_{i+p}−u_i) N_i^{p−1} − p/(u_{i+p+1}−u_{i+1}) N_{i+1}^{p−1}`.
fn d_rec(knots: &[f64], i: usize, p: usize, t: f64, k: usize, right_closed: bool) -> f64 {
    if k == 0 {
        return n_rec(knots, i, p, t, right_closed);
    }
    if p == 0 {
        return 0.0;
    }
    let pf = p as f64;
    let mut v = 0.0;
    let d1 = knots[i + p] - knots[i];
    if d1 != 0.0 {
        v += pf / d1 * d_rec(knots, i, p - 1, t, k - 1, right_closed);
    }
    let d2 = knots[i + p + 1] - knots[i + 1];
    if d2 != 0.0 {
        v -= pf / d2 * d_rec(knots, i + 1, p - 1, t, k - 1, right_closed);
    }
    v
}

/// The B-spline basis function `N_i^g(t)` by the Cox–de Boor recursion of seeds/002:
/// `N_i^0(t) = 1` if `u_i ≤ t < u_{i+1}` and `u_i < u_{i+1}`, else `0`;
/// `N_i^g = (t − u_i)/(u_{i+g} − u_i) N_i^{g−1} + (u_{i+g+1} − t)/(u_{i+g+1} − u_{i+1}) N_{i+1}^{g−1}`,
/// a term with a zero denominator counting as `0` (0/0 = 0). At `t` equal to the right end of
/// the domain of degree `g` the limit from the left is returned (see the module docs). No
/// clamping: outside the domain the recursion is evaluated as is.
///
/// # Panics
/// If `i + g + 1 >= knots.len()`.
///
/// ```
/// // seeds/004: T = (0,0,0,1,2,3,3,3), N_{2,3} = t/2 N_{2,2} + (3−t)/2 N_{3,2}; at t = 1 it is 1/2.
/// let k = [0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0];
/// assert_eq!(strak_ref::cox_de_boor(&k, 2, 2, 1.0), 0.5);
/// assert_eq!(strak_ref::cox_de_boor(&k, 4, 2, 3.0), 1.0); // closed end: last basis is 1
/// ```
pub fn cox_de_boor(knots: &[f64], i: usize, g: usize, t: f64) -> f64 {
    assert!(i + g + 1 < knots.len(), "cox_de_boor: index out of range");
    n_rec(knots, i, g, t, right_end_flag(knots, g, t))
}

/// The `k`-th derivative of `N_i^g` at `t`, by repeated use of
/// `N_i^g' = g/(u_{i+g} − u_i) N_i^{g−1} − g/(u_{i+g+1} − u_{i+1}) N_{i+1}^{g−1}` (0/0 = 0),
/// down to the recursion of [`cox_de_boor`] (same end-of-domain rule). At a knot the
/// derivative from the right is returned (from the left at the domain end).
///
/// # Panics
/// If `i + g + 1 >= knots.len()`.
///
/// ```
/// // N_0^1 on knots (0, 1, 2) is the hat t, 2 − t: slope 1 on [0, 1), −1 on [1, 2).
/// assert_eq!(strak_ref::cox_de_boor_deriv(&[0.0, 1.0, 2.0], 0, 1, 0.5, 1), 1.0);
/// assert_eq!(strak_ref::cox_de_boor_deriv(&[0.0, 1.0, 2.0], 0, 1, 1.5, 1), -1.0);
/// ```
pub fn cox_de_boor_deriv(knots: &[f64], i: usize, g: usize, t: f64, k: usize) -> f64 {
    assert!(
        i + g + 1 < knots.len(),
        "cox_de_boor_deriv: index out of range"
    );
    d_rec(knots, i, g, t, k, right_end_flag(knots, g, t))
}

fn check_open(knots: &[f64], g: usize, ctrl: &[Vec<f64>]) {
    assert!(
        knots.windows(2).all(|w| w[0] <= w[1]),
        "bspline: knots must be non-decreasing"
    );
    assert!(ctrl.len() > g, "bspline: need more than g de Boor points");
    assert_eq!(
        knots.len(),
        ctrl.len() + g + 1,
        "bspline: need K + g + 1 knots"
    );
    let (a, b) = bspline_domain(knots, g);
    assert!(a < b, "bspline: empty domain");
}

/// A point `c(t) = Σ_{i=0}^{K−1} d_i N_i^g(t)` of the open B-spline of degree `g` with de Boor
/// points `ctrl` (seeds/002), `t` clamped to the domain [`bspline_domain`] (closed at both ends).
///
/// # Panics
/// If `knots.len() != ctrl.len() + g + 1`, `ctrl.len() <= g`, the knots decrease, or the
/// domain is empty.
///
/// ```
/// // Clamped quadratic: interpolates the first and last de Boor points.
/// let k = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
/// let d = [vec![0.0, 0.0], vec![1.0, 2.0], vec![2.0, 0.0]];
/// assert_eq!(strak_ref::bspline_point(&k, 2, &d, 1.0), vec![2.0, 0.0]);
/// assert_eq!(strak_ref::bspline_point(&k, 2, &d, 0.5), vec![1.0, 1.0]);
/// ```
pub fn bspline_point(knots: &[f64], g: usize, ctrl: &[Vec<f64>], t: f64) -> Vec<f64> {
    bspline_deriv(knots, g, ctrl, t, 0)
}

/// The `k`-th derivative `Σ d_i N_i^{g (k)}(t)` of the open B-spline ([`cox_de_boor_deriv`]),
/// `t` clamped to the domain. At an inner knot the derivative from the right, at the domain
/// end from the left.
///
/// # Panics
/// As [`bspline_point`].
///
/// ```
/// // Degree 1: the polyline; slope of the second leg.
/// let k = [0.0, 0.0, 1.0, 2.0, 2.0];
/// let d = [vec![0.0], vec![1.0], vec![3.0]];
/// assert_eq!(strak_ref::bspline_deriv(&k, 1, &d, 1.0, 1), vec![2.0]);
/// ```
pub fn bspline_deriv(knots: &[f64], g: usize, ctrl: &[Vec<f64>], t: f64, k: usize) -> Vec<f64> {
    check_open(knots, g, ctrl);
    let (a, b) = bspline_domain(knots, g);
    let t = t.clamp(a, b);
    let w: Vec<f64> = (0..ctrl.len())
        .map(|i| cox_de_boor_deriv(knots, i, g, t, k))
        .collect();
    weighted_sum(ctrl, &w)
}

/// The clamped uniform knot vector of degree `g` for `k_points` de Boor points on
/// `[u0, u1]`, by the seeds/004 formula (order `k = g + 1`, `n = K − 1`):
/// `t_j = 0` for `j < k`, `j − k + 1` for `k ≤ j ≤ n`, `n − k + 2` for `j > n`
/// (`j = 0..n+k`), then mapped linearly from `[0, n − k + 2]` to `[u0, u1]`.
/// That is `g + 1` copies of `u0`, `K − g − 1` equally spaced inner knots, `g + 1` copies of `u1`.
///
/// # Panics
/// If `k_points <= g`.
///
/// ```
/// // seeds/004: n = 4, k = 3 gives T = (0,0,0,1,2,3,3,3).
/// let t = strak_ref::clamped_uniform_knots(2, 5, 0.0, 3.0);
/// assert_eq!(t, vec![0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0]);
/// ```
pub fn clamped_uniform_knots(g: usize, k_points: usize, u0: f64, u1: f64) -> Vec<f64> {
    assert!(k_points > g, "clamped_uniform_knots: need K > g");
    let n = k_points - 1;
    let k = g + 1;
    let top = (n + 2 - k) as f64;
    (0..=n + k)
        .map(|j| {
            let tj = if j < k {
                0.0
            } else if j <= n {
                (j + 1 - k) as f64
            } else {
                top
            };
            u0 + (u1 - u0) * tj / top
        })
        .collect()
}

/// The `K + 1` uniform knots `0, 1/K, …, 1` of one period of a closed B-spline with `K`
/// de Boor points (see [`closed_bspline_point`](crate::closed_bspline_point)).
///
/// # Panics
/// If `k_points == 0`.
///
/// ```
/// assert_eq!(strak_ref::periodic_uniform_knots(4), vec![0.0, 0.25, 0.5, 0.75, 1.0]);
/// ```
pub fn periodic_uniform_knots(k_points: usize) -> Vec<f64> {
    assert!(k_points > 0, "periodic_uniform_knots: need K > 0");
    (0..=k_points).map(|i| i as f64 / k_points as f64).collect()
}

/// The index `j` of the knot span `[u_j, u_{j+1})` containing `t` within the domain of an open
/// B-spline of degree `g` (`g ≤ j ≤ K − 1`), with `t` clamped; at the domain end the last
/// non-degenerate span. Helpful to compare with span searches of fast evaluators.
///
/// # Panics
/// If the domain is empty or `knots.len() < 2g + 2`.
///
/// ```
/// let k = [0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0];
/// assert_eq!(strak_ref::bspline_span(&k, 2, 1.0), 3);
/// assert_eq!(strak_ref::bspline_span(&k, 2, 3.0), 4);
/// ```
pub fn bspline_span(knots: &[f64], g: usize, t: f64) -> usize {
    let kp = knots.len() - g - 1;
    // Distinct breakpoints of the domain with the span index that starts at each.
    let mut breaks = Vec::new();
    let mut starts = Vec::new();
    for j in g..kp {
        if knots[j] < knots[j + 1] {
            if breaks.is_empty() {
                breaks.push(knots[j]);
            }
            starts.push(j);
            breaks.push(knots[j + 1]);
        }
    }
    assert!(!starts.is_empty(), "bspline_span: empty domain");
    let (p, _) = find_piece(&breaks, t);
    starts[p]
}

#[cfg(test)]
mod tests {
    use super::*;

    const SEED_T: [f64; 8] = [0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0];

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn seed_004_example_knots_and_recursion() {
        // n = 4, k = 3 (order 3 = degree 2): T = (0,0,0,1,2,3,3,3).
        assert_eq!(clamped_uniform_knots(2, 5, 0.0, 3.0), SEED_T.to_vec());
        for j in 0..=30 {
            let t = j as f64 / 10.0;
            // N_{3,2} = (t−1) N_{3,1} + (3−t) N_{4,1}  (order notation) = N_3^1 (degree).
            let n32 = (t - 1.0) * cox_de_boor(&SEED_T, 3, 0, t)
                + (3.0 - t) * cox_de_boor(&SEED_T, 4, 0, t);
            assert!(close(cox_de_boor(&SEED_T, 3, 1, t), n32, 1e-15));
            // N_{2,3} = t/2 N_{2,2} + (3−t)/2 N_{3,2}.
            let n23 = t / 2.0 * cox_de_boor(&SEED_T, 2, 1, t)
                + (3.0 - t) / 2.0 * cox_de_boor(&SEED_T, 3, 1, t);
            assert!(close(cox_de_boor(&SEED_T, 2, 2, t), n23, 1e-15));
            // Written out piecewise: t²/2, (t(2−t) + (3−t)(t−1))/2, (3−t)²/2.
            let explicit = if t < 1.0 {
                t * t / 2.0
            } else if t < 2.0 {
                (t * (2.0 - t) + (3.0 - t) * (t - 1.0)) / 2.0
            } else {
                (3.0 - t) * (3.0 - t) / 2.0
            };
            assert!(
                close(cox_de_boor(&SEED_T, 2, 2, t), explicit, 1e-15),
                "t={t}"
            );
        }
        // N_{3,2} at the seed's picture: hat on [1, 3] with peak 1 at t = 2.
        assert_eq!(cox_de_boor(&SEED_T, 3, 1, 2.0), 1.0);
    }

    #[test]
    fn partition_of_unity_and_nonnegativity() {
        let vectors: Vec<(Vec<f64>, usize)> = vec![
            (SEED_T.to_vec(), 2),
            (
                vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 4.0, 4.0, 4.0, 4.0],
                3,
            ),
            (
                vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 5.0, 5.0, 5.0],
                3,
            ),
            (vec![0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0], 2), // uniform, unclamped
            (vec![0.0, 0.0, 0.0, 0.5, 0.5, 2.0, 3.0, 3.0, 3.0], 2), // inner double knot
            (vec![0.0, 0.0, 1.0, 1.0, 1.0, 2.5, 2.5], 1),
        ];
        for (knots, g) in vectors {
            let kp = knots.len() - g - 1;
            let (a, b) = bspline_domain(&knots, g);
            for j in 0..=200 {
                let t = a + (b - a) * j as f64 / 200.0;
                let mut sum = 0.0;
                for i in 0..kp {
                    let v = cox_de_boor(&knots, i, g, t);
                    assert!(v >= 0.0);
                    sum += v;
                }
                assert!(close(sum, 1.0, 1e-14), "knots {knots:?} t={t} sum={sum}");
                // Derivatives of a partition of unity sum to zero.
                let ds: f64 = (0..kp).map(|i| cox_de_boor_deriv(&knots, i, g, t, 1)).sum();
                assert!(close(ds, 0.0, 1e-12));
            }
        }
    }

    #[test]
    fn domain_end_is_left_limit() {
        let knots = [0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 4.0, 4.0, 4.0, 4.0];
        let eps = 1e-9;
        for i in 0..7 {
            let at = cox_de_boor(&knots, i, 3, 4.0);
            let before = cox_de_boor(&knots, i, 3, 4.0 - eps);
            assert!(close(at, before, 1e-8));
            let d_at = cox_de_boor_deriv(&knots, i, 3, 4.0, 1);
            let d_before = cox_de_boor_deriv(&knots, i, 3, 4.0 - eps, 1);
            assert!(close(d_at, d_before, 1e-6));
        }
        // Outside the domain nothing is clamped: all zero beyond the last knot.
        assert_eq!(cox_de_boor(&knots, 6, 3, 4.5), 0.0);
    }

    #[test]
    fn bernstein_special_case_of_seed_004() {
        // k = n + 1: T = (0,…,0, 1,…,1) (k times each) gives the Bernstein polynomials.
        for g in 1..=5 {
            let mut knots = vec![0.0; g + 1];
            knots.extend(vec![1.0; g + 1]);
            for j in 0..=20 {
                let t = j as f64 / 20.0;
                for i in 0..=g {
                    let b = crate::bernstein::bernstein(i, g, t);
                    assert!(close(cox_de_boor(&knots, i, g, t), b, 1e-14));
                    for k in 1..=g {
                        let bd = crate::bernstein::bernstein_deriv(i, g, t, k);
                        let nd = cox_de_boor_deriv(&knots, i, g, t, k);
                        assert!(close(nd, bd, 1e-10 * (1.0 + bd.abs())), "g{g} i{i} k{k}");
                    }
                }
            }
        }
    }

    #[test]
    fn derivative_matches_finite_difference() {
        let knots = [0.0, 0.0, 0.0, 0.0, 0.7, 1.5, 3.0, 4.0, 4.0, 4.0, 4.0];
        let ctrl = vec![
            vec![0.0, 0.0],
            vec![1.0, 2.0],
            vec![2.0, -1.0],
            vec![3.0, 3.0],
            vec![4.0, 0.0],
            vec![5.0, 1.0],
            vec![6.0, -2.0],
        ];
        let h = 1e-6;
        for j in 1..40 {
            let t = j as f64 / 10.0;
            // C² at simple knots: the third derivative jumps there, so skip it at knots.
            let at_knot = knots.iter().any(|&u| close(u, t, 1e-12));
            for k in 0..if at_knot { 2 } else { 3 } {
                let d = bspline_deriv(&knots, 3, &ctrl, t, k + 1);
                let p = bspline_deriv(&knots, 3, &ctrl, t + h, k);
                let m = bspline_deriv(&knots, 3, &ctrl, t - h, k);
                for c in 0..2 {
                    let fd = (p[c] - m[c]) / (2.0 * h);
                    assert!(close(d[c], fd, 1e-4 * (1.0 + fd.abs())), "t={t} k={k}");
                }
            }
        }
        assert_eq!(bspline_deriv(&knots, 3, &ctrl, 2.0, 4), vec![0.0, 0.0]);
    }

    #[test]
    fn clamped_ends_interpolate_and_multiplicity_g_interpolates() {
        let knots = [0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 4.0, 4.0, 4.0, 4.0];
        let ctrl: Vec<Vec<f64>> = (0..7).map(|i| vec![i as f64, (i * i) as f64]).collect();
        assert_eq!(bspline_point(&knots, 3, &ctrl, 0.0), ctrl[0]);
        let e = bspline_point(&knots, 3, &ctrl, 4.0);
        assert!(close(e[0], 6.0, 1e-14) && close(e[1], 36.0, 1e-14));
        // Clamping of t.
        assert_eq!(bspline_point(&knots, 3, &ctrl, -1.0), ctrl[0]);
        // End tangent interpolation: c'(0) = g/(u_{g+1} − u_1) (d_1 − d_0) = 3 (d_1 − d_0).
        assert_eq!(bspline_deriv(&knots, 3, &ctrl, 0.0, 1), vec![3.0, 3.0]);
        // Inner knot of multiplicity g = 2 interpolates d_2 (seeds/002 "Multiplizität").
        let k2 = [0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 2.0];
        let d2: Vec<Vec<f64>> = (0..5).map(|i| vec![i as f64, (i % 2) as f64]).collect();
        assert_eq!(bspline_point(&k2, 2, &d2, 1.0), d2[2]);
    }

    #[test]
    fn spans_and_knot_helpers() {
        assert_eq!(bspline_span(&SEED_T, 2, 0.0), 2);
        assert_eq!(bspline_span(&SEED_T, 2, 0.99), 2);
        assert_eq!(bspline_span(&SEED_T, 2, 2.5), 4);
        assert_eq!(bspline_span(&SEED_T, 2, 9.0), 4);
        let k = clamped_uniform_knots(3, 7, 0.0, 4.0);
        assert_eq!(
            k,
            vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 4.0, 4.0, 4.0, 4.0]
        );
        // seeds/004 second example: n = 8, k = 4 → (0,0,0,0,1,2,3,4,5,6,6,6,6).
        let k = clamped_uniform_knots(3, 9, 0.0, 6.0);
        assert_eq!(
            k,
            vec![
                0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 6.0, 6.0, 6.0
            ]
        );
        assert_eq!(
            clamped_uniform_knots(1, 2, -1.0, 1.0),
            vec![-1.0, -1.0, 1.0, 1.0]
        );
    }

    #[test]
    #[should_panic(expected = "K + g + 1 knots")]
    fn wrong_knot_count_panics() {
        let _ = bspline_point(&SEED_T, 2, &vec![vec![0.0]; 4], 0.5);
    }
}
