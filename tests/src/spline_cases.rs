//! Random B-spline and NURBS inputs and the property harness the spline comparisons share
//! (`bspline_vs_ref.rs`, `nurbs_vs_ref.rs`, `analysis_on_curves.rs`): knot vectors with
//! repeated knots, sample parameters, the derivative scales `A_k` that set the tolerances,
//! and a runner that records the worst `error / tolerance`.

use std::cell::Cell;
use std::fmt::Debug;

use proptest::prelude::*;
use proptest::test_runner::{Config, TestCaseError, TestCaseResult, TestRunner};
use strak_curves::Scalar;

use crate::max_diff;

/// Runs `test` on `cases` random values of `strategy` (no failure persistence: the printed
/// minimal failing input is the regression record); panics on failure.
pub fn property<S: Strategy>(cases: u32, strategy: S, test: impl Fn(S::Value) -> TestCaseResult)
where
    S::Value: Debug,
{
    let config = Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    };
    if let Err(e) = TestRunner::new(config).run(&strategy, test) {
        panic!("{e}");
    }
}

/// A constructor's error as a failed test case.
pub fn fail(e: strak_curves::Error) -> TestCaseError {
    TestCaseError::fail(format!("unexpected error: {e:?}"))
}

/// The largest `error / tolerance` seen, for the printed summary.
#[derive(Debug, Default)]
pub struct Worst(Cell<f64>);

impl Worst {
    /// `Err` unless `got` is within `tol` of `want` (largest coordinate difference).
    pub fn check(
        &self,
        got: &[f64],
        want: &[f64],
        tol: f64,
        what: impl Fn() -> String,
    ) -> TestCaseResult {
        let err = max_diff(got, want);
        if tol > 0.0 {
            self.0.set(self.0.get().max(err / tol));
        }
        if err <= tol {
            Ok(())
        } else {
            Err(TestCaseError::fail(format!(
                "{}: got {got:?}, want {want:?}, error {err:e} > tolerance {tol:e}",
                what()
            )))
        }
    }

    /// Prints the worst ratio.
    pub fn report(&self, name: &str) {
        eprintln!("{name}: largest error / tolerance = {:.3e}", self.0.get());
    }
}

/// `x` as the scalar `S` (rounded; test inputs are chosen to fit).
pub fn sc<S: Scalar>(x: f64) -> S {
    S::from_f64(x).expect("test value fits the scalar")
}

/// How a tolerance is derived (see each test file's module docs).
#[derive(Clone, Copy, Debug)]
pub enum Tol {
    /// Relative to the scale `A_k`.
    Float(f64),
    /// A safety factor over a first-order fixed-point error estimate.
    Fixed(f64),
}

/// `A_0..A_{g+1}` for point magnitudes `mags`: the derivative de Boor point recursion with
/// absolute values and sums instead of differences,
/// `A_r = max_i (g − r + 1)·(a_i + a_{i+1}) / (u_{i+g+1} − u_{i+r})` (or, with `mags = 0` and
/// `add = 1`, the error recursion `e_k` in units of `ε`).
pub fn scales(knots: &[f64], g: usize, mags: &[f64], add: f64) -> Vec<f64> {
    let mut v = mags.to_vec();
    let mut out = vec![v.iter().copied().fold(0.0, f64::max)];
    for r in 1..=g + 1 {
        let f = (g + 1 - r) as f64;
        let next: Vec<f64> = (0..v.len().saturating_sub(1))
            .map(|i| {
                let den = knots[i + g + 1] - knots[i + r];
                if den > 0.0 {
                    f * (v[i] + v[i + 1]) / den + add
                } else {
                    0.0
                }
            })
            .collect();
        out.push(next.iter().copied().fold(0.0, f64::max));
        v = next;
    }
    out
}

/// A knot gap: zero (a repeated knot) or in `min..max`.
pub fn gap(min: f64, max: f64) -> impl Strategy<Value = f64> {
    prop_oneof![1 => Just(0.0), 3 => min..max]
}

/// A knot gap on the grid `1/16`: zero or in `[0.25, 1.5]`. Dyadic knots make the periodic
/// extension `u_j ± T` exact in every scalar type, so that strak-ref's extension (which does
/// not snap `u_{K−1} − T` to `u_0` when `u_{K−1} = u_K`) sees exactly the same knots.
pub fn dyadic_gap() -> impl Strategy<Value = f64> {
    prop_oneof![1 => Just(0.0), 3 => (4..=24_u32).prop_map(|n| f64::from(n) / 16.0)]
}

/// Knots from gaps: clamped ends (`g + 1` equal knots) if asked, inner runs of equal knots at
/// most `g` long (a zero gap that would make a run longer becomes `fill`), non-empty domain.
pub fn open_knots(g: usize, clamped: bool, mut gaps: Vec<f64>, start: f64, fill: f64) -> Vec<f64> {
    let m = gaps.len() + 1;
    let k = m - g - 1;
    if clamped {
        for j in 0..g {
            gaps[j] = 0.0;
            gaps[m - 2 - j] = 0.0;
        }
        if gaps[g] == 0.0 {
            gaps[g] = fill;
        }
        if gaps[m - 2 - g] == 0.0 {
            gaps[m - 2 - g] = fill;
        }
    }
    if gaps[g..k].iter().all(|&x| x == 0.0) {
        gaps[g] = fill;
    }
    let mut run = 1;
    for (j, gp) in gaps.iter_mut().enumerate() {
        let protected = clamped && (j < g || j >= m - 1 - g);
        if *gp == 0.0 {
            if !protected && run >= g {
                *gp = fill;
                run = 1;
            } else {
                run += 1;
            }
        } else {
            run = 1;
        }
    }
    cumulative(start, gaps)
}

/// Period knots from `K` gaps: multiplicities around the circle at most `g` (consecutive zero
/// gaps at most `g − 1`, counting the run that wraps over the seam; others become `fill`).
pub fn period_knots(g: usize, mut gaps: Vec<f64>, start: f64, fill: f64) -> Vec<f64> {
    let mut zeros = 0;
    for gp in gaps.iter_mut() {
        if *gp == 0.0 {
            if zeros + 1 > g - 1 {
                *gp = fill;
                zeros = 0;
            } else {
                zeros += 1;
            }
        } else {
            zeros = 0;
        }
    }
    let lead = gaps.iter().take_while(|&&x| x == 0.0).count();
    let trail = gaps.iter().rev().take_while(|&&x| x == 0.0).count();
    if lead == gaps.len() || lead + trail > g - 1 {
        gaps[0] = fill;
    }
    cumulative(start, gaps)
}

/// `start` and the running sums of `gaps`.
fn cumulative(start: f64, gaps: Vec<f64>) -> Vec<f64> {
    let mut knots = vec![start];
    for gp in gaps {
        knots.push(knots.last().copied().unwrap_or(start) + gp);
    }
    knots
}

/// The sample parameters of a spline of degree `g` with `knots`: the domain ends, every knot
/// inside the domain and the random fractions of the domain, all as `S`.
pub fn params<S: Scalar>(knots: &[S], g: usize, fracs: &[f64]) -> Vec<S> {
    let k = knots.len() - g - 1;
    let (lo, hi) = (knots[g], knots[k]);
    let mut out: Vec<S> = knots[g..=k].to_vec();
    let (a, b) = (lo.to_f64(), hi.to_f64());
    for f in fracs {
        out.push(sc::<S>(a + (b - a) * f).clamp_to(lo, hi));
    }
    out
}
