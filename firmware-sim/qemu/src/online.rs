//! The online solver on the device: the host benchmark's random 3-axis moves
//! ([`cases`], the same file as the host's), each solved with [`OnlineMove::solve_in_place`]
//! (time synchronization) in `f32` or `f64`, its instructions counted.

#[path = "../../../bench/src/online_cases.rs"]
pub mod cases;

use core::hint::black_box;

use strak_trajectory::{MoveOptions, OnlineMove, Real};

use crate::counter::{Calibration, WideCounter};
use cases::{BENCH_SEED, OnlineCase};

/// One solve, as firmware makes it: into a move kept in place.
#[inline(never)]
fn solve<R: Real>(m: &mut OnlineMove<R, 3>, c: &OnlineCase<R, 3>, options: &MoveOptions) -> bool {
    m.solve_in_place(&c.start, &c.target, &c.limits, options)
        .is_ok()
}

/// Solves the first `counts.len()` moves of [`BENCH_SEED`] in `R` (`narrow` makes a move of
/// `R` from the `f64` move), writing each solve's instructions into `counts`. Returns the
/// index of the first move that did not solve, if one did not, and the sum of the
/// durations' bits (`f64::to_bits`, wrapping), which the host computes alike.
pub fn count_solves<R: Real>(
    counter: &WideCounter,
    cal: &Calibration,
    narrow: impl Fn(&OnlineCase<f64, 3>) -> Option<OnlineCase<R, 3>>,
    counts: &mut [u32],
) -> Result<u64, usize> {
    let options = MoveOptions::new();
    let moves = || cases::online_cases::<3>(BENCH_SEED, false).map(|c| narrow(&c));
    // the move the solves write into: the first one, solved once before the counting
    let first = moves().next().flatten().ok_or(0_usize)?;
    let mut m = OnlineMove::solve(&first.start, &first.target, &first.limits, &options)
        .map_err(|_| 0_usize)?;
    let mut bits = 0_u64;
    for ((i, slot), c) in counts.iter_mut().enumerate().zip(moves()) {
        let c = black_box(c.ok_or(i)?);
        let (n, solved) = counter.counts(|| solve(black_box(&mut m), &c, &options));
        if !solved {
            return Err(i);
        }
        *slot = u32::try_from(cal.instructions_wide(n)).unwrap_or(u32::MAX);
        bits = bits.wrapping_add(m.duration().to_f64().to_bits());
    }
    Ok(bits)
}
