//! What the compiled path promises beyond the plan's path limits, measured from the
//! samples: every tick within the tolerance of `c(u(t))` where the law is not smooth
//! between the knots, the per-axis limits of a plan, the tangential acceleration of the
//! global trapezoid, and the arc-length mapping near a point where the curve's speed
//! vanishes. Each case is the smallest form of an input the `pipeline` fuzz target found
//! (`fuzz/artifacts-kept/pipeline/accuracy-f64` and `axis-velocity-f64`).
//!
//! The finite differences of one tick are the means of the motion's derivatives over the
//! tick (the compiled motion is one cubic between two ticks), so they add nothing above
//! the motion's peaks; in `f64` the allowance is rounding only: `10⁻⁶` of the limit.

use strak_curves::{BSpline, Bezier, ParamCurve};
use strak_trajectory::{
    Along, CompileOptions, Limits, Path, PathTiming, PlanOptions, ProfileShape, Sample, Sampler,
    Timing, compile,
};

/// The relative allowance of the limits in `f64` (rounding of the plan and the differences).
const RELATIVE: f64 = 1e-6;

/// Every sample of `path` at feed 1.
fn samples<const A: usize, const P: usize>(path: &Path<f64, A, P>) -> Vec<Sample<f64, A>> {
    let mut sampler = Sampler::new(path);
    let mut out = vec![sampler.next()];
    while !sampler.is_finished() {
        out.push(sampler.next());
    }
    assert_eq!(out.len() as u64, u64::from(path.ticks()) + 1);
    out
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// A cubic Bézier curve whose last two control points coincide (a quadratic-looking curve
/// whose speed `|c'(u)|` falls to 0 at the end, linearly in `1 − u`).
fn stalling() -> Bezier<[f64; 2], 4> {
    let p = [[-6.325, -8.05], [-4.025, 23.575], [-21.85, 4.025]];
    Bezier::new([p[0], p[1], p[2], p[2]]).unwrap()
}

/// The global trapezoid of the fuzz input `accuracy-f64`.
const TRAPEZOID: (f64, f64) = (145.475, 414.60375);

/// The fuzz input's compile settings, with the machine's limits: the trapezoid reserves
/// nothing for feed changes, so the machine is taken to have the default share (¼) more
/// than the law's tangential limit.
fn stalling_options() -> CompileOptions {
    let machine = TRAPEZOID.1 / (1.0 - CompileOptions::DEFAULT_FEED_SHARE);
    CompileOptions::new()
        .with_relative_tolerance(1.08e-4)
        .with_max_piece_ticks(55)
        .with_limits(machine, 100.0 * machine)
}

/// The largest distance of the samples from `c(u(t))` at the plan time of their tick.
fn largest_error<C, T, const P: usize>(curve: &C, law: &T, path: &Path<f64, 2, P>) -> f64
where
    C: ParamCurve<Point = [f64; 2]>,
    T: Timing,
{
    let mut worst = 0.0_f64;
    for s in samples(path) {
        #[allow(clippy::cast_precision_loss)]
        let t = path.plan_time(s.tick as f64);
        let want = curve.eval(law.param(t).0);
        for (x, w) in s.position.iter().zip(want) {
            worst = worst.max((x - w).abs());
        }
    }
    worst
}

/// A time law with a narrow bump in speed: `u = τ + ε·exp(−((t − t₀)/w)²)` (`τ = t/D`),
/// centred 8 ticks (at 1 kHz) into a piece of 64 ticks, where none of its quarter points
/// (16, 32, 48) sees it.
struct Bump;

impl Bump {
    const DURATION: f64 = 0.64;
    const CENTRE: f64 = 0.328;
    const WIDTH: f64 = 0.0015;
    const HEIGHT: f64 = 1e-4;
}

impl Timing for Bump {
    fn duration(&self) -> f64 {
        Self::DURATION
    }
    fn param(&self, t: f64) -> (f64, f64) {
        let t = t.clamp(0.0, Self::DURATION);
        let z = (t - Self::CENTRE) / Self::WIDTH;
        let g = Self::HEIGHT * (-z * z).exp();
        (
            t / Self::DURATION + g,
            1.0 / Self::DURATION - 2.0 * z / Self::WIDTH * g,
        )
    }
}

/// The compiler checks every tick against the tolerance, not only each piece's quarter
/// points: a law whose error hides between them (a bump of 3 ticks, 8 ticks into a piece)
/// is split there. Without the check of every tick the bump's ticks are up to
/// `10⁻⁴·|c'| = 5·10⁻³` off, 50 times the tolerance.
#[test]
fn every_tick_within_the_tolerance_between_the_quarter_points() {
    let line = Bezier::new([[0.0_f64, 0.0], [30.0, 40.0]]).unwrap(); // |c'| = 50
    let tolerance = 1e-4;
    let options = CompileOptions::new()
        .with_tolerance(tolerance)
        .with_max_piece_ticks(64);
    let path: Path<f64, 2, 64> = compile(&Along::new(&line, &Bump), 1_000.0, &options).unwrap();
    assert_eq!(path.ticks(), 640);
    let worst = largest_error(&line, &Bump, &path);
    assert!(worst <= tolerance, "{worst:e} > {tolerance:e}");
    // the bump needed pieces shorter than 64 ticks around tick 328
    let around = path
        .pieces()
        .iter()
        .find(|p| p.start() <= 328 && 328 < p.start() + p.ticks())
        .unwrap();
    assert!(around.ticks() < 64, "{}", around.ticks());
}

/// The fuzz input `accuracy-f64`: a global trapezoid on the stalling Bézier curve, pieces of
/// at most 55 ticks; a sample was 2.165·10⁻³ from `c(u(t))` with a tolerance of
/// 1.918·10⁻³.
#[test]
fn every_tick_within_the_tolerance_on_a_stalling_curve() {
    let curve = stalling();
    let law = PathTiming::<_, 64, 64>::trapezoid(&curve, TRAPEZOID.0, TRAPEZOID.1).unwrap();
    let path: Path<f64, 2, 64> = compile(&law, 1_000.0, &stalling_options()).unwrap();
    let worst = largest_error(&curve, &law, &path);
    assert!(
        worst <= path.tolerance(),
        "{worst:e} > {:e}",
        path.tolerance()
    );
}

/// The motion along the stalling curve moves at the planned speed `ṡ` up to its end: the
/// parameter at an arc length is the root of the table's interpolant of `s(u)`. (The
/// table's inverse interpolant `u(s)` cannot follow `du/ds = 1/|c'| → ∞` there: the speed
/// was 3.59 against a planned 2.28 two ticks before the end, 1.87 against 3.52 at another.)
#[test]
fn the_motion_keeps_the_planned_speed_where_the_curve_stalls() {
    let curve = stalling();
    let law = PathTiming::<_, 64, 64>::trapezoid(&curve, TRAPEZOID.0, TRAPEZOID.1).unwrap();
    let d = law.duration();
    let steps = 20_000;
    let at = |k: u32| curve.eval(law.param(d * f64::from(k) / f64::from(steps)).0);
    let dt = d / f64::from(steps);
    let mut worst = 0.0_f64;
    for k in 0..steps {
        let (a, b) = (at(k), at(k + 1));
        let speed = norm(&[b[0] - a[0], b[1] - a[1]]) / dt;
        let planned = law.motion().state(dt * (f64::from(k) + 0.5)).v;
        // the chord's mean speed against the plan's speed in the middle of the step: they
        // differ by the step's curvature of the speed, far below 10⁻³·v_max here
        worst = worst.max((speed - planned).abs());
    }
    assert!(worst < 1e-3 * TRAPEZOID.0, "{worst}");
}

/// The global trapezoid promises its tangential acceleration, and the compiler keeps it:
/// the C² spline smooths the trapezoid's acceleration steps with an overshoot (+33 % in
/// the samples of the fuzz input), which the compiler now slows down for.
/// Measured as `(|v_{k+1}| − |v_k|)/T`, the mean of `d|ẋ|/dt` over each tick.
#[test]
fn the_global_trapezoid_keeps_its_tangential_acceleration() {
    let curve = stalling();
    let (v_max, a_max) = TRAPEZOID;
    let law = PathTiming::<_, 64, 64>::trapezoid(&curve, v_max, a_max).unwrap();
    let rate = 1_000.0;
    let path: Path<f64, 2, 64> = compile(&law, rate, &stalling_options()).unwrap();
    let s = samples(&path);
    let (mut speed, mut tangential) = (0.0_f64, 0.0_f64);
    for w in s.windows(2) {
        let dx = [
            w[1].position[0] - w[0].position[0],
            w[1].position[1] - w[0].position[1],
        ];
        speed = speed.max(norm(&dx) * rate);
        let dv = norm(&w[1].velocity) - norm(&w[0].velocity);
        tangential = tangential.max(dv.abs() * rate);
    }
    println!(
        "speed {speed:.4} of {v_max}, tangential acceleration {tangential:.4} of {a_max}, \
         time scale {:.4}",
        path.time_scale()
    );
    assert!(speed <= v_max * (1.0 + RELATIVE), "{speed}");
    assert!(tangential <= a_max * (1.0 + RELATIVE), "{tangential}");
    assert!(path.time_scale() < 1.0);
}

/// The fuzz input `axis-velocity-f64`: a planned trapezoid on a 3-axis cubic B-spline with
/// a velocity limit of 2.604 on x (the path limit 12.5), compiled at 100 Hz to a coarse
/// tolerance (0.12). The compiled pieces overshot the law's x velocity by 17 % (3.055),
/// which the compiler did not see, knowing only the path limits: a plan now reports its
/// per-axis limits ([`strak_trajectory::MotionLimits`]), and the compiler slows down
/// for them.
#[test]
fn the_compiled_pieces_keep_the_per_axis_velocity() {
    let points = [
        [-0.414, -1.173, 0.276],
        [-5.037, -0.828, 1.104],
        [-0.276, 8.556, 4.692],
        [1.38, -5.589, 0.0],
        [8.073, 4.692, 8.28],
    ];
    let curve = BSpline::<_, 8, 12>::clamped_uniform(3, &points, 0.0, 1.0).unwrap();
    let axis_v = [2.6038116, 92.26005525, 1.9528587];
    let keep = 0.61;
    let limits = Limits::new(12.518325, 116.29523925 * keep, 2698.0495506 * keep)
        .and_then(|l| l.with_axis_velocity(axis_v))
        .unwrap();
    let plan = PlanOptions::new()
        .with_samples(240)
        .with_zone_tolerance(7.74)
        .with_centripetal_share(0.42)
        .with_corner_angle(1e-4)
        .with_shape(ProfileShape::Trapezoid);
    let law = PathTiming::<_, 64, 64>::plan(&curve, &limits, &plan).unwrap();
    let options = CompileOptions::new()
        .with_tolerance(0.12122265)
        .with_max_piece_ticks(371);
    let rate = 100.0;
    let path: Path<f64, 3, 64> = compile(&Along::new(&curve, &law), rate, &options).unwrap();
    let s = samples(&path);
    let mut worst = [0.0_f64; 3];
    for w in s.windows(2) {
        for (i, m) in worst.iter_mut().enumerate() {
            *m = m.max((w[1].position[i] - w[0].position[i]).abs() * rate);
        }
    }
    println!(
        "axis velocities {worst:?} of {axis_v:?}, time scale {:.4}",
        path.time_scale()
    );
    for i in 0..3 {
        assert!(
            worst[i] <= axis_v[i] * (1.0 + RELATIVE),
            "axis {i}: {}",
            worst[i]
        );
    }
    assert!(path.time_scale() < 1.0);
}
