//! `strak-sim`: the host simulator of strak.
//!
//! ```text
//! strak-sim sample CURVE.toml [--count N] [--derivatives K] [--number f64|f32|fixed] [--out FILE]
//! strak-sim run [JOB.toml] [--out DIR]      # exit 3: a planned motion exceeded a limit
//!                                           # (a `[path]` job, or `[[moves]]` streamed)
//! strak-sim compile JOB.toml --number f32|fixed|f64 --out FILE.strk
//! strak-sim move MOVE.toml [--out DIR]     # exit 3: the samples exceeded a limit
//! strak-sim gcode FILE.gcode [--machine MACHINE.toml] [--out DIR] [--every K]
//!                                           # exit 3: a limit or the tolerance exceeded
//! ```

use std::fs;
use std::io::{self, Write};
use std::path::{Path as FsPath, PathBuf};
use std::process::ExitCode;

use anyhow::Context;
use clap::{Parser, Subcommand};

use strak_sim::curve_file::CurveFile;
use strak_sim::export::export;
use strak_sim::gcode_run::run_gcode;
use strak_sim::job::Job;
use strak_sim::line::line_move;
use strak_sim::machine::{DEFAULT_MACHINE, Machine};
use strak_sim::moves::{MovesJob, is_moves_job};
use strak_sim::number::{self, NumberFormat};
use strak_sim::online_move::{MoveJob, run_move};
use strak_sim::run::{
    BUNDLED_JOB, BUNDLED_NAME, EXIT_EXCEEDED, RunOptions, exit_code, run_job, violation_lines,
};
use strak_sim::sample::{SampleOptions, sample_to_csv};
use strak_sim::stream_run::run_moves;
use strak_sim::summary::Summary;

/// Host simulator for strak: sample curves, run jobs through the firmware's sampler.
#[derive(Debug, Parser)]
#[command(name = "strak-sim", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Evaluate a curve file at evenly spaced parameters over its whole domain and write CSV
    /// (`u,x,y[,z]` then `d1x,d1y[,d1z]` … for each derivative).
    Sample {
        /// The curve file (TOML).
        curve: PathBuf,
        /// Number of parameter values, first and last of the domain included.
        #[arg(long, default_value_t = 101, value_parser = clap::value_parser!(u32).range(2..=10_000_000))]
        count: u32,
        /// Number of derivatives with respect to u to write after the point.
        #[arg(long, default_value_t = 0)]
        derivatives: usize,
        /// Number format the curve is built and evaluated in: f64, f32 or fixed (I32F32,
        /// Q31.32).
        #[arg(long, value_parser = number::parse, default_value = "f64")]
        number: NumberFormat,
        /// Output file; standard output when omitted.
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Plan, compile and play a job through the sampler firmware uses; write samples.csv,
    /// summary.json, path.svg and motion.svg, and print the summary. A job with `[[moves]]`
    /// in place of `[path]` streams its moves through the look-ahead planner, corners
    /// blended. Without JOB it runs the bundled example (a 3-axis pick-and-place move at
    /// 1 kHz with an S-curve profile).
    /// Exit code 3 (one error line per quantity) when a trapezoid or S-curve exceeds a limit
    /// it is planned under or the accuracy bound, measured from the samples.
    Run {
        /// The job file (TOML); the bundled example when omitted.
        job: Option<PathBuf>,
        /// Output folder (created if missing); default `out/<job name>`.
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Solve an online move (from any start state to a target, with new targets and quick
    /// stops at given ticks), compile it and play it through the sampler firmware uses; write
    /// samples.csv, summary.json and motion.svg, and print the summary. Exit code 3 (one
    /// error line per quantity) when a sample exceeds an axis limit.
    Move {
        /// The move file (TOML).
        file: PathBuf,
        /// Output folder (created if missing); default `out/<file name>`.
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Play a G-code program on a machine as its firmware would: read it line by line into
    /// the look-ahead stream (corners blended, G61/G64 P, G4 dwells, the axes after x y z
    /// riding along), poll and sample it each tick; write samples.csv, summary.json,
    /// path.svg and motion.svg, and print the summary. Exit code 3 (one error line per
    /// quantity) when a sample exceeds a limit or strays from the program by more than the
    /// largest corner tolerance.
    Gcode {
        /// The G-code program.
        file: PathBuf,
        /// The machine file (TOML); without it, the bundled small mill in mm (x y z, 1 kHz,
        /// f32, ε 0.02 mm).
        #[arg(long)]
        machine: Option<PathBuf>,
        /// Output folder (created if missing); default `out/<file name>`.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Write every K-th tick to samples.csv (every tick is measured).
        #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..))]
        every: u64,
    },
    /// Plan and compile a job exactly as `run` does and write the path as a blob
    /// (`Path::to_bytes`) for firmware to embed and play (`PathBlob::from_bytes`). The number format
    /// is chosen here, not by the job: `f32` (curve and playback in f32), `fixed` (curve in
    /// I32F32, playback in Q40) or `f64`.
    Compile {
        /// The job file (TOML).
        job: PathBuf,
        /// Playback number format of the blob: f32, fixed or f64.
        #[arg(long, value_parser = number::parse)]
        number: NumberFormat,
        /// The blob file to write.
        #[arg(long)]
        out: PathBuf,
    },
}

/// How a command ended without an error.
enum Outcome {
    /// Everything held.
    Done,
    /// `strak-sim run`: the planned motion failed checks: the exit code and one error line
    /// each.
    Exceeded(u8, Vec<String>),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(Outcome::Done) => ExitCode::SUCCESS,
        Ok(Outcome::Exceeded(code, lines)) => {
            for line in lines {
                eprintln!("{line}");
            }
            ExitCode::from(code)
        }
        Err(e) => {
            eprintln!("strak-sim: error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

fn run(cli: Cli) -> anyhow::Result<Outcome> {
    match cli.command {
        Command::Sample {
            curve,
            count,
            derivatives,
            number,
            out,
        } => {
            let options = SampleOptions {
                count: count as usize,
                derivatives,
                number,
            };
            sample(&curve, &options, out.as_deref())
        }
        Command::Run { job, out } => run_command(job.as_deref(), out),
        Command::Compile { job, number, out } => compile_command(&job, number, &out),
        Command::Move { file, out } => move_command(&file, out),
        Command::Gcode {
            file,
            machine,
            out,
            every,
        } => gcode_command(&file, machine.as_deref(), out, every),
    }
}

/// `strak-sim gcode`: the summary on standard output; the violations, if any, for the exit.
fn gcode_command(
    file: &FsPath,
    machine: Option<&FsPath>,
    out: Option<PathBuf>,
    every: u64,
) -> anyhow::Result<Outcome> {
    let label = file.display().to_string();
    let (machine_text, machine_label) = match machine {
        Some(path) => (
            fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))?,
            path.display().to_string(),
        ),
        None => (DEFAULT_MACHINE.to_owned(), "bundled mill.toml".to_owned()),
    };
    let machine =
        Machine::parse(&machine_text).map_err(|e| anyhow::anyhow!("{machine_label}: {e}"))?;
    let text = fs::read(file).with_context(|| format!("cannot read {label}"))?;
    let name = file
        .file_stem()
        .map_or_else(|| "gcode".to_owned(), |s| s.to_string_lossy().into_owned());
    let options = RunOptions {
        out_dir: out.unwrap_or_else(|| PathBuf::from("out").join(&name)),
        name,
        progress: true,
        velocity_factor: None,
    };
    let summary = run_gcode(&text, &label, &machine, &options, every)
        .map_err(|e| anyhow::anyhow!("{label}: {e}"))?;
    Ok(summary_outcome(&summary, &label))
}

/// `strak-sim sample`.
fn sample(
    curve: &FsPath,
    options: &SampleOptions,
    out: Option<&FsPath>,
) -> anyhow::Result<Outcome> {
    let text =
        fs::read_to_string(curve).with_context(|| format!("cannot read {}", curve.display()))?;
    let file = CurveFile::parse(&text).map_err(|e| anyhow::anyhow!("{}: {e}", curve.display()))?;
    let csv =
        sample_to_csv(&file, options).map_err(|e| anyhow::anyhow!("{}: {e}", curve.display()))?;
    match out {
        Some(path) => {
            fs::write(path, csv).with_context(|| format!("cannot write {}", path.display()))?;
        }
        None => io::stdout().lock().write_all(csv.as_bytes())?,
    }
    Ok(Outcome::Done)
}

/// `strak-sim run`: the summary on standard output; the violations, if any, for the exit.
fn run_command(job: Option<&FsPath>, out: Option<PathBuf>) -> anyhow::Result<Outcome> {
    let (name, text, label) = match job {
        Some(path) => {
            let text = fs::read_to_string(path)
                .with_context(|| format!("cannot read {}", path.display()))?;
            let name = path
                .file_stem()
                .map_or_else(|| "job".to_owned(), |s| s.to_string_lossy().into_owned());
            (name, text, path.display().to_string())
        }
        None => (
            BUNDLED_NAME.to_owned(),
            BUNDLED_JOB.to_owned(),
            format!("bundled {BUNDLED_NAME}.toml"),
        ),
    };
    let options = RunOptions {
        out_dir: out.unwrap_or_else(|| PathBuf::from("out").join(&name)),
        name,
        progress: true,
        velocity_factor: None,
    };
    if is_moves_job(&text) {
        let job = MovesJob::parse(&text).map_err(|e| anyhow::anyhow!("{label}: {e}"))?;
        let summary = run_moves(&job, &options).map_err(|e| anyhow::anyhow!("{label}: {e}"))?;
        return Ok(summary_outcome(&summary, &label));
    }
    let job = Job::parse(&text).map_err(|e| anyhow::anyhow!("{label}: {e}"))?;
    if let Some(line) = line_move(&job) {
        let line = line.map_err(|e| anyhow::anyhow!("{label}: {e}"))?;
        println!(
            "a straight line with an S-curve profile: the time-optimal online move along it, \
             at the full limits"
        );
        return move_outcome(&line, &options, &label);
    }
    let summary = run_job(&job, &options).map_err(|e| anyhow::anyhow!("{label}: {e}"))?;
    Ok(summary_outcome(&summary, &label))
}

/// Prints a run's summary (a warning when it did not finish); the violations, if any, for
/// the exit.
fn summary_outcome(summary: &Summary, label: &str) -> Outcome {
    println!("{summary}");
    if !summary.finished {
        eprintln!("strak-sim: warning: {}", summary.stop);
    }
    match exit_code(summary) {
        0 => Outcome::Done,
        code => Outcome::Exceeded(code, violation_lines(label, summary)),
    }
}

/// `strak-sim move`: the summary on standard output; the violations, if any, for the exit.
fn move_command(file: &FsPath, out: Option<PathBuf>) -> anyhow::Result<Outcome> {
    let label = file.display().to_string();
    let text = fs::read_to_string(file).with_context(|| format!("cannot read {label}"))?;
    let job = MoveJob::parse(&text).map_err(|e| anyhow::anyhow!("{label}: {e}"))?;
    let name = file
        .file_stem()
        .map_or_else(|| "move".to_owned(), |s| s.to_string_lossy().into_owned());
    let options = RunOptions {
        out_dir: out.unwrap_or_else(|| PathBuf::from("out").join(&name)),
        name,
        progress: false,
        velocity_factor: None,
    };
    move_outcome(&job, &options, &label)
}

/// Runs a move and prints its summary; the violations, if any, for the exit.
fn move_outcome(job: &MoveJob, options: &RunOptions, label: &str) -> anyhow::Result<Outcome> {
    let summary = run_move(job, options).map_err(|e| anyhow::anyhow!("{label}: {e}"))?;
    println!("{summary}");
    if summary.violations.is_empty() {
        Ok(Outcome::Done)
    } else {
        let lines = summary
            .violations
            .iter()
            .map(|v| format!("strak-sim: error: {label}: limit exceeded: {v}"))
            .collect();
        Ok(Outcome::Exceeded(EXIT_EXCEEDED, lines))
    }
}

/// `strak-sim compile`.
fn compile_command(job: &FsPath, number: NumberFormat, out: &FsPath) -> anyhow::Result<Outcome> {
    let label = job.display().to_string();
    let text = fs::read_to_string(job).with_context(|| format!("cannot read {label}"))?;
    let parsed = Job::parse(&text).map_err(|e| anyhow::anyhow!("{label}: {e}"))?;
    let compiled = export(&parsed, number).map_err(|e| anyhow::anyhow!("{label}: {e}"))?;
    fs::write(out, &compiled.blob).with_context(|| format!("cannot write {}", out.display()))?;
    println!(
        "{}: {} bytes, {} axes, {} pieces, {} ticks ({})",
        out.display(),
        compiled.blob.len(),
        compiled.axes,
        compiled.pieces,
        compiled.ticks,
        number::name(number)
    );
    Ok(Outcome::Done)
}
