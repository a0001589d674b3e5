//! A motion of one axis that takes a given duration: what synchronizes an axis with a
//! slower one.
//!
//! With the start, the end velocity and acceleration and the duration fixed, the motions
//! that keep the limits form a convex set (the dynamics are linear, the limits are
//! intervals), so the positions they end on form an interval `[p_lo, p_hi]`. Its ends are
//! reached by the motions that go as far as the duration allows in either direction: by
//! Pontryagin's maximum principle (maximizing `p(T)`, the costate of the acceleration is a
//! convex parabola in time) these are of the form `(+J, 0, −J, 0, −J, 0, +J)` and its
//! mirror image, with the duration fixed instead of the position; every limit combination
//! of the form is a closed form here (at most a quadratic). The duration is feasible
//! exactly when the target position lies in `[p_lo, p_hi]`; the motion is then the convex
//! combination `λ·x_hi(t) + (1 − λ)·x_lo(t)` that ends on it, whose jerk
//! `λ·j_hi + (1 − λ)·j_lo` never exceeds `J` and whose velocity and acceleration stay
//! within the limits because both motions' do. It has at most 13 phases (the two motions'
//! switching times merged).

use super::form::{Candidate, Shape, Up};
use super::profile::{AxisLimits, AxisProfile, JerkPhase, Kinematics, MAX_PHASES};
use super::real::Real;
use super::step1::with_brake;

impl<R: Real> Up<R> {
    /// The motion of the form with duration `tau` that ends farthest in the positive
    /// direction, with its end position.
    fn farthest(&self, tau: R) -> Option<(Candidate<R>, R)> {
        let mut best: Option<(Candidate<R>, R)> = None;
        let mut consider = |s: Shape<R>| {
            if let Some((c, p)) = self.integrate(&s)
                && best.is_none_or(|(_, q)| p > q)
            {
                best = Some((c, p));
            }
        };
        if let Some(s) = self.cruise_within(tau) {
            consider(s);
        }
        for s in self.fixed_duration_shapes(tau).into_iter().flatten() {
            consider(s);
        }
        best
    }

    /// The velocity held at `v_max` between the time-optimal changes to and from it, for
    /// what remains of `tau`.
    fn cruise_within(&self, tau: R) -> Option<Shape<R>> {
        let (l, j) = (&self.l, self.l.jerk);
        let two = R::TWO;
        let peak = self.a0 * self.a0 * R::HALF + j * (l.v_max - self.v0);
        let trough = self.af * self.af * R::HALF + j * (l.v_max - self.vf);
        if peak.is_negative() || trough.is_negative() {
            return None;
        }
        let mut s = Shape {
            a1: peak.sqrt(),
            t2: R::ZERO,
            t4: R::ZERO,
            a5: -trough.sqrt(),
            t6: R::ZERO,
            cruise: true,
        };
        if s.a1 > l.a_max {
            s.a1 = l.a_max;
            s.t2 = (l.v_max - self.v0 - (two * l.a_max * l.a_max - self.a0 * self.a0) / (two * j))
                / l.a_max;
        }
        if s.a5 < l.a_min {
            s.a5 = l.a_min;
            s.t6 = (self.vf - l.v_max - (self.af * self.af - two * l.a_min * l.a_min) / (two * j))
                / l.a_min;
        }
        let t = self.durations(&s)?;
        let mut rest = tau;
        for x in &t {
            rest -= *x;
        }
        s.t4 = rest;
        Some(s)
    }

    /// The forms without cruise whose duration is `tau`: no hold (`u = a₁ − a₅` from the
    /// duration, `a₁ + a₅` from the velocity), the peak held (a quadratic in `a₅`), the
    /// trough held (a quadratic in `a₁`), both held (linear in `t₂`).
    fn fixed_duration_shapes(&self, tau: R) -> [Option<Shape<R>>; 4] {
        let (l, j) = (&self.l, self.l.jerk);
        let (a0, v0, af, vf) = (self.a0, self.v0, self.af, self.vf);
        let (a, am, two, half) = (l.a_max, l.a_min, R::TWO, R::HALF);
        let merged = |a1: R, t2: R, a5: R, t6: R| {
            Some(Shape {
                a1,
                t2,
                t4: R::ZERO,
                a5,
                t6,
                cruise: false,
            })
        };
        let squares = (a0 * a0 - af * af) * half;
        let kk = j * (vf - v0) + squares;
        let u = (j * tau + a0 - af) * half;
        let none = if u > R::ZERO {
            merged((u + kk / u) * half, R::ZERO, (kk / u - u) * half, R::ZERO)
        } else {
            merged(a0, R::ZERO, a0, R::ZERO)
        };
        let c = -a * a + a * (j * tau + a0 - af) + j * (v0 - vf) - squares;
        let peak = (a * a + c >= R::ZERO).then(|| {
            let a5 = a - (a * a + c).sqrt();
            Shape {
                a1: a,
                t2: (j * tau - two * a + a0 - af + two * a5) / j,
                t4: R::ZERO,
                a5,
                t6: R::ZERO,
                cruise: false,
            }
        });
        let c = am * am + am * (j * tau + a0 - af) + j * (v0 - vf) - squares;
        let trough = (am * am - c >= R::ZERO).then(|| {
            let a1 = am + (am * am - c).sqrt();
            Shape {
                a1,
                t2: R::ZERO,
                t4: R::ZERO,
                a5: am,
                t6: (two * am + j * tau + a0 - af - two * a1) / j,
                cruise: false,
            }
        });
        let span = a - am;
        let t2 = (-span * span - am * (j * tau + a0 - af) + j * (vf - v0) + squares) / (j * span);
        let t6 = (-two * span + j * (tau - t2) + a0 - af) / j;
        [none, peak, trough, merged(a, t2, am, t6)]
    }
}

/// The motion from `origin` (first the `brake` phases) to `target` that takes exactly
/// `duration` seconds, or `None` when the axis cannot take that duration.
pub(super) fn with_duration<R: Real>(
    origin: &Kinematics<R>,
    brake: [JerkPhase<R>; 2],
    target: &Kinematics<R>,
    l: &AxisLimits<R>,
    duration: R,
) -> Option<AxisProfile<R>> {
    let mut start = *origin;
    let mut tau = duration;
    for p in &brake {
        start = start.advance(p.jerk, p.duration);
        tau -= p.duration;
    }
    let up = Up::new(&start, target, l);
    if tau < -up.tol.time {
        return None;
    }
    let tau = tau.max_of(R::ZERO);
    let (hi, p_hi) = up.farthest(tau)?;
    let (lo, p_lo) = up.mirrored().farthest(tau)?;
    let (lo, p_lo) = (lo.negated(), -p_lo);
    let tol = hi.position_tolerance.max_of(lo.position_tolerance);
    if up.dp > p_hi + tol || up.dp < p_lo - tol {
        return None;
    }
    let width = p_hi - p_lo;
    let lambda = if width > tol {
        ((up.dp - p_lo) / width).clamp_to(R::ZERO, R::ONE)
    } else {
        R::ONE
    };
    let hi = with_brake(origin, brake, &hi.t, &hi.jerks, &hi.accelerations);
    let lo = with_brake(origin, brake, &lo.t, &lo.jerks, &lo.accelerations);
    Some(blend(&hi, &lo, lambda))
}

/// The switching times of a profile's main phases (after the brake), in increasing order:
/// the ends of its phases of positive duration.
fn switches<R: Real>(p: &AxisProfile<R>, out: &mut [R; 7]) -> usize {
    let mut t = p.phases[0].duration + p.phases[1].duration;
    let mut n = 0;
    for phase in &p.phases[2..] {
        if phase.duration > R::ZERO && n < out.len() {
            t += phase.duration;
            out[n] = t;
            n += 1;
        }
    }
    n
}

/// `λ·x_hi(t) + (1 − λ)·x_lo(t)`: the phases between the merged switching times of both,
/// each with the blended jerk, and the blended states at their starts. The two motions
/// share their first two phases (the brake).
pub(super) fn blend<R: Real>(
    hi: &AxisProfile<R>,
    lo: &AxisProfile<R>,
    lambda: R,
) -> AxisProfile<R> {
    let mix = |x: R, y: R| lambda * x + (R::ONE - lambda) * y;
    let state = |t: R| {
        let (x, y) = (hi.at(t), lo.at(t));
        Kinematics::new(
            mix(x.position, y.position),
            mix(x.velocity, y.velocity),
            mix(x.acceleration, y.acceleration),
        )
    };
    let (mut a, mut b) = ([R::ZERO; 7], [R::ZERO; 7]);
    let (na, nb) = (switches(hi, &mut a), switches(lo, &mut b));
    let mut phases = [JerkPhase::default(); MAX_PHASES];
    let mut states = [hi.start(); MAX_PHASES + 1];
    phases[..2].copy_from_slice(&hi.phases[..2]);
    states[..3].copy_from_slice(&hi.states[..3]);
    let mut t = hi.phases[0].duration + hi.phases[1].duration;
    let (mut i, mut k, mut n) = (0, 0, 2);
    while (i < na || k < nb) && n < MAX_PHASES {
        let next = if k >= nb || (i < na && a[i] <= b[k]) {
            a[i]
        } else {
            b[k]
        };
        if i < na && a[i] <= next {
            i += 1;
        }
        if k < nb && b[k] <= next {
            k += 1;
        }
        if next > t {
            let mid = t + (next - t) * R::HALF;
            phases[n] = JerkPhase {
                jerk: mix(hi.jerk_at(mid), lo.jerk_at(mid)),
                duration: next - t,
            };
            // Both motions start the main phases from the same state: keep it exact.
            if n > 2 {
                states[n] = state(t);
            }
            n += 1;
            t = next;
        }
    }
    for s in &mut states[n..] {
        *s = state(t);
    }
    let mut duration = R::ZERO;
    for p in &phases {
        duration += p.duration;
    }
    AxisProfile {
        phases,
        states,
        duration,
    }
}
