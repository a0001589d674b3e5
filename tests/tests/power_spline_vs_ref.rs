//! strak-curves' `PowerSpline` (a B-spline as per-span power-basis polynomials, Horner)
//! against strak-ref, the slow textbook Cox–de Boor recursion (seeds/000, 002
//! "Basis-Splines", seeds/004 "B-Splines").
//!
//! Random knot vectors — uniform (the O(1) span lookup) and non-uniform, clamped and
//! unclamped, inner multiplicities up to the degree — degrees 1..=5, the point and the
//! derivatives of every order `0..=g+1` (`eval`, `deriv`, `piece_deriv` at the start, middle
//! and end of every piece), in `f64`, `f32`, `I32F32` and `I16F16`; closed curves against
//! `BSpline::closed`.
//!
//! # Tolerances
//!
//! With `A_k` the uncancelled derivative scale of `bspline_vs_ref.rs` (it bounds
//! `|c^{(k)}|` and the rounding of the reference), and for the piece on `[u_s, u_{s+1})` of
//! length `Δ`, `r = 1/Δ`, `D = max |d_i|`:
//!
//! - the power coefficients are the Taylor coefficients `a_j = c^{(j)}(u_s)·Δ^j/j!` (taken
//!   from the reference), so Horner's condition for the `k`-th derivative is
//!   `H_k = r^k·Σ_{j≥k} j!/(j−k)!·|a_j|`;
//! - the coefficients are computed in `f64` through the Bézier points (convex combinations,
//!   `|b_i| ≤ D`) and `T_{M←B}` (entries `C(g,j)·C(j,i)`), so a coefficient's rounding is
//!   bounded by a multiple of `ε·C(g,j)·2^j·D`, which enters the `k`-th derivative as
//!   `W_k = r^k·Σ_{j≥k} j!/(j−k)!·C(g,j)·2^j·D`.
//!
//! **Floats:** `|power − ref| ≤ rel·(A_k + H_k + W_k)`, `rel = 1e-13` for `f64` (about 900 ε,
//! for the `O(g)` roundings of each step; the worst case seen is about 1 ε) and `rel = 1e-5`
//! for `f32` (about 80 ε of `f32`; the reference runs in `f64` on the same `f32`-rounded knots
//! and points). A wrong coefficient or a wrong piece is an error of the order of the points
//! (see `tolerance_detects_a_perturbed_curve`: a change of 1e-9 is caught).
//!
//! **Fixed-point** (absolute errors, `ε = 2^{−f}`): each coefficient is rounded once (`ε/2`),
//! each Horner step truncates once (`ε`), `t = (u − u_s)·r` is off by at most `ε·(1 + Δ/2)`
//! (`r` rounded by `ε/2`) which moves the polynomial by `|p'(t)|·δt ≤ S_{k+1}·δt` (`S_k` the
//! `t`-domain sum `Σ_{j≥k} j!/(j−k)!·|a_j|`), and each of the `k` multiplications by `r` adds a
//! relative `ε·Δ/2` and an absolute `ε`:
//! `E_k = ε·[r^k·((g + 1) + F_k/2 + S_{k+1}·(1 + Δ/2) + k·S_k·Δ/2) + k·max(1, r)^k]`
//! with `F_k = Σ_{j≥k} j!/(j−k)!`. The tolerance is `4·E_k` plus the reference's own `f64`
//! rounding (`1e-12·A_k`).
//!
//! Every test prints the largest `error / tolerance` it met (`cargo test -- --nocapture`).

// The derivative order `k` indexes the tolerances and is passed to the reference.
#![allow(clippy::needless_range_loop)]

use std::ops::RangeInclusive;

use proptest::prelude::*;
use proptest::test_runner::{TestCaseError, TestCaseResult};
use strak_curves::glam::{DVec3, Vec3};
use strak_curves::{
    BSpline, I16F16, I32F32, ParamCurve, ParamCurveDeriv, PieceDeriv, Point, PowerSpline, Scalar,
};
use strak_tests::spline_cases::{Tol, Worst, gap, open_knots, params, property, sc, scales};
use strak_tests::{pts, to_vec, to_vecs};

/// `j!/(j−k)!` (0 for `k > j`).
fn falling(j: usize, k: usize) -> f64 {
    if k > j {
        return 0.0;
    }
    (0..k).map(|m| (j - m) as f64).product()
}

fn binomial(n: usize, k: usize) -> f64 {
    falling(n, k) / falling(k, k)
}

/// The tolerances of the orders `0..=g+1` on the piece `[knots[s], knots[s+1])`.
fn piece_tolerances<S: Scalar>(
    tol: Tol,
    knots: &[f64],
    g: usize,
    points: &[Vec<f64>],
    s: usize,
) -> Vec<f64> {
    let mags: Vec<f64> = points
        .iter()
        .map(|p| p.iter().fold(0.0_f64, |m, x| m.max(x.abs())))
        .collect();
    let d = mags.iter().copied().fold(0.0, f64::max);
    let a = scales(knots, g, &mags, 0.0);
    let (u0, delta) = (knots[s], knots[s + 1] - knots[s]);
    let r = 1.0 / delta;
    // |a_j| = |c^{(j)}(u_s)|·Δ^j/j! from the reference (largest coordinate).
    let taylor: Vec<f64> = (0..=g)
        .map(|j| {
            let v = strak_ref::bspline_deriv(knots, g, points, u0, j);
            let m = v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
            m * delta.powi(j as i32) / falling(j, j)
        })
        .collect();
    let sum = |k: usize, w: &dyn Fn(usize) -> f64| -> f64 {
        (k..=g).map(|j| falling(j, k) * w(j)).sum::<f64>()
    };
    (0..=g + 1)
        .map(|k| {
            let s_k = sum(k, &|j| taylor[j]);
            let s_k1 = sum(k + 1, &|j| taylor[j]);
            let rk = r.powi(k as i32);
            match tol {
                Tol::Float(rel) => {
                    let w = sum(k, &|j| binomial(g, j) * 2f64.powi(j as i32) * d);
                    rel * (a[k] + rk * s_k + rk * w)
                }
                Tol::Fixed(safety) => {
                    let f = sum(k, &|_| 1.0);
                    let e = rk
                        * ((g + 1) as f64
                            + f / 2.0
                            + s_k1 * (1.0 + delta / 2.0)
                            + k as f64 * s_k * delta / 2.0)
                        + k as f64 * r.max(1.0).powi(k as i32);
                    safety * S::EPSILON * e + 1e-12 * a[k]
                }
            }
        })
        .collect()
}

/// The knot index `s` of the non-empty span of the domain containing `u` (right end: last).
fn span_of(knots: &[f64], g: usize, u: f64) -> usize {
    let k = knots.len() - g - 1;
    let mut best = g;
    for s in g..k {
        if knots[s] < knots[s + 1] && knots[s] <= u {
            best = s;
        }
    }
    best
}

/// The knot indices `s` of the non-empty spans of the domain.
fn spans(knots: &[f64], g: usize) -> Vec<usize> {
    let k = knots.len() - g - 1;
    (g..k).filter(|&s| knots[s] < knots[s + 1]).collect()
}

/// A random open B-spline: degree, knots, de Boor points and sample fractions.
#[derive(Clone, Debug)]
struct Case {
    g: usize,
    knots: Vec<f64>,
    points: Vec<Vec<f64>>,
    fracs: Vec<f64>,
    uniform: bool,
}

/// The shape of random cases.
#[derive(Clone, Debug)]
struct Shape {
    degrees: RangeInclusive<usize>,
    dim: usize,
    range: f64,
    min_gap: f64,
    max_gap: f64,
    max_extra: usize,
}

impl Shape {
    fn new(degrees: RangeInclusive<usize>, dim: usize) -> Self {
        Shape {
            degrees,
            dim,
            range: 4.0,
            min_gap: 0.25,
            max_gap: 1.5,
            max_extra: 8,
        }
    }
}

/// Random open B-splines: half of them with equally spaced knots (clamped or not).
fn open_case(shape: Shape) -> impl Strategy<Value = Case> {
    let Shape {
        degrees,
        dim,
        range,
        min_gap,
        max_gap,
        max_extra,
    } = shape;
    (degrees, 0..=max_extra, any::<bool>(), any::<bool>()).prop_flat_map(
        move |(g, extra, clamped, uniform)| {
            let k = g + 1 + extra;
            let m = k + g + 1;
            (
                prop::collection::vec(gap(min_gap, max_gap), m - 1),
                min_gap..max_gap,
                -2.0..2.0_f64,
                strak_tests::points(k..=k, dim, range),
                prop::collection::vec(0.0..1.0_f64, 8),
            )
                .prop_map(move |(gaps, h, start, points, fracs)| {
                    let gaps = if uniform { vec![h; gaps.len()] } else { gaps };
                    Case {
                        g,
                        knots: open_knots(g, clamped, gaps, start, 0.5 * (min_gap + max_gap)),
                        points,
                        fracs,
                        uniform,
                    }
                })
        },
    )
}

/// `eval`, `deriv` (`k = 0..=g+1`) at every knot of the domain and random parameters, and
/// `piece_deriv` at the start, middle and end of every piece, against `bspline_deriv`.
fn check_open<P: Point>(case: &Case, tol: Tol, worst: &Worst) -> TestCaseResult {
    let g = case.g;
    let knots: Vec<P::Scalar> = case.knots.iter().map(|&x| sc(x)).collect();
    let kf: Vec<f64> = knots.iter().map(|x| x.to_f64()).collect();
    let points: Vec<P> = pts(&case.points);
    let pf = to_vecs(&points);
    let b = BSpline::<P, 16, 32>::new(g, &points, &knots)
        .map_err(|e| TestCaseError::fail(format!("B-spline construction failed: {e:?}")))?;
    let c = PowerSpline::<P, 6, 16>::from_bspline(&b)
        .map_err(|e| TestCaseError::fail(format!("conversion failed: {e:?}")))?;
    prop_assert_eq!(c.degree(), g);
    prop_assert_eq!(c.domain(), b.domain());
    if case.uniform && !P::Scalar::IS_FIXED {
        prop_assert!(
            c.is_uniform(),
            "equally spaced knots should give O(1) lookup"
        );
    }
    let tols: Vec<Vec<f64>> = spans(&kf, g)
        .iter()
        .map(|&s| piece_tolerances::<P::Scalar>(tol, &kf, g, &pf, s))
        .collect();
    let sp = spans(&kf, g);
    let tol_at = |s: usize| &tols[sp.iter().position(|&x| x == s).unwrap_or(0)];
    for u in params(&knots, g, &case.fracs) {
        let uf = u.to_f64();
        let t = tol_at(span_of(&kf, g, uf));
        for k in 0..=g + 1 {
            let want = strak_ref::bspline_deriv(&kf, g, &pf, uf, k);
            let what = |f: &str| format!("{f} u = {uf}, k = {k}");
            worst.check(&to_vec(c.deriv(u, k)), &want, t[k], || what("deriv"))?;
            if k == 0 {
                worst.check(&to_vec(c.eval(u)), &want, t[0], || what("eval"))?;
            }
        }
    }
    prop_assert_eq!(c.piece_count(), sp.len());
    for (i, &s) in sp.iter().enumerate() {
        let (a, e) = c.piece_domain(i);
        prop_assert_eq!((a.to_f64(), e.to_f64()), (kf[s], kf[s + 1]));
        let mid = sc::<P::Scalar>(0.5 * (kf[s] + kf[s + 1])).clamp_to(a, e);
        let (sub_k, sub_p) = (&kf[s - g..=s + g + 1], &pf[s - g..=s]);
        for k in 0..=g + 1 {
            let t = tols[i][k];
            let what = |f: &str| format!("piece_deriv piece {i} at {f}, k = {k}");
            let want = strak_ref::bspline_deriv(&kf, g, &pf, kf[s], k);
            worst.check(&to_vec(c.piece_deriv(i, a, k)), &want, t, || what("start"))?;
            let want = strak_ref::bspline_deriv(&kf, g, &pf, mid.to_f64(), k);
            worst.check(&to_vec(c.piece_deriv(i, mid, k)), &want, t, || {
                what("middle")
            })?;
            let want = strak_ref::bspline_deriv(sub_k, g, sub_p, kf[s + 1], k);
            worst.check(&to_vec(c.piece_deriv(i, e, k)), &want, t, || what("end"))?;
        }
    }
    Ok(())
}

fn open<P: Point>(name: &str, cases: u32, shape: Shape, tol: Tol) {
    let worst = Worst::default();
    property(cases, open_case(shape), |case| {
        check_open::<P>(&case, tol, &worst)
    });
    worst.report(name);
}

#[test]
fn power_f64_2d() {
    open::<[f64; 2]>(
        "power f64 [f64; 2]",
        64,
        Shape::new(1..=5, 2),
        Tol::Float(1e-13),
    );
}

#[test]
fn power_f64_3d() {
    open::<[f64; 3]>(
        "power f64 [f64; 3]",
        32,
        Shape::new(1..=5, 3),
        Tol::Float(1e-13),
    );
}

#[test]
fn power_dvec3() {
    open::<DVec3>("power DVec3", 24, Shape::new(1..=5, 3), Tol::Float(1e-13));
}

#[test]
fn power_f32_2d() {
    open::<[f32; 2]>(
        "power f32 [f32; 2]",
        64,
        Shape::new(1..=5, 2),
        Tol::Float(1e-5),
    );
}

#[test]
fn power_vec3() {
    open::<Vec3>("power Vec3", 24, Shape::new(1..=5, 3), Tol::Float(1e-5));
}

#[test]
fn power_i32f32_2d() {
    open::<[I32F32; 2]>(
        "power I32F32 [I32F32; 2]",
        64,
        Shape::new(1..=5, 2),
        Tol::Fixed(4.0),
    );
}

#[test]
fn power_i32f32_3d() {
    open::<[I32F32; 3]>(
        "power I32F32 [I32F32; 3]",
        16,
        Shape::new(1..=5, 3),
        Tol::Fixed(4.0),
    );
}

/// I16F16: range ±16383, so small coordinates (±2), well-spaced knots (gaps ≥ 0.5) and degree
/// ≤ 3 keep every coefficient sum and derivative in range.
#[test]
fn power_i16f16_2d() {
    let shape = Shape {
        range: 2.0,
        min_gap: 0.5,
        max_gap: 1.5,
        ..Shape::new(1..=3, 2)
    };
    open::<[I16F16; 2]>("power I16F16 [I16F16; 2]", 64, shape, Tol::Fixed(4.0));
}

/// A wrong coefficient must fail: perturbing one de Boor point by 1e-9 (points of size ≤ 4)
/// moves the curve by far more than the `f64` tolerance.
#[test]
fn tolerance_detects_a_perturbed_curve() {
    let knots = [0.0, 0.0, 0.0, 0.0, 0.5, 1.25, 2.0, 2.0, 2.0, 2.0];
    let pf = vec![
        vec![0.0, 1.0],
        vec![2.0, 3.0],
        vec![-1.0, -2.0],
        vec![4.0, 0.5],
        vec![3.0, 4.0],
        vec![1.0, -1.0],
    ];
    let mut moved = pf.clone();
    moved[2][0] += 1e-9;
    let b = BSpline::<[f64; 2], 8, 16>::new(3, &pts(&moved), &knots).unwrap();
    let c = PowerSpline::<[f64; 2], 4, 8>::from_bspline(&b).unwrap();
    let s = 4;
    let tols = piece_tolerances::<f64>(Tol::Float(1e-13), &knots, 3, &pf, s);
    let u = 0.9;
    let want = strak_ref::bspline_point(&knots, 3, &pf, u);
    let err = strak_tests::max_diff(&to_vec(c.eval(u)), &want);
    assert!(
        err > tols[0],
        "error {err:e} within tolerance {:e}",
        tols[0]
    );
    // Unperturbed, it is within.
    let b = BSpline::<[f64; 2], 8, 16>::new(3, &pts(&pf), &knots).unwrap();
    let c = PowerSpline::<[f64; 2], 4, 8>::from_bspline(&b).unwrap();
    let err = strak_tests::max_diff(&to_vec(c.eval(u)), &want);
    assert!(err <= tols[0], "error {err:e} > tolerance {:e}", tols[0]);
}

/// Closed B-splines (the open representation over the periodically extended knots): the
/// power form against `BSpline::closed` itself (tested against strak-ref in
/// `bspline_vs_ref.rs`), with the `f64` tolerance of its pieces.
#[test]
fn closed_f64_matches_bspline() {
    let worst = Worst::default();
    property(
        32,
        (
            1..=5_usize,
            strak_tests::points(6..=10, 2, 4.0),
            prop::collection::vec(gap(0.25, 1.5), 11),
            prop::collection::vec(0.0..1.0_f64, 8),
        ),
        |(g, points, gaps, fracs)| {
            let k = points.len();
            let mut period = vec![0.0];
            for i in 0..k {
                period.push(period[i] + gaps[i].max(0.25));
            }
            let p: Vec<[f64; 2]> = pts(&points);
            let b = BSpline::<[f64; 2], 16, 32>::closed(g, &p, Some(&period))
                .map_err(|e| TestCaseError::fail(format!("{e:?}")))?;
            let c = PowerSpline::<[f64; 2], 6, 16>::from_bspline(&b)
                .map_err(|e| TestCaseError::fail(format!("{e:?}")))?;
            prop_assert_eq!(c.piece_count(), k);
            let kf = b.knots().to_vec();
            let pf = to_vecs(b.control_points());
            for u in params(&kf, g, &fracs) {
                let t = piece_tolerances::<f64>(Tol::Float(1e-13), &kf, g, &pf, span_of(&kf, g, u));
                for k in 0..=g + 1 {
                    worst.check(&c.deriv(u, k), &b.deriv(u, k), 2.0 * t[k], || {
                        format!("closed g = {g}, u = {u}, k = {k}")
                    })?;
                }
            }
            Ok(())
        },
    );
    worst.report("closed f64");
}
