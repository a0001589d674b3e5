//! `strak-sim run` on a moves job ([`MovesJob`]): the moves streamed through the
//! look-ahead planner and played tick by tick, as firmware's main loop and tick interrupt
//! would.
//!
//! 1. **Stream.** A [`Stream`] at rest at the job's start, under its limits, blending every
//!    corner within `tolerance` (4 zones of look-ahead per segment of `queue`). Each tick
//!    the main loop pushes the moves that have arrived (all at once, or with `[produce]`
//!    one every `rate_hz / moves_per_second` ticks) while the stream has room, finishes
//!    the program after the last one, and polls the stream into a single-producer
//!    single-consumer queue of [`PIECE_QUEUE`] pieces.
//! 2. **Play** with [`StreamSampler`], one sample per tick, until everything is pushed, the
//!    stream is idle and the sampler holds at the end (or, guarding against a stream that
//!    makes no progress, after [`guard_ticks`] samples).
//! 3. **Measure** every sample as a path job's ([`crate::measure`]): the sampled velocity
//!    and acceleration, their finite differences and the jerk against the job's limits,
//!    with the allowance of the playback format ([`allowance`]); the distance of each
//!    sample from the programmed moves against the blend tolerance plus the stream's fit
//!    tolerance ([`crate::programmed`]).
//! 4. **Report** the stream's statistics beside the checks ([`StreamReport`]); a run whose
//!    samples exceed a limit or the distance bound lists the quantities in
//!    [`Summary::violations`] (exit code 3).

use std::fs::{self, File};
use std::io::{BufWriter, Write};
use std::path::PathBuf;
use std::sync::mpsc;
use std::time::{Duration, Instant};

use strak_curves::ParamCurve;
use strak_curves::heapless::spsc::Queue;
use strak_trajectory::{
    Error as TrajError, Junction, Kernel, Limits, Move, MoveCurve, NoCurve, Number, Piece,
    PieceQueue, PlanOptions, Q40, Sample, Stream, StreamOptions, StreamSampler, StreamStats,
    chain_junctions, junction,
};

use crate::job::{JobError, JobLimits, RATE_RANGE};
use crate::measure::{Measure, Observed, distance, to_f64};
use crate::moves::{MovesJob, QUEUE_SIZES, push_error};
use crate::number::{self, NumberFormat};
use crate::plot::{self, PathMarks, PlotLimits, Recorder};
use crate::programmed::Programmed;
use crate::run::{Allowance, CsvCell, RunError, RunOptions, channels, csv_header_named, write_row};
use crate::summary::{
    Accuracy, CheckRule, Checked, EndPoint, PlannedLimits, ReferenceDistance, StreamReport,
    Summary, WallTime,
};

/// The pieces between the stream and the sampler (the queue holds one less).
pub const PIECE_QUEUE: usize = 64;

/// The fit tolerance of the stream's pieces (units): how far they may lie from the
/// planned motion ([`StreamOptions::with_fit_tolerance`]).
pub const FIT_TOLERANCE: f64 = 1e-5;

/// How the distance of a sample from the moves is measured (reported in the summary).
pub const DISTANCE_METHOD: &str = "the nearest point of the programmed moves (each curved move \
     a polygon of 256 chords, its sag allowed)";

/// What a streamed run plays on: the control rate, the number format, the stream's
/// capacities, tolerances and limits, and the axes (a moves job's, or a G-code machine's).
#[derive(Clone, Debug, PartialEq)]
pub struct StreamSetup {
    /// Control rate in Hz.
    pub rate_hz: f64,
    /// Playback number format.
    pub number: NumberFormat,
    /// The length unit, for display.
    pub unit: String,
    /// The corner blend tolerance ε the stream starts with (units).
    pub tolerance: f64,
    /// Whether a sharp corner stops where that is estimated faster than its blend.
    pub faster_stops: bool,
    /// Look-ahead segments (the window holds four zones per segment).
    pub queue: usize,
    /// How far an arc's end may lie off the circle through its start (units).
    pub arc_tolerance: f64,
    /// The limits: path limits over the path axes, per-axis limits over every axis.
    pub limits: JobLimits,
    /// The rate the moves arrive at (`None`: all at once).
    pub moves_per_second: Option<f64>,
    /// The axes' names, in order.
    pub axis_names: Vec<String>,
    /// The axes of the path, the first of [`axis_names`](Self::axis_names); the others ride
    /// along.
    pub path_axes: usize,
}

impl StreamSetup {
    /// The zones of the look-ahead window: four per segment.
    pub fn zones(&self) -> usize {
        4 * self.queue
    }

    /// Checks the ranges of the control rate, the corner tolerance, the look-ahead and the
    /// arrival rate.
    ///
    /// # Errors
    /// A [`JobError`] naming the field.
    pub fn check(&self) -> Result<(), JobError> {
        if !(self.rate_hz >= RATE_RANGE.0 && self.rate_hz <= RATE_RANGE.1) {
            return Err(JobError::new(
                "rate_hz",
                format!(
                    "the control rate must be between 100 Hz and 100 kHz, not {} Hz",
                    self.rate_hz
                ),
            ));
        }
        if !(self.tolerance.is_finite() && self.tolerance >= 0.0) {
            return Err(JobError::new("tolerance", "must be finite and ≥ 0"));
        }
        if !QUEUE_SIZES.contains(&self.queue) {
            return Err(JobError::new(
                "queue",
                format!("must be 8, 16, 32 or 64 segments, not {}", self.queue),
            ));
        }
        if self
            .moves_per_second
            .is_some_and(|mps| !(mps.is_finite() && mps > 0.0))
        {
            return Err(JobError::new(
                "produce.moves_per_second",
                "must be finite and > 0",
            ));
        }
        Ok(())
    }
}

/// The allowance of the checks in each playback format, as the trajectory crate's stream
/// tests state it: forward differencing over a piece of up to 256 ticks adds up to
/// `256·ε·|a|` to the acceleration channel (`ε = 2⁻²⁴` in `f32`), a jerk from differences
/// of that channel twice that over a tick, and the position and velocity channels drift by
/// up to half a unit per tick until the next piece starts from the exact state
/// ([`Allowance::drift_ticks`]: 256); `Q40` rounds to `2⁻⁴⁰` units and adds exactly;
/// `f64` leaves the check's own rounding and the drift.
pub fn allowance(number: NumberFormat) -> Allowance {
    // the stream's longest piece (`StreamOptions`' default)
    let drift_ticks = 256.0;
    match number {
        NumberFormat::F32 => Allowance {
            sampled: 1e-4,
            jerk: 4e-3,
            drift_ticks,
        },
        NumberFormat::Q40 => Allowance {
            sampled: 1e-6,
            jerk: 1e-5,
            drift_ticks: 0.0,
        },
        NumberFormat::F64 => Allowance {
            drift_ticks,
            ..Allowance::default()
        },
    }
}

/// The position error of playback in each format at coordinates up to `far` units.
fn position_allowance(number: NumberFormat, far: f64) -> f64 {
    match number {
        NumberFormat::F32 => 256.0 * f64::from(f32::EPSILON) * far.max(1.0),
        _ => 1e-9,
    }
}

/// The samples after which a run stops although the stream has not ended: the ticks the
/// moves take to arrive, plus twenty times the program's length `length` at its slowest
/// feed, plus its dwells `rest_s`, plus ten seconds.
pub fn guard_ticks<const D: usize>(
    setup: &StreamSetup,
    program: &[Move<D>],
    length: f64,
    rest_s: f64,
) -> u64 {
    let slowest = program
        .iter()
        .filter_map(|m| m.feed)
        .fold(setup.limits.velocity, f64::min);
    let arrive = setup
        .moves_per_second
        .map_or(0.0, |mps| program.len() as f64 / mps);
    let seconds = arrive + 20.0 * length / slowest + rest_s + 10.0;
    (seconds * setup.rate_hz).ceil() as u64
}

/// How a corner between two moves was passed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CornerKind {
    /// Replaced by a blend.
    Blended,
    /// An exact stop (tolerance 0, a near-reversal).
    Stop,
    /// The moves join smoothly.
    Straight,
    /// The next move had not arrived: the motion came to rest there.
    Starved,
}

/// What driving the stream produced.
#[derive(Clone, Debug)]
pub(crate) struct Driven {
    pub(crate) stats: StreamStats,
    pub(crate) underruns: u32,
    pub(crate) ticks: u32,
    pub(crate) pieces: usize,
    pub(crate) planning: Duration,
    /// Each corner (the end of move `i`, `i + 1` pushed) and how it was passed.
    pub(crate) corners: Vec<CornerKind>,
    pub(crate) finished: bool,
}

/// The sink of the samples: it runs on a thread of its own, beside the loop that plans and
/// plays.
pub type Sink<'a, T, const D: usize> = dyn FnMut(&Sample<T, D>) -> Result<(), RunError> + Send + 'a;

/// Samples handed from the loop that plans and plays to the sink's thread at a time.
const BATCH: usize = 4_096;

/// Batches on their way to the sink's thread at most: the loop waits while they are all
/// unread.
const BATCHES: usize = 8;

/// A piece queue that counts the pieces it is given.
struct Counted<'a, P> {
    queue: &'a mut P,
    pieces: usize,
}

impl<N, const A: usize, P: PieceQueue<N, A>> PieceQueue<N, A> for Counted<'_, P> {
    fn room(&self) -> usize {
        self.queue.room()
    }
    fn push_piece(&mut self, piece: Piece<N, A>) {
        self.pieces += 1;
        self.queue.push_piece(piece);
    }
}

/// The machine limits of the stream.
fn stream_limits<const D: usize>(setup: &StreamSetup) -> Result<Limits<D>, JobError> {
    crate::pipeline::limits_of::<D>(&setup.limits, 1.0)
}

/// The stream's options: the setup's rate, tolerances and choice of stops.
pub fn stream_options(setup: &StreamSetup) -> StreamOptions {
    StreamOptions::new(setup.rate_hz)
        .with_tolerance(setup.tolerance)
        .with_faster_stops(setup.faster_stops)
        .with_arc_tolerance(setup.arc_tolerance)
        .with_fit_tolerance(FIT_TOLERANCE)
}

/// An error of [`Stream::poll`] or [`Stream::finish`] as an error on the run.
pub(crate) fn stream_error(setup: &StreamSetup, e: TrajError) -> JobError {
    match e {
        TrajError::OutOfRange => JobError::new(
            "number",
            format!(
                "a position, velocity or acceleration does not fit `{}` playback: move or \
                 scale the moves, or use number = \"f64\"",
                number::name(setup.number)
            ),
        ),
        other => JobError::new("moves", format!("the stream failed: {other}")),
    }
}

/// Whether a push or a finish found the stream full (poll, then try again).
fn is_full(e: &TrajError) -> bool {
    matches!(
        e,
        TrajError::CapacityExceeded { .. } | TrajError::ZoneCapacityExceeded { .. }
    )
}

/// How each corner was passed, from the stream's statistics around each push of a move.
#[derive(Clone, Debug, Default)]
pub(crate) struct Corners {
    /// Each corner (the end of move `i`, `i + 1` pushed) and how it was passed.
    pub(crate) kinds: Vec<CornerKind>,
    /// Moves pushed.
    moves: usize,
    /// The stream's starved rests at the last push.
    starved: usize,
}

impl Corners {
    /// Notes a move pushed, with the stream's statistics `before` and `after` the push.
    pub(crate) fn pushed(&mut self, before: &StreamStats, after: &StreamStats) {
        if self.moves > 0 {
            self.kinds.push(if after.blends > before.blends {
                CornerKind::Blended
            } else if after.stops > before.stops {
                CornerKind::Stop
            } else if before.starved > self.starved {
                CornerKind::Starved
            } else {
                CornerKind::Straight
            });
        }
        self.starved = after.starved;
        self.moves += 1;
    }
}

/// The main loop's side of a program: it hands the stream what has arrived.
pub(crate) trait Feed<const D: usize> {
    /// Hands the stream the moves before `arrived` (and what comes between them) while it
    /// has room; after the last one, finishes the program.
    ///
    /// # Errors
    /// A [`RunError`] naming the move the stream refuses.
    fn push_arrived<const Q: usize, const Z: usize, const R: usize>(
        &mut self,
        stream: &mut Stream<D, Q, Z, NoCurve<D>, R>,
        arrived: usize,
    ) -> Result<(), RunError>;

    /// Whether the whole program has been handed over and the stream finished.
    fn is_finished(&self) -> bool;

    /// How each corner was passed.
    fn corners(&mut self) -> Vec<CornerKind>;
}

/// A moves job's program, pushed move by move.
struct Feeder<'p, const D: usize> {
    setup: &'p StreamSetup,
    program: &'p [Move<D>],
    next: usize,
    corners: Corners,
    finished: bool,
}

impl<'p, const D: usize> Feeder<'p, D> {
    fn new(setup: &'p StreamSetup, program: &'p [Move<D>]) -> Self {
        Feeder {
            setup,
            program,
            next: 0,
            corners: Corners::default(),
            finished: false,
        }
    }
}

impl<const D: usize> Feed<D> for Feeder<'_, D> {
    fn push_arrived<const Q: usize, const Z: usize, const R: usize>(
        &mut self,
        stream: &mut Stream<D, Q, Z, NoCurve<D>, R>,
        arrived: usize,
    ) -> Result<(), RunError> {
        while self.next < arrived.min(self.program.len()) {
            let before = stream.stats();
            match stream.push(&self.program[self.next]) {
                Ok(()) => {}
                Err(e) if is_full(&e) => break,
                Err(e) => return Err(push_error(self.next, e).into()),
            }
            self.corners.pushed(&before, &stream.stats());
            self.next += 1;
        }
        if self.next == self.program.len() && !self.finished {
            match stream.finish() {
                Ok(()) => self.finished = true,
                Err(e) if is_full(&e) => {}
                Err(e) => return Err(stream_error(self.setup, e).into()),
            }
        }
        Ok(())
    }

    fn is_finished(&self) -> bool {
        self.finished
    }

    fn corners(&mut self) -> Vec<CornerKind> {
        core::mem::take(&mut self.corners.kinds)
    }
}

/// Drives the stream `Stream<D, Q, Z, _, R>` from `start` through the program `feed` hands
/// it (its moves arriving at the setup's rate), handing each sample to `sink`. The sink
/// runs on a second thread, fed batches of [`BATCH`] samples in order, so that measuring
/// and recording overlap planning; `planning` times the loop that plans and plays.
///
/// # Errors
/// The sink's first error; else the stream's and the feed's.
pub(crate) fn drive<N, F, const D: usize, const Q: usize, const Z: usize, const R: usize>(
    setup: &StreamSetup,
    start: [f64; D],
    feed: &mut F,
    guard: u64,
    sink: &mut Sink<'_, N::Out, D>,
) -> Result<Driven, RunError>
where
    N: Kernel,
    F: Feed<D>,
{
    std::thread::scope(|scope| {
        let (batches, received) = mpsc::sync_channel::<Vec<Sample<N::Out, D>>>(BATCHES);
        let measured = scope.spawn(move || {
            for batch in received {
                batch.iter().try_for_each(&mut *sink)?;
            }
            Ok::<(), RunError>(())
        });
        let mut batch = Vec::with_capacity(BATCH);
        let mut hand = |s: Sample<N::Out, D>| {
            batch.push(s);
            if batch.len() < BATCH {
                return Ok(());
            }
            let full = std::mem::replace(&mut batch, Vec::with_capacity(BATCH));
            batches.send(full).map_err(|_| sink_stopped())
        };
        let played = play::<N, F, D, Q, Z, R>(setup, start, feed, guard, &mut hand);
        let last = batches.send(batch).map_err(|_| sink_stopped());
        drop(batches);
        match measured.join() {
            Ok(measured) => measured?,
            Err(panic) => std::panic::resume_unwind(panic),
        }
        last?;
        played
    })
}

/// The error of the loop when the sink's thread stopped taking samples (it returns its
/// own error, which is reported in its place).
fn sink_stopped() -> RunError {
    RunError::Io("the samples' sink stopped".to_owned())
}

/// The loop of [`drive`]: per tick the moves arrived pushed, one poll and one sample handed
/// to `hand`, until the program is finished, the stream idle and the sampler holding, or
/// `guard` ticks have passed.
fn play<N, F, const D: usize, const Q: usize, const Z: usize, const R: usize>(
    setup: &StreamSetup,
    start: [f64; D],
    feed: &mut F,
    guard: u64,
    hand: &mut impl FnMut(Sample<N::Out, D>) -> Result<(), RunError>,
) -> Result<Driven, RunError>
where
    N: Kernel,
    F: Feed<D>,
{
    let clock = Instant::now();
    let mut stream = Box::new(
        Stream::<D, Q, Z, NoCurve<D>, R>::new(
            start,
            stream_limits::<D>(setup)?,
            stream_options(setup),
        )
        .map_err(|e| JobError::new("tolerance", e.to_string()))?,
    );
    let mut queue = Queue::<Piece<N, D>, PIECE_QUEUE>::new();
    let (mut producer, consumer) = queue.split();
    let mut pieces = Counted {
        queue: &mut producer,
        pieces: 0,
    };
    let mut sampler = StreamSampler::new(consumer, &*stream).map_err(|e| stream_error(setup, e))?;
    let mut done = false;
    for tick in 0..guard {
        feed.push_arrived(&mut stream, arrived(setup, tick))?;
        stream
            .poll(&mut pieces)
            .map_err(|e| stream_error(setup, e))?;
        hand(sampler.next())?;
        done = feed.is_finished() && stream.is_idle() && sampler.is_holding();
        if done {
            break;
        }
    }
    Ok(Driven {
        stats: stream.stats(),
        underruns: sampler.underruns(),
        ticks: stream.ticks(),
        pieces: pieces.pieces,
        planning: clock.elapsed(),
        corners: feed.corners(),
        finished: done,
    })
}

/// The longest moves a sample may pass over between two ticks (as [`Programmed`] follows
/// them): four ticks at the velocity limit plus twice the largest corner tolerance
/// `tolerance`, the moves a blend may cut across.
pub(crate) fn skip_length(setup: &StreamSetup, tolerance: f64) -> f64 {
    4.0 * setup.limits.velocity / setup.rate_hz + 2.0 * tolerance
}

/// The moves (and dwells) arrived by `tick`: all of them (`usize::MAX`), or with the setup's
/// rate one every `rate_hz / moves_per_second` ticks, the first at tick 0
/// ([`strak_gcode::arrived`], as a firmware counts them).
///
/// ```
/// # use strak_sim::stream_run::{StreamSetup, arrived};
/// # use strak_sim::{job::JobLimits, number::NumberFormat};
/// let setup = StreamSetup {
///     rate_hz: 1_000.0, number: NumberFormat::F64, unit: "mm".into(), tolerance: 0.0,
///     faster_stops: true, queue: 8, arc_tolerance: 1e-6,
///     limits: JobLimits { velocity: 1.0, acceleration: 1.0, jerk: 1.0, axis_velocity: None,
///         axis_acceleration: None },
///     moves_per_second: Some(400.0), axis_names: vec!["x".into()], path_axes: 1,
/// };
/// assert_eq!([0, 2, 3, 100].map(|t| arrived(&setup, t)), [1, 1, 2, 41]);
/// ```
pub fn arrived(setup: &StreamSetup, tick: u64) -> usize {
    setup.moves_per_second.map_or(usize::MAX, |mps| {
        strak_gcode::arrived(tick, setup.rate_hz / mps)
    })
}

/// The samples as they are played: written to `samples.csv` (every `every`-th), measured
/// and recorded for the plots.
pub(crate) struct Recording<const D: usize> {
    csv: BufWriter<File>,
    csv_path: PathBuf,
    measure: Measure<D>,
    pub(crate) recorder: Recorder,
    programmed: Programmed<D>,
    rate: f64,
    row: String,
    values: Vec<f64>,
    samples: u64,
    every: u64,
    path_axes: usize,
    last: [f64; D],
}

impl<const D: usize> Recording<D> {
    /// Creates `samples.csv` in `options.out_dir`, for about `expected` samples, of which
    /// every `every`-th is written.
    pub(crate) fn new(
        setup: &StreamSetup,
        programmed: Programmed<D>,
        options: &RunOptions,
        (expected, every): (u64, u64),
    ) -> Result<Self, RunError> {
        let csv_path = options.out_dir.join("samples.csv");
        let io =
            |e: std::io::Error| RunError::Io(format!("cannot write {}: {e}", csv_path.display()));
        let mut csv = BufWriter::new(File::create(&csv_path).map_err(io)?);
        writeln!(csv, "{}", csv_header_named(&setup.axis_names)).map_err(io)?;
        let p = setup.path_axes;
        Ok(Recording {
            csv,
            csv_path,
            measure: Measure::new(setup.rate_hz).with_path_axes(p),
            recorder: Recorder::new(D, expected).with_axes(&setup.axis_names, p),
            programmed: programmed.with_path_axes(p),
            rate: setup.rate_hz,
            row: String::new(),
            values: Vec::with_capacity(4 * D + 3),
            samples: 0,
            every: every.max(1),
            path_axes: p,
            last: [0.0; D],
        })
    }

    /// Flushes `samples.csv`.
    pub(crate) fn flush(&mut self) -> Result<(), RunError> {
        self.csv
            .flush()
            .map_err(|e| RunError::Io(format!("cannot write {}: {e}", self.csv_path.display())))
    }

    /// Writes, measures and records one sample.
    pub(crate) fn push<T: CsvCell>(
        &mut self,
        s: &Sample<T, D>,
        factor: Option<f64>,
    ) -> Result<(), RunError> {
        let k = self.samples;
        let t = k as f64 / self.rate;
        if k.is_multiple_of(self.every) {
            write_row(&mut self.row, k, t, s);
            self.csv.write_all(self.row.as_bytes()).map_err(|e| {
                RunError::Io(format!("cannot write {}: {e}", self.csv_path.display()))
            })?;
        }
        let position = to_f64(&s.position);
        let nearest = self.programmed.nearest(&position);
        let mut observed = Observed {
            t,
            position,
            velocity: to_f64(&s.velocity),
            acceleration: to_f64(&s.acceleration),
            reference: nearest,
            curve: nearest,
            // the direction of motion is the tangent of the path played
            tangent: to_f64(&s.velocity),
        };
        if let Some(f) = factor {
            observed.velocity = observed.velocity.map(|v| v * f);
        }
        let jerk = self.measure.push(&observed);
        channels(&observed, jerk, self.path_axes, &mut self.values);
        self.recorder.push(t, &self.values);
        self.last = position;
        self.samples += 1;
        Ok(())
    }
}

/// Calls `$f::<N, F, D, Q, Z, R>` with the look-ahead capacities of the setup's `queue`.
#[macro_export]
macro_rules! by_queue {
    ($setup:expr, $f:ident::<$n:ty, $feed:ty, $d:ident, $r:ident>($($arg:expr),*)) => {
        match $setup.queue {
            8 => $f::<$n, $feed, $d, 8, 32, $r>($($arg),*),
            16 => $f::<$n, $feed, $d, 16, 64, $r>($($arg),*),
            32 => $f::<$n, $feed, $d, 32, 128, $r>($($arg),*),
            64 => $f::<$n, $feed, $d, 64, 256, $r>($($arg),*),
            q => Err($crate::job::JobError::new(
                "queue",
                format!("must be 8, 16, 32 or 64 segments, not {q}"),
            )
            .into()),
        }
    };
}

/// Runs a moves job: streams and plays its moves, writes `samples.csv`, `summary.json`,
/// `path.svg` and `motion.svg` into `options.out_dir`, and returns the summary (its
/// [`Summary::violations`] name the checks the run failed).
///
/// # Errors
/// [`RunError::Job`] naming the move and field for a move the stream refuses, or the field
/// of a job the stream cannot play; [`RunError::Io`] when the output cannot be written.
pub fn run_moves(job: &MovesJob, options: &RunOptions) -> Result<Summary, RunError> {
    let axes =
        || -> RunError { JobError::new("moves[0]", "points need 1 to 6 coordinates").into() };
    match job.number {
        NumberFormat::F64 => {
            crate::with_axes!(job.axes(), run_typed::<f64>(job, options), Err(axes()))
        }
        NumberFormat::F32 => {
            crate::with_axes!(job.axes(), run_typed::<f32>(job, options), Err(axes()))
        }
        NumberFormat::Q40 => {
            crate::with_axes!(job.axes(), run_typed::<Q40>(job, options), Err(axes()))
        }
    }
}

fn run_typed<N, const D: usize>(job: &MovesJob, options: &RunOptions) -> Result<Summary, RunError>
where
    N: Kernel,
    N::Out: CsvCell,
{
    const R: usize = 0;
    let started = Instant::now();
    let setup = job.setup();
    let program = job.program::<D>()?;
    let start = job.start::<D>();
    let programmed = Programmed::new(start, &program, setup.arc_tolerance)
        .with_skip(skip_length(&setup, setup.tolerance));
    let guard = guard_ticks(&setup, &program, programmed.length, 0.0);
    create_out_dir(options)?;
    let mut rec = Recording::new(&setup, programmed, options, (guard / 20, 1))?;
    let factor = options.velocity_factor;
    let mut sink = |s: &Sample<N::Out, D>| rec.push(s, factor);
    let mut feeder = Feeder::new(&setup, &program);
    let driven = by_queue!(
        setup,
        drive::<N, Feeder<'_, D>, D, R>(&setup, start, &mut feeder, guard, &mut sink)
    )?;
    rec.flush()?;
    let play_s = started.elapsed().as_secs_f64();
    let mut summary = summarize::<N, D>(&setup, options, &driven, (&rec, setup.tolerance));
    summary.wall_time.plan_s = driven.planning.as_secs_f64();
    summary.wall_time.play_s = play_s - summary.wall_time.plan_s;
    let plots = Instant::now();
    let marks = marks(job, &program, &driven.corners);
    write_plots(&setup, options, &summary, &rec.recorder, &marks)?;
    summary.wall_time.plots_s = plots.elapsed().as_secs_f64();
    summary.wall_time.total_s = started.elapsed().as_secs_f64();
    write_summary(options, &summary)?;
    Ok(summary)
}

/// Creates the output folder.
pub(crate) fn create_out_dir(options: &RunOptions) -> Result<(), RunError> {
    let out = &options.out_dir;
    fs::create_dir_all(out)
        .map_err(|e| RunError::Io(format!("cannot write {}: {e}", out.display())))
}

/// Writes `summary.json`.
pub(crate) fn write_summary(options: &RunOptions, summary: &Summary) -> Result<(), RunError> {
    let json_path = options.out_dir.join("summary.json");
    let json = serde_json::to_string_pretty(summary)
        .map_err(|e| RunError::Io(format!("cannot write {}: {e}", json_path.display())))?;
    fs::write(&json_path, json + "\n")
        .map_err(|e| RunError::Io(format!("cannot write {}: {e}", json_path.display())))
}

/// The blends and the stops of the path plot: each blended corner's blend curve (the
/// stream's own blend: [`junction`] of the two moves at the job's tolerance, joined along
/// chains of short lines by [`chain_junctions`] as the stream joins them) and each corner
/// where the motion came to rest.
fn marks<const D: usize>(job: &MovesJob, program: &[Move<D>], corners: &[CornerKind]) -> PathMarks {
    let mut marks = PathMarks::default();
    let mut from = job.start::<D>();
    let tol = job.arc_tolerance();
    let curves: Vec<Option<MoveCurve<D>>> = program
        .iter()
        .map(|mv| {
            let c = MoveCurve::new(from, mv, tol).ok();
            from = mv.to;
            c
        })
        .collect();
    for (i, kind) in corners.iter().enumerate() {
        if matches!(kind, CornerKind::Stop | CornerKind::Starved) {
            marks.stops.push(program[i].to.to_vec());
        }
    }
    // the blends along each run of moves that all have curves, chained as the stream does
    let mut start = 0;
    while start < curves.len() {
        let run: Vec<MoveCurve<D>> = curves[start..].iter().map_while(|c| *c).collect();
        // a corner the stream did not blend (a stop, a starved move) ends a chain there
        let mut junctions: Vec<Junction<D>> = run
            .windows(2)
            .enumerate()
            .map(|(k, w)| match corners.get(start + k) {
                Some(CornerKind::Blended) => {
                    junction(&w[0], &w[1], job.tolerance).unwrap_or(Junction::Stop)
                }
                _ => Junction::Stop,
            })
            .collect();
        chain_junctions(&run, &mut junctions, job.tolerance);
        for (k, j) in junctions.iter().enumerate() {
            if let (Some(CornerKind::Blended), Junction::Blend(blend)) = (corners.get(start + k), j)
            {
                let c = blend.curve();
                marks.blends.push(
                    (0..=32)
                        .map(|t| c.eval(f64::from(t) / 32.0).to_vec())
                        .collect(),
                );
            }
        }
        start += run.len().max(1);
    }
    marks
}

/// Writes `path.svg` and `motion.svg`.
pub(crate) fn write_plots(
    setup: &StreamSetup,
    options: &RunOptions,
    summary: &Summary,
    recorder: &Recorder,
    marks: &PathMarks,
) -> Result<(), RunError> {
    let title = format!(
        "{} — {} moves streamed, ε {} {}, {} Hz, {}",
        options.name,
        summary.stream.as_ref().map_or(0, |s| s.moves),
        crate::summary::num(setup.tolerance),
        setup.unit,
        crate::summary::num(setup.rate_hz),
        summary.playback
    );
    let l = &setup.limits;
    let limits = PlotLimits {
        velocity: Some(l.velocity),
        acceleration: Some(l.acceleration),
        jerk: Some(l.jerk),
    };
    let path_svg = options.out_dir.join("path.svg");
    plot::write_path(&path_svg, recorder, &setup.unit, &title, marks)
        .map_err(|e| RunError::Io(format!("cannot write {}: {e}", path_svg.display())))?;
    let motion_svg = options.out_dir.join("motion.svg");
    plot::write_motion(&motion_svg, recorder, &setup.unit, limits, &title)
        .map_err(|e| RunError::Io(format!("cannot write {}: {e}", motion_svg.display())))
}

/// Which checks fail a moves run.
const CHECK_RULE: &str = "the stream plans jerk-limited motion under every limit: exceeding \
     one, or the blend tolerance (plus the fit tolerance) from the moves, fails the run";

/// The wall time before it is measured.
const NO_TIME: WallTime = WallTime {
    plan_s: 0.0,
    compile_s: 0.0,
    play_s: 0.0,
    plots_s: 0.0,
    total_s: 0.0,
};

/// The playback format and sample type.
fn playback_name<N: Number>() -> String {
    match N::FORMAT {
        NumberFormat::Q40 => format!("{} (samples I32F32)", N::NAME),
        _ => N::NAME.to_owned(),
    }
}

/// The stream's statistics for the summary; `tolerance`: the largest corner tolerance the
/// program asked for.
fn report(setup: &StreamSetup, driven: &Driven, tolerance: f64) -> StreamReport {
    let s = &driven.stats;
    let deviation = Checked::new(s.max_deviation, 0.0, Some(tolerance)).enforce(tolerance > 0.0);
    StreamReport {
        moves: s.moves,
        blends: s.blends,
        stops: s.stops,
        tolerance,
        max_deviation: deviation,
        starved: s.starved,
        underruns: driven.underruns,
        queue: setup.queue,
        zones: setup.zones(),
        piece_queue: PIECE_QUEUE - 1,
        moves_per_second: setup.moves_per_second,
        planning_per_move_s: driven.planning.as_secs_f64() / s.moves.max(1) as f64,
    }
}

/// The limits the stream plans with: the acceleration and jerk less the planner's feed
/// share.
fn planned_with<const D: usize>(setup: &StreamSetup) -> PlannedLimits {
    let keep = 1.0 - PlanOptions::DEFAULT_FEED_SHARE;
    let l = &setup.limits;
    let axis_a = crate::pipeline::axis_array::<D>(l.axis_acceleration.as_deref());
    PlannedLimits {
        velocity: l.velocity,
        acceleration: l.acceleration * keep,
        jerk: l.jerk * keep,
        axis_acceleration: axis_a
            .iter()
            .map(|a| Some(a * keep).filter(|x| x.is_finite()))
            .collect(),
    }
}

/// The distance of the samples from the moves, against the largest corner tolerance plus
/// the fit tolerance (allowing the chords' sag and the playback's position error).
fn accuracy<const D: usize>(setup: &StreamSetup, rec: &Recording<D>, tolerance: f64) -> Accuracy {
    let m = &rec.measure;
    let p = &rec.programmed;
    let slack = 2.0 * p.sag + position_allowance(setup.number, p.far);
    Accuracy {
        method: DISTANCE_METHOD.to_owned(),
        distance: Checked::new(m.curve.max, m.curve.at_s, Some(tolerance + FIT_TOLERANCE))
            .allowing(slack)
            .enforce(true),
    }
}

/// The summary of a streamed run whose corners were blended within at most `tolerance`.
pub(crate) fn summarize<N: Number, const D: usize>(
    setup: &StreamSetup,
    options: &RunOptions,
    driven: &Driven,
    (rec, tolerance): (&Recording<D>, f64),
) -> Summary {
    let m = &rec.measure;
    let enforced = (true, true);
    let names: Vec<&str> = setup.axis_names.iter().map(String::as_str).collect();
    let number = setup.number;
    let (path, per_axis, finite_differences, along_path) = crate::run::maxima_of(
        &setup.limits,
        number,
        enforced,
        allowance(number),
        &names,
        m,
    );
    let end = rec.programmed.end;
    let ticks = driven.ticks;
    let rate = setup.rate_hz;
    let mut summary = Summary {
        job: options.name.clone(),
        number: number::name(number).to_owned(),
        playback: playback_name::<N>(),
        axes: D,
        unit: setup.unit.clone(),
        rate_hz: rate,
        profile: "stream".to_owned(),
        feed_share: PlanOptions::DEFAULT_FEED_SHARE,
        planned_with: planned_with::<D>(setup),
        duration_s: f64::from(ticks) / rate,
        plan_duration_s: f64::from(ticks) / rate,
        ticks,
        samples: rec.samples,
        run_time_s: rec.samples.saturating_sub(1) as f64 / rate,
        stop: if driven.finished {
            "end of the moves".to_owned()
        } else {
            format!("stopped by the guard after {} samples", rec.samples)
        },
        finished: driven.finished,
        events_applied: 0,
        events_ignored: 0,
        events_late_ticks: 0,
        events_refused: 0,
        feed_events: Vec::new(),
        path_length: rec.programmed.length,
        pieces: driven.pieces,
        piece_capacity: PIECE_QUEUE - 1,
        tolerance: FIT_TOLERANCE,
        playback_bound: position_allowance(number, rec.programmed.far),
        path,
        along_path,
        per_axis,
        limits_respected: false,
        finite_differences,
        accuracy: accuracy(setup, rec, tolerance),
        check: CheckRule {
            enforced: true,
            rule: CHECK_RULE.to_owned(),
            relative_tolerance: crate::measure::RELATIVE_TOLERANCE,
        },
        violations: Vec::new(),
        reference_distance: ReferenceDistance {
            method: DISTANCE_METHOD.to_owned(),
            max: m.reference.max,
            at_s: m.reference.at_s,
        },
        end_point: EndPoint {
            last_sample: rec.last.to_vec(),
            path_end: end.to_vec(),
            reference_end: end.to_vec(),
            error_to_path_end: distance(&rec.last, &end),
            error_to_reference_end: distance(&rec.last, &end),
        },
        wall_time: NO_TIME,
        files: ["samples.csv", "summary.json", "path.svg", "motion.svg"]
            .iter()
            .map(|f| options.out_dir.join(f).display().to_string())
            .collect(),
        stream: Some(report(setup, driven, tolerance)),
        gcode: None,
    };
    summary.limits_respected = summary
        .all_checked()
        .iter()
        .all(|c| c.within != Some(false));
    summary.violations = summary.find_violations();
    summary
}

#[cfg(test)]
mod tests {
    use super::*;
    use strak_trajectory::Toolpath;

    /// Five chords of 0.2 mm on a circle of radius 10 mm, all corners blended: the plot's
    /// blends are the chained ones the stream plays (as a whole toolpath of the moves joins
    /// them), not each corner's blend alone; a starved corner ends the chain.
    #[test]
    fn the_plot_marks_the_chained_blends() {
        let mut text = String::from(
            "rate_hz = 1000\nnumber = \"f64\"\ntolerance = 0.02\nstart = [10, 0, 0]\n\
             [limits]\nvelocity = 200\nacceleration = 3000\njerk = 100000\n",
        );
        for i in 1..=5 {
            let th = 0.02 * f64::from(i);
            text += &format!(
                "[[moves]]\nline = [{}, {}, 0]\n",
                10.0 * th.cos(),
                10.0 * th.sin()
            );
        }
        let job = MovesJob::parse(&text).unwrap();
        let program = job.program::<3>().unwrap();
        let path = Toolpath::<3, 8>::new(job.start(), &program, 0.02, job.arc_tolerance()).unwrap();
        let blended = marks(&job, &program, &[CornerKind::Blended; 4]);
        assert_eq!(blended.blends.len(), 4);
        for (drawn, j) in blended.blends.iter().zip(path.junctions()) {
            let Junction::Blend(b) = j else {
                panic!("a blend")
            };
            let mid = b.curve().eval(0.5).to_vec();
            assert_eq!(drawn[16], mid);
        }
        // a starved corner in the middle: the blends before and after it are not chained to it
        let corners = [
            CornerKind::Blended,
            CornerKind::Starved,
            CornerKind::Blended,
            CornerKind::Blended,
        ];
        let starved = marks(&job, &program, &corners);
        assert_eq!((starved.blends.len(), starved.stops.len()), (3, 1));
        assert_ne!(starved.blends[0][16], blended.blends[0][16]);
        assert_eq!(starved.blends[2][16], blended.blends[3][16]);
    }
}
