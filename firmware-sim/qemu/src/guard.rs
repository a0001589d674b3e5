//! The feed guard's cost on the device: [`FeedGuard::schedule`] of a hold at every
//! [`EVERY`]-th tick of the bundled pick-and-place path in `f32` (planned at the full
//! limits, without a feed reserve), each from the sampler's state at that tick, counted by
//! the instruction counter. The guard checks the job's own limits.

use core::hint::black_box;

use strak_trajectory::{Event, FeedGuard, Limits, NumberFormat, PathBlob, Sample, Sampler};

use crate::counter::{Calibration, WideCounter};
use crate::jobs::{BLOB_JOBS, DEVICE_JOBS};

/// Ticks between two counted holds.
pub const EVERY: u32 = 25;

/// The job whose path is measured.
const JOB: &str = "pick-and-place";

/// Counts the scheduling of a hold at every [`EVERY`]-th tick into `counts`; the number
/// counted and the sum of their delays in ticks.
///
/// # Errors
/// What is missing or invalid: the job's blob or recipe, its limits, or a hold the guard
/// refuses.
pub fn count_holds(
    counter: &WideCounter,
    cal: &Calibration,
    counts: &mut [u32],
) -> Result<(usize, u64), &'static str> {
    let job = BLOB_JOBS
        .iter()
        .find(|j| j.name == JOB && j.format == NumberFormat::F32)
        .ok_or("no f32 blob of the job")?;
    let recipe = DEVICE_JOBS
        .iter()
        .find(|j| j.name == JOB)
        .ok_or("no recipe of the job")?;
    let mut blob = PathBlob::<f32, 3>::new();
    blob.read_bytes(job.blob)
        .map_err(|_| "the blob does not read")?;
    let [v, a, j] = recipe.machine_limits;
    let limits = Limits::<3>::new(v, a, j)
        .and_then(|l| l.with_axis_velocity(recipe.machine_axis_velocity))
        .and_then(|l| l.with_axis_acceleration(recipe.axis_acceleration))
        .map_err(|_| "bad limits")?;
    let guard = FeedGuard::new(&limits);
    let mut sampler = Sampler::new(blob.view());
    let mut last: Option<Sample<f32, 3>> = None;
    let (mut n, mut delays) = (0, 0_u64);
    for slot in counts.iter_mut() {
        if sampler.is_finished() {
            break;
        }
        let (c, when) = counter
            .counts(|| black_box(&guard).schedule(black_box(&sampler), last.as_ref(), Event::Hold));
        let when = when.ok_or("a hold refused")?;
        *slot = u32::try_from(cal.instructions_wide(c)).unwrap_or(u32::MAX);
        delays += u64::from(when.delay);
        n += 1;
        for _ in 0..EVERY {
            last = Some(sampler.next());
        }
    }
    Ok((n, delays))
}
