//! The compiled path: polynomial pieces in control ticks, stored as forward-difference states.

use heapless::Vec;
use strak_curves::Scalar;

use crate::error::Error;
use crate::number::Number;
use crate::sampler::Sample;

/// The forward-difference state of one axis at one tick. Position differences are per tick,
/// velocity in units/s, acceleration in units/s².
///
/// A path of `N` ticks at rate `f` (tick period `T = 1/f`) is a sequence of pieces with
/// boundaries on the tick grid. Piece `j` covers the ticks `k_j ..= k_{j+1}` (`n_j ≥ 1` ticks
/// long) and is, per axis, the cubic `p(i) = a + b·i + c·i² + d·i³` in the local tick index
/// `i`. It is stored as the forward-difference state at `i = 0` (DESIGN.md, "Compile, then
/// play"):
///
/// | value                                    | formula            | unit            |
/// |------------------------------------------|--------------------|-----------------|
/// | [`position`](AxisState::position)        | `a`                | units           |
/// | [`delta1`](AxisState::delta1)            | `b + c + d`        | units / tick    |
/// | [`delta2`](AxisState::delta2)            | `2c + 6d`          | units / tick²   |
/// | [`delta3`](AxisState::delta3)            | `6d`               | units / tick³   |
/// | [`velocity`](AxisState::velocity)        | `b / T`            | units / s       |
/// | [`velocity_delta1`](AxisState::velocity_delta1) | `(2c + 3d) / T` | units / s / tick |
/// | [`velocity_delta2`](AxisState::velocity_delta2) | `6d / T`     | units / s / tick² |
/// | [`acceleration`](AxisState::acceleration)| `2c / T²`          | units / s²      |
/// | [`acceleration_delta`](AxisState::acceleration_delta) | `6d / T²` | units / s² / tick |
///
/// One tick ([`AxisState::step`]) is six additions per axis; a piece switch is a load of the
/// next piece's state, so rounding errors never carry from one piece into the next.
///
/// ```
/// use strak_trajectory::AxisState;
/// // p(i) = i³: a = b = c = 0, d = 1, at T = 1 s
/// let mut s = AxisState { position: 0.0_f64, delta1: 1.0, delta2: 6.0, delta3: 6.0,
///     velocity: 0.0, velocity_delta1: 3.0, velocity_delta2: 6.0,
///     acceleration: 0.0, acceleration_delta: 6.0 };
/// s.step();
/// s.step();
/// assert_eq!((s.position, s.velocity, s.acceleration), (8.0, 12.0, 12.0)); // i³, 3i², 6i at 2
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[repr(C)] // nine consecutive values: the Cortex-M tick kernels load an axis in one instruction
pub struct AxisState<N> {
    /// Position `p(i)`.
    pub position: N,
    /// First forward difference `p(i+1) − p(i)`.
    pub delta1: N,
    /// Second forward difference.
    pub delta2: N,
    /// Third forward difference (constant over a piece).
    pub delta3: N,
    /// Velocity `p'(i)/T`.
    pub velocity: N,
    /// First forward difference of the velocity.
    pub velocity_delta1: N,
    /// Second forward difference of the velocity (constant over a piece).
    pub velocity_delta2: N,
    /// Acceleration `p''(i)/T²`.
    pub acceleration: N,
    /// Forward difference of the acceleration (constant over a piece).
    pub acceleration_delta: N,
}

/// The coefficients of Newton's forward-difference formula at a fractional offset `θ`:
/// `p(i + θ) = p(i) + θ·Δ¹ + C(θ,2)·Δ² + C(θ,3)·Δ³`, with the binomial coefficients
/// `C(θ,2) = θ(θ−1)/2` and `C(θ,3) = θ(θ−1)(θ−2)/6`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Newton<N> {
    pub(crate) c1: N,
    pub(crate) c2: N,
    pub(crate) c3: N,
}

impl<N: Number> Newton<N> {
    /// The coefficients at `θ` (4 multiplications).
    #[inline]
    pub(crate) fn at(theta: N) -> Self {
        let c2 = theta * (theta - N::ONE) * N::HALF;
        let c3 = c2 * (theta - N::ONE - N::ONE) * N::THIRD;
        Newton { c1: theta, c2, c3 }
    }
}

impl<N: Number> AxisState<N> {
    /// Advances the state by one tick: `f += Δ¹; Δ¹ += Δ²; Δ² += Δ³; v += Δv¹; Δv¹ += Δv²;
    /// a += Δa` (six additions, exact in fixed-point).
    ///
    /// ```
    /// use strak_trajectory::{AxisState, Number, Q40};
    /// let q = |x: f64| Q40::from_f64(x).unwrap();
    /// // p(i) = 1 + i²/2 (T = 1 s): Δ¹ = ½, Δ² = 1
    /// let mut s = AxisState { position: q(1.0), delta1: q(0.5), delta2: q(1.0),
    ///     velocity_delta1: q(1.0), acceleration: q(1.0), ..AxisState::default() };
    /// for _ in 0..4 { s.step(); }
    /// assert_eq!(s.position, q(9.0));
    /// assert_eq!(s.velocity, q(4.0));
    /// ```
    #[inline]
    pub fn step(&mut self) {
        self.position = self.position + self.delta1;
        self.delta1 = self.delta1 + self.delta2;
        self.delta2 = self.delta2 + self.delta3;
        self.velocity = self.velocity + self.velocity_delta1;
        self.velocity_delta1 = self.velocity_delta1 + self.velocity_delta2;
        self.acceleration = self.acceleration + self.acceleration_delta;
    }

    /// The state at the fractional offset `θ` (Newton's forward-difference formula applied
    /// to every value; the constant differences are unchanged). 10 multiplications.
    #[inline]
    pub(crate) fn shifted(&self, c: &Newton<N>) -> Self {
        AxisState {
            position: self.position + c.c1 * self.delta1 + c.c2 * self.delta2 + c.c3 * self.delta3,
            delta1: self.delta1 + c.c1 * self.delta2 + c.c2 * self.delta3,
            delta2: self.delta2 + c.c1 * self.delta3,
            delta3: self.delta3,
            velocity: self.velocity + c.c1 * self.velocity_delta1 + c.c2 * self.velocity_delta2,
            velocity_delta1: self.velocity_delta1 + c.c1 * self.velocity_delta2,
            velocity_delta2: self.velocity_delta2,
            acceleration: self.acceleration + c.c1 * self.acceleration_delta,
            acceleration_delta: self.acceleration_delta,
        }
    }

    /// The state with every value converted to `f64`.
    fn to_f64(self) -> AxisState<f64> {
        AxisState {
            position: self.position.to_f64(),
            delta1: self.delta1.to_f64(),
            delta2: self.delta2.to_f64(),
            delta3: self.delta3.to_f64(),
            velocity: self.velocity.to_f64(),
            velocity_delta1: self.velocity_delta1.to_f64(),
            velocity_delta2: self.velocity_delta2.to_f64(),
            acceleration: self.acceleration.to_f64(),
            acceleration_delta: self.acceleration_delta.to_f64(),
        }
    }

    /// The nine values in storage order (the order of serialized paths).
    pub(crate) fn values(&self) -> [N; 9] {
        [
            self.position,
            self.delta1,
            self.delta2,
            self.delta3,
            self.velocity,
            self.velocity_delta1,
            self.velocity_delta2,
            self.acceleration,
            self.acceleration_delta,
        ]
    }

    /// The state from the nine values in storage order.
    pub(crate) fn from_values(v: [N; 9]) -> Self {
        let [
            position,
            delta1,
            delta2,
            delta3,
            velocity,
            velocity_delta1,
            velocity_delta2,
            acceleration,
            acceleration_delta,
        ] = v;
        AxisState {
            position,
            delta1,
            delta2,
            delta3,
            velocity,
            velocity_delta1,
            velocity_delta2,
            acceleration,
            acceleration_delta,
        }
    }
}

/// One piece of a path: its first tick, its length in ticks and the forward-difference
/// start state of each axis.
///
/// ```
/// use strak_trajectory::{compile, CompileOptions, Path, Timing};
/// use strak_curves::Bezier;
/// struct Ramp;
/// impl Timing for Ramp {
///     fn duration(&self) -> f64 { 0.1 }
///     fn param(&self, t: f64) -> (f64, f64) { (t.clamp(0.0, 0.1) * 10.0, 10.0) }
/// }
/// let line = Bezier::new([[0.0_f64], [2.0]])?;
/// let path: Path<f64, 1, 4> = compile(&line, &Ramp, 1_000.0, &CompileOptions::default())?;
/// let piece = &path.pieces()[0];
/// assert_eq!((piece.start(), piece.ticks()), (0, 100)); // one piece, 100 ticks
/// assert_eq!(piece.axes()[0].position, 0.0);
/// assert!((piece.axes()[0].velocity - 20.0).abs() < 1e-9); // 2 units in 0.1 s
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Piece<N, const A: usize> {
    pub(crate) start: u32,
    pub(crate) ticks: u32,
    pub(crate) axes: [AxisState<N>; A],
}

impl<N: Number, const A: usize> Piece<N, A> {
    /// The tick at which the piece starts.
    pub fn start(&self) -> u32 {
        self.start
    }

    /// The length in ticks (≥ 1).
    pub fn ticks(&self) -> u32 {
        self.ticks
    }

    /// The forward-difference start state of each axis.
    pub fn axes(&self) -> &[AxisState<N>; A] {
        &self.axes
    }
}

/// Where a path ends: the exact end point (as the curve computes it, converted once) and
/// the end velocity and acceleration, in the sample type.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PathEnd<T, const A: usize> {
    pub(crate) position: [T; A],
    pub(crate) velocity: [T; A],
    pub(crate) acceleration: [T; A],
}

/// The scalar description of a path (all `f64`): rate, timing, tolerance and the kinematic
/// peaks and limits the feed ramps are derived from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PathMeta {
    pub(crate) rate: f64,
    pub(crate) plan_duration: f64,
    pub(crate) tolerance: f64,
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

/// The smallest change of the feed rate per tick: 2⁻⁴⁰ (one `Q40` ulp).
const MIN_ALPHA: f64 = 1.0 / (1_u64 << 40) as f64;

/// The lowest and highest control rates in Hz.
pub(crate) const RATE_RANGE: (f64, f64) = (100.0, 100_000.0);

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
struct PieceBounds {
    /// Bound on the magnitude of every position-related value and partial sum.
    position_sum: f64,
    /// Bound on every velocity-related value and partial sum.
    velocity_sum: f64,
    /// Bound on every acceleration-related value and partial sum (before the `φ̇·v` term).
    acceleration_sum: f64,
    /// Bound on the playback error of the position at any tick of the piece.
    playback_error: f64,
}

fn piece_bounds<N: Number>(state: &AxisState<N>, ticks: u32) -> PieceBounds {
    let s = state.to_f64();
    let n = f64::from(ticks);
    let (c1, c2, c3) = (
        binomial_bound(n, 1),
        binomial_bound(n, 2),
        binomial_bound(n, 3),
    );
    let m3 = s.delta3.abs();
    let m2 = s.delta2.abs() + c1 * m3;
    let m1 = s.delta1.abs() + c1 * s.delta2.abs() + c2 * m3;
    let mf = s.position.abs() + c1 * s.delta1.abs() + c2 * s.delta2.abs() + c3 * m3;
    let v2 = s.velocity_delta2.abs();
    let v1 = s.velocity_delta1.abs() + c1 * v2;
    let v0 = s.velocity.abs() + c1 * s.velocity_delta1.abs() + c2 * v2;
    let a1 = s.acceleration_delta.abs();
    let a0 = s.acceleration.abs() + c1 * a1;
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

/// The feed-ramp constants (per tick) from the path's kinematic description.
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
/// `2⁻⁴⁰ ≤ α ≤ ¼` (the same resolution in every format), `ω_max ≤ min(½, √α)`.
pub(crate) fn feed_ramp_f64(meta: &PathMeta) -> (f64, f64) {
    let a_ramp = (meta.acceleration_limit - meta.peak_acceleration)
        .max(meta.feed_share * meta.acceleration_limit);
    let j_ramp = (meta.jerk_limit - meta.peak_jerk).max(meta.feed_share * meta.jerk_limit);
    let (omega, alpha) = if meta.peak_velocity > 0.0 {
        let v = meta.peak_velocity;
        let c = 3.0 * meta.peak_acceleration / v;
        let (sv, sr) = (libm::sqrt(v), libm::sqrt(j_ramp));
        let a = a_ramp.min(sv * j_ramp / (sr + c * sv));
        (
            a / (v * meta.rate),
            (j_ramp - c * a) / (v * meta.rate * meta.rate),
        )
    } else {
        (0.5, 0.25)
    };
    let alpha = alpha.clamp(MIN_ALPHA, 0.25);
    let omega = omega.min(0.5).min(libm::sqrt(alpha));
    (omega, alpha)
}

/// A compiled path with `A` axes and room for `P` pieces, played back in the number format
/// `N` (see [`Number`]): what [`compile`](crate::compile) produces, [`Sampler`](crate::Sampler)
/// plays and [`Path::to_bytes`] / [`Path::from_bytes`] serialize.
///
/// Tick `k` of the path is at time `k·T` (`T = 1/rate`), `k = 0 ..= ticks()`. The time law
/// was stretched by [`time_scale`](Path::time_scale) ≤ 1 so that the motion ends exactly on
/// tick [`ticks()`](Path::ticks): path time `t` corresponds to time `t · time_scale` of the
/// [`Timing`](crate::Timing).
///
/// # Accuracy
/// At every tick the position of the compiled spline is within
/// [`tolerance()`](Path::tolerance) of the exact `c(u(t))` (the compiler checks the quarter
/// points of every piece against half the tolerance; tests check every tick), and playback in
/// the number format adds at most [`playback_bound()`](Path::playback_bound).
///
/// # Range
/// Every path was checked, in `f64`, to keep every value and partial sum playback forms
/// (forward differencing, Newton evaluation at a fractional tick, feed scaling) within
/// [`Number::LIMIT`]; [`Error::OutOfRange`] otherwise.
///
/// ```
/// use strak_trajectory::{compile, CompileOptions, Path, Q40, Timing};
/// use strak_curves::Bezier;
/// struct Ramp;
/// impl Timing for Ramp {
///     fn duration(&self) -> f64 { 0.5 }
///     fn param(&self, t: f64) -> (f64, f64) { (t.clamp(0.0, 0.5) * 2.0, 2.0) }
/// }
/// let curve = Bezier::new([[0.0_f64, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]])?;
/// let path: Path<Q40, 2, 16> = compile(&curve, &Ramp, 1_000.0, &CompileOptions::default())?;
/// assert_eq!(path.ticks(), 500);
/// assert_eq!(path.end_position()[0].to_num::<f64>(), 4.0);
/// let mid = path.eval(250.0); // the compiled polynomial, in f64
/// assert!((mid.position[0] - 2.0).abs() < 1e-3 && (mid.position[1] - 1.5).abs() < 1e-3);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Path<N: Number, const A: usize, const P: usize> {
    pub(crate) pieces: Vec<Piece<N, A>, P>,
    pub(crate) ticks: u32,
    pub(crate) meta: PathMeta,
    pub(crate) end: PathEnd<N::Out, A>,
    /// The end as two pieces without motion, for the sampler's fast path: `[0]` the end
    /// sample (the end's position, velocity and acceleration, zero differences), `[1]` the
    /// standstill after it (the end position, everything else zero). Derived from `end`.
    pub(crate) end_states: [[AxisState<N>; A]; 2],
    pub(crate) ramp: FeedRampLimits<N>,
    pub(crate) playback_bound: f64,
}

/// [`Path::end_states`] from the end's sample values.
///
/// # Errors
/// [`Error::OutOfRange`] when a sample value has no exact accumulator value.
#[allow(clippy::type_complexity)]
fn end_states<N: Number, const A: usize>(
    end: &PathEnd<N::Out, A>,
) -> Result<[[AxisState<N>; A]; 2], Error> {
    let exact = |v: N::Out| {
        let n = N::from_out(v);
        if n.to_out() == v {
            Ok(n)
        } else {
            Err(Error::OutOfRange)
        }
    };
    let mut sample = [AxisState::default(); A];
    let mut rest = [AxisState::default(); A];
    for (a, (e, r)) in sample.iter_mut().zip(rest.iter_mut()).enumerate() {
        if let (Some(&x), Some(&v), Some(&acc)) = (
            end.position.get(a),
            end.velocity.get(a),
            end.acceleration.get(a),
        ) {
            e.position = exact(x)?;
            e.velocity = exact(v)?;
            e.acceleration = exact(acc)?;
            r.position = e.position;
        }
    }
    Ok([sample, rest])
}

fn positive(x: f64) -> bool {
    x.is_finite() && x > 0.0
}

impl<N: Number, const A: usize, const P: usize> Path<N, A, P> {
    /// Checks the parts, derives the feed-ramp constants and the playback bound, and checks
    /// the range of every value playback forms.
    ///
    /// # Errors
    /// [`Error::InvalidRate`] for a rate outside 100 Hz ..= 100 kHz; [`Error::CorruptBlob`]
    /// for inconsistent pieces (only reachable from [`Path::from_bytes`]) or a non-finite
    /// value; [`Error::InvalidLimit`] for bad kinematic data; [`Error::OutOfRange`] when a
    /// value playback forms could exceed [`Number::LIMIT`].
    pub(crate) fn from_parts(
        pieces: Vec<Piece<N, A>, P>,
        meta: PathMeta,
        end: PathEnd<N::Out, A>,
    ) -> Result<Self, Error> {
        if !(meta.rate >= RATE_RANGE.0 && meta.rate <= RATE_RANGE.1) {
            return Err(Error::InvalidRate);
        }
        let nonneg = |x: f64| x.is_finite() && x >= 0.0;
        if !(positive(meta.plan_duration)
            && positive(meta.tolerance)
            && nonneg(meta.peak_velocity)
            && nonneg(meta.peak_acceleration)
            && nonneg(meta.peak_jerk)
            && positive(meta.acceleration_limit)
            && positive(meta.jerk_limit)
            && positive(meta.feed_share)
            && meta.feed_share <= 1.0)
        {
            return Err(Error::InvalidLimit);
        }
        let finite_out = |v: &[N::Out; A]| v.iter().all(|x| Scalar::is_finite(*x));
        if !(finite_out(&end.position)
            && finite_out(&end.velocity)
            && finite_out(&end.acceleration))
        {
            return Err(Error::CorruptBlob);
        }
        let (omega, alpha) = feed_ramp_f64(&meta);
        let alpha = N::from_f64(alpha).ok_or(Error::OutOfRange)?;
        // ω_max a whole multiple of α, so that ω stays one and the ramp's braking distance is
        // exact: at most 2²⁰ steps, as ω_max ≤ √α and α ≥ 2⁻⁴⁰.
        #[allow(clippy::cast_possible_truncation)]
        let k_max = libm::floor(omega / alpha.to_f64()).clamp(1.0, f64::from(1_u32 << 20)) as i64;
        let ramp = FeedRampLimits {
            alpha,
            k_max,
            rate: N::from_f64(meta.rate).ok_or(Error::OutOfRange)?,
            snap: if alpha > N::EPSILON {
                alpha
            } else {
                N::EPSILON
            },
        };
        // φ̇ = ω·f never exceeds this; the acceleration output adds φ̇·v.
        let phi_dot_max = ramp.alpha.to_f64() * (ramp.k_max as f64) * meta.rate;
        let mut next_start = 0_u32;
        let mut playback_bound = 0.0_f64;
        for piece in &pieces {
            if piece.start != next_start || piece.ticks == 0 {
                return Err(Error::CorruptBlob);
            }
            next_start = next_start
                .checked_add(piece.ticks)
                .ok_or(Error::CorruptBlob)?;
            for axis in &piece.axes {
                if !axis.values().iter().all(|v| v.is_finite()) {
                    return Err(Error::CorruptBlob);
                }
                let b = piece_bounds(axis, piece.ticks);
                // Margin: the accumulated rounding error on top of the exact values.
                let margin = 2.0 * b.playback_error;
                let fits = |x: f64| x.is_finite() && x * (1.0 + 1e-9) + margin <= N::LIMIT;
                if !(fits(b.position_sum)
                    && fits(b.velocity_sum)
                    && fits(b.acceleration_sum + phi_dot_max * b.velocity_sum))
                {
                    return Err(Error::OutOfRange);
                }
                playback_bound = playback_bound.max(b.playback_error);
            }
        }
        if pieces.is_empty() {
            return Err(Error::EmptyPath);
        }
        let end_states = end_states(&end)?;
        Ok(Path {
            pieces,
            ticks: next_start,
            meta,
            end,
            end_states,
            ramp,
            playback_bound,
        })
    }

    /// The pieces, in order.
    pub fn pieces(&self) -> &[Piece<N, A>] {
        &self.pieces
    }

    /// The number of ticks `N`: samples are at ticks `0 ..= N`, the last one is the end point.
    pub fn ticks(&self) -> u32 {
        self.ticks
    }

    /// The control rate in Hz.
    pub fn rate(&self) -> f64 {
        self.meta.rate
    }

    /// The tick period `T = 1/rate` in seconds.
    pub fn period(&self) -> f64 {
        1.0 / self.meta.rate
    }

    /// The duration of the compiled motion, `ticks · T` seconds.
    pub fn duration(&self) -> f64 {
        f64::from(self.ticks) / self.meta.rate
    }

    /// The duration of the time law the path was compiled from (≤ [`Path::duration`]).
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
        self.meta.peak_velocity
    }

    /// The largest acceleration `|ẍ|` along the path.
    pub fn peak_acceleration(&self) -> f64 {
        self.meta.peak_acceleration
    }

    /// The largest jerk `|x⃛|` along the path.
    pub fn peak_jerk(&self) -> f64 {
        self.meta.peak_jerk
    }

    /// The acceleration limit feed changes respect (given, or derived; see
    /// [`CompileOptions`](crate::CompileOptions)).
    pub fn acceleration_limit(&self) -> f64 {
        self.meta.acceleration_limit
    }

    /// The jerk limit of feed changes.
    pub fn jerk_limit(&self) -> f64 {
        self.meta.jerk_limit
    }

    /// The share of the limits reserved for feed changes.
    pub fn feed_share(&self) -> f64 {
        self.meta.feed_share
    }

    /// The compiled polynomial at a (possibly fractional) tick, evaluated in `f64` from the
    /// stored states (Newton's forward-difference formula): position, velocity (units/s) and
    /// acceleration (units/s²). `tick` is clamped to `[0, ticks]`; at `ticks` the end values
    /// are returned. The returned sample's `tick` is `⌊tick⌋`. For tests and the simulator
    /// (a binary search over the pieces, `O(log P)`).
    pub fn eval(&self, tick: f64) -> Sample<f64, A> {
        let last = f64::from(self.ticks);
        let t = if tick >= 0.0 { tick.min(last) } else { 0.0 };
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let whole = libm::floor(t) as u64;
        let j = self
            .pieces
            .partition_point(|p| f64::from(p.start) <= t)
            .saturating_sub(1);
        match self.pieces.get(j) {
            Some(piece) if t < last => {
                let x = t - f64::from(piece.start);
                let c = Newton::at(x);
                let axes = piece.axes.map(|a| a.to_f64().shifted(&c));
                Sample {
                    tick: whole,
                    position: axes.map(|a| a.position),
                    velocity: axes.map(|a| a.velocity),
                    acceleration: axes.map(|a| a.acceleration),
                }
            }
            _ => Sample {
                tick: whole,
                position: self.end.position.map(Scalar::to_f64),
                velocity: self.end.velocity.map(Scalar::to_f64),
                acceleration: self.end.acceleration.map(Scalar::to_f64),
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::number::Q40;

    fn cubic_state(a: f64, b: f64, c: f64, d: f64, t: f64) -> AxisState<f64> {
        AxisState {
            position: a,
            delta1: b + c + d,
            delta2: 2.0 * c + 6.0 * d,
            delta3: 6.0 * d,
            velocity: b / t,
            velocity_delta1: (2.0 * c + 3.0 * d) / t,
            velocity_delta2: 6.0 * d / t,
            acceleration: 2.0 * c / (t * t),
            acceleration_delta: 6.0 * d / (t * t),
        }
    }

    #[test]
    fn forward_differencing_reproduces_the_cubic() {
        let (a, b, c, d, t) = (1.0, -0.5, 0.25, 0.125, 0.5);
        let mut s = cubic_state(a, b, c, d, t);
        for i in 0..=20 {
            let x = f64::from(i);
            assert_eq!(s.position, a + b * x + c * x * x + d * x * x * x);
            assert_eq!(s.velocity, (b + 2.0 * c * x + 3.0 * d * x * x) / t);
            assert_eq!(s.acceleration, (2.0 * c + 6.0 * d * x) / (t * t));
            s.step();
        }
    }

    #[test]
    fn newton_shift_is_the_cubic_at_a_fraction() {
        let (a, b, c, d, t) = (1.0, -0.5, 0.25, 0.125, 0.5);
        let s = cubic_state(a, b, c, d, t);
        for x in [0.0, 0.25, 0.5, 0.9, 3.7] {
            let z = s.shifted(&Newton::at(x));
            let p = a + b * x + c * x * x + d * x * x * x;
            let dp = b + 2.0 * c * x + 3.0 * d * x * x;
            let d1 = (a + b * (x + 1.0) + c * (x + 1.0) * (x + 1.0) + d * (x + 1.0).powi(3)) - p;
            assert!((z.position - p).abs() < 1e-14);
            assert!((z.delta1 - d1).abs() < 1e-14);
            assert!((z.delta2 - (2.0 * c + 6.0 * d * (x + 1.0))).abs() < 1e-14);
            assert!((z.velocity - dp / t).abs() < 1e-14);
            assert!((z.acceleration - (2.0 * c + 6.0 * d * x) / (t * t)).abs() < 1e-13);
        }
        // θ = 0 is exact in fixed-point
        let q = |v: f64| Q40::from_f64(v).unwrap();
        let sq = AxisState {
            position: q(1.0),
            delta1: q(0.3),
            delta2: q(-0.2),
            delta3: q(0.01),
            ..AxisState::default()
        };
        assert_eq!(sq.shifted(&Newton::at(Q40::ZERO)), sq);
    }

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
        let meta = PathMeta {
            rate: 1000.0,
            plan_duration: 1.0,
            tolerance: 1e-3,
            peak_velocity: 100.0,
            peak_acceleration: 600.0,
            peak_jerk: 1000.0,
            acceleration_limit: 1000.0,
            jerk_limit: 10_000.0,
            feed_share: 0.25,
        };
        let (omega, alpha) = feed_ramp_f64(&meta);
        let (f, v) = (meta.rate, meta.peak_velocity);
        // a_ramp = max(400, 250) = 400, R = j_ramp = max(9000, 2500) = 9000, c = 3·600/100:
        // the split √v·R/(√R + c·√v) = 327.4 < a_ramp
        let (r, c) = (9000.0, 18.0);
        let split = 10.0 * r / (r.sqrt() + c * 10.0);
        assert!(split < 400.0);
        assert!((omega * v * f - split).abs() < 1e-9);
        // the jerk terms 3·φ̇·a_peak + φ̈·v_peak use exactly R
        let jerk = 3.0 * omega * f * meta.peak_acceleration + alpha * f * f * v;
        assert!((jerk - r).abs() < 1e-9, "{jerk}");
        // and the split is the fastest ramp over 1: 1/φ̇ + φ̇/φ̈ is least there
        let time = |a: f64| v / a + a / (r - c * a);
        assert!(time(split) < time(split * 1.01) && time(split) < time(split * 0.99));
        // without acceleration at the peak (c = 0): ω = min(a_ramp/(v f), √α), α = R/(v f²)
        let flat = PathMeta {
            peak_acceleration: 0.0,
            ..meta
        };
        let (omega, alpha) = feed_ramp_f64(&flat);
        assert!((alpha - 9e-5).abs() < 1e-18);
        assert!((omega - 9e-5_f64.sqrt()).abs() < 1e-15);
        // a small jerk budget: ω is capped by √α
        let tight = PathMeta {
            jerk_limit: 1.0,
            peak_jerk: 0.0,
            peak_acceleration: 0.0,
            ..meta
        };
        let (omega, alpha) = feed_ramp_f64(&tight);
        assert!((alpha - 1e-8).abs() < 1e-22);
        assert!((omega - 1e-4).abs() < 1e-15);
    }
}
