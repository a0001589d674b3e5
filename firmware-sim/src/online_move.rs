//! `strak-sim move`: an online move ([`OnlineMove`]) from a start state to a target,
//! compiled on the tick grid and played through the sampler firmware uses, with new targets
//! and quick stops taken over at given ticks.
//!
//! ```toml
//! rate_hz = 1000
//! number = "f64"                 # f64 | f32 | fixed
//! sync = "time"                  # time | phase | none (default time)
//! unit = "mm"                    # optional, for the summary and plots
//! [limits]                       # one value per axis, > 0
//! velocity = [500, 500, 400]
//! acceleration = [5000, 5000, 3000]
//! jerk = [100000, 100000, 80000]
//! [start]                        # velocity and acceleration optional, default 0
//! position = [0, 0, 0]
//! velocity = [100, 0, 0]
//! acceleration = [0, 500, 0]
//! [target]                       # position may be left out for a velocity move
//! position = [300, 150, 80]
//! velocity = [0, 0, 0]           # optional, default 0
//! acceleration = [0, 0, 0]       # optional, default 0
//! [[events]]                     # optional: a new target, or a quick stop, at a tick
//! tick = 300
//! target = { position = [100, 100, 0] }
//! # or: stop = true | feed = 0.5 (0, or 0.01 ..= 1) | hold = true | resume = true | abort = true
//! ```
//!
//! The move is solved in the format the firmware would solve it in (`f32` for `number =
//! "f32"`, `f64` otherwise), on the tick grid of `rate_hz`, and compiled
//! ([`compile_move_into`]) into a path in the playback format. An event at tick `k` takes
//! the sample of tick `k − 1` as the start of a new move (a quick stop: a velocity move to
//! rest, each axis as fast as it can, all ending together), whose second sample is the
//! sample of tick `k`. The summary measures every sample like `strak-sim run`: the sampled
//! velocity and acceleration and the jerk from finite differences of the accelerations, per
//! axis against its limits, from the first sample at which every axis is within its limits
//! and can stay there (a start outside them brakes into them first). The checks allow the
//! playback's rounding of the paths played (the sampled values their channel's bound, a
//! finite difference twice that per tick: [`Path::playback_bound`] and
//! [`Path::channel_bounds`]; at least the samples' resolution) and, for the jerk, the
//! solver's rounding of the acceleration at a switching time (twice `64 ε` of the
//! acceleration limit per tick for the `f32` solver, `1024 ε` for `f64`).
//!
//! [`Path::playback_bound`]: strak_trajectory::PathHeader::playback_bound
//! [`Path::channel_bounds`]: strak_trajectory::Path::channel_bounds

use std::fmt;
use std::fs::{self, File};
use std::io::{BufWriter, Write};
use std::path::Path as FsPath;

use serde::{Deserialize, Serialize};
use strak_curves::Scalar;
use strak_trajectory::{
    AxisLimits, Interface, Kernel, Kinematics, MoveOptions, OnlineMove, Q40, Real, Sample, Sampler,
    Synchronization, compile_move_into, take_over_into,
};

use crate::export::OutBits;
use crate::job::{Action, JobError};
use crate::measure::{Measure, Observed, norm, to_f64};
use crate::number::{self, NumberFormat};
use crate::pipeline::boxed_path;
use crate::plot::{self, PlotLimits, Recorder};
use crate::run::{CsvCell, RunError, RunOptions, csv_header, write_row};
use crate::summary::{Checked, num};
use crate::toml_error::locate;

/// The synchronization names of the file.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
enum SyncName {
    #[default]
    Time,
    Phase,
    None,
}

/// A state of the file: position (optional for a target: a velocity move), velocity and
/// acceleration (default zero).
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct StateFile {
    position: Option<Vec<f64>>,
    velocity: Option<Vec<f64>>,
    acceleration: Option<Vec<f64>>,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct LimitsFile {
    velocity: Vec<f64>,
    acceleration: Vec<f64>,
    jerk: Vec<f64>,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct EventFile {
    tick: u64,
    target: Option<StateFile>,
    stop: Option<bool>,
    feed: Option<f64>,
    hold: Option<bool>,
    resume: Option<bool>,
    abort: Option<bool>,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MoveFile {
    rate_hz: f64,
    #[serde(deserialize_with = "number::deserialize")]
    number: NumberFormat,
    #[serde(default)]
    sync: SyncName,
    unit: Option<String>,
    limits: LimitsFile,
    start: StateFile,
    target: StateFile,
    #[serde(default)]
    events: Vec<EventFile>,
}

/// A target: the states and whether the positions count (a position move) or not.
#[derive(Clone, Debug, PartialEq)]
pub struct MoveTarget {
    /// Per axis `(position, velocity, acceleration)` (position 0 for a velocity move).
    pub states: Vec<[f64; 3]>,
    /// A position move (the file gave positions).
    pub position: bool,
}

/// What happens at a tick.
#[derive(Clone, Debug, PartialEq)]
pub enum MoveEvent {
    /// A new target.
    Target(MoveTarget),
    /// Come to rest as fast as the limits allow; the target becomes rest.
    Stop,
    /// The operator: feed override, hold, resume, abort (see [`play_moves`]).
    Operator(Action),
}

/// The smallest feed override other than 0: the rest of a move is re-timed with the velocity
/// limits times the feed, so a smaller one would make it last more than 100 times as long.
pub const MIN_FEED: f64 = 0.01;

/// A checked move file.
#[derive(Clone, Debug, PartialEq)]
pub struct MoveJob {
    /// Control rate in Hz.
    pub rate_hz: f64,
    /// Playback number format.
    pub number: NumberFormat,
    /// How the axes are timed together.
    pub sync: Synchronization,
    /// Length unit.
    pub unit: String,
    /// Per axis `(velocity, acceleration, jerk)` limits.
    pub limits: Vec<[f64; 3]>,
    /// Per axis start `(position, velocity, acceleration)`.
    pub start: Vec<[f64; 3]>,
    /// The first target.
    pub target: MoveTarget,
    /// Events by tick (increasing).
    pub events: Vec<(u64, MoveEvent)>,
}

impl MoveJob {
    /// Parses and checks a move file; every problem names its field.
    ///
    /// # Errors
    /// A [`JobError`] naming the field.
    pub fn parse(text: &str) -> Result<Self, JobError> {
        let file: MoveFile = toml::from_str(text).map_err(|e| {
            let l = locate(text, &e, &[]);
            JobError::new(l.field, l.message)
        })?;
        let axes = file.limits.velocity.len();
        if !(1..=crate::axes::MAX_AXES).contains(&axes) {
            return Err(JobError::new(
                "limits.velocity",
                "1 to 6 axes, one value each",
            ));
        }
        if !(file.rate_hz >= crate::job::RATE_RANGE.0 && file.rate_hz <= crate::job::RATE_RANGE.1) {
            return Err(JobError::new("rate_hz", "must be 100 ..= 100000 Hz"));
        }
        let list =
            |field: &str, v: &Option<Vec<f64>>, default: bool| -> Result<Vec<f64>, JobError> {
                match v {
                    Some(v) if v.len() != axes => Err(JobError::new(
                        field,
                        format!("{} values for {axes} axes", v.len()),
                    )),
                    Some(v) => match v.iter().position(|x| !x.is_finite()) {
                        Some(i) => Err(JobError::new(format!("{field}[{i}]"), "must be finite")),
                        None => Ok(v.clone()),
                    },
                    None if default => Ok(vec![0.0; axes]),
                    None => Err(JobError::new(field, "missing")),
                }
            };
        let mut limits = vec![[0.0; 3]; axes];
        for (q, (name, v)) in [
            ("velocity", &file.limits.velocity),
            ("acceleration", &file.limits.acceleration),
            ("jerk", &file.limits.jerk),
        ]
        .into_iter()
        .enumerate()
        {
            let field = format!("limits.{name}");
            let v = list(&field, &Some(v.clone()), false)?;
            for (i, x) in v.iter().enumerate() {
                if *x <= 0.0 {
                    return Err(JobError::new(format!("{field}[{i}]"), "must be > 0"));
                }
                limits[i][q] = *x;
            }
        }
        let state = |table: &str,
                     s: &StateFile,
                     position_required: bool|
         -> Result<(Vec<[f64; 3]>, bool), JobError> {
            let p = list(
                &format!("{table}.position"),
                &s.position,
                !position_required,
            )?;
            let v = list(&format!("{table}.velocity"), &s.velocity, true)?;
            let a = list(&format!("{table}.acceleration"), &s.acceleration, true)?;
            Ok((
                (0..axes).map(|i| [p[i], v[i], a[i]]).collect(),
                s.position.is_some(),
            ))
        };
        let (start, _) = state("start", &file.start, true)?;
        let (states, position) = state("target", &file.target, false)?;
        let target = MoveTarget { states, position };
        let mut events = Vec::new();
        let mut last = None;
        for (n, e) in file.events.iter().enumerate() {
            let field = format!("events[{n}]");
            if e.tick == 0 || last.is_some_and(|t| e.tick <= t) {
                return Err(JobError::new(
                    format!("{field}.tick"),
                    "ticks must be > 0 and increase",
                ));
            }
            last = Some(e.tick);
            let flag = |f: Option<bool>| f == Some(true);
            let event = match (
                &e.target,
                flag(e.stop),
                e.feed,
                flag(e.hold),
                flag(e.resume),
                flag(e.abort),
            ) {
                (Some(t), false, None, false, false, false) => {
                    let (states, position) = state(&format!("{field}.target"), t, false)?;
                    MoveEvent::Target(MoveTarget { states, position })
                }
                (None, true, None, false, false, false) => MoveEvent::Stop,
                (None, false, Some(f), false, false, false) => {
                    MoveEvent::Operator(Action::Feed(check_feed(&format!("{field}.feed"), f)?))
                }
                (None, false, None, true, false, false) => MoveEvent::Operator(Action::Hold),
                (None, false, None, false, true, false) => MoveEvent::Operator(Action::Resume),
                (None, false, None, false, false, true) => MoveEvent::Operator(Action::Abort),
                _ => {
                    return Err(JobError::new(
                        field,
                        "one of `target`, `stop = true`, `feed`, `hold = true`, `resume = true` \
                         or `abort = true`",
                    ));
                }
            };
            events.push((e.tick, event));
        }
        let sync = match file.sync {
            SyncName::Time => Synchronization::Time,
            SyncName::Phase => Synchronization::Phase,
            SyncName::None => Synchronization::None,
        };
        Ok(MoveJob {
            rate_hz: file.rate_hz,
            number: file.number,
            sync,
            unit: file.unit.unwrap_or_else(|| "units".to_owned()),
            limits,
            start,
            target,
            events,
        })
    }

    /// The number of axes.
    pub fn axes(&self) -> usize {
        self.limits.len()
    }
}

/// One solved move of a run.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct SolvedMove {
    /// The tick it took over at (0 for the first).
    pub tick: u64,
    /// `target` or `stop`.
    pub kind: String,
    /// Its duration in seconds (whole ticks).
    pub duration_s: f64,
    /// Each axis's shortest duration on its own.
    pub min_durations_s: Vec<f64>,
    /// The synchronization used.
    pub synchronization: String,
    /// Pieces of its compiled path.
    pub pieces: usize,
}

/// One axis's maxima against its limits.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct AxisMaxima {
    /// The axis name.
    pub name: String,
    /// `|v|` of the samples.
    pub velocity: Checked,
    /// `|a|` of the samples.
    pub acceleration: Checked,
    /// `|Δa|·f`.
    pub jerk: Checked,
    /// `|Δx|·f`.
    pub dx: Checked,
    /// `|Δv|·f`.
    pub dv: Checked,
}

/// Everything `strak-sim move` reports.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct MoveSummary {
    /// The file's name.
    pub name: String,
    /// The playback format.
    pub number: String,
    /// The solver's format.
    pub solver: String,
    /// Number of axes.
    pub axes: usize,
    /// Length unit.
    pub unit: String,
    /// Control rate in Hz.
    pub rate_hz: f64,
    /// The duration of everything played (the last sample's time), in seconds.
    pub duration_s: f64,
    /// Samples written.
    pub samples: u64,
    /// The moves solved: the first, and one per event.
    pub moves: Vec<SolvedMove>,
    /// Events not played: after a move that ends moving (a path ends there).
    pub events_ignored: usize,
    /// From this time on the limits are checked (0 unless the start is outside them).
    pub checked_from_s: f64,
    /// Each axis's maxima against its limits.
    pub per_axis: Vec<AxisMaxima>,
    /// The last sample minus the last target, per axis (position, for a position move; then
    /// velocity and acceleration).
    pub end_error: Vec<[f64; 3]>,
    /// The enforced checks the run failed, one line each (empty: it passed).
    pub violations: Vec<String>,
    /// The files written.
    pub files: Vec<String>,
}

impl fmt::Display for MoveSummary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "{}: {} axes, {} playback ({} solver), {} Hz",
            self.name,
            self.axes,
            self.number,
            self.solver,
            num(self.rate_hz)
        )?;
        writeln!(
            f,
            "  duration_s {} ({} samples)",
            num(self.duration_s),
            self.samples
        )?;
        for m in &self.moves {
            let mins: Vec<String> = m.min_durations_s.iter().map(|x| num(*x)).collect();
            writeln!(
                f,
                "  move at tick {} ({}): {} s, {} synchronization, axis minima [{}] s, {} pieces",
                m.tick,
                m.kind,
                num(m.duration_s),
                m.synchronization,
                mins.join(", "),
                m.pieces
            )?;
        }
        if self.checked_from_s > 0.0 {
            writeln!(
                f,
                "  limits checked from {} s (the start brakes into them)",
                num(self.checked_from_s)
            )?;
        }
        for a in &self.per_axis {
            let c =
                |q: &Checked| format!("{} / {}", num(q.max), q.limit.map_or("-".to_owned(), num));
            writeln!(
                f,
                "  {}: |v| {}  |a| {}  |j| {} {}/s³",
                a.name,
                c(&a.velocity),
                c(&a.acceleration),
                c(&a.jerk),
                self.unit
            )?;
        }
        let worst = self
            .end_error
            .iter()
            .flat_map(|e| e.iter())
            .fold(0.0_f64, |m, x| m.max(x.abs()));
        writeln!(
            f,
            "  end error {} (largest of position, velocity, acceleration)",
            num(worst)
        )?;
        if self.violations.is_empty() {
            write!(f, "  every limit held")
        } else {
            write!(f, "  limits exceeded: {}", self.violations.join("; "))
        }
    }
}

/// Calls `f::<N, R, D>(args)` with the playback format `N` of `playback`, the solver's
/// format `R` that `strak-sim move` pairs with it (`f32` for `f32`, `f64` otherwise) and
/// the job's axis count `D`.
macro_rules! by_format {
    ($job:expr, $playback:expr, $f:ident($($arg:expr),*)) => {{
        let axes = || -> RunError { JobError::new("limits.velocity", "1 to 6 axes").into() };
        match $playback {
            NumberFormat::F64 => crate::with_axes!($job.axes(), $f::<f64, f64>($($arg),*), Err(axes())),
            NumberFormat::F32 => crate::with_axes!($job.axes(), $f::<f32, f32>($($arg),*), Err(axes())),
            NumberFormat::Q40 => crate::with_axes!($job.axes(), $f::<Q40, f64>($($arg),*), Err(axes())),
        }
    }};
}

/// Runs a move file: solves, compiles and plays it with its events, writes `samples.csv`,
/// `summary.json` and `motion.svg` into `options.out_dir`, and returns the summary.
///
/// # Errors
/// [`RunError::Job`] naming the field (a target outside the limits, an event the solver
/// cannot take); [`RunError::Io`] when the output cannot be written.
pub fn run_move(job: &MoveJob, options: &RunOptions) -> Result<MoveSummary, RunError> {
    by_format!(job, job.number, run_typed(job, options))
}

/// Every sample's raw bits ([`OutBits`]; `3 · axes` per tick: positions, velocities,
/// accelerations) of the job's moves played in `playback`, whatever the job's `number`, with
/// the solver `strak-sim move` pairs with it (`f32` for `f32`, `f64` otherwise). The
/// firmware under QEMU plays the same moves and must produce the same bits.
///
/// # Errors
/// As [`run_move`] (no files are written).
pub fn move_bits(job: &MoveJob, playback: NumberFormat) -> Result<Vec<u64>, RunError> {
    fn bits<N: Kernel, R: Real, const D: usize>(job: &MoveJob) -> Result<Vec<u64>, RunError>
    where
        N::Out: OutBits,
    {
        let mut out = Vec::new();
        play_moves::<N, R, D>(job, &mut |s| {
            let values = s.position.iter().chain(&s.velocity).chain(&s.acceleration);
            out.extend(values.map(|v| v.out_bits()));
            Ok(())
        })?;
        Ok(out)
    }
    by_format!(job, playback, bits(job))
}

/// `feed` if it is 0 or in `[MIN_FEED, 1]`.
///
/// # Errors
/// A [`JobError`] on `field` otherwise.
pub fn check_feed(field: &str, feed: f64) -> Result<f64, JobError> {
    if feed == 0.0 || (MIN_FEED..=1.0).contains(&feed) {
        Ok(feed)
    } else {
        Err(JobError::new(
            field,
            format!("the feed override must be 0 or between {MIN_FEED} and 1, not {feed}"),
        ))
    }
}

/// Each axis's limits in the solver's format, the velocity limits times `feed` (> 0).
fn axis_limits<R: Real, const D: usize>(job: &MoveJob, feed: f64) -> [AxisLimits<R>; D] {
    core::array::from_fn(|i| {
        let [v, a, j] = job.limits[i];
        AxisLimits::new(R::lit(v * feed), R::lit(a), R::lit(j))
            .unwrap_or_else(|_| unreachable!("checked by the parse, and feed > 0"))
    })
}

/// Per axis `(position, velocity, acceleration)` in the solver's format.
fn states<R: Real, const D: usize>(states: &[[f64; 3]]) -> [Kinematics<R>; D] {
    core::array::from_fn(|i| {
        let [p, v, a] = states[i];
        Kinematics::new(R::lit(p), R::lit(v), R::lit(a))
    })
}

/// The solver's options for a move to `target` (a quick stop for `stop`).
fn move_options(job: &MoveJob, target: &MoveTarget, stop: bool) -> MoveOptions {
    let options = MoveOptions::new()
        .with_rate(job.rate_hz)
        .with_synchronization(job.sync);
    match (stop, target.position) {
        (true, _) => options.quick_stop(),
        (false, true) => options.with_interface(Interface::Position),
        (false, false) => options.with_interface(Interface::Velocity),
    }
}

fn sync_name(s: Synchronization) -> String {
    match s {
        Synchronization::Time => "time",
        Synchronization::Phase => "phase",
        Synchronization::None => "none",
    }
    .to_owned()
}

fn report<R: Real, const D: usize>(
    m: &OnlineMove<R, D>,
    tick: u64,
    kind: &str,
    pieces: usize,
) -> SolvedMove {
    SolvedMove {
        tick,
        kind: kind.to_owned(),
        duration_s: m.duration().to_f64(),
        min_durations_s: m.min_durations().iter().map(|x| x.to_f64()).collect(),
        synchronization: sync_name(m.synchronization()),
        pieces,
    }
}

/// Whether every axis of the sample is within its limits and can stay there (its velocity
/// once the jerk has brought its acceleration to zero is within them too).
fn settled<const D: usize>(job: &MoveJob, s: &Observed<D>) -> bool {
    let slack = 1.0 + crate::measure::RELATIVE_TOLERANCE;
    job.limits.iter().enumerate().all(|(i, &[v, a, j])| {
        let (vi, ai) = (s.velocity[i], s.acceleration[i]);
        let carried = vi + ai * ai.abs() / (2.0 * j);
        vi.abs() <= v * slack && carried.abs() <= v * slack && ai.abs() <= a * slack
    })
}

/// The run's moves and samples so far.
struct Played<const D: usize> {
    moves: Vec<SolvedMove>,
    measure: Measure<D>,
    recorder: Recorder,
    samples: u64,
    checked_from: Option<f64>,
    last: [[f64; 3]; D],
    last_target: MoveTarget,
    ignored: usize,
    rounding: [f64; 3],
}

fn run_typed<N, R, const D: usize>(
    job: &MoveJob,
    options: &RunOptions,
) -> Result<MoveSummary, RunError>
where
    N: Kernel,
    N::Out: CsvCell,
    R: Real,
{
    let out = &options.out_dir;
    fs::create_dir_all(out)
        .map_err(|e| RunError::Io(format!("cannot write {}: {e}", out.display())))?;
    let played = play::<N, R, D>(job, out)?;
    let names = crate::axes::names(D);
    let m = &played.measure;
    // A finite difference moves by twice a channel's playback rounding (or the samples'
    // resolution); the jerk also by the solver's rounding of the acceleration at switching
    // times (see the module docs).
    let [e_x, e_v, e_a] = played.rounding;
    let slack = |magnitude: f64, rounding: f64| {
        m.slack(job.number, magnitude, false)
            .max(2.0 * rounding * job.rate_hz)
    };
    let solver_ulps = R::EPS.to_f64()
        * if R::EPS.to_f64() > 1e-10 {
            64.0
        } else {
            1024.0
        };
    let per_axis: Vec<AxisMaxima> = (0..D)
        .map(|i| {
            let [v, a, j] = job.limits[i];
            let check = |w: crate::measure::Worst, limit: f64, extra: f64| {
                Checked::new(w.max, w.at_s, Some(limit))
                    .allowing(extra)
                    .enforce(true)
            };
            let snap = 2.0 * solver_ulps * a * job.rate_hz;
            AxisMaxima {
                name: names[i].to_owned(),
                velocity: check(m.velocity.axes[i], v, e_v),
                acceleration: check(m.acceleration.axes[i], a, e_a),
                jerk: check(
                    m.jerk.axes[i],
                    j,
                    slack(m.acceleration.magnitude, e_a) + snap,
                ),
                dx: check(m.dx.axes[i], v, slack(m.position.magnitude, e_x)),
                dv: check(m.dv.axes[i], a, slack(m.velocity.magnitude, e_v)),
            }
        })
        .collect();
    let mut violations = Vec::new();
    for a in &per_axis {
        for (what, c) in [
            ("velocity", &a.velocity),
            ("acceleration", &a.acceleration),
            ("jerk", &a.jerk),
            ("Δx·f", &a.dx),
            ("Δv·f", &a.dv),
        ] {
            if c.exceeds() {
                violations.push(format!(
                    "axis {} {what} {} > {}",
                    a.name,
                    num(c.max),
                    c.limit.map_or("-".to_owned(), num)
                ));
            }
        }
    }
    let end_error = (0..D)
        .map(|i| {
            let want = played.last_target.states[i];
            let got = played.last[i];
            let dp = if played.last_target.position {
                got[0] - want[0]
            } else {
                0.0
            };
            [dp, got[1] - want[1], got[2] - want[2]]
        })
        .collect();
    let duration_s = (played.samples.saturating_sub(1)) as f64 / job.rate_hz;
    let title = format!("{}: online move", options.name);
    let motion = out.join("motion.svg");
    plot::write_motion(
        &motion,
        &played.recorder,
        &job.unit,
        PlotLimits {
            velocity: None,
            acceleration: None,
            jerk: None,
        },
        &title,
    )
    .map_err(|e| RunError::Io(format!("cannot write {}: {e}", motion.display())))?;
    let mut summary = MoveSummary {
        name: options.name.clone(),
        number: number::name(job.number).to_owned(),
        solver: R::NAME.to_owned(),
        axes: D,
        unit: job.unit.clone(),
        rate_hz: job.rate_hz,
        duration_s,
        samples: played.samples,
        moves: played.moves,
        events_ignored: played.ignored,
        checked_from_s: played.checked_from.unwrap_or(duration_s),
        per_axis,
        end_error,
        violations,
        files: ["samples.csv", "summary.json", "motion.svg"]
            .map(str::to_owned)
            .to_vec(),
    };
    let json_path = out.join("summary.json");
    let json = serde_json::to_string_pretty(&summary)
        .map_err(|e| RunError::Io(format!("cannot write {}: {e}", json_path.display())))?;
    fs::write(&json_path, json + "\n")
        .map_err(|e| RunError::Io(format!("cannot write {}: {e}", json_path.display())))?;
    summary.files.sort();
    Ok(summary)
}

/// The moves of a run: each one solved, the last target, the events not played.
#[derive(Clone, Debug, PartialEq)]
pub struct Moves {
    /// The moves solved: the first, and one per event played.
    pub moves: Vec<SolvedMove>,
    /// The target of the last move.
    pub last_target: MoveTarget,
    /// Events not played: after a move that ends moving (a path ends there), or after an
    /// abort.
    pub ignored: usize,
    /// The largest playback rounding of the paths played: position
    /// ([`playback_bound`](strak_trajectory::PathHeader::playback_bound)), velocity and
    /// acceleration ([`channel_bounds`](strak_trajectory::Path::channel_bounds)).
    pub rounding: [f64; 3],
}

/// The larger of two roundings, quantity by quantity, with the path's.
fn with_rounding<N: Kernel, const D: usize, const P: usize>(
    r: [f64; 3],
    path: &strak_trajectory::Path<N, D, P>,
) -> [f64; 3] {
    let (e_v, e_a) = path.channel_bounds();
    [
        r[0].max(path.playback_bound()),
        r[1].max(e_v),
        r[2].max(e_a),
    ]
}

/// What [`play_moves`] hands each sample to.
pub type SampleSink<'a, T, const D: usize> = dyn FnMut(&Sample<T, D>) -> Result<(), RunError> + 'a;

/// The error of a move the solver or the compiler rejects, naming `field`.
fn failed(field: &str, e: strak_trajectory::Error) -> RunError {
    RunError::Job(JobError::new(field, e.to_string()))
}

/// The operator's side of a run: where the motion goes when it may, the feed override,
/// and whether it is held or aborted. Each event changes it and says which move to take
/// over with.
///
/// A feed override `φ` re-times the rest of the motion from the current state: the move
/// to the goal is solved again with every velocity limit, and the goal's velocities and
/// accelerations, times `φ` (a start above the new velocity limit brakes into it first,
/// within the acceleration and jerk limits, which stay whole). A hold is a quick stop that
/// keeps the goal; resume solves the move to it again. Feed 0 stops like a hold until the
/// feed rises. An abort is a quick stop after which every event is ignored.
#[derive(Clone, Debug)]
struct Control {
    goal: MoveTarget,
    feed: f64,
    held: bool,
    aborted: bool,
}

/// The move an event asks for.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Order {
    /// To the goal at the feed override.
    Go,
    /// A quick stop.
    Stop,
}

impl Control {
    fn new(goal: &MoveTarget) -> Self {
        Control {
            goal: goal.clone(),
            feed: 1.0,
            held: false,
            aborted: false,
        }
    }

    /// Applies `event`; the move to take over with (`None`: the motion goes on as it is).
    fn apply(&mut self, event: &MoveEvent) -> Option<Order> {
        match event {
            _ if self.aborted => return None,
            MoveEvent::Target(t) => self.goal = t.clone(),
            MoveEvent::Stop => {
                self.goal = rest(self.goal.states.len());
                return Some(Order::Stop);
            }
            MoveEvent::Operator(Action::Feed(f)) => self.feed = *f,
            MoveEvent::Operator(Action::Hold) => {
                self.held = true;
                return Some(Order::Stop);
            }
            MoveEvent::Operator(Action::Resume) if !self.held => return None,
            MoveEvent::Operator(Action::Resume) => self.held = false,
            MoveEvent::Operator(Action::Abort) => {
                self.aborted = true;
                return Some(Order::Stop);
            }
        }
        self.order()
    }

    /// What the state asks for: nothing new while held, a quick stop at feed 0, else the
    /// move to the goal.
    fn order(&self) -> Option<Order> {
        match (self.held, self.feed == 0.0) {
            (true, _) => None,
            (false, true) => Some(Order::Stop),
            (false, false) => Some(Order::Go),
        }
    }

    /// The target, limits and options the solver is given for `order`.
    fn request<R: Real, const D: usize>(
        &self,
        job: &MoveJob,
        order: Order,
    ) -> (MoveTarget, [AxisLimits<R>; D], MoveOptions) {
        match order {
            Order::Stop => {
                let target = rest(D);
                let options = move_options(job, &target, true);
                (target, axis_limits(job, 1.0), options)
            }
            Order::Go => {
                let phi = self.feed;
                let states = self.goal.states.iter();
                let target = MoveTarget {
                    states: states.map(|&[p, v, a]| [p, v * phi, a * phi]).collect(),
                    position: self.goal.position,
                };
                let options = move_options(job, &target, false);
                (target, axis_limits(job, phi), options)
            }
        }
    }
}

/// Rest, position free (the target of a quick stop).
fn rest(axes: usize) -> MoveTarget {
    MoveTarget {
        states: vec![[0.0; 3]; axes],
        position: false,
    }
}

/// The name of an event in the summary.
fn event_name(event: &MoveEvent) -> &'static str {
    match event {
        MoveEvent::Target(_) => "target",
        MoveEvent::Stop => "stop",
        MoveEvent::Operator(Action::Feed(_)) => "feed",
        MoveEvent::Operator(Action::Hold) => "hold",
        MoveEvent::Operator(Action::Resume) => "resume",
        MoveEvent::Operator(Action::Abort) => "abort",
    }
}

/// Plays the job's first move and every event's through the sampler, handing each sample
/// to `sink` (its `tick` counted from the run's start). An event at tick `k > 0` takes over
/// from the sample of tick `k − 1` ([`take_over_into`]); events at tick 0 shape the first
/// move. Feed override, hold, resume and abort re-time the motion: a feed override solves
/// the move to the target again with every velocity limit (and the target's velocity and
/// acceleration) times the feed, a hold is a quick stop that keeps the target, resume
/// solves the move to it again, feed 0 stops like a hold, an abort is a quick stop after
/// which every event is ignored. The
/// firmware under QEMU plays targets and stops alike (`firmware-sim/qemu/src/moves.rs`).
///
/// # Errors
/// [`RunError::Job`] for a move the solver or the compiler rejects (naming the target or
/// the event); the sink's error.
pub fn play_moves<N, R, const D: usize>(
    job: &MoveJob,
    sink: &mut SampleSink<'_, N::Out, D>,
) -> Result<Moves, RunError>
where
    N: Kernel,
    R: Real,
{
    let mut control = Control::new(&job.target);
    let mut events = job.events.iter().peekable();
    let mut ignored = 0;
    while let Some((_, event)) = events.next_if(|(tick, _)| *tick == 0) {
        ignored += usize::from(control.aborted);
        control.apply(event);
    }
    // Two paths: the one playing, and the one the next move is compiled into.
    let mut paths = [boxed_path::<N, D>(), boxed_path::<N, D>()];
    let mut m = Box::new(OnlineMove::<R, D>::new());
    let (mut last_target, limits, options) =
        control.request::<R, D>(job, control.order().unwrap_or(Order::Stop));
    m.solve_in_place(
        &states(&job.start),
        &states(&last_target.states),
        &limits,
        &options,
    )
    .map_err(|e| failed("target", e))?;
    compile_move_into(&*m, &mut *paths[0]).map_err(|e| failed("target", e))?;
    let mut rounding = with_rounding([0.0; 3], &paths[0]);
    let mut moves = vec![report(&m, 0, "target", paths[0].pieces().len())];
    let mut current = 0;
    let mut sampler = Sampler::new(&*paths[current]);
    let mut k: u64 = 0;
    let mut last: Option<Sample<N::Out, D>> = None;
    loop {
        while let (Some(prev), Some((tick, event))) =
            (last.as_ref(), events.next_if(|(tick, _)| *tick == k))
        {
            ignored += usize::from(control.aborted);
            let Some(order) = control.apply(event) else {
                continue;
            };
            let (target, limits, options) = control.request::<R, D>(job, order);
            // The playback rounding of the sample taken over.
            let playing = &paths[current];
            let (e_v, e_a) = playing.channel_bounds();
            let options =
                options.with_start_rounding(0.0, playing.playback_bound().max(e_v).max(e_a));
            let next = 1 - current;
            let field = format!("events at tick {tick}");
            take_over_into(
                prev,
                &states(&target.states),
                &limits,
                &options,
                &mut m,
                &mut paths[next],
            )
            .map_err(|e| failed(&field, e))?;
            moves.push(report(
                &m,
                *tick,
                event_name(event),
                paths[next].pieces().len(),
            ));
            rounding = with_rounding(rounding, &paths[next]);
            last_target = target;
            current = next;
            sampler = Sampler::new(&*paths[current]);
            // Its first sample is the one just played.
            let _ = sampler.next();
        }
        // The end of the last move, or of an abort; or of a move that ends moving (a
        // velocity target): a path ends there, so the events after it are not played.
        let moving = last
            .as_ref()
            .is_some_and(|l| l.velocity.iter().any(|v| v.to_f64() != 0.0));
        if sampler.is_finished() && (events.peek().is_none() || moving || control.aborted) {
            break;
        }
        let mut s = sampler.next();
        s.tick = k;
        sink(&s)?;
        last = Some(s);
        k += 1;
    }
    Ok(Moves {
        moves,
        last_target,
        ignored: ignored + events.count(),
        rounding,
    })
}

/// Plays the moves ([`play_moves`]), writing `samples.csv` and measuring.
fn play<N, R, const D: usize>(job: &MoveJob, out: &FsPath) -> Result<Played<D>, RunError>
where
    N: Kernel,
    N::Out: CsvCell,
    R: Real,
{
    let csv_path = out.join("samples.csv");
    let io = |e: std::io::Error| RunError::Io(format!("cannot write {}: {e}", csv_path.display()));
    let mut csv = BufWriter::new(File::create(&csv_path).map_err(io)?);
    writeln!(csv, "{}", csv_header(D)).map_err(io)?;
    let mut measure = Measure::<D>::new(job.rate_hz);
    // Every sample's time and plot channels, recorded once their count is known.
    let mut traces: Vec<(f64, Vec<f64>)> = Vec::new();
    let mut row = String::new();
    let mut checked_from = None;
    let mut samples = 0_u64;
    let mut last = [[0.0; 3]; D];
    let played = play_moves::<N, R, D>(job, &mut |s| {
        let k = s.tick;
        let t = k as f64 / job.rate_hz;
        write_row(&mut row, k, t, s);
        csv.write_all(row.as_bytes()).map_err(io)?;
        let observed = Observed {
            t,
            position: to_f64(&s.position),
            velocity: to_f64(&s.velocity),
            acceleration: to_f64(&s.acceleration),
            reference: to_f64(&s.position),
            curve: to_f64(&s.position),
            tangent: [0.0; D],
        };
        if checked_from.is_none() && settled(job, &observed) {
            checked_from = Some(t);
        }
        // The limits are measured from the first settled sample on.
        let jerk = if checked_from.is_some() {
            measure.push(&observed)
        } else {
            None
        };
        let mut values = Vec::with_capacity(4 * D + 3);
        values.extend_from_slice(&observed.position);
        values.extend_from_slice(&observed.velocity);
        values.push(norm(&observed.velocity));
        values.extend_from_slice(&observed.acceleration);
        values.push(norm(&observed.acceleration));
        match jerk {
            Some(j) => {
                values.extend_from_slice(&j);
                values.push(norm(&j));
            }
            None => values.extend(std::iter::repeat_n(f64::NAN, D + 1)),
        }
        traces.push((t, values));
        last = core::array::from_fn(|i| {
            [
                observed.position[i],
                observed.velocity[i],
                observed.acceleration[i],
            ]
        });
        samples = k + 1;
        Ok(())
    })?;
    csv.flush().map_err(io)?;
    if samples == 0 {
        return Err(RunError::Io("no sample".to_owned()));
    }
    let mut recorder = Recorder::new(D, samples);
    for (t, values) in &traces {
        recorder.push(*t, values);
    }
    Ok(Played {
        moves: played.moves,
        measure,
        recorder,
        samples,
        checked_from,
        last,
        last_target: played.last_target,
        ignored: played.ignored,
        rounding: played.rounding,
    })
}
