//! The speed limit `v_lim(s)` along a curve, sampled and grouped into zones of nearly
//! constant limit.
//!
//! At a parameter `u` with the derivatives `c', c'', c'''` (in `f64`), `σ = |c'|`, and `x(s)`
//! the curve by arc length:
//!
//! ```text
//! T = x_s = c'/σ                                    unit tangent
//! κN = x_ss = (c'' − σ'·T)/σ²                       curvature vector (κ = |κN|), σ' = c'·c''/σ
//! x_sss = (c''' − σ''·T − 3σσ'·κN)/σ³               σ'' = (c''·c'' + c'·c''' − σ'²)/σ
//! ```
//!
//! A motion `s(t)` with `v = ṡ`, `a = s̈`, `j = s⃛` moves the point with
//!
//! ```text
//! ẍ = a·T + v²·κN
//! x⃛ = j·T + 3·v·a·κN + v³·x_sss
//! ```
//!
//! With `q` the centripetal share of [`PlanOptions`], the speed limit is
//!
//! ```text
//! v_lim = min( v_max, √(q·a_max/κ), ∛(q·j_max/|x_sss|), v_i/|T_i|, √(q·a_i/|κN_i|) )
//! ```
//!
//! and a zone whose speed limit is `v_z` and whose worst sampled values are `κ`, `|x_sss|`,
//! `|T_i|`, `|κN_i|` plans with the path acceleration and jerk limits
//!
//! ```text
//! a_z = min( √(a_max² − (v_z²κ)²),  (a_i − v_z²|κN_i|)/|T_i|,  √v_z·R/(√R + c·√v_z) )
//! j_z = R − c·a_z,        R = j_max − v_z³·|x_sss|,   c = 3·v_z·κ
//! ```
//!
//! The third term splits the jerk left, `R`, between speed changes (`j_z`) and the turning
//! while they run (`c·a_z`) so that a speed change from rest to `v_z`, which takes about
//! `v_z/a + a/j`, is fastest (on a straight line it is `√(v_z·j_max)`, the acceleration a
//! jerk-limited change to `v_z` reaches anyway).
//!
//! (the first two terms at least `√(1 − q²)·a_max` and `(1 − q)·a_i/|T_i|`, `j_rest` at
//! least `(1 − q)·j_max`, against rounding). Inside the zone `v ≤ v_z`, `|a| ≤ a_z` and
//! `|j| ≤ j_z`, so `|ẍ| ≤ a_max`, `|ẍ_i| ≤ a_i` and, by the triangle inequality,
//! `|x⃛| ≤ j_max`: the limits hold for the motion in space, not only along the path. The
//! price is speed in curved stretches: at most `√q` of the centripetal limit `√(a_max/κ)`,
//! and gentler speed changes where the path turns while the speed is high.
//!
//! The zone's jerk is further limited to `a_z·f/16` at the control rate `f`, so that a jerk
//! phase to `a_z` lasts at least 16 ticks ([`PlanOptions::MIN_JERK_TICKS`]). Zones also end
//! at the joins and cusps where the speed is capped (`plan/joins.rs`).
//!
//! The loads are sampled, and between samples they can rise well above them: near a
//! cusp the parametric speed `σ` nearly vanishes and `κ` and `|x_sss|` peak within a
//! small fraction of the sampling step. Where the samples of an interval spread too far,
//! or its tangents turn further than its sampled curvature allows (`|T_b − T_a| ≤ ∫κ ds`),
//! the interval is halved (`Refiner`), and each interval then takes its largest sample
//! plus the spread of its samples. Within each piece of the curve this is an
//! estimate of the peak, not a bound: it can fall short by a little (a test over random
//! cubic Béziers measures by how much, from samples 64 times finer), and the feed reserve
//! of the limits is far larger.

use heapless::Vec;
use strak_curves::{ArcLengthTable, ParamCurveDeriv, Point, Scalar};

use super::arc_inverse::param_at_length;
use super::joins::{JoinRule, locate_reversal, reverses};
use super::limits::Limits;
use super::motion::ProfileZone;
use super::options::{PlanOptions, ProfileShape};
use super::{greater, to_param};
use crate::error::Error;

/// The limits sampled at one parameter (or the worst over an interval).
#[derive(Clone, Copy, Debug)]
struct Local<const A: usize> {
    /// The speed limit.
    v: f64,
    /// The curvature `κ`.
    kappa: f64,
    /// `|x_sss|`: the turning part of the jerk is `v³·x_sss`.
    turn: f64,
    /// Per axis `|T_i|`.
    tangent: [f64; A],
    /// Per axis `|κN_i|`.
    normal: [f64; A],
    /// The unit tangent of this sample (not merged: kept from the first).
    direction: [f64; A],
    /// The parametric speed `|c'|` of this sample (not merged: kept from the first).
    speed: f64,
}

impl<const A: usize> Local<A> {
    /// No information: the path velocity limit, no load.
    fn neutral(v_max: f64) -> Self {
        Local {
            v: v_max,
            kappa: 0.0,
            turn: 0.0,
            tangent: [0.0; A],
            normal: [0.0; A],
            direction: [0.0; A],
            speed: 0.0,
        }
    }

    /// The worst of both: the smaller speed limit, the larger loads.
    fn merge(&mut self, other: &Self) {
        self.v = self.v.min(other.v);
        self.kappa = self.kappa.max(other.kappa);
        self.turn = self.turn.max(other.turn);
        for (a, b) in self.tangent.iter_mut().zip(other.tangent.iter()) {
            *a = a.max(*b);
        }
        for (a, b) in self.normal.iter_mut().zip(other.normal.iter()) {
            *a = a.max(*b);
        }
    }
}

/// The path limits a zone plans with.
#[derive(Clone, Copy, Debug, PartialEq)]
struct ZoneLimits {
    /// `|s̈|` limit.
    acceleration: f64,
    /// `|s⃛|` limit (`∞` for trapezoids).
    jerk: f64,
}

/// The limits at the parameter `u`; `None` where `c'(u) = 0` (no tangent: the sample is
/// skipped, its neighbours decide). `jerk` is the path jerk limit (`∞`: not limited).
fn local<C, const A: usize>(
    curve: &C,
    u: f64,
    limits: &Limits<A>,
    (jerk, share): (f64, f64),
    path: usize,
) -> Result<Option<Local<A>>, Error>
where
    C: ParamCurveDeriv,
{
    let Some(mut out) = loads::<C, A>(curve, u, limits.velocity(), path)? else {
        return Ok(None);
    };
    out.v = speed_limit(&out, limits, jerk, share);
    Ok(Some(out))
}

/// The loads of the path at the parameter `u` (curvature `κ`, the turning term `|x_sss|`,
/// per axis `|T_i|` and `|κN_i|`, the unit tangent), with the speed limit `v_max`; `None`
/// where `c'(u) = 0`. The Frenet–Serret formulas in the curve's parameter: with
/// `σ = |c'|`, `T = c'/σ`, `κN = (c'' − σ'T)/σ²` and the third derivative by arc length
/// `x_sss = (c''' − σ''T − 3σσ'κN)/σ³` (do Carmo, *Differential Geometry of Curves and
/// Surfaces*, §1-5).
fn loads<C, const A: usize>(
    curve: &C,
    u: f64,
    v_max: f64,
    path: usize,
) -> Result<Option<Local<A>>, Error>
where
    C: ParamCurveDeriv,
{
    let us = to_param(curve, u);
    let [d1, d2, d3] = curve.deriv_triple(us);
    let dim = <C::Point as Point>::DIM;
    let shaping = dim.min(path);
    let coords = |i: usize| {
        (
            d1.coord(i).to_f64(),
            d2.coord(i).to_f64(),
            d3.coord(i).to_f64(),
        )
    };
    let (mut s11, mut s12, mut s22, mut s13, mut s33) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for i in 0..shaping {
        let (x1, x2, x3) = coords(i);
        s11 += x1 * x1;
        s12 += x1 * x2;
        s22 += x2 * x2;
        s13 += x1 * x3;
        s33 += x3 * x3;
    }
    if ![s11, s12, s22, s13, s33].iter().all(|x| x.is_finite()) {
        return Err(Error::Curve(strak_curves::Error::NonFinite));
    }
    if !greater(s11, 0.0) {
        return Ok(None);
    }
    let sigma = libm::sqrt(s11);
    let sigma1 = s12 / sigma;
    let sigma2 = (s22 + s13 - sigma1 * sigma1) / sigma;
    let mut out = Local::<A>::neutral(v_max);
    out.speed = sigma;
    let (mut kappa2, mut turn2) = (0.0, 0.0);
    for i in 0..dim {
        let (x1, x2, x3) = coords(i);
        let t = x1 / sigma;
        let kn = (x2 - sigma1 * t) / s11;
        if let Some(slot) = out.tangent.get_mut(i) {
            *slot = t.abs();
        }
        if let Some(slot) = out.normal.get_mut(i) {
            *slot = kn.abs();
        }
        if i >= shaping {
            continue; // an axis riding along: its own velocity and acceleration only
        }
        let sss = (x3 - sigma2 * t - 3.0 * sigma * sigma1 * kn) / (s11 * sigma);
        kappa2 += kn * kn;
        turn2 += sss * sss;
        if let Some(slot) = out.direction.get_mut(i) {
            *slot = t;
        }
    }
    out.kappa = libm::sqrt(kappa2);
    out.turn = libm::sqrt(turn2);
    if !(out.kappa.is_finite() && out.turn.is_finite()) {
        return Err(Error::Curve(strak_curves::Error::NonFinite));
    }
    // Rounding noise of the derivatives and formulas (a straight line with uneven parametric
    // speed must get κ = 0 and x_sss = 0, or v³·x_sss at high speeds would eat into the jerk
    // budget; measured noise up to 30·ε relative to these floors' scales).
    let (n2, n3) = (libm::sqrt(s22), libm::sqrt(s33));
    let noise = 1024.0 * f64::EPSILON;
    if out.kappa <= noise * n2 / s11 {
        out.kappa = 0.0;
        out.normal = [0.0; A];
    }
    if out.turn <= noise * (2.0 * n3 / (s11 * sigma) + 8.0 * s22 / (s11 * s11)) {
        out.turn = 0.0;
    }
    Ok(Some(out))
}

/// The speed limit of the loads `out`: the path velocity limit, the centripetal
/// acceleration `v²κ` and the turning jerk `v³|x_sss|` within the share `share` of the
/// acceleration and jerk limits, and per axis the velocity `v·|T_i|` and the centripetal
/// acceleration `v²|κN_i|` within the axis limits.
fn speed_limit<const A: usize>(out: &Local<A>, limits: &Limits<A>, jerk: f64, share: f64) -> f64 {
    let mut v = turning_limit(out, limits, jerk, share);
    let (av, aa) = (limits.axis_velocity(), limits.axis_acceleration());
    for (((t, n), vi), ai) in out.tangent.iter().zip(&out.normal).zip(&av).zip(&aa) {
        if *t > 0.0 {
            v = v.min(vi / t);
        }
        if *n > 0.0 {
            v = v.min(libm::sqrt(share * ai / n));
        }
    }
    v
}

/// The speed limit of the turning loads of `out` alone: the path velocity limit, and the
/// centripetal acceleration `v²κ` and the turning jerk `v³|x_sss|` within the share `share`
/// of the acceleration and jerk limits.
fn turning_limit<const A: usize>(out: &Local<A>, limits: &Limits<A>, jerk: f64, share: f64) -> f64 {
    let mut v = limits.velocity();
    if out.kappa > 0.0 {
        v = v.min(libm::sqrt(share * limits.acceleration() / out.kappa));
    }
    if out.turn > 0.0 {
        let bound = share * jerk / out.turn;
        // Where `v³ ≤ bound/2` the root lies above `1.26·v` and cannot lower `v`: it is not
        // taken (a cube root costs more than the rest of a sample's limits).
        if v * v * v > 0.5 * bound {
            v = v.min(libm::cbrt(bound));
        }
    }
    v
}

/// How many times a sampling interval is halved at most where its samples do not resolve
/// the loads.
const REFINE_DEPTH: u32 = 4;

/// An interval is resolved when the spread of its samples' curvature and turning term
/// changes the centripetal acceleration `v²κ` and the turning jerk `v³|x_sss|`, at its
/// highest sampled speed limit `v`, by at most this share of the acceleration and jerk
/// limits.
const RESOLVED_SHARE: f64 = 0.125;

/// A speed-limit sample: its parameter, arc length and loads (with the parametric speed).
#[derive(Clone, Copy)]
struct Sampled<const A: usize> {
    u: f64,
    s: f64,
    loads: Local<A>,
}

/// The arc length halfway (in the parameter) between the samples `a` and `b`, by the cubic
/// Hermite interpolant of `s(u)` (slopes `|c'|`): it weighs the turn of the tangents
/// between samples ([`bent`]) and places no zone.
fn halfway<const A: usize>(a: &Sampled<A>, b: &Sampled<A>) -> f64 {
    0.5 * (a.s + b.s) + (b.u - a.u) / 8.0 * (a.loads.speed - b.loads.speed)
}

/// The curvature that turning from the tangent of `a` to that of `b` needs at least:
/// `|T_b − T_a| / (s_b − s_a)`, as `|T_b − T_a| ≤ ∫κ ds` (0 for coincident samples).
fn bent<const A: usize>(a: &Sampled<A>, b: &Sampled<A>) -> f64 {
    let ds = b.s - a.s;
    let dt = a
        .loads
        .direction
        .iter()
        .zip(&b.loads.direction)
        .map(|(x, y)| (y - x) * (y - x))
        .sum::<f64>();
    if ds > 0.0 { libm::sqrt(dt) / ds } else { 0.0 }
}

/// The loads of a curve between speed-limit samples, found by halving the sampling
/// intervals where the samples disagree.
struct Refiner<'a, C, L, const A: usize> {
    curve: &'a C,
    arcs: &'a L,
    limits: &'a Limits<A>,
    jerk: f64,
    share: f64,
    /// The axes that shape the path ([`PlanOptions`]).
    path: usize,
}

impl<C: ParamCurveDeriv, L: ArcLengths, const A: usize> Refiner<'_, C, L, A> {
    /// The sample at the parameter `u`, at the arc length `s` (`None` where the curve has
    /// no tangent).
    fn sample_at(&self, u: f64, s: f64) -> Result<Option<Sampled<A>>, Error> {
        let loads = local(
            self.curve,
            u,
            self.limits,
            (self.jerk, self.share),
            self.path,
        )?;
        Ok(loads.map(|loads| Sampled { u, s, loads }))
    }

    /// The sample at the parameter `u` of the sampling grid, at its arc length.
    fn sample(&self, u: f64) -> Result<Option<Sampled<A>>, Error> {
        self.sample_at(u, self.arcs.length_at(u))
    }

    /// The sample at `u`, halfway between `a` and `b` (in the parameter), at the arc length
    /// [`halfway`] gives.
    fn halfway(&self, u: f64, a: &Sampled<A>, b: &Sampled<A>) -> Result<Option<Sampled<A>>, Error> {
        self.sample_at(u, halfway(a, b))
    }

    /// The worst loads over the interval from `a` to `b` with the midpoint sample `m`.
    ///
    /// The curvature `κ` and the turning term `|x_sss|` are sampled, so a peak between the
    /// samples is estimated: an interval whose samples spread too far (see
    /// [`RESOLVED_SHARE`]), or whose tangents turn more than its sampled curvature allows,
    /// is halved up to [`REFINE_DEPTH`] times. The loads of an interval are its largest
    /// sample plus the spread of its samples (for a peak between them), and where it is
    /// still not resolved, at least the curvature its tangents' turning proves ([`bent`];
    /// a resolved interval leaves it out, as there it differs from the samples by little
    /// more than the rounding of `f32` tangents). The speed limit is lowered to fit.
    fn worst(&self, [a, m, b]: [&Sampled<A>; 3], depth: u32) -> Result<Local<A>, Error> {
        let mut worst = a.loads;
        worst.merge(&m.loads);
        worst.merge(&b.loads);
        let v = a.loads.v.max(m.loads.v).max(b.loads.v);
        let low = |f: fn(&Local<A>) -> f64| f(&a.loads).min(f(&m.loads)).min(f(&b.loads));
        let kappa_spread = worst.kappa - low(|l| l.kappa);
        let turn_spread = worst.turn - low(|l| l.turn);
        let proven = bent(a, m).max(bent(m, b));
        let acceleration = RESOLVED_SHARE * self.limits.acceleration() / (v * v);
        let resolved = kappa_spread.max(proven - worst.kappa) <= acceleration
            && turn_spread * v * v * v <= RESOLVED_SHARE * self.jerk;
        if !resolved && depth > 0 {
            let halves = (
                self.halfway(0.5 * (a.u + m.u), a, m)?,
                self.halfway(0.5 * (m.u + b.u), m, b)?,
            );
            if let (Some(l), Some(r)) = halves {
                let mut out = self.worst([a, &l, m], depth - 1)?;
                out.merge(&self.worst([m, &r, b], depth - 1)?);
                return Ok(out);
            }
        }
        worst.kappa += kappa_spread;
        if !resolved {
            worst.kappa = worst.kappa.max(proven);
        }
        worst.turn += turn_spread;
        worst.v = worst
            .v
            .min(turning_limit(&worst, self.limits, self.jerk, self.share));
        Ok(worst)
    }
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

/// The path acceleration and jerk limits of a zone with speed limit `worst.v` (see the
/// module docs; `jerk = ∞` leaves the jerk unlimited), the jerk at most
/// `a_z·rate/MIN_JERK_TICKS` ([`PlanOptions::MIN_JERK_TICKS`]).
fn zone_limits<const A: usize>(
    worst: &Local<A>,
    limits: &Limits<A>,
    jerk: f64,
    share: f64,
    rate: f64,
) -> ZoneLimits {
    let a_max = limits.acceleration();
    let v = worst.v;
    let centripetal = v * v * worst.kappa;
    let mut a = libm::sqrt((a_max * a_max - centripetal * centripetal).max(0.0))
        .max(libm::sqrt(1.0 - share * share) * a_max);
    let aa = limits.axis_acceleration();
    for ((t, n), ai) in worst.tangent.iter().zip(&worst.normal).zip(&aa) {
        if *t > 0.0 && ai.is_finite() {
            let left = (ai - v * v * n).max((1.0 - share) * ai);
            a = a.min(left / t);
        }
    }
    if !jerk.is_finite() {
        return ZoneLimits {
            acceleration: a,
            jerk,
        };
    }
    let rest = (jerk - v * v * v * worst.turn).max((1.0 - share) * jerk);
    let turning = 3.0 * v * worst.kappa;
    if turning > 0.0 {
        let (sv, sr) = (libm::sqrt(v), libm::sqrt(rest));
        a = a.min(sv * rest / (sr + turning * sv));
    }
    ZoneLimits {
        acceleration: a,
        jerk: (rest - turning * a).min(a * rate / PlanOptions::MIN_JERK_TICKS),
    }
}

/// The samples at the middle and the end of the grid's interval `k`, after `prev` (at its
/// start). The end's arc length is that of the arcs, or with `simpson` Simpson's rule on
/// the three samples' speeds from `prev`'s (the arcs' where a sample is missing); the
/// middle's is [`halfway`].
fn grid_pair<C: ParamCurveDeriv, L: ArcLengths, const A: usize>(
    refiner: &Refiner<'_, C, L, A>,
    grid: &Grid,
    k: usize,
    prev: Option<&Sampled<A>>,
    simpson: bool,
) -> Result<(Option<Sampled<A>>, Option<Sampled<A>>), Error> {
    let (u_mid, u_next) = (grid.at(2 * k + 1), grid.at(2 * k + 2));
    let mut mid = refiner.sample_at(u_mid, f64::NAN)?;
    let mut next = refiner.sample_at(u_next, f64::NAN)?;
    if let Some(b) = next.as_mut() {
        b.s = match (prev, &mid) {
            (Some(a), Some(m)) if simpson => {
                a.s + (b.u - a.u) / 6.0 * (a.loads.speed + 4.0 * m.loads.speed + b.loads.speed)
            }
            _ => refiner.arcs.length_at(u_next),
        };
    }
    if let Some(m) = mid.as_mut() {
        m.s = match (prev, &next) {
            (Some(a), Some(b)) => halfway(a, b),
            _ => refiner.arcs.length_at(u_mid),
        };
    }
    Ok((mid, next))
}

/// The parameters of the sampling grid: `2·m + 1` samples uniform in `[u0, u1]`, the ends
/// exact.
#[derive(Clone, Copy)]
struct Grid {
    u0: f64,
    u1: f64,
    m: usize,
}

impl Grid {
    /// Sample `k` of `0 ..= 2m`.
    fn at(&self, k: usize) -> f64 {
        if k == 0 {
            self.u0
        } else if k >= 2 * self.m {
            self.u1
        } else {
            #[allow(clippy::cast_precision_loss)]
            let f = k as f64 / (2 * self.m) as f64;
            self.u0 + (self.u1 - self.u0) * f
        }
    }
}

/// Where zones go as they are closed: a plan's own zones, or the zones of one segment of a
/// streamed path on their way into a look-ahead window.
pub(crate) trait ZoneSink {
    /// The most zones it holds.
    fn capacity(&self) -> usize;
    /// Appends the zone `span` (arc lengths) with the speed, acceleration and jerk limits
    /// `limits` and the speed cap `exit_cap` at its end, and returns the number of zones it
    /// takes (0 where the sink merges it into the one before); nothing is stored when it is
    /// full (the builder counts the zones needed).
    fn push(&mut self, span: (f64, f64), limits: (f64, f64, f64), exit_cap: f64) -> usize;
    /// Lowers the exit cap of the last zone to at most `cap`.
    fn cap_last(&mut self, cap: f64);
}

impl<const Z: usize> ZoneSink for Vec<ProfileZone, Z> {
    fn capacity(&self) -> usize {
        Z
    }
    fn push(
        &mut self,
        (start, end): (f64, f64),
        (v, a, j): (f64, f64, f64),
        exit_cap: f64,
    ) -> usize {
        let mut zone = ProfileZone::new(start, end, v, a, j);
        zone.exit_cap = exit_cap;
        let _ = Vec::push(self, zone);
        1
    }
    fn cap_last(&mut self, cap: f64) {
        if let Some(last) = self.last_mut() {
            last.exit_cap = last.exit_cap.min(cap);
        }
    }
}

/// The zones being collected, in order along the path.
struct ZoneBuilder<'a, const A: usize, S: ZoneSink> {
    limits: &'a Limits<A>,
    /// The path jerk limit (`∞` for trapezoids).
    jerk: f64,
    share: f64,
    rate: f64,
    /// `1 + zone_tolerance`.
    ratio: f64,
    /// Arc lengths closer than this are the same point.
    same: f64,
    open: Option<Open<A>>,
    /// The zones closed so far.
    out: &'a mut S,
    /// Zones closed so far (beyond the capacity only the count goes on).
    required: usize,
}

impl<const A: usize, S: ZoneSink> ZoneBuilder<'_, A, S> {
    /// Closes the open zone at `s_end` with the speed cap `exit_cap` at its end.
    fn close(&mut self, s_end: f64, exit_cap: f64) {
        if let Some(open) = &self.open {
            let zl = zone_limits(&open.worst, self.limits, self.jerk, self.share, self.rate);
            let limits = (open.worst.v, zl.acceleration, zl.jerk);
            self.required += self.out.push((open.s_start, s_end), limits, exit_cap);
        }
    }

    /// Adds the sampling interval starting at arc length `s_here` with the limits `worst`:
    /// to the open zone while its limits stay within the zone tolerance, else in a new zone.
    fn interval(&mut self, s_here: f64, worst: Local<A>) {
        let Some(z) = self.open.as_mut() else {
            self.open = Some(Open {
                s_start: s_here,
                v_high: worst.v,
                worst,
            });
            return;
        };
        let high = z.v_high.max(worst.v);
        let low = z.worst.v.min(worst.v);
        if high <= self.ratio * low || !greater(s_here, z.s_start) {
            z.v_high = high;
            z.worst.merge(&worst);
        } else {
            self.close(s_here, f64::INFINITY);
            self.open = Some(Open {
                s_start: s_here,
                v_high: worst.v,
                worst,
            });
        }
    }

    /// A point at the arc length `s()` (in the current interval, whose limits are `worst`)
    /// that the motion passes at most at `cap`: the open zone ends there when the cap binds.
    fn cap_at(&mut self, s: impl FnOnce() -> f64, cap: f64, worst: Local<A>) {
        let Some(z) = self.open.as_ref() else {
            return;
        };
        if cap >= z.worst.v {
            return; // the zone's own limit is lower
        }
        let s = s();
        if s - z.s_start > self.same {
            self.close(s, cap);
            self.open = Some(Open {
                s_start: s,
                v_high: worst.v,
                worst,
            });
        } else {
            // at the start of the open zone: the end of the previous one
            self.out.cap_last(cap);
        }
    }

    /// Closes the last zone at the path's `length`.
    ///
    /// # Errors
    /// [`Error::ZoneCapacityExceeded`] with the number of zones needed when they exceed the
    /// sink's capacity.
    fn finish(mut self, length: f64) -> Result<(), Error> {
        self.close(length, f64::INFINITY);
        let capacity = self.out.capacity();
        if self.required > capacity {
            return Err(Error::ZoneCapacityExceeded {
                capacity,
                required: self.required,
            });
        }
        Ok(())
    }
}

/// The arc lengths along a curve as the speed-limit sampling places its zones by them.
pub(crate) trait ArcLengths {
    /// The parameter domain, in `f64`.
    fn domain(&self) -> (f64, f64);
    /// The length.
    fn length(&self) -> f64;
    /// The arc length at the parameter `u`.
    fn length_at(&self, u: f64) -> f64;
    /// The parameter at the arc length `s` at which the motion is.
    fn param_at(&self, s: f64) -> f64;
    /// Whether the speed-limit sampling takes the arc lengths of its grid from the speeds
    /// of its samples (Simpson's rule on each interval), where [`length_at`](Self::length_at)
    /// costs a quadrature each: the arc lengths only place the zones' ends.
    fn lengths_by_samples(&self) -> bool {
        false
    }
}

/// A plan's arc lengths: the table of its curve, inverted as the motion is
/// ([`param_at_length`]).
pub(crate) struct TableArcs<'a, C, const N: usize> {
    pub(crate) curve: &'a C,
    pub(crate) table: &'a ArcLengthTable<f64, N>,
}

impl<C: ParamCurveDeriv, const N: usize> ArcLengths for TableArcs<'_, C, N> {
    fn domain(&self) -> (f64, f64) {
        self.table.domain()
    }
    fn length(&self) -> f64 {
        self.table.length()
    }
    fn length_at(&self, u: f64) -> f64 {
        self.table.length_at(u)
    }
    fn param_at(&self, s: f64) -> f64 {
        param_at_length(self.curve, self.table, s).0
    }
}

/// How many times [`arc_at`] moves its arc length up by one unit of `f64` at most.
const ARC_NUDGES: usize = 8;

/// The arc length at which the motion's parameter ([`ArcLengths::param_at`]) reaches `u`:
/// `length_at(u)`, moved up by a few units of `f64` where rounding leaves the parameter
/// below `u`. A motion that rests at this `s` rests at `u` itself (a cusp is passed at
/// rest).
fn arc_at<L: ArcLengths>(arcs: &L, u: f64) -> f64 {
    let mut s = arcs.length_at(u);
    for _ in 0..ARC_NUDGES {
        if arcs.param_at(s) >= u || s >= arcs.length() {
            break;
        }
        s = s.next_up();
    }
    s
}

/// The cusps in the two halves of a sampling interval: where the tangent of a sample points
/// away from the last known tangent (`last`: its parameter and direction), located by
/// bisection. `samples` are the interval's midpoint and end.
fn cusps_in<C: ParamCurveDeriv, const A: usize>(
    curve: &C,
    last: &mut Option<(f64, [f64; A])>,
    samples: [(f64, Option<&Local<A>>); 2],
    path: usize,
) -> [Option<f64>; 2] {
    let mut out = [None; 2];
    for ((u, l), slot) in samples.into_iter().zip(out.iter_mut()) {
        let Some(l) = l else { continue };
        if let Some((u_a, t_a)) = *last
            && reverses(&t_a, &l.direction)
        {
            *slot = Some(locate_reversal(curve, (u_a, t_a), u, path));
        }
        *last = Some((u, l.direction));
    }
    out
}

/// The joins of the curve's pieces, in order, and how they are passed.
struct Joins<const A: usize> {
    rule: JoinRule<A>,
    /// The number of joins (pieces − 1).
    count: usize,
    /// The next join to mark.
    next: usize,
}

/// Marks the points of the current sampling interval (limits `worst`) where the speed is
/// capped, in order along the path: the joins before `u_end` (all that are left for
/// `None`) and the interval's `cusps`.
fn mark_points<C: ParamCurveDeriv, const A: usize, L: ArcLengths, S: ZoneSink>(
    zones: &mut ZoneBuilder<'_, A, S>,
    curve: &C,
    arcs: &L,
    joins: &mut Joins<A>,
    mut cusps: [Option<f64>; 2],
    u_end: Option<f64>,
    worst: Local<A>,
) {
    loop {
        let u_join = (joins.next < joins.count)
            .then(|| curve.piece_domain(joins.next).1.to_f64())
            .filter(|u| u_end.is_none_or(|end| *u < end));
        let cusp = cusps.iter().flatten().next().copied();
        let join_first = match (u_join, cusp) {
            (None, None) => break,
            (Some(uj), Some(uc)) => uj <= uc,
            (Some(_), None) => true,
            (None, Some(_)) => false,
        };
        if let (true, Some(uj)) = (join_first, u_join) {
            let cap = joins.rule.cap(curve, joins.next);
            zones.cap_at(|| arc_at(arcs, uj), cap, worst);
            joins.next += 1;
        } else if let Some(uc) = cusps.iter_mut().find_map(Option::take) {
            zones.cap_at(|| arc_at(arcs, uc), 0.0, worst);
        }
    }
}

/// Samples the speed limit on `options.samples()` intervals uniform in the parameter (each
/// interval at its ends and midpoint, taking the worst), groups consecutive intervals into
/// zones while the largest limit in a zone stays within `1 + zone_tolerance` of the
/// smallest, and ends a zone at every join and cusp whose speed cap binds (see
/// [`PlanOptions`] and `plan/joins.rs`). Writes the zones into `out`, which is empty (arc
/// lengths from `arcs`, limits and exit caps).
///
/// # Errors
/// [`Error::ZoneCapacityExceeded`] with the number of zones needed when they exceed the
/// capacity of `out`; [`Error::Curve`] for non-finite derivatives.
pub(crate) fn zones_into<C, const A: usize, L: ArcLengths, S: ZoneSink>(
    curve: &C,
    arcs: &L,
    limits: &Limits<A>,
    options: &PlanOptions,
    out: &mut S,
) -> Result<(), Error>
where
    C: ParamCurveDeriv,
{
    let share = options.centripetal_share();
    let jerk = match options.shape() {
        ProfileShape::SCurve => limits.jerk(),
        ProfileShape::Trapezoid => f64::INFINITY,
    };
    let (u0, u1) = arcs.domain();
    let grid = Grid {
        u0,
        u1,
        m: options.samples(),
    };
    let refiner = Refiner {
        curve,
        arcs,
        limits,
        jerk,
        share,
        path: options.path_axes(),
    };
    let sample = |k: usize| refiner.sample(grid.at(k));
    let simpson = arcs.lengths_by_samples();
    let mut joins = Joins {
        rule: JoinRule::new(limits, jerk, options),
        count: curve.piece_count().saturating_sub(1),
        next: 0,
    };
    let mut zones = ZoneBuilder::<A, S> {
        limits,
        jerk,
        share,
        rate: options.rate(),
        ratio: 1.0 + options.zone_tolerance(),
        same: 1e-12 * arcs.length(),
        open: None,
        out,
        required: 0,
    };
    let mut prev = sample(0)?;
    let mut last = prev.as_ref().map(|l| (l.u, l.loads.direction));
    for k in 0..grid.m {
        let (mid, next) = grid_pair(&refiner, &grid, k, prev.as_ref(), simpson)?;
        let u_next = grid.at(2 * k + 2);
        let smooth =
            joins.next >= joins.count || curve.piece_domain(joins.next).1.to_f64() > u_next;
        let worst = match (&prev, &mid, &next) {
            (Some(a), Some(m), Some(b)) if smooth => refiner.worst([a, m, b], REFINE_DEPTH)?,
            _ => {
                let mut worst = Local::<A>::neutral(limits.velocity());
                for l in [&prev, &mid, &next].into_iter().flatten() {
                    worst.merge(&l.loads);
                }
                worst
            }
        };
        let s_here = prev
            .as_ref()
            .map_or_else(|| arcs.length_at(grid.at(2 * k)), |p| p.s);
        zones.interval(s_here, worst);
        let cusps = cusps_in(
            curve,
            &mut last,
            [
                (grid.at(2 * k + 1), mid.as_ref().map(|l| &l.loads)),
                (u_next, next.as_ref().map(|l| &l.loads)),
            ],
            refiner.path,
        );
        let u_end = (k + 1 < grid.m).then_some(u_next);
        mark_points(&mut zones, curve, arcs, &mut joins, cusps, u_end, worst);
        prev = next;
    }
    zones.finish(arcs.length())
}

#[cfg(test)]
mod tests {
    extern crate std;

    use super::*;
    use strak_curves::{Bezier, Nurbs};

    /// The exact arc lengths of a curve, taken from the samples' speeds in the grid.
    struct Exact<'a>(&'a Bezier<[f64; 2], 6>);

    impl ArcLengths for Exact<'_> {
        fn domain(&self) -> (f64, f64) {
            (0.0, 1.0)
        }
        fn length(&self) -> f64 {
            self.length_at(1.0)
        }
        fn length_at(&self, u: f64) -> f64 {
            strak_curves::arc_length_between(self.0, 0.0, u, 1e-14).unwrap()
        }
        fn param_at(&self, s: f64) -> f64 {
            strak_curves::param_at_length(self.0, s, 1e-14).unwrap()
        }
        fn lengths_by_samples(&self) -> bool {
            true
        }
    }

    /// The grid's arc lengths by Simpson's rule on the samples' speeds (and the middles'
    /// by the Hermite interpolant) stay within 10⁻⁶ of the length of a blend-like quintic
    /// on 32 intervals.
    #[test]
    fn grid_arc_lengths_from_the_samples() {
        let b = crate::plan::testcurves::blend_like_quintic();
        let arcs = Exact(&b);
        let limits = Limits::<2>::new(100.0, 1000.0, 1e4).unwrap();
        let refiner = Refiner {
            curve: &b,
            arcs: &arcs,
            limits: &limits,
            jerk: 1e4,
            share: 0.5,
            path: usize::MAX,
        };
        let grid = Grid {
            u0: 0.0,
            u1: 1.0,
            m: 32,
        };
        let length = arcs.length();
        let mut prev = refiner.sample(0.0).unwrap();
        let mut worst = 0.0_f64;
        for k in 0..grid.m {
            let (mid, next) = grid_pair(&refiner, &grid, k, prev.as_ref(), true).unwrap();
            for p in [&mid, &next] {
                let p = p.as_ref().unwrap();
                worst = worst.max((p.s - arcs.length_at(p.u)).abs() / length);
            }
            prev = next;
        }
        std::println!("largest error of the grid's arc lengths: {worst:e} of the length");
        assert!(worst < 1e-6, "{worst}");
    }

    const RATE: f64 = PlanOptions::DEFAULT_RATE;

    #[test]
    fn circle_limits() {
        // radius 10: κ = 0.1, x_sss = −κ²·T; √(q·a/κ) = √(0.5·1000·10) = √5000
        let c = Nurbs::<[f64; 2], 9, 12>::circle([0.0, 0.0], 10.0).unwrap();
        let limits = Limits::<2>::new(500.0, 1000.0, 1e4).unwrap();
        for k in 0..=40 {
            let l = local(&c, 0.1 * f64::from(k), &limits, (1e4, 0.5), usize::MAX)
                .unwrap()
                .unwrap();
            assert!((l.kappa - 0.1).abs() < 1e-12, "κ = {}", l.kappa);
            assert!((l.turn - 0.01).abs() < 1e-12, "|x_sss| = {}", l.turn);
            assert!((l.v - 5000.0_f64.sqrt()).abs() < 1e-9);
        }
        // the jerk limit binds below j = q·... : ∛(0.5·100/0.01) = ∛5000
        let l = local(&c, 0.5, &limits, (100.0, 0.5), usize::MAX)
            .unwrap()
            .unwrap();
        assert!((l.v - libm::cbrt(5000.0)).abs() < 1e-9);
        // at the start (10, 0): tangent (0, 1), κN = (−0.1, 0)
        let l = local(&c, 0.0, &limits, (1e4, 0.5), usize::MAX)
            .unwrap()
            .unwrap();
        assert!(l.tangent[0].abs() < 1e-12 && (l.tangent[1] - 1.0).abs() < 1e-12);
        assert!((l.normal[0] - 0.1).abs() < 1e-12 && l.normal[1].abs() < 1e-12);
        // an axis acceleration limit of 100 on x with share 0.5: v ≤ √(50/0.1) ≈ 22.36
        let limits = limits
            .with_axis_acceleration([100.0, f64::INFINITY])
            .unwrap();
        let l = local(&c, 0.0, &limits, (f64::INFINITY, 0.5), usize::MAX)
            .unwrap()
            .unwrap();
        assert!((l.v - 500.0_f64.sqrt()).abs() < 1e-9);
        // x is loaded only centripetally there (T_x = 0): the path's own budget is left,
        // a_max² − (v²κ)² = 1000² − 50²
        let zl = zone_limits(&l, &limits, f64::INFINITY, 0.5, RATE);
        assert!((zl.acceleration - (1e6_f64 - 2500.0).sqrt()).abs() < 1e-9);
        assert_eq!(zl.jerk, f64::INFINITY);
    }

    #[test]
    fn third_derivative_by_arc_length_matches_differences() {
        // a twisted 3-D cubic with uneven parametric speed: x_sss against central
        // differences of κN(u) divided by σ = |c'|
        let c = Bezier::new([
            [0.0, 0.0, 0.0],
            [1.0, 3.0, -1.0],
            [4.0, -2.0, 2.0],
            [5.0, 1.0, 4.0],
        ])
        .unwrap();
        let kn = |u: f64| -> [f64; 3] {
            let (d1, d2) = (c.deriv(u, 1), c.deriv(u, 2));
            let s11: f64 = d1.iter().map(|x| x * x).sum();
            let s12: f64 = d1.iter().zip(&d2).map(|(a, b)| a * b).sum();
            core::array::from_fn(|i| (d2[i] - s12 / s11 * d1[i]) / s11)
        };
        let limits = Limits::<3>::new(1.0, 1.0, 1.0).unwrap();
        for k in 1..10 {
            let u = 0.1 * f64::from(k);
            let l = local(&c, u, &limits, (1.0, 0.5), usize::MAX)
                .unwrap()
                .unwrap();
            let h = 1e-5;
            let (p, m) = (kn(u + h), kn(u - h));
            let sigma = c.deriv(u, 1).iter().map(|x| x * x).sum::<f64>().sqrt();
            let fd = (0..3)
                .map(|i| ((p[i] - m[i]) / (2.0 * h) / sigma).powi(2))
                .sum::<f64>()
                .sqrt();
            let n = kn(u);
            let kappa = n.iter().map(|x| x * x).sum::<f64>().sqrt();
            assert!((l.kappa - kappa).abs() < 1e-12 * (1.0 + kappa));
            assert!(
                (l.turn - fd).abs() < 1e-6 * (1.0 + fd),
                "u = {u}: {} vs {fd}",
                l.turn
            );
        }
    }

    #[test]
    fn zero_speed_sample_is_skipped() {
        // c'(0) = 0: the first two control points coincide
        let c = Bezier::new([[0.0, 0.0], [0.0, 0.0], [1.0, 1.0]]).unwrap();
        let limits = Limits::<2>::new(1.0, 1.0, 1.0).unwrap();
        assert!(
            local(&c, 0.0, &limits, (1.0, 0.5), usize::MAX)
                .unwrap()
                .is_none()
        );
        assert!(
            local(&c, 0.5, &limits, (1.0, 0.5), usize::MAX)
                .unwrap()
                .is_some()
        );
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
        let a =
            |w: &Local<1>, l: &Limits<1>, q| zone_limits(w, l, f64::INFINITY, q, RATE).acceleration;
        // what the centripetal part (25·0.02 = 0.5) leaves: (4 − 0.5)/0.5 = 7
        assert_eq!(a(&w, &limits, 0.25), 7.0);
        // never below (1 − share)·a_i/|T_i| (only reached through rounding)
        w.v = 20.0;
        assert_eq!(a(&w, &limits, 0.25), 6.0);
        // the path limit caps it
        let limits = Limits::<1>::new(10.0, 2.0, 1.0)
            .unwrap()
            .with_axis_acceleration([4.0])
            .unwrap();
        assert_eq!(a(&w, &limits, 0.25), 2.0);
    }

    #[test]
    fn jerk_budget_sums_to_the_limit() {
        let limits = Limits::<1>::new(100.0, 1000.0, 1e4).unwrap();
        let mut w = Local::<1>::neutral(10.0);
        w.kappa = 0.1;
        w.turn = 0.01;
        // v = 10: R = 9990, c = 3, √10·R/(√R + 3√10) ≈ 300.5 < √(1000² − 10²)
        // v = 50: R = 8750, c = 15, √50·R/(√R + 15√50) ≈ 301.5
        let split = |v: f64, r: f64, c: f64| v.sqrt() * r / (r.sqrt() + c * v.sqrt());
        for (v, a_expected) in [
            (10.0, split(10.0, 9990.0, 3.0)),
            (50.0, split(50.0, 8750.0, 15.0)),
        ] {
            w.v = v;
            let zl = zone_limits(&w, &limits, 1e4, 0.5, RATE);
            assert!((zl.acceleration - a_expected).abs() < 1e-9 * a_expected);
            // tangential + turning-while-accelerating + turning at speed = j_max
            let total = zl.jerk + 3.0 * v * w.kappa * zl.acceleration + v * v * v * w.turn;
            assert!((total - 1e4).abs() < 1e-9, "total {total}");
            // and the acceleration in space is within a_max
            let centripetal = v * v * w.kappa;
            assert!(zl.acceleration.hypot(centripetal) <= 1000.0 * (1.0 + 1e-12));
        }
        // the split is the fastest change from rest to v: v/a + a/(R − c·a) is least there
        let (v, r, c) = (50.0, 8750.0, 15.0);
        let time = |a: f64| v / a + a / (r - c * a);
        let best = split(v, r, c);
        assert!(time(best) < time(best * 1.01) && time(best) < time(best * 0.99));
        // a straight stretch keeps the whole budget
        let straight = Local::<1>::neutral(100.0);
        let zl = zone_limits(&straight, &limits, 1e4, 0.5, RATE);
        assert_eq!((zl.acceleration, zl.jerk), (1000.0, 1e4));
    }

    /// Random cubic Béziers (control points up to 6 apart in x and y, 2 in z, as the
    /// stream tests draw them), sampled on 32 intervals as a stream samples a Bézier move:
    /// at 64 times finer samples, each zone's speed limit keeps the centripetal
    /// acceleration `v²κ` and the turning jerk `v³|x_sss|` within their share of the
    /// limits, up to 1 % (the estimate between samples is not a bound; BENCHMARKS.md has
    /// the measured figure). Curves with a cusp (the tangent reverses) are left
    /// out: the motion passes a cusp at rest, whatever its zone's limit.
    #[test]
    fn sampled_loads_cover_the_peaks_between_samples() {
        let limits = Limits::<3>::new(200.0, 2250.0, 75_000.0).unwrap();
        let options = PlanOptions::new().with_samples(32);
        let mut rng = crate::online::testing::Rng(0x2545_f491_4f6c_dd1d);
        let (mut worst, mut curves) = ([0.0_f64; 2], 0);
        for _ in 0..400 {
            let mut near = |p: [f64; 3]| {
                [
                    p[0] + rng.range(-6.0, 6.0),
                    p[1] + rng.range(-6.0, 6.0),
                    p[2] + rng.range(-2.0, 2.0),
                ]
            };
            let p0 = [0.0; 3];
            let points = [p0, near(p0), near(p0), near(p0)];
            let c = Bezier::<[f64; 3], 4>::new(points).unwrap();
            let table = ArcLengthTable::<f64, 64>::new(&c, 1e-9).unwrap();
            let arcs = TableArcs {
                curve: &c,
                table: &table,
            };
            let mut zones = Vec::<ProfileZone, 256>::new();
            zones_into(&c, &arcs, &limits, &options, &mut zones).unwrap();
            let fine = 32 * 2 * 64;
            let samples: std::vec::Vec<(f64, Local<3>)> = (0..=fine)
                .filter_map(|k| {
                    let u = f64::from(k) / f64::from(fine);
                    loads::<_, 3>(&c, u, 200.0, usize::MAX)
                        .unwrap()
                        .map(|l| (table.length_at(u), l))
                })
                .collect();
            let reverses = samples.windows(2).any(|w| {
                let dot: f64 = (0..3)
                    .map(|i| w[0].1.direction[i] * w[1].1.direction[i])
                    .sum();
                dot < 0.0
            });
            if reverses {
                continue;
            }
            curves += 1;
            for (s, l) in &samples {
                let z = zones.iter().find(|z| *s <= z.end()).unwrap();
                let v = z.v_limit();
                worst[0] = worst[0].max(v * v * l.kappa / (0.5 * 2250.0));
                worst[1] = worst[1].max(v * v * v * l.turn / (0.5 * 75_000.0));
            }
        }
        std::println!("{curves} curves: v²κ and v³|x_sss| at most {worst:?} of their share");
        assert!(curves > 300);
        assert!(worst[0] <= 1.01 && worst[1] <= 1.01, "{worst:?}");
    }

    #[test]
    fn jerk_phases_last_sixteen_ticks() {
        // j = 10⁸ with a = 1000: T_j = 10 µs; at 1 kHz the jerk is capped at a·f/16
        let limits = Limits::<1>::new(100.0, 1000.0, 1e8).unwrap();
        let straight = Local::<1>::neutral(100.0);
        let zl = zone_limits(&straight, &limits, 1e8, 0.5, 1000.0);
        assert_eq!(zl.acceleration, 1000.0);
        assert_eq!(zl.jerk, 1000.0 * 1000.0 / 16.0);
        assert_eq!(zl.acceleration / zl.jerk * 1000.0, 16.0);
        // at 100 kHz: 6.25·10⁶
        let zl = zone_limits(&straight, &limits, 1e8, 0.5, 1e5);
        assert_eq!(zl.jerk, 6.25e6);
        // a trapezoid keeps its infinite jerk
        let zl = zone_limits(&straight, &limits, f64::INFINITY, 0.5, 1000.0);
        assert_eq!(zl.jerk, f64::INFINITY);
    }
}
