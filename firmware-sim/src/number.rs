//! The number formats a curve file is built and evaluated in (`--number` of
//! `strak-sim sample`; a job's `number` picks its curve format through
//! [`JobNumber::curve_number`](crate::job::JobNumber::curve_number)).

use strak_curves::I32F32;

/// The number format a curve is built and evaluated in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Number {
    /// IEEE 754 double precision.
    F64,
    /// IEEE 754 single precision.
    F32,
    /// Fixed-point `I32F32` (Q31.32: range ±2³¹, resolution 2⁻³²).
    Fixed,
}

/// The fixed-point type behind `--number fixed`.
pub type FixedScalar = I32F32;
