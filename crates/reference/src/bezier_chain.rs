//! Composite Bézier curves ("Bézier spline", seeds/002 "Stetiges Aneinanderfügen"): `n`
//! Bézier segments of degree `g` on the parameter domain `[0, n]`, segment `i` on `[i, i + 1]`
//! with local parameter `t = u − i`, given by the composite representation of
//! `n·g + 1` points in which consecutive segments share their join point.
//!
//! Each segment is a Bernstein sum (seeds/000), its derivatives the Bernstein sums of the
//! forward differences, `c^{(k)}(t) = g!/(g−k)! Σ_{i=0}^{g−k} Δ^k b_i B_i^{g−k}(t)` (seeds/004
//! derivative rule applied `k` times) — a different route than [`crate::bezier_deriv`] and
//! than `strak-curves`' de Casteljau.

use crate::bernstein::bernstein;
use crate::piece::find_piece;
use crate::vecops::{vec_sub, vec_zero, weighted_sum};

/// The segments of the composite representation: segment `i` is
/// `points[i·g ..= (i+1)·g]`.
///
/// # Panics
/// If `degree` is 0 or the number of points is not `n·degree + 1` with `n ≥ 1`.
///
/// ```
/// let pts = [vec![0.0], vec![1.0], vec![2.0], vec![5.0], vec![6.0]];
/// let segs = strak_ref::bezier_chain_segments(&pts, 2);
/// assert_eq!(segs, vec![pts[..3].to_vec(), pts[2..].to_vec()]);
/// ```
pub fn bezier_chain_segments(points: &[Vec<f64>], degree: usize) -> Vec<Vec<Vec<f64>>> {
    assert!(degree >= 1, "bezier chain: degree 0");
    assert!(
        points.len() > degree && (points.len() - 1).is_multiple_of(degree),
        "bezier chain: {} points are not n·{degree} + 1",
        points.len()
    );
    let n = (points.len() - 1) / degree;
    (0..n)
        .map(|i| points[i * degree..=(i + 1) * degree].to_vec())
        .collect()
}

/// The point of the composite Bézier curve at `u` (clamped to `[0, n]`; at an inner join the
/// segment starting there, at `u = n` the last segment).
///
/// # Panics
/// As [`bezier_chain_segments`].
///
/// ```
/// // two linear segments 0 → 1 → 3
/// let pts = [vec![0.0], vec![1.0], vec![3.0]];
/// assert_eq!(strak_ref::bezier_chain_eval(&pts, 1, 1.5), vec![2.0]);
/// assert_eq!(strak_ref::bezier_chain_eval(&pts, 1, 9.0), vec![3.0]);
/// ```
pub fn bezier_chain_eval(points: &[Vec<f64>], degree: usize, u: f64) -> Vec<f64> {
    bezier_chain_deriv(points, degree, u, 0)
}

/// The `k`-th derivative with respect to `u` of the composite Bézier curve at `u` (clamped;
/// segment choice as [`bezier_chain_eval`]). Each segment spans one unit of `u`, so this is
/// the segment's derivative `g!/(g−k)! Σ Δ^k b_i B_i^{g−k}(t)` at `t = u − i`; zero for
/// `k > g`.
///
/// # Panics
/// As [`bezier_chain_segments`].
///
/// ```
/// // cubic 0, 1, 2, 3 (a line at unit speed per unit t, times 3 / 3) then a cubic on to 9
/// let pts: Vec<Vec<f64>> = [0.0, 1.0, 2.0, 3.0, 5.0, 7.0, 9.0].iter().map(|&x| vec![x]).collect();
/// assert_eq!(strak_ref::bezier_chain_deriv(&pts, 3, 0.5, 1), vec![3.0]);
/// assert_eq!(strak_ref::bezier_chain_deriv(&pts, 3, 1.0, 1), vec![6.0]);
/// assert_eq!(strak_ref::bezier_chain_deriv(&pts, 3, 1.5, 2), vec![0.0]);
/// ```
pub fn bezier_chain_deriv(points: &[Vec<f64>], degree: usize, u: f64, k: usize) -> Vec<f64> {
    let segs = bezier_chain_segments(points, degree);
    let breaks: Vec<f64> = (0..=segs.len()).map(|i| i as f64).collect();
    let (i, u) = find_piece(&breaks, u);
    segment_deriv(&segs[i], u - breaks[i], k)
}

/// `g!/(g−k)! Σ_{i=0}^{g−k} Δ^k b_i B_i^{g−k}(t)`.
fn segment_deriv(ctrl: &[Vec<f64>], t: f64, k: usize) -> Vec<f64> {
    let g = ctrl.len() - 1;
    if k > g {
        return vec_zero(ctrl[0].len());
    }
    let mut diff = ctrl.to_vec();
    for _ in 0..k {
        diff = diff.windows(2).map(|w| vec_sub(&w[1], &w[0])).collect();
    }
    let factor: f64 = (0..k).map(|m| (g - m) as f64).product();
    let w: Vec<f64> = (0..=g - k)
        .map(|i| factor * bernstein(i, g - k, t))
        .collect();
    weighted_sum(&diff, &w)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bezier_deriv;

    #[test]
    fn agrees_with_single_segments_and_joins() {
        let pts: Vec<Vec<f64>> = [
            [0.0, 0.0],
            [1.0, 1.0],
            [2.0, 1.0],
            [3.0, 0.0],
            [4.0, -1.0],
            [5.0, -1.0],
            [6.0, 0.0],
        ]
        .iter()
        .map(|p| p.to_vec())
        .collect();
        for j in 0..=20 {
            let t = j as f64 / 20.0;
            for k in 0..=4 {
                let a = bezier_chain_deriv(&pts, 3, t, k);
                let b = bezier_deriv(&pts[..4], t, k);
                let c = bezier_chain_deriv(&pts, 3, 1.0 + t, k);
                let d = bezier_deriv(&pts[3..], t, k);
                for x in 0..2 {
                    if t < 1.0 {
                        assert!((a[x] - b[x]).abs() < 1e-12);
                    }
                    assert!((c[x] - d[x]).abs() < 1e-12);
                }
            }
        }
        // C¹ join: c'(1) = 3 (b3 − b2) = (3, −3) from both sides; clamping
        assert_eq!(bezier_chain_deriv(&pts, 3, 1.0, 1), vec![3.0, -3.0]);
        assert_eq!(bezier_chain_eval(&pts, 3, -2.0), vec![0.0, 0.0]);
        assert_eq!(bezier_chain_eval(&pts, 3, 2.0), vec![6.0, 0.0]);
        assert_eq!(bezier_chain_eval(&pts, 3, 1.5), vec![4.5, -0.75]);
    }

    #[test]
    #[should_panic(expected = "not n·3 + 1")]
    fn wrong_count_panics() {
        bezier_chain_segments(&vec![vec![0.0]; 5], 3);
    }
}
