//! Compiling a motion stretch by stretch: the pieces of the next few hundred ticks at a time,
//! each stretch continuing the last in position, velocity and acceleration, so that the
//! pieces of consecutive stretches play as one path.

use heapless::Vec;
use strak_curves::ParamCurveDeriv;

use super::knots::{Knots, PieceKnots};
use super::law::{TickLaw, TickMotion};
use super::online::chord_state;
use super::options::{CompileOptions, Tolerance};
use super::spline_fit::{Clamped, SplineFit};
use super::{CHECK_FRACTION, fit_peaks, round_state, write_states};
use crate::error::Error;
use crate::num::Number;
use crate::online::Kinematics;
use crate::path::{AxisState, Piece};
use crate::plan::{Timing, Trajectory};

/// How many times a stretch is fitted again, each time to a quarter of the tolerance, when
/// its pieces exceed a limit of the law.
const TIGHTER_FITS: usize = 4;

/// Samples of the law that the extent of a relative tolerance is taken from.
const EXTENT_SAMPLES: u32 = 256;

/// A trajectory compiled in stretches: each call of [`next_into`](Self::next_into) writes the
/// pieces of the next stretch of ticks, starting and ending on the motion's exact state
/// (position, velocity and acceleration, from the law's `u`, `u̇` and
/// [`ü`](Timing::param_acceleration)), so that the pieces of consecutive stretches join
/// like the pieces inside one path and a device can compile a long motion into a small
/// ring of pieces while it plays.
///
/// Inside a stretch, the ticks around every jump of the law's jerk ([`Timing::breaks`])
/// get pieces of one tick that end on the exact state in every chain (position, velocity
/// and acceleration, as [`compile_move`](crate::compile_move) does at an online move's
/// switches), so the samples there are the motion's states and their differences the
/// motion's means over the tick. Between them the motion is smooth, and a C² cubic spline
/// in ticks clamped at both ends to the exact position, velocity and acceleration follows
/// it, refined until every tick is within the tolerance (as [`compile`](crate::compile())
/// fits). A stretch of the spline whose pieces exceed a limit the law promises
/// ([`Timing::limits`]) is fitted again to a quarter of the tolerance, up to four times
/// (a stretch cannot be slowed down alone once those before it have been played), and is
/// otherwise written as pieces of one tick that end on the exact state, as around the
/// breaks, which keep the limits by construction. That happens on short spans between
/// breaks near a limit, where a spline clamped at both ends overshoots the motion's jerk by
/// parts in 10⁴.
///
/// The motion takes `⌈duration · rate⌉` ticks, the law stretched to end on the last. A
/// relative tolerance is taken of the extent of the positions at 256 ticks spread over the
/// motion.
///
/// ```
/// use heapless::Vec;
/// use strak_curves::Bezier;
/// use strak_trajectory::{Along, CompileOptions, ParameterTiming, Piece, Stretches};
/// let curve = Bezier::new([[0.0_f64, 0.0], [50.0, 0.0], [50.0, 50.0]])?;
/// let law = ParameterTiming::at_rate(&curve, 1.0)?; // one second
/// let trajectory = Along::new(&curve, &law);
/// let mut stretches = Stretches::<_, 2>::new(&trajectory, 1_000.0, &CompileOptions::new().with_tolerance(1e-6))?;
/// let mut pieces: Vec<Piece<f32, 2>, 32> = Vec::new();
/// let mut ticks = 0;
/// while stretches.remaining() > 0 {
///     let n = stretches.next_into(200, &mut pieces)?; // play or store these pieces
///     assert_eq!(pieces.iter().map(|p| p.ticks()).sum::<u32>(), n);
///     assert_eq!(pieces[0].start(), ticks);
///     ticks += n;
/// }
/// assert_eq!(ticks, 1_000);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct Stretches<'a, M: Trajectory + ?Sized, const A: usize> {
    law: TickLaw<'a, M::Curve, M::Law>,
    fit: StretchFit,
    /// The first tick of the next stretch.
    next: u32,
}

impl<M: Trajectory + ?Sized, const A: usize> core::fmt::Debug for Stretches<'_, M, A> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Stretches")
            .field("ticks", &self.law.ticks)
            .field("next", &self.next)
            .field("tolerance", &self.fit.tolerance)
            .finish_non_exhaustive()
    }
}

impl<'a, M: Trajectory + ?Sized, const A: usize> Stretches<'a, M, A> {
    /// The stretches of `trajectory` played at `rate_hz`, fitted with `options` (its
    /// tolerance and piece length; its feed reserve and slow-down are not used).
    ///
    /// # Errors
    /// As [`compile`](crate::compile()) before it fits: [`Error::InvalidLimit`] for bad
    /// options, [`Error::InvalidRate`], [`Error::AxisMismatch`], [`Error::EmptyPath`],
    /// [`Error::TooLong`]; [`Error::Curve`] for a law that gives a non-finite value.
    ///
    /// ```
    /// use strak_curves::Bezier;
    /// use strak_trajectory::{Along, CompileOptions, Error, ParameterTiming, Stretches};
    /// let curve = Bezier::new([[0.0_f64, 0.0], [1.0, 1.0]])?;
    /// let law = ParameterTiming::at_rate(&curve, 1.0)?;
    /// let t = Along::new(&curve, &law);
    /// assert!(matches!(Stretches::<_, 3>::new(&t, 1_000.0, &CompileOptions::new()), Err(Error::AxisMismatch { .. })));
    /// assert_eq!(Stretches::<_, 2>::new(&t, 1_000.0, &CompileOptions::new())?.remaining(), 1_000);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn new(trajectory: &'a M, rate_hz: f64, options: &CompileOptions) -> Result<Self, Error> {
        let (curve, timing) = (trajectory.curve(), trajectory.law());
        super::check_inputs::<A, M::Curve, M::Law>(timing, rate_hz, options)?;
        let law = TickLaw::new(curve, timing, rate_hz, 1.0, 0)?;
        let tolerance = match options.tolerance() {
            Tolerance::Absolute(t) => t,
            Tolerance::Relative(r) => r * extent::<M::Curve, M::Law, A>(&law)?,
        };
        let fit = StretchFit {
            tolerance,
            max_piece_ticks: options.max_piece_ticks(),
            path_axes: A,
        };
        Ok(Stretches { law, fit, next: 0 })
    }

    /// The ticks of the whole motion.
    ///
    /// ```
    /// # use strak_curves::Bezier;
    /// # use strak_trajectory::{Along, CompileOptions, ParameterTiming, Stretches};
    /// # let curve = Bezier::new([[0.0_f64, 0.0], [1.0, 1.0]])?;
    /// # let law = ParameterTiming::at_rate(&curve, 4.0)?;
    /// # let t = Along::new(&curve, &law);
    /// assert_eq!(Stretches::<_, 2>::new(&t, 1_000.0, &CompileOptions::new())?.ticks(), 250);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn ticks(&self) -> u32 {
        self.law.ticks
    }

    /// The ticks not yet compiled.
    ///
    /// ```
    /// # use strak_curves::Bezier;
    /// # use strak_trajectory::{Along, CompileOptions, ParameterTiming, Piece, Stretches};
    /// # let curve = Bezier::new([[0.0_f64, 0.0], [1.0, 1.0]])?;
    /// # let law = ParameterTiming::at_rate(&curve, 4.0)?;
    /// # let t = Along::new(&curve, &law);
    /// let mut s = Stretches::<_, 2>::new(&t, 1_000.0, &CompileOptions::new())?;
    /// let mut pieces = heapless::Vec::<Piece<f64, 2>, 8>::new();
    /// s.next_into(100, &mut pieces)?;
    /// assert_eq!(s.remaining(), 150);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn remaining(&self) -> u32 {
        self.law.ticks - self.next
    }

    /// Compiles the next stretch of at most `max_ticks` ticks (at least two, or the rest
    /// when fewer remain) into `pieces` (cleared first), each piece's `start` the tick of
    /// the whole motion it starts at; returns the stretch's ticks (0 once all are compiled).
    ///
    /// # Errors
    /// [`Error::CapacityExceeded`] when the stretch needs more than `P` pieces (compile
    /// shorter stretches); [`Error::OutOfRange`] for a
    /// value that does not fit `N`; [`Error::Curve`] for a non-finite value of the law.
    /// On an error `pieces` is empty and the stretch is not consumed.
    pub fn next_into<N: Number, const P: usize>(
        &mut self,
        max_ticks: u32,
        pieces: &mut Vec<Piece<N, A>, P>,
    ) -> Result<u32, Error> {
        pieces.clear();
        let first = self.next;
        let rest = self.law.ticks - first;
        if rest == 0 {
            return Ok(0);
        }
        let mut ticks = max_ticks.max(2).min(rest);
        if rest - ticks == 1 {
            ticks -= 1; // never leave a last stretch of one tick (it cannot be clamped)
        }
        if let Err(e) = self.fit.write(&self.law, first, first + ticks, pieces) {
            pieces.clear();
            return Err(e);
        }
        self.next = first + ticks;
        Ok(ticks)
    }
}

/// Where a write of a stretch stands after one of the motion's breaks
/// ([`StretchFit::write_from`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Progress {
    /// How many breaks it has passed.
    breaks: usize,
    /// The last of them, as a fractional tick.
    pub(crate) at: f64,
    /// How many pieces it has written.
    pieces: usize,
    /// The tick the next span starts at.
    from: u32,
}

/// How a stretch is fitted: the position tolerance and the longest piece.
#[derive(Clone, Copy, Debug)]
pub(crate) struct StretchFit {
    pub(crate) tolerance: f64,
    pub(crate) max_piece_ticks: u32,
    /// The axes that shape the path: the limits of speed, acceleration and jerk are norms
    /// over these (the others are held to their own limits).
    pub(crate) path_axes: usize,
}

impl StretchFit {
    /// Writes the pieces of ticks `first ..= last` of `motion` after `pieces`: spline
    /// spans between the one-tick pieces around the motion's breaks, every piece's `start`
    /// its tick.
    pub(crate) fn write<M, N, const A: usize, const P: usize>(
        &self,
        motion: &M,
        first: u32,
        last: u32,
        pieces: &mut Vec<Piece<N, A>, P>,
    ) -> Result<(), Error>
    where
        M: TickMotion<A> + ?Sized,
        N: Number,
    {
        self.write_from(motion, (first, last), pieces, None, &mut |_| {})
    }

    /// [`write`](Self::write) of the ticks `first ..= last`, resumed after the break of
    /// `resume` where given: a progress that `passed` reported to an earlier write of the
    /// same motion from the same first tick, whose break lies before `last`. Up to that
    /// break both writes pass the same breaks (the breaks before `last` in order) and write
    /// the same pieces, which `pieces` keeps (it is cut to them; without `resume` the pieces
    /// are written after `pieces`). Calls `passed` with the progress after each break.
    pub(crate) fn write_from<M, N, const A: usize, const P: usize>(
        &self,
        motion: &M,
        (first, last): (u32, u32),
        pieces: &mut Vec<Piece<N, A>, P>,
        resume: Option<Progress>,
        passed: &mut dyn FnMut(Progress),
    ) -> Result<(), Error>
    where
        M: TickMotion<A> + ?Sized,
        N: Number,
    {
        let (mut from, skip) = match resume {
            Some(p) => {
                pieces.truncate(p.pieces);
                (p.from, p.breaks)
            }
            None => (first, 0),
        };
        let (mut breaks, mut result) = (0, Ok(()));
        motion.breaks_between(first, last, &mut |k| {
            breaks += 1;
            if result.is_err() || breaks <= skip {
                return;
            }
            let near = libm::round(k);
            let (lo, hi) = if (k - near).abs() <= 1e-9 * k.max(1.0) {
                (near, near)
            } else {
                (libm::floor(k), libm::ceil(k))
            };
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            let (lo, hi) = (lo as u32, hi as u32);
            result = self
                .span(motion, from, lo.max(from), pieces)
                .and_then(|()| chords(motion, lo.max(from), hi.max(from), pieces));
            from = hi.max(from);
            if result.is_ok() {
                passed(Progress {
                    breaks,
                    at: k,
                    pieces: pieces.len(),
                    from,
                });
            }
        });
        result?;
        self.span(motion, from, last, pieces)
    }

    /// The spline of ticks `from ..= to`, clamped at both ends to the exact state, fitted
    /// tighter until its pieces keep the motion's limits, written after `pieces`; one-tick
    /// pieces for a span too short for both clamps, or where no fit keeps the limits.
    fn span<M, N, const A: usize, const P: usize>(
        &self,
        motion: &M,
        from: u32,
        to: u32,
        pieces: &mut Vec<Piece<N, A>, P>,
    ) -> Result<(), Error>
    where
        M: TickMotion<A> + ?Sized,
        N: Number,
    {
        if to < from + 3 {
            return chords(motion, from, to, pieces);
        }
        let period = motion.period();
        let offset = pieces.len();
        let mut fit = SplineFit::<A, _, Clamped<A>>::empty(PieceKnots { pieces, offset });
        let mut tolerance = self.tolerance;
        for _ in 0..=TIGHTER_FITS {
            self.fit_span(motion, from, to, tolerance, &mut fit)?;
            let quantity = match motion.limits() {
                Some(limits) => {
                    let peaks = fit_peaks(&fit, period, false, self.path_axes, limits.velocity);
                    peaks.slowdown(&limits)?.1
                }
                None => None,
            };
            if quantity.is_none() {
                return write_states(fit, from, period);
            }
            tolerance /= 4.0;
        }
        pieces.truncate(offset); // the fit's knots, which lay there
        chords(motion, from, to, pieces)
    }

    /// One fit of ticks `from ..= to` to `tolerance`, clamped at both ends (no break of the
    /// motion lies inside: [`write`](Self::write) splits the stretch at them).
    fn fit_span<M, K, const A: usize>(
        &self,
        motion: &M,
        from: u32,
        to: u32,
        tolerance: f64,
        fit: &mut SplineFit<A, K, Clamped<A>>,
    ) -> Result<(), Error>
    where
        M: TickMotion<A> + ?Sized,
        K: Knots<A>,
    {
        let mut exact = |k: u32| motion.position(from + k);
        let (s0, s1) = (motion.slope(from)?, motion.slope(to)?);
        fit.init(to - from, to - from, s0, s1, &mut exact)?;
        let clamps = [Some(motion.second(from)?), Some(motion.second(to)?)];
        fit.clamp_accelerations(clamps, &mut exact)?;
        fit.subdivide(self.max_piece_ticks, &mut exact)?;
        fit.refine_every_tick(tolerance * CHECK_FRACTION, tolerance, &mut exact)
    }
}

/// The exact state of every axis of `motion` at tick `k`, in units, units/s and units/s².
fn state<M: TickMotion<A> + ?Sized, const A: usize>(
    motion: &M,
    k: u32,
) -> Result<[Kinematics<f64>; A], Error> {
    // The slope first: a motion that caches its states whole has the others at hand then.
    let slope = motion.slope(k)?;
    let (x, second) = (motion.position(k)?, motion.second(k)?);
    let (p, pp) = (motion.period(), motion.period() * motion.period());
    Ok(core::array::from_fn(|a| {
        Kinematics::new(x[a], slope[a] / p, second[a] / pp)
    }))
}

/// One-tick pieces from tick `from` to tick `to` after `pieces`, each from the exact state
/// to the exact state of the next tick in every chain.
fn chords<M, N, const A: usize, const P: usize>(
    motion: &M,
    from: u32,
    to: u32,
    pieces: &mut Vec<Piece<N, A>, P>,
) -> Result<(), Error>
where
    M: TickMotion<A> + ?Sized,
    N: Number,
{
    if from >= to {
        return Ok(());
    }
    let period = motion.period();
    let mut start = state(motion, from)?;
    for k in from..to {
        let end = state(motion, k + 1)?;
        let mut axes = [AxisState::ZERO; A];
        for (axis, (s, e)) in axes.iter_mut().zip(start.iter().zip(&end)) {
            *axis = round_state(&chord_state(s, e, 1, period))?;
        }
        let piece = Piece {
            axes,
            start: k,
            ticks: 1,
        };
        pieces.push(piece).map_err(|_| Error::CapacityExceeded {
            capacity: P,
            required: P + 1,
        })?;
        start = end;
    }
    Ok(())
}

/// The extent of the positions at [`EXTENT_SAMPLES`] ticks spread over the law (at least
/// the level of `f64` rounding of their magnitude).
fn extent<C, T, const A: usize>(law: &TickLaw<'_, C, T>) -> Result<f64, Error>
where
    C: ParamCurveDeriv + ?Sized,
    T: Timing + ?Sized,
{
    let (extent, big) = extent_and_magnitude::<C, T, A>(law)?;
    Ok(extent.max(1e-12 * (1.0 + big)))
}

/// The largest extent of one coordinate and the largest magnitude, over the positions at
/// [`EXTENT_SAMPLES`] ticks spread over the law.
fn extent_and_magnitude<C, T, const A: usize>(law: &TickLaw<'_, C, T>) -> Result<(f64, f64), Error>
where
    C: ParamCurveDeriv + ?Sized,
    T: Timing + ?Sized,
{
    let first = law.position::<A>(0)?;
    let (mut lo, mut hi) = (first, first);
    let mut big = 0.0_f64;
    for i in 1..=EXTENT_SAMPLES {
        #[allow(clippy::cast_possible_truncation)]
        let k = (u64::from(law.ticks) * u64::from(i) / u64::from(EXTENT_SAMPLES)) as u32;
        for (a, v) in law.position::<A>(k)?.into_iter().enumerate() {
            lo[a] = lo[a].min(v);
            hi[a] = hi[a].max(v);
            big = big.max(v.abs());
        }
    }
    let extent = lo.iter().zip(hi).fold(0.0_f64, |m, (l, h)| m.max(h - l));
    Ok((extent, big))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::MotionLimits;

    /// `x = 10·sin(k/50)` in ticks of a millisecond, with a break every 5.5 ticks.
    struct Wave;

    impl TickMotion<1> for Wave {
        fn period(&self) -> f64 {
            1e-3
        }
        fn position(&self, k: u32) -> Result<[f64; 1], Error> {
            Ok([10.0 * libm::sin(f64::from(k) / 50.0)])
        }
        fn slope(&self, k: u32) -> Result<[f64; 1], Error> {
            Ok([0.2 * libm::cos(f64::from(k) / 50.0)])
        }
        fn second(&self, k: u32) -> Result<[f64; 1], Error> {
            Ok([-0.004 * libm::sin(f64::from(k) / 50.0)])
        }
        fn breaks_between(&self, first: u32, last: u32, f: &mut dyn FnMut(f64)) {
            let mut k = 5.5;
            while k < f64::from(last) {
                if k > f64::from(first) {
                    f(k);
                }
                k += 5.5;
            }
        }
        fn limits(&self) -> Option<MotionLimits> {
            None
        }
    }

    /// A write resumed from the progress of a longer write after its last break before the
    /// shorter one's end writes the pieces of a write of its own.
    #[test]
    fn a_resumed_write_equals_a_fresh_one() {
        let fit = StretchFit {
            tolerance: 1e-6,
            max_piece_ticks: 16,
            path_axes: 1,
        };
        let (first, last) = (3, 40);
        let mut fresh: Vec<Piece<f64, 1>, 64> = Vec::new();
        fit.write(&Wave, first, last, &mut fresh).unwrap();
        let mut pieces: Vec<Piece<f64, 1>, 64> = Vec::new();
        let mut before = None;
        let mut passed = |p: Progress| {
            if p.at < f64::from(last) {
                before = Some(p);
            }
        };
        // the longer write runs out of pieces, as a stretch that is halved does
        let long = fit.write_from(&Wave, (first, 300), &mut pieces, None, &mut passed);
        assert!(
            matches!(long, Err(Error::CapacityExceeded { .. })),
            "{long:?}"
        );
        assert!(before.is_some_and(|p| p.breaks == 7 && p.pieces > 0));
        fit.write_from(&Wave, (first, last), &mut pieces, before, &mut |_| {})
            .unwrap();
        assert_eq!(pieces, fresh);
    }
}
