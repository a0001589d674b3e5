//! A piecewise Bézier curve: Bézier segments joined end to start (Farin, *Curves and
//! Surfaces for CAGD*, 5th ed., ch. 7 "Spline Curves in Bézier Form", §7.1 "Global and Local
//! Parameters", §7.2 "Smoothness Conditions").

use heapless::Vec;

use super::curve::Bezier;
use crate::curve::{ParamCurve, ParamCurveDeriv, PieceDeriv};
use crate::error::Error;
use crate::point::Point;
use crate::scalar::Scalar;

/// A composite Bézier curve (a spline curve in Bézier form): `n ≤ M` [`Bezier`] segments of
/// degree `g = N − 1`, segment `i` ending where segment `i + 1` starts (C⁰ at least).
///
/// The parameter domain is `[0, n]`; segment `i` covers `[i, i + 1]` with its local parameter
/// `t = u − i`. Because every segment has a parameter interval of length 1, derivatives with
/// respect to `u` are the segments' own derivatives with respect to `t`, and the join
/// conditions (Farin §7.2) read directly: the chain is C¹ at the join `u = i + 1` exactly when
/// `b_{g−1}, b_g = c_0, c_1` are collinear and equally spaced (what
/// [`Bezier::join_c1`] produces), G¹ when only the directions agree ([`Bezier::join_g1`]).
///
/// Evaluation finds the segment by binary search over the join parameters `0, 1, …, n − 1`
/// (the segment that *starts* at an inner join, the last one at `u = n`) and runs
/// de Casteljau's algorithm on it. `u` outside `[0, n]` is clamped; a NaN parameter maps to
/// `u = 0`.
///
/// # Fixed-point range
/// Each segment is validated by [`Bezier::new`] (its points and all its hodographs fit the
/// scalar type), and the largest parameter `n` must fit as well ([`Error::OutOfRange`]
/// otherwise; `I16F16` allows up to 16 383 segments). The local parameter `u − i` lies in
/// `[0, 1]`, so evaluation cannot overflow.
///
/// ```
/// use strak_curves::{BezierChain, ParamCurve, ParamCurveDeriv};
///
/// // Two cubic segments joined C¹ at (3, 0): b_2, b_3 = c_0, c_1 equally spaced on a line.
/// let chain = BezierChain::<_, 4, 8>::new(&[
///     [0.0, 0.0], [1.0, 1.0], [2.0, 1.0], [3.0, 0.0],
///     [4.0, -1.0], [5.0, -1.0], [6.0, 0.0],
/// ])?;
/// assert_eq!(chain.segment_count(), 2);
/// assert_eq!(chain.domain(), (0.0, 2.0));
/// assert_eq!(chain.eval(1.0), [3.0, 0.0]);
/// assert_eq!(chain.eval(1.5), [4.5, -0.75]);
/// assert_eq!(chain.deriv(1.0, 1), [3.0, -3.0]);
/// # Ok::<(), strak_curves::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct BezierChain<P: Point, const N: usize, const M: usize> {
    segments: Vec<Bezier<P, N>, M>,
    /// The join parameters `0, 1, …, n − 1`: where each segment starts.
    starts: Vec<P::Scalar, M>,
    /// The end of the domain, `n`.
    end: P::Scalar,
}

/// Rejects degree-0 segments: their composite representation has one point for any number
/// of segments.
fn check_degree<const N: usize>() -> Result<(), Error> {
    if N < 2 {
        Err(Error::InvalidArgument)
    } else {
        Ok(())
    }
}

/// The segments' start parameters `0, …, n − 1` and the end `n` in `S`.
fn parameters<S: Scalar, const M: usize>(n: usize) -> Result<(Vec<S, M>, S), Error> {
    let end = n as f64;
    if !S::fits(end) {
        return Err(Error::OutOfRange);
    }
    let mut starts = Vec::new();
    for i in 0..n {
        let s = S::from_f64(i as f64).ok_or(Error::OutOfRange)?;
        starts.push(s).map_err(|_| Error::CapacityExceeded {
            capacity: M,
            required: n,
        })?;
    }
    Ok((starts, S::from_f64(end).ok_or(Error::OutOfRange)?))
}

impl<P: Point, const N: usize, const M: usize> BezierChain<P, N, M> {
    /// The chain from its composite representation: `n·(N − 1) + 1` points, where segment `i`
    /// has the points `points[i·(N−1) ..= (i+1)·(N−1)]`, so consecutive segments share their
    /// join point (the piecewise Bézier polygon, Farin §7.1).
    ///
    /// # Errors
    /// * [`Error::InvalidArgument`] for degree-0 segments (`N < 2`);
    /// * [`Error::TooFewPoints`] below `N` points (one segment);
    /// * [`Error::LengthMismatch`] when the number of points is not of the form
    ///   `n·(N − 1) + 1`; `expected` is the nearest count of that form (the smaller one on a
    ///   tie);
    /// * [`Error::CapacityExceeded`] for more than `M` segments (`capacity: M`,
    ///   `required: n`);
    /// * [`Error::NonFinite`] for a NaN or infinite coordinate;
    /// * [`Error::OutOfRange`] when a segment (its points or derivatives, see [`Bezier::new`])
    ///   or the parameter `n` does not fit the scalar type.
    ///
    /// ```
    /// use strak_curves::{BezierChain, Error};
    ///
    /// // quadratic segments need 2n + 1 points: 4 is one short of 5 (and one above 3)
    /// let e = BezierChain::<_, 3, 4>::new(&[[0.0_f32], [1.0], [2.0], [3.0]]);
    /// assert_eq!(e, Err(Error::LengthMismatch { expected: 3, found: 4 }));
    /// let c = BezierChain::<_, 3, 4>::new(&[[0.0_f32], [1.0], [2.0], [3.0], [4.0]])?;
    /// assert_eq!((c.segment_count(), c.degree()), (2, 2));
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn new(points: &[P]) -> Result<Self, Error> {
        check_degree::<N>()?;
        let g = N - 1;
        if points.len() < N {
            return Err(Error::TooFewPoints {
                required: N,
                found: points.len(),
            });
        }
        let inner = points.len() - 1;
        let n = inner / g;
        if !inner.is_multiple_of(g) {
            let (below, above) = (n * g + 1, (n + 1) * g + 1);
            let expected = if points.len() - below <= above - points.len() {
                below
            } else {
                above
            };
            return Err(Error::LengthMismatch {
                expected,
                found: points.len(),
            });
        }
        if n > M {
            return Err(Error::CapacityExceeded {
                capacity: M,
                required: n,
            });
        }
        if !points.iter().all(|p| p.is_finite()) {
            return Err(Error::NonFinite);
        }
        let mut segments = Vec::new();
        for i in 0..n {
            let seg: [P; N] =
                core::array::from_fn(|j| points.get(i * g + j).copied().unwrap_or_else(P::zero));
            let seg = Bezier::new(seg)?;
            segments.push(seg).map_err(|_| Error::CapacityExceeded {
                capacity: M,
                required: n,
            })?;
        }
        let (starts, end) = parameters::<P::Scalar, M>(n)?;
        Ok(Self {
            segments,
            starts,
            end,
        })
    }

    /// The chain of the given segments, each validated already by [`Bezier::new`] (for
    /// example the output of [`Bezier::join_c1`] or [`Bezier::join_g1`]).
    ///
    /// # Errors
    /// * [`Error::InvalidArgument`] for degree-0 segments (`N < 2`), or when a segment does
    ///   not start exactly (bit for bit) at the last point of the previous one;
    /// * [`Error::TooFewPoints`] for no segment (`required: 1`);
    /// * [`Error::CapacityExceeded`] for more than `M` segments;
    /// * [`Error::OutOfRange`] when the parameter `n` does not fit the scalar type.
    ///
    /// ```
    /// use strak_curves::{Bezier, BezierChain, Error, ParamCurveDeriv};
    ///
    /// let a = Bezier::new([[0.0, 0.0], [1.0, 1.0], [2.0, 1.0], [3.0, 0.0]])?;
    /// let b = Bezier::new([[0.0, 0.0], [0.0, 0.0], [5.0, 1.0], [6.0, 0.0]])?;
    /// // b does not start at (3, 0)
    /// assert_eq!(
    ///     BezierChain::<_, 4, 4>::from_segments(&[a, b]),
    ///     Err(Error::InvalidArgument)
    /// );
    /// let chain = BezierChain::<_, 4, 4>::from_segments(&[a, a.join_c1(&b)?])?;
    /// assert_eq!(chain.deriv(1.0, 1), a.deriv(1.0, 1));
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn from_segments(segments: &[Bezier<P, N>]) -> Result<Self, Error> {
        check_degree::<N>()?;
        if segments.is_empty() {
            return Err(Error::TooFewPoints {
                required: 1,
                found: 0,
            });
        }
        let n = segments.len();
        let too_many = |_| Error::CapacityExceeded {
            capacity: M,
            required: n,
        };
        let stored = Vec::from_slice(segments).map_err(too_many)?;
        for pair in segments.windows(2) {
            if let [a, b] = pair {
                let end = a.control_points().last();
                let start = b.control_points().first();
                if end != start {
                    return Err(Error::InvalidArgument);
                }
            }
        }
        let (starts, end) = parameters::<P::Scalar, M>(n)?;
        Ok(Self {
            segments: stored,
            starts,
            end,
        })
    }

    /// The segments, in order; segment `i` covers `u ∈ [i, i + 1]`.
    ///
    /// ```
    /// use strak_curves::BezierChain;
    /// let c = BezierChain::<_, 2, 4>::new(&[[0.0], [1.0], [3.0]])?;
    /// assert_eq!(c.segments()[1].control_points(), &[[1.0], [3.0]]);
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn segments(&self) -> &[Bezier<P, N>] {
        &self.segments
    }

    /// The number of segments `n` (at least 1).
    pub fn segment_count(&self) -> usize {
        self.segments.len()
    }

    /// The degree `g = N − 1` of every segment.
    pub fn degree(&self) -> usize {
        N.saturating_sub(1)
    }

    /// The index of the segment containing `u` (binary search): the segment that starts at
    /// `u` when `u` is an inner join, the last segment at and beyond the end, the first
    /// before the start or for NaN.
    pub fn segment_index(&self, u: P::Scalar) -> usize {
        let count = self.starts.partition_point(|&s| s <= u);
        count.saturating_sub(1).min(self.last())
    }

    fn last(&self) -> usize {
        self.segments.len().saturating_sub(1)
    }

    /// Segment `i` (clamped to the last), `u` clamped to its interval, differentiated.
    fn piece(&self, i: usize, u: P::Scalar, k: usize) -> P {
        let i = i.min(self.last());
        let (a, b) = self.piece_domain(i);
        match self.segments.get(i) {
            Some(seg) => seg.deriv(u.clamp_to(a, b) - a, k),
            None => P::zero(),
        }
    }
}

impl<P: Point, const N: usize, const M: usize> ParamCurve for BezierChain<P, N, M> {
    type Point = P;

    /// `(0, n)`.
    fn domain(&self) -> (P::Scalar, P::Scalar) {
        (P::Scalar::ZERO, self.end)
    }

    /// De Casteljau on the segment containing `u` (clamped to `[0, n]`).
    fn eval(&self, u: P::Scalar) -> P {
        self.deriv(u, 0)
    }

    /// `n`.
    fn piece_count(&self) -> usize {
        self.segments.len().max(1)
    }

    /// `(i, i + 1)`; the last segment's for `i ≥ n`.
    fn piece_domain(&self, i: usize) -> (P::Scalar, P::Scalar) {
        let i = i.min(self.last());
        let a = self.starts.get(i).copied().unwrap_or(P::Scalar::ZERO);
        let b = self.starts.get(i + 1).copied().unwrap_or(self.end);
        (a, b)
    }
}

impl<P: Point, const N: usize, const M: usize> ParamCurveDeriv for BezierChain<P, N, M> {
    /// The `k`-th derivative of the segment containing `u` (clamped to `[0, n]`); at an inner
    /// join the segment starting there, at `u = n` the last one. Since each segment spans one
    /// unit of `u`, this is the segment's own derivative at `t = u − i`.
    fn deriv(&self, u: P::Scalar, k: usize) -> P {
        let u = u.clamp_to(P::Scalar::ZERO, self.end);
        self.piece(self.segment_index(u), u, k)
    }
}

impl<P: Point, const N: usize, const M: usize> PieceDeriv for BezierChain<P, N, M> {
    /// Segment `piece` (the last for `piece ≥ n`) at `u` clamped to `[piece, piece + 1]`: at
    /// the segment's end this is the left-hand limit at the join.
    fn piece_deriv(&self, piece: usize, u: P::Scalar, k: usize) -> P {
        self.piece(piece, u, k)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Continuity, I16F16, I32F32, QUARTER_CIRCLE_KAPPA, classify_breaks};
    use glam::{DVec2, Vec3};

    /// Two cubics joined C¹ at (3, 0).
    fn c1_pair() -> BezierChain<[f64; 2], 4, 4> {
        BezierChain::new(&[
            [0.0, 0.0],
            [1.0, 1.0],
            [2.0, 1.0],
            [3.0, 0.0],
            [4.0, -1.0],
            [5.0, -1.0],
            [6.0, 0.0],
        ])
        .unwrap()
    }

    #[test]
    fn segments_domain_and_joins() {
        let c = c1_pair();
        assert_eq!(c.segment_count(), 2);
        assert_eq!(c.degree(), 3);
        assert_eq!(c.piece_count(), 2);
        assert_eq!(c.domain(), (0.0, 2.0));
        assert_eq!(c.piece_domain(0), (0.0, 1.0));
        assert_eq!(c.piece_domain(1), (1.0, 2.0));
        assert_eq!(c.piece_domain(7), (1.0, 2.0));
        assert_eq!(c.segments()[1].control_points()[0], [3.0, 0.0]);
        // end points, the join, and the cubic midpoint (b0 + 3b1 + 3b2 + b3)/8
        assert_eq!(c.eval(0.0), [0.0, 0.0]);
        assert_eq!(c.eval(1.0), [3.0, 0.0]);
        assert_eq!(c.eval(2.0), [6.0, 0.0]);
        assert_eq!(c.eval(0.5), [1.5, 0.75]);
        assert_eq!(c.eval(1.5), [4.5, -0.75]);
        // clamped outside, NaN to the start
        assert_eq!(c.eval(-1.0), [0.0, 0.0]);
        assert_eq!(c.eval(9.0), [6.0, 0.0]);
        assert_eq!(c.eval(f64::NAN), [0.0, 0.0]);
        assert_eq!(c.deriv(f64::NAN, 1), [3.0, 3.0]);
        assert_eq!(c.segment_index(f64::NAN), 0);
        assert_eq!(c.segment_index(1.0), 1);
        assert_eq!(c.segment_index(2.0), 1);
        assert_eq!(c.segment_index(0.999), 0);
    }

    #[test]
    fn derivatives_are_the_segments_own() {
        let c = c1_pair();
        // c'(u) at the start: 3 (b1 − b0); at the join both sides 3 (b3 − b2) = (3, −3)
        assert_eq!(c.deriv(0.0, 1), [3.0, 3.0]);
        assert_eq!(c.deriv(1.0, 1), [3.0, -3.0]);
        assert_eq!(c.piece_deriv(0, 1.0, 1), [3.0, -3.0]);
        // second derivative 6 (b2 − 2 b1 + b0)… at u = 1 left: 6 (b3 − 2b2 + b1) = (0, −6),
        // right: 6 (c2 − 2 c1 + c0) = (0, 6): a C¹ join, not C²
        assert_eq!(c.piece_deriv(0, 1.0, 2), [0.0, -6.0]);
        assert_eq!(c.deriv(1.0, 2), [0.0, 6.0]);
        // end of the domain: the last segment
        assert_eq!(c.deriv(2.0, 1), [3.0, 3.0]);
        assert_eq!(c.deriv(5.0, 1), [3.0, 3.0]);
        // above the degree: zero
        assert_eq!(c.deriv(0.3, 4), [0.0, 0.0]);
        // piece_deriv clamps to the piece
        assert_eq!(c.piece_deriv(0, 1.7, 0), [3.0, 0.0]);
        assert_eq!(c.piece_deriv(1, 0.2, 0), [3.0, 0.0]);
        assert_eq!(c.piece_deriv(9, 2.0, 0), [6.0, 0.0]);
        for s in 0..=16 {
            let t = f64::from(s) / 16.0;
            for k in 0..=4 {
                assert_eq!(c.deriv(1.0 + t, k), c.segments()[1].deriv(t, k));
                assert_eq!(c.piece_deriv(0, t, k), c.segments()[0].deriv(t, k));
            }
        }
    }

    #[test]
    fn continuity_of_joins() {
        let c1 = classify_breaks(&c1_pair(), 1e-12).unwrap();
        assert!(c1.is_c(1) && !c1.is_c(2), "{c1:?}");
        // a corner at (3, 0)
        let corner = BezierChain::<_, 4, 4>::new(&[
            [0.0, 0.0],
            [1.0, 1.0],
            [2.0, 1.0],
            [3.0, 0.0],
            [3.0, 1.0],
            [5.0, 1.0],
            [6.0, 0.0],
        ])
        .unwrap();
        let c0 = classify_breaks(&corner, 1e-12).unwrap();
        assert_eq!(
            c0,
            Continuity {
                parametric: Some(0),
                geometric: Some(0)
            }
        );
    }

    #[test]
    fn full_circle_from_four_quarter_circles() {
        // The cubic quarter circle, κ = 0.551897, repeated around the unit circle: each join
        // has equally spaced collinear tangent points, so the chain is C¹.
        let k = QUARTER_CIRCLE_KAPPA;
        let p = |x: f64, y: f64| DVec2::new(x, y);
        let c = BezierChain::<_, 4, 4>::new(&[
            p(1.0, 0.0),
            p(1.0, k),
            p(k, 1.0),
            p(0.0, 1.0),
            p(-k, 1.0),
            p(-1.0, k),
            p(-1.0, 0.0),
            p(-1.0, -k),
            p(-k, -1.0),
            p(0.0, -1.0),
            p(k, -1.0),
            p(1.0, -k),
            p(1.0, 0.0),
        ])
        .unwrap();
        assert_eq!(c.domain(), (0.0, 4.0));
        for i in 0..4 {
            let u = f64::from(i);
            // the tangent at each join has length 3κ
            assert!((c.deriv(u, 1).length() - 3.0 * k).abs() < 1e-15);
            assert!((c.eval(u + 0.5).length() - 1.0).abs() < 3e-4);
        }
        assert!(classify_breaks(&c, 1e-12).unwrap().is_c(1));
        assert_eq!(c.eval(4.0), p(1.0, 0.0));
    }

    #[test]
    fn from_segments_with_joins() {
        let a = Bezier::new([
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 2.0, 0.0),
            Vec3::new(2.0, 2.0, 1.0),
        ])
        .unwrap();
        let b = Bezier::new([Vec3::ZERO, Vec3::ZERO, Vec3::new(5.0, 0.0, 0.0)]).unwrap();
        let b = a.join_c1(&b).unwrap();
        let c = BezierChain::<_, 3, 2>::from_segments(&[a, b]).unwrap();
        assert_eq!(c.deriv(1.0, 1), c.piece_deriv(0, 1.0, 1));
        let g = a.join_g1(&b, Some(0.5)).unwrap();
        let c = BezierChain::<_, 3, 2>::from_segments(&[a, g]).unwrap();
        let cont = classify_breaks(&c, 1e-5).unwrap();
        assert!(cont.is_g(1) && !cont.is_c(1), "{cont:?}");
        // same as the composite representation
        let pts = [
            a.control_points()[0],
            a.control_points()[1],
            a.control_points()[2],
            g.control_points()[1],
            g.control_points()[2],
        ];
        assert_eq!(BezierChain::<_, 3, 2>::new(&pts).unwrap(), c);
    }

    #[test]
    fn fixed_point_agrees_with_f64() {
        let q = [
            [0.0, 0.0],
            [1.5, 3.0],
            [4.25, -2.0],
            [6.0, 1.0],
            [7.5, 0.5],
            [9.0, 0.0],
            [9.5, 2.0],
        ];
        let cf = BezierChain::<_, 4, 2>::new(&q).unwrap();
        let cx = BezierChain::<_, 4, 2>::new(&q.map(|p| p.map(I16F16::from_num))).unwrap();
        let cy = BezierChain::<_, 4, 2>::new(&q.map(|p| p.map(I32F32::from_num))).unwrap();
        assert_eq!(cx.domain(), (I16F16::ZERO, I16F16::from_num(2)));
        for step in 0..=64 {
            let u = f64::from(step) / 32.0;
            for k in 0..=3 {
                let r = cf.deriv(u, k);
                let x = cx.deriv(I16F16::from_num(u), k);
                let y = cy.deriv(I32F32::from_num(u), k);
                for d in 0..2 {
                    // as Bezier's own bound: (2g + 1) 2^k g!/(g−k)! units
                    let scale = 7.0 * f64::from(1 << k) * [1.0, 3.0, 6.0, 6.0][k];
                    assert!((x[d].to_f64() - r[d]).abs() <= scale * <I16F16 as Scalar>::EPSILON);
                    assert!((y[d].to_f64() - r[d]).abs() <= scale * <I32F32 as Scalar>::EPSILON);
                }
            }
        }
    }

    #[test]
    fn error_invalid_argument_degree_zero() {
        assert_eq!(
            BezierChain::<_, 1, 4>::new(&[[0.0], [1.0]]),
            Err(Error::InvalidArgument)
        );
        let p = Bezier::new([[0.0]]).unwrap();
        assert_eq!(
            BezierChain::<_, 1, 4>::from_segments(&[p]),
            Err(Error::InvalidArgument)
        );
    }

    #[test]
    fn error_invalid_argument_join_mismatch() {
        let a = Bezier::new([[0.0_f32, 0.0], [1.0, 0.0]]).unwrap();
        let b = Bezier::new([[1.0, 0.0], [1.0, 1.0]]).unwrap();
        let c = Bezier::new([[1.0, 1.0 + f32::EPSILON], [0.0, 1.0]]).unwrap();
        assert!(BezierChain::<_, 2, 3>::from_segments(&[a, b]).is_ok());
        assert_eq!(
            BezierChain::<_, 2, 3>::from_segments(&[a, b, c]),
            Err(Error::InvalidArgument)
        );
    }

    #[test]
    fn error_too_few_points() {
        assert_eq!(
            BezierChain::<_, 4, 4>::new(&[[0.0], [1.0], [2.0]]),
            Err(Error::TooFewPoints {
                required: 4,
                found: 3
            })
        );
        assert_eq!(
            BezierChain::<[f64; 1], 4, 4>::from_segments(&[]),
            Err(Error::TooFewPoints {
                required: 1,
                found: 0
            })
        );
    }

    #[test]
    fn error_length_mismatch() {
        let p = [[0.0]; 9];
        // cubic: valid counts 4, 7, 10
        let e = |n: usize, expected| {
            assert_eq!(
                BezierChain::<_, 4, 8>::new(&p[..n]),
                Err(Error::LengthMismatch { expected, found: n })
            );
        };
        e(5, 4);
        e(6, 7);
        e(8, 7);
        e(9, 10);
        // quadratic tie: 4 is between 3 and 5, the smaller wins
        assert_eq!(
            BezierChain::<_, 3, 8>::new(&p[..4]),
            Err(Error::LengthMismatch {
                expected: 3,
                found: 4
            })
        );
    }

    #[test]
    fn error_capacity_exceeded() {
        let p = [[0.0]; 7];
        assert_eq!(
            BezierChain::<_, 2, 5>::new(&p),
            Err(Error::CapacityExceeded {
                capacity: 5,
                required: 6
            })
        );
        let s = Bezier::new([[0.0], [0.0]]).unwrap();
        assert_eq!(
            BezierChain::<_, 2, 2>::from_segments(&[s; 3]),
            Err(Error::CapacityExceeded {
                capacity: 2,
                required: 3
            })
        );
        assert!(BezierChain::<_, 2, 6>::new(&p).is_ok());
    }

    #[test]
    fn error_non_finite() {
        assert_eq!(
            BezierChain::<_, 2, 4>::new(&[[0.0], [1.0], [f64::NAN]]),
            Err(Error::NonFinite)
        );
        assert_eq!(
            BezierChain::<_, 2, 4>::new(&[[f32::INFINITY], [1.0], [2.0]]),
            Err(Error::NonFinite)
        );
    }

    #[test]
    fn error_out_of_range() {
        let p = |x: f64| [I16F16::from_num(x)];
        // the second segment's derivative 3 · 6000 does not fit I16F16
        assert_eq!(
            BezierChain::<_, 4, 4>::new(&[
                p(0.0),
                p(1.0),
                p(2.0),
                p(3.0),
                p(6003.0),
                p(4.0),
                p(5.0)
            ]),
            Err(Error::OutOfRange)
        );
        // the parameter n = 16 400 does not fit I16F16's limit 16 383.5
        let line = [p(0.0); 16_401];
        assert_eq!(
            BezierChain::<_, 2, 16_400>::new(&line),
            Err(Error::OutOfRange)
        );
        let seg = Bezier::new([p(0.0), p(0.0)]).unwrap();
        assert_eq!(
            BezierChain::<_, 2, 16_400>::from_segments(&[seg; 16_400]),
            Err(Error::OutOfRange)
        );
        assert!(BezierChain::<_, 2, 16_383>::new(&line[..16_384]).is_ok());
    }
}
