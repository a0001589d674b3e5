//! A move of several axes from their current states to targets ([`OnlineMove`]).

use super::profile::{AxisLimits, AxisProfile, Kinematics};
use super::real::Real;
use super::step1::Span;
use super::sync::{self, Grid, Interface, Synchronization};
use crate::error::Error;
use crate::num::RATE_RANGE;

/// How a move is timed and what it goes to.
///
/// ```
/// use strak_trajectory::{Interface, MoveOptions, Synchronization};
/// let o = MoveOptions::new().with_synchronization(Synchronization::Phase);
/// assert_eq!((o.synchronization, o.interface), (Synchronization::Phase, Interface::Position));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct MoveOptions {
    /// How the axes are timed together (default: [`Synchronization::Time`]).
    pub synchronization: Synchronization,
    /// Position or velocity targets (default: [`Interface::Position`]).
    pub interface: Interface,
    /// The control rate the move is played at (Hz), if any: every axis's duration is then
    /// a whole number of ticks, so that the compiled path ends on the target exactly at a
    /// tick (default: none, the durations as solved).
    pub rate_hz: Option<f64>,
    /// How far the start state may lie from the exact one, `(relative, absolute)`: each
    /// value within `relative·|x| + absolute` (a start read from a sample carries the
    /// rounding of its number format). [`Synchronization::Phase`] takes values that lie on
    /// one line within it as on one line, so that a take-over of a motion along a line
    /// stays on it (default `(0, 0)`: only the solver's own rounding).
    pub start_rounding: (f64, f64),
}

impl MoveOptions {
    /// Time-synchronized, to target positions, off the tick grid.
    pub const fn new() -> Self {
        MoveOptions {
            synchronization: Synchronization::Time,
            interface: Interface::Position,
            rate_hz: None,
            start_rounding: (0.0, 0.0),
        }
    }

    /// With the given rounding of the start state ([`MoveOptions::start_rounding`]).
    ///
    /// ```
    /// use strak_trajectory::MoveOptions;
    /// let o = MoveOptions::new().with_start_rounding(1e-7, 0.0);
    /// assert_eq!(o.start_rounding, (1e-7, 0.0));
    /// ```
    #[must_use]
    pub const fn with_start_rounding(self, relative: f64, absolute: f64) -> Self {
        MoveOptions {
            start_rounding: (relative, absolute),
            ..self
        }
    }

    /// Durations in whole ticks of `rate_hz` (100 Hz ..= 100 kHz, checked by
    /// [`OnlineMove::solve`]).
    #[must_use]
    pub const fn with_rate(self, rate_hz: f64) -> Self {
        MoveOptions {
            rate_hz: Some(rate_hz),
            ..self
        }
    }

    /// With the given synchronization.
    #[must_use]
    pub const fn with_synchronization(self, synchronization: Synchronization) -> Self {
        MoveOptions {
            synchronization,
            ..self
        }
    }

    /// With the given interface.
    #[must_use]
    pub const fn with_interface(self, interface: Interface) -> Self {
        MoveOptions { interface, ..self }
    }

    /// The options of a quick stop: to the targets' velocities and accelerations (rest, for
    /// targets at rest), the positions free ([`Interface::Velocity`]), every axis on the
    /// line it moves along when the axes move along one ([`Synchronization::Phase`]), all
    /// ending together; the rate is kept.
    ///
    /// ```
    /// use strak_trajectory::{AxisLimits, Kinematics, MoveOptions, OnlineMove};
    /// let limits = [AxisLimits::new(500.0_f64, 5_000.0, 100_000.0)?; 2];
    /// let moving = [Kinematics::new(3.0, 300.0, 1_000.0), Kinematics::new(1.0, 100.0, 0.0)];
    /// let rest = [Kinematics::at_rest(0.0); 2];
    /// let options = MoveOptions::new().with_rate(1_000.0).quick_stop();
    /// let m = OnlineMove::solve(&moving, &rest, &limits, &options)?;
    /// for p in m.profiles() {
    ///     assert!(p.end().velocity.abs() < 1e-9 && p.end().acceleration.abs() < 1e-9);
    /// }
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    #[must_use]
    pub const fn quick_stop(self) -> Self {
        MoveOptions {
            synchronization: Synchronization::Phase,
            interface: Interface::Velocity,
            ..self
        }
    }
}

/// A jerk-limited move of `A` axes from any state to target states, solved in bounded time
/// (`no_std`, no heap): each axis's motion as constant-jerk phases ([`AxisProfile`]).
///
/// ```
/// use strak_trajectory::{AxisLimits, Kinematics, MoveOptions, OnlineMove};
/// let limits = [AxisLimits::new(500.0_f64, 5_000.0, 100_000.0)?; 3];
/// let start = [Kinematics::new(0.0, 100.0, 0.0), Kinematics::new(0.0, 0.0, 500.0), Kinematics::at_rest(0.0)];
/// let target = [Kinematics::at_rest(300.0), Kinematics::at_rest(150.0), Kinematics::at_rest(80.0)];
/// let m = OnlineMove::solve(&start, &target, &limits, &MoveOptions::new())?;
/// // Every axis ends together, at the slowest axis's minimum duration.
/// assert_eq!(m.duration(), m.min_durations()[0]);
/// for (p, t) in m.profiles().iter().zip(&target) {
///     assert!((p.duration() - m.duration()).abs() < 1e-12);
///     assert!((p.end().position - t.position).abs() < 1e-9);
/// }
/// # Ok::<(), strak_trajectory::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct OnlineMove<R, const A: usize> {
    profiles: [AxisProfile<R>; A],
    min_durations: [R; A],
    targets: [Kinematics<R>; A],
    duration: R,
    synchronization: Synchronization,
    interface: Interface,
    rate_hz: Option<f64>,
    limits: [AxisLimits<R>; A],
}

impl<R: Real, const A: usize> Default for OnlineMove<R, A> {
    /// [`OnlineMove::new`].
    fn default() -> Self {
        OnlineMove::new()
    }
}

impl<R: Real, const A: usize> OnlineMove<R, A> {
    /// A move of no duration at position zero (its limits 1), to solve into with
    /// [`OnlineMove::solve_in_place`]: a `const fn`, so that firmware can keep the move in a
    /// `static` and never move it by value.
    ///
    /// ```
    /// use strak_trajectory::{AxisLimits, Kinematics, MoveOptions, OnlineMove};
    /// static IDLE: OnlineMove<f32, 3> = OnlineMove::new(); // a `static` initializer
    /// let mut m = OnlineMove::<f32, 3>::new();
    /// assert_eq!(m.duration(), 0.0);
    /// let limits = [AxisLimits::new(500.0_f32, 5_000.0, 100_000.0)?; 3];
    /// let target = [Kinematics::at_rest(10.0_f32); 3];
    /// m.solve_in_place(&[Kinematics::at_rest(0.0); 3], &target, &limits, &MoveOptions::new())?;
    /// assert!(m.duration() > 0.0);
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub const fn new() -> Self {
        OnlineMove {
            profiles: [AxisProfile::still(R::ZERO); A],
            min_durations: [R::ZERO; A],
            targets: [Kinematics::at_rest(R::ZERO); A],
            duration: R::ZERO,
            synchronization: Synchronization::Time,
            interface: Interface::Position,
            rate_hz: None,
            limits: [AxisLimits::UNIT; A],
        }
    }

    /// The move from `start` to `target` within `limits` (one of each per axis).
    ///
    /// # Errors
    /// As [`solve_axis`](crate::solve_axis) for each axis; [`Error::NoProfile`] also when
    /// an axis finds no motion of the common duration (a numerical failure);
    /// [`Error::InvalidRate`] for a rate outside 100 Hz ..= 100 kHz;
    /// [`Error::AccelerationAfterArrival`] for an unsynchronized move in which an axis
    /// arrives early with a target acceleration.
    pub fn solve(
        start: &[Kinematics<R>; A],
        target: &[Kinematics<R>; A],
        limits: &[AxisLimits<R>; A],
        options: &MoveOptions,
    ) -> Result<Self, Error> {
        let mut m = OnlineMove::new();
        m.solve_in_place(start, target, limits, options)?;
        Ok(m)
    }

    /// [`OnlineMove::solve`] into `self` (in place, for firmware that keeps the move in a
    /// `static`: nothing of the move's size is moved by value). On an error `self` is a
    /// move of no duration at the start positions.
    ///
    /// # Errors
    /// As [`OnlineMove::solve`].
    pub fn solve_in_place(
        &mut self,
        start: &[Kinematics<R>; A],
        target: &[Kinematics<R>; A],
        limits: &[AxisLimits<R>; A],
        options: &MoveOptions,
    ) -> Result<(), Error> {
        self.targets = *target;
        self.limits = *limits;
        self.interface = options.interface;
        self.rate_hz = options.rate_hz;
        let result = self.solve_profiles(start, options);
        if result.is_err() {
            for (p, s) in self.profiles.iter_mut().zip(start) {
                *p = AxisProfile::still(s.position);
            }
            self.duration = R::ZERO;
            self.min_durations = [R::ZERO; A];
        }
        result
    }

    /// Every axis's motion, the move's duration and the synchronization used, in place.
    fn solve_profiles(
        &mut self,
        start: &[Kinematics<R>; A],
        options: &MoveOptions,
    ) -> Result<(), Error> {
        let interface = options.interface;
        if options
            .rate_hz
            .is_some_and(|f| !(f >= RATE_RANGE.0 && f <= RATE_RANGE.1))
        {
            return Err(Error::InvalidRate);
        }
        let grid = Grid(options.rate_hz);
        let (target, limits) = (&self.targets, &self.limits);
        let mut spans = [Span::from(R::ZERO); A];
        for i in 0..A {
            spans[i] = sync::axis_span(
                &start[i],
                &target[i],
                &limits[i],
                interface,
                &mut self.profiles[i],
            )?;
            self.min_durations[i] = spans[i].t_min;
        }
        let mut used = options.synchronization;
        let mut durations = self.min_durations;
        if used == Synchronization::Phase {
            let (relative, absolute) = options.start_rounding;
            let rounding = (R::lit(relative), R::lit(absolute));
            let phase = sync::phase_profiles(
                start,
                target,
                limits,
                interface,
                grid,
                rounding,
                &mut self.profiles,
            )?;
            if phase {
                durations = [self.profiles[0].duration(); A];
            } else {
                used = Synchronization::Time;
            }
        }
        if used != Synchronization::Phase {
            let common = sync::common_duration(&spans, grid);
            for i in 0..A {
                durations[i] = match used {
                    Synchronization::None => {
                        sync::common_duration(core::slice::from_ref(&spans[i]), grid)
                    }
                    _ => common,
                };
                let solved = durations[i] == spans[i].t_min
                    || sync::axis_with_duration(
                        &start[i],
                        &target[i],
                        &limits[i],
                        interface,
                        durations[i],
                        &mut self.profiles[i],
                    );
                if !solved {
                    return Err(Error::NoProfile);
                }
            }
        }
        self.duration = R::ZERO;
        for d in &durations {
            self.duration = self.duration.max_of(*d);
        }
        // An axis that arrives early goes on at its target state until the move ends: only
        // at constant velocity does that stay within its limits.
        for (i, (d, t)) in durations.iter().zip(target).enumerate() {
            if *d < self.duration && t.acceleration != R::ZERO {
                return Err(Error::AccelerationAfterArrival { axis: i });
            }
        }
        self.synchronization = used;
        Ok(())
    }

    /// The duration in seconds (the longest axis's).
    pub fn duration(&self) -> R {
        self.duration
    }

    /// Each axis's motion.
    pub fn profiles(&self) -> &[AxisProfile<R>; A] {
        &self.profiles
    }

    /// Each axis's shortest duration on its own.
    pub fn min_durations(&self) -> &[R; A] {
        &self.min_durations
    }

    /// The targets.
    pub fn targets(&self) -> &[Kinematics<R>; A] {
        &self.targets
    }

    /// The synchronization used ([`Synchronization::Phase`] falls back to
    /// [`Synchronization::Time`] when the states do not lie on one line).
    pub fn synchronization(&self) -> Synchronization {
        self.synchronization
    }

    /// Position or velocity targets.
    pub fn interface(&self) -> Interface {
        self.interface
    }

    /// Each axis's limits.
    pub fn limits(&self) -> &[AxisLimits<R>; A] {
        &self.limits
    }

    /// The control rate the durations are whole ticks of, if one was given.
    pub fn rate_hz(&self) -> Option<f64> {
        self.rate_hz
    }

    /// Every axis's state at time `t` (seconds from the start).
    pub fn at(&self, t: R) -> [Kinematics<R>; A] {
        self.profiles.map(|p| p.at(t))
    }
}
