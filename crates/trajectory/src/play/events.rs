//! The event player: a run's operator events (feed override, hold, resume, abort) applied to
//! a sampler before the sample of their tick, and the run guard that ends a run the sampler
//! never finishes (a hold without resume).

use super::{Kernel, Sampler};
use crate::path::Sample;

/// An operator event: a call of the [`Sampler`]'s feed interface.
///
/// ```
/// use strak_trajectory::Event;
/// let hold = Event::Hold;
/// assert_ne!(hold, Event::Resume);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Event {
    /// Feed override in `[0, 1]` ([`Sampler::set_feed`]).
    Feed(f32),
    /// Feed hold: ramp down to rest on the path ([`Sampler::hold`]).
    Hold,
    /// Resume after a hold ([`Sampler::resume`]).
    Resume,
    /// Abort: come to rest on the path and finish there ([`Sampler::abort`]).
    Abort,
    /// Slows the later feed ramps by `2⁻ˢʰⁱᶠᵗ` ([`Sampler::scale_feed_ramp`]): what a
    /// [`FeedGuard`](crate::FeedGuard) puts before a feed change it has checked.
    RampScale(u8),
}

/// An event at a tick: it applies before the sample of `tick` (ticks count the samples of a
/// run from 0, holds included).
///
/// ```
/// use strak_trajectory::{Event, TimedEvent};
/// let e = TimedEvent { tick: 250, event: Event::Feed(0.5) };
/// assert_eq!(e.tick, 250);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct TimedEvent {
    /// The tick before whose sample the event applies.
    pub tick: u64,
    /// What happens.
    pub event: Event,
}

/// What the [`EventPlayer`] needs of a sampler: one sample per tick, whether the motion is
/// over, and the operator events. [`Sampler`] implements it; a test may implement it for a
/// stand-in.
///
/// ```
/// use strak_trajectory::{Event, Playable};
///
/// /// Counts down to 0, standing still while held.
/// struct Countdown { left: u32, held: bool }
/// impl Playable for Countdown {
///     type Sample = u32;
///     fn next_sample(&mut self) -> u32 {
///         if !self.held { self.left = self.left.saturating_sub(1); }
///         self.left
///     }
///     fn is_finished(&self) -> bool { self.left == 0 }
///     fn apply(&mut self, event: Event) { self.held = event == Event::Hold; }
/// }
/// let mut c = Countdown { left: 2, held: false };
/// c.apply(Event::Hold);
/// assert_eq!(c.next_sample(), 2);
/// ```
pub trait Playable {
    /// One control tick's sample.
    type Sample;
    /// The next sample (one control tick).
    fn next_sample(&mut self) -> Self::Sample;
    /// Whether the motion is over: every further sample repeats the last position at rest.
    fn is_finished(&self) -> bool;
    /// Applies `event`.
    fn apply(&mut self, event: Event);
}

impl<N: Kernel, const A: usize> Playable for Sampler<'_, N, A> {
    type Sample = Sample<N::Out, A>;

    #[inline]
    fn next_sample(&mut self) -> Self::Sample {
        self.next()
    }

    #[inline]
    fn is_finished(&self) -> bool {
        Sampler::is_finished(self)
    }

    #[inline]
    fn apply(&mut self, event: Event) {
        match event {
            Event::Feed(f) => self.set_feed(f),
            Event::Hold => self.hold(),
            Event::Resume => self.resume(),
            Event::Abort => self.abort(),
            Event::RampScale(shift) => {
                self.scale_feed_ramp(shift);
            }
        }
    }
}

/// Why a run ended.
///
/// ```
/// use strak_trajectory::RunEnd;
/// assert_ne!(RunEnd::Finished, RunEnd::Guard);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum RunEnd {
    /// The sampler finished: the end of the path, or at rest after an abort.
    Finished,
    /// The guard ended a run the sampler had not finished (a hold without resume, or a feed
    /// override below 1/10 for most of the path).
    Guard,
}

/// The multiple of a path's duration (in ticks, the end sample included) after which the
/// guard ends a run: a run at feed override 1/10 takes that long.
const GUARD_FACTOR: u64 = 10;

/// Plays a run: applies sorted [`TimedEvent`]s to a [`Playable`] sampler before the sample of
/// their tick, and ends the run once the sampler is finished or the guard is reached.
///
/// * The events of tick `k` (with `tick ≤ k`, in their order, each once) apply before sample
///   `k`; ticks count samples from 0, a held sampler's samples included.
/// * A run takes at least one sample, and ends after the sample on which the sampler is
///   finished.
/// * The guard ends a run the sampler never finishes after
///   `10·(ticks + 1) + last event tick + 1` samples, `ticks` being the path's duration in
///   ticks ([`PathHeader::ticks`](crate::PathHeader::ticks)): ten times the path played at
///   full feed, after the last event.
///
/// The player holds the events by reference and four counters: no allocation, no panic path,
/// constant time per tick beyond the events applied.
///
/// ```
/// use strak_curves::Bezier;
/// use strak_trajectory::{
///     compile, Along, CompileOptions, Event, EventPlayer, Path, RunEnd, Sampler, TimedEvent,
///     Timing,
/// };
///
/// /// Rest to rest in 2 s: u = 3τ² − 2τ³.
/// struct Smooth;
/// impl Timing for Smooth {
///     fn duration(&self) -> f64 { 2.0 }
///     fn param(&self, t: f64) -> (f64, f64) {
///         let s = t.clamp(0.0, 2.0) / 2.0;
///         (s * s * (3.0 - 2.0 * s), 6.0 * s * (1.0 - s) / 2.0)
///     }
/// }
/// let curve = Bezier::new([[0.0_f64, 0.0], [5.0, 0.0], [5.0, 5.0]])?;
/// // Feed changes ramp within the machine's acceleration and jerk limits.
/// let options = CompileOptions::new().with_limits(100.0, 10_000.0);
/// let path: Path<f64, 2, 64> = compile(&Along::new(&curve, &Smooth), 1_000.0, &options)?;
///
/// // A hold at tick 10 and a resume at tick 1 500: the run takes longer than the path.
/// let events = [
///     TimedEvent { tick: 10, event: Event::Hold },
///     TimedEvent { tick: 1_500, event: Event::Resume },
/// ];
/// let mut player = EventPlayer::new(&events, path.ticks());
/// let mut sampler = Sampler::new(&path);
/// let mut last = None;
/// while let Some(s) = player.step(&mut sampler) {
///     last = Some(s);
/// }
/// assert_eq!(player.end(&sampler), RunEnd::Finished);
/// assert!(player.samples() > u64::from(path.ticks()) + 1);
/// assert_eq!(last.unwrap().position, path.end_position());
///
/// // Without the resume, the guard ends the run.
/// let mut player = EventPlayer::new(&events[..1], path.ticks());
/// let mut sampler = Sampler::new(&path);
/// while player.step(&mut sampler).is_some() {}
/// assert_eq!(player.end(&sampler), RunEnd::Guard);
/// assert_eq!(player.samples(), 10 * (u64::from(path.ticks()) + 1) + 10 + 1);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct EventPlayer<'e> {
    events: &'e [TimedEvent],
    next: usize,
    samples: u64,
    guard: u64,
    aborted: bool,
}

impl<'e> EventPlayer<'e> {
    /// A player at tick 0 of a path of `ticks` ticks; `events` sorted by tick (an event out
    /// of order applies with the first later tick's events).
    ///
    /// ```
    /// use strak_trajectory::EventPlayer;
    /// assert_eq!(EventPlayer::new(&[], 99).guard(), 1_001);
    /// ```
    pub const fn new(events: &'e [TimedEvent], ticks: u32) -> Self {
        let last_event = match events.last() {
            Some(e) => e.tick,
            None => 0,
        };
        let path_samples = ticks as u64 + 1;
        EventPlayer {
            events,
            next: 0,
            samples: 0,
            guard: (GUARD_FACTOR * path_samples)
                .saturating_add(last_event)
                .saturating_add(1),
            aborted: false,
        }
    }

    /// Applies the events due before the next sample (none twice).
    ///
    /// ```
    /// use strak_trajectory::{Event, EventPlayer, Playable, TimedEvent};
    /// struct Log(u32);
    /// impl Playable for Log {
    ///     type Sample = ();
    ///     fn next_sample(&mut self) {}
    ///     fn is_finished(&self) -> bool { false }
    ///     fn apply(&mut self, _: Event) { self.0 += 1; }
    /// }
    /// let events = [TimedEvent { tick: 0, event: Event::Hold }];
    /// let (mut player, mut log) = (EventPlayer::new(&events, 5), Log(0));
    /// player.apply_due(&mut log);
    /// player.apply_due(&mut log);
    /// assert_eq!(log.0, 1);
    /// ```
    #[inline]
    pub fn apply_due<P: Playable>(&mut self, sampler: &mut P) {
        while let Some(e) = self.events.get(self.next) {
            if e.tick > self.samples {
                break;
            }
            self.aborted |= e.event == Event::Abort;
            sampler.apply(e.event);
            self.next += 1;
        }
    }

    /// One tick: the events due, then one sample; `None` once the run is over
    /// ([`is_over`](Self::is_over)).
    ///
    /// ```
    /// use strak_trajectory::{EventPlayer, Playable, Event};
    /// struct Done;
    /// impl Playable for Done {
    ///     type Sample = u8;
    ///     fn next_sample(&mut self) -> u8 { 7 }
    ///     fn is_finished(&self) -> bool { true }
    ///     fn apply(&mut self, _: Event) {}
    /// }
    /// let mut player = EventPlayer::new(&[], 0);
    /// assert_eq!(player.step(&mut Done), Some(7)); // a run takes at least one sample
    /// assert_eq!(player.step(&mut Done), None);
    /// ```
    #[inline]
    pub fn step<P: Playable>(&mut self, sampler: &mut P) -> Option<P::Sample> {
        if self.is_over(sampler) {
            return None;
        }
        self.apply_due(sampler);
        self.samples += 1;
        Some(sampler.next_sample())
    }

    /// Whether the run is over: the sampler finished after at least one sample, or the guard
    /// is reached.
    ///
    /// ```
    /// use strak_trajectory::{EventPlayer, Path, Sampler};
    /// let path = Path::<f32, 1, 4>::new();
    /// let (player, sampler) = (EventPlayer::new(&[], 0), Sampler::new(&path));
    /// assert!(!player.is_over(&sampler)); // no sample yet
    /// ```
    #[inline]
    pub fn is_over<P: Playable>(&self, sampler: &P) -> bool {
        self.samples > 0 && (sampler.is_finished() || self.samples >= self.guard)
    }

    /// Why the run ended (or would end now): [`RunEnd::Finished`] if the sampler is
    /// finished, else [`RunEnd::Guard`].
    ///
    /// ```
    /// use strak_trajectory::{EventPlayer, Path, RunEnd, Sampler};
    /// let path = Path::<f32, 1, 4>::new();
    /// let mut sampler = Sampler::new(&path);
    /// let mut player = EventPlayer::new(&[], path.ticks());
    /// while player.step(&mut sampler).is_some() {}
    /// assert_eq!(player.end(&sampler), RunEnd::Finished);
    /// ```
    pub fn end<P: Playable>(&self, sampler: &P) -> RunEnd {
        if sampler.is_finished() {
            RunEnd::Finished
        } else {
            RunEnd::Guard
        }
    }

    /// The samples played.
    ///
    /// ```
    /// use strak_trajectory::EventPlayer;
    /// assert_eq!(EventPlayer::new(&[], 3).samples(), 0);
    /// ```
    pub const fn samples(&self) -> u64 {
        self.samples
    }

    /// The most samples a run takes: `10·(ticks + 1) + last event tick + 1`.
    ///
    /// ```
    /// use strak_trajectory::{Event, EventPlayer, TimedEvent};
    /// let events = [TimedEvent { tick: 40, event: Event::Hold }];
    /// assert_eq!(EventPlayer::new(&events, 9).guard(), 100 + 40 + 1);
    /// ```
    pub const fn guard(&self) -> u64 {
        self.guard
    }

    /// The events applied so far.
    ///
    /// ```
    /// use strak_trajectory::EventPlayer;
    /// assert_eq!(EventPlayer::new(&[], 3).applied(), 0);
    /// ```
    pub const fn applied(&self) -> usize {
        self.next
    }

    /// The events not applied (so far; after the run, those whose tick came after its end).
    ///
    /// ```
    /// use strak_trajectory::{Event, EventPlayer, TimedEvent};
    /// let events = [TimedEvent { tick: 5, event: Event::Abort }];
    /// assert_eq!(EventPlayer::new(&events, 3).ignored(), 1);
    /// ```
    pub const fn ignored(&self) -> usize {
        self.events.len().saturating_sub(self.next)
    }

    /// Whether an abort was applied.
    ///
    /// ```
    /// use strak_trajectory::EventPlayer;
    /// assert!(!EventPlayer::new(&[], 3).aborted());
    /// ```
    pub const fn aborted(&self) -> bool {
        self.aborted
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use std::vec::Vec;

    use strak_curves::Bezier;

    use super::*;
    use crate::{Along, CompileOptions, Path, Timing, compile};

    /// Finishes after `left` unheld samples; records each event with the sample count at
    /// which it applied; its sample is its own sample count.
    struct Fake {
        left: u32,
        held: bool,
        seen: Vec<(u32, Event)>,
        count: u32,
    }

    impl Playable for Fake {
        type Sample = u32;
        fn next_sample(&mut self) -> u32 {
            self.count += 1;
            if !self.held {
                self.left = self.left.saturating_sub(1);
            }
            self.count - 1
        }
        fn is_finished(&self) -> bool {
            self.left == 0
        }
        fn apply(&mut self, e: Event) {
            self.held = match e {
                Event::Hold => true,
                Event::Resume => false,
                _ => self.held,
            };
            self.seen.push((self.count, e));
        }
    }

    fn fake(left: u32) -> Fake {
        Fake {
            left,
            held: false,
            seen: Vec::new(),
            count: 0,
        }
    }

    fn at(tick: u64, event: Event) -> TimedEvent {
        TimedEvent { tick, event }
    }

    #[test]
    fn an_event_applies_before_the_sample_of_its_tick() {
        let events = [
            at(0, Event::Feed(0.5)),
            at(2, Event::Hold),
            at(4, Event::Resume),
            at(99, Event::Abort),
        ];
        let mut p = EventPlayer::new(&events, 5);
        let mut s = fake(6);
        let mut samples = Vec::new();
        while let Some(k) = p.step(&mut s) {
            samples.push(k);
        }
        assert_eq!(
            s.seen,
            [(0, Event::Feed(0.5)), (2, Event::Hold), (4, Event::Resume)]
        );
        // Held for ticks 2 and 3: two samples more than the six of the path.
        assert_eq!(samples, [0, 1, 2, 3, 4, 5, 6, 7]);
        assert_eq!((p.applied(), p.ignored(), p.aborted()), (3, 1, false));
        assert_eq!(p.end(&s), RunEnd::Finished);
        p.apply_due(&mut s);
        assert_eq!(s.seen.len(), 3, "apply_due applies nothing twice");
    }

    #[test]
    fn holds_count_ticks() {
        // Events at the same tick apply together; a late event after a hold still comes at
        // its tick, counted in samples (the held ones included), not in path progress.
        let events = [
            at(1, Event::Hold),
            at(1, Event::Feed(0.5)),
            at(6, Event::Resume),
        ];
        let mut p = EventPlayer::new(&events, 2);
        let mut s = fake(3);
        while p.step(&mut s).is_some() {}
        assert_eq!(
            s.seen,
            [(1, Event::Hold), (1, Event::Feed(0.5)), (6, Event::Resume)]
        );
        // 1 sample before the hold, 5 held, 2 after the resume.
        assert_eq!(p.samples(), 8);
    }

    #[test]
    fn the_guard_ends_a_hold_without_resume_after_the_documented_samples() {
        let events = [at(3, Event::Hold)];
        let mut p = EventPlayer::new(&events, 5);
        assert_eq!(p.guard(), 10 * 6 + 3 + 1);
        let mut s = fake(6);
        let mut n = 0_u64;
        while p.step(&mut s).is_some() {
            n += 1;
        }
        assert_eq!((n, p.samples()), (64, 64));
        assert_eq!(p.end(&s), RunEnd::Guard);
        assert!(p.step(&mut s).is_none());
    }

    #[test]
    fn a_finished_path_still_plays_one_sample_and_an_abort_is_recorded() {
        let mut p = EventPlayer::new(&[], 0);
        let mut s = fake(0);
        assert_eq!(p.step(&mut s), Some(0));
        assert_eq!(p.step(&mut s), None);
        let abort = [at(0, Event::Abort)];
        let mut p = EventPlayer::new(&abort, 3);
        let mut s = fake(1);
        while p.step(&mut s).is_some() {}
        assert!(p.aborted());
    }

    /// Rest to rest in 200 ms: u = 3τ² − 2τ³.
    struct Smooth;
    impl Timing for Smooth {
        fn duration(&self) -> f64 {
            0.2
        }
        fn param(&self, t: f64) -> (f64, f64) {
            let s = t.clamp(0.0, 0.2) / 0.2;
            (s * s * (3.0 - 2.0 * s), 6.0 * s * (1.0 - s) / 0.2)
        }
    }

    #[test]
    fn the_sampler_plays_the_events_as_its_own_calls() {
        let curve = Bezier::new([[0.0_f64, 0.0], [4.0, 0.0], [4.0, 4.0]]).unwrap();
        let options = CompileOptions::new().with_limits(2_000.0, 200_000.0);
        let path: Path<f32, 2, 16> =
            compile(&Along::new(&curve, &Smooth), 1_000.0, &options).unwrap();
        let events = [
            at(30, Event::Feed(0.5)),
            at(80, Event::Hold),
            at(300, Event::Resume),
        ];
        let mut player = EventPlayer::new(&events, path.ticks());
        let mut by_player = Sampler::new(&path);
        let mut by_hand = Sampler::new(&path);
        let mut k = 0_u64;
        while let Some(s) = player.step(&mut by_player) {
            match k {
                30 => by_hand.set_feed(0.5),
                80 => by_hand.hold(),
                300 => by_hand.resume(),
                _ => {}
            }
            assert_eq!(s, by_hand.next(), "tick {k}");
            let holding = by_player.state() == crate::SamplerState::Holding;
            if !by_player.is_finished() {
                let held = (80..300).contains(&k);
                assert_eq!(
                    holding, held,
                    "tick {k}: hold before sample 80, resume before 300"
                );
            }
            k += 1;
        }
        assert!(by_hand.is_finished());
        assert_eq!(player.end(&by_player), RunEnd::Finished);
        // Held from tick 80 to 300 (at rest after the ramp down): the run outlasts the path
        // by more than 150 ticks.
        let ticks = u64::from(path.ticks());
        assert!(k > ticks + 150, "{k} samples, {ticks} ticks");
    }
}
