//! What can be wrong with a line of G-code, and where.

use core::fmt;

/// An error in a line of G-code: what is wrong ([`ErrorKind`]) and where (the line's
/// number, counted from 1 by the caller, and the column of the offending byte, from 1).
///
/// ```
/// use strak_gcode::{ErrorKind, GcodeError};
/// let e = GcodeError { line: 12, column: 5, kind: ErrorKind::MissingValue };
/// assert_eq!(e.to_string(), "line 12, column 5: a word without a value");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct GcodeError {
    /// The line (from 1).
    pub line: u32,
    /// The column of the offending byte (from 1).
    pub column: u32,
    /// What is wrong.
    pub kind: ErrorKind,
}

/// What is wrong with a line of G-code.
///
/// ```
/// use strak_gcode::ErrorKind;
/// assert_ne!(ErrorKind::BadNumber, ErrorKind::MissingValue);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ErrorKind {
    /// A number that does not parse (`X1.2.3`, `X-`, `X.`), or is not finite.
    BadNumber,
    /// A letter without a number after it (`X` alone, `G`).
    MissingValue,
    /// A byte that is no part of a word, comment or line number (`#`, `[`, `=`: parameters
    /// and expressions are not read).
    Unexpected,
    /// A comment `(` without its `)`.
    UnclosedComment,
    /// A checksum (`*` and a number after the line) that is not the XOR of the bytes before
    /// the `*`.
    BadChecksum,
    /// The same word twice in one line (`X1 X2`), or two codes of one modal group (`G0 G1`).
    Repeated,
    /// An axis letter the machine does not have.
    UnknownAxis,
    /// Axis words without a motion mode (no `G0`, `G1`, `G2`, `G3` or `G5` yet).
    NoMotionMode,
    /// A feed move (`G1`, `G2`, `G3`, `G5`) before any `F`, or with `F` 0 or negative.
    NoFeed,
    /// An arc without its centre (`I`, `J`, `K` of its plane) or radius (`R`), or with both.
    ArcWithoutCenter,
    /// An arc whose end does not lie on the circle through its start: the distances from
    /// the centre differ by more than the reader's arc tolerance; or a radius `R` shorter
    /// than half the chord.
    ArcRadiusMismatch,
    /// An arc with `R` whose end is its start (a full circle needs `I J K`).
    ArcFullCircleWithRadius,
    /// A `G5` outside the XY plane (`G17`), without `P Q`, or without `I J` where no `G5`
    /// precedes it.
    BadCubic,
    /// A `G4` without `P`, or with a negative one.
    BadDwell,
    /// A line longer than the buffer that collects it.
    LineTooLong,
}

impl fmt::Display for ErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            ErrorKind::BadNumber => "a number that does not parse",
            ErrorKind::MissingValue => "a word without a value",
            ErrorKind::Unexpected => "a character that is not G-code here",
            ErrorKind::UnclosedComment => "a comment without its closing parenthesis",
            ErrorKind::BadChecksum => "the checksum does not match the line",
            ErrorKind::Repeated => "a word or a code of one modal group twice in the line",
            ErrorKind::UnknownAxis => "an axis the machine does not have",
            ErrorKind::NoMotionMode => "axis words without a motion mode (G0, G1, G2, G3, G5)",
            ErrorKind::NoFeed => "a feed move without a positive feed (F)",
            ErrorKind::ArcWithoutCenter => "an arc needs I J K of its plane or R, not both",
            ErrorKind::ArcRadiusMismatch => "the arc's end is not on the circle of its start",
            ErrorKind::ArcFullCircleWithRadius => "a full circle cannot be given by R",
            ErrorKind::BadCubic => "G5 needs the XY plane, P and Q, and I and J at first",
            ErrorKind::BadDwell => "G4 needs a dwell P of zero or more seconds",
            ErrorKind::LineTooLong => "the line is longer than the line buffer",
        })
    }
}

impl fmt::Display for GcodeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "line {}, column {}: {}",
            self.line, self.column, self.kind
        )
    }
}

impl core::error::Error for GcodeError {}
