#![doc = include_str!("../../../README.md")]
//!
//! # This crate
//!
//! Shared helpers for strak's cross-crate tests of the motion (`tests/trajectory/tests/*.rs`):
//! compiling paths on the heap, playing them against the exact `f64` curve, and measuring
//! the limits from the samples ([`limits_check`]).

pub mod limits_check;

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
