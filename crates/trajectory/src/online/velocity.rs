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
use super::step2::Phases;

/// The three phases (rise, hold, fall) in the frame where the first phase has positive jerk,
/// if they are a motion: every duration non-negative.
fn rise_hold_fall<R: Real>(v0: R, a0: R, vf: R, af: R, a_max: R, j: R) -> Option<[R; 3]> {
    let two = R::TWO;
    let peak2 = (a0 * a0 + af * af) * R::HALF + j * (vf - v0);
    if peak2.is_negative() {
        return None;
    }
    let mut peak = peak2.sqrt();
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

/// The velocity change of duration `tau` that ends fastest in the positive direction
/// (rise to a peak, held at `a_max` if it would pass it, fall to `a_f`), with its phases
/// and end velocity; `None` if `tau` is too short to bring the acceleration to `a_f`.
fn fastest<R: Real>(v0: R, a0: R, af: R, a_max: R, j: R, tau: R) -> Option<([R; 3], R)> {
    let mut peak = (j * tau + a0 + af) * R::HALF;
    let mut hold = R::ZERO;
    if peak > a_max {
        peak = a_max;
        hold = tau - (R::TWO * a_max - a0 - af) / j;
    }
    let t = [(peak - a0) / j, hold, (peak - af) / j];
    let slack = R::lit(64.0) * R::EPS * (a_max / j + tau);
    if !t.iter().all(|&x| x >= -slack) {
        return None;
    }
    let t = t.map(|x| x.max_of(R::ZERO));
    let v = v0
        + (peak * peak - a0 * a0) / (R::TWO * j)
        + peak * t[1]
        + (peak * peak - af * af) / (R::TWO * j);
    Some((t, v))
}

/// The velocity change from `origin` to `target`'s velocity and acceleration that takes
/// exactly `duration` seconds: the convex combination of the fastest changes in either
/// direction that ends on the target velocity (see the fixed-duration position motions).
pub(super) fn with_duration<R: Real>(
    origin: &Kinematics<R>,
    target: &Kinematics<R>,
    l: &AxisLimits<R>,
    duration: R,
    out: &mut AxisProfile<R>,
) -> bool {
    let brake = velocity_mode_brake(origin.acceleration, l);
    let (start, brake_time) = after(origin, &brake);
    let tau = duration - brake_time;
    let (v0, a0, vf, af, j) = (
        start.velocity,
        start.acceleration,
        target.velocity,
        target.acceleration,
        l.jerk,
    );
    let tau = tau.max_of(R::ZERO);
    let (Some((t_hi, v_hi)), Some((t_lo, v_lo))) = (
        fastest(v0, a0, af, l.a_max, j, tau),
        fastest(-v0, -a0, -af, -l.a_min, j, tau),
    ) else {
        return false;
    };
    let v_lo = -v_lo;
    let scale = v0.abs().max_of(vf.abs()).max_of(l.a_max * tau) + l.a_max * l.a_max / j;
    let tol = R::lit(1024.0) * R::EPS * scale;
    if vf > v_hi + tol || vf < v_lo - tol {
        return false;
    }
    let width = v_hi - v_lo;
    let lambda = if width > tol {
        ((vf - v_lo) / width).clamp_to(R::ZERO, R::ONE)
    } else {
        R::ONE
    };
    let peak_hi = a0 + j * t_hi[0];
    let peak_lo = a0 - j * t_lo[0];
    let (jerks_hi, jerks_lo) = ([j, R::ZERO, -j], [-j, R::ZERO, j]);
    let (accs_hi, accs_lo) = ([a0, peak_hi, peak_hi, af], [a0, peak_lo, peak_lo, af]);
    let hi = Phases {
        t: &t_hi,
        jerks: &jerks_hi,
        accelerations: &accs_hi,
    };
    let lo = Phases {
        t: &t_lo,
        jerks: &jerks_lo,
        accelerations: &accs_lo,
    };
    super::step2::blend(origin, brake, &hi, &lo, lambda, out);
    true
}
