#![no_std]
#![doc = include_str!("../README.md")]
// Unsafe code only in the Cortex-M tick kernels (`play/kernel/vfp.rs`, inline assembly).
#![deny(unsafe_code)]

// The layers, in the order data flows through them: each names only the layers before it
// (checked by `tests/layering.rs`).
mod compile;
mod error;
mod num;
mod online;
mod path;
mod plan;
mod play;
mod stream;

pub use compile::{
    CompileOptions, Stretches, Tolerance, compile, compile_into, compile_move, compile_move_into,
    take_over_into,
};
pub use error::{BlobFormat, Error, Quantity, Units};
pub use num::{LIMIT_CHECK_RELATIVE, Number, NumberFormat, ParseNumberFormatError, Q40};
pub use online::{
    AxisLimits, AxisProfile, Block, Interface, JerkPhase, Kinematics, MAX_PHASES, MoveOptions,
    OnlineMove, Real, Synchronization, solve_axis, solve_axis_velocity,
};
pub use path::{
    AlignedBlob, AxisState, BLOB_MAGIC, BLOB_VERSION, END_AGREEMENT_SLACK, Path, PathBlob,
    PathHeader, PathView, Piece, Sample, crc32,
};
pub use plan::*;
pub use play::events::{Event, EventPlayer, Playable, RunEnd, TimedEvent};
pub use play::guard::{FeedGuard, MAX_DELAY, MAX_RAMP_TICKS, Schedule};
pub use play::{Kernel, Sampler, SamplerState, StreamSampler};
pub use stream::{
    Blend, Junction, Move, MoveCurve, NoCurve, PieceQueue, REVERSAL_ANGLE, STRETCH_PIECES, Shape,
    Stream, StreamCurve, StreamOptions, StreamStats, Toolpath, chain_junctions, junction,
    plan_path_into,
};
