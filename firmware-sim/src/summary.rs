//! The summary of a `strak-sim run`: written as `summary.json` and printed.

use std::fmt;

use serde::Serialize;

use crate::measure::RELATIVE_TOLERANCE;

/// A maximum over the run, where it happened, and the limit it is checked against.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Checked {
    /// The largest value.
    pub max: f64,
    /// The time of the largest value in seconds.
    pub at_s: f64,
    /// The job's limit, if there is one.
    pub limit: Option<f64>,
    /// `max ≤ limit + tolerance`; `None` without a limit.
    pub within: Option<bool>,
    /// What the check allows above the limit: the relative 10⁻⁹ of the `f64` arithmetic, and
    /// for finite differences the resolution of the samples (see [`crate::measure`]).
    pub tolerance: f64,
    /// Whether exceeding the limit fails the run (a limit the time law is planned under).
    pub enforced: bool,
}

impl Checked {
    /// A maximum checked against `limit` (`None` or `inf`: no limit), with the relative
    /// tolerance only, not enforced.
    ///
    /// ```
    /// use strak_sim::summary::Checked;
    /// let c = Checked::new(2.5, 0.1, Some(2.0)).allowing(0.5).enforce(true);
    /// assert_eq!((c.within, c.enforced, c.exceeds()), (Some(true), true, false));
    /// assert!(Checked::new(2.5, 0.1, Some(2.0)).enforce(true).exceeds());
    /// ```
    pub fn new(max: f64, at_s: f64, limit: Option<f64>) -> Self {
        let limit = limit.filter(|l| l.is_finite());
        let tolerance = limit.map_or(0.0, |l| l * RELATIVE_TOLERANCE);
        Checked {
            max,
            at_s,
            limit,
            within: limit.map(|l| max <= l + tolerance),
            tolerance,
            enforced: false,
        }
    }

    /// The same maximum, allowing `slack` more above the limit.
    #[must_use]
    pub fn allowing(self, slack: f64) -> Self {
        let tolerance = self.tolerance + slack;
        Checked {
            within: self.limit.map(|l| self.max <= l + tolerance),
            tolerance,
            ..self
        }
    }

    /// The same maximum, enforced or not (never without a limit).
    #[must_use]
    pub fn enforce(self, enforced: bool) -> Self {
        Checked {
            enforced: enforced && self.limit.is_some(),
            ..self
        }
    }

    /// Whether the maximum exceeds an enforced limit (the run fails).
    pub fn exceeds(&self) -> bool {
        self.enforced && self.within == Some(false)
    }
}

/// Finite differences of the samples of one axis (or the norms over the axes): the
/// velocity `Δx·f` and the acceleration `Δv·f`, next to the sampled values of [`Maxima`].
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Differences {
    /// `x`, `y`, `z`, `w`, `x5`, `x6`, or `path`.
    pub name: String,
    /// `|Δx|·f`.
    pub velocity: Checked,
    /// `|Δv|·f`.
    pub acceleration: Checked,
}

/// The finite differences of the run: the path norms and each axis.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct FiniteDifferences {
    /// The norms over the axes.
    pub path: Differences,
    /// Each axis.
    pub per_axis: Vec<Differences>,
}

/// The distance of the samples from the curve in the job's number format, against the bound
/// the compiled path promises: the compile tolerance plus the playback bound.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Accuracy {
    /// How the curve point of a sample is chosen.
    pub method: String,
    /// The distance against `tolerance + playback_bound`.
    pub distance: Checked,
}

/// Which checks fail a run.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct CheckRule {
    /// The time law is planned under the limits (trapezoid, S-curve): exceeding an enforced
    /// limit or the accuracy bound fails the run (exit code 3).
    pub enforced: bool,
    /// In words.
    pub rule: String,
    /// The relative tolerance of every check.
    pub relative_tolerance: f64,
}

/// The maxima of one axis (or of the path: the Euclidean norms over the axes).
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Maxima {
    /// `x`, `y`, `z`, `w`, `x5`, `x6`, or `path`.
    pub name: String,
    /// Velocity (from the samples).
    pub velocity: Checked,
    /// Acceleration (from the samples).
    pub acceleration: Checked,
    /// Jerk (finite differences of consecutive acceleration samples, times the rate).
    pub jerk: Checked,
}

/// The components the time law plans along the path: with the unit tangent `T` of the f64
/// reference curve at the sample's planned parameter, the
/// tangential acceleration `s̈ = a·T`, the centripetal acceleration `|a − s̈T|` and the
/// tangential jerk `s⃛` (finite differences of `s̈`). The planner bounds `s̈`, `v²κ` and `s⃛`
/// by the limits one by one; the Cartesian norms `|a|`, `|j|` add up their vector sums and the
/// jerk of the turning direction (`2vs̈κ`, `v³·dκ/ds`).
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct AlongPath {
    /// `|s̈|` against the acceleration limit.
    pub tangential_acceleration: Checked,
    /// `v²κ` against the acceleration limit.
    pub centripetal_acceleration: Checked,
    /// `|s⃛|` against the jerk limit.
    pub tangential_jerk: Checked,
}

/// Distance of the samples from the f64 reference curve.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct ReferenceDistance {
    /// How the reference point of a sample is chosen.
    pub method: String,
    /// The largest Euclidean distance.
    pub max: f64,
    /// The time of the largest distance in seconds.
    pub at_s: f64,
}

/// The last sample against the end points.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct EndPoint {
    /// The last sample's position.
    pub last_sample: Vec<f64>,
    /// The path's end point (the curve's end point in the job's number format).
    pub path_end: Vec<f64>,
    /// The end point of the f64 reference curve.
    pub reference_end: Vec<f64>,
    /// `|last sample − path end|` (0: the end is exact).
    pub error_to_path_end: f64,
    /// `|last sample − f64 reference end|` (the rounding of the end point into the format).
    pub error_to_reference_end: f64,
}

/// Wall-clock times of the run's steps in seconds.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct WallTime {
    /// Building the curves and planning the time law; of a stream, the loop that pushes,
    /// polls and plays (its samples are measured beside it, on a second thread).
    pub plan_s: f64,
    /// Compiling the path.
    pub compile_s: f64,
    /// Playing the path (sampler, CSV, statistics); of a stream, the rest of the run before
    /// the plots (reading ahead, and the measuring that outlasts the loop).
    pub play_s: f64,
    /// Writing the plots.
    pub plots_s: f64,
    /// Everything.
    pub total_s: f64,
}

/// The planning limits: the job's limits with acceleration and jerk reduced by the feed share.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct PlannedLimits {
    /// Path velocity.
    pub velocity: f64,
    /// Path acceleration `(1 − feed_share)·a`.
    pub acceleration: f64,
    /// Path jerk `(1 − feed_share)·j`.
    pub jerk: f64,
    /// Per-axis acceleration `(1 − feed_share)·aᵢ` (`None`: no axis limit).
    pub axis_acceleration: Vec<Option<f64>>,
}

/// When one of the job's events took effect.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Applied {
    /// The event's tick in the job.
    pub tick: u64,
    /// The tick it applied at; `None` when the guard found no tick and slow-down that keeps
    /// the limits (the event is left out).
    pub at: Option<u64>,
    /// The slow-down `2⁻ˢʰⁱᶠᵗ` of the feed ramps from then on.
    pub ramp_shift: u8,
}

/// What a G-code program held and how fast it was read and planned
/// ([`crate::gcode_run`]).
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct GcodeReport {
    /// The program's file.
    pub file: String,
    /// Its size in bytes.
    pub bytes: usize,
    /// Its lines.
    pub lines: u32,
    /// Its moves.
    pub moves: usize,
    /// Its dwells (`G4`) and their seconds in all.
    pub dwells: usize,
    /// The seconds of all dwells.
    pub dwell_s: f64,
    /// The axes that rode along the path.
    pub riding_axes: Vec<String>,
    /// The codes read but ignored (`M`, `T`, `S`, unknown `G` codes), each with its count.
    pub ignored: Vec<IgnoredCode>,
    /// Ignored codes beyond the kinds counted one by one.
    pub ignored_others: u32,
    /// Wall-clock seconds of reading the program once (a measurement of this host).
    pub read_s: f64,
    /// Moves read, planned and compiled per wall-clock second of the run's main loop.
    pub planned_moves_per_s: f64,
}

/// An ignored code and how often it occurred.
#[derive(Clone, Debug, Serialize, PartialEq, Eq)]
pub struct IgnoredCode {
    /// The code (`M104`, `T0`, `G28`, …).
    pub code: String,
    /// Its occurrences.
    pub count: u32,
}

/// What the stream of a moves job did ([`crate::stream_run`]).
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct StreamReport {
    /// Moves pushed.
    pub moves: usize,
    /// Corners blended.
    pub blends: usize,
    /// Exact stops at corners (a zero tolerance, a near-reversal).
    pub stops: usize,
    /// The corner blend tolerance ε.
    pub tolerance: f64,
    /// The largest deviation bound of a blend from its corner, against ε.
    pub max_deviation: Checked,
    /// Rests at the end of a move because the next one had not arrived.
    pub starved: usize,
    /// Ticks the sampler held still while moving (the piece queue ran empty).
    pub underruns: u32,
    /// Look-ahead segments.
    pub queue: usize,
    /// Look-ahead zones.
    pub zones: usize,
    /// Pieces the queue between the stream and the sampler holds.
    pub piece_queue: usize,
    /// The rate the moves arrived at (`None`: all at once).
    pub moves_per_second: Option<f64>,
    /// Wall-clock time of pushing, polling and playing per move, in seconds (a measurement
    /// of this host).
    pub planning_per_move_s: f64,
}

/// Everything `strak-sim run` reports.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Summary {
    /// The job's name (file stem).
    pub job: String,
    /// The job's number format: `f64`, `f32` or `fixed`.
    pub number: String,
    /// The playback format and sample type.
    pub playback: String,
    /// Number of axes.
    pub axes: usize,
    /// Length unit.
    pub unit: String,
    /// Control rate in Hz.
    pub rate_hz: f64,
    /// The time law.
    pub profile: String,
    /// Share of acceleration and jerk reserved for feed changes.
    pub feed_share: f64,
    /// The limits the time law was planned with.
    pub planned_with: PlannedLimits,
    /// Duration of the compiled motion (`ticks / rate`).
    pub duration_s: f64,
    /// Duration of the time law before stretching onto the tick grid.
    pub plan_duration_s: f64,
    /// Ticks of the path (samples at feed 1 are `ticks + 1`).
    pub ticks: u32,
    /// Samples written (one per control tick, holds included).
    pub samples: u64,
    /// Time of the last sample in seconds.
    pub run_time_s: f64,
    /// Why the run stopped.
    pub stop: String,
    /// The sampler finished (end of path, or stopped after an abort).
    pub finished: bool,
    /// Events applied.
    pub events_applied: usize,
    /// Events whose tick came after the run had ended.
    pub events_ignored: usize,
    /// The most ticks an event waited for the feed guard (0 on a path with a feed share).
    pub events_late_ticks: u64,
    /// Events the feed guard found no tick for within the limits (left out).
    pub events_refused: usize,
    /// When each of the job's events took effect, and the feed ramps' slow-down from then.
    pub feed_events: Vec<Applied>,
    /// Arc length of the f64 reference curve.
    pub path_length: f64,
    /// Polynomial pieces of the compiled path.
    pub pieces: usize,
    /// The simulator's piece capacity.
    pub piece_capacity: usize,
    /// Position tolerance of the compiled spline.
    pub tolerance: f64,
    /// Bound of the error playback adds in the number format (at feed 1).
    pub playback_bound: f64,
    /// The maxima along the path (norms over the axes).
    pub path: Maxima,
    /// The maxima of the planned components along the path.
    pub along_path: AlongPath,
    /// The maxima of each axis.
    pub per_axis: Vec<Maxima>,
    /// Every maximum with a limit is within it.
    pub limits_respected: bool,
    /// The finite differences of the samples.
    pub finite_differences: FiniteDifferences,
    /// The distance from the curve against the compiled path's bound.
    pub accuracy: Accuracy,
    /// Which checks fail the run.
    pub check: CheckRule,
    /// The enforced checks the run failed, one line each (empty: it passed).
    pub violations: Vec<String>,
    /// Distance from the f64 reference curve.
    pub reference_distance: ReferenceDistance,
    /// The end point.
    pub end_point: EndPoint,
    /// Wall-clock times.
    pub wall_time: WallTime,
    /// The files written.
    pub files: Vec<String>,
    /// The stream's statistics (moves jobs and G-code only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stream: Option<StreamReport>,
    /// The G-code program (G-code only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gcode: Option<GcodeReport>,
}

/// Six significant digits, without trailing zeros; scientific for very small or large values.
pub fn num(x: f64) -> String {
    if x == 0.0 {
        return "0".to_owned();
    }
    if !x.is_finite() {
        return format!("{x}");
    }
    let a = x.abs();
    if !(1e-3..1e7).contains(&a) {
        return format!("{x:.3e}");
    }
    let digits = (5 - a.log10().floor() as i32).max(0) as usize;
    let s = format!("{x:.digits$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        s
    }
}

fn check_mark(c: &Checked) -> &'static str {
    match (c.within, c.enforced) {
        (Some(true), _) => "ok",
        (Some(false), true) => "EXCEEDED",
        (Some(false), false) => "exceeded (not enforced)",
        (None, _) => "",
    }
}

/// The G-code lines of the head.
fn fmt_gcode(f: &mut fmt::Formatter<'_>, g: &GcodeReport) -> fmt::Result {
    let riding = if g.riding_axes.is_empty() {
        String::new()
    } else {
        format!("; {} riding along", g.riding_axes.join(", "))
    };
    writeln!(
        f,
        "  program    {}: {} bytes, {} lines, {} moves, {} dwell(s) of {} s{riding}",
        g.file,
        g.bytes,
        g.lines,
        g.moves,
        g.dwells,
        num(g.dwell_s)
    )?;
    let mut ignored: Vec<String> = g
        .ignored
        .iter()
        .map(|c| format!("{} ×{}", c.code, c.count))
        .collect();
    if g.ignored_others > 0 {
        ignored.push(format!("{} other(s)", g.ignored_others));
    }
    if ignored.is_empty() {
        ignored.push("none".to_owned());
    }
    writeln!(f, "  ignored    {}", ignored.join(", "))?;
    writeln!(
        f,
        "  rate       read in {} s; read, planned and compiled at {} moves/s (wall clock on this host)",
        num(g.read_s),
        num(g.planned_moves_per_s)
    )
}

/// One row of the maxima table.
fn row(f: &mut fmt::Formatter<'_>, what: &str, unit: &str, c: &Checked) -> fmt::Result {
    let line = format!(
        "  {:<22}{:>14}{:>12}{:>14}  {}",
        format!("{what} [{unit}]"),
        num(c.max),
        num(c.at_s),
        c.limit.map_or("-".to_owned(), num),
        check_mark(c)
    );
    writeln!(f, "{}", line.trim_end())
}

impl Summary {
    /// All maxima: the path first, then each axis.
    pub fn all_maxima(&self) -> impl Iterator<Item = &Maxima> {
        std::iter::once(&self.path).chain(self.per_axis.iter())
    }

    /// Every limit check with the name of its quantity: path norms and each axis (samples,
    /// then finite differences), then the components along the path.
    pub fn named_checks(&self) -> Vec<(String, &Checked)> {
        let mut all = Vec::new();
        for m in self.all_maxima() {
            let (v, a, j) = match m.name.as_str() {
                "path" => ("|v|".to_owned(), "|a|".to_owned(), "|j|".to_owned()),
                x => (format!("v_{x}"), format!("a_{x}"), format!("j_{x}")),
            };
            all.push((format!("velocity {v}"), &m.velocity));
            all.push((format!("acceleration {a}"), &m.acceleration));
            all.push((format!("jerk {j} (Δa·f)"), &m.jerk));
        }
        let fd = &self.finite_differences;
        for d in std::iter::once(&fd.path).chain(&fd.per_axis) {
            let x = if d.name == "path" {
                String::new()
            } else {
                format!("_{}", d.name)
            };
            all.push((format!("velocity |Δx{x}|·f"), &d.velocity));
            all.push((format!("acceleration |Δv{x}|·f"), &d.acceleration));
        }
        let along = &self.along_path;
        all.push((
            "tangential acceleration a_t".to_owned(),
            &along.tangential_acceleration,
        ));
        all.push((
            "centripetal acceleration a_n".to_owned(),
            &along.centripetal_acceleration,
        ));
        all.push(("tangential jerk j_t".to_owned(), &along.tangential_jerk));
        all
    }

    /// Every checked figure: path norms, each axis, finite differences, components along the
    /// path.
    pub fn all_checked(&self) -> Vec<&Checked> {
        self.named_checks().into_iter().map(|(_, c)| c).collect()
    }

    /// One line for each enforced check the run failed, naming the quantity (the limits,
    /// then the accuracy bound).
    pub fn find_violations(&self) -> Vec<String> {
        let exceeded = |name: &str, c: &Checked| {
            let limit = c.limit.unwrap_or(f64::NAN);
            format!(
                "{name} = {} at t = {} s exceeds {} by {} % (tolerance {})",
                num(c.max),
                num(c.at_s),
                num(limit),
                num(100.0 * (c.max / limit - 1.0)),
                num(c.tolerance)
            )
        };
        let mut lines: Vec<String> = self
            .named_checks()
            .into_iter()
            .filter(|(_, c)| c.exceeds())
            .map(|(name, c)| exceeded(&name, c))
            .collect();
        if self.events_refused > 0 {
            lines.push(format!(
                "the feed guard found no tick for {} event(s) within the limits (left out)",
                self.events_refused
            ));
        }
        if let Some(s) = &self.stream
            && s.max_deviation.exceeds()
        {
            lines.push(exceeded(
                "blend deviation from its corner",
                &s.max_deviation,
            ));
        }
        if self.accuracy.distance.exceeds() {
            lines.push(exceeded(
                "accuracy: distance to the curve (bound: tolerance + playback bound)",
                &self.accuracy.distance,
            ));
        }
        lines
    }

    fn fmt_head(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let u = &self.unit;
        writeln!(
            f,
            "strak-sim {}: {} — {} axes, {} Hz, {} profile, {} playback",
            if self.gcode.is_some() { "gcode" } else { "run" },
            self.job,
            self.axes,
            num(self.rate_hz),
            self.profile,
            self.playback
        )?;
        writeln!(
            f,
            "  motion     {} s = {} ticks (time law {} s), path length {} {u}",
            num(self.duration_s),
            self.ticks,
            num(self.plan_duration_s),
            num(self.path_length)
        )?;
        let ignored = if self.events_ignored > 0 {
            format!(", {} after the end ignored", self.events_ignored)
        } else {
            String::new()
        };
        let late = if self.events_late_ticks > 0 {
            format!(
                " (the latest {} ticks = {} s late)",
                self.events_late_ticks,
                num(self.events_late_ticks as f64 / self.rate_hz)
            )
        } else {
            String::new()
        };
        writeln!(
            f,
            "  run        {} samples, last at {} s, {} event(s) applied{late}{ignored}; stop: {}",
            self.samples,
            num(self.run_time_s),
            self.events_applied,
            self.stop
        )?;
        if let Some(g) = &self.gcode {
            fmt_gcode(f, g)?;
        }
        if let Some(s) = &self.stream {
            return self.fmt_stream(f, s);
        }
        writeln!(
            f,
            "  compiled   {} pieces (capacity {}), tolerance {} {u}, playback bound {} {u}",
            self.pieces,
            self.piece_capacity,
            num(self.tolerance),
            num(self.playback_bound)
        )?;
        if self.feed_share > 0.0 {
            writeln!(
                f,
                "  planned    with v = {}, a = {}, j = {} (a and j: {} of the limits; the rest is kept for feed changes)",
                num(self.planned_with.velocity),
                num(self.planned_with.acceleration),
                num(self.planned_with.jerk),
                num(1.0 - self.feed_share)
            )
        } else {
            writeln!(
                f,
                "  planned    with v = {}, a = {}, j = {} (the full limits; the feed guard schedules feed changes)",
                num(self.planned_with.velocity),
                num(self.planned_with.acceleration),
                num(self.planned_with.jerk),
            )
        }
    }

    /// The stream's lines of the head.
    fn fmt_stream(&self, f: &mut fmt::Formatter<'_>, s: &StreamReport) -> fmt::Result {
        let u = &self.unit;
        let arrival = s.moves_per_second.map_or_else(
            || "all at once".to_owned(),
            |r| format!("{} moves/s", num(r)),
        );
        writeln!(
            f,
            "  stream     {} moves ({arrival}), {} blends, {} exact stops; look-ahead {} segments, {} zones; {} pieces",
            s.moves, s.blends, s.stops, s.queue, s.zones, self.pieces
        )?;
        writeln!(
            f,
            "  corners    largest deviation {} {u} of ε = {} {u} {}",
            num(s.max_deviation.max),
            num(s.tolerance),
            check_mark(&s.max_deviation)
        )?;
        writeln!(
            f,
            "  starved    {} rest(s) with an empty queue (the next move had not arrived), {} underrun tick(s)",
            s.starved, s.underruns
        )?;
        writeln!(
            f,
            "  planning   {} µs per move (push + poll + play, wall clock on this host)",
            num(s.planning_per_move_s * 1e6)
        )?;
        writeln!(
            f,
            "  planned    with v = {}, a = {}, j = {} (a and j: {} of the limits, the stream's feed share kept back)",
            num(self.planned_with.velocity),
            num(self.planned_with.acceleration),
            num(self.planned_with.jerk),
            num(1.0 - self.feed_share)
        )
    }

    fn fmt_table(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let u = &self.unit;
        writeln!(
            f,
            "  {:<22}{:>14}{:>12}{:>14}",
            "maximum", "value", "at t [s]", "limit"
        )?;
        let units = [format!("{u}/s"), format!("{u}/s²"), format!("{u}/s³")];
        let along = &self.along_path;
        row(
            f,
            "a_t tangential",
            &units[1],
            &along.tangential_acceleration,
        )?;
        row(
            f,
            "a_n centripetal",
            &units[1],
            &along.centripetal_acceleration,
        )?;
        row(f, "j_t tangential", &units[2], &along.tangential_jerk)?;
        for m in self.all_maxima() {
            let name = if m.name == "path" {
                "|·|"
            } else {
                m.name.as_str()
            };
            row(f, &format!("v {name}"), &units[0], &m.velocity)?;
            row(f, &format!("a {name}"), &units[1], &m.acceleration)?;
            row(f, &format!("j {name}"), &units[2], &m.jerk)?;
        }
        let fd = &self.finite_differences.path;
        row(f, "|Δx|·f", &units[0], &fd.velocity)?;
        row(f, "|Δv|·f", &units[1], &fd.acceleration)
    }

    fn fmt_tail(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let u = &self.unit;
        let limits = match (self.limits_respected, self.check.enforced) {
            (true, _) => "all respected",
            (false, true) if self.violations.is_empty() => {
                "exceeded only in checks that are not enforced (see above)"
            }
            (false, true) => "EXCEEDED (see above)",
            (false, false) => {
                "exceeded (see above; not enforced: the time law is not planned under the limits)"
            }
        };
        writeln!(f, "  limits     {limits}")?;
        let a = &self.accuracy.distance;
        let (from, bound) = match self.stream {
            Some(_) => ("the moves", "ε + fit tolerance"),
            None => ("the curve", "tolerance + playback bound"),
        };
        writeln!(
            f,
            "  accuracy   max distance {} {u} from {from} at t = {} s, bound {} {u} ({bound}) {}",
            num(a.max),
            num(a.at_s),
            a.limit.map_or("-".to_owned(), num),
            check_mark(a)
        )?;
        let w = &self.wall_time;
        if self.stream.is_some() {
            writeln!(
                f,
                "  end point  error {} {u} to the last move's end",
                num(self.end_point.error_to_path_end)
            )?;
            writeln!(
                f,
                "  wall time  push + poll + play {} s (measured beside it), other {} s, plots {} s, total {} s",
                num(w.plan_s),
                num(w.play_s),
                num(w.plots_s),
                num(w.total_s)
            )?;
            return write!(f, "  wrote      {}", self.files.join(", "));
        }
        writeln!(
            f,
            "  reference  max distance {} {u} at t = {} s ({})",
            num(self.reference_distance.max),
            num(self.reference_distance.at_s),
            self.reference_distance.method
        )?;
        writeln!(
            f,
            "  end point  error {} {u} to the path's end point, {} {u} to the f64 curve's end point",
            num(self.end_point.error_to_path_end),
            num(self.end_point.error_to_reference_end)
        )?;
        writeln!(
            f,
            "  wall time  plan {} s, compile {} s, play {} s, plots {} s, total {} s",
            num(w.plan_s),
            num(w.compile_s),
            num(w.play_s),
            num(w.plots_s),
            num(w.total_s)
        )?;
        write!(f, "  wrote      {}", self.files.join(", "))
    }
}

impl fmt::Display for Summary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.fmt_head(f)?;
        self.fmt_table(f)?;
        self.fmt_tail(f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_have_six_significant_digits() {
        assert_eq!(num(0.0), "0");
        assert_eq!(num(499.99871234), "499.999");
        assert_eq!(num(1.5), "1.5");
        assert_eq!(num(100000.0), "100000");
        assert_eq!(num(2.5e-7), "2.500e-7");
    }

    #[test]
    fn checked_compares_with_the_limit() {
        assert_eq!(Checked::new(1.0, 0.0, Some(2.0)).within, Some(true));
        assert_eq!(Checked::new(3.0, 0.0, Some(2.0)).within, Some(false));
        assert_eq!(Checked::new(3.0, 0.0, Some(f64::INFINITY)).within, None);
        assert_eq!(Checked::new(3.0, 0.0, None).limit, None);
        let c = Checked::new(2.0 + 3e-9, 0.0, Some(2.0));
        assert_eq!((c.within, c.tolerance), (Some(false), 2e-9));
        assert_eq!(c.clone().allowing(1e-9).within, Some(true));
        assert!(!c.exceeds() && c.enforce(true).exceeds());
    }
}
