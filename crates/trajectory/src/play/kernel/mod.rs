//! The forward-differencing tick: the only code [`Sampler::next`](crate::Sampler::next) runs
//! on an ordinary tick, written once in portable Rust ([`portable`]) and, where a target's
//! compiler output is measurably slower than the instruction set allows, once more in
//! hand-scheduled assembly with the very same additions in the very same order (so the same
//! bits; the QEMU bit-identity check of `cargo xtask qemu` compares every sample with the
//! host's).
//!
//! Why assembly on Cortex-M: a tick reads the nine state values of every axis and writes six
//! back. The compiler moves them one register at a time (`vldr`/`vstr`, 27 loads and 18
//! stores for 3 axes before a single addition); Armv7-M moves a whole axis in one
//! `vldm`/`vstm`.
//! Which kernel a format uses is chosen by its implementation of [`Kernel`].

use core::fmt;

#[cfg(strak_thumb2)]
use strak_curves::I32F32;
use strak_curves::fixed::types::I24F40;

use crate::num::{Number, Q40};
use crate::path::{AxisState, Sample};

/// Axes the assembly kernels handle unrolled (more axes use the portable kernel).
#[cfg(strak_thumb2)]
const UNROLLED: usize = 8;

/// Calls `$f::<A, K>(args)` for `K = 0 .. A` (A ≤ [`UNROLLED`]), unrolled: the conditions are
/// constants, so the kernels have no loop and their offsets are immediates.
#[cfg(strak_thumb2)]
macro_rules! each_axis {
    ($A:ident, $f:ident, $($arg:expr),*) => {
        if $A > 0 { $f::<$A, 0>($($arg),*); }
        if $A > 1 { $f::<$A, 1>($($arg),*); }
        if $A > 2 { $f::<$A, 2>($($arg),*); }
        if $A > 3 { $f::<$A, 3>($($arg),*); }
        if $A > 4 { $f::<$A, 4>($($arg),*); }
        if $A > 5 { $f::<$A, 5>($($arg),*); }
        if $A > 6 { $f::<$A, 6>($($arg),*); }
        if $A > 7 { $f::<$A, 7>($($arg),*); }
    };
}

mod check;
pub(crate) mod portable;
#[cfg(strak_thumb2)]
pub(crate) mod thumb2;
#[cfg(strak_thumb2)]
mod unaligned;
#[cfg(strak_vfp)]
pub(crate) mod vfp;

/// The tick kernels of a number format: what [`Sampler`](crate::Sampler) runs on a tick,
/// portable Rust unless the format has a faster kernel on the target (hand-scheduled
/// Thumb-2 for [`Q40`] on Armv7-M and Armv8-M Mainline, VFP for `f32` where the hard-float
/// ABI has a single-precision FPU), with the same additions in the same order, so the same
/// bits on every target.
///
/// The trait is **sealed**: it is implemented for `f32`, `f64` and [`Q40`], the formats
/// of [`Number`] (itself sealed), and cannot be implemented outside this crate. Code that
/// is generic over the number format and plays paths bounds it by `Kernel` (which implies
/// [`Number`]); apart from [`Kernel::Native`] and [`Kernel::native_to_out`] its methods are
/// the sampler's internals.
///
/// ```
/// use strak_trajectory::{Kernel, PathView, Q40, Sampler};
///
/// fn first_position<N: Kernel>(path: PathView<'_, N, 2>) -> [N::Out; 2] {
///     Sampler::new(path).next_position()
/// }
/// # let _ = first_position::<Q40>;
/// ```
pub trait Kernel: Number {
    /// The sample type in the accumulator's own format, as
    /// [`Sampler::next_into`](crate::Sampler::next_into) delivers it: `f32` and `f64`
    /// themselves, [`I24F40`] for [`Q40`] (the accumulator's 64 bits, 40 of them
    /// fractional: no rounding).
    type Native: Copy + Default + PartialEq + fmt::Debug + Send + Sync + 'static;

    /// Zero in [`Kernel::Native`].
    const NATIVE_ZERO: Self::Native;

    /// The value [`Sampler::next`](crate::Sampler::next) delivers for the value
    /// [`Sampler::next_into`](crate::Sampler::next_into) delivers: the identity for floats,
    /// for `Q40` the rounding of [`Number::to_out`] (`I24F40` to [`I32F32`](strak_curves::I32F32)
    /// to nearest, raw `+ 2⁷` shifted right by 8).
    ///
    /// ```
    /// use strak_curves::{I32F32, fixed::types::I24F40};
    /// use strak_trajectory::{Kernel, Q40};
    /// let x = I24F40::from_bits(0x180); // 1.5 · 2⁻³²
    /// assert_eq!(Q40::native_to_out(x), I32F32::from_bits(2)); // to nearest, ties up
    /// assert_eq!(<f32 as Kernel>::native_to_out(0.25), 0.25);
    /// ```
    fn native_to_out(v: Self::Native) -> Self::Out;

    /// Crate-internal: the value in [`Kernel::Native`] (the same bits).
    #[doc(hidden)]
    fn to_native(self) -> Self::Native;

    /// Crate-internal: a sample-type value in [`Kernel::Native`] (exact: `native_to_out`
    /// gives it back).
    #[doc(hidden)]
    fn native_from_out(v: Self::Out) -> Self::Native;

    /// Crate-internal: the value of the same bits as `v`.
    #[doc(hidden)]
    fn from_native(v: Self::Native) -> Self;

    /// Not part of the API: the check that firmware makes on its target. Runs every entry
    /// point of this format's tick kernels (a tick with the full sample, positions only and
    /// in [`Kernel::Native`]; a piece switch of each, from RAM and from a blob record at an
    /// aligned and at an odd address) and of the portable kernel on `state` (`next`: the
    /// next piece) and names the first entry point whose output or resulting state
    /// differs, bit for bit (`A` ≤ 8).
    #[doc(hidden)]
    fn check_kernels<const A: usize>(
        state: &[AxisState<Self>; A],
        next: &[AxisState<Self>; A],
        tick: u64,
    ) -> Result<(), &'static str> {
        check::run(state, next, tick)
    }

    /// Crate-internal: the sample of `state` at `tick`, then one forward-differencing step
    /// of every axis.
    #[doc(hidden)]
    #[inline(always)]
    fn tick_sample<const A: usize>(
        state: &mut [AxisState<Self>; A],
        tick: u64,
    ) -> Sample<Self::Out, A> {
        portable::tick_sample(state, tick)
    }

    /// Crate-internal: [`Kernel::tick_sample`]'s positions and step.
    #[doc(hidden)]
    #[inline(always)]
    fn tick_position<const A: usize>(state: &mut [AxisState<Self>; A]) -> [Self::Out; A] {
        portable::tick_position(state)
    }

    /// Crate-internal: the sample of `state` at `tick`, then `state = *next` (a piece
    /// switch).
    #[doc(hidden)]
    #[inline(always)]
    fn switch_sample<const A: usize>(
        state: &mut [AxisState<Self>; A],
        next: &[AxisState<Self>; A],
        tick: u64,
    ) -> Sample<Self::Out, A> {
        portable::switch_sample(state, next, tick)
    }

    /// Crate-internal: the sample of `state` at `tick`, then `state` read from the `9·A`
    /// little-endian values of a blob's piece record (a piece switch from a blob).
    #[doc(hidden)]
    #[inline(always)]
    fn switch_sample_bytes<const A: usize>(
        state: &mut [AxisState<Self>; A],
        next: &[u8],
        tick: u64,
    ) -> Sample<Self::Out, A> {
        portable::switch_sample_bytes(state, next, tick)
    }

    /// Crate-internal: [`Kernel::switch_sample`]'s positions (the state is replaced whole).
    #[doc(hidden)]
    #[inline(always)]
    fn switch_position<const A: usize>(
        state: &mut [AxisState<Self>; A],
        next: &[AxisState<Self>; A],
    ) -> [Self::Out; A] {
        portable::switch_position(state, next)
    }

    /// Crate-internal: [`Kernel::switch_sample_bytes`]'s positions.
    #[doc(hidden)]
    #[inline(always)]
    fn switch_position_bytes<const A: usize>(
        state: &mut [AxisState<Self>; A],
        next: &[u8],
    ) -> [Self::Out; A] {
        portable::switch_position_bytes(state, next)
    }

    /// Crate-internal: [`Kernel::tick_sample`] in [`Kernel::Native`], written to `out`.
    #[doc(hidden)]
    #[inline(always)]
    fn tick_native<const A: usize>(
        state: &mut [AxisState<Self>; A],
        tick: u64,
        out: &mut Sample<Self::Native, A>,
    ) {
        portable::tick_native(state, tick, out);
    }

    /// Crate-internal: [`Kernel::switch_sample`] in [`Kernel::Native`], written to `out`.
    #[doc(hidden)]
    #[inline(always)]
    fn switch_native<const A: usize>(
        state: &mut [AxisState<Self>; A],
        next: &[AxisState<Self>; A],
        tick: u64,
        out: &mut Sample<Self::Native, A>,
    ) {
        portable::switch_native(state, next, tick, out);
    }

    /// Crate-internal: [`Kernel::switch_sample_bytes`] in [`Kernel::Native`], written to
    /// `out`.
    #[doc(hidden)]
    #[inline(always)]
    fn switch_native_bytes<const A: usize>(
        state: &mut [AxisState<Self>; A],
        next: &[u8],
        tick: u64,
        out: &mut Sample<Self::Native, A>,
    ) {
        portable::switch_native_bytes(state, next, tick, out);
    }
}

impl Kernel for f64 {
    type Native = f64;
    const NATIVE_ZERO: f64 = 0.0;
    #[inline(always)]
    fn native_to_out(v: f64) -> f64 {
        v
    }
    #[inline(always)]
    fn to_native(self) -> f64 {
        self
    }
    #[inline(always)]
    fn native_from_out(v: f64) -> f64 {
        v
    }
    #[inline(always)]
    fn from_native(v: f64) -> f64 {
        v
    }
}

impl Kernel for f32 {
    type Native = f32;
    const NATIVE_ZERO: f32 = 0.0;
    #[inline(always)]
    fn native_to_out(v: f32) -> f32 {
        v
    }
    #[inline(always)]
    fn to_native(self) -> f32 {
        self
    }
    #[inline(always)]
    fn native_from_out(v: f32) -> f32 {
        v
    }
    #[inline(always)]
    fn from_native(v: f32) -> f32 {
        v
    }
    #[cfg(strak_vfp)]
    #[inline(always)]
    fn tick_sample<const A: usize>(state: &mut [AxisState<f32>; A], tick: u64) -> Sample<f32, A> {
        vfp::tick_sample(state, tick)
    }
    #[cfg(strak_vfp)]
    #[inline(always)]
    fn tick_position<const A: usize>(state: &mut [AxisState<f32>; A]) -> [f32; A] {
        vfp::tick_position(state)
    }
    #[cfg(strak_vfp)]
    #[inline(always)]
    fn switch_sample<const A: usize>(
        state: &mut [AxisState<f32>; A],
        next: &[AxisState<f32>; A],
        tick: u64,
    ) -> Sample<f32, A> {
        vfp::switch_sample(state, next, tick)
    }
    #[cfg(strak_vfp)]
    #[inline(always)]
    fn switch_sample_bytes<const A: usize>(
        state: &mut [AxisState<f32>; A],
        next: &[u8],
        tick: u64,
    ) -> Sample<f32, A> {
        vfp::switch_sample_bytes(state, next, tick)
    }
    #[cfg(strak_vfp)]
    #[inline(always)]
    fn switch_position<const A: usize>(
        state: &mut [AxisState<f32>; A],
        next: &[AxisState<f32>; A],
    ) -> [f32; A] {
        vfp::switch_position(state, next)
    }
    #[cfg(strak_vfp)]
    #[inline(always)]
    fn switch_position_bytes<const A: usize>(
        state: &mut [AxisState<f32>; A],
        next: &[u8],
    ) -> [f32; A] {
        vfp::switch_position_bytes(state, next)
    }
    #[cfg(strak_vfp)]
    #[inline(always)]
    fn tick_native<const A: usize>(
        state: &mut [AxisState<f32>; A],
        tick: u64,
        out: &mut Sample<f32, A>,
    ) {
        vfp::tick_into(state, tick, out);
    }
    #[cfg(strak_vfp)]
    #[inline(always)]
    fn switch_native<const A: usize>(
        state: &mut [AxisState<f32>; A],
        next: &[AxisState<f32>; A],
        tick: u64,
        out: &mut Sample<f32, A>,
    ) {
        vfp::switch_into(state, next, tick, out);
    }
    #[cfg(strak_vfp)]
    #[inline(always)]
    fn switch_native_bytes<const A: usize>(
        state: &mut [AxisState<f32>; A],
        next: &[u8],
        tick: u64,
        out: &mut Sample<f32, A>,
    ) {
        vfp::switch_bytes_into(state, next, tick, out);
    }
}

impl Kernel for Q40 {
    type Native = I24F40;
    const NATIVE_ZERO: I24F40 = I24F40::ZERO;
    #[inline(always)]
    fn native_to_out(v: I24F40) -> Self::Out {
        Q40::from_bits(v.to_bits()).to_out()
    }
    #[inline(always)]
    fn to_native(self) -> I24F40 {
        I24F40::from_bits(self.to_bits())
    }
    #[inline(always)]
    fn native_from_out(v: Self::Out) -> I24F40 {
        I24F40::from_bits(Q40::from_out(v).to_bits())
    }
    #[inline(always)]
    fn from_native(v: I24F40) -> Q40 {
        Q40::from_bits(v.to_bits())
    }
    #[cfg(strak_thumb2)]
    #[inline(always)]
    fn tick_sample<const A: usize>(
        state: &mut [AxisState<Q40>; A],
        tick: u64,
    ) -> Sample<I32F32, A> {
        thumb2::tick_sample(state, tick)
    }
    #[cfg(strak_thumb2)]
    #[inline(always)]
    fn tick_position<const A: usize>(state: &mut [AxisState<Q40>; A]) -> [I32F32; A] {
        thumb2::tick_position(state)
    }
    #[cfg(strak_thumb2)]
    #[inline(always)]
    fn switch_sample<const A: usize>(
        state: &mut [AxisState<Q40>; A],
        next: &[AxisState<Q40>; A],
        tick: u64,
    ) -> Sample<I32F32, A> {
        thumb2::switch_sample(state, next, tick)
    }
    #[cfg(strak_thumb2)]
    #[inline(always)]
    fn switch_sample_bytes<const A: usize>(
        state: &mut [AxisState<Q40>; A],
        next: &[u8],
        tick: u64,
    ) -> Sample<I32F32, A> {
        thumb2::switch_sample_bytes(state, next, tick)
    }
    #[cfg(strak_thumb2)]
    #[inline(always)]
    fn switch_position<const A: usize>(
        state: &mut [AxisState<Q40>; A],
        next: &[AxisState<Q40>; A],
    ) -> [I32F32; A] {
        thumb2::switch_position(state, next)
    }
    #[cfg(strak_thumb2)]
    #[inline(always)]
    fn switch_position_bytes<const A: usize>(
        state: &mut [AxisState<Q40>; A],
        next: &[u8],
    ) -> [I32F32; A] {
        thumb2::switch_position_bytes(state, next)
    }
    #[cfg(strak_thumb2)]
    #[inline(always)]
    fn tick_native<const A: usize>(
        state: &mut [AxisState<Q40>; A],
        tick: u64,
        out: &mut Sample<I24F40, A>,
    ) {
        thumb2::tick_native(state, tick, out);
    }
    #[cfg(strak_thumb2)]
    #[inline(always)]
    fn switch_native<const A: usize>(
        state: &mut [AxisState<Q40>; A],
        next: &[AxisState<Q40>; A],
        tick: u64,
        out: &mut Sample<I24F40, A>,
    ) {
        thumb2::switch_native(state, next, tick, out);
    }
    #[cfg(strak_thumb2)]
    #[inline(always)]
    fn switch_native_bytes<const A: usize>(
        state: &mut [AxisState<Q40>; A],
        next: &[u8],
        tick: u64,
        out: &mut Sample<I24F40, A>,
    ) {
        thumb2::switch_native_bytes(state, next, tick, out);
    }
}
