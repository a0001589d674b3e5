//! The shared workload: the control points, the parameter tables and the compiled paths that
//! every benchmark (strak and its peers) uses.

use std::boxed::Box;

use strak_curves::{BSpline, ParamCurve, ParamCurveDeriv, PowerSpline};
use strak_trajectory::{
    CompileOptions, Kernel, Limits, Number, Path, PathTiming, PlanOptions, Q40, Sampler,
    compile_into,
};

/// The control-point counts measured: 8, 64, 1024 and 8192.
pub const SIZES: [usize; 4] = [8, 64, 1024, 8192];
/// Capacity of the strak curves (de Boor points): the largest size.
pub const MAX_POINTS: usize = 8192;
/// Capacity of the strak knot vectors: `MAX_POINTS + 4` (cubic).
pub const MAX_KNOTS: usize = MAX_POINTS + 4;
/// Piece capacity of the compiled paths.
pub const PIECES: usize = 65_536;
/// The degree of every curve: cubic.
pub const DEGREE: usize = 3;
/// How many parameters each evaluation table holds (one criterion iteration evaluates all).
pub const TABLE_LEN: usize = 1024;
/// The control rate of the compiled paths (Hz).
pub const RATE_HZ: f64 = 1_000.0;
/// The compile tolerance (absolute, mm): the same for every size, so that the piece density
/// along the path does not depend on `n`.
pub const TOLERANCE_MM: f64 = 1e-3;
/// Arc-length table samples of the time law: two per span of the largest curve (with 1 024
/// the 8 192-point path's compiled jerk exceeds its limit beyond the compiler's slow-down,
/// `Error::LimitExceeded`).
const ARC_TABLE: usize = 16_384;
/// Zone capacity of the time law.
const ZONES: usize = 4_096;

/// The `n` de Boor points: a helix of radius 50 mm, 16 points per turn, rising 0.5 mm per
/// turn (every span has the same shape, so the path grows with `n` at a constant density
/// of detail; all coordinates stay within the range of `I16F16`, and low enough for `f32`
/// to keep the compile tolerance: at 0.5 mm per point the 1 024-point path's playback bound
/// in `f32` was 1.44 µm against the tolerance of 1 µm).
pub fn helix_points(n: usize) -> Vec<[f64; 3]> {
    (0..n)
        .map(|i| {
            let a = i as f64 * core::f64::consts::TAU / 16.0;
            [50.0 * a.cos(), 50.0 * a.sin(), i as f64 / 32.0]
        })
        .collect()
}

/// The parameter domain of the `n`-point clamped uniform cubic: `[0, n − 3]` (knot spacing
/// 1, exact in every number format, short enough spans never scale derivatives up).
pub fn domain(n: usize) -> (f64, f64) {
    (0.0, (n - DEGREE) as f64)
}

/// The clamped uniform knot vector of `n` points over [`domain`]: `n + 4` knots.
pub fn clamped_knots(n: usize) -> Vec<f64> {
    let inner = n - DEGREE;
    let mut k = vec![0.0; DEGREE + 1];
    k.extend((1..inner).map(|j| j as f64));
    k.extend(std::iter::repeat_n(inner as f64, DEGREE + 1));
    k
}

/// `TABLE_LEN` parameters evenly spaced over the domain of the `n`-point curve, both ends
/// included.
pub fn even_params(n: usize) -> Vec<f64> {
    let (lo, hi) = domain(n);
    (0..TABLE_LEN)
        .map(|i| lo + (hi - lo) * i as f64 / (TABLE_LEN - 1) as f64)
        .collect()
}

/// `TABLE_LEN` pseudo-random parameters in the domain of the `n`-point curve (a fixed
/// xorshift sequence: the same table in every run and for every library).
pub fn random_params(n: usize) -> Vec<f64> {
    let (lo, hi) = domain(n);
    let mut x: u64 = 0x9E37_79B9_7F4A_7C15 ^ n as u64;
    (0..TABLE_LEN)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let unit = (x >> 11) as f64 / (1u64 << 53) as f64;
            lo + (hi - lo) * unit
        })
        .collect()
}

/// strak's B-spline of the `n` helix points in the scalar of `P` (`[f32; 3]`, `[f64; 3]`,
/// `[I32F32; 3]`, `[I16F16; 3]`).
///
/// # Panics
/// When the curve cannot be built (a bug of the fixture).
pub fn strak_curve<P: strak_curves::Point>(n: usize) -> Box<BSpline<P, MAX_POINTS, MAX_KNOTS>> {
    let points: Vec<P> = helix_points(n)
        .iter()
        .map(|p| P::from_f64_slice(p).expect("point in range"))
        .collect();
    let (lo, hi) = domain(n);
    let s = |v: f64| <P::Scalar as strak_curves::Scalar>::from_f64(v).expect("knot in range");
    Box::new(BSpline::clamped_uniform(DEGREE, &points, s(lo), s(hi)).expect("valid curve"))
}

/// strak's fast random-access evaluator of the same curve as [`strak_curve`]: the B-spline
/// converted into per-span power-basis polynomials ([`PowerSpline`], order 4).
///
/// # Panics
/// When the curve cannot be converted (a bug of the fixture).
pub fn strak_power<P: strak_curves::Point>(n: usize) -> Box<PowerSpline<P, 4, MAX_POINTS>> {
    Box::new(PowerSpline::from_bspline(&*strak_curve::<P>(n)).expect("valid power spline"))
}

/// The limits the paths are planned with (mm, s): v 500 mm/s, a 5000 mm/s², j 100 000 mm/s³.
///
/// # Panics
/// Never (constant, valid limits).
pub fn limits() -> Limits<3> {
    Limits::new(500.0, 5_000.0, 100_000.0).expect("valid limits")
}

/// The compiled paths of one size in every number format.
#[derive(Debug)]
pub struct Paths {
    /// Played in `f32`.
    pub f32: Box<Path<f32, 3, PIECES>>,
    /// Played in `f64`.
    pub f64: Box<Path<f64, 3, PIECES>>,
    /// Played in `Q40` (samples as `I32F32`).
    pub q40: Box<Path<Q40, 3, PIECES>>,
}

/// The paths of the `n`-point helix B-spline (`f64`): one jerk-limited S-curve
/// ([`PathTiming::scurve`]'s plan under [`limits`]), compiled at [`RATE_HZ`] with
/// [`TOLERANCE_MM`] into `f32`, `f64` and `Q40`. The plan (2.5 MB) and the paths (up to 15 MB)
/// are boxed empty and filled in place ([`PathTiming::plan_into`], [`compile_into`]): none
/// lies on the stack.
///
/// # Panics
/// When planning or compiling fails (a bug of the fixture).
pub fn strak_paths(n: usize) -> Paths {
    let curve = strak_curve::<[f64; 3]>(n);
    let limits = limits();
    let mut timing = boxed_plan(&*curve);
    timing
        .plan_into(&limits, &PlanOptions::new())
        .expect("plan");
    let options = CompileOptions::new()
        .with_tolerance(TOLERANCE_MM)
        .with_path_limits(&limits);
    Paths {
        f32: compiled(&*timing, &options),
        f64: compiled(&*timing, &options),
        q40: compiled(&*timing, &options),
    }
}

/// `timing` compiled at [`RATE_HZ`] into a boxed empty path, in place.
fn compiled<N: Number, C: ParamCurveDeriv, const T: usize, const Z: usize>(
    timing: &PathTiming<'_, C, T, Z>,
    options: &CompileOptions,
) -> Box<Path<N, 3, PIECES>> {
    let mut path = boxed_path();
    compile_into(timing, RATE_HZ, options, &mut path).expect("compile");
    path
}

/// An empty path on the heap, written in place: in a small function of its own an
/// optimized build allocates first and writes only the header and the length (the storage
/// stays unwritten), so that the path never lies on the stack.
#[inline(never)]
fn boxed_path<N: Number>() -> Box<Path<N, 3, PIECES>> {
    Box::new(Path::new())
}

/// An empty plan on the heap (2.5 MB of zeros): not inlined, as [`boxed_path`].
#[inline(never)]
fn boxed_plan<C: ParamCurveDeriv>(curve: &C) -> Box<PathTiming<'_, C, ARC_TABLE, ZONES>> {
    Box::new(PathTiming::empty(curve))
}

/// A sampler of `path` advanced by `ticks` calls of [`Sampler::next`].
pub fn sampler_at<N: Kernel, const A: usize, const P: usize>(
    path: &Path<N, A, P>,
    ticks: u64,
) -> Sampler<'_, N, A> {
    let mut s = Sampler::new(path);
    for _ in 0..ticks {
        s.next();
    }
    s
}

/// Evaluates `curve` at every parameter of `table` and returns the points in `f64`
/// (for cross-checks between libraries).
pub fn eval_table<C: ParamCurve>(curve: &C, table: &[f64]) -> Vec<[f64; 3]>
where
    C::Point: strak_curves::Point,
{
    use strak_curves::{Point, Scalar};
    table
        .iter()
        .map(|&u| {
            let u = <C::Point as Point>::Scalar::from_f64(u).expect("parameter in range");
            let p = curve.eval(u);
            [
                p.coord(0).to_f64(),
                p.coord(1).to_f64(),
                p.coord(2).to_f64(),
            ]
        })
        .collect()
}
