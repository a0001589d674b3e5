//! Conversion between Bézier points and monomial coefficients, `a⃗ = T_{M←B} b⃗` and
//! `b⃗ = T_{B←M} a⃗` (Farin, *Curves and Surfaces for CAGD*, 5th ed., §4.8; the matrices and
//! their derivation are in the [`basis`](crate::basis) module docs).

use super::curve::Bezier;
use crate::basis::{MonomialCurve, binomial_f64};
use crate::basis::{bernstein_to_monomial_f64, map_coordinates, monomial_to_bernstein_f64};
use crate::curve::ParamCurve;
use crate::error::Error;
use crate::point::Point;
use crate::scalar::Scalar;

impl<P: Point, const N: usize> Bezier<P, N> {
    /// The same polynomial in the monomial basis over `[0, 1]`: coefficients
    /// `a⃗ = T_{M←B} b⃗`, `a_j = C(g, j) Δʲ b_0` (computed in `f64`, rounded once).
    ///
    /// Horner evaluation of the result is faster than de Casteljau but not a convex
    /// combination: prefer it where speed matters and the range allows.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] when a coefficient or a Horner intermediate of the monomial curve
    /// does not fit the scalar type (monomial coefficients grow like `2^g · max |b_i|`).
    ///
    /// ```
    /// use strak_curves::Bezier;
    /// // (2, −2, 5, 1) ↦ 2 − 12t + 33t² − 22t³
    /// let m = Bezier::new([[2.0], [-2.0], [5.0], [1.0]])?.to_monomial()?;
    /// assert_eq!(m.coefficients(), &[[2.0], [-12.0], [33.0], [-22.0]]);
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn to_monomial(&self) -> Result<MonomialCurve<P, N>, Error> {
        let a = map_coordinates(self.control_points(), bernstein_to_monomial_f64)?;
        MonomialCurve::new(a)
    }

    /// The Bézier curve of a monomial curve. For a domain `[u_0, u_1]` other than `[0, 1]` the
    /// result is reparameterized to `[0, 1]`: `b(s) = m(u_0 + s (u_1 − u_0))`. The shift and
    /// scaling `c_j = Σ_{i≥j} a_i C(i, j) u_0^{i−j} (u_1 − u_0)ʲ` and `b⃗ = T_{B←M} c⃗` are
    /// computed in `f64` and rounded once.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] when a Bézier point or a derivative bound does not fit the scalar
    /// type (see [`Bezier::new`]).
    ///
    /// ```
    /// use strak_curves::{Bezier, basis::MonomialCurve};
    /// let m = MonomialCurve::new([[2.0], [-12.0], [33.0], [-22.0]])?;
    /// let b = Bezier::from_monomial(&m)?;
    /// assert_eq!(b.control_points(), &[[2.0], [-2.0], [5.0], [1.0]]);
    /// // u² on [1, 3] becomes (1 + 2s)²: Bézier points 1, 3, 9
    /// let sq = MonomialCurve::with_domain([[0.0], [0.0], [1.0]], 1.0, 3.0)?;
    /// assert_eq!(Bezier::from_monomial(&sq)?.control_points(), &[[1.0], [3.0], [9.0]]);
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn from_monomial(m: &MonomialCurve<P, N>) -> Result<Self, Error> {
        let (start, end) = m.domain();
        let u0 = start.to_f64();
        let du = end.to_f64() - u0;
        let points = map_coordinates(m.coefficients(), |a: &[f64; N]| {
            let c: [f64; N] = core::array::from_fn(|j| {
                let mut v = 0.0;
                for (i, &ai) in a.iter().enumerate().skip(j) {
                    v += ai * binomial_f64(i, j) * powi(u0, i - j) * powi(du, j);
                }
                v
            });
            monomial_to_bernstein_f64(&c)
        })?;
        Self::new(points)
    }
}

/// `xⁿ` by repeated multiplication (`x⁰ = 1`, also for `x = 0`).
fn powi(x: f64, n: usize) -> f64 {
    let mut r = 1.0;
    for _ in 0..n {
        r *= x;
    }
    r
}

#[cfg(test)]
mod tests {
    use crate::basis::MonomialCurve;
    use crate::{Bezier, Error, I16F16, I32F32, ParamCurve, ParamCurveDeriv, Scalar};
    use glam::DVec2;

    #[test]
    fn worked_example_round_trip() {
        let b = Bezier::new([[2.0], [-2.0], [5.0], [1.0]]).unwrap();
        let m = b.to_monomial().unwrap();
        assert_eq!(m.coefficients(), &[[2.0], [-12.0], [33.0], [-22.0]]);
        assert_eq!(Bezier::from_monomial(&m).unwrap(), b);
    }

    #[test]
    fn monomial_curve_evaluates_like_the_bezier_curve() {
        let b = Bezier::new([
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 3.0),
            DVec2::new(2.5, -1.0),
            DVec2::new(4.0, 2.0),
            DVec2::new(5.0, 0.5),
        ])
        .unwrap();
        let m = b.to_monomial().unwrap();
        for step in 0..=16 {
            let t = step as f64 / 16.0;
            for k in 0..=5 {
                assert!(
                    (m.deriv(t, k) - b.deriv(t, k)).length() < 1e-11,
                    "k={k} t={t}"
                );
            }
        }
        let back = Bezier::from_monomial(&m).unwrap();
        for (p, q) in back.control_points().iter().zip(b.control_points()) {
            assert!((*p - *q).length() < 1e-13);
        }
    }

    #[test]
    fn domain_is_reparameterized() {
        let m = MonomialCurve::with_domain(
            [
                DVec2::new(1.0, 0.0),
                DVec2::new(-2.0, 1.0),
                DVec2::new(0.5, 0.25),
            ],
            -1.0,
            2.0,
        )
        .unwrap();
        let b = Bezier::from_monomial(&m).unwrap();
        for step in 0..=8 {
            let s = step as f64 / 8.0;
            assert!((b.eval(s) - m.eval(-1.0 + 3.0 * s)).length() < 1e-13);
        }
    }

    #[test]
    fn fixed_point_conversion_agrees_with_f64() {
        let q = [[0.0, 0.0], [1.0, 3.0], [2.5, -1.0], [4.0, 2.0]];
        let mf = Bezier::new(q).unwrap().to_monomial().unwrap();
        let mx = Bezier::new(q.map(|p| p.map(I16F16::from_num)))
            .unwrap()
            .to_monomial()
            .unwrap();
        let my = Bezier::new(q.map(|p| p.map(I32F32::from_num)))
            .unwrap()
            .to_monomial()
            .unwrap();
        // integer arithmetic on representable inputs: exact
        for i in 0..4 {
            for d in 0..2 {
                assert_eq!(mx.coefficients()[i][d].to_f64(), mf.coefficients()[i][d]);
                assert_eq!(my.coefficients()[i][d].to_f64(), mf.coefficients()[i][d]);
            }
        }
        let back = Bezier::from_monomial(&mx).unwrap();
        assert_eq!(back.control_points()[2][0], I16F16::from_num(2.5));
    }

    #[test]
    fn error_out_of_range() {
        // b = (0, x, 0, x): the Bézier bounds are x, 3x, 12x, 24x; the monomial
        // coefficients (0, 3x, −6x, 4x) give the Horner bound 36x for the second derivative
        let p = |x: f64| [I16F16::from_num(x)];
        let b = Bezier::new([p(0.0), p(5000.0), p(0.0), p(5000.0)]);
        assert_eq!(b, Err(Error::OutOfRange));
        let b = Bezier::new([p(0.0), p(500.0), p(0.0), p(500.0)]).unwrap();
        assert_eq!(b.to_monomial(), Err(Error::OutOfRange));
        // a monomial curve whose Bézier points do not fit
        let m = MonomialCurve::with_domain(
            [p(0.0), p(0.0), p(1.0)],
            I16F16::ZERO,
            I16F16::from_num(100),
        )
        .unwrap();
        assert_eq!(Bezier::from_monomial(&m), Err(Error::OutOfRange));
    }
}
