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

    /// The first three derivatives `[c′(u), c″(u), c‴(u)]`, each as
    /// [`deriv`](Self::deriv) gives it: what the curvature and the derivative of the
    /// curvature along the curve need (the Frenet–Serret apparatus; do Carmo, *Differential
    /// Geometry of Curves and Surfaces*, §1-5). A curve whose derivatives share work gives
    /// them in one pass.
    ///
    /// ```
    /// use strak_curves::{Bezier, ParamCurveDeriv};
    /// let b = Bezier::new([[0.0_f64, 0.0], [1.0, 2.0], [3.0, 3.0], [4.0, 0.0]])?;
    /// assert_eq!(b.deriv_triple(0.3), [b.deriv(0.3, 1), b.deriv(0.3, 2), b.deriv(0.3, 3)]);
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    fn deriv_triple(&self, u: ScalarOf<Self>) -> [Self::Point; 3] {
        [self.deriv(u, 1), self.deriv(u, 2), self.deriv(u, 3)]
    }
}

/// A piecewise curve that can differentiate each piece on its own closed interval, which is
/// what the left-hand limit at a piece boundary needs.
///
/// [`ParamCurveDeriv::deriv`] at an inner piece boundary returns the derivative of the piece
/// that *starts* there, so it cannot give the left limit of the piece that ends there.
/// `piece_deriv(i, u, k)` differentiates the polynomial (or rational function) of piece `i`
/// with `u` clamped to `piece_domain(i)`; at the piece's end it is the left limit.
///
/// ```
/// use strak_curves::{ParamCurve, ParamCurveDeriv, PieceDeriv};
///
/// /// |u| on [-1, 1] as a 1-D curve with two linear pieces.
/// struct Abs;
/// impl ParamCurve for Abs {
///     type Point = [f64; 1];
///     fn domain(&self) -> (f64, f64) { (-1.0, 1.0) }
///     fn eval(&self, u: f64) -> [f64; 1] { [u.clamp(-1.0, 1.0).abs()] }
///     fn piece_count(&self) -> usize { 2 }
///     fn piece_domain(&self, i: usize) -> (f64, f64) {
///         if i == 0 { (-1.0, 0.0) } else { (0.0, 1.0) }
///     }
/// }
/// impl ParamCurveDeriv for Abs {
///     fn deriv(&self, u: f64, k: usize) -> [f64; 1] {
///         self.piece_deriv(usize::from(u >= 0.0), u, k)
///     }
/// }
/// impl PieceDeriv for Abs {
///     fn piece_deriv(&self, i: usize, u: f64, k: usize) -> [f64; 1] {
///         let (a, b) = self.piece_domain(i);
///         let (u, sign) = (u.clamp(a, b), if i == 0 { -1.0 } else { 1.0 });
///         match k { 0 => [sign * u], 1 => [sign], _ => [0.0] }
///     }
/// }
/// assert_eq!(Abs.piece_deriv(0, 0.0, 1), [-1.0]); // left limit
/// assert_eq!(Abs.deriv(0.0, 1), [1.0]); // the piece starting at 0
/// ```
pub trait PieceDeriv: ParamCurveDeriv {
    /// The derivative of order `k` of piece `piece` (the last piece for
    /// `piece >= piece_count()`) at `u` clamped to that piece's interval.
    fn piece_deriv(&self, piece: usize, u: ScalarOf<Self>, k: usize) -> Self::Point;
}

/// A reference to a curve is the curve: analysis, planning and streaming take curves by
/// value where they keep them (a [`Copy`] reference then stands for a curve they borrow),
/// and `&dyn PieceDeriv<Point = P>` lets one collection hold curves of different types.
///
/// ```
/// use strak_curves::{Bezier, ParamCurve, ParamCurveDeriv, PieceDeriv};
/// let b = Bezier::new([[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]])?;
/// let r: &dyn PieceDeriv<Point = [f64; 2]> = &b;
/// assert_eq!((&b).eval(0.5), b.eval(0.5));
/// assert_eq!(r.deriv(0.5, 1), b.deriv(0.5, 1));
/// # Ok::<(), strak_curves::Error>(())
/// ```
impl<C: ParamCurve + ?Sized> ParamCurve for &C {
    type Point = C::Point;

    fn domain(&self) -> (ScalarOf<Self>, ScalarOf<Self>) {
        (**self).domain()
    }

    fn eval(&self, u: ScalarOf<Self>) -> Self::Point {
        (**self).eval(u)
    }

    fn piece_count(&self) -> usize {
        (**self).piece_count()
    }

    fn piece_domain(&self, i: usize) -> (ScalarOf<Self>, ScalarOf<Self>) {
        (**self).piece_domain(i)
    }
}

impl<C: ParamCurveDeriv + ?Sized> ParamCurveDeriv for &C {
    fn deriv(&self, u: ScalarOf<Self>, k: usize) -> Self::Point {
        (**self).deriv(u, k)
    }
}

impl<C: PieceDeriv + ?Sized> PieceDeriv for &C {
    fn piece_deriv(&self, piece: usize, u: ScalarOf<Self>, k: usize) -> Self::Point {
        (**self).piece_deriv(piece, u, k)
    }
}
