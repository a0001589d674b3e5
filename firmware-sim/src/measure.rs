//! Measuring a run from its samples: the maxima of the sampled velocity and acceleration, of
//! their finite differences and of the jerk, the components along the path, and the distance
//! of each sample from the curve.
//!
//! # Tolerance of the finite differences
//! A quantity taken by finite differences, `q = (y_{k+1} − y_k)·f` (`f` the control rate), is
//! checked against its limit `L` as `q ≤ L·(1 + 10⁻⁹) + 2·u(M)·f`, and a norm over `D` axes
//! with `√D` times that. `u(M)` is the resolution of the sample type at the run's largest
//! magnitude `M` of `y`: `M·2⁻⁵²` for `f64`, `M·2⁻²³` for `f32`, `2⁻³²` for the `I32F32`
//! samples of `fixed`. Each sample is within half a unit `u` of the value the sampler
//! computed before its conversion to the sample type, plus half a unit for the rounding of the
//! last forward-difference addition, so the difference of two samples carries at most `2u`
//! that no motion has. The relative `10⁻⁹` covers the `f64` arithmetic of the check itself;
//! the sampled velocities and accelerations are checked with it alone (they are the samples,
//! not an estimate).

use strak_curves::Scalar;

use crate::number::NumberFormat;

/// The relative tolerance of every check: the rounding of the `f64` arithmetic of the check
/// (the library's, which its feed guard checks with).
pub const RELATIVE_TOLERANCE: f64 = strak_trajectory::LIMIT_CHECK_RELATIVE;

/// The resolution `u(M)` of a sample value of magnitude `magnitude` in the job's format.
///
/// ```
/// use strak_sim::number::NumberFormat;
/// use strak_sim::measure::resolution;
/// assert_eq!(resolution(NumberFormat::F32, 1.0), f64::from(f32::EPSILON));
/// assert_eq!(resolution(NumberFormat::Q40, 1e6), 2f64.powi(-32));
/// ```
pub fn resolution(number: NumberFormat, magnitude: f64) -> f64 {
    number.sample_resolution(magnitude)
}

/// `|v|` over the axes.
pub fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// `|a − b|` over the axes.
pub fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// A largest value and its time.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Worst {
    /// The value.
    pub max: f64,
    /// When, in seconds.
    pub at_s: f64,
}

impl Worst {
    fn push(&mut self, t: f64, x: f64) {
        if x > self.max {
            *self = Worst { max: x, at_s: t };
        }
    }
}

/// Running maxima of one quantity: its norm and each axis.
#[derive(Clone, Debug)]
pub struct Peak<const D: usize> {
    /// The norm over the axes.
    pub norm: Worst,
    /// Each axis, in absolute value.
    pub axes: [Worst; D],
    /// The largest absolute coordinate.
    pub magnitude: f64,
}

impl<const D: usize> Default for Peak<D> {
    fn default() -> Self {
        Peak {
            norm: Worst::default(),
            axes: [Worst::default(); D],
            magnitude: 0.0,
        }
    }
}

impl<const D: usize> Peak<D> {
    /// Adds `v`; its norm is taken over the first `path_axes` axes.
    fn push(&mut self, t: f64, v: &[f64; D], path_axes: usize) {
        self.norm.push(t, norm(&v[..path_axes]));
        for (p, x) in self.axes.iter_mut().zip(v) {
            p.push(t, x.abs());
            self.magnitude = self.magnitude.max(x.abs());
        }
    }
}

/// One sample as the measurement sees it, in `f64`.
#[derive(Clone, Copy, Debug)]
pub struct Observed<const D: usize> {
    /// Time in seconds.
    pub t: f64,
    /// Position, velocity and acceleration samples.
    pub position: [f64; D],
    /// The sampled velocity.
    pub velocity: [f64; D],
    /// The sampled acceleration.
    pub acceleration: [f64; D],
    /// The `f64` reference curve at the sample's planned parameter.
    pub reference: [f64; D],
    /// The curve in the job's number format at the same parameter.
    pub curve: [f64; D],
    /// The reference curve's first derivative there.
    pub tangent: [f64; D],
}

/// Everything measured over a run. Norms and distances are taken over the path axes: the
/// first [`path_axes`](Measure::path_axes) (all of them unless
/// [`with_path_axes`](Measure::with_path_axes) says fewer); the axes after them ride along
/// and are measured one by one.
#[derive(Clone, Debug, Default)]
pub struct Measure<const D: usize> {
    rate: f64,
    path_axes: usize,
    /// Position samples (for their magnitude).
    pub position: Peak<D>,
    /// Velocity samples.
    pub velocity: Peak<D>,
    /// Acceleration samples.
    pub acceleration: Peak<D>,
    /// `Δa·f`: the jerk.
    pub jerk: Peak<D>,
    /// `Δx·f`.
    pub dx: Peak<D>,
    /// `Δv·f`.
    pub dv: Peak<D>,
    /// Tangential acceleration `s̈ = a·T`.
    pub tangential_acceleration: Worst,
    /// Centripetal acceleration `|a − s̈T|`.
    pub centripetal_acceleration: Worst,
    /// Tangential jerk: finite differences of `s̈`.
    pub tangential_jerk: Worst,
    /// Distance from the `f64` reference curve.
    pub reference: Worst,
    /// Distance from the curve in the job's format.
    pub curve: Worst,
    previous: Option<Observed<D>>,
    unit_tangent: Option<[f64; D]>,
    previous_at: Option<f64>,
}

impl<const D: usize> Measure<D> {
    /// A measurement of a run at `rate` Hz.
    pub fn new(rate: f64) -> Self {
        Measure {
            rate,
            path_axes: D,
            ..Measure::default()
        }
    }

    /// The same measurement with norms and distances over the first `path_axes` axes only
    /// (1 to `D`; others are clamped into that range).
    ///
    /// ```
    /// use strak_sim::measure::{Measure, Observed};
    /// let mut m = Measure::<2>::new(1_000.0).with_path_axes(1);
    /// let at = [3.0, 0.0];
    /// m.push(&Observed { t: 0.0, position: at, velocity: [3.0, 4.0], acceleration: [0.0; 2],
    ///     reference: at, curve: [3.0, 7.0], tangent: [1.0, 0.0] });
    /// assert_eq!((m.velocity.norm.max, m.velocity.axes[1].max, m.curve.max), (3.0, 4.0, 0.0));
    /// ```
    pub fn with_path_axes(mut self, path_axes: usize) -> Self {
        self.path_axes = path_axes.clamp(1, D.max(1));
        self
    }

    /// The axes norms and distances are taken over.
    pub fn path_axes(&self) -> usize {
        self.path_axes
    }

    /// Adds one sample; returns its jerk (`None` for the first sample).
    pub fn push(&mut self, s: &Observed<D>) -> Option<[f64; D]> {
        let (t, p) = (s.t, self.path_axes);
        self.position.push(t, &s.position, p);
        self.velocity.push(t, &s.velocity, p);
        self.acceleration.push(t, &s.acceleration, p);
        let jerk = self.previous.map(|prev| {
            let diff = |a: &[f64; D], b: &[f64; D]| {
                let mut d = [0.0; D];
                for ((d, x), y) in d.iter_mut().zip(a).zip(b) {
                    *d = (x - y) * self.rate;
                }
                d
            };
            self.dx.push(t, &diff(&s.position, &prev.position), p);
            self.dv.push(t, &diff(&s.velocity, &prev.velocity), p);
            let j = diff(&s.acceleration, &prev.acceleration);
            self.jerk.push(t, &j, p);
            j
        });
        self.reference
            .push(t, distance(&s.position[..p], &s.reference[..p]));
        self.curve
            .push(t, distance(&s.position[..p], &s.curve[..p]));
        self.push_along(s);
        self.previous = Some(*s);
        jerk
    }

    /// The components along the path, with the unit tangent of the reference curve (the last
    /// one where it is defined).
    fn push_along(&mut self, s: &Observed<D>) {
        let p = self.path_axes;
        let dn = norm(&s.tangent[..p]);
        if dn > 0.0 && dn.is_finite() {
            let mut unit = [0.0; D];
            for (u, x) in unit.iter_mut().zip(&s.tangent[..p]) {
                *u = x / dn;
            }
            self.unit_tangent = Some(unit);
        }
        let Some(tv) = &self.unit_tangent else { return };
        let mut a = [0.0; D];
        a[..p].copy_from_slice(&s.acceleration[..p]);
        let at: f64 = a.iter().zip(tv).map(|(x, y)| x * y).sum();
        let mut normal = a;
        for (n, y) in normal.iter_mut().zip(tv) {
            *n -= at * y;
        }
        self.tangential_acceleration.push(s.t, at.abs());
        self.centripetal_acceleration.push(s.t, norm(&normal));
        if let Some(pa) = self.previous_at {
            self.tangential_jerk
                .push(s.t, ((at - pa) * self.rate).abs());
        }
        self.previous_at = Some(at);
    }

    /// The tolerance of a finite difference of samples of magnitude `magnitude`, for one axis
    /// (`norm`: for the norm over the axes); see the module docs.
    pub fn slack(&self, number: NumberFormat, magnitude: f64, norm: bool) -> f64 {
        let axes = if norm {
            (self.path_axes as f64).sqrt()
        } else {
            1.0
        };
        number.difference_allowance(magnitude, self.rate) * axes
    }
}

/// A sample value in `f64`.
pub fn to_f64<T: Scalar, const D: usize>(v: &[T; D]) -> [f64; D] {
    v.map(Scalar::to_f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn observed(t: f64, x: f64, v: f64, a: f64) -> Observed<1> {
        Observed {
            t,
            position: [x],
            velocity: [v],
            acceleration: [a],
            reference: [x + 0.5],
            curve: [x],
            tangent: [1.0],
        }
    }

    #[test]
    fn differences_and_maxima() {
        let mut m = Measure::<1>::new(10.0);
        assert_eq!(m.push(&observed(0.0, 0.0, 0.0, 1.0)), None);
        assert_eq!(m.push(&observed(0.1, 0.2, 3.0, -2.0)), Some([-30.0]));
        assert_eq!(
            m.dx.norm,
            Worst {
                max: 2.0,
                at_s: 0.1
            }
        );
        assert_eq!(m.dv.axes[0].max, 30.0);
        assert_eq!(m.velocity.norm.max, 3.0);
        assert_eq!(m.acceleration.magnitude, 2.0);
        assert_eq!(m.reference.max, 0.5);
        assert_eq!(m.curve.max, 0.0);
        assert_eq!(m.tangential_acceleration.max, 2.0);
        assert_eq!(m.tangential_jerk.max, 30.0);
        assert_eq!(m.centripetal_acceleration.max, 0.0);
    }

    #[test]
    fn slack_is_two_units_per_tick() {
        let m = Measure::<4>::new(1000.0);
        assert_eq!(
            m.slack(NumberFormat::Q40, 5.0, false),
            2.0 * 2f64.powi(-32) * 1000.0
        );
        assert_eq!(
            m.slack(NumberFormat::F32, 2.0, true),
            2.0 * 2.0 * f64::from(f32::EPSILON) * 1000.0 * 2.0
        );
    }
}
