//! A move of several axes from their current states to targets ([`OnlineMove`]).

use super::profile::{AxisLimits, AxisProfile, Kinematics};
use super::real::Real;
use super::step1::Block;
use super::sync::{self, Interface, Synchronization};
use crate::error::Error;

/// How a move is timed and what it goes to.
///
/// ```
/// use strak_trajectory::{Interface, MoveOptions, Synchronization};
/// let o = MoveOptions::new().with_synchronization(Synchronization::Phase);
/// assert_eq!((o.synchronization, o.interface), (Synchronization::Phase, Interface::Position));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct MoveOptions {
    /// How the axes are timed together (default: [`Synchronization::Time`]).
    pub synchronization: Synchronization,
    /// Position or velocity targets (default: [`Interface::Position`]).
    pub interface: Interface,
}

impl MoveOptions {
    /// Time-synchronized, to target positions.
    pub const fn new() -> Self {
        MoveOptions { synchronization: Synchronization::Time, interface: Interface::Position }
    }

    /// With the given synchronization.
    #[must_use]
    pub const fn with_synchronization(self, synchronization: Synchronization) -> Self {
        MoveOptions { synchronization, ..self }
    }

    /// With the given interface.
    #[must_use]
    pub const fn with_interface(self, interface: Interface) -> Self {
        MoveOptions { interface, ..self }
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
}

impl<R: Real, const A: usize> OnlineMove<R, A> {
    /// The move from `start` to `target` within `limits` (one of each per axis).
    ///
    /// # Errors
    /// As [`solve_axis`](crate::solve_axis) for each axis; [`Error::NoProfile`] also when
    /// an axis finds no motion of the common duration (a numerical failure).
    pub fn solve(
        start: &[Kinematics<R>; A],
        target: &[Kinematics<R>; A],
        limits: &[AxisLimits<R>; A],
        options: &MoveOptions,
    ) -> Result<Self, Error> {
        let mut m = OnlineMove {
            profiles: [*Block::still().profile(); A],
            min_durations: [R::ZERO; A],
            targets: *target,
            duration: R::ZERO,
            synchronization: options.synchronization,
            interface: options.interface,
        };
        m.solve_in_place(start, target, limits, options)?;
        Ok(m)
    }

    /// [`OnlineMove::solve`] into `self` (in place, for firmware that keeps the move in a
    /// `static`). On an error `self` is unchanged.
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
        let interface = options.interface;
        let mut blocks = [Block::still(); A];
        for i in 0..A {
            blocks[i] = sync::axis_block(&start[i], &target[i], &limits[i], interface)?;
        }
        let mut used = options.synchronization;
        let mut profiles = blocks.map(|b| *b.profile());
        let mut duration = R::ZERO;
        for b in &blocks {
            duration = duration.max_of(b.t_min());
        }
        if used == Synchronization::Phase {
            match sync::phase_profiles(start, target, limits, interface)? {
                Some(p) => {
                    profiles = p;
                    duration = profiles[0].duration();
                }
                None => used = Synchronization::Time,
            }
        }
        if used == Synchronization::Time {
            duration = sync::common_duration(&blocks);
            for i in 0..A {
                if blocks[i].t_min() < duration {
                    profiles[i] = sync::axis_with_duration(&start[i], &target[i], &limits[i], interface, duration)
                        .ok_or(Error::NoProfile)?;
                }
            }
        }
        *self = OnlineMove {
            profiles,
            min_durations: blocks.map(|b| b.t_min()),
            targets: *target,
            duration,
            synchronization: used,
            interface,
        };
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

    /// Every axis's state at time `t` (seconds from the start).
    pub fn at(&self, t: R) -> [Kinematics<R>; A] {
        self.profiles.map(|p| p.at(t))
    }
}
