//! Property tests: strak-curves' [`BezierChain`] against strak-ref's composite Bézier curve
//! (`bezier_chain_deriv`: Bernstein sums of forward differences per segment), in `f64`,
//! `f32`, `I32F32` and `I16F16`, for degrees 1..=5 and 1..=6 segments, at random parameters
//! in `[-0.5, n + 0.5]` (clamped) and at every join; plus the left-hand limits of
//! `PieceDeriv` against the single segments, and `from_segments` against `new`.
//!
//! # Tolerances
//! One rounding unit of a value of magnitude `m` is `EPSILON · m` for floats and `EPSILON`
//! (absolute) for fixed-point, plus `f64::EPSILON · m` for the reference. The chain evaluates
//! one segment by de Casteljau at `t = u − i`, which is exact (Sterbenz in floats, exact
//! subtraction in fixed-point), so the bound is the single Bézier's: ≤ 2 units per de Casteljau
//! level (`g − k` levels), the `k`-th forward difference doubles it `k` times, then
//! `× g!/(g−k)!`; the reference's Bernstein sum has the same order; factor 2 slack:
//! `4 (g + 1) 2^k g!/(g−k)! · unit(m)`.
//!
//! Measured (printed with `--nocapture`): see the report of each property.

use proptest::prelude::*;
use proptest::test_runner::{TestCaseError, TestCaseResult};
use strak_curves::{
    Bezier, BezierChain, I16F16, I32F32, ParamCurve, ParamCurveDeriv, PieceDeriv, Point, Scalar,
};
use strak_tests::{Stats, ensure, max_diff, pt, run, to_vec, to_vecs};

/// Cases per property; each case checks degrees 1..=5.
const CASES: u32 = 64;
/// Largest coordinate magnitude of generated points.
const CAP: f64 = 1000.0;
/// Largest number of segments.
const SEGMENTS: usize = 6;

/// `g!/(g−k)!` (0 for `k > g`).
fn ff(g: usize, k: usize) -> f64 {
    if k > g {
        return 0.0;
    }
    (0..k).map(|m| (g - m) as f64).product()
}

/// One rounding unit of a value of magnitude `m` in `S`, plus the reference's own.
fn unit<S: Scalar>(m: f64) -> f64 {
    (if S::IS_FIXED {
        S::EPSILON
    } else {
        S::EPSILON * m
    }) + f64::EPSILON * m
}

/// The coordinate scale for degree `g`: ≤ [`CAP`], and small enough that every hodograph
/// `g!/(g−k)! Δᵏ b` (`|Δᵏ b| ≤ 2ᵏ max |b|`) fits the scalar type.
fn scale<S: Scalar>(g: usize) -> f64 {
    let worst = (0..=g)
        .map(|k| ff(g, k) * f64::from(1 << k))
        .fold(1.0, f64::max);
    (0.9 * S::LIMIT / worst).min(CAP)
}

/// Unit points, the number of segments and unit parameters (mapped to `[-0.5, n + 0.5]`).
fn input() -> impl Strategy<Value = (Vec<Vec<f64>>, usize, Vec<f64>)> {
    (
        strak_tests::points(5 * SEGMENTS + 1..=5 * SEGMENTS + 1, 3, 1.0),
        1..=SEGMENTS,
        prop::collection::vec(0.0..1.0_f64, 8),
    )
}

/// Checks one degree `N − 1` and scalar type.
fn check<P: Point, const N: usize>(
    (unit_points, n, params): &(Vec<Vec<f64>>, usize, Vec<f64>),
    stats: &Stats,
) -> TestCaseResult {
    let g = N - 1;
    let m = scale::<P::Scalar>(g);
    let points: Vec<P> = unit_points[..n * g + 1]
        .iter()
        .map(|c| {
            let c: Vec<f64> = c.iter().take(P::DIM).map(|v| v * m).collect();
            pt(&c)
        })
        .collect();
    let chain = BezierChain::<P, N, SEGMENTS>::new(&points)
        .map_err(|e| TestCaseError::fail(format!("BezierChain::new: {e:?}")))?;
    ensure(chain.segment_count() == *n, || "segment count".into())?;
    ensure(chain.domain().1.to_f64() == *n as f64, || "domain".into())?;
    let ctrl = to_vecs(&points);
    let mag = ctrl
        .iter()
        .flatten()
        .fold(1e-300_f64, |a, v| a.max(v.abs()));
    let mut us: Vec<f64> = params
        .iter()
        .map(|t| -0.5 + t * (*n as f64 + 1.0))
        .collect();
    us.extend((0..=*n).map(|i| i as f64));
    for &u in &us {
        let us = P::Scalar::from_f64(u).expect("parameter");
        let uf = us.to_f64();
        for k in 0..=g + 1 {
            let got = to_vec(chain.deriv(us, k));
            let want = strak_ref::bezier_chain_deriv(&ctrl, g, uf, k);
            let tol = 4.0 * (g + 1) as f64 * f64::from(1 << k) * ff(g, k) * unit::<P::Scalar>(mag);
            stats.check(max_diff(&got, &want), tol, || {
                format!(
                    "{} degree {g}, {n} segments, k = {k}, u = {uf}",
                    P::Scalar::NAME
                )
            })?;
        }
    }
    // left-hand limits at the joins: the end of segment i
    for i in 0..*n {
        let end = P::Scalar::from_f64((i + 1) as f64).expect("join");
        for k in 0..=g {
            let got = to_vec(chain.piece_deriv(i, end, k));
            let want = strak_ref::bezier_deriv(&ctrl[i * g..=(i + 1) * g], 1.0, k);
            let tol = 4.0 * (g + 1) as f64 * f64::from(1 << k) * ff(g, k) * unit::<P::Scalar>(mag);
            stats.check(max_diff(&got, &want), tol, || {
                format!("left limit, degree {g}, join {i}, k = {k}")
            })?;
        }
    }
    // from_segments gives the same chain
    let segs: Vec<Bezier<P, N>> = chain.segments().to_vec();
    let again = BezierChain::<P, N, SEGMENTS>::from_segments(&segs)
        .map_err(|e| TestCaseError::fail(format!("from_segments: {e:?}")))?;
    ensure(again == chain, || "from_segments ≠ new".into())
}

macro_rules! degrees {
    ($p:ty, $v:expr, $s:expr) => {{
        check::<$p, 2>($v, $s)?;
        check::<$p, 3>($v, $s)?;
        check::<$p, 4>($v, $s)?;
        check::<$p, 5>($v, $s)?;
        check::<$p, 6>($v, $s)?;
        Ok(())
    }};
}

#[test]
fn chain_f64_matches_reference() {
    run("chain f64", CASES, input(), |v, s| {
        degrees!([f64; 3], &v, s)
    });
}

#[test]
fn chain_glam_dvec2_matches_reference() {
    run("chain DVec2", CASES, input(), |v, s| {
        degrees!(glam::DVec2, &v, s)
    });
}

#[test]
fn chain_f32_matches_reference() {
    run("chain f32", CASES, input(), |v, s| {
        degrees!(glam::Vec3, &v, s)
    });
}

#[test]
fn chain_i32f32_matches_reference() {
    run("chain I32F32", CASES, input(), |v, s| {
        degrees!([I32F32; 3], &v, s)
    });
}

#[test]
fn chain_i16f16_matches_reference() {
    run("chain I16F16", CASES, input(), |v, s| {
        degrees!([I16F16; 2], &v, s)
    });
}
