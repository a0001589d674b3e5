//! Durations against closed forms written here from the textbook, through the planner and
//! through the compiled path.
//!
//! * Jerk-limited S-curve ("double S"), rest to rest, over a straight line of length `L` with
//!   limits `v`, `a`, `j` (Biagiotti & Melchiorri, *Trajectory Planning for Automatic
//!   Machines and Robots*, §3.4, with `v₀ = v₁ = 0`): accelerating from rest to a speed `w`
//!   (and braking back) takes
//!   `T_a(w) = w/a + a/j` if `w·j ≥ a²` (the acceleration limit is reached), else
//!   `T_a(w) = 2·√(w/j)`; it covers `w·T_a(w)` (mean speed `w/2` over `2·T_a`). Then
//!   1. `L ≥ v·T_a(v)`: the speed limit is reached (with or without reaching `a`, the two
//!      sub-cases of `T_a`): `T = L/v + T_a(v)`;
//!   2. `L < v·T_a(v)` and `L ≥ 2a³/j²`: the peak speed `w < v` still reaches `a`; `w` solves
//!      `w² + w·a²/j − a·L = 0`, `w = (−a²/j + √(a⁴/j² + 4aL))/2`, `T = 2·T_a(w)`;
//!   3. `L < 2a³/j²`: neither limit is reached: `w = (L·√j/2)^(2/3)`,
//!      `T = 4·(L/(2j))^(1/3)`.
//! * Trapezoid: `T = L/v + v/a` if `L ≥ v²/a`, else `T = 2·√(L/a)`.
//! * Constant speed: `T = L/v`. Parameter law: the duration given.
//!
//! Per-axis limits on a line with unit direction `d`: the speed limit is
//! `min(v, min_i vᵢ/|dᵢ|)`, the acceleration limit `min(a, min_i aᵢ/|dᵢ|)` (no curvature).
//!
//! The compiled path has `N = ⌈T·f⌉` ticks: `N/f ≥ T` and `N/f − T < 1/f`.
//!
//! [`PathTiming::plan`] plans with `1 − s` of the acceleration and jerk limits (`s` the feed
//! share, ¼ by default) and a jerk of at most `a·f/16` at its rate `f` ([`planned`]); the
//! closed forms are evaluated with those limits.

use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};
use strak_curves::Bezier;
use strak_trajectory::{
    Along, CompileOptions, Limits, MotionProfile, ParameterTiming, Path, PathTiming, PlanOptions,
    ProfileShape, Timing,
};
use strak_trajectory_tests::{Unpromised, compile_boxed};

/// The planner's durations must match within 0.1 % (the requirement); they are
/// computed by bisection to the last bits, so 10⁻⁹ is asserted as well.
const REQUIRED: f64 = 1e-3;
const ACHIEVED: f64 = 1e-9;

/// The path limits `(v, a, j)` a default [`PathTiming::plan`] plans with for the machine's
/// `(v, a, j)` on a line: `(1 − s)·a`, `(1 − s)·j` (the feed reserve), the jerk at most
/// `a·f/16` (jerk phases of at least [`PlanOptions::MIN_JERK_TICKS`] ticks at 1 kHz).
fn planned(v: f64, a: f64, j: f64) -> (f64, f64, f64) {
    let keep = 1.0 - PlanOptions::DEFAULT_FEED_SHARE;
    let (a, j) = (a * keep, j * keep);
    (
        v,
        a,
        j.min(a * PlanOptions::DEFAULT_RATE / PlanOptions::MIN_JERK_TICKS),
    )
}

/// The time-optimal rest-to-rest jerk-limited duration (see the module docs).
fn scurve_duration(l: f64, v: f64, a: f64, j: f64) -> f64 {
    let ramp = |w: f64| {
        if w * j >= a * a {
            w / a + a / j
        } else {
            2.0 * (w / j).sqrt()
        }
    };
    if l >= v * ramp(v) {
        l / v + ramp(v)
    } else if l >= 2.0 * a * a * a / (j * j) {
        let w = 0.5 * (-a * a / j + (a.powi(4) / (j * j) + 4.0 * a * l).sqrt());
        2.0 * ramp(w)
    } else {
        4.0 * (l / (2.0 * j)).cbrt()
    }
}

/// Which limits the S-curve reaches: (speed, acceleration).
fn scurve_regime(l: f64, v: f64, a: f64, j: f64) -> (bool, bool) {
    let ramp_v = if v * j >= a * a {
        v / a + a / j
    } else {
        2.0 * (v / j).sqrt()
    };
    if l >= v * ramp_v {
        (true, v * j >= a * a)
    } else {
        (false, l >= 2.0 * a * a * a / (j * j))
    }
}

fn trapezoid_duration(l: f64, v: f64, a: f64) -> f64 {
    if l >= v * v / a {
        l / v + v / a
    } else {
        2.0 * (l / a).sqrt()
    }
}

fn rel(x: f64, y: f64) -> f64 {
    (x - y).abs() / y
}

/// A straight line from `p` to `q` with uneven parametric speed (collinear cubic Bézier
/// points at 0, 0.05, 0.5 and 1 of the way): the planner must work along the arc length.
fn line(p: [f64; 3], q: [f64; 3]) -> Bezier<[f64; 3], 4> {
    let at = |s: f64| core::array::from_fn(|i| p[i] + s * (q[i] - p[i]));
    Bezier::new([at(0.0), at(0.05), at(0.5), at(1.0)]).expect("line")
}

fn length(p: [f64; 3], q: [f64; 3]) -> f64 {
    (0..3).map(|i| (q[i] - p[i]).powi(2)).sum::<f64>().sqrt()
}

/// Checks a compiled path's tick count against the plan's duration at `rate`.
fn check_ticks<T: Timing>(curve: &Bezier<[f64; 3], 4>, timing: &T, rate: f64) -> f64 {
    // long pieces: only the tick count matters here (65 s at 100 kHz)
    let options = CompileOptions::new().with_max_piece_ticks(1 << 20);
    let path: Box<Path<f64, 3, 4096>> =
        compile_boxed(&Along::new(curve, &Unpromised(timing)), rate, &options).expect("compile");
    let d = timing.duration();
    let compiled = f64::from(path.ticks()) / rate;
    assert_eq!(path.plan_duration(), d);
    assert_eq!(path.duration(), compiled);
    // ⌈d·f⌉ ticks (a duration that is a whole number of ticks up to 10⁻¹² is not stretched)
    assert!(
        compiled >= d * (1.0 - 1e-12),
        "{compiled} < {d} at {rate} Hz"
    );
    assert!(compiled - d < 1.0 / rate, "{compiled} vs {d} at {rate} Hz");
    assert!(path.time_scale() <= 1.0 + 1e-12);
    compiled
}

const RATES: [f64; 5] = [100.0, 1_000.0, 4_321.0, 20_000.0, 100_000.0];

// ---------------------------------------------------------------------------------------------
// S-curve
// ---------------------------------------------------------------------------------------------

/// (L, v, a, j) in each regime: which limits are reached.
const SCURVE_CASES: [(f64, f64, f64, f64, bool, bool); 6] = [
    // v and a reached: v·j ≥ a², L ≥ v·(v/a + a/j)
    (130.0, 10.0, 20.0, 100.0, true, true),
    // v reached, a not: v·j < a²
    (130.0, 2.0, 20.0, 100.0, true, false),
    // a reached, v not
    (1.3, 10.0, 20.0, 1_000.0, false, true),
    // neither
    (0.013, 10.0, 20.0, 100.0, false, false),
    // machine-like numbers (mm, s): v and a reached
    (130.0, 200.0, 2_000.0, 50_000.0, true, true),
    // exactly at the boundary of regimes 2 and 3: L = 2a³/j²
    (1.0, 10.0, 2.0, 4.0, false, true), // 2a³/j² = 2·8/16 = 1
];

#[test]
fn scurve_closed_form_regimes() {
    for (l, v, a, j, v_reached, a_reached) in SCURVE_CASES {
        assert_eq!(
            scurve_regime(l, v, a, j),
            (v_reached, a_reached),
            "{l} {v} {a} {j}"
        );
        let exact = scurve_duration(l, v, a, j);
        let m = MotionProfile::<1>::scurve(l, v, a, j).expect("profile");
        let r = rel(m.duration(), exact);
        println!(
            "S-curve L={l} v={v} a={a} j={j}: T = {:.9} closed form {exact:.9} (rel {r:.1e})",
            m.duration()
        );
        assert!(r < REQUIRED, "{r}");
        assert!(r < ACHIEVED, "{r}");
    }
}

/// Hand-computed values of the closed form (guards the formula itself).
#[test]
fn scurve_closed_form_hand_values() {
    // v and a reached: T = L/v + v/a + a/j = 13 + 0.5 + 0.2
    assert!((scurve_duration(130.0, 10.0, 20.0, 100.0) - 13.7).abs() < 1e-12);
    // v reached, a not (v·j = 200 < a² = 400): T = L/v + 2√(v/j) = 65 + 2·√0.02
    assert!(
        (scurve_duration(130.0, 2.0, 20.0, 100.0) - (65.0 + 2.0 * 0.02_f64.sqrt())).abs() < 1e-12
    );
    // neither: L = 4, j = 2: T = 4·(4/4)^(1/3) = 4
    assert!((scurve_duration(4.0, 100.0, 100.0, 2.0) - 4.0).abs() < 1e-12);
    // a reached, v not: a = 1, j = 1, L = 6: w² + w − 6 = 0, w = 2, T = 2·(2 + 1) = 6
    assert!((scurve_duration(6.0, 100.0, 1.0, 1.0) - 6.0).abs() < 1e-12);
    // continuity at the regime boundaries
    for (l, v, a, j) in [(1.0, 10.0, 2.0, 4.0), (1.0, 10.0, 1.0, 1.0)] {
        let (lo, hi) = (
            scurve_duration(l * (1.0 - 1e-9), v, a, j),
            scurve_duration(l * (1.0 + 1e-9), v, a, j),
        );
        assert!(rel(hi, lo) < 1e-8, "{lo} {hi}");
    }
}

#[test]
fn scurve_straight_line_through_planner_and_compiler() {
    let (p, q) = ([1.0, -2.0, 3.0], [31.0, 38.0, 123.0]); // length 130
    let curve = line(p, q);
    let l = length(p, q);
    assert!((l - 130.0).abs() < 1e-12);
    for (l_case, v, a, j, _, _) in SCURVE_CASES {
        // scale the limits so that this line of length 130 is in the same regime
        let s = l / l_case;
        let (v, a, j) = (v * s, a * s, j * s);
        let limits = Limits::<3>::new(v, a, j).expect("limits");
        let timing = PathTiming::<_, 64, 8>::scurve(&curve, &limits).expect("plan");
        assert_eq!(
            timing.motion().zones().len(),
            1,
            "a straight line is one zone"
        );
        let (v, a, j) = planned(v, a, j);
        let exact = scurve_duration(l, v, a, j);
        let r = rel(timing.duration(), exact);
        println!(
            "line S-curve v={v:.3} a={a:.3} j={j:.3}: T = {:.9}, closed form {exact:.9} (rel {r:.1e})",
            timing.duration()
        );
        assert!(r < REQUIRED, "{r}");
        assert!(r < ACHIEVED, "{r}");
        for rate in RATES {
            let compiled = check_ticks(&curve, &timing, rate);
            assert!(compiled >= exact * (1.0 - ACHIEVED));
            assert!(compiled < exact * (1.0 + ACHIEVED) + 1.0 / rate);
        }
    }
}

/// Per-axis limits on a line: the planner's duration is the closed form with the effective
/// limits `min(v, vᵢ/|dᵢ|)` and `min(a, aᵢ/|dᵢ|)`.
#[test]
fn scurve_line_with_axis_limits() {
    let (p, q) = ([0.0, 0.0, 0.0], [30.0, 40.0, 120.0]); // direction (3, 4, 12)/13
    let curve = line(p, q);
    let d = [3.0 / 13.0, 4.0 / 13.0, 12.0 / 13.0];
    let limits = Limits::<3>::new(200.0, 2_000.0, 50_000.0)
        .and_then(|l| l.with_axis_velocity([1e9, 1e9, 60.0]))
        .and_then(|l| l.with_axis_acceleration([1e9, 200.0, 1e9]))
        .expect("limits");
    let v = 200.0_f64.min(60.0 / d[2]);
    let a = 2_000.0_f64.min(200.0 / d[1]);
    let (v, a, j) = planned(v, a, 50_000.0);
    let exact = scurve_duration(130.0, v, a, j);
    let timing = PathTiming::<_, 64, 8>::scurve(&curve, &limits).expect("plan");
    let r = rel(timing.duration(), exact);
    println!(
        "line with axis limits: v {v}, a {a}: T = {:.9}, closed form {exact:.9} (rel {r:.1e})",
        timing.duration()
    );
    assert!(r < REQUIRED, "{r}");
    assert!(r < 1e-6, "{r}");
    for rate in RATES {
        check_ticks(&curve, &timing, rate);
    }
}

#[test]
fn scurve_random_lines_match_the_closed_form() {
    let mut runner = TestRunner::new(Config {
        cases: 512,
        failure_persistence: None,
        ..Config::default()
    });
    // log-uniform magnitudes over several decades
    let e = |lo: f64, hi: f64| (lo..hi).prop_map(|x: f64| 10f64.powf(x));
    let strategy = (
        prop::array::uniform3(-100.0_f64..100.0),
        prop::array::uniform3(-100.0_f64..100.0),
        e(-1.0, 3.0),
        e(0.0, 4.0),
        e(1.0, 6.0),
    );
    runner
        .run(&strategy, |(p, q, v, a, j)| {
            let l = length(p, q);
            prop_assume!(l > 1e-3);
            let curve = line(p, q);
            let limits = Limits::<3>::new(v, a, j).expect("limits");
            let timing = PathTiming::<_, 64, 8>::scurve(&curve, &limits).expect("plan");
            let (pv, pa, pj) = planned(v, a, j);
            let exact = scurve_duration(l, pv, pa, pj);
            let r = rel(timing.duration(), exact);
            prop_assert!(
                r < REQUIRED,
                "L {} v {} a {} j {}: {} vs {} (rel {})",
                l,
                v,
                a,
                j,
                timing.duration(),
                exact,
                r
            );
            prop_assert!(r < 1e-8, "rel {}", r);
            let m = MotionProfile::<1>::scurve(l, v, a, j).expect("profile");
            prop_assert!(rel(m.duration(), scurve_duration(l, v, a, j)) < ACHIEVED);
            Ok(())
        })
        .expect("random lines");
}

// ---------------------------------------------------------------------------------------------
// Trapezoid, constant speed, parameter law
// ---------------------------------------------------------------------------------------------

#[test]
fn trapezoid_closed_form() {
    let (p, q) = ([1.0, -2.0, 3.0], [31.0, 38.0, 123.0]); // length 130
    let curve = line(p, q);
    let l = 130.0;
    for (v, a) in [
        (10.0, 20.0),         // cruise: L ≥ v²/a
        (100.0, 20.0),        // triangle: L < v²/a = 500
        (50.0, 500.0 / 26.0), // exactly L = v²/a
        (200.0, 2_000.0),
    ] {
        let exact = trapezoid_duration(l, v, a);
        let m = MotionProfile::<1>::trapezoid(l, v, a).expect("profile");
        assert!(
            rel(m.duration(), exact) < ACHIEVED,
            "{} vs {exact}",
            m.duration()
        );
        let timing = PathTiming::<_, 64, 8>::trapezoid(&curve, v, a).expect("plan");
        let r = rel(timing.duration(), exact);
        println!(
            "trapezoid v={v} a={a:.4}: T = {:.9}, closed form {exact:.9} (rel {r:.1e})",
            timing.duration()
        );
        assert!(r < REQUIRED, "{r}");
        assert!(r < ACHIEVED, "{r}");
        // the planner with a trapezoid shape and global limits only: the same
        let limits = Limits::<3>::new(v, a, 1.0).expect("limits");
        let options = PlanOptions::new().with_shape(ProfileShape::Trapezoid);
        let plan = PathTiming::<_, 64, 8>::plan(&curve, &limits, &options).expect("plan");
        let (_, a_planned, _) = planned(v, a, 1.0);
        let exact_planned = trapezoid_duration(l, v, a_planned);
        assert!(rel(plan.duration(), exact_planned) < ACHIEVED);
        for rate in RATES {
            check_ticks(&curve, &timing, rate);
        }
    }
}

#[test]
fn constant_speed_duration_is_length_over_speed() {
    let (p, q) = ([0.0, 0.0, 0.0], [30.0, 40.0, 120.0]);
    let curve = line(p, q);
    for v in [0.5, 13.0, 130.0, 2_600.0] {
        let timing = PathTiming::<_, 64, 1>::constant_speed(&curve, v).expect("plan");
        let exact = 130.0 / v;
        let r = rel(timing.duration(), exact);
        assert!(r < REQUIRED, "v {v}: {} vs {exact}", timing.duration());
        assert!(r < ACHIEVED, "v {v}: {} vs {exact}", timing.duration());
        assert_eq!(
            MotionProfile::<1>::constant_speed(130.0, v)
                .expect("profile")
                .duration(),
            exact
        );
        for rate in RATES {
            check_ticks(&curve, &timing, rate);
        }
    }
}

#[test]
fn parameter_law_duration_and_ticks() {
    let curve = line([0.0; 3], [30.0, 40.0, 120.0]);
    for d in [0.01, 0.3, 1.0, 2.5e-3] {
        let timing = ParameterTiming::over(&curve, d).expect("law");
        assert_eq!(timing.duration(), d);
        for rate in RATES {
            let compiled = check_ticks(&curve, &timing, rate);
            // ⌈d·f⌉ ticks
            let ticks = (compiled * rate).round();
            assert_eq!(
                ticks,
                (d * rate * (1.0 - 1e-12)).ceil().max(1.0),
                "{d} s at {rate} Hz"
            );
        }
    }
    // the domain at a rate: duration = (u_end − u_start)/rate
    let timing = ParameterTiming::at_rate(&curve, 4.0).expect("law");
    assert_eq!(timing.duration(), 0.25);
}
