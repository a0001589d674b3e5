//! `strak-sim sample`: evaluate a curve at evenly spaced parameters and write CSV.
//!
//! The curve comes from [`build_curve`] (curve file → [`builder`](crate::builder) → here):
//! this module uses the builder, never the other way round.

use std::fmt::Write as _;

use crate::builder::build_curve;
use crate::curve_file::{CurveFile, FieldError};
pub use crate::number::{FixedScalar, NumberFormat};

/// What to sample.
#[derive(Clone, Copy, Debug)]
pub struct SampleOptions {
    /// Number of parameter values (at least 2), first and last of the domain included.
    pub count: usize,
    /// Number of derivatives after the point.
    pub derivatives: usize,
    /// Number format.
    pub number: NumberFormat,
}

/// The evenly spaced parameters over `[a, b]`, first and last exactly `a` and `b`.
pub fn parameters(a: f64, b: f64, count: usize) -> Vec<f64> {
    let last = count.saturating_sub(1).max(1);
    (0..count)
        .map(|i| {
            if i == last {
                b
            } else {
                a + (b - a) * (i as f64 / last as f64)
            }
        })
        .collect()
}

/// The CSV header: `u,x,y[,z[,w[,x5[,x6]]]]` then `d1x,d1y,…` up to `dKx,…`.
pub fn header(dim: usize, derivatives: usize) -> Vec<String> {
    let mut h = vec!["u".to_owned()];
    for k in 0..=derivatives {
        for axis in crate::axes::names(dim) {
            h.push(if k == 0 {
                (*axis).to_owned()
            } else {
                format!("d{k}{axis}")
            });
        }
    }
    h
}

/// Builds the curve in the requested number format and samples it into rows
/// (`u`, point, derivatives), all as `f64`.
pub fn sample_rows(file: &CurveFile, options: &SampleOptions) -> Result<Vec<Vec<f64>>, FieldError> {
    let curve = build_curve(file, options.number)?;
    let (a, b) = curve.domain_f64();
    let rows = parameters(a, b, options.count)
        .into_iter()
        .map(|u| {
            let mut row = vec![curve.param(u)];
            for k in 0..=options.derivatives {
                curve.push_deriv(u, k, &mut row);
            }
            row
        })
        .collect();
    Ok(rows)
}

/// Samples the curve and renders the CSV text.
pub fn sample_to_csv(file: &CurveFile, options: &SampleOptions) -> Result<String, FieldError> {
    let rows = sample_rows(file, options)?;
    let mut writer = csv::Writer::from_writer(Vec::new());
    let io = |e: csv::Error| FieldError::new("out", e.to_string());
    writer
        .write_record(header(file.dim(), options.derivatives))
        .map_err(io)?;
    let mut cell = String::new();
    for row in &rows {
        let cells: Vec<String> = row
            .iter()
            .map(|v| {
                cell.clear();
                // Rust's shortest round-trip formatting: the value is read back exactly.
                let _ = write!(cell, "{v:?}");
                cell.clone()
            })
            .collect();
        writer.write_record(&cells).map_err(io)?;
    }
    let bytes = writer
        .into_inner()
        .map_err(|e| FieldError::new("out", e.to_string()))?;
    String::from_utf8(bytes).map_err(|e| FieldError::new("out", e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parameters_include_both_ends() {
        let p = parameters(0.25, 4.0, 4);
        assert_eq!(p, vec![0.25, 1.5, 2.75, 4.0]);
    }

    #[test]
    fn header_names_coordinates_and_derivatives() {
        assert_eq!(header(2, 1), ["u", "x", "y", "d1x", "d1y"]);
        assert_eq!(header(3, 0), ["u", "x", "y", "z"]);
        assert_eq!(header(1, 2), ["u", "x", "d1x", "d2x"]);
        assert_eq!(header(6, 0)[4..], ["w", "x5", "x6"]);
    }
}
