#![doc = include_str!("../../README.md")]
//!
//! # This crate
//!
//! Shared helpers for strak's cross-crate tests (`tests/tests/*.rs`): conversions between
//! strak-curves point types and strak-ref's `Vec<f64>` points, error measures, and proptest
//! strategies for well-conditioned inputs.

use proptest::prelude::*;
use strak_curves::Point;

pub mod limits_check;
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

// ---------------------------------------------------------------------------------------------
// Trajectory playback against the exact f64 curve

use strak_curves::{ParamCurveDeriv, Scalar};
use strak_trajectory::{
    CompileOptions, Error, Kernel, Number, Path, PathTiming, Sample, Sampler, Timing, Trajectory,
    compile_into,
};

/// An empty path on the heap. An empty path is its header and length followed by unwritten
/// storage; in this small function of its own an optimized build (the test profile) allocates
/// and writes only those, so that a path of thousands of pieces (MBs in `f64`) never lies on
/// the test thread's stack (libtest's default 2 MiB). Not inlined: inside a larger caller the
/// optimizer may build the value on the stack first.
#[inline(never)]
pub fn boxed_path<N: Number, const A: usize, const P: usize>() -> Box<Path<N, A, P>> {
    Box::new(Path::new())
}

/// [`compile_into`] a [`boxed_path`]: the path is written in place on the heap.
///
/// # Errors
/// As [`compile_into`].
pub fn compile_boxed<N: Number, const A: usize, const P: usize, M>(
    trajectory: &M,
    rate: f64,
    options: &CompileOptions,
) -> Result<Box<Path<N, A, P>>, Error>
where
    M: Trajectory + ?Sized,
{
    let mut path = boxed_path();
    compile_into(trajectory, rate, options, &mut path)?;
    Ok(path)
}

/// [`PathTiming::compile_into`] a boxed empty path: [`PathTiming::compile`] without the path
/// on the stack (see [`compile_boxed`]).
///
/// # Errors
/// As [`PathTiming::compile_into`].
pub fn compile_plan_boxed<
    N: Number,
    const A: usize,
    const P: usize,
    C,
    const T: usize,
    const Z: usize,
>(
    plan: &PathTiming<'_, C, T, Z>,
    options: &CompileOptions,
) -> Result<Box<Path<N, A, P>>, Error>
where
    C: ParamCurveDeriv,
{
    let mut path = boxed_path();
    plan.compile_into(options, &mut path)?;
    Ok(path)
}

/// [`compile_boxed`], and when the number format's playback bound exceeds the tolerance
/// ([`Error::PlaybackBoundExceeded`], typical of `f32` at tight tolerances), once more to
/// twice the bound the error names: the error is what a user acts on.
///
/// # Errors
/// As [`compile_into`].
pub fn compile_within_bound<N: Number, const A: usize, const P: usize, M>(
    trajectory: &M,
    rate: f64,
    options: &CompileOptions,
) -> Result<Box<Path<N, A, P>>, Error>
where
    M: Trajectory + ?Sized,
{
    match compile_boxed(trajectory, rate, options) {
        Err(Error::PlaybackBoundExceeded { bound, .. }) => {
            compile_boxed(trajectory, rate, &options.with_tolerance(2.0 * bound.0))
        }
        other => other,
    }
}

/// The exact position at tick `k` of `path`: the `f64` curve at the time law's parameter at
/// the tick's plan time (the compiler's time stretch included), `x_k = c(u(t_k))`; the last
/// tick is the plan's end.
pub fn exact_position<C, T, N, const A: usize, const P: usize>(
    curve: &C,
    timing: &T,
    path: &Path<N, A, P>,
    k: u32,
) -> [f64; A]
where
    C: ParamCurveDeriv<Point = [f64; A]>,
    T: Timing,
    N: Kernel,
{
    let t = if k >= path.ticks() {
        timing.duration()
    } else {
        path.plan_time(f64::from(k))
    };
    curve.eval(timing.param(t).0)
}

/// The largest position error of a playback, and its largest ratio to the bound.
#[derive(Clone, Copy, Debug, Default)]
pub struct Playback {
    /// Number of samples until the sampler finished.
    pub samples: u64,
    /// Largest `|x − x_exact|` over all samples and axes.
    pub err: f64,
    /// Largest ratio of that error to the documented bound.
    pub ratio: f64,
}

/// Plays `path` to its end and checks every sample against [`exact_position`]: the position
/// error is within the documented bound `tolerance + playback_bound + output rounding`
/// (`½ε·|x|` for floats via [`Number::rounding_error`], [`Number::OUT_ERROR`] for fixed-point);
/// the number of samples is `ticks + 1`; the last sample is [`Path::end_position`](strak_trajectory::PathHeader::end_position) bit for
/// bit. Panics (naming `name`) on a violation.
pub fn check_playback<C, T, N, const A: usize, const P: usize>(
    name: &str,
    curve: &C,
    timing: &T,
    path: &Path<N, A, P>,
) -> Playback
where
    C: ParamCurveDeriv<Point = [f64; A]>,
    T: Timing,
    N: Kernel,
{
    let mut sampler = Sampler::new(path);
    let mut out = Playback::default();
    let mut last: Option<Sample<N::Out, A>> = None;
    while !sampler.is_finished() {
        let s = sampler.next();
        assert_eq!(s.tick, out.samples, "{name}: tick count");
        let k = u32::try_from(s.tick).expect("ticks fit u32");
        let ex = exact_position(curve, timing, path, k);
        for (i, (p, e)) in s.position.iter().zip(ex).enumerate() {
            let x = p.to_f64();
            let rounding = if N::IS_FIXED {
                N::OUT_ERROR
            } else {
                N::rounding_error(x)
            };
            let bound = path.tolerance() + path.playback_bound() + rounding;
            let err = (x - e).abs();
            out.err = out.err.max(err);
            out.ratio = out.ratio.max(err / bound);
            assert!(
                err <= bound,
                "{name}: tick {k}, axis {i}: error {err:e} > bound {bound:e}"
            );
        }
        last = Some(s);
        out.samples += 1;
        assert!(
            out.samples <= u64::from(path.ticks()) + 1,
            "{name}: not finished"
        );
    }
    assert_eq!(
        out.samples,
        u64::from(path.ticks()) + 1,
        "{name}: ticks + 1 samples"
    );
    let last = last.expect("at least one sample");
    let end = path.end_position();
    for (i, (p, e)) in last.position.iter().zip(end).enumerate() {
        assert_eq!(
            p.to_f64().to_bits(),
            e.to_f64().to_bits(),
            "{name}: end point bit for bit, axis {i}"
        );
    }
    out
}

/// A time law that forwards another's duration, parameter and breaks, but neither the
/// limits it promises nor its feed reserve: the compiler then keeps its duration (it slows
/// a law with limits down where the fitted pieces would exceed them) and takes the feed
/// share of the given limits without checking the plan.
#[derive(Debug)]
pub struct Unpromised<'a, T>(pub &'a T);

impl<T: strak_trajectory::Timing> strak_trajectory::Timing for Unpromised<'_, T> {
    fn duration(&self) -> f64 {
        self.0.duration()
    }
    fn param(&self, t: f64) -> (f64, f64) {
        self.0.param(t)
    }
    fn breaks(&self, out: &mut dyn FnMut(f64)) {
        self.0.breaks(out);
    }
}
