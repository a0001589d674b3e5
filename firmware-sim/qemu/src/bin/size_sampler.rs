//! Size probe, with the sampler: loads the fixed-point pick-and-place blob and plays it
//! through the library's event player and `Sampler`, logging one hash of the positions.
//! `size-baseline` is the same firmware without the sampler; `cargo xtask qemu` reports the
//! difference of their flash sizes as the sampler's cost.

#![no_std]
#![no_main]
#![forbid(unsafe_code)]

use cortex_m_rt::entry;
use strak_qemu::jobs::{BLOB_JOBS, NumberFormat};
use strak_qemu::play::OutBits;
use strak_qemu::{PIECES, exit_failure, exit_success, mix};
use strak_trajectory::{EventPlayer, Path, Q40, Sampler};

#[entry]
fn main() -> ! {
    let Some(job) = BLOB_JOBS
        .iter()
        .find(|j| j.format == NumberFormat::Q40 && j.axes == 3)
    else {
        exit_failure()
    };
    let Ok(path) = Path::<Q40, 3, PIECES>::from_bytes(job.blob) else {
        exit_failure()
    };
    let mut player = EventPlayer::new(job.events, path.ticks());
    let mut sampler = Sampler::new(&path);
    let mut hash = 0_u64;
    while let Some(s) = player.step(&mut sampler) {
        for p in s.position {
            hash = mix(hash, p.out_bits());
        }
    }
    defmt::println!("{=u64}", hash);
    exit_success()
}
