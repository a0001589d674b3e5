//! The fuzz corpora as ordinary tests: every harness of `fuzz/` ([`strak_fuzz::TARGETS`]) on
//! every checked-in input of its corpus (`fuzz/corpus/<target>/`), on its seeds
//! ([`strak_fuzz::seeds`]), and on every input that once failed (`fuzz/artifacts-kept/<target>/`).
//!
//! An input that fails today is listed in [`KNOWN_FAILURES`] with a fragment of its
//! failure: the test asserts that it still fails that way, so a fix makes the test fail
//! until the entry is removed (the input then stays as a regression test). Every other input
//! must pass. A panic counts as a failure (the harness's own checks report violations as
//! errors).

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};

use strak_fuzz::{TARGETS, Target};

/// Inputs under `fuzz/artifacts-kept/<target>/` that fail today: target, file name, and a
/// fragment of the failure message. Each is a bug in the library, reported with the
/// input; remove the entry when it is fixed.
const KNOWN_FAILURES: &[(&str, &str, &str)] = &[];

fn fuzz_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz")
}

/// The files of a folder, sorted by name (none when it does not exist).
fn files(dir: &Path) -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|d| d.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    out.retain(|p| p.is_file());
    out.sort();
    out
}

/// The harness's verdict on `bytes`: a violation or a panic is an error.
fn verdict(target: &Target, bytes: &[u8]) -> Result<(), String> {
    match catch_unwind(AssertUnwindSafe(|| (target.run)(bytes))) {
        Ok(Ok(())) => Ok(()),
        Ok(Err(v)) => Err(v.to_string()),
        Err(panic) => Err(format!(
            "panic: {}",
            panic
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panic.downcast_ref::<&str>().map(|s| (*s).to_owned()))
                .unwrap_or_default()
        )),
    }
}

fn target(name: &str) -> &'static Target {
    TARGETS
        .iter()
        .find(|t| t.name == name)
        .unwrap_or_else(|| panic!("no fuzz target `{name}`"))
}

fn known(target: &str, file: &Path) -> Option<&'static str> {
    let name = file.file_name()?.to_str()?;
    KNOWN_FAILURES
        .iter()
        .find(|(t, f, _)| *t == target && *f == name)
        .map(|(_, _, fragment)| *fragment)
}

#[test]
fn every_corpus_input_passes() {
    let mut failures = Vec::new();
    for t in &TARGETS {
        let inputs = files(&fuzz_dir().join("corpus").join(t.name));
        assert!(!inputs.is_empty(), "fuzz/corpus/{} is empty", t.name);
        for file in inputs {
            let bytes = std::fs::read(&file).expect("read a corpus file");
            if let Err(e) = verdict(t, &bytes) {
                failures.push(format!("{}: {e}", file.display()));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} corpus inputs fail:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn every_seed_passes() {
    let seeds = strak_fuzz::seeds::all();
    for name in TARGETS.map(|t| t.name) {
        assert!(seeds.iter().any(|s| s.target == name), "no seed for {name}");
    }
    for s in seeds {
        if let Err(e) = verdict(target(s.target), &s.bytes) {
            panic!("seed {}/{}: {e}", s.target, s.name);
        }
    }
}

#[test]
fn inputs_that_once_failed_pass_unless_known() {
    let mut unexpected = Vec::new();
    for t in &TARGETS {
        for file in files(&fuzz_dir().join("artifacts-kept").join(t.name)) {
            if file.extension().is_some_and(|e| e == "md") {
                continue;
            }
            let bytes = std::fs::read(&file).expect("read a kept artifact");
            match (verdict(t, &bytes), known(t.name, &file)) {
                (Ok(()), None) => {}
                (Ok(()), Some(_)) => unexpected.push(format!(
                    "{}: passes now; remove it from KNOWN_FAILURES",
                    file.display()
                )),
                (Err(e), None) => unexpected.push(format!("{}: {e}", file.display())),
                (Err(e), Some(fragment)) if !e.contains(fragment) => unexpected.push(format!(
                    "{}: fails otherwise than known (`{fragment}`): {e}",
                    file.display()
                )),
                (Err(_), Some(_)) => {}
            }
        }
    }
    assert!(unexpected.is_empty(), "{}", unexpected.join("\n"));
}

#[test]
fn every_known_failure_is_kept() {
    for (t, file, _) in KNOWN_FAILURES {
        target(t);
        let path = fuzz_dir().join("artifacts-kept").join(t).join(file);
        assert!(
            path.is_file(),
            "KNOWN_FAILURES names a missing input {}",
            path.display()
        );
    }
}
