//! Flattening: a polyline that approximates a curve within a distance tolerance.
//!
//! The method, its guarantee and its work bound are documented at [`flatten`].

use crate::curve::{ParamCurveDeriv, ScalarOf};
use crate::error::Error;
use crate::point::Point;
use crate::scalar::Scalar;

use super::{c64, check_resolvable, greater, norm64, param, resolution, spacing};

/// The highest derivative used in the bound on `|c''|` (exact for degree ≤ 8).
const MAX_ORDER: usize = 8;

/// The largest number of segments of the whole curve (all pieces together); more means the
/// tolerance is far below the curve's size (a polyline of 2¹⁶ segments resolves a circle to
/// 10⁻⁹ of its radius).
const MAX_SEGMENTS: usize = 1 << 16;

/// Bisection for the segment count stops when the bracket is below `1/2^BISECT_SHIFT` of
/// its upper end (exact below `2^(BISECT_SHIFT + 1)` segments).
const BISECT_SHIFT: u32 = 6;

/// The most uniform segments of one interval; an interval that needs more is halved.
const RUN: usize = 64;

/// The most intervals (uniform runs and halved ones) of the whole curve: room for
/// [`MAX_SEGMENTS`] in runs of 16 on average, and a work bound of about 2.5·10⁷ evaluations.
const MAX_INTERVALS: usize = 1 << 12;

/// The most pending intervals of one piece: an interval is halved at most `MAX_DEPTH − 1`
/// times (to `2⁻⁷⁹` of its piece; near 0 an `f64` parameter could be halved ~1 000 times).
const MAX_DEPTH: usize = 80;

/// Flattens `curve` into a polyline whose distance to the curve is at most `tolerance`,
/// written to `out`; returns the number of vertices.
///
/// The first vertex is `curve.eval(u_start)`, the last `curve.eval(u_end)`, and every piece
/// boundary is a vertex.
///
/// # Method and guarantee
///
/// Every piece of the curve is flattened on its own; piece boundaries are always vertices.
/// An interval `[a, b]` of a piece (at first the whole piece) is cut into `n` segments
/// uniform in the parameter; when it needs more than 64, it is halved in the parameter and
/// each half is flattened the same way, left to right, so that the spacing follows what
/// the curve needs where it needs it (a rational piece near a pole of its weight function,
/// a tight turn) instead of the worst spot setting the spacing of the whole piece. On a
/// segment
/// `[s, s + h]` the deviation of the curve from its chord is the error of linear
/// interpolation (de Boor, *A Practical Guide to Splines*, ch. III "Broken line
/// interpolation"; Burden & Faires, *Numerical Analysis*, §3.1, the interpolation error
/// theorem with `n = 1`)
///
/// ```text
/// c(u) − chord(u) = −(u − s)(s + h − u)/2 · (weighted mean of c'' over the segment)
/// ```
///
/// (the Peano kernel of linear interpolation is non-negative), so its size is at most
/// `h²/8 · max|c''|`. Splitting `c''` into its parts along the chord direction `e` and normal
/// to it sharpens this: when `h² · max|c''·e| ≤ 2·|chord|` the curve cannot run past the
/// chord's ends, and the distance to the chord segment is at most `h²/8 · max|c'' − (c''·e)e|`
/// (the normal part); otherwise the full `h²/8 · max|c''|` is used. The maxima over the segment
/// are bounded by the Taylor expansion of `c''` at `s` (for each of the three measures):
///
/// ```text
/// |c''(s + t)| ≤ max(|c''(s)|, |c''(s) + c'''(s)·h|) + Σ_{k=4..8} |c^(k)(s)| h^(k−2)/(k−2)!
/// ```
///
/// (the norm of the linear part is convex in `t`, so its maximum is at an end). For every
/// piece that is a polynomial of degree ≤ 8 — Bézier, Lagrange, Hermite, cubic-spline and
/// B-spline pieces — this expansion is exact, so **the polyline is within `tolerance` of the
/// curve** (in both directions, since every vertex lies on the curve), up to the rounding of
/// the derivative values and of the vertex positions to the point type. For degree ≤ 3 the
/// Taylor part is the exact maximum. For rational pieces (NURBS) or higher degree the series
/// is cut after `c^(8)` and its last term is added once more as an estimate of the remainder:
/// then the result is an estimate, accurate when segments are short compared with the
/// distance to the nearest (complex) pole of the piece.
///
/// `n` is found by growing a count from an estimate (by at least a quarter per step) until
/// the certificate holds, then bisecting towards the smallest passing count, exactly (below
/// 128 segments); an interval whose estimate or search exceeds 64 is halved instead. The
/// tests find the vertex count within 10% of the smallest uniform count that meets the
/// tolerance, or below it where halving adapts the spacing.
///
/// Parameters are computed in `f64` and rounded to the curve's scalar; with fixed-point
/// scalars the vertices lie at the rounded parameters, and the certificate is computed for the
/// segments between those rounded parameters.
///
/// # Work bound
///
/// The tolerance is checked against [`resolution`](crate::resolution) before anything else
/// (`2·piece_count + 2` evaluations). Each interval takes two derivatives for its estimate
/// and, when it is not halved at once, growing and bisecting take at most `12·64` chord
/// certificates (each 7 derivatives and one point); an interval is halved only while its
/// halves have distinct parameter values in the scalar, and at most 79 times (to `2⁻⁷⁹` of
/// its piece; an interval that short that still needs more than 64 segments is an
/// error, as the halving stops there). At most 2¹² intervals are taken
/// in all (the halved ones included), and the counts of all pieces together never exceed
/// 2¹⁶ segments: a curve that would need more is an error, found within that work whatever
/// the curve: at most `2¹²·(2 + 12·64·8)` (about 2.5·10⁷) evaluations in all, and one per
/// vertex written.
///
/// # Errors
/// - [`Error::InvalidArgument`]: `tolerance` is not finite and positive.
/// - [`Error::ToleranceBelowResolution`]: `tolerance` is below
///   [`resolution`](crate::resolution) (the spacing of the point type's values at the
///   curve's size), or a piece would need segments shorter than the spacing of its
///   parameter values.
/// - [`Error::CapacityExceeded`]: `out` is too short; `required` is the number of vertices
///   needed (then `out` holds the first `out.len()` of them). Also when the pieces together
///   would need more than 2¹⁶ segments (a tolerance far below the curve's size); then
///   `capacity` is 2¹⁶ and `required` a lower estimate.
/// - [`Error::IterationLimit`]: more than 2¹² intervals (`limit` 2¹²), or an interval
///   halved 79 times that still needs more than 64 segments (`limit` 80): a tolerance far
///   below the curve's size, found before the segment count.
/// - [`Error::NonFinite`]: a derivative of the curve is not finite.
///
/// ```
/// use strak_curves::{flatten, ParamCurve, ParamCurveDeriv};
///
/// /// The parabola (t, t²) on [-1, 1].
/// struct Parabola;
/// impl ParamCurve for Parabola {
///     type Point = [f64; 2];
///     fn domain(&self) -> (f64, f64) { (-1.0, 1.0) }
///     fn eval(&self, t: f64) -> [f64; 2] { self.deriv(t, 0) }
/// }
/// impl ParamCurveDeriv for Parabola {
///     fn deriv(&self, t: f64, k: usize) -> [f64; 2] {
///         let t = t.clamp(-1.0, 1.0);
///         match k { 0 => [t, t * t], 1 => [1.0, 2.0 * t], 2 => [0.0, 2.0], _ => [0.0, 0.0] }
///     }
/// }
///
/// let mut out = [[0.0; 2]; 64];
/// // h²/8 · |c''| ≤ 0.0125 with |c''| = 2 needs h ≤ √0.05 ≈ 0.224: 9 segments on [-1, 1].
/// let n = flatten(&Parabola, 0.0125, &mut out)?;
/// assert_eq!(n, 10);
/// assert_eq!((out[0], out[n - 1]), ([-1.0, 1.0], [1.0, 1.0]));
/// # Ok::<(), strak_curves::Error>(())
/// ```
pub fn flatten<C: ParamCurveDeriv>(
    curve: &C,
    tolerance: f64,
    out: &mut [C::Point],
) -> Result<usize, Error> {
    let capacity = out.len();
    let count = run(curve, tolerance, Some(out))?;
    if count > capacity {
        return Err(Error::CapacityExceeded {
            capacity,
            required: count,
        });
    }
    Ok(count)
}

/// The number of vertices [`flatten`] produces for `curve` and `tolerance`, without storing
/// them (to size the output storage).
///
/// Errors and work bound as for [`flatten`], except that there is no capacity limit on the
/// output.
///
/// ```
/// use strak_curves::{flatten_count, ParamCurve, ParamCurveDeriv};
///
/// /// A straight line: two vertices whatever the tolerance.
/// struct Line;
/// impl ParamCurve for Line {
///     type Point = [f64; 2];
///     fn domain(&self) -> (f64, f64) { (0.0, 1.0) }
///     fn eval(&self, t: f64) -> [f64; 2] { self.deriv(t, 0) }
/// }
/// impl ParamCurveDeriv for Line {
///     fn deriv(&self, t: f64, k: usize) -> [f64; 2] {
///         match k { 0 => [3.0 * t, 4.0 * t], 1 => [3.0, 4.0], _ => [0.0, 0.0] }
///     }
/// }
/// assert_eq!(flatten_count(&Line, 1e-9)?, 2);
/// # Ok::<(), strak_curves::Error>(())
/// ```
pub fn flatten_count<C: ParamCurveDeriv>(curve: &C, tolerance: f64) -> Result<usize, Error> {
    run(curve, tolerance, None)
}

/// Flattens, storing vertices into `out` while they fit; returns the vertex count.
fn run<C: ParamCurveDeriv>(
    curve: &C,
    tolerance: f64,
    mut out: Option<&mut [C::Point]>,
) -> Result<usize, Error> {
    check_resolvable::<ScalarOf<C>>(tolerance, resolution(curve))?;
    let (start, end) = curve.domain();
    let mut count = 0;
    // Segments of the pieces done so far: the pieces share one budget of MAX_SEGMENTS.
    let mut segments_so_far = 0;
    let mut put = |count: &mut usize, u: ScalarOf<C>| {
        if let Some(slot) = out.as_deref_mut().and_then(|o| o.get_mut(*count)) {
            *slot = curve.eval(u);
        }
        *count += 1;
    };
    put(&mut count, start);
    let pieces = curve.piece_count();
    let mut visited = 0;
    for i in 0..pieces {
        let (a, b) = curve.piece_domain(i);
        let a = a.max_of(start);
        // The last piece ends exactly at the domain end.
        let b = if i + 1 == pieces { end } else { b.min_of(end) };
        if !greater(b, a) {
            continue;
        }
        let mut intervals = Intervals {
            visited,
            ends: [b; MAX_DEPTH],
            depth: 1,
        };
        let mut left = a;
        while let Some(right) = intervals.next()? {
            let budget = MAX_SEGMENTS - segments_so_far;
            if budget == 0 {
                return Err(Error::CapacityExceeded {
                    capacity: MAX_SEGMENTS,
                    required: MAX_SEGMENTS + 1,
                });
            }
            let middle = param(0.5 * (left.to_f64() + right.to_f64()), left, right);
            let halve = greater(middle, left) && greater(right, middle);
            match segments(curve, left, right, tolerance, budget, halve)? {
                Some(n) => {
                    segments_so_far += n;
                    for j in 1..=n {
                        put(&mut count, node(left, right, j, n));
                    }
                    left = right;
                }
                None if intervals.has_room() => intervals.halve(middle),
                None => {
                    return Err(Error::IterationLimit { limit: MAX_DEPTH });
                }
            }
        }
        visited = intervals.visited;
    }
    Ok(count)
}

/// Parameter `j` of `n` uniform segments on `[a, b]`, rounded to the scalar (exact at the
/// ends).
fn node<S: Scalar>(a: S, b: S, j: usize, n: usize) -> S {
    if j == 0 {
        a
    } else if j >= n {
        b
    } else {
        let (af, bf) = (a.to_f64(), b.to_f64());
        #[allow(clippy::cast_precision_loss)]
        let t = j as f64 / n as f64;
        param(af + (bf - af) * t, a, b)
    }
}

/// The largest segment count worth trying on `[a, b]`: the `budget` left of
/// [`MAX_SEGMENTS`], or fewer when the scalar has fewer distinct parameter values in the
/// piece; and the error for a piece that needs more.
fn segment_cap<S: Scalar>(a: S, b: S, budget: usize, needed: impl Fn() -> usize) -> (usize, Error) {
    let (af, bf) = (a.to_f64(), b.to_f64());
    let steps = (bf - af) / spacing::<S>(af.abs().max(bf.abs()));
    #[allow(clippy::cast_precision_loss)]
    let limited = steps < budget as f64;
    if limited {
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let cap = (steps as usize).max(1);
        (cap, Error::ToleranceBelowResolution { scalar: S::NAME })
    } else {
        let required = (MAX_SEGMENTS - budget).saturating_add(needed());
        let e = Error::CapacityExceeded {
            capacity: MAX_SEGMENTS,
            required,
        };
        (budget, e)
    }
}

/// The intervals of one piece still to flatten, left to right: the right ends of a
/// depth-first halving (the left end of the next is the right end of the last one done).
struct Intervals<S> {
    /// Intervals taken from all pieces so far.
    visited: usize,
    /// The right ends, innermost last.
    ends: [S; MAX_DEPTH],
    depth: usize,
}

impl<S: Copy> Intervals<S> {
    /// The right end of the next interval, `None` when the piece is done.
    ///
    /// # Errors
    /// [`Error::IterationLimit`] beyond [`MAX_INTERVALS`] intervals.
    fn next(&mut self) -> Result<Option<S>, Error> {
        let Some(top) = self.depth.checked_sub(1) else {
            return Ok(None);
        };
        self.visited += 1;
        if self.visited > MAX_INTERVALS {
            return Err(Error::IterationLimit {
                limit: MAX_INTERVALS,
            });
        }
        self.depth = top;
        Ok(self.ends.get(top).copied())
    }

    /// Whether one more halving fits.
    fn has_room(&self) -> bool {
        self.depth + 2 <= MAX_DEPTH
    }

    /// Replaces the interval just taken (ending at `right`) by its halves at `middle`.
    fn halve(&mut self, middle: S) {
        // The right half stays (its end is still stored above `depth`); the left half is next.
        if let Some(slot) = self.ends.get_mut(self.depth + 1) {
            *slot = middle;
            self.depth += 2;
        }
    }
}

/// A number of uniform segments on the interval `[a, b]` that passes the chord-error
/// certificate, within `1/2^BISECT_SHIFT` of the smallest, within the work bound of
/// [`flatten`]; `None` when the interval needs more than [`RUN`] and may be halved
/// (`halve`).
fn segments<C: ParamCurveDeriv>(
    curve: &C,
    a: ScalarOf<C>,
    b: ScalarOf<C>,
    tolerance: f64,
    budget: usize,
    halve: bool,
) -> Result<Option<usize>, Error> {
    let len = b.to_f64() - a.to_f64();
    // First guess from the linear part of c'' over the whole interval (the exact maximum of
    // |c''| for cubic pieces).
    let m0 = linear_part_bound(curve, a, len);
    let estimate = segment_count_for(len, m0, tolerance)?;
    if halve && estimate > RUN {
        return Ok(None);
    }
    let (cap, too_many) = segment_cap(a, b, budget, || estimate.max(budget + 1));
    let cap = if halve { cap.min(RUN) } else { cap };
    let mut n = estimate.min(cap);
    // Grow until the certificate holds; `lo` is the largest count known to fail. Each step
    // grows by at least a quarter, so these passes add up to at most 5 times the last count.
    let mut lo = 0;
    let hi = loop {
        // At the cap only pass or fail matters: stop at the first failing segment.
        let stop = (n >= cap).then_some(tolerance);
        let e = worst_chord_error(curve, a, b, n, stop)?;
        if e <= tolerance {
            break n;
        }
        if n >= cap {
            return if halve { Ok(None) } else { Err(too_many) };
        }
        lo = n;
        // The chord errors shrink as 1/n²: `n·√(e/tol)` is the count they ask for; more
        // than a run is a halving now rather than after growing passes.
        let ratio = libm::sqrt(e / tolerance);
        #[allow(clippy::cast_precision_loss)]
        if halve && n as f64 * ratio > RUN as f64 {
            return Ok(None);
        }
        #[allow(clippy::cast_precision_loss)]
        let grow = libm::ceil(n as f64 * ratio.clamp(1.25, 4.0));
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let next = grow.min(usize::MAX as f64) as usize;
        n = next.clamp(n + 1, cap);
    };
    // Bisect in (lo, hi] down to a bracket of hi/2^BISECT_SHIFT: at most BISECT_SHIFT + 1
    // passes, failing passes stop at their first failing segment.
    let (mut lo, mut hi) = (lo, hi);
    while hi - lo > (hi >> BISECT_SHIFT).max(1) {
        let mid = lo + (hi - lo) / 2;
        if worst_chord_error(curve, a, b, mid, Some(tolerance))? <= tolerance {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Ok(Some(hi))
}

/// `n = ⌈len · √(m / (8 tol))⌉`, at least 1: uniform segments with `h²/8 · m ≤ tol`
/// (saturating).
fn segment_count_for(len: f64, m: f64, tolerance: f64) -> Result<usize, Error> {
    let n = libm::ceil(len * libm::sqrt(m / (8.0 * tolerance)));
    if !n.is_finite() {
        return Err(Error::NonFinite);
    }
    #[allow(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        clippy::cast_precision_loss
    )]
    Ok((n.min(usize::MAX as f64) as usize).max(1))
}

/// `max(|c''(u)|, |c''(u) + c'''(u)·h|)`: the maximum of the linear part of `c''` on
/// `[u, u + h]`.
fn linear_part_bound<C: ParamCurveDeriv>(curve: &C, u: ScalarOf<C>, h: f64) -> f64 {
    let d2 = curve.deriv(u, 2);
    let d3 = curve.deriv(u, 3);
    let (mut n0, mut n1) = (0.0, 0.0);
    for i in 0..C::Point::DIM {
        let x = c64(&d2, i);
        let y = x + c64(&d3, i) * h;
        n0 += x * x;
        n1 += y * y;
    }
    libm::sqrt(n0).max(libm::sqrt(n1))
}

/// `[|x|, |x·e|, |x − (x·e)e|]` for the vector with coordinates `x(i)` and a unit (or zero)
/// vector `e`.
fn measures(dim: usize, x: impl Fn(usize) -> f64, e: impl Fn(usize) -> f64) -> [f64; 3] {
    let (mut xx, mut xe) = (0.0, 0.0);
    for i in 0..dim {
        xx += x(i) * x(i);
        xe += x(i) * e(i);
    }
    let mut pp = 0.0;
    for i in 0..dim {
        let q = x(i) - xe * e(i);
        pp += q * q;
    }
    [libm::sqrt(xx), xe.abs(), libm::sqrt(pp)]
}

/// The certified distance between the curve on `[u0, u0 + h]` and the chord from
/// `p0 = c(u0)` to `p1 = c(u0 + h)` (see [`flatten`]).
fn chord_error<C: ParamCurveDeriv>(
    curve: &C,
    u0: ScalarOf<C>,
    h: f64,
    p0: &C::Point,
    p1: &C::Point,
) -> f64 {
    let dim = C::Point::DIM;
    let len = norm64(&p1.minus(*p0));
    let e = |i: usize| {
        if len > 0.0 {
            (c64(p1, i) - c64(p0, i)) / len
        } else {
            0.0
        }
    };
    // d[j] = c^(j+2)(u0).
    let d: [C::Point; MAX_ORDER - 1] = core::array::from_fn(|j| curve.deriv(u0, j + 2));
    let (d2, d3) = (&d[0], &d[1]);
    let lin0 = measures(dim, |i| c64(d2, i), e);
    let lin1 = measures(dim, |i| c64(d2, i) + c64(d3, i) * h, e);
    // bound[m] for the measures m = full norm, tangential, normal.
    let mut bound: [f64; 3] = core::array::from_fn(|m| lin0[m].max(lin1[m]));
    // f = h^(k−2) / (k−2)! for k = j + 2 = 4, 5, …
    let mut f = h;
    let mut last = [0.0; 3];
    for (j, dk) in d.iter().enumerate().skip(2) {
        #[allow(clippy::cast_precision_loss)]
        let div = j as f64;
        f *= h / div;
        let m = measures(dim, |i| c64(dk, i), e);
        for (b, (l, mk)) in bound.iter_mut().zip(last.iter_mut().zip(m)) {
            *l = mk * f;
            *b += *l;
        }
    }
    // Remainder estimate for non-polynomial pieces (zero for degree < 8).
    let [full, tangential, normal]: [f64; 3] = core::array::from_fn(|m| bound[m] + last[m]);
    // Without overshoot past the chord's ends only the normal part of c'' counts.
    let max_c2 = if h * h * tangential <= 2.0 * len {
        normal
    } else {
        full
    };
    h * h / 8.0 * max_c2
}

/// The largest certified chord error over the `n` uniform segments of `[a, b]`; with
/// `stop = Some(t)` the first error above `t` is returned as soon as it is found.
fn worst_chord_error<C: ParamCurveDeriv>(
    curve: &C,
    a: ScalarOf<C>,
    b: ScalarOf<C>,
    n: usize,
    stop: Option<f64>,
) -> Result<f64, Error> {
    let mut worst = 0.0_f64;
    let mut u0 = a;
    let mut p0 = curve.eval(a);
    for j in 1..=n {
        let u1 = node(a, b, j, n);
        let p1 = curve.eval(u1);
        let h = u1.to_f64() - u0.to_f64();
        if h > 0.0 {
            let e = chord_error(curve, u0, h, &p0, &p1);
            if !e.is_finite() {
                return Err(Error::NonFinite);
            }
            worst = worst.max(e);
            if stop.is_some_and(|t| e > t) {
                return Ok(worst);
            }
        }
        u0 = u1;
        p0 = p1;
    }
    Ok(worst)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use std::vec;
    use std::vec::Vec;

    use super::*;
    use crate::analysis::testcurves::{FnCurve, PolyCurve, arc};
    use crate::analysis::{Counted, resolution};
    use crate::curve::ParamCurve;
    use crate::scalar::{I16F16, I32F32};

    fn to64<P: Point>(p: &P) -> [f64; 2] {
        [c64(p, 0), c64(p, 1)]
    }

    fn dist_to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let l2 = dx * dx + dy * dy;
        let t = if l2 > 0.0 {
            (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let (qx, qy) = (a[0] + t * dx - p[0], a[1] + t * dy - p[1]);
        libm::sqrt(qx * qx + qy * qy)
    }

    /// The largest distance from a dense sampling of the curve to the polyline.
    fn max_deviation<C: ParamCurveDeriv>(curve: &C, poly: &[C::Point]) -> f64 {
        let poly: Vec<[f64; 2]> = poly.iter().map(to64).collect();
        let (a, b) = curve.domain();
        let (a, b) = (a.to_f64(), b.to_f64());
        let samples = 4000;
        let mut worst = 0.0_f64;
        for i in 0..=samples {
            let u = a + (b - a) * i as f64 / samples as f64;
            let p = to64(&curve.eval(param(u, curve.domain().0, curve.domain().1)));
            let d = poly
                .windows(2)
                .map(|w| dist_to_segment(p, w[0], w[1]))
                .fold(f64::INFINITY, f64::min);
            worst = worst.max(d);
        }
        worst
    }

    fn flatten_vec<C: ParamCurveDeriv>(curve: &C, tol: f64) -> Vec<C::Point> {
        let n = flatten_count(curve, tol).unwrap();
        let mut out = vec![curve.eval(curve.domain().0); n];
        assert_eq!(flatten(curve, tol, &mut out).unwrap(), n);
        out
    }

    /// The smallest uniform segment count on a one-piece curve that meets the tolerance
    /// (checked by dense sampling).
    fn min_uniform_segments<C: ParamCurveDeriv>(curve: &C, tol: f64) -> usize {
        let (a, b) = curve.domain();
        (1..10_000)
            .find(|&n| {
                let poly: Vec<C::Point> = (0..=n).map(|j| curve.eval(node(a, b, j, n))).collect();
                max_deviation(curve, &poly) <= tol
            })
            .unwrap()
    }

    fn parabola() -> PolyCurve<f64> {
        PolyCurve::single(-1.0, 1.0, &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])
    }

    fn three_cubics() -> PolyCurve<f64> {
        PolyCurve::new(
            &[0.0, 1.0, 1.5, 3.0],
            &[
                &[[0.0, 0.0], [1.0, 2.0], [0.5, -3.0], [-0.2, 1.0]],
                &[[1.3, 0.0], [1.5, 0.2], [1.0, 0.5], [0.3, -2.0]],
                &[[2.3375, -0.025], [0.0, -1.0], [2.0, 0.0], [-0.5, 0.4]],
            ],
        )
    }

    fn quintic() -> PolyCurve<f64> {
        PolyCurve::single(
            0.0,
            2.0,
            &[
                [0.0, 0.0],
                [1.0, 0.5],
                [0.0, -2.0],
                [0.5, 1.0],
                [-0.4, 0.3],
                [0.05, -0.1],
            ],
        )
    }

    #[test]
    fn polyline_is_within_tolerance() {
        for tol in [1e-1, 1e-2, 1e-3, 1e-4] {
            let p = flatten_vec(&parabola(), tol);
            assert!(max_deviation(&parabola(), &p) <= tol, "parabola {tol}");
            let c = three_cubics();
            let p = flatten_vec(&c, tol);
            assert!(max_deviation(&c, &p) <= tol, "cubics {tol}");
            let q = quintic();
            let p = flatten_vec(&q, tol);
            assert!(max_deviation(&q, &p) <= tol, "quintic {tol}");
            let ar = arc(2.0, 0.0, 3.0);
            let p = flatten_vec(&ar, tol);
            assert!(max_deviation(&ar, &p) <= tol, "arc {tol}");
            // The cusp (t³, t²).
            let cusp = PolyCurve::<f64>::single(
                -1.0,
                1.0,
                &[[0.0, 0.0], [0.0, 0.0], [0.0, 1.0], [1.0, 0.0]],
            );
            let p = flatten_vec(&cusp, tol);
            assert!(max_deviation(&cusp, &p) <= tol, "cusp {tol}");
        }
    }

    #[test]
    fn vertex_count_is_near_minimal() {
        for tol in [1e-2, 1e-3, 1e-4] {
            let cases: [(&str, usize, usize); 3] = [
                (
                    "parabola",
                    flatten_count(&parabola(), tol).unwrap() - 1,
                    min_uniform_segments(&parabola(), tol),
                ),
                (
                    "arc",
                    flatten_count(&arc(2.0, 0.0, 3.0), tol).unwrap() - 1,
                    min_uniform_segments(&arc(2.0, 0.0, 3.0), tol),
                ),
                (
                    "quintic",
                    flatten_count(&quintic(), tol).unwrap() - 1,
                    min_uniform_segments(&quintic(), tol),
                ),
            ];
            for (name, ours, best) in cases {
                // (`ours` may be below `best`: halved intervals adapt the spacing.)
                assert!(
                    ours <= best + best / 10 + 1,
                    "{name} {tol}: {ours} vs minimum {best}"
                );
            }
        }
    }

    #[test]
    fn parabola_count_is_exact() {
        // |c''| = 2 everywhere: n = ⌈2 · √(2 / (8 tol))⌉ = ⌈1/√tol⌉.
        // (Tolerances away from the exact thresholds 1/n², where rounding decides.)
        assert_eq!(flatten_count(&parabola(), 0.0125).unwrap(), 10);
        // 71 uniform segments on [-1, 1] are more than one run: the halves take 36 each.
        assert_eq!(flatten_count(&parabola(), 2e-4).unwrap(), 73);
        assert_eq!(flatten_count(&parabola(), 1.0 / 81.0 * 1.001).unwrap(), 10);
        assert_eq!(flatten_count(&parabola(), 1.0 / 81.0 * 0.999).unwrap(), 11);
    }

    #[test]
    fn ends_and_piece_boundaries_are_vertices() {
        let c = three_cubics();
        let p = flatten_vec(&c, 1e-3);
        assert_eq!(p[0], c.eval(0.0));
        assert_eq!(*p.last().unwrap(), c.eval(3.0));
        for u in [1.0, 1.5] {
            assert!(p.contains(&c.eval(u)), "boundary {u}");
        }
        // A straight line is two vertices; a polyline of lines is one vertex per corner.
        let line = PolyCurve::<f64>::single(0.0, 1.0, &[[1.0, 2.0], [3.0, -4.0]]);
        assert_eq!(flatten_vec(&line, 1e-12), vec![[1.0, 2.0], [4.0, -2.0]]);
        let corners = PolyCurve::<f64>::new(
            &[0.0, 1.0, 2.0],
            &[&[[0.0, 0.0], [1.0, 0.0]], &[[1.0, 0.0], [0.0, 1.0]]],
        );
        assert_eq!(
            flatten_vec(&corners, 1e-12),
            vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]
        );
    }

    #[test]
    fn capacity_exceeded_reports_the_required_count() {
        let c = parabola();
        let need = flatten_count(&c, 0.01).unwrap();
        let mut small = [[0.0; 2]; 5];
        assert_eq!(
            flatten(&c, 0.01, &mut small),
            Err(Error::CapacityExceeded {
                capacity: 5,
                required: need
            })
        );
        // The prefix that fits is written.
        assert_eq!(small[0], [-1.0, 1.0]);
        let mut exact = vec![[0.0; 2]; need];
        assert_eq!(flatten(&c, 0.01, &mut exact), Ok(need));
    }

    #[test]
    fn bad_tolerance_is_invalid_argument() {
        let mut out = [[0.0; 2]; 8];
        for tol in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert_eq!(
                flatten(&parabola(), tol, &mut out),
                Err(Error::InvalidArgument)
            );
            assert_eq!(flatten_count(&parabola(), tol), Err(Error::InvalidArgument));
        }
    }

    #[test]
    fn non_finite_derivative_is_reported() {
        let bad = FnCurve {
            f: |t: f64, k: usize| if k == 2 { [f64::NAN, 0.0] } else { [t, 0.0] },
            a: 0.0,
            b: 1.0,
        };
        assert_eq!(flatten_count(&bad, 0.1), Err(Error::NonFinite));
    }

    #[test]
    fn the_pieces_share_one_segment_budget() {
        // (s, s²) on pieces of length 1: h²/8·2 ≤ tol needs n = √(1/(4 tol)) segments per
        // piece, 3.2·10⁴ at tol = 2.5e-10. One piece fits 2¹⁶ segments, three do not.
        let piece: &[[f64; 2]] = &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
        let tol = 2.5e-10;
        let one = PolyCurve::<f64>::new(&[0.0, 1.0], &[piece]);
        let n = flatten_count(&one, tol).unwrap();
        // (Fewer than uniform segments: halved intervals follow the chord's turn, which
        // lowers the normal part of c'' where the parabola is steep.)
        assert!((22_000..32_000).contains(&n), "{n}");
        let three = PolyCurve::<f64>::new(&[0.0, 1.0, 2.0, 3.0], &[piece, piece, piece]);
        let counted = Counted::new(&three);
        match flatten_count(&counted, tol) {
            Err(Error::CapacityExceeded { capacity, required }) => {
                assert_eq!(capacity, MAX_SEGMENTS);
                assert!(required > MAX_SEGMENTS, "{required}");
            }
            other => panic!("{other:?}"),
        }
        // The documented bound: the resolution check, then at most 2¹² intervals of two
        // evaluations and 12·64 certificates of 8 evaluations each.
        let bound = (2 * 3 + 2 + MAX_INTERVALS * (2 + 12 * RUN * 8)) as u64;
        assert!(counted.calls() <= bound, "{}", counted.calls());
    }

    #[test]
    fn unreachable_tolerance_is_an_error() {
        // 1e-300 is below f64's resolution at the parabola's size (extent 1): rejected at once.
        assert_eq!(
            flatten_count(&parabola(), 1e-300),
            Err(Error::ToleranceBelowResolution { scalar: "f64" })
        );
        // 1e-14 is resolvable but needs about 1/√tol = 10⁷ segments: more than 2^16, in
        // more than 2^12 intervals of at most 64 segments, which is found first.
        assert_eq!(
            flatten_count(&parabola(), 1e-14),
            Err(Error::IterationLimit {
                limit: MAX_INTERVALS
            })
        );
        // In I16F16 the resolution is the spacing 2⁻¹⁶ of its values.
        let q = PolyCurve::<I16F16>::single(-1.0, 1.0, &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
        assert_eq!(resolution(&q), 1.0 / 65536.0);
        assert_eq!(
            flatten_count(&q, 1e-8),
            Err(Error::ToleranceBelowResolution { scalar: "I16F16" })
        );
        let n = flatten_count(&q, 1.5 / 65536.0).unwrap();
        assert!(n > 100, "{n}");
    }

    #[test]
    fn the_halving_depth_is_bounded() {
        // A "curve" whose second derivative claims 10⁶⁰ on [0, 1]: h²/8·10⁶⁰ ≤ 10⁻³ needs
        // h ≤ 2.8·10⁻³², far below the 2⁻⁷⁹ ≈ 1.7·10⁻²⁴ of 79 halvings. The halving goes
        // down one side, two evaluations per interval, and stops at its depth with an error
        // (not with a uniform run of 2¹⁶ segments at the deepest interval).
        let steep = FnCurve {
            f: |t: f64, k: usize| match k {
                0 => [t, 0.0],
                1 => [1.0, 0.0],
                2 => [0.0, 1e60],
                _ => [0.0, 0.0],
            },
            a: 0.0,
            b: 1.0,
        };
        let counted = Counted::new(&steep);
        assert_eq!(
            flatten_count(&counted, 1e-3),
            Err(Error::IterationLimit { limit: MAX_DEPTH })
        );
        assert!(
            counted.calls() <= 4 + 2 * MAX_DEPTH as u64,
            "{}",
            counted.calls()
        );
    }

    #[test]
    fn segments_below_the_parameter_spacing_are_an_error() {
        // (t, t²), t = u − 1500 on u ∈ [1500, 1500.01] in f32: the parameter spacing there is
        // 2⁻¹³ ≈ 1.22·10⁻⁴, so the piece has only 82 parameter steps. Tolerance 1e-8 needs
        // h ≤ 2·10⁻⁴ (50 segments); 5e-9 needs h ≤ 1.41·10⁻⁴, which uniform segments of
        // rounded parameters cannot keep (some span two steps), but halved intervals of one
        // step can; 2e-9 needs h ≤ 8.9·10⁻⁵, shorter than a step: an error, although 2e-9
        // is above the resolution of the points.
        let q = PolyCurve::<f32>::new(&[1500.0, 1500.01], &[&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]]);
        assert!(resolution(&q) < 2e-9);
        // (The rounded parameters decide the counts: at most one vertex per step.)
        let n = flatten_count(&q, 1e-8).unwrap();
        assert!((50..=83).contains(&n), "{n}");
        let fine = flatten_vec(&q, 5e-9);
        assert!(fine.len() <= 83, "{}", fine.len());
        assert!(fine.windows(2).all(|w| w[0] != w[1]), "a repeated vertex");
        assert!(max_deviation(&q, &fine) <= 5e-9 * (1.0 + 1e-6));
        assert_eq!(
            flatten_count(&q, 2e-9),
            Err(Error::ToleranceBelowResolution { scalar: "f32" })
        );
    }

    #[test]
    fn works_in_f32_and_fixed_point() {
        let c = PolyCurve::<f32>::single(-1.0, 1.0, &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
        let p = flatten_vec(&c, 1e-3);
        assert_eq!(p.len(), flatten_count(&parabola(), 1e-3).unwrap());
        assert!(max_deviation(&c, &p) <= 1e-3 + 1e-6);
        let c = PolyCurve::<I32F32>::new(
            &[0.0, 1.0, 1.5, 3.0],
            &[
                &[[0.0, 0.0], [1.0, 2.0], [0.5, -3.0], [-0.2, 1.0]],
                &[[1.3, 0.0], [1.5, 0.2], [1.0, 0.5], [0.3, -2.0]],
                &[[2.3375, -0.025], [0.0, -1.0], [2.0, 0.0], [-0.5, 0.4]],
            ],
        );
        let p = flatten_vec(&c, 1e-3);
        assert!(max_deviation(&c, &p) <= 1e-3 + 1e-8);
        assert_eq!(p[0], c.eval(c.domain().0));
        assert_eq!(*p.last().unwrap(), c.eval(c.domain().1));
    }
}
