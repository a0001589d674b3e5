//! The cubic Bézier approximation of a quarter circle (seeds/004, "Approximation von
//! Viertelkreis", "Bezier-Viertelkreis") and its radial error.

use crate::bernstein::bezier_point;
use crate::vecops::vec_norm;

/// The seeds/004 Bézier quarter circle with inner control offset `κ`:
/// `(0, 1), (κ, 1), (1, κ), (1, 0)`. The seed uses `κ = 0.551897`; the classical choice
/// `4/3 (√2 − 1) ≈ 0.5522847` puts `c(1/2)` exactly on the circle.
///
/// ```
/// let b = strak_ref::quarter_circle_bezier(0.5);
/// assert_eq!(b[2], vec![1.0, 0.5]);
/// ```
pub fn quarter_circle_bezier(kappa: f64) -> Vec<Vec<f64>> {
    vec![
        vec![0.0, 1.0],
        vec![kappa, 1.0],
        vec![1.0, kappa],
        vec![1.0, 0.0],
    ]
}

/// The maximum radial error `max_{t∈[0,1]} |‖c(t)‖ − 1|` of [`quarter_circle_bezier`]`(κ)`:
/// `100 000` equal steps of `t` (the curve evaluated as a Bernstein sum), then a
/// golden-section search for the maximum on the two steps around the best sample, down to an
/// interval of `1e−13`.
///
/// Values (pinned by the unit tests):
/// * `κ = 0.551897` (seeds/004) → `2.0564e−4`, attained at `t = 1/2` where the curve is
///   *inside* the circle (`‖c(1/2)‖ − 1 = −2.0564e−4`); outward it reaches `+1.9278e−4` near
///   `t ≈ 0.181` and `0.819`. So the seed's `c(1/2) = (cos 45°, sin 45°)` holds only to
///   `1.5e−4` per coordinate. (The minimax choice `κ ≈ 0.551915` equalizes both at ≈ `1.961e−4`.)
/// * `κ = 4/3 (√2 − 1) ≈ 0.5522847` → `2.7253e−4`, near `t ≈ 0.211` and `0.789`; the curve is
///   never inside the circle and exact at `t = 0, 1/2, 1`.
///
/// ```
/// let e = strak_ref::quarter_circle_radial_error(4.0 / 3.0 * (2f64.sqrt() - 1.0));
/// assert!((e - 2.7253e-4).abs() < 1e-7);
/// ```
pub fn quarter_circle_radial_error(kappa: f64) -> f64 {
    let ctrl = quarter_circle_bezier(kappa);
    let err = |t: f64| (vec_norm(&bezier_point(&ctrl, t)) - 1.0).abs();
    let steps: usize = 100_000;
    let mut best_j: usize = 0;
    let mut best = err(0.0);
    for j in 1..=steps {
        let e = err(j as f64 / steps as f64);
        if e > best {
            best = e;
            best_j = j;
        }
    }
    // Golden-section search for the maximum on [t_{j−1}, t_{j+1}] ∩ [0, 1].
    let mut a = (best_j.saturating_sub(1)) as f64 / steps as f64;
    let mut b = ((best_j + 1).min(steps)) as f64 / steps as f64;
    let r = (5f64.sqrt() - 1.0) / 2.0;
    let mut x1 = b - r * (b - a);
    let mut x2 = a + r * (b - a);
    let mut f1 = err(x1);
    let mut f2 = err(x2);
    while b - a > 1e-13 {
        if f1 > f2 {
            b = x2;
            x2 = x1;
            f2 = f1;
            x1 = b - r * (b - a);
            f1 = err(x1);
        } else {
            a = x1;
            x1 = x2;
            f1 = f2;
            x2 = a + r * (b - a);
            f2 = err(x2);
        }
    }
    best.max(f1).max(f2)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed_quarter_circle_point_formulas() {
        // seeds/004: f1(t) = 3t(1−t)² κ + 3t²(1−t) + t³ (x), f2(t) = (1−t)³ + 3t(1−t)² + 3t²(1−t) κ (y).
        let k = 0.551897;
        let b = quarter_circle_bezier(k);
        for j in 0..=20 {
            let t = j as f64 / 20.0;
            let s = 1.0 - t;
            let x = 3.0 * t * s * s * k + 3.0 * t * t * s + t * t * t;
            let y = s * s * s + 3.0 * t * s * s + 3.0 * t * t * s * k;
            let p = bezier_point(&b, t);
            assert!((p[0] - x).abs() < 1e-15 && (p[1] - y).abs() < 1e-15);
        }
        // P(0.5) ≈ (cos 45°, sin 45°).
        let p = bezier_point(&b, 0.5);
        let c = std::f64::consts::FRAC_1_SQRT_2;
        assert!((p[0] - c).abs() < 1.5e-4 && (p[1] - c).abs() < 1.5e-4);
        assert!((p[0] - c).abs() > 1.4e-4); // the seed's κ is not exact at t = 1/2
    }

    #[test]
    fn radial_errors_of_both_kappas() {
        let classic = 4.0 / 3.0 * (2f64.sqrt() - 1.0);
        let e_classic = quarter_circle_radial_error(classic);
        let e_seed = quarter_circle_radial_error(0.551897);
        assert!((e_classic - 2.7253e-4).abs() < 1e-8, "{e_classic:e}");
        assert!((e_seed - 2.0564e-4).abs() < 1e-8, "{e_seed:e}");
        let inside = vec_norm(&bezier_point(&quarter_circle_bezier(0.551897), 0.5)) - 1.0;
        assert!((inside + 2.0564e-4).abs() < 1e-8);
        assert!((quarter_circle_radial_error(0.551915) - 1.961e-4).abs() < 1e-7);
        // Classic κ is exact at t = 1/2.
        let p = bezier_point(&quarter_circle_bezier(classic), 0.5);
        assert!((vec_norm(&p) - 1.0).abs() < 1e-15);
        // Exact circle would need no error: a bad κ gives a big error.
        assert!(quarter_circle_radial_error(0.5) > 1e-2);
    }
}
