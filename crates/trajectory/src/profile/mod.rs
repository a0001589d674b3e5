//! Time laws: where on the curve the motion is at time `t`, as [`Timing`](crate::Timing)
//! implementations.
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

mod constant_speed;
mod joins;
mod motion;
mod options;
mod parameter;
mod path_timing;
mod planner;
mod scurve;
mod speed_limit;
mod trapezoid;

#[cfg(test)]
mod testcurves;

/// `a > b`, false when either is NaN.
#[inline]
fn greater(a: f64, b: f64) -> bool {
    a.partial_cmp(&b) == Some(core::cmp::Ordering::Greater)
}

pub use motion::{MotionProfile, MotionState, Phase, ProfileZone};
pub use options::{PlanOptions, ProfileShape};
pub use parameter::ParameterTiming;
pub use path_timing::PathTiming;
