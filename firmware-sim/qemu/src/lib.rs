//! strak's example firmware, shared by its binaries: the jobs embedded in flash, the
//! tick handler that plays a path through
//! [`Sampler`](strak_trajectory::Sampler), on-device compiling, online moves
//! with new targets and quick stops ([`moves`]), the output
//! protocol, the panic handler and the exit to QEMU; for the measuring firmware the
//! instruction counter ([`counter`]) and the instructions of a streaming loop's calls
//! counted with it ([`costs`]), the check of the tick kernels against the portable
//! kernel ([`kernel_check`]), the stack measurement ([`stack`]), the MPU set-up that
//! confines a firmware to the memories of a real part ([`mpu`]), the planning job
//! ([`planning`]), the online solves ([`online`]), the feed guard's cost ([`guard`]),
//! streaming moves ([`streaming`]); for the G-code firmware (`src/bin/gcode.rs`) a program
//! read line by line on the device and streamed as its moves arrive ([`gcode`]).
//!
//! `cargo xtask qemu` compiles every bundled job on the host (`strak_sim::export`, the same
//! code as `strak-sim compile`), writes the blobs and a `jobs.rs` describing them into a
//! folder and builds this crate with `STRAK_BLOBS` pointing there; `build.rs` copies
//! `jobs.rs` into `OUT_DIR`, where [`jobs`] includes it.
//!
//! # Output protocol (defmt, decoded by `defmt-print`)
//! ```text
//! J <job> <format> <source> <axes>      a stream starts (source: blob | device | online | gcode)
//! C <job> <format> <bytes> <pieces>     the device compiled the job; its blob equals the host's
//! S <tick> [<bits>, …]                  one sample: positions, velocities, accelerations
//! E <job> <format> <source> <samples>   the stream ends
//! DONE <streams>                        all streams played; exit code 0 follows
//! ```
//! `<format>` is the playback format's [`NumberFormat`](strak_trajectory::NumberFormat)
//! name (`f32`, `Q40`). A sample's bits are `f32::to_bits` (f32 playback) or the `i64` bits
//! of the `I32F32` output (`Q40` playback), widened to `u64`. Nothing else is logged on success, so
//! the output is deterministic.

#![no_std]
// `deny`, not `forbid`: the stack measurement reads and writes the unused stack, and the MPU
// set-up writes the MPU's registers (the two modules that allow it).
#![deny(unsafe_code)]

pub mod costs;
pub mod counter;
pub mod device;
pub mod gcode;
pub mod guard;
pub mod jobs;
pub mod kernel_check;
pub mod moves;
#[allow(unsafe_code)]
pub mod mpu;
pub mod online;
pub mod planning;
pub mod play;
pub mod sampler_check;
#[allow(unsafe_code)]
pub mod stack;
pub mod streaming;

use cortex_m_semihosting::debug;
// The defmt global logger (semihosting) is linked from here.
use defmt_semihosting as _;

/// Path capacity of the firmware: the bundled jobs need at most 166 pieces.
pub const PIECES: usize = 256;

/// The bundled job whose blob the stack firmware validates and plays from flash (the
/// flash-playback firmware plays [`jobs::FLASH_BLOB`]).
pub const STACK_JOB: &str = "pick-and-place";

/// Exits QEMU with status 0.
pub fn exit_success() -> ! {
    debug::exit(debug::EXIT_SUCCESS);
    loop {
        cortex_m::asm::bkpt();
    }
}

/// Exits QEMU with a failure status.
pub fn exit_failure() -> ! {
    debug::exit(debug::EXIT_FAILURE);
    loop {
        cortex_m::asm::bkpt();
    }
}

/// Logs the panic through defmt (`defmt-print` drops plain-text panic messages) and exits
/// QEMU with failure.
#[panic_handler]
fn panic(info: &core::panic::PanicInfo<'_>) -> ! {
    defmt::error!("panic: {}", defmt::Display2Format(info));
    exit_failure()
}

/// One step of a 64-bit FNV-1a-style hash over whole words (for the size probes' output).
pub fn mix(hash: u64, word: u64) -> u64 {
    (hash ^ word).wrapping_mul(0x0000_0100_0000_01b3)
}
