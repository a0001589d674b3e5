//! Corner blends: the curvature-continuous (G²) quintic that replaces the junction of two
//! moves, within a tolerance of the programmed path.
//!
//! # The blend
//!
//! A blend leaves the incoming move at the arc length `L` before the junction `C` and joins
//! the outgoing move at `L` after it. It is the quintic Bézier curve (Farin, *Curves and
//! Surfaces for CAGD*, 5th ed., ch. 4) with the control points
//!
//! ```text
//! b₀ = S,  b₁ = S + a·T_S,  b₂ = S + (a+b)·T_S + (5/4)·a²·k_S,
//! b₅ = E,  b₄ = E − a·T_E,  b₃ = E − (a+b)·T_E + (5/4)·a²·k_E,
//! ```
//!
//! where `S`, `E` are the points where it leaves and joins, `T` the unit tangents there and
//! `k` the curvature vectors (`d²c/ds²`), `a = 0.4·L` and `b = 0.325·L`. At `t = 0`,
//! `B' = 5a·T_S` and `B'' = 20·((b − a)·T_S + (5/4)·a²·k_S)`, whose part normal to `T_S`
//! divided by `|B'|²` is `k_S`: position, tangent and curvature vector agree with the move,
//! and likewise at `t = 1`. The fractions `0.4` and `0.325` keep the largest curvature
//! derivative `dκ/ds` low (it, not the curvature, binds the speed through a tight corner
//! under a jerk limit: `v³·|dκ/ds| ≤ j`); at a right angle they need 18 % more curvature
//! than the fractions of least curvature but a sixteenth of their curvature derivative.
//!
//! # The deviation bound
//!
//! Let `u₁`, `u₂` be the unit tangents at `C` and `φ` the angle between them. The same
//! construction on the two tangent lines at `C` has the control points
//! `q₀ = C − L·u₁, q₁ = C − (L−a)·u₁, q₂ = C − (L−a−b)·u₁` and their mirror images
//! `q₃, q₄, q₅` on `C + s·u₂`. Its Bernstein weights give the corner blend of two lines:
//!
//! * `Σ Bᵢ(t)·qᵢ = C − α(t)·u₁ + β(t)·u₂`, where `α` has the coefficients
//!   `(L, L−a, L−a−b, 0, 0, 0)`, so it falls monotonically, and `β` is its mirror image
//!   and rises. Both equal `K/32` at `t = ½`, with `K = 16L − 15a − 10b`.
//! * Where `β ≤ α` the point lies `β·sin φ ≤ (K/32)·sin φ` from the tangent line of `u₁`,
//!   with its foot at most `x = L·(1 + max(0, −cos φ))` from `C`; likewise on the other
//!   side. The midpoint is `(K/16)·sin(φ/2)` from `C`, which bounds both.
//!
//! The blend's control points differ from these by `eᵢ = bᵢ − qᵢ`, and a convex combination
//! of the `eᵢ` is no longer than the longest, so every point of the blend lies within
//! `(K/16)·sin(φ/2) + max|eᵢ|` of a foot on a tangent line, and `C` lies that close to the
//! blend's midpoint. A move whose parameter runs at the speed `|c'| = σ` at `C` departs from
//! its tangent line by at most `M₂·(x/σ)²/2` over the length `x` (Taylor's theorem with
//! `M₂ ≥ |c''|` over the parameters within `x/σ` of `C`,
//! [`MoveCurve::second_derivative_bound`]; for a curve move of rational pieces `M₂` is an
//! estimate, so the bound is too). So
//!
//! ```text
//! deviation ≤ (K/16)·sin(φ/2) + max|eᵢ| + max over both moves of M₂·(x/σ)²/2
//! ```
//!
//! bounds both the distance of every point of the blend from the programmed path and the
//! distance of `C` from the blend (a two-sided bound, as G64 P means it). For two lines
//! the last two terms vanish and `L = 16·ε / ((16 − 15·0.4 − 10·0.325)·sin(φ/2))` meets the
//! tolerance `ε` exactly; otherwise `L` starts there and shrinks until the bound holds.
//! It never exceeds half of either move, so that the blends at both ends of a move never
//! overlap, nor, for a curve move of several pieces, the part of its first or last piece
//! from that piece's middle on (a stream appends the rest before the next move is known).
//!
//! # Chains
//!
//! Where the blends at both ends of a line take half of it each (a dense chain of short
//! lines, as a slicer writes a curved wall), they meet at its midpoint, where the line's
//! curvature is zero: each blend's curvature would rise from zero to a peak and fall back
//! on every line, and its derivative `dκ/ds` (about `4·κ/c` for lines of length `c` on a
//! wall of curvature `κ`) binds the speed under a jerk limit. [`chain`] gives both blends
//! the same curvature vector `k` at the midpoint instead: the mean of their mean curvatures
//! there (each blend's turn `u₂ − u₁`, normal to the line, over its length `2L`), or half
//! of it. The blends still meet with the same point, tangent and curvature vector (G²), and
//! a blend with a chained end takes the legs `a = b = 0.4·L`, with which equal end
//! curvatures draw a nearly circular arc (on a circle of 0.2 mm chords the curvature stays
//! within 0.02 % of the circle's). Only the control points `b₂` or `b₃` move, by
//! `(5/4)·a²·k`, so the deviation bound above, evaluated with the moved points (and
//! `K = 16L − 15a − 10b` of the legs), still holds; the shared curvature is taken only
//! where both blends keep within the tolerance.

use strak_curves::{Bezier, ParamCurve, ParamCurveDeriv, Point};

use super::moves::{MoveCurve, StreamCurve};
use crate::error::Error;

/// `a / L`: the first control leg of a blend, as a share of its trim length.
const FIRST_LEG: f64 = 0.4;
/// `b / L`: the second control leg.
const SECOND_LEG: f64 = 0.325;
/// `K / L = 16 − 15·a/L − 10·b/L`.
const MIDPOINT_FACTOR: f64 = 16.0 - 15.0 * FIRST_LEG - 10.0 * SECOND_LEG;

/// `a / L` and `b / L` of a blend that joins a neighbouring blend with their shared
/// curvature (a chain, module docs): with equal ends of curvature `κ` they draw a nearly
/// circular arc, whose curvature derivative is a ten-thousandth of the zero-curvature
/// fractions' at a 1° turn.
const CHAIN_LEGS: (f64, f64) = (0.4, 0.4);

/// The largest turn that is blended (radians): beyond it the junction is an exact stop. A
/// blend of a near-reversal folds back on itself within a width of `ε`, and its curvature
/// derivative (growing as the fold tightens) allows so little speed that a stop at the
/// corner costs no time.
pub const REVERSAL_ANGLE: f64 = 170.0 * core::f64::consts::PI / 180.0;

/// Joins whose tangents and curvature vectors differ by less than this (relative) are
/// passed straight through: the difference is the rounding of the moves' ends.
const STRAIGHT: f64 = 1e-9;

/// Shrinking steps of the trim length before a junction is left to an exact stop.
const SHRINK_STEPS: usize = 64;

/// A curvature-continuous blend that replaces a junction of two moves.
///
/// ```
/// use strak_trajectory::{Junction, Move, MoveCurve, junction};
/// use strak_curves::ParamCurve;
/// let a = MoveCurve::new([0.0, 0.0], &Move::<2>::line([10.0, 0.0]), 0.0)?;
/// let b = MoveCurve::new([10.0, 0.0], &Move::<2>::line([10.0, 10.0]), 0.0)?;
/// let Junction::Blend(blend) = junction(&a, &b, 0.05)? else { panic!("a right angle blends") };
/// let mid = blend.curve().eval(0.5);
/// let corner = ((mid[0] - 10.0).powi(2) + mid[1].powi(2)).sqrt();
/// assert!((corner - 0.05).abs() < 1e-10); // the midpoint is the tolerance from the corner
/// assert!(blend.deviation() <= 0.05);
/// # Ok::<(), strak_trajectory::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Blend<const D: usize> {
    curve: Bezier<[f64; D], 6>,
    leave: f64,
    join: f64,
    trim: f64,
    deviation: f64,
    corner: Corner<D>,
    /// Where it leaves and where it joins: the point, the unit tangent and the curvature
    /// vector the blend has there.
    ends: [End<D>; 2],
    /// Whether the curvature at each end is a chain's (not the move's).
    chained: [bool; 2],
    /// The moves' departure from their tangent lines over the blend's reach.
    departure: f64,
}

/// A point of a curve with its unit tangent and curvature vector `d²c/ds²`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct End<const D: usize> {
    point: [f64; D],
    tangent: [f64; D],
    curvature: [f64; D],
}

impl<const D: usize> Blend<D> {
    /// `cos φ` of the turn of the tangent at the corner.
    pub(super) fn cos_turn(&self) -> f64 {
        self.corner.cos_phi
    }

    /// The blend curve, a quintic Bézier from where it leaves the incoming move to where it
    /// joins the outgoing one.
    ///
    /// ```
    /// # use strak_trajectory::{Junction, Move, MoveCurve, junction};
    /// # let a = MoveCurve::new([0.0, 0.0], &Move::<2>::line([10.0, 0.0]), 0.0)?;
    /// # let b = MoveCurve::new([10.0, 0.0], &Move::<2>::line([10.0, 10.0]), 0.0)?;
    /// # let Junction::Blend(blend) = junction(&a, &b, 0.05)? else { unreachable!() };
    /// assert_eq!(blend.curve().control_points().len(), 6);
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn curve(&self) -> &Bezier<[f64; D], 6> {
        &self.curve
    }

    /// The parameter of the incoming move where the blend leaves it.
    ///
    /// ```
    /// # use strak_trajectory::{Junction, Move, MoveCurve, junction};
    /// # let a = MoveCurve::new([0.0, 0.0], &Move::<2>::line([10.0, 0.0]), 0.0)?;
    /// # let b = MoveCurve::new([10.0, 0.0], &Move::<2>::line([10.0, 10.0]), 0.0)?;
    /// # let Junction::Blend(blend) = junction(&a, &b, 0.05)? else { unreachable!() };
    /// assert!((blend.leave() - (1.0 - blend.trim() / 10.0)).abs() < 1e-15);
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn leave(&self) -> f64 {
        self.leave
    }

    /// The parameter of the outgoing move where the blend joins it.
    ///
    /// ```
    /// # use strak_trajectory::{Junction, Move, MoveCurve, junction};
    /// # let a = MoveCurve::new([0.0, 0.0], &Move::<2>::line([10.0, 0.0]), 0.0)?;
    /// # let b = MoveCurve::new([10.0, 0.0], &Move::<2>::line([10.0, 10.0]), 0.0)?;
    /// # let Junction::Blend(blend) = junction(&a, &b, 0.05)? else { unreachable!() };
    /// assert!((blend.join() - blend.trim() / 10.0).abs() < 1e-15);
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn join(&self) -> f64 {
        self.join
    }

    /// The arc length `L` the blend takes from each move.
    ///
    /// ```
    /// # use strak_trajectory::{Junction, Move, MoveCurve, junction};
    /// # let a = MoveCurve::new([0.0, 0.0], &Move::<2>::line([10.0, 0.0]), 0.0)?;
    /// # let b = MoveCurve::new([10.0, 0.0], &Move::<2>::line([10.0, 10.0]), 0.0)?;
    /// # let Junction::Blend(blend) = junction(&a, &b, 0.05)? else { unreachable!() };
    /// // two lines at a right angle: L = 16·ε / (6.75·sin 45°)
    /// let l = 16.0 * 0.05 / (6.75 * core::f64::consts::FRAC_1_SQRT_2);
    /// assert!((blend.trim() - l).abs() < 1e-8 * l);
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn trim(&self) -> f64 {
        self.trim
    }

    /// The proven bound of the blend's deviation from the programmed path (see the module
    /// docs): at most the tolerance it was made for.
    ///
    /// ```
    /// # use strak_trajectory::{Junction, Move, MoveCurve, junction};
    /// # let a = MoveCurve::new([0.0, 0.0], &Move::<2>::line([10.0, 0.0]), 0.0)?;
    /// # let b = MoveCurve::new([10.0, 0.0], &Move::<2>::line([10.0, 10.0]), 0.0)?;
    /// # let Junction::Blend(blend) = junction(&a, &b, 0.05)? else { unreachable!() };
    /// assert!(blend.deviation() <= 0.05);
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn deviation(&self) -> f64 {
        self.deviation
    }
}

/// How the motion passes from one move to the next.
///
/// ```
/// use strak_trajectory::{Junction, Move, MoveCurve, junction};
/// let a = MoveCurve::new([0.0, 0.0], &Move::<2>::line([1.0, 0.0]), 0.0)?;
/// let b = MoveCurve::new([1.0, 0.0], &Move::<2>::line([2.0, 0.0]), 0.0)?;
/// assert_eq!(junction(&a, &b, 0.01)?, Junction::Straight);
/// assert_eq!(junction(&a, &b, 0.0)?, Junction::Straight);
/// # Ok::<(), strak_trajectory::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Junction<const D: usize> {
    /// The moves join with continuous tangent and curvature: the motion passes straight on.
    Straight,
    /// The motion comes to rest at the junction (an exact stop: a zero tolerance, or a turn
    /// beyond [`REVERSAL_ANGLE`]).
    Stop,
    /// A blend replaces the junction.
    Blend(Blend<D>),
}

/// The unit tangent, the curvature vector `d²c/ds²` and the speed `|c'|` at `u`; `None`
/// where the speed vanishes.
fn frame<const D: usize, C: StreamCurve<D>>(
    curve: &MoveCurve<D, C>,
    u: f64,
) -> Option<([f64; D], [f64; D], f64)> {
    let (d1, d2) = (curve.deriv(u, 1), curve.deriv(u, 2));
    let speed = d1.norm();
    if !(speed > 0.0 && speed.is_finite()) {
        return None;
    }
    let t = d1.times(1.0 / speed);
    let normal = d2.minus(t.times(d2.dot(t)));
    Some((t, normal.times(1.0 / (speed * speed)), speed))
}

/// How the motion passes the junction of `incoming` (ending at the junction) and `outgoing`
/// (starting there) within the tolerance `tolerance` (units; 0 for an exact stop): straight
/// on where tangent and curvature are continuous, an exact stop for a zero tolerance or a
/// near-reversal, else a [`Blend`] whose deviation from the programmed path is at most the
/// tolerance (module docs) and which takes at most half of either move (of a curve move of
/// several pieces, at most its first or last piece from its middle on).
///
/// # Errors
/// [`Error::InvalidTolerance`] for a negative or non-finite tolerance;
/// [`Error::DegenerateMove`] when the moves do not meet (the outgoing move must start where
/// the incoming one ends); [`Error::Curve`] when an arc-length inversion fails.
///
/// ```
/// use strak_trajectory::{Junction, Move, MoveCurve, junction};
/// let a = MoveCurve::new([0.0, 0.0], &Move::<2>::line([1.0, 0.0]), 0.0)?;
/// let back = MoveCurve::new([1.0, 0.0], &Move::<2>::line([0.0, 0.0]), 0.0)?;
/// assert_eq!(junction(&a, &back, 0.01)?, Junction::Stop); // a reversal
/// # Ok::<(), strak_trajectory::Error>(())
/// ```
pub fn junction<const D: usize, C: StreamCurve<D>>(
    incoming: &MoveCurve<D, C>,
    outgoing: &MoveCurve<D, C>,
    tolerance: f64,
) -> Result<Junction<D>, Error> {
    if !(tolerance.is_finite() && tolerance >= 0.0) {
        return Err(Error::InvalidTolerance);
    }
    let corner = incoming.eval(1.0);
    if corner != outgoing.eval(0.0) {
        return Err(Error::DegenerateMove);
    }
    let (Some(end), Some(start)) = (frame(incoming, 1.0), frame(outgoing, 0.0)) else {
        return Err(Error::DegenerateMove);
    };
    let (u1, u2) = (end.0, start.0);
    let curvature_step = end.1.minus(start.1).norm();
    if u1.minus(u2).norm() <= STRAIGHT
        && curvature_step <= STRAIGHT * (end.1.norm() + start.1.norm())
    {
        return Ok(Junction::Straight);
    }
    let cos_phi = u1.dot(u2).clamp(-1.0, 1.0);
    if tolerance == 0.0 || cos_phi < libm::cos(REVERSAL_ANGLE) {
        return Ok(Junction::Stop);
    }
    let corner_frame = Corner {
        point: corner,
        tangents: [u1, u2],
        speeds: [end.2, start.2],
        cos_phi,
        half_sin: libm::sqrt((1.0 - cos_phi) / 2.0),
    };
    let half = incoming.blend_room(true)?.min(outgoing.blend_room(false)?);
    let mut trim = if corner_frame.half_sin > 0.0 {
        // a hair inside, so that the rounding of the control points does not cost a step
        (16.0 * tolerance * (1.0 - 1e-9) / (MIDPOINT_FACTOR * corner_frame.half_sin)).min(half)
    } else {
        half
    };
    for _ in 0..SHRINK_STEPS {
        match corner_frame.blend(incoming, outgoing, trim)? {
            Some(blend) if blend.deviation <= tolerance => return Ok(Junction::Blend(blend)),
            Some(blend) => trim = corner_frame.shorter(trim, blend.deviation, tolerance),
            None => trim *= 0.5,
        }
    }
    Ok(Junction::Stop)
}

/// The junction point, the unit tangents and the parameter speeds there.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Corner<const D: usize> {
    point: [f64; D],
    tangents: [[f64; D]; 2],
    speeds: [f64; 2],
    cos_phi: f64,
    /// `sin(φ/2)`.
    half_sin: f64,
}

impl<const D: usize> Corner<D> {
    /// The part of the deviation bound that grows linearly with the trim: that of the
    /// corner of the tangent lines, `(K/16)·sin(φ/2)`.
    fn tangent_corner(&self, trim: f64) -> f64 {
        MIDPOINT_FACTOR * trim / 16.0 * self.half_sin
    }

    /// The largest distance `max|eᵢ|` of the control points `points`, of a blend of trim
    /// `trim` with the legs `legs`, from those of the blend of the tangent lines.
    fn control_error(&self, points: &[[f64; D]; 6], trim: f64, (a, b): (f64, f64)) -> f64 {
        let [u1, u2] = self.tangents;
        let offsets = [trim, trim - a, trim - a - b];
        let mut error: f64 = 0.0;
        for (i, offset) in offsets.into_iter().enumerate() {
            let q_in = self.point.minus(u1.times(offset));
            let q_out = self.point.plus(u2.times(offset));
            error = error
                .max(points[i].minus(q_in).norm())
                .max(points[5 - i].minus(q_out).norm());
        }
        error
    }

    /// A shorter trim for a blend of trim `trim` whose bound `deviation` exceeds
    /// `tolerance`: the root of `c₁·L + c₂·L² = tolerance`, with `c₁·trim` the tangent
    /// corner's part and `c₂·trim²` the rest (the control points' and the moves' departures
    /// from the tangent lines grow about as `L²`), a little inside, and at most `(1 − 10⁻⁶)·trim`.
    fn shorter(&self, trim: f64, deviation: f64, tolerance: f64) -> f64 {
        let linear = self.tangent_corner(trim);
        let c1 = linear / trim;
        let c2 = ((deviation - linear) / (trim * trim)).max(0.0);
        let target = tolerance * (1.0 - 1e-9);
        let root = 2.0 * target / (c1 + libm::sqrt(c1 * c1 + 4.0 * c2 * target));
        root.min(trim * (1.0 - 1e-6))
    }

    /// The blend of trim length `trim` and its deviation bound; `None` where a move's
    /// speed vanishes at the trim or its tangent-line bound would reach past its start or
    /// end.
    fn blend<C: StreamCurve<D>>(
        &self,
        incoming: &MoveCurve<D, C>,
        outgoing: &MoveCurve<D, C>,
        trim: f64,
    ) -> Result<Option<Blend<D>>, Error> {
        let leave = incoming.param_at(incoming.length() - trim)?;
        let join = outgoing.param_at(trim)?;
        let (Some(s), Some(e)) = (frame(incoming, leave), frame(outgoing, join)) else {
            return Ok(None);
        };
        let ends = [
            End {
                point: incoming.eval(leave),
                tangent: s.0,
                curvature: s.1,
            },
            End {
                point: outgoing.eval(join),
                tangent: e.0,
                curvature: e.1,
            },
        ];
        let reach = trim * (1.0 + (-self.cos_phi).max(0.0));
        let (tau_in, tau_out) = (reach / self.speeds[0], reach / self.speeds[1]);
        if tau_in > 1.0 || tau_out > 1.0 {
            return Ok(None);
        }
        let departure =
            (incoming.second_derivative_bound_on((1.0 - tau_in, 1.0)) * tau_in * tau_in)
                .max(outgoing.second_derivative_bound_on((0.0, tau_out)) * tau_out * tau_out)
                / 2.0;
        Ok(Blend::shaped(
            *self,
            ends,
            [false; 2],
            (leave, join, trim),
            departure,
        ))
    }
}

impl<const D: usize> Blend<D> {
    /// The blend of the corner `corner` from the end `ends[0]` to `ends[1]`, at the moves'
    /// parameters `leave` and `join` and the trim `trim`, with its deviation bound (module
    /// docs); the chain's legs where an end is `chained`. `None` where the control points
    /// do not make a curve.
    fn shaped(
        corner: Corner<D>,
        ends: [End<D>; 2],
        chained: [bool; 2],
        (leave, join, trim): (f64, f64, f64),
        departure: f64,
    ) -> Option<Self> {
        let (fa, fb) = if chained[0] || chained[1] {
            CHAIN_LEGS
        } else {
            (FIRST_LEG, SECOND_LEG)
        };
        let (a, b) = (fa * trim, fb * trim);
        let bend = 1.25 * a * a;
        let [s, e] = ends;
        let points = [
            s.point,
            s.point.plus(s.tangent.times(a)),
            s.point
                .plus(s.tangent.times(a + b))
                .plus(s.curvature.times(bend)),
            e.point
                .minus(e.tangent.times(a + b))
                .plus(e.curvature.times(bend)),
            e.point.minus(e.tangent.times(a)),
            e.point,
        ];
        let midpoint_factor = 16.0 - 15.0 * fa - 10.0 * fb;
        let lines = midpoint_factor * trim / 16.0 * corner.half_sin;
        let control_error = corner.control_error(&points, trim, (a, b));
        let curve = Bezier::new(points).ok()?;
        Some(Blend {
            curve,
            leave,
            join,
            trim,
            deviation: lines + control_error + departure,
            corner,
            ends,
            chained,
            departure,
        })
    }

    /// The same blend with the curvature vector `curvature` (normal to the tangent) at its
    /// end `end` (0: where it leaves, 1: where it joins), taken from a chain.
    fn chained_at(&self, end: usize, curvature: [f64; D]) -> Option<Self> {
        let mut ends = self.ends;
        ends[end].curvature = curvature;
        let mut chained = self.chained;
        chained[end] = true;
        let at = (self.leave, self.join, self.trim);
        Self::shaped(self.corner, ends, chained, at, self.departure)
    }

    /// The mean curvature vector of the blend at its end `end`: its turn `u₂ − u₁` (of
    /// length `2·sin(φ/2)`) normal to the tangent there, over the blend's length `2L`.
    fn mean_curvature(&self, end: usize) -> [f64; D] {
        let [u1, u2] = self.corner.tangents;
        let t = self.ends[end].tangent;
        let turn = u2.minus(u1);
        turn.minus(t.times(turn.dot(t))).times(0.5 / self.trim)
    }
}

/// Whether a move's parameters `(begin, end)` between its blends hold a part of it: not
/// where the blends at both ends take half of the move each (up to rounding).
pub(super) fn has_span((begin, end): (f64, f64)) -> bool {
    end - begin > 1e-12
}

/// Joins the blends of `junctions` (the junction after each move of `moves` but the last,
/// from [`junction`]) at both ends of each line they take all of between them, in order
/// along the path, as a [`Stream`](crate::Stream) does with the moves pushed into it: in
/// place of the line's zero curvature where they meet, both take one shared curvature
/// where it keeps them within `tolerance` (see the module docs, "Chains").
///
/// ```
/// use strak_trajectory::{Junction, Move, MoveCurve, chain_junctions, junction};
/// use strak_curves::ParamCurveDeriv;
/// // three chords of 0.2 mm on a circle of radius 10: both blends take all of the middle one
/// let p = |i: f64| [10.0 * (0.02 * i).cos(), 10.0 * (0.02 * i).sin()];
/// let moves = [
///     MoveCurve::new(p(0.0), &Move::<2>::line(p(1.0)), 0.0)?,
///     MoveCurve::new(p(1.0), &Move::<2>::line(p(2.0)), 0.0)?,
///     MoveCurve::new(p(2.0), &Move::<2>::line(p(3.0)), 0.0)?,
/// ];
/// let mut junctions = [junction(&moves[0], &moves[1], 0.02)?, junction(&moves[1], &moves[2], 0.02)?];
/// chain_junctions(&moves, &mut junctions, 0.02);
/// let Junction::Blend(first) = &junctions[0] else { panic!("a blend") };
/// let k = first.curve().deriv(1.0, 2); // where it meets the next blend: curved
/// assert!(k[0].hypot(k[1]) > 0.0);
/// # Ok::<(), strak_trajectory::Error>(())
/// ```
pub fn chain_junctions<const D: usize, C: StreamCurve<D>>(
    moves: &[MoveCurve<D, C>],
    junctions: &mut [Junction<D>],
    tolerance: f64,
) {
    for i in 1..junctions.len() {
        let (done, rest) = junctions.split_at_mut(i);
        if let (Some(Junction::Blend(before)), Some(Junction::Blend(after)), Some(through)) =
            (done.last_mut(), rest.first_mut(), moves.get(i))
            && !has_span((before.join(), after.leave()))
        {
            chain(before, after, through, tolerance);
        }
    }
}

/// Joins the blends `before` and `after` of the two corners of the line `through` where
/// they take all of it between them (they meet at one point of it): in place of the line's
/// zero curvature at that point, both take the mean of their mean curvatures there (or half
/// of it), where both stay within `tolerance`. A dense chain of short lines on a curved wall
/// then draws a curve of nearly constant curvature, as the wall, and not one whose curvature
/// falls to zero on every line: its curvature derivative, which binds the speed under a
/// jerk limit (`v³·|dκ/ds| ≤ j`), falls from about `4·κ/c` (lines of length `c`) to nearly
/// zero. Each end's control point moves by `(5/4)·a²·Δk`; the deviation bound (module
/// docs) is evaluated again with the moved points, so it still holds. Nothing changes where
/// the line is not a line or neither mean fits.
pub(super) fn chain<const D: usize, C: StreamCurve<D>>(
    before: &mut Blend<D>,
    after: &mut Blend<D>,
    through: &MoveCurve<D, C>,
    tolerance: f64,
) {
    if !through.is_line() {
        return;
    }
    let mean = before
        .mean_curvature(1)
        .plus(after.mean_curvature(0))
        .times(0.5);
    for share in [1.0, 0.5] {
        let k = mean.times(share);
        if let (Some(b), Some(a)) = (before.chained_at(1, k), after.chained_at(0, k))
            && b.deviation <= tolerance
            && a.deviation <= tolerance
        {
            (*before, *after) = (b, a);
            return;
        }
    }
}
