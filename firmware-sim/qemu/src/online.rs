//! The online solver on the device: the host benchmark's random 3-axis moves
//! ([`cases`], the same file as the host's), each solved with [`OnlineMove::solve_in_place`]
//! (time synchronization) in `f32` or `f64`, its instructions counted.

#[path = "../../../bench/src/online_cases.rs"]
pub mod cases;

use core::hint::black_box;

use strak_trajectory::{MoveOptions, OnlineMove, Real, solve_axis};

use crate::counter::{Calibration, WideCounter};
use crate::kernel_check::XorShift;
use cases::{BENCH_SEED, OnlineCase};

/// One solve, as firmware makes it: into a move kept in place.
#[inline(never)]
fn solve<R: Real>(m: &mut OnlineMove<R, 3>, c: &OnlineCase<R, 3>, options: &MoveOptions) -> bool {
    m.solve_in_place(&c.start, &c.target, &c.limits, options)
        .is_ok()
}

/// Random values for [`check_root`].
pub const ROOTS: u32 = 65_536;

/// The solver's `f32` square root ([`Real::root`]: the FPU's `vsqrt.f32` on the Cortex-M4F)
/// against the software one (`Scalar::sqrt`, `libm::sqrtf`), bit for bit: on special values
/// (±0, negatives, subnormals, the largest, infinities, NaN) and on [`ROOTS`] random bit
/// patterns. Returns the values compared, or the first whose roots differ (its bits).
///
/// # Errors
/// The bits of the first value whose two roots differ.
pub fn check_root() -> Result<u32, u32> {
    use strak_curves::Scalar;
    let special = [
        0.0_f32,
        -0.0,
        -1.0,
        f32::MIN_POSITIVE,
        f32::from_bits(1),
        f32::MAX,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
        2.0,
        0.25,
    ];
    let mut rng = XorShift::new(0x2545_f491_4f6c_dd1d);
    #[allow(clippy::cast_possible_truncation)]
    let random = (0..ROOTS).map(|_| f32::from_bits(rng.next_u64() as u32));
    let mut n = 0;
    for x in special.into_iter().chain(random) {
        if Real::root(x).to_bits() != Scalar::sqrt(x).to_bits() {
            return Err(x.to_bits());
        }
        n += 1;
    }
    Ok(n)
}

/// The first step of a solve alone: each axis's time-optimal motion and the durations it
/// can take, without the common duration.
#[inline(never)]
fn solve_axes<R: Real>(c: &OnlineCase<R, 3>) -> bool {
    (0..3).all(|i| solve_axis(&c.start[i], &c.target[i], &c.limits[i]).is_ok())
}

/// Counts the first step of each of the first `counts.len()` moves of [`BENCH_SEED`] in `R`
/// (the three axes solved alone, [`solve_axis`]), writing its instructions into `counts`:
/// the rest of a solve's count is the synchronization. Returns the index of the first move
/// whose axes did not solve, if one did not.
pub fn count_axis_solves<R: Real>(
    counter: &WideCounter,
    cal: &Calibration,
    narrow: impl Fn(&OnlineCase<f64, 3>) -> Option<OnlineCase<R, 3>>,
    counts: &mut [u32],
) -> Result<(), usize> {
    let moves = cases::online_cases::<3>(BENCH_SEED, false).map(|c| narrow(&c));
    for ((i, slot), c) in counts.iter_mut().enumerate().zip(moves) {
        let c = black_box(c.ok_or(i)?);
        let (n, solved) = counter.counts(|| solve_axes(black_box(&c)));
        if !solved {
            return Err(i);
        }
        *slot = u32::try_from(cal.instructions_wide(n)).unwrap_or(u32::MAX);
    }
    Ok(())
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
