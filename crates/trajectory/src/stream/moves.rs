//! The moves of a stream and the curves they trace: a line, a circular arc or helix (G2/G3),
//! a cubic Bézier (G5), each from the end of the move before.

use strak_curves::{
    Bezier, CircularArc, ParamCurve, ParamCurveDeriv, Plane, Point, Turn, arc_length,
    arc_length_between, param_at_length,
};

use crate::error::Error;

/// The relative accuracy of the arc lengths of curved moves (spirals and Béziers; the
/// lengths of lines, circles and helices are closed forms).
pub(super) const LENGTH_ACCURACY: f64 = 1e-12;

/// The geometry of a move: what it traces from the end of the move before to its
/// [`Move::to`].
///
/// ```
/// use strak_trajectory::Shape;
/// use strak_curves::{Plane, Turn};
/// let quarter = Shape::<3>::ArcCenter { center: [0.0, 0.0], plane: Plane::XY, turn: Turn::CounterClockwise };
/// assert_ne!(quarter, Shape::Line);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Shape<const D: usize> {
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
}

/// One move of a stream: a shape to a point of `D` axes, at a feed.
///
/// ```
/// use strak_trajectory::{Move, Shape};
/// let m = Move::line([10.0, 0.0, 0.0]).with_feed(150.0);
/// assert_eq!((m.to, m.shape, m.feed), ([10.0, 0.0, 0.0], Shape::Line, Some(150.0)));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Move<const D: usize> {
    /// Where the move ends.
    pub to: [f64; D],
    /// What it traces to there.
    pub shape: Shape<D>,
    /// The largest path velocity of the move (units/s); `None` for a rapid move, which runs
    /// at the machine's limits.
    pub feed: Option<f64>,
}

impl<const D: usize> Move<D> {
    /// A rapid straight move to `to`.
    ///
    /// ```
    /// use strak_trajectory::Move;
    /// assert_eq!(Move::line([1.0, 2.0]).feed, None);
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
    /// let half = Move::new([2.0, 0.0], Shape::ArcRadius { radius: 1.0, plane: Plane::XY, turn: Turn::Clockwise });
    /// assert_eq!(half.to, [2.0, 0.0]);
    /// ```
    pub const fn new(to: [f64; D], shape: Shape<D>) -> Self {
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
    /// assert_eq!(Move::line([1.0]).with_feed(5.0).feed, Some(5.0));
    /// ```
    #[must_use]
    pub const fn with_feed(self, feed: f64) -> Self {
        Move {
            feed: Some(feed),
            ..self
        }
    }
}

/// The curve a [`Move`] traces from a start point, over the parameter domain `[0, 1]`.
///
/// Lines, circles and helices have a constant speed in the parameter, so their lengths and
/// the parameters at given lengths are closed forms; spirals (an arc whose end lies off the
/// start's circle within the tolerance) and Béziers use adaptive Gauss–Legendre arc lengths
/// ([`strak_curves::arc_length`]).
///
/// ```
/// use strak_trajectory::{Move, MoveCurve};
/// use strak_curves::ParamCurve;
/// let c = MoveCurve::new([0.0, 0.0], &Move::line([3.0, 4.0]), 1e-6)?;
/// assert_eq!((c.length(), c.eval(0.5)), (5.0, [1.5, 2.0]));
/// # Ok::<(), strak_trajectory::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MoveCurve<const D: usize> {
    shape: Traced<D>,
    length: f64,
    /// `|c'|` where it is constant (lines, circles, helices).
    speed: Option<f64>,
}

/// The curve of each shape.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Traced<const D: usize> {
    Line { from: [f64; D], to: [f64; D] },
    Arc(CircularArc<[f64; D]>),
    Bezier(Bezier<[f64; D], 4>),
}

impl<const D: usize> MoveCurve<D> {
    /// The curve of `mv` from `from`. An arc's end may lie off the circle of its start by
    /// at most `arc_tolerance` (as [`CircularArc`] takes it).
    ///
    /// # Errors
    /// [`Error::DegenerateMove`] for a move of zero length, or a Bézier whose tangent
    /// vanishes at an end (a control point on its end point); [`Error::Curve`] for an arc
    /// the [`CircularArc`] constructors reject (a degenerate arc, an end off the circle, a
    /// bad plane) and for non-finite values; [`Error::InvalidLimit`] for a feed that is not
    /// finite and positive.
    ///
    /// ```
    /// use strak_trajectory::{Error, Move, MoveCurve};
    /// assert_eq!(MoveCurve::new([1.0, 1.0], &Move::line([1.0, 1.0]), 0.0), Err(Error::DegenerateMove));
    /// ```
    pub fn new(from: [f64; D], mv: &Move<D>, arc_tolerance: f64) -> Result<Self, Error> {
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

    /// `|c'|` of a line, a circle or a helix; `None` where it varies.
    fn constant_speed(&self) -> Option<f64> {
        match &self.shape {
            Traced::Line { from, to } => Some(to.minus(*from).norm()),
            Traced::Arc(arc) => {
                let (r0, r1) = arc.radii();
                (r0 == r1).then(|| arc.deriv(0.0, 1).norm())
            }
            Traced::Bezier(_) => None,
        }
    }

    /// An upper bound of the length: the control polygon (or chord and sweep).
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
        }
    }

    /// The arc length of the move.
    ///
    /// ```
    /// use strak_trajectory::{Move, MoveCurve, Shape};
    /// use strak_curves::{Plane, Turn};
    /// let half = Move::new([2.0, 0.0], Shape::ArcRadius { radius: 1.0, plane: Plane::XY, turn: Turn::Clockwise });
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
    /// let c = MoveCurve::new([0.0, 0.0], &Move::line([3.0, 4.0]), 0.0)?;
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
    /// Farin, *Curves and Surfaces for CAGD*, 5th ed., §5.3).
    ///
    /// ```
    /// use strak_trajectory::{Move, MoveCurve};
    /// let c = MoveCurve::new([0.0, 0.0], &Move::line([3.0, 4.0]), 0.0)?;
    /// assert_eq!(c.second_derivative_bound(), 0.0);
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn second_derivative_bound(&self) -> f64 {
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
        }
    }
}

impl<const D: usize> ParamCurve for MoveCurve<D> {
    type Point = [f64; D];

    fn domain(&self) -> (f64, f64) {
        (0.0, 1.0)
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
        }
    }
}

impl<const D: usize> ParamCurveDeriv for MoveCurve<D> {
    fn deriv(&self, u: f64, k: usize) -> [f64; D] {
        match &self.shape {
            Traced::Line { from, to } => match k {
                0 => self.eval(u),
                1 => to.minus(*from),
                _ => [0.0; D],
            },
            Traced::Arc(arc) => arc.deriv(u, k),
            Traced::Bezier(b) => b.deriv(u, k),
        }
    }
}
