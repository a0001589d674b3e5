//! Stack high-water marks by painting: [`measure`] (and [`usage`]) fills the unused stack
//! below the current stack pointer with [`PAINT`], runs an operation, and scans from the
//! stack's bottom upwards for the deepest word the operation overwrote.
//!
//! The stack is the RAM between the end of the statics (`_stack_end` of cortex-m-rt's
//! `link.x`: `.data`, `.bss` and `.uninit` lie below it) and the initial stack pointer
//! (`_stack_start`, the top of the `RAM` region of the binary's `memory.x`). The firmware
//! has no heap.
//!
//! Painting measures what was *written*: a frame the operation reserves but never writes
//! below its deepest store is not counted, and a store of the paint value itself at the
//! deepest word would hide that one word. Both err by at most the unwritten part of the
//! deepest frame; a call-graph walk of the disassembly (the sum of the frame sizes along
//! the deepest path) is the upper bound.
//!
//! The library's `unsafe` code is all here: `paint` and `scan` write and read the words of
//! the unused stack, and the linker's symbols are declared in an `unsafe extern` block.

use core::ptr;
use core::sync::atomic::{Ordering, compiler_fence};

/// The word the unused stack is painted with (cortex-m-rt's `paint-stack` uses the same).
pub const PAINT: u32 = 0xCCCC_CCCC;

// The symbols of cortex-m-rt's `link.x`; only their addresses are used.
unsafe extern "C" {
    /// The end of the statics (`.data`, `.bss`, `.uninit`): the lowest address of the stack.
    static _stack_end: u32;
    /// The initial stack pointer: the highest address of the stack (exclusive).
    static _stack_start: u32;
    /// The start of the `RAM` region.
    static _ram_start: u32;
}

/// The lowest address of the stack (the end of the statics).
pub fn bottom() -> usize {
    (&raw const _stack_end).addr()
}

/// The initial stack pointer (the stack's top, exclusive).
pub fn top() -> usize {
    (&raw const _stack_start).addr()
}

/// The bytes of RAM the statics take (`.data`, `.bss`, `.uninit`): from the start of the
/// `RAM` region to [`bottom`].
pub fn statics() -> usize {
    bottom().saturating_sub((&raw const _ram_start).addr())
}

/// The current stack pointer.
#[inline(always)]
pub fn sp() -> usize {
    cortex_m::register::msp::read() as usize
}

/// The bytes of stack in use at the caller: from [`top`] down to the current stack pointer.
#[inline(always)]
pub fn depth() -> usize {
    top().saturating_sub(sp())
}

/// Paints the words of `[from, to)` with [`PAINT`] (`from` and `to` 4-byte aligned).
///
/// Inlined into [`usage`] and so into its caller: it needs no stack below that frame.
#[inline(always)]
fn paint(from: usize, to: usize) {
    let mut at = from;
    while at < to {
        let word = ptr::with_exposed_provenance_mut::<u32>(at);
        // SAFETY: `from` is `_stack_end` (rounded up to a word) and `to` the stack pointer of
        // the frame that `usage` is inlined into, so `[from, to)` lies in the `RAM` region
        // between the statics and the current frame, and holds no live value: the statics end
        // at `from`, nothing of this thread lives below its stack pointer, and the firmware has
        // no heap. An exception taken meanwhile stacks its frame below the stack pointer and
        // has returned (its frame dead) before this code runs on. `at` is word-aligned: both
        // bounds are (`from` rounded up, the stack pointer 8-byte aligned and rounded down).
        unsafe { word.write_volatile(PAINT) };
        at += 4;
    }
}

/// The lowest address in `[from, to)` whose word is not [`PAINT`] (`to` when every word is).
///
/// Inlined into [`usage`], as [`paint`].
#[inline(always)]
fn scan(from: usize, to: usize) -> usize {
    let mut at = from;
    while at < to {
        let word = ptr::with_exposed_provenance::<u32>(at);
        // SAFETY: as in `paint`: `[from, to)` is aligned RAM of the stack below the measuring
        // frame, holding no live value of this thread; reading it has no effect.
        if unsafe { word.read_volatile() } != PAINT {
            return at;
        }
        at += 4;
    }
    to
}

/// What an operation used, measured by [`usage`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, defmt::Format)]
pub struct Usage {
    /// The stack high-water mark in bytes: how far below the stack pointer of the
    /// measurement the operation wrote.
    pub stack: usize,
    /// The RAM the firmware needed while the operation ran, in bytes: the statics, the stack
    /// above the measurement (the caller's frames, the values they hold) and [`Usage::stack`].
    pub ram: usize,
}

/// Runs `op` and returns its result with its stack high-water mark in bytes: how far below
/// the stack pointer of this call `op` wrote (its call, its frames and everything it calls;
/// the value it returns lies in the caller's frame and is not counted).
///
/// Not reentrant: a `measure` inside `op` repaints the stack below itself and hides what
/// `op` used before it from the outer measurement.
///
/// ```ignore
/// let (path, stack_bytes) = stack::measure(|| Path::<Q40, 3, 256>::from_bytes(BLOB));
/// ```
#[inline(always)]
pub fn measure<R>(op: impl FnOnce() -> R) -> (R, usize) {
    let (r, used) = usage(op);
    (r, used.stack)
}

/// [`measure`], with the RAM the firmware needed while `op` ran.
///
/// Inlined into its caller: the stack pointer read is that of the caller's frame, which holds
/// the result, so that no frame of the measurement itself holds a copy of it.
#[inline(always)]
pub fn usage<R>(op: impl FnOnce() -> R) -> (R, Usage) {
    let here = sp() & !3;
    let from = (bottom() + 3) & !3;
    paint(from, here);
    compiler_fence(Ordering::SeqCst);
    let r = run(op);
    compiler_fence(Ordering::SeqCst);
    let deepest = scan(from, here);
    let used = Usage {
        stack: here - deepest,
        ram: statics() + (top() - deepest),
    };
    (r, used)
}

/// Calls `op` from a frame of its own below the caller of [`usage`], so that inlining `op`
/// cannot move its locals into that caller's frame (above the painted region).
#[inline(never)]
fn run<R>(op: impl FnOnce() -> R) -> R {
    op()
}

/// Logs a measurement in the output protocol: `STACK <operation> <stack bytes> <ram bytes>`.
pub fn log(operation: &str, used: Usage) {
    defmt::println!(
        "STACK {=str} {=usize} {=usize}",
        operation,
        used.stack,
        used.ram
    );
}
