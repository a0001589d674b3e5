//! The cubic Bézier approximation of a quarter of the unit circle (Goldapp, "Approximation
//! of circular arcs by cubic polynomials", *Computer Aided Geometric Design* 8(3), 1991). A
//! polynomial curve cannot be a circle; the exact circle is the rational [`Nurbs::circle`](crate::Nurbs::circle).
//! The values of κ and the radial errors are documented on [`QUARTER_CIRCLE_KAPPA`] and
//! [`quarter_circle_radial_error`].

use super::curve::Bezier;
use crate::error::Error;
use crate::point::Point;
use crate::scalar::Scalar;

/// `κ = 0.551897`, a tangent length of the cubic quarter circle in common use (for example
/// O. Vornberger's lecture notes *Computergrafik*, Universität Osnabrück, ch. 7 "2D-Kurven").
///
/// The arc from `(0, 1)` to `(1, 0)` is approximated by the Bézier points
/// `(0, 1), (κ, 1), (1, κ), (1, 0)` ([`Bezier::quarter_circle`]): the end points and end
/// tangents are exact, `κ` sets the tangent length. In coordinates,
/// `f_1(t) = 3t(1−t)² κ + 3t²(1−t) + t³`, `f_2(t) = (1−t)³ + 3t(1−t)² + 3t²(1−t) κ`.
///
/// The midpoint `P(0.5) = (cos 45°, sin 45°)` lies on the circle for
/// `κ = 4/3 (√2 − 1)` ([`QUARTER_CIRCLE_KAPPA_MIDPOINT`]) only. With `κ = 0.551897`,
/// `P(0.5) = (0.706961, 0.706961)`: this value trades the exact midpoint for a smaller,
/// nearly balanced maximal radial error (see [`quarter_circle_radial_error`]; the
/// equioscillating optimum is `κ ≈ 0.551915` with `±1.96 · 10⁻⁴`).
pub const QUARTER_CIRCLE_KAPPA: f64 = 0.551897;

/// `κ = 4/3 (√2 − 1) ≈ 0.552 284 75`, the tangent length for which the cubic quarter circle
/// passes exactly through `(cos 45°, sin 45°)` at `t = 1/2`.
pub const QUARTER_CIRCLE_KAPPA_MIDPOINT: f64 = 0.552_284_749_830_793_5;

impl<P: Point> Bezier<P, 4> {
    /// The cubic quarter circle `(0, 1), (κ, 1), (1, κ), (1, 0)` for any `κ`, in
    /// the plane of the first two coordinates (further coordinates are zero).
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] for points with fewer than two coordinates,
    /// [`Error::NonFinite`] for a NaN/∞ `κ`, [`Error::OutOfRange`] when the curve does not fit
    /// the scalar type.
    ///
    /// ```
    /// use strak_curves::{Bezier, ParamCurve, QUARTER_CIRCLE_KAPPA_MIDPOINT};
    /// use glam::DVec2;
    /// let c = Bezier::<DVec2, 4>::quarter_circle(QUARTER_CIRCLE_KAPPA_MIDPOINT)?;
    /// let m = c.eval(0.5);
    /// assert!((m.x - core::f64::consts::FRAC_1_SQRT_2).abs() < 1e-15);
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn quarter_circle(kappa: P::Scalar) -> Result<Self, Error> {
        if P::DIM < 2 {
            return Err(Error::LengthMismatch {
                expected: 2,
                found: P::DIM,
            });
        }
        if !kappa.is_finite() {
            return Err(Error::NonFinite);
        }
        let o = P::Scalar::ZERO;
        let l = P::Scalar::ONE;
        let xy = |x: P::Scalar, y: P::Scalar| {
            P::from_coords(|i| match i {
                0 => x,
                1 => y,
                _ => o,
            })
        };
        Self::new([xy(o, l), xy(kappa, l), xy(l, kappa), xy(l, o)])
    }

    /// The quarter circle with `κ =` [`QUARTER_CIRCLE_KAPPA`] `= 0.551897`
    /// (rounded to the scalar type).
    ///
    /// # Errors
    /// As [`Bezier::quarter_circle`].
    ///
    /// ```
    /// use strak_curves::{Bezier, I16F16, ParamCurve};
    /// let c = Bezier::<[I16F16; 2], 4>::quarter_circle_seed()?;
    /// let p = c.eval(I16F16::from_num(0.5));
    /// assert!((p[0].to_num::<f64>() - 0.706961).abs() < 1e-4);
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn quarter_circle_seed() -> Result<Self, Error> {
        let kappa = P::Scalar::from_f64(QUARTER_CIRCLE_KAPPA).ok_or(Error::OutOfRange)?;
        Self::quarter_circle(kappa)
    }
}

/// Point and derivative of the quarter circle with tangent length `kappa` at `t`, in `f64`.
fn arc(kappa: f64, t: f64) -> ([f64; 2], [f64; 2]) {
    let s = 1.0 - t;
    let b = [[0.0, 1.0], [kappa, 1.0], [1.0, kappa], [1.0, 0.0]];
    let w = [s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t];
    let dw = [s * s, 2.0 * s * t, t * t];
    let mut p = [0.0; 2];
    let mut d = [0.0; 2];
    for c in 0..2 {
        p[c] = w[0] * b[0][c] + w[1] * b[1][c] + w[2] * b[2][c] + w[3] * b[3][c];
        d[c] = 3.0
            * (dw[0] * (b[1][c] - b[0][c])
                + dw[1] * (b[2][c] - b[1][c])
                + dw[2] * (b[3][c] - b[2][c]));
    }
    (p, d)
}

/// The maximal radial error `max_{t∈[0,1]} | ‖c(t)‖ − 1 |` of the cubic quarter circle with
/// tangent length `kappa`, in `f64`. `NaN` for a non-finite `kappa`.
///
/// The extrema of `‖c(t)‖` are the roots of `d/dt ‖c‖²/2 = c · c'`. The function samples
/// `c · c'` on 512 equal intervals, refines every sign change by bisection to the resolution
/// of `f64`, and returns the largest `|‖c‖ − 1|` over those roots and all sample points
/// (including `t = 0, 1`). Values:
///
/// | κ | max radial error | where |
/// |---|------------------|-------|
/// | [`QUARTER_CIRCLE_KAPPA`] = 0.551897 | 2.0564 · 10⁻⁴ | `t = 1/2`, inside the circle (`‖c‖ = 0.999794`); outside by at most 1.928 · 10⁻⁴ near `t ≈ 0.181` and `0.819` |
/// | [`QUARTER_CIRCLE_KAPPA_MIDPOINT`] = 4/3 (√2 − 1) ≈ 0.5522847 | 2.7253 · 10⁻⁴ | `t = 1/2 ± √3/6`, outside; exact at `t = 1/2` |
///
/// ```
/// use strak_curves::{QUARTER_CIRCLE_KAPPA, quarter_circle_radial_error};
/// let e = quarter_circle_radial_error(QUARTER_CIRCLE_KAPPA);
/// assert!((e - 2.0564e-4).abs() < 1e-8);
/// ```
pub fn quarter_circle_radial_error(kappa: f64) -> f64 {
    if !kappa.is_finite() {
        return f64::NAN;
    }
    const SAMPLES: usize = 512;
    let radial = |t: f64| {
        let (p, _) = arc(kappa, t);
        (libm::sqrt(p[0] * p[0] + p[1] * p[1]) - 1.0).abs()
    };
    let slope = |t: f64| {
        let (p, d) = arc(kappa, t);
        p[0] * d[0] + p[1] * d[1]
    };
    let mut max = 0.0_f64;
    let mut prev_t = 0.0;
    let mut prev_s = slope(0.0);
    for i in 0..=SAMPLES {
        let t = i as f64 / SAMPLES as f64;
        let s = slope(t);
        max = max.max(radial(t));
        if (prev_s < 0.0 && s > 0.0) || (prev_s > 0.0 && s < 0.0) {
            let (mut lo, mut hi, lo_s) = (prev_t, t, prev_s);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break;
                }
                let ms = slope(mid);
                if (ms < 0.0) == (lo_s < 0.0) && ms != 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            max = max.max(radial(lo)).max(radial(hi));
        }
        prev_t = t;
        prev_s = s;
    }
    max
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{I16F16, I32F32, ParamCurve, ParamCurveDeriv};
    use glam::{DVec2, Vec2, Vec3};

    #[test]
    fn control_points_and_end_conditions() {
        let c = Bezier::<DVec2, 4>::quarter_circle_seed().unwrap();
        assert_eq!(
            c.control_points(),
            &[
                DVec2::new(0.0, 1.0),
                DVec2::new(0.551897, 1.0),
                DVec2::new(1.0, 0.551897),
                DVec2::new(1.0, 0.0)
            ]
        );
        assert_eq!(c.eval(0.0), DVec2::new(0.0, 1.0));
        assert_eq!(c.eval(1.0), DVec2::new(1.0, 0.0));
        // tangents are horizontal at the start and vertical at the end
        assert_eq!(c.deriv(0.0, 1).y, 0.0);
        assert_eq!(c.deriv(1.0, 1).x, 0.0);
        // the coordinate functions f_1 and f_2 at t = 1/2
        let k = QUARTER_CIRCLE_KAPPA;
        let f1 = |t: f64| 3.0 * t * (1.0 - t).powi(2) * k + 3.0 * t * t * (1.0 - t) + t.powi(3);
        let f2 =
            |t: f64| (1.0 - t).powi(3) + 3.0 * t * (1.0 - t).powi(2) + 3.0 * t * t * (1.0 - t) * k;
        for step in 0..=10 {
            let t = step as f64 / 10.0;
            let p = c.eval(t);
            assert!((p.x - f1(t)).abs() < 1e-15 && (p.y - f2(t)).abs() < 1e-15);
        }
        assert!((c.eval(0.5).x - 0.706961375).abs() < 1e-12);
        // 3-D points: the arc lies in the xy-plane
        let c3 = Bezier::<Vec3, 4>::quarter_circle(0.5).unwrap();
        assert!(c3.control_points().iter().all(|p| p.z == 0.0));
    }

    #[test]
    fn radial_error_values() {
        let e_common = quarter_circle_radial_error(QUARTER_CIRCLE_KAPPA);
        let e_mid = quarter_circle_radial_error(QUARTER_CIRCLE_KAPPA_MIDPOINT);
        // κ = 0.551897: the extremum is at t = 1/2, inside the circle
        let c = Bezier::<DVec2, 4>::quarter_circle(QUARTER_CIRCLE_KAPPA).unwrap();
        assert!(
            (e_common - (1.0 - c.eval(0.5).length())).abs() < 1e-15,
            "{e_common}"
        );
        assert!((e_common - 2.056_354e-4).abs() < 1e-9, "{e_common}");
        // κ = 4/3(√2 − 1): maximum at t = 1/2 ± √3/6, outside the circle
        let t = 0.5 - 3f64.sqrt() / 6.0;
        let cm = Bezier::<DVec2, 4>::quarter_circle(QUARTER_CIRCLE_KAPPA_MIDPOINT).unwrap();
        assert!((e_mid - (cm.eval(t).length() - 1.0)).abs() < 1e-15);
        assert!((e_mid - 2.725_300e-4).abs() < 1e-9, "{e_mid}");
        assert!((cm.eval(0.5).length() - 1.0).abs() < 1e-15);
        // the constant is 4/3(√2 − 1)
        assert!((QUARTER_CIRCLE_KAPPA_MIDPOINT - 4.0 / 3.0 * (2f64.sqrt() - 1.0)).abs() < 1e-16);
        // a bad κ is much worse; dense sampling never finds a larger error
        let e_bad = quarter_circle_radial_error(0.3);
        assert!(e_bad > 0.02);
        for kappa in [
            0.3,
            QUARTER_CIRCLE_KAPPA,
            QUARTER_CIRCLE_KAPPA_MIDPOINT,
            0.7,
        ] {
            let e = quarter_circle_radial_error(kappa);
            let c = Bezier::<DVec2, 4>::quarter_circle(kappa).unwrap();
            for step in 0..=10_000 {
                let r = c.eval(step as f64 / 10_000.0).length();
                assert!((r - 1.0).abs() <= e + 1e-15);
            }
        }
        assert!(quarter_circle_radial_error(f64::NAN).is_nan());
    }

    #[test]
    fn f32_and_fixed_point_agree_with_f64() {
        let cf = Bezier::<DVec2, 4>::quarter_circle_seed().unwrap();
        let c32 = Bezier::<Vec2, 4>::quarter_circle_seed().unwrap();
        let cx = Bezier::<[I16F16; 2], 4>::quarter_circle_seed().unwrap();
        let cy = Bezier::<[I32F32; 2], 4>::quarter_circle_seed().unwrap();
        for step in 0..=16 {
            let t = step as f64 / 16.0;
            let r = cf.eval(t);
            let a = c32.eval(t as f32);
            let x = cx.eval(I16F16::from_num(t));
            let y = cy.eval(I32F32::from_num(t));
            assert!((f64::from(a.x) - r.x).abs() < 1e-6);
            // κ is rounded to the nearest fixed-point value (≤ ½ ulp), then ≤ 6 ulps of
            // truncation in three de Casteljau levels
            assert!((x[0].to_f64() - r.x).abs() <= 7.0 * <I16F16 as Scalar>::EPSILON);
            assert!((x[1].to_f64() - r.y).abs() <= 7.0 * <I16F16 as Scalar>::EPSILON);
            assert!((y[0].to_f64() - r.x).abs() <= 7.0 * <I32F32 as Scalar>::EPSILON);
        }
    }

    #[test]
    fn error_length_mismatch_for_one_dimensional_points() {
        assert_eq!(
            Bezier::<[f64; 1], 4>::quarter_circle(0.5),
            Err(Error::LengthMismatch {
                expected: 2,
                found: 1
            })
        );
    }

    #[test]
    fn error_non_finite() {
        assert_eq!(
            Bezier::<DVec2, 4>::quarter_circle(f64::NAN),
            Err(Error::NonFinite)
        );
    }

    #[test]
    fn error_out_of_range() {
        // κ = 10 000 fits I16F16, the start derivative 3 κ does not
        assert_eq!(
            Bezier::<[I16F16; 2], 4>::quarter_circle(I16F16::from_num(10000)),
            Err(Error::OutOfRange)
        );
    }
}
