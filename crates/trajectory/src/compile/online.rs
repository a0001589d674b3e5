//! Compiling an online move ([`OnlineMove`]) into a path: pieces on the tick grid whose
//! samples are the move's states.
//!
//! An axis's motion is a cubic in time between its switching times, which lie anywhere
//! between ticks. The pieces' boundaries are the ticks just before and just after every
//! switching time of every axis (and at most every `max_piece_ticks` ticks, the bound of
//! playback's rounding in the number format). A piece of two or more ticks then holds no
//! switch: it is the axis's cubic, exactly (forward differences of its Taylor polynomial in
//! ticks). A piece of one tick may hold switches: it starts on the exact state, and its
//! three chains end on the exact state of the next tick (position cubic through the start
//! position, velocity and acceleration and the end position; velocity quadratic through
//! both velocities with the start acceleration; acceleration linear between both). So every
//! sample at a tick is the move's state at that tick, rounded once into the number format;
//! between ticks (feed changes) a one-tick piece follows its chains, whose acceleration is
//! the chord of the move's and whose velocity deviates from the move's by at most about
//! `0.05·J·T²`.

use super::options::CompileOptions;
use super::{check_playback_bound, round_state};
use crate::error::Error;
use crate::num::{Number, RATE_RANGE};
use crate::online::{
    AxisLimits, AxisProfile, Kinematics, MAX_PHASES, MoveOptions, OnlineMove, Real,
};
use crate::path::{AxisState, Path, PathMeta, RampBasis, Sample};

/// An axis's motion with its phases' start times, read in `f64` (every value converted
/// exactly where it is used: the profile is not copied).
struct Axis<'a, R> {
    profile: &'a AxisProfile<R>,
    starts: [f64; MAX_PHASES + 1],
}

impl<'a, R: Real> Axis<'a, R> {
    fn new(profile: &'a AxisProfile<R>) -> Self {
        let mut starts = [0.0; MAX_PHASES + 1];
        for i in 0..MAX_PHASES {
            starts[i + 1] = starts[i] + profile.phases()[i].duration.to_f64();
        }
        Axis { profile, starts }
    }

    /// Phase `i`'s jerk and duration (`None` past the last phase).
    fn jerk_phase(&self, i: usize) -> Option<(f64, f64)> {
        let p = self.profile.phases().get(i)?;
        Some((p.jerk.to_f64(), p.duration.to_f64()))
    }

    /// The state at the start of phase `i` (the end state for `i = MAX_PHASES`).
    fn state(&self, i: usize) -> Option<Kinematics<f64>> {
        self.profile.states().get(i).map(|k| k.to_f64())
    }

    /// The state at the end.
    fn end(&self) -> Kinematics<f64> {
        self.profile.end().to_f64()
    }

    /// The duration in seconds.
    fn duration(&self) -> f64 {
        self.profile.duration().to_f64()
    }

    /// The phase that holds time `t` (`MAX_PHASES` from the end on).
    fn phase(&self, t: f64) -> usize {
        (0..MAX_PHASES)
            .find(|&i| t < self.starts[i + 1] && self.profile.phases()[i].duration > R::ZERO)
            .unwrap_or(MAX_PHASES)
    }

    /// The state and jerk at `t` on the polynomial of phase `i` (after the end: the end
    /// state continued without jerk).
    fn eval(&self, i: usize, t: f64) -> (Kinematics<f64>, f64) {
        match (self.state(i), self.jerk_phase(i)) {
            (Some(s), Some((jerk, _))) => (s.advance(jerk, t - self.starts[i]), jerk),
            _ => (self.end().advance(0.0, t - self.starts[MAX_PHASES]), 0.0),
        }
    }

    /// The state at `t` (of the phase that holds it).
    fn at(&self, t: f64) -> Kinematics<f64> {
        self.eval(self.phase(t), t).0
    }

    /// Whether a switching time lies strictly between ticks `k` and `k + 1`.
    fn switches_within(&self, k: u32, rate: f64) -> bool {
        let (lo, hi) = (f64::from(k), f64::from(k) + 1.0);
        self.starts[1..]
            .iter()
            .zip(self.profile.phases())
            .any(|(&s, p)| {
                let x = s * rate;
                p.duration > R::ZERO && x > lo + SNAP && x < hi - SNAP
            })
    }

    /// The first boundary after tick `k`: the tick before or after a switching time.
    fn next_boundary(&self, k: u32, rate: f64, ticks: u32) -> u32 {
        let mut next = ticks;
        for (&s, p) in self.starts[1..].iter().zip(self.profile.phases()) {
            if p.duration <= R::ZERO {
                continue;
            }
            let x = s * rate;
            for b in [libm::floor(x + SNAP), libm::ceil(x - SNAP)] {
                if b > f64::from(k) && b < f64::from(next) {
                    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                    let b = b as u32;
                    next = b;
                }
            }
        }
        next
    }
}

/// A switching time within this many ticks of a tick is on it.
const SNAP: f64 = 1e-9;

/// Compiles an online move solved on a tick grid ([`MoveOptions::with_rate`]) into a path
/// of at most `P` pieces, in the number format `N`. Every sample at a tick is the move's
/// state at that tick (rounded once into `N`), the first is the start state and the last
/// the target (position exactly as given, for a position move).
///
/// [`MoveOptions::with_rate`]: crate::MoveOptions::with_rate
///
/// # Errors
/// * [`Error::InvalidRate`]: the move was not solved on a tick grid;
/// * [`Error::EmptyPath`]: the move takes no time;
/// * [`Error::CapacityExceeded`]: more than `P` pieces needed;
/// * [`Error::OutOfRange`], [`Error::PlaybackBoundExceeded`]: a value does not fit `N`, or
///   playback in `N` rounds by more than `10⁻⁴` of the motion's extent.
///
/// ```
/// use strak_trajectory::{AxisLimits, Kinematics, MoveOptions, OnlineMove, Path, Sampler, compile_move};
/// let limits = [AxisLimits::new(500.0_f64, 5_000.0, 100_000.0)?; 2];
/// let start = [Kinematics::new(0.0, 100.0, 0.0), Kinematics::at_rest(0.0)];
/// let target = [Kinematics::at_rest(30.0), Kinematics::at_rest(-20.0)];
/// let m = OnlineMove::solve(&start, &target, &limits, &MoveOptions::new().with_rate(1_000.0))?;
/// let path: Path<f32, 2, 64> = compile_move(&m)?;
/// let mut sampler = Sampler::new(&path);
/// let first = sampler.next();
/// assert_eq!((first.position, first.velocity), ([0.0, 0.0], [100.0, 0.0]));
/// let mut last = first;
/// while !sampler.is_finished() {
///     last = sampler.next();
/// }
/// assert_eq!(last.position, [30.0, -20.0]); // the target, exactly
/// # Ok::<(), strak_trajectory::Error>(())
/// ```
pub fn compile_move<N, R, const A: usize, const P: usize>(
    m: &OnlineMove<R, A>,
) -> Result<Path<N, A, P>, Error>
where
    N: Number,
    R: Real,
{
    let mut path = Path::new();
    compile_move_into(m, &mut path)?;
    Ok(path)
}

/// [`compile_move`] into caller storage, in place; on an error the path is left empty.
///
/// # Errors
/// As [`compile_move`].
pub fn compile_move_into<N, R, const A: usize, const P: usize>(
    m: &OnlineMove<R, A>,
    path: &mut Path<N, A, P>,
) -> Result<(), Error>
where
    N: Number,
    R: Real,
{
    path.clear();
    let result = write_move(m, path, false);
    if result.is_err() {
        path.clear();
    }
    result
}

/// Takes over a running motion: solves the move from `last`, the sample a running sampler
/// played last, to `target` (in place into `m`) and compiles it into `path` (in place). The
/// path's first sample is `last` again; a sampler of `path` whose first sample is skipped
/// plays on from the next tick, without a jump in position, velocity or acceleration. The
/// running sampler may be a path's, an earlier move's, or anything that yields samples in
/// `N`. A quick stop is a take-over with targets at rest and
/// [`MoveOptions::quick_stop`].
///
/// `last` is converted into `R` as [`Sample::kinematics`] does; `options` needs the
/// sampler's rate ([`MoveOptions::with_rate`]). When `last` already is the target (a quick
/// stop or a hold at rest), the move takes no time and the path stands on it for one tick.
///
/// A sample carries the playback's rounding, which [`Synchronization::Phase`] must allow
/// for to keep a motion along a line on it: about one rounding of each value per tick of
/// a piece is assumed; where the running path's rounding is larger (`Q40` positions in
/// long pieces), give its bounds with [`MoveOptions::with_start_rounding`]
/// (`absolute` at least the largest of [`playback_bound`](crate::PathHeader::playback_bound)
/// and [`channel_bounds`](Path::channel_bounds)).
///
/// [`Synchronization::Phase`]: crate::Synchronization::Phase
///
/// # Errors
/// As [`OnlineMove::solve_in_place`] (a target outside the limits, …) and
/// [`compile_move`] (but not [`Error::EmptyPath`]); on an error `path` is empty.
///
/// ```
/// use strak_trajectory::{AxisLimits, Kinematics, MoveOptions, OnlineMove, Path, Sampler, take_over_into};
/// let limits = [AxisLimits::new(500.0_f32, 5_000.0, 100_000.0)?];
/// let options = MoveOptions::new().with_rate(1_000.0);
/// let mut m = OnlineMove::<f32, 1>::new();
/// let (mut first, mut second) = (Path::<f32, 1, 64>::new(), Path::<f32, 1, 64>::new());
/// m.solve_in_place(&[Kinematics::at_rest(0.0)], &[Kinematics::at_rest(100.0)], &limits, &options)?;
/// strak_trajectory::compile_move_into(&m, &mut first)?;
/// let mut sampler = Sampler::new(&first);
/// let mut last = sampler.next();
/// for _ in 0..60 {
///     last = sampler.next(); // tick 60: moving
/// }
/// // A new target at tick 61, going back.
/// take_over_into(&last, &[Kinematics::at_rest(-20.0)], &limits, &options, &mut m, &mut second)?;
/// let mut sampler = Sampler::new(&second);
/// assert_eq!(sampler.next().position, last.position); // the sample just played
/// let next = sampler.next(); // tick 61
/// assert!((next.position[0] - last.position[0]).abs() <= 500.0 / 1_000.0);
/// let mut end = next;
/// while !sampler.is_finished() {
///     end = sampler.next();
/// }
/// assert_eq!(end.position, [-20.0]);
/// # Ok::<(), strak_trajectory::Error>(())
/// ```
pub fn take_over_into<N, R, const A: usize, const P: usize>(
    last: &Sample<N::Out, A>,
    target: &[Kinematics<R>; A],
    limits: &[AxisLimits<R>; A],
    options: &MoveOptions,
    m: &mut OnlineMove<R, A>,
    path: &mut Path<N, A, P>,
) -> Result<(), Error>
where
    N: Number,
    R: Real,
{
    path.clear();
    // The sample carries the playback's rounding: within a piece of at most 256 ticks,
    // about one rounding of each value per tick (relative in a float, absolute in `Q40`),
    // and its conversion into `N::Out`.
    let (at_one, at_zero) = (N::rounding_error(1.0), N::rounding_error(0.0));
    let (relative, absolute) = options.start_rounding;
    let options = options.with_start_rounding(
        relative.max(256.0 * (at_one - at_zero)),
        absolute.max(256.0 * at_zero + 2.0 * N::OUT_ERROR),
    );
    let result = m
        .solve_in_place(&last.kinematics(), target, limits, &options)
        .and_then(|()| write_move(m, path, true));
    if result.is_err() {
        path.clear();
    }
    result
}

fn write_move<N, R, const A: usize, const P: usize>(
    m: &OnlineMove<R, A>,
    path: &mut Path<N, A, P>,
    stand: bool,
) -> Result<(), Error>
where
    N: Number,
    R: Real,
{
    let rate = m.rate_hz().ok_or(Error::InvalidRate)?;
    if !(rate >= RATE_RANGE.0 && rate <= RATE_RANGE.1) {
        return Err(Error::InvalidRate);
    }
    let exact = m.duration().to_f64() * rate;
    let ticks = libm::round(exact);
    if ticks.is_nan() || ticks < 0.0 || (ticks == 0.0 && !stand) {
        return Err(Error::EmptyPath);
    }
    if (ticks - exact).abs() > 1e-6 * ticks {
        return Err(Error::InvalidRate);
    }
    // A move that takes no time (the start is the target) stands for one tick.
    let ticks = ticks.max(1.0);
    if ticks > f64::from(u32::MAX - 1) {
        return Err(Error::TooLong);
    }
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let ticks = ticks as u32;
    let axes: [Axis<'_, R>; A] = core::array::from_fn(|i| Axis::new(&m.profiles()[i]));
    let end_time = f64::from(ticks) / rate;
    let ends: [Kinematics<f64>; A] =
        core::array::from_fn(|i| end_state(m, &axes[i], i, end_time, rate));
    let (meta, largest) = meta::<N, R, A>(m, &axes, rate);
    write_pieces(
        &axes,
        &ends,
        rate,
        ticks,
        longest::<N>(&meta, largest),
        path,
    )?;
    path.header.meta = meta;
    write_end(&ends, path)?;
    path.seal()?;
    check_playback_bound(&path.header)
}

/// The pieces between the boundaries (every switch's neighbouring ticks, at most
/// `max_piece_ticks` apart).
fn write_pieces<N: Number, R: Real, const A: usize, const P: usize>(
    axes: &[Axis<'_, R>; A],
    ends: &[Kinematics<f64>; A],
    rate: f64,
    ticks: u32,
    longest: u32,
    path: &mut Path<N, A, P>,
) -> Result<(), Error> {
    let period = 1.0 / rate;
    let mut k = 0;
    while k < ticks {
        let mut next = ticks.min(k.saturating_add(longest));
        for axis in axes {
            next = next.min(axis.next_boundary(k, rate, ticks));
        }
        let n = next - k;
        let mut states = [AxisState::ZERO; A];
        for ((state, axis), end) in states.iter_mut().zip(axes).zip(ends) {
            let start = || axis.at(f64::from(k) * period);
            let s = if next == ticks {
                // The last piece ends on the path's end exactly (the target, not the
                // solver's rounding of it).
                chord_state(&start(), end, n, period)
            } else if n == 1 && axis.switches_within(k, rate) {
                chord_state(&start(), &axis.at(f64::from(next) * period), 1, period)
            } else {
                cubic_state(axis, k, next, period)
            };
            *state = round_state(&s)?;
        }
        let piece = crate::path::Piece {
            axes: states,
            start: k,
            ticks: n,
        };
        path.pieces
            .push(piece)
            .map_err(|_| Error::CapacityExceeded {
                capacity: P,
                required: P + 1,
            })?;
        k = next;
    }
    Ok(())
}

/// The forward-difference state of the axis's cubic on ticks `k ..= next` (no switch
/// inside): its Taylor polynomial at tick `k` in the tick index.
fn cubic_state<R: Real>(axis: &Axis<'_, R>, k: u32, next: u32, period: f64) -> AxisState<f64> {
    let t0 = f64::from(k) * period;
    let mid = (f64::from(k) + f64::from(next)) * 0.5 * period;
    // The state of the phase that holds `t0`, the jerk of the one that holds the piece (they
    // differ only by a switch within `SNAP` of the tick).
    let s = axis.at(t0);
    let j = axis.eval(axis.phase(mid), t0).1;
    let (t, tt) = (period, period * period);
    // The forward differences of p + v·τ + a·τ²/2 + j·τ³/6 at τ = i·T, with the state's
    // own position, velocity and acceleration (not recovered from the differences, so that
    // they are the move's to the last bit).
    AxisState {
        position: s.position,
        delta1: t * (s.velocity + t * (0.5 * s.acceleration + t * (j / 6.0))),
        delta2: tt * (s.acceleration + t * j),
        delta3: tt * t * j,
        velocity: s.velocity,
        velocity_delta1: t * (s.acceleration + 0.5 * t * j),
        velocity_delta2: tt * j,
        acceleration: s.acceleration,
        acceleration_delta: t * j,
    }
}

/// The state of a piece of `n` ticks from the state `s` that ends exactly on the state `e`
/// in every chain: position `a + b·i + c·i² + d·i³` with the start's value and derivatives,
/// through the end position; velocity `v₀ + a₀T·i + q·i²` through the end velocity;
/// acceleration linear between both. For a piece on one cubic phase whose end is that
/// phase's end this is the phase itself (up to rounding).
pub(super) fn chord_state(
    s: &Kinematics<f64>,
    e: &Kinematics<f64>,
    n: u32,
    period: f64,
) -> AxisState<f64> {
    let n = f64::from(n);
    let tt = period * period;
    let (a, b, c) = (s.position, s.velocity * period, s.acceleration * tt * 0.5);
    let d = (e.position - (a + n * (b + n * c))) / (n * n * n);
    let q = (e.velocity - s.velocity - s.acceleration * period * n) / (n * n);
    AxisState {
        position: a,
        delta1: b + c + d,
        delta2: 2.0 * c + 6.0 * d,
        delta3: 6.0 * d,
        velocity: s.velocity,
        velocity_delta1: s.acceleration * period + q,
        velocity_delta2: 2.0 * q,
        acceleration: s.acceleration,
        acceleration_delta: (e.acceleration - s.acceleration) / n,
    }
}

/// The longest piece whose position additions (one per tick, each rounded at the largest
/// position `largest`) round by at most half the path's tolerance: at most
/// [`CompileOptions::DEFAULT_MAX_PIECE_TICKS`] (all of them in `Q40`, whose additions are
/// exact), at least one.
fn longest<N: Number>(meta: &PathMeta, largest: f64) -> u32 {
    let per_tick = N::addition_error(largest);
    let cap = f64::from(CompileOptions::DEFAULT_MAX_PIECE_TICKS);
    let n = if per_tick > 0.0 {
        libm::floor(0.5 * meta.tolerance / per_tick).clamp(1.0, cap)
    } else {
        cap
    };
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let n = n as u32;
    n
}

/// The path's description, and the largest position of any axis: the move's peaks
/// (Euclidean bounds from each axis's largest values), its axes' limits as the feed ramps'
/// limits, and the tolerance that playback's rounding must stay within: `10⁻⁴` of the
/// motion's extent, and at least 16 times the rounding of a value of `N` at the largest
/// position (a smaller one could not be met: a short move far from the origin in `f32`).
fn meta<N: Number, R: Real, const A: usize>(
    m: &OnlineMove<R, A>,
    axes: &[Axis<'_, R>; A],
    rate: f64,
) -> (PathMeta, f64) {
    let (mut v, mut a, mut j, mut a_lim, mut j_lim) = (0.0, 0.0, 0.0, 0.0, 0.0);
    let (mut extent, mut big) = (0.0_f64, 0.0_f64);
    for (axis, l) in axes.iter().zip(m.limits()) {
        let (mut vm, mut am, mut jm) = (0.0_f64, 0.0_f64, 0.0_f64);
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for i in 0..MAX_PHASES {
            let (Some(s), Some((jerk, duration))) = (axis.state(i), axis.jerk_phase(i)) else {
                break;
            };
            vm = vm.max(s.velocity.abs());
            am = am.max(s.acceleration.abs());
            jm = jm.max(jerk.abs());
            lo = lo.min(s.position);
            hi = hi.max(s.position);
            // The velocity's extreme inside the phase.
            if jerk != 0.0 {
                let tz = -s.acceleration / jerk;
                if tz > 0.0 && tz < duration {
                    let x = s.advance(jerk, tz);
                    vm = vm.max(x.velocity.abs());
                    lo = lo.min(x.position);
                    hi = hi.max(x.position);
                }
            }
        }
        let e = axis.end();
        vm = vm.max(e.velocity.abs());
        am = am.max(e.acceleration.abs());
        extent = extent.max(hi.max(e.position) - lo.min(e.position));
        big = big.max(hi.abs()).max(lo.abs());
        v += vm * vm;
        a += am * am;
        j += jm * jm;
        let (al, jl) = (
            l.acceleration_max()
                .to_f64()
                .max(-l.acceleration_min().to_f64()),
            l.jerk().to_f64(),
        );
        a_lim += al * al;
        j_lim += jl * jl;
    }
    let tolerance = (CompileOptions::DEFAULT_RELATIVE_TOLERANCE * extent)
        .max(1e-12 * (1.0 + big))
        .max(16.0 * (N::rounding_error(big) + N::OUT_ERROR));
    let meta = PathMeta {
        // Whole ticks, at least the one a move that takes no time stands for.
        plan_duration: m.duration().to_f64().max(1.0 / rate),
        tolerance,
        ramp: RampBasis {
            rate,
            peak_velocity: libm::sqrt(v),
            peak_acceleration: libm::sqrt(a),
            peak_jerk: libm::sqrt(j),
            acceleration_limit: libm::sqrt(a_lim).max(libm::sqrt(a)),
            jerk_limit: libm::sqrt(j_lim).max(libm::sqrt(j)),
            feed_share: CompileOptions::DEFAULT_FEED_SHARE,
        },
    };
    (meta, big)
}

/// Where axis `i` ends: its target (for a position move its position exactly as given; for
/// a velocity move, or an axis that arrived early and moves on, the state at the end).
fn end_state<R: Real, const A: usize>(
    m: &OnlineMove<R, A>,
    axis: &Axis<'_, R>,
    i: usize,
    end: f64,
    rate: f64,
) -> Kinematics<f64> {
    let s = axis.at(end);
    // Durations are whole ticks: an axis that arrives early does so by a tick at least.
    let arrives = (end - axis.duration()) * rate < 0.5;
    let position_move = m.interface() == crate::online::Interface::Position;
    match m.targets().get(i) {
        Some(t) if arrives => Kinematics::new(
            if position_move {
                t.position.to_f64()
            } else {
                s.position
            },
            t.velocity.to_f64(),
            t.acceleration.to_f64(),
        ),
        _ => s,
    }
}

/// The path's end, in the sample type.
fn write_end<N: Number, const A: usize, const P: usize>(
    ends: &[Kinematics<f64>; A],
    path: &mut Path<N, A, P>,
) -> Result<(), Error> {
    let out = |v: f64| N::out_from_f64(v).ok_or(Error::OutOfRange);
    let e = &mut path.header.end;
    for (i, s) in ends.iter().enumerate() {
        e.position[i] = out(s.position)?;
        e.velocity[i] = out(s.velocity)?;
        e.acceleration[i] = out(s.acceleration)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    extern crate std;

    use std::boxed::Box;
    use std::vec::Vec;

    use super::*;
    use crate::num::Q40;
    use crate::online::testing::{Rng, case, target};
    use crate::online::{AxisLimits, MoveOptions, Synchronization};
    use crate::play::{Kernel, Sampler};
    use strak_curves::Scalar;

    const RATE: f64 = 1_000.0;
    type Move = OnlineMove<f64, 3>;

    /// A random 3-axis move on the 1 kHz grid (at most 20 s), with its limits. A fifth are
    /// unsynchronized, with targets without acceleration (an axis that arrives early moves
    /// on at its target velocity).
    fn random_move(rng: &mut Rng, k: f64) -> Move {
        loop {
            let mut cases: [_; 3] = core::array::from_fn(|_| case(rng, k));
            let none = rng.next() < 0.2;
            if none {
                for c in &mut cases {
                    c.1.acceleration = 0.0;
                }
            }
            let sync = if none {
                Synchronization::None
            } else {
                Synchronization::Time
            };
            let options = MoveOptions::new()
                .with_rate(RATE)
                .with_synchronization(sync);
            let m = OnlineMove::solve(
                &cases.map(|c| c.0),
                &cases.map(|c| c.1),
                &cases.map(|c| c.2),
                &options,
            )
            .expect("a move");
            if m.duration() < 20.0 && m.duration() > 0.0 {
                return m;
            }
        }
    }

    /// Every sample of a path.
    fn samples<N: Kernel>(path: &Path<N, 3, 512>) -> Vec<Sample<N::Out, 3>> {
        let mut sampler = Sampler::new(path);
        let mut out = Vec::new();
        while !sampler.is_finished() {
            out.push(sampler.next());
        }
        out
    }

    /// A sample's positions, velocities and accelerations in `f64`.
    fn in_f64<T: Scalar>(s: &Sample<T, 3>) -> [[f64; 3]; 3] {
        [
            s.position.map(Scalar::to_f64),
            s.velocity.map(Scalar::to_f64),
            s.acceleration.map(Scalar::to_f64),
        ]
    }

    /// Every sample of the compiled move, in `f64`.
    fn play<N: Kernel>(path: &Path<N, 3, 512>) -> Vec<[[f64; 3]; 3]> {
        samples(path).iter().map(in_f64).collect()
    }

    /// The samples equal the move's states at their ticks, within `tol(magnitude)`.
    fn assert_samples_are_states<N: Kernel>(m: &Move, tol: impl Fn(f64) -> f64, what: &str) {
        let path: Box<Path<N, 3, 512>> =
            Box::new(compile_move(m).unwrap_or_else(|e| panic!("{what}: {e}")));
        let bound = path.playback_bound();
        let samples = play(&path);
        assert_eq!(samples.len(), path.ticks() as usize + 1, "{what}");
        for (k, s) in samples.iter().enumerate() {
            #[allow(clippy::cast_precision_loss)]
            let t = k as f64 / RATE;
            let want = m.at(t);
            for i in 0..3 {
                let (w, g) = (&want[i], s);
                for (x, y) in [
                    (w.position, g[0][i]),
                    (w.velocity, g[1][i]),
                    (w.acceleration, g[2][i]),
                ] {
                    assert!(
                        (x - y).abs() <= bound + tol(x.abs()),
                        "{what}: tick {k} axis {i}: {y} vs {x}"
                    );
                }
            }
        }
        let end = path.end_position().map(Scalar::to_f64);
        let last = samples.last().expect("samples")[0];
        assert_eq!(end, last, "{what}");
        if m.synchronization() == Synchronization::Time {
            for (e, t) in end.iter().zip(m.targets()) {
                assert_eq!(
                    *e,
                    N::out_from_f64(t.position).expect("in range").to_f64(),
                    "{what}"
                );
            }
        }
    }

    #[test]
    fn every_sample_is_the_moves_state() {
        let mut rng = Rng(0x5DEE_CE66_D1CE_4E5B);
        for n in 0..60 {
            let m = random_move(&mut rng, 1.2);
            let what = std::format!("move {n}: {m:?}");
            // The playback bound of the path, and the rounding of a value into the format.
            assert_samples_are_states::<f64>(&m, |x| 1e-12 * (1.0 + x), &what);
            assert_samples_are_states::<f32>(
                &m,
                |x| 2.0 * f64::from(f32::EPSILON) * (1.0 + x),
                &what,
            );
            assert_samples_are_states::<Q40>(&m, |_| 1e-9, &what);
        }
    }

    /// Finite differences of the samples: `(x[k+1] − x[k])·f` of the positions, velocities
    /// and accelerations are averages of the velocity, acceleration and jerk over the tick,
    /// so they keep the limits (here within 10⁻⁹ relative, for rounding).
    fn assert_differences_keep_limits(
        samples: &[[[f64; 3]; 3]],
        limits: &[AxisLimits<f64>; 3],
        what: &str,
    ) {
        for w in samples.windows(2) {
            for (i, l) in limits.iter().enumerate() {
                let d = |q: usize| (w[1][q][i] - w[0][q][i]) * RATE;
                let slack = |x: f64| x * (1.0 + 1e-9) + 1e-9;
                assert!(
                    d(0) <= slack(l.velocity_max()) && -d(0) <= slack(-l.velocity_min()),
                    "{what}: v {} axis {i}",
                    d(0)
                );
                assert!(
                    d(1) <= slack(l.acceleration_max()) && -d(1) <= slack(-l.acceleration_min()),
                    "{what}: a {} axis {i}",
                    d(1)
                );
                assert!(d(2).abs() <= slack(l.jerk()), "{what}: j {} axis {i}", d(2));
            }
        }
    }

    /// The first sample at which every axis is in its limits and can stay there (its
    /// velocity, and the velocity it reaches when its acceleration is brought to zero at
    /// full jerk, within the velocity limits): from there on the limits hold.
    fn first_safe(samples: &[[[f64; 3]; 3]], limits: &[AxisLimits<f64>; 3]) -> usize {
        let safe = |s: &[[f64; 3]; 3]| {
            limits.iter().enumerate().all(|(i, l)| {
                let (v, a) = (s[1][i], s[2][i]);
                let carried = v + a * a.abs() / (2.0 * l.jerk());
                (l.velocity_min()..=l.velocity_max()).contains(&v)
                    && (l.velocity_min()..=l.velocity_max()).contains(&carried)
                    && (l.acceleration_min()..=l.acceleration_max()).contains(&a)
            })
        };
        samples.iter().position(safe).unwrap_or(samples.len())
    }

    #[test]
    fn differences_of_the_samples_keep_the_limits() {
        let mut rng = Rng(0x1234_5678_9ABC_DEF1);
        for n in 0..60 {
            let m = random_move(&mut rng, 0.6);
            let path: Box<Path<f64, 3, 512>> = Box::new(compile_move(&m).expect("compiles"));
            let samples = play(&path);
            let from = first_safe(&samples, m.limits());
            assert_differences_keep_limits(&samples[from..], m.limits(), &std::format!("move {n}"));
        }
    }

    /// Takes over from sample `k` of `before` with `targets` ([`take_over_into`]) and checks
    /// the new path: its first sample is sample `k`, bit for bit, and the samples played
    /// (`before` up to `k`, then the new path's) keep the limits from the first sample at
    /// which every axis is safe on. Returns that sample's index, or `None` for a move of no
    /// time or longer than 20 s (skipped).
    fn assert_takes_over(
        before: &[Sample<f64, 3>],
        k: usize,
        targets: &[Kinematics<f64>; 3],
        limits: &[AxisLimits<f64>; 3],
        what: &str,
    ) -> Option<usize> {
        let mut m = Box::new(OnlineMove::new());
        let mut path: Box<Path<f64, 3, 512>> = Box::default();
        let options = MoveOptions::new().with_rate(RATE);
        let taken = take_over_into(&before[k], targets, limits, &options, &mut m, &mut path);
        if m.duration() == 0.0 || m.duration() > 20.0 {
            return None;
        }
        taken.unwrap_or_else(|e| panic!("{what}: {e}"));
        let after = samples(&path);
        assert_eq!(in_f64(&after[0]), in_f64(&before[k]), "{what}");
        let joined: Vec<_> = before[..=k].iter().chain(&after[1..]).map(in_f64).collect();
        let from = first_safe(&joined, limits);
        assert_differences_keep_limits(&joined[from..], limits, what);
        Some(from)
    }

    /// A random tick of `n` samples.
    fn random_tick(rng: &mut Rng, n: usize) -> usize {
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let k = (rng.next() * (n - 1) as f64) as usize;
        k
    }

    #[test]
    fn a_new_target_takes_over_at_any_tick_without_a_jump() {
        let mut rng = Rng(0xA076_1D64_78BD_642F);
        let mut taken = 0;
        for n in 0..60 {
            let first = random_move(&mut rng, 0.5);
            let a: Box<Path<f64, 3, 512>> = Box::new(compile_move(&first).expect("compiles"));
            let before = samples(&a);
            let k = random_tick(&mut rng, before.len());
            let targets: [Kinematics<f64>; 3] =
                core::array::from_fn(|i| target(&mut rng, &first.limits()[i]));
            let what = std::format!("take-over {n} at tick {k}");
            taken += usize::from(
                assert_takes_over(&before, k, &targets, first.limits(), &what).is_some(),
            );
        }
        assert!(taken >= 45, "{taken} of 60 take-overs played");
    }

    #[test]
    fn a_new_target_takes_over_a_planned_path_without_a_jump() {
        use crate::plan::{Limits, PathTiming, PlanOptions};
        use strak_curves::BSpline;
        let points = [
            [0.0, 0.0, 0.0],
            [0.0, 0.0, 20.0],
            [50.0, 30.0, 20.0],
            [50.0, 30.0, 0.0],
        ];
        let curve =
            BSpline::<[f64; 3], 8, 16>::clamped_uniform(3, &points, 0.0, 1.0).expect("curve");
        let (v, a, j) = (200.0, 2_000.0, 50_000.0);
        let plan = PlanOptions::new().with_rate(RATE);
        let timing = PathTiming::<_, 256, 64>::plan(
            &curve,
            &Limits::<3>::new(v, a, j).expect("limits"),
            &plan,
        )
        .expect("plans");
        let path: Box<Path<f64, 3, 512>> = Box::new(
            timing
                .compile(&crate::CompileOptions::new())
                .expect("compiles"),
        );
        let before = samples(&path);
        // The machine's limits per axis: those of the path (each axis moves at most as fast as
        // the path).
        let limits = [AxisLimits::new(v, a, j).expect("limits"); 3];
        let mut rng = Rng(0xC0FF_EE00_C0FF_EE00);
        let mut taken = 0;
        for n in 0..40 {
            let k = random_tick(&mut rng, before.len());
            let targets: [Kinematics<f64>; 3] = core::array::from_fn(|i| {
                let t = target(&mut rng, &limits[i]);
                Kinematics::new(t.position * 10.0, t.velocity, t.acceleration)
            });
            let what = std::format!("take-over {n} at tick {k}");
            if let Some(from) = assert_takes_over(&before, k, &targets, &limits, &what) {
                assert!(
                    from <= k + 1,
                    "{what}: the path was outside the limits at tick {from}"
                );
                taken += 1;
            }
        }
        assert!(taken >= 30, "{taken} of 40 take-overs played");
    }

    #[test]
    fn moves_solved_in_f32_end_exactly_on_their_targets() {
        let mut rng = Rng(0x0F32_0F32_0F32_0F32);
        #[allow(clippy::cast_possible_truncation)]
        let c = |x: f64| x as f32;
        for n in 0..60 {
            let m = random_move(&mut rng, 0.8);
            if m.synchronization() != Synchronization::Time {
                continue;
            }
            let k32 = |k: &Kinematics<f64>| {
                Kinematics::new(c(k.position), c(k.velocity), c(k.acceleration))
            };
            let start = m.profiles().map(|p| k32(&p.start()));
            let target = m.targets().map(|t| k32(&t));
            let limits = m.limits().map(|l| {
                AxisLimits::new(c(l.velocity_max()), c(l.acceleration_max()), c(l.jerk()))
                    .expect("limits")
            });
            let options = MoveOptions::new().with_rate(RATE);
            let Ok(m32) = OnlineMove::solve(&start, &target, &limits, &options) else {
                continue;
            };
            let f32_path: Box<Path<f32, 3, 512>> = Box::new(compile_move(&m32).expect("compiles"));
            let q40_path: Box<Path<Q40, 3, 512>> = Box::new(compile_move(&m32).expect("compiles"));
            let (a, b) = (play(&f32_path), play(&q40_path));
            for (i, t) in target.iter().enumerate() {
                let end = a.last().expect("samples");
                assert_eq!(
                    (end[0][i], end[1][i], end[2][i]),
                    (
                        f64::from(t.position),
                        f64::from(t.velocity),
                        f64::from(t.acceleration)
                    ),
                    "f32 move {n}"
                );
                let end = b.last().expect("samples");
                let q = |x: f32| Q40::out_from_f64(f64::from(x)).expect("in range").to_f64();
                assert_eq!(
                    (end[0][i], end[1][i], end[2][i]),
                    (q(t.position), q(t.velocity), q(t.acceleration)),
                    "Q40 move {n}"
                );
                assert_eq!(
                    (a[0][0][i], a[0][1][i]),
                    (f64::from(start[i].position), f64::from(start[i].velocity)),
                    "f32 move {n}"
                );
            }
        }
    }

    #[test]
    fn a_move_off_the_grid_or_without_time_is_an_error() {
        let l = [AxisLimits::new(1.0_f64, 1.0, 1.0).expect("limits"); 1];
        let rest = [Kinematics::at_rest(0.0)];
        let off = OnlineMove::solve(&rest, &[Kinematics::at_rest(1.0)], &l, &MoveOptions::new())
            .expect("solves");
        assert_eq!(
            compile_move::<f64, _, 1, 8>(&off).err(),
            Some(Error::InvalidRate)
        );
        let none = OnlineMove::solve(&rest, &rest, &l, &MoveOptions::new().with_rate(RATE))
            .expect("solves");
        assert_eq!(
            compile_move::<f64, _, 1, 8>(&none).err(),
            Some(Error::EmptyPath)
        );
        let far = OnlineMove::solve(
            &rest,
            &[Kinematics::at_rest(100.0)],
            &l,
            &MoveOptions::new().with_rate(RATE),
        )
        .expect("solves");
        assert!(matches!(
            compile_move::<f64, _, 1, 8>(&far).err(),
            Some(Error::CapacityExceeded { .. })
        ));
    }
}
