//! Shared helpers for strak's cross-crate tests of the curves (`tests/tests/*.rs`):
//! conversions between strak-curves point types and strak-ref's `Vec<f64>` points, error measures, and proptest
//! strategies for well-conditioned inputs.

use proptest::prelude::*;
use strak_curves::Point;

pub mod spline_cases;

/// The coordinates of a point as strak-ref's `Vec<f64>`.
pub fn to_vec<P: Point>(p: P) -> Vec<f64> {
    (0..P::DIM)
        .map(|i| strak_curves::Scalar::to_f64(p.coord(i)))
        .collect()
}

/// All points as strak-ref's `&[Vec<f64>]`.
pub fn to_vecs<P: Point>(points: &[P]) -> Vec<Vec<f64>> {
    points.iter().map(|p| to_vec(*p)).collect()
}

/// A point of type `P` from `f64` coordinates (panics when out of range: test input only).
pub fn pt<P: Point>(coords: &[f64]) -> P {
    P::from_f64_slice(coords).expect("test point out of range")
}

/// Points of type `P` from `f64` coordinates.
pub fn pts<P: Point>(points: &[Vec<f64>]) -> Vec<P> {
    points.iter().map(|c| pt(c)).collect()
}

/// The largest coordinate difference.
pub fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len(), "dimension mismatch");
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// The extent of a point set: the largest coordinate range (at least `f64::MIN_POSITIVE`).
pub fn extent(points: &[Vec<f64>]) -> f64 {
    let dim = points.first().map_or(0, Vec::len);
    (0..dim)
        .map(|i| {
            let lo = points.iter().map(|p| p[i]).fold(f64::INFINITY, f64::min);
            let hi = points
                .iter()
                .map(|p| p[i])
                .fold(f64::NEG_INFINITY, f64::max);
            hi - lo
        })
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE)
}

/// `n` points of dimension `dim` with coordinates in `[-range, range]`.
pub fn points(
    n: std::ops::RangeInclusive<usize>,
    dim: usize,
    range: f64,
) -> impl Strategy<Value = Vec<Vec<f64>>> {
    prop::collection::vec(prop::collection::vec(-range..range, dim), n)
}

/// `n` strictly increasing nodes starting at `start`, with gaps in `[min_gap, max_gap]`
/// (well separated, so interpolation problems are well conditioned).
pub fn increasing_nodes(
    n: usize,
    start: f64,
    min_gap: f64,
    max_gap: f64,
) -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(min_gap..max_gap, n.saturating_sub(1)).prop_map(move |gaps| {
        let mut u = vec![start];
        for g in gaps {
            let last = *u.last().unwrap_or(&start);
            u.push(last + g);
        }
        u
    })
}

/// Evenly spaced parameters over `[a, b]`, both ends included.
pub fn linspace(a: f64, b: f64, count: usize) -> Vec<f64> {
    let last = (count - 1).max(1) as f64;
    (0..count)
        .map(|i| {
            if i + 1 == count {
                b
            } else {
                a + (b - a) * (i as f64 / last)
            }
        })
        .collect()
}

// ---------------------------------------------------------------------------------------------
// Property harness with measured errors (printed with `--nocapture`)

use std::cell::Cell;
use std::fmt::Debug;

use proptest::test_runner::{Config, TestCaseError, TestCaseResult, TestRunner};

/// The largest error and the largest error/tolerance ratio seen by one property.
#[derive(Debug, Default)]
pub struct Stats {
    /// The largest error seen.
    pub err: Cell<f64>,
    /// The largest error/tolerance ratio seen.
    pub ratio: Cell<f64>,
}

impl Stats {
    /// Checks `err <= tol` and records both.
    pub fn check(&self, err: f64, tol: f64, what: impl FnOnce() -> String) -> TestCaseResult {
        self.err.set(self.err.get().max(err));
        if tol > 0.0 {
            self.ratio.set(self.ratio.get().max(err / tol));
        }
        if err <= tol {
            Ok(())
        } else {
            Err(TestCaseError::fail(format!(
                "{}: error {err:e} > tolerance {tol:e}",
                what()
            )))
        }
    }
}

/// Runs a property over `cases` random inputs and prints the measured errors.
pub fn run<T>(
    name: &str,
    cases: u32,
    strategy: T,
    body: impl Fn(T::Value, &Stats) -> TestCaseResult,
) where
    T: Strategy,
    T::Value: Debug,
{
    let stats = Stats::default();
    let mut runner = TestRunner::new(Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    });
    if let Err(e) = runner.run(&strategy, |v| body(v, &stats)) {
        panic!("{name}: {e}");
    }
    eprintln!(
        "{name}: max error {:.3e}, max error/tolerance {:.3}",
        stats.err.get(),
        stats.ratio.get()
    );
}

/// `Err` unless `cond`.
pub fn ensure(cond: bool, what: impl FnOnce() -> String) -> TestCaseResult {
    if cond {
        Ok(())
    } else {
        Err(TestCaseError::fail(what()))
    }
}
