//! Knot insertion (Boehm's algorithm): one more knot and one more de Boor point, same curve.
//!
//! Inserting `ū` into the span `[u_s, u_{s+1})` of a B-spline of degree `g` replaces the
//! de Boor points `d_{s−g+1}, …, d_s` by
//!
//! ```text
//! d̄_i = (1 − α_i)·d_{i−1} + α_i·d_i,   α_i = (ū − u_i)/(u_{i+g} − u_i),   s − g + 1 ≤ i ≤ s
//! ```
//!
//! keeps `d_0, …, d_{s−g}` and shifts `d_s, …, d_{K−1}` by one index. Every `α_i ∈ [0, 1]`
//! (the divisor contains the non-empty span `s`), so the new points are convex combinations
//! of the old ones.

use super::curve::BSpline;
use super::knots::ratio;
use crate::error::Error;
use crate::point::Point;
use crate::scalar::Scalar;

impl<P: Point, const N: usize, const M: usize> BSpline<P, N, M> {
    /// The same curve with the knot `u` inserted once (Boehm), as a new curve with one more de
    /// Boor point and one more knot. `u` must lie in the domain `[u_g, u_K]`; the knot may be
    /// inserted until its multiplicity is `g` (inner knots) or `g + 1` (knots at the ends of the
    /// knot vector). Inserting into a closed curve gives an open representation of the same
    /// closed curve ([`BSpline::is_closed`] is `false`).
    ///
    /// # Errors
    /// [`Error::NonFinite`]; [`Error::InvalidArgument`] when `u` is outside the domain;
    /// [`Error::CapacityExceeded`] when `N` or `M` has no room for one more point or knot;
    /// [`Error::KnotMultiplicity`] when `u` already has the largest allowed multiplicity;
    /// [`Error::OutOfRange`] (re-checked, cannot normally occur).
    ///
    /// ```
    /// use strak_curves::{BSpline, ParamCurve};
    ///
    /// let d = [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]];
    /// let c = BSpline::<[f64; 2], 8, 16>::clamped_uniform(3, &d, 0.0, 1.0).unwrap();
    /// let r = c.insert_knot(0.5).unwrap();
    /// assert_eq!(r.control_points().len(), 5);
    /// assert_eq!(r.knots(), &[0., 0., 0., 0., 0.5, 1., 1., 1., 1.]);
    /// let (a, b) = (r.eval(0.3), c.eval(0.3));
    /// assert!((a[0] - b[0]).abs() < 1e-15 && (a[1] - b[1]).abs() < 1e-15);
    /// ```
    pub fn insert_knot(&self, u: P::Scalar) -> Result<Self, Error> {
        if !u.is_finite() {
            return Err(Error::NonFinite);
        }
        let (lo, hi) = self.domain();
        if u < lo || u > hi {
            return Err(Error::InvalidArgument);
        }
        let points = self.control_points();
        let knots = self.knots();
        let count = points.len();
        if count + 1 > N {
            return Err(Error::CapacityExceeded {
                capacity: N,
                required: count + 1,
            });
        }
        if knots.len() + 1 > M {
            return Err(Error::CapacityExceeded {
                capacity: M,
                required: knots.len() + 1,
            });
        }
        let g = self.degree();
        let kv = self.knot_vector();
        let s = kv.span(u);
        let mut new_points: heapless::Vec<P, N> = heapless::Vec::new();
        for i in 0..=count {
            let p = if i + g <= s {
                points.get(i).copied()
            } else if i > s {
                points.get(i - 1).copied()
            } else {
                let lo = kv.knot(i);
                let alpha = ratio(u - lo, kv.knot(i + g) - lo);
                match (points.get(i - 1), points.get(i)) {
                    (Some(a), Some(b)) => Some(a.lerp(*b, alpha)),
                    _ => None,
                }
            };
            let p = p.ok_or(Error::InvalidArgument)?;
            new_points.push(p).map_err(|_| Error::CapacityExceeded {
                capacity: N,
                required: count + 1,
            })?;
        }
        let mut new_knots: heapless::Vec<P::Scalar, M> = heapless::Vec::new();
        for (i, &k) in knots.iter().enumerate() {
            new_knots.push(k).map_err(|_| Error::CapacityExceeded {
                capacity: M,
                required: knots.len() + 1,
            })?;
            if i == s {
                new_knots.push(u).map_err(|_| Error::CapacityExceeded {
                    capacity: M,
                    required: knots.len() + 1,
                })?;
            }
        }
        Self::new(g, &new_points, &new_knots)
    }
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;
    use crate::curve::{ParamCurve, ParamCurveDeriv};
    use crate::scalar::I32F32;

    type C2 = BSpline<[f64; 2], 16, 32>;
    const D: [[f64; 2]; 6] = [
        [0.0, 0.0],
        [1.0, 3.0],
        [3.0, 4.0],
        [5.0, 1.0],
        [6.0, -2.0],
        [8.0, 0.5],
    ];

    fn close(a: [f64; 2], b: [f64; 2], tol: f64) -> bool {
        (a[0] - b[0]).abs() <= tol && (a[1] - b[1]).abs() <= tol
    }

    fn assert_same(a: &C2, b: &C2) {
        let (lo, hi) = a.domain();
        assert_eq!(a.domain(), b.domain());
        for i in 0..=300 {
            let u = lo + (hi - lo) * f64::from(i) / 300.0;
            for k in 0..=a.degree() {
                let (x, y) = (a.deriv(u, k), b.deriv(u, k));
                assert!(
                    close(x, y, 1e-10 * (1.0 + x[0].abs() + x[1].abs())),
                    "u={u} k={k} {x:?} {y:?}"
                );
            }
        }
    }

    #[test]
    fn insertion_preserves_the_curve() {
        let c = C2::new(3, &D, &[0., 0., 0., 0., 0.7, 1.2, 2., 2., 2., 2.]).unwrap();
        let mut r = c.clone();
        for u in [0.1, 0.7, 0.7, 1.9, 1.99, 0.01, 1.2] {
            r = r.insert_knot(u).unwrap();
            assert_same(&c, &r);
        }
        assert_eq!(r.control_points().len(), D.len() + 7);
        assert_eq!(r.knot_vector().multiplicity(0.7), 3);
        // Multiplicity g = 3 at 0.7: the curve passes through a de Boor point there.
        let hit = r
            .control_points()
            .iter()
            .any(|p| close(*p, c.eval(0.7), 1e-12));
        assert!(hit);
    }

    #[test]
    fn insertion_into_unclamped_and_closed_curves() {
        let c = C2::new(2, &D, &[-2., -1., 0., 1., 2., 3., 4., 5., 6.]).unwrap();
        let r = c
            .insert_knot(2.5)
            .unwrap()
            .insert_knot(4.0)
            .unwrap()
            .insert_knot(0.0)
            .unwrap();
        assert_same(&c, &r);
        let c = C2::closed(3, &D, None).unwrap();
        let r = c.insert_knot(0.25).unwrap().insert_knot(1.0).unwrap();
        assert!(!r.is_closed());
        assert_same(&c, &r);
    }

    #[test]
    fn insertion_in_fixed_point() {
        let d = D.map(|p| p.map(I32F32::from_num));
        let c = BSpline::<[I32F32; 2], 8, 16>::clamped_uniform(3, &d, I32F32::ZERO, I32F32::ONE)
            .unwrap();
        let r = c.insert_knot(I32F32::from_num(0.3)).unwrap();
        for i in 0..=64 {
            let u = I32F32::from_num(i) / 64;
            let (a, b) = (c.eval(u), r.eval(u));
            for j in 0..2 {
                assert!((a[j] - b[j]).to_f64().abs() < 1e-8);
            }
        }
    }

    #[test]
    fn insertion_errors() {
        let c = BSpline::<[f64; 2], 6, 10>::clamped_uniform(3, &D, 0.0, 1.0).unwrap();
        assert_eq!(
            c.insert_knot(0.5).unwrap_err(),
            Error::CapacityExceeded {
                capacity: 6,
                required: 7
            }
        );
        let c = BSpline::<[f64; 2], 8, 10>::clamped_uniform(3, &D, 0.0, 1.0).unwrap();
        assert_eq!(
            c.insert_knot(0.5).unwrap_err(),
            Error::CapacityExceeded {
                capacity: 10,
                required: 11
            }
        );
        let c = C2::clamped_uniform(3, &D, 0.0, 1.0).unwrap();
        assert_eq!(c.insert_knot(1.5).unwrap_err(), Error::InvalidArgument);
        assert_eq!(c.insert_knot(f64::NAN).unwrap_err(), Error::NonFinite);
        // Clamped end already has multiplicity g + 1.
        assert_eq!(
            c.insert_knot(0.0).unwrap_err(),
            Error::KnotMultiplicity { index: 0 }
        );
        // Inner knot 1/3 up to multiplicity g = 3, then no more.
        let third = c.knots()[4];
        let r = c.insert_knot(third).unwrap().insert_knot(third).unwrap();
        assert_eq!(r.knot_vector().multiplicity(third), 3);
        assert_eq!(
            r.insert_knot(third).unwrap_err(),
            Error::KnotMultiplicity { index: 4 }
        );
    }
}
