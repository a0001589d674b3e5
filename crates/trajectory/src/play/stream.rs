//! Playing a stream's pieces as they arrive: the sampler's tick kernels, fed from a
//! single-producer single-consumer queue that the main loop fills ([`Stream::poll`]) and the
//! tick interrupt drains.
//!
//! [`Stream::poll`]: crate::Stream::poll

use heapless::spsc::Consumer;

use super::kernel::Kernel;
use crate::path::{AxisState, Piece, Sample};

/// Plays the pieces of a [`Stream`](crate::Stream) from a queue, one [`Sample`] per call of
/// [`next`](Self::next), in constant time: a forward-differencing tick inside a piece, and
/// on a piece's last tick the load of the next one from the queue (the same tick kernels as
/// [`Sampler`](crate::Sampler)'s, so the same bits). While the queue is empty it holds
/// still: at the end of the motion (the stream's pieces end at rest), or, if the main
/// loop fell behind with [`poll`](crate::Stream::poll), wherever the last piece ended
/// ([`underruns`](Self::underruns) counts those ticks: keep the queue ahead).
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
/// let mut sampler = StreamSampler::new(consumer, [0.0, 0.0]);
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
    /// Ticks left in the current piece, this one included; 0 while holding.
    left: u32,
    /// The next sample's tick.
    tick: u64,
    /// Whether the state holding still is at rest (the end of a motion).
    at_rest: bool,
    underruns: u32,
}

impl<N: Kernel, const A: usize> core::fmt::Debug for StreamSampler<'_, N, A> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("StreamSampler")
            .field("state", &self.state)
            .field("left", &self.left)
            .field("tick", &self.tick)
            .field("queued", &self.queue.len())
            .finish_non_exhaustive()
    }
}

impl<'q, N: Kernel, const A: usize> StreamSampler<'q, N, A> {
    /// A sampler holding still at `start` (the stream's start) until the first piece
    /// arrives in `queue`.
    pub fn new(queue: Consumer<'q, Piece<N, A>>, start: [N; A]) -> Self {
        StreamSampler {
            queue,
            state: start.map(|position| AxisState {
                position,
                ..AxisState::default()
            }),
            left: 0,
            tick: 0,
            at_rest: true,
            underruns: 0,
        }
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
        self.last_or_hold(tick)
    }

    /// A piece's last tick (then the next piece from the queue, or holding), or a tick
    /// while holding (a piece from the queue starts, or it holds on).
    #[inline(always)]
    fn last_or_hold(&mut self, tick: u64) -> Sample<N::Out, A> {
        if self.left == 0 {
            let Some(piece) = self.queue.dequeue() else {
                return self.hold(tick);
            };
            (self.state, self.left) = (piece.axes, piece.ticks);
            if self.left > 1 {
                self.left -= 1;
                return N::tick_sample(&mut self.state, tick);
            }
        }
        match self.queue.dequeue() {
            Some(piece) => {
                self.left = piece.ticks;
                N::switch_sample(&mut self.state, &piece.axes, tick)
            }
            None => {
                self.left = 0;
                let sample = N::tick_sample(&mut self.state, tick);
                let zero = N::ZERO;
                self.at_rest = self
                    .state
                    .iter()
                    .all(|s| s.velocity == zero && s.acceleration == zero);
                sample
            }
        }
    }

    /// The sample of a tick without a piece: the position held, no velocity or acceleration.
    fn hold(&mut self, tick: u64) -> Sample<N::Out, A> {
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

    /// Whether no piece is playing: before the first, at the end of the motion, or after an
    /// underrun.
    ///
    /// ```
    /// # use heapless::spsc::Queue;
    /// # use strak_trajectory::{Piece, StreamSampler};
    /// let mut queue = Queue::<Piece<f64, 1>, 4>::new();
    /// let (_, consumer) = queue.split();
    /// assert!(StreamSampler::new(consumer, [0.0]).is_holding());
    /// ```
    pub fn is_holding(&self) -> bool {
        self.left == 0
    }

    /// The ticks held still while the motion had not come to rest: the queue ran empty
    /// under a moving axis (the main loop polled too late). The stream's pieces end at rest
    /// wherever it stops, so a loop that keeps the queue ahead never counts one.
    ///
    /// ```
    /// # use heapless::spsc::Queue;
    /// # use strak_trajectory::{Piece, StreamSampler};
    /// let mut queue = Queue::<Piece<f64, 1>, 4>::new();
    /// let (_, consumer) = queue.split();
    /// let mut sampler = StreamSampler::new(consumer, [0.0]);
    /// sampler.next();
    /// assert_eq!(sampler.underruns(), 0); // holding at rest before the first piece
    /// ```
    pub fn underruns(&self) -> u32 {
        self.underruns
    }
}
