//! Tests of the online solver: worked examples, and properties over random states.

extern crate std;

use std::format;

use super::testing::{Rng, case};
use super::*;

/// The limits hold at 400 points of the profile from the first instant on at which the
/// state is in the limits and can stay there (its velocity, and the velocity it reaches
/// while the jerk brings its acceleration to zero, within the velocity limits): a start
/// outside them first brakes into them. The jerk holds everywhere.
fn assert_keeps_limits(p: &AxisProfile<f64>, l: &AxisLimits<f64>, what: &str) {
    let slack = 1e-9;
    let within = |x: f64, lo: f64, hi: f64| {
        x <= hi * (1.0 + slack) + slack && x >= lo * (1.0 + slack) - slack
    };
    let inside = |k: &Kinematics<f64>| {
        within(k.velocity, l.v_min, l.v_max) && within(k.acceleration, l.a_min, l.a_max)
    };
    let safe = |k: &Kinematics<f64>| {
        let carried = k.velocity + k.acceleration * k.acceleration.abs() / (2.0 * l.jerk);
        inside(k) && within(carried, l.v_min, l.v_max)
    };
    for ph in p.phases() {
        assert!(
            ph.jerk.abs() <= l.jerk * (1.0 + 1e-12),
            "{what}: jerk {}",
            ph.jerk
        );
        assert!(ph.duration >= 0.0, "{what}");
    }
    let mut entered = false;
    for i in 0..=400 {
        let k = p.at(p.duration() * f64::from(i) / 400.0);
        if entered {
            assert!(inside(&k), "{what}: {k:?} outside {l:?} at {i}/400\n{p:?}");
        }
        entered |= safe(&k);
    }
}

fn assert_reaches(p: &AxisProfile<f64>, target: &Kinematics<f64>, what: &str) {
    let e = p.end();
    let scale = 1.0 + p.duration() * 10.0;
    assert!(
        (e.position - target.position).abs() < 1e-9 * scale,
        "{what}: {e:?} vs {target:?}"
    );
    assert!(
        (e.velocity - target.velocity).abs() < 1e-9 * scale,
        "{what}: {e:?} vs {target:?}"
    );
    assert!(
        (e.acceleration - target.acceleration).abs() < 1e-9,
        "{what}: {e:?} vs {target:?}"
    );
}

#[test]
fn rest_to_rest_with_every_limit_reached() {
    // v = a = j = 1, 10 units: 1 s to a_max, 1 s back to a = 0 at v_max, 8 s cruise, 2 s.
    let l = AxisLimits::new(1.0_f64, 1.0, 1.0).unwrap();
    let b = solve_axis(&Kinematics::at_rest(0.0), &Kinematics::at_rest(10.0), &l).unwrap();
    assert!((b.t_min() - 12.0).abs() < 1e-14);
    let jerks: [f64; 7] = core::array::from_fn(|i| b.profile().phases()[2 + i].jerk);
    let durations: [f64; 7] = core::array::from_fn(|i| b.profile().phases()[2 + i].duration);
    assert_eq!(jerks, [1.0, 0.0, -1.0, 0.0, -1.0, 0.0, 1.0]);
    for (d, want) in durations.iter().zip([1.0, 0.0, 1.0, 8.0, 1.0, 0.0, 1.0]) {
        assert!((d - want).abs() < 1e-14, "{durations:?}");
    }
    // Backwards: the mirror image.
    let back = solve_axis(&Kinematics::at_rest(10.0), &Kinematics::at_rest(0.0), &l).unwrap();
    assert!((back.t_min() - 12.0).abs() < 1e-14);
    assert_eq!(back.profile().phases()[2].jerk, -1.0);
}

#[test]
fn short_move_reaches_no_limit() {
    // Rest to rest over d with no limit reached: four jerk phases of (d/(2J))^(1/3) each.
    let l = AxisLimits::new(10.0_f64, 10.0, 1.0).unwrap();
    let b = solve_axis(&Kinematics::at_rest(0.0), &Kinematics::at_rest(2.0), &l).unwrap();
    assert!((b.t_min() - 4.0).abs() < 1e-13, "{}", b.t_min());
    assert!(b.gaps().is_empty());
}

#[test]
fn moving_towards_a_target_behind_overshoots_and_comes_back() {
    let l = AxisLimits::new(1.0, 1.0, 1.0).unwrap();
    let start = Kinematics::new(0.0, 1.0, 0.0);
    let b = solve_axis(&start, &Kinematics::at_rest(-1.0), &l).unwrap();
    let p = b.profile();
    assert_reaches(p, &Kinematics::at_rest(-1.0), "overshoot");
    // It passes beyond the start before it turns.
    let farthest = (0..=100)
        .map(|i| p.at(p.duration() * f64::from(i) / 100.0).position)
        .fold(0.0, f64::max);
    assert!(farthest > 0.9, "{farthest}");
}

#[test]
fn random_states_reach_their_targets_within_the_limits() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    for (k, label) in [(1.0, "inside"), (1.5, "outside")] {
        for n in 0..4_000 {
            let (start, target, l) = case(&mut rng, k);
            let what = format!("{label} {n}: {start:?} -> {target:?} {l:?}");
            let b = solve_axis(&start, &target, &l).unwrap_or_else(|e| panic!("{what}: {e}"));
            assert_reaches(b.profile(), &target, &what);
            assert_keeps_limits(b.profile(), &l, &what);
            // Every feasible duration has a motion that takes it exactly, and no duration in
            // a gap has one: step 1's gaps agree with step 2's feasibility test.
            let t = b.t_min();
            let mut probes = [t * 1.0001, t * 1.3, t * 3.0, 0.0, 0.0];
            for (m, &(lo, hi)) in b.gaps().iter().enumerate() {
                probes[3 + m] = lo + (hi - lo) * 0.5;
            }
            for &probe in probes.iter().filter(|&&x| x > 0.0) {
                let brake = brake::position_brake(start.velocity, start.acceleration, &l);
                let mut p = AxisProfile::still(0.0);
                let got = step2::with_duration(&start, brake, &target, &l, probe, &mut p);
                assert_eq!(
                    got,
                    !b.is_blocked(probe),
                    "{what}: duration {probe} gaps {:?}",
                    b.gaps()
                );
                if got {
                    assert!((p.duration() - probe).abs() < 1e-9 * probe, "{what}");
                    assert_reaches(&p, &target, &what);
                    assert_keeps_limits(&p, &l, &what);
                }
            }
        }
    }
}

#[test]
fn several_axes_finish_together() {
    let mut rng = Rng(0x2545_F491_4F6C_DD1D);
    for n in 0..1_000 {
        let cases: [_; 3] = core::array::from_fn(|_| case(&mut rng, 1.2));
        let start = cases.map(|c| c.0);
        let target = cases.map(|c| c.1);
        let limits = cases.map(|c| c.2);
        let m = OnlineMove::solve(&start, &target, &limits, &MoveOptions::new()).unwrap();
        let longest = m.min_durations().iter().fold(0.0_f64, |x, &y| x.max(y));
        assert!(m.duration() >= longest, "{n}");
        for i in 0..3 {
            let what = format!("{n} axis {i}");
            let p = &m.profiles()[i];
            assert!(
                (p.duration() - m.duration()).abs() < 1e-9 * m.duration(),
                "{what}"
            );
            assert_reaches(p, &target[i], &what);
            assert_keeps_limits(p, &limits[i], &what);
        }
    }
}

#[test]
fn phase_synchronized_axes_move_on_a_line() {
    let limits = [
        AxisLimits::new(2.0, 10.0, 100.0).unwrap(),
        AxisLimits::new(1.0, 10.0, 100.0).unwrap(),
        AxisLimits::new(2.0, 3.0, 100.0).unwrap(),
    ];
    let dir = [1.0, -0.5, 2.0];
    let start = dir.map(|d| Kinematics::new(1.0, 0.3 * d, 0.0));
    let target = dir.map(|d| Kinematics::new(1.0 + 4.0 * d, 0.0, 0.0));
    let options = MoveOptions::new().with_synchronization(Synchronization::Phase);
    let m = OnlineMove::solve(&start, &target, &limits, &options).unwrap();
    assert_eq!(m.synchronization(), Synchronization::Phase);
    for i in 0..=50 {
        let s = m.at(m.duration() * f64::from(i) / 50.0);
        let along = (s[0].position - 1.0) / dir[0];
        for k in 0..3 {
            assert!(
                (s[k].position - 1.0 - along * dir[k]).abs() < 1e-12,
                "{i} {s:?}"
            );
        }
    }
    for i in 0..3 {
        assert_reaches(&m.profiles()[i], &target[i], "phase");
        assert_keeps_limits(&m.profiles()[i], &limits[i], "phase");
    }
    // Off the line (a start velocity across it): time synchronization instead.
    let mut off = start;
    off[1].velocity = 0.7;
    let m = OnlineMove::solve(&off, &target, &limits, &options).unwrap();
    assert_eq!(m.synchronization(), Synchronization::Time);
}

#[test]
fn an_unsynchronized_axis_arriving_early_with_an_acceleration_is_an_error() {
    let l = [AxisLimits::new(1.0_f64, 1.0, 1.0).unwrap(); 2];
    let start = [Kinematics::at_rest(0.0); 2];
    // The second axis arrives first, still accelerating: going on would leave its limits.
    let target = [Kinematics::at_rest(10.0), Kinematics::new(1.0, 0.5, 0.5)];
    let none = MoveOptions::new().with_synchronization(Synchronization::None);
    assert_eq!(
        OnlineMove::solve(&start, &target, &l, &none),
        Err(Error::AccelerationAfterArrival { axis: 1 })
    );
    // Synchronized, or arriving at constant velocity: a move.
    assert!(OnlineMove::solve(&start, &target, &l, &MoveOptions::new()).is_ok());
    let coasting = [Kinematics::at_rest(10.0), Kinematics::new(1.0, 0.5, 0.0)];
    let m = OnlineMove::solve(&start, &coasting, &l, &none).unwrap();
    let after = m.at(m.duration());
    assert!((after[1].velocity - 0.5).abs() < 1e-12 && after[1].acceleration == 0.0);
}

#[test]
fn velocity_mode_reaches_the_velocity() {
    let mut rng = Rng(42);
    for n in 0..2_000 {
        let (start, mut target, l) = case(&mut rng, 1.3);
        target.acceleration = 0.0;
        let b = solve_axis_velocity(&start, &target, &l).unwrap();
        let e = b.profile().end();
        assert!(
            (e.velocity - target.velocity).abs() < 1e-9 * (1.0 + b.t_min()),
            "{n}"
        );
        assert_eq!(e.acceleration, target.acceleration);
        let t = b.t_min() * 1.7 + 0.1;
        let mut p = AxisProfile::still(0.0);
        assert!(velocity::with_duration(&start, &target, &l, t, &mut p));
        assert!((p.duration() - t).abs() < 1e-12 * t);
        assert!(
            (p.end().velocity - target.velocity).abs() < 1e-9 * (1.0 + t),
            "{n}"
        );
    }
}

#[test]
fn bad_input_is_an_error() {
    let l = AxisLimits::new(1.0, 1.0, 1.0).unwrap();
    let rest = Kinematics::at_rest(0.0);
    assert_eq!(
        solve_axis(&Kinematics::new(f64::NAN, 0.0, 0.0), &rest, &l),
        Err(Error::NonFiniteState)
    );
    assert_eq!(
        solve_axis(&rest, &Kinematics::new(0.0, f64::INFINITY, 0.0), &l),
        Err(Error::NonFiniteState)
    );
    let too_fast = Kinematics::new(1.0, 1.5, 0.0);
    assert_eq!(
        solve_axis(&rest, &too_fast, &l),
        Err(Error::TargetOutsideLimits {
            quantity: crate::Quantity::Velocity
        })
    );
    // At v_max while decelerating: it was faster just before.
    let passing = Kinematics::new(1.0, 1.0, -0.5);
    assert_eq!(
        solve_axis(&rest, &passing, &l),
        Err(Error::TargetOutsideLimits {
            quantity: crate::Quantity::Velocity
        })
    );
    assert_eq!(
        AxisLimits::new(1.0, f64::NAN, 1.0),
        Err(Error::InvalidLimit)
    );
    assert_eq!(l.with_minimum(0.0, -1.0), Err(Error::InvalidLimit));
}

#[test]
fn f32_agrees_with_f64() {
    let mut rng = Rng(7);
    let mut worst = 0.0_f64;
    for _ in 0..5_000 {
        let (s, t, l) = case(&mut rng, 1.0);
        #[allow(clippy::cast_possible_truncation)]
        let c = |x: f64| x as f32;
        let k32 =
            |k: &Kinematics<f64>| Kinematics::new(c(k.position), c(k.velocity), c(k.acceleration));
        let k64 = |k: &Kinematics<f32>| {
            Kinematics::new(
                f64::from(k.position),
                f64::from(k.velocity),
                f64::from(k.acceleration),
            )
        };
        let (s32, t32) = (k32(&s), k32(&t));
        let l32 = AxisLimits::new(c(l.v_max), c(l.a_max), c(l.jerk)).unwrap();
        let l64 = AxisLimits::new(
            f64::from(l32.v_max),
            f64::from(l32.a_max),
            f64::from(l32.jerk),
        )
        .unwrap();
        let Ok(d) = solve_axis(&k64(&s32), &k64(&t32), &l64) else {
            continue;
        };
        let f = solve_axis(&s32, &t32, &l32).unwrap();
        // The position difference is known to the f32 spacing of the positions.
        let dp = (t.position - s.position).abs().max(1e-3);
        let quantized = f64::from(f32::EPSILON) * (s.position.abs() + t.position.abs()) / dp;
        let rel = (d.t_min() - f64::from(f.t_min())).abs() / d.t_min();
        worst = worst.max(rel / (1e-5 + quantized));
    }
    assert!(worst < 1.0, "{worst}");
}

/// High jerks against the acceleration (short jerk phases) make the forms' polynomial
/// coefficients large (`J²·a_max²` and beyond): `f32` solves them as `f64` does, to its
/// rounding, with jerks up to `10⁸` (the coefficients are scaled before their roots are
/// sought; unscaled, the discriminant overflowed `f32` from a jerk of about `5·10⁵` here).
#[test]
fn f32_solves_moves_with_high_jerk() {
    use super::sync::{self, Interface};
    for j in [1e3, 1e5, 5e5, 6.487e5, 5e6, 1e8] {
        for (p0, p1) in [(0.0, 32.38), (-149.007_59, -181.387_93), (0.0, -1e-3)] {
            let solve = |r: &mut AxisProfile<f64>, single: bool| -> f64 {
                let (v, a) = (433.18, 5_164.67);
                if single {
                    let l = AxisLimits::new(v as f32, a as f32, j as f32).unwrap();
                    let (s, t) = (
                        Kinematics::at_rest(p0 as f32),
                        Kinematics::at_rest(p1 as f32),
                    );
                    let mut p = AxisProfile::still(0.0_f32);
                    let span = sync::axis_span(&s, &t, &l, Interface::Position, &mut p);
                    f64::from(span.unwrap_or_else(|e| panic!("f32, j {j}: {e:?}")).t_min)
                } else {
                    let l = AxisLimits::new(v, a, j).unwrap();
                    let (s, t) = (Kinematics::at_rest(p0), Kinematics::at_rest(p1));
                    sync::axis_span(&s, &t, &l, Interface::Position, r)
                        .unwrap()
                        .t_min
                }
            };
            let mut p = AxisProfile::still(0.0);
            let (t32, t64) = (solve(&mut p, true), solve(&mut p, false));
            assert!((t32 - t64).abs() <= 1e-5 * t64, "j {j}: {t32} vs {t64}");
        }
    }
}

/// A quick stop from a sample of an earlier quick stop: the state lies on its braking curve
/// (full jerk brings the acceleration and the velocity to zero together, after exactly 3
/// ticks), within rounding on either side. On the tick grid, and in every synchronization,
/// the stop takes those 3 ticks: the fixed-duration change accepts the double root its
/// quadratic has there.
#[test]
fn a_quick_stop_on_its_braking_curve_takes_its_ticks() {
    let l = [
        AxisLimits::new(40.47157985694891_f64, 332.4618566754005, 43304.52910547757).unwrap(),
        AxisLimits::new(5.124668755963456, 19.881156491218718, 2589.602694678804).unwrap(),
        AxisLimits::new(53.48040870029315, 207.47728784374232, 27024.77312736395).unwrap(),
    ];
    let s = [
        Kinematics::new(175.68422161034854, 0.19487038097464895, -129.91358731643268),
        Kinematics::new(-114.33383275814259, 0.01165321212605461, -7.768808084036408),
        Kinematics::new(12.051128817003796, 0.12161147907313771, -81.07431938209184),
    ];
    let rest = [Kinematics::at_rest(0.0); 3];
    let stop = MoveOptions::new().with_rate(1_000.0).quick_stop();
    for sync in [
        Synchronization::Phase,
        Synchronization::Time,
        Synchronization::None,
    ] {
        let m = OnlineMove::solve(&s, &rest, &l, &stop.with_synchronization(sync))
            .unwrap_or_else(|e| panic!("{sync:?}: {e:?}"));
        assert!(
            (m.duration() - 0.003).abs() < 1e-15,
            "{sync:?}: {}",
            m.duration()
        );
    }
}
