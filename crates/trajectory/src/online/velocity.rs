//! The time-optimal change of velocity of one axis (the velocity mode): from `(v₀, a₀)` to
//! `(v_f, a_f)` with the position free. The acceleration rises to a peak `a₁` (held at
//! `a_max` if it would pass it) and falls to `a_f`, or the mirror image; with the velocity
//! equation `a₁² = (a₀² + a_f²)/2 + J(v_f − v₀)` this is a closed form (Biagiotti &
//! Melchiorri, *Trajectory Planning for Automatic Machines and Robots*, §3.4, the
//! acceleration phase of the double S generalized to non-zero end accelerations).

use super::brake::{after, velocity_mode_brake};
use super::profile::AxisProfile;
use super::profile::{AxisLimits, Kinematics};
use super::real::Real;
use super::step1::{Span, with_brake};

/// The three phases (rise, hold, fall) in the frame where the first phase has positive jerk,
/// if they are a motion: every duration non-negative.
fn rise_hold_fall<R: Real>(v0: R, a0: R, vf: R, af: R, a_max: R, j: R) -> Option<[R; 3]> {
    let two = R::TWO;
    let peak2 = (a0 * a0 + af * af) * R::HALF + j * (vf - v0);
    if peak2.is_negative() {
        return None;
    }
    let mut peak = peak2.root();
    let mut hold = R::ZERO;
    if peak > a_max {
        peak = a_max;
        hold = (vf - v0 - (two * a_max * a_max - a0 * a0 - af * af) / (two * j)) / a_max;
    }
    let t = [(peak - a0) / j, hold, (peak - af) / j];
    let slack = R::lit(64.0) * R::EPS * (a_max / j);
    if t.iter().all(|&x| x >= -slack) {
        Some(t.map(|x| x.max_of(R::ZERO)))
    } else {
        None
    }
}

/// The time-optimal velocity change from `origin` to `target`'s velocity and acceleration.
pub(super) fn time_optimal<R: Real>(
    origin: &Kinematics<R>,
    target: &Kinematics<R>,
    l: &AxisLimits<R>,
    out: &mut AxisProfile<R>,
) -> Option<Span<R>> {
    let brake = velocity_mode_brake(origin.acceleration, l);
    let (start, _) = after(origin, &brake);
    let (v0, a0, vf, af, j) = (
        start.velocity,
        start.acceleration,
        target.velocity,
        target.acceleration,
        l.jerk,
    );
    let up = rise_hold_fall(v0, a0, vf, af, l.a_max, j).map(|t| (t, j));
    let down = rise_hold_fall(-v0, -a0, -vf, -af, -l.a_min, j).map(|t| (t, -j));
    let sum = |t: &[R; 3]| t[0] + t[1] + t[2];
    let (t, jerk) = match (up, down) {
        (Some(u), Some(d)) => {
            if sum(&d.0) < sum(&u.0) {
                d
            } else {
                u
            }
        }
        (Some(u), None) => u,
        (None, Some(d)) => d,
        (None, None) => return None,
    };
    let peak = a0 + jerk * t[0];
    with_brake(
        origin,
        brake,
        &t,
        &[jerk, R::ZERO, -jerk],
        &[a0, peak, peak, af],
        out,
    );
    Some(Span::from(out.duration))
}

/// A velocity change of exactly `tau` seconds from `(v0, a0)` to `(vf, af)` as a ramp of
/// jerk `j1`, a hold at `a1` and a ramp of jerk `j3` (each `±J`): its phases and `a1`, if
/// the durations are non-negative (within rounding) and `a1` within `[a_min, a_max]`.
///
/// With `t₁ = (a₁ − a₀)/j₁`, `t₃ = (a_f − a₁)/j₃`, `t₂ = τ − t₁ − t₃`, the velocity
/// gained, `(a₁² − a₀²)/2j₁ + a₁t₂ + (a_f² − a₁²)/2j₃ = v_f − v₀`, is
/// `c₂a₁² + c₁a₁ + c₀ = 0` with `c₂ = 1/2j₃ − 1/2j₁`, `c₁ = τ + a₀/j₁ − a_f/j₃`,
/// `c₀ = a_f²/2j₃ − a₀²/2j₁ − (v_f − v₀)`: linear when both ramps have the same jerk.
fn ramp_hold_ramp<R: Real>(
    (v0, a0): (R, R),
    (vf, af): (R, R),
    (j1, j3): (R, R),
    tau: R,
    l: &AxisLimits<R>,
    root: bool,
) -> Option<([R; 3], R)> {
    let two = R::TWO;
    let c2 = R::ONE / (two * j3) - R::ONE / (two * j1);
    let c1 = tau + a0 / j1 - af / j3;
    let c0 = af * af / (two * j3) - a0 * a0 / (two * j1) - (vf - v0);
    let a1 = if c2 == R::ZERO {
        if root || c1 == R::ZERO {
            return None;
        }
        -c0 / c1
    } else {
        let mut disc = c1 * c1 - R::lit(4.0) * c2 * c0;
        // A double root (the time-optimal change itself, at its duration) rounds either way:
        // `c₀` is a difference of velocities of the scale below.
        let c0_rounding = R::lit(64.0)
            * R::EPS
            * (a0 * a0 / (two * j1.abs()) + af * af / (two * j3.abs()) + v0.abs() + vf.abs());
        if disc.is_negative() && -disc <= R::lit(4.0) * c2.abs() * c0_rounding {
            disc = R::ZERO;
        }
        if disc.is_negative() {
            return None;
        }
        // The root without cancellation, and its partner from the product of the roots.
        let root_disc = if c1.is_negative() {
            -disc.root()
        } else {
            disc.root()
        };
        let q = -(c1 + root_disc) * R::HALF;
        match (root, q == R::ZERO) {
            (_, true) => return None,
            (false, false) => q / c2,
            (true, false) => c0 / q,
        }
    };
    let (t1, t3) = ((a1 - a0) / j1, (af - a1) / j3);
    let scale = l.a_max.max_of(-l.a_min);
    let slack = R::lit(64.0) * R::EPS * (scale / l.jerk + tau);
    let a_slack = R::lit(64.0) * R::EPS * scale;
    let fits = a1 <= l.a_max + a_slack && a1 >= l.a_min - a_slack;
    if !fits || t1 < -slack || t3 < -slack || tau - t1 - t3 < -slack {
        return None;
    }
    // Durations that add up to `tau` (a duration on the tick grid stays on it): what
    // rounding left negative is taken from the longer ramp.
    let mut t = [t1.max_of(R::ZERO), R::ZERO, t3.max_of(R::ZERO)];
    t[1] = tau - t[0] - t[2];
    if t[1].is_negative() {
        let longer = if t[0] >= t[2] { 0 } else { 2 };
        t[longer] = (t[longer] + t[1]).max_of(R::ZERO);
        t[1] = R::ZERO;
    }
    Some((t, a1))
}

/// Whether the velocity of the phases stays within the limits, or within the least
/// excursion any motion from `(v0, a0)` must make beyond them (the velocity at which full
/// jerk brings `a0` to zero).
fn keeps_velocity<R: Real>(
    v0: R,
    a0: R,
    t: &[R; 3],
    jerks: [R; 2],
    a1: R,
    l: &AxisLimits<R>,
) -> bool {
    let forced = v0 + a0 * a0.abs() / (R::TWO * l.jerk);
    let tol = R::lit(64.0) * R::EPS * (l.v_max.max_of(-l.v_min) + forced.abs());
    let (hi, lo) = (l.v_max.max_of(forced) + tol, l.v_min.min_of(forced) - tol);
    // The velocity is extreme where the acceleration passes zero inside a ramp.
    let v1 = v0 + (a1 * a1 - a0 * a0) / (R::TWO * jerks[0]);
    let v2 = v1 + a1 * t[1];
    let mut ok = true;
    if a0 * a1 < R::ZERO {
        let v = v0 - a0 * a0 / (R::TWO * jerks[0]);
        ok &= v <= hi && v >= lo;
    }
    if a1 * (a1 + jerks[1] * t[2]) < R::ZERO {
        let v = v2 - a1 * a1 / (R::TWO * jerks[1]);
        ok &= v <= hi && v >= lo;
    }
    ok
}

/// The velocity change from `origin` to `target`'s velocity and acceleration that takes
/// exactly `duration` seconds: after the brake into the acceleration limits, a ramp at full
/// jerk, a hold and a ramp at full jerk (the time-optimal change's form with a lower peak
/// acceleration, or with both ramps the same way), whose velocity stays within the limits
/// wherever the start allows it.
pub(super) fn with_duration<R: Real>(
    origin: &Kinematics<R>,
    target: &Kinematics<R>,
    l: &AxisLimits<R>,
    duration: R,
    out: &mut AxisProfile<R>,
) -> bool {
    let brake = velocity_mode_brake(origin.acceleration, l);
    let (start, brake_time) = after(origin, &brake);
    let tau = (duration - brake_time).max_of(R::ZERO);
    let (v0, a0, vf, af, j) = (
        start.velocity,
        start.acceleration,
        target.velocity,
        target.acceleration,
        l.jerk,
    );
    for (j1, j3) in [(j, -j), (-j, j), (j, j), (-j, -j)] {
        for root in [false, true] {
            let Some((t, a1)) = ramp_hold_ramp((v0, a0), (vf, af), (j1, j3), tau, l, root) else {
                continue;
            };
            if keeps_velocity(v0, a0, &t, [j1, j3], a1, l) {
                with_brake(
                    origin,
                    brake,
                    &t,
                    &[j1, R::ZERO, j3],
                    &[a0, a1, a1, af],
                    out,
                );
                return true;
            }
        }
    }
    false
}
