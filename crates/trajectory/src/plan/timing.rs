//! The interface between planning and compiling: where on the curve the motion is at time t.

use strak_curves::MAX_DIM;

/// The limits a time law keeps along its curve: the speed `|ẋ|` and the Euclidean norms of
/// the acceleration `|ẍ|` and the jerk `|x⃛|` of the motion in space, the tangential
/// acceleration `d|ẋ|/dt`, and per axis `i` the
/// velocity `|ẋᵢ|` and the acceleration `|ẍᵢ|` (path units and seconds; `f64::INFINITY`
/// for a quantity the law does not bound, and for the entries beyond the curve's axes: a
/// point has at most [`MAX_DIM`] coordinates). A planned law reports them through
/// [`Timing::limits`], and [`compile`](crate::compile) keeps its pieces within them.
///
/// ```
/// use strak_trajectory::MotionLimits;
/// let planned = MotionLimits::new(200.0, 2_000.0, f64::INFINITY);
/// assert!(planned.jerk.is_infinite() && planned.axis_velocity[0].is_infinite());
/// let mut z_slow = planned;
/// z_slow.axis_velocity[2] = 20.0;
/// assert_eq!(z_slow.axis_velocity[..3], [f64::INFINITY, f64::INFINITY, 20.0]);
/// // speed and tangential acceleration only
/// let along = MotionLimits {
///     tangential_acceleration: 2_000.0,
///     ..MotionLimits::new(200.0, f64::INFINITY, f64::INFINITY)
/// };
/// assert!(along.acceleration.is_infinite());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct MotionLimits {
    /// The largest speed `|ẋ|`.
    pub velocity: f64,
    /// The largest acceleration `|ẍ|`.
    pub acceleration: f64,
    /// The largest jerk `|x⃛|`.
    pub jerk: f64,
    /// The largest tangential acceleration `|d|ẋ|/dt|` (the change of speed along the path,
    /// without the centripetal part), for a law that bounds only that (a trapezoid along
    /// the arc length); `|ẍ| ≤ acceleration` implies it.
    pub tangential_acceleration: f64,
    /// The largest velocity `|ẋᵢ|` of axis `i`.
    pub axis_velocity: [f64; MAX_DIM],
    /// The largest acceleration `|ẍᵢ|` of axis `i`.
    pub axis_acceleration: [f64; MAX_DIM],
}

impl MotionLimits {
    /// Limits along the path, none per axis and none of the tangential acceleration beyond
    /// `acceleration`.
    ///
    /// ```
    /// use strak_trajectory::MotionLimits;
    /// let l = MotionLimits::new(1.0, 2.0, 3.0);
    /// assert_eq!((l.velocity, l.acceleration, l.jerk), (1.0, 2.0, 3.0));
    /// assert!(l.axis_acceleration.iter().all(|a| a.is_infinite()));
    /// ```
    pub const fn new(velocity: f64, acceleration: f64, jerk: f64) -> Self {
        MotionLimits {
            velocity,
            acceleration,
            jerk,
            tangential_acceleration: f64::INFINITY,
            axis_velocity: [f64::INFINITY; MAX_DIM],
            axis_acceleration: [f64::INFINITY; MAX_DIM],
        }
    }
}

/// What a planned motion left free for feed changes (override, hold, resume): the machine's
/// limits it was planned against (path acceleration and jerk, per-axis accelerations,
/// `f64::INFINITY` for an axis without a limit of its own and beyond the curve's axes) and
/// the share of them the plan did not use. [`compile`](crate::compile()) derives the feed
/// ramps from it when its options give no limits (see
/// [`CompileOptions`](crate::CompileOptions)).
///
/// ```
/// use strak_curves::Bezier;
/// use strak_trajectory::{Limits, PathTiming, Timing};
/// let line = Bezier::new([[0.0, 0.0], [30.0, 40.0]])?;
/// let limits = Limits::<2>::new(100.0, 1_000.0, 20_000.0)?
///     .with_axis_acceleration([800.0, f64::INFINITY])?;
/// let reserve = PathTiming::<_, 16, 4>::scurve(&line, &limits)?.feed_reserve().unwrap();
/// assert_eq!((reserve.acceleration, reserve.jerk, reserve.share), (1_000.0, 20_000.0, 0.25));
/// assert_eq!(reserve.axis_acceleration[..2], [800.0, f64::INFINITY]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FeedReserve {
    /// The path acceleration limit `|ẍ|`.
    pub acceleration: f64,
    /// The path jerk limit `|x⃛|`.
    pub jerk: f64,
    /// The acceleration limit `|ẍᵢ|` of axis `i`.
    pub axis_acceleration: [f64; MAX_DIM],
    /// The share of these limits the plan left free (in `(0, 1)`).
    pub share: f64,
}

/// A time law mapped onto a curve: the curve parameter `u(t)` and its rate `du/dt` over
/// `t ∈ [0, duration]`.
///
/// Planners (parameter-proportional, constant speed, trapezoid, S-curve) implement it; the
/// compiler samples it. Implementations clamp `t` to `[0, duration]`.
///
/// ```
/// use strak_trajectory::Timing;
/// /// u runs from 0 to 1 in 2 s at a constant rate.
/// struct Linear;
/// impl Timing for Linear {
///     fn duration(&self) -> f64 { 2.0 }
///     fn param(&self, t: f64) -> (f64, f64) { (t.clamp(0.0, 2.0) / 2.0, 0.5) }
/// }
/// assert_eq!(Linear.param(1.0), (0.5, 0.5));
/// ```
pub trait Timing {
    /// The duration in seconds (finite, > 0).
    fn duration(&self) -> f64;

    /// `(u, du/dt)` at time `t` (clamped to `[0, duration]`).
    fn param(&self, t: f64) -> (f64, f64);

    /// `d²u/dt²` at time `t` (clamped to `[0, duration]`): the stretches of a compile
    /// ([`Stretches`](crate::Stretches)) start and end on the motion's exact state, its
    /// acceleration `c''·u̇² + c'·ü` included. The default is the central difference of
    /// `du/dt` over `10⁻⁶` of the duration (one-sided at the ends), which the stretches
    /// before and after a tick share, so they still meet there; the planned laws of this
    /// crate give it exactly.
    ///
    /// ```
    /// use strak_trajectory::Timing;
    /// /// u = t² on [0, 1].
    /// struct Square;
    /// impl Timing for Square {
    ///     fn duration(&self) -> f64 { 1.0 }
    ///     fn param(&self, t: f64) -> (f64, f64) { let t = t.clamp(0.0, 1.0); (t * t, 2.0 * t) }
    /// }
    /// assert!((Square.param_acceleration(0.5) - 2.0).abs() < 1e-8);
    /// assert!((Square.param_acceleration(1.0) - 2.0).abs() < 1e-8);
    /// ```
    fn param_acceleration(&self, t: f64) -> f64 {
        let duration = self.duration();
        let h = 1e-6 * duration;
        let t = t.clamp(0.0, duration);
        let (lo, hi) = ((t - h).max(0.0), (t + h).min(duration));
        if hi > lo {
            (self.param(hi).1 - self.param(lo).1) / (hi - lo)
        } else {
            0.0
        }
    }

    /// Reports the break times: the times in `(0, duration)` where the motion's jerk (the
    /// third derivative of the path position) jumps while the acceleration is continuous,
    /// e.g. the phase boundaries of an S-curve, by calling `out` once per break in
    /// increasing order (duplicates allowed).
    ///
    /// The compiler puts a spline knot on the tick nearest each break (see
    /// [`compile`](crate::compile)), so that the fitted cubic pieces need not follow a jump in
    /// jerk inside a piece. The default reports none (a smooth time law).
    ///
    /// ```
    /// use strak_trajectory::Timing;
    /// /// Constant jerk for 1 s, then constant acceleration for 1 s: u(t) in [0, 7/6].
    /// struct Ramp;
    /// impl Timing for Ramp {
    ///     fn duration(&self) -> f64 { 2.0 }
    ///     fn param(&self, t: f64) -> (f64, f64) {
    ///         let t = t.clamp(0.0, 2.0);
    ///         if t < 1.0 {
    ///             (t * t * t / 6.0, 0.5 * t * t)
    ///         } else {
    ///             let r = t - 1.0;
    ///             (1.0 / 6.0 + 0.5 * r + 0.5 * r * r, 0.5 + r)
    ///         }
    ///     }
    ///     fn breaks(&self, out: &mut dyn FnMut(f64)) { out(1.0) }
    /// }
    /// let mut seen = [0.0; 1];
    /// Ramp.breaks(&mut |t| seen[0] = t);
    /// assert_eq!(seen, [1.0]);
    /// ```
    fn breaks(&self, out: &mut dyn FnMut(f64)) {
        let _ = out;
    }

    /// The limits the motion keeps, if the time law promises any ([`MotionLimits`]); the
    /// compiler then keeps the compiled pieces within them, slowing the motion down by the
    /// small factor the fit needs or failing with
    /// [`Error::LimitExceeded`](crate::Error::LimitExceeded) (see
    /// [`compile`](crate::compile)). The default promises none (unplanned laws: a parameter
    /// rate, a constant speed).
    ///
    /// ```
    /// use strak_trajectory::{MotionLimits, Timing};
    /// struct Slow;
    /// impl Timing for Slow {
    ///     fn duration(&self) -> f64 { 1.0 }
    ///     fn param(&self, t: f64) -> (f64, f64) { (t.clamp(0.0, 1.0), 1.0) }
    /// }
    /// assert_eq!(Slow.limits(), None);
    /// ```
    fn limits(&self) -> Option<MotionLimits> {
        None
    }

    /// What the law left free for feed changes, if it was planned with a reserve
    /// ([`FeedReserve`]); the default has none (the compiler then takes a law that promises
    /// [`limits`](Self::limits) to move at them, and derives the feed limits of any other
    /// from the compiled peaks, see [`CompileOptions`](crate::CompileOptions)).
    ///
    /// ```
    /// use strak_trajectory::Timing;
    /// struct Slow;
    /// impl Timing for Slow {
    ///     fn duration(&self) -> f64 { 1.0 }
    ///     fn param(&self, t: f64) -> (f64, f64) { (t.clamp(0.0, 1.0), 1.0) }
    /// }
    /// assert_eq!(Slow.feed_reserve(), None);
    /// ```
    fn feed_reserve(&self) -> Option<FeedReserve> {
        None
    }
}
