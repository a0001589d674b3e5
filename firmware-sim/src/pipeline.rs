//! The pipeline `strak-sim run` and `strak-sim compile` share: build the curve, plan the time
//! law, compile the path.
//!
//! 1. **Curve.** The `[path]` is built in the job's number format (`f64`, `f32`, or `I32F32`
//!    for `fixed`): the curve firmware would hold. In `fixed`, every point must lie within the
//!    Q40 playback range first ([`check_playback_range`]).
//! 2. **Time law** (`[profile]`), planned in `f64` from that curve: `parameter`
//!    ([`ParameterTiming::over`]), `constant-speed` ([`PathTiming::constant_speed`]),
//!    `trapezoid` and `s-curve` ([`PathTiming::plan`] with [`ProfileShape::Trapezoid`] /
//!    [`ProfileShape::SCurve`]: curvature and per-axis limits included), at the job's rate
//!    and with the **feed share** `s` (`[compile] feed_share`, default 0) reserved by the
//!    planner ([`PlanOptions::with_feed_share`]: it plans with `(1 − s)·a`, `(1 − s)·j`,
//!    `(1 − s)·aᵢ`); the velocity limits (path and per axis) are reduced by
//!    [`VELOCITY_RESERVE`] for the compiled spline's fit error. The compiler is given `a`,
//!    `j` and `aᵢ` as the limits of feed changes and checks that the plan left `s` of each
//!    free, so a feed ramp adds to the path and to each axis only what the plan left free.
//!    Without a share (the default) the motion uses the full limits and the feed events are
//!    scheduled by the feed guard ([`crate::schedule`]).
//! 3. **Compile** ([`compile_into`]) into a [`Path`] of at most [`PIECES`] pieces, in the
//!    playback format (`f64`, `f32`, [`Q40`]).
//!
//! # Stack
//! The plan and the path live on the heap and are filled in place: the plan
//! ([`PathTiming::empty`], then [`PathTiming::plan_into`]) and the path ([`Path::new`], then
//! [`compile_into`]) are boxed empty and written where they lie; neither is returned by
//! value, and planning and compiling need small fixed frames. A path of 6 axes in `f64` holds
//! about 7 MB, more than a thread's default stack (2 MiB): it is never built on the stack
//! first because an empty path is its header followed by unwritten storage, which an
//! optimized build allocates and writes in place (strak-sim's own debug builds are optimized
//! for that reason: see the workspace's `Cargo.toml`). What the stack holds at most is the
//! curve being built ([`build_dyn`]: a curve's constructor returns it by value, up to about
//! 0.5 MB at 4 096 points and 6 axes, with its own work arrays).
//!
//! Every error is a [`JobError`] on the field that causes it.

use std::time::{Duration, Instant};

use strak_curves::{MAX_DIM, ParamCurveDeriv, Scalar};
use strak_trajectory::{
    Along, CompileOptions, Error as TrajError, Limits, Number, ParameterTiming, Path, PathTiming,
    PlanOptions, ProfileShape, Q40, Timing, compile_into,
};

use crate::dyn_curve::{DynCurve, build_dyn};
use crate::job::{Job, JobError, JobLimits, Profile, ProfileKind};
use crate::number::{self, NumberFormat};
use crate::summary::num;

/// Piece capacity of a compiled path (a path of `A` axes in `f64` takes about
/// `PIECES · (8 + 72·A)` bytes).
pub const PIECES: usize = 16_384;
/// Zone capacity of a planned motion, trapezoid or S-curve (the planner's default 1024
/// sampling intervals never need more; the constant-speed law has one zone).
pub const ZONES: usize = 1_024;
/// Samples of the arc-length table of a curve of at most `TABLE / 2` pieces (the QEMU
/// firmware plans its jobs on the device with the same table, so that its paths are the
/// host's bit for bit).
pub const TABLE: usize = 1_024;
/// Samples of the arc-length table of a curve of more pieces: two per piece of the largest
/// curve (4 096 points). With [`TABLE`] the compiled 6-axis path of a 4 096-point B-spline
/// exceeds its jerk limit beyond the compiler's slow-down (`LimitExceeded`).
pub const LARGE_TABLE: usize = 8_192;
/// The share of the velocity limits (path and per axis) a planned motion leaves unused:
/// the compiled spline follows the planned velocity to about 10⁻³ of it, so a plan at the
/// full limit would overshoot it.
pub const VELOCITY_RESERVE: f64 = 0.005;

/// The job's per-axis limits as an array (`inf` where none is given).
pub fn axis_array<const D: usize>(v: Option<&[f64]>) -> [f64; D] {
    let mut out = [f64::INFINITY; D];
    if let Some(v) = v {
        for (o, x) in out.iter_mut().zip(v) {
            *o = *x;
        }
    }
    out
}

/// The limits the time law is planned with: the job's, with velocities scaled by
/// `1 − VELOCITY_RESERVE` (the planner itself reserves the feed share of the acceleration and
/// jerk: [`plan_options`]).
///
/// # Errors
/// A [`JobError`] on `limits` for a limit the trajectory layer rejects.
pub fn planning_limits<const D: usize>(job: &Job) -> Result<Limits<D>, JobError> {
    job_limits(job, 1.0 - VELOCITY_RESERVE)
}

/// The job's limits (path and per axis), with the velocities times `v_keep`.
///
/// # Errors
/// A [`JobError`] on `limits` for a limit the trajectory layer rejects.
pub fn job_limits<const D: usize>(job: &Job, v_keep: f64) -> Result<Limits<D>, JobError> {
    limits_of(&job.limits, v_keep)
}

/// The limits `l` (path and per axis), with the velocities times `v_keep`.
///
/// # Errors
/// A [`JobError`] on `limits` for a limit the trajectory layer rejects.
pub fn limits_of<const D: usize>(l: &JobLimits, v_keep: f64) -> Result<Limits<D>, JobError> {
    let bad = |field: &'static str| move |e: TrajError| JobError::new(field, e.to_string());
    Limits::<D>::new(l.velocity * v_keep, l.acceleration, l.jerk)
        .map_err(bad("limits"))?
        .with_axis_velocity(axis_array::<D>(l.axis_velocity.as_deref()).map(|v| v * v_keep))
        .map_err(bad("limits.axis_velocity"))?
        .with_axis_acceleration(axis_array::<D>(l.axis_acceleration.as_deref()))
        .map_err(bad("limits.axis_acceleration"))
}

/// The compiler settings of the job: `[compile]`, and the machine's limits for feed
/// changes (`a`, `j`, `aᵢ`).
pub fn compile_options(job: &Job) -> CompileOptions {
    let l = &job.limits;
    let mut axis_acceleration = [f64::INFINITY; MAX_DIM];
    for (o, a) in axis_acceleration
        .iter_mut()
        .zip(l.axis_acceleration.iter().flatten())
    {
        *o = *a;
    }
    let mut o = CompileOptions::new()
        .with_feed_share(job.feed_share())
        .with_limits(l.acceleration, l.jerk)
        .with_axis_acceleration(axis_acceleration);
    if let Some(t) = job.compile.tolerance {
        o = o.with_tolerance(t);
    }
    if let Some(m) = job.compile.max_piece_ticks {
        o = o.with_max_piece_ticks(m);
    }
    o
}

/// The planner settings of a trapezoid or S-curve profile: the job's rate and feed share,
/// and `[profile]` (the defaults for the others).
pub fn plan_options(job: &Job) -> PlanOptions {
    let mut o = PlanOptions::new()
        .with_shape(match job.profile {
            Profile::Trapezoid(_) => ProfileShape::Trapezoid,
            _ => ProfileShape::SCurve,
        })
        .with_rate(job.rate_hz)
        .with_feed_share(job.feed_share());
    let Some(p) = job.profile.planner() else {
        return o;
    };
    if let Some(n) = p.samples {
        o = o.with_samples(n);
    }
    if let Some(t) = p.zone_tolerance {
        o = o.with_zone_tolerance(t);
    }
    if let Some(s) = p.centripetal_share {
        o = o.with_centripetal_share(s);
    }
    if let Some(a) = p.corner_angle {
        o = o.with_corner_angle(a);
    }
    o
}

/// The time law of `job` along `curve` (built in the job's number format), planned with
/// `limits` ([`planning_limits`]).
///
/// # Errors
/// A [`JobError`] naming the field for a profile that cannot be planned.
pub fn plan_timing<'c, S: Scalar, const D: usize>(
    job: &Job,
    curve: &'c DynCurve<S, D>,
    limits: &Limits<D>,
) -> Result<Box<dyn Timing + 'c>, JobError> {
    let err = |e| plan_error(job, e);
    match &job.profile {
        Profile::Parameter(p) => Ok(Box::new(
            ParameterTiming::over(curve, p.duration).map_err(err)?,
        )),
        Profile::ConstantSpeed(c) => {
            constant_speed(curve, c.speed.unwrap_or(job.limits.velocity)).map_err(err)
        }
        Profile::Trapezoid(_) | Profile::SCurve(_) => {
            planned(curve, limits, &plan_options(job)).map_err(err)
        }
    }
}

/// Whether `curve` takes the [`LARGE_TABLE`].
fn large<C: ParamCurveDeriv>(curve: &C) -> bool {
    curve.piece_count() > TABLE / 2
}

/// The constant-speed law (one zone), built in place into a boxed empty plan.
fn constant_speed<S: Scalar, const D: usize>(
    curve: &DynCurve<S, D>,
    speed: f64,
) -> Result<Box<dyn Timing + '_>, TrajError> {
    if large(curve) {
        boxed_law::<_, LARGE_TABLE, 1>(curve, |p| p.constant_speed_into(speed))
    } else {
        boxed_law::<_, TABLE, 1>(curve, |p| p.constant_speed_into(speed))
    }
}

/// A trapezoid or S-curve, planned in place into a boxed empty plan.
fn planned<'c, S: Scalar, const D: usize>(
    curve: &'c DynCurve<S, D>,
    limits: &Limits<D>,
    options: &PlanOptions,
) -> Result<Box<dyn Timing + 'c>, TrajError> {
    if large(curve) {
        boxed_law::<_, LARGE_TABLE, ZONES>(curve, |p| p.plan_into(limits, options))
    } else {
        boxed_law::<_, TABLE, ZONES>(curve, |p| p.plan_into(limits, options))
    }
}

/// A boxed empty plan of `T` samples and `Z` zones, filled in place by `build`. Not
/// inlined, so that the empty plan this frame may hold while it is moved to the heap is not
/// part of the caller's.
#[inline(never)]
fn boxed_law<'c, C: ParamCurveDeriv, const T: usize, const Z: usize>(
    curve: &'c C,
    build: impl FnOnce(&mut PathTiming<'c, C, T, Z>) -> Result<(), TrajError>,
) -> Result<Box<dyn Timing + 'c>, TrajError> {
    let mut plan = boxed_plan::<_, T, Z>(curve);
    build(&mut plan)?;
    Ok(plan)
}

/// A curve file error as an error on the job's `path.…` field.
pub fn curve_error(e: crate::curve_file::FieldError) -> JobError {
    JobError::new(
        format!("path.{}", e.field),
        e.message.replace("--number ", "number = "),
    )
}

fn plan_error(job: &Job, e: TrajError) -> JobError {
    match e {
        TrajError::EmptyPath => JobError::new(
            "path",
            "the path has zero length (its points coincide): there is nothing to play",
        ),
        TrajError::ZoneCapacityExceeded { capacity, required } => JobError::new(
            "profile.zone_tolerance",
            format!(
                "the speed limit along the path needs {required} zones, the simulator plans \
                 with at most {capacity} zones: raise profile.zone_tolerance or lower \
                 profile.samples"
            ),
        ),
        TrajError::InvalidLimit => JobError::new(
            "profile",
            format!(
                "the `{}` profile rejected a setting: {e}",
                job.profile.kind().name()
            ),
        ),
        TrajError::Curve(c) => JobError::new(
            "path",
            format!("the curve cannot be planned along (arc length or derivatives): {c}"),
        ),
        other => JobError::new("profile", other.to_string()),
    }
}

/// The largest coordinate of the path's points.
fn max_abs(job: &Job) -> f64 {
    job.path
        .points()
        .iter()
        .flatten()
        .fold(0.0_f64, |m, x| m.max(x.abs()))
}

/// In `fixed`, every point within the range of Q40 playback, `±`[`Q40`]`::LIMIT` (2²²):
/// the error names the first coordinate outside it (`path.points[3][1]`). Points within the
/// range keep a B-spline, Bézier or NURBS curve inside it (the convex hull); an interpolating
/// curve may still overshoot between its points ([`compile_error()`]).
///
/// # Errors
/// A [`JobError`] on the coordinate.
pub fn check_playback_range(job: &Job) -> Result<(), JobError> {
    if job.number != NumberFormat::Q40 {
        return Ok(());
    }
    let limit = <Q40 as Number>::LIMIT;
    for (i, p) in job.path.points().iter().enumerate() {
        if let Some(j) = p.iter().position(|x| x.abs() > limit) {
            return Err(JobError::new(
                format!("path.points[{i}][{j}]"),
                format!(
                    "{} is outside the range of number = \"fixed\": Q40 playback holds \
                     positions, velocities and accelerations within ±{} units (2²²); move or \
                     scale the path, or use number = \"f64\"",
                    num(p[j]),
                    num(limit)
                ),
            ));
        }
    }
    Ok(())
}

/// A compile error as an error on the job field that causes it.
pub fn compile_error(job: &Job, e: TrajError, duration: f64) -> JobError {
    let rate = job.rate_hz;
    match e {
        TrajError::InvalidRate => JobError::new("rate_hz", e.to_string()),
        TrajError::TooLong => JobError::new(
            "rate_hz",
            format!("the motion ({duration} s at {rate} Hz) takes more ticks than a u32 counts"),
        ),
        TrajError::EmptyPath => JobError::new("path", "the motion has zero duration"),
        TrajError::CapacityExceeded { capacity, required } => {
            capacity_error(job, capacity, required, duration)
        }
        TrajError::OutOfRange => JobError::new(
            "number",
            format!(
                "the compiled path does not fit `{}` playback ({}; the path's points reach {}, \
                 the curve between them goes further): move or scale the path, or use number \
                 = \"f64\"",
                number::name(job.number),
                match job.number {
                    NumberFormat::Q40 => format!(
                        "Q40 keeps every position, velocity and acceleration within ±{} units",
                        num(<Q40 as Number>::LIMIT)
                    ),
                    _ => "a value exceeds the format's range".to_owned(),
                },
                num(max_abs(job))
            ),
        ),
        TrajError::InvalidLimit => JobError::new("compile", e.to_string()),
        TrajError::Curve(c) => JobError::new("path", format!("compiling the curve failed: {c}")),
        other => JobError::new("path", other.to_string()),
    }
}

/// More pieces than a path holds: from the motion's length (`rate_hz`) or the tolerance.
fn capacity_error(job: &Job, capacity: usize, required: usize, duration: f64) -> JobError {
    let rate = job.rate_hz;
    let per_piece = f64::from(
        job.compile
            .max_piece_ticks
            .unwrap_or(CompileOptions::DEFAULT_MAX_PIECE_TICKS),
    );
    let at_least = (duration * rate / per_piece).ceil();
    if at_least > capacity as f64 {
        JobError::new(
            "rate_hz",
            format!(
                "the motion ({} s at {} Hz, pieces of at most {per_piece} ticks) needs at least \
                 {required} pieces, the simulator's paths hold {capacity} pieces: lower \
                 rate_hz, raise compile.max_piece_ticks or split the path",
                num(duration),
                num(rate)
            ),
        )
    } else {
        JobError::new(
            "compile.tolerance",
            format!(
                "the compiled path needs at least {required} pieces to meet the tolerance, the \
                 simulator's paths hold {capacity} pieces: raise compile.tolerance"
            ),
        )
    }
}

/// The curve of a job in its number format and the limits it is planned with.
pub struct Prepared<S: Scalar, const D: usize> {
    /// The curve in the job's number format.
    pub curve: DynCurve<S, D>,
    /// The planning limits ([`planning_limits`]).
    pub limits: Limits<D>,
}

impl<S: Scalar, const D: usize> std::fmt::Debug for Prepared<S, D> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Prepared")
            .field("curve", &self.curve)
            .field("limits", &self.limits)
            .finish()
    }
}

/// A job planned and compiled.
pub struct Compiled<'c, N: Number, const D: usize> {
    /// The time law.
    pub timing: Box<dyn Timing + 'c>,
    /// The compiled path.
    pub path: Box<Path<N, D, PIECES>>,
    /// The wall-clock time of planning.
    pub plan_time: Duration,
    /// The wall-clock time of compiling.
    pub compile_time: Duration,
}

impl<N: Number, const D: usize> std::fmt::Debug for Compiled<'_, N, D> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Compiled")
            .field("duration", &self.timing.duration())
            .field("pieces", &self.path.pieces().len())
            .field("ticks", &self.path.ticks())
            .finish()
    }
}

impl<S: Scalar, const D: usize> Prepared<S, D> {
    /// Checks the range, builds the curve of `job` in its number format (whose scalar must be
    /// `S`, with `D` axes) and the planning limits.
    ///
    /// # Errors
    /// A [`JobError`] naming the field.
    pub fn new(job: &Job) -> Result<Self, JobError> {
        check_playback_range(job)?;
        let curve = build_dyn(&job.path, job.number).map_err(curve_error)?;
        let limits = planning_limits::<D>(job)?;
        Ok(Prepared { curve, limits })
    }

    /// Plans the time law and compiles the path in the playback format `N`.
    ///
    /// # Errors
    /// A [`JobError`] naming the field for a job that cannot be planned or compiled.
    pub fn compile<N: Number>(&self, job: &Job) -> Result<Compiled<'_, N, D>, JobError> {
        let started = Instant::now();
        let timing = plan_timing(job, &self.curve, &self.limits)?;
        let plan_time = started.elapsed();
        let mut path = boxed_path::<N, D>();
        compile_into(
            &Along::new(&self.curve, &*timing),
            job.rate_hz,
            &compile_options(job),
            &mut path,
        )
        .map_err(|e| compile_error(job, e, timing.duration()))?;
        Ok(Compiled {
            timing,
            path,
            plan_time,
            compile_time: started.elapsed() - plan_time,
        })
    }
}

/// An empty path of [`PIECES`] pieces on the heap, for [`compile_into`] or
/// [`Path::read_bytes`]. An empty path is its header and length followed by unwritten
/// storage; in this small function of its own an optimized build allocates and writes only
/// those, so that the path (about 7 MB for 6 axes in `f64`) never lies on the stack. Not
/// inlined: inside a larger caller the optimizer may build the value on the stack first.
#[inline(never)]
pub fn boxed_path<N: Number, const D: usize>() -> Box<Path<N, D, PIECES>> {
    Box::new(Path::new())
}

/// An empty plan of `T` samples ([`TABLE`] or [`LARGE_TABLE`]) and `Z` zones ([`ZONES`]
/// for the planned laws) along `curve` on the heap, for [`PathTiming::plan_into`] or
/// [`PathTiming::constant_speed_into`]: not inlined, as [`boxed_path`].
#[inline(never)]
pub fn boxed_plan<C: ParamCurveDeriv, const T: usize, const Z: usize>(
    curve: &C,
) -> Box<PathTiming<'_, C, T, Z>> {
    Box::new(PathTiming::empty(curve))
}

/// Whether the job's time law is planned under its limits.
pub fn is_planned(job: &Job) -> bool {
    ProfileKind::is_planned(job.profile.kind())
}

#[cfg(test)]
mod tests {
    use super::*;

    const JOB: &str = r#"
rate_hz = 1000
number = "fixed"
[path]
kind = "bezier"
points = [[0, 0], [10, 0], [10, 10]]
[limits]
velocity = 100
acceleration = 1000
jerk = 10000
[profile]
kind = "s-curve"
"#;

    #[test]
    fn a_point_outside_q40_is_named() {
        let job = Job::parse(&JOB.replace("[10, 0]", "[10, 4194305]")).unwrap();
        let e = check_playback_range(&job).unwrap_err();
        assert_eq!(e.field, "path.points[1][1]");
        assert!(
            e.message.contains("4194305") && e.message.contains("4194304"),
            "{e}"
        );
        let inside = Job::parse(&JOB.replace("[10, 0]", "[10, 4194304]")).unwrap();
        assert!(check_playback_range(&inside).is_ok());
        let f64_job = Job::parse(
            &JOB.replace("[10, 0]", "[10, 4194305]")
                .replace("\"fixed\"", "\"f64\""),
        )
        .unwrap();
        assert!(check_playback_range(&f64_job).is_ok());
    }

    #[test]
    fn planning_limits_keep_the_reserves() {
        let job = Job::parse(&JOB.replace(
            "jerk = 10000",
            "jerk = 10000\naxis_acceleration = [800, inf]",
        ))
        .unwrap();
        let l = planning_limits::<2>(&job).unwrap();
        // the planner reserves the feed share itself: none by default
        assert_eq!(l.acceleration(), 1000.0);
        assert_eq!(l.velocity(), 100.0 * (1.0 - VELOCITY_RESERVE));
        assert_eq!(l.axis_acceleration(), [800.0, f64::INFINITY]);
        let plan = plan_options(&job);
        assert_eq!((plan.feed_share(), plan.rate()), (0.0, job.rate_hz));
        let reserved = Job::parse(&format!("{JOB}\n[compile]\nfeed_share = 0.25\n")).unwrap();
        assert_eq!(plan_options(&reserved).feed_share(), 0.25);
        assert_eq!(compile_options(&reserved).feed_share(), 0.25);
        let compile = compile_options(&job);
        assert_eq!(compile.limits(), Some((1000.0, 10000.0)));
        assert_eq!(
            compile.axis_acceleration()[..3],
            [800.0, f64::INFINITY, f64::INFINITY]
        );
    }
}
