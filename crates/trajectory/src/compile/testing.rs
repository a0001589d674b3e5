//! Test support: small time laws and curves with closed-form derivatives, and the exact
//! composition `x(t) = c(u(t))` with its time derivatives; compiling into a boxed path.

extern crate std;

use strak_curves::{ParamCurve, ParamCurveDeriv};

use super::{CompileOptions, compile_into};
use crate::error::Error;
use crate::num::Number;
use crate::path::Path;
use crate::plan::{Timing, Trajectory};

/// A time law with its second derivative (for exact accelerations).
pub(crate) trait TestTiming: Timing {
    /// `d²u/dt²` at `t`.
    fn ddu(&self, t: f64) -> f64;
}

/// Parameter-proportional: `u = t/T`.
pub(crate) struct Linear(pub(crate) f64);

impl Timing for Linear {
    fn duration(&self) -> f64 {
        self.0
    }
    fn param(&self, t: f64) -> (f64, f64) {
        (t.clamp(0.0, self.0) / self.0, 1.0 / self.0)
    }
}

impl TestTiming for Linear {
    fn ddu(&self, _t: f64) -> f64 {
        0.0
    }
}

/// Rest to rest: `u = 3τ² − 2τ³`, `τ = t/T`.
pub(crate) struct Smoothstep(f64);

impl Smoothstep {
    pub(crate) fn new(duration: f64) -> Self {
        Smoothstep(duration)
    }
}

impl Timing for Smoothstep {
    fn duration(&self) -> f64 {
        self.0
    }
    fn param(&self, t: f64) -> (f64, f64) {
        let s = t.clamp(0.0, self.0) / self.0;
        (s * s * (3.0 - 2.0 * s), 6.0 * s * (1.0 - s) / self.0)
    }
}

impl TestTiming for Smoothstep {
    fn ddu(&self, t: f64) -> f64 {
        let s = t.clamp(0.0, self.0) / self.0;
        (6.0 - 12.0 * s) / (self.0 * self.0)
    }
}

/// Rest to rest with zero end accelerations: `u = 10τ³ − 15τ⁴ + 6τ⁵`.
pub(crate) struct Quintic(pub(crate) f64);

impl Timing for Quintic {
    fn duration(&self) -> f64 {
        self.0
    }
    fn param(&self, t: f64) -> (f64, f64) {
        let s = t.clamp(0.0, self.0) / self.0;
        let u = s * s * s * (10.0 + s * (-15.0 + 6.0 * s));
        let du = 30.0 * s * s * (1.0 - s) * (1.0 - s) / self.0;
        (u, du)
    }
}

impl TestTiming for Quintic {
    fn ddu(&self, t: f64) -> f64 {
        let s = t.clamp(0.0, self.0) / self.0;
        60.0 * s * (1.0 - s) * (1.0 - 2.0 * s) / (self.0 * self.0)
    }
}

/// Trapezoidal velocity in `u` (jumps in acceleration): accelerate for `r·T`, cruise,
/// decelerate for `r·T` (`0 < r ≤ ½`).
pub(crate) struct Trapezoid {
    pub(crate) duration: f64,
    pub(crate) ramp: f64,
}

impl Trapezoid {
    fn peak(&self) -> f64 {
        // area: v·(T − rT) = 1
        1.0 / (self.duration * (1.0 - self.ramp))
    }
}

impl Timing for Trapezoid {
    fn duration(&self) -> f64 {
        self.duration
    }
    fn param(&self, t: f64) -> (f64, f64) {
        let t = t.clamp(0.0, self.duration);
        let (v, tr) = (self.peak(), self.ramp * self.duration);
        let acc = v / tr;
        if t < tr {
            (0.5 * acc * t * t, acc * t)
        } else if t <= self.duration - tr {
            (0.5 * v * tr + v * (t - tr), v)
        } else {
            let r = self.duration - t;
            (1.0 - 0.5 * acc * r * r, acc * r)
        }
    }
}

impl TestTiming for Trapezoid {
    fn ddu(&self, t: f64) -> f64 {
        let tr = self.ramp * self.duration;
        let acc = self.peak() / tr;
        if t < tr {
            acc
        } else if t <= self.duration - tr {
            0.0
        } else {
            -acc
        }
    }
}

/// A helix around the z axis: `(r cos 2πwu, r sin 2πwu, h u)` for `u ∈ [0, 1]`, `w` turns.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Helix {
    r: f64,
    w: f64,
    h: f64,
}

pub(crate) fn helix(r: f64, turns: f64, h: f64) -> Helix {
    Helix { r, w: turns, h }
}

impl ParamCurve for Helix {
    type Point = [f64; 3];
    fn domain(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn eval(&self, u: f64) -> [f64; 3] {
        self.deriv(u, 0)
    }
}

impl ParamCurveDeriv for Helix {
    fn deriv(&self, u: f64, k: usize) -> [f64; 3] {
        let u = u.clamp(0.0, 1.0);
        let om = 2.0 * core::f64::consts::PI * self.w;
        let ph = om * u;
        let (s, c) = (libm::sin(ph), libm::cos(ph));
        let f = self.r * om.powi(k as i32);
        match k % 4 {
            _ if k == 0 => [self.r * c, self.r * s, self.h * u],
            1 => [-f * s, f * c, self.h],
            2 => [-f * c, -f * s, 0.0],
            3 => [f * s, -f * c, 0.0],
            _ => [f * c, f * s, 0.0],
        }
    }
}

/// A 1-D wave `x(u) = offset + amp·sin(2πwu)` for `u ∈ [0, 1]`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Wave {
    pub(crate) offset: f64,
    pub(crate) amp: f64,
    pub(crate) cycles: f64,
}

impl ParamCurve for Wave {
    type Point = [f64; 1];
    fn domain(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn eval(&self, u: f64) -> [f64; 1] {
        self.deriv(u, 0)
    }
}

impl ParamCurveDeriv for Wave {
    fn deriv(&self, u: f64, k: usize) -> [f64; 1] {
        let u = u.clamp(0.0, 1.0);
        let om = 2.0 * core::f64::consts::PI * self.cycles;
        let (s, c) = (libm::sin(om * u), libm::cos(om * u));
        let f = self.amp * om.powi(k as i32);
        [match k % 4 {
            _ if k == 0 => self.offset + self.amp * s,
            1 => f * c,
            2 => -f * s,
            3 => -f * c,
            _ => f * s,
        }]
    }
}

/// The exact position, velocity and acceleration of `curve` under `timing` at (fractional)
/// path tick `k` of `path` (with the path's time stretch).
pub(crate) fn exact<N: Number, const A: usize, const P: usize, C, T>(
    curve: &C,
    timing: &T,
    path: &Path<N, A, P>,
    k: f64,
) -> ([f64; A], [f64; A], [f64; A])
where
    C: ParamCurveDeriv<Point = [f64; A]>,
    T: TestTiming,
{
    let t = if k >= f64::from(path.ticks()) {
        path.plan_duration()
    } else {
        path.plan_time(k)
    };
    let sigma = path.time_scale();
    let (u, du) = timing.param(t);
    let ddu = timing.ddu(t);
    let p = curve.eval(u);
    let d1 = curve.deriv(u, 1);
    let d2 = curve.deriv(u, 2);
    let v = core::array::from_fn(|i| d1[i] * du * sigma);
    let a = core::array::from_fn(|i| (d2[i] * du * du + d1[i] * ddu) * sigma * sigma);
    (p, v, a)
}

/// [`compile`] into a boxed path, in place ([`compile_into`]): a path of thousands of pieces
/// (hundreds of KB, MBs in `f64` with several axes) stays off the test thread's stack.
pub(crate) fn compile_boxed<N, const A: usize, const P: usize, M>(
    trajectory: &M,
    rate_hz: f64,
    options: &CompileOptions,
) -> Result<std::boxed::Box<Path<N, A, P>>, Error>
where
    N: Number,
    M: Trajectory + ?Sized,
{
    let mut path = boxed_path();
    compile_into(trajectory, rate_hz, options, &mut path)?;
    Ok(path)
}

/// An empty path on the heap, written in place: in a small function of its own the optimized
/// test build allocates first and writes only the header and the length.
#[inline(never)]
fn boxed_path<N: Number, const A: usize, const P: usize>() -> std::boxed::Box<Path<N, A, P>> {
    std::boxed::Box::new(Path::new())
}
