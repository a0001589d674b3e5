//! The exit code of `strak-sim run`: 3, with one error line naming each quantity, when a time
//! law planned under the limits (trapezoid, S-curve) exceeds a limit it plans for or the
//! accuracy bound in its samples; 0 when everything holds, and 0 for the laws not planned
//! under the limits (parameter, constant speed), whose summary reports the excess.

mod common;

use std::path::Path as FsPath;
use std::process::Output;

use common::{QUARTER_TURN as GOOD, bundled_jobs, run_text, stem};
use strak_sim::job::Job;
use strak_sim::run::{RunOptions, exit_code, run_job, violation_lines};
use strak_sim::summary::Summary;

/// A straight line (73.65 units) at 1 kHz in f64 with an S-curve whose jerk phases last a few
/// ticks, planned at its velocity limit of 21.23.
const SHORT_JERK_PHASES: &str = r#"rate_hz = 1000
number = "f64"

[path]
kind = "bspline"
degree = 1
points = [[0, 0, 0], [60, 40, 15]]

[limits]
velocity = 21.23
acceleration = 823
jerk = 193600

[profile]
kind = "s-curve"
"#;

struct Run {
    output: Output,
    stdout: String,
    stderr: String,
    summary: serde_json::Value,
}

/// `strak-sim run` on `text` (see [`common::run_text`]), with its `summary.json` (`null`
/// when it wrote none).
fn run(name: &str, text: &str, dir: &FsPath) -> Run {
    let common::Run {
        output,
        stdout,
        stderr,
        out,
    } = run_text(name, text, dir);
    let summary = std::fs::read_to_string(out.join("summary.json"))
        .map(|t| serde_json::from_str(&t).unwrap())
        .unwrap_or(serde_json::Value::Null);
    Run {
        output,
        stdout,
        stderr,
        summary,
    }
}

/// The exit code agrees with `summary.json`: 3 and one line per violation when it lists
/// violations, 0 otherwise.
fn agrees(r: &Run) {
    let violations: Vec<&str> = r.summary["violations"]
        .as_array()
        .expect("summary.json has violations")
        .iter()
        .map(|v| v.as_str().unwrap())
        .collect();
    if violations.is_empty() {
        assert_eq!(r.output.status.code(), Some(0), "{}", r.stderr);
        assert!(!r.stderr.contains("limit exceeded"), "{}", r.stderr);
    } else {
        assert_eq!(r.output.status.code(), Some(3), "{}", r.stderr);
        let lines: Vec<&str> = r.stderr.lines().collect();
        assert_eq!(lines.len(), violations.len(), "{}", r.stderr);
        for (line, v) in lines.iter().zip(&violations) {
            assert!(
                line.starts_with("strak-sim: error: ") && line.ends_with(v),
                "{line}"
            );
        }
    }
}

#[test]
fn a_planned_job_that_holds_exits_0() {
    let dir = tempfile::tempdir().unwrap();
    let r = run("good", GOOD, dir.path());
    assert_eq!(r.output.status.code(), Some(0), "{}", r.stderr);
    assert!(
        r.stdout.contains("limits     all respected"),
        "{}",
        r.stdout
    );
    assert_eq!(r.summary["check"]["enforced"], true);
    assert_eq!(r.summary["accuracy"]["distance"]["within"], true);
    agrees(&r);
}

/// The run of `text` through the library (`run_job`, as `strak-sim run` calls it) with its
/// sampled velocities multiplied by `factor` before they are measured.
fn run_scaled(name: &str, text: &str, dir: &FsPath, factor: Option<f64>) -> Summary {
    let options = RunOptions {
        out_dir: dir.join(name),
        name: name.to_owned(),
        progress: false,
        velocity_factor: factor,
    };
    run_job(&Job::parse(text).unwrap(), &options).unwrap()
}

/// No planned job is known to break a limit (the library keeps them), so the samples of the
/// straight line are made to: its sampled velocities, 3 % too fast, go through the run's
/// measuring, checks and violations to the exit code and the error lines of `strak-sim
/// run` (`exit_code`, `violation_lines`, the functions the binary calls).
#[test]
fn a_planned_overshoot_exits_3_naming_the_quantity() {
    let dir = tempfile::tempdir().unwrap();
    let held = run_scaled("line", SHORT_JERK_PHASES, dir.path(), None);
    assert_eq!(exit_code(&held), 0, "{:?}", held.violations);
    let v_max = held.path.velocity.max;
    assert!(v_max <= 21.23 && v_max > 0.99 * 21.23, "{v_max}");

    let s = run_scaled("line", SHORT_JERK_PHASES, dir.path(), Some(1.03));
    assert_eq!(exit_code(&s), 3);
    let lines = violation_lines("line.toml", &s);
    // Only the sampled velocity is scaled: it exceeds its limit, and so do its finite
    // differences, 1.03 times an acceleration planned at its limit (the finite differences
    // of the positions and the accelerations are the run's own).
    assert_eq!(lines.len(), 2, "{lines:?}");
    assert!(
        lines[1].starts_with("strak-sim: error: line.toml: limit exceeded: acceleration |Δv|·f = "),
        "{}",
        lines[1]
    );
    let measured: f64 = lines[0]
        .strip_prefix("strak-sim: error: line.toml: limit exceeded: velocity |v| = ")
        .and_then(|rest| rest.split_once(" at t = "))
        .and_then(|(v, _)| v.parse().ok())
        .unwrap_or_else(|| panic!("{}", lines[0]));
    assert!(
        (measured / (1.03 * v_max) - 1.0).abs() < 1e-5,
        "{}",
        lines[0]
    );
    assert!(lines[0].contains("exceeds 21.23 by "), "{}", lines[0]);
    assert_eq!(s.path.velocity.within, Some(false));
    assert!(s.path.velocity.enforced);
    assert!(!s.limits_respected);
    assert!(s.to_string().contains("EXCEEDED"), "{s}");
    // The output is written all the same, for a look at what went wrong.
    assert!(dir.path().join("line/samples.csv").exists());

    // A law not planned under the limits reports the same excess without failing.
    let unplanned = SHORT_JERK_PHASES.replace(
        "kind = \"s-curve\"",
        "kind = \"constant-speed\"\nspeed = 21",
    );
    let u = run_scaled("speed", &unplanned, dir.path(), Some(1.03));
    assert_eq!(u.path.velocity.within, Some(false));
    assert_eq!((exit_code(&u), violation_lines("x", &u).len()), (0, 0));
}

#[test]
fn an_unplanned_law_reports_without_failing() {
    let dir = tempfile::tempdir().unwrap();
    for (name, profile) in [
        ("speed", "kind = \"constant-speed\"\nspeed = 250"),
        ("parameter", "kind = \"parameter\"\nduration = 0.05"),
    ] {
        let r = run(
            name,
            &GOOD.replace("kind = \"s-curve\"", profile),
            dir.path(),
        );
        assert_eq!(r.output.status.code(), Some(0), "{name}: {}", r.stderr);
        assert_eq!(r.summary["check"]["enforced"], false, "{name}");
        assert_eq!(r.summary["path"]["velocity"]["within"], false, "{name}");
        assert!(
            r.stdout.contains("exceeded (not enforced)"),
            "{name}: {}",
            r.stdout
        );
        agrees(&r);
    }
}

#[test]
fn a_trapezoid_is_not_failed_for_its_jerk() {
    let dir = tempfile::tempdir().unwrap();
    let r = run(
        "trapezoid",
        &GOOD.replace("kind = \"s-curve\"", "kind = \"trapezoid\""),
        dir.path(),
    );
    assert_eq!(r.output.status.code(), Some(0), "{}", r.stderr);
    let jerk = &r.summary["path"]["jerk"];
    assert_eq!(
        (&jerk["within"], &jerk["enforced"]),
        (&false.into(), &false.into())
    );
    assert_eq!(r.summary["path"]["acceleration"]["enforced"], true);
    assert_eq!(r.summary["path"]["acceleration"]["within"], true);
    agrees(&r);
}

/// Every bundled job, and each in the other number formats: the exit code agrees with the
/// summary (the bundled jobs as they are must pass).
#[test]
fn bundled_jobs_in_every_format() {
    let dir = tempfile::tempdir().unwrap();
    let mut failed = Vec::new();
    for file in bundled_jobs() {
        let name = stem(&file);
        let text = std::fs::read_to_string(&file).unwrap();
        let own = run(&name, &text, dir.path());
        assert_eq!(own.output.status.code(), Some(0), "{name}: {}", own.stderr);
        for number in ["f64", "f32", "fixed"] {
            let line = text.lines().find(|l| l.starts_with("number = ")).unwrap();
            let r = run(
                &format!("{name}-{number}"),
                &text.replace(line, &format!("number = \"{number}\"")),
                dir.path(),
            );
            agrees(&r);
            if r.output.status.code() != Some(0) {
                failed.push(format!("{name} in {number}: {}", r.stderr.trim_end()));
            }
        }
    }
    println!("bundled jobs that exceed in another format: {failed:#?}");
}

/// The largest norm over the axes of the columns `first ..` (one per axis) of `samples.csv`.
fn column_peak(csv: &str, first: usize, axes: usize) -> f64 {
    csv.lines()
        .skip(1)
        .map(|row| {
            let cells: Vec<f64> = row.split(',').map(|c| c.parse().unwrap()).collect();
            cells[first..first + axes]
                .iter()
                .map(|x| x * x)
                .sum::<f64>()
                .sqrt()
        })
        .fold(0.0, f64::max)
}

/// The bundled moves contour (lines, arcs, a Bézier, feeds; ε = 0.02 mm) runs: exit 0, every
/// corner blended within ε (the tangent join of its first line and arc) or stopped where
/// that is estimated faster, the samples (from `samples.csv`) within the limits, the end on
/// the last move's end.
#[test]
fn the_moves_contour_streams_within_its_limits() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(common::jobs_dir().join("moves-contour.toml")).unwrap();
    let r = run("moves-contour", &text, dir.path());
    assert_eq!(r.output.status.code(), Some(0), "{}", r.stderr);
    agrees(&r);
    let s = &r.summary["stream"];
    let (blends, stops) = (s["blends"].as_u64().unwrap(), s["stops"].as_u64().unwrap());
    assert_eq!((s["moves"].as_u64(), blends + stops), (Some(6), 5));
    assert!(blends >= 1, "{s}");
    assert_eq!(s["starved"].as_u64(), Some(0));
    assert_eq!(s["underruns"], 0);
    assert!(s["max_deviation"]["max"].as_f64().unwrap() <= 0.02);
    assert!(s["planning_per_move_s"].as_f64().is_some());
    assert_eq!(r.summary["limits_respected"], true);
    assert_eq!(r.summary["accuracy"]["distance"]["within"], true);
    assert_eq!(r.summary["end_point"]["error_to_path_end"], 0.0);
    for what in ["moves", "blends", "starved", "planning", "deviation"] {
        assert!(r.stdout.contains(what), "{what}: {}", r.stdout);
    }
    let csv = std::fs::read_to_string(dir.path().join("moves-contour/samples.csv")).unwrap();
    let (v, a) = (column_peak(&csv, 5, 3), column_peak(&csv, 8, 3));
    assert!(v <= 200.0 * (1.0 + 1e-9) && v > 100.0, "{v}");
    assert!(a <= 3000.0 * (1.0 + 1e-9) && a > 1000.0, "{a}");
    assert!(dir.path().join("moves-contour/path.svg").exists());
}

/// The moves contour with `faster_stops = false`: every corner blended (5), none stopped,
/// within the limits and ε.
#[test]
fn the_moves_contour_blends_every_corner_without_faster_stops() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(common::jobs_dir().join("moves-contour.toml")).unwrap();
    let job = text.replace(
        "tolerance = 0.02 ",
        "faster_stops = false\ntolerance = 0.02 ",
    );
    let r = run("blends", &job, dir.path());
    assert_eq!(r.output.status.code(), Some(0), "{}", r.stderr);
    agrees(&r);
    let s = &r.summary["stream"];
    assert_eq!(
        (s["blends"].as_u64(), s["stops"].as_u64()),
        (Some(5), Some(0)),
        "{s}"
    );
    assert_eq!(r.summary["limits_respected"], true);
}

/// Moves that arrive more slowly than the machine runs them: the stream rests at the end of
/// what it has ("starved"), and the limits hold.
#[test]
fn slowly_produced_moves_starve_the_stream() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(common::jobs_dir().join("moves-starved.toml")).unwrap();
    let r = run("moves-starved", &text, dir.path());
    assert_eq!(r.output.status.code(), Some(0), "{}", r.stderr);
    agrees(&r);
    let s = &r.summary["stream"];
    assert_eq!(s["moves"], 6);
    assert!(s["starved"].as_u64().unwrap() > 0, "{s}");
    assert!(s["blends"].as_u64().unwrap() < 5, "{s}");
    assert_eq!(r.summary["limits_respected"], true);
}

/// The moves contour in f32 and fixed-point playback (and with exact stops, on a smaller
/// look-ahead): each holds its limits and ends on the last move's end.
#[test]
fn moves_run_in_f32_and_fixed() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(common::jobs_dir().join("moves-contour.toml")).unwrap();
    for (name, from, to) in [
        ("f32", "number = \"f64\"", "number = \"f32\""),
        ("fixed", "number = \"f64\"", "number = \"fixed\""),
        ("stops", "tolerance = 0.02 ", "queue = 8\ntolerance = 0 #"),
    ] {
        let job = text.replace(from, to).replace(
            "queue = 32 ",
            if name == "stops" { "#" } else { "queue = 32 " },
        );
        let r = run(name, &job, dir.path());
        assert_eq!(r.output.status.code(), Some(0), "{name}: {}", r.stderr);
        agrees(&r);
        assert_eq!(r.summary["limits_respected"], true, "{name}");
        assert!(
            r.summary["end_point"]["error_to_path_end"]
                .as_f64()
                .unwrap()
                < 1e-6,
            "{name}"
        );
        if name == "stops" {
            assert_eq!(r.summary["stream"]["blends"], 0);
            assert!(r.summary["stream"]["stops"].as_u64().unwrap() >= 4);
        }
    }
}
