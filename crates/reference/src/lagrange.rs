//! Lagrange interpolation (seeds/000/002 "Lagrange Interpolation", seeds/003).

use crate::poly::Poly;
use crate::vecops::weighted_sum;

/// The Lagrange basis polynomial `L_i(t) = Π_{k≠i} (t − u_k) / (u_i − u_k)` for the nodes
/// `u_0..u_g` (seeds/000), evaluated as that product at any real `t`.
///
/// # Panics
/// If `i >= nodes.len()`.
///
/// ```
/// // seeds/002: nodes {0, 1, 3}, L_0(t) = (t² − 4t + 3)/3.
/// assert_eq!(strak_ref::lagrange_basis(&[0.0, 1.0, 3.0], 0, 2.0), -1.0 / 3.0);
/// ```
pub fn lagrange_basis(nodes: &[f64], i: usize, t: f64) -> f64 {
    assert!(i < nodes.len(), "lagrange_basis: index out of range");
    let mut l = 1.0;
    for (k, &uk) in nodes.iter().enumerate() {
        if k != i {
            l *= (t - uk) / (nodes[i] - uk);
        }
    }
    l
}

/// `L_i` expanded into the monomial basis: the product of the linear factors
/// `(t − u_k) / (u_i − u_k)`, `k ≠ i`, multiplied out with [`Poly`].
///
/// # Panics
/// If `i >= nodes.len()`.
///
/// ```
/// let l1 = strak_ref::lagrange_basis_poly(&[0.0, 1.0, 3.0], 1);
/// assert_eq!(l1.coeffs, vec![0.0, 1.5, -0.5]); // t(t − 3)/(−2)
/// ```
pub fn lagrange_basis_poly(nodes: &[f64], i: usize) -> Poly {
    assert!(i < nodes.len(), "lagrange_basis_poly: index out of range");
    let mut p = Poly::constant(1.0);
    for (k, &uk) in nodes.iter().enumerate() {
        if k != i {
            p = (&p * &Poly::from_root(uk)).scale(1.0 / (nodes[i] - uk));
        }
    }
    p
}

/// The Lagrange curve `c(t) = Σ q_i L_i(t)` through `pts[i]` at `nodes[i]` (seeds/000), at any
/// real `t` (no clamping: it is one polynomial).
///
/// # Panics
/// If `nodes` and `pts` differ in length, or are empty.
///
/// ```
/// let c = strak_ref::lagrange_point(&[0.0, 1.0, 3.0], &[vec![1.0, 0.0], vec![-1.0, 0.0], vec![3.0, 3.0]], 3.0);
/// assert_eq!(c, vec![3.0, 3.0]);
/// ```
pub fn lagrange_point(nodes: &[f64], pts: &[Vec<f64>], t: f64) -> Vec<f64> {
    assert_eq!(nodes.len(), pts.len(), "lagrange_point: length mismatch");
    let w: Vec<f64> = (0..nodes.len())
        .map(|i| lagrange_basis(nodes, i, t))
        .collect();
    weighted_sum(pts, &w)
}

/// The exact `k`-th derivative `c^{(k)}(t) = Σ q_i L_i^{(k)}(t)`: each `L_i` is expanded into a
/// [`Poly`] ([`lagrange_basis_poly`]) and differentiated `k` times.
///
/// # Panics
/// If `nodes` and `pts` differ in length, or are empty.
///
/// ```
/// // Through (0,0), (1,1), (2,4): the parabola t², second derivative 2.
/// let d = strak_ref::lagrange_deriv(&[0.0, 1.0, 2.0], &[vec![0.0], vec![1.0], vec![4.0]], 0.3, 2);
/// assert!((d[0] - 2.0).abs() < 1e-13);
/// ```
pub fn lagrange_deriv(nodes: &[f64], pts: &[Vec<f64>], t: f64, k: usize) -> Vec<f64> {
    assert_eq!(nodes.len(), pts.len(), "lagrange_deriv: length mismatch");
    let w: Vec<f64> = (0..nodes.len())
        .map(|i| lagrange_basis_poly(nodes, i).nth_derivative(k).eval(t))
        .collect();
    weighted_sum(pts, &w)
}

#[cfg(test)]
mod tests {
    use super::*;

    const NODES: [f64; 3] = [0.0, 1.0, 3.0];

    fn seed_pts() -> Vec<Vec<f64>> {
        vec![vec![1.0, 0.0], vec![-1.0, 0.0], vec![3.0, 3.0]]
    }

    #[test]
    fn seed_basis_formulas() {
        // seeds/002: L_0 = (t² − 4t + 3)/3, L_1 = t(t − 3)/(−2), L_2 = t(t − 1)/6.
        for j in -10..=40 {
            let t = j as f64 / 10.0;
            let l0 = (t * t - 4.0 * t + 3.0) / 3.0;
            let l1 = t * (t - 3.0) / -2.0;
            let l2 = t * (t - 1.0) / 6.0;
            assert!((lagrange_basis(&NODES, 0, t) - l0).abs() < 1e-13);
            assert!((lagrange_basis(&NODES, 1, t) - l1).abs() < 1e-13);
            assert!((lagrange_basis(&NODES, 2, t) - l2).abs() < 1e-13);
            assert!((lagrange_basis_poly(&NODES, 0).eval(t) - l0).abs() < 1e-13);
            assert!((lagrange_basis_poly(&NODES, 2).eval(t) - l2).abs() < 1e-13);
            // Affine invariance: Σ L_i = 1.
            let s: f64 = (0..3).map(|i| lagrange_basis(&NODES, i, t)).sum();
            assert!((s - 1.0).abs() < 1e-13);
        }
    }

    #[test]
    fn seed_curve_interpolates_and_matches_formula() {
        let pts = seed_pts();
        for (i, p) in pts.iter().enumerate() {
            let c = lagrange_point(&NODES, &pts, NODES[i]);
            assert!((c[0] - p[0]).abs() < 1e-15 && (c[1] - p[1]).abs() < 1e-15);
        }
        // c(t) = (1,0)(t²−4t+3)/3 + (−1,0) t(t−3)/(−2) + (3,3) t(t−1)/6.
        let t = 2.0;
        let l0 = (t * t - 4.0 * t + 3.0) / 3.0;
        let l1 = t * (t - 3.0) / -2.0;
        let l2 = t * (t - 1.0) / 6.0;
        let c = lagrange_point(&NODES, &pts, t);
        assert!((c[0] - (l0 - l1 + 3.0 * l2)).abs() < 1e-14);
        assert!((c[1] - 3.0 * l2).abs() < 1e-14);
    }

    #[test]
    fn derivatives_of_seed_curve() {
        // x(t) = (t²−4t+3)/3 + t(t−3)/2 + t(t−1)/2 = (4/3)t² − (10/3)t + 1, y(t) = (t² − t)/2.
        let pts = seed_pts();
        let t = 0.7;
        let d1 = lagrange_deriv(&NODES, &pts, t, 1);
        assert!((d1[0] - (8.0 / 3.0 * t - 10.0 / 3.0)).abs() < 1e-13);
        assert!((d1[1] - (t - 0.5)).abs() < 1e-13);
        let d2 = lagrange_deriv(&NODES, &pts, t, 2);
        assert!((d2[0] - 8.0 / 3.0).abs() < 1e-13 && (d2[1] - 1.0).abs() < 1e-13);
        assert_eq!(lagrange_deriv(&NODES, &pts, t, 3), vec![0.0, 0.0]);
        let d0 = lagrange_deriv(&NODES, &pts, t, 0);
        let p = lagrange_point(&NODES, &pts, t);
        assert!((d0[0] - p[0]).abs() < 1e-14 && (d0[1] - p[1]).abs() < 1e-14);
    }
}
