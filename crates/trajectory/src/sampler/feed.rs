//! The jerk-limited ramp of the feed factor `φ` (feed override, hold, resume, abort).
//!
//! `φ ∈ [0, 1]` moves towards its target with a rate `ω` (change of `φ` per tick) bounded by
//! `ω_max`, and `ω` changes by at most `α` per tick (the per-tick forms of the acceleration and
//! jerk the path reserves for feed changes; see [`CompileOptions`](crate::CompileOptions)).
//! Each tick picks the largest of `ω + α`, `ω`, `ω − α` (toward the target) after which the
//! ramp can still stop in time: decelerating from `c` by `α` per tick covers
//! `c²/(2α) − c/2`, so `c` is admissible while
//!
//! `2α·(dist − c) ≥ c² − α·c`, i.e. `2α·dist ≥ c² + α·c`,
//!
//! (no division, and all terms are at most `2α ≤ ½`, so no fixed-point overflow). Within `α`
//! of the target at a rate of at most `α`, `φ` snaps onto the target (a change of `ω` by at
//! most `α`). Constant work: at most 8 multiplications per tick.

use crate::number::Number;

/// The state of the feed factor ramp.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FeedRamp<N> {
    /// The feed factor `φ ∈ [0, 1]`.
    pub(crate) phi: N,
    /// Its change in the last tick.
    pub(crate) omega: N,
    /// Where it is going (in `[0, 1]`).
    pub(crate) target: N,
}

impl<N: Number> FeedRamp<N> {
    /// At full feed, at rest.
    pub(crate) fn full() -> Self {
        FeedRamp {
            phi: N::ONE,
            omega: N::ZERO,
            target: N::ONE,
        }
    }

    /// `true` when `φ` rests on its target.
    #[inline]
    pub(crate) fn is_idle(&self) -> bool {
        self.phi == self.target && self.omega == N::ZERO
    }

    /// One tick of the ramp.
    #[inline]
    pub(crate) fn step(&mut self, omega_max: N, alpha: N) {
        if self.is_idle() {
            return;
        }
        let e = self.target - self.phi;
        // Work in the direction of the target: distance ≥ 0, speed toward it (< 0: away).
        let toward = e > N::ZERO || (e == N::ZERO && self.omega < N::ZERO);
        let (dist, v) = if toward {
            (e, self.omega)
        } else {
            (-e, -self.omega)
        };
        let abs_v = if v < N::ZERO { -v } else { v };
        if dist <= alpha && abs_v <= alpha {
            self.phi = self.target;
            self.omega = N::ZERO;
            return;
        }
        let c = if v < N::ZERO {
            // moving away: turn around
            v + alpha
        } else {
            let budget = (alpha + alpha) * dist;
            let fits = |c: N| c * c + alpha * c <= budget;
            let up = min(v + alpha, omega_max);
            let hold = min(v, omega_max);
            if fits(up) {
                up
            } else if fits(hold) {
                hold
            } else {
                v - alpha
            }
        };
        let omega = if toward { c } else { -c };
        let next = self.phi + omega;
        // φ stays in [0, 1]; the rate is what was actually moved.
        let next = if next > N::ONE {
            N::ONE
        } else if next < N::ZERO {
            N::ZERO
        } else {
            next
        };
        self.omega = next - self.phi;
        self.phi = next;
    }
}

#[inline]
fn min<N: Number>(a: N, b: N) -> N {
    if b < a { b } else { a }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::number::Q40;

    /// Runs the ramp to its target; returns the number of ticks and checks the limits.
    fn run<N: Number>(ramp: &mut FeedRamp<N>, omega_max: f64, alpha: f64) -> u32 {
        let (wm, al) = (N::from_f64(omega_max).unwrap(), N::from_f64(alpha).unwrap());
        let mut ticks = 0;
        let mut prev_omega = ramp.omega.to_f64();
        while !ramp.is_idle() {
            ramp.step(wm, al);
            let w = ramp.omega.to_f64();
            let phi = ramp.phi.to_f64();
            assert!((0.0..=1.0).contains(&phi));
            assert!(w.abs() <= omega_max * (1.0 + 1e-6) + 1e-15, "ω = {w}");
            assert!(
                (w - prev_omega).abs() <= alpha * (1.0 + 1e-3) + 1e-12,
                "Δω = {} at tick {ticks}",
                w - prev_omega
            );
            prev_omega = w;
            ticks += 1;
            assert!(ticks < 1_000_000, "ramp does not end");
        }
        ticks
    }

    fn ramp_down_and_up<N: Number>() {
        let mut r = FeedRamp::<N>::full();
        r.target = N::ZERO;
        // ω_max = 0.01, α = 1e-4: 100 ticks to reach ω_max, ~200 ticks of full rate
        let down = run(&mut r, 0.01, 1e-4);
        assert_eq!(r.phi, N::ZERO);
        // continuous time: t = ω/α + 1/ω = 200 ticks
        assert!((195..=210).contains(&down), "{down}");
        r.target = N::from_f64(0.5).unwrap();
        let up = run(&mut r, 0.01, 1e-4);
        assert_eq!(r.phi.to_f64(), 0.5);
        // 0.5 with α = 1e-4: a triangle (ω peaks at √(α·d) ≈ 0.007 < ω_max), t = 2√(d/α)
        assert!((140..=150).contains(&up), "{up}");
    }

    #[test]
    fn ramps_in_every_format() {
        ramp_down_and_up::<f32>();
        ramp_down_and_up::<f64>();
        ramp_down_and_up::<Q40>();
    }

    #[test]
    fn short_moves_are_jerk_limited_triangles() {
        // distance 0.01 with α = 1e-4: ω peaks at ~√(α·d) = 1e-3 < ω_max
        let mut r = FeedRamp::<f64>::full();
        r.target = 0.99;
        let n = run(&mut r, 0.5, 1e-4);
        assert_eq!(r.phi, 0.99);
        assert!((18..=24).contains(&n), "{n}");
    }

    #[test]
    fn target_change_mid_ramp_reverses_smoothly() {
        let mut r = FeedRamp::<Q40>::full();
        r.target = Q40::ZERO;
        let (wm, al) = (Q40::from_f64(0.01).unwrap(), Q40::from_f64(1e-4).unwrap());
        for _ in 0..120 {
            r.step(wm, al);
        }
        assert!(r.omega.to_f64() < -0.007, "{:?}", r.omega);
        r.target = Q40::ONE; // resume while still slowing down
        let ticks = run(&mut r, 0.01, 1e-4);
        assert_eq!(r.phi, Q40::ONE);
        assert!(ticks > 100);
    }

    #[test]
    fn idle_ramp_does_nothing() {
        let mut r = FeedRamp::<f32>::full();
        r.step(0.1, 0.01);
        assert_eq!(r, FeedRamp::full());
    }
}
