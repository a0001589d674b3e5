//! Flash playback on a part with the RAM of a real microcontroller: validates the blob
//! [`FLASH_BLOB`] in flash (3 axes, Q40, [`FLASH_PIECES`] = 256 pieces, the firmware's
//! capacity; compiled by `cargo xtask qemu` from `flash-256.toml`) and plays it to its end
//! through [`play_blob`], the whole work of a firmware that plays paths from flash, and logs
//! its stack high-water mark and the hash of its samples. A blob of another piece count
//! fails the run.
//!
//! Linked with the memory of a real part (`memory/flash-<target>.x`, chosen by `build.rs`):
//! the Cortex-M3 build has the 64 KiB of RAM of the LM3S6965 and runs on QEMU's
//! `lm3s6965evb`, the Cortex-M4F build the 64 KiB of an STM32F401CB on `mps2-an386`. The stack
//! grows down from the top of that RAM towards the statics at its start, and the MPU
//! ([`mpu::confine`]) allows no access outside the part's flash and RAM, so a stack that
//! outgrows the part faults.
//!
//! # Output protocol (defmt, read by `cargo xtask qemu`)
//! ```text
//! RAM <bytes>                         the RAM of the part (statics and stack)
//! STACK <operation> <stack> <ram>     stack high-water mark and RAM needed, in bytes
//! H <job> <format> <samples> <hash>   the blob played: its samples and their hash
//! STACKS 1
//! ```

#![no_std]
#![no_main]
#![deny(unsafe_code)]

use cortex_m_rt::{ExceptionFrame, entry, exception};
use strak_qemu::jobs::{FLASH_BLOB, FLASH_PIECES, NumberFormat};
use strak_qemu::play::play_blob;
use strak_qemu::{exit_failure, exit_success};
use strak_qemu::{mpu, stack};
use strak_trajectory::Q40;

#[entry]
fn main() -> ! {
    let Some(mut p) = cortex_m::Peripherals::take() else {
        exit_failure()
    };
    if let Err(e) = mpu::confine(&mut p.MPU) {
        defmt::error!("the MPU cannot confine the firmware to its part: {}", e);
        exit_failure()
    }
    let [_, (_, ram)] = mpu::part();
    defmt::println!("RAM {=u32}", ram);
    let job = &FLASH_BLOB;
    if job.format != NumberFormat::Q40 || job.axes != 3 {
        defmt::error!("{=str}: not a 3-axis fixed-point blob", job.name);
        exit_failure()
    }
    let (played, used) = stack::usage(|| play_blob::<Q40, 3>(job.blob, job.events));
    match played {
        Ok(played) if played.pieces != FLASH_PIECES => {
            defmt::error!(
                "{=str}: {=usize} pieces, the flash-playback firmware plays {=usize}",
                job.name,
                played.pieces,
                FLASH_PIECES
            );
            exit_failure()
        }
        Ok(played) => {
            stack::log("flash-play-q40", used);
            defmt::println!(
                "H {=str} {=str} {=u32} {=u64}",
                job.name,
                NumberFormat::Q40.name(),
                played.samples,
                played.hash
            );
            defmt::println!("STACKS 1");
            exit_success()
        }
        Err(e) => {
            defmt::error!("{=str}: the blob does not play: {}", job.name, e);
            exit_failure()
        }
    }
}

/// A fault (the stack outgrowing the part's RAM) is logged and fails the run, when the core
/// can still take the exception (a stack pointer below the RAM locks the core up instead,
/// which stops QEMU with an error).
#[allow(unsafe_code)]
#[exception]
unsafe fn HardFault(frame: &ExceptionFrame) -> ! {
    defmt::error!("hard fault at pc {=u32:#x}", frame.pc());
    exit_failure()
}
