//! The curve parameter at an arc length: the root of the arc-length table's interpolant
//! `s(u)`, found by a safeguarded Newton iteration.

use strak_curves::{ArcLengthTable, ParamCurveDeriv};

use super::{norm64, to_param};

/// The most Newton or bisection steps: bisection alone halves the bracket each step, and 64
/// steps exhaust the `f64` resolution of any interval.
const MAX_STEPS: usize = 64;

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
/// The iteration is Newton's method for `length_at(u) − s` with the slope `|c'(u)|`,
/// starting at the table's inverse and kept inside the sampling interval that holds `s`
/// (a step leaving the current bracket bisects it instead: Press, Teukolsky, Vetterling &
/// Flannery, *Numerical Recipes*, 3rd ed., §9.4, "rtsafe").
pub(crate) fn param_at_length<C: ParamCurveDeriv, const N: usize>(
    curve: &C,
    table: &ArcLengthTable<f64, N>,
    s: f64,
) -> (f64, f64) {
    let speed = |u: f64| norm64(&curve.deriv(to_param(curve, u), 1));
    let (start, end) = table.domain();
    let length = table.length();
    if s.is_nan() || s <= 0.0 {
        return (start, speed(start));
    }
    if s >= length {
        return (end, speed(end));
    }
    let (mut lo, mut hi) = bracket(table, s);
    let mut u = table.param_at(s).clamp(lo, hi);
    let resolution = 4.0 * f64::EPSILON * length;
    for _ in 0..MAX_STEPS {
        let f = table.length_at(u) - s;
        let v = speed(u);
        if f.is_nan() || f.abs() <= resolution {
            return (u, v);
        }
        if f > 0.0 {
            hi = u;
        } else {
            lo = u;
        }
        let newton = u - f / v;
        let next = if newton > lo && newton < hi {
            newton
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

/// The parameters of the table's sampling interval that holds the arc length `s`
/// (`0 < s < L`), by binary search over the samples.
fn bracket<const N: usize>(table: &ArcLengthTable<f64, N>, s: f64) -> (f64, f64) {
    let arc = |i: usize| table.sample(i).map_or(f64::INFINITY, |(_, si)| si);
    let param = |i: usize| table.sample(i).map_or(table.domain().1, |(ui, _)| ui);
    // The last sample with an arc length ≤ s (sample 0 has s = 0).
    let (mut lo, mut hi) = (0, N.saturating_sub(1));
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if arc(mid) <= s {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    (param(lo), param(hi))
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
            assert!((table.length_at(u) - s).abs() <= 4.0 * f64::EPSILON * length, "{k}");
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
