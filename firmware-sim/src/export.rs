//! Jobs for firmware: compile a job into a path blob exactly as `strak-sim run` compiles it,
//! and play it on the host with the job's events, keeping every sample's raw bits.
//!
//! This is what `strak-sim compile` writes and what `cargo xtask qemu` compares the firmware
//! under QEMU against: the firmware plays the same blob with the same events, one
//! [`Sampler::next`] per tick, and must produce the same bits.
//!
//! The playback format is chosen here, not by the job's `number`: [`NumberFormat::F32`] builds
//! the curve in `f32` and plays `Path<f32, …>`, [`NumberFormat::Q40`] builds it in `I32F32` and
//! plays `Path<Q40, …>`, [`NumberFormat::F64`] builds and plays in `f64` (as `strak-sim run`
//! pairs them). Planning and compiling are the [`pipeline`](crate::pipeline) of
//! `strak-sim run`, and the events are played by the same [`EventPlayer`].

use strak_curves::{I32F32, Scalar};
use strak_trajectory::{
    CompileOptions, EventPlayer, Kernel, Limits, Number, Path, PlanOptions, Q40, RunEnd, Sampler,
    TimedEvent,
};

use crate::curve_file::CurveFile;
use crate::job::{Job, JobError};
use crate::number::NumberFormat;
use crate::pipeline::{
    PIECES, Prepared, axis_array, boxed_path, compile_options, is_planned, plan_options,
};
use crate::schedule::schedule;

/// A sample value's raw bits, widened to `u64` (`f32`, `f64`: `to_bits`; `I32F32`: the `i64`
/// bits reinterpreted).
pub trait OutBits: Scalar {
    /// The bits.
    fn out_bits(self) -> u64;
}

impl OutBits for f32 {
    fn out_bits(self) -> u64 {
        u64::from(self.to_bits())
    }
}

impl OutBits for f64 {
    fn out_bits(self) -> u64 {
        self.to_bits()
    }
}

impl OutBits for I32F32 {
    fn out_bits(self) -> u64 {
        self.to_bits().cast_unsigned()
    }
}

/// The settings `strak-sim run` plans and compiles a job with, as plain values: what firmware
/// needs to compile the same path on the device.
#[derive(Clone, Debug, PartialEq)]
pub struct DeviceRecipe {
    /// The control rate in Hz.
    pub rate_hz: f64,
    /// The B-spline's degree (clamped uniform knots over `[0, 1]`).
    pub degree: usize,
    /// The B-spline's control points.
    pub points: Vec<Vec<f64>>,
    /// Planning limits: path velocity (reduced for the fit, as `strak-sim run` plans),
    /// acceleration, jerk (the planner reserves the feed share itself).
    pub limits: [f64; 3],
    /// Per-axis velocity limits, reduced for the fit (`inf`: none).
    pub axis_velocity: Vec<f64>,
    /// Per-axis acceleration limits (`inf`: none).
    pub axis_acceleration: Vec<f64>,
    /// The job's own path limits (velocity, acceleration, jerk), which its samples keep and
    /// a feed guard checks.
    pub machine_limits: [f64; 3],
    /// The job's own per-axis velocity limits (`inf`: none).
    pub machine_axis_velocity: Vec<f64>,
    /// The planner's settings.
    pub plan: PlanOptions,
    /// The compiler's settings.
    pub compile: CompileOptions,
}

/// A job compiled for firmware and played on the host.
#[derive(Clone, Debug)]
pub struct Export {
    /// The playback format.
    pub playback: NumberFormat,
    /// Number of axes.
    pub axes: usize,
    /// The serialized path ([`Path::to_bytes`]).
    pub blob: Vec<u8>,
    /// Number of pieces of the path.
    pub pieces: usize,
    /// Length of the path in ticks.
    pub ticks: u32,
    /// The events, sorted by tick, as the [`EventPlayer`] plays them.
    pub events: Vec<TimedEvent>,
    /// Every sample's bits, `3 · axes` values per tick: positions, velocities, accelerations.
    pub bits: Vec<u64>,
    /// Whether the sampler finished (`false`: stopped by the guard of `strak-sim run`).
    pub finished: bool,
    /// The settings to compile the same path on the device, for the job kinds firmware can
    /// build without the curve file parser (clamped uniform B-splines planned as trapezoid or
    /// S-curve); `None` otherwise.
    pub recipe: Option<DeviceRecipe>,
}

impl Export {
    /// Number of samples played.
    pub fn samples(&self) -> usize {
        self.bits.len() / (3 * self.axes).max(1)
    }

    /// The bits of sample `tick` (positions, velocities, accelerations).
    pub fn sample(&self, tick: usize) -> Option<&[u64]> {
        let n = 3 * self.axes;
        self.bits.get(tick * n..(tick + 1) * n)
    }
}

/// Compiles `job` for firmware in `playback` and plays it on the host (see the module docs).
///
/// # Errors
/// A [`JobError`] naming the field, as `strak-sim run` reports it, when the job cannot be
/// built, planned, compiled or serialized.
pub fn export(job: &Job, playback: NumberFormat) -> Result<Export, JobError> {
    let mut job = job.clone();
    job.number = playback;
    match playback {
        NumberFormat::F32 => by_dim::<f32, f32>(&job, playback),
        NumberFormat::F64 => by_dim::<f64, f64>(&job, playback),
        NumberFormat::Q40 => by_dim::<Q40, I32F32>(&job, playback),
    }
}

fn by_dim<N, S>(job: &Job, playback: NumberFormat) -> Result<Export, JobError>
where
    N: Kernel,
    N::Out: OutBits,
    S: Scalar,
{
    crate::with_axes!(
        job.axes(),
        export_typed::<N, S>(job, playback),
        Err(JobError::new(
            "path.points",
            "points need 1 to 6 coordinates"
        ))
    )
}

/// `path` as a blob, and the path read back from it (checked to equal `path`; read in place
/// into a boxed empty path, as the pipeline compiles).
#[allow(clippy::type_complexity)]
fn to_blob<N: Number, const D: usize>(
    path: &Path<N, D, PIECES>,
) -> Result<(Vec<u8>, Box<Path<N, D, PIECES>>), JobError> {
    let mut blob = vec![0_u8; path.blob_len()];
    let written = path
        .to_bytes(&mut blob)
        .map_err(|e| JobError::new("path", format!("cannot serialize the path: {e}")))?;
    blob.truncate(written);
    let mut back = boxed_path::<N, D>();
    back.read_bytes(&blob)
        .map_err(|e| JobError::new("path", format!("the blob does not read back: {e}")))?;
    if *back != *path {
        return Err(JobError::new(
            "path",
            "the blob reads back as a different path",
        ));
    }
    Ok((blob, back))
}

/// Plays `path` with the scheduled events as `strak-sim run` does; every sample's bits, and
/// whether the sampler finished.
fn play_bits<N, const D: usize>(
    events: &[TimedEvent],
    path: &Path<N, D, PIECES>,
) -> (Vec<u64>, bool)
where
    N: Kernel,
    N::Out: OutBits,
{
    let mut player = EventPlayer::new(events, path.ticks());
    let mut sampler = Sampler::new(path);
    let mut bits = Vec::with_capacity(3 * D * (path.ticks() as usize + 1));
    while let Some(s) = player.step(&mut sampler) {
        for v in s.position.iter().chain(&s.velocity).chain(&s.acceleration) {
            bits.push(v.out_bits());
        }
    }
    (bits, player.end(&sampler) == RunEnd::Finished)
}

fn export_typed<N, S, const D: usize>(job: &Job, playback: NumberFormat) -> Result<Export, JobError>
where
    N: Kernel,
    N::Out: OutBits,
    S: Scalar,
{
    let prepared = Prepared::<S, D>::new(job)?;
    let compiled = prepared.compile::<N>(job)?;
    let path = &*compiled.path;
    // What firmware plays is what was compiled: the blob reads back as the path.
    let (blob, back) = to_blob(path)?;
    let events = schedule(job, &back)?.events;
    let (bits, finished) = play_bits(&events, &back);
    Ok(Export {
        playback,
        axes: D,
        blob,
        pieces: path.pieces().len(),
        ticks: path.ticks(),
        events,
        bits,
        finished,
        recipe: recipe::<D>(job, &prepared.limits),
    })
}

/// The device recipe of a clamped uniform B-spline job planned as trapezoid or S-curve.
fn recipe<const D: usize>(job: &Job, limits: &Limits<D>) -> Option<DeviceRecipe> {
    let CurveFile::Bspline(b) = &job.path else {
        return None;
    };
    if b.knots.is_some() || b.closed || !is_planned(job) {
        return None;
    }
    Some(DeviceRecipe {
        rate_hz: job.rate_hz,
        degree: b.degree,
        points: b.points.clone(),
        limits: [limits.velocity(), limits.acceleration(), limits.jerk()],
        axis_velocity: limits.axis_velocity().to_vec(),
        axis_acceleration: limits.axis_acceleration().to_vec(),
        plan: plan_options(job),
        compile: compile_options(job),
        machine_limits: [
            job.limits.velocity,
            job.limits.acceleration,
            job.limits.jerk,
        ],
        machine_axis_velocity: axis_array::<D>(job.limits.axis_velocity.as_deref()).to_vec(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn out_bits_are_the_raw_bits() {
        assert_eq!(1.0_f32.out_bits(), 0x3f80_0000);
        assert_eq!((-2.0_f64).out_bits(), 0xc000_0000_0000_0000);
        assert_eq!(I32F32::from_num(-1).out_bits(), 0xffff_ffff_0000_0000);
    }
}
