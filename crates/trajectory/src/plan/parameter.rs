//! The parameter-proportional time law: `u` runs over the curve's domain at a constant rate.

use strak_curves::{ParamCurve, Scalar};

use super::timing::Timing;
use crate::error::Error;

/// The curve parameter at a constant rate: `u(t) = u_start + rate·t` over
/// `t ∈ [0, duration]`, `du/dt = rate`, with `rate = (u_end − u_start)/duration`.
///
/// The speed along the path is `|c'(u)|·rate`, so it follows the curve's parameterization
/// (for a chord-length parameterized spline roughly the speed of the chords). The motion
/// does **not** start or end at rest: it starts and ends with `du/dt = rate`, and a compiled
/// path ends with that velocity.
///
/// ```
/// use strak_curves::Bezier;
/// use strak_trajectory::{ParameterTiming, Timing};
///
/// let line = Bezier::new([[0.0, 0.0], [3.0, 4.0]])?; // domain [0, 1]
/// let timing = ParameterTiming::over(&line, 2.0)?;
/// assert_eq!(timing.duration(), 2.0);
/// assert_eq!(timing.param(0.5), (0.25, 0.5));
/// assert_eq!(timing.param(9.0), (1.0, 0.5)); // clamped to the duration
/// let fast = ParameterTiming::at_rate(&line, 4.0)?;
/// assert_eq!(fast.duration(), 0.25);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ParameterTiming {
    start: f64,
    end: f64,
    duration: f64,
    rate: f64,
}

impl ParameterTiming {
    /// `u` runs over the whole domain of `curve` in `duration` seconds.
    ///
    /// # Errors
    /// [`Error::EmptyPath`] for a zero duration; [`Error::InvalidLimit`] for a negative or
    /// non-finite duration.
    ///
    /// ```
    /// use strak_curves::Bezier;
    /// use strak_trajectory::{Error, ParameterTiming};
    /// let line = Bezier::new([[0.0_f32], [1.0]])?;
    /// assert_eq!(ParameterTiming::over(&line, 0.0), Err(Error::EmptyPath));
    /// assert_eq!(ParameterTiming::over(&line, -1.0), Err(Error::InvalidLimit));
    /// assert_eq!(ParameterTiming::over(&line, 4.0)?.rate(), 0.25);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn over<C: ParamCurve>(curve: &C, duration: f64) -> Result<Self, Error> {
        if duration == 0.0 {
            return Err(Error::EmptyPath);
        }
        if !(duration.is_finite() && duration > 0.0) {
            return Err(Error::InvalidLimit);
        }
        let (a, b) = curve.domain();
        let (start, end) = (a.to_f64(), b.to_f64());
        let rate = (end - start) / duration;
        if !(rate.is_finite() && rate > 0.0) {
            return Err(Error::InvalidLimit);
        }
        Ok(ParameterTiming {
            start,
            end,
            duration,
            rate,
        })
    }

    /// `u` runs over the whole domain of `curve` at `rate` parameter units per second; the
    /// duration is `(u_end − u_start)/rate`.
    ///
    /// # Errors
    /// [`Error::InvalidLimit`] unless `rate` is finite and positive and the duration is
    /// finite.
    ///
    /// ```
    /// use strak_curves::Bezier;
    /// use strak_trajectory::{Error, ParameterTiming, Timing};
    /// let line = Bezier::new([[0.0_f32], [1.0]])?;
    /// assert_eq!(ParameterTiming::at_rate(&line, 0.5)?.duration(), 2.0);
    /// assert_eq!(ParameterTiming::at_rate(&line, 0.0), Err(Error::InvalidLimit));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn at_rate<C: ParamCurve>(curve: &C, rate: f64) -> Result<Self, Error> {
        if !(rate.is_finite() && rate > 0.0) {
            return Err(Error::InvalidLimit);
        }
        let (a, b) = curve.domain();
        let (start, end) = (a.to_f64(), b.to_f64());
        let duration = (end - start) / rate;
        if !(duration.is_finite() && duration > 0.0) {
            return Err(Error::InvalidLimit);
        }
        Ok(ParameterTiming {
            start,
            end,
            duration,
            rate,
        })
    }

    /// The rate `du/dt` in parameter units per second.
    pub fn rate(&self) -> f64 {
        self.rate
    }
}

impl Timing for ParameterTiming {
    fn duration(&self) -> f64 {
        self.duration
    }

    /// `(u_start + rate·t, rate)`, `t` clamped to `[0, duration]` (NaN counts as 0); the
    /// domain ends exactly at `t ≤ 0` and `t ≥ duration`.
    fn param(&self, t: f64) -> (f64, f64) {
        let u = if t >= self.duration {
            self.end
        } else if t > 0.0 {
            (self.start + self.rate * t).min(self.end)
        } else {
            self.start
        };
        (u, self.rate)
    }

    /// 0: the parameter runs at a constant rate.
    fn param_acceleration(&self, _t: f64) -> f64 {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use strak_curves::Bezier;

    #[test]
    fn constant_rate_over_domain() {
        let c = Bezier::new([[1.0_f64, 2.0], [3.0, 2.0], [5.0, 0.0]]).unwrap();
        let t = ParameterTiming::over(&c, 8.0).unwrap();
        assert_eq!(t.rate(), 0.125);
        assert_eq!(t.param(0.0), (0.0, 0.125));
        assert_eq!(t.param(4.0), (0.5, 0.125));
        assert_eq!(t.param(8.0), (1.0, 0.125));
        assert_eq!(t.param(-3.0), (0.0, 0.125));
        assert_eq!(t.param(f64::NAN), (0.0, 0.125));
        let r = ParameterTiming::at_rate(&c, 0.125).unwrap();
        assert_eq!(r, t);
    }

    #[test]
    fn errors() {
        let c = Bezier::new([[1.0_f64], [3.0]]).unwrap();
        assert_eq!(ParameterTiming::over(&c, 0.0), Err(Error::EmptyPath));
        assert_eq!(
            ParameterTiming::over(&c, f64::NAN),
            Err(Error::InvalidLimit)
        );
        assert_eq!(
            ParameterTiming::over(&c, f64::INFINITY),
            Err(Error::InvalidLimit)
        );
        assert_eq!(ParameterTiming::over(&c, -2.0), Err(Error::InvalidLimit));
        assert_eq!(ParameterTiming::over(&c, 1e-320), Err(Error::InvalidLimit));
        assert_eq!(ParameterTiming::at_rate(&c, -1.0), Err(Error::InvalidLimit));
        assert_eq!(
            ParameterTiming::at_rate(&c, f64::INFINITY),
            Err(Error::InvalidLimit)
        );
        assert_eq!(
            ParameterTiming::at_rate(&c, 1e-320),
            Err(Error::InvalidLimit)
        );
    }
}
