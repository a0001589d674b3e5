//! Cubic Hermite interpolation: curve pieces through points `q_i` with prescribed tangents
//! `m_i` at nodes `u_i` (Farin, *Curves and Surfaces for CAGD*, 5th ed., §6.5 "Cubic Hermite
//! Interpolation", §8.1 "C1 Piecewise Cubic Hermite Interpolation"; de Boor, *A Practical
//! Guide to Splines*, ch. IV "Piecewise cubic Hermite interpolation").
//!
//! On `[u_i, u_{i+1}]`, with `Δ_i = u_{i+1} − u_i` and `s = (t − u_i)/Δ_i`,
//!
//! `c_i(t) = H0(s)·q_i + Δ_i·H1(s)·m_i + Δ_i·H2(s)·m_{i+1} + H3(s)·q_{i+1}`
//!
//! with the cubic Hermite polynomials `H0 = (1−s)²(1+2s)`, `H1 = s(1−s)²`, `H2 = −s²(1−s)`,
//! `H3 = (3−2s)s²`. The tangents are derivatives with respect to `u` (not `s`), hence the
//! factor `Δ_i`. Each piece is evaluated in its Bézier form
//! `b0 = q_i, b1 = q_i + Δ_i·m_i/3, b2 = q_{i+1} − Δ_i·m_{i+1}/3, b3 = q_{i+1}`
//! with de Casteljau's algorithm (convex combinations only), and its derivatives
//! with respect to `u` as the Bézier curves of the hodograph.

use heapless::Vec;

use super::parameterization::NodeSource;
use crate::curve::{ParamCurve, ParamCurveDeriv, PieceDeriv};
use crate::error::Error;
use crate::point::Point;
use crate::scalar::Scalar;

/// One cubic Hermite piece on `[u0, u1]` through `q0`, `q1` with tangents `m0`, `m1`
/// (derivatives with respect to `u`): `c(u) = H0(s) q0 + Δ H1(s) m0 + Δ H2(s) m1 + H3(s) q1`
/// with `Δ = u1 − u0`, `s = (u − u0)/Δ` (Farin §6.5).
///
/// ```
/// use strak_curves::{HermiteSegment, ParamCurve, ParamCurveDeriv};
///
/// // On [0, 2] from (0, 0) to (2, 0), leaving and arriving with velocity (1, 1) and (1, -1).
/// let seg = HermiteSegment::new(0.0, 2.0, [0.0_f64, 0.0], [2.0, 0.0], [1.0, 1.0], [1.0, -1.0])
///     .unwrap();
/// assert_eq!(seg.eval(0.0), [0.0, 0.0]);
/// assert_eq!(seg.eval(2.0), [2.0, 0.0]);
/// assert_eq!(seg.deriv(2.0, 1), [1.0, -1.0]);
/// // Bézier form: b1 = q0 + Δ·m0/3
/// assert_eq!(seg.bezier_points()[1], [2.0 / 3.0, 2.0 / 3.0]);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HermiteSegment<P: Point> {
    u0: P::Scalar,
    u1: P::Scalar,
    q0: P,
    q1: P,
    m0: P,
    m1: P,
}

impl<P: Point> HermiteSegment<P> {
    /// The Hermite piece on `[u0, u1]` with end points `q0`, `q1` and end tangents `m0`, `m1`.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite value, [`Error::NodesNotIncreasing`]
    /// (`index: 1`) unless `u0 < u1`, [`Error::OutOfRange`] when a value that evaluation can
    /// produce (Bézier points, derivatives up to order 3) does not fit the scalar type.
    ///
    /// ```
    /// use strak_curves::{Error, HermiteSegment};
    ///
    /// let e = HermiteSegment::new(1.0, 1.0, [0.0_f32], [1.0], [0.0], [0.0]);
    /// assert_eq!(e, Err(Error::NodesNotIncreasing { index: 1 }));
    /// ```
    pub fn new(u0: P::Scalar, u1: P::Scalar, q0: P, q1: P, m0: P, m1: P) -> Result<Self, Error> {
        if !(u0.is_finite() && u1.is_finite() && [q0, q1, m0, m1].iter().all(|p| p.is_finite())) {
            return Err(Error::NonFinite);
        }
        if u1 <= u0 {
            return Err(Error::NodesNotIncreasing { index: 1 });
        }
        let bound = piece_bound(u0, u1, q0, q1, m0, m1);
        if !(<P::Scalar as Scalar>::fits(bound)
            && <P::Scalar as Scalar>::fits(u0.to_f64())
            && <P::Scalar as Scalar>::fits(u1.to_f64()))
        {
            return Err(Error::OutOfRange);
        }
        Ok(Self {
            u0,
            u1,
            q0,
            q1,
            m0,
            m1,
        })
    }

    /// The parameter interval `(u0, u1)`.
    pub fn nodes(&self) -> (P::Scalar, P::Scalar) {
        (self.u0, self.u1)
    }

    /// The end points `(q0, q1)`.
    pub fn points(&self) -> (P, P) {
        (self.q0, self.q1)
    }

    /// The end tangents `(m0, m1)` (derivatives with respect to `u`).
    pub fn tangents(&self) -> (P, P) {
        (self.m0, self.m1)
    }

    /// The Bézier points of the piece:
    /// `[q0, q0 + Δ·m0/3, q1 − Δ·m1/3, q1]` with `Δ = u1 − u0`.
    pub fn bezier_points(&self) -> [P; 4] {
        let h = (self.u1 - self.u0) / P::Scalar::from_i16(3);
        [
            self.q0,
            self.q0.plus(self.m0.times(h)),
            self.q1.minus(self.m1.times(h)),
            self.q1,
        ]
    }
}

impl<P: Point> ParamCurve for HermiteSegment<P> {
    type Point = P;

    fn domain(&self) -> (P::Scalar, P::Scalar) {
        (self.u0, self.u1)
    }

    fn eval(&self, u: P::Scalar) -> P {
        eval_piece(self.u0, self.u1, self.q0, self.q1, self.m0, self.m1, u, 0)
    }
}

impl<P: Point> ParamCurveDeriv for HermiteSegment<P> {
    fn deriv(&self, u: P::Scalar, k: usize) -> P {
        eval_piece(self.u0, self.u1, self.q0, self.q1, self.m0, self.m1, u, k)
    }
}

impl<P: Point> PieceDeriv for HermiteSegment<P> {
    fn piece_deriv(&self, _piece: usize, u: P::Scalar, k: usize) -> P {
        self.deriv(u, k)
    }
}

/// A C¹ cubic Hermite spline: pieces [`HermiteSegment`] between consecutive nodes, sharing
/// points and tangents at the nodes (Farin §8.1). Moving a point or tangent changes the two
/// pieces next to it only (local control).
///
/// Holds at most `N` nodes (so `N − 1` pieces). The piece containing `u` is found by binary
/// search over the nodes; `u` outside `[u_0, u_n]` is clamped.
///
/// ```
/// use strak_curves::{HermiteSpline, ParamCurve, ParamCurveDeriv, Parameterization};
///
/// let pts = [[0.0_f64, 0.0], [1.0, 1.0], [2.0, 0.0]];
/// let tangents = [[1.0, 1.0], [1.0, 0.0], [1.0, -1.0]];
/// let h = HermiteSpline::<_, 8>::new(&pts, &tangents, Parameterization::Uniform).unwrap();
/// assert_eq!(h.domain(), (0.0, 2.0));
/// assert_eq!(h.piece_count(), 2);
/// assert_eq!(h.eval(1.0), [1.0, 1.0]);
/// assert_eq!(h.deriv(1.0, 1), [1.0, 0.0]);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct HermiteSpline<P: Point, const N: usize> {
    nodes: Vec<P::Scalar, N>,
    points: Vec<P, N>,
    tangents: Vec<P, N>,
}

impl<P: Point, const N: usize> HermiteSpline<P, N> {
    /// The Hermite spline through `points` with `tangents` (derivatives with respect to `u`)
    /// at the given nodes or at nodes computed by a [`Parameterization`](crate::Parameterization).
    ///
    /// # Errors
    /// [`Error::TooFewPoints`] below 2 points, [`Error::CapacityExceeded`] above `N`,
    /// [`Error::LengthMismatch`] when `tangents` (or given nodes) differ in number from the
    /// points, [`Error::NonFinite`], [`Error::NodesNotIncreasing`],
    /// [`Error::ZeroLengthInterval`] (computed nodes), [`Error::OutOfRange`] when a value an
    /// evaluation can produce does not fit the scalar type.
    ///
    /// ```
    /// use strak_curves::{Error, HermiteSpline, Parameterization};
    ///
    /// let e = HermiteSpline::<_, 4>::new(&[[0.0_f64]], &[[1.0]], Parameterization::Uniform);
    /// assert_eq!(e, Err(Error::TooFewPoints { required: 2, found: 1 }));
    /// ```
    pub fn new<'a>(
        points: &[P],
        tangents: &[P],
        nodes: impl Into<NodeSource<'a, P::Scalar>>,
    ) -> Result<Self, Error> {
        check_points::<P, N>(points, 2)?;
        if tangents.len() != points.len() {
            return Err(Error::LengthMismatch {
                expected: points.len(),
                found: tangents.len(),
            });
        }
        if !tangents.iter().all(|p| p.is_finite()) {
            return Err(Error::NonFinite);
        }
        let nodes = nodes.into().resolve::<P, N>(points)?;
        for ((u, q), m) in nodes
            .windows(2)
            .zip(points.windows(2))
            .zip(tangents.windows(2))
        {
            if let ([u0, u1], [q0, q1], [m0, m1]) = (u, q, m) {
                HermiteSegment::new(*u0, *u1, *q0, *q1, *m0, *m1)?;
            }
        }
        let too_many = |_| Error::CapacityExceeded {
            capacity: N,
            required: points.len(),
        };
        Ok(Self {
            nodes,
            points: Vec::from_slice(points).map_err(too_many)?,
            tangents: Vec::from_slice(tangents).map_err(too_many)?,
        })
    }

    /// The nodes `u_0 < … < u_n`.
    pub fn nodes(&self) -> &[P::Scalar] {
        &self.nodes
    }

    /// The interpolated points `q_0, …, q_n`.
    pub fn points(&self) -> &[P] {
        &self.points
    }

    /// The tangents `m_0, …, m_n` (derivatives with respect to `u`).
    pub fn tangents(&self) -> &[P] {
        &self.tangents
    }

    /// Piece `i` (between nodes `i` and `i + 1`), or `None` for `i ≥ piece_count()`.
    pub fn segment(&self, i: usize) -> Option<HermiteSegment<P>> {
        let (u0, u1, q0, q1, m0, m1) = self.piece_data(i)?;
        Some(HermiteSegment {
            u0,
            u1,
            q0,
            q1,
            m0,
            m1,
        })
    }

    /// The index of the piece containing `u` (binary search): the piece that starts at `u`
    /// when `u` is a node, the last piece at and beyond the end, the first before the start.
    pub fn piece_index(&self, u: P::Scalar) -> usize {
        let count = self.nodes.partition_point(|&x| x <= u);
        count.saturating_sub(1).min(self.pieces() - 1)
    }

    fn pieces(&self) -> usize {
        self.nodes.len().saturating_sub(1).max(1)
    }

    #[allow(clippy::type_complexity)]
    fn piece_data(&self, i: usize) -> Option<(P::Scalar, P::Scalar, P, P, P, P)> {
        Some((
            *self.nodes.get(i)?,
            *self.nodes.get(i + 1)?,
            *self.points.get(i)?,
            *self.points.get(i + 1)?,
            *self.tangents.get(i)?,
            *self.tangents.get(i + 1)?,
        ))
    }
}

impl<P: Point, const N: usize> ParamCurve for HermiteSpline<P, N> {
    type Point = P;

    fn domain(&self) -> (P::Scalar, P::Scalar) {
        let first = self.nodes.first().copied().unwrap_or(P::Scalar::ZERO);
        let last = self.nodes.last().copied().unwrap_or(P::Scalar::ONE);
        (first, last)
    }

    fn eval(&self, u: P::Scalar) -> P {
        self.deriv(u, 0)
    }

    fn piece_count(&self) -> usize {
        self.pieces()
    }

    fn piece_domain(&self, i: usize) -> (P::Scalar, P::Scalar) {
        let i = i.min(self.pieces() - 1);
        match (self.nodes.get(i), self.nodes.get(i + 1)) {
            (Some(&a), Some(&b)) => (a, b),
            _ => self.domain(),
        }
    }
}

impl<P: Point, const N: usize> ParamCurveDeriv for HermiteSpline<P, N> {
    fn deriv(&self, u: P::Scalar, k: usize) -> P {
        let (start, end) = self.domain();
        let u = u.clamp_to(start, end);
        match self.piece_data(self.piece_index(u)) {
            Some((u0, u1, q0, q1, m0, m1)) => eval_piece(u0, u1, q0, q1, m0, m1, u, k),
            None => P::zero(),
        }
    }
}

impl<P: Point, const N: usize> PieceDeriv for HermiteSpline<P, N> {
    fn piece_deriv(&self, piece: usize, u: P::Scalar, k: usize) -> P {
        match self.piece_data(piece.min(self.pieces() - 1)) {
            Some((u0, u1, q0, q1, m0, m1)) => eval_piece(u0, u1, q0, q1, m0, m1, u, k),
            None => P::zero(),
        }
    }
}

/// Checks the number of points (at least `required`, at most `N`) and that they are finite.
pub(super) fn check_points<P: Point, const N: usize>(
    points: &[P],
    required: usize,
) -> Result<(), Error> {
    if points.len() < required {
        return Err(Error::TooFewPoints {
            required,
            found: points.len(),
        });
    }
    if points.len() > N {
        return Err(Error::CapacityExceeded {
            capacity: N,
            required: points.len(),
        });
    }
    if points.iter().all(|p| p.is_finite()) {
        Ok(())
    } else {
        Err(Error::NonFinite)
    }
}

/// `p / s` coordinate by coordinate (`s` is validated non-zero by the caller).
fn div_point<P: Point>(p: P, s: P::Scalar) -> P {
    P::from_coords(|i| p.coord(i) / s)
}

/// The Hermite piece (Bézier form) and its derivatives with respect to `u`, at `u` clamped
/// to `[u0, u1]`. The constructors guarantee `u0 < u1` and that every value fits
/// ([`piece_bound`]).
#[allow(clippy::too_many_arguments)]
pub(super) fn eval_piece<P: Point>(
    u0: P::Scalar,
    u1: P::Scalar,
    q0: P,
    q1: P,
    m0: P,
    m1: P,
    u: P::Scalar,
    k: usize,
) -> P {
    let delta = u1 - u0;
    if delta <= P::Scalar::ZERO {
        return q0;
    }
    let s = (u.clamp_to(u0, u1) - u0) / delta;
    if k == 0 {
        let h = delta / P::Scalar::from_i16(3);
        let b1 = q0.plus(m0.times(h));
        let b2 = q1.minus(m1.times(h));
        // de Casteljau, cubic
        let (a0, a1, a2) = (q0.lerp(b1, s), b1.lerp(b2, s), b2.lerp(q1, s));
        let (c0, c1) = (a0.lerp(a1, s), a1.lerp(a2, s));
        return c0.lerp(c1, s);
    }
    // Hodograph (w.r.t. u): quadratic Bézier m0, d1, m1 with d1 = 3(q1 − q0)/Δ − m0 − m1.
    let d1 = div_point(q1.minus(q0), delta)
        .times(P::Scalar::from_i16(3))
        .minus(m0)
        .minus(m1);
    if k == 1 {
        return m0.lerp(d1, s).lerp(d1.lerp(m1, s), s);
    }
    // Second derivative: linear Bézier e0 = 2(d1 − m0)/Δ, e1 = 2(m1 − d1)/Δ.
    let e0 = div_point(d1.minus(m0), delta).times(P::Scalar::TWO);
    let e1 = div_point(m1.minus(d1), delta).times(P::Scalar::TWO);
    match k {
        2 => e0.lerp(e1, s),
        3 => div_point(e1.minus(e0), delta),
        _ => P::zero(),
    }
}

/// A conservative bound (in `f64`) on the magnitude of every value [`eval_piece`] computes:
/// the parameter span, the Bézier points and the products `Δ·m/3`, the hodograph points and
/// their partial sums, the second-derivative points and the third derivative, including
/// the `1/Δ^k` scaling.
pub(super) fn piece_bound<P: Point>(
    u0: P::Scalar,
    u1: P::Scalar,
    q0: P,
    q1: P,
    m0: P,
    m1: P,
) -> f64 {
    let delta = u1.to_f64() - u0.to_f64();
    let (q0, q1, m0, m1) = (
        q0.to_f64_array(),
        q1.to_f64_array(),
        m0.to_f64_array(),
        m1.to_f64_array(),
    );
    let mut bound = delta;
    for c in 0..P::DIM {
        let (a0, a1, t0, t1) = (q0[c].abs(), q1[c].abs(), m0[c].abs(), m1[c].abs());
        let h = delta / 3.0;
        let pos = (a0 + t0 * delta).max(a1 + t1 * delta);
        let dq = (q1[c] - q0[c]).abs();
        let d1 = 3.0 * dq / delta + t0 + t1;
        let e0 = 2.0 * (d1 + t0) / delta;
        let e1 = 2.0 * (d1 + t1) / delta;
        let third = (e0 + e1) / delta;
        for v in [pos, h, dq, d1, d1 + t0, d1 + t1, e0, e1, e0 + e1, third] {
            // NaN (never expected) counts as out of range
            bound = if v.is_nan() {
                f64::INFINITY
            } else {
                bound.max(v)
            };
        }
    }
    bound
}

/// The curve traits of a type that stores its curve as a `hermite: HermiteSpline<P, N>` field
/// (cubic splines and parabolic blending are Hermite splines with particular tangents).
macro_rules! curve_via_hermite {
    ($t:ident) => {
        impl<P: Point, const N: usize> $crate::curve::ParamCurve for $t<P, N> {
            type Point = P;

            fn domain(&self) -> (P::Scalar, P::Scalar) {
                $crate::curve::ParamCurve::domain(&self.hermite)
            }

            fn eval(&self, u: P::Scalar) -> P {
                $crate::curve::ParamCurve::eval(&self.hermite, u)
            }

            fn piece_count(&self) -> usize {
                $crate::curve::ParamCurve::piece_count(&self.hermite)
            }

            fn piece_domain(&self, i: usize) -> (P::Scalar, P::Scalar) {
                $crate::curve::ParamCurve::piece_domain(&self.hermite, i)
            }
        }

        impl<P: Point, const N: usize> $crate::curve::ParamCurveDeriv for $t<P, N> {
            fn deriv(&self, u: P::Scalar, k: usize) -> P {
                $crate::curve::ParamCurveDeriv::deriv(&self.hermite, u, k)
            }
        }

        impl<P: Point, const N: usize> $crate::curve::PieceDeriv for $t<P, N> {
            fn piece_deriv(&self, piece: usize, u: P::Scalar, k: usize) -> P {
                $crate::curve::PieceDeriv::piece_deriv(&self.hermite, piece, u, k)
            }
        }
    };
}
pub(super) use curve_via_hermite;

#[cfg(test)]
#[allow(clippy::needless_range_loop, clippy::cast_possible_truncation)]
mod tests {
    use super::*;
    use crate::Parameterization;
    use crate::scalar::{I16F16, I32F32};

    fn h0(t: f64) -> f64 {
        (1.0 - t) * (1.0 - t) * (1.0 + 2.0 * t)
    }
    fn h1(t: f64) -> f64 {
        t * (1.0 - t) * (1.0 - t)
    }
    fn h2(t: f64) -> f64 {
        -t * t * (1.0 - t)
    }
    fn h3(t: f64) -> f64 {
        (3.0 - 2.0 * t) * t * t
    }

    /// c_i(t) = H0(s) q_i + Δ H1(s) m_i + Δ H2(s) m_{i+1} + H3(s) q_{i+1}.
    fn textbook_formula(u: [f64; 2], q: [[f64; 2]; 2], m: [[f64; 2]; 2], t: f64) -> [f64; 2] {
        let d = u[1] - u[0];
        let s = (t - u[0]) / d;
        core::array::from_fn(|c| {
            h0(s) * q[0][c] + d * h1(s) * m[0][c] + d * h2(s) * m[1][c] + h3(s) * q[1][c]
        })
    }

    fn close(a: [f64; 2], b: [f64; 2], tol: f64) -> bool {
        (a[0] - b[0]).abs() <= tol && (a[1] - b[1]).abs() <= tol
    }

    const Q: [[f64; 2]; 2] = [[1.0, -2.0], [4.0, 3.0]];
    const M: [[f64; 2]; 2] = [[2.0, 5.0], [-1.0, 0.5]];
    const U: [f64; 2] = [0.5, 3.0];

    fn seg() -> HermiteSegment<[f64; 2]> {
        HermiteSegment::new(U[0], U[1], Q[0], Q[1], M[0], M[1]).unwrap()
    }

    #[test]
    fn segment_matches_textbook_formula() {
        let s = seg();
        for i in 0..=20 {
            let t = U[0] + (U[1] - U[0]) * f64::from(i) / 20.0;
            assert!(
                close(s.eval(t), textbook_formula(U, Q, M, t), 1e-13),
                "t = {t}"
            );
        }
    }

    #[test]
    fn segment_interpolates_points_and_tangents() {
        let s = seg();
        assert_eq!(s.eval(U[0]), Q[0]);
        assert_eq!(s.eval(U[1]), Q[1]);
        assert!(close(s.deriv(U[0], 1), M[0], 1e-13));
        assert!(close(s.deriv(U[1], 1), M[1], 1e-13));
        assert_eq!(s.nodes(), (U[0], U[1]));
        assert_eq!(s.points(), (Q[0], Q[1]));
        assert_eq!(s.tangents(), (M[0], M[1]));
    }

    #[test]
    fn segment_derivatives_match_hermite_matrix_coefficients() {
        // The algebraic form Q(s) = A s³ + B s² + C s + D with the tangents scaled by Δ
        // (A = 2(q0 − q1) + Δm0 + Δm1, B = 3(q1 − q0) − 2Δm0 − Δm1, C = Δm0, D = q0).
        let s = seg();
        let d = U[1] - U[0];
        for c in 0..2 {
            let a = 2.0 * (Q[0][c] - Q[1][c]) + d * M[0][c] + d * M[1][c];
            let b = 3.0 * (Q[1][c] - Q[0][c]) - 2.0 * d * M[0][c] - d * M[1][c];
            let cc = d * M[0][c];
            for i in 0..=10 {
                let x = f64::from(i) / 10.0;
                let t = U[0] + d * x;
                let p = ((a * x + b) * x + cc) * x + Q[0][c];
                let p1 = ((3.0 * a * x + 2.0 * b) * x + cc) / d;
                let p2 = (6.0 * a * x + 2.0 * b) / (d * d);
                let p3 = 6.0 * a / (d * d * d);
                assert!((s.eval(t)[c] - p).abs() < 1e-12);
                assert!((s.deriv(t, 1)[c] - p1).abs() < 1e-12);
                assert!((s.deriv(t, 2)[c] - p2).abs() < 1e-12);
                assert!((s.deriv(t, 3)[c] - p3).abs() < 1e-12);
                assert_eq!(s.deriv(t, 4), [0.0, 0.0]);
            }
        }
    }

    #[test]
    fn segment_clamps_parameter() {
        let s = seg();
        assert_eq!(s.eval(-10.0), Q[0]);
        assert_eq!(s.eval(10.0), Q[1]);
    }

    #[test]
    fn segment_errors() {
        assert_eq!(
            HermiteSegment::new(0.0, f64::NAN, [0.0], [1.0], [0.0], [0.0]),
            Err(Error::NonFinite)
        );
        assert_eq!(
            HermiteSegment::new(0.0, 1.0, [0.0], [1.0], [f64::INFINITY], [0.0]),
            Err(Error::NonFinite)
        );
        assert_eq!(
            HermiteSegment::new(2.0, 1.0, [0.0], [1.0], [0.0], [0.0]),
            Err(Error::NodesNotIncreasing { index: 1 })
        );
        // Δ = 2^-16 in I16F16: the third derivative scales with 1/Δ³.
        let z = I16F16::ZERO;
        let eps = I16F16::from_bits(1);
        assert_eq!(
            HermiteSegment::new(z, eps, [z], [I16F16::ONE], [z], [z]),
            Err(Error::OutOfRange)
        );
        assert!(HermiteSegment::new(z, I16F16::ONE, [z], [I16F16::ONE], [z], [z]).is_ok());
    }

    fn spline() -> HermiteSpline<[f64; 2], 8> {
        let pts = [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, -1.0]];
        let tan = [[1.0, 0.0], [2.0, 1.0], [0.0, -1.0], [1.0, 1.0]];
        HermiteSpline::new(&pts, &tan, &[0.0, 1.0, 2.5, 3.0]).unwrap()
    }

    #[test]
    fn spline_interpolates_and_is_c1() {
        let h = spline();
        assert_eq!(h.piece_count(), 3);
        assert_eq!(h.domain(), (0.0, 3.0));
        assert_eq!(h.piece_domain(1), (1.0, 2.5));
        assert_eq!(h.piece_domain(7), (2.5, 3.0));
        for i in 0..4 {
            let u = h.nodes()[i];
            assert_eq!(h.eval(u), h.points()[i]);
            assert!(close(h.deriv(u, 1), h.tangents()[i], 1e-12));
        }
        // left limits at inner nodes agree with the node data (C¹)
        for i in 1..3 {
            let left = h.segment(i - 1).unwrap();
            let u = h.nodes()[i];
            assert_eq!(left.eval(u), h.points()[i]);
            assert!(close(left.deriv(u, 1), h.tangents()[i], 1e-12));
        }
        assert!(h.segment(3).is_none());
    }

    #[test]
    fn spline_pieces_match_textbook_formula() {
        let h = spline();
        for i in 0..3 {
            let u = [h.nodes()[i], h.nodes()[i + 1]];
            let q = [h.points()[i], h.points()[i + 1]];
            let m = [h.tangents()[i], h.tangents()[i + 1]];
            for j in 0..=8 {
                let t = u[0] + (u[1] - u[0]) * f64::from(j) / 8.0;
                assert!(close(h.eval(t), textbook_formula(u, q, m, t), 1e-13));
            }
        }
    }

    #[test]
    fn spline_piece_search() {
        let h = spline();
        assert_eq!(h.piece_index(-1.0), 0);
        assert_eq!(h.piece_index(0.0), 0);
        assert_eq!(h.piece_index(0.99), 0);
        assert_eq!(h.piece_index(1.0), 1);
        assert_eq!(h.piece_index(2.5), 2);
        assert_eq!(h.piece_index(3.0), 2);
        assert_eq!(h.piece_index(9.0), 2);
        // at an inner node the piece starting there gives the second derivative
        let right = h.segment(1).unwrap();
        assert_eq!(h.deriv(1.0, 2), right.deriv(1.0, 2));
        assert_eq!(h.eval(-5.0), [0.0, 0.0]);
        assert_eq!(h.eval(5.0), [4.0, -1.0]);
        assert_eq!(h.deriv(5.0, 3), h.segment(2).unwrap().deriv(3.0, 3));
        assert_eq!(h.deriv(0.3, 4), [0.0, 0.0]);
    }

    #[test]
    fn spline_fixed_point_matches_f64() {
        let h = spline();
        let pts = h.points().iter().map(|p| p.map(I32F32::from_num));
        let pts: heapless::Vec<[I32F32; 2], 8> = pts.collect();
        let tan: heapless::Vec<[I32F32; 2], 8> = h
            .tangents()
            .iter()
            .map(|p| p.map(I32F32::from_num))
            .collect();
        let nodes: heapless::Vec<I32F32, 8> =
            h.nodes().iter().map(|&u| I32F32::from_num(u)).collect();
        let hf = HermiteSpline::<_, 8>::new(&pts, &tan, nodes.as_slice()).unwrap();
        let pts16: heapless::Vec<[I16F16; 2], 8> =
            h.points().iter().map(|p| p.map(I16F16::from_num)).collect();
        let tan16: heapless::Vec<[I16F16; 2], 8> = h
            .tangents()
            .iter()
            .map(|p| p.map(I16F16::from_num))
            .collect();
        let nodes16: heapless::Vec<I16F16, 8> =
            h.nodes().iter().map(|&u| I16F16::from_num(u)).collect();
        let h16 = HermiteSpline::<_, 8>::new(&pts16, &tan16, nodes16.as_slice()).unwrap();
        let h32 = HermiteSpline::<[f32; 2], 8>::new(
            &h.points()
                .iter()
                .map(|p| p.map(|x| x as f32))
                .collect::<heapless::Vec<_, 8>>(),
            &h.tangents()
                .iter()
                .map(|p| p.map(|x| x as f32))
                .collect::<heapless::Vec<_, 8>>(),
            &h.nodes()
                .iter()
                .map(|&x| x as f32)
                .collect::<heapless::Vec<_, 8>>()[..],
        )
        .unwrap();
        for j in 0..=60 {
            let u = 3.0 * f64::from(j) / 60.0;
            for k in 0..=3 {
                let want = h.deriv(u, k);
                let a = hf.deriv(I32F32::from_num(u), k).map(|x| x.to_num::<f64>());
                let b = h16.deriv(I16F16::from_num(u), k).map(|x| x.to_num::<f64>());
                let c = h32.deriv(u as f32, k).map(f64::from);
                // tolerances: a few units of the last place, times 1/Δ^k (Δ ≥ 0.5)
                assert!(
                    close(a, want, 1e-7),
                    "I32F32 k={k} u={u}: {a:?} vs {want:?}"
                );
                assert!(
                    close(b, want, 3e-3),
                    "I16F16 k={k} u={u}: {b:?} vs {want:?}"
                );
                assert!(close(c, want, 1e-4), "f32 k={k} u={u}: {c:?} vs {want:?}");
            }
        }
    }

    #[test]
    fn spline_with_parameterization() {
        let pts = [[0.0_f64, 0.0], [3.0, 4.0], [3.0, 5.0]];
        let tan = [[0.0, 0.0]; 3];
        let h = HermiteSpline::<_, 3>::new(&pts, &tan, Parameterization::ChordLength).unwrap();
        assert_eq!(h.nodes(), &[0.0, 5.0, 6.0]);
        assert_eq!(h.eval(5.0), [3.0, 4.0]);
    }

    #[test]
    fn spline_errors() {
        let pts = [[0.0_f64], [1.0], [2.0]];
        let tan = [[0.0_f64], [1.0], [2.0]];
        let uni = Parameterization::Uniform;
        assert_eq!(
            HermiteSpline::<_, 4>::new(&pts[..1], &tan[..1], uni),
            Err(Error::TooFewPoints {
                required: 2,
                found: 1
            })
        );
        assert_eq!(
            HermiteSpline::<_, 2>::new(&pts, &tan, uni),
            Err(Error::CapacityExceeded {
                capacity: 2,
                required: 3
            })
        );
        assert_eq!(
            HermiteSpline::<_, 4>::new(&pts, &tan[..2], uni),
            Err(Error::LengthMismatch {
                expected: 3,
                found: 2
            })
        );
        assert_eq!(
            HermiteSpline::<_, 4>::new(&pts, &tan, &[0.0, 1.0]),
            Err(Error::LengthMismatch {
                expected: 3,
                found: 2
            })
        );
        assert_eq!(
            HermiteSpline::<_, 4>::new(&[[0.0], [f64::NAN]], &tan[..2], uni),
            Err(Error::NonFinite)
        );
        assert_eq!(
            HermiteSpline::<_, 4>::new(&pts, &[[0.0], [f64::NAN], [0.0]], uni),
            Err(Error::NonFinite)
        );
        assert_eq!(
            HermiteSpline::<_, 4>::new(&pts, &tan, &[0.0, 2.0, 1.0]),
            Err(Error::NodesNotIncreasing { index: 2 })
        );
        assert_eq!(
            HermiteSpline::<_, 4>::new(&[[0.0], [0.0]], &tan[..2], Parameterization::ChordLength),
            Err(Error::ZeroLengthInterval { index: 0 })
        );
        let big = I16F16::from_num(10000);
        let z = I16F16::ZERO;
        assert_eq!(
            HermiteSpline::<_, 4>::new(&[[z], [big]], &[[z], [z]], &[z, I16F16::ONE]),
            Err(Error::OutOfRange)
        );
    }
}
