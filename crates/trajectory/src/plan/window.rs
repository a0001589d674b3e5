//! Look-ahead over a path that grows while the motion runs: zones of constant limits are
//! appended as moves arrive, the boundary speeds of the zones not yet committed are planned
//! so that the motion can always come to rest at the end of what is known, and the first
//! zone is committed (its double S, or its transition into the next zone where that carries
//! the acceleration across their boundary) when the motion needs it.
//!
//! Why committing is always safe: the boundary speeds come from a forward pass from the
//! committed speed and a backward pass from rest at the window's end, so the first zone's
//! end speed is one from which the rest of the window can still brake to rest. Appending
//! zones only moves the point of rest further on, which can only raise the speeds the
//! backward pass allows, never lower them; so the speed a committed zone ends at stays one
//! the next zone can start from, whatever arrives later, and a producer that falls behind
//! only makes the motion slow down and rest at the end of what it sent. A zone entered
//! with acceleration keeps the motion that entered it with (ending at the speed planned at
//! that time) as its fallback, so the same holds for it: its planned end speed is never
//! below its fallback's, and the fallback's end stays one the next zone can start from.

use heapless::Vec;

use super::motion::ProfileZone;
use super::scurve::{change_distance, fill_zone, last_fitting, reach};
use super::speed_limit::ZoneSink;
use super::transitions::{carry_across, entered_with};
use crate::error::Error;

/// The boundary speeds of the window's zones: the first starts at `v_entry`, the last ends
/// at rest, and each zone can go from its start to its end within its length and limits,
/// ending no faster than its exit cap or the next zone's limit.
///
/// Braking distances are not monotone in the end speed: a jerk-limited change from `v0` to
/// `v1 < v0` covers `D(v1, v0) = (v0 + v1)/2 · T(v0 − v1)`, and braking from `v0` to about
/// `v0/3` takes longer than braking to rest. So a zone's end speed is a cap, not a target,
/// and the backward pass asks, for each zone, for the fastest start `B` from which some end
/// speed at most its cap `c` fits: the largest `v0` with `D(v1, v0) ≤ L` has a single
/// minimum over `v1` (it falls while `v1` is below half the speed change, or below
/// `a²/2j` with a phase of constant acceleration, and rises after), so the fastest start is
/// that of `v1 = 0` or of `v1 = c`. Any start at most `B` is then feasible (to the end that
/// gave `B`, or cruising), so the starts allowed form `[0, B]` and the forward pass can take,
/// zone by zone, the fastest end that fits from the start it has and is at most the next
/// zone's `B` ([`fastest_end`]). With `v_entry` at most the first zone's `B`, which any
/// entry an earlier pass over fewer zones allowed is, every zone fits.
///
/// A zone's cap and fastest start depend only on the zones after it, so when zones are
/// appended the backward pass stops at the first zone whose cap and fastest start come out
/// as before (the zones before it keep theirs), and the forward pass starts again there.
///
/// The first zone ends no slower than `floor`: the end speed of its fallback where the
/// motion enters it with acceleration (see [`LookAhead`]), which it can always keep to.
fn plan_speeds(zones: &mut [WindowZone], (v_entry, floor): (f64, f64)) {
    plan_speeds_under(zones, (v_entry, floor), |_, z| z.v_limit());
}

/// [`plan_speeds`] with the speed limit `limit(i, zone)` of each zone `i` (the zones' own,
/// or those a feed scale would give them).
fn plan_speeds_under(
    zones: &mut [WindowZone],
    (v_entry, floor): (f64, f64),
    limit: impl Fn(usize, &WindowZone) -> f64,
) {
    let mut bound = 0.0;
    let mut from = 0;
    for i in (0..zones.len()).rev() {
        let next_limit = zones.get(i + 1).map_or(0.0, |z| limit(i + 1, z));
        if let Some(z) = zones.get_mut(i) {
            let (length, v_limit) = (z.end - z.start, limit(i, z));
            let cap = z.exit_cap.min(next_limit).min(bound).min(v_limit);
            let from_rest = reach(0.0, length, v_limit, z.a_limit, z.j_limit);
            let from_cap = reach(cap, length, v_limit, z.a_limit, z.j_limit);
            bound = from_rest.max(from_cap);
            if cap == z.cap && bound == z.bound {
                from = i;
                break;
            }
            (z.cap, z.bound) = (cap, bound);
        }
    }
    let mut v = match from.checked_sub(1).and_then(|i| zones.get(i)) {
        Some(z) => z.v_end,
        None => v_entry,
    };
    for (i, z) in zones.iter_mut().enumerate().skip(from) {
        z.v_start = v;
        z.v_end = fastest_end(v, z.cap, z.end - z.start, z.a_limit, z.j_limit);
        if i == 0 {
            z.v_end = z.v_end.max(floor);
        }
        v = z.v_end;
    }
}

/// The forward pass of [`plan_speeds`] alone, for a new entry speed `v_entry` of zones
/// whose caps are planned, up to the first zone whose start speed comes out as before
/// (the zones from there on keep theirs).
fn forward_from(zones: &mut [WindowZone], (v_entry, floor): (f64, f64)) {
    let mut v = v_entry;
    for (i, z) in zones.iter_mut().enumerate() {
        if i > 0 && z.v_start == v {
            break;
        }
        z.v_start = v;
        z.v_end = fastest_end(v, z.cap, z.end - z.start, z.a_limit, z.j_limit);
        if i == 0 {
            z.v_end = z.v_end.max(floor);
        }
        v = z.v_end;
    }
}

/// The fastest end speed at most `cap` that a zone of `length` entered at `v0` can reach:
/// accelerating towards `cap` where it lies above `v0`; else `cap` where braking to it
/// fits, or the fastest slower speed that fits (the distance rises with the end speed from
/// rest up to the gap of speeds that do not fit, so bisection on `[0, cap]` finds its
/// edge); rest when nothing fits (not for a start the backward pass allowed).
fn fastest_end(v0: f64, cap: f64, length: f64, a: f64, j: f64) -> f64 {
    if cap >= v0 {
        return reach(v0, length, cap, a, j);
    }
    if change_distance(cap, v0, a, j) <= length {
        return cap;
    }
    last_fitting(0.0, cap, |v| change_distance(v, v0, a, j) <= length)
}

/// A zone of the look-ahead window: a stretch of arc length with constant limits, without
/// phases (those are made when it is committed), so that a window of many zones stays
/// small (88 bytes).
///
/// ```
/// use strak_trajectory::{Error, WindowZone};
/// assert!(WindowZone::new((0.0, 10.0), (100.0, 1_000.0, 20_000.0), f64::INFINITY).is_ok());
/// assert_eq!(WindowZone::new((5.0, 5.0), (100.0, 1_000.0, 20_000.0), 0.0), Err(Error::EmptyPath));
/// assert_eq!(WindowZone::new((0.0, 1.0), (100.0, 0.0, 20_000.0), 0.0), Err(Error::InvalidLimit));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WindowZone {
    start: f64,
    end: f64,
    /// The speed limit of the path and the machine (curvature, axes), without the feed.
    v_machine: f64,
    /// The highest `v_machine` of the zones merged into it.
    v_high: f64,
    /// The programmed feed (`∞` for none; rounded down to `f32`), times `scale` where it
    /// applies.
    feed: f32,
    /// The feed override the zone is planned with (1 to 2).
    scale: f32,
    /// Seconds the motion rests before it enters the zone (a dwell; the zone before ends
    /// at rest).
    hold: f32,
    a_limit: f64,
    j_limit: f64,
    exit_cap: f64,
    /// The largest end speed the window allows (the exit cap, the next zone's limit and
    /// fastest start).
    cap: f64,
    /// The fastest start from which the window after it can be kept to (NaN before the
    /// first plan).
    bound: f64,
    v_start: f64,
    v_end: f64,
}

impl WindowZone {
    /// The zone `[start, end]` of arc length with the speed, acceleration and jerk limits
    /// `v`, `a`, `j` (`j = ∞`: trapezoidal speed changes) and the largest speed at its end
    /// `exit_cap` (0 for a stop there, `∞` for none).
    ///
    /// # Errors
    /// [`Error::EmptyPath`] for an empty or reversed extent; [`Error::InvalidLimit`] for a
    /// limit that is not positive (or a NaN), a non-finite `v` or `a`, or a negative or NaN
    /// exit cap.
    ///
    /// ```
    /// use strak_trajectory::WindowZone;
    /// let corner = WindowZone::new((0.0, 2.5), (150.0, 3_000.0, 100_000.0), 0.0)?; // stops at its end
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn new(
        (start, end): (f64, f64),
        (v, a, j): (f64, f64, f64),
        exit_cap: f64,
    ) -> Result<Self, Error> {
        if !(end > start && start.is_finite() && end.is_finite()) {
            return Err(Error::EmptyPath);
        }
        let positive = |x: f64| x > 0.0;
        let finite = |x: f64| positive(x) && x.is_finite();
        if !(finite(v) && finite(a) && positive(j) && (exit_cap == 0.0 || positive(exit_cap))) {
            return Err(Error::InvalidLimit);
        }
        Ok(WindowZone::unchecked((start, end), (v, a, j), exit_cap))
    }

    /// The speed limit: the machine's, or the feed scaled by the override where lower.
    fn v_limit(&self) -> f64 {
        self.limit_at(self.scale)
    }

    /// The speed limit under the feed override `scale`.
    fn limit_at(&self, scale: f32) -> f64 {
        self.v_machine.min(f64::from(self.feed) * f64::from(scale))
    }

    /// This zone and `next` (which starts where it ends) as one zone under the lower limits
    /// of both, where their speed limits are within `ratio` of each other (the highest of
    /// all merged at most `ratio` times the lowest), nothing caps the speed where they
    /// meet, and they have the same feed and override; else `None`.
    fn merged(&self, next: &WindowZone, ratio: f64) -> Option<Self> {
        let high = self.v_high.max(next.v_high);
        let low = self.v_machine.min(next.v_machine);
        let same_feed = self.feed == next.feed && self.scale == next.scale;
        if !(self.exit_cap == f64::INFINITY && same_feed && high <= ratio * low) {
            return None;
        }
        Some(WindowZone {
            end: next.end,
            v_machine: low,
            v_high: high,
            a_limit: self.a_limit.min(next.a_limit),
            j_limit: self.j_limit.min(next.j_limit),
            exit_cap: next.exit_cap,
            bound: f64::NAN,
            ..*self
        })
    }

    /// The zone to its planned end speed, entered at time `t` and speed `v`, without
    /// phases.
    fn blank(&self, t: f64, v: f64) -> ProfileZone {
        let (v_limit, a_limit, j_limit) = (self.v_limit(), self.a_limit, self.j_limit);
        let mut zone = ProfileZone::new(self.start, self.end, v_limit, a_limit, j_limit);
        zone.exit_cap = self.exit_cap;
        zone.v_start = v;
        zone.v_end = self.v_end;
        zone.t_start = t;
        zone
    }

    /// The zone's double S from the speed `v` to its planned end speed, entered at time `t`
    /// and arc length `s`.
    fn profile(&self, (t, s, v): (f64, f64, f64)) -> ProfileZone {
        let mut zone = self.blank(t, v);
        fill_zone(&mut zone, s);
        zone
    }

    /// The zone of [`new`](Self::new), its values not checked.
    const fn unchecked(
        (start, end): (f64, f64),
        (v, a, j): (f64, f64, f64),
        exit_cap: f64,
    ) -> Self {
        WindowZone {
            start,
            end,
            v_machine: v,
            v_high: v,
            feed: f32::INFINITY,
            scale: 1.0,
            hold: 0.0,
            a_limit: a,
            j_limit: j,
            exit_cap,
            cap: 0.0,
            bound: f64::NAN,
            v_start: 0.0,
            v_end: 0.0,
        }
    }
}

/// The look-ahead window: up to `Z` zones not yet committed, in order along the path, and
/// the state where the committed motion ends (at rest, at arc length 0 and time 0, before
/// anything is committed). See the module docs of `plan::window` for why a committed zone
/// never needs to be taken back: the motion can always come to rest at the end of the
/// zones pushed so far.
///
/// Pushing a zone runs the forward/backward pass over the window (`O(Z)`); committing
/// fills one zone's double S ([`ProfileZone`]) and shifts the window (`O(Z)`). Where the
/// speed changes in one direction on both sides of the boundary after the committed zone,
/// the commit carries the acceleration across it, as a whole path's plan does (see
/// [`PathTiming`](crate::PathTiming)): the time-optimal transition from the start of the
/// committed zone's last speed change to the end of the next zone's first, under the
/// tighter limits of the two, kept where it is faster and keeps each zone's limits. The
/// next zone is then entered with acceleration; its motion with the transition (ending at
/// the speed planned then) is kept as its fallback, so that the window stays one the
/// motion can keep to, while the next commit goes from the state it is entered in to the
/// end speed planned by then, by the online solver, where that keeps the zone's limits.
///
/// ```
/// use strak_trajectory::{LookAhead, WindowZone};
/// let mut window = LookAhead::<8>::new();
/// window.push(WindowZone::new((0.0, 10.0), (100.0, 1_000.0, 20_000.0), f64::INFINITY)?)?;
/// let first = window.commit().unwrap(); // all that is known: it ends at rest
/// assert_eq!((first.v_start(), first.v_end()), (0.0, 0.0));
/// window.push(WindowZone::new((10.0, 30.0), (100.0, 1_000.0, 20_000.0), f64::INFINITY)?)?;
/// window.push(WindowZone::new((30.0, 40.0), (50.0, 1_000.0, 20_000.0), f64::INFINITY)?)?;
/// let second = window.commit().unwrap(); // from rest, to what the next zone allows
/// assert_eq!(second.v_start(), 0.0);
/// assert!(second.v_end() > 0.0 && second.v_end() <= 50.0);
/// assert_eq!(second.t_start(), first.phases().last().unwrap().end());
/// # Ok::<(), strak_trajectory::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct LookAhead<const Z: usize> {
    zones: Vec<WindowZone, Z>,
    /// Where the committed motion ends: time, arc length and speed.
    entry: (f64, f64, f64),
    /// Where the committed motion ends with acceleration (it carries it into the first
    /// zone): the first zone's motion from there to the end speed planned when it was
    /// committed, which keeps the limits.
    carry: Option<ProfileZone>,
}

impl<const Z: usize> Default for LookAhead<Z> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const Z: usize> LookAhead<Z> {
    /// An empty window at rest at arc length 0 and time 0.
    ///
    /// ```
    /// use strak_trajectory::LookAhead;
    /// assert_eq!(LookAhead::<4>::new().entry(), (0.0, 0.0, 0.0));
    /// ```
    pub const fn new() -> Self {
        LookAhead {
            zones: Vec::new(),
            entry: (0.0, 0.0, 0.0),
            carry: None,
        }
    }

    /// Empties the window, in place: at rest at arc length 0 and time 0.
    pub(crate) fn clear(&mut self) {
        self.zones.clear();
        self.carry = None;
        self.entry = (0.0, 0.0, 0.0);
    }

    /// The zones not yet committed.
    ///
    /// ```
    /// use strak_trajectory::LookAhead;
    /// assert_eq!(LookAhead::<4>::new().len(), 0);
    /// ```
    pub fn len(&self) -> usize {
        self.zones.len()
    }

    /// Whether no zone waits to be committed.
    ///
    /// ```
    /// use strak_trajectory::LookAhead;
    /// assert!(LookAhead::<4>::new().is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.zones.is_empty()
    }

    /// The speed the first zone is entered at and the least it ends at (the end speed of
    /// its fallback where it is entered with acceleration, else 0), for [`plan_speeds`].
    fn planned_entry(&self) -> (f64, f64) {
        (self.entry.2, self.carry.as_ref().map_or(0.0, |f| f.v_end))
    }

    /// Whether the committed motion can go on within the window's plan: entered without
    /// acceleration, at a speed at most the first zone's fastest start; entered with
    /// acceleration, its fallback ends at a speed the rest of the window can start from
    /// (rest at the window's end).
    fn entry_fits(&self) -> bool {
        match &self.carry {
            None => self.zones.first().is_none_or(|z| self.entry.2 <= z.bound),
            Some(fallback) => match self.zones.get(1) {
                Some(next) => fallback.v_end <= next.bound,
                None => fallback.v_end == 0.0,
            },
        }
    }

    /// The time, arc length and speed where the committed motion ends (it may still
    /// accelerate there).
    ///
    /// ```
    /// use strak_trajectory::{LookAhead, WindowZone};
    /// let mut window = LookAhead::<4>::new();
    /// window.push(WindowZone::new((0.0, 1.0), (10.0, 100.0, 1_000.0), f64::INFINITY)?)?;
    /// let zone = window.commit().unwrap();
    /// assert_eq!(window.entry(), (zone.phases().last().unwrap().end(), 1.0, 0.0));
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn entry(&self) -> (f64, f64, f64) {
        self.entry
    }

    /// Appends a zone, which must start where the window (or, when it is empty, the
    /// committed motion) ends, and plans the boundary speeds again.
    ///
    /// # Errors
    /// [`Error::CapacityExceeded`] when the window holds `Z` zones (commit first);
    /// [`Error::EmptyPath`] when the zone does not start where the window ends.
    ///
    /// ```
    /// use strak_trajectory::{Error, LookAhead, WindowZone};
    /// let mut window = LookAhead::<1>::new();
    /// let limits = (10.0, 100.0, 1_000.0);
    /// assert_eq!(window.push(WindowZone::new((1.0, 2.0), limits, 0.0)?), Err(Error::EmptyPath));
    /// window.push(WindowZone::new((0.0, 1.0), limits, 0.0)?)?;
    /// assert!(matches!(window.push(WindowZone::new((1.0, 2.0), limits, 0.0)?), Err(Error::CapacityExceeded { .. })));
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn push(&mut self, zone: WindowZone) -> Result<(), Error> {
        self.extend(core::slice::from_ref(&zone))
    }

    /// Appends `zones` (in order along the path, the first starting where the window ends)
    /// and plans the window's speeds again, once.
    ///
    /// # Errors
    /// [`Error::CapacityExceeded`] when they do not all fit (nothing is appended);
    /// [`Error::EmptyPath`] when one does not start where the one before ends (nothing is
    /// appended).
    ///
    /// ```
    /// use strak_trajectory::{LookAhead, WindowZone};
    /// let mut window = LookAhead::<4>::new();
    /// let limits = (10.0, 100.0, 1_000.0);
    /// let zones = [WindowZone::new((0.0, 1.0), limits, 0.0)?, WindowZone::new((1.0, 3.0), limits, 0.0)?];
    /// window.extend(&zones)?;
    /// assert_eq!(window.len(), 2);
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn extend(&mut self, zones: &[WindowZone]) -> Result<(), Error> {
        self.check(zones)?;
        for zone in zones {
            let _ = self.zones.push(*zone);
        }
        let entry = self.planned_entry();
        plan_speeds(&mut self.zones, entry);
        Ok(())
    }

    /// An error unless `zones` fit and each starts where the one before it (the first:
    /// where the window) ends.
    fn check(&self, zones: &[WindowZone]) -> Result<(), Error> {
        let required = self.zones.len() + zones.len();
        if required > Z {
            return Err(Error::CapacityExceeded {
                capacity: Z,
                required,
            });
        }
        let mut end = self.zones.last().map_or(self.entry.1, |z| z.end);
        for zone in zones {
            if zone.start != end {
                return Err(Error::EmptyPath);
            }
            end = zone.end;
        }
        Ok(())
    }

    /// [`extend`](Self::extend), merging each zone into the window's last while that one is
    /// crossed at its speed limit in fewer than [`MIN_ZONE_TICKS`] ticks of the control
    /// period `period` and their speed limits are within `ratio` of each other
    /// ([`WindowZone::merged`]): a dense chain of short segments then plans its speed
    /// changes across several of them, where each zone alone (entered and left without
    /// acceleration) would let the speed change by a sliver. The merged zones stay short,
    /// as a committed zone is planned no further: longer ones would take the look-ahead of
    /// a short queue. A merge that would leave the committed speed no way to keep to the
    /// window (it lowers the last zone's limits) is taken back, and a zone entered with
    /// acceleration is not merged into (its fallback ends where it ends).
    ///
    /// # Errors
    /// As [`extend`](Self::extend).
    pub(crate) fn extend_merging(
        &mut self,
        zones: &[WindowZone],
        ratio: f64,
        period: f64,
    ) -> Result<(), Error> {
        self.check(zones)?;
        let mut rest = zones;
        let fixed = usize::from(self.carry.is_some());
        while let (Some(next), Some(last)) = (
            rest.first(),
            self.zones.get_mut(fixed..).and_then(<[_]>::last_mut),
        ) {
            if last.end - last.start >= MIN_ZONE_TICKS * period * last.v_limit() {
                break;
            }
            let Some(merged) = last.merged(next, ratio) else {
                break;
            };
            let kept = core::mem::replace(last, merged);
            let entry = self.planned_entry();
            plan_speeds(&mut self.zones, entry);
            if !self.entry_fits() {
                if let Some(last) = self.zones.last_mut() {
                    *last = kept;
                }
                self.replan();
                break;
            }
            rest = &rest[1..];
        }
        self.extend(rest)
    }

    /// Moves the window's entry time on to `t` while the committed motion rests at its end
    /// (it holds still until then); nothing when it moves, or `t` is earlier.
    ///
    /// ```
    /// use strak_trajectory::LookAhead;
    /// let mut window = LookAhead::<4>::new();
    /// window.hold_until(2.5);
    /// assert_eq!(window.entry(), (2.5, 0.0, 0.0));
    /// ```
    pub fn hold_until(&mut self, t: f64) {
        let (t0, s, v) = self.entry;
        if v == 0.0 && t > t0 && self.carry.is_none() {
            self.entry = (t, s, v);
        }
    }

    /// Plans the zones with the feed override `scale` (1 to 2): their feeds times `scale`,
    /// never above the machine's limits. Where a lower override would leave the committed
    /// speed no way to keep to the window, the fewest zones at its front keep the override
    /// they had (the motion cannot slow down in time for them).
    pub(crate) fn scale_feeds(&mut self, scale: f32) {
        let (mut lo, mut hi) = (0, self.zones.len());
        while lo < hi {
            let keep = lo + (hi - lo) / 2;
            if self.fits_from(keep, scale) {
                hi = keep;
            } else {
                lo = keep + 1;
            }
        }
        let keep = if self.fits_from(lo, scale) {
            lo
        } else {
            self.zones.len()
        };
        for z in self.zones.iter_mut().skip(keep) {
            z.scale = scale;
        }
        self.replan();
    }

    /// Whether the committed motion can keep to the window with its zones from `keep` on
    /// planned with the override `scale` (the speeds planned are left for
    /// [`replan`](Self::replan)).
    fn fits_from(&mut self, keep: usize, scale: f32) -> bool {
        for z in self.zones.iter_mut() {
            z.bound = f64::NAN;
        }
        let entry = self.planned_entry();
        plan_speeds_under(&mut self.zones, entry, |i, z| {
            if i < keep {
                z.v_limit()
            } else {
                z.limit_at(scale)
            }
        });
        self.entry_fits()
    }

    /// Plans every zone's speeds afresh.
    fn replan(&mut self) {
        for z in self.zones.iter_mut() {
            z.bound = f64::NAN;
        }
        let entry = self.planned_entry();
        plan_speeds(&mut self.zones, entry);
    }

    /// Commits the first zone, as a [`ProfileZone`] with its phases from the committed
    /// time, arc length and speed to the end speed the window allows: its double S, or,
    /// where the motion enters it with acceleration, the online solver's motion (its
    /// fallback where that leaves a limit). Where the speed changes in one direction on both
    /// sides of its end, the zone ends with the transition that carries the acceleration
    /// across. `None` for an empty window.
    ///
    /// ```
    /// use strak_trajectory::LookAhead;
    /// assert!(LookAhead::<4>::new().commit().is_none());
    /// ```
    pub fn commit(&mut self) -> Option<ProfileZone> {
        let first = *self.zones.first()?;
        if first.hold > 0.0 && self.entry.2 == 0.0 && self.carry.is_none() {
            self.entry.0 += f64::from(first.hold);
        }
        let (t, _, v) = self.entry;
        let zone = match self.carry.take() {
            None => first.profile(self.entry),
            Some(fallback) => match fallback.phases().first() {
                Some(p) => entered_with(&first.blank(t, v), p.local(0.0)).unwrap_or(fallback),
                None => fallback,
            },
        };
        self.zones.remove(0);
        self.entry = (zone.t_end(), zone.end, zone.v_end);
        if zone.v_end != first.v_end {
            let entry = self.planned_entry();
            forward_from(&mut self.zones, entry);
        }
        Some(self.carry_on(zone))
    }

    /// `zone`, just committed, with the transition into the window's first zone where that
    /// carries the acceleration across their boundary (the first zone keeps the rest of the
    /// transition as its fallback, and its speeds are planned again from the new entry).
    fn carry_on(&mut self, mut zone: ProfileZone) -> ProfileZone {
        let Some(next) = self.zones.first().filter(|_| self.zones.len() > 1) else {
            return zone;
        };
        let mut next = next.profile(self.entry);
        if carry_across(&mut zone, &mut next) {
            self.entry = (zone.t_end(), zone.end, zone.v_end);
            self.carry = Some(next);
            let entry = self.planned_entry();
            forward_from(&mut self.zones, entry);
        }
        zone
    }
}

/// The zones of one segment of a streamed path on their way into a window. The speed-limit
/// sampling places them by the segment's own arc lengths; they are shifted to where it
/// starts on the path (the first one starts exactly at the segment's start, the last one
/// ends exactly at its end).
///
/// A zone that its own speed limit crosses in fewer than [`MIN_ZONE_TICKS`] ticks is merged
/// with its neighbour in the segment, under the lower limits of both: a zone is entered and
/// left without acceleration, so in so short a zone the motion could change its speed only
/// by a sliver, in jerk phases shorter than a tick.
pub(crate) struct SegmentZones<const K: usize> {
    zones: Vec<WindowZone, K>,
    /// The zones held before the segment being placed.
    base: usize,
    start: f64,
    length: f64,
    /// The control period in seconds.
    period: f64,
    /// The segment's feed (rounded down to `f32`) and the override it is planned with.
    feed: (f32, f32),
}

/// A feed `x > 0` in `f32`, rounded down (a feed kept as a limit must not grow).
fn round_down(x: f64) -> f32 {
    #[allow(clippy::cast_possible_truncation)]
    let y = x as f32;
    if f64::from(y) > x { y.next_down() } else { y }
}

/// The fewest ticks in which a zone of a segment is crossed at its speed limit (else it is
/// merged with its neighbour).
const MIN_ZONE_TICKS: f64 = 16.0;

impl<const K: usize> SegmentZones<K> {
    /// No zones.
    pub(crate) const fn new() -> Self {
        SegmentZones {
            zones: Vec::new(),
            base: 0,
            start: 0.0,
            length: 0.0,
            period: 0.0,
            feed: (f32::INFINITY, 1.0),
        }
    }

    /// The zones that follow are of a segment at the arc length `start` of the path, of
    /// length `length`, played at the control period `period`, at the feed `feed` (`∞`:
    /// none) under the override `scale`.
    pub(crate) fn place(&mut self, (start, length): (f64, f64), period: f64, feed: (f64, f32)) {
        self.base = self.zones.len();
        (self.start, self.length, self.period) = (start, length, period);
        self.feed = (round_down(feed.0), feed.1);
    }

    /// Whether `zone` is crossed at its speed limit in fewer than [`MIN_ZONE_TICKS`] ticks.
    fn short(&self, zone: &WindowZone) -> bool {
        zone.end - zone.start < zone.v_limit() * self.period * MIN_ZONE_TICKS
    }

    /// The arc length of the path at the segment's arc length `s` (its end exactly).
    fn at(&self, s: f64) -> f64 {
        if s >= self.length {
            self.start + self.length
        } else {
            self.start + s
        }
    }

    /// The last zone ends at rest (an exact stop).
    pub(crate) fn stop_at_end(&mut self) {
        if let Some(last) = self.zones.last_mut() {
            last.exit_cap = 0.0;
        }
    }

    /// The lowest speed limit of the zones (feeds included); `∞` without zones.
    pub(crate) fn slowest(&self) -> f64 {
        self.zones
            .iter()
            .map(WindowZone::v_limit)
            .fold(f64::INFINITY, f64::min)
    }

    /// The time the zones take at their speed limits (feeds included).
    pub(crate) fn crossing_time(&self) -> f64 {
        self.zones
            .iter()
            .map(|z| (z.end - z.start) / z.v_limit())
            .sum()
    }

    /// The zones.
    pub(crate) fn zones(&self) -> &[WindowZone] {
        &self.zones
    }

    /// Makes the motion rest `seconds` before it enters the first zone (a dwell after a
    /// stop).
    pub(crate) fn hold_first(&mut self, seconds: f32) {
        if let Some(z) = self.zones.first_mut() {
            z.hold = seconds;
        }
    }
}

impl<const K: usize> ZoneSink for SegmentZones<K> {
    fn capacity(&self) -> usize {
        K - self.base
    }
    fn push(
        &mut self,
        (start, end): (f64, f64),
        (v, a, j): (f64, f64, f64),
        exit_cap: f64,
    ) -> usize {
        // the segment's first zone starts where it does exactly (its own arc lengths can
        // put it a rounding past its start)
        let first = self.zones.len() == self.base;
        let start = if first { self.start } else { self.at(start) };
        let mut zone = WindowZone::unchecked((start, self.at(end)), (v, a, j), exit_cap);
        (zone.feed, zone.scale) = self.feed;
        let merge = self.zones.len() > self.base
            && self.zones.last().is_some_and(|last| {
                last.exit_cap == f64::INFINITY && (self.short(last) || self.short(&zone))
            });
        match self.zones.last_mut() {
            Some(last) if merge => {
                last.end = zone.end;
                last.v_machine = last.v_machine.min(zone.v_machine);
                last.v_high = last.v_high.max(zone.v_high);
                last.a_limit = last.a_limit.min(zone.a_limit);
                last.j_limit = last.j_limit.min(zone.j_limit);
                last.exit_cap = zone.exit_cap;
                0
            }
            _ => {
                let _ = self.zones.push(zone);
                1
            }
        }
    }
    fn cap_last(&mut self, cap: f64) {
        if let Some(last) = self.zones.last_mut() {
            last.exit_cap = last.exit_cap.min(cap);
        }
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::online::testing::Rng;
    use std::vec::Vec as StdVec;

    /// `n` contiguous random zones from 0: lengths 0.05 to 20, limits across two decades,
    /// a stop at the end of one in ten, a finite cap at the end of one in five.
    fn random_zones(rng: &mut Rng, n: usize) -> StdVec<WindowZone> {
        let mut s = 0.0;
        (0..n)
            .map(|_| {
                let length = if rng.next() < 0.3 {
                    rng.range(0.05, 0.5)
                } else {
                    rng.range(0.5, 20.0)
                };
                let cap = match rng.next() {
                    x if x < 0.1 => 0.0,
                    x if x < 0.3 => rng.range(0.0, 100.0),
                    _ => f64::INFINITY,
                };
                let limits = (
                    rng.range(10.0, 200.0),
                    rng.range(100.0, 3000.0),
                    rng.range(1e3, 1e5),
                );
                let zone = WindowZone::new((s, s + length), limits, cap).unwrap();
                s += length;
                zone
            })
            .collect()
    }

    /// The committed zones are one continuous motion (time, arc length, speed and
    /// acceleration) within every zone's limits and cap, sampled at 64 points of every
    /// phase; returns the duration and the number of boundaries passed with acceleration.
    fn check_motion(zones: &[ProfileZone]) -> (f64, usize) {
        let (mut t, mut s, mut v, mut a) = (0.0, 0.0, 0.0, 0.0);
        let mut carried = 0;
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * (1.0 + a.abs().max(b.abs()));
        for z in zones {
            assert!(close(z.t_start, t) && close(z.start, s) && close(z.v_start, v));
            let a0 = z.phases().first().map_or(0.0, |p| p.a0);
            assert!((a0 - a).abs() <= 1e-6 * z.a_limit, "{a0} {a} {z:?}");
            let mut t_phase = z.t_start;
            for p in z.phases() {
                assert!(close(p.t0, t_phase), "{z:?}");
                t_phase = p.end();
            }
            for p in z.phases() {
                for i in 0..=64 {
                    let st = p.state_at(p.t0 + p.duration * f64::from(i) / 64.0);
                    assert!(
                        st.v >= -1e-9 && st.v <= z.v_limit * (1.0 + 1e-9),
                        "{st:?} {z:?}"
                    );
                    assert!(st.a.abs() <= z.a_limit * (1.0 + 1e-9), "{st:?}");
                    assert!(st.j.abs() <= z.j_limit * (1.0 + 1e-9), "{st:?}");
                }
            }
            let end = z.end_state();
            assert!(
                close(end.s, z.end) && close(end.v, z.v_end),
                "{end:?} {z:?}"
            );
            assert!(z.v_end <= z.exit_cap);
            carried += usize::from(end.a.abs() > 1e-6 * z.a_limit);
            (t, s, v, a) = (z.t_end(), z.end, z.v_end, end.a);
        }
        let a_limit = zones.last().map_or(0.0, |z| z.a_limit);
        assert!(
            v == 0.0 && a.abs() <= 1e-6 * a_limit,
            "the motion ends at rest"
        );
        (t, carried)
    }

    /// Zones streamed into a window that commits as soon as it holds more than `ahead`:
    /// the committed motion, its end speeds per zone.
    fn stream(zones: &[WindowZone], ahead: usize) -> (StdVec<ProfileZone>, StdVec<f64>) {
        let mut window = LookAhead::<64>::new();
        let mut out = StdVec::new();
        for z in zones {
            window.push(*z).unwrap();
            if window.len() > ahead {
                out.push(window.commit().unwrap());
            }
        }
        while let Some(z) = window.commit() {
            out.push(z);
        }
        let ends = out.iter().map(|z| z.v_end).collect();
        (out, ends)
    }

    /// Random zones streamed with every look-ahead from none to all: one continuous motion
    /// within every zone's limits and caps, at rest at the end (with none ahead, at the end
    /// of every zone). Printed: how much longer the motion takes with less look-ahead.
    #[test]
    fn streamed_zones_keep_the_limits() {
        let mut rng = Rng(0x5eed_1234_abcd_0001);
        let mut ratios = [0.0_f64; 4];
        let mut carried = 0;
        for _ in 0..200 {
            let n = 2 + (rng.next() * 40.0) as usize;
            let zones = random_zones(&mut rng, n);
            let (whole, _) = stream(&zones, 64);
            let (whole_time, whole_carried) = check_motion(&whole);
            carried += whole_carried;
            for (k, ahead) in [0, 1, 3, 8].into_iter().enumerate() {
                let (streamed, ends) = stream(&zones, ahead);
                ratios[k] = ratios[k].max(check_motion(&streamed).0 / whole_time);
                if ahead == 0 {
                    assert!(ends.iter().all(|&e| e == 0.0));
                }
            }
        }
        std::println!("largest duration against the whole plan, look-ahead 0, 1, 3, 8: {ratios:?}");
        std::println!("boundaries passed with acceleration: {carried}");
        assert!(carried > 100);
    }

    /// Zones of the limits `(v, a, j)` = `(100, a, 20 000)` over the extents `(start, end, a)`.
    fn rising(extents: &[(f64, f64, f64)]) -> StdVec<WindowZone> {
        let limits = |a| (100.0, a, 20_000.0);
        let zone = |&(start, end, a)| WindowZone::new((start, end), limits(a), f64::INFINITY);
        extents.iter().map(|e| zone(e).unwrap()).collect()
    }

    /// A speed that rises through two zones of different acceleration limits keeps rising
    /// across their boundary: the committed zones meet with acceleration, and the motion is
    /// faster than each zone's double S.
    #[test]
    fn a_commit_carries_the_acceleration_across_a_boundary() {
        let mut window = LookAhead::<4>::new();
        let zones = rising(&[(0.0, 2.0, 1_000.0), (2.0, 5.0, 800.0), (5.0, 9.0, 800.0)]);
        window.extend(&zones).unwrap();
        let mut double_s = 0.0;
        let mut entry = window.entry();
        for w in &window.zones {
            let z = w.profile(entry);
            double_s += z.t_end() - z.t_start;
            entry = (z.t_end(), z.end, z.v_end);
        }
        let first = window.commit().unwrap();
        assert!(first.end_state().a > 100.0, "{first:?}");
        let mut committed = std::vec![first];
        committed.extend(core::iter::from_fn(|| window.commit()));
        let (duration, carried) = check_motion(&committed);
        assert!(carried >= 1);
        assert!(duration < double_s - 1e-3, "{duration} {double_s}");
    }

    /// A zone entered with acceleration ends at the speed the window plans when it is
    /// committed (the online solver's motion), above its fallback's once more is known.
    #[test]
    fn a_zone_entered_with_acceleration_ends_as_planned_when_committed() {
        let mut window = LookAhead::<4>::new();
        let zones = rising(&[(0.0, 2.0, 1_000.0), (2.0, 5.0, 800.0), (5.0, 5.5, 800.0)]);
        window.extend(&zones).unwrap();
        let first = window.commit().unwrap();
        let fallback = window.carry.map(|f| f.v_end).unwrap();
        window.push(rising(&[(5.5, 40.0, 800.0)])[0]).unwrap();
        let second = window.commit().unwrap();
        assert!(second.v_end > fallback + 1.0, "{} {fallback}", second.v_end);
        let mut committed = std::vec![first, second];
        committed.extend(core::iter::from_fn(|| window.commit()));
        check_motion(&committed);
    }

    /// Chains of short zones whose limits differ by up to 4 % (a dense chain of blends),
    /// between longer zones, streamed one by one with merging (control period 1 ms): fewer
    /// zones are committed, each merged one is crossed at its limit (before its last part
    /// was merged) in fewer than 16 ticks plus its last part, and the committed motion keeps
    /// every original zone's limits.
    #[test]
    fn merged_zones_keep_every_zones_limits() {
        let mut rng = Rng(0x5eed_1234_abcd_0003);
        let period = 1e-3;
        let (mut pushed, mut committed) = (0, 0);
        for _ in 0..100 {
            let mut zones = StdVec::new();
            let mut s = 0.0;
            for _ in 0..(2 + (rng.next() * 6.0) as usize) {
                let (v, a, j) = (
                    rng.range(20.0, 200.0),
                    rng.range(500.0, 3000.0),
                    rng.range(1e4, 1e5),
                );
                let short = rng.next() < 0.7;
                for _ in 0..if short { 30 } else { 1 } {
                    let length = if short {
                        rng.range(0.05, 0.3)
                    } else {
                        rng.range(1.0, 20.0)
                    };
                    let w = 1.0 + 0.04 * rng.next();
                    let zone =
                        WindowZone::new((s, s + length), (v * w, a * w, j * w), f64::INFINITY)
                            .unwrap();
                    zones.push(zone);
                    s += length;
                }
            }
            let mut window = LookAhead::<64>::new();
            let mut out = StdVec::new();
            for z in &zones {
                window
                    .extend_merging(core::slice::from_ref(z), 1.05, period)
                    .unwrap();
                if window.len() > 4 {
                    out.push(window.commit().unwrap());
                }
            }
            while let Some(z) = window.commit() {
                out.push(z);
            }
            check_motion(&out);
            (pushed, committed) = (pushed + zones.len(), committed + out.len());
            for z in &out {
                let inside: StdVec<&WindowZone> = zones
                    .iter()
                    .filter(|w| w.start >= z.start && w.end <= z.end)
                    .collect();
                let last = inside.last().map_or(0.0, |w| w.end - w.start);
                // (the limit before the last merge was at most 1.05 times the merged one)
                assert!(z.end - z.start - last < 16.0 * period * 1.05 * z.v_limit);
                for p in z.phases() {
                    for i in 0..=16 {
                        let st = p.state_at(p.t0 + p.duration * f64::from(i) / 16.0);
                        let w = inside.iter().find(|w| st.s <= w.end).unwrap_or(&inside[0]);
                        assert!(st.v <= w.v_machine * (1.0 + 1e-9), "{st:?} {w:?}");
                        assert!(st.a.abs() <= w.a_limit * (1.0 + 1e-9), "{st:?} {w:?}");
                        assert!(st.j.abs() <= w.j_limit * (1.0 + 1e-9), "{st:?} {w:?}");
                    }
                }
            }
        }
        std::println!("{pushed} zones pushed, {committed} committed");
        assert!(2 * committed < pushed, "{committed} of {pushed}");
    }

    /// A merge that lowers the last zone's speed limit below the committed speed is taken
    /// back: the zone is appended on its own, and the motion slows down into it.
    #[test]
    fn a_merge_below_the_committed_speed_is_taken_back() {
        let limits = |v: f64| (v, 3_000.0, 1e5);
        let mut window = LookAhead::<8>::new();
        window
            .push(WindowZone::new((0.0, 1_000.0), limits(100.0), f64::INFINITY).unwrap())
            .unwrap();
        window
            .push(WindowZone::new((1_000.0, 1_100.0), limits(100.0), f64::INFINITY).unwrap())
            .unwrap();
        let first = window.commit().unwrap();
        assert_eq!(first.v_end, 100.0);
        // within 5 % and crossed in fewer than 16 ticks of 0.1 s: merged
        let above = WindowZone::new((1_100.0, 1_110.0), limits(100.5), f64::INFINITY).unwrap();
        window.extend_merging(&[above], 1.05, 0.1).unwrap();
        assert_eq!(window.len(), 1);
        // lower than the committed 100: taken back
        let below = WindowZone::new((1_110.0, 1_120.0), limits(96.0), f64::INFINITY).unwrap();
        window.extend_merging(&[below], 1.05, 0.1).unwrap();
        assert_eq!(window.len(), 2);
        let mut out = std::vec![first];
        while let Some(z) = window.commit() {
            out.push(z);
        }
        check_motion(&out);
        assert_eq!(out[1].v_limit, 100.0);
        assert_eq!(out[2].v_limit, 96.0);
    }

    /// A window that runs dry comes to rest, and the zones that arrive afterwards start from
    /// rest where it stopped.
    /// Feed overrides changed at random while zones with random feeds are streamed: the
    /// committed motion stays continuous and within every zone's limits, raising the
    /// override never slows a zone down, and the zones keep their feeds times the override
    /// they were committed with (never above the machine's limit).
    #[test]
    fn feed_overrides_keep_the_window_feasible() {
        let mut rng = Rng(0x5eed_1234_abcd_0002);
        let mut kept = 0;
        for _ in 0..200 {
            let n = 4 + (rng.next() * 40.0) as usize;
            let mut zones = random_zones(&mut rng, n);
            for z in &mut zones {
                z.feed = round_down(rng.range(5.0, 150.0));
            }
            let ahead = 1 + (rng.next() * 12.0) as usize;
            let mut window = LookAhead::<64>::new();
            let mut out = StdVec::new();
            let mut scale = 1.0_f32;
            for z in &zones {
                let mut z = *z;
                z.scale = scale;
                window.push(z).unwrap();
                if rng.next() < 0.3 {
                    #[allow(clippy::cast_possible_truncation)]
                    let next = if rng.next() < 0.5 {
                        1.0
                    } else {
                        rng.range(1.0, 2.0) as f32
                    };
                    let before: StdVec<f32> = window.zones.iter().map(|z| z.scale).collect();
                    window.scale_feeds(next);
                    let changed = window.zones.iter().zip(&before);
                    kept += changed
                        .filter(|(z, b)| z.scale == **b && **b != next)
                        .count();
                    scale = next;
                }
                if window.len() > ahead {
                    out.push(window.commit().unwrap());
                }
            }
            while let Some(z) = window.commit() {
                out.push(z);
            }
            check_motion(&out);
            for (p, z) in out.iter().zip(&zones) {
                assert!(p.v_limit <= z.v_machine);
                assert!(p.v_limit <= f64::from(z.feed) * 2.0);
            }
        }
        std::println!("zones that kept a higher override to stay feasible: {kept}");
    }

    #[test]
    fn a_drained_window_rests_and_resumes() {
        let limits = (100.0, 1_000.0, 20_000.0);
        let mut window = LookAhead::<4>::new();
        window
            .push(WindowZone::new((0.0, 5.0), limits, f64::INFINITY).unwrap())
            .unwrap();
        window
            .push(WindowZone::new((5.0, 10.0), limits, f64::INFINITY).unwrap())
            .unwrap();
        let a = window.commit().unwrap();
        assert!(a.v_end > 0.0, "a zone with one behind it keeps moving");
        let b = window.commit().unwrap();
        assert_eq!(b.v_end, 0.0);
        assert_eq!(window.entry(), (b.t_end(), 10.0, 0.0));
        window
            .push(WindowZone::new((10.0, 20.0), limits, f64::INFINITY).unwrap())
            .unwrap();
        let c = window.commit().unwrap();
        assert_eq!((c.v_start, c.t_start, c.start), (0.0, b.t_end(), 10.0));
        check_motion(&[a, b, c]);
    }
}
