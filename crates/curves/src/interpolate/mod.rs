//! Interpolating curves: Lagrange curves, Hermite splines (with Catmull-Rom and cardinal
//! tangents), parabolic blending and interpolating cubic splines, plus the interpolation
//! nodes (parameterizations) and the tridiagonal solvers they need.

mod catmull_rom;
mod cubic_spline;
mod hermite;
mod lagrange;
mod parabolic;
mod parameterization;
mod tridiagonal;

pub use cubic_spline::{CubicSpline, SplineBoundary};
pub use hermite::{HermiteSegment, HermiteSpline};
pub use lagrange::LagrangeCurve;
pub use parabolic::ParabolicBlend;
pub use parameterization::{NodeSource, Parameterization, validate_interpolation_nodes};
pub use tridiagonal::{solve_cyclic_tridiagonal, solve_tridiagonal};
