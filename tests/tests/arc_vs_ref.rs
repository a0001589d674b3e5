//! strak-curves' `CircularArc` against strak-ref's `GcodeArc` (the start's radius vector
//! rotated by the rotation matrix, the turn read from cross and dot products, the radius
//! form's centre as an intersection of two circles), on random arcs and helices of 3 axes in
//! every plane and sense, in both G-code forms, with the end on the start's circle or off it
//! within the tolerance (a spiral), in `f64`, `f32` and `I32F32`.
//!
//! # Tolerances
//!
//! Both compute in `f64` from the same inputs (the reference from the inputs as the scalar
//! type holds them), by different routes (absolute angles from `atan2` against a rotation of
//! the start vector). The `k`-th derivative is of size at most
//! `M_k = (|c| + r + |q|)·(1 + |Δθ|)ᵏ`, and its rounding in `f64` at most a few hundred units
//! of `M_k` (the angle's error, times `Δθᵏ`): `|strak − ref| ≤ 10⁻¹³·M_k` plus the rounding of
//! the result into the scalar type (`M_k·ε` for floats) and that of the radius form's
//! centre, `δ = M₀·ε` (floats) or `4·2⁻³²` (`I32F32`), which moves the `k`-th derivative by
//! up to `(k + 1)·δ·(1 + |Δθ|)ᵏ`. Sweeps agree within `10⁻¹²·2π` plus the turn of
//! that rounded centre (`(64·ε·M₀ + 4·2⁻³²)/r`).

use std::f64::consts::TAU;

use proptest::prelude::*;
use proptest::test_runner::TestCaseResult;
use strak_curves::{CircularArc, I32F32, ParamCurve, ParamCurveDeriv, Plane, Scalar, Turn};
use strak_ref::GcodeArc;
use strak_tests::spline_cases::{Worst, fail, property, sc};
use strak_tests::to_vec;

/// One random arc: the plane, the sense, the centre, the start and end radii and angles, the
/// coordinate outside the plane at both ends, and the form.
#[derive(Clone, Debug)]
struct Case {
    plane: Plane,
    clockwise: bool,
    center: [f64; 2],
    radius: f64,
    /// The end's radius relative to the start's (1: on the circle).
    spiral: f64,
    angles: [f64; 2],
    heights: [f64; 2],
    /// `G2`/`G3` with `R` (the end on the circle) instead of `I J K`.
    radius_form: bool,
}

fn cases() -> impl Strategy<Value = Case> {
    (
        prop_oneof![Just(Plane::XY), Just(Plane::ZX), Just(Plane::YZ)],
        any::<bool>(),
        [-100.0..100.0_f64, -100.0..100.0_f64],
        0.5..50.0_f64,
        prop_oneof![Just(1.0), 0.999..1.001_f64],
        [-3.2..3.2_f64, -3.2..3.2_f64],
        [-50.0..50.0_f64, -50.0..50.0_f64],
        any::<bool>(),
    )
        .prop_map(
            |(plane, clockwise, center, radius, spiral, angles, heights, radius_form)| Case {
                plane,
                clockwise,
                center,
                radius,
                spiral,
                angles,
                heights,
                radius_form,
            },
        )
        // The turn of nearly coincident ends (a tiny arc or a full turn) is decided by rounding.
        .prop_filter("ends not nearly coincident", |c| {
            let d = (c.angles[1] - c.angles[0]).rem_euclid(TAU);
            d > 1e-3 && d < TAU - 1e-3
        })
}

/// The start and end points of a case, every coordinate.
fn ends(c: &Case) -> [[f64; 3]; 2] {
    let mut out = [[0.0; 3]; 2];
    for (k, p) in out.iter_mut().enumerate() {
        let r = if k == 0 {
            c.radius
        } else {
            c.radius * c.spiral
        };
        let a = c.angles[k];
        let third = 3 - c.plane.first - c.plane.second;
        p[c.plane.first] = c.center[0] + r * a.cos();
        p[c.plane.second] = c.center[1] + r * a.sin();
        p[third] = c.heights[k];
    }
    out
}

fn check<S: Scalar>(c: &Case, float_eps: f64, fixed_unit: f64, worst: &Worst) -> TestCaseResult {
    let turn = if c.clockwise {
        Turn::Clockwise
    } else {
        Turn::CounterClockwise
    };
    let [s, e] = ends(c);
    let (start, end) = (s.map(sc::<S>), e.map(sc::<S>));
    let (sf, ef) = (to_vec(start), to_vec(end));
    let plane = (c.plane.first, c.plane.second);
    let tolerance = sc::<S>(c.radius * 0.002 + 1e-6);
    let (arc, reference) = if c.radius_form {
        // The end on the start's circle, and the shorter or the longer arc by the sign.
        let cf = [sc::<S>(c.center[0]), sc::<S>(c.center[1])].map(|x| x.to_f64());
        let long = GcodeArc::with_center(&sf, &ef, cf, plane, c.clockwise)
            .sweep
            .abs()
            > std::f64::consts::PI;
        let r0 = (sf[plane.0] - cf[0]).hypot(sf[plane.1] - cf[1]);
        let r = if long { -r0 } else { r0 };
        let arc = CircularArc::with_radius(start, end, sc::<S>(r), c.plane, turn, tolerance)
            .map_err(fail)?;
        let r_held = sc::<S>(r).to_f64();
        (
            arc,
            GcodeArc::with_radius(&sf, &ef, r_held, plane, c.clockwise),
        )
    } else {
        let center = [sc::<S>(c.center[0]), sc::<S>(c.center[1])];
        let arc =
            CircularArc::with_center(start, end, center, c.plane, turn, tolerance).map_err(fail)?;
        let cf = center.map(|x| x.to_f64());
        (arc, GcodeArc::with_center(&sf, &ef, cf, plane, c.clockwise))
    };
    let size = reference.center[0].abs().max(reference.center[1].abs())
        + c.radius.max(c.radius * c.spiral)
        + c.heights[0].abs().max(c.heights[1].abs());
    // The radius form's centre is held in the scalar type: rounded by up to `|c|·ε` (floats)
    // or the unit (fixed point), which turns the angles by that over the radius.
    let sweep_tol = 1e-12 * TAU + (64.0 * float_eps * size + 4.0 * fixed_unit) / c.radius;
    if (arc.sweep() - reference.sweep).abs() > sweep_tol {
        return Err(TestCaseError::fail(format!(
            "sweep {} against the reference's {}",
            arc.sweep(),
            reference.sweep
        )));
    }
    if to_vec(arc.eval(S::ONE)) != ef || to_vec(arc.eval(S::ZERO)) != sf {
        return Err(TestCaseError::fail(
            "the ends are not the given points".to_string(),
        ));
    }
    for i in 0..=16 {
        let u = f64::from(i) / 16.0;
        for k in 0..=3 {
            let m = size * (1.0 + reference.sweep.abs()).powi(k as i32);
            // The parameter as the scalar holds it (exact: a multiple of 1/16).
            let got = to_vec(arc.deriv(sc::<S>(u), k));
            let want = reference.deriv(u, k);
            // The centre's rounding `δ` moves a derivative by up to `(k + 1)·δ·(1 + |Δθ|)ᵏ`.
            let growth = (1.0 + reference.sweep.abs()).powi(k as i32);
            let centre = fixed_unit + size * float_eps;
            let tol = 1e-13 * m + m * float_eps + centre * (k as f64 + 1.0) * growth;
            worst.check(&got, &want, tol, || format!("{c:?} u {u} k {k}"))?;
        }
    }
    Ok(())
}

#[test]
fn arcs_agree_with_the_reference_in_f64() {
    let worst = Worst::default();
    property(2_000, cases(), |c| {
        check::<f64>(&c, f64::EPSILON, 0.0, &worst)
    });
    worst.report("f64");
}

#[test]
fn arcs_agree_with_the_reference_in_f32() {
    let worst = Worst::default();
    property(1_000, cases(), |c| {
        check::<f32>(&c, f64::from(f32::EPSILON), 0.0, &worst)
    });
    worst.report("f32");
}

#[test]
fn arcs_agree_with_the_reference_in_fixed_point() {
    let worst = Worst::default();
    property(1_000, cases(), |c| {
        check::<I32F32>(&c, 0.0, 4.0 * I32F32::EPSILON, &worst)
    });
    worst.report("I32F32");
}
