//! A motion along the path: the arc length `s(t)` as a list of constant-jerk phases.

use heapless::Vec;

use super::greater;
use crate::error::Error;
use crate::num::RATE_RANGE;

/// The longest motion a path can play: `u32::MAX` ticks at the slowest control rate.
const MAX_DURATION: f64 = u32::MAX as f64 / RATE_RANGE.0;

/// The most phases one zone of a profile has: jerk up, constant acceleration, jerk down,
/// cruise, and the three mirrored phases of the deceleration ("double S", seven phases).
pub(crate) const PHASES_PER_ZONE: usize = 7;

/// The kinematic state along the path at one instant: arc length `s`, speed `v = ṡ`,
/// acceleration `a = s̈` and jerk `j = s⃛`.
///
/// ```
/// use strak_trajectory::MotionProfile;
/// let m = MotionProfile::<1>::constant_speed(10.0, 2.0)?;
/// let st = m.state(1.5);
/// assert_eq!((st.s, st.v, st.a, st.j), (3.0, 2.0, 0.0, 0.0));
/// # Ok::<(), strak_trajectory::Error>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct MotionState {
    /// Arc length from the path start.
    pub s: f64,
    /// Speed along the path, `ds/dt`.
    pub v: f64,
    /// Path acceleration, `d²s/dt²`.
    pub a: f64,
    /// Path jerk, `d³s/dt³`.
    pub j: f64,
}

/// One phase of constant jerk: for `t ∈ [t0, t0 + duration]`, with `τ = t − t0`,
///
/// ```text
/// s(t) = s0 + v0·τ + a0·τ²/2 + j·τ³/6,   v(t) = v0 + a0·τ + j·τ²/2,   a(t) = a0 + j·τ.
/// ```
///
/// ```
/// use strak_trajectory::Phase;
/// let p = Phase { t0: 1.0, duration: 2.0, s0: 0.0, v0: 0.0, a0: 0.0, j: 6.0 };
/// let st = p.state_at(2.0); // τ = 1
/// assert_eq!((st.s, st.v, st.a, st.j), (1.0, 3.0, 6.0, 6.0));
/// assert_eq!(p.end(), 3.0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Phase {
    /// Start time in seconds.
    pub t0: f64,
    /// Duration in seconds (> 0 in a profile).
    pub duration: f64,
    /// Arc length at the start.
    pub s0: f64,
    /// Speed at the start.
    pub v0: f64,
    /// Acceleration at the start.
    pub a0: f64,
    /// The constant jerk of the phase.
    pub j: f64,
}

impl Phase {
    /// The end time `t0 + duration`.
    #[inline]
    pub fn end(&self) -> f64 {
        self.t0 + self.duration
    }

    /// The state at time `t`, clamped to `[t0, t0 + duration]` (evaluated by Horner's rule
    /// in `τ = t − t0`).
    #[inline]
    pub fn state_at(&self, t: f64) -> MotionState {
        let tau = (t - self.t0).clamp(0.0, self.duration);
        self.local(tau)
    }

    /// The state at `τ` seconds after the start (not clamped).
    #[inline]
    pub(super) fn local(&self, tau: f64) -> MotionState {
        let j = self.j;
        MotionState {
            s: self.s0 + tau * (self.v0 + tau * (0.5 * self.a0 + tau * (j / 6.0))),
            v: self.v0 + tau * (self.a0 + tau * (0.5 * j)),
            a: self.a0 + tau * j,
            j,
        }
    }
}

/// One zone of a [`MotionProfile`]: a stretch `[start, end]` of arc length with a constant
/// speed, acceleration and jerk limit, entered at speed `v_start` and left at `v_end` with
/// zero acceleration, and its phases (at most seven).
///
/// ```
/// use strak_trajectory::MotionProfile;
/// let m = MotionProfile::<1>::scurve(10.0, 2.0, 4.0, 16.0)?;
/// let z = &m.zones()[0];
/// assert_eq!((z.start(), z.end(), z.v_limit(), z.a_limit()), (0.0, 10.0, 2.0, 4.0));
/// assert_eq!(z.j_limit(), 16.0);
/// assert_eq!((z.v_start(), z.v_end()), (0.0, 0.0));
/// assert_eq!(z.phases().len(), 7); // reaches a_max and v_max: all seven phases
/// # Ok::<(), strak_trajectory::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ProfileZone {
    pub(super) start: f64,
    pub(super) end: f64,
    pub(super) v_limit: f64,
    pub(super) a_limit: f64,
    pub(super) j_limit: f64,
    /// The largest speed at the zone's end (0 at a corner or cusp).
    pub(super) exit_cap: f64,
    pub(super) v_start: f64,
    pub(super) v_end: f64,
    pub(super) t_start: f64,
    pub(super) phases: [Phase; PHASES_PER_ZONE],
    pub(super) count: usize,
}

impl ProfileZone {
    /// A zone without phases yet (`j_limit = ∞`: trapezoidal speed changes).
    pub(super) fn new(start: f64, end: f64, v_limit: f64, a_limit: f64, j_limit: f64) -> Self {
        ProfileZone {
            start,
            end,
            v_limit,
            a_limit,
            j_limit,
            exit_cap: f64::INFINITY,
            v_start: 0.0,
            v_end: 0.0,
            t_start: 0.0,
            phases: [Phase::default(); PHASES_PER_ZONE],
            count: 0,
        }
    }

    /// Arc length where the zone starts.
    pub fn start(&self) -> f64 {
        self.start
    }

    /// Arc length where the zone ends.
    pub fn end(&self) -> f64 {
        self.end
    }

    /// The zone's speed limit (the smallest limit sampled in the zone); the motion never
    /// cruises faster.
    pub fn v_limit(&self) -> f64 {
        self.v_limit
    }

    /// The zone's limit of the path acceleration `|s̈|`.
    pub fn a_limit(&self) -> f64 {
        self.a_limit
    }

    /// The zone's limit of the path jerk `|s⃛|` (`∞` for trapezoidal profiles).
    pub fn j_limit(&self) -> f64 {
        self.j_limit
    }

    /// `true` when the zone ends at a corner or a cusp of the path, where the motion comes to
    /// rest.
    pub fn stops_at_end(&self) -> bool {
        self.exit_cap == 0.0
    }

    /// The largest speed the motion may have at the zone's end: 0 at a corner or a cusp, the
    /// speed a join passed at speed allows (see [`PlanOptions`](crate::PlanOptions)),
    /// `f64::INFINITY` where the zone's end is not a join.
    pub fn exit_cap(&self) -> f64 {
        self.exit_cap
    }

    /// Speed on entering the zone.
    pub fn v_start(&self) -> f64 {
        self.v_start
    }

    /// Speed on leaving the zone.
    pub fn v_end(&self) -> f64 {
        self.v_end
    }

    /// Time at which the motion enters the zone.
    pub fn t_start(&self) -> f64 {
        self.t_start
    }

    /// The phases of the zone, in time order (empty phases are left out).
    pub fn phases(&self) -> &[Phase] {
        self.phases.get(..self.count).unwrap_or(&[])
    }

    /// Appends a phase of `duration` starting with acceleration `a0` and jerk `j`; the start
    /// time, arc length and speed continue from the previous phase (or from the zone entry
    /// `(t, s, v)`). Phases that are not longer than zero are left out, and a cruise
    /// (`a0 = j = 0`) after a cruise lengthens it. `false` when the phase is lost because
    /// all [`PHASES_PER_ZONE`] slots are taken.
    pub(super) fn push(&mut self, entry: (f64, f64, f64), duration: f64, a0: f64, j: f64) -> bool {
        if !greater(duration, 0.0) {
            return true;
        }
        let cruise = |a0: f64, j: f64| a0 == 0.0 && j == 0.0;
        if let Some(last) = self.phases_mut().last_mut()
            && cruise(last.a0, last.j)
            && cruise(a0, j)
        {
            last.duration += duration;
            return true;
        }
        let (t0, s0, v0) = match self.phases().last() {
            Some(last) => {
                let st = last.local(last.duration);
                (last.end(), st.s, st.v)
            }
            None => entry,
        };
        if let Some(slot) = self.phases.get_mut(self.count) {
            *slot = Phase {
                t0,
                duration,
                s0,
                v0,
                a0,
                j,
            };
            self.count += 1;
            return true;
        }
        false
    }

    /// The phases of the zone, to change in place.
    pub(super) fn phases_mut(&mut self) -> &mut [Phase] {
        self.phases.get_mut(..self.count).unwrap_or(&mut [])
    }

    /// The time at which the zone's last phase ends (`t_start` for a zone without phases).
    pub(super) fn t_end(&self) -> f64 {
        self.phases().last().map_or(self.t_start, Phase::end)
    }

    /// The state at the end of the zone's last phase, or the entry state.
    pub(super) fn end_state(&self) -> MotionState {
        match self.phases().last() {
            Some(p) => p.local(p.duration),
            None => MotionState {
                s: self.start,
                v: self.v_start,
                a: 0.0,
                j: 0.0,
            },
        }
    }
}

/// A motion along a path of length `L`: the arc length `s(t)`, piecewise cubic in `t`, as a
/// list of constant-jerk [`Phase`]s grouped in at most `Z` [`ProfileZone`]s.
///
/// `s`, `v` and (for the S-curve) `a` are continuous; the jerk is piecewise constant. The
/// profiles are built by [`MotionProfile::scurve`] (jerk-limited, rest to rest),
/// [`MotionProfile::trapezoid`] (acceleration-limited, rest to rest),
/// [`MotionProfile::constant_speed`] and, with speed limits varying along a curve, by
/// [`PathTiming::plan`](crate::PathTiming::plan).
///
/// ```
/// use strak_trajectory::MotionProfile;
/// // 10 mm, at most 2 mm/s, 4 mm/s², 16 mm/s³
/// let m = MotionProfile::<1>::scurve(10.0, 2.0, 4.0, 16.0)?;
/// // textbook: T = L/v_max + a_max/j_max + v_max/a_max
/// assert!((m.duration() - (5.0 + 0.25 + 0.5)).abs() < 1e-12);
/// assert_eq!(m.state(m.duration()).s, 10.0);
/// assert!((m.state(0.5 * m.duration()).v - 2.0).abs() < 1e-12);
/// # Ok::<(), strak_trajectory::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct MotionProfile<const Z: usize> {
    pub(super) zones: Vec<ProfileZone, Z>,
    pub(super) length: f64,
    pub(super) duration: f64,
}

impl<const Z: usize> MotionProfile<Z> {
    /// A profile without zones (no motion): storage that planning in place fills.
    pub(super) const EMPTY: Self = MotionProfile {
        zones: Vec::new(),
        length: 0.0,
        duration: 0.0,
    };

    /// Builds the profile from zones whose phases are set, in order; checks that the
    /// duration is positive and fits `u32::MAX` ticks at the slowest control rate (100 Hz,
    /// about 497 days; [`Error::TooLong`] otherwise, an infinite duration included).
    pub(super) fn from_zones(zones: Vec<ProfileZone, Z>, length: f64) -> Result<Self, Error> {
        let mut profile = MotionProfile {
            zones,
            ..Self::EMPTY
        };
        profile.seal(length)?;
        Ok(profile)
    }

    /// [`from_zones`](Self::from_zones) in place, for the zones already in `self.zones`.
    pub(super) fn seal(&mut self, length: f64) -> Result<(), Error> {
        let duration = self.zones.last().map_or(0.0, ProfileZone::t_end);
        if greater(duration, MAX_DURATION) {
            return Err(Error::TooLong);
        }
        if !greater(duration, 0.0) {
            return Err(Error::EmptyPath);
        }
        self.length = length;
        self.duration = duration;
        Ok(())
    }

    /// The duration in seconds.
    pub fn duration(&self) -> f64 {
        self.duration
    }

    /// The path length `L` the motion covers.
    pub fn length(&self) -> f64 {
        self.length
    }

    /// The zones, in order along the path.
    pub fn zones(&self) -> &[ProfileZone] {
        &self.zones
    }

    /// All phases, in time order.
    pub fn phases(&self) -> impl Iterator<Item = &Phase> {
        self.zones.iter().flat_map(ProfileZone::phases)
    }

    /// The state at time `t`, clamped to `[0, duration]` (NaN counts as 0). At `t ≥ duration`
    /// the state is exactly `s = L`, the final speed (0 for rest-to-rest profiles), `a = 0`,
    /// `j = 0`. Finds the zone by binary search (`O(log Z)`), then the phase (at most 7).
    pub fn state(&self, t: f64) -> MotionState {
        if t >= self.duration {
            return MotionState {
                s: self.length,
                v: self.zones.last().map_or(0.0, |z| z.v_end),
                a: 0.0,
                j: 0.0,
            };
        }
        let t = if t > 0.0 { t } else { 0.0 };
        let zi = self
            .zones
            .partition_point(|z| z.t_start <= t)
            .saturating_sub(1);
        let Some(zone) = self.zones.get(zi) else {
            return MotionState::default();
        };
        let phases = zone.phases();
        let pi = phases.partition_point(|p| p.t0 <= t).saturating_sub(1);
        match phases.get(pi) {
            Some(p) => p.state_at(t),
            None => zone.end_state(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn phase_polynomial() {
        let p = Phase {
            t0: 2.0,
            duration: 3.0,
            s0: 1.0,
            v0: 2.0,
            a0: -1.0,
            j: 0.5,
        };
        let st = p.state_at(4.0);
        let tau: f64 = 2.0;
        assert_eq!(
            st.s,
            1.0 + 2.0 * tau - 0.5 * tau * tau + 0.5 * tau.powi(3) / 6.0
        );
        assert_eq!(st.v, 2.0 - tau + 0.25 * tau * tau);
        assert_eq!(st.a, -1.0 + 0.5 * tau);
        // clamped to the phase
        assert_eq!(p.state_at(-5.0).s, 1.0);
        assert_eq!(p.state_at(100.0), p.state_at(5.0));
    }

    #[test]
    fn zone_push_continues_and_skips_empty() {
        let mut z = ProfileZone::new(0.0, 10.0, 2.0, 1.0, 1.0);
        z.push((1.0, 0.0, 0.0), 2.0, 1.0, 0.0);
        z.push((9.0, 9.0, 9.0), 0.0, 5.0, 5.0); // empty: left out
        z.push((9.0, 9.0, 9.0), 1.0, 0.0, 0.0);
        assert_eq!(z.phases().len(), 2);
        let second = z.phases()[1];
        assert_eq!((second.t0, second.s0, second.v0), (3.0, 2.0, 2.0));
        assert_eq!(z.t_end(), 4.0);
        assert_eq!(z.end_state().s, 4.0);
        // at most seven phases are stored
        for k in 0..10 {
            let kept = z.push((0.0, 0.0, 0.0), 1.0, 1.0, 0.0);
            assert_eq!(kept, k < PHASES_PER_ZONE - 2);
        }
        assert_eq!(z.phases().len(), PHASES_PER_ZONE);
        // a cruise after a cruise lengthens it
        let mut c = ProfileZone::new(0.0, 10.0, 2.0, 1.0, 1.0);
        c.push((0.0, 0.0, 1.0), 2.0, 0.0, 0.0);
        c.push((0.0, 0.0, 1.0), 3.0, 0.0, 0.0);
        assert_eq!((c.phases().len(), c.t_end()), (1, 5.0));
    }

    #[test]
    fn empty_profile_is_an_error() {
        let zones: Vec<ProfileZone, 2> = Vec::new();
        assert_eq!(MotionProfile::from_zones(zones, 1.0), Err(Error::EmptyPath));
        let mut zones: Vec<ProfileZone, 2> = Vec::new();
        let mut z = ProfileZone::new(0.0, 1.0, 1.0, 1.0, 1.0);
        z.push((0.0, 0.0, 1e-300), f64::INFINITY, 0.0, 0.0);
        assert!(zones.push(z).is_ok());
        assert_eq!(MotionProfile::from_zones(zones, 1.0), Err(Error::TooLong));
        // the longest: u32::MAX ticks at 100 Hz
        for (d, ok) in [(MAX_DURATION, true), (MAX_DURATION * (1.0 + 1e-15), false)] {
            let mut zones: Vec<ProfileZone, 2> = Vec::new();
            let mut z = ProfileZone::new(0.0, 1.0, 1.0, 1.0, 1.0);
            z.push((0.0, 0.0, 1.0 / d), d, 0.0, 0.0);
            assert!(zones.push(z).is_ok());
            let r = MotionProfile::from_zones(zones, 1.0);
            assert_eq!(r.is_ok(), ok, "{d}: {r:?}");
        }
    }
}
