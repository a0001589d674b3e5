//! Host benchmarks of strak against its peers (criterion, `benches/peers.rs`) and the
//! generator of `BENCHMARKS.md` (`cargo run -p strak-bench --bin report`).

pub mod corners;
pub mod fixture;
pub mod online_cases;
pub mod report;
