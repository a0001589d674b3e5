//! The job file of `strak-sim run`: a path, a control rate, a number format, limits, a time law
//! and optional feed events, in TOML, checked field by field.
//!
//! ```toml
//! rate_hz = 1000              # control rate, 100 ..= 100000 Hz
//! number = "f64"              # f64 | f32 | fixed (Q40 playback, samples as I32F32)
//! unit = "mm"                 # optional, for the summary and the plots (default "units")
//!
//! [path]                      # the curve file format of `strak-sim sample`
//! kind = "bspline"
//! degree = 3
//! points = [[0, 0, 0], [0, 0, 80], [300, 150, 80], [300, 150, 0]]
//!
//! [limits]                    # path units and seconds; all > 0
//! velocity = 500              # |v| along the path
//! acceleration = 5000         # |a| in space (tangential and centripetal together)
//! jerk = 100000               # |j|
//! axis_velocity = [500, 500, 250]        # optional, one per axis (inf: none)
//! axis_acceleration = [5000, 5000, 2500] # optional, one per axis (inf: none)
//!
//! [profile]
//! kind = "s-curve"            # parameter | constant-speed | trapezoid | s-curve
//! # parameter:      duration = 2.0 (seconds, required)
//! # constant-speed: speed = 100.0 (optional, default limits.velocity)
//! # trapezoid, s-curve: samples = 1024, zone_tolerance = 0.05,
//! #                     centripetal_share = 0.5, corner_angle = 1e-4 (radians; optional
//! #                     planner settings)
//!
//! [compile]                   # optional
//! tolerance = 0.001           # position tolerance in units (default 1e-4 of the extent)
//! max_piece_ticks = 256       # longest polynomial piece in ticks
//! feed_share = 0.25           # share of acceleration and jerk reserved for feed changes
//!
//! [[events]]                  # optional, any number; one action each
//! tick = 300
//! feed = 0.5                  # or: hold = true | resume = true | abort = true
//! ```
//!
//! Every problem is reported as one [`JobError`] naming the field (`limits.velocity`,
//! `events[1].feed`, `path.points`, …).

use std::fmt;

use serde::Deserialize;

use crate::curve_file::CurveFile;
use crate::sample::Number as CurveNumber;

/// The lowest and highest control rates in Hz.
pub const RATE_RANGE: (f64, f64) = (100.0, 100_000.0);

/// The largest number of planner sampling intervals (`profile.samples`).
pub const MAX_PLAN_SAMPLES: usize = 1 << 20;

/// The number format of playback.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum JobNumber {
    /// The curve in `f64`, playback in `f64`.
    F64,
    /// The curve in `f32`, playback in `f32`.
    F32,
    /// The curve in `I32F32`, playback in `Q40` (Q23.40), samples as `I32F32`.
    Fixed,
}

impl JobNumber {
    /// The name used in the file.
    pub fn name(self) -> &'static str {
        match self {
            JobNumber::F64 => "f64",
            JobNumber::F32 => "f32",
            JobNumber::Fixed => "fixed",
        }
    }

    /// The number format the curve is built in (the format of `strak-sim sample`).
    pub fn curve_number(self) -> CurveNumber {
        match self {
            JobNumber::F64 => CurveNumber::F64,
            JobNumber::F32 => CurveNumber::F32,
            JobNumber::Fixed => CurveNumber::Fixed,
        }
    }
}

/// The `[limits]` table.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JobLimits {
    /// Path velocity limit (units/s).
    pub velocity: f64,
    /// Acceleration limit (units/s²): the norm of the acceleration in space.
    pub acceleration: f64,
    /// Jerk limit (units/s³): the norm of the jerk in space (S-curve).
    pub jerk: f64,
    /// Per-axis velocity limits, one per axis (`inf`: none).
    pub axis_velocity: Option<Vec<f64>>,
    /// Per-axis acceleration limits, one per axis (`inf`: none).
    pub axis_acceleration: Option<Vec<f64>>,
}

/// The time laws.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ProfileKind {
    /// The curve parameter at a constant rate over `duration` seconds.
    Parameter,
    /// Constant speed along the arc length.
    ConstantSpeed,
    /// Trapezoidal speed, rest to rest, under the limits (jerk not limited).
    Trapezoid,
    /// Jerk-limited S-curve, rest to rest, under the limits.
    SCurve,
}

impl ProfileKind {
    /// The name used in the file.
    pub fn name(self) -> &'static str {
        match self {
            ProfileKind::Parameter => "parameter",
            ProfileKind::ConstantSpeed => "constant-speed",
            ProfileKind::Trapezoid => "trapezoid",
            ProfileKind::SCurve => "s-curve",
        }
    }
}

/// The `[profile]` table.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JobProfile {
    /// The time law.
    pub kind: ProfileKind,
    /// Parameter law: the duration in seconds.
    pub duration: Option<f64>,
    /// Constant speed: the speed (default `limits.velocity`).
    pub speed: Option<f64>,
    /// Trapezoid, S-curve: planner sampling intervals (default 1024).
    pub samples: Option<usize>,
    /// Trapezoid, S-curve: relative spread of the speed limit inside one zone (default 0.05).
    pub zone_tolerance: Option<f64>,
    /// Trapezoid, S-curve: the share of the acceleration and jerk limits (path and per
    /// axis) the turning of the path may take (default 0.5).
    pub centripetal_share: Option<f64>,
    /// Trapezoid, S-curve: the smallest turn of the tangent at a join that counts as a
    /// corner, where the motion stops (radians, default 10⁻⁴).
    pub corner_angle: Option<f64>,
}

/// The optional `[compile]` table.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JobCompile {
    /// Absolute position tolerance in units (default: 1e-4 of the path's extent).
    pub tolerance: Option<f64>,
    /// The longest piece in ticks (default 256).
    pub max_piece_ticks: Option<u32>,
    /// The share of acceleration and jerk reserved for feed changes (default 0.25).
    pub feed_share: Option<f64>,
}

/// One `[[events]]` entry: at `tick`, exactly one action.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JobEvent {
    /// The wall-clock tick (sample number, counted from 0, holds included) before whose
    /// sample the action is applied.
    pub tick: u64,
    /// Feed override in `[0, 1]`.
    pub feed: Option<f64>,
    /// Feed hold (`true`).
    pub hold: Option<bool>,
    /// Resume after a hold (`true`).
    pub resume: Option<bool>,
    /// Abort (`true`).
    pub abort: Option<bool>,
}

/// The action of an event.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Action {
    /// Feed override.
    Feed(f64),
    /// Feed hold.
    Hold,
    /// Resume.
    Resume,
    /// Abort.
    Abort,
}

impl JobEvent {
    /// The event's action (checked by [`Job::check`]: exactly one is set).
    pub fn action(&self) -> Option<Action> {
        match (self.feed, self.hold, self.resume, self.abort) {
            (Some(f), None, None, None) => Some(Action::Feed(f)),
            (None, Some(true), None, None) => Some(Action::Hold),
            (None, None, Some(true), None) => Some(Action::Resume),
            (None, None, None, Some(true)) => Some(Action::Abort),
            _ => None,
        }
    }
}

/// A job file.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Job {
    /// Control rate in Hz.
    pub rate_hz: f64,
    /// Number format of the curve and of playback.
    pub number: JobNumber,
    /// The length unit, for display (default "units").
    pub unit: Option<String>,
    /// The curve.
    pub path: CurveFile,
    /// Kinematic limits.
    pub limits: JobLimits,
    /// The time law.
    pub profile: JobProfile,
    /// Compiler settings.
    #[serde(default)]
    pub compile: JobCompile,
    /// Feed events.
    #[serde(default)]
    pub events: Vec<JobEvent>,
}

/// A problem with one field of a job file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct JobError {
    /// The field's path in the file (`rate_hz`, `limits.velocity`, `events[0].feed`, …).
    pub field: String,
    /// What is wrong with it.
    pub message: String,
}

impl JobError {
    /// A new error for `field`.
    pub fn new(field: impl Into<String>, message: impl Into<String>) -> Self {
        JobError {
            field: field.into(),
            message: message.into(),
        }
    }
}

impl fmt::Display for JobError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "field `{}`: {}", self.field, self.message)
    }
}

impl std::error::Error for JobError {}

fn positive(x: f64) -> bool {
    x.is_finite() && x > 0.0
}

/// The table a byte offset of `text` lies in (`limits`, `events[2]`, or "" at the top), from
/// the headers before it.
fn table_at(text: &str, offset: usize) -> String {
    let mut table = String::new();
    let mut arrays: Vec<(String, usize)> = Vec::new();
    for line in text[..offset].lines() {
        let l = line.trim();
        if let Some(name) = l.strip_prefix("[[").and_then(|r| r.split("]]").next()) {
            let name = name.trim().to_owned();
            let index = match arrays.iter_mut().find(|(n, _)| *n == name) {
                Some((_, count)) => {
                    *count += 1;
                    *count - 1
                }
                None => {
                    arrays.push((name.clone(), 1));
                    0
                }
            };
            table = format!("{name}[{index}]");
        } else if let Some(name) = l.strip_prefix('[').and_then(|r| r.split(']').next()) {
            table = name.trim().to_owned();
        }
    }
    table
}

fn join(table: &str, key: &str) -> String {
    if table.is_empty() {
        key.to_owned()
    } else {
        format!("{table}.{key}")
    }
}

/// The required fields of each table of a job file.
const REQUIRED: [(&str, &[&str]); 5] = [
    ("", &["rate_hz", "number", "path", "limits", "profile"]),
    ("path", &["kind", "points"]),
    ("limits", &["velocity", "acceleration", "jerk"]),
    ("profile", &["kind"]),
    ("events", &["tick"]),
];

/// The table (as `limits`, `events[1]`, or "" for the top level) that lacks the required field
/// `field`, found in the parsed document.
fn table_missing(text: &str, field: &str) -> Option<String> {
    let doc: toml::Table = toml::from_str(text).ok()?;
    for (table, required) in REQUIRED {
        if !required.contains(&field) {
            continue;
        }
        match table {
            "" => {
                if !doc.contains_key(field) {
                    return Some(String::new());
                }
            }
            "events" => {
                let events = doc.get("events").and_then(toml::Value::as_array)?;
                for (i, e) in events.iter().enumerate() {
                    if e.as_table().is_some_and(|t| !t.contains_key(field)) {
                        return Some(format!("events[{i}]"));
                    }
                }
            }
            name => {
                if let Some(t) = doc.get(name).and_then(toml::Value::as_table)
                    && !t.contains_key(field)
                {
                    return Some(name.to_owned());
                }
            }
        }
    }
    None
}

/// One error line naming the field, from toml's error (its message spans several lines with a
/// source excerpt: only the first is kept).
fn parse_error(text: &str, e: &toml::de::Error) -> JobError {
    let msg = e
        .message()
        .trim()
        .lines()
        .next()
        .unwrap_or_default()
        .to_owned();
    let quoted = |prefix: &str| {
        msg.strip_prefix(prefix)
            .and_then(|r| r.split('`').next())
            .map(str::to_owned)
    };
    if let Some(field) = quoted("missing field `") {
        let table = table_missing(text, &field).unwrap_or_default();
        return JobError::new(join(&table, &field), msg);
    }
    let Some(span) = e.span() else {
        return JobError::new("job", msg);
    };
    let start = span.start.min(text.len());
    let line = text[..start].lines().count().max(1);
    let table = table_at(text, start);
    if let Some(field) = quoted("unknown field `") {
        return JobError::new(join(&table, &field), format!("line {line}: {msg}"));
    }
    // The key of the line the error is on.
    let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
    let line_end = text[start..].find('\n').map_or(text.len(), |i| start + i);
    let line_text = &text[line_start..line_end];
    match line_text.split_once('=') {
        Some((key, _)) if !key.trim().is_empty() && !key.contains('[') => {
            JobError::new(join(&table, key.trim()), format!("line {line}: {msg}"))
        }
        _ if !table.is_empty() => JobError::new(table, format!("line {line}: {msg}")),
        _ => JobError::new("job", format!("line {line}: {msg}")),
    }
}

impl Job {
    /// Parses TOML text and checks every field; the error names the field.
    pub fn parse(text: &str) -> Result<Self, JobError> {
        let job: Job = toml::from_str(text).map_err(|e| parse_error(text, &e))?;
        job.check()?;
        Ok(job)
    }

    /// The number of axes (coordinates per point of the path).
    pub fn axes(&self) -> usize {
        self.path.dim()
    }

    /// The length unit for display.
    pub fn unit(&self) -> &str {
        self.unit.as_deref().unwrap_or("units")
    }

    /// The share of acceleration and jerk reserved for feed changes.
    pub fn feed_share(&self) -> f64 {
        self.compile
            .feed_share
            .unwrap_or(strak_trajectory::CompileOptions::DEFAULT_FEED_SHARE)
    }

    /// The events sorted by tick (stable: events of one tick in file order).
    pub fn sorted_events(&self) -> Vec<(u64, Action)> {
        let mut events: Vec<(u64, Action)> = self
            .events
            .iter()
            .filter_map(|e| e.action().map(|a| (e.tick, a)))
            .collect();
        events.sort_by_key(|(tick, _)| *tick);
        events
    }

    /// Checks every field that does not need the curve built.
    pub fn check(&self) -> Result<(), JobError> {
        self.path
            .check()
            .map_err(|e| JobError::new(format!("path.{}", e.field), e.message))?;
        let dim = self.axes();
        if !positive(self.rate_hz) {
            return Err(JobError::new(
                "rate_hz",
                format!("must be a positive rate in Hz, not {}", self.rate_hz),
            ));
        }
        if !(self.rate_hz >= RATE_RANGE.0 && self.rate_hz <= RATE_RANGE.1) {
            return Err(JobError::new(
                "rate_hz",
                format!(
                    "the control rate must be between 100 Hz and 100 kHz, not {} Hz",
                    self.rate_hz
                ),
            ));
        }
        if let Some(u) = &self.unit
            && u.trim().is_empty()
        {
            return Err(JobError::new("unit", "must not be empty"));
        }
        let l = &self.limits;
        for (field, v) in [
            ("limits.velocity", l.velocity),
            ("limits.acceleration", l.acceleration),
            ("limits.jerk", l.jerk),
        ] {
            if !positive(v) {
                return Err(JobError::new(
                    field,
                    format!("must be finite and > 0, not {v}"),
                ));
            }
        }
        for (field, axes) in [
            ("limits.axis_velocity", &l.axis_velocity),
            ("limits.axis_acceleration", &l.axis_acceleration),
        ] {
            if let Some(axes) = axes {
                if axes.len() != dim {
                    return Err(JobError::new(
                        field,
                        format!(
                            "one limit per axis: the path has {dim} axes, {} limits given",
                            axes.len()
                        ),
                    ));
                }
                if let Some((i, v)) = axes
                    .iter()
                    .enumerate()
                    .find(|(_, v)| v.is_nan() || **v <= 0.0)
                {
                    return Err(JobError::new(
                        field,
                        format!("limit {i} must be > 0 (inf for none), not {v}"),
                    ));
                }
            }
        }
        self.check_profile()?;
        self.check_compile()?;
        self.check_events()
    }

    fn check_profile(&self) -> Result<(), JobError> {
        use ProfileKind::*;
        let p = &self.profile;
        let k = p.kind;
        let uses = |field: &str, present: bool, allowed: &[ProfileKind]| {
            if present && !allowed.contains(&k) {
                Err(JobError::new(
                    format!("profile.{field}"),
                    format!("does not apply to kind `{}`", k.name()),
                ))
            } else {
                Ok(())
            }
        };
        uses("duration", p.duration.is_some(), &[Parameter])?;
        uses("speed", p.speed.is_some(), &[ConstantSpeed])?;
        uses("samples", p.samples.is_some(), &[Trapezoid, SCurve])?;
        uses(
            "zone_tolerance",
            p.zone_tolerance.is_some(),
            &[Trapezoid, SCurve],
        )?;
        uses(
            "centripetal_share",
            p.centripetal_share.is_some(),
            &[Trapezoid, SCurve],
        )?;
        uses(
            "corner_angle",
            p.corner_angle.is_some(),
            &[Trapezoid, SCurve],
        )?;
        match (k, p.duration) {
            (Parameter, None) => {
                return Err(JobError::new(
                    "profile.duration",
                    "required for kind `parameter` (seconds)",
                ));
            }
            (_, Some(d)) if !positive(d) => {
                return Err(JobError::new(
                    "profile.duration",
                    format!("must be finite and > 0 seconds, not {d}"),
                ));
            }
            _ => {}
        }
        if let Some(v) = p.speed
            && !positive(v)
        {
            return Err(JobError::new(
                "profile.speed",
                format!("must be finite and > 0, not {v}"),
            ));
        }
        if let Some(n) = p.samples
            && !(1..=MAX_PLAN_SAMPLES).contains(&n)
        {
            return Err(JobError::new(
                "profile.samples",
                format!("must be between 1 and {MAX_PLAN_SAMPLES}, not {n}"),
            ));
        }
        if let Some(t) = p.zone_tolerance
            && !(t.is_finite() && t >= 0.0)
        {
            return Err(JobError::new(
                "profile.zone_tolerance",
                format!("must be finite and ≥ 0, not {t}"),
            ));
        }
        if let Some(s) = p.centripetal_share
            && !(s > 0.0 && s < 1.0)
        {
            return Err(JobError::new(
                "profile.centripetal_share",
                format!("must be between 0 and 1 (exclusive), not {s}"),
            ));
        }
        if let Some(a) = p.corner_angle
            && !positive(a)
        {
            return Err(JobError::new(
                "profile.corner_angle",
                format!("must be finite and > 0 radians, not {a}"),
            ));
        }
        Ok(())
    }

    fn check_compile(&self) -> Result<(), JobError> {
        let c = &self.compile;
        if let Some(t) = c.tolerance
            && !positive(t)
        {
            return Err(JobError::new(
                "compile.tolerance",
                format!("must be finite and > 0, not {t}"),
            ));
        }
        if c.max_piece_ticks == Some(0) {
            return Err(JobError::new(
                "compile.max_piece_ticks",
                "must be at least 1",
            ));
        }
        if let Some(s) = c.feed_share
            && !(s > 0.0 && s < 1.0)
        {
            return Err(JobError::new(
                "compile.feed_share",
                format!("must be between 0 and 1 (exclusive), not {s}"),
            ));
        }
        Ok(())
    }

    fn check_events(&self) -> Result<(), JobError> {
        for (i, e) in self.events.iter().enumerate() {
            let set = [
                e.feed.is_some(),
                e.hold.is_some(),
                e.resume.is_some(),
                e.abort.is_some(),
            ]
            .iter()
            .filter(|s| **s)
            .count();
            if set != 1 {
                return Err(JobError::new(
                    format!("events[{i}]"),
                    format!("give exactly one of feed, hold, resume, abort (found {set})"),
                ));
            }
            if let Some(f) = e.feed
                && !(0.0..=1.0).contains(&f)
            {
                return Err(JobError::new(
                    format!("events[{i}].feed"),
                    format!("the feed override must be between 0 and 1, not {f}"),
                ));
            }
            for (name, v) in [("hold", e.hold), ("resume", e.resume), ("abort", e.abort)] {
                if v == Some(false) {
                    return Err(JobError::new(
                        format!("events[{i}].{name}"),
                        "must be true (leave the event out otherwise)",
                    ));
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = r#"
rate_hz = 1000
number = "f64"
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

    fn err(text: &str) -> JobError {
        Job::parse(text).unwrap_err()
    }

    #[test]
    fn parses_a_job() {
        let job = Job::parse(GOOD).unwrap();
        assert_eq!(job.rate_hz, 1000.0);
        assert_eq!(job.number, JobNumber::F64);
        assert_eq!(job.axes(), 2);
        assert_eq!(job.profile.kind, ProfileKind::SCurve);
        assert_eq!(job.feed_share(), 0.25);
        assert!(job.events.is_empty());
    }

    #[test]
    fn errors_name_the_field() {
        assert_eq!(err(&GOOD.replace("rate_hz = 1000\n", "")).field, "rate_hz");
        assert_eq!(
            err(&GOOD.replace("velocity = 100\n", "")).field,
            "limits.velocity"
        );
        assert_eq!(
            err(&GOOD.replace("rate_hz = 1000", "rate_hz = 0")).field,
            "rate_hz"
        );
        assert_eq!(
            err(&GOOD.replace("jerk = 10000", "jerk = -1")).field,
            "limits.jerk"
        );
        assert_eq!(
            err(&GOOD.replace("jerk = 10000", "jerk = 1\ncolour = 3")).field,
            "limits.colour"
        );
        assert_eq!(
            err(&GOOD.replace("points = [[0, 0], [10, 0], [10, 10]]", "points = []")).field,
            "path.points"
        );
        assert_eq!(err(&GOOD.replace("\"f64\"", "\"f16\"")).field, "number");
        assert_eq!(
            err(&format!("{GOOD}[[events]]\ntick = 3\nfeed = 2\n")).field,
            "events[0].feed"
        );
        assert_eq!(
            err(&format!(
                "{GOOD}[[events]]\ntick = 3\nfeed = 0.5\n[[events]]\ntick = 4\n"
            ))
            .field,
            "events[1]"
        );
        assert_eq!(
            err(&GOOD.replace("kind = \"s-curve\"", "kind = \"parameter\"")).field,
            "profile.duration"
        );
    }
}
