//! Several axes moved together: each axis's time-optimal motion and feasible durations,
//! then one duration for all ([`Synchronization`]).

use super::profile::JerkPhase;
use super::profile::{AxisLimits, AxisProfile, Kinematics};
use super::real::Real;
use super::step1::{self, Span};
use super::{brake, step2, velocity};
use crate::error::Error;

/// How the axes of a move are timed together.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Synchronization {
    /// Every axis finishes at the same time: the smallest duration that every axis can take
    /// (at least the slowest axis's minimum, and outside every axis's gaps).
    #[default]
    Time,
    /// Every axis follows the same motion scaled (a straight line in axis space) when the
    /// start and target states lie on one line (velocities and accelerations parallel to
    /// the displacement); otherwise as [`Synchronization::Time`].
    Phase,
    /// Every axis on its own, as fast as it can.
    None,
}

/// Whether the move goes to a target position, or only to a velocity.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Interface {
    /// To the target's position, velocity and acceleration.
    #[default]
    Position,
    /// To the target's velocity and acceleration, the position free (jogging).
    Velocity,
}

/// One axis's time-optimal motion (into `out`) and feasible durations in the move's
/// interface.
pub(super) fn axis_span<R: Real>(
    start: &Kinematics<R>,
    target: &Kinematics<R>,
    l: &AxisLimits<R>,
    interface: Interface,
    out: &mut AxisProfile<R>,
) -> Result<Span<R>, Error> {
    let position = interface == Interface::Position;
    let finite =
        start.is_finite() && target.velocity.is_finite() && target.acceleration.is_finite();
    if !finite || (position && !target.position.is_finite()) {
        return Err(Error::NonFiniteState);
    }
    super::check_target(target, l, position)?;
    let span = if position {
        let brake = brake::position_brake(start.velocity, start.acceleration, l);
        step1::time_optimal(start, brake, target, l, out)
    } else {
        velocity::time_optimal(start, target, l, out)
    };
    span.ok_or(Error::NoProfile)
}

/// One axis's motion of exactly `duration` in the move's interface.
pub(super) fn axis_with_duration<R: Real>(
    start: &Kinematics<R>,
    target: &Kinematics<R>,
    l: &AxisLimits<R>,
    interface: Interface,
    duration: R,
    out: &mut AxisProfile<R>,
) -> bool {
    match interface {
        Interface::Position => {
            let brake = brake::position_brake(start.velocity, start.acceleration, l);
            step2::with_duration(start, brake, target, l, duration, out)
        }
        Interface::Velocity => velocity::with_duration(start, target, l, duration, out),
    }
}

/// Rounds durations up to whole ticks of a control rate (or leaves them as they are).
#[derive(Clone, Copy, Debug)]
pub(super) struct Grid(pub(super) Option<f64>);

impl Grid {
    /// `t` rounded up to the next tick (at most one tick longer).
    pub(super) fn up<R: Real>(&self, t: R) -> R {
        match self.0 {
            Some(rate) => R::lit(libm::ceil(t.to_f64() * rate) / rate),
            None => t,
        }
    }
}

/// The smallest duration on the grid, at least every axis's minimum, that no axis finds in
/// a gap: the largest minimum, or the end of a gap that holds it (and so on: each pass
/// moves past one gap, so at most one pass per gap and one more).
pub(super) fn common_duration<R: Real>(blocks: &[Span<R>], grid: Grid) -> R {
    let mut t = R::ZERO;
    for b in blocks {
        t = t.max_of(b.t_min);
    }
    t = grid.up(t);
    for _ in 0..=2 * blocks.len() {
        let mut moved = false;
        for b in blocks {
            for &(lo, hi) in b.gaps() {
                if t > lo && t < hi {
                    t = grid.up(hi);
                    moved = true;
                }
            }
        }
        if !moved {
            break;
        }
    }
    t
}

/// The state of axis `i` as its share `r` of a line motion that starts at `line0`:
/// `x₀ + r·(x_line − x_line₀)`, velocity and acceleration `r·` the line's.
fn scaled<R: Real>(x0: R, r: R, line0: R, k: &Kinematics<R>) -> Kinematics<R> {
    Kinematics::new(
        x0 + r * (k.position - line0),
        r * k.velocity,
        r * k.acceleration,
    )
}

/// The values that must lie on one line for a phase-synchronized move (displacement,
/// start and target velocity and acceleration), and the magnitudes their rounding scales
/// with (the positions', for the displacement).
fn line_values<R: Real>(
    start: &Kinematics<R>,
    target: &Kinematics<R>,
    interface: Interface,
) -> ([R; 5], [R; 5]) {
    let (dp, dp_scale) = match interface {
        Interface::Position => (
            target.position - start.position,
            target.position.abs() + start.position.abs(),
        ),
        Interface::Velocity => (R::ZERO, R::ZERO),
    };
    let values = [
        dp,
        start.velocity,
        start.acceleration,
        target.velocity,
        target.acceleration,
    ];
    let mut scales = values.map(|x| x.abs());
    scales[0] = dp_scale;
    (values, scales)
}

/// The share `r_i` of every axis in a line through the reference axis's values, if the
/// axes' values lie on one, with the reference axis. "On one line" allows twice what the
/// values' rounding explains: each value's (the solver's, `64 ε` of the value's magnitude,
/// or the start's, [`MoveOptions::start_rounding`](super::MoveOptions::start_rounding):
/// `relative` of the magnitude plus `absolute`), the reference's share of it, and the
/// uncertainty of the share itself (a ratio of two rounded values: a short displacement
/// far from the origin is known to few digits).
fn line_shares<R: Real, const A: usize>(
    values: &[[R; 5]; A],
    scales: &[[R; 5]; A],
    (relative, absolute): (R, R),
) -> Option<([R; A], usize)> {
    let relative = relative.max_of(R::lit(64.0) * R::EPS);
    let tol = |i: usize, m: usize| relative * scales[i][m] + absolute;
    // The reference: the value known to the most digits (largest against its rounding), so
    // that the shares are as certain as the values allow.
    let mut reference = None;
    let mut best = R::ZERO;
    for (i, w) in values.iter().enumerate() {
        for (m, x) in w.iter().enumerate() {
            let t = tol(i, m);
            if x.abs() > best * t {
                best = x.abs() / t;
                reference = Some((i, m));
            }
        }
    }
    let (k, c) = reference?;
    let mut shares = [R::ZERO; A];
    let reference = values[k];
    for (i, w) in values.iter().enumerate() {
        let r = w[c] / reference[c];
        // The share is as uncertain as the values it is the ratio of.
        let dr = (tol(i, c) + r.abs() * tol(k, c)) / reference[c].abs();
        for m in 0..5 {
            let allowed = tol(i, m) + r.abs() * tol(k, m) + dr * reference[m].abs();
            if (w[m] - r * reference[m]).abs() > R::TWO * allowed {
                return None;
            }
        }
        shares[i] = r;
    }
    Some((shares, k))
}

/// The limits of the line parameter (the reference axis's coordinate): every axis's
/// limits divided by its share, the tightest of each.
fn line_limits<R: Real, const A: usize>(
    shares: &[R; A],
    limits: &[AxisLimits<R>; A],
) -> Result<AxisLimits<R>, Error> {
    let big = R::MAX;
    let (mut v_max, mut v_min, mut a_max, mut a_min, mut jerk) = (big, -big, big, -big, big);
    for (r, l) in shares.iter().zip(limits) {
        let m = r.abs();
        if m == R::ZERO {
            continue;
        }
        let l = if r.is_negative() { l.mirrored() } else { *l };
        v_max = v_max.min_of(l.v_max / m);
        v_min = v_min.max_of(l.v_min / m);
        a_max = a_max.min_of(l.a_max / m);
        a_min = a_min.max_of(l.a_min / m);
        jerk = jerk.min_of(l.jerk / m);
    }
    AxisLimits::new(v_max, a_max, jerk)?.with_minimum(v_min, a_min)
}

/// The phase-synchronized profiles: the reference axis's motion along the line, every
/// axis its share of it. `None` when the states do not lie on one line.
pub(super) fn phase_profiles<R: Real, const A: usize>(
    start: &[Kinematics<R>; A],
    target: &[Kinematics<R>; A],
    limits: &[AxisLimits<R>; A],
    interface: Interface,
    grid: Grid,
    rounding: (R, R),
    out: &mut [AxisProfile<R>; A],
) -> Result<bool, Error> {
    let mut values = [[R::ZERO; 5]; A];
    let mut scales = [[R::ZERO; 5]; A];
    for i in 0..A {
        (values[i], scales[i]) = line_values(&start[i], &target[i], interface);
    }
    let Some((shares, k)) = line_shares(&values, &scales, rounding) else {
        return Ok(false);
    };
    let line_limits = line_limits(&shares, limits)?;
    let mut reference = AxisProfile::still(start[k].position);
    let line = axis_span(
        &start[k],
        &target[k],
        &line_limits,
        interface,
        &mut reference,
    )?;
    let duration = common_duration(core::slice::from_ref(&line), grid);
    if duration != line.t_min
        && !axis_with_duration(
            &start[k],
            &target[k],
            &line_limits,
            interface,
            duration,
            &mut reference,
        )
    {
        return Err(Error::NoProfile);
    }
    for (i, p) in out.iter_mut().enumerate() {
        let r = shares[i];
        p.duration = reference.duration;
        for (ph, k_phase) in p.phases.iter_mut().zip(&reference.phases) {
            *ph = JerkPhase {
                jerk: r * k_phase.jerk,
                duration: k_phase.duration,
            };
        }
        for (s, k_state) in p.states.iter_mut().zip(&reference.states) {
            *s = scaled(start[i].position, r, start[k].position, k_state);
        }
    }
    Ok(true)
}
