//! The tick kernels for [`Q40`] on Armv7-M and Armv8-M Mainline (Thumb-2: `strak_thumb2`,
//! set by `build.rs`), the Cortex-M3 among them.
//!
//! A `Q40` value is an `i64` ([`Q40`] is `#[repr(transparent)]`, [`AxisState`] `#[repr(C)]`:
//! 18 consecutive words per axis). Per axis: the position chain in one `ldm` (8 words), the
//! velocity chain in one, the acceleration chain in two `ldrd`; each 64-bit addition of
//! [`portable::step_whole`](super::portable::step_whole) is an `adds`/`adc` pair (exact, like
//! `Q40`'s wrapping `+`); the sample values are `Number::to_out`'s rounding
//! `(x + 2⁷) >> 8` into [`I32F32`]: five instructions and one `strd`. A position-only tick
//! steps the position chain alone (the sampler catches the others up). The axes are unrolled
//! (up to [`UNROLLED`]; more axes use the portable kernel). Integer arithmetic: the same bits
//! as the portable kernel by construction (checked on every sample by the firmware's
//! bit-identity run).
#![allow(unsafe_code)]

use core::arch::asm;
use core::mem::{MaybeUninit, align_of, offset_of, size_of};

use strak_curves::I32F32;
use strak_curves::fixed::types::I24F40;

use super::{UNROLLED, portable, unaligned};
use crate::num::{Number, Q40};
use crate::path::view::piece_record_len;
use crate::path::{AxisState, Sample};

/// Bytes from an axis's state to its velocity (after `p`, `Δ¹`, `Δ²`, `Δ³`).
const POSITION_CHAIN: usize = 4 * size_of::<Q40>();

// The layout the assembly below hard-codes, checked at compile time: an axis is 18 words,
// the position chain (`p`, `Δ¹`, `Δ²`, `Δ³`) in the first 32 bytes (one `ldm` of eight
// registers), the velocity chain in the next 24 (`ldm` of six from `POSITION_CHAIN`), the
// acceleration and its difference 8 and 16 bytes after the velocity's second difference
// (`ldrd … #8`, `#16`), 72 bytes per axis in all (the `#24` step, the piece switch's 8 + 10
// words); `I32F32` positions are stored 8 bytes apart; a blob's piece record holds after
// its 4-byte tick count the same 72 bytes per axis, little-endian.
const _: () = {
    type S = AxisState<Q40>;
    assert!(size_of::<Q40>() == 8 && size_of::<S>() == 72 && align_of::<S>() <= 8);
    assert!(offset_of!(S, position) == 0);
    assert!(offset_of!(S, delta1) == 8);
    assert!(offset_of!(S, delta2) == 16);
    assert!(offset_of!(S, delta3) == 24);
    assert!(offset_of!(S, velocity) == POSITION_CHAIN && POSITION_CHAIN == 32);
    assert!(offset_of!(S, velocity_delta1) == 40);
    assert!(offset_of!(S, velocity_delta2) == 48);
    assert!(offset_of!(S, acceleration) == 56);
    assert!(offset_of!(S, acceleration_delta) == 64);
    assert!(9 * <Q40 as Number>::BYTES == size_of::<S>());
    assert!(piece_record_len::<Q40>(3) == 4 + 3 * size_of::<S>());
    assert!(cfg!(target_endian = "little"));
    assert!(size_of::<I32F32>() == 8);
    // The native sample's values are the accumulator's 8 bytes, stored with `strd` at
    // offsets below 1 024 (its range of immediates) and word-aligned.
    assert!(size_of::<I24F40>() == 8 && align_of::<Sample<I24F40, UNROLLED>>() >= 4);
    assert!(size_of::<Sample<I24F40, UNROLLED>>() < 1024);
};

/// `I32F32` from its two words (`lo`, `hi`).
#[inline(always)]
fn out(lo: u32, hi: u32) -> I32F32 {
    I32F32::from_bits((i64::from(hi.cast_signed()) << 32) | i64::from(lo))
}

/// `Number::to_out` for `Q40` in assembly: the 64-bit value in `$slo`/`$shi` rounded to
/// `I32F32`, `(x + 2⁷) >> 8` (arithmetic), into `$lo`/`$hi` (five instructions; source and
/// destination may be the same registers).
macro_rules! round_asm {
    ($lo:literal, $hi:literal, $slo:literal, $shi:literal) => {
        concat!(
            "adds ",
            $lo,
            ", ",
            $slo,
            ", #128\n",
            "adc ",
            $hi,
            ", ",
            $shi,
            ", #0\n",
            "lsr ",
            $lo,
            ", ",
            $lo,
            ", #8\n",
            "orr ",
            $lo,
            ", ",
            $lo,
            ", ",
            $hi,
            ", lsl #24\n",
            "asr ",
            $hi,
            ", ",
            $hi,
            ", #8\n",
        )
    };
}

/// The position chain of the axis at `{st}`: `p += Δ¹; Δ¹ += Δ²; Δ² += Δ³` (computed from
/// the last difference up, so each sum still reads the old values), then the old `p`
/// rounded to `I32F32` in `r0` (low word) and `r1`, the registers that held it: the kernel
/// needs no register beyond the eight it loads. Touches the first 32 bytes at `{st}`.
macro_rules! position_chain_asm {
    () => {
        concat!(
            "ldm {st}, {{r0, r1, r2, r3, r4, r5, r8, r9}}\n",
            "adds r8, r4, r8\n",
            "adc r9, r5, r9\n",
            "adds r4, r2, r4\n",
            "adc r5, r3, r5\n",
            "adds r2, r0, r2\n",
            "adc r3, r1, r3\n",
            "stm {st}, {{r2, r3, r4, r5, r8, r9}}\n",
            round_asm!("r0", "r1", "r0", "r1"),
        )
    };
}

/// [`position_chain_asm`] for the axis at `st`; returns the old `p` as `I32F32`.
///
/// # Safety
/// `st` points to a readable and writable `AxisState<Q40>`.
#[inline(always)]
unsafe fn position_chain(st: *mut AxisState<Q40>) -> I32F32 {
    let (lo, hi): (u32, u32);
    // SAFETY: the caller's contract; the asm touches only the first 32 bytes at `st` and
    // the declared registers.
    unsafe {
        asm!(
            position_chain_asm!(),
            st = in(reg) st,
            out("r0") lo,
            out("r1") hi,
            out("r2") _, out("r3") _, out("r4") _, out("r5") _, out("r8") _, out("r9") _,
            options(nostack),
        );
    }
    out(lo, hi)
}

/// The velocity and acceleration chains of the axis whose velocity is at `*st`
/// (`v += Δv¹; Δv¹ += Δv²; a += Δa`); returns the old `v` and `a` as `I32F32` and moves
/// `*st` to the next axis.
///
/// # Safety
/// `*st` points to the velocity of a readable and writable `AxisState<Q40>`.
#[inline(always)]
unsafe fn derivative_chains(st: &mut *mut AxisState<Q40>) -> (I32F32, I32F32) {
    let (vlo, vhi, alo, ahi): (u32, u32, u32, u32);
    // SAFETY: the caller's contract; the asm touches only the last 40 bytes of the state.
    unsafe {
        asm!(
            "ldm {st}, {{r0, r1, r2, r3, r4, r5}}",
            round_asm!("{vlo}", "{vhi}", "r0", "r1"),
            "adds r0, r0, r2",
            "adc r1, r1, r3",
            "adds r2, r2, r4",
            "adc r3, r3, r5",
            "stmia {st}!, {{r0, r1, r2, r3}}",
            "ldrd r0, r1, [{st}, #8]",
            "ldrd r2, r3, [{st}, #16]",
            round_asm!("{alo}", "{ahi}", "r0", "r1"),
            "adds r0, r0, r2",
            "adc r1, r1, r3",
            "strd r0, r1, [{st}, #8]",
            "add {st}, {st}, #24",
            st = inout(reg) *st,
            vlo = out(reg) vlo,
            vhi = out(reg) vhi,
            alo = out(reg) alo,
            ahi = out(reg) ahi,
            out("r0") _, out("r1") _, out("r2") _, out("r3") _, out("r4") _, out("r5") _,
            options(nostack),
        );
    }
    (out(vlo, vhi), out(alo, ahi))
}

/// Axis `K` of a full tick into `s`.
///
/// # Safety
/// `*st` points to axis `K` of a readable and writable `[AxisState<Q40>; A]`.
#[inline(always)]
unsafe fn axis_sample<const A: usize, const K: usize>(
    st: &mut *mut AxisState<Q40>,
    s: &mut Sample<I32F32, A>,
) {
    // SAFETY: the caller's contract; the velocity starts after the four position values.
    let (x, (v, a)) = unsafe {
        let x = position_chain(*st);
        *st = st.wrapping_byte_add(POSITION_CHAIN);
        (x, derivative_chains(st))
    };
    if let (Some(px), Some(pv), Some(pa)) = (
        s.position.get_mut(K),
        s.velocity.get_mut(K),
        s.acceleration.get_mut(K),
    ) {
        (*px, *pv, *pa) = (x, v, a);
    }
}

/// Axis `K` of a position-only tick: the position chain only, the position stored to `o`
/// straight from the kernel (values returned in registers would wait in spilled registers
/// for the end of the tick).
///
/// # Safety
/// As [`axis_sample`], with `o` a writable `[I32F32; A]`.
#[inline(always)]
unsafe fn axis_position<const A: usize, const K: usize>(
    st: &mut *mut AxisState<Q40>,
    o: *mut [I32F32; A],
) {
    // SAFETY: the caller's contract: the 32 bytes at `*st` and axis K's slot of `o`.
    unsafe {
        asm!(
            position_chain_asm!(),
            "strd r0, r1, [{o}, #{x}]",
            st = in(reg) *st,
            o = in(reg) o,
            x = const K * size_of::<I32F32>(),
            out("r0") _, out("r1") _, out("r2") _, out("r3") _, out("r4") _, out("r5") _,
            out("r8") _, out("r9") _,
            options(nostack),
        );
    }
    // The velocity and acceleration chains are left for the sampler to catch up.
    *st = st.wrapping_byte_add(size_of::<AxisState<Q40>>());
}

/// Axis `K` of a piece switch: the sample values of the current state into `s`, then the
/// next piece's state `*nx` copied over it (18 words in four transfers); both pointers move
/// to the next axis.
///
/// # Safety
/// As [`axis_sample`], and `*nx` points to a readable `AxisState<Q40>` not overlapping `*st`.
#[inline(always)]
unsafe fn axis_switch<const A: usize, const K: usize>(
    (st, nx): (&mut *mut AxisState<Q40>, &mut *const AxisState<Q40>),
    s: &mut Sample<I32F32, A>,
) {
    let (xlo, xhi, vlo, vhi, alo, ahi): (u32, u32, u32, u32, u32, u32);
    // SAFETY: the caller's contract; the first asm reads 72 bytes at `*st`, the second
    // copies 72 bytes from `*nx` to `*st`.
    unsafe {
        asm!(
            "ldrd {xlo}, {xhi}, [{st}]",
            "ldrd {vlo}, {vhi}, [{st}, #32]",
            "ldrd {alo}, {ahi}, [{st}, #56]",
            round_asm!("{xlo}", "{xhi}", "{xlo}", "{xhi}"),
            round_asm!("{vlo}", "{vhi}", "{vlo}", "{vhi}"),
            round_asm!("{alo}", "{ahi}", "{alo}", "{ahi}"),
            st = in(reg) *st,
            xlo = out(reg) xlo,
            xhi = out(reg) xhi,
            vlo = out(reg) vlo,
            vhi = out(reg) vhi,
            alo = out(reg) alo,
            ahi = out(reg) ahi,
            options(nostack, readonly),
        );
        asm!(
            "ldmia {nx}!, {{r0, r1, r2, r3, r4, r5, r8, r9}}",
            "stmia {st}!, {{r0, r1, r2, r3, r4, r5, r8, r9}}",
            "ldmia {nx}!, {{r0, r1, r2, r3, r4, r5, r8, r9, r12, lr}}",
            "stmia {st}!, {{r0, r1, r2, r3, r4, r5, r8, r9, r12, lr}}",
            st = inout(reg) *st,
            nx = inout(reg) *nx,
            out("r0") _, out("r1") _, out("r2") _, out("r3") _, out("r4") _, out("r5") _,
            out("r8") _, out("r9") _, out("r12") _, out("lr") _,
            options(nostack),
        );
    }
    if let (Some(px), Some(pv), Some(pa)) = (
        s.position.get_mut(K),
        s.velocity.get_mut(K),
        s.acceleration.get_mut(K),
    ) {
        (*px, *pv, *pa) = (out(xlo, xhi), out(vlo, vhi), out(alo, ahi));
    }
}

/// A sample at `tick` with every value zero (each is overwritten by the axis kernels; the
/// compiler drops the zeroing, since the values come out of registers).
#[inline(always)]
fn blank<const A: usize>(tick: u64) -> Sample<I32F32, A> {
    Sample {
        tick,
        position: [I32F32::ZERO; A],
        velocity: [I32F32::ZERO; A],
        acceleration: [I32F32::ZERO; A],
    }
}

/// [`portable::tick_sample`] for `Q40`.
#[inline(always)]
pub(crate) fn tick_sample<const A: usize>(
    state: &mut [AxisState<Q40>; A],
    tick: u64,
) -> Sample<I32F32, A> {
    if A > UNROLLED {
        return portable::tick_sample(state, tick);
    }
    let mut s = blank(tick);
    let mut st = state.as_mut_ptr();
    // SAFETY: `st` walks the A states of `state` (exclusive borrow), one axis per call.
    unsafe {
        each_axis!(A, axis_sample, &mut st, &mut s);
    }
    s
}

/// [`portable::tick_position`] for `Q40`.
#[inline(always)]
pub(crate) fn tick_position<const A: usize>(state: &mut [AxisState<Q40>; A]) -> [I32F32; A] {
    if A > UNROLLED {
        return portable::tick_position(state);
    }
    let mut out = MaybeUninit::<[I32F32; A]>::uninit();
    let o = out.as_mut_ptr();
    let mut st = state.as_mut_ptr();
    // SAFETY: `st` walks the A states of `state` (exclusive borrow); the A axis kernels
    // write all A positions of `out` (A ≤ UNROLLED), so `assume_init` is sound.
    unsafe {
        each_axis!(A, axis_position, &mut st, o);
        out.assume_init()
    }
}

/// [`portable::switch_sample`] for `Q40`.
#[inline(always)]
pub(crate) fn switch_sample<const A: usize>(
    state: &mut [AxisState<Q40>; A],
    next: &[AxisState<Q40>; A],
    tick: u64,
) -> Sample<I32F32, A> {
    if A > UNROLLED {
        return portable::switch_sample(state, next, tick);
    }
    let mut s = blank(tick);
    let mut st = state.as_mut_ptr();
    let mut nx = next.as_ptr();
    // SAFETY: as in `tick_sample`; `nx` walks `next` (a shared borrow, so it cannot overlap
    // the exclusively borrowed `state`).
    unsafe {
        each_axis!(A, axis_switch, (&mut st, &mut nx), &mut s);
    }
    s
}

/// [`portable::switch_sample_bytes`] for `Q40`: a record whose values are 4-byte aligned is
/// copied with the `ldm`/`stm` of [`switch_sample`] (the record holds the nine `i64` of each
/// axis in [`AxisState`]'s order, little-endian, as the state does in memory); any other
/// record is decoded by the portable kernel.
#[inline(always)]
pub(crate) fn switch_sample_bytes<const A: usize>(
    state: &mut [AxisState<Q40>; A],
    next: &[u8],
    tick: u64,
) -> Sample<I32F32, A> {
    if !aligned_record::<A>(next) {
        return unaligned::switch_sample_bytes(state, next, tick);
    }
    let mut s = blank(tick);
    let mut st = state.as_mut_ptr();
    let mut nx = next.as_ptr().cast::<AxisState<Q40>>();
    // SAFETY: as in `switch_sample`; `nx` points to at least `A · 72` readable bytes (the
    // length check), word-aligned as `ldmia` requires (it is only read by `ldmia`, never
    // dereferenced as an `AxisState`), in a shared borrow that cannot overlap `state`. Any
    // bits are a valid `Q40`.
    unsafe {
        each_axis!(A, axis_switch, (&mut st, &mut nx), &mut s);
    }
    s
}

/// Byte offset of axis `K`'s value in the native sample's array at `array`.
const fn at<const K: usize>(array: usize) -> usize {
    array + K * size_of::<I24F40>()
}

/// Axis `K` of a full tick in the accumulator's format: the old `p`, `v` and `a` stored to
/// `o` straight from the loaded registers (no rounding), the six additions of
/// [`portable::step_whole`], the state written back; `*st` moves to the next axis.
///
/// Per axis: `ldmia` of the position chain (8 words, `st` then points to the velocity),
/// one `strd`, three `adds`/`adc` pairs, `stmdb` of the chain back; `ldm` of the velocity
/// chain and the acceleration (10 words), two `strd`, three pairs, `stmia` back (unchanged
/// values rewritten): 19 instructions.
///
/// # Safety
/// `*st` points to axis `K` of a readable and writable `[AxisState<Q40>; A]`, `o` to a
/// writable `Sample<I24F40, A>`, `K < A`.
#[inline(always)]
unsafe fn axis_native<const A: usize, const K: usize>(
    st: &mut *mut AxisState<Q40>,
    o: *mut Sample<I24F40, A>,
) {
    // SAFETY: the caller's contract; the asm touches the 72 bytes at `*st`, axis K's three
    // slots of `*o`, and the declared registers.
    unsafe {
        asm!(
            "ldmia {st}!, {{r0, r1, r2, r3, r4, r5, r8, r9}}",
            "strd r0, r1, [{o}, #{x}]",
            "adds r0, r0, r2",
            "adc r1, r1, r3",
            "adds r2, r2, r4",
            "adc r3, r3, r5",
            "adds r4, r4, r8",
            "adc r5, r5, r9",
            "stmdb {st}, {{r0, r1, r2, r3, r4, r5, r8, r9}}",
            "ldm {st}, {{r0, r1, r2, r3, r4, r5, r8, r9, r12, lr}}",
            "strd r0, r1, [{o}, #{v}]",
            "strd r8, r9, [{o}, #{a}]",
            "adds r0, r0, r2",
            "adc r1, r1, r3",
            "adds r2, r2, r4",
            "adc r3, r3, r5",
            "adds r8, r8, r12",
            "adc r9, r9, lr",
            "stmia {st}!, {{r0, r1, r2, r3, r4, r5, r8, r9, r12, lr}}",
            st = inout(reg) *st,
            o = in(reg) o,
            x = const at::<K>(offset_of!(Sample<I24F40, A>, position)),
            v = const at::<K>(offset_of!(Sample<I24F40, A>, velocity)),
            a = const at::<K>(offset_of!(Sample<I24F40, A>, acceleration)),
            out("r0") _, out("r1") _, out("r2") _, out("r3") _, out("r4") _, out("r5") _,
            out("r8") _, out("r9") _, out("r12") _, out("lr") _,
            options(nostack),
        );
    }
}

/// Copies the 18 words of the axis state at `{nx}` to `{st}` in two transfers of nine
/// (`r0`–`r5`, `r8`, `r9`, `r12`), moving both pointers to the next axis.
macro_rules! copy_axis_asm {
    () => {
        concat!(
            "ldmia {nx}!, {{r0, r1, r2, r3, r4, r5, r8, r9, r12}}\n",
            "stmia {st}!, {{r0, r1, r2, r3, r4, r5, r8, r9, r12}}\n",
            "ldmia {nx}!, {{r0, r1, r2, r3, r4, r5, r8, r9, r12}}\n",
            "stmia {st}!, {{r0, r1, r2, r3, r4, r5, r8, r9, r12}}\n",
        )
    };
}

/// Axis `K` of a piece switch in the accumulator's format: `p`, `v` and `a` of the current
/// state stored to `o`, then the next piece's state `*nx` copied over it; both pointers move
/// to the next axis (10 instructions).
///
/// # Safety
/// As [`axis_native`], and `*nx` points to a readable `AxisState<Q40>` (word-aligned) not
/// overlapping `*st`.
#[inline(always)]
unsafe fn axis_switch_native<const A: usize, const K: usize>(
    (st, nx): (&mut *mut AxisState<Q40>, &mut *const AxisState<Q40>),
    o: *mut Sample<I24F40, A>,
) {
    // SAFETY: the caller's contract: reads 72 bytes at `*nx` and `*st`, writes 72 at `*st`
    // and axis K's slots of `*o`.
    unsafe {
        asm!(
            "ldrd r0, r1, [{st}]",
            "ldrd r2, r3, [{st}, #32]",
            "ldrd r4, r5, [{st}, #56]",
            "strd r0, r1, [{o}, #{x}]",
            "strd r2, r3, [{o}, #{v}]",
            "strd r4, r5, [{o}, #{a}]",
            copy_axis_asm!(),
            st = inout(reg) *st,
            nx = inout(reg) *nx,
            o = in(reg) o,
            x = const at::<K>(offset_of!(Sample<I24F40, A>, position)),
            v = const at::<K>(offset_of!(Sample<I24F40, A>, velocity)),
            a = const at::<K>(offset_of!(Sample<I24F40, A>, acceleration)),
            out("r0") _, out("r1") _, out("r2") _, out("r3") _, out("r4") _, out("r5") _,
            out("r8") _, out("r9") _, out("r12") _,
            options(nostack),
        );
    }
}

/// Axis `K` of a position-only piece switch: the current `p` rounded to `I32F32` into `o`,
/// then the next piece's state `*nx` copied over the state (11 instructions).
///
/// # Safety
/// As [`axis_switch_native`], with `o` a writable `[I32F32; A]`.
#[inline(always)]
unsafe fn axis_switch_position<const A: usize, const K: usize>(
    (st, nx): (&mut *mut AxisState<Q40>, &mut *const AxisState<Q40>),
    o: *mut [I32F32; A],
) {
    // SAFETY: as in `axis_switch_native` (axis K's slot of `*o`).
    unsafe {
        asm!(
            "ldrd r0, r1, [{st}]",
            round_asm!("r0", "r1", "r0", "r1"),
            "strd r0, r1, [{o}, #{x}]",
            copy_axis_asm!(),
            st = inout(reg) *st,
            nx = inout(reg) *nx,
            o = in(reg) o,
            x = const K * size_of::<I32F32>(),
            out("r0") _, out("r1") _, out("r2") _, out("r3") _, out("r4") _, out("r5") _,
            out("r8") _, out("r9") _, out("r12") _,
            options(nostack),
        );
    }
}

/// `true` when `next` holds the `A` states word-aligned, as `ldmia` reads them.
#[inline(always)]
fn aligned_record<const A: usize>(next: &[u8]) -> bool {
    A <= UNROLLED
        && next.len() >= A * size_of::<AxisState<Q40>>()
        && next.as_ptr().addr().is_multiple_of(4)
}

/// [`portable::tick_native`] for `Q40`.
#[inline(always)]
pub(crate) fn tick_native<const A: usize>(
    state: &mut [AxisState<Q40>; A],
    tick: u64,
    out: &mut Sample<I24F40, A>,
) {
    if A > UNROLLED {
        return portable::tick_native(state, tick, out);
    }
    out.tick = tick;
    let o: *mut Sample<I24F40, A> = out;
    let mut st = state.as_mut_ptr();
    // SAFETY: `st` walks the A states of `state` (exclusive borrow), one axis per call; `o`
    // is the exclusively borrowed `out`.
    unsafe {
        each_axis!(A, axis_native, &mut st, o);
    }
}

/// [`portable::switch_native`] for `Q40`.
#[inline(always)]
pub(crate) fn switch_native<const A: usize>(
    state: &mut [AxisState<Q40>; A],
    next: &[AxisState<Q40>; A],
    tick: u64,
    out: &mut Sample<I24F40, A>,
) {
    if A > UNROLLED {
        return portable::switch_native(state, next, tick, out);
    }
    out.tick = tick;
    let o: *mut Sample<I24F40, A> = out;
    let mut st = state.as_mut_ptr();
    let mut nx = next.as_ptr();
    // SAFETY: as in `tick_native`; `nx` walks `next` (a shared borrow, so it cannot overlap
    // the exclusively borrowed `state`).
    unsafe {
        each_axis!(A, axis_switch_native, (&mut st, &mut nx), o);
    }
}

/// [`portable::switch_native_bytes`] for `Q40`: a word-aligned record is copied as in
/// [`switch_native`] (see [`switch_sample_bytes`]), any other is decoded by the portable
/// kernel.
#[inline(always)]
pub(crate) fn switch_native_bytes<const A: usize>(
    state: &mut [AxisState<Q40>; A],
    next: &[u8],
    tick: u64,
    out: &mut Sample<I24F40, A>,
) {
    if !aligned_record::<A>(next) {
        return unaligned::switch_native_bytes(state, next, tick, out);
    }
    out.tick = tick;
    let o: *mut Sample<I24F40, A> = out;
    let mut st = state.as_mut_ptr();
    let mut nx = next.as_ptr().cast::<AxisState<Q40>>();
    // SAFETY: as in `switch_native`; `nx` points to at least `A · 72` readable bytes,
    // word-aligned (`aligned_record`), only read by `ldmia`/`ldrd`. Any bits are a valid
    // `Q40`.
    unsafe {
        each_axis!(A, axis_switch_native, (&mut st, &mut nx), o);
    }
}

/// [`portable::switch_position`] for `Q40`.
#[inline(always)]
pub(crate) fn switch_position<const A: usize>(
    state: &mut [AxisState<Q40>; A],
    next: &[AxisState<Q40>; A],
) -> [I32F32; A] {
    if A > UNROLLED {
        return portable::switch_position(state, next);
    }
    let mut out = MaybeUninit::<[I32F32; A]>::uninit();
    let o = out.as_mut_ptr();
    let mut st = state.as_mut_ptr();
    let mut nx = next.as_ptr();
    // SAFETY: as in `switch_native`; the A axis kernels write all A positions of `out`.
    unsafe {
        each_axis!(A, axis_switch_position, (&mut st, &mut nx), o);
        out.assume_init()
    }
}

/// [`portable::switch_position_bytes`] for `Q40` (a word-aligned record as in
/// [`switch_position`], any other by the portable kernel).
#[inline(always)]
pub(crate) fn switch_position_bytes<const A: usize>(
    state: &mut [AxisState<Q40>; A],
    next: &[u8],
) -> [I32F32; A] {
    if !aligned_record::<A>(next) {
        return unaligned::switch_position_bytes(state, next);
    }
    let mut out = MaybeUninit::<[I32F32; A]>::uninit();
    let o = out.as_mut_ptr();
    let mut st = state.as_mut_ptr();
    let mut nx = next.as_ptr().cast::<AxisState<Q40>>();
    // SAFETY: as in `switch_native_bytes`; the A axis kernels write all A positions.
    unsafe {
        each_axis!(A, axis_switch_position, (&mut st, &mut nx), o);
        out.assume_init()
    }
}
