//! The event player: a path's operator events (feed override, hold, resume, abort), applied
//! before the sample of their tick, and the run guard that ends a run the sampler never
//! finishes (a hold without resume).
//!
//! One definition for `strak-sim run`, `strak-sim compile` (the samples firmware is compared
//! against) and the firmware: the events of tick `k` (ticks count samples from 0, holds
//! included) apply before sample `k`; the run ends after the sample on which the sampler is
//! finished, or after `10·(ticks + 1) + last event tick + 1` samples.
//!
//! The core uses neither `std` nor allocation: [`EventPlayer`] borrows the events and drives
//! any [`Playable`] sampler.

use strak_trajectory::{Kernel, Sampler};

/// An operator event.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Event {
    /// Feed override (the sampler takes it as `f32`).
    Feed(f32),
    /// Feed hold: decelerate to rest on the path.
    Hold,
    /// Resume after a hold.
    Resume,
    /// Abort: come to rest on the path and finish there.
    Abort,
}

/// An event at a tick: before the sample of `tick` (ticks count samples, holds included).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimedEvent {
    /// The tick before whose sample the event applies.
    pub tick: u64,
    /// What happens.
    pub event: Event,
}

/// What the event player needs of a sampler.
pub trait Playable {
    /// One control tick's sample.
    type Sample;
    /// The next sample (one control tick).
    fn next_sample(&mut self) -> Self::Sample;
    /// Whether the motion is over.
    fn is_finished(&self) -> bool;
    /// Applies `event`.
    fn apply(&mut self, event: Event);
}

impl<N: Kernel, const A: usize> Playable for Sampler<'_, N, A> {
    type Sample = strak_trajectory::Sample<N::Out, A>;

    fn next_sample(&mut self) -> Self::Sample {
        self.next()
    }

    fn is_finished(&self) -> bool {
        Sampler::is_finished(self)
    }

    fn apply(&mut self, event: Event) {
        match event {
            Event::Feed(f) => self.set_feed(f),
            Event::Hold => self.hold(),
            Event::Resume => self.resume(),
            Event::Abort => self.abort(),
        }
    }
}

/// Why a run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stop {
    /// The sampler finished (the end of the path, or at rest after an abort).
    Finished,
    /// The guard stopped a run the sampler did not finish (a hold without resume?).
    Guard,
}

/// Plays the events of a path of `ticks` ticks; see the module docs.
///
/// ```
/// use strak_sim::player::{Event, EventPlayer, Playable, Stop, TimedEvent};
///
/// /// A sampler that counts down and takes events as they come.
/// struct Countdown(u32, Vec<Event>);
/// impl Playable for Countdown {
///     type Sample = u32;
///     fn next_sample(&mut self) -> u32 { self.0 = self.0.saturating_sub(1); self.0 }
///     fn is_finished(&self) -> bool { self.0 == 0 }
///     fn apply(&mut self, e: Event) { self.1.push(e) }
/// }
/// let events = [TimedEvent { tick: 1, event: Event::Hold }];
/// let mut player = EventPlayer::new(&events, 3);
/// let mut sampler = Countdown(3, Vec::new());
/// while player.step(&mut sampler).is_some() {}
/// assert_eq!((player.samples(), player.stop(&sampler)), (3, Stop::Finished));
/// assert_eq!(sampler.1, [Event::Hold]);
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
    /// A player at tick 0 of a path of `ticks` ticks; `events` sorted by tick.
    pub fn new(events: &'e [TimedEvent], ticks: u32) -> Self {
        let last_event = events.last().map_or(0, |e| e.tick);
        EventPlayer {
            events,
            next: 0,
            samples: 0,
            guard: 10 * (u64::from(ticks) + 1) + last_event + 1,
            aborted: false,
        }
    }

    /// Applies the events due before the next sample (none twice).
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

    /// One tick: the events due, then one sample; `None` once the run is over.
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
    pub fn is_over<P: Playable>(&self, sampler: &P) -> bool {
        self.samples > 0 && (sampler.is_finished() || self.samples >= self.guard)
    }

    /// Why the run ended (or would end now).
    pub fn stop<P: Playable>(&self, sampler: &P) -> Stop {
        if sampler.is_finished() {
            Stop::Finished
        } else {
            Stop::Guard
        }
    }

    /// The samples played.
    pub fn samples(&self) -> u64 {
        self.samples
    }

    /// The most samples a run takes (the guard).
    pub fn guard(&self) -> u64 {
        self.guard
    }

    /// The events applied.
    pub fn applied(&self) -> usize {
        self.next
    }

    /// The events not applied (their tick came after the run had ended).
    pub fn ignored(&self) -> usize {
        self.events.len() - self.next
    }

    /// Whether an abort was applied.
    pub fn aborted(&self) -> bool {
        self.aborted
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Finishes after `left` samples unless held; records the events with their sample.
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

    #[test]
    fn events_apply_before_the_sample_of_their_tick() {
        let events = [
            TimedEvent {
                tick: 0,
                event: Event::Feed(0.5),
            },
            TimedEvent {
                tick: 2,
                event: Event::Hold,
            },
            TimedEvent {
                tick: 4,
                event: Event::Resume,
            },
            TimedEvent {
                tick: 99,
                event: Event::Abort,
            },
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
        assert_eq!(samples, [0, 1, 2, 3, 4, 5, 6, 7]);
        assert_eq!((p.applied(), p.ignored(), p.aborted()), (3, 1, false));
        assert_eq!(p.stop(&s), Stop::Finished);
        // apply_due twice applies nothing twice
        p.apply_due(&mut s);
        assert_eq!(s.seen.len(), 3);
    }

    #[test]
    fn the_guard_ends_a_hold_without_resume() {
        let events = [TimedEvent {
            tick: 3,
            event: Event::Hold,
        }];
        let mut p = EventPlayer::new(&events, 5);
        assert_eq!(p.guard(), 10 * 6 + 3 + 1);
        let mut s = fake(6);
        while p.step(&mut s).is_some() {}
        assert_eq!(p.samples(), p.guard());
        assert_eq!(p.stop(&s), Stop::Guard);
    }

    #[test]
    fn a_finished_path_still_plays_one_sample() {
        let mut p = EventPlayer::new(&[], 0);
        let mut s = fake(0);
        assert_eq!(p.step(&mut s), Some(0));
        assert_eq!(p.step(&mut s), None);
        let abort = [TimedEvent {
            tick: 0,
            event: Event::Abort,
        }];
        let mut p = EventPlayer::new(&abort, 3);
        let mut s = fake(1);
        while p.step(&mut s).is_some() {}
        assert!(p.aborted());
    }
}
