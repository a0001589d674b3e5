//! strak-sim's largest job shape runs on a thread with libtest's default stack (2 MiB): a
//! 6-axis clamped cubic B-spline of 4 096 points (the builder's largest size class), planned
//! with the pipeline's plan of [`LARGE_TABLE`] samples and [`ZONES`] zones and compiled into a path
//! of [`PIECES`] pieces, in `f64` and in fixed point (Q40 playback), through `run_job` (what
//! `strak-sim run` calls) and `export` (what `strak-sim compile` calls). The plan and the path
//! are boxed and filled in place (a 6-axis `f64` path of that capacity holds about 7 MB); a
//! frame that held either would overflow the stack and abort this test binary. And the
//! `strak-sim` binary runs the bundled jobs with its main thread's stack limited to as much.

mod common;

use std::process::Command;

use strak_sim::export::export;
use strak_sim::job::Job;
use strak_sim::number::NumberFormat;
use strak_sim::pipeline::{LARGE_TABLE, PIECES, ZONES};
use strak_sim::run::{RunOptions, exit_code, run_job};

/// libtest's default: the stack of every test thread.
const STACK_BYTES: usize = 2 << 20;

/// Points of the job: the largest a curve file takes.
const POINTS: usize = 4_096;

/// Runs `f` on a thread with a [`STACK_BYTES`] stack.
fn on_default_stack<R: Send>(f: impl FnOnce() -> R + Send) -> R {
    std::thread::scope(|scope| {
        std::thread::Builder::new()
            .stack_size(STACK_BYTES)
            .spawn_scoped(scope, f)
            .expect("spawn the test thread")
            .join()
            .expect("the job ran without a panic")
    })
}

/// Point `i` of [`POINTS`]: three turns of a helix of radius 200 rising 100 in x, y, z, and
/// three slower axes.
fn point(i: usize) -> [f64; 6] {
    let s = i as f64 / (POINTS - 1) as f64;
    let t = std::f64::consts::TAU * s;
    [
        200.0 * (3.0 * t).cos(),
        200.0 * (3.0 * t).sin(),
        100.0 * s,
        50.0 * (2.0 * t).sin(),
        30.0 * t.cos(),
        20.0 * s,
    ]
}

/// The job: [`POINTS`] de Boor points of degree 3 on clamped knots `0, 1, …, 4 093` (one unit
/// per piece, so that the derivatives of the spline stay small enough for fixed point), at
/// 1 kHz with an S-curve, in `number`.
fn largest_job(number: &str) -> Job {
    let degree = 3;
    let last = POINTS - degree;
    let knots: Vec<String> = std::iter::repeat_n(0, degree)
        .chain(0..=last)
        .chain(std::iter::repeat_n(last, degree))
        .map(|k| k.to_string())
        .collect();
    let points: Vec<String> = (0..POINTS)
        .map(|i| {
            let p = point(i).map(|x| format!("{x:.6}"));
            format!("[{}]", p.join(", "))
        })
        .collect();
    let text = format!(
        "rate_hz = 1000\nnumber = \"{number}\"\n\n[path]\nkind = \"bspline\"\ndegree = {degree}\n\
         knots = [{}]\npoints = [{}]\n\n[limits]\nvelocity = 500\nacceleration = 5000\n\
         jerk = 100000\n\n[profile]\nkind = \"s-curve\"\n",
        knots.join(", "),
        points.join(", ")
    );
    let job = Job::parse(&text).expect("the job parses");
    assert_eq!((job.axes(), job.path.points().len()), (6, POINTS));
    job
}

/// The shape this file covers is the pipeline's largest.
#[test]
fn the_capacities_are_the_pipelines() {
    assert_eq!((PIECES, LARGE_TABLE, ZONES), (16_384, 8_192, 1_024));
}

fn run_on_default_stack(number: &str) {
    let job = largest_job(number);
    let dir = tempfile::tempdir().unwrap();
    let options = RunOptions {
        out_dir: dir.path().to_owned(),
        name: format!("largest-{number}"),
        progress: false,
        velocity_factor: None,
    };
    let summary = on_default_stack(|| run_job(&job, &options)).expect("the run succeeds");
    assert_eq!(summary.axes, 6);
    assert!(summary.finished, "{}", summary.stop);
    assert!(summary.ticks > 1_000, "{}", summary.ticks);
    assert!(summary.pieces > 1 && summary.pieces <= PIECES);
    assert_eq!(exit_code(&summary), 0, "{:?}", summary.violations);
    assert!(dir.path().join("samples.csv").metadata().unwrap().len() > 1_000_000);
}

#[test]
fn run_f64_on_the_default_stack() {
    run_on_default_stack("f64");
}

#[test]
fn run_fixed_on_the_default_stack() {
    run_on_default_stack("fixed");
}

fn export_on_default_stack(number: &str, playback: NumberFormat) {
    let job = largest_job(number);
    let e = on_default_stack(|| export(&job, playback)).expect("the export succeeds");
    assert_eq!((e.playback, e.axes), (playback, 6));
    assert!(e.finished);
    assert!(e.ticks > 1_000 && e.pieces > 1 && e.pieces <= PIECES);
    assert_eq!(e.samples(), e.ticks as usize + 1);
    assert_eq!(e.bits.len(), e.samples() * 3 * 6);
}

#[test]
fn export_f64_on_the_default_stack() {
    export_on_default_stack("f64", NumberFormat::F64);
}

#[test]
fn export_q40_on_the_default_stack() {
    export_on_default_stack("fixed", NumberFormat::Q40);
}

/// `strak-sim run` on every bundled job with the stack limit (`ulimit -s`, which bounds the
/// main thread's stack) set to [`STACK_BYTES`].
#[cfg(unix)]
#[test]
fn the_binary_runs_the_bundled_jobs_within_the_default_stack() {
    let dir = tempfile::tempdir().unwrap();
    for job in common::bundled_jobs() {
        let out = dir.path().join(common::stem(&job));
        let output = Command::new("sh")
            .arg("-c")
            .arg(format!(
                "ulimit -s {} && exec \"$0\" run \"$1\" --out \"$2\"",
                STACK_BYTES >> 10
            ))
            .arg(env!("CARGO_BIN_EXE_strak-sim"))
            .arg(&job)
            .arg(&out)
            .output()
            .unwrap();
        assert!(
            output.status.success(),
            "{}: {:?}\n{}",
            job.display(),
            output.status,
            String::from_utf8_lossy(&output.stderr)
        );
        assert!(out.join("summary.json").exists(), "{}", job.display());
    }
}
