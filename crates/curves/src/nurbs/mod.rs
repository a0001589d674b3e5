//! NURBS: rational B-splines in homogeneous coordinates, and the exact circle (seeds/004).

mod circle;
mod curve;

pub use curve::{Homogeneous, Nurbs};
