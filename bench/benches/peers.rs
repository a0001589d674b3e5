//! strak against its peers on the same work, in one criterion run (issue 5, part 1).
//!
//! Groups (criterion ids `group/function/parameter`; the report reads them back):
//! - `eval_even`, `eval_random`: random-access evaluation of the 3-D clamped uniform cubic
//!   B-spline of `n` helix points at [`TABLE_LEN`] evenly spaced / pseudo-random parameters
//!   (one iteration evaluates the whole table; throughput = table length). strak twice:
//!   `strak_<format>` is de Boor's algorithm (`BSpline::eval`, the exact evaluator),
//!   `strak_power_<format>` the power-basis pieces (`PowerSpline::eval`, Horner).
//! - `playback`: one `Sampler::next()` per iteration over the whole compiled path (the sampler
//!   restarts when finished), f32, f64 and Q40, per `n`.
//! - `fill`: batch playback, one whole playback of the path per iteration by `Sampler::fill`
//!   in batches of 1024 samples, f32, f64 and Q40, per `n`; time per sample.
//! - `fill_positions`: as `fill`, with `Sampler::fill_positions` (positions only, the peers'
//!   job).
//! - `flatness_<format>`: one `next()` at chosen ticks of the 1024-point path, on a clone of a
//!   sampler advanced to just before that tick (`iter_batched_ref`), and the same harness with
//!   an empty routine (`baseline`) to subtract.
//! - `floor`: the forward-differencing step alone on a state kept in memory (what any
//!   per-call tick must pay; no sampler around it), f32, f64 and Q40.
//! - `online`: one time-synchronized 3-axis online move per element, over the same
//!   [`ONLINE_CASES`] random moves for every solver: `strak_f64`, `strak_f32`
//!   (`OnlineMove::solve_in_place`), `ruckig` (Ruckig's C++, `calculate`), `rsruckig`.
//! - `online_case`: strak's median and slowest case of those (chosen by timing each case),
//!   one solve per iteration.

use std::hint::black_box;
use std::ops::{Add, Div, Mul, Sub};
use std::time::Duration;

use criterion::{BatchSize, BenchmarkGroup, Criterion, Throughput, measurement::WallTime};
use strak_bench::fixture::{
    DEGREE, PIECES, SIZES, TABLE_LEN, clamped_knots, domain, even_params, helix_points,
    random_params, sampler_at, strak_curve, strak_paths, strak_power,
};
use strak_bench::online_cases::{BENCH_SEED, OnlineCase, online_cases};
use strak_curves::{I16F16, I32F32, ParamCurve, Point, Scalar, ScalarOf};
use strak_trajectory::{Kernel, MoveOptions, OnlineMove, Path, Sample, Sampler};

/// A 3-D point for the peers (they take any type with `+` and `* scalar`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct V3<F>([F; 3]);

impl<F: Copy + Add<Output = F>> Add for V3<F> {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        V3([self.0[0] + o.0[0], self.0[1] + o.0[1], self.0[2] + o.0[2]])
    }
}

impl<F: Copy + Sub<Output = F>> Sub for V3<F> {
    type Output = Self;
    #[inline]
    fn sub(self, o: Self) -> Self {
        V3([self.0[0] - o.0[0], self.0[1] - o.0[1], self.0[2] - o.0[2]])
    }
}

impl<F: Copy + Mul<Output = F>> Mul<F> for V3<F> {
    type Output = Self;
    #[inline]
    fn mul(self, s: F) -> Self {
        V3([self.0[0] * s, self.0[1] * s, self.0[2] * s])
    }
}

impl<F: Copy + Div<Output = F>> Div<F> for V3<F> {
    type Output = Self;
    #[inline]
    fn div(self, s: F) -> Self {
        V3([self.0[0] / s, self.0[1] / s, self.0[2] / s])
    }
}

/// The float types the peers run in.
trait PeerFloat:
    Copy
    + Default
    + PartialOrd
    + core::fmt::Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + num_like::FromF64
    + 'static
{
    const NAME: &'static str;
}

mod num_like {
    /// Conversion from the fixture's f64 values.
    pub(crate) trait FromF64 {
        fn from_fixture(v: f64) -> Self;
        fn to_fixture(self) -> f64;
    }
    impl FromF64 for f32 {
        fn from_fixture(v: f64) -> Self {
            v as f32
        }
        fn to_fixture(self) -> f64 {
            f64::from(self)
        }
    }
    impl FromF64 for f64 {
        fn from_fixture(v: f64) -> Self {
            v
        }
        fn to_fixture(self) -> f64 {
            self
        }
    }
}

impl PeerFloat for f32 {
    const NAME: &'static str = "f32";
}
impl PeerFloat for f64 {
    const NAME: &'static str = "f64";
}

/// Catmull-Rom (cubic Hermite with the neighbours' secant tangents) for the `splines` crate,
/// written exactly as the crate's own `impl_Interpolate!` macro does for its float types
/// (the macro cannot be used outside the crate: it is gated on the crate's `std` feature).
macro_rules! splines_interpolate {
    ($t:ty) => {
        impl splines::Interpolate<$t> for V3<$t> {
            fn step(t: $t, threshold: $t, a: Self, b: Self) -> Self {
                if t < threshold { a } else { b }
            }
            fn lerp(t: $t, a: Self, b: Self) -> Self {
                a * (1. - t) + b * t
            }
            fn cosine(t: $t, a: Self, b: Self) -> Self {
                let c = (1. - (t * core::f64::consts::PI as $t).cos()) * 0.5;
                Self::lerp(c, a, b)
            }
            fn cubic_hermite(
                t: $t,
                x: ($t, Self),
                a: ($t, Self),
                b: ($t, Self),
                y: ($t, Self),
            ) -> Self {
                let two_t = t * 2.;
                let three_t = t * 3.;
                let t2 = t * t;
                let t3 = t2 * t;
                let two_t3 = t2 * two_t;
                let two_t2 = t * two_t;
                let three_t2 = t * three_t;
                let m0 = (b.1 - x.1) / (b.0 - x.0) * (b.0 - a.0);
                let m1 = (y.1 - a.1) / (y.0 - a.0) * (b.0 - a.0);
                a.1 * (two_t3 - three_t2 + 1.)
                    + m0 * (t3 - two_t2 + t)
                    + b.1 * (three_t2 - two_t3)
                    + m1 * (t3 - t2)
            }
            fn quadratic_bezier(t: $t, a: Self, u: Self, b: Self) -> Self {
                let one_t = 1. - t;
                u + (a - u) * (one_t * one_t) + (b - u) * (t * t)
            }
            fn cubic_bezier(t: $t, a: Self, u: Self, v: Self, b: Self) -> Self {
                let one_t = 1. - t;
                let one_t2 = one_t * one_t;
                let t2 = t * t;
                a * (one_t2 * one_t) + (u * (one_t2 * t) + v * (one_t * t2)) * 3. + b * (t2 * t)
            }
            fn cubic_bezier_mirrored(t: $t, a: Self, u: Self, v: Self, b: Self) -> Self {
                Self::cubic_bezier(t, a, u, b + b - v, b)
            }
        }
    };
}
splines_interpolate!(f32);
splines_interpolate!(f64);

fn peer_points<F: PeerFloat>(n: usize) -> Vec<V3<F>> {
    helix_points(n)
        .iter()
        .map(|p| V3(p.map(F::from_fixture)))
        .collect()
}

fn table<F: PeerFloat>(t: &[f64]) -> Vec<F> {
    t.iter().map(|&u| F::from_fixture(u)).collect()
}

/// Criterion settings: short, so that the whole run stays within minutes on 2 cores.
fn configure(g: &mut BenchmarkGroup<'_, WallTime>) {
    g.sample_size(20)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_millis(1_000));
}

/// The largest difference between two evaluated tables (cross-check of the libraries).
fn max_diff(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    a.iter()
        .zip(b)
        .flat_map(|(p, q)| (0..3).map(move |i| (p[i] - q[i]).abs()))
        .fold(0.0, f64::max)
}

/// Times `curve.eval` over `params` as benchmark `id`, after checking it against the
/// reference table within `tolerance`.
fn strak_timed<C>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    id: String,
    curve: &C,
    params: &[f64],
    reference: &[[f64; 3]],
    tolerance: f64,
) where
    C: ParamCurve,
    C::Point: Point,
{
    let us: Vec<ScalarOf<C>> = params
        .iter()
        .map(|&u| ScalarOf::<C>::from_f64(u).expect("parameter in range"))
        .collect();
    let got = strak_bench::fixture::eval_table(curve, params);
    let d = max_diff(&got, reference);
    assert!(d <= tolerance, "{id}: off by {d}");
    g.bench_function(id, |b| {
        b.iter(|| {
            for &u in &us {
                black_box(curve.eval(black_box(u)));
            }
        });
    });
}

/// strak's de Boor evaluator (`BSpline::eval`, the exact one).
fn strak_eval<P: Point>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    n: usize,
    params: &[f64],
    reference: &[[f64; 3]],
    tolerance: f64,
) {
    let curve = strak_curve::<P>(n);
    strak_timed(
        g,
        format!("strak_{name}/{n}"),
        &*curve,
        params,
        reference,
        tolerance,
    );
}

/// strak's power-basis evaluator ([`strak_curves::PowerSpline`]: span lookup and Horner).
fn strak_power_eval<P: Point>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    n: usize,
    params: &[f64],
    reference: &[[f64; 3]],
    tolerance: f64,
) {
    let curve = strak_power::<P>(n);
    strak_timed(
        g,
        format!("strak_power_{name}/{n}"),
        &*curve,
        params,
        reference,
        tolerance,
    );
}

fn enterpolation_eval<F: PeerFloat + num_traits::Float + num_traits::FromPrimitive>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    n: usize,
    params: &[f64],
    reference: &[[f64; 3]],
    tolerance: f64,
) {
    use enterpolation::Signal;
    use enterpolation::bspline::BSpline;
    let (lo, hi) = domain(n);
    let curve = BSpline::builder()
        .clamped()
        .elements(peer_points::<F>(n))
        .equidistant::<F>()
        .degree(DEGREE)
        .domain(F::from_fixture(lo), F::from_fixture(hi))
        .constant::<{ DEGREE + 1 }>()
        .build()
        .expect("enterpolation curve");
    let us = table::<F>(params);
    let got: Vec<[f64; 3]> = us
        .iter()
        .map(|&u| curve.eval(u).0.map(F::to_fixture))
        .collect();
    let d = max_diff(&got, reference);
    assert!(
        d <= tolerance,
        "enterpolation {} n={n}: off by {d}",
        F::NAME
    );
    g.bench_function(format!("enterpolation_{}/{n}", F::NAME), |b| {
        b.iter(|| {
            for &u in &us {
                black_box(curve.eval(black_box(u)));
            }
        });
    });
}

fn bspline_eval<F: PeerFloat + num_traits::Float>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    n: usize,
    params: &[f64],
    reference: &[[f64; 3]],
    tolerance: f64,
) {
    let knots: Vec<F> = clamped_knots(n).into_iter().map(F::from_fixture).collect();
    let curve = bspline::BSpline::new(DEGREE, peer_points::<F>(n), knots);
    let us = table::<F>(params);
    let got: Vec<[f64; 3]> = us
        .iter()
        .map(|&u| curve.point(u).0.map(F::to_fixture))
        .collect();
    let d = max_diff(&got, reference);
    assert!(d <= tolerance, "bspline {} n={n}: off by {d}", F::NAME);
    g.bench_function(format!("bspline_{}/{n}", F::NAME), |b| {
        b.iter(|| {
            for &u in &us {
                black_box(curve.point(black_box(u)));
            }
        });
    });
}

/// Catmull-Rom through the same points, keys at `t = i − 1` so that the inner segments cover
/// `[0, n − 3]`, the B-spline's domain (a different curve of the same cost class: a span
/// search and one cubic per sample).
fn splines_eval<F>(g: &mut BenchmarkGroup<'_, WallTime>, n: usize, params: &[f64])
where
    V3<F>: splines::Interpolate<F>,
    F: PeerFloat + splines::interpolate::Interpolator,
{
    use splines::{Interpolation, Key, Spline};
    let keys = peer_points::<F>(n)
        .into_iter()
        .enumerate()
        .map(|(i, p)| {
            Key::new(
                F::from_fixture(i as f64 - 1.0),
                p,
                Interpolation::CatmullRom,
            )
        })
        .collect();
    let curve = Spline::from_vec(keys);
    // The inner segments are half-open: the domain's end itself has no Catmull-Rom sample.
    let (_, hi) = domain(n);
    let inside: Vec<f64> = params.iter().map(|&u| u.min(hi - 1e-3)).collect();
    let us = table::<F>(&inside);
    for &u in &us {
        assert!(curve.clamped_sample(u).is_some(), "splines: no sample");
    }
    g.bench_function(format!("splines_catmull_rom_{}/{n}", F::NAME), |b| {
        b.iter(|| {
            for &u in &us {
                black_box(curve.clamped_sample(black_box(u)));
            }
        });
    });
}

/// kurbo's `CubicBez` (2-D, f64): one cubic Bézier, no span search (a lower bound for any
/// piecewise curve). Parameters mapped onto `[0, 1]`.
fn kurbo_eval(g: &mut BenchmarkGroup<'_, WallTime>, n: usize, params: &[f64]) {
    use kurbo::{CubicBez, ParamCurve as _};
    let p = helix_points(4);
    let c = CubicBez::new(
        (p[0][0], p[0][1]),
        (p[1][0], p[1][1]),
        (p[2][0], p[2][1]),
        (p[3][0], p[3][1]),
    );
    let (lo, hi) = domain(n);
    let us: Vec<f64> = params.iter().map(|u| (u - lo) / (hi - lo)).collect();
    g.bench_function(format!("kurbo_cubicbez_f64/{n}"), |b| {
        b.iter(|| {
            for &u in &us {
                black_box(c.eval(black_box(u)));
            }
        });
    });
}

fn evaluation(c: &mut Criterion) {
    for (group, make) in [
        ("eval_even", even_params as fn(usize) -> Vec<f64>),
        ("eval_random", random_params),
    ] {
        let mut g = c.benchmark_group(group);
        configure(&mut g);
        g.throughput(Throughput::Elements(TABLE_LEN as u64));
        for n in SIZES {
            let params = make(n);
            // f32 parameters near n carry a rounding of n·2⁻²⁴ (about 20 mm per unit of u).
            let tol32 = 1e-3 * (1.0 + n as f64 / 512.0);
            let reference = strak_bench::fixture::eval_table(&*strak_curve::<[f64; 3]>(n), &params);
            strak_eval::<[f32; 3]>(&mut g, "f32", n, &params, &reference, tol32);
            strak_eval::<[f64; 3]>(&mut g, "f64", n, &params, &reference, 0.0);
            strak_eval::<[I32F32; 3]>(&mut g, "i32f32", n, &params, &reference, 1e-6);
            strak_eval::<[I16F16; 3]>(&mut g, "i16f16", n, &params, &reference, 2e-3);
            strak_power_eval::<[f32; 3]>(&mut g, "f32", n, &params, &reference, tol32);
            strak_power_eval::<[f64; 3]>(&mut g, "f64", n, &params, &reference, 1e-11);
            strak_power_eval::<[I32F32; 3]>(&mut g, "i32f32", n, &params, &reference, 1e-6);
            strak_power_eval::<[I16F16; 3]>(&mut g, "i16f16", n, &params, &reference, 2e-3);
            enterpolation_eval::<f32>(&mut g, n, &params, &reference, tol32);
            enterpolation_eval::<f64>(&mut g, n, &params, &reference, 1e-9);
            bspline_eval::<f32>(&mut g, n, &params, &reference, tol32);
            bspline_eval::<f64>(&mut g, n, &params, &reference, 1e-9);
            splines_eval::<f32>(&mut g, n, &params);
            splines_eval::<f64>(&mut g, n, &params);
            kurbo_eval(&mut g, n, &params);
        }
        g.finish();
    }
}

fn playback_one<N: Kernel>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    n: usize,
    path: &Path<N, 3, PIECES>,
) {
    let mut s = Sampler::new(path);
    g.bench_function(format!("strak_{}/{n}", N::NAME.to_lowercase()), |b| {
        b.iter(|| {
            if s.is_finished() {
                s = Sampler::new(path);
            }
            black_box(s.next())
        });
    });
}

fn playback(c: &mut Criterion) {
    let mut g = c.benchmark_group("playback");
    configure(&mut g);
    g.throughput(Throughput::Elements(1));
    for n in SIZES {
        let paths = strak_paths(n);
        playback_one(&mut g, n, &*paths.f32);
        playback_one(&mut g, n, &*paths.f64);
        playback_one(&mut g, n, &*paths.q40);
    }
    g.finish();
}

/// Samples per `Sampler::fill` / `Sampler::fill_positions` call in the batch groups.
const BATCH: usize = 1024;

/// One whole playback of `path` per iteration in batches of [`BATCH`] by `fill` (the last
/// batch holds the samples left, so that no standstill after the end is counted); the
/// throughput is the path's samples, `ticks + 1`.
fn batch_one<N: Kernel, T: Copy>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    n: usize,
    path: &Path<N, 3, PIECES>,
    zero: T,
    fill: impl Fn(&mut Sampler<'_, N, 3>, &mut [T]),
) {
    let samples = path.ticks() as usize + 1;
    g.throughput(Throughput::Elements(samples as u64));
    let mut buf = vec![zero; BATCH];
    g.bench_function(format!("strak_{}/{n}", N::NAME.to_lowercase()), |b| {
        b.iter(|| {
            let mut s = Sampler::new(black_box(path));
            let mut left = samples;
            while left > 0 {
                let k = left.min(BATCH);
                fill(&mut s, black_box(&mut buf[..k]));
                left -= k;
            }
            black_box(&buf);
        });
    });
}

/// Batch playback: `Sampler::fill`, whole samples, over the whole path; the time is per
/// sample.
fn fill(c: &mut Criterion) {
    let mut g = c.benchmark_group("fill");
    configure(&mut g);
    for n in SIZES {
        let paths = strak_paths(n);
        batch_one(&mut g, n, &*paths.f32, Sample::splat(0.0), |s, b| s.fill(b));
        batch_one(&mut g, n, &*paths.f64, Sample::splat(0.0), |s, b| s.fill(b));
        batch_one(
            &mut g,
            n,
            &*paths.q40,
            Sample::splat(I32F32::ZERO),
            |s, b| s.fill(b),
        );
    }
    g.finish();
}

/// Batch playback of positions, the peers' job: `Sampler::fill_positions` over the whole
/// path; the time is per sample.
fn fill_positions(c: &mut Criterion) {
    let mut g = c.benchmark_group("fill_positions");
    configure(&mut g);
    for n in SIZES {
        let paths = strak_paths(n);
        batch_one(&mut g, n, &*paths.f32, [0.0; 3], |s, b| s.fill_positions(b));
        batch_one(&mut g, n, &*paths.f64, [0.0; 3], |s, b| s.fill_positions(b));
        batch_one(&mut g, n, &*paths.q40, [I32F32::ZERO; 3], |s, b| {
            s.fill_positions(b)
        });
    }
    g.finish();
}

/// The floor of any forward-differencing tick that keeps its state in memory between calls
/// (as a sampler must: an interrupt handler returns between ticks): the six additions per
/// axis of `AxisState::step` on the three states of the path's first piece, the state passed
/// through `black_box` every tick so that it is stored and reloaded, the positions returned.
/// No sampler bookkeeping, no sample construction: what is left is the chain
/// `p(k+1) = p(k) + Δ¹(k)` through a store and a load per tick.
fn floor_one<N: Kernel>(g: &mut BenchmarkGroup<'_, WallTime>, path: &Path<N, 3, PIECES>) {
    let Some(first) = path.pieces().first() else {
        return;
    };
    let mut state = *first.axes();
    g.bench_function(format!("strak_{}", N::NAME.to_lowercase()), |b| {
        b.iter(|| {
            let s = black_box(&mut state);
            let position = [s[0].position, s[1].position, s[2].position];
            for axis in s.iter_mut() {
                axis.step();
            }
            black_box(position)
        });
    });
}

fn floor(c: &mut Criterion) {
    let mut g = c.benchmark_group("floor");
    configure(&mut g);
    g.throughput(Throughput::Elements(1));
    let paths = strak_paths(FLATNESS_N);
    floor_one(&mut g, &*paths.f32);
    floor_one(&mut g, &*paths.f64);
    floor_one(&mut g, &*paths.q40);
    g.finish();
}

/// The size whose path the flatness benches play.
const FLATNESS_N: usize = 1024;

fn flatness_one<N: Kernel>(c: &mut Criterion, path: &Path<N, 3, PIECES>) {
    let ticks = u64::from(path.ticks());
    let pieces = path.pieces();
    // The tick whose `next()` loads a new piece: the last tick of a piece.
    let switch = |j: usize| {
        let p = &pieces[j];
        u64::from(p.start()) + u64::from(p.ticks()) - 1
    };
    let mid_piece = pieces.len() / 2;
    let at = [
        ("start".to_string(), 0),
        ("first_switch".to_string(), switch(0)),
        ("middle".to_string(), ticks / 2 + 1),
        ("middle_switch".to_string(), switch(mid_piece)),
        ("last_switch".to_string(), switch(pieces.len() - 2)),
        ("before_end".to_string(), ticks - 1),
        ("end".to_string(), ticks),
    ];
    let mut g = c.benchmark_group(format!("flatness_{}", N::NAME.to_lowercase()));
    configure(&mut g);
    g.throughput(Throughput::Elements(1));
    let base = sampler_at(path, 0);
    g.bench_function("baseline", |b| {
        b.iter_batched_ref(
            || base.clone(),
            |s| black_box(&*s).is_finished(),
            BatchSize::SmallInput,
        );
    });
    for (name, tick) in at {
        let s0 = sampler_at(path, tick);
        g.bench_function(name, |b| {
            b.iter_batched_ref(
                || s0.clone(),
                |s| black_box(s.next()),
                BatchSize::SmallInput,
            );
        });
    }
    g.finish();
}

/// The random moves of the `online` groups.
const ONLINE_CASES: usize = 1_000;

/// The `online` groups.
fn online(c: &mut Criterion) {
    let cases: Vec<OnlineCase<f64, 3>> =
        online_cases(BENCH_SEED, false).take(ONLINE_CASES).collect();
    let cases32: Vec<OnlineCase<f32, 3>> = cases
        .iter()
        .map(|c| c.in_f32().expect("the limits fit f32"))
        .collect();
    let options = MoveOptions::new();
    let mut m64 = OnlineMove::solve(
        &cases[0].start,
        &cases[0].target,
        &cases[0].limits,
        &options,
    )
    .expect("solves");
    let mut m32 = OnlineMove::solve(
        &cases32[0].start,
        &cases32[0].target,
        &cases32[0].limits,
        &options,
    )
    .expect("solves");
    let mut ruckig = ruckig::Ruckig::new_offline(3, 0);
    let mut trajectory = ruckig::Trajectory::new_direct(3);
    let mut inputs: Vec<ruckig::InputParameter> = cases.iter().map(ruckig_input).collect();
    let mut rs =
        rsruckig::prelude::Ruckig::<3, rsruckig::prelude::ThrowErrorHandler>::new(None, 0.001);
    let mut rs_trajectory = rsruckig::prelude::Trajectory::<3>::new(None);
    let rs_inputs: Vec<rsruckig::prelude::InputParameter<3>> =
        cases.iter().map(rsruckig_input).collect();
    let mut g = c.benchmark_group("online");
    configure(&mut g);
    g.throughput(Throughput::Elements(cases.len() as u64));
    g.bench_function("strak_f64", |b| {
        b.iter(|| {
            for c in &cases {
                let _ = black_box(m64.solve_in_place(&c.start, &c.target, &c.limits, &options));
            }
        });
    });
    g.bench_function("strak_f32", |b| {
        b.iter(|| {
            for c in &cases32 {
                let _ = black_box(m32.solve_in_place(&c.start, &c.target, &c.limits, &options));
            }
        });
    });
    g.bench_function("ruckig", |b| {
        b.iter(|| {
            for input in &mut inputs {
                black_box(ruckig.calculate(input, &mut trajectory));
            }
        });
    });
    g.bench_function("rsruckig", |b| {
        b.iter(|| {
            for input in &rs_inputs {
                let _ = black_box(rs.calculate(input, &mut rs_trajectory));
            }
        });
    });
    g.finish();
    // strak's median and slowest case: each case timed (the fastest of 30 solves).
    let mut times: Vec<(f64, usize)> = cases
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let best = (0..30)
                .map(|_| {
                    let t = std::time::Instant::now();
                    let _ = black_box(m64.solve_in_place(&c.start, &c.target, &c.limits, &options));
                    t.elapsed().as_secs_f64()
                })
                .fold(f64::INFINITY, f64::min);
            (best, i)
        })
        .collect();
    times.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut g = c.benchmark_group("online_case");
    configure(&mut g);
    for (name, (_, i)) in [
        ("median", times[times.len() / 2]),
        ("worst", times[times.len() - 1]),
    ] {
        let c = &cases[i];
        g.bench_function(name, |b| {
            b.iter(|| black_box(m64.solve_in_place(&c.start, &c.target, &c.limits, &options)));
        });
    }
    g.finish();
}

/// Writes a case into a Ruckig input (the C++ library's and rsruckig's have the same
/// fields).
macro_rules! fill_input {
    ($input:expr, $c:expr) => {
        for i in 0..3 {
            $input.current_position[i] = $c.start[i].position;
            $input.current_velocity[i] = $c.start[i].velocity;
            $input.current_acceleration[i] = $c.start[i].acceleration;
            $input.target_position[i] = $c.target[i].position;
            $input.target_velocity[i] = $c.target[i].velocity;
            $input.target_acceleration[i] = $c.target[i].acceleration;
            $input.max_velocity[i] = $c.limits[i].velocity_max();
            $input.max_acceleration[i] = $c.limits[i].acceleration_max();
            $input.max_jerk[i] = $c.limits[i].jerk();
        }
    };
}

/// Ruckig's input for a case.
fn ruckig_input(c: &OnlineCase<f64, 3>) -> ruckig::InputParameter {
    let mut input = ruckig::InputParameter::new(3);
    fill_input!(input, c);
    input
}

/// rsruckig's input for a case.
fn rsruckig_input(c: &OnlineCase<f64, 3>) -> rsruckig::prelude::InputParameter<3> {
    let mut input = rsruckig::prelude::InputParameter::new(None);
    fill_input!(input, c);
    input
}

fn main() {
    let mut c = Criterion::default().without_plots().configure_from_args();
    online(&mut c);
    evaluation(&mut c);
    playback(&mut c);
    fill(&mut c);
    fill_positions(&mut c);
    floor(&mut c);
    let paths = strak_paths(FLATNESS_N);
    flatness_one(&mut c, &*paths.f32);
    flatness_one(&mut c, &*paths.f64);
    flatness_one(&mut c, &*paths.q40);
    c.final_summary();
}
