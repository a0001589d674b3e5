//! The exit code of `strak-sim run`: 3, with one error line naming each quantity, when a time
//! law planned under the limits (trapezoid, S-curve) exceeds a limit it plans for or the
//! accuracy bound in its samples; 0 when everything holds, and 0 for the laws not planned
//! under the limits (parameter, constant speed), whose summary reports the excess.

mod common;

use std::path::Path as FsPath;
use std::process::Output;

use common::{QUARTER_TURN as GOOD, bundled_jobs, run_text, stem};

/// A straight line (73.65 units) at 1 kHz in f64 with an S-curve whose jerk phases last a few
/// ticks: the compiled spline overshoots the planned velocity, |v| 21.72 against 21.23.
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

#[test]
#[ignore = "the job's straight-line overshoot is fixed (the compiled fit keeps the plan's limits): \
            no planned job is known to break a limit; it needs a new violating job"]
fn a_planned_overshoot_exits_3_naming_the_quantity() {
    let dir = tempfile::tempdir().unwrap();
    let r = run("line", SHORT_JERK_PHASES, dir.path());
    assert_eq!(
        r.output.status.code(),
        Some(3),
        "{}\n{}",
        r.stderr,
        r.stdout
    );
    assert!(
        r.stderr
            .lines()
            .any(|l| l.contains("line.toml: limit exceeded: velocity |v| = ")),
        "{}",
        r.stderr
    );
    assert_eq!(r.summary["path"]["velocity"]["within"], false);
    assert_eq!(r.summary["path"]["velocity"]["enforced"], true);
    assert!(r.stdout.contains("EXCEEDED"), "{}", r.stdout);
    // The output is written all the same, for a look at what went wrong.
    assert!(dir.path().join("line/samples.csv").exists());
    agrees(&r);
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
