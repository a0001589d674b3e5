#![no_std]
#![doc = include_str!("../README.md")]
#![forbid(unsafe_code)]

mod analysis;
mod arc;
pub mod basis;
mod bezier;
mod bspline;
mod curve;
mod error;
mod interpolate;
mod nurbs;
mod point;
mod scalar;

pub use analysis::*;
pub use arc::{CircularArc, Plane, Turn};
pub use bezier::*;
pub use bspline::*;
pub use curve::{ParamCurve, ParamCurveDeriv, PieceDeriv, ScalarOf};
pub use error::Error;
pub use interpolate::*;
pub use nurbs::*;
pub use point::{MAX_DIM, Point};
pub use scalar::{I16F16, I32F32, Scalar};

/// The `fixed` crate, re-exported so that users name the same fixed-point types.
pub use fixed;
/// The `glam` crate (no_std, libm), re-exported for its vector types.
pub use glam;
/// The `heapless` crate, re-exported for the fixed-capacity vectors in the API.
pub use heapless;
