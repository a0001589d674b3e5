//! The online solver against strak-ref's independent reference (an enumeration of the
//! seven-phase forms with the velocity equation solved in closed form and the position
//! residual scanned and bisected), on 10⁵ random axes, and on 10⁵ random moves of 3 and of
//! 6 axes drawn from them:
//!
//! * one axis: the shortest duration within 10⁻⁹ relative, and the same gaps (durations
//!   the axis cannot take);
//! * several axes, time-synchronized: the move's duration is the reference's smallest
//!   duration that every axis can take, within 10⁻⁹ relative, and every axis's motion
//!   takes it and ends on its target.
//!
//! The cases: starts within 1.5 times the limits (a third outside them, braking first),
//! targets inside the limits with velocity and acceleration (zero a third of the time each),
//! symmetric and asymmetric limits, at two scales (units of 0.1–10, and a machine's mm with
//! limits up to 800 mm/s, 10⁴ mm/s², 2·10⁵ mm/s³).

use std::sync::OnceLock;

use strak_ref::{
    OnlineDurations, OnlineLimits, OnlineState, online_durations, online_synchronized,
};
use strak_trajectory::{AxisLimits, Kinematics, MoveOptions, OnlineMove, solve_axis};

/// A small deterministic generator (xorshift64).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1_u64 << 53) as f64
    }

    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }

    fn value(&mut self, lo: f64, hi: f64) -> f64 {
        if self.next() < 0.3 {
            0.0
        } else {
            self.range(lo, hi)
        }
    }

    fn index(&mut self, n: usize) -> usize {
        ((self.next() * n as f64) as usize).min(n - 1)
    }
}

/// One axis: start, target, limits, and the reference's durations.
struct Case {
    start: Kinematics<f64>,
    target: Kinematics<f64>,
    limits: AxisLimits<f64>,
    reference: OnlineDurations,
}

fn random_case(rng: &mut Rng) -> Case {
    let machine = rng.next() < 0.5;
    let (v, a, j, p) = if machine {
        (
            rng.range(5.0, 800.0),
            rng.range(50.0, 1e4),
            rng.range(1e3, 2e5),
            300.0,
        )
    } else {
        (
            rng.range(0.1, 10.0),
            rng.range(0.1, 10.0),
            rng.range(0.1, 10.0),
            5.0,
        )
    };
    let (v_min, a_min) = if rng.next() < 0.2 {
        (-v * rng.range(0.3, 1.0), -a * rng.range(0.3, 1.0))
    } else {
        (-v, -a)
    };
    let limits = AxisLimits::new(v, a, j)
        .unwrap()
        .with_minimum(v_min, a_min)
        .unwrap();
    let k = if rng.next() < 0.33 { 1.5 } else { 1.0 };
    let start = Kinematics::new(
        rng.range(-p, p),
        rng.value(k * v_min, k * v),
        rng.value(k * a_min, k * a),
    );
    let target = loop {
        let t = Kinematics::new(rng.range(-p, p), rng.value(v_min, v), rng.value(a_min, a));
        let carried = t.acceleration * t.acceleration / (2.0 * j);
        let passes = (t.acceleration < 0.0 && t.velocity + carried > v)
            || (t.acceleration > 0.0 && t.velocity - carried < v_min);
        if !passes {
            break t;
        }
    };
    let l = OnlineLimits {
        v_max: v,
        v_min,
        a_max: a,
        a_min,
        jerk: j,
    };
    let state = |k: &Kinematics<f64>| OnlineState::new(k.position, k.velocity, k.acceleration);
    let reference = online_durations(&state(&start), &state(&target), &l);
    Case {
        start,
        target,
        limits,
        reference,
    }
}

const CASES: usize = 100_000;
const TOLERANCE: f64 = 1e-9;

/// The random axes with their reference durations, computed once for all three tests.
fn cases() -> &'static [Case] {
    static CASES_ONCE: OnceLock<Vec<Case>> = OnceLock::new();
    CASES_ONCE.get_or_init(|| {
        let mut rng = Rng(0x0DDB_1A5E_5BAD_5EED);
        (0..CASES).map(|_| random_case(&mut rng)).collect()
    })
}

#[test]
fn one_axis_agrees_with_the_reference() {
    let cases = cases();
    let mut failures = Vec::new();
    for (n, c) in cases.iter().enumerate() {
        let block = solve_axis(&c.start, &c.target, &c.limits).expect("solves");
        let r = &c.reference;
        let close = |x: f64, y: f64| (x - y).abs() <= TOLERANCE * y.abs().max(1e-3);
        let gaps_agree = block.gaps().len() == r.gaps.len()
            && block
                .gaps()
                .iter()
                .zip(&r.gaps)
                .all(|(g, h)| close(g.0, h.0) && close(g.1, h.1));
        if !close(block.t_min(), r.t_min) || !gaps_agree {
            failures.push(format!(
                "{n}: t_min {} vs {} gaps {:?} vs {:?}",
                block.t_min(),
                r.t_min,
                block.gaps(),
                r.gaps
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {CASES} disagree:\n{}",
        failures.len(),
        failures[..failures.len().min(20)].join("\n")
    );
}

fn synchronized<const A: usize>(seed: u64) {
    let cases = cases();
    let mut rng = Rng(seed);
    let mut failures = Vec::new();
    for n in 0..CASES {
        let pick: [usize; A] = core::array::from_fn(|_| rng.index(cases.len()));
        let start = pick.map(|i| cases[i].start);
        let target = pick.map(|i| cases[i].target);
        let limits = pick.map(|i| cases[i].limits);
        let m = OnlineMove::solve(&start, &target, &limits, &MoveOptions::new()).expect("solves");
        let references: Vec<OnlineDurations> =
            pick.iter().map(|&i| cases[i].reference.clone()).collect();
        let want = online_synchronized(&references);
        let mut ok = (m.duration() - want).abs() <= TOLERANCE * want.max(1e-3);
        for (p, t) in m.profiles().iter().zip(&target) {
            let e = p.end();
            let scale = 1.0 + t.position.abs() + p.duration() * (t.velocity.abs() + 1.0);
            ok &= (p.duration() - m.duration()).abs() <= 1e-9 * m.duration().max(1e-3);
            ok &= (e.position - t.position).abs() <= 1e-8 * scale
                && (e.velocity - t.velocity).abs() <= 1e-8 * scale;
        }
        if !ok {
            failures.push(format!(
                "{n}: duration {} vs {want}, axes {pick:?}",
                m.duration()
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {CASES} disagree:\n{}",
        failures.len(),
        failures[..failures.len().min(20)].join("\n")
    );
}

#[test]
fn three_axes_agree_with_the_reference() {
    synchronized::<3>(0x3333_AAAA_5555_CCCC);
}

#[test]
fn six_axes_agree_with_the_reference() {
    synchronized::<6>(0x6666_BBBB_9999_EEEE);
}
