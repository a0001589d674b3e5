//! The kinematic limits of a compiled path, measured from its samples alone.
//!
//! [`measure`] plays a whole [`Path`] with [`Sampler::next`] at feed 1, converts every sample
//! to `f64` and takes, over all ticks `k` (tick period `T`, norms over the axes):
//!
//! | quantity                       | from                              |
//! |--------------------------------|-----------------------------------|
//! | speed, sampled                 | `‖v_k‖`                           |
//! | speed, finite difference       | `‖x_{k+1} − x_k‖ / T`             |
//! | acceleration, sampled          | `‖a_k‖`                           |
//! | acceleration, finite difference| `‖v_{k+1} − v_k‖ / T`             |
//! | jerk, finite difference        | `‖a_{k+1} − a_k‖ / T`             |
//!
//! [`Kinematics::check`] compares them with the limits plus the [`Allowance`] below.
//!
//! # The tolerance and why
//!
//! **Finite differences add nothing upward.** Between two ticks the compiled path is one
//! cubic per axis, so `(x_{k+1} − x_k)/T` is the mean of the velocity over the tick, and
//! `‖mean‖ ≤ mean ‖·‖ ≤ max ‖·‖` over the tick (the norm is convex); the same holds for the
//! velocity and acceleration channels, which are the exact derivatives of the position
//! polynomial. The truncation error of a one-tick difference (`O(T·ẍ)` for the velocity,
//! `O(T·j)` for the acceleration, `O(T·ȷ̇)`, zero in a cubic, for the jerk) only moves the
//! measured value *inside* the range the derivative takes over the tick. So a motion whose
//! derivatives stay within the limits at every instant measures within them, and no
//! truncation allowance is needed.
//!
//! **What remains is playback rounding.** Each sample differs from the compiled polynomial
//! by the playback error of its channel: the rounding of the piece's stored state into the
//! number format, propagated by forward differencing, plus the rounding of each addition
//! (floats) and of the conversion into the sample type. Per piece of `n` ticks and axis,
//! with the stored values `v, Δv¹, Δv²` and `a, Δa` (magnitudes including their growth over
//! the piece, as in [`Path::playback_bound`](strak_trajectory::PathHeader::playback_bound) for the position):
//!
//! * `e_v = r(v) + n·(r(Δv¹) + add(v)) + C(n,2)·(r(Δv²) + add(Δv¹)) + out`,
//! * `e_a = r(a) + n·(r(Δa) + add(a)) + out`,
//!
//! (`r`, `add`: [`Number::rounding_error`](strak_trajectory::Number::rounding_error), [`Number::addition_error`](strak_trajectory::Number::addition_error); `out`:
//! [`Number::OUT_ERROR`](strak_trajectory::Number::OUT_ERROR)), and `e_x` = [`Path::playback_bound`](strak_trajectory::PathHeader::playback_bound). Over `A` axes a norm moves
//! by at most `√A` times the per-axis error, a difference of two samples by twice that, so
//!
//! * speed: `√A·e_v` sampled, `2√A·e_x/T` by differences;
//! * acceleration: `√A·e_a` sampled, `2√A·e_v/T` by differences;
//! * jerk: `2√A·e_a/T`;
//!
//! plus `10⁻⁹` relative for the arithmetic of the comparison (the rounding of the `f64`
//! samples themselves is part of `e_x`, `e_v`, `e_a`). In `f64` and `Q40` playback the
//! allowance is orders of magnitude below the limits. In `f32` the allowance for the speed
//! by differences of positions grows with the coordinates' magnitude, the piece length and
//! the rate (`2√A·e_x/T`, `e_x ≈ n·½ε·|x|`): the `f32` position channel does not resolve
//! the speed better than that, and at 10 kHz with coordinates of a few hundred units the
//! allowance is several per cent of a speed limit of 200 units/s.
//!
//! Across a piece switch the samples of the next piece are the previous piece's polynomial
//! at its end (the spline is C²), so a difference over the last tick of a piece is the
//! mean over that tick as well; the last sample is the path's end, the spline's end.

use strak_curves::Scalar;
use strak_trajectory::{Kernel, Path, Sampler};

/// Relative allowance for the `f64` arithmetic of the difference quotients.
pub const F64_ROUNDING: f64 = 1e-9;

/// Where and how large: the largest value of one measured quantity and its tick.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Peak {
    /// The largest value measured.
    pub value: f64,
    /// The tick at which it was measured (the earlier tick of a difference).
    pub tick: u64,
}

impl Peak {
    fn update(&mut self, value: f64, tick: u64) {
        if value > self.value || value.is_nan() {
            *self = Peak { value, tick };
        }
    }
}

/// The largest speed, acceleration and jerk of a played path (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Kinematics {
    /// `‖v_k‖` of the velocity channel.
    pub speed: Peak,
    /// `‖x_{k+1} − x_k‖ / T`.
    pub speed_fd: Peak,
    /// `‖a_k‖` of the acceleration channel.
    pub acceleration: Peak,
    /// `‖v_{k+1} − v_k‖ / T`.
    pub acceleration_fd: Peak,
    /// `‖a_{k+1} − a_k‖ / T`.
    pub jerk_fd: Peak,
    /// The number of samples until the sampler finished (`ticks + 1`).
    pub samples: u64,
    /// The allowance for playback rounding (see [`Allowance`]).
    pub allowance: Allowance,
}

/// The absolute allowances (units/s, units/s², units/s³) for playback rounding of one path
/// (see the module docs for their derivation).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Allowance {
    /// For the sampled speed.
    pub speed: f64,
    /// For the speed by differences of positions.
    pub speed_fd: f64,
    /// For the sampled acceleration.
    pub acceleration: f64,
    /// For the acceleration by differences of velocities.
    pub acceleration_fd: f64,
    /// For the jerk by differences of accelerations.
    pub jerk_fd: f64,
}

impl Allowance {
    /// The allowances of `path` (see the module docs).
    pub fn of<N: Kernel, const A: usize, const P: usize>(path: &Path<N, A, P>) -> Self {
        let (e_v, e_a) = path.channel_bounds();
        #[allow(clippy::cast_precision_loss)]
        let root = (A as f64).sqrt();
        let rate = path.rate();
        Allowance {
            speed: root * e_v,
            speed_fd: 2.0 * root * path.playback_bound() * rate,
            acceleration: root * e_a,
            acceleration_fd: 2.0 * root * e_v * rate,
            jerk_fd: 2.0 * root * e_a * rate,
        }
    }
}

fn norm<const A: usize>(x: &[f64; A]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>().sqrt()
}

fn to_f64<T: Scalar, const A: usize>(x: &[T; A]) -> [f64; A] {
    x.map(Scalar::to_f64)
}

/// Plays `path` in full with [`Sampler::next`] and measures it (see the module docs).
/// Panics unless the sampler delivers `ticks + 1` samples with consecutive ticks.
pub fn measure<N: Kernel, const A: usize, const P: usize>(path: &Path<N, A, P>) -> Kinematics {
    let rate = path.rate();
    let mut k = Kinematics {
        allowance: Allowance::of(path),
        ..Kinematics::default()
    };
    let mut sampler = Sampler::new(path);
    let mut prev: Option<([f64; A], [f64; A], [f64; A])> = None;
    while !sampler.is_finished() {
        let s = sampler.next();
        assert_eq!(s.tick, k.samples, "consecutive ticks");
        let (x, v, a) = (
            to_f64(&s.position),
            to_f64(&s.velocity),
            to_f64(&s.acceleration),
        );
        k.speed.update(norm(&v), s.tick);
        k.acceleration.update(norm(&a), s.tick);
        if let Some((x0, v0, a0)) = prev {
            let d = |p: &[f64; A], q: &[f64; A]| -> [f64; A] {
                core::array::from_fn(|i| (q[i] - p[i]) * rate)
            };
            let t = s.tick - 1;
            k.speed_fd.update(norm(&d(&x0, &x)), t);
            k.acceleration_fd.update(norm(&d(&v0, &v)), t);
            k.jerk_fd.update(norm(&d(&a0, &a)), t);
        }
        prev = Some((x, v, a));
        k.samples += 1;
        assert!(
            k.samples <= u64::from(path.ticks()) + 1,
            "the sampler does not finish"
        );
    }
    assert_eq!(k.samples, u64::from(path.ticks()) + 1, "ticks + 1 samples");
    k
}

/// The largest ratios of the measured quantities (allowance removed) to the limits.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Ratios {
    /// Speed (the larger of sampled and by differences) over the velocity limit.
    pub velocity: f64,
    /// Acceleration over its limit.
    pub acceleration: f64,
    /// Jerk over its limit.
    pub jerk: f64,
}

impl Kinematics {
    /// Checks the measured peaks against the path limits `(v, a, j)` with the allowance
    /// (see the module docs); returns a message naming the quantity, its value, the limit,
    /// the allowance and the tick for every violation.
    ///
    /// # Errors
    /// The list of violations, one per line.
    pub fn check(&self, v: f64, a: f64, j: f64) -> Result<Ratios, String> {
        let al = &self.allowance;
        let rows = [
            ("speed (sampled)", self.speed, v, al.speed),
            ("speed (differences)", self.speed_fd, v, al.speed_fd),
            (
                "acceleration (sampled)",
                self.acceleration,
                a,
                al.acceleration,
            ),
            (
                "acceleration (differences)",
                self.acceleration_fd,
                a,
                al.acceleration_fd,
            ),
            ("jerk (differences)", self.jerk_fd, j, al.jerk_fd),
        ];
        let mut errors = String::new();
        for (what, peak, limit, allowance) in rows {
            let bound = limit * (1.0 + F64_ROUNDING) + allowance;
            if peak.value.is_nan() || peak.value > bound {
                errors.push_str(&format!(
                    "{what} {:.6e} at tick {} exceeds the limit {limit:.6e} \
                     (x{:.4}; allowance {allowance:.3e})\n",
                    peak.value,
                    peak.tick,
                    peak.value / limit
                ));
            }
        }
        if errors.is_empty() {
            Ok(self.ratios(v, a, j))
        } else {
            Err(errors)
        }
    }

    /// The ratios to the limits `(v, a, j)`.
    pub fn ratios(&self, v: f64, a: f64, j: f64) -> Ratios {
        Ratios {
            velocity: self.speed.value.max(self.speed_fd.value) / v,
            acceleration: self.acceleration.value.max(self.acceleration_fd.value) / a,
            jerk: self.jerk_fd.value / j,
        }
    }
}
