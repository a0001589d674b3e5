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
        let mut s = self.cruise_shape()?;
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
            let a5 = a - (a * a + c).root();
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
            let a1 = am + (am * am - c).root();
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
    out: &mut AxisProfile<R>,
) -> bool {
    let (start, brake_time) = super::brake::after(origin, &brake);
    let tau = duration - brake_time;
    let up = Up::new(&start, target, l);
    if tau < -up.tol.time {
        return false;
    }
    let tau = tau.max_of(R::ZERO);
    let (Some((hi, p_hi)), Some((lo, p_lo))) = (up.farthest(tau), up.mirrored().farthest(tau))
    else {
        return false;
    };
    let (lo, p_lo) = (lo.negated(), -p_lo);
    let tol = hi.position_tolerance.max_of(lo.position_tolerance);
    if up.dp > p_hi + tol || up.dp < p_lo - tol {
        return false;
    }
    let width = p_hi - p_lo;
    let lambda = if width > tol {
        ((up.dp - p_lo) / width).clamp_to(R::ZERO, R::ONE)
    } else {
        R::ONE
    };
    let hi = Phases {
        t: &hi.t,
        jerks: &hi.jerks,
        accelerations: &hi.accelerations,
    };
    let lo = Phases {
        t: &lo.t,
        jerks: &lo.jerks,
        accelerations: &lo.accelerations,
    };
    blend(origin, brake, &hi, &lo, lambda, out);
    true
}

/// The main phases of a motion (after the brake): durations, jerks, and the accelerations
/// at their starts and at the end, as its form prescribes.
#[derive(Clone, Copy, Debug)]
pub(super) struct Phases<'a, R> {
    pub(super) t: &'a [R],
    pub(super) jerks: &'a [R],
    pub(super) accelerations: &'a [R],
}

/// A walk along [`Phases`] from a start state: the current phase, its start time and state.
struct Walk<'a, R> {
    phases: &'a Phases<'a, R>,
    i: usize,
    begin: R,
    state: Kinematics<R>,
}

impl<R: Real> Walk<'_, R> {
    /// The end of the current phase (the last end once past the last phase).
    fn end(&self) -> R {
        match self.phases.t.get(self.i) {
            Some(&d) => self.begin + d,
            None => self.begin,
        }
    }

    fn done(&self) -> bool {
        self.i >= self.phases.t.len()
    }

    fn jerk(&self) -> R {
        self.phases.jerks.get(self.i).copied().unwrap_or(R::ZERO)
    }

    /// The state at time `x` of the current phase (after the last, continued without jerk).
    fn at(&self, x: R) -> Kinematics<R> {
        self.state.advance(self.jerk(), x - self.begin)
    }

    /// On to the next phase, at the acceleration the form prescribes there.
    fn step(&mut self) {
        if let Some(&d) = self.phases.t.get(self.i) {
            self.state = self.state.advance(self.jerk(), d);
            if let Some(&a) = self.phases.accelerations.get(self.i + 1) {
                self.state.acceleration = a;
            }
            self.begin += d;
            self.i += 1;
        }
    }
}

/// `λ·x_hi(t) + (1 − λ)·x_lo(t)` into `out`: the brake, then the phases between the merged
/// switching times of both motions, each with the blended jerk, and the blended states at
/// their starts (each motion's state evaluated on its own phase, not integrated across the
/// blend).
pub(super) fn blend<R: Real>(
    origin: &Kinematics<R>,
    brake: [JerkPhase<R>; 2],
    hi: &Phases<'_, R>,
    lo: &Phases<'_, R>,
    lambda: R,
    out: &mut AxisProfile<R>,
) {
    let mix = |x: R, y: R| lambda * x + (R::ONE - lambda) * y;
    let mixed = |x: &Kinematics<R>, y: &Kinematics<R>| {
        Kinematics::new(
            mix(x.position, y.position),
            mix(x.velocity, y.velocity),
            mix(x.acceleration, y.acceleration),
        )
    };
    let mut phases = [JerkPhase::default(); MAX_PHASES];
    phases[..2].copy_from_slice(&brake);
    out.states[0] = *origin;
    for (i, b) in brake.iter().enumerate() {
        let mut next = out.states[i].advance(b.jerk, b.duration);
        next.acceleration = out.states[i].acceleration + b.jerk * b.duration;
        out.states[i + 1] = next;
    }
    let start = out.states[2];
    let mut a = Walk {
        phases: hi,
        i: 0,
        begin: R::ZERO,
        state: start,
    };
    let mut b = Walk {
        phases: lo,
        i: 0,
        begin: R::ZERO,
        state: start,
    };
    let (mut time, mut n) = (R::ZERO, 2);
    while !(a.done() && b.done()) && n < MAX_PHASES {
        let next = if a.done() {
            b.end()
        } else if b.done() {
            a.end()
        } else {
            a.end().min_of(b.end())
        };
        if next > time {
            phases[n] = JerkPhase {
                jerk: mix(a.jerk(), b.jerk()),
                duration: next - time,
            };
            // Both motions start the main phases from the same state: keep it exact.
            out.states[n] = if n == 2 {
                start
            } else {
                mixed(&a.at(time), &b.at(time))
            };
            n += 1;
            time = next;
        }
        if !a.done() && a.end() <= next {
            a.step();
        }
        if !b.done() && b.end() <= next {
            b.step();
        }
    }
    let end = mixed(&a.at(time), &b.at(time));
    for s in &mut out.states[n..] {
        *s = end;
    }
    out.phases = phases;
    out.duration = brake[0].duration + brake[1].duration + time;
}
