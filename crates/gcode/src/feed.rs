//! Handing the blocks of a program to a stream: the main loop's side of streaming G-code.

use strak_trajectory::{Error, NoCurve, Stream};

use crate::reader::{Action, Block, PathMode};

/// Hands the blocks a [`Reader`](crate::Reader) reads to a [`Stream`]: a block's path mode
/// sets the stream's corner tolerance ([`PathMode::Blend`] without `P`: `default_tolerance`;
/// [`PathMode::ExactStop`]: 0), its move is pushed and its dwell added. A block the stream
/// has no room for yet is held and offered again by [`retry`](Self::retry) after a poll;
/// read the next line only when the feeder is [`ready`](Self::is_ready).
///
/// ```
/// use heapless::Deque;
/// use strak_gcode::{Feeder, Reader, lines};
/// use strak_trajectory::{Limits, Piece, Stream, StreamOptions};
/// let program = b"G21 G90 G64 P0.02\nG1 X10 F3000\nG1 Y10\nG4 P0.1\nG0 X0 Y0\n";
/// let limits = Limits::new(200.0, 3_000.0, 100_000.0)?;
/// let mut stream = Stream::<2, 8, 64>::new([0.0; 2], limits, StreamOptions::new(1_000.0))?;
/// let mut reader = Reader::new(*b"XY")?;
/// let mut feeder = Feeder::new(0.02);
/// let mut pieces = Deque::<Piece<f32, 2>, 64>::new();
/// let mut lines = lines(program);
/// loop {
///     if feeder.is_ready() {
///         match lines.next() {
///             Some(line) => feeder.offer(reader.read_line(line)?, &mut stream)?,
///             None if feeder.finish(&mut stream)? => break,
///             None => {}
///         }
///     } else {
///         feeder.retry(&mut stream)?;
///     }
///     stream.poll(&mut pieces)?;
///     pieces.clear(); // the sampler plays them
/// }
/// while !stream.is_idle() {
///     stream.poll(&mut pieces)?;
///     pieces.clear();
/// }
/// assert_eq!(stream.position()?, [0.0, 0.0]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Feeder<const D: usize> {
    held: Option<Block<D>>,
    default_tolerance: f64,
}

impl<const D: usize> Feeder<D> {
    /// A feeder holding nothing; `G64` without `P` blends within `default_tolerance`.
    pub const fn new(default_tolerance: f64) -> Self {
        Feeder {
            held: None,
            default_tolerance,
        }
    }

    /// Whether no block is held: the next line may be read.
    pub fn is_ready(&self) -> bool {
        self.held.is_none()
    }

    /// Hands `block` to `stream`, or holds it while the stream has no room.
    ///
    /// # Errors
    /// The stream's error for a block it refuses for another reason (a bad move: the
    /// block's line is the reader's [`lines`](crate::Reader::lines)); the block is dropped.
    /// [`Error::CapacityExceeded`] when the feeder already holds a block (it holds one:
    /// offer only when it [`is_ready`](Self::is_ready)); `block` is not taken.
    pub fn offer<const Q: usize, const Z: usize, const R: usize>(
        &mut self,
        block: Block<D>,
        stream: &mut Stream<D, Q, Z, NoCurve<D>, R>,
    ) -> Result<(), Error> {
        if self.held.is_some() {
            return Err(Error::CapacityExceeded {
                capacity: 1,
                required: 2,
            });
        }
        self.held = Some(block);
        self.retry(stream).map(|_| ())
    }

    /// Offers the held block again; returns whether the feeder is ready.
    ///
    /// # Errors
    /// As [`offer`](Self::offer).
    pub fn retry<const Q: usize, const Z: usize, const R: usize>(
        &mut self,
        stream: &mut Stream<D, Q, Z, NoCurve<D>, R>,
    ) -> Result<bool, Error> {
        let Some(block) = self.held else {
            return Ok(true);
        };
        match self.hand(&block, stream) {
            Ok(()) => {
                self.held = None;
                Ok(true)
            }
            Err(Error::CapacityExceeded { .. } | Error::ZoneCapacityExceeded { .. }) => Ok(false),
            Err(e) => {
                self.held = None;
                Err(e)
            }
        }
    }

    /// At the program's end: offers the held block, then finishes the stream; returns
    /// whether everything is handed over (else poll and call it again).
    ///
    /// # Errors
    /// As [`offer`](Self::offer) and [`Stream::finish`].
    pub fn finish<const Q: usize, const Z: usize, const R: usize>(
        &mut self,
        stream: &mut Stream<D, Q, Z, NoCurve<D>, R>,
    ) -> Result<bool, Error> {
        if !self.retry(stream)? {
            return Ok(false);
        }
        match stream.finish() {
            Ok(()) => Ok(true),
            Err(Error::CapacityExceeded { .. } | Error::ZoneCapacityExceeded { .. }) => Ok(false),
            Err(e) => Err(e),
        }
    }

    /// The block to the stream: its path mode, then its action.
    fn hand<const Q: usize, const Z: usize, const R: usize>(
        &self,
        block: &Block<D>,
        stream: &mut Stream<D, Q, Z, NoCurve<D>, R>,
    ) -> Result<(), Error> {
        match block.path_mode {
            Some(PathMode::ExactStop) => stream.set_tolerance(0.0)?,
            Some(PathMode::Blend(p)) => {
                stream.set_tolerance(p.unwrap_or(self.default_tolerance))?
            }
            None => {}
        }
        match block.action {
            Action::Move(m) => stream.push(&m),
            Action::Dwell(seconds) => stream.dwell(seconds),
            Action::None => Ok(()),
        }
    }
}
