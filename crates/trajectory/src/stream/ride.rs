//! Axes that ride along the path: an extruder, a rotary axis. They do not shape the path
//! (its arc length, curvature and corner tolerance are those of the other axes); along a
//! move each goes from its start to its end in proportion to the move's arc length, and
//! through a corner blend from the value and rate it leaves one move with to those it
//! enters the next with.
//!
//! On a span of a move, `e(s) = e₀ + (e₁ − e₀)·s/L`. On a blend, over its parameter `u`, the
//! quintic Hermite interpolant of the values, first and second derivatives by `u` at both
//! ends: where a move has `e = e₀ + m·s`, its derivatives by the blend's parameter are
//! `m·σ` and `m·σ'` (`σ = |c'(u)|`, `σ' = c'·c''/σ`), so the axis's velocity and acceleration
//! are continuous through the blend.

/// One axis riding along a segment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Ride {
    /// On a span: from `e0` to `e1` in proportion to the arc length.
    Linear { e0: f64, e1: f64 },
    /// On a blend: the monomial coefficients of a quintic in the blend's parameter.
    Quintic([f64; 6]),
    /// On a move of the riding axes alone: the segment traces them itself.
    Alone,
}

impl Default for Ride {
    fn default() -> Self {
        Ride::Linear { e0: 0.0, e1: 0.0 }
    }
}

/// A value with its first and second derivatives.
pub(crate) type Jet = (f64, f64, f64);

impl Ride {
    /// The quintic over `[0, 1]` with the value, first and second derivative `start` at 0 and
    /// `end` at 1.
    pub(crate) fn hermite((p0, v0, a0): Jet, (p1, v1, a1): Jet) -> Self {
        let d = p1 - p0;
        Ride::Quintic([
            p0,
            v0,
            0.5 * a0,
            10.0 * d - 6.0 * v0 - 4.0 * v1 - 0.5 * (3.0 * a0 - a1),
            -15.0 * d + 8.0 * v0 + 7.0 * v1 + 0.5 * (3.0 * a0 - 2.0 * a1),
            6.0 * d - 3.0 * (v0 + v1) - 0.5 * (a0 - a1),
        ])
    }

    /// The rate `de/ds` on a span of arc length `length` (0 on a blend).
    pub(crate) fn slope(&self, length: f64) -> f64 {
        match *self {
            Ride::Linear { e0, e1 } => (e1 - e0) / length,
            Ride::Quintic(_) | Ride::Alone => 0.0,
        }
    }

    /// On a span of arc length `length`: the value at the arc length `local` from its start
    /// (its end value exactly at the end), and `de/ds`.
    pub(crate) fn along(&self, local: f64, length: f64) -> (f64, f64) {
        match *self {
            Ride::Linear { e0, e1 } if local >= length => (e1, (e1 - e0) / length),
            Ride::Linear { e0, e1 } => (e0 + (e1 - e0) * (local / length), (e1 - e0) / length),
            Ride::Quintic(_) | Ride::Alone => (0.0, 0.0),
        }
    }

    /// On a blend: the `k`-th derivative by the parameter at `u` (`k ≤ 5`; 0 beyond, and on a
    /// span).
    pub(crate) fn poly(&self, u: f64, k: usize) -> f64 {
        let Ride::Quintic(c) = self else {
            return 0.0;
        };
        let Some(falling) = FALLING.get(k) else {
            return 0.0;
        };
        // the k-th derivative's coefficients: c_i · i!/(i − k)!
        let mut acc = 0.0;
        for (&c, &f) in c.iter().zip(falling).skip(k).rev() {
            acc = acc * u + c * f;
        }
        acc
    }
}

/// The falling factorials `i!/(i − k)!` for `k` (row) and `i` (column) up to 5, the factors
/// of the quintic's coefficients in its `k`-th derivative (0 for `i < k`, where the
/// derivative has no term).
const FALLING: [[f64; 6]; 6] = [
    [1.0, 1.0, 1.0, 1.0, 1.0, 1.0],
    [0.0, 1.0, 2.0, 3.0, 4.0, 5.0],
    [0.0, 0.0, 2.0, 6.0, 12.0, 20.0],
    [0.0, 0.0, 0.0, 6.0, 24.0, 60.0],
    [0.0, 0.0, 0.0, 0.0, 24.0, 120.0],
    [0.0, 0.0, 0.0, 0.0, 0.0, 120.0],
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_hermite_quintic_meets_its_ends() {
        let r = Ride::hermite((1.0, 2.0, -3.0), (5.0, -1.0, 0.5));
        let at = |u: f64| (r.poly(u, 0), r.poly(u, 1), r.poly(u, 2));
        let close = |a: Jet, b: Jet| {
            (a.0 - b.0).abs() < 1e-12 && (a.1 - b.1).abs() < 1e-12 && (a.2 - b.2).abs() < 1e-12
        };
        assert!(close(at(0.0), (1.0, 2.0, -3.0)), "{:?}", at(0.0));
        assert!(close(at(1.0), (5.0, -1.0, 0.5)), "{:?}", at(1.0));
        // the derivative by differences
        let h = 1e-6;
        let fd = (r.poly(0.3 + h, 0) - r.poly(0.3 - h, 0)) / (2.0 * h);
        assert!((fd - r.poly(0.3, 1)).abs() < 1e-8);
        let fd3 = (r.poly(0.3 + h, 2) - r.poly(0.3 - h, 2)) / (2.0 * h);
        assert!((fd3 - r.poly(0.3, 3)).abs() < 1e-6);
    }

    /// The table against the falling factorials multiplied out.
    #[test]
    fn falling_factorials() {
        for (k, row) in FALLING.iter().enumerate() {
            for (i, &f) in row.iter().enumerate() {
                let want = if i < k {
                    0.0
                } else {
                    ((i + 1 - k)..=i).fold(1.0, |p, f| p * f as f64)
                };
                assert_eq!(f, want, "{k} {i}");
            }
        }
        assert_eq!(Ride::Quintic([1.0; 6]).poly(0.5, 6), 0.0);
    }

    #[test]
    fn a_span_rides_in_proportion_and_ends_exactly() {
        let r = Ride::Linear { e0: 0.1, e1: 0.7 };
        let (end, rate) = r.along(3.0, 3.0);
        assert!(end == 0.7 && (rate - 0.2).abs() < 1e-15);
        let (e, m) = r.along(1.5, 3.0);
        assert!((e - 0.4).abs() < 1e-15 && (m - 0.2).abs() < 1e-15);
    }
}
