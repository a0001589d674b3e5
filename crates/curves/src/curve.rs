//! Capabilities shared by every curve: evaluation, derivatives and the piece structure.
//!
//! Every curve type implements the capabilities it has, so that analysis (continuity,
//! flattening, arc length), the simulator and the tests are written once against the traits.

use crate::point::Point;

/// The scalar type of a curve's points.
pub type ScalarOf<C> = <<C as ParamCurve>::Point as Point>::Scalar;

/// A parametric curve `c(u)` over a closed parameter domain `[u_start, u_end]`.
///
/// Parameters outside the domain are clamped to it: `eval(u)` for `u < u_start` is
/// `eval(u_start)`, and likewise at the end. Evaluation never panics.
///
/// A curve is made of pieces (Bézier curves and Lagrange curves have one; splines have one per
/// non-empty knot interval or node interval). Each piece is a polynomial (or a rational
/// function for NURBS) in `u`; at piece boundaries the curve is only as smooth as its
/// continuity allows.
pub trait ParamCurve {
    /// The point type.
    type Point: Point;

    /// The parameter domain `(u_start, u_end)`, with `u_start < u_end`.
    fn domain(&self) -> (ScalarOf<Self>, ScalarOf<Self>);

    /// The point `c(u)`, with `u` clamped to the domain.
    fn eval(&self, u: ScalarOf<Self>) -> Self::Point;

    /// The number of pieces (at least 1).
    fn piece_count(&self) -> usize {
        1
    }

    /// The parameter interval of piece `i`; the last piece for `i >= piece_count()`.
    fn piece_domain(&self, i: usize) -> (ScalarOf<Self>, ScalarOf<Self>) {
        let _ = i;
        self.domain()
    }
}

/// A curve with derivatives with respect to its parameter.
pub trait ParamCurveDeriv: ParamCurve {
    /// The derivative of order `k` with respect to `u` at `u` (clamped to the domain):
    /// `k = 0` is the point itself, derivatives above the polynomial degree are zero.
    ///
    /// At a piece boundary the derivative of the piece that *starts* there is returned,
    /// except at the end of the domain, where the last piece is used.
    fn deriv(&self, u: ScalarOf<Self>, k: usize) -> Self::Point;
}
