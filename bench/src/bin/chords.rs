//! Instructions per streamed move, for `valgrind --tool=callgrind` (repeatable, unlike
//! wall-clock times on a shared machine): streams the example firmware's job (80 chords of
//! 0.2 mm on a circle of 10 mm radius at a feed of 100 mm/s, blended within 0.02 mm,
//! through a `Stream<3, 64, 128>`, polled once per tick into a queue of 32 `f32` pieces and
//! played by a `StreamSampler`) inside the function `stream_all`, and prints the ticks and
//! the end point.
//!
//! ```text
//! cargo build --release -p strak-bench --bin chords
//! valgrind --tool=callgrind --callgrind-out-file=cg.out target/release/chords
//! callgrind_annotate --inclusive=yes cg.out | grep strak_trajectory
//! ```
//! Instructions per move: the inclusive `Ir` of `chords::stream_all` divided by 80; the
//! lines of `Stream::push` and `Stream::poll` split it.

use std::process::ExitCode;

use strak_curves::heapless::spsc::Queue;
use strak_trajectory::{Error, Limits, Move, Piece, Stream, StreamOptions, StreamSampler};

/// The moves streamed.
const CHORDS: usize = 80;

/// The end of chord `i`, on the circle from (10, 0, 0).
fn chord(i: usize) -> Move<3> {
    #[allow(clippy::cast_precision_loss)]
    let angle = 0.02 * (i + 1) as f64;
    Move::line([10.0 * angle.cos(), 10.0 * angle.sin(), 0.0]).with_feed(100.0)
}

/// Whether a push or finish was taken: `false` while the stream is full.
fn taken(r: Result<(), Error>) -> Result<bool, Error> {
    match r {
        Ok(()) => Ok(true),
        Err(Error::CapacityExceeded { .. } | Error::ZoneCapacityExceeded { .. }) => Ok(false),
        Err(e) => Err(e),
    }
}

/// Streams the chords as the firmware does: each tick pushes the next move if the stream
/// takes it, polls once and plays one tick; returns the ticks and the last position.
#[inline(never)]
fn stream_all(stream: &mut Stream<3, 64, 128>) -> Result<(u32, [f32; 3]), Error> {
    let limits = Limits::new(200.0, 3_000.0, 100_000.0)?;
    stream.reset(
        [10.0, 0.0, 0.0],
        limits,
        StreamOptions::new(1_000.0).with_tolerance(0.02),
    )?;
    let mut queue = Queue::<Piece<f32, 3>, 32>::new();
    let (mut producer, consumer) = queue.split();
    let mut sampler = StreamSampler::new(consumer, stream)?;
    let (mut next, mut finished) = (0, false);
    for tick in 0..100_000 {
        if next < CHORDS {
            if taken(stream.push(&chord(next)))? {
                next += 1;
            }
        } else if !finished {
            finished = taken(stream.finish())?;
        }
        stream.poll(&mut producer)?;
        let sample = sampler.next();
        if finished && stream.is_idle() && sampler.is_holding() {
            return Ok((tick + 1, sample.position));
        }
    }
    Err(Error::CapacityExceeded {
        capacity: 100_000,
        required: 100_001,
    })
}

fn main() -> ExitCode {
    let mut stream = Box::new(Stream::<3, 64, 128>::unset());
    match stream_all(&mut stream) {
        Ok((ticks, end)) => {
            println!("{CHORDS} moves, {ticks} ticks, end {end:?}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("chords: {e}");
            ExitCode::FAILURE
        }
    }
}
