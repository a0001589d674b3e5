//! `strak_sim::export` (what firmware is compared against) plays exactly what `strak-sim run`
//! plays: for a job whose own number format is the playback format, every sample's bits equal
//! the values of `samples.csv`.

mod common;

use std::fs;

use common::bundled_job;
use strak_curves::I32F32;
use strak_sim::export::export;
use strak_sim::job::Job;
use strak_sim::number::NumberFormat;
use strak_sim::run::{RunOptions, run_job};
use strak_trajectory::{Event, Path, Q40, Sampler};

/// The bits of every value of `samples.csv` (tick and time dropped).
fn csv_bits(job: &Job, parse: fn(&str) -> u64) -> Vec<u64> {
    let dir = tempfile::tempdir().unwrap();
    let options = RunOptions {
        out_dir: dir.path().to_owned(),
        name: "export".to_owned(),
        progress: false,
        velocity_factor: None,
    };
    let summary = run_job(job, &options).unwrap();
    assert!(summary.finished);
    let text = fs::read_to_string(dir.path().join("samples.csv")).unwrap();
    text.lines()
        .skip(1)
        .flat_map(|line| line.split(',').skip(2).map(parse).collect::<Vec<_>>())
        .collect()
}

#[test]
fn f32_export_equals_the_run_of_an_f32_job() {
    let job = bundled_job("circle-f32");
    let e = export(&job, NumberFormat::F32).unwrap();
    assert!(e.finished);
    assert_eq!(e.axes, 2);
    assert_eq!(e.samples(), e.ticks as usize + 1);
    let run = csv_bits(&job, |s| u64::from(s.parse::<f32>().unwrap().to_bits()));
    assert_eq!(run.len(), e.bits.len());
    assert!(run == e.bits, "the f32 export differs from `strak-sim run`");
}

#[test]
fn fixed_export_equals_the_run_of_a_fixed_job() {
    let job = bundled_job("contour-fixed");
    let e = export(&job, NumberFormat::Q40).unwrap();
    assert!(e.finished);
    let run = csv_bits(&job, |s| {
        s.parse::<I32F32>().unwrap().to_bits().cast_unsigned()
    });
    assert_eq!(run.len(), e.bits.len());
    assert!(
        run == e.bits,
        "the fixed export differs from `strak-sim run`"
    );
}

#[test]
fn events_are_applied_and_the_blob_plays_back() {
    let job = bundled_job("feed-hold");
    let e = export(&job, NumberFormat::Q40).unwrap();
    // the job's four events, each after the ramp slow-down the feed guard chose for it
    let job_events = e
        .events
        .iter()
        .filter(|e| !matches!(e.event, Event::RampScale(_)));
    assert_eq!(job_events.count(), 4);
    assert_eq!(e.events.len(), 8);
    // the hold stretches the run beyond the path's ticks
    assert!(e.samples() > e.ticks as usize + 1);
    let path: Path<Q40, 3, 64> = Path::from_bytes(&e.blob).unwrap();
    assert_eq!(path.pieces().len(), e.pieces);
    // without the events the blob plays the path's ticks + 1 samples; the first equals the export's
    let mut s = Sampler::new(&path);
    let first = s.next();
    assert_eq!(
        first.position.map(|p| p.to_bits().cast_unsigned()),
        e.sample(0).unwrap()[..3]
    );
    // a recipe for on-device compiling exists for the plain B-spline, not for the circle
    assert!(e.recipe.is_some());
    assert!(
        export(&bundled_job("circle-f32"), NumberFormat::F32)
            .unwrap()
            .recipe
            .is_none()
    );
}
