//! The random online moves the benchmarks and the comparison with Ruckig share: 3 axes (or
//! any count), machine-sized limits (50–800 mm/s, 10³–10⁴ mm/s², 10⁴–2·10⁵ mm/s³), starts
//! and targets with velocity and acceleration inside the limits (each zero 30 % of the
//! time), positions within ±300 mm.
//!
//! It uses `core` only: the example firmware (`firmware-sim/qemu`) compiles this file too
//! (by `#[path]`) and counts the solver's instructions on the same moves.

use strak_trajectory::{AxisLimits, Kinematics};

/// The seed of the moves of the benchmarks (criterion's `online` groups, and the example
/// firmware's instruction counts).
pub const BENCH_SEED: u64 = 0x0B1E_C7ED_0011_1111;

/// One move: start, target and limits per axis (symmetric limits, as Ruckig's Rust wrapper
/// takes them).
#[derive(Clone, Copy, Debug)]
pub struct OnlineCase<R, const A: usize> {
    /// The start states.
    pub start: [Kinematics<R>; A],
    /// The targets.
    pub target: [Kinematics<R>; A],
    /// The limits.
    pub limits: [AxisLimits<R>; A],
}

impl<const A: usize> OnlineCase<f64, A> {
    /// The same move in `f32` (every value rounded to nearest); `None` if a limit rounds to
    /// an invalid one (it does not for these ranges).
    #[allow(clippy::cast_possible_truncation)]
    pub fn in_f32(&self) -> Option<OnlineCase<f32, A>> {
        let narrow = |k: &Kinematics<f64>| {
            Kinematics::new(k.position as f32, k.velocity as f32, k.acceleration as f32)
        };
        let limits = all(self.limits.map(|l| {
            AxisLimits::new(
                l.velocity_max() as f32,
                l.acceleration_max() as f32,
                l.jerk() as f32,
            )
            .ok()
        }))?;
        Some(OnlineCase {
            start: self.start.each_ref().map(narrow),
            target: self.target.each_ref().map(narrow),
            limits,
        })
    }
}

/// A small deterministic generator (Marsaglia's xorshift64, *Xorshift RNGs*, J. Stat.
/// Softw. 8(14), 2003: shifts 13, 7, 17); the state must not be 0.
#[derive(Debug)]
pub struct Rng(pub u64);

impl Rng {
    /// The next value in `[0, 1)`.
    pub fn unit(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1_u64 << 53) as f64
    }

    /// A value in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// 0 with probability 0.3, else a value in `[-limit, limit)`.
    pub fn value(&mut self, limit: f64) -> f64 {
        if self.unit() < 0.3 {
            0.0
        } else {
            self.range(-limit, limit)
        }
    }
}

/// The random moves of `A` axes from one seed, endless (see [`online_cases`]).
#[derive(Debug)]
pub struct OnlineCases<const A: usize> {
    rng: Rng,
    /// How far beyond the limits a start may lie (1 or 1.5).
    reach: f64,
}

/// One axis of a move: start, target, limits; `None` for a target that cannot be reached
/// without passing a velocity limit (it is drawn again).
type Axis = Option<(Kinematics<f64>, Kinematics<f64>, AxisLimits<f64>)>;

impl<const A: usize> OnlineCases<A> {
    fn axis(&mut self) -> Axis {
        let rng = &mut self.rng;
        let (v, a, j) = (
            rng.range(50.0, 800.0),
            rng.range(1e3, 1e4),
            rng.range(1e4, 2e5),
        );
        let limits = AxisLimits::new(v, a, j).ok()?;
        let k = self.reach;
        let start = Kinematics::new(rng.range(-300.0, 300.0), rng.value(k * v), rng.value(k * a));
        let target = Kinematics::new(rng.range(-300.0, 300.0), rng.value(v), rng.value(a));
        let carried = target.acceleration * target.acceleration / (2.0 * j);
        let passes = (target.acceleration < 0.0 && target.velocity + carried > v)
            || (target.acceleration > 0.0 && target.velocity - carried < -v);
        (!passes).then_some((start, target, limits))
    }
}

impl<const A: usize> Iterator for OnlineCases<A> {
    type Item = OnlineCase<f64, A>;

    fn next(&mut self) -> Option<Self::Item> {
        loop {
            if let Some(axes) = all::<_, A>(core::array::from_fn(|_| self.axis())) {
                return Some(OnlineCase {
                    start: axes.map(|a| a.0),
                    target: axes.map(|a| a.1),
                    limits: axes.map(|a| a.2),
                });
            }
        }
    }
}

/// The random moves of `A` axes from `seed` (`outside`: starts up to 1.5 times the limits),
/// without end: take as many as needed.
pub fn online_cases<const A: usize>(seed: u64, outside: bool) -> OnlineCases<A> {
    OnlineCases {
        rng: Rng(seed | 1),
        reach: if outside { 1.5 } else { 1.0 },
    }
}

/// Every value, or `None` if one is missing (or `A` is 0).
fn all<T: Copy, const A: usize>(values: [Option<T>; A]) -> Option<[T; A]> {
    let mut out = [(*values.first()?)?; A];
    for (o, v) in out.iter_mut().zip(values) {
        *o = v?;
    }
    Some(out)
}
