//! `strak-sim run`: plan, compile and play a job through the sampler firmware uses, and write
//! the samples, a summary and plots.
//!
//! 1. **Plan and compile** with the [`pipeline`](crate::pipeline) `strak-sim compile` uses;
//!    the curve is built once more in `f64` as the reference.
//! 2. **Play** with [`Sampler`], one `next()` per control tick, the `[[events]]` applied by the
//!    [`EventPlayer`] before the sample of their tick, until the sampler is finished, or,
//!    guarding against a hold without resume, after `10·(ticks + 1) + last event tick + 1`
//!    samples.
//! 3. **Measure** every sample ([`Measure`]): the sampled velocity and acceleration, their
//!    finite differences, the jerk, the components along the path, and the distance from the
//!    curve, each against its limit ([`crate::measure`] states the tolerance).
//! 4. **Report**: a time law planned under the limits (trapezoid, S-curve) whose samples
//!    exceed a limit it plans for, or whose distance from the curve exceeds the compiled
//!    path's bound, lists the quantities in [`Summary::violations`] (and `strak-sim run`
//!    exits with code 3). The trapezoid does not plan the jerk; the parameter and
//!    constant-speed laws plan none of the limits: the summary reports them without failing.
//!
//! Everything runs on the caller's thread: the plan and the path are on the heap, filled in
//! place, and the stack holds small frames and the curve being built (see
//! [`pipeline`](crate::pipeline#stack)).

use std::fs::{self, File};
use std::io::{BufWriter, IsTerminal, Write};
use std::path::{Path as FsPath, PathBuf};
use std::time::Instant;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use strak_curves::{I32F32, ParamCurve, ParamCurveDeriv, Scalar, arc_length};
use strak_trajectory::{
    Event, EventPlayer, Kernel, Number, Q40, RunEnd, Sample, Sampler, TimedEvent,
};

use crate::dyn_curve::{DynCurve, build_dyn};
use crate::job::{Job, JobError, JobLimits, ProfileKind};
use crate::measure::{Measure, Observed, distance, norm, to_f64};
use crate::number::{self, NumberFormat};
use crate::pipeline::{Compiled, PIECES, Prepared, axis_array, curve_error, is_planned};
use crate::plot::{self, PlotLimits, Recorder};
use crate::schedule::{Scheduled, schedule};
use crate::summary::{
    Accuracy, AlongPath, CheckRule, Checked, Differences, EndPoint, FiniteDifferences, Maxima,
    PlannedLimits, ReferenceDistance, Summary, WallTime,
};

/// Runs expected to take at least this many samples show a progress bar (on a terminal).
pub const PROGRESS_MIN_SAMPLES: u64 = 200_000;

/// The bundled example: a 3-axis pick-and-place move at 1 kHz with an S-curve profile.
pub const BUNDLED_JOB: &str = include_str!("../examples/jobs/pick-and-place.toml");
/// The bundled example's name.
pub const BUNDLED_NAME: &str = "pick-and-place";

/// How the reference point of each sample is chosen (reported in the summary).
pub const REFERENCE_METHOD: &str =
    "f64 curve at the same planned parameter u(t) of the sample's playback point";
/// How the curve point of the accuracy check is chosen (reported in the summary).
pub const ACCURACY_METHOD: &str = "the curve in the job's number format at the same planned \
     parameter u(t), against the compile tolerance plus the playback bound";

/// Where and how to run.
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// The output folder (created if missing).
    pub out_dir: PathBuf,
    /// The job's name for the summary and plot titles.
    pub name: String,
    /// Show a progress bar on long runs (only when standard error is a terminal).
    pub progress: bool,
    /// For tests of the verdict only: every sampled velocity is multiplied by this factor
    /// before it is measured, so that the samples of a planned motion exceed its velocity
    /// limit (the library's planned motions do not) and the run's checks, violations and
    /// [`exit_code`] can be seen to fail. `None` in every real run.
    pub velocity_factor: Option<f64>,
}

/// The exit code of `strak-sim run` whose planned motion exceeded a limit or the accuracy
/// bound.
pub const EXIT_EXCEEDED: u8 = 3;

/// The exit code of `strak-sim run` for a run that produced `summary`: 0, or
/// [`EXIT_EXCEEDED`] when it lists [`violations`](Summary::violations).
pub fn exit_code(summary: &Summary) -> u8 {
    if summary.violations.is_empty() {
        0
    } else {
        EXIT_EXCEEDED
    }
}

/// The lines `strak-sim run` writes to standard error for `summary`'s violations, one per
/// quantity: `strak-sim: error: <label>: limit exceeded: <violation>`.
pub fn violation_lines(label: &str, summary: &Summary) -> Vec<String> {
    summary
        .violations
        .iter()
        .map(|v| format!("strak-sim: error: {label}: limit exceeded: {v}"))
        .collect()
}

/// Why a run failed.
#[derive(Debug)]
pub enum RunError {
    /// The job is bad (one field named).
    Job(JobError),
    /// Writing the output failed.
    Io(String),
    /// A line of a G-code program is bad, or the stream refused its move (the message names
    /// the line).
    Program(String),
}

impl std::fmt::Display for RunError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RunError::Job(e) => write!(f, "{e}"),
            RunError::Io(e) => f.write_str(e),
            RunError::Program(e) => f.write_str(e),
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
    csv_header_named(crate::axes::names(axes))
}

/// The header of `samples.csv` for axes of these names: `tick,t`, then the positions, the
/// velocities (`v` before the name) and the accelerations (`a` before it).
///
/// ```
/// assert_eq!(strak_sim::run::csv_header_named(&["x", "e"]), "tick,t,x,e,vx,ve,ax,ae");
/// ```
pub fn csv_header_named<S: AsRef<str>>(names: &[S]) -> String {
    let names: Vec<&str> = names.iter().map(AsRef::as_ref).collect();
    let mut h = vec!["tick".to_owned(), "t".to_owned()];
    h.extend(names.iter().map(|n| (*n).to_owned()));
    h.extend(names.iter().map(|n| format!("v{n}")));
    h.extend(names.iter().map(|n| format!("a{n}")));
    h.join(",")
}

/// Runs `job`, writes `samples.csv`, `summary.json`, `path.svg` and `motion.svg` into
/// `options.out_dir` and returns the summary (its [`Summary::violations`] name the enforced
/// checks the run failed).
///
/// # Errors
/// [`RunError::Job`] naming the field for a job that cannot be planned or compiled;
/// [`RunError::Io`] when the output cannot be written.
pub fn run_job(job: &Job, options: &RunOptions) -> Result<Summary, RunError> {
    let axes =
        || -> RunError { JobError::new("path.points", "points need 1 to 6 coordinates").into() };
    match job.number {
        NumberFormat::F64 => {
            crate::with_axes!(job.axes(), run_typed::<f64, f64>(job, options), Err(axes()))
        }
        NumberFormat::F32 => {
            crate::with_axes!(job.axes(), run_typed::<f32, f32>(job, options), Err(axes()))
        }
        NumberFormat::Q40 => {
            crate::with_axes!(
                job.axes(),
                run_typed::<Q40, I32F32>(job, options),
                Err(axes())
            )
        }
    }
}

/// The curves of a run: in the job's format, and the `f64` reference.
struct Curves<'a, S: Scalar, const D: usize> {
    curve: &'a DynCurve<S, D>,
    reference: &'a DynCurve<f64, D>,
}

/// What playing a path produced.
struct Played<const D: usize> {
    measure: Measure<D>,
    recorder: Recorder,
    samples: u64,
    stop: RunEnd,
    aborted: bool,
    applied: usize,
    ignored: usize,
    scheduled: Scheduled,
    last_position: [f64; D],
    exact_end: bool,
}

fn run_typed<N, S, const D: usize>(job: &Job, options: &RunOptions) -> Result<Summary, RunError>
where
    N: Kernel,
    N::Out: CsvCell,
    S: Scalar,
{
    let started = Instant::now();
    let prepared = Prepared::<S, D>::new(job)?;
    let reference: DynCurve<f64, D> =
        build_dyn(&job.path, NumberFormat::F64).map_err(curve_error)?;
    let built = started.elapsed();
    let compiled = prepared.compile::<N>(job)?;
    let curves = Curves {
        curve: &prepared.curve,
        reference: &reference,
    };
    let out = &options.out_dir;
    fs::create_dir_all(out).map_err(io_error(out))?;
    let play_started = Instant::now();
    let played = play(job, &compiled, &curves, options)?;
    let wall = WallTime {
        plan_s: (built + compiled.plan_time).as_secs_f64(),
        compile_s: compiled.compile_time.as_secs_f64(),
        play_s: play_started.elapsed().as_secs_f64(),
        plots_s: 0.0,
        total_s: 0.0,
    };
    let mut summary = summarize(job, options, &compiled, &curves, &played, wall);
    let plots_started = Instant::now();
    write_plots(job, options, &summary, &played.recorder)?;
    summary.wall_time.plots_s = plots_started.elapsed().as_secs_f64();
    summary.wall_time.total_s = started.elapsed().as_secs_f64();
    let json_path = out.join("summary.json");
    let json = serde_json::to_string_pretty(&summary)
        .map_err(|e| RunError::Io(format!("cannot write {}: {e}", json_path.display())))?;
    fs::write(&json_path, json + "\n").map_err(io_error(&json_path))?;
    Ok(summary)
}

/// A progress bar for runs expected to take `expected` samples, when it should be shown.
fn progress_bar(show: bool, expected: u64) -> Option<ProgressBar> {
    if !(show && std::io::stderr().is_terminal() && expected >= PROGRESS_MIN_SAMPLES) {
        return None;
    }
    let bar = ProgressBar::with_draw_target(Some(expected), ProgressDrawTarget::stderr());
    if let Ok(style) =
        ProgressStyle::with_template("{spinner} playing {bar:40} {pos}/{len} ticks, {eta} left")
    {
        bar.set_style(style);
    }
    Some(bar)
}

/// One CSV row: `tick,t`, positions, velocities, accelerations.
pub(crate) fn write_row<T: CsvCell, const D: usize>(
    row: &mut String,
    k: u64,
    t: f64,
    s: &Sample<T, D>,
) {
    use std::fmt::Write as _;
    row.clear();
    let _ = write!(row, "{k},{t:?}");
    for v in s.position.iter().chain(&s.velocity).chain(&s.acceleration) {
        row.push(',');
        v.write_cell(row);
    }
    row.push('\n');
}

/// The sample in `f64` with the curve points at its planned parameter (`progress`: the
/// sampler's progress before the sample).
fn observe<N: Number, S: Scalar, const D: usize>(
    t: f64,
    s: &Sample<N::Out, D>,
    progress: f64,
    compiled: &Compiled<'_, N, D>,
    curves: &Curves<'_, S, D>,
) -> Observed<D> {
    let u = compiled.timing.param(compiled.path.plan_time(progress)).0;
    let (lo, hi) = curves.curve.domain();
    let (lo, hi) = (lo.to_f64(), hi.to_f64());
    let u_s = S::from_f64(u.clamp(lo, hi)).unwrap_or(S::ZERO);
    Observed {
        t,
        position: to_f64(&s.position),
        velocity: to_f64(&s.velocity),
        acceleration: to_f64(&s.acceleration),
        reference: curves.reference.eval(u),
        curve: to_f64(&curves.curve.eval(u_s)),
        tangent: curves.reference.deriv(u, 1),
    }
}

/// The plot channels of one sample (see [`Recorder`]).
pub(crate) fn channels<const D: usize>(
    s: &Observed<D>,
    jerk: Option<[f64; D]>,
    path_axes: usize,
    values: &mut Vec<f64>,
) {
    values.clear();
    values.extend_from_slice(&s.position);
    values.extend_from_slice(&s.velocity);
    values.push(norm(&s.velocity[..path_axes]));
    values.extend_from_slice(&s.acceleration);
    values.push(norm(&s.acceleration[..path_axes]));
    match &jerk {
        Some(j) => {
            values.extend_from_slice(j);
            values.push(norm(&j[..path_axes]));
        }
        None => values.extend(std::iter::repeat_n(f64::NAN, D + 1)),
    }
}

/// Plays the compiled path with the job's events, writing `samples.csv` and measuring.
fn play<N, S, const D: usize>(
    job: &Job,
    compiled: &Compiled<'_, N, D>,
    curves: &Curves<'_, S, D>,
    options: &RunOptions,
) -> Result<Played<D>, RunError>
where
    N: Kernel,
    N::Out: CsvCell,
    S: Scalar,
{
    let out = &options.out_dir;
    let csv_path = out.join("samples.csv");
    let mut csv = BufWriter::new(File::create(&csv_path).map_err(io_error(&csv_path))?);
    writeln!(csv, "{}", csv_header(D)).map_err(io_error(&csv_path))?;
    let path = &*compiled.path;
    let scheduled = schedule(job, path)?;
    let events = &scheduled.events;
    let mut player = EventPlayer::new(events, path.ticks());
    let last_event = events.last().map_or(0, |e| e.tick);
    let expected = (u64::from(path.ticks()) + 1).max(last_event + 1);
    let bar = progress_bar(options.progress, expected);
    let mut sampler = Sampler::new(path);
    let mut measure = Measure::<D>::new(job.rate_hz);
    let mut recorder = Recorder::new(D, expected);
    let (mut row, mut values) = (String::new(), Vec::with_capacity(4 * D + 3));
    let mut last = None;
    while !player.is_over(&sampler) {
        player.apply_due(&mut sampler);
        let before = sampler.progress();
        let Some(s) = player.step(&mut sampler) else {
            break;
        };
        let k = player.samples() - 1;
        let t = k as f64 / job.rate_hz;
        write_row(&mut row, k, t, &s);
        csv.write_all(row.as_bytes()).map_err(io_error(&csv_path))?;
        let mut observed = observe(t, &s, before, compiled, curves);
        if let Some(f) = options.velocity_factor {
            observed.velocity = observed.velocity.map(|v| v * f);
        }
        channels(&observed, measure.push(&observed), D, &mut values);
        recorder.push(t, &values);
        last = Some((observed.position, s.position));
        if let Some(bar) = &bar
            && player.samples().is_multiple_of(8192)
        {
            bar.set_length(player.samples().max(expected).min(player.guard()));
            bar.set_position(player.samples());
        }
    }
    csv.flush().map_err(io_error(&csv_path))?;
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    let (last_position, last_out) = last.ok_or_else(|| RunError::Io("no sample".to_owned()))?;
    Ok(Played {
        measure,
        recorder,
        samples: player.samples(),
        stop: player.end(&sampler),
        aborted: player.aborted(),
        applied: job_events(&events[..player.applied()]),
        ignored: job_events(&events[player.applied()..]),
        scheduled: scheduled.clone(),
        last_position,
        exact_end: last_out == path.end_position(),
    })
}

/// The job's events among `events` (not the ramp scales the feed guard put before them).
fn job_events(events: &[TimedEvent]) -> usize {
    events
        .iter()
        .filter(|e| !matches!(e.event, Event::RampScale(_)))
        .count()
}

/// The relative allowances of a playback format over the limits, beyond the checks' own
/// (see [`crate::stream_run::allowance`]): of the sampled velocities and accelerations
/// (and their finite differences), and of the jerk.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Allowance {
    /// Relative to the velocity and acceleration limits.
    pub sampled: f64,
    /// Relative to the jerk limit.
    pub jerk: f64,
    /// The ticks of forward differencing whose rounding one finite difference may carry
    /// besides its own: a piece's channels drift by up to half a unit per tick added, and
    /// the next piece starts from the exact state, so the difference across the join of two
    /// pieces of `n` ticks carries up to `n/2` units more (0: pieces end exactly).
    pub drift_ticks: f64,
}

/// The limit checks of the sampled maxima, the finite differences and the components along
/// the path.
fn maxima<const D: usize>(
    job: &Job,
    m: &Measure<D>,
) -> (Maxima, Vec<Maxima>, FiniteDifferences, AlongPath) {
    let enforced = (is_planned(job), job.profile.kind() == ProfileKind::SCurve);
    let names = crate::axes::names(D);
    maxima_of(
        &job.limits,
        job.number,
        enforced,
        Allowance::default(),
        names,
        m,
    )
}

/// The limit checks of the sampled maxima, the finite differences and the components along
/// the path against `l`; `enforced`: whether the velocity and acceleration limits, and the
/// jerk limit, fail the run; `allowance`: the playback format's.
pub(crate) fn maxima_of<const D: usize>(
    l: &JobLimits,
    number: NumberFormat,
    (planned, jerk_planned): (bool, bool),
    allowance: Allowance,
    names: &[&str],
    m: &Measure<D>,
) -> (Maxima, Vec<Maxima>, FiniteDifferences, AlongPath) {
    let axis_v = axis_array::<D>(l.axis_velocity.as_deref());
    let axis_a = axis_array::<D>(l.axis_acceleration.as_deref());
    let check = |w: crate::measure::Worst, limit: f64, slack: f64, enforced: bool| {
        let share = if limit.is_finite() {
            allowance.sampled * limit
        } else {
            0.0
        };
        Checked::new(w.max, w.at_s, Some(limit))
            .allowing(slack.max(share))
            .enforce(enforced)
    };
    let drift = 1.0 + allowance.drift_ticks / 2.0;
    let slack = |magnitude: f64, norm: bool| m.slack(number, magnitude, norm) * drift;
    let (sx, sv, sa) = (
        m.position.magnitude,
        m.velocity.magnitude,
        m.acceleration.magnitude,
    );
    let path = Maxima {
        name: "path".to_owned(),
        velocity: check(m.velocity.norm, l.velocity, 0.0, planned),
        acceleration: check(m.acceleration.norm, l.acceleration, 0.0, planned),
        jerk: check(
            m.jerk.norm,
            l.jerk,
            slack(sa, true).max(allowance.jerk * l.jerk),
            jerk_planned,
        ),
    };
    let per_axis = (0..D)
        .map(|i| Maxima {
            name: names[i].to_owned(),
            velocity: check(m.velocity.axes[i], axis_v[i], 0.0, planned),
            acceleration: check(m.acceleration.axes[i], axis_a[i], 0.0, planned),
            jerk: Checked::new(m.jerk.axes[i].max, m.jerk.axes[i].at_s, None),
        })
        .collect();
    let differences = FiniteDifferences {
        path: Differences {
            name: "path".to_owned(),
            velocity: check(m.dx.norm, l.velocity, slack(sx, true), planned),
            acceleration: check(m.dv.norm, l.acceleration, slack(sv, true), planned),
        },
        per_axis: (0..D)
            .map(|i| Differences {
                name: names[i].to_owned(),
                velocity: check(m.dx.axes[i], axis_v[i], slack(sx, false), planned),
                acceleration: check(m.dv.axes[i], axis_a[i], slack(sv, false), planned),
            })
            .collect(),
    };
    let along = AlongPath {
        tangential_acceleration: check(m.tangential_acceleration, l.acceleration, 0.0, false),
        centripetal_acceleration: check(m.centripetal_acceleration, l.acceleration, 0.0, false),
        tangential_jerk: check(m.tangential_jerk, l.jerk, 0.0, false),
    };
    (path, per_axis, differences, along)
}

/// The arc length of the reference curve (0 for a curve of zero length).
fn path_length<const D: usize>(reference: &DynCurve<f64, D>) -> f64 {
    let (a, b) = reference.domain();
    let u = |k: usize| a + (b - a) * (k as f64 / 64.0);
    let estimate: f64 = (0..64)
        .map(|k| distance(&reference.eval(u(k)), &reference.eval(u(k + 1))))
        .sum();
    if estimate > 0.0 {
        arc_length(reference, 1e-10 * estimate).unwrap_or(f64::NAN)
    } else {
        0.0
    }
}

fn stop_text<const D: usize>(played: &Played<D>) -> String {
    match played.stop {
        RunEnd::Guard => format!(
            "stopped by the guard after {} samples: the sampler did not finish (a hold without resume?)",
            played.samples
        ),
        RunEnd::Finished if played.aborted && !played.exact_end => {
            "aborted (stopped on the path before its end)".to_owned()
        }
        RunEnd::Finished => "end of path".to_owned(),
    }
}

fn check_rule(job: &Job) -> CheckRule {
    let kind = job.profile.kind();
    let rule = match kind {
        ProfileKind::SCurve => "the s-curve is planned under every limit: exceeding one, or the \
             accuracy bound, fails the run"
            .to_owned(),
        ProfileKind::Trapezoid => "the trapezoid is planned under the velocity and acceleration \
             limits (not the jerk): exceeding one, or the accuracy bound, fails the run"
            .to_owned(),
        _ => format!(
            "the {} law is not planned under the limits: the summary reports them without \
             failing",
            kind.name()
        ),
    };
    CheckRule {
        enforced: kind.is_planned(),
        rule,
        relative_tolerance: crate::measure::RELATIVE_TOLERANCE,
    }
}

/// The limits the time law is planned with, as reported.
fn planned_with<const D: usize>(job: &Job) -> PlannedLimits {
    let keep = 1.0 - job.feed_share();
    let axis_a = axis_array::<D>(job.limits.axis_acceleration.as_deref());
    PlannedLimits {
        velocity: job.limits.velocity * (1.0 - crate::pipeline::VELOCITY_RESERVE),
        acceleration: job.limits.acceleration * keep,
        jerk: job.limits.jerk * keep,
        axis_acceleration: axis_a
            .iter()
            .map(|a| Some(a * keep).filter(|x| x.is_finite()))
            .collect(),
    }
}

/// The last sample against the path's end and the reference curve's.
fn end_point<N: Number, const D: usize>(
    path: &strak_trajectory::Path<N, D, PIECES>,
    reference: &DynCurve<f64, D>,
    last: &[f64; D],
) -> EndPoint {
    let path_end = to_f64(&path.end_position());
    let reference_end = reference.eval(reference.domain().1);
    EndPoint {
        last_sample: last.to_vec(),
        path_end: path_end.to_vec(),
        reference_end: reference_end.to_vec(),
        error_to_path_end: distance(last, &path_end),
        error_to_reference_end: distance(last, &reference_end),
    }
}

/// The distance from the curve against `tolerance + playback bound`.
fn accuracy<const D: usize>(job: &Job, m: &Measure<D>, bound: f64) -> Accuracy {
    let slack = (D as f64).sqrt() * crate::measure::resolution(job.number, m.position.magnitude);
    Accuracy {
        method: ACCURACY_METHOD.to_owned(),
        distance: Checked::new(m.curve.max, m.curve.at_s, Some(bound))
            .allowing(slack)
            .enforce(is_planned(job)),
    }
}

fn summarize<N: Number, S: Scalar, const D: usize>(
    job: &Job,
    options: &RunOptions,
    compiled: &Compiled<'_, N, D>,
    curves: &Curves<'_, S, D>,
    played: &Played<D>,
    wall_time: WallTime,
) -> Summary {
    let path = &*compiled.path;
    let m = &played.measure;
    let (path_max, per_axis, finite_differences, along_path) = maxima(job, m);
    let mut summary = Summary {
        job: options.name.clone(),
        number: number::name(job.number).to_owned(),
        playback: match job.number {
            NumberFormat::Q40 => format!("{} (samples I32F32)", N::NAME),
            _ => N::NAME.to_owned(),
        },
        axes: D,
        unit: job.unit().to_owned(),
        rate_hz: job.rate_hz,
        profile: job.profile.kind().name().to_owned(),
        feed_share: job.feed_share(),
        planned_with: planned_with::<D>(job),
        duration_s: path.duration(),
        plan_duration_s: path.plan_duration(),
        ticks: path.ticks(),
        samples: played.samples,
        run_time_s: played.samples.saturating_sub(1) as f64 / job.rate_hz,
        stop: stop_text(played),
        finished: played.stop == RunEnd::Finished,
        events_applied: played.applied,
        events_ignored: played.ignored,
        events_late_ticks: played.scheduled.latest(),
        events_refused: played.scheduled.refused(),
        feed_events: played.scheduled.applied.clone(),
        path_length: path_length(curves.reference),
        pieces: path.pieces().len(),
        piece_capacity: PIECES,
        tolerance: path.tolerance(),
        playback_bound: path.playback_bound(),
        path: path_max,
        along_path,
        per_axis,
        limits_respected: false,
        finite_differences,
        accuracy: accuracy(job, m, path.tolerance() + path.playback_bound()),
        check: check_rule(job),
        violations: Vec::new(),
        reference_distance: ReferenceDistance {
            method: REFERENCE_METHOD.to_owned(),
            max: m.reference.max,
            at_s: m.reference.at_s,
        },
        end_point: end_point(path, curves.reference, &played.last_position),
        wall_time,
        files: ["samples.csv", "summary.json", "path.svg", "motion.svg"]
            .iter()
            .map(|f| options.out_dir.join(f).display().to_string())
            .collect(),
        stream: None,
        gcode: None,
    };
    summary.limits_respected = summary
        .all_checked()
        .iter()
        .all(|c| c.within != Some(false));
    summary.violations = summary.find_violations();
    summary
}

fn write_plots(
    job: &Job,
    options: &RunOptions,
    summary: &Summary,
    recorder: &Recorder,
) -> Result<(), RunError> {
    let title = format!(
        "{} — {} {}, {} Hz, {}",
        options.name,
        summary.profile,
        summary.playback,
        crate::summary::num(job.rate_hz),
        if summary.finished {
            "finished"
        } else {
            "not finished"
        }
    );
    let l = &job.limits;
    let plot_limits = PlotLimits {
        velocity: Some(l.velocity),
        acceleration: Some(l.acceleration),
        jerk: Some(l.jerk),
    };
    let out = &options.out_dir;
    let path_svg = out.join("path.svg");
    plot::write_path(
        &path_svg,
        recorder,
        job.unit(),
        &title,
        &plot::PathMarks::default(),
    )
    .map_err(|e| RunError::Io(format!("cannot write {}: {e}", path_svg.display())))?;
    let motion_svg = out.join("motion.svg");
    plot::write_motion(&motion_svg, recorder, job.unit(), plot_limits, &title)
        .map_err(|e| RunError::Io(format!("cannot write {}: {e}", motion_svg.display())))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::{VELOCITY_RESERVE, planning_limits};

    #[test]
    fn header_names_every_axis() {
        assert_eq!(csv_header(2), "tick,t,x,y,vx,vy,ax,ay");
        assert_eq!(csv_header(3), "tick,t,x,y,z,vx,vy,vz,ax,ay,az");
        assert!(csv_header(6).ends_with(",aw,ax5,ax6"));
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
        assert_eq!(job.profile.kind(), ProfileKind::SCurve);
        let limits = planning_limits::<3>(&job).unwrap();
        // planned at the full acceleration and jerk (no feed share by default)
        assert_eq!(limits.acceleration(), job.limits.acceleration);
        assert_eq!(crate::pipeline::plan_options(&job).feed_share(), 0.0);
        assert_eq!(
            limits.velocity(),
            job.limits.velocity * (1.0 - VELOCITY_RESERVE)
        );
        assert_eq!(limits.axis_velocity()[2], 400.0 * (1.0 - VELOCITY_RESERVE));
    }
}
