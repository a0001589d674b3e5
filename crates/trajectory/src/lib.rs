#![no_std]
#![doc = include_str!("../README.md")]
#![forbid(unsafe_code)]

mod error;
mod limits;
mod timing;

pub use error::Error;
pub use limits::Limits;
pub use timing::Timing;
mod profile;
pub use profile::*;
