//! The ticks off the sampler's fast path: the catch-up of the chains that position-only ticks
//! leave behind, the end after a feed change, the standstill after the end, and
//! interpolation under a feed override or a ramp (the piece switch at full feed is
//! [`switch`](super::switch)'s).

use super::form::{Form, Native, Rounded};
use super::{Kernel, Sampler, SamplerState};
use crate::num::Number;
use crate::path::{Newton, Sample};

impl<N: Kernel, const A: usize> Sampler<'_, N, A> {
    /// A tick of [`next`](Self::next) off its fast path: after position-only ticks, the
    /// chains caught up, then the piece switch or the ordinary tick; otherwise
    /// [`next_other`](Self::next_other). Out of line, so that the common tick carries none
    /// of its code.
    #[inline(never)]
    pub(super) fn next_edge(&mut self) -> Sample<N::Out, A> {
        self.catch_up();
        if self.left > 1 {
            let tick = self.count_tick();
            return N::tick_sample(&mut self.state, tick);
        }
        if self.left == 1 {
            return self.switch_sample();
        }
        self.next_other::<Rounded>()
    }

    /// [`next_edge`](Self::next_edge) for [`next_into`](Self::next_into).
    #[inline(never)]
    pub(super) fn next_edge_into(&mut self, out: &mut Sample<N::Native, A>) {
        self.catch_up();
        if self.left > 1 {
            let tick = self.count_tick();
            return N::tick_native(&mut self.state, tick, out);
        }
        if self.left == 1 {
            return self.switch_native(out);
        }
        self.next_other_into(out);
    }

    /// [`next_other`](Self::next_other) in the accumulator's format, copied to `out`.
    #[inline(never)]
    pub(super) fn next_other_into(&mut self, out: &mut Sample<N::Native, A>) {
        *out = self.next_other::<Native>();
    }

    /// [`next_other`](Self::next_other)'s positions (the chains caught up first), for
    /// [`next_position`](Self::next_position) off its fast path and its piece switch.
    #[inline(never)]
    pub(super) fn next_other_position(&mut self) -> [N::Out; A] {
        self.catch_up();
        self.next_other::<Rounded>().position
    }

    /// Steps the velocity and acceleration chains over the `chains − left` ticks that
    /// position-only ticks left out, in closed form (Newton's forward formula at the integer
    /// offset `m`: `v += m·Δv¹ + C(m,2)·Δv²`, `Δv¹ += m·Δv²`, `a += m·Δa`): exact in `Q40`
    /// (integer products, the same bits as `m` steps), within rounding in floats. Constant
    /// time.
    #[inline]
    fn catch_up(&mut self) {
        let lag = self.chains.wrapping_sub(self.left);
        self.chains = self.left;
        if lag == 0 {
            return;
        }
        let m = i64::from(lag);
        let pairs = m.wrapping_mul(m - 1) / 2;
        for s in &mut self.state {
            s.velocity =
                s.velocity + s.velocity_delta1.mul_int(m) + s.velocity_delta2.mul_int(pairs);
            s.velocity_delta1 = s.velocity_delta1 + s.velocity_delta2.mul_int(m);
            s.acceleration = s.acceleration + s.acceleration_delta.mul_int(m);
        }
    }

    /// Every tick that is not a plain forward-differencing step or a piece switch at full
    /// feed: the end sample after a feed change, standing at the end, interpolation (feed
    /// override, ramps). Out of line, so that the common tick carries none of its code or
    /// register saves.
    #[inline(never)]
    pub(super) fn next_other<F: Form<N>>(&mut self) -> Sample<F::T, A> {
        self.sync();
        let sample = self.next_checked::<F>();
        self.refresh();
        sample
    }

    /// The tick by the full case analysis (it does not rely on [`left`](Self::left)).
    #[inline(always)]
    fn next_checked<F: Form<N>>(&mut self) -> Sample<F::T, A> {
        let tick = self.end;
        if self.mode == SamplerState::Finished {
            self.end = tick.wrapping_add(1);
            return Sample {
                tick,
                position: self.rest.map(F::of_out),
                velocity: [F::ZERO; A],
                acceleration: [F::ZERO; A],
            };
        }
        if self.at_end() {
            self.end = tick.wrapping_add(1);
            self.mode = SamplerState::Finished;
            let end = &self.path.header().end;
            self.rest = end.position;
            let (velocity, acceleration) = if self.feed.phi == N::ONE {
                (end.velocity, end.acceleration)
            } else {
                let phi = self.feed.phi.to_out();
                (
                    end.velocity.map(|v| v * phi),
                    end.acceleration.map(|a| a * phi * phi),
                )
            };
            return Sample {
                tick,
                position: end.position.map(F::of_out),
                velocity: velocity.map(F::of_out),
                acceleration: acceleration.map(F::of_out),
            };
        }
        self.end = tick.wrapping_add(1);
        let tick_grid = self.feed.phi == N::ONE && self.theta == N::ZERO && self.feed.is_idle();
        if tick_grid {
            let sample = F::tick(&mut self.state, tick);
            self.advance_index();
            return sample;
        }
        self.interpolate::<F>(tick)
    }

    /// A tick in interpolation mode.
    fn interpolate<F: Form<N>>(&mut self, tick: u64) -> Sample<F::T, A> {
        let c = Newton::at(self.theta);
        let phi = self.feed.phi;
        let phi2 = phi * phi;
        let phi_dot = self.feed.omega * self.path.header().ramp.rate;
        let mut sample = Sample::splat(F::ZERO);
        sample.tick = tick;
        let mut positions = [N::ZERO; A];
        let values = sample
            .position
            .iter_mut()
            .zip(sample.velocity.iter_mut())
            .zip(sample.acceleration.iter_mut())
            .zip(positions.iter_mut());
        for (s, (((x, y), z), q)) in self.state.iter().zip(values) {
            let p = s.position + c.c1 * s.delta1 + c.c2 * s.delta2 + c.c3 * s.delta3;
            let v = s.velocity + c.c1 * s.velocity_delta1 + c.c2 * s.velocity_delta2;
            let acc = s.acceleration + c.c1 * s.acceleration_delta;
            *q = p;
            *x = F::of(p);
            *y = F::of(phi * v);
            *z = F::of(phi2 * acc + phi_dot * v);
        }
        if self.mode == SamplerState::Aborting && self.feed.is_idle() && phi == N::ZERO {
            // Stopped: this is the final sample.
            self.mode = SamplerState::Finished;
            self.rest = positions.map(Number::to_out);
            return sample;
        }
        self.advance_feed();
        sample
    }

    /// The feed ramp's step, then the playback point by `φ` (stepping the state when it
    /// crosses a tick), and back on the tick grid when the ramp has returned to full feed.
    fn advance_feed(&mut self) {
        self.feed.step(&self.ramp);
        // Invariant: shift + θ ∈ [0, 1), so the playback point stays inside the current
        // tick interval of the current piece (θ may be negative after a step).
        self.theta = self.theta + self.feed.phi;
        if self.shift + self.theta >= N::ONE {
            self.theta = self.theta - N::ONE;
            for s in &mut self.state {
                s.step();
            }
            self.advance_index();
        }
        // Back at full feed: shift the state onto the playback point, resume differencing.
        if self.feed.phi == N::ONE && self.feed.is_idle() && self.theta != N::ZERO && !self.at_end()
        {
            let c = Newton::at(self.theta);
            for s in &mut self.state {
                *s = s.shifted(&c);
            }
            self.shift = self.shift + self.theta;
            self.on_grid = self.shift == N::ZERO;
            self.theta = N::ZERO;
            self.set_ahead(self.piece());
        }
    }
}
