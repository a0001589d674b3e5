//! The library behind the `strak-sim` command line: curve files and sampling
//! (`strak-sim sample`), job files and playback (`strak-sim run`: a curve, or moves
//! streamed through the look-ahead planner), G-code programs played on a machine
//! (`strak-sim gcode`).
//!
//! The binary is a thin clap front end; tests call these functions directly.

pub mod axes;
pub mod builder;
pub mod curve_file;
pub mod dyn_curve;
pub mod export;
pub mod gcode_run;
pub mod job;
pub mod line;
pub mod machine;
pub mod measure;
pub mod moves;
pub mod number;
pub mod online_move;
pub mod pipeline;
pub mod plot;
pub mod programmed;
pub mod run;
pub mod sample;
pub mod schedule;
pub mod stream_run;
pub mod summary;
pub mod toml_error;
