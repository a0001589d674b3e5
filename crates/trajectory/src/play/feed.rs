//! The jerk-limited ramp of the feed factor `φ` (feed override, hold, resume, abort).
//!
//! `φ ∈ [0, 1]` moves towards its target with a rate `ω` (change of `φ` per tick) bounded by
//! `ω_max`, and `ω` changes by at most `α` per tick (the per-tick forms of the acceleration and
//! jerk the path reserves for feed changes; see [`CompileOptions`](crate::CompileOptions)).
//! `ω = K·α` is always a whole multiple of `α` (the integer `K` is the state; `|K| ≤ K_max`).
//! Each tick picks the largest of `K + 1`, `K`, `K − 1` (toward the target) after which the
//! ramp can still stop in time: decelerating from `Kα` by `α` per tick covers exactly
//! `Σ_{k=1..K} (K − k)·α = α·K(K − 1)/2`, so `K` is admissible while
//!
//! `dist − Kα ≥ α·K(K − 1)/2`, i.e. `α·K(K + 1) ≤ 2·dist`,
//!
//! one multiplication by an integer: exact in fixed-point, whatever the size of `α` (no
//! division; `K(K+1) ≤ 2⁴¹`, `α·K(K+1) ≤ 2·ω_max²/α + … ≤ 3`, no overflow). Because the
//! distance is exact, `K − 1` is always admissible when `K` was: the ramp never overshoots a
//! target that stays put, and `|Δω| ≤ α` every tick. Within `snap = max(α, ε)` of the target
//! at a rate toward it of at most `snap` (not away from it: turning around first keeps
//! `|Δω| ≤ snap`), `φ` lands on the target in one step (`ε` is the format's
//! spacing at 1, the resolution of a float `φ` near 1; in `f32` slow ramps are quantized by
//! it). That step's rate `ω` is the distance it moves, not a multiple of `α`, and the tick
//! after it `ω` is 0: the rate reported with the samples (`φ̇` in their acceleration) falls
//! to 0 by at most `snap` per tick, as it rose. Constant work: 4 multiplications by an
//! integer per tick.

use crate::num::Number;
use crate::path::FeedRampLimits;

/// The state of the feed factor ramp.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FeedRamp<N> {
    /// The feed factor `φ ∈ [0, 1]`.
    pub(crate) phi: N,
    /// Its rate in multiples of `α`.
    pub(crate) k: i64,
    /// Its rate `ω = k·α` (change per tick), or the landing step's distance while `k = 0`.
    pub(crate) omega: N,
    /// Where it is going (in `[0, 1]`).
    pub(crate) target: N,
}

impl<N: Number> FeedRamp<N> {
    /// At full feed, at rest.
    pub(crate) fn full() -> Self {
        FeedRamp {
            phi: N::ONE,
            k: 0,
            omega: N::ZERO,
            target: N::ONE,
        }
    }

    /// `true` when `φ` rests on its target.
    #[inline]
    pub(crate) fn is_idle(&self) -> bool {
        self.phi == self.target && self.k == 0 && self.omega == N::ZERO
    }

    /// One tick of the ramp.
    #[inline]
    pub(crate) fn step(&mut self, limits: &FeedRampLimits<N>) {
        if self.is_idle() {
            return;
        }
        if self.k == 0 && self.omega != N::ZERO {
            // The tick after a landing step: the rate falls from that step's distance to 0.
            self.omega = N::ZERO;
            return;
        }
        let alpha = limits.alpha;
        let e = self.target - self.phi;
        // Work in the direction of the target: distance ≥ 0, rate toward it (< 0: away).
        let toward = e > N::ZERO || (e == N::ZERO && self.k < 0);
        let (dist, kv) = if toward { (e, self.k) } else { (-e, -self.k) };
        if kv >= 0 && dist <= limits.snap && alpha.mul_int(kv) <= limits.snap {
            self.land(self.target);
            return;
        }
        let kc = if kv < 0 {
            // moving away: turn around
            kv + 1
        } else {
            let two_dist = dist + dist;
            let fits = |k: i64| alpha.mul_int(k * (k + 1)) <= two_dist;
            let up = (kv + 1).min(limits.k_max);
            let hold = kv.min(limits.k_max);
            if fits(up) {
                up
            } else if fits(hold) {
                hold
            } else {
                kv - 1
            }
        };
        self.k = if toward { kc } else { -kc };
        self.omega = alpha.mul_int(self.k);
        let next = self.phi + self.omega;
        // φ stays in [0, 1] (only a float's rounding could overshoot the end of the range).
        if next > N::ONE || next < N::ZERO {
            self.land(if next > N::ONE { N::ONE } else { N::ZERO });
        } else {
            self.phi = next;
        }
    }

    /// The step that ends a ramp on `phi`: its rate is the distance it moves (at most
    /// `snap`), so the rate reported with the next sample (`φ̇` in its acceleration) falls
    /// to 0 over two ticks, by at most `snap` each, and the ramp is idle one tick later.
    fn land(&mut self, phi: N) {
        self.omega = phi - self.phi;
        self.phi = phi;
        self.k = 0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::Q40;

    /// The limits as the path stores them: ω_max a whole multiple of α.
    fn limits<N: Number>(omega_max: f64, alpha: f64) -> FeedRampLimits<N> {
        let alpha = N::from_f64(alpha).unwrap();
        FeedRampLimits::new(
            alpha,
            libm::floor(omega_max / alpha.to_f64()) as i64,
            N::ONE,
        )
    }

    /// Runs the ramp to its target; returns the number of ticks and checks the limits.
    fn run<N: Number>(ramp: &mut FeedRamp<N>, omega_max: f64, alpha: f64) -> u32 {
        let limits = limits::<N>(omega_max, alpha);
        let jump = limits.snap.to_f64().max(alpha);
        let mut ticks = 0;
        let mut prev_omega = ramp.omega.to_f64();
        let target = ramp.target.to_f64();
        let from_below = ramp.phi.to_f64() < target;
        let from_rest = ramp.k == 0;
        let mut prev_phi = ramp.phi.to_f64();
        while !ramp.is_idle() {
            ramp.step(&limits);
            let w = ramp.omega.to_f64();
            let phi = ramp.phi.to_f64();
            assert!((0.0..=1.0).contains(&phi));
            // The rate is the step taken (up to the rounding of φ + ω): the sampler reports
            // it as φ̇, so the reported acceleration agrees with the positions.
            assert!(
                (phi - prev_phi - w).abs() <= N::EPSILON.to_f64(),
                "step {} with ω = {w} at tick {ticks}",
                phi - prev_phi
            );
            prev_phi = phi;
            if from_rest {
                // no overshoot
                assert!(
                    (phi <= target) == from_below || phi == target,
                    "overshoot: {phi}"
                );
            }
            assert!(w.abs() <= omega_max * (1.0 + 1e-6) + 1e-15, "ω = {w}");
            assert!(
                (w - prev_omega).abs() <= jump * (1.0 + 1e-3) + 1e-15,
                "Δω = {} at tick {ticks}",
                w - prev_omega
            );
            prev_omega = w;
            ticks += 1;
            assert!(ticks < 10_000_000, "ramp does not end");
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
        let limits = limits::<Q40>(0.01, 1e-4);
        for _ in 0..120 {
            r.step(&limits);
        }
        assert!(r.omega.to_f64() < -0.007, "{:?}", r.omega);
        r.target = Q40::ONE; // resume while still slowing down
        let ticks = run(&mut r, 0.01, 1e-4);
        assert_eq!(r.phi, Q40::ONE);
        assert!(ticks > 100);
    }

    /// A target set just behind `φ` while it moves away: the ramp turns around before it
    /// lands, so the rate never jumps from `+α` to minus the distance (`|Δω|` up to `2α`).
    fn target_just_behind<N: Number>() {
        let mut r = FeedRamp::<N>::full();
        r.phi = N::from_f64(0.25).unwrap();
        r.target = N::ONE;
        r.step(&limits::<N>(0.5, 0.125));
        assert_eq!((r.phi.to_f64(), r.k), (0.375, 1));
        r.target = N::from_f64(0.3125).unwrap();
        run(&mut r, 0.5, 0.125);
        assert_eq!(r.phi.to_f64(), 0.3125);
    }

    #[test]
    fn a_target_just_behind_turns_around_before_landing() {
        target_just_behind::<f32>();
        target_just_behind::<f64>();
        target_just_behind::<Q40>();
    }

    #[test]
    fn idle_ramp_does_nothing() {
        let mut r = FeedRamp::<f32>::full();
        r.step(&limits(0.1, 0.01));
        assert_eq!(r, FeedRamp::full());
    }

    /// A slow ramp (α far below the spacing of f32 near 1) must not stall in `f32`.
    #[test]
    fn slow_ramps_do_not_stall_in_f32() {
        let mut r = FeedRamp::<f32>::full();
        r.target = 0.5;
        // ω_max ≈ √α: about ω/α + d/ω ≈ 4.7·10⁵ ticks
        let n = run(&mut r, 3e-6, 1e-11);
        assert_eq!(r.phi, 0.5);
        assert!((400_000..600_000).contains(&n), "{n}");
        r.target = 1.0;
        let n = run(&mut r, 3e-6, 1e-11);
        assert_eq!(r.phi, 1.0);
        assert!((400_000..600_000).contains(&n), "{n}");
        let mut q = FeedRamp::<Q40>::full();
        q.target = Q40::HALF;
        let m = run(&mut q, 3e-6, 1e-11);
        assert!(m.abs_diff(n) < n / 100, "{m} vs {n}"); // f32 quantizes φ near 1
    }
}
