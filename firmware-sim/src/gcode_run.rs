//! `strak-sim gcode`: a G-code program played on a machine ([`Machine`]) as its firmware
//! would play it.
//!
//! 1. **Read ahead** the whole program once with [`Reader`] for the measurement: its moves
//!    (the path the samples are measured against), its dwells, its ignored codes and the
//!    largest corner tolerance it asks for. A bad line ends the run with an error naming the
//!    line and column.
//! 2. **Stream** it as firmware's main loop does ([`Program`]): each tick, read the next
//!    lines while the moves they hold have arrived (all at once, or with `[produce]` one
//!    every `rate_hz / moves_per_second` ticks, a dwell counting as a move) and the
//!    [`Stream`] takes their blocks (`G61`/`G64 P` set its corner tolerance, `G4` its
//!    dwells; the machine's axes after `x y z` ride along), finish the stream after the
//!    last line, poll it into the piece queue and play one sample ([`crate::stream_run`]'s
//!    loop, shared with the moves jobs).
//! 3. **Measure and report** as a moves job: limits from the samples (path norms over the
//!    path axes, each axis against its own limits), the distance from the programmed moves
//!    against the largest tolerance, the end point; `samples.csv` (every `every`-th tick),
//!    `summary.json`, `path.svg` (blended corners and stops marked) and `motion.svg`.

use std::io::IsTerminal;
use std::time::Instant;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use strak_gcode::{Action, GcodeError, PathMode, Program, Reader, Step};
use strak_trajectory::{Kernel, Move, NoCurve, Q40, Sample, Stream};

use crate::machine::Machine;
use crate::number::NumberFormat;
use crate::plot::PathMarks;
use crate::programmed::Programmed;
use crate::run::{CsvCell, RunError, RunOptions};
use crate::stream_run::{
    CornerKind, Corners, Feed, Recording, Sink, StreamSetup, create_out_dir, drive, guard_ticks,
    skip_length, summarize, write_plots, write_summary,
};
use crate::summary::{GcodeReport, IgnoredCode, Summary};

/// Programs of at least this many bytes show a progress bar (on a terminal).
pub const PROGRESS_MIN_BYTES: usize = 256 * 1024;

/// The most blended corners and stops the path plot marks (evenly chosen among them).
pub const MAX_MARKS: usize = 2_000;

/// What the program holds, read ahead for the measurement and the report.
#[derive(Clone, Debug)]
struct Contents<const D: usize> {
    moves: Vec<Move<D>>,
    dwells: usize,
    dwell_s: f64,
    lines: u32,
    /// The largest corner tolerance the program blends with.
    tolerance: f64,
    ignored: Vec<IgnoredCode>,
    ignored_others: u32,
    read_s: f64,
}

/// A line's error as the run's.
fn line_error(e: &GcodeError) -> RunError {
    RunError::Program(e.to_string())
}

/// A reader of the machine's axes and arc tolerance.
fn reader<const D: usize>(machine: &Machine) -> Result<Reader<D>, RunError> {
    Ok(Reader::new(machine.letters::<D>())
        .map_err(|e| line_error(&e))?
        .with_arc_tolerance(machine.arc_tolerance))
}

/// Reads the whole program.
fn read_program<const D: usize>(text: &[u8], machine: &Machine) -> Result<Contents<D>, RunError> {
    let started = Instant::now();
    let mut r = reader::<D>(machine)?;
    let mut p = Contents {
        moves: Vec::new(),
        dwells: 0,
        dwell_s: 0.0,
        lines: 0,
        tolerance: machine.tolerance,
        ignored: Vec::new(),
        ignored_others: 0,
        read_s: 0.0,
    };
    for line in strak_gcode::lines(text) {
        let block = r.read_line(line).map_err(|e| line_error(&e))?;
        if let Some(PathMode::Blend(Some(t))) = block.path_mode {
            p.tolerance = p.tolerance.max(t);
        }
        match block.action {
            Action::Move(m) => p.moves.push(m),
            Action::Dwell(s) => {
                p.dwells += 1;
                p.dwell_s += s;
            }
            Action::None => {}
        }
    }
    p.lines = r.lines();
    p.ignored = r
        .ignored()
        .kinds()
        .iter()
        .map(|(code, count)| IgnoredCode {
            code: code.to_string(),
            count: *count,
        })
        .collect();
    p.ignored_others = r.ignored().others();
    p.read_s = started.elapsed().as_secs_f64();
    Ok(p)
}

/// The program handed to the stream as its moves arrive ([`Program`], as a firmware's main
/// loop hands it), with the corners noted and the progress shown.
struct GcodeFeed<'t, const D: usize> {
    program: Program<'t, D>,
    corners: Corners,
    progress: Option<(ProgressBar, usize)>,
}

impl<'t, const D: usize> GcodeFeed<'t, D> {
    /// The lines of `text` for `machine`.
    fn new(
        text: &'t [u8],
        machine: &Machine,
        progress: Option<(ProgressBar, usize)>,
    ) -> Result<Self, RunError> {
        Ok(GcodeFeed {
            program: Program::new(text, reader::<D>(machine)?, machine.tolerance),
            corners: Corners::default(),
            progress,
        })
    }

    fn show_progress(&mut self) {
        if let Some((bar, lines)) = &mut self.progress {
            let read = self.program.reader().lines() as usize;
            if read >= *lines + 256 {
                *lines = read;
                bar.set_position(read as u64);
            }
            if self.program.is_finished() {
                bar.finish_and_clear();
            }
        }
    }
}

impl<const D: usize> Feed<D> for GcodeFeed<'_, D> {
    fn push_arrived<const Q: usize, const Z: usize, const R: usize>(
        &mut self,
        stream: &mut Stream<D, Q, Z, NoCurve<D>, R>,
        arrived: usize,
    ) -> Result<(), RunError> {
        loop {
            let before = stream.stats();
            let step = self
                .program
                .step(stream, arrived)
                .map_err(|e| RunError::Program(e.to_string()))?;
            match step {
                Step::Handed { moved } => {
                    if moved {
                        self.corners.pushed(&before, &stream.stats());
                    }
                }
                _ => break,
            }
        }
        self.show_progress();
        Ok(())
    }

    fn is_finished(&self) -> bool {
        self.program.is_finished()
    }

    fn corners(&mut self) -> Vec<CornerKind> {
        core::mem::take(&mut self.corners.kinds)
    }
}

/// A progress bar over the program's lines, for a long program on a terminal.
fn progress_bar(show: bool, bytes: usize, lines: u32) -> Option<(ProgressBar, usize)> {
    if !(show && std::io::stderr().is_terminal() && bytes >= PROGRESS_MIN_BYTES) {
        return None;
    }
    let bar = ProgressBar::with_draw_target(Some(u64::from(lines)), ProgressDrawTarget::stderr());
    if let Ok(style) = ProgressStyle::with_template(
        "{spinner} reading, planning and playing {bar:40} {pos}/{len} lines, {eta} left",
    ) {
        bar.set_style(style);
    }
    Some((bar, 0))
}

/// Plays the G-code `text` (read from `file`) on `machine`: writes `samples.csv` (every
/// `every`-th tick), `summary.json`, `path.svg` and `motion.svg` into `options.out_dir`,
/// and returns the summary (its [`Summary::violations`] name the checks the run failed).
///
/// # Errors
/// [`RunError::Program`] naming the line and column of a bad line, or the line whose block
/// the stream refused; [`RunError::Job`] for a machine the stream cannot play;
/// [`RunError::Io`] when the output cannot be written.
pub fn run_gcode(
    text: &[u8],
    file: &str,
    machine: &Machine,
    options: &RunOptions,
    every: u64,
) -> Result<Summary, RunError> {
    let axes = || -> RunError {
        crate::job::JobError::new("axes", "path axes 1 to 3, riding axes 0 to 3").into()
    };
    let input = Input {
        text,
        file,
        machine,
        options,
        every,
    };
    match machine.number {
        NumberFormat::F64 => {
            crate::with_machine_axes!(machine, run_typed::<f64>(&input), Err(axes()))
        }
        NumberFormat::F32 => {
            crate::with_machine_axes!(machine, run_typed::<f32>(&input), Err(axes()))
        }
        NumberFormat::Q40 => {
            crate::with_machine_axes!(machine, run_typed::<Q40>(&input), Err(axes()))
        }
    }
}

/// What a run plays and where it writes.
struct Input<'a> {
    text: &'a [u8],
    file: &'a str,
    machine: &'a Machine,
    options: &'a RunOptions,
    every: u64,
}

fn run_typed<N, const D: usize, const R: usize>(input: &Input<'_>) -> Result<Summary, RunError>
where
    N: Kernel,
    N::Out: CsvCell,
{
    let started = Instant::now();
    let (machine, options) = (input.machine, input.options);
    let setup = machine.setup();
    let program = read_program::<D>(input.text, machine)?;
    let start = [0.0; D];
    let programmed = Programmed::new(start, &program.moves, setup.arc_tolerance)
        .with_skip(skip_length(&setup, program.tolerance));
    let guard = guard_ticks(&setup, &program.moves, programmed.length, program.dwell_s);
    create_out_dir(options)?;
    let mut rec = Recording::new(&setup, programmed, options, (guard / 20, input.every))?;
    let mut sink = |s: &Sample<N::Out, D>| rec.push(s, None);
    let progress = progress_bar(options.progress, input.text.len(), program.lines);
    let mut feed = GcodeFeed::<D>::new(input.text, machine, progress)?;
    let driven = crate::by_queue!(
        setup,
        drive::<N, _, D, R>(&setup, start, &mut feed, guard, &mut sink)
    )?;
    rec.flush()?;
    let play_s = started.elapsed().as_secs_f64();
    let mut summary = summarize::<N, D>(&setup, options, &driven, (&rec, program.tolerance));
    summary.gcode = Some(report(
        input,
        &setup,
        &program,
        driven.planning.as_secs_f64(),
    ));
    summary.wall_time.plan_s = driven.planning.as_secs_f64();
    summary.wall_time.play_s = play_s - summary.wall_time.plan_s;
    let plots = Instant::now();
    let marks = marks(&program.moves, &driven.corners);
    write_plots(&setup, options, &summary, &rec.recorder, &marks)?;
    summary.wall_time.plots_s = plots.elapsed().as_secs_f64();
    summary.wall_time.total_s = started.elapsed().as_secs_f64();
    write_summary(options, &summary)?;
    Ok(summary)
}

/// The program's part of the summary.
fn report<const D: usize>(
    input: &Input<'_>,
    setup: &StreamSetup,
    program: &Contents<D>,
    planning_s: f64,
) -> GcodeReport {
    GcodeReport {
        file: input.file.to_owned(),
        bytes: input.text.len(),
        lines: program.lines,
        moves: program.moves.len(),
        dwells: program.dwells,
        dwell_s: program.dwell_s,
        riding_axes: setup.axis_names[setup.path_axes..].to_vec(),
        ignored: program.ignored.clone(),
        ignored_others: program.ignored_others,
        read_s: program.read_s,
        planned_moves_per_s: program.moves.len() as f64 / planning_s.max(1e-9),
    }
}

/// The path plot's marks: the corners blended and those where the motion stopped (at most
/// [`MAX_MARKS`] of each, evenly chosen).
fn marks<const D: usize>(moves: &[Move<D>], corners: &[CornerKind]) -> PathMarks {
    let at = |kinds: &[CornerKind]| -> Vec<Vec<f64>> {
        let all: Vec<usize> = (0..corners.len())
            .filter(|&i| kinds.contains(&corners[i]))
            .collect();
        let step = all.len().div_ceil(MAX_MARKS).max(1);
        all.iter()
            .step_by(step)
            .filter_map(|&i| moves.get(i).map(|m| m.to.to_vec()))
            .collect()
    };
    PathMarks {
        blends: Vec::new(),
        corners: at(&[CornerKind::Blended]),
        stops: at(&[CornerKind::Stop, CornerKind::Starved]),
    }
}

/// The samples of `text` played on `machine` as `strak-sim gcode` plays them (the same
/// reading, arrival schedule, stream and sampler), handed to `sink` one by one; returns
/// the ticks played. For comparing a firmware's samples with the host's.
///
/// # Errors
/// As [`run_gcode`].
pub fn gcode_samples<N: Kernel, const D: usize, const R: usize>(
    text: &[u8],
    machine: &Machine,
    sink: &mut Sink<'_, N::Out, D>,
) -> Result<u64, RunError> {
    let setup = machine.setup();
    let program = read_program::<D>(text, machine)?;
    let length = Programmed::new([0.0; D], &program.moves, setup.arc_tolerance).length;
    let guard = guard_ticks(&setup, &program.moves, length, program.dwell_s);
    let mut feed = GcodeFeed::<D>::new(text, machine, None)?;
    let mut samples = 0u64;
    let mut counted = |s: &Sample<N::Out, D>| {
        samples += 1;
        sink(s)
    };
    let driven = crate::by_queue!(
        setup,
        drive::<N, _, D, R>(&setup, [0.0; D], &mut feed, guard, &mut counted)
    )?;
    if !driven.finished {
        return Err(RunError::Program(format!(
            "the program did not end within {guard} ticks"
        )));
    }
    Ok(samples)
}
