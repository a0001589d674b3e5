//! A built curve behind a trait object, so that planning and compiling are instantiated once
//! per scalar and dimension instead of once per curve type.
//!
//! The boxed curve is called through the same trait methods as the concrete type (a virtual
//! call instead of a direct one), so every value is the same bit for bit.

use std::any::Any;

use strak_curves::{ParamCurve, ParamCurveDeriv, PieceDeriv, Scalar};

use crate::builder::{CurveVisitor, visit_curve};
use crate::curve_file::{CurveFile, FieldError};
use crate::number::NumberFormat;

/// Any curve of strak-curves with points `[S; D]`, boxed.
pub struct DynCurve<S: Scalar, const D: usize>(Box<dyn PieceDeriv<Point = [S; D]>>);

impl<S: Scalar, const D: usize> std::fmt::Debug for DynCurve<S, D> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (a, b) = self.0.domain();
        write!(
            f,
            "DynCurve<{}, {D}> over [{a:?}, {b:?}], {} pieces",
            std::any::type_name::<S>(),
            self.0.piece_count()
        )
    }
}

impl<S: Scalar, const D: usize> ParamCurve for DynCurve<S, D> {
    type Point = [S; D];

    fn domain(&self) -> (S, S) {
        self.0.domain()
    }

    fn eval(&self, u: S) -> [S; D] {
        self.0.eval(u)
    }

    fn piece_count(&self) -> usize {
        self.0.piece_count()
    }

    fn piece_domain(&self, i: usize) -> (S, S) {
        self.0.piece_domain(i)
    }
}

impl<S: Scalar, const D: usize> ParamCurveDeriv for DynCurve<S, D> {
    fn deriv(&self, u: S, k: usize) -> [S; D] {
        self.0.deriv(u, k)
    }
}

impl<S: Scalar, const D: usize> PieceDeriv for DynCurve<S, D> {
    fn piece_deriv(&self, piece: usize, u: S, k: usize) -> [S; D] {
        self.0.piece_deriv(piece, u, k)
    }
}

/// The visitor that boxes the built curve as a [`DynCurve`] inside a `Box<dyn Any>`.
#[derive(Debug, Clone, Copy)]
struct BoxDyn;

impl CurveVisitor for BoxDyn {
    type Output = Box<dyn Any>;

    fn visit<S, const D: usize, C>(self, curve: Box<C>) -> Self::Output
    where
        S: Scalar,
        C: PieceDeriv<Point = [S; D]> + 'static,
    {
        Box::new(DynCurve::<S, D>(curve))
    }
}

/// Builds the curve of `file` in the number format `number`, whose scalar must be `S`
/// (`f64`, `f32`, `I32F32` for [`NumberFormat::F64`], [`NumberFormat::F32`], [`NumberFormat::Q40`]) with `D`
/// coordinates per point.
///
/// # Errors
/// The builder's error for a bad file; a [`FieldError`] on `points` when `S` or `D` do not
/// match `number` and the file (a bug of the caller).
pub fn build_dyn<S: Scalar, const D: usize>(
    file: &CurveFile,
    number: NumberFormat,
) -> Result<DynCurve<S, D>, FieldError> {
    let any = visit_curve(file, number, BoxDyn)?;
    any.downcast::<DynCurve<S, D>>()
        .map(|b| *b)
        .map_err(|_| FieldError::new("points", format!("expected {D} coordinates per point")))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn boxed_curve_evaluates_like_the_file() {
        let file =
            CurveFile::parse("kind = \"bezier\"\npoints = [[0.0, 0.0], [2.0, 4.0]]").unwrap();
        let c: DynCurve<f64, 2> = build_dyn(&file, NumberFormat::F64).unwrap();
        assert_eq!(c.domain(), (0.0, 1.0));
        assert_eq!(c.eval(0.25), [0.5, 1.0]);
        assert_eq!(c.deriv(0.5, 1), [2.0, 4.0]);
        assert_eq!(c.piece_deriv(0, 1.0, 0), [2.0, 4.0]);
        let f: DynCurve<f32, 2> = build_dyn(&file, NumberFormat::F32).unwrap();
        assert_eq!(f.eval(0.5), [1.0, 2.0]);
        // the wrong dimension or scalar is an error, not a panic
        assert!(build_dyn::<f64, 3>(&file, NumberFormat::F64).is_err());
        assert!(build_dyn::<f32, 2>(&file, NumberFormat::F64).is_err());
    }

    #[test]
    fn boxed_bezier_chain_keeps_its_pieces() {
        let file = CurveFile::parse(
            "kind = \"bezier-chain\"\ndegree = 1\npoints = [[0.0, 0.0], [2.0, 4.0], [3.0, 4.0]]",
        )
        .unwrap();
        let c: DynCurve<f64, 2> = build_dyn(&file, NumberFormat::F64).unwrap();
        assert_eq!(c.domain(), (0.0, 2.0));
        assert_eq!(c.piece_count(), 2);
        assert_eq!(c.piece_domain(1), (1.0, 2.0));
        assert_eq!(c.eval(1.5), [2.5, 4.0]);
        // at the join: the segment starting there, and the left-hand limit of the one ending
        assert_eq!(c.deriv(1.0, 1), [1.0, 0.0]);
        assert_eq!(c.piece_deriv(0, 1.0, 1), [2.0, 4.0]);
        let q: DynCurve<strak_curves::I32F32, 2> = build_dyn(&file, NumberFormat::Q40).unwrap();
        assert_eq!(q.piece_count(), 2);
    }
}
