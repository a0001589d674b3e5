//! The job's feed events as they are played: on a path planned at the full limits (no feed
//! share), each event is scheduled by the library's [`FeedGuard`], which finds the first
//! tick from the event's own on, and the least slow-down of the feed ramp, at which the
//! change keeps the job's limits to the end of its ramp; the event plays there, after an
//! [`Event::RampScale`] that sets that slow-down. `strak-sim run`, `strak-sim compile` and
//! the firmware under QEMU all play the scheduled list, so they agree sample for sample.
//!
//! On a path with a feed share, and for the laws not planned under the limits (parameter,
//! constant speed), the events play at their own ticks.

use strak_trajectory::{Event, FeedGuard, Kernel, Path, Playable, Sample, Sampler, TimedEvent};

use crate::job::{Job, JobError, ProfileKind};
use crate::pipeline::{is_planned, job_limits};
use crate::summary::Applied;

/// The events as played, and how late each of the job's events took effect.
#[derive(Clone, Debug, PartialEq)]
pub struct Scheduled {
    /// What the event player plays: the job's events at their scheduled ticks, each after
    /// the [`Event::RampScale`] it needs.
    pub events: Vec<TimedEvent>,
    /// Per job event (sorted by tick): when it took effect.
    pub applied: Vec<Applied>,
}

impl Scheduled {
    /// The most ticks an event waited (0 without events).
    pub fn latest(&self) -> u64 {
        self.applied
            .iter()
            .filter_map(|a| a.at.map(|at| at - a.tick))
            .max()
            .unwrap_or(0)
    }

    /// The events the guard refused.
    pub fn refused(&self) -> usize {
        self.applied.iter().filter(|a| a.at.is_none()).count()
    }
}

/// The job's events scheduled on `path` (see the module docs).
///
/// # Errors
/// A [`JobError`] on `limits` for a limit the trajectory layer rejects.
pub fn schedule<N: Kernel, const D: usize, const P: usize>(
    job: &Job,
    path: &Path<N, D, P>,
) -> Result<Scheduled, JobError> {
    let events = job.timed_events();
    let at_once = |e: &TimedEvent, ramp_shift| Applied {
        tick: e.tick,
        at: Some(e.tick),
        ramp_shift,
    };
    if path.feed_share() > 0.0 || !is_planned(job) {
        let applied = events.iter().map(|e| at_once(e, 0)).collect();
        return Ok(Scheduled { events, applied });
    }
    let guard = guard::<D>(job)?;
    let mut sampler = Sampler::new(path);
    let mut last: Option<Sample<N::Out, D>> = None;
    let (mut tick, mut played) = (0_u64, Vec::with_capacity(2 * events.len()));
    let (mut applied, mut ramp_shift) = (Vec::with_capacity(events.len()), 0);
    for e in events {
        while tick < e.tick && !sampler.is_finished() {
            last = Some(sampler.next());
            tick += 1;
        }
        if sampler.is_finished() {
            // After the end: the player ignores it where the job has it.
            played.push(e);
            applied.push(at_once(&e, ramp_shift));
            continue;
        }
        let Some(when) = guard.schedule(&sampler, last.as_ref(), e.event) else {
            applied.push(Applied {
                at: None,
                ..at_once(&e, ramp_shift)
            });
            continue;
        };
        for _ in 0..when.delay {
            last = Some(sampler.next());
            tick += 1;
        }
        if let Some(shift) = when.shift {
            ramp_shift = shift;
            let scale = Event::RampScale(shift);
            sampler.apply(scale);
            played.push(TimedEvent { tick, event: scale });
        }
        sampler.apply(e.event);
        played.push(TimedEvent {
            tick,
            event: e.event,
        });
        applied.push(Applied {
            at: Some(tick),
            ..at_once(&e, ramp_shift)
        });
    }
    Ok(Scheduled {
        events: played,
        applied,
    })
}

/// The guard of the job's limits (path and per axis; without the jerk for a trapezoid).
fn guard<const D: usize>(job: &Job) -> Result<FeedGuard<D>, JobError> {
    let limits = job_limits::<D>(job, 1.0)?;
    let guard = FeedGuard::new(&limits);
    Ok(if job.profile.kind() == ProfileKind::SCurve {
        guard
    } else {
        guard.without_jerk()
    })
}
