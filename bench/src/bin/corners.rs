//! Prints the corner comparison of `BENCHMARKS.md` ([`strak_bench::corners`]).
//!
//! ```text
//! cargo run --release -p strak-bench --bin corners
//! ```

fn main() {
    print!("{}", strak_bench::corners::section());
}
