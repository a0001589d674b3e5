//! The tick kernels in portable Rust (every target; the reference for the assembly ones).

use strak_curves::Scalar;

use super::Kernel;
use crate::num::Number;
use crate::path::view::decode_states;
use crate::path::{AxisState, Sample};

/// [`AxisState::step`] written as one read of the old state and one write of the new: the
/// same six additions of the same operands (every sum uses the old values, as `step` does),
/// so the same bits. Reading the whole state first keeps the compiler from pairing
/// neighbouring fields into overlapping vector loads of values the previous tick has just
/// stored (a store-forwarding stall on x86-64).
#[inline(always)]
pub(crate) fn step_whole<N: Number>(s: &mut AxisState<N>) {
    let o = *s;
    *s = AxisState {
        position: o.position + o.delta1,
        delta1: o.delta1 + o.delta2,
        delta2: o.delta2 + o.delta3,
        delta3: o.delta3,
        velocity: o.velocity + o.velocity_delta1,
        velocity_delta1: o.velocity_delta1 + o.velocity_delta2,
        velocity_delta2: o.velocity_delta2,
        acceleration: o.acceleration + o.acceleration_delta,
        acceleration_delta: o.acceleration_delta,
    };
}

/// The sample of the current state (tick `tick`), then one step of every axis.
#[inline(always)]
pub(crate) fn tick_sample<N: Number, const A: usize>(
    state: &mut [AxisState<N>; A],
    tick: u64,
) -> Sample<N::Out, A> {
    let mut sample = Sample {
        tick,
        position: [N::Out::ZERO; A],
        velocity: [N::Out::ZERO; A],
        acceleration: [N::Out::ZERO; A],
    };
    // One pass over the axes: read a state, write its sample values and its step
    // (`state.map(..)` per output array copied the whole state three times: measured on
    // the Cortex-M4F, firmware-sim/qemu/ICOUNT.md).
    let out = sample
        .position
        .iter_mut()
        .zip(sample.velocity.iter_mut())
        .zip(sample.acceleration.iter_mut());
    for (s, ((x, v), a)) in state.iter_mut().zip(out) {
        *x = s.position.to_out();
        *v = s.velocity.to_out();
        *a = s.acceleration.to_out();
        step_whole(s);
    }
    sample
}

/// The positions of the current state, then one step of every axis's position chain
/// (`p += Δ¹; Δ¹ += Δ²; Δ² += Δ³`, the additions of [`step_whole`]); the velocity and
/// acceleration chains are left for the sampler to catch up.
#[inline(always)]
pub(crate) fn tick_position<N: Number, const A: usize>(
    state: &mut [AxisState<N>; A],
) -> [N::Out; A] {
    let mut position = [N::Out::ZERO; A];
    for (s, x) in state.iter_mut().zip(position.iter_mut()) {
        *x = s.position.to_out();
        let (p, d1, d2, d3) = (s.position, s.delta1, s.delta2, s.delta3);
        s.position = p + d1;
        s.delta1 = d1 + d2;
        s.delta2 = d2 + d3;
    }
    position
}

/// The sample of the current state, then the state replaced by `next` (a piece switch with
/// no shift).
#[inline(always)]
pub(crate) fn switch_sample<N: Number, const A: usize>(
    state: &mut [AxisState<N>; A],
    next: &[AxisState<N>; A],
    tick: u64,
) -> Sample<N::Out, A> {
    let sample = sample_of(state, tick);
    *state = *next;
    sample
}

/// The sample of the current state, then the state replaced by the `9·A` little-endian
/// values in `next` (a piece switch from a blob's record; values missing from a short
/// slice read as 0, which validation rules out).
#[inline(always)]
pub(crate) fn switch_sample_bytes<N: Number, const A: usize>(
    state: &mut [AxisState<N>; A],
    next: &[u8],
    tick: u64,
) -> Sample<N::Out, A> {
    let sample = sample_of(state, tick);
    decode_states(next, state);
    sample
}

/// The sample of the current state at `tick`.
#[inline(always)]
fn sample_of<N: Number, const A: usize>(state: &[AxisState<N>; A], tick: u64) -> Sample<N::Out, A> {
    Sample {
        tick,
        position: state.map(|s| s.position.to_out()),
        velocity: state.map(|s| s.velocity.to_out()),
        acceleration: state.map(|s| s.acceleration.to_out()),
    }
}

/// The positions of the current state, then the state replaced by `next`.
#[inline(always)]
pub(crate) fn switch_position<N: Number, const A: usize>(
    state: &mut [AxisState<N>; A],
    next: &[AxisState<N>; A],
) -> [N::Out; A] {
    let position = state.map(|s| s.position.to_out());
    *state = *next;
    position
}

/// The positions of the current state, then the state replaced by the `9·A` little-endian
/// values in `next` (as [`switch_sample_bytes`]).
#[inline(always)]
pub(crate) fn switch_position_bytes<N: Number, const A: usize>(
    state: &mut [AxisState<N>; A],
    next: &[u8],
) -> [N::Out; A] {
    let position = state.map(|s| s.position.to_out());
    decode_states(next, state);
    position
}

/// The sample of the current state in the accumulator's format into `out`.
#[inline(always)]
fn native_of<N: Kernel, const A: usize>(
    state: &[AxisState<N>; A],
    tick: u64,
    out: &mut Sample<N::Native, A>,
) {
    out.tick = tick;
    let values = out
        .position
        .iter_mut()
        .zip(out.velocity.iter_mut())
        .zip(out.acceleration.iter_mut());
    for (s, ((x, v), a)) in state.iter().zip(values) {
        *x = s.position.to_native();
        *v = s.velocity.to_native();
        *a = s.acceleration.to_native();
    }
}

/// [`tick_sample`] in the accumulator's format, written to `out`.
#[inline(always)]
pub(crate) fn tick_native<N: Kernel, const A: usize>(
    state: &mut [AxisState<N>; A],
    tick: u64,
    out: &mut Sample<N::Native, A>,
) {
    native_of(state, tick, out);
    for s in state.iter_mut() {
        step_whole(s);
    }
}

/// [`switch_sample`] in the accumulator's format, written to `out`.
#[inline(always)]
pub(crate) fn switch_native<N: Kernel, const A: usize>(
    state: &mut [AxisState<N>; A],
    next: &[AxisState<N>; A],
    tick: u64,
    out: &mut Sample<N::Native, A>,
) {
    native_of(state, tick, out);
    *state = *next;
}

/// [`switch_sample_bytes`] in the accumulator's format, written to `out`.
#[inline(always)]
pub(crate) fn switch_native_bytes<N: Kernel, const A: usize>(
    state: &mut [AxisState<N>; A],
    next: &[u8],
    tick: u64,
    out: &mut Sample<N::Native, A>,
) {
    native_of(state, tick, out);
    decode_states(next, state);
}
