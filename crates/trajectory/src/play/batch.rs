//! Batch playback for simulation: many ticks in one call, the state kept in registers
//! across the ticks of a piece.

use super::{Kernel, Sampler};
use crate::num::Number;
use crate::path::{AxisState, Sample};

impl<N: Kernel, const A: usize> Sampler<'_, N, A> {
    /// Fills `out` with the next `out.len()` setpoints: the samples of as many calls of
    /// [`next`](Self::next), bit for bit, and the sampler advances as far (the calls may be
    /// mixed freely).
    ///
    /// For simulation and export on the host: the plain forward-differencing ticks of a
    /// piece run as one loop over a copy of the state held in registers (no store and
    /// reload of the state between ticks, the one dependency a per-call tick cannot avoid);
    /// every other tick (a piece switch, a feed ramp, the end) is [`next`](Self::next).
    ///
    /// ```
    /// use strak_trajectory::{compile, Along, CompileOptions, Path, Sample, Sampler, Timing};
    /// use strak_curves::Bezier;
    ///
    /// struct Linear;
    /// impl Timing for Linear {
    ///     fn duration(&self) -> f64 { 0.01 }
    ///     fn param(&self, t: f64) -> (f64, f64) { (t.clamp(0.0, 0.01) / 0.01, 100.0) }
    /// }
    /// let line = Bezier::new([[0.0_f64, 1.0], [2.0, 3.0]])?;
    /// let path: Path<f64, 2, 8> = compile(&Along::new(&line, &Linear), 1_000.0, &CompileOptions::new())?;
    /// let mut batch = [Sample::splat(0.0); 12];
    /// let (mut a, mut b) = (Sampler::new(&path), Sampler::new(&path));
    /// a.fill(&mut batch);
    /// assert!(batch.iter().all(|s| *s == b.next()));
    /// assert_eq!(batch[11].position, path.end_position()); // tick 10 is the end; then it stands
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn fill(&mut self, out: &mut [Sample<N::Out, A>]) {
        let mut rest = out;
        while !rest.is_empty() {
            let all = core::mem::take(&mut rest);
            if self.on_fast_path() {
                // `left − 1` plain ticks before the switch tick.
                let run = usize::try_from(self.left - 1).map_or(all.len(), |r| r.min(all.len()));
                let tick = self.end.wrapping_sub(u64::from(self.left));
                let (now, later) = all.split_at_mut(run);
                run_ticks(&mut self.state, tick, now);
                // `run < left`, so the count fits.
                self.left -= u32::try_from(run).unwrap_or(0);
                self.chains = self.left;
                rest = later;
            } else if let Some((first, later)) = all.split_first_mut() {
                *first = self.next();
                rest = later;
            }
        }
    }
}

/// `out.len()` plain forward-differencing ticks from `tick` on: each sample, then the step
/// of [`portable::step_whole`](super::kernel::portable::step_whole) (the same additions in
/// the same order as every tick kernel), on a copy of the state that the compiler keeps in
/// registers.
#[inline(always)]
fn run_ticks<N: Number, const A: usize>(
    state: &mut [AxisState<N>; A],
    tick: u64,
    out: &mut [Sample<N::Out, A>],
) {
    let mut s = *state;
    let mut t = tick;
    for o in out {
        o.tick = t;
        for (a, x) in s.iter_mut().enumerate() {
            if let (Some(p), Some(v), Some(c)) = (
                o.position.get_mut(a),
                o.velocity.get_mut(a),
                o.acceleration.get_mut(a),
            ) {
                (*p, *v, *c) = (
                    x.position.to_out(),
                    x.velocity.to_out(),
                    x.acceleration.to_out(),
                );
            }
            super::kernel::portable::step_whole(x);
        }
        t = t.wrapping_add(1);
    }
    *state = s;
}
