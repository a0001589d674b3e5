//! # strak-ref
//!
//! Independent `f64` textbook implementations of the curve mathematics of the lecture notes in
//! `seeds/*.txt` (bases, Bézier, Lagrange, Hermite, cubic splines, parabolic blending,
//! B-splines, NURBS). This crate exists **only to check** the fast `no_std` crate
//! `strak-curves`: every function here is written straight from the seeds' formulas (Bernstein
//! sums with binomials, Lagrange products, the Hermite matrix K⁻¹, the dense 4n×4n spline system,
//! the Cox–de Boor recursion), simple and slow on purpose, so that an error in a clever fast path
//! cannot hide behind the same error in its check.
//!
//! Points are plain `Vec<f64>` / `&[Vec<f64>]` of any dimension, so tests can feed any point type
//! after converting it to `f64` coordinates.
//!
//! Conventions shared by all piecewise curves here (they match `strak-curves`' `ParamCurve`):
//! parameters outside the domain are clamped to it; at an inner piece boundary the piece that
//! starts there is used; at the end of the domain the last piece is used (see [`find_piece`]).
//! Closed B-splines are the exception: their parameter wraps around the period.
//!
//! ```
//! use strak_ref::{bezier_point, monomial_from_bernstein};
//! // seeds/000: Bernstein coefficients (2, -2, 5, 1) in the monomial basis.
//! let a = monomial_from_bernstein(&[2.0, -2.0, 5.0, 1.0]);
//! assert!((a[3] - (-22.0)).abs() < 1e-12);
//! let p = bezier_point(&[vec![0.0], vec![1.0]], 0.25);
//! assert!((p[0] - 0.25).abs() < 1e-15);
//! ```

// Textbook index notation (a[i][j], d_i N_i) reads closer to the seeds than iterator chains.
#![allow(clippy::needless_range_loop)]

mod arc_length;
mod basis_change;
mod bernstein;
mod bezier_chain;
mod bspline;
mod closed_bspline;
mod combinatorics;
mod cubic_spline;
mod gcode_arc;
mod hermite;
mod lagrange;
mod linalg;
mod nurbs;
mod online;
mod parabolic;
mod parameterization;
mod piece;
mod poly;
mod quarter_circle;
mod vecops;

pub use arc_length::*;
pub use basis_change::*;
pub use bernstein::*;
pub use bezier_chain::*;
pub use bspline::*;
pub use closed_bspline::*;
pub use combinatorics::*;
pub use cubic_spline::*;
pub use gcode_arc::*;
pub use hermite::*;
pub use lagrange::*;
pub use linalg::*;
pub use nurbs::*;
pub use online::*;
pub use parabolic::*;
pub use parameterization::*;
pub use piece::*;
pub use poly::*;
pub use quarter_circle::*;
pub use vecops::*;
