//! The Bézier curve type, its validation and de Casteljau evaluation (Farin, *Curves and
//! Surfaces for CAGD*, 5th ed., §3.2 "The de Casteljau Algorithm"; Piegl & Tiller, *The NURBS
//! Book*, 2nd ed., §1.3, Algorithm A1.5).

use crate::basis::{MAX_DEGREE, falling_factorial_f64, int_scalar};
use crate::curve::{ParamCurve, ParamCurveDeriv, PieceDeriv};
use crate::error::Error;
use crate::point::Point;
use crate::scalar::Scalar;

/// A Bézier curve `c(t) = Σ_{i=0}^{g} b_i B_i^g(t)`, `t ∈ [0, 1]`, of degree `g = N − 1`
/// with the `N` Bézier points `b_0, …, b_g` (Farin §4.1–4.2).
///
/// Properties (Farin §3.3, §4.2): the curve interpolates `b_0` and `b_g` and is tangent to
/// the control polygon there (`c'(0) = g(b_1 − b_0)`, `c'(1) = g(b_g − b_{g−1})`), lies in
/// the convex hull of its points, and is affinely invariant; it approximates the inner points
/// and every point influences the whole curve (no local control).
///
/// Evaluation is de Casteljau's algorithm, `b_i^r = (1 − t) b_i^{r−1} + t b_{i+1}^{r−1}`,
/// `c(t) = b_0^g`: `g(g + 1)/2` convex combinations (`O(g²)`), so in fixed-point it cannot overflow
/// when the points fit. The `k`-th derivative is de Casteljau down to level `g − k`, then the
/// `k`-th forward difference times `g!/(g − k)!`:
/// `c^{(k)}(t) = g!/(g−k)! · Σ_i Δ^k b_i B_i^{g−k}(t)`; zero above the degree.
/// Parameters outside `[0, 1]` are clamped.
///
/// # Fixed-point range
/// The constructor computes in `f64`, per coordinate, the control points of every hodograph
/// (`g!/(g−k)! · Δ^k b_i` for `k = 0..=g`, i.e. the points and all derivative curves) and
/// rejects the curve with [`Error::OutOfRange`] unless each fits the scalar type. All
/// intermediates of evaluation (de Casteljau points, differences `Δ^m`, the partial products
/// of the factor `g (g−1) ⋯`) are bounded by these values.
///
/// ```
/// use strak_curves::{Bezier, ParamCurve, ParamCurveDeriv};
///
/// // The cubic with Bernstein coefficients (2, −2, 5, 1)
/// let c = Bezier::new([[2.0], [-2.0], [5.0], [1.0]])?;
/// assert_eq!(c.eval(0.5), [2.0 - 6.0 + 33.0 / 4.0 - 22.0 / 8.0]);
/// assert_eq!(c.deriv(0.0, 1), [-12.0]); // 3 (b_1 − b_0)
/// assert_eq!(c.deriv(0.0, 3), [-132.0]); // 6 Δ³b_0 = 3! · (−22)
/// # Ok::<(), strak_curves::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bezier<P: Point, const N: usize> {
    points: [P; N],
}

/// One de Casteljau step on `w`: `w[i] ← (1 − t) w[i] + t w[i + 1]` for `i < len − 1`.
#[inline]
pub(super) fn casteljau_step<P: Point>(w: &mut [P], t: P::Scalar) {
    for i in 1..w.len() {
        w[i - 1] = w[i - 1].lerp(w[i], t);
    }
}

/// Validates Bézier points: count, degree, finiteness and the hodograph range bound.
fn validate<P: Point, const N: usize>(points: &[P; N]) -> Result<(), Error> {
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
    if !points.iter().all(|p| p.is_finite()) {
        return Err(Error::NonFinite);
    }
    for c in 0..P::DIM {
        let mut d = points.map(|p| p.coord(c).to_f64());
        for k in 0..=g {
            let len = N - k;
            if k > 0 {
                for i in 1..=len {
                    d[i - 1] = d[i] - d[i - 1];
                }
            }
            let max = d.iter().take(len).fold(0.0_f64, |m, v| m.max(v.abs()));
            // A zero difference is zero whatever the factor (which overflows f64 for g ≥ 171).
            if max > 0.0 && !P::Scalar::fits(max * falling_factorial_f64(g, k)) {
                return Err(Error::OutOfRange);
            }
        }
    }
    Ok(())
}

impl<P: Point, const N: usize> Bezier<P, N> {
    /// The Bézier curve with the points `[b_0, …, b_g]`.
    ///
    /// # Errors
    /// [`Error::TooFewPoints`] for `N = 0`, [`Error::DegreeTooHigh`] above
    /// [`basis::MAX_DEGREE`](crate::basis::MAX_DEGREE), [`Error::NonFinite`] for NaN/∞
    /// coordinates, [`Error::OutOfRange`] when a point or a derivative could leave the scalar's
    /// range (see the type docs).
    ///
    /// ```
    /// use strak_curves::{Bezier, Error, I16F16, ParamCurve};
    /// let p = |x: f64, y: f64| [I16F16::from_num(x), I16F16::from_num(y)];
    /// let c = Bezier::new([p(0.0, 0.0), p(1.0, 2.0), p(3.0, 2.0), p(4.0, 0.0)])?;
    /// assert_eq!(c.eval(I16F16::from_num(0.5)), p(2.0, 1.5));
    /// // the points fit I16F16 (|x| ≤ 16 383) in both cases, but the derivative
    /// // 2 · (b_1 − b_0) = 20 000 of the quadratic does not
    /// let line = Bezier::new([p(-5000.0, 0.0), p(5000.0, 0.0)]);
    /// assert!(line.is_ok());
    /// let quad = Bezier::new([p(-5000.0, 0.0), p(5000.0, 0.0), p(-5000.0, 0.0)]);
    /// assert_eq!(quad, Err(Error::OutOfRange));
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn new(points: [P; N]) -> Result<Self, Error> {
        validate(&points)?;
        Ok(Self { points })
    }

    /// Wraps points derived from a valid curve by convex combinations (subdivision,
    /// sub-segments, reversal), whose hodograph bounds cannot exceed the original's.
    pub(super) fn from_valid(points: [P; N]) -> Self {
        Self { points }
    }

    /// The Bézier points `[b_0, …, b_g]`.
    ///
    /// ```
    /// use strak_curves::Bezier;
    /// let c = Bezier::new([[0.0_f32, 0.0], [1.0, 1.0]])?;
    /// assert_eq!(c.control_points(), &[[0.0, 0.0], [1.0, 1.0]]);
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn control_points(&self) -> &[P; N] {
        &self.points
    }

    /// The degree `g = N − 1`.
    pub fn degree(&self) -> usize {
        N.saturating_sub(1)
    }

    /// The same curve traversed backwards: points `[b_g, …, b_0]`, `c̃(t) = c(1 − t)`.
    ///
    /// ```
    /// use strak_curves::{Bezier, ParamCurve};
    /// let c = Bezier::new([[0.0], [1.0], [4.0]])?;
    /// let r = c.reverse();
    /// assert_eq!(r.control_points(), &[[4.0], [1.0], [0.0]]);
    /// assert_eq!(r.eval(0.25), c.eval(0.75));
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn reverse(&self) -> Self {
        let mut points = self.points;
        points.reverse();
        Self::from_valid(points)
    }
}

impl<P: Point, const N: usize> ParamCurve for Bezier<P, N> {
    type Point = P;

    /// Always `(0, 1)`.
    fn domain(&self) -> (P::Scalar, P::Scalar) {
        (P::Scalar::ZERO, P::Scalar::ONE)
    }

    /// de Casteljau's algorithm, `t` clamped to `[0, 1]`.
    fn eval(&self, t: P::Scalar) -> P {
        let t = t.clamp_to(P::Scalar::ZERO, P::Scalar::ONE);
        let mut w = self.points;
        for len in (2..=N).rev() {
            casteljau_step(&mut w[..len], t);
        }
        w.first().copied().unwrap_or_else(P::zero)
    }
}

impl<P: Point, const N: usize> ParamCurveDeriv for Bezier<P, N> {
    /// de Casteljau to level `g − k`, then the `k`-th forward difference times
    /// `g (g − 1) ⋯ (g − k + 1)`; zero for `k > g`. `t` clamped to `[0, 1]`.
    fn deriv(&self, t: P::Scalar, k: usize) -> P {
        let g = N.saturating_sub(1);
        if N == 0 || k > g {
            return P::zero();
        }
        let t = t.clamp_to(P::Scalar::ZERO, P::Scalar::ONE);
        let mut w = self.points;
        // de Casteljau to level g − k: k + 1 points remain in w[..=k]
        for len in (k + 2..=N).rev() {
            casteljau_step(&mut w[..len], t);
        }
        // k-th forward difference of those k + 1 points
        for len in (2..=k + 1).rev() {
            for i in 1..len {
                w[i - 1] = w[i].minus(w[i - 1]);
            }
        }
        let mut d = w.first().copied().unwrap_or_else(P::zero);
        for m in 0..k {
            d = d.times(int_scalar(g - m));
        }
        d
    }
}

/// A single piece: [`PieceDeriv::piece_deriv`] is [`ParamCurveDeriv::deriv`].
impl<P: Point, const N: usize> PieceDeriv for Bezier<P, N> {
    fn piece_deriv(&self, _piece: usize, u: P::Scalar, k: usize) -> P {
        self.deriv(u, k)
    }
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)] // index loops mirror the formulas
mod tests {
    use super::*;
    use crate::basis::{bernstein_all, bernstein_f64};
    use crate::{I16F16, I32F32};
    use glam::{DVec2, Vec2};

    #[test]
    fn de_casteljau_at_one_third_equals_bernstein_sum() {
        // Coefficients (2, −2, 5, 1): Σ b_i B_i³(1/3) = 23/27
        let c = Bezier::new([[2.0], [-2.0], [5.0], [1.0]]).unwrap();
        let t = 1.0 / 3.0;
        let b = bernstein_all::<f64, 4>(t);
        let sum = 2.0 * b[0] - 2.0 * b[1] + 5.0 * b[2] + b[3];
        assert!((c.eval(t)[0] - 23.0 / 27.0).abs() < 1e-15);
        assert!((c.eval(t)[0] - sum).abs() < 1e-15);
        // P(1/3) by de Casteljau in 2-D, against the closed-form Bernstein sum
        let q = [
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 3.0),
            DVec2::new(4.0, 3.0),
            DVec2::new(5.0, 0.0),
        ];
        let c = Bezier::new(q).unwrap();
        let mut s = DVec2::ZERO;
        for i in 0..4 {
            s += q[i] * bernstein_f64(3, i, t);
        }
        assert!((c.eval(t) - s).length() < 1e-15);
        // with t = 1/3 exactly representable steps "2/3·P + 1/3·P" by hand
        let l1: [DVec2; 3] = core::array::from_fn(|i| q[i] * (2.0 / 3.0) + q[i + 1] * t);
        let l2: [DVec2; 2] = core::array::from_fn(|i| l1[i] * (2.0 / 3.0) + l1[i + 1] * t);
        let p = l2[0] * (2.0 / 3.0) + l2[1] * t;
        assert!((c.eval(t) - p).length() < 1e-15);
    }

    #[test]
    fn end_points_and_end_tangents_are_interpolated() {
        let c = Bezier::new([[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]]).unwrap();
        assert_eq!(c.eval(0.0), [0.0, 0.0]);
        assert_eq!(c.eval(1.0), [4.0, 0.0]);
        assert_eq!(c.eval(0.5), [2.0, 1.5]);
        assert_eq!(c.eval(-3.0), [0.0, 0.0]);
        assert_eq!(c.eval(7.0), [4.0, 0.0]);
        assert_eq!(c.deriv(0.0, 1), [3.0, 6.0]);
        assert_eq!(c.deriv(1.0, 1), [3.0, -6.0]);
        assert_eq!(c.domain(), (0.0, 1.0));
        assert_eq!(c.degree(), 3);
        assert_eq!(c.piece_count(), 1);
    }

    #[test]
    fn derivatives_match_the_monomial_form() {
        // c(t) = 2 − 12t + 33t² − 22t³
        let c = Bezier::new([[2.0], [-2.0], [5.0], [1.0]]).unwrap();
        for step in 0..=8 {
            let t = step as f64 / 8.0;
            assert_eq!(c.deriv(t, 0), c.eval(t));
            let d1 = -12.0 + 66.0 * t - 66.0 * t * t;
            let d2 = 66.0 - 132.0 * t;
            assert!((c.deriv(t, 1)[0] - d1).abs() < 1e-13);
            assert!((c.deriv(t, 2)[0] - d2).abs() < 1e-13);
            assert_eq!(c.deriv(t, 3), [-132.0]);
            assert_eq!(c.deriv(t, 4), [0.0]);
            assert_eq!(c.deriv(t, 100), [0.0]);
        }
        // degree 0: constant, derivatives zero
        let k = Bezier::new([[3.0, 4.0]]).unwrap();
        assert_eq!(k.eval(0.3), [3.0, 4.0]);
        assert_eq!(k.deriv(0.3, 1), [0.0, 0.0]);
    }

    #[test]
    fn reverse_runs_backwards() {
        let c = Bezier::new([
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 2.0),
            Vec2::new(4.0, 1.0),
        ])
        .unwrap();
        let r = c.reverse();
        for step in 0..=8 {
            let t = step as f32 / 8.0;
            assert!((r.eval(t) - c.eval(1.0 - t)).length() < 1e-6);
            assert!((r.deriv(t, 1) + c.deriv(1.0 - t, 1)).length() < 1e-5);
        }
        assert_eq!(r.reverse(), c);
    }

    #[test]
    fn error_too_few_points() {
        assert_eq!(
            Bezier::<[f64; 2], 0>::new([]),
            Err(Error::TooFewPoints {
                required: 1,
                found: 0
            })
        );
    }

    #[test]
    fn error_non_finite() {
        assert_eq!(
            Bezier::new([[0.0, 0.0], [f64::NAN, 1.0]]),
            Err(Error::NonFinite)
        );
        assert_eq!(
            Bezier::new([Vec2::ZERO, Vec2::new(f32::INFINITY, 0.0)]),
            Err(Error::NonFinite)
        );
    }

    #[test]
    fn error_out_of_range() {
        let p = |x: f64| [I16F16::from_num(x)];
        // a point beyond LIMIT (16 383)
        assert_eq!(Bezier::new([p(0.0), p(20000.0)]), Err(Error::OutOfRange));
        // points fit, first derivative 3 · |Δb| = 3 · 8000 does not
        assert_eq!(
            Bezier::new([p(0.0), p(8000.0), p(8000.0), p(8000.0)]),
            Err(Error::OutOfRange)
        );
        // first and second derivative fit (3 · 1000, 6 · 2000), the third does not:
        // 6 · |Δ³b| = 6 · 4000
        assert_eq!(
            Bezier::new([p(1000.0), p(0.0), p(1000.0), p(0.0)]),
            Err(Error::OutOfRange)
        );
        assert!(Bezier::new([p(500.0), p(0.0), p(500.0), p(0.0)]).is_ok());
        // the same in I32F32 and f64 is fine
        assert!(Bezier::new([[2000.0], [0.0], [2000.0], [0.0]]).is_ok());
        // f32: beyond f32::MAX / 2
        assert_eq!(Bezier::new([[0.0_f32], [3.0e38]]), Err(Error::OutOfRange));
    }

    #[test]
    fn error_degree_too_high() {
        let pts = [[I16F16::ZERO]; MAX_DEGREE + 2];
        assert_eq!(
            Bezier::new(pts),
            Err(Error::DegreeTooHigh {
                max: MAX_DEGREE,
                found: MAX_DEGREE + 1
            })
        );
    }

    #[test]
    fn f32_and_fixed_point_agree_with_f64() {
        let q = [[0.0, 0.0], [1.5, 3.0], [4.25, -2.0], [6.0, 1.0], [7.5, 0.5]];
        let cf = Bezier::new(q).unwrap();
        let c32 = Bezier::new(q.map(|p| Vec2::new(p[0] as f32, p[1] as f32))).unwrap();
        let cx = Bezier::new(q.map(|p| p.map(I16F16::from_num))).unwrap();
        let cy = Bezier::new(q.map(|p| p.map(I32F32::from_num))).unwrap();
        let g = 4.0;
        for step in 0..=32 {
            let t = step as f64 / 32.0;
            for k in 0..=4 {
                let r = cf.deriv(t, k);
                let a = c32.deriv(t as f32, k);
                let x = cx.deriv(I16F16::from_num(t), k);
                let y = cy.deriv(I32F32::from_num(t), k);
                // de Casteljau: ≤ 2 ulps per level; Δ^k doubles it k times; × g!/(g−k)!
                let scale = (2.0 * g + 1.0) * 2f64.powi(k as i32) * falling_factorial_f64(4, k);
                for d in 0..2 {
                    assert!((f64::from(a[d]) - r[d]).abs() < 1e-6 * scale * 8.0);
                    let ex = (x[d].to_f64() - r[d]).abs();
                    let ey = (y[d].to_f64() - r[d]).abs();
                    assert!(
                        ex <= scale * <I16F16 as Scalar>::EPSILON,
                        "k={k} t={t}: {ex}"
                    );
                    assert!(
                        ey <= scale * <I32F32 as Scalar>::EPSILON,
                        "k={k} t={t}: {ey}"
                    );
                }
            }
        }
    }
}
