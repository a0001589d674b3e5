//! A job whose path is a straight segment and whose profile is an S-curve, run as the
//! time-optimal online move along it.
//!
//! Along a line `x = p₀ + s·u` (`u` the unit direction) every axis moves by `uᵢ·s`, so the
//! job's limits are limits on `s` alone: `ṡ ≤ min(V, Vᵢ/|uᵢ|)`, `|s̈| ≤ min(A, Aᵢ/|uᵢ|)`,
//! `|s⃛| ≤ J` (the path limits bound the norms, the axis limits each axis). The fastest
//! jerk-limited motion of `s` from rest to rest under them is the one-dimensional
//! time-optimal profile (Kröger, *On-Line Trajectory Generation in Robotic Systems*,
//! Springer 2010, ch. 4): here it is the [`OnlineMove`](strak_trajectory::OnlineMove) of
//! the axes, each with its share of those limits (`|uᵢ|` times them, and its own limit),
//! synchronized in phase, so that the axes stay on the line. Nothing is held back: the
//! motion uses the full limits.
//!
//! The feed events re-time the rest of the motion from the sample before them with the
//! same solver ([`play_moves`](crate::online_move::play_moves)): a feed override solves the
//! move again with the velocity limits times the feed (braking first within the
//! acceleration and jerk limits when the motion is faster), a hold is a quick stop on the
//! line, resume solves the move to the end again, an abort stops for good. Each takes
//! effect at the tick it is given, within every limit.

use crate::curve_file::CurveFile;
use crate::job::{Job, JobError, Profile};
use crate::number::NumberFormat;
use crate::online_move::{MoveEvent, MoveJob, MoveTarget, check_feed};
use strak_trajectory::Synchronization;

/// The two end points of a path that is a straight segment traversed once: a Bézier curve,
/// a B-spline (open) or a Lagrange interpolant of two distinct points.
fn segment(path: &CurveFile) -> Option<(&[f64], &[f64])> {
    let points = match path {
        CurveFile::Bezier(b) => &b.points,
        CurveFile::Bspline(b) if !b.closed => &b.points,
        CurveFile::Lagrange(l) => &l.points,
        _ => return None,
    };
    match points.as_slice() {
        [a, b] if a != b => Some((a, b)),
        _ => None,
    }
}

/// The move along the job's path when it is a straight segment (a `bezier`, open `bspline`
/// or `lagrange` path of two distinct points) with an
/// S-curve profile (`None` otherwise: the job is planned along its curve).
///
/// # Errors
/// A [`JobError`] on `events[i].feed` for a feed override between 0 and
/// [`MIN_FEED`](crate::online_move::MIN_FEED).
pub fn line_move(job: &Job) -> Option<Result<MoveJob, JobError>> {
    let (from, to) = segment(&job.path)?;
    if !matches!(job.profile, Profile::SCurve(_)) {
        return None;
    }
    // The end points as the solver holds them (`f32` for `f32` playback): the direction,
    // and so each axis's share of the limits, of the line it moves along.
    let solver = |x: &f64| match job.number {
        #[allow(clippy::cast_possible_truncation)]
        NumberFormat::F32 => f64::from(*x as f32),
        _ => *x,
    };
    let (from, to): (Vec<f64>, Vec<f64>) = (
        from.iter().map(solver).collect(),
        to.iter().map(solver).collect(),
    );
    let delta: Vec<f64> = from.iter().zip(&to).map(|(a, b)| b - a).collect();
    let length = delta.iter().map(|d| d * d).sum::<f64>().sqrt();
    let l = &job.limits;
    let axis = |v: &Option<Vec<f64>>, i: usize| v.as_ref().map_or(f64::INFINITY, |v| v[i]);
    let limits = delta
        .iter()
        .enumerate()
        .map(|(i, d)| {
            let share = d.abs() / length;
            // An axis that does not move keeps the path's limits (any positive value).
            let of = |path: f64, own: f64| match path * share {
                x if x > 0.0 => x.min(own),
                _ => path,
            };
            [
                of(l.velocity, axis(&l.axis_velocity, i)),
                of(l.acceleration, axis(&l.axis_acceleration, i)),
                of(l.jerk, f64::INFINITY),
            ]
        })
        .collect();
    Some(events(job).map(|events| MoveJob {
        rate_hz: job.rate_hz,
        number: job.number,
        sync: Synchronization::Phase,
        unit: job.unit().to_owned(),
        limits,
        start: from.iter().map(|&p| [p, 0.0, 0.0]).collect(),
        target: MoveTarget {
            states: to.iter().map(|&p| [p, 0.0, 0.0]).collect(),
            position: true,
        },
        events,
    }))
}

/// The job's events by tick (stable), as the operator events of a move.
fn events(job: &Job) -> Result<Vec<(u64, MoveEvent)>, JobError> {
    let mut events = Vec::with_capacity(job.events.len());
    for (i, e) in job.events.iter().enumerate() {
        let Some(action) = e.action() else {
            continue;
        };
        if let crate::job::Action::Feed(f) = action {
            check_feed(&format!("events[{i}].feed"), f)?;
        }
        events.push((e.tick, MoveEvent::Operator(action)));
    }
    events.sort_by_key(|(tick, _)| *tick);
    Ok(events)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn job(path: &str, events: &str) -> Job {
        Job::parse(&format!(
            "rate_hz = 1000\nnumber = \"f64\"\n[path]\n{path}\n[limits]\nvelocity = 500\n\
             acceleration = 5000\njerk = 100000\naxis_velocity = [500, 100, 400]\n\
             [profile]\nkind = \"s-curve\"\n{events}"
        ))
        .unwrap()
    }

    #[test]
    fn a_segment_becomes_a_phase_synchronized_move_with_its_share_of_the_limits() {
        let j = job("kind = \"bezier\"\npoints = [[0, 0, 0], [300, 400, 0]]", "");
        let m = line_move(&j).unwrap().unwrap();
        assert_eq!(m.sync, Synchronization::Phase);
        // u = (0.6, 0.8, 0): x 300 of 500, y min(400, 100), z keeps the path's limits
        assert_eq!(m.limits[0], [300.0, 3_000.0, 60_000.0]);
        assert_eq!(m.limits[1], [100.0, 4_000.0, 80_000.0]);
        assert_eq!(m.limits[2], [500.0, 5_000.0, 100_000.0]);
        assert_eq!(m.start[1], [0.0, 0.0, 0.0]);
        assert_eq!(m.target.states[1], [400.0, 0.0, 0.0]);
    }

    #[test]
    fn curves_and_other_profiles_are_planned_along_the_curve() {
        let bent = "kind = \"bezier\"\npoints = [[0, 0, 0], [1, 1, 0], [2, 0, 0]]";
        assert!(line_move(&job(bent, "")).is_none());
        let point = "kind = \"bezier\"\npoints = [[1, 1, 1], [1, 1, 1]]";
        assert!(line_move(&job(point, "")).is_none());
        let mut trapezoid = job("kind = \"bezier\"\npoints = [[0, 0, 0], [1, 0, 0]]", "");
        trapezoid.profile = Profile::Trapezoid(Default::default());
        assert!(line_move(&trapezoid).is_none());
    }

    #[test]
    fn feed_events_keep_their_order_and_tiny_feeds_are_refused() {
        let line = "kind = \"lagrange\"\npoints = [[0, 0, 0], [10, 0, 0]]";
        let j = job(
            line,
            "[[events]]\ntick = 9\nhold = true\n[[events]]\ntick = 3\nfeed = 0.5\n",
        );
        let m = line_move(&j).unwrap().unwrap();
        let ticks: Vec<u64> = m.events.iter().map(|(t, _)| *t).collect();
        assert_eq!(ticks, [3, 9]);
        let e = line_move(&job(line, "[[events]]\ntick = 3\nfeed = 0.001\n"))
            .unwrap()
            .unwrap_err();
        assert_eq!(e.field, "events[0].feed");
    }
}
