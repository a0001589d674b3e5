//! A SysTick-based counter of **instructions** (not cycles) under QEMU `-icount`.
//!
//! QEMU does not implement the DWT cycle counter (it reads 0). Run with
//! `-icount shift=N` and the virtual clock advances `2^N` ns per instruction, so SysTick on
//! the 25 MHz core clock (40 ns per count) counts **instructions**, not cycles,
//! deterministically. `shift=0` is too coarse (one count is 40 instructions);
//! `cargo xtask qemu` runs the `icount` firmware with [`ICOUNT_SHIFT`] = 10: one instruction is
//! 1024 ns = 25.6 counts, so a count difference converts to a whole number of instructions
//! with no rounding ambiguity ([`Calibration`] measures the ratio and the measurement's own
//! overhead with straight runs of `nop`s). Without `-icount` the counts follow the host's wall
//! clock and are not reproducible: the example firmware (`strak-qemu`) logs none of them.

use core::sync::atomic::{AtomicU32, Ordering, compiler_fence};

use cortex_m::peripheral::SYST;
use cortex_m::peripheral::syst::SystClkSource;

/// SysTick free-running down from its largest reload value (24 bits) on the core clock.
pub struct Counter {
    syst: SYST,
}

impl core::fmt::Debug for Counter {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str("Counter(SysTick)")
    }
}

/// SysTick's reload value (the counter is 24 bits wide).
const RELOAD: u32 = 0x00ff_ffff;

impl Counter {
    /// Starts SysTick counting down from [`RELOAD`] on the core clock, without interrupt.
    pub fn start(mut syst: SYST) -> Self {
        syst.set_clock_source(SystClkSource::Core);
        syst.set_reload(RELOAD);
        syst.clear_current();
        syst.disable_interrupt();
        syst.enable_counter();
        Counter { syst }
    }

    /// The current count (counts down, wraps at 2²⁴).
    pub fn now(&self) -> u32 {
        SYST::get_current()
    }

    /// Counts elapsed since `earlier` (a value of [`Counter::now`]), modulo 2²⁴: valid for
    /// spans shorter than one wrap.
    pub fn since(&self, earlier: u32) -> u32 {
        earlier.wrapping_sub(self.now()) & RELOAD
    }

    /// SysTick counts spent in `f`: the counter is read, `f` runs, the counter is read again.
    ///
    /// Not inlined, so that the compiler cannot move the caller's own work in between the two
    /// reads; make `f` a call of an `#[inline(never)]` function, and the region measured is
    /// that call (its argument set-up, `bl`, the function, its return) and the second read.
    /// [`Calibration`] subtracts the counts of a call of an empty function measured the same
    /// way.
    #[inline(never)]
    pub fn counts<R>(&self, f: impl FnOnce() -> R) -> (u32, R) {
        let t0 = self.now();
        compiler_fence(Ordering::SeqCst);
        let r = f();
        compiler_fence(Ordering::SeqCst);
        (self.since(t0), r)
    }

    /// Stops the counter and hands SysTick back.
    pub fn stop(mut self) -> SYST {
        self.syst.disable_counter();
        self.syst
    }
}

/// SysTick wraps since [`WideCounter::start`], counted by [`WideCounter::on_wrap`].
static WRAPS: AtomicU32 = AtomicU32::new(0);

/// SysTick extended to 64 bits by counting its wraps in its exception, for spans longer
/// than one wrap (2²⁴ counts: 655 360 instructions at [`ICOUNT_SHIFT`]), such as planning
/// and compiling a path.
///
/// The firmware's `SysTick` exception handler must call [`WideCounter::on_wrap`]. The
/// handler's own instructions (a few per wrap of 655 360 instructions) are counted with
/// the work; under `-icount` the exception is taken at the instruction where the counter
/// wraps, so the counts are reproducible. Convert them with
/// [`Calibration::instructions_wide`].
pub struct WideCounter {
    syst: SYST,
}

impl core::fmt::Debug for WideCounter {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str("WideCounter(SysTick)")
    }
}

impl WideCounter {
    /// Starts SysTick counting down from [`RELOAD`] on the core clock, its exception taken
    /// at every wrap.
    pub fn start(mut syst: SYST) -> Self {
        syst.set_clock_source(SystClkSource::Core);
        syst.set_reload(RELOAD);
        syst.clear_current();
        WRAPS.store(0, Ordering::SeqCst);
        syst.enable_interrupt();
        syst.enable_counter();
        WideCounter { syst }
    }

    /// Counts one wrap: the body of the firmware's `SysTick` exception handler.
    pub fn on_wrap() {
        WRAPS.fetch_add(1, Ordering::SeqCst);
    }

    /// Counts since [`WideCounter::start`] (the wraps and the current count, read until a
    /// wrap does not fall between them).
    pub fn now(&self) -> u64 {
        loop {
            let wraps = WRAPS.load(Ordering::SeqCst);
            let current = SYST::get_current();
            if WRAPS.load(Ordering::SeqCst) == wraps {
                return (u64::from(wraps) << 24) | u64::from(RELOAD - (current & RELOAD));
            }
        }
    }

    /// SysTick counts spent in `f`, measured as [`Counter::counts`] measures them.
    #[inline(never)]
    pub fn counts<R>(&self, f: impl FnOnce() -> R) -> (u64, R) {
        let t0 = self.now();
        compiler_fence(Ordering::SeqCst);
        let r = f();
        compiler_fence(Ordering::SeqCst);
        (self.now().wrapping_sub(t0), r)
    }

    /// The calibration of this counter (see [`Calibration::measure`]).
    pub fn calibrate(&self) -> Calibration {
        let narrow = |c: u64| u32::try_from(c).unwrap_or(u32::MAX);
        let (empty, ()) = self.counts(nothing);
        let (nops, ()) = self.counts(nops);
        Calibration {
            empty: narrow(empty),
            nops: narrow(nops),
        }
    }

    /// The instructions of a call of 64 `nop`s measured now (exactly 64 when counting is
    /// exact; see [`Calibration::check_nop64`]).
    pub fn check_nop64(&self, cal: &Calibration) -> u64 {
        let (c, ()) = self.counts(nops64);
        cal.instructions_wide(c)
    }

    /// Stops the counter and its exception and hands SysTick back.
    pub fn stop(mut self) -> SYST {
        self.syst.disable_counter();
        self.syst.disable_interrupt();
        self.syst
    }
}

/// Nanoseconds per SysTick count: the 25 MHz core clock of QEMU's MPS2 boards.
pub const NS_PER_COUNT: u64 = 40;

/// The `-icount shift` that `cargo xtask qemu` runs the `icount` firmware with.
pub const ICOUNT_SHIFT: u32 = 10;

/// The length of the calibration's straight run of `nop`s.
pub const CALIBRATION_NOPS: u32 = 256;

/// Converts SysTick counts into instructions: the counts of an empty measurement (the
/// overhead, subtracted) and of a straight run of [`CALIBRATION_NOPS`] `nop`s (the scale),
/// both measured with [`Counter::counts`] exactly as the work is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, defmt::Format)]
pub struct Calibration {
    /// Counts of an empty measurement.
    pub empty: u32,
    /// Counts of [`CALIBRATION_NOPS`] `nop`s.
    pub nops: u32,
}

/// 64 `nop` instructions in a row (inline assembly: one instruction each, no loop).
#[inline(always)]
fn nop64() {
    macro_rules! x8 {
        ($e:expr) => {
            $e;
            $e;
            $e;
            $e;
            $e;
            $e;
            $e;
            $e;
        };
    }
    x8!(x8!(cortex_m::asm::nop()));
}

/// An empty function: its call is the measurement's overhead.
#[inline(never)]
fn nothing() {
    cortex_m::asm::nop();
}

/// [`CALIBRATION_NOPS`] `nop`s in a function shaped like [`nothing`].
#[inline(never)]
fn nops() {
    cortex_m::asm::nop();
    nop64();
    nop64();
    nop64();
    nop64();
}

/// 64 `nop`s in a function shaped like [`nothing`].
#[inline(never)]
fn nops64() {
    cortex_m::asm::nop();
    nop64();
}

impl Calibration {
    /// Measures the overhead and the scale.
    pub fn measure(counter: &Counter) -> Self {
        let (empty, ()) = counter.counts(nothing);
        let (nops, ()) = counter.counts(nops);
        Calibration { empty, nops }
    }

    /// A check of the calibration: the instructions of a call of 64 `nop`s, measured now
    /// (exactly 64 when counting is exact).
    pub fn check_nop64(&self, counter: &Counter) -> u32 {
        let (c, ()) = counter.counts(nops64);
        self.instructions(c)
    }

    /// The instructions of a measurement of `counts` SysTick counts, the overhead subtracted
    /// (rounded to nearest; 0 when the measurement is at or below the overhead, or when the
    /// calibration is degenerate).
    pub fn instructions(&self, counts: u32) -> u32 {
        let span = u64::from(self.nops.saturating_sub(self.empty));
        if span == 0 {
            return 0;
        }
        let c = u64::from(counts.saturating_sub(self.empty));
        let n = (c * u64::from(CALIBRATION_NOPS) + span / 2) / span;
        u32::try_from(n).unwrap_or(u32::MAX)
    }

    /// The instructions of a [`WideCounter`] measurement of `counts` SysTick counts, the
    /// overhead subtracted, rounded to nearest.
    ///
    /// Converted at the exact ratio of the clocks, [`NS_PER_COUNT`] ns per count and
    /// 2^[`ICOUNT_SHIFT`] ns per instruction (25.6 counts per instruction), not at the scale
    /// of the 256 `nop`s: their count is rounded to a whole count, which is exact for one
    /// tick but off by up to 1 in 6 554 over millions of instructions.
    pub fn instructions_wide(&self, counts: u64) -> u64 {
        let c = counts.saturating_sub(u64::from(self.empty));
        let ns_per_instruction = 1_u64 << ICOUNT_SHIFT;
        (c.saturating_mul(NS_PER_COUNT) + ns_per_instruction / 2) / ns_per_instruction
    }
}
