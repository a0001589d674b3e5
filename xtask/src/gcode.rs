//! The G-code jobs of `cargo xtask qemu`: the bundled programs the firmware reads line by
//! line and streams on its machine ([`MACHINE_FILE`]), played on the host as `strak-sim
//! gcode` plays them ([`gcode_samples`]), and the firmware's constants and jobs for them,
//! generated from the same machine file so that the device's stream is the host's.

use std::fs;
use std::path::{Path, PathBuf};

use strak_sim::export::OutBits;
use strak_sim::gcode_run::{gcode_samples, run_gcode};
use strak_sim::machine::Machine;
use strak_sim::pipeline::{axis_array, limits_of};
use strak_sim::run::RunOptions;
use strak_sim::stream_run::{FIT_TOLERANCE, PIECE_QUEUE, StreamSetup, stream_options};
use strak_trajectory::{Kernel, Limits, NumberFormat, Q40, StreamOptions};

/// The machine the firmware streams G-code on (relative to the workspace root).
pub(crate) const MACHINE_FILE: &str = "firmware-sim/qemu/gcode-machine.toml";

/// The programs the firmware streams: the stream's job name and the file (relative to the
/// workspace root).
pub(crate) const PROGRAMS: [(&str, &str); 1] =
    [("gcode-contour", "firmware-sim/examples/gcode/contour.nc")];

/// The axes of the firmware's G-code stream (`strak_qemu::gcode::GcodeStream`: 3 path axes,
/// none riding along).
pub(crate) const AXES: usize = 3;

/// A program played on the host in one format, as the firmware plays it.
pub(crate) struct HostGcode {
    /// The stream's job name.
    pub(crate) name: String,
    /// The program's file.
    pub(crate) file: PathBuf,
    /// The playback format.
    pub(crate) playback: NumberFormat,
    /// Every sample's bits: positions, velocities, accelerations.
    pub(crate) bits: Vec<u64>,
}

/// The firmware's machine and the programs played on the host in each of `formats`.
pub(crate) struct GcodeJobs {
    /// The machine.
    pub(crate) machine: Machine,
    /// Each program in each format.
    pub(crate) played: Vec<HostGcode>,
}

/// Every sample's bits of `text` played on `machine` in `N` ([`gcode_samples`]).
fn bits<N: Kernel>(text: &[u8], machine: &Machine) -> Result<Vec<u64>, String>
where
    N::Out: OutBits,
{
    let mut out = Vec::new();
    gcode_samples::<N, AXES, 0>(text, machine, &mut |s| {
        let values = s.position.iter().chain(&s.velocity).chain(&s.acceleration);
        out.extend(values.map(|v| v.out_bits()));
        Ok(())
    })
    .map_err(|e| e.to_string())?;
    Ok(out)
}

/// Reads the firmware's machine and plays every program of [`PROGRAMS`] on it in each of
/// `formats`.
///
/// # Errors
/// A machine the firmware cannot stream on, or a program the host cannot play.
pub(crate) fn export(root: &Path, formats: &[NumberFormat]) -> Result<GcodeJobs, String> {
    let file = root.join(MACHINE_FILE);
    let text =
        fs::read_to_string(&file).map_err(|e| format!("cannot read {}: {e}", file.display()))?;
    let machine = Machine::parse(&text).map_err(|e| format!("{}: {e}", file.display()))?;
    if (machine.axes.len(), machine.riding_axes()) != (AXES, 0) {
        return Err(format!(
            "{}: the firmware streams G-code on {AXES} path axes and none riding along",
            file.display()
        ));
    }
    device_limits(&machine.setup()).map_err(|e| format!("{}: {e}", file.display()))?;
    let mut played = Vec::new();
    for (name, program) in PROGRAMS {
        let path = root.join(program);
        let text = fs::read(&path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        starves(root, name, &text, &machine).map_err(|e| format!("{}: {e}", path.display()))?;
        for &playback in formats {
            let bits = match playback {
                NumberFormat::F32 => bits::<f32>(&text, &machine),
                NumberFormat::Q40 => bits::<Q40>(&text, &machine),
                NumberFormat::F64 => bits::<f64>(&text, &machine),
            }
            .map_err(|e| format!("{} ({playback}): {e}", path.display()))?;
            println!(
                "    {name} {playback}: G-code streamed on {MACHINE_FILE}, {} samples",
                bits.len() / (3 * AXES)
            );
            played.push(HostGcode {
                name: name.to_owned(),
                file: path.clone(),
                playback,
                bits,
            });
        }
    }
    Ok(GcodeJobs { machine, played })
}

/// Checks that `text` played on `machine` as `strak-sim gcode` plays it (its report
/// written into `target/qemu/gcode/<name>`) starves the stream at least once, so that the
/// firmware streams through a rest for want of a move: a machine without `[produce]`, or
/// one whose moves arrive too fast for that, fails.
///
/// # Errors
/// The run's error, or a run that never starved.
fn starves(root: &Path, name: &str, text: &[u8], machine: &Machine) -> Result<(), String> {
    let options = RunOptions {
        out_dir: root.join("target").join("qemu").join("gcode").join(name),
        name: name.to_owned(),
        progress: false,
        velocity_factor: None,
    };
    let summary = run_gcode(text, name, machine, &options, 1).map_err(|e| e.to_string())?;
    let starved = summary.stream.as_ref().map_or(0, |s| s.starved);
    if starved == 0 {
        return Err(format!(
            "the stream never starved on {MACHINE_FILE}: the firmware is to stream through a \
             rest for want of a move (lower [produce] moves_per_second)"
        ));
    }
    println!(
        "    {name}: the stream starves {starved} time(s) on {MACHINE_FILE} ({})",
        options.out_dir.display()
    );
    Ok(())
}

/// What the firmware's job holds of `setup`: path limits, per-axis velocity and
/// acceleration limits.
type DeviceLimits = ([f64; 3], [f64; AXES], [f64; AXES]);

/// The limits the firmware is given, checked to build the host's stream limits and options
/// exactly as the firmware builds them (`strak_qemu::gcode::limits` and `options`).
///
/// # Errors
/// The limits or options the firmware would build differ from the host's.
fn device_limits(setup: &StreamSetup) -> Result<DeviceLimits, String> {
    let l = &setup.limits;
    let ours = (
        [l.velocity, l.acceleration, l.jerk],
        axis_array::<AXES>(l.axis_velocity.as_deref()),
        axis_array::<AXES>(l.axis_acceleration.as_deref()),
    );
    let built = Limits::<AXES>::new(ours.0[0], ours.0[1], ours.0[2])
        .and_then(|x| x.with_axis_velocity(ours.1))
        .and_then(|x| x.with_axis_acceleration(ours.2))
        .map_err(|e| e.to_string())?;
    let host = limits_of::<AXES>(l, 1.0).map_err(|e| e.to_string())?;
    if built != host {
        return Err(format!(
            "the firmware's limits {built:?} differ from the host's {host:?}"
        ));
    }
    let options = StreamOptions::new(setup.rate_hz)
        .with_tolerance(setup.tolerance)
        .with_faster_stops(setup.faster_stops)
        .with_arc_tolerance(setup.arc_tolerance)
        .with_fit_tolerance(FIT_TOLERANCE);
    if options != stream_options(setup) {
        return Err(format!(
            "the firmware's stream options {options:?} differ from the host's {:?}",
            stream_options(setup)
        ));
    }
    Ok(ours)
}

/// Rust source of an `f64` with exactly these bits.
fn f64_src(x: f64) -> String {
    format!("f64::from_bits({:#018x})", x.to_bits())
}

/// Rust source of a list of `f64`s.
fn list_src(v: &[f64]) -> String {
    let items: Vec<String> = v.iter().map(|&x| f64_src(x)).collect();
    format!("[{}]", items.join(", "))
}

/// The G-code part of the firmware's `jobs.rs`: the stream's capacities and the piece
/// queue's from the machine, and one `GcodeJob` per program, its text included from its
/// file.
///
/// # Errors
/// As [`device_limits`].
pub(crate) fn source(jobs: &GcodeJobs) -> Result<String, String> {
    let setup = jobs.machine.setup();
    let (limits, axis_velocity, axis_acceleration) = device_limits(&setup)?;
    let letters = jobs.machine.letters::<AXES>();
    let ticks_per_move = setup.moves_per_second.map_or_else(
        || "None".to_owned(),
        |mps| format!("Some({})", f64_src(setup.rate_hz / mps)),
    );
    let mut s = format!(
        "\n/// The look-ahead segments of the G-code stream (the machine's `queue`).\n\
         pub const GCODE_SEGMENTS: usize = {};\n\
         /// The zones of the G-code stream's look-ahead window (four per segment).\n\
         pub const GCODE_ZONES: usize = {};\n\
         /// The pieces between the G-code stream and its sampler (`strak-sim`'s).\n\
         pub const GCODE_PIECE_QUEUE: usize = {PIECE_QUEUE};\n\n\
         /// The G-code programs the device reads and streams (3 axes).\n\
         pub static GCODE_JOBS: &[GcodeJob<3>] = &[\n",
        setup.queue,
        setup.zones(),
    );
    let mut seen = Vec::new();
    for j in &jobs.played {
        if seen.contains(&&j.name) {
            continue;
        }
        seen.push(&j.name);
        s += &format!(
            "    GcodeJob {{ name: {:?}, text: include_bytes!({:?}), letters: *b{:?}, rate_hz: {}, \
             tolerance: {}, faster_stops: {}, arc_tolerance: {}, fit_tolerance: {}, limits: {}, \
             axis_velocity: {}, axis_acceleration: {}, ticks_per_move: {ticks_per_move} }},\n",
            j.name,
            j.file.to_string_lossy(),
            String::from_utf8_lossy(&letters),
            f64_src(setup.rate_hz),
            f64_src(setup.tolerance),
            setup.faster_stops,
            f64_src(setup.arc_tolerance),
            f64_src(FIT_TOLERANCE),
            list_src(&limits),
            list_src(&axis_velocity),
            list_src(&axis_acceleration),
        );
    }
    s += "];\n";
    Ok(s)
}
