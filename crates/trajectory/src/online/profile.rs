//! The state of one axis, its limits, and its motion as a list of constant-jerk phases.

use super::real::Real;
use crate::error::Error;

/// Position, velocity and acceleration of one axis at one instant (units, units/s,
/// units/s²).
///
/// ```
/// use strak_trajectory::Kinematics;
/// let k = Kinematics::new(1.0_f64, 2.0, 0.0).advance(6.0, 1.0); // jerk 6 for 1 s
/// assert_eq!((k.position, k.velocity, k.acceleration), (4.0, 5.0, 6.0));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Kinematics<R> {
    /// Position.
    pub position: R,
    /// Velocity.
    pub velocity: R,
    /// Acceleration.
    pub acceleration: R,
}

impl<R: Real> Kinematics<R> {
    /// The state `(position, velocity, acceleration)`.
    pub const fn new(position: R, velocity: R, acceleration: R) -> Self {
        Kinematics {
            position,
            velocity,
            acceleration,
        }
    }

    /// At rest at `position`.
    pub const fn at_rest(position: R) -> Self {
        Kinematics::new(position, R::ZERO, R::ZERO)
    }

    /// The state after `dt` seconds of constant jerk `jerk`:
    /// `p + v·dt + a·dt²/2 + j·dt³/6`, `v + a·dt + j·dt²/2`, `a + j·dt` (Horner's rule).
    #[inline]
    pub fn advance(&self, jerk: R, dt: R) -> Self {
        let half = R::HALF;
        let sixth = R::lit(1.0 / 6.0);
        let a = self.acceleration;
        Kinematics {
            position: self.position + dt * (self.velocity + dt * (half * a + dt * (sixth * jerk))),
            velocity: self.velocity + dt * (a + dt * (half * jerk)),
            acceleration: a + dt * jerk,
        }
    }

    /// The state in `f64` (exactly).
    pub(crate) fn to_f64(self) -> Kinematics<f64> {
        Kinematics::new(
            self.position.to_f64(),
            self.velocity.to_f64(),
            self.acceleration.to_f64(),
        )
    }

    /// Every value finite.
    pub(super) fn is_finite(&self) -> bool {
        self.position.is_finite() && self.velocity.is_finite() && self.acceleration.is_finite()
    }
}

/// The limits of one axis: velocity and acceleration in `[minimum, maximum]` (by default
/// symmetric, `minimum = −maximum`), and `|jerk| ≤ jerk`.
///
/// ```
/// use strak_trajectory::{AxisLimits, Error};
/// let l = AxisLimits::new(500.0_f64, 5_000.0, 100_000.0)?;
/// assert_eq!((l.velocity_min(), l.acceleration_max()), (-500.0, 5_000.0));
/// // A slower retract: at most 200 units/s and 2 000 units/s² backwards.
/// let l = l.with_minimum(-200.0, -2_000.0)?;
/// assert_eq!((l.velocity_min(), l.acceleration_min()), (-200.0, -2_000.0));
/// assert_eq!(AxisLimits::new(0.0_f64, 1.0, 1.0), Err(Error::InvalidLimit));
/// # Ok::<(), Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AxisLimits<R> {
    pub(super) v_max: R,
    pub(super) v_min: R,
    pub(super) a_max: R,
    pub(super) a_min: R,
    pub(super) jerk: R,
}

impl<R: Real> AxisLimits<R> {
    /// Velocity, acceleration and jerk limited to 1 (the limits of a move not yet solved,
    /// [`OnlineMove::new`](crate::OnlineMove::new)).
    pub(super) const UNIT: Self = AxisLimits {
        v_max: R::ONE,
        v_min: R::MINUS_ONE,
        a_max: R::ONE,
        a_min: R::MINUS_ONE,
        jerk: R::ONE,
    };

    /// Symmetric limits: `|v| ≤ velocity`, `|a| ≤ acceleration`, `|j| ≤ jerk`.
    ///
    /// # Errors
    /// [`Error::InvalidLimit`] unless every limit is finite and positive.
    pub fn new(velocity: R, acceleration: R, jerk: R) -> Result<Self, Error> {
        let limits = AxisLimits {
            v_max: velocity,
            v_min: -velocity,
            a_max: acceleration,
            a_min: -acceleration,
            jerk,
        };
        limits.validated()
    }

    /// Separate limits for the negative direction: `v ≥ velocity_min`,
    /// `a ≥ acceleration_min`.
    ///
    /// # Errors
    /// [`Error::InvalidLimit`] unless both are finite and negative.
    pub fn with_minimum(self, velocity_min: R, acceleration_min: R) -> Result<Self, Error> {
        AxisLimits {
            v_min: velocity_min,
            a_min: acceleration_min,
            ..self
        }
        .validated()
    }

    fn validated(self) -> Result<Self, Error> {
        let positive = |x: R| x.is_finite() && x > R::ZERO;
        let ok = positive(self.v_max)
            && positive(-self.v_min)
            && positive(self.a_max)
            && positive(-self.a_min)
            && positive(self.jerk);
        if ok {
            Ok(self)
        } else {
            Err(Error::InvalidLimit)
        }
    }

    /// The largest velocity.
    pub fn velocity_max(&self) -> R {
        self.v_max
    }

    /// The smallest (most negative) velocity.
    pub fn velocity_min(&self) -> R {
        self.v_min
    }

    /// The largest acceleration.
    pub fn acceleration_max(&self) -> R {
        self.a_max
    }

    /// The smallest (most negative) acceleration.
    pub fn acceleration_min(&self) -> R {
        self.a_min
    }

    /// The largest `|jerk|`.
    pub fn jerk(&self) -> R {
        self.jerk
    }

    /// The limits of the mirror image (`x → −x`): minimum and maximum exchanged and negated.
    pub(super) fn mirrored(&self) -> Self {
        AxisLimits {
            v_max: -self.v_min,
            v_min: -self.v_max,
            a_max: -self.a_min,
            a_min: -self.a_max,
            jerk: self.jerk,
        }
    }
}

/// The most phases of one axis's motion: two to brake into the limits, then up to seven
/// (the time-optimal motion) or fourteen (a motion of a given duration: two seven-phase
/// motions blended, their switching times merged).
pub const MAX_PHASES: usize = 16;

/// A phase of constant jerk.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct JerkPhase<R> {
    /// The jerk (units/s³).
    pub jerk: R,
    /// The duration (s, ≥ 0).
    pub duration: R,
}

/// The motion of one axis from a start state: at most [`MAX_PHASES`] phases of constant
/// jerk. Its last state is the target's (within the solver's rounding; the compiled path
/// ends on the target exactly).
///
/// ```
/// use strak_trajectory::{AxisLimits, Kinematics, solve_axis};
/// let limits = AxisLimits::new(1.0_f64, 1.0, 1.0)?;
/// let block = solve_axis(&Kinematics::at_rest(0.0), &Kinematics::at_rest(10.0), &limits)?;
/// let p = block.profile();
/// assert!((p.duration() - 12.0).abs() < 1e-12); // 1 s up, 1 s down, 8 s cruise, 2 s
/// assert!((p.at(6.0).position - 5.0).abs() < 1e-12); // halfway at half time
/// # Ok::<(), strak_trajectory::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AxisProfile<R> {
    pub(super) phases: [JerkPhase<R>; MAX_PHASES],
    /// The state at the start of each phase, and at the end.
    pub(super) states: [Kinematics<R>; MAX_PHASES + 1],
    pub(super) duration: R,
}

impl<R: Real> AxisProfile<R> {
    /// The motion of the given phases from `start` (unused phases have duration 0). The
    /// acceleration at the start of phase `i` (and at the end, `i = MAX_PHASES`) is set to
    /// `accelerations[i]` where the integration would put it only within rounding: the
    /// value the profile's form prescribes (zero during a cruise, a limit during a hold),
    /// so that rounding does not turn a hold or a cruise into a slow drift.
    pub(super) fn set(
        &mut self,
        start: Kinematics<R>,
        phases: [JerkPhase<R>; MAX_PHASES],
        accelerations: &[R; MAX_PHASES + 1],
    ) {
        self.phases = phases;
        self.states[0] = start;
        let mut duration = R::ZERO;
        for (i, p) in phases.iter().enumerate() {
            self.states[i + 1] = self.states[i].advance(p.jerk, p.duration);
            self.states[i + 1].acceleration = accelerations[i + 1];
            duration += p.duration;
        }
        self.duration = duration;
    }

    /// At rest at `position`, duration 0.
    pub(super) const fn still(position: R) -> Self {
        let start = Kinematics::at_rest(position);
        let none = JerkPhase {
            jerk: R::ZERO,
            duration: R::ZERO,
        };
        AxisProfile {
            phases: [none; MAX_PHASES],
            states: [start; MAX_PHASES + 1],
            duration: R::ZERO,
        }
    }

    /// The duration in seconds.
    pub fn duration(&self) -> R {
        self.duration
    }

    /// The profile with every value converted to `f64` (exactly).
    pub fn to_f64(&self) -> AxisProfile<f64> {
        AxisProfile {
            phases: self.phases.map(|p| JerkPhase {
                jerk: p.jerk.to_f64(),
                duration: p.duration.to_f64(),
            }),
            states: self.states.map(|s| s.to_f64()),
            duration: self.duration.to_f64(),
        }
    }

    /// The start state.
    pub fn start(&self) -> Kinematics<R> {
        self.states[0]
    }

    /// The state at the end of the last phase.
    pub fn end(&self) -> Kinematics<R> {
        self.states[MAX_PHASES]
    }

    /// The phases, in order (unused ones have duration 0).
    pub fn phases(&self) -> &[JerkPhase<R>; MAX_PHASES] {
        &self.phases
    }

    /// The state at the start of each phase, and at the end.
    pub fn states(&self) -> &[Kinematics<R>; MAX_PHASES + 1] {
        &self.states
    }

    /// The phase that holds time `t`, and `t` less the phase's start time: a scan of the
    /// [`MAX_PHASES`] phases. Before the start, phase 0 at offset 0; from the end on, past
    /// the last phase.
    fn locate(&self, t: R) -> (usize, R) {
        let mut left = if t > R::ZERO { t } else { R::ZERO };
        for (i, p) in self.phases.iter().enumerate() {
            if left < p.duration {
                return (i, left);
            }
            left -= p.duration;
        }
        (MAX_PHASES, R::ZERO)
    }

    /// The state at time `t` in seconds from the start: the start state before it; from
    /// the end on, the end state continued without jerk (an axis of an unsynchronized
    /// move that arrives early goes on at its target velocity).
    pub fn at(&self, t: R) -> Kinematics<R> {
        match self.locate(t) {
            (MAX_PHASES, _) => self.end().advance(R::ZERO, t - self.duration),
            (i, dt) => self.states[i].advance(self.phases[i].jerk, dt),
        }
    }

    /// The jerk at time `t` (zero before the start and from the end on).
    pub fn jerk_at(&self, t: R) -> R {
        match self.locate(t) {
            (MAX_PHASES, _) => R::ZERO,
            _ if t < R::ZERO => R::ZERO,
            (i, _) => self.phases[i].jerk,
        }
    }
}
