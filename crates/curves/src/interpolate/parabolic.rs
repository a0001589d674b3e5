//! Parabolic blending (Overhauser, "Analytic definition of curves and surfaces by parabolic
//! blending", Ford Motor Company, Scientific Research Staff, 1968; Rogers & Adams,
//! *Mathematical Elements for Computer Graphics*, McGraw-Hill 1976, pp. 133–138): between two
//! points, the weighted mean of the two overlapping parabolas (Lagrange polynomials of degree
//! 2) through three consecutive points.
//!
//! With `n + 1` points `P_0 … P_n`, node `i` at `u = i`, and on piece `r` the local
//! parameter `t = u − r ∈ [0, 1]`:
//!
//! - `S_0(t) = P_0·(t−1)(t−2)/2 − P_1·t(t−2) + P_2·t(t−1)/2` (the parabola through
//!   `P_0, P_1, P_2`, kept without blending),
//! - `S_r(t) = (1−t)·(P_{r−1}·t(t−1)/2 − P_r·(t+1)(t−1) + P_{r+1}·t(t+1)/2)
//!   + t·(P_r·(t−1)(t−2)/2 − P_{r+1}·t(t−2) + P_{r+2}·t(t−1)/2)` for `0 < r < n − 1`,
//! - `S_{n−1}(t) = P_{n−2}·t(t−1)/2 − P_{n−1}·(t+1)(t−1) + P_n·t(t+1)/2` (the parabola
//!   through the last three points).
//!
//! Each piece is a cubic with `S_r(0) = P_r`, `S_r(1) = P_{r+1}`, so it is the Hermite piece
//! with the end derivatives of the blend: `S_r'(0) = (P_{r+1} − P_{r−1})/2` and
//! `S_r'(1) = (P_{r+2} − P_r)/2` inside (the uniform Catmull-Rom tangents), and the parabolas'
//! `(−3P_0 + 4P_1 − P_2)/2` and `(P_{n−2} − 4P_{n−1} + 3P_n)/2` at the two ends. That is how
//! it is stored and evaluated: as a [`HermiteSpline`] (Bézier form, de Casteljau), which
//! makes the C¹ continuity exact by construction.

use heapless::Vec;

use super::hermite::{HermiteSpline, check_points};
use super::parameterization::Parameterization;
use crate::error::Error;
use crate::point::{MAX_DIM, Point};

/// A parabolic blending (Overhauser) curve through at least 3 points, node `i` at `u = i`,
/// domain `[0, n]`; C¹, piecewise cubic (quadratic on the first and last piece).
///
/// ```
/// use strak_curves::{ParabolicBlend, ParamCurve, ParamCurveDeriv};
///
/// let pts = [[0.0_f64, 0.0], [1.0, 1.0], [2.0, 0.0], [3.0, 1.0]];
/// let c = ParabolicBlend::<_, 8>::new(&pts).unwrap();
/// assert_eq!(c.domain(), (0.0, 3.0));
/// assert_eq!(c.eval(2.0), [2.0, 0.0]);
/// // S_0 is the parabola through P0, P1, P2 at t = 0, 1, 2: S_0(1/2) = (1/2, 3/4).
/// let p = c.eval(0.5);
/// assert!((p[0] - 0.5).abs() < 1e-15 && (p[1] - 0.75).abs() < 1e-15);
/// assert_eq!(c.deriv(1.0, 1), [1.0, 0.0]);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct ParabolicBlend<P: Point, const N: usize> {
    hermite: HermiteSpline<P, N>,
}

impl<P: Point, const N: usize> ParabolicBlend<P, N> {
    /// The parabolic blending curve through `points` (at least 3).
    ///
    /// The node tangents are computed in `f64` and rounded once to the scalar type.
    ///
    /// # Errors
    /// [`Error::TooFewPoints`] below 3 points, [`Error::CapacityExceeded`] above `N`,
    /// [`Error::NonFinite`], [`Error::OutOfRange`] when a node `n`, a tangent or a value an
    /// evaluation can produce does not fit the scalar type.
    ///
    /// ```
    /// use strak_curves::{Error, ParabolicBlend};
    ///
    /// let e = ParabolicBlend::<_, 8>::new(&[[0.0_f32], [1.0]]);
    /// assert_eq!(e, Err(Error::TooFewPoints { required: 3, found: 2 }));
    /// ```
    pub fn new(points: &[P]) -> Result<Self, Error> {
        check_points::<P, N>(points, 3)?;
        let n = points.len() - 1;
        let mut tangents: Vec<P, N> = Vec::new();
        for i in 0..=n {
            let f = |j: usize| points.get(j).map_or([0.0; MAX_DIM], |p| p.to_f64_array());
            let m: [f64; MAX_DIM] = if i == 0 {
                let (p0, p1, p2) = (f(0), f(1), f(2));
                core::array::from_fn(|c| (-3.0 * p0[c] + 4.0 * p1[c] - p2[c]) / 2.0)
            } else if i == n {
                let (a, b, c2) = (f(n - 2), f(n - 1), f(n));
                core::array::from_fn(|c| (a[c] - 4.0 * b[c] + 3.0 * c2[c]) / 2.0)
            } else {
                let (a, b) = (f(i - 1), f(i + 1));
                core::array::from_fn(|c| (b[c] - a[c]) / 2.0)
            };
            let m = P::from_f64_slice(&m[..P::DIM]).ok_or(Error::OutOfRange)?;
            tangents.push(m).map_err(|_| Error::CapacityExceeded {
                capacity: N,
                required: points.len(),
            })?;
        }
        let hermite = HermiteSpline::new(points, &tangents, Parameterization::Uniform)?;
        Ok(Self { hermite })
    }

    /// The interpolated points `P_0 … P_n`.
    pub fn points(&self) -> &[P] {
        self.hermite.points()
    }

    /// The curve as a Hermite spline (nodes `0, 1, …, n` and the blend's node derivatives).
    pub fn as_hermite(&self) -> &HermiteSpline<P, N> {
        &self.hermite
    }
}

super::hermite::curve_via_hermite!(ParabolicBlend);

#[cfg(test)]
#[allow(clippy::needless_range_loop, clippy::cast_possible_truncation)]
mod tests {
    use super::*;
    use crate::curve::{ParamCurve, ParamCurveDeriv};
    use crate::scalar::{I16F16, I32F32};

    const PTS: [[f64; 2]; 6] = [
        [0.0, 0.0],
        [1.0, 2.0],
        [3.0, 3.0],
        [4.0, 0.0],
        [6.0, 1.0],
        [7.0, -2.0],
    ];

    /// The blend of the two parabolas, literally (module docs).
    fn blend_s(p: &[[f64; 2]], r: usize, t: f64) -> [f64; 2] {
        let n = p.len() - 1;
        let first = |a: [f64; 2], b: [f64; 2], c: [f64; 2], k: usize| {
            a[k] * (t - 1.0) * (t - 2.0) / 2.0 - b[k] * t * (t - 2.0) + c[k] * t * (t - 1.0) / 2.0
        };
        let centred = |a: [f64; 2], b: [f64; 2], c: [f64; 2], k: usize| {
            a[k] * t * (t - 1.0) / 2.0 - b[k] * (t + 1.0) * (t - 1.0) + c[k] * t * (t + 1.0) / 2.0
        };
        core::array::from_fn(|k| {
            if r == 0 {
                first(p[0], p[1], p[2], k)
            } else if r == n - 1 {
                centred(p[n - 2], p[n - 1], p[n], k)
            } else {
                (1.0 - t) * centred(p[r - 1], p[r], p[r + 1], k)
                    + t * first(p[r], p[r + 1], p[r + 2], k)
            }
        })
    }

    #[test]
    fn matches_blend_formulas() {
        let c = ParabolicBlend::<_, 8>::new(&PTS).unwrap();
        assert_eq!(c.domain(), (0.0, 5.0));
        assert_eq!(c.piece_count(), 5);
        for r in 0..5 {
            for j in 0..=10 {
                let t = f64::from(j) / 10.0;
                let want = blend_s(&PTS, r, t);
                let got = c.eval(r as f64 + t);
                for k in 0..2 {
                    assert!(
                        (got[k] - want[k]).abs() < 1e-13,
                        "r={r} t={t}: {got:?} vs {want:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn interpolates_and_is_c1() {
        let c = ParabolicBlend::<_, 8>::new(&PTS).unwrap();
        assert_eq!(c.points(), &PTS);
        for (i, p) in PTS.iter().enumerate() {
            assert_eq!(c.eval(i as f64), *p);
        }
        // d/dt S_r(1) = d/dt S_{r+1}(0), by numerical differentiation of the blend formulas
        // and by the curve's own derivatives.
        let h = 1e-6;
        for r in 0..4 {
            let left = c.as_hermite().segment(r).unwrap().deriv((r + 1) as f64, 1);
            let right = c.deriv((r + 1) as f64, 1);
            let left_fd = blend_s(&PTS, r, 1.0);
            let left_fd2 = blend_s(&PTS, r, 1.0 - h);
            let right_fd = blend_s(&PTS, r + 1, h);
            let right_fd0 = blend_s(&PTS, r + 1, 0.0);
            for k in 0..2 {
                assert!((left[k] - right[k]).abs() < 1e-13);
                let l = (left_fd[k] - left_fd2[k]) / h;
                let rr = (right_fd[k] - right_fd0[k]) / h;
                assert!((l - rr).abs() < 1e-4, "r={r}: {l} vs {rr}");
                assert!((l - left[k]).abs() < 1e-4);
            }
        }
    }

    #[test]
    fn end_pieces_are_parabolas() {
        let c = ParabolicBlend::<_, 8>::new(&PTS).unwrap();
        assert_eq!(c.deriv(0.5, 3), [0.0, 0.0]);
        assert_eq!(c.deriv(4.5, 3), [0.0, 0.0]);
        // S_0'' = P0 − 2P1 + P2 = (1, −1)
        assert_eq!(c.deriv(0.25, 2), [1.0, -1.0]);
        // inner pieces are true cubics
        assert_ne!(c.deriv(2.5, 3), [0.0, 0.0]);
    }

    #[test]
    fn three_points_give_one_parabola() {
        let pts = [[0.0_f64, 0.0], [1.0, 1.0], [2.0, 0.0]];
        let c = ParabolicBlend::<_, 3>::new(&pts).unwrap();
        for j in 0..=20 {
            let u = f64::from(j) / 10.0;
            let p = c.eval(u);
            assert!((p[0] - u).abs() < 1e-14 && (p[1] - u * (2.0 - u)).abs() < 1e-14);
        }
    }

    #[test]
    fn fixed_point_matches_f64() {
        let c = ParabolicBlend::<_, 8>::new(&PTS).unwrap();
        let p32 = PTS.map(|p| p.map(I32F32::from_num));
        let p16 = PTS.map(|p| p.map(I16F16::from_num));
        let c32 = ParabolicBlend::<_, 8>::new(&p32).unwrap();
        let c16 = ParabolicBlend::<_, 8>::new(&p16).unwrap();
        for j in 0..=50 {
            let u = f64::from(j) / 10.0;
            for k in 0..=2 {
                let want = c.deriv(u, k);
                let a = c32.deriv(I32F32::from_num(u), k);
                let b = c16.deriv(I16F16::from_num(u), k);
                for i in 0..2 {
                    assert!((a[i].to_num::<f64>() - want[i]).abs() < 1e-8);
                    assert!((b[i].to_num::<f64>() - want[i]).abs() < 1e-3);
                }
            }
        }
    }

    #[test]
    fn errors() {
        assert_eq!(
            ParabolicBlend::<_, 8>::new(&PTS[..2]),
            Err(Error::TooFewPoints {
                required: 3,
                found: 2
            })
        );
        assert_eq!(
            ParabolicBlend::<_, 4>::new(&PTS),
            Err(Error::CapacityExceeded {
                capacity: 4,
                required: 6
            })
        );
        assert_eq!(
            ParabolicBlend::<_, 8>::new(&[[0.0], [f64::NAN], [1.0]]),
            Err(Error::NonFinite)
        );
        let f = |x: i32| [I16F16::from_num(x)];
        assert_eq!(
            ParabolicBlend::<_, 8>::new(&[f(0), f(12000), f(0)]),
            Err(Error::OutOfRange)
        );
    }
}
