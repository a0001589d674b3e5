//! The number formats as a value: what a blob's header records, what a command line names.

use core::fmt;
use core::str::FromStr;

/// The number format of a path's playback, as a value: `f32`, `f64` or
/// [`Q40`](crate::Q40) ([`Number::FORMAT`](crate::Number::FORMAT) of each type).
///
/// Its id byte is what a serialized path records ([`NumberFormat::id`]); its name
/// ([`Display`](fmt::Display)) is what [`FromStr`] reads back.
///
/// ```
/// use strak_trajectory::{Number, NumberFormat, Q40};
///
/// assert_eq!(<Q40 as Number>::FORMAT, NumberFormat::Q40);
/// assert_eq!(NumberFormat::Q40.id(), 3);
/// assert_eq!(NumberFormat::from_id(1), Some(NumberFormat::F32));
/// assert_eq!(NumberFormat::F64.to_string(), "f64");
/// assert_eq!("Q40".parse::<NumberFormat>(), Ok(NumberFormat::Q40));
/// assert!("q23.40".parse::<NumberFormat>().is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum NumberFormat {
    /// IEEE binary32 (`f32`).
    F32,
    /// IEEE binary64 (`f64`).
    F64,
    /// The fixed-point accumulator [`Q40`](crate::Q40) (Q23.40 in an `i64`).
    Q40,
}

impl NumberFormat {
    /// Every format, in the order of their ids.
    pub const ALL: [NumberFormat; 3] = [NumberFormat::F32, NumberFormat::F64, NumberFormat::Q40];

    /// The id byte a serialized path records: 1 `f32`, 2 `f64`, 3 `Q40`.
    ///
    /// ```
    /// use strak_trajectory::NumberFormat;
    /// assert_eq!(NumberFormat::F32.id(), 1);
    /// ```
    pub const fn id(self) -> u8 {
        match self {
            NumberFormat::F32 => 1,
            NumberFormat::F64 => 2,
            NumberFormat::Q40 => 3,
        }
    }

    /// The format with the id byte `id`, or `None` when no format has it.
    ///
    /// ```
    /// use strak_trajectory::NumberFormat;
    /// assert_eq!(NumberFormat::from_id(3), Some(NumberFormat::Q40));
    /// assert_eq!(NumberFormat::from_id(9), None);
    /// ```
    pub const fn from_id(id: u8) -> Option<Self> {
        match id {
            1 => Some(NumberFormat::F32),
            2 => Some(NumberFormat::F64),
            3 => Some(NumberFormat::Q40),
            _ => None,
        }
    }

    /// The name: `"f32"`, `"f64"`, `"Q40"`.
    ///
    /// ```
    /// use strak_trajectory::NumberFormat;
    /// assert_eq!(NumberFormat::Q40.name(), "Q40");
    /// ```
    pub const fn name(self) -> &'static str {
        match self {
            NumberFormat::F32 => "f32",
            NumberFormat::F64 => "f64",
            NumberFormat::Q40 => "Q40",
        }
    }

    /// Bytes per value in a serialized path: 4 for `f32`, 8 otherwise.
    ///
    /// ```
    /// use strak_trajectory::NumberFormat;
    /// assert_eq!(NumberFormat::F32.bytes(), 4);
    /// ```
    pub const fn bytes(self) -> usize {
        match self {
            NumberFormat::F32 => 4,
            NumberFormat::F64 | NumberFormat::Q40 => 8,
        }
    }

    /// The resolution `u(M)` of a sample value of magnitude `magnitude`: the spacing of the
    /// sampler's output type there (`M·2⁻⁵²` in `f64`, `M·2⁻²³` in `f32`, `2⁻³²` for the
    /// `I32F32` samples of `Q40`). Two samples of a motion differ by up to `2·u(M)` more than
    /// the motion does, which a check of their finite differences allows.
    ///
    /// ```
    /// use strak_trajectory::NumberFormat;
    /// assert_eq!(NumberFormat::F32.sample_resolution(1.0), f64::from(f32::EPSILON));
    /// assert_eq!(NumberFormat::Q40.sample_resolution(1e6), 2f64.powi(-32));
    /// ```
    pub fn sample_resolution(self, magnitude: f64) -> f64 {
        match self {
            NumberFormat::F64 => magnitude * f64::EPSILON,
            NumberFormat::F32 => magnitude * f64::from(f32::EPSILON),
            NumberFormat::Q40 => libm::ldexp(1.0, -32),
        }
    }

    /// The rounding a limit check allows a finite difference `(y₁ − y₀)·rate` of two samples
    /// of magnitude at most `magnitude` on one axis: `2·u(M)·rate` (see
    /// [`sample_resolution`](Self::sample_resolution)); a norm over `D` axes allows `√D`
    /// times this. A check passes when the difference is at most
    /// `L·(1 + LIMIT_CHECK_RELATIVE)` plus this.
    ///
    /// ```
    /// use strak_trajectory::NumberFormat;
    /// let allowance = NumberFormat::Q40.difference_allowance(5.0, 1_000.0);
    /// assert_eq!(allowance, 2.0 * 2f64.powi(-32) * 1_000.0);
    /// ```
    pub fn difference_allowance(self, magnitude: f64, rate: f64) -> f64 {
        2.0 * self.sample_resolution(magnitude) * rate
    }
}

/// The relative tolerance of a limit check of samples: the rounding of its own `f64`
/// arithmetic (see [`NumberFormat::difference_allowance`]).
///
/// ```
/// assert!(strak_trajectory::LIMIT_CHECK_RELATIVE < 1e-6);
/// ```
pub const LIMIT_CHECK_RELATIVE: f64 = 1e-9;

impl fmt::Display for NumberFormat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A name that is not one of a [`NumberFormat`]'s (`f32`, `f64`, `Q40`).
///
/// ```
/// use strak_trajectory::{NumberFormat, ParseNumberFormatError};
/// let e = "f16".parse::<NumberFormat>().unwrap_err();
/// assert_eq!(e, ParseNumberFormatError);
/// assert_eq!(e.to_string(), "unknown number format (expected f32, f64 or Q40)");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ParseNumberFormatError;

impl fmt::Display for ParseNumberFormatError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("unknown number format (expected f32, f64 or Q40)")
    }
}

impl core::error::Error for ParseNumberFormatError {}

impl FromStr for NumberFormat {
    type Err = ParseNumberFormatError;

    /// The format named `s`: exactly a name [`Display`](fmt::Display) writes.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        NumberFormat::ALL
            .into_iter()
            .find(|f| f.name() == s)
            .ok_or(ParseNumberFormatError)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use std::string::ToString;

    use super::*;

    #[test]
    fn ids_names_and_parsing_round_trip() {
        for (i, f) in NumberFormat::ALL.into_iter().enumerate() {
            assert_eq!(usize::from(f.id()), i + 1);
            assert_eq!(NumberFormat::from_id(f.id()), Some(f));
            assert_eq!(f.to_string().parse::<NumberFormat>(), Ok(f));
        }
        for id in [0, 4, 255] {
            assert_eq!(NumberFormat::from_id(id), None);
        }
        for bad in ["", "F32", "q40", "f32 ", "fixed"] {
            assert_eq!(
                bad.parse::<NumberFormat>(),
                Err(ParseNumberFormatError),
                "{bad:?}"
            );
        }
    }
}
