//! Instructions per sample of playback, for `valgrind --tool=callgrind` (repeatable, unlike
//! wall-clock times on a shared machine): plays the bench's n = 1024 path (3 axes) to its
//! end `REPEATS` times, by `Sampler::next()` (`next`) or by `Sampler::fill` in batches of
//! 1024 (`fill`), in `f32`, `f64` or `q40`, inside the function `play`, and prints the
//! samples played and a checksum (of the last sample of every batch).
//!
//! ```text
//! cargo build --release -p strak-bench --bin ticks
//! valgrind --tool=callgrind --toggle-collect='*play*' target/release/ticks fill f64
//! ```
//! Instructions per sample: the collected `Ir` divided by the samples printed.

use std::hint::black_box;

use strak_bench::fixture::{PIECES, strak_paths};
use strak_curves::Scalar;
use strak_trajectory::{Kernel, Path, Sample, Sampler};

/// Whole-path playbacks per run.
const REPEATS: usize = 20;

/// Plays `path` to its end `REPEATS` times; returns the samples and a checksum.
#[inline(never)]
fn play<N: Kernel>(path: &Path<N, 3, PIECES>, batch: bool) -> (u64, u64) {
    let mut buf = vec![Sample::splat(<N::Out as Scalar>::ZERO); 1024];
    let (mut samples, mut sum) = (0_u64, 0_u64);
    for _ in 0..REPEATS {
        let mut s = Sampler::new(black_box(path));
        while !s.is_finished() {
            if batch {
                s.fill(&mut buf);
            } else {
                for b in &mut buf {
                    *b = s.next();
                }
            }
            let last = black_box(&buf)[buf.len() - 1];
            sum = sum.wrapping_add(last.position[0].to_f64().to_bits());
            samples += buf.len() as u64;
        }
    }
    (samples, sum)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let batch = args.get(1).is_some_and(|a| a == "fill");
    let paths = strak_paths(1024);
    let (n, sum) = match args.get(2).map(String::as_str) {
        Some("f32") => play(&paths.f32, batch),
        Some("q40") => play(&paths.q40, batch),
        _ => play(&paths.f64, batch),
    };
    println!("{n} samples, checksum {sum:#x}");
}
