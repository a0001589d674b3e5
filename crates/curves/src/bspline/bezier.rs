//! Conversion of a B-spline into its Bézier segments.
//!
//! Inserting every knot of the domain until it has multiplicity `g` turns the de Boor points
//! into Bézier points: the piece on `[u_s, u_{s+1}]` is the Bézier curve of degree `g` whose
//! points are `b_j = f(u_s^{g−j}, u_{s+1}^j)`, the blossom (polar form) of the piece with
//! `g − j` arguments `u_s` and `j` arguments `u_{s+1}`. The blossom is de Boor's triangle with
//! the inserted knot at each level, i.e. exactly the convex combinations that repeated knot
//! insertion (Boehm) computes for that span; working span by span needs no intermediate curve
//! with `(g + 1)·n` points.

use heapless::Vec;

use super::curve::BSpline;
use super::knots::{BSPLINE_MAX_DEGREE, KnotVector, LOCAL, ratio};
use crate::error::Error;
use crate::point::Point;

impl<P: Point, const N: usize, const M: usize> BSpline<P, N, M> {
    /// The Bézier points of every piece, in order: segment `i` is the Bézier curve of degree
    /// `g` with points `[b_0, …, b_g]` (`NB = g + 1`) on the parameter interval
    /// [`piece_domain(i)`](crate::ParamCurve::piece_domain), reparameterized to `[0, 1]`.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] when `NB ≠ g + 1`; [`Error::CapacityExceeded`] when the curve
    /// has more than `K` pieces.
    ///
    /// ```
    /// use strak_curves::{BSpline, ParamCurve};
    ///
    /// let d = [[0.0], [3.0], [6.0], [3.0], [0.0]];
    /// let c = BSpline::<[f64; 1], 8, 16>::clamped_uniform(2, &d, 0.0, 3.0).unwrap();
    /// let segs = c.to_bezier_segments::<3, 4>().unwrap();
    /// assert_eq!(segs.len(), 3);
    /// assert_eq!(segs[0], [[0.0], [3.0], [4.5]]);
    /// assert_eq!(segs[1], [[4.5], [6.0], [4.5]]);
    /// assert_eq!(segs[1][0], c.eval(1.0));
    /// ```
    pub fn to_bezier_segments<const NB: usize, const K: usize>(
        &self,
    ) -> Result<Vec<[P; NB], K>, Error> {
        let g = self.degree();
        if NB != g + 1 {
            return Err(Error::LengthMismatch {
                expected: g + 1,
                found: NB,
            });
        }
        let kv = self.knot_vector();
        let count = kv.piece_count();
        if count > K {
            return Err(Error::CapacityExceeded {
                capacity: K,
                required: count,
            });
        }
        let mut out = Vec::new();
        for s in g..kv.control_point_count() {
            let (a, b) = (kv.knot(s), kv.knot(s + 1));
            if a >= b {
                continue;
            }
            let local = self.local_points(s);
            let seg: [P; NB] = core::array::from_fn(|j| blossom(kv, s, local, g - j.min(g), a, b));
            out.push(seg).map_err(|_| Error::CapacityExceeded {
                capacity: K,
                required: count,
            })?;
        }
        Ok(out)
    }
}

/// The blossom `f(a^{na}, b^{g−na})` of the piece on span `s` (de Boor's triangle with the
/// argument `a` at the first `na` levels and `b` at the others).
fn blossom<P: Point, const M: usize>(
    kv: &KnotVector<P::Scalar, M>,
    s: usize,
    mut d: [P; LOCAL],
    na: usize,
    a: P::Scalar,
    b: P::Scalar,
) -> P {
    let g = kv.degree().min(BSPLINE_MAX_DEGREE);
    for r in 1..=g {
        let x = if r <= na { a } else { b };
        for j in (r..=g).rev() {
            let i = (s + j).saturating_sub(g);
            let lo = kv.knot(i);
            let alpha = ratio(x - lo, kv.knot(i + g + 1 - r) - lo);
            d[j] = d[j - 1].lerp(d[j], alpha);
        }
    }
    d[g]
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;
    use crate::curve::{ParamCurve, ParamCurveDeriv};
    use crate::scalar::{I16F16, Scalar};

    type C2 = BSpline<[f64; 2], 16, 32>;
    const D: [[f64; 2]; 7] = [
        [0.0, 0.0],
        [1.0, 3.0],
        [3.0, 4.0],
        [5.0, 1.0],
        [6.0, -2.0],
        [8.0, 0.5],
        [9.0, 3.0],
    ];

    /// De Casteljau on an array of Bézier points.
    fn casteljau<const NB: usize>(b: &[[f64; 2]; NB], t: f64) -> [f64; 2] {
        let mut p = *b;
        for r in 1..NB {
            for j in 0..NB - r {
                p[j] = [
                    (1.0 - t) * p[j][0] + t * p[j + 1][0],
                    (1.0 - t) * p[j][1] + t * p[j + 1][1],
                ];
            }
        }
        p[0]
    }

    fn check<const NB: usize>(c: &C2) {
        let segs = c.to_bezier_segments::<NB, 16>().unwrap();
        assert_eq!(segs.len(), c.piece_count());
        for (i, seg) in segs.iter().enumerate() {
            let (a, b) = c.piece_domain(i);
            for j in 0..=50 {
                let t = f64::from(j) / 50.0;
                let u = a + (b - a) * t;
                let (x, y) = (casteljau(seg, t), c.eval(u));
                assert!(
                    (x[0] - y[0]).abs() < 1e-12 && (x[1] - y[1]).abs() < 1e-12,
                    "seg {i} t {t}"
                );
            }
            // End tangent of the Bézier segment: g·(b_1 − b_0)/(b − a) = c'(a).
            let g = (NB - 1) as f64;
            let d = c.deriv(a, 1);
            let e = [
                g * (seg[1][0] - seg[0][0]) / (b - a),
                g * (seg[1][1] - seg[0][1]) / (b - a),
            ];
            assert!((d[0] - e[0]).abs() < 1e-10 && (d[1] - e[1]).abs() < 1e-10);
        }
        // Consecutive segments join.
        for w in segs.windows(2) {
            assert_eq!(w[0][NB - 1], w[1][0]);
        }
    }

    #[test]
    fn bezier_segments_reproduce_the_curve() {
        check::<4>(&C2::new(3, &D, &[0., 0., 0., 0., 1., 2., 3., 4., 4., 4., 4.]).unwrap());
        check::<4>(&C2::new(3, &D, &[-3., -2., -1., 0., 0.5, 2., 2.5, 3., 4., 5., 6.]).unwrap());
        check::<3>(
            &C2::new(2, &D, &[0., 0., 0., 1., 1., 2., 3., 3., 3., 3.]).unwrap_or_else(|_| {
                C2::new(2, &D, &[0., 0., 0., 1., 1., 2., 3., 4., 4., 4.]).unwrap()
            }),
        );
        check::<2>(&C2::new(1, &D, &[0., 0., 1., 2., 3., 4., 5., 6., 6.]).unwrap());
        check::<4>(&C2::closed(3, &D, None).unwrap());
    }

    #[test]
    fn bernstein_curve_is_its_own_bezier() {
        let c = C2::new(3, &D[..4], &[0., 0., 0., 0., 1., 1., 1., 1.]).unwrap();
        let segs = c.to_bezier_segments::<4, 1>().unwrap();
        assert_eq!(segs[0], [D[0], D[1], D[2], D[3]]);
    }

    #[test]
    fn fixed_point_segments() {
        let d = D.map(|p| p.map(I16F16::from_num));
        let c = BSpline::<[I16F16; 2], 8, 16>::clamped_uniform(3, &d, I16F16::ZERO, I16F16::ONE)
            .unwrap();
        let segs = c.to_bezier_segments::<4, 4>().unwrap();
        assert_eq!(segs.len(), 4);
        assert_eq!(segs[0][0], d[0]);
        assert_eq!(segs[3][3], d[6]);
        let (a, _) = c.piece_domain(2);
        let p = c.eval(a);
        for j in 0..2 {
            assert!((segs[2][0][j] - p[j]).to_f64().abs() < 1e-4);
        }
    }

    #[test]
    fn errors() {
        let c = C2::clamped_uniform(3, &D, 0.0, 1.0).unwrap();
        assert_eq!(
            c.to_bezier_segments::<3, 8>().unwrap_err(),
            Error::LengthMismatch {
                expected: 4,
                found: 3
            }
        );
        assert_eq!(
            c.to_bezier_segments::<4, 3>().unwrap_err(),
            Error::CapacityExceeded {
                capacity: 3,
                required: 4
            }
        );
    }
}
