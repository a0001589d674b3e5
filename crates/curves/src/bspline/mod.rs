//! B-splines (Piegl & Tiller, *The NURBS Book*, 2nd ed., ch. 2, 3 and 5; de Boor, *A
//! Practical Guide to Splines*, ch. IX–XI): knot vectors,
//! the Cox–de Boor basis, the curve with de Boor evaluation and derivatives, knot insertion and
//! conversion to Bézier segments.

mod basis;
mod bezier;
mod curve;
mod derivative;
mod insert;
mod knots;
mod power;

pub use basis::{basis_function, bspline_basis, bspline_basis_derivs};
pub use curve::BSpline;
pub use knots::{BSPLINE_MAX_DEGREE, KnotVector};
pub use power::PowerSpline;

pub(crate) use derivative::{local_coords, span_coord_bounds};
pub(crate) use knots::{LOCAL, ratio};
