//! Size probe, with the sampler: loads the fixed-point pick-and-place blob and plays it
//! through the tick handler ([`Player`], i.e. `Sampler`), logging one hash of the positions.
//! `size-baseline` is the same firmware without the sampler; `cargo xtask qemu` reports the
//! difference of their flash sizes as the sampler's cost.

#![no_std]
#![no_main]
#![forbid(unsafe_code)]

use cortex_m_rt::entry;
use strak_qemu::jobs::{BLOB_JOBS, Format};
use strak_qemu::play::{OutBits, Player};
use strak_qemu::{PIECES, exit_failure, exit_success, mix};
use strak_trajectory::{Path, Q40};

#[entry]
fn main() -> ! {
    let Some(job) = BLOB_JOBS
        .iter()
        .find(|j| j.format == Format::Fixed && j.axes == 3)
    else {
        exit_failure()
    };
    let Ok(path) = Path::<Q40, 3, PIECES>::from_bytes(job.blob) else {
        exit_failure()
    };
    let mut player = Player::new(&path, job.events);
    let mut hash = 0_u64;
    loop {
        let s = player.on_tick();
        for p in s.position {
            hash = mix(hash, p.out_bits());
        }
        if player.done() {
            break;
        }
    }
    defmt::println!("{=u64}", hash);
    exit_success()
}
