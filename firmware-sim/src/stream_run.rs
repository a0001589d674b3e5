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
use std::time::{Duration, Instant};

use strak_curves::ParamCurve;
use strak_curves::heapless::spsc::Queue;
use strak_trajectory::{
    Error as TrajError, Junction, Kernel, Limits, Move, MoveCurve, Number, Piece, PieceQueue,
    PlanOptions, Q40, Sample, Stream, StreamOptions, StreamSampler, StreamStats, chain_junctions,
    junction,
};

use crate::job::JobError;
use crate::measure::{Measure, Observed, distance, to_f64};
use crate::moves::{MovesJob, push_error};
use crate::number::{self, NumberFormat};
use crate::plot::{self, PathMarks, PlotLimits, Recorder};
use crate::programmed::Programmed;
use crate::run::{Allowance, CsvCell, RunError, RunOptions, channels, csv_header, write_row};
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

/// The relative allowance of the sampled velocities and accelerations and of the jerk over
/// the limits in each playback format, as the trajectory crate's stream tests state it:
/// forward differencing over a piece of up to 256 ticks adds up to `256·ε·|a|` to the
/// acceleration channel (`ε = 2⁻²⁴` in `f32`), a jerk from differences of that channel
/// twice that over a tick; `Q40` rounds to `2⁻⁴⁰` units; `f64` leaves the check's own
/// rounding.
pub fn allowance(number: NumberFormat) -> Allowance {
    match number {
        NumberFormat::F32 => Allowance {
            sampled: 1e-4,
            jerk: 4e-3,
        },
        NumberFormat::Q40 => Allowance {
            sampled: 1e-6,
            jerk: 1e-5,
        },
        _ => Allowance::default(),
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
/// moves take to arrive, plus twenty times the program at the slowest feed, plus ten
/// seconds.
pub fn guard_ticks(job: &MovesJob, length: f64) -> u64 {
    let slowest = job
        .moves
        .iter()
        .filter_map(|m| m.feed)
        .fold(job.limits.velocity, f64::min);
    let arrive = job
        .produce
        .as_ref()
        .map_or(0.0, |p| job.moves.len() as f64 / p.moves_per_second);
    let seconds = arrive + 20.0 * length / slowest + 10.0;
    (seconds * job.rate_hz).ceil() as u64
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
struct Driven {
    stats: StreamStats,
    underruns: u32,
    ticks: u32,
    pieces: usize,
    planning: Duration,
    /// Each corner (the end of move `i`, `i + 1` pushed) and how it was passed.
    corners: Vec<CornerKind>,
    finished: bool,
}

/// The sink of the samples.
type Sink<'a, T, const D: usize> = dyn FnMut(&Sample<T, D>) -> Result<(), RunError> + 'a;

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
fn stream_limits<const D: usize>(job: &MovesJob) -> Result<Limits<D>, JobError> {
    crate::pipeline::limits_of::<D>(&job.limits, 1.0)
}

/// The stream's options: the job's rate, tolerances and choice of stops.
fn stream_options(job: &MovesJob) -> StreamOptions {
    StreamOptions::new(job.rate_hz)
        .with_tolerance(job.tolerance)
        .with_faster_stops(job.faster_stops)
        .with_arc_tolerance(job.arc_tolerance())
        .with_fit_tolerance(FIT_TOLERANCE)
}

/// An error of [`Stream::poll`] or [`Stream::finish`] as an error on the job.
fn stream_error(job: &MovesJob, e: TrajError) -> JobError {
    match e {
        TrajError::OutOfRange => JobError::new(
            "number",
            format!(
                "a position, velocity or acceleration does not fit `{}` playback: move or \
                 scale the moves, or use number = \"f64\"",
                number::name(job.number)
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

/// The main loop's side of the program: the moves pushed so far, how each corner was
/// passed, and whether the program is finished.
struct Feeder<'p, const D: usize> {
    program: &'p [Move<D>],
    next: usize,
    corners: Vec<CornerKind>,
    /// The stream's starved rests at the last push.
    starved: usize,
    finished: bool,
}

impl<'p, const D: usize> Feeder<'p, D> {
    fn new(program: &'p [Move<D>]) -> Self {
        Feeder {
            program,
            next: 0,
            corners: Vec::new(),
            starved: 0,
            finished: false,
        }
    }

    /// Pushes the moves before `arrived` while the stream has room, then finishes the
    /// program after the last one.
    fn push_arrived<const Q: usize, const Z: usize>(
        &mut self,
        job: &MovesJob,
        stream: &mut Stream<D, Q, Z>,
        arrived: usize,
    ) -> Result<(), RunError> {
        while self.next < arrived {
            let before = stream.stats();
            match stream.push(&self.program[self.next]) {
                Ok(()) => {}
                Err(e) if is_full(&e) => break,
                Err(e) => return Err(push_error(self.next, e).into()),
            }
            let after = stream.stats();
            if self.next > 0 {
                self.corners.push(if after.blends > before.blends {
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
            self.next += 1;
        }
        if self.next == self.program.len() && !self.finished {
            match stream.finish() {
                Ok(()) => self.finished = true,
                Err(e) if is_full(&e) => {}
                Err(e) => return Err(stream_error(job, e).into()),
            }
        }
        Ok(())
    }
}

/// Drives the stream `Stream<D, Q, Z>` through the job, handing each sample to `sink`.
fn drive<N: Kernel, const D: usize, const Q: usize, const Z: usize>(
    job: &MovesJob,
    program: &[Move<D>],
    guard: u64,
    sink: &mut Sink<'_, N::Out, D>,
) -> Result<Driven, RunError> {
    let start = job.start::<D>();
    let mut stream = Box::new(
        Stream::<D, Q, Z>::new(start, stream_limits::<D>(job)?, stream_options(job))
            .map_err(|e| JobError::new("tolerance", e.to_string()))?,
    );
    let mut queue = Queue::<Piece<N, D>, PIECE_QUEUE>::new();
    let (mut producer, consumer) = queue.split();
    let mut pieces = Counted {
        queue: &mut producer,
        pieces: 0,
    };
    let mut sampler = StreamSampler::new(consumer, &*stream).map_err(|e| stream_error(job, e))?;
    // The ticks between two arrivals.
    let every = job
        .produce
        .as_ref()
        .map(|p| job.rate_hz / p.moves_per_second);
    let mut feeder = Feeder::new(program);
    let mut planning = Duration::ZERO;
    let mut done = false;
    for tick in 0..guard {
        let clock = Instant::now();
        let arrived = every.map_or(program.len(), |e| {
            ((tick as f64 / e).floor() as usize + 1).min(program.len())
        });
        feeder.push_arrived(job, &mut stream, arrived)?;
        stream.poll(&mut pieces).map_err(|e| stream_error(job, e))?;
        planning += clock.elapsed();
        sink(&sampler.next())?;
        done = feeder.finished && stream.is_idle() && sampler.is_holding();
        if done {
            break;
        }
    }
    Ok(Driven {
        stats: stream.stats(),
        underruns: sampler.underruns(),
        ticks: stream.ticks(),
        pieces: pieces.pieces,
        planning,
        corners: feeder.corners,
        finished: done,
    })
}

/// The samples as they are played: written to `samples.csv`, measured and recorded for the
/// plots.
struct Recording<const D: usize> {
    csv: BufWriter<File>,
    csv_path: PathBuf,
    measure: Measure<D>,
    recorder: Recorder,
    programmed: Programmed<D>,
    rate: f64,
    row: String,
    values: Vec<f64>,
    samples: u64,
    last: [f64; D],
}

impl<const D: usize> Recording<D> {
    fn new(
        job: &MovesJob,
        programmed: Programmed<D>,
        options: &RunOptions,
    ) -> Result<Self, RunError> {
        let csv_path = options.out_dir.join("samples.csv");
        let io =
            |e: std::io::Error| RunError::Io(format!("cannot write {}: {e}", csv_path.display()));
        let mut csv = BufWriter::new(File::create(&csv_path).map_err(io)?);
        writeln!(csv, "{}", csv_header(D)).map_err(io)?;
        let expected = guard_ticks(job, programmed.length) / 20;
        Ok(Recording {
            csv,
            csv_path,
            measure: Measure::new(job.rate_hz),
            recorder: Recorder::new(D, expected),
            programmed,
            rate: job.rate_hz,
            row: String::new(),
            values: Vec::with_capacity(4 * D + 3),
            samples: 0,
            last: [0.0; D],
        })
    }

    /// Writes, measures and records one sample.
    fn push<T: CsvCell>(&mut self, s: &Sample<T, D>, factor: Option<f64>) -> Result<(), RunError> {
        let k = self.samples;
        let t = k as f64 / self.rate;
        write_row(&mut self.row, k, t, s);
        self.csv
            .write_all(self.row.as_bytes())
            .map_err(|e| RunError::Io(format!("cannot write {}: {e}", self.csv_path.display())))?;
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
        channels(&observed, self.measure.push(&observed), &mut self.values);
        self.recorder.push(t, &self.values);
        self.last = position;
        self.samples += 1;
        Ok(())
    }
}

/// Calls `$f::<N, D, Q, Z>` with the look-ahead capacities of the job's `queue`.
macro_rules! by_queue {
    ($job:expr, $f:ident::<$n:ty, $d:ident>($($arg:expr),*)) => {
        match $job.queue {
            8 => $f::<$n, $d, 8, 32>($($arg),*),
            16 => $f::<$n, $d, 16, 64>($($arg),*),
            32 => $f::<$n, $d, 32, 128>($($arg),*),
            64 => $f::<$n, $d, 64, 256>($($arg),*),
            q => Err(JobError::new("queue", format!("must be 8, 16, 32 or 64 segments, not {q}")).into()),
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
    let started = Instant::now();
    let program = job.program::<D>()?;
    let start = job.start::<D>();
    let programmed = Programmed::new(start, &program, job.arc_tolerance());
    let guard = guard_ticks(job, programmed.length);
    let out = &options.out_dir;
    fs::create_dir_all(out)
        .map_err(|e| RunError::Io(format!("cannot write {}: {e}", out.display())))?;
    let mut rec = Recording::new(job, programmed, options)?;
    let factor = options.velocity_factor;
    let mut sink = |s: &Sample<N::Out, D>| rec.push(s, factor);
    let driven = by_queue!(job, drive::<N, D>(job, &program, guard, &mut sink))?;
    rec.csv
        .flush()
        .map_err(|e| RunError::Io(format!("cannot write {}: {e}", rec.csv_path.display())))?;
    let play_s = started.elapsed().as_secs_f64();
    let mut summary = summarize::<N, D>(job, options, &driven, &rec);
    summary.wall_time.plan_s = driven.planning.as_secs_f64();
    summary.wall_time.play_s = play_s - summary.wall_time.plan_s;
    let plots = Instant::now();
    write_plots(
        job,
        options,
        &summary,
        &rec.recorder,
        &marks(job, &program, &driven.corners),
    )?;
    summary.wall_time.plots_s = plots.elapsed().as_secs_f64();
    summary.wall_time.total_s = started.elapsed().as_secs_f64();
    let json_path = out.join("summary.json");
    let json = serde_json::to_string_pretty(&summary)
        .map_err(|e| RunError::Io(format!("cannot write {}: {e}", json_path.display())))?;
    fs::write(&json_path, json + "\n")
        .map_err(|e| RunError::Io(format!("cannot write {}: {e}", json_path.display())))?;
    Ok(summary)
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

fn write_plots(
    job: &MovesJob,
    options: &RunOptions,
    summary: &Summary,
    recorder: &Recorder,
    marks: &PathMarks,
) -> Result<(), RunError> {
    let title = format!(
        "{} — {} moves streamed, ε {} {}, {} Hz, {}",
        options.name,
        job.moves.len(),
        crate::summary::num(job.tolerance),
        job.unit(),
        crate::summary::num(job.rate_hz),
        summary.playback
    );
    let l = &job.limits;
    let limits = PlotLimits {
        velocity: Some(l.velocity),
        acceleration: Some(l.acceleration),
        jerk: Some(l.jerk),
    };
    let path_svg = options.out_dir.join("path.svg");
    plot::write_path(&path_svg, recorder, job.unit(), &title, marks)
        .map_err(|e| RunError::Io(format!("cannot write {}: {e}", path_svg.display())))?;
    let motion_svg = options.out_dir.join("motion.svg");
    plot::write_motion(&motion_svg, recorder, job.unit(), limits, &title)
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

/// The stream's statistics for the summary.
fn report(job: &MovesJob, driven: &Driven) -> StreamReport {
    let s = &driven.stats;
    let deviation =
        Checked::new(s.max_deviation, 0.0, Some(job.tolerance)).enforce(job.tolerance > 0.0);
    StreamReport {
        moves: s.moves,
        blends: s.blends,
        stops: s.stops,
        tolerance: job.tolerance,
        max_deviation: deviation,
        starved: s.starved,
        underruns: driven.underruns,
        queue: job.queue,
        zones: job.zones(),
        piece_queue: PIECE_QUEUE - 1,
        moves_per_second: job.produce.as_ref().map(|p| p.moves_per_second),
        planning_per_move_s: driven.planning.as_secs_f64() / s.moves.max(1) as f64,
    }
}

/// The limits the stream plans with: the acceleration and jerk less the planner's feed
/// share.
fn planned_with<const D: usize>(job: &MovesJob) -> PlannedLimits {
    let keep = 1.0 - PlanOptions::DEFAULT_FEED_SHARE;
    let axis_a = crate::pipeline::axis_array::<D>(job.limits.axis_acceleration.as_deref());
    PlannedLimits {
        velocity: job.limits.velocity,
        acceleration: job.limits.acceleration * keep,
        jerk: job.limits.jerk * keep,
        axis_acceleration: axis_a
            .iter()
            .map(|a| Some(a * keep).filter(|x| x.is_finite()))
            .collect(),
    }
}

/// The distance of the samples from the moves, against the blend tolerance plus the fit
/// tolerance (allowing the chords' sag and the playback's position error).
fn accuracy<const D: usize>(job: &MovesJob, rec: &Recording<D>) -> Accuracy {
    let m = &rec.measure;
    let p = &rec.programmed;
    let slack = 2.0 * p.sag + position_allowance(job.number, p.far);
    Accuracy {
        method: DISTANCE_METHOD.to_owned(),
        distance: Checked::new(
            m.curve.max,
            m.curve.at_s,
            Some(job.tolerance + FIT_TOLERANCE),
        )
        .allowing(slack)
        .enforce(true),
    }
}

fn summarize<N: Number, const D: usize>(
    job: &MovesJob,
    options: &RunOptions,
    driven: &Driven,
    rec: &Recording<D>,
) -> Summary {
    let m = &rec.measure;
    let enforced = (true, true);
    let (path, per_axis, finite_differences, along_path) =
        crate::run::maxima_of(&job.limits, job.number, enforced, allowance(job.number), m);
    let end = rec.programmed.end;
    let ticks = driven.ticks;
    let mut summary = Summary {
        job: options.name.clone(),
        number: number::name(job.number).to_owned(),
        playback: playback_name::<N>(),
        axes: D,
        unit: job.unit().to_owned(),
        rate_hz: job.rate_hz,
        profile: "stream".to_owned(),
        feed_share: PlanOptions::DEFAULT_FEED_SHARE,
        planned_with: planned_with::<D>(job),
        duration_s: f64::from(ticks) / job.rate_hz,
        plan_duration_s: f64::from(ticks) / job.rate_hz,
        ticks,
        samples: rec.samples,
        run_time_s: rec.samples.saturating_sub(1) as f64 / job.rate_hz,
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
        playback_bound: position_allowance(job.number, rec.programmed.far),
        path,
        along_path,
        per_axis,
        limits_respected: false,
        finite_differences,
        accuracy: accuracy(job, rec),
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
        stream: Some(report(job, driven)),
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
