//! A borrowed curve behind a trait object, so that the checks and the analysis are
//! instantiated once per point type instead of once per curve type (every call goes
//! through the same trait methods, so every value is the same).

use strak_curves::{ParamCurve, ParamCurveDeriv, PieceDeriv, Point};

/// Any curve with points `P`, borrowed.
#[derive(Clone, Copy)]
pub struct Dyn<'a, P: Point>(pub &'a dyn PieceDeriv<Point = P>);

impl<P: Point> std::fmt::Debug for Dyn<'_, P> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Dyn({:?})", self.0.domain())
    }
}

impl<P: Point> ParamCurve for Dyn<'_, P> {
    type Point = P;

    fn domain(&self) -> (P::Scalar, P::Scalar) {
        self.0.domain()
    }

    fn eval(&self, u: P::Scalar) -> P {
        self.0.eval(u)
    }

    fn piece_count(&self) -> usize {
        self.0.piece_count()
    }

    fn piece_domain(&self, i: usize) -> (P::Scalar, P::Scalar) {
        self.0.piece_domain(i)
    }
}

impl<P: Point> ParamCurveDeriv for Dyn<'_, P> {
    fn deriv(&self, u: P::Scalar, k: usize) -> P {
        self.0.deriv(u, k)
    }
}

impl<P: Point> PieceDeriv for Dyn<'_, P> {
    fn piece_deriv(&self, piece: usize, u: P::Scalar, k: usize) -> P {
        self.0.piece_deriv(piece, u, k)
    }
}
