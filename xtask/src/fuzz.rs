//! `cargo xtask fuzz [--time SECONDS] [--runs N] [--fork JOBS] [--no-trace-compares]
//! [--keep-going] [--ignore FRAGMENT] [--minimize] [TARGET]`: the coverage-guided fuzz targets
//! of `fuzz/` (cargo-fuzz, libFuzzer), each for a given time or number of executions.
//!
//! 1. Installs cargo-fuzz (`cargo install cargo-fuzz --locked`) when `cargo fuzz` does not
//!    run; fails loudly when it cannot.
//! 2. Chooses the toolchain: nightly when rustup has one, else stable with
//!    `RUSTC_BOOTSTRAP=1` (cargo-fuzz passes `-Z` flags to rustc).
//! 3. Builds the targets with debug assertions and overflow checks (`-a`: a fixed-point or
//!    integer overflow is a panic) and without a sanitizer (the crates have no `unsafe` on
//!    the host; coverage instrumentation only, for speed). `--no-trace-compares` leaves out
//!    the tracing of integer comparisons (cargo-fuzz's flag of that name; a build of its own
//!    in `fuzz/target/no-trace-compares/`): it guides mutations towards the constants that
//!    integer comparisons test, but the float-heavy targets (`pipeline`, `curves`) test
//!    floats, which it does not trace, and spend half their time in it.
//! 4. Writes the seeds ([`strak_fuzz::seeds`]) into the working corpus `fuzz/work/<target>/`
//!    (not checked in), then runs each target on it and on the checked-in corpus
//!    `fuzz/corpus/<target>/` for `--time` seconds (default 60; with `--runs N` and no
//!    `--time`, until it has run `N` inputs, libFuzzer's `-runs`) in one process
//!    (`-fork=1 -ignore_crashes=1` with `--keep-going`, which goes on after a failure;
//!    `--fork JOBS` runs that many libFuzzer processes at a time under one parent, libFuzzer's
//!    fork mode, which merges their findings into the one corpus and counts all their
//!    executions), and
//!    prints the executions and the result; failing inputs go to `fuzz/artifacts/<target>/`.
//!    `--ignore FRAGMENT` (repeatable) masks the violations whose message contains it
//!    ([`strak_fuzz::IGNORE_VAR`]): a known failure, so that the run finds others.
//! 5. `--minimize` instead merges the working and the checked-in corpus into a minimal set
//!    with the same edge coverage (`-merge=1 -use_counters=0`, inputs up to [`MAX_LEN`]
//!    bytes) and writes it
//!    into `fuzz/corpus/<target>/`.
//!
//! The replay of the checked-in corpora is an ordinary test (`tests/tests/fuzz_replay.rs`)
//! that needs neither nightly nor cargo-fuzz.

use std::env;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Instant;

/// The longest input libFuzzer generates and the minimized corpus keeps.
const MAX_LEN: usize = 4096;
/// A single input running longer than this is a failure (libFuzzer's `-timeout`).
const TIMEOUT_S: u32 = 30;

/// The options of `cargo xtask fuzz`.
#[derive(Clone, Debug, Default)]
pub(crate) struct FuzzOptions {
    /// Seconds per target (0: no limit).
    pub(crate) seconds: u64,
    /// Executions per target (libFuzzer's `-runs`), if limited.
    pub(crate) runs: Option<u64>,
    /// Go on after a failure (fork mode).
    pub(crate) keep_going: bool,
    /// libFuzzer processes at a time (fork mode), if more than one.
    pub(crate) fork: Option<u32>,
    /// Build without cargo-fuzz's tracing of integer comparisons.
    pub(crate) no_trace_compares: bool,
    /// Merge the corpora instead of fuzzing.
    pub(crate) minimize: bool,
    /// Only this target.
    pub(crate) target: Option<String>,
    /// Fragments of violation messages to ignore (known failures).
    pub(crate) ignore: Vec<String>,
}

/// Parses the arguments after `fuzz`.
pub(crate) fn parse(args: &[String]) -> Result<FuzzOptions, String> {
    let mut o = FuzzOptions::default();
    let mut seconds = None;
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--time" => {
                let v = it.next().ok_or("--time needs a number of seconds")?;
                seconds = Some(
                    v.parse()
                        .map_err(|_| format!("--time {v}: not a number of seconds"))?,
                );
            }
            "--runs" => {
                let v = it.next().ok_or("--runs needs a number of executions")?;
                o.runs = Some(
                    v.parse()
                        .map_err(|_| format!("--runs {v}: not a number of executions"))?,
                );
            }
            "--keep-going" => o.keep_going = true,
            "--fork" => {
                let v = it.next().ok_or("--fork needs a number of processes")?;
                o.fork = Some(
                    v.parse()
                        .ok()
                        .filter(|n| *n >= 1)
                        .ok_or_else(|| format!("--fork {v}: not a number of processes"))?,
                );
            }
            "--no-trace-compares" => o.no_trace_compares = true,
            "--ignore" => o.ignore.push(
                it.next()
                    .ok_or("--ignore needs a fragment of a failure message")?
                    .clone(),
            ),
            "--minimize" => o.minimize = true,
            t if !t.starts_with('-') && o.target.is_none() => o.target = Some(t.to_owned()),
            other => return Err(format!("unknown option `{other}` of fuzz")),
        }
    }
    o.seconds = seconds.unwrap_or(if o.runs.is_some() { 0 } else { 60 });
    if let Some(t) = &o.target
        && !strak_fuzz::TARGETS.iter().any(|x| x.name == t)
    {
        let names: Vec<&str> = strak_fuzz::TARGETS.iter().map(|x| x.name).collect();
        return Err(format!(
            "no fuzz target `{t}`; targets: {}",
            names.join(", ")
        ));
    }
    Ok(o)
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map_or_else(|| PathBuf::from("."), Path::to_owned)
}

/// How `cargo fuzz` is started: the toolchain and its environment.
struct Toolchain {
    label: &'static str,
    envs: Vec<(&'static str, &'static str)>,
}

impl Toolchain {
    /// `cargo` from PATH (the rustup proxy) with the toolchain's environment, without the
    /// outer cargo's `CARGO` (cargo-fuzz would call it instead of the proxy).
    fn cargo(&self) -> Command {
        let mut c = Command::new("cargo");
        c.env_remove("CARGO").envs(self.envs.iter().copied());
        c
    }
}

fn has_nightly() -> bool {
    Command::new("rustup")
        .args(["toolchain", "list"])
        .output()
        .is_ok_and(|o| {
            String::from_utf8_lossy(&o.stdout)
                .lines()
                .any(|l| l.starts_with("nightly"))
        })
}

fn toolchain() -> Toolchain {
    if has_nightly() {
        Toolchain {
            label: "nightly",
            envs: vec![("RUSTUP_TOOLCHAIN", "nightly")],
        }
    } else {
        Toolchain {
            label: "stable with RUSTC_BOOTSTRAP=1",
            envs: vec![("RUSTC_BOOTSTRAP", "1")],
        }
    }
}

/// Installs cargo-fuzz when `cargo fuzz --version` fails.
fn ensure_cargo_fuzz(tc: &Toolchain) -> Result<(), String> {
    let runs = |tc: &Toolchain| {
        tc.cargo()
            .args(["fuzz", "--version"])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|s| s.success())
    };
    if runs(tc) {
        return Ok(());
    }
    println!("==> installing cargo-fuzz: cargo install cargo-fuzz --locked");
    let ok = Command::new("cargo")
        .env_remove("CARGO")
        .args(["install", "cargo-fuzz", "--locked"])
        .status()
        .is_ok_and(|s| s.success());
    if ok && runs(tc) {
        Ok(())
    } else {
        Err("cargo-fuzz is needed and `cargo install cargo-fuzz --locked` failed".to_owned())
    }
}

/// The cargo-fuzz flags of every build and run of `o`: debug assertions, no sanitizer, and
/// without the tracing of comparisons when asked (in a target folder of its own, so that
/// the two builds do not replace each other).
fn build_flags(o: &FuzzOptions, fuzz_dir: &Path) -> Vec<String> {
    let mut flags: Vec<String> = ["--debug-assertions", "--sanitizer", "none"]
        .map(str::to_owned)
        .into();
    if o.no_trace_compares {
        let dir = fuzz_dir.join("target").join("no-trace-compares");
        flags.extend(["--no-trace-compares".to_owned(), "--target-dir".to_owned()]);
        flags.push(dir.display().to_string());
    }
    flags.extend(["--fuzz-dir".to_owned(), fuzz_dir.display().to_string()]);
    flags
}

/// Runs `cargo xtask fuzz`.
pub(crate) fn fuzz(o: &FuzzOptions) -> Result<(), String> {
    let started = Instant::now();
    let root = root();
    let fuzz_dir = root.join("fuzz");
    let tc = toolchain();
    ensure_cargo_fuzz(&tc)?;
    println!("==> cargo fuzz build ({})", tc.label);
    let status = tc
        .cargo()
        .current_dir(&root)
        .args(["fuzz", "build"])
        .args(build_flags(o, &fuzz_dir))
        .status()
        .map_err(|e| format!("could not start cargo fuzz: {e}"))?;
    if !status.success() {
        return Err(format!("cargo fuzz build failed ({status})"));
    }
    let targets: Vec<&str> = strak_fuzz::TARGETS
        .iter()
        .map(|t| t.name)
        .filter(|t| o.target.as_deref().is_none_or(|w| w == *t))
        .collect();
    let mut results = Vec::new();
    for t in &targets {
        let r = if o.minimize {
            minimize(&tc, &fuzz_dir, t, o)?
        } else {
            run_target(&tc, &fuzz_dir, t, o)?
        };
        println!("<== {t}: {}", r.summary());
        results.push((*t, r));
    }
    println!("\nxtask fuzz ({:.0} s):", started.elapsed().as_secs_f64());
    for (t, r) in &results {
        println!("  {t:<9} {}", r.summary());
    }
    let failed: Vec<&str> = results
        .iter()
        .filter(|(_, r)| !r.ok)
        .map(|(t, _)| *t)
        .collect();
    if failed.is_empty() {
        Ok(())
    } else {
        Err(format!(
            "fuzz targets with failures: {} (inputs in fuzz/artifacts/<target>/)",
            failed.join(", ")
        ))
    }
}

/// What one run printed.
#[derive(Debug, Default)]
struct RunResult {
    ok: bool,
    executions: u64,
    per_second: u64,
    failures: u64,
    corpus: usize,
    artifacts: Vec<String>,
}

impl RunResult {
    fn summary(&self) -> String {
        let mut s = format!(
            "{} executions ({}/s), {} failing, corpus {} inputs",
            self.executions, self.per_second, self.failures, self.corpus
        );
        for a in &self.artifacts {
            s.push_str(&format!("\n             failing input: {a}"));
        }
        s
    }
}

fn count_files(dir: &Path) -> usize {
    fs::read_dir(dir).map_or(0, |d| d.filter(|e| e.is_ok()).count())
}

/// Writes the target's seeds into its working corpus.
fn write_seeds(dir: &Path, target: &str) -> Result<(), String> {
    fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    for s in strak_fuzz::seeds::all()
        .into_iter()
        .filter(|s| s.target == target)
    {
        let path = dir.join(format!("seed-{}", s.name));
        fs::write(&path, &s.bytes).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    }
    Ok(())
}

/// The arguments libFuzzer gets for a run of `o` writing its failing inputs into
/// `artifacts`.
fn libfuzzer_args(o: &FuzzOptions, artifacts: &Path) -> Vec<String> {
    let mut args: Vec<String> = vec![
        format!("-max_total_time={}", o.seconds),
        format!("-timeout={TIMEOUT_S}"),
        format!("-max_len={MAX_LEN}"),
        "-rss_limit_mb=4096".to_owned(),
        "-print_final_stats=1".to_owned(),
        format!("-artifact_prefix={}/", artifacts.display()),
    ];
    if let Some(n) = o.runs {
        args.push(format!("-runs={n}"));
    }
    if o.fork.is_some() || o.keep_going {
        args.push(format!("-fork={}", o.fork.unwrap_or(1)));
    }
    if o.keep_going {
        args.extend(
            ["-ignore_crashes=1", "-ignore_timeouts=1", "-ignore_ooms=1"].map(str::to_owned),
        );
    }
    args
}

fn run_target(
    tc: &Toolchain,
    fuzz_dir: &Path,
    t: &str,
    o: &FuzzOptions,
) -> Result<RunResult, String> {
    let work = fuzz_dir.join("work").join(t);
    let artifacts = fuzz_dir.join("artifacts").join(t);
    write_seeds(&work, t)?;
    fs::create_dir_all(&artifacts)
        .map_err(|e| format!("cannot create {}: {e}", artifacts.display()))?;
    let log = fuzz_dir.join("work").join(format!("{t}.log"));
    let limit = match (o.runs, o.seconds) {
        (Some(n), 0) => format!("{n} executions"),
        (Some(n), s) => format!("{n} executions or {s} s"),
        (None, s) => format!("{s} s"),
    };
    println!("\n==> fuzz {t} for {limit} (log: {})", log.display());
    if !o.ignore.is_empty() {
        println!("    ignoring failures containing: {}", o.ignore.join(" | "));
    }
    let args = libfuzzer_args(o, &artifacts);
    let before = count_files(&artifacts);
    let file =
        fs::File::create(&log).map_err(|e| format!("cannot create {}: {e}", log.display()))?;
    let status = tc
        .cargo()
        .current_dir(fuzz_dir.parent().unwrap_or(fuzz_dir))
        .args(["fuzz", "run"])
        .args(build_flags(o, fuzz_dir))
        .arg(t)
        .arg(&work)
        .arg(fuzz_dir.join("corpus").join(t))
        .env(strak_fuzz::IGNORE_VAR, o.ignore.join(";"))
        .arg("--")
        .args(&args)
        .stdout(Stdio::null())
        .stderr(file)
        .status()
        .map_err(|e| format!("could not start cargo fuzz run: {e}"))?;
    let text = fs::read_to_string(&log).unwrap_or_default();
    let mut r = parse_log(&text);
    r.corpus = count_files(&work);
    r.failures = r
        .failures
        .max((count_files(&artifacts) - before.min(count_files(&artifacts))) as u64);
    r.ok = status.success() && r.failures == 0;
    if !status.success() && r.failures == 0 {
        r.failures = 1;
        println!(
            "{}",
            text.lines()
                .rev()
                .take(30)
                .collect::<Vec<_>>()
                .into_iter()
                .rev()
                .collect::<Vec<_>>()
                .join("\n")
        );
    }
    Ok(r)
}

/// Executions, speed, failures and failing inputs from libFuzzer's output (the final
/// statistics, or in fork mode the last status line).
fn parse_log(text: &str) -> RunResult {
    let mut r = RunResult::default();
    for line in text.lines() {
        let number = |key: &str| {
            line.strip_prefix(key)
                .and_then(|v| v.trim().parse::<u64>().ok())
        };
        if let Some(n) = number("stat::number_of_executed_units:") {
            r.executions = r.executions.max(n);
        } else if let Some(n) = number("stat::average_exec_per_sec:") {
            r.per_second = n;
        } else if let Some(rest) = line.strip_prefix('#') {
            // fork mode: "#123456: cov: … exec/s: 789 oom/timeout/crash: 0/0/2 time: …"
            let mut words = rest.split_whitespace();
            if let Some(n) = words
                .next()
                .and_then(|w| w.trim_end_matches(':').parse::<u64>().ok())
            {
                r.executions = r.executions.max(n);
            }
            let fields: Vec<&str> = rest.split_whitespace().collect();
            for w in fields.windows(2) {
                match w[0] {
                    "exec/s:" => r.per_second = w[1].parse().unwrap_or(r.per_second),
                    "oom/timeout/crash:" => {
                        r.failures = w[1].split('/').filter_map(|x| x.parse::<u64>().ok()).sum();
                    }
                    _ => {}
                }
            }
        }
        if let Some(i) = line.find("Test unit written to ") {
            r.artifacts
                .push(line[i + "Test unit written to ".len()..].trim().to_owned());
        }
    }
    r
}

/// Merges `fuzz/work/<t>` and `fuzz/corpus/<t>` into a minimal corpus with the same
/// coverage, written into `fuzz/corpus/<t>`.
fn minimize(
    tc: &Toolchain,
    fuzz_dir: &Path,
    t: &str,
    o: &FuzzOptions,
) -> Result<RunResult, String> {
    let work = fuzz_dir.join("work").join(t);
    let corpus = fuzz_dir.join("corpus").join(t);
    let merged = fuzz_dir.join("work").join(format!("{t}-merged"));
    let _ = fs::remove_dir_all(&merged);
    for d in [&work, &corpus, &merged] {
        fs::create_dir_all(d).map_err(|e| format!("cannot create {}: {e}", d.display()))?;
    }
    println!("\n==> minimize the corpus of {t}");
    let status = tc
        .cargo()
        .current_dir(fuzz_dir.parent().unwrap_or(fuzz_dir))
        .args(["fuzz", "run"])
        .args(build_flags(o, fuzz_dir))
        .arg(t)
        .args([&merged, &corpus, &work])
        .arg("--")
        .args([
            "-merge=1",
            // Edges, not hit counts: a far smaller set with the same edge coverage.
            "-use_counters=0",
            &format!("-max_len={MAX_LEN}"),
            &format!("-timeout={TIMEOUT_S}"),
        ])
        .status()
        .map_err(|e| format!("could not start cargo fuzz run -merge=1: {e}"))?;
    if !status.success() {
        return Err(format!("merging the corpus of {t} failed ({status})"));
    }
    let _ = fs::remove_dir_all(&corpus);
    fs::rename(&merged, &corpus)
        .map_err(|e| format!("cannot replace {}: {e}", corpus.display()))?;
    Ok(RunResult {
        ok: true,
        corpus: count_files(&corpus),
        ..RunResult::default()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(a: &[&str]) -> Vec<String> {
        a.iter().map(|s| (*s).to_owned()).collect()
    }

    #[test]
    fn runs_and_time() {
        let o = parse(&args(&["blob"])).unwrap();
        assert_eq!((o.seconds, o.runs), (60, None));
        let o = parse(&args(&["--runs", "10000000", "blob"])).unwrap();
        assert_eq!((o.seconds, o.runs), (0, Some(10_000_000)));
        let o = parse(&args(&["--runs", "5", "--time", "9"])).unwrap();
        assert_eq!((o.seconds, o.runs), (9, Some(5)));
        assert!(libfuzzer_args(&o, Path::new("a")).contains(&"-runs=5".to_owned()));
        assert!(parse(&args(&["--runs", "many"])).is_err());
        assert!(parse(&args(&["--runs"])).is_err());
    }

    #[test]
    fn fork_and_trace_compares() {
        let o = parse(&args(&["--fork", "2", "--no-trace-compares", "pipeline"])).unwrap();
        assert_eq!((o.fork, o.no_trace_compares), (Some(2), true));
        let a = libfuzzer_args(&o, Path::new("a"));
        assert!(a.contains(&"-fork=2".to_owned()), "{a:?}");
        assert!(!a.iter().any(|x| x.starts_with("-ignore_crashes")), "{a:?}");
        let flags = build_flags(&o, Path::new("fuzz"));
        assert!(
            flags.contains(&"--no-trace-compares".to_owned()),
            "{flags:?}"
        );
        assert!(
            flags.contains(&"fuzz/target/no-trace-compares".to_owned()),
            "{flags:?}"
        );
        assert_eq!(flags.last().map(String::as_str), Some("fuzz"));
        let plain = parse(&args(&["--keep-going"])).unwrap();
        let a = libfuzzer_args(&plain, Path::new("a"));
        assert!(a.contains(&"-fork=1".to_owned()) && a.contains(&"-ignore_crashes=1".to_owned()));
        assert!(
            !build_flags(&plain, Path::new("fuzz")).contains(&"--no-trace-compares".to_owned())
        );
        assert!(parse(&args(&["--fork", "0"])).is_err());
        assert!(parse(&args(&["--fork"])).is_err());
    }
}
