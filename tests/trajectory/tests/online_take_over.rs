//! Taking over a running online move at a random tick with a new target
//! ([`take_over_into`]), in every playback format (`f32` with the `f32` solver, `f64` and
//! `Q40` with the `f64` solver, as `strak-sim move` and the firmware pair them), on the
//! benchmark's random 3-axis moves (`bench/src/online_cases.rs`, starts and targets with
//! velocity and acceleration inside the limits).
//!
//! Checked from the samples alone, for the first move up to the switch and for the new
//! move from the switch on, each from its first sample at which every axis is within its
//! limits and can stay there (from a state moving and accelerating towards a velocity limit
//! every motion passes it: a first move that heads for such a target, or a start there):
//! * the new path's first sample is the sample it took over from, bit for bit, and the
//!   second continues from it: no jump in position, velocity or acceleration beyond one
//!   tick's worth of the limits (finite differences below);
//! * across the switch and to the end, every axis's finite differences `Δx·f`, `Δv·f`,
//!   `Δa·f` (means of its velocity, acceleration and jerk over each tick) and its sampled
//!   velocity and acceleration keep that axis's limits, within the playback rounding of the
//!   two paths ([`Allowance`], the bound of `limits_check` for a norm over the axes, which
//!   bounds each axis too) and `10⁻⁹` relative; the jerk also within the solver's rounding
//!   of the acceleration where a phase ends: the profile sets the acceleration at each
//!   switching time to the value its form prescribes (zero in a cruise, a limit during a
//!   hold), within `ulps · a_max` of where the phases' integration puts it (`ulps` = 64 ε for
//!   the `f32` solver, 1024 ε for `f64`: the solver's tolerance), so a tick that holds one or
//!   two switching times may step the acceleration by twice that (`f32`: 1.5·10⁻⁵ of
//!   `a_max`, `1.5·10⁻² · a_max` units/s³ at 1 kHz; `f64`: negligible);
//! * the motion ends on the new target, positions exactly as given (rounded once into the
//!   format), at rest.

#[path = "../../../bench/src/online_cases.rs"]
pub mod online_cases;

use online_cases::{OnlineCase, online_cases};
use strak_curves::Scalar;
use strak_trajectory::{
    AxisLimits, Kernel, Kinematics, MoveOptions, OnlineMove, Path, Real, Sample, Sampler,
    compile_move_into, take_over_into,
};
use strak_trajectory_tests::boxed_path;
use strak_trajectory_tests::limits_check::{Allowance, F64_ROUNDING};

const RATE: f64 = 1_000.0;
const MOVES: usize = 2_000;
const PIECES: usize = 512;
/// A seed of its own: not the benchmark's moves in the benchmark's order.
const SEED: u64 = 0x7A4E_0BE5_2026_1203;

/// Every sample of a path, to its end.
fn play<N: Kernel>(path: &Path<N, 3, PIECES>) -> Vec<Sample<N::Out, 3>> {
    let mut sampler = Sampler::new(path);
    let mut out = Vec::new();
    while !sampler.is_finished() {
        out.push(sampler.next());
    }
    out
}

/// The larger of two allowances, quantity by quantity.
fn larger(a: Allowance, b: Allowance) -> Allowance {
    Allowance {
        speed: a.speed.max(b.speed),
        speed_fd: a.speed_fd.max(b.speed_fd),
        acceleration: a.acceleration.max(b.acceleration),
        acceleration_fd: a.acceleration_fd.max(b.acceleration_fd),
        jerk_fd: a.jerk_fd.max(b.jerk_fd),
    }
}

/// The first sample at which every axis is within its limits and can stay there: its
/// velocity, and the velocity it reaches when full jerk brings its acceleration to zero,
/// within the velocity limit. A start that is moving and accelerating may be carried
/// beyond the limit first, whatever the motion does.
fn first_safe<T: Scalar>(samples: &[Sample<T, 3>], limits: &[AxisLimits<f64>; 3]) -> usize {
    let safe = |s: &Sample<T, 3>| {
        limits.iter().enumerate().all(|(i, l)| {
            let (v, a) = (s.velocity[i].to_f64(), s.acceleration[i].to_f64());
            let carried = v + a * a.abs() / (2.0 * l.jerk());
            v.abs() <= l.velocity_max()
                && carried.abs() <= l.velocity_max()
                && a.abs() <= l.acceleration_max()
        })
    };
    samples.iter().position(safe).unwrap_or(samples.len())
}

/// Checks every axis of `samples` against its limits (see the module docs).
fn assert_within<T: Scalar>(
    samples: &[Sample<T, 3>],
    limits: &[AxisLimits<f64>; 3],
    allow: &Allowance,
    solver_ulps: f64,
    what: &str,
) {
    let slack = |x: f64, extra: f64| x * (1.0 + F64_ROUNDING) + extra;
    for (k, w) in samples.windows(2).enumerate() {
        for (i, l) in limits.iter().enumerate() {
            let (v, a, j) = (l.velocity_max(), l.acceleration_max(), l.jerk());
            let d = |q: usize| {
                let of = |s: &Sample<T, 3>| [s.position, s.velocity, s.acceleration][q][i];
                (of(&w[1]).to_f64() - of(&w[0]).to_f64()) * RATE
            };
            let checks = [
                ("Δx·f", d(0), slack(v, allow.speed_fd)),
                ("Δv·f", d(1), slack(a, allow.acceleration_fd)),
                (
                    "Δa·f",
                    d(2),
                    slack(j, allow.jerk_fd + 2.0 * solver_ulps * a * RATE),
                ),
                ("v", w[0].velocity[i].to_f64(), slack(v, allow.speed)),
                (
                    "a",
                    w[0].acceleration[i].to_f64(),
                    slack(a, allow.acceleration),
                ),
            ];
            for (name, value, limit) in checks {
                assert!(
                    value.abs() <= limit,
                    "{what}: tick {k} axis {i}: |{name}| = {} > {limit}",
                    value.abs()
                );
            }
        }
    }
}

/// The first moves of [`SEED`], each taken over at a random tick by the target of the next
/// move (positions only, at rest), played in `N` with the solver in `R` (`narrow` makes the
/// moves of `R`). Returns how many take-overs were played.
fn take_overs<N: Kernel, R: Real>(
    narrow: impl Fn(&OnlineCase<f64, 3>) -> Option<OnlineCase<R, 3>>,
) -> usize {
    let options = MoveOptions::new().with_rate(RATE);
    let cases: Vec<OnlineCase<f64, 3>> = online_cases::<3>(SEED, false).take(MOVES + 1).collect();
    let (mut first, mut second) = (boxed_path::<N, 3, PIECES>(), boxed_path::<N, 3, PIECES>());
    let mut m = Box::new(OnlineMove::<R, 3>::new());
    let mut played = 0;
    for (n, pair) in cases.windows(2).enumerate() {
        let (Some(c), Some(next)) = (narrow(&pair[0]), narrow(&pair[1])) else {
            panic!("move {n} does not convert");
        };
        let what = format!("{} move {n}", N::NAME);
        m.solve_in_place(&c.start, &c.target, &c.limits, &options)
            .unwrap_or_else(|e| panic!("{what}: {e}"));
        if compile_move_into(&*m, &mut *first).is_err() {
            // Longer than the path's capacity at this rate: not a take-over case.
            continue;
        }
        let before = play(&first);
        // A random tick from the move's own numbers (deterministic).
        let k = (pair[1].start[0].position.abs() * 1e3) as usize % before.len();
        let target = next.target.map(|t| Kinematics::at_rest(t.position));
        let taken = take_over_into(
            &before[k],
            &target,
            &c.limits,
            &options,
            &mut m,
            &mut *second,
        );
        match taken {
            Ok(()) => {}
            Err(strak_trajectory::Error::CapacityExceeded { .. }) => continue,
            Err(e) => panic!("{what}: take-over at tick {k}: {e}"),
        }
        let after = play(&second);
        let same = |s: &Sample<N::Out, 3>| (s.position, s.velocity, s.acceleration);
        assert_eq!(same(&after[0]), same(&before[k]), "{what}: tick {k}");
        let limits = c.limits.map(|l| {
            AxisLimits::new(
                l.velocity_max().to_f64(),
                l.acceleration_max().to_f64(),
                l.jerk().to_f64(),
            )
            .unwrap_or_else(|e| panic!("{what}: {e}"))
        });
        let allow = larger(Allowance::of(&first), Allowance::of(&second));
        // The solver's relative tolerance (`online/form.rs`, `Tolerance::of`).
        let eps = R::EPS.to_f64();
        let ulps = eps * if eps > 1e-10 { 64.0 } else { 1024.0 };
        // The first move up to the switch, then the new one from the switch (its first
        // sample is the switch's), each from its first safe sample: a state from which
        // every motion passes a limit (the first move heading for a target that goes on
        // beyond it) brakes into the limits first.
        for (part, samples) in [("before", &before[..=k]), ("after", &after[..])] {
            let from = first_safe(samples, &limits);
            let what = format!("{what}, taken over at tick {k}, {part} from its sample {from}");
            assert_within(&samples[from..], &limits, &allow, ulps, &what);
        }
        let end = after.last().unwrap_or_else(|| panic!("{what}: no sample"));
        for (i, t) in target.iter().enumerate() {
            let want = N::out_from_f64(t.position.to_f64()).unwrap_or_else(|| panic!("{what}"));
            assert_eq!(
                end.position[i], want,
                "{what}: axis {i} ends off its target"
            );
            assert_eq!(
                end.velocity[i].to_f64(),
                0.0,
                "{what}: axis {i} moves at the end"
            );
        }
        played += 1;
    }
    played
}

#[test]
fn a_new_target_takes_over_in_f64() {
    let played = take_overs::<f64, f64>(|c| Some(*c));
    assert!(played >= MOVES * 9 / 10, "{played} of {MOVES} played");
}

#[test]
fn a_new_target_takes_over_in_f32() {
    let played = take_overs::<f32, f32>(OnlineCase::in_f32);
    assert!(played >= MOVES * 9 / 10, "{played} of {MOVES} played");
}

#[test]
fn a_new_target_takes_over_in_q40() {
    let played = take_overs::<strak_trajectory::Q40, f64>(|c| Some(*c));
    assert!(played >= MOVES * 9 / 10, "{played} of {MOVES} played");
}
