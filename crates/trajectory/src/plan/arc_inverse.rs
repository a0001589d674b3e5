//! The curve parameter at an arc length: the root of the arc-length table's interpolant
//! `s(u)`, found by a safeguarded secant iteration.

use strak_curves::{ArcLengthTable, ParamCurveDeriv};

use super::{norm64, to_param};

/// The most iterations: the bracket at least halves every second one (Illinois), and 128
/// exhaust the `f64` resolution of any interval.
const MAX_STEPS: usize = 128;

/// The parameter `u` at which the table's interpolant of the arc length reaches `s`, and the
/// curve's speed `|c'(u)|` there: the root of `length_at(u) = s`
/// ([`ArcLengthTable::length_at`], a cubic Hermite interpolant per interval with the slopes
/// `|c'|` at the samples, monotone), to the resolution of `f64`. `s` is clamped to
/// `[0, L]`; `0` and `L` give the domain ends exactly.
///
/// Why not the table's inverse interpolant [`ArcLengthTable::param_at`]: where the curve's
/// speed vanishes (an end with a repeated control point, a cusp), `du/ds = 1/|c'|` grows
/// without bound, which a cubic in `s` cannot follow (its slopes are limited to three times
/// the secant there), and the motion's speed `|c'(u)|·(du/ds)·ṡ` then misses the planned
/// `ṡ` by tens of percent, with accelerations several times the plan's. The interpolant
/// of `s(u)` has the slope `|c'|` itself and follows `s(u) ≈ L − k·(u_end − u)²` there.
///
/// The iteration is the Illinois variant of regula falsi on the sampling interval that
/// holds `s`, starting from the table's inverse (Dahlquist & Björck, *Numerical Methods*,
/// §6.2.3): superlinear, the root always bracketed, and no derivative of the curve but the
/// one of the answer.
pub(crate) fn param_at_length<C: ParamCurveDeriv, const N: usize>(
    curve: &C,
    table: &ArcLengthTable<f64, N>,
    s: f64,
) -> (f64, f64) {
    let speed = |u: f64| norm64(&curve.deriv(to_param(curve, u), 1));
    let (start, end) = table.domain();
    let length = table.length();
    if !(s > 0.0) {
        return (start, speed(start));
    }
    if s >= length {
        return (end, speed(end));
    }
    let ((mut lo, s_lo), (mut hi, s_hi)) = bracket(table, s);
    let (mut f_lo, mut f_hi) = (s_lo - s, s_hi - s);
    let resolution = 4.0 * f64::EPSILON * length;
    // The table's inverse first, then secants of the bracket.
    let mut u = table.param_at(s).clamp(lo, hi);
    let mut kept = 0_i8; // which end stayed last time: −1 low, 1 high
    for _ in 0..MAX_STEPS {
        let f = table.length_at(u) - s;
        if !(f.abs() > resolution) {
            break;
        }
        if f < 0.0 {
            (lo, f_lo) = (u, f);
            if kept == 1 {
                f_hi *= 0.5;
            }
            kept = 1;
        } else {
            (hi, f_hi) = (u, f);
            if kept == -1 {
                f_lo *= 0.5;
            }
            kept = -1;
        }
        let secant = lo - f_lo * (hi - lo) / (f_hi - f_lo);
        let next = if secant > lo && secant < hi {
            secant
        } else {
            0.5 * (lo + hi)
        };
        if !(next > lo && next < hi) {
            break;
        }
        u = next;
    }
    (u, speed(u))
}

/// The sampling interval of the table that holds the arc length `s` (`0 < s < L`), as
/// `(u, s)` at its ends, by binary search over the samples.
fn bracket<const N: usize>(table: &ArcLengthTable<f64, N>, s: f64) -> ((f64, f64), (f64, f64)) {
    let sample = |i: usize| {
        table
            .sample(i)
            .unwrap_or((table.domain().1, table.length()))
    };
    // The last sample with an arc length ≤ s (sample 0 has s = 0).
    let (mut lo, mut hi) = (0, N.saturating_sub(1));
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if sample(mid).1 <= s {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    (sample(lo), sample(hi))
}

#[cfg(test)]
mod tests {
    use super::*;
    use strak_curves::{Bezier, ParamCurve};

    /// A cubic Bézier curve whose last two control points coincide: its speed vanishes at
    /// the end, `|c'(u)| ∝ (1 − u)`.
    fn stalling() -> Bezier<[f64; 2], 4> {
        let p = [[-6.325, -8.05], [-4.025, 23.575], [-21.85, 4.025]];
        Bezier::new([p[0], p[1], p[2], p[2]]).unwrap()
    }

    #[test]
    fn the_root_of_the_forward_interpolant() {
        let c = stalling();
        let table = ArcLengthTable::<f64, 64>::new(&c, 1e-9).unwrap();
        let length = table.length();
        for k in 0..=1000 {
            let s = length * f64::from(k) / 1000.0;
            let (u, v) = param_at_length(&c, &table, s);
            assert!(
                (table.length_at(u) - s).abs() <= 4.0 * f64::EPSILON * length,
                "{k}"
            );
            assert_eq!(v, norm64(&c.deriv(u, 1)));
        }
        assert_eq!(param_at_length(&c, &table, 0.0).0, 0.0);
        assert_eq!(param_at_length(&c, &table, length).0, 1.0);
        assert_eq!(param_at_length(&c, &table, -1.0).0, 0.0);
        assert_eq!(param_at_length(&c, &table, f64::NAN).0, 0.0);
        assert_eq!(param_at_length(&c, &table, 2.0 * length).0, 1.0);
    }

    /// The speed factor `|dc/ds|` of the mapping, by central differences of `c(u(s))`:
    /// within 10⁻⁴ of 1 along the whole curve with the forward root, the end included,
    /// where the table's inverse interpolant misses by more than 10 %.
    #[test]
    fn unit_speed_up_to_a_stalling_end() {
        let c = stalling();
        let table = ArcLengthTable::<f64, 64>::new(&c, 1e-9).unwrap();
        let length = table.length();
        let factor = |inverse: &dyn Fn(f64) -> f64, s: f64| {
            let h = 1e-4;
            let (a, b) = (c.eval(inverse(s - h)), c.eval(inverse(s + h)));
            libm::hypot(b[0] - a[0], b[1] - a[1]) / (2.0 * h)
        };
        let root = |s: f64| param_at_length(&c, &table, s).0;
        let table_inverse = |s: f64| table.param_at(s);
        let (mut worst_root, mut worst_table) = (0.0_f64, 0.0_f64);
        for k in 1..2000 {
            let s = length * f64::from(k) / 2000.0;
            if s + 1e-4 < length {
                worst_root = worst_root.max((factor(&root, s) - 1.0).abs());
                worst_table = worst_table.max((factor(&table_inverse, s) - 1.0).abs());
            }
        }
        assert!(worst_root < 1e-4, "{worst_root}");
        assert!(worst_table > 0.1, "{worst_table}");
    }
}
