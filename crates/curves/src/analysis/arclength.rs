//! Arc length `s(u) = ∫ |c'(u)| du`, its inverse `u(s)`, and an arc-length table for time laws
//! (adaptive Gaussian quadrature and a table inverted by interpolation, as in Guenter &
//! Parent, "Computing the Arc Length of Parametric Curves", *IEEE Computer Graphics and
//! Applications* 10(3), 1990).
//!
//! The quadrature, its accuracy and its work bound are documented at [`arc_length`].

use crate::curve::{ParamCurve, ParamCurveDeriv, ScalarOf};
use crate::error::Error;
use crate::point::Point;
use crate::scalar::Scalar;

use super::{check_length_accuracy, greater, norm64, param};

/// Nodes of the 8-point Gauss–Legendre rule on `[−1, 1]` (the positive half; Abramowitz &
/// Stegun, *Handbook of Mathematical Functions*, Table 25.4).
const GL_X: [f64; 4] = [
    0.183_434_642_495_649_8,
    0.525_532_409_916_329,
    0.796_666_477_413_626_7,
    0.960_289_856_497_536_3,
];
/// Weights of the 8-point Gauss–Legendre rule, matching [`GL_X`].
const GL_W: [f64; 4] = [
    0.362_683_783_378_362,
    0.313_706_645_877_887_3,
    0.222_381_034_453_374_5,
    0.101_228_536_290_376_26,
];

/// The deepest bisection of an interval (parameter widths down to `2⁻³²` of a piece).
const MAX_DEPTH: u32 = 32;

/// The most interval splits of one piece's adaptive integral (each split evaluates two
/// 8-point rules); beyond it the accuracy counts as unreachable. A smooth speed needs a few
/// splits per part, a cusp about two per bisection level; only speeds that no rule resolves
/// (oscillations finer than the nodes, or the rounding noise of fixed-point derivatives)
/// run into it.
const MAX_SPLITS: usize = 1 << 12;

/// Iteration limit of the safeguarded Newton method in [`param_at_length`]; bisection alone
/// reaches the resolution of `f64` in fewer than 64 steps.
const MAX_NEWTON: usize = 128;

/// The speed `|c'(u)|` in `f64`, with `u` rounded to the scalar and clamped to `[lo, hi]`.
fn speed<C: ParamCurveDeriv>(curve: &C, u: f64, lo: ScalarOf<C>, hi: ScalarOf<C>) -> f64 {
    norm64(&curve.deriv(param(u, lo, hi), 1))
}

/// 8-point Gauss–Legendre of `|c'|` over `[a, b] ⊂ [lo, hi]`.
fn gauss<C: ParamCurveDeriv>(curve: &C, a: f64, b: f64, lo: ScalarOf<C>, hi: ScalarOf<C>) -> f64 {
    let mid = 0.5 * (a + b);
    let half = 0.5 * (b - a);
    let mut sum = 0.0;
    for (x, w) in GL_X.iter().zip(GL_W.iter()) {
        let d = half * x;
        sum += w * (speed(curve, mid - d, lo, hi) + speed(curve, mid + d, lo, hi));
    }
    sum * half
}

/// The number of equal parts each interval is split into before adaptive refinement starts:
/// comparing one 8-point rule with its two halves can agree on a wrong value when a feature
/// (a near-cusp, a fast turn) hides between the nodes; 16 starting parts make that rare.
const INITIAL_PARTS: u32 = 16;

/// Adaptive Gauss–Legendre of `|c'|` over `[a, b]`, inside the piece `[lo, hi]`, starting from
/// [`INITIAL_PARTS`] equal parts that share the accuracy.
fn integrate<C: ParamCurveDeriv>(
    curve: &C,
    a: f64,
    b: f64,
    lo: ScalarOf<C>,
    hi: ScalarOf<C>,
    accuracy: f64,
) -> Result<f64, Error> {
    let parts = f64::from(INITIAL_PARTS);
    let mut total = 0.0;
    let mut budget = MAX_SPLITS;
    for i in 0..INITIAL_PARTS {
        let x0 = a + (b - a) * (f64::from(i) / parts);
        let x1 = if i + 1 == INITIAL_PARTS {
            b
        } else {
            a + (b - a) * (f64::from(i + 1) / parts)
        };
        total += integrate_part(curve, (x0, x1), (lo, hi), accuracy / parts, &mut budget)?;
    }
    Ok(total)
}

/// Adaptive Gauss–Legendre of `|c'|` over `[a, b]`, inside the piece `[lo, hi]`, splitting
/// at most `budget` intervals (shared with the caller's other parts).
fn integrate_part<C: ParamCurveDeriv>(
    curve: &C,
    (a, b): (f64, f64),
    (lo, hi): (ScalarOf<C>, ScalarOf<C>),
    accuracy: f64,
    budget: &mut usize,
) -> Result<f64, Error> {
    if !greater(b, a) {
        return Ok(0.0);
    }
    let eps = ScalarOf::<C>::EPSILON;
    // The rounding noise of the sums reaches tens of ε on fast curves: two estimates that
    // agree to this floor are accepted whatever the accuracy asked for.
    let rel_floor = 128.0 * f64::EPSILON.max(eps);
    // Depth-first stack of (a, b, estimate on [a, b], accuracy share, depth).
    let mut stack = [(0.0, 0.0, 0.0, 0.0, 0_u32); MAX_DEPTH as usize + 2];
    let mut top = 1;
    if let Some(first) = stack.first_mut() {
        *first = (a, b, gauss(curve, a, b, lo, hi), accuracy, 0);
    }
    let mut total = 0.0;
    while top > 0 {
        top -= 1;
        let Some(&(a, b, whole, share, depth)) = stack.get(top) else {
            break;
        };
        let m = 0.5 * (a + b);
        let left = gauss(curve, a, m, lo, hi);
        let right = gauss(curve, m, b, lo, hi);
        let fine = left + right;
        if !fine.is_finite() || !whole.is_finite() {
            return Err(Error::NonFinite);
        }
        let tiny = (b - a) <= 4.0 * eps * a.abs().max(b.abs()).max(1.0);
        if (fine - whole).abs() <= share.max(rel_floor * fine.abs()) || tiny {
            total += fine;
            continue;
        }
        if depth >= MAX_DEPTH {
            return Err(Error::IterationLimit {
                limit: MAX_DEPTH as usize,
            });
        }
        *budget = budget
            .checked_sub(1)
            .ok_or(Error::IterationLimit { limit: MAX_SPLITS })?;
        let half = 0.5 * share;
        for item in [
            (m, b, right, half, depth + 1),
            (a, m, left, half, depth + 1),
        ] {
            match stack.get_mut(top) {
                Some(slot) => *slot = item,
                None => {
                    return Err(Error::IterationLimit {
                        limit: MAX_DEPTH as usize,
                    });
                }
            }
            top += 1;
        }
    }
    Ok(total)
}

/// The length of `curve` between the `f64` parameters `x0 ≤ x1` (inside the domain),
/// piece by piece, with the accuracy shared in proportion to parameter length.
fn length_between<C: ParamCurveDeriv>(
    curve: &C,
    x0: f64,
    x1: f64,
    accuracy: f64,
) -> Result<f64, Error> {
    let width = x1 - x0;
    if !greater(width, 0.0) {
        return Ok(0.0);
    }
    let (start, end) = curve.domain();
    let pieces = curve.piece_count();
    let mut total = 0.0;
    for i in 0..pieces {
        let (lo, hi) = piece_bounds(curve, i, pieces, start, end);
        let a = lo.to_f64().max(x0);
        let b = hi.to_f64().min(x1);
        if b > a {
            total += integrate(curve, a, b, lo, hi, accuracy * ((b - a) / width))?;
        }
    }
    Ok(total)
}

/// Piece `i` clamped to the domain (the last piece ends exactly at the domain end).
fn piece_bounds<C: ParamCurve>(
    curve: &C,
    i: usize,
    pieces: usize,
    start: ScalarOf<C>,
    end: ScalarOf<C>,
) -> (ScalarOf<C>, ScalarOf<C>) {
    let (a, b) = curve.piece_domain(i);
    let b = if i + 1 == pieces { end } else { b.min_of(end) };
    (a.max_of(start), b)
}

/// The arc length of the whole curve, `∫ |c'(u)| du` over the domain, within `accuracy`
/// (absolute, in the curve's length unit).
///
/// Computed and returned in `f64`.
///
/// # Quadrature
///
/// The integral is computed per piece (the speed `|c'|` is smooth inside a piece, but may jump
/// at piece boundaries) with the 8-point Gauss–Legendre rule, exact for polynomials of degree
/// 15 (Burden & Faires, *Numerical Analysis*, §4.7), and adaptive bisection (Burden & Faires
/// §4.6): an interval is accepted when the rule on the whole interval
/// and the sum over its two halves agree within the interval's share of the accuracy
/// (proportional to its parameter length); otherwise both halves are refined with half the
/// share each. The shares add up to the requested accuracy, and the accepted (finer) value is
/// far more accurate than the difference that is tested for smooth speeds, so the result is
/// within the accuracy — a standard error estimate, not a proof. Each piece starts from 16
/// equal parts, so that a feature between the nodes of one rule (a near-cusp) is not missed
/// by two estimates that agree on a wrong value; a zero of the speed (a cusp) within about
/// 2% of an interval's width from its end lies outside every node, and both estimates can
/// still agree on the smooth continuation of the speed there. Two estimates that agree to the
/// rounding noise of the sums, `128 · max(ε_f64, ε_S)` of the interval's length, are accepted
/// whatever the accuracy, since the derivative values and the sums themselves carry that
/// rounding.
///
/// # Work bound
///
/// The accuracy is checked against [`length_resolution`](crate::length_resolution) first
/// (`2·piece_count + 2` evaluations). Per piece the quadrature bisects at most 32 levels deep
/// and splits at most 2¹² intervals, so it evaluates the speed at most
/// `16·(16 + 2·(2·2¹² + 16))` times; a piece that needs more is
/// [`Error::IterationLimit`].
///
/// Everything is computed in `f64` from the curve's derivatives ([`Scalar::to_f64`]) and
/// lengths are returned as `f64`: the quadrature sums many terms, fixed-point scalars lack
/// the resolution for an accuracy like `1e-9`, and a length can exceed the range of a
/// fixed-point scalar even when every point fits. [`ArcLengthTable`] converts its samples to
/// the curve's scalar (checking the range) for use in firmware.
///
/// # Errors
/// [`Error::InvalidArgument`] when `accuracy` is not finite and positive;
/// [`Error::ToleranceBelowResolution`] when it is below
/// [`length_resolution`](crate::length_resolution); [`Error::IterationLimit`] when a piece
/// needs more than 32 bisection levels or 2¹² splits (pathological speeds, or derivatives
/// whose rounding noise exceeds the accuracy: fixed-point Lagrange curves, for example);
/// [`Error::NonFinite`] when a derivative is not finite.
///
/// ```
/// use strak_curves::{arc_length, ParamCurve, ParamCurveDeriv};
///
/// /// The unit circle (cos t, sin t) on [0, π].
/// struct Half;
/// impl ParamCurve for Half {
///     type Point = [f64; 2];
///     fn domain(&self) -> (f64, f64) { (0.0, core::f64::consts::PI) }
///     fn eval(&self, t: f64) -> [f64; 2] { self.deriv(t, 0) }
/// }
/// impl ParamCurveDeriv for Half {
///     fn deriv(&self, t: f64, k: usize) -> [f64; 2] {
///         let p = t + k as f64 * core::f64::consts::FRAC_PI_2;
///         [p.cos(), p.sin()]
///     }
/// }
/// let l = arc_length(&Half, 1e-12)?;
/// assert!((l - core::f64::consts::PI).abs() <= 1e-12);
/// # Ok::<(), strak_curves::Error>(())
/// ```
pub fn arc_length<C: ParamCurveDeriv>(curve: &C, accuracy: f64) -> Result<f64, Error> {
    check_length_accuracy(curve, accuracy)?;
    let (start, end) = curve.domain();
    length_between(curve, start.to_f64(), end.to_f64(), accuracy)
}

/// The arc length between the parameters `a` and `b` by one 8-point Gauss–Legendre rule
/// (exact where the speed `|c'|` is a polynomial of degree 15 or less), without error
/// control: for intervals on which [`arc_length_between`] or a comparison of the rule with
/// its two halves has shown it accurate enough. `a` and `b` are clamped to the domain, and
/// the curve is evaluated as one piece.
///
/// ```
/// use strak_curves::{Bezier, arc_length, gauss_length};
/// let quadratic = Bezier::new([[0.0, 0.0], [1.0, 2.0], [4.0, 0.0]])?; // its speed is not a polynomial
/// let exact = arc_length(&quadratic, 1e-12)?;
/// let halves = gauss_length(&quadratic, 0.0, 0.5) + gauss_length(&quadratic, 0.5, 1.0);
/// assert!((halves - exact).abs() < 1e-6 * exact);
/// assert!((halves - exact).abs() < (gauss_length(&quadratic, 0.0, 1.0) - exact).abs());
/// let line = Bezier::new([[0.0, 0.0], [3.0, 4.0]])?;
/// assert!((gauss_length(&line, 0.25, 0.75) - 2.5).abs() < 1e-15);
/// # Ok::<(), strak_curves::Error>(())
/// ```
pub fn gauss_length<C: ParamCurveDeriv>(curve: &C, a: f64, b: f64) -> f64 {
    let (lo, hi) = curve.domain();
    let clamp = |u: f64| u.clamp(lo.to_f64(), hi.to_f64());
    gauss(curve, clamp(a), clamp(b), lo, hi)
}

/// The arc length between the parameters `u0` and `u1` (both clamped to the domain) within
/// `accuracy`: `s(u1) − s(u0)`, negative when `u1 < u0`.
///
/// Errors and work bound as for [`arc_length`].
///
/// ```
/// use strak_curves::{arc_length_between, ParamCurve, ParamCurveDeriv};
///
/// /// The line (3u, 4u) on [0, 2]: speed 5.
/// struct Line;
/// impl ParamCurve for Line {
///     type Point = [f64; 2];
///     fn domain(&self) -> (f64, f64) { (0.0, 2.0) }
///     fn eval(&self, u: f64) -> [f64; 2] { self.deriv(u, 0) }
/// }
/// impl ParamCurveDeriv for Line {
///     fn deriv(&self, u: f64, k: usize) -> [f64; 2] {
///         match k { 0 => [3.0 * u, 4.0 * u], 1 => [3.0, 4.0], _ => [0.0, 0.0] }
///     }
/// }
/// let s = arc_length_between(&Line, 0.5, 1.5, 1e-12)?;
/// assert!((s - 5.0).abs() <= 1e-12);
/// let back = arc_length_between(&Line, 1.5, 9.0, 1e-12)?; // 9.0 is clamped to 2.0
/// assert!((back - 2.5).abs() <= 1e-12);
/// # Ok::<(), strak_curves::Error>(())
/// ```
pub fn arc_length_between<C: ParamCurveDeriv>(
    curve: &C,
    u0: ScalarOf<C>,
    u1: ScalarOf<C>,
    accuracy: f64,
) -> Result<f64, Error> {
    check_length_accuracy(curve, accuracy)?;
    let (start, end) = curve.domain();
    let x0 = u0.clamp_to(start, end).to_f64();
    let x1 = u1.clamp_to(start, end).to_f64();
    if x1 >= x0 {
        length_between(curve, x0, x1, accuracy)
    } else {
        Ok(-length_between(curve, x1, x0, accuracy)?)
    }
}

/// The parameter `u` at which the arc length from the domain start is `s`: the inverse of
/// `s(u)`, with `|s(u) − s| ≤ accuracy` (up to the parameter resolution of the scalar type).
///
/// `s` is clamped to `[0, L]`: `s ≤ 0` gives the domain start, `s ≥ L` the domain end, exactly.
/// The piece containing `s` is found by summing piece lengths (with half the accuracy);
/// inside it a safeguarded Newton method solves `s(u) = s` (`ds/du = |c'(u)|`), falling back
/// to bisection of the bracketing interval when a Newton step leaves the bracket or the speed
/// is zero (cusps) (Press et al., *Numerical Recipes*, 3rd ed., §9.4).
///
/// # Work bound
///
/// One arc-length integral per piece up to the piece containing `s` (each bounded as in
/// [`arc_length`]), then at most 128 Newton or bisection steps of one integral each.
///
/// # Errors
/// [`Error::NonFinite`] when `s` is NaN or a derivative is not finite;
/// [`Error::InvalidArgument`] when `accuracy` is not finite and positive;
/// [`Error::ToleranceBelowResolution`] when it is below
/// [`length_resolution`](crate::length_resolution); [`Error::IterationLimit`] when an
/// integral exceeds its bound or the steps do not converge within 128.
///
/// ```
/// use strak_curves::{param_at_length, ParamCurve, ParamCurveDeriv};
///
/// /// The parabola (t, t²/2) on [0, 2]: s(t) = (t·√(1+t²) + asinh t) / 2.
/// struct Parabola;
/// impl ParamCurve for Parabola {
///     type Point = [f64; 2];
///     fn domain(&self) -> (f64, f64) { (0.0, 2.0) }
///     fn eval(&self, t: f64) -> [f64; 2] { self.deriv(t, 0) }
/// }
/// impl ParamCurveDeriv for Parabola {
///     fn deriv(&self, t: f64, k: usize) -> [f64; 2] {
///         match k { 0 => [t, t * t / 2.0], 1 => [1.0, t], 2 => [0.0, 1.0], _ => [0.0, 0.0] }
///     }
/// }
/// let t: f64 = 1.25;
/// let s = (t * (1.0 + t * t).sqrt() + t.asinh()) / 2.0;
/// let u = param_at_length(&Parabola, s, 1e-12)?;
/// assert!((u - t).abs() <= 1e-11);
/// assert_eq!(param_at_length(&Parabola, 1e9, 1e-9)?, 2.0);
/// # Ok::<(), strak_curves::Error>(())
/// ```
pub fn param_at_length<C: ParamCurveDeriv>(
    curve: &C,
    s: f64,
    accuracy: f64,
) -> Result<ScalarOf<C>, Error> {
    check_length_accuracy(curve, accuracy)?;
    if s.is_nan() {
        return Err(Error::NonFinite);
    }
    let (start, end) = curve.domain();
    if !greater(s, 0.0) {
        return Ok(start);
    }
    let width = end.to_f64() - start.to_f64();
    if !greater(width, 0.0) {
        return Ok(start);
    }
    let pieces = curve.piece_count();
    let mut before = 0.0;
    for i in 0..pieces {
        let (lo, hi) = piece_bounds(curve, i, pieces, start, end);
        let (a, b) = (lo.to_f64(), hi.to_f64());
        if !greater(b, a) {
            continue;
        }
        let len = integrate(curve, a, b, lo, hi, 0.5 * accuracy * ((b - a) / width))?;
        if before + len >= s {
            return solve_in_piece(curve, lo, hi, s - before, len, 0.5 * accuracy);
        }
        before += len;
    }
    Ok(end)
}

/// Solves `∫_lo^u |c'| = r` for `u` in the piece `[lo, hi]` of length `len`, to within
/// `accuracy` in length.
fn solve_in_piece<C: ParamCurveDeriv>(
    curve: &C,
    lo: ScalarOf<C>,
    hi: ScalarOf<C>,
    r: f64,
    len: f64,
    accuracy: f64,
) -> Result<ScalarOf<C>, Error> {
    if !greater(r, 0.0) {
        return Ok(lo);
    }
    if r >= len {
        return Ok(hi);
    }
    let (a, b) = (lo.to_f64(), hi.to_f64());
    let resolution = 4.0 * f64::EPSILON.max(ScalarOf::<C>::EPSILON) * a.abs().max(b.abs()).max(1.0);
    let (mut x0, mut x1) = (a, b);
    let mut u = a + (b - a) * (r / len);
    let half = 0.5 * accuracy;
    for _ in 0..MAX_NEWTON {
        let f = integrate(curve, a, u, lo, hi, half)? - r;
        if f.abs() <= half {
            return Ok(param(u, lo, hi));
        }
        if f < 0.0 {
            x0 = u;
        } else {
            x1 = u;
        }
        if x1 - x0 <= resolution {
            return Ok(param(u, lo, hi));
        }
        // Newton inside the bracket, bisection otherwise (a safeguarded Newton method,
        // Numerical Recipes, 3rd ed., §9.4).
        let v = speed(curve, u, lo, hi);
        let newton = u - f / v;
        u = if v > 0.0 && newton > x0 && newton < x1 {
            newton
        } else {
            0.5 * (x0 + x1)
        };
    }
    Err(Error::IterationLimit { limit: MAX_NEWTON })
}

/// A table of arc length against parameter for a time law: `N` samples `(u_i, s_i)` with
/// `u(s)` and `s(u)` interpolated by C¹ piecewise cubic Hermite (never linearly: linear
/// interpolation of `u(s)` makes the speed `ds/dt · du/ds` jump at every sample, and the
/// acceleration and jerk of a time law built on it spike there).
///
/// # Samples
///
/// Every inner piece boundary (knot) of the curve ([`ParamCurve::piece_count`],
/// [`ParamCurve::piece_domain`]) is a sample, so that no table interval straddles a knot; the
/// `N − 1` intervals are shared among the pieces in proportion to their parameter length
/// (rounded, at least one interval per piece), and each piece is sampled uniformly in the
/// parameter. A single-piece curve is sampled uniformly over the domain. **Fallback:** when
/// the curve has more pieces than `N − 1` intervals, the samples are uniform in the
/// parameter over the whole domain and the limits below apply at the knots between samples.
///
/// # Interpolation
///
/// On interval `i`, with `t = (s − s_i)/Δs_i`, `u(s) = u_i + h₀₁(t)·Δu_i + h₁₀(t)·Δs_i·m_i +
/// h₁₁(t)·Δs_i·m_{i+1}` (cubic Hermite basis `h₀₁ = t²(3 − 2t)`, `h₁₀ = t(1 − t)²`,
/// `h₁₁ = −t²(1 − t)`), where the tangents `m_i = du/ds = 1/|c'(u_i)|` are exact derivatives;
/// at a knot they are one-sided: the end tangent of the interval left of the knot uses the
/// speed of the piece ending there, the start tangent of the interval right of it the speed
/// of the piece starting there. The left speed is evaluated with [`ParamCurveDeriv::deriv`]
/// two units of the scalar's resolution below the knot (an `O(ε·|c''|)` error; where `S` is
/// finer than the curve's own scalar, as for an `f64` table of an `f32` curve, that point may
/// round back onto the knot and the right speed is used). The tangents are
/// limited as by Fritsch & Carlson ("Monotone Piecewise Cubic Interpolation", *SIAM J. Numer.
/// Anal.* 17(2), 1980) to `m_i ≤ 3·min(Δu/Δs)` of the two adjacent intervals: this
/// keeps `u(s)` monotone and finite at zero speed (cusps), and leaves smooth curves with
/// sampled speed ratios below 3 untouched. `s(u)` is interpolated the same way with slopes
/// `ds/du = |c'(u_i)|`. The tangents are stored pre-multiplied by the interval width, which
/// bounds them by `3·Δu` (resp. `3·Δs`) and makes fixed-point evaluation overflow-free.
///
/// # Accuracy
///
/// The samples `s_i` are within `accuracy / 2` of the true arc length. Where `u(s)` is smooth,
/// cubic Hermite interpolation with exact slopes has the error `Δs⁴/384 · max|u⁗(s)|` per
/// interval (fourth order; linear interpolation is second order, `Δs²/8 · max|u''|`). The
/// constructor measures the interpolation error at every interval midpoint (where the Hermite
/// error kernel `t²(1 − t)²` peaks) in length units and reports the largest value plus the
/// accuracy as [`ArcLengthTable::error_estimate`].
///
/// # Known limits
///
/// With the knots among the samples, a kink or jump of the speed at a `C¹`, `G¹` or `C⁰`
/// join lies on a sample, where the interpolant is only C⁰ in its slope by construction (the
/// one-sided slopes), so the time law follows the curve's own jump there and each interval
/// keeps the fourth-order error of a smooth piece. In the fallback (more pieces than
/// intervals) a knot inside an interval is smoothed over: the error is first order there
/// (second order for a C¹ join) and the time law's acceleration jumps inside the interval;
/// use `N > piece_count()` for time laws.
///
/// Evaluation clamps its argument to the table, returns the domain ends exactly at the
/// table's ends, and has no panic path.
///
/// ```
/// use strak_curves::{ArcLengthTable, ParamCurve, ParamCurveDeriv};
///
/// /// The parabola (t, t²/2) on [0, 2].
/// struct Parabola;
/// impl ParamCurve for Parabola {
///     type Point = [f64; 2];
///     fn domain(&self) -> (f64, f64) { (0.0, 2.0) }
///     fn eval(&self, t: f64) -> [f64; 2] { self.deriv(t, 0) }
/// }
/// impl ParamCurveDeriv for Parabola {
///     fn deriv(&self, t: f64, k: usize) -> [f64; 2] {
///         match k { 0 => [t, t * t / 2.0], 1 => [1.0, t], 2 => [0.0, 1.0], _ => [0.0, 0.0] }
///     }
/// }
/// let table = ArcLengthTable::<f64, 16>::new(&Parabola, 1e-10)?;
/// let exact = (2.0 * 5.0_f64.sqrt() + 2.0_f64.asinh()) / 2.0;
/// assert!((table.length() - exact).abs() <= 1e-10);
/// assert!(table.error_estimate() < 1e-5);
/// let u = table.param_at(table.length_at(1.25));
/// assert!((u - 1.25).abs() < 1e-5);
/// assert_eq!(table.param_at(table.length()), 2.0); // exact end
/// # Ok::<(), strak_curves::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct ArcLengthTable<S: Scalar, const N: usize> {
    /// Sample parameters, strictly increasing, `u[0]` and `u[N − 1]` the domain ends.
    u: [S; N],
    /// Arc length at the samples, strictly increasing, `s[0] = 0`.
    s: [S; N],
    /// Interval `i`: Hermite tangents of `u(s)` at its start and end, times `Δs_i`.
    u_tan: [[S; 2]; N],
    /// Interval `i`: Hermite tangents of `s(u)` at its start and end, times `Δu_i`.
    s_tan: [[S; 2]; N],
    /// Largest measured midpoint error plus the accuracy, in length units.
    error: f64,
}

/// Element `i` of `a`, or the default value (never reached for valid indices).
#[inline]
fn at<T: Copy + Default>(a: &[T], i: usize) -> T {
    a.get(i).copied().unwrap_or_default()
}

/// Cubic Hermite on one interval: `y0 + h01·(y1 − y0) + h10·m0 + h11·m1`, with the tangents
/// `m0`, `m1` already scaled by the interval width, clamped to `[y0, y1]`.
#[inline]
fn hermite<S: Scalar>(y0: S, y1: S, m: [S; 2], t: S) -> S {
    let omt = S::ONE - t;
    let t2 = t * t;
    let h01 = t2 * (S::from_i16(3) - S::TWO * t);
    let h10 = t * omt * omt;
    let h11 = t2 * omt;
    (y0 + h01 * (y1 - y0) + h10 * m[0] - h11 * m[1]).clamp_to(y0, y1)
}

/// The interval `i ∈ [0, N − 2]` with `xs[i] ≤ x < xs[i + 1]` (clamped at the ends).
#[inline]
fn interval<S: Scalar>(xs: &[S], x: S) -> usize {
    xs.partition_point(|v| *v <= x)
        .saturating_sub(1)
        .min(xs.len().saturating_sub(2))
}

/// The table's sample parameters and which of them are inner piece boundaries.
///
/// Every inner piece boundary (of positive-width pieces inside the domain) is a sample; the
/// `N − 1` intervals are shared among the pieces in proportion to their parameter length
/// (largest-remainder rounding of the cumulative share), at least one interval per piece, and
/// each piece is sampled uniformly in the parameter. When the curve has more pieces than
/// `N − 1`, the samples fall back to uniform in the parameter over the whole domain (no
/// sample is flagged as a piece boundary).
fn nodes<C, const N: usize>(curve: &C, u: &mut [ScalarOf<C>; N]) -> [bool; N]
where
    C: ParamCurve,
{
    let (start, end) = curve.domain();
    let (a, b) = (start.to_f64(), end.to_f64());
    let width = b - a;
    let last = N.saturating_sub(1);
    #[allow(clippy::cast_precision_loss)]
    let last_f = last as f64;
    u.fill(start);
    let mut knot = [false; N];
    let pieces = curve.piece_count();
    let bounds = |i: usize| piece_bounds(curve, i, pieces, start, end);
    let count = (0..pieces)
        .filter(|&i| {
            let (lo, hi) = bounds(i);
            greater(hi, lo)
        })
        .count();
    if count < 2 || count > last || !greater(width, 0.0) {
        for (i, ui) in u.iter_mut().enumerate() {
            #[allow(clippy::cast_precision_loss)]
            let t = i as f64 / last_f;
            *ui = if i + 1 == N {
                end
            } else {
                param(a + width * t, start, end)
            };
        }
        if let Some(first) = u.first_mut() {
            *first = start;
        }
        return knot;
    }
    let (mut j0, mut k) = (0_usize, 0_usize);
    for i in 0..pieces {
        let (lo, hi) = bounds(i);
        if !greater(hi, lo) {
            continue;
        }
        k += 1;
        let j1 = if k == count {
            last
        } else {
            let share = last_f * ((hi.to_f64() - a) / width) + 0.5;
            #[allow(
                clippy::cast_possible_truncation,
                clippy::cast_sign_loss,
                reason = "a finite value in [0.5, N − 0.5]; `as` saturates anyway"
            )]
            let ideal = share as usize;
            ideal.max(j0 + 1).min(last - (count - k))
        };
        #[allow(clippy::cast_precision_loss)]
        let m = (j1 - j0) as f64;
        let (x0, x1) = (lo.to_f64(), hi.to_f64());
        for j in j0..j1 {
            #[allow(clippy::cast_precision_loss)]
            let t = (j - j0) as f64 / m;
            if let Some(slot) = u.get_mut(j) {
                *slot = if j == j0 {
                    lo
                } else {
                    param(x0 + (x1 - x0) * t, lo, hi)
                };
            }
        }
        if j0 > 0
            && let Some(flag) = knot.get_mut(j0)
        {
            *flag = true;
        }
        j0 = j1;
    }
    if let Some(first) = u.first_mut() {
        *first = start;
    }
    if let Some(final_) = u.last_mut() {
        *final_ = end;
    }
    knot
}

/// A parameter just below the piece boundary `x` (about two units of the scalar's
/// resolution, not below `floor`), where [`ParamCurveDeriv::deriv`] uses the piece ending
/// at `x`: its speed is the left-sided speed at `x` up to `O(ε·|c''|)`. `x` itself when the
/// scalar cannot represent a smaller value above `floor`.
fn below<S: Scalar>(x: S, floor: S) -> S {
    let xf = x.to_f64();
    let step = 2.0 * S::EPSILON * xf.abs().max(1.0);
    let v = param(xf - step, floor, x);
    if v < x { v } else { x }
}

impl<S: Scalar, const N: usize> ArcLengthTable<S, N> {
    /// Builds the table for `curve` with `N` samples on the curve's knots and uniform in the
    /// parameter inside each piece (uniform over the domain when the curve has more than
    /// `N − 1` pieces), the arc lengths computed within `accuracy / 2` (see the
    /// [type documentation](Self)).
    ///
    /// # Work bound
    ///
    /// `2(N − 1)` arc-length integrals (each bounded as in [`arc_length`]) and `3N` speed
    /// evaluations, after the resolution check.
    ///
    /// # Errors
    /// - [`Error::InvalidArgument`]: `N < 2`, or `accuracy` not finite and positive.
    /// - [`Error::ToleranceBelowResolution`]: `accuracy` is below
    ///   [`length_resolution`](crate::length_resolution).
    /// - [`Error::IterationLimit`]: an integral exceeds the bound of [`arc_length`].
    /// - [`Error::ZeroLengthInterval`]: two samples have the same parameter or the same arc
    ///   length in `S` (a curve standing still over a whole interval, or a domain too short
    ///   for the scalar's resolution); `index` is the interval.
    /// - [`Error::OutOfRange`]: the length does not fit the scalar type.
    /// - [`Error::NonFinite`]: a derivative of the curve is not finite.
    ///
    /// ```
    /// use strak_curves::{ArcLengthTable, Error, ParamCurve, ParamCurveDeriv};
    ///
    /// /// The line (3u, 4u) on [0, 1].
    /// struct Line;
    /// impl ParamCurve for Line {
    ///     type Point = [f32; 2];
    ///     fn domain(&self) -> (f32, f32) { (0.0, 1.0) }
    ///     fn eval(&self, u: f32) -> [f32; 2] { self.deriv(u, 0) }
    /// }
    /// impl ParamCurveDeriv for Line {
    ///     fn deriv(&self, u: f32, k: usize) -> [f32; 2] {
    ///         match k { 0 => [3.0 * u, 4.0 * u], 1 => [3.0, 4.0], _ => [0.0, 0.0] }
    ///     }
    /// }
    /// let table = ArcLengthTable::<f32, 8>::new(&Line, 1e-6)?;
    /// assert_eq!(table.length(), 5.0);
    /// assert!((table.param_at(2.5) - 0.5).abs() < 1e-6);
    /// assert_eq!(ArcLengthTable::<f32, 1>::new(&Line, 1e-6), Err(Error::InvalidArgument));
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn new<C>(curve: &C, accuracy: f64) -> Result<Self, Error>
    where
        C: ParamCurveDeriv,
        C::Point: Point<Scalar = S>,
    {
        let mut table = Self::EMPTY;
        table.rebuild(curve, accuracy)?;
        Ok(table)
    }

    /// A table of length zero (every sample at 0; lookups return 0): storage that
    /// [`rebuild`](Self::rebuild) fills in place, for example in a `static` or inside a
    /// larger value.
    ///
    /// ```
    /// use strak_curves::ArcLengthTable;
    /// static TABLE: ArcLengthTable<f32, 64> = ArcLengthTable::EMPTY;
    /// assert_eq!((TABLE.length(), TABLE.param_at(1.0)), (0.0, 0.0));
    /// ```
    pub const EMPTY: Self = ArcLengthTable {
        u: [S::ZERO; N],
        s: [S::ZERO; N],
        u_tan: [[S::ZERO; 2]; N],
        s_tan: [[S::ZERO; 2]; N],
        error: 0.0,
    };

    /// [`new`](Self::new), in place: the samples are written where the table lies, so that
    /// building it needs no stack frame the size of the table. On an error the table is
    /// left [`EMPTY`](Self::EMPTY).
    ///
    /// # Errors
    /// As [`new`](Self::new).
    ///
    /// ```
    /// use strak_curves::{ArcLengthTable, Bezier};
    /// let mut table = ArcLengthTable::<f64, 16>::EMPTY;
    /// table.rebuild(&Bezier::new([[0.0, 0.0], [3.0, 4.0]])?, 1e-9)?;
    /// assert!((table.length() - 5.0).abs() < 1e-9);
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn rebuild<C>(&mut self, curve: &C, accuracy: f64) -> Result<(), Error>
    where
        C: ParamCurveDeriv,
        C::Point: Point<Scalar = S>,
    {
        let result = self.build(curve, accuracy);
        if result.is_err() {
            *self = Self::EMPTY;
        }
        result
    }

    /// The body of [`rebuild`](Self::rebuild).
    fn build<C>(&mut self, curve: &C, accuracy: f64) -> Result<(), Error>
    where
        C: ParamCurveDeriv,
        C::Point: Point<Scalar = S>,
    {
        if N < 2 {
            return Err(Error::InvalidArgument);
        }
        check_length_accuracy(curve, accuracy)?;
        #[allow(clippy::cast_precision_loss)]
        let last = (N - 1) as f64;
        let knot = nodes::<C, N>(curve, &mut self.u);
        let u = &self.u;
        for i in 1..N {
            if !greater(at(&self.u, i), at(&self.u, i - 1)) {
                return Err(Error::ZeroLengthInterval { index: i - 1 });
            }
        }

        // Arc lengths, accumulated in f64, each interval within accuracy / (2 (N − 1)).
        let share = 0.5 * accuracy / last;
        let s = &mut self.s;
        s.fill(S::ZERO);
        let mut acc = 0.0;
        for i in 1..N {
            acc += length_between(curve, at(u, i - 1).to_f64(), at(u, i).to_f64(), share)?;
            let si = S::from_f64(acc).ok_or(Error::OutOfRange)?;
            if !greater(si, at(&s[..], i - 1)) {
                return Err(Error::ZeroLengthInterval { index: i - 1 });
            }
            if let Some(slot) = s.get_mut(i) {
                *slot = si;
            }
        }

        // Hermite slopes at the samples, limited to three times the adjacent secants: at a
        // piece boundary one-sided (the left slope from the left piece limited by the left
        // interval, the right slope from the right piece by the right interval), elsewhere
        // one slope limited by both intervals.
        let s = &self.s;
        let du = |i: usize| at(u, i + 1).to_f64() - at(u, i).to_f64();
        let ds = |i: usize| at(s, i + 1).to_f64() - at(s, i).to_f64();
        let (u_tan, s_tan) = (&mut self.u_tan, &mut self.s_tan);
        u_tan.fill([S::ZERO; 2]);
        s_tan.fill([S::ZERO; 2]);
        // (du/ds, ds/du) from the left and from the right of sample i.
        let slopes = |i: usize| -> Result<[(f64, f64); 2], Error> {
            let ui = at(u, i);
            let right = norm64(&curve.deriv(ui, 1));
            let is_knot = at(&knot, i);
            let left = if is_knot {
                norm64(&curve.deriv(below(ui, at(u, i.saturating_sub(1))), 1))
            } else {
                right
            };
            if !(left.is_finite() && right.is_finite()) {
                return Err(Error::NonFinite);
            }
            let mut out = [(1.0 / left, left), (1.0 / right, right)];
            // The intervals i − 1 (left side) and i (right side), where they exist; away
            // from a piece boundary both sides are limited by both intervals.
            for (side, slot) in out.iter_mut().enumerate() {
                let mut lo = i.saturating_sub(1);
                let mut hi = (i + 1).min(N - 1);
                if is_knot {
                    if side == 0 {
                        hi = i;
                    } else {
                        lo = i;
                    }
                }
                for j in lo..hi {
                    slot.0 = slot.0.min(3.0 * du(j) / ds(j));
                    slot.1 = slot.1.min(3.0 * ds(j) / du(j));
                }
            }
            Ok(out)
        };
        let mut here = slopes(0)?;
        for i in 0..N - 1 {
            let next = slopes(i + 1)?;
            let scaled = |x: f64| S::from_f64(x).ok_or(Error::OutOfRange);
            let (start_side, end_side) = (here[1], next[0]);
            if let Some(slot) = u_tan.get_mut(i) {
                *slot = [scaled(start_side.0 * ds(i))?, scaled(end_side.0 * ds(i))?];
            }
            if let Some(slot) = s_tan.get_mut(i) {
                *slot = [scaled(start_side.1 * du(i))?, scaled(end_side.1 * du(i))?];
            }
            here = next;
        }

        self.error = 0.0;
        let table = &*self;
        // Measure the interpolation error at the interval midpoints.
        let mut worst = 0.0_f64;
        for i in 0..N - 1 {
            let (u0, u1) = (at(&table.u, i), at(&table.u, i + 1));
            let um = param(0.5 * (u0.to_f64() + u1.to_f64()), u0, u1);
            let sm =
                at(&table.s, i).to_f64() + length_between(curve, u0.to_f64(), um.to_f64(), share)?;
            let v = norm64(&curve.deriv(um, 1));
            let sm_s = S::from_f64(sm).ok_or(Error::OutOfRange)?;
            let err_u = (table.param_at(sm_s).to_f64() - um.to_f64()).abs() * v;
            let err_s = (table.length_at(um).to_f64() - sm).abs();
            worst = worst.max(err_u).max(err_s);
        }
        if !worst.is_finite() {
            return Err(Error::NonFinite);
        }
        self.error = worst + accuracy;
        Ok(())
    }

    /// The total arc length `L` (the last sample).
    #[inline]
    pub fn length(&self) -> S {
        at(&self.s, N.saturating_sub(1))
    }

    /// The parameter domain covered by the table, `(u_start, u_end)`.
    #[inline]
    pub fn domain(&self) -> (S, S) {
        (at(&self.u, 0), at(&self.u, N.saturating_sub(1)))
    }

    /// Sample `i` as `(u_i, s_i)`, `None` for `i ≥ N`.
    #[inline]
    pub fn sample(&self, i: usize) -> Option<(S, S)> {
        Some((*self.u.get(i)?, *self.s.get(i)?))
    }

    /// The estimated largest interpolation error in length units: the largest error measured
    /// at the interval midpoints when the table was built (for `u(s)` as `|c'|·|Δu|`, for
    /// `s(u)` directly), plus the arc-length accuracy. An estimate, not a bound: the midpoint
    /// is where the Hermite error kernel `t²(1 − t)²` peaks. On smooth pieces the true maximum
    /// is within 1.5 times this value; knots are samples, so this holds next to them too,
    /// except in the fallback with more pieces than intervals, where near a knot at which
    /// the curve is only C¹ (or C⁰) the tests find up to about 5 times, so budget 8 times
    /// the estimate there.
    #[inline]
    pub fn error_estimate(&self) -> f64 {
        self.error
    }

    /// The arc length `s(u)` from the domain start, by cubic Hermite interpolation; `u` is
    /// clamped to the domain.
    pub fn length_at(&self, u: S) -> S {
        let (start, end) = self.domain();
        if u <= start {
            return S::ZERO;
        }
        if u >= end {
            return self.length();
        }
        let i = interval(&self.u, u);
        let (u0, u1) = (at(&self.u, i), at(&self.u, i + 1));
        // u1 > u0 was checked at construction, and u0 ≤ u < u1.
        let t = ((u - u0) / (u1 - u0)).clamp_to(S::ZERO, S::ONE);
        hermite(at(&self.s, i), at(&self.s, i + 1), at(&self.s_tan, i), t)
    }

    /// The parameter `u(s)` at arc length `s`, by C¹ cubic Hermite interpolation; `s` is
    /// clamped to `[0, L]`, and `0` and `L` give the domain ends exactly. Binary search for
    /// the interval (`O(log N)`); see [`param_at_from`](Self::param_at_from) for monotone
    /// playback.
    pub fn param_at(&self, s: S) -> S {
        self.param_in(s, interval(&self.s, s))
    }

    /// [`param_at`](Self::param_at) starting the interval search at `*cursor` and storing the
    /// interval found there: constant time per call when `s` changes monotonically by less
    /// than one interval per call (playback at a fixed rate).
    ///
    /// ```
    /// use strak_curves::{ArcLengthTable, ParamCurve, ParamCurveDeriv};
    /// # struct Line;
    /// # impl ParamCurve for Line {
    /// #     type Point = [f64; 2];
    /// #     fn domain(&self) -> (f64, f64) { (0.0, 1.0) }
    /// #     fn eval(&self, u: f64) -> [f64; 2] { self.deriv(u, 0) }
    /// # }
    /// # impl ParamCurveDeriv for Line {
    /// #     fn deriv(&self, u: f64, k: usize) -> [f64; 2] {
    /// #         match k { 0 => [3.0 * u, 4.0 * u], 1 => [3.0, 4.0], _ => [0.0, 0.0] }
    /// #     }
    /// # }
    /// // `Line` is (3u, 4u) on [0, 1], of length 5.
    /// let table = ArcLengthTable::<f64, 8>::new(&Line, 1e-9)?;
    /// let mut cursor = 0;
    /// for k in 0..=50 {
    ///     let s = 0.1 * f64::from(k);
    ///     assert_eq!(table.param_at_from(s, &mut cursor), table.param_at(s));
    /// }
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn param_at_from(&self, s: S, cursor: &mut usize) -> S {
        let last = N.saturating_sub(2);
        let mut i = (*cursor).min(last);
        while i < last && s >= at(&self.s, i + 1) {
            i += 1;
        }
        while i > 0 && s < at(&self.s, i) {
            i -= 1;
        }
        *cursor = i;
        self.param_in(s, i)
    }

    /// `u(s)` on interval `i`.
    fn param_in(&self, s: S, i: usize) -> S {
        if s <= S::ZERO {
            return at(&self.u, 0);
        }
        if s >= self.length() {
            return at(&self.u, N.saturating_sub(1));
        }
        let (s0, s1) = (at(&self.s, i), at(&self.s, i + 1));
        // s1 > s0 was checked at construction, and s0 ≤ s < s1.
        let t = ((s - s0) / (s1 - s0)).clamp_to(S::ZERO, S::ONE);
        hermite(at(&self.u, i), at(&self.u, i + 1), at(&self.u_tan, i), t)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use std::vec::Vec;

    use super::*;
    use crate::analysis::length_resolution;
    use crate::analysis::testcurves::{FnCurve, PolyCurve, arc};
    use crate::scalar::{I16F16, I32F32};
    use core::f64::consts::PI;

    /// (t, t²) on [a, b].
    fn parabola(a: f64, b: f64) -> PolyCurve<f64> {
        PolyCurve::single(a, b, &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])
    }

    /// The closed-form arc length of (t, t²) from 0 to t: (t√(1+4t²))/2 + asinh(2t)/4.
    fn parabola_s(t: f64) -> f64 {
        t * libm::sqrt(1.0 + 4.0 * t * t) / 2.0 + libm::asinh(2.0 * t) / 4.0
    }

    #[test]
    fn gauss_legendre_rule() {
        let w: f64 = GL_W.iter().sum();
        assert!((2.0 * w - 2.0).abs() < 1e-15);
        // Exact for x^14: ∫_{-1}^{1} x^14 = 2/15.
        let m: f64 = GL_X
            .iter()
            .zip(GL_W.iter())
            .map(|(x, w)| 2.0 * w * x.powi(14))
            .sum();
        assert!((m - 2.0 / 15.0).abs() < 1e-15);
    }

    #[test]
    fn circle_arc_length() {
        for (r, fraction) in [(1.0, 1.0), (2.0, 0.3), (0.5, 0.77), (10.0, 0.05)] {
            let c = arc(r, 0.4, 0.4 + 2.0 * PI * fraction);
            let l = arc_length(&c, 1e-12).unwrap();
            assert!(
                (l - 2.0 * PI * r * fraction).abs() <= 1e-12,
                "{r} {fraction}: {l}"
            );
        }
    }

    #[test]
    fn straight_line_is_exact() {
        // (1 + 3u, 2 − 4u) on [0, 2]: speed 5, length 10.
        let line = PolyCurve::<f64>::single(0.0, 2.0, &[[1.0, 2.0], [3.0, -4.0]]);
        let l = arc_length(&line, 1e-12).unwrap();
        assert!((l - 10.0).abs() <= 4.0 * f64::EPSILON * 10.0, "{l}");
        assert!((arc_length_between(&line, 0.5, 1.0, 1e-12).unwrap() - 2.5).abs() < 1e-14);
        assert!((param_at_length(&line, 5.0, 1e-12).unwrap() - 1.0).abs() <= 1e-12 / 5.0);
    }

    #[test]
    fn parabola_against_closed_form() {
        let c = parabola(-0.5, 2.0);
        let exact = parabola_s(2.0) + parabola_s(0.5);
        assert!((arc_length(&c, 1e-12).unwrap() - exact).abs() <= 1e-12);
        let part = arc_length_between(&c, 0.25, 1.5, 1e-12).unwrap();
        assert!((part - (parabola_s(1.5) - parabola_s(0.25))).abs() <= 1e-12);
        let back = arc_length_between(&c, 1.5, 0.25, 1e-12).unwrap();
        assert_eq!(back, -part);
        // Accuracies are honoured loosely too (not more accurate than asked is fine).
        assert!((arc_length(&c, 1e-3).unwrap() - exact).abs() <= 1e-3);
    }

    #[test]
    fn cusp_with_a_kink_in_the_speed() {
        // The cusp (t³, t²): |c'| = |t|·√(9t² + 4) has a kink at t = 0 (not a dyadic point
        // of [−1, 2]). ∫₀ᵃ t√(9t²+4) dt = ((9a²+4)^{3/2} − 8)/27.
        let c =
            PolyCurve::<f64>::single(-1.0, 2.0, &[[0.0, 0.0], [0.0, 0.0], [0.0, 1.0], [1.0, 0.0]]);
        let part = |a: f64| (libm::pow(9.0 * a * a + 4.0, 1.5) - 8.0) / 27.0;
        let exact = part(1.0) + part(2.0);
        assert!((arc_length(&c, 1e-10).unwrap() - exact).abs() <= 1e-10);
        // The inverse passes the cusp (zero speed) by bisection.
        let u = param_at_length(&c, part(1.0), 1e-10).unwrap();
        assert!(u.abs() < 1e-4, "{u}"); // s(u) − s(0) ≈ u² near the cusp
        let u = param_at_length(&c, part(1.0) + part(0.5), 1e-10).unwrap();
        assert!((u - 0.5).abs() < 1e-9, "{u}");
    }

    #[test]
    fn piecewise_lengths_add_up() {
        // Three cubic pieces, C⁰ only: the sum over pieces equals the per-piece integrals.
        let c = PolyCurve::<f64>::new(
            &[0.0, 1.0, 3.0, 3.5],
            &[
                &[[0.0, 0.0], [1.0, 2.0], [0.5, -3.0], [-0.2, 1.0]],
                &[[1.3, 0.0], [1.5, 0.2], [1.0, 0.5], [0.3, -2.0]],
                &[[0.0, 0.0], [4.0, 0.0]],
            ],
        );
        let total = arc_length(&c, 1e-12).unwrap();
        let parts: f64 = [(0.0, 1.0), (1.0, 3.0), (3.0, 3.5)]
            .iter()
            .map(|&(a, b)| arc_length_between(&c, a, b, 1e-13).unwrap())
            .sum();
        assert!((total - parts).abs() <= 2e-12);
        assert!((arc_length_between(&c, 3.0, 3.5, 1e-12).unwrap() - 2.0).abs() < 1e-13);
    }

    #[test]
    fn inverse_round_trip() {
        let c = PolyCurve::<f64>::new(
            &[0.0, 1.0, 2.5],
            &[
                &[[0.0, 0.0], [1.0, 2.0], [0.5, -3.0], [-0.2, 1.0]],
                &[[1.3, 0.0], [1.5, 0.2], [1.0, 0.5], [0.3, -2.0]],
            ],
        );
        for k in 0..=25 {
            let u = 0.1 * f64::from(k);
            let s = arc_length_between(&c, 0.0, u, 1e-12).unwrap();
            let back = param_at_length(&c, s, 1e-10).unwrap();
            let speed = norm64(&c.deriv(u, 1));
            assert!((back - u).abs() * speed <= 2e-10, "{u}: {back}");
        }
        let a = arc(3.0, -1.0, 2.0);
        for k in 0..=9 {
            let s = f64::from(k);
            let u = param_at_length(&a, s, 1e-12).unwrap();
            assert!(
                (u - (-1.0 + s / 3.0)).abs() <= 1e-12 / 3.0 + 1e-15,
                "{s}: {u}"
            );
        }
        // Clamping of s.
        assert_eq!(param_at_length(&a, -1.0, 1e-9).unwrap(), -1.0);
        assert_eq!(param_at_length(&a, 100.0, 1e-9).unwrap(), 2.0);
        assert_eq!(param_at_length(&a, f64::INFINITY, 1e-9).unwrap(), 2.0);
    }

    #[test]
    fn errors() {
        let c = parabola(0.0, 1.0);
        for acc in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert_eq!(arc_length(&c, acc), Err(Error::InvalidArgument));
            assert_eq!(
                arc_length_between(&c, 0.0, 1.0, acc),
                Err(Error::InvalidArgument)
            );
            assert_eq!(param_at_length(&c, 0.5, acc), Err(Error::InvalidArgument));
            assert_eq!(
                ArcLengthTable::<f64, 4>::new(&c, acc),
                Err(Error::InvalidArgument)
            );
        }
        assert_eq!(param_at_length(&c, f64::NAN, 1e-9), Err(Error::NonFinite));
        let bad = FnCurve {
            f: |t: f64, k: usize| if k == 1 { [f64::NAN, 0.0] } else { [t, 0.0] },
            a: 0.0,
            b: 1.0,
        };
        assert_eq!(arc_length(&bad, 1e-9), Err(Error::NonFinite));
        assert_eq!(param_at_length(&bad, 0.5, 1e-9), Err(Error::NonFinite));
        assert_eq!(
            ArcLengthTable::<f64, 4>::new(&bad, 1e-9),
            Err(Error::NonFinite)
        );
    }

    #[test]
    fn unresolvable_speed_stops_at_the_split_budget() {
        // (t, sin(ωt)/ω) with ω = 10⁷ on [0, 1]: the speed √(1 + cos²(ωt)) oscillates 1.6·10⁶
        // times; no rule resolves it within 2¹² splits. The error comes after at most
        // 16 + 2·(2·2¹² + 16) Gauss rules of 16 speed evaluations, counted here (no timing),
        // plus the 3 points of the resolution check.
        let calls = core::cell::Cell::new(0_usize);
        let w = 1.0e7;
        let c = FnCurve {
            f: |t: f64, k: usize| {
                calls.set(calls.get() + 1);
                match k {
                    0 => [t, libm::sin(w * t) / w],
                    1 => [1.0, libm::cos(w * t)],
                    _ => [0.0, -w * libm::sin(w * t)],
                }
            },
            a: 0.0,
            b: 1.0,
        };
        assert_eq!(
            arc_length(&c, 1e-9),
            Err(Error::IterationLimit { limit: MAX_SPLITS })
        );
        let bound = 16 * (16 + 2 * (2 * MAX_SPLITS + 16)) + 3;
        assert!(calls.get() <= bound, "{} > {bound}", calls.get());
    }

    #[test]
    fn fixed_point_and_f32_lengths() {
        let c = PolyCurve::<I32F32>::single(0.0, 2.0, &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
        let l = arc_length(&c, 1e-8).unwrap();
        assert!((l - parabola_s(2.0)).abs() <= 1e-8);
        let u = param_at_length(&c, parabola_s(1.25), 1e-8).unwrap();
        assert!((u.to_f64() - 1.25).abs() <= 1e-8);
        let c = PolyCurve::<f32>::single(0.0, 2.0, &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
        // An accuracy below f32's resolution at the curve's length is rejected at once; one
        // just above it converges.
        assert_eq!(
            arc_length(&c, 1e-15),
            Err(Error::ToleranceBelowResolution { scalar: "f32" })
        );
        let l = arc_length(&c, 2.0 * length_resolution(&c)).unwrap();
        assert!((l - parabola_s(2.0)).abs() <= 1e-5);
    }

    /// The exact inverse of the closed-form parabola length, by bisection.
    fn parabola_u(s: f64) -> f64 {
        let (mut lo, mut hi) = (0.0, 10.0);
        for _ in 0..200 {
            let m = 0.5 * (lo + hi);
            if parabola_s(m) < s { lo = m } else { hi = m }
        }
        0.5 * (lo + hi)
    }

    #[test]
    fn table_hermite_beats_linear_and_meets_its_estimate() {
        let c = parabola(0.0, 2.0);
        let table = ArcLengthTable::<f64, 16>::new(&c, 1e-12).unwrap();
        let l = parabola_s(2.0);
        assert!((table.length() - l).abs() <= 1e-12);
        let (mut herm, mut lin) = (0.0_f64, 0.0_f64);
        let samples: Vec<f64> = (0..=3000).map(|k| l * f64::from(k) / 3000.0).collect();
        for &s in &samples {
            let exact = parabola_u(s);
            let speed = libm::sqrt(1.0 + 4.0 * exact * exact);
            herm = herm.max((table.param_at(s) - exact).abs() * speed);
            // Linear interpolation on the same samples.
            let i = interval(&table.s, s);
            let (s0, s1) = (table.s[i], table.s[i + 1]);
            let (u0, u1) = (table.u[i], table.u[i + 1]);
            let linear = u0 + (u1 - u0) * (s - s0) / (s1 - s0);
            lin = lin.max((linear - exact).abs() * speed);
        }
        // Stated bound: the error estimate (midpoint errors) holds within a factor 1.5, and
        // is below 2e-5 for 16 samples; linear interpolation is ~100× worse.
        assert!(
            herm <= 1.5 * table.error_estimate(),
            "{herm} vs {}",
            table.error_estimate()
        );
        assert!(table.error_estimate() < 2e-5, "{}", table.error_estimate());
        assert!(herm * 50.0 < lin, "hermite {herm}, linear {lin}");
        // s(u) too.
        let mut s_err = 0.0_f64;
        for k in 0..=1000 {
            let u = 2.0 * f64::from(k) / 1000.0;
            s_err = s_err.max((table.length_at(u) - parabola_s(u)).abs());
        }
        assert!(s_err <= 1.5 * table.error_estimate(), "{s_err}");
        // Fourth order: doubling the samples cuts the error by about 16.
        let fine = ArcLengthTable::<f64, 31>::new(&c, 1e-12).unwrap();
        assert!(fine.error_estimate() * 8.0 < table.error_estimate());
    }

    #[test]
    fn table_ends_are_exact_and_monotone() {
        let c = parabola(-1.0, 1.5);
        let table = ArcLengthTable::<f64, 12>::new(&c, 1e-10).unwrap();
        assert_eq!(table.domain(), (-1.0, 1.5));
        assert_eq!(table.param_at(0.0), -1.0);
        assert_eq!(table.param_at(-5.0), -1.0);
        assert_eq!(table.param_at(table.length()), 1.5);
        assert_eq!(table.param_at(1e9), 1.5);
        assert_eq!(table.length_at(-1.0), 0.0);
        assert_eq!(table.length_at(1.5), table.length());
        assert_eq!(table.sample(0), Some((-1.0, 0.0)));
        assert_eq!(table.sample(12), None);
        let mut prev = -1.0;
        let mut cursor = 5;
        for k in 0..=2000 {
            let s = table.length() * f64::from(k) / 2000.0;
            let u = table.param_at(s);
            assert!(u >= prev);
            assert_eq!(table.param_at_from(s, &mut cursor), u);
            prev = u;
        }
    }

    #[test]
    fn table_through_a_cusp_stays_monotone() {
        // (t³, t²) on [−1, 1.3]: zero speed at t = 0 → du/ds infinite; the slope limit keeps
        // the interpolant finite and monotone.
        let c =
            PolyCurve::<f64>::single(-1.0, 1.3, &[[0.0, 0.0], [0.0, 0.0], [0.0, 1.0], [1.0, 0.0]]);
        let table = ArcLengthTable::<f64, 24>::new(&c, 1e-10).unwrap();
        let mut prev = -1.0;
        for k in 0..=5000 {
            let s = table.length() * f64::from(k) / 5000.0;
            let u = table.param_at(s);
            assert!(u.is_finite() && u >= prev, "{s}: {u}");
            prev = u;
        }
        assert!(table.error_estimate() < 1e-2);
    }

    #[test]
    fn table_in_f32_and_fixed_point() {
        let c = PolyCurve::<f32>::single(0.0, 2.0, &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
        let t = ArcLengthTable::<f32, 16>::new(&c, 1e-6).unwrap();
        assert!((t.param_at(t.length_at(1.25)) - 1.25).abs() < 1e-4);
        let c = PolyCurve::<I16F16>::single(0.0, 2.0, &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
        let t = ArcLengthTable::<I16F16, 16>::new(&c, 1e-4).unwrap();
        let s = I16F16::from_num(parabola_s(1.25));
        assert!((t.param_at(s).to_f64() - 1.25).abs() < 1e-3);
        assert!(t.error_estimate() < 1e-3);
        assert_eq!(t.param_at(t.length()).to_f64(), 2.0);
    }

    #[test]
    fn table_errors() {
        let c = parabola(0.0, 1.0);
        assert_eq!(
            ArcLengthTable::<f64, 1>::new(&c, 1e-9),
            Err(Error::InvalidArgument)
        );
        assert_eq!(
            ArcLengthTable::<f64, 0>::new(&c, 1e-9),
            Err(Error::InvalidArgument)
        );
        // A curve standing still: all arc lengths zero.
        let still = PolyCurve::<f64>::single(0.0, 1.0, &[[1.0, 1.0]]);
        assert_eq!(
            ArcLengthTable::<f64, 4>::new(&still, 1e-9),
            Err(Error::ZeroLengthInterval { index: 0 })
        );
        // A domain of 3 fixed-point steps cannot hold 8 distinct samples.
        let short = PolyCurve::<I16F16>::single(0.0, 3.0 / 65536.0, &[[0.0, 0.0], [1.0, 0.0]]);
        assert!(matches!(
            ArcLengthTable::<I16F16, 8>::new(&short, 1e-3),
            Err(Error::ZeroLengthInterval { .. })
        ));
        // Back and forth over 8000 units three times: length 24000 > I16F16 limit 16383.
        let long = PolyCurve::<I16F16>::new(
            &[0.0, 1.0, 2.0, 3.0],
            &[
                &[[0.0, 0.0], [8000.0, 0.0]],
                &[[8000.0, 0.0], [-8000.0, 0.0]],
                &[[0.0, 0.0], [8000.0, 0.0]],
            ],
        );
        assert_eq!(
            ArcLengthTable::<I16F16, 8>::new(&long, 1e-3),
            Err(Error::OutOfRange)
        );
    }

    /// (u, 0) on [0, 1], then (1 + x + x²/2, 0) with x = u − 1 on [1, 2.2]: C¹ at the knot
    /// u = 1 (c' = (1, 0) on both sides) with a kink in the speed (slope 0, then 1).
    fn c1_kink() -> PolyCurve<f64> {
        PolyCurve::new(
            &[0.0, 1.0, 2.2],
            &[
                &[[0.0, 0.0], [1.0, 0.0]],
                &[[1.0, 0.0], [1.0, 0.0], [0.5, 0.0]],
            ],
        )
    }

    /// The exact inverse of [`c1_kink`]: `u = s` up to 1, then `1 + √(2s − 1) − 1`.
    fn c1_kink_u(s: f64) -> f64 {
        if s <= 1.0 {
            s
        } else {
            libm::sqrt(2.0 * s - 1.0)
        }
    }

    #[test]
    fn table_nodes_include_the_knots() {
        // 7 intervals over widths 1 and 1.2: round(7/2.2) = 3 on the first piece.
        let table = ArcLengthTable::<f64, 8>::new(&c1_kink(), 1e-12).unwrap();
        assert_eq!(table.sample(3).unwrap().0, 1.0);
        assert!((table.sample(3).unwrap().1 - 1.0).abs() < 1e-12);
        assert_eq!(table.sample(0), Some((0.0, 0.0)));
        assert_eq!(table.sample(7).unwrap().0, 2.2);
        // Uniform inside each piece.
        assert!((table.sample(1).unwrap().0 - 1.0 / 3.0).abs() < 1e-15);
        assert!((table.sample(5).unwrap().0 - 1.6).abs() < 1e-15);
        // Three pieces of widths 0.1, 5, 0.1 and 8 samples: every piece gets an interval.
        let c = PolyCurve::<f64>::new(
            &[0.0, 0.1, 5.1, 5.2],
            &[
                &[[0.0, 0.0], [1.0, 0.0]],
                &[[0.1, 0.0], [1.0, 0.0]],
                &[[5.1, 0.0], [1.0, 0.0]],
            ],
        );
        let table = ArcLengthTable::<f64, 8>::new(&c, 1e-12).unwrap();
        let u: Vec<f64> = (0..8).map(|i| table.sample(i).unwrap().0).collect();
        assert_eq!(u[0], 0.0);
        assert_eq!(u[1], 0.1);
        assert_eq!(u[6], 5.1);
        assert_eq!(u[7], 5.2);
        assert!((u[2] - 1.1).abs() < 1e-12, "{u:?}");
        // In fixed point the knot is a sample too.
        let c = PolyCurve::<I16F16>::new(
            &[0.0, 1.0, 2.25],
            &[
                &[[0.0, 0.0], [1.0, 0.0]],
                &[[1.0, 0.0], [1.0, 0.0], [0.5, 0.0]],
            ],
        );
        let table = ArcLengthTable::<I16F16, 10>::new(&c, 1e-4).unwrap();
        assert!((0..10).any(|i| table.sample(i).unwrap().0 == I16F16::ONE));
    }

    #[test]
    fn table_inverse_is_accurate_at_a_c1_knot() {
        let table = ArcLengthTable::<f64, 8>::new(&c1_kink(), 1e-12).unwrap();
        let len = table.length();
        assert!((len - c1_kink_u_inv(2.2)).abs() < 1e-12);
        let mut worst = 0.0_f64;
        for k in 0..=4000 {
            let s = len * f64::from(k) / 4000.0;
            worst = worst.max((table.param_at(s) - c1_kink_u(s)).abs());
        }
        // The first piece is linear (exact); the second is a smooth inverse with exact
        // one-sided slopes at the knot.
        assert!(worst < 5e-4, "{worst}");
        for s in [0.999_999, 1.0, 1.000_001] {
            assert!((table.param_at(s) - c1_kink_u(s)).abs() < 1e-9, "{s}");
        }
        // The time law's acceleration: the second difference of u(s) just left of the knot
        // is that of the linear piece (zero), not smoothed across the knot.
        let h = 1e-4;
        let d2 =
            table.param_at(1.0 - 2.0 * h) - 2.0 * table.param_at(1.0 - h) + table.param_at(1.0);
        assert!(d2.abs() < 1e-12, "{d2}");
        assert!(table.error_estimate() < 1e-3);
    }

    /// Arc length of [`c1_kink`] from 0 to `u`.
    fn c1_kink_u_inv(u: f64) -> f64 {
        if u <= 1.0 {
            u
        } else {
            let x = u - 1.0;
            1.0 + x + 0.5 * x * x
        }
    }

    #[test]
    fn table_uses_one_sided_speeds_at_a_speed_jump() {
        // (u, 0) on [0, 1], then (1 + 2x, 0): the speed jumps from 1 to 2 at the knot (C⁰).
        // With a sample on the knot and one-sided slopes both pieces are reproduced exactly.
        let c = PolyCurve::<f64>::new(
            &[0.0, 1.0, 2.0],
            &[&[[0.0, 0.0], [1.0, 0.0]], &[[1.0, 0.0], [2.0, 0.0]]],
        );
        let table = ArcLengthTable::<f64, 7>::new(&c, 1e-12).unwrap();
        assert!((table.length() - 3.0).abs() < 1e-12);
        for k in 0..=300 {
            let s = 3.0 * f64::from(k) / 300.0;
            let u = if s <= 1.0 { s } else { 1.0 + 0.5 * (s - 1.0) };
            assert!((table.param_at(s) - u).abs() < 1e-12, "{s}");
            assert!((table.length_at(u) - s).abs() < 1e-12, "{u}");
        }
        assert!(table.error_estimate() < 1e-10);
    }

    #[test]
    fn table_with_more_pieces_than_intervals_samples_uniformly() {
        // 5 pieces, 4 intervals: documented fallback to uniform samples over the domain.
        let c = PolyCurve::<f64>::new(
            &[0.0, 0.5, 1.0, 1.5, 2.0, 3.0],
            &[
                &[[0.0, 0.0], [1.0, 0.0]],
                &[[0.5, 0.0], [1.0, 0.0]],
                &[[1.0, 0.0], [1.0, 0.0]],
                &[[1.5, 0.0], [1.0, 0.0]],
                &[[2.0, 0.0], [1.0, 0.0]],
            ],
        );
        let table = ArcLengthTable::<f64, 5>::new(&c, 1e-12).unwrap();
        for i in 0..5 {
            assert!((table.sample(i).unwrap().0 - 0.75 * i as f64).abs() < 1e-15);
        }
        assert!((table.param_at(1.2) - 1.2).abs() < 1e-12);
    }

    #[test]
    fn below_a_knot() {
        assert!(below(2.0_f64, 1.0) < 2.0);
        assert!(below(3.0_f64, 1.0) < 3.0);
        assert!(below(3.0_f64, 1.0) > 2.0);
        assert!(3.0 - below(3.0_f64, 1.0) < 1e-14);
        assert_eq!(below(1.0_f32, 0.0), 1.0 - 2.0 * f32::EPSILON);
        let one = I16F16::ONE;
        assert_eq!(below(one, I16F16::ZERO), one - I16F16::from_bits(2));
        // Never below the floor, and the floor equal to x gives x.
        assert_eq!(below(1.0_f64, 1.0), 1.0);
        assert_eq!(below(1.0_f64, 1.0 - 1e-17), 1.0 - 1e-17);
    }
}
