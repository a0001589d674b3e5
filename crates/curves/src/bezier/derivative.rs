//! The hodograph (derivative curve) of a Bézier curve: `c'(t) = g Σ (b_{i+1} − b_i) B_i^{g−1}(t)`
//! (Farin, *Curves and Surfaces for CAGD*, 5th ed., §4.3 "The Derivative of a Bézier Curve",
//! from `dB_{i,n}/dt = n (B_{i−1,n−1} − B_{i,n−1})`; at the ends it gives the end-tangent
//! interpolation `c'(0) = g (b_1 − b_0)`).

use super::curve::Bezier;
use crate::basis::int_scalar;
use crate::error::Error;
use crate::point::Point;

impl<P: Point, const N: usize> Bezier<P, N> {
    /// The hodograph: the derivative `c'(t)` as a Bézier curve of degree `g − 1` with the points
    /// `g (b_{i+1} − b_i)`. `M` must be `N − 1`.
    ///
    /// Its values equal [`deriv(t, 1)`](crate::ParamCurveDeriv::deriv) of this curve. The points
    /// are within range because the constructor checked every hodograph.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] when `M ≠ N − 1`; [`Error::TooFewPoints`] for a curve of degree
    /// 0 (`M = 0`: the derivative of a constant has no Bézier points of degree −1).
    ///
    /// ```
    /// use strak_curves::{Bezier, ParamCurve, ParamCurveDeriv};
    /// let c = Bezier::new([[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]])?;
    /// let h = c.hodograph::<3>()?;
    /// assert_eq!(h.control_points(), &[[3.0, 6.0], [6.0, 0.0], [3.0, -6.0]]);
    /// assert_eq!(h.eval(0.25), c.deriv(0.25, 1));
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn hodograph<const M: usize>(&self) -> Result<Bezier<P, M>, Error> {
        let g = N.saturating_sub(1);
        if M != g {
            return Err(Error::LengthMismatch {
                expected: g,
                found: M,
            });
        }
        let gs = int_scalar::<P::Scalar>(g);
        let b = self.control_points();
        let points = core::array::from_fn(|i| match (b.get(i), b.get(i + 1)) {
            (Some(&p), Some(&q)) => q.minus(p).times(gs),
            _ => P::zero(),
        });
        Bezier::new(points)
    }
}

#[cfg(test)]
mod tests {
    use crate::{Bezier, Error, I16F16, ParamCurve, ParamCurveDeriv, Scalar};

    #[test]
    fn hodograph_values_equal_the_derivative() {
        let c = Bezier::new([[2.0], [-2.0], [5.0], [1.0]]).unwrap();
        let h = c.hodograph::<3>().unwrap();
        assert_eq!(h.control_points(), &[[-12.0], [21.0], [-12.0]]);
        let h2 = h.hodograph::<2>().unwrap();
        assert_eq!(h2.control_points(), &[[66.0], [-66.0]]);
        let h3 = h2.hodograph::<1>().unwrap();
        assert_eq!(h3.control_points(), &[[-132.0]]);
        for step in 0..=10 {
            let t = step as f64 / 10.0;
            assert!((h.eval(t)[0] - c.deriv(t, 1)[0]).abs() < 1e-13);
            assert!((h2.eval(t)[0] - c.deriv(t, 2)[0]).abs() < 1e-13);
            assert!((h.deriv(t, 1)[0] - c.deriv(t, 2)[0]).abs() < 1e-13);
        }
    }

    #[test]
    fn fixed_point_hodograph_is_exact_for_integer_points() {
        let p = |x: f64| [I16F16::from_num(x)];
        let c = Bezier::new([p(2.0), p(-2.0), p(5.0), p(1.0)]).unwrap();
        let h = c.hodograph::<3>().unwrap();
        assert_eq!(
            h.control_points().map(|q| q[0].to_f64()),
            [-12.0, 21.0, -12.0]
        );
    }

    #[test]
    fn error_length_mismatch() {
        let c = Bezier::new([[0.0], [1.0], [3.0]]).unwrap();
        assert_eq!(
            c.hodograph::<3>(),
            Err(Error::LengthMismatch {
                expected: 2,
                found: 3
            })
        );
    }

    #[test]
    fn error_too_few_points_for_degree_zero() {
        let c = Bezier::new([[1.0, 2.0]]).unwrap();
        assert_eq!(
            c.hodograph::<0>(),
            Err(Error::TooFewPoints {
                required: 1,
                found: 0
            })
        );
    }
}
