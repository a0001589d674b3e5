//! The forward-differencing tick: the only code [`Sampler::next`](super::Sampler::next) runs
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
//! Which kernel a format uses is chosen by [`Number`]'s hidden `tick_*` methods.

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

pub(crate) mod portable;
#[cfg(strak_thumb2)]
pub(crate) mod thumb2;
#[cfg(strak_vfp)]
pub(crate) mod vfp;
