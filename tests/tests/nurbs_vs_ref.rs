//! strak-curves' NURBS against strak-ref (`nurbs_point` / `nurbs_deriv`: the rational basis
//! `R_i = h_i N_i / Σ h_j N_j` of seeds/004 with the Cox–de Boor recursion and Leibniz's rule),
//! and the seeds' NURBS properties.
//!
//! Random positive weights in `[0.25, 4]`, random non-uniform knot vectors (clamped or not,
//! inner multiplicities up to the degree), degrees 1..=5, derivatives of orders 0..=3 (a
//! rational curve has non-zero derivatives above its degree), closed curves, in `f64`, `f32`,
//! `I32F32` and `I16F16`.
//!
//! # Tolerances
//!
//! With `H_k` the uncancelled size of the `k`-th derivative of the homogeneous B-spline
//! `(h_i P_i, h_i)` and `W_k` that of the weight function alone (the recursion `A_k` of
//! `bspline_vs_ref.rs`), Leibniz's rule `c^{(j)} = (A^{(j)} − Σ C(j,i) w^{(i)} c^{(j−i)}) / w`
//! bounds the size of every term by
//!
//! ```text
//! C_0 = max |P_i|,   C_j = (H_j + Σ_{i=1..j} C(j,i) W_i C_{j−i}) / min h
//! ```
//!
//! - **Floats:** `|strak − ref| ≤ rel · (j + 1) · C_j`, `rel = 1e-12` for `f64` and `1e-5`
//!   for `f32` (as for B-splines, plus one rounding per Leibniz term).
//! - **Fixed-point:** the homogeneous derivatives carry the B-spline error `e^h_j`
//!   (`4ε((g+1)(2 + 2H_j) + e_j)`); Leibniz's rule propagates it to first order as
//!   `E_j = (e^h_j + Σ C(j,i)(C_{j−i} e^h_i + W_i E_{j−i} + 2ε) + C_j e^h_0) / min h + ε`,
//!   and the tolerance is `4·E_j`.
//!
//! Every test prints the largest `error / tolerance` it met (`cargo test -- --nocapture`).

// The derivative order `k` indexes the tolerances and is passed to the reference: textbook
// index loops read closer to the formulas (as in strak-ref).
#![allow(clippy::needless_range_loop)]

use std::fmt::Debug;
use std::ops::RangeInclusive;

use proptest::prelude::*;
use proptest::test_runner::TestCaseResult;
use strak_curves::glam::{DVec3, Vec3};
use strak_curves::{BSpline, I16F16, I32F32, Nurbs, ParamCurve, ParamCurveDeriv, Point, Scalar};
use strak_tests::spline_cases::{
    Tol, Worst, dyadic_gap, fail, gap, open_knots, params, period_knots, property, sc, scales,
};
use strak_tests::{max_diff, pts, to_vec, to_vecs};

// ---------------------------------------------------------------------------------------------
// Harness (as in bspline_vs_ref.rs)
// ---------------------------------------------------------------------------------------------

fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// Tolerances for the orders `0..=kmax` of a NURBS curve (see the module docs).
fn tolerances<S: Scalar>(
    tol: Tol,
    knots: &[f64],
    g: usize,
    points: &[Vec<f64>],
    weights: &[f64],
    kmax: usize,
) -> Vec<f64> {
    let mag = |p: &Vec<f64>| p.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let hom: Vec<f64> = points
        .iter()
        .zip(weights)
        .map(|(p, w)| (mag(p) * w).max(*w))
        .collect();
    let at = |v: &Vec<f64>, i: usize| v.get(i).copied().unwrap_or(0.0);
    let h = scales(knots, g, &hom, 0.0);
    let w = scales(knots, g, weights, 0.0);
    let w_min = weights.iter().copied().fold(f64::INFINITY, f64::min);
    let mut c = vec![points.iter().map(mag).fold(0.0, f64::max)];
    for j in 1..=kmax {
        let s: f64 = (1..=j).map(|i| binomial(j, i) * at(&w, i) * c[j - i]).sum();
        c.push((at(&h, j) + s) / w_min);
    }
    match tol {
        Tol::Float(rel) => (0..=kmax).map(|j| rel * (j + 1) as f64 * c[j]).collect(),
        Tol::Fixed(safety) => {
            let eps = S::EPSILON;
            let e = scales(knots, g, &vec![0.0; hom.len()], 1.0);
            let eh: Vec<f64> = (0..=kmax)
                .map(|j| 4.0 * eps * ((g + 1) as f64 * (2.0 + 2.0 * at(&h, j)) + at(&e, j)))
                .collect();
            let mut big_e: Vec<f64> = Vec::new();
            for j in 0..=kmax {
                let s: f64 = (1..=j)
                    .map(|i| {
                        binomial(j, i) * (c[j - i] * eh[i] + at(&w, i) * big_e[j - i] + 2.0 * eps)
                    })
                    .sum();
                big_e.push((eh[j] + s + c[j] * eh[0]) / w_min + eps);
            }
            big_e.iter().map(|x| safety * x).collect()
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Random cases
// ---------------------------------------------------------------------------------------------

#[derive(Clone, Debug)]
struct Case {
    g: usize,
    knots: Vec<f64>,
    points: Vec<Vec<f64>>,
    weights: Vec<f64>,
    fracs: Vec<f64>,
}

#[derive(Clone, Debug)]
struct Shape {
    degrees: RangeInclusive<usize>,
    dim: usize,
    range: f64,
    min_gap: f64,
    weights: (f64, f64),
}

impl Shape {
    fn new(degrees: RangeInclusive<usize>, dim: usize) -> Self {
        Shape {
            degrees,
            dim,
            range: 4.0,
            min_gap: 0.25,
            weights: (0.25, 4.0),
        }
    }
}

fn case(shape: Shape) -> impl Strategy<Value = Case> {
    let Shape {
        degrees,
        dim,
        range,
        min_gap,
        weights,
    } = shape;
    (degrees, 0..=5_usize, any::<bool>()).prop_flat_map(move |(g, extra, clamped)| {
        let k = g + 1 + extra;
        let m = k + g + 1;
        (
            prop::collection::vec(gap(min_gap, 1.5), m - 1),
            -2.0..2.0_f64,
            strak_tests::points(k..=k, dim, range),
            prop::collection::vec(weights.0..weights.1, k),
            prop::collection::vec(0.0..1.0_f64, 6),
        )
            .prop_map(move |(gaps, start, points, weights, fracs)| Case {
                g,
                knots: open_knots(g, clamped, gaps, start, 0.5 * (min_gap + 1.5)),
                points,
                weights,
                fracs,
            })
    })
}

// ---------------------------------------------------------------------------------------------
// Open NURBS
// ---------------------------------------------------------------------------------------------

/// `eval`, `deriv` (orders 0..=3), `derivatives` and `piece_deriv` (at the end of each piece
/// against the reference restricted to that piece, whose domain end is the left limit)
/// against `nurbs_deriv`, on the scalar-rounded inputs.
fn check_open<P: Point>(case: &Case, tol: Tol, worst: &Worst) -> TestCaseResult {
    let g = case.g;
    let knots: Vec<P::Scalar> = case.knots.iter().map(|&x| sc(x)).collect();
    let weights: Vec<P::Scalar> = case.weights.iter().map(|&x| sc(x)).collect();
    let kf: Vec<f64> = knots.iter().map(|x| x.to_f64()).collect();
    let wf: Vec<f64> = weights.iter().map(|x| x.to_f64()).collect();
    let points: Vec<P> = pts(&case.points);
    let pf = to_vecs(&points);
    let c = Nurbs::<P, 16, 32>::new(g, &points, &weights, &knots).map_err(fail)?;
    let kmax = 3.min(c.max_deriv_order());
    prop_assert!(c.max_deriv_order() >= g);
    if !P::Scalar::IS_FIXED {
        prop_assert_eq!(c.max_deriv_order(), 7);
    }
    let tols = tolerances::<P::Scalar>(tol, &kf, g, &pf, &wf, kmax);
    for u in params(&knots, g, &case.fracs) {
        let uf = u.to_f64();
        let mut all = vec![P::zero(); kmax + 1];
        c.derivatives(u, &mut all);
        for k in 0..=kmax {
            let want = strak_ref::nurbs_deriv(&kf, g, &pf, &wf, uf, k);
            let what = |f: &str| format!("{f} u = {uf}, k = {k}");
            worst.check(&to_vec(c.deriv(u, k)), &want, tols[k], || what("deriv"))?;
            worst.check(&to_vec(all[k]), &want, tols[k], || what("derivatives"))?;
            if k == 0 {
                worst.check(&to_vec(c.eval(u)), &want, tols[0], || what("eval"))?;
            }
        }
    }
    let spans: Vec<usize> = (g..kf.len() - g - 1)
        .filter(|&s| kf[s] < kf[s + 1])
        .collect();
    prop_assert_eq!(c.piece_count(), spans.len());
    for (i, &s) in spans.iter().enumerate() {
        let (a, b) = c.piece_domain(i);
        let (sk, sp, sw) = (&kf[s - g..=s + g + 1], &pf[s - g..=s], &wf[s - g..=s]);
        for k in 0..=kmax {
            let want = strak_ref::nurbs_deriv(&kf, g, &pf, &wf, kf[s], k);
            worst.check(&to_vec(c.piece_deriv(i, a, k)), &want, tols[k], || {
                format!("piece {i} start k = {k}")
            })?;
            let want = strak_ref::nurbs_deriv(sk, g, sp, sw, kf[s + 1], k);
            worst.check(&to_vec(c.piece_deriv(i, b, k)), &want, tols[k], || {
                format!("piece {i} end k = {k}")
            })?;
        }
    }
    Ok(())
}

fn open<P: Point>(name: &str, cases: u32, shape: Shape, tol: Tol) {
    let worst = Worst::default();
    property(cases, case(shape), |c| check_open::<P>(&c, tol, &worst));
    worst.report(name);
}

#[test]
fn open_f64_2d() {
    open::<[f64; 2]>(
        "NURBS f64 [f64; 2]",
        48,
        Shape::new(1..=5, 2),
        Tol::Float(1e-12),
    );
}

#[test]
fn open_dvec3() {
    open::<DVec3>("NURBS DVec3", 24, Shape::new(1..=5, 3), Tol::Float(1e-12));
}

#[test]
fn open_f64_3d() {
    open::<[f64; 3]>(
        "NURBS f64 [f64; 3]",
        16,
        Shape::new(1..=5, 3),
        Tol::Float(1e-12),
    );
}

#[test]
fn open_f32_2d() {
    open::<[f32; 2]>(
        "NURBS f32 [f32; 2]",
        48,
        Shape::new(1..=5, 2),
        Tol::Float(1e-5),
    );
}

#[test]
fn open_vec3() {
    open::<Vec3>("NURBS Vec3", 24, Shape::new(1..=5, 3), Tol::Float(1e-5));
}

/// I32F32: coordinates ±2, weights in [0.5, 2], so that the rational derivative bounds stay in
/// range for degree ≤ 4.
#[test]
fn open_i32f32_2d() {
    let shape = Shape {
        range: 2.0,
        weights: (0.5, 2.0),
        ..Shape::new(1..=4, 2)
    };
    open::<[I32F32; 2]>("NURBS I32F32 [I32F32; 2]", 48, shape, Tol::Fixed(4.0));
}

/// I16F16: coordinates ±1, weights in [0.5, 2], knot gaps ≥ 0.75 and degree ≤ 2.
#[test]
fn open_i16f16_2d() {
    let shape = Shape {
        range: 1.0,
        min_gap: 0.75,
        weights: (0.5, 2.0),
        ..Shape::new(1..=2, 2)
    };
    open::<[I16F16; 2]>("NURBS I16F16 [I16F16; 2]", 48, shape, Tol::Fixed(4.0));
}

// ---------------------------------------------------------------------------------------------
// Closed NURBS
// ---------------------------------------------------------------------------------------------

/// A closed NURBS curve against `nurbs_deriv` of its definition as an open curve: the periodic
/// extension of the knots (`strak_ref::periodic_extended_knots`) with the last `g` points and
/// weights repeated in front (seeds/000 "geschlossene B-Splines"; the convention of
/// `strak_ref::closed_bspline_point`), for parameters in `[u_0, u_K]`.
#[test]
fn closed_f64() {
    let worst = Worst::default();
    let strategy = (1..=5_usize, 0..=4_usize).prop_flat_map(|(g, extra)| {
        let k = g + 1 + extra;
        (
            Just(g),
            prop::collection::vec(dyadic_gap(), k),
            (-32..=32_i32).prop_map(|n| f64::from(n) / 16.0),
            strak_tests::points(k..=k, 2, 4.0),
            prop::collection::vec(0.25..4.0_f64, k),
            prop::collection::vec(0.0..=1.0_f64, 8),
        )
    });
    property(48, strategy, |(g, gaps, start, points, weights, fracs)| {
        let period = period_knots(g, gaps, start, 0.75);
        let kp = points.len();
        let p: Vec<[f64; 2]> = pts(&points);
        let c = Nurbs::<[f64; 2], 24, 40>::closed(g, &p, &weights, Some(&period)).map_err(fail)?;
        prop_assert!(c.is_closed());
        let ext = strak_ref::periodic_extended_knots(g, &period);
        prop_assert_eq!(c.knots(), ext.as_slice());
        let ep: Vec<Vec<f64>> = points[kp - g..].iter().chain(&points).cloned().collect();
        let ew: Vec<f64> = weights[kp - g..].iter().chain(&weights).copied().collect();
        for (a, b) in to_vecs(c.control_points()).iter().zip(&ep) {
            // projections A_i / h_i of the homogeneous points: one rounding
            prop_assert!(max_diff(a, b) <= 4.0 * f64::EPSILON * 4.0);
        }
        prop_assert_eq!(c.weights(), ew.as_slice());
        let tols = tolerances::<f64>(Tol::Float(1e-12), &ext, g, &ep, &ew, 3);
        let mut us: Vec<f64> = period.clone();
        us.extend(
            fracs
                .iter()
                .map(|f| period[0] + (period[kp] - period[0]) * f),
        );
        for u in us {
            for k in 0..=3 {
                let want = strak_ref::nurbs_deriv(&ext, g, &ep, &ew, u, k);
                worst.check(&c.deriv(u, k), &want, tols[k], || {
                    format!("closed u = {u}, k = {k}")
                })?;
            }
        }
        Ok(())
    });
    worst.report("closed NURBS f64");
}

// ---------------------------------------------------------------------------------------------
// The seeds' properties (seeds/004 "NURBS", "Auswirkung der NURBS-Gewichte")
// ---------------------------------------------------------------------------------------------

/// Equal weights give the B-spline with the same de Boor points: `R_i = h N_i / (h Σ N_j) =
/// N_i`. All orders up to `g + 1`, within the `f64` tolerance (the NURBS divides by `w = h`).
#[test]
fn equal_weights_give_the_bspline() {
    let worst = Worst::default();
    property(
        48,
        (case(Shape::new(1..=5, 2)), 0.25..4.0_f64),
        |(case, h)| {
            let g = case.g;
            let p: Vec<[f64; 2]> = pts(&case.points);
            let w = vec![h; p.len()];
            let r = Nurbs::<[f64; 2], 16, 32>::new(g, &p, &w, &case.knots).map_err(fail)?;
            let b = BSpline::<[f64; 2], 16, 32>::new(g, &p, &case.knots).map_err(fail)?;
            let tols =
                tolerances::<f64>(Tol::Float(1e-12), &case.knots, g, &case.points, &w, g + 1);
            for u in params(&case.knots, g, &case.fracs) {
                for k in 0..=g + 1 {
                    worst.check(&r.deriv(u, k), &b.deriv(u, k), tols[k], || {
                        format!("u = {u}, k = {k}")
                    })?;
                }
            }
            Ok(())
        },
    );
    worst.report("equal weights");
}

/// "Gewicht erhöhen: Punkte wandern auf Kontrollpunkt zu" (seeds/004): raising the weight
/// `h_i` moves every point of the support of `N_i` along the straight line towards `P_i`:
/// `c_new = (A + δ N_i P_i) / (w + δ N_i)` is a convex combination of `c_old` and `P_i`. So
/// the distance to `P_i` shrinks and `c_old`, `c_new`, `P_i` are collinear.
#[test]
fn raising_a_weight_pulls_towards_its_point() {
    property(
        48,
        (
            case(Shape::new(1..=5, 2)),
            any::<prop::sample::Index>(),
            1.5..4.0_f64,
        ),
        |(case, idx, factor)| {
            let g = case.g;
            let p: Vec<[f64; 2]> = pts(&case.points);
            let i = idx.index(p.len());
            let mut heavier = case.weights.clone();
            heavier[i] *= factor;
            let a =
                Nurbs::<[f64; 2], 16, 32>::new(g, &p, &case.weights, &case.knots).map_err(fail)?;
            let b = Nurbs::<[f64; 2], 16, 32>::new(g, &p, &heavier, &case.knots).map_err(fail)?;
            for u in params(&case.knots, g, &case.fracs) {
                if strak_ref::cox_de_boor(&case.knots, i, g, u) < 1e-6 {
                    continue;
                }
                let (x, y) = (a.eval(u), b.eval(u));
                let (d0, d1) = (
                    strak_ref::vec_dist(&x, &p[i]),
                    strak_ref::vec_dist(&y, &p[i]),
                );
                if d0 <= 1e-12 {
                    continue; // the curve passes through P_i here (degree 1 at a knot)
                }
                prop_assert!(d1 < d0, "u = {}: distance {} → {}", u, d0, d1);
                let cross =
                    (x[0] - p[i][0]) * (y[1] - p[i][1]) - (x[1] - p[i][1]) * (y[0] - p[i][0]);
                prop_assert!(
                    cross.abs() <= 1e-12 * (1.0 + d0 * d0),
                    "not collinear: {}",
                    cross
                );
            }
            Ok(())
        },
    );
}

/// Convex hull property with positive weights: every point lies in the bounding box of the
/// `g + 1` control points of its span (the `R_i` are non-negative and sum to one), up to
/// `1e-14·max|P|` of rounding.
#[test]
fn convex_hull() {
    property(48, case(Shape::new(1..=5, 3)), |case| {
        let g = case.g;
        let p: Vec<[f64; 3]> = pts(&case.points);
        let c = Nurbs::<[f64; 3], 16, 32>::new(g, &p, &case.weights, &case.knots).map_err(fail)?;
        let a0 = case
            .points
            .iter()
            .flatten()
            .fold(0.0_f64, |m, x| m.max(x.abs()));
        for u in params(&case.knots, g, &case.fracs) {
            let s = c.knot_vector().span(u);
            let x = c.eval(u);
            for dim in 0..3 {
                let active = p[s - g..=s].iter().map(|d| d[dim]);
                let lo = active.clone().fold(f64::INFINITY, f64::min);
                let hi = active.fold(f64::NEG_INFINITY, f64::max);
                prop_assert!(lo - 1e-14 * a0 <= x[dim] && x[dim] <= hi + 1e-14 * a0);
            }
        }
        Ok(())
    });
}

/// Knot insertion on the homogeneous points keeps the NURBS curve (orders 0..=3).
#[test]
fn knot_insertion_preserves_curve() {
    let worst = Worst::default();
    property(
        48,
        (case(Shape::new(1..=5, 2)), 0.0..=1.0_f64),
        |(case, f)| {
            let g = case.g;
            let p: Vec<[f64; 2]> = pts(&case.points);
            let c =
                Nurbs::<[f64; 2], 24, 40>::new(g, &p, &case.weights, &case.knots).map_err(fail)?;
            let (lo, hi) = c.domain();
            let u = lo + (hi - lo) * f;
            let r = match c.insert_knot(u) {
                Ok(r) => r,
                Err(strak_curves::Error::KnotMultiplicity { .. }) => return Ok(()),
                Err(e) => return Err(fail(e)),
            };
            prop_assert_eq!(r.control_points().len(), p.len() + 1);
            let old = tolerances::<f64>(
                Tol::Float(1e-12),
                &case.knots,
                g,
                &case.points,
                &case.weights,
                3,
            );
            let new = tolerances::<f64>(
                Tol::Float(1e-12),
                r.knots(),
                g,
                &to_vecs(r.control_points()),
                r.weights(),
                3,
            );
            for v in params(&case.knots, g, &case.fracs) {
                for k in 0..=3 {
                    worst.check(&r.deriv(v, k), &c.deriv(v, k), old[k].max(new[k]), || {
                        format!("insert {u}: k = {k} at {v}")
                    })?;
                }
            }
            Ok(())
        },
    );
    worst.report("NURBS knot insertion");
}

/// `to_rational_bezier_segments::<NB, _>`: each segment, evaluated as the rational Bézier
/// curve `Σ w_j b_j B_j(t) / Σ w_j B_j(t)` with strak-ref's Bernstein polynomials, is the
/// curve on its piece.
fn check_rational_segments<const NB: usize>(case: &Case, worst: &Worst) -> TestCaseResult {
    let g = case.g;
    let p: Vec<[f64; 2]> = pts(&case.points);
    let c = Nurbs::<[f64; 2], 16, 32>::new(g, &p, &case.weights, &case.knots).map_err(fail)?;
    let segs = c.to_rational_bezier_segments::<NB, 16>().map_err(fail)?;
    prop_assert_eq!(segs.len(), c.piece_count());
    let tols = tolerances::<f64>(
        Tol::Float(1e-12),
        &case.knots,
        g,
        &case.points,
        &case.weights,
        0,
    );
    for (i, (b, w)) in segs.iter().enumerate() {
        let (lo, hi) = c.piece_domain(i);
        for &t in case.fracs.iter().chain(&[0.0, 1.0]) {
            let (mut num, mut den) = ([0.0; 2], 0.0);
            for j in 0..NB {
                let f = w[j] * strak_ref::bernstein(j, g, t);
                num = [num[0] + f * b[j][0], num[1] + f * b[j][1]];
                den += f;
            }
            let want = [num[0] / den, num[1] / den];
            let got = c.piece_deriv(i, lo + (hi - lo) * t, 0);
            worst.check(&got, &want, tols[0], || format!("segment {i} at t = {t}"))?;
        }
    }
    Ok(())
}

#[test]
fn rational_bezier_segments_preserve_curve() {
    let worst = Worst::default();
    property(48, case(Shape::new(1..=5, 2)), |case| match case.g {
        1 => check_rational_segments::<2>(&case, &worst),
        2 => check_rational_segments::<3>(&case, &worst),
        3 => check_rational_segments::<4>(&case, &worst),
        4 => check_rational_segments::<5>(&case, &worst),
        _ => check_rational_segments::<6>(&case, &worst),
    });
    worst.report("rational Bézier segments");
}

/// The homogeneous B-spline round-trips: `from_homogeneous(c.homogeneous())` is `c`, and its
/// control points are `(h_i P_i, h_i)`.
#[test]
fn homogeneous_round_trip() {
    property(32, case(Shape::new(1..=5, 2)), |case| {
        let p: Vec<[f64; 2]> = pts(&case.points);
        let c =
            Nurbs::<[f64; 2], 16, 32>::new(case.g, &p, &case.weights, &case.knots).map_err(fail)?;
        for (h, (q, w)) in c
            .homogeneous()
            .control_points()
            .iter()
            .zip(p.iter().zip(&case.weights))
        {
            prop_assert_eq!(h.weighted, [q[0] * w, q[1] * w]);
            prop_assert_eq!(h.weight, *w);
        }
        let back = Nurbs::from_homogeneous(c.homogeneous().clone()).map_err(fail)?;
        prop_assert_eq!(back, c);
        Ok(())
    });
}

/// The NURBS circle of seeds/004 at any center and radius against `nurbs_deriv` of the seed's
/// control polygon mapped by `center + radius·P`, orders 0..=3, within `1e-12·C_k` (`f64`).
#[test]
fn circle_vs_reference() {
    let worst = Worst::default();
    property(
        48,
        (
            -10.0..10.0_f64,
            -10.0..10.0_f64,
            0.01..10.0_f64,
            0.0..=4.0_f64,
        ),
        |(cx, cy, r, u)| {
            let c = Nurbs::<[f64; 2], 9, 12>::circle([cx, cy], r).map_err(fail)?;
            let (knots, ctrl, weights) = strak_ref::nurbs_circle();
            let mapped: Vec<Vec<f64>> = ctrl
                .iter()
                .map(|p| vec![cx + r * p[0], cy + r * p[1]])
                .collect();
            // The stored control points are the projections A_i / h_i of the homogeneous points:
            // equal to the mapped square up to one rounding.
            let stored = to_vecs(c.control_points());
            for (a, b) in stored.iter().zip(&mapped) {
                prop_assert!(max_diff(a, b) <= 4.0 * f64::EPSILON * (cx.abs() + cy.abs() + r));
            }
            let tols = tolerances::<f64>(Tol::Float(1e-12), &knots, 2, &mapped, &weights, 3);
            for k in 0..=3 {
                let want = strak_ref::nurbs_deriv(&knots, 2, &mapped, &weights, u, k);
                worst.check(&c.deriv(u, k), &want, tols[k], || {
                    format!("circle u = {u}, k = {k}")
                })?;
            }
            Ok(())
        },
    );
    worst.report("NURBS circle");
}
