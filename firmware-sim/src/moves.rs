//! The moves job of `strak-sim run`: a program of moves (lines, circular arcs, cubic
//! Béziers) streamed through the look-ahead planner ([`Stream`](strak_trajectory::Stream)),
//! in place of a `[path]` curve.
//!
//! ```toml
//! rate_hz = 1000
//! number = "f32"              # f64 | f32 | fixed
//! unit = "mm"                 # optional, for the summary and the plots
//! tolerance = 0.02            # corner blend tolerance ε in units (0: exact stops)
//! faster_stops = true         # optional: stop at a sharp corner where that is faster
//! queue = 32                  # look-ahead segments: 8, 16, 32 or 64 (zones: 4 per segment)
//! start = [0, 0, 0]           # optional, default the origin
//!
//! [limits]                    # as for a path; per-axis arrays of one value per axis
//! velocity = 200
//! acceleration = 3000
//! jerk = 100000
//!
//! [[moves]]
//! line = [10, 0, 0]           # to this point
//! feed = 150                  # optional: the move's largest path velocity (units/s)
//! [[moves]]
//! arc = { to = [20, 10, 0], center = [10, 10, 0], clockwise = false }  # or radius = 10
//! [[moves]]                   # (a negative radius: the longer arc); plane = "xy" | "zx" | "yz"
//! bezier = { to = [30, 0, 0], c1 = [22, 15, 0], c2 = [28, 5, 0] }
//!
//! [produce]                   # optional: the moves arrive at this rate (else all at once)
//! moves_per_second = 50
//! ```
//!
//! The axis count is the length of the first move's point (1 to 6); every point agrees. An
//! arc's end lies on the circle through its start about its centre within the arc
//! tolerance ([`MovesJob::arc_tolerance`]: the blend tolerance, at least 10⁻⁶ units). Every
//! problem is one [`JobError`] naming the move and its field (`moves[2].arc.to`).

use serde::Deserialize;
use strak_curves::{Plane, Turn};
use strak_trajectory::{Error as TrajError, Move, MoveCurve, Shape};

use crate::job::{JobError, JobLimits};
use crate::number::{self, NumberFormat};
use crate::stream_run::StreamSetup;
use crate::toml_error::locate;

/// The look-ahead capacities `queue` may name (segments; the window holds four zones per
/// segment).
pub const QUEUE_SIZES: [usize; 4] = [8, 16, 32, 64];

/// The smallest arc tolerance (units): an arc's end may lie this far off its circle at a
/// blend tolerance of 0.
pub const MIN_ARC_TOLERANCE: f64 = 1e-6;

/// `arc = { … }`.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ArcFile {
    /// The end point.
    pub to: Vec<f64>,
    /// The centre (a point of every axis; its coordinates in the plane count).
    pub center: Option<Vec<f64>>,
    /// The radius (negative: the longer arc).
    pub radius: Option<f64>,
    /// Clockwise (G2) or counter-clockwise (G3, the default).
    #[serde(default)]
    pub clockwise: bool,
    /// `xy` (default), `zx` or `yz`.
    pub plane: Option<String>,
}

/// `bezier = { … }`.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BezierFile {
    /// The end point.
    pub to: Vec<f64>,
    /// The control point after the start.
    pub c1: Vec<f64>,
    /// The control point before the end.
    pub c2: Vec<f64>,
}

/// One `[[moves]]` entry: exactly one shape, and an optional feed.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MoveFile {
    /// A straight line to this point.
    pub line: Option<Vec<f64>>,
    /// A circular arc.
    pub arc: Option<ArcFile>,
    /// A cubic Bézier.
    pub bezier: Option<BezierFile>,
    /// The move's largest path velocity (units/s).
    pub feed: Option<f64>,
}

/// The optional `[produce]` table.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Produce {
    /// Moves that become available per second.
    pub moves_per_second: f64,
}

/// A moves job.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MovesJob {
    /// Control rate in Hz.
    pub rate_hz: f64,
    /// Playback number format (read by [`number::parse`]).
    #[serde(deserialize_with = "number::deserialize")]
    pub number: NumberFormat,
    /// The length unit, for display (default "units").
    pub unit: Option<String>,
    /// Corner blend tolerance ε in units (0: exact stops; default 0).
    #[serde(default)]
    pub tolerance: f64,
    /// Whether a sharp corner comes to an exact stop where that is estimated faster than
    /// its blend ([`StreamOptions::with_faster_stops`](strak_trajectory::StreamOptions::with_faster_stops);
    /// default true; false blends every corner it can).
    #[serde(default = "default_faster_stops")]
    pub faster_stops: bool,
    /// Look-ahead segments ([`QUEUE_SIZES`]; default 32).
    #[serde(default = "default_queue")]
    pub queue: usize,
    /// The start point (default the origin).
    pub start: Option<Vec<f64>>,
    /// Kinematic limits.
    pub limits: JobLimits,
    /// The program.
    pub moves: Vec<MoveFile>,
    /// The rate the moves arrive at (default: all at once).
    pub produce: Option<Produce>,
}

fn default_queue() -> usize {
    32
}

fn default_faster_stops() -> bool {
    true
}

/// Whether the TOML `text` is a moves job (it has `moves` at the top level): `strak-sim run`
/// plays it with [`crate::stream_run`], not as a `[path]` job.
///
/// ```
/// assert!(strak_sim::moves::is_moves_job("[[moves]]\nline = [1]\n"));
/// assert!(!strak_sim::moves::is_moves_job("[path]\nkind = \"bezier\"\n"));
/// ```
pub fn is_moves_job(text: &str) -> bool {
    toml::from_str::<toml::Table>(text).is_ok_and(|t| t.contains_key("moves"))
}

/// `Err` on `field` unless every value of `v` is finite and there are `axes` of them.
fn point(field: &str, v: &[f64], axes: usize) -> Result<(), JobError> {
    if let Some(i) = v.iter().position(|x| !x.is_finite()) {
        return Err(JobError::new(
            format!("{field}[{i}]"),
            format!("must be finite, not {}", v[i]),
        ));
    }
    if v.len() != axes {
        return Err(JobError::new(
            field,
            format!("{} coordinates: the first move's point has {axes}", v.len()),
        ));
    }
    Ok(())
}

/// The plane named `name`.
fn plane(field: &str, name: Option<&str>, axes: usize) -> Result<Plane, JobError> {
    let name = name.unwrap_or("xy");
    let p = match name {
        "xy" => Plane::XY,
        "zx" => Plane::ZX,
        "yz" => Plane::YZ,
        other => {
            return Err(JobError::new(
                field,
                format!("`{other}`: the plane is xy, zx or yz"),
            ));
        }
    };
    if p.first.max(p.second) >= axes {
        return Err(JobError::new(
            field,
            format!("an arc in the {name} plane needs more than {axes} axes"),
        ));
    }
    Ok(p)
}

impl MovesJob {
    /// Parses TOML text and checks every field; the error names the field (`moves[2].arc.to`).
    ///
    /// # Errors
    /// A [`JobError`] naming the field.
    pub fn parse(text: &str) -> Result<Self, JobError> {
        if toml::from_str::<toml::Table>(text).is_ok_and(|t| t.contains_key("path")) {
            return Err(JobError::new(
                "path",
                "a job has either a [path] or [[moves]], not both",
            ));
        }
        let job: MovesJob = toml::from_str(text).map_err(|e| {
            let at = locate(text, &e, &[]);
            JobError::new(at.field, at.message)
        })?;
        job.check()?;
        Ok(job)
    }

    /// The number of axes: the length of the first move's point.
    pub fn axes(&self) -> usize {
        self.moves.first().map_or(0, |m| {
            let to = m.line.as_ref();
            let to = to.or(m.arc.as_ref().map(|a| &a.to));
            to.or(m.bezier.as_ref().map(|b| &b.to)).map_or(0, Vec::len)
        })
    }

    /// The length unit for display.
    pub fn unit(&self) -> &str {
        self.unit.as_deref().unwrap_or("units")
    }

    /// How far an arc's end may lie off the circle through its start: the blend tolerance,
    /// at least [`MIN_ARC_TOLERANCE`].
    pub fn arc_tolerance(&self) -> f64 {
        self.tolerance.max(MIN_ARC_TOLERANCE)
    }

    /// What the job streams on: its rate, format, tolerances, limits and arrival rate, its
    /// axes all path axes.
    pub fn setup(&self) -> StreamSetup {
        let axes = self.axes();
        StreamSetup {
            rate_hz: self.rate_hz,
            number: self.number,
            unit: self.unit().to_owned(),
            tolerance: self.tolerance,
            faster_stops: self.faster_stops,
            queue: self.queue,
            arc_tolerance: self.arc_tolerance(),
            limits: self.limits.clone(),
            moves_per_second: self.produce.as_ref().map(|p| p.moves_per_second),
            axis_names: crate::axes::names(axes)
                .iter()
                .map(|n| (*n).to_owned())
                .collect(),
            path_axes: axes,
        }
    }

    /// The start point in `D` axes.
    pub fn start<const D: usize>(&self) -> [f64; D] {
        let mut p = [0.0; D];
        for (o, x) in p.iter_mut().zip(self.start.iter().flatten()) {
            *o = *x;
        }
        p
    }

    /// Checks what serde cannot: the ranges, the axis counts, one shape per move, finite
    /// points, arcs' ends on their circles, and moves of a length.
    ///
    /// # Errors
    /// A [`JobError`] naming the field.
    pub fn check(&self) -> Result<(), JobError> {
        self.setup().check()?;
        if self.moves.is_empty() {
            return Err(JobError::new("moves", "give at least one move"));
        }
        let axes = self.axes();
        if !(1..=crate::axes::MAX_AXES).contains(&axes) {
            return Err(JobError::new(
                format!("moves[0].{}", self.moves[0].shape_name().unwrap_or("line")),
                "points need 1 to 6 coordinates",
            ));
        }
        self.limits.check_axes(axes, "the moves have")?;
        if let Some(s) = &self.start {
            point("start", s, axes)?;
        }
        match axes {
            1 => check_moves::<1>(self),
            2 => check_moves::<2>(self),
            3 => check_moves::<3>(self),
            4 => check_moves::<4>(self),
            5 => check_moves::<5>(self),
            _ => check_moves::<6>(self),
        }
    }

    /// The moves in `D` axes (checked by [`MovesJob::check`]).
    ///
    /// # Errors
    /// A [`JobError`] naming the move's field.
    pub fn program<const D: usize>(&self) -> Result<Vec<Move<D>>, JobError> {
        self.moves
            .iter()
            .enumerate()
            .map(|(i, m)| m.to_move::<D>(&format!("moves[{i}]")))
            .collect()
    }
}

/// Builds every move's curve from the end of the one before, naming the field of the first
/// that fails.
fn check_moves<const D: usize>(job: &MovesJob) -> Result<(), JobError> {
    let mut from = job.start::<D>();
    for (i, (m, mv)) in job.moves.iter().zip(job.program::<D>()?).enumerate() {
        let field = format!("moves[{i}]");
        m.check_arc(&field, &from, job.arc_tolerance())?;
        MoveCurve::new(from, &mv, job.arc_tolerance())
            .map_err(|e| m.curve_error(&field, &from, e))?;
        from = mv.to;
    }
    Ok(())
}

impl MoveFile {
    /// The name of the move's shape (`None` unless exactly one is given).
    pub fn shape_name(&self) -> Option<&'static str> {
        match (&self.line, &self.arc, &self.bezier) {
            (Some(_), None, None) => Some("line"),
            (None, Some(_), None) => Some("arc"),
            (None, None, Some(_)) => Some("bezier"),
            _ => None,
        }
    }

    /// The move in `D` axes, its values checked (`field`: `moves[i]`).
    ///
    /// # Errors
    /// A [`JobError`] naming the field: not one shape, a non-finite value, a point of
    /// another axis count, a bad plane, a feed that is not positive.
    pub fn to_move<const D: usize>(&self, field: &str) -> Result<Move<D>, JobError> {
        let Some(name) = self.shape_name() else {
            let found = [
                self.line.is_some(),
                self.arc.is_some(),
                self.bezier.is_some(),
            ];
            return Err(JobError::new(
                field,
                format!(
                    "give exactly one of line, arc, bezier (found {})",
                    found.iter().filter(|x| **x).count()
                ),
            ));
        };
        let at = |key: &str| format!("{field}.{name}{key}");
        let arr = |v: &[f64], key: &str| -> Result<[f64; D], JobError> {
            point(&at(key), v, D)?;
            let mut p = [0.0; D];
            p.copy_from_slice(v);
            Ok(p)
        };
        let mv = match (&self.line, &self.arc, &self.bezier) {
            (Some(to), _, _) => Move::line(arr(to, "")?),
            (_, Some(a), _) => Move::new(arr(&a.to, ".to")?, self.arc_shape::<D>(a, field)?),
            (_, _, Some(b)) => Move::new(
                arr(&b.to, ".to")?,
                Shape::Bezier {
                    c1: arr(&b.c1, ".c1")?,
                    c2: arr(&b.c2, ".c2")?,
                },
            ),
            _ => unreachable!("one shape, by shape_name"),
        };
        match self.feed {
            None => Ok(mv),
            Some(f) if f.is_finite() && f > 0.0 => Ok(mv.with_feed(f)),
            Some(f) => Err(JobError::new(
                format!("{field}.feed"),
                format!("must be finite and > 0, not {f}"),
            )),
        }
    }

    fn arc_shape<const D: usize>(&self, a: &ArcFile, field: &str) -> Result<Shape<D>, JobError> {
        let p = plane(&format!("{field}.arc.plane"), a.plane.as_deref(), D)?;
        let turn = if a.clockwise {
            Turn::Clockwise
        } else {
            Turn::CounterClockwise
        };
        match (&a.center, a.radius) {
            (Some(c), None) => {
                point(&format!("{field}.arc.center"), c, D)?;
                Ok(Shape::ArcCenter {
                    center: [c[p.first], c[p.second]],
                    plane: p,
                    turn,
                })
            }
            (None, Some(radius)) if radius.is_finite() && radius != 0.0 => Ok(Shape::ArcRadius {
                radius,
                plane: p,
                turn,
            }),
            (None, Some(radius)) => Err(JobError::new(
                format!("{field}.arc.radius"),
                format!("must be finite and not 0, not {radius}"),
            )),
            _ => Err(JobError::new(
                format!("{field}.arc"),
                "give exactly one of center and radius",
            )),
        }
    }

    /// An arc about a centre: the centre off the start, the end on the circle through the
    /// start within `tolerance`.
    fn check_arc<const D: usize>(
        &self,
        field: &str,
        from: &[f64; D],
        tolerance: f64,
    ) -> Result<(), JobError> {
        let Some(a) = &self.arc else { return Ok(()) };
        let Some(c) = &a.center else { return Ok(()) };
        let p = plane(&format!("{field}.arc.plane"), a.plane.as_deref(), D)?;
        let radius = |x: &[f64]| (x[p.first] - c[p.first]).hypot(x[p.second] - c[p.second]);
        let (r0, r1) = (radius(from), radius(&a.to));
        if r0 == 0.0 {
            return Err(JobError::new(
                format!("{field}.arc.center"),
                "the centre lies on the start point",
            ));
        }
        if (r1 - r0).abs() > tolerance {
            return Err(JobError::new(
                format!("{field}.arc.to"),
                format!(
                    "the end is {} units from the centre, the start {}: off the circle by {} \
                     (more than the tolerance {})",
                    crate::summary::num(r1),
                    crate::summary::num(r0),
                    crate::summary::num((r1 - r0).abs()),
                    crate::summary::num(tolerance)
                ),
            ));
        }
        Ok(())
    }

    /// A curve error of the move from `from` as an error on its field.
    fn curve_error<const D: usize>(&self, field: &str, from: &[f64; D], e: TrajError) -> JobError {
        let name = self.shape_name().unwrap_or("line");
        let (key, message) = match (&e, &self.bezier) {
            (TrajError::DegenerateMove, Some(b)) if b.c1 == from.as_slice() => (
                ".c1",
                "the first control point lies on the start: the tangent vanishes there".to_owned(),
            ),
            (TrajError::DegenerateMove, Some(b)) if b.c2 == b.to => (
                ".c2",
                "the second control point lies on the end: the tangent vanishes there".to_owned(),
            ),
            (TrajError::DegenerateMove, _) => (
                if name == "line" { "" } else { ".to" },
                "the move has zero length (it ends where it starts)".to_owned(),
            ),
            (_, _) if self.arc.as_ref().is_some_and(|a| a.radius.is_some()) => {
                (".radius", format!("the arc cannot be built: {e}"))
            }
            (_, _) => (
                if name == "line" { "" } else { ".to" },
                format!("the move cannot be built: {e}"),
            ),
        };
        JobError::new(format!("{field}.{name}{key}"), message)
    }
}

/// A push error of the stream as an error on move `index`.
pub fn push_error(index: usize, e: TrajError) -> JobError {
    JobError::new(
        format!("moves[{index}]"),
        format!("the stream refused the move: {e}"),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = r#"
rate_hz = 1000
number = "f64"
tolerance = 0.02
[limits]
velocity = 200
acceleration = 3000
jerk = 100000
[[moves]]
line = [10, 0, 0]
feed = 150
[[moves]]
arc = { to = [20, 10, 0], center = [10, 10, 0], clockwise = false }
[[moves]]
bezier = { to = [30, 0, 0], c1 = [22, 15, 0], c2 = [28, 5, 0] }
"#;

    fn field(text: &str) -> String {
        MovesJob::parse(text).unwrap_err().field
    }

    #[test]
    fn parses_a_program() {
        let job = MovesJob::parse(GOOD).unwrap();
        assert_eq!((job.axes(), job.queue, job.setup().zones()), (3, 32, 128));
        let p = job.program::<3>().unwrap();
        assert_eq!(p[0], Move::line([10.0, 0.0, 0.0]).with_feed(150.0));
        assert!(matches!(
            p[1].shape,
            Shape::ArcCenter {
                center: [10.0, 10.0],
                ..
            }
        ));
        assert!(is_moves_job(GOOD));
    }

    #[test]
    fn errors_name_the_move_and_field() {
        let cases = [
            (
                GOOD.replace("line = [10, 0, 0]", "line = [0, 0, 0]"),
                "moves[0].line",
            ),
            (
                GOOD.replace("[20, 10, 0], center", "[20, 11, 0], center"),
                "moves[1].arc.to",
            ),
            (
                GOOD.replace("c1 = [22, 15, 0]", "c1 = [22, nan, 0]"),
                "moves[2].bezier.c1[1]",
            ),
            (
                GOOD.replace(
                    "feed = 150",
                    "bezier = { to = [1, 1, 1], c1 = [1, 2, 3], c2 = [3, 2, 1] }",
                ),
                "moves[0]",
            ),
            (
                GOOD.replace("[30, 0, 0], c1", "[30, 0], c1"),
                "moves[2].bezier.to",
            ),
            (
                GOOD.replace("queue", "q")
                    .replace("tolerance = 0.02", "queue = 12"),
                "queue",
            ),
            (GOOD.replace("feed = 150", "feed = -1"), "moves[0].feed"),
            (format!("{GOOD}[path]\nkind = \"bezier\"\n"), "path"),
            (
                GOOD.replace("center = [10, 10, 0]", "center = [10, 0, 0]"),
                "moves[1].arc.center",
            ),
        ];
        for (text, want) in cases {
            assert_eq!(field(&text), want, "{text}");
        }
    }
}
