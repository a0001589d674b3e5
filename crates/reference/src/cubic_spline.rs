//! Interpolating cubic splines via the dense `4n × 4n` linear system of seeds/004
//! ("Gleichungssystem"), solved with [`solve_dense`].
//!
//! For nodes `t_0 < … < t_n` and points `P_0..P_n` the seed seeks per interval
//! `i = 1..n` a cubic `f_i(t) = a_i + b_i t + c_i t² + d_i t³` with
//!
//! * `f_1(t_0) = P_0` and `f_i(t_i) = P_i` for `i = 1..n` (interpolation, `n + 1` equations),
//! * `f_i(t_i) = f_{i+1}(t_i)`, `f_i'(t_i) = f_{i+1}'(t_i)`, `f_i''(t_i) = f_{i+1}''(t_i)` for
//!   `i = 1..n−1` (C⁰, C¹, C², `3(n − 1)` equations),
//! * two end equations: natural `f_1''(t_0) = 0 = f_n''(t_n)` (seeds/004); clamped
//!   `f_1'(t_0) = m_start`, `f_n'(t_n) = m_end` (seeds/003, "man gibt die 1. Ableitung in den
//!   Endpunkten vor"); periodic (`P_n = P_0`) `f_1'(t_0) = f_n'(t_n)` and
//!   `f_1''(t_0) = f_n''(t_n)` (C¹ and C² across the seam).
//!
//! That is `4n` equations in `4n` unknowns, set up densely and solved once per coordinate.
//! **Conditioning:** each piece uses the *local* variable `s = t − t_{i−1}` instead of `t`
//! (`f_i = a_i + b_i s + c_i s² + d_i s³`); the equations are the same with `t_{i−1} ↦ 0` and
//! `t_i ↦ h_i = t_i − t_{i−1}`. Pieces are stored 0-based here: piece `j = i − 1` covers
//! `[t_j, t_{j+1}]`.

use crate::linalg::solve_dense;
use crate::piece::find_piece;
use crate::poly::Poly;

enum Ends<'a> {
    Natural,
    Clamped(&'a [f64], &'a [f64]),
    Periodic,
}

/// An interpolating cubic spline computed by the dense seeds/004 system (see the module docs).
///
/// Evaluation clamps `u` to `[t_0, t_n]`; at an inner node the piece starting there is used,
/// at `t_n` the last piece ([`find_piece`]).
///
/// ```
/// use strak_ref::CubicSplineRef;
/// // Natural spline through (0,0), (1,1), (2,0): on [0,1] it is 1.5t − 0.5t³.
/// let s = CubicSplineRef::natural(&[0.0, 1.0, 2.0], &[vec![0.0], vec![1.0], vec![0.0]]);
/// assert!((s.eval(0.5)[0] - (0.75 - 0.0625)).abs() < 1e-14);
/// assert!(s.deriv(0.0, 2)[0].abs() < 1e-14);
/// ```
#[derive(Debug, Clone)]
pub struct CubicSplineRef {
    nodes: Vec<f64>,
    /// `pieces[j][c]`: coordinate `c` of piece `j` as a polynomial in `s = u − t_j`.
    pieces: Vec<Vec<Poly>>,
}

impl CubicSplineRef {
    /// The natural cubic spline (`f'' = 0` at both ends, seeds/004).
    ///
    /// # Panics
    /// If fewer than two points are given, the lengths or dimensions differ, the nodes are not
    /// strictly increasing, or the system is singular.
    ///
    /// ```
    /// let s = strak_ref::CubicSplineRef::natural(&[0.0, 2.0], &[vec![1.0, 1.0], vec![3.0, 5.0]]);
    /// assert_eq!(s.eval(1.0), vec![2.0, 3.0]); // two points: the straight line
    /// ```
    pub fn natural(nodes: &[f64], pts: &[Vec<f64>]) -> Self {
        Self::build(nodes, pts, Ends::Natural)
    }

    /// The clamped (complete) cubic spline with prescribed first derivatives at both ends.
    ///
    /// # Panics
    /// As [`CubicSplineRef::natural`], and if a tangent's dimension differs from the points'.
    ///
    /// ```
    /// // Reproduces the cubic t³ exactly when given its end slopes.
    /// let nodes = [0.0, 0.5, 1.5, 2.0];
    /// let pts: Vec<Vec<f64>> = nodes.iter().map(|t| vec![t * t * t]).collect();
    /// let s = strak_ref::CubicSplineRef::clamped(&nodes, &pts, &[0.0], &[12.0]);
    /// assert!((s.eval(1.2)[0] - 1.728).abs() < 1e-12);
    /// ```
    pub fn clamped(
        nodes: &[f64],
        pts: &[Vec<f64>],
        start_tangent: &[f64],
        end_tangent: &[f64],
    ) -> Self {
        Self::build(nodes, pts, Ends::Clamped(start_tangent, end_tangent))
    }

    /// The periodic cubic spline: the last point must equal the first *exactly*; the two end
    /// equations are replaced by C¹ and C² continuity across the seam `t_n ≡ t_0`.
    ///
    /// # Panics
    /// As [`CubicSplineRef::natural`], and if `pts` does not end with a copy of `pts[0]`.
    ///
    /// ```
    /// let nodes = [0.0, 1.0, 2.0, 3.0];
    /// let pts = [vec![1.0], vec![0.0], vec![-1.0], vec![1.0]];
    /// let s = strak_ref::CubicSplineRef::periodic(&nodes, &pts);
    /// assert!((s.deriv(0.0, 1)[0] - s.deriv(3.0, 1)[0]).abs() < 1e-12);
    /// ```
    pub fn periodic(nodes: &[f64], pts: &[Vec<f64>]) -> Self {
        assert!(
            pts.len() >= 2 && pts[0] == pts[pts.len() - 1],
            "CubicSplineRef::periodic: last point must equal the first"
        );
        Self::build(nodes, pts, Ends::Periodic)
    }

    fn build(nodes: &[f64], pts: &[Vec<f64>], ends: Ends<'_>) -> Self {
        assert!(pts.len() >= 2, "CubicSplineRef: need at least two points");
        assert_eq!(
            nodes.len(),
            pts.len(),
            "CubicSplineRef: nodes/points mismatch"
        );
        assert!(
            nodes.windows(2).all(|w| w[0] < w[1]) && nodes.iter().all(|t| t.is_finite()),
            "CubicSplineRef: nodes must be finite and strictly increasing"
        );
        let dim = pts[0].len();
        assert!(
            pts.iter().all(|p| p.len() == dim),
            "CubicSplineRef: dimension mismatch"
        );
        if let Ends::Clamped(a, b) = ends {
            assert!(
                a.len() == dim && b.len() == dim,
                "CubicSplineRef: tangent dimension mismatch"
            );
        }
        let n = nodes.len() - 1;
        let h: Vec<f64> = (0..n).map(|j| nodes[j + 1] - nodes[j]).collect();
        // Unknown index of coefficient c (0=a, 1=b, 2=c, 3=d) of seed interval i (1-based).
        let col = |i: usize, c: usize| 4 * (i - 1) + c;
        let hi = |i: usize| h[i - 1];
        let size = 4 * n;
        // Each row: (coefficients, right-hand side as a function of the coordinate).
        let mut rows: Vec<(Vec<f64>, Rhs)> = Vec::with_capacity(size);
        let new_row = || vec![0.0; size];
        // f_1(t_0) = P_0.
        let mut r = new_row();
        r[col(1, 0)] = 1.0;
        rows.push((r, Rhs::Point(0)));
        // f_i(t_i) = P_i, i = 1..n.
        for i in 1..=n {
            let mut r = new_row();
            r[col(i, 0)] = 1.0;
            r[col(i, 1)] = hi(i);
            r[col(i, 2)] = hi(i).powi(2);
            r[col(i, 3)] = hi(i).powi(3);
            rows.push((r, Rhs::Point(i)));
        }
        // C⁰, C¹, C² at t_i, i = 1..n−1.
        for i in 1..n {
            let x = hi(i);
            let mut c0 = new_row();
            c0[col(i, 0)] = 1.0;
            c0[col(i, 1)] = x;
            c0[col(i, 2)] = x * x;
            c0[col(i, 3)] = x * x * x;
            c0[col(i + 1, 0)] = -1.0;
            rows.push((c0, Rhs::Zero));
            let mut c1 = new_row();
            c1[col(i, 1)] = 1.0;
            c1[col(i, 2)] = 2.0 * x;
            c1[col(i, 3)] = 3.0 * x * x;
            c1[col(i + 1, 1)] = -1.0;
            rows.push((c1, Rhs::Zero));
            let mut c2 = new_row();
            c2[col(i, 2)] = 2.0;
            c2[col(i, 3)] = 6.0 * x;
            c2[col(i + 1, 2)] = -2.0;
            rows.push((c2, Rhs::Zero));
        }
        // End equations. f_n'(t_n) and f_n''(t_n) rows in the unknowns of piece n:
        let x = hi(n);
        let mut d1_end = new_row();
        d1_end[col(n, 1)] = 1.0;
        d1_end[col(n, 2)] = 2.0 * x;
        d1_end[col(n, 3)] = 3.0 * x * x;
        let mut d2_end = new_row();
        d2_end[col(n, 2)] = 2.0;
        d2_end[col(n, 3)] = 6.0 * x;
        let mut d1_start = new_row();
        d1_start[col(1, 1)] = 1.0;
        let mut d2_start = new_row();
        d2_start[col(1, 2)] = 2.0;
        match ends {
            Ends::Natural => {
                rows.push((d2_start, Rhs::Zero));
                rows.push((d2_end, Rhs::Zero));
            }
            Ends::Clamped(..) => {
                rows.push((d1_start, Rhs::StartTangent));
                rows.push((d1_end, Rhs::EndTangent));
            }
            Ends::Periodic => {
                let diff = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x - y).collect();
                rows.push((diff(&d1_start, &d1_end), Rhs::Zero));
                rows.push((diff(&d2_start, &d2_end), Rhs::Zero));
            }
        }
        assert_eq!(rows.len(), size, "4n equations");
        let matrix: Vec<Vec<f64>> = rows.iter().map(|(r, _)| r.clone()).collect();
        let mut pieces = vec![Vec::with_capacity(dim); n];
        for c in 0..dim {
            let rhs: Vec<f64> = rows
                .iter()
                .map(|(_, kind)| match *kind {
                    Rhs::Zero => 0.0,
                    Rhs::Point(i) => pts[i][c],
                    Rhs::StartTangent => match ends {
                        Ends::Clamped(a, _) => a[c],
                        _ => 0.0,
                    },
                    Rhs::EndTangent => match ends {
                        Ends::Clamped(_, b) => b[c],
                        _ => 0.0,
                    },
                })
                .collect();
            let x = solve_dense(matrix.clone(), rhs).expect("CubicSplineRef: singular system");
            for (j, piece) in pieces.iter_mut().enumerate() {
                piece.push(Poly::new(x[4 * j..4 * j + 4].to_vec()));
            }
        }
        Self {
            nodes: nodes.to_vec(),
            pieces,
        }
    }

    /// The nodes `t_0..t_n`.
    ///
    /// ```
    /// let s = strak_ref::CubicSplineRef::natural(&[0.0, 1.0], &[vec![0.0], vec![1.0]]);
    /// assert_eq!(s.nodes(), &[0.0, 1.0]);
    /// ```
    pub fn nodes(&self) -> &[f64] {
        &self.nodes
    }

    /// Number of pieces `n`.
    ///
    /// ```
    /// let s = strak_ref::CubicSplineRef::natural(&[0.0, 1.0, 3.0], &[vec![0.0], vec![1.0], vec![0.0]]);
    /// assert_eq!(s.piece_count(), 2);
    /// ```
    pub fn piece_count(&self) -> usize {
        self.pieces.len()
    }

    /// Coordinate `coord` of piece `j` (on `[t_j, t_{j+1}]`) as the cubic
    /// `a + b s + c s² + d s³` in the local variable `s = u − t_j` (the seed's `a_i, b_i, c_i,
    /// d_i` for `i = j + 1`, in the local variable).
    ///
    /// # Panics
    /// If `j` or `coord` is out of range.
    ///
    /// ```
    /// let s = strak_ref::CubicSplineRef::natural(&[0.0, 1.0, 2.0], &[vec![0.0], vec![1.0], vec![0.0]]);
    /// let p = s.piece_poly(0, 0);
    /// assert!((p.coeffs[1] - 1.5).abs() < 1e-14 && (p.coeffs[3] + 0.5).abs() < 1e-14);
    /// ```
    pub fn piece_poly(&self, j: usize, coord: usize) -> &Poly {
        &self.pieces[j][coord]
    }

    /// The point at `u` (clamped to `[t_0, t_n]`).
    ///
    /// ```
    /// let s = strak_ref::CubicSplineRef::natural(&[0.0, 1.0, 2.0], &[vec![0.0], vec![1.0], vec![0.0]]);
    /// assert!((s.eval(1.0)[0] - 1.0).abs() < 1e-14);
    /// assert!((s.eval(-3.0)[0]).abs() < 1e-14);
    /// ```
    pub fn eval(&self, u: f64) -> Vec<f64> {
        self.deriv(u, 0)
    }

    /// The `k`-th derivative at `u` (clamped; piece convention of [`find_piece`]).
    ///
    /// ```
    /// let s = strak_ref::CubicSplineRef::natural(&[0.0, 1.0, 2.0], &[vec![0.0], vec![1.0], vec![0.0]]);
    /// assert!((s.deriv(0.0, 1)[0] - 1.5).abs() < 1e-14);
    /// assert_eq!(s.deriv(0.5, 4), vec![0.0]);
    /// ```
    pub fn deriv(&self, u: f64, k: usize) -> Vec<f64> {
        let (j, u) = find_piece(&self.nodes, u);
        let s = u - self.nodes[j];
        self.pieces[j]
            .iter()
            .map(|p| p.nth_derivative(k).eval(s))
            .collect()
    }
}

#[derive(Clone, Copy)]
enum Rhs {
    Zero,
    Point(usize),
    StartTangent,
    EndTangent,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parameterization::chord_length_nodes;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    /// Left limit of the k-th derivative at node index `i` (end of piece i − 1).
    fn left_deriv(s: &CubicSplineRef, i: usize, k: usize) -> Vec<f64> {
        let h = s.nodes[i] - s.nodes[i - 1];
        s.pieces[i - 1]
            .iter()
            .map(|p| p.nth_derivative(k).eval(h))
            .collect()
    }

    fn sample() -> (Vec<f64>, Vec<Vec<f64>>) {
        let pts = vec![
            vec![0.0, 0.0],
            vec![1.0, 2.0],
            vec![3.0, 3.0],
            vec![4.0, 1.0],
            vec![6.0, 0.0],
        ];
        (chord_length_nodes(&pts), pts)
    }

    #[test]
    fn natural_interpolates_zero_end_curvature_and_c2_inside() {
        let (nodes, pts) = sample();
        let s = CubicSplineRef::natural(&nodes, &pts);
        for (i, p) in pts.iter().enumerate() {
            let e = s.eval(nodes[i]);
            assert!(close(e[0], p[0], 1e-12) && close(e[1], p[1], 1e-12));
        }
        let n = nodes.len() - 1;
        for c in 0..2 {
            assert!(close(s.deriv(nodes[0], 2)[c], 0.0, 1e-12));
            assert!(close(s.deriv(nodes[n], 2)[c], 0.0, 1e-12));
        }
        for i in 1..n {
            for k in 0..=2 {
                let l = left_deriv(&s, i, k);
                let r = s.deriv(nodes[i], k);
                for c in 0..2 {
                    assert!(close(l[c], r[c], 1e-11), "node {i} k {k}");
                }
            }
            // The third derivative jumps in general.
            let l3 = left_deriv(&s, i, 3);
            let r3 = s.deriv(nodes[i], 3);
            assert!((l3[0] - r3[0]).abs() > 1e-6);
        }
    }

    #[test]
    fn natural_closed_form_three_points() {
        // (0,0), (1,1), (2,0): moments M0 = M2 = 0, M1 = −3, so f = 1.5t − 0.5t³ on [0,1].
        let s = CubicSplineRef::natural(&[0.0, 1.0, 2.0], &[vec![0.0], vec![1.0], vec![0.0]]);
        for j in 0..=10 {
            let t = j as f64 / 10.0;
            assert!(close(s.eval(t)[0], 1.5 * t - 0.5 * t * t * t, 1e-14));
            assert!(close(s.eval(2.0 - t)[0], 1.5 * t - 0.5 * t * t * t, 1e-14));
        }
        assert!(close(s.deriv(1.0, 2)[0], -3.0, 1e-13));
    }

    #[test]
    fn clamped_reproduces_cubic() {
        let p = |t: f64| t * t * t - 2.0 * t + 1.0;
        let dp = |t: f64| 3.0 * t * t - 2.0;
        let nodes = [-1.0, 0.0, 0.3, 1.0, 2.5];
        let pts: Vec<Vec<f64>> = nodes.iter().map(|&t| vec![p(t), -p(t)]).collect();
        let s = CubicSplineRef::clamped(&nodes, &pts, &[dp(-1.0), -dp(-1.0)], &[dp(2.5), -dp(2.5)]);
        for j in 0..=35 {
            let t = -1.0 + j as f64 / 10.0;
            let e = s.eval(t);
            assert!(close(e[0], p(t), 1e-12) && close(e[1], -p(t), 1e-12));
            assert!(close(s.deriv(t, 1)[0], dp(t), 1e-11));
            assert!(close(s.deriv(t, 3)[0], 6.0, 1e-9));
        }
    }

    #[test]
    fn periodic_is_c2_across_seam() {
        let k = 8;
        let nodes: Vec<f64> = (0..=k).map(|i| i as f64 * 0.75).collect();
        let mut pts: Vec<Vec<f64>> = (0..k)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / k as f64;
                vec![a.cos(), (2.0 * a).sin()]
            })
            .collect();
        pts.push(pts[0].clone());
        let s = CubicSplineRef::periodic(&nodes, &pts);
        let n = nodes.len() - 1;
        for kd in 0..=2 {
            let start = s.deriv(nodes[0], kd);
            let end = left_deriv(&s, n, kd);
            for c in 0..2 {
                assert!(close(start[c], end[c], 1e-11), "k={kd}");
            }
        }
        for i in 1..n {
            for kd in 0..=2 {
                let l = left_deriv(&s, i, kd);
                let r = s.deriv(nodes[i], kd);
                assert!(close(l[0], r[0], 1e-11) && close(l[1], r[1], 1e-11));
            }
        }
    }

    #[test]
    #[should_panic(expected = "last point must equal the first")]
    fn periodic_rejects_open_points() {
        let _ = CubicSplineRef::periodic(&[0.0, 1.0, 2.0], &[vec![0.0], vec![1.0], vec![0.5]]);
    }

    #[test]
    #[should_panic(expected = "strictly increasing")]
    fn rejects_unsorted_nodes() {
        let _ = CubicSplineRef::natural(&[0.0, 1.0, 1.0], &[vec![0.0], vec![1.0], vec![0.5]]);
    }
}
