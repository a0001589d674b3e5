//! The settings of the planner: the profile shape, sampling, zones, the shares of the limits
//! the turning of the path and feed changes may take, corners, and the control rate.

use super::limits::Limits;
use super::timing::MotionLimits;
use crate::error::Error;
use crate::num::RATE_RANGE;

/// The most sampling intervals [`PlanOptions::with_samples`] accepts.
pub(super) const MAX_SAMPLES: usize = 1 << 20;

/// The velocity profile of each zone.
///
/// ```
/// use strak_trajectory::{PlanOptions, ProfileShape};
/// assert_eq!(PlanOptions::new().shape(), ProfileShape::SCurve);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ProfileShape {
    /// Jerk-limited "double S": continuous acceleration, `|j| ≤` the jerk limit.
    #[default]
    SCurve,
    /// Trapezoidal speed: the acceleration jumps between `±a` and 0 (the jerk limit is
    /// ignored).
    Trapezoid,
}

/// Settings of [`PathTiming::plan`](crate::PathTiming::plan).
///
/// # Algorithm
///
/// 0. **Feed reserve.** The motion is planned with the acceleration and jerk limits (path
///    and per axis) times `1 − feed_share`; the rest is left to the sampler's feed changes
///    (override, hold, resume), which [`PathTiming::compile`](crate::PathTiming::compile)
///    sets up with the full limits. Velocities are not reduced (a feed factor `≤ 1` only
///    slows down).
/// 1. **Sampling.** The speed limit `v_lim` and the loads of the path (curvature `κ`, the
///    turning term `|x_sss|` of the jerk) and of the axes (`|T_i|`, `|κN_i|`) are evaluated
///    at the ends and midpoints of `samples` intervals uniform in the curve parameter
///    (uniform in `u` puts more samples where the parametric speed drops, as in tight
///    corners of splines); an interval takes the worst of its three samples. The speed limit
///    keeps the centripetal acceleration `v²κ` (path and per axis) and the turning jerk
///    `v³|x_sss|` within the centripetal share `q` of their limits. Samples where `c'(u) = 0`
///    are skipped (the tangent is undefined there).
/// 2. **Zones.** Consecutive intervals form a zone while the largest limit in it is at most
///    `1 + zone_tolerance` times the smallest; the zone's limit is the smallest (so the plan
///    may be up to that ratio slower than necessary inside a zone). Limits are capped at the
///    path velocity limit, so straight stretches form a single zone. At most `Z` zones. Each
///    zone gets its own path acceleration and jerk limit: what the turning terms at the
///    zone's speed limit leave of `a_max`, `a_i` and `j_max`, so that the acceleration and
///    jerk **in space** stay within the limits (the formulas are in the source of
///    `plan/speed_limit.rs`). The jerk limit is at most `a_z·f/16` (`f` the control
///    rate, 16 = [`MIN_JERK_TICKS`](Self::MIN_JERK_TICKS)): a jerk phase to the zone's
///    acceleration lasts at least 16 ticks, so that the compiled spline, whose pieces start
///    on ticks, can follow it.
/// 3. **Corners, joins and cusps.** Where the tangent turns at a join of pieces by an angle
///    `θ` (a C⁰ corner of a Bézier chain, a polyline or a Hermite spline, a B-spline knot of
///    full multiplicity), a motion at speed `v` has a velocity step `v·|ΔT| = 2v·sin(θ/2)`
///    there, which no finite acceleration follows. A join with `θ` above the corner angle is
///    a **corner**: the zone ends there and the motion comes to rest. A smaller turn is
///    passed at a speed whose step fits the centripetal share of the limits over one tick
///    `T = 1/f`: `v·|ΔT| ≤ q·min(a·T, j·T²)` and per axis `v·|ΔT_i| ≤ q·a_i·T` (were the
///    compiled path to make the turn within a single tick, its sampled acceleration and jerk
///    would stay within that share); a join of a tangent-continuous (G¹) curve has `θ = 0`
///    up to rounding and no cap. A **cusp**, where the tangent reverses inside a piece (the
///    parametric speed `|c'(u)|` falls to 0 and the direction flips, as in a path that
///    doubles back on itself), is located between two samples whose tangents are more than
///    90° apart, by bisection on the direction; the motion comes to rest there. (A turn of
///    more than 90° between two samples that is no cusp — a loop too tight for the sampling,
///    or a join turning by more than 90° whatever the corner angle — is treated the same
///    way.)
/// 4. **Boundary speeds.** A forward pass sets each zone's exit speed to the fastest
///    reachable from its entry speed within its length (the exact minimum distance of a
///    jerk-limited speed change with zero acceleration at both ends), capped by the limits
///    of both adjacent zones and the cap at its end (0 at corners and cusps); a backward
///    pass lowers entry speeds to what can still brake to the exit speed. The path starts
///    and ends at rest.
/// 5. **Profiles.** Each zone gets the fastest double S (or trapezoid) from its entry to
///    its exit speed under its limits, cruising at most at its speed limit, with zero
///    acceleration at its ends: `s`, `v` and `a` are continuous across zones (the jerk
///    steps there).
/// 6. **Transitions.** Where the speed rises (or falls) on both sides of a boundary, the
///    stretch from the start of the change before it to the end of the change after it is
///    replaced by the time-optimal motion between those two states under the tighter
///    limits of the two zones (the one-dimensional online solver, [`solve_axis`](crate::solve_axis)):
///    it passes the boundary with acceleration instead of flattening out there. It is kept
///    only where it is faster and keeps each zone's speed, acceleration and jerk limits on
///    its part of the zone (where the faster rise would pass the speed limit of the zone
///    before the boundary, the boundary keeps its zero acceleration).
///
/// The plan is made for one control rate: compile it at that rate
/// ([`PathTiming::compile`](crate::PathTiming::compile) does).
///
/// ```
/// use strak_trajectory::{PlanOptions, ProfileShape};
/// let o = PlanOptions::new()
///     .with_shape(ProfileShape::Trapezoid)
///     .with_samples(2048)
///     .with_zone_tolerance(0.1)
///     .with_centripetal_share(0.3)
///     .with_feed_share(0.2)
///     .with_rate(4_000.0);
/// assert_eq!(o.samples(), 2048);
/// assert_eq!(o.zone_tolerance(), 0.1);
/// assert_eq!(o.centripetal_share(), 0.3);
/// assert_eq!((o.feed_share(), o.rate()), (0.2, 4_000.0));
/// assert_eq!(PlanOptions::default(), PlanOptions::new());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PlanOptions {
    shape: ProfileShape,
    samples: usize,
    zone_tolerance: f64,
    centripetal_share: f64,
    corner_angle: f64,
    feed_share: f64,
    rate: f64,
    /// The axes that shape the path (the first ones): the norms of speed, acceleration,
    /// jerk and curvature are taken over them; the others ride along (a stream's
    /// [`StreamOptions::with_path_axes`](crate::StreamOptions::with_path_axes)).
    path_axes: usize,
}

impl Default for PlanOptions {
    fn default() -> Self {
        Self::new()
    }
}

impl PlanOptions {
    /// The default control rate in Hz.
    pub const DEFAULT_RATE: f64 = 1_000.0;
    /// The default share of the acceleration and jerk limits reserved for feed changes (the
    /// same as [`CompileOptions::DEFAULT_FEED_SHARE`](crate::CompileOptions::DEFAULT_FEED_SHARE)).
    pub const DEFAULT_FEED_SHARE: f64 = 0.25;
    /// The shortest jerk phase to a zone's acceleration limit, in ticks of the plan's rate:
    /// a zone's jerk limit is at most `a_z·f / MIN_JERK_TICKS`.
    pub const MIN_JERK_TICKS: f64 = 16.0;

    /// The defaults: S-curve, 1024 sampling intervals, zone tolerance 0.05 (5 %),
    /// centripetal share 0.5, corner angle 10⁻⁴ rad, feed share ¼, 1 kHz.
    pub const fn new() -> Self {
        PlanOptions {
            shape: ProfileShape::SCurve,
            samples: 1024,
            zone_tolerance: 0.05,
            centripetal_share: 0.5,
            corner_angle: 1e-4,
            feed_share: Self::DEFAULT_FEED_SHARE,
            rate: Self::DEFAULT_RATE,
            path_axes: usize::MAX,
        }
    }

    /// The velocity profile of the zones.
    pub const fn with_shape(mut self, shape: ProfileShape) -> Self {
        self.shape = shape;
        self
    }

    /// The number of sampling intervals along the parameter (`1 ..= 2²⁰`; each costs two
    /// evaluations of `c'`, `c''` and `c'''`).
    pub const fn with_samples(mut self, samples: usize) -> Self {
        self.samples = samples;
        self
    }

    /// The relative spread of the speed limit allowed inside one zone (finite, `≥ 0`; 0
    /// merges only equal limits).
    pub const fn with_zone_tolerance(mut self, tolerance: f64) -> Self {
        self.zone_tolerance = tolerance;
        self
    }

    /// The share `q` (in `(0, 1)`) of the acceleration and jerk limits that the turning of
    /// the path may take at the speed limit: the centripetal acceleration `v²κ ≤ q·a_max`
    /// and `v²|κN_i| ≤ q·a_i` per axis, the turning jerk `v³|x_sss| ≤ q·j_max`, and the
    /// velocity step at a join passed at speed. The rest is left for speed changes along the
    /// path. A larger share corners faster and accelerates more gently in curves.
    pub const fn with_centripetal_share(mut self, share: f64) -> Self {
        self.centripetal_share = share;
        self
    }

    /// The turn of the tangent at a join of pieces above which the motion stops there, in
    /// radians (finite, `> 0`). Any value keeps the limits: a join with a smaller turn is
    /// passed at the speed its velocity step allows (see the algorithm above), which for a
    /// visible turn is a crawl, so a larger angle rarely saves time.
    pub const fn with_corner_angle(mut self, radians: f64) -> Self {
        self.corner_angle = radians;
        self
    }

    /// The share (in `[0, 1)`) of the acceleration and jerk limits, path and per axis,
    /// reserved for feed changes: the motion is planned with `1 − share` of them, and the
    /// sampler's feed override, hold and resume ramp within the rest. With 0 the motion
    /// uses the full limits and a feed change keeps them only once a
    /// [`FeedGuard`](crate::FeedGuard) has found when and how fast it can ramp.
    pub const fn with_feed_share(mut self, share: f64) -> Self {
        self.feed_share = share;
        self
    }

    /// The control rate in Hz the plan is compiled and played at (100 Hz ..= 100 kHz):
    /// it sets the shortest jerk phase and the speed at joins passed at speed.
    pub const fn with_rate(mut self, rate_hz: f64) -> Self {
        self.rate = rate_hz;
        self
    }

    /// These options with the first `axes` axes shaping the path (see the field).
    pub(crate) const fn with_path_axes(mut self, axes: usize) -> Self {
        self.path_axes = axes;
        self
    }

    /// How many of the first axes shape the path (all of them: `usize::MAX`).
    pub(crate) const fn path_axes(&self) -> usize {
        self.path_axes
    }

    /// The turn at a join above which the motion stops there (radians).
    pub const fn corner_angle(&self) -> f64 {
        self.corner_angle
    }

    /// The velocity profile of the zones.
    pub const fn shape(&self) -> ProfileShape {
        self.shape
    }

    /// The number of sampling intervals.
    pub const fn samples(&self) -> usize {
        self.samples
    }

    /// The relative spread of the speed limit inside one zone.
    pub const fn zone_tolerance(&self) -> f64 {
        self.zone_tolerance
    }

    /// The share of the limits the turning of the path may take.
    pub const fn centripetal_share(&self) -> f64 {
        self.centripetal_share
    }

    /// The share of the acceleration and jerk limits reserved for feed changes.
    pub const fn feed_share(&self) -> f64 {
        self.feed_share
    }

    /// The control rate in Hz.
    pub const fn rate(&self) -> f64 {
        self.rate
    }

    /// What a motion planned under `limits` with these options keeps to at feed 1: the
    /// velocities, and the accelerations and jerk less the feed share these options leave
    /// free for feed ramps (no jerk limit for trapezoids).
    pub(crate) fn promised<const A: usize>(&self, limits: &Limits<A>) -> MotionLimits {
        let keep = 1.0 - self.feed_share();
        let jerk = match self.shape {
            ProfileShape::SCurve => keep * limits.jerk(),
            ProfileShape::Trapezoid => f64::INFINITY,
        };
        let mut promised = MotionLimits::new(limits.velocity(), keep * limits.acceleration(), jerk);
        let axes = limits
            .axis_velocity()
            .into_iter()
            .zip(limits.axis_acceleration());
        let slots = promised
            .axis_velocity
            .iter_mut()
            .zip(promised.axis_acceleration.iter_mut());
        for ((pv, pa), (v, a)) in slots.zip(axes) {
            (*pv, *pa) = (v, keep * a);
        }
        promised
    }

    /// Checks the settings.
    ///
    /// # Errors
    /// [`Error::InvalidRate`] for a rate outside 100 Hz ..= 100 kHz (or NaN);
    /// [`Error::InvalidLimit`] for any other setting out of range.
    pub(crate) fn validate(&self) -> Result<(), Error> {
        if !(self.rate >= RATE_RANGE.0 && self.rate <= RATE_RANGE.1) {
            return Err(Error::InvalidRate);
        }
        let share = |s: f64| s > 0.0 && s < 1.0;
        let tol = self.zone_tolerance;
        if (1..=MAX_SAMPLES).contains(&self.samples)
            && share(self.centripetal_share)
            && (self.feed_share == 0.0 || share(self.feed_share))
            && tol.is_finite()
            && tol >= 0.0
            && self.corner_angle.is_finite()
            && self.corner_angle > 0.0
        {
            Ok(())
        } else {
            Err(Error::InvalidLimit)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn validation() {
        assert_eq!(PlanOptions::new().validate(), Ok(()));
        for rate in [99.9, 100_000.1, f64::NAN, 0.0, f64::INFINITY] {
            assert_eq!(
                PlanOptions::new().with_rate(rate).validate(),
                Err(Error::InvalidRate),
                "{rate}"
            );
        }
        for ok in [100.0, 100_000.0] {
            assert_eq!(PlanOptions::new().with_rate(ok).validate(), Ok(()));
        }
        for share in [1.0, -0.1, f64::NAN] {
            assert_eq!(
                PlanOptions::new().with_feed_share(share).validate(),
                Err(Error::InvalidLimit),
                "{share}"
            );
        }
        assert_eq!(PlanOptions::new().with_feed_share(0.9).validate(), Ok(()));
        assert_eq!(PlanOptions::new().with_feed_share(0.0).validate(), Ok(()));
        assert_eq!(
            PlanOptions::DEFAULT_FEED_SHARE,
            crate::CompileOptions::DEFAULT_FEED_SHARE
        );
    }
}
