//! Subdivision with the de Casteljau triangle and sub-segments by blossoming (Farin, *Curves
//! and Surfaces for CAGD*, 5th ed., §4.6 "Subdivision", §3.4 "The Blossom"; Ramshaw, "Blossoms
//! are polar forms", *Computer Aided Geometric Design* 6(4), 1989). Splitting a cubic at
//! `t = 1/2` gives `(P0, P01, P012, P0123)` and `(P0123, P123, P23, P3)`, built from midpoints.

use super::curve::{Bezier, casteljau_step};
use crate::point::Point;
use crate::scalar::Scalar;

impl<P: Point, const N: usize> Bezier<P, N> {
    /// Splits the curve at `t` (clamped to `[0, 1]`) into the parts over `[0, t]` and `[t, 1]`,
    /// each reparameterized to `[0, 1]`: the left part has the points `b_0^0, b_0^1, …, b_0^g`
    /// (the upper edge of the de Casteljau triangle), the right part `b_0^g, b_1^{g−1}, …, b_g^0`
    /// (its lower edge); for `t = 1/2` every point is a midpoint of two others.
    ///
    /// Both parts are built from convex combinations of the points, so their derivatives are
    /// bounded by this curve's (scaled by `tᵏ` and `(1 − t)ᵏ`); no new range check is needed.
    ///
    /// ```
    /// use strak_curves::{Bezier, ParamCurve};
    /// let c = Bezier::new([[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]])?;
    /// let (l, r) = c.subdivide(0.5);
    /// assert_eq!(l.control_points(), &[[0.0, 0.0], [0.5, 1.0], [1.25, 1.5], [2.0, 1.5]]);
    /// assert_eq!(r.control_points(), &[[2.0, 1.5], [2.75, 1.5], [3.5, 1.0], [4.0, 0.0]]);
    /// assert_eq!(l.eval(0.5), c.eval(0.25));
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn subdivide(&self, t: P::Scalar) -> (Self, Self) {
        let t = t.clamp_to(P::Scalar::ZERO, P::Scalar::ONE);
        let mut w = *self.control_points();
        let mut left = w;
        let mut right = w;
        for level in 1..N {
            let len = N - level + 1;
            casteljau_step(&mut w[..len], t);
            // level `level` now occupies w[..N − level]
            left[level] = w[0];
            right[N - 1 - level] = w[N - 1 - level];
        }
        (Self::from_valid(left), Self::from_valid(right))
    }

    /// The part of the curve over `[t0, t1]` (both clamped to `[0, 1]`) as a Bézier curve over
    /// `[0, 1]`: `s ↦ c(t0 + s (t1 − t0))`. `t0 > t1` gives the part reversed, `t0 = t1` a
    /// constant curve.
    ///
    /// The points are the blossom values `b(t0, …, t0, t1, …, t1)` (`g − i` times `t0`, `i`
    /// times `t1`), each computed by de Casteljau steps with mixed parameters — convex
    /// combinations only, without the division of a subdivide-twice approach; derivatives are
    /// scaled by `|t1 − t0|ᵏ ≤ 1`, so no new range check is needed.
    ///
    /// ```
    /// use strak_curves::{Bezier, ParamCurve};
    /// let c = Bezier::new([[0.0], [3.0], [3.0], [0.0]])?;
    /// let s = c.segment(0.25, 0.75);
    /// assert_eq!(s.eval(0.0), c.eval(0.25));
    /// assert_eq!(s.eval(0.5), c.eval(0.5));
    /// assert_eq!(s.eval(1.0), c.eval(0.75));
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn segment(&self, t0: P::Scalar, t1: P::Scalar) -> Self {
        let t0 = t0.clamp_to(P::Scalar::ZERO, P::Scalar::ONE);
        let t1 = t1.clamp_to(P::Scalar::ZERO, P::Scalar::ONE);
        let b = self.control_points();
        let points = core::array::from_fn(|i| {
            let mut w = *b;
            for (step, len) in (2..=N).rev().enumerate() {
                let t = if step < i { t1 } else { t0 };
                casteljau_step(&mut w[..len], t);
            }
            w.first().copied().unwrap_or_else(P::zero)
        });
        Self::from_valid(points)
    }
}

#[cfg(test)]
mod tests {
    use crate::{Bezier, I16F16, I32F32, ParamCurve, ParamCurveDeriv, Scalar};
    use glam::{DVec2, DVec3};

    fn sample() -> Bezier<DVec3, 5> {
        Bezier::new([
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 3.0, -1.0),
            DVec3::new(2.5, -1.0, 2.0),
            DVec3::new(4.0, 2.0, 0.5),
            DVec3::new(5.0, 0.0, 1.0),
        ])
        .unwrap()
    }

    #[test]
    fn halves_reproduce_the_curve() {
        let c = sample();
        for split in [0.5, 0.3, 0.9] {
            let (l, r) = c.subdivide(split);
            assert_eq!(l.eval(1.0), r.eval(0.0));
            for step in 0..=16 {
                let s = step as f64 / 16.0;
                assert!((l.eval(s) - c.eval(s * split)).length() < 1e-14);
                assert!((r.eval(s) - c.eval(split + s * (1.0 - split))).length() < 1e-14);
                // chain rule: l'(s) = split · c'(split · s)
                let dl = l.deriv(s, 1);
                let dc = c.deriv(s * split, 1) * split;
                assert!((dl - dc).length() < 1e-12);
            }
        }
        // The halves at t = 1/2 are built from midpoints only
        let q = [
            DVec2::new(0.0, 0.0),
            DVec2::new(2.0, 4.0),
            DVec2::new(6.0, 4.0),
            DVec2::new(8.0, 0.0),
        ];
        let c = Bezier::new(q).unwrap();
        let (l, r) = c.subdivide(0.5);
        let h = |a: DVec2, b: DVec2| (a + b) / 2.0;
        let (p01, p12, p23) = (h(q[0], q[1]), h(q[1], q[2]), h(q[2], q[3]));
        let (p012, p123) = (h(p01, p12), h(p12, p23));
        let p0123 = h(p012, p123);
        assert_eq!(l.control_points(), &[q[0], p01, p012, p0123]);
        assert_eq!(r.control_points(), &[p0123, p123, p23, q[3]]);
    }

    #[test]
    fn subdivide_at_the_ends_and_clamped() {
        let c = sample();
        let (l, r) = c.subdivide(0.0);
        assert_eq!(r, c);
        assert!(l.control_points().iter().all(|p| *p == DVec3::ZERO));
        let (l, _) = c.subdivide(1.5);
        assert_eq!(l, c);
        let k = Bezier::new([[1.0]]).unwrap();
        assert_eq!(k.subdivide(0.5), (k, k));
    }

    #[test]
    fn segment_reproduces_the_curve_piece() {
        let c = sample();
        assert_eq!(c.segment(0.0, 1.0), c);
        assert_eq!(c.segment(1.0, 0.0), c.reverse());
        let s = c.segment(0.2, 0.7);
        for step in 0..=16 {
            let u = step as f64 / 16.0;
            assert!((s.eval(u) - c.eval(0.2 + u * 0.5)).length() < 1e-14);
        }
        let (l, _) = c.subdivide(0.4);
        let s = c.segment(0.0, 0.4);
        for (a, b) in s.control_points().iter().zip(l.control_points()) {
            assert!((*a - *b).length() < 1e-14);
        }
        let point = c.segment(0.3, 0.3);
        assert!(
            point
                .control_points()
                .iter()
                .all(|p| (*p - c.eval(0.3)).length() < 1e-14)
        );
    }

    #[test]
    fn fixed_point_subdivision_agrees_with_f64() {
        let q = [[0.0, 0.0], [1.0, 3.0], [2.5, -1.0], [4.0, 2.0]];
        let cf = Bezier::new(q).unwrap();
        let cx = Bezier::new(q.map(|p| p.map(I16F16::from_num))).unwrap();
        let cy = Bezier::new(q.map(|p| p.map(I32F32::from_num))).unwrap();
        let (lf, rf) = cf.subdivide(0.375);
        let (lx, rx) = cx.subdivide(I16F16::from_num(0.375));
        let (ly, ry) = cy.subdivide(I32F32::from_num(0.375));
        let sf = cf.segment(0.25, 0.625);
        let sx = cx.segment(I16F16::from_num(0.25), I16F16::from_num(0.625));
        for i in 0..4 {
            for d in 0..2 {
                let tol = 8.0 * <I16F16 as Scalar>::EPSILON;
                assert!(
                    (lx.control_points()[i][d].to_f64() - lf.control_points()[i][d]).abs() < tol
                );
                assert!(
                    (rx.control_points()[i][d].to_f64() - rf.control_points()[i][d]).abs() < tol
                );
                assert!(
                    (sx.control_points()[i][d].to_f64() - sf.control_points()[i][d]).abs() < tol
                );
                let toly = 8.0 * <I32F32 as Scalar>::EPSILON;
                assert!(
                    (ly.control_points()[i][d].to_f64() - lf.control_points()[i][d]).abs() < toly
                );
                assert!(
                    (ry.control_points()[i][d].to_f64() - rf.control_points()[i][d]).abs() < toly
                );
            }
        }
    }
}
