//! Derivatives of a B-spline through the de Boor points of its derivative curves, and the
//! fixed-point range bound that makes them safe.
//!
//! The derivative of a B-spline of degree `g` is a B-spline of degree `g − 1` on the same knots
//! with the de Boor points (Piegl & Tiller, *The NURBS Book*, 2nd ed., §3.3;
//! differentiating the Cox–de Boor recursion)
//!
//! ```text
//! Q_i = g · (d_{i+1} − d_i) / (u_{i+g+1} − u_{i+1})
//! ```
//!
//! applied `k` times for the `k`-th derivative. Evaluation applies it *locally*: on the span
//! `[u_s, u_{s+1})` only the `g + 1` points `d_{s−g}, …, d_s` are differenced, and every knot
//! difference in the divisor contains that non-empty span, so it is positive. The results are
//! exactly the global derivative points restricted to the span; no extra storage is needed.
//!
//! Range: at construction [`check_range`] repeats, in f64, every multiplication and division
//! that evaluation performs for every non-empty span and every order `1 ≤ k ≤ g` (the integer
//! factor is applied before the division, so both the scaled difference and the quotient are
//! bounded), and requires the largest magnitude to fit [`Scalar::fits`]. The de Boor
//! evaluation of the derivative points is a convex combination and adds nothing.

use super::knots::{BSPLINE_MAX_DEGREE, KnotVector, LOCAL, ratio};
use crate::error::Error;
use crate::point::Point;
use crate::scalar::Scalar;

/// One differencing step of order `r` (`1 ≤ r ≤ g`) on the local points of span `s`:
/// afterwards `d[j]`, `r ≤ j ≤ g`, holds the `r`-th derivative point acting on
/// `N_{s−g+j}^{g−r}`.
pub(crate) fn derive_local<P: Point, const M: usize>(
    kv: &KnotVector<P::Scalar, M>,
    s: usize,
    r: usize,
    d: &mut [P; LOCAL],
) {
    let g = kv.degree().min(BSPLINE_MAX_DEGREE);
    if r == 0 || r > g {
        return;
    }
    let f = P::Scalar::from_i16((g + 1 - r) as i16);
    for j in (r..=g).rev() {
        let lo = kv.knot((s + j).saturating_sub(g));
        let hi = kv.knot((s + j + 1).saturating_sub(r));
        let den = hi - lo;
        let diff = d[j].minus(d[j - 1]).times(f);
        d[j] = P::from_coords(|c| ratio(diff.coord(c), den));
    }
}

/// For one coordinate of the local points `v[0..=g]` of span `s`: the largest magnitude of
/// the derivative points of every order (`[0]` is the points themselves) and of every scaled
/// difference `(g − r + 1)·(v_j − v_{j−1})`, computed in f64 like [`derive_local`].
#[allow(clippy::needless_range_loop)] // r is the derivative order
pub(crate) fn span_coord_bounds<S: Scalar, const M: usize>(
    kv: &KnotVector<S, M>,
    s: usize,
    mut v: [f64; LOCAL],
) -> ([f64; LOCAL], f64) {
    let g = kv.degree().min(BSPLINE_MAX_DEGREE);
    let t = |i: usize| kv.knot(i).to_f64();
    let mut maxima = [0.0_f64; LOCAL];
    let mut inter = 0.0_f64;
    maxima[0] = v.iter().take(g + 1).fold(0.0, |m, x| m.max(x.abs()));
    for r in 1..=g {
        let f = (g + 1 - r) as f64;
        for j in (r..=g).rev() {
            let den = t(s + j + 1 - r) - t(s + j - g);
            let m = (v[j] - v[j - 1]) * f;
            inter = inter.max(m.abs());
            v[j] = if den > 0.0 { m / den } else { 0.0 };
        }
        maxima[r] = v
            .iter()
            .take(g + 1)
            .skip(r)
            .fold(0.0, |m, x| m.max(x.abs()));
    }
    (maxima, inter)
}

/// The f64 values of coordinate `c` of the local points `d_{s−g}, …, d_s`.
pub(crate) fn local_coords<P: Point>(points: &[P], s: usize, g: usize, c: usize) -> [f64; LOCAL] {
    let mut v = [0.0_f64; LOCAL];
    for (j, x) in v.iter_mut().enumerate().take(g + 1) {
        *x = points.get(s + j - g).map_or(0.0, |p| p.coord(c).to_f64());
    }
    v
}

/// `Ok` when every point and every value the evaluation of the curve and its derivatives up
/// to order `g` produces fits the scalar's range; [`Error::OutOfRange`] otherwise.
pub(crate) fn check_range<P: Point, const M: usize>(
    points: &[P],
    kv: &KnotVector<P::Scalar, M>,
) -> Result<(), Error> {
    let g = kv.degree().min(BSPLINE_MAX_DEGREE);
    let mut worst = points.iter().fold(0.0_f64, |m, p| m.max(p.max_abs()));
    for s in g..kv.control_point_count() {
        if kv.knot(s) >= kv.knot(s + 1) {
            continue;
        }
        for c in 0..P::DIM {
            let (maxima, inter) = span_coord_bounds(kv, s, local_coords(points, s, g, c));
            worst = maxima.iter().fold(worst.max(inter), |m, x| m.max(*x));
        }
    }
    if <P::Scalar as Scalar>::fits(worst) {
        Ok(())
    } else {
        Err(Error::OutOfRange)
    }
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;
    use crate::bspline::BSpline;
    use crate::curve::ParamCurveDeriv;
    use crate::scalar::{I16F16, I32F32};

    #[test]
    fn derivative_points_of_clamped_cubic() {
        // Global derivative points Q_i = g (d_{i+1} − d_i)/(u_{i+g+1} − u_{i+1}) for the knots
        // U = [0,0,0,0,1,2,3,4,4,4,4]; on the first span they are Q_0, Q_1, Q_2.
        let d = [[0.0], [1.0], [3.0], [6.0], [10.0], [15.0], [21.0]];
        let c = BSpline::<[f64; 1], 8, 12>::clamped_uniform(3, &d, 0.0, 4.0).unwrap();
        let kv = c.knot_vector();
        let mut loc = [[0.0]; LOCAL];
        loc[..4].copy_from_slice(&d[..4]);
        derive_local(kv, 3, 1, &mut loc);
        // Q_0 = 3·1/1, Q_1 = 3·2/2, Q_2 = 3·3/3
        assert_eq!(&loc[1..4], &[[3.0], [3.0], [3.0]]);
        derive_local(kv, 3, 2, &mut loc);
        assert_eq!(&loc[2..4], &[[0.0], [0.0]]);
        assert_eq!(c.deriv(0.5, 1), [3.0]);
    }

    #[test]
    fn deriv_matches_finite_differences_nonuniform() {
        let d = [
            [0.0, 1.0],
            [2.0, 3.0],
            [1.0, -2.0],
            [5.0, 0.5],
            [4.0, 4.0],
            [7.0, 1.0],
        ];
        let t = [0., 0., 0., 0., 0.4, 1.5, 2., 2., 2., 2.];
        let c = BSpline::<[f64; 2], 8, 12>::new(3, &d, &t).unwrap();
        for i in 1..200 {
            let u = 2.0 * f64::from(i) / 200.0;
            for k in 1..=3 {
                let h = 1e-6;
                let (a, b) = (c.deriv(u - h, k - 1), c.deriv(u + h, k - 1));
                let exact = c.deriv(u, k);
                // Skip knots, where the (k−1)-th derivative may have a kink.
                if t.iter().any(|&x| (x - u).abs() < 2.0 * h) {
                    continue;
                }
                for j in 0..2 {
                    let fd = (b[j] - a[j]) / (2.0 * h);
                    assert!(
                        (fd - exact[j]).abs() < 1e-4 * (1.0 + exact[j].abs()),
                        "u={u} k={k}"
                    );
                }
            }
            assert_eq!(c.deriv(u, 4), [0.0, 0.0]);
        }
    }

    #[test]
    fn range_check_rejects_short_spans_in_fixed_point() {
        // Points of magnitude 100 with a span of 1/64: the second derivative is ~ 100·64²·…
        let e = 1.0 / 64.0;
        let pts = [[0.0], [100.0], [-100.0], [100.0]].map(|p: [f64; 1]| p.map(I16F16::from_num));
        let t = [0., 0., 0., e, 1., 1., 1.].map(I16F16::from_num);
        assert_eq!(
            BSpline::<[I16F16; 1], 4, 8>::new(2, &pts, &t).unwrap_err(),
            Error::OutOfRange
        );
        // The same curve fits I32F32.
        let pts = [[0.0], [100.0], [-100.0], [100.0]].map(|p: [f64; 1]| p.map(I32F32::from_num));
        let t = [0., 0., 0., e, 1., 1., 1.].map(I32F32::from_num);
        let c = BSpline::<[I32F32; 1], 4, 8>::new(2, &pts, &t).unwrap();
        assert!(c.deriv(I32F32::from_num(e / 2.0), 2)[0].to_f64().abs() > 1000.0);
        let (lo, hi) = c.domain();
        assert!(lo < hi);
    }
}
