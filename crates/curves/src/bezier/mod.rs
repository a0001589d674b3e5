//! Bézier curves (Farin, *Curves and Surfaces for CAGD*, 5th ed., ch. 3–5; Piegl & Tiller,
//! *The NURBS Book*, 2nd ed., §1.3).
//!
//! [`Bezier`] is one polynomial segment `c(t) = Σ b_i B_i^g(t)`, `t ∈ [0, 1]`, given by its
//! `N = g + 1` Bézier points, evaluated with de Casteljau's algorithm. The operations live in
//! one file each: evaluation and validation (`curve.rs`), derivatives and the hodograph
//! (`derivative.rs`), subdivision and sub-segments (`subdivide.rs`), degree elevation
//! (`elevate.rs`), conversion to and from the monomial basis (`convert.rs`), C¹/G¹ joining
//! (`join.rs`), the cubic quarter circle (`circle.rs`) and [`BezierChain`], segments joined
//! end to start (`chain.rs`).

mod chain;
mod circle;
mod convert;
mod curve;
mod derivative;
mod elevate;
mod join;
mod subdivide;

pub use chain::*;
pub use circle::*;
pub use curve::*;
