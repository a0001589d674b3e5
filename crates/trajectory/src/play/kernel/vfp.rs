//! The tick kernels for `f32` on Cortex-M cores with a single-precision FPU (Armv7E-M and
//! Armv8-M Mainline, hard-float ABI: `strak_vfp`, set by `build.rs`).
//!
//! Per axis: one `vldmia` of the nine state values ([`AxisState`] is `#[repr(C)]`, nine
//! consecutive `f32`), the sample values stored straight from the registers, the six
//! additions of [`portable::step_whole`](super::portable::step_whole) in its order, one
//! `vstmia` of the nine values back (the three constant differences are rewritten
//! unchanged). A position-only tick loads, steps and stores the position chain alone (four
//! values; the sampler catches the others up). The axes are unrolled (up to [`UNROLLED`]; more axes use the portable
//! kernel), so the tick has no loop and the sample's offsets are immediates.
//!
//! `vadd.f32` is the IEEE-754 single-precision addition the compiler emits for `+` on this
//! target (round to nearest, the FPSCR left as the runtime set it), so these kernels give
//! the portable kernel's bits; the firmware's bit-identity check against the host compares
//! them on every sample.
#![allow(unsafe_code)]

use core::arch::asm;
use core::mem::{MaybeUninit, align_of, offset_of, size_of};

use super::{UNROLLED, portable, unaligned};
use crate::num::Number;
use crate::path::view::piece_record_len;
use crate::path::{AxisState, Sample};

// The layout the assembly below hard-codes, checked at compile time: `vldmia`/`vstmia` of
// `s0`–`s8` move the nine `f32` of an axis in the order of `AxisState`'s fields (36 bytes,
// `s0` = position … `s8` = acceleration difference), the position-only kernel moves the
// first four, the state pointer steps by 36 bytes per axis, and a blob's piece record holds
// after its 4-byte tick count the same 36 bytes per axis, little-endian.
const _: () = {
    type S = AxisState<f32>;
    assert!(size_of::<S>() == 36 && align_of::<S>() == 4);
    assert!(offset_of!(S, position) == 0);
    assert!(offset_of!(S, delta1) == 4);
    assert!(offset_of!(S, delta2) == 8);
    assert!(offset_of!(S, delta3) == 12);
    assert!(offset_of!(S, velocity) == 16);
    assert!(offset_of!(S, velocity_delta1) == 20);
    assert!(offset_of!(S, velocity_delta2) == 24);
    assert!(offset_of!(S, acceleration) == 28);
    assert!(offset_of!(S, acceleration_delta) == 32);
    assert!(9 * <f32 as Number>::BYTES == size_of::<S>());
    assert!(piece_record_len::<f32>(3) == 4 + 3 * size_of::<S>());
    assert!(cfg!(target_endian = "little"));
    // The sample's arrays hold `f32` (4 bytes apart: `at`).
    assert!(size_of::<[f32; UNROLLED]>() == UNROLLED * 4);
    assert!(offset_of!(Sample<f32, 3>, position) % 4 == 0);
};

/// Byte offset of axis `K`'s value in one of the sample's arrays starting at `array`.
const fn at<const K: usize>(array: usize) -> usize {
    array + K * size_of::<f32>()
}

/// Loads the axis state at `{st}` into `s0`–`s8` (`p, Δ¹, Δ², Δ³, v, Δv¹, Δv², a, Δa`) and
/// stores its sample values `p`, `v`, `a` at `{o}` + `{x}`, `{v}`, `{a}`.
macro_rules! sample_asm {
    () => {
        concat!(
            "vldmia {st}, {{s0-s8}}\n",
            "vstr s0, [{o}, #{x}]\n",
            "vstr s4, [{o}, #{v}]\n",
            "vstr s7, [{o}, #{a}]\n",
        )
    };
}

/// Axis `K` of a full tick: sample values to `o`, step, state pointer `st` to the next axis.
///
/// # Safety
/// `*st` points to a readable and writable `AxisState<f32>`; `o` to a writable
/// `Sample<f32, A>`, `K < A`.
#[inline(always)]
unsafe fn axis_sample<const A: usize, const K: usize>(
    st: &mut *mut AxisState<f32>,
    o: *mut Sample<f32, A>,
) {
    // SAFETY: the caller's contract; the asm touches only the 36 bytes at `*st`, the three
    // sample slots of axis K, and s0–s8 (declared clobbered).
    unsafe {
        asm!(
            sample_asm!(),
            "vadd.f32 s0, s0, s1",
            "vadd.f32 s1, s1, s2",
            "vadd.f32 s2, s2, s3",
            "vadd.f32 s4, s4, s5",
            "vadd.f32 s5, s5, s6",
            "vadd.f32 s7, s7, s8",
            "vstmia {st}!, {{s0-s8}}",
            st = inout(reg) *st,
            o = in(reg) o,
            x = const at::<K>(offset_of!(Sample<f32, A>, position)),
            v = const at::<K>(offset_of!(Sample<f32, A>, velocity)),
            a = const at::<K>(offset_of!(Sample<f32, A>, acceleration)),
            out("s0") _, out("s1") _, out("s2") _, out("s3") _, out("s4") _,
            out("s5") _, out("s6") _, out("s7") _, out("s8") _,
            options(nostack),
        );
    }
}

/// Axis `K` of a position-only tick: the position to `o`, the position chain stepped (the
/// first three additions of [`axis_sample`]), `st` to the next axis.
///
/// # Safety
/// As [`axis_sample`], with `o` a writable `[f32; A]`.
#[inline(always)]
unsafe fn axis_position<const A: usize, const K: usize>(
    st: &mut *mut AxisState<f32>,
    o: *mut [f32; A],
) {
    // SAFETY: as in `axis_sample` (the first 16 bytes of the state).
    unsafe {
        asm!(
            "vldmia {st}, {{s0-s3}}",
            "vstr s0, [{o}, #{x}]",
            "vadd.f32 s0, s0, s1",
            "vadd.f32 s1, s1, s2",
            "vadd.f32 s2, s2, s3",
            "vstmia {st}, {{s0-s2}}",
            "add {st}, {st}, #{axis}",
            st = inout(reg) *st,
            o = in(reg) o,
            x = const at::<K>(0),
            axis = const size_of::<AxisState<f32>>(),
            out("s0") _, out("s1") _, out("s2") _, out("s3") _,
            options(nostack),
        );
    }
}

/// Axis `K` of a piece switch: sample values of the current state to `o`, then the next
/// piece's state `*nx` copied over it; both pointers move to the next axis.
///
/// # Safety
/// As [`axis_sample`], and `*nx` points to a readable `AxisState<f32>` not overlapping `*st`.
#[inline(always)]
unsafe fn axis_switch<const A: usize, const K: usize>(
    (st, nx): (&mut *mut AxisState<f32>, &mut *const AxisState<f32>),
    o: *mut Sample<f32, A>,
) {
    // SAFETY: as in `axis_sample`; the second load reads the 36 bytes at `*nx`.
    unsafe {
        asm!(
            sample_asm!(),
            "vldmia {nx}!, {{s0-s8}}",
            "vstmia {st}!, {{s0-s8}}",
            st = inout(reg) *st,
            nx = inout(reg) *nx,
            o = in(reg) o,
            x = const at::<K>(offset_of!(Sample<f32, A>, position)),
            v = const at::<K>(offset_of!(Sample<f32, A>, velocity)),
            a = const at::<K>(offset_of!(Sample<f32, A>, acceleration)),
            out("s0") _, out("s1") _, out("s2") _, out("s3") _, out("s4") _,
            out("s5") _, out("s6") _, out("s7") _, out("s8") _,
            options(nostack),
        );
    }
}

/// [`portable::tick_sample`] for `f32`.
#[inline(always)]
pub(crate) fn tick_sample<const A: usize>(
    state: &mut [AxisState<f32>; A],
    tick: u64,
) -> Sample<f32, A> {
    if A > UNROLLED {
        return portable::tick_sample(state, tick);
    }
    let mut out = MaybeUninit::<Sample<f32, A>>::uninit();
    let o = out.as_mut_ptr();
    let mut st = state.as_mut_ptr();
    // SAFETY: `st` walks the A states of `state` (exclusive borrow); `o` is the sample being
    // built. Every field is written: `tick` here, the three arrays' A values by the A axis
    // kernels (A ≤ UNROLLED), so `assume_init` is sound.
    unsafe {
        (&raw mut (*o).tick).write(tick);
        each_axis!(A, axis_sample, &mut st, o);
        out.assume_init()
    }
}

/// [`portable::tick_position`] for `f32`.
#[inline(always)]
pub(crate) fn tick_position<const A: usize>(state: &mut [AxisState<f32>; A]) -> [f32; A] {
    if A > UNROLLED {
        return portable::tick_position(state);
    }
    let mut out = MaybeUninit::<[f32; A]>::uninit();
    let o = out.as_mut_ptr();
    let mut st = state.as_mut_ptr();
    // SAFETY: as in `tick_sample`; the A axis kernels write all A positions.
    unsafe {
        each_axis!(A, axis_position, &mut st, o);
        out.assume_init()
    }
}

/// [`portable::switch_sample`] for `f32`.
#[inline(always)]
pub(crate) fn switch_sample<const A: usize>(
    state: &mut [AxisState<f32>; A],
    next: &[AxisState<f32>; A],
    tick: u64,
) -> Sample<f32, A> {
    if A > UNROLLED {
        return portable::switch_sample(state, next, tick);
    }
    let mut out = MaybeUninit::<Sample<f32, A>>::uninit();
    let o = out.as_mut_ptr();
    let mut st = state.as_mut_ptr();
    let mut nx = next.as_ptr();
    // SAFETY: as in `tick_sample`; `nx` walks `next` (a shared borrow, so it cannot overlap
    // the exclusively borrowed `state`).
    unsafe {
        (&raw mut (*o).tick).write(tick);
        each_axis!(A, axis_switch, (&mut st, &mut nx), o);
        out.assume_init()
    }
}

/// [`portable::switch_sample_bytes`] for `f32`: a record whose values are 4-byte aligned
/// is loaded with the word loads of [`switch_sample`] (the record holds the nine `f32` of
/// each axis in [`AxisState`]'s order, little-endian, as the state does in memory); any
/// other record is decoded by the portable kernel.
#[inline(always)]
pub(crate) fn switch_sample_bytes<const A: usize>(
    state: &mut [AxisState<f32>; A],
    next: &[u8],
    tick: u64,
) -> Sample<f32, A> {
    if !aligned_record::<A>(next) {
        return unaligned::switch_sample_bytes(state, next, tick);
    }
    let mut out = MaybeUninit::<Sample<f32, A>>::uninit();
    let o = out.as_mut_ptr();
    let mut st = state.as_mut_ptr();
    let mut nx = next.as_ptr().cast::<AxisState<f32>>();
    // SAFETY: as in `switch_sample`; `nx` points to at least `A · 36` readable bytes (the
    // length check), word-aligned as `vldmia` requires, in a shared borrow that cannot
    // overlap `state`. Any bits are a valid `f32`.
    unsafe {
        (&raw mut (*o).tick).write(tick);
        each_axis!(A, axis_switch, (&mut st, &mut nx), o);
        out.assume_init()
    }
}

/// Axis `K` of a position-only piece switch: the current position to `o`, then the next
/// piece's state `*nx` copied over the state; both pointers move to the next axis (four
/// instructions).
///
/// # Safety
/// As [`axis_switch`], with `o` a writable `[f32; A]`.
#[inline(always)]
unsafe fn axis_switch_position<const A: usize, const K: usize>(
    (st, nx): (&mut *mut AxisState<f32>, &mut *const AxisState<f32>),
    o: *mut [f32; A],
) {
    // SAFETY: as in `axis_switch` (axis K's slot of `*o`).
    unsafe {
        asm!(
            "vldr s0, [{st}]",
            "vstr s0, [{o}, #{x}]",
            "vldmia {nx}!, {{s0-s8}}",
            "vstmia {st}!, {{s0-s8}}",
            st = inout(reg) *st,
            nx = inout(reg) *nx,
            o = in(reg) o,
            x = const at::<K>(0),
            out("s0") _, out("s1") _, out("s2") _, out("s3") _, out("s4") _,
            out("s5") _, out("s6") _, out("s7") _, out("s8") _,
            options(nostack),
        );
    }
}

/// `true` when `next` holds the `A` states word-aligned, as `vldmia` reads them.
#[inline(always)]
fn aligned_record<const A: usize>(next: &[u8]) -> bool {
    A <= UNROLLED
        && next.len() >= A * size_of::<AxisState<f32>>()
        && next.as_ptr().addr().is_multiple_of(4)
}

/// [`portable::tick_native`] for `f32`: [`tick_sample`] written to `out` in place.
#[inline(always)]
pub(crate) fn tick_into<const A: usize>(
    state: &mut [AxisState<f32>; A],
    tick: u64,
    out: &mut Sample<f32, A>,
) {
    if A > UNROLLED {
        return portable::tick_native(state, tick, out);
    }
    out.tick = tick;
    let o: *mut Sample<f32, A> = out;
    let mut st = state.as_mut_ptr();
    // SAFETY: `st` walks the A states of `state` (exclusive borrow); `o` is the exclusively
    // borrowed `out`.
    unsafe {
        each_axis!(A, axis_sample, &mut st, o);
    }
}

/// [`portable::switch_native`] for `f32`: [`switch_sample`] written to `out` in place.
#[inline(always)]
pub(crate) fn switch_into<const A: usize>(
    state: &mut [AxisState<f32>; A],
    next: &[AxisState<f32>; A],
    tick: u64,
    out: &mut Sample<f32, A>,
) {
    if A > UNROLLED {
        return portable::switch_native(state, next, tick, out);
    }
    out.tick = tick;
    let o: *mut Sample<f32, A> = out;
    let mut st = state.as_mut_ptr();
    let mut nx = next.as_ptr();
    // SAFETY: as in `tick_into`; `nx` walks `next` (a shared borrow, so it cannot overlap
    // the exclusively borrowed `state`).
    unsafe {
        each_axis!(A, axis_switch, (&mut st, &mut nx), o);
    }
}

/// [`portable::switch_native_bytes`] for `f32`: a word-aligned record as in
/// [`switch_into`], any other by the portable kernel.
#[inline(always)]
pub(crate) fn switch_bytes_into<const A: usize>(
    state: &mut [AxisState<f32>; A],
    next: &[u8],
    tick: u64,
    out: &mut Sample<f32, A>,
) {
    if !aligned_record::<A>(next) {
        return unaligned::switch_native_bytes(state, next, tick, out);
    }
    out.tick = tick;
    let o: *mut Sample<f32, A> = out;
    let mut st = state.as_mut_ptr();
    let mut nx = next.as_ptr().cast::<AxisState<f32>>();
    // SAFETY: as in `switch_into`; `nx` points to at least `A · 36` readable bytes,
    // word-aligned (`aligned_record`), only read by `vldmia`. Any bits are a valid `f32`.
    unsafe {
        each_axis!(A, axis_switch, (&mut st, &mut nx), o);
    }
}

/// [`portable::switch_position`] for `f32`.
#[inline(always)]
pub(crate) fn switch_position<const A: usize>(
    state: &mut [AxisState<f32>; A],
    next: &[AxisState<f32>; A],
) -> [f32; A] {
    if A > UNROLLED {
        return portable::switch_position(state, next);
    }
    let mut out = MaybeUninit::<[f32; A]>::uninit();
    let o = out.as_mut_ptr();
    let mut st = state.as_mut_ptr();
    let mut nx = next.as_ptr();
    // SAFETY: as in `switch_into`; the A axis kernels write all A positions of `out`.
    unsafe {
        each_axis!(A, axis_switch_position, (&mut st, &mut nx), o);
        out.assume_init()
    }
}

/// [`portable::switch_position_bytes`] for `f32` (a word-aligned record as in
/// [`switch_position`], any other by the portable kernel).
#[inline(always)]
pub(crate) fn switch_position_bytes<const A: usize>(
    state: &mut [AxisState<f32>; A],
    next: &[u8],
) -> [f32; A] {
    if !aligned_record::<A>(next) {
        return unaligned::switch_position_bytes(state, next);
    }
    let mut out = MaybeUninit::<[f32; A]>::uninit();
    let o = out.as_mut_ptr();
    let mut st = state.as_mut_ptr();
    let mut nx = next.as_ptr().cast::<AxisState<f32>>();
    // SAFETY: as in `switch_bytes_into`; the A axis kernels write all A positions.
    unsafe {
        each_axis!(A, axis_switch_position, (&mut st, &mut nx), o);
        out.assume_init()
    }
}
