#![no_std]
#![doc = include_str!("../README.md")]
#![forbid(unsafe_code)]

mod error;
mod feed;
mod line;
mod lines;
mod program;
mod reader;
mod words;

pub use error::{ErrorKind, GcodeError};
pub use feed::Feeder;
pub use line::{Code, IGNORED_KINDS, Ignored};
pub use lines::{LineBuffer, Lines, lines};
pub use program::{FeedError, Program, Step, arrived};
pub use reader::{Action, Block, Motion, PathMode, Reader};
