//! Streaming moves: the moves of a toolpath as they arrive (lines, circular arcs and helices,
//! cubic Béziers) and the curvature-continuous blends that replace their corners.

mod blend;
mod moves;
mod toolpath;

pub use blend::{Blend, Junction, REVERSAL_ANGLE, junction};
pub use moves::{Move, MoveCurve, Shape};
pub use toolpath::Toolpath;
