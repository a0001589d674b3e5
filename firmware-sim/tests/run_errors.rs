//! Bad jobs: each error case gives exactly one error line on standard error naming the field,
//! and a non-zero exit — never a panic.

mod common;

use std::process::Command;

use common::{QUARTER_TURN as GOOD, quarter_turn_with as with, run_text};

/// Runs `strak-sim run` on `text`; asserts a failure with one line naming `field`.
fn fails_naming(text: &str, field: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    let common::Run { output, stderr, .. } = run_text("bad", text, dir.path());
    assert!(!output.status.success(), "succeeded on a bad job:\n{text}");
    assert_eq!(
        output.status.code(),
        Some(1),
        "exit code (a panic gives 101): {stderr}"
    );
    assert_eq!(
        stderr.lines().count(),
        1,
        "expected one error line, got:\n{stderr}"
    );
    assert!(
        stderr.starts_with("strak-sim: error: ") && stderr.contains("bad.toml"),
        "{stderr}"
    );
    assert!(
        stderr.contains(&format!("field `{field}`")),
        "expected field `{field}` in: {stderr}"
    );
    stderr
}

#[test]
fn the_good_job_runs() {
    let dir = tempfile::tempdir().unwrap();
    let r = run_text("good", GOOD, dir.path());
    assert!(r.output.status.success(), "{}", r.stderr);
}

#[test]
fn missing_top_level_field() {
    fails_naming(&with("rate_hz = 1000\n", ""), "rate_hz");
}

#[test]
fn missing_limit() {
    fails_naming(&with("velocity = 100\n", ""), "limits.velocity");
}

#[test]
fn missing_table() {
    let text = with("[profile]\nkind = \"s-curve\"\n", "");
    fails_naming(&text, "profile");
}

#[test]
fn unknown_field() {
    fails_naming(
        &with("jerk = 10000\n", "jerk = 10000\ncolour = 3\n"),
        "limits.colour",
    );
}

#[test]
fn rate_zero() {
    fails_naming(&with("rate_hz = 1000", "rate_hz = 0"), "rate_hz");
}

#[test]
fn rate_negative() {
    fails_naming(&with("rate_hz = 1000", "rate_hz = -5"), "rate_hz");
}

#[test]
fn rate_out_of_range() {
    let e = fails_naming(&with("rate_hz = 1000", "rate_hz = 200000"), "rate_hz");
    assert!(e.contains("100 kHz"), "{e}");
}

#[test]
fn velocity_limit_zero() {
    fails_naming(&with("velocity = 100", "velocity = 0"), "limits.velocity");
}

#[test]
fn acceleration_limit_negative() {
    fails_naming(
        &with("acceleration = 1000", "acceleration = -1000"),
        "limits.acceleration",
    );
}

#[test]
fn jerk_limit_not_finite() {
    fails_naming(&with("jerk = 10000", "jerk = inf"), "limits.jerk");
}

#[test]
fn axis_limits_of_the_wrong_length() {
    fails_naming(
        &with(
            "jerk = 10000\n",
            "jerk = 10000\naxis_velocity = [10, 10, 10]\n",
        ),
        "limits.axis_velocity",
    );
}

#[test]
fn axis_limit_zero() {
    fails_naming(
        &with(
            "jerk = 10000\n",
            "jerk = 10000\naxis_acceleration = [10, 0]\n",
        ),
        "limits.axis_acceleration",
    );
}

#[test]
fn empty_path() {
    let e = fails_naming(
        &with("points = [[0, 0], [10, 0], [10, 10]]", "points = []"),
        "path.points",
    );
    assert!(e.contains("empty"), "{e}");
}

#[test]
fn path_of_zero_length() {
    let e = fails_naming(
        &with(
            "points = [[0, 0], [10, 0], [10, 10]]",
            "points = [[5, 5], [5, 5], [5, 5]]",
        ),
        "path",
    );
    assert!(e.contains("zero length"), "{e}");
}

#[test]
fn bad_curve_field() {
    fails_naming(
        &with("kind = \"bezier\"", "kind = \"bspline\""),
        "path.degree",
    );
}

#[test]
fn unknown_number_format() {
    fails_naming(&with("number = \"f64\"", "number = \"f16\""), "number");
}

#[test]
fn capacity_too_small_for_the_motion() {
    // 200 s at 100 kHz: at least 78 125 pieces of 256 ticks, the simulator holds 16 384.
    let text = with("rate_hz = 1000", "rate_hz = 100000").replace(
        "kind = \"s-curve\"",
        "kind = \"parameter\"\nduration = 200.0",
    );
    let e = fails_naming(&text, "rate_hz");
    assert!(e.contains("hold 16384 pieces"), "{e}");
}

#[test]
fn capacity_too_small_for_the_tolerance() {
    // A circle at constant speed (positions not polynomial in t anywhere) at 100 kHz, to a
    // tolerance below the rounding of f64: only pieces of one tick meet it, 62 832 of them.
    let text = r#"rate_hz = 100000
number = "f64"

[path]
kind = "nurbs"
degree = 2
points = [[10, 0], [10, 10], [0, 10], [-10, 10], [-10, 0], [-10, -10], [0, -10], [10, -10], [10, 0]]
weights = [1, 0.7071067811865476, 1, 0.7071067811865476, 1, 0.7071067811865476, 1, 0.7071067811865476, 1]
knots = [0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4]

[limits]
velocity = 100
acceleration = 1000
jerk = 10000

[profile]
kind = "constant-speed"

[compile]
tolerance = 1e-15
"#;
    let e = fails_naming(text, "compile.tolerance");
    assert!(e.contains("hold 16384 pieces"), "{e}");
}

#[test]
fn zone_capacity_too_small() {
    // A wavy path sampled finely with no zone merging needs more than 1024 zones.
    let text = with(
        "points = [[0, 0], [10, 0], [10, 10]]",
        "points = [[0, 0], [10, 8], [20, -8], [30, 8], [40, -8], [50, 8], [60, -8], [70, 8], [80, 0]]",
    )
    .replace("kind = \"bezier\"", "kind = \"cubic-spline\"")
    .replace(
        "kind = \"s-curve\"",
        "kind = \"s-curve\"\nsamples = 8192\nzone_tolerance = 0.0",
    );
    let e = fails_naming(&text, "profile.zone_tolerance");
    assert!(e.contains("at most 1024 zones"), "{e}");
}

#[test]
fn range_too_large_for_fixed_point() {
    // Q40 holds ±4 194 304 units; these points fit I32F32 (the curve) but not the path.
    let text = with("number = \"f64\"", "number = \"fixed\"").replace(
        "points = [[0, 0], [10, 0], [10, 10]]",
        "points = [[5000000, 0], [5000010, 0], [5000010, 10]]",
    );
    let e = fails_naming(&text, "path.points[0][0]");
    assert!(e.contains("5000000") && e.contains("4194304"), "{e}");
}

#[test]
fn a_far_point_is_named_not_the_rate() {
    // A long motion from a point outside the Q40 range: the coordinate is the error, not the
    // number of pieces the motion would need.
    let text = with("number = \"f64\"", "number = \"fixed\"").replace(
        "points = [[0, 0], [10, 0], [10, 10]]",
        "points = [[0, 0], [10, 0], [10, 4194310], [4194000, 20]]",
    );
    let e = fails_naming(&text, "path.points[2][1]");
    assert!(e.contains("4194310") && e.contains("±4194304"), "{e}");
}

#[test]
fn range_too_large_for_the_fixed_point_curve() {
    let text = with("number = \"f64\"", "number = \"fixed\"").replace(
        "points = [[0, 0], [10, 0], [10, 10]]",
        "points = [[0, 0], [1e10, 0], [10, 10]]",
    );
    fails_naming(&text, "path.points[1][0]");
}

#[test]
fn range_too_large_for_an_f32_curve() {
    let text = with("number = \"f64\"", "number = \"f32\"").replace(
        "points = [[0, 0], [10, 0], [10, 10]]",
        "points = [[0, 0], [10, 1e39], [10, 10]]",
    );
    let e = fails_naming(&text, "path.points[1][1]");
    assert!(e.contains("number = f32"), "{e}");
}

#[test]
fn point_of_the_wrong_dimension() {
    fails_naming(
        &with("[10, 0], [10, 10]]", "[10, 0, 1], [10, 10]]"),
        "path.points[1]",
    );
}

#[test]
fn seven_axes() {
    let e = fails_naming(
        &with(
            "points = [[0, 0], [10, 0], [10, 10]]",
            "points = [[0, 0, 0, 0, 0, 0, 0], [1, 1, 1, 1, 1, 1, 1]]",
        ),
        "path.points[0]",
    );
    assert!(e.contains("1 to 6 coordinates"), "{e}");
}

#[test]
fn too_many_points() {
    let points: Vec<String> = (0..4097).map(|i| format!("[{i}, 0]")).collect();
    let text = with("kind = \"bezier\"", "kind = \"bspline\"\ndegree = 1").replace(
        "points = [[0, 0], [10, 0], [10, 10]]",
        &format!("points = [{}]", points.join(", ")),
    );
    let e = fails_naming(&text, "path.points");
    assert!(
        e.contains("4097 points") && e.contains("at most 4096"),
        "{e}"
    );
}

#[test]
fn mistyped_field_in_a_tagged_table() {
    fails_naming(
        &with(
            "kind = \"bezier\"",
            "kind = \"bspline\"\ndegree = \"three\"",
        ),
        "path.degree",
    );
    fails_naming(
        &with(
            "kind = \"s-curve\"",
            "kind = \"s-curve\"\nsamples = \"many\"",
        ),
        "profile.samples",
    );
}

#[test]
fn parameter_profile_without_duration() {
    fails_naming(
        &with("kind = \"s-curve\"", "kind = \"parameter\""),
        "profile.duration",
    );
}

#[test]
fn profile_field_of_another_kind() {
    fails_naming(
        &with("kind = \"s-curve\"", "kind = \"s-curve\"\nspeed = 3"),
        "profile.speed",
    );
}

#[test]
fn planner_settings_out_of_range() {
    for (setting, field) in [
        ("samples = 0", "profile.samples"),
        ("zone_tolerance = -0.1", "profile.zone_tolerance"),
        ("centripetal_share = 1.0", "profile.centripetal_share"),
        ("corner_angle = 0.0", "profile.corner_angle"),
        ("corner_angle = -1e-3", "profile.corner_angle"),
    ] {
        fails_naming(
            &with(
                "kind = \"s-curve\"",
                &format!("kind = \"s-curve\"\n{setting}"),
            ),
            field,
        );
    }
}

#[test]
fn feed_out_of_range() {
    fails_naming(
        &format!("{GOOD}\n[[events]]\ntick = 10\nfeed = 1.5\n"),
        "events[0].feed",
    );
}

#[test]
fn event_without_action() {
    fails_naming(
        &format!("{GOOD}\n[[events]]\ntick = 10\nhold = true\n\n[[events]]\ntick = 20\n"),
        "events[1]",
    );
}

#[test]
fn event_with_a_negative_tick() {
    fails_naming(
        &format!("{GOOD}\n[[events]]\ntick = -3\nhold = true\n"),
        "events[0].tick",
    );
}

#[test]
fn feed_share_out_of_range() {
    fails_naming(
        &format!("{GOOD}\n[compile]\nfeed_share = 1.0\n"),
        "compile.feed_share",
    );
}

#[test]
fn missing_job_file() {
    let output = Command::new(env!("CARGO_BIN_EXE_strak-sim"))
        .args(["run", "/nonexistent/job.toml"])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("cannot read"), "{stderr}");
}

/// The bundled moves job, the one the bad moves below break one field of.
fn moves_job() -> String {
    std::fs::read_to_string(common::jobs_dir().join("moves-contour.toml")).unwrap()
}

/// The moves job with `from` replaced by `to` (`from` must occur in it).
fn moves_with(from: &str, to: &str) -> String {
    let text = moves_job();
    assert!(text.contains(from), "{from}");
    text.replacen(from, to, 1)
}

#[test]
fn moves_a_zero_length_line() {
    let e = fails_naming(
        &moves_with("line = [10, 0, 0]", "line = [0, 0, 0]"),
        "moves[0].line",
    );
    assert!(e.contains("zero length"), "{e}");
}

#[test]
fn moves_an_arc_whose_end_is_off_its_circle() {
    let e = fails_naming(
        &moves_with("to = [20, 10, 0], center", "to = [20, 11, 0], center"),
        "moves[1].arc.to",
    );
    assert!(e.contains("off the circle"), "{e}");
}

#[test]
fn moves_a_non_finite_value() {
    fails_naming(
        &moves_with("c1 = [22, 15, 0]", "c1 = [22, nan, 0]"),
        "moves[2].bezier.c1[1]",
    );
    fails_naming(
        &moves_with("line = [30, -10, 2]", "line = [30, inf, 2]"),
        "moves[3].line[1]",
    );
}

#[test]
fn moves_two_shapes_in_one_move() {
    let e = fails_naming(
        &moves_with(
            "feed = 150",
            "feed = 150\nbezier = { to = [1, 1, 0], c1 = [0, 1, 0], c2 = [1, 0, 0] }",
        ),
        "moves[0]",
    );
    assert!(e.contains("exactly one of line, arc, bezier"), "{e}");
}

#[test]
fn moves_of_another_axis_count() {
    fails_naming(
        &moves_with("line = [30, -10, 2]", "line = [30, -10]"),
        "moves[3].line",
    );
}

#[test]
fn moves_a_queue_the_simulator_does_not_build() {
    let e = fails_naming(&moves_with("queue = 32", "queue = 12"), "queue");
    assert!(e.contains("8, 16, 32 or 64"), "{e}");
}

#[test]
fn moves_a_bezier_whose_tangent_vanishes() {
    fails_naming(
        &moves_with("c2 = [28, 5, 0]", "c2 = [30, 0, 0]"),
        "moves[2].bezier.c2",
    );
}

#[test]
fn moves_beside_a_path() {
    fails_naming(
        &format!("{}\n[path]\nkind = \"bezier\"\n", moves_job()),
        "path",
    );
}
