//! Fixtures shared by the integration tests of strak-sim: the bundled jobs, a small job that
//! holds its limits, and running the `strak-sim` binary on a job text.

// Each test file uses a part of these.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use strak_sim::job::Job;

/// A 2-axis quarter turn (a quadratic Bézier curve of 10 units a side) at 1 kHz in f64 with
/// an S-curve, well within its limits: the job the error and exit-code tests break one field
/// of at a time.
pub(crate) const QUARTER_TURN: &str = r#"rate_hz = 1000
number = "f64"

[path]
kind = "bezier"
points = [[0, 0], [10, 0], [10, 10]]

[limits]
velocity = 100
acceleration = 1000
jerk = 10000

[profile]
kind = "s-curve"
"#;

/// [`QUARTER_TURN`] with `from` replaced by `to` (`from` must occur in it).
pub(crate) fn quarter_turn_with(from: &str, to: &str) -> String {
    assert!(QUARTER_TURN.contains(from), "{from}");
    QUARTER_TURN.replace(from, to)
}

/// The folder of the bundled jobs (`examples/jobs`).
pub(crate) fn jobs_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/jobs")
}

/// The bundled job files, sorted by name (at least the four bundled ones).
pub(crate) fn bundled_jobs() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(jobs_dir())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    assert!(
        files.len() >= 4,
        "expected the bundled jobs, found {files:?}"
    );
    files
}

/// The bundled jobs with a `[path]` (not the `[[moves]]` jobs), sorted by name.
pub(crate) fn bundled_path_jobs() -> Vec<PathBuf> {
    bundled_jobs()
        .into_iter()
        .filter(|f| !strak_sim::moves::is_moves_job(&std::fs::read_to_string(f).unwrap()))
        .collect()
}

/// The bundled job `name` (`examples/jobs/<name>.toml`), parsed.
pub(crate) fn bundled_job(name: &str) -> Job {
    let text = std::fs::read_to_string(jobs_dir().join(format!("{name}.toml"))).unwrap();
    Job::parse(&text).unwrap()
}

/// The name of a job file (its stem).
pub(crate) fn stem(file: &Path) -> String {
    file.file_stem().unwrap().to_string_lossy().into_owned()
}

/// What `strak-sim run` did.
pub(crate) struct Run {
    /// The exit status and raw output.
    pub(crate) output: Output,
    /// Standard output as text.
    pub(crate) stdout: String,
    /// Standard error as text.
    pub(crate) stderr: String,
    /// The output folder (`<dir>/<name>`).
    pub(crate) out: PathBuf,
}

/// Writes `text` to `<dir>/<name>.toml` and runs `strak-sim run` on it with the output in
/// `<dir>/<name>`.
pub(crate) fn run_text(name: &str, text: &str, dir: &Path) -> Run {
    let job = dir.join(format!("{name}.toml"));
    std::fs::write(&job, text).unwrap();
    let out = dir.join(name);
    let output = Command::new(env!("CARGO_BIN_EXE_strak-sim"))
        .arg("run")
        .arg(&job)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    Run {
        stdout: String::from_utf8_lossy(&output.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&output.stderr).into_owned(),
        output,
        out,
    }
}
