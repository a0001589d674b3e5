//! Kinematic limits of a motion: along the path and per axis.

use crate::error::Error;

/// Limits of a motion with `A` axes, in path units (for example mm) and seconds.
///
/// * `velocity`, `acceleration`, `jerk`: limits of the speed and of the norms of the
///   acceleration and jerk vectors (finite, > 0); [`PathTiming::plan`](crate::PathTiming::plan)
///   keeps the motion in space within them, curves included.
/// * `axis_velocity`, `axis_acceleration`: per-axis limits of `|ẋᵢ|` and `|ẍᵢ|` (> 0;
///   `f64::INFINITY` for an axis without a limit of its own).
///
/// ```
/// use strak_trajectory::Limits;
/// let limits = Limits::<3>::new(200.0, 2_000.0, 50_000.0)?
///     .with_axis_velocity([150.0, 150.0, 20.0])?;
/// assert_eq!(limits.axis_velocity()[2], 20.0);
/// assert!(Limits::<3>::new(0.0, 1.0, 1.0).is_err());
/// # Ok::<(), strak_trajectory::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limits<const A: usize> {
    velocity: f64,
    acceleration: f64,
    jerk: f64,
    axis_velocity: [f64; A],
    axis_acceleration: [f64; A],
}

fn positive_finite(x: f64) -> Result<f64, Error> {
    if x.is_finite() && x > 0.0 {
        Ok(x)
    } else {
        Err(Error::InvalidLimit)
    }
}

fn positive_axes<const A: usize>(x: [f64; A]) -> Result<[f64; A], Error> {
    // NaN fails `> 0`; +∞ means "no limit of its own".
    if x.iter().all(|v| *v > 0.0) {
        Ok(x)
    } else {
        Err(Error::InvalidLimit)
    }
}

impl<const A: usize> Limits<A> {
    /// Path limits without per-axis limits.
    ///
    /// # Errors
    /// [`Error::InvalidLimit`] unless each limit is finite and positive.
    pub fn new(velocity: f64, acceleration: f64, jerk: f64) -> Result<Self, Error> {
        Ok(Limits {
            velocity: positive_finite(velocity)?,
            acceleration: positive_finite(acceleration)?,
            jerk: positive_finite(jerk)?,
            axis_velocity: [f64::INFINITY; A],
            axis_acceleration: [f64::INFINITY; A],
        })
    }

    /// The same limits with per-axis velocity limits.
    ///
    /// # Errors
    /// [`Error::InvalidLimit`] unless each entry is positive (`f64::INFINITY` allowed).
    pub fn with_axis_velocity(mut self, limits: [f64; A]) -> Result<Self, Error> {
        self.axis_velocity = positive_axes(limits)?;
        Ok(self)
    }

    /// The same limits with per-axis acceleration limits.
    ///
    /// # Errors
    /// [`Error::InvalidLimit`] unless each entry is positive (`f64::INFINITY` allowed).
    pub fn with_axis_acceleration(mut self, limits: [f64; A]) -> Result<Self, Error> {
        self.axis_acceleration = positive_axes(limits)?;
        Ok(self)
    }

    /// Path velocity limit.
    pub fn velocity(&self) -> f64 {
        self.velocity
    }

    /// Path acceleration limit (tangential, and centripetal in curves).
    pub fn acceleration(&self) -> f64 {
        self.acceleration
    }

    /// Path jerk limit.
    pub fn jerk(&self) -> f64 {
        self.jerk
    }

    /// Per-axis velocity limits (`f64::INFINITY`: none).
    pub fn axis_velocity(&self) -> [f64; A] {
        self.axis_velocity
    }

    /// Per-axis acceleration limits (`f64::INFINITY`: none).
    pub fn axis_acceleration(&self) -> [f64; A] {
        self.axis_acceleration
    }

    /// No motion at all: every limit 0 (a placeholder until real limits are set).
    pub(crate) const NONE: Self = Limits {
        velocity: 0.0,
        acceleration: 0.0,
        jerk: 0.0,
        axis_velocity: [0.0; A],
        axis_acceleration: [0.0; A],
    };

    /// What is left for the planned motion when `share` (in `(0, 1)`) of the acceleration
    /// and jerk limits (path and per axis) is reserved for feed changes: those limits times
    /// `1 − share`; the velocity limits are kept (a feed factor `≤ 1` only slows down).
    pub(crate) fn without_reserve(&self, share: f64) -> Self {
        let keep = 1.0 - share;
        Limits {
            velocity: self.velocity,
            acceleration: self.acceleration * keep,
            jerk: self.jerk * keep,
            axis_velocity: self.axis_velocity,
            axis_acceleration: self.axis_acceleration.map(|a| a * keep),
        }
    }

    /// The same limits with the velocities (path and per axis) times `keep`.
    pub(crate) fn with_velocities_times(&self, keep: f64) -> Self {
        Limits {
            velocity: self.velocity * keep,
            axis_velocity: self.axis_velocity.map(|v| v * keep),
            ..*self
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_bad_limits() {
        assert_eq!(
            Limits::<2>::new(f64::NAN, 1.0, 1.0),
            Err(Error::InvalidLimit)
        );
        assert_eq!(Limits::<2>::new(1.0, -1.0, 1.0), Err(Error::InvalidLimit));
        assert_eq!(
            Limits::<2>::new(1.0, 1.0, f64::INFINITY),
            Err(Error::InvalidLimit)
        );
        let l = Limits::<2>::new(1.0, 2.0, 3.0).unwrap();
        assert_eq!(l.with_axis_velocity([1.0, 0.0]), Err(Error::InvalidLimit));
        assert_eq!(
            l.with_axis_acceleration([f64::NAN, 1.0]),
            Err(Error::InvalidLimit)
        );
        assert!(l.with_axis_velocity([1.0, f64::INFINITY]).is_ok());
    }

    #[test]
    fn reserve_scales_accelerations_and_jerk() {
        let l = Limits::<2>::new(10.0, 100.0, 1000.0)
            .and_then(|l| l.with_axis_velocity([5.0, f64::INFINITY]))
            .and_then(|l| l.with_axis_acceleration([80.0, f64::INFINITY]))
            .unwrap();
        let r = l.without_reserve(0.25);
        assert_eq!(
            (r.velocity(), r.acceleration(), r.jerk()),
            (10.0, 75.0, 750.0)
        );
        assert_eq!(r.axis_velocity(), [5.0, f64::INFINITY]);
        assert_eq!(r.axis_acceleration(), [60.0, f64::INFINITY]);
    }
}
