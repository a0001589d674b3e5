//! `strak-sim run`: plan, compile and play a job through the sampler firmware uses, and write
//! the samples, a summary and plots.
//!
//! # Pipeline
//! 1. **Curves.** The `[path]` is built in the job's number format (`f64`, `f32`, or `I32F32`
//!    for `fixed`) — the curve firmware would hold — and once more in `f64` as the reference.
//! 2. **Time law** (`[profile]`), planned in `f64` from the curve in the job's format:
//!    `parameter` ([`ParameterTiming::over`]), `constant-speed`
//!    ([`PathTiming::constant_speed`]), `trapezoid` and `s-curve` ([`PathTiming::plan`] with
//!    [`ProfileShape::Trapezoid`] / [`ProfileShape::SCurve`]: curvature and per-axis limits
//!    included). Trapezoid and S-curve are planned with the job's acceleration and jerk limits
//!    (path and per axis) **reduced by the feed share** `s` (`[compile] feed_share`, default
//!    ¼): `(1 − s)·a`, `(1 − s)·j`, `(1 − s)·aᵢ`; the velocity limits (path and per axis)
//!    are reduced by [`VELOCITY_RESERVE`] for the compiled spline's fit error. The compiler
//!    is given `min(a, aᵢ)` and `j` as the limits of feed changes, so a feed ramp adds at
//!    most `s·min(a, aᵢ)` (or what the plan left free) to the acceleration: the samples respect
//!    the job's acceleration limits, path and per axis, even while a feed ramp runs.
//! 3. **Compile** ([`compile`]) into a [`Path`] of at most [`PIECES`] pieces (boxed: a path is
//!    large), in the playback format (`f64`, `f32`, [`Q40`]).
//! 4. **Play** with [`Sampler`], one `next()` per control tick, applying the `[[events]]` before
//!    the sample of their tick, until the sampler is finished — or, guarding against a hold
//!    without resume, after `10·(ticks + 1) + last event tick + 1` samples.
//!
//! Everything runs on a thread with a [`STACK_BYTES`] stack (planning and compiling keep
//! their work arrays on the stack).

use std::fs::{self, File};
use std::io::{BufWriter, IsTerminal, Write};
use std::path::{Path as FsPath, PathBuf};
use std::time::Instant;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use strak_curves::{I32F32, ParamCurve, ParamCurveDeriv, Scalar, arc_length};
use strak_trajectory::{
    CompileOptions, Error as TrajError, Limits, Number, ParameterTiming, Path, PathTiming,
    PlanOptions, ProfileShape, Q40, Sampler, Timing, compile,
};

use crate::dyn_curve::{DynCurve, build_dyn};
use crate::job::{Action, Job, JobError, JobNumber, ProfileKind};
use crate::plot::{self, PlotLimits, Recorder};
use crate::sample::Number as CurveNumber;
use crate::summary::{
    AlongPath, Checked, EndPoint, Maxima, PlannedLimits, ReferenceDistance, Summary, WallTime,
};

/// Piece capacity of a compiled path (a path of `A` axes in `f64` takes about
/// `PIECES · (8 + 72·A)` bytes).
pub const PIECES: usize = 16_384;
/// Zone capacity of a planned motion (the planner's default 1024 sampling intervals never
/// need more).
pub const ZONES: usize = 1_024;
/// Samples of the arc-length table.
pub const TABLE: usize = 1_024;
/// The stack of the thread a job runs on.
pub const STACK_BYTES: usize = 256 << 20;
/// The share of the velocity limits (path and per axis) a planned motion leaves unused:
/// the compiled spline follows the planned velocity to about 10⁻³ of it (measured: 5·10⁻⁴
/// on a line cruising at an axis limit), so a plan at the full limit would overshoot it.
pub const VELOCITY_RESERVE: f64 = 0.005;
/// Runs expected to take at least this many samples show a progress bar (on a terminal).
pub const PROGRESS_MIN_SAMPLES: u64 = 200_000;

/// The bundled example: a 3-axis pick-and-place move at 1 kHz with an S-curve profile.
pub const BUNDLED_JOB: &str = include_str!("../examples/jobs/pick-and-place.toml");
/// The bundled example's name.
pub const BUNDLED_NAME: &str = "pick-and-place";

const AXIS_NAMES: [&str; 4] = ["x", "y", "z", "w"];

/// How the reference point of each sample is chosen (reported in the summary).
pub const REFERENCE_METHOD: &str =
    "f64 curve at the same planned parameter u(t) of the sample's playback point";

/// Where and how to run.
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// The output folder (created if missing).
    pub out_dir: PathBuf,
    /// The job's name for the summary and plot titles.
    pub name: String,
    /// Show a progress bar on long runs (only when standard error is a terminal).
    pub progress: bool,
}

/// Why a run failed.
#[derive(Debug)]
pub enum RunError {
    /// The job is bad (one field named).
    Job(JobError),
    /// Writing the output failed.
    Io(String),
}

impl std::fmt::Display for RunError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RunError::Job(e) => write!(f, "{e}"),
            RunError::Io(e) => f.write_str(e),
        }
    }
}

impl std::error::Error for RunError {}

impl From<JobError> for RunError {
    fn from(e: JobError) -> Self {
        RunError::Job(e)
    }
}

fn io_error(what: &FsPath) -> impl Fn(std::io::Error) -> RunError + '_ {
    move |e| RunError::Io(format!("cannot write {}: {e}", what.display()))
}

/// A sample value written to CSV with the shortest text that reads back to the same bits.
pub trait CsvCell: Scalar {
    /// Appends the value.
    fn write_cell(self, out: &mut String);
}

impl CsvCell for f64 {
    fn write_cell(self, out: &mut String) {
        use std::fmt::Write as _;
        let _ = write!(out, "{self:?}");
    }
}

impl CsvCell for f32 {
    fn write_cell(self, out: &mut String) {
        use std::fmt::Write as _;
        let _ = write!(out, "{self:?}");
    }
}

impl CsvCell for I32F32 {
    fn write_cell(self, out: &mut String) {
        use std::fmt::Write as _;
        // fixed's Display writes the shortest decimal that parses back to the same bits.
        let _ = write!(out, "{self}");
    }
}

/// The CSV header: `tick,t,x,y[,z…],vx,vy[,vz…],ax,ay[,az…]`.
pub fn csv_header(axes: usize) -> String {
    let names = &AXIS_NAMES[..axes.min(AXIS_NAMES.len())];
    let mut h = vec!["tick".to_owned(), "t".to_owned()];
    h.extend(names.iter().map(|n| (*n).to_owned()));
    h.extend(names.iter().map(|n| format!("v{n}")));
    h.extend(names.iter().map(|n| format!("a{n}")));
    h.join(",")
}

/// Runs `job`, writes `samples.csv`, `summary.json`, `path.svg` and `motion.svg` into
/// `options.out_dir` and returns the summary.
///
/// # Errors
/// [`RunError::Job`] naming the field for a job that cannot be planned or compiled;
/// [`RunError::Io`] when the output cannot be written.
pub fn run_job(job: &Job, options: &RunOptions) -> Result<Summary, RunError> {
    std::thread::scope(|scope| {
        std::thread::Builder::new()
            .name("strak-sim run".to_owned())
            .stack_size(STACK_BYTES)
            .spawn_scoped(scope, || dispatch(job, options))
            .map_err(|e| RunError::Io(format!("cannot start the run thread: {e}")))?
            .join()
            .map_err(|_| RunError::Io("the run thread panicked".to_owned()))?
    })
}

fn dispatch(job: &Job, options: &RunOptions) -> Result<Summary, RunError> {
    macro_rules! by_dim {
        ($n:ty, $s:ty) => {
            match job.axes() {
                1 => run_typed::<$n, $s, 1>(job, options),
                2 => run_typed::<$n, $s, 2>(job, options),
                3 => run_typed::<$n, $s, 3>(job, options),
                4 => run_typed::<$n, $s, 4>(job, options),
                d => Err(JobError::new(
                    "path.points",
                    format!("points need 1 to 4 coordinates, not {d}"),
                )
                .into()),
            }
        };
    }
    match job.number {
        JobNumber::F64 => by_dim!(f64, f64),
        JobNumber::F32 => by_dim!(f32, f32),
        JobNumber::Fixed => by_dim!(Q40, I32F32),
    }
}

/// Applies the events due before the sample of tick `tick` (`events` sorted by tick,
/// `next` the first not yet applied); `true` when one of them was an abort. The one place
/// that defines how `strak-sim run` (and the firmware comparison) apply `[[events]]`.
pub fn apply_due_events<N: Number, const D: usize>(
    sampler: &mut Sampler<'_, N, D>,
    events: &[(u64, Action)],
    next: &mut usize,
    tick: u64,
) -> bool {
    let mut aborted = false;
    while let Some(&(at, action)) = events.get(*next) {
        if at > tick {
            break;
        }
        match action {
            Action::Feed(f) => sampler.set_feed(f as f32),
            Action::Hold => sampler.hold(),
            Action::Resume => sampler.resume(),
            Action::Abort => {
                sampler.abort();
                aborted = true;
            }
        }
        *next += 1;
    }
    aborted
}

/// The job's per-axis limits as an array (`inf` where none is given).
fn axis_array<const D: usize>(v: Option<&[f64]>) -> [f64; D] {
    let mut out = [f64::INFINITY; D];
    if let Some(v) = v {
        for (o, x) in out.iter_mut().zip(v) {
            *o = *x;
        }
    }
    out
}

/// The limits the time law is planned with: the job's, with acceleration and jerk (path and
/// per axis) scaled by `1 − feed_share` and velocities by `1 − VELOCITY_RESERVE`.
///
/// # Errors
/// A [`JobError`] on `limits` for a limit the trajectory layer rejects.
pub fn planning_limits<const D: usize>(job: &Job) -> Result<Limits<D>, JobError> {
    let l = &job.limits;
    let keep = 1.0 - job.feed_share();
    let bad = |field: &str| {
        let field = field.to_owned();
        move |e: TrajError| JobError::new(field.clone(), e.to_string())
    };
    let v_keep = 1.0 - VELOCITY_RESERVE;
    Limits::<D>::new(l.velocity * v_keep, l.acceleration * keep, l.jerk * keep)
        .map_err(bad("limits"))?
        .with_axis_velocity(axis_array::<D>(l.axis_velocity.as_deref()).map(|v| v * v_keep))
        .map_err(bad("limits.axis_velocity"))?
        .with_axis_acceleration(axis_array::<D>(l.axis_acceleration.as_deref()).map(|a| a * keep))
        .map_err(bad("limits.axis_acceleration"))
}

/// The compiler settings of the job: `[compile]`, and the feed-change limits `min(a, aᵢ)`, `j`.
pub fn compile_options(job: &Job) -> CompileOptions {
    let l = &job.limits;
    let a_feed = l
        .axis_acceleration
        .iter()
        .flatten()
        .fold(l.acceleration, |m, a| m.min(*a));
    let mut o = CompileOptions::new()
        .with_feed_share(job.feed_share())
        .with_limits(a_feed, l.jerk);
    if let Some(t) = job.compile.tolerance {
        o = o.with_tolerance(t);
    }
    if let Some(m) = job.compile.max_piece_ticks {
        o = o.with_max_piece_ticks(m);
    }
    o
}

/// The planner settings of a trapezoid or S-curve profile.
pub fn plan_options(job: &Job) -> PlanOptions {
    let p = &job.profile;
    let mut o = PlanOptions::new().with_shape(if p.kind == ProfileKind::Trapezoid {
        ProfileShape::Trapezoid
    } else {
        ProfileShape::SCurve
    });
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
/// `limits` ([`planning_limits`]) as `strak-sim run` plans it.
///
/// # Errors
/// A [`JobError`] naming the field for a profile that cannot be planned.
pub fn plan_timing<'c, S: Scalar, const D: usize>(
    job: &Job,
    curve: &'c DynCurve<S, D>,
    limits: &Limits<D>,
) -> Result<Box<dyn Timing + 'c>, JobError> {
    Ok(match job.profile.kind {
        ProfileKind::Parameter => Box::new(
            ParameterTiming::over(curve, job.profile.duration.unwrap_or(1.0))
                .map_err(|e| plan_error(job, e))?,
        ),
        ProfileKind::ConstantSpeed => Box::new(
            PathTiming::<_, TABLE, ZONES>::constant_speed(
                curve,
                job.profile.speed.unwrap_or(job.limits.velocity),
            )
            .map_err(|e| plan_error(job, e))?,
        ),
        ProfileKind::Trapezoid | ProfileKind::SCurve => Box::new(
            PathTiming::<_, TABLE, ZONES>::plan(curve, limits, &plan_options(job))
                .map_err(|e| plan_error(job, e))?,
        ),
    })
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
        TrajError::CapacityExceeded { capacity, required } => JobError::new(
            "profile.zone_tolerance",
            format!(
                "the speed limit along the path needs {required} zones, the simulator holds \
                 {capacity}: raise profile.zone_tolerance or lower profile.samples"
            ),
        ),
        TrajError::InvalidLimit => JobError::new(
            "profile",
            format!(
                "the `{}` profile rejected a setting: {e}",
                job.profile.kind.name()
            ),
        ),
        TrajError::Curve(c) => JobError::new(
            "path",
            format!("the curve cannot be planned along (arc length or derivatives): {c}"),
        ),
        other => JobError::new("profile", other.to_string()),
    }
}

/// A compile error as an error on the job field that causes it (`max_abs`: the largest
/// coordinate of the path's points, for the fixed-point range message).
pub fn compile_error(job: &Job, e: TrajError, duration: f64, max_abs: f64) -> JobError {
    let rate = job.rate_hz;
    match e {
        TrajError::InvalidRate => JobError::new("rate_hz", e.to_string()),
        TrajError::TooLong => JobError::new(
            "rate_hz",
            format!("the motion ({duration} s at {rate} Hz) takes more ticks than a u32 counts"),
        ),
        TrajError::EmptyPath => JobError::new("path", "the motion has zero duration"),
        TrajError::CapacityExceeded { capacity, required } => {
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
                        "the motion ({} s at {} Hz, pieces of at most {per_piece} ticks) needs at \
                         least {required} pieces, the simulator holds {capacity}: lower rate_hz, \
                         raise compile.max_piece_ticks or split the path",
                        crate::summary::num(duration),
                        crate::summary::num(rate)
                    ),
                )
            } else {
                JobError::new(
                    "compile.tolerance",
                    format!(
                        "the compiled path needs at least {required} pieces to meet the \
                         tolerance, the simulator holds {capacity}: raise compile.tolerance"
                    ),
                )
            }
        }
        TrajError::OutOfRange => JobError::new(
            "number",
            format!(
                "the compiled path does not fit `{}` playback ({}; the path's coordinates reach \
                 {}): move or scale the path, or use number = \"f64\"",
                job.number.name(),
                match job.number {
                    JobNumber::Fixed => {
                        "Q40 keeps every position, velocity and acceleration within ±4194304 units"
                    }
                    _ => "a value exceeds the format's range",
                },
                crate::summary::num(max_abs)
            ),
        ),
        TrajError::InvalidLimit => JobError::new("compile", e.to_string()),
        TrajError::Curve(c) => JobError::new("path", format!("compiling the curve failed: {c}")),
        other => JobError::new("path", other.to_string()),
    }
}

/// `|a − b|` over the axes.
fn distance<const D: usize>(a: &[f64; D], b: &[f64; D]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Running maxima of one quantity: norm and per axis.
#[derive(Clone, Debug)]
struct Peak<const D: usize> {
    norm: (f64, f64),
    axes: [(f64, f64); D],
}

impl<const D: usize> Peak<D> {
    fn new() -> Self {
        Peak {
            norm: (0.0, 0.0),
            axes: [(0.0, 0.0); D],
        }
    }

    fn push(&mut self, t: f64, v: &[f64; D]) {
        let n = norm(v);
        if n > self.norm.0 {
            self.norm = (n, t);
        }
        for (p, x) in self.axes.iter_mut().zip(v) {
            if x.abs() > p.0 {
                *p = (x.abs(), t);
            }
        }
    }
}

fn out_f64<T: Scalar, const D: usize>(v: &[T; D]) -> [f64; D] {
    v.map(Scalar::to_f64)
}

#[allow(clippy::too_many_lines)]
fn run_typed<N, S, const D: usize>(job: &Job, options: &RunOptions) -> Result<Summary, RunError>
where
    N: Number,
    N::Out: CsvCell,
    S: Scalar,
{
    let started = Instant::now();
    let curve: DynCurve<S, D> =
        build_dyn(&job.path, job.number.curve_number()).map_err(curve_error)?;
    let reference: DynCurve<f64, D> =
        build_dyn(&job.path, CurveNumber::F64).map_err(curve_error)?;
    let limits = planning_limits::<D>(job)?;

    // The time law.
    let timing = plan_timing(job, &curve, &limits)?;
    let planned = started.elapsed();

    // Compile.
    let max_abs = job
        .path
        .points
        .iter()
        .flatten()
        .fold(0.0_f64, |m, x| m.max(x.abs()));
    let path: Box<Path<N, D, PIECES>> = Box::new(
        compile(&curve, &*timing, job.rate_hz, &compile_options(job))
            .map_err(|e| compile_error(job, e, timing.duration(), max_abs))?,
    );
    let compiled = started.elapsed();

    let out = &options.out_dir;
    fs::create_dir_all(out).map_err(io_error(out))?;
    let csv_path = out.join("samples.csv");
    let mut csv = BufWriter::new(File::create(&csv_path).map_err(io_error(&csv_path))?);
    writeln!(csv, "{}", csv_header(D)).map_err(io_error(&csv_path))?;

    // Play.
    let events = job.sorted_events();
    let last_event = events.last().map_or(0, |e| e.0);
    let ticks = u64::from(path.ticks());
    let guard = 10 * (ticks + 1) + last_event + 1;
    let expected = (ticks + 1).max(last_event + 1);
    let rate = job.rate_hz;
    let bar = (options.progress
        && std::io::stderr().is_terminal()
        && expected >= PROGRESS_MIN_SAMPLES)
        .then(|| {
            let bar = ProgressBar::with_draw_target(Some(expected), ProgressDrawTarget::stderr());
            if let Ok(style) = ProgressStyle::with_template(
                "{spinner} playing {bar:40} {pos}/{len} ticks, {eta} left",
            ) {
                bar.set_style(style);
            }
            bar
        });

    let mut sampler = Sampler::new(&*path);
    let mut recorder = Recorder::new(D, expected);
    let (mut vel, mut acc, mut jerk) = (Peak::<D>::new(), Peak::<D>::new(), Peak::<D>::new());
    let mut worst_ref = (0.0_f64, 0.0_f64);
    // Along the path: tangential and centripetal acceleration, tangential jerk.
    let (mut at_max, mut an_max, mut jt_max) = ((0.0_f64, 0.0), (0.0_f64, 0.0), (0.0_f64, 0.0));
    let mut tangent: Option<[f64; D]> = None;
    let mut prev_at: Option<f64> = None;
    let mut prev_acc: Option<[f64; D]> = None;
    let mut last_position: [f64; D];
    let mut last_out: [N::Out; D];
    let mut next_event = 0;
    let mut aborted = false;
    let mut samples: u64 = 0;
    let mut row = String::new();
    let mut values: Vec<f64> = Vec::with_capacity(4 * D + 3);
    let finished = loop {
        aborted |= apply_due_events(&mut sampler, &events, &mut next_event, samples);
        let progress = sampler.progress();
        let s = sampler.next();
        let k = samples;
        samples += 1;
        let t = k as f64 / rate;

        row.clear();
        {
            use std::fmt::Write as _;
            let _ = write!(row, "{k},{t:?}");
        }
        for v in s.position.iter().chain(&s.velocity).chain(&s.acceleration) {
            row.push(',');
            v.write_cell(&mut row);
        }
        row.push('\n');
        csv.write_all(row.as_bytes()).map_err(io_error(&csv_path))?;

        let p = out_f64(&s.position);
        let v = out_f64(&s.velocity);
        let a = out_f64(&s.acceleration);
        vel.push(t, &v);
        acc.push(t, &a);
        let j = prev_acc.map(|pa| {
            let mut j = [0.0; D];
            for ((jj, x), y) in j.iter_mut().zip(&a).zip(&pa) {
                *jj = (x - y) * rate;
            }
            j
        });
        if let Some(j) = &j {
            jerk.push(t, j);
        }
        prev_acc = Some(a);
        // The reference: the f64 curve at the planned parameter of this sample's playback point.
        let u = timing.param(path.plan_time(progress)).0;
        let r = reference.eval(u);
        let d = distance(&p, &r);
        if d > worst_ref.0 {
            worst_ref = (d, t);
        }
        // The unit tangent of the reference curve there (the last one where c'(u) = 0).
        let dc = reference.deriv(u, 1);
        let dn = norm(&dc);
        if dn > 0.0 && dn.is_finite() {
            tangent = Some(dc.map(|x| x / dn));
        }
        if let Some(tv) = &tangent {
            let at: f64 = a.iter().zip(tv).map(|(x, y)| x * y).sum();
            let mut normal = a;
            for (n, y) in normal.iter_mut().zip(tv) {
                *n -= at * y;
            }
            let an = norm(&normal);
            if at.abs() > at_max.0 {
                at_max = (at.abs(), t);
            }
            if an > an_max.0 {
                an_max = (an, t);
            }
            if let Some(pa) = prev_at {
                let jt = ((at - pa) * rate).abs();
                if jt > jt_max.0 {
                    jt_max = (jt, t);
                }
            }
            prev_at = Some(at);
        }
        values.clear();
        values.extend_from_slice(&p);
        values.extend_from_slice(&v);
        values.push(norm(&v));
        values.extend_from_slice(&a);
        values.push(norm(&a));
        match &j {
            Some(j) => {
                values.extend_from_slice(j);
                values.push(norm(j));
            }
            None => values.extend(std::iter::repeat_n(f64::NAN, D + 1)),
        }
        recorder.push(t, &values);
        last_position = p;
        last_out = s.position;

        if let Some(bar) = &bar
            && samples.is_multiple_of(8192)
        {
            if samples > expected {
                bar.set_length(samples.min(guard));
            }
            bar.set_position(samples);
        }
        if sampler.is_finished() {
            break true;
        }
        if samples >= guard {
            break false;
        }
    };
    csv.flush().map_err(io_error(&csv_path))?;
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    let played = started.elapsed();

    // Summary.
    let l = &job.limits;
    let axis_v = axis_array::<D>(l.axis_velocity.as_deref());
    let axis_a = axis_array::<D>(l.axis_acceleration.as_deref());
    let path_max = Maxima {
        name: "path".to_owned(),
        velocity: Checked::new(vel.norm.0, vel.norm.1, Some(l.velocity)),
        acceleration: Checked::new(acc.norm.0, acc.norm.1, Some(l.acceleration)),
        jerk: Checked::new(jerk.norm.0, jerk.norm.1, Some(l.jerk)),
    };
    let per_axis: Vec<Maxima> = (0..D)
        .map(|i| Maxima {
            name: AXIS_NAMES[i].to_owned(),
            velocity: Checked::new(vel.axes[i].0, vel.axes[i].1, Some(axis_v[i])),
            acceleration: Checked::new(acc.axes[i].0, acc.axes[i].1, Some(axis_a[i])),
            jerk: Checked::new(jerk.axes[i].0, jerk.axes[i].1, None),
        })
        .collect();
    let along_path = AlongPath {
        tangential_acceleration: Checked::new(at_max.0, at_max.1, Some(l.acceleration)),
        centripetal_acceleration: Checked::new(an_max.0, an_max.1, Some(l.acceleration)),
        tangential_jerk: Checked::new(jt_max.0, jt_max.1, Some(l.jerk)),
    };
    let path_end = out_f64(&path.end_position());
    let reference_end = reference.eval(reference.domain().1);
    let exact_end = last_out == path.end_position();
    let stop = if !finished {
        format!(
            "stopped by the guard after {samples} samples: the sampler did not finish (a hold without resume?)"
        )
    } else if aborted && !exact_end {
        "aborted (stopped on the path before its end)".to_owned()
    } else {
        "end of path".to_owned()
    };
    let keep = 1.0 - job.feed_share();
    let length_estimate = {
        let (a, b) = reference.domain();
        (0..64)
            .map(|k| {
                let u = |k: usize| a + (b - a) * (k as f64 / 64.0);
                distance(&reference.eval(u(k)), &reference.eval(u(k + 1)))
            })
            .sum::<f64>()
    };
    let path_length = if length_estimate > 0.0 {
        arc_length(&reference, 1e-10 * length_estimate).unwrap_or(f64::NAN)
    } else {
        0.0
    };
    let mut files: Vec<String> = ["samples.csv", "summary.json", "path.svg", "motion.svg"]
        .iter()
        .map(|f| out.join(f).display().to_string())
        .collect();
    files.truncate(4);
    let mut summary = Summary {
        job: options.name.clone(),
        number: job.number.name().to_owned(),
        playback: match job.number {
            JobNumber::Fixed => format!("{} (samples I32F32)", N::NAME),
            _ => N::NAME.to_owned(),
        },
        axes: D,
        unit: job.unit().to_owned(),
        rate_hz: rate,
        profile: job.profile.kind.name().to_owned(),
        feed_share: job.feed_share(),
        planned_with: PlannedLimits {
            velocity: limits.velocity(),
            acceleration: limits.acceleration(),
            jerk: limits.jerk(),
            axis_acceleration: axis_a
                .iter()
                .map(|a| Some(a * keep).filter(|x| x.is_finite()))
                .collect(),
        },
        duration_s: path.duration(),
        plan_duration_s: path.plan_duration(),
        ticks: path.ticks(),
        samples,
        run_time_s: samples.saturating_sub(1) as f64 / rate,
        stop,
        finished,
        events_applied: next_event,
        events_ignored: events.len() - next_event,
        path_length,
        pieces: path.pieces().len(),
        piece_capacity: PIECES,
        tolerance: path.tolerance(),
        playback_bound: path.playback_bound(),
        path: path_max,
        along_path,
        per_axis,
        limits_respected: false,
        reference_distance: ReferenceDistance {
            method: REFERENCE_METHOD.to_owned(),
            max: worst_ref.0,
            at_s: worst_ref.1,
        },
        end_point: EndPoint {
            last_sample: last_position.to_vec(),
            path_end: path_end.to_vec(),
            reference_end: reference_end.to_vec(),
            error_to_path_end: distance(&last_position, &path_end),
            error_to_reference_end: distance(&last_position, &reference_end),
        },
        wall_time: WallTime {
            plan_s: planned.as_secs_f64(),
            compile_s: (compiled - planned).as_secs_f64(),
            play_s: (played - compiled).as_secs_f64(),
            plots_s: 0.0,
            total_s: 0.0,
        },
        files,
    };

    summary.limits_respected = summary
        .all_checked()
        .iter()
        .all(|c| c.within != Some(false));

    // Plots.
    let title = format!(
        "{} — {} {}, {} Hz, {}",
        options.name,
        job.profile.kind.name(),
        summary.playback,
        crate::summary::num(rate),
        if finished { "finished" } else { "not finished" }
    );
    let plot_limits = PlotLimits {
        velocity: Some(l.velocity),
        acceleration: Some(l.acceleration),
        jerk: Some(l.jerk),
    };
    let path_svg = out.join("path.svg");
    plot::write_path(&path_svg, &recorder, job.unit(), &title)
        .map_err(|e| RunError::Io(format!("cannot write {}: {e}", path_svg.display())))?;
    let motion_svg = out.join("motion.svg");
    plot::write_motion(&motion_svg, &recorder, job.unit(), plot_limits, &title)
        .map_err(|e| RunError::Io(format!("cannot write {}: {e}", motion_svg.display())))?;
    let total = started.elapsed();
    summary.wall_time.plots_s = (total - played).as_secs_f64();
    summary.wall_time.total_s = total.as_secs_f64();

    let json_path = out.join("summary.json");
    let json = serde_json::to_string_pretty(&summary)
        .map_err(|e| RunError::Io(format!("cannot write {}: {e}", json_path.display())))?;
    fs::write(&json_path, json + "\n").map_err(io_error(&json_path))?;
    Ok(summary)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_names_every_axis() {
        assert_eq!(csv_header(2), "tick,t,x,y,vx,vy,ax,ay");
        assert_eq!(csv_header(3), "tick,t,x,y,z,vx,vy,vz,ax,ay,az");
    }

    #[test]
    fn fixed_cells_read_back_exactly() {
        for bits in [
            1_i64,
            -1,
            0x1234_5678_9abc_def0,
            -(1 << 40) + 7,
            i64::MAX / 3,
        ] {
            let x = I32F32::from_bits(bits);
            let mut s = String::new();
            x.write_cell(&mut s);
            assert_eq!(s.parse::<I32F32>().unwrap(), x, "{s}");
        }
    }

    #[test]
    fn bundled_job_parses() {
        let job = Job::parse(BUNDLED_JOB).unwrap();
        assert_eq!(job.axes(), 3);
        assert_eq!(job.rate_hz, 1000.0);
        assert_eq!(job.profile.kind, ProfileKind::SCurve);
        let limits = planning_limits::<3>(&job).unwrap();
        assert_eq!(limits.acceleration(), job.limits.acceleration * 0.75);
        assert_eq!(
            limits.velocity(),
            job.limits.velocity * (1.0 - VELOCITY_RESERVE)
        );
        assert_eq!(limits.axis_velocity()[2], 400.0 * (1.0 - VELOCITY_RESERVE));
    }
}
