//! Playing a stream's pieces as they arrive: the sampler's tick kernels, fed from a
//! single-producer single-consumer queue that the main loop fills ([`Stream::poll`]) and the
//! tick interrupt drains, with the sampler's feed ramp for override, hold, resume, abort and
//! quick stop.
//!
//! [`Stream::poll`]: crate::Stream::poll

use heapless::spsc::Consumer;

use super::SamplerState;
use super::feed::FeedRamp;
use super::kernel::Kernel;
use crate::error::Error;
use crate::path::{AxisState, FeedRampLimits, Newton, Piece, Sample};
use crate::stream::{Stream, StreamCurve};

/// Plays the pieces of a [`Stream`] from a queue, one [`Sample`] per call of
/// [`next`](Self::next), in constant time: a forward-differencing tick inside a piece, and
/// on a piece's last tick the load of the next one from the queue (the same tick kernels as
/// [`Sampler`](crate::Sampler)'s, so the same bits). While the queue is empty it holds
/// still: at the end of the motion (the stream's pieces end at rest), or, if the main
/// loop fell behind with [`poll`](crate::Stream::poll), wherever the last piece ended
/// ([`underruns`](Self::underruns) counts those ticks: keep the queue ahead).
///
/// # Feed
/// [`set_feed`](Self::set_feed) (override in `[0, 1]`), [`hold`](Self::hold),
/// [`resume`](Self::resume), [`abort`](Self::abort) and [`quick_stop`](Self::quick_stop)
/// ramp the feed factor `φ` as [`Sampler`](crate::Sampler)'s do: the playback point moves
/// `φ` ticks per tick along the pieces (Newton's forward-difference formula at the
/// fractional offset), so the motion stays on the path and never jumps, and the ramp keeps
/// within what the stream's plan leaves free of the limits
/// ([`PlanOptions::feed_share`](crate::PlanOptions::feed_share)): `|ẍ| = |φ²·p″ + φ̇·p′|`
/// and the jerk with the ramp's terms stay within the machine's limits. The ramps take
/// effect at once, whatever the queue holds; overrides above 100 % raise the feeds of moves
/// not yet compiled ([`Stream::set_feed_override`]).
///
/// ```
/// use heapless::spsc::Queue;
/// use strak_trajectory::{Limits, Move, Piece, Stream, StreamOptions, StreamSampler};
/// let limits = Limits::new(100.0, 2_000.0, 50_000.0)?;
/// let mut stream = Stream::<2, 8, 32>::new([0.0, 0.0], limits, StreamOptions::new(1_000.0))?;
/// stream.push(&Move::line([5.0, 0.0]))?;
/// stream.finish()?;
/// let mut queue = Queue::<Piece<f32, 2>, 32>::new();
/// let (mut producer, consumer) = queue.split();
/// let mut sampler = StreamSampler::new(consumer, &stream)?;
/// let mut last = sampler.next(); // nothing queued yet: holds still at the start
/// for _ in 0..200 {
///     stream.poll(&mut producer)?; // the main loop
///     last = sampler.next(); // the tick interrupt
/// }
/// assert_eq!(last.position, [5.0, 0.0]);
/// assert!(sampler.is_holding() && sampler.underruns() == 0);
/// # Ok::<(), strak_trajectory::Error>(())
/// ```
pub struct StreamSampler<'q, N: Kernel, const A: usize> {
    queue: Consumer<'q, Piece<N, A>>,
    state: [AxisState<N>; A],
    /// Ticks [`next`](Self::next) may still take on its fast path (full feed, no ramp, on
    /// the playback point): the ticks left in the current piece, this one included; 0 off
    /// the fast path and while holding.
    left: u32,
    /// The ticks left in the current piece off the fast path (0: no piece plays).
    remaining: u32,
    /// Whether `left` counts (the fast path) or `remaining` does.
    fast: bool,
    /// The next sample's tick.
    tick: u64,
    /// Whether the state holding still is at rest (the end of a motion).
    at_rest: bool,
    underruns: u32,
    feed: FeedRamp<N>,
    /// The ramp of overrides, holds, resumes and aborts ([`scale_feed_ramp`](Self::scale_feed_ramp)).
    ramp: FeedRampLimits<N>,
    /// The ramp of a quick stop: the whole feed reserve.
    full: FeedRampLimits<N>,
    /// Whether a quick stop runs (with the `full` ramp).
    quick: bool,
    feed_override: N,
    mode: SamplerState,
    /// The playback point's offset from the state, with `shift + theta ∈ [0, 1)`.
    theta: N,
    /// The offset by which the state, and every piece loaded, lies off the tick grid.
    shift: N,
}

impl<N: Kernel, const A: usize> core::fmt::Debug for StreamSampler<'_, N, A> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("StreamSampler")
            .field("state", &self.state)
            .field("left", &self.left)
            .field("remaining", &self.remaining)
            .field("tick", &self.tick)
            .field("mode", &self.mode)
            .field("feed", &self.feed.phi)
            .field("queued", &self.queue.len())
            .finish_non_exhaustive()
    }
}

impl<'q, N: Kernel, const A: usize> StreamSampler<'q, N, A> {
    /// A sampler holding still where `stream`'s motion is (its start, for a new stream)
    /// until the first piece arrives in `queue`, at full feed, with the stream's feed ramp.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] when the position or the ramp's constants do not fit `N`.
    pub fn new<const Q: usize, const Z: usize, C: StreamCurve<A>, const R: usize>(
        queue: Consumer<'q, Piece<N, A>>,
        stream: &Stream<A, Q, Z, C, R>,
    ) -> Result<Self, Error> {
        let mut state = [AxisState::ZERO; A];
        for (s, x) in state.iter_mut().zip(stream.position()?) {
            s.position = N::from_f64(x).ok_or(Error::OutOfRange)?;
        }
        let (omega, alpha, rate) = stream.feed_ramp();
        let ramp = FeedRampLimits::from_rates(omega, alpha, rate)?;
        Ok(StreamSampler {
            queue,
            state,
            left: 0,
            remaining: 0,
            fast: true,
            tick: 0,
            at_rest: true,
            underruns: 0,
            feed: FeedRamp::full(),
            ramp,
            full: ramp,
            quick: false,
            feed_override: N::ONE,
            mode: SamplerState::Running,
            theta: N::ZERO,
            shift: N::ZERO,
        })
    }

    /// The next setpoint; call once per tick. Constant time, no panic path.
    #[allow(clippy::should_implement_trait)]
    #[inline(always)] // into the caller's tick handler, like `Sampler::next`
    pub fn next(&mut self) -> Sample<N::Out, A> {
        let tick = self.tick;
        self.tick = tick.wrapping_add(1);
        if self.left > 1 {
            self.left -= 1;
            return N::tick_sample(&mut self.state, tick);
        }
        self.next_other(tick)
    }

    /// A tick off the fast path's inner ticks: a piece's last tick at full feed, holding,
    /// or interpolation under a feed ramp.
    #[inline(never)]
    fn next_other(&mut self, tick: u64) -> Sample<N::Out, A> {
        if self.fast {
            return self.last_or_hold(tick);
        }
        let sample = self.interpolate(tick);
        self.refresh();
        sample
    }

    /// At full feed: a piece's last tick (then the next piece from the queue, or holding),
    /// or a tick while holding (a piece from the queue starts, or it holds on).
    fn last_or_hold(&mut self, tick: u64) -> Sample<N::Out, A> {
        if self.left == 0 {
            let Some(piece) = self.queue.dequeue() else {
                return self.held(tick);
            };
            self.left = self.load(&piece);
            if self.left > 1 {
                self.left -= 1;
                return N::tick_sample(&mut self.state, tick);
            }
        }
        match self.queue.dequeue() {
            Some(piece) if self.shift == N::ZERO => {
                self.left = piece.ticks;
                N::switch_sample(&mut self.state, &piece.axes, tick)
            }
            Some(piece) => {
                let sample = N::tick_sample(&mut self.state, tick);
                self.left = self.load(&piece);
                sample
            }
            None => {
                self.left = 0;
                let sample = N::tick_sample(&mut self.state, tick);
                self.note_rest();
                sample
            }
        }
    }

    /// Loads `piece` into the state, shifted off the grid by `shift`; returns its ticks.
    fn load(&mut self, piece: &Piece<N, A>) -> u32 {
        self.state = piece.axes;
        if self.shift != N::ZERO {
            let c = Newton::at(self.shift);
            for s in &mut self.state {
                *s = s.shifted(&c);
            }
        }
        piece.ticks
    }

    /// Records whether the state left after the last piece is at rest.
    fn note_rest(&mut self) {
        let zero = N::ZERO;
        self.at_rest = self
            .state
            .iter()
            .all(|s| s.velocity == zero && s.acceleration == zero);
    }

    /// The sample of a tick without a piece: the position held, no velocity or acceleration.
    fn held(&mut self, tick: u64) -> Sample<N::Out, A> {
        if !self.at_rest {
            self.underruns = self.underruns.saturating_add(1);
        }
        let zero = N::ZERO.to_out();
        Sample {
            tick,
            position: self.state.map(|s| s.position.to_out()),
            velocity: [zero; A],
            acceleration: [zero; A],
        }
    }

    /// A tick under the feed ramp: the sample at the playback point (`x = p(i + θ)`,
    /// `v = φ·p′`, `a = φ²·p″ + φ̇·p′`, per tick of the pieces), then the ramp's step and
    /// the playback point `φ` ticks on. After a stop (an abort or quick stop, at feed 0)
    /// it holds there, and drops one stale piece from the queue per tick.
    fn interpolate(&mut self, tick: u64) -> Sample<N::Out, A> {
        if self.mode == SamplerState::Finished {
            let _ = self.queue.dequeue();
            return self.held(tick);
        }
        if self.remaining == 0 {
            match self.queue.dequeue() {
                Some(piece) => self.remaining = self.load(&piece),
                None if self.mode == SamplerState::Aborting => {
                    // Nothing plays: an abort stops at once.
                    self.stop_here();
                    return self.held(tick);
                }
                None => {
                    self.step_feed();
                    return self.held(tick);
                }
            }
        }
        let c = Newton::at(self.theta);
        let phi = self.feed.phi;
        let phi_dot = self.feed.omega * self.ramp.rate;
        let mut sample = Sample::splat(N::ZERO.to_out());
        sample.tick = tick;
        let values = sample
            .position
            .iter_mut()
            .zip(sample.velocity.iter_mut())
            .zip(sample.acceleration.iter_mut());
        for (s, ((x, v), a)) in self.state.iter().zip(values) {
            let p = s.position + c.c1 * s.delta1 + c.c2 * s.delta2 + c.c3 * s.delta3;
            let dp = s.velocity + c.c1 * s.velocity_delta1 + c.c2 * s.velocity_delta2;
            let ddp = s.acceleration + c.c1 * s.acceleration_delta;
            (*x, *v, *a) = (
                p.to_out(),
                (phi * dp).to_out(),
                (phi * phi * ddp + phi_dot * dp).to_out(),
            );
        }
        if self.mode == SamplerState::Aborting && phi == N::ZERO && self.feed.is_idle() {
            self.stop_here();
            return sample;
        }
        self.step_feed();
        self.advance();
        sample
    }

    /// One step of the feed ramp (a quick stop's own ramp while one runs).
    fn step_feed(&mut self) {
        let ramp = if self.quick { self.full } else { self.ramp };
        self.feed.step(&ramp);
    }

    /// Moves the playback point `φ` ticks on: the state steps a tick when the point
    /// crosses one (to the next piece from the queue at a piece's end), and when the ramp has
    /// returned to full feed the state is shifted onto the point, so that forward
    /// differencing resumes there (and later pieces load shifted by the same fraction).
    fn advance(&mut self) {
        self.theta = self.theta + self.feed.phi;
        if self.shift + self.theta >= N::ONE {
            self.theta = self.theta - N::ONE;
            self.step_tick();
        }
        if self.feed.phi == N::ONE && self.feed.is_idle() && self.theta != N::ZERO {
            let c = Newton::at(self.theta);
            for s in &mut self.state {
                *s = s.shifted(&c);
            }
            self.shift = self.shift + self.theta;
            self.theta = N::ZERO;
        }
    }

    /// The state one tick on: inside the piece, or the next piece, or (none queued) past
    /// the piece's end, holding from there.
    fn step_tick(&mut self) {
        if self.remaining > 1 {
            self.remaining -= 1;
            for s in &mut self.state {
                s.step();
            }
            return;
        }
        match self.queue.dequeue() {
            Some(piece) => self.remaining = self.load(&piece),
            None => {
                self.remaining = 0;
                for s in &mut self.state {
                    s.step();
                }
                self.note_rest();
            }
        }
    }

    /// Ends an abort or quick stop at the playback point: the state rests there and the
    /// sampler is finished.
    fn stop_here(&mut self) {
        let c = Newton::at(self.theta);
        for s in &mut self.state {
            *s = AxisState {
                position: s.shifted(&c).position,
                ..AxisState::ZERO
            };
        }
        (self.theta, self.shift, self.remaining) = (N::ZERO, N::ZERO, 0);
        (self.mode, self.quick, self.at_rest) = (SamplerState::Finished, false, true);
    }

    /// Chooses the fast path or interpolation after every change other than a fast tick:
    /// the fast path while running at full feed with no ramp, on the playback point.
    fn refresh(&mut self) {
        let fast = self.mode == SamplerState::Running
            && self.feed.phi == N::ONE
            && self.feed.is_idle()
            && self.theta == N::ZERO;
        if fast && !self.fast {
            self.left = self.remaining;
        } else if !fast && self.fast {
            (self.remaining, self.left) = (self.left, 0);
        }
        self.fast = fast;
    }

    /// Sets the feed override `f`, clamped to `[0, 1]` (NaN is ignored): the feed factor
    /// ramps to it at once, within the stream's feed reserve. While holding it is stored for
    /// [`resume`](Self::resume). Converts through `f64` once: not for an FPU-less part's
    /// tick handler.
    ///
    /// ```
    /// # use heapless::spsc::Queue;
    /// # use strak_trajectory::{Limits, Piece, Stream, StreamOptions, StreamSampler};
    /// # let limits = Limits::new(100.0, 2_000.0, 50_000.0)?;
    /// # let stream = Stream::<2, 8, 32>::new([0.0, 0.0], limits, StreamOptions::new(1_000.0))?;
    /// # let mut queue = Queue::<Piece<f32, 2>, 8>::new();
    /// # let (_, consumer) = queue.split();
    /// let mut sampler = StreamSampler::new(consumer, &stream)?;
    /// sampler.set_feed(0.5);
    /// assert_eq!(sampler.feed_override(), 0.5);
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn set_feed(&mut self, f: f32) {
        if f.is_nan() {
            return;
        }
        if let Some(v) = N::from_f64(f64::from(f.clamp(0.0, 1.0))) {
            self.feed_override = v;
            if self.mode == SamplerState::Running {
                self.feed.target = v;
            }
        }
        self.refresh();
    }

    /// The feed override last set (1 initially).
    ///
    /// ```
    /// # use heapless::spsc::Queue;
    /// # use strak_trajectory::{Limits, Piece, Stream, StreamOptions, StreamSampler};
    /// # let limits = Limits::new(100.0, 2_000.0, 50_000.0)?;
    /// # let stream = Stream::<2, 8, 32>::new([0.0, 0.0], limits, StreamOptions::new(1_000.0))?;
    /// # let mut queue = Queue::<Piece<f32, 2>, 8>::new();
    /// # let (_, consumer) = queue.split();
    /// assert_eq!(StreamSampler::new(consumer, &stream)?.feed_override(), 1.0);
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn feed_override(&self) -> f64 {
        self.feed_override.to_f64()
    }

    /// The current feed factor `φ` (moving toward its target during a ramp).
    ///
    /// ```
    /// # use heapless::spsc::Queue;
    /// # use strak_trajectory::{Limits, Piece, Stream, StreamOptions, StreamSampler};
    /// # let limits = Limits::new(100.0, 2_000.0, 50_000.0)?;
    /// # let stream = Stream::<2, 8, 32>::new([0.0, 0.0], limits, StreamOptions::new(1_000.0))?;
    /// # let mut queue = Queue::<Piece<f32, 2>, 8>::new();
    /// # let (_, consumer) = queue.split();
    /// assert_eq!(StreamSampler::new(consumer, &stream)?.feed(), 1.0);
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn feed(&self) -> f64 {
        self.feed.phi.to_f64()
    }

    /// Feed hold: ramp down to feed 0 and stand still on the path (ignored unless running).
    ///
    /// ```
    /// # use heapless::spsc::Queue;
    /// # use strak_trajectory::{Limits, Piece, SamplerState, Stream, StreamOptions, StreamSampler};
    /// # let limits = Limits::new(100.0, 2_000.0, 50_000.0)?;
    /// # let stream = Stream::<2, 8, 32>::new([0.0, 0.0], limits, StreamOptions::new(1_000.0))?;
    /// # let mut queue = Queue::<Piece<f32, 2>, 8>::new();
    /// # let (_, consumer) = queue.split();
    /// let mut sampler = StreamSampler::new(consumer, &stream)?;
    /// sampler.hold();
    /// assert_eq!(sampler.state(), SamplerState::Holding);
    /// sampler.resume();
    /// assert_eq!(sampler.state(), SamplerState::Running);
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn hold(&mut self) {
        if self.mode == SamplerState::Running {
            self.mode = SamplerState::Holding;
            self.feed.target = N::ZERO;
        }
        self.refresh();
    }

    /// Resume after a hold: ramp back up to the override (ignored unless holding).
    pub fn resume(&mut self) {
        if self.mode == SamplerState::Holding {
            self.mode = SamplerState::Running;
            self.feed.target = self.feed_override;
        }
        self.refresh();
    }

    /// Abort: ramp down to feed 0 and stop on the path, then hold there, finished, dropping
    /// the pieces still queued. Then [`Stream::abort`] with [`position`](Self::position)
    /// and [`restart`](Self::restart) start again from there.
    pub fn abort(&mut self) {
        if matches!(self.mode, SamplerState::Running | SamplerState::Holding) {
            self.mode = SamplerState::Aborting;
            self.feed.target = N::ZERO;
        }
        self.refresh();
    }

    /// Quick stop: an [`abort`](Self::abort) with the fastest ramp the stream's feed
    /// reserve allows, whatever [`scale_feed_ramp`](Self::scale_feed_ramp) set for the
    /// others (also during a hold or an abort: it takes over their ramp).
    pub fn quick_stop(&mut self) {
        if self.mode != SamplerState::Finished {
            self.mode = SamplerState::Aborting;
            self.feed.target = N::ZERO;
            self.quick = true;
        }
        self.refresh();
    }

    /// After an abort or a quick stop has finished: drops what the queue still holds and
    /// runs again at full feed from where it stopped; `false` (nothing changed) before.
    /// Call it once the stream has been told where the motion stopped
    /// ([`Stream::abort`]), before it compiles new pieces.
    ///
    /// ```
    /// use heapless::spsc::Queue;
    /// use strak_trajectory::{Limits, Move, Piece, Stream, StreamOptions, StreamSampler};
    /// let limits = Limits::new(100.0, 2_000.0, 50_000.0)?;
    /// let mut stream = Stream::<2, 8, 32>::new([0.0, 0.0], limits, StreamOptions::new(1_000.0))?;
    /// stream.push(&Move::line([100.0, 0.0]))?;
    /// let mut queue = Queue::<Piece<f64, 2>, 64>::new();
    /// let (mut producer, consumer) = queue.split();
    /// let mut sampler = StreamSampler::new(consumer, &stream)?;
    /// for tick in 0..1_000 {
    ///     if tick == 200 { sampler.quick_stop(); }
    ///     if !sampler.is_finished() { stream.poll(&mut producer)?; }
    ///     sampler.next();
    /// }
    /// assert!(sampler.is_finished());
    /// let here = sampler.position();
    /// assert!(here[0] > 0.0 && here[0] < 100.0); // stopped on the way
    /// stream.abort(here)?;
    /// assert!(sampler.restart());
    /// stream.push(&Move::line([0.0, 0.0]))?; // back from there
    /// stream.finish()?;
    /// for _ in 0..3_000 {
    ///     stream.poll(&mut producer)?;
    ///     sampler.next();
    /// }
    /// assert_eq!(sampler.position(), [0.0, 0.0]);
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn restart(&mut self) -> bool {
        if self.mode != SamplerState::Finished {
            return false;
        }
        while self.queue.dequeue().is_some() {}
        self.mode = SamplerState::Running;
        self.feed = FeedRamp::full();
        self.refresh();
        true
    }

    /// Slows the ramps of overrides, holds, resumes and aborts down to `2⁻ˢʰⁱᶠᵗ` of the
    /// stream's (0: its own), as [`Sampler::scale_feed_ramp`](crate::Sampler::scale_feed_ramp)
    /// does; a quick stop keeps the full ramp. Only while no ramp runs: `false` (nothing
    /// changed) otherwise, or when the slowed change per tick is below 2⁻⁴⁰ or not exact in
    /// the number format.
    ///
    /// ```
    /// # use heapless::spsc::Queue;
    /// # use strak_trajectory::{Limits, Piece, Stream, StreamOptions, StreamSampler};
    /// # let limits = Limits::new(100.0, 2_000.0, 50_000.0)?;
    /// # let stream = Stream::<2, 8, 32>::new([0.0, 0.0], limits, StreamOptions::new(1_000.0))?;
    /// # let mut queue = Queue::<Piece<f32, 2>, 8>::new();
    /// # let (_, consumer) = queue.split();
    /// let mut sampler = StreamSampler::new(consumer, &stream)?;
    /// assert!(sampler.scale_feed_ramp(3));
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn scale_feed_ramp(&mut self, shift: u8) -> bool {
        if !self.feed.is_idle() || shift >= 40 {
            return false;
        }
        match self.full.scaled(shift) {
            Some(ramp) => {
                self.ramp = ramp;
                true
            }
            None => false,
        }
    }

    /// What the sampler is doing: running, holding (after [`hold`](Self::hold)), aborting
    /// (ramping down after [`abort`](Self::abort) or [`quick_stop`](Self::quick_stop)) or
    /// finished (stopped after one).
    pub fn state(&self) -> SamplerState {
        self.mode
    }

    /// Whether an abort or quick stop has stopped the motion.
    pub fn is_finished(&self) -> bool {
        self.mode == SamplerState::Finished
    }

    /// Where the state is: the position it holds when no piece plays, or after a stop.
    pub fn position(&self) -> [f64; A] {
        self.state.map(|s| s.position.to_f64())
    }

    /// Whether no piece is playing: before the first, at the end of the motion, after an
    /// underrun, or after a stop.
    ///
    /// ```
    /// # use heapless::spsc::Queue;
    /// # use strak_trajectory::{Limits, Piece, Stream, StreamOptions, StreamSampler};
    /// # let limits = Limits::new(100.0, 2_000.0, 50_000.0)?;
    /// # let stream = Stream::<1, 8, 32>::new([0.0], limits, StreamOptions::new(1_000.0))?;
    /// let mut queue = Queue::<Piece<f64, 1>, 4>::new();
    /// let (_, consumer) = queue.split();
    /// assert!(StreamSampler::new(consumer, &stream)?.is_holding());
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn is_holding(&self) -> bool {
        if self.fast {
            self.left == 0
        } else {
            self.remaining == 0
        }
    }

    /// The ticks held still while the motion had not come to rest: the queue ran empty
    /// under a moving axis (the main loop polled too late). The stream's pieces end at rest
    /// wherever it stops, so a loop that keeps the queue ahead never counts one.
    ///
    /// ```
    /// # use heapless::spsc::Queue;
    /// # use strak_trajectory::{Limits, Piece, Stream, StreamOptions, StreamSampler};
    /// # let limits = Limits::new(100.0, 2_000.0, 50_000.0)?;
    /// # let stream = Stream::<1, 8, 32>::new([0.0], limits, StreamOptions::new(1_000.0))?;
    /// let mut queue = Queue::<Piece<f64, 1>, 4>::new();
    /// let (_, consumer) = queue.split();
    /// let mut sampler = StreamSampler::new(consumer, &stream)?;
    /// sampler.next();
    /// assert_eq!(sampler.underruns(), 0); // holding at rest before the first piece
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn underruns(&self) -> u32 {
        self.underruns
    }
}
