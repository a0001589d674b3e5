//! The sample type: one setpoint of every axis.

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
