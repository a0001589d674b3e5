//! The time-optimal motion of one axis from a state inside its limits to a target state, and
//! the durations it can take: every profile of the form that the time-optimal motion has.
//!
//! By Pontryagin's maximum principle the time-optimal jerk-limited motion switches between
//! maximal jerk `±J` and zero jerk, and zero jerk only on a limit: the acceleration held at
//! a limit, or the velocity held at a limit with zero acceleration. Berscheid & Kröger
//! ("Jerk-limited Real-time Trajectory Generation with Arbitrary Target States", *Robotics:
//! Science and Systems* 2021, §III–IV) show that the time-optimal motion between states
//! inside the limits has at most seven phases with the jerks `(+J, 0, −J, 0, −J, 0, +J)` or
//! their mirror image `(−J, 0, +J, 0, +J, 0, −J)` ("UDDU"). In the first form the
//! acceleration rises from `a₀` to a peak `a₁` (held there for `t₂` if `a₁ = a_max`), falls
//! to a trough `a₅` (through zero, where the velocity may be held at `v_max` for `t₄`), is
//! held there for `t₆` if `a₅ = a_min`, and rises to `a_f`.
//!
//! Which limits are reached decides the unknowns. The velocity equation and the position
//! equation leave one unknown, found as a root of a polynomial:
//!
//! | limits reached   | unknown               | equation                              |
//! |------------------|-----------------------|---------------------------------------|
//! | `v` (± `a` both) | —                     | closed form, `t₄` from the position   |
//! | `a_max`, `a_min` | `t₂`                  | quadratic                             |
//! | `a_max`          | `a₅`                  | quartic                               |
//! | `a_min`          | `a₁`                  | quartic                               |
//! | none             | `u = a₁ − a₅`         | quartic (`a₁, a₅ = (K/u ± u)/2`)      |
//!
//! The polynomials follow from integrating the phases (derived symbolically; the tests
//! check each against the integrated motion). A root is a profile when every duration is
//! non-negative, the limits hold in every phase (the velocity where the acceleration
//! crosses zero included) and the integrated motion ends on the target.
//!
//! Every such profile is a local extreme of the durations the axis can take: they sort
//! into `t_min` and pairs bounding the gaps (durations the axis cannot take although a
//! shorter one is possible, when the target has a velocity or the start is moving). See
//! [`Block`].

use super::form::{Candidate, Shape, Up};
use super::profile::{AxisLimits, AxisProfile, JerkPhase, Kinematics, MAX_PHASES};
use super::real::Real;
use super::roots::roots_in;

/// The most profiles one axis can have: the boundaries of `[t_min, ∞)` and two gaps.
const MAX_VALID: usize = 5;

/// The durations one axis can take, and its time-optimal profile.
///
/// The feasible durations are `[t_min, ∞)` without at most two open gaps. A synchronized
/// motion of several axes takes the smallest duration that no axis finds in a gap.
///
/// ```
/// use strak_trajectory::{AxisLimits, Kinematics, solve_axis};
/// let limits = AxisLimits::new(1.0_f64, 1.0, 1.0)?;
/// // Moving fast towards a target that must be passed at full speed in the other direction:
/// let start = Kinematics::new(0.0, 1.0, 0.0);
/// let target = Kinematics::new(0.5, -1.0, 0.0);
/// let block = solve_axis(&start, &target, &limits)?;
/// assert!(block.t_min() > 2.0);
/// assert!(!block.is_blocked(block.t_min()));
/// # Ok::<(), strak_trajectory::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Block<R> {
    pub(super) profile: AxisProfile<R>,
    pub(super) span: Span<R>,
}

impl<R: Real> Block<R> {
    /// The time-optimal profile.
    pub fn profile(&self) -> &AxisProfile<R> {
        &self.profile
    }

    /// The shortest duration.
    pub fn t_min(&self) -> R {
        self.span.t_min
    }

    /// The gaps: open intervals of durations the axis cannot take.
    pub fn gaps(&self) -> &[(R, R)] {
        self.span.gaps()
    }

    /// Whether the axis cannot take the duration `t`.
    pub fn is_blocked(&self, t: R) -> bool {
        self.span.is_blocked(t)
    }
}

/// The durations an axis can take: the shortest, and at most two gaps.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(super) struct Span<R> {
    pub(super) t_min: R,
    gaps: [(R, R); 2],
    gap_count: usize,
}

impl<R: Real> Span<R> {
    /// `[t_min, ∞)` without gaps.
    pub(super) fn from(t_min: R) -> Self {
        Span {
            t_min,
            gaps: [(R::ZERO, R::ZERO); 2],
            gap_count: 0,
        }
    }

    /// The gaps.
    pub(super) fn gaps(&self) -> &[(R, R)] {
        &self.gaps[..self.gap_count]
    }

    /// Whether the duration `t` is not feasible.
    pub(super) fn is_blocked(&self, t: R) -> bool {
        t < self.t_min || self.gaps().iter().any(|&(a, b)| t > a && t < b)
    }
}

impl<R: Real> Up<R> {
    /// Every profile of the first form, written to `out`.
    fn profiles(&self, out: &mut Found<R>) {
        let families: [fn(&Self, &mut Found<R>); 5] = [
            Self::with_cruise,
            Self::no_limit,
            Self::peak_at_limit,
            Self::trough_at_limit,
            Self::both_accelerations,
        ];
        for family in families {
            if out.complete() {
                return;
            }
            family(self, out);
        }
    }

    fn add(&self, s: &Shape<R>, out: &mut Found<R>) {
        if let Some(c) = self.reaching(s) {
            out.push(c);
        }
    }

    /// The velocity held at `v_max`: the time-optimal velocity changes from the start to
    /// `(v_max, 0)` and from there to the target, and the cruise in between from the
    /// position.
    fn with_cruise(&self, out: &mut Found<R>) {
        let l = &self.l;
        let Some(mut s) = self.cruise_shape() else {
            return;
        };
        // The distance without cruise, then the cruise that covers the rest.
        let Some(t) = self.durations(&s) else { return };
        let mut k = Kinematics::new(R::ZERO, self.v0, self.a0);
        for (&jk, &dt) in self.jerks().iter().zip(&t) {
            k = k.advance(jk, dt);
        }
        s.t4 = (self.dp - k.position) / l.v_max;
        self.add(&s, out);
    }

    /// Both acceleration limits reached, no cruise: `t₂` from a quadratic, `t₆` from the
    /// velocity.
    fn both_accelerations(&self, out: &mut Found<R>) {
        let (l, j) = (&self.l, self.l.jerk);
        let (a, am) = (l.a_max, l.a_min);
        let (a0, v0, af, vf, dp) = (self.a0, self.v0, self.af, self.vf, self.dp);
        let c = R::lit;
        let (a0s, afs) = (a0 * a0, af * af);
        let c2 = -c(12.0) * a * j * j * (a - am);
        let c1 = -c(12.0) * j * (a - am) * (c(2.0) * a * a - a * am + c(2.0) * j * v0 - a0s);
        let c0 = c(-12.0) * a * a * a * a + c(24.0) * a * a * a * am
            - c(12.0) * a * a * am * am
            - c(24.0) * a * a * j * v0
            + c(12.0) * a * a * a0s
            + c(48.0) * a * am * j * v0
            - c(24.0) * a * am * a0s
            - c(12.0) * am * am * j * (v0 + vf)
            + c(6.0) * am * am * (a0s + afs)
            - c(24.0) * am * j * j * dp
            - c(24.0) * am * j * (a0 * v0 - af * vf)
            + c(8.0) * am * (a0s * a0 - afs * af)
            + self.common_terms();
        let hi = self.t_bound();
        for &t2 in roots_in(&[c0, c1, c2], R::ZERO, hi).as_slice() {
            let t6 = -(c(2.0) * a * a + c(2.0) * a * j * t2 - c(2.0) * am * am
                + c(2.0) * j * (v0 - vf)
                - a0s
                + afs)
                / (c(2.0) * am * j);
            self.add(
                &Shape {
                    a1: a,
                    t2,
                    t4: R::ZERO,
                    a5: am,
                    t6,
                    cruise: false,
                },
                out,
            );
        }
    }

    /// `−12J²v0² + 12J²vf² + 12J(a0²v0 − af²vf) − 3a0⁴ + 3af⁴`: the part of the position
    /// polynomials' constant terms that every form shares.
    fn common_terms(&self) -> R {
        let c = R::lit;
        let (a0s, afs, j) = (self.a0 * self.a0, self.af * self.af, self.l.jerk);
        c(12.0) * j * j * (self.vf * self.vf - self.v0 * self.v0)
            + c(12.0) * j * (a0s * self.v0 - afs * self.vf)
            + c(3.0) * (afs * afs - a0s * a0s)
    }

    /// An upper bound of any hold in a profile: long enough to change the velocity across
    /// its range at the smaller acceleration limit, twice.
    fn t_bound(&self) -> R {
        let l = &self.l;
        let a = l.a_max.min_of(-l.a_min);
        let span = (l.v_max - l.v_min) + self.v0.abs() + self.vf.abs();
        R::lit(4.0) * span / a + R::lit(4.0) * (l.a_max - l.a_min) / l.jerk
    }

    /// The peak held at `a_max`, no cruise: the trough `a₅` from a quartic, `t₂` from the
    /// velocity.
    fn peak_at_limit(&self, out: &mut Found<R>) {
        let (l, j) = (&self.l, self.l.jerk);
        let a = l.a_max;
        let (a0, v0, af, vf, dp) = (self.a0, self.v0, self.af, self.vf, self.dp);
        let c = R::lit;
        let (a0s, afs) = (a0 * a0, af * af);
        let k = c(2.0) * j * vf - afs;
        let c0 = c(12.0) * a * a * j * (v0 + vf)
            - c(6.0) * a * a * (a0s + afs)
            - c(24.0) * a * j * j * dp
            - c(24.0) * a * j * (a0 * v0 - af * vf)
            + c(8.0) * a * (a0s * a0 - afs * af)
            + self.common_terms();
        let coeffs = [
            c0,
            -c(24.0) * a * k,
            c(12.0) * (a * a + k),
            -c(24.0) * a,
            c(12.0),
        ];
        // `t₂ ≥ 0` (within the time tolerance) needs `a₅² ≥ q`: below `−√q` or above `√q`.
        let q = a * a - j * (vf - v0) - (a0s - afs) * R::HALF - a * j * self.tol.time;
        let (lo, mut hi) = (l.a_min, af.min_of(a));
        if q > R::ZERO && hi < q.root() {
            hi = hi.min_of(-q.root());
        }
        for &a5 in roots_in(&coeffs, lo, hi).as_slice() {
            let t2 = (-c(2.0) * a * a + c(2.0) * j * (vf - v0) + a0s - afs + c(2.0) * a5 * a5)
                / (c(2.0) * a * j);
            self.add(
                &Shape {
                    a1: a,
                    t2,
                    t4: R::ZERO,
                    a5,
                    t6: R::ZERO,
                    cruise: false,
                },
                out,
            );
        }
    }

    /// The trough held at `a_min`, no cruise: the peak `a₁` from a quartic, `t₆` from the
    /// velocity.
    fn trough_at_limit(&self, out: &mut Found<R>) {
        let (l, j) = (&self.l, self.l.jerk);
        let am = l.a_min;
        let (a0, v0, af, vf, dp) = (self.a0, self.v0, self.af, self.vf, self.dp);
        let c = R::lit;
        let (a0s, afs) = (a0 * a0, af * af);
        let k = c(2.0) * j * v0 - a0s;
        let c0 = -c(12.0) * am * am * j * (v0 + vf) + c(6.0) * am * am * (a0s + afs)
            - c(24.0) * am * j * j * dp
            - c(24.0) * am * j * (a0 * v0 - af * vf)
            + c(8.0) * am * (a0s * a0 - afs * af)
            + self.common_terms();
        let coeffs = [
            c0,
            c(24.0) * am * k,
            -c(12.0) * (am * am + k),
            c(24.0) * am,
            -c(12.0),
        ];
        // `t₆ ≥ 0` (within the time tolerance) needs `a₁² ≥ q`: below `−√q` or above `√q`.
        let q = am * am - j * (v0 - vf) + (a0s - afs) * R::HALF + am * j * self.tol.time;
        let mut lo = a0.max_of(am);
        if q > R::ZERO && lo > -q.root() {
            lo = lo.max_of(q.root());
        }
        for &a1 in roots_in(&coeffs, lo, l.a_max).as_slice() {
            let t6 = -(-c(2.0) * am * am + c(2.0) * j * (v0 - vf) - a0s + afs + c(2.0) * a1 * a1)
                / (c(2.0) * am * j);
            self.add(
                &Shape {
                    a1,
                    t2: R::ZERO,
                    t4: R::ZERO,
                    a5: am,
                    t6,
                    cruise: false,
                },
                out,
            );
        }
    }

    /// No limit reached: `u = a₁ − a₅` from a quartic; the velocity gives
    /// `a₁² − a₅² = K = J(v_f − v₀) + (a₀² − a_f²)/2`. At `u = 0` (then `K = 0`) the motion
    /// is one phase of rising acceleration.
    fn no_limit(&self, out: &mut Found<R>) {
        let j = self.l.jerk;
        let (a0, v0, af, vf, dp) = (self.a0, self.v0, self.af, self.vf, self.dp);
        let c = R::lit;
        let (a0s, afs) = (a0 * a0, af * af);
        let kk = j * (vf - v0) + (a0s - afs) * R::HALF;
        let coeffs = [
            -c(12.0) * kk * kk,
            -c(16.0)
                * (c(3.0) * j * j * dp + c(3.0) * j * (a0 * v0 - af * vf) - a0s * a0 + afs * af),
            c(24.0) * (c(2.0) * j * (v0 + vf) - a0s - afs),
            R::ZERO,
            c(12.0),
        ];
        let Some((lo, hi)) = self.no_limit_range(kk) else {
            return;
        };
        for &u in roots_in(&coeffs, lo, hi).as_slice() {
            let (a1, a5) = if u > R::ZERO {
                ((u + kk / u) * R::HALF, (kk / u - u) * R::HALF)
            } else {
                (a0, a0)
            };
            self.add(
                &Shape {
                    a1,
                    t2: R::ZERO,
                    t4: R::ZERO,
                    a5,
                    t6: R::ZERO,
                    cruise: false,
                },
                out,
            );
        }
    }
}

impl<R: Real> Up<R> {
    /// The `u = a₁ − a₅` of [`Up::no_limit`] whose peak and trough keep the acceleration
    /// limits (within the tolerance): `a₁ = (u + K/u)/2 ≤ a_max` and `a₅ = (K/u − u)/2 ≥
    /// a_min` hold between the roots of `u² − 2a_max·u + K` and of `u² + 2a_min·u − K`,
    /// here widened by their discriminants' rounding; `None` when no `u ∈ [0, a_max − a_min]`
    /// can keep both.
    fn no_limit_range(&self, kk: R) -> Option<(R, R)> {
        let l = &self.l;
        let slack = self.tol.acceleration;
        let between = |m: R, sign: R| -> Option<(R, R)> {
            // u² − 2·m·u + sign·K ≤ 0 with m = a_max (sign +1) or m = −a_min (sign −1).
            let d = m * m - sign * kk;
            let e = R::lit(8.0) * R::EPS * (m * m + kk.abs());
            if (d + e).is_negative() {
                return None;
            }
            let r = (d + e).root() + R::lit(8.0) * R::EPS * m;
            Some((m - r, m + r))
        };
        let (lo1, hi1) = between(l.a_max + slack, R::ONE)?;
        let (lo2, hi2) = between(-l.a_min + slack, R::MINUS_ONE)?;
        let lo = lo1.max_of(lo2).max_of(R::ZERO);
        let hi = hi1.min_of(hi2).min_of(l.a_max - l.a_min);
        (lo <= hi).then_some((lo, hi))
    }
}

/// The durations of the profiles found (at most [`MAX_VALID`] + 3 kept), and the shortest
/// profile (the first found of that duration).
#[derive(Clone, Copy, Debug)]
struct Found<R> {
    durations: [R; MAX_VALID + 3],
    len: usize,
    best: Candidate<R>,
    /// The profiles found now are of the mirrored problem: negate them.
    mirrored: bool,
    /// Stop at the first profile.
    first_only: bool,
}

impl<R: Real> Found<R> {
    /// Whether no further profile is needed: one was found and the target is at rest (then
    /// it is the only one).
    fn complete(&self) -> bool {
        self.first_only && self.len > 0
    }

    fn push(&mut self, c: Candidate<R>) {
        if self.len < self.durations.len() {
            let d = c.duration();
            if self.len == 0 || d < self.shortest() {
                self.best = if self.mirrored { c.negated() } else { c };
            }
            self.durations[self.len] = d;
            self.len += 1;
        }
    }

    /// The duration of [`best`](Self::best) (some profile must have been found).
    fn shortest(&self) -> R {
        self.best.duration()
    }
}

/// The time-optimal profile from `start` (inside the limits, after any brake phases
/// `brake`) to `target`, and the feasible durations; `None` when no profile passes its
/// checks (a numerical failure).
pub(super) fn time_optimal<R: Real>(
    origin: &Kinematics<R>,
    brake: [JerkPhase<R>; 2],
    target: &Kinematics<R>,
    l: &AxisLimits<R>,
    out: &mut AxisProfile<R>,
) -> Option<Span<R>> {
    let (start, brake_time) = super::brake::after(origin, &brake);
    let up = Up::new(&start, target, l);
    let down = up.mirrored();
    let empty = Candidate {
        t: [R::ZERO; 7],
        jerks: [R::ZERO; 7],
        accelerations: [R::ZERO; 8],
        position_tolerance: R::ZERO,
    };
    // A target at rest has one profile (no gaps: Berscheid & Kröger, §IV-C): the search
    // stops at the first, beginning in the direction of the target.
    let first_only = target.velocity == R::ZERO && target.acceleration == R::ZERO;
    let mut found = Found {
        durations: [R::ZERO; MAX_VALID + 3],
        len: 0,
        best: empty,
        mirrored: false,
        first_only,
    };
    let directions = if up.dp.is_negative() {
        [(&down, true), (&up, false)]
    } else {
        [(&up, false), (&down, true)]
    };
    for (problem, mirrored) in directions {
        found.mirrored = mirrored;
        problem.profiles(&mut found);
    }
    block(origin, brake, brake_time, &mut found, up.tol.time, out)
}

/// Sorts the profiles by duration, merges those that coincide within `tol`, and reads the
/// block: the shortest, and the gaps between the next pairs.
fn block<R: Real>(
    origin: &Kinematics<R>,
    brake: [JerkPhase<R>; 2],
    brake_time: R,
    found: &mut Found<R>,
    tol: R,
    out: &mut AxisProfile<R>,
) -> Option<Span<R>> {
    if found.len == 0 {
        return None;
    }
    let sorted = &mut found.durations[..found.len];
    // Insertion sort (at most eight durations).
    for i in 1..sorted.len() {
        let mut k = i;
        while k > 0 && sorted[k] < sorted[k - 1] {
            sorted.swap(k, k - 1);
            k -= 1;
        }
    }
    let mut durations = [R::ZERO; MAX_VALID + 3];
    let mut n = 0;
    for &d in sorted.iter() {
        if n == 0 || d - durations[n - 1] > tol {
            durations[n] = d;
            n += 1;
        }
    }
    let best = found.best;
    with_brake(
        origin,
        brake,
        &best.t,
        &best.jerks,
        &best.accelerations,
        out,
    );
    let mut gaps = [(R::ZERO, R::ZERO); 2];
    let mut gap_count = 0;
    // An even count means a boundary was missed or found twice: the gaps cannot be read,
    // and the shortest duration stands alone.
    if n % 2 == 1 {
        let mut i = 1;
        while i + 1 < n && gap_count < 2 {
            gaps[gap_count] = (durations[i] + brake_time, durations[i + 1] + brake_time);
            gap_count += 1;
            i += 2;
        }
    }
    Some(Span {
        t_min: out.duration,
        gaps,
        gap_count,
    })
}

/// The profile of the brake phases followed by up to seven main phases (durations, jerks,
/// and the accelerations at the main phases' starts and end).
pub(super) fn with_brake<R: Real>(
    origin: &Kinematics<R>,
    brake: [JerkPhase<R>; 2],
    t: &[R],
    jerks: &[R],
    accelerations: &[R],
    out: &mut AxisProfile<R>,
) {
    let mut phases = [JerkPhase::default(); MAX_PHASES];
    let mut accs = [R::ZERO; MAX_PHASES + 1];
    let mut a = origin.acceleration;
    accs[0] = a;
    for (i, p) in brake.iter().enumerate() {
        phases[i] = *p;
        a += p.jerk * p.duration;
        accs[i + 1] = a;
    }
    for (i, (&dt, &j)) in t.iter().zip(jerks).enumerate() {
        phases[2 + i] = JerkPhase {
            jerk: j,
            duration: dt,
        };
    }
    // The main phases start where the brake ends; then the form's accelerations.
    let last = accelerations.len().min(MAX_PHASES - 1);
    accs[2..2 + last].copy_from_slice(&accelerations[..last]);
    for a in &mut accs[2 + last..] {
        *a = accelerations[last - 1];
    }
    out.set(*origin, phases, &accs);
}
