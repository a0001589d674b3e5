//! strak's one entry point for checks, so that a local run is the CI run.
//!
//! ```text
//! cargo xtask bench    criterion benchmarks against the peers, then BENCHMARKS.md
//! cargo xtask test     formatting, clippy -D warnings, host tests + doctests, rustdoc,
//!                      no_std cross builds for thumbv6m-none-eabi and thumbv7em-none-eabihf,
//!                      then `qemu`
//! cargo xtask fuzz [--time SECONDS] [--runs N] [--fork JOBS] [--no-trace-compares]
//!                  [--keep-going] [--ignore FRAGMENT] [--minimize] [TARGET]
//!                      the coverage-guided fuzz targets of fuzz/ (cargo-fuzz, libFuzzer), each
//!                      for SECONDS (default 60) or N executions; executions and result
//!                      per target
//! cargo xtask qemu [--bless]
//!                      the example firmware under QEMU (Cortex-M4F and Cortex-M3), its samples
//!                      compared bit for bit with the host's; firmware sizes checked against
//!                      firmware-sim/qemu/sizes.txt, stack per operation against
//!                      firmware-sim/qemu/stack-budgets.txt, instructions per tick and of
//!                      planning and compiling under QEMU -icount against
//!                      firmware-sim/qemu/icount-budgets.txt (`--bless` rewrites all three)
//! ```
//!
//! Missing rustup targets, qemu-system-arm and defmt-print are installed; anything that cannot
//! be installed fails loudly.

mod budget;
mod compare;
mod fuzz;
mod gcode;
mod icount;
mod online;
mod qemu;
mod size;
mod stack;

use std::env;
use std::process::{Command, ExitCode};
use std::time::Instant;

/// The `no_std` crates, proven by cross builds (a host `cargo test` proves nothing about no_std).
const NO_STD_CRATES: &[&str] = &["strak-curves", "strak-trajectory", "strak-gcode"];

/// The bare-metal targets the `no_std` crates must build for: Cortex-M0+ (no FPU, no
/// hardware divide) and Cortex-M4F.
const CROSS_TARGETS: &[&str] = &["thumbv6m-none-eabi", "thumbv7em-none-eabihf"];

fn main() -> ExitCode {
    let args: Vec<String> = env::args().skip(1).collect();
    let result = match args.first().map(String::as_str) {
        Some("test") => test(),
        Some("qemu") => match args.get(1).map(String::as_str) {
            None => qemu::qemu(false),
            Some("--bless") => qemu::qemu(true),
            Some(other) => Err(format!(
                "unknown option `{other}` of qemu; try `cargo xtask help`"
            )),
        },
        Some("bench") => bench(),
        Some("fuzz") => fuzz::parse(&args[1..]).and_then(|o| fuzz::fuzz(&o)),
        Some("help") | Some("--help") | Some("-h") | None => {
            print_help();
            Ok(())
        }
        Some(other) => Err(format!("unknown task `{other}`; try `cargo xtask help`")),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("xtask: error: {message}");
            ExitCode::FAILURE
        }
    }
}

fn print_help() {
    println!("cargo xtask <task>");
    println!();
    println!("tasks:");
    println!("  test   fmt check, clippy -D warnings, host tests and doctests, rustdoc,");
    println!("         no_std cross builds (installs missing rustup targets), then qemu");
    println!("  qemu   build the example firmware (firmware-sim/qemu) for Cortex-M4F and");
    println!("         Cortex-M3, run it under QEMU, compare every sample with the host bit for");
    println!("         bit, check the firmware sizes, the stack of loading, planning and");
    println!("         compiling (measured on the core), and the instructions per tick and of");
    println!("         planning and compiling under -icount (instruction counts, not cycles;");
    println!("         installs qemu-system-arm, defmt-print)");
    println!("  qemu --bless");
    println!("         the same, rewriting firmware-sim/qemu/sizes.txt, stack-budgets.txt and");
    println!("         icount-budgets.txt");
    println!("  bench  criterion benchmarks of strak against its peers (bench/), then");
    println!("         BENCHMARKS.md from their results and the QEMU counts in target/qemu");
    println!("  fuzz [--time SECONDS] [--runs N] [--fork JOBS] [--no-trace-compares]");
    println!("       [--keep-going] [--ignore FRAGMENT] [--minimize] [TARGET]");
    println!("         the fuzz targets of fuzz/ (blob, curves, pipeline, job), each for");
    println!("         SECONDS (default 60) or N executions, with libFuzzer through cargo-fuzz");
    println!("         (installed when missing; nightly, or stable with RUSTC_BOOTSTRAP=1);");
    println!("         prints executions and failures. --fork runs JOBS libFuzzer processes");
    println!("         as one run (fork mode); --no-trace-compares builds without the tracing");
    println!("         of integer comparisons (twice as fast for pipeline and curves);");
    println!("         --keep-going goes on after a failure;");
    println!("         --ignore masks the failures whose message contains FRAGMENT (known ones);");
    println!("         --minimize merges the working corpus into fuzz/corpus/. The checked-in");
    println!("         corpora are replayed by `cargo test` (tests/tests/fuzz_replay.rs)");
}

/// `cargo xtask bench`: the host benchmarks (one criterion run, peers included) and the
/// report. The Cortex-M section of the report is filled from `target/qemu` when
/// `cargo xtask qemu` has written its counts there.
fn bench() -> Result<(), String> {
    let started = Instant::now();
    step(
        "benchmarks (strak and its peers)",
        &["bench", "-p", "strak-bench", "--bench", "peers"],
        &[],
    )?;
    step(
        "BENCHMARKS.md",
        &["run", "--release", "-p", "strak-bench", "--bin", "report"],
        &[],
    )?;
    println!(
        "\nxtask bench: BENCHMARKS.md written ({:.0} s)",
        started.elapsed().as_secs_f64()
    );
    Ok(())
}

/// The README's test command.
fn test() -> Result<(), String> {
    let started = Instant::now();
    ensure_targets(CROSS_TARGETS)?;

    step("format", &["fmt", "--all", "--", "--check"], &[])?;
    step(
        "clippy (host, all targets)",
        &[
            "clippy",
            "--workspace",
            "--all-targets",
            "--",
            "-D",
            "warnings",
        ],
        &[],
    )?;
    step(
        "clippy (no_std crates with defmt)",
        &[
            "clippy",
            "-p",
            "strak-curves",
            "-p",
            "strak-trajectory",
            "-p",
            "strak-gcode",
            "--features",
            "strak-curves/defmt,strak-trajectory/defmt,strak-gcode/defmt",
            "--",
            "-D",
            "warnings",
        ],
        &[],
    )?;
    step("host tests and doctests", &["test", "--workspace"], &[])?;
    step(
        "rustdoc (warnings are errors)",
        &["doc", "--workspace", "--no-deps"],
        &[("RUSTDOCFLAGS", "-D warnings")],
    )?;
    for target in CROSS_TARGETS {
        for krate in NO_STD_CRATES {
            for features in [None, Some("defmt")] {
                let mut args = vec!["build", "--release", "-p", krate, "--target", target];
                if let Some(f) = features {
                    args.extend(["--features", f]);
                }
                let label = format!(
                    "no_std build {krate} for {target}{}",
                    features.map(|f| format!(" (+{f})")).unwrap_or_default()
                );
                step(&label, &args, &[("RUSTFLAGS", "-D warnings")])?;
            }
        }
    }
    qemu::qemu(false)?;
    println!(
        "\nxtask test: all checks passed in {:.0} s",
        started.elapsed().as_secs_f64()
    );
    Ok(())
}

/// Runs `cargo ARGS` with extra environment variables, failing with the step's name.
fn step(name: &str, args: &[&str], envs: &[(&str, &str)]) -> Result<(), String> {
    println!("\n==> {name}: cargo {}", args.join(" "));
    let t = Instant::now();
    let cargo = env::var("CARGO").unwrap_or_else(|_| "cargo".to_owned());
    let status = Command::new(cargo)
        .args(args)
        .envs(envs.iter().copied())
        .status()
        .map_err(|e| format!("{name}: could not start cargo: {e}"))?;
    if status.success() {
        println!("<== {name}: ok ({:.0} s)", t.elapsed().as_secs_f64());
        Ok(())
    } else {
        Err(format!("{name} failed ({status})"))
    }
}

/// Installs the rustup targets that are missing; fails loudly when rustup cannot.
pub(crate) fn ensure_targets(targets: &[&str]) -> Result<(), String> {
    let output = Command::new("rustup")
        .args(["target", "list", "--installed"])
        .output()
        .map_err(|e| format!("rustup is needed to install cross targets but could not run: {e}"))?;
    if !output.status.success() {
        return Err("`rustup target list --installed` failed".to_owned());
    }
    let installed = String::from_utf8_lossy(&output.stdout);
    let missing: Vec<&str> = targets
        .iter()
        .copied()
        .filter(|t| !installed.lines().any(|l| l.trim() == *t))
        .collect();
    if missing.is_empty() {
        return Ok(());
    }
    println!("==> installing rustup targets: {}", missing.join(" "));
    let status = Command::new("rustup")
        .args(["target", "add"])
        .args(&missing)
        .status()
        .map_err(|e| format!("could not run rustup target add: {e}"))?;
    if status.success() {
        Ok(())
    } else {
        Err(format!("rustup target add {} failed", missing.join(" ")))
    }
}
