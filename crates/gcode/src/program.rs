//! A whole program in memory (or flash) handed to a stream as its moves arrive: the main
//! loop of a firmware that plays G-code, one call per tick.

use strak_trajectory::{Error, NoCurve, Stream};

use crate::error::GcodeError;
use crate::feed::Feeder;
use crate::lines::{Lines, lines};
use crate::reader::{Action, Reader};

/// The moves arrived by `tick` when one arrives every `ticks_per_move` ticks, the first at
/// tick 0 (a producer at a limited rate: a host streaming over a slow link).
///
/// ```
/// assert_eq!([0, 2, 3, 100].map(|t| strak_gcode::arrived(t, 2.5)), [1, 1, 2, 41]);
/// ```
pub fn arrived(tick: u64, ticks_per_move: f64) -> usize {
    #[allow(clippy::cast_precision_loss, clippy::cast_possible_truncation)]
    let n = libm::floor(tick as f64 / ticks_per_move) as usize;
    n.saturating_add(1)
}

/// What a [`Program::step`] did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Step {
    /// A line was read and its block handed to the stream (`moved`: the block was a move).
    Handed {
        /// Whether the block was a move.
        moved: bool,
    },
    /// The stream has no room for the block held (poll it, then step again).
    Full,
    /// The moves and dwells that have arrived are read; the next has not arrived.
    Waiting,
    /// The whole program is handed over and the stream finished.
    Finished,
}

/// Why a program cannot be played on.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum FeedError {
    /// A line is bad.
    Line(GcodeError),
    /// The stream refused the block of the line `line`.
    Refused {
        /// The line (from 1).
        line: u32,
        /// The stream's error.
        error: Error,
    },
}

impl core::fmt::Display for FeedError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            FeedError::Line(e) => write!(f, "{e}"),
            FeedError::Refused { line, error } => {
                write!(f, "line {line}: the stream refused the block: {error}")
            }
        }
    }
}

impl core::error::Error for FeedError {}

/// A program's text read line by line into a stream as its moves arrive: each call of
/// [`feed`](Self::feed) reads the lines whose moves (and dwells) have arrived while the
/// stream takes their blocks, and finishes the stream after the last line.
///
/// ```
/// use heapless::Deque;
/// use strak_gcode::{Program, Reader};
/// use strak_trajectory::{Limits, Piece, Stream, StreamOptions};
/// let text = b"G21 G64 P0.02\nG1 X10 F3000\nG1 Y10\nM5\nG0 X0 Y0\n";
/// let limits = Limits::new(200.0, 3_000.0, 100_000.0)?;
/// let mut stream = Stream::<2, 8, 32>::new([0.0; 2], limits, StreamOptions::new(1_000.0))?;
/// let mut program = Program::new(text, Reader::new(*b"XY")?, 0.02);
/// let mut pieces = Deque::<Piece<f32, 2>, 64>::new();
/// for tick in 0.. {
///     // one move arrives every 100 ticks
///     program.feed(&mut stream, strak_gcode::arrived(tick, 100.0))?;
///     stream.poll(&mut pieces)?;
///     pieces.clear(); // the sampler plays them
///     if program.is_finished() && stream.is_idle() {
///         break;
///     }
/// }
/// assert_eq!((program.motions(), stream.position()?), (3, [0.0, 0.0]));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct Program<'t, const D: usize> {
    lines: Lines<'t>,
    reader: Reader<D>,
    feeder: Feeder<D>,
    motions: usize,
    held_move: bool,
    finished: bool,
}

impl<'t, const D: usize> Program<'t, D> {
    /// The program `text` read by `reader`; `G64` without `P` blends within
    /// `default_tolerance`.
    pub fn new(text: &'t [u8], reader: Reader<D>, default_tolerance: f64) -> Self {
        Program {
            lines: lines(text),
            reader,
            feeder: Feeder::new(default_tolerance),
            motions: 0,
            held_move: false,
            finished: false,
        }
    }

    /// The reader (its position, lines read and ignored codes).
    pub fn reader(&self) -> &Reader<D> {
        &self.reader
    }

    /// The moves and dwells read so far.
    pub fn motions(&self) -> usize {
        self.motions
    }

    /// Whether the whole program is handed over and the stream finished.
    pub fn is_finished(&self) -> bool {
        self.finished
    }

    /// Steps ([`step`](Self::step)) while lines are handed over.
    ///
    /// # Errors
    /// As [`step`](Self::step).
    pub fn feed<const Q: usize, const Z: usize, const R: usize>(
        &mut self,
        stream: &mut Stream<D, Q, Z, NoCurve<D>, R>,
        arrived: usize,
    ) -> Result<Step, FeedError> {
        loop {
            match self.step(stream, arrived)? {
                Step::Handed { .. } => {}
                other => return Ok(other),
            }
        }
    }

    /// Hands the block held to the stream, else reads the next line if a move or dwell is
    /// still to arrive (`arrived`: the moves and dwells arrived so far), else finishes the
    /// stream after the last line.
    ///
    /// # Errors
    /// [`FeedError::Line`] for a bad line; [`FeedError::Refused`] for a block the stream
    /// refuses (a move it cannot play). The program cannot go on after either.
    pub fn step<const Q: usize, const Z: usize, const R: usize>(
        &mut self,
        stream: &mut Stream<D, Q, Z, NoCurve<D>, R>,
        arrived: usize,
    ) -> Result<Step, FeedError> {
        if !self.feeder.is_ready() {
            return Ok(if self.retry(stream)? {
                Step::Handed {
                    moved: self.held_move,
                }
            } else {
                Step::Full
            });
        }
        if self.finished {
            return Ok(Step::Finished);
        }
        if self.motions >= arrived {
            return Ok(Step::Waiting);
        }
        let Some(line) = self.lines.next() else {
            self.finished = self.feeder.finish(stream).map_err(|e| self.refused(e))?;
            return Ok(if self.finished {
                Step::Finished
            } else {
                Step::Full
            });
        };
        let block = self.reader.read_line(line).map_err(FeedError::Line)?;
        self.held_move = matches!(block.action, Action::Move(_));
        if !matches!(block.action, Action::None) {
            self.motions += 1;
        }
        self.feeder
            .offer(block, stream)
            .map_err(|e| self.refused(e))?;
        Ok(if self.feeder.is_ready() {
            Step::Handed {
                moved: self.held_move,
            }
        } else {
            Step::Full
        })
    }

    fn retry<const Q: usize, const Z: usize, const R: usize>(
        &mut self,
        stream: &mut Stream<D, Q, Z, NoCurve<D>, R>,
    ) -> Result<bool, FeedError> {
        self.feeder.retry(stream).map_err(|e| self.refused(e))
    }

    fn refused(&self, error: Error) -> FeedError {
        FeedError::Refused {
            line: self.reader.lines(),
            error,
        }
    }
}
