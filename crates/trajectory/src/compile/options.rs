//! The settings of [`compile`](crate::compile): tolerance, piece length, limits of feed changes.

use crate::error::Error;
use crate::plan::Limits;

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
/// * the acceleration and jerk limits of the machine (norms along the path, as in
///   [`Limits`]) and the share of them reserved for feed changes (default ¼): feed override,
///   hold and resume ramp the feed factor `φ` with `|φ̇|·v_peak ≤ a_ramp` and
///   `|φ̈|·v_peak ≤ j_ramp`, where `a_ramp = max(a_max − a_peak, share·a_max)` (likewise for
///   jerk) and `a_peak`, `v_peak` are the compiled path's own peaks. If the plan used at
///   most `(1 − share)·a_max`, the acceleration `φ²·a + φ̇·v` stays within `a_max` during
///   feed changes. Without limits, the compiler assumes the plan used exactly
///   `(1 − share)` of them: `a_max = a_peak/(1 − share)`, `j_max = j_peak/(1 − share)`,
///   where for a law that limits only the tangential acceleration (such as
///   [`PathTiming::trapezoid`](crate::PathTiming::trapezoid)) `a_peak` is the tangential
///   peak (for a path without acceleration or jerk: `a_max = v_peak / 0.1 s`,
///   `j_max = a_max / 0.1 s`), and `a_max` is at most `aᵢ/(1 − share)` for the
///   acceleration `aᵢ` the law promises for each axis ([`Timing::limits`](crate::Timing::limits)).
///   The ramp bounds the path's acceleration, not each axis's (it adds `φ̇·ẋᵢ ≤ φ̇·|ẋ|` to
///   axis `i`): with per-axis acceleration limits `aᵢ`, the machine's acceleration must be
///   `min(a, aᵢ)`, as [`with_path_limits`](Self::with_path_limits) and
///   [`PathTiming::compile_options`](crate::PathTiming::compile_options) give it, so that
///   no axis gets more than its own share.
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
/// assert_eq!(CompileOptions::default().tolerance(), Tolerance::Relative(1e-4));
/// # Ok::<(), strak_trajectory::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct CompileOptions {
    tolerance: Tolerance,
    max_piece_ticks: u32,
    limits: Option<(f64, f64)>,
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

    /// The limits of a feed ramp on a machine with `limits`: the smallest of its path and
    /// per-axis acceleration limits, `min(a, aᵢ)`, and its jerk. A ramp changes the speed
    /// along the tangent, so it adds `φ̇·ẋᵢ ≤ φ̇·|ẋ|` to axis `i`: with the path's `a` alone,
    /// an axis with a tighter `aᵢ` would exceed it during a feed change.
    ///
    /// ```
    /// use strak_trajectory::{CompileOptions, Limits};
    /// let limits = Limits::<3>::new(200.0, 2_000.0, 50_000.0)?
    ///     .with_axis_acceleration([1_500.0, 1_500.0, 1_000.0])?;
    /// let o = CompileOptions::new().with_path_limits(&limits);
    /// assert_eq!(o.limits(), Some((1_000.0, 50_000.0)));
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn with_path_limits<const A: usize>(self, limits: &Limits<A>) -> Self {
        self.with_limits(limits.ramp_acceleration(), limits.jerk())
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

    /// The acceleration and jerk limits, if given.
    pub const fn limits(&self) -> Option<(f64, f64)> {
        self.limits
    }

    /// The share of the limits reserved for feed changes.
    pub const fn feed_share(&self) -> f64 {
        self.feed_share
    }

    /// Checks the settings.
    ///
    /// # Errors
    /// [`Error::InvalidLimit`] for a tolerance, limit or share that is not finite and
    /// positive (share: in `(0, 1)`), a maximal piece length of 0, or a largest slow-down
    /// that is not finite and at least 1.
    pub(crate) fn validate(&self) -> Result<(), Error> {
        let positive = |x: f64| x.is_finite() && x > 0.0;
        let tol = match self.tolerance {
            Tolerance::Absolute(t) | Tolerance::Relative(t) => t,
        };
        let limits_ok = match self.limits {
            None => true,
            Some((a, j)) => positive(a) && positive(j),
        };
        if positive(tol)
            && limits_ok
            && self.max_piece_ticks >= 1
            && positive(self.feed_share)
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
        let bad = [
            CompileOptions::new().with_tolerance(0.0),
            CompileOptions::new().with_relative_tolerance(f64::NAN),
            CompileOptions::new().with_max_piece_ticks(0),
            CompileOptions::new().with_limits(-1.0, 1.0),
            CompileOptions::new().with_limits(1.0, f64::INFINITY),
            CompileOptions::new().with_feed_share(1.0),
            CompileOptions::new().with_feed_share(0.0),
            CompileOptions::new().with_max_slowdown(0.99),
            CompileOptions::new().with_max_slowdown(f64::NAN),
            CompileOptions::new().with_max_slowdown(f64::INFINITY),
        ];
        for o in bad {
            assert_eq!(o.validate(), Err(Error::InvalidLimit), "{o:?}");
        }
    }
}
