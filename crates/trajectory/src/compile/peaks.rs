//! The kinematic peaks of the compiled pieces and the slow-down that keeps them within a
//! time law's limits.

use strak_curves::MAX_DIM;

use crate::error::{Error, Quantity};
use crate::plan::MotionLimits;

/// Bisection steps for a critical point of the speed (each halves the bracket; 64 exhaust
/// the `f64` resolution of any bracket inside a piece).
const BISECTION_STEPS: usize = 64;

/// Relative slack of the comparison with a limit: the `f64` rounding of the polynomial
/// coefficients and of the peaks themselves.
pub(super) const LIMIT_SLACK: f64 = 1e-12;

/// How far below a speed limit (relative) the speed bound of a piece must lie to stand in
/// for its exact speed peak ([`Peaks::of_piece_below`]): far beyond the rounding of either,
/// which both follow the same speed from above or to within rounding.
const BOUND_MARGIN: f64 = 1e-9;

/// The largest speed `|ẋ|`, acceleration `|ẍ|` and jerk `|x⃛|` (Euclidean norms over the
/// axes) of a motion, in units/s, units/s², units/s³, and per axis the largest `|ẋᵢ|` and
/// `|ẍᵢ|` (the first [`MAX_DIM`] axes: a point has no more).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct Peaks {
    pub(super) velocity: f64,
    pub(super) acceleration: f64,
    pub(super) jerk: f64,
    /// An upper bound of the speed from three samples per piece (see
    /// [`Peaks::of_piece`]), which the feed ramps are derived from.
    pub(super) velocity_bound: f64,
    /// A bound of the tangential acceleration `d|ẋ|/dt` as the samples show it at any feed
    /// (computed only when asked for: [`Tangential`](super::tangential::Tangential); 0
    /// otherwise).
    pub(super) tangential: f64,
    pub(super) axis_velocity: [f64; MAX_DIM],
    pub(super) axis_acceleration: [f64; MAX_DIM],
}

impl Peaks {
    /// The larger of each.
    pub(super) fn max(self, other: Peaks) -> Peaks {
        let each = |a: [f64; MAX_DIM], b: [f64; MAX_DIM]| core::array::from_fn(|i| a[i].max(b[i]));
        Peaks {
            velocity: self.velocity.max(other.velocity),
            acceleration: self.acceleration.max(other.acceleration),
            jerk: self.jerk.max(other.jerk),
            velocity_bound: self.velocity_bound.max(other.velocity_bound),
            tangential: self.tangential.max(other.tangential),
            axis_velocity: each(self.axis_velocity, other.axis_velocity),
            axis_acceleration: each(self.axis_acceleration, other.axis_acceleration),
        }
    }

    /// The peaks of one piece `p(i) = a + b i + c i² + d i³` per axis (`i` in ticks,
    /// `0 ≤ i ≤ n`, tick period `period`).
    ///
    /// The jerk is constant; `ẍ` is affine in `i`, so its norm (convex) is largest at an end.
    /// The squared speed `|ẋ|² = Σ (b + 2ci + 3di²)²/T²` is a quartic whose derivative
    /// `g(i) = Σ 2bc + (6bd + 4c²)i + 18cd·i² + 18d²·i³` is a cubic: the speed is largest at
    /// an end or at a root of `g`. The roots of `g'` split `[0, n]` into at most three
    /// intervals on which `g` is monotone; a sign change of `g` on one of them brackets one
    /// root, found by bisection. So the speed peak is exact up to rounding.
    ///
    /// Per axis the velocity `(b + 2ci + 3di²)/T` is largest in magnitude at an end or at
    /// its vertex `i = −c/(3d)`, the acceleration `(2c + 6di)/T²` at an end.
    ///
    /// The speed bound: `ẋ(s + δ) = ẋ(s) + δ·ẍ(s) + ½δ²·x⃛` exactly; around the samples
    /// `s ∈ {0, n/2, n}` with `|δ| ≤ Δ = (n/4)·T`,
    /// `|ẋ| ≤ max(|ẋ(s) + Δẍ(s)|, |ẋ(s) − Δẍ(s)|) + ½Δ²|x⃛|` (the norm of an affine function
    /// of `δ` is largest at an end of the interval).
    pub(super) fn of_piece<const A: usize>(coeffs: &[[f64; 4]; A], n: f64, period: f64) -> Peaks {
        Self::of_piece_below(coeffs, n, period, f64::NEG_INFINITY)
    }

    /// [`of_piece`](Self::of_piece), but where the speed bound lies at or below
    /// `speed_limit · (1 − BOUND_MARGIN)` the bound stands in for the exact speed peak: a
    /// check against a speed limit (with [`LIMIT_SLACK`]) comes out the same with either,
    /// and the bound costs no roots of the speed's derivative.
    pub(super) fn of_piece_below<const A: usize>(
        coeffs: &[[f64; 4]; A],
        n: f64,
        period: f64,
        speed_limit: f64,
    ) -> Peaks {
        let sq = |f: &dyn Fn(&[f64; 4]) -> f64| coeffs.iter().map(|c| f(c) * f(c)).sum::<f64>();
        let tt = period * period;
        let acc = |i: f64| libm::sqrt(sq(&|&[_, _, c, d]| (2.0 * c + 6.0 * d * i) / tt));
        let velocity_bound = speed_bound(coeffs, n, period);
        let velocity =
            if velocity_bound.is_finite() && velocity_bound <= speed_limit * (1.0 - BOUND_MARGIN) {
                velocity_bound
            } else {
                speed_peak(coeffs, n, period)
            };
        let (axis_velocity, axis_acceleration) = axis_peaks(coeffs, n, period);
        Peaks {
            velocity,
            acceleration: acc(0.0).max(acc(n)),
            jerk: libm::sqrt(sq(&|c| 6.0 * c[3] / (tt * period))),
            velocity_bound,
            tangential: 0.0,
            axis_velocity,
            axis_acceleration,
        }
    }

    /// [`of_piece_below`](Self::of_piece_below) of a motion whose first `path` axes shape
    /// the path: the norms over those, the per-axis peaks of every axis.
    pub(super) fn of_shaped_piece_below<const A: usize>(
        coeffs: &[[f64; 4]; A],
        n: f64,
        period: f64,
        path: usize,
        speed_limit: f64,
    ) -> Peaks {
        if path >= A {
            return Self::of_piece_below(coeffs, n, period, speed_limit);
        }
        let mut shaped = *coeffs;
        for c in shaped.iter_mut().skip(path) {
            *c = [0.0; 4];
        }
        let mut peaks = Self::of_piece_below(&shaped, n, period, speed_limit);
        (peaks.axis_velocity, peaks.axis_acceleration) = axis_peaks(coeffs, n, period);
        peaks
    }

    /// The smallest factor `λ ≥ 1` by which slowing the motion down (time stretched by `λ`:
    /// speed `/λ`, acceleration `/λ²`, jerk `/λ³`) brings these peaks within `limits`, and the
    /// quantity that needs the most; `(1, None)` when they are within already (up to
    /// rounding).
    ///
    /// # Errors
    /// [`Error::Curve`] when a peak is not finite.
    pub(super) fn slowdown(&self, limits: &MotionLimits) -> Result<(f64, Option<Quantity>), Error> {
        let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
        if !(finite(&[self.velocity, self.acceleration, self.jerk, self.tangential])
            && finite(&self.axis_velocity)
            && finite(&self.axis_acceleration))
        {
            return Err(Error::Curve(strak_curves::Error::NonFinite));
        }
        let mut worst = (1.0, None);
        let mut consider = |quantity, peak: f64, limit: f64, power: f64| {
            if peak > limit * (1.0 + LIMIT_SLACK) {
                let factor = libm::pow(peak / limit, power);
                if factor > worst.0 {
                    worst = (factor, Some(quantity));
                }
            }
        };
        consider(Quantity::Velocity, self.velocity, limits.velocity, 1.0);
        let (a, a_limit) = (self.acceleration, limits.acceleration);
        consider(Quantity::Acceleration, a, a_limit, 0.5);
        consider(Quantity::Jerk, self.jerk, limits.jerk, 1.0 / 3.0);
        let (a, a_limit) = (self.tangential, limits.tangential_acceleration);
        consider(Quantity::TangentialAcceleration, a, a_limit, 0.5);
        for axis in 0..MAX_DIM {
            let (v, v_limit) = (self.axis_velocity[axis], limits.axis_velocity[axis]);
            consider(Quantity::AxisVelocity { axis }, v, v_limit, 1.0);
            let (a, a_limit) = (self.axis_acceleration[axis], limits.axis_acceleration[axis]);
            consider(Quantity::AxisAcceleration { axis }, a, a_limit, 0.5);
        }
        Ok(worst)
    }
}

/// The roots in `(0, n)`, ascending, of `g = d|ẋ|²/di` of a piece (the `g` of
/// [`Peaks::of_piece`]) where it changes sign: the speed's turning points inside the piece,
/// at most three.
pub(super) fn speed_turns<const A: usize>(coeffs: &[[f64; 4]; A], n: f64) -> ([f64; 3], usize) {
    // `g` of the coefficients divided by their largest magnitude: the same roots, and no
    // overflow in `g` or its discriminant for paths of any size.
    let scale = coeffs
        .iter()
        .flat_map(|&[_, b, c, d]| [b, c, d])
        .fold(0.0_f64, |m, x| m.max(libm::fabs(x)));
    let unit = if scale > 0.0 && scale.is_finite() {
        scale
    } else {
        1.0
    };
    let mut g = [0.0_f64; 4];
    for &[_, b, c, d] in coeffs {
        let (b, c, d) = (b / unit, c / unit, d / unit);
        g[0] += 2.0 * b * c;
        g[1] += 6.0 * b * d + 4.0 * c * c;
        g[2] += 18.0 * c * d;
        g[3] += 18.0 * d * d;
    }
    let (mut turns, mut count) = ([0.0; 3], 0);
    for_each_root(g, n, &mut |i| {
        if let Some(slot) = turns.get_mut(count) {
            *slot = i;
            count += 1;
        }
    });
    (turns, count)
}

/// The speed peak `|ẋ|` of [`Peaks::of_piece`]: the largest at the ends and at the speed's
/// turning points inside.
fn speed_peak<const A: usize>(coeffs: &[[f64; 4]; A], n: f64, period: f64) -> f64 {
    let speed2 = |i: f64| {
        coeffs
            .iter()
            .map(|&[_, b, c, d]| {
                let v = b + i * (2.0 * c + 3.0 * d * i);
                v * v
            })
            .sum::<f64>()
    };
    let mut best = speed2(0.0).max(speed2(n));
    let (turns, count) = speed_turns(coeffs, n);
    for &i in turns.get(..count).unwrap_or(&[]) {
        best = best.max(speed2(i));
    }
    libm::sqrt(best) / period
}

/// The per-axis velocity and acceleration peaks of [`Peaks::of_piece`].
fn axis_peaks<const A: usize>(
    coeffs: &[[f64; 4]; A],
    n: f64,
    period: f64,
) -> ([f64; MAX_DIM], [f64; MAX_DIM]) {
    let (mut velocity, mut acceleration) = ([0.0; MAX_DIM], [0.0; MAX_DIM]);
    for ((&[_, b, c, d], v), a) in coeffs.iter().zip(&mut velocity).zip(&mut acceleration) {
        let slope = |i: f64| libm::fabs(b + i * (2.0 * c + 3.0 * d * i));
        let mut peak = slope(0.0).max(slope(n));
        let vertex = -c / (3.0 * d);
        if vertex > 0.0 && vertex < n {
            peak = peak.max(slope(vertex));
        }
        *v = peak / period;
        *a = libm::fabs(2.0 * c).max(libm::fabs(2.0 * c + 6.0 * d * n)) / (period * period);
    }
    (velocity, acceleration)
}

/// The speed bound of [`Peaks::of_piece`].
fn speed_bound<const A: usize>(coeffs: &[[f64; 4]; A], n: f64, period: f64) -> f64 {
    let vel = |i: f64, a: usize| {
        coeffs.get(a).map_or(0.0, |[_, b, c, d]| {
            (b + i * (2.0 * c + 3.0 * d * i)) / period
        })
    };
    let acc = |i: f64, a: usize| {
        coeffs.get(a).map_or(0.0, |[_, _, c, d]| {
            (2.0 * c + 6.0 * d * i) / (period * period)
        })
    };
    let norm = |f: &dyn Fn(usize) -> f64| libm::sqrt((0..A).map(|a| f(a) * f(a)).sum());
    let jerk = norm(&|a| coeffs.get(a).map_or(0.0, |c| 6.0 * c[3]) / (period * period * period));
    let delta = 0.25 * n * period;
    let mut v_max = 0.0_f64;
    for s in [0.0, 0.5 * n, n] {
        let plus = norm(&|a| vel(s, a) + delta * acc(s, a));
        let minus = norm(&|a| vel(s, a) - delta * acc(s, a));
        v_max = v_max.max(plus.max(minus) + 0.5 * delta * delta * jerk);
    }
    v_max
}

/// Calls `out` with every root in `(0, n)` of the cubic `g[0] + g[1] i + g[2] i² + g[3] i³`
/// that is a sign change on an interval where `g` is monotone (enough for the extrema of
/// the quartic whose derivative `g` is).
fn for_each_root(g: [f64; 4], n: f64, out: &mut impl FnMut(f64)) {
    let eval = |i: f64| g[0] + i * (g[1] + i * (g[2] + i * g[3]));
    // g' = g1 + 2 g2 i + 3 g3 i²: its roots inside (0, n), sorted.
    let (qa, qb, qc) = (3.0 * g[3], 2.0 * g[2], g[1]);
    let mut cuts = [0.0, n, n, n];
    let mut count = 1;
    let mut push = |x: f64| {
        if x > 0.0
            && x < n
            && let Some(slot) = cuts.get_mut(count)
        {
            *slot = x;
            count += 1;
        }
    };
    if qa != 0.0 {
        let disc = qb * qb - 4.0 * qa * qc;
        if disc >= 0.0 {
            let r = libm::sqrt(disc);
            let (x0, x1) = ((-qb - r) / (2.0 * qa), (-qb + r) / (2.0 * qa));
            push(x0.min(x1));
            push(x0.max(x1));
        }
    } else if qb != 0.0 {
        push(-qc / qb);
    }
    if let Some(slot) = cuts.get_mut(count) {
        *slot = n;
    }
    for w in cuts.get(..=count).unwrap_or(&[]).windows(2) {
        if let [lo, hi] = *w
            && let Some(x) = bisect(&eval, lo, hi)
        {
            out(x);
        }
    }
}

/// A root of the monotone `f` in `[lo, hi]` by bisection, if `f` changes sign there.
fn bisect(f: &impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> Option<f64> {
    let (flo, fhi) = (f(lo), f(hi));
    if !(flo.is_finite() && fhi.is_finite()) || (flo > 0.0) == (fhi > 0.0) {
        return None;
    }
    let rising = fhi > flo;
    for _ in 0..BISECTION_STEPS {
        let mid = 0.5 * (lo + hi);
        if !(mid > lo && mid < hi) {
            break;
        }
        if (f(mid) > 0.0) == rising {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Some(0.5 * (lo + hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The speed of a piece sampled densely.
    fn sampled_speed<const A: usize>(coeffs: &[[f64; 4]; A], n: f64, period: f64) -> f64 {
        (0..=10_000)
            .map(|k| {
                let i = n * f64::from(k) / 10_000.0;
                let s: f64 = coeffs
                    .iter()
                    .map(|&[_, b, c, d]| {
                        let v = b + i * (2.0 * c + 3.0 * d * i);
                        v * v
                    })
                    .sum();
                s.sqrt() / period
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn speed_peak_is_exact() {
        let period = 1e-3;
        // an interior maximum (a speed bump), a monotone piece, a turning 2-D piece
        let cases: [[[f64; 4]; 2]; 3] = [
            [[0.0, 0.1, 0.01, -1e-4], [0.0, 0.0, 0.0, 0.0]],
            [[0.0, 0.1, 0.001, 1e-6], [0.0, 0.05, 0.0, 0.0]],
            [[0.0, 0.2, -0.004, 1e-5], [0.0, -0.1, 0.003, -2e-5]],
        ];
        for coeffs in cases {
            let p = Peaks::of_piece(&coeffs, 100.0, period);
            let s = sampled_speed(&coeffs, 100.0, period);
            assert!(p.velocity >= s * (1.0 - 1e-12), "{} < {s}", p.velocity);
            assert!(p.velocity <= s * (1.0 + 1e-7), "{} > {s}", p.velocity);
            assert!(
                p.velocity_bound >= p.velocity,
                "{} {}",
                p.velocity_bound,
                p.velocity
            );
        }
        // from rest to an interior peak, in units of 10¹³⁷: unscaled, the discriminant of g'
        // overflows, and g(0) = 0 brackets no root on [0, n]
        let huge = [[0.0, 0.0, 0.01e137, -1e133]];
        let p = Peaks::of_piece(&huge, 60.0, period);
        let want = 0.01 * 0.01 / (3.0 * 1e-4) / period * 1e137;
        assert!(
            (p.velocity - want).abs() < 1e-9 * want,
            "{} {want}",
            p.velocity
        );
        // the bump: b + 2ci + 3di² peaks at i = −c/(3d) = 33.3
        let bump = [[0.0, 0.1, 0.01, -1e-4]];
        let want = (0.1 + 0.01 * 0.01 / (3.0 * 1e-4)) / period;
        let p = Peaks::of_piece(&bump, 60.0, period);
        assert!(
            (p.velocity - want).abs() < 1e-9 * want,
            "{} {want}",
            p.velocity
        );
        assert!((p.jerk - 6.0 * 1e-4 / (period * period * period)).abs() < 1e-3);
        // |ẍ| at the ends: 2c = 0.02 and 2c + 6d·60 = −0.016 (per tick²)
        let a_end = 0.02 / (period * period);
        assert!((p.acceleration - a_end).abs() < 1e-9 * a_end);
    }

    /// Far below a speed limit the bound stands in for the speed peak, and the check against
    /// the limits comes out the same; at the bound the peak is exact.
    #[test]
    fn the_bound_stands_in_below_the_speed_limit() {
        let period = 1e-3;
        let coeffs = [[0.0, 0.1, 0.01, -1e-4], [0.0, -0.05, 0.002, 1e-6]];
        let exact = Peaks::of_piece(&coeffs, 60.0, period);
        assert!(exact.velocity_bound > exact.velocity);
        let far = Peaks::of_piece_below(&coeffs, 60.0, period, 2.0 * exact.velocity_bound);
        assert_eq!(far.velocity, exact.velocity_bound);
        assert_eq!(
            Peaks {
                velocity: exact.velocity,
                ..far
            },
            exact
        );
        let limits = MotionLimits::new(2.0 * exact.velocity_bound, 1e12, 1e18);
        assert_eq!(far.slowdown(&limits), exact.slowdown(&limits));
        let near = Peaks::of_piece_below(&coeffs, 60.0, period, exact.velocity_bound);
        assert_eq!(near, exact);
    }

    #[test]
    fn slowdown_per_quantity() {
        let limits = MotionLimits::new(10.0, 100.0, 1000.0);
        let within = Peaks {
            velocity: 10.0,
            acceleration: 50.0,
            jerk: 1000.0,
            velocity_bound: 10.0,
            ..Peaks::default()
        };
        assert_eq!(within.slowdown(&limits), Ok((1.0, None)));
        let fast = Peaks {
            velocity: 10.5,
            acceleration: 121.0,
            jerk: 1000.0,
            velocity_bound: 11.0,
            ..Peaks::default()
        };
        // √(121/100) = 1.1 > 1.05
        let (f, q) = fast.slowdown(&limits).unwrap();
        assert!((f - 1.1).abs() < 1e-12 && q == Some(Quantity::Acceleration));
        let jerky = Peaks {
            jerk: 8000.0,
            ..within
        };
        let (f, q) = jerky.slowdown(&limits).unwrap();
        assert!((f - 2.0).abs() < 1e-12 && q == Some(Quantity::Jerk));
        let unbounded = MotionLimits {
            jerk: f64::INFINITY,
            ..limits
        };
        assert_eq!(jerky.slowdown(&unbounded), Ok((1.0, None)));
        let bad = Peaks {
            velocity: f64::NAN,
            ..within
        };
        assert!(bad.slowdown(&limits).is_err());
        // per axis: axis 1 at 1.2× its velocity limit, axis 0 at 1.21× its acceleration limit
        let mut per_axis = limits;
        per_axis.axis_velocity[1] = 5.0;
        per_axis.axis_acceleration[0] = 40.0;
        let mut axes = within;
        axes.axis_velocity[1] = 6.0;
        axes.axis_acceleration[0] = 48.4;
        let (f, q) = axes.slowdown(&per_axis).unwrap();
        assert!((f - 1.2).abs() < 1e-12 && q == Some(Quantity::AxisVelocity { axis: 1 }));
        axes.axis_velocity[1] = 5.0;
        let (f, q) = axes.slowdown(&per_axis).unwrap();
        assert!((f - 1.1).abs() < 1e-12 && q == Some(Quantity::AxisAcceleration { axis: 0 }));
        assert_eq!(axes.slowdown(&limits), Ok((1.0, None)));
    }

    /// The per-axis peaks of a piece against the piece sampled densely.
    #[test]
    fn axis_peaks_are_exact() {
        let period = 1e-3;
        // axis 0 with a velocity vertex inside, axis 1 monotone, axis 2 at rest
        let coeffs = [
            [0.0, 0.1, 0.01, -1e-4],
            [1.0, -0.05, 0.002, 1e-6],
            [3.0, 0.0, 0.0, 0.0],
        ];
        let n = 60.0;
        let p = Peaks::of_piece(&coeffs, n, period);
        for (a, &[_, b, c, d]) in coeffs.iter().enumerate() {
            let (mut v, mut acc) = (0.0_f64, 0.0_f64);
            for k in 0..=6_000 {
                let i = n * f64::from(k) / 6_000.0;
                v = v.max((b + i * (2.0 * c + 3.0 * d * i)).abs() / period);
                acc = acc.max((2.0 * c + 6.0 * d * i).abs() / (period * period));
            }
            let peak = p.axis_velocity[a];
            assert!(
                peak >= v * (1.0 - 1e-12) && peak <= v * (1.0 + 1e-7),
                "{a}: {peak} {v}"
            );
            assert!((p.axis_acceleration[a] - acc).abs() <= 1e-9 * acc, "{a}");
        }
        // the vertex of axis 0: i = −c/(3d) = 33.3, v = (0.1 + c²/(3d))/T
        let want = (0.1 + 0.01 * 0.01 / (3.0 * 1e-4)) / period;
        assert!((p.axis_velocity[0] - want).abs() < 1e-9 * want);
        assert_eq!(p.axis_velocity[3..], [0.0; MAX_DIM - 3]);
    }
}
