//! Planner options and limits that could break the kinematic limits, end to end (plan →
//! compile → play in `f64`), checked only from the samples: corner angles up to π on
//! polylines, paths that double back on themselves (cusps), jerk limits whose phases would
//! be far shorter than a tick, velocity limits too small to play, and the feed reserve of the
//! planning API under feed override, hold and resume. And the texts of the planner's errors.
//!
//! # Method
//!
//! Each motion is planned with the machine's limits through the library's one way,
//! [`PathTiming::plan`] (which keeps the feed share of the acceleration and jerk limits
//! free, ¼ by default) and [`PathTiming::compile`] (at the plan's rate, with the machine's
//! limits for feed ramps), and played with [`Sampler`]. From the samples `x_k`, `v_k`, `a_k`
//! (period `T`) the speed is `|x_{k+1} − x_k|/T`, the acceleration `|v_{k+1} − v_k|/T` and
//! the jerk `|a_{k+1} − a_k|/T` (vector norms, and per axis).
//!
//! # Tolerances
//!
//! * A difference quotient over one tick is the mean of the derivative over that tick (the
//!   compiled path is one cubic between two ticks), so it never exceeds the largest value of
//!   the played motion: no allowance for the differencing itself beyond `f64` rounding
//!   ([`ROUNDING`]).
//! * Acceleration and jerk at feed 1: within the machine's limits. The plan uses ¾ of them;
//!   the fit of the compiled spline must stay within the rest.
//! * Speed: the compiled spline follows positions within the tolerance `tol`, and its
//!   velocity is off by about `3.2·tol/h` (cubic spline interpolation's interior error
//!   constants, Hall & Meyer 1976; `h` the longest piece) — velocities are not reserved
//!   (a feed factor `≤ 1` only slows down), so the allowance is that bound
//!   ([`velocity_allowance`]).
//! * During feed ramps: within the machine's limits too. In continuous time the ramp adds
//!   `φ̇·v` to the acceleration and `3·φ·φ̇·p'' + φ̈·p'` to the jerk (chain rule), which the
//!   compiled path's ramp constants keep within what the plan left free; the ramp changes
//!   `φ̇` once per tick, which shifts these terms by a tick at most, and no allowance is made
//!   for it (the test would catch it).

use strak_curves::{BSpline, Bezier, ParamCurveDeriv, Scalar};
use strak_trajectory::{
    Along, CompileOptions, Error, Kernel, Limits, Path, PathTiming, PlanOptions, Quantity, Sampler,
    Timing,
};
use strak_trajectory_tests::{Unpromised, compile_boxed, compile_plan_boxed};

/// Relative `f64` rounding of the difference quotients.
const ROUNDING: f64 = 1e-9;
/// Piece capacity of the compiled paths.
const PIECES: usize = 4096;
/// Arc-length table and zones of the plans.
const TABLE: usize = 256;
const ZONES: usize = 256;

type Plan<'a, C> = PathTiming<'a, C, TABLE, ZONES>;

fn norm<const A: usize>(x: &[f64; A]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>().sqrt()
}

/// The largest values measured from the samples, as ratios to the machine's limits.
#[derive(Clone, Copy, Debug, Default)]
struct Ratios {
    speed: f64,
    axis_speed: f64,
    acceleration: f64,
    axis_acceleration: f64,
    jerk: f64,
}

/// Plays `path` to the end, calling `control(k, sampler)` before sample `k`; measures the
/// samples against `machine`. Returns the ratios and the number of samples.
fn play<N: Kernel, const A: usize>(
    path: &Path<N, A, PIECES>,
    machine: &Limits<A>,
    mut control: impl FnMut(u64, &mut Sampler<'_, N, A>),
) -> (Ratios, u64) {
    let t = path.period();
    let mut s = Sampler::new(path);
    let mut r = Ratios::default();
    let mut prev: Option<[[f64; A]; 3]> = None;
    let mut k = 0_u64;
    while !s.is_finished() {
        control(k, &mut s);
        let smp = s.next();
        let cur = [
            smp.position.map(Scalar::to_f64),
            smp.velocity.map(Scalar::to_f64),
            smp.acceleration.map(Scalar::to_f64),
        ];
        if let Some(p) = prev {
            let d = |i: usize| -> [f64; A] { core::array::from_fn(|a| (cur[i][a] - p[i][a]) / t) };
            let (v, a, j) = (d(0), d(1), d(2));
            r.speed = r.speed.max(norm(&v) / machine.velocity());
            r.acceleration = r.acceleration.max(norm(&a) / machine.acceleration());
            r.jerk = r.jerk.max(norm(&j) / machine.jerk());
            for i in 0..A {
                r.axis_speed = r.axis_speed.max(v[i].abs() / machine.axis_velocity()[i]);
                r.axis_acceleration = r
                    .axis_acceleration
                    .max(a[i].abs() / machine.axis_acceleration()[i]);
            }
        }
        prev = Some(cur);
        k += 1;
        assert!(k < 100_000_000, "the sampler does not finish");
    }
    (r, k)
}

/// How much the compiled velocity may exceed the plan's (units/s): `3.2·tol/h` on the
/// longest pieces (see the module docs).
fn velocity_allowance<N: Kernel, const A: usize>(path: &Path<N, A, PIECES>) -> f64 {
    let longest = path.pieces().iter().map(|p| p.ticks()).max().unwrap_or(1);
    3.2 * path.tolerance() / (f64::from(longest) * path.period())
}

/// Asserts the ratios of a run at feed 1 against the machine's limits.
fn assert_within<N: Kernel, const A: usize>(
    name: &str,
    r: &Ratios,
    path: &Path<N, A, PIECES>,
    machine: &Limits<A>,
) {
    println!(
        "{name}: |v| {:.4} (axis {:.4}) |a| {:.4} (axis {:.4}) |j| {:.4} of the limits, {} ticks",
        r.speed,
        r.axis_speed,
        r.acceleration,
        r.axis_acceleration,
        r.jerk,
        path.ticks()
    );
    let fit = velocity_allowance(path) / machine.velocity();
    assert!(r.speed <= 1.0 + fit + ROUNDING, "{name}: speed {}", r.speed);
    assert!(r.axis_speed <= 1.0 + fit + ROUNDING, "{name}: axis speed");
    assert!(
        r.acceleration <= 1.0 + ROUNDING,
        "{name}: |a| {}",
        r.acceleration
    );
    assert!(r.axis_acceleration <= 1.0 + ROUNDING, "{name}: axis |a|");
    assert!(r.jerk <= 1.0 + ROUNDING, "{name}: |j| {}", r.jerk);
}

/// Plans with `options`, compiles at the plan's rate and plays at feed 1.
fn run<C, const A: usize>(name: &str, curve: &C, machine: &Limits<A>, options: &PlanOptions)
where
    C: ParamCurveDeriv<Point = [f64; A]>,
{
    let plan: Plan<'_, C> = PathTiming::plan(curve, machine, options).expect("plan");
    let path: Box<Path<f64, A, PIECES>> =
        compile_plan_boxed(&plan, &CompileOptions::new()).expect("compile");
    let (r, _) = play(&path, machine, |_, _| {});
    assert_within(name, &r, &path, machine);
}

// ---------------------------------------------------------------------------------------------
// Corner angles
// ---------------------------------------------------------------------------------------------

fn machine2() -> Limits<2> {
    Limits::new(200.0, 2_000.0, 50_000.0).expect("limits")
}

/// A polyline (0,0) → (50,0) → 50 more at the turn `radians`: a degree-1 B-spline.
fn polyline(radians: f64) -> BSpline<[f64; 2], 4, 8> {
    let pts = [
        [0.0, 0.0],
        [50.0, 0.0],
        [50.0 + 50.0 * radians.cos(), 50.0 * radians.sin()],
    ];
    BSpline::clamped_uniform(1, &pts, 0.0, 1.0).expect("polyline")
}

/// A G1-style polyline through 21 points, 10 mm apart, alternating 90° and 30° turns.
fn zigzag() -> BSpline<[f64; 2], 24, 32> {
    let mut pts = [[0.0; 2]; 21];
    let mut heading = 0.0_f64;
    for i in 1..21 {
        heading += if i % 2 == 0 { 90.0_f64 } else { -30.0 }.to_radians();
        pts[i] = [
            pts[i - 1][0] + 10.0 * heading.cos(),
            pts[i - 1][1] + 10.0 * heading.sin(),
        ];
    }
    BSpline::clamped_uniform(1, &pts, 0.0, 1.0).expect("zigzag")
}

/// Any corner angle, default to π (no join ever counts as a corner): joins from 0.06° to 179°
/// keep the limits at 1 and 10 kHz, by stopping or by crawling through.
#[test]
fn corner_angle_never_breaks_the_limits() {
    let m = machine2();
    for angle in [1e-4, 1.0, core::f64::consts::PI] {
        for rate in [1_000.0, 10_000.0] {
            let o = PlanOptions::new().with_corner_angle(angle).with_rate(rate);
            for deg in [0.06, 1.0, 5.0, 30.0, 90.0, 179.0] {
                let name = format!("turn {deg}° corner angle {angle} at {rate} Hz");
                run(&name, &polyline(f64::to_radians(deg)), &m, &o);
            }
            let name = format!("zigzag, corner angle {angle} at {rate} Hz");
            run(&name, &zigzag(), &m, &o);
        }
    }
}

/// The measurement catches a join passed at speed: a plan whose zones are forced through the
/// 30° join at full speed (a time law of our own) breaks the acceleration limit many times.
#[test]
fn a_join_at_speed_is_caught() {
    /// Constant speed 150 along the polyline's arc length (= parameter · 100).
    struct Through;
    impl Timing for Through {
        fn duration(&self) -> f64 {
            100.0 / 150.0
        }
        fn param(&self, t: f64) -> (f64, f64) {
            ((t * 1.5).clamp(0.0, 1.0), 1.5)
        }
    }
    let m = machine2();
    let c = polyline(30.0_f64.to_radians());
    let path: Box<Path<f64, 2, PIECES>> =
        compile_boxed(&Along::new(&c, &Through), 1_000.0, &CompileOptions::new()).expect("compile");
    let (r, _) = play(&path, &m, |_, _| {});
    println!("30° at 150 mm/s: |a| {:.1} × the limit", r.acceleration);
    assert!(r.acceleration > 5.0, "{}", r.acceleration);
}

// ---------------------------------------------------------------------------------------------
// Cusps
// ---------------------------------------------------------------------------------------------

/// Paths that double back on themselves: the tangent reverses inside a piece. The motion
/// comes to rest at the reversal and keeps the limits.
#[test]
fn cusps_stop_the_motion() {
    let m = machine2();
    let o = PlanOptions::new();
    // out to x = 4, back to x = −5 (c' = 0 at u = 0.4)
    let back = Bezier::new([[0.0, 0.0], [10.0, 0.0], [-5.0, 0.0]]).expect("curve");
    run("doubles back", &back, &m, &o);
    // twice back and forth along x
    let twice = Bezier::new([[0.0, 0.0], [30.0, 0.0], [-10.0, 0.0], [20.0, 0.0]]).expect("c");
    run("back and forth", &twice, &m, &o);
    // the semicubical parabola (20(2t − 1)², 20(2t − 1)³): a cusp at t = ½
    let cusp = Bezier::new([
        [20.0, -20.0],
        [-20.0 / 3.0, 20.0],
        [-20.0 / 3.0, -20.0],
        [20.0, 20.0],
    ])
    .expect("cusp");
    run("semicubical cusp", &cusp, &m, &o);
    // 3-D: a B-spline of four pieces that turns back at an inner knot and inside a piece
    let pts = [
        [0.0, 0.0, 0.0],
        [20.0, 0.0, 0.0],
        [40.0, 5.0, 2.0],
        [20.0, 5.0, 2.0],
        [0.0, 5.0, 2.0],
        [0.0, 5.0, 2.0],
        [30.0, 10.0, 4.0],
    ];
    let spline = BSpline::<[f64; 3], 8, 16>::clamped_uniform(3, &pts, 0.0, 1.0).expect("b");
    let m3 = Limits::<3>::new(200.0, 2_000.0, 50_000.0).expect("limits");
    run("3-D B-spline with reversals", &spline, &m3, &o);
}

// ---------------------------------------------------------------------------------------------
// Extreme limits
// ---------------------------------------------------------------------------------------------

/// Jerk limits up to 10¹⁴ (jerk phases of picoseconds): the plan keeps every jerk phase at 16
/// ticks or more, and the samples keep the acceleration limit.
#[test]
fn extreme_jerk_limits_keep_the_limits() {
    let line = Bezier::new([[0.0, 0.0], [30.0, 40.0]]).expect("line");
    for j in [2e5, 1e6, 1e8, 1e10, 1e14] {
        for v in [20.0, 200.0] {
            for rate in [1_000.0, 10_000.0] {
                let m = Limits::<2>::new(v, 2_000.0, j).expect("limits");
                let o = PlanOptions::new().with_rate(rate);
                run(&format!("line v {v} j {j:e} at {rate} Hz"), &line, &m, &o);
            }
        }
    }
}

/// Limits whose motion no `u32` tick count can hold are rejected by the planner.
#[test]
fn limits_too_small_to_play_are_rejected() {
    let line = Bezier::new([[0.0, 0.0], [30.0, 40.0]]).expect("line");
    for (v, a, j) in [
        (1.5e-304, 2_000.0, 5e4),
        (1e-310, 2_000.0, 5e4),
        (100.0, 1e-300, 5e4),
        (100.0, 1_000.0, 1e-300),
    ] {
        let m = Limits::<2>::new(v, a, j).expect("limits");
        let r = PathTiming::<_, 16, 4>::scurve(&line, &m);
        assert!(
            matches!(r, Err(Error::TooLong)),
            "{v} {a} {j}: {:?}",
            r.err()
        );
    }
}

// ---------------------------------------------------------------------------------------------
// The feed reserve
// ---------------------------------------------------------------------------------------------

/// The README's 3-axis move.
fn readme_move() -> BSpline<[f64; 3], 8, 16> {
    let points = [
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 20.0],
        [50.0, 30.0, 20.0],
        [50.0, 30.0, 0.0],
    ];
    BSpline::clamped_uniform(3, &points, 0.0, 1.0).expect("readme")
}

/// Feed changes at every 10th tick of the motion, one per run: an override to ½, and a hold
/// with a resume 300 ticks later. Returns the worst ratios over all runs.
fn feed_changes<N: Kernel, const A: usize>(
    name: &str,
    path: &Path<N, A, PIECES>,
    m: &Limits<A>,
) -> Ratios {
    let mut worst = Ratios::default();
    let ticks = u64::from(path.ticks());
    for start in (0..ticks).step_by(10) {
        for kind in 0..2 {
            let (r, _) = play(path, m, |k, s| match (kind, k) {
                (0, k) if k == start => s.set_feed(0.5),
                (1, k) if k == start => s.hold(),
                (1, k) if k == start + 300 => s.resume(),
                _ => {}
            });
            worst.speed = worst.speed.max(r.speed);
            worst.acceleration = worst.acceleration.max(r.acceleration);
            worst.axis_acceleration = worst.axis_acceleration.max(r.axis_acceleration);
            worst.jerk = worst.jerk.max(r.jerk);
        }
    }
    println!(
        "{name}: feed changes: |v| {:.4} |a| {:.4} (axis {:.4}) |j| {:.4} of the limits",
        worst.speed, worst.acceleration, worst.axis_acceleration, worst.jerk
    );
    worst
}

/// Planned and compiled the library's way ([`PathTiming::plan`], [`PathTiming::compile`]),
/// feed override, hold and resume keep every limit, in every number format.
fn reserve_keeps_the_limits<N: Kernel>() {
    let m3 = Limits::<3>::new(200.0, 2_000.0, 50_000.0)
        .and_then(|l| l.with_axis_acceleration([1_500.0, f64::INFINITY, 1_000.0]))
        .expect("limits");
    let o = PlanOptions::new();
    let curve = readme_move();
    let plan: Plan<'_, _> = PathTiming::plan(&curve, &m3, &o).expect("plan");
    let path: Box<Path<N, 3, PIECES>> =
        compile_plan_boxed(&plan, &CompileOptions::new()).expect("compile");
    let r = feed_changes(&format!("README move {}", N::NAME), &path, &m3);
    assert!(
        r.speed <= 1.0 + velocity_allowance(&path) / m3.velocity(),
        "{r:?}"
    );
    assert!(r.acceleration <= 1.0 + ROUNDING, "{r:?}");
    assert!(r.axis_acceleration <= 1.0 + ROUNDING, "{r:?}");
    assert!(r.jerk <= 1.0 + ROUNDING, "{r:?}");
    let line = Bezier::new([[0.0, 0.0, 0.0], [100.0, 50.0, 20.0]]).expect("line");
    let plan: Plan<'_, _> = PathTiming::plan(&line, &m3, &o).expect("plan");
    let path: Box<Path<N, 3, PIECES>> =
        compile_plan_boxed(&plan, &CompileOptions::new()).expect("compile");
    let r = feed_changes(&format!("line at the limits {}", N::NAME), &path, &m3);
    assert!(r.acceleration <= 1.0 + ROUNDING, "{r:?}");
    assert!(r.axis_acceleration <= 1.0 + ROUNDING, "{r:?}");
    assert!(r.jerk <= 1.0 + ROUNDING, "{r:?}");
}

#[test]
fn feed_override_hold_and_resume_keep_the_limits() {
    reserve_keeps_the_limits::<f64>();
    reserve_keeps_the_limits::<f32>();
    reserve_keeps_the_limits::<strak_trajectory::Q40>();
}

/// A plan that leaves 0.1 % free cannot be compiled for the default share of ¼ (the plan's
/// own compile takes its share); and the measurement catches such a path where the law
/// hides its plan: a hold breaks the limits.
#[test]
fn a_plan_without_the_reserve_is_rejected_and_caught() {
    let m3 = Limits::<3>::new(200.0, 2_000.0, 50_000.0).expect("limits");
    let line = Bezier::new([[0.0, 0.0, 0.0], [100.0, 50.0, 20.0]]).expect("line");
    let o = PlanOptions::new().with_feed_share(1e-3);
    let plan: Plan<'_, _> = PathTiming::plan(&line, &m3, &o).expect("plan");
    let options = CompileOptions::new().with_path_limits(&m3);
    let r: Result<Box<Path<f64, 3, PIECES>>, _> = compile_boxed(&plan, plan.rate(), &options);
    assert_eq!(
        r.err(),
        Some(Error::FeedReserveExceeded {
            quantity: Quantity::Acceleration
        })
    );
    let own: Box<Path<f64, 3, PIECES>> =
        compile_plan_boxed(&plan, &CompileOptions::new()).expect("compile");
    assert_eq!(own.feed_share(), 1e-3);
    let r = feed_changes("line planned at the full limits", &own, &m3);
    assert!(
        r.acceleration <= 1.0 + ROUNDING && r.jerk <= 1.0 + ROUNDING,
        "{r:?}"
    );
    let hidden = Unpromised(&plan);
    let path: Box<Path<f64, 3, PIECES>> =
        compile_boxed(&Along::new(&line, &hidden), plan.rate(), &options).expect("compile");
    let r = feed_changes("line planned at the full limits, hidden", &path, &m3);
    assert!(r.acceleration > 1.01 || r.jerk > 1.01, "{r:?}");
}

// ---------------------------------------------------------------------------------------------
// Error texts
// ---------------------------------------------------------------------------------------------

/// The planner's errors name the quantity: zones (not pieces) for the plan's capacity, the
/// tick count for a plan too long to play, the rate for a rate out of range.
#[test]
fn planner_errors_name_the_quantity() {
    let arc = Bezier::new([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]]).expect("arc");
    let m = Limits::<2>::new(100.0, 10.0, 100.0).expect("limits");
    let o = PlanOptions::new()
        .with_zone_tolerance(0.0)
        .with_samples(100);
    let e = PathTiming::<_, 64, 8>::plan(&arc, &m, &o).expect_err("too many zones");
    let Error::ZoneCapacityExceeded { capacity, required } = e else {
        panic!("{e:?}");
    };
    assert_eq!(capacity, 8);
    assert!(required > 8);
    let text = e.to_string();
    println!("{text}");
    assert!(
        text.contains(&format!("{required} planning zones")),
        "{text}"
    );
    assert!(
        text.contains("holds 8") && text.contains("PathTiming<_, N, Z>"),
        "{text}"
    );
    assert!(!text.contains("pieces"), "{text}");
    // the compiler's capacity is in pieces
    let pieces = Error::CapacityExceeded {
        capacity: 3,
        required: 4,
    };
    assert!(pieces.to_string().contains("4 pieces"));
    let slow = Limits::<2>::new(1e-9, 10.0, 100.0).expect("limits");
    let e = PathTiming::<_, 64, 8>::scurve(&arc, &slow).expect_err("too long");
    assert_eq!(e, Error::TooLong);
    assert!(e.to_string().contains("ticks"), "{e}");
    let e = PathTiming::<_, 64, 8>::plan(&arc, &m, &PlanOptions::new().with_rate(50.0))
        .expect_err("rate");
    assert_eq!(e, Error::InvalidRate);
    assert!(e.to_string().contains("100 Hz and 100 kHz"), "{e}");
}
