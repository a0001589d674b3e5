//! The words of a line of G-code: a letter and a number each (`G1`, `X-12.5`), with the
//! comments (`( … )` and `; …` to the end), spaces, the program delimiter `%`, the block
//! delete `/` and a trailing checksum (`*` and the XOR of the bytes before it, as RepRap
//! firmware's serial protocol sends it) taken out.

use crate::error::ErrorKind;

/// A word: its letter (upper case), its value and the column of its letter (from 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Word {
    pub(crate) letter: u8,
    pub(crate) value: f64,
    pub(crate) column: u32,
}

/// The longest number read (digits, sign and point).
const NUMBER_BYTES: usize = 32;

/// Calls `emit` with the words of `line` in order; stops at the first error of the line or
/// of `emit`, and returns it with its column.
pub(crate) fn words(
    line: &[u8],
    emit: &mut dyn FnMut(Word) -> Result<(), ErrorKind>,
) -> Result<(), (u32, ErrorKind)> {
    let line = checked(line)?;
    let mut i = 0;
    while let Some(&b) = line.get(i) {
        let column = column_of(i);
        match b {
            b' ' | b'\t' | b'\r' | b'\n' | b'%' | b'/' => i += 1,
            b';' => break,
            b'(' => match line[i..].iter().position(|&c| c == b')') {
                Some(close) => i += close + 1,
                None => return Err((column, ErrorKind::UnclosedComment)),
            },
            b'a'..=b'z' | b'A'..=b'Z' => {
                let (value, next) = number(line, i + 1).map_err(|k| (column, k))?;
                let letter = b.to_ascii_uppercase();
                emit(Word {
                    letter,
                    value,
                    column,
                })
                .map_err(|k| (column, k))?;
                i = next;
            }
            _ => return Err((column, ErrorKind::Unexpected)),
        }
    }
    Ok(())
}

/// The column (from 1) of the byte at index `i`.
fn column_of(i: usize) -> u32 {
    u32::try_from(i + 1).unwrap_or(u32::MAX)
}

/// `line` up to its checksum `*`, once the checksum is checked (the whole line without
/// one).
fn checked(line: &[u8]) -> Result<&[u8], (u32, ErrorKind)> {
    let Some(star) = line.iter().position(|&b| b == b'*') else {
        return Ok(line);
    };
    let column = column_of(star);
    let digits = line[star + 1..].trim_ascii();
    let given = core::str::from_utf8(digits)
        .ok()
        .and_then(|s| s.parse::<u8>().ok())
        .ok_or((column, ErrorKind::BadChecksum))?;
    let sum = line[..star].iter().fold(0_u8, |x, b| x ^ b);
    if sum == given {
        Ok(&line[..star])
    } else {
        Err((column, ErrorKind::BadChecksum))
    }
}

/// The number starting at or after index `i` of `line` (spaces before it skipped), and the
/// index after it.
fn number(line: &[u8], mut i: usize) -> Result<(f64, usize), ErrorKind> {
    while matches!(line.get(i), Some(b' ' | b'\t')) {
        i += 1;
    }
    let mut text = [0_u8; NUMBER_BYTES];
    let (mut len, mut digits, mut point) = (0, 0, false);
    while let Some(&b) = line.get(i) {
        let sign = (b == b'-' || b == b'+') && len == 0;
        match b {
            b'0'..=b'9' => digits += 1,
            b'.' if !point => point = true,
            b'.' => return Err(ErrorKind::BadNumber),
            _ if sign => {}
            _ => break,
        }
        *text.get_mut(len).ok_or(ErrorKind::BadNumber)? = b;
        len += 1;
        i += 1;
    }
    if len == 0 {
        return Err(ErrorKind::MissingValue);
    }
    if digits == 0 {
        return Err(ErrorKind::BadNumber);
    }
    let value = core::str::from_utf8(&text[..len])
        .ok()
        .and_then(|s| s.parse::<f64>().ok())
        .filter(|v| v.is_finite())
        .ok_or(ErrorKind::BadNumber)?;
    Ok((value, i))
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::vec;
    use std::vec::Vec;

    /// A word as `(letter, value, column)`.
    type Read = (char, f64, u32);

    fn all(line: &str) -> Result<Vec<Read>, (u32, ErrorKind)> {
        let mut out = Vec::new();
        words(line.as_bytes(), &mut |w| {
            out.push((char::from(w.letter), w.value, w.column));
            Ok(())
        })?;
        Ok(out)
    }

    #[test]
    fn words_comments_and_spaces() {
        assert_eq!(
            all("N10 g01 X-1.5 (a comment) y .25; the rest"),
            Ok(vec![
                ('N', 10.0, 1),
                ('G', 1.0, 5),
                ('X', -1.5, 9),
                ('Y', 0.25, 27)
            ])
        );
        assert_eq!(
            all("G1X10Y+2."),
            Ok(vec![('G', 1.0, 1), ('X', 10.0, 3), ('Y', 2.0, 6)])
        );
        assert_eq!(all("% / ( only comments ) ;"), Ok(vec![]));
        assert_eq!(all("X 12"), Ok(vec![('X', 12.0, 1)]));
    }

    #[test]
    fn bad_words_name_their_column() {
        assert_eq!(all("G1 X"), Err((4, ErrorKind::MissingValue)));
        assert_eq!(all("G1 X Y2"), Err((4, ErrorKind::MissingValue)));
        assert_eq!(all("G1 X1.2.3"), Err((4, ErrorKind::BadNumber)));
        assert_eq!(all("G1 X-"), Err((4, ErrorKind::BadNumber)));
        assert_eq!(all("G1 X."), Err((4, ErrorKind::BadNumber)));
        assert_eq!(all("G1 X#1"), Err((4, ErrorKind::MissingValue)));
        assert_eq!(all("G1 #1=2"), Err((4, ErrorKind::Unexpected)));
        assert_eq!(all("G1 (open"), Err((4, ErrorKind::UnclosedComment)));
        let long = "X1234567890123456789012345678901234567890";
        assert_eq!(all(long), Err((1, ErrorKind::BadNumber)));
    }

    #[test]
    fn checksums_are_checked() {
        let body = "N3 T0";
        let sum = body.bytes().fold(0_u8, |x, b| x ^ b);
        let good = std::format!("{body}*{sum}");
        assert_eq!(all(&good), Ok(vec![('N', 3.0, 1), ('T', 0.0, 4)]));
        let bad = std::format!("{body}*{}", sum ^ 1);
        assert_eq!(all(&bad), Err((6, ErrorKind::BadChecksum)));
        assert_eq!(all("N3 T0*x"), Err((6, ErrorKind::BadChecksum)));
    }
}
