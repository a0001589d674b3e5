//! What a path is besides its pieces: rate, timing, end, feed-ramp constants and bounds, and
//! the validation every path passes (compiled, or loaded from a blob).

use strak_curves::Scalar;

use super::sample::Sample;
use super::state::{AxisState, Newton};
use crate::error::Error;
use crate::num::{Number, RATE_RANGE};

/// Where a path ends: the exact end point (as the curve computes it, converted once) and
/// the end velocity and acceleration, in the sample type.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PathEnd<T, const A: usize> {
    pub(crate) position: [T; A],
    pub(crate) velocity: [T; A],
    pub(crate) acceleration: [T; A],
}

/// The scalar description of a path (all `f64`): timing, tolerance, and the rate, kinematic
/// peaks and limits its feed ramps are sized from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PathMeta {
    pub(crate) plan_duration: f64,
    pub(crate) tolerance: f64,
    /// What the path's feed ramps are sized from.
    pub(crate) ramp: RampBasis,
}

/// What a feed ramp is sized from: the control rate, the motion's peaks, the limits and
/// the feed share of them kept free (see [`feed_ramp_f64`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct RampBasis {
    pub(crate) rate: f64,
    pub(crate) peak_velocity: f64,
    pub(crate) peak_acceleration: f64,
    pub(crate) peak_jerk: f64,
    pub(crate) acceleration_limit: f64,
    pub(crate) jerk_limit: f64,
    pub(crate) feed_share: f64,
}

/// The feed-ramp constants of a path in its number format, per tick.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FeedRampLimits<N> {
    /// Largest change of the feed factor's rate `ω` per tick; `ω` is a whole multiple of it.
    pub(crate) alpha: N,
    /// Largest `|ω|` in multiples of `α` (1 ..= 2²⁰).
    pub(crate) k_max: i64,
    /// The rate in ticks per second (`φ̇ = ω · rate`).
    pub(crate) rate: N,
    /// Within this distance of its target, at a rate at most this, the feed factor snaps onto
    /// the target: `max(α, ε)` (ε: the format's spacing at 1, below which a float `φ` near 1
    /// cannot move).
    pub(crate) snap: N,
}

impl<N: Number> FeedRampLimits<N> {
    /// The constants of a ramp changing `ω` by at most `alpha` per tick, up to
    /// `k_max · alpha`, with its snap distance `max(α, ε)`.
    pub(crate) fn new(alpha: N, k_max: i64, rate: N) -> Self {
        let snap = if alpha > N::EPSILON {
            alpha
        } else {
            N::EPSILON
        };
        FeedRampLimits {
            alpha,
            k_max,
            rate,
            snap,
        }
    }

    /// The constants in `N` of a ramp with the largest rate `omega` and change per tick
    /// `alpha` (from [`feed_ramp_f64`]) at `rate` ticks per second: `ω_max` rounded down to a
    /// whole multiple of `α`, so that `ω` stays one and the ramp's braking distance is exact
    /// (at most 2²⁰ steps, as `ω_max ≤ √α` and `α ≥ 2⁻⁴⁰`).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] when `α` or the rate does not fit `N`.
    pub(crate) fn from_rates(omega: f64, alpha: f64, rate: f64) -> Result<Self, Error> {
        let alpha = N::from_f64(alpha).ok_or(Error::OutOfRange)?;
        #[allow(clippy::cast_possible_truncation)]
        let k_max = libm::floor(omega / alpha.to_f64()).clamp(1.0, f64::from(1_u32 << 20)) as i64;
        let rate = N::from_f64(rate).ok_or(Error::OutOfRange)?;
        Ok(Self::new(alpha, k_max, rate))
    }

    /// The largest rate of the feed factor `φ̇ = α·K_max·rate`, per second, at `rate` ticks
    /// per second.
    #[allow(clippy::cast_precision_loss)]
    pub(crate) fn phi_dot_max(&self, rate: f64) -> f64 {
        self.alpha.to_f64() * (self.k_max as f64) * rate
    }

    /// The ramp slowed to `2⁻ˢʰⁱᶠᵗ`: its change per tick `α` (and so its largest rate) times
    /// `2⁻ˢʰⁱᶠᵗ`; `None` when that is below 2⁻⁴⁰ or not exact in `N`.
    pub(crate) fn scaled(&self, shift: u8) -> Option<Self> {
        let alpha = self.alpha.to_f64() * libm::ldexp(1.0, -i32::from(shift));
        let scaled = N::from_f64(alpha).filter(|a| a.to_f64() == alpha && alpha >= MIN_ALPHA)?;
        Some(self.with_alpha(scaled))
    }

    /// The same ramp with the change per tick `alpha` (and `ω` up to `k_max · alpha`).
    pub(crate) fn with_alpha(&self, alpha: N) -> Self {
        Self::new(alpha, self.k_max, self.rate)
    }
}

/// The share of the limits the feed ramps of a path without a reserve are sized for.
pub(crate) const UNRESERVED_RAMP_SHARE: f64 = 0.25;

/// The smallest change of the feed rate per tick: 2⁻⁴⁰ (one `Q40` ulp).
pub(crate) const MIN_ALPHA: f64 = 1.0 / (1_u64 << 40) as f64;

/// `max |C(x, k)|` for `x ∈ [0, n]`, `k ≤ 3` (the Newton coefficients of an offset `x`).
fn binomial_bound(n: f64, k: u32) -> f64 {
    match k {
        0 => 1.0,
        1 => n,
        2 => (n * (n - 1.0) / 2.0).max(0.125),
        // |θ(θ−1)(θ−2)/6| ≤ 0.0642 on [0, 2]
        _ => (n * (n - 1.0) * (n - 2.0) / 6.0).max(0.065),
    }
}

/// `C(n, k)` for the error propagation of forward differencing (`n ≥ 0`).
fn binomial(n: f64, k: u32) -> f64 {
    match k {
        0 => 1.0,
        1 => n,
        2 => n * (n - 1.0) / 2.0,
        _ => n * (n - 1.0) * (n - 2.0) / 6.0,
    }
}

/// Range and error bounds of one axis of one piece.
pub(crate) struct PieceBounds {
    /// Bound on the magnitude of every position-related value and partial sum.
    position_sum: f64,
    /// Bound on every velocity-related value and partial sum.
    velocity_sum: f64,
    /// Bound on every acceleration-related value and partial sum (before the `φ̇·v` term).
    acceleration_sum: f64,
    /// Bound on the playback error of the position at any tick of the piece.
    playback_error: f64,
}

pub(crate) fn piece_bounds<N: Number>(state: &AxisState<N>, ticks: u32) -> PieceBounds {
    // Each value converted where it is used (no `f64` copy of the state in this frame, which
    // lies below the blob validation's).
    let abs = |x: N| x.to_f64().abs();
    let n = f64::from(ticks);
    let (c1, c2, c3) = (
        binomial_bound(n, 1),
        binomial_bound(n, 2),
        binomial_bound(n, 3),
    );
    let (d1, d2, m3) = (abs(state.delta1), abs(state.delta2), abs(state.delta3));
    let m2 = d2 + c1 * m3;
    let m1 = d1 + c1 * d2 + c2 * m3;
    let mf = abs(state.position) + c1 * d1 + c2 * d2 + c3 * m3;
    let v2 = abs(state.velocity_delta2);
    let vd1 = abs(state.velocity_delta1);
    let v1 = vd1 + c1 * v2;
    let v0 = abs(state.velocity) + c1 * vd1 + c2 * v2;
    let a1 = abs(state.acceleration_delta);
    let a0 = abs(state.acceleration) + c1 * a1;
    // Error after i ≤ n ticks: r_f + i·r₁ + C(i,2)·r₂ + C(i,3)·(r₃ + add₂) + C(i,2)·add₁ + i·add_f
    // (r: rounding of the stored value, add: rounding of an addition; 0 in fixed-point).
    let r = N::rounding_error;
    let add = N::addition_error;
    let playback_error = r(mf)
        + n * (r(m1) + add(mf))
        + binomial(n, 2) * (r(m2) + add(m1))
        + binomial(n, 3) * (r(m3) + add(m2))
        + N::OUT_ERROR;
    PieceBounds {
        position_sum: mf + m1 + m2 + m3,
        velocity_sum: v0 + v1 + v2,
        acceleration_sum: a0 + a1,
        playback_error,
    }
}

/// The feed-ramp constants (per tick) from the motion's kinematic description `basis`.
///
/// Played with the feed factor `φ(t)` (`θ̇ = φ`, `x = p(θ)`), the motion is, by the chain
/// rule, `ẋ = φ·p′`, `ẍ = φ²·p″ + φ̇·p′`, `x⃛ = φ³·p‴ + 3·φ·φ̇·p″ + φ̈·p′`: a ramp with
/// `|φ̇| ≤ φ̇_max` and `|φ̈| ≤ φ̈_max` adds at most `φ̇_max·v_peak` to the acceleration and
/// `3·φ̇_max·a_peak + φ̈_max·v_peak` to the jerk. With what the path leaves of the limits,
/// `a_ramp = max(a_max − a_peak, share · a_max)` and
/// `R = j_ramp = max(j_max − j_peak, share · j_max)`, the ramp takes
/// `A = φ̇_max·v_peak = min(a_ramp, √v·R/(√R + c·√v))` and `φ̈_max·v_peak = R − c·A`
/// (`v = v_peak`, `c = 3·a_peak/v_peak`): the split of `R` between the two jerk terms for
/// which a ramp of `φ` from 1 to 0, about `1/φ̇_max + φ̇_max/φ̈_max` seconds, is fastest
/// (without the cross term, `c = 0`, `A ≤ √(v·R)`, the rate a jerk-limited ramp over 1
/// reaches anyway). Per tick: `ω_max = A/(v_peak·f)`, `α = (R − c·A)/(v_peak·f²)`,
/// `2⁻⁴⁰ ≤ α ≤ ¼` (the same resolution in every format), `ω_max ≤ min(½, √α)`, and
/// `α ≤ ω_max` (a smaller `α` where the jerk would reach `ω_max` within a tick).
///
/// A path without a reserve (`share = 0`) sizes its ramps as if
/// [`UNRESERVED_RAMP_SHARE`] of the limits were free: nothing keeps them free, so its feed
/// changes keep the limits only where a [`FeedGuard`](crate::FeedGuard) has checked them.
pub(crate) fn feed_ramp_f64(basis: &RampBasis) -> (f64, f64) {
    let share = if basis.feed_share > 0.0 {
        basis.feed_share
    } else {
        UNRESERVED_RAMP_SHARE
    };
    let a_ramp =
        (basis.acceleration_limit - basis.peak_acceleration).max(share * basis.acceleration_limit);
    let j_ramp = (basis.jerk_limit - basis.peak_jerk).max(share * basis.jerk_limit);
    let (omega, alpha) = if basis.peak_velocity > 0.0 {
        let v = basis.peak_velocity;
        let c = 3.0 * basis.peak_acceleration / v;
        let (sv, sr) = (libm::sqrt(v), libm::sqrt(j_ramp));
        let a = a_ramp.min(sv * j_ramp / (sr + c * sv));
        (
            a / (v * basis.rate),
            (j_ramp - c * a) / (v * basis.rate * basis.rate),
        )
    } else {
        (0.5, 0.25)
    };
    let alpha = alpha.clamp(MIN_ALPHA, 0.25);
    let omega = omega.min(0.5).min(libm::sqrt(alpha));
    // A jerk so high that `ω` could reach `ω_max` within a tick: one step of `ω_max` (the
    // ramp's rate is a whole multiple of `α`, at least one).
    let alpha = alpha.min(omega.max(MIN_ALPHA));
    (omega, alpha)
}

/// Writes [`PathHeader::end_state`] from the header's end, in place.
///
/// # Errors
/// [`Error::OutOfRange`] when a sample value has no exact accumulator value.
fn write_end_state<N: Number, const A: usize>(header: &mut PathHeader<N, A>) -> Result<(), Error> {
    let exact = |v: N::Out| {
        let n = N::from_out(v);
        if n.to_out() == v {
            Ok(n)
        } else {
            Err(Error::OutOfRange)
        }
    };
    let end = &header.end;
    for (a, e) in header.end_state.iter_mut().enumerate() {
        *e = AxisState::ZERO;
        if let (Some(&x), Some(&v), Some(&acc)) = (
            end.position.get(a),
            end.velocity.get(a),
            end.acceleration.get(a),
        ) {
            e.position = exact(x)?;
            e.velocity = exact(v)?;
            e.acceleration = exact(acc)?;
        }
    }
    Ok(())
}

fn positive(x: f64) -> bool {
    x.is_finite() && x > 0.0
}

/// Everything about a path except its pieces: rate, duration, tolerance, the end, the feed
/// ramp constants and the playback bound. [`Path`](crate::Path),
/// [`PathBlob`](crate::PathBlob) and [`PathView`](crate::PathView) dereference to it, so
/// these accessors are the same on all three.
///
/// ```
/// use strak_trajectory::{compile, Along, CompileOptions, Path, Timing};
/// use strak_curves::Bezier;
/// struct Ramp;
/// impl Timing for Ramp {
///     fn duration(&self) -> f64 { 0.1 }
///     fn param(&self, t: f64) -> (f64, f64) { (t.clamp(0.0, 0.1) * 10.0, 10.0) }
/// }
/// let line = Bezier::new([[0.0_f64], [2.0]])?;
/// let trajectory = Along::new(&line, &Ramp);
/// let path: Path<f64, 1, 4> = compile(&trajectory, 1_000.0, &CompileOptions::new())?;
/// let header = &*path; // the `PathHeader` of the path
/// assert_eq!((header.ticks(), header.rate()), (100, 1_000.0));
/// assert_eq!(path.end_position(), [2.0]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct PathHeader<N: Number, const A: usize> {
    pub(crate) ticks: u32,
    pub(crate) meta: PathMeta,
    pub(crate) end: PathEnd<N::Out, A>,
    /// The end sample as a piece state without motion, for the sampler's piece switch: the
    /// end's position, velocity and acceleration, every difference zero. Derived from `end`.
    pub(crate) end_state: [AxisState<N>; A],
    pub(crate) ramp: FeedRampLimits<N>,
    pub(crate) playback_bound: f64,
}

impl<N: Number, const A: usize> PathHeader<N, A> {
    /// The header of a path without pieces: no ticks, at rest at the origin.
    pub(crate) const EMPTY: Self = PathHeader {
        ticks: 0,
        meta: PathMeta {
            plan_duration: 0.0,
            tolerance: 0.0,
            ramp: RampBasis {
                rate: RATE_RANGE.0,
                peak_velocity: 0.0,
                peak_acceleration: 0.0,
                peak_jerk: 0.0,
                acceleration_limit: 0.0,
                jerk_limit: 0.0,
                feed_share: 0.0,
            },
        },
        end: PathEnd {
            position: [<N::Out as Scalar>::ZERO; A],
            velocity: [<N::Out as Scalar>::ZERO; A],
            acceleration: [<N::Out as Scalar>::ZERO; A],
        },
        end_state: [AxisState::ZERO; A],
        ramp: FeedRampLimits {
            alpha: N::ZERO,
            k_max: 1,
            rate: N::ZERO,
            snap: N::ZERO,
        },
        playback_bound: 0.0,
    };

    /// The number of ticks `N`: samples are at ticks `0 ..= N`, the last one is the end point.
    pub fn ticks(&self) -> u32 {
        self.ticks
    }

    /// The control rate in Hz.
    pub fn rate(&self) -> f64 {
        self.meta.ramp.rate
    }

    /// The tick period `T = 1/rate` in seconds.
    pub fn period(&self) -> f64 {
        1.0 / self.meta.ramp.rate
    }

    /// The duration of the compiled motion, `ticks · T` seconds.
    pub fn duration(&self) -> f64 {
        f64::from(self.ticks) / self.meta.ramp.rate
    }

    /// The duration of the time law the path was compiled from (≤ [`duration`](Self::duration)).
    pub fn plan_duration(&self) -> f64 {
        self.meta.plan_duration
    }

    /// The time stretch `plan_duration / duration` (≤ 1 up to a relative 10⁻¹²): path time
    /// `t` is time `t · time_scale` of the time law, velocities are scaled by it.
    pub fn time_scale(&self) -> f64 {
        self.meta.plan_duration / self.duration()
    }

    /// The time of the time law at (possibly fractional) tick `k`: `k · plan_duration / ticks`
    /// (the mapping the compiler used).
    pub fn plan_time(&self, tick: f64) -> f64 {
        tick * (self.meta.plan_duration / f64::from(self.ticks))
    }

    /// The position tolerance the spline was fitted to, in units.
    pub fn tolerance(&self) -> f64 {
        self.meta.tolerance
    }

    /// A bound on the error that playback in the number format adds to the compiled
    /// polynomial's position, at feed 1 (rounding of the stored states, propagated by
    /// forward differencing; float additions; conversion to the sample type). See
    /// [`Number`].
    pub fn playback_bound(&self) -> f64 {
        self.playback_bound
    }

    /// The exact end point, as the curve computed it, converted once into the sample type.
    pub fn end_position(&self) -> [N::Out; A] {
        self.end.position
    }

    /// The velocity at the end (zero for rest-to-rest time laws; the time law's end
    /// velocity otherwise).
    pub fn end_velocity(&self) -> [N::Out; A] {
        self.end.velocity
    }

    /// The acceleration at the end (the compiled spline's end value).
    pub fn end_acceleration(&self) -> [N::Out; A] {
        self.end.acceleration
    }

    /// An upper bound of the speed `|ẋ|` (Euclidean norm over the axes) along the path.
    pub fn peak_velocity(&self) -> f64 {
        self.meta.ramp.peak_velocity
    }

    /// The largest acceleration `|ẍ|` along the path.
    pub fn peak_acceleration(&self) -> f64 {
        self.meta.ramp.peak_acceleration
    }

    /// The largest jerk `|x⃛|` along the path.
    pub fn peak_jerk(&self) -> f64 {
        self.meta.ramp.peak_jerk
    }

    /// The acceleration limit feed changes respect: [`peak_acceleration`](Self::peak_acceleration)
    /// plus what a feed ramp may add (from the limits given or derived, each axis's free
    /// part included; see [`CompileOptions`](crate::CompileOptions)).
    pub fn acceleration_limit(&self) -> f64 {
        self.meta.ramp.acceleration_limit
    }

    /// The jerk limit of feed changes: [`peak_jerk`](Self::peak_jerk) plus what a feed
    /// ramp may add.
    pub fn jerk_limit(&self) -> f64 {
        self.meta.ramp.jerk_limit
    }

    /// The share of the limits reserved for feed changes (at most what the ramps may add,
    /// relative to [`acceleration_limit`](Self::acceleration_limit) and
    /// [`jerk_limit`](Self::jerk_limit)); 0 for a path planned at the full limits, whose
    /// feed changes need a [`FeedGuard`](crate::FeedGuard).
    pub fn feed_share(&self) -> f64 {
        self.meta.ramp.feed_share
    }

    /// The end as a sample in `f64` (at tick `⌊tick⌋`).
    pub(crate) fn end_sample(&self, tick: u64) -> Sample<f64, A> {
        Sample {
            tick,
            position: self.end.position.map(Scalar::to_f64),
            velocity: self.end.velocity.map(Scalar::to_f64),
            acceleration: self.end.acceleration.map(Scalar::to_f64),
        }
    }
}

/// Checks a path piece by piece, the same way for a freshly compiled path and a loaded blob,
/// and completes its header in place: [`begin`](Self::begin) with the header's description
/// and end already written, [`piece`](Self::piece) (or [`piece_start`](Self::piece_start)
/// and [`axis`](Self::axis) for each axis) for every piece in order, [`finish`](Self::finish)
/// with the last piece. Nothing larger than one axis state is passed by value.
pub(crate) struct Validator<'h, N: Number, const A: usize> {
    header: &'h mut PathHeader<N, A>,
    /// `φ̇ = ω·f` never exceeds this; the acceleration output adds `φ̇·v`.
    phi_dot_max: f64,
    next_start: u32,
    playback_bound: f64,
}

impl<'h, N: Number, const A: usize> Validator<'h, N, A> {
    /// Checks the header's description (`meta`) and writes the feed-ramp constants into it.
    ///
    /// # Errors
    /// [`Error::InvalidRate`] for a rate outside 100 Hz ..= 100 kHz; [`Error::InvalidLimit`]
    /// for bad kinematic data; [`Error::OutOfRange`] when the ramp constants do not fit `N`.
    pub(crate) fn begin(header: &'h mut PathHeader<N, A>) -> Result<Self, Error> {
        let meta = &header.meta;
        if !(meta.ramp.rate >= RATE_RANGE.0 && meta.ramp.rate <= RATE_RANGE.1) {
            return Err(Error::InvalidRate);
        }
        let nonneg = |x: f64| x.is_finite() && x >= 0.0;
        if !(positive(meta.plan_duration)
            && positive(meta.tolerance)
            && nonneg(meta.ramp.peak_velocity)
            && nonneg(meta.ramp.peak_acceleration)
            && nonneg(meta.ramp.peak_jerk)
            && positive(meta.ramp.acceleration_limit)
            && positive(meta.ramp.jerk_limit)
            && nonneg(meta.ramp.feed_share)
            && meta.ramp.feed_share <= 1.0)
        {
            return Err(Error::InvalidLimit);
        }
        let (omega, alpha) = feed_ramp_f64(&meta.ramp);
        let ramp = FeedRampLimits::from_rates(omega, alpha, meta.ramp.rate)?;
        let phi_dot_max = ramp.phi_dot_max(meta.ramp.rate);
        header.ramp = ramp;
        Ok(Validator {
            header,
            phi_dot_max,
            next_start: 0,
            playback_bound: 0.0,
        })
    }

    /// The tick the next piece must start at.
    pub(crate) fn next_start(&self) -> u32 {
        self.next_start
    }

    /// Checks the next piece: its start and length, and for each axis what
    /// [`axis`](Self::axis) checks.
    ///
    /// # Errors
    /// As [`piece_start`](Self::piece_start) and [`axis`](Self::axis).
    pub(crate) fn piece(
        &mut self,
        start: u32,
        ticks: u32,
        axes: &[AxisState<N>; A],
    ) -> Result<(), Error> {
        self.piece_start(start, ticks)?;
        axes.iter().try_for_each(|axis| self.axis(ticks, axis))
    }

    /// Checks that the next piece starts where the last one ended and has ticks.
    ///
    /// # Errors
    /// [`Error::CorruptBlob`] for a piece that does not follow on or has no ticks.
    pub(crate) fn piece_start(&mut self, start: u32, ticks: u32) -> Result<(), Error> {
        if start != self.next_start || ticks == 0 {
            return Err(Error::CorruptBlob);
        }
        self.next_start = start.checked_add(ticks).ok_or(Error::CorruptBlob)?;
        Ok(())
    }

    /// Checks one axis of the current piece of `ticks` ticks: finite values, and the range
    /// of every value and partial sum playback forms.
    ///
    /// # Errors
    /// [`Error::CorruptBlob`] for a non-finite value; [`Error::OutOfRange`] when a value
    /// could exceed [`Number::LIMIT`].
    pub(crate) fn axis(&mut self, ticks: u32, axis: &AxisState<N>) -> Result<(), Error> {
        if !axis.values().iter().all(|v| v.is_finite()) {
            return Err(Error::CorruptBlob);
        }
        let b = piece_bounds(axis, ticks);
        // Margin: the accumulated rounding error on top of the exact values.
        let margin = 2.0 * b.playback_error;
        let fits = |x: f64| x.is_finite() && x * (1.0 + 1e-9) + margin <= N::LIMIT;
        if !(fits(b.position_sum)
            && fits(b.velocity_sum)
            && fits(b.acceleration_sum + self.phi_dot_max * b.velocity_sum))
        {
            return Err(Error::OutOfRange);
        }
        self.playback_bound = self.playback_bound.max(b.playback_error);
        Ok(())
    }

    /// Checks the header's end (finite, in range, exactly representable by the
    /// accumulator, and continuing the last piece within the path's bounds) and completes
    /// the header: tick count, end state, playback bound. `last` is the last piece's
    /// length and the state of its axis `a` for each `a`.
    ///
    /// # Errors
    /// [`Error::EmptyPath`] without pieces; [`Error::CorruptBlob`] for a non-finite end or
    /// one that does not continue the last piece; [`Error::OutOfRange`] for an end outside
    /// the format's range.
    pub(crate) fn finish(
        self,
        last: Option<(u32, impl Fn(usize) -> AxisState<N>)>,
    ) -> Result<(), Error> {
        let Some((ticks, last)) = last else {
            return Err(Error::EmptyPath);
        };
        let end = &self.header.end;
        let values = || {
            end.position
                .iter()
                .chain(&end.velocity)
                .chain(&end.acceleration)
        };
        if !values().all(|x| Scalar::is_finite(*x)) {
            return Err(Error::CorruptBlob);
        }
        if !values().all(|x| x.to_f64().abs() <= N::LIMIT) {
            return Err(Error::OutOfRange);
        }
        for a in 0..A {
            check_continuation(&self.header.meta, end, a, ticks, &last(a))?;
        }
        write_end_state(self.header)?;
        self.header.ticks = self.next_start;
        self.header.playback_bound = self.playback_bound;
        Ok(())
    }
}

/// The relative slack with which a path's end must continue its last piece, beyond the
/// tolerance and the rounding bounds of the stored states: the f64 rounding of the fit's
/// coefficients (a linear solve) and of the Newton sums that evaluate the piece at its end,
/// relative to the sums' terms (and, for the velocity, to the path's peak speed). Such
/// rounding has been seen up to about 50 ε; this allows about 4 500 ε. A loaded blob whose
/// end differs from its last piece's end by more is [`Error::CorruptBlob`].
///
/// ```
/// assert!(strak_trajectory::END_AGREEMENT_SLACK > 1_000.0 * f64::EPSILON);
/// ```
pub const END_AGREEMENT_SLACK: f64 = 1e-12;

/// Axis `a` of the end continues the last piece (`state`, `ticks` long): its position,
/// velocity and acceleration at the piece's last tick, evaluated in `f64` from the stored
/// state (Newton's formula), agree with the end within the rounding the stored values carry
/// (the bound of [`piece_bounds`] for each chain, doubled) plus, for the position, the fit's
/// tolerance once, plus [`END_AGREEMENT_SLACK`] times `1 + m`, `m` the largest of the two
/// values, the sum of the terms' magnitudes and, for the velocity, the path's peak speed.
fn check_continuation<N: Number, const A: usize>(
    meta: &PathMeta,
    end: &PathEnd<N::Out, A>,
    a: usize,
    ticks: u32,
    state: &AxisState<N>,
) -> Result<(), Error> {
    let n = f64::from(ticks);
    let r = N::rounding_error;
    let s = state.to_f64();
    let c = Newton::at(n);
    let position = chain_at([s.position, s.delta1, s.delta2, s.delta3], &c);
    let velocity = chain_at([s.velocity, s.velocity_delta1, s.velocity_delta2, 0.0], &c);
    let acceleration = chain_at([s.acceleration, s.acceleration_delta, 0.0, 0.0], &c);
    let b = piece_bounds(state, ticks);
    let (Some(x), Some(v), Some(acc)) = (
        end.position.get(a),
        end.velocity.get(a),
        end.acceleration.get(a),
    ) else {
        return Err(Error::CorruptBlob);
    };
    let slack = |m: f64| END_AGREEMENT_SLACK * (1.0 + m);
    let v_bound = r(s.velocity.abs())
        + n * r(s.velocity_delta1.abs())
        + binomial(n, 2) * r(s.velocity_delta2.abs())
        + N::OUT_ERROR;
    let a_bound = r(s.acceleration.abs()) + n * r(s.acceleration_delta.abs()) + N::OUT_ERROR;
    // `scale`: the path's peak speed for the velocity (the law's end velocity of one axis
    // is the speed times a direction, rounded relative to the speed); the end acceleration
    // is the last piece's own.
    let near = |(got, terms): (f64, f64), want: f64, bound: f64, scale: f64| {
        let m = got.abs().max(want.abs()).max(terms).max(scale);
        (got - want).abs() <= 2.0 * bound + slack(m)
    };
    let tolerance = b.playback_error + 0.5 * meta.tolerance;
    if near(position, x.to_f64(), tolerance, 0.0)
        && near(velocity, v.to_f64(), v_bound, meta.ramp.peak_velocity)
        && near(acceleration, acc.to_f64(), a_bound, 0.0)
    {
        Ok(())
    } else {
        Err(Error::CorruptBlob)
    }
}

/// One chain (`x, Δ¹, Δ², Δ³`) at the offset of `c` by Newton's forward formula, and the
/// same sum of the terms' magnitudes: the f64 rounding of the sum is relative to that,
/// which can be far above a sum near zero.
fn chain_at(x: [f64; 4], c: &Newton<f64>) -> (f64, f64) {
    let sum = |y: [f64; 4]| y[0] + c.c1 * y[1] + c.c2 * y[2] + c.c3 * y[3];
    (sum(x), sum(x.map(f64::abs)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::Q40;
    #[test]
    fn q40_error_bound_formula() {
        // n = 256, dyadic values (exact in Q40): ½ulp·(1 + n + C(n,2) + C(n,3)) + output rounding
        let q = |v: f64| Q40::from_f64(v).unwrap();
        let (f, d1, d2, d3) = (1.0, 2f64.powi(-10), 2f64.powi(-20), 2f64.powi(-30));
        let s = AxisState {
            position: q(f),
            delta1: q(d1),
            delta2: q(d2),
            delta3: q(d3),
            ..AxisState::default()
        };
        let b = piece_bounds(&s, 256);
        let want =
            0.5 / (1u64 << 40) as f64 * (1.0 + 256.0 + 32_640.0 + 2_763_520.0) + Q40::OUT_ERROR;
        assert!((b.playback_error - want).abs() < 1e-20);
        assert!(b.playback_error < 1.3e-6);
        let (n, c2, c3) = (256.0, 32_640.0, 2_763_520.0);
        let mf = f + n * d1 + c2 * d2 + c3 * d3;
        let m1 = d1 + n * d2 + c2 * d3;
        let m2 = d2 + n * d3;
        assert_eq!(b.position_sum, mf + m1 + m2 + d3);
    }

    #[test]
    fn feed_ramp_constants() {
        let ramp = RampBasis {
            rate: 1000.0,
            peak_velocity: 100.0,
            peak_acceleration: 600.0,
            peak_jerk: 1000.0,
            acceleration_limit: 1000.0,
            jerk_limit: 10_000.0,
            feed_share: 0.25,
        };
        let (omega, alpha) = feed_ramp_f64(&ramp);
        let (f, v) = (ramp.rate, ramp.peak_velocity);
        // a_ramp = max(400, 250) = 400, R = j_ramp = max(9000, 2500) = 9000, c = 3·600/100:
        // the split √v·R/(√R + c·√v) = 327.4 < a_ramp
        let (r, c) = (9000.0, 18.0);
        let split = 10.0 * r / (r.sqrt() + c * 10.0);
        assert!(split < 400.0);
        assert!((omega * v * f - split).abs() < 1e-9);
        // the jerk terms 3·φ̇·a_peak + φ̈·v_peak use exactly R
        let jerk = 3.0 * omega * f * ramp.peak_acceleration + alpha * f * f * v;
        assert!((jerk - r).abs() < 1e-9, "{jerk}");
        // and the split is the fastest ramp over 1: 1/φ̇ + φ̇/φ̈ is least there
        let time = |a: f64| v / a + a / (r - c * a);
        assert!(time(split) < time(split * 1.01) && time(split) < time(split * 0.99));
        // without acceleration at the peak (c = 0): ω = min(a_ramp/(v f), √α), α = R/(v f²)
        let flat = RampBasis {
            peak_acceleration: 0.0,
            ..ramp
        };
        let (omega, alpha) = feed_ramp_f64(&flat);
        assert!((alpha - 9e-5).abs() < 1e-18);
        assert!((omega - 9e-5_f64.sqrt()).abs() < 1e-15);
        // a small jerk budget: ω is capped by √α
        let tight = RampBasis {
            jerk_limit: 1.0,
            peak_jerk: 0.0,
            peak_acceleration: 0.0,
            ..ramp
        };
        let (omega, alpha) = feed_ramp_f64(&tight);
        assert!((alpha - 1e-8).abs() < 1e-22);
        assert!((omega - 1e-4).abs() < 1e-15);
    }
}
