//! The stream: moves pushed one by one while the machine runs, their corners blended,
//! planned in a look-ahead window over the blended path and compiled a stretch of ticks at
//! a time into pieces for the sampler.
//!
//! # How a move flows through
//!
//! 1. [`Stream::push`] keeps the newest move pending until the next one arrives: only then
//!    is its end junction known ([`junction`]). The blend before the pending move (held
//!    back until then, so that two blends taking all of a short line between them can be
//!    joined with a shared curvature, [`chain`]) and the pending move's part between its
//!    blends become segments of the path; each segment's speed
//!    limits are sampled into zones ([`PlanOptions`]: curvature, turning jerk, per-axis
//!    limits, the moves' feeds) and appended to the window ([`LookAhead`]), which keeps a
//!    plan that comes to rest at the end of the path known so far.
//! 2. [`Stream::poll`] compiles the next stretch of ticks: it commits zones from the front of
//!    the window as the stretch needs them, and fits the stretch's pieces to the committed
//!    motion (a stretch starts and ends on the motion's exact state, so stretches join
//!    without a seam).
//! 3. When the stretch needs the window's last zone while a move is still pending (the
//!    producer has fallen behind), the pending move is finished with an exact stop at its
//!    end: the motion comes to rest there within the limits, and the next move starts from
//!    rest. [`Stream::finish`] does the same at the end of a program.
//!
//! A curve move of several pieces ([`Move::curve`]) is not held back whole: a blend takes at
//! most half of its first or its last piece, so the rest is appended while it is pending, a
//! segment from the middle of one piece to the middle of the next (so that every join of
//! pieces lies inside a segment, where the speed limits cap it), as the window makes room
//! (`advance`). A curve of any number of pieces streams through a window of a few.

use core::cell::Cell;

use heapless::spsc::Producer;
use heapless::{Deque, Vec};
use strak_curves::ParamCurve;

use super::blend::{Blend, Junction, chain, has_span, junction};
use super::committed::{Committed, PHASES, TickCache};
use super::moves::{Move, MoveCurve, NoCurve, Shape, StreamCurve};
use super::segment::Segment;
use crate::compile::TickMotion;
use crate::compile::{Progress, StreamedPlan, StretchFit};
use crate::error::Error;
use crate::num::Number;
use crate::path::{AxisState, MIN_ALPHA, Piece, RampBasis, feed_ramp_f64};
use crate::plan::{
    Limits, LookAhead, MotionLimits, PHASES_PER_ZONE, Phase, PlanOptions, SegmentZones, reach,
    slowing_loss, zones_into,
};

/// The segments of a pending curve move `Stream::advance` appends per call at most: a
/// bound on the work of a push or a poll.
const ADVANCE_SEGMENTS: usize = 4;

/// The speed-limit samples of a segment whose loads vary (a blend, a Bézier move), per piece
/// of a curve move it crosses.
const LOAD_SAMPLES: usize = 32;

/// The least turn of the tangent (radians) at a corner that may come to an exact stop in
/// place of its blend: joins with a continuous tangent (a line meeting an arc tangentially)
/// and slight turns are always blended, as a machine is expected to pass them moving.
const STOP_TURN: f64 = 5.0 * core::f64::consts::PI / 180.0;

/// The most zones of one segment.
const SEGMENT_ZONES: usize = 24;

/// The share of the promised acceleration and jerk the window plans with: the pieces fitted
/// to the planned motion carry rounding noise in their jerk (about `ε·|x|/(j·T³)` relative,
/// `1e-10` at 10 units from the origin), which stays below the margin's `1e-6`.
const FIT_MARGIN: f64 = 1.0 - 1e-6;

/// The share of the velocity limits the window plans with: where the motion cruises at a
/// velocity limit along a curve, the pieces fitted to it deviate from its speed by parts in
/// 10⁷ at the fit tolerance (more than tightening the fit removes), which stays below the
/// margin's `1e-5`.
const VELOCITY_FIT_MARGIN: f64 = 1.0 - 1e-5;

/// How many halvings of a stretch ahead [`Stream::poll`] keeps the progress of its write
/// for (a stretch of up to 64 ticks halved down to 2; the tries of a longer one shorter
/// than that fit from its first tick again).
const HALVINGS: usize = 5;

/// The most pieces one [`Stream::poll`] writes (a stretch that needs more is halved): it
/// compiles only into a queue with more room than this.
///
/// ```
/// assert_eq!(strak_trajectory::STRETCH_PIECES, 24);
/// ```
pub const STRETCH_PIECES: usize = 24;

/// Where a stream's pieces go: a queue the sampler plays from.
///
/// ```
/// use heapless::Deque;
/// use strak_trajectory::{Piece, PieceQueue};
/// let queue = Deque::<Piece<f32, 2>, 8>::new();
/// assert_eq!(queue.room(), 8);
/// ```
pub trait PieceQueue<N, const A: usize> {
    /// How many more pieces it takes.
    fn room(&self) -> usize;
    /// Appends `piece` (the stream calls it only when there is room).
    fn push_piece(&mut self, piece: Piece<N, A>);
}

/// The producer half of the queue a [`StreamSampler`](crate::StreamSampler) plays from.
impl<N, const A: usize> PieceQueue<N, A> for Producer<'_, Piece<N, A>> {
    fn room(&self) -> usize {
        self.capacity() - self.len()
    }
    fn push_piece(&mut self, piece: Piece<N, A>) {
        let _ = self.enqueue(piece);
    }
}

impl<N, const A: usize, const P: usize> PieceQueue<N, A> for Deque<Piece<N, A>, P> {
    fn room(&self) -> usize {
        P - self.len()
    }
    fn push_piece(&mut self, piece: Piece<N, A>) {
        let _ = self.push_back(piece);
    }
}

/// How a stream blends, plans and compiles.
///
/// ```
/// use strak_trajectory::{PlanOptions, StreamOptions};
/// let o = StreamOptions::new(1_000.0).with_tolerance(0.02);
/// assert_eq!((o.tolerance(), o.plan().rate()), (0.02, 1_000.0));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StreamOptions {
    tolerance: f64,
    arc_tolerance: f64,
    fit_tolerance: f64,
    max_piece_ticks: u32,
    stretch_ticks: u32,
    faster_stops: bool,
    plan: PlanOptions,
}

impl StreamOptions {
    /// Exact stops at every corner, arcs' ends within `1e-6` units of their circles, the
    /// compiled pieces within `1e-5` units of the motion, pieces of at most 256 ticks,
    /// stretches of 64 ticks, exact stops where they are estimated faster than a blend, and
    /// the default [`PlanOptions`] at the control rate `rate_hz`.
    pub const fn new(rate_hz: f64) -> Self {
        StreamOptions {
            tolerance: 0.0,
            arc_tolerance: 1e-6,
            fit_tolerance: 1e-5,
            max_piece_ticks: 256,
            stretch_ticks: 64,
            faster_stops: true,
            plan: PlanOptions::new().with_rate(rate_hz),
        }
    }

    /// The corner blend tolerance `ε` in units (G64 P); 0 for exact stops (G61).
    ///
    /// ```
    /// # use strak_trajectory::StreamOptions;
    /// assert_eq!(StreamOptions::new(1_000.0).with_tolerance(0.05).tolerance(), 0.05);
    /// ```
    pub const fn with_tolerance(mut self, units: f64) -> Self {
        self.tolerance = units;
        self
    }

    /// How far an arc's end may lie off the circle through its start (units).
    ///
    /// ```
    /// # use strak_trajectory::{Limits, Stream, StreamOptions};
    /// let o = StreamOptions::new(1_000.0).with_arc_tolerance(f64::NAN);
    /// assert!(Stream::<2, 8, 32>::new([0.0; 2], Limits::new(1.0, 1.0, 1.0)?, o).is_err());
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub const fn with_arc_tolerance(mut self, units: f64) -> Self {
        self.arc_tolerance = units;
        self
    }

    /// How far the compiled pieces may lie from the planned motion at any tick (units).
    ///
    /// ```
    /// # use strak_trajectory::{Limits, Stream, StreamOptions};
    /// let o = StreamOptions::new(1_000.0).with_fit_tolerance(0.0);
    /// assert!(Stream::<2, 8, 32>::new([0.0; 2], Limits::new(1.0, 1.0, 1.0)?, o).is_err());
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub const fn with_fit_tolerance(mut self, units: f64) -> Self {
        self.fit_tolerance = units;
        self
    }

    /// The planner's options (control rate, centripetal and feed shares, zone tolerance).
    ///
    /// ```
    /// # use strak_trajectory::{PlanOptions, StreamOptions};
    /// let o = StreamOptions::new(1_000.0).with_plan(PlanOptions::new().with_rate(2_000.0));
    /// assert_eq!(o.plan().rate(), 2_000.0);
    /// ```
    pub const fn with_plan(mut self, plan: PlanOptions) -> Self {
        self.plan = plan;
        self
    }

    /// The ticks [`Stream::poll`] compiles at most per call.
    ///
    /// ```
    /// # use strak_trajectory::{Limits, Stream, StreamOptions};
    /// let o = StreamOptions::new(1_000.0).with_stretch_ticks(0);
    /// assert!(Stream::<2, 8, 32>::new([0.0; 2], Limits::new(1.0, 1.0, 1.0)?, o).is_err());
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub const fn with_stretch_ticks(mut self, ticks: u32) -> Self {
        self.stretch_ticks = ticks;
        self
    }

    /// Whether a corner that could be blended comes to an exact stop where the stop is
    /// estimated to take less time than the blend (`true`, the default: at a sharp corner
    /// under a jerk limit the blend's speed limit can cost more than a stop); `false` blends
    /// every corner it can.
    ///
    /// ```
    /// # use strak_trajectory::StreamOptions;
    /// let blends = StreamOptions::new(1_000.0).with_tolerance(0.02).with_faster_stops(false);
    /// assert!(!blends.faster_stops() && StreamOptions::new(1_000.0).faster_stops());
    /// ```
    pub const fn with_faster_stops(mut self, on: bool) -> Self {
        self.faster_stops = on;
        self
    }

    /// Whether corners stop where that is estimated faster than their blends.
    ///
    /// ```
    /// # use strak_trajectory::StreamOptions;
    /// assert!(StreamOptions::new(1_000.0).faster_stops());
    /// ```
    pub const fn faster_stops(&self) -> bool {
        self.faster_stops
    }

    /// The corner blend tolerance.
    ///
    /// ```
    /// # use strak_trajectory::StreamOptions;
    /// assert_eq!(StreamOptions::new(1_000.0).tolerance(), 0.0); // exact stops
    /// ```
    pub const fn tolerance(&self) -> f64 {
        self.tolerance
    }

    /// The planner's options.
    ///
    /// ```
    /// # use strak_trajectory::StreamOptions;
    /// assert_eq!(StreamOptions::new(500.0).plan().rate(), 500.0);
    /// ```
    pub const fn plan(&self) -> &PlanOptions {
        &self.plan
    }
}

/// What a stream has done so far.
///
/// ```
/// use strak_trajectory::StreamStats;
/// assert_eq!(StreamStats::default().moves, 0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StreamStats {
    /// Moves pushed.
    pub moves: usize,
    /// Corners blended.
    pub blends: usize,
    /// Exact stops at corners (a zero tolerance, a near-reversal, a stop estimated faster
    /// than the blend).
    pub stops: usize,
    /// Rests at the end of a move because the next one had not arrived.
    pub starved: usize,
    /// The largest deviation bound of a blend from its corner.
    pub max_deviation: f64,
}

/// The newest move, whose end junction is not yet known: its curve, the parameter where its
/// part after the blend before it starts, its feed, and the blend before it with that
/// blend's feed (held back until the next junction is known: where the two blends take all
/// of the move between them, they are joined as a [`chain`]).
#[derive(Clone, Copy, Debug)]
struct Pending<const D: usize, C, const R: usize> {
    curve: MoveCurve<D, C>,
    /// Where each axis riding along starts and ends the move.
    ride: [(f64, f64); R],
    /// Whether it is a move of the riding axes alone (`curve` traces them; the other axes
    /// stand still).
    alone: bool,
    from: f64,
    feed: f64,
    before: Option<(Blend<D>, f64)>,
    /// The move's arc length up to `from`, for a curve move (its segments' own offsets).
    offset: f64,
}

impl<const D: usize, C: StreamCurve<D>, const R: usize> Pending<D, C, R> {
    /// The value and rate `de/ds` of each axis riding along at the move's parameter `u`: in
    /// proportion to the move's arc length from its start value to its end value (each end
    /// exactly).
    ///
    /// # Errors
    /// [`Error::Curve`] when the move's arc length does not converge.
    fn riding_at(&self, u: f64) -> Result<[(f64, f64); R], Error> {
        let length = self.curve.length();
        let share = if R == 0 || u <= 0.0 || u >= 1.0 {
            0.0
        } else {
            self.curve.length_to(u)? / length
        };
        Ok(self.ride.map(|(e0, e1)| {
            let e = match u {
                u if u >= 1.0 => e1,
                u if u <= 0.0 => e0,
                _ => e0 + (e1 - e0) * share,
            };
            (e, (e1 - e0) / length)
        }))
    }
}

/// A stream of moves in `D` axes: at most `Q` segments (each move's part between its blends,
/// and each blend) and `Z` zones in the look-ahead window; `C` is the type of its curve
/// moves ([`Move::curve`]).
///
/// # Axes that ride along
/// The last `R` axes (0 by default) do not shape the path: an extruder E after X, Y, Z
/// (`Stream<4, Q, Z, NoCurve<4>, 1>`), a rotary axis. The path is that of the first `D − R`
/// axes: its arc length, its curvature, the corner tolerance, and the path limits of
/// [`Limits`] (velocity, acceleration, jerk, and each move's feed) are taken over them alone.
/// Along a move each riding axis goes from its start to its end in proportion to the
/// move's arc length; through a corner blend it goes from the value and rate it leaves one
/// move with to those it enters the next with, on a quintic in the blend's parameter, so
/// that its velocity and acceleration are continuous. Its limits enter the plan as the
/// per-axis limits of [`Limits`] ([`with_axis_velocity`](Limits::with_axis_velocity),
/// [`with_axis_acceleration`](Limits::with_axis_acceleration)): with `e' = de/ds` and
/// `e'' = d²e/ds²` along the path, its velocity `e'·v` and acceleration `e'·a + e''·v²` are
/// kept within them, so a move whose riding axis travels far for its path length (a long
/// extrusion on a short line) moves the path slower. A line that leaves the path where it
/// is and moves riding axes (a retraction, a prime) moves them alone, along a straight line
/// in them, from rest to rest: its feed is their speed, and the path's acceleration and
/// jerk limits and their own per-axis limits hold. A curve move, which shapes all of its
/// axes, is refused while axes ride along ([`Error::AxisMismatch`]).
///
/// ```
/// use heapless::Deque;
/// use strak_trajectory::{Limits, Move, NoCurve, Piece, Stream, StreamOptions};
/// let limits = Limits::new(100.0, 2_000.0, 50_000.0)?
///     .with_axis_velocity([f64::INFINITY, f64::INFINITY, 5.0])?; // E at most 5 mm/s
/// let mut stream = Stream::<3, 8, 64, NoCurve<3>, 1>::new([0.0; 3], limits, StreamOptions::new(1_000.0))?;
/// stream.push(&Move::line([10.0, 0.0, 1.0]))?; // X, Y and E: 10 mm of path, 1 mm of E
/// stream.push(&Move::line([10.0, 2.0, 3.0]))?; // 2 mm of path, 2 mm of E: E binds
/// stream.finish()?;
/// let mut pieces = Deque::<Piece<f64, 3>, 64>::new();
/// while !stream.is_idle() {
///     stream.poll(&mut pieces)?;
///     pieces.clear();
/// }
/// assert_eq!(stream.position()?, [10.0, 2.0, 3.0]);
/// # Ok::<(), strak_trajectory::Error>(())
/// ```
///
/// ```
/// use heapless::Deque;
/// use strak_trajectory::{Limits, Move, Piece, Stream, StreamOptions};
/// let limits = Limits::new(100.0, 2_000.0, 50_000.0)?;
/// let options = StreamOptions::new(1_000.0).with_tolerance(0.05);
/// let mut stream = Stream::<2, 16, 64>::new([0.0, 0.0], limits, options)?;
/// stream.push(&Move::line([10.0, 0.0]))?;
/// stream.push(&Move::line([20.0, 2.0]))?; // a turn of 11°
/// stream.finish()?;
/// let mut pieces = Deque::<Piece<f32, 2>, 64>::new();
/// let mut ticks = 0;
/// loop {
///     let n = stream.poll(&mut pieces)?;
///     ticks += n;
///     pieces.clear(); // a sampler plays them
///     if n == 0 { break; }
/// }
/// assert!(ticks > 200 && stream.stats().blends == 1);
/// # Ok::<(), strak_trajectory::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Stream<
    const D: usize,
    const Q: usize,
    const Z: usize,
    C = NoCurve<D>,
    const R: usize = 0,
> {
    /// Whether limits and options are set ([`Stream::reset`]).
    ready: bool,
    /// The limits the window plans with (the feed reserve taken off).
    planned: Limits<D>,
    /// What the compiled motion keeps to.
    promised: MotionLimits,
    options: StreamOptions,
    fit: StretchFit,
    segments: Deque<Segment<D, C, R>, Q>,
    pending: Option<Pending<D, C, R>>,
    /// Where the next move starts (the axes riding along at 0: see `ride_end`).
    end: [f64; D],
    /// Where the axes riding along are at the end of the last move pushed.
    ride_end: [f64; R],
    /// The value and rate `de/ds` of each axis riding along where the appended path ends.
    ride_tail: [(f64, f64); R],
    /// The arc length of the path up to the pending move's part.
    length: f64,
    window: LookAhead<Z>,
    committed: Deque<Phase, PHASES>,
    /// The first tick not yet compiled.
    next_tick: u32,
    stats: StreamStats,
    /// The feed ramp's largest rate and change per tick of the feed factor (the sampler's).
    ramp: (f64, f64),
    /// The feed override (0 to 2): the feeds are planned with its part above 1.
    feed_override: f64,
    /// Seconds the motion rests before the next move ([`Stream::dwell`]).
    dwell: f32,
    /// What the committed motion keeps of the ticks it evaluated while a stretch is
    /// compiled.
    ticks: TickCache<D>,
}

impl<const D: usize, const Q: usize, const Z: usize, C: StreamCurve<D>, const R: usize>
    Stream<D, Q, Z, C, R>
{
    /// A stream at rest at `start`, under the machine's `limits`.
    ///
    /// ```
    /// use strak_trajectory::{Limits, Stream, StreamOptions};
    /// let limits = Limits::new(100.0, 1_000.0, 10_000.0)?;
    /// let stream = Stream::<2, 8, 32>::new([1.0, 2.0], limits, StreamOptions::new(1_000.0))?;
    /// assert!(stream.is_idle());
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`reset`](Self::reset).
    pub fn new(start: [f64; D], limits: Limits<D>, options: StreamOptions) -> Result<Self, Error> {
        let mut stream = Self::unset();
        stream.reset(start, limits, options)?;
        Ok(stream)
    }

    /// A stream without limits that refuses every move ([`Error::InvalidLimit`]) until
    /// [`reset`](Self::reset) gives it its start, limits and options: firmware builds a large
    /// stream in place with it (`let mut stream = Stream::unset();` in the frame that runs
    /// it, or a `static`), where [`new`](Self::new) would return it by value. Only the small
    /// fields are written; the queues' storage is left uninitialized.
    ///
    /// ```
    /// use strak_trajectory::{Error, Limits, Move, Stream, StreamOptions};
    /// let mut stream = Stream::<2, 8, 32>::unset();
    /// assert_eq!(stream.push(&Move::line([1.0, 0.0])), Err(Error::InvalidLimit));
    /// let limits = Limits::new(100.0, 1_000.0, 10_000.0)?;
    /// stream.reset([0.0; 2], limits, StreamOptions::new(1_000.0))?;
    /// stream.push(&Move::line([1.0, 0.0]))?;
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    #[inline(never)] // the caller's slot is written in place (the value is returned through it)
    pub const fn unset() -> Self {
        Stream {
            ready: false,
            ramp: (0.0, 0.0),
            feed_override: 1.0,
            dwell: 0.0,
            ticks: TickCache::new(),
            planned: Limits::NONE,
            promised: MotionLimits::new(0.0, 0.0, 0.0),
            options: StreamOptions::new(PlanOptions::DEFAULT_RATE),
            fit: StretchFit {
                tolerance: 0.0,
                max_piece_ticks: 0,
                path_axes: D,
            },
            segments: Deque::new(),
            pending: None,
            end: [0.0; D],
            ride_end: [0.0; R],
            ride_tail: [(0.0, 0.0); R],
            length: 0.0,
            window: LookAhead::new(),
            committed: Deque::new(),
            next_tick: 0,
            stats: StreamStats {
                moves: 0,
                blends: 0,
                stops: 0,
                starved: 0,
                max_deviation: 0.0,
            },
        }
    }

    /// Starts the stream afresh, in place: at rest at `start`, under the machine's `limits`,
    /// with `options`; what it held is dropped, its statistics and ticks start from 0.
    ///
    /// # Errors
    /// [`Error::InvalidLimit`] for invalid options (a negative or non-finite tolerance,
    /// stretches of no tick, invalid [`PlanOptions`]); [`Error::Curve`] for a non-finite
    /// start; [`Error::AxisMismatch`] when every axis rides along (`R ≥ D`: no path).
    /// Nothing changes on an error.
    ///
    /// ```
    /// # use strak_trajectory::{Error, Limits, Stream, StreamOptions};
    /// # let limits = Limits::new(100.0, 1_000.0, 10_000.0)?;
    /// let mut stream = Stream::<2, 8, 32>::new([0.0; 2], limits, StreamOptions::new(1_000.0))?;
    /// let bad = StreamOptions::new(1_000.0).with_tolerance(-1.0);
    /// assert_eq!(stream.reset([0.0; 2], limits, bad), Err(Error::InvalidLimit));
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn reset(
        &mut self,
        start: [f64; D],
        limits: Limits<D>,
        options: StreamOptions,
    ) -> Result<(), Error> {
        options.plan.validate()?;
        let finite = |x: f64| x.is_finite() && x >= 0.0;
        if !(finite(options.tolerance)
            && finite(options.arc_tolerance)
            && options.fit_tolerance > 0.0
            && finite(options.fit_tolerance)
            && options.stretch_ticks > 0
            && options.max_piece_ticks > 0)
        {
            return Err(Error::InvalidLimit);
        }
        if !start.iter().all(|x| x.is_finite()) {
            return Err(Error::Curve(strak_curves::Error::NonFinite));
        }
        if R >= D {
            return Err(Error::AxisMismatch { curve: D, path: 0 });
        }
        let options = options.with_plan(options.plan.with_path_axes(D - R));
        self.ramp = feed_ramp(&limits, &options);
        self.feed_override = 1.0;
        let keep = (1.0 - options.plan.feed_share()) * FIT_MARGIN;
        self.planned = limits
            .without_reserve(1.0 - keep)
            .with_velocities_times(VELOCITY_FIT_MARGIN);
        self.promised = options.plan.promised(&limits);
        self.options = options;
        self.fit = StretchFit {
            tolerance: options.fit_tolerance,
            max_piece_ticks: options.max_piece_ticks,
            path_axes: D - R,
        };
        self.next_tick = 0;
        self.stats = StreamStats::default();
        self.ready = true;
        self.restart_at(start);
        Ok(())
    }

    /// Drops the segments, the pending move, a dwell not yet begun, the window and the
    /// committed motion, in place: at rest at `at`, from the first tick not yet compiled on.
    fn restart_at(&mut self, at: [f64; D]) {
        self.segments.clear();
        self.committed.clear();
        self.pending = None;
        self.dwell = 0.0;
        (self.end, self.length) = (Self::shaping(at), 0.0);
        self.ride_end = core::array::from_fn(|i| at[D - R + i]);
        self.ride_tail = self.ride_end.map(|e| (e, 0.0));
        self.window.clear();
        self.window
            .hold_until(f64::from(self.next_tick) * self.period());
    }

    /// `x` with its axes riding along at 0: the point of the path its other axes shape.
    fn shaping(mut x: [f64; D]) -> [f64; D] {
        for c in x.iter_mut().skip(D - R) {
            *c = 0.0;
        }
        x
    }

    /// `geometric` (a point of the path) with the axes riding along at `ride`.
    fn riding(mut geometric: [f64; D], ride: [f64; R]) -> [f64; D] {
        for (c, e) in geometric.iter_mut().skip(D - R).zip(ride) {
            *c = e;
        }
        geometric
    }

    /// What the stream has done so far.
    ///
    /// ```
    /// # use strak_trajectory::{Limits, Move, Stream, StreamOptions};
    /// # let limits = Limits::new(100.0, 1_000.0, 10_000.0)?;
    /// let mut stream = Stream::<2, 8, 32>::new([0.0; 2], limits, StreamOptions::new(1_000.0))?;
    /// stream.push(&Move::line([1.0, 0.0]))?;
    /// stream.push(&Move::line([1.0, 1.0]))?; // a corner: an exact stop at tolerance 0
    /// assert_eq!((stream.stats().moves, stream.stats().stops), (2, 1));
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn stats(&self) -> StreamStats {
        self.stats
    }

    /// The first tick not yet compiled: the ticks compiled so far.
    ///
    /// ```
    /// # use strak_trajectory::{Limits, Stream, StreamOptions};
    /// # let limits = Limits::new(100.0, 1_000.0, 10_000.0)?;
    /// let stream = Stream::<2, 8, 32>::new([0.0; 2], limits, StreamOptions::new(1_000.0))?;
    /// assert_eq!(stream.ticks(), 0);
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn ticks(&self) -> u32 {
        self.next_tick
    }

    /// Whether everything pushed is compiled and the motion has come to rest.
    ///
    /// ```
    /// # use strak_trajectory::{Limits, Move, Stream, StreamOptions};
    /// # let limits = Limits::new(100.0, 1_000.0, 10_000.0)?;
    /// let mut stream = Stream::<2, 8, 32>::new([0.0; 2], limits, StreamOptions::new(1_000.0))?;
    /// stream.push(&Move::line([1.0, 0.0]))?;
    /// assert!(!stream.is_idle());
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn is_idle(&self) -> bool {
        self.pending.is_none() && self.window.is_empty() && {
            let (t, _, _) = self.window.entry();
            f64::from(self.next_tick) * self.period() >= t
        }
    }

    fn period(&self) -> f64 {
        1.0 / self.options.plan.rate()
    }

    /// What the stream plans and compiles under, with the machine's `limits` it was reset
    /// with: the header of a path of its pieces is derived from it.
    pub(super) fn plan_of<'a>(&'a self, limits: &'a Limits<D>) -> StreamedPlan<'a, D> {
        StreamedPlan {
            rate: self.options.plan.rate(),
            tolerance: self.fit.tolerance,
            promised: &self.promised,
            limits,
            feed_share: self.options.plan.feed_share(),
        }
    }

    /// The feed ramp's largest rate and change per tick of the feed factor, and the rate in
    /// ticks per second, for [`StreamSampler`](crate::StreamSampler).
    pub(crate) fn feed_ramp(&self) -> (f64, f64, f64) {
        (self.ramp.0, self.ramp.1, self.options.plan.rate())
    }

    /// Where the motion is at the first tick not yet compiled: the start of what was pushed
    /// while nothing is compiled, the end of the motion after it.
    ///
    /// ```
    /// # use strak_trajectory::{Limits, Move, Stream, StreamOptions};
    /// # let limits = Limits::new(100.0, 1_000.0, 10_000.0)?;
    /// let mut stream = Stream::<2, 8, 32>::new([1.0, 2.0], limits, StreamOptions::new(1_000.0))?;
    /// stream.push(&Move::line([5.0, 2.0]))?;
    /// assert_eq!(stream.position()?, [1.0, 2.0]);
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Curve`] for a segment whose arc length does not converge.
    pub fn position(&self) -> Result<[f64; D], Error> {
        if self.segments.is_empty() {
            return Ok(match &self.pending {
                Some(p) if p.from == 0.0 => Self::riding(p.curve.eval(0.0), p.ride.map(|r| r.0)),
                _ => Self::riding(self.end, self.ride_end),
            });
        }
        if self.is_idle() {
            return self.rest_point();
        }
        self.motion().position(self.next_tick)
    }

    /// Sets the feed override `f` (clamped to `[0, 2]`; NaN is ignored) and returns the
    /// part of it for the sampler, [`StreamSampler::set_feed`](crate::StreamSampler::set_feed)'s
    /// `min(f, 1)`. Above 1 the stream plans the feeds of the moves not yet compiled
    /// (those in the look-ahead window and those pushed later) `f` times faster, never above
    /// the machine's limits; rapid moves run at the machine's limits anyway. It takes
    /// effect after the pieces already compiled (the queue's lead); where a lower override
    /// would leave the motion no room to slow down, the zones at the window's front keep
    /// the override they had. Below 1 the sampler's feed ramp slows the motion at once.
    ///
    /// ```
    /// # use strak_trajectory::{Limits, Stream, StreamOptions};
    /// # let limits = Limits::new(100.0, 1_000.0, 10_000.0)?;
    /// let mut stream = Stream::<2, 8, 32>::new([0.0; 2], limits, StreamOptions::new(1_000.0))?;
    /// assert_eq!(stream.set_feed_override(1.5), 1.0); // the stream plans 150 % of the feeds
    /// assert_eq!(stream.set_feed_override(0.6), 0.6); // the sampler ramps to 60 %
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn set_feed_override(&mut self, f: f64) -> f32 {
        if !f.is_nan() {
            let before = self.feed_scale();
            self.feed_override = f.clamp(0.0, 2.0);
            if self.feed_scale() != before {
                self.window.scale_feeds(self.feed_scale());
            }
        }
        #[allow(clippy::cast_possible_truncation)]
        let sampler = self.feed_override.min(1.0) as f32;
        sampler
    }

    /// The feed override's part above 1, the factor the feeds are planned with.
    fn feed_scale(&self) -> f32 {
        #[allow(clippy::cast_possible_truncation)]
        let scale = self.feed_override.max(1.0) as f32;
        scale
    }

    /// Drops everything not yet compiled and rests at `at`, where an aborted
    /// [`StreamSampler`](crate::StreamSampler) stopped ([`position`](crate::StreamSampler::position)):
    /// the next move starts there, from rest. The statistics and the tick count go on.
    ///
    /// ```
    /// # use strak_trajectory::{Limits, Move, Stream, StreamOptions};
    /// # let limits = Limits::new(100.0, 1_000.0, 10_000.0)?;
    /// let mut stream = Stream::<2, 8, 32>::new([0.0; 2], limits, StreamOptions::new(1_000.0))?;
    /// stream.push(&Move::line([5.0, 0.0]))?;
    /// stream.abort([2.5, 0.0])?;
    /// assert!(stream.is_idle());
    /// assert_eq!(stream.position()?, [2.5, 0.0]);
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Curve`] with a non-finite coordinate (nothing changed).
    pub fn abort(&mut self, at: [f64; D]) -> Result<(), Error> {
        if !at.iter().all(|x| x.is_finite()) {
            return Err(Error::Curve(strak_curves::Error::NonFinite));
        }
        self.restart_at(at);
        Ok(())
    }

    /// Appends the move `mv`, from the end of the move before (or the start).
    ///
    /// # Errors
    /// [`Error::CapacityExceeded`] when fewer than two segments are free (checked first, at
    /// no cost), the window is full, or the pending curve move is not yet appended up to
    /// the middle of its last piece (poll, then push again; the move was not taken); the
    /// errors of [`MoveCurve::new`] and [`junction`] for a bad move (nothing changed).
    ///
    /// ```
    /// # use strak_trajectory::{Error, Limits, Move, Stream, StreamOptions};
    /// # let limits = Limits::new(100.0, 1_000.0, 10_000.0)?;
    /// let mut stream = Stream::<2, 8, 32>::new([0.0; 2], limits, StreamOptions::new(1_000.0))?;
    /// assert_eq!(stream.push(&Move::line([0.0, 0.0])), Err(Error::DegenerateMove));
    /// assert_eq!(stream.stats().moves, 0);
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn push(&mut self, mv: &Move<D, C>) -> Result<(), Error> {
        if !self.ready {
            return Err(Error::InvalidLimit);
        }
        if self.segments.len() + 2 > Q {
            // A move adds at most two segments: refused before any work.
            return Err(Error::CapacityExceeded {
                capacity: Q,
                required: self.segments.len() + 2,
            });
        }
        let (curve, alone) = self.move_curve(mv)?;
        let feed = mv.feed.unwrap_or(f64::INFINITY);
        let ride: [(f64, f64); R] = core::array::from_fn(|i| (self.ride_end[i], mv.to[D - R + i]));
        if !self.advance()? {
            return Err(self.behind());
        }
        let Some(prev) = self.pending else {
            self.pending = Some(Pending {
                curve,
                ride,
                alone,
                from: 0.0,
                feed,
                before: None,
                offset: 0.0,
            });
            self.end_move(&curve, alone, ride);
            self.stats.moves += 1;
            return Ok(());
        };
        let corner = if alone || prev.alone {
            Junction::Stop // a move of the riding axes alone starts and ends at rest
        } else {
            let corner = junction(&prev.curve, &curve, self.options.tolerance)?;
            self.blend_or_stop(corner, &prev, &curve, feed)?
        };
        let (leave, from, mut after) = match corner {
            Junction::Blend(b) => (b.leave(), b.join(), Some(b)),
            _ => (1.0, 0.0, None),
        };
        let through = has_span((prev.from, leave));
        let mut before = prev.before;
        if let (Some((b, _)), Some(a), false) = (before.as_mut(), after.as_mut(), through) {
            chain(b, a, &prev.curve, self.options.tolerance);
        }
        let stop = matches!(corner, Junction::Stop);
        self.emit(&prev, before, through.then_some((leave, stop)))?;
        let before = after.map(|b| (b, prev.feed.min(feed)));
        let offset = if curve.is_curve() {
            curve.length_to(from)?
        } else {
            0.0
        };
        self.pending = Some(Pending {
            curve,
            ride,
            alone,
            from,
            feed,
            before,
            offset,
        });
        self.end_move(&curve, alone, ride);
        self.stats.moves += 1;
        match corner {
            Junction::Blend(_) => self.stats.blends += 1,
            Junction::Stop => self.stats.stops += 1,
            Junction::Straight => {}
        }
        Ok(())
    }

    /// The curve of `mv` from where the stream is, and whether it moves the riding axes
    /// alone: a line whose end leaves the path where it is and changes a riding axis is
    /// traced in the riding axes (the other axes stand still); any other move is traced as
    /// the path's axes shape it ([`Self::shaped`]).
    ///
    /// # Errors
    /// The errors of [`Self::shaped`] and [`MoveCurve::new`].
    fn move_curve(&self, mv: &Move<D, C>) -> Result<(MoveCurve<D, C>, bool), Error> {
        let shaped = self.shaped(mv)?;
        let riding: [f64; R] = core::array::from_fn(|i| mv.to[D - R + i]);
        let tolerance = self.options.arc_tolerance;
        if R > 0 && matches!(mv.shape, Shape::Line) && shaped.to == self.end {
            let from = Self::riding(self.end, self.ride_end);
            let line = Move {
                to: Self::riding(self.end, riding),
                shape: Shape::Line,
                feed: mv.feed,
            };
            return Ok((MoveCurve::new(from, &line, tolerance)?, true));
        }
        Ok((MoveCurve::new(self.end, &shaped, tolerance)?, false))
    }

    /// Takes the end of the move just pushed (its `curve`, whether it moves the riding axes
    /// `alone`, and where they start and end it) as where the next move starts.
    fn end_move(&mut self, curve: &MoveCurve<D, C>, alone: bool, ride: [(f64, f64); R]) {
        if !alone {
            self.end = curve.eval(1.0);
        }
        self.ride_end = ride.map(|r| r.1);
    }

    /// `mv` as the path's axes shape it: its points with the axes riding along at 0.
    ///
    /// # Errors
    /// [`Error::AxisMismatch`] for a curve move while axes ride along (a curve shapes all of
    /// its axes).
    fn shaped(&self, mv: &Move<D, C>) -> Result<Move<D, C>, Error> {
        if R == 0 {
            return Ok(*mv);
        }
        let shape = match mv.shape {
            Shape::Bezier { c1, c2 } => Shape::Bezier {
                c1: Self::shaping(c1),
                c2: Self::shaping(c2),
            },
            Shape::Curve(_) => {
                return Err(Error::AxisMismatch {
                    curve: D,
                    path: D - R,
                });
            }
            other => other,
        };
        Ok(Move {
            to: Self::shaping(mv.to),
            shape,
            feed: mv.feed,
        })
    }

    /// Finishes the pending move with a stop at its end: the motion comes to rest at the end
    /// of what was pushed (a later move starts from rest there).
    ///
    /// # Errors
    /// [`Error::CapacityExceeded`] when too few segments are free (checked first, at no
    /// cost) or the pending curve move is not yet appended up to the middle of its last
    /// piece, [`Error::ZoneCapacityExceeded`] when the window is full (poll, then finish
    /// again; the move is not finished).
    ///
    /// ```
    /// # use heapless::Deque;
    /// # use strak_trajectory::{Limits, Move, Piece, Stream, StreamOptions};
    /// # let limits = Limits::new(100.0, 1_000.0, 10_000.0)?;
    /// let mut stream = Stream::<2, 8, 32>::new([0.0; 2], limits, StreamOptions::new(1_000.0))?;
    /// stream.push(&Move::line([1.0, 0.0]))?;
    /// stream.finish()?;
    /// let mut pieces = Deque::<Piece<f64, 2>, 32>::new();
    /// while stream.poll(&mut pieces)? > 0 {}
    /// assert_eq!(stream.stats().starved, 0); // the end was known
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn finish(&mut self) -> Result<(), Error> {
        if !self.advance()? {
            return Err(self.behind());
        }
        let Some(prev) = self.pending else {
            return Ok(());
        };
        self.room_for(1 + usize::from(prev.before.is_some()), 0)?;
        self.emit(&prev, prev.before, Some((1.0, true)))?;
        self.pending = None;
        Ok(())
    }

    /// A dwell (G-code's `G4`): the pending move ends at rest ([`finish`](Self::finish)),
    /// and the motion rests there `seconds` before the next move pushed starts (a dwell
    /// with no move after it moves nothing). Dwells in a row add up.
    ///
    /// # Errors
    /// [`Error::InvalidLimit`] for a negative or non-finite duration; [`Error::TooLong`]
    /// for one of more ticks than a `u32` counts; the errors of [`finish`](Self::finish)
    /// (poll, then dwell again: nothing was added).
    ///
    /// ```
    /// # use heapless::Deque;
    /// # use strak_trajectory::{Limits, Move, Piece, Stream, StreamOptions};
    /// # let limits = Limits::new(100.0, 1_000.0, 10_000.0)?;
    /// let mut with = Stream::<2, 8, 32>::new([0.0; 2], limits, StreamOptions::new(1_000.0))?;
    /// let mut without = with.clone();
    /// for (stream, dwell) in [(&mut with, 0.25), (&mut without, 0.0)] {
    ///     stream.push(&Move::line([5.0, 0.0]))?;
    ///     stream.dwell(dwell)?;
    ///     stream.push(&Move::line([5.0, 5.0]))?;
    ///     stream.finish()?;
    ///     let mut pieces = Deque::<Piece<f64, 2>, 32>::new();
    ///     while !stream.is_idle() {
    ///         stream.poll(&mut pieces)?;
    ///         pieces.clear();
    ///     }
    /// }
    /// assert_eq!(with.ticks(), without.ticks() + 250);
    /// assert_eq!(with.dwell(f64::NAN), Err(strak_trajectory::Error::InvalidLimit));
    /// assert_eq!(with.dwell(1e300), Err(strak_trajectory::Error::TooLong));
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn dwell(&mut self, seconds: f64) -> Result<(), Error> {
        if !(seconds.is_finite() && seconds >= 0.0) {
            return Err(Error::InvalidLimit);
        }
        if seconds * self.options.plan.rate() > f64::from(u32::MAX) {
            return Err(Error::TooLong);
        }
        self.finish()?;
        #[allow(clippy::cast_possible_truncation)]
        let seconds = seconds as f32;
        self.dwell += seconds;
        Ok(())
    }

    /// The corner blend tolerance from the next corner on (G-code's `G64 P`; 0 for exact
    /// stops, `G61`): the corner between the pending move and the next one pushed is the
    /// first it applies to.
    ///
    /// # Errors
    /// [`Error::InvalidLimit`] for a negative or non-finite tolerance (nothing changes).
    ///
    /// ```
    /// # use strak_trajectory::{Limits, Move, Stream, StreamOptions};
    /// # let limits = Limits::new(100.0, 1_000.0, 10_000.0)?;
    /// let options = StreamOptions::new(1_000.0).with_faster_stops(false);
    /// let mut stream = Stream::<2, 8, 32>::new([0.0; 2], limits, options)?;
    /// stream.push(&Move::line([5.0, 0.0]))?;
    /// stream.push(&Move::line([10.0, 1.0]))?; // an exact stop: tolerance 0
    /// stream.set_tolerance(0.05)?;
    /// stream.push(&Move::line([15.0, 0.0]))?; // this corner is blended
    /// assert_eq!((stream.stats().stops, stream.stats().blends), (1, 1));
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn set_tolerance(&mut self, units: f64) -> Result<(), Error> {
        if !(units.is_finite() && units >= 0.0) {
            return Err(Error::InvalidLimit);
        }
        self.options = self.options.with_tolerance(units);
        Ok(())
    }

    /// The error of a push or a finish while the pending curve move is not caught up
    /// ([`Self::advance`]): the segments it would need with those held, about one per piece
    /// left.
    fn behind(&self) -> Error {
        let left = self.pending.map_or(0, |p| {
            p.curve.pieces_within((p.from, p.curve.streamed_until())).1
        });
        Error::CapacityExceeded {
            capacity: Q,
            required: self.segments.len() + left,
        }
    }

    /// Whether nothing of the pending move is left to append before its end junction is
    /// known (see [`Self::advance`]).
    fn caught_up(&self) -> bool {
        self.pending
            .is_none_or(|p| !p.curve.is_curve() || p.from >= p.curve.streamed_until())
    }

    /// Appends the part of the pending curve move that no blend with a next move can take
    /// (up to the middle of its last piece, [`MoveCurve`]), a segment from the middle of one
    /// piece to the middle of the next (with the blend before the move ahead of the first),
    /// while there is room, at most [`ADVANCE_SEGMENTS`] per call.
    /// Returns whether the pending move is caught up: nothing of it is left to append before
    /// its end junction is known.
    ///
    /// # Errors
    /// The errors of [`Self::emit`], but for a lack of room while segments are buffered
    /// ahead (they make room as they are played).
    fn advance(&mut self) -> Result<bool, Error> {
        for _ in 0..ADVANCE_SEGMENTS {
            let Some(prev) = self.pending.filter(|_| !self.caught_up()) else {
                return Ok(true);
            };
            let to = prev.curve.next_cut(prev.from);
            match self.emit(&prev, prev.before, Some((to, false))) {
                Ok(()) => {}
                Err(Error::CapacityExceeded { .. } | Error::ZoneCapacityExceeded { .. })
                    if !self.segments.is_empty() =>
                {
                    return Ok(false);
                }
                Err(e) => return Err(e),
            }
            let length = self.segments.back().map_or(0.0, |g| g.length);
            self.pending = Some(Pending {
                from: to,
                before: None,
                offset: prev.offset + length,
                ..prev
            });
        }
        Ok(self.caught_up())
    }

    /// Appends the path of the pending move `prev` that is now known: the blend `before` it
    /// (held back, with its feed) and, with `span = Some((to, stop))`, its part up to its
    /// parameter `to` (ending at rest for a `stop`), with their zones; counts the blend's
    /// deviation. Nothing changes on an error.
    // Inlined into `push`, `finish` and `advance`: as a call of its own its frame (the segments' zones)
    // stacks on that of `push` (measured on the Cortex-M4F; ICOUNT.md).
    #[inline(always)]
    fn emit(
        &mut self,
        prev: &Pending<D, C, R>,
        before: Option<(Blend<D>, f64)>,
        span: Option<(f64, bool)>,
    ) -> Result<(), Error> {
        let mut added = Vec::<Segment<D, C, R>, 2>::new();
        let mut zones = SegmentZones::<{ 2 * SEGMENT_ZONES }>::new();
        let (mut s, mut tail) = (self.length, self.ride_tail);
        if let Some(blend) = self.blend_of(before, prev, (s, tail), &mut zones)? {
            (s, tail) = (blend.end(), blend.ride_end());
            let _ = added.push(blend);
        }
        if let Some((to, stop)) = span {
            let part = self.span_of(prev, (to, stop), (s, tail), &mut zones)?;
            (s, tail) = (part.end(), part.ride_end());
            let _ = added.push(part);
        }
        self.room_for(added.len(), zones.zones().len())?;
        if self.dwell > 0.0 {
            zones.hold_first(self.dwell);
        }
        self.append(&added, &zones)?;
        (self.length, self.ride_tail) = (s, tail);
        self.dwell = 0.0;
        self.note_deviation(before);
        Ok(())
    }

    /// `corner`, or an exact stop where the motion is estimated to pass the corner sooner by
    /// stopping there than through its blend: at a sharp corner under a jerk limit the
    /// blend's curvature changes so fast along it that its speed limit costs more than a
    /// stop. The estimate ([`slowing_loss`]) slows to the blend's lowest speed limit and
    /// crosses its zones at their limits, against a stop, both from the speed reached from
    /// rest in half the shorter of the two moves' parts beside the blend (at most the feeds
    /// and the velocity limit), under the path's acceleration and jerk limits. Blends of
    /// turns up to [`STOP_TURN`] and blends that take all of a move (a chain of short moves)
    /// are kept, and so is every blend without [`StreamOptions::with_faster_stops`].
    ///
    /// # Errors
    /// [`Error::Curve`] for a blend whose arc length does not converge.
    fn blend_or_stop(
        &self,
        corner: Junction<D>,
        prev: &Pending<D, C, R>,
        next: &MoveCurve<D, C>,
        feed: f64,
    ) -> Result<Junction<D>, Error> {
        let Junction::Blend(blend) = corner else {
            return Ok(corner);
        };
        if !self.options.faster_stops {
            return Ok(corner);
        }
        let (leave, join) = (blend.leave(), blend.join());
        let sharp = blend.cos_turn() < libm::cos(STOP_TURN);
        if !(sharp && has_span((prev.from, leave)) && has_span((join, 1.0))) {
            return Ok(corner);
        }
        let beside = (prev.curve.length() * (leave - prev.from)).min(next.length() * (1.0 - join));
        let feed = prev.feed.min(feed);
        let segment = Segment::blend(&blend, 0.0, feed)?;
        let mut zones = SegmentZones::<SEGMENT_ZONES>::new();
        self.zones_of(&segment, &mut zones)?;
        let (a, j) = (self.planned.acceleration(), self.planned.jerk());
        let cap = feed.min(self.planned.velocity());
        let v_cruise = reach(0.0, 0.5 * beside, cap, a, j);
        let crossing = zones.crossing_time() - segment.length / v_cruise;
        let pass = slowing_loss(zones.slowest(), v_cruise, a, j) + crossing.max(0.0);
        let stop = slowing_loss(0.0, v_cruise, a, j);
        Ok(if stop < pass { Junction::Stop } else { corner })
    }

    /// The segment of the blend `before` (with its feed) at the path's arc length `start`,
    /// with its zones appended to `zones`; `None` without a blend.
    fn blend_of<const K: usize>(
        &self,
        before: Option<(Blend<D>, f64)>,
        next: &Pending<D, C, R>,
        (start, tail): (f64, [(f64, f64); R]),
        zones: &mut SegmentZones<K>,
    ) -> Result<Option<Segment<D, C, R>>, Error> {
        let Some((blend, feed)) = before else {
            return Ok(None);
        };
        let ends = next.riding_at(next.from)?;
        let ride = core::array::from_fn(|i| (tail[i], ends[i]));
        let segment = Segment::blend(&blend, start, feed)?.with_ride(ride);
        self.zones_of(&segment, zones)?;
        Ok(Some(segment))
    }

    /// Counts the deviation of the blend `before`, now a segment of the path.
    fn note_deviation(&mut self, before: Option<(Blend<D>, f64)>) {
        if let Some((b, _)) = before {
            self.stats.max_deviation = self.stats.max_deviation.max(b.deviation());
        }
    }

    /// The segment of the pending move `prev` from its start up to its parameter `to`, at the
    /// path's arc length `start`, with its zones appended to `zones` (ending at rest for a
    /// `stop`).
    fn span_of<const K: usize>(
        &self,
        prev: &Pending<D, C, R>,
        (to, stop): (f64, bool),
        (start, tail): (f64, [(f64, f64); R]),
        zones: &mut SegmentZones<K>,
    ) -> Result<Segment<D, C, R>, Error> {
        let span = Segment::span(&prev.curve, (prev.from, to), start, prev.feed, prev.offset)?;
        let span = if prev.alone {
            span.riding_alone()
        } else {
            let ends = prev.riding_at(to)?;
            span.with_ride(core::array::from_fn(|i| (tail[i], ends[i])))
        };
        self.zones_of(&span, zones)?;
        if stop {
            zones.stop_at_end();
        }
        Ok(span)
    }

    /// The zones of `segment` appended to `out`.
    fn zones_of<const K: usize>(
        &self,
        segment: &Segment<D, C, R>,
        out: &mut SegmentZones<K>,
    ) -> Result<(), Error> {
        let feed = (segment.feed, self.feed_scale());
        out.place((segment.start, segment.length), self.period(), feed);
        let samples = if segment.uniform() {
            1
        } else {
            LOAD_SAMPLES * ParamCurve::piece_count(segment)
        };
        let mut options = self.options.plan.with_samples(samples);
        if segment.rides_alone() {
            // the riding axes' own line is the path of this move
            options = options.with_path_axes(D);
        }
        zones_into(segment, segment, &self.planned, &options, out)
    }

    /// An error unless `segments` more segments and `zones` more zones fit.
    fn room_for(&self, segments: usize, zones: usize) -> Result<(), Error> {
        if self.segments.len() + segments > Q {
            return Err(Error::CapacityExceeded {
                capacity: Q,
                required: self.segments.len() + segments,
            });
        }
        if self.window.len() + zones > Z {
            return Err(Error::ZoneCapacityExceeded {
                capacity: Z,
                required: self.window.len() + zones,
            });
        }
        Ok(())
    }

    /// Appends segments and their zones (room checked).
    fn append(
        &mut self,
        segments: &[Segment<D, C, R>],
        zones: &SegmentZones<{ 2 * SEGMENT_ZONES }>,
    ) -> Result<(), Error> {
        for g in segments {
            let _ = self.segments.push_back(*g);
        }
        let ratio = 1.0 + self.options.plan.zone_tolerance();
        self.window
            .extend_merging(zones.zones(), ratio, self.period())
    }

    /// Compiles the next stretch of at most the options' stretch ticks into `out`, committing
    /// zones from the window as it needs them; returns the ticks compiled (0 when nothing is
    /// left to compile, or `out` has too little room).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for a value that does not fit `N`;
    /// [`Error::Curve`] for a segment whose arc length does not converge.
    ///
    /// ```
    /// # use heapless::Deque;
    /// # use strak_trajectory::{Limits, Move, Piece, Stream, StreamOptions};
    /// # let limits = Limits::new(100.0, 1_000.0, 10_000.0)?;
    /// let mut stream = Stream::<2, 8, 32>::new([0.0; 2], limits, StreamOptions::new(1_000.0))?;
    /// stream.push(&Move::line([10.0, 0.0]))?;
    /// let mut pieces = Deque::<Piece<f32, 2>, 32>::new();
    /// assert_eq!(stream.poll(&mut pieces)?, 64); // a stretch of 64 ticks
    /// assert_eq!(stream.stats().starved, 1); // no move after it: it stops at its end
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn poll<N: Number>(&mut self, out: &mut impl PieceQueue<N, D>) -> Result<u32, Error> {
        if out.room() <= STRETCH_PIECES {
            return Ok(0);
        }
        let known = self.caught_up();
        self.advance()?;
        let first = self.next_tick;
        let want = first.saturating_add(self.options.stretch_ticks);
        let (last, rests) = self.cover(want, known)?;
        if last <= first {
            return Ok(0);
        }
        let mut ticks = last - first;
        let mut pieces = Vec::<Piece<N, D>, STRETCH_PIECES>::new();
        // One motion for every try: the positions it keeps serve the shorter stretches.
        let motion = self.motion();
        // For the tries after this one (the stretch halved once, twice, …), the progress
        // after the last break before their last tick: they resume from it.
        let mut ahead: [Option<Progress>; HALVINGS] = [None; HALVINGS];
        let mut resume = None;
        loop {
            let mut passed = |p: Progress| {
                for (h, slot) in (1..).zip(ahead.iter_mut()) {
                    if p.at < f64::from(first + (ticks >> h)) {
                        *slot = Some(p);
                    }
                }
            };
            if resume.is_none() {
                pieces.clear();
            }
            let span = (first, first + ticks);
            match self
                .fit
                .write_from(&motion, span, &mut pieces, resume, &mut passed)
            {
                Ok(()) => break,
                Err(Error::CapacityExceeded { .. }) if ticks > 2 => {
                    ticks /= 2;
                    resume = ahead[0];
                    ahead.rotate_left(1);
                    ahead[HALVINGS - 1] = None;
                }
                Err(e) => return Err(e),
            }
        }
        for piece in pieces {
            out.push_piece(piece);
        }
        self.next_tick = first + ticks;
        if rests && self.next_tick == last {
            out.push_piece(self.rest_piece(last)?);
            self.next_tick = last + 1;
        }
        self.drop_played();
        Ok(self.next_tick - first)
    }

    /// The piece of one tick at rest where the motion ends at tick `last`: the exact end
    /// point, no velocity or acceleration, so that a sampler holding on after it holds
    /// exactly there.
    fn rest_piece<N: Number>(&self, last: u32) -> Result<Piece<N, D>, Error> {
        let end = self.rest_point()?;
        let mut axes = [AxisState::ZERO; D];
        for (axis, x) in axes.iter_mut().zip(end) {
            axis.position = N::from_f64(x).ok_or(Error::OutOfRange)?;
        }
        Ok(Piece {
            axes,
            start: last,
            ticks: 1,
        })
    }

    /// Where the motion rests once the window is empty: the end of its last segment exactly
    /// (the committed motion's arc length can fall short of it by the rounding of the last
    /// phase's speed, and a curve evaluated short of its end misses the end point).
    fn rest_point(&self) -> Result<[f64; D], Error> {
        let last = self.segments.back().ok_or(Error::EmptyPath)?;
        Ok(last.frame(last.end())?.point)
    }

    /// The committed motion.
    fn motion(&self) -> Committed<'_, D, Q, C, R> {
        self.ticks.clear();
        Committed {
            segments: &self.segments,
            phases: &self.committed,
            period: self.period(),
            limits: self.promised,
            end: self.window.entry(),
            ticks: &self.ticks,
            cursor: Cell::new(0),
        }
    }

    /// Commits zones until the committed motion reaches tick `want`, and returns the last
    /// tick it covers, at most `want`: the end of the committed motion (the tick after it
    /// when it rests there), and whether the motion rests from that tick on. The pending
    /// move is finished (the producer has fallen behind) only where it was `known` whole
    /// before this poll: a curve move whose last pieces were appended during it ends the
    /// stretch early instead, so that its next move can be pushed.
    fn cover(&mut self, want: u32, known: bool) -> Result<(u32, bool), Error> {
        let period = self.period();
        loop {
            let (t_end, _, v_end) = self.window.entry();
            if t_end >= f64::from(want) * period {
                return Ok((want, false));
            }
            let last_zone = self.window.len() <= 1;
            if last_zone && self.pending.is_some() {
                let length = self.length;
                self.advance()?;
                if self.length > length {
                    continue; // the pending curve went on: no starvation
                }
                #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                let end = libm::floor(t_end / period) as u32;
                if !known && end > self.next_tick {
                    return Ok((end.min(want), false));
                }
                match self.finish() {
                    Ok(()) => {
                        self.stats.starved += 1;
                        continue;
                    }
                    // Full: the motion rests at the window's end, and the pending move is
                    // finished once the played segments make room.
                    Err(Error::CapacityExceeded { .. } | Error::ZoneCapacityExceeded { .. }) => {}
                    Err(e) => return Err(e),
                }
            }
            if self.window.is_empty() {
                #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                let end = libm::ceil(t_end / period - 1e-9) as u32;
                return Ok((end.min(want), end <= want));
            }
            if self.committed.len() + PHASES_PER_ZONE > PHASES {
                #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                let end = libm::floor(t_end / period) as u32;
                return Ok((end.min(want), false));
            }
            let now = f64::from(self.next_tick) * period;
            if v_end == 0.0 && t_end < now {
                self.window.hold_until(now);
            }
            if let Some(zone) = self.window.commit() {
                for p in zone.phases() {
                    let _ = self.committed.push_back(*p);
                }
            }
        }
    }

    /// Drops the phases and segments the compiled ticks have passed.
    fn drop_played(&mut self) {
        let t = f64::from(self.next_tick) * self.period();
        while self.committed.len() > 1 && self.committed.iter().nth(1).is_some_and(|p| p.t0 <= t) {
            self.committed.pop_front();
        }
        let s = self.motion().state(t).s;
        while self.segments.len() > 1 && self.segments.front().is_some_and(|g| g.end() < s) {
            self.segments.pop_front();
        }
    }
}

/// The feed ramp of a stream's sampler: its largest rate and change per tick of the feed
/// factor, from what the window leaves free of the limits (the feed share of the
/// acceleration and jerk; the motion's speed at most the path velocity limit), as a compiled
/// path's ramp is sized from its peaks. A ramp adds `φ̇·ẋᵢ` to each axis's acceleration,
/// so its rate is also kept within the share of each axis's acceleration limit.
fn feed_ramp<const D: usize>(limits: &Limits<D>, options: &StreamOptions) -> (f64, f64) {
    let share = options.plan.feed_share();
    let rate = options.plan.rate();
    let basis = RampBasis {
        rate,
        peak_velocity: limits.velocity(),
        peak_acceleration: (1.0 - share) * limits.acceleration(),
        peak_jerk: (1.0 - share) * limits.jerk(),
        acceleration_limit: limits.acceleration(),
        jerk_limit: limits.jerk(),
        feed_share: share,
    };
    let (mut omega, alpha) = feed_ramp_f64(&basis);
    for (v, a) in limits
        .axis_velocity()
        .into_iter()
        .zip(limits.axis_acceleration())
    {
        if a.is_finite() {
            omega = omega.min(share * a / (v.min(limits.velocity()) * rate));
        }
    }
    (omega, alpha.min(omega.max(MIN_ALPHA)))
}
