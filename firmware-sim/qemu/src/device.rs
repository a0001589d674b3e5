//! Compiling a path on the device at start-up, with the settings `strak-sim` uses: the curve
//! is built in the playback format's scalar (`f32` for `f32` playback, `I32F32` for
//! fixed-point), the time law planned in `f64` (soft-float on these cores: IEEE-exact
//! `+ − × ÷ √`, the same `libm` code as on the host), then compiled.

use heapless::Vec;
use strak_curves::{BSpline, Point, Scalar};
use strak_trajectory::{Error, Limits, Number, Path, PathTiming, compile};

use crate::jobs::DeviceJob;

/// The most control points of a device job.
pub const MAX_POINTS: usize = 16;
/// Knot capacity (`MAX_POINTS` + degree + 1 for degrees up to 7).
pub const MAX_KNOTS: usize = MAX_POINTS + 8;
/// Samples of the arc-length table: `strak-sim`'s `TABLE` (the plan depends on it).
pub const TABLE: usize = 1_024;
/// Zone capacity of the plan: `strak-sim`'s `ZONES`.
pub const ZONES: usize = 1_024;

/// Builds, plans and compiles `job` into a path played in `N`, the curve's scalar being `S`.
///
/// # Errors
/// The first error of the curve constructor, the planner or the compiler;
/// [`Error::OutOfRange`] for a point that does not fit `S`,
/// [`Error::CapacityExceeded`] for more than [`MAX_POINTS`] points.
pub fn compile_job<N, S, const D: usize, const P: usize>(
    job: &DeviceJob<D>,
) -> Result<Path<N, D, P>, Error>
where
    N: Number,
    S: Scalar,
    [S; D]: Point<Scalar = S>,
{
    let mut points: Vec<[S; D], MAX_POINTS> = Vec::new();
    for p in job.points {
        let q = <[S; D] as Point>::from_f64_slice(p).ok_or(Error::OutOfRange)?;
        points.push(q).map_err(|_| Error::CapacityExceeded {
            capacity: MAX_POINTS,
            required: job.points.len(),
        })?;
    }
    let curve = BSpline::<[S; D], MAX_POINTS, MAX_KNOTS>::clamped_uniform(
        job.degree,
        &points,
        S::ZERO,
        S::ONE,
    )?;
    let [v, a, j] = job.limits;
    let limits = Limits::<D>::new(v, a, j)?
        .with_axis_velocity(job.axis_velocity)?
        .with_axis_acceleration(job.axis_acceleration)?;
    let timing = PathTiming::<_, TABLE, ZONES>::plan(&curve, &limits, &job.plan)?;
    compile(&timing, job.rate_hz, &job.compile)
}

/// The first index where `a` and `b` differ (a length difference counts at the shorter
/// length), or `None` when they are equal.
pub fn first_difference(a: &[u8], b: &[u8]) -> Option<usize> {
    match a.iter().zip(b).position(|(x, y)| x != y) {
        Some(i) => Some(i),
        None if a.len() == b.len() => None,
        None => Some(a.len().min(b.len())),
    }
}
