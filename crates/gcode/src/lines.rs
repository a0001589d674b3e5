//! Lines of a program: from a byte slice in memory or flash ([`lines`]), or collected from
//! bytes as a serial link delivers them ([`LineBuffer`]), so that a firmware never holds
//! more of the program than one line.

use crate::error::ErrorKind;

/// The lines of `text` (split at `\n`; a `\r` before it stays, which the reader skips), the
/// last one without a line end included when it is not empty.
///
/// ```
/// let text = b"G21\r\nG1 X1 F60\n\nG1 X2";
/// let lines: Vec<&[u8]> = strak_gcode::lines(text).collect();
/// assert_eq!(lines, [&b"G21\r"[..], b"G1 X1 F60", b"", b"G1 X2"]);
/// assert_eq!(strak_gcode::lines(b"G1 X1\n").count(), 1);
/// ```
pub fn lines(text: &[u8]) -> Lines<'_> {
    Lines { rest: text }
}

/// The lines of a program in memory ([`lines`]).
#[derive(Clone, Debug)]
pub struct Lines<'a> {
    rest: &'a [u8],
}

impl<'a> Iterator for Lines<'a> {
    type Item = &'a [u8];

    fn next(&mut self) -> Option<&'a [u8]> {
        if self.rest.is_empty() {
            return None;
        }
        let (line, rest) = match self.rest.iter().position(|&b| b == b'\n') {
            Some(end) => (&self.rest[..end], &self.rest[end + 1..]),
            None => (self.rest, &self.rest[self.rest.len()..]),
        };
        self.rest = rest;
        Some(line)
    }
}

impl core::iter::FusedIterator for Lines<'_> {}

/// Collects bytes into lines of at most `N` bytes: [`push`](Self::push) each byte as it
/// arrives; at a line end it returns the line (until the next push).
///
/// ```
/// use strak_gcode::{ErrorKind, LineBuffer};
/// let mut buffer = LineBuffer::<16>::new();
/// let mut got = Vec::new();
/// for &b in b"G1 X1\nM2\n" {
///     if let Some(line) = buffer.push(b) {
///         got.push(line.map(|l| l.to_vec()));
///     }
/// }
/// assert_eq!(got, [Ok(b"G1 X1".to_vec()), Ok(b"M2".to_vec())]);
/// let mut small = LineBuffer::<4>::new();
/// let last = b"G1 X10\n".iter().filter_map(|&b| small.push(b).map(|l| l.map(<[u8]>::len))).last();
/// assert_eq!(last, Some(Err(ErrorKind::LineTooLong)));
/// ```
#[derive(Clone, Debug)]
pub struct LineBuffer<const N: usize> {
    bytes: [u8; N],
    len: usize,
    /// The line held is complete (it is dropped at the next push).
    complete: bool,
    /// More bytes came than fit since the last line end.
    overflow: bool,
}

impl<const N: usize> Default for LineBuffer<N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize> LineBuffer<N> {
    /// An empty buffer.
    pub const fn new() -> Self {
        LineBuffer {
            bytes: [0; N],
            len: 0,
            complete: false,
            overflow: false,
        }
    }

    /// Takes one byte; at a line end (`\n`) returns the line without it, or
    /// [`ErrorKind::LineTooLong`] when it held more than `N` bytes (the next line starts
    /// afresh).
    pub fn push(&mut self, byte: u8) -> Option<Result<&[u8], ErrorKind>> {
        if self.complete {
            (self.len, self.complete, self.overflow) = (0, false, false);
        }
        if byte == b'\n' {
            self.complete = true;
            return Some(if self.overflow {
                Err(ErrorKind::LineTooLong)
            } else {
                Ok(&self.bytes[..self.len])
            });
        }
        match self.bytes.get_mut(self.len) {
            Some(slot) => {
                *slot = byte;
                self.len += 1;
            }
            None => self.overflow = true,
        }
        None
    }
}
