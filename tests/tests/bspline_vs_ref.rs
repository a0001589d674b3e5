//! strak-curves' B-splines against strak-ref, the slow textbook Cox–de Boor recursion of the
//! seeds (seeds/000, 002 "Basis-Splines", seeds/004 "B-Splines"), and the seeds' B-spline
//! properties as invariants.
//!
//! Random non-uniform knot vectors (clamped and unclamped, inner multiplicities up to the
//! degree), degrees 1..=5 (and 7 once), derivatives of every order `0..=g+1`, closed curves,
//! in `f64`, `f32`, `I32F32` and `I16F16`, with `[S; 2]`, `[S; 3]`, glam `Vec3` and `DVec3`.
//!
//! # Tolerances
//!
//! The error of both evaluators is governed by the *uncancelled* size of the values they
//! combine. For the `k`-th derivative that is
//!
//! ```text
//! A_0 = max_i |d_i|,    A_r = max_i (g − r + 1)·(a_i + a_{i+1}) / (u_{i+g+1} − u_{i+r})
//! ```
//!
//! (the derivative de Boor point recursion `Q_i = (g−r+1)(Q_{i+1} − Q_i)/Δu` with absolute
//! values and sums instead of differences; `|c^{(k)}| ≤ A_k`, and by the same re-indexing
//! `Σ |d_i| |N_i^{(k)}|` computed without cancellation is at most `A_k` too, which bounds the
//! rounding of the reference). Hence:
//!
//! - **Floats:** `|strak − ref| ≤ rel · A_k` with `rel = 1e-12` for `f64` (about 4500 ulp of
//!   headroom for the `O(g)` roundings of each algorithm) and `rel = 1e-5` for `f32` (about 80
//!   units of `f32` epsilon, for `O(g + k)` roundings in de Boor's algorithm and the
//!   differencing steps; the reference runs in `f64` on the same `f32`-rounded inputs).
//! - **Fixed-point:** errors are absolute. Every division of a derivative step rounds by one
//!   `ε` and amplifies the incoming error by `(g−r+1)·2/Δu`, giving `e_k` (the same recursion
//!   with `e_0 = 0` and `+1` per step); every de Boor level adds `2ε` for the two products and
//!   `ε·2A_k` for the rounded `α`. The tolerance is `4·ε·((g+1)(2 + 2A_k) + e_k)`: a factor 4
//!   over this first-order estimate.
//!
//! Closed curves additionally compare inputs that differ by the rounding of the periodically
//! extended knots (`δ`, measured); that perturbation is allowed as `(g+1)·δ·(A_{k+1} + A_k/Δ)`.
//!
//! Every test prints the largest `error / tolerance` it met (`cargo test -- --nocapture`).

// The derivative order `k` indexes the tolerances and is passed to the reference: textbook
// index loops read closer to the formulas (as in strak-ref).
#![allow(clippy::needless_range_loop)]

use std::fmt::Debug;
use std::ops::RangeInclusive;

use proptest::prelude::*;
use proptest::test_runner::{TestCaseError, TestCaseResult};
use strak_curves::glam::{DVec3, Vec3};
use strak_curves::{
    BSpline, Error, I16F16, I32F32, KnotVector, ParamCurve, ParamCurveDeriv, Point, Scalar,
    basis_function, bspline_basis, bspline_basis_derivs, classify_breaks,
};
use strak_tests::spline_cases::{
    Tol, Worst, dyadic_gap, gap, open_knots, params, period_knots, property, sc, scales,
};
use strak_tests::{max_diff, pts, to_vec, to_vecs};

// ---------------------------------------------------------------------------------------------
// Harness
// ---------------------------------------------------------------------------------------------

/// The smallest positive knot difference.
fn min_gap(knots: &[f64]) -> f64 {
    knots
        .windows(2)
        .map(|w| w[1] - w[0])
        .filter(|&d| d > 0.0)
        .fold(f64::INFINITY, f64::min)
}

/// Tolerances for the derivative orders `0..=g+1` of a B-spline with these (already rounded)
/// knots and points; `delta` is a knot perturbation between the two evaluators.
fn tolerances<S: Scalar>(
    tol: Tol,
    knots: &[f64],
    g: usize,
    points: &[Vec<f64>],
    delta: f64,
) -> Vec<f64> {
    let mags: Vec<f64> = points
        .iter()
        .map(|p| p.iter().fold(0.0_f64, |m, x| m.max(x.abs())))
        .collect();
    let a = scales(knots, g, &mags, 0.0);
    let e = scales(knots, g, &vec![0.0; mags.len()], 1.0);
    let dmin = min_gap(knots);
    (0..=g + 1)
        .map(|k| {
            let next = a.get(k + 1).copied().unwrap_or(0.0);
            let knot_term = (g + 1) as f64 * delta * (next + a[k] / dmin);
            let base = match tol {
                Tol::Float(rel) => rel * a[k],
                Tol::Fixed(safety) => {
                    safety * S::EPSILON * ((g + 1) as f64 * (2.0 + 2.0 * a[k]) + e[k])
                }
            };
            base + knot_term
        })
        .collect()
}

/// The knot indices `s` of the non-empty spans `[u_s, u_{s+1})` of the domain `[u_g, u_K]`.
fn spans(knots: &[f64], g: usize) -> Vec<usize> {
    let k = knots.len() - g - 1;
    (g..k).filter(|&s| knots[s] < knots[s + 1]).collect()
}

// ---------------------------------------------------------------------------------------------
// Random knot vectors
// ---------------------------------------------------------------------------------------------

/// A random open B-spline: degree, knots, de Boor points and sample positions (fractions of
/// the domain).
#[derive(Clone, Debug)]
struct Case {
    g: usize,
    knots: Vec<f64>,
    points: Vec<Vec<f64>>,
    fracs: Vec<f64>,
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
            max_extra: 5,
        }
    }
}

/// Random open B-splines of the given shape (clamped or not).
fn open_case(shape: Shape) -> impl Strategy<Value = Case> {
    let Shape {
        degrees,
        dim,
        range,
        min_gap,
        max_gap,
        max_extra,
    } = shape;
    (degrees, 0..=max_extra, any::<bool>()).prop_flat_map(move |(g, extra, clamped)| {
        let k = g + 1 + extra;
        let m = k + g + 1;
        (
            prop::collection::vec(gap(min_gap, max_gap), m - 1),
            -2.0..2.0_f64,
            strak_tests::points(k..=k, dim, range),
            prop::collection::vec(0.0..1.0_f64, 6),
        )
            .prop_map(move |(gaps, start, points, fracs)| Case {
                g,
                knots: open_knots(g, clamped, gaps, start, 0.5 * (min_gap + max_gap)),
                points,
                fracs,
            })
    })
}

// ---------------------------------------------------------------------------------------------
// Open curves
// ---------------------------------------------------------------------------------------------

/// Every evaluation path of an open B-spline of point type `P` against `bspline_deriv`:
/// `eval`, `deriv` for `k = 0..=g+1`, `derivatives`, and `piece_deriv` at the start, middle
/// and end of every piece (the end against the left limit of the reference restricted to the
/// piece: knots `u_{s−g}..u_{s+g+1}` and points `d_{s−g}..d_s`, whose domain is the span).
fn check_open<P: Point>(case: &Case, tol: Tol, worst: &Worst) -> TestCaseResult {
    let g = case.g;
    let knots: Vec<P::Scalar> = case.knots.iter().map(|&x| sc(x)).collect();
    let kf: Vec<f64> = knots.iter().map(|x| x.to_f64()).collect();
    let points: Vec<P> = pts(&case.points);
    let pf = to_vecs(&points);
    let c = BSpline::<P, 16, 32>::new(g, &points, &knots)
        .map_err(|e| TestCaseError::fail(format!("construction failed: {e:?}")))?;
    let tols = tolerances::<P::Scalar>(tol, &kf, g, &pf, 0.0);
    for u in params(&knots, g, &case.fracs) {
        let uf = u.to_f64();
        let mut all = vec![P::zero(); g + 2];
        c.derivatives(u, &mut all);
        for k in 0..=g + 1 {
            let want = strak_ref::bspline_deriv(&kf, g, &pf, uf, k);
            let what = |f: &str| format!("{f} u = {uf}, k = {k}");
            worst.check(&to_vec(c.deriv(u, k)), &want, tols[k], || what("deriv"))?;
            worst.check(&to_vec(all[k]), &want, tols[k], || what("derivatives"))?;
            if k == 0 {
                worst.check(&to_vec(c.eval(u)), &want, tols[0], || what("eval"))?;
            }
        }
    }
    let sp = spans(&kf, g);
    prop_assert_eq!(c.piece_count(), sp.len());
    for (i, &s) in sp.iter().enumerate() {
        let (a, b) = c.piece_domain(i);
        prop_assert_eq!((a.to_f64(), b.to_f64()), (kf[s], kf[s + 1]));
        let mid = sc::<P::Scalar>(0.5 * (kf[s] + kf[s + 1])).clamp_to(a, b);
        let (sub_k, sub_p) = (&kf[s - g..=s + g + 1], &pf[s - g..=s]);
        for k in 0..=g + 1 {
            let what = |f: &str| format!("piece_deriv piece {i} at {f}, k = {k}");
            let want = strak_ref::bspline_deriv(&kf, g, &pf, kf[s], k);
            worst.check(&to_vec(c.piece_deriv(i, a, k)), &want, tols[k], || {
                what("start")
            })?;
            let want = strak_ref::bspline_deriv(&kf, g, &pf, mid.to_f64(), k);
            worst.check(&to_vec(c.piece_deriv(i, mid, k)), &want, tols[k], || {
                what("middle")
            })?;
            let want = strak_ref::bspline_deriv(sub_k, g, sub_p, kf[s + 1], k);
            worst.check(&to_vec(c.piece_deriv(i, b, k)), &want, tols[k], || {
                what("end")
            })?;
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
fn open_f64_2d() {
    open::<[f64; 2]>(
        "open f64 [f64; 2]",
        48,
        Shape::new(1..=5, 2),
        Tol::Float(1e-12),
    );
}

#[test]
fn open_f64_3d() {
    open::<[f64; 3]>(
        "open f64 [f64; 3]",
        32,
        Shape::new(1..=5, 3),
        Tol::Float(1e-12),
    );
}

#[test]
fn open_dvec3() {
    open::<DVec3>("open DVec3", 24, Shape::new(1..=5, 3), Tol::Float(1e-12));
}

#[test]
fn open_degree_7_f64() {
    let shape = Shape {
        max_extra: 3,
        ..Shape::new(7..=7, 2)
    };
    open::<[f64; 2]>("open degree 7 f64", 6, shape, Tol::Float(1e-12));
}

#[test]
fn open_f32_2d() {
    open::<[f32; 2]>(
        "open f32 [f32; 2]",
        48,
        Shape::new(1..=5, 2),
        Tol::Float(1e-5),
    );
}

#[test]
fn open_vec3() {
    open::<Vec3>("open Vec3", 24, Shape::new(1..=5, 3), Tol::Float(1e-5));
}

#[test]
fn open_i32f32_2d() {
    open::<[I32F32; 2]>(
        "open I32F32 [I32F32; 2]",
        48,
        Shape::new(1..=5, 2),
        Tol::Fixed(4.0),
    );
}

#[test]
fn open_i32f32_3d() {
    open::<[I32F32; 3]>(
        "open I32F32 [I32F32; 3]",
        16,
        Shape::new(1..=5, 3),
        Tol::Fixed(4.0),
    );
}

/// I16F16: range ±16383, so small coordinates (±2), well-spaced knots (gaps ≥ 0.5) and degree
/// ≤ 3 keep every derivative (≲ 800) in range.
#[test]
fn open_i16f16_2d() {
    let shape = Shape {
        range: 2.0,
        min_gap: 0.5,
        max_gap: 1.5,
        ..Shape::new(1..=3, 2)
    };
    open::<[I16F16; 2]>("open I16F16 [I16F16; 2]", 48, shape, Tol::Fixed(4.0));
}

// ---------------------------------------------------------------------------------------------
// Closed curves
// ---------------------------------------------------------------------------------------------

/// A random closed B-spline: `K` points and the `K + 1` knots of one period (or `None` for
/// uniform knots on `[0, 1]`).
#[derive(Clone, Debug)]
struct ClosedCase {
    g: usize,
    period: Option<Vec<f64>>,
    points: Vec<Vec<f64>>,
    fracs: Vec<f64>,
}

fn closed_case(degrees: RangeInclusive<usize>, dim: usize) -> impl Strategy<Value = ClosedCase> {
    (degrees, 0..=5_usize, any::<bool>()).prop_flat_map(move |(g, extra, uniform)| {
        let k = g + 1 + extra;
        (
            prop::collection::vec(dyadic_gap(), k),
            (-32..=32_i32).prop_map(|n| f64::from(n) / 16.0),
            strak_tests::points(k..=k, dim, 4.0),
            prop::collection::vec(0.0..1.0_f64, 8),
        )
            .prop_map(move |(gaps, start, points, fracs)| ClosedCase {
                g,
                period: (!uniform).then(|| period_knots(g, gaps, start, 0.75)),
                points,
                fracs,
            })
    })
}

/// A closed B-spline against `closed_bspline_deriv` (which wraps the parameter): every order at
/// `u_0`, every knot and random parameters in `[u_0, u_K)`; at `u_K` (the last piece, a left
/// limit) the orders `k ≤ g − μ` that are continuous across the seam of multiplicity `μ`.
fn check_closed<P: Point>(case: &ClosedCase, tol: Tol, worst: &Worst) -> TestCaseResult {
    let g = case.g;
    let points: Vec<P> = pts(&case.points);
    let pf = to_vecs(&points);
    let kp = points.len();
    let period_s: Option<Vec<P::Scalar>> = case
        .period
        .as_ref()
        .map(|v| v.iter().map(|&x| sc(x)).collect());
    let c = BSpline::<P, 24, 40>::closed(g, &points, period_s.as_deref())
        .map_err(|e| TestCaseError::fail(format!("construction failed: {e:?}")))?;
    prop_assert!(c.is_closed());
    // One period as strak stores it (for `None`, the uniform knots rounded to `S`).
    let period: Vec<f64> = c.knots()[g..=g + kp].iter().map(|x| x.to_f64()).collect();
    if let Some(v) = &period_s {
        prop_assert_eq!(&c.knots()[g..=g + kp], v.as_slice());
    } else {
        let uniform = strak_ref::periodic_uniform_knots(kp);
        prop_assert!(max_diff(&period, &uniform) <= P::Scalar::EPSILON);
    }
    // The extended representation: knots as the reference extends them, last g points first.
    let ext = strak_ref::periodic_extended_knots(g, &period);
    let kf: Vec<f64> = c.knots().iter().map(|x| x.to_f64()).collect();
    prop_assert_eq!(kf.len(), ext.len());
    let delta = max_diff(&kf, &ext);
    prop_assert!(
        delta <= 4.0 * P::Scalar::EPSILON * extent_abs(&ext),
        "extended knots differ by {delta:e}"
    );
    let ext_points: Vec<Vec<f64>> = pf[kp - g..].iter().chain(&pf).cloned().collect();
    prop_assert_eq!(to_vecs(c.control_points()), ext_points.clone());
    let tols = tolerances::<P::Scalar>(tol, &ext, g, &ext_points, delta);
    let (lo, hi) = c.domain();
    prop_assert_eq!((lo.to_f64(), hi.to_f64()), (period[0], period[kp]));
    let mut us: Vec<P::Scalar> = c.knots()[g..g + kp].to_vec();
    for f in &case.fracs {
        us.push(sc::<P::Scalar>(period[0] + (period[kp] - period[0]) * f).clamp_to(lo, hi));
    }
    for u in us {
        let uf = u.to_f64();
        if uf >= period[kp] {
            continue;
        }
        for k in 0..=g + 1 {
            let want = strak_ref::closed_bspline_deriv(g, &pf, &period, uf, k);
            worst.check(&to_vec(c.deriv(u, k)), &want, tols[k], || {
                format!("closed u = {uf}, k = {k}")
            })?;
        }
    }
    // The seam: multiplicity of u_0 around the circle.
    let mu = period[..kp].iter().filter(|&&x| x == period[0]).count()
        + period[1..kp].iter().filter(|&&x| x == period[kp]).count();
    for k in 0..=g - mu {
        let want = strak_ref::closed_bspline_deriv(g, &pf, &period, period[0], k);
        worst.check(&to_vec(c.deriv(hi, k)), &want, tols[k], || {
            format!("closed seam u_K, k = {k}")
        })?;
    }
    Ok(())
}

/// The largest magnitude in a list of values (at least 1).
fn extent_abs(v: &[f64]) -> f64 {
    v.iter().fold(1.0_f64, |m, x| m.max(x.abs()))
}

fn closed<P: Point>(name: &str, cases: u32, dim: usize, tol: Tol) {
    let worst = Worst::default();
    property(cases, closed_case(1..=5, dim), |case| {
        check_closed::<P>(&case, tol, &worst)
    });
    worst.report(name);
}

#[test]
fn closed_f64_2d() {
    closed::<[f64; 2]>("closed f64 [f64; 2]", 48, 2, Tol::Float(1e-12));
}

#[test]
fn closed_dvec3() {
    closed::<DVec3>("closed DVec3", 16, 3, Tol::Float(1e-12));
}

#[test]
fn closed_f32_2d() {
    closed::<[f32; 2]>("closed f32 [f32; 2]", 32, 2, Tol::Float(1e-5));
}

#[test]
fn closed_i32f32_2d() {
    closed::<[I32F32; 2]>("closed I32F32 [I32F32; 2]", 32, 2, Tol::Fixed(4.0));
}

// ---------------------------------------------------------------------------------------------
// Basis functions
// ---------------------------------------------------------------------------------------------

/// `bspline_basis`, `bspline_basis_derivs` and `basis_function` against `cox_de_boor` and
/// `cox_de_boor_deriv`: the span agrees with `bspline_span`, the `g + 1` active functions and
/// all derivative rows match, entries above `g` are zero, and `basis_function` matches for
/// every index, also outside the domain (no clamping there).
fn check_basis<S: Scalar>(case: &Case, tol: Tol, worst: &Worst) -> TestCaseResult {
    let g = case.g;
    let knots: Vec<S> = case.knots.iter().map(|&x| sc(x)).collect();
    let kf: Vec<f64> = knots.iter().map(|x| x.to_f64()).collect();
    let kv = KnotVector::<S, 32>::new(g, &knots)
        .map_err(|e| TestCaseError::fail(format!("knot vector rejected: {e:?}")))?;
    let kp = kv.control_point_count();
    prop_assert_eq!(kp, knots.len() - g - 1);
    // Unit de Boor points: the tolerances of the basis functions themselves.
    let tols = tolerances::<S>(tol, &kf, g, &vec![vec![1.0]; kp], 0.0);
    for u in params(&knots, g, &case.fracs) {
        let uf = u.to_f64();
        let (s, n) = bspline_basis(&kv, u);
        prop_assert_eq!(s, strak_ref::bspline_span(&kf, g, uf), "span at {}", uf);
        let mut rows = vec![[S::ZERO; 8]; g + 2];
        let (s2, valid) = bspline_basis_derivs(&kv, u, &mut rows);
        prop_assert_eq!((s2, valid), (s, g + 2));
        for j in 0..8 {
            if j > g {
                prop_assert!(n[j] == S::ZERO && rows.iter().all(|r| r[j] == S::ZERO));
                continue;
            }
            let i = s - g + j;
            let want = strak_ref::cox_de_boor(&kf, i, g, uf);
            worst.check(&[n[j].to_f64()], &[want], tols[0], || {
                format!("N_{i} at {uf}")
            })?;
            for (k, row) in rows.iter().enumerate() {
                let want = strak_ref::cox_de_boor_deriv(&kf, i, g, uf, k);
                worst.check(&[row[j].to_f64()], &[want], tols[k], || {
                    format!("N_{i}^({k}) at {uf}")
                })?;
            }
        }
    }
    // basis_function, inside and outside the domain.
    let (a, b) = (kf[0] - 0.5, kf[kf.len() - 1] + 0.5);
    let mut us: Vec<f64> = kf.clone();
    us.extend(case.fracs.iter().map(|f| a + (b - a) * f));
    for uf in us {
        let u = sc::<S>(uf);
        for i in 0..kp {
            let got = basis_function(&knots, i, g, u)
                .map_err(|e| TestCaseError::fail(format!("{e:?}")))?;
            let want = strak_ref::cox_de_boor(&kf, i, g, u.to_f64());
            worst.check(&[got.to_f64()], &[want], tols[0], || {
                format!("basis_function N_{i} at {uf}")
            })?;
        }
    }
    Ok(())
}

fn basis<S: Scalar>(name: &str, cases: u32, degrees: RangeInclusive<usize>, tol: Tol) {
    let worst = Worst::default();
    property(cases, open_case(Shape::new(degrees, 1)), |case| {
        check_basis::<S>(&case, tol, &worst)
    });
    worst.report(name);
}

#[test]
fn basis_f64() {
    basis::<f64>("basis f64", 48, 1..=5, Tol::Float(1e-12));
}

#[test]
fn basis_degree_7_f64() {
    basis::<f64>("basis degree 7 f64", 6, 6..=7, Tol::Float(1e-12));
}

#[test]
fn basis_f32() {
    basis::<f32>("basis f32", 32, 1..=5, Tol::Float(1e-5));
}

#[test]
fn basis_i32f32() {
    basis::<I32F32>("basis I32F32", 32, 1..=5, Tol::Fixed(4.0));
}

#[test]
fn basis_i16f16() {
    basis::<I16F16>("basis I16F16", 32, 1..=3, Tol::Fixed(4.0));
}

/// Bernstein polynomials as the special case of B-splines (seeds/004 "Sonderfall": knots
/// `0,…,0, 1,…,1`, each `g + 1` times): `N_i^g = B_i^g` with all derivatives, degrees 1..=7.
#[test]
fn bernstein_special_case() {
    let worst = Worst::default();
    property(48, (1..=7_usize, 0.0..=1.0_f64), |(g, t)| {
        let knots: Vec<f64> = (0..2 * g + 2)
            .map(|j| if j <= g { 0.0 } else { 1.0 })
            .collect();
        let kv = KnotVector::<f64, 16>::new(g, &knots)
            .map_err(|e| TestCaseError::fail(format!("{e:?}")))?;
        let tols = tolerances::<f64>(Tol::Float(1e-13), &knots, g, &vec![vec![1.0]; g + 1], 0.0);
        let mut rows = vec![[0.0; 8]; g + 1];
        let (s, _) = bspline_basis_derivs(&kv, t, &mut rows);
        prop_assert_eq!(s, g);
        for i in 0..=g {
            for (k, row) in rows.iter().enumerate() {
                let want = strak_ref::bernstein_deriv(i, g, t, k);
                worst.check(&[row[i]], &[want], tols[k], || {
                    format!("B_{i}^{g}({k}) at {t}")
                })?;
            }
        }
        Ok(())
    });
    worst.report("Bernstein special case");
}

// ---------------------------------------------------------------------------------------------
// The seeds' properties (seeds/000, 002 "Basis-Splines Eigenschaften")
// ---------------------------------------------------------------------------------------------

/// "Die N_i^g(t) summieren sich zu 1 und sind größer gleich null": partition of unity and
/// non-negativity of the active basis functions (exactly non-negative: every step of the
/// triangular scheme is a convex split); derivative rows sum to zero.
/// "Die Basisfunktion N_i^g beeinflusst den Spline im Parameterbereich [u_i, u_{i+g+1})":
/// `N_i^g` is exactly zero outside and positive inside its support.
fn check_partition<S: Scalar>(case: &Case, unity: f64) -> TestCaseResult {
    let g = case.g;
    let knots: Vec<S> = case.knots.iter().map(|&x| sc(x)).collect();
    let kf: Vec<f64> = knots.iter().map(|x| x.to_f64()).collect();
    let kv =
        KnotVector::<S, 32>::new(g, &knots).map_err(|e| TestCaseError::fail(format!("{e:?}")))?;
    let tols = tolerances::<f64>(
        Tol::Float(1e-12),
        &kf,
        g,
        &vec![vec![1.0]; kv.control_point_count()],
        0.0,
    );
    for u in params(&knots, g, &case.fracs) {
        let (_, n) = bspline_basis(&kv, u);
        prop_assert!(
            n.iter().all(|&x| x >= S::ZERO),
            "negative basis value at {:?}: {:?}",
            u,
            n
        );
        let sum: f64 = n.iter().map(|x| x.to_f64()).sum();
        prop_assert!((sum - 1.0).abs() <= unity, "Σ N = {} at {:?}", sum, u);
        if !S::IS_FIXED {
            let mut rows = vec![[S::ZERO; 8]; g + 1];
            bspline_basis_derivs(&kv, u, &mut rows);
            for (k, row) in rows.iter().enumerate().skip(1) {
                let s: f64 = row.iter().map(|x| x.to_f64()).sum();
                prop_assert!(s.abs() <= tols[k] * (g + 1) as f64, "Σ N^({}) = {}", k, s);
            }
        }
    }
    let (a, b) = (kf[0] - 1.0, kf[kf.len() - 1] + 1.0);
    for f in &case.fracs {
        let u = sc::<S>(a + (b - a) * f);
        let uf = u.to_f64();
        for i in 0..kv.control_point_count() {
            let n = basis_function(&knots, i, g, u)
                .map_err(|e| TestCaseError::fail(format!("{e:?}")))?;
            let (lo, hi) = (kf[i], kf[i + g + 1]);
            if uf < lo || uf > hi || (uf == hi && uf != kf[kf.len() - g - 1]) {
                prop_assert!(
                    n == S::ZERO,
                    "N_{} = {:?} outside its support at {}",
                    i,
                    n,
                    uf
                );
            } else if lo < uf && uf < hi && !S::IS_FIXED {
                // (Fixed-point may round a tiny value near the support's ends to zero.)
                prop_assert!(
                    n > S::ZERO,
                    "N_{} = {:?} not positive inside its support at {}",
                    i,
                    n,
                    uf
                );
            }
        }
    }
    Ok(())
}

#[test]
fn partition_of_unity_non_negativity_local_support_f64() {
    property(48, open_case(Shape::new(1..=7, 1)), |case| {
        check_partition::<f64>(&case, 4e-16 * 8.0)
    });
}

/// In fixed-point the convex splits truncate, so the sum may fall short of 1 by about one `ε`
/// per product: at most `2(g+1)ε`, checked with `16ε`.
#[test]
fn partition_of_unity_non_negativity_local_support_i32f32() {
    property(32, open_case(Shape::new(1..=5, 1)), |case| {
        check_partition::<I32F32>(&case, 16.0 * I32F32::EPSILON)
    });
}

/// "Das Intervall [u_i, u_{i+1}) wird nur von den g+1 De Boor-Punkten d_{i−g}, …, d_i
/// beeinflusst": moving `d_j` leaves the curve bit-for-bit unchanged outside
/// `[u_j, u_{j+g+1}]`, and changes it inside (where `N_j > 1e-6`, so that the change is
/// visible in `f64`).
#[test]
fn local_control() {
    property(
        48,
        (
            open_case(Shape::new(1..=5, 2)),
            any::<prop::sample::Index>(),
        ),
        |(case, idx)| {
            let g = case.g;
            let points: Vec<[f64; 2]> = pts(&case.points);
            let c = BSpline::<[f64; 2], 16, 32>::new(g, &points, &case.knots)
                .map_err(|e| TestCaseError::fail(format!("{e:?}")))?;
            let j = idx.index(points.len());
            let mut moved = points.clone();
            moved[j] = [moved[j][0] + 1.0, moved[j][1] - 2.0];
            let d = BSpline::<[f64; 2], 16, 32>::new(g, &moved, &case.knots)
                .map_err(|e| TestCaseError::fail(format!("{e:?}")))?;
            let (lo, hi) = (case.knots[j], case.knots[j + g + 1]);
            for u in params(&case.knots, g, &case.fracs) {
                if u < lo || u > hi {
                    prop_assert_eq!(c.eval(u), d.eval(u), "u = {} outside [{}, {}]", u, lo, hi);
                } else if lo < u && u < hi && strak_ref::cox_de_boor(&case.knots, j, g, u) > 1e-6 {
                    prop_assert_ne!(c.eval(u), d.eval(u), "u = {} inside ({}, {})", u, lo, hi);
                }
            }
            Ok(())
        },
    );
}

/// "Der Spline liegt in der Vereinigung der konvexen Hüllen von d_i, …, d_{i+g}": each point
/// lies in the bounding box of the `g + 1` de Boor points of its span (a necessary condition
/// of the convex hull property), up to `1e-15·A_0` of rounding in `f64` and `2(g+1)ε` of
/// truncation in fixed-point.
fn check_hull<P: Point>(case: &Case, slack: impl Fn(f64) -> f64) -> TestCaseResult {
    let g = case.g;
    let knots: Vec<P::Scalar> = case.knots.iter().map(|&x| sc(x)).collect();
    let points: Vec<P> = pts(&case.points);
    let pf = to_vecs(&points);
    let c = BSpline::<P, 16, 32>::new(g, &points, &knots)
        .map_err(|e| TestCaseError::fail(format!("{e:?}")))?;
    let a0 = pf.iter().flatten().fold(0.0_f64, |m, x| m.max(x.abs()));
    for u in params(&knots, g, &case.fracs) {
        let s = c.knot_vector().span(u);
        let p = to_vec(c.eval(u));
        for (dim, x) in p.iter().enumerate() {
            let active = pf[s - g..=s].iter().map(|d| d[dim]);
            let lo = active.clone().fold(f64::INFINITY, f64::min);
            let hi = active.fold(f64::NEG_INFINITY, f64::max);
            prop_assert!(
                lo - slack(a0) <= *x && *x <= hi + slack(a0),
                "coordinate {} = {} outside [{}, {}] at u = {:?}",
                dim,
                x,
                lo,
                hi,
                u
            );
        }
    }
    Ok(())
}

#[test]
fn convex_hull_f64() {
    property(48, open_case(Shape::new(1..=5, 3)), |case| {
        check_hull::<[f64; 3]>(&case, |a0| 1e-15 * a0)
    });
}

#[test]
fn convex_hull_i16f16() {
    let shape = Shape {
        range: 2.0,
        min_gap: 0.5,
        ..Shape::new(1..=3, 2)
    };
    property(48, open_case(shape), |case| {
        let g = case.g as f64;
        check_hull::<[I16F16; 2]>(&case, move |_| 2.0 * (g + 1.0) * I16F16::EPSILON)
    });
}

/// "affin invariant" (seeds/000, 004 "Affine Abbildung y = A·x + b"): the curve of the mapped
/// de Boor points is the mapped curve, within `1e-12·(|A|·A_k + |b|)`.
#[test]
fn affine_invariance() {
    let worst = Worst::default();
    let map = prop::collection::vec(-2.0..2.0_f64, 6);
    property(48, (open_case(Shape::new(1..=5, 2)), map), |(case, m)| {
        let g = case.g;
        let affine = |p: &[f64]| {
            [
                m[0] * p[0] + m[1] * p[1] + m[4],
                m[2] * p[0] + m[3] * p[1] + m[5],
            ]
        };
        let linear = |p: &[f64]| [m[0] * p[0] + m[1] * p[1], m[2] * p[0] + m[3] * p[1]];
        let points: Vec<[f64; 2]> = pts(&case.points);
        let mapped: Vec<[f64; 2]> = points.iter().map(|p| affine(p)).collect();
        let c = BSpline::<[f64; 2], 16, 32>::new(g, &points, &case.knots)
            .map_err(|e| TestCaseError::fail(format!("{e:?}")))?;
        let d = BSpline::<[f64; 2], 16, 32>::new(g, &mapped, &case.knots)
            .map_err(|e| TestCaseError::fail(format!("{e:?}")))?;
        let pf = to_vecs(&points);
        let tols = tolerances::<f64>(Tol::Float(1e-12), &case.knots, g, &pf, 0.0);
        let norm = m[..4].iter().fold(0.0_f64, |s, x| s + x.abs());
        let shift = m[4].abs().max(m[5].abs());
        for u in params(&case.knots, g, &case.fracs) {
            worst.check(
                &d.eval(u),
                &affine(&c.eval(u)),
                tols[0] * norm + 1e-12 * shift,
                || format!("point at {u}"),
            )?;
            for k in 1..=g {
                // Derivatives transform with the linear part only.
                worst.check(
                    &d.deriv(u, k),
                    &linear(&c.deriv(u, k)),
                    tols[k] * norm,
                    || format!("k = {k} at {u}"),
                )?;
            }
        }
        Ok(())
    });
    worst.report("affine invariance");
}

/// Clamped knot vectors ("offene B-Splines", end multiplicity `g + 1`): the curve starts at
/// `d_0` and ends at `d_{K−1}` — exactly, since every de Boor weight `α` is exactly 0 resp. 1
/// there — with the end tangents `g/(u_{g+1} − u_1)·(d_1 − d_0)` and
/// `g/(u_{K+g−1} − u_{K−1})·(d_{K−1} − d_{K−2})` ("Endtangenteninterpolation", seeds/000).
fn check_clamped_ends<P: Point>(case: &Case, tangent_tol: f64) -> TestCaseResult {
    let g = case.g;
    let kp = case.points.len();
    let knots: Vec<P::Scalar> = (0..kp + g + 1)
        .map(|j| {
            sc(if j <= g {
                case.knots[g]
            } else if j >= kp {
                case.knots[kp]
            } else {
                case.knots[j]
            })
        })
        .collect();
    let kf: Vec<f64> = knots.iter().map(|x| x.to_f64()).collect();
    let points: Vec<P> = pts(&case.points);
    let pf = to_vecs(&points);
    let c = match BSpline::<P, 16, 32>::new(g, &points, &knots) {
        Ok(c) => c,
        // Clamping can create an inner run longer than g next to an end run: not a case.
        Err(Error::KnotMultiplicity { .. }) => return Ok(()),
        Err(e) => return Err(TestCaseError::fail(format!("{e:?}"))),
    };
    let (lo, hi) = c.domain();
    prop_assert_eq!(c.eval(lo), points[0]);
    prop_assert_eq!(c.eval(hi), points[kp - 1]);
    let start: Vec<f64> = (0..P::DIM)
        .map(|i| g as f64 / (kf[g + 1] - kf[1]) * (pf[1][i] - pf[0][i]))
        .collect();
    let end: Vec<f64> = (0..P::DIM)
        .map(|i| g as f64 / (kf[kp + g - 1] - kf[kp - 1]) * (pf[kp - 1][i] - pf[kp - 2][i]))
        .collect();
    let scale = |v: &[f64]| tangent_tol * v.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
    let got = to_vec(c.deriv(lo, 1));
    prop_assert!(
        max_diff(&got, &start) <= scale(&start),
        "start tangent {:?} vs {:?}",
        got,
        start
    );
    let got = to_vec(c.deriv(hi, 1));
    prop_assert!(
        max_diff(&got, &end) <= scale(&end),
        "end tangent {:?} vs {:?}",
        got,
        end
    );
    Ok(())
}

#[test]
fn clamped_end_interpolation_f64() {
    property(48, open_case(Shape::new(1..=5, 2)), |case| {
        check_clamped_ends::<[f64; 2]>(&case, 1e-13)
    });
}

#[test]
fn clamped_end_interpolation_i16f16() {
    let shape = Shape {
        range: 2.0,
        min_gap: 0.5,
        ..Shape::new(1..=3, 2)
    };
    // Fixed-point tangent: one rounded division, ≤ 2^-16 absolute; checked with 1e-4 relative
    // to max(|tangent|, 1).
    property(48, open_case(shape), |case| {
        check_clamped_ends::<[I16F16; 2]>(&case, 1e-4)
    });
}

/// "In u_i vermindert sich die Stetigkeit auf C^{g−μ}" (seeds/000, 002): at an inner knot of
/// multiplicity `μ` the left limit (end of the previous piece, `piece_deriv`) and the right
/// value agree for the derivatives `k ≤ g − μ` (within the `f64` tolerance of the module docs),
/// and `classify_breaks` reports at least `C^{min(g − μ_max, 3)}`.
#[test]
fn continuity_at_knots() {
    let worst = Worst::default();
    property(48, open_case(Shape::new(1..=5, 2)), |case| {
        let g = case.g;
        let points: Vec<[f64; 2]> = pts(&case.points);
        let c = BSpline::<[f64; 2], 16, 32>::new(g, &points, &case.knots)
            .map_err(|e| TestCaseError::fail(format!("{e:?}")))?;
        let tols = tolerances::<f64>(Tol::Float(1e-12), &case.knots, g, &case.points, 0.0);
        let mut mu_max = 0;
        for i in 1..c.piece_count() {
            let (_, t) = c.piece_domain(i - 1);
            let mu = case.knots.iter().filter(|&&x| x == t).count();
            mu_max = mu_max.max(mu);
            for k in 0..=g - mu {
                let (l, r) = (c.piece_deriv(i - 1, t, k), c.piece_deriv(i, t, k));
                worst.check(&l, &r, 2.0 * tols[k], || {
                    format!("C^{k} at knot {t} of multiplicity {mu}")
                })?;
            }
        }
        let cont = classify_breaks(&c, 1e-9).map_err(|e| TestCaseError::fail(format!("{e:?}")))?;
        let expected = if c.piece_count() > 1 {
            (g - mu_max).min(3) as u8
        } else {
            3
        };
        prop_assert!(
            cont.is_c(expected),
            "classify_breaks {:?}, expected at least C^{}",
            cont,
            expected
        );
        Ok(())
    });
    worst.report("continuity at knots");
}

/// Knot insertion (Boehm) keeps the curve and its derivatives (within the `f64` tolerance),
/// adds one point and one knot, and refuses only a knot already at its largest multiplicity.
#[test]
fn knot_insertion_preserves_curve() {
    let worst = Worst::default();
    property(
        48,
        (
            open_case(Shape::new(1..=5, 2)),
            0.0..=1.0_f64,
            any::<bool>(),
        ),
        |(case, f, at_knot)| {
            let g = case.g;
            let points: Vec<[f64; 2]> = pts(&case.points);
            let c = BSpline::<[f64; 2], 24, 40>::new(g, &points, &case.knots)
                .map_err(|e| TestCaseError::fail(format!("{e:?}")))?;
            let (lo, hi) = c.domain();
            let kp = points.len();
            let u = if at_knot {
                case.knots[g + ((f * (kp - g) as f64) as usize).min(kp - g)]
            } else {
                lo + (hi - lo) * f
            };
            let mu = case.knots.iter().filter(|&&x| x == u).count();
            let at_end = u == case.knots[0] || u == case.knots[case.knots.len() - 1];
            let limit = if at_end { g + 1 } else { g };
            let r = match c.insert_knot(u) {
                Ok(r) => r,
                Err(Error::KnotMultiplicity { .. }) => {
                    prop_assert!(
                        mu >= limit,
                        "refused u = {} of multiplicity {} < {}",
                        u,
                        mu,
                        limit
                    );
                    return Ok(());
                }
                Err(e) => return Err(TestCaseError::fail(format!("{e:?}"))),
            };
            prop_assert_eq!(r.control_points().len(), kp + 1);
            prop_assert_eq!(r.knots().len(), case.knots.len() + 1);
            prop_assert_eq!(r.knots().iter().filter(|&&x| x == u).count(), mu + 1);
            prop_assert_eq!(r.domain(), c.domain());
            // Both curves' own error scales (the new knot vector has shorter intervals).
            let old = tolerances::<f64>(Tol::Float(1e-12), &case.knots, g, &case.points, 0.0);
            let new = tolerances::<f64>(
                Tol::Float(1e-12),
                r.knots(),
                g,
                &to_vecs(r.control_points()),
                0.0,
            );
            for v in params(&case.knots, g, &case.fracs) {
                for k in 0..=g {
                    let tol = old[k].max(new[k]);
                    worst.check(&r.deriv(v, k), &c.deriv(v, k), tol, || {
                        format!("insert {u}: k = {k} at {v}")
                    })?;
                }
            }
            Ok(())
        },
    );
    worst.report("knot insertion");
}

/// `to_bezier_segments::<NB, _>` for degree `NB − 1`: every segment evaluated with the
/// Bernstein sum of strak-ref (`bezier_point`) on `[0, 1]` equals the curve on its piece.
fn check_bezier_segments<const NB: usize>(case: &Case, worst: &Worst) -> TestCaseResult {
    let g = case.g;
    let points: Vec<[f64; 2]> = pts(&case.points);
    let c = BSpline::<[f64; 2], 16, 32>::new(g, &points, &case.knots)
        .map_err(|e| TestCaseError::fail(format!("{e:?}")))?;
    let segs = c
        .to_bezier_segments::<NB, 16>()
        .map_err(|e| TestCaseError::fail(format!("{e:?}")))?;
    prop_assert_eq!(segs.len(), c.piece_count());
    let tols = tolerances::<f64>(Tol::Float(1e-12), &case.knots, g, &case.points, 0.0);
    for (i, seg) in segs.iter().enumerate() {
        let (a, b) = c.piece_domain(i);
        let sv = to_vecs(seg);
        for &t in case.fracs.iter().chain(&[0.0, 1.0]) {
            let u = a + (b - a) * t;
            let want = to_vec(c.piece_deriv(i, u, 0));
            worst.check(&strak_ref::bezier_point(&sv, t), &want, tols[0], || {
                format!("segment {i} at t = {t}")
            })?;
        }
    }
    Ok(())
}

#[test]
fn bezier_segments_preserve_curve() {
    let worst = Worst::default();
    property(48, open_case(Shape::new(1..=5, 2)), |case| match case.g {
        1 => check_bezier_segments::<2>(&case, &worst),
        2 => check_bezier_segments::<3>(&case, &worst),
        3 => check_bezier_segments::<4>(&case, &worst),
        4 => check_bezier_segments::<5>(&case, &worst),
        _ => check_bezier_segments::<6>(&case, &worst),
    });
    worst.report("Bézier segments");
}

/// strak-ref's `periodic_extended_knots` once computed `ũ_{−1} = u_{K−1} − T` in floating
/// point; when the seam knot is repeated (`u_{K−1} = u_K`) that is not exactly `u_0`, and the
/// extended vector could even decrease. Knots on a period boundary now map exactly.
#[test]
fn reference_extension_rounding_at_a_multiple_seam() {
    let period = [
        0.11557225727654868,
        0.8655722572765487,
        1.6155722572765487,
        1.6155722572765487,
    ];
    let ext = strak_ref::periodic_extended_knots(2, &period);
    assert!(
        ext.windows(2).all(|w| w[0] <= w[1]),
        "extended knots decrease: {ext:?}"
    );
    let d = [vec![0.0, 0.0], vec![0.0, 1.0], vec![0.0, 0.0]];
    let p = strak_ref::closed_bspline_point(2, &d, &period, period[0]);
    let c =
        BSpline::<[f64; 2], 8, 16>::closed(2, &[[0.0, 0.0], [0.0, 1.0], [0.0, 0.0]], Some(&period))
            .unwrap();
    // Both should be d_1 = (0, 1): the seam has multiplicity g = 2, so the curve passes through it.
    assert_eq!(c.eval(period[0]), [0.0, 1.0]);
    assert!((p[1] - 1.0).abs() < 1e-12, "strak-ref gives {p:?}");
}
