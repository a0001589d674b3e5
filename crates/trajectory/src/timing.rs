//! The interface between planning and compiling: where on the curve the motion is at time t.

/// A time law mapped onto a curve: the curve parameter `u(t)` and its rate `du/dt` over
/// `t ∈ [0, duration]`.
///
/// Planners (parameter-proportional, constant speed, trapezoid, S-curve) implement it; the
/// compiler samples it. Implementations clamp `t` to `[0, duration]`.
///
/// ```
/// use strak_trajectory::Timing;
/// /// u runs from 0 to 1 in 2 s at a constant rate.
/// struct Linear;
/// impl Timing for Linear {
///     fn duration(&self) -> f64 { 2.0 }
///     fn param(&self, t: f64) -> (f64, f64) { (t.clamp(0.0, 2.0) / 2.0, 0.5) }
/// }
/// assert_eq!(Linear.param(1.0), (0.5, 0.5));
/// ```
pub trait Timing {
    /// The duration in seconds (finite, > 0).
    fn duration(&self) -> f64;

    /// `(u, du/dt)` at time `t` (clamped to `[0, duration]`).
    fn param(&self, t: f64) -> (f64, f64);
}
