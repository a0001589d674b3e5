//! Compiling a curve and a time law into a [`Path`] of polynomial pieces in control ticks.

mod knots;
mod law;
mod online;
mod options;
mod peaks;
mod planned;
mod spline_fit;
mod streamed;
mod stretch;
mod tangential;
#[cfg(test)]
pub(crate) mod testing;

pub use online::{compile_move, compile_move_into, take_over_into};
pub use options::{CompileOptions, Tolerance};
pub use stretch::Stretches;

pub(crate) use law::TickMotion;
pub(crate) use streamed::{StreamedPlan, seal_streamed};
pub(crate) use stretch::{Progress, StretchFit};

use strak_curves::{ParamCurveDeriv, Point, Scalar, ScalarOf};

use crate::error::{Error, Quantity, Units};
use crate::num::{Number, RATE_RANGE};
use crate::path::{AxisState, Path, PathEnd, PathHeader, PathMeta, RampBasis};
use crate::plan::{FeedReserve, MotionLimits, Timing, Trajectory};
use knots::{Knots, PieceKnots};
use law::TickLaw;
use peaks::{LIMIT_SLACK, Peaks};
use spline_fit::{EndClamps, SplineFit};

/// The largest share of the law's jerk limit that the rounding of the positions (in the
/// curve's scalar) may put into the jerk of a piece of one tick: `6σ/T³` for a noise `σ`.
const ONE_TICK_NOISE: f64 = 0.01;

/// The fraction of the tolerance the quarter points are checked against.
const CHECK_FRACTION: f64 = 0.5;

/// How many fits the compiler tries before it reports [`Error::LimitExceeded`].
const SLOWDOWN_ATTEMPTS: usize = 6;

/// What the first slow-down adds to the factor the peaks ask for, doubled at every further
/// attempt: the refit on the new tick grid has an error of its own (the law's breaks and
/// steps fall elsewhere between the ticks).
const SLOWDOWN_MARGIN: f64 = 1e-3;

/// Compiles a [`Trajectory`] (a curve and the time law along it: a planned
/// [`PathTiming`](crate::PathTiming), or any law paired with its curve by
/// [`Along`](crate::Along)) into a path of at most `P` pieces with `A` axes, played at
/// `rate_hz`, in the number format `N`. A planned motion compiles itself at the rate it was
/// planned for with [`PathTiming::compile`](crate::PathTiming::compile).
///
/// 1. **Ticks.** At the rate `f` (100 Hz ..= 100 kHz) the motion takes
///    `N = ⌈duration · f⌉` ticks; the time law is stretched by `duration / (N/f) ≤ 1` so that
///    the motion ends exactly on tick `N` (velocities only decrease).
/// 2. **Spline in time.** The positions `x(k) = c(u(k · duration/N))` at the ticks are
///    approximated by a C² cubic spline in the tick index with knots on the tick grid,
///    clamped at both ends with the exact end velocities `c'(u)·du/dt`, starting from the
///    knots on the breaks (step 3) and, between them, a uniform grid of pieces of at most
///    `max_piece_ticks` ticks (the interpolating cubic spline in Hermite form: de Boor,
///    *A Practical Guide to Splines*, ch. IV).
/// 3. **Knots on the breaks.** A cubic piece cannot follow a jump in jerk inside it (the
///    S-curve's phase and zone boundaries): the fitted jerk would overshoot the plan's. So
///    every break time the time law reports ([`Timing::breaks`], in increasing order)
///    becomes a knot on the nearest tick (stretched time, ticks `1 ..= N−1`), before the
///    refinement: the jerk steps sit within half a tick of a knot. A break closer than 8
///    ticks to its neighbouring breaks (or the ends) gets no knot: half a tick off a knot,
///    a jerk step `Δj` disturbs the jerk of a piece of `h` ticks by about `Δj/(2h)`, and
///    chains of short pieces ring (the planner's zones can hold phases of a few ticks).
///    When *every* break is that close to another (all jerk phases last a few ticks, as
///    with a high jerk limit), every break gets knots on the ticks before and after it
///    instead: a piece of one tick holds the step and the pieces between follow single
///    phases. A one-tick piece turns the rounding `σ` of the positions in the curve's
///    scalar into a jerk of about `6σ/T³`, so this needs `6·ε·|x|/T³` within 1 % of the
///    law's jerk limit (`f64` curves; fixed-point curves at low rates). The uniform grid is
///    laid out between the break knots, so that no grid knot sits a tick or two from a
///    break.
/// 4. **Adaptive knots.** Each piece is checked at its quarter points (`n/4, n/2, 3n/4`)
///    against half the tolerance; pieces that fail are split at their middle tick, the
///    spline is solved again, until every piece passes. At the knots the spline is exact;
///    where the law is smooth, a spline's error between two knots is dominated by the bump
///    `∝ (i − k_j)²(k_{j+1} − i)²` (largest in the middle, 9/16 of it at the quarter
///    points) plus terms from the knot slopes, so the quarter points find most of what
///    needs splitting. Then every tick is checked against the tolerance itself (a law need
///    not be smooth between knots: a trapezoid's acceleration steps, any law's features
///    shorter than a piece), and the pieces that fail are split and both checks repeated:
///    every tick is within the tolerance.
/// 5. **Limits.** When the time law promises limits ([`Timing::limits`]: the planned laws
///    of [`PathTiming`](crate::PathTiming)), the compiled pieces keep them: the spline only
///    approximates the law (within the tolerance in position), so its speed, acceleration
///    and jerk can exceed the law's by the fit's error (most where the law's jerk steps lie
///    between ticks or its phases last a few ticks). The peaks of every piece (the speed
///    exactly, from the roots of `d|ẋ|²/dt`; per axis the velocity at the ends and the
///    vertex; the accelerations at the piece ends; the constant jerk; for a law that bounds
///    the tangential acceleration, a bound of what the samples show at any feed and phase,
///    from the speed's extremes on cells of 1/16 tick) are compared with the limits,
///    the per-axis ones included, and if one is exceeded by the factor `r` (a
///    velocity `r`, an acceleration `r²`, the jerk `r³`) the whole motion is slowed down by `r`
///    and a small margin (more ticks, steps 1–4 again), up to
///    [`CompileOptions::max_slowdown`] in all (and a tick); otherwise
///    [`Error::LimitExceeded`]. [`Path::time_scale`](crate::PathHeader::time_scale) reports the slow-down. The same check
///    catches a law that exceeds its own limits between its samples: the C² spline smooths
///    a trapezoid's acceleration steps with an overshoot (slowed down by about 15 %), and a
///    jerk-limited law along a path whose curvature jumps (the C¹ joins of Hermite or
///    Catmull-Rom splines, quadratic B-splines) steps its acceleration by `v²·Δκ` there,
///    which usually needs more than the largest slow-down (`LimitExceeded` for the jerk).
/// 6. **States.** Each piece becomes its forward-difference start state per axis, rounded
///    once into the number format `N` (range-checked: [`Error::OutOfRange`]).
///
/// The first sample (tick 0) is the curve's point at the time law's start; the last (tick
/// [`Path::ticks`](crate::PathHeader::ticks)) is the curve's point at the end, exactly as the curve computes it in its
/// own scalar type, converted once into the sample type.
///
/// # Memory
/// The path holds `P·(8 + 9·A·size_of::<N>())` bytes of pieces and is returned by value:
/// on a small stack use [`compile_into`], which writes it in place. The fit keeps its
/// knots in the path's own pieces, so compiling needs no storage beside the path whatever
/// `P`, only small fixed frames of stack.
///
/// # Errors
/// * [`Error::InvalidLimit`]: bad [`CompileOptions`] (or a bad
///   [`FeedReserve`](crate::FeedReserve) of the law, used without limits in the options);
/// * [`Error::InvalidRate`]: `rate_hz` outside 100 Hz ..= 100 kHz (or NaN);
/// * [`Error::AxisMismatch`]: `A` differs from the curve's point dimension;
/// * [`Error::EmptyPath`]: the time law's duration is zero, negative or NaN;
/// * [`Error::TooLong`]: more ticks than a `u32` counts (or an infinite duration);
/// * [`Error::CapacityExceeded`]: more than `P` pieces needed, the knots on the breaks
///   included (`required` is a lower bound);
/// * [`Error::OutOfRange`]: a value does not fit the number format (fixed-point range);
/// * [`Error::LimitExceeded`]: the compiled pieces exceed a limit of the time law by more
///   than [`CompileOptions::max_slowdown`] allows;
/// * [`Error::FeedReserveExceeded`]: the motion uses more than `1 − share` of a limit
///   given for feed changes that its law promises (see [`CompileOptions`]);
/// * [`Error::PlaybackBoundExceeded`]: the error playback in `N` may add
///   ([`playback_bound`](crate::PathHeader::playback_bound)) exceeds the tolerance (`f32`
///   far from the origin);
/// * [`Error::Curve`]: the time law or the curve produced a non-finite value.
///
/// ```
/// use strak_trajectory::{compile, Along, CompileOptions, Path, Sampler, Timing};
/// use strak_curves::Bezier;
///
/// /// Rest to rest in 0.2 s: u = 3τ² − 2τ³.
/// struct Smooth;
/// impl Timing for Smooth {
///     fn duration(&self) -> f64 { 0.2 }
///     fn param(&self, t: f64) -> (f64, f64) {
///         let s = t.clamp(0.0, 0.2) / 0.2;
///         (s * s * (3.0 - 2.0 * s), 6.0 * s * (1.0 - s) / 0.2)
///     }
/// }
/// let curve = Bezier::new([[0.0_f64, 0.0, 0.0], [10.0, 0.0, 0.0], [10.0, 10.0, 5.0]])?;
/// let options = CompileOptions::new().with_tolerance(1e-4); // within f32 playback (2·10⁻⁵)
/// let path: Path<f32, 3, 64> = compile(&Along::new(&curve, &Smooth), 10_000.0, &options)?;
/// assert_eq!(path.ticks(), 2_000);
/// assert_eq!(path.end_position(), [10.0, 10.0, 5.0]);
/// assert!(path.pieces().len() >= 8); // at most 256 ticks per piece
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn compile<N, const A: usize, const P: usize, M>(
    trajectory: &M,
    rate_hz: f64,
    options: &CompileOptions,
) -> Result<Path<N, A, P>, Error>
where
    N: Number,
    M: Trajectory + ?Sized,
{
    let mut path = Path::new();
    compile_into(trajectory, rate_hz, options, &mut path)?;
    Ok(path)
}

/// [`compile`] into caller-provided storage: the path is written in place (a `static`, or
/// a path the caller keeps), and no path or piece array is moved by value. The fit keeps
/// its knots in the path's own pieces until it writes them as pieces, so compiling needs
/// only small fixed frames of stack beside `path`, whatever `P`. On an error the path is
/// left empty ([`Path::new`]).
///
/// # Errors
/// As [`compile`].
///
/// ```
/// use strak_trajectory::{compile_into, Along, CompileOptions, Path, Timing};
/// use strak_curves::Bezier;
/// struct Smooth;
/// impl Timing for Smooth {
///     fn duration(&self) -> f64 { 0.2 }
///     fn param(&self, t: f64) -> (f64, f64) {
///         let s = t.clamp(0.0, 0.2) / 0.2;
///         (s * s * (3.0 - 2.0 * s), 6.0 * s * (1.0 - s) / 0.2)
///     }
/// }
/// static mut PATH: Path<f32, 2, 64> = Path::new(); // in firmware: a `static`
/// let mut path: Path<f32, 2, 64> = Path::new();
/// let curve = Bezier::new([[0.0_f64, 0.0], [10.0, 0.0], [10.0, 10.0]])?;
/// compile_into(&Along::new(&curve, &Smooth), 1_000.0, &CompileOptions::new(), &mut path)?;
/// assert_eq!((path.ticks(), path.end_position()), (200, [10.0, 10.0]));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn compile_into<N, const A: usize, const P: usize, M>(
    trajectory: &M,
    rate_hz: f64,
    options: &CompileOptions,
    path: &mut Path<N, A, P>,
) -> Result<(), Error>
where
    N: Number,
    M: Trajectory + ?Sized,
{
    path.clear();
    let result = fit_into(trajectory, rate_hz, options, path);
    if result.is_err() {
        path.clear();
    }
    result
}

/// Steps 1–5 of [`compile`] (the fit in `path`'s pieces, slowed down until its pieces keep
/// the law's limits), then step 6 ([`assemble`]).
fn fit_into<N, const A: usize, const P: usize, M>(
    trajectory: &M,
    rate_hz: f64,
    options: &CompileOptions,
    path: &mut Path<N, A, P>,
) -> Result<(), Error>
where
    N: Number,
    M: Trajectory + ?Sized,
{
    let (curve, timing) = (trajectory.curve(), trajectory.law());
    check_inputs::<A, M::Curve, M::Law>(timing, rate_hz, options)?;
    let period = 1.0 / rate_hz;
    let limits = timing.limits();
    let mut fit = SplineFit::<A, _>::empty(PieceKnots::new(&mut path.pieces));
    let (mut stretch, mut min_ticks) = (1.0_f64, 0_u32);
    let (mut exceeded, mut margin) = (Quantity::Velocity, SLOWDOWN_MARGIN);
    for _ in 0..SLOWDOWN_ATTEMPTS {
        let law = TickLaw::new(curve, timing, rate_hz, stretch, min_ticks)?;
        let tolerance = fit_law(&law, options, &mut fit)?;
        let tangential = limits.is_some_and(|l| l.tangential_acceleration.is_finite());
        let peaks = fit_peaks(&fit, period, tangential, usize::MAX, f64::NEG_INFINITY);
        let (factor, quantity) = match &limits {
            Some(limits) => peaks.slowdown(limits)?,
            None => (1.0, None),
        };
        let Some(quantity) = quantity else {
            let duration = law.duration();
            let described = LawPeaks {
                peaks,
                promised: limits.as_ref(),
                axes: A,
            };
            let reserve = || timing.feed_reserve();
            path.header.meta =
                path_meta(&described, &reserve, rate_hz, duration, tolerance, options)?;
            end_into::<N, _, _, A, _>(curve, &law, &fit, &mut path.header.end)?;
            write_states(fit, 0, period)?;
            path.seal()?;
            return check_playback_bound(&path.header);
        };
        // Slower by what the peaks ask for (and a margin), at least one tick, at most the
        // largest slow-down.
        exceeded = quantity;
        if stretch >= options.max_slowdown() {
            break;
        }
        stretch = (stretch * (factor + margin)).min(options.max_slowdown());
        min_ticks = law.ticks.saturating_add(1);
        margin *= 2.0;
    }
    Err(Error::LimitExceeded { quantity: exceeded })
}

/// The playback bound of a compiled path within its tolerance.
///
/// # Errors
/// [`Error::PlaybackBoundExceeded`] otherwise.
pub(super) fn check_playback_bound<N: Number, const A: usize>(
    header: &PathHeader<N, A>,
) -> Result<(), Error> {
    let (bound, tolerance) = (header.playback_bound(), header.tolerance());
    if bound <= tolerance {
        Ok(())
    } else {
        Err(Error::PlaybackBoundExceeded {
            bound: Units(bound),
            tolerance: Units(tolerance),
        })
    }
}

/// Checks the options, the rate, the axis count and the time law's duration.
fn check_inputs<const A: usize, C, T>(
    timing: &T,
    rate_hz: f64,
    options: &CompileOptions,
) -> Result<(), Error>
where
    C: ParamCurveDeriv + ?Sized,
    T: Timing + ?Sized,
{
    options.validate()?;
    if !(rate_hz >= RATE_RANGE.0 && rate_hz <= RATE_RANGE.1) {
        return Err(Error::InvalidRate);
    }
    let dim = <C::Point as Point>::DIM;
    if dim != A {
        return Err(Error::AxisMismatch {
            curve: dim,
            path: A,
        });
    }
    let duration = timing.duration();
    if duration.is_nan() || duration <= 0.0 {
        return Err(Error::EmptyPath);
    }
    if !duration.is_finite() {
        return Err(Error::TooLong);
    }
    Ok(())
}

/// Fits the spline to `law` (steps 2–4 of [`compile`]) in `fit`; returns the tolerance.
fn fit_law<C, T, const A: usize, K: Knots<A>>(
    law: &TickLaw<'_, C, T>,
    options: &CompileOptions,
    fit: &mut SplineFit<A, K>,
) -> Result<f64, Error>
where
    C: ParamCurveDeriv + ?Sized,
    T: Timing + ?Sized,
{
    let mut exact = |k: u32| law.position::<A>(k);
    let start_slope = law.slope(0.0)?;
    let final_slope = law.slope(law.duration())?;
    // One piece first; the knots on the breaks, then the uniform grid between them.
    fit.init(law.ticks, law.ticks, start_slope, final_slope, &mut exact)?;
    let one_tick_pieces = law.limits().is_some_and(|l| {
        let noise = ScalarOf::<C>::EPSILON * fit_magnitude(fit);
        6.0 * noise / (law.period * law.period * law.period) <= ONE_TICK_NOISE * l.jerk
    });
    law.knots_on_breaks(fit, one_tick_pieces)?;
    fit.subdivide(options.max_piece_ticks(), &mut exact)?;
    let tolerance = match options.tolerance() {
        Tolerance::Absolute(t) => t,
        Tolerance::Relative(r) => relative_tolerance(r, fit),
    };
    fit.refine_every_tick(tolerance * CHECK_FRACTION, tolerance, &mut exact)?;
    Ok(tolerance)
}

/// The largest coordinate magnitude of the knot values.
fn fit_magnitude<const A: usize, K: Knots<A>>(fit: &SplineFit<A, K>) -> f64 {
    (0..=fit.pieces()).fold(0.0_f64, |m, j| {
        fit.value(j).iter().fold(m, |m, v| m.max(v.abs()))
    })
}

/// The tolerance `r` times the extent of the knot values (at least the level of `f64`
/// rounding, for a path that stands still).
fn relative_tolerance<const A: usize, K: Knots<A>>(r: f64, fit: &SplineFit<A, K>) -> f64 {
    let mut lo = fit.value(0);
    let mut hi = lo;
    let mut big = 0.0_f64;
    for j in 1..=fit.pieces() {
        for (a, v) in fit.value(j).into_iter().enumerate() {
            lo[a] = lo[a].min(v);
            hi[a] = hi[a].max(v);
            big = big.max(v.abs());
        }
    }
    let extent = lo.iter().zip(hi).fold(0.0_f64, |m, (l, h)| m.max(h - l));
    (r * extent).max(1e-12 * (1.0 + big))
}

/// The peaks of the fitted spline's pieces (with the tangential acceleration when
/// `tangential`: its bound at any feed, [`tangential_peak`]); the speed peak exact where it
/// may reach `speed_limit`, a bound of it below ([`Peaks::of_piece_below`]).
fn fit_peaks<const A: usize, K: Knots<A>, E: EndClamps<A>>(
    fit: &SplineFit<A, K, E>,
    period: f64,
    tangential: bool,
    path: usize,
    speed_limit: f64,
) -> Peaks {
    let mut peaks = Peaks::default();
    fit.each_piece(|coeffs, n| {
        let piece = Peaks::of_shaped_piece_below(&coeffs, f64::from(n), period, path, speed_limit);
        peaks = peaks.max(piece);
    });
    if tangential {
        peaks.tangential = tangential_peak(fit, period);
    }
    peaks
}

/// The bound of the tangential acceleration over the fitted pieces
/// ([`tangential::Tangential`]); in a frame of its own, so that compiling a law without a
/// tangential limit does not carry its cells on the stack.
#[inline(never)]
fn tangential_peak<const A: usize, K: Knots<A>, E: EndClamps<A>>(
    fit: &SplineFit<A, K, E>,
    period: f64,
) -> f64 {
    let mut bound = tangential::Tangential::new();
    for j in 0..fit.pieces() {
        let (coeffs, n) = fit.piece(j);
        bound.piece(&coeffs, n);
    }
    bound.peak(period)
}

/// The forward-difference start state of one axis of a piece `a + b i + c i² + d i³`.
fn piece_state([a, b, c, d]: [f64; 4], period: f64) -> AxisState<f64> {
    let tt = period * period;
    AxisState {
        position: a,
        delta1: b + c + d,
        delta2: 2.0 * c + 6.0 * d,
        delta3: 6.0 * d,
        velocity: b / period,
        velocity_delta1: (2.0 * c + 3.0 * d) / period,
        velocity_delta2: 6.0 * d / period,
        acceleration: 2.0 * c / tt,
        acceleration_delta: 6.0 * d / tt,
    }
}

/// The end of the path (step 6 of [`compile`]) into `end`: the curve's own end point,
/// converted once, the law's end velocity and the last piece's end acceleration.
///
/// # Errors
/// [`Error::OutOfRange`] for a value the sample type cannot hold; the law's errors.
fn end_into<N, C, T, const A: usize, K: Knots<A>>(
    curve: &C,
    law: &TickLaw<'_, C, T>,
    fit: &SplineFit<A, K>,
    end: &mut PathEnd<N::Out, A>,
) -> Result<(), Error>
where
    N: Number,
    C: ParamCurveDeriv + ?Sized,
    T: Timing + ?Sized,
{
    let period = law.period;
    let (coeffs, n) = fit.piece(fit.pieces().saturating_sub(1));
    let duration = law.duration();
    let final_slope: [f64; A] = law.slope(duration)?;
    let end_point = curve.eval(law.param(duration)?.0);
    let out = |v: f64| N::out_from_f64(v).ok_or(Error::OutOfRange);
    for (a, [_, _, c, d]) in coeffs.into_iter().enumerate() {
        let acceleration = (2.0 * c + 6.0 * d * f64::from(n)) / (period * period);
        if let (Some(x), Some(v), Some(acc), Some(s)) = (
            end.position.get_mut(a),
            end.velocity.get_mut(a),
            end.acceleration.get_mut(a),
            final_slope.get(a),
        ) {
            *x = out(end_point.coord(a).to_f64())?;
            *v = out(s / period)?;
            *acc = out(acceleration)?;
        }
    }
    Ok(())
}

/// The pieces' forward-difference states in `N` (step 6 of [`compile`]), written over the
/// fit's knots in the path's own pieces, their starts counted from the tick `first`.
///
/// # Errors
/// [`Error::OutOfRange`] for a value that does not fit `N`.
pub(super) fn write_states<N: Number, const A: usize, const P: usize, E: EndClamps<A>>(
    fit: SplineFit<A, PieceKnots<'_, N, A, P>, E>,
    first: u32,
    period: f64,
) -> Result<(), Error> {
    fit.write_pieces(|knots, j, coeffs, start, ticks| {
        let Some(piece) = knots.piece_mut(j) else {
            return Err(Error::CapacityExceeded {
                capacity: P,
                required: j + 1,
            });
        };
        piece.start = first + start;
        piece.ticks = ticks;
        for (axis, c) in piece.axes.iter_mut().zip(coeffs) {
            *axis = round_state(&piece_state(c, period))?;
        }
        Ok(())
    })
}

/// What the compiled path's feed limits are derived from: its peaks, the limits its law
/// promises, and its number of axes.
struct LawPeaks<'a> {
    peaks: Peaks,
    promised: Option<&'a MotionLimits>,
    axes: usize,
}

impl LawPeaks<'_> {
    /// Whether the law limits only the tangential acceleration (its centripetal part is
    /// not limited, so it says nothing of the machine's limit).
    fn tangential(&self) -> bool {
        self.promised
            .is_some_and(|l| l.tangential_acceleration.is_finite())
    }

    /// The acceleration a feed ramp adds to: the tangential peak for a law that limits only
    /// that (a ramp adds only tangential acceleration), else the peak of `|ẍ|`.
    fn acceleration_used(&self) -> f64 {
        if self.tangential() {
            self.peaks.tangential.min(self.peaks.acceleration)
        } else {
            self.peaks.acceleration
        }
    }

    /// The reserve of a law that promises limits but reserves nothing: it is taken to move
    /// at the limits it promises, which stand in for the machine's (the tangential
    /// acceleration for a tangential law, the jerk, the axis accelerations); a quantity it
    /// does not promise is derived as in [`derived_limits`].
    fn standing_reserve(&self, share: f64) -> Option<FeedReserve> {
        let promised = self.promised?;
        let (a, j) = derived_limits(self, share);
        let a_promised = if self.tangential() {
            promised.tangential_acceleration
        } else {
            promised.acceleration
        };
        let given = |p: f64, derived: f64| if p.is_finite() { p } else { derived };
        Some(FeedReserve {
            acceleration: given(a_promised, a),
            jerk: given(promised.jerk, j),
            axis_acceleration: promised.axis_acceleration,
            share,
        })
    }
}

/// The path's description: its peaks, and the limits of feed changes (the peaks plus what
/// a ramp may add, [`ramp_budget`], from the given limits or those derived from the peaks;
/// see [`CompileOptions`]).
///
/// Without limits in `options`, the limits and share of the law's reserve are used; for a
/// law that promises limits without a reserve, the limits it promises
/// ([`LawPeaks::standing_reserve`]).
/// Not inlined: its frame (the completed options) lives only after the fit, not through it.
///
/// # Errors
/// [`Error::FeedReserveExceeded`] when the motion uses more than `1 − share` of a given
/// limit its law promises; [`Error::InvalidLimit`] for a reserve that is not valid
/// compile options.
#[inline(never)]
fn path_meta(
    law: &LawPeaks<'_>,
    reserve: &dyn Fn() -> Option<FeedReserve>,
    rate_hz: f64,
    duration: f64,
    tolerance: f64,
    options: &CompileOptions,
) -> Result<PathMeta, Error> {
    let standing = || law.standing_reserve(options.feed_share());
    let options = &options.completed_by(reserve().or_else(standing));
    // A law's own reserve is checked like the options.
    options.validate()?;
    let share = options.feed_share();
    let peaks = &law.peaks;
    let (a_free, j_free) = match options.limits() {
        Some((a, j)) => ramp_budget(law, options, a, j)?,
        None => derived_budget(law, share),
    };
    let acceleration_limit = peaks.acceleration + a_free;
    let jerk_limit = peaks.jerk + j_free;
    // The ramps take `max(limit − peak, share·limit)`: a share no larger than what is free
    // leaves them `limit − peak`.
    let feed_share = share
        .min(a_free / acceleration_limit)
        .min(j_free / jerk_limit);
    Ok(PathMeta {
        plan_duration: duration,
        tolerance,
        ramp: RampBasis {
            rate: rate_hz,
            peak_velocity: peaks.velocity_bound,
            peak_acceleration: peaks.acceleration,
            peak_jerk: peaks.jerk,
            acceleration_limit,
            jerk_limit,
            feed_share,
        },
    })
}

/// What a feed ramp may add to the acceleration and to the jerk under the given path
/// limits `a`, `j` and the options' per-axis accelerations `aᵢ`: `a − a_peak`, and
/// `(aᵢ − aᵢ,peak)·v_peak/vᵢ,peak` for each axis (a ramp that adds `A` to `|ẍ|` adds
/// `A·|ẋᵢ|/v_peak` to axis `i`), and `j − j_peak`; each at least `share` of its limit.
///
/// # Errors
/// [`Error::FeedReserveExceeded`] when a peak exceeds `1 − share` of a limit the law
/// promises: the floor `share·limit` would then take the motion beyond it.
fn ramp_budget(
    law: &LawPeaks<'_>,
    options: &CompileOptions,
    a: f64,
    j: f64,
) -> Result<(f64, f64), Error> {
    let share = options.feed_share();
    // Twice the peaks' slack: the law's promise is itself a rounded `(1 − share)·limit`.
    let keep = (1.0 - share) * (1.0 + 2.0 * LIMIT_SLACK);
    let none = MotionLimits::new(f64::INFINITY, f64::INFINITY, f64::INFINITY);
    let promised = law.promised.unwrap_or(&none);
    let free = |quantity, peak: f64, limit: f64, promises: bool| {
        if promises && peak > keep * limit {
            Err(Error::FeedReserveExceeded { quantity })
        } else {
            Ok((limit - peak).max(share * limit))
        }
    };
    let peaks = &law.peaks;
    let (quantity, promises_a) = if law.tangential() {
        (Quantity::TangentialAcceleration, true)
    } else {
        (Quantity::Acceleration, promised.acceleration.is_finite())
    };
    let mut a_free = free(quantity, law.acceleration_used(), a, promises_a)?;
    let axes = options.axis_acceleration().into_iter().enumerate();
    for (axis, limit) in axes.take(law.axes).filter(|(_, l)| l.is_finite()) {
        let (v, peak) = (peaks.axis_velocity[axis], peaks.axis_acceleration[axis]);
        let promises = promised.axis_acceleration[axis].is_finite();
        let quantity = Quantity::AxisAcceleration { axis };
        let axis_free = free(quantity, peak, limit, promises)?;
        if v > 0.0 {
            a_free = a_free.min(axis_free * peaks.velocity_bound / v);
        }
    }
    let j_free = free(Quantity::Jerk, peaks.jerk, j, promised.jerk.is_finite())?;
    Ok((a_free, j_free))
}

/// What a feed ramp may add when neither the options nor the law give limits: `share` of
/// the limits the plan is assumed to have used `1 − share` of ([`derived_limits`]).
fn derived_budget(law: &LawPeaks<'_>, share: f64) -> (f64, f64) {
    let (a, j) = derived_limits(law, share);
    (
        (a - law.peaks.acceleration).max(share * a),
        (j - law.peaks.jerk).max(share * j),
    )
}

/// The path acceleration and jerk limits of a motion assumed to use `1 − share` of them
/// (see [`CompileOptions`]): `a_used/(1 − share)` and `j_peak/(1 − share)`; for a motion
/// without acceleration `v_peak / 0.1 s`, without jerk `a / 0.1 s`.
fn derived_limits(law: &LawPeaks<'_>, share: f64) -> (f64, f64) {
    let peaks = &law.peaks;
    let (v_peak, a_used, j_peak) = (peaks.velocity_bound, law.acceleration_used(), peaks.jerk);
    let a = if a_used > 0.0 {
        a_used / (1.0 - share)
    } else if v_peak > 0.0 {
        v_peak / 0.1
    } else {
        1.0
    };
    let j = if j_peak > 0.0 {
        j_peak / (1.0 - share)
    } else {
        a / 0.1
    };
    (a, j)
}

/// The state rounded into `N` ([`Error::OutOfRange`] if a value does not fit).
pub(super) fn round_state<N: Number>(s: &AxisState<f64>) -> Result<AxisState<N>, Error> {
    let r = |v: f64| N::from_f64(v).ok_or(Error::OutOfRange);
    Ok(AxisState {
        position: r(s.position)?,
        delta1: r(s.delta1)?,
        delta2: r(s.delta2)?,
        delta3: r(s.delta3)?,
        velocity: r(s.velocity)?,
        velocity_delta1: r(s.velocity_delta1)?,
        velocity_delta2: r(s.velocity_delta2)?,
        acceleration: r(s.acceleration)?,
        acceleration_delta: r(s.acceleration_delta)?,
    })
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::testing::{
        Linear, Quintic, Smoothstep, TestTiming, Trapezoid, compile_boxed, exact, helix,
    };
    use super::*;
    use crate::num::Q40;
    use crate::plan::Along;
    use std::boxed::Box;
    use strak_curves::{Bezier, I32F32, ParamCurve};

    fn line() -> Bezier<[f64; 2], 2> {
        Bezier::new([[0.0, 0.0], [3.0, 4.0]]).unwrap()
    }

    /// An `f32` path 4.5·10⁶ units from the origin: the spacing of `f32` there (0.5) puts
    /// the playback bound far above a tolerance of 0.001, which the compiler reports with
    /// both figures; `f64` and a wide enough tolerance compile.
    #[test]
    fn playback_bound_above_the_tolerance_is_an_error() {
        use std::string::ToString;
        let far = Bezier::new([[4.5e6, 0.0, 0.0], [4.5e6 + 20.0, 10.0, 0.0]]).unwrap();
        let law = Smoothstep::new(0.5);
        let trajectory = Along::new(&far, &law);
        let options = CompileOptions::new().with_tolerance(1e-3);
        let r: Result<Path<f32, 3, 64>, _> = compile(&trajectory, 1_000.0, &options);
        let Err(Error::PlaybackBoundExceeded { bound, tolerance }) = r else {
            panic!("{r:?}");
        };
        assert_eq!(tolerance, Units(1e-3));
        assert!(bound.0 > 0.1 && bound.0 < 100.0, "{bound}");
        let message = Error::PlaybackBoundExceeded { bound, tolerance }.to_string();
        assert!(message.contains(&bound.to_string()) && message.contains("0.001"));
        let wide: Path<f64, 3, 64> = compile(&trajectory, 1_000.0, &options).unwrap();
        assert!(wide.playback_bound() <= 1e-3);
        let loose = CompileOptions::new().with_tolerance(2.0 * bound.0);
        let coarse: Path<f32, 3, 64> = compile(&trajectory, 1_000.0, &loose).unwrap();
        assert!(coarse.playback_bound() <= coarse.tolerance());
    }

    #[test]
    fn axis_mismatch() {
        let r: Result<Path<f64, 3, 8>, _> = compile(
            &Along::new(&line(), &Linear(1.0)),
            1000.0,
            &CompileOptions::new(),
        );
        assert_eq!(r, Err(Error::AxisMismatch { curve: 2, path: 3 }));
    }

    #[test]
    fn invalid_rate() {
        for rate in [99.9, 100_001.0, f64::NAN, f64::INFINITY, -1000.0] {
            let r: Result<Path<f64, 2, 8>, _> = compile(
                &Along::new(&line(), &Linear(1.0)),
                rate,
                &CompileOptions::new(),
            );
            assert_eq!(r, Err(Error::InvalidRate), "{rate}");
        }
        for rate in [100.0, 100_000.0] {
            let r: Result<Path<f64, 2, 1024>, _> = compile(
                &Along::new(&line(), &Linear(1.0)),
                rate,
                &CompileOptions::new(),
            );
            assert!(r.is_ok());
        }
    }

    #[test]
    fn empty_path() {
        for d in [0.0, -1.0, f64::NAN] {
            let r: Result<Path<f64, 2, 8>, _> = compile(
                &Along::new(&line(), &Linear(d)),
                1000.0,
                &CompileOptions::new(),
            );
            assert_eq!(r, Err(Error::EmptyPath), "{d}");
        }
    }

    #[test]
    fn too_long() {
        // 10⁵ s at 100 kHz = 10¹⁰ ticks > u32::MAX
        let r: Result<Path<f64, 2, 8>, _> = compile(
            &Along::new(&line(), &Linear(1.0e5)),
            100_000.0,
            &CompileOptions::new(),
        );
        assert_eq!(r, Err(Error::TooLong));
        let r: Result<Path<f64, 2, 8>, _> = compile(
            &Along::new(&line(), &Linear(f64::INFINITY)),
            1000.0,
            &CompileOptions::new(),
        );
        assert_eq!(r, Err(Error::TooLong));
    }

    #[test]
    fn capacity_exceeded() {
        // 1000 ticks in pieces of at most 256: 4 pieces needed
        let r: Result<Path<f64, 2, 3>, _> = compile(
            &Along::new(&line(), &Linear(1.0)),
            1000.0,
            &CompileOptions::new(),
        );
        assert_eq!(
            r,
            Err(Error::CapacityExceeded {
                capacity: 3,
                required: 4
            })
        );
        // refinement needs more than the grid
        let r: Result<Path<f64, 3, 8>, _> = compile(
            &Along::new(&helix(1.0, 3.0, 1.0), &Smoothstep::new(0.2)),
            1000.0,
            &CompileOptions::new().with_tolerance(1e-9),
        );
        assert!(matches!(
            r,
            Err(Error::CapacityExceeded { capacity: 8, required }) if required > 8
        ));
    }

    #[test]
    fn out_of_range_for_fixed_point() {
        // 10⁷ units exceed Q40's checked range ±2²²; f32 and f64 take them.
        let far = Bezier::new([[0.0_f64], [1.0e7]]).unwrap();
        let o = CompileOptions::new();
        let r: Result<Path<Q40, 1, 8>, _> = compile(&Along::new(&far, &Linear(1.0)), 1000.0, &o);
        assert_eq!(r, Err(Error::OutOfRange));
        let r: Result<Path<f32, 1, 8>, _> = compile(&Along::new(&far, &Linear(1.0)), 1000.0, &o);
        assert!(r.is_ok());
        // within range: 4·10⁶ units
        let near = Bezier::new([[0.0_f64], [4.0e6]]).unwrap();
        let r: Result<Path<Q40, 1, 8>, _> = compile(&Along::new(&near, &Linear(1.0)), 1000.0, &o);
        assert!(r.is_ok());
        // a large velocity at a large position: the sums of the range check exceed 2²²
        let fast = Bezier::new([[4.0e6_f64], [4.19e6]]).unwrap();
        let r: Result<Path<Q40, 1, 8>, _> = compile(&Along::new(&fast, &Linear(0.01)), 1000.0, &o);
        assert_eq!(r, Err(Error::OutOfRange));
    }

    #[test]
    fn invalid_options() {
        let r: Result<Path<f64, 2, 8>, _> = compile(
            &Along::new(&line(), &Linear(1.0)),
            1000.0,
            &CompileOptions::new().with_tolerance(-1.0),
        );
        assert_eq!(r, Err(Error::InvalidLimit));
    }

    struct Broken;
    impl Timing for Broken {
        fn duration(&self) -> f64 {
            1.0
        }
        fn param(&self, t: f64) -> (f64, f64) {
            (if t > 0.5 { f64::NAN } else { t }, 1.0)
        }
    }

    #[test]
    fn non_finite_time_law() {
        let r: Result<Path<f64, 2, 8>, _> = compile(
            &Along::new(&line(), &Broken),
            1000.0,
            &CompileOptions::new(),
        );
        assert_eq!(r, Err(Error::Curve(strak_curves::Error::NonFinite)));
    }

    #[test]
    fn ticks_and_time_stretch() {
        let o = CompileOptions::new();
        // 0.3 s at 1 kHz is 300 ticks although 0.3·1000 = 300.00000000000006
        let p: Path<f64, 2, 8> = compile(&Along::new(&line(), &Linear(0.3)), 1000.0, &o).unwrap();
        assert_eq!(p.ticks(), 300);
        assert!((p.time_scale() - 1.0).abs() < 1e-12);
        // 0.3004 s: 301 ticks, stretched by 0.3004/0.301
        let p: Path<f64, 2, 8> =
            compile(&Along::new(&line(), &Linear(0.3004)), 1000.0, &o).unwrap();
        assert_eq!(p.ticks(), 301);
        assert!((p.time_scale() - 0.3004 / 0.301).abs() < 1e-15);
        // velocities decrease by the stretch: 5 units in 0.301 s
        let v = p.eval(100.0).velocity;
        assert!((v[0] - 3.0 / 0.301).abs() < 1e-9 && (v[1] - 4.0 / 0.301).abs() < 1e-9);
        // a very short law still has one tick
        let p: Path<f64, 2, 8> = compile(&Along::new(&line(), &Linear(1e-6)), 1000.0, &o).unwrap();
        assert_eq!(p.ticks(), 1);
        assert_eq!(p.eval(1.0).position, [3.0, 4.0]);
    }

    #[test]
    fn end_point_is_the_curves_own() {
        // a fixed-point curve: its end point as it computes it, bit for bit
        let p = |x: f64| [I32F32::from_num(x)];
        let c = Bezier::new([p(0.1), p(-0.7), p(1.3), p(2.0 / 3.0)]).unwrap();
        let path: Path<Q40, 1, 64> = compile(
            &Along::new(&c, &Smoothstep::new(0.5)),
            1000.0,
            &CompileOptions::new(),
        )
        .unwrap();
        assert_eq!(path.end_position(), c.eval(I32F32::ONE));
        assert_eq!(path.end_velocity(), [I32F32::ZERO]);
        // f32 from an f64 curve: rounded once
        let c = Bezier::new([[0.0_f64], [0.1]]).unwrap();
        let path: Path<f32, 1, 8> = compile(
            &Along::new(&c, &Smoothstep::new(0.5)),
            1000.0,
            &CompileOptions::new(),
        )
        .unwrap();
        assert_eq!(path.end_position(), [0.1_f32]);
    }

    /// Checks the compiled polynomial at every tick against the exact composition.
    /// The largest errors of position, velocity, acceleration against the exact composition
    /// at every tick, and the path's peak velocity and acceleration.
    struct Errors {
        position: f64,
        velocity: f64,
        acceleration: f64,
        peak_velocity: f64,
        peak_acceleration: f64,
    }

    fn check_every_tick<T: TestTiming + Send + Sync + 'static>(
        timing: T,
        rate: f64,
        tol: f64,
    ) -> Errors {
        check_every_tick_on(&timing, rate, tol)
    }

    fn check_every_tick_on<T: TestTiming>(timing: &T, rate: f64, tol: f64) -> Errors {
        let curve = helix(2.0, 2.0, 1.0);
        let path: Box<Path<f64, 3, 4096>> = compile_boxed(
            &Along::new(&curve, timing),
            rate,
            &CompileOptions::new().with_tolerance(tol),
        )
        .unwrap();
        assert_eq!(path.tolerance(), tol);
        let (mut ep, mut ev, mut ea) = (0.0_f64, 0.0_f64, 0.0_f64);
        for k in 0..=path.ticks() {
            let s = path.eval(f64::from(k));
            let (p, v, a) = exact(&curve, timing, &path, f64::from(k));
            for i in 0..3 {
                ep = ep.max((s.position[i] - p[i]).abs());
                ev = ev.max((s.velocity[i] - v[i]).abs());
                ea = ea.max((s.acceleration[i] - a[i]).abs());
            }
        }
        std::println!(
            "tol {tol:e}: pieces {} pos {ep:.3e} vel {ev:.3e} (peak {:.3e}) acc {ea:.3e} (peak {:.3e})",
            path.pieces().len(),
            path.peak_velocity(),
            path.peak_acceleration()
        );
        // The documented bound: every tick within the tolerance.
        assert!(ep <= tol, "position error {ep} > {tol}");
        Errors {
            position: ep,
            velocity: ev,
            acceleration: ea,
            peak_velocity: path.peak_velocity(),
            peak_acceleration: path.peak_acceleration(),
        }
    }

    #[test]
    fn every_tick_within_tolerance() {
        // Smooth time laws: the spline's derivatives follow closely, too (measured: velocity
        // ≈ 6·10⁻⁶·v_peak, acceleration ≈ 4·10⁻⁴·a_peak at tol = 10⁻⁶ of an extent of 4).
        for e in [
            check_every_tick(Smoothstep::new(0.5), 10_000.0, 1e-6),
            check_every_tick(Quintic(0.5), 10_000.0, 1e-6),
            check_every_tick(Linear(1.0), 1_000.0, 1e-6),
        ] {
            assert!(e.velocity < 1e-5 * e.peak_velocity, "{}", e.velocity);
            assert!(
                e.acceleration < 1e-3 * e.peak_acceleration,
                "{}",
                e.acceleration
            );
        }
        for tol in [1e-3, 1e-5, 1e-7] {
            let e = check_every_tick(Quintic(0.3), 20_000.0, tol);
            // the quarter-point check against tol/2 finds the largest error well
            assert!(e.position > 0.3 * tol, "{}", e.position);
        }
    }

    #[test]
    fn every_tick_within_tolerance_with_acceleration_jumps() {
        // The trapezoid's acceleration jumps by Δa; a C² spline cannot follow that, but the
        // positions stay within the tolerance at every tick (knots are inserted at the jumps)
        // and the velocity error is of the order √(Δa·tol).
        for tol in [1e-4, 1e-6] {
            let e = check_every_tick(
                Trapezoid {
                    duration: 0.8,
                    ramp: 0.25,
                },
                10_000.0,
                tol,
            );
            let jump = e.peak_acceleration;
            assert!(e.velocity < libm::sqrt(jump * tol), "{}", e.velocity);
            assert!(e.acceleration < 0.5 * jump, "{}", e.acceleration);
        }
    }

    #[test]
    fn relative_tolerance_uses_the_extent() {
        let curve = helix(2.0, 2.0, 1.0);
        let path: Path<f64, 3, 256> = compile(
            &Along::new(&curve, &Quintic(0.5)),
            10_000.0,
            &CompileOptions::new(),
        )
        .unwrap();
        // extent: x and y span ≈ 4 units (at the knots: slightly less)
        assert!(path.tolerance() > 3.9e-4 && path.tolerance() <= 4e-4);
    }

    #[test]
    fn peaks_bound_the_path() {
        peaks_bound_the_path_on();
    }

    fn peaks_bound_the_path_on() {
        let curve = helix(2.0, 2.0, 1.0);
        let timing = Quintic(0.5);
        let path: Box<Path<f64, 3, 4096>> = compile_boxed(
            &Along::new(&curve, &timing),
            10_000.0,
            &CompileOptions::new().with_tolerance(1e-7),
        )
        .unwrap();
        let (mut v, mut a, mut v_path) = (0.0_f64, 0.0_f64, 0.0_f64);
        for k in 0..=path.ticks() {
            let (_, ve, ae) = exact(&curve, &timing, &path, f64::from(k));
            v = v.max(libm::sqrt(ve.iter().map(|x| x * x).sum()));
            a = a.max(libm::sqrt(ae.iter().map(|x| x * x).sum()));
            let vp = path.eval(f64::from(k)).velocity;
            v_path = v_path.max(libm::sqrt(vp.iter().map(|x| x * x).sum()));
        }
        // an upper bound of the compiled polynomial's speed, close to the law's
        assert!(
            path.peak_velocity() >= v_path && path.peak_velocity() < v * 1.001,
            "{} {v_path} {v}",
            path.peak_velocity()
        );
        assert!((path.peak_acceleration() - a).abs() < a * 1e-3);
        // default limits: the plan is assumed to have used 3/4
        assert!((path.acceleration_limit() - path.peak_acceleration() / 0.75).abs() < 1e-9);
        assert!((path.jerk_limit() - path.peak_jerk() / 0.75).abs() < 1e-6);
        let with: Box<Path<f64, 3, 4096>> = compile_boxed(
            &Along::new(&curve, &timing),
            10_000.0,
            &CompileOptions::new()
                .with_tolerance(1e-7)
                .with_limits(1e4, 1e6),
        )
        .unwrap();
        assert_eq!((with.acceleration_limit(), with.jerk_limit()), (1e4, 1e6));
    }

    #[test]
    fn a_tangential_law_without_a_reserve_stands_at_its_tangential_limit() {
        // v²/r = 40 on a circle of radius 2.5 at v = 10: the centripetal part, which the
        // trapezoid law does not limit, is four times its tangential limit
        let circle = strak_curves::Nurbs::<[f64; 2], 9, 12>::circle([0.0, 0.0], 2.5).unwrap();
        let o = CompileOptions::new().with_tolerance(1e-6);
        let full = crate::PathTiming::<_, 256, 4>::trapezoid(&circle, 10.0, 10.0).unwrap();
        // at its limit of 10 it leaves nothing for the default share of ¼
        let r: Result<Box<Path<f64, 2, 1024>>, _> = compile_boxed(&full, 1_000.0, &o);
        let quantity = Quantity::TangentialAcceleration;
        assert_eq!(r.err(), Some(Error::FeedReserveExceeded { quantity }));
        // planned at ¾ of the machine's 10 and compiled with the machine's limits, a ramp
        // may add what the compiled motion leaves of 10: about the remaining quarter, 2.5
        // (the compiled tangential peak is 7.47)
        let kept = crate::PathTiming::<_, 256, 4>::trapezoid(&circle, 10.0, 7.5).unwrap();
        let path: Box<Path<f64, 2, 1024>> =
            compile_boxed(&kept, 1_000.0, &o.with_limits(10.0, 1e6)).unwrap();
        assert!(
            path.peak_acceleration() > 35.0,
            "{}",
            path.peak_acceleration()
        );
        let ramp = path.acceleration_limit() - path.peak_acceleration();
        assert!(ramp > 2.5 && ramp < 2.55, "{ramp}");
    }

    /// Forwards a time law with or without its breaks and its limits (with its reserve).
    struct Forward<'a, T> {
        law: &'a T,
        breaks: bool,
        limits: bool,
    }
    impl<T: Timing> Timing for Forward<'_, T> {
        fn duration(&self) -> f64 {
            self.law.duration()
        }
        fn param(&self, t: f64) -> (f64, f64) {
            self.law.param(t)
        }
        fn breaks(&self, out: &mut dyn FnMut(f64)) {
            if self.breaks {
                self.law.breaks(out);
            }
        }
        fn limits(&self) -> Option<crate::MotionLimits> {
            self.law.limits().filter(|_| self.limits)
        }
        fn feed_reserve(&self) -> Option<FeedReserve> {
            self.law.feed_reserve().filter(|_| self.limits)
        }
    }

    /// An S-curve along a straight line compiled with or without its breaks and limits:
    /// the compiled peak jerk relative to `j_max`, and the path's time scale.
    fn scurve_line_jerk(rate: f64, tol: f64, breaks: bool, limits: bool) -> (f64, f64) {
        let line = Bezier::new([[0.0_f64, 0.0], [30.0, 40.0]]).unwrap();
        let lim = crate::Limits::<2>::new(97.3, 1130.7, 21_713.0).unwrap();
        let plan = crate::PathTiming::<_, 64, 4>::scurve(&line, &lim).unwrap();
        let o = CompileOptions::new().with_relative_tolerance(tol);
        let law = Forward {
            law: &plan,
            breaks,
            limits,
        };
        let path: Box<Path<f64, 2, 4096>> =
            compile_boxed(&Along::new(&line, &law), rate, &o).unwrap();
        // the plan keeps the feed reserve: it uses 1 − share of the jerk limit
        let planned = (1.0 - crate::PlanOptions::DEFAULT_FEED_SHARE) * lim.jerk();
        (path.peak_jerk() / planned, path.time_scale())
    }

    #[test]
    fn knots_on_the_breaks_keep_the_jerk() {
        for rate in [1_000.0, 10_000.0] {
            for tol in [1e-4, 1e-6] {
                let (with, _) = scurve_line_jerk(rate, tol, true, false);
                let (without, _) = scurve_line_jerk(rate, tol, false, false);
                std::println!(
                    "{rate} Hz tol {tol:e}: jerk {with:.4} (without breaks {without:.4})"
                );
                // the breaks sit within half a tick of a knot (measured: 0.9997, 1.040
                // at 1 kHz; 1.0017 at 10 kHz)
                assert!(with > 0.99 && with < 1.05, "{rate} {tol}: {with}");
                // without them the spline overshoots the jerk steps (measured: 1.10,
                // 1.13 at 1 kHz; 1.06, 1.03 at 10 kHz)
                assert!(without > with + 0.02, "{rate} {tol}: {without}");
            }
        }
    }

    #[test]
    fn the_laws_limits_are_kept_by_slowing_down() {
        for rate in [1_000.0, 10_000.0] {
            for tol in [1e-4, 1e-6] {
                let (free, free_scale) = scurve_line_jerk(rate, tol, true, false);
                let (kept, scale) = scurve_line_jerk(rate, tol, true, true);
                std::println!(
                    "{rate} Hz tol {tol:e}: jerk {kept:.6} at time scale {scale:.6} \
                     (unchecked: {free:.6})"
                );
                assert!(kept <= 1.0 + 1e-12, "{rate} {tol}: {kept}");
                // slowed down by the cube root of the excess (measured at most 1.3 %)
                let excess = libm::cbrt(free.max(1.0));
                assert!(scale <= free_scale && scale * excess >= 0.98 * free_scale);
                if free > 1.0 + 1e-9 {
                    assert!(scale < free_scale, "{rate} {tol}: not slowed down");
                }
            }
        }
    }

    /// Jerk phases of 4.25 ticks (all breaks close): with the law's limits and an `f64`
    /// curve every break sits in a piece of one tick; without limits, or with an `f32`
    /// curve (whose rounding a one-tick piece would turn into jerk), no break gets a knot.
    #[test]
    fn one_tick_pieces_hold_the_breaks_of_short_phases() {
        let lim = crate::Limits::<2>::new(21.23, 823.0, 193_600.0).unwrap();
        let one_tick =
            |path: &Path<f64, 2, 4096>| path.pieces().iter().filter(|p| p.ticks() == 1).count();
        let o = CompileOptions::new();
        let line = Bezier::new([[0.0_f64, 0.0], [52.255, 52.255]]).unwrap();
        // planned for 100 kHz: its jerk phases last 16 ticks there, a fraction of a tick
        // at the 1 kHz it is compiled for
        let fine = crate::PlanOptions::new().with_rate(100_000.0);
        let plan = crate::PathTiming::<_, 64, 4>::plan(&line, &lim, &fine).unwrap();
        let mut breaks = 0;
        plan.breaks(&mut |_| breaks += 1);
        assert_eq!(breaks, 6);
        let kept: Box<Path<f64, 2, 4096>> = compile_boxed(&plan, 1_000.0, &o).unwrap();
        assert_eq!(one_tick(&kept), breaks, "{:?}", kept.pieces().len());
        let law = Forward {
            law: &plan,
            breaks: true,
            limits: false,
        };
        let free: Box<Path<f64, 2, 4096>> =
            compile_boxed(&Along::new(&line, &law), 1_000.0, &o).unwrap();
        assert_eq!(one_tick(&free), 0);
        let line32 = Bezier::new([[0.0_f32, 0.0], [52.255, 52.255]]).unwrap();
        let plan32 = crate::PathTiming::<_, 64, 4>::plan(&line32, &lim, &fine).unwrap();
        let coarse: Box<Path<f64, 2, 4096>> = compile_boxed(&plan32, 1_000.0, &o).unwrap();
        assert_eq!(one_tick(&coarse), 0);
    }

    #[test]
    fn limit_exceeded_beyond_the_largest_slowdown() {
        let line = Bezier::new([[0.0_f64, 0.0], [30.0, 40.0]]).unwrap();
        let lim = crate::Limits::<2>::new(97.3, 1130.7, 21_713.0).unwrap();
        let plan = crate::PathTiming::<_, 64, 4>::scurve(&line, &lim).unwrap();
        // at 1 kHz the fit overshoots the law (see above): no slow-down allowed
        let strict = CompileOptions::new().with_max_slowdown(1.0);
        let r: Result<Box<Path<f64, 2, 4096>>, _> = compile_boxed(&plan, 1_000.0, &strict);
        assert!(matches!(r, Err(Error::LimitExceeded { .. })), "{r:?}");
        // a law so long that its ticks overflow to ∞ (∞ ticks, not one): the planner
        // refuses such a plan itself, so a law of its own
        struct Crawl;
        impl Timing for Crawl {
            fn duration(&self) -> f64 {
                1.0e305
            }
            fn param(&self, t: f64) -> (f64, f64) {
                (t / 1.0e305, 1.0 / 1.0e305)
            }
        }
        let crawl = crate::Limits::<2>::new(1.5e-304, 1130.7, 21_713.0).unwrap();
        let planned = crate::PathTiming::<_, 64, 4>::scurve(&line, &crawl);
        assert_eq!(planned.err(), Some(Error::TooLong));
        let r: Result<Path<f64, 2, 8>, _> =
            compile(&Along::new(&line, &Crawl), 1_000.0, &CompileOptions::new());
        assert_eq!(r.err(), Some(Error::TooLong));
    }

    #[test]
    fn piece_lengths_respect_the_maximum() {
        let path: Path<f64, 2, 64> = compile(
            &Along::new(&line(), &Linear(1.0)),
            1000.0,
            &CompileOptions::new().with_max_piece_ticks(100),
        )
        .unwrap();
        assert_eq!(path.pieces().len(), 10);
        assert!(path.pieces().iter().all(|p| p.ticks() == 100));
        let starts: std::vec::Vec<u32> = path.pieces().iter().map(|p| p.start()).collect();
        assert_eq!(starts, [0, 100, 200, 300, 400, 500, 600, 700, 800, 900]);
        let _ = line().domain();
    }
}
