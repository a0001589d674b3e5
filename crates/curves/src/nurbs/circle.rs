//! The exact circle as a NURBS curve (Piegl & Tiller, *The NURBS Book*, 2nd ed., §7.5
//! "Construction of Circles", the nine-point square; here with the knots scaled to `[0, 4]`).
//!
//! Degree 2, nine control points on the square around the circle — `(1,0), (1,1), (0,1),
//! (−1,1), (−1,0), (−1,−1), (0,−1), (1,−1), (1,0)` — with weights `1, √2/2, 1, √2/2, …` and the
//! knot vector `0,0,0,1,1,2,2,3,3,4,4,4`. Each quarter is a rational quadratic Bézier arc. The
//! double inner knots only guarantee `C⁰`; by the symmetry of the control square the pieces
//! meet `C¹` (equal velocity `√2·radius`), while the second derivative jumps (its tangential
//! part changes sign). On the first quarter, with `t = u/4`, expanding the rational quadratic:
//!
//! ```text
//! Px(t) = (16t² − 8t + 1 + √2/2·(−32t² + 8t)) / (16t² − 8t + 1 + √2/2·(−32t² + 8t) + 16t²)
//! Py(t) = (√2/2·(−32t² + 8t) + 16t²)          / (16t² − 8t + 1 + √2/2·(−32t² + 8t) + 16t²)
//! ```
//!
//! and `Px² + Py² = 1`.

use core::f64::consts::FRAC_1_SQRT_2;

use super::curve::Nurbs;
use crate::error::Error;
use crate::point::Point;
use crate::scalar::Scalar;

/// The control points of the unit circle (the square around it).
const UNIT: [(f64, f64); 9] = [
    (1.0, 0.0),
    (1.0, 1.0),
    (0.0, 1.0),
    (-1.0, 1.0),
    (-1.0, 0.0),
    (-1.0, -1.0),
    (0.0, -1.0),
    (1.0, -1.0),
    (1.0, 0.0),
];

/// The knot vector, one quarter per unit.
const KNOTS: [i16; 12] = [0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4];

impl<P: Point, const N: usize, const M: usize> Nurbs<P, N, M> {
    /// The full circle of `radius` around `center` in the plane of the first two coordinates
    /// (other coordinates are the center's), as Piegl & Tiller §7.5: degree 2, 9 control points,
    /// weights `1, √2/2` alternating, knots `0,0,0,1,1,2,2,3,3,4,4,4`. The domain is `[0, 4]`,
    /// one quarter per unit, counter-clockwise from `center + (radius, 0)`. Needs `N ≥ 9`,
    /// `M ≥ 12`.
    ///
    /// In f64 the distance from the center equals `radius` to within a few ulp (the weight
    /// `√2/2` is rounded once); in fixed-point to within a few `ε·radius`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for points with fewer than 2 coordinates or a radius that is
    /// not positive; [`Error::NonFinite`]; [`Error::CapacityExceeded`]; [`Error::OutOfRange`]
    /// when the control square does not fit the scalar's range.
    ///
    /// ```
    /// use strak_curves::{Nurbs, ParamCurve, ParamCurveDeriv};
    ///
    /// let c = Nurbs::<[f64; 2], 9, 12>::circle([1.0, 2.0], 3.0).unwrap();
    /// assert_eq!(c.domain(), (0.0, 4.0));
    /// assert_eq!(c.eval(1.0), [1.0, 5.0]); // a quarter turn
    /// let p = c.eval(2.7);
    /// let r = ((p[0] - 1.0).powi(2) + (p[1] - 2.0).powi(2)).sqrt();
    /// assert!((r - 3.0).abs() < 1e-14);
    /// ```
    pub fn circle(center: P, radius: P::Scalar) -> Result<Self, Error> {
        if P::DIM < 2 {
            return Err(Error::InvalidArgument);
        }
        if !center.is_finite() || !radius.is_finite() {
            return Err(Error::NonFinite);
        }
        if radius <= P::Scalar::ZERO {
            return Err(Error::InvalidArgument);
        }
        let r = radius.to_f64();
        let (cx, cy) = (center.coord(0).to_f64(), center.coord(1).to_f64());
        let mut ok = true;
        let points: [P; 9] = UNIT.map(|(x, y)| {
            P::from_coords(|c| {
                let v = match c {
                    0 => P::Scalar::from_f64(cx + r * x),
                    1 => P::Scalar::from_f64(cy + r * y),
                    _ => Some(center.coord(c)),
                };
                v.unwrap_or_else(|| {
                    ok = false;
                    P::Scalar::ZERO
                })
            })
        });
        if !ok {
            return Err(Error::OutOfRange);
        }
        let half = P::Scalar::from_f64(FRAC_1_SQRT_2).ok_or(Error::OutOfRange)?;
        let weights: [P::Scalar; 9] =
            core::array::from_fn(|i| if i % 2 == 0 { P::Scalar::ONE } else { half });
        let knots = KNOTS.map(P::Scalar::from_i16);
        Self::new(2, &points, &weights, &knots)
    }
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;
    use crate::curve::{ParamCurve, ParamCurveDeriv};
    use crate::scalar::{I16F16, I32F32};
    use glam::{DVec2, DVec3, Vec2};

    type Circle = Nurbs<[f64; 2], 9, 12>;

    /// The expanded first quarter (module docs), t ∈ [0, 1/4].
    fn quarter(t: f64) -> [f64; 2] {
        let s = FRAC_1_SQRT_2;
        let a = 16.0 * t * t - 8.0 * t + 1.0;
        let b = s * (-32.0 * t * t + 8.0 * t);
        let den = a + b + 16.0 * t * t;
        [(a + b) / den, (b + 16.0 * t * t) / den]
    }

    #[test]
    fn control_points_weights_knots() {
        let c = Circle::circle([0.0, 0.0], 1.0).unwrap();
        assert_eq!(c.degree(), 2);
        let expected: [[f64; 2]; 9] = UNIT.map(|(x, y)| [x, y]);
        assert_eq!(c.control_points(), &expected);
        assert_eq!(c.knots(), &[0., 0., 0., 1., 1., 2., 2., 3., 3., 4., 4., 4.]);
        let s = FRAC_1_SQRT_2;
        assert_eq!(c.weights(), &[1.0, s, 1.0, s, 1.0, s, 1.0, s, 1.0]);
        assert_eq!(c.piece_count(), 4);
    }

    #[test]
    fn radius_is_one_to_f64_rounding() {
        let c = Circle::circle([0.0, 0.0], 1.0).unwrap();
        let mut worst = 0.0_f64;
        for i in 0..=100_000 {
            let u = 4.0 * f64::from(i) / 100_000.0;
            let p = c.eval(u);
            worst = worst.max(((p[0] * p[0] + p[1] * p[1]).sqrt() - 1.0).abs());
        }
        // Stated tolerance: 4 ulp of 1.0 (8.9e-16).
        assert!(worst <= 4.0 * f64::EPSILON, "max |‖c(u)‖ − 1| = {worst:e}");
        // The quarter points are exact.
        assert_eq!(c.eval(0.0), [1.0, 0.0]);
        assert_eq!(c.eval(1.0), [0.0, 1.0]);
        assert_eq!(c.eval(2.0), [-1.0, 0.0]);
        assert_eq!(c.eval(3.0), [0.0, -1.0]);
        assert_eq!(c.eval(4.0), [1.0, 0.0]);
    }

    #[test]
    fn first_quarter_equals_expanded_formula() {
        let c = Circle::circle([0.0, 0.0], 1.0).unwrap();
        for i in 0..=1000 {
            let t = 0.25 * f64::from(i) / 1000.0;
            let (a, b) = (c.eval(4.0 * t), quarter(t));
            assert!((a[0] - b[0]).abs() <= 4.0 * f64::EPSILON, "t={t}");
            assert!((a[1] - b[1]).abs() <= 4.0 * f64::EPSILON, "t={t}");
            let r = b[0] * b[0] + b[1] * b[1];
            assert!((r - 1.0).abs() <= 4.0 * f64::EPSILON);
        }
    }

    #[test]
    fn derivatives_of_the_circle() {
        // |c|² = 1 ⇒ Σ_{i=0}^{n} C(n,i) c^{(i)}·c^{(n−i)} = 0 for every n ≥ 1 (all orders ≤ 7).
        let c = Circle::circle([0.0, 0.0], 1.0).unwrap();
        assert_eq!(c.max_deriv_order(), 7);
        for i in 0..400 {
            let u = 4.0 * f64::from(i) / 400.0 + 1e-3;
            let mut d = [[0.0; 2]; 8];
            c.derivatives(u, &mut d);
            for n in 1..=7 {
                let mut sum = 0.0;
                let mut scale = 0.0;
                for i in 0..=n {
                    let dot = d[i][0] * d[n - i][0] + d[i][1] * d[n - i][1];
                    let b = f64::from(BINOM_TEST[n][i]);
                    sum += b * dot;
                    scale += (b * dot).abs();
                }
                assert!(
                    sum.abs() <= 1e-12 * (1.0 + scale),
                    "u={u} n={n} sum={sum} scale={scale}"
                );
            }
        }
        // C¹ but not C² at the double knots.
        for (i, u) in [1.0, 2.0, 3.0].into_iter().enumerate() {
            let (l1, r1) = (c.piece_deriv(i, u, 1), c.deriv(u, 1));
            assert!((l1[0] - r1[0]).abs() < 1e-15 && (l1[1] - r1[1]).abs() < 1e-15);
            let (l2, r2) = (c.piece_deriv(i, u, 2), c.deriv(u, 2));
            assert!((l2[0] - r2[0]).abs() + (l2[1] - r2[1]).abs() > 1.0);
        }
        // The tangent at the start is vertical: c'(0) = 2·w₁/w₀·(P₁ − P₀) = (0, √2).
        let d = c.deriv(0.0, 1);
        assert_eq!(d[0], 0.0);
        assert!((d[1] - core::f64::consts::SQRT_2).abs() < 1e-15);
    }

    const BINOM_TEST: [[u8; 8]; 8] = [
        [1, 0, 0, 0, 0, 0, 0, 0],
        [1, 1, 0, 0, 0, 0, 0, 0],
        [1, 2, 1, 0, 0, 0, 0, 0],
        [1, 3, 3, 1, 0, 0, 0, 0],
        [1, 4, 6, 4, 1, 0, 0, 0],
        [1, 5, 10, 10, 5, 1, 0, 0],
        [1, 6, 15, 20, 15, 6, 1, 0],
        [1, 7, 21, 35, 35, 21, 7, 1],
    ];

    #[test]
    fn center_radius_and_point_types() {
        let c = Nurbs::<DVec3, 9, 12>::circle(DVec3::new(1.0, -2.0, 5.0), 2.5).unwrap();
        for i in 0..=100 {
            let p = c.eval(0.04 * f64::from(i));
            assert!((p.z - 5.0).abs() < 1e-14);
            assert!(((p - DVec3::new(1.0, -2.0, 5.0)).length() - 2.5).abs() < 1e-14);
        }
        let c = Nurbs::<DVec2, 9, 12>::circle(DVec2::ZERO, 1.0).unwrap();
        assert!((c.eval(0.5).length() - 1.0).abs() < 1e-15);
        let c = Nurbs::<Vec2, 9, 12>::circle(Vec2::ZERO, 1.0).unwrap();
        for i in 0..=400 {
            let p = c.eval(0.01 * i as f32);
            assert!((p.length() - 1.0).abs() < 4.0 * f32::EPSILON, "{p:?}");
        }
    }

    #[test]
    fn fixed_point_circles() {
        let c16 = Nurbs::<[I16F16; 2], 9, 12>::circle([I16F16::ZERO; 2], I16F16::ONE).unwrap();
        let c32 = Nurbs::<[I32F32; 2], 9, 12>::circle([I32F32::ZERO; 2], I32F32::ONE).unwrap();
        let big = Nurbs::<[I16F16; 2], 9, 12>::circle(
            [I16F16::from_num(100), I16F16::from_num(-50)],
            I16F16::from_num(1000),
        )
        .unwrap();
        // I16F16 cannot hold the 7th derivative bound of the unit circle; I32F32 can.
        assert!(c16.max_deriv_order() >= 2 && c16.max_deriv_order() < 7);
        assert_eq!(c32.max_deriv_order(), 7);
        let f = Circle::circle([0.0, 0.0], 1.0).unwrap();
        let (mut w16, mut w32, mut wb) = (0.0_f64, 0.0_f64, 0.0_f64);
        let (mut d16, mut d32) = (0.0_f64, 0.0_f64);
        for i in 0..=4000 {
            let u = f64::from(i) / 1000.0;
            let p = c16.eval(I16F16::from_num(u)).map(|x| x.to_f64());
            let q = c32.eval(I32F32::from_num(u)).map(|x| x.to_f64());
            let b = big.eval(I16F16::from_num(u)).map(|x| x.to_f64());
            w16 = w16.max((p[0].hypot(p[1]) - 1.0).abs());
            w32 = w32.max((q[0].hypot(q[1]) - 1.0).abs());
            wb = wb.max(((b[0] - 100.0).hypot(b[1] + 50.0) - 1000.0).abs());
            let e = f.deriv(u, 1);
            let a = c16.deriv(I16F16::from_num(u), 1).map(|x| x.to_f64());
            let c = c32.deriv(I32F32::from_num(u), 1).map(|x| x.to_f64());
            d16 = d16.max((a[0] - e[0]).abs().max((a[1] - e[1]).abs()));
            d32 = d32.max((c[0] - e[0]).abs().max((c[1] - e[1]).abs()));
        }
        // Tolerances: a few ε (I16F16 ε = 1.5e-5, I32F32 ε = 2.3e-10), times the radius.
        assert!(w16 < 8.0 * I16F16::EPSILON, "I16F16 radius error {w16:e}");
        assert!(w32 < 8.0 * I32F32::EPSILON, "I32F32 radius error {w32:e}");
        assert!(
            wb < 8.0 * I16F16::EPSILON * 1000.0,
            "I16F16 r = 1000 radius error {wb:e}"
        );
        assert!(d16 < 3e-4 && d32 < 5e-9, "{d16:e} {d32:e}");
    }

    #[test]
    fn circle_errors() {
        assert_eq!(
            Nurbs::<[f64; 1], 9, 12>::circle([0.0], 1.0).unwrap_err(),
            Error::InvalidArgument
        );
        assert_eq!(
            Circle::circle([0.0, 0.0], 0.0).unwrap_err(),
            Error::InvalidArgument
        );
        assert_eq!(
            Circle::circle([0.0, 0.0], -1.0).unwrap_err(),
            Error::InvalidArgument
        );
        assert_eq!(
            Circle::circle([f64::NAN, 0.0], 1.0).unwrap_err(),
            Error::NonFinite
        );
        assert_eq!(
            Nurbs::<[f64; 2], 8, 12>::circle([0.0, 0.0], 1.0).unwrap_err(),
            Error::CapacityExceeded {
                capacity: 8,
                required: 9
            }
        );
        assert_eq!(
            Nurbs::<[f64; 2], 9, 11>::circle([0.0, 0.0], 1.0).unwrap_err(),
            Error::CapacityExceeded {
                capacity: 11,
                required: 12
            }
        );
        assert_eq!(
            Nurbs::<[I16F16; 2], 9, 12>::circle(
                [I16F16::from_num(16000); 2],
                I16F16::from_num(1000)
            )
            .unwrap_err(),
            Error::OutOfRange
        );
    }
}
