//! End to end accuracy of playback in every number format (`f32`, `f64`, fixed-point `Q40`)
//! over more than 10⁶ ticks: the samples against the exact `f64` composition
//! `x(t) = c(u(t))`, and the exact end point.
//!
//! # Reference
//!
//! The exact motion is the `f64` curve at the time law's parameter at the plan time of each
//! tick, `x_k = c(u(t_k))` with `t_k = path.plan_time(k)` (the compiler's time stretch
//! included). Its velocity and acceleration are the time derivatives of that composition
//! (times the stretch `σ`, `σ²`), taken by central differences of step `δ` = 20 µs of the
//! exact composition; their error, `δ²/6·J + ε|x|/δ` and `δ·J/3 + 4ε|x|/δ²` (truncation, also
//! across a jerk step of up to `2J`, and `f64` rounding), is added to the bounds. (Not the
//! analytic `c'(u)·ṡ/|c'(u)|`: the arc-length table's inverse `u(s)` is only C¹ and its
//! derivative differs from `1/|c'|`; the compiler fits the composition as it is.)
//!
//! # Bounds
//!
//! * **Position** (the documented bound): `|x − x_exact| ≤ tolerance + playback_bound +
//!   output rounding`, where `output rounding` is `½ε·|x|` for floats (ε of the format) and
//!   2⁻³³ for `Q40` → `I32F32`.
//! * **Velocity and acceleration** (stated here): the compiled spline interpolates the exact
//!   motion at its knots; the classic error of cubic spline interpolation of a function whose
//!   third derivative is bounded by `J` scales as `‖e^(r)‖ ≤ C_r·J·h^(3−r)` on a piece of `h`
//!   seconds. With `J` = the compiled path's peak jerk and `h` the piece containing the
//!   tick, we allow `|Δv| ≤ J·h²/4` and `|Δa| ≤ J·h/2` (measured: 0.027·J·h² and
//!   0.15·J·h), plus the number format's error of the velocity and acceleration channels:
//!   `2(n + 1)·r(v_peak) + n²·r(a_peak·T)` and `2(n + 1)·r(a_peak)` (`r(m)` the rounding of a
//!   value of magnitude `m`: `½ε·m` for floats, 2⁻⁴¹ for `Q40`; `n` the piece length in
//!   ticks), plus the output rounding.
//! * **End**: the last sample equals the end point bit for bit: the `f64` curve's end point
//!   in `f64`, that point rounded to `f32` for `f32`, and to `I32F32` for `Q40`; for curves in
//!   `f32` or `I32F32` their own end point.

#![allow(clippy::needless_range_loop)] // axis loops index several arrays at once

use strak_curves::{BSpline, I32F32, Nurbs, ParamCurve, ParamCurveDeriv, Scalar};
use strak_trajectory::{
    Along, CompileOptions, Kernel, Limits, Number, Path, PathTiming, Q40, Sample, Sampler, Timing,
};
use strak_trajectory_tests::{compile_boxed, compile_within_bound};

/// 100 kHz: 10⁶ ticks in 10 s.
const RATE: f64 = 100_000.0;
/// Time step of the reference's central differences (seconds).
const DELTA: f64 = 2e-5;
/// Piece capacity (10⁶ ticks need ≥ 3907 pieces of 256 ticks).
const PIECES: usize = 8192;

/// The pick-and-place de Boor points (mm).
const PICK: [[f64; 3]; 8] = [
    [0.0, 0.0, 0.0],
    [0.0, 0.0, 30.0],
    [0.0, 0.0, 60.0],
    [60.0, 30.0, 60.0],
    [120.0, 60.0, 60.0],
    [180.0, 90.0, 60.0],
    [180.0, 90.0, 30.0],
    [180.0, 90.0, 0.0],
];

fn pick_and_place() -> BSpline<[f64; 3], 8, 12> {
    BSpline::clamped_uniform(3, &PICK, 0.0, 1.0).expect("pick and place")
}

/// The exact motion and its derivatives at tick `k` of `path`.
struct Exact<const A: usize> {
    x: [f64; A],
    v: [f64; A],
    a: [f64; A],
}

fn exact<C, N, const A: usize, const P: usize, const T: usize, const Z: usize>(
    curve: &C,
    plan: &PathTiming<'_, C, T, Z>,
    path: &Path<N, A, P>,
    k: u32,
) -> Exact<A>
where
    C: ParamCurveDeriv<Point = [f64; A]>,
    N: Kernel,
{
    let t = if k >= path.ticks() {
        plan.duration()
    } else {
        path.plan_time(f64::from(k))
    };
    let sigma = path.time_scale();
    let at = |t: f64| curve.eval(plan.param(t).0);
    let (xm, x, xp) = (at(t - DELTA), at(t), at(t + DELTA));
    Exact {
        x,
        v: core::array::from_fn(|i| (xp[i] - xm[i]) / (2.0 * DELTA) * sigma),
        a: core::array::from_fn(|i| (xp[i] - 2.0 * x[i] + xm[i]) / (DELTA * DELTA) * sigma * sigma),
    }
}

/// The error of the reference's central differences for a motion with jerk ≤ `j` and
/// coordinates ≤ `x` (velocity, acceleration): truncation `δ²/6·|x⃛|` and, where the jerk
/// steps by up to `2j`, `δ·2j/6`; rounding `ε|x|/δ` and `4ε|x|/δ²`.
fn reference_error(j: f64, x: f64) -> (f64, f64) {
    let eps = f64::EPSILON;
    (
        DELTA * DELTA * j / 6.0 + eps * x / DELTA,
        DELTA * 2.0 * j / 6.0 + 4.0 * eps * x / (DELTA * DELTA),
    )
}

/// The rounding of a value of magnitude `m` in `N`.
fn rounding<N: Kernel>(m: f64) -> f64 {
    N::rounding_error(m)
}

/// The output rounding of a sample value of magnitude `m`.
fn out_rounding<N: Kernel>(m: f64) -> f64 {
    if N::IS_FIXED {
        N::OUT_ERROR
    } else {
        N::rounding_error(m)
    }
}

/// Tracks one number format's samples against the exact motion.
struct Tracker<'a, N: Kernel, const A: usize, const P: usize> {
    path: &'a Path<N, A, P>,
    sampler: Sampler<'a, N, A>,
    piece: usize,
    /// Largest errors, and largest errors relative to their bounds.
    err: [f64; 3],
    ratio: [f64; 3],
    last: Option<Sample<N::Out, A>>,
}

impl<'a, N: Kernel, const A: usize, const P: usize> Tracker<'a, N, A, P> {
    fn new(path: &'a Path<N, A, P>) -> Self {
        Tracker {
            path,
            sampler: Sampler::new(path),
            piece: 0,
            err: [0.0; 3],
            ratio: [0.0; 3],
            last: None,
        }
    }

    fn step(&mut self, k: u32, ex: &Exact<A>) {
        let path = self.path;
        assert!(!self.sampler.is_finished());
        let s = self.sampler.next();
        assert_eq!(s.tick, u64::from(k));
        let pieces = path.pieces();
        while self.piece + 1 < pieces.len() && pieces[self.piece + 1].start() <= k {
            self.piece += 1;
        }
        let n = f64::from(pieces[self.piece].ticks());
        let period = path.period();
        let h = n * period;
        let (v_peak, a_peak, j) = (
            path.peak_velocity(),
            path.peak_acceleration(),
            path.peak_jerk(),
        );
        let v_format =
            2.0 * (n + 1.0) * rounding::<N>(v_peak) + n * n * rounding::<N>(a_peak * period);
        let a_format = 2.0 * (n + 1.0) * rounding::<N>(a_peak);
        let scale = ex.x.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
        let (v_ref, a_ref) = reference_error(j, scale);
        for i in 0..A {
            let (x, v, a) = (
                s.position[i].to_f64(),
                s.velocity[i].to_f64(),
                s.acceleration[i].to_f64(),
            );
            let errs = [
                (x - ex.x[i]).abs(),
                (v - ex.v[i]).abs(),
                (a - ex.a[i]).abs(),
            ];
            let bounds = [
                path.tolerance() + path.playback_bound() + out_rounding::<N>(x),
                j * h * h / 4.0 + v_format + v_ref + out_rounding::<N>(v),
                j * h / 2.0 + a_format + a_ref + out_rounding::<N>(a),
            ];
            for q in 0..3 {
                self.err[q] = self.err[q].max(errs[q]);
                self.ratio[q] = self.ratio[q].max(errs[q] / bounds[q]);
            }
        }
        self.last = Some(s);
    }

    /// Checks the end and reports.
    fn finish(self, name: &str) -> Sample<N::Out, A> {
        assert!(
            self.sampler.is_finished(),
            "{name}: not finished after the end sample"
        );
        let last = self.last.expect("samples");
        println!(
            "{name} {:>3}: {} ticks, {} pieces; position error {:.3e} (bound: tolerance {:.3e} \
             + playback {:.3e}), {:.3} of the bound; velocity error {:.3e} ({:.3} of its bound), \
             acceleration error {:.3e} ({:.3} of its bound)",
            N::NAME,
            self.path.ticks(),
            self.path.pieces().len(),
            self.err[0],
            self.path.tolerance(),
            self.path.playback_bound(),
            self.ratio[0],
            self.err[1],
            self.ratio[1],
            self.err[2],
            self.ratio[2],
        );
        for (q, what) in ["position", "velocity", "acceleration"].iter().enumerate() {
            assert!(
                self.ratio[q] <= 1.0,
                "{name} {}: {what} error {:e} is {} × its bound",
                N::NAME,
                self.err[q],
                self.ratio[q]
            );
        }
        assert_eq!(last.position, self.path.end_position(), "{name}: exact end");
        assert_eq!(last.velocity, [N::Out::ZERO; A], "{name}: rest at the end");
        last
    }
}

/// Compiles `plan` in all three formats, plays them in lockstep against the exact motion,
/// checks the bounds and the end point; returns the number of ticks.
fn three_formats<C, const A: usize, const T: usize, const Z: usize>(
    name: &str,
    curve: &C,
    plan: &PathTiming<'_, C, T, Z>,
    options: &CompileOptions,
) -> u32
where
    C: ParamCurveDeriv<Point = [f64; A]>,
{
    // f32 and Q40 within what their playback holds (the tolerance widened to twice the bound
    // where it is finer)
    let p32: Box<Path<f32, A, PIECES>> =
        compile_within_bound(&Along::new(curve, plan), RATE, options).expect("f32");
    let p64: Box<Path<f64, A, PIECES>> =
        compile_boxed(&Along::new(curve, plan), RATE, options).expect("f64");
    let pq: Box<Path<Q40, A, PIECES>> =
        compile_within_bound(&Along::new(curve, plan), RATE, options).expect("Q40");
    assert_eq!(p32.ticks(), p64.ticks());
    assert_eq!(pq.ticks(), p64.ticks());
    let (mut t32, mut t64, mut tq) = (Tracker::new(&p32), Tracker::new(&p64), Tracker::new(&pq));
    for k in 0..=p64.ticks() {
        let ex = exact(curve, plan, &p64, k);
        t32.step(k, &ex);
        t64.step(k, &ex);
        tq.step(k, &ex);
    }
    // The end point, bit for bit.
    let (_, u_end) = curve.domain();
    let end = curve.eval(u_end);
    let l32 = t32.finish(name);
    let l64 = t64.finish(name);
    let lq = tq.finish(name);
    for i in 0..A {
        #[allow(clippy::cast_possible_truncation)]
        let e32 = end[i] as f32;
        assert_eq!(
            l32.position[i].to_bits(),
            e32.to_bits(),
            "{name}: f32 end, axis {i}"
        );
        assert_eq!(
            l64.position[i].to_bits(),
            end[i].to_bits(),
            "{name}: f64 end, axis {i}"
        );
        assert_eq!(
            lq.position[i],
            I32F32::from_num(end[i]),
            "{name}: Q40 end, axis {i}"
        );
    }
    p64.ticks()
}

#[test]
fn million_ticks_in_every_format() {
    let ticks = {
        // Pick and place at 28 mm/s: about 10.6 s, 1.06·10⁶ ticks at 100 kHz.
        let curve = pick_and_place();
        let limits = Limits::<3>::new(28.0, 300.0, 6_000.0).expect("limits");
        let plan = PathTiming::<_, 256, 128>::scurve(&curve, &limits).expect("plan");
        let options = CompileOptions::new().with_relative_tolerance(1e-7);
        let a = three_formats("pick-and-place", &curve, &plan, &options);

        // A NURBS circle of radius 10 far from the origin (1000, −2000): large coordinates
        // stress the float formats. 257 table samples put the circle's knots on table nodes.
        let circle = Nurbs::<[f64; 2], 9, 12>::circle([1_000.0, -2_000.0], 10.0).expect("circle");
        let limits = Limits::<2>::new(40.0, 400.0, 8_000.0).expect("limits");
        let plan = PathTiming::<_, 257, 128>::scurve(&circle, &limits).expect("plan");
        let options = CompileOptions::new().with_tolerance(1e-6);
        let b = three_formats("far circle", &circle, &plan, &options);
        u64::from(a) + u64::from(b)
    };
    println!("{ticks} ticks in total");
    assert!(ticks >= 1_000_000, "{ticks}");
}

/// The end point of a curve in `f32` or `I32F32` is the path's end, bit for bit: the curve's
/// own end point, not a rounding of the `f64` one.
#[test]
fn end_point_of_curves_in_their_own_type() {
    // f32 curve → f32 path
    let pts32: Vec<[f32; 3]> = PICK
        .iter()
        .map(|p| p.map(|x| x as f32 * 1.1 + 0.1))
        .collect();
    let c32 = BSpline::<[f32; 3], 8, 12>::clamped_uniform(3, &pts32, 0.0, 1.0).expect("f32");
    let limits = Limits::<3>::new(200.0, 2_000.0, 50_000.0).expect("limits");
    let plan = PathTiming::<_, 256, 128>::scurve(&c32, &limits).expect("plan");
    let path: Box<Path<f32, 3, 1024>> =
        compile_boxed(&Along::new(&c32, &plan), 10_000.0, &CompileOptions::new()).expect("compile");
    let last = play_to_end(&path);
    let end = c32.eval(1.0);
    for i in 0..3 {
        assert_eq!(last.position[i].to_bits(), end[i].to_bits(), "axis {i}");
    }

    // I32F32 curve → Q40 path
    let ptsq: Vec<[I32F32; 3]> = PICK
        .iter()
        .map(|p| p.map(|x| I32F32::from_num(x * 1.1 + 0.1 / 3.0)))
        .collect();
    let cq = BSpline::<[I32F32; 3], 8, 12>::clamped_uniform(3, &ptsq, I32F32::ZERO, I32F32::ONE)
        .expect("fixed");
    let plan = PathTiming::<_, 256, 128>::scurve(&cq, &limits).expect("plan");
    let path: Box<Path<Q40, 3, 1024>> =
        compile_boxed(&Along::new(&cq, &plan), 10_000.0, &CompileOptions::new()).expect("compile");
    let last = play_to_end(&path);
    assert_eq!(last.position, cq.eval(I32F32::ONE));
    assert_eq!(path.end_position(), cq.eval(I32F32::ONE));

    // f64 curve → f64 path with an end point that is not a round number
    let c64 = BSpline::<[f64; 3], 8, 12>::clamped_uniform(
        3,
        &PICK.map(|p| p.map(|x| x / 3.0 + 0.1)),
        0.0,
        1.0,
    )
    .expect("f64");
    let plan = PathTiming::<_, 256, 128>::scurve(&c64, &limits).expect("plan");
    let path: Box<Path<f64, 3, 1024>> =
        compile_boxed(&Along::new(&c64, &plan), 10_000.0, &CompileOptions::new()).expect("compile");
    let last = play_to_end(&path);
    let end = c64.eval(1.0);
    for i in 0..3 {
        assert_eq!(last.position[i].to_bits(), end[i].to_bits(), "axis {i}");
    }
}

/// Plays a path to its end; returns the last sample (checks the sampler's end semantics).
fn play_to_end<N: Kernel, const A: usize, const P: usize>(
    path: &Path<N, A, P>,
) -> Sample<N::Out, A> {
    let mut s = Sampler::new(path);
    let mut last = None;
    let mut count = 0_u64;
    while !s.is_finished() {
        last = Some(s.next());
        count += 1;
        assert!(count <= u64::from(path.ticks()) + 1);
    }
    assert_eq!(count, u64::from(path.ticks()) + 1);
    let last = last.expect("samples");
    // after the end: the end point, at rest, forever
    for _ in 0..3 {
        let after = s.next();
        assert_eq!(after.position, last.position);
        assert_eq!(after.velocity, [N::Out::ZERO; A]);
        assert_eq!(after.acceleration, [N::Out::ZERO; A]);
    }
    last
}

/// The playback bound of a long piece in `Q40` is the documented
/// `½ulp·(1 + n + n²/2 + n³/6)` scale, about 2.5·10⁻⁶ at n = 256 (plus the output rounding),
/// and the measured format error (samples against the compiled polynomial evaluated in
/// `f64`) stays within it.
#[test]
fn q40_format_error_within_the_playback_bound() {
    let curve = pick_and_place();
    let limits = Limits::<3>::new(28.0, 300.0, 6_000.0).expect("limits");
    let plan = PathTiming::<_, 256, 128>::scurve(&curve, &limits).expect("plan");
    let path: Box<Path<Q40, 3, PIECES>> =
        compile_boxed(&Along::new(&curve, &plan), RATE, &CompileOptions::new()).expect("compile");
    let n = 256.0_f64;
    let ulp = 2f64.powi(-40);
    let documented = 0.5 * ulp * (1.0 + n + n * n / 2.0 + n * n * n / 6.0);
    println!(
        "Q40 playback bound {:.3e}, documented scale {documented:.3e}",
        path.playback_bound()
    );
    assert!(path.playback_bound() <= 1.3 * documented + Q40::OUT_ERROR);
    assert!(path.playback_bound() >= 0.5 * documented);
    let mut s = Sampler::new(&*path);
    let mut worst = 0.0_f64;
    for k in 0..=path.ticks() {
        let smp = s.next();
        let poly = path.eval(f64::from(k));
        for i in 0..3 {
            worst = worst.max((smp.position[i].to_f64() - poly.position[i]).abs());
        }
    }
    println!("Q40 measured format error {worst:.3e}");
    assert!(worst <= path.playback_bound(), "{worst}");
}

/// Sanity of the reference: it starts and ends at the curve's ends, at rest.
#[test]
fn reference_starts_and_ends_at_rest() {
    let curve = pick_and_place();
    let limits = Limits::<3>::new(28.0, 300.0, 6_000.0).expect("limits");
    let plan = PathTiming::<_, 256, 128>::scurve(&curve, &limits).expect("plan");
    let path: Box<Path<f64, 3, PIECES>> =
        compile_boxed(&Along::new(&curve, &plan), 1_000.0, &CompileOptions::new())
            .expect("compile");
    let start = exact(&curve, &plan, &path, 0);
    let end = exact(&curve, &plan, &path, path.ticks());
    assert_eq!(start.x, [0.0, 0.0, 0.0]);
    assert_eq!(end.x, [180.0, 90.0, 0.0]);
    // at rest, up to the reference's own difference error (δ²·j)
    let (v_ref, _) = reference_error(6_000.0, 200.0);
    assert!(
        start.v.iter().chain(&end.v).all(|v| v.abs() <= v_ref),
        "{:?} {:?}",
        start.v,
        end.v
    );
    assert_eq!(plan.param(0.0), (0.0, 0.0));
    assert_eq!(plan.param(plan.duration()).0, 1.0);
}

/// One axis (a spindle or a linear stage) and six axes (the joints of a robot arm, in
/// degrees): the same bounds and the exact end point in every format.
#[test]
fn one_and_six_axes() {
    let stage = BSpline::<[f64; 1], 5, 9>::clamped_uniform(
        3,
        &[[0.0], [20.0], [5.0], [60.0], [80.0]],
        0.0,
        1.0,
    )
    .expect("stage");
    let limits = Limits::<1>::new(100.0, 1_000.0, 20_000.0).expect("limits");
    let plan = PathTiming::<_, 256, 128>::scurve(&stage, &limits).expect("plan");
    let one = three_formats("one axis", &stage, &plan, &CompileOptions::new());

    let joints: [[f64; 6]; 6] = [
        [0.0, -90.0, 90.0, 0.0, 45.0, 0.0],
        [10.0, -80.0, 85.0, 5.0, 40.0, 15.0],
        [40.0, -60.0, 70.0, 20.0, 30.0, 60.0],
        [80.0, -45.0, 60.0, 10.0, 35.0, 120.0],
        [110.0, -50.0, 75.0, -5.0, 45.0, 170.0],
        [120.0, -55.0, 80.0, -10.0, 50.0, 180.0],
    ];
    let arm = BSpline::<[f64; 6], 6, 10>::clamped_uniform(3, &joints, 0.0, 1.0).expect("arm");
    let limits = Limits::<6>::new(180.0, 720.0, 10_000.0)
        .and_then(|l| l.with_axis_velocity([90.0, 60.0, 60.0, 120.0, 120.0, 180.0]))
        .expect("limits");
    let plan = PathTiming::<_, 256, 128>::scurve(&arm, &limits).expect("plan");
    let six = three_formats("six axes", &arm, &plan, &CompileOptions::new());
    println!("one axis: {one} ticks, six axes: {six} ticks");
    assert!(one > 10_000 && six > 10_000);
}
