#![no_std]
#![doc = include_str!("../README.md")]
#![forbid(unsafe_code)]

mod error;
mod limits;
mod timing;

pub use error::Error;
pub use limits::Limits;
pub use timing::Timing;

mod blob;
mod compile;
mod number;
mod path;
mod sampler;

pub use blob::{BLOB_MAGIC, BLOB_VERSION, crc32};
pub use compile::{CompileOptions, Tolerance, compile};
pub use number::{Number, Q40};
pub use path::{AxisState, Path, Piece};
pub use sampler::{Sample, Sampler, SamplerState};
