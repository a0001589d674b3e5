//! Streaming on the device: a dense polyline (chords of 0.2 mm on a circle of 10 mm radius,
//! at a feed of 100 mm/s, blended within 0.02 mm) pushed into a [`Stream`] as fast as it
//! takes them, polled in the main loop and played by a [`StreamSampler`] one tick per
//! iteration, as a printer's firmware streams a curved wall: the RAM, stack and
//! instructions per move that the `stack` firmware measures.
//!
//! A whole curve planned through the same stream ([`run_curve`]): the 16-point B-spline of
//! [`planning`] pushed as one move ([`Move::curve`]) into a window of
//! [`CURVE_SEGMENTS`] segments, which its pieces pass through as they are played, so that
//! the device plans it with the window's memory and not the whole path's.
//!
//! The stream, the piece queue and the sampler are values of [`run`]'s (and
//! [`run_curve`]'s) frame, so that a stack measurement around it counts all of them with
//! the stack they need.

use heapless::spsc::Queue;
use strak_curves::ParamCurve;
use strak_trajectory::{
    Error, Kernel, Limits, Move, Piece, Stream, StreamCurve, StreamOptions, StreamSampler,
};

use crate::costs::{Costs, count};
use crate::planning;

/// Segments of the stream: a move's part between its blends and its blend each take one;
/// these chords are short enough that their blends take all of each, so 64 hold 64 moves.
pub const SEGMENTS: usize = 64;
/// Zones of the look-ahead window.
pub const ZONES: usize = 128;
/// Pieces between the main loop and the tick.
pub const PIECE_QUEUE: usize = 32;
/// The moves streamed.
pub const CHORDS: usize = 80;
/// The most ticks a run may take (it takes about 550).
const MAX_TICKS: u32 = 100_000;

/// The stream of the job: 3 axes, [`SEGMENTS`] segments, [`ZONES`] zones.
pub type DeviceStream = Stream<3, SEGMENTS, ZONES>;

/// Segments of the window the whole curve passes through: each from the middle of one of
/// its pieces to the middle of the next.
pub const CURVE_SEGMENTS: usize = 8;
/// Zones of that window.
pub const CURVE_ZONES: usize = 64;

/// The stream a whole curve passes through: 3 axes, [`CURVE_SEGMENTS`] segments,
/// [`CURVE_ZONES`] zones, moves along the job's B-spline.
pub type CurveStream<'a> = Stream<3, CURVE_SEGMENTS, CURVE_ZONES, &'a planning::Curve<f64>>;

/// The circle's radius (mm) and the angle of a chord (rad): chords of `2·R·sin(δ/2)`,
/// 0.19999 mm.
const RADIUS: f64 = 10.0;
const STEP: f64 = 0.02;

/// The end of chord `i` (from the point at angle `i·δ` to the one at `(i + 1)·δ`).
pub fn chord(i: usize) -> Move<3> {
    #[allow(clippy::cast_precision_loss)]
    let angle = STEP * (i + 1) as f64;
    Move::line([RADIUS * libm::cos(angle), RADIUS * libm::sin(angle), 0.0]).with_feed(100.0)
}

/// Starts `stream` at the circle's first point, in place: limits of 200 mm/s, 3 000 mm/s²
/// and 100 000 mm/s³ at 1 kHz, blends within 0.02 mm.
///
/// # Errors
/// As [`Stream::reset`] (not for these constants).
pub fn start(stream: &mut DeviceStream) -> Result<(), Error> {
    let limits = Limits::new(200.0, 3_000.0, 100_000.0)?;
    let options = StreamOptions::new(1_000.0).with_tolerance(0.02);
    stream.reset([RADIUS, 0.0, 0.0], limits, options)
}

/// What a run did: the ticks played, the moves pushed, the end position and the underruns.
pub struct Streamed {
    /// Ticks until the stream was idle and the sampler held at its end.
    pub ticks: u32,
    /// The last sample's position, in `f64`.
    pub end: [f64; 3],
    /// Ticks the sampler held mid-motion.
    pub underruns: u32,
}

/// The most polls that compile ticks in a run.
pub const POLLS: usize = 256;

/// What a counted run counts: each push that took a move (of [`CHORDS`]), each poll that
/// compiled ticks (of up to [`POLLS`]), and every push (refused ones too), the finish and
/// every poll.
pub type StreamCosts<'a> = Costs<'a, CHORDS, POLLS>;

/// Streams the job in `N` (`drive` over the chords); with `costs`, counts its
/// instructions into them.
///
/// # Errors
/// As `drive`: the stream's errors; [`Error::CapacityExceeded`] when the run does not
/// end.
#[inline(never)]
pub fn run<N: Kernel>(costs: Option<&mut StreamCosts<'_>>) -> Result<Streamed, Error> {
    let mut stream = DeviceStream::unset();
    start(&mut stream)?;
    drive::<N, SEGMENTS, ZONES, _>(&mut stream, (&chord, CHORDS), costs)
}

/// Plans and plays the whole B-spline of [`planning`] as one move through a
/// [`CurveStream`] in `N`, at the limits of that job, blended nowhere (it is one move),
/// compiled at its rate; with `costs`, counts its instructions into them.
///
/// # Errors
/// The curve's errors, and as `drive`: the stream's; [`Error::CapacityExceeded`] when the
/// run does not end.
#[inline(never)]
pub fn run_curve<N: Kernel>(costs: Option<&mut StreamCosts<'_>>) -> Result<Streamed, Error> {
    let curve = planning::curve::<f64>()?;
    let mut stream = CurveStream::unset();
    let options = StreamOptions::new(planning::RATE_HZ);
    stream.reset(curve.eval(0.0), planning::limits()?, options)?;
    let one = |_| Move::curve(&curve);
    drive::<N, CURVE_SEGMENTS, CURVE_ZONES, _>(&mut stream, (&one, 1), costs)
}

/// Streams `count` moves (`moves(i)` the `i`-th) through `stream` in `N`: each iteration
/// pushes the next move if the stream takes it (it refuses while its segments or window are
/// full), polls once and plays one tick; with `costs`, counts its instructions into them.
///
/// # Errors
/// The stream's errors; [`Error::CapacityExceeded`] when it does not end within
/// [`MAX_TICKS`].
fn drive<N: Kernel, const Q: usize, const Z: usize, C: StreamCurve<3>>(
    stream: &mut Stream<3, Q, Z, C>,
    (moves, count_of): (&dyn Fn(usize) -> Move<3, C>, usize),
    mut costs: Option<&mut StreamCosts<'_>>,
) -> Result<Streamed, Error> {
    let mut queue = Queue::<Piece<N, 3>, PIECE_QUEUE>::new();
    let (mut producer, consumer) = queue.split();
    let mut sampler = StreamSampler::new(consumer, stream)?;
    let (mut next, mut finished) = (0, false);
    for tick in 0..MAX_TICKS {
        if next < count_of {
            let mv = moves(next);
            let (c, pushed) = count(costs.as_deref_mut(), || stream.push(&mv));
            if take(pushed)? {
                if let Some(costs) = costs.as_deref_mut() {
                    costs.list_move(c);
                }
                next += 1;
            }
        } else if !finished {
            let (_, done) = count(costs.as_deref_mut(), || stream.finish());
            finished = take(done)?;
        }
        let (c, polled) = count(costs.as_deref_mut(), || stream.poll(&mut producer));
        if polled? > 0
            && let Some(costs) = costs.as_deref_mut()
        {
            costs.list_poll(c);
        }
        let sample = sampler.next();
        if finished && stream.is_idle() && sampler.is_holding() {
            return Ok(Streamed {
                ticks: tick + 1,
                end: sample.position.map(strak_curves::Scalar::to_f64),
                underruns: sampler.underruns(),
            });
        }
    }
    Err(Error::CapacityExceeded {
        capacity: MAX_TICKS as usize,
        required: MAX_TICKS as usize + 1,
    })
}

/// Whether a push or finish was taken: `false` while the stream is full, its other errors.
fn take(r: Result<(), Error>) -> Result<bool, Error> {
    match r {
        Ok(()) => Ok(true),
        Err(Error::CapacityExceeded { .. } | Error::ZoneCapacityExceeded { .. }) => Ok(false),
        Err(e) => Err(e),
    }
}
