//! The speed limit `v_lim(s)` along a curve, sampled and grouped into zones of nearly
//! constant limit.
//!
//! At a parameter `u` with `c' = c'(u)`, `c'' = c''(u)` (in `f64`):
//!
//! ```text
//! T = c'/|c'|                                 unit tangent
//! κN = (c'' − (c''·T)·T) / |c'|²              curvature vector (κ = |κN|)
//! v_lim = min( v_max, √(a_max/κ), v_i/|T_i|, √(share·a_i/|κN_i|) )   over the axes i
//! ```
//!
//! The axis acceleration is `ẍ_i = s̈·T_i + ṡ²·κN_i`: the last term reserves the share
//! `share` of `a_i` for the centripetal part, and the zone's tangential limit
//! `(a_i − v_zone²·max|κN_i|)/max|T_i|` (at least `(1 − share)·a_i/max|T_i|`) the rest.

use heapless::Vec;
use strak_curves::{ArcLengthTable, ParamCurveDeriv, Point, Scalar};

use super::greater;
use super::motion::ProfileZone;
use super::path_timing::to_param;
use super::planner::PlanOptions;
use crate::error::Error;
use crate::limits::Limits;

/// The limits sampled at one parameter (or the worst over an interval).
#[derive(Clone, Copy, Debug)]
struct Local<const A: usize> {
    /// The speed limit.
    v: f64,
    /// Per axis `|T_i|`.
    tangent: [f64; A],
    /// Per axis `|κN_i|`.
    normal: [f64; A],
}

impl<const A: usize> Local<A> {
    /// No information: the path velocity limit, no axis load.
    fn neutral(v_max: f64) -> Self {
        Local {
            v: v_max,
            tangent: [0.0; A],
            normal: [0.0; A],
        }
    }

    /// The worst of both: the smaller speed limit, the larger axis loads.
    fn merge(&mut self, other: &Self) {
        self.v = self.v.min(other.v);
        for (a, b) in self.tangent.iter_mut().zip(other.tangent.iter()) {
            *a = a.max(*b);
        }
        for (a, b) in self.normal.iter_mut().zip(other.normal.iter()) {
            *a = a.max(*b);
        }
    }
}

/// The limits at the parameter `u`; `None` where `c'(u) = 0` (no tangent: the sample is
/// skipped, its neighbours decide).
fn local<C, const A: usize>(
    curve: &C,
    u: f64,
    limits: &Limits<A>,
    share: f64,
) -> Result<Option<Local<A>>, Error>
where
    C: ParamCurveDeriv,
{
    let us = to_param(curve, u);
    let d1 = curve.deriv(us, 1);
    let d2 = curve.deriv(us, 2);
    let dim = <C::Point as Point>::DIM;
    let (mut s11, mut s12) = (0.0, 0.0);
    for i in 0..dim {
        let (x1, x2) = (d1.coord(i).to_f64(), d2.coord(i).to_f64());
        s11 += x1 * x1;
        s12 += x1 * x2;
    }
    if !(s11.is_finite() && s12.is_finite()) {
        return Err(Error::Curve(strak_curves::Error::NonFinite));
    }
    if !greater(s11, 0.0) {
        return Ok(None);
    }
    let speed = libm::sqrt(s11);
    let along = s12 / s11;
    let mut kappa2 = 0.0;
    let mut out = Local::<A>::neutral(limits.velocity());
    for i in 0..dim {
        let (x1, x2) = (d1.coord(i).to_f64(), d2.coord(i).to_f64());
        let kn = (x2 - along * x1) / s11;
        kappa2 += kn * kn;
        if let Some(t) = out.tangent.get_mut(i) {
            *t = (x1 / speed).abs();
        }
        if let Some(n) = out.normal.get_mut(i) {
            *n = kn.abs();
        }
    }
    let kappa = libm::sqrt(kappa2);
    if !kappa.is_finite() {
        return Err(Error::Curve(strak_curves::Error::NonFinite));
    }
    let mut v = limits.velocity();
    if kappa > 0.0 {
        v = v.min(libm::sqrt(limits.acceleration() / kappa));
    }
    let (av, aa) = (limits.axis_velocity(), limits.axis_acceleration());
    for (((t, n), vi), ai) in out.tangent.iter().zip(&out.normal).zip(&av).zip(&aa) {
        if *t > 0.0 {
            v = v.min(vi / t);
        }
        if *n > 0.0 {
            v = v.min(libm::sqrt(share * ai / n));
        }
    }
    out.v = v;
    Ok(Some(out))
}

/// A zone being collected.
struct Open<const A: usize> {
    /// Arc length where it starts.
    s_start: f64,
    /// The largest interval limit in it (the smallest is `worst.v`).
    v_high: f64,
    /// The worst limits over it.
    worst: Local<A>,
}

/// The path acceleration limit of a zone with speed limit `worst.v`.
fn zone_acceleration<const A: usize>(worst: &Local<A>, limits: &Limits<A>, share: f64) -> f64 {
    let mut a = limits.acceleration();
    let aa = limits.axis_acceleration();
    let v2 = worst.v * worst.v;
    for ((t, n), ai) in worst.tangent.iter().zip(&worst.normal).zip(&aa) {
        if *t > 0.0 && ai.is_finite() {
            let left = (ai - v2 * n).max((1.0 - share) * ai);
            a = a.min(left / t);
        }
    }
    a
}

/// Samples the speed limit on `options.samples()` intervals uniform in the parameter (each
/// interval at its ends and midpoint, taking the worst) and groups consecutive intervals
/// into zones while the largest limit in a zone stays within `1 + zone_tolerance` of the
/// smallest. Returns the zones (arc lengths from `table`, limits set, no phases).
///
/// # Errors
/// [`Error::CapacityExceeded`] with the number of zones needed when they exceed `Z`;
/// [`Error::Curve`] for non-finite derivatives.
pub(super) fn zones<C, const A: usize, const N: usize, const Z: usize>(
    curve: &C,
    table: &ArcLengthTable<f64, N>,
    limits: &Limits<A>,
    options: &PlanOptions,
) -> Result<Vec<ProfileZone, Z>, Error>
where
    C: ParamCurveDeriv,
{
    let share = options.axis_centripetal_share();
    let ratio = 1.0 + options.zone_tolerance();
    let m = options.samples();
    let (u0, u1) = table.domain();
    let length = table.length();
    #[allow(clippy::cast_precision_loss)]
    let at = |k: usize| -> f64 {
        if k == 0 {
            u0
        } else if k >= 2 * m {
            u1
        } else {
            u0 + (u1 - u0) * (k as f64 / (2 * m) as f64)
        }
    };
    let sample =
        |k: usize| -> Result<Option<Local<A>>, Error> { local(curve, at(k), limits, share) };

    let mut out: Vec<ProfileZone, Z> = Vec::new();
    let mut required = 0_usize;
    let mut close = |open: &Open<A>, s_end: f64, out: &mut Vec<ProfileZone, Z>| {
        required += 1;
        let zone = ProfileZone::new(
            open.s_start,
            s_end,
            open.worst.v,
            zone_acceleration(&open.worst, limits, share),
        );
        // Beyond the capacity only the count goes on.
        let _ = out.push(zone);
    };

    let mut prev = sample(0)?;
    let mut open: Option<Open<A>> = None;
    for k in 0..m {
        let mid = sample(2 * k + 1)?;
        let next = sample(2 * k + 2)?;
        let mut worst = Local::<A>::neutral(limits.velocity());
        for l in [&prev, &mid, &next].into_iter().flatten() {
            worst.merge(l);
        }
        prev = next;
        let u_here = at(2 * k);
        match open.as_mut() {
            None => {
                open = Some(Open {
                    s_start: 0.0,
                    v_high: worst.v,
                    worst,
                });
            }
            Some(z) => {
                let high = z.v_high.max(worst.v);
                let low = z.worst.v.min(worst.v);
                let s_here = table.length_at(u_here);
                if high <= ratio * low || !greater(s_here, z.s_start) {
                    z.v_high = high;
                    z.worst.merge(&worst);
                } else {
                    close(z, s_here, &mut out);
                    *z = Open {
                        s_start: s_here,
                        v_high: worst.v,
                        worst,
                    };
                }
            }
        }
    }
    if let Some(z) = open.as_ref() {
        close(z, length, &mut out);
    }
    if required > Z {
        return Err(Error::CapacityExceeded {
            capacity: Z,
            required,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use strak_curves::{Bezier, Nurbs};

    #[test]
    fn circle_limits() {
        // radius 10: κ = 0.1; √(a/κ) = √(1000·10) = 100
        let c = Nurbs::<[f64; 2], 9, 12>::circle([0.0, 0.0], 10.0).unwrap();
        let limits = Limits::<2>::new(500.0, 1000.0, 1e4).unwrap();
        let l = local(&c, 0.5, &limits, 0.5).unwrap().unwrap();
        assert!((l.v - 100.0).abs() < 1e-9);
        // at the start (10, 0): tangent (0, 1), κN = (−0.1, 0)
        let l = local(&c, 0.0, &limits, 0.5).unwrap().unwrap();
        assert!(l.tangent[0].abs() < 1e-12 && (l.tangent[1] - 1.0).abs() < 1e-12);
        assert!((l.normal[0] - 0.1).abs() < 1e-12 && l.normal[1].abs() < 1e-12);
        // an axis acceleration limit of 100 on x with share 0.5: v ≤ √(50/0.1) ≈ 22.36
        let limits = limits
            .with_axis_acceleration([100.0, f64::INFINITY])
            .unwrap();
        let l = local(&c, 0.0, &limits, 0.5).unwrap().unwrap();
        assert!((l.v - 500.0_f64.sqrt()).abs() < 1e-9);
        // zone acceleration: x is loaded only centripetally there (T_x = 0): a_max stays
        assert_eq!(zone_acceleration(&l, &limits, 0.5), 1000.0);
    }

    #[test]
    fn zero_speed_sample_is_skipped() {
        // c'(0) = 0: the first two control points coincide
        let c = Bezier::new([[0.0, 0.0], [0.0, 0.0], [1.0, 1.0]]).unwrap();
        let limits = Limits::<2>::new(1.0, 1.0, 1.0).unwrap();
        assert!(local(&c, 0.0, &limits, 0.5).unwrap().is_none());
        assert!(local(&c, 0.5, &limits, 0.5).unwrap().is_some());
    }

    #[test]
    fn tangential_budget() {
        let mut w = Local::<1>::neutral(5.0);
        w.tangent = [0.5];
        w.normal = [0.02];
        let limits = Limits::<1>::new(10.0, 1000.0, 1.0)
            .unwrap()
            .with_axis_acceleration([4.0])
            .unwrap();
        // what the centripetal part (25·0.02 = 0.5) leaves: (4 − 0.5)/0.5 = 7
        assert_eq!(zone_acceleration(&w, &limits, 0.25), 7.0);
        // never below (1 − share)·a_i/|T_i| (only reached through rounding)
        w.v = 20.0;
        assert_eq!(zone_acceleration(&w, &limits, 0.25), 6.0);
        // the path limit caps it
        let limits = Limits::<1>::new(10.0, 2.0, 1.0)
            .unwrap()
            .with_axis_acceleration([4.0])
            .unwrap();
        assert_eq!(zone_acceleration(&w, &limits, 0.25), 2.0);
    }
}
