//! Points of a curve where the motion must slow down or stop: joins of pieces where the
//! tangent turns (a corner, or a smaller turn passed at a bounded speed), and cusps, where the
//! tangent reverses inside a piece.
//!
//! At a join where the unit tangent steps from `T_L` to `T_R` (a turn by `θ`,
//! `|ΔT| = |T_R − T_L| = 2·sin(θ/2)`), a motion at speed `v` has the velocity step `v·ΔT`.
//! In continuous time no finite acceleration follows it; played at `f` ticks per second, the
//! step, were it made within one tick `T = 1/f`, shows in the samples as an acceleration
//! `v·|ΔT|/T` and a jerk `v·|ΔT|/T²`. So a join is passed at most at the speed for which
//! these stay within the centripetal share `q` of the limits (the turning of the path):
//!
//! ```text
//! v·|ΔT| ≤ q·min(a·T, j·T²),   v·|ΔT_i| ≤ q·a_i·T per axis
//! ```
//!
//! and a join that turns by more than the corner angle is a corner, where the motion stops.
//! A step within the rounding of the tangents (`64·ε` of the curve's scalar, relative to
//! `max(1, |c'|)`) is no turn: the positions carry that rounding anyway.
//!
//! Where the tangent is continuous but the curvature vector steps by `Δk` (a line meeting an
//! arc tangentially), the acceleration steps by `v²·|Δk|`, which the samples show as a jerk
//! `v²·|Δk|/T`; so such a join is passed at most at
//!
//! ```text
//! v²·|Δk| ≤ q·j·T
//! ```
//!
//! (no cap without a jerk limit). A step within `1024·ε` of the curvatures is no step.

use strak_curves::{ParamCurveDeriv, Point, Scalar, ScalarOf};

use super::limits::Limits;
use super::options::PlanOptions;
use super::{greater, to_param};

/// Bisection steps to locate a cusp (the loop ends earlier when the interval no longer
/// shrinks in the curve's scalar).
const CUSP_STEPS: usize = 200;

/// The unit tangent `c'/|c'|` at `u` in `f64` (`None` where `c'` vanishes or is not
/// finite), and `|c'|`, in the first `path` axes (the others, which ride along, are 0).
pub(super) fn direction<C: ParamCurveDeriv, const A: usize>(
    curve: &C,
    us: ScalarOf<C>,
    path: usize,
) -> Option<([f64; A], f64)> {
    let d = curve.deriv(us, 1);
    let mut t = [0.0; A];
    let mut n2 = 0.0;
    let dim = <C::Point as Point>::DIM.min(path);
    for (i, slot) in t.iter_mut().enumerate().take(dim) {
        let x = d.coord(i).to_f64();
        *slot = x;
        n2 += x * x;
    }
    let n = libm::sqrt(n2);
    if !(greater(n, 0.0) && n.is_finite()) {
        return None;
    }
    Some((t.map(|x| x / n), n))
}

/// The curvature vector `(c'' − (c''·T)·T)/|c'|²` at `u`, where the unit tangent is `t`
/// and `|c'| = speed`, in the first `path` axes (the others are 0).
fn curvature<C: ParamCurveDeriv, const A: usize>(
    curve: &C,
    u: ScalarOf<C>,
    (t, speed): (&[f64; A], f64),
    path: usize,
) -> [f64; A] {
    let d = curve.deriv(u, 2);
    let mut c2 = [0.0; A];
    let dim = <C::Point as Point>::DIM.min(path);
    for (i, slot) in c2.iter_mut().enumerate().take(dim) {
        *slot = d.coord(i).to_f64();
    }
    let along = dot(&c2, t);
    core::array::from_fn(|i| (c2[i] - along * t[i]) / (speed * speed))
}

fn dot<const A: usize>(a: &[f64; A], b: &[f64; A]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// How joins are passed: the corner angle and the largest velocity step at speed.
pub(super) struct JoinRule<const A: usize> {
    cos_corner: f64,
    /// `q·min(a·T, j·T²)`: the largest `v·|ΔT|`.
    step: f64,
    /// `q·a_i·T` per axis: the largest `v·|ΔT_i|`.
    axis_step: [f64; A],
    /// `q·j·T`: the largest `v²·|Δk|`.
    curvature_step: f64,
    /// The axes that shape the path (see [`PlanOptions`]).
    path: usize,
}

impl<const A: usize> JoinRule<A> {
    /// The rule for the planned `limits` (`jerk = ∞`: a trapezoid, no jerk limit).
    pub(super) fn new(limits: &Limits<A>, jerk: f64, options: &PlanOptions) -> Self {
        let q = options.centripetal_share();
        let period = 1.0 / options.rate();
        let step = q * (limits.acceleration() * period).min(jerk * period * period);
        JoinRule {
            cos_corner: libm::cos(options.corner_angle()),
            step,
            axis_step: limits.axis_acceleration().map(|a| q * a * period),
            curvature_step: q * jerk * period,
            path: options.path_axes(),
        }
    }

    /// The largest speed at the join after piece `piece`: 0 at a corner, the speed whose
    /// velocity step fits the rule for a smaller turn, `∞` for no turn (or where either
    /// tangent vanishes: a cusp there is found by [`locate_reversal`]).
    pub(super) fn cap<C: ParamCurveDeriv>(&self, curve: &C, piece: usize) -> f64 {
        let (lo, u_join) = curve.piece_domain(piece);
        let (lo, u) = (lo.to_f64(), u_join.to_f64());
        let step = 2.0 * ScalarOf::<C>::EPSILON.to_f64() * u.abs().max(1.0);
        let left_at = to_param(curve, (u - step).max(lo));
        let (Some((left, sl)), Some((right, sr))) = (
            direction::<C, A>(curve, left_at, self.path),
            direction::<C, A>(curve, u_join, self.path),
        ) else {
            return f64::INFINITY;
        };
        if dot(&left, &right) < self.cos_corner {
            return 0.0;
        }
        let mut cap = self.curvature_cap::<ScalarOf<C>>(
            curvature(curve, left_at, (&left, sl), self.path),
            curvature(curve, u_join, (&right, sr), self.path),
        );
        let delta: [f64; A] = core::array::from_fn(|i| right[i] - left[i]);
        let noise = 64.0 * ScalarOf::<C>::EPSILON.to_f64() * (1.0 / sl.min(sr)).max(1.0);
        let jump = libm::sqrt(dot(&delta, &delta));
        if jump <= noise {
            return cap;
        }
        cap = cap.min(self.step / jump);
        for (d, s) in delta.iter().zip(&self.axis_step) {
            if d.abs() > noise {
                cap = cap.min(s / d.abs());
            }
        }
        cap
    }

    /// The largest speed at a join where the curvature vector steps from `left` to
    /// `right`: `√(q·j·T / |Δk|)`, `∞` for a step within the rounding.
    fn curvature_cap<S: Scalar>(&self, left: [f64; A], right: [f64; A]) -> f64 {
        let delta: [f64; A] = core::array::from_fn(|i| right[i] - left[i]);
        let step = libm::sqrt(dot(&delta, &delta));
        let size = libm::sqrt(dot(&left, &left)) + libm::sqrt(dot(&right, &right));
        if step <= 1024.0 * S::EPSILON.to_f64() * size {
            return f64::INFINITY;
        }
        libm::sqrt(self.curvature_step / step)
    }
}

/// The parameter in `(u_a, u_b)` where the tangent leaves the half-space of `t_a` (the
/// unit tangent at `u_a`; the tangent at `u_b` points away from it), by bisection: a cusp
/// (or a turn too tight for the sampling). A parameter where `c'` vanishes is returned at
/// once.
pub(super) fn locate_reversal<C: ParamCurveDeriv, const A: usize>(
    curve: &C,
    (u_a, t_a): (f64, [f64; A]),
    u_b: f64,
    path: usize,
) -> f64 {
    let (mut lo, mut hi) = (u_a, u_b);
    for _ in 0..CUSP_STEPS {
        let mid = 0.5 * (lo + hi);
        let (m, l, h) = (
            to_param(curve, mid),
            to_param(curve, lo),
            to_param(curve, hi),
        );
        if !(mid > lo && mid < hi) || m == l || m == h {
            break;
        }
        match direction::<C, A>(curve, m, path) {
            None => return mid,
            Some((t, _)) if dot(&t, &t_a) > 0.0 => lo = mid,
            Some(_) => hi = mid,
        }
    }
    0.5 * (lo + hi)
}

/// Whether the tangents `t_a`, `t_b` of two neighbouring samples are more than 90° apart.
pub(super) fn reverses<const A: usize>(t_a: &[f64; A], t_b: &[f64; A]) -> bool {
    dot(t_a, t_b) < 0.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use strak_curves::{BSpline, Bezier};

    fn rule(options: &PlanOptions) -> JoinRule<2> {
        let l = Limits::<2>::new(200.0, 2000.0, 50_000.0).unwrap();
        JoinRule::new(&l, l.jerk(), options)
    }

    /// A polyline (0,0) → (50,0) → 50 more at the turn `deg`.
    fn polyline(deg: f64) -> BSpline<[f64; 2], 4, 8> {
        let th = deg.to_radians();
        let pts = [
            [0.0, 0.0],
            [50.0, 0.0],
            [50.0 + 50.0 * th.cos(), 50.0 * th.sin()],
        ];
        BSpline::clamped_uniform(1, &pts, 0.0, 1.0).unwrap()
    }

    #[test]
    fn corners_stop_smaller_turns_are_capped() {
        let o = PlanOptions::new();
        // 30°: a corner
        assert_eq!(rule(&o).cap(&polyline(30.0), 0), 0.0);
        // 10⁻³ rad under a corner angle of 1 rad: |ΔT| = 10⁻³,
        // q·min(a T, j T²) = 0.5·min(2, 0.05) = 0.025 at 1 kHz → v ≤ 25
        let o = o.with_corner_angle(1.0);
        let cap = rule(&o).cap(&polyline(1e-3_f64.to_degrees()), 0);
        assert!((cap - 25.0).abs() < 1e-6 * 25.0, "{cap}");
        // ten times the rate: a hundredth (the jerk term binds)
        let cap10 = rule(&o.with_rate(10_000.0)).cap(&polyline(1e-3_f64.to_degrees()), 0);
        assert!((cap10 - 0.25).abs() < 1e-6, "{cap10}");
        // a straight join: no cap
        assert_eq!(rule(&o).cap(&polyline(0.0), 0), f64::INFINITY);
    }

    /// A line meeting an arc of radius 2 tangentially: the curvature steps by 0.5, so
    /// `v ≤ √(q·j·T/|Δk|) = √(0.5·50 000·10⁻³/0.5) = √50`; without a jerk limit, no cap.
    #[test]
    fn a_curvature_step_caps_the_join() {
        let c = crate::plan::testcurves::LineArcLine::new(100.0, 2.0, 100.0);
        let cap = rule(&PlanOptions::new()).cap(&c, 0);
        assert!((cap - 50.0_f64.sqrt()).abs() < 1e-9, "{cap}");
        assert!((rule(&PlanOptions::new()).cap(&c, 1) - cap).abs() < 1e-9);
        let l = Limits::<2>::new(200.0, 2000.0, 50_000.0).unwrap();
        let trapezoid = JoinRule::new(&l, f64::INFINITY, &PlanOptions::new());
        assert_eq!(trapezoid.cap(&c, 0), f64::INFINITY);
    }

    #[test]
    fn axis_acceleration_caps_the_join() {
        let l = Limits::<2>::new(200.0, 2000.0, 1e12)
            .and_then(|l| l.with_axis_acceleration([f64::INFINITY, 100.0]))
            .unwrap();
        let o = PlanOptions::new().with_corner_angle(1.0);
        let r = JoinRule::new(&l, l.jerk(), &o);
        // |ΔT| ≈ |ΔT_y| = 10⁻³ (x changes by 5·10⁻⁷): q·a_y·T = 0.05 → v ≤ 50
        let cap = r.cap(&polyline(1e-3_f64.to_degrees()), 0);
        assert!((cap - 50.0).abs() < 1e-3, "{cap}");
    }

    #[test]
    fn cusp_is_located() {
        // c(u) = (20u − 25u², 0): c' = 20 − 50u vanishes at u = 0.4 and reverses
        let c = Bezier::new([[0.0, 0.0], [10.0, 0.0], [-5.0, 0.0]]).unwrap();
        let ta = direction::<_, 2>(&c, 0.1, 2).unwrap().0;
        let tb = direction::<_, 2>(&c, 0.7, 2).unwrap().0;
        assert!(reverses(&ta, &tb));
        let u = locate_reversal(&c, (0.1, ta), 0.7, 2);
        assert!((u - 0.4).abs() < 1e-12, "{u}");
        assert!(direction::<_, 2>(&c, 0.4, 2).is_none());
        // f32: located to the scalar's resolution
        let c = Bezier::new([[0.0_f32, 0.0], [10.0, 0.0], [-5.0, 0.0]]).unwrap();
        let ta = direction::<_, 2>(&c, 0.1, 2).unwrap().0;
        let u = locate_reversal(&c, (0.1, ta), 0.7, 2);
        assert!((u - 0.4).abs() < 1e-6, "{u}");
    }
}
