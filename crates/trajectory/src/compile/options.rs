//! The settings of [`compile`](crate::compile): tolerance, piece length, limits of feed changes.

use strak_curves::MAX_DIM;

use crate::error::Error;
use crate::plan::{FeedReserve, Limits};

/// How far the compiled positions may be from the exact `x(t) = c(u(t))` at every tick.
///
/// ```
/// use strak_trajectory::{CompileOptions, Tolerance};
/// let o = CompileOptions::new().with_tolerance(1e-3);
/// assert_eq!(o.tolerance(), Tolerance::Absolute(1e-3));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Tolerance {
    /// In path units (per axis).
    Absolute(f64),
    /// A fraction of the path's extent: the largest width, over the axes, of the bounding box
    /// of the positions at the initial knots.
    Relative(f64),
}

/// Settings of [`compile`](crate::compile).
///
/// * tolerance: default [`Tolerance::Relative`]`(1e-4)`;
/// * maximal piece length: default 256 ticks (bounds the forward-differencing error, see
///   [`Number`](crate::Number));
/// * the largest slow-down (default 1.25): the factor by which [`compile`](crate::compile)
///   may stretch a time law's duration so that the compiled pieces keep the limits the law
///   promises ([`Timing::limits`](crate::Timing::limits)); 1 allows none;
/// * the machine's limits for feed changes (path acceleration and jerk, per-axis
///   accelerations, as in [`Limits`]) and the share of them the plan must have left free
///   (default ¼). Feed override, hold and resume ramp the feed factor `φ`, which adds
///   `φ̇·|ẋ|` to the acceleration (`φ̇·|ẋᵢ|` to axis `i`) and `3·φ̇·a_peak + φ̈·v_peak` to
///   the jerk (see [`Sampler::set_feed`](crate::Sampler::set_feed)); the ramps take what the
///   compiled motion leaves free, `a_ramp = min(a − a_peak, minᵢ (aᵢ − aᵢ,peak)·v_peak/vᵢ,peak)`
///   and `j_ramp = j − j_peak` (`peak`: the compiled pieces' own peaks), so that the
///   samples stay within the limits during feed changes. For a law that promises limits
///   ([`Timing::limits`](crate::Timing::limits)), `compile` checks that its peaks use at
///   most `1 − share` of each given limit it promises (path or tangential acceleration,
///   jerk, axis accelerations), and fails with
///   [`Error::FeedReserveExceeded`](crate::Error::FeedReserveExceeded) otherwise: a plan
///   that left less than the share free cannot exceed a limit through a feed change. For a
///   law that promises none (a parameter rate, a constant speed: its own motion is not
///   limited), each free part is at least `share` of its limit.
/// * Without limits, a planned law's reserve ([`Timing::feed_reserve`](crate::Timing::feed_reserve):
///   the machine's limits and the plan's share, which replaces this one) is used. A law
///   that promises limits but reserves nothing (such as
///   [`PathTiming::trapezoid`](crate::PathTiming::trapezoid)) is taken to move at them: they
///   stand in for the machine's, so that with a share it fails with
///   [`Error::FeedReserveExceeded`](crate::Error::FeedReserveExceeded) unless the options
///   give the machine's limits (plan it with `1 − share` of them). For a law that promises
///   no limits the compiler assumes the plan used exactly `(1 − share)` of the
///   limits: `a_max = a_peak/(1 − share)`, `j_max = j_peak/(1 − share)`, where for a law that
///   limits only the tangential acceleration (such as
///   [`PathTiming::trapezoid`](crate::PathTiming::trapezoid)) `a_peak` is the tangential
///   peak (for a path without acceleration or jerk: `a_max = v_peak / 0.1 s`,
///   `j_max = a_max / 0.1 s`), and `a_max` is at most `aᵢ/(1 − share)` for the
///   acceleration `aᵢ` the law promises for each axis.
///
/// ```
/// use strak_trajectory::{CompileOptions, Limits, Tolerance};
/// let limits = Limits::<3>::new(200.0, 2_000.0, 50_000.0)?;
/// let o = CompileOptions::new()
///     .with_tolerance(1e-4)
///     .with_max_piece_ticks(128)
///     .with_path_limits(&limits);
/// assert_eq!(o.max_piece_ticks(), 128);
/// assert_eq!(o.limits(), Some((2_000.0, 50_000.0)));
/// assert!(o.axis_acceleration().iter().all(|a| a.is_infinite()));
/// assert_eq!(CompileOptions::default().tolerance(), Tolerance::Relative(1e-4));
/// # Ok::<(), strak_trajectory::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct CompileOptions {
    tolerance: Tolerance,
    max_piece_ticks: u32,
    limits: Option<(f64, f64)>,
    axis_acceleration: [f64; MAX_DIM],
    feed_share: f64,
    max_slowdown: f64,
}

impl Default for CompileOptions {
    fn default() -> Self {
        Self::new()
    }
}

impl CompileOptions {
    /// The default relative tolerance: 10⁻⁴ of the path's extent.
    pub const DEFAULT_RELATIVE_TOLERANCE: f64 = 1e-4;
    /// The default maximal piece length in ticks.
    pub const DEFAULT_MAX_PIECE_TICKS: u32 = 256;
    /// The default share of the acceleration and jerk limits reserved for feed changes.
    pub const DEFAULT_FEED_SHARE: f64 = 0.25;
    /// The default largest slow-down.
    pub const DEFAULT_MAX_SLOWDOWN: f64 = 1.25;

    /// The defaults (see the type docs).
    pub const fn new() -> Self {
        CompileOptions {
            tolerance: Tolerance::Relative(Self::DEFAULT_RELATIVE_TOLERANCE),
            max_piece_ticks: Self::DEFAULT_MAX_PIECE_TICKS,
            limits: None,
            axis_acceleration: [f64::INFINITY; MAX_DIM],
            feed_share: Self::DEFAULT_FEED_SHARE,
            max_slowdown: Self::DEFAULT_MAX_SLOWDOWN,
        }
    }

    /// An absolute position tolerance in path units (finite, > 0; checked by `compile`).
    pub const fn with_tolerance(mut self, units: f64) -> Self {
        self.tolerance = Tolerance::Absolute(units);
        self
    }

    /// A tolerance relative to the path's extent (finite, > 0; checked by `compile`).
    pub const fn with_relative_tolerance(mut self, fraction: f64) -> Self {
        self.tolerance = Tolerance::Relative(fraction);
        self
    }

    /// The maximal piece length in ticks (≥ 1; checked by `compile`).
    pub const fn with_max_piece_ticks(mut self, ticks: u32) -> Self {
        self.max_piece_ticks = ticks;
        self
    }

    /// The machine's path acceleration (units/s²) and jerk (units/s³) limits for feed changes
    /// (finite, > 0; checked by `compile`).
    pub const fn with_limits(mut self, acceleration: f64, jerk: f64) -> Self {
        self.limits = Some((acceleration, jerk));
        self
    }

    /// The per-axis acceleration limits (units/s²; > 0, `f64::INFINITY` for an axis without
    /// a limit of its own; checked by `compile`) for feed changes: a ramp adds `φ̇·|ẋᵢ|` to
    /// axis `i`. Entries beyond [`MAX_DIM`] are ignored.
    ///
    /// ```
    /// use strak_trajectory::CompileOptions;
    /// let o = CompileOptions::new().with_axis_acceleration([1_500.0, 1_500.0, 300.0]);
    /// assert_eq!(o.axis_acceleration()[2], 300.0);
    /// assert!(o.axis_acceleration()[3].is_infinite());
    /// ```
    pub const fn with_axis_acceleration<const A: usize>(mut self, limits: [f64; A]) -> Self {
        // A `while` loop: this builder also runs in `const` and `static` initializers.
        let mut i = 0;
        while i < A && i < MAX_DIM {
            self.axis_acceleration[i] = limits[i];
            i += 1;
        }
        self
    }

    /// The limits of a machine with `limits` for feed changes: its path acceleration and
    /// jerk ([`with_limits`](Self::with_limits)) and its per-axis accelerations
    /// ([`with_axis_acceleration`](Self::with_axis_acceleration)).
    ///
    /// ```
    /// use strak_trajectory::{CompileOptions, Limits};
    /// let limits = Limits::<3>::new(200.0, 2_000.0, 50_000.0)?
    ///     .with_axis_acceleration([1_500.0, 1_500.0, 1_000.0])?;
    /// let o = CompileOptions::new().with_path_limits(&limits);
    /// assert_eq!(o.limits(), Some((2_000.0, 50_000.0)));
    /// assert_eq!(o.axis_acceleration()[..3], [1_500.0, 1_500.0, 1_000.0]);
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn with_path_limits<const A: usize>(self, limits: &Limits<A>) -> Self {
        self.with_limits(limits.acceleration(), limits.jerk())
            .with_axis_acceleration(limits.axis_acceleration())
    }

    /// The limits and share of a plan's [`FeedReserve`]: what [`compile`](crate::compile())
    /// uses for a planned law when the options give no limits.
    ///
    /// ```
    /// use strak_curves::MAX_DIM;
    /// use strak_trajectory::{CompileOptions, FeedReserve};
    /// let reserve = FeedReserve {
    ///     acceleration: 2_000.0,
    ///     jerk: 50_000.0,
    ///     axis_acceleration: [f64::INFINITY; MAX_DIM],
    ///     share: 0.1,
    /// };
    /// let o = CompileOptions::new().with_feed_reserve(&reserve);
    /// assert_eq!((o.limits(), o.feed_share()), (Some((2_000.0, 50_000.0)), 0.1));
    /// ```
    pub fn with_feed_reserve(self, reserve: &FeedReserve) -> Self {
        let mut o = self
            .with_limits(reserve.acceleration, reserve.jerk)
            .with_feed_share(reserve.share);
        o.axis_acceleration = reserve.axis_acceleration;
        o
    }

    /// These options, with `reserve` when they give no limits (see
    /// [`with_feed_reserve`](Self::with_feed_reserve)).
    pub(crate) fn completed_by(&self, reserve: Option<FeedReserve>) -> Self {
        match (self.limits, reserve) {
            (None, Some(r)) => self.with_feed_reserve(&r),
            _ => *self,
        }
    }

    /// The share of the limits reserved for feed changes (in `(0, 1)`; checked by `compile`).
    pub const fn with_feed_share(mut self, share: f64) -> Self {
        self.feed_share = share;
        self
    }

    /// The largest factor (finite, `≥ 1`; checked by `compile`) by which `compile` may
    /// stretch the time law's duration so that the compiled pieces keep the law's limits.
    ///
    /// ```
    /// use strak_trajectory::CompileOptions;
    /// let strict = CompileOptions::new().with_max_slowdown(1.0); // an error rather than slower
    /// assert_eq!(strict.max_slowdown(), 1.0);
    /// ```
    pub const fn with_max_slowdown(mut self, factor: f64) -> Self {
        self.max_slowdown = factor;
        self
    }

    /// The largest slow-down.
    pub const fn max_slowdown(&self) -> f64 {
        self.max_slowdown
    }

    /// The tolerance.
    pub const fn tolerance(&self) -> Tolerance {
        self.tolerance
    }

    /// The maximal piece length in ticks.
    pub const fn max_piece_ticks(&self) -> u32 {
        self.max_piece_ticks
    }

    /// The path acceleration and jerk limits, if given.
    pub const fn limits(&self) -> Option<(f64, f64)> {
        self.limits
    }

    /// The per-axis acceleration limits (`f64::INFINITY`: none).
    pub const fn axis_acceleration(&self) -> [f64; MAX_DIM] {
        self.axis_acceleration
    }

    /// The share of the limits reserved for feed changes.
    pub const fn feed_share(&self) -> f64 {
        self.feed_share
    }

    /// Checks the settings.
    ///
    /// # Errors
    /// [`Error::InvalidLimit`] for a tolerance, limit or share that is not finite and
    /// positive (share: in `[0, 1)`; an axis acceleration may be `f64::INFINITY`), a maximal
    /// piece length of 0, or a largest slow-down that is not finite and at least 1.
    pub(crate) fn validate(&self) -> Result<(), Error> {
        let positive = |x: f64| x.is_finite() && x > 0.0;
        let tol = match self.tolerance {
            Tolerance::Absolute(t) | Tolerance::Relative(t) => t,
        };
        let limits_ok = match self.limits {
            None => true,
            Some((a, j)) => positive(a) && positive(j),
        };
        // NaN fails `> 0`; +∞ means "no limit of its own".
        let axes_ok = self.axis_acceleration.iter().all(|a| *a > 0.0);
        if positive(tol)
            && limits_ok
            && axes_ok
            && self.max_piece_ticks >= 1
            && self.feed_share >= 0.0
            && self.feed_share < 1.0
            && self.max_slowdown.is_finite()
            && self.max_slowdown >= 1.0
        {
            Ok(())
        } else {
            Err(Error::InvalidLimit)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn validation() {
        assert_eq!(CompileOptions::new().validate(), Ok(()));
        // no reserve: the feed changes go through a feed guard
        assert_eq!(
            CompileOptions::new().with_feed_share(0.0).validate(),
            Ok(())
        );
        let bad = [
            CompileOptions::new().with_tolerance(0.0),
            CompileOptions::new().with_relative_tolerance(f64::NAN),
            CompileOptions::new().with_max_piece_ticks(0),
            CompileOptions::new().with_limits(-1.0, 1.0),
            CompileOptions::new().with_limits(1.0, f64::INFINITY),
            CompileOptions::new().with_axis_acceleration([1.0, 0.0]),
            CompileOptions::new().with_axis_acceleration([f64::NAN]),
            CompileOptions::new().with_feed_share(1.0),
            CompileOptions::new().with_feed_share(-0.1),
            CompileOptions::new().with_feed_share(f64::NAN),
            CompileOptions::new().with_max_slowdown(0.99),
            CompileOptions::new().with_max_slowdown(f64::NAN),
            CompileOptions::new().with_max_slowdown(f64::INFINITY),
        ];
        for o in bad {
            assert_eq!(o.validate(), Err(Error::InvalidLimit), "{o:?}");
        }
    }
}
