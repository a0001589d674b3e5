//! Online motion: the time-optimal jerk-limited motion of an axis from any state (position,
//! velocity, acceleration) to any target state, computed in bounded time on the device.
//!
//! * [`OnlineMove`]: 1 to 6 axes to their targets, synchronized ([`Synchronization`]).
//! * [`solve_axis`]: one axis to a target position, velocity and acceleration.
//! * [`solve_axis_velocity`]: one axis to a target velocity and acceleration, the position
//!   free (jogging).
//!
//! A start outside the limits first brakes into them (at most two phases,
//! [`AxisProfile::phases`]); the rest follows Berscheid & Kröger, "Jerk-limited Real-time
//! Trajectory Generation with Arbitrary Target States", *Robotics: Science and Systems*
//! 2021 (the profile forms; the equations here are derived for this crate's
//! parametrization).
//!
//! # Bounded work
//! Every solve evaluates a fixed set of closed forms and finds the roots of at most four
//! polynomials of degree ≤ 4 per direction, each by root isolation with at most 80
//! bracketed Newton steps per root: no loop whose count depends on the data beyond that
//! bound.

mod brake;
mod form;
mod moves;
mod profile;
mod real;
mod roots;
mod step1;
mod step2;
mod sync;
mod velocity;

pub use moves::{MoveOptions, OnlineMove};
pub use profile::{AxisLimits, AxisProfile, JerkPhase, Kinematics, MAX_PHASES};
pub use real::Real;
pub use step1::Block;
pub use sync::{Interface, Synchronization};

use crate::error::Error;
use crate::error::Quantity;

/// The time-optimal motion of one axis from `start` to `target` within `limits`, and the
/// durations the axis can take (for synchronizing several axes).
///
/// The start may lie outside the limits (a velocity or acceleration beyond them, or an
/// acceleration that carries the velocity beyond its limit): the motion first brakes into
/// them. The target must lie inside them.
///
/// # Errors
/// * [`Error::NonFiniteState`]: a start or target value is NaN or infinite;
/// * [`Error::TargetOutsideLimits`]: the target velocity or acceleration is outside the
///   limits, or the target cannot be arrived at without passing a velocity limit
///   (`v_f + a_f²/(2J) > v_max` with `a_f < 0`, or `v_f − a_f²/(2J) < v_min` with `a_f > 0`);
/// * [`Error::NoProfile`]: the solver's checks rejected every candidate (a numerical
///   failure, for example with values far apart in magnitude in `f32`).
///
/// ```
/// use strak_trajectory::{AxisLimits, Kinematics, solve_axis};
/// let limits = AxisLimits::new(500.0_f64, 5_000.0, 100_000.0)?;
/// // Moving at 100 units/s and accelerating; stop at 80 units with 50 units/s.
/// let start = Kinematics::new(0.0, 100.0, 2_000.0);
/// let target = Kinematics::new(80.0, 50.0, 0.0);
/// let block = solve_axis(&start, &target, &limits)?;
/// let end = block.profile().end();
/// assert!((end.position - 80.0).abs() < 1e-9 && (end.velocity - 50.0).abs() < 1e-9);
/// # Ok::<(), strak_trajectory::Error>(())
/// ```
pub fn solve_axis<R: Real>(
    start: &Kinematics<R>,
    target: &Kinematics<R>,
    limits: &AxisLimits<R>,
) -> Result<Block<R>, Error> {
    let mut profile = AxisProfile::still(start.position);
    let span = sync::axis_span(start, target, limits, Interface::Position, &mut profile)?;
    Ok(Block { profile, span })
}

/// The time-optimal motion of one axis from `start` to the velocity and acceleration of
/// `target` (its position is ignored), within the acceleration and jerk limits. The velocity
/// limits bound the target velocity only: on the way the velocity moves monotonically
/// between start and target except where the start's acceleration carries it beyond.
///
/// # Errors
/// As [`solve_axis`].
///
/// ```
/// use strak_trajectory::{AxisLimits, Kinematics, solve_axis_velocity};
/// let limits = AxisLimits::new(500.0_f64, 5_000.0, 100_000.0)?;
/// let jog = Kinematics::new(0.0, 200.0, 0.0); // position free
/// let block = solve_axis_velocity(&Kinematics::at_rest(10.0), &jog, &limits)?;
/// // The acceleration peaks at √(J·Δv) ≈ 4 472 units/s², below its limit: 2·4 472/100 000 s.
/// assert!((block.t_min() - 0.0894427191).abs() < 1e-9);
/// assert!((block.profile().end().velocity - 200.0).abs() < 1e-9);
/// # Ok::<(), strak_trajectory::Error>(())
/// ```
pub fn solve_axis_velocity<R: Real>(
    start: &Kinematics<R>,
    target: &Kinematics<R>,
    limits: &AxisLimits<R>,
) -> Result<Block<R>, Error> {
    let mut profile = AxisProfile::still(start.position);
    let span = sync::axis_span(start, target, limits, Interface::Velocity, &mut profile)?;
    Ok(Block { profile, span })
}

/// The target's velocity and acceleration inside the limits (and, in position mode,
/// reachable without passing a velocity limit).
fn check_target<R: Real>(
    target: &Kinematics<R>,
    l: &AxisLimits<R>,
    position: bool,
) -> Result<(), Error> {
    let (v, a) = (target.velocity, target.acceleration);
    if v > l.v_max || v < l.v_min {
        return Err(Error::TargetOutsideLimits {
            quantity: Quantity::Velocity,
        });
    }
    if a > l.a_max || a < l.a_min {
        return Err(Error::TargetOutsideLimits {
            quantity: Quantity::Acceleration,
        });
    }
    let carried = a * a / (R::TWO * l.jerk);
    let passes = (a < R::ZERO && v + carried > l.v_max) || (a > R::ZERO && v - carried < l.v_min);
    if position && passes {
        return Err(Error::TargetOutsideLimits {
            quantity: Quantity::Velocity,
        });
    }
    Ok(())
}

#[cfg(test)]
pub(crate) mod testing;
#[cfg(test)]
mod tests;
