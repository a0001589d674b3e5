//! Size probe, without the sampler: `size-sampler` with the playback replaced by a hash of
//! the pieces' start positions (the blob is loaded and the hash logged as there).

#![no_std]
#![no_main]
#![forbid(unsafe_code)]

use cortex_m_rt::entry;
use strak_qemu::jobs::{BLOB_JOBS, NumberFormat};
use strak_qemu::play::OutBits;
use strak_qemu::{PIECES, exit_failure, exit_success, mix};
use strak_trajectory::{Number, Path, Q40};

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
    let mut hash = 0_u64;
    for piece in path.pieces() {
        for axis in piece.axes() {
            hash = mix(hash, axis.position.to_out().out_bits());
        }
    }
    defmt::println!("{=u64}", hash);
    exit_success()
}
