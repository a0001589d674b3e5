//! Confines the firmware to the memories of its part with the memory protection unit (the
//! PMSAv7 MPU of the Cortex-M3 and Cortex-M4; ARM, *ARMv7-M Architecture Reference Manual*,
//! §B3.5): one region for the flash (read-only, executable), one for the RAM (read-write,
//! never executed), and no background region, so that any other access faults.
//!
//! QEMU's boards map more memory than a real part has, and read the unmapped addresses
//! below the RAM as zero instead of faulting: without the MPU, a stack that outgrows the
//! part's RAM would run on into them unnoticed. With it, the first access below the RAM is a
//! MemManage fault, escalated to HardFault (the handler runs with the MPU off), or a lockup
//! when the exception cannot be stacked either; QEMU stops on both.
//!
//! The bounds come from the linker: `_flash_start` and `_flash_end` (defined by the part's
//! `memory.x`), `_ram_start` and `_ram_end` (cortex-m-rt's `link.x`). Each region must be a
//! power of two of at least 32 bytes, aligned to its size.

use cortex_m::asm;
use cortex_m::peripheral::MPU;

// The symbols of the part's `memory.x` and of cortex-m-rt's `link.x`; only their addresses
// are used.
unsafe extern "C" {
    /// The first address of the flash.
    static _flash_start: u32;
    /// The end of the flash (exclusive).
    static _flash_end: u32;
    /// The first address of the RAM.
    static _ram_start: u32;
    /// The end of the RAM (exclusive).
    static _ram_end: u32;
}

/// A memory region that the MPU cannot describe (its size is not a power of two of at least
/// 32 bytes, or its start is not aligned to its size).
#[derive(Clone, Copy, Debug, PartialEq, Eq, defmt::Format)]
pub struct BadRegion {
    /// The region's first address.
    pub start: u32,
    /// Its size in bytes.
    pub size: u32,
}

/// RASR: `XN` (never execute).
const XN: u32 = 1 << 28;
/// RASR `AP` = 0b110: read-only.
const READ_ONLY: u32 = 0b110 << 24;
/// RASR `AP` = 0b011: read-write.
const READ_WRITE: u32 = 0b011 << 24;
/// RASR `TEX` = 0, `C` = 1, `B` = 0: normal memory, write-through (flash and SRAM).
const NORMAL: u32 = 1 << 17;
/// RASR `S`: shareable.
const SHAREABLE: u32 = 1 << 18;
/// RASR `ENABLE`, RBAR `VALID`, CTRL `ENABLE`.
const ENABLE: u32 = 1;
const VALID: u32 = 1 << 4;

/// The RASR `SIZE` field of a region of `size` bytes (`2^(SIZE + 1)` bytes), if the MPU can
/// describe it at `start`.
fn size_field(start: u32, size: u32) -> Result<u32, BadRegion> {
    if size < 32 || !size.is_power_of_two() || !start.is_multiple_of(size) {
        return Err(BadRegion { start, size });
    }
    Ok((size.trailing_zeros() - 1) << 1)
}

/// The part's flash and RAM: `(start, size)` each.
pub fn part() -> [(u32, u32); 2] {
    let flash = (&raw const _flash_start).addr() as u32;
    let flash_end = (&raw const _flash_end).addr() as u32;
    let ram = (&raw const _ram_start).addr() as u32;
    let ram_end = (&raw const _ram_end).addr() as u32;
    [
        (flash, flash_end.wrapping_sub(flash)),
        (ram, ram_end.wrapping_sub(ram)),
    ]
}

/// Enables the MPU with the part's flash (region 0) and RAM (region 1) and nothing else.
///
/// # Errors
/// [`BadRegion`] for a memory the MPU cannot describe; the MPU is left off.
pub fn confine(mpu: &mut MPU) -> Result<(), BadRegion> {
    let [(flash, flash_size), (ram, ram_size)] = part();
    let regions = [
        (flash, size_field(flash, flash_size)? | READ_ONLY | NORMAL),
        (
            ram,
            size_field(ram, ram_size)? | READ_WRITE | NORMAL | SHAREABLE | XN,
        ),
    ];
    for (number, (start, attributes)) in (0_u32..).zip(regions) {
        // SAFETY: writing RBAR (with VALID, selecting the region) and RASR describes one MPU
        // region; the MPU is still off, so nothing that runs changes its meaning meanwhile.
        unsafe {
            mpu.rbar.write(start | VALID | number);
            mpu.rasr.write(attributes | ENABLE);
        }
    }
    // SAFETY: turns the MPU on without the background region (PRIVDEFENA = 0) and off in
    // HardFault and NMI (HFNMIENA = 0). The code, its constants and the blobs are in the flash
    // region, the stack and statics in the RAM region, and the system registers (SysTick,
    // SCB, the MPU itself) are in the private peripheral bus that the MPU never checks, so
    // the firmware keeps every access it makes within its part's memories.
    unsafe { mpu.ctrl.write(ENABLE) };
    asm::dsb();
    asm::isb();
    Ok(())
}
