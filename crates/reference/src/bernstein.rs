//! Bernstein basis and Bézier curves as Bernstein sums (seeds/000 "Bernsteinbasis",
//! seeds/004 "Bernstein-Polynome" and their derivative rule).

use crate::combinatorics::binomial;
use crate::vecops::weighted_sum;

/// The Bernstein polynomial `B_i^g(t) = C(g, i) (1−t)^{g−i} t^i` (seeds/000); `0` for `i > g`.
/// Evaluated directly from the formula for any real `t` (no clamping).
///
/// ```
/// // B_1^3(1/2) = 3 · (1/2)² · (1/2) = 3/8
/// assert_eq!(strak_ref::bernstein(1, 3, 0.5), 0.375);
/// ```
pub fn bernstein(i: usize, g: usize, t: f64) -> f64 {
    if i > g {
        return 0.0;
    }
    binomial(g as u32, i as u32) * (1.0 - t).powi((g - i) as i32) * t.powi(i as i32)
}

/// The `k`-th derivative of `B_i^g` at `t`, by repeated use of the seeds/004 rule
/// `d/dt B_{i,n} = n (B_{i−1,n−1} − B_{i,n−1})`, with `B_{−1,·} = B_{n,n−1} = 0`.
/// `k = 0` is [`bernstein`]; `k > g` gives `0`.
///
/// ```
/// // B_3^3 = t³, so B''' = 6.
/// assert_eq!(strak_ref::bernstein_deriv(3, 3, 0.7, 3), 6.0);
/// assert_eq!(strak_ref::bernstein_deriv(0, 2, 0.0, 1), -2.0);
/// ```
pub fn bernstein_deriv(i: usize, g: usize, t: f64, k: usize) -> f64 {
    if k == 0 {
        return bernstein(i, g, t);
    }
    if g == 0 || i > g {
        return 0.0;
    }
    let left = if i == 0 {
        0.0
    } else {
        bernstein_deriv(i - 1, g - 1, t, k - 1)
    };
    let right = bernstein_deriv(i, g - 1, t, k - 1); // zero when i > g − 1
    g as f64 * (left - right)
}

/// The Bézier curve `c(t) = Σ_{i=0}^{g} b_i B_i^g(t)` with `g = ctrl.len() − 1` (seeds/000), as
/// a plain Bernstein sum (not de Casteljau), at any real `t` (no clamping).
///
/// # Panics
/// If `ctrl` is empty or the points differ in dimension.
///
/// ```
/// let ctrl = [vec![0.0, 0.0], vec![1.0, 2.0], vec![2.0, 0.0]];
/// assert_eq!(strak_ref::bezier_point(&ctrl, 0.5), vec![1.0, 1.0]);
/// ```
pub fn bezier_point(ctrl: &[Vec<f64>], t: f64) -> Vec<f64> {
    bezier_deriv(ctrl, t, 0)
}

/// The `k`-th derivative `c^{(k)}(t) = Σ b_i (B_i^g)^{(k)}(t)` of a Bézier curve, using
/// [`bernstein_deriv`]. `k = 0` is [`bezier_point`]; `k > g` gives the zero vector.
///
/// # Panics
/// If `ctrl` is empty or the points differ in dimension.
///
/// ```
/// // End tangent interpolation: c'(0) = g (b_1 − b_0).
/// let ctrl = [vec![0.0, 0.0], vec![1.0, 2.0], vec![2.0, 0.0], vec![3.0, 3.0]];
/// assert_eq!(strak_ref::bezier_deriv(&ctrl, 0.0, 1), vec![3.0, 6.0]);
/// ```
pub fn bezier_deriv(ctrl: &[Vec<f64>], t: f64, k: usize) -> Vec<f64> {
    assert!(!ctrl.is_empty(), "bezier: no control points");
    let g = ctrl.len() - 1;
    let w: Vec<f64> = (0..=g).map(|i| bernstein_deriv(i, g, t, k)).collect();
    weighted_sum(ctrl, &w)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn cubic_basis_matches_seed_vector() {
        // seeds/000: B³(t) = ((1−t)³, 3(1−t)²t, 3(1−t)t², t³).
        for j in 0..=20 {
            let t = j as f64 / 20.0;
            let s = 1.0 - t;
            let expect = [s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t];
            for i in 0..4 {
                assert!(close(bernstein(i, 3, t), expect[i], 1e-15));
            }
        }
        assert_eq!(bernstein(4, 3, 0.5), 0.0);
    }

    #[test]
    fn partition_of_unity_positivity_symmetry_maximum() {
        // seeds/004: Σ B_{i,n} = 1, B ≥ 0 on [0,1], B_{i,n}(t) = B_{n−i,n}(1−t), max at i/n.
        for g in 0..=8 {
            for j in 0..=50 {
                let t = j as f64 / 50.0;
                let sum: f64 = (0..=g).map(|i| bernstein(i, g, t)).sum();
                assert!(close(sum, 1.0, 1e-14));
                for i in 0..=g {
                    assert!(bernstein(i, g, t) >= 0.0);
                    assert!(close(
                        bernstein(i, g, t),
                        bernstein(g - i, g, 1.0 - t),
                        1e-15
                    ));
                }
            }
            // Inner maxima are stationary points (i = 0, g peak at the interval ends).
            for i in 1..g {
                let peak = i as f64 / g as f64;
                let d = bernstein_deriv(i, g, peak, 1);
                assert!(close(d, 0.0, 1e-12), "g={g} i={i} d={d}");
            }
        }
    }

    #[test]
    fn derivative_matches_finite_difference_and_closed_form() {
        // B_1^3 = 3t − 6t² + 3t³: B' = 3 − 12t + 9t², B'' = −12 + 18t, B''' = 18.
        let t = 0.3;
        assert!(close(
            bernstein_deriv(1, 3, t, 1),
            3.0 - 12.0 * t + 9.0 * t * t,
            1e-14
        ));
        assert!(close(bernstein_deriv(1, 3, t, 2), -12.0 + 18.0 * t, 1e-13));
        assert!(close(bernstein_deriv(1, 3, t, 3), 18.0, 1e-13));
        assert_eq!(bernstein_deriv(1, 3, t, 4), 0.0);
        let h = 1e-6;
        for i in 0..=5 {
            let fd = (bernstein(i, 5, t + h) - bernstein(i, 5, t - h)) / (2.0 * h);
            assert!(close(bernstein_deriv(i, 5, t, 1), fd, 1e-7));
        }
    }

    #[test]
    fn bezier_sum_equals_de_casteljau_of_seed() {
        // seeds/000/004: the de Casteljau scheme gives the same point as the Bernstein sum.
        let ctrl = vec![
            vec![0.0, 0.0],
            vec![1.0, 3.0],
            vec![4.0, 3.0],
            vec![5.0, -1.0],
        ];
        let t: f64 = 1.0 / 3.0;
        let mut pts = ctrl.clone();
        while pts.len() > 1 {
            pts = pts
                .windows(2)
                .map(|w| {
                    vec![
                        (1.0 - t) * w[0][0] + t * w[1][0],
                        (1.0 - t) * w[0][1] + t * w[1][1],
                    ]
                })
                .collect();
        }
        let p = bezier_point(&ctrl, t);
        assert!(close(p[0], pts[0][0], 1e-14) && close(p[1], pts[0][1], 1e-14));
        // End point and end tangent interpolation.
        assert_eq!(bezier_point(&ctrl, 1.0), vec![5.0, -1.0]);
        assert_eq!(bezier_deriv(&ctrl, 1.0, 1), vec![3.0, -12.0]);
        assert_eq!(bezier_deriv(&ctrl, 0.4, 4), vec![0.0, 0.0]);
    }
}
