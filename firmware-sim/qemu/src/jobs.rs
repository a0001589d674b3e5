//! The jobs embedded in flash: what `cargo xtask qemu` generated into `jobs.rs` (see the
//! crate docs), as the types of this module and the library's events and number formats.

use strak_trajectory::{CompileOptions, PlanOptions};
pub use strak_trajectory::{Event, NumberFormat, Synchronization, TimedEvent};

/// Whether this firmware plays `format`: `Q40` everywhere, `f32` only on a target with a
/// floating-point unit (the jobs are bundled in these two formats).
pub fn played_here(format: NumberFormat) -> bool {
    match format {
        NumberFormat::F32 => cfg!(target_abi = "eabihf"),
        NumberFormat::Q40 => true,
        NumberFormat::F64 => false,
    }
}

/// A job compiled on the host: a path blob in flash and its events.
#[derive(Clone, Copy, Debug)]
pub struct BlobJob {
    /// The job's name (its file name).
    pub name: &'static str,
    /// The blob's playback format (`f32` or `Q40`).
    pub format: NumberFormat,
    /// Number of axes.
    pub axes: usize,
    /// The serialized path (`Path::to_bytes` on the host).
    pub blob: &'static [u8],
    /// The events, sorted by tick.
    pub events: &'static [TimedEvent],
}

/// A job the device compiles at start-up: a clamped uniform B-spline over `[0, 1]` with the
/// planner and compiler settings of `strak-sim` (velocity limits reduced for the fit, as
/// `strak-sim run` plans; the planner reserves the feed share itself).
#[derive(Clone, Copy, Debug)]
pub struct DeviceJob<const D: usize> {
    /// The job's name.
    pub name: &'static str,
    /// Control rate in Hz.
    pub rate_hz: f64,
    /// The B-spline's degree.
    pub degree: usize,
    /// The de Boor (control) points.
    pub points: &'static [[f64; D]],
    /// Path velocity, acceleration and jerk limits for planning.
    pub limits: [f64; 3],
    /// Per-axis velocity limits (`inf`: none).
    pub axis_velocity: [f64; D],
    /// Per-axis acceleration limits (`inf`: none).
    pub axis_acceleration: [f64; D],
    /// The job's own path velocity, acceleration and jerk limits (what a feed guard checks).
    pub machine_limits: [f64; 3],
    /// The job's own per-axis velocity limits (`inf`: none).
    pub machine_axis_velocity: [f64; D],
    /// The planner's settings.
    pub plan: PlanOptions,
    /// The compiler's settings.
    pub compile: CompileOptions,
    /// The events, sorted by tick.
    pub events: &'static [TimedEvent],
    /// The host's blob of the same job in `f32`, compared byte for byte.
    pub host_blob_f32: &'static [u8],
    /// The host's blob of the same job in fixed-point, compared byte for byte.
    pub host_blob_fixed: &'static [u8],
}

/// A target of an online move: per axis `(position, velocity, acceleration)`; the positions
/// count for a position move, not for a velocity move.
#[derive(Clone, Copy, Debug)]
pub struct MoveTarget<const D: usize> {
    /// Per axis `(position, velocity, acceleration)`.
    pub states: [[f64; 3]; D],
    /// A position move (`false`: a velocity move, the positions free).
    pub position: bool,
}

/// What happens at a tick of an online move.
#[derive(Clone, Copy, Debug)]
pub enum MoveEvent<const D: usize> {
    /// A new target.
    Target(MoveTarget<D>),
    /// A quick stop.
    Stop,
}

/// An online move the device solves, compiles and plays with its events: a move file of
/// `firmware-sim/examples/moves` as `strak-sim move` reads it.
#[derive(Clone, Copy, Debug)]
pub struct MoveJob<const D: usize> {
    /// The job's name (its file name).
    pub name: &'static str,
    /// Control rate in Hz.
    pub rate_hz: f64,
    /// How the axes are timed together.
    pub sync: Synchronization,
    /// Per axis `(velocity, acceleration, jerk)` limits.
    pub limits: [[f64; 3]; D],
    /// Per axis start `(position, velocity, acceleration)`.
    pub start: [[f64; 3]; D],
    /// The first target.
    pub target: MoveTarget<D>,
    /// New targets and quick stops by tick (increasing).
    pub events: &'static [(u64, MoveEvent<D>)],
}

/// A G-code program the device reads line by line from flash and streams on the firmware's
/// machine (`firmware-sim/qemu/gcode-machine.toml`, read by `cargo xtask qemu` as
/// `strak-sim gcode` reads it): its axes, rate, tolerances, limits and arrival rate.
#[derive(Clone, Copy, Debug)]
pub struct GcodeJob<const D: usize> {
    /// The job's name.
    pub name: &'static str,
    /// The program's text.
    pub text: &'static [u8],
    /// The axis letters the reader takes, in order.
    pub letters: [u8; D],
    /// Control rate in Hz.
    pub rate_hz: f64,
    /// The corner blend tolerance the stream starts with and `G64` without `P` blends within.
    pub tolerance: f64,
    /// Whether a sharp corner stops where that is estimated faster than its blend.
    pub faster_stops: bool,
    /// How far an arc's end may lie off the circle through its start, for the reader and
    /// the stream alike.
    pub arc_tolerance: f64,
    /// How far the stream's pieces may lie from the planned motion.
    pub fit_tolerance: f64,
    /// Path velocity, acceleration and jerk limits.
    pub limits: [f64; 3],
    /// Per-axis velocity limits (`inf`: none).
    pub axis_velocity: [f64; D],
    /// Per-axis acceleration limits (`inf`: none).
    pub axis_acceleration: [f64; D],
    /// One move (or dwell) arrives every this many ticks, the first at tick 0 (`None`: all
    /// at once).
    pub ticks_per_move: Option<f64>,
}

/// The pieces of [`FLASH_BLOB`]: the firmware's capacity ([`crate::PIECES`]).
pub const FLASH_PIECES: usize = crate::PIECES;

/// The blob job `name` in `format` with `axes` axes, if bundled.
pub fn find_blob(name: &str, format: NumberFormat, axes: usize) -> Option<&'static BlobJob> {
    BLOB_JOBS
        .iter()
        .find(|j| j.name == name && j.format == format && j.axes == axes)
}

include!(concat!(env!("OUT_DIR"), "/jobs.rs"));
