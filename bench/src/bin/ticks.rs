//! Instructions per sample of playback, for `valgrind --tool=callgrind` (repeatable, unlike
//! wall-clock times on a shared machine): plays the bench's n = 1024 path (3 axes) to its
//! end `REPEATS` times, by `Sampler::next()` (`next`), by `Sampler::fill` in batches of
//! 1024 (`fill`) or by `Sampler::fill_positions` in batches of 1024 (`positions`), in `f32`,
//! `f64` or `q40`, inside the function `play`, and prints the samples played and a checksum
//! (of the last position of every batch).
//!
//! ```text
//! cargo build --release -p strak-bench --bin ticks
//! valgrind --tool=callgrind --callgrind-out-file=cg.out target/release/ticks fill f64
//! callgrind_annotate --inclusive=yes --threshold=100 cg.out | grep 'ticks::play'
//! ```
//! Instructions per sample: the inclusive `Ir` of `ticks::play` divided by the samples
//! printed (building the paths, outside `play`, costs far more and is left out).

use std::hint::black_box;

use strak_bench::fixture::{PIECES, strak_paths};
use strak_curves::Scalar;
use strak_trajectory::{Kernel, Path, Sample, Sampler};

/// Whole-path playbacks per run.
const REPEATS: usize = 20;

/// Samples per batch.
const BATCH: usize = 1024;

/// How a run plays.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Mode {
    Next,
    Fill,
    Positions,
}

/// Plays `path` to its end `REPEATS` times; returns the samples and a checksum.
#[inline(never)]
fn play<N: Kernel>(path: &Path<N, 3, PIECES>, mode: Mode) -> (u64, u64) {
    let mut buf = vec![Sample::splat(<N::Out as Scalar>::ZERO); BATCH];
    let mut positions = vec![[<N::Out as Scalar>::ZERO; 3]; BATCH];
    let (mut samples, mut sum) = (0_u64, 0_u64);
    for _ in 0..REPEATS {
        let mut s = Sampler::new(black_box(path));
        while !s.is_finished() {
            let last = match mode {
                Mode::Positions => {
                    s.fill_positions(&mut positions);
                    black_box(&positions)[BATCH - 1][0]
                }
                Mode::Fill => {
                    s.fill(&mut buf);
                    black_box(&buf)[BATCH - 1].position[0]
                }
                Mode::Next => {
                    for b in &mut buf {
                        *b = s.next();
                    }
                    black_box(&buf)[BATCH - 1].position[0]
                }
            };
            sum = sum.wrapping_add(last.to_f64().to_bits());
            samples += BATCH as u64;
        }
    }
    (samples, sum)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let mode = match args.get(1).map(String::as_str) {
        Some("fill") => Mode::Fill,
        Some("positions") => Mode::Positions,
        _ => Mode::Next,
    };
    let paths = strak_paths(1024);
    let (n, sum) = match args.get(2).map(String::as_str) {
        Some("f32") => play(&paths.f32, mode),
        Some("q40") => play(&paths.q40, mode),
        _ => play(&paths.f64, mode),
    };
    println!("{n} samples, checksum {sum:#x}");
}
