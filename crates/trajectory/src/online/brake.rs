//! Braking into the limits: a start state outside them (a velocity or acceleration beyond
//! its limit, or an acceleration that will carry the velocity beyond its limit before the
//! jerk can bring the acceleration to zero) first follows at most two phases that bring it
//! back, as hard as the jerk allows: a phase of maximal jerk towards the allowed range, then
//! if needed a phase at the acceleration limit. This is the brake pre-trajectory of
//! Berscheid & Kröger, "Jerk-limited Real-time Trajectory Generation with Arbitrary Target
//! States", *Robotics: Science and Systems* 2021, §IV-A, so that durations agree with
//! Ruckig's for such starts.

use super::profile::{AxisLimits, JerkPhase, Kinematics};
use super::real::Real;

/// The velocity when the acceleration `a` has been brought to zero at jerk `j` (with the
/// sign of `−a`): `v + a|a|/(2|j|)`, written with the jerk's sign as `v − a²/(2j)`.
fn velocity_at_zero_acceleration<R: Real>(v: R, a: R, j: R) -> R {
    v - a * a / (R::TWO * j)
}

/// The velocity after `t` seconds from `(v, a)` at jerk `j`.
fn velocity_after<R: Real>(v: R, a: R, j: R, t: R) -> R {
    v + t * (a + j * t * R::HALF)
}

/// The brake phases from `(v, a)` (at most two; durations 0 when the state is within the
/// limits and can stay there).
pub(super) fn position_brake<R: Real>(v: R, a: R, l: &AxisLimits<R>) -> [JerkPhase<R>; 2] {
    let j = l.jerk;
    if a > l.a_max {
        acceleration_brake(v, a, l)
    } else if a < l.a_min {
        negated(acceleration_brake(-v, -a, &l.mirrored()))
    } else if (v > l.v_max && velocity_at_zero_acceleration(v, a, j) > l.v_min)
        || (a > R::ZERO && velocity_at_zero_acceleration(v, a, -j) > l.v_max)
    {
        velocity_brake(v, a, l)
    } else if (v < l.v_min && velocity_at_zero_acceleration(v, a, -j) < l.v_max)
        || (a < R::ZERO && velocity_at_zero_acceleration(v, a, j) < l.v_min)
    {
        negated(velocity_brake(-v, -a, &l.mirrored()))
    } else {
        [JerkPhase::default(); 2]
    }
}

/// The brake phases of the velocity mode: only an acceleration beyond its limit is brought
/// back.
pub(super) fn velocity_mode_brake<R: Real>(a: R, l: &AxisLimits<R>) -> [JerkPhase<R>; 2] {
    let mut phases = [JerkPhase::default(); 2];
    if a > l.a_max {
        phases[0] = JerkPhase {
            jerk: -l.jerk,
            duration: (a - l.a_max) / l.jerk,
        };
    } else if a < l.a_min {
        phases[0] = JerkPhase {
            jerk: l.jerk,
            duration: (l.a_min - a) / l.jerk,
        };
    }
    phases
}

/// The state at the end of the brake phases, and their duration.
pub(super) fn after<R: Real>(
    origin: &Kinematics<R>,
    brake: &[JerkPhase<R>; 2],
) -> (Kinematics<R>, R) {
    let mut state = *origin;
    let mut time = R::ZERO;
    for p in brake {
        state = state.advance(p.jerk, p.duration);
        time += p.duration;
    }
    (state, time)
}

fn negated<R: Real>(mut phases: [JerkPhase<R>; 2]) -> [JerkPhase<R>; 2] {
    for p in &mut phases {
        p.jerk = -p.jerk;
    }
    phases
}

/// `a > a_max`: the jerk brings the acceleration down to `a_max`; if the velocity is still
/// below `v_min` there, the acceleration is held at `a_max` until it is not; if it would pass
/// `v_max` before the acceleration reaches zero, the velocity brake instead.
fn acceleration_brake<R: Real>(v: R, a: R, l: &AxisLimits<R>) -> [JerkPhase<R>; 2] {
    let j = l.jerk;
    let to_a_max = (a - l.a_max) / j;
    let v_at_a_max = velocity_after(v, a, -j, to_a_max);
    let v_at_zero = velocity_after(v, a, -j, a / j);
    let mut phases = [
        JerkPhase {
            jerk: -j,
            duration: to_a_max,
        },
        JerkPhase::default(),
    ];
    if v_at_zero > l.v_max {
        return velocity_brake(v, a, l);
    }
    if v_at_a_max < l.v_min {
        let to_v_min = (l.v_min - v_at_a_max) / l.a_max;
        let to_v_max = (l.v_max - v_at_a_max) / l.a_max - l.a_max / (R::TWO * j);
        let hold = to_v_min.min_of(to_v_max);
        phases[1].duration = hold.max_of(R::ZERO);
    }
    phases
}

/// The velocity is (or will be) above `v_max`: maximal negative jerk until the velocity is
/// back at `v_max` or (if that comes first) the acceleration reaches `a_min`, then `a_min`
/// held until the velocity is back. Neither may carry the velocity below what a later
/// reversal of the acceleration can keep above `v_min`.
fn velocity_brake<R: Real>(v: R, a: R, l: &AxisLimits<R>) -> [JerkPhase<R>; 2] {
    let j = l.jerk;
    let to_a_min = (a - l.a_min) / j;
    let to_v_max = (a + (a * a + R::TWO * j * (v - l.v_max)).root()) / j;
    let to_v_min = (a + (a * a * R::HALF + j * (v - l.v_min)).root()) / j;
    let first = to_v_max.min_of(to_v_min);
    let mut phases = [
        JerkPhase {
            jerk: -j,
            duration: first,
        },
        JerkPhase::default(),
    ];
    if to_a_min < first {
        let v_at_a_min = velocity_after(v, a, -j, to_a_min);
        let hold_to_v_max = (l.v_max - v_at_a_min) / l.a_min;
        let hold_to_v_min = l.a_min / (R::TWO * j) - (v_at_a_min - l.v_min) / l.a_min;
        phases[0].duration = to_a_min.max_of(R::ZERO);
        phases[1].duration = hold_to_v_max.min_of(hold_to_v_min).max_of(R::ZERO);
    }
    phases
}
