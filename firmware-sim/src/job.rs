//! The job file of `strak-sim run`: a path, a control rate, a number format, limits, a time law
//! and optional feed events, in TOML.
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
//!                             # (default 0: none, the feed guard schedules feed events;
//!                             # not for a straight line: see `crate::line`)
//!
//! [[events]]                  # optional, any number; one action each
//! tick = 300
//! feed = 0.5                  # or: hold = true | resume = true | abort = true
//! ```
//!
//! A file with `[[moves]]` in place of `[path]` is a moves job, streamed through the
//! look-ahead planner: see [`crate::moves`].
//!
//! The path and the time law are serde enums tagged by `kind`; every range is checked while
//! deserializing. What serde cannot say ([`Job::check`]: the path's lists, per-axis limits of
//! one entry per axis, one action per event) is checked after. Every problem is reported as
//! one [`JobError`] naming the field (`limits.velocity`, `events[1].feed`,
//! `path.points[3][1]`, …).

use std::fmt;

use serde::{Deserialize, Deserializer, de::Error as _};

use crate::curve_file::CurveFile;
use crate::number::{self, NumberFormat};
use crate::toml_error::{Tagged, locate};
use strak_trajectory::{Event, TimedEvent};

/// The lowest and highest control rates in Hz.
pub const RATE_RANGE: (f64, f64) = (100.0, 100_000.0);

/// The largest number of planner sampling intervals (`profile.samples`).
pub const MAX_PLAN_SAMPLES: usize = 1 << 20;

/// Range checks run while deserializing, so that the error carries the value's place.
mod range {
    use super::{Deserialize, Deserializer, MAX_PLAN_SAMPLES, RATE_RANGE};
    use serde::de::Error as _;

    fn check<'de, D: Deserializer<'de>, T: Deserialize<'de> + Copy>(
        d: D,
        ok: impl Fn(T) -> bool,
        says: impl Fn(T) -> String,
    ) -> Result<T, D::Error> {
        let v = T::deserialize(d)?;
        if ok(v) {
            Ok(v)
        } else {
            Err(D::Error::custom(says(v)))
        }
    }

    fn positive_f64(x: f64) -> bool {
        x.is_finite() && x > 0.0
    }

    pub(super) fn positive<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        check(d, positive_f64, |v: f64| {
            format!("must be finite and > 0, not {v}")
        })
    }

    pub(super) fn some_positive<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
        positive(d).map(Some)
    }

    pub(super) fn rate<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        check(
            d,
            |v: f64| v >= RATE_RANGE.0 && v <= RATE_RANGE.1,
            |v: f64| format!("the control rate must be between 100 Hz and 100 kHz, not {v} Hz"),
        )
    }

    /// A share strictly between 0 and 1.
    pub(super) fn some_share<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
        check(
            d,
            |v: f64| v > 0.0 && v < 1.0,
            |v: f64| format!("must be between 0 and 1 (exclusive), not {v}"),
        )
        .map(Some)
    }

    pub(super) fn some_reserve<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
        check(
            d,
            |v: f64| (0.0..1.0).contains(&v),
            |v: f64| format!("must be at least 0 and below 1, not {v}"),
        )
        .map(Some)
    }

    pub(super) fn some_feed<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
        check(
            d,
            |v: f64| (0.0..=1.0).contains(&v),
            |v: f64| format!("the feed override must be between 0 and 1, not {v}"),
        )
        .map(Some)
    }

    pub(super) fn some_samples<'de, D: Deserializer<'de>>(d: D) -> Result<Option<usize>, D::Error> {
        check(
            d,
            |n: usize| (1..=MAX_PLAN_SAMPLES).contains(&n),
            |n: usize| format!("must be between 1 and {MAX_PLAN_SAMPLES}, not {n}"),
        )
        .map(Some)
    }

    pub(super) fn some_non_negative<'de, D: Deserializer<'de>>(
        d: D,
    ) -> Result<Option<f64>, D::Error> {
        check(
            d,
            |v: f64| v.is_finite() && v >= 0.0,
            |v: f64| format!("must be finite and ≥ 0, not {v}"),
        )
        .map(Some)
    }

    pub(super) fn some_ticks<'de, D: Deserializer<'de>>(d: D) -> Result<Option<u32>, D::Error> {
        check(d, |n: u32| n >= 1, |_| "must be at least 1".to_owned()).map(Some)
    }

    /// `true` (an action flag: leave the event out otherwise).
    pub(super) fn flag<'de, D: Deserializer<'de>>(d: D) -> Result<Option<bool>, D::Error> {
        check(
            d,
            |b: bool| b,
            |_| "must be true (leave the event out otherwise)".to_owned(),
        )
        .map(Some)
    }

    /// Per-axis limits: each > 0, `inf` for none.
    pub(super) fn some_axis_limits<'de, D: Deserializer<'de>>(
        d: D,
    ) -> Result<Option<Vec<f64>>, D::Error> {
        let v = Vec::<f64>::deserialize(d)?;
        match v.iter().position(|x| x.is_nan() || *x <= 0.0) {
            Some(i) => Err(D::Error::custom(format!(
                "limit {i} must be > 0 (inf for none), not {}",
                v[i]
            ))),
            None => Ok(Some(v)),
        }
    }
}

/// The `[limits]` table.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JobLimits {
    /// Path velocity limit (units/s).
    #[serde(deserialize_with = "range::positive")]
    pub velocity: f64,
    /// Acceleration limit (units/s²): the norm of the acceleration in space.
    #[serde(deserialize_with = "range::positive")]
    pub acceleration: f64,
    /// Jerk limit (units/s³): the norm of the jerk in space (S-curve).
    #[serde(deserialize_with = "range::positive")]
    pub jerk: f64,
    /// Per-axis velocity limits, one per axis (`inf`: none).
    #[serde(default, deserialize_with = "range::some_axis_limits")]
    pub axis_velocity: Option<Vec<f64>>,
    /// Per-axis acceleration limits, one per axis (`inf`: none).
    #[serde(default, deserialize_with = "range::some_axis_limits")]
    pub axis_acceleration: Option<Vec<f64>>,
}

impl JobLimits {
    /// `Err` on the per-axis array that does not have one limit for each of `axes` axes;
    /// `whose` names what has them (`the path has`).
    ///
    /// ```
    /// use strak_sim::job::JobLimits;
    /// let l = JobLimits { velocity: 1.0, acceleration: 1.0, jerk: 1.0,
    ///     axis_velocity: Some(vec![1.0; 2]), axis_acceleration: None };
    /// assert!(l.check_axes(2, "the path has").is_ok());
    /// assert_eq!(l.check_axes(3, "the path has").unwrap_err().field, "limits.axis_velocity");
    /// ```
    ///
    /// # Errors
    /// A [`JobError`] naming the array.
    pub fn check_axes(&self, axes: usize, whose: &str) -> Result<(), JobError> {
        for (field, v) in [
            ("limits.axis_velocity", &self.axis_velocity),
            ("limits.axis_acceleration", &self.axis_acceleration),
        ] {
            if let Some(v) = v
                && v.len() != axes
            {
                return Err(JobError::new(
                    field,
                    format!(
                        "one limit per axis: {whose} {axes} axes, {} limits given",
                        v.len()
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// The time laws.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
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

    /// Whether the law is planned under the limits (trapezoid, S-curve): only then does a
    /// run fail when its samples exceed a limit.
    pub fn is_planned(self) -> bool {
        matches!(self, ProfileKind::Trapezoid | ProfileKind::SCurve)
    }
}

/// `kind = "parameter"`.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParameterLaw {
    /// The duration in seconds.
    #[serde(deserialize_with = "range::positive")]
    pub duration: f64,
}

/// `kind = "constant-speed"`.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConstantSpeedLaw {
    /// The speed (default `limits.velocity`).
    #[serde(default, deserialize_with = "range::some_positive")]
    pub speed: Option<f64>,
}

/// `kind = "trapezoid"` and `kind = "s-curve"`: the planner's optional settings.
#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlannerSettings {
    /// Planner sampling intervals (default 1024).
    #[serde(default, deserialize_with = "range::some_samples")]
    pub samples: Option<usize>,
    /// Relative spread of the speed limit inside one zone (default 0.05).
    #[serde(default, deserialize_with = "range::some_non_negative")]
    pub zone_tolerance: Option<f64>,
    /// The share of the acceleration and jerk limits (path and per axis) the turning of the
    /// path may take (default 0.5).
    #[serde(default, deserialize_with = "range::some_share")]
    pub centripetal_share: Option<f64>,
    /// The smallest turn of the tangent at a join that counts as a corner, where the motion
    /// stops (radians, default 10⁻⁴).
    #[serde(default, deserialize_with = "range::some_positive")]
    pub corner_angle: Option<f64>,
}

/// The `[profile]` table: the time law, tagged by `kind`.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Profile {
    /// The curve parameter at a constant rate.
    Parameter(ParameterLaw),
    /// Constant speed along the arc length.
    ConstantSpeed(ConstantSpeedLaw),
    /// Trapezoidal speed under the limits (jerk not limited).
    Trapezoid(PlannerSettings),
    /// Jerk-limited S-curve under the limits.
    SCurve(PlannerSettings),
}

impl Profile {
    /// The kind of time law.
    pub fn kind(&self) -> ProfileKind {
        match self {
            Profile::Parameter(_) => ProfileKind::Parameter,
            Profile::ConstantSpeed(_) => ProfileKind::ConstantSpeed,
            Profile::Trapezoid(_) => ProfileKind::Trapezoid,
            Profile::SCurve(_) => ProfileKind::SCurve,
        }
    }

    /// The planner settings of a trapezoid or S-curve.
    pub fn planner(&self) -> Option<&PlannerSettings> {
        match self {
            Profile::Trapezoid(p) | Profile::SCurve(p) => Some(p),
            _ => None,
        }
    }

    fn diagnose(kind: &str, text: &str) -> Option<toml::de::Error> {
        match kind {
            "parameter" => toml::from_str::<ParameterLaw>(text).err(),
            "constant-speed" => toml::from_str::<ConstantSpeedLaw>(text).err(),
            "trapezoid" | "s-curve" => toml::from_str::<PlannerSettings>(text).err(),
            _ => None,
        }
    }
}

/// The optional `[compile]` table.
#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JobCompile {
    /// Absolute position tolerance in units (default: 1e-4 of the path's extent).
    #[serde(default, deserialize_with = "range::some_positive")]
    pub tolerance: Option<f64>,
    /// The longest piece in ticks (default 256).
    #[serde(default, deserialize_with = "range::some_ticks")]
    pub max_piece_ticks: Option<u32>,
    /// The share of acceleration and jerk reserved for feed changes (default 0: none, feed
    /// events are scheduled by the feed guard).
    #[serde(default, deserialize_with = "range::some_reserve")]
    pub feed_share: Option<f64>,
}

/// One `[[events]]` entry: at `tick`, exactly one action.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JobEvent {
    /// The wall-clock tick (sample number, counted from 0, holds included) before whose
    /// sample the action is applied.
    pub tick: u64,
    /// Feed override in `[0, 1]`.
    #[serde(default, deserialize_with = "range::some_feed")]
    pub feed: Option<f64>,
    /// Feed hold (`true`).
    #[serde(default, deserialize_with = "range::flag")]
    pub hold: Option<bool>,
    /// Resume after a hold (`true`).
    #[serde(default, deserialize_with = "range::flag")]
    pub resume: Option<bool>,
    /// Abort (`true`).
    #[serde(default, deserialize_with = "range::flag")]
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

fn non_empty<'de, D: Deserializer<'de>>(d: D) -> Result<Option<String>, D::Error> {
    let s = String::deserialize(d)?;
    if s.trim().is_empty() {
        Err(D::Error::custom("must not be empty"))
    } else {
        Ok(Some(s))
    }
}

/// A job file.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Job {
    /// Control rate in Hz.
    #[serde(deserialize_with = "range::rate")]
    pub rate_hz: f64,
    /// Number format of the curve and of playback (`f64`, `f32`, or `fixed`: the curve in
    /// `I32F32`, playback in `Q40`; read by [`number::parse`]).
    #[serde(deserialize_with = "number::deserialize")]
    pub number: NumberFormat,
    /// The length unit, for display (default "units").
    #[serde(default, deserialize_with = "non_empty")]
    pub unit: Option<String>,
    /// The curve.
    pub path: CurveFile,
    /// Kinematic limits.
    pub limits: JobLimits,
    /// The time law.
    pub profile: Profile,
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

/// The tables of a job tagged by `kind`.
const TAGGED: [Tagged; 2] = [
    Tagged {
        table: "path",
        diagnose: CurveFile::diagnose,
    },
    Tagged {
        table: "profile",
        diagnose: Profile::diagnose,
    },
];

impl Job {
    /// Parses TOML text and checks every field; the error names the field.
    pub fn parse(text: &str) -> Result<Self, JobError> {
        let job: Job = toml::from_str(text).map_err(|e| {
            let at = locate(text, &e, &TAGGED);
            JobError::new(at.field, at.message)
        })?;
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

    /// The share of acceleration and jerk reserved for feed changes (default 0: the motion
    /// uses the full limits and a [`FeedGuard`](strak_trajectory::FeedGuard) schedules each
    /// feed event).
    pub fn feed_share(&self) -> f64 {
        self.compile.feed_share.unwrap_or(0.0)
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

    /// The events as the event player takes them: sorted by tick, the feed as `f32` (the
    /// sampler's type).
    pub fn timed_events(&self) -> Vec<TimedEvent> {
        self.sorted_events()
            .into_iter()
            .map(|(tick, action)| TimedEvent {
                tick,
                event: match action {
                    Action::Feed(f) => Event::Feed(f as f32),
                    Action::Hold => Event::Hold,
                    Action::Resume => Event::Resume,
                    Action::Abort => Event::Abort,
                },
            })
            .collect()
    }

    /// Checks what serde cannot: the path's lists ([`CurveFile::check`]), one per-axis limit
    /// per axis, and exactly one action per event.
    pub fn check(&self) -> Result<(), JobError> {
        self.path
            .check()
            .map_err(|e| JobError::new(format!("path.{}", e.field), e.message))?;
        let dim = self.axes();
        self.limits.check_axes(dim, "the path has")?;
        for (i, e) in self.events.iter().enumerate() {
            if e.action().is_none() {
                let set = [e.feed.is_some(), e.hold.is_some(), e.resume.is_some()]
                    .into_iter()
                    .chain([e.abort.is_some()])
                    .filter(|s| *s)
                    .count();
                return Err(JobError::new(
                    format!("events[{i}]"),
                    format!("give exactly one of feed, hold, resume, abort (found {set})"),
                ));
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
        assert_eq!(job.number, NumberFormat::F64);
        assert_eq!(job.axes(), 2);
        assert_eq!(job.profile.kind(), ProfileKind::SCurve);
        assert_eq!(job.profile.planner(), Some(&PlannerSettings::default()));
        assert_eq!(job.feed_share(), 0.0);
        assert!(job.events.is_empty());
    }

    #[test]
    fn errors_name_the_field() {
        let cases = [
            (GOOD.replace("rate_hz = 1000\n", ""), "rate_hz"),
            (GOOD.replace("velocity = 100\n", ""), "limits.velocity"),
            (GOOD.replace("rate_hz = 1000", "rate_hz = 0"), "rate_hz"),
            (GOOD.replace("jerk = 10000", "jerk = -1"), "limits.jerk"),
            (
                GOOD.replace("jerk = 10000", "jerk = 1\ncolour = 3"),
                "limits.colour",
            ),
            (
                GOOD.replace("[[0, 0], [10, 0], [10, 10]]", "[]"),
                "path.points",
            ),
            (
                GOOD.replace("[[0, 0], [10, 0], [10, 10]]", "[[0, 0], [1, nan]]"),
                "path.points[1][1]",
            ),
            (GOOD.replace("\"f64\"", "\"f16\""), "number"),
            (
                format!("{GOOD}[[events]]\ntick = 3\nfeed = 2\n"),
                "events[0].feed",
            ),
            (
                format!("{GOOD}[[events]]\ntick = 3\nfeed = 0.5\n[[events]]\ntick = 4\n"),
                "events[1]",
            ),
            (
                format!("{GOOD}[[events]]\ntick = 3\nhold = false\n"),
                "events[0].hold",
            ),
            (
                GOOD.replace("kind = \"s-curve\"", "kind = \"parameter\""),
                "profile.duration",
            ),
            (
                GOOD.replace("kind = \"s-curve\"", "kind = \"parameter\"\nduration = -2"),
                "profile.duration",
            ),
            (
                GOOD.replace("kind = \"s-curve\"", "kind = \"s-curve\"\nsamples = 0"),
                "profile.samples",
            ),
            (
                GOOD.replace("kind = \"s-curve\"", "kind = \"s-curve\"\nspeed = 3"),
                "profile.speed",
            ),
            (
                GOOD.replace(
                    "kind = \"s-curve\"",
                    "kind = \"s-curve\"\nsamples = \"many\"",
                ),
                "profile.samples",
            ),
            (
                GOOD.replace("kind = \"s-curve\"", "kind = \"spiral\""),
                "profile.kind",
            ),
            (
                GOOD.replace("kind = \"bezier\"", "kind = \"bspline\""),
                "path.degree",
            ),
            (
                GOOD.replace("kind = \"bezier\"", "kind = \"bezier\"\nknots = [0, 1]"),
                "path.knots",
            ),
            (
                GOOD.replace("kind = \"bezier\"", "kind = \"bezier\"\ndegree = \"two\""),
                "path.degree",
            ),
            (GOOD.replace("kind = \"bezier\"\n", ""), "path.kind"),
            (
                GOOD.replace("[profile]\nkind = \"s-curve\"", "").replace(
                    "number = \"f64\"",
                    "number = \"f64\"\nprofile = { kind = \"s-curve\", samples = -1 }",
                ),
                "profile.samples",
            ),
            (
                format!("{GOOD}[compile]\nfeed_share = 1.0\n"),
                "compile.feed_share",
            ),
            (
                GOOD.replace("jerk = 10000", "jerk = 10000\naxis_velocity = [1, 0]"),
                "limits.axis_velocity",
            ),
            (
                GOOD.replace("jerk = 10000", "jerk = 10000\naxis_velocity = [1]"),
                "limits.axis_velocity",
            ),
        ];
        for (text, field) in cases {
            assert_eq!(err(&text).field, field, "{text}");
        }
    }
}
