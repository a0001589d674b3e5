//! The machine file of `strak-sim gcode`: what a G-code program is played on.
//!
//! ```toml
//! rate_hz = 1000
//! number = "f32"                  # f64 | f32 | fixed
//! unit = "mm"                     # optional (default "mm"), for the summary and the plots
//! tolerance = 0.02                # corner blend tolerance (G64 P overrides it, G61: exact stops)
//! arc_tolerance = 0.002           # optional (default 0.002): an arc's end off its circle
//! faster_stops = true             # optional: stop at a sharp corner where that is faster
//! queue = 32                      # optional (default 32): look-ahead segments, 8, 16, 32 or 64
//! axes = ["x", "y", "z", "e"]     # optional (default x, y, z): the axis letters played
//!
//! [limits]                        # path limits (over x, y, z), units/s, /s², /s³
//! velocity = 150
//! acceleration = 3000
//! jerk = 100000
//! axis_velocity = [300, 300, 20, 60]          # optional, one per entry of axes
//! axis_acceleration = [5000, 5000, 300, 5000] # optional
//!
//! [produce]                       # optional: moves arrive at a limited rate (a slow link)
//! moves_per_second = 400
//! ```
//!
//! The axes are letters among `x y z a b c u v w e`, each once. The path axes `x`, `y`, `z`
//! (those the machine has) come first: the path's geometry, its corner tolerance and the
//! path limits are theirs. The others ride along (at most [`MAX_RIDING`]): each moves in
//! proportion to the path's arc length, bounded by its own axis limits, and alone where a
//! line moves no path axis (a printer's retraction), as LinuxCNC takes the feed of its
//! rotary and extra axes.

use serde::Deserialize;

use crate::job::{JobError, JobLimits};
use crate::moves::{MIN_ARC_TOLERANCE, Produce};
use crate::number::{self, NumberFormat};
use crate::stream_run::StreamSetup;
use crate::toml_error::locate;

/// The machine `strak-sim gcode` plays on without `--machine`: a small three-axis mill in
/// millimetres.
pub const DEFAULT_MACHINE: &str = include_str!("../examples/machines/mill.toml");

/// The axis letters a machine may have.
pub const AXIS_LETTERS: &str = "xyzabcuvwe";

/// The path axes' letters.
const PATH_LETTERS: &str = "xyz";

/// The most axes that ride along.
pub const MAX_RIDING: usize = 3;

/// A machine file.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Machine {
    /// Control rate in Hz.
    pub rate_hz: f64,
    /// Playback number format (read by [`number::parse`]).
    #[serde(deserialize_with = "number::deserialize")]
    pub number: NumberFormat,
    /// The length unit, for display.
    #[serde(default = "default_unit")]
    pub unit: String,
    /// The corner blend tolerance of `G64` without `P` (units; 0: exact stops).
    pub tolerance: f64,
    /// How far an arc's end may lie off the circle through its start (units), for the
    /// reader and the stream alike.
    #[serde(default = "default_arc_tolerance")]
    pub arc_tolerance: f64,
    /// Whether a sharp corner stops where that is estimated faster than its blend.
    #[serde(default = "default_true")]
    pub faster_stops: bool,
    /// Look-ahead segments ([`QUEUE_SIZES`](crate::moves::QUEUE_SIZES)).
    #[serde(default = "default_queue")]
    pub queue: usize,
    /// The axis letters played, in order.
    #[serde(default = "default_axes")]
    pub axes: Vec<String>,
    /// Kinematic limits.
    pub limits: JobLimits,
    /// The rate the moves arrive at (default: all at once).
    pub produce: Option<Produce>,
}

fn default_unit() -> String {
    "mm".to_owned()
}

fn default_arc_tolerance() -> f64 {
    0.002
}

fn default_true() -> bool {
    true
}

fn default_queue() -> usize {
    32
}

fn default_axes() -> Vec<String> {
    ["x", "y", "z"].map(str::to_owned).to_vec()
}

impl Machine {
    /// Parses TOML text and checks every field; the error names the field.
    ///
    /// ```
    /// use strak_sim::machine::{DEFAULT_MACHINE, Machine};
    /// let mill = Machine::parse(DEFAULT_MACHINE)?;
    /// assert_eq!((mill.path_axes(), mill.riding_axes()), (3, 0));
    /// let bad = DEFAULT_MACHINE.replace(r#"axes = ["x", "y", "z"]"#, r#"axes = ["e", "x"]"#);
    /// assert_eq!(Machine::parse(&bad).unwrap_err().field, "axes[1]");
    /// # Ok::<(), strak_sim::job::JobError>(())
    /// ```
    ///
    /// # Errors
    /// A [`JobError`] naming the field.
    pub fn parse(text: &str) -> Result<Self, JobError> {
        let machine: Machine = toml::from_str(text).map_err(|e| {
            let at = locate(text, &e, &[]);
            JobError::new(at.field, at.message)
        })?;
        machine.check()?;
        Ok(machine)
    }

    /// Checks what serde cannot: the ranges, the axes and the per-axis limits' lengths.
    ///
    /// # Errors
    /// A [`JobError`] naming the field.
    pub fn check(&self) -> Result<(), JobError> {
        self.setup().check()?;
        if !(self.arc_tolerance.is_finite() && self.arc_tolerance >= MIN_ARC_TOLERANCE) {
            return Err(JobError::new(
                "arc_tolerance",
                format!("must be finite and ≥ {MIN_ARC_TOLERANCE}"),
            ));
        }
        self.check_axes()?;
        self.limits.check_axes(self.axes.len(), "the machine has")
    }

    fn check_axes(&self) -> Result<(), JobError> {
        if !(1..=crate::axes::MAX_AXES).contains(&self.axes.len()) {
            return Err(JobError::new("axes", "name 1 to 6 axes"));
        }
        for (i, a) in self.axes.iter().enumerate() {
            let field = format!("axes[{i}]");
            let lower = a.to_ascii_lowercase();
            if lower.len() != 1 || !AXIS_LETTERS.contains(lower.as_str()) {
                return Err(JobError::new(
                    field,
                    format!("`{a}`: an axis is one of the letters x y z a b c u v w e"),
                ));
            }
            if self.axes[..i].iter().any(|b| b.eq_ignore_ascii_case(a)) {
                return Err(JobError::new(field, format!("`{a}` is named twice")));
            }
            if PATH_LETTERS.contains(lower.as_str()) && i > 0 && !is_path(&self.axes[i - 1]) {
                return Err(JobError::new(
                    field,
                    format!("`{a}`: the path axes x, y, z come before the axes that ride along"),
                ));
            }
        }
        if self.path_axes() == 0 {
            return Err(JobError::new(
                "axes[0]",
                format!(
                    "`{}`: the first axis is a path axis (x, y or z)",
                    self.axes[0]
                ),
            ));
        }
        if self.riding_axes() > MAX_RIDING {
            return Err(JobError::new(
                "axes",
                format!("at most {MAX_RIDING} axes besides x, y, z"),
            ));
        }
        Ok(())
    }

    /// The path axes: the leading `x`, `y`, `z`.
    pub fn path_axes(&self) -> usize {
        self.axes.iter().take_while(|a| is_path(a)).count()
    }

    /// The axes that ride along: those after the path axes.
    pub fn riding_axes(&self) -> usize {
        self.axes.len() - self.path_axes()
    }

    /// The axis letters as the G-code reader takes them (upper case); `D` is the axis
    /// count.
    pub fn letters<const D: usize>(&self) -> [u8; D] {
        let mut letters = [b'X'; D];
        for (l, a) in letters.iter_mut().zip(&self.axes) {
            *l = a.as_bytes().first().map_or(b'X', u8::to_ascii_uppercase);
        }
        letters
    }

    /// What the machine streams on.
    pub fn setup(&self) -> StreamSetup {
        StreamSetup {
            rate_hz: self.rate_hz,
            number: self.number,
            unit: self.unit.clone(),
            tolerance: self.tolerance,
            faster_stops: self.faster_stops,
            queue: self.queue,
            arc_tolerance: self.arc_tolerance,
            limits: self.limits.clone(),
            moves_per_second: self.produce.as_ref().map(|p| p.moves_per_second),
            axis_names: self.axes.iter().map(|a| a.to_ascii_lowercase()).collect(),
            path_axes: self.path_axes(),
        }
    }
}

/// Whether `axis` is one of the path axes `x`, `y`, `z`.
fn is_path(axis: &str) -> bool {
    axis.len() == 1 && PATH_LETTERS.contains(axis.to_ascii_lowercase().as_str())
}

/// Calls `$f::<…, D, R>(args)` with `D` the machine's axis count and `R` its riding axes
/// (path axes 1 to 3, riding axes 0 to [`MAX_RIDING`]); any other pair evaluates
/// `$otherwise`.
#[macro_export]
macro_rules! with_machine_axes {
    ($m:expr, $f:ident::<$($g:ty),*>($($arg:expr),* $(,)?), $otherwise:expr) => {
        match ($m.axes.len(), $m.riding_axes()) {
            (1, 0) => $f::<$($g,)* 1, 0>($($arg),*),
            (2, 0) => $f::<$($g,)* 2, 0>($($arg),*),
            (3, 0) => $f::<$($g,)* 3, 0>($($arg),*),
            (2, 1) => $f::<$($g,)* 2, 1>($($arg),*),
            (3, 1) => $f::<$($g,)* 3, 1>($($arg),*),
            (4, 1) => $f::<$($g,)* 4, 1>($($arg),*),
            (3, 2) => $f::<$($g,)* 3, 2>($($arg),*),
            (4, 2) => $f::<$($g,)* 4, 2>($($arg),*),
            (5, 2) => $f::<$($g,)* 5, 2>($($arg),*),
            (4, 3) => $f::<$($g,)* 4, 3>($($arg),*),
            (5, 3) => $f::<$($g,)* 5, 3>($($arg),*),
            (6, 3) => $f::<$($g,)* 6, 3>($($arg),*),
            _ => $otherwise,
        }
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    fn with(line: &str) -> Result<Machine, JobError> {
        Machine::parse(&DEFAULT_MACHINE.replace(r#"axes = ["x", "y", "z"]"#, line))
    }

    #[test]
    fn the_bundled_machines_parse() {
        let mill = Machine::parse(DEFAULT_MACHINE).unwrap();
        assert_eq!(mill.letters::<3>(), *b"XYZ");
        let printer = Machine::parse(include_str!("../examples/machines/printer.toml")).unwrap();
        assert_eq!((printer.path_axes(), printer.riding_axes()), (3, 1));
        assert_eq!(printer.letters::<4>(), *b"XYZE");
        let setup = printer.setup();
        assert_eq!(setup.axis_names, ["x", "y", "z", "e"]);
        assert_eq!(setup.moves_per_second, Some(400.0));
    }

    #[test]
    fn bad_axes_name_their_field() {
        let no_axis_limits = |axes: &str| {
            let text: Vec<&str> = DEFAULT_MACHINE
                .lines()
                .filter(|l| !l.starts_with("axis_"))
                .collect();
            Machine::parse(&text.join("\n").replace(r#"axes = ["x", "y", "z"]"#, axes))
        };
        assert_eq!(
            no_axis_limits(r#"axes = ["x", "q"]"#).unwrap_err().field,
            "axes[1]"
        );
        assert_eq!(
            no_axis_limits(r#"axes = ["x", "X"]"#).unwrap_err().field,
            "axes[1]"
        );
        assert_eq!(
            no_axis_limits(r#"axes = ["x", "e", "y"]"#)
                .unwrap_err()
                .field,
            "axes[2]"
        );
        assert_eq!(
            no_axis_limits(r#"axes = ["a"]"#).unwrap_err().field,
            "axes[0]"
        );
        assert_eq!(no_axis_limits("axes = []").unwrap_err().field, "axes");
        let four = r#"axes = ["x", "a", "b", "c", "e"]"#;
        assert_eq!(no_axis_limits(four).unwrap_err().field, "axes");
        let m = no_axis_limits(r#"axes = ["X", "Z", "a", "E"]"#).unwrap();
        assert_eq!(
            (m.path_axes(), m.riding_axes(), m.letters::<4>()),
            (2, 2, *b"XZAE")
        );
        assert_eq!(
            with(r#"axes = ["x", "y"]"#).unwrap_err().field,
            "limits.axis_velocity"
        );
    }

    #[test]
    fn bad_values_name_their_field() {
        let replace = |from: &str, to: &str| Machine::parse(&DEFAULT_MACHINE.replace(from, to));
        let field = |r: Result<Machine, JobError>| r.unwrap_err().field;
        assert_eq!(field(replace("rate_hz = 1000", "rate_hz = 10")), "rate_hz");
        assert_eq!(field(replace("queue = 32", "queue = 12")), "queue");
        assert_eq!(
            field(replace("tolerance = 0.02 ", "tolerance = -1 ")),
            "tolerance"
        );
        assert_eq!(
            field(replace("arc_tolerance = 0.002", "arc_tolerance = 0")),
            "arc_tolerance"
        );
        assert_eq!(field(replace("rate_hz = 1000", "rate = 1000")), "rate");
        let produce = format!("{DEFAULT_MACHINE}\n[produce]\nmoves_per_second = 0\n");
        assert_eq!(field(Machine::parse(&produce)), "produce.moves_per_second");
    }
}
