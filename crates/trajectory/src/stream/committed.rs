//! The committed motion of a stream on the tick grid: the phases of the zones the window has
//! committed, along the segments of the path, as the stretch fit takes it.
//!
//! With the arc length `s(t)` of the phases, `v = ṡ`, `a = s̈` and the frame `x(s)`,
//! `T = x_s`, `κN = x_ss` of the segment under `s`, the motion is
//!
//! ```text
//! x(t) = x(s(t)),   ẋ = v·T,   ẍ = a·T + v²·κN
//! ```
//!
//! and per tick of `h` seconds the slope is `ẋ·h` and the second derivative `ẍ·h²`.

use core::cell::Cell;

use heapless::Deque;

use super::moves::StreamCurve;
use super::segment::{Frame, Segment};
use crate::compile::TickMotion;
use crate::error::Error;
use crate::plan::{MotionLimits, MotionState, PHASES_PER_ZONE, Phase};

/// The most phases committed and not yet compiled past: two zones' worth and room for one
/// more.
pub(super) const PHASES: usize = 3 * PHASES_PER_ZONE;

/// The ticks whose states and frames a committed motion keeps: a span's two ends, or the
/// ticks of a run of one-tick pieces in turn.
pub(super) const RECENT: usize = 4;

/// The ticks whose positions a committed motion keeps: a stretch of the default length
/// ([`StreamOptions`](super::StreamOptions)), so that the spline fit, which checks its
/// pieces against every tick and fits again tighter where they exceed a limit, evaluates
/// each tick's position once.
pub(super) const POINTS: usize = 64;

/// Bisection steps locating a join of segments in a phase: to well below a nanosecond.
const JOIN_BISECTION_STEPS: usize = 48;

/// How far past a join (relative to the arc length, at least 1 unit) a braking motion is
/// still taken to be on the segment it arrives on: the rounding of the arc lengths.
const JOIN_ROUNDING: f64 = 1e-12;

/// What a committed motion keeps of the ticks it evaluated last. The stream holds it, so
/// that the stack holds one (a stretch's positions are a few kilobytes), and clears it for
/// every committed motion it makes.
#[derive(Clone, Debug)]
pub(super) struct TickCache<const D: usize> {
    /// The ticks evaluated last, their states and frames, by tick modulo [`RECENT`]: a
    /// stretch asks for the position, slope and second derivative of a tick in turn, and
    /// for the ticks near it again as it refines its pieces.
    recent: [Cell<Option<(u32, MotionState, Frame<D>)>>; RECENT],
    /// The ticks whose position alone was evaluated last, by tick modulo [`POINTS`], each
    /// plus one (0: none; the last tick of all is never kept): the spline fit checks its
    /// pieces against the positions of every tick, which need neither the tangent nor the
    /// curvature of the frame.
    point_ticks: [Cell<u32>; POINTS],
    /// Their points.
    points: [Cell<[f64; D]>; POINTS],
}

impl<const D: usize> TickCache<D> {
    /// Nothing kept.
    pub(super) const fn new() -> Self {
        TickCache {
            recent: [const { Cell::new(None) }; RECENT],
            point_ticks: [const { Cell::new(0) }; POINTS],
            points: [const { Cell::new([0.0; D]) }; POINTS],
        }
    }

    /// Forgets every tick.
    pub(super) fn clear(&self) {
        for slot in &self.recent {
            slot.set(None);
        }
        for tick in &self.point_ticks {
            tick.set(0);
        }
    }
}

/// The committed motion of a stream: its phases in time order and the segments they run
/// along, on the grid of `period` seconds, within the limits `limits`, up to `end`.
pub(super) struct Committed<'a, const D: usize, const Q: usize, C, const R: usize> {
    pub(super) segments: &'a Deque<Segment<D, C, R>, Q>,
    pub(super) phases: &'a Deque<Phase, PHASES>,
    pub(super) period: f64,
    pub(super) limits: MotionLimits,
    /// The end of the committed motion: time, arc length and speed.
    pub(super) end: (f64, f64, f64),
    /// The states, frames and positions of the ticks evaluated last.
    pub(super) ticks: &'a TickCache<D>,
    /// The index of the segment found last.
    pub(super) cursor: Cell<usize>,
}

impl<const D: usize, const Q: usize, C: StreamCurve<D>, const R: usize> Committed<'_, D, Q, C, R> {
    /// The state at time `t`: in the last phase that starts at or before it. After a phase
    /// that ends at rest the motion holds still until the next phase, exactly where that
    /// one starts (or at the committed end `end`, the end of its last zone): the rounding
    /// of a zone's phases leaves their end within about `1e-9` of the zone's own.
    pub(super) fn state(&self, t: f64) -> MotionState {
        let mut found = None;
        let mut next = None;
        for p in self.phases.iter() {
            if p.t0 <= t || found.is_none() {
                found = Some(p);
            } else {
                next = Some(p);
                break;
            }
        }
        let Some(p) = found else {
            return MotionState::default();
        };
        let st = p.state_at(t);
        if t < p.end() || st.v > 0.0 {
            return st;
        }
        let s = match next {
            Some(q) => q.s0,
            None if self.end.2 == 0.0 => self.end.1,
            None => st.s,
        };
        MotionState {
            s,
            ..MotionState::default()
        }
    }

    /// The state and the frame at tick `k`.
    fn at_tick(&self, k: u32) -> Result<(MotionState, Frame<D>), Error> {
        let slot = &self.ticks.recent[k as usize % RECENT];
        if let Some((tick, st, f)) = slot.get()
            && tick == k
        {
            return Ok((st, f));
        }
        let st = self.state(f64::from(k) * self.period);
        let f = self.segment_at(st.s, st.a < 0.0)?.frame(st.s)?;
        slot.set(Some((k, st, f)));
        Ok((st, f))
    }

    /// The position at tick `k`: the point of its frame ([`Self::at_tick`]), evaluated
    /// alone where the frame is not at hand.
    fn point_at(&self, k: u32) -> Result<[f64; D], Error> {
        let slot = k as usize % POINTS;
        let (tick, point) = (&self.ticks.point_ticks[slot], &self.ticks.points[slot]);
        let key = k.wrapping_add(1);
        if key != 0 && tick.get() == key {
            return Ok(point.get());
        }
        if let Some((tick, _, f)) = self.ticks.recent[k as usize % RECENT].get()
            && tick == k
        {
            return Ok(f.point);
        }
        let st = self.state(f64::from(k) * self.period);
        let x = self.segment_at(st.s, st.a < 0.0)?.point(st.s)?;
        tick.set(key);
        point.set(x);
        Ok(x)
    }

    /// Calls `emit` with the times in the phase `p` at which the path passes from one
    /// segment to the next, in order (by bisection: `s` does not fall within a phase).
    fn joins_in(&self, p: &Phase, emit: &mut impl FnMut(f64)) {
        let end = p.state_at(p.end()).s;
        for join in self.segments.iter().skip(1).map(|g| g.start) {
            if join >= end {
                break;
            }
            if join < p.s0 {
                continue;
            }
            let (mut a, mut b) = (p.t0, p.end());
            for _ in 0..JOIN_BISECTION_STEPS {
                let mid = 0.5 * (a + b);
                if p.state_at(mid).s < join {
                    a = mid;
                } else {
                    b = mid;
                }
            }
            emit(b);
        }
    }

    /// The segment of the path at the arc length `s`: the last segment that starts at or
    /// before it (the first one before the start). At a join the motion is on the segment
    /// it enters, so that after an exact stop at a corner it leaves along the next segment
    /// from its first tick (the previous segment's end, `start + length`, can exceed the
    /// join by its rounding); but while it is `braking` it is on the segment it arrives on
    /// up to [`JOIN_ROUNDING`] past the join, so that a tick a sliver before it comes to
    /// rest at a corner keeps the direction it arrives from (the corner turns its
    /// acceleration, which the jerk from tick to tick would otherwise take as a step).
    fn segment_at(&self, s: f64, braking: bool) -> Result<&Segment<D, C, R>, Error> {
        let slack = if braking {
            JOIN_ROUNDING * s.abs().max(1.0)
        } else {
            0.0
        };
        let on = last_holding(self.segments, &self.cursor, |g| {
            g.start + slack < s || (!braking && g.start <= s)
        });
        self.segments.get(on).ok_or(Error::EmptyPath)
    }
}

/// The index of the last of `items` for which `holds` is true (0 where it holds for none),
/// where it holds for a prefix of them (the segments start in order along the path). The
/// ticks asked for mostly follow each other: the index found last, in `cursor`, is tried
/// first, then the one after it, then the bisection of the deque.
fn last_holding<T, const N: usize>(
    items: &Deque<T, N>,
    cursor: &Cell<usize>,
    holds: impl Fn(&T) -> bool,
) -> usize {
    let is_last = |i: usize| {
        (i == 0 || items.get(i).is_some_and(&holds)) && items.get(i + 1).is_none_or(|x| !holds(x))
    };
    let hint = cursor.get();
    let at = if is_last(hint) {
        hint
    } else if is_last(hint + 1) {
        hint + 1
    } else {
        prefix_len(items, &holds).saturating_sub(1)
    };
    cursor.set(at);
    at
}

/// The length of the prefix of `items` for which `holds` is true, where it holds for a
/// prefix (items in an order that `holds` respects), by bisection of the deque's two
/// slices.
fn prefix_len<T, const N: usize>(items: &Deque<T, N>, holds: impl Fn(&T) -> bool) -> usize {
    let (head, tail) = items.as_slices();
    let n = head.partition_point(&holds);
    if n < head.len() {
        n
    } else {
        n + tail.partition_point(holds)
    }
}

impl<const D: usize, const Q: usize, C: StreamCurve<D>, const R: usize> TickMotion<D>
    for Committed<'_, D, Q, C, R>
{
    fn period(&self) -> f64 {
        self.period
    }

    fn position(&self, k: u32) -> Result<[f64; D], Error> {
        self.point_at(k)
    }

    fn slope(&self, k: u32) -> Result<[f64; D], Error> {
        let (st, f) = self.at_tick(k)?;
        let h = self.period;
        Ok(f.tangent.map(|t| t * st.v * h))
    }

    fn second(&self, k: u32) -> Result<[f64; D], Error> {
        let (st, f) = self.at_tick(k)?;
        let hh = self.period * self.period;
        Ok(core::array::from_fn(|i| {
            (f.tangent[i] * st.a + f.normal[i] * st.v * st.v) * hh
        }))
    }

    /// The times where the jerk changes: the starts of the phases whose jerk differs from
    /// the motion's before them, the ends of the phases after which it rests, and the joins
    /// of segments (where the derivative of the curvature steps, and with it `x⃛`).
    fn breaks_between(&self, first: u32, last: u32, f: &mut dyn FnMut(f64)) {
        let (lo, hi) = (f64::from(first), f64::from(last));
        let mut latest = lo;
        let mut emit = |t: f64| {
            let k = t / self.period;
            if k > latest && k < hi {
                f(k);
                latest = k;
            }
        };
        let mut prev: Option<&Phase> = None;
        for p in self.phases.iter() {
            let before = match prev {
                Some(q) if p.t0 > q.end() => {
                    if q.j != 0.0 {
                        emit(q.end());
                    }
                    0.0
                }
                Some(q) => q.j,
                None => 0.0,
            };
            if p.j != before {
                emit(p.t0);
            }
            self.joins_in(p, &mut emit);
            prev = Some(p);
        }
        if let Some(q) = prev.filter(|q| q.j != 0.0) {
            emit(q.end());
        }
    }

    fn limits(&self) -> Option<MotionLimits> {
        Some(self.limits)
    }
}
