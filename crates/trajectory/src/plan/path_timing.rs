//! A motion along the arc length mapped onto a curve: `u(t) = u(s(t))`, `du/dt = ṡ/|c'(u)|`.

use strak_curves::{ArcLengthTable, MAX_DIM, ParamCurve, ParamCurveDeriv, Point, Scalar, ScalarOf};

use super::arc_inverse::param_at_length;
use super::limits::Limits;
use super::motion::{MotionProfile, Phase};
use super::options::PlanOptions;
use super::planner::plan_motion_into;
use super::timing::{FeedReserve, MotionLimits, Timing};
use super::trajectory::Trajectory;
use super::{greater, norm64, to_param};
use crate::error::Error;

/// Chords summed for the length estimate that scales the arc-length accuracy.
const ESTIMATE_CHORDS: usize = 64;

/// Arc-length accuracy relative to the length estimate.
const RELATIVE_ACCURACY: f64 = 1e-10;

/// A one-dimensional stand-in for a curve whose first derivative is the curve's speed
/// `|c'(u)|`, in `f64`: the arc-length table of it is the curve's arc-length table, computed
/// in `f64` whatever the curve's scalar (only first derivatives are used by the table).
struct SpeedCurve<'a, C>(&'a C);

impl<C: ParamCurveDeriv> ParamCurve for SpeedCurve<'_, C> {
    type Point = [f64; 1];

    fn domain(&self) -> (f64, f64) {
        let (a, b) = self.0.domain();
        (a.to_f64(), b.to_f64())
    }

    /// Not a geometric point: the table never evaluates it.
    fn eval(&self, _u: f64) -> [f64; 1] {
        [0.0]
    }

    fn piece_count(&self) -> usize {
        self.0.piece_count()
    }

    fn piece_domain(&self, i: usize) -> (f64, f64) {
        let (a, b) = self.0.piece_domain(i);
        (a.to_f64(), b.to_f64())
    }
}

impl<C: ParamCurveDeriv> ParamCurveDeriv for SpeedCurve<'_, C> {
    fn deriv(&self, u: f64, k: usize) -> [f64; 1] {
        if k == 1 {
            [norm64(&self.0.deriv(param_on_side(self.0, u), 1))]
        } else {
            [0.0]
        }
    }
}

/// The curve's parameter for the table's `f64` parameter `u`, on the side of `u`: where
/// rounding into the curve's scalar moves `u` up by at most a few `f64` units, the value
/// two of the scalar's units below is taken instead. [`ArcLengthTable`] evaluates the
/// left-sided speed at a knot two `f64` units below it; in a coarser scalar (`f32`,
/// fixed-point) that point rounds back onto the knot, where the curve's derivative is the
/// right piece's, and the table's interval left of the knot would get the speed of the
/// piece after it as its end slope (a polyline with unequal segments then plans a time law
/// whose acceleration misses the plan by several times the limit).
fn param_on_side<C: ParamCurve>(curve: &C, u: f64) -> ScalarOf<C> {
    let s = to_param(curve, u);
    let rounded = s.to_f64();
    if !(rounded > u && rounded - u <= 8.0 * f64::EPSILON * u.abs().max(1.0)) {
        return s;
    }
    let lower = to_param(
        curve,
        rounded - 2.0 * ScalarOf::<C>::EPSILON * rounded.abs().max(1.0),
    );
    if lower < s { lower } else { s }
}

/// The arc-length table of `curve` in `f64`, written into `table`. The accuracy is `1e-10`
/// of a length estimate (the sum of 64 chords, a lower bound of the length), but not below
/// the noise of the curve's scalar: `32·ε_S·(u_end − u_start)·max(1, max|c'|)` (`ε_S` the
/// scalar's resolution, `max|c'|` over the 65 chord ends), since each speed value carries a
/// rounding error of a few `ε_S·max(1, |c'|)`.
fn arc_table_into<C: ParamCurveDeriv, const N: usize>(
    curve: &C,
    table: &mut ArcLengthTable<f64, N>,
) -> Result<(), Error> {
    let (a, b) = curve.domain();
    let (a, b) = (a.to_f64(), b.to_f64());
    let at = |k: usize| {
        #[allow(clippy::cast_precision_loss)]
        let u = a + (b - a) * (k as f64 / ESTIMATE_CHORDS as f64);
        to_param(curve, u)
    };
    let mut estimate = 0.0;
    let mut max_speed = norm64(&curve.deriv(at(0), 1));
    let mut prev = curve.eval(at(0));
    for k in 1..=ESTIMATE_CHORDS {
        let next = curve.eval(at(k));
        estimate += norm64(&next.minus(prev));
        max_speed = max_speed.max(norm64(&curve.deriv(at(k), 1)));
        prev = next;
    }
    if !(estimate.is_finite() && max_speed.is_finite()) {
        return Err(Error::Curve(strak_curves::Error::NonFinite));
    }
    if !greater(estimate, 0.0) {
        return Err(Error::EmptyPath);
    }
    let floor = 32.0 * ScalarOf::<C>::EPSILON * (b - a) * max_speed.max(1.0);
    let accuracy = (RELATIVE_ACCURACY * estimate).max(floor);
    table.rebuild(&SpeedCurve(curve), accuracy)?;
    if !greater(table.length(), 0.0) {
        return Err(Error::EmptyPath);
    }
    Ok(())
}

/// A motion along the arc length of a curve ([`MotionProfile`], at most `Z` zones) mapped
/// onto the curve's parameter through an [`ArcLengthTable`] of `N` samples: the [`Timing`]
///
/// ```text
/// u(t) = u(s(t))  (the root of the table's C¹ cubic Hermite interpolant of s(u)),
/// du/dt = ṡ(t) / |c'(u(t))|.
/// ```
///
/// The time laws:
/// * [`constant_speed`](Self::constant_speed): `s = v·t`;
/// * [`trapezoid`](Self::trapezoid): trapezoidal speed, rest to rest, global `v_max`,
///   `a_max` only;
/// * [`scurve`](Self::scurve) / [`plan`](Self::plan): jerk-limited (or trapezoidal) speed,
///   rest to rest, under [`Limits`] with the speed limit varying along the path (curvature,
///   per-axis velocity and acceleration).
///
/// The table and the planning are computed in `f64` from the curve's derivatives (converted
/// with [`Scalar::to_f64`]), whatever the curve's scalar; the arc lengths within `1e-10` of
/// the length (see [`ArcLengthTable`] for the interpolation error, reported by
/// [`table().error_estimate()`](ArcLengthTable::error_estimate); `N = 64 … 256` suits most
/// paths). Where `|c'(u)| = 0` (a cusp of the parameterization) `du/dt` is returned as 0.
///
/// ```
/// use strak_curves::Bezier;
/// use strak_trajectory::{PathTiming, Timing};
///
/// let line = Bezier::new([[0.0, 0.0], [3.0, 4.0], [30.0, 40.0]])?; // length 50, uneven speed
/// let timing = PathTiming::<_, 64, 1>::constant_speed(&line, 10.0)?;
/// assert!((timing.duration() - 5.0).abs() < 1e-9);
/// let (u, du_dt) = timing.param(2.5); // halfway along the arc length
/// assert!((timing.table().length_at(u) - 25.0).abs() < 1e-6);
/// assert!(du_dt > 0.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug)]
pub struct PathTiming<'a, C, const N: usize, const Z: usize> {
    curve: &'a C,
    table: ArcLengthTable<f64, N>,
    motion: MotionProfile<Z>,
    /// The control rate the motion was planned for.
    rate: f64,
    /// The feed-change limits and share for the compiler (none for the laws without
    /// [`Limits`]).
    feed: Option<FeedReserve>,
    /// What the law promises ([`Timing::limits`]).
    limits: Option<MotionLimits>,
}

/// Cloning shares the curve reference (the curve need not be `Clone`).
impl<C, const N: usize, const Z: usize> Clone for PathTiming<'_, C, N, Z> {
    fn clone(&self) -> Self {
        PathTiming {
            curve: self.curve,
            table: self.table.clone(),
            motion: self.motion.clone(),
            rate: self.rate,
            feed: self.feed,
            limits: self.limits,
        }
    }
}

impl<'a, C: ParamCurveDeriv, const N: usize, const Z: usize> PathTiming<'a, C, N, Z> {
    /// Constant speed along the arc length: `s = speed·t`, so `|dx/dt| = speed` up to the
    /// table's interpolation error. Starts and ends at `speed` (not at rest).
    ///
    /// # Errors
    /// [`Error::EmptyPath`] for a curve of zero length; [`Error::InvalidLimit`] for a speed
    /// that is not finite and positive; [`Error::Curve`] when the arc-length table fails
    /// (for example `N < 2`, or the curve stands still over a table interval);
    /// [`Error::CapacityExceeded`] for `Z = 0`.
    ///
    /// ```
    /// use strak_curves::Bezier;
    /// use strak_trajectory::{Error, PathTiming, Timing};
    /// let line = Bezier::new([[0.0, 0.0], [3.0, 4.0]])?;
    /// let t = PathTiming::<_, 16, 1>::constant_speed(&line, 2.0)?;
    /// assert!((t.duration() - 2.5).abs() < 1e-12);
    /// let still = Bezier::new([[1.0, 1.0], [1.0, 1.0]])?;
    /// assert!(matches!(
    ///     PathTiming::<_, 16, 1>::constant_speed(&still, 2.0),
    ///     Err(Error::EmptyPath)
    /// ));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn constant_speed(curve: &'a C, speed: f64) -> Result<Self, Error> {
        let mut timing = Self::empty(curve);
        timing.constant_speed_into(speed)?;
        Ok(timing)
    }

    /// [`constant_speed`](Self::constant_speed) along this plan's curve, in place (as
    /// [`plan_into`](Self::plan_into)): the arc-length table is written where this value
    /// lies. On an error the plan is left [`empty`](Self::empty).
    ///
    /// # Errors
    /// As [`constant_speed`](Self::constant_speed).
    ///
    /// ```
    /// use strak_curves::Bezier;
    /// use strak_trajectory::{PathTiming, Timing};
    /// let line = Bezier::new([[0.0, 0.0], [3.0, 4.0]])?;
    /// let mut t = Box::new(PathTiming::<_, 16, 1>::empty(&line)); // on the heap
    /// t.constant_speed_into(2.0)?;
    /// assert!((t.duration() - 2.5).abs() < 1e-12);
    /// assert!(t.constant_speed_into(-1.0).is_err() && t.length() == 0.0);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn constant_speed_into(&mut self, speed: f64) -> Result<(), Error> {
        self.in_place(|t| {
            arc_table_into(t.curve, &mut t.table)?;
            t.motion = MotionProfile::constant_speed(t.table.length(), speed)?;
            (t.rate, t.feed, t.limits) = (PlanOptions::DEFAULT_RATE, None, None);
            Ok(())
        })
    }

    /// The trapezoidal speed profile along the arc length, rest to rest, with the global
    /// limits `v_max` and `a_max` only (no curvature or per-axis limits: for those use
    /// [`plan`](Self::plan) with [`ProfileShape::Trapezoid`](crate::ProfileShape)). See
    /// [`MotionProfile::trapezoid`]. It reserves nothing for feed changes: to compile it for
    /// feed override, plan it with `1 − share` of the machine's tangential acceleration and
    /// give the machine's limits to [`CompileOptions::with_limits`](crate::CompileOptions::with_limits).
    ///
    /// # Errors
    /// As for [`constant_speed`](Self::constant_speed).
    ///
    /// ```
    /// use strak_curves::Bezier;
    /// use strak_trajectory::{PathTiming, Timing};
    /// let line = Bezier::new([[0.0, 0.0], [30.0, 40.0]])?; // length 50
    /// let t = PathTiming::<_, 16, 1>::trapezoid(&line, 10.0, 20.0)?;
    /// assert!((t.duration() - (50.0 / 10.0 + 10.0 / 20.0)).abs() < 1e-9);
    /// assert_eq!(t.param(t.duration()), (1.0, 0.0));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn trapezoid(curve: &'a C, v_max: f64, a_max: f64) -> Result<Self, Error> {
        let mut timing = Self::empty(curve);
        timing.trapezoid_into(v_max, a_max)?;
        Ok(timing)
    }

    /// [`trapezoid`](Self::trapezoid) along this plan's curve, in place (as
    /// [`plan_into`](Self::plan_into)). On an error the plan is left
    /// [`empty`](Self::empty).
    ///
    /// # Errors
    /// As [`trapezoid`](Self::trapezoid).
    ///
    /// ```
    /// use strak_curves::Bezier;
    /// use strak_trajectory::{PathTiming, Timing};
    /// let line = Bezier::new([[0.0, 0.0], [30.0, 40.0]])?; // length 50
    /// let mut t = Box::new(PathTiming::<_, 16, 1>::empty(&line));
    /// t.trapezoid_into(10.0, 20.0)?;
    /// assert!((t.duration() - (50.0 / 10.0 + 10.0 / 20.0)).abs() < 1e-9);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn trapezoid_into(&mut self, v_max: f64, a_max: f64) -> Result<(), Error> {
        self.in_place(|t| {
            arc_table_into(t.curve, &mut t.table)?;
            t.motion = MotionProfile::trapezoid(t.table.length(), v_max, a_max)?;
            (t.rate, t.feed) = (PlanOptions::DEFAULT_RATE, None);
            // The speed along the path; the acceleration only tangentially (not in curves).
            t.limits = Some(MotionLimits {
                tangential_acceleration: a_max,
                ..MotionLimits::new(v_max, f64::INFINITY, f64::INFINITY)
            });
            Ok(())
        })
    }

    /// Runs `build` on this plan (which writes every field but the curve) and leaves the
    /// plan [`empty`](Self::empty) when `build` fails: the one frame of every in-place
    /// constructor.
    fn in_place(
        &mut self,
        build: impl FnOnce(&mut Self) -> Result<(), Error>,
    ) -> Result<(), Error> {
        let result = build(self);
        if result.is_err() {
            self.clear();
        }
        result
    }

    /// Everything but the curve as in [`empty`](Self::empty), in place.
    fn clear(&mut self) {
        self.table = ArcLengthTable::EMPTY;
        self.motion = MotionProfile::EMPTY;
        (self.rate, self.feed, self.limits) = (PlanOptions::DEFAULT_RATE, None, None);
    }

    /// The jerk-limited S-curve, rest to rest, under the machine's `limits` (less the default
    /// feed reserve of ¼, planned for 1 kHz) with the speed limit varying along the path:
    /// [`plan`](Self::plan) with the default [`PlanOptions`].
    ///
    /// # Errors
    /// As for [`plan`](Self::plan).
    ///
    /// ```
    /// use strak_curves::Bezier;
    /// use strak_trajectory::{Limits, PathTiming, Timing};
    /// let arc = Bezier::new([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]])?;
    /// let limits = Limits::<2>::new(20.0, 100.0, 1000.0)?;
    /// let t = PathTiming::<_, 64, 32>::scurve(&arc, &limits)?;
    /// assert!(t.duration() > t.length() / 20.0);
    /// assert_eq!(t.param(t.duration()).0, 1.0);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn scurve<const A: usize>(curve: &'a C, limits: &Limits<A>) -> Result<Self, Error> {
        Self::plan(curve, limits, &PlanOptions::new())
    }

    /// Plans a rest-to-rest motion along the curve under the machine's `limits`, less the
    /// feed reserve (see [`PlanOptions`] for the algorithm and its settings, `q` its
    /// centripetal share, `s` its feed share): the motion uses at most `(1 − s)` of the
    /// acceleration and jerk limits (path and per axis), the rest is left to feed changes
    /// (compile with [`compile`](Self::compile)). With `a`, `j`, `a_i` so reduced, the speed
    /// limit `v_lim(s)` is the smallest of
    /// * the path velocity limit,
    /// * the curvature limit `√(q·a/κ)` (centripetal acceleration `v²κ ≤ q·a`),
    /// * the turning-jerk limit `∛(q·j/|x_sss|)` (S-curve; `x_sss` the third derivative
    ///   of the curve by arc length, `κ²` on a circle),
    /// * per axis `i`, `v_i/|T_i|` (unit tangent `T`),
    /// * per axis `i`, `√(q·a_i/|κN_i|)` (curvature vector `κN`),
    ///
    /// sampled along the curve and grouped into zones of nearly constant limit (at most `Z`).
    /// Each zone plans its speed changes with the path acceleration and jerk that the turning
    /// at its speed limit leaves, so that the motion **in space** keeps `|ẍ| ≤ a`,
    /// `|ẍ_i| ≤ a_i` and `|x⃛| ≤ j`. The motion stops at corners and cusps and passes smaller
    /// turns at joins at a bounded speed. A forward and a backward pass choose the speeds at
    /// the zone boundaries, and each zone gets a double S (or trapezoid) from its entry to its
    /// exit speed, with zero acceleration at the boundaries.
    ///
    /// The jerk bound assumes a curvature-continuous (G²) curve: where the curvature jumps
    /// (a line tangent to an arc, the joins of C¹ Hermite or Catmull-Rom splines) the
    /// centripetal acceleration steps by `v²·Δκ`.
    ///
    /// # Errors
    /// - [`Error::AxisMismatch`] when `A` is not the curve's point dimension;
    /// - [`Error::EmptyPath`] for a curve of zero length;
    /// - [`Error::InvalidRate`] for a rate outside 100 Hz ..= 100 kHz;
    /// - [`Error::InvalidLimit`] for another option out of range (see [`PlanOptions`]);
    /// - [`Error::TooLong`] when the motion takes more ticks at the plan's rate than a `u32`
    ///   counts (limits so small that the duration is huge or infinite);
    /// - [`Error::ZoneCapacityExceeded`] when the speed limit needs more than `Z` zones
    ///   (`required` is the number of zones needed; raise `Z` or the zone tolerance);
    /// - [`Error::Curve`] when the arc-length table fails or a derivative is not finite.
    ///
    /// ```
    /// use strak_curves::Bezier;
    /// use strak_trajectory::{Error, Limits, PathTiming, PlanOptions, ProfileShape, Timing};
    /// let line = Bezier::new([[0.0, 0.0], [30.0, 40.0]])?; // length 50
    /// let limits = Limits::<2>::new(10.0, 20.0, 1000.0)?.with_axis_velocity([3.0, 100.0])?;
    /// let options = PlanOptions::new().with_shape(ProfileShape::Trapezoid);
    /// let t = PathTiming::<_, 16, 4>::plan(&line, &limits, &options)?;
    /// // |T_x| = 0.6: the x axis limits the speed to 3/0.6 = 5; ¾ of a = 20 is planned
    /// assert!((t.motion().zones()[0].v_limit() - 5.0).abs() < 1e-12);
    /// assert!((t.duration() - (50.0 / 5.0 + 5.0 / 15.0)).abs() < 1e-9);
    /// let wrong = Limits::<3>::new(10.0, 20.0, 1000.0)?;
    /// assert!(matches!(
    ///     PathTiming::<_, 16, 4>::scurve(&line, &wrong),
    ///     Err(Error::AxisMismatch { curve: 2, path: 3 })
    /// ));
    /// let slow = Limits::<2>::new(1e-300, 20.0, 1000.0)?;
    /// assert!(matches!(PathTiming::<_, 16, 4>::scurve(&line, &slow), Err(Error::TooLong)));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn plan<const A: usize>(
        curve: &'a C,
        limits: &Limits<A>,
        options: &PlanOptions,
    ) -> Result<Self, Error> {
        let mut timing = Self::empty(curve);
        timing.plan_into(limits, options)?;
        Ok(timing)
    }

    /// A plan along `curve` without motion (zero length and duration): storage that
    /// [`plan_into`](Self::plan_into) fills in place, for example a `static` on a device
    /// (with a `'static` curve).
    ///
    /// ```
    /// use strak_curves::Bezier;
    /// use strak_trajectory::{PathTiming, Timing};
    /// let line = Bezier::new([[0.0, 0.0], [3.0, 4.0]])?;
    /// let empty = PathTiming::<_, 16, 4>::empty(&line);
    /// assert_eq!((empty.duration(), empty.length()), (0.0, 0.0));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub const fn empty(curve: &'a C) -> Self {
        PathTiming {
            curve,
            table: ArcLengthTable::EMPTY,
            motion: MotionProfile::EMPTY,
            rate: PlanOptions::DEFAULT_RATE,
            feed: None,
            limits: None,
        }
    }

    /// [`plan`](Self::plan) along this plan's curve, in place: the arc-length table and the
    /// zones are written where this value lies, so that planning needs no stack frame the
    /// size of the plan (the largest frames hold one zone or one sample of the speed
    /// limit). On an error the plan is left [`empty`](Self::empty).
    ///
    /// # Errors
    /// As [`plan`](Self::plan).
    ///
    /// ```
    /// use strak_curves::Bezier;
    /// use strak_trajectory::{Limits, PathTiming, PlanOptions, Timing};
    /// let line = Bezier::new([[0.0, 0.0], [30.0, 40.0]])?; // length 50
    /// let limits = Limits::<2>::new(10.0, 20.0, 1000.0)?;
    /// let mut timing = PathTiming::<_, 16, 4>::empty(&line);
    /// timing.plan_into(&limits, &PlanOptions::new())?;
    /// assert!((timing.length() - 50.0).abs() < 1e-9 && timing.duration() > 5.0);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn plan_into<const A: usize>(
        &mut self,
        limits: &Limits<A>,
        options: &PlanOptions,
    ) -> Result<(), Error> {
        self.in_place(|t| t.plan_in_place(limits, options))
    }

    /// The body of [`plan_into`](Self::plan_into).
    fn plan_in_place<const A: usize>(
        &mut self,
        limits: &Limits<A>,
        options: &PlanOptions,
    ) -> Result<(), Error> {
        let curve = self.curve;
        let dim = <C::Point as Point>::DIM;
        if dim != A {
            return Err(Error::AxisMismatch {
                curve: dim,
                path: A,
            });
        }
        options.validate()?;
        arc_table_into(curve, &mut self.table)?;
        plan_motion_into(curve, &self.table, limits, options, &mut self.motion)?;
        self.limits = Some(options.promised(limits));
        self.rate = options.rate();
        let mut axis_acceleration = [f64::INFINITY; MAX_DIM];
        for (r, a) in axis_acceleration.iter_mut().zip(limits.axis_acceleration()) {
            *r = a;
        }
        self.feed = Some(FeedReserve {
            acceleration: limits.acceleration(),
            jerk: limits.jerk(),
            axis_acceleration,
            share: options.feed_share(),
        });
        Ok(())
    }

    /// The control rate in Hz the motion was planned for ([`PlanOptions::with_rate`];
    /// 1 kHz for [`constant_speed`](Self::constant_speed) and [`trapezoid`](Self::trapezoid)).
    pub fn rate(&self) -> f64 {
        self.rate
    }

    /// The curve.
    pub fn curve(&self) -> &'a C {
        self.curve
    }

    /// The arc-length table (in `f64`).
    pub fn table(&self) -> &ArcLengthTable<f64, N> {
        &self.table
    }

    /// The motion along the arc length, `s(t)`.
    pub fn motion(&self) -> &MotionProfile<Z> {
        &self.motion
    }

    /// The arc length `L` of the curve.
    pub fn length(&self) -> f64 {
        self.table.length()
    }
}

impl<C: ParamCurveDeriv, const N: usize, const Z: usize> Timing for PathTiming<'_, C, N, Z> {
    fn duration(&self) -> f64 {
        self.motion.duration()
    }

    /// `u = u(s(t))`, the root of the table's interpolant `s(u) = s(t)` (a safeguarded
    /// secant iteration from the table's inverse, accurate where the curve's speed
    /// vanishes), `du/dt = ṡ/|c'(u)|` (0 where `|c'(u)| = 0`); `t` is clamped to
    /// `[0, duration]`, and the domain ends are returned exactly at the ends. Bounded
    /// iterations only; no panic path.
    fn param(&self, t: f64) -> (f64, f64) {
        let st = self.motion.state(t);
        let (u, speed) = param_at_length(self.curve, &self.table, st.s);
        let rate = st.v / speed;
        if speed > 0.0 && rate.is_finite() {
            (u, rate)
        } else {
            (u, 0.0)
        }
    }

    /// `ü = (s̈ − σ′·u̇²)/σ` with `σ = |c'(u)|` and `σ′ = c'·c''/σ` (from `u̇ = ṡ/σ`); 0
    /// where `|c'(u)| = 0`.
    fn param_acceleration(&self, t: f64) -> f64 {
        let st = self.motion.state(t);
        let (u, speed) = param_at_length(self.curve, &self.table, st.s);
        let rate = st.v / speed;
        if !(speed > 0.0 && rate.is_finite()) {
            return 0.0;
        }
        let us = to_param(self.curve, u);
        let (d1, d2) = (self.curve.deriv(us, 1), self.curve.deriv(us, 2));
        let dot: f64 = (0..<C::Point as Point>::DIM)
            .map(|i| d1.coord(i).to_f64() * d2.coord(i).to_f64())
            .sum();
        let accel = (st.a - dot / speed * rate * rate) / speed;
        if accel.is_finite() { accel } else { 0.0 }
    }

    /// The planned laws ([`plan`](Self::plan), [`scurve`](Self::scurve)) promise the path
    /// and per-axis limits they were planned with, less the feed reserve (the jerk only for
    /// the S-curve); [`trapezoid`](Self::trapezoid) the speed and the tangential
    /// acceleration; [`constant_speed`](Self::constant_speed) nothing.
    fn limits(&self) -> Option<MotionLimits> {
        self.limits
    }

    /// The planned laws ([`plan`](Self::plan), [`scurve`](Self::scurve)) leave their
    /// [`PlanOptions::feed_share`] of the machine's [`Limits`] free; the others reserve
    /// nothing.
    fn feed_reserve(&self) -> Option<FeedReserve> {
        self.feed
    }

    /// The phase boundaries of the motion profile where its jerk `s⃛` jumps and its
    /// acceleration is continuous (the S-curve's; zone boundaries included), strictly inside
    /// `(0, duration)`. The trapezoid's acceleration steps are left out: a C² spline with a
    /// knot near an acceleration step rings (measured: the axis acceleration 1.38 × the plan
    /// on the pick-and-place path instead of 1.12 × without the knots).
    fn breaks(&self, out: &mut dyn FnMut(f64)) {
        let duration = self.motion.duration();
        let end_acc = |p: &Phase| p.state_at(p.end()).a;
        // The acceleration scale: steps below 10⁻³ of it are rounding, not steps.
        let scale = self
            .motion
            .phases()
            .fold(0.0_f64, |m, p| m.max(p.a0.abs()).max(end_acc(p).abs()));
        let mut prev: Option<&Phase> = None;
        for phase in self.motion.phases() {
            if let Some(p) = prev {
                let continuous = (end_acc(p) - phase.a0).abs() <= 1e-3 * scale;
                if continuous && p.j != phase.j && phase.t0 > 0.0 && phase.t0 < duration {
                    out(phase.t0);
                }
            }
            prev = Some(phase);
        }
    }
}

/// A planned law holds its curve: it is the whole trajectory.
impl<C: ParamCurveDeriv, const N: usize, const Z: usize> Trajectory for PathTiming<'_, C, N, Z> {
    type Curve = C;
    type Law = Self;

    fn curve(&self) -> &C {
        self.curve
    }

    fn law(&self) -> &Self {
        self
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use strak_curves::{Bezier, I16F16, MAX_DIM};

    /// `x(t) = c(u(t))` in f64.
    fn pos<C: ParamCurveDeriv, T: Timing>(c: &C, timing: &T, t: f64) -> [f64; MAX_DIM] {
        c.eval(to_param(c, timing.param(t).0)).to_f64_array()
    }

    fn dist(a: [f64; MAX_DIM], b: [f64; MAX_DIM]) -> f64 {
        a.iter()
            .zip(b.iter())
            .map(|(x, y)| (x - y) * (x - y))
            .sum::<f64>()
            .sqrt()
    }

    #[test]
    fn constant_speed_is_constant() {
        // A quadratic with strongly uneven parametric speed.
        let c = Bezier::new([[0.0, 0.0], [1.0, 8.0], [10.0, 0.0]]).unwrap();
        let timing = PathTiming::<_, 128, 1>::constant_speed(&c, 3.0).unwrap();
        let err = timing.table().error_estimate();
        let d = timing.duration();
        assert!((d - timing.length() / 3.0).abs() < 1e-12);
        let h = 1e-4;
        let mut worst = 0.0_f64;
        for k in 1..200 {
            let t = d * k as f64 / 200.0;
            // finite-difference speed of the composed motion
            let fd = dist(pos(&c, &timing, t + h), pos(&c, &timing, t - h)) / (2.0 * h);
            worst = worst.max((fd - 3.0).abs());
            // and the analytic one: |c'(u)| du/dt
            let (u, du) = timing.param(t);
            let sp = norm64(&c.deriv(u, 1));
            assert!((sp * du - 3.0).abs() < 1e-12);
        }
        std::println!("constant speed 3: worst |dx/dt| error {worst:e}, table error {err:e}");
        assert!(worst < 1e-5, "worst speed error {worst}, table error {err}");
        // ends exactly
        assert_eq!(timing.param(0.0).0, 0.0);
        assert_eq!(timing.param(d).0, 1.0);
    }

    #[test]
    fn fixed_point_curve_plans_in_f64() {
        let p = |x: f64, y: f64| [I16F16::from_num(x), I16F16::from_num(y)];
        let c = Bezier::new([p(0.0, 0.0), p(300.0, 400.0)]).unwrap();
        let timing = PathTiming::<_, 16, 1>::trapezoid(&c, 100.0, 1000.0).unwrap();
        assert!((timing.length() - 500.0).abs() < 1e-6);
        assert!((timing.duration() - (5.0 + 0.1)).abs() < 1e-6);
        let (u, du) = timing.param(2.55);
        assert!((u - 0.5).abs() < 1e-4);
        assert!((du - 100.0 / 500.0).abs() < 1e-4);
    }

    #[test]
    fn breaks_are_the_scurves_jerk_steps() {
        let line = Bezier::new([[0.0_f64, 0.0], [30.0, 40.0]]).unwrap();
        let breaks = |t: &dyn Timing| {
            let mut v = std::vec::Vec::new();
            t.breaks(&mut |b| v.push(b));
            v
        };
        // 50 mm at 10 mm/s, 20 mm/s², 400 mm/s³: seven phases, six inner boundaries
        let limits = Limits::<2>::new(10.0, 20.0, 400.0).unwrap();
        let plan = PathTiming::<_, 32, 2>::scurve(&line, &limits).unwrap();
        let want: std::vec::Vec<f64> = plan.motion().phases().skip(1).map(|p| p.t0).collect();
        assert_eq!(want.len(), 6);
        let got = breaks(&plan);
        assert_eq!(got, want);
        // planned with ¾ of a and j (the feed reserve): a = 15, j = 300,
        // t_j = a/j = 0.05 s, t_a = v/a − a/j = 0.6167 s
        assert!(
            (got[0] - 0.05).abs() < 1e-12 && (got[1] - 10.0 / 15.0).abs() < 1e-12,
            "{got:?}"
        );
        // the trapezoid's steps are in the acceleration: not reported
        let plan = PathTiming::<_, 32, 2>::trapezoid(&line, 10.0, 20.0).unwrap();
        assert!(breaks(&plan).is_empty());
        // constant speed: smooth
        let plan = PathTiming::<_, 32, 2>::constant_speed(&line, 10.0).unwrap();
        assert!(breaks(&plan).is_empty());
    }

    #[test]
    fn errors() {
        let c = Bezier::new([[0.0, 0.0], [3.0, 4.0]]).unwrap();
        let still = Bezier::new([[2.0, 2.0], [2.0, 2.0], [2.0, 2.0]]).unwrap();
        assert!(matches!(
            PathTiming::<_, 8, 1>::constant_speed(&still, 1.0),
            Err(Error::EmptyPath)
        ));
        assert!(matches!(
            PathTiming::<_, 8, 1>::trapezoid(&still, 1.0, 1.0),
            Err(Error::EmptyPath)
        ));
        assert!(matches!(
            PathTiming::<_, 8, 1>::constant_speed(&c, -1.0),
            Err(Error::InvalidLimit)
        ));
        assert!(matches!(
            PathTiming::<_, 8, 1>::trapezoid(&c, 1.0, 0.0),
            Err(Error::InvalidLimit)
        ));
        assert!(matches!(
            PathTiming::<_, 1, 1>::constant_speed(&c, 1.0),
            Err(Error::Curve(strak_curves::Error::InvalidArgument))
        ));
        assert!(matches!(
            PathTiming::<_, 8, 0>::constant_speed(&c, 1.0),
            Err(Error::ZoneCapacityExceeded {
                capacity: 0,
                required: 1
            })
        ));
        let bad = Bezier::new([[0.0, 0.0], [f64::MAX, 0.0], [-f64::MAX, 0.0]]);
        if let Ok(bad) = bad {
            assert!(PathTiming::<_, 8, 1>::constant_speed(&bad, 1.0).is_err());
        }
    }
}
