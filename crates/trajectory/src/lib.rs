#![no_std]
#![doc = include_str!("../README.md")]
// Unsafe code only in the Cortex-M tick kernels (`sampler/kernel/vfp.rs`, inline assembly).
#![deny(unsafe_code)]

mod blob;
mod compile;
mod error;
mod limits;
mod number;
mod path;
mod profile;
mod sampler;
mod timing;

pub use blob::{BLOB_MAGIC, BLOB_VERSION, crc32};
pub use compile::{CompileOptions, Tolerance, compile};
pub use error::{Error, Quantity};
pub use limits::Limits;
pub use number::{Number, Q40};
pub use path::{AxisState, Path, Piece};
pub use profile::*;
pub use sampler::{Sample, Sampler, SamplerState};
pub use timing::{MotionLimits, Timing};
