//! The forward-difference state of an axis, and a piece of a path.

use crate::num::Number;

/// The forward-difference state of one axis at one tick. Position differences are per tick,
/// velocity in units/s, acceleration in units/s².
///
/// A path of `N` ticks at rate `f` (tick period `T = 1/f`) is a sequence of pieces with
/// boundaries on the tick grid. Piece `j` covers the ticks `k_j ..= k_{j+1}` (`n_j ≥ 1` ticks
/// long) and is, per axis, the cubic `p(i) = a + b·i + c·i² + d·i³` in the local tick index
/// `i`. It is stored as the forward-difference state at `i = 0` (forward differencing of a
/// polynomial: Foley, van Dam, Feiner & Hughes, *Computer Graphics: Principles and Practice*,
/// 2nd ed., §11.2.9):
///
/// | value                                    | formula            | unit            |
/// |------------------------------------------|--------------------|-----------------|
/// | [`position`](AxisState::position)        | `a`                | units           |
/// | [`delta1`](AxisState::delta1)            | `b + c + d`        | units / tick    |
/// | [`delta2`](AxisState::delta2)            | `2c + 6d`          | units / tick²   |
/// | [`delta3`](AxisState::delta3)            | `6d`               | units / tick³   |
/// | [`velocity`](AxisState::velocity)        | `b / T`            | units / s       |
/// | [`velocity_delta1`](AxisState::velocity_delta1) | `(2c + 3d) / T` | units / s / tick |
/// | [`velocity_delta2`](AxisState::velocity_delta2) | `6d / T`     | units / s / tick² |
/// | [`acceleration`](AxisState::acceleration)| `2c / T²`          | units / s²      |
/// | [`acceleration_delta`](AxisState::acceleration_delta) | `6d / T²` | units / s² / tick |
///
/// One tick ([`AxisState::step`]) is six additions per axis; a piece switch is a load of the
/// next piece's state, so rounding errors never carry from one piece into the next.
///
/// ```
/// use strak_trajectory::AxisState;
/// // p(i) = i³: a = b = c = 0, d = 1, at T = 1 s
/// let mut s = AxisState { position: 0.0_f64, delta1: 1.0, delta2: 6.0, delta3: 6.0,
///     velocity: 0.0, velocity_delta1: 3.0, velocity_delta2: 6.0,
///     acceleration: 0.0, acceleration_delta: 6.0 };
/// s.step();
/// s.step();
/// assert_eq!((s.position, s.velocity, s.acceleration), (8.0, 12.0, 12.0)); // i³, 3i², 6i at 2
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[repr(C)] // nine consecutive values: the Cortex-M tick kernels load an axis in one instruction
pub struct AxisState<N> {
    /// Position `p(i)`.
    pub position: N,
    /// First forward difference `p(i+1) − p(i)`.
    pub delta1: N,
    /// Second forward difference.
    pub delta2: N,
    /// Third forward difference (constant over a piece).
    pub delta3: N,
    /// Velocity `p'(i)/T`.
    pub velocity: N,
    /// First forward difference of the velocity.
    pub velocity_delta1: N,
    /// Second forward difference of the velocity (constant over a piece).
    pub velocity_delta2: N,
    /// Acceleration `p''(i)/T²`.
    pub acceleration: N,
    /// Forward difference of the acceleration (constant over a piece).
    pub acceleration_delta: N,
}

/// The coefficients of Newton's forward-difference formula at a fractional offset `θ`:
/// `p(i + θ) = p(i) + θ·Δ¹ + C(θ,2)·Δ² + C(θ,3)·Δ³`, with the binomial coefficients
/// `C(θ,2) = θ(θ−1)/2` and `C(θ,3) = θ(θ−1)(θ−2)/6`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Newton<N> {
    pub(crate) c1: N,
    pub(crate) c2: N,
    pub(crate) c3: N,
}

impl<N: Number> Newton<N> {
    /// The coefficients at `θ` (4 multiplications).
    #[inline]
    pub(crate) fn at(theta: N) -> Self {
        let c2 = theta * (theta - N::ONE) * N::HALF;
        let c3 = c2 * (theta - N::ONE - N::ONE) * N::THIRD;
        Newton { c1: theta, c2, c3 }
    }
}

impl<N: Number> AxisState<N> {
    /// Every value zero.
    pub const ZERO: Self = AxisState {
        position: N::ZERO,
        delta1: N::ZERO,
        delta2: N::ZERO,
        delta3: N::ZERO,
        velocity: N::ZERO,
        velocity_delta1: N::ZERO,
        velocity_delta2: N::ZERO,
        acceleration: N::ZERO,
        acceleration_delta: N::ZERO,
    };

    /// Advances the state by one tick: `f += Δ¹; Δ¹ += Δ²; Δ² += Δ³; v += Δv¹; Δv¹ += Δv²;
    /// a += Δa` (six additions, exact in fixed-point).
    ///
    /// ```
    /// use strak_trajectory::{AxisState, Number, Q40};
    /// let q = |x: f64| Q40::from_f64(x).unwrap();
    /// // p(i) = 1 + i²/2 (T = 1 s): Δ¹ = ½, Δ² = 1
    /// let mut s = AxisState { position: q(1.0), delta1: q(0.5), delta2: q(1.0),
    ///     velocity_delta1: q(1.0), acceleration: q(1.0), ..AxisState::default() };
    /// for _ in 0..4 { s.step(); }
    /// assert_eq!(s.position, q(9.0));
    /// assert_eq!(s.velocity, q(4.0));
    /// ```
    #[inline]
    pub fn step(&mut self) {
        self.position = self.position + self.delta1;
        self.delta1 = self.delta1 + self.delta2;
        self.delta2 = self.delta2 + self.delta3;
        self.velocity = self.velocity + self.velocity_delta1;
        self.velocity_delta1 = self.velocity_delta1 + self.velocity_delta2;
        self.acceleration = self.acceleration + self.acceleration_delta;
    }

    /// The state at the fractional offset `θ` (Newton's forward-difference formula applied
    /// to every value; the constant differences are unchanged). 10 multiplications.
    #[inline]
    pub(crate) fn shifted(&self, c: &Newton<N>) -> Self {
        AxisState {
            position: self.position + c.c1 * self.delta1 + c.c2 * self.delta2 + c.c3 * self.delta3,
            delta1: self.delta1 + c.c1 * self.delta2 + c.c2 * self.delta3,
            delta2: self.delta2 + c.c1 * self.delta3,
            delta3: self.delta3,
            velocity: self.velocity + c.c1 * self.velocity_delta1 + c.c2 * self.velocity_delta2,
            velocity_delta1: self.velocity_delta1 + c.c1 * self.velocity_delta2,
            velocity_delta2: self.velocity_delta2,
            acceleration: self.acceleration + c.c1 * self.acceleration_delta,
            acceleration_delta: self.acceleration_delta,
        }
    }

    /// The state with every value converted to `f64`.
    pub(crate) fn to_f64(self) -> AxisState<f64> {
        AxisState {
            position: self.position.to_f64(),
            delta1: self.delta1.to_f64(),
            delta2: self.delta2.to_f64(),
            delta3: self.delta3.to_f64(),
            velocity: self.velocity.to_f64(),
            velocity_delta1: self.velocity_delta1.to_f64(),
            velocity_delta2: self.velocity_delta2.to_f64(),
            acceleration: self.acceleration.to_f64(),
            acceleration_delta: self.acceleration_delta.to_f64(),
        }
    }

    /// The nine values in storage order (the order of serialized paths).
    pub(crate) fn values(&self) -> [N; 9] {
        [
            self.position,
            self.delta1,
            self.delta2,
            self.delta3,
            self.velocity,
            self.velocity_delta1,
            self.velocity_delta2,
            self.acceleration,
            self.acceleration_delta,
        ]
    }
}

/// One piece of a path: its first tick, its length in ticks and the forward-difference
/// start state of each axis.
///
/// ```
/// use strak_trajectory::{compile, Along, CompileOptions, Path, Timing};
/// use strak_curves::Bezier;
/// struct Ramp;
/// impl Timing for Ramp {
///     fn duration(&self) -> f64 { 0.1 }
///     fn param(&self, t: f64) -> (f64, f64) { (t.clamp(0.0, 0.1) * 10.0, 10.0) }
/// }
/// let line = Bezier::new([[0.0_f64], [2.0]])?;
/// let trajectory = Along::new(&line, &Ramp);
/// let path: Path<f64, 1, 4> = compile(&trajectory, 1_000.0, &CompileOptions::default())?;
/// let piece = &path.pieces()[0];
/// assert_eq!((piece.start(), piece.ticks()), (0, 100)); // one piece, 100 ticks
/// assert_eq!(piece.axes()[0].position, 0.0);
/// assert!((piece.axes()[0].velocity - 20.0).abs() < 1e-9); // 2 units in 0.1 s
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[repr(C)] // the states first: the piece switch loads them from the piece's own address
pub struct Piece<N, const A: usize> {
    pub(crate) axes: [AxisState<N>; A],
    pub(crate) start: u32,
    pub(crate) ticks: u32,
}

impl<N: Number, const A: usize> Piece<N, A> {
    /// The tick at which the piece starts.
    pub fn start(&self) -> u32 {
        self.start
    }

    /// The length in ticks (≥ 1).
    pub fn ticks(&self) -> u32 {
        self.ticks
    }

    /// The forward-difference start state of each axis.
    pub fn axes(&self) -> &[AxisState<N>; A] {
        &self.axes
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::Q40;

    fn cubic_state(a: f64, b: f64, c: f64, d: f64, t: f64) -> AxisState<f64> {
        AxisState {
            position: a,
            delta1: b + c + d,
            delta2: 2.0 * c + 6.0 * d,
            delta3: 6.0 * d,
            velocity: b / t,
            velocity_delta1: (2.0 * c + 3.0 * d) / t,
            velocity_delta2: 6.0 * d / t,
            acceleration: 2.0 * c / (t * t),
            acceleration_delta: 6.0 * d / (t * t),
        }
    }

    #[test]
    fn forward_differencing_reproduces_the_cubic() {
        let (a, b, c, d, t) = (1.0, -0.5, 0.25, 0.125, 0.5);
        let mut s = cubic_state(a, b, c, d, t);
        for i in 0..=20 {
            let x = f64::from(i);
            assert_eq!(s.position, a + b * x + c * x * x + d * x * x * x);
            assert_eq!(s.velocity, (b + 2.0 * c * x + 3.0 * d * x * x) / t);
            assert_eq!(s.acceleration, (2.0 * c + 6.0 * d * x) / (t * t));
            s.step();
        }
    }

    #[test]
    fn newton_shift_is_the_cubic_at_a_fraction() {
        let (a, b, c, d, t) = (1.0, -0.5, 0.25, 0.125, 0.5);
        let s = cubic_state(a, b, c, d, t);
        for x in [0.0, 0.25, 0.5, 0.9, 3.7] {
            let z = s.shifted(&Newton::at(x));
            let p = a + b * x + c * x * x + d * x * x * x;
            let dp = b + 2.0 * c * x + 3.0 * d * x * x;
            let d1 = (a + b * (x + 1.0) + c * (x + 1.0) * (x + 1.0) + d * (x + 1.0).powi(3)) - p;
            assert!((z.position - p).abs() < 1e-14);
            assert!((z.delta1 - d1).abs() < 1e-14);
            assert!((z.delta2 - (2.0 * c + 6.0 * d * (x + 1.0))).abs() < 1e-14);
            assert!((z.velocity - dp / t).abs() < 1e-14);
            assert!((z.acceleration - (2.0 * c + 6.0 * d * x) / (t * t)).abs() < 1e-13);
        }
        // θ = 0 is exact in fixed-point
        let q = |v: f64| Q40::from_f64(v).unwrap();
        let sq = AxisState {
            position: q(1.0),
            delta1: q(0.3),
            delta2: q(-0.2),
            delta3: q(0.01),
            ..AxisState::default()
        };
        assert_eq!(sq.shifted(&Newton::at(Q40::ZERO)), sq);
    }
}
