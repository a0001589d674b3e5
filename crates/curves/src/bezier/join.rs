//! Joining Bézier segments with C¹ or G¹ continuity (Farin, *Curves and Surfaces for CAGD*,
//! 5th ed., §7.2 "Smoothness Conditions", §7.3 "C1 and C2 Continuity"; for geometric
//! continuity Barsky & DeRose, "Geometric Continuity of Parametric Curves", *IEEE Computer
//! Graphics and Applications* 9(6), 1989).
//!
//! A segment `b` of degree `g` ends with the derivative `c_b'(1) = g (b_g − b_{g−1})`; a
//! following segment `c` of degree `h` starts with `c_c'(0) = h (c_1 − c_0)`.
//! * C⁰: `c_0 = b_g`.
//! * C¹ (parametric): additionally `h (c_1 − c_0) = g (b_g − b_{g−1})`, i.e.
//!   `c_1 = b_g + (g/h)(b_g − b_{g−1})` — for equal degrees `b_{g−1}, b_g, c_1` are collinear
//!   and equally spaced.
//! * G¹ (geometric): `c_1 − c_0` only has the direction of `b_g − b_{g−1}` (the tangent
//!   vectors agree up to a factor `k > 0`); its length is free.
//!
//! Both functions return the *following* segment adjusted: `c_0` and `c_1` replaced, all other
//! points kept (for a line, `M = 2`, that moves its end point).

use super::curve::Bezier;
use crate::error::Error;
use crate::point::Point;
use crate::scalar::Scalar;

/// The last two points of `b` in `f64` (`b_{g−1}` is `b_g` for degree 0).
fn end_pair<P: Point, const N: usize>(b: &Bezier<P, N>) -> (P, P) {
    let pts = b.control_points();
    let last = pts.last().copied().unwrap_or_else(P::zero);
    let prev = N
        .checked_sub(2)
        .and_then(|i| pts.get(i))
        .copied()
        .unwrap_or(last);
    (prev, last)
}

/// `next` with `c_0 = start` and `c_1 = start + step`, validated.
fn with_start<P: Point, const M: usize>(
    next: &Bezier<P, M>,
    start: P,
    step: impl Fn(usize) -> f64,
) -> Result<Bezier<P, M>, Error> {
    let mut ok = true;
    let c1 = P::from_coords(|c| {
        let v = start.coord(c).to_f64() + step(c);
        P::Scalar::from_f64(v).unwrap_or_else(|| {
            ok = false;
            P::Scalar::ZERO
        })
    });
    if !ok {
        return Err(Error::OutOfRange);
    }
    let mut pts = *next.control_points();
    if let [c0, c1_slot, ..] = pts.as_mut_slice() {
        *c0 = start;
        *c1_slot = c1;
    }
    Bezier::new(pts)
}

impl<P: Point, const N: usize> Bezier<P, N> {
    /// The segment `next` adjusted to join this one with C¹ continuity: `c_0 = b_g` and
    /// `c_1 = b_g + (g/h)(b_g − b_{g−1})` (`g`, `h` the degrees of `self` and `next`), so that
    /// the first derivatives agree at the joint. The other points of `next` are kept.
    ///
    /// A zero end tangent (`b_{g−1} = b_g`, or degree 0) is allowed: then `c_1 = c_0`, both
    /// derivatives vanish.
    ///
    /// # Errors
    /// [`Error::TooFewPoints`] when `next` has degree 0 (`M < 2`, no inner point to place),
    /// [`Error::OutOfRange`] when the new point or the adjusted curve does not fit the scalar
    /// type.
    ///
    /// ```
    /// use strak_curves::{Bezier, ParamCurveDeriv};
    /// let a = Bezier::new([[0.0, 0.0], [1.0, 1.0], [2.0, 1.0], [3.0, 0.0]])?;
    /// let b = Bezier::new([[9.0, 9.0], [9.0, 9.0], [5.0, 0.0]])?;
    /// let j = a.join_c1(&b)?;
    /// // c_1 = b_3 + (3/2)(b_3 − b_2) = (4.5, −1.5)
    /// assert_eq!(j.control_points(), &[[3.0, 0.0], [4.5, -1.5], [5.0, 0.0]]);
    /// assert_eq!(j.deriv(0.0, 1), a.deriv(1.0, 1));
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn join_c1<const M: usize>(&self, next: &Bezier<P, M>) -> Result<Bezier<P, M>, Error> {
        if M < 2 {
            return Err(Error::TooFewPoints {
                required: 2,
                found: M,
            });
        }
        let g = N.saturating_sub(1) as f64;
        let h = (M - 1) as f64;
        let (prev, last) = end_pair(self);
        with_start(next, last, |c| {
            (last.coord(c).to_f64() - prev.coord(c).to_f64()) * g / h
        })
    }

    /// The segment `next` adjusted to join this one with G¹ continuity: `c_0 = b_g` and
    /// `c_1 = b_g + L · (b_g − b_{g−1}) / |b_g − b_{g−1}|`, with the tangent length `L` given
    /// by `tangent_length`, or, for `None`, the length `|c_1 − c_0|` of `next`'s own first
    /// leg (the tangent direction is imposed, its length kept). The other points of `next`
    /// are kept.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the end tangent of `self` is zero (`b_{g−1} = b_g` or
    /// degree 0: no direction), when `tangent_length` is not positive, or when it is `None`
    /// and `next` has `c_1 = c_0`; [`Error::NonFinite`] for a NaN/∞ `tangent_length`;
    /// [`Error::TooFewPoints`] when `next` has degree 0; [`Error::OutOfRange`] when the new
    /// point or the adjusted curve does not fit the scalar type.
    ///
    /// ```
    /// use strak_curves::Bezier;
    /// let a = Bezier::new([[0.0, 0.0], [1.0, 1.0], [2.0, 1.0], [3.0, 0.0]])?;
    /// let b = Bezier::new([[3.0, 0.0], [3.0, 2.0], [5.0, 0.0], [6.0, 0.0]])?;
    /// // keep the leg length 2, impose the direction (1, −1)/√2
    /// let j = a.join_g1(&b, None)?;
    /// let c1 = j.control_points()[1];
    /// assert!((c1[0] - (3.0 + 2.0_f64.sqrt())).abs() < 1e-15);
    /// assert!((c1[1] + 2.0_f64.sqrt()).abs() < 1e-15);
    /// // or choose the length
    /// let j = a.join_g1(&b, Some(0.5))?;
    /// assert!((j.control_points()[1][0] - (3.0 + 0.5 / 2.0_f64.sqrt())).abs() < 1e-15);
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn join_g1<const M: usize>(
        &self,
        next: &Bezier<P, M>,
        tangent_length: Option<P::Scalar>,
    ) -> Result<Bezier<P, M>, Error> {
        if M < 2 {
            return Err(Error::TooFewPoints {
                required: 2,
                found: M,
            });
        }
        let (prev, last) = end_pair(self);
        let dir_len = dist_f64(prev, last);
        if dir_len == 0.0 {
            return Err(Error::InvalidArgument);
        }
        let len = match tangent_length {
            Some(l) => {
                if !l.is_finite() {
                    return Err(Error::NonFinite);
                }
                l.to_f64()
            }
            None => {
                let pts = next.control_points();
                match (pts.first(), pts.get(1)) {
                    (Some(&c0), Some(&c1)) => dist_f64(c0, c1),
                    _ => 0.0,
                }
            }
        };
        if len <= 0.0 {
            return Err(Error::InvalidArgument);
        }
        let scale = len / dir_len;
        with_start(next, last, |c| {
            (last.coord(c).to_f64() - prev.coord(c).to_f64()) * scale
        })
    }
}

/// `|q − p|` in `f64`.
fn dist_f64<P: Point>(p: P, q: P) -> f64 {
    let mut s = 0.0;
    for c in 0..P::DIM {
        let d = q.coord(c).to_f64() - p.coord(c).to_f64();
        s += d * d;
    }
    libm::sqrt(s)
}

#[cfg(test)]
mod tests {
    use crate::{Bezier, Error, I16F16, ParamCurve, ParamCurveDeriv, Scalar};
    use glam::{DVec2, DVec3, Vec2};

    #[test]
    fn c1_join_derivatives_equal() {
        let a = Bezier::new([
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 2.0, 0.5),
            DVec3::new(3.0, 2.0, 1.0),
            DVec3::new(4.0, 0.0, 1.0),
        ])
        .unwrap();
        // equal degree: mirrored inner point
        let b = Bezier::new([
            DVec3::ZERO,
            DVec3::ZERO,
            DVec3::new(7.0, 1.0, 0.0),
            DVec3::new(8.0, 0.0, 0.0),
        ])
        .unwrap();
        let j = a.join_c1(&b).unwrap();
        assert_eq!(j.control_points()[0], DVec3::new(4.0, 0.0, 1.0));
        assert_eq!(j.control_points()[1], DVec3::new(5.0, -2.0, 1.0));
        assert_eq!(&j.control_points()[2..], &b.control_points()[2..]);
        assert_eq!(j.eval(0.0), a.eval(1.0));
        assert_eq!(j.deriv(0.0, 1), a.deriv(1.0, 1));
        // different degrees: quartic after cubic, and a line after a cubic
        let q = Bezier::new([DVec3::ZERO; 5]).unwrap();
        let jq = a.join_c1(&q).unwrap();
        assert!((jq.deriv(0.0, 1) - a.deriv(1.0, 1)).length() < 1e-14);
        let l = Bezier::new([DVec3::ZERO; 2]).unwrap();
        let jl = a.join_c1(&l).unwrap();
        assert_eq!(jl.deriv(0.0, 1), a.deriv(1.0, 1));
        // a zero end tangent is fine for C¹: both derivatives vanish
        let flat = Bezier::new([DVec3::ZERO, DVec3::X, DVec3::X]).unwrap();
        let jf = flat.join_c1(&b).unwrap();
        assert_eq!(jf.control_points()[1], DVec3::X);
        assert_eq!(jf.deriv(0.0, 1), DVec3::ZERO);
    }

    #[test]
    fn g1_join_tangent_directions_equal() {
        let a = Bezier::new([
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 2.0),
            Vec2::new(3.0, 3.0),
        ])
        .unwrap();
        let b = Bezier::new([
            Vec2::new(5.0, 5.0),
            Vec2::new(5.0, 8.0),
            Vec2::new(9.0, 1.0),
            Vec2::new(10.0, 0.0),
        ])
        .unwrap();
        for len in [None, Some(0.25), Some(4.0)] {
            let j = a.join_g1(&b, len).unwrap();
            assert_eq!(j.eval(0.0), a.eval(1.0));
            let ta = a.deriv(1.0, 1);
            let tj = j.deriv(0.0, 1);
            // parallel and pointing the same way
            assert!(ta.perp_dot(tj).abs() < 1e-5 * ta.length() * tj.length());
            assert!(ta.dot(tj) > 0.0);
            let leg = (j.control_points()[1] - j.control_points()[0]).length();
            assert!((leg - len.unwrap_or(3.0)).abs() < 1e-6);
            assert_eq!(&j.control_points()[2..], &b.control_points()[2..]);
        }
        // G¹ but not C¹: the speeds differ
        let j = a.join_g1(&b, Some(0.25)).unwrap();
        assert!((j.deriv(0.0, 1) - a.deriv(1.0, 1)).length() > 1.0);
    }

    #[test]
    fn fixed_point_join() {
        let p = |x: f64, y: f64| [I16F16::from_num(x), I16F16::from_num(y)];
        let a = Bezier::new([p(0.0, 0.0), p(1.0, 1.0), p(2.0, 1.0), p(3.0, 0.0)]).unwrap();
        let b = Bezier::new([p(3.0, 0.0), p(3.0, 1.0), p(5.0, 0.0), p(6.0, 0.0)]).unwrap();
        let j = a.join_c1(&b).unwrap();
        assert_eq!(j.deriv(I16F16::ZERO, 1), a.deriv(I16F16::ONE, 1));
        let j = a.join_g1(&b, None).unwrap();
        let c1 = j.control_points()[1];
        let s = core::f64::consts::FRAC_1_SQRT_2;
        assert!((c1[0].to_f64() - (3.0 + s)).abs() <= <I16F16 as Scalar>::EPSILON);
        assert!((c1[1].to_f64() + s).abs() <= <I16F16 as Scalar>::EPSILON);
    }

    #[test]
    fn error_too_few_points() {
        let a = Bezier::new([DVec2::ZERO, DVec2::X]).unwrap();
        let k = Bezier::new([DVec2::Y]).unwrap();
        let e = Err(Error::TooFewPoints {
            required: 2,
            found: 1,
        });
        assert_eq!(a.join_c1(&k), e);
        assert_eq!(a.join_g1(&k, None), e);
    }

    #[test]
    fn error_invalid_argument() {
        let b = Bezier::new([DVec2::ZERO, DVec2::Y, DVec2::X]).unwrap();
        // zero end tangent: no direction for G¹
        let flat = Bezier::new([DVec2::ZERO, DVec2::X, DVec2::X]).unwrap();
        assert_eq!(flat.join_g1(&b, None), Err(Error::InvalidArgument));
        let point = Bezier::new([DVec2::X]).unwrap();
        assert_eq!(point.join_g1(&b, Some(1.0)), Err(Error::InvalidArgument));
        // non-positive length
        let a = Bezier::new([DVec2::ZERO, DVec2::X]).unwrap();
        assert_eq!(a.join_g1(&b, Some(0.0)), Err(Error::InvalidArgument));
        assert_eq!(a.join_g1(&b, Some(-1.0)), Err(Error::InvalidArgument));
        // kept length of a degenerate first leg
        let d = Bezier::new([DVec2::Y, DVec2::Y, DVec2::X]).unwrap();
        assert_eq!(a.join_g1(&d, None), Err(Error::InvalidArgument));
    }

    #[test]
    fn error_non_finite() {
        let a = Bezier::new([DVec2::ZERO, DVec2::X]).unwrap();
        let b = Bezier::new([DVec2::ZERO, DVec2::Y, DVec2::X]).unwrap();
        assert_eq!(a.join_g1(&b, Some(f64::NAN)), Err(Error::NonFinite));
        assert_eq!(a.join_g1(&b, Some(f64::INFINITY)), Err(Error::NonFinite));
    }

    #[test]
    fn error_out_of_range() {
        let p = |x: f64| [I16F16::from_num(x)];
        // c_1 = 10 000 + 10 000 leaves I16F16's range
        let a = Bezier::new([p(0.0), p(10000.0)]).unwrap();
        let b = Bezier::new([p(0.0), p(0.0)]).unwrap();
        assert_eq!(a.join_c1(&b), Err(Error::OutOfRange));
        // the new point fits but the adjusted curve's derivative 3 · 9000 does not
        let a = Bezier::new([p(0.0), p(3000.0), p(6000.0)]).unwrap();
        let c = Bezier::new([p(0.0), p(0.0), p(0.0), p(0.0)]).unwrap();
        assert_eq!(
            a.join_g1(&c, Some(I16F16::from_num(9000))),
            Err(Error::OutOfRange)
        );
    }
}
