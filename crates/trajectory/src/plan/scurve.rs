//! The jerk-limited "double S" velocity profile (Biagiotti & Melchiorri, *Trajectory Planning
//! for Automatic Machines and Robots*, 2008, §3.4), written from the mathematics.
//!
//! # Velocity change
//!
//! The fastest change of speed by `Δv > 0` that starts and ends with zero acceleration, with
//! `|a| ≤ a_max` and `|j| ≤ j_max`, raises the acceleration with jerk `j_max`, holds it, and
//! lowers it with jerk `−j_max`:
//!
//! * `Δv ≥ a_max²/j_max` (`a_max` is reached): jerk phases `T_j = a_max/j_max`, a constant
//!   acceleration phase `Δv/a_max − T_j`, total `T = T_j + Δv/a_max`;
//! * otherwise (`a_max` is not reached): `T_j = √(Δv/j_max)`, peak acceleration
//!   `j_max·T_j < a_max`, no constant phase, total `T = 2·T_j`.
//!
//! The acceleration is symmetric about the middle of the change, so the speed is point
//! symmetric about it and the mean speed is `(v0 + v1)/2`: the change covers exactly the
//! **minimum distance** `D(v0, v1) = (v0 + v1)/2 · T(|v1 − v0|)`. `D` is symmetric in
//! `v0, v1` and increases with the larger of the two, which the forward/backward pass of the
//! planner relies on.
//!
//! # One zone
//!
//! A zone of length `L` with speed limit `v_lim`, entered at `v0` and left at `v1`
//! (`D(v0, v1) ≤ L`, both `≤ v_lim`), accelerates from `v0` to a peak `v_p`, cruises at
//! `v_p`, and decelerates to `v1` (seven phases at most). When
//! `D(v0, v_lim) + D(v_lim, v1) ≤ L`, `v_p = v_lim` and the cruise takes the rest of the
//! length; otherwise the zone is too short to reach its limit, and `v_p` is the solution of
//! `D(v0, v_p) + D(v_p, v1) = L` on `[max(v0, v1), v_lim]`, found by bisection (the left
//! side increases with `v_p`), keeping the feasible side so that the remainder of the length
//! (a few ulp) becomes a short cruise. For rest to rest with one zone this is the
//! time-optimal double S of the textbook (`T_v = 0` when `v_max` is not reached).
//!
//! An infinite jerk limit gives `T_j = 0`: the same code yields the trapezoidal profile.

use heapless::Vec;

use super::greater;
use super::motion::{MotionProfile, ProfileZone};
use crate::error::Error;

/// Bisection steps: enough to exhaust the `f64` resolution of any bracket (the loop stops
/// earlier when the midpoint no longer differs from the ends).
const BISECTION_STEPS: usize = 2200;

/// The fastest velocity change by `dv` (≥ 0) from zero to zero acceleration: the duration of
/// each jerk phase, of the constant-acceleration phase, and the peak acceleration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Change {
    /// Duration of each of the two jerk phases.
    pub(super) tj: f64,
    /// Duration of the constant-acceleration phase.
    pub(super) tc: f64,
    /// The peak acceleration (`a_max` when reached).
    pub(super) peak: f64,
}

impl Change {
    /// The change by `dv` under the limits `a`, `j` (`j = ∞`: no jerk limit).
    pub(super) fn new(dv: f64, a: f64, j: f64) -> Self {
        if !greater(dv, 0.0) {
            return Change {
                tj: 0.0,
                tc: 0.0,
                peak: 0.0,
            };
        }
        if dv * j >= a * a {
            let tj = a / j;
            Change {
                tj,
                tc: (dv / a - tj).max(0.0),
                peak: a,
            }
        } else {
            let tj = libm::sqrt(dv / j);
            Change {
                tj,
                tc: 0.0,
                peak: j * tj,
            }
        }
    }

    /// The duration `2·T_j + T_c`.
    pub(super) fn time(&self) -> f64 {
        2.0 * self.tj + self.tc
    }
}

/// `D(v0, v1)`: the minimum distance of a jerk-limited change of speed from `v0` to `v1`.
pub(super) fn change_distance(v0: f64, v1: f64, a: f64, j: f64) -> f64 {
    0.5 * (v0 + v1) * Change::new((v1 - v0).abs(), a, j).time()
}

/// The time that a motion cruising at `v_cruise` loses against cruising on by slowing to
/// `v_low` and speeding up again: each a jerk-limited change under `a`, `j`, of duration
/// `T`, losing `T·Δv/(2·v_cruise)` against the cruise over the distance it covers. For an
/// exact stop (`v_low = 0`) that is `T(v_cruise)`; nothing is lost at `v_low ≥ v_cruise`.
pub(crate) fn slowing_loss(v_low: f64, v_cruise: f64, a: f64, j: f64) -> f64 {
    if v_low >= v_cruise {
        return 0.0;
    }
    let dv = v_cruise - v_low;
    Change::new(dv, a, j).time() * dv / v_cruise
}

/// The largest `v ∈ [v_from, cap]` with `D(v_from, v) ≤ length` (`cap` itself when
/// `cap ≤ v_from`). By the symmetry of `D` this is both the speed reachable by accelerating
/// from `v_from` and the highest speed from which `v_from` can be reached by braking.
///
/// `D(v_from, ·) = length` is solved in closed form ([`reach_gain`]) and the edge of
/// `D ≤ length` in `f64` is then found from that root one unit of `f64` at a time
/// ([`edge_near`]), or by bisection of the whole of `[v_from, cap]` where it lies further.
pub(crate) fn reach(v_from: f64, length: f64, cap: f64, a: f64, j: f64) -> f64 {
    if cap <= v_from || change_distance(v_from, cap, a, j) <= length {
        return cap;
    }
    let fits = |v| change_distance(v_from, v, a, j) <= length;
    let root = v_from + reach_gain(v_from, length, a, j);
    edge_near(root, (v_from, cap), fits).unwrap_or_else(|| last_fitting(v_from, cap, fits))
}

/// The most units of `f64` [`edge_near`] steps from the closed-form root: its rounding is a
/// few.
const EDGE_STEPS: usize = 16;

/// The edge of `fits` on `[lo, hi]` near `guess`: the speed where it holds and fails one
/// unit of `f64` above (at `hi` it fails, at `lo` it holds), found by stepping from `guess`
/// (clamped to `[lo, hi]`) one unit at a time; `None` when it lies more than
/// [`EDGE_STEPS`] units away or `guess` is NaN. Where `fits` changes once, this is the edge
/// the bisection finds.
fn edge_near(guess: f64, (lo, hi): (f64, f64), fits: impl Fn(f64) -> bool) -> Option<f64> {
    if guess.is_nan() {
        return None;
    }
    let mut v = guess.clamp(lo, hi);
    let up = v == lo || (v < hi && fits(v));
    for _ in 0..EDGE_STEPS {
        if up {
            let next = v.next_up();
            if next >= hi || !fits(next) {
                return Some(v);
            }
            v = next;
        } else {
            let next = v.next_down();
            if next <= lo || fits(next) {
                return Some(next.max(lo));
            }
            v = next;
        }
    }
    None
}

/// The speed gain `Δ = v − w` with `D(w, v) = length`, in closed form (both branches of
/// [`Change`]):
/// - where `a` is reached (`Δ ≥ a²/j`, or `j = ∞`), `D = (w + Δ/2)·(Δ/a + a/j)`, a quadratic
///   in `Δ`, whose positive root is taken in the form without cancellation;
/// - otherwise `D = (2w + Δ)·√(Δ/j)`, so `x = √Δ` solves the depressed cubic
///   `x³ + 2w·x − L·√j = 0`, whose one real root (its derivative is positive) Cardano's
///   formula gives as `u − p/(3u)` with `u³ = q/2 + √(q²/4 + p³/27)`, `p = 2w`,
///   `q = L·√j`, written as `q/(u² + p/3 + (p/(3u))²)` (from `u³ − (p/(3u))³ = q`), which
///   has no cancellation (Press et al., *Numerical Recipes*, 3rd ed., §5.6).
fn reach_gain(w: f64, length: f64, a: f64, j: f64) -> f64 {
    let ta = a / j;
    let dv_a = a * ta;
    if length >= (w + 0.5 * dv_a) * 2.0 * ta {
        let (b, c) = (w / a + 0.5 * ta, w * ta - length);
        return -2.0 * c / (b + libm::sqrt(b * b - 2.0 * c / a));
    }
    let (p, q) = (2.0 * w, length * libm::sqrt(j));
    let u = libm::cbrt(0.5 * q + libm::sqrt(0.25 * q * q + p * p * p / 27.0));
    if u <= 0.0 {
        return 0.0;
    }
    let v = p / (3.0 * u);
    let x = q / (u * u + p / 3.0 + v * v);
    x * x
}

/// The edge of `fits` on `[lo, hi]` by bisection, from below: a speed where `fits` holds
/// (`lo` itself when no midpoint does), for a `fits` that holds at `lo` and fails at `hi`
/// and changes once between them. It stops when the interval cannot be halved in `f64`.
pub(super) fn last_fitting(mut lo: f64, mut hi: f64, fits: impl Fn(f64) -> bool) -> f64 {
    for _ in 0..BISECTION_STEPS {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if fits(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

/// The peak speed of a zone: `v_lim` when it is reached, else the largest `v_p` in
/// `[max(v0, v1), v_lim]` with `D(v0, v_p) + D(v_p, v1) ≤ length`.
pub(super) fn peak_speed(v0: f64, v1: f64, v_lim: f64, length: f64, a: f64, j: f64) -> f64 {
    let need = |vp: f64| change_distance(v0, vp, a, j) + change_distance(vp, v1, a, j);
    let floor = v0.max(v1);
    if v_lim <= floor || need(v_lim) <= length {
        return v_lim.max(floor);
    }
    last_fitting(floor, v_lim, |vp| need(vp) <= length)
}

/// Fills the phases of `zone` (whose `v_start`, `v_end`, limits and `t_start` are set) with
/// the double S from `v_start` to `v_end` over the zone's length under its limits; the
/// zone is entered at arc length `s_entry` (the end of the previous zone's motion).
pub(super) fn fill_zone(zone: &mut ProfileZone, s_entry: f64) {
    let (v0, v1, a, j) = (zone.v_start, zone.v_end, zone.a_limit, zone.j_limit);
    let length = zone.end - zone.start;
    let vp = peak_speed(v0, v1, zone.v_limit, length, a, j);
    let up = Change::new(vp - v0, a, j);
    let down = Change::new(vp - v1, a, j);
    let used = 0.5 * (v0 + vp) * up.time() + 0.5 * (vp + v1) * down.time();
    let cruise = if vp > 0.0 {
        ((length - used) / vp).max(0.0)
    } else {
        0.0
    };
    let entry = (zone.t_start, s_entry, v0);
    // An infinite jerk makes the ramps empty (T_j = 0): the trapezoid.
    let (jerk_up, jerk_down) = if j.is_finite() { (j, -j) } else { (0.0, 0.0) };
    zone.push(entry, up.tj, 0.0, jerk_up);
    zone.push(entry, up.tc, up.peak, 0.0);
    zone.push(entry, up.tj, up.peak, jerk_down);
    zone.push(entry, cruise, 0.0, 0.0);
    zone.push(entry, down.tj, 0.0, jerk_down);
    zone.push(entry, down.tc, -down.peak, 0.0);
    zone.push(entry, down.tj, -down.peak, jerk_up);
}

/// Checks that a limit is finite and positive.
pub(super) fn check_limit(x: f64) -> Result<f64, Error> {
    if x.is_finite() && x > 0.0 {
        Ok(x)
    } else {
        Err(Error::InvalidLimit)
    }
}

/// Checks that a length is finite and positive.
pub(super) fn check_length(length: f64) -> Result<f64, Error> {
    if length.is_finite() && length > 0.0 {
        Ok(length)
    } else {
        Err(Error::EmptyPath)
    }
}

/// One zone from rest to rest over `[0, length]`.
pub(super) fn rest_to_rest<const Z: usize>(
    length: f64,
    v: f64,
    a: f64,
    j: f64,
) -> Result<MotionProfile<Z>, Error> {
    let mut zone = ProfileZone::new(0.0, length, v, a, j);
    fill_zone(&mut zone, 0.0);
    let mut zones = Vec::new();
    zones.push(zone).map_err(|_| Error::ZoneCapacityExceeded {
        capacity: Z,
        required: 1,
    })?;
    MotionProfile::from_zones(zones, length)
}

impl<const Z: usize> MotionProfile<Z> {
    /// The time-optimal jerk-limited ("double S") motion over `length` from rest to rest:
    /// speed `≤ v_max`, `|a| ≤ a_max`, `|j| ≤ j_max`, with continuous acceleration. One zone;
    /// `Z ≥ 1`.
    ///
    /// The acceleration to the peak speed `v_p` and the deceleration from it are each the
    /// fastest change of speed between zero accelerations: jerk phases of
    /// `T_j = a_max/j_max` around a constant-acceleration phase when `v_p ≥ a_max²/j_max`,
    /// else two jerk phases of `T_j = √(v_p/j_max)`; each covers `v_p/2 · (2·T_j + T_c)`.
    /// `v_p = v_max` with a cruise when the length allows it, else `v_p` fills the length
    /// exactly (found by bisection). This is the double S of Biagiotti & Melchiorri
    /// (*Trajectory Planning for Automatic Machines and Robots*, §3.4) with `T_v = 0`
    /// whenever `v_max` is not reached.
    ///
    /// # Errors
    /// [`Error::EmptyPath`] unless `length` is finite and positive; [`Error::InvalidLimit`]
    /// unless each limit is finite and positive;
    /// [`Error::TooLong`] for a duration beyond `u32::MAX` ticks at 100 Hz (infinite
    /// included); [`Error::ZoneCapacityExceeded`] for `Z = 0`.
    ///
    /// ```
    /// use strak_trajectory::{Error, MotionProfile};
    /// // a_max is not reached: T = 4·(L / (2 j_max))^(1/3) = 4 s
    /// let m = MotionProfile::<1>::scurve(4.0, 100.0, 100.0, 2.0)?;
    /// assert!((m.duration() - 4.0).abs() < 1e-12);
    /// let mid = m.state(2.0); // peak speed (L/2)^(2/3)·j^(1/3) = 2
    /// assert!((mid.s - 2.0).abs() < 1e-12 && (mid.v - 2.0).abs() < 1e-12);
    /// assert_eq!(MotionProfile::<1>::scurve(1.0, 1.0, 1.0, 0.0), Err(Error::InvalidLimit));
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn scurve(length: f64, v_max: f64, a_max: f64, j_max: f64) -> Result<Self, Error> {
        let length = check_length(length)?;
        rest_to_rest(
            length,
            check_limit(v_max)?,
            check_limit(a_max)?,
            check_limit(j_max)?,
        )
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::plan::testcurves::textbook_scurve_duration as textbook_duration;

    fn check_regime(l: f64, v: f64, a: f64, j: f64, v_reached: bool, a_reached: bool) {
        let m = MotionProfile::<1>::scurve(l, v, a, j).unwrap();
        let exact = textbook_duration(l, v, a, j);
        let rel = (m.duration() - exact).abs() / exact;
        assert!(rel < 1e-3, "duration {} vs {exact}", m.duration());
        assert!(
            rel < 1e-12,
            "duration {} vs {exact} (rel {rel})",
            m.duration()
        );
        let (mut vmax, mut amax, mut jmax) = (0.0_f64, 0.0_f64, 0.0_f64);
        let n = 20_000;
        let mut prev = m.state(0.0);
        for k in 1..=n {
            let t = m.duration() * k as f64 / n as f64;
            let st = m.state(t);
            vmax = vmax.max(st.v);
            amax = amax.max(st.a.abs());
            jmax = jmax.max(st.j.abs());
            assert!(st.s >= prev.s - 1e-12);
            prev = st;
        }
        assert!(vmax <= v * (1.0 + 1e-12));
        assert!(amax <= a * (1.0 + 1e-12));
        assert!(jmax <= j * (1.0 + 1e-12));
        assert_eq!((vmax - v).abs() < 1e-9 * v, v_reached, "vmax {vmax}");
        assert_eq!((amax - a).abs() < 1e-9 * a, a_reached, "amax {amax}");
        let end = m.state(m.duration());
        assert_eq!((end.s, end.v, end.a), (l, 0.0, 0.0));
        // the last phase ends at the path end
        let last = m.phases().last().unwrap();
        let st = last.state_at(last.end());
        assert!((st.s - l).abs() < 1e-12 * l && st.v.abs() < 1e-12 * v);
    }

    #[test]
    fn straight_line_duration_all_regimes() {
        // v_max and a_max reached
        check_regime(100.0, 10.0, 20.0, 100.0, true, true);
        // v_max reached, a_max not (v_max < a_max²/j_max)
        check_regime(100.0, 2.0, 20.0, 100.0, true, false);
        // a_max reached, v_max not
        check_regime(1.0, 10.0, 20.0, 1000.0, false, true);
        // neither reached
        check_regime(0.01, 10.0, 20.0, 100.0, false, false);
    }

    #[test]
    fn change_closed_forms() {
        // a_max reached: Δv = 4 ≥ a²/j = 1
        let c = Change::new(4.0, 2.0, 4.0);
        assert_eq!((c.tj, c.tc, c.peak), (0.5, 1.5, 2.0));
        assert_eq!(c.time(), 2.5);
        // not reached: Δv = 0.25 < 1, T_j = √(Δv/j) = 0.25
        let c = Change::new(0.25, 2.0, 4.0);
        assert_eq!((c.tj, c.tc, c.peak), (0.25, 0.0, 1.0));
        // infinite jerk: a trapezoid ramp
        let c = Change::new(3.0, 2.0, f64::INFINITY);
        assert_eq!((c.tj, c.tc, c.peak), (0.0, 1.5, 2.0));
        assert_eq!(Change::new(0.0, 2.0, 4.0).time(), 0.0);
        // distance = mean speed · time
        assert_eq!(change_distance(1.0, 5.0, 2.0, 4.0), 3.0 * 2.5);
        assert_eq!(change_distance(5.0, 1.0, 2.0, 4.0), 3.0 * 2.5);
    }

    #[test]
    fn reach_and_peak() {
        let (a, j) = (2.0, 4.0);
        // enough room: the cap
        assert_eq!(reach(1.0, 100.0, 5.0, a, j), 5.0);
        // cap below the start: the cap
        assert_eq!(reach(3.0, 0.0, 1.0, a, j), 1.0);
        // exact inverse of D
        let v = reach(1.0, change_distance(1.0, 4.0, a, j), 10.0, a, j);
        assert!((v - 4.0).abs() < 1e-12);
        assert!(change_distance(1.0, v, a, j) <= change_distance(1.0, 4.0, a, j));
        // the peak fills the length
        let l = change_distance(0.5, 3.0, a, j) + change_distance(3.0, 1.0, a, j);
        let vp = peak_speed(0.5, 1.0, 10.0, l, a, j);
        assert!((vp - 3.0).abs() < 1e-12);
        assert_eq!(peak_speed(0.5, 1.0, 2.0, l, a, j), 2.0);
    }

    /// The closed form's edge against the bisection of all of `[v_from, cap]`, over speeds,
    /// lengths and limits in both branches of [`Change`] and without a jerk limit: it fits,
    /// the next `f64` above it does not, it is the bisection's edge to the bit, and the steps
    /// from the root reach it.
    #[test]
    fn reach_finds_the_edge_the_bisection_finds() {
        let mut cases = 0;
        for (a, j) in [
            (3_000.0, 100_000.0),
            (2.0, 4.0),
            (50.0, 1e7),
            (3_000.0, f64::INFINITY),
        ] {
            for w in [0.0, 1e-6, 0.3, 7.0, 149.9, 2_000.0] {
                for length in [1e-9, 1e-4, 0.02, 0.7, 3.0, 45.0, 1e4] {
                    let cap = w + 1e4;
                    let fits = |v| change_distance(w, v, a, j) <= length;
                    let edge = reach(w, length, cap, a, j);
                    let bisected = last_fitting(w, cap, fits);
                    assert!(fits(edge), "{w} {length} {a} {j}: {edge} does not fit");
                    assert!(
                        !fits(edge.next_up()),
                        "{w} {length} {a} {j}: {edge} not the edge"
                    );
                    assert_eq!(edge.to_bits(), bisected.to_bits(), "{w} {length} {a} {j}");
                    let root = w + reach_gain(w, length, a, j);
                    let stepped = edge_near(root, (w, cap), fits);
                    assert!(stepped.is_some(), "{w} {length} {a} {j}: the root is far");
                    cases += 1;
                }
            }
        }
        assert_eq!(cases, 168);
    }

    #[test]
    fn zone_between_speeds_is_continuous() {
        let mut z = ProfileZone::new(5.0, 25.0, 4.0, 3.0, 10.0);
        z.v_start = 1.0;
        z.v_end = 2.0;
        z.t_start = 7.0;
        fill_zone(&mut z, 5.0);
        let p = z.phases();
        assert_eq!(p.len(), 7);
        for w in p.windows(2) {
            let end = w[0].local(w[0].duration);
            assert_eq!(w[1].t0, w[0].end());
            assert_eq!((w[1].s0, w[1].v0), (end.s, end.v));
            assert!((w[1].a0 - end.a).abs() < 1e-12);
        }
        let end = z.end_state();
        assert!((end.s - 25.0).abs() < 1e-12 && (end.v - 2.0).abs() < 1e-12);
        assert!(end.a.abs() < 1e-12);
        assert_eq!(p[0].v0, 1.0);
        assert!((p[3].v0 - 4.0).abs() < 1e-12); // the cruise at the limit
        assert_eq!((p[3].a0, p[3].j), (0.0, 0.0));
    }

    #[test]
    fn errors() {
        assert_eq!(
            MotionProfile::<1>::scurve(0.0, 1.0, 1.0, 1.0),
            Err(Error::EmptyPath)
        );
        assert_eq!(
            MotionProfile::<1>::scurve(f64::NAN, 1.0, 1.0, 1.0),
            Err(Error::EmptyPath)
        );
        assert_eq!(
            MotionProfile::<1>::scurve(1.0, -1.0, 1.0, 1.0),
            Err(Error::InvalidLimit)
        );
        assert_eq!(
            MotionProfile::<1>::scurve(1.0, 1.0, f64::INFINITY, 1.0),
            Err(Error::InvalidLimit)
        );
        assert_eq!(
            MotionProfile::<1>::scurve(1.0, 1.0, 1.0, f64::NAN),
            Err(Error::InvalidLimit)
        );
        assert_eq!(
            MotionProfile::<0>::scurve(1.0, 1.0, 1.0, 1.0),
            Err(Error::ZoneCapacityExceeded {
                capacity: 0,
                required: 1
            })
        );
        // an infinite duration, and a finite one beyond u32::MAX ticks at 100 Hz
        assert_eq!(
            MotionProfile::<1>::scurve(1e300, 1e-300, 1.0, 1.0),
            Err(Error::TooLong)
        );
        assert_eq!(
            MotionProfile::<1>::scurve(50.0, 1.5e-304, 2000.0, 5e4),
            Err(Error::TooLong)
        );
    }

    #[test]
    fn deterministic() {
        let a = MotionProfile::<1>::scurve(1.2345, 0.7, 3.1, 17.0).unwrap();
        let b = MotionProfile::<1>::scurve(1.2345, 0.7, 3.1, 17.0).unwrap();
        assert_eq!(a.duration().to_bits(), b.duration().to_bits());
        for (p, q) in a.phases().zip(b.phases()) {
            assert_eq!(p.duration.to_bits(), q.duration.to_bits());
            assert_eq!(p.s0.to_bits(), q.s0.to_bits());
        }
    }
}
