//! `strak-sim move`: the bundled online move (a moving start, a new target at 0.3 s, a quick
//! stop at 0.6 s) in every number format, read back from its files and checked here from the
//! samples; velocity moves; a start outside the limits; the operator events (feed override,
//! hold, resume, abort); and bad files (one error line naming the field, exit 1).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The bundled move.
fn bundled() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/moves/retarget.toml")
}

/// Runs `strak-sim move` on `text` (written to `<dir>/<name>.toml`), output in `<dir>/<name>`.
fn run(name: &str, text: &str, dir: &Path) -> (Output, String, PathBuf) {
    let file = dir.join(format!("{name}.toml"));
    std::fs::write(&file, text).unwrap();
    let out = dir.join(name);
    let output = Command::new(env!("CARGO_BIN_EXE_strak-sim"))
        .args([
            "move",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    (output, stderr, out)
}

/// The samples of a run: `tick, t`, then positions, velocities, accelerations.
fn samples(out: &Path) -> (String, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(out.join("samples.csv")).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().to_owned();
    let rows = lines
        .map(|l| l.split(',').map(|x| x.parse::<f64>().unwrap()).collect())
        .collect();
    (header, rows)
}

fn summary(out: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
}

/// The finite differences of the samples keep every axis's limits (10⁻⁹ relative, and the
/// samples' resolution for the differences of positions and velocities).
fn assert_keeps(rows: &[Vec<f64>], limits: &[[f64; 3]], resolution: f64) {
    let d = limits.len();
    for w in rows.windows(2) {
        for (i, [v, a, j]) in limits.iter().enumerate() {
            let diff = |q: usize| (w[1][2 + q * d + i] - w[0][2 + q * d + i]) * 1000.0;
            let slack = |x: f64, of: f64| x * (1.0 + 1e-9) + 2.0 * resolution * of * 1000.0;
            assert!(
                diff(0).abs() <= slack(*v, 400.0),
                "tick {}: Δx·f {}",
                w[1][0],
                diff(0)
            );
            assert!(
                diff(1).abs() <= slack(*a, *v),
                "tick {}: Δv·f {}",
                w[1][0],
                diff(1)
            );
            assert!(
                diff(2).abs() <= slack(*j, *a),
                "tick {}: Δa·f {}",
                w[1][0],
                diff(2)
            );
            assert!(
                w[1][2 + d + i].abs() <= v * (1.0 + 1e-9)
                    && w[1][2 + 2 * d + i].abs() <= a * (1.0 + 1e-9)
            );
        }
    }
}

const LIMITS: [[f64; 3]; 3] = [
    [500.0, 5000.0, 1e5],
    [500.0, 5000.0, 1e5],
    [400.0, 3000.0, 8e4],
];

#[test]
fn the_bundled_move_runs_in_every_format_within_the_limits() {
    let text = std::fs::read_to_string(bundled()).unwrap();
    let dir = tempfile::tempdir().unwrap();
    for (number, resolution) in [
        ("f64", f64::EPSILON),
        ("f32", f64::from(f32::EPSILON)),
        ("fixed", 1e-9),
    ] {
        let text = text.replace("number = \"f64\"", &format!("number = \"{number}\""));
        let (output, stderr, out) = run(number, &text, dir.path());
        assert!(output.status.success(), "{number}: {stderr}");
        let (header, rows) = samples(&out);
        assert_eq!(header, "tick,t,x,y,z,vx,vy,vz,ax,ay,az");
        assert_keeps(&rows, &LIMITS, resolution);
        // The start, exactly; then the stop: at rest.
        assert_eq!(
            &rows[0][2..11],
            &[0.0, 0.0, 0.0, 100.0, 0.0, 0.0, 0.0, 500.0, 0.0]
        );
        assert_eq!(&rows.last().unwrap()[5..11], &[0.0; 6]);
        let s = summary(&out);
        let moves = s["moves"].as_array().unwrap();
        assert_eq!(moves.len(), 3, "{number}");
        assert_eq!(
            (moves[1]["tick"].as_u64(), moves[2]["kind"].as_str()),
            (Some(300), Some("stop"))
        );
        assert!(s["violations"].as_array().unwrap().is_empty());
        assert_eq!(s["checked_from_s"].as_f64(), Some(0.0));
        // The quick stop takes its slowest axis's minimum, rounded up to a tick.
        let stop = &moves[2];
        let slowest = stop["min_durations_s"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .fold(0.0, f64::max);
        let took = stop["duration_s"].as_f64().unwrap();
        assert!(
            took >= slowest && took < slowest + 1e-3 + 1e-9,
            "{number}: {took} vs {slowest}"
        );
        // It starts from the sample of tick 599 (its own tick 0) and ends `took` later.
        let end = s["duration_s"].as_f64().unwrap();
        assert!((end - (0.599 + took)).abs() < 1e-6, "{number}: {end}");
        // The take-over continues the samples: no step beyond a tick's worth of jerk.
        let k = 300;
        for i in 0..3 {
            let da = (rows[k][8 + i] - rows[k - 1][8 + i]).abs();
            assert!(
                da <= LIMITS[i][2] / 1000.0 * (1.0 + 1e-9) + 1e-3,
                "{number}: axis {i} Δa {da}"
            );
        }
    }
}

#[test]
fn a_move_without_target_position_reaches_the_velocity() {
    let text = r#"rate_hz = 2000
number = "f64"
[limits]
velocity = [100, 50]
acceleration = [1000, 800]
jerk = [20000, 20000]
[start]
position = [5, -5]
[target]
velocity = [80, -30]
"#;
    let dir = tempfile::tempdir().unwrap();
    let (output, stderr, out) = run("jog", text, dir.path());
    assert!(output.status.success(), "{stderr}");
    let (_, rows) = samples(&out);
    let last = rows.last().unwrap();
    assert_eq!(&last[4..8], &[80.0, -30.0, 0.0, 0.0]);
    let s = summary(&out);
    assert_eq!(s["moves"][0]["synchronization"], "time");
}

#[test]
fn a_start_beyond_the_limits_brakes_into_them_and_is_checked_from_there() {
    let text = r#"rate_hz = 1000
number = "f64"
[limits]
velocity = [100]
acceleration = [1000]
jerk = [10000]
[start]
position = [0]
velocity = [150]
acceleration = [800]
[target]
position = [0]
"#;
    let dir = tempfile::tempdir().unwrap();
    let (output, stderr, out) = run("brake", text, dir.path());
    assert!(output.status.success(), "{stderr}");
    let s = summary(&out);
    let from = s["checked_from_s"].as_f64().unwrap();
    assert!(from > 0.1, "{from}");
    let (_, rows) = samples(&out);
    let first = rows.iter().position(|r| r[1] >= from - 1e-12).unwrap();
    assert_keeps(&rows[first..], &[[100.0, 1000.0, 10000.0]], f64::EPSILON);
    assert_eq!(rows.last().unwrap()[2..5], [0.0, 0.0, 0.0]);
}

/// A bad file: exit 1 (not a panic), one error line naming `field`.
fn fails_naming(text: &str, field: &str) {
    let dir = tempfile::tempdir().unwrap();
    let (output, stderr, _) = run("bad", text, dir.path());
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains(&format!("field `{field}`")),
        "expected `{field}` in {stderr}"
    );
}

const GOOD: &str = r#"rate_hz = 1000
number = "f64"
[limits]
velocity = [100, 100]
acceleration = [1000, 1000]
jerk = [10000, 10000]
[start]
position = [0, 0]
[target]
position = [10, 5]
"#;

#[test]
fn bad_files_name_their_field() {
    let with = |from: &str, to: &str| {
        assert!(GOOD.contains(from), "{from}");
        GOOD.replace(from, to)
    };
    fails_naming(&with("rate_hz = 1000", "rate_hz = 10"), "rate_hz");
    fails_naming(&with("number = \"f64\"", "number = \"f16\""), "number");
    fails_naming(
        &with("acceleration = [1000, 1000]", "acceleration = [1000]"),
        "limits.acceleration",
    );
    fails_naming(
        &with("jerk = [10000, 10000]", "jerk = [10000, 0]"),
        "limits.jerk[1]",
    );
    fails_naming(
        &with("position = [0, 0]", "position = [0, 0, 0]"),
        "start.position",
    );
    fails_naming(
        &with(
            "position = [10, 5]",
            "position = [10, 5]\nvelocity = [200, 0]",
        ),
        "target",
    );
    fails_naming(&with("[start]", "sync = \"sometimes\"\n[start]"), "sync");
    fails_naming(&format!("{GOOD}[[events]]\ntick = 5\n"), "events[0]");
    fails_naming(
        &format!("{GOOD}[[events]]\ntick = 5\nstop = true\n[[events]]\ntick = 5\nstop = true\n"),
        "events[1].tick",
    );
    fails_naming(&with("[target]", "[target]\nspeed = 3"), "target.speed");
    fails_naming(
        &format!("{GOOD}[[events]]\ntick = 5\nfeed = 0.005\n"),
        "events[0].feed",
    );
    fails_naming(
        &format!("{GOOD}[[events]]\ntick = 5\nhold = true\nabort = true\n"),
        "events[0]",
    );
}

/// The operator events re-time the move: a feed override, a hold (a quick stop that keeps
/// the target), a new target while held (it waits), resume (to the new target), an abort
/// (every later event ignored); every limit holds, in every format.
#[test]
fn operator_events_re_time_the_move_within_the_limits() {
    let events = "[[events]]\ntick = 20\nfeed = 0.5\n[[events]]\ntick = 150\nhold = true\n\
                  [[events]]\ntick = 180\ntarget = { position = [-5, 5] }\n\
                  [[events]]\ntick = 400\nresume = true\n[[events]]\ntick = 460\nabort = true\n\
                  [[events]]\ntick = 700\nresume = true\n";
    let dir = tempfile::tempdir().unwrap();
    for (number, resolution) in [
        ("f64", f64::EPSILON),
        ("f32", f64::from(f32::EPSILON)),
        ("fixed", 1e-9),
    ] {
        let text = format!("{GOOD}{events}").replace("\"f64\"", &format!("\"{number}\""));
        let (output, stderr, out) = run(number, &text, dir.path());
        assert!(output.status.success(), "{number}: {stderr}");
        let (_, rows) = samples(&out);
        let limits = [[100.0, 1000.0, 10000.0]; 2];
        assert_keeps(&rows, &limits, resolution);
        let s = summary(&out);
        let kinds: Vec<&str> = s["moves"]
            .as_array()
            .unwrap()
            .iter()
            .map(|m| m["kind"].as_str().unwrap())
            .collect();
        // The new target while held moves nothing; the resume after the abort is ignored.
        assert_eq!(
            kinds,
            ["target", "feed", "hold", "resume", "abort"],
            "{number}"
        );
        assert_eq!(s["events_ignored"].as_u64(), Some(1), "{number}");
        // The feed halves the velocity limits from tick 20 on (the x axis, which limits the
        // move, reaches its half; at full feed it would be past it by tick 150); the hold
        // stops the motion before the resume.
        let vx = rows[20..150].iter().fold(0.0_f64, |m, r| m.max(r[4].abs()));
        assert!(vx <= 50.0 * (1.0 + 1e-9) && vx > 45.0, "{number}: {vx}");
        assert_eq!((rows[399][4], rows[399][5]), (0.0, 0.0), "{number}");
        assert_eq!(&rows.last().unwrap()[4..8], &[0.0; 4], "{number}: at rest");
    }
}
