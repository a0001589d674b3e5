//! The forward-differencing tick: the only code [`Sampler::next`](super::Sampler::next) runs
//! on an ordinary tick, written once in portable Rust ([`portable`]) and, where a target's
//! compiler output is measurably slower than the instruction set allows, once more in
//! hand-scheduled assembly with the very same additions in the very same order (so the same
//! bits; the QEMU bit-identity check of `cargo xtask qemu` compares every sample with the
//! host's).
//!
//! Why assembly on Cortex-M: a tick reads the nine state values of every axis and writes six
//! back. The compiler moves them one register at a time (`vldr`/`vstr`, 27 loads and 18
//! stores for 3 axes: over the 72-instruction budget before a single addition);
//! Armv7-M moves a whole axis in one `vldm`/`vstm` (measured: firmware-sim/qemu/ICOUNT.md).
//! Which kernel a format uses is chosen by [`Number`]'s hidden `tick_*` methods.

pub(crate) mod portable;
#[cfg(strak_thumb2)]
pub(crate) mod thumb2;
#[cfg(strak_vfp)]
pub(crate) mod vfp;
