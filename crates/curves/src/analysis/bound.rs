//! A bound of the second derivative over a parameter interval.

use crate::curve::{ParamCurveDeriv, ScalarOf};
use crate::error::Error;
use crate::point::Point;
use crate::scalar::Scalar;

use super::{c64, param};

/// The highest derivative of the Taylor bound (exact for pieces of degree ≤ 8).
const MAX_ORDER: usize = 8;

/// Equal parts of each piece's share of the interval, each bounded by its own expansion.
const PARTS: usize = 4;

/// An upper bound of `|c''(u)|` over `u ∈ [a, b]` (clamped to the domain).
///
/// Each piece's share of `[a, b]` is cut into four equal parts; on a part `[s, s + h]` the
/// Taylor expansion of `c''` at `s` gives
///
/// ```text
/// |c''(s + t)| ≤ max(|c''(s)|, |c''(s) + c'''(s)·h|) + Σ_{k=4..8} |c^(k)(s)|·h^(k−2)/(k−2)!
/// ```
///
/// (the norm of the linear part is convex in `t`, so its largest value is at an end; the
/// rest by the triangle inequality). For pieces that are polynomials of degree ≤ 8
/// (Bézier, B-spline, Lagrange, Hermite and cubic-spline pieces) the expansion is exact, so
/// the bound holds, up to the rounding of the derivative values. For rational pieces
/// (NURBS), circular arcs or higher degrees the series is cut after `c^(8)` and its last
/// term is added once more as an estimate of the remainder: then the result is an
/// estimate, accurate where the parts are short against the distance to the nearest
/// (complex) singularity of the piece. The same expansion certifies [`flatten`](crate::flatten)'s
/// chord errors.
///
/// Work: a binary search for the first piece (`log₂(piece_count)` piece domains), then
/// `4·7` derivative evaluations per piece the interval touches.
///
/// # Errors
/// [`Error::InvalidArgument`] for `b < a` or a parameter that is not finite;
/// [`Error::NonFinite`] when a derivative is not finite.
///
/// ```
/// use strak_curves::{Bezier, second_derivative_bound};
/// // c''(u) = 2·(b₀ − 2b₁ + b₂) = (0, −8) everywhere on this parabola
/// let b = Bezier::new([[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]])?;
/// assert_eq!(second_derivative_bound(&b, 0.0, 1.0)?, 8.0);
/// # Ok::<(), strak_curves::Error>(())
/// ```
pub fn second_derivative_bound<C: ParamCurveDeriv>(
    curve: &C,
    a: ScalarOf<C>,
    b: ScalarOf<C>,
) -> Result<f64, Error> {
    let (af, bf) = (a.to_f64(), b.to_f64());
    if !(af.is_finite() && bf.is_finite() && af <= bf) {
        return Err(Error::InvalidArgument);
    }
    let (lo, hi) = curve.domain();
    let (af, bf) = (af.max(lo.to_f64()), bf.min(hi.to_f64()));
    let mut bound: f64 = 0.0;
    let mut piece = first_piece(curve, af);
    while piece < curve.piece_count() {
        let (p0, p1) = curve.piece_domain(piece);
        let (x0, x1) = (af.max(p0.to_f64()), bf.min(p1.to_f64()));
        if x0 > bf {
            break;
        }
        #[allow(clippy::cast_precision_loss)]
        let h = (x1 - x0).max(0.0) / PARTS as f64;
        for part in 0..PARTS {
            #[allow(clippy::cast_precision_loss)]
            let s = param(x0 + h * part as f64, p0, p1);
            bound = bound.max(taylor_bound(curve, s, h));
        }
        piece += 1;
    }
    if bound.is_finite() {
        Ok(bound)
    } else {
        Err(Error::NonFinite)
    }
}

/// The first piece whose interval ends after `u` (the last piece if none): a binary search,
/// as the pieces are ordered along the parameter.
fn first_piece<C: ParamCurveDeriv>(curve: &C, u: f64) -> usize {
    let (mut lo, mut hi) = (0, curve.piece_count().saturating_sub(1));
    while lo < hi {
        let mid = lo + (hi - lo) / 2;
        if curve.piece_domain(mid).1.to_f64() <= u {
            lo = mid + 1;
        } else {
            hi = mid;
        }
    }
    lo
}

/// The Taylor bound of `|c''|` on `[s, s + h]` (see [`second_derivative_bound`]).
fn taylor_bound<C: ParamCurveDeriv>(curve: &C, s: ScalarOf<C>, h: f64) -> f64 {
    let norm = |p: &C::Point, q: Option<(&C::Point, f64)>| {
        let mut n2 = 0.0;
        for i in 0..C::Point::DIM {
            let x = c64(p, i) + q.map_or(0.0, |(q, f)| c64(q, i) * f);
            n2 += x * x;
        }
        libm::sqrt(n2)
    };
    let (d2, d3) = (curve.deriv(s, 2), curve.deriv(s, 3));
    let mut bound = norm(&d2, None).max(norm(&d2, Some((&d3, h))));
    // f = h^(k−2) / (k−2)! for k = 4, 5, …
    let (mut f, mut last) = (h, 0.0);
    for k in 4..=MAX_ORDER {
        #[allow(clippy::cast_precision_loss)]
        let div = (k - 2) as f64;
        f *= h / div;
        last = norm(&curve.deriv(s, k), None) * f;
        bound += last;
    }
    bound + last
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{BSpline, Nurbs};

    /// The largest |c''| over a fine grid of `[a, b]`.
    fn sampled<C: ParamCurveDeriv<Point = [f64; 2]>>(c: &C, a: f64, b: f64) -> f64 {
        (0..=4000)
            .map(|i| {
                let d = c.deriv(a + (b - a) * f64::from(i) / 4000.0, 2);
                d[0].hypot(d[1])
            })
            .fold(0.0, f64::max)
    }

    /// On a cubic B-spline the bound is at least the sampled maximum over every interval
    /// and not far above it; intervals inside one piece and across several.
    #[test]
    fn bounds_a_b_spline() {
        let points = [
            [0.0, 0.0],
            [1.0, 3.0],
            [3.0, -1.0],
            [4.0, 2.0],
            [6.0, 0.0],
            [7.0, 4.0],
        ];
        let knots = [0.0, 0.0, 0.0, 0.0, 1.0, 2.5, 4.0, 4.0, 4.0, 4.0];
        let c = BSpline::<[f64; 2], 6, 10>::new(3, &points, &knots).unwrap();
        for (a, b) in [(0.0, 4.0), (0.3, 0.6), (0.9, 1.2), (2.0, 3.9), (4.0, 4.0)] {
            let (bound, seen) = (
                second_derivative_bound(&c, a, b).unwrap(),
                sampled(&c, a, b),
            );
            assert!(
                bound >= seen * (1.0 - 1e-12),
                "[{a}, {b}]: {bound} < {seen}"
            );
            assert!(bound <= 3.0 * seen + 1e-9, "[{a}, {b}]: {bound} ≫ {seen}");
        }
        assert_eq!(
            second_derivative_bound(&c, 1.0, 0.5),
            Err(Error::InvalidArgument)
        );
        assert_eq!(
            second_derivative_bound(&c, f64::NAN, 0.5),
            Err(Error::InvalidArgument)
        );
    }

    /// On a rational quarter circle of radius 2 (|c''| is not constant in its parameter) the
    /// estimate is above the sampled maximum, by less than half of it.
    #[test]
    fn estimates_a_rational_quarter_circle() {
        let w = core::f64::consts::FRAC_1_SQRT_2;
        let c = Nurbs::<[f64; 2], 3, 6>::new(
            2,
            &[[2.0, 0.0], [2.0, 2.0], [0.0, 2.0]],
            &[1.0, w, 1.0],
            &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        )
        .unwrap();
        let (lo, hi) = c.domain();
        let (bound, seen) = (
            second_derivative_bound(&c, lo, hi).unwrap(),
            sampled(&c, lo, hi),
        );
        assert!(bound >= seen && bound <= 1.6 * seen, "{bound} vs {seen}");
    }
}
