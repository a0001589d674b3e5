//! NURBS: rational B-splines in homogeneous coordinates, and the exact circle (Piegl &
//! Tiller, *The NURBS Book*, 2nd ed., ch. 4 and §7.5).

mod circle;
mod curve;

pub use curve::{Homogeneous, Nurbs};
