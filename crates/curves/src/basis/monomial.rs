//! The monomial (power) basis `M_i^g(t) = tⁱ` and the Horner scheme (Piegl & Tiller, *The
//! NURBS Book*, 2nd ed., §1.2 "Power Basis Form of a Curve", Algorithm A1.1; Knuth, *The Art
//! of Computer Programming*, vol. 2, §4.6.4).
//!
//! A polynomial `f(t) = a_0 + a_1 t + … + a_g t^g` is evaluated with the Horner scheme
//! `f(t) = a_0 + t(a_1 + t(… + t(a_{g−1} + t a_g)…))`: `g` multiplications and `g` additions.
//! [`MonomialCurve`] is a polynomial curve stored by its monomial coefficients (points), the
//! fast evaluator once the coefficients are known (the algebraic form of a cubic segment,
//! `Q(u) = p_0 + p_1 u + p_2 u² + p_3 u³`).

use super::{MAX_DEGREE, falling_factorial_f64, int_scalar};
use crate::curve::{ParamCurve, ParamCurveDeriv, PieceDeriv};
use crate::error::Error;
use crate::point::Point;
use crate::scalar::Scalar;

/// The polynomial `Σ a_i tⁱ` with scalar coefficients `coeffs = [a_0, …, a_g]`, by the Horner
/// scheme (`f = a_g; for i = g−1..0: f = a_i + t·f`): `g` multiplications and `g`
/// additions, where evaluating each power separately takes `O(g²)` multiplications. Zero for
/// no coefficients.
///
/// No clamping and no range check.
///
/// # Panics
/// Never for `f32`/`f64`. For fixed-point, an intermediate beyond the type's range overflows
/// (a panic in debug builds, wrapping in release) unless the caller keeps every partial Horner
/// sum `Σ_{i≥j} |a_i| |t|^{i−j}` in range; [`MonomialCurve`] checks exactly that at
/// construction.
///
/// ```
/// use strak_curves::basis::horner;
/// // t(2 + t²) − 1 = −1 + 2t + t³
/// assert_eq!(horner(&[-1.0, 2.0, 0.0, 1.0], 2.0), 11.0);
/// ```
pub fn horner<S: Scalar>(coeffs: &[S], t: S) -> S {
    let Some((&last, rest)) = coeffs.split_last() else {
        return S::ZERO;
    };
    let mut f = last;
    for &a in rest.iter().rev() {
        f = a + t * f;
    }
    f
}

/// The polynomial curve `Σ a_i tⁱ` with point coefficients `coeffs = [a_0, …, a_g]`, by the
/// Horner scheme applied coordinate-wise. The origin for no coefficients.
///
/// No clamping and no range check.
///
/// # Panics
/// As [`horner`]: only on fixed-point overflow of an unvalidated input; [`MonomialCurve`]
/// validates the range at construction.
///
/// ```
/// use strak_curves::basis::horner_points;
/// let c = horner_points(&[[1.0, 0.0], [0.0, 2.0], [1.0, 1.0]], 0.5);
/// assert_eq!(c, [1.25, 1.25]);
/// ```
pub fn horner_points<P: Point>(coeffs: &[P], t: P::Scalar) -> P {
    let Some((&last, rest)) = coeffs.split_last() else {
        return P::zero();
    };
    let mut f = last;
    for &a in rest.iter().rev() {
        f = a.plus(f.times(t));
    }
    f
}

/// The monomial basis `M⃗^g(t) = (1, t, t², …, t^g)` with `g = N − 1`, by repeated
/// multiplication. `t` is clamped to `[0, 1]`, the domain on which the bases of this module
/// are compared, so every value lies in `[0, 1]`.
///
/// ```
/// use strak_curves::basis::monomials;
/// assert_eq!(monomials::<f64, 4>(0.5), [1.0, 0.5, 0.25, 0.125]);
/// assert_eq!(monomials::<f64, 3>(2.0), [1.0, 1.0, 1.0]); // clamped to t = 1
/// ```
pub fn monomials<S: Scalar, const N: usize>(t: S) -> [S; N] {
    let t = t.clamp_to(S::ZERO, S::ONE);
    let mut out = [S::ONE; N];
    let mut p = S::ONE;
    for o in out.iter_mut().skip(1) {
        p *= t;
        *o = p;
    }
    out
}

/// A polynomial curve `c(u) = Σ_{i=0}^{g} a_i uⁱ` of degree at most `g = N − 1`, stored by its
/// monomial coefficients (Piegl & Tiller §1.2), over the domain `[u_start, u_end]`
/// (`[0, 1]` from [`MonomialCurve::new`]).
///
/// The polynomial is in the parameter `u` itself (not normalized to the domain),
/// `Q(u) = p_0 + p_1 u + …`. Evaluation uses the Horner scheme; the `k`-th
/// derivative is the Horner scheme on the differentiated coefficients
/// `a_i · i!/(i − k)!` (formed at evaluation by multiplying with small integers).
/// Parameters outside the domain are clamped to it.
///
/// # Fixed-point range
/// The constructor bounds, per coordinate and for every derivative order `k ≤ g`, every
/// partial Horner sum `Σ_{i≥j} |a_i| · i!/(i−k)! · R^{i−j}` with `R = max(|u_start|, |u_end|)`,
/// and rejects the curve with [`Error::OutOfRange`] unless each bound fits the scalar type.
///
/// ```
/// use strak_curves::{ParamCurve, ParamCurveDeriv, basis::MonomialCurve};
///
/// // f(t) = 2 − 12t + 33t² − 22t³ (the monomial form of Bernstein (2, −2, 5, 1))
/// let f = MonomialCurve::new([[2.0], [-12.0], [33.0], [-22.0]])?;
/// assert_eq!(f.eval(1.0), [1.0]);
/// assert_eq!(f.deriv(0.0, 1), [-12.0]);
/// assert_eq!(f.deriv(0.0, 3), [-132.0]);
/// # Ok::<(), strak_curves::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MonomialCurve<P: Point, const N: usize> {
    coeffs: [P; N],
    start: P::Scalar,
    end: P::Scalar,
}

impl<P: Point, const N: usize> MonomialCurve<P, N> {
    /// The curve `Σ a_i uⁱ` over `[0, 1]` from `coeffs = [a_0, …, a_g]`.
    ///
    /// # Errors
    /// [`Error::TooFewPoints`] for `N = 0`, [`Error::DegreeTooHigh`] above
    /// [`MAX_DEGREE`], [`Error::NonFinite`] for NaN/∞ coefficients, [`Error::OutOfRange`] when
    /// an evaluation could leave the scalar's range.
    ///
    /// ```
    /// use strak_curves::{ParamCurve, basis::MonomialCurve};
    /// let line = MonomialCurve::new([[1.0_f32, 1.0], [2.0, 0.0]])?;
    /// assert_eq!(line.eval(0.5), [2.0, 1.0]);
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn new(coeffs: [P; N]) -> Result<Self, Error> {
        Self::with_domain(coeffs, P::Scalar::ZERO, P::Scalar::ONE)
    }

    /// The curve `Σ a_i uⁱ` over `[start, end]`.
    ///
    /// # Errors
    /// As [`MonomialCurve::new`]; also [`Error::NonFinite`] for a NaN/∞ domain bound,
    /// [`Error::ZeroLengthInterval`] for `start == end` and [`Error::InvalidArgument`] for
    /// `start > end`.
    ///
    /// ```
    /// use strak_curves::{ParamCurve, basis::MonomialCurve};
    /// let c = MonomialCurve::with_domain([[0.0], [0.0], [1.0]], 1.0, 3.0)?; // u² on [1, 3]
    /// assert_eq!(c.eval(2.0), [4.0]);
    /// assert_eq!(c.eval(5.0), [9.0]); // clamped to u = 3
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn with_domain(coeffs: [P; N], start: P::Scalar, end: P::Scalar) -> Result<Self, Error> {
        let Some(g) = N.checked_sub(1) else {
            return Err(Error::TooFewPoints {
                required: 1,
                found: 0,
            });
        };
        if g > MAX_DEGREE {
            return Err(Error::DegreeTooHigh {
                max: MAX_DEGREE,
                found: g,
            });
        }
        if !start.is_finite() || !end.is_finite() || !coeffs.iter().all(|a| a.is_finite()) {
            return Err(Error::NonFinite);
        }
        if start == end {
            return Err(Error::ZeroLengthInterval { index: 0 });
        }
        if start > end {
            return Err(Error::InvalidArgument);
        }
        let r = start.to_f64().abs().max(end.to_f64().abs());
        if !P::Scalar::fits(r) {
            return Err(Error::OutOfRange);
        }
        for c in 0..P::DIM {
            for k in 0..=g {
                let mut h = 0.0_f64;
                for (i, a) in coeffs.iter().enumerate().skip(k).rev() {
                    // A zero coefficient adds nothing, whatever the factor (which overflows f64
                    // for degrees ≥ 171).
                    let a = a.coord(c).to_f64().abs();
                    let term = if a == 0.0 {
                        0.0
                    } else {
                        a * falling_factorial_f64(i, k)
                    };
                    h = term + r * h;
                    if !P::Scalar::fits(h) {
                        return Err(Error::OutOfRange);
                    }
                }
            }
        }
        Ok(Self { coeffs, start, end })
    }

    /// The monomial coefficients `[a_0, …, a_g]`.
    ///
    /// ```
    /// use strak_curves::basis::MonomialCurve;
    /// let c = MonomialCurve::new([[1.0], [2.0]])?;
    /// assert_eq!(c.coefficients(), &[[1.0], [2.0]]);
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn coefficients(&self) -> &[P; N] {
        &self.coeffs
    }

    /// The degree bound `g = N − 1` (the actual degree is lower when `a_g = 0`).
    pub fn degree(&self) -> usize {
        N.saturating_sub(1)
    }
}

impl<P: Point, const N: usize> ParamCurve for MonomialCurve<P, N> {
    type Point = P;

    fn domain(&self) -> (P::Scalar, P::Scalar) {
        (self.start, self.end)
    }

    /// `Σ a_i uⁱ` by the Horner scheme, `u` clamped to the domain.
    fn eval(&self, u: P::Scalar) -> P {
        horner_points(&self.coeffs, u.clamp_to(self.start, self.end))
    }
}

impl<P: Point, const N: usize> ParamCurveDeriv for MonomialCurve<P, N> {
    /// The Horner scheme on the `k`-times differentiated coefficients
    /// `a_i · i (i − 1) ⋯ (i − k + 1)`; zero for `k > g`.
    fn deriv(&self, u: P::Scalar, k: usize) -> P {
        let u = u.clamp_to(self.start, self.end);
        // The orders a path asks for (the point, the tangent, the curvature) by a loop of a
        // known length each; the same products in the same order for every order.
        match k {
            0 => horner_points(&self.coeffs, u),
            1 => derivative_horner::<P, N, 1>(&self.coeffs, u),
            2 => derivative_horner::<P, N, 2>(&self.coeffs, u),
            3 => derivative_horner::<P, N, 3>(&self.coeffs, u),
            _ => {
                let mut f: Option<P> = None;
                for (i, &a) in self.coeffs.iter().enumerate().skip(k).rev() {
                    let coef = (0..k).fold(a, |c, m| c.times(int_scalar(i - m)));
                    f = Some(match f {
                        None => coef,
                        Some(f) => coef.plus(f.times(u)),
                    });
                }
                f.unwrap_or_else(P::zero)
            }
        }
    }
}

/// The Horner scheme on the `K`-times differentiated coefficients
/// `a_i · i (i − 1) ⋯ (i − K + 1)` (each the products in that order); zero for `K ≥ N`.
#[inline(always)]
fn derivative_horner<P: Point, const N: usize, const K: usize>(coeffs: &[P; N], u: P::Scalar) -> P {
    let coef = |i: usize| {
        let mut c = coeffs.get(i).copied().unwrap_or_else(P::zero);
        for m in 0..K {
            c = c.times(int_scalar(i - m));
        }
        c
    };
    let Some(top) = N.checked_sub(1).filter(|&top| top >= K) else {
        return P::zero();
    };
    let mut f = coef(top);
    for i in (K..top).rev() {
        f = coef(i).plus(f.times(u));
    }
    f
}

/// A single piece: [`PieceDeriv::piece_deriv`] is [`ParamCurveDeriv::deriv`].
impl<P: Point, const N: usize> PieceDeriv for MonomialCurve<P, N> {
    fn piece_deriv(&self, _piece: usize, u: P::Scalar, k: usize) -> P {
        self.deriv(u, k)
    }
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)] // index loops mirror the matrix formulas
mod tests {
    use super::*;
    use crate::{I16F16, I32F32};
    use glam::Vec2;

    #[test]
    fn horner_of_a_worked_example() {
        // t(2 + t²) − 1 = 2t + t³ − 1
        let a = [-1.0, 2.0, 0.0, 1.0];
        for t in [-2.0, -0.5, 0.0, 0.5, 1.0, 3.0] {
            assert_eq!(horner(&a, t), t * (2.0 + t * t) - 1.0);
        }
        assert_eq!(horner::<f64>(&[], 3.0), 0.0);
        assert_eq!(horner(&[7.0], 3.0), 7.0);
        assert_eq!(horner_points::<[f64; 2]>(&[], 3.0), [0.0, 0.0]);
        assert_eq!(monomials::<f64, 0>(2.0), [0.0_f64; 0]);
        assert_eq!(monomials::<f64, 1>(2.0), [1.0]);
    }

    #[test]
    fn horner_equals_standard_evaluation() {
        // The sum of separately formed powers (quadratic cost) vs Horner (linear cost)
        let a = [0.5, -1.25, 3.0, 0.75, -2.0];
        for t in [0.0, 0.25, 0.5, 1.0] {
            let m = monomials::<f64, 5>(t);
            let standard: f64 = a.iter().zip(m.iter()).map(|(x, y)| x * y).sum();
            assert!((horner(&a, t) - standard).abs() < 1e-15);
        }
    }

    #[test]
    fn curve_derivatives_are_exact() {
        // c(u) = (1 + 2u + 3u² + 4u³, u³)
        let c = MonomialCurve::new([[1.0, 0.0], [2.0, 0.0], [3.0, 0.0], [4.0, 1.0]]).unwrap();
        assert_eq!(c.domain(), (0.0, 1.0));
        assert_eq!(c.degree(), 3);
        let u = 0.5;
        assert_eq!(c.eval(u), [1.0 + 1.0 + 0.75 + 0.5, 0.125]);
        assert_eq!(c.deriv(u, 0), c.eval(u));
        assert_eq!(c.deriv(u, 1), [2.0 + 6.0 * u + 12.0 * u * u, 3.0 * u * u]);
        assert_eq!(c.deriv(u, 2), [6.0 + 24.0 * u, 6.0 * u]);
        assert_eq!(c.deriv(u, 3), [24.0, 6.0]);
        assert_eq!(c.deriv(u, 4), [0.0, 0.0]);
        assert_eq!(c.deriv(u, 99), [0.0, 0.0]);
        // clamped
        assert_eq!(c.eval(-1.0), c.eval(0.0));
        assert_eq!(c.deriv(2.0, 1), c.deriv(1.0, 1));
    }

    #[test]
    fn domain_is_the_raw_parameter() {
        let c = MonomialCurve::with_domain([Vec2::new(0.0, 1.0), Vec2::new(1.0, 0.0)], -2.0, 2.0)
            .unwrap();
        assert_eq!(c.domain(), (-2.0, 2.0));
        assert_eq!(c.eval(-2.0), Vec2::new(-2.0, 1.0));
        assert_eq!(c.eval(-3.0), Vec2::new(-2.0, 1.0));
        assert_eq!(c.deriv(0.0, 1), Vec2::new(1.0, 0.0));
    }

    #[test]
    fn error_too_few_points() {
        assert_eq!(
            MonomialCurve::<[f64; 2], 0>::new([]),
            Err(Error::TooFewPoints {
                required: 1,
                found: 0
            })
        );
    }

    #[test]
    fn error_degree_too_high() {
        let coeffs = [[I16F16::ZERO]; MAX_DEGREE + 2];
        assert_eq!(
            MonomialCurve::new(coeffs),
            Err(Error::DegreeTooHigh {
                max: MAX_DEGREE,
                found: MAX_DEGREE + 1
            })
        );
    }

    #[test]
    fn error_non_finite() {
        assert_eq!(MonomialCurve::new([[f64::NAN]]), Err(Error::NonFinite));
        assert_eq!(
            MonomialCurve::with_domain([[1.0]], 0.0, f64::INFINITY),
            Err(Error::NonFinite)
        );
    }

    #[test]
    fn error_zero_length_and_reversed_domain() {
        assert_eq!(
            MonomialCurve::with_domain([[1.0]], 1.0, 1.0),
            Err(Error::ZeroLengthInterval { index: 0 })
        );
        assert_eq!(
            MonomialCurve::with_domain([[1.0]], 2.0, 1.0),
            Err(Error::InvalidArgument)
        );
    }

    #[test]
    fn error_out_of_range() {
        let x = |v: f64| [I16F16::from_num(v)];
        // coefficients fit, but the derivative 3·4000 + 2·4000… does not: Horner bound 24 000.
        assert_eq!(
            MonomialCurve::new([x(0.0), x(4000.0), x(4000.0), x(4000.0)]),
            Err(Error::OutOfRange)
        );
        // the value bound on [0, 1]: 3 × 6000 > 16 383
        assert_eq!(
            MonomialCurve::new([x(6000.0), x(6000.0), x(6000.0)]),
            Err(Error::OutOfRange)
        );
        // a domain far from 0 makes uⁱ large
        assert_eq!(
            MonomialCurve::with_domain([x(0.0), x(0.0), x(1.0)], x(0.0)[0], x(200.0)[0]),
            Err(Error::OutOfRange)
        );
        // a domain bound beyond LIMIT
        assert_eq!(
            MonomialCurve::with_domain([x(1.0)], x(0.0)[0], I16F16::from_num(20000)),
            Err(Error::OutOfRange)
        );
        assert!(MonomialCurve::new([x(1000.0), x(1000.0), x(1000.0)]).is_ok());
    }

    #[test]
    fn f32_and_fixed_point_agree_with_f64() {
        let a = [[0.5, -1.0], [2.0, 0.25], [-3.0, 1.5], [1.25, -0.75]];
        let cf = MonomialCurve::new(a).unwrap();
        let c32 = MonomialCurve::new(a.map(|p| p.map(|v| v as f32))).unwrap();
        let cx = MonomialCurve::new(a.map(|p| p.map(I16F16::from_num))).unwrap();
        let cy = MonomialCurve::new(a.map(|p| p.map(I32F32::from_num))).unwrap();
        for step in 0..=16 {
            let u = step as f64 / 16.0;
            for k in 0..4 {
                let r = cf.deriv(u, k);
                let p32 = c32.deriv(u as f32, k);
                let px = cx.deriv(I16F16::from_num(u), k);
                let py = cy.deriv(I32F32::from_num(u), k);
                for d in 0..2 {
                    assert!((f64::from(p32[d]) - r[d]).abs() < 1e-5);
                    assert!((px[d].to_f64() - r[d]).abs() < 50.0 * <I16F16 as Scalar>::EPSILON);
                    assert!((py[d].to_f64() - r[d]).abs() < 50.0 * <I32F32 as Scalar>::EPSILON);
                }
            }
        }
    }
}
