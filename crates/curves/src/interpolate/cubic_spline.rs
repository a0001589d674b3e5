//! Interpolating cubic splines: piecewise cubic curves through the points, C² at the inner
//! nodes, with two end conditions (de Boor, *A Practical Guide to Splines*, ch. IV "Cubic
//! spline interpolation", "Boundary conditions"; Burden & Faires, *Numerical Analysis*,
//! §3.5 "Cubic Spline Interpolation").
//!
//! The spline is stored in Hermite form: per node the point `q_i` and the first derivative
//! `m_i` (w.r.t. `u`), each piece evaluated as a [`HermiteSegment`](crate::HermiteSegment)
//! (Bézier form, de Casteljau). C² continuity at node `i` (with `h_i = u_{i+1} − u_i` and the
//! slopes `δ_i = (q_{i+1} − q_i)/h_i`) is the tridiagonal equation of de Boor's slope form
//!
//! `m_{i−1}/h_{i−1} + 2·(1/h_{i−1} + 1/h_i)·m_i + m_{i+1}/h_i = 3·(δ_{i−1}/h_{i−1} + δ_i/h_i)`,
//!
//! which replaces the dense `4n × 4n` system for the monomial coefficients of every piece by
//! an `O(n)` solve
//! ([`solve_tridiagonal`](crate::solve_tridiagonal), or
//! [`solve_cyclic_tridiagonal`](crate::solve_cyclic_tridiagonal) for closed curves). The end
//! conditions: natural `c''(u_0) = 0 ⇔ 2m_0 + m_1 = 3δ_0` and
//! `c''(u_n) = 0 ⇔ m_{n−1} + 2m_n = 3δ_{n−1}`; clamped (complete) `m_0`, `m_n` given;
//! periodic: the C² equation also at the seam `u_0 ≅ u_n`, a cyclic tridiagonal system.

use heapless::Vec;

use super::hermite::{HermiteSpline, check_points};
use super::parameterization::NodeSource;
use super::tridiagonal::{solve_cyclic_tridiagonal, solve_tridiagonal};
use crate::error::Error;
use crate::point::{MAX_DIM, Point};
use crate::scalar::Scalar;

/// The two end conditions of an interpolating [`CubicSpline`].
///
/// ```
/// use strak_curves::SplineBoundary;
///
/// let b = SplineBoundary::Clamped { start: [1.0_f64, 0.0], end: [0.0, 1.0] };
/// assert_ne!(b, SplineBoundary::Natural);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SplineBoundary<P> {
    /// Natural spline: zero second derivative at both ends, `c''(u_0) = c''(u_n) = 0`.
    Natural,
    /// Clamped (complete) spline: the first derivatives (w.r.t. `u`) at the two ends are given.
    Clamped {
        /// `c'(u_0)`.
        start: P,
        /// `c'(u_n)`.
        end: P,
    },
    /// Closed (periodic) spline: the last point must be *exactly* equal to the first (else
    /// [`Error::InvalidArgument`]); the curve is C² across the seam, `c^{(k)}(u_0) = c^{(k)}(u_n)`
    /// for `k ≤ 2`. Needs at least 3 points (2 distinct ones and the repeated first).
    Periodic,
}

/// An interpolating cubic spline through at most `N` points: C² at
/// the inner nodes, with the end conditions of a [`SplineBoundary`].
///
/// Nodes are given or computed by a [`Parameterization`](crate::Parameterization) (chord
/// length is the usual choice for curves). `u` outside `[u_0, u_n]` is clamped. Every
/// tangent depends on every point (no local control). The linear system is solved once
/// in `f64` in fixed storage (`O(n)`); the node derivatives are then rounded to the scalar
/// type and the spline is evaluated in it as Hermite pieces.
///
/// ```
/// use strak_curves::{CubicSpline, ParamCurve, ParamCurveDeriv, Parameterization, SplineBoundary};
///
/// let pts = [[0.0_f64, 0.0], [1.0, 1.0], [2.0, 0.0]];
/// let s = CubicSpline::<_, 8>::new(&pts, Parameterization::Uniform, SplineBoundary::Natural)
///     .unwrap();
/// // 2m0 + m1 = 3δ0, m0 + 4m1 + m2 = 3(δ0 + δ1), m1 + 2m2 = 3δ1 (unit intervals)
/// for (m, want) in s.tangents().iter().zip([[1.0, 1.5], [1.0, 0.0], [1.0, -1.5]]) {
///     assert!((m[0] - want[0]).abs() < 1e-15 && (m[1] - want[1]).abs() < 1e-15);
/// }
/// assert_eq!(s.eval(1.0), [1.0, 1.0]);
/// assert!(s.deriv(0.0, 2)[1].abs() < 1e-14); // natural end
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct CubicSpline<P: Point, const N: usize> {
    hermite: HermiteSpline<P, N>,
    boundary: SplineBoundary<P>,
}

impl<P: Point, const N: usize> CubicSpline<P, N> {
    /// The interpolating cubic spline through `points` at the given or computed nodes, with the
    /// end conditions `boundary`.
    ///
    /// # Errors
    /// [`Error::TooFewPoints`] (below 2; below 3 for [`SplineBoundary::Periodic`]),
    /// [`Error::CapacityExceeded`] above `N` points, [`Error::LengthMismatch`] (given nodes),
    /// [`Error::NonFinite`] (points, nodes, clamped end derivatives),
    /// [`Error::NodesNotIncreasing`], [`Error::ZeroLengthInterval`] (computed nodes),
    /// [`Error::InvalidArgument`] for a periodic spline whose last point differs from the
    /// first, [`Error::OutOfRange`] when a node derivative or a value an evaluation can produce
    /// (derivatives up to order 3) does not fit the scalar type.
    ///
    /// ```
    /// use strak_curves::{CubicSpline, Error, Parameterization, SplineBoundary};
    ///
    /// let open = [[0.0_f32, 0.0], [1.0, 0.0], [1.0, 1.0]];
    /// let e = CubicSpline::<_, 4>::new(&open, Parameterization::ChordLength, SplineBoundary::Periodic);
    /// assert_eq!(e, Err(Error::InvalidArgument));
    /// let closed = [[0.0_f32, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 0.0]];
    /// assert!(CubicSpline::<_, 4>::new(&closed, Parameterization::ChordLength, SplineBoundary::Periodic).is_ok());
    /// ```
    pub fn new<'a>(
        points: &[P],
        nodes: impl Into<NodeSource<'a, P::Scalar>>,
        boundary: SplineBoundary<P>,
    ) -> Result<Self, Error> {
        let periodic = matches!(boundary, SplineBoundary::Periodic);
        check_points::<P, N>(points, if periodic { 3 } else { 2 })?;
        match boundary {
            SplineBoundary::Periodic => {
                if points.first() != points.last() {
                    return Err(Error::InvalidArgument);
                }
            }
            SplineBoundary::Clamped { start, end } => {
                if !(start.is_finite() && end.is_finite()) {
                    return Err(Error::NonFinite);
                }
            }
            SplineBoundary::Natural => {}
        }
        let nodes = nodes.into().resolve::<P, N>(points)?;
        let tangents = solve_tangents::<P, N>(points, &nodes, boundary)?;
        let hermite = HermiteSpline::new(points, &tangents, NodeSource::Given(&nodes))?;
        Ok(Self { hermite, boundary })
    }

    /// The end conditions.
    pub fn boundary(&self) -> SplineBoundary<P> {
        self.boundary
    }

    /// The nodes `u_0 < … < u_n`.
    pub fn nodes(&self) -> &[P::Scalar] {
        self.hermite.nodes()
    }

    /// The interpolated points.
    pub fn points(&self) -> &[P] {
        self.hermite.points()
    }

    /// The first derivatives (w.r.t. `u`) at the nodes, solved from the C² conditions.
    pub fn tangents(&self) -> &[P] {
        self.hermite.tangents()
    }

    /// The spline as a Hermite spline (same nodes, points and node derivatives).
    pub fn as_hermite(&self) -> &HermiteSpline<P, N> {
        &self.hermite
    }
}

/// Sets up and solves the tridiagonal (or cyclic) system for the node derivatives, in `f64`.
fn solve_tangents<P: Point, const N: usize>(
    points: &[P],
    nodes: &[P::Scalar],
    boundary: SplineBoundary<P>,
) -> Result<Vec<P, N>, Error> {
    let n = points.len() - 1;
    // Interval i = 0 … n−1: 1/h_i and 3·δ_i/h_i, computed from the data when needed (the
    // construction stack holds only the system: 5·N scalars and N right-hand sides).
    let h = |i: usize| match (nodes.get(i), nodes.get(i + 1)) {
        (Some(a), Some(b)) => b.to_f64() - a.to_f64(),
        _ => f64::NAN,
    };
    let inv_h = |i: usize| 1.0 / h(i);
    let rhs_part = |i: usize| -> [f64; MAX_DIM] {
        let hi = h(i);
        match (points.get(i), points.get(i + 1)) {
            (Some(a), Some(b)) => {
                let (a, b) = (a.to_f64_array(), b.to_f64_array());
                core::array::from_fn(|c| 3.0 * (b[c] - a[c]) / (hi * hi))
            }
            _ => [f64::NAN; MAX_DIM],
        }
    };
    let mut sub = [0.0_f64; N];
    let mut diag = [0.0_f64; N];
    let mut sup = [0.0_f64; N];
    let mut rhs = [[0.0_f64; MAX_DIM]; N];
    let mut scratch = [0.0_f64; N];
    let add = |a: [f64; MAX_DIM], b: [f64; MAX_DIM]| -> [f64; MAX_DIM] {
        core::array::from_fn(|c| a[c] + b[c])
    };
    let size = if matches!(boundary, SplineBoundary::Periodic) {
        n
    } else {
        n + 1
    };
    for i in 1..n {
        sub[i] = inv_h(i - 1);
        diag[i] = 2.0 * (inv_h(i - 1) + inv_h(i));
        sup[i] = inv_h(i);
        rhs[i] = add(rhs_part(i - 1), rhs_part(i));
    }
    match boundary {
        SplineBoundary::Natural => {
            diag[0] = 2.0 * inv_h(0);
            sup[0] = inv_h(0);
            rhs[0] = rhs_part(0);
            sub[n] = inv_h(n - 1);
            diag[n] = 2.0 * inv_h(n - 1);
            rhs[n] = rhs_part(n - 1);
            solve_tridiagonal(
                &sub[..size],
                &diag[..size],
                &sup[..size],
                &mut rhs[..size],
                &mut scratch[..size],
            )?;
        }
        SplineBoundary::Clamped { start, end } => {
            diag[0] = 1.0;
            rhs[0] = start.to_f64_array();
            diag[n] = 1.0;
            rhs[n] = end.to_f64_array();
            solve_tridiagonal(
                &sub[..size],
                &diag[..size],
                &sup[..size],
                &mut rhs[..size],
                &mut scratch[..size],
            )?;
        }
        SplineBoundary::Periodic => {
            // Row 0 wraps around: its left neighbour is node n − 1 (interval n − 1).
            sub[0] = inv_h(n - 1);
            diag[0] = 2.0 * (inv_h(n - 1) + inv_h(0));
            sup[0] = inv_h(0);
            rhs[0] = add(rhs_part(n - 1), rhs_part(0));
            // Row n − 1's right neighbour is node n ≅ node 0: the corner entry sup[n − 1].
            let mut correction = [0.0_f64; N];
            solve_cyclic_tridiagonal(
                &sub[..size],
                &diag[..size],
                &sup[..size],
                &mut rhs[..size],
                &mut scratch[..size],
                &mut correction[..size],
            )?;
            rhs[n] = rhs[0];
        }
    }
    let mut tangents: Vec<P, N> = Vec::new();
    for (i, m) in rhs.iter().take(n + 1).enumerate() {
        let p = match boundary {
            SplineBoundary::Clamped { start, .. } if i == 0 => start,
            SplineBoundary::Clamped { end, .. } if i == n => end,
            _ => P::from_f64_slice(&m[..P::DIM]).ok_or(Error::OutOfRange)?,
        };
        tangents.push(p).map_err(|_| Error::CapacityExceeded {
            capacity: N,
            required: n + 1,
        })?;
    }
    // Round-trip check of the solve (only fails on non-finite f64 results).
    if tangents
        .iter()
        .all(|m| m.is_finite() && <P::Scalar as Scalar>::fits(m.max_abs()))
    {
        Ok(tangents)
    } else {
        Err(Error::OutOfRange)
    }
}

super::hermite::curve_via_hermite!(CubicSpline);

#[cfg(test)]
#[allow(clippy::needless_range_loop, clippy::cast_possible_truncation)]
mod tests {
    use super::*;
    use crate::Parameterization;
    use crate::curve::{ParamCurve, ParamCurveDeriv};
    use crate::scalar::{I16F16, I32F32};

    const PTS: [[f64; 2]; 6] = [
        [0.0, 0.0],
        [1.0, 2.0],
        [3.0, 3.0],
        [4.0, 0.0],
        [6.0, 1.0],
        [7.0, -2.0],
    ];
    const CHORD: Parameterization = Parameterization::ChordLength;

    fn near(a: [f64; 2], b: [f64; 2], tol: f64) -> bool {
        (a[0] - b[0]).abs() <= tol && (a[1] - b[1]).abs() <= tol
    }

    fn natural() -> CubicSpline<[f64; 2], 8> {
        CubicSpline::new(&PTS, CHORD, SplineBoundary::Natural).unwrap()
    }

    /// The dense 4n×4n system of the monomial pieces for one coordinate, solved by Gaussian elimination
    /// with partial pivoting: f_i(t) = a + b t + c t² + d t³ on [t_{i−1}, t_i].
    fn dense_natural(t: &[f64], y: &[f64]) -> [[f64; 4]; 5] {
        const M: usize = 20;
        let n = t.len() - 1;
        assert_eq!(4 * n, M);
        let mut a = [[0.0_f64; M + 1]; M];
        let mut row = 0;
        let put =
            |a: &mut [[f64; M + 1]; M], row: usize, piece: usize, x: f64, order: u32, s: f64| {
                let cols: [f64; 4] = match order {
                    0 => [1.0, x, x * x, x * x * x],
                    1 => [0.0, 1.0, 2.0 * x, 3.0 * x * x],
                    _ => [0.0, 0.0, 2.0, 6.0 * x],
                };
                for k in 0..4 {
                    a[row][4 * piece + k] += s * cols[k];
                }
            };
        put(&mut a, row, 0, t[0], 0, 1.0);
        a[row][M] = y[0];
        row += 1;
        for i in 1..=n {
            put(&mut a, row, i - 1, t[i], 0, 1.0);
            a[row][M] = y[i];
            row += 1;
        }
        for i in 1..n {
            for order in 0..3 {
                put(&mut a, row, i - 1, t[i], order, 1.0);
                put(&mut a, row, i, t[i], order, -1.0);
                row += 1;
            }
        }
        put(&mut a, row, 0, t[0], 2, 1.0);
        row += 1;
        put(&mut a, row, n - 1, t[n], 2, 1.0);
        row += 1;
        assert_eq!(row, M);
        for col in 0..M {
            let piv = (col..M)
                .max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))
                .unwrap();
            a.swap(col, piv);
            for r in 0..M {
                if r != col {
                    let f = a[r][col] / a[col][col];
                    for k in col..=M {
                        a[r][k] -= f * a[col][k];
                    }
                }
            }
        }
        core::array::from_fn(|i| {
            core::array::from_fn(|k| a[4 * i + k][M] / a[4 * i + k][4 * i + k])
        })
    }

    #[test]
    fn natural_matches_dense_system() {
        let s = natural();
        let t = s.nodes();
        for c in 0..2 {
            let y: [f64; 6] = core::array::from_fn(|i| PTS[i][c]);
            let coef = dense_natural(t, &y);
            for i in 0..5 {
                for j in 0..=10 {
                    let x = t[i] + (t[i + 1] - t[i]) * f64::from(j) / 10.0;
                    let [a, b, cc, d] = coef[i];
                    let want = ((d * x + cc) * x + b) * x + a;
                    assert!((s.eval(x)[c] - want).abs() < 1e-9, "piece {i} x {x}");
                }
            }
        }
    }

    #[test]
    fn interpolates_and_is_c2() {
        for b in [
            SplineBoundary::Natural,
            SplineBoundary::Clamped {
                start: [1.0, 0.0],
                end: [0.0, -3.0],
            },
        ] {
            let s = CubicSpline::<_, 8>::new(&PTS, CHORD, b).unwrap();
            assert_eq!(s.boundary(), b);
            assert_eq!(s.points(), &PTS);
            assert_eq!(s.piece_count(), 5);
            for (i, p) in PTS.iter().enumerate() {
                assert_eq!(s.eval(s.nodes()[i]), *p);
            }
            for i in 1..5 {
                let u = s.nodes()[i];
                let left = s.as_hermite().segment(i - 1).unwrap();
                for k in 1..=2 {
                    assert!(
                        near(left.deriv(u, k), s.deriv(u, k), 1e-12),
                        "node {i} order {k}"
                    );
                }
            }
        }
    }

    #[test]
    fn natural_ends_have_zero_curvature() {
        let s = natural();
        let (a, b) = s.domain();
        assert!(near(s.deriv(a, 2), [0.0, 0.0], 1e-13));
        assert!(near(s.deriv(b, 2), [0.0, 0.0], 1e-13));
    }

    #[test]
    fn hand_solved_three_points() {
        // natural: 2m0 + m1 = 3, m0 + 4m1 + m2 = 0, m1 + 2m2 = −3 (y); x is a line
        let pts = [[0.0_f64, 0.0], [1.0, 1.0], [2.0, 0.0]];
        let s = CubicSpline::<_, 4>::new(&pts, Parameterization::Uniform, SplineBoundary::Natural)
            .unwrap();
        for (m, want) in s
            .tangents()
            .iter()
            .zip([[1.0, 1.5], [1.0, 0.0], [1.0, -1.5]])
        {
            assert!(near(*m, want, 1e-15));
        }
        // y on [0,1]: 1.5u − 0.5u³
        assert!((s.eval(0.5)[1] - (0.75 - 0.0625)).abs() < 1e-15);
        assert!(near(s.deriv(0.5, 3), [0.0, -3.0], 1e-14));
        // clamped with zero end slopes: m1 = 0 too
        let z = [0.0, 0.0];
        let s = CubicSpline::<_, 4>::new(
            &pts,
            Parameterization::Uniform,
            SplineBoundary::Clamped { start: z, end: z },
        )
        .unwrap();
        // x: 4m1 = 3(δ0 + δ1) = 6; y: 4m1 = 3(1 − 1) = 0
        for (m, want) in s
            .tangents()
            .iter()
            .zip([[0.0, 0.0], [1.5, 0.0], [0.0, 0.0]])
        {
            assert!(near(*m, want, 1e-15));
        }
    }

    #[test]
    fn clamped_end_tangents() {
        let start = [2.0, -1.0];
        let end = [0.5, 0.25];
        let s =
            CubicSpline::<_, 8>::new(&PTS, CHORD, SplineBoundary::Clamped { start, end }).unwrap();
        let (a, b) = s.domain();
        assert_eq!(s.deriv(a, 1), start);
        assert!(near(s.deriv(b, 1), end, 1e-13));
        assert_eq!(s.tangents()[5], end);
    }

    #[test]
    fn periodic_seam_is_c2() {
        let pts = [
            [0.0_f64, 0.0],
            [2.0, 0.0],
            [3.0, 2.0],
            [1.0, 3.0],
            [-1.0, 1.0],
            [0.0, 0.0],
        ];
        let s = CubicSpline::<_, 8>::new(&pts, CHORD, SplineBoundary::Periodic).unwrap();
        let (a, b) = s.domain();
        assert_eq!(s.eval(a), s.eval(b));
        for k in 1..=2 {
            assert!(near(s.deriv(a, k), s.deriv(b, k), 1e-12), "order {k}");
        }
        for i in 1..5 {
            let u = s.nodes()[i];
            let left = s.as_hermite().segment(i - 1).unwrap();
            assert!(near(left.deriv(u, 2), s.deriv(u, 2), 1e-12));
        }
        // three points: a closed loop through two distinct points
        let s = CubicSpline::<_, 3>::new(
            &[[0.0_f64], [1.0], [0.0]],
            Parameterization::Uniform,
            SplineBoundary::Periodic,
        )
        .unwrap();
        assert!(near(
            [s.deriv(0.0, 2)[0], 0.0],
            [s.deriv(2.0, 2)[0], 0.0],
            1e-13
        ));
        assert_eq!(s.tangents(), &[[0.0], [0.0], [0.0]]);
    }

    #[test]
    fn straight_line_is_reproduced() {
        // points on a line at uneven spacing, chord-length nodes: the spline is the line.
        let pts = [
            [1.0_f64, 1.0],
            [1.6, 1.8],
            [4.6, 5.8],
            [5.2, 6.6],
            [11.2, 14.6],
        ];
        for b in [
            SplineBoundary::Natural,
            SplineBoundary::Clamped {
                start: [0.6, 0.8],
                end: [0.6, 0.8],
            },
        ] {
            let s = CubicSpline::<_, 8>::new(&pts, CHORD, b).unwrap();
            let (_, end) = s.domain();
            assert!((end - 17.0).abs() < 1e-12);
            for j in 0..=85 {
                let u = f64::from(j) / 5.0;
                let want = [1.0 + 0.6 * u, 1.0 + 0.8 * u];
                assert!(near(s.eval(u), want, 1e-12), "u = {u}");
                assert!(near(s.deriv(u, 1), [0.6, 0.8], 1e-12));
                assert!(near(s.deriv(u, 2), [0.0, 0.0], 1e-11));
            }
        }
    }

    #[test]
    fn scalar_types_agree_with_f64() {
        let s = natural();
        let nodes = s.nodes();
        let p32: [[f32; 2]; 6] = PTS.map(|p| p.map(|x| x as f32));
        let n32: [f32; 6] = core::array::from_fn(|i| nodes[i] as f32);
        let pi16 = PTS.map(|p| p.map(I16F16::from_num));
        let ni16: [I16F16; 6] = core::array::from_fn(|i| I16F16::from_num(nodes[i]));
        let pi32 = PTS.map(|p| p.map(I32F32::from_num));
        let ni32: [I32F32; 6] = core::array::from_fn(|i| I32F32::from_num(nodes[i]));
        let a = CubicSpline::<_, 8>::new(&p32, &n32, SplineBoundary::Natural).unwrap();
        let b = CubicSpline::<_, 8>::new(&pi16, &ni16, SplineBoundary::Natural).unwrap();
        let c = CubicSpline::<_, 8>::new(&pi32, &ni32, SplineBoundary::Natural).unwrap();
        let end = nodes[5];
        for j in 0..=100 {
            let u = end * f64::from(j) / 100.0;
            for k in 0..=3 {
                let want = s.deriv(u, k);
                let fa = a.deriv(u as f32, k).map(f64::from);
                let fb = b.deriv(I16F16::from_num(u), k).map(|x| x.to_num::<f64>());
                let fc = c.deriv(I32F32::from_num(u), k).map(|x| x.to_num::<f64>());
                // Stated tolerances (shortest interval ≈ 2.2): f32 1e-4, I16F16 2e-3
                // (nodes rounded to 2^-16), I32F32 1e-7.
                assert!(near(fa, want, 1e-4), "f32 k={k} u={u}: {fa:?} {want:?}");
                assert!(near(fb, want, 2e-3), "I16F16 k={k} u={u}: {fb:?} {want:?}");
                assert!(near(fc, want, 1e-7), "I32F32 k={k} u={u}: {fc:?} {want:?}");
            }
        }
    }

    #[test]
    fn glam_points() {
        use glam::{DVec2, Vec3};
        let pts = PTS.map(|p| DVec2::new(p[0], p[1]));
        let s = CubicSpline::<_, 8>::new(&pts, CHORD, SplineBoundary::Natural).unwrap();
        let r = natural();
        for j in 0..=20 {
            let u = r.domain().1 * f64::from(j) / 20.0;
            let (a, b) = (s.eval(u), r.eval(u));
            assert!((a.x - b[0]).abs() < 1e-12 && (a.y - b[1]).abs() < 1e-12);
        }
        let pts3 = [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 1.0), Vec3::ZERO];
        let s = CubicSpline::<_, 4>::new(&pts3, CHORD, SplineBoundary::Periodic).unwrap();
        assert_eq!(s.eval(s.nodes()[2]), Vec3::new(1.0, 1.0, 1.0));
        assert!((s.deriv(0.0, 1) - s.deriv(s.domain().1, 1)).length() < 1e-5);
    }

    #[test]
    fn error_non_finite() {
        let nat = SplineBoundary::Natural;
        assert_eq!(
            CubicSpline::<_, 8>::new(&[[0.0, f64::NAN], [1.0, 1.0]], CHORD, nat),
            Err(Error::NonFinite)
        );
        let bad = SplineBoundary::Clamped {
            start: [f64::INFINITY, 0.0],
            end: [0.0, 0.0],
        };
        assert_eq!(
            CubicSpline::<_, 8>::new(&PTS, CHORD, bad),
            Err(Error::NonFinite)
        );
        assert_eq!(
            CubicSpline::<_, 8>::new(&PTS, &[0.0, 1.0, 2.0, f64::NAN, 4.0, 5.0], nat),
            Err(Error::NonFinite)
        );
    }

    #[test]
    fn error_too_few_points() {
        assert_eq!(
            CubicSpline::<_, 8>::new(&PTS[..1], CHORD, SplineBoundary::Natural),
            Err(Error::TooFewPoints {
                required: 2,
                found: 1
            })
        );
        assert_eq!(
            CubicSpline::<_, 8>::new(&[[0.0_f64], [0.0]], CHORD, SplineBoundary::Periodic),
            Err(Error::TooFewPoints {
                required: 3,
                found: 2
            })
        );
    }

    #[test]
    fn error_capacity_exceeded() {
        assert_eq!(
            CubicSpline::<_, 5>::new(&PTS, CHORD, SplineBoundary::Natural),
            Err(Error::CapacityExceeded {
                capacity: 5,
                required: 6
            })
        );
    }

    #[test]
    fn error_nodes_not_increasing() {
        assert_eq!(
            CubicSpline::<_, 8>::new(
                &PTS,
                &[0.0, 1.0, 2.0, 3.0, 3.0, 5.0],
                SplineBoundary::Natural
            ),
            Err(Error::NodesNotIncreasing { index: 4 })
        );
    }

    #[test]
    fn error_zero_length_interval() {
        let pts = [[0.0_f64, 0.0], [1.0, 1.0], [1.0, 1.0]];
        assert_eq!(
            CubicSpline::<_, 8>::new(&pts, CHORD, SplineBoundary::Natural),
            Err(Error::ZeroLengthInterval { index: 1 })
        );
    }

    #[test]
    fn error_length_mismatch() {
        assert_eq!(
            CubicSpline::<_, 8>::new(&PTS, &[0.0, 1.0, 2.0], SplineBoundary::Natural),
            Err(Error::LengthMismatch {
                expected: 6,
                found: 3
            })
        );
    }

    #[test]
    fn error_out_of_range() {
        // I16F16: an interval of 1/256 between points 100 apart gives slopes of 25 600.
        let f = |x: f64| I16F16::from_num(x);
        let pts = [[f(0.0)], [f(100.0)], [f(0.0)]];
        let nodes = [f(0.0), f(1.0 / 256.0), f(1.0)];
        assert_eq!(
            CubicSpline::<_, 4>::new(&pts, &nodes, SplineBoundary::Natural),
            Err(Error::OutOfRange)
        );
        // the same data is fine in f32
        let pts = [[0.0_f32], [100.0], [0.0]];
        let nodes = [0.0, 1.0 / 256.0, 1.0];
        assert!(CubicSpline::<_, 4>::new(&pts, &nodes, SplineBoundary::Natural).is_ok());
    }

    #[test]
    fn error_periodic_not_closed() {
        let pts = [[0.0_f64, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1e-12]];
        assert_eq!(
            CubicSpline::<_, 8>::new(&pts, CHORD, SplineBoundary::Periodic),
            Err(Error::InvalidArgument)
        );
    }

    #[test]
    fn breaks_are_c2_but_not_c3_and_left_limits_differ() {
        use crate::{PieceDeriv, classify_breaks};
        let pts = [
            [0.0_f64, 0.0],
            [1.0, 2.0],
            [3.0, 3.0],
            [4.0, 0.0],
            [6.0, 1.0],
        ];
        let c =
            CubicSpline::<_, 8>::new(&pts, Parameterization::ChordLength, SplineBoundary::Natural)
                .unwrap();
        let k = classify_breaks(&c, 1e-9).unwrap();
        assert_eq!(k.parametric, Some(2));
        let (_, end) = c.piece_domain(0);
        let left = c.piece_deriv(0, end, 3);
        let right = c.piece_deriv(1, end, 3);
        assert_ne!(left, right, "the third derivative jumps at an inner node");
        assert_eq!(
            c.deriv(end, 3),
            right,
            "deriv at a node uses the piece starting there"
        );
    }
}
