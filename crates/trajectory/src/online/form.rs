//! The form of the time-optimal motion and of the motions at a given duration: seven
//! phases with the jerks `(+J, 0, −J, 0, −J, 0, +J)` ("UDDU", Berscheid & Kröger,
//! "Jerk-limited Real-time Trajectory Generation with Arbitrary Target States", *Robotics:
//! Science and Systems* 2021, §III), described by its peak and trough accelerations and
//! holds ([`Shape`]), and checked by integrating it ([`Up::integrate`]). Its mirror image
//! (`x → −x`) is the same form on the mirrored problem ([`Up::mirrored`]).

use super::profile::{AxisLimits, Kinematics};
use super::real::Real;

/// The problem in the frame where the first phase has positive jerk, with the start at
/// position 0.
#[derive(Clone, Copy, Debug)]
pub(super) struct Up<R> {
    pub(super) v0: R,
    pub(super) a0: R,
    /// Target position relative to the start.
    pub(super) dp: R,
    pub(super) vf: R,
    pub(super) af: R,
    pub(super) l: AxisLimits<R>,
    pub(super) tol: Tolerance<R>,
}

/// How far a candidate may miss, in this frame's units.
#[derive(Clone, Copy, Debug)]
pub(super) struct Tolerance<R> {
    /// The relative rounding allowed.
    pub(super) ulps: R,
    pub(super) time: R,
    pub(super) position: R,
    pub(super) velocity: R,
    pub(super) acceleration: R,
}

impl<R: Real> Tolerance<R> {
    /// Relative to the problem's scales: rounding in the formulas loses a few hundred units
    /// in the last place (`f64`), or a few tens of them of the coarser `f32` spacing.
    pub(super) fn of(start: &Kinematics<R>, target: &Kinematics<R>, l: &AxisLimits<R>) -> Self {
        let ulps = R::lit(if R::EPS > R::lit(1e-10) { 64.0 } else { 1024.0 }) * R::EPS;
        let big = |a: R, b: R| if a.abs() > b.abs() { a.abs() } else { b.abs() };
        let a = big(
            big(l.a_max, l.a_min),
            big(start.acceleration, target.acceleration),
        );
        let v = big(big(l.v_max, l.v_min), big(start.velocity, target.velocity));
        let t = a / l.jerk + v / a;
        // The displacement's own scale, and its rounding from the positions: not the
        // limits' (a short move would count as reached without moving).
        let dp = (target.position - start.position).abs();
        let positions = start.position.abs() + target.position.abs();
        Tolerance {
            ulps,
            time: ulps * t,
            position: ulps * dp + R::lit(4.0) * R::EPS * positions,
            velocity: ulps * v,
            acceleration: ulps * a,
        }
    }
}

/// A candidate in the first form: peak `a1` (held `t2`), trough `a5` (held `t6`), and the
/// velocity held for `t4` at zero acceleration between them (`cruise`) or not (the falling
/// phases merged).
#[derive(Clone, Copy, Debug)]
pub(super) struct Shape<R> {
    pub(super) a1: R,
    pub(super) t2: R,
    pub(super) t4: R,
    pub(super) a5: R,
    pub(super) t6: R,
    pub(super) cruise: bool,
}

impl<R: Real> Up<R> {
    /// The problem from `start` to `target`.
    pub(super) fn new(start: &Kinematics<R>, target: &Kinematics<R>, l: &AxisLimits<R>) -> Self {
        Up {
            v0: start.velocity,
            a0: start.acceleration,
            dp: target.position - start.position,
            vf: target.velocity,
            af: target.acceleration,
            l: *l,
            tol: Tolerance::of(start, target, l),
        }
    }

    /// The mirror image: every value negated, the limits exchanged.
    pub(super) fn mirrored(&self) -> Self {
        Up {
            v0: -self.v0,
            a0: -self.a0,
            dp: -self.dp,
            vf: -self.vf,
            af: -self.af,
            l: self.l.mirrored(),
            tol: self.tol,
        }
    }
}

impl<R: Real> Up<R> {
    /// The velocity held at `v_max` between the time-optimal velocity changes to and from
    /// it: rising to `a₁` and falling to zero (`a₁² = a₀²/2 + J(v_max − v₀)`, held at
    /// `a_max` beyond), then falling to `a₅` and rising to `a_f` (`a₅² = a_f²/2 + J(v_max −
    /// v_f)`, held at `a_min` beyond). The cruise `t₄` is left zero for the caller. `None`
    /// when `v_max` cannot be reached from the start or left towards the target that way.
    pub(super) fn cruise_shape(&self) -> Option<Shape<R>> {
        let (l, j, two) = (&self.l, self.l.jerk, R::TWO);
        let peak = self.a0 * self.a0 * R::HALF + j * (l.v_max - self.v0);
        let trough = self.af * self.af * R::HALF + j * (l.v_max - self.vf);
        if peak.is_negative() || trough.is_negative() {
            return None;
        }
        let mut s = Shape {
            a1: peak.root(),
            t2: R::ZERO,
            t4: R::ZERO,
            a5: -trough.root(),
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
        Some(s)
    }

    pub(super) fn jerks(&self) -> [R; 7] {
        let j = self.l.jerk;
        [j, R::ZERO, -j, R::ZERO, -j, R::ZERO, j]
    }

    /// The seven durations of a candidate (`None` if one is negative beyond rounding).
    pub(super) fn durations(&self, s: &Shape<R>) -> Option<[R; 7]> {
        let j = self.l.jerk;
        let (t3, t5) = if s.cruise {
            (s.a1 / j, -s.a5 / j)
        } else {
            ((s.a1 - s.a5) / j, R::ZERO)
        };
        let mut t = [
            (s.a1 - self.a0) / j,
            s.t2,
            t3,
            s.t4,
            t5,
            s.t6,
            (self.af - s.a5) / j,
        ];
        for x in &mut t {
            if (*x)
                .partial_cmp(&-self.tol.time)
                .is_none_or(core::cmp::Ordering::is_lt)
            {
                return None;
            }
            if x.is_negative() {
                *x = R::ZERO;
            }
        }
        Some(t)
    }

    /// The acceleration at the start of each phase and at the end, as the form prescribes.
    fn accelerations(&self, s: &Shape<R>) -> [R; 8] {
        let m = if s.cruise { R::ZERO } else { s.a5 };
        [self.a0, s.a1, s.a1, m, m, s.a5, s.a5, self.af]
    }

    /// The motion of a candidate when it is one: durations non-negative, limits kept, and
    /// the target velocity and acceleration reached. Returns it with its end position.
    pub(super) fn integrate(&self, s: &Shape<R>) -> Option<(Candidate<R>, R)> {
        let t = self.durations(s)?;
        let accelerations = self.accelerations(s);
        let jerks = self.jerks();
        let tol = &self.tol;
        let l = &self.l;
        let v_ok = |v: R| v <= l.v_max + tol.velocity && v >= l.v_min - tol.velocity;
        let a_ok = |a: R| a <= l.a_max + tol.acceleration && a >= l.a_min - tol.acceleration;
        let mut k = Kinematics::new(R::ZERO, self.v0, self.a0);
        // A bound of the distance travelled, the scale of the end position's rounding.
        let mut travelled = R::ZERO;
        for (i, (&j, &dt)) in jerks.iter().zip(&t).enumerate() {
            // The velocity's extreme inside the phase, where the acceleration crosses zero.
            // The first rise and hold are exempt: a start that brakes into the limits ends
            // its brake where the velocity is still coming back (inside the limits, the
            // first phases cannot pass a velocity limit).
            let checked = i >= 2;
            if checked && j != R::ZERO && dt > R::ZERO {
                let to_zero = -k.acceleration / j;
                if to_zero > R::ZERO && to_zero < dt && !v_ok(k.advance(j, to_zero).velocity) {
                    return None;
                }
            }
            let integrated = k.advance(j, dt);
            travelled += k.velocity.abs().max_of(integrated.velocity.abs()) * dt;
            if (checked && !v_ok(integrated.velocity)) || !a_ok(integrated.acceleration) {
                return None;
            }
            // The form's acceleration where rounding left it a little off.
            let close = (integrated.acceleration - accelerations[i + 1]).abs() <= tol.acceleration;
            k = Kinematics {
                acceleration: accelerations[i + 1],
                ..integrated
            };
            if !close {
                return None;
            }
        }
        let reached = (k.velocity - self.vf).abs() <= tol.velocity;
        // Rounding of a velocity (of the problem's velocity scale) grows linearly in time.
        let mut total = R::ZERO;
        for x in &t {
            total += *x;
        }
        let position_tolerance = tol
            .position
            .max_of(tol.ulps * travelled)
            .max_of(tol.velocity * total);
        reached.then_some((
            Candidate {
                t,
                jerks,
                accelerations,
                position_tolerance,
            },
            k.position,
        ))
    }

    /// The motion of a candidate when it is one and ends on the target position.
    pub(super) fn reaching(&self, s: &Shape<R>) -> Option<Candidate<R>> {
        let (c, end) = self.integrate(s)?;
        ((end - self.dp).abs() <= c.position_tolerance).then_some(c)
    }
}

/// A profile of the main phases: durations, jerks, and the accelerations at the phase
/// starts and the end.
#[derive(Clone, Copy, Debug)]
pub(super) struct Candidate<R> {
    pub(super) t: [R; 7],
    pub(super) jerks: [R; 7],
    pub(super) accelerations: [R; 8],
    /// How far the integrated end position may be off (rounding over the distance
    /// travelled).
    pub(super) position_tolerance: R,
}

impl<R: Real> Candidate<R> {
    pub(super) fn duration(&self) -> R {
        let mut total = R::ZERO;
        for x in &self.t {
            total += *x;
        }
        total
    }

    /// The mirror image.
    pub(super) fn negated(mut self) -> Self {
        self.jerks = self.jerks.map(|j| -j);
        self.accelerations = self.accelerations.map(|a| -a);
        self
    }
}
