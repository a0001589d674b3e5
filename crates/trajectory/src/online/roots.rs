//! Real roots of a polynomial of degree at most [`MAX_DEGREE`] in an interval, in bounded
//! work: the roots of the derivative split the interval into pieces on which the polynomial
//! is monotone (recursively, down to a linear derivative), and each piece whose ends differ
//! in sign holds one root, found by Newton's method safeguarded by bisection (root isolation
//! by the critical points: Press, Teukolsky, Vetterling & Flannery, *Numerical Recipes*,
//! 3rd ed., §9.4 "Newton-Raphson Method Using Derivative" with bracketing, and §5.6 on
//! polynomial roots).

use super::real::Real;

/// The highest degree the solver needs.
pub(super) const MAX_DEGREE: usize = 4;

/// The most Newton or bisection steps per root. Newton's steps inside the bracket converge
/// quadratically from the chord's start and end the search within a few steps as soon as a
/// step no longer moves the point; bisection alone would narrow the bracket by `2⁻⁸⁰`. At
/// the bound the search returns its current point.
const MAX_STEPS: usize = 80;

/// The roots found in an interval, in increasing order.
#[derive(Clone, Copy, Debug)]
pub(super) struct Roots<R> {
    values: [R; MAX_DEGREE],
    len: usize,
}

impl<R: Real> Roots<R> {
    fn new() -> Self {
        Roots {
            values: [R::ZERO; MAX_DEGREE],
            len: 0,
        }
    }

    /// Appends `x` unless it repeats the last root (a root found from both sides of a
    /// critical point) or the storage is full.
    fn push(&mut self, x: R) {
        if self.len > 0 && self.values[self.len - 1] == x {
            return;
        }
        if self.len < MAX_DEGREE {
            self.values[self.len] = x;
            self.len += 1;
        }
    }

    /// The roots.
    pub(super) fn as_slice(&self) -> &[R] {
        &self.values[..self.len]
    }
}

/// `p(x)` and `p'(x)` for the coefficients `c` in ascending order (Horner's rule), and a
/// bound of the rounding error of `p(x)`.
fn eval<R: Real>(c: &[R], x: R) -> (R, R, R) {
    let mut p = R::ZERO;
    let mut d = R::ZERO;
    let mut size = R::ZERO;
    let ax = x.abs();
    for &k in c.iter().rev() {
        d = d * x + p;
        p = p * x + k;
        size = size * ax + k.abs();
    }
    // Horner's rule errs by at most about 2n·ε·Σ|cᵢ||x|ⁱ (Higham, *Accuracy and Stability
    // of Numerical Algorithms*, 2nd ed., §5.1).
    let n = R::from_i16(i16::try_from(2 * c.len()).unwrap_or(i16::MAX));
    (p, d, n * R::EPS * size)
}

/// The real roots of `c[0] + c[1]·x + … + c[n]·xⁿ` (`n ≤ MAX_DEGREE`) in `[lo, hi]`, in
/// increasing order. A root of even multiplicity (the polynomial touches zero at a critical
/// point, within its rounding error) is reported once.
pub(super) fn roots_in<R: Real>(c: &[R], lo: R, hi: R) -> Roots<R> {
    let mut out = Roots::new();
    let mut n = c.len().min(MAX_DEGREE + 1);
    while n > 0 && c[n - 1] == R::ZERO {
        n -= 1;
    }
    if n < 2 || lo.partial_cmp(&hi).is_none_or(core::cmp::Ordering::is_gt) {
        return out;
    }
    let c = &c[..n];
    if n == 3 {
        return quadratic_in(c[0], c[1], c[2], lo, hi);
    }
    if cannot_vanish(c, lo, hi) {
        return out;
    }
    // The pieces of monotony: the derivative's roots in the interval.
    let mut d = [R::ZERO; MAX_DEGREE];
    for (i, &k) in c.iter().enumerate().skip(1) {
        d[i - 1] = k * R::from_i16(i16::try_from(i).unwrap_or(0));
    }
    let critical = if n > 2 {
        roots_in(&d[..n - 1], lo, hi)
    } else {
        Roots::new()
    };
    let mut left = lo;
    let (mut f_left, _, mut err_left) = eval(c, left);
    if f_left.abs() <= err_left {
        out.push(left);
    }
    for i in 0..=critical.len {
        let right = if i < critical.len {
            critical.values[i]
        } else {
            hi
        };
        let (f_right, _, err_right) = eval(c, right);
        let left_zero = f_left.abs() <= err_left;
        let right_zero = f_right.abs() <= err_right;
        if right_zero {
            if !(left_zero && right == left) {
                out.push(right);
            }
        } else if !left_zero && (f_left < R::ZERO) != (f_right < R::ZERO) {
            out.push(bracketed(c, left, right, f_left));
        }
        left = right;
        f_left = f_right;
        err_left = err_right;
    }
    out
}

/// The coefficients scaled by a power of two (exactly: the roots are unchanged) so that
/// the largest magnitude lies in `[1, 2)`. The forms' coefficients grow with powers of the
/// jerk (`J²·a_max²` and more): unscaled, the `f32` discriminant of a quadratic (the only
/// product of two coefficients) overflows for jerks of a few `10⁵`.
fn normalized<R: Real>(c: &[R]) -> [R; MAX_DEGREE + 1] {
    let mut out = [R::ZERO; MAX_DEGREE + 1];
    let largest = c.iter().fold(R::ZERO, |m, &x| m.max_of(x.abs())).to_f64();
    // 2^−e for the binary exponent e of `largest` (its bits: no logarithm on the device).
    let exponent = i64::try_from((largest.to_bits() >> 52) & 0x7ff).unwrap_or(1023) - 1023;
    let scale = if largest > 0.0 && largest.is_finite() && exponent.abs() < 1000 {
        #[allow(clippy::cast_sign_loss)]
        let bits = ((1023 - exponent) as u64) << 52;
        R::lit(f64::from_bits(bits))
    } else {
        R::ONE
    };
    for (o, &x) in out.iter_mut().zip(c) {
        *o = x * scale;
    }
    out
}

/// Whether the polynomial keeps its sign on `[lo, hi]` for a reason seen at once: at `lo`
/// it is farther from zero than a bound of `|p'|` (from `Σ i·|cᵢ|·rⁱ⁻¹`, `r = max(|lo|,
/// |hi|)`) times the interval's length allows it to travel.
fn cannot_vanish<R: Real>(c: &[R], lo: R, hi: R) -> bool {
    let r = lo.abs().max_of(hi.abs());
    let mut slope = R::ZERO;
    let mut value = R::ZERO;
    for (i, &k) in c.iter().enumerate().rev() {
        value = value * lo + k;
        if i > 0 {
            slope = slope * r + k.abs() * R::from_i16(i16::try_from(i).unwrap_or(0));
        }
    }
    // A margin for the rounding of both sums.
    value.abs() > slope * (hi - lo) * R::lit(1.001) + R::lit(64.0) * R::EPS * value.abs()
}

/// The roots of `c₀ + c₁x + c₂x²` in `[lo, hi]` (the numerically stable form of the
/// quadratic formula; a double root reported once), in increasing order.
fn quadratic_in<R: Real>(c0: R, c1: R, c2: R, lo: R, hi: R) -> Roots<R> {
    let mut out = Roots::new();
    let [c0, c1, c2, ..] = normalized(&[c0, c1, c2]);
    let disc = c1 * c1 - R::lit(4.0) * c2 * c0;
    let (mut x1, mut x2);
    if disc.is_negative() {
        // A double root within rounding: the vertex, if the polynomial touches zero there.
        let x = -c1 / (R::TWO * c2);
        let (f, _, err) = eval(&[c0, c1, c2], x);
        if f.abs() > err {
            return out;
        }
        x1 = x;
        x2 = x;
    } else {
        let q =
            -(c1 + if c1.is_negative() {
                -disc.root()
            } else {
                disc.root()
            }) * R::HALF;
        x1 = q / c2;
        x2 = if q == R::ZERO { x1 } else { c0 / q };
        if x2 < x1 {
            core::mem::swap(&mut x1, &mut x2);
        }
    }
    for x in [x1, x2] {
        if x >= lo && x <= hi {
            out.push(x);
        }
    }
    out
}

/// The root of `c` in `[l, r]`, where the polynomial is monotone and `p(l)` (`f_l`) and
/// `p(r)` differ in sign: Newton steps that stay inside the bracket, bisection otherwise;
/// every step narrows the bracket. At most [`MAX_STEPS`] steps.
fn bracketed<R: Real>(c: &[R], mut l: R, mut r: R, f_l: R) -> R {
    let l_negative = f_l < R::ZERO;
    // Start where the chord crosses zero.
    let f_r = eval(c, r).0;
    let chord = l + (r - l) * (f_l / (f_l - f_r));
    let mut x = if chord > l && chord < r {
        chord
    } else {
        (l + r) * R::HALF
    };
    for _ in 0..MAX_STEPS {
        let (f, df, _) = eval(c, x);
        if f == R::ZERO {
            return x;
        }
        if (f < R::ZERO) == l_negative {
            l = x;
        } else {
            r = x;
        }
        let newton = x - f / df;
        let next = if newton > l && newton < r {
            newton
        } else {
            (l + r) * R::HALF
        };
        if (next - x).abs() <= R::EPS * x.abs() || next == l || next == r {
            return next;
        }
        x = next;
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    fn expand(roots: &[f64]) -> [f64; 7] {
        let mut c = [0.0; 7];
        c[0] = 1.0;
        for (k, &r) in roots.iter().enumerate() {
            for i in (0..=k + 1).rev() {
                let prev = if i > 0 { c[i - 1] } else { 0.0 };
                c[i] = prev - r * c[i];
            }
        }
        c
    }

    #[test]
    fn finds_every_simple_root_in_the_interval() {
        let want = [-3.0, 0.25, 1.0, 7.0];
        let c = expand(&want);
        let got = roots_in(&c[..5], -10.0, 10.0);
        assert_eq!(got.as_slice().len(), 4);
        for (g, w) in got.as_slice().iter().zip(want) {
            assert!((g - w).abs() < 1e-12, "{g} vs {w}");
        }
        let inner = roots_in(&c[..5], 0.0, 1.5);
        assert_eq!(inner.as_slice().len(), 2);
        assert!((inner.as_slice()[0] - 0.25).abs() < 1e-14);
    }

    #[test]
    fn reports_a_double_root_once_and_ends_that_are_roots() {
        // (x − 1)²(x + 2)
        let c = expand(&[1.0, 1.0, -2.0]);
        let got = roots_in(&c[..4], -5.0, 5.0);
        assert_eq!(got.as_slice().len(), 2, "{:?}", got.as_slice());
        assert!((got.as_slice()[0] + 2.0).abs() < 1e-12);
        assert!((got.as_slice()[1] - 1.0).abs() < 1e-7);
        let at_end = roots_in(&c[..4], -2.0, 0.0);
        assert_eq!(at_end.as_slice(), &[-2.0]);
    }

    #[test]
    fn f32_and_degenerate_inputs() {
        let c: [f32; 3] = [-2.0, 0.0, 1.0]; // x² − 2
        let got = roots_in(&c, 0.0, 2.0);
        assert_eq!(got.as_slice().len(), 1);
        assert!((got.as_slice()[0] - core::f32::consts::SQRT_2).abs() < 2e-7);
        assert!(
            roots_in(&[1.0_f64, 0.0, 0.0], -1.0, 1.0)
                .as_slice()
                .is_empty()
        );
        assert!(roots_in(&c, 2.0, 0.0).as_slice().is_empty());
        assert!(roots_in(&c, f32::NAN, 1.0).as_slice().is_empty());
        assert_eq!(roots_in(&[-1.0_f64, 2.0], 0.0, 1.0).as_slice(), &[0.5]);
    }
}
