//! The number formats as strak-sim names them: the library's [`NumberFormat`], read from a
//! job file's `number` and from `--number` by [`parse`].
//!
//! strak-sim names a format as the library does (`f64`, `f32`, `Q40`) and accepts `fixed`
//! for [`NumberFormat::Q40`]: the curve built in [`FixedScalar`] (`I32F32`), played back in
//! `Q40`, its samples in `I32F32`. [`name`] is the name strak-sim writes (`fixed` for `Q40`,
//! the name job files use).

use serde::{Deserialize, Deserializer};
use strak_curves::I32F32;
pub use strak_trajectory::NumberFormat;

/// The fixed-point type a curve is built in for [`NumberFormat::Q40`] (`--number fixed`).
pub type FixedScalar = I32F32;

/// The name strak-sim writes for `format`: `fixed` for `Q40`, the library's name otherwise.
///
/// ```
/// use strak_sim::number::{NumberFormat, name};
/// assert_eq!(name(NumberFormat::Q40), "fixed");
/// assert_eq!(name(NumberFormat::F32), "f32");
/// ```
pub fn name(format: NumberFormat) -> &'static str {
    match format {
        NumberFormat::Q40 => "fixed",
        other => other.name(),
    }
}

/// The format named `s`: a name of [`name`] or of [`NumberFormat`]'s `FromStr`.
///
/// # Errors
/// A message listing the names, for any other `s`.
///
/// ```
/// use strak_sim::number::{NumberFormat, parse};
/// assert_eq!(parse("fixed"), Ok(NumberFormat::Q40));
/// assert_eq!(parse("Q40"), Ok(NumberFormat::Q40));
/// assert_eq!(parse("f64"), Ok(NumberFormat::F64));
/// assert!(parse("f16").unwrap_err().contains("f64, f32 or fixed"));
/// ```
pub fn parse(s: &str) -> Result<NumberFormat, String> {
    NumberFormat::ALL
        .into_iter()
        .find(|&f| name(f) == s)
        .map_or_else(|| s.parse::<NumberFormat>().ok(), Some)
        .ok_or_else(|| format!("unknown number format `{s}` (expected f64, f32 or fixed)"))
}

/// Deserializes a format by [`parse`] (`#[serde(deserialize_with = "number::deserialize")]`).
///
/// # Errors
/// The message of [`parse`] as the deserializer's error.
pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<NumberFormat, D::Error> {
    let s = String::deserialize(d)?;
    parse(&s).map_err(serde::de::Error::custom)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_format_reads_back_from_both_names() {
        for f in NumberFormat::ALL {
            assert_eq!(parse(name(f)), Ok(f));
            assert_eq!(parse(f.name()), Ok(f));
        }
        for bad in ["", "F64", "q40", "I32F32", "fixed "] {
            assert!(parse(bad).is_err(), "{bad:?}");
        }
    }

    #[test]
    fn a_job_field_reads_through_parse() {
        #[derive(Deserialize)]
        struct Field {
            #[serde(deserialize_with = "deserialize")]
            number: NumberFormat,
        }
        let f: Field = toml::from_str("number = \"fixed\"").unwrap();
        assert_eq!(f.number, NumberFormat::Q40);
        let e = toml::from_str::<Field>("number = \"f16\"").err().unwrap();
        assert!(e.to_string().contains("unknown number format `f16`"), "{e}");
    }
}
