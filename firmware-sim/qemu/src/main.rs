//! strak's example firmware: plays every bundled job through the sampler — from the blobs the
//! host compiled, from paths compiled on the device at start-up, and online moves solved on
//! the device with their new targets and quick stops — and logs every sample through defmt
//! for `cargo xtask qemu` to compare with the host bit for bit.
//!
//! On the Cortex-M4F (`thumbv7em-none-eabihf`, QEMU `mps2-an386`) it plays `f32` and
//! fixed-point; on the Cortex-M3 (`thumbv7m-none-eabi`, `mps2-an385`) fixed-point only.

#![no_std]
#![no_main]
// `deny`, not `forbid`: cortex-m-rt requires the HardFault handler to be an `unsafe fn`
// (measured: "defining a `HardFault` handler is unsafe and requires an `unsafe fn`"); that one
// item allows it, it contains no unsafe operation. The library crate forbids unsafe code.
#![deny(unsafe_code)]

use cortex_m_rt::{ExceptionFrame, entry, exception};
use strak_curves::{I32F32, Point, Scalar};
use strak_qemu::device::{compile_job, first_difference};
use strak_qemu::jobs::{
    BLOB_JOBS, BlobJob, DEVICE_JOBS, DeviceJob, MOVE_JOBS, MoveJob, NumberFormat, played_here,
};
use strak_qemu::moves::play_move;
use strak_qemu::play::{OutBits, play_and_log};
use strak_qemu::{PIECES, counter::Counter, exit_failure, exit_success};
use strak_trajectory::{Kernel, OnlineMove, Path, PathBlob, Q40, Real};

/// The largest blob the device compiles (`PIECES` pieces of 3 axes in `f64`-sized values, and
/// the header).
const MAX_BLOB: usize = 64 * 1024;

#[entry]
fn main() -> ! {
    // The instruction-count hook (issue 5 reads it under `-icount`); not logged here.
    let _counter = cortex_m::Peripherals::take().map(|p| Counter::start(p.SYST));
    let mut streams: u32 = 0;
    for job in BLOB_JOBS {
        if played_here(job.format) {
            play_blob(job);
            streams += 1;
        }
    }
    for job in DEVICE_JOBS {
        for format in [NumberFormat::F32, NumberFormat::Q40] {
            if played_here(format) {
                match format {
                    NumberFormat::F32 => device::<f32, f32>(job, format, job.host_blob_f32),
                    _ => device::<Q40, I32F32>(job, format, job.host_blob_fixed),
                }
                streams += 1;
            }
        }
    }
    for job in MOVE_JOBS {
        for format in [NumberFormat::F32, NumberFormat::Q40] {
            if played_here(format) {
                // The solver `strak-sim move` pairs with the playback format.
                match format {
                    NumberFormat::F32 => online::<f32, f32>(job, format),
                    _ => online::<Q40, f64>(job, format),
                }
                streams += 1;
            }
        }
    }
    defmt::println!("DONE {=u32}", streams);
    exit_success()
}

fn play_blob(job: &BlobJob) {
    match (job.format, job.axes) {
        (NumberFormat::F32, 2) => blob::<f32, 2>(job),
        (NumberFormat::F32, 3) => blob::<f32, 3>(job),
        (NumberFormat::Q40, 2) => blob::<Q40, 2>(job),
        (NumberFormat::Q40, 3) => blob::<Q40, 3>(job),
        (format, axes) => {
            defmt::error!(
                "{=str}: {=str} with {=usize} axes is not built into this firmware",
                job.name,
                format.name(),
                axes
            );
            exit_failure()
        }
    }
}

// Not inlined: each job's path and plan live in this call's frame only while it runs, instead
// of every instantiation's frame adding up in `main`'s (measured: 2.2 MiB in `main` otherwise).
#[inline(never)]
fn blob<N: Kernel, const A: usize>(job: &BlobJob)
where
    N::Out: OutBits,
{
    // Validated once, then played from the bytes in flash: no copy of the pieces in RAM.
    match PathBlob::<N, A>::from_bytes(job.blob) {
        Ok(blob) => {
            play_and_log(job.name, job.format, "blob", &blob, job.events);
        }
        Err(e) => {
            defmt::error!(
                "{=str} {=str}: the blob does not load: {}",
                job.name,
                job.format.name(),
                e
            );
            exit_failure()
        }
    }
}

#[inline(never)]
fn device<N, S>(job: &DeviceJob<3>, format: NumberFormat, host_blob: &[u8])
where
    N: Kernel,
    N::Out: OutBits,
    S: Scalar,
    [S; 3]: Point<Scalar = S>,
{
    let path = match compile_job::<N, S, 3, PIECES>(job) {
        Ok(p) => p,
        Err(e) => {
            defmt::error!(
                "{=str} {=str}: compiling on the device failed: {}",
                job.name,
                format.name(),
                e
            );
            exit_failure()
        }
    };
    let mut buf = [0_u8; MAX_BLOB];
    let ours = match path.to_bytes(&mut buf) {
        Ok(n) => buf.get(..n).unwrap_or(&[]),
        Err(e) => {
            defmt::error!("{=str}: serializing failed: {}", job.name, e);
            exit_failure()
        }
    };
    if let Some(i) = first_difference(ours, host_blob) {
        defmt::error!(
            "{=str} {=str}: the path compiled on the device differs from the host's blob at byte {=usize} (device {=usize} bytes, host {=usize})",
            job.name,
            format.name(),
            i,
            ours.len(),
            host_blob.len()
        );
        exit_failure()
    }
    defmt::println!(
        "C {=str} {=str} {=usize} {=usize}",
        job.name,
        format.name(),
        ours.len(),
        path.pieces().len()
    );
    play_and_log(job.name, format, "device", &path, job.events);
}

/// Plays the online move `job` in `N` with the solver in `R` ([`play_move`]); the move and
/// both paths live in this call's frame only while it runs.
#[inline(never)]
fn online<N, R>(job: &MoveJob<3>, format: NumberFormat)
where
    N: Kernel,
    N::Out: OutBits,
    R: Real,
{
    let mut m = OnlineMove::<R, 3>::new();
    let mut paths = [Path::<N, 3, PIECES>::new(), Path::new()];
    if let Err(e) = play_move(job, format, &mut m, &mut paths) {
        defmt::error!(
            "{=str} {=str}: the online move failed on the device: {}",
            job.name,
            format.name(),
            e
        );
        exit_failure()
    }
}

/// A fault (a stack overflow runs into unmapped memory below RAM) is logged and fails the run
/// instead of hanging in cortex-m-rt's default handler.
#[allow(unsafe_code)]
#[exception]
unsafe fn HardFault(frame: &ExceptionFrame) -> ! {
    defmt::error!("hard fault at pc {=u32:#x}", frame.pc());
    exit_failure()
}
