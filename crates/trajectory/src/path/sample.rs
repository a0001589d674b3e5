//! The sample type: one setpoint of every axis.

use strak_curves::Scalar;

use crate::online::{Kinematics, Real};

/// One setpoint: position (units), velocity (units/s) and acceleration (units/s²) of every
/// axis at wall-clock tick `tick` (counted from the sampler's start, including ticks held).
///
/// ```
/// use strak_trajectory::Sample;
/// let s = Sample { tick: 3, position: [1.0_f32], velocity: [0.0], acceleration: [0.0] };
/// assert_eq!(s.position[0], 1.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Sample<T, const A: usize> {
    /// Wall-clock tick of this sample (0 for the first).
    pub tick: u64,
    /// Position of each axis.
    pub position: [T; A],
    /// Velocity of each axis.
    pub velocity: [T; A],
    /// Acceleration of each axis.
    pub acceleration: [T; A],
}

impl<T: Copy, const A: usize> Sample<T, A> {
    /// A sample at tick 0 with every value `v`: for example the buffer that
    /// [`Sampler::next_into`](crate::Sampler::next_into) and
    /// [`Sampler::fill`](crate::Sampler::fill) overwrite.
    ///
    /// ```
    /// use strak_trajectory::{Kernel, Q40, Sample};
    /// let s: Sample<_, 3> = Sample::splat(Q40::NATIVE_ZERO);
    /// assert_eq!((s.tick, s.position), (0, [Q40::NATIVE_ZERO; 3]));
    /// ```
    pub const fn splat(v: T) -> Self {
        Sample {
            tick: 0,
            position: [v; A],
            velocity: [v; A],
            acceleration: [v; A],
        }
    }
}

impl<T: Scalar, const A: usize> Sample<T, A> {
    /// Every axis's state in the solver's format `R`: the start of a move that takes over
    /// from this sample ([`take_over_into`](crate::take_over_into)). Exact from `f32` into
    /// `f32` or `f64` and from `f64` into `f64`; from `I32F32` through `f64`, exact below
    /// 2²¹ units.
    ///
    /// ```
    /// use strak_trajectory::Sample;
    /// let s = Sample { tick: 7, position: [1.5_f32], velocity: [-2.0], acceleration: [0.25] };
    /// let [k] = s.kinematics::<f64>();
    /// assert_eq!((k.position, k.velocity, k.acceleration), (1.5, -2.0, 0.25));
    /// ```
    pub fn kinematics<R: Real>(&self) -> [Kinematics<R>; A] {
        core::array::from_fn(|i| {
            Kinematics::new(
                R::lit(self.position[i].to_f64()),
                R::lit(self.velocity[i].to_f64()),
                R::lit(self.acceleration[i].to_f64()),
            )
        })
    }
}
