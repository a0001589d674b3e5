//! `strak-sim gcode` end to end: the bundled programs played on the bundled machines in every
//! number format stay within the limits (measured from the samples), deviate at most the
//! corner tolerance, and end exactly at the program's last position, E included; the CSV,
//! `--every`, starvation and errors naming the line.

use std::path::{Path, PathBuf};
use std::process::Command;

use strak_sim::gcode_run::run_gcode;
use strak_sim::machine::{DEFAULT_MACHINE, Machine};
use strak_sim::number::NumberFormat;
use strak_sim::run::{RunError, RunOptions};
use strak_sim::summary::Summary;

fn example(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join(path)
}

fn printer() -> String {
    std::fs::read_to_string(example("machines/printer.toml")).unwrap()
}

/// `machine` with its number format `number`.
fn in_format(machine: &str, number: &str) -> Machine {
    let text = machine.replace("number = \"f32\"", &format!("number = \"{number}\""));
    assert!(text.contains(&format!("number = \"{number}\"")));
    Machine::parse(&text).unwrap()
}

fn play(program: &str, machine: &Machine, dir: &Path, every: u64) -> Result<Summary, RunError> {
    let text = std::fs::read(example(program)).unwrap();
    let options = RunOptions {
        out_dir: dir.to_path_buf(),
        name: "test".to_owned(),
        progress: false,
        velocity_factor: None,
    };
    run_gcode(&text, program, machine, &options, every)
}

/// The last value of each axis letter in a program of absolute X Y Z and relative E (the
/// sum of its E words), read by splitting words: independent of the reader.
fn program_end(program: &str) -> [f64; 4] {
    let text = std::fs::read_to_string(example(program)).unwrap();
    let mut end = [0.0; 4];
    let mut incremental = false;
    for line in text.lines() {
        let code = line.split([';', '(']).next().unwrap();
        for word in code.split_whitespace() {
            match word {
                "G91" => incremental = true,
                "G90" => incremental = false,
                _ => {}
            }
            let (letter, value) = word.split_at(1);
            let Some(i) = "XYZE".find(letter) else {
                continue;
            };
            let v: f64 = value.parse().unwrap();
            if i == 3 || incremental {
                end[i] += v;
            } else {
                end[i] = v;
            }
        }
    }
    end
}

/// The checks every bundled run passes.
fn holds(s: &Summary, end: &[f64], number: NumberFormat) {
    assert!(s.finished, "{}", s.stop);
    assert!(s.violations.is_empty(), "{:#?}", s.violations);
    assert!(s.limits_respected);
    let stream = s.stream.as_ref().unwrap();
    assert!(stream.max_deviation.max <= stream.tolerance, "{stream:?}");
    assert_eq!(s.accuracy.distance.within, Some(true));
    for (i, (got, want)) in s.end_point.last_sample.iter().zip(end).enumerate() {
        let unit = match number {
            NumberFormat::F64 => 0.0,
            NumberFormat::F32 => want.abs() * f64::from(f32::EPSILON),
            NumberFormat::Q40 => 2f64.powi(-32),
        };
        assert!(
            (got - want).abs() <= unit,
            "axis {i}: ended at {got}, the program at {want}"
        );
    }
}

#[test]
fn the_contour_plays_within_the_limits_in_every_format() {
    let dir = tempfile::tempdir().unwrap();
    let end = program_end("gcode/contour.nc");
    assert_eq!(end[..3], [0.0, 0.0, 5.0]);
    for (number, format) in [
        ("f64", NumberFormat::F64),
        ("f32", NumberFormat::F32),
        ("fixed", NumberFormat::Q40),
    ] {
        let machine = in_format(DEFAULT_MACHINE, number);
        let s = play("gcode/contour.nc", &machine, dir.path(), 1).unwrap();
        holds(&s, &end[..3], format);
        let g = s.gcode.as_ref().unwrap();
        assert_eq!((g.moves, g.dwells, g.dwell_s), (25, 1, 0.5));
        let ignored: Vec<&str> = g.ignored.iter().map(|c| c.code.as_str()).collect();
        assert_eq!(ignored, ["G94", "T1", "M6", "M3", "S", "M5", "M30"]);
        let stream = s.stream.as_ref().unwrap();
        // G64 P0.02 blends the outline's corners; G61 stops at the slot's
        assert!(stream.blends >= 4 && stream.stops >= 4, "{stream:?}");
        assert_eq!(stream.tolerance, 0.02);
    }
}

#[test]
fn the_print_plays_within_the_limits_with_e_riding_along() {
    let dir = tempfile::tempdir().unwrap();
    let end = program_end("gcode/print.gcode");
    assert_eq!(end[..3], [0.0, 200.0, 5.0]);
    assert!(end[3] > 100.0, "{end:?}");
    for (number, format) in [("f32", NumberFormat::F32), ("fixed", NumberFormat::Q40)] {
        let machine = in_format(&printer(), number);
        let s = play("gcode/print.gcode", &machine, dir.path(), 1).unwrap();
        holds(&s, &end, format);
        let g = s.gcode.as_ref().unwrap();
        assert_eq!(g.riding_axes, ["e"]);
        assert!(g.ignored.iter().any(|c| c.code == "M104" && c.count == 2));
        // the path norms are over x, y, z: E's own limits bound it
        let e = &s.per_axis[3];
        assert_eq!(e.name, "e");
        assert!(e.velocity.max > 0.0 && e.velocity.max <= 60.0 * (1.0 + 1e-4));
        assert!(s.path.velocity.max <= 150.0 * (1.0 + 1e-4));
    }
}

#[test]
fn a_slow_producer_starves_the_stream_within_the_limits() {
    let dir = tempfile::tempdir().unwrap();
    let text = format!("{DEFAULT_MACHINE}\n[produce]\nmoves_per_second = 4\n");
    let machine = Machine::parse(&text).unwrap();
    let s = play("gcode/contour.nc", &machine, dir.path(), 1).unwrap();
    holds(&s, &program_end("gcode/contour.nc")[..3], NumberFormat::F32);
    let stream = s.stream.as_ref().unwrap();
    assert!(stream.starved > 0, "{stream:?}");
    assert_eq!(stream.moves_per_second, Some(4.0));
    // 26 moves and dwells, one every 250 ticks: the last arrives after 6.25 s
    assert!(s.duration_s > 6.25);
}

#[test]
fn the_csv_has_the_machine_axes_and_every_kth_tick() {
    let dir = tempfile::tempdir().unwrap();
    let machine = Machine::parse(&printer()).unwrap();
    let s = play("gcode/print.gcode", &machine, dir.path(), 100).unwrap();
    let csv = std::fs::read_to_string(dir.path().join("samples.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("tick,t,x,y,z,e,vx,vy,vz,ve,ax,ay,az,ae"));
    let ticks: Vec<u64> = lines
        .map(|l| l.split(',').next().unwrap().parse().unwrap())
        .collect();
    assert_eq!(ticks.len() as u64, s.samples.div_ceil(100));
    assert!(ticks.iter().enumerate().all(|(i, &t)| t == 100 * i as u64));
    for file in ["summary.json", "path.svg", "motion.svg"] {
        assert!(dir.path().join(file).is_file(), "{file}");
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("summary.json")).unwrap())
            .unwrap();
    assert_eq!(json["gcode"]["riding_axes"][0], "e");
    assert!(json["gcode"]["planned_moves_per_s"].as_f64().unwrap() > 0.0);
}

#[test]
fn a_bad_line_is_an_error_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let machine = Machine::parse(DEFAULT_MACHINE).unwrap();
    let options = RunOptions {
        out_dir: dir.path().to_path_buf(),
        name: "bad".to_owned(),
        progress: false,
        velocity_factor: None,
    };
    let run = |text: &str| run_gcode(text.as_bytes(), "bad.nc", &machine, &options, 1);
    let e = run("G21\nG1 X10 F600\nG1 Y\n").unwrap_err().to_string();
    assert!(e.starts_with("line 3, column 4"), "{e}");
    let e = run("G0 X10\nG2 X0 Y10 I-10 J0.1\n")
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("line 2"), "{e}");
    // an axis the machine does not have
    let e = run("G1 E5 F600\n").unwrap_err().to_string();
    assert!(e.starts_with("line 1"), "{e}");
}

#[test]
fn the_command_line_writes_its_files_and_exits_zero() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("contour");
    let output = Command::new(env!("CARGO_BIN_EXE_strak-sim"))
        .arg("gcode")
        .arg(example("gcode/contour.nc"))
        .args(["--every", "10", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(stdout.starts_with("strak-sim gcode: contour"), "{stdout}");
    assert!(stdout.contains("ignored    G94 ×1"), "{stdout}");
    assert!(out.join("samples.csv").is_file());
    let missing = Command::new(env!("CARGO_BIN_EXE_strak-sim"))
        .args(["gcode", "no-such-file.nc", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(missing.status.code(), Some(1));
}
