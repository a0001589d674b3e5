//! Playing a compiled [`Path`] back at its control rate: one [`Sample`] per tick, in constant
//! time, with feed override, feed hold, resume and abort.

mod batch;
mod edge;
pub(crate) mod events;
mod feed;
mod form;
pub(crate) mod guard;
pub(crate) mod kernel;
mod stream;
mod switch;

use crate::path::{AxisState, FeedRampLimits, Newton, PathView, Piece, Sample};
use feed::FeedRamp;
pub use kernel::Kernel;
pub use stream::StreamSampler;
use switch::After;

/// What the sampler is doing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum SamplerState {
    /// Following the path at the feed override.
    Running,
    /// Ramping down to (or standing at) feed 0 after [`Sampler::hold`].
    Holding,
    /// Ramping down to feed 0 after [`Sampler::abort`]; then finished.
    Aborting,
    /// At the end (or stopped after an abort): every further sample repeats the last position
    /// with zero velocity and acceleration.
    Finished,
}

/// Plays a path back, one [`Sample`] per call of [`Sampler::next`] (a timer interrupt).
///
/// The sampler plays a [`PathView`]: a [`Path`](crate::Path) in RAM or a
/// [`PathBlob`](crate::PathBlob) read in place from flash, the same way and with the same
/// samples (`Sampler::new(&path)`, `Sampler::new(blob.view())`). It borrows the path
/// (firmware keeps the path in a `static`, the sampler in the interrupt's state) and holds
/// only the view, the current forward-difference states and the feed ramp: `O(A)` memory. [`Sampler::next`] has no panic path and a constant cost (see below).
///
/// The first sample is tick 0 of the path, the sample at path tick [`Path::ticks`](crate::PathHeader::ticks) is the
/// end point exactly ([`Path::end_position`](crate::PathHeader::end_position), bit for bit in every number format), with the
/// path's end velocity and acceleration; after it [`Sampler::is_finished`] is `true` and
/// every further call returns the end point with zero velocity and acceleration.
///
/// # Feed
/// [`set_feed`](Sampler::set_feed) (override in `[0, 1]`), [`hold`](Sampler::hold),
/// [`resume`](Sampler::resume) and [`abort`](Sampler::abort) ramp the feed factor `φ`
/// with the path's limits (jerk-limited: see [`CompileOptions`](crate::CompileOptions)); the
/// motion stays on the path and never jumps.
///
/// # Two modes, both constant time
/// * **Forward differencing** (feed 1, no ramp running): per tick and axis six additions
///   ([`AxisState::step`](crate::AxisState::step)); on the last tick of a piece a load of the
///   next piece's state (copy) instead, taken from the pieces still to come in order (no
///   search). The end sample is played the same way (a piece of one tick without motion);
///   its own tick finishes. On Cortex-M cores with Thumb-2 the
///   tick is a hand-scheduled kernel (`vldm`/`vstm` per axis in `f32`, `ldm`/`stm` and
///   `adds`/`adc` in `Q40`) with the same additions in the same order, so the same bits.
/// * **Interpolation** (feed ≠ 1 or a ramp running): the playback point advances by the feed
///   factor `φ` per tick, so it lies at a fractional offset `θ` (`|θ| < 1`) from the current
///   forward-difference state, inside the current tick interval of the current piece; the sample is Newton's forward-difference formula at `θ`
///   (the piece's cubic evaluated exactly from its differences, in the number format):
///   `x = p(i+θ)`, `v = φ·p'(i+θ)/T`, `a = φ²·p''(i+θ)/T² + φ̇·p'(i+θ)/T`. Because `φ ≤ 1`,
///   the state steps at most once per tick.
///
/// When the feed returns to 1, the state is shifted onto the fractional point once (the same
/// formula) and forward differencing resumes; later piece loads are shifted by the same
/// fraction.
///
/// # Per-tick cost (A axes, operations in the number format `N`)
/// | tick                                        | additions      | multiplications |
/// |---------------------------------------------|----------------|-----------------|
/// | forward differencing                        | 6A             | 0               |
/// | … positions only ([`Sampler::next_position`])| 3A            | 0               |
/// | … at a piece switch (load: copy of 9A values)| 0              | 0               |
/// | … first [`next`](Sampler::next) after positions only (catch-up) | 6A | 4A by an integer |
/// | … at a piece switch after an override (shifted load) | 16A + 3 | 10A + 4        |
/// | interpolation (incl. ramp and a step)       | ≤ 13A + 14     | ≤ 9A + 6, and 4 by an integer |
/// | … with a shifted piece load in the same tick| ≤ 23A + 17     | ≤ 19A + 10, and 4 by an integer |
///
/// plus comparisons and the conversion into the sample type (free for floats, an addition
/// and a shift per value for `Q40`). A `Q40` multiplication is an `i64 × i64 → i128`
/// product (a library call on Cortex-M0/M3); a multiplication by an integer is an `i64`
/// product. The counts do not depend on the path (the measured times and instruction counts
/// per tick are in the project's benchmark report); there is no search and no loop other
/// than over the axes. The interpolation mode sets the
/// worst-case budget of an interrupt.
///
/// ```
/// use strak_trajectory::{compile, Along, CompileOptions, Path, Q40, Sampler, Timing};
/// use strak_curves::Bezier;
///
/// /// Rest to rest in 50 ms: u = 3τ² − 2τ³.
/// struct Smooth;
/// impl Timing for Smooth {
///     fn duration(&self) -> f64 { 0.05 }
///     fn param(&self, t: f64) -> (f64, f64) {
///         let s = t.clamp(0.0, 0.05) / 0.05;
///         (s * s * (3.0 - 2.0 * s), 6.0 * s * (1.0 - s) / 0.05)
///     }
/// }
///
/// // At start-up (or on the host, then serialized): compile the move.
/// let curve = Bezier::new([[0.0_f64, 0.0], [5.0, 0.0], [5.0, 5.0]])?;
/// let trajectory = Along::new(&curve, &Smooth);
/// let path: Path<Q40, 2, 32> = compile(&trajectory, 20_000.0, &CompileOptions::new())?;
///
/// // The timer interrupt: one call per tick, constant time, no allocation, no panic.
/// let mut sampler = Sampler::new(&path);
/// let mut last = None;
/// while !sampler.is_finished() {
///     let s = sampler.next(); // -> Sample<I32F32, 2>: write s.position to the drives
///     last = Some(s);
/// }
/// let last = last.unwrap();
/// assert_eq!(last.tick, 1_000);
/// assert_eq!(last.position, path.end_position()); // exact end
/// assert_eq!(last.position[1].to_num::<f64>(), 5.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct Sampler<'a, N: Kernel, const A: usize> {
    path: PathView<'a, N, A>,
    /// The pieces after the current one, for the inline piece switch to load in order: those
    /// of a path in RAM while the switch may load them unshifted (on the tick grid); empty
    /// otherwise (for a blob; off the grid empty at the same place, so that it still tells
    /// the current piece: [`piece`](Self::piece)).
    pieces: &'a [Piece<N, A>],
    /// The piece records after the current one: those of a blob (empty for a path in RAM).
    records: &'a [u8],
    /// Past the last piece: at the end sample (the current piece is the path's end state,
    /// one tick long) or finished.
    ended: bool,
    /// What the inline piece switch does once `pieces` is empty.
    after: After,
    /// The state is at tick `local + shift` of the current piece, `piece_ticks` long: as of
    /// the last [`sync`](Self::sync) while [`left`](Self::left) is 0; while the fast path runs
    /// they are derived from `left` ([`sync`](Self::sync)).
    local: u32,
    piece_ticks: u32,
    state: [AxisState<N>; A],
    /// Fraction by which the state (and every later load) is shifted off the tick grid.
    shift: N,
    /// `shift == 0` (a flag costs fewer instructions than a comparison in the number format).
    on_grid: bool,
    /// Fractional playback offset after the state (interpolation mode), with
    /// `shift + theta ∈ [0, 1)`.
    theta: N,
    feed: FeedRamp<N>,
    /// The feed ramp's constants: the path's, scaled by [`Sampler::scale_feed_ramp`].
    ramp: FeedRampLimits<N>,
    /// The override set by [`Sampler::set_feed`].
    feed_override: N,
    /// What the sampler is doing.
    mode: SamplerState,
    /// The wall-clock tick of the next sample plus `left` (the fast path counts only
    /// `left` down: the next sample's tick is `end − left`).
    end: u64,
    /// The position after finishing.
    rest: [N::Out; A],
    /// Ticks [`next`](Sampler::next) may still take on its fast path: while running at full
    /// feed with no ramp and `θ = 0`, the ticks left in the current piece (the last of them
    /// outputs and loads the next piece: [`switch_sample`](Self::switch_sample)); 0
    /// otherwise. Set by [`Sampler::refresh`] after every change other than the
    /// forward-differencing tick itself.
    left: u32,
    /// `left` when the velocity and acceleration chains were last stepped: position-only
    /// ticks ([`Sampler::next_position`]) count down `left` alone, so the chains lag the
    /// position by `chains − left` ticks until [`catch_up`](Sampler::catch_up).
    chains: u32,
}

impl<'a, N: Kernel, const A: usize> Sampler<'a, N, A> {
    /// A sampler at tick 0 of `path` (a `&Path`, a [`PathView`], or a `&PathBlob`), at full
    /// feed.
    pub fn new(path: impl Into<PathView<'a, N, A>>) -> Self {
        let path = path.into();
        let mut s = Sampler {
            path,
            pieces: &[],
            records: &[],
            ended: false,
            after: After::Other,
            local: 0,
            piece_ticks: 0,
            state: [AxisState::default(); A],
            shift: N::ZERO,
            on_grid: true,
            theta: N::ZERO,
            feed: FeedRamp::full(),
            ramp: path.header().ramp,
            feed_override: N::ONE,
            mode: SamplerState::Running,
            end: 0,
            rest: path.end_position(),
            left: 0,
            chains: 0,
        };
        s.load(0);
        s.refresh();
        s
    }

    /// The path played.
    pub fn path(&self) -> PathView<'a, N, A> {
        self.path
    }

    /// `true` once the current piece is past the path's pieces: the end sample (piece
    /// `count`), or finished.
    #[inline]
    fn at_end(&self) -> bool {
        self.ended
    }

    /// The current piece's index (the path's piece count at the end sample and after it).
    fn piece(&self) -> usize {
        if self.ended {
            return self.path.piece_count();
        }
        self.path.index_before(self.pieces, self.records)
    }

    /// Sets what comes after piece `j` for the piece switch: the pieces (or records) after
    /// it, and what follows them.
    fn set_ahead(&mut self, j: usize) {
        self.ended = j >= self.path.piece_count();
        self.records = self.path.records_after(j);
        let pieces = self.path.pieces_after(j);
        let inline = self.on_grid && self.path.in_ram() && !self.ended;
        self.pieces = if inline {
            pieces
        } else {
            pieces.get(..0).unwrap_or_default()
        };
        self.after = if inline { After::End } else { After::Other };
    }

    /// Loads piece `j` (shifted by `shift`), or marks the end.
    #[inline]
    fn load(&mut self, j: usize) {
        self.local = 0;
        self.set_ahead(j);
        match self.path.load(j, &mut self.state) {
            Some(ticks) => {
                self.piece_ticks = ticks;
                self.chains = self.left;
                if self.shift != N::ZERO {
                    let c = Newton::at(self.shift);
                    for s in &mut self.state {
                        *s = s.shifted(&c);
                    }
                }
            }
            None => self.set_left(0),
        }
    }

    /// Moves the playback index one tick on (the state must already be there).
    #[inline]
    fn advance_index(&mut self) {
        self.local += 1;
        if self.local >= self.piece_ticks {
            self.load(self.piece() + 1);
        }
    }

    /// Sets `left`, keeping the chains' lag (`chains − left`).
    #[inline]
    fn set_left(&mut self, left: u32) {
        let lag = self.chains.wrapping_sub(self.left);
        self.left = left;
        self.chains = left.wrapping_add(lag);
    }

    /// Leaves the fast path: brings `local` and `piece_ticks` up to date with the ticks the
    /// fast path has counted down in `left`, then sets `left` to 0 (`end` is the next
    /// sample's tick). Every change other than a fast tick starts with it and ends with
    /// [`refresh`](Self::refresh).
    #[inline]
    fn sync(&mut self) {
        if self.left > 0 {
            self.piece_ticks = self.ticks_of(self.piece());
            self.local = self.piece_ticks.wrapping_sub(self.left);
            self.end = self.end.wrapping_sub(u64::from(self.left));
            self.set_left(0);
        }
    }

    /// The length in ticks of piece `j`, the end sample (piece `count`, one tick) included.
    fn ticks_of(&self, j: usize) -> u32 {
        self.path.piece_ticks(j).unwrap_or(1)
    }

    /// Sets [`left`](Self::left) from the state (after [`sync`](Self::sync)): called after
    /// every change other than the forward-differencing tick itself.
    #[inline]
    fn refresh(&mut self) {
        let fast = self.mode != SamplerState::Finished
            && !self.at_end()
            && self.feed.phi == N::ONE
            && self.theta == N::ZERO
            && self.feed.is_idle();
        let left = if fast {
            self.piece_ticks.saturating_sub(self.local)
        } else {
            0
        };
        self.set_left(left);
        self.end = self.end.wrapping_add(u64::from(left));
    }

    /// `true` when the next tick is a plain forward-differencing step inside a piece.
    #[inline(always)]
    fn on_fast_path(&self) -> bool {
        self.left > 1 && self.chains == self.left
    }

    /// The fast path's bookkeeping: counts one tick down and returns its number.
    #[inline(always)]
    fn count_tick(&mut self) -> u64 {
        let tick = self.end.wrapping_sub(u64::from(self.left));
        self.left -= 1;
        self.chains = self.left;
        tick
    }

    /// The next setpoint; call once per tick.
    ///
    /// Constant time, no panic path (see [`Sampler`] for the operation counts). After the end (or an abort) it keeps returning the last position with zero
    /// velocity and acceleration.
    #[allow(clippy::should_implement_trait)]
    #[inline(always)] // into the caller's tick handler: the tick and its piece switch make no call
    pub fn next(&mut self) -> Sample<N::Out, A> {
        if self.chains == self.left {
            if self.left > 1 {
                // A plain forward-differencing tick inside a piece: one counter and the
                // format's tick kernel.
                let tick = self.count_tick();
                return N::tick_sample(&mut self.state, tick);
            }
            if self.left == 1 {
                return self.switch_sample();
            }
        }
        self.next_edge()
    }

    /// [`next`](Self::next) in the accumulator's own format ([`Kernel::Native`]: `f32`,
    /// `f64`, or [`I24F40`](strak_curves::fixed::types::I24F40) for `Q40`), written in
    /// place: `Kernel::native_to_out` of every value of `out` is [`next`](Self::next)'s
    /// value, bit for bit, and the sampler advances as with [`next`](Self::next) (the
    /// entry points may be mixed freely).
    ///
    /// For firmware that wants the full setpoint at the least cost per tick: no rounding
    /// into the sample type, and no sample returned by value (the tick kernel stores each
    /// value straight into `out`). Constant time and no panic path, like
    /// [`next`](Self::next).
    ///
    /// ```
    /// use strak_trajectory::{compile, Along, CompileOptions, Kernel, Path, Q40, Sample, Sampler, Timing};
    /// use strak_curves::Bezier;
    ///
    /// struct Linear;
    /// impl Timing for Linear {
    ///     fn duration(&self) -> f64 { 0.01 }
    ///     fn param(&self, t: f64) -> (f64, f64) { (t.clamp(0.0, 0.01) / 0.01, 100.0) }
    /// }
    /// let line = Bezier::new([[0.0_f64], [2.0]])?;
    /// let path: Path<Q40, 1, 8> = compile(&Along::new(&line, &Linear), 1_000.0, &CompileOptions::new())?;
    /// let (mut a, mut b) = (Sampler::new(&path), Sampler::new(&path));
    /// let mut s = Sample::splat(Q40::NATIVE_ZERO); // Sample<I24F40, 1>
    /// while !a.is_finished() {
    ///     a.next_into(&mut s);
    ///     let want = b.next();
    ///     assert_eq!((s.tick, Q40::native_to_out(s.position[0])), (want.tick, want.position[0]));
    /// }
    /// assert_eq!(s.position[0].to_num::<f64>(), 2.0);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[inline(always)] // into the caller's tick handler: the tick and its piece switch make no call
    pub fn next_into(&mut self, out: &mut Sample<N::Native, A>) {
        if self.chains == self.left {
            if self.left > 1 {
                let tick = self.count_tick();
                return N::tick_native(&mut self.state, tick, out);
            }
            if self.left == 1 {
                return self.switch_native(out);
            }
        }
        self.next_edge_into(out);
    }

    /// The next setpoint's positions only: exactly [`next`](Self::next)`().position`, bit for
    /// bit, and the sampler advances as with [`next`](Self::next) (the two may be mixed
    /// freely).
    ///
    /// For firmware that only commands positions: an ordinary tick steps only the position
    /// chains (three additions per axis instead of six) and writes only the positions. The
    /// velocity and acceleration chains catch up in closed form when [`next`](Self::next)
    /// follows (at most once per piece; exact in `Q40`, within a few roundings in floats)
    /// or at the next piece, which loads them afresh. Constant time and no panic path, like
    /// [`next`](Self::next).
    ///
    /// ```
    /// use strak_trajectory::{compile, Along, CompileOptions, Path, Sampler, Timing};
    /// use strak_curves::Bezier;
    ///
    /// struct Linear;
    /// impl Timing for Linear {
    ///     fn duration(&self) -> f64 { 0.01 }
    ///     fn param(&self, t: f64) -> (f64, f64) { (t.clamp(0.0, 0.01) / 0.01, 100.0) }
    /// }
    /// let line = Bezier::new([[0.0_f64], [2.0]])?;
    /// let trajectory = Along::new(&line, &Linear);
    /// let path: Path<f32, 1, 8> = compile(&trajectory, 1_000.0, &CompileOptions::new())?;
    /// let (mut a, mut b) = (Sampler::new(&path), Sampler::new(&path));
    /// while !a.is_finished() {
    ///     assert_eq!(a.next_position(), b.next().position);
    /// }
    /// assert_eq!(b.next().position, path.end_position());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[inline(always)] // into the caller's tick handler: the tick and its piece switch make no call
    pub fn next_position(&mut self) -> [N::Out; A] {
        if self.left > 1 {
            // `next`'s fast path, stepping the position chains only (the others catch up
            // when they are next needed).
            self.left -= 1;
            N::tick_position(&mut self.state)
        } else if self.left == 1 {
            // A piece switch loads fresh chains: the lagging ones need no catching up.
            self.switch_position()
        } else {
            self.next_other_position()
        }
    }

    /// `true` after the end sample (or the stop after an abort) has been returned.
    pub fn is_finished(&self) -> bool {
        self.mode == SamplerState::Finished
    }

    /// What the sampler is doing.
    pub fn state(&self) -> SamplerState {
        self.mode
    }

    /// Sets the feed override `f`, clamped to `[0, 1]` (NaN is ignored). Takes effect
    /// through a jerk-limited ramp; while holding it is stored for [`resume`](Self::resume).
    /// The ramp keeps the limits within the path's feed reserve
    /// ([`PathHeader::feed_share`](crate::PathHeader::feed_share)); on a path planned without
    /// one, call it when and after the slow-down a [`FeedGuard`](crate::FeedGuard) schedules
    /// (the same for [`hold`](Self::hold), [`resume`](Self::resume) and [`abort`](Self::abort)).
    /// Not for the interrupt's hot path on FPU-less parts: converts through `f64` once.
    pub fn set_feed(&mut self, f: f32) {
        if f.is_nan() {
            return;
        }
        self.sync();
        let f = f64::from(f.clamp(0.0, 1.0));
        if let Some(v) = N::from_f64(f) {
            self.feed_override = v;
            if self.mode == SamplerState::Running {
                self.feed.target = v;
            }
        }
        self.refresh();
    }

    /// The feed override last set (1 initially).
    pub fn feed_override(&self) -> f64 {
        self.feed_override.to_f64()
    }

    /// The current feed factor `φ` (moving toward the override during a ramp).
    pub fn feed(&self) -> f64 {
        self.feed.phi.to_f64()
    }

    /// `true` while the feed factor ramps (or the ramp's last step is still in the
    /// acceleration the next sample reports).
    pub fn is_ramping(&self) -> bool {
        !self.feed.is_idle()
    }

    /// Slows the feed ramps down: their largest rate `φ̇` and its change per tick `φ̈` become
    /// the path's times `2⁻ˢʰⁱᶠᵗ` (0: the path's own), for every later feed change. A ramp
    /// so slowed adds `2⁻ˢʰⁱᶠᵗ` of the acceleration and jerk a full one adds, and takes
    /// about `2ˢʰⁱᶠᵗ` times as long. Only while no ramp runs ([`is_ramping`](Self::is_ramping)):
    /// returns `false` and changes nothing otherwise, or when the slowed change per tick is
    /// below 2⁻⁴⁰ or not exact in the number format. A [`FeedGuard`](crate::FeedGuard)
    /// chooses the shift.
    ///
    /// ```
    /// use strak_curves::Bezier;
    /// use strak_trajectory::{CompileOptions, Limits, Path, PathTiming, PlanOptions, Sampler};
    /// let line = Bezier::new([[0.0_f64], [10.0]])?;
    /// let limits = Limits::<1>::new(100.0, 1_000.0, 20_000.0)?;
    /// let timing = PathTiming::<_, 16, 4>::plan(&line, &limits, &PlanOptions::new())?;
    /// let path: Path<f64, 1, 64> = timing.compile(&CompileOptions::new())?;
    /// let mut sampler = Sampler::new(&path);
    /// assert!(sampler.scale_feed_ramp(2));
    /// sampler.hold();
    /// assert!(!sampler.scale_feed_ramp(0)); // a ramp runs
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn scale_feed_ramp(&mut self, shift: u8) -> bool {
        if self.is_ramping() || shift >= 40 {
            return false;
        }
        match self.path.header().ramp.scaled(shift) {
            Some(ramp) => {
                self.ramp = ramp;
                true
            }
            None => false,
        }
    }

    /// Feed hold: ramp down to feed 0 and stand still on the path (ignored after an abort).
    pub fn hold(&mut self) {
        self.sync();
        if self.mode == SamplerState::Running {
            self.mode = SamplerState::Holding;
            self.feed.target = N::ZERO;
        }
        self.refresh();
    }

    /// Resume after a hold: ramp back up to the override (ignored unless holding).
    pub fn resume(&mut self) {
        self.sync();
        if self.mode == SamplerState::Holding {
            self.mode = SamplerState::Running;
            self.feed.target = self.feed_override;
        }
        self.refresh();
    }

    /// Abort: ramp down to feed 0, then finish where the motion stopped (on the path, not at
    /// its end).
    pub fn abort(&mut self) {
        self.sync();
        if matches!(self.mode, SamplerState::Running | SamplerState::Holding) {
            self.mode = SamplerState::Aborting;
            self.feed.target = N::ZERO;
        }
        self.refresh();
    }

    /// The playback point in (fractional) path ticks: where the next sample is taken
    /// (`Path::eval(progress())` is that sample's exact position). For tests and simulation.
    pub fn progress(&self) -> f64 {
        if self.at_end() {
            return f64::from(self.path.ticks());
        }
        let piece = self.piece();
        let start = f64::from(self.path.piece_start(piece));
        let local = if self.left > 0 {
            self.ticks_of(piece).wrapping_sub(self.left)
        } else {
            self.local
        };
        start + f64::from(local) + self.shift.to_f64() + self.theta.to_f64()
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::compile::testing::{Quintic, Smoothstep, Wave, compile_boxed, exact, helix};
    use crate::compile::{CompileOptions, compile};
    use crate::num::Q40;
    use crate::path::Path;
    use crate::plan::Along;
    use std::boxed::Box;
    use strak_curves::ParamCurveDeriv;
    use strak_curves::Scalar;

    fn f<T: Scalar, const A: usize>(x: [T; A]) -> [f64; A] {
        x.map(Scalar::to_f64)
    }

    /// 10⁶ ticks (10 s at 100 kHz) of a 1-axis wave under a rest-to-rest law: every sample
    /// against the exact composition.
    fn million_ticks<N: Kernel>() {
        let curve = Wave {
            offset: 0.0,
            amp: 10.0,
            cycles: 50.0,
        };
        let timing = Smoothstep::new(10.0);
        // Within what playback in `N` can hold (its bound: 1.6·10⁻⁴ in f32, 1.3·10⁻⁶ in Q40).
        let tol = match N::FORMAT {
            crate::NumberFormat::F32 => 2e-4,
            crate::NumberFormat::Q40 => 2e-6,
            crate::NumberFormat::F64 => 1e-6,
        };
        let path: Box<Path<N, 1, 16384>> = compile_boxed(
            &Along::new(&curve, &timing),
            100_000.0,
            &CompileOptions::new().with_tolerance(tol),
        )
        .unwrap();
        assert_eq!(path.ticks(), 1_000_000);
        let n_max = path.pieces().iter().map(|p| p.ticks()).max().unwrap();
        assert_eq!(n_max, 256);
        // refined beyond the uniform grid of 3907 pieces where the tolerance is tight
        let refined = if N::FORMAT == crate::NumberFormat::F64 {
            6000
        } else {
            3907
        };
        assert!(path.pieces().len() >= refined, "{}", path.pieces().len());
        let bound = path.playback_bound();
        let (v_peak, a_peak) = (path.peak_velocity(), path.peak_acceleration());
        let n = f64::from(n_max);
        // Format errors of the velocity and acceleration (rounding of v and Δv¹ propagated
        // over a piece; float additions), on top of the spline's own derivative errors.
        let r = |m: f64| N::rounding_error(m) + N::addition_error(m);
        let v_format = 2.0 * (n + 1.0) * r(v_peak) + n * n * r(a_peak / 1e5) + N::OUT_ERROR;
        let a_format = 2.0 * (n + 1.0) * r(a_peak) + N::OUT_ERROR;
        let mut sampler = Sampler::new(&*path);
        let (mut ep, mut ev, mut ea, mut ee) = (0.0_f64, 0.0_f64, 0.0_f64, 0.0_f64);
        for k in 0..=path.ticks() {
            assert!(!sampler.is_finished());
            let s = sampler.next();
            assert_eq!(s.tick, u64::from(k));
            let (p, v, a) = exact(&curve, &timing, &path, f64::from(k));
            let x = f(s.position)[0];
            ep = ep.max((x - p[0]).abs());
            ev = ev.max((f(s.velocity)[0] - v[0]).abs());
            ea = ea.max((f(s.acceleration)[0] - a[0]).abs());
            // against the compiled polynomial: only the number format's error
            ee = ee.max((x - path.eval(f64::from(k)).position[0]).abs());
            if k == path.ticks() {
                // the end point, bit for bit
                assert_eq!(s.position, path.end_position());
                assert_eq!(f(s.velocity), [0.0]);
            }
        }
        assert!(sampler.is_finished());
        std::println!(
            "{}: pieces {} bound {bound:.2e}; errors: format {ee:.2e}, position {ep:.2e}, \
             velocity {ev:.2e} (peak {v_peak:.1}), acceleration {ea:.2e} (peak {a_peak:.1})",
            N::NAME,
            path.pieces().len()
        );
        assert!(ee <= bound, "format error {ee} > {bound}");
        assert!(ep <= tol + bound, "position error {ep}");
        assert!(ev <= 1e-5 * v_peak + v_format, "velocity error {ev}");
        // the fit's acceleration error grows with its tolerance (200 times wider in f32)
        let fit_share = if N::FORMAT == crate::NumberFormat::F32 {
            2e-3
        } else {
            1e-3
        };
        assert!(
            ea <= fit_share * a_peak + a_format,
            "acceleration error {ea}"
        );
    }

    #[test]
    fn million_ticks_f32() {
        million_ticks::<f32>();
    }

    #[test]
    fn million_ticks_f64() {
        million_ticks::<f64>();
    }

    #[test]
    fn million_ticks_q40() {
        million_ticks::<Q40>();
    }

    fn helix_path<N: Kernel>() -> Path<N, 3, 512> {
        compile(
            &Along::new(&helix(2.0, 2.0, 1.0), &Quintic(0.5)),
            10_000.0,
            // within f32's playback bound (3.9·10⁻⁶ here)
            &CompileOptions::new().with_tolerance(1e-5),
        )
        .unwrap()
    }

    /// `next_position` against `next().position`, bit for bit, over a whole path with a feed
    /// override, a hold and a resume, alternating the two calls on a third sampler.
    fn position_only<N: Kernel>() {
        let path = helix_path::<N>();
        let mut full = Sampler::new(&path);
        let mut pos = Sampler::new(&path);
        let mut mixed = Sampler::new(&path);
        let mut k = 0_u64;
        while !full.is_finished() {
            for s in [&mut full, &mut pos, &mut mixed] {
                match k {
                    400 => s.set_feed(0.6),
                    900 => s.hold(),
                    2500 => s.resume(),
                    3000 => s.set_feed(1.0),
                    _ => {}
                }
            }
            let want = full.next();
            assert_eq!(pos.next_position(), want.position, "tick {k}");
            let m = if k.is_multiple_of(2) {
                mixed.next_position()
            } else {
                mixed.next().position
            };
            assert_eq!(m, want.position, "tick {k} (mixed)");
            assert_eq!(pos.state(), full.state());
            k += 1;
            assert!(k < 20 * u64::from(path.ticks()));
        }
        assert!(pos.is_finished() && mixed.is_finished());
        assert_eq!(pos.next_position(), path.end_position());
        assert!(
            k > u64::from(path.ticks()) + 1000,
            "the hold took time: {k}"
        );
    }

    /// After position-only ticks the velocity and acceleration chains catch up: mixing
    /// `next_position` and `next` gives `next`'s velocities and accelerations, bit for bit in
    /// `Q40` (integer closed form), within a few roundings in floats.
    fn catch_up_after_positions<N: Kernel>(rel: f64) {
        let path = helix_path::<N>();
        let mut full = Sampler::new(&path);
        let mut mixed = Sampler::new(&path);
        let (v_peak, a_peak) = (path.peak_velocity(), path.peak_acceleration());
        let (mut checked, mut k) = (0, 0_u64);
        while !full.is_finished() {
            let want = full.next();
            // runs of 1..=12 position-only ticks between full ones, across piece switches
            if (k * 7 + k / 13) % 13 < 9 {
                assert_eq!(mixed.next_position(), want.position, "tick {k}");
            } else {
                let got = mixed.next();
                assert_eq!(got.position, want.position, "tick {k}");
                for a in 0..3 {
                    let (gv, wv) = (got.velocity[a].to_f64(), want.velocity[a].to_f64());
                    let (ga, wa) = (got.acceleration[a].to_f64(), want.acceleration[a].to_f64());
                    if N::IS_FIXED {
                        assert_eq!(got.velocity, want.velocity, "tick {k}");
                        assert_eq!(got.acceleration, want.acceleration, "tick {k}");
                    }
                    assert!((gv - wv).abs() <= rel * v_peak, "tick {k}: v {gv} vs {wv}");
                    assert!((ga - wa).abs() <= rel * a_peak, "tick {k}: a {ga} vs {wa}");
                }
                checked += 1;
            }
            k += 1;
        }
        assert!(mixed.is_finished());
        assert!(checked > 500, "{checked}");
    }

    #[test]
    fn velocities_catch_up_after_position_only_ticks() {
        catch_up_after_positions::<Q40>(0.0);
        catch_up_after_positions::<f64>(1e-11);
        catch_up_after_positions::<f32>(1e-4);
    }

    #[test]
    fn next_position_is_next_position_bit_for_bit() {
        position_only::<f32>();
        position_only::<f64>();
        position_only::<Q40>();
    }

    /// The control events of the entry-point comparisons: a feed override, a hold, a
    /// resume, back to full feed (then piece switches at full feed and the end).
    /// The ticks at which [`events`] acts.
    const EVENT_TICKS: [u64; 4] = [300, 700, 2300, 2800];

    /// The length of batch `n` starting at tick `k`: `1 + (n·m + n/d) mod 300` (so that
    /// batches start and end inside pieces, at piece switches and at the end), cut at the
    /// next of the [`EVENT_TICKS`], so that a batch never crosses an event.
    fn batch_len(k: u64, n: usize, m: usize, d: usize) -> usize {
        EVENT_TICKS
            .iter()
            .filter(|&&e| e > k)
            .map(|&e| usize::try_from(e - k).unwrap())
            .fold(1 + (n * m + n / d) % 300, usize::min)
    }

    fn events<N: Kernel>(k: u64, s: &mut Sampler<'_, N, 3>) {
        match k {
            300 => s.set_feed(0.6),
            700 => s.hold(),
            2300 => s.resume(),
            2800 => s.set_feed(1.0),
            _ => {}
        }
    }

    /// `next_into` against `next`, bit for bit (`native_to_out` of every value), over a path
    /// in RAM and the same path read from a blob (aligned and at an odd address), with
    /// `next_position` and `next` mixed in on a third sampler.
    fn native_samples<N: Kernel>() {
        let path = helix_path::<N>();
        let mut bytes = std::vec![0_u8; 1 << 16];
        let len = path.to_bytes(&mut bytes[1..]).unwrap();
        bytes.copy_within(1..=len, 0);
        let aligned = crate::PathBlob::<N, 3>::from_bytes(&bytes[..len]).unwrap();
        let mut odd = std::vec![0_u8; len + 1];
        odd[1..].copy_from_slice(&bytes[..len]);
        let unaligned = crate::PathBlob::<N, 3>::from_bytes(&odd[1..]).unwrap();
        for view in [path.view(), aligned.view(), unaligned.view()] {
            let mut full = Sampler::new(view);
            let mut native = Sampler::new(view);
            let mut mixed = Sampler::new(view);
            let mut s = Sample::splat(N::NATIVE_ZERO);
            let mut k = 0_u64;
            let mut checked = 0;
            while !full.is_finished() || k < u64::from(path.ticks()) + 3000 {
                for t in [&mut full, &mut native, &mut mixed] {
                    events(k, t);
                }
                let want = full.next();
                native.next_into(&mut s);
                assert_eq!(s.tick, want.tick, "tick {k}");
                assert_eq!(s.position.map(N::native_to_out), want.position, "tick {k}");
                assert_eq!(s.velocity.map(N::native_to_out), want.velocity, "tick {k}");
                assert_eq!(
                    s.acceleration.map(N::native_to_out),
                    want.acceleration,
                    "tick {k}"
                );
                match k % 5 {
                    0 => assert_eq!(mixed.next_position(), want.position, "tick {k}"),
                    1 | 2 => assert_eq!(mixed.next(), want, "tick {k}"),
                    _ => {
                        let mut m = Sample::splat(N::NATIVE_ZERO);
                        mixed.next_into(&mut m);
                        assert_eq!(m.velocity.map(N::native_to_out), want.velocity, "tick {k}");
                    }
                }
                assert_eq!(native.state(), full.state());
                checked += 1;
                k += 1;
            }
            assert!(native.is_finished() && mixed.is_finished());
            assert!(checked > path.ticks() + 1000, "{checked}");
        }
    }

    #[test]
    fn next_into_is_next_in_the_accumulators_format() {
        native_samples::<f32>();
        native_samples::<f64>();
        native_samples::<Q40>();
    }

    /// A value's every bit as text: `Debug` prints the shortest decimal that reads back
    /// as the same value, and the sign of a zero, which `==` does not compare.
    pub(super) fn bits<T: core::fmt::Debug>(x: &T) -> std::string::String {
        std::format!("{x:?}")
    }

    /// `fill` against as many `next` calls, bit for bit: batches of 1 to 300 samples (so
    /// that batches start and end inside pieces, at piece switches and at the end), with the
    /// control events between batches.
    fn batches<N: Kernel>() {
        let path = helix_path::<N>();
        let mut one = Sampler::new(&path);
        let mut batched = Sampler::new(&path);
        let mut buf = std::vec![Sample::splat(<N::Out as Scalar>::ZERO); 300];
        let (mut k, mut n) = (0_u64, 0_usize);
        let end = u64::from(path.ticks()) + 4000;
        while k < end {
            for s in [&mut one, &mut batched] {
                events(k, s);
            }
            let len = batch_len(k, n, 37, 3);
            batched.fill(&mut buf[..len]);
            for (i, got) in buf[..len].iter().enumerate() {
                assert_eq!(
                    bits(got),
                    bits(&one.next()),
                    "tick {} (batch {n}, {len} long)",
                    k + i as u64
                );
            }
            assert_eq!(bits(&batched.state()), bits(&one.state()));
            assert_eq!(batched.progress(), one.progress());
            k += len as u64;
            n += 1;
        }
        assert!(one.is_finished() && batched.is_finished());
        let mut empty: [Sample<N::Out, 3>; 0] = [];
        batched.fill(&mut empty);
        assert_eq!(batched.next(), one.next());
    }

    #[test]
    fn fill_is_next_called_as_often() {
        batches::<f32>();
        batches::<f64>();
        batches::<Q40>();
    }

    /// `fill_positions` against as many `next_position` calls, bit for bit, in batches as
    /// in [`batches`], with the control events between batches and every fifth batch
    /// followed by one `next()` on both (the lagging chains caught up after a batch).
    fn position_batches<N: Kernel>() {
        let path = helix_path::<N>();
        let mut one = Sampler::new(&path);
        let mut batched = Sampler::new(&path);
        let mut buf = std::vec![[<N::Out as Scalar>::ZERO; 3]; 300];
        let (mut k, mut n) = (0_u64, 0_usize);
        let end = u64::from(path.ticks()) + 4000;
        while k < end {
            for s in [&mut one, &mut batched] {
                events(k, s);
            }
            let len = batch_len(k, n, 41, 5);
            batched.fill_positions(&mut buf[..len]);
            for (i, got) in buf[..len].iter().enumerate() {
                assert_eq!(
                    bits(got),
                    bits(&one.next_position()),
                    "tick {} (batch {n})",
                    k + i as u64
                );
            }
            k += len as u64;
            if n % 5 == 4 && !EVENT_TICKS.contains(&k) {
                assert_eq!(batched.next(), one.next(), "tick {k}");
                k += 1;
            }
            assert_eq!(bits(&batched.state()), bits(&one.state()));
            n += 1;
        }
        assert!(one.is_finished() && batched.is_finished());
        batched.fill_positions(&mut []);
        assert_eq!(batched.next(), one.next());
    }

    #[test]
    fn fill_positions_is_next_position_called_as_often() {
        position_batches::<f32>();
        position_batches::<f64>();
        position_batches::<Q40>();
    }

    fn exact_loads<N: Kernel>() {
        let path = helix_path::<N>();
        assert!(path.pieces().len() > 20);
        let mut sampler = Sampler::new(&path);
        let mut pieces = path.pieces().iter().peekable();
        for k in 0..=path.ticks() {
            let s = sampler.next();
            if let Some(p) = pieces.next_if(|p| p.start() == k) {
                for (a, st) in p.axes().iter().enumerate() {
                    assert_eq!(s.position[a], st.position.to_out(), "tick {k}");
                    assert_eq!(s.velocity[a], st.velocity.to_out(), "tick {k}");
                    assert_eq!(s.acceleration[a], st.acceleration.to_out(), "tick {k}");
                }
            }
        }
        assert!(pieces.next().is_none(), "every piece start was seen");
    }

    #[test]
    fn piece_switches_are_exact_loads() {
        exact_loads::<f32>();
        exact_loads::<f64>();
        exact_loads::<Q40>();
    }

    fn end_is_exact<N: Kernel>() {
        let curve = helix(2.0, 2.0, 1.0);
        let path = helix_path::<N>();
        let want = curve.deriv(1.0, 0).map(|x| N::out_from_f64(x).unwrap());
        assert_eq!(path.end_position(), want);
        let mut sampler = Sampler::new(&path);
        let mut last = sampler.next();
        while !sampler.is_finished() {
            last = sampler.next();
        }
        assert_eq!(last.tick, u64::from(path.ticks()));
        assert_eq!(last.position, want);
        assert_eq!(f(last.velocity), [0.0; 3]);
        // the quintic ends with zero acceleration; the spline's end value is close to it
        assert!(f(last.acceleration).iter().all(|a| a.abs() < 1.0));
        // afterwards: standing at the end
        for t in 1..=3 {
            let s = sampler.next();
            assert_eq!(s.tick, last.tick + t);
            assert_eq!(s.position, want);
            assert_eq!(f(s.velocity), [0.0; 3]);
            assert_eq!(f(s.acceleration), [0.0; 3]);
        }
        assert_eq!(sampler.state(), SamplerState::Finished);
    }

    #[test]
    fn final_sample_is_the_end_point_exactly() {
        end_is_exact::<f32>();
        end_is_exact::<f64>();
        end_is_exact::<Q40>();
    }

    /// Runs the sampler to the end with `control(tick, sampler)` called before each sample;
    /// checks that every sample lies on the compiled path, never jumps and stays within the
    /// acceleration limit. Returns the number of samples and the samples' tick count at the
    /// first standstill (feed 0), if any.
    fn run_checked<N: Kernel>(
        path: &Path<N, 3, 512>,
        mut control: impl FnMut(u64, &mut Sampler<'_, N, 3>),
    ) -> (u64, Sampler<'_, N, 3>) {
        let mut sampler = Sampler::new(path);
        let t = path.period();
        // a discrete slack: the jerk of feed changes and of the path over one tick, and the
        // rounding of the format (Newton evaluation in N: a few roundings of the values)
        let jerk = path.jerk_limit() + path.peak_jerk();
        let a_bound = path.acceleration_limit() + 3.0 * jerk * t;
        let slack = |mag: f64| 32.0 * (N::rounding_error(mag) + N::OUT_ERROR);
        let x_slack = 2.0 * path.playback_bound() + slack(3.0);
        let mut prev: Option<Sample<N::Out, 3>> = None;
        let mut count = 0_u64;
        let mut max_dv = 0.0_f64;
        while !sampler.is_finished() {
            control(count, &mut sampler);
            let progress = sampler.progress();
            let s = sampler.next();
            count += 1;
            assert!(count < 10 * u64::from(path.ticks()), "does not end");
            // on the compiled path
            let on = path.eval(progress);
            for a in 0..3 {
                let x = f(s.position)[a];
                assert!(
                    (x - on.position[a]).abs() <= x_slack,
                    "{} tick {count}: off the path: {x} vs {} (progress {progress}, slack {x_slack})",
                    N::NAME,
                    on.position[a]
                );
            }
            if let Some(p) = prev {
                for a in 0..3 {
                    let dx = (f(s.position)[a] - f(p.position)[a]).abs();
                    assert!(
                        dx <= path.peak_velocity() * t + x_slack,
                        "jump at {count}: {dx}"
                    );
                    let dv = (f(s.velocity)[a] - f(p.velocity)[a]).abs() / t;
                    let lim = a_bound + slack(path.peak_velocity()) / t;
                    assert!(dv <= lim, "acceleration at {count}: {dv} > {lim}");
                    max_dv = max_dv.max(dv);
                }
            }
            prev = Some(s);
        }
        let last = prev.unwrap();
        assert_eq!(f(last.velocity), [0.0; 3]);
        std::println!(
            "{}: largest |Δv|/T {max_dv:.1}, a_peak {:.1}, a_max {:.1}, slack {:.1}",
            N::NAME,
            path.peak_acceleration(),
            path.acceleration_limit(),
            a_bound - path.acceleration_limit() + slack(path.peak_velocity()) / t
        );
        (count, sampler)
    }

    fn override_run<N: Kernel>() {
        let path = helix_path::<N>();
        let (count, sampler) = run_checked(&path, |k, s| match k {
            500 => s.set_feed(0.5),
            2000 => s.set_feed(1.0),
            2600 => s.set_feed(0.2),
            2700 => s.set_feed(0.9),
            _ => {}
        });
        assert!(count > u64::from(path.ticks()) + 100, "slower: {count}");
        assert!((sampler.feed() - 0.9).abs() < 1e-7);
        let mut sampler = Sampler::new(&path);
        // the end is exact after overrides, too
        let mut last = sampler.next();
        sampler.set_feed(0.7);
        while !sampler.is_finished() {
            last = sampler.next();
        }
        assert_eq!(last.position, path.end_position());
    }

    #[test]
    fn feed_override_without_jumps_within_the_acceleration_limit() {
        override_run::<f32>();
        override_run::<f64>();
        override_run::<Q40>();
    }

    fn back_to_full_feed<N: Kernel>() {
        let path = helix_path::<N>();
        let mut sampler = Sampler::new(&path);
        for _ in 0..300 {
            sampler.next();
        }
        sampler.set_feed(0.3);
        for _ in 0..500 {
            sampler.next();
        }
        sampler.set_feed(1.0);
        let mut k = 0;
        while !(sampler.feed.is_idle() && sampler.theta == N::ZERO) {
            sampler.next();
            k += 1;
            assert!(k < 2000);
        }
        // forward differencing again, at a fractional offset from the tick grid
        assert!(sampler.shift > N::ZERO && sampler.shift < N::ONE);
        let slack = 4.0 * path.playback_bound() + 64.0 * N::rounding_error(3.0) + 1e-12;
        let mut last = None;
        while !sampler.is_finished() {
            let progress = sampler.progress();
            let s = sampler.next();
            if !sampler.is_finished() {
                let on = path.eval(progress);
                for a in 0..3 {
                    assert!((f(s.position)[a] - on.position[a]).abs() <= slack);
                    assert!((f(s.velocity)[a] - on.velocity[a]).abs() <= 1e-3);
                }
            }
            last = Some(s);
        }
        assert_eq!(last.unwrap().position, path.end_position());
    }

    #[test]
    fn forward_differencing_resumes_at_full_feed() {
        back_to_full_feed::<f32>();
        back_to_full_feed::<f64>();
        back_to_full_feed::<Q40>();
    }

    fn hold_and_resume<N: Kernel>() {
        let path = helix_path::<N>();
        let mut held_at = None;
        let mut standing = 0;
        let (count, _) = run_checked(&path, |k, s| {
            if k == 1500 {
                s.hold();
                assert_eq!(s.state(), SamplerState::Holding);
            }
            if s.state() == SamplerState::Holding && s.feed() == 0.0 && s.feed.is_idle() {
                // standing still: the same position every tick
                let here = s.progress();
                assert_eq!(*held_at.get_or_insert(here), here);
                standing += 1;
                if standing == 1000 {
                    s.resume();
                    assert_eq!(s.state(), SamplerState::Running);
                }
            }
        });
        assert_eq!(standing, 1000);
        assert!(count > u64::from(path.ticks()) + 1000);
        let held = held_at.unwrap();
        // the ramp to rest takes about 1300 ticks (its jerk budget includes 3·φ·φ̇·p'')
        assert!(held > 1500.0 && held < 3000.0, "{held}");
    }

    #[test]
    fn hold_stands_still_and_resume_reaches_the_exact_end() {
        hold_and_resume::<f32>();
        hold_and_resume::<f64>();
        hold_and_resume::<Q40>();
    }

    fn held_samples_do_not_move<N: Kernel>() {
        let path = helix_path::<N>();
        let mut sampler = Sampler::new(&path);
        for _ in 0..1000 {
            sampler.next();
        }
        sampler.hold();
        let mut s = sampler.next();
        for _ in 0..5000 {
            s = sampler.next();
        }
        assert_eq!(f(s.velocity), [0.0; 3]);
        assert_eq!(f(s.acceleration), [0.0; 3]);
        let t = sampler.next();
        assert_eq!(t.position, s.position);
        assert_eq!(t.tick, s.tick + 1);
        // a new override while holding is kept for the resume
        sampler.set_feed(0.5);
        assert_eq!(sampler.feed(), 0.0);
        sampler.resume();
        for _ in 0..5000 {
            sampler.next();
        }
        assert_eq!(sampler.feed(), 0.5);
    }

    #[test]
    fn held_samples_repeat_bit_for_bit() {
        held_samples_do_not_move::<f32>();
        held_samples_do_not_move::<Q40>();
    }

    fn abort_stops<N: Kernel>() {
        let path = helix_path::<N>();
        let (count, mut sampler) = run_checked(&path, |k, s| {
            if k == 1200 {
                s.abort();
                s.resume(); // ignored
                s.hold(); // ignored
                assert_eq!(s.state(), SamplerState::Aborting);
            }
        });
        assert!(sampler.is_finished());
        let stop = sampler.progress();
        assert!(
            stop > 1200.0 && stop < f64::from(path.ticks()) - 1000.0,
            "{stop}"
        );
        assert!(count < u64::from(path.ticks()));
        // the stop position stays
        let a = sampler.next();
        let b = sampler.next();
        assert_eq!(a.position, b.position);
        assert_eq!(f(b.velocity), [0.0; 3]);
        let on = path.eval(stop).position;
        for (x, y) in f(a.position).into_iter().zip(on) {
            assert!((x - y).abs() < 1e-3);
        }
    }

    #[test]
    fn abort_ramps_down_and_finishes_on_the_path() {
        abort_stops::<f32>();
        abort_stops::<f64>();
        abort_stops::<Q40>();
    }

    #[test]
    fn set_feed_clamps_and_ignores_nan() {
        let path = helix_path::<f64>();
        let mut s = Sampler::new(&path);
        s.set_feed(f32::NAN);
        assert_eq!(s.feed_override(), 1.0);
        s.set_feed(-3.0);
        assert_eq!(s.feed_override(), 0.0);
        s.set_feed(7.0);
        assert_eq!(s.feed_override(), 1.0);
        s.set_feed(0.25);
        assert_eq!(s.feed_override(), 0.25);
        assert_eq!(s.feed(), 1.0); // the ramp has not started yet
        s.next();
        assert!(s.feed() < 1.0);
    }

    #[test]
    fn zero_feed_from_the_start_stops_and_stands() {
        let path = helix_path::<Q40>();
        let mut s = Sampler::new(&path);
        s.set_feed(0.0);
        for _ in 0..20_000 {
            s.next();
        }
        // the ramp to feed 0 took a while; then it stands
        let stop = s.progress();
        assert!(stop > 10.0 && stop < 2000.0, "{stop}");
        for _ in 0..100_000 {
            s.next();
        }
        assert_eq!(s.progress(), stop);
        assert_eq!(f(s.next().velocity), [0.0; 3]);
        assert!(!s.is_finished());
    }

    /// A line at constant speed (no planned acceleration): a feed change may use the whole
    /// acceleration and jerk limits, and reaches them without exceeding them.
    fn ramp_uses_and_respects_the_limits<N: Kernel>() {
        let line = strak_curves::Bezier::new([[0.0_f64, 0.0], [30.0, 40.0]]).unwrap();
        let (a_max, j_max) = (1000.0, 1.0e5);
        let path: Path<N, 2, 64> = compile(
            &Along::new(&line, &crate::compile::testing::Linear(0.5)),
            10_000.0,
            &CompileOptions::new().with_limits(a_max, j_max),
        )
        .unwrap();
        assert!((path.peak_velocity() - 100.0).abs() < 1e-9);
        assert!(path.peak_acceleration() < 1e-9);
        let t = path.period();
        let mut sampler = Sampler::new(&path);
        let norm = |x: [f64; 2]| libm::sqrt(x[0] * x[0] + x[1] * x[1]);
        let (mut prev_v, mut prev_a) = (None::<[f64; 2]>, None::<[f64; 2]>);
        let (mut max_fd, mut max_a, mut max_j) = (0.0_f64, 0.0_f64, 0.0_f64);
        let mut k = 0;
        while !sampler.is_finished() {
            if k == 500 {
                sampler.set_feed(0.2);
            }
            if k == 2000 {
                sampler.set_feed(1.0);
            }
            let s = sampler.next();
            let (v, a) = (f(s.velocity), f(s.acceleration));
            if let (Some(pv), Some(pa)) = (prev_v, prev_a) {
                max_fd = max_fd.max(norm([v[0] - pv[0], v[1] - pv[1]]) / t);
                max_j = max_j.max(norm([a[0] - pa[0], a[1] - pa[1]]) / t);
            }
            max_a = max_a.max(norm(a));
            prev_v = Some(v);
            prev_a = Some(a);
            k += 1;
        }
        std::println!(
            "{}: |Δv|/T {max_fd:.2}, |a| {max_a:.2}, |Δa|/T {max_j:.0}",
            N::NAME
        );
        // the finite differences of the velocity and the reported acceleration
        assert!(max_fd <= a_max * 1.001 && max_fd > 0.95 * a_max, "{max_fd}");
        assert!(max_a <= a_max * 1.001 && max_a > 0.95 * a_max, "{max_a}");
        // jerk: within the limit (one tick of α may be rounded in the format)
        assert!(max_j <= j_max * 1.01 && max_j > 0.9 * j_max, "{max_j}");
    }

    #[test]
    fn feed_ramps_reach_but_never_exceed_the_limits() {
        ramp_uses_and_respects_the_limits::<f32>();
        ramp_uses_and_respects_the_limits::<f64>();
        ramp_uses_and_respects_the_limits::<Q40>();
    }
}
