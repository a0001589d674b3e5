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

    /// Fills `out` with the positions of the next `out.len()` setpoints: the values of as
    /// many calls of [`next_position`](Self::next_position), bit for bit, and the sampler
    /// advances as far (the calls may be mixed freely with every other entry point).
    ///
    /// The batch form of [`next_position`](Self::next_position), for simulation and export
    /// of positions only: within a piece each axis's position chain (`p += Δ¹; Δ¹ += Δ²;
    /// Δ² += Δ³`) runs as one loop over locals, the axes side by side, so that a tick is
    /// three additions per axis with no load or store of the state; the velocity and
    /// acceleration chains catch up as after [`next_position`](Self::next_position).
    ///
    /// ```
    /// use strak_trajectory::{compile, Along, CompileOptions, Path, Sampler, Timing};
    /// use strak_curves::Bezier;
    ///
    /// struct Linear;
    /// impl Timing for Linear {
    ///     fn duration(&self) -> f64 { 0.01 }
    ///     fn param(&self, t: f64) -> (f64, f64) { (t.clamp(0.0, 0.01) / 0.01, 100.0) }
    /// }
    /// let line = Bezier::new([[0.0_f64, 1.0], [2.0, 3.0]])?;
    /// let path: Path<f64, 2, 8> = compile(&Along::new(&line, &Linear), 1_000.0, &CompileOptions::new())?;
    /// let mut batch = [[0.0; 2]; 12];
    /// let (mut a, mut b) = (Sampler::new(&path), Sampler::new(&path));
    /// a.fill_positions(&mut batch);
    /// assert!(batch.iter().all(|p| *p == b.next().position));
    /// assert_eq!(batch[11], path.end_position());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn fill_positions(&mut self, out: &mut [[N::Out; A]]) {
        let mut rest = out;
        while !rest.is_empty() {
            let all = core::mem::take(&mut rest);
            if self.left > 1 {
                // `left − 1` position ticks before the switch tick, as `next_position` runs.
                let run = usize::try_from(self.left - 1).map_or(all.len(), |r| r.min(all.len()));
                let (now, later) = all.split_at_mut(run);
                run_positions(&mut self.state, now);
                // `run < left`, so the count fits.
                self.left -= u32::try_from(run).unwrap_or(0);
                rest = later;
            } else if let Some((first, later)) = all.split_first_mut() {
                *first = self.next_position();
                rest = later;
            }
        }
    }
}

/// `out.len()` plain forward-differencing ticks from `tick` on: each sample, then the
/// additions of [`portable::step_whole`](super::kernel::portable::step_whole) (the same
/// additions of the same values as every tick kernel), on the chains copied into one local
/// array per difference order, the axes of one order side by side so that the compiler keeps
/// them in registers and may add them as one vector.
#[inline(always)]
fn run_ticks<N: Number, const A: usize>(
    state: &mut [AxisState<N>; A],
    tick: u64,
    out: &mut [Sample<N::Out, A>],
) {
    let mut p = state.map(|s| s.position);
    let mut d1 = state.map(|s| s.delta1);
    let mut d2 = state.map(|s| s.delta2);
    let d3 = state.map(|s| s.delta3);
    let mut v = state.map(|s| s.velocity);
    let mut v1 = state.map(|s| s.velocity_delta1);
    let v2 = state.map(|s| s.velocity_delta2);
    let mut a = state.map(|s| s.acceleration);
    let a1 = state.map(|s| s.acceleration_delta);
    let mut t = tick;
    for o in out {
        o.tick = t;
        o.position = p.map(N::to_out);
        o.velocity = v.map(N::to_out);
        o.acceleration = a.map(N::to_out);
        add_each(&mut p, &d1);
        add_each(&mut d1, &d2);
        add_each(&mut d2, &d3);
        add_each(&mut v, &v1);
        add_each(&mut v1, &v2);
        add_each(&mut a, &a1);
        t = t.wrapping_add(1);
    }
    for (i, s) in state.iter_mut().enumerate() {
        if let (Some(&p), Some(&d1), Some(&d2), Some(&v), Some(&v1), Some(&a)) = (
            p.get(i),
            d1.get(i),
            d2.get(i),
            v.get(i),
            v1.get(i),
            a.get(i),
        ) {
            (s.position, s.delta1, s.delta2) = (p, d1, d2);
            (s.velocity, s.velocity_delta1, s.acceleration) = (v, v1, a);
        }
    }
}

/// `out.len()` position ticks: each position, then the additions of
/// [`portable::tick_position`](super::kernel::portable::tick_position) in its order, on the
/// position chains copied into one local array per difference order (the axes of one order
/// side by side, which the compiler may add as one vector).
#[inline(always)]
fn run_positions<N: Number, const A: usize>(
    state: &mut [AxisState<N>; A],
    out: &mut [[N::Out; A]],
) {
    let mut p = state.map(|s| s.position);
    let mut d1 = state.map(|s| s.delta1);
    let mut d2 = state.map(|s| s.delta2);
    let d3 = state.map(|s| s.delta3);
    for o in out {
        *o = p.map(N::to_out);
        add_each(&mut p, &d1);
        add_each(&mut d1, &d2);
        add_each(&mut d2, &d3);
    }
    for (s, ((p, d1), d2)) in state.iter_mut().zip(p.iter().zip(&d1).zip(&d2)) {
        (s.position, s.delta1, s.delta2) = (*p, *d1, *d2);
    }
}

/// One forward-differencing addition of every axis: `x += d`, axis by axis.
#[inline(always)]
fn add_each<N: Number, const A: usize>(x: &mut [N; A], d: &[N; A]) {
    for (x, d) in x.iter_mut().zip(d) {
        *x = *x + *d;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Q40;
    use crate::play::kernel::portable::tick_sample;
    use crate::play::tests::bits;

    /// An axis whose every chain value is `v`.
    fn axis<N: Number>(v: N) -> AxisState<N> {
        AxisState {
            position: v,
            delta1: v,
            delta2: v,
            delta3: v,
            velocity: v,
            velocity_delta1: v,
            velocity_delta2: v,
            acceleration: v,
            acceleration_delta: v,
        }
    }

    /// `run_ticks` against `tick_sample` called as often, bit for bit: an axis at rest on
    /// negative zeros (a padding or reordering of the additions that adds `+0.0` turns them
    /// positive, which `==` cannot see), one on positive zeros, and one moving.
    fn run_ticks_is_tick_sample_repeated<N: Number>() {
        let zero = N::ZERO;
        let moving = AxisState {
            position: N::from_f64(-1.25).unwrap(),
            delta1: N::from_f64(0.5).unwrap(),
            delta2: N::from_f64(-0.125).unwrap(),
            delta3: N::from_f64(0.0625).unwrap(),
            velocity: N::from_f64(-0.75).unwrap(),
            velocity_delta1: N::from_f64(0.25).unwrap(),
            velocity_delta2: N::from_f64(-0.5).unwrap(),
            acceleration: zero - N::EPSILON,
            acceleration_delta: N::EPSILON,
        };
        let start = [axis(-zero), axis(zero), moving];
        let (mut batched, mut one) = (start, start);
        let mut out = [Sample::splat(<N::Out as strak_curves::Scalar>::ZERO); 7];
        run_ticks(&mut batched, 40, &mut out);
        for (k, got) in out.iter().enumerate() {
            assert_eq!(
                bits(got),
                bits(&tick_sample(&mut one, 40 + k as u64)),
                "tick {k}"
            );
        }
        assert_eq!(bits(&batched), bits(&one));
    }

    #[test]
    fn run_ticks_keeps_every_bit() {
        run_ticks_is_tick_sample_repeated::<f32>();
        run_ticks_is_tick_sample_repeated::<f64>();
        run_ticks_is_tick_sample_repeated::<Q40>();
    }
}
