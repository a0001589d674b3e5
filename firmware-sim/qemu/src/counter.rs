//! A SysTick-based counter: the hook for counting instructions per tick later.
//!
//! QEMU does not implement the DWT cycle counter (it reads 0). Run with
//! `-icount shift=N` and the virtual clock advances per instruction, so SysTick on the core
//! clock counts **instructions**, not cycles, deterministically (`shift=0`: one 25 MHz
//! SysTick count is 40 instructions; a larger shift resolves finer). Without `-icount` the
//! counts follow the host's wall clock and are not reproducible: nothing here is logged by
//! the firmware's normal run.

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

    /// Stops the counter and hands SysTick back.
    pub fn stop(mut self) -> SYST {
        self.syst.disable_counter();
        self.syst
    }
}
