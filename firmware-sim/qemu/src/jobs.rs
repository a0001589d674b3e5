//! The jobs embedded in flash: what `cargo xtask qemu` generated into `jobs.rs` (see the
//! crate docs), as the types of this module.

use strak_trajectory::{CompileOptions, PlanOptions};

/// The playback number format of a job.
#[derive(Clone, Copy, Debug, PartialEq, Eq, defmt::Format)]
pub enum Format {
    /// Curve and playback in `f32` (needs the FPU to be fast; Cortex-M4F only here).
    F32,
    /// Curve in `I32F32`, playback in `Q40`, samples in `I32F32` (any Cortex-M).
    Fixed,
}

impl Format {
    /// The name in the output protocol.
    pub fn name(self) -> &'static str {
        match self {
            Format::F32 => "f32",
            Format::Fixed => "fixed",
        }
    }

    /// Whether this firmware plays the format: fixed-point everywhere, `f32` only on a
    /// target with a floating-point unit.
    pub fn played_here(self) -> bool {
        match self {
            Format::F32 => cfg!(target_abi = "eabihf"),
            Format::Fixed => true,
        }
    }
}

/// An operator event of a job, applied before the sample of its tick.
#[derive(Clone, Copy, Debug, PartialEq, defmt::Format)]
pub enum Event {
    /// `Sampler::set_feed`.
    Feed(f32),
    /// `Sampler::hold`.
    Hold,
    /// `Sampler::resume`.
    Resume,
    /// `Sampler::abort`.
    Abort,
}

/// An event at a tick (ticks count samples, holds included).
#[derive(Clone, Copy, Debug, PartialEq, defmt::Format)]
pub struct TimedEvent {
    /// The tick before whose sample the event applies.
    pub tick: u64,
    /// What happens.
    pub event: Event,
}

/// A job compiled on the host: a path blob in flash and its events.
#[derive(Clone, Copy, Debug)]
pub struct BlobJob {
    /// The job's name (its file name).
    pub name: &'static str,
    /// The blob's playback format.
    pub format: Format,
    /// Number of axes.
    pub axes: usize,
    /// The serialized path (`Path::to_bytes` on the host).
    pub blob: &'static [u8],
    /// The events, sorted by tick.
    pub events: &'static [TimedEvent],
}

/// A job the device compiles at start-up: a clamped uniform B-spline over `[0, 1]` with the
/// planner and compiler settings of `strak-sim` (acceleration and jerk limits already
/// reduced by the feed share, as `strak-sim run` plans).
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

/// The pieces of [`FLASH_BLOB`]: the firmware's capacity ([`crate::PIECES`]).
pub const FLASH_PIECES: usize = crate::PIECES;

/// The blob job `name` in `format` with `axes` axes, if bundled.
pub fn find_blob(name: &str, format: Format, axes: usize) -> Option<&'static BlobJob> {
    BLOB_JOBS
        .iter()
        .find(|j| j.name == name && j.format == format && j.axes == axes)
}

include!(concat!(env!("OUT_DIR"), "/jobs.rs"));
