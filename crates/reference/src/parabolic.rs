//! Parabolic blending (seeds/003, "Parabolic Blending"): between each pair of points the
//! weighted mean `S_r(t) = (1−t) Q_r(t) + t Q_{r+1}(t)` of the two overlapping Lagrange
//! parabolas; the first and last pieces keep the plain parabola.
//!
//! Points `P_0..P_n` (`n ≥ 2`), node `i` at `u = i`, so the domain is `[0, n]` and piece `r`
//! (`r = 0..n−1`) is `S_r(u − r)` on `[r, r+1]`. Formulas of the seed, with local `t ∈ [0, 1]`:
//!
//! * `S_0(t) = P_0 (t−1)(t−2)/2 − P_1 t(t−2) + P_2 t(t−1)/2`
//! * `S_r(t) = (1−t) (P_{r−1} t(t−1)/2 − P_r (t+1)(t−1) + P_{r+1} t(t+1)/2)
//!   + t (P_r (t−1)(t−2)/2 − P_{r+1} t(t−2) + P_{r+2} t(t−1)/2)`
//! * `S_{n−1}(t) = P_{n−2} t(t−1)/2 − P_{n−1} (t+1)(t−1) + P_n t(t+1)/2` ("analog zu `S_0`":
//!   the parabola through `P_{n−2}, P_{n−1}, P_n` at `t = −1, 0, 1`, the one that `S_{n−2}`
//!   blends in, so the curve is C¹ there as well).
//!
//! The seed asks for `n > 2`; with `n = 2` (three points) both pieces are the one parabola.

use crate::piece::find_piece;
use crate::poly::Poly;
use crate::vecops::weighted_sum;

fn lin(a: f64) -> Poly {
    Poly::from_root(a)
}

/// Weights of the parabola through three points at local nodes `−1, 0, 1` (seed's `Q_r`).
fn parabola_left() -> [Poly; 3] {
    [
        (&lin(0.0) * &lin(1.0)).scale(0.5),   // t(t−1)/2
        (&lin(-1.0) * &lin(1.0)).scale(-1.0), // −(t+1)(t−1)
        (&lin(0.0) * &lin(-1.0)).scale(0.5),  // t(t+1)/2
    ]
}

/// Weights of the parabola through three points at local nodes `0, 1, 2` (seed's `Q_{r+1}`).
fn parabola_right() -> [Poly; 3] {
    [
        (&lin(1.0) * &lin(2.0)).scale(0.5),  // (t−1)(t−2)/2
        (&lin(0.0) * &lin(2.0)).scale(-1.0), // −t(t−2)
        (&lin(0.0) * &lin(1.0)).scale(0.5),  // t(t−1)/2
    ]
}

/// The weight polynomials of piece `r` as `(first point index, [weights of 3 or 4 points])`.
fn piece_weights(n: usize, r: usize) -> (usize, Vec<Poly>) {
    if r == 0 {
        (0, parabola_right().to_vec())
    } else if r == n - 1 {
        (n - 2, parabola_left().to_vec())
    } else {
        let one_minus_t = Poly::new(vec![1.0, -1.0]);
        let t = Poly::new(vec![0.0, 1.0]);
        let l = parabola_left();
        let rt = parabola_right();
        let zero = Poly::constant(0.0);
        // Points P_{r−1}, P_r, P_{r+1}, P_{r+2}.
        let left = [&l[0], &l[1], &l[2], &zero];
        let right = [&zero, &rt[0], &rt[1], &rt[2]];
        let w = (0..4)
            .map(|j| &(&one_minus_t * left[j]) + &(&t * right[j]))
            .collect();
        (r - 1, w)
    }
}

/// A point of the parabolic blending curve through `pts` (node `i` at `u = i`), `u` clamped to
/// `[0, n]`; at inner nodes the piece starting there is used (see the module docs).
///
/// # Panics
/// If fewer than three points are given.
///
/// ```
/// let pts = [vec![0.0, 0.0], vec![1.0, 1.0], vec![2.0, 0.0], vec![3.0, 1.0]];
/// assert_eq!(strak_ref::parabolic_blend(&pts, 2.0), vec![2.0, 0.0]);
/// ```
pub fn parabolic_blend(pts: &[Vec<f64>], u: f64) -> Vec<f64> {
    parabolic_blend_deriv(pts, u, 0)
}

/// The `k`-th derivative of [`parabolic_blend`] with respect to `u` (the local `t = u − r`
/// has unit speed, so no scaling).
///
/// # Panics
/// If fewer than three points are given.
///
/// ```
/// // Points on the parabola u²: every piece reproduces it, so c''(u) = 2.
/// let pts: Vec<Vec<f64>> = (0..5).map(|i| vec![(i * i) as f64]).collect();
/// let d = strak_ref::parabolic_blend_deriv(&pts, 2.5, 2);
/// assert!((d[0] - 2.0).abs() < 1e-12);
/// ```
pub fn parabolic_blend_deriv(pts: &[Vec<f64>], u: f64, k: usize) -> Vec<f64> {
    assert!(
        pts.len() >= 3,
        "parabolic_blend: need at least three points"
    );
    let n = pts.len() - 1;
    let breaks: Vec<f64> = (0..=n).map(|i| i as f64).collect();
    let (r, u) = find_piece(&breaks, u);
    let t = u - r as f64;
    let (first, w) = piece_weights(n, r);
    let values: Vec<f64> = w.iter().map(|p| p.nth_derivative(k).eval(t)).collect();
    weighted_sum(&pts[first..first + w.len()], &values)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    fn sample() -> Vec<Vec<f64>> {
        vec![
            vec![0.0, 0.0],
            vec![1.0, 2.0],
            vec![3.0, 3.0],
            vec![4.0, 1.0],
            vec![6.0, 0.0],
            vec![7.0, 2.0],
        ]
    }

    #[test]
    fn interpolates_all_points() {
        let pts = sample();
        for (i, p) in pts.iter().enumerate() {
            let c = parabolic_blend(&pts, i as f64);
            assert!(
                close(c[0], p[0], 1e-14) && close(c[1], p[1], 1e-14),
                "i={i}"
            );
        }
    }

    #[test]
    fn c1_at_inner_nodes_with_seed_formulas() {
        let pts = sample();
        for i in 1..pts.len() - 1 {
            let u = i as f64;
            let right = parabolic_blend_deriv(&pts, u, 1);
            // Left limit: evaluate the previous piece's weights at t = 1.
            let (first, w) = piece_weights(pts.len() - 1, i - 1);
            let vals: Vec<f64> = w.iter().map(|p| p.derivative().eval(1.0)).collect();
            let left = weighted_sum(&pts[first..first + w.len()], &vals);
            for c in 0..2 {
                assert!(close(left[c], right[c], 1e-13), "node {i}");
            }
        }
    }

    #[test]
    fn pieces_equal_seed_formulas_written_out() {
        let pts = sample();
        let n = pts.len() - 1;
        for j in 0..=10 {
            let t = j as f64 / 10.0;
            for c in 0..2 {
                let p = |i: usize| pts[i][c];
                let s0 = p(0) * (t - 1.0) * (t - 2.0) / 2.0 - p(1) * t * (t - 2.0)
                    + p(2) * t * (t - 1.0) / 2.0;
                let r = 2;
                let sr = (1.0 - t)
                    * (p(r - 1) * t * (t - 1.0) / 2.0 - p(r) * (t + 1.0) * (t - 1.0)
                        + p(r + 1) * t * (t + 1.0) / 2.0)
                    + t * (p(r) * (t - 1.0) * (t - 2.0) / 2.0 - p(r + 1) * t * (t - 2.0)
                        + p(r + 2) * t * (t - 1.0) / 2.0);
                let sn = p(n - 2) * t * (t - 1.0) / 2.0 - p(n - 1) * (t + 1.0) * (t - 1.0)
                    + p(n) * t * (t + 1.0) / 2.0;
                if t < 1.0 {
                    assert!(close(parabolic_blend(&pts, t)[c], s0, 1e-13));
                    assert!(close(parabolic_blend(&pts, r as f64 + t)[c], sr, 1e-13));
                }
                assert!(close(
                    parabolic_blend(&pts, (n - 1) as f64 + t)[c],
                    sn,
                    1e-13
                ));
            }
        }
    }

    #[test]
    fn three_points_is_one_parabola_and_clamps() {
        let pts = vec![vec![1.0], vec![0.0], vec![3.0]];
        // Parabola through (0,1),(1,0),(2,3): 1 − 3u + 2u².
        for j in 0..=20 {
            let u = j as f64 / 10.0;
            assert!(close(
                parabolic_blend(&pts, u)[0],
                1.0 - 3.0 * u + 2.0 * u * u,
                1e-13
            ));
        }
        assert_eq!(parabolic_blend(&pts, -1.0), vec![1.0]);
        assert!(close(parabolic_blend(&pts, 5.0)[0], 3.0, 1e-14));
        assert_eq!(parabolic_blend_deriv(&pts, 1.5, 3), vec![0.0]);
    }
}
