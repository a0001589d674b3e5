//! NURBS (seeds/004, "NURBS"): rational B-splines `P(t) = Σ R_i(t) P_i` with
//! `R_i = h_i N_i / Σ_j h_j N_j`, their derivatives, and the seed's NURBS circle.

use crate::bspline::{bspline_domain, cox_de_boor_deriv};
use crate::combinatorics::binomial;
use crate::vecops::{vec_add_scaled, vec_scale, vec_zero};

fn check(knots: &[f64], g: usize, ctrl: &[Vec<f64>], weights: &[f64]) {
    assert_eq!(ctrl.len(), weights.len(), "nurbs: one weight per point");
    assert!(
        weights.iter().all(|&h| h > 0.0),
        "nurbs: weights must be positive"
    );
    assert!(ctrl.len() > g, "nurbs: need more than g points");
    assert_eq!(
        knots.len(),
        ctrl.len() + g + 1,
        "nurbs: need K + g + 1 knots"
    );
    assert!(
        knots.windows(2).all(|w| w[0] <= w[1]),
        "nurbs: knots must be non-decreasing"
    );
}

/// `A^{(j)}(t) = Σ h_i N_i^{(j)}(t) P_i` and `w^{(j)}(t) = Σ h_i N_i^{(j)}(t)` for `j = 0..=k`.
fn homogeneous_derivs(
    knots: &[f64],
    g: usize,
    ctrl: &[Vec<f64>],
    weights: &[f64],
    t: f64,
    k: usize,
) -> (Vec<Vec<f64>>, Vec<f64>) {
    let dim = ctrl[0].len();
    let mut a = vec![vec_zero(dim); k + 1];
    let mut w = vec![0.0; k + 1];
    for j in 0..=k {
        for (i, p) in ctrl.iter().enumerate() {
            let n = cox_de_boor_deriv(knots, i, g, t, j);
            vec_add_scaled(&mut a[j], p, weights[i] * n);
            w[j] += weights[i] * n;
        }
    }
    (a, w)
}

/// The NURBS point `P(t) = Σ R_i(t) P_i`, `R_i = h_i N_i^g / Σ_j h_j N_j^g` (seeds/004; the
/// seed's `N_{i,k}` has order `k = g + 1`), computed as `A(t) / w(t)` with `A = Σ h_i N_i P_i`
/// and `w = Σ h_i N_i`. `t` is clamped to the domain [`bspline_domain`] (closed at both ends,
/// see [`cox_de_boor`](crate::cox_de_boor)).
///
/// # Panics
/// If the lengths do not match (`K` points, `K` weights, `K + g + 1` knots), `K <= g`, a
/// weight is not positive, or the knots decrease.
///
/// ```
/// let (knots, ctrl, weights) = strak_ref::nurbs_circle();
/// let p = strak_ref::nurbs_point(&knots, 2, &ctrl, &weights, 0.5);
/// assert!(((p[0] * p[0] + p[1] * p[1]).sqrt() - 1.0).abs() < 1e-15);
/// ```
pub fn nurbs_point(
    knots: &[f64],
    g: usize,
    ctrl: &[Vec<f64>],
    weights: &[f64],
    t: f64,
) -> Vec<f64> {
    nurbs_deriv(knots, g, ctrl, weights, t, 0)
}

/// The `k`-th derivative of the NURBS curve: from `A = w P` and Leibniz's rule,
/// `A^{(k)} = Σ_{j=0}^{k} C(k, j) w^{(j)} P^{(k−j)}`, hence
/// `P^{(k)} = (A^{(k)} − Σ_{j=1}^{k} C(k, j) w^{(j)} P^{(k−j)}) / w` (for `k = 1` the quotient
/// rule `P' = (A' − w' P) / w`). `t` clamped as in [`nurbs_point`]; derivatives from the right
/// at inner knots, from the left at the domain end.
///
/// # Panics
/// As [`nurbs_point`].
///
/// ```
/// // The tangent of the circle is perpendicular to the radius.
/// let (knots, ctrl, weights) = strak_ref::nurbs_circle();
/// let p = strak_ref::nurbs_point(&knots, 2, &ctrl, &weights, 1.3);
/// let v = strak_ref::nurbs_deriv(&knots, 2, &ctrl, &weights, 1.3, 1);
/// assert!((p[0] * v[0] + p[1] * v[1]).abs() < 1e-14);
/// ```
pub fn nurbs_deriv(
    knots: &[f64],
    g: usize,
    ctrl: &[Vec<f64>],
    weights: &[f64],
    t: f64,
    k: usize,
) -> Vec<f64> {
    check(knots, g, ctrl, weights);
    let (lo, hi) = bspline_domain(knots, g);
    let t = t.clamp(lo, hi);
    let (a, w) = homogeneous_derivs(knots, g, ctrl, weights, t, k);
    let mut p: Vec<Vec<f64>> = Vec::with_capacity(k + 1);
    for order in 0..=k {
        let mut v = a[order].clone();
        for j in 1..=order {
            let c = binomial(order as u32, j as u32) * w[j];
            vec_add_scaled(&mut v, &p[order - j], -c);
        }
        p.push(vec_scale(&v, 1.0 / w[0]));
    }
    p.swap_remove(k)
}

/// The NURBS circle of seeds/004: degree 2, de Boor points
/// `(1,0), (1,1), (0,1), (−1,1), (−1,0), (−1,−1), (0,−1), (1,−1), (1,0)`, weights
/// `1, √2/2, 1, √2/2, …, 1`, knot vector `0,0,0,1,1,2,2,3,3,4,4,4`. Returns
/// `(knots, ctrl, weights)`; each unit of the parameter is one quarter of the unit circle,
/// counter-clockwise from `(1, 0)`.
///
/// ```
/// let (knots, ctrl, weights) = strak_ref::nurbs_circle();
/// assert_eq!((knots.len(), ctrl.len(), weights.len()), (12, 9, 9));
/// ```
pub fn nurbs_circle() -> (Vec<f64>, Vec<Vec<f64>>, Vec<f64>) {
    let s = 2f64.sqrt() / 2.0;
    let knots = vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 3.0, 3.0, 4.0, 4.0, 4.0];
    let ctrl = vec![
        vec![1.0, 0.0],
        vec![1.0, 1.0],
        vec![0.0, 1.0],
        vec![-1.0, 1.0],
        vec![-1.0, 0.0],
        vec![-1.0, -1.0],
        vec![0.0, -1.0],
        vec![1.0, -1.0],
        vec![1.0, 0.0],
    ];
    let weights = vec![1.0, s, 1.0, s, 1.0, s, 1.0, s, 1.0];
    (knots, ctrl, weights)
}

/// The seed's closed formula for the quarter circle by NURBS (seeds/004, "Viertelkreis durch
/// NURBS"), with `s = √2/2` and `D(t) = 16t² − 8t + 1 + s(−32t² + 8t) + 16t²`:
/// `P_x = (16t² − 8t + 1 + s(−32t² + 8t)) / D`, `P_y = (s(−32t² + 8t) + 16t²) / D`.
/// The seed's `t` is the circle's parameter scaled to `[0, 1]` for the full circle, so the first
/// quarter is `t ∈ [0, 1/4]`: it equals [`nurbs_point`] of [`nurbs_circle`] at `4t`.
///
/// ```
/// let p = strak_ref::nurbs_quarter_circle_seed(0.25);
/// assert!(p[0].abs() < 1e-15 && (p[1] - 1.0).abs() < 1e-15);
/// ```
pub fn nurbs_quarter_circle_seed(t: f64) -> Vec<f64> {
    let s = 2f64.sqrt() / 2.0;
    let x_num = 16.0 * t * t - 8.0 * t + 1.0 + s * (-32.0 * t * t + 8.0 * t);
    let y_num = s * (-32.0 * t * t + 8.0 * t) + 16.0 * t * t;
    let d = 16.0 * t * t - 8.0 * t + 1.0 + s * (-32.0 * t * t + 8.0 * t) + 16.0 * t * t;
    vec![x_num / d, y_num / d]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn circle_has_radius_one() {
        let (knots, ctrl, weights) = nurbs_circle();
        let mut worst: f64 = 0.0;
        for j in 0..=4000 {
            let t = 4.0 * j as f64 / 4000.0;
            let p = nurbs_point(&knots, 2, &ctrl, &weights, t);
            worst = worst.max((p[0].hypot(p[1]) - 1.0).abs());
        }
        assert!(worst <= 1e-15, "worst radial error {worst:e}");
        // Quarter points.
        let q = [
            (0.0, [1.0, 0.0]),
            (1.0, [0.0, 1.0]),
            (2.0, [-1.0, 0.0]),
            (3.0, [0.0, -1.0]),
        ];
        for (t, e) in q {
            let p = nurbs_point(&knots, 2, &ctrl, &weights, t);
            assert!(close(p[0], e[0], 1e-15) && close(p[1], e[1], 1e-15));
        }
        let end = nurbs_point(&knots, 2, &ctrl, &weights, 4.0);
        assert!(close(end[0], 1.0, 1e-15) && close(end[1], 0.0, 1e-15));
    }

    #[test]
    fn seed_quarter_formula_equals_nurbs_point() {
        let (knots, ctrl, weights) = nurbs_circle();
        for j in 0..=1000 {
            let u = j as f64 / 1000.0;
            let a = nurbs_point(&knots, 2, &ctrl, &weights, u);
            let b = nurbs_quarter_circle_seed(u / 4.0);
            assert!(
                close(a[0], b[0], 1e-15) && close(a[1], b[1], 1e-15),
                "u={u}"
            );
            // The seed's claim P_x² + P_y² = 1.
            assert!(close(b[0] * b[0] + b[1] * b[1], 1.0, 1e-15));
        }
    }

    #[test]
    fn derivatives_match_finite_differences_and_circle_geometry() {
        let (knots, ctrl, weights) = nurbs_circle();
        let h = 1e-5;
        for j in 1..40 {
            let t = j as f64 / 10.0 + 0.05;
            let p = nurbs_point(&knots, 2, &ctrl, &weights, t);
            let v = nurbs_deriv(&knots, 2, &ctrl, &weights, t, 1);
            let acc = nurbs_deriv(&knots, 2, &ctrl, &weights, t, 2);
            let pp = nurbs_point(&knots, 2, &ctrl, &weights, t + h);
            let pm = nurbs_point(&knots, 2, &ctrl, &weights, t - h);
            let vp = nurbs_deriv(&knots, 2, &ctrl, &weights, t + h, 1);
            let vm = nurbs_deriv(&knots, 2, &ctrl, &weights, t - h, 1);
            for c in 0..2 {
                assert!(close(v[c], (pp[c] - pm[c]) / (2.0 * h), 1e-8));
                assert!(close(acc[c], (vp[c] - vm[c]) / (2.0 * h), 1e-6));
            }
            // |P|² = 1 ⇒ P·P' = 0 and P·P'' + |P'|² = 0.
            let pv = p[0] * v[0] + p[1] * v[1];
            let pa = p[0] * acc[0] + p[1] * acc[1] + v[0] * v[0] + v[1] * v[1];
            assert!(close(pv, 0.0, 1e-14) && close(pa, 0.0, 1e-12));
        }
        // Third derivative vs finite difference of the second.
        let t = 0.37;
        let d3 = nurbs_deriv(&knots, 2, &ctrl, &weights, t, 3);
        let ap = nurbs_deriv(&knots, 2, &ctrl, &weights, t + h, 2);
        let am = nurbs_deriv(&knots, 2, &ctrl, &weights, t - h, 2);
        assert!(close(d3[0], (ap[0] - am[0]) / (2.0 * h), 1e-4));
    }

    #[test]
    fn unit_weights_reduce_to_bspline() {
        let knots = [0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0];
        let ctrl: Vec<Vec<f64>> = (0..5)
            .map(|i| vec![i as f64, ((i * 7) % 3) as f64])
            .collect();
        let w = [1.0; 5];
        for j in 0..=30 {
            let t = j as f64 / 10.0;
            for k in 0..=3 {
                let a = nurbs_deriv(&knots, 2, &ctrl, &w, t, k);
                let b = crate::bspline::bspline_deriv(&knots, 2, &ctrl, t, k);
                assert!(close(a[0], b[0], 1e-12) && close(a[1], b[1], 1e-12));
            }
        }
    }

    #[test]
    #[should_panic(expected = "weights must be positive")]
    fn rejects_zero_weight() {
        let (knots, ctrl, mut weights) = nurbs_circle();
        weights[3] = 0.0;
        let _ = nurbs_point(&knots, 2, &ctrl, &weights, 0.5);
    }
}
