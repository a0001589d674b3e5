//! Prints the corner comparison of `BENCHMARKS.md` ([`strak_bench::corners`]).
//!
//! ```text
//! cargo run --release -p strak-bench --bin corners
//! ```

fn main() {
    if std::env::args().any(|a| a == "--stream") {
        for (name, start, moves, tolerance) in strak_bench::corners::cases() {
            let (duration, rate, _) = strak_bench::corners::streamed(start, &moves, tolerance);
            println!("{name}: streamed {duration:.3} s, {rate:.0} moves/s");
        }
        return;
    }
    print!("{}", strak_bench::corners::section());
}
