//! Closed (periodic) B-splines (seeds/002: "geschlossene Splines", `K = n` segments, one knot
//! per de Boor point and period).
//!
//! **Construction (by definition).** One period has `K` de Boor points `d_0..d_{K−1}` and
//! `K + 1` knots `u_0 < … ≤ u_K` (period `T = u_K − u_0`). The knots are extended periodically,
//! `ũ_{j + qK} = u_j + qT` for all integers `j, q`, and `Ñ_j^g` denotes the ordinary
//! Cox–de Boor basis function on `ũ` (support `[ũ_j, ũ_{j+g+1}]`). The periodic basis function
//! of `d_i` is the sum of its shifted copies, `N_i^{per}(t) = Σ_q Ñ_{i+qK}^g(t)`, and the curve is
//! `c(t) = Σ_{i=0}^{K−1} d_i N_i^{per}(t)`. As in the open case (seeds/002), `d_i` influences
//! `[u_i, u_{i+g+1}]` (mod `T`).
//!
//! Equivalently (checked in the tests): `c` on `[u_0, u_K]` is the open B-spline on the knots
//! `ũ_{−g}..ũ_{K+g}` ([`periodic_extended_knots`]) with the de Boor points
//! `d_{K−g}, …, d_{K−1}, d_0, …, d_{K−1}` (the *last* `g` points prepended). For a uniform cubic
//! this gives `c(u_0) = (d_{K−3} + 4 d_{K−2} + d_{K−1}) / 6`.
//!
//! The parameter **wraps**: `t` is reduced modulo `T` into `[u_0, u_K)` (so `u_K` evaluates
//! as `u_0`, the same point by periodicity).

use crate::bspline::cox_de_boor_deriv;
use crate::vecops::weighted_sum;

fn check_closed(g: usize, k_points: usize, period_knots: &[f64]) {
    assert!(k_points > g, "closed_bspline: need K > g de Boor points");
    assert_eq!(
        period_knots.len(),
        k_points + 1,
        "closed_bspline: need K + 1 knots per period"
    );
    assert!(
        period_knots.windows(2).all(|w| w[0] <= w[1]),
        "closed_bspline: knots must be non-decreasing"
    );
    assert!(
        period_knots[0] < period_knots[k_points],
        "closed_bspline: empty period"
    );
}

/// The periodically extended knots `ũ_{−g}, …, ũ_{K+g}` (`K + 2g + 1` values) with
/// `ũ_{j+qK} = u_j + q (u_K − u_0)`; index `j` of the result is `ũ_{j−g}`.
///
/// # Panics
/// If `period_knots` has fewer than two entries.
///
/// ```
/// let e = strak_ref::periodic_extended_knots(2, &[0.0, 1.0, 3.0, 4.0]);
/// assert_eq!(e, vec![-3.0, -1.0, 0.0, 1.0, 3.0, 4.0, 5.0, 7.0]);
/// ```
pub fn periodic_extended_knots(g: usize, period_knots: &[f64]) -> Vec<f64> {
    assert!(
        period_knots.len() >= 2,
        "periodic_extended_knots: need K + 1 >= 2 knots"
    );
    let k = (period_knots.len() - 1) as i64;
    let (first, last) = (period_knots[0], period_knots[k as usize]);
    let period = last - first;
    // The period boundaries u_0 + qT, exact where they are given knots (q = 0, 1).
    let boundary = |q: i64| match q {
        0 => first,
        1 => last,
        _ => first + q as f64 * period,
    };
    (-(g as i64)..=k + g as i64)
        .map(|j| {
            let r = j.rem_euclid(k) as usize;
            let q = j.div_euclid(k);
            // Knots equal to a period boundary map to the shifted boundary exactly, so that a
            // repeated seam knot stays repeated (u_{K−1} − T would round away from u_0).
            if period_knots[r] == first {
                boundary(q)
            } else if period_knots[r] == last {
                boundary(q + 1)
            } else {
                period_knots[r] + q as f64 * period
            }
        })
        .collect()
}

fn wrap(period_knots: &[f64], t: f64) -> f64 {
    let a = period_knots[0];
    let b = period_knots[period_knots.len() - 1];
    let period = b - a;
    let mut s = t - period * ((t - a) / period).floor();
    if !(s >= a && s < b) {
        s = a;
    }
    s
}

/// The `k`-th derivative of the periodic basis function `N_i^{per}` of a closed B-spline
/// (sum of the shifted copies `Ñ_{i+qK}^g`, see the module docs), `t` wrapped into the period.
/// `k = 0` gives the value.
///
/// # Panics
/// If `period_knots.len() != K + 1` with `K = k_points`, `K <= g`, `i >= K`, the knots
/// decrease, or the period is empty.
///
/// ```
/// // Uniform cubic, K = 4: at t = u_0 the weights are 1/6, 4/6, 1/6 on d_1, d_2, d_3.
/// let u = strak_ref::periodic_uniform_knots(4);
/// let w: Vec<f64> = (0..4).map(|i| strak_ref::closed_bspline_basis(3, 4, &u, i, 0.0, 0)).collect();
/// assert!((w[0]).abs() < 1e-15 && (w[2] - 4.0 / 6.0).abs() < 1e-15);
/// ```
pub fn closed_bspline_basis(
    g: usize,
    k_points: usize,
    period_knots: &[f64],
    i: usize,
    t: f64,
    k: usize,
) -> f64 {
    check_closed(g, k_points, period_knots);
    assert!(i < k_points, "closed_bspline_basis: index out of range");
    let ext = periodic_extended_knots(g, period_knots);
    let t = wrap(period_knots, t);
    let kk = k_points as i64;
    let gi = g as i64;
    // Shifted copies j = i + qK that can be non-zero on [u_0, u_K): −g ≤ j ≤ K − 1.
    let mut v = 0.0;
    let mut j = i as i64;
    while j >= -gi {
        // Ñ_j is basis function index j + g of `ext`.
        v += cox_de_boor_deriv(&ext, (j + gi) as usize, g, t, k);
        j -= kk;
    }
    v
}

/// A point `c(t) = Σ_{i=0}^{K−1} d_i N_i^{per}(t)` of the closed B-spline of degree `g` with de
/// Boor points `ctrl` (`K = ctrl.len()`) and one period of knots `period_knots`
/// (`u_0..u_K`), by the definition in the module docs; `t` wraps around the period.
///
/// # Panics
/// If `period_knots.len() != ctrl.len() + 1`, `ctrl.len() <= g`, the knots decrease, or the
/// period is empty.
///
/// ```
/// // Uniform quadratic closed spline on a square: c(u_0) is the midpoint of d_2 and d_3.
/// let d = [vec![1.0, 0.0], vec![0.0, 1.0], vec![-1.0, 0.0], vec![0.0, -1.0]];
/// let u = strak_ref::periodic_uniform_knots(4);
/// let p = strak_ref::closed_bspline_point(2, &d, &u, 0.0);
/// assert!((p[0] + 0.5).abs() < 1e-15 && (p[1] + 0.5).abs() < 1e-15);
/// ```
pub fn closed_bspline_point(g: usize, ctrl: &[Vec<f64>], period_knots: &[f64], t: f64) -> Vec<f64> {
    closed_bspline_deriv(g, ctrl, period_knots, t, 0)
}

/// The `k`-th derivative `Σ d_i N_i^{per (k)}(t)` of the closed B-spline; `t` wraps around the
/// period; at a knot the derivative from the right.
///
/// # Panics
/// As [`closed_bspline_point`].
///
/// ```
/// let d = [vec![1.0, 0.0], vec![0.0, 1.0], vec![-1.0, 0.0], vec![0.0, -1.0]];
/// let u = strak_ref::periodic_uniform_knots(4);
/// // Uniform quadratic: c'(u_0) = (d_3 − d_2) / Δu = 4 (d_3 − d_2).
/// let v = strak_ref::closed_bspline_deriv(2, &d, &u, 0.0, 1);
/// assert!((v[0] - 4.0).abs() < 1e-13 && (v[1] + 4.0).abs() < 1e-13);
/// ```
pub fn closed_bspline_deriv(
    g: usize,
    ctrl: &[Vec<f64>],
    period_knots: &[f64],
    t: f64,
    k: usize,
) -> Vec<f64> {
    let kp = ctrl.len();
    check_closed(g, kp, period_knots);
    let w: Vec<f64> = (0..kp)
        .map(|i| closed_bspline_basis(g, kp, period_knots, i, t, k))
        .collect();
    weighted_sum(ctrl, &w)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bspline::bspline_deriv;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    fn hexagon() -> Vec<Vec<f64>> {
        (0..6)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / 6.0;
                vec![2.0 * a.cos(), a.sin() + 0.3 * (i % 2) as f64]
            })
            .collect()
    }

    #[test]
    fn periodic_partition_of_unity() {
        let u = [0.0, 0.5, 1.5, 2.0, 3.5, 4.0, 5.0];
        for g in 0..=5 {
            for j in 0..=100 {
                let t = 5.0 * j as f64 / 100.0;
                let s: f64 = (0..6)
                    .map(|i| closed_bspline_basis(g, 6, &u, i, t, 0))
                    .sum();
                assert!(close(s, 1.0, 1e-14), "g={g} t={t}");
                let ds: f64 = (0..6)
                    .map(|i| closed_bspline_basis(g, 6, &u, i, t, 1))
                    .sum();
                assert!(close(ds, 0.0, 1e-11));
            }
        }
    }

    #[test]
    fn uniform_cubic_weights_at_start() {
        let d = hexagon();
        let u = crate::bspline::periodic_uniform_knots(6);
        let p = closed_bspline_point(3, &d, &u, 0.0);
        for c in 0..2 {
            let expect = (d[3][c] + 4.0 * d[4][c] + d[5][c]) / 6.0;
            assert!(close(p[c], expect, 1e-14));
        }
    }

    #[test]
    fn equals_open_spline_with_last_g_points_prepended() {
        let d = hexagon();
        let u = [0.0, 0.4, 1.0, 1.2, 2.5, 3.0, 4.0];
        for g in 1..=4 {
            let ext = periodic_extended_knots(g, &u);
            let mut open = d[6 - g..].to_vec();
            open.extend(d.iter().cloned());
            for j in 0..=80 {
                let t = 4.0 * j as f64 / 80.0 * 0.999_999;
                for k in 0..=2 {
                    let a = closed_bspline_deriv(g, &d, &u, t, k);
                    let b = bspline_deriv(&ext, g, &open, t, k);
                    for c in 0..2 {
                        assert!(close(a[c], b[c], 1e-11), "g={g} t={t} k={k}");
                    }
                }
            }
        }
    }

    #[test]
    fn wraps_and_is_smooth_across_the_seam() {
        let d = hexagon();
        let u = [0.0, 0.4, 1.0, 1.2, 2.5, 3.0, 4.0];
        let g = 3;
        let p0 = closed_bspline_point(g, &d, &u, 0.0);
        assert_eq!(closed_bspline_point(g, &d, &u, 4.0), p0);
        let shifted = closed_bspline_point(g, &d, &u, 1.3 + 8.0);
        let base = closed_bspline_point(g, &d, &u, 1.3);
        assert!(close(shifted[0], base[0], 1e-13) && close(shifted[1], base[1], 1e-13));
        let neg = closed_bspline_point(g, &d, &u, 1.3 - 4.0);
        assert!(close(neg[0], base[0], 1e-13));
        // C² across the seam: left limits at u_K equal values at u_0.
        let eps = 1e-7;
        for k in 0..=2 {
            let left = closed_bspline_deriv(g, &d, &u, 4.0 - eps, k);
            let right = closed_bspline_deriv(g, &d, &u, 0.0, k);
            for c in 0..2 {
                assert!(
                    close(left[c], right[c], 1e-4 * (1.0 + right[c].abs())),
                    "k={k}"
                );
            }
        }
    }

    #[test]
    fn derivative_matches_finite_difference() {
        let d = hexagon();
        let u = [0.0, 0.4, 1.0, 1.2, 2.5, 3.0, 4.0];
        let h = 1e-6;
        for j in 0..40 {
            let t = 0.05 + j as f64 / 10.0;
            let dv = closed_bspline_deriv(2, &d, &u, t, 1);
            let p = closed_bspline_point(2, &d, &u, t + h);
            let m = closed_bspline_point(2, &d, &u, t - h);
            for c in 0..2 {
                assert!(close(dv[c], (p[c] - m[c]) / (2.0 * h), 1e-5));
            }
        }
    }

    #[test]
    #[should_panic(expected = "K + 1 knots")]
    fn wrong_knot_count_panics() {
        let _ = closed_bspline_point(2, &hexagon(), &[0.0, 1.0, 2.0], 0.5);
    }
}
