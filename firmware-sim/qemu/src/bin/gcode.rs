//! strak's G-code firmware: streams every bundled G-code program ([`GCODE_JOBS`]), its text
//! in flash read line by line on the device by [`strak_gcode::Program`] as its moves arrive
//! from a producer at a limited rate ([`strak_qemu::gcode::run`]), and logs every sample
//! through defmt (`J`, `S`, `E` with source `gcode`, then `DONE`, the protocol of the example
//! firmware) for `cargo xtask qemu` to compare with `strak-sim gcode`'s bit for bit.
//!
//! On the Cortex-M4F (`thumbv7em-none-eabihf`) it plays `f32` and fixed-point; on the
//! Cortex-M3 (`thumbv7m-none-eabi`) fixed-point only.

#![no_std]
#![no_main]
// `deny`, not `forbid`: cortex-m-rt requires the HardFault handler to be an `unsafe fn`;
// that one item allows it, it contains no unsafe operation.
#![deny(unsafe_code)]

use cortex_m_rt::{ExceptionFrame, entry, exception};
use strak_qemu::jobs::{GCODE_JOBS, GcodeJob, NumberFormat, played_here};
use strak_qemu::play::{OutBits, log_sample};
use strak_qemu::{exit_failure, exit_success};
use strak_trajectory::{Kernel, Q40};

#[entry]
fn main() -> ! {
    let mut streams: u32 = 0;
    for job in GCODE_JOBS {
        for format in [NumberFormat::F32, NumberFormat::Q40] {
            if played_here(format) {
                match format {
                    NumberFormat::F32 => gcode::<f32>(job, format),
                    _ => gcode::<Q40>(job, format),
                }
                streams += 1;
            }
        }
    }
    defmt::println!("DONE {=u32}", streams);
    exit_success()
}

/// Streams the G-code job `job` in `N` ([`strak_qemu::gcode::run`]) and logs the stream
/// (`J`, one `S` per tick, `E`, source `gcode`); the stream, its piece queue and its sampler
/// live in that call's frame only while it runs.
#[inline(never)]
fn gcode<N>(job: &GcodeJob<3>, format: NumberFormat)
where
    N: Kernel,
    N::Out: OutBits,
{
    defmt::println!("J {=str} {=str} gcode 3", job.name, format.name());
    match strak_qemu::gcode::run::<N>(job, None, &mut |k, s| log_sample(k, s)) {
        Ok(run) => defmt::println!(
            "E {=str} {=str} gcode {=u32}",
            job.name,
            format.name(),
            run.samples
        ),
        Err(e) => {
            defmt::error!(
                "{=str} {=str}: streaming the G-code on the device failed: {}",
                job.name,
                format.name(),
                e
            );
            exit_failure()
        }
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
