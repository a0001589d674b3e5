//! The motion `x(k) = c(u(t_k))` on the tick grid: the time law sampled at the ticks of one
//! stretch of time, the end slopes, and the knots on the law's breaks.

use strak_curves::{ParamCurveDeriv, Point, Scalar, ScalarOf};

use super::knots::Knots;
use super::spline_fit::SplineFit;
use crate::error::Error;
use crate::plan::{MotionLimits, Timing};

/// Breaks of the time law closer than this many ticks to their neighbours (or the ends) get
/// no knot: a jerk step up to half a tick off a knot disturbs the jerk of a piece of `h`
/// ticks by about `Δj/(2h)`, and chains of short pieces ring.
const MIN_BREAK_GAP: f64 = 8.0;

/// The time law `timing` along `curve` played over `ticks` ticks: tick `k` is at time-law
/// time `k · per_tick` (the last tick exactly at the law's end).
pub(super) struct TickLaw<'a, C: ?Sized, T: ?Sized> {
    curve: &'a C,
    timing: &'a T,
    /// The time law's duration in seconds.
    duration: f64,
    /// The number of ticks.
    pub(super) ticks: u32,
    /// Time-law seconds per tick (the tick period times the time scale).
    pub(super) per_tick: f64,
    /// The tick period in seconds.
    pub(super) period: f64,
    /// The curve's domain in `f64`.
    domain: (f64, f64),
}

impl<'a, C, T> TickLaw<'a, C, T>
where
    C: ParamCurveDeriv + ?Sized,
    T: Timing + ?Sized,
{
    /// The law over `⌈duration · rate · stretch⌉` ticks, at least `min_ticks` (a duration
    /// that is a whole number of ticks up to rounding is not lengthened by a tick).
    ///
    /// # Errors
    /// [`Error::TooLong`] for more ticks than a `u32` counts.
    pub(super) fn new(
        curve: &'a C,
        timing: &'a T,
        rate: f64,
        stretch: f64,
        min_ticks: u32,
    ) -> Result<Self, Error> {
        let duration = timing.duration();
        let raw = duration * rate * stretch;
        // (an overflow to ∞ would make `raw − raw·10⁻¹²` NaN, and `max` would take 1)
        if raw > f64::from(u32::MAX) {
            return Err(Error::TooLong);
        }
        let ticks_f = libm::ceil(raw - raw * 1e-12)
            .max(1.0)
            .max(f64::from(min_ticks));
        if ticks_f > f64::from(u32::MAX) {
            return Err(Error::TooLong);
        }
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let ticks = ticks_f as u32;
        let (lo, hi) = curve.domain();
        Ok(TickLaw {
            curve,
            timing,
            duration,
            ticks,
            per_tick: duration / ticks_f,
            period: 1.0 / rate,
            domain: (lo.to_f64(), hi.to_f64()),
        })
    }

    /// The time law's duration in seconds.
    pub(super) fn duration(&self) -> f64 {
        self.duration
    }

    /// The limits the time law promises ([`Timing::limits`]).
    pub(super) fn limits(&self) -> Option<MotionLimits> {
        self.timing.limits()
    }

    /// The curve parameter at time-law time `t`, in the curve's scalar type, and `du/dt`.
    pub(super) fn param(&self, t: f64) -> Result<(ScalarOf<C>, f64), Error> {
        let (u, du) = self.timing.param(t);
        if !(u.is_finite() && du.is_finite()) {
            return Err(Error::Curve(strak_curves::Error::NonFinite));
        }
        let s = <ScalarOf<C> as Scalar>::from_f64(u.clamp(self.domain.0, self.domain.1))
            .ok_or(Error::Curve(strak_curves::Error::OutOfRange))?;
        Ok((s, du))
    }

    /// The time-law time of tick `k` (the law's end exactly at the last tick).
    pub(super) fn time(&self, k: u32) -> f64 {
        if k == self.ticks {
            self.duration
        } else {
            f64::from(k) * self.per_tick
        }
    }

    /// The exact position at tick `k` (the law's end at the last tick).
    pub(super) fn position<const A: usize>(&self, k: u32) -> Result<[f64; A], Error> {
        coords(self.curve.eval(self.param(self.time(k))?.0))
    }

    /// The slope `dx/dk = c'(u) · du/dt · per_tick` (units per tick) at time-law time `t`.
    pub(super) fn slope<const A: usize>(&self, t: f64) -> Result<[f64; A], Error> {
        let (u, du) = self.param(t)?;
        let d: [f64; A] = coords(self.curve.deriv(u, 1))?;
        Ok(d.map(|v| v * du * self.per_tick))
    }

    /// Calls `f(k, before, after)` for every break of the time law ([`Timing::breaks`]) at
    /// tick `k` strictly inside the motion, with the ticks of its neighbouring breaks (or
    /// the ends), once per break; stops at the first error.
    fn for_each_break(
        &self,
        f: &mut dyn FnMut(f64, f64, f64) -> Result<(), Error>,
    ) -> Result<(), Error> {
        let mut result = Ok(());
        let mut prev = 0.0_f64;
        let mut pending: Option<f64> = None;
        self.timing.breaks(&mut |t: f64| {
            if result.is_err() || !(t > 0.0 && t < self.duration) {
                return;
            }
            let k = t / self.per_tick;
            if let Some(cur) = pending {
                if (k - cur).abs() < 1e-6 {
                    return; // the same break twice (e.g. around an empty phase)
                }
                result = f(cur, prev, k);
                prev = cur;
            }
            pending = Some(k);
        });
        result?;
        match pending {
            Some(cur) => f(cur, prev, f64::from(self.ticks)),
            None => Ok(()),
        }
    }

    /// Puts knots on the breaks of the time law ([`Timing::breaks`]):
    ///
    /// * a break at least [`MIN_BREAK_GAP`] ticks from its neighbouring breaks and the ends
    ///   gets a knot on the nearest tick;
    /// * when every break is closer than that to a neighbour (a law whose jerk phases all
    ///   last a few ticks) and `one_tick_pieces` holds, every break gets knots on the ticks
    ///   before and after it: a piece of one tick holds the jerk step, and the pieces
    ///   between follow the law's phases without a step inside. A piece of one tick takes up
    ///   the acceleration errors of its neighbours divided by the tick period, and a break
    ///   half a tick off its knot leaves an acceleration error of up to `Δj·T/2` in the
    ///   pieces after it: so pieces of one tick are used only when no break is placed on a
    ///   single knot;
    /// * otherwise a close break gets no knot.
    pub(super) fn knots_on_breaks<const A: usize, K: Knots<A>>(
        &self,
        fit: &mut SplineFit<A, K>,
        one_tick_pieces: bool,
    ) -> Result<(), Error> {
        let isolated = |k: f64, before: f64, after: f64| {
            (k - before).abs() >= MIN_BREAK_GAP && (after - k).abs() >= MIN_BREAK_GAP
        };
        let mut all_close = one_tick_pieces;
        if all_close {
            self.for_each_break(&mut |k, before, after| {
                all_close &= !isolated(k, before, after);
                Ok(())
            })?;
        }
        let ticks_f = f64::from(self.ticks);
        let mut exact = |k: u32| self.position::<A>(k);
        self.for_each_break(&mut |k, before, after| {
            let (lo, hi) = if all_close {
                (libm::floor(k), libm::ceil(k))
            } else if isolated(k, before, after) {
                (libm::round(k), libm::round(k))
            } else {
                return Ok(());
            };
            for tick in [lo, hi] {
                if tick >= 1.0 && tick < ticks_f {
                    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                    fit.insert_knot(tick as u32, &mut exact)?;
                }
            }
            Ok(())
        })
    }
}

/// A motion on the tick grid as a stretch is fitted to it: its exact position, slope and
/// second derivative (per tick and per tick²) at every tick, the jumps of its jerk, and
/// the limits it promises.
pub(crate) trait TickMotion<const A: usize> {
    /// The tick period in seconds.
    fn period(&self) -> f64;
    /// The position at tick `k`.
    fn position(&self, k: u32) -> Result<[f64; A], Error>;
    /// The slope `dx/dk` at tick `k`.
    fn slope(&self, k: u32) -> Result<[f64; A], Error>;
    /// The second derivative `d²x/dk²` at tick `k`.
    fn second(&self, k: u32) -> Result<[f64; A], Error>;
    /// Calls `f` with every jump of the jerk strictly between the ticks `first` and `last`,
    /// as a fractional tick, in increasing order.
    fn breaks_between(&self, first: u32, last: u32, f: &mut dyn FnMut(f64));
    /// The limits the motion promises, if any.
    fn limits(&self) -> Option<MotionLimits>;
}

/// The law's motion: `d²x/dk² = (c''·u̇² + c'·ü) · per_tick²` with `ü` from
/// [`Timing::param_acceleration`], and the breaks of [`Timing::breaks`].
impl<C, T, const A: usize> TickMotion<A> for TickLaw<'_, C, T>
where
    C: ParamCurveDeriv + ?Sized,
    T: Timing + ?Sized,
{
    fn period(&self) -> f64 {
        self.period
    }
    fn position(&self, k: u32) -> Result<[f64; A], Error> {
        TickLaw::position(self, k)
    }
    fn slope(&self, k: u32) -> Result<[f64; A], Error> {
        TickLaw::slope(self, self.time(k))
    }
    fn second(&self, k: u32) -> Result<[f64; A], Error> {
        let t = self.time(k);
        let (u, du) = self.param(t)?;
        let ddu = self.timing.param_acceleration(t);
        let d1: [f64; A] = coords(self.curve.deriv(u, 1))?;
        let d2: [f64; A] = coords(self.curve.deriv(u, 2))?;
        let scale = self.per_tick * self.per_tick;
        let x: [f64; A] = core::array::from_fn(|a| (d2[a] * du * du + d1[a] * ddu) * scale);
        if x.iter().all(|v| v.is_finite()) {
            Ok(x)
        } else {
            Err(Error::Curve(strak_curves::Error::NonFinite))
        }
    }
    fn breaks_between(&self, first: u32, last: u32, f: &mut dyn FnMut(f64)) {
        let (lo, hi) = (f64::from(first), f64::from(last));
        let mut prev = f64::NEG_INFINITY;
        self.timing.breaks(&mut |t: f64| {
            let k = t / self.per_tick;
            if k > lo && k < hi && k - prev >= 1e-6 {
                f(k);
                prev = k;
            }
        });
    }
    fn limits(&self) -> Option<MotionLimits> {
        TickLaw::limits(self)
    }
}

/// The coordinates of `p` in `f64` (all finite, else [`Error::Curve`]).
pub(super) fn coords<P: Point, const A: usize>(p: P) -> Result<[f64; A], Error> {
    let x: [f64; A] = core::array::from_fn(|i| p.coord(i).to_f64());
    if x.iter().all(|v| v.is_finite()) {
        Ok(x)
    } else {
        Err(Error::Curve(strak_curves::Error::NonFinite))
    }
}
