//! strak-sim's job and curve files: TOML text through [`Job::parse`] and
//! [`CurveFile::parse`], then what `strak-sim run` does with a valid job, in small
//! capacities.
//!
//! Invariants:
//!
//! * parsing and checking never panic; an error names a field and says what is wrong;
//! * a valid curve file builds in every number format or is rejected with an error, and
//!   its samples (`strak-sim sample`) are finite;
//! * a valid job's curve builds in the job's number format or is rejected; its time law is
//!   planned with [`planning_limits`] and [`plan_options`] (at most [`MAX_PLAN_SAMPLES`]
//!   sampling intervals) and compiled with [`compile_options`] when it takes at most
//!   [`MAX_TICKS`] ticks; the compiled path is checked and played with the job's events
//!   as in [`pipeline`](crate::pipeline) ([`check_compiled`]), the job's limits holding for
//!   the planned laws (trapezoid, S-curve).

use strak_curves::{I32F32, Scalar};
use strak_sim::curve_file::CurveFile;
use strak_sim::dyn_curve::{DynCurve, build_dyn};
use strak_sim::job::{Job, JobEvent, Profile, ProfileKind};
use strak_sim::pipeline::{compile_options, plan_options, planning_limits};
use strak_sim::sample::{NumberFormat, SampleOptions, sample_rows};
use strak_sim::schedule::schedule;
use strak_trajectory::{
    Along, Event, Kernel, ParameterTiming, Path, PathTiming, Q40, Timing, compile,
};

use crate::check::{Bounds, FeedEvent, MAX_TICKS};
use crate::pipeline::check_compiled;
use crate::{Violation, violation};

/// Planner sampling intervals are capped at this many (strak-sim's default is 1024).
pub const MAX_PLAN_SAMPLES: usize = 256;
/// Arc-length table size and zone capacity of the plans, pieces of the paths.
const TABLE: usize = 128;
const ZONES: usize = 128;
const PIECES: usize = 256;

/// The harness: `data` as UTF-8 text (other bytes are no case).
///
/// # Errors
/// The first broken invariant.
pub fn run(data: &[u8]) -> Result<(), Violation> {
    let Ok(text) = std::str::from_utf8(data) else {
        return Ok(());
    };
    if let Ok(file) = CurveFile::parse(text) {
        curve_file(&file)?;
    }
    match Job::parse(text) {
        Ok(job) => valid_job(&job),
        Err(e) if e.field.trim().is_empty() || e.message.trim().is_empty() => {
            Err(violation!("a job error without a field or message: {e:?}"))
        }
        Err(_) => Ok(()),
    }
}

fn curve_file(file: &CurveFile) -> Result<(), Violation> {
    for number in [NumberFormat::F64, NumberFormat::F32, NumberFormat::Q40] {
        let options = SampleOptions {
            count: 9,
            derivatives: 2,
            number,
        };
        if let Ok(rows) = sample_rows(file, &options)
            && let Some(row) = rows.iter().find(|r| !r.iter().all(|v| v.is_finite()))
        {
            return Err(violation!(
                "{number:?} curve file sample not finite: {row:?}"
            ));
        }
    }
    Ok(())
}

fn valid_job(job: &Job) -> Result<(), Violation> {
    let mut job = job.clone();
    if let Profile::Trapezoid(p) | Profile::SCurve(p) = &mut job.profile {
        p.samples = Some(p.samples.unwrap_or(MAX_PLAN_SAMPLES).min(MAX_PLAN_SAMPLES));
    }
    match job.axes() {
        1 => by_number::<1>(&job),
        2 => by_number::<2>(&job),
        3 => by_number::<3>(&job),
        4 => by_number::<4>(&job),
        d => Err(violation!("a valid job with {d} axes")),
    }
}

fn by_number<const D: usize>(job: &Job) -> Result<(), Violation> {
    let n = job.number;
    match job.number {
        NumberFormat::F64 => {
            build_dyn::<f64, D>(&job.path, n).map_or(Ok(()), |c| plan::<f64, f64, D>(job, &c))
        }
        NumberFormat::F32 => {
            build_dyn::<f32, D>(&job.path, n).map_or(Ok(()), |c| plan::<f32, f32, D>(job, &c))
        }
        NumberFormat::Q40 => {
            build_dyn::<I32F32, D>(&job.path, n).map_or(Ok(()), |c| plan::<Q40, I32F32, D>(job, &c))
        }
    }
}

fn plan<N: Kernel, S: Scalar, const D: usize>(
    job: &Job,
    curve: &DynCurve<S, D>,
) -> Result<(), Violation> {
    let Ok(limits) = planning_limits::<D>(job) else {
        return Ok(());
    };
    let timing: Box<dyn Timing + '_> = match &job.profile {
        Profile::Parameter(p) => match ParameterTiming::over(curve, p.duration) {
            Ok(t) => Box::new(t),
            Err(_) => return Ok(()),
        },
        Profile::ConstantSpeed(p) => {
            match PathTiming::<_, TABLE, ZONES>::constant_speed(
                curve,
                p.speed.unwrap_or(job.limits.velocity),
            ) {
                Ok(t) => Box::new(t),
                Err(_) => return Ok(()),
            }
        }
        Profile::Trapezoid(_) | Profile::SCurve(_) => {
            match PathTiming::<_, TABLE, ZONES>::plan(curve, &limits, &plan_options(job)) {
                Ok(t) => Box::new(t),
                Err(_) => return Ok(()),
            }
        }
    };
    if !(timing.duration() * job.rate_hz <= MAX_TICKS) {
        return Ok(());
    }
    let Ok(path) = compile::<N, D, PIECES, _>(
        &Along::new(curve, &*timing),
        job.rate_hz,
        &compile_options(job),
    ) else {
        return Ok(());
    };
    play(job, curve, &*timing, &path)
}

/// The job's events as strak-sim plays them ([`schedule`]: on a path without a feed share
/// each where and as slowly as the feed guard allows), without an abort (it ends the motion
/// on the path, not at its end) and with a resume and feed 1 after the last event and the
/// path's end (scheduled too), so that the motion finishes.
///
/// # Errors
/// A violation when the guard refuses an event.
fn scheduled_events<N: Kernel, const D: usize>(
    job: &Job,
    path: &Path<N, D, PIECES>,
) -> Result<Vec<(u64, FeedEvent)>, Violation> {
    let mut job = job.clone();
    job.events.retain(|e| e.abort != Some(true));
    let last = job.events.iter().map(|e| e.tick).max().unwrap_or(0);
    if !job.events.is_empty() {
        let tick = last.max(u64::from(path.ticks())) + 1;
        let event = |feed, resume| JobEvent {
            tick,
            feed,
            hold: None,
            resume,
            abort: None,
        };
        job.events.push(event(None, Some(true)));
        job.events.push(event(Some(1.0), None));
    }
    let scheduled = schedule(&job, path).map_err(|e| violation!("scheduling: {e}"))?;
    if scheduled.refused() > 0 {
        return Err(violation!(
            "the feed guard refused {} event(s)",
            scheduled.refused()
        ));
    }
    Ok(scheduled
        .events
        .iter()
        .filter_map(|e| {
            let event = match e.event {
                Event::Feed(f) => FeedEvent::Feed(f),
                Event::Hold => FeedEvent::Hold,
                Event::Resume => FeedEvent::Resume,
                Event::RampScale(shift) => FeedEvent::RampScale(shift),
                Event::Abort => return None,
            };
            Some((e.tick, event))
        })
        .collect())
}

fn play<N: Kernel, S: Scalar, const D: usize>(
    job: &Job,
    curve: &DynCurve<S, D>,
    timing: &dyn Timing,
    path: &Path<N, D, PIECES>,
) -> Result<(), Violation> {
    let planned = matches!(
        job.profile.kind(),
        ProfileKind::Trapezoid | ProfileKind::SCurve
    );
    let l = &job.limits;
    let axis = |v: &Option<Vec<f64>>| -> [f64; D] {
        core::array::from_fn(|i| {
            v.as_ref()
                .and_then(|v| v.get(i).copied())
                .unwrap_or(f64::INFINITY)
        })
    };
    let bounds = Bounds {
        velocity: l.velocity,
        acceleration: l.acceleration,
        jerk: (job.profile.kind() == ProfileKind::SCurve).then_some(l.jerk),
        axis_velocity: axis(&l.axis_velocity),
        axis_acceleration: axis(&l.axis_acceleration),
        tangential: false,
    };
    let events = scheduled_events(job, path)?;
    check_compiled(
        curve,
        timing,
        path,
        &events,
        planned.then_some(&bounds),
        planned,
    )
    .map_err(|v| {
        violation!(
            "job ({} axes, {}, {}): {v}",
            D,
            job.number.name(),
            job.profile.kind().name()
        )
    })
}
