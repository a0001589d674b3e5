//! Random cases for the tests of the online solver and of what builds on it.

use super::{AxisLimits, Kinematics, check_target};

/// A small deterministic generator (xorshift64) for the random cases.
pub(crate) struct Rng(pub(crate) u64);

impl Rng {
    pub(crate) fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        #[allow(clippy::cast_precision_loss)]
        let x = (self.0 >> 11) as f64 / (1_u64 << 53) as f64;
        x
    }

    pub(crate) fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }

    /// A value in `±k·limit`, zero 30 % of the time.
    pub(crate) fn value(&mut self, k: f64, limit: f64) -> f64 {
        let x = self.range(-k * limit, k * limit);
        if self.next() < 0.3 { 0.0 } else { x }
    }
}

/// A random target within `l` (velocity and acceleration inside, and reachable).
pub(crate) fn target(rng: &mut Rng, l: &AxisLimits<f64>) -> Kinematics<f64> {
    loop {
        let t = Kinematics::new(
            rng.range(-5.0, 5.0),
            rng.value(1.0, l.v_max),
            rng.value(1.0, l.a_max),
        );
        if check_target(&t, l, true).is_ok() {
            return t;
        }
    }
}

/// A random case: start (within `k` times the limits), target (within the limits and
/// reachable), limits.
pub(crate) fn case(rng: &mut Rng, k: f64) -> (Kinematics<f64>, Kinematics<f64>, AxisLimits<f64>) {
    let (v, a, j) = (
        rng.range(0.1, 10.0),
        rng.range(0.1, 10.0),
        rng.range(0.1, 10.0),
    );
    let start = Kinematics::new(rng.range(-5.0, 5.0), rng.value(k, v), rng.value(k, a));
    let limits = AxisLimits::new(v, a, j).unwrap();
    (start, target(rng, &limits), limits)
}
