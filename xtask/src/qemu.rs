//! `cargo xtask qemu`: the sampler inside real Cortex-M firmware under QEMU, compared bit for
//! bit with the host.
//!
//! 1. Installs what is missing: the rustup targets, `qemu-system-arm` (apt-get),
//!    `defmt-print` (cargo install, pinned to [`DEFMT_PRINT_VERSION`]).
//! 2. Compiles every bundled `[path]` job (`firmware-sim/examples/jobs/*.toml`) on the host in `f32`
//!    and fixed-point with `strak_sim::export` (what `strak-sim compile` writes) and plays it
//!    with its events, keeping every sample's bits, and the flash-playback firmware's job
//!    [`FLASH_JOB_FILE`] in fixed-point; streams the G-code programs of [`crate::gcode`] on
//!    the firmware's machine as `strak-sim gcode` does, in both formats; writes the blobs and
//!    a `jobs.rs` for the firmware (the G-code stream's constants generated from that
//!    machine) into `target/qemu/blobs`.
//! 3. Checks formatting and clippy of the firmware workspace `firmware-sim/qemu`, builds it
//!    for the Cortex-M4F and the Cortex-M3.
//! 4. Runs each firmware under QEMU, and the G-code firmware `gcode` (which reads the
//!    programs of [`crate::gcode`] line by line on the device and streams them), decodes
//!    their defmt output with defmt-print, and compares every stream with the host's (the
//!    first differing tick and value is named).
//! 5. Reads the firmware sizes from the ELF headers and checks them against
//!    `firmware-sim/qemu/sizes.txt` (`--bless` rewrites it).
//! 6. Runs the `stack` firmware under QEMU `-icount` on both targets (the stack and RAM of
//!    loading and playing a blob, of planning and of compiling on the device, of streaming
//!    and of streaming the first G-code program, the sizes of their values, the
//!    instructions of planning, compiling and streaming) and the flash-playback
//!    firmware `flash-play` on a part with the RAM of a real microcontroller (64 KiB: the
//!    LM3S6965 on `lm3s6965evb`, an STM32F401CB's on `mps2-an386`), which plays the path of
//!    [`FLASH_JOB_FILE`] (3 axes, Q40, [`FLASH_PIECES`] pieces, compiled in step 2 and
//!    checked for its piece count there and in the firmware); checks that the blobs and the
//!    G-code program they played give the host's samples (a hash of every sample's bits),
//!    and the stack against `firmware-sim/qemu/stack-budgets.txt` (`--bless` rewrites
//!    it), written to `target/qemu/stack.json` (see [`crate::stack`]).
//! 7. Runs the `icount` firmware under QEMU `-icount` on both targets: instructions per
//!    tick (instruction counts, not cycles); checks them and the instructions the `stack`
//!    firmware counted against `firmware-sim/qemu/icount-budgets.txt` (`--bless` rewrites it),
//!    written to `target/qemu/counts.json` (see [`crate::icount`]); and the online
//!    solves of random moves, whose durations must equal the host's bit for bit (see
//!    [`crate::online`]).

use std::env;
use std::fs;
use std::fs::File;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::thread;
use std::time::{Duration, Instant};

use strak_sim::export::{DeviceRecipe, Export, export};
use strak_sim::job::Job;
use strak_sim::online_move::{MoveEvent, MoveJob, MoveTarget, move_bits};
use strak_trajectory::{Event, NumberFormat, Synchronization, TimedEvent};

use crate::compare::{self, StreamKey};
use crate::gcode::{self, GcodeJobs, HostGcode};
use crate::icount;
use crate::online;
use crate::size::{self, Expected};
use crate::stack;

/// The defmt-print release matching the firmware's defmt 1.x.
pub(crate) const DEFMT_PRINT_VERSION: &str = "1.2.0";

/// How long one firmware may run under QEMU.
const QEMU_TIMEOUT: Duration = Duration::from_secs(600);

/// The firmware binaries built for each target: the example firmware, the size probes, the
/// stack-measuring firmware, the flash-playback firmware and the G-code firmware (the
/// `icount` firmware is not size-checked).
const BINARIES: [&str; 6] = [
    "strak-qemu",
    "size-sampler",
    "size-baseline",
    "stack",
    "flash-play",
    "gcode",
];

/// The playback formats of the firmware: `f32` (Cortex-M4F only) and `Q40`.
const FIRMWARE_FORMATS: [NumberFormat; 2] = [NumberFormat::F32, NumberFormat::Q40];

/// The job of the flash-playback firmware, compiled in fixed-point into exactly
/// [`FLASH_PIECES`] pieces of 3 axes (relative to the workspace root).
const FLASH_JOB_FILE: &str = "firmware-sim/qemu/flash-256.toml";

/// The pieces of the flash-playback firmware's path: the firmware's capacity
/// (`strak_qemu::PIECES`), which the firmware checks too.
const FLASH_PIECES: usize = 256;

/// One firmware build and the QEMU machine it runs on.
#[derive(Clone, Copy, Debug)]
struct Firmware {
    label: &'static str,
    target: &'static str,
    cpu: &'static str,
    machine: &'static str,
    formats: &'static [NumberFormat],
    /// The flash-playback firmware's machine and its label (the part it stands for).
    flash_machine: &'static str,
    flash_label: &'static str,
}

const FIRMWARES: [Firmware; 2] = [
    Firmware {
        label: "Cortex-M4F (mps2-an386)",
        target: "thumbv7em-none-eabihf",
        cpu: "cortex-m4",
        machine: "mps2-an386",
        formats: &[NumberFormat::F32, NumberFormat::Q40],
        flash_machine: "mps2-an386",
        flash_label: "Cortex-M4F (mps2-an386, the RAM and flash of an STM32F401CB)",
    },
    Firmware {
        label: "Cortex-M3 (mps2-an385)",
        target: "thumbv7m-none-eabi",
        cpu: "cortex-m3",
        machine: "mps2-an385",
        formats: &[NumberFormat::Q40],
        flash_machine: "lm3s6965evb",
        flash_label: "Cortex-M3 (lm3s6965evb: the LM3S6965, 64 KiB RAM)",
    },
];

/// A job exported for firmware in one format.
struct HostJob {
    name: String,
    export: Export,
    blob_path: PathBuf,
}

/// An online move played on the host in one format, as the firmware plays it.
struct HostMove {
    name: String,
    job: MoveJob,
    /// The firmware source of its events ([`move_events_src`]).
    events: String,
    playback: NumberFormat,
    /// Every sample's bits ([`move_bits`]).
    bits: Vec<u64>,
}

/// The folder of the move files the firmware plays (relative to the workspace root).
const MOVES_DIR: &str = "firmware-sim/examples/moves";

/// The axes of the firmware's online moves (`strak_qemu::jobs::MoveJob<3>`).
const MOVE_AXES: usize = 3;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map_or_else(|| PathBuf::from("."), Path::to_owned)
}

/// Runs the whole check; `bless` rewrites the expected sizes instead of checking them.
pub(crate) fn qemu(bless: bool) -> Result<(), String> {
    let started = Instant::now();
    let root = root();
    let fw_dir = root.join("firmware-sim").join("qemu");
    let targets: Vec<&str> = FIRMWARES.iter().map(|f| f.target).collect();
    crate::ensure_targets(&targets)?;
    let qemu = ensure_qemu()?;
    let defmt_print = ensure_defmt_print()?;

    println!("\n==> host: compiling and playing the bundled jobs (f32 and Q40)");
    let t = Instant::now();
    let blob_dir = root.join("target").join("qemu").join("blobs");
    let jobs = export_jobs(&root.join("firmware-sim/examples/jobs"), &blob_dir)?;
    let flash = flash_job(&root.join(FLASH_JOB_FILE), &blob_dir)?;
    let moves = export_moves(&root.join(MOVES_DIR))?;
    let gcode = gcode::export(&root, &FIRMWARE_FORMATS)?;
    let source = jobs_source(&jobs, &flash, &moves) + &gcode::source(&gcode)?;
    write_if_changed(&blob_dir.join("jobs.rs"), source.as_bytes())?;
    println!(
        "<== host: {} jobs × formats, {} samples ({:.1} s)",
        jobs.len(),
        jobs.iter().map(|j| j.export.samples()).sum::<usize>(),
        t.elapsed().as_secs_f64()
    );

    build_firmware(&fw_dir, &blob_dir)?;

    let mut compared = 0_usize;
    for fw in &FIRMWARES {
        let elf = fw_dir
            .join("target")
            .join(fw.target)
            .join("release")
            .join("strak-qemu");
        println!("\n==> QEMU {}: {}", fw.label, elf.display());
        let t = Instant::now();
        let text = run_firmware(&qemu, &defmt_print, fw, &elf, &[])?;
        let secs = t.elapsed().as_secs_f64();
        let n = check_output(fw, &jobs, &moves, &text)?;
        compared += n;
        println!(
            "<== QEMU {}: {n} samples equal the host's bit for bit ({secs:.1} s)",
            fw.label
        );
        compared += gcode_firmware(&qemu, &defmt_print, &fw_dir, fw, &gcode)?;
    }

    check_sizes(&fw_dir, bless)?;
    let flash = [flash];
    let host = [host_played(&jobs, &gcode.played), host_played(&flash, &[])];
    let planning = check_stack(&qemu, &defmt_print, &root, &fw_dir, &host, bless)?;
    check_icount(&qemu, &defmt_print, &root, &fw_dir, planning, bless)?;
    println!(
        "\nxtask qemu: {compared} firmware samples equal the host's bit for bit; done in {:.0} s",
        started.elapsed().as_secs_f64()
    );
    Ok(())
}

/// Checks the formatting and clippy of the firmware workspace `fw_dir` and builds its
/// binaries for every target, with the blobs and `jobs.rs` of `blob_dir`.
fn build_firmware(fw_dir: &Path, blob_dir: &Path) -> Result<(), String> {
    let blobs = blob_dir.to_string_lossy().into_owned();
    let envs = [("STRAK_BLOBS", blobs.as_str())];
    fw_step(fw_dir, "firmware format", &["fmt", "--", "--check"], &envs)?;
    for fw in &FIRMWARES {
        fw_step(
            fw_dir,
            &format!("firmware clippy ({})", fw.target),
            &[
                "clippy",
                "--release",
                "--target",
                fw.target,
                "--",
                "-D",
                "warnings",
            ],
            &envs,
        )?;
        fw_step(
            fw_dir,
            &format!("firmware build ({})", fw.target),
            &["build", "--release", "--target", fw.target, "--bins"],
            &envs,
        )?;
    }
    Ok(())
}

/// The `.toml` files of `dir`, sorted.
fn toml_files(dir: &Path) -> Result<Vec<PathBuf>, String> {
    let mut files: Vec<PathBuf> = fs::read_dir(dir)
        .map_err(|e| format!("cannot read {}: {e}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    Ok(files)
}

/// Exports every job file of `dir` with a `[path]` in both formats, writing the blobs into
/// `blob_dir` (the moves jobs stream on the host only: the firmware plays compiled paths).
fn export_jobs(dir: &Path, blob_dir: &Path) -> Result<Vec<HostJob>, String> {
    let mut files = toml_files(dir)?;
    files.retain(|f| {
        fs::read_to_string(f).map_or(true, |text| !strak_sim::moves::is_moves_job(&text))
    });
    if files.is_empty() {
        return Err(format!("no job files in {}", dir.display()));
    }
    fs::create_dir_all(blob_dir)
        .map_err(|e| format!("cannot create {}: {e}", blob_dir.display()))?;
    let mut out = Vec::new();
    for file in files {
        out.extend(export_file(&file, blob_dir, &FIRMWARE_FORMATS)?);
    }
    Ok(out)
}

/// Exports the job file `file` in each of `playbacks`, writing the blobs into `blob_dir`.
fn export_file(
    file: &Path,
    blob_dir: &Path,
    playbacks: &[NumberFormat],
) -> Result<Vec<HostJob>, String> {
    let name = file
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let text =
        fs::read_to_string(file).map_err(|e| format!("cannot read {}: {e}", file.display()))?;
    let job = Job::parse(&text).map_err(|e| format!("{}: {e}", file.display()))?;
    let mut out = Vec::new();
    for &playback in playbacks {
        let export =
            export(&job, playback).map_err(|e| format!("{} ({playback}): {e}", file.display()))?;
        let blob_path = blob_dir.join(format!("{name}-{playback}.strk"));
        write_if_changed(&blob_path, &export.blob)?;
        println!(
            "    {name} {playback}: {} axes, {} pieces, {} ticks, {} samples, blob {} bytes{}",
            export.axes,
            export.pieces,
            export.ticks,
            export.samples(),
            export.blob.len(),
            if export.recipe.is_some() && export.axes == 3 {
                ", also compiled on the device"
            } else {
                ""
            }
        );
        out.push(HostJob {
            name: name.clone(),
            export,
            blob_path,
        });
    }
    Ok(out)
}

/// Plays every move file of `dir` on the host in each firmware format ([`move_bits`]).
fn export_moves(dir: &Path) -> Result<Vec<HostMove>, String> {
    let files = toml_files(dir)?;
    let mut out = Vec::new();
    for file in files {
        let name = file
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let text = fs::read_to_string(&file)
            .map_err(|e| format!("cannot read {}: {e}", file.display()))?;
        let job = MoveJob::parse(&text).map_err(|e| format!("{}: {e}", file.display()))?;
        if job.axes() != MOVE_AXES {
            return Err(format!(
                "{}: the firmware plays online moves of {MOVE_AXES} axes, this one has {}",
                file.display(),
                job.axes()
            ));
        }
        let events = move_events_src(&job).map_err(|e| format!("{}: {e}", file.display()))?;
        for playback in FIRMWARE_FORMATS {
            let bits = move_bits(&job, playback)
                .map_err(|e| format!("{} ({playback}): {e}", file.display()))?;
            println!(
                "    {name} {playback}: online move, {} events, {} samples",
                job.events.len(),
                bits.len() / (3 * MOVE_AXES)
            );
            out.push(HostMove {
                name: name.clone(),
                job: job.clone(),
                events: events.clone(),
                playback,
                bits,
            });
        }
    }
    Ok(out)
}

/// Exports the flash-playback firmware's job ([`FLASH_JOB_FILE`]) in `Q40` and checks its
/// blob ([`check_flash_blob`]).
fn flash_job(file: &Path, blob_dir: &Path) -> Result<HostJob, String> {
    let mut jobs = export_file(file, blob_dir, &[NumberFormat::Q40])?;
    let job = jobs
        .pop()
        .ok_or_else(|| format!("{}: nothing exported", file.display()))?;
    check_flash_blob(&job.export.blob).map_err(|e| format!("{}: {e}", file.display()))?;
    Ok(job)
}

/// Checks that `blob` is what the flash-playback firmware plays: it loads as a 3-axis `Q40`
/// path (as the firmware loads it, [`PathBlob::from_bytes`](strak_trajectory::PathBlob)) of
/// [`FLASH_PIECES`] pieces. The firmware fails on any other blob; this check names the cause
/// on the host.
///
/// # Errors
/// The load error, or the piece count and how to change it.
fn check_flash_blob(blob: &[u8]) -> Result<(), String> {
    let path = strak_trajectory::PathBlob::<strak_trajectory::Q40, 3>::from_bytes(blob).map_err(
        |e| format!("the flash-playback firmware plays a 3-axis Q40 blob; this one does not load as one: {e}"),
    )?;
    let pieces = path.view().piece_count();
    if pieces != FLASH_PIECES {
        return Err(format!(
            "compiles to {pieces} pieces; the flash-playback firmware plays a path of \
             {FLASH_PIECES} pieces of 3 axes (the pieces are duration · rate_hz / \
             max_piece_ticks: change those)"
        ));
    }
    Ok(())
}

/// Writes `bytes` to `path` unless it holds them already (an unchanged file keeps its time,
/// so cargo does not rebuild the firmware).
fn write_if_changed(path: &Path, bytes: &[u8]) -> Result<(), String> {
    if fs::read(path).is_ok_and(|old| old == bytes) {
        return Ok(());
    }
    fs::write(path, bytes).map_err(|e| format!("cannot write {}: {e}", path.display()))
}

/// Rust source of an `f64` with exactly these bits.
fn f64_src(x: f64) -> String {
    format!("f64::from_bits({:#018x})", x.to_bits())
}

/// Rust source of the events (`strak_trajectory::TimedEvent`s), the feed with its bits.
fn events_src(events: &[TimedEvent]) -> String {
    let list: Vec<String> = events
        .iter()
        .map(|e| {
            let event = match e.event {
                Event::Feed(f) => format!("Event::Feed(f32::from_bits({:#010x}))", f.to_bits()),
                Event::Hold => "Event::Hold".to_owned(),
                Event::Resume => "Event::Resume".to_owned(),
                Event::Abort => "Event::Abort".to_owned(),
                Event::RampScale(shift) => format!("Event::RampScale({shift})"),
            };
            format!("TimedEvent {{ tick: {}, event: {event} }}", e.tick)
        })
        .collect();
    format!("&[{}]", list.join(", "))
}

/// The jobs that are compiled on the device too: plain B-spline jobs of 3 axes.
fn device_jobs(jobs: &[HostJob]) -> Vec<(&HostJob, &HostJob)> {
    jobs.iter()
        .filter(|j| {
            j.export.playback == NumberFormat::F32
                && j.export.axes == 3
                && j.export.recipe.is_some()
        })
        .filter_map(|f| {
            jobs.iter()
                .find(|x| x.name == f.name && x.export.playback == NumberFormat::Q40)
                .map(|x| (f, x))
        })
        .collect()
}

/// The firmware's `jobs.rs`: the blobs (`include_bytes!`) and their events, the device
/// jobs, and the blob of the flash-playback firmware (`flash`).
fn jobs_source(jobs: &[HostJob], flash: &HostJob, moves: &[HostMove]) -> String {
    let mut s = String::from(
        "// @generated by `cargo xtask qemu` from firmware-sim/examples/jobs, \
         firmware-sim/examples/moves, firmware-sim/qemu/flash-256.toml, \
         firmware-sim/qemu/gcode-machine.toml and firmware-sim/examples/gcode: do not edit.\n\n\
         /// The jobs compiled on the host, as blobs in flash.\npub static BLOB_JOBS: &[BlobJob] = &[\n",
    );
    for j in jobs {
        s += &format!("    {},\n", blob_job_src(j));
    }
    s += "];\n\n/// The jobs compiled on the device at start-up (3 axes).\npub static DEVICE_JOBS: &[DeviceJob<3>] = &[\n";
    for (f, x) in device_jobs(jobs) {
        if let Some(r) = &f.export.recipe {
            s += &device_job_src(r, f, x);
        }
    }
    s += "];\n\n/// The path of the flash-playback firmware: 3 axes, Q40, `FLASH_PIECES` pieces.\n";
    s += &format!(
        "pub static FLASH_BLOB: BlobJob = {};\n",
        blob_job_src(flash)
    );
    s += "\n/// The online moves the device solves and plays (3 axes).\npub static MOVE_JOBS: &[MoveJob<3>] = &[\n";
    for m in moves.iter().filter(|m| m.playback == FIRMWARE_FORMATS[0]) {
        s += &format!("    {},\n", move_job_src(&m.name, &m.job, &m.events));
    }
    s += "];\n";
    s
}

/// The source of states, one `[position, velocity, acceleration]` per axis.
fn states_src(v: &[[f64; 3]]) -> String {
    let rows: Vec<String> = v
        .iter()
        .map(|r| format!("[{}]", r.map(f64_src).join(", ")))
        .collect();
    format!("[{}]", rows.join(", "))
}

/// A `MoveTarget` literal.
fn target_src(t: &MoveTarget) -> String {
    format!(
        "MoveTarget {{ states: {}, position: {} }}",
        states_src(&t.states),
        t.position
    )
}

/// The source of a move file's events (the inside of a slice literal).
///
/// # Errors
/// An operator event (feed override, hold, resume, abort): the firmware plays new targets
/// and stops only.
fn move_events_src(job: &MoveJob) -> Result<String, String> {
    let event = |(tick, e): &(u64, MoveEvent)| match e {
        MoveEvent::Target(t) => Ok(format!("({tick}, MoveEvent::Target({}))", target_src(t))),
        MoveEvent::Stop => Ok(format!("({tick}, MoveEvent::Stop)")),
        MoveEvent::Operator(_) => Err(format!(
            "the event at tick {tick}: the firmware plays new targets and stops, not feed \
             override, hold, resume or abort"
        )),
    };
    let events: Result<Vec<String>, String> = job.events.iter().map(event).collect();
    Ok(events?.join(", "))
}

/// A `MoveJob` literal for the move file `name`, with its `events` ([`move_events_src`]).
fn move_job_src(name: &str, job: &MoveJob, events: &str) -> String {
    let sync = match job.sync {
        Synchronization::Time => "Time",
        Synchronization::Phase => "Phase",
        Synchronization::None => "None",
    };
    format!(
        "MoveJob {{ name: {name:?}, rate_hz: {}, sync: Synchronization::{sync}, limits: {}, start: {}, target: {}, events: &[{events}] }}",
        f64_src(job.rate_hz),
        states_src(&job.limits),
        states_src(&job.start),
        target_src(&job.target),
    )
}

/// A `BlobJob` literal for `j`, its blob included from its file.
fn blob_job_src(j: &HostJob) -> String {
    format!(
        "BlobJob {{ name: {:?}, format: NumberFormat::{:?}, axes: {}, blob: &strak_trajectory::AlignedBlob(*include_bytes!({:?})).0, events: {} }}",
        j.name,
        j.export.playback,
        j.export.axes,
        j.blob_path.to_string_lossy(),
        events_src(&j.export.events)
    )
}

/// The compile options of `r` as a `CompileOptions` expression.
fn compile_src(r: &DeviceRecipe) -> String {
    let c = &r.compile;
    let mut compile = String::from("strak_trajectory::CompileOptions::new()");
    match c.tolerance() {
        strak_trajectory::Tolerance::Absolute(t) => {
            compile += &format!(".with_tolerance({})", f64_src(t));
        }
        strak_trajectory::Tolerance::Relative(t) => {
            compile += &format!(".with_relative_tolerance({})", f64_src(t));
        }
    }
    compile += &format!(".with_max_piece_ticks({})", c.max_piece_ticks());
    if let Some((a, j)) = c.limits() {
        compile += &format!(".with_limits({}, {})", f64_src(a), f64_src(j));
    }
    let axes = c.axis_acceleration();
    if axes.iter().any(|a| a.is_finite()) {
        let list: Vec<String> = axes.iter().map(|&a| f64_src(a)).collect();
        compile += &format!(".with_axis_acceleration([{}])", list.join(", "));
    }
    compile += &format!(".with_feed_share({})", f64_src(c.feed_share()));
    compile
}

/// The planner options of `r` as a `PlanOptions` expression.
fn plan_src(r: &DeviceRecipe) -> String {
    let p = &r.plan;
    format!(
        "strak_trajectory::PlanOptions::new().with_shape(strak_trajectory::ProfileShape::{:?}).with_samples({}).with_zone_tolerance({}).with_centripetal_share({}).with_corner_angle({}).with_feed_share({}).with_rate({})",
        p.shape(),
        p.samples(),
        f64_src(p.zone_tolerance()),
        f64_src(p.centripetal_share()),
        f64_src(p.corner_angle()),
        f64_src(p.feed_share()),
        f64_src(p.rate()),
    )
}

/// A `DeviceJob` literal (with its trailing comma) for the recipe `r` of the job exported
/// as `f` (f32) and `x` (fixed-point).
fn device_job_src(r: &DeviceRecipe, f: &HostJob, x: &HostJob) -> String {
    let list = |v: &[f64]| v.iter().map(|x| f64_src(*x)).collect::<Vec<_>>().join(", ");
    let points: Vec<String> = r.points.iter().map(|p| format!("[{}]", list(p))).collect();
    format!(
        "    DeviceJob {{\n        name: {:?},\n        rate_hz: {},\n        degree: {},\n        points: &[{}],\n        limits: [{}],\n        axis_velocity: [{}],\n        axis_acceleration: [{}],\n        machine_limits: [{}],\n        machine_axis_velocity: [{}],\n        plan: {},\n        compile: {},\n        events: {},\n        host_blob_f32: include_bytes!({:?}),\n        host_blob_fixed: include_bytes!({:?}),\n    }},\n",
        f.name,
        f64_src(r.rate_hz),
        r.degree,
        points.join(", "),
        list(&r.limits),
        list(&r.axis_velocity),
        list(&r.axis_acceleration),
        list(&r.machine_limits),
        list(&r.machine_axis_velocity),
        plan_src(r),
        compile_src(r),
        events_src(&f.export.events),
        f.blob_path.to_string_lossy(),
        x.blob_path.to_string_lossy(),
    )
}

/// `cargo ARGS` in the firmware workspace (its own `.cargo/config.toml` applies).
fn fw_step(dir: &Path, name: &str, args: &[&str], envs: &[(&str, &str)]) -> Result<(), String> {
    println!("\n==> {name}: cargo {}", args.join(" "));
    let t = Instant::now();
    let cargo = env::var("CARGO").unwrap_or_else(|_| "cargo".to_owned());
    let status = Command::new(cargo)
        .args(args)
        .current_dir(dir)
        .envs(envs.iter().copied())
        // The firmware's linker scripts come from its config; a RUSTFLAGS would replace them.
        .env_remove("RUSTFLAGS")
        .env_remove("CARGO_TARGET_DIR")
        .status()
        .map_err(|e| format!("{name}: could not start cargo: {e}"))?;
    if status.success() {
        println!("<== {name}: ok ({:.0} s)", t.elapsed().as_secs_f64());
        Ok(())
    } else {
        Err(format!("{name} failed ({status})"))
    }
}

fn runs(program: &Path, args: &[&str]) -> Option<String> {
    let out = Command::new(program).args(args).output().ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).into_owned())
}

/// `qemu-system-arm`, installed with apt-get when missing (`apt-get update` and a second
/// try when the first install fails).
fn ensure_qemu() -> Result<PathBuf, String> {
    let qemu = PathBuf::from("qemu-system-arm");
    if runs(&qemu, &["--version"]).is_some() {
        return Ok(qemu);
    }
    println!("==> installing qemu-system-arm: apt-get install -y qemu-system-arm");
    let install = || {
        Command::new("apt-get")
            .args(["install", "-y", "qemu-system-arm"])
            .env("DEBIAN_FRONTEND", "noninteractive")
            .status()
            .is_ok_and(|s| s.success())
    };
    if !install() {
        println!("==> apt-get install failed; apt-get update, then again");
        let updated = Command::new("apt-get")
            .arg("update")
            .env("DEBIAN_FRONTEND", "noninteractive")
            .status()
            .is_ok_and(|s| s.success());
        if !updated || !install() {
            return Err(
                "qemu-system-arm is missing and `apt-get install -y qemu-system-arm` failed \
                 (it needs root and Debian's package lists); install it by hand"
                    .to_owned(),
            );
        }
    }
    runs(&qemu, &["--version"])
        .map(|_| qemu)
        .ok_or_else(|| "qemu-system-arm was installed but does not run".to_owned())
}

/// `defmt-print` of [`DEFMT_PRINT_VERSION`], installed with `cargo install --locked` when
/// missing or of another version.
fn ensure_defmt_print() -> Result<PathBuf, String> {
    let cargo_home = env::var_os("CARGO_HOME")
        .map(PathBuf::from)
        .or_else(|| env::var_os("HOME").map(|h| PathBuf::from(h).join(".cargo")));
    let candidates: Vec<PathBuf> = cargo_home
        .iter()
        .map(|h| h.join("bin").join("defmt-print"))
        .chain([PathBuf::from("defmt-print")])
        .collect();
    let wanted = format!("defmt-print {DEFMT_PRINT_VERSION}");
    let find = || {
        candidates.iter().find(|c| {
            runs(c, &["-V"]).is_some_and(|v| v.lines().next().is_some_and(|l| l.trim() == wanted))
        })
    };
    if let Some(found) = find() {
        return Ok(found.clone());
    }
    println!(
        "==> installing {wanted}: cargo install defmt-print --version ={DEFMT_PRINT_VERSION} --locked"
    );
    let cargo = env::var("CARGO").unwrap_or_else(|_| "cargo".to_owned());
    let ok = Command::new(cargo)
        .args(["install", "defmt-print", "--version"])
        .arg(format!("={DEFMT_PRINT_VERSION}"))
        .arg("--locked")
        .env_remove("RUSTFLAGS")
        .status()
        .is_ok_and(|s| s.success());
    if !ok {
        return Err(format!(
            "`cargo install defmt-print --version ={DEFMT_PRINT_VERSION} --locked` failed"
        ));
    }
    find().cloned().ok_or_else(|| {
        format!("{wanted} was installed but is not found in $CARGO_HOME/bin or on PATH")
    })
}

fn read_all(mut r: impl Read + Send + 'static) -> thread::JoinHandle<String> {
    thread::spawn(move || {
        let mut buf = Vec::new();
        let _ = r.read_to_end(&mut buf);
        String::from_utf8_lossy(&buf).into_owned()
    })
}

fn kill(child: &mut Child) {
    let _ = child.kill();
    let _ = child.wait();
}

/// Runs `elf` under QEMU with its output written to a file, then decodes the file with
/// defmt-print; returns defmt-print's text.
///
/// Not a pipe: QEMU's semihosting writes to a non-blocking standard output, and into a full
/// pipe (a slow reader on a loaded machine) they fail and the bytes are lost, which
/// defmt-print then skips. A file never refuses a write.
fn run_firmware(
    qemu: &Path,
    defmt_print: &Path,
    fw: &Firmware,
    elf: &Path,
    extra: &[&str],
) -> Result<String, String> {
    let raw = elf.with_extension("defmt");
    let raw_file =
        File::create(&raw).map_err(|e| format!("cannot create {}: {e}", raw.display()))?;
    let mut q = Command::new(qemu)
        .args(["-cpu", fw.cpu, "-machine", fw.machine, "-nographic"])
        .args(extra)
        .args(["-semihosting-config", "enable=on,target=native", "-kernel"])
        .arg(elf)
        .stdin(Stdio::null())
        .stdout(raw_file)
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("cannot start {}: {e}", qemu.display()))?;
    let q_err = read_all(q.stderr.take().ok_or("no QEMU stderr")?);
    let deadline = Instant::now() + QEMU_TIMEOUT;
    let status = loop {
        match q.try_wait() {
            Ok(Some(status)) => break Some(status),
            Ok(None) if Instant::now() < deadline => thread::sleep(Duration::from_millis(50)),
            _ => {
                kill(&mut q);
                break None;
            }
        }
    };
    let mut q_err = q_err.join().unwrap_or_default();
    if q_err.contains("Lockup") {
        q_err += "(the core locked up: a fault it could not take, such as a stack that outgrew \
                  the RAM)\n";
    }
    let input = File::open(&raw).map_err(|e| format!("cannot read {}: {e}", raw.display()))?;
    let decoded = Command::new(defmt_print)
        .arg("-e")
        .arg(elf)
        .args(["--log-format", "{L} {s}"])
        .stdin(input)
        .output()
        .map_err(|e| format!("cannot start {}: {e}", defmt_print.display()))?;
    let text = String::from_utf8_lossy(&decoded.stdout).into_owned();
    let d_err = String::from_utf8_lossy(&decoded.stderr).into_owned();
    let tail = |s: &str| {
        s.lines()
            .rev()
            .take(20)
            .collect::<Vec<_>>()
            .into_iter()
            .rev()
            .collect::<Vec<_>>()
            .join("\n")
    };
    match status {
        Some(s) if s.success() => Ok(text),
        Some(s) => Err(format!(
            "{} failed under QEMU ({s}); its last lines:\n{}\n{}{}",
            fw.label,
            tail(&text),
            q_err,
            d_err
        )),
        None => Err(format!(
            "{} did not finish within {} s under QEMU; its last lines:\n{}",
            fw.label,
            QEMU_TIMEOUT.as_secs(),
            tail(&text)
        )),
    }
}

/// Compares the firmware's output with the host's streams; returns the samples compared.
fn check_output(
    fw: &Firmware,
    jobs: &[HostJob],
    moves: &[HostMove],
    text: &str,
) -> Result<usize, String> {
    let out = parse_output(fw, text)?;
    // Each stream the firmware must play: its key, axes and the host's bits.
    let mut expected: Vec<(StreamKey, usize, &[u64])> = Vec::new();
    for j in jobs
        .iter()
        .filter(|j| fw.formats.contains(&j.export.playback))
    {
        let key = (j.name.clone(), j.export.playback, "blob".to_owned());
        expected.push((key, j.export.axes, &j.export.bits));
    }
    for (f, x) in device_jobs(jobs) {
        for j in [f, x] {
            if fw.formats.contains(&j.export.playback) {
                let format = j.export.playback;
                match out.compiled.get(&(j.name.clone(), format)) {
                    Some(&(bytes, pieces))
                        if bytes == j.export.blob.len() && pieces == j.export.pieces => {}
                    other => {
                        return Err(format!(
                            "{}: {} {format}: the device did not report its compiled path as equal to the host's blob ({other:?})",
                            fw.label, j.name
                        ));
                    }
                }
                let key = (j.name.clone(), format, "device".to_owned());
                expected.push((key, j.export.axes, &j.export.bits));
            }
        }
    }
    for m in moves.iter().filter(|m| fw.formats.contains(&m.playback)) {
        let key = (m.name.clone(), m.playback, "online".to_owned());
        expected.push((key, MOVE_AXES, &m.bits));
    }
    compare_streams(fw, &out, &expected)
}

/// The firmware's output parsed ([`compare::parse`]), with nothing outside the protocol.
fn parse_output(fw: &Firmware, text: &str) -> Result<compare::FirmwareOutput, String> {
    let out = compare::parse(text)?;
    if !out.other.is_empty() {
        return Err(format!(
            "{}: unexpected firmware output:\n{}",
            fw.label,
            out.other.join("\n")
        ));
    }
    Ok(out)
}

/// Compares the G-code firmware's output with the host's G-code streams of `fw`'s formats;
/// returns the samples compared.
fn check_gcode_output(fw: &Firmware, gcode: &GcodeJobs, text: &str) -> Result<usize, String> {
    let out = parse_output(fw, text)?;
    let expected: Vec<(StreamKey, usize, &[u64])> = gcode
        .played
        .iter()
        .filter(|g| fw.formats.contains(&g.playback))
        .map(|g| {
            let key = (g.name.clone(), g.playback, "gcode".to_owned());
            (key, gcode::AXES, g.bits.as_slice())
        })
        .collect();
    compare_streams(fw, &out, &expected)
}

/// Compares every stream of `expected` (key, axes, the host's bits) with the firmware's
/// `out` bit for bit, and checks that the firmware played these streams and no others;
/// returns the samples compared.
///
/// # Errors
/// A stream missing, of other axes, or differing (the first differing tick and value named).
fn compare_streams(
    fw: &Firmware,
    out: &compare::FirmwareOutput,
    expected: &[(StreamKey, usize, &[u64])],
) -> Result<usize, String> {
    let mut samples = 0;
    for &(ref key, axes, bits) in expected {
        let label = format!("{}: {} {} ({})", fw.label, key.0, key.1, key.2);
        let stream = out
            .stream(key)
            .ok_or_else(|| format!("{label}: the firmware did not play this stream"))?;
        if stream.axes != axes {
            return Err(format!(
                "{label}: {} axes, the host has {axes}",
                stream.axes
            ));
        }
        let n = compare::compare(bits, &stream.bits, stream.axes, key.1)
            .map_err(|m| format!("{label}: the firmware differs from the host: {m}"))?;
        if stream.ended != u32::try_from(n).ok() {
            return Err(format!(
                "{label}: the stream ended with {:?} samples, {n} were compared",
                stream.ended
            ));
        }
        samples += n;
    }
    if out.streams.len() != expected.len() || out.done != u32::try_from(expected.len()).ok() {
        return Err(format!(
            "{}: {} streams played (DONE {:?}), {} expected",
            fw.label,
            out.streams.len(),
            out.done,
            expected.len()
        ));
    }
    Ok(samples)
}

/// Runs the G-code firmware of `fw` under QEMU and compares its streams with the host's;
/// returns the samples compared.
fn gcode_firmware(
    qemu: &Path,
    defmt_print: &Path,
    fw_dir: &Path,
    fw: &Firmware,
    gcode: &GcodeJobs,
) -> Result<usize, String> {
    let elf = firmware_elf(fw_dir, fw, "gcode");
    println!(
        "\n==> QEMU {}: G-code read and streamed on the device: {}",
        fw.label,
        elf.display()
    );
    let t = Instant::now();
    let text = run_firmware(qemu, defmt_print, fw, &elf, &[])?;
    let secs = t.elapsed().as_secs_f64();
    let n = check_gcode_output(fw, gcode, &text)?;
    println!(
        "<== QEMU {}: {n} G-code samples equal the host's bit for bit ({secs:.1} s)",
        fw.label
    );
    Ok(n)
}

/// Reads the sizes of every firmware binary and checks them (or rewrites the file).
fn check_sizes(fw_dir: &Path, bless: bool) -> Result<(), String> {
    let file = fw_dir.join("sizes.txt");
    let mut actual = Vec::new();
    for fw in &FIRMWARES {
        for bin in BINARIES {
            let elf = fw_dir
                .join("target")
                .join(fw.target)
                .join("release")
                .join(bin);
            let bytes =
                fs::read(&elf).map_err(|e| format!("cannot read {}: {e}", elf.display()))?;
            let sizes = size::elf32_sizes(&bytes).map_err(|e| format!("{}: {e}", elf.display()))?;
            actual.push(Expected {
                name: bin.to_owned(),
                target: fw.target.to_owned(),
                sizes,
            });
        }
    }
    println!("\n==> firmware sizes (bytes)");
    for a in &actual {
        println!("    {:<14} {:<22} {}", a.name, a.target, a.sizes);
    }
    for fw in &FIRMWARES {
        let flash = |bin: &str| {
            actual
                .iter()
                .find(|a| a.name == bin && a.target == fw.target)
                .map_or(0, |a| a.sizes.flash())
        };
        println!(
            "    sampler alone on {}: {} bytes of flash (size-sampler − size-baseline)",
            fw.target,
            flash("size-sampler").cast_signed() - flash("size-baseline").cast_signed()
        );
    }
    if bless {
        fs::write(&file, size::write_expected(&actual))
            .map_err(|e| format!("cannot write {}: {e}", file.display()))?;
        println!("<== wrote {}", file.display());
        return Ok(());
    }
    let text = fs::read_to_string(&file).map_err(|e| {
        format!(
            "cannot read {}: {e} (create it with `cargo xtask qemu --bless`)",
            file.display()
        )
    })?;
    let expected = size::parse_expected(&text)?;
    for a in &actual {
        let e = expected
            .iter()
            .find(|e| e.name == a.name && e.target == a.target)
            .ok_or_else(|| {
                format!(
                    "{} has no line for {} {}: run `cargo xtask qemu --bless` and commit it",
                    file.display(),
                    a.name,
                    a.target
                )
            })?;
        size::check(&format!("{} ({})", a.name, a.target), e.sizes, a.sizes)?;
    }
    println!(
        "<== sizes within {:.0} % of {}",
        size::GROWTH * 100.0,
        file.display()
    );
    Ok(())
}

/// The instruction counts of `cases` as a table.
fn print_counts(cases: &[icount::Measured]) {
    println!(
        "    {:<30} {:>6} {:>6} {:>6} {:>6} {:>9}",
        "case", "min", "median", "max", "calls", "max at"
    );
    for m in cases {
        println!(
            "    {:<30} {:>6} {:>6} {:>6} {:>6} {:>9}",
            m.name, m.min, m.median, m.max, m.calls, m.worst
        );
    }
}

/// Runs the `icount` firmware on every target under `-icount`, checks its counts and the
/// counts of planning and compiling (`planning`) against the budget file (or rewrites it
/// when `bless`) and writes `target/qemu/counts.json`.
fn check_icount(
    qemu: &Path,
    defmt_print: &Path,
    root: &Path,
    fw_dir: &Path,
    planning: Vec<icount::Measured>,
    bless: bool,
) -> Result<(), String> {
    let shift = format!("shift={}", icount::ICOUNT_SHIFT);
    let mut measured = Vec::new();
    for fw in &FIRMWARES {
        let elf = fw_dir
            .join("target")
            .join(fw.target)
            .join("release")
            .join("icount");
        println!(
            "\n==> QEMU -icount {shift} {}: instructions per call (instruction counts, not cycles)",
            fw.label
        );
        let text = run_firmware(qemu, defmt_print, fw, &elf, &["-icount", &shift])?;
        let cases =
            icount::parse_output(&text, fw.target).map_err(|e| format!("{}: {e}", fw.label))?;
        let agreed = icount::sampler_checked(&text).map_err(|e| format!("{}: {e}", fw.label))?;
        println!("    the sampler's entry points agree bit for bit over {agreed} ticks");
        let solved = online::parse(&text).map_err(|e| format!("{}: {e}", fw.label))?;
        online::check(&solved).map_err(|e| format!("{}: {e}", fw.label))?;
        for s in &solved {
            println!(
                "    {}: the device's {} solves equal the host's, bit for bit",
                s.name, s.moves
            );
        }
        print_counts(&cases);
        measured.extend(cases);
    }
    measured.extend(planning);
    for line in icount::target_report(&measured) {
        println!("    target: {line}");
    }
    let file = fw_dir.join("icount-budgets.txt");
    if bless {
        fs::write(&file, icount::write_budgets(&measured))
            .map_err(|e| format!("cannot write {}: {e}", file.display()))?;
        println!("<== wrote {}", file.display());
    }
    let text = fs::read_to_string(&file).map_err(|e| {
        format!(
            "cannot read {}: {e} (create it with `cargo xtask qemu --bless`)",
            file.display()
        )
    })?;
    let budgets = icount::parse_budgets(&text).map_err(|e| format!("{}: {e}", file.display()))?;
    let json = root.join("target").join("qemu").join("counts.json");
    fs::write(&json, icount::counts_json(&measured, &budgets))
        .map_err(|e| format!("cannot write {}: {e}", json.display()))?;
    println!("    wrote {}", json.display());
    icount::check(&measured, &budgets)?;
    icount::check_constant_time(&measured)?;
    println!(
        "<== instruction counts within {}; every playback case in constant time",
        file.display()
    );
    Ok(())
}

/// The path of the release binary `bin` of `fw`.
fn firmware_elf(fw_dir: &Path, fw: &Firmware, bin: &str) -> PathBuf {
    fw_dir
        .join("target")
        .join(fw.target)
        .join("release")
        .join(bin)
}

/// What the stack-measuring firmware reported on every target.
#[derive(Default)]
struct StackRun {
    /// The stack of each operation.
    measured: Vec<stack::Measured>,
    /// The sizes of the values: name, target, bytes.
    sizes: Vec<(String, String, u64)>,
    /// The instruction counts of planning and compiling.
    counts: Vec<icount::Measured>,
}

/// Runs the `stack` firmware (under `-icount`) and the flash-playback firmware on every
/// target, checks what they played against the host's samples (`stack_host`, `flash`) and
/// their stack against the budget file (or rewrites it when `bless`), writes
/// `target/qemu/stack.json`, and returns the instruction counts the `stack` firmware made.
fn check_stack(
    qemu: &Path,
    defmt_print: &Path,
    root: &Path,
    fw_dir: &Path,
    [stack_host, flash]: &[Vec<stack::Played>; 2],
    bless: bool,
) -> Result<Vec<icount::Measured>, String> {
    let mut run = StackRun::default();
    for fw in &FIRMWARES {
        stack_firmware(qemu, defmt_print, fw_dir, fw, stack_host, &mut run)?;
        let flash_stack = flash_firmware(qemu, defmt_print, fw_dir, fw, flash)?;
        run.measured.extend(flash_stack);
    }
    let StackRun {
        measured,
        sizes,
        counts,
    } = run;
    for line in stack::target_report(&measured) {
        println!("    target: {line}");
    }
    let file = fw_dir.join("stack-budgets.txt");
    if bless {
        fs::write(&file, stack::write_budgets(&measured))
            .map_err(|e| format!("cannot write {}: {e}", file.display()))?;
        println!("<== wrote {}", file.display());
    }
    let text = fs::read_to_string(&file).map_err(|e| {
        format!(
            "cannot read {}: {e} (create it with `cargo xtask qemu --bless`)",
            file.display()
        )
    })?;
    let budgets = stack::parse_budgets(&text).map_err(|e| format!("{}: {e}", file.display()))?;
    let json = root.join("target").join("qemu").join("stack.json");
    fs::write(&json, stack::stack_json(&measured, &budgets, &sizes))
        .map_err(|e| format!("cannot write {}: {e}", json.display()))?;
    println!("    wrote {}", json.display());
    stack::check(&measured, &budgets)?;
    println!("<== stack within {}", file.display());
    Ok(counts)
}

/// Runs the `stack` firmware of `fw` under `-icount`, checks the blobs and G-code programs
/// it played against the host's (`host`), and adds what it measured to `run`.
fn stack_firmware(
    qemu: &Path,
    defmt_print: &Path,
    fw_dir: &Path,
    fw: &Firmware,
    host: &[stack::Played],
    run: &mut StackRun,
) -> Result<(), String> {
    let shift = format!("shift={}", icount::ICOUNT_SHIFT);
    let elf = firmware_elf(fw_dir, fw, "stack");
    println!(
        "\n==> QEMU -icount {shift} {}: stack and RAM of loading, planning and compiling",
        fw.label
    );
    let text = run_firmware(qemu, defmt_print, fw, &elf, &["-icount", &shift])?;
    let report = stack::parse_output(&text, fw.target).map_err(|e| format!("{}: {e}", fw.label))?;
    check_played(fw.label, host, &report)?;
    let cases = icount::parse_output(&report.rest, fw.target)
        .map_err(|e| format!("{} (stack firmware): {e}", fw.label))?;
    print_stack(&report);
    for (name, pieces, ticks) in &report.compiled {
        println!("    {name}: {pieces} pieces, {ticks} ticks");
    }
    print_counts(&cases);
    run.sizes.extend(
        report
            .sizes
            .iter()
            .map(|(n, b)| (n.clone(), fw.target.to_owned(), *b)),
    );
    run.measured.extend(report.stacks);
    run.counts.extend(cases);
    Ok(())
}

/// Runs the flash-playback firmware of `fw` on its part, checks that it played `flash` as
/// the host does and named the part's RAM, and returns its stack measurements.
fn flash_firmware(
    qemu: &Path,
    defmt_print: &Path,
    fw_dir: &Path,
    fw: &Firmware,
    flash: &[stack::Played],
) -> Result<Vec<stack::Measured>, String> {
    let part = Firmware {
        machine: fw.flash_machine,
        label: fw.flash_label,
        ..*fw
    };
    let elf = firmware_elf(fw_dir, fw, "flash-play");
    println!(
        "\n==> QEMU {}: playing a blob of {FLASH_PIECES} pieces from flash",
        part.label
    );
    let text = run_firmware(qemu, defmt_print, &part, &elf, &[])?;
    let report =
        stack::parse_output(&text, fw.target).map_err(|e| format!("{}: {e}", part.label))?;
    check_played(part.label, flash, &report)?;
    let ram = report
        .part_ram
        .ok_or_else(|| format!("{}: the flash-playback firmware named no RAM", part.label))?;
    println!("    the part's RAM: {ram} bytes");
    print_stack(&report);
    Ok(report.stacks)
}

/// The stack measurements and sizes of `report` as tables.
fn print_stack(report: &stack::Report) {
    for (name, bytes) in &report.sizes {
        println!("    size_of {name:<44} {bytes:>7} bytes");
    }
    println!("    {:<30} {:>9} {:>9}", "operation", "stack", "RAM");
    for m in &report.stacks {
        println!("    {:<30} {:>9} {:>9}", m.name, m.stack, m.ram);
    }
}

/// What the host played of `jobs` and of the G-code programs `gcode`, in the shape of a
/// firmware's `H` lines: each stream's job, format, samples and the hash of their bits.
fn host_played(jobs: &[HostJob], gcode: &[HostGcode]) -> Vec<stack::Played> {
    let blobs = jobs.iter().map(|j| stack::Played {
        job: j.name.clone(),
        format: j.export.playback,
        samples: j.export.samples() as u64,
        hash: stack::hash(&j.export.bits),
    });
    let programs = gcode.iter().map(|g| stack::Played {
        job: g.name.clone(),
        format: g.playback,
        samples: (g.bits.len() / (3 * gcode::AXES)) as u64,
        hash: stack::hash(&g.bits),
    });
    blobs.chain(programs).collect()
}

/// Checks every stream the firmware played (an `H` line: a blob, a G-code program) against
/// the host's of the same job and format (`host`): the number of samples and the hash of
/// their bits.
fn check_played(label: &str, host: &[stack::Played], report: &stack::Report) -> Result<(), String> {
    if report.played.is_empty() {
        return Err(format!("{label}: the firmware played no blob"));
    }
    for p in &report.played {
        let h = host
            .iter()
            .find(|h| h.job == p.job && h.format == p.format)
            .ok_or_else(|| {
                format!(
                    "{label}: played {} {}, which the host has not",
                    p.job, p.format
                )
            })?;
        if (p.samples, p.hash) != (h.samples, h.hash) {
            return Err(format!(
                "{label}: {} {}: {} samples of hash {:#018x}, the host has {} of hash {:#018x}",
                p.job, p.format, p.samples, p.hash, h.samples, h.hash
            ));
        }
    }
    println!(
        "    {} stream(s) played, every sample equal to the host's (hash of their bits)",
        report.played.len()
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn exported(file: &str, format: NumberFormat) -> Export {
        let path = root().join(file);
        let text = fs::read_to_string(&path).unwrap();
        export(&Job::parse(&text).unwrap(), format).unwrap()
    }

    #[test]
    fn the_flash_job_compiles_to_the_blob_the_flash_firmware_plays() {
        let e = exported(FLASH_JOB_FILE, NumberFormat::Q40);
        assert_eq!((e.axes, e.pieces), (3, FLASH_PIECES));
        assert_eq!(check_flash_blob(&e.blob), Ok(()));
    }

    #[test]
    fn a_blob_of_another_piece_count_is_named_with_its_count() {
        let e = exported(
            "firmware-sim/examples/jobs/pick-and-place.toml",
            NumberFormat::Q40,
        );
        assert_eq!(e.axes, 3);
        assert_ne!(e.pieces, FLASH_PIECES);
        let m = check_flash_blob(&e.blob).unwrap_err();
        assert!(
            m.starts_with(&format!("compiles to {} pieces;", e.pieces)),
            "{m}"
        );
        assert!(
            m.contains(&format!("plays a path of {FLASH_PIECES} pieces")),
            "{m}"
        );
    }

    #[test]
    fn a_blob_of_another_format_or_axis_count_does_not_load() {
        let f32_blob = exported(
            "firmware-sim/examples/jobs/pick-and-place.toml",
            NumberFormat::F32,
        );
        let two_axes = exported(
            "firmware-sim/examples/jobs/circle-f32.toml",
            NumberFormat::Q40,
        );
        assert_eq!(two_axes.axes, 2);
        for blob in [&f32_blob.blob, &two_axes.blob] {
            let m = check_flash_blob(blob).unwrap_err();
            assert!(m.contains("does not load as one"), "{m}");
        }
    }
}
