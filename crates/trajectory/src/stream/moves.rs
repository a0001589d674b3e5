//! The moves of a stream and the curves they trace: a line, a circular arc or helix (G2/G3),
//! a cubic Bézier (G5), or any curve of strak-curves, each from the end of the move before.

use strak_curves::{
    Bezier, CircularArc, ParamCurve, ParamCurveDeriv, PieceDeriv, Plane, Point, Turn, arc_length,
    arc_length_between, param_at_length, second_derivative_bound,
};

use crate::error::Error;

/// The relative accuracy of the arc lengths of curved moves (spirals and Béziers; the
/// lengths of lines, circles and helices are closed forms).
pub(super) const LENGTH_ACCURACY: f64 = 1e-12;

/// A curve that a move can trace whole: any curve of strak-curves (or of your own) with
/// points of `D` axes in `f64`, passed by reference (`&BSpline<[f64; 3], 16, 20>`), or as
/// `&dyn PieceDeriv<Point = [f64; D]>` to mix curve types in one stream.
///
/// ```
/// use strak_curves::{Bezier, PieceDeriv};
/// use strak_trajectory::StreamCurve;
/// fn traceable<C: StreamCurve<2>>(_: C) {}
/// let b = Bezier::new([[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]])?;
/// traceable(&b);
/// traceable(&b as &dyn PieceDeriv<Point = [f64; 2]>);
/// # Ok::<(), strak_curves::Error>(())
/// ```
pub trait StreamCurve<const D: usize>: PieceDeriv<Point = [f64; D]> + Copy {}

impl<const D: usize, T: PieceDeriv<Point = [f64; D]> + Copy> StreamCurve<D> for T {}

/// The curve type of moves and streams that trace no [`Shape::Curve`]: it has no values, so
/// such moves cost nothing for it.
///
/// ```
/// use strak_trajectory::{Move, NoCurve};
/// let m: Move<2, NoCurve<2>> = Move::line([1.0, 0.0]);
/// assert_eq!(core::mem::size_of::<Move<2>>(), core::mem::size_of_val(&m));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NoCurve<const D: usize> {}

impl<const D: usize> ParamCurve for NoCurve<D> {
    type Point = [f64; D];

    fn domain(&self) -> (f64, f64) {
        match *self {}
    }

    fn eval(&self, _: f64) -> [f64; D] {
        match *self {}
    }
}

impl<const D: usize> ParamCurveDeriv for NoCurve<D> {
    fn deriv(&self, _: f64, _: usize) -> [f64; D] {
        match *self {}
    }
}

impl<const D: usize> PieceDeriv for NoCurve<D> {
    fn piece_deriv(&self, _: usize, _: f64, _: usize) -> [f64; D] {
        match *self {}
    }
}

#[cfg(feature = "defmt")]
impl<const D: usize> defmt::Format for NoCurve<D> {
    fn format(&self, _: defmt::Formatter) {
        match *self {}
    }
}

/// The geometry of a move: what it traces from the end of the move before to its
/// [`Move::to`]; `C` is the type of the curves of [`Shape::Curve`].
///
/// ```
/// use strak_trajectory::Shape;
/// use strak_curves::{Plane, Turn};
/// let quarter = Shape::<3>::ArcCenter { center: [0.0, 0.0], plane: Plane::XY, turn: Turn::CounterClockwise };
/// assert_ne!(quarter, Shape::Line);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Shape<const D: usize, C = NoCurve<D>> {
    /// A straight line (G0, G1).
    Line,
    /// A circular arc about `center` (its two coordinates in `plane`), as G2/G3 with
    /// `I J K` give it: a full turn when the start and the end coincide in the plane; the
    /// coordinates outside the plane move linearly with the angle (a helix).
    ArcCenter {
        /// The centre's coordinates in the plane.
        center: [f64; 2],
        /// The plane of the turn (G17, G18, G19).
        plane: Plane,
        /// The sense of the turn (G2 clockwise, G3 counter-clockwise).
        turn: Turn,
    },
    /// A circular arc of radius `|radius|`, as G2/G3 with `R` give it: the shorter arc for a
    /// positive radius, the longer for a negative one.
    ArcRadius {
        /// The radius, negative for the longer arc.
        radius: f64,
        /// The plane of the turn (G17, G18, G19).
        plane: Plane,
        /// The sense of the turn (G2 clockwise, G3 counter-clockwise).
        turn: Turn,
    },
    /// A cubic Bézier curve with the inner control points `c1`, `c2` (G5 with `I J P Q`).
    Bezier {
        /// The control point after the start.
        c1: [f64; D],
        /// The control point before the end.
        c2: [f64; D],
    },
    /// A curve traced whole over its parameter domain ([`Move::curve`]): its start must be
    /// the end of the move before, and its end the move's [`Move::to`], each within the arc
    /// tolerance (a gap within it is spread linearly along the parameter, so that the move
    /// starts and ends exactly there).
    Curve(C),
}

/// One move of a stream: a shape to a point of `D` axes, at a feed; `C` is the type of the
/// curves it may trace ([`Move::curve`]).
///
/// ```
/// use strak_trajectory::{Move, Shape};
/// let m = Move::<3>::line([10.0, 0.0, 0.0]).with_feed(150.0);
/// assert_eq!((m.to, m.shape, m.feed), ([10.0, 0.0, 0.0], Shape::Line, Some(150.0)));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Move<const D: usize, C = NoCurve<D>> {
    /// Where the move ends.
    pub to: [f64; D],
    /// What it traces to there.
    pub shape: Shape<D, C>,
    /// The largest path velocity of the move (units/s); `None` for a rapid move, which runs
    /// at the machine's limits.
    pub feed: Option<f64>,
}

impl<const D: usize, C: Copy> Move<D, C> {
    /// A rapid straight move to `to`.
    ///
    /// ```
    /// use strak_trajectory::Move;
    /// assert_eq!(Move::<2>::line([1.0, 2.0]).feed, None);
    /// ```
    pub const fn line(to: [f64; D]) -> Self {
        Move {
            to,
            shape: Shape::Line,
            feed: None,
        }
    }

    /// A move of the given shape to `to`.
    ///
    /// ```
    /// use strak_trajectory::{Move, Shape};
    /// use strak_curves::{Plane, Turn};
    /// let half = Move::<2>::new([2.0, 0.0], Shape::ArcRadius { radius: 1.0, plane: Plane::XY, turn: Turn::Clockwise });
    /// assert_eq!(half.to, [2.0, 0.0]);
    /// ```
    pub const fn new(to: [f64; D], shape: Shape<D, C>) -> Self {
        Move {
            to,
            shape,
            feed: None,
        }
    }

    /// The same move at the feed `feed` (units/s).
    ///
    /// ```
    /// use strak_trajectory::Move;
    /// assert_eq!(Move::<1>::line([1.0]).with_feed(5.0).feed, Some(5.0));
    /// ```
    #[must_use]
    pub const fn with_feed(self, feed: f64) -> Self {
        Move {
            feed: Some(feed),
            ..self
        }
    }
}

impl<const D: usize, C: StreamCurve<D>> Move<D, C> {
    /// A rapid move along the whole of `curve`, to its end: a curve of strak-curves as one
    /// move. Its joins of pieces are passed as the whole-path planner passes them (where
    /// the tangent or the curvature steps, at the speed the limits allow over one tick; a
    /// turn beyond the corner angle of the plan options stops there).
    ///
    /// ```
    /// use strak_curves::BSpline;
    /// use strak_trajectory::{Move, Shape};
    /// let points = [[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [20.0, 10.0]];
    /// let s = BSpline::<[f64; 2], 4, 8>::new(3, &points, &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0])?;
    /// let m = Move::curve(&s);
    /// assert_eq!((m.to, m.shape), ([20.0, 10.0], Shape::Curve(&s)));
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn curve(curve: C) -> Self {
        Move {
            to: curve.eval(curve.domain().1),
            shape: Shape::Curve(curve),
            feed: None,
        }
    }
}

/// The curve a [`Move`] traces from a start point, over the parameter domain `[0, 1]`.
///
/// Lines, circles and helices have a constant speed in the parameter, so their lengths and
/// the parameters at given lengths are closed forms; spirals (an arc whose end lies off the
/// start's circle within the tolerance), Béziers and curves use adaptive Gauss–Legendre arc
/// lengths ([`strak_curves::arc_length`]). A curve's domain is mapped onto `[0, 1]`
/// linearly, and its pieces with it.
///
/// ```
/// use strak_trajectory::{Move, MoveCurve};
/// use strak_curves::ParamCurve;
/// let c = MoveCurve::new([0.0, 0.0], &Move::<2>::line([3.0, 4.0]), 1e-6)?;
/// assert_eq!((c.length(), c.eval(0.5)), (5.0, [1.5, 2.0]));
/// # Ok::<(), strak_trajectory::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MoveCurve<const D: usize, C = NoCurve<D>> {
    shape: Traced<D, C>,
    length: f64,
    /// `|c'|` where it is constant (lines, circles, helices).
    speed: Option<f64>,
}

/// The curve of each shape.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Traced<const D: usize, C> {
    Line {
        from: [f64; D],
        to: [f64; D],
    },
    Arc(CircularArc<[f64; D]>),
    Bezier(Bezier<[f64; D], 4>),
    /// `curve` over its domain `[lo, lo + span]`, moved by `gaps[0]` at its start and
    /// `gaps[1]` at its end (linearly in between) onto the move's `ends`.
    Curve {
        curve: C,
        lo: f64,
        span: f64,
        ends: [[f64; D]; 2],
        gaps: [[f64; D]; 2],
    },
}

impl<const D: usize, C: StreamCurve<D>> MoveCurve<D, C> {
    /// The curve of `mv` from `from`. An arc's end may lie off the circle of its start by
    /// at most `arc_tolerance` (as [`CircularArc`] takes it).
    ///
    /// A curve's start may lie off `from`, and its end off `mv.to`, by at most
    /// `arc_tolerance` too.
    ///
    /// # Errors
    /// [`Error::DegenerateMove`] for a move of zero length, a Bézier or a curve whose
    /// tangent vanishes at an end (a control point on its end point), or a curve whose ends
    /// lie off `from` or `mv.to`; [`Error::Curve`] for an arc the [`CircularArc`]
    /// constructors reject (a degenerate arc, an end off the circle, a bad plane) and for
    /// non-finite values; [`Error::InvalidLimit`] for a feed that is not finite and
    /// positive.
    ///
    /// ```
    /// use strak_trajectory::{Error, Move, MoveCurve};
    /// assert_eq!(MoveCurve::new([1.0, 1.0], &Move::<2>::line([1.0, 1.0]), 0.0), Err(Error::DegenerateMove));
    /// ```
    pub fn new(from: [f64; D], mv: &Move<D, C>, arc_tolerance: f64) -> Result<Self, Error> {
        if mv
            .feed
            .is_some_and(|feed| !(feed.is_finite() && feed > 0.0))
        {
            return Err(Error::InvalidLimit);
        }
        let to = mv.to;
        if !(from.is_finite() && to.is_finite()) {
            return Err(Error::Curve(strak_curves::Error::NonFinite));
        }
        let shape = match mv.shape {
            Shape::Line => Traced::Line { from, to },
            Shape::ArcCenter {
                center,
                plane,
                turn,
            } => Traced::Arc(CircularArc::with_center(
                from,
                to,
                center,
                plane,
                turn,
                arc_tolerance,
            )?),
            Shape::ArcRadius {
                radius,
                plane,
                turn,
            } => Traced::Arc(CircularArc::with_radius(
                from,
                to,
                radius,
                plane,
                turn,
                arc_tolerance,
            )?),
            Shape::Bezier { c1, c2 } => {
                if c1 == from || c2 == to {
                    return Err(Error::DegenerateMove);
                }
                Traced::Bezier(Bezier::new([from, c1, c2, to])?)
            }
            Shape::Curve(curve) => Self::traced(curve, [from, to], arc_tolerance)?,
        };
        let mut curve = MoveCurve {
            shape,
            length: 0.0,
            speed: None,
        };
        curve.speed = curve.constant_speed();
        curve.length = match curve.speed {
            Some(speed) => speed,
            None => arc_length(&curve, LENGTH_ACCURACY * curve.chord_bound())?,
        };
        if !(curve.length > 0.0 && curve.length.is_finite()) {
            return Err(Error::DegenerateMove);
        }
        Ok(curve)
    }

    /// The trace of `curve` from `ends[0]` to `ends[1]`, where its ends lie within
    /// `arc_tolerance` of those points and its tangent is finite and non-zero at both.
    fn traced(curve: C, ends: [[f64; D]; 2], arc_tolerance: f64) -> Result<Traced<D, C>, Error> {
        let (lo, hi) = curve.domain();
        if !(lo.is_finite() && hi.is_finite()) {
            return Err(Error::Curve(strak_curves::Error::NonFinite));
        }
        let gaps = [ends[0].minus(curve.eval(lo)), ends[1].minus(curve.eval(hi))];
        if !gaps.iter().all(|g| g.norm() <= arc_tolerance) || hi <= lo {
            return Err(Error::DegenerateMove);
        }
        let tangents = [curve.piece_deriv(0, lo, 1), curve.deriv(hi, 1)];
        if !tangents.iter().all(|t| t.norm() > 0.0 && t.is_finite()) {
            return Err(Error::DegenerateMove);
        }
        Ok(Traced::Curve {
            curve,
            lo,
            span: hi - lo,
            ends,
            gaps,
        })
    }

    /// `|c'|` of a line, a circle or a helix; `None` where it varies.
    fn constant_speed(&self) -> Option<f64> {
        match &self.shape {
            Traced::Line { from, to } => Some(to.minus(*from).norm()),
            Traced::Arc(arc) => {
                let (r0, r1) = arc.radii();
                (r0 == r1).then(|| arc.deriv(0.0, 1).norm())
            }
            Traced::Bezier(_) | Traced::Curve { .. } => None,
        }
    }

    /// The scale of the arc lengths' accuracy: an upper bound of the length (the control
    /// polygon, or chord and sweep); for a curve its length once known, before that the
    /// polygon through its piece ends and middles.
    fn chord_bound(&self) -> f64 {
        match &self.shape {
            Traced::Line { from, to } => to.minus(*from).norm(),
            Traced::Arc(arc) => {
                let (r0, r1) = arc.radii();
                arc.eval(1.0).minus(arc.eval(0.0)).norm()
                    + r0.max(r1) * arc.sweep().abs()
                    + (r1 - r0).abs()
            }
            Traced::Bezier(b) => {
                let p = b.control_points();
                (0..3).map(|i| p[i + 1].minus(p[i]).norm()).sum()
            }
            Traced::Curve { .. } if self.length > 0.0 => self.length,
            Traced::Curve { .. } => {
                let mut polygon = 0.0;
                for i in 0..ParamCurve::piece_count(self) {
                    let (a, b) = self.piece_domain(i);
                    let (p, m, q) = (self.eval(a), self.eval(0.5 * (a + b)), self.eval(b));
                    polygon += m.minus(p).norm() + q.minus(m).norm();
                }
                polygon
            }
        }
    }

    /// Whether the move is a line.
    pub(crate) fn is_line(&self) -> bool {
        matches!(self.shape, Traced::Line { .. })
    }

    /// Whether the move is a curve ([`Shape::Curve`]).
    pub(crate) fn is_curve(&self) -> bool {
        matches!(self.shape, Traced::Curve { .. })
    }

    /// The middle (in the parameter) of piece `i`.
    pub(crate) fn piece_middle(&self, i: usize) -> f64 {
        let (a, b) = self.piece_domain(i);
        0.5 * (a + b)
    }

    /// Up to where a stream may append a curve move of several pieces before the move after
    /// it is known: the middle of its last piece, which a corner blend at its end does not
    /// pass ([`blend_room`](Self::blend_room)); 0 for one piece and the other shapes.
    pub(crate) fn streamed_until(&self) -> f64 {
        let n = ParamCurve::piece_count(self);
        if n < 2 { 0.0 } else { self.piece_middle(n - 1) }
    }

    /// The longest arc length a corner blend may take from the move at its end (`at_end`)
    /// or its start: half of it, and for a curve of several pieces no more than from the
    /// middle of its last (first) piece on, so that a stream can append the rest before the
    /// next move is known, cut in the middles of the pieces (each join of pieces then lies
    /// inside a segment, where the speed limits cap it).
    ///
    /// # Errors
    /// [`Error::Curve`] when the arc length of that part does not converge.
    pub(crate) fn blend_room(&self, at_end: bool) -> Result<f64, Error> {
        let (half, n) = (self.length / 2.0, ParamCurve::piece_count(self));
        if n < 2 {
            return Ok(half);
        }
        let (a, b) = if at_end {
            (self.streamed_until(), 1.0)
        } else {
            (0.0, self.piece_middle(0))
        };
        let part = arc_length_between(self, a, b, LENGTH_ACCURACY * self.chord_bound())?;
        Ok(half.min(part))
    }

    /// Where the next segment of a curve move streamed from `from` ends: the next middle of
    /// a piece after `from`, at most [`streamed_until`](Self::streamed_until).
    pub(crate) fn next_cut(&self, from: f64) -> f64 {
        let piece = self.piece_at(from);
        let middle = self.piece_middle(piece);
        let cut = if from < middle {
            middle
        } else {
            self.piece_middle(piece + 1)
        };
        cut.min(self.streamed_until())
    }

    /// The arc length of the move.
    ///
    /// ```
    /// use strak_trajectory::{Move, MoveCurve, Shape};
    /// use strak_curves::{Plane, Turn};
    /// let half = Move::<2>::new([2.0, 0.0], Shape::ArcRadius { radius: 1.0, plane: Plane::XY, turn: Turn::Clockwise });
    /// let c = MoveCurve::new([0.0, 0.0], &half, 1e-9)?;
    /// assert!((c.length() - core::f64::consts::PI).abs() < 1e-15);
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn length(&self) -> f64 {
        self.length
    }

    /// The parameter at the arc length `s` from the start (`s` clamped to the move).
    ///
    /// # Errors
    /// [`Error::Curve`] when the arc-length inversion of a spiral or a Bézier does not
    /// converge (see [`strak_curves::param_at_length`]).
    ///
    /// ```
    /// use strak_trajectory::{Move, MoveCurve};
    /// let c = MoveCurve::new([0.0, 0.0], &Move::<2>::line([3.0, 4.0]), 0.0)?;
    /// assert_eq!(c.param_at(1.0)?, 0.2);
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn param_at(&self, s: f64) -> Result<f64, Error> {
        let s = s.clamp(0.0, self.length);
        match self.speed {
            Some(_) => Ok((s / self.length).min(1.0)),
            None => Ok(param_at_length(
                self,
                s,
                LENGTH_ACCURACY * self.chord_bound(),
            )?),
        }
    }

    /// Whether the speed `|c'|` is constant (lines, circles, helices): the parameter is then
    /// proportional to the arc length.
    pub(crate) fn has_constant_speed(&self) -> bool {
        self.speed.is_some()
    }

    /// The arc length from the start to the parameter `u` (clamped to `[0, 1]`).
    ///
    /// # Errors
    /// [`Error::Curve`] when the arc length of a spiral or a Bézier does not converge.
    pub(crate) fn length_to(&self, u: f64) -> Result<f64, Error> {
        let u = u.clamp(0.0, 1.0);
        match self.speed {
            Some(_) if u >= 1.0 => Ok(self.length),
            Some(speed) => Ok(speed * u),
            None if u >= 1.0 => Ok(self.length),
            None => Ok(arc_length_between(
                self,
                0.0,
                u,
                LENGTH_ACCURACY * self.chord_bound(),
            )?),
        }
    }

    /// An upper bound of `|c''(u)|` over the whole move: 0 for a line; `r·w² + 2·|r′|·w` for
    /// an arc of largest radius `r`, sweep `w` and radius change `r′` (the coordinates
    /// outside the plane are linear in `u`); `6·max|Δ²bᵢ|` for a cubic Bézier (its second
    /// derivative is a linear Bézier in the second differences of the control points;
    /// Farin, *Curves and Surfaces for CAGD*, 5th ed., §5.3); for a curve the Taylor bound
    /// of [`strak_curves::second_derivative_bound`] (a bound for polynomial pieces up to
    /// degree 8, an estimate for rational ones), `∞` where that fails.
    ///
    /// ```
    /// use strak_trajectory::{Move, MoveCurve};
    /// let c = MoveCurve::new([0.0, 0.0], &Move::<2>::line([3.0, 4.0]), 0.0)?;
    /// assert_eq!(c.second_derivative_bound(), 0.0);
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn second_derivative_bound(&self) -> f64 {
        self.second_derivative_bound_on((0.0, 1.0))
    }

    /// An upper bound of `|c''(u)|` over `u ∈ [a, b]`: a curve's own over that part of it,
    /// the whole move's for the other shapes (see
    /// [`second_derivative_bound`](Self::second_derivative_bound)).
    pub(crate) fn second_derivative_bound_on(&self, (a, b): (f64, f64)) -> f64 {
        match &self.shape {
            Traced::Line { .. } => 0.0,
            Traced::Arc(arc) => {
                let (r0, r1) = arc.radii();
                let w = arc.sweep().abs();
                r0.max(r1) * w * w + 2.0 * (r1 - r0).abs() * w
            }
            Traced::Bezier(b) => {
                let p = b.control_points();
                let second = |i: usize| p[i + 2].minus(p[i + 1].times(2.0)).plus(p[i]).norm();
                6.0 * second(0).max(second(1))
            }
            Traced::Curve {
                curve, lo, span, ..
            } => second_derivative_bound(curve, lo + a * span, lo + b * span)
                .map_or(f64::INFINITY, |m| m * span * span),
        }
    }

    /// The piece of a curve at `u` (in `[0, 1]`): the last whose mapped start is at most
    /// `u`, so that a piece's derivatives are taken from its own start on; 0 for the other
    /// shapes.
    fn piece_at(&self, u: f64) -> usize {
        let n = ParamCurve::piece_count(self);
        // first the piece of equal pieces (a uniform knot vector's), then a binary search
        #[allow(
            clippy::cast_possible_truncation,
            clippy::cast_sign_loss,
            clippy::cast_precision_loss
        )]
        let guess = ((u * n as f64) as usize).min(n - 1);
        if self.piece_start(guess) <= u && (guess + 1 == n || u < self.piece_start(guess + 1)) {
            return guess;
        }
        let (mut lo, mut hi) = (0, n - 1);
        while lo < hi {
            let mid = hi - (hi - lo) / 2;
            if self.piece_start(mid) <= u {
                lo = mid;
            } else {
                hi = mid - 1;
            }
        }
        lo
    }

    /// Where piece `i` starts, mapped onto `[0, 1]` (0 for the first piece and the other
    /// shapes).
    fn piece_start(&self, i: usize) -> f64 {
        match &self.shape {
            Traced::Curve {
                curve, lo, span, ..
            } if i > 0 => ((curve.piece_domain(i).0 - lo) / span).clamp(0.0, 1.0),
            _ => 0.0,
        }
    }

    /// The pieces of the move that its parameters `from ..= to` cross: the first and their
    /// number (one for the shapes other than curves).
    pub(crate) fn pieces_within(&self, (from, to): (f64, f64)) -> (usize, usize) {
        if !matches!(self.shape, Traced::Curve { .. }) {
            return (0, 1);
        }
        let first = self.piece_at(from);
        let mut last = self.piece_at(to);
        if last > first && self.piece_domain(last).0 >= to {
            last -= 1;
        }
        (first, last - first + 1)
    }

    /// The derivative of order `k` of a curve's trace at `u` (clamped to `[0, 1]`).
    fn curve_deriv(&self, u: f64, k: usize) -> [f64; D] {
        let Traced::Curve {
            curve,
            lo,
            span,
            ends,
            gaps,
        } = &self.shape
        else {
            return [0.0; D];
        };
        let u = u.clamp(0.0, 1.0);
        if k == 0 && (u == 0.0 || u == 1.0) {
            return ends[usize::from(u == 1.0)];
        }
        let d = curve.piece_deriv(self.piece_at(u), lo + u * span, k);
        match k {
            0 => d.plus(gaps[0].lerp(gaps[1], u)),
            1 => d.times(*span).plus(gaps[1].minus(gaps[0])),
            _ => d.times((0..k).fold(1.0, |p, _| p * span)),
        }
    }
}

impl<const D: usize, C: StreamCurve<D>> ParamCurve for MoveCurve<D, C> {
    type Point = [f64; D];

    fn domain(&self) -> (f64, f64) {
        (0.0, 1.0)
    }

    fn piece_count(&self) -> usize {
        match &self.shape {
            Traced::Curve { curve, .. } => curve.piece_count(),
            _ => 1,
        }
    }

    /// A curve's piece `i` mapped onto `[0, 1]` (its ends exactly 0 and 1): from its start
    /// to the next piece's.
    fn piece_domain(&self, i: usize) -> (f64, f64) {
        let last = ParamCurve::piece_count(self) - 1;
        let i = i.min(last);
        let end = if i == last {
            1.0
        } else {
            self.piece_start(i + 1)
        };
        (self.piece_start(i), end)
    }

    fn eval(&self, u: f64) -> [f64; D] {
        match &self.shape {
            Traced::Line { from, to } => {
                let u = u.clamp(0.0, 1.0);
                if u == 1.0 { *to } else { from.lerp(*to, u) }
            }
            Traced::Arc(arc) => arc.eval(u),
            // the end points exactly (de Casteljau's sums round off them)
            Traced::Bezier(b) if u >= 1.0 => b.control_points()[3],
            Traced::Bezier(b) if u <= 0.0 => b.control_points()[0],
            Traced::Bezier(b) => b.eval(u),
            Traced::Curve { .. } => self.curve_deriv(u, 0),
        }
    }
}

impl<const D: usize, C: StreamCurve<D>> ParamCurveDeriv for MoveCurve<D, C> {
    fn deriv(&self, u: f64, k: usize) -> [f64; D] {
        match &self.shape {
            Traced::Line { from, to } => match k {
                0 => self.eval(u),
                1 => to.minus(*from),
                _ => [0.0; D],
            },
            Traced::Arc(arc) => arc.deriv(u, k),
            Traced::Bezier(b) => b.deriv(u, k),
            Traced::Curve { .. } => self.curve_deriv(u, k),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use strak_curves::BSpline;

    /// A quadratic B-spline over `[2, 5]` with knots at 3 and 4: tangent-continuous, its
    /// second derivative steps at the knots.
    fn quadratic() -> BSpline<[f64; 2], 5, 8> {
        let points = [[0.0, 0.0], [2.0, 2.0], [4.0, 0.0], [6.0, 2.0], [8.0, 0.0]];
        BSpline::new(2, &points, &[2.0, 2.0, 2.0, 3.0, 4.0, 5.0, 5.0, 5.0]).unwrap()
    }

    /// The curve's domain maps onto `[0, 1]`, with its pieces: the derivatives are the
    /// curve's own (by the chain rule), each piece's from its own start on and its left
    /// limit just before, and the ends are the move's exactly.
    #[test]
    fn a_curve_move_traces_its_curve_piece_by_piece() {
        let s = quadratic();
        let m = MoveCurve::new([0.0, 0.0], &Move::curve(&s), 1e-9).unwrap();
        assert_eq!(
            (m.piece_count(), m.piece_domain(0).0, m.piece_domain(2).1),
            (3, 0.0, 1.0)
        );
        let knot = m.piece_domain(1).0;
        assert_eq!(knot, m.piece_domain(0).1);
        assert!((knot - 1.0 / 3.0).abs() < 1e-15);
        let before = knot - 1e-15;
        for (u, piece) in [(knot, 1), (before, 0), (0.8, 2)] {
            for k in 0..3 {
                let scale = 3.0_f64.powi(i32::try_from(k).unwrap());
                let x = (2.0 + 3.0 * u).clamp(s.piece_domain(piece).0, s.piece_domain(piece).1);
                let want = s.piece_deriv(piece, x, k).times(scale);
                let got = m.deriv(u, k);
                assert!(
                    got.minus(want).norm() <= 1e-12 * (1.0 + want.norm()),
                    "{u} {k}"
                );
            }
        }
        assert!(m.deriv(knot, 2).minus(m.deriv(before, 2)).norm() > 1.0);
        assert_eq!((m.eval(0.0), m.eval(1.0)), ([0.0, 0.0], [8.0, 0.0]));
        let length = arc_length(&s, 1e-13).unwrap();
        assert!((m.length() - length).abs() < 1e-11 * length);
        assert_eq!(m.pieces_within((0.1, knot)), (0, 1));
        assert_eq!(m.pieces_within((knot, 0.9)), (1, 2));
        assert_eq!(m.pieces_within((0.0, 1.0)), (0, 3));
        // c'' is constant on each piece: the bound is its largest size, times 3²
        let largest = (0..3_u8)
            .map(|i: u8| s.piece_deriv(usize::from(i), 2.5 + f64::from(i), 2).norm())
            .fold(0.0, f64::max);
        let c2 = m.second_derivative_bound();
        assert!((c2 - 9.0 * largest).abs() < 1e-9 * c2, "{c2} {largest}");
    }

    /// A curve that starts or ends off the move's ends by at most the tolerance is moved
    /// onto them (the ends exactly); farther off, or with a vanishing end tangent, it is
    /// refused.
    #[test]
    fn a_curve_move_meets_its_ends_or_is_refused() {
        let s = quadratic();
        let from = [1e-8, 0.0];
        let m = MoveCurve::new(from, &Move::curve(&s), 1e-7).unwrap();
        assert_eq!((m.eval(0.0), m.eval(1.0)), (from, [8.0, 0.0]));
        assert!(m.eval(0.5).minus(s.eval(3.5)).norm() < 1e-8);
        assert_eq!(
            MoveCurve::new(from, &Move::curve(&s), 1e-9),
            Err(Error::DegenerateMove)
        );
        let mut off = Move::curve(&s);
        off.to = [8.0, 1e-6];
        assert_eq!(
            MoveCurve::new([0.0; 2], &off, 1e-9),
            Err(Error::DegenerateMove)
        );
        let points = [[0.0, 0.0], [0.0, 0.0], [4.0, 0.0], [6.0, 2.0]];
        let flat = BSpline::<[f64; 2], 4, 8>::new(3, &points, &[0., 0., 0., 0., 1., 1., 1., 1.]);
        let flat = flat.unwrap();
        assert_eq!(
            MoveCurve::new([0.0; 2], &Move::curve(&flat), 1e-9),
            Err(Error::DegenerateMove)
        );
    }
}
