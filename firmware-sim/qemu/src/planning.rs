//! Planning and compiling on the device: a 16-control-point clamped cubic B-spline in 3 axes
//! (mm), planned as a jerk-limited S-curve ([`PathTiming::scurve`]) and compiled into a
//! [`Path`] of [`PIECES`] pieces at [`RATE_HZ`], the operations whose stack and instructions
//! the `stack` firmware measures.
//!
//! Each stage is one `#[inline(never)]` function taking its input by reference and writing
//! its result in place into the caller's value (the plan, the path), so that a measurement
//! around it sees that stage's own stack alone.

use heapless::Vec;
use strak_curves::{BSpline, Point, Scalar};
use strak_trajectory::{CompileOptions, Error, Limits, Number, Path, PathTiming, PlanOptions};

use crate::PIECES;

/// Control points of the job.
pub const POINTS: usize = 16;
/// Knots of a clamped cubic B-spline of [`POINTS`] points: `POINTS + 3 + 1`.
pub const KNOTS: usize = POINTS + 4;
/// Samples of the plan's arc-length table.
pub const TABLE: usize = 256;
/// Zone capacity of the plan.
pub const ZONES: usize = 64;
/// Control rate in Hz.
pub const RATE_HZ: f64 = 1_000.0;

/// The job's curve in the scalar `S`.
pub type Curve<S> = BSpline<[S; 3], POINTS, KNOTS>;

/// The job's plan: the time law along the curve.
pub type Plan<'a, S> = PathTiming<'a, Curve<S>, TABLE, ZONES>;

/// The de Boor points (mm): 16 points on a helix of 1¼ turns around (150, 75), radii 120
/// and 60 mm, rising 4 mm per point (`150 + 120·cos 0.35i`, `75 + 60·sin 0.35i`, `4i`,
/// rounded to 0.1 mm), so that the curvature and the per-axis share of the speed vary
/// along it.
const CONTROL_POINTS: [[f64; 3]; POINTS] = [
    [270.0, 75.0, 0.0],
    [262.7, 95.6, 4.0],
    [241.8, 113.7, 8.0],
    [209.7, 127.0, 12.0],
    [170.4, 134.1, 16.0],
    [128.6, 134.0, 20.0],
    [89.4, 126.8, 24.0],
    [57.6, 113.3, 28.0],
    [36.9, 95.1, 32.0],
    [30.0, 74.5, 36.0],
    [37.6, 54.0, 40.0],
    [58.9, 36.0, 44.0],
    [91.2, 22.7, 48.0],
    [130.6, 15.8, 52.0],
    [172.4, 16.1, 56.0],
    [211.5, 23.5, 60.0],
];

/// Path velocity (mm/s), acceleration (mm/s²) and jerk (mm/s³) limits.
const LIMITS: [f64; 3] = [300.0, 3_000.0, 60_000.0];

/// The job's limits.
///
/// # Errors
/// As [`Limits::new`] (not for these constants).
pub fn limits() -> Result<Limits<3>, Error> {
    let [v, a, j] = LIMITS;
    Limits::new(v, a, j)
}

/// The job's curve, its points converted to `S`.
///
/// # Errors
/// [`Error::OutOfRange`] for a point that `S` cannot hold; the curve constructor's error.
pub fn curve<S: Scalar>() -> Result<Curve<S>, Error>
where
    [S; 3]: Point<Scalar = S>,
{
    let mut points: Vec<[S; 3], POINTS> = Vec::new();
    for p in &CONTROL_POINTS {
        let q = <[S; 3] as Point>::from_f64_slice(p).ok_or(Error::OutOfRange)?;
        points.push(q).map_err(|_| Error::CapacityExceeded {
            capacity: POINTS,
            required: CONTROL_POINTS.len(),
        })?;
    }
    Ok(BSpline::clamped_uniform(3, &points, S::ZERO, S::ONE)?)
}

/// Plans the S-curve along the curve of `plan` under the job's limits, in place
/// ([`PathTiming::plan_into`] with the default options, as [`PathTiming::scurve`]).
///
/// # Errors
/// The planner's error.
#[inline(never)]
pub fn plan<S: Scalar>(plan: &mut Plan<'_, S>) -> Result<(), Error>
where
    [S; 3]: Point<Scalar = S>,
{
    plan.plan_into(&limits()?, &PlanOptions::new())
}

/// Compiles `plan` (along its curve) into `path`, in place, played in `N`, with the default
/// options ([`PathTiming::compile_into`]).
///
/// # Errors
/// The compiler's error.
#[inline(never)]
pub fn compile_plan<N: Number, S: Scalar>(
    plan: &Plan<'_, S>,
    path: &mut Path<N, 3, PIECES>,
) -> Result<(), Error>
where
    [S; 3]: Point<Scalar = S>,
{
    plan.compile_into(&CompileOptions::new(), path)
}
