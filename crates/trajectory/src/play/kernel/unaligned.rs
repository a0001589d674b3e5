//! The portable piece switches from blob records at addresses the assembly kernels cannot
//! load from (not word-aligned), out of line: they decode value by value through a
//! stack copy, and inlined they would give every switch their frame.

use super::{Kernel, portable};
use crate::path::{AxisState, Sample};

/// [`portable::switch_sample_bytes`], out of line.
#[inline(never)]
#[cold]
pub(crate) fn switch_sample_bytes<N: Kernel, const A: usize>(
    state: &mut [AxisState<N>; A],
    next: &[u8],
    tick: u64,
) -> Sample<N::Out, A> {
    portable::switch_sample_bytes(state, next, tick)
}

/// [`portable::switch_position_bytes`], out of line.
#[inline(never)]
#[cold]
pub(crate) fn switch_position_bytes<N: Kernel, const A: usize>(
    state: &mut [AxisState<N>; A],
    next: &[u8],
) -> [N::Out; A] {
    portable::switch_position_bytes(state, next)
}

/// [`portable::switch_native_bytes`], out of line.
#[inline(never)]
#[cold]
pub(crate) fn switch_native_bytes<N: Kernel, const A: usize>(
    state: &mut [AxisState<N>; A],
    next: &[u8],
    tick: u64,
    out: &mut Sample<N::Native, A>,
) {
    portable::switch_native_bytes(state, next, tick, out);
}
