//! Planning: the machine's [`Limits`], the time laws that say where on the curve the motion
//! is at time `t` ([`Timing`] implementations), and the planner that fits a motion to the
//! limits.
//!
//! * [`ParameterTiming`]: the parameter at a constant rate (`u = u_start + rate·t`).
//! * [`PathTiming`]: a motion along the arc length `s(t)` ([`MotionProfile`]) mapped onto the
//!   curve through an arc-length table, `u(t) = u(s(t))`, `du/dt = ṡ/|c'(u)|`:
//!   - constant speed, `s = v·t`;
//!   - trapezoidal speed, rest to rest, with global limits;
//!   - the jerk-limited S-curve ("double S", Biagiotti & Melchiorri, *Trajectory Planning
//!     for Automatic Machines and Robots*, §3.4), rest to rest, with the speed limit
//!     varying along the path (curvature, per-axis velocity and acceleration), planned over
//!     zones of constant limit by a forward/backward pass ([`PlanOptions`]).
//!
//! `s(t)` is piecewise cubic in `t`: a list of constant-jerk [`Phase`]s. All planning runs
//! in `f64` without fused multiply-add, so the same inputs give the same bits on every
//! target.

mod arc_inverse;
mod constant_speed;
mod joins;
mod limits;
mod motion;
mod options;
mod parameter;
mod path_timing;
mod planner;
mod scurve;
mod speed_limit;
mod timing;
mod trajectory;
mod transitions;
mod trapezoid;
mod window;

#[cfg(test)]
pub(crate) mod testcurves;

use strak_curves::{ParamCurve, Point, Scalar, ScalarOf};

/// `a > b`, false when either is NaN.
#[inline]
fn greater(a: f64, b: f64) -> bool {
    a.partial_cmp(&b) == Some(core::cmp::Ordering::Greater)
}

/// The `f64` parameter `u` as the curve's scalar: clamped to the domain, rounded to nearest
/// (the domain start when it cannot be represented).
pub(crate) fn to_param<C: ParamCurve + ?Sized>(curve: &C, u: f64) -> ScalarOf<C> {
    let (lo, hi) = curve.domain();
    if !greater(u, lo.to_f64()) {
        return lo;
    }
    if u >= hi.to_f64() {
        return hi;
    }
    ScalarOf::<C>::from_f64(u).unwrap_or(lo).clamp_to(lo, hi)
}

/// `|p|` in `f64`.
pub(crate) fn norm64<P: Point>(p: &P) -> f64 {
    let mut acc = 0.0;
    for i in 0..P::DIM {
        let x = p.coord(i).to_f64();
        acc += x * x;
    }
    libm::sqrt(acc)
}

pub use limits::Limits;
pub use motion::{MotionProfile, MotionState, Phase, ProfileZone};
pub use options::{PlanOptions, ProfileShape};
pub use parameter::ParameterTiming;
pub use path_timing::PathTiming;
pub use timing::{FeedReserve, MotionLimits, Timing};
pub use trajectory::{Along, Trajectory};
pub use window::{LookAhead, WindowZone};

pub(crate) use motion::PHASES_PER_ZONE;
pub(crate) use scurve::{reach, slowing_loss};
pub(crate) use speed_limit::{ArcLengths, zones_into};
pub(crate) use window::SegmentZones;
