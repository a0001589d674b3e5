#![no_std]
#![doc = include_str!("../README.md")]
// Unsafe code only in the Cortex-M tick kernels (`sampler/kernel/vfp.rs`, inline assembly).
#![deny(unsafe_code)]

mod compile;
mod error;
mod limits;
mod number;
mod path;
mod profile;
mod sampler;
mod timing;

pub use compile::{CompileOptions, Tolerance, compile};
pub use error::{BlobFormat, Error, Quantity};
pub use limits::Limits;
pub use number::{Number, Q40};
pub use path::{
    AlignedBlob, AxisState, BLOB_MAGIC, BLOB_VERSION, Path, PathBlob, PathHeader, PathView, Piece,
    Sample, crc32,
};
pub use profile::*;
pub use sampler::{Sampler, SamplerState};
pub use timing::{MotionLimits, Timing};
