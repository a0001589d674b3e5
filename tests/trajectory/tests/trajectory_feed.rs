//! End to end feed override, feed hold, resume and abort (plan → compile → sample), in every
//! number format, checked from the samples:
//!
//! * no position jump: `|Δx| ≤ v_max·T` per tick (path), `|Δxᵢ| ≤ vᵢ·T·(1 + fit)` per axis;
//! * the acceleration from velocity differences `(v_{k+1} − v_k)/T` within the machine's
//!   path acceleration limit, tangential and centripetal (and the vector norm, which the
//!   feed ramps are designed against: `a_peak + a_ramp ≤ a_max`), and per axis within its
//!   own limit (the ramps take what each axis leaves free, [`CompileOptions::with_path_limits`]);
//! * the jerk from acceleration differences within the machine's jerk limit;
//! * the same path: every sample lies on the exact `f64` composition `c(u(t))` at the
//!   sampler's playback point ([`Sampler::progress`]) within the compile tolerance plus the
//!   format's error;
//! * the exact end point, bit for bit; hold stands still bit for bit; abort stops and stays;
//!   [`Sampler::is_finished`] turns true exactly with the last sample.
//!
//! The motion is the pick-and-place S-curve planned with the accelerations and jerk reduced
//! by the feed share (¼) and compiled with the machine's limits at 1 kHz, so the feed ramps
//! may use the reserved share.
//!
//! # Tolerances
//!
//! * Acceleration: the ramps keep `φ²·|a| + |φ̇|·|v| ≤ a_peak + a_ramp = a_max` exactly in
//!   continuous time; a difference quotient is the mean over one tick (never above the
//!   largest value). The feed factor changes once per tick, so the sampled velocity
//!   `φ·p'(τ)/T` steps with `φ`; the quotient sees `φ̇` a tick early or late, within the
//!   ramp's jerk: `j·T` ([`ramp_slack`]); per axis the same over the tightest axis limit.
//! * Jerk: [`JERK_SLACK`], the rounding of the reported accelerations.
//! * Same path: `tolerance + 2·playback_bound + 16·ε·max|x|` — the compile tolerance, the
//!   forward-differencing error (doubled: after an override the loads are shifted by a
//!   fraction of a tick, which rounds each state once more), and the rounding of Newton's
//!   formula at a fractional tick (three products and three sums, ε the format's epsilon;
//!   2⁻⁴⁰ for `Q40`).

#![allow(clippy::needless_range_loop)] // axis loops index several arrays at once

use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};
use strak_curves::{BSpline, ParamCurve, Scalar};
use strak_trajectory::{
    Along, CompileOptions, Error, Kernel, Limits, Path, PathTiming, PlanOptions, Q40, Quantity,
    Sample, Sampler, SamplerState, Timing,
};
use strak_trajectory_tests::compile_boxed;

const RATE: f64 = 1_000.0;
const PIECES: usize = 1024;

type Curve = BSpline<[f64; 3], 8, 12>;
type Plan<'a> = PathTiming<'a, Curve, 256, 128>;

fn pick_and_place() -> Curve {
    let d = [
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 30.0],
        [0.0, 0.0, 60.0],
        [60.0, 30.0, 60.0],
        [120.0, 60.0, 60.0],
        [180.0, 90.0, 60.0],
        [180.0, 90.0, 30.0],
        [180.0, 90.0, 0.0],
    ];
    BSpline::clamped_uniform(3, &d, 0.0, 1.0).expect("pick and place")
}

/// The machine's limits.
fn machine() -> Limits<3> {
    Limits::new(200.0, 2_000.0, 50_000.0)
        .and_then(|l| l.with_axis_velocity([150.0, 150.0, 100.0]))
        .and_then(|l| l.with_axis_acceleration([1_500.0, 1_500.0, 1_000.0]))
        .expect("limits")
}

/// The S-curve under the machine's limits, less the feed share that [`PathTiming::scurve`]
/// reserves.
fn plan(curve: &Curve) -> Plan<'_> {
    PathTiming::scurve(curve, &machine()).expect("plan")
}

/// The path, compiled in place on the heap ([`compile_boxed`]).
fn compile_path<N: Kernel>(curve: &Curve, plan: &Plan<'_>) -> Box<Path<N, 3, PIECES>> {
    let options = CompileOptions::new().with_path_limits(&machine());
    compile_boxed(&Along::new(curve, plan), RATE, &options).expect("compile")
}

fn norm(x: &[f64; 3]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>().sqrt()
}

fn dot(x: &[f64; 3], y: &[f64; 3]) -> f64 {
    x.iter().zip(y).map(|(a, b)| a * b).sum()
}

fn f64s<T: Scalar>(x: [T; 3]) -> [f64; 3] {
    x.map(Scalar::to_f64)
}

/// How far a difference quotient of the velocity may be off the continuous-time
/// acceleration while the feed ramps: one tick of the ramp's jerk.
fn ramp_slack<N: Kernel, const P: usize>(path: &Path<N, 3, P>) -> f64 {
    path.jerk_limit() * path.period()
}

/// The smallest of `limits`.
fn tightest(limits: &[f64; 3]) -> f64 {
    limits.iter().fold(f64::INFINITY, |m, &l| m.min(l))
}

/// How far the jerk from acceleration differences may exceed the machine's jerk, relative:
/// the rounding of the reported accelerations, whose differences are divided by `T` (in
/// `f32`, `2·ε·|a|/T` is about 10⁻⁵ of `j` here).
const JERK_SLACK: f64 = 1e-4;

/// Largest values seen during a run, from the samples.
#[derive(Debug, Clone, Copy)]
struct Seen {
    /// The limits the ratios are taken to.
    machine: Limits<3>,
    /// `|Δx|/T` per tick, largest, path and per axis (ratios to the limits).
    speed: f64,
    axis_speed: f64,
    /// Acceleration from velocity differences: vector, tangential, centripetal, per axis
    /// (ratios to the machine's limits).
    accel: f64,
    tangential: f64,
    centripetal: f64,
    axis_accel: f64,
    /// Jerk from acceleration differences (ratio to the machine's jerk).
    jerk: f64,
    /// Distance from the exact composition at the playback point, and its bound.
    off_path: f64,
    off_path_bound: f64,
    ticks: u64,
}

/// Plays `path` to the end (or `max_ticks`), calling `control(k, sampler)` before each
/// sample; checks every sample; returns what it saw and the last sample.
fn run<N: Kernel>(
    curve: &Curve,
    plan: &Plan<'_>,
    path: &Path<N, 3, PIECES>,
    m: &Limits<3>,
    max_ticks: u64,
    mut control: impl FnMut(u64, &mut Sampler<'_, N, 3>),
) -> (Seen, Option<Sample<N::Out, 3>>, SamplerState) {
    let t = path.period();
    let eps = if N::IS_FIXED {
        N::MIN_POSITIVE
    } else {
        N::EPSILON.to_f64()
    };
    let off_bound = path.tolerance() + 2.0 * path.playback_bound() + 16.0 * eps * 200.0;
    let mut seen = Seen {
        machine: *m,
        speed: 0.0,
        axis_speed: 0.0,
        accel: 0.0,
        tangential: 0.0,
        centripetal: 0.0,
        axis_accel: 0.0,
        jerk: 0.0,
        off_path: 0.0,
        off_path_bound: off_bound,
        ticks: 0,
    };
    let mut sampler = Sampler::new(path);
    let mut prev: Option<([f64; 3], [f64; 3], [f64; 3])> = None;
    let mut last = None;
    let mut k = 0_u64;
    while !sampler.is_finished() && k < max_ticks {
        control(k, &mut sampler);
        let at = sampler.progress();
        let s = sampler.next();
        assert_eq!(s.tick, k);
        let (x, v, a) = (f64s(s.position), f64s(s.velocity), f64s(s.acceleration));
        // on the path: the exact composition at the playback point
        let tick = at.min(f64::from(path.ticks()));
        let plan_t = if tick >= f64::from(path.ticks()) {
            plan.duration()
        } else {
            path.plan_time(tick)
        };
        let exact = curve.eval(plan.param(plan_t).0);
        for i in 0..3 {
            seen.off_path = seen.off_path.max((x[i] - exact[i]).abs());
        }
        if let Some((px, pv, pa)) = prev {
            let dx: [f64; 3] = core::array::from_fn(|i| (x[i] - px[i]) / t);
            seen.speed = seen.speed.max(norm(&dx) / m.velocity());
            for i in 0..3 {
                seen.axis_speed = seen.axis_speed.max(dx[i].abs() / m.axis_velocity()[i]);
            }
            let afd: [f64; 3] = core::array::from_fn(|i| (v[i] - pv[i]) / t);
            seen.accel = seen.accel.max(norm(&afd) / m.acceleration());
            for i in 0..3 {
                seen.axis_accel = seen.axis_accel.max(afd[i].abs() / m.axis_acceleration()[i]);
            }
            let mid: [f64; 3] = core::array::from_fn(|i| 0.5 * (v[i] + pv[i]));
            let sp = norm(&mid);
            if sp > 0.2 {
                let tan = dot(&afd, &mid) / sp;
                let n: [f64; 3] = core::array::from_fn(|i| afd[i] - tan * mid[i] / sp);
                seen.tangential = seen.tangential.max(tan.abs() / m.acceleration());
                seen.centripetal = seen.centripetal.max(norm(&n) / m.acceleration());
            }
            let jfd: [f64; 3] = core::array::from_fn(|i| (a[i] - pa[i]) / t);
            seen.jerk = seen.jerk.max(norm(&jfd) / m.jerk());
        }
        prev = Some((x, v, a));
        last = Some(s);
        k += 1;
    }
    seen.ticks = k;
    (seen, last, sampler.state())
}

/// The checks every feed run must pass.
fn assert_seen<N: Kernel>(name: &str, seen: &Seen, path: &Path<N, 3, PIECES>) {
    println!(
        "{name} {:>3}: {} ticks; |Δx|/T {:.4} (axis {:.4}) of v; |Δv|/T {:.4} (tangential {:.4}, \
         centripetal {:.4}, axis {:.4}) of a; |Δa|/T {:.4} of j; off the path {:.2e} (bound {:.2e})",
        N::NAME,
        seen.ticks,
        seen.speed,
        seen.axis_speed,
        seen.accel,
        seen.tangential,
        seen.centripetal,
        seen.axis_accel,
        seen.jerk,
        seen.off_path,
        seen.off_path_bound,
    );
    let slack = ramp_slack(path) / seen.machine.acceleration();
    assert!(seen.speed <= 1.0, "{name}: position jump {}", seen.speed);
    assert!(
        seen.axis_speed <= 1.01,
        "{name}: axis position jump {}",
        seen.axis_speed
    );
    assert!(
        seen.accel <= 1.0 + slack,
        "{name}: acceleration {}",
        seen.accel
    );
    assert!(
        seen.tangential <= 1.0 + slack,
        "{name}: tangential {}",
        seen.tangential
    );
    assert!(
        seen.centripetal <= 1.0 + slack,
        "{name}: centripetal {}",
        seen.centripetal
    );
    let axis_slack = ramp_slack(path) / tightest(&seen.machine.axis_acceleration());
    assert!(
        seen.axis_accel <= 1.0 + axis_slack,
        "{name}: axis acceleration {}",
        seen.axis_accel
    );
    assert!(seen.jerk <= 1.0 + JERK_SLACK, "{name}: jerk {}", seen.jerk);
    assert!(
        seen.off_path <= seen.off_path_bound,
        "{name}: {} off the path",
        seen.off_path
    );
}

// ---------------------------------------------------------------------------------------------
// Override at fixed ticks
// ---------------------------------------------------------------------------------------------

fn override_steps<N: Kernel>() {
    let curve = pick_and_place();
    let plan = plan(&curve);
    let path = compile_path::<N>(&curve, &plan);
    let nominal = u64::from(path.ticks());
    let (seen, last, state) = run(
        &curve,
        &plan,
        &path,
        &machine(),
        100 * nominal,
        |k, s| match k {
            300 => s.set_feed(0.5),
            800 => s.set_feed(0.1),
            1500 => s.set_feed(1.0),
            _ => {}
        },
    );
    assert_seen("override 0.5, 0.1, 1", &seen, &path);
    assert_eq!(state, SamplerState::Finished);
    let last = last.expect("samples");
    assert_eq!(last.position, path.end_position(), "exact end");
    assert_eq!(last.velocity, [N::Out::ZERO; 3]);
    // slower than at full feed
    assert!(seen.ticks > nominal + 400, "{} vs {nominal}", seen.ticks);
}

#[test]
fn override_at_fixed_ticks() {
    override_steps::<f32>();
    override_steps::<f64>();
    override_steps::<Q40>();
}

/// At feed 0.1, once the ramp has settled, the speed is a tenth of the full-feed speed at
/// the same place on the path.
fn override_scales_the_speed<N: Kernel>() {
    let curve = pick_and_place();
    let plan = plan(&curve);
    let path = compile_path::<N>(&curve, &plan);
    let mut sampler = Sampler::new(&*path);
    for _ in 0..800 {
        sampler.next();
    }
    sampler.set_feed(0.1);
    let mut ramp = 0;
    while sampler.feed() != 0.1_f32 as f64 && ramp < 1_000 {
        sampler.next();
        ramp += 1;
    }
    assert_eq!(sampler.feed(), 0.1_f32 as f64, "settled after {ramp} ticks");
    let at = sampler.progress();
    let s = sampler.next();
    let full = path.eval(at);
    let (v, vf) = (norm(&f64s(s.velocity)), norm(&full.velocity));
    println!("{}: speed {v:.4} at feed 0.1, {vf:.4} at feed 1", N::NAME);
    assert!((v / vf - 0.1).abs() < 1e-4, "{v} vs {vf}");
}

#[test]
fn override_scales_the_speed_in_every_format() {
    override_scales_the_speed::<f32>();
    override_scales_the_speed::<f64>();
    override_scales_the_speed::<Q40>();
}

// ---------------------------------------------------------------------------------------------
// Override changing every tick (proptest)
// ---------------------------------------------------------------------------------------------

fn random_feeds<N: Kernel>(feeds: &[f32], events: &[(u16, u8)]) -> Result<(), TestCaseError> {
    let curve = pick_and_place();
    let plan = plan(&curve);
    let path = compile_path::<N>(&curve, &plan);
    let nominal = u64::from(path.ticks());
    // after the sequence and the events: resume, full feed, and run to the end
    let end_of_sequence = 3_000;
    let (seen, last, state) = run(
        &curve,
        &plan,
        &path,
        &machine(),
        100 * nominal + 10_000,
        |k, s| {
            if let Some(&feed) = feeds.get(k as usize) {
                s.set_feed(feed);
            }
            for &(tick, what) in events {
                if u64::from(tick) == k {
                    match what {
                        0 => s.hold(),
                        1 => s.resume(),
                        _ => s.set_feed(0.0),
                    }
                }
            }
            if k == end_of_sequence {
                s.set_feed(1.0);
                s.resume();
            }
        },
    );
    assert_seen("random feed", &seen, &path);
    prop_assert_eq!(state, SamplerState::Finished);
    let last = last.expect("samples");
    prop_assert_eq!(last.position, path.end_position());
    Ok(())
}

#[test]
fn override_every_tick_random() {
    let mut runner = TestRunner::new(Config {
        cases: 24,
        failure_persistence: None,
        ..Config::default()
    });
    let strategy = (
        prop::collection::vec(0.0_f32..=1.0, 0..3000),
        prop::collection::vec((0_u16..3_000, 0_u8..3), 0..4),
        0_u8..3,
    );
    runner
        .run(&strategy, |(feeds, events, format)| match format {
            0 => random_feeds::<f32>(&feeds, &events),
            1 => random_feeds::<f64>(&feeds, &events),
            _ => random_feeds::<Q40>(&feeds, &events),
        })
        .expect("random feed sequences");
}

// ---------------------------------------------------------------------------------------------
// Hold, resume, abort, finished
// ---------------------------------------------------------------------------------------------

fn hold_and_resume<N: Kernel>() {
    let curve = pick_and_place();
    let plan = plan(&curve);
    let path = compile_path::<N>(&curve, &plan);
    let mut held: Vec<Sample<N::Out, 3>> = Vec::new();
    let mut resumed_at = None;
    let (seen, last, state) = run(&curve, &plan, &path, &machine(), 100_000, |k, s| {
        if k == 1000 {
            s.hold();
            assert_eq!(s.state(), SamplerState::Holding);
            s.hold(); // idempotent
            assert_eq!(s.state(), SamplerState::Holding);
        }
        if k > 1000 && resumed_at.is_none() && s.feed() == 0.0 {
            // standing: record what it delivers
            held.push(s.clone().next());
            if held.len() == 2000 {
                s.resume();
                assert_eq!(s.state(), SamplerState::Running);
                resumed_at = Some(k);
            }
        }
        if k < 1000 || resumed_at.is_none() {
            assert!(!s.is_finished());
        }
    });
    assert_seen("hold, resume", &seen, &path);
    assert!(resumed_at.is_some(), "the hold came to a standstill");
    // standing still bit for bit, with zero velocity and acceleration (the first sample at
    // φ = 0 still carries the landing step's rate φ̇ in its acceleration, which falls to 0
    // over two ticks)
    let first = held[0];
    for (i, h) in held.iter().enumerate() {
        assert_eq!(h.position, first.position);
        assert_eq!(h.velocity, [N::Out::ZERO; 3]);
        if i > 0 {
            assert_eq!(h.acceleration, [N::Out::ZERO; 3]);
        }
    }
    assert_eq!(state, SamplerState::Finished);
    let last = last.expect("samples");
    assert_eq!(
        last.position,
        path.end_position(),
        "exact end after the resume"
    );
    assert!(seen.ticks > u64::from(path.ticks()) + 2000);
}

#[test]
fn hold_stands_still_and_resume_reaches_the_exact_end() {
    hold_and_resume::<f32>();
    hold_and_resume::<f64>();
    hold_and_resume::<Q40>();
}

fn abort_stops<N: Kernel>() {
    let curve = pick_and_place();
    let plan = plan(&curve);
    let path = compile_path::<N>(&curve, &plan);
    let mut aborted_at = 0.0;
    let (seen, last, state) = run(&curve, &plan, &path, &machine(), 100_000, |k, s| {
        if k == 1200 {
            aborted_at = s.progress();
            s.abort();
            assert_eq!(s.state(), SamplerState::Aborting);
            s.resume(); // ignored
            s.hold(); // ignored
            s.set_feed(1.0); // stored, but the abort goes on
            assert_eq!(s.state(), SamplerState::Aborting);
        }
    });
    assert_seen("abort", &seen, &path);
    assert_eq!(state, SamplerState::Finished);
    assert!(
        seen.ticks < u64::from(path.ticks()),
        "stopped before the end"
    );
    let last = last.expect("samples");
    assert_ne!(last.position, path.end_position());
    // stays put: replay and look past the stop
    let mut s = Sampler::new(&*path);
    let mut stop = None;
    for k in 0..seen.ticks + 50 {
        if k == 1200 {
            s.abort();
        }
        let smp = s.next();
        if k + 1 == seen.ticks {
            assert_eq!(smp.position, last.position);
            assert!(s.is_finished());
            stop = Some(s.progress());
        }
        if k >= seen.ticks {
            assert_eq!(smp.position, last.position);
            assert_eq!(smp.velocity, [N::Out::ZERO; 3]);
            assert_eq!(smp.acceleration, [N::Out::ZERO; 3]);
            assert_eq!(s.state(), SamplerState::Finished);
        }
    }
    let stop = stop.expect("stop");
    println!(
        "{}: aborted at tick {aborted_at:.1}, stopped at {stop:.1}",
        N::NAME
    );
    assert!(stop > aborted_at && stop < f64::from(path.ticks()));
    // nothing restarts a finished sampler
    s.resume();
    s.set_feed(1.0);
    assert_eq!(s.next().position, last.position);
    assert!(s.is_finished());
}

#[test]
fn abort_stops_within_the_limits_and_stays_put() {
    abort_stops::<f32>();
    abort_stops::<f64>();
    abort_stops::<Q40>();
}

/// `is_finished` becomes true exactly when the end sample (tick `ticks()`) has been returned;
/// afterwards every call repeats the end point at rest, and hold, resume and abort change
/// nothing.
fn finished_semantics<N: Kernel>() {
    let curve = pick_and_place();
    let plan = plan(&curve);
    let path = compile_path::<N>(&curve, &plan);
    let mut s = Sampler::new(&*path);
    assert!(!s.is_finished());
    assert_eq!(s.state(), SamplerState::Running);
    for k in 0..path.ticks() {
        let smp = s.next();
        assert_eq!(smp.tick, u64::from(k));
        assert!(!s.is_finished(), "finished early at tick {k}");
    }
    let end = s.next();
    assert_eq!(end.tick, u64::from(path.ticks()));
    assert!(s.is_finished());
    assert_eq!(s.state(), SamplerState::Finished);
    assert_eq!(end.position, path.end_position());
    s.hold();
    s.abort();
    s.resume();
    s.set_feed(0.3);
    for k in 1..=10 {
        let after = s.next();
        assert_eq!(after.tick, u64::from(path.ticks()) + k);
        assert_eq!(after.position, end.position);
        assert_eq!(after.velocity, [N::Out::ZERO; 3]);
        assert_eq!(after.acceleration, [N::Out::ZERO; 3]);
        assert_eq!(s.state(), SamplerState::Finished);
    }
}

#[test]
fn finished_exactly_after_the_end_sample() {
    finished_semantics::<f32>();
    finished_semantics::<f64>();
    finished_semantics::<Q40>();
}

/// A hold never finishes by itself, and zero feed from the start stands still near the
/// start: it moves during the ramp down, but (at a feed factor `≤ 1`) never further than the
/// motion at full feed moves in as many ticks.
fn zero_feed_from_the_start<N: Kernel>() {
    let curve = pick_and_place();
    let plan = plan(&curve);
    let path = compile_path::<N>(&curve, &plan);
    let mut s = Sampler::new(&*path);
    s.hold();
    let mut last = s.next();
    let mut ramp = 1_u32;
    while s.feed() != 0.0 && ramp < 20_000 {
        last = s.next();
        ramp += 1;
    }
    for _ in 0..20_000 {
        last = s.next();
    }
    assert!(!s.is_finished());
    assert_eq!(s.state(), SamplerState::Holding);
    assert_eq!(last.velocity, [N::Out::ZERO; 3]);
    let again = s.next();
    assert_eq!(again.position, last.position);
    let d = norm(&f64s(last.position));
    let full = norm(&f64s(path.eval(f64::from(ramp)).position));
    println!(
        "{}: stopped {d:.4} mm from the start after {ramp} ticks (full feed: {full:.4} mm)",
        N::NAME
    );
    assert!(d < full, "{d} vs {full}");
    s.resume();
    let mut k = 0;
    while !s.is_finished() {
        last = s.next();
        k += 1;
        assert!(k < 100_000);
    }
    assert_eq!(last.position, path.end_position());
}

#[test]
fn hold_from_the_start_then_resume() {
    zero_feed_from_the_start::<f32>();
    zero_feed_from_the_start::<f64>();
    zero_feed_from_the_start::<Q40>();
}

/// The end point of a run with overrides is bit for bit the one at full feed.
#[test]
fn end_is_exact_with_an_override_until_the_end() {
    let curve = pick_and_place();
    let plan = plan(&curve);
    let path = compile_path::<Q40>(&curve, &plan);
    let (_, last, _) = run(&curve, &plan, &path, &machine(), 1_000_000, |k, s| {
        if k == 5 {
            s.set_feed(0.37);
        }
    });
    assert_eq!(last.expect("samples").position, path.end_position());
    let end = curve.eval(curve.domain().1);
    assert_eq!(
        path.end_position(),
        end.map(strak_curves::I32F32::from_num),
        "the Q40 end point is the f64 end rounded to I32F32"
    );
}

// ---------------------------------------------------------------------------------------------
// Feed ramps keep the axis limits
// ---------------------------------------------------------------------------------------------

/// A feed ramp adds `φ̇·ẋᵢ` to each axis, so what it may add is bounded by each axis's
/// free part: given the machine's limits ([`CompileOptions::with_path_limits`]), or derived
/// without them from the plan (at most the tightest `aᵢ/(1 − share)` the law promises).
/// Two cases:
///
/// * a vertical lift on a machine whose z axis takes a tenth of the path's acceleration
///   (200 against 2 000): a ramp at the path's limit gives z several times its own;
/// * the pick-and-place on [`machine`], whose path peak comes from the travel in x and y,
///   where z stands still (derived from that peak alone, the limit would be 1 212 against
///   z's 1 000).
///
/// Held at every 40th tick of the first 800 and resumed once at rest (a late hold may reach
/// the end first; at least five come to rest), every run passes [`assert_seen`],
/// which checks each axis's acceleration from the samples.
fn feed_ramps_keep_the_axis_limits<N: Kernel>(
    curve: &Curve,
    m: &Limits<3>,
    options: &CompileOptions,
    what: &str,
) {
    let plan: Plan<'_> = PathTiming::scurve(curve, m).expect("plan");
    let path: Box<Path<N, 3, PIECES>> =
        compile_boxed(&Along::new(curve, &plan), RATE, options).expect("compile");
    let mut rested = 0;
    for hold in (40..800).step_by(40) {
        let mut resume = None;
        let (seen, last, _) = run(curve, &plan, &path, m, 100_000, |k, s| {
            if k == hold {
                s.hold();
            }
            if k > hold && resume.is_none() && s.feed() == 0.0 {
                s.resume();
                resume = Some(k);
            }
        });
        rested += usize::from(resume.is_some());
        assert_seen(&format!("{what}, held at {hold}"), &seen, &path);
        assert_eq!(last.map(|s| s.position), Some(path.end_position()));
    }
    assert!(rested >= 5, "{what}: {rested} holds came to rest");
}

#[test]
fn feed_ramps_keep_the_axis_limits_given_or_derived() {
    let lift_machine = Limits::new(200.0, 2_000.0, 50_000.0)
        .and_then(|l| l.with_axis_velocity([f64::INFINITY, f64::INFINITY, 100.0]))
        .and_then(|l| l.with_axis_acceleration([f64::INFINITY, f64::INFINITY, 200.0]))
        .expect("limits");
    let lift = BSpline::clamped_uniform(1, &[[0.0, 0.0, 0.0], [0.0, 0.0, 100.0]], 0.0, 1.0)
        .expect("a vertical line");
    let cases = [
        (lift, lift_machine, "lift"),
        (pick_and_place(), machine(), "pick and place"),
    ];
    for (curve, m, name) in &cases {
        let given = CompileOptions::new().with_path_limits(m);
        for (options, limits) in [(given, "given"), (CompileOptions::new(), "derived")] {
            let what = format!("{name}, {limits} limits");
            feed_ramps_keep_the_axis_limits::<f32>(curve, m, &options, &what);
            feed_ramps_keep_the_axis_limits::<f64>(curve, m, &options, &what);
            feed_ramps_keep_the_axis_limits::<Q40>(curve, m, &options, &what);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The compile asks no more than the plan left free
// ---------------------------------------------------------------------------------------------

/// A 100 mm line in the xy plane, S-curve planned on [`machine`] with `plan_share` of the
/// acceleration and jerk left free.
fn line_plan(curve: &Curve, plan_share: f64) -> Plan<'_> {
    let options = PlanOptions::new().with_feed_share(plan_share);
    PathTiming::plan(curve, &machine(), &options).expect("plan")
}

fn line() -> Curve {
    BSpline::clamped_uniform(1, &[[0.0, 0.0, 0.0], [60.0, 80.0, 0.0]], 0.0, 1.0).expect("a line")
}

/// A compile whose feed share is larger than the plan left free would let a feed change
/// take the motion beyond the limits (measured before the check: held at every 10th tick,
/// 1.28× the jerk limit for a plan leaving ¼ and a compile asking 0.9, 1.11× for 0.01 and
/// ¼); it is an error naming the quantity, with the limits given or taken from the plan.
#[test]
fn a_compile_asking_more_than_the_plan_left_free_is_an_error() {
    let curve = line();
    // the line's y axis takes 0.8 of the path's acceleration and has 1 500 against 2 000:
    // with a share only slightly above the plan's, y is the first to lack its reserve
    let y = Quantity::AxisAcceleration { axis: 1 };
    let cases = [
        (0.25, 0.9, Quantity::Acceleration),
        (0.01, 0.25, Quantity::Acceleration),
        (0.1, 0.11, y),
    ];
    for (plan_share, compile_share, quantity) in cases {
        let plan = line_plan(&curve, plan_share);
        let options = CompileOptions::new()
            .with_path_limits(&machine())
            .with_feed_share(compile_share);
        let r: Result<Box<Path<f64, 3, PIECES>>, _> =
            compile_boxed(&Along::new(&curve, &plan), RATE, &options);
        assert_eq!(
            r.err(),
            Some(Error::FeedReserveExceeded { quantity }),
            "plan {plan_share}, compile {compile_share}"
        );
    }
    // the pick-and-place uses z's acceleration more than the path's
    let pnp = pick_and_place();
    let plan = line_plan(&pnp, 0.1);
    let options = CompileOptions::new()
        .with_limits(10_000.0, 1e6)
        .with_axis_acceleration(machine().axis_acceleration())
        .with_feed_share(0.25);
    let r: Result<Box<Path<f32, 3, PIECES>>, _> =
        compile_boxed(&Along::new(&pnp, &plan), RATE, &options);
    assert!(
        matches!(
            r.err(),
            Some(Error::FeedReserveExceeded {
                quantity: Quantity::AxisAcceleration { .. }
            })
        ),
        "an axis's reserve"
    );
}

/// Where the compile asks at most what the plan left free, or takes the plan's reserve
/// (no limits given), holds at every 10th tick keep every limit in the samples.
fn holds_keep_the_limits<N: Kernel>(curve: &Curve, plan_share: f64, options: &CompileOptions) {
    let plan = line_plan(curve, plan_share);
    let path: Box<Path<N, 3, PIECES>> =
        compile_boxed(&Along::new(curve, &plan), RATE, options).expect("compile");
    let what = format!("{} plan {plan_share}, {options:?}", N::NAME);
    for hold in (10..path.ticks().min(600)).step_by(10) {
        let mut resumed = false;
        let (seen, last, _) = run(curve, &plan, &path, &machine(), 100_000, |k, s| {
            if k == u64::from(hold) {
                s.hold();
            }
            if k > u64::from(hold) && !resumed && s.feed() == 0.0 {
                s.resume();
                resumed = true;
            }
        });
        assert_seen(&format!("{what}, held at {hold}"), &seen, &path);
        assert_eq!(last.map(|s| s.position), Some(path.end_position()));
    }
}

#[test]
fn holds_within_the_plans_reserve_keep_the_limits() {
    let given = |share| {
        CompileOptions::new()
            .with_path_limits(&machine())
            .with_feed_share(share)
    };
    for curve in [line(), pick_and_place()] {
        for (plan_share, options) in [
            (0.25, given(0.25)),
            (0.25, given(0.1)),
            (0.01, CompileOptions::new()),
            (0.01, given(0.01)),
        ] {
            holds_keep_the_limits::<f32>(&curve, plan_share, &options);
            holds_keep_the_limits::<f64>(&curve, plan_share, &options);
            holds_keep_the_limits::<Q40>(&curve, plan_share, &options);
        }
    }
}
