//! Cubic Hermite interpolation: the matrix `K` and `K⁻¹` of seeds/003, the Hermite basis of
//! seeds/002, Hermite segments with the `Δ` scaling of seeds/002, Hermite splines and
//! Catmull–Rom tangents.
//!
//! Basis order (seeds/002): `H0 = (1−t)²(1+2t)`, `H1 = t(1−t)²`, `H2 = −t²(1−t)`,
//! `H3 = (3−2t)t²`. In seeds/003's names these are `H_{r,0}`, `H_{r,1}`, `H_{r+1,1}`,
//! `H_{r+1,0}`; note `H2 = −t²(1−t) = t³ − t² = H_{r+1,1}` — the two seeds agree in sign
//! (`H2'(1) = 1`), the minus sign of seeds/002 is only the factored form.

use crate::linalg::invert;
use crate::piece::find_piece;
use crate::poly::Poly;
use crate::vecops::{vec_add_scaled, vec_scale, vec_sub, vec_zero};

/// The matrix `K` of seeds/003 for the parameter interval `[t0, t1]`: rows
/// `(t0³, t0², t0, 1)`, `(t1³, t1², t1, 1)`, `(3t0², 2t0, 1, 0)`, `(3t1², 2t1, 1, 0)`, so that
/// `(P_r, P_{r+1}, P'_r, P'_{r+1})ᵀ = K M_H` for `Q(t) = (t³, t², t, 1) M_H`.
///
/// ```
/// let k = strak_ref::hermite_k(0.0, 1.0);
/// assert_eq!(k[3], [3.0, 2.0, 1.0, 0.0]);
/// ```
pub fn hermite_k(t0: f64, t1: f64) -> [[f64; 4]; 4] {
    [
        [t0 * t0 * t0, t0 * t0, t0, 1.0],
        [t1 * t1 * t1, t1 * t1, t1, 1.0],
        [3.0 * t0 * t0, 2.0 * t0, 1.0, 0.0],
        [3.0 * t1 * t1, 2.0 * t1, 1.0, 0.0],
    ]
}

/// `K⁻¹` for `t0 = 0, t1 = 1`, computed by inverting [`hermite_k`]`(0, 1)` with [`invert`]
/// (not hard-coded). seeds/003 prints it as
/// `[[2, −2, 1, 1], [−3, 3, −2, −1], [0, 0, 1, 0], [1, 0, 0, 0]]`.
///
/// # Panics
/// Never (`K(0, 1)` is regular); an `expect` guards the inversion.
///
/// ```
/// let ki = strak_ref::hermite_k_inverse();
/// assert!((ki[0][0] - 2.0).abs() < 1e-15 && (ki[1][3] + 1.0).abs() < 1e-15);
/// ```
pub fn hermite_k_inverse() -> [[f64; 4]; 4] {
    let k: Vec<Vec<f64>> = hermite_k(0.0, 1.0).iter().map(|r| r.to_vec()).collect();
    let inv = invert(&k).expect("K(0,1) is regular");
    let mut out = [[0.0; 4]; 4];
    for i in 0..4 {
        for j in 0..4 {
            out[i][j] = inv[i][j];
        }
    }
    out
}

/// The four cubic Hermite basis polynomials `[H0, H1, H2, H3]` (seeds/002 order) as
/// [`Poly`]s, read from the columns of [`hermite_k_inverse`]: `Q(t) = (t³, t², t, 1) K⁻¹ G` with
/// `G = (P_r, P_{r+1}, P'_r, P'_{r+1})`, so column `j` of `K⁻¹` holds the `(t³, t², t, 1)`
/// coefficients of the function multiplying `G_j`. `H0 ↔ P_r`, `H1 ↔ P'_r`, `H2 ↔ P'_{r+1}`,
/// `H3 ↔ P_{r+1}`.
///
/// ```
/// let h = strak_ref::hermite_basis_polys();
/// // H3 = 3t² − 2t³ (seeds/003's H_{r+1,0}).
/// let c: Vec<f64> = h[3].coeffs.iter().map(|c| c.round()).collect();
/// assert_eq!(c, vec![0.0, 0.0, 3.0, -2.0]);
/// ```
pub fn hermite_basis_polys() -> [Poly; 4] {
    let ki = hermite_k_inverse();
    let column = |j: usize| Poly::new(vec![ki[3][j], ki[2][j], ki[1][j], ki[0][j]]);
    [column(0), column(2), column(3), column(1)]
}

/// The Hermite basis values `[H0(t), H1(t), H2(t), H3(t)]` (seeds/002 order), derived from
/// `K⁻¹` via [`hermite_basis_polys`].
///
/// ```
/// let h = strak_ref::hermite_basis(0.5);
/// assert!((h[0] - 0.5).abs() < 1e-15 && (h[1] - 0.125).abs() < 1e-15);
/// assert!((h[2] + 0.125).abs() < 1e-15 && (h[3] - 0.5).abs() < 1e-15);
/// ```
pub fn hermite_basis(t: f64) -> [f64; 4] {
    hermite_basis_deriv(t, 0)
}

/// The `k`-th derivatives `[H0^{(k)}(t), …, H3^{(k)}(t)]` of the Hermite basis.
///
/// ```
/// // H0'(0) = 0, H1'(0) = 1, H2'(1) = 1, H3'(1) = 0.
/// assert!((strak_ref::hermite_basis_deriv(0.0, 1)[1] - 1.0).abs() < 1e-15);
/// assert!((strak_ref::hermite_basis_deriv(1.0, 1)[2] - 1.0).abs() < 1e-15);
/// ```
pub fn hermite_basis_deriv(t: f64, k: usize) -> [f64; 4] {
    let h = hermite_basis_polys();
    [
        h[0].nth_derivative(k).eval(t),
        h[1].nth_derivative(k).eval(t),
        h[2].nth_derivative(k).eval(t),
        h[3].nth_derivative(k).eval(t),
    ]
}

/// One cubic Hermite segment on `[u0, u1]` (seeds/002, "in Klausur gegeben"):
/// `c(t) = H0(s) q0 + Δ H1(s) m0 + Δ H2(s) m1 + H3(s) q1` with `Δ = u1 − u0`,
/// `s = (t − u0)/Δ`. Then `c(u0) = q0`, `c(u1) = q1`, `c'(u0) = m0`, `c'(u1) = m1`.
/// Evaluated at any real `t` (no clamping: one polynomial).
///
/// # Panics
/// If the points differ in dimension.
///
/// ```
/// // Straight line from 0 to 2 on [0, 2] with matching tangents 1: c(t) = t.
/// let c = strak_ref::hermite_segment(&[0.0], &[2.0], &[1.0], &[1.0], 0.0, 2.0, 0.5);
/// assert!((c[0] - 0.5).abs() < 1e-15);
/// ```
pub fn hermite_segment(
    q0: &[f64],
    q1: &[f64],
    m0: &[f64],
    m1: &[f64],
    u0: f64,
    u1: f64,
    t: f64,
) -> Vec<f64> {
    hermite_segment_deriv(q0, q1, m0, m1, u0, u1, t, 0)
}

/// The `k`-th derivative with respect to `t` of [`hermite_segment`]: by the chain rule
/// `d^k/dt^k = Δ^{−k} d^k/ds^k`, i.e.
/// `Δ^{−k} (H0^{(k)}(s) q0 + Δ H1^{(k)}(s) m0 + Δ H2^{(k)}(s) m1 + H3^{(k)}(s) q1)`.
///
/// # Panics
/// If the points differ in dimension.
///
/// ```
/// let d = strak_ref::hermite_segment_deriv(&[0.0], &[1.0], &[5.0], &[-2.0], 0.0, 1.0, 1.0, 1);
/// assert!((d[0] + 2.0).abs() < 1e-14);
/// ```
#[allow(clippy::too_many_arguments)]
pub fn hermite_segment_deriv(
    q0: &[f64],
    q1: &[f64],
    m0: &[f64],
    m1: &[f64],
    u0: f64,
    u1: f64,
    t: f64,
    k: usize,
) -> Vec<f64> {
    let delta = u1 - u0;
    let s = (t - u0) / delta;
    let h = hermite_basis_deriv(s, k);
    let mut c = vec_zero(q0.len());
    vec_add_scaled(&mut c, q0, h[0]);
    vec_add_scaled(&mut c, m0, delta * h[1]);
    vec_add_scaled(&mut c, m1, delta * h[2]);
    vec_add_scaled(&mut c, q1, h[3]);
    vec_scale(&c, delta.powi(-(k as i32)))
}

/// A cubic Hermite spline through `pts[i]` at `nodes[i]` with tangents `tangents[i]`
/// (seeds/002): segment `i` is [`hermite_segment`] on `[u_i, u_{i+1}]`. `u` is clamped to
/// `[u_0, u_n]`; piece choice by [`find_piece`].
///
/// # Panics
/// If fewer than two nodes are given or the lengths differ.
///
/// ```
/// let nodes = [0.0, 1.0, 3.0];
/// let pts = [vec![0.0], vec![1.0], vec![0.0]];
/// let m = [vec![0.0], vec![0.0], vec![0.0]];
/// assert_eq!(strak_ref::hermite_spline(&nodes, &pts, &m, 1.0), vec![1.0]);
/// ```
pub fn hermite_spline(nodes: &[f64], pts: &[Vec<f64>], tangents: &[Vec<f64>], u: f64) -> Vec<f64> {
    hermite_spline_deriv(nodes, pts, tangents, u, 0)
}

/// The `k`-th derivative of [`hermite_spline`] (same clamping and piece convention).
///
/// # Panics
/// If fewer than two nodes are given or the lengths differ.
///
/// ```
/// let nodes = [0.0, 1.0, 3.0];
/// let pts = [vec![0.0], vec![1.0], vec![0.0]];
/// let m = [vec![2.0], vec![-1.0], vec![0.5]];
/// let d = strak_ref::hermite_spline_deriv(&nodes, &pts, &m, 1.0, 1);
/// assert!((d[0] + 1.0).abs() < 1e-14);
/// ```
pub fn hermite_spline_deriv(
    nodes: &[f64],
    pts: &[Vec<f64>],
    tangents: &[Vec<f64>],
    u: f64,
    k: usize,
) -> Vec<f64> {
    assert_eq!(
        nodes.len(),
        pts.len(),
        "hermite_spline: nodes/points mismatch"
    );
    assert_eq!(
        nodes.len(),
        tangents.len(),
        "hermite_spline: nodes/tangents mismatch"
    );
    let (i, u) = find_piece(nodes, u);
    hermite_segment_deriv(
        &pts[i],
        &pts[i + 1],
        &tangents[i],
        &tangents[i + 1],
        nodes[i],
        nodes[i + 1],
        u,
        k,
    )
}

/// Catmull–Rom style tangents for non-uniform nodes: inner
/// `m_i = (q_{i+1} − q_{i−1}) / (u_{i+1} − u_{i−1})`, at the ends the one-sided differences
/// `m_0 = (q_1 − q_0)/(u_1 − u_0)` and `m_n = (q_n − q_{n−1})/(u_n − u_{n−1})`.
///
/// # Panics
/// If fewer than two nodes are given or the lengths differ.
///
/// ```
/// let m = strak_ref::catmull_rom_tangents(&[0.0, 1.0, 3.0], &[vec![0.0], vec![2.0], vec![8.0]]);
/// assert_eq!(m, vec![vec![2.0], vec![8.0 / 3.0], vec![3.0]]);
/// ```
pub fn catmull_rom_tangents(nodes: &[f64], pts: &[Vec<f64>]) -> Vec<Vec<f64>> {
    assert_eq!(
        nodes.len(),
        pts.len(),
        "catmull_rom_tangents: length mismatch"
    );
    let n = nodes.len();
    assert!(n >= 2, "catmull_rom_tangents: need at least two points");
    (0..n)
        .map(|i| {
            let (a, b) = if i == 0 {
                (0, 1)
            } else if i == n - 1 {
                (n - 2, n - 1)
            } else {
                (i - 1, i + 1)
            };
            vec_scale(&vec_sub(&pts[b], &pts[a]), 1.0 / (nodes[b] - nodes[a]))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn k_inverse_equals_seed() {
        let seed = [
            [2.0, -2.0, 1.0, 1.0],
            [-3.0, 3.0, -2.0, -1.0],
            [0.0, 0.0, 1.0, 0.0],
            [1.0, 0.0, 0.0, 0.0],
        ];
        let ki = hermite_k_inverse();
        for i in 0..4 {
            for j in 0..4 {
                assert!(
                    close(ki[i][j], seed[i][j], 1e-15),
                    "K⁻¹[{i}][{j}] = {}",
                    ki[i][j]
                );
            }
        }
        assert_eq!(hermite_k(0.0, 1.0)[0], [0.0, 0.0, 0.0, 1.0]);
        assert_eq!(hermite_k(0.0, 1.0)[1], [1.0, 1.0, 1.0, 1.0]);
        assert_eq!(hermite_k(2.0, 3.0)[2], [12.0, 4.0, 1.0, 0.0]);
    }

    #[test]
    fn basis_equals_seed_002_formulas() {
        for j in 0..=20 {
            let t = j as f64 / 20.0;
            let s = 1.0 - t;
            let seed = [
                s * s * (1.0 + 2.0 * t),
                t * s * s,
                -t * t * s,
                (3.0 - 2.0 * t) * t * t,
            ];
            let h = hermite_basis(t);
            for i in 0..4 {
                assert!(close(h[i], seed[i], 1e-15));
            }
            // seeds/003 monomial forms.
            assert!(close(h[0], 2.0 * t * t * t - 3.0 * t * t + 1.0, 1e-15));
            assert!(close(h[3], -2.0 * t * t * t + 3.0 * t * t, 1e-15));
            assert!(close(h[1], t * t * t - 2.0 * t * t + t, 1e-15));
            assert!(close(h[2], t * t * t - t * t, 1e-15));
        }
    }

    #[test]
    fn basis_values_at_0_half_1() {
        let h0 = hermite_basis(0.0);
        let hh = hermite_basis(0.5);
        let h1 = hermite_basis(1.0);
        let exp0 = [1.0, 0.0, 0.0, 0.0];
        let exph = [0.5, 0.125, -0.125, 0.5];
        let exp1 = [0.0, 0.0, 0.0, 1.0];
        for i in 0..4 {
            assert!(close(h0[i], exp0[i], 1e-15));
            assert!(close(hh[i], exph[i], 1e-15));
            assert!(close(h1[i], exp1[i], 1e-15));
        }
        // Derivative conditions δ_{ij} δ_{kr} of seeds/003.
        let d0 = hermite_basis_deriv(0.0, 1);
        let d1 = hermite_basis_deriv(1.0, 1);
        let exd0 = [0.0, 1.0, 0.0, 0.0];
        let exd1 = [0.0, 0.0, 1.0, 0.0];
        for i in 0..4 {
            assert!(close(d0[i], exd0[i], 1e-15));
            assert!(close(d1[i], exd1[i], 1e-15));
        }
    }

    #[test]
    fn segment_interpolates_with_delta_scaling_and_matches_seed_003() {
        let (q0, q1) = (vec![1.0, 2.0], vec![4.0, -1.0]);
        let (m0, m1) = (vec![3.0, 0.5], vec![-2.0, 1.0]);
        let (u0, u1) = (2.0, 4.5);
        let p0 = hermite_segment(&q0, &q1, &m0, &m1, u0, u1, u0);
        let p1 = hermite_segment(&q0, &q1, &m0, &m1, u0, u1, u1);
        let d0 = hermite_segment_deriv(&q0, &q1, &m0, &m1, u0, u1, u0, 1);
        let d1 = hermite_segment_deriv(&q0, &q1, &m0, &m1, u0, u1, u1, 1);
        for c in 0..2 {
            assert!(close(p0[c], q0[c], 1e-14) && close(p1[c], q1[c], 1e-14));
            assert!(close(d0[c], m0[c], 1e-13) && close(d1[c], m1[c], 1e-13));
        }
        // seeds/003 on [0,1]: Q = A t³ + B t² + C t + D with
        // A = 2(P0 − P1) + P0' + P1', B = 3(P1 − P0) − 2P0' − P1', C = P0', D = P0.
        let t = 0.3;
        let q = hermite_segment(&q0, &q1, &m0, &m1, 0.0, 1.0, t);
        for c in 0..2 {
            let a = 2.0 * (q0[c] - q1[c]) + m0[c] + m1[c];
            let b = 3.0 * (q1[c] - q0[c]) - 2.0 * m0[c] - m1[c];
            let expect = a * t * t * t + b * t * t + m0[c] * t + q0[c];
            assert!(close(q[c], expect, 1e-14));
        }
        // Third derivative is constant 6A / Δ³, fourth is zero.
        let d3 = hermite_segment_deriv(&q0, &q1, &m0, &m1, 0.0, 1.0, 0.9, 3);
        assert!(close(d3[0], 6.0 * (2.0 * (1.0 - 4.0) + 3.0 - 2.0), 1e-12));
        let d4 = hermite_segment_deriv(&q0, &q1, &m0, &m1, u0, u1, 3.0, 4);
        assert_eq!(d4, vec![0.0, 0.0]);
    }

    #[test]
    fn spline_is_c1_and_clamps() {
        let nodes = [0.0, 0.5, 2.0, 2.25];
        let pts = vec![
            vec![0.0, 0.0],
            vec![1.0, 1.0],
            vec![2.0, -1.0],
            vec![3.0, 0.0],
        ];
        let m = catmull_rom_tangents(&nodes, &pts);
        for &u in &nodes[1..3] {
            let eps = 1e-9;
            let left = hermite_spline_deriv(&nodes, &pts, &m, u - eps, 1);
            let right = hermite_spline_deriv(&nodes, &pts, &m, u, 1);
            for c in 0..2 {
                assert!(close(left[c], right[c], 1e-6));
            }
        }
        for (i, &u) in nodes.iter().enumerate() {
            let p = hermite_spline(&nodes, &pts, &m, u);
            assert!(close(p[0], pts[i][0], 1e-14) && close(p[1], pts[i][1], 1e-14));
        }
        assert_eq!(hermite_spline(&nodes, &pts, &m, -1.0), pts[0]);
        let end = hermite_spline(&nodes, &pts, &m, 10.0);
        assert!(close(end[0], 3.0, 1e-14) && close(end[1], 0.0, 1e-14));
    }

    #[test]
    fn catmull_rom_ends_are_one_sided() {
        let nodes = [0.0, 2.0, 3.0, 7.0];
        let pts = vec![vec![0.0], vec![4.0], vec![5.0], vec![13.0]];
        let m = catmull_rom_tangents(&nodes, &pts);
        let expect = [2.0, 5.0 / 3.0, 9.0 / 5.0, 2.0];
        for i in 0..4 {
            assert!(close(m[i][0], expect[i], 1e-15), "m[{i}] = {}", m[i][0]);
        }
        let two = catmull_rom_tangents(&[0.0, 2.0], &[vec![1.0], vec![5.0]]);
        assert_eq!(two, vec![vec![2.0], vec![2.0]]);
    }
}
