//! A B-spline converted once into per-span polynomials in the power (monomial) basis and
//! evaluated with the Horner scheme: the fast random-access evaluator.
//!
//! The route is the textbook one: each non-empty knot span `[u_s, u_{s+1})` of a B-spline of
//! degree `g` is one polynomial piece. Its Bézier points are the blossom values
//! `b_j = f(u_s^{g−j}, u_{s+1}^j)` (Bézier extraction by knot insertion, Piegl & Tiller,
//! *The NURBS Book*, 2nd ed., §5.3; the same triangle as [`BSpline::to_bezier_segments`]),
//! and the Bernstein → monomial matrix `T_{M←B}` (Farin, *Curves and Surfaces for CAGD*,
//! 5th ed., §4.8; [`bernstein_to_monomial_matrix`](crate::basis::bernstein_to_monomial_matrix)) turns them
//! into the coefficients of
//!
//! ```text
//! c(u) = a_0 + a_1 t + … + a_g t^g,   t = (u − u_s)·r_s ∈ [0, 1],   r_s = 1/(u_{s+1} − u_s),
//! ```
//!
//! evaluated by Horner (Piegl & Tiller §1.2, Algorithm A1.1): `g` multiplications and `g`
//! additions per coordinate, no division. Derivatives: `c^{(k)}(u) = r_s^k · Σ_{j≥k}
//! j!/(j−k)!·a_j t^{j−k}`.
//!
//! The coefficients are computed in `f64` from the de Boor points and rounded once to the
//! scalar; the result differs from de Boor's algorithm ([`BSpline`]'s `eval`, which stays the
//! exact reference) by a few roundings.

use heapless::Vec;

use super::curve::BSpline;
use super::knots::{BSPLINE_MAX_DEGREE, KnotVector, LOCAL};
use super::local_coords;
use crate::basis::bernstein_to_monomial_matrix;
use crate::curve::{ParamCurve, ParamCurveDeriv, PieceDeriv};
use crate::error::Error;
use crate::point::Point;
use crate::scalar::Scalar;

/// One polynomial piece: its knot span `[start, end)`, the reciprocal
/// `scale = r = 1/(end − start)` and the power-basis coefficients in the normalised parameter
/// (in this order: span lookup and Horner read one record, the lookup fields first).
///
/// On x86-64 and AArch64 hosts aligned to a 64-byte cache line: a cubic 3-D piece (`f32`:
/// 60 bytes, `f64`/`I32F32`: 120 bytes) then occupies exactly one or two lines and no load
/// straddles two lines, which measurably speeds up random access there. Microcontrollers
/// (no such cache) keep the pieces packed: no padding in their RAM or flash.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    any(target_arch = "x86_64", target_arch = "aarch64"),
    repr(C, align(64))
)]
#[cfg_attr(not(any(target_arch = "x86_64", target_arch = "aarch64")), repr(C))]
struct Piece<P: Point, const K: usize> {
    start: P::Scalar,
    end: P::Scalar,
    scale: P::Scalar,
    coef: [P; K],
}

/// A B-spline as piecewise polynomials in the power (monomial) basis, evaluated with the
/// Horner scheme: the fast random-access evaluator of a [`BSpline`] (the piecewise power
/// basis form, Piegl & Tiller §1.2 and §5.3).
///
/// `K` is the order (coefficients per piece, at least degree + 1; higher coefficients are
/// zero), `N` the capacity of pieces (non-empty knot spans). Piece `i` on `[u_s, u_{s+1})`
/// stores `a_0, …, a_{K−1}` with `c(u) = Σ a_j t^j`, `t = (u − u_s)·r_s`,
/// `r_s = 1/(u_{s+1} − u_s)`; built by Bézier extraction and the Bernstein → monomial matrix
/// `T_{M←B}` (module docs).
///
/// **Span lookup** (no panic path): when the pieces are (nearly) equally long — checked at
/// construction, in the scalar's own arithmetic, for every piece — the index is
/// `⌊(u − u_first)·(1/h)⌋`, clamped, then corrected by at most one step against the stored
/// start and end of that piece: O(1). Otherwise a binary search over the piece starts. Parameters outside the domain are
/// clamped to it; at an inner knot the piece starting there is used, at the right end the last
/// piece (the convention of [`BSpline`] and [`KnotVector::span`]). Zero-length spans (knots
/// of multiplicity > 1) are no pieces.
///
/// **Accuracy.** Not bit-identical to [`BSpline`]'s de Boor evaluation: the coefficients are
/// rounded once from `f64`, and Horner's rounding error is bounded by
/// `≈ 2g·ε·Σ_j |a_j|` (the power basis's condition on `[0, 1]`).
///
/// **Fixed-point range.** The constructor computes in `f64`, for every piece and coordinate,
/// with `T = max(1, t_max)` (`t_max` the largest `t` the rounded `(u − u_s)·r_s` can reach):
/// every coefficient, every partial Horner sum `Σ_{i≥j} i!/(i−k)!·|a_i|·T^{i−j}` for every
/// derivative order `0 ≤ k ≤ g`, and the scaled results `·max(1, r_s)^k`; and the span index
/// product `(u − u_first)·(1/h)`. All must satisfy [`Scalar::fits`], else
/// [`Error::OutOfRange`]. The Horner scheme has no divisor; every `r_s` is checked positive.
///
/// ```
/// use strak_curves::{BSpline, ParamCurve, ParamCurveDeriv, PowerSpline};
///
/// let d = [[0.0, 0.0, 0.0], [1.0, 2.0, 0.5], [3.0, 2.0, 1.0], [4.0, 0.0, 1.5], [6.0, 1.0, 2.0]];
/// let b = BSpline::<[f64; 3], 8, 16>::clamped_uniform(3, &d, 0.0, 2.0).unwrap();
/// let p = PowerSpline::<[f64; 3], 4, 8>::from_bspline(&b).unwrap();
/// assert_eq!(p.piece_count(), 2);
/// for i in 0..=20 {
///     let u = 0.1 * f64::from(i);
///     let (x, y) = (p.eval(u), b.eval(u));
///     let (dx, dy) = (p.deriv(u, 1), b.deriv(u, 1));
///     for c in 0..3 {
///         assert!((x[c] - y[c]).abs() < 1e-13);
///         assert!((dx[c] - dy[c]).abs() < 1e-12);
///     }
/// }
/// assert_eq!(p.eval(2.0), [6.0, 1.0, 2.0]);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct PowerSpline<P: Point, const K: usize, const N: usize> {
    /// The pieces in order (`start` strictly increasing, `end` = the next `start`).
    pieces: Vec<Piece<P, K>, N>,
    /// The domain `[u_g, u_K]`.
    lo: P::Scalar,
    hi: P::Scalar,
    degree: usize,
    /// `n/(u_K − u_g)` when the O(1) span guess is validated for every piece.
    inv_spacing: Option<P::Scalar>,
}

impl<P: Point, const K: usize, const N: usize> PowerSpline<P, K, N> {
    /// Converts an open or closed [`BSpline`] (for a closed curve the periodic pieces of its
    /// domain; evaluation clamps like [`BSpline`], it does not wrap).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for `K = 0`; [`Error::DegreeTooHigh`] (`max: K − 1`) when
    /// the degree exceeds `K − 1`; [`Error::CapacityExceeded`] when the curve has more than
    /// `N` pieces; [`Error::OutOfRange`] when a coefficient or an intermediate value of the
    /// evaluation does not fit the scalar (see the type's range rule).
    ///
    /// ```
    /// use strak_curves::{BSpline, Error, I32F32, ParamCurve, PowerSpline};
    ///
    /// let f = |x: f64| I32F32::from_num(x);
    /// let d = [[f(0.0)], [f(3.0)], [f(6.0)], [f(3.0)], [f(0.0)]];
    /// let b = BSpline::<[I32F32; 1], 8, 16>::clamped_uniform(2, &d, f(0.0), f(3.0)).unwrap();
    /// let p = PowerSpline::<[I32F32; 1], 3, 4>::from_bspline(&b).unwrap();
    /// assert_eq!(p.eval(f(1.5)), [f(5.25)]);
    /// assert_eq!(p.eval(f(1.5)), b.eval(f(1.5)));
    /// let e = PowerSpline::<[I32F32; 1], 3, 2>::from_bspline(&b).unwrap_err();
    /// assert_eq!(e, Error::CapacityExceeded { capacity: 2, required: 3 });
    /// let e = PowerSpline::<[I32F32; 1], 2, 4>::from_bspline(&b).unwrap_err();
    /// assert_eq!(e, Error::DegreeTooHigh { max: 1, found: 2 });
    /// ```
    pub fn from_bspline<const NB: usize, const MB: usize>(
        curve: &BSpline<P, NB, MB>,
    ) -> Result<Self, Error> {
        if K == 0 {
            return Err(Error::InvalidArgument);
        }
        let g = curve.degree();
        if g + 1 > K {
            return Err(Error::DegreeTooHigh {
                max: K - 1,
                found: g,
            });
        }
        let kv = curve.knot_vector();
        let count = kv.piece_count();
        if count > N {
            return Err(Error::CapacityExceeded {
                capacity: N,
                required: count,
            });
        }
        let capacity = || Error::CapacityExceeded {
            capacity: N,
            required: count,
        };
        let (lo, hi) = kv.domain();
        let mut pieces: Vec<Piece<P, K>, N> = Vec::new();
        for s in g..kv.control_point_count() {
            let (a, b) = (kv.knot(s), kv.knot(s + 1));
            if a >= b {
                continue;
            }
            let piece = convert_span(curve, s)?;
            check_piece_range(&piece, g)?;
            pieces.push(piece).map_err(|_| capacity())?;
        }
        if pieces.is_empty() {
            // A validated knot vector has a non-empty domain: never reached.
            return Err(Error::ZeroLengthInterval { index: g });
        }
        let inv_spacing = uniform_guess(&pieces, lo, hi);
        Ok(PowerSpline {
            pieces,
            lo,
            hi,
            degree: g,
            inv_spacing,
        })
    }

    /// The degree `g` of the B-spline the pieces came from.
    #[inline]
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The power-basis coefficients `[a_0, …, a_{K−1}]` of piece `i` in the normalised
    /// parameter `t ∈ [0, 1]`, and `r = 1/(u_{s+1} − u_s)`; `None` for `i ≥ piece_count()`.
    ///
    /// ```
    /// use strak_curves::{BSpline, PowerSpline};
    /// // Degree 1 through 0, 2, 3 on knots 0, 0, 1, 3, 3: pieces 0 + 2t and 2 + t.
    /// let b = BSpline::<[f64; 1], 4, 8>::new(1, &[[0.0], [2.0], [3.0]], &[0., 0., 1., 3., 3.])
    ///     .unwrap();
    /// let p = PowerSpline::<[f64; 1], 2, 4>::from_bspline(&b).unwrap();
    /// assert_eq!(p.piece_coefficients(0), Some((&[[0.0], [2.0]], 1.0)));
    /// assert_eq!(p.piece_coefficients(1), Some((&[[2.0], [1.0]], 0.5)));
    /// assert_eq!(p.piece_coefficients(2), None);
    /// ```
    pub fn piece_coefficients(&self, i: usize) -> Option<(&[P; K], P::Scalar)> {
        self.pieces.get(i).map(|p| (&p.coef, p.scale))
    }

    /// `true` when span lookup is O(1) (equally long pieces, validated at construction);
    /// otherwise it is a binary search.
    #[inline]
    pub fn is_uniform(&self) -> bool {
        self.inv_spacing.is_some()
    }

    /// The piece of `u` (already clamped to the domain): `start ≤ u < end`, the last piece
    /// at the right end. `None` only for a curve without pieces (never constructed).
    #[inline(always)]
    fn piece_of(&self, u: P::Scalar) -> Option<&Piece<P, K>> {
        let pieces = self.pieces.as_slice();
        let last = pieces.len().saturating_sub(1);
        let i = if let Some(inv) = self.inv_spacing {
            // Within one piece of the right one (checked at construction).
            let i = guess(u, self.lo, inv, last);
            let p = pieces.get(i)?;
            if u < p.start {
                i.saturating_sub(1)
            } else if u >= p.end && i < last {
                i + 1
            } else {
                return Some(p);
            }
        } else {
            pieces.partition_point(|p| p.start <= u).saturating_sub(1)
        };
        pieces.get(i)
    }

    /// `c^{(k)}` on `piece` at `u` (any `u`; callers clamp).
    fn deriv_in_piece(&self, piece: Option<&Piece<P, K>>, u: P::Scalar, k: usize) -> P {
        let g = self.degree;
        let Some(piece) = piece.filter(|_| k <= g) else {
            return P::zero();
        };
        let t = (u - piece.start) * piece.scale;
        if k == 0 {
            return horner(&piece.coef, t);
        }
        let mut acc = P::zero();
        for (j, a) in piece.coef.iter().enumerate().take(g + 1).skip(k).rev() {
            let f = P::Scalar::from_i16(falling_factorial(j, k));
            acc = acc.times(t).plus(a.times(f));
        }
        for _ in 0..k {
            acc = acc.times(piece.scale);
        }
        acc
    }
}

/// The Horner scheme `a_0 + t(a_1 + t(… + t·a_{K−1}))` over all `K` coefficients (a
/// constant trip count: unrolled for each `K`).
#[inline(always)]
fn horner<P: Point, const K: usize>(coef: &[P; K], t: P::Scalar) -> P {
    let Some((&last, rest)) = coef.split_last() else {
        return P::zero();
    };
    let mut acc = last;
    for &a in rest.iter().rev() {
        acc = acc.times(t).plus(a);
    }
    acc
}

/// `j!/(j − k)!` for `k ≤ j ≤` [`BSPLINE_MAX_DEGREE`] (at most 7! = 5040); saturating.
fn falling_factorial(j: usize, k: usize) -> i16 {
    let mut r: i16 = 1;
    for m in 0..k.min(j) {
        r = r.saturating_mul(i16::try_from(j - m).unwrap_or(i16::MAX));
    }
    r
}

/// The piece of span `s`: Bézier extraction in `f64` (the blossom), `T_{M←B}`, rounding.
fn convert_span<P: Point, const K: usize, const NB: usize, const MB: usize>(
    curve: &BSpline<P, NB, MB>,
    s: usize,
) -> Result<Piece<P, K>, Error> {
    let kv = curve.knot_vector();
    let g = kv.degree().min(BSPLINE_MAX_DEGREE);
    let (a, b) = (kv.knot(s), kv.knot(s + 1));
    let h = (b - a).to_f64();
    let scale = P::Scalar::from_f64(1.0 / h).ok_or(Error::OutOfRange)?;
    if scale <= P::Scalar::ZERO {
        return Err(Error::OutOfRange);
    }
    let mut coef = [P::zero(); K];
    for c in 0..P::DIM {
        let v = local_coords(curve.control_points(), s, g, c);
        let bez: [f64; LOCAL] = core::array::from_fn(|j| {
            if j <= g {
                blossom_f64(kv, s, v, g - j)
            } else {
                0.0
            }
        });
        let mono = monomial_of(g, &bez)?;
        for (j, o) in coef.iter_mut().enumerate() {
            let x = mono.get(j).copied().unwrap_or(0.0);
            let x = P::Scalar::from_f64(x).ok_or(Error::OutOfRange)?;
            let old = *o;
            *o = P::from_coords(|d| if d == c { x } else { old.coord(d) });
        }
    }
    Ok(Piece {
        start: a,
        end: b,
        scale,
        coef,
    })
}

/// The blossom `f(u_s^{na}, u_{s+1}^{g−na})` of one coordinate of the piece on span `s`
/// (de Boor's triangle in `f64` with `u_s` at the first `na` levels, `u_{s+1}` after).
fn blossom_f64<S: Scalar, const M: usize>(
    kv: &KnotVector<S, M>,
    s: usize,
    mut d: [f64; LOCAL],
    na: usize,
) -> f64 {
    let g = kv.degree().min(BSPLINE_MAX_DEGREE);
    let t = |i: usize| kv.knot(i).to_f64();
    let (a, b) = (t(s), t(s + 1));
    for r in 1..=g {
        let x = if r <= na { a } else { b };
        for j in (r..=g).rev() {
            let i = (s + j).saturating_sub(g);
            let den = t(i + g + 1 - r) - t(i);
            let alpha = if den > 0.0 { (x - t(i)) / den } else { 0.0 };
            d[j] = (1.0 - alpha) * d[j - 1] + alpha * d[j];
        }
    }
    d[g]
}

/// `a⃗ = T_{M←B} b⃗` for degree `g` (the first `g + 1` entries of `b`).
fn monomial_of(g: usize, b: &[f64; LOCAL]) -> Result<[f64; LOCAL], Error> {
    match g {
        0 => apply::<1>(b),
        1 => apply::<2>(b),
        2 => apply::<3>(b),
        3 => apply::<4>(b),
        4 => apply::<5>(b),
        5 => apply::<6>(b),
        6 => apply::<7>(b),
        _ => apply::<8>(b),
    }
}

/// `a_j = Σ_i T_{M←B}[j][i]·b_i` with the matrix of degree `G1 − 1`.
fn apply<const G1: usize>(b: &[f64; LOCAL]) -> Result<[f64; LOCAL], Error> {
    let t = bernstein_to_monomial_matrix::<f64, G1>()?;
    let mut a = [0.0; LOCAL];
    for (aj, row) in a.iter_mut().zip(t.iter()) {
        *aj = row.iter().zip(b.iter()).map(|(m, x)| m * x).sum();
    }
    Ok(a)
}

/// The fixed-point range rule of [`PowerSpline`] for one piece.
fn check_piece_range<P: Point, const K: usize>(piece: &Piece<P, K>, g: usize) -> Result<(), Error> {
    let len = piece.end - piece.start;
    let eps = <P::Scalar as Scalar>::EPSILON;
    let r = piece.scale.to_f64();
    // t = (u − u_s)·r with 0 ≤ u − u_s ≤ len (exact or rounded by ≤ ε relative), one rounding.
    let t_max = (len.to_f64() * r * (1.0 + 4.0 * eps) + eps).max(1.0);
    let fits = <P::Scalar as Scalar>::fits;
    if !fits(t_max) || !fits(r) || !fits(len.to_f64()) {
        return Err(Error::OutOfRange);
    }
    for c in 0..P::DIM {
        for k in 0..=g {
            let mut h = 0.0_f64;
            for (j, a) in piece.coef.iter().enumerate().skip(k).rev() {
                let ff = if j <= g {
                    f64::from(falling_factorial(j, k))
                } else {
                    1.0
                };
                h = a.coord(c).to_f64().abs() * ff + t_max * h;
                if !fits(h) {
                    return Err(Error::OutOfRange);
                }
            }
            for _ in 0..k {
                h *= r.max(1.0);
                if !fits(h) {
                    return Err(Error::OutOfRange);
                }
            }
        }
    }
    Ok(())
}

/// The O(1) span guess `min(⌊(u − lo)·inv⌋, last)` (monotone in `u`). The conversion goes
/// through `u32` (cheaper than `usize` from `f64`) and saturates (NaN → 0), so it cannot
/// overflow; beyond `u32::MAX` pieces the construction-time check rejects the guess.
#[inline(always)]
fn guess<S: Scalar>(u: S, lo: S, inv: S, last: usize) -> usize {
    let g = ((u - lo) * inv).to_f64() as u32;
    (g as usize).min(last)
}

/// `Some(n/(hi − lo))` when, in the scalar's arithmetic, the clamped guess
/// `⌊(u − lo)·inv⌋` is within one piece of the right one for every `u` of every piece (the
/// guess is monotone in `u`, so the ends of each piece suffice); `None` otherwise.
fn uniform_guess<P: Point, const K: usize>(
    pieces: &[Piece<P, K>],
    lo: P::Scalar,
    hi: P::Scalar,
) -> Option<P::Scalar> {
    let n = pieces.len();
    let width = hi.to_f64() - lo.to_f64();
    let inv = P::Scalar::from_f64(n as f64 / width)?;
    let eps = <P::Scalar as Scalar>::EPSILON;
    if inv <= P::Scalar::ZERO
        || !<P::Scalar as Scalar>::fits(width * inv.to_f64() * (1.0 + 4.0 * eps) + 2.0)
    {
        return None;
    }
    let last = n.saturating_sub(1);
    for (i, p) in pieces.iter().enumerate() {
        if guess(p.start, lo, inv, last) + 1 < i || guess(p.end, lo, inv, last) > i + 1 {
            return None;
        }
    }
    Some(inv)
}

impl<P: Point, const K: usize, const N: usize> ParamCurve for PowerSpline<P, K, N> {
    type Point = P;

    fn domain(&self) -> (P::Scalar, P::Scalar) {
        (self.lo, self.hi)
    }

    /// `c(u)`, `u` clamped to the domain: span lookup, `t = (u − u_s)·r_s`, Horner.
    #[inline]
    fn eval(&self, u: P::Scalar) -> P {
        let u = u.clamp_to(self.lo, self.hi);
        match self.piece_of(u) {
            Some(p) => horner(&p.coef, (u - p.start) * p.scale),
            None => P::zero(),
        }
    }

    fn piece_count(&self) -> usize {
        self.pieces.len()
    }

    fn piece_domain(&self, i: usize) -> (P::Scalar, P::Scalar) {
        let i = i.min(self.pieces.len().saturating_sub(1));
        self.pieces
            .get(i)
            .map_or((self.lo, self.hi), |p| (p.start, p.end))
    }
}

impl<P: Point, const K: usize, const N: usize> ParamCurveDeriv for PowerSpline<P, K, N> {
    /// `c^{(k)}(u) = r_s^k·Σ_{j≥k} j!/(j−k)!·a_j t^{j−k}`, `u` clamped; zero for `k > g`.
    #[inline]
    fn deriv(&self, u: P::Scalar, k: usize) -> P {
        let u = u.clamp_to(self.lo, self.hi);
        self.deriv_in_piece(self.piece_of(u), u, k)
    }
}

/// One-sided limits: piece `piece` (the last for `piece ≥ piece_count()`) at `u` clamped to
/// its domain.
impl<P: Point, const K: usize, const N: usize> PieceDeriv for PowerSpline<P, K, N> {
    fn piece_deriv(&self, piece: usize, u: P::Scalar, k: usize) -> P {
        let p = self
            .pieces
            .get(piece.min(self.pieces.len().saturating_sub(1)));
        let u = p.map_or(u, |p| u.clamp_to(p.start, p.end));
        self.deriv_in_piece(p, u, k)
    }
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    extern crate std;

    use super::*;
    use crate::scalar::{I16F16, I32F32};
    use glam::{DVec3, Vec3};

    type B2 = BSpline<[f64; 2], 16, 32>;
    type P2 = PowerSpline<[f64; 2], 4, 16>;

    const D7: [[f64; 2]; 7] = [
        [0.0, 0.0],
        [1.0, 3.0],
        [3.0, 4.0],
        [5.0, 1.0],
        [6.0, -2.0],
        [8.0, 0.5],
        [9.0, 3.0],
    ];

    fn close(a: [f64; 2], b: [f64; 2], tol: f64) -> bool {
        (a[0] - b[0]).abs() <= tol && (a[1] - b[1]).abs() <= tol
    }

    /// Compares every derivative at many parameters, inner knots and the ends included.
    fn agrees(b: &B2, p: &P2, tol: f64) {
        let (lo, hi) = b.domain();
        let mut us: std::vec::Vec<f64> = (0..=400)
            .map(|i| lo + (hi - lo) * f64::from(i) / 400.0)
            .collect();
        us.extend_from_slice(b.knots());
        us.extend([lo - 1.0, hi + 1.0]);
        for u in us {
            for k in 0..=b.degree() + 1 {
                let (x, y) = (p.deriv(u, k), b.deriv(u, k));
                let scale = 1.0 + y[0].abs().max(y[1].abs());
                assert!(close(x, y, tol * scale), "u={u} k={k} {x:?} {y:?}");
            }
            assert_eq!(p.eval(u), p.deriv(u, 0));
        }
    }

    /// The open cubic (g = 3, U = [0,0,0,0,1,2,3,4,4,4,4]) with the de Boor points
    /// d_i = (i, i²): a clamped uniform cubic reproduces quadratics exactly where the
    /// knot vector is uniform enough; here checked at the closed-form values c(0) = d_0,
    /// c(4) = d_6 and the uniform inner-piece formula c(u_s) = (d_{s−3} + 4 d_{s−2} + d_{s−1})/6.
    #[test]
    fn open_cubic_example() {
        let d: [[f64; 2]; 7] = core::array::from_fn(|i| [i as f64, (i * i) as f64]);
        let b = B2::new(3, &d, &[0., 0., 0., 0., 1., 2., 3., 4., 4., 4., 4.]).unwrap();
        let p = P2::from_bspline(&b).unwrap();
        assert_eq!(p.piece_count(), 4);
        assert!(p.is_uniform());
        assert_eq!(p.eval(0.0), d[0]);
        assert!(close(p.eval(4.0), d[6], 1e-14));
        // At u = 2 (s = 5): (d_2 + 4 d_3 + d_4)/6 = (3, (4 + 36 + 16)/6).
        assert!(close(p.eval(2.0), [3.0, 56.0 / 6.0], 1e-14));
        // End tangent 3/(u_4 − u_1)·(d_1 − d_0) = 3·(1, 1).
        assert!(close(p.deriv(0.0, 1), [3.0, 3.0], 1e-14));
        agrees(&b, &p, 1e-13);
    }

    #[test]
    fn coefficients_of_a_cubic_bezier() {
        // One piece (Bernstein): the monomial form of b = (2, −2, 5, 1) is (2, −12, 33, −22)
        // (the worked example of the basis module docs).
        let d = [[2.0, 0.0], [-2.0, 0.0], [5.0, 0.0], [1.0, 0.0]];
        let b = B2::new(3, &d, &[1., 1., 1., 1., 3., 3., 3., 3.]).unwrap();
        let p = P2::from_bspline(&b).unwrap();
        let (c, r) = p.piece_coefficients(0).unwrap();
        assert_eq!(c.map(|x| x[0]), [2.0, -12.0, 33.0, -22.0]);
        assert_eq!(r, 0.5);
        assert_eq!(p.eval(2.0), [2.0 - 6.0 + 33.0 / 4.0 - 22.0 / 8.0, 0.0]);
        // c'(u) = r·(−12 + 66t − 66t²)
        assert_eq!(p.deriv(1.0, 1), [-6.0, 0.0]);
        assert_eq!(p.deriv(1.5, 3), [-132.0 / 8.0, 0.0]);
        assert_eq!(p.deriv(1.5, 4), [0.0, 0.0]);
    }

    #[test]
    fn non_uniform_and_multiple_knots() {
        let b = B2::new(3, &D7, &[-3., -2., -1., 0., 0.5, 2., 2.5, 3., 4., 5., 6.]).unwrap();
        let p = P2::from_bspline(&b).unwrap();
        // Unequal pieces, but the O(1) guess ⌊u·4/3⌋ is never off by more than one.
        assert!(p.is_uniform());
        agrees(&b, &p, 1e-12);
        let b = B2::new(3, &D7, &[-3., -2., -1., 0., 0.1, 0.2, 2.5, 3., 4., 5., 6.]).unwrap();
        let p = P2::from_bspline(&b).unwrap();
        assert!(!p.is_uniform());
        agrees(&b, &p, 1e-12);
        // Multiplicity 2 at 1 and 3 (= g) at 2: zero-length spans are skipped.
        let t = [0., 0., 0., 0., 1., 1., 2., 2., 2., 3., 3., 3., 3.];
        let d: [[f64; 2]; 9] = core::array::from_fn(|i| [i as f64, ((i * 7) % 5) as f64]);
        let b = B2::new(3, &d, &t).unwrap();
        let p = P2::from_bspline(&b).unwrap();
        assert_eq!(p.piece_count(), 3);
        assert_eq!(p.piece_domain(0), (0.0, 1.0));
        assert_eq!(p.piece_domain(1), (1.0, 2.0));
        assert_eq!(p.piece_domain(9), (2.0, 3.0));
        assert!(p.is_uniform());
        agrees(&b, &p, 1e-12);
        assert!(close(p.eval(2.0), d[5], 1e-14));
        // One-sided limits at the C⁰ knot u = 2.
        let (l, r) = (p.piece_deriv(1, 2.0, 1), p.piece_deriv(2, 2.0, 1));
        assert!(close(l, b.piece_deriv(1, 2.0, 1), 1e-12));
        assert!(close(r, b.piece_deriv(2, 2.0, 1), 1e-12));
        assert!(!close(l, r, 1e-6));
    }

    #[test]
    fn span_lookup_at_inner_knots_and_ends() {
        // Degree 1 (exact in f64): the value identifies the piece; slopes 1, 2, 3, 4.
        let d = [[0.0], [1.0], [3.0], [6.0], [10.0]];
        for knots in [
            [0., 0., 1., 2., 3., 4., 4.],
            [0., 0., 0.125, 0.25, 3.75, 4., 4.],
        ] {
            let b = BSpline::<[f64; 1], 8, 16>::new(1, &d, &knots).unwrap();
            let p = PowerSpline::<[f64; 1], 2, 4>::from_bspline(&b).unwrap();
            assert_eq!(p.is_uniform(), knots[2] == 1.0);
            for s in 1..=4 {
                let u = knots[s];
                // deriv at an inner knot: the piece starting there; at the end: the last.
                let want = b.deriv(u, 1);
                assert_eq!(p.deriv(u, 1), want, "u = {u}");
                let start = |u: f64| p.piece_of(u).map(|q| q.start);
                assert_eq!(start(u), Some(knots[s.min(4)]));
                if s > 1 {
                    let below = f64::from_bits(u.to_bits() - 1);
                    assert_eq!(start(below), Some(knots[s - 1]));
                }
            }
            assert_eq!(p.eval(4.0), [10.0]);
            assert_eq!(p.eval(0.0), [0.0]);
        }
    }

    #[test]
    fn domain_is_clamped() {
        let b = B2::clamped_uniform(3, &D7, 0.0, 1.0).unwrap();
        let p = P2::from_bspline(&b).unwrap();
        assert_eq!(p.domain(), (0.0, 1.0));
        assert_eq!(p.eval(-5.0), D7[0]);
        assert_eq!(p.eval(7.0), D7[6]);
        assert_eq!(p.eval(f64::NAN), D7[0]);
        assert_eq!(p.deriv(9.0, 1), p.deriv(1.0, 1));
        assert_eq!(p.deriv(f64::NEG_INFINITY, 2), p.deriv(0.0, 2));
        assert_eq!(p.piece_deriv(0, 0.9, 0), p.piece_deriv(0, 0.25, 0));
    }

    #[test]
    fn closed_curve() {
        let pts = [
            [2.0, 0.0],
            [1.0, 1.5],
            [-1.0, 1.0],
            [-2.0, -0.5],
            [0.0, -2.0],
        ];
        for g in 1..=3 {
            let b = B2::closed(g, &pts, Some(&[0.0, 0.5, 1.5, 2.0, 3.5, 4.0])).unwrap();
            let p = P2::from_bspline(&b).unwrap();
            assert_eq!(p.piece_count(), 5);
            agrees(&b, &p, 1e-12);
        }
        let b = B2::closed(3, &pts, None).unwrap();
        let p = P2::from_bspline(&b).unwrap();
        assert!(p.is_uniform());
        assert!(close(p.eval(0.0), p.eval(1.0), 1e-14));
    }

    #[test]
    fn lower_degree_in_higher_order_and_degree_zero() {
        let b = B2::clamped_uniform(2, &D7, 0.0, 5.0).unwrap();
        let p = PowerSpline::<[f64; 2], 6, 8>::from_bspline(&b).unwrap();
        assert_eq!(p.degree(), 2);
        let (c, _) = p.piece_coefficients(2).unwrap();
        assert_eq!(&c[3..], &[[0.0; 2]; 3]);
        for i in 0..=50 {
            let u = 0.1 * f64::from(i);
            for k in 0..=3 {
                assert!(close(p.deriv(u, k), b.deriv(u, k), 1e-12));
            }
        }
        let b = B2::new(0, &D7[..3], &[0., 1., 2., 3.]).unwrap();
        let p = PowerSpline::<[f64; 2], 1, 4>::from_bspline(&b).unwrap();
        assert_eq!(p.eval(1.0), D7[1]);
        assert_eq!(p.eval(3.0), D7[2]);
        assert_eq!(p.deriv(0.5, 1), [0.0, 0.0]);
    }

    #[test]
    fn degree_seven() {
        let d: [[f64; 2]; 10] = core::array::from_fn(|i| [i as f64, ((i * 3) % 7) as f64]);
        let b = B2::clamped_uniform(7, &d, 0.0, 3.0).unwrap();
        let p = PowerSpline::<[f64; 2], 8, 4>::from_bspline(&b).unwrap();
        for i in 0..=30 {
            let u = 0.1 * f64::from(i);
            for k in 0..=8 {
                let (x, y) = (p.deriv(u, k), b.deriv(u, k));
                let s = 1.0 + y[0].abs().max(y[1].abs());
                assert!(close(x, y, 1e-10 * s), "u={u} k={k}");
            }
        }
    }

    #[test]
    fn glam_and_f32() {
        let d = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 2.0, 3.0),
            DVec3::new(2.0, 0.0, 1.0),
            DVec3::new(4.0, 1.0, 0.0),
            DVec3::X,
        ];
        let b = BSpline::<DVec3, 8, 16>::clamped_uniform(3, &d, 0.0, 2.0).unwrap();
        let p = PowerSpline::<DVec3, 4, 4>::from_bspline(&b).unwrap();
        let df = d.map(|v| v.as_vec3());
        let bf = BSpline::<Vec3, 8, 16>::clamped_uniform(3, &df, 0.0, 2.0).unwrap();
        let pf = PowerSpline::<Vec3, 4, 4>::from_bspline(&bf).unwrap();
        for i in 0..=40 {
            let u = 0.05 * f64::from(i);
            for k in 0..=3 {
                let e = b.deriv(u, k);
                assert!((p.deriv(u, k) - e).abs().max_element() < 1e-12 * (1.0 + e.length()));
                let f = pf.deriv(u as f32, k).as_dvec3();
                assert!(
                    (f - e).abs().max_element() < 1e-5 * (1.0 + e.length()),
                    "k={k}"
                );
            }
        }
    }

    #[test]
    fn fixed_point_matches_f64() {
        let b = B2::new(3, &D7, &[0., 0., 0., 0., 0.5, 2., 2.75, 4., 4., 4., 4.]).unwrap();
        let p = P2::from_bspline(&b).unwrap();
        let t16: heapless::Vec<I16F16, 16> =
            b.knots().iter().map(|&x| I16F16::from_num(x)).collect();
        let b16 = BSpline::<[I16F16; 2], 8, 16>::new(3, &D7.map(|q| q.map(I16F16::from_num)), &t16)
            .unwrap();
        let p16 = PowerSpline::<[I16F16; 2], 4, 8>::from_bspline(&b16).unwrap();
        let t32: heapless::Vec<I32F32, 16> =
            b.knots().iter().map(|&x| I32F32::from_num(x)).collect();
        let b32 = BSpline::<[I32F32; 2], 8, 16>::new(3, &D7.map(|q| q.map(I32F32::from_num)), &t32)
            .unwrap();
        let p32 = PowerSpline::<[I32F32; 2], 4, 8>::from_bspline(&b32).unwrap();
        let mut worst16 = [0.0_f64; 4];
        let mut worst32 = [0.0_f64; 4];
        for i in 0..=400 {
            let u = 4.0 * f64::from(i) / 400.0;
            for k in 0..=3 {
                let e = p.deriv(u, k);
                let x = p16.deriv(I16F16::from_num(u), k);
                let y = p32.deriv(I32F32::from_num(u), k);
                for j in 0..2 {
                    worst16[k] = worst16[k].max((x[j].to_f64() - e[j]).abs());
                    worst32[k] = worst32[k].max((y[j].to_f64() - e[j]).abs());
                }
            }
        }
        assert!(
            worst16[0] < 2e-4 && worst16[1] < 2e-3 && worst16[3] < 2e-2,
            "{worst16:?}"
        );
        assert!(
            worst32[0] < 4e-9 && worst32[1] < 4e-8 && worst32[3] < 4e-7,
            "{worst32:?}"
        );
    }

    #[test]
    fn error_invalid_argument_for_order_zero() {
        let b = B2::new(0, &D7[..3], &[0., 1., 2., 3.]).unwrap();
        assert_eq!(
            PowerSpline::<[f64; 2], 0, 4>::from_bspline(&b).unwrap_err(),
            Error::InvalidArgument
        );
    }

    #[test]
    fn error_degree_too_high() {
        let b = B2::clamped_uniform(3, &D7, 0.0, 1.0).unwrap();
        assert_eq!(
            PowerSpline::<[f64; 2], 3, 8>::from_bspline(&b).unwrap_err(),
            Error::DegreeTooHigh { max: 2, found: 3 }
        );
    }

    #[test]
    fn error_capacity_exceeded() {
        let b = B2::clamped_uniform(3, &D7, 0.0, 1.0).unwrap();
        assert_eq!(
            PowerSpline::<[f64; 2], 4, 3>::from_bspline(&b).unwrap_err(),
            Error::CapacityExceeded {
                capacity: 3,
                required: 4
            }
        );
        assert!(PowerSpline::<[f64; 2], 4, 4>::from_bspline(&b).is_ok());
    }

    #[test]
    fn error_out_of_range() {
        let f = |x: f64| I16F16::from_num(x);
        // The B-spline fits (de Boor points ±2000 on a span of length 8: its derivatives are
        // small), but the power-basis coefficients of the normalised piece, (2000, −12000,
        // 24000, −16000), do not.
        let d = [[f(2000.0)], [f(-2000.0)], [f(2000.0)], [f(-2000.0)]];
        let b = BSpline::<[I16F16; 1], 4, 8>::clamped_uniform(3, &d, f(0.0), f(8.0)).unwrap();
        assert_eq!(
            PowerSpline::<[I16F16; 1], 4, 4>::from_bspline(&b).unwrap_err(),
            Error::OutOfRange
        );
        // The same curve scaled down fits, and in I32F32 it fits as it is.
        let d = [[f(40.0)], [f(-40.0)], [f(40.0)], [f(-40.0)]];
        let b = BSpline::<[I16F16; 1], 4, 8>::clamped_uniform(3, &d, f(0.0), f(8.0)).unwrap();
        let p = PowerSpline::<[I16F16; 1], 4, 4>::from_bspline(&b).unwrap();
        assert_eq!(p.piece_coefficients(0).unwrap().0[3], [f(-320.0)]);
        let g = |x: f64| I32F32::from_num(x);
        let d = [[g(2000.0)], [g(-2000.0)], [g(2000.0)], [g(-2000.0)]];
        let b = BSpline::<[I32F32; 1], 4, 8>::clamped_uniform(3, &d, g(0.0), g(8.0)).unwrap();
        assert!(PowerSpline::<[I32F32; 1], 4, 4>::from_bspline(&b).is_ok());
    }

    /// Whatever the constructor accepts evaluates without overflow (debug builds of `fixed`
    /// panic on overflow), inside and outside the domain, every derivative order.
    #[test]
    fn accepted_fixed_point_curves_never_overflow() {
        let f = |x: f64| I16F16::from_num(x);
        let mut accepted = 0;
        for scale in [1.0, 100.0, 1000.0, 4000.0, 16000.0] {
            for span in [1.0 / 64.0, 0.25, 1.0, 8.0, 1000.0] {
                for g in 1..=4 {
                    let pts: [[I16F16; 2]; 7] = core::array::from_fn(|i| {
                        let s = if i % 2 == 0 { 1.0 } else { -1.0 };
                        [f(scale * s), f(scale * (i as f64 / 7.0))]
                    });
                    let Ok(b) = BSpline::<[I16F16; 2], 8, 16>::clamped_uniform(
                        g,
                        &pts,
                        f(-3.0),
                        f(-3.0 + span * 4.0),
                    ) else {
                        continue;
                    };
                    let Ok(p) = PowerSpline::<[I16F16; 2], 5, 8>::from_bspline(&b) else {
                        continue;
                    };
                    accepted += 1;
                    let (lo, hi) = p.domain();
                    for i in -10..=210 {
                        let (a, w) = (lo.to_f64(), (hi - lo).to_f64());
                        let u = f(a + w * f64::from(i) / 200.0);
                        for k in 0..=g + 1 {
                            let _ = p.deriv(u, k);
                        }
                        for piece in 0..p.piece_count() + 1 {
                            let _ = p.piece_deriv(piece, u, 1);
                        }
                        let _ = p.eval(u);
                    }
                }
            }
        }
        assert!(accepted >= 20, "{accepted}");
    }

    #[test]
    fn falling_factorials() {
        assert_eq!(falling_factorial(3, 0), 1);
        assert_eq!(falling_factorial(3, 2), 6);
        assert_eq!(falling_factorial(7, 7), 5040);
        assert_eq!(falling_factorial(5, 3), 60);
    }
}
