//! Degree elevation: the same curve with one more Bézier point (Farin, *Curves and Surfaces
//! for CAGD*, 5th ed., §5.1 "Degree Elevation"; Piegl & Tiller, *The NURBS Book*, 2nd ed.,
//! §5.5). It brings segments of different degree to one degree before they are joined.

use super::curve::Bezier;
use crate::error::Error;
use crate::point::Point;
use crate::scalar::Scalar;

impl<P: Point, const N: usize> Bezier<P, N> {
    /// The same curve as a Bézier curve of degree `g + 1` (`M = N + 1` points):
    /// `c_0 = b_0`, `c_i = (i/(g+1)) b_{i−1} + (1 − i/(g+1)) b_i`, `c_{g+1} = b_g`.
    ///
    /// The weights `i/(g+1)` are rounded once to the scalar type; the new points are convex
    /// combinations of neighbouring points.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] when `M ≠ N + 1`; [`Error::DegreeTooHigh`] when `g + 1`
    /// exceeds [`basis::MAX_DEGREE`](crate::basis::MAX_DEGREE); [`Error::OutOfRange`] when the
    /// elevated curve's range check fails: the rounded weights can push a derivative bound
    /// that sat at the limit of a fixed-point type just past it.
    ///
    /// ```
    /// use strak_curves::{Bezier, ParamCurve};
    /// let c = Bezier::new([[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]])?;
    /// let e = c.elevate::<5>()?;
    /// assert_eq!(e.control_points(), &[[0.0, 0.0], [0.75, 1.5], [2.0, 2.0], [3.25, 1.5], [4.0, 0.0]]);
    /// assert_eq!(e.eval(0.5), c.eval(0.5));
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn elevate<const M: usize>(&self) -> Result<Bezier<P, M>, Error> {
        if M != N + 1 {
            return Err(Error::LengthMismatch {
                expected: N + 1,
                found: M,
            });
        }
        let b = self.control_points();
        let points = core::array::from_fn(|i| {
            let alpha = P::Scalar::from_f64(i as f64 / N as f64).unwrap_or(P::Scalar::ZERO);
            match (i.checked_sub(1).and_then(|j| b.get(j)), b.get(i)) {
                (Some(&prev), Some(&cur)) => cur.lerp(prev, alpha),
                (None, Some(&cur)) => cur,
                (Some(&prev), None) => prev,
                (None, None) => P::zero(),
            }
        });
        Bezier::new(points)
    }
}

#[cfg(test)]
mod tests {
    use crate::{Bezier, Error, I16F16, I32F32, ParamCurve, ParamCurveDeriv, Scalar};
    use glam::DVec2;

    #[test]
    fn elevation_preserves_the_curve() {
        let c = Bezier::new([
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 3.0),
            DVec2::new(2.5, -1.0),
            DVec2::new(4.0, 2.0),
        ])
        .unwrap();
        let e = c.elevate::<5>().unwrap();
        let e2 = e.elevate::<6>().unwrap();
        assert_eq!(e.degree(), 4);
        for step in 0..=20 {
            let t = step as f64 / 20.0;
            assert!((e.eval(t) - c.eval(t)).length() < 1e-14);
            assert!((e2.eval(t) - c.eval(t)).length() < 1e-14);
            for k in 1..=3 {
                assert!((e.deriv(t, k) - c.deriv(t, k)).length() < 1e-11, "k={k}");
            }
            assert!(e.deriv(t, 4).length() < 1e-11);
        }
        // a line elevated stays evenly spaced
        let l = Bezier::new([[0.0], [3.0]]).unwrap();
        assert_eq!(
            l.elevate::<3>().unwrap().control_points(),
            &[[0.0], [1.5], [3.0]]
        );
        let k = Bezier::new([[2.0]]).unwrap();
        assert_eq!(k.elevate::<2>().unwrap().control_points(), &[[2.0], [2.0]]);
    }

    #[test]
    fn fixed_point_elevation_agrees_with_f64() {
        let q = [[0.0, 0.0], [1.0, 3.0], [2.5, -1.0], [4.0, 2.0]];
        let cf = Bezier::new(q).unwrap().elevate::<5>().unwrap();
        let cx = Bezier::new(q.map(|p| p.map(I16F16::from_num)))
            .unwrap()
            .elevate::<5>()
            .unwrap();
        let cy = Bezier::new(q.map(|p| p.map(I32F32::from_num)))
            .unwrap()
            .elevate::<5>()
            .unwrap();
        for i in 0..5 {
            for d in 0..2 {
                let r = cf.control_points()[i][d];
                assert!(
                    (cx.control_points()[i][d].to_f64() - r).abs()
                        < 4.0 * <I16F16 as Scalar>::EPSILON
                );
                assert!(
                    (cy.control_points()[i][d].to_f64() - r).abs()
                        < 4.0 * <I32F32 as Scalar>::EPSILON
                );
            }
        }
    }

    #[test]
    fn error_length_mismatch() {
        let c = Bezier::new([[0.0], [1.0], [3.0]]).unwrap();
        assert_eq!(
            c.elevate::<5>(),
            Err(Error::LengthMismatch {
                expected: 4,
                found: 5
            })
        );
        assert_eq!(
            c.elevate::<3>(),
            Err(Error::LengthMismatch {
                expected: 4,
                found: 3
            })
        );
    }
}
