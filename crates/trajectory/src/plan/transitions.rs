//! Transitions between zones that carry the acceleration across the boundary.
//!
//! Each zone's profile starts and ends with zero acceleration, so a speed that rises (or
//! falls) through several zones flattens out at every boundary and ramps up again: about
//! `a/j` seconds lost per boundary. Where the motion changes speed in the same direction on
//! both sides of a boundary, the stretch from the start of the change before it (`p`) to the
//! end of the change after it (`q`) is replaced by the time-optimal jerk-limited motion from
//! the state at `p` to the state at `q` under the tighter limits of the two zones: the
//! one-dimensional online solver ([`solve_axis`]), after Berscheid & Kröger, "Jerk-limited
//! Real-time Trajectory Generation with Arbitrary Target States", *RSS* 2021. It reaches
//! the speed at `q` as early as the limits allow (or leaves the speed at `p` as late as they
//! allow) and passes the boundary with whatever acceleration it has there.
//!
//! The replacement is kept only where it is faster and stays within each zone's limits on
//! its part of the zone: speed `0 ≤ v ≤ v_limit` (and the boundary's exit cap), `|a|` and
//! `|j|` within the zone's, checked on every phase (the speed of a constant-jerk phase
//! peaks at its ends or where its acceleration crosses zero), and where both zones still
//! hold it in their seven phases. One pass from the first boundary to the
//! last; a zone whose start was changed by one boundary may be changed again at the next,
//! starting from a state with acceleration.

use super::motion::{MotionState, Phase, ProfileZone};
use crate::online::{AxisLimits, AxisProfile, Kinematics, solve_axis};

/// The relative rounding allowed on a zone's speed and acceleration limit: the transition is
/// solved at the limits, and its integrated phases may pass them by a few ulp.
const ROUNDING: f64 = 1e-12;

/// Bisection steps for the time at which a constant-jerk phase reaches the boundary: the
/// bracket is a phase of at most a few seconds, halved to far below one `f64` ulp of it.
const SPLIT_STEPS: usize = 80;

/// The direction of a speed change: rising (`true`) or falling.
type Rising = bool;

/// Replaces the stretch around each boundary of `zones` whose speed changes in one direction
/// on both sides by the faster online transition, where it keeps the zones' limits, then
/// restores the start times of the zones and phases. Zones with an infinite jerk limit
/// (trapezoids, whose acceleration may jump at the boundary anyway) are left as they are.
pub(super) fn carry_acceleration(zones: &mut [ProfileZone]) {
    for i in 1..zones.len() {
        if let [.., before, after] = &mut zones[..=i] {
            carry_across(before, after);
        }
    }
    retime(zones, 0.0);
}

/// Replaces the stretch around the boundary of `before` and `after` whose speed changes in
/// one direction on both sides by the transition that carries the acceleration across it,
/// in place, `after` timed on from the end of `before`; `false` (the zones unchanged)
/// where there is none, it is not faster, or it leaves a limit.
pub(super) fn carry_across(before: &mut ProfileZone, after: &mut ProfileZone) -> bool {
    for rising in [true, false] {
        if let Some((b, a)) = transition(before, after, rising) {
            (*before, *after) = (b, a);
            retime(core::slice::from_mut(after), before.t_end());
            return true;
        }
    }
    false
}

/// The two zones with the transition through their boundary in the direction `rising`, or
/// `None` where there is none, it is not faster, or it leaves a limit.
fn transition(
    before: &ProfileZone,
    after: &ProfileZone,
    rising: Rising,
) -> Option<(ProfileZone, ProfileZone)> {
    if !(before.j_limit.is_finite() && after.j_limit.is_finite()) {
        return None;
    }
    let head = changing_run(before.phases().iter().rev(), rising)?;
    let tail = changing_run(after.phases().iter(), rising)?;
    let first = before.phases().len() - head;
    let p = before.phases().get(first)?.local(0.0);
    let last = after.phases().get(tail - 1)?;
    let q = last.local(last.duration);
    let old: f64 = before.phases()[first..]
        .iter()
        .chain(&after.phases()[..tail])
        .map(|ph| ph.duration)
        .sum();
    let a = before.a_limit.min(after.a_limit);
    let j = before.j_limit.min(after.j_limit);
    let limits = AxisLimits::new(p.v.max(q.v), a, j).ok()?;
    let start = Kinematics::new(p.s, p.v, p.a);
    let target = Kinematics::new(q.s, q.v, q.a);
    let block = solve_axis(&start, &target, &limits).ok()?;
    let profile = block.profile();
    if profile.duration() >= old || profile.duration().is_nan() {
        return None;
    }
    split_at(before, after, first, tail, phases_of(profile))
}

/// The phases of an online profile: their durations, start accelerations and jerks (the
/// empty ones left out).
fn phases_of(profile: &AxisProfile<f64>) -> impl Iterator<Item = (f64, f64, f64)> + Clone + '_ {
    profile
        .phases()
        .iter()
        .zip(profile.states())
        .filter(|(ph, _)| ph.duration > 0.0)
        .map(|(ph, st)| (ph.duration, st.acceleration, ph.jerk))
}

/// `zone` (its extent, limits, entry time and end speed) entered in the state `start`, with
/// acceleration: the time-optimal motion from there to the zone's end at its end speed and
/// without acceleration (the online solver's). `None` where that leaves the zone's limits,
/// takes more than its phases, or misses its end.
pub(super) fn entered_with(zone: &ProfileZone, start: MotionState) -> Option<ProfileZone> {
    let limits = AxisLimits::new(zone.v_limit, zone.a_limit, zone.j_limit).ok()?;
    let from = Kinematics::new(start.s, start.v, start.a);
    let to = Kinematics::new(zone.end, zone.v_end, 0.0);
    let block = solve_axis(&from, &to, &limits).ok()?;
    let mut out = cleared(zone);
    out.v_start = start.v;
    let mut state = start;
    for (duration, a0, j) in phases_of(block.profile()) {
        let phase = phase_from(&state, duration, a0, j);
        push_within(&mut out, &phase)?;
        state = phase.local(duration);
    }
    let close = |x: f64, y: f64| (x - y).abs() <= 1e-9 * (1.0 + x.abs().max(y.abs()));
    let ends = close(state.s, zone.end) && close(state.v, zone.v_end);
    (ends && state.a.abs() <= 1e-6 * zone.a_limit).then_some(out)
}

/// The number of phases at the start of `phases` (taken in the order given) that change
/// the speed only in the direction `rising` or hold it, when at least one of them changes
/// it; `None` otherwise.
fn changing_run<'a>(phases: impl Iterator<Item = &'a Phase>, rising: Rising) -> Option<usize> {
    let (mut count, mut changes) = (0, false);
    for ph in phases {
        let end = ph.local(ph.duration).a;
        let along = |a: f64| if rising { a >= 0.0 } else { a <= 0.0 };
        if !(along(ph.a0) && along(end)) {
            break;
        }
        changes |= ph.j != 0.0;
        count += 1;
    }
    changes.then_some(count)
}

/// The two zones rebuilt: `before` keeps its phases up to `first`, then the transition's
/// `phases` up to its boundary; `after` starts with the rest of them and goes on with its
/// own phases from `tail` on. `None` where a part leaves its zone's limits or phases.
fn split_at(
    before: &ProfileZone,
    after: &ProfileZone,
    first: usize,
    tail: usize,
    phases: impl Iterator<Item = (f64, f64, f64)> + Clone,
) -> Option<(ProfileZone, ProfileZone)> {
    let mut b = cleared(before);
    for ph in before.phases().get(..first)? {
        push_counted(&mut b, ph)?;
    }
    let start = before.phases().get(first)?.local(0.0);
    let mut a = cleared(after);
    let mut state = start;
    let mut crossed = false;
    for (duration, a0, j) in phases {
        let phase = phase_from(&state, duration, a0, j);
        let end = phase.local(duration);
        if crossed {
            push_within(&mut a, &phase)?;
        } else if end.s <= after.start {
            push_within(&mut b, &phase)?;
        } else {
            let tau = crossing(&phase, after.start);
            let at = phase.local(tau);
            push_within(
                &mut b,
                &Phase {
                    duration: tau,
                    ..phase
                },
            )?;
            a.v_start = at.v;
            let rest = Phase {
                duration: duration - tau,
                s0: at.s,
                v0: at.v,
                a0: at.a,
                ..phase
            };
            push_within(&mut a, &rest)?;
            crossed = true;
        }
        state = end;
    }
    b.v_end = a.v_start;
    for ph in after.phases().get(tail..)? {
        push_counted(&mut a, ph)?;
    }
    (crossed && b.v_end <= before.exit_cap).then_some((b, a))
}

/// The phase of `duration` from `state`'s arc length and speed with the acceleration `a0`
/// and the jerk `j` (its start time is set where it is pushed).
fn phase_from(state: &MotionState, duration: f64, a0: f64, j: f64) -> Phase {
    Phase {
        t0: 0.0,
        duration,
        s0: state.s,
        v0: state.v,
        a0,
        j,
    }
}

/// `zone` without phases.
fn cleared(zone: &ProfileZone) -> ProfileZone {
    ProfileZone { count: 0, ..*zone }
}

/// [`push_counted`] when `phase` keeps the zone's limits (within [`ROUNDING`]).
fn push_within(zone: &mut ProfileZone, phase: &Phase) -> Option<()> {
    let (lo, hi) = speed_range(phase);
    let a_end = phase.a0 + phase.j * phase.duration;
    let keeps = lo >= 0.0
        && hi <= zone.v_limit * (1.0 + ROUNDING)
        && phase.a0.abs().max(a_end.abs()) <= zone.a_limit * (1.0 + ROUNDING)
        && phase.j.abs() <= zone.j_limit;
    if !keeps {
        return None;
    }
    push_counted(zone, phase)
}

/// Appends `phase` to `zone` (continuing its state; the first phase starts at the phase's
/// own arc length and speed) when a free phase slot is left (a cruise continuing a cruise
/// takes none).
fn push_counted(zone: &mut ProfileZone, phase: &Phase) -> Option<()> {
    let entry = (zone.t_start, phase.s0, phase.v0);
    zone.push(entry, phase.duration, phase.a0, phase.j)
        .then_some(())
}

/// The least and the largest speed of `phase`: at its ends, or where its acceleration
/// crosses zero inside it.
fn speed_range(phase: &Phase) -> (f64, f64) {
    let (v0, v1) = (phase.v0, phase.local(phase.duration).v);
    let (mut lo, mut hi) = (v0.min(v1), v0.max(v1));
    if phase.j != 0.0 {
        let tau = -phase.a0 / phase.j;
        if tau > 0.0 && tau < phase.duration {
            let v = phase.local(tau).v;
            (lo, hi) = (lo.min(v), hi.max(v));
        }
    }
    (lo, hi)
}

/// The time in `phase` at which its arc length reaches `s` (its speed is not negative, so
/// the arc length rises): bisection, the end of the bracket whose arc length is at least
/// `s`.
fn crossing(phase: &Phase, s: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, phase.duration);
    for _ in 0..SPLIT_STEPS {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if phase.local(mid).s < s {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    hi
}

/// Sets the start time of every zone and phase from the durations, in order from `t`.
fn retime(zones: &mut [ProfileZone], mut t: f64) {
    for zone in zones.iter_mut() {
        zone.t_start = t;
        for ph in zone.phases_mut() {
            ph.t0 = t;
            t += ph.duration;
        }
    }
}
