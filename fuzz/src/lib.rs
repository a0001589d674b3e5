//! The bodies of strak's fuzz harnesses, as plain functions from bytes to a verdict.
//!
//! Each module is one target of `cargo xtask fuzz` (libFuzzer through cargo-fuzz, the
//! entry points in `fuzz_targets/`), and the replay test (`tests/tests/fuzz_replay.rs`, an
//! ordinary stable test) runs the same function on every checked-in input:
//!
//! | target       | input                         | invariants |
//! |--------------|-------------------------------|------------|
//! | [`blob`]     | a serialized path, its CRC also resealed | loading never panics; a path that loads serializes back to the same bytes, plays with finite samples, ends exactly on its end point, and its end agrees with its last piece |
//! | [`curves`]   | a curve constructor and its input, evaluation parameters | constructors never panic; a curve that builds evaluates to finite points and derivatives, and its analysis (arc length, flattening, continuity) returns in bounded time |
//! | [`pipeline`] | a curve, limits, planner, compiler and feed options | plan → compile → play never panics; samples are finite, the end is exact, and the limits hold in the samples (finite differences, [`check::Allowance`]) |
//! | [`job`]      | a strak-sim job or curve file (TOML) | parsing and checking never panic; a valid job's curve builds, plans, compiles and plays as in [`pipeline`] |
//!
//! Every input is decoded into a bounded case (a few points, small capacities, at most
//! [`check::MAX_TICKS`] ticks played), so that one execution takes milliseconds.
//!
//! ```
//! // An empty input decodes to the smallest case of each target, and passes.
//! for target in strak_fuzz::TARGETS {
//!     assert!((target.run)(&[]).is_ok(), "{}", target.name);
//! }
//! ```

// Every check is written `!(value <= limit)`, so that a NaN fails it.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod blob;
pub mod check;
pub mod curves;
mod decode;
pub mod dyn_curve;
pub mod job;
pub mod pipeline;
pub mod seeds;

use std::fmt;

/// An invariant a harness found broken: what, where, and the measured values.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Violation(pub String);

impl fmt::Display for Violation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Violation {}

/// A [`Violation`] from a formatted message.
macro_rules! violation {
    ($($arg:tt)*) => { $crate::Violation(format!($($arg)*)) };
}
pub(crate) use violation;

/// The environment variable naming violations to ignore while fuzzing: fragments of their
/// messages, separated by `;` (`cargo xtask fuzz --ignore FRAGMENT`). It masks a known
/// failure, so that a run goes on to find others; the replay test never ignores anything.
pub const IGNORE_VAR: &str = "STRAK_FUZZ_IGNORE";

/// `true` when `violation` contains a fragment of [`IGNORE_VAR`] (read once).
pub fn ignored(violation: &Violation) -> bool {
    static FRAGMENTS: std::sync::OnceLock<Vec<String>> = std::sync::OnceLock::new();
    FRAGMENTS
        .get_or_init(|| {
            std::env::var(IGNORE_VAR)
                .unwrap_or_default()
                .split(';')
                .map(str::trim)
                .filter(|f| !f.is_empty())
                .map(str::to_owned)
                .collect()
        })
        .iter()
        .any(|f| violation.0.contains(f.as_str()))
}

/// One fuzz target: its name (the cargo-fuzz binary and corpus folder) and its harness.
#[derive(Clone, Copy, Debug)]
pub struct Target {
    /// The name of the target (`fuzz_targets/<name>.rs`, `corpus/<name>/`).
    pub name: &'static str,
    /// The harness: `Ok` when every invariant holds for the input.
    pub run: fn(&[u8]) -> Result<(), Violation>,
}

/// Every fuzz target, in the order `cargo xtask fuzz` runs them.
pub const TARGETS: [Target; 4] = [
    Target {
        name: "blob",
        run: blob::run,
    },
    Target {
        name: "curves",
        run: curves::run,
    },
    Target {
        name: "pipeline",
        run: pipeline::run,
    },
    Target {
        name: "job",
        run: job::run,
    },
];
