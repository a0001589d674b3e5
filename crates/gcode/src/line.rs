//! One line's words sorted by their role: the G codes, the axis words, the parameters of
//! arcs, cubics, dwells and path modes, and the feed. The codes a reader does not act on
//! are counted ([`Ignored`]).

use heapless::Vec;

use crate::error::ErrorKind;
use crate::words::{Word, words};

/// The most G codes of one line.
const LINE_CODES: usize = 8;

/// The most distinct codes [`Ignored`] counts one by one.
pub const IGNORED_KINDS: usize = 32;

/// A code a reader does not act on: its letter and number (`M3` is `(b'M', 30)`, in tenths
/// so that `G64.1` fits; `S` and other letters without a code number count as number 0).
///
/// ```
/// use strak_gcode::Code;
/// let m3 = Code { letter: b'M', tenths: 30 };
/// assert_eq!(m3.to_string(), "M3");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Code {
    /// The letter, upper case.
    pub letter: u8,
    /// The number in tenths (`G61.1`: 611).
    pub tenths: u32,
}

impl core::fmt::Display for Code {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let letter = char::from(self.letter);
        match self.letter {
            b'G' | b'M' | b'T' if self.tenths.is_multiple_of(10) => {
                write!(f, "{letter}{}", self.tenths / 10)
            }
            b'G' | b'M' | b'T' => write!(f, "{letter}{}.{}", self.tenths / 10, self.tenths % 10),
            _ => write!(f, "{letter}"),
        }
    }
}

/// The codes a reader did not act on, each with how often it came (the first
/// [`IGNORED_KINDS`] distinct ones; the others are counted together).
///
/// ```
/// use strak_gcode::Ignored;
/// let none = Ignored::default();
/// assert_eq!((none.kinds().len(), none.others()), (0, 0));
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Ignored {
    kinds: Vec<(Code, u32), IGNORED_KINDS>,
    others: u32,
}

impl Ignored {
    /// The codes counted one by one, in the order they first came, with their counts.
    pub fn kinds(&self) -> &[(Code, u32)] {
        &self.kinds
    }

    /// How many codes came beyond the first [`IGNORED_KINDS`] distinct ones.
    pub fn others(&self) -> u32 {
        self.others
    }

    /// Counts one more `code`.
    pub(crate) fn count(&mut self, code: Code) {
        if let Some((_, n)) = self.kinds.iter_mut().find(|(c, _)| *c == code) {
            *n = n.saturating_add(1);
        } else if self.kinds.push((code, 1)).is_err() {
            self.others = self.others.saturating_add(1);
        }
    }
}

/// A value of a line with the column of its word.
pub(crate) type At = (f64, u32);

/// The words of one line, by role.
#[derive(Debug)]
pub(crate) struct Line<const D: usize> {
    /// The G codes in tenths, with their columns.
    pub(crate) codes: Vec<(u32, u32), LINE_CODES>,
    /// The axis words, by the machine's axis index.
    pub(crate) axes: [Option<At>; D],
    /// `I`, `J`, `K`, `R`, `P`, `Q`.
    pub(crate) params: [Option<At>; 6],
    pub(crate) feed: Option<At>,
    /// The column of the line's first word (1 for a line without words).
    pub(crate) first: u32,
    /// The codes it holds that a reader does not act on (beyond 8: not kept).
    pub(crate) ignored: Vec<Code, LINE_CODES>,
}

/// The parameter letters of [`Line::params`], in order.
pub(crate) const PARAMS: [u8; 6] = *b"IJKRPQ";

impl<const D: usize> Line<D> {
    /// Sorts the words of `text` for a machine with the axis letters `axes`.
    pub(crate) fn read(text: &[u8], axes: &[u8; D]) -> Result<Self, (u32, ErrorKind)> {
        let mut line = Line {
            codes: Vec::new(),
            axes: [None; D],
            params: [None; 6],
            feed: None,
            first: 0,
            ignored: Vec::new(),
        };
        words(text, &mut |w| line.take(w, axes))?;
        if line.first == 0 {
            line.first = 1;
        }
        Ok(line)
    }

    /// Files the word `w`.
    fn take(&mut self, w: Word, axes: &[u8; D]) -> Result<(), ErrorKind> {
        if self.first == 0 {
            self.first = w.column;
        }
        let at = (w.value, w.column);
        match w.letter {
            b'G' => {
                let tenths = tenths(w.value)?;
                if self.codes.iter().any(|&(c, _)| c == tenths) {
                    return Err(ErrorKind::Repeated);
                }
                self.codes
                    .push((tenths, w.column))
                    .map_err(|_| ErrorKind::Repeated)
            }
            b'M' | b'T' => {
                let tenths = tenths(w.value)?;
                let _ = self.ignored.push(Code {
                    letter: w.letter,
                    tenths,
                });
                Ok(())
            }
            b'N' => Ok(()),
            b'F' => set(&mut self.feed, at),
            b'X' | b'Y' | b'Z' | b'A' | b'B' | b'C' | b'E' | b'U' | b'V' | b'W' => {
                let axis = axes.iter().position(|&a| a == w.letter);
                let slot = axis
                    .and_then(|i| self.axes.get_mut(i))
                    .ok_or(ErrorKind::UnknownAxis)?;
                set(slot, at)
            }
            letter => match PARAMS.iter().position(|&p| p == letter) {
                Some(i) => set(&mut self.params[i], at),
                None => {
                    let _ = self.ignored.push(Code { letter, tenths: 0 });
                    Ok(())
                }
            },
        }
    }

    /// The parameter `letter` (one of [`PARAMS`]).
    pub(crate) fn param(&self, letter: u8) -> Option<At> {
        let i = PARAMS.iter().position(|&p| p == letter)?;
        self.params[i]
    }

    /// Whether the line has any axis word.
    pub(crate) fn moves_axes(&self) -> bool {
        self.axes.iter().any(Option::is_some)
    }
}

/// A slot filled once per line.
fn set(slot: &mut Option<At>, at: At) -> Result<(), ErrorKind> {
    if slot.is_some() {
        return Err(ErrorKind::Repeated);
    }
    *slot = Some(at);
    Ok(())
}

/// A code number in tenths (`61.1` → 611): a non-negative number with at most one decimal.
fn tenths(value: f64) -> Result<u32, ErrorKind> {
    let t = libm::round(value * 10.0);
    if !(value >= 0.0 && (value * 10.0 - t).abs() < 1e-6 && t <= f64::from(u32::MAX)) {
        return Err(ErrorKind::BadNumber);
    }
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    Ok(t as u32)
}
