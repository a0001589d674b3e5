//! Knot vectors: validation, generators, multiplicity and knot-span search.
//!
//! Notation (as Piegl & Tiller, *The NURBS Book*, 2nd ed., §2.2, with `g` for their `p`):
//! degree `g`, `K` de Boor points, a
//! knot vector `U = (u_0, …, u_{m−1})` with `m = K + g + 1` entries for an open B-spline. The
//! curve is defined on the domain `[u_g, u_K]`; the knot interval `[u_i, u_{i+1})` is a
//! *span* and only the `g + 1` de Boor points `d_{i−g}, …, d_i` act on it. A knot repeated `μ`
//! times has *multiplicity* `μ`: the curve is `C^{g−μ}` there, `μ = g + 1` (a jump) is only
//! allowed at the two ends of the knot vector (clamped, "open" B-splines).

use heapless::Vec;

use crate::error::Error;
use crate::scalar::Scalar;

/// The largest degree `g` of [`BSpline`](crate::BSpline), [`Nurbs`](crate::Nurbs) and
/// [`KnotVector`]: 7 (order 8).
///
/// Evaluation works on the `g + 1` de Boor points of one knot span in a stack array of
/// `BSPLINE_MAX_DEGREE + 1` entries, so the bound keeps every evaluator allocation-free and
/// constant in stack size. Motion control rarely needs more than degree 5 (C⁴, continuous
/// snap); 7 leaves room for C⁶. Constructors return [`Error::DegreeTooHigh`] above it.
///
/// ```
/// use strak_curves::{BSPLINE_MAX_DEGREE, Error, KnotVector};
/// assert_eq!(BSPLINE_MAX_DEGREE, 7);
/// let e = KnotVector::<f64, 32>::clamped_uniform(8, 9, 0.0, 1.0).unwrap_err();
/// assert_eq!(e, Error::DegreeTooHigh { max: 7, found: 8 });
/// ```
pub const BSPLINE_MAX_DEGREE: usize = 7;

/// Length of the local arrays that hold the `g + 1` values of one knot span.
pub(crate) const LOCAL: usize = BSPLINE_MAX_DEGREE + 1;

/// `Err(DegreeTooHigh)` above [`BSPLINE_MAX_DEGREE`].
pub(crate) fn check_degree(degree: usize) -> Result<(), Error> {
    if degree > BSPLINE_MAX_DEGREE {
        Err(Error::DegreeTooHigh {
            max: BSPLINE_MAX_DEGREE,
            found: degree,
        })
    } else {
        Ok(())
    }
}

/// `num / den`, or zero when `den` is not positive: the `0/0 := 0` convention of the Cox–de
/// Boor recursion (Piegl & Tiller §2.2). Every caller passes a knot difference that is positive by
/// construction; the guard makes the absence of a division by zero evident.
#[inline]
pub(crate) fn ratio<S: Scalar>(num: S, den: S) -> S {
    if den > S::ZERO { num / den } else { S::ZERO }
}

/// A validated knot vector `u_0 ≤ u_1 ≤ … ≤ u_{m−1}` for B-splines of a given degree `g`,
/// stored in a fixed capacity of `M` knots.
///
/// Invariants (checked by every constructor):
/// - `g ≤` [`BSPLINE_MAX_DEGREE`], `m ≥ 2g + 2` (at least `g + 1` de Boor points);
/// - every knot finite and within the scalar's range ([`Scalar::fits`]), as is `u_{m−1} − u_0`;
/// - non-decreasing;
/// - multiplicity at most `g` for an inner run of equal knots and at most `g + 1` for a run
///   that starts at `u_0` or ends at `u_{m−1}` (for `g = 0`, inner knots may be simple);
/// - the domain `[u_g, u_K]`, `K = m − g − 1`, is not empty.
///
/// ```
/// use strak_curves::KnotVector;
///
/// // g = 3, n = 4 segments, K = 7, m = 11, U = [0,0,0,0,1,2,3,4,4,4,4]
/// let kv = KnotVector::<f64, 16>::new(3, &[0., 0., 0., 0., 1., 2., 3., 4., 4., 4., 4.]).unwrap();
/// assert_eq!(kv.control_point_count(), 7);
/// assert_eq!(kv.domain(), (0.0, 4.0));
/// assert_eq!(kv.multiplicity(4.0), 4);
/// assert_eq!(kv.span(2.5), 5); // u_5 = 2 ≤ 2.5 < u_6 = 3
/// assert_eq!(kv.span(4.0), 6); // the right end uses the last non-empty span
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct KnotVector<S: Scalar, const M: usize> {
    knots: Vec<S, M>,
    degree: usize,
    /// The last non-empty span of the domain (used at the right end).
    last_span: usize,
    /// Number of non-empty spans in the domain.
    pieces: usize,
    /// `(K − g) / (u_K − u_g)` when the domain spans are (nearly) equal: O(1) span guess.
    inv_spacing: Option<S>,
    /// Highest order of basis-function derivatives that fits the scalar's range.
    basis_orders: usize,
}

impl<S: Scalar, const M: usize> KnotVector<S, M> {
    /// Validates `knots` as a knot vector for degree `degree` (see the type's invariants).
    ///
    /// # Errors
    /// [`Error::DegreeTooHigh`], [`Error::KnotCount`] (fewer than `2g + 2` knots),
    /// [`Error::CapacityExceeded`] (more than `M`), [`Error::NonFinite`],
    /// [`Error::OutOfRange`], [`Error::KnotsUnsorted`], [`Error::KnotMultiplicity`],
    /// [`Error::ZeroLengthInterval`] (empty domain, `index = g`).
    ///
    /// ```
    /// use strak_curves::{Error, KnotVector};
    /// let kv = KnotVector::<f32, 8>::new(1, &[0.0, 0.0, 0.5, 1.0, 1.0]).unwrap();
    /// assert_eq!(kv.domain(), (0.0, 1.0));
    /// let e = KnotVector::<f32, 8>::new(1, &[0.0, 0.0, 0.5, 0.25, 1.0]).unwrap_err();
    /// assert_eq!(e, Error::KnotsUnsorted { index: 3 });
    /// ```
    pub fn new(degree: usize, knots: &[S]) -> Result<Self, Error> {
        check_degree(degree)?;
        let m = knots.len();
        let min = 2 * degree + 2;
        if m < min {
            return Err(Error::KnotCount {
                expected: min,
                found: m,
            });
        }
        let v = Vec::from_slice(knots).map_err(|_| Error::CapacityExceeded {
            capacity: M,
            required: m,
        })?;
        Self::from_vec(degree, v)
    }

    /// The clamped (open, nonperiodic) uniform knot vector for `count` de Boor points over
    /// `[u0, u1]`: `g + 1` copies of `u0`, `count − g − 1` equally spaced inner knots, `g + 1`
    /// copies of `u1`. The curve interpolates its first and last de Boor point.
    ///
    /// # Errors
    /// [`Error::DegreeTooHigh`], [`Error::TooFewPoints`] (`count ≤ g`),
    /// [`Error::CapacityExceeded`] (`count + g + 1 > M`), [`Error::NonFinite`],
    /// [`Error::ZeroLengthInterval`] (`u0 == u1`), [`Error::KnotsUnsorted`] (`u1 < u0`),
    /// [`Error::OutOfRange`].
    ///
    /// ```
    /// use strak_curves::KnotVector;
    /// let kv = KnotVector::<f64, 16>::clamped_uniform(2, 5, 0.0, 3.0).unwrap();
    /// assert_eq!(kv.as_slice(), &[0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0]);
    /// ```
    pub fn clamped_uniform(degree: usize, count: usize, u0: S, u1: S) -> Result<Self, Error> {
        let m = count + degree + 1;
        Self::generate(degree, count, m, u0, u1, |j| {
            if j <= degree {
                Gen::Start
            } else if j >= count {
                Gen::End
            } else {
                Gen::At(j as f64 - degree as f64, (count - degree) as f64)
            }
        })
    }

    /// The unclamped uniform knot vector for `count` de Boor points whose domain
    /// `[u_g, u_K]` is `[u0, u1]`: `u_j = u0 + (j − g)·h` with `h = (u1 − u0)/(count − g)`.
    /// The curve does not interpolate its end points.
    ///
    /// # Errors
    /// As [`KnotVector::clamped_uniform`].
    ///
    /// ```
    /// use strak_curves::KnotVector;
    /// let kv = KnotVector::<f64, 16>::uniform(2, 4, 0.0, 2.0).unwrap();
    /// assert_eq!(kv.as_slice(), &[-2.0, -1.0, 0.0, 1.0, 2.0, 3.0, 4.0]);
    /// assert_eq!(kv.domain(), (0.0, 2.0));
    /// ```
    pub fn uniform(degree: usize, count: usize, u0: S, u1: S) -> Result<Self, Error> {
        let m = count + degree + 1;
        Self::generate(degree, count, m, u0, u1, |j| {
            if j == degree {
                Gen::Start
            } else if j == count {
                Gen::End
            } else {
                Gen::At(j as f64 - degree as f64, (count - degree) as f64)
            }
        })
    }

    /// The periodically extended uniform knot vector of a closed B-spline with `count`
    /// de Boor points (one segment per point) over one period `[u0, u1]`:
    /// `count + 2g + 1` knots `u_j = u0 + (j − g)·h`, `h = (u1 − u0)/count`. It belongs to the
    /// open B-spline with `count + g` points whose first `g` points repeat the last `g`
    /// (see [`BSpline::closed`](crate::BSpline::closed)).
    ///
    /// # Errors
    /// As [`KnotVector::clamped_uniform`] (capacity: `count + 2g + 1 > M`).
    ///
    /// ```
    /// use strak_curves::KnotVector;
    /// let kv = KnotVector::<f64, 16>::periodic(2, 4, 0.0, 1.0).unwrap();
    /// assert_eq!(kv.as_slice(), &[-0.5, -0.25, 0.0, 0.25, 0.5, 0.75, 1.0, 1.25, 1.5]);
    /// assert_eq!(kv.control_point_count(), 6);
    /// assert_eq!(kv.domain(), (0.0, 1.0));
    /// ```
    pub fn periodic(degree: usize, count: usize, u0: S, u1: S) -> Result<Self, Error> {
        let m = count + 2 * degree + 1;
        Self::generate(degree, count, m, u0, u1, |j| {
            if j == degree {
                Gen::Start
            } else if j == count + degree {
                Gen::End
            } else {
                Gen::At(j as f64 - degree as f64, count as f64)
            }
        })
    }

    fn generate(
        degree: usize,
        count: usize,
        m: usize,
        u0: S,
        u1: S,
        rule: impl Fn(usize) -> Gen,
    ) -> Result<Self, Error> {
        check_degree(degree)?;
        if count < degree + 1 {
            return Err(Error::TooFewPoints {
                required: degree + 1,
                found: count,
            });
        }
        if m > M {
            return Err(Error::CapacityExceeded {
                capacity: M,
                required: m,
            });
        }
        if !u0.is_finite() || !u1.is_finite() {
            return Err(Error::NonFinite);
        }
        if u1 == u0 {
            return Err(Error::ZeroLengthInterval { index: degree });
        }
        if u1 < u0 {
            return Err(Error::KnotsUnsorted {
                index: m - degree - 1,
            });
        }
        let (a, b) = (u0.to_f64(), u1.to_f64());
        let mut v: Vec<S, M> = Vec::new();
        for j in 0..m {
            let k = match rule(j) {
                Gen::Start => u0,
                Gen::End => u1,
                Gen::At(num, den) => {
                    S::from_f64(a + (b - a) * num / den).ok_or(Error::OutOfRange)?
                }
            };
            v.push(k).map_err(|_| Error::CapacityExceeded {
                capacity: M,
                required: m,
            })?;
        }
        Self::from_vec(degree, v)
    }

    fn from_vec(degree: usize, knots: Vec<S, M>) -> Result<Self, Error> {
        validate(degree, &knots)?;
        let m = knots.len();
        let count = m - degree - 1;
        let mut kv = KnotVector {
            knots,
            degree,
            last_span: degree,
            pieces: 0,
            inv_spacing: None,
            basis_orders: degree,
        };
        for s in degree..count {
            if kv.knot(s) < kv.knot(s + 1) {
                kv.last_span = s;
                kv.pieces += 1;
            }
        }
        kv.inv_spacing = kv.detect_uniform();
        kv.basis_orders = super::basis::basis_derivative_orders(&kv);
        Ok(kv)
    }

    /// `Some(1/h)` when all domain spans have (nearly) the same length `h`.
    fn detect_uniform(&self) -> Option<S> {
        let g = self.degree;
        let n = self.control_point_count() - g;
        let (lo, hi) = (self.knot(g).to_f64(), self.knot(g + n).to_f64());
        let h = (hi - lo) / n as f64;
        for j in 0..=n {
            let t = self.knot(g + j).to_f64();
            if (t - (lo + j as f64 * h)).abs() > 0.25 * h {
                return None;
            }
        }
        if !S::fits(n as f64 + 2.0) {
            return None;
        }
        S::from_f64(n as f64 / (hi - lo))
    }

    /// Knot `i` (provably in range at every call site; zero otherwise, never a panic).
    #[inline]
    pub(crate) fn knot(&self, i: usize) -> S {
        self.knots.get(i).copied().unwrap_or(S::ZERO)
    }

    /// The degree `g` this knot vector was validated for.
    #[inline]
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The knots `u_0, …, u_{m−1}`.
    #[inline]
    pub fn as_slice(&self) -> &[S] {
        &self.knots
    }

    /// The number `K = m − g − 1` of de Boor points a B-spline on this knot vector has.
    #[inline]
    pub fn control_point_count(&self) -> usize {
        self.knots.len() - self.degree - 1
    }

    /// The parameter domain `[u_g, u_K]` of the B-spline.
    #[inline]
    pub fn domain(&self) -> (S, S) {
        (
            self.knot(self.degree),
            self.knot(self.control_point_count()),
        )
    }

    /// `true` when all spans of the domain have (nearly) equal length; span search is then
    /// O(1) (a guess from `(u − u_g)/h`, verified against the knots).
    #[inline]
    pub fn is_uniform(&self) -> bool {
        self.inv_spacing.is_some()
    }

    /// The multiplicity of the value `u`: how many knots equal it (0 if `u` is no knot).
    ///
    /// ```
    /// use strak_curves::KnotVector;
    /// let kv = KnotVector::<f64, 16>::new(2, &[0., 0., 0., 1., 1., 2., 2., 2.]).unwrap();
    /// assert_eq!(kv.multiplicity(1.0), 2);
    /// assert_eq!(kv.multiplicity(0.5), 0);
    /// ```
    pub fn multiplicity(&self, u: S) -> usize {
        self.knots.iter().filter(|&&k| k == u).count()
    }

    /// The number of non-empty knot spans in the domain: the pieces of the curve.
    #[inline]
    pub fn piece_count(&self) -> usize {
        self.pieces
    }

    /// The knot index `s` of piece `i` (the `i`-th non-empty span `[u_s, u_{s+1})` of the
    /// domain); the last piece for `i ≥ piece_count()`. O(1) when no interior knot is
    /// repeated (every span of the domain a piece), a scan of the knots otherwise.
    pub fn piece_span(&self, i: usize) -> usize {
        let g = self.degree;
        if self.pieces == self.control_point_count() - g {
            return if i < self.pieces {
                g + i
            } else {
                self.last_span
            };
        }
        let mut seen = 0;
        for s in g..self.control_point_count() {
            if self.knot(s) < self.knot(s + 1) {
                if seen == i {
                    return s;
                }
                seen += 1;
            }
        }
        self.last_span
    }

    /// The highest order `k ≤ g` of basis-function derivatives that
    /// [`bspline_basis_derivs`](crate::bspline_basis_derivs) computes: `g` unless the bound
    /// `|N^{(k)}| ≲ g!/(g−k)!·(2/Δu)^k` of short spans exceeds the scalar's range
    /// (fixed-point with very short knot spans).
    #[inline]
    pub fn max_basis_derivative(&self) -> usize {
        self.basis_orders
    }

    /// The knot span `s` of `u` (clamped to the domain): `g ≤ s ≤ K − 1` with
    /// `u_s ≤ u < u_{s+1}`, so `u_s < u_{s+1}`. At the right end `u = u_K` it is the last
    /// non-empty span. O(1) for uniform knots, a binary search otherwise.
    pub fn span(&self, u: S) -> usize {
        let g = self.degree;
        let k = self.control_point_count();
        let (lo, hi) = self.domain();
        let u = u.clamp_to(lo, hi);
        if u >= hi {
            return self.last_span;
        }
        if let Some(inv) = self.inv_spacing {
            // `as` saturates (and maps NaN to 0): no overflow; the guess is verified below.
            let guess = ((u - lo) * inv).to_f64() as usize;
            let s = g.saturating_add(guess).min(k - 1);
            for c in [s, s.saturating_sub(1).max(g), (s + 1).min(k - 1)] {
                if self.knot(c) <= u && u < self.knot(c + 1) {
                    return c;
                }
            }
        }
        self.binary_span(u)
    }

    /// The span of `u` when `hint` is likely the span or the one before it (monotone
    /// queries, e.g. a sampler walking forward): checks `hint` and `hint + 1` first, then
    /// falls back to [`KnotVector::span`]. Always returns the same as `span(u)`.
    ///
    /// ```
    /// use strak_curves::KnotVector;
    /// let kv = KnotVector::<f64, 16>::new(2, &[0., 0., 0., 0.1, 0.7, 1., 1., 1.]).unwrap();
    /// let mut s = kv.span(0.0);
    /// for i in 0..=100 {
    ///     let u = f64::from(i) / 100.0;
    ///     s = kv.span_with_hint(u, s);
    ///     assert_eq!(s, kv.span(u));
    /// }
    /// ```
    pub fn span_with_hint(&self, u: S, hint: usize) -> usize {
        let g = self.degree;
        let k = self.control_point_count();
        let (lo, hi) = self.domain();
        let u = u.clamp_to(lo, hi);
        if u >= hi {
            return self.last_span;
        }
        let h = hint.clamp(g, k - 1);
        for c in [h, (h + 1).min(k - 1)] {
            if self.knot(c) <= u && u < self.knot(c + 1) {
                return c;
            }
        }
        self.span(u)
    }

    /// Binary search for `u_s ≤ u < u_{s+1}`, `g ≤ s < K`, given `u_g ≤ u < u_K`.
    fn binary_span(&self, u: S) -> usize {
        let mut lo = self.degree;
        let mut hi = self.control_point_count();
        while hi - lo > 1 {
            let mid = lo + (hi - lo) / 2;
            if u < self.knot(mid) {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        lo
    }
}

/// How a generator fills knot `j`.
enum Gen {
    Start,
    End,
    /// `u0 + (u1 − u0)·num/den`, computed in f64.
    At(f64, f64),
}

/// The checks of [`KnotVector::new`] after count and capacity.
pub(crate) fn validate<S: Scalar>(degree: usize, knots: &[S]) -> Result<(), Error> {
    check_values(knots)?;
    let m = knots.len();
    // Runs of equal knots.
    let mut a = 0;
    while a < m {
        let mut b = a + 1;
        while b < m && knots.get(b) == knots.get(a) {
            b += 1;
        }
        let at_end = a == 0 || b == m;
        let limit = if at_end { degree + 1 } else { degree.max(1) };
        if b - a > limit {
            return Err(Error::KnotMultiplicity { index: a });
        }
        a = b;
    }
    let count = m - degree - 1;
    match (knots.get(degree), knots.get(count)) {
        (Some(lo), Some(hi)) if lo < hi => Ok(()),
        _ => Err(Error::ZeroLengthInterval { index: degree }),
    }
}

/// Finite, within range (values and total span), non-decreasing.
pub(crate) fn check_values<S: Scalar>(knots: &[S]) -> Result<(), Error> {
    if knots.iter().any(|k| !k.is_finite()) {
        return Err(Error::NonFinite);
    }
    if knots.iter().any(|k| !S::fits(k.to_f64())) {
        return Err(Error::OutOfRange);
    }
    for (i, w) in knots.windows(2).enumerate() {
        if let [x, y] = w
            && y < x
        {
            return Err(Error::KnotsUnsorted { index: i + 1 });
        }
    }
    if let (Some(first), Some(last)) = (knots.first(), knots.last())
        && !S::fits(last.to_f64() - first.to_f64())
    {
        return Err(Error::OutOfRange);
    }
    Ok(())
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;
    use crate::scalar::{I16F16, I32F32};

    type Kv = KnotVector<f64, 32>;

    #[test]
    fn clamped_cubic_examples() {
        // g = 3, n = 4, K = 7, m = 11, U = [0,0,0,0,1,2,3,4,4,4,4]
        let kv = Kv::clamped_uniform(3, 7, 0.0, 4.0).unwrap();
        assert_eq!(kv.as_slice(), &[0., 0., 0., 0., 1., 2., 3., 4., 4., 4., 4.]);
        assert_eq!(kv.control_point_count(), 7);
        assert_eq!(kv.piece_count(), 4);
        assert_eq!(kv.domain(), (0.0, 4.0));
        assert!(kv.is_uniform());
        // g = 3, n = 5, m = 12, K = 8, U = 000012345555
        let kv = Kv::clamped_uniform(3, 8, 0.0, 5.0).unwrap();
        assert_eq!(
            kv.as_slice(),
            &[0., 0., 0., 0., 1., 2., 3., 4., 5., 5., 5., 5.]
        );
        // Order 4 with 9 points: T = (0,0,0,0,1,2,3,4,5,6,6,6,6)
        let kv = Kv::clamped_uniform(3, 9, 0.0, 6.0).unwrap();
        assert_eq!(
            kv.as_slice(),
            &[0., 0., 0., 0., 1., 2., 3., 4., 5., 6., 6., 6., 6.]
        );
    }

    #[test]
    fn generators() {
        let kv = Kv::uniform(3, 5, 0.0, 2.0).unwrap();
        assert_eq!(kv.as_slice(), &[-3., -2., -1., 0., 1., 2., 3., 4., 5.]);
        assert_eq!(kv.domain(), (0.0, 2.0));
        let kv = Kv::periodic(3, 4, 0.0, 4.0).unwrap();
        assert_eq!(
            kv.as_slice(),
            &[-3., -2., -1., 0., 1., 2., 3., 4., 5., 6., 7.]
        );
        assert_eq!(kv.control_point_count(), 7);
        assert_eq!(kv.domain(), (0.0, 4.0));
        let kv = KnotVector::<I16F16, 16>::clamped_uniform(
            2,
            5,
            I16F16::from_num(0),
            I16F16::from_num(1),
        )
        .unwrap();
        assert_eq!(
            kv.as_slice()[3].to_f64(),
            1.0 / 3.0_f64 - (1.0 / 3.0_f64) % (1.0 / 65536.0)
        );
        assert!(kv.is_uniform());
    }

    #[test]
    fn multiplicity_and_pieces() {
        let kv = Kv::new(3, &[0., 0., 0., 0., 1., 1., 1., 2., 2., 2., 2.]).unwrap();
        assert_eq!(kv.multiplicity(0.0), 4);
        assert_eq!(kv.multiplicity(1.0), 3);
        assert_eq!(kv.multiplicity(1.5), 0);
        assert_eq!(kv.piece_count(), 2);
        assert_eq!(kv.piece_span(0), 3);
        assert_eq!(kv.piece_span(1), 6);
        assert_eq!(kv.piece_span(9), 6);
        assert!(!kv.is_uniform());
    }

    /// `piece_span` (O(1) without repeated interior knots) against the definition: the
    /// `i`-th span `[u_s, u_{s+1})` with `u_s < u_{s+1}`, with and without repeated knots.
    #[test]
    fn piece_spans_are_the_non_empty_spans() {
        let knots: [&[f64]; 3] = [
            &[0., 0., 0., 0., 1., 2.5, 3., 7., 7., 7., 7.],
            &[0., 0., 0., 1., 2., 2., 3., 4., 4., 4.],
            &[0., 0., 0., 0., 1., 1., 2., 3., 3., 3., 3.],
        ];
        for (g, k) in [3, 2, 3].into_iter().zip(knots) {
            let kv = Kv::new(g, k).unwrap();
            let mut spans = (g..kv.control_point_count()).filter(|&s| k[s] < k[s + 1]);
            let mut count = 0;
            let mut last = 0;
            for (i, s) in spans.by_ref().enumerate() {
                assert_eq!(kv.piece_span(i), s, "degree {g}, piece {i}");
                (count, last) = (i + 1, s);
            }
            assert_eq!(kv.piece_count(), count);
            assert_eq!(kv.piece_span(count), last);
        }
    }

    #[test]
    fn span_search_all_paths_agree() {
        let knots = [0., 0., 0., 0.5, 0.5, 1.25, 2., 3., 3., 3.];
        let kv = Kv::new(2, &knots).unwrap();
        assert!(!kv.is_uniform());
        let uni = Kv::uniform(2, 9, 0.0, 3.0).unwrap();
        assert!(uni.is_uniform());
        for kv in [&kv, &uni] {
            let (lo, hi) = kv.domain();
            let mut hint = 0;
            for i in 0..=3000 {
                let u = lo + (hi - lo) * f64::from(i) / 3000.0;
                let s = kv.span(u);
                assert!(
                    kv.knot(s) <= u && (u < kv.knot(s + 1) || u == hi),
                    "u = {u}"
                );
                assert!(kv.knot(s) < kv.knot(s + 1));
                if u < hi {
                    assert_eq!(s, kv.binary_span(u));
                } else {
                    assert_eq!(s, kv.last_span);
                }
                hint = kv.span_with_hint(u, hint);
                assert_eq!(hint, s);
            }
        }
        // Right end: last non-empty span; outside: clamped.
        assert_eq!(kv.span(3.0), 6);
        assert_eq!(kv.span(10.0), 6);
        assert_eq!(kv.span(-1.0), 2);
        assert_eq!(kv.span(f64::NAN), 2);
        // Inner double knot: the span starting there.
        assert_eq!(kv.span(0.5), 4);
        assert_eq!(kv.span(0.4999), 2);
    }

    #[test]
    fn uniform_span_in_fixed_point() {
        let kv = KnotVector::<I16F16, 64>::clamped_uniform(
            3,
            40,
            I16F16::from_num(-3),
            I16F16::from_num(7),
        )
        .unwrap();
        assert!(kv.is_uniform());
        for i in 0..=2000 {
            let u = I16F16::from_num(-3) + I16F16::from_num(10) * I16F16::from_num(i) / 2000;
            let s = kv.span(u);
            if u < kv.domain().1 {
                assert_eq!(s, kv.binary_span(u));
            }
            assert!(kv.knot(s) <= u);
        }
    }

    #[test]
    fn error_degree_too_high() {
        assert_eq!(
            Kv::new(8, &[0.0; 18]).unwrap_err(),
            Error::DegreeTooHigh { max: 7, found: 8 }
        );
    }

    #[test]
    fn error_knot_count() {
        assert_eq!(
            Kv::new(2, &[0., 0., 0., 1., 1.]).unwrap_err(),
            Error::KnotCount {
                expected: 6,
                found: 5
            }
        );
    }

    #[test]
    fn error_capacity() {
        assert_eq!(
            KnotVector::<f64, 4>::new(1, &[0., 0., 1., 2., 2.]).unwrap_err(),
            Error::CapacityExceeded {
                capacity: 4,
                required: 5
            }
        );
        assert_eq!(
            KnotVector::<f64, 6>::clamped_uniform(2, 4, 0.0, 1.0).unwrap_err(),
            Error::CapacityExceeded {
                capacity: 6,
                required: 7
            }
        );
    }

    #[test]
    fn error_too_few_points() {
        assert_eq!(
            Kv::clamped_uniform(3, 3, 0.0, 1.0).unwrap_err(),
            Error::TooFewPoints {
                required: 4,
                found: 3
            }
        );
    }

    #[test]
    fn error_non_finite() {
        assert_eq!(
            Kv::new(1, &[0., 0., f64::NAN, 1., 1.]).unwrap_err(),
            Error::NonFinite
        );
        assert_eq!(
            Kv::uniform(1, 3, 0.0, f64::INFINITY).unwrap_err(),
            Error::NonFinite
        );
    }

    #[test]
    fn error_unsorted() {
        assert_eq!(
            Kv::new(2, &[0., 0., 0., 2., 1., 3., 3., 3.]).unwrap_err(),
            Error::KnotsUnsorted { index: 4 }
        );
        assert_eq!(
            Kv::clamped_uniform(2, 4, 1.0, 0.0).unwrap_err(),
            Error::KnotsUnsorted { index: 4 }
        );
    }

    #[test]
    fn error_multiplicity() {
        // Inner knot of multiplicity g + 1 = 3 (a jump inside the domain).
        assert_eq!(
            Kv::new(2, &[0., 0., 0., 1., 1., 1., 2., 2., 2.]).unwrap_err(),
            Error::KnotMultiplicity { index: 3 }
        );
        // End multiplicity g + 2.
        assert_eq!(
            Kv::new(2, &[0., 0., 0., 0., 1., 2., 2., 2.]).unwrap_err(),
            Error::KnotMultiplicity { index: 0 }
        );
        // Multiplicity g inside and g + 1 at the ends is fine.
        assert!(Kv::new(2, &[0., 0., 0., 1., 1., 2., 2., 2.]).is_ok());
        // Degree 0: simple inner knots are allowed.
        assert!(Kv::new(0, &[0., 1., 2., 3.]).is_ok());
    }

    #[test]
    fn error_zero_length_domain() {
        // g = 3, K = 4: domain [u_3, u_4] with u_3 = u_4 (inner multiplicity 2 ≤ g).
        assert_eq!(
            Kv::new(3, &[0., 1., 2., 5., 5., 6., 7., 8.]).unwrap_err(),
            Error::ZeroLengthInterval { index: 3 }
        );
        assert_eq!(
            Kv::clamped_uniform(2, 4, 1.0, 1.0).unwrap_err(),
            Error::ZeroLengthInterval { index: 2 }
        );
    }

    #[test]
    fn error_out_of_range() {
        let big = I16F16::from_num(20000);
        let z = I16F16::ZERO;
        assert_eq!(
            KnotVector::<I16F16, 8>::new(1, &[z, z, big, big]).unwrap_err(),
            Error::OutOfRange
        );
        // Values fit, but the total span u_{m−1} − u_0 does not.
        let a = I16F16::from_num(-10000);
        let b = I16F16::from_num(10000);
        assert_eq!(
            KnotVector::<I16F16, 8>::new(1, &[a, a, b, b]).unwrap_err(),
            Error::OutOfRange
        );
        assert!(
            KnotVector::<I32F32, 8>::new(
                1,
                &[
                    I32F32::from_num(-10000),
                    I32F32::from_num(-10000),
                    I32F32::from_num(10000),
                    I32F32::from_num(10000)
                ]
            )
            .is_ok()
        );
    }
}
