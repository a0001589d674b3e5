//! Stack, RAM and instructions of the firmware's larger operations, measured on the core:
//! the stack by painting ([`strak_qemu::stack`]), the instructions with SysTick under QEMU
//! `-icount` ([`WideCounter`]; **instruction counts, not cycles**).
//!
//! Operations, on the Cortex-M4F (`thumbv7em-none-eabihf`, `mps2-an386`) and the Cortex-M3
//! (`thumbv7m-none-eabi`, `mps2-an385`):
//! - validating the bundled pick-and-place blob and playing it to its end
//!   ([`play_blob`], the pieces read in place from flash): fixed-point on both cores, `f32`
//!   on the Cortex-M4F;
//! - planning ([`planning::plan`]) and compiling ([`planning::compile_plan`]) the
//!   16-control-point cubic B-spline job into a `Path<_, 3, 256>`: `f32` on the Cortex-M4F,
//!   the `I32F32` curve into a `Q40` path on the Cortex-M3;
//! - solving online moves ([`OnlineMove::solve_in_place`], the benchmark's random 3-axis
//!   moves on a 1 kHz grid) and compiling them ([`compile_move_into`]) into a
//!   `Path<_, 3, 256>`: the `f32` solver and `f32` path on the Cortex-M4F, the `f64`
//!   solver and `Q40` path on the Cortex-M3 (the pairs `strak-sim move` plays);
//! - streaming a dense polyline ([`streaming::run`]: 80 chords of 0.2 mm pushed into a
//!   `Stream<3, 64, 128>`, polled into a queue of 32 pieces and played by a
//!   `StreamSampler`, all in the measured frame): `f32` pieces on the Cortex-M4F, `Q40` on
//!   the Cortex-M3, the stack with the stream, queue and sampler, and the instructions per
//!   move (its push and the polls until the next move is taken);
//! - planning and playing the same B-spline through a stream instead
//!   ([`streaming::run_curve`]: one move of a `Stream<3, 8, 64, _>`, its pieces passing
//!   through the window as they are played): the stack with the stream, queue and sampler,
//!   and the instructions of the whole run.
//! - streaming the first bundled G-code program ([`gcode::run`]: its text read line by
//!   line from flash by a `Program` as its moves arrive, slowly enough that the stream
//!   comes to rest for want of the next, into the stream of the G-code firmware, polled
//!   into its piece queue and played by a `StreamSampler`, all in the measured frame):
//!   `f32` pieces on the Cortex-M4F, `Q40` on the Cortex-M3, the stack with the stream,
//!   queue, sampler and program, and the instructions per feed that read a move or dwell,
//!   per poll that compiled ticks, and of all of them per move or dwell; every sample is
//!   hashed and the hash checked against the host's.
//!
//! This firmware keeps the large RAM of `memory/boards.x` (4 MiB) and reports the RAM each
//! operation needs.
//!
//! # Output protocol (defmt, read by `cargo xtask qemu`)
//! ```text
//! CAL <empty> <nops> <nop64>          the counter's calibration (as the icount firmware's)
//! SIZE <value> <bytes>                size_of of a planning or playback value
//! STACK <operation> <stack> <ram>     stack high-water mark and RAM needed, in bytes
//! H <job> <format> <samples> <hash>   a blob or G-code program played: its samples and
//!                                     their hash
//! C <operation> <pieces> <ticks>      the path compiled on the device
//! I <case> <min> <median> <max> <calls> <worst>
//!                                     instructions of calls: the least, median and most,
//!                                     the calls, the first that took the most
//! STACKS <n>                          the number of STACK lines
//! DONE <cases>                        the number of I lines
//! ```

#![no_std]
#![no_main]
#![deny(unsafe_code)]

use cortex_m_rt::{ExceptionFrame, entry, exception};
use strak_curves::{BSpline, I32F32, ParamCurve, Point, Scalar};
use strak_gcode::Program;
use strak_qemu::costs::Costs;
use strak_qemu::counter::{Calibration, WideCounter};
use strak_qemu::gcode::{self, GcodeCosts, GcodeFailure, GcodeRun, GcodeStream};
use strak_qemu::jobs::{
    GCODE_JOBS, GCODE_SEGMENTS, GCODE_ZONES, GcodeJob, NumberFormat, find_blob,
};
use strak_qemu::online::cases::{BENCH_SEED, OnlineCase, online_cases};
use strak_qemu::planning::{self, Curve, Plan};
use strak_qemu::play::{OutBits, Played, fold_sample, play_blob};
use strak_qemu::stack::{self, Usage};
use strak_qemu::streaming::{self, StreamCosts};
use strak_qemu::{PIECES, STACK_JOB, exit_failure, exit_success};
use strak_trajectory::{
    Kernel, MoveOptions, Number, OnlineMove, Path, PathBlob, PathTiming, Piece, Q40, Real, Sample,
    Sampler, StreamSampler, compile_move_into,
};

/// The online moves whose solve and compile the stack is measured over (each measurement
/// paints the whole stack below it).
const STACK_MOVES: usize = 32;

/// Counts of the report lines.
#[derive(Default)]
struct Lines {
    stacks: u32,
    cases: u32,
}

/// The stack and instruction cases of planning, compiling, and of both.
#[cfg(target_abi = "eabihf")]
const PLAN_NAMES: [&str; 3] = [
    "plan-bspline16-f32",
    "compile-bspline16-f32",
    "plan-compile-bspline16-f32",
];
/// The stack and instruction cases of planning, compiling, and of both.
#[cfg(not(target_abi = "eabihf"))]
const PLAN_NAMES: [&str; 3] = [
    "plan-bspline16-i32f32",
    "compile-bspline16-q40",
    "plan-compile-bspline16-q40",
];

#[entry]
fn main() -> ! {
    let Some(p) = cortex_m::Peripherals::take() else {
        exit_failure()
    };
    sizes();
    // The stack first, with SysTick and its exception off: no exception frame lands in a
    // measurement.
    let mut lines = Lines::default();
    let gcode_played = stacks(&mut lines);
    defmt::println!("STACKS {=u32}", lines.stacks);

    let counter = WideCounter::start(p.SYST);
    let cal = counter.calibrate();
    let check = counter.check_nop64(&cal);
    defmt::println!("CAL {=u32} {=u32} {=u64}", cal.empty, cal.nops, check);
    counts(&counter, &cal, gcode_played, &mut lines);
    defmt::println!("DONE {=u32}", lines.cases);
    exit_success()
}

/// Measures the stack of every operation played on this core; returns what the G-code run
/// played, which the counted run must play again.
fn stacks(lines: &mut Lines) -> GcodePlayed {
    blob::<Q40>("load-play-q40", NumberFormat::Q40, lines);
    #[cfg(target_abi = "eabihf")]
    {
        blob::<f32>("load-play-f32", NumberFormat::F32, lines);
        plan_compile::<f32, f32>(PLAN_NAMES, lines);
        online::<f32, f32>(
            ["solve-online-f32-3axis", "compile-move-f32-3axis"],
            OnlineCase::in_f32,
            lines,
        );
        stream::<f32>("stream-f32", lines);
        stream_curve::<f32>("stream-bspline16-f32", None, lines);
        gcode_stack::<f32>("gcode-f32", NumberFormat::F32, lines)
    }
    #[cfg(not(target_abi = "eabihf"))]
    {
        plan_compile::<Q40, I32F32>(PLAN_NAMES, lines);
        online::<Q40, f64>(
            ["solve-online-f64-3axis", "compile-move-q40-3axis"],
            |c| Some(*c),
            lines,
        );
        stream::<Q40>("stream-q40", lines);
        stream_curve::<Q40>("stream-bspline16-q40", None, lines);
        gcode_stack::<Q40>("gcode-q40", NumberFormat::Q40, lines)
    }
}

/// Counts the instructions of every operation counted on this core; `gcode` is what the
/// G-code run played when its stack was measured.
fn counts(counter: &WideCounter, cal: &Calibration, gcode: GcodePlayed, lines: &mut Lines) {
    #[cfg(target_abi = "eabihf")]
    {
        count_plan_compile::<f32, f32>(PLAN_NAMES, counter, cal, lines);
        count_stream::<f32>(
            ["stream-push-f32", "stream-poll-f32", "stream-move-f32"],
            counter,
            cal,
            lines,
        );
        stream_curve::<f32>("stream-bspline16-f32", Some((counter, cal)), lines);
        let names = ["gcode-feed-f32", "gcode-poll-f32", "gcode-move-f32"];
        count_gcode::<f32>(names, gcode, counter, cal, lines);
    }
    #[cfg(not(target_abi = "eabihf"))]
    {
        count_plan_compile::<Q40, I32F32>(PLAN_NAMES, counter, cal, lines);
        count_stream::<Q40>(
            ["stream-push-q40", "stream-poll-q40", "stream-move-q40"],
            counter,
            cal,
            lines,
        );
        stream_curve::<Q40>("stream-bspline16-q40", Some((counter, cal)), lines);
        let names = ["gcode-feed-q40", "gcode-poll-q40", "gcode-move-q40"];
        count_gcode::<Q40>(names, gcode, counter, cal, lines);
    }
}

fn size<T>(name: &str) {
    defmt::println!("SIZE {=str} {=usize}", name, core::mem::size_of::<T>());
}

/// The sizes of the values of planning, playback and streaming.
fn sizes() {
    type Plan<S> = PathTiming<'static, Curve<S>, { planning::TABLE }, { planning::ZONES }>;
    size::<Curve<f32>>("BSpline<[f32;3],16,20>");
    size::<Curve<I32F32>>("BSpline<[I32F32;3],16,20>");
    size::<Plan<f32>>("PathTiming<BSpline<[f32;3],16,20>,256,64>");
    size::<Plan<I32F32>>("PathTiming<BSpline<[I32F32;3],16,20>,256,64>");
    size::<Path<f32, 3, PIECES>>("Path<f32,3,256>");
    size::<Path<Q40, 3, PIECES>>("Path<Q40,3,256>");
    size::<PathBlob<'static, f32, 3>>("PathBlob<f32,3>");
    size::<PathBlob<'static, Q40, 3>>("PathBlob<Q40,3>");
    size::<Sampler<'static, f32, 3>>("Sampler<f32,3>");
    size::<Sampler<'static, Q40, 3>>("Sampler<Q40,3>");
    size::<BSpline<[f64; 3], 16, 24>>("BSpline<[f64;3],16,24>");
    size::<OnlineMove<f32, 3>>("OnlineMove<f32,3>");
    size::<OnlineMove<f64, 3>>("OnlineMove<f64,3>");
    size::<streaming::DeviceStream>("Stream<3,64,128>");
    size::<streaming::CurveStream<'static>>("Stream<3,8,64,&BSpline<[f64;3],16,20>>");
    size::<StreamSampler<'static, f32, 3>>("StreamSampler<f32,3>");
    size::<StreamSampler<'static, Q40, 3>>("StreamSampler<Q40,3>");
    size::<Piece<f32, 3>>("Piece<f32,3>");
    size::<Piece<Q40, 3>>("Piece<Q40,3>");
    defmt::println!(
        "SIZE Stream<3,{=usize},{=usize},NoCurve<3>> {=usize}",
        GCODE_SEGMENTS,
        GCODE_ZONES,
        core::mem::size_of::<GcodeStream>()
    );
    size::<Program<'static, 3>>("Program<3>");
}

/// Validates and plays the bundled blob of [`STACK_JOB`] in `N` from flash, logging its stack
/// and its stream's hash.
#[inline(never)]
fn blob<N: Kernel>(name: &str, format: NumberFormat, lines: &mut Lines)
where
    N::Out: OutBits,
{
    let Some(job) = find_blob(STACK_JOB, format, 3) else {
        defmt::error!(
            "{=str}: no 3-axis {=str} blob bundled",
            STACK_JOB,
            format.name()
        );
        exit_failure()
    };
    let (played, used) = stack::usage(|| play_blob::<N, 3>(job.blob, job.events));
    let played: Played = match played {
        Ok(p) => p,
        Err(e) => {
            defmt::error!("{=str}: the blob does not play: {}", name, e);
            exit_failure()
        }
    };
    stack::log(name, used);
    lines.stacks += 1;
    defmt::println!(
        "H {=str} {=str} {=u32} {=u64}",
        job.name,
        format.name(),
        played.samples,
        played.hash
    );
}

/// Plans and compiles the job with the curve in `S` and the path in `N`, logging the stack of
/// each stage (`names`: plan, compile, and a third unused here). The plan and the path are
/// values of this frame, written in place by each stage: what a stage's stack counts is its
/// own work beyond the values it writes.
#[inline(never)]
fn plan_compile<N: Number, S: Scalar>(names: [&str; 3], lines: &mut Lines)
where
    [S; 3]: Point<Scalar = S>,
{
    let curve = ok_or_fail(names[0], planning::curve::<S>());
    let mut plan = Plan::<S>::empty(&curve);
    let (planned, used) = stack::usage(|| planning::plan(&mut plan));
    ok_or_fail(names[0], planned);
    stack::log(names[0], used);
    let mut path = Path::<N, 3, PIECES>::new();
    let (compiled, used) = stack::usage(|| planning::compile_plan::<N, S>(&plan, &mut path));
    ok_or_fail(names[1], compiled);
    stack::log(names[1], used);
    lines.stacks += 2;
    defmt::println!(
        "C {=str} {=usize} {=u32}",
        names[1],
        path.pieces().len(),
        path.ticks()
    );
}

/// Solves the first [`STACK_MOVES`] of the benchmark's random 3-axis moves in `R` (`narrow`
/// makes them from the `f64` moves) on a 1 kHz grid, each in place into one move of this
/// frame, and compiles each into one path of this frame in `N`, measuring every solve and
/// every compile; logs the deepest of each (`names`: solve, compile).
#[inline(never)]
fn online<N: Number, R: Real>(
    names: [&str; 2],
    narrow: impl Fn(&OnlineCase<f64, 3>) -> Option<OnlineCase<R, 3>>,
    lines: &mut Lines,
) {
    let options = MoveOptions::new().with_rate(1_000.0);
    let mut m = OnlineMove::<R, 3>::new();
    let mut path = Path::<N, 3, PIECES>::new();
    let deepest =
        |a: Option<Usage>, b: Usage| Some(a.map_or(b, |a| if b.stack > a.stack { b } else { a }));
    let (mut solve, mut compile) = (None, None);
    for c in online_cases::<3>(BENCH_SEED, false).take(STACK_MOVES) {
        let Some(c) = narrow(&c) else {
            defmt::error!("{=str}: a move does not convert", names[0]);
            exit_failure()
        };
        let (solved, used) =
            stack::usage(|| m.solve_in_place(&c.start, &c.target, &c.limits, &options));
        ok_or_fail(names[0], solved);
        solve = deepest(solve, used);
        let (compiled, used) = stack::usage(|| compile_move_into(&m, &mut path));
        ok_or_fail(names[1], compiled);
        compile = deepest(compile, used);
    }
    for (name, used) in names.iter().zip([solve, compile]) {
        if let Some(used) = used {
            stack::log(name, used);
            lines.stacks += 1;
        }
    }
}

/// Counts the instructions of planning and of compiling the job, and of both (`names`: plan,
/// compile, both).
#[inline(never)]
fn count_plan_compile<N: Number, S: Scalar>(
    names: [&str; 3],
    counter: &WideCounter,
    cal: &Calibration,
    lines: &mut Lines,
) where
    [S; 3]: Point<Scalar = S>,
{
    let curve = ok_or_fail(names[0], planning::curve::<S>());
    let mut plan = Plan::<S>::empty(&curve);
    let (c, planned) = counter.counts(|| planning::plan(&mut plan));
    let plan_instructions = cal.instructions_wide(c);
    ok_or_fail(names[0], planned);
    let mut path = Path::<N, 3, PIECES>::new();
    let (c, compiled) = counter.counts(|| planning::compile_plan::<N, S>(&plan, &mut path));
    let compile_instructions = cal.instructions_wide(c);
    ok_or_fail(names[1], compiled);
    instructions(names[0], plan_instructions);
    instructions(names[1], compile_instructions);
    instructions(names[2], plan_instructions + compile_instructions);
    lines.cases += 3;
}

/// Streams the dense polyline with pieces in `N` ([`streaming::run`]), logging the stack of
/// the whole run (the stream, the queue and the sampler are values of its frame).
#[inline(never)]
fn stream<N: Kernel>(name: &str, lines: &mut Lines) {
    let (streamed, used) = stack::usage(|| streaming::run::<N>(None));
    let streamed = ok_or_fail(name, streamed);
    check_streamed(name, &streamed);
    stack::log(name, used);
    lines.stacks += 1;
}

/// Plans and plays the whole B-spline of the plan cases through a stream with pieces in `N`
/// ([`streaming::run_curve`]): without a counter, logs the stack of the whole run (the
/// stream, the queue and the sampler are values of its frame); with one, the instructions
/// of the whole run. Fails unless it ends on the curve's end without an underrun.
#[inline(never)]
fn stream_curve<N: Kernel>(
    name: &str,
    counter: Option<(&WideCounter, &Calibration)>,
    lines: &mut Lines,
) {
    let mut costs = counter.map(|(counter, cal)| StreamCosts::new(counter, cal));
    let (streamed, used) = stack::usage(|| streaming::run_curve::<N>(costs.as_mut()));
    let streamed = ok_or_fail(name, streamed);
    let curve = ok_or_fail(name, planning::curve::<f64>());
    check_ends(name, &streamed, curve.eval(1.0));
    if let Some(costs) = costs {
        instructions(name, costs.total);
        lines.cases += 1;
    } else {
        stack::log(name, used);
        lines.stacks += 1;
    }
}

/// Fails the run unless the stream ended on the last chord's end without an underrun.
fn check_streamed(name: &str, streamed: &streaming::Streamed) {
    check_ends(name, streamed, streaming::chord(streaming::CHORDS - 1).to);
}

/// Fails the run unless the stream ended on `end` without an underrun.
fn check_ends(name: &str, streamed: &streaming::Streamed, end: [f64; 3]) {
    let off = (0..3).fold(0.0_f64, |m, i| m.max((streamed.end[i] - end[i]).abs()));
    if off > 1e-5 || streamed.underruns > 0 {
        defmt::error!(
            "{=str}: ends {=f64} from the last move, {=u32} underruns",
            name,
            off,
            streamed.underruns
        );
        exit_failure()
    }
}

/// Counts the instructions of streaming the dense polyline with pieces in `N` (`names`: per
/// push that took a move, per poll that compiled ticks, and the whole run per move).
#[inline(never)]
fn count_stream<N: Kernel>(
    names: [&str; 3],
    counter: &WideCounter,
    cal: &Calibration,
    lines: &mut Lines,
) {
    let mut costs = StreamCosts::new(counter, cal);
    let streamed = ok_or_fail(names[0], streaming::run::<N>(Some(&mut costs)));
    check_streamed(names[0], &streamed);
    log_costs(names, &mut costs, streaming::CHORDS, lines);
}

/// What a G-code run played: its report and every sample folded into a hash
/// ([`fold_sample`]).
#[derive(Clone, Copy, PartialEq, Eq)]
struct GcodePlayed {
    run: GcodeRun,
    hash: u64,
}

/// The first bundled G-code job, or a failed run.
fn gcode_job(name: &str) -> &'static GcodeJob<3> {
    let Some(job) = GCODE_JOBS.first() else {
        defmt::error!("{=str}: no G-code job bundled", name);
        exit_failure()
    };
    job
}

/// What a G-code run played, `hash` its samples folded; fails the run unless it finished
/// (the program read, the stream idle, the sampler at its end) and the sampler never held
/// mid-motion: the job's moves arrive slowly enough that the stream comes to rest for want
/// of the next, which is no underrun.
fn checked_gcode(name: &str, run: Result<GcodeRun, GcodeFailure>, hash: u64) -> GcodePlayed {
    let run = ok_or_fail(name, run);
    if run.underruns > 0 {
        defmt::error!("{=str}: {=u32} underruns", name, run.underruns);
        exit_failure()
    }
    GcodePlayed { run, hash }
}

/// Streams the first G-code job with pieces in `N` ([`gcode::run`]), every sample folded
/// into a hash, logging the stack of the whole run (the stream, the queue, the sampler and
/// the program are values of its frame) and what it played (an `H` line, checked against
/// the host's samples); returns that.
#[inline(never)]
fn gcode_stack<N: Kernel>(name: &str, format: NumberFormat, lines: &mut Lines) -> GcodePlayed
where
    N::Out: OutBits,
{
    let job = gcode_job(name);
    let mut hash = 0;
    let mut sink = |_: u32, s: &Sample<N::Out, 3>| hash = fold_sample(hash, s);
    let (run, used) = stack::usage(|| gcode::run::<N>(job, None, &mut sink));
    let played = checked_gcode(name, run, hash);
    stack::log(name, used);
    lines.stacks += 1;
    defmt::println!(
        "H {=str} {=str} {=u32} {=u64}",
        job.name,
        format.name(),
        played.run.samples,
        played.hash
    );
    played
}

/// Counts the instructions of streaming the first G-code job with pieces in `N` (`names`:
/// per feed that read a move or dwell, per poll that compiled ticks, and the whole run's
/// feeds and polls per move or dwell); fails the run unless it plays what the run of
/// [`gcode_stack`] played (`played`).
#[inline(never)]
fn count_gcode<N: Kernel>(
    names: [&str; 3],
    played: GcodePlayed,
    counter: &WideCounter,
    cal: &Calibration,
    lines: &mut Lines,
) where
    N::Out: OutBits,
{
    let job = gcode_job(names[0]);
    let mut costs = GcodeCosts::new(counter, cal);
    let mut hash = 0;
    let mut sink = |_: u32, s: &Sample<N::Out, 3>| hash = fold_sample(hash, s);
    let run = gcode::run::<N>(job, Some(&mut costs), &mut sink);
    let counted = checked_gcode(names[0], run, hash);
    if counted != played {
        defmt::error!(
            "{=str}: counted, the run played {=u32} samples of hash {=u64}, not {=u32} of {=u64}",
            names[0],
            counted.run.samples,
            counted.hash,
            played.run.samples,
            played.hash
        );
        exit_failure()
    }
    log_costs(names, &mut costs, counted.run.motions, lines);
}

/// Logs what a streaming run counted (`names`: per call that handed the stream a move, per
/// poll that compiled ticks, and the whole run per move of `moves`); fails the run when a
/// list had no room for a count.
fn log_costs<const M: usize, const P: usize>(
    names: [&str; 3],
    costs: &mut Costs<'_, M, P>,
    moves: usize,
    lines: &mut Lines,
) {
    if costs.unlisted > 0 {
        defmt::error!(
            "{=str}: {=usize} counts found their list full",
            names[0],
            costs.unlisted
        );
        exit_failure()
    }
    spread(names[0], &mut costs.moves);
    spread(names[1], &mut costs.polls);
    let per_move = costs.total / moves.max(1) as u64;
    defmt::println!(
        "I {=str} {=u64} {=u64} {=u64} {=usize} 0",
        names[2],
        per_move,
        per_move,
        per_move,
        moves
    );
    lines.cases += 3;
}

/// Logs calls' instructions as an `I` line: least, median and most, the calls, the first
/// call that took the most.
fn spread(name: &str, costs: &mut [u64]) {
    let worst = costs.iter().enumerate().fold(
        (0, 0),
        |(w, m), (i, &c)| if c > m { (i, c) } else { (w, m) },
    );
    costs.sort_unstable();
    let median = costs.get(costs.len() / 2).copied().unwrap_or(0);
    let min = costs.first().copied().unwrap_or(0);
    defmt::println!(
        "I {=str} {=u64} {=u64} {=u64} {=usize} {=usize}",
        name,
        min,
        median,
        worst.1,
        costs.len(),
        worst.0
    );
}

/// Logs the instructions of one call as an `I` line.
fn instructions(name: &str, n: u64) {
    defmt::println!("I {=str} {=u64} {=u64} {=u64} 1 0", name, n, n, n);
}

/// The value, or the error logged for `what` and a failed run.
fn ok_or_fail<T, E: defmt::Format>(what: &str, r: Result<T, E>) -> T {
    match r {
        Ok(v) => v,
        Err(e) => {
            defmt::error!("{=str}: {}", what, e);
            exit_failure()
        }
    }
}

/// Counts SysTick's wraps for [`WideCounter`].
#[exception]
fn SysTick() {
    WideCounter::on_wrap();
}

/// A fault is logged and fails the run.
#[allow(unsafe_code)]
#[exception]
unsafe fn HardFault(frame: &ExceptionFrame) -> ! {
    defmt::error!("hard fault at pc {=u32:#x}", frame.pc());
    exit_failure()
}
