//! Instructions per online solve, for `valgrind --tool=callgrind` (repeatable, unlike
//! wall-clock times on a shared machine): solves the first `n` random 3-axis moves of the
//! benchmark (`online_cases`, [`BENCH_SEED`], time synchronization) in `f32` or `f64`
//! inside the function `solve_all`, and prints the moves solved and the sum of the
//! durations' bits (the checksum the example firmware prints for the same moves).
//!
//! ```text
//! cargo build --release -p strak-bench --bin solves
//! valgrind --tool=callgrind --callgrind-out-file=cg.out target/release/solves f32 2000
//! callgrind_annotate --inclusive=yes cg.out | grep strak_trajectory
//! ```
//! Instructions per move: the inclusive `Ir` of `solves::solve_all` divided by the moves
//! printed; the other lines split it among the solver's steps.

use std::hint::black_box;
use std::process::ExitCode;

use strak_bench::online_cases::{BENCH_SEED, OnlineCase, online_cases};
use strak_trajectory::{MoveOptions, OnlineMove, Real};

/// Solves every move of `cases`; returns the moves solved and the sum of the durations'
/// bits, or the index of a move that did not solve.
#[inline(never)]
fn solve_all<R: Real>(cases: &[OnlineCase<R, 3>]) -> Result<(usize, u64), usize> {
    let options = MoveOptions::new();
    let mut bits = 0_u64;
    for (i, c) in cases.iter().enumerate() {
        let c = black_box(c);
        let m = OnlineMove::solve(&c.start, &c.target, &c.limits, &options).map_err(|_| i)?;
        bits = bits.wrapping_add(m.duration().to_f64().to_bits());
    }
    Ok((cases.len(), bits))
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let n = match args.get(1).map(|s| s.parse::<usize>()) {
        None => 2_000,
        Some(Ok(n)) => n,
        Some(Err(_)) => {
            eprintln!("usage: solves [f32|f64] [MOVES]");
            return ExitCode::FAILURE;
        }
    };
    let cases = online_cases::<3>(BENCH_SEED, false).take(n);
    let solved = match args.first().map_or("f32", String::as_str) {
        "f64" => solve_all(&cases.collect::<Vec<_>>()),
        "f32" => solve_all(&cases.filter_map(|c| c.in_f32()).collect::<Vec<_>>()),
        _ => {
            eprintln!("usage: solves [f32|f64] [MOVES]");
            return ExitCode::FAILURE;
        }
    };
    match solved {
        Ok((moves, bits)) => {
            println!("{moves} moves solved, duration bits summed: {bits:#018x}");
            ExitCode::SUCCESS
        }
        Err(i) => {
            eprintln!("move {i} did not solve");
            ExitCode::FAILURE
        }
    }
}
