//! Streaming moves: the moves of a toolpath as they arrive (lines, circular arcs and helices,
//! cubic Béziers), the curvature-continuous blends that replace their corners, and the
//! stream that plans them in a look-ahead window and compiles them a stretch at a time.

mod arc_map;
mod blend;
mod committed;
mod moves;
mod queue;
mod ride;
mod segment;
mod toolpath;
mod whole;

pub use blend::{Blend, Junction, REVERSAL_ANGLE, chain_junctions, junction};
pub use moves::{Move, MoveCurve, NoCurve, Shape, StreamCurve};
pub use queue::{PieceQueue, STRETCH_PIECES, Stream, StreamOptions, StreamStats};
pub use toolpath::Toolpath;
pub use whole::plan_path_into;
