//! The random online moves the benchmarks and the comparison with Ruckig share: 3 axes (or
//! any count), machine-sized limits (50–800 mm/s, 10³–10⁴ mm/s², 10⁴–2·10⁵ mm/s³), starts
//! and targets with velocity and acceleration inside the limits (each zero 30 % of the
//! time), positions within ±300 mm.

use strak_trajectory::{AxisLimits, Kinematics};

/// One move: start, target and limits per axis (symmetric limits, as Ruckig's Rust wrapper
/// takes them).
#[derive(Clone, Copy, Debug)]
pub struct OnlineCase<const A: usize> {
    /// The start states.
    pub start: [Kinematics<f64>; A],
    /// The targets.
    pub target: [Kinematics<f64>; A],
    /// The limits.
    pub limits: [AxisLimits<f64>; A],
}

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

    fn value(&mut self, limit: f64) -> f64 {
        if self.next() < 0.3 {
            0.0
        } else {
            self.range(-limit, limit)
        }
    }
}

/// `n` random moves of `A` axes from `seed` (`outside`: starts up to 1.5 times the limits).
pub fn online_cases<const A: usize>(n: usize, seed: u64, outside: bool) -> Vec<OnlineCase<A>> {
    let mut rng = Rng(seed | 1);
    let k = if outside { 1.5 } else { 1.0 };
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let case: [_; A] = core::array::from_fn(|_| {
            let (v, a, j) = (
                rng.range(50.0, 800.0),
                rng.range(1e3, 1e4),
                rng.range(1e4, 2e5),
            );
            let limits = AxisLimits::new(v, a, j).expect("positive");
            let start =
                Kinematics::new(rng.range(-300.0, 300.0), rng.value(k * v), rng.value(k * a));
            let target = Kinematics::new(rng.range(-300.0, 300.0), rng.value(v), rng.value(a));
            // A target must be reachable without passing a velocity limit.
            let carried = target.acceleration * target.acceleration / (2.0 * j);
            let passes = (target.acceleration < 0.0 && target.velocity + carried > v)
                || (target.acceleration > 0.0 && target.velocity - carried < -v);
            (start, target, limits, passes)
        });
        if case.iter().any(|c| c.3) {
            continue;
        }
        out.push(OnlineCase {
            start: case.map(|c| c.0),
            target: case.map(|c| c.1),
            limits: case.map(|c| c.2),
        });
    }
    out
}
