//! The library behind the `strak-sim` command line: curve files and sampling.
//!
//! The binary is a thin clap front end; tests call these functions directly.

pub mod builder;
pub mod curve_file;
pub mod sample;
