//! The B-spline curve `c(u) = Σ d_i N_i^g(u)` with de Boor points `d_i` (Piegl & Tiller,
//! *The NURBS Book*, 2nd ed., §3.2), evaluated with de Boor's algorithm (de Boor, *A Practical
//! Guide to Splines*, ch. X "The Stable Evaluation of B-splines and Splines").

use heapless::Vec;

use super::derivative::{check_range, derive_local};
use super::knots::{BSPLINE_MAX_DEGREE, KnotVector, LOCAL, check_degree, check_values, ratio};
use crate::curve::{ParamCurve, ParamCurveDeriv, PieceDeriv};
use crate::error::Error;
use crate::point::Point;
use crate::scalar::Scalar;

/// A B-spline curve of degree `g ≤` [`BSPLINE_MAX_DEGREE`] with up to `N` de Boor points and
/// up to `M` knots (Piegl & Tiller §3.2; some texts use the order `k = g + 1`).
///
/// `c(u) = Σ_{i=0}^{K−1} d_i N_i^g(u)` on the domain `[u_g, u_K]` of a knot vector with
/// `m = K + g + 1` knots. Each non-empty knot span is one polynomial piece; at a knot of
/// multiplicity `μ` the curve is `C^{g−μ}`, and a knot of multiplicity `g` makes it pass
/// through a de Boor point. The curve lies in the union of the convex hulls of `g + 1`
/// consecutive de Boor points, is affine invariant, and moving `d_i` changes it only on
/// `[u_i, u_{i+g+1})` (local control; Piegl & Tiller §3.2).
///
/// Evaluation is de Boor's algorithm (convex combinations only, safe in fixed-point):
/// O(g²) after an O(log K) span search (O(1) for uniform knots). Parameters outside the
/// domain are clamped to it; at an inner knot the span starting there is used, at the right
/// end the last non-empty span.
///
/// Derivatives use the de Boor points of the derivative curve,
/// `Q_i = g·(d_{i+1} − d_i)/(u_{i+g+1} − u_{i+1})` (applied `k` times), computed locally for
/// the span of `u` (no extra storage), then de Boor's algorithm of degree `g − k`.
///
/// **Fixed-point range.** The constructors check, in f64, every value evaluation can produce:
/// the knots and `u_{m−1} − u_0`, the de Boor points, and for every non-empty span and every
/// order `1 ≤ k ≤ g` each scaled difference `(g − k + 1)·(Q_{i+1} − Q_i)` and each derivative
/// point (which carries the `1/Δu^k` of short spans); all must satisfy [`Scalar::fits`],
/// otherwise [`Error::OutOfRange`]. Every divisor is a knot difference over a non-empty span,
/// so it is positive. De Boor's convex combinations add nothing to the bound.
///
/// **Open** curves ([`BSpline::new`], [`BSpline::clamped_uniform`],
/// [`BSpline::from_knot_vector`]) use `K ≤ N` points and `K + g + 1 ≤ M` knots. A clamped
/// knot vector (end multiplicity `g + 1`) makes the curve interpolate `d_0` and `d_{K−1}`.
///
/// **Closed** curves ([`BSpline::closed`]: `K` segments for `K` points) with `K` de Boor points are
/// stored as the open B-spline over the periodically extended knot vector with the last `g`
/// points repeated in front: they need `N ≥ K + g` and `M ≥ K + 2g + 1`, and
/// [`BSpline::control_points`] / [`BSpline::knots`] return that extended representation.
///
/// ```
/// use strak_curves::{BSpline, ParamCurve, ParamCurveDeriv};
///
/// let d = [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]];
/// let c = BSpline::<[f64; 2], 8, 16>::clamped_uniform(2, &d, 0.0, 1.0).unwrap();
/// assert_eq!(c.eval(0.0), [0.0, 0.0]);
/// assert_eq!(c.eval(1.0), [4.0, 0.0]);
/// assert_eq!(c.eval(0.5), [2.0, 2.0]);
/// // End tangent g/(u_{g+1} − u_1)·(d_1 − d_0) = 2/0.5·(1, 2)
/// assert_eq!(c.deriv(0.0, 1), [4.0, 8.0]);
/// assert_eq!(c.piece_count(), 2);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct BSpline<P: Point, const N: usize, const M: usize> {
    points: Vec<P, N>,
    knots: KnotVector<P::Scalar, M>,
    closed: bool,
}

impl<P: Point, const N: usize, const M: usize> BSpline<P, N, M> {
    /// An open B-spline of degree `degree` with the de Boor points `points` (`K` of them) and
    /// the knot vector `knots` (`K + g + 1` knots, clamped or not).
    ///
    /// # Errors
    /// [`Error::DegreeTooHigh`], [`Error::TooFewPoints`] (`K ≤ g`),
    /// [`Error::CapacityExceeded`] (`K > N` or `K + g + 1 > M`), [`Error::KnotCount`],
    /// [`Error::NonFinite`], [`Error::KnotsUnsorted`], [`Error::KnotMultiplicity`],
    /// [`Error::ZeroLengthInterval`], [`Error::OutOfRange`] (see the module's range rule).
    ///
    /// ```
    /// use strak_curves::{BSpline, ParamCurve};
    ///
    /// // g = 3, K = 7, U = [0,0,0,0,1,2,3,4,4,4,4]
    /// let d = [[0.0], [1.0], [2.0], [3.0], [4.0], [5.0], [6.0]];
    /// let t = [0., 0., 0., 0., 1., 2., 3., 4., 4., 4., 4.];
    /// let c = BSpline::<[f64; 1], 8, 12>::new(3, &d, &t).unwrap();
    /// assert_eq!(c.domain(), (0.0, 4.0));
    /// assert_eq!(c.eval(4.0), [6.0]);
    /// ```
    pub fn new(degree: usize, points: &[P], knots: &[P::Scalar]) -> Result<Self, Error> {
        check_degree(degree)?;
        let k = points.len();
        check_counts::<N>(degree, k, k)?;
        let m = k + degree + 1;
        if knots.len() != m {
            return Err(Error::KnotCount {
                expected: m,
                found: knots.len(),
            });
        }
        if m > M {
            return Err(Error::CapacityExceeded {
                capacity: M,
                required: m,
            });
        }
        let kv = KnotVector::new(degree, knots)?;
        Self::from_knot_vector(points, kv)
    }

    /// An open B-spline on a validated [`KnotVector`] (its degree is the curve's degree).
    ///
    /// # Errors
    /// [`Error::TooFewPoints`], [`Error::KnotCount`] (`points.len()` is not
    /// `knots.control_point_count()`), [`Error::CapacityExceeded`], [`Error::NonFinite`],
    /// [`Error::OutOfRange`].
    ///
    /// ```
    /// use strak_curves::{BSpline, KnotVector, ParamCurve};
    ///
    /// let kv = KnotVector::<f64, 16>::uniform(3, 6, 0.0, 3.0).unwrap();
    /// let d = [[0.0], [1.0], [2.0], [3.0], [4.0], [5.0]];
    /// let c = BSpline::<[f64; 1], 8, 16>::from_knot_vector(&d, kv).unwrap();
    /// // A uniform cubic reproduces linear data: c(u) = u + 1 on [0, 3].
    /// assert!((c.eval(1.7)[0] - 2.7).abs() < 1e-14);
    /// ```
    pub fn from_knot_vector(points: &[P], knots: KnotVector<P::Scalar, M>) -> Result<Self, Error> {
        let g = knots.degree();
        let k = points.len();
        check_counts::<N>(g, k, k)?;
        let expected = knots.control_point_count();
        if k != expected {
            return Err(Error::KnotCount {
                expected: k + g + 1,
                found: knots.as_slice().len(),
            });
        }
        if points.iter().any(|p| !p.is_finite()) {
            return Err(Error::NonFinite);
        }
        check_range(points, &knots)?;
        let points = Vec::from_slice(points).map_err(|_| Error::CapacityExceeded {
            capacity: N,
            required: k,
        })?;
        Ok(BSpline {
            points,
            knots,
            closed: false,
        })
    }

    /// An open B-spline with the clamped uniform knot vector over `[u0, u1]`
    /// ([`KnotVector::clamped_uniform`]): it starts at the first and ends at the last de Boor
    /// point, tangent to the control polygon there.
    ///
    /// # Errors
    /// As [`BSpline::new`]; `u0 == u1` gives [`Error::ZeroLengthInterval`], `u1 < u0`
    /// [`Error::KnotsUnsorted`].
    ///
    /// ```
    /// use strak_curves::{BSpline, I16F16, ParamCurve};
    ///
    /// let f = |x: f64| I16F16::from_num(x);
    /// let d = [[f(0.0), f(0.0)], [f(1.0), f(1.0)], [f(2.0), f(0.0)]];
    /// let c = BSpline::<[I16F16; 2], 4, 8>::clamped_uniform(2, &d, f(0.0), f(1.0)).unwrap();
    /// assert_eq!(c.eval(f(0.5)), [f(1.0), f(0.5)]);
    /// ```
    pub fn clamped_uniform(
        degree: usize,
        points: &[P],
        u0: P::Scalar,
        u1: P::Scalar,
    ) -> Result<Self, Error> {
        check_degree(degree)?;
        check_counts::<N>(degree, points.len(), points.len())?;
        let kv = KnotVector::clamped_uniform(degree, points.len(), u0, u1)?;
        Self::from_knot_vector(points, kv)
    }

    /// A closed (periodic) B-spline with `K = points.len()` de Boor points: `K` segments and
    /// `K` knots on the circle of one period.
    ///
    /// `knots = None` gives uniform knots with period `[0, 1]`. Otherwise `knots` holds the
    /// `K + 1` values `u_0 ≤ u_1 ≤ … ≤ u_K` (`u_0 < u_K`) whose `K` intervals make one period;
    /// `u_K` closes the period, so knot multiplicities are counted around the circle and must
    /// be at most `g`. The domain is `[u_0, u_K]`; as for every curve, parameters outside it
    /// are clamped (not wrapped), and at `u_K` the last piece is used.
    ///
    /// As for open B-splines, `d_i` acts on `[u_i, u_{i+g+1}]`, read modulo the
    /// period. Internally this is the open B-spline over the periodically extended knot vector
    /// `u_{−g}, …, u_{K+g}` (`u_{j+K} = u_j + (u_K − u_0)`, `K + 2g + 1` knots) with the de Boor
    /// points `d_{K−g}, …, d_{K−1}, d_0, …, d_{K−1}` (the last `g` repeated in front), so it
    /// needs `N ≥ K + g` and `M ≥ K + 2g + 1`. The curve closes with `C^{g−μ}` continuity at
    /// the seam (`C^{g−1}` for a simple seam knot). For a uniform cubic,
    /// `c(u_0) = (d_{K−3} + 4 d_{K−2} + d_{K−1}) / 6`.
    ///
    /// # Errors
    /// As [`BSpline::new`], and [`Error::InvalidArgument`] for degree 0,
    /// [`Error::KnotCount`] unless `knots` has `K + 1` entries,
    /// [`Error::ZeroLengthInterval`] (`index 0`) when `u_0 == u_K`.
    ///
    /// ```
    /// use strak_curves::{BSpline, ParamCurve, ParamCurveDeriv};
    ///
    /// let square = [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]];
    /// let c = BSpline::<[f64; 2], 8, 16>::closed(3, &square, None).unwrap();
    /// assert_eq!(c.domain(), (0.0, 1.0));
    /// let (a, b) = (c.eval(0.0), c.eval(1.0));
    /// assert!((a[0] - b[0]).abs() < 1e-15 && (a[1] - b[1]).abs() < 1e-15);
    /// let (da, db) = (c.deriv(0.0, 2), c.deriv(1.0, 2));
    /// assert!((da[0] - db[0]).abs() < 1e-12 && (da[1] - db[1]).abs() < 1e-12);
    /// ```
    pub fn closed(degree: usize, points: &[P], knots: Option<&[P::Scalar]>) -> Result<Self, Error> {
        check_degree(degree)?;
        if degree == 0 {
            return Err(Error::InvalidArgument);
        }
        let k = points.len();
        check_counts::<N>(degree, k, k + degree)?;
        let m = k + 2 * degree + 1;
        if m > M {
            return Err(Error::CapacityExceeded {
                capacity: M,
                required: m,
            });
        }
        let kv = match knots {
            None => KnotVector::periodic(degree, k, P::Scalar::ZERO, P::Scalar::ONE)?,
            Some(u) => periodic_knots(degree, k, u)?,
        };
        let mut ext: Vec<P, N> = Vec::new();
        for p in points.iter().skip(k - degree).chain(points.iter()) {
            ext.push(*p).map_err(|_| Error::CapacityExceeded {
                capacity: N,
                required: k + degree,
            })?;
        }
        let mut c = Self::from_knot_vector(&ext, kv)?;
        c.closed = true;
        Ok(c)
    }

    /// The degree `g`.
    #[inline]
    pub fn degree(&self) -> usize {
        self.knots.degree()
    }

    /// The de Boor points (for a closed curve the extended list: the last `g` given points,
    /// then all `K`).
    #[inline]
    pub fn control_points(&self) -> &[P] {
        &self.points
    }

    /// The knots `u_0, …, u_{m−1}` (for a closed curve the periodically extended vector).
    #[inline]
    pub fn knots(&self) -> &[P::Scalar] {
        self.knots.as_slice()
    }

    /// The validated knot vector (span search, multiplicities, basis functions).
    #[inline]
    pub fn knot_vector(&self) -> &KnotVector<P::Scalar, M> {
        &self.knots
    }

    /// The parameter domain `[u_g, u_K]`.
    #[inline]
    pub fn domain(&self) -> (P::Scalar, P::Scalar) {
        self.knots.domain()
    }

    /// `true` for a curve made by [`BSpline::closed`] (knot insertion returns an open
    /// representation of the same closed curve).
    #[inline]
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// The point and its derivatives at `u` (clamped to the domain) in one pass:
    /// `out[k]` receives `c^{(k)}(u)` for `k < out.len()` (zero above the degree).
    ///
    /// ```
    /// use strak_curves::BSpline;
    /// let d = [[0.0], [1.0], [4.0]];
    /// let c = BSpline::<[f64; 1], 4, 8>::clamped_uniform(2, &d, 0.0, 1.0).unwrap();
    /// let mut out = [[0.0]; 4];
    /// c.derivatives(0.5, &mut out);
    /// assert_eq!(out, [[1.5], [4.0], [4.0], [0.0]]); // c(u) = 2u + 2u² on [0, 1]
    /// ```
    pub fn derivatives(&self, u: P::Scalar, out: &mut [P]) {
        let (lo, hi) = self.domain();
        let u = u.clamp_to(lo, hi);
        let s = self.knots.span(u);
        let mut all = [P::zero(); LOCAL];
        self.derivs_in_span(s, u, out.len().saturating_sub(1), &mut all);
        for (k, o) in out.iter_mut().enumerate() {
            *o = all.get(k).copied().unwrap_or_else(P::zero);
        }
    }

    /// The derivative of order `k` of the polynomial of piece `piece` (the last piece for
    /// `piece ≥ piece_count()`) at `u` clamped to
    /// [`piece_domain(piece)`](crate::ParamCurve::piece_domain): at the end of a piece this is
    /// the limit from the left, which [`ParamCurveDeriv::deriv`] (the piece starting at a knot)
    /// does not give. `k = 0` is the point; zero for `k > g`.
    ///
    /// ```
    /// use strak_curves::{BSpline, ParamCurveDeriv};
    /// // Degree 1 through (0), (1), (3): slope 1 on the first piece, 2 on the second.
    /// let c = BSpline::<[f64; 1], 4, 8>::new(1, &[[0.0], [1.0], [3.0]], &[0., 0., 1., 2., 2.])
    ///     .unwrap();
    /// assert_eq!(c.piece_deriv(0, 1.0, 1), [1.0]); // left limit at the knot
    /// assert_eq!(c.deriv(1.0, 1), [2.0]); // the piece starting there
    /// ```
    pub fn piece_deriv(&self, piece: usize, u: P::Scalar, k: usize) -> P {
        let s = self.knots.piece_span(piece);
        let u = u.clamp_to(self.knots.knot(s), self.knots.knot(s + 1));
        self.deriv_in_span(s, u, k)
    }

    /// The de Boor points `d_{s−g}, …, d_s` acting on span `s`.
    pub(crate) fn local_points(&self, s: usize) -> [P; LOCAL] {
        let g = self.degree().min(BSPLINE_MAX_DEGREE);
        let mut d = [P::zero(); LOCAL];
        for (j, x) in d.iter_mut().enumerate().take(g + 1) {
            *x = self
                .points
                .get((s + j).saturating_sub(g))
                .copied()
                .unwrap_or_else(P::zero);
        }
        d
    }

    /// `c(u)` on the polynomial piece of span `s` (also used for one-sided limits in tests).
    #[inline]
    pub(crate) fn eval_in_span(&self, s: usize, u: P::Scalar) -> P {
        if self.degree() == 3
            && let Some(p) = self.cubic_in_span(s, u)
        {
            return p;
        }
        de_boor(&self.knots, s, self.degree(), self.local_points(s), u)
    }

    /// De Boor's algorithm for degree 3 on span `s`, unrolled: the same convex combinations
    /// with the same operands in the same order as [`de_boor`] (bit for bit the same result),
    /// without the generic loops and the copy of a `LOCAL`-sized array. `None` when the span
    /// does not have its 4 de Boor points and 6 knots (never for a span from the knot vector).
    #[inline]
    fn cubic_in_span(&self, s: usize, u: P::Scalar) -> Option<P> {
        let [d0, d1, d2, d3] = *self.points.get(s.checked_sub(3)?..=s)? else {
            return None;
        };
        let [t0, t1, t2, t3, t4, t5] = *self.knots.as_slice().get(s.checked_sub(2)?..s + 4)? else {
            return None;
        };
        // r = 1 (j = 3, 2, 1), r = 2 (j = 3, 2), r = 3 (j = 3); t_k here is u_{s−2+k}.
        let e3 = d2.lerp(d3, ratio(u - t2, t5 - t2));
        let e2 = d1.lerp(d2, ratio(u - t1, t4 - t1));
        let e1 = d0.lerp(d1, ratio(u - t0, t3 - t0));
        let f3 = e2.lerp(e3, ratio(u - t2, t4 - t2));
        let f2 = e1.lerp(e2, ratio(u - t1, t3 - t1));
        Some(f2.lerp(f3, ratio(u - t2, t3 - t2)))
    }

    /// `c^{(k)}(u)` on the polynomial piece of span `s`.
    pub(crate) fn deriv_in_span(&self, s: usize, u: P::Scalar, k: usize) -> P {
        let g = self.degree().min(BSPLINE_MAX_DEGREE);
        if k > g {
            return P::zero();
        }
        let mut d = self.local_points(s);
        for r in 1..=k {
            derive_local(&self.knots, s, r, &mut d);
        }
        de_boor(&self.knots, s, g - k, shifted(&d, k, g), u)
    }

    /// `out[k] = c^{(k)}(u)` on span `s` for `k ≤ min(kmax, g)`; the rest of `out` is zero.
    #[allow(clippy::needless_range_loop)] // r is the derivative order
    pub(crate) fn derivs_in_span(&self, s: usize, u: P::Scalar, kmax: usize, out: &mut [P; LOCAL]) {
        let g = self.degree().min(BSPLINE_MAX_DEGREE);
        *out = [P::zero(); LOCAL];
        let mut d = self.local_points(s);
        out[0] = de_boor(&self.knots, s, g, d, u);
        for r in 1..=kmax.min(g) {
            derive_local(&self.knots, s, r, &mut d);
            out[r] = de_boor(&self.knots, s, g - r, shifted(&d, r, g), u);
        }
    }
}

/// `d[k..=g]` moved to the front.
fn shifted<P: Point>(d: &[P; LOCAL], k: usize, g: usize) -> [P; LOCAL] {
    let mut e = [P::zero(); LOCAL];
    for (dst, src) in e.iter_mut().zip(d.iter().skip(k)).take(g + 1 - k.min(g)) {
        *dst = *src;
    }
    e
}

/// De Boor's algorithm (de Boor, *A Practical Guide to Splines*, ch. X; Piegl & Tiller §5.2,
/// computing a point by corner cutting) for a curve of degree `p` on span `s`: `d[j]` holds the de
/// Boor point acting on `N_{s−p+j}^p`, `j = 0..=p`. Each step is the convex combination
/// `(1 − α)·d_{j−1} + α·d_j` with `α = (u − u_i)/(u_{i+p+1−r} − u_i) ∈ [0, 1]`.
pub(crate) fn de_boor<P: Point, const M: usize>(
    kv: &KnotVector<P::Scalar, M>,
    s: usize,
    p: usize,
    mut d: [P; LOCAL],
    u: P::Scalar,
) -> P {
    let p = p.min(BSPLINE_MAX_DEGREE);
    for r in 1..=p {
        for j in (r..=p).rev() {
            let i = (s + j).saturating_sub(p);
            let lo = kv.knot(i);
            let alpha = ratio(u - lo, kv.knot(i + p + 1 - r) - lo);
            d[j] = d[j - 1].lerp(d[j], alpha);
        }
    }
    d[p]
}

/// Degree/point-count/capacity checks shared by the constructors: `count` points given,
/// `stored` points to store.
fn check_counts<const N: usize>(degree: usize, count: usize, stored: usize) -> Result<(), Error> {
    if count < degree + 1 {
        return Err(Error::TooFewPoints {
            required: degree + 1,
            found: count,
        });
    }
    if stored > N {
        return Err(Error::CapacityExceeded {
            capacity: N,
            required: stored,
        });
    }
    Ok(())
}

/// The periodically extended knot vector of a closed B-spline from the `K + 1` knots of one
/// period.
fn periodic_knots<S: Scalar, const M: usize>(
    degree: usize,
    count: usize,
    u: &[S],
) -> Result<KnotVector<S, M>, Error> {
    if u.len() != count + 1 {
        return Err(Error::KnotCount {
            expected: count + 1,
            found: u.len(),
        });
    }
    check_values(u)?;
    let at = |j: usize| u.get(j).copied().unwrap_or(S::ZERO);
    let (u0, uk) = (at(0), at(count));
    if u0 >= uk {
        return Err(Error::ZeroLengthInterval { index: 0 });
    }
    // Multiplicity around the circle: the run at u_0 joins the run at the end equal to u_K.
    let seam_tail = (1..count).rev().take_while(|&j| at(j) == uk).count();
    let mut a = 0;
    while a < count {
        let mut b = a + 1;
        while b < count && at(b) == at(a) {
            b += 1;
        }
        let mult = if a == 0 { b - a + seam_tail } else { b - a };
        if mult > degree {
            return Err(Error::KnotMultiplicity { index: a });
        }
        a = b;
    }
    let period = uk.to_f64() - u0.to_f64();
    let mut v: Vec<S, M> = Vec::new();
    let m = count + 2 * degree + 1;
    for j in 0..m {
        let value = if j < degree {
            // u_{j−g} = u_{K+j−g} − period
            let r = at(count + j - degree);
            if r == uk {
                u0
            } else {
                S::from_f64(r.to_f64() - period).ok_or(Error::OutOfRange)?
            }
        } else if j <= count + degree {
            at(j - degree)
        } else {
            let r = at(j - degree - count);
            if r == u0 {
                uk
            } else {
                S::from_f64(r.to_f64() + period).ok_or(Error::OutOfRange)?
            }
        };
        v.push(value).map_err(|_| Error::CapacityExceeded {
            capacity: M,
            required: m,
        })?;
    }
    KnotVector::new(degree, &v)
}

impl<P: Point, const N: usize, const M: usize> ParamCurve for BSpline<P, N, M> {
    type Point = P;

    fn domain(&self) -> (P::Scalar, P::Scalar) {
        self.knots.domain()
    }

    fn eval(&self, u: P::Scalar) -> P {
        let (lo, hi) = self.knots.domain();
        let u = u.clamp_to(lo, hi);
        self.eval_in_span(self.knots.span(u), u)
    }

    fn piece_count(&self) -> usize {
        self.knots.piece_count()
    }

    fn piece_domain(&self, i: usize) -> (P::Scalar, P::Scalar) {
        let s = self.knots.piece_span(i);
        (self.knots.knot(s), self.knots.knot(s + 1))
    }
}

impl<P: Point, const N: usize, const M: usize> ParamCurveDeriv for BSpline<P, N, M> {
    /// `c^{(k)}(u)` from the local derivative de Boor points (`Q_i = g(d_{i+1} − d_i)/(u_{i+g+1} − u_{i+1})`,
    /// applied `k` times) and de Boor's algorithm of degree `g − k`; zero for `k > g`.
    fn deriv(&self, u: P::Scalar, k: usize) -> P {
        let (lo, hi) = self.knots.domain();
        let u = u.clamp_to(lo, hi);
        self.deriv_in_span(self.knots.span(u), u, k)
    }
}

/// Forwards to the inherent [`BSpline::piece_deriv`] (one-sided limits at knots).
impl<P: Point, const N: usize, const M: usize> PieceDeriv for BSpline<P, N, M> {
    fn piece_deriv(&self, piece: usize, u: P::Scalar, k: usize) -> P {
        BSpline::piece_deriv(self, piece, u, k)
    }
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;
    use crate::scalar::{I16F16, I32F32};
    use glam::{DVec2, DVec3, Vec3};

    type C2 = BSpline<[f64; 2], 16, 32>;

    fn close(a: [f64; 2], b: [f64; 2], tol: f64) -> bool {
        (a[0] - b[0]).abs() <= tol && (a[1] - b[1]).abs() <= tol
    }

    const D7: [[f64; 2]; 7] = [
        [0.0, 0.0],
        [1.0, 3.0],
        [3.0, 4.0],
        [5.0, 1.0],
        [6.0, -2.0],
        [8.0, 0.5],
        [9.0, 3.0],
    ];

    fn open_cubic() -> C2 {
        // g = 3, n = 4 segments, K = 7, m = 11, U = [0,0,0,0,1,2,3,4,4,4,4]
        C2::new(3, &D7, &[0., 0., 0., 0., 1., 2., 3., 4., 4., 4., 4.]).unwrap()
    }

    /// c(u) = Σ d_i N_i^g(u) with the literal Cox–de Boor recursion.
    fn by_basis(c: &C2, u: f64) -> [f64; 2] {
        let mut acc = [0.0; 2];
        for (i, d) in c.control_points().iter().enumerate() {
            let n = crate::bspline::basis_function(c.knots(), i, c.degree(), u).unwrap();
            acc[0] += n * d[0];
            acc[1] += n * d[1];
        }
        acc
    }

    /// The unrolled cubic gives the generic de Boor's bits (non-uniform knots, every format).
    #[test]
    fn cubic_fast_path_is_bit_identical() {
        fn check<P: Point>(c: &BSpline<P, 16, 32>) {
            let (lo, hi) = c.domain();
            for i in 0..=997 {
                let u =
                    P::Scalar::from_f64(lo.to_f64() + (hi - lo).to_f64() * f64::from(i) / 997.0)
                        .unwrap();
                let s = c.knots.span(u);
                let generic = de_boor(&c.knots, s, 3, c.local_points(s), u);
                assert_eq!(c.cubic_in_span(s, u), Some(generic), "u = {u:?}");
                assert_eq!(c.eval(u), generic);
            }
        }
        let t = [0., 0., 0., 0., 0.3, 0.31, 1.7, 2., 4., 4., 4., 4.];
        let d: [[f64; 2]; 8] = core::array::from_fn(|i| {
            let x = i as f64;
            [x * 1.37 - 2.0, (x * 0.9).sin() * 3.1]
        });
        check(&C2::new(3, &d, &t).unwrap());
        let f = |x: f64| [x as f32, (x * 0.7) as f32, 1.0 / (x + 1.5) as f32];
        let d32: [[f32; 3]; 8] = core::array::from_fn(|i| f(i as f64));
        let t32 = t.map(|x| x as f32);
        check(&BSpline::<[f32; 3], 16, 32>::new(3, &d32, &t32).unwrap());
        let q = |x: f64| I32F32::from_num(x);
        let dq: [[I32F32; 2]; 8] = core::array::from_fn(|i| [q(d[i][0]), q(d[i][1])]);
        check(&BSpline::<[I32F32; 2], 16, 32>::new(3, &dq, &t.map(q)).unwrap());
        let h = |x: f64| I16F16::from_num(x);
        let dh: [[I16F16; 2]; 8] = core::array::from_fn(|i| [h(d[i][0]), h(d[i][1])]);
        check(&BSpline::<[I16F16; 2], 16, 32>::new(3, &dh, &t.map(h)).unwrap());
    }

    #[test]
    fn de_boor_equals_basis_sum() {
        let curves = [
            open_cubic(),
            C2::new(2, &D7, &[0., 0., 0., 0.3, 0.3, 1.1, 2., 3., 3., 3.]).unwrap(),
            C2::new(3, &D7, &[-3., -2., -1., 0., 1., 2., 3., 4., 5., 6., 7.]).unwrap(),
            C2::new(1, &D7[..3], &[0., 0., 1., 2., 2.]).unwrap(),
        ];
        for c in &curves {
            let (lo, hi) = c.domain();
            for i in 0..=500 {
                let u = lo + (hi - lo) * f64::from(i) / 500.0;
                assert!(close(c.eval(u), by_basis(c, u), 1e-13), "u = {u}");
            }
        }
    }

    #[test]
    fn endpoint_interpolation_and_end_tangents() {
        let c = open_cubic();
        assert_eq!(c.eval(0.0), D7[0]);
        assert_eq!(c.eval(4.0), D7[6]);
        // c'(u_g) = g/(u_{g+1} − u_1)·(d_1 − d_0) and c'(u_K) = g/(u_{K+g−1}... ) (d_{K−1} − d_{K−2})
        let t = c.knots();
        let g = 3.0;
        let s0 = g / (t[4] - t[1]);
        assert!(close(
            c.deriv(0.0, 1),
            [s0 * (D7[1][0] - D7[0][0]), s0 * (D7[1][1] - D7[0][1])],
            1e-13
        ));
        let s1 = g / (t[9] - t[6]);
        assert!(close(
            c.deriv(4.0, 1),
            [s1 * (D7[6][0] - D7[5][0]), s1 * (D7[6][1] - D7[5][1])],
            1e-13
        ));
        // Outside the domain: clamped.
        assert_eq!(c.eval(-1.0), D7[0]);
        assert_eq!(c.eval(9.0), D7[6]);
    }

    /// The k-th derivative from the left at span boundary `u_s` (end of the previous piece).
    fn left_right(c: &C2, s: usize, k: usize) -> ([f64; 2], [f64; 2]) {
        let kv = c.knot_vector();
        let u = kv.knot(s);
        let mut prev = s - 1;
        while kv.knot(prev) >= kv.knot(prev + 1) {
            prev -= 1;
        }
        (c.deriv_in_span(prev, u, k), c.deriv_in_span(s, u, k))
    }

    #[test]
    fn continuity_at_simple_knots_is_g_minus_1() {
        let c = open_cubic();
        for s in 4..=6 {
            for k in 0..3 {
                let (l, r) = left_right(&c, s, k);
                assert!(close(l, r, 1e-12), "s={s} k={k} {l:?} {r:?}");
            }
            let (l, r) = left_right(&c, s, 3);
            assert!(!close(l, r, 1e-6), "third derivative should jump at s={s}");
            // deriv at an inner knot uses the piece starting there.
            assert!(close(c.deriv(c.knots()[s], 3), r, 0.0));
        }
    }

    #[test]
    fn multiplicity_reduces_continuity_and_interpolates() {
        // Cubic, knot 1 with multiplicity 2 (C¹) and knot 2 with multiplicity 3 = g (C⁰).
        let t = [0., 0., 0., 0., 1., 1., 2., 2., 2., 3., 3., 3., 3.];
        let d: [[f64; 2]; 9] = core::array::from_fn(|i| [i as f64, ((i * 7) % 5) as f64]);
        let c = C2::new(3, &d, &t).unwrap();
        // μ = 2 at u = 1 (span starts at index 5): C¹ but not C².
        for k in 0..=1 {
            let (l, r) = left_right(&c, 5, k);
            assert!(close(l, r, 1e-12), "k={k}");
        }
        let (l, r) = left_right(&c, 5, 2);
        assert!(!close(l, r, 1e-6));
        // μ = g = 3 at u = 2 (first knot of the run at index 6): C⁰ and c(2) = d_5.
        let (l, r) = left_right(&c, 8, 0);
        assert!(close(l, r, 1e-12));
        let (l, r) = left_right(&c, 8, 1);
        assert!(!close(l, r, 1e-6));
        assert!(close(c.eval(2.0), d[5], 1e-14));
        assert_eq!(c.piece_count(), 3);
        assert_eq!(c.piece_domain(1), (1.0, 2.0));
        assert_eq!(c.piece_domain(7), (2.0, 3.0));
    }

    #[test]
    fn affine_invariance() {
        let c = open_cubic();
        let f = |p: [f64; 2]| [0.6 * p[0] - 0.8 * p[1] + 3.0, 0.8 * p[0] + 0.6 * p[1] - 1.0];
        let img: [[f64; 2]; 7] = D7.map(f);
        let ci = C2::new(3, &img, c.knots()).unwrap();
        for i in 0..=100 {
            let u = 4.0 * f64::from(i) / 100.0;
            assert!(close(ci.eval(u), f(c.eval(u)), 1e-12));
        }
    }

    #[test]
    fn closed_curve_is_periodic() {
        let pts = [
            [2.0, 0.0],
            [1.0, 1.5],
            [-1.0, 1.0],
            [-2.0, -0.5],
            [0.0, -2.0],
        ];
        let knots = [0.0, 0.5, 1.5, 2.0, 3.5, 4.0];
        for g in 1..=4 {
            for kn in [None, Some(&knots[..])] {
                let c = C2::closed(g, &pts, kn).unwrap();
                assert!(c.is_closed());
                assert_eq!(c.control_points().len(), 5 + g);
                let (lo, hi) = c.domain();
                assert_eq!((lo, hi), if kn.is_some() { (0.0, 4.0) } else { (0.0, 1.0) });
                for k in 0..g {
                    let (a, b) = (c.deriv(lo, k), c.deriv(hi, k));
                    let tol = 1e-12 * (1.0 + a[0].abs() + a[1].abs());
                    assert!(close(a, b, tol), "g={g} k={k} {a:?} {b:?}");
                }
                assert_eq!(c.piece_count(), 5);
            }
        }
        // Closed linear: d_i acts on [u_i, u_{i+2}], so c(u_{i+1}) = d_i.
        let c = C2::closed(1, &pts, Some(&knots)).unwrap();
        assert_eq!(
            c.control_points(),
            &[pts[4], pts[0], pts[1], pts[2], pts[3], pts[4]]
        );
        assert!(close(c.eval(0.5), pts[0], 1e-15));
        assert!(close(c.eval(1.5), pts[1], 1e-15));
        assert!(close(c.eval(0.0), pts[4], 1e-15));
        assert!(close(c.eval(4.0), pts[4], 1e-15));
        // Uniform quadratic on a square (as strak-ref): c(u_0) = (d_2 + d_3)/2, c'(u_0) = 4(d_3 − d_2).
        let sq = [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]];
        let c = C2::closed(2, &sq, None).unwrap();
        assert!(close(c.eval(0.0), [-0.5, -0.5], 1e-15));
        assert!(close(c.deriv(0.0, 1), [4.0, -4.0], 1e-13));
        // Uniform cubic: c(u_0) = (d_{K−3} + 4 d_{K−2} + d_{K−1})/6.
        let c = C2::closed(3, &pts, None).unwrap();
        let e = [
            (pts[2][0] + 4.0 * pts[3][0] + pts[4][0]) / 6.0,
            (pts[2][1] + 4.0 * pts[3][1] + pts[4][1]) / 6.0,
        ];
        assert!(close(c.eval(0.0), e, 1e-15));
        // Seam with multiplicity 2 on a cubic (u_0 = u_1): C¹ there.
        let c = C2::closed(3, &pts, Some(&[0.0, 0.0, 1.0, 2.0, 3.0, 4.0])).unwrap();
        let (a, b) = (c.deriv(0.0, 1), c.deriv(4.0, 1));
        assert!(close(a, b, 1e-12));
    }

    #[test]
    fn glam_points_and_f32() {
        let d = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 2.0, 3.0),
            DVec3::new(2.0, 0.0, 1.0),
            DVec3::X,
        ];
        let c = BSpline::<DVec3, 4, 8>::clamped_uniform(3, &d, 0.0, 1.0).unwrap();
        let df: [Vec3; 4] = d.map(|p| p.as_vec3());
        let cf = BSpline::<Vec3, 4, 8>::clamped_uniform(3, &df, 0.0, 1.0).unwrap();
        for i in 0..=50 {
            let u = f64::from(i) / 50.0;
            for k in 0..=3 {
                let (a, b) = (c.deriv(u, k), cf.deriv(u as f32, k).as_dvec3());
                assert!(
                    (a - b).abs().max_element() < 1e-5 * (1.0 + a.abs().max_element()),
                    "k={k}"
                );
            }
        }
        let _ = DVec2::ZERO;
    }

    #[test]
    fn fixed_point_matches_f64() {
        let c = open_cubic();
        let t16 = c.knots().iter().map(|&x| I16F16::from_num(x));
        let t16: heapless::Vec<I16F16, 16> = t16.collect();
        let d16 = D7.map(|p| p.map(I16F16::from_num));
        let c16 = BSpline::<[I16F16; 2], 8, 16>::new(3, &d16, &t16).unwrap();
        let t32: heapless::Vec<I32F32, 16> =
            c.knots().iter().map(|&x| I32F32::from_num(x)).collect();
        let d32 = D7.map(|p| p.map(I32F32::from_num));
        let c32 = BSpline::<[I32F32; 2], 8, 16>::new(3, &d32, &t32).unwrap();
        let mut worst16 = [0.0_f64; 4];
        let mut worst32 = [0.0_f64; 4];
        for i in 0..=400 {
            let u = 4.0 * f64::from(i) / 400.0;
            for k in 0..=3 {
                let e = c.deriv(u, k);
                let a = c16.deriv(I16F16::from_num(u), k);
                let b = c32.deriv(I32F32::from_num(u), k);
                for j in 0..2 {
                    worst16[k] = worst16[k].max((a[j].to_f64() - e[j]).abs());
                    worst32[k] = worst32[k].max((b[j].to_f64() - e[j]).abs());
                }
            }
        }
        // Tolerances: I16F16 ε = 1.5e-5, I32F32 ε = 2.3e-10, times the derivative scaling.
        assert!(
            worst16[0] < 2e-4 && worst16[1] < 1e-3 && worst16[3] < 1e-2,
            "{worst16:?}"
        );
        assert!(
            worst32[0] < 4e-9 && worst32[1] < 2e-8 && worst32[3] < 2e-7,
            "{worst32:?}"
        );
    }

    #[test]
    fn error_non_finite() {
        let mut d = D7;
        d[2][1] = f64::NAN;
        assert_eq!(
            C2::clamped_uniform(3, &d, 0.0, 1.0).unwrap_err(),
            Error::NonFinite
        );
        assert_eq!(
            C2::new(1, &D7[..2], &[0., 0., f64::INFINITY, 1.]).unwrap_err(),
            Error::NonFinite
        );
    }

    #[test]
    fn error_too_few_points() {
        assert_eq!(
            C2::clamped_uniform(3, &D7[..3], 0.0, 1.0).unwrap_err(),
            Error::TooFewPoints {
                required: 4,
                found: 3
            }
        );
        assert_eq!(
            C2::closed(3, &D7[..3], None).unwrap_err(),
            Error::TooFewPoints {
                required: 4,
                found: 3
            }
        );
    }

    #[test]
    fn error_capacity() {
        assert_eq!(
            BSpline::<[f64; 2], 6, 32>::clamped_uniform(3, &D7, 0.0, 1.0).unwrap_err(),
            Error::CapacityExceeded {
                capacity: 6,
                required: 7
            }
        );
        assert_eq!(
            BSpline::<[f64; 2], 8, 10>::new(3, &D7, &[0., 0., 0., 0., 1., 2., 3., 4., 4., 4., 4.])
                .unwrap_err(),
            Error::CapacityExceeded {
                capacity: 10,
                required: 11
            }
        );
        // Closed: K + g points and K + 2g + 1 knots.
        assert_eq!(
            BSpline::<[f64; 2], 9, 32>::closed(3, &D7, None).unwrap_err(),
            Error::CapacityExceeded {
                capacity: 9,
                required: 10
            }
        );
        assert_eq!(
            BSpline::<[f64; 2], 10, 13>::closed(3, &D7, None).unwrap_err(),
            Error::CapacityExceeded {
                capacity: 13,
                required: 14
            }
        );
        assert!(BSpline::<[f64; 2], 10, 14>::closed(3, &D7, None).is_ok());
    }

    #[test]
    fn error_knot_count() {
        assert_eq!(
            C2::new(3, &D7, &[0., 0., 0., 0., 1., 2., 4., 4., 4., 4.]).unwrap_err(),
            Error::KnotCount {
                expected: 11,
                found: 10
            }
        );
        assert_eq!(
            C2::closed(2, &D7, Some(&[0., 1., 2.])).unwrap_err(),
            Error::KnotCount {
                expected: 8,
                found: 3
            }
        );
        let kv = KnotVector::<f64, 32>::clamped_uniform(2, 5, 0.0, 1.0).unwrap();
        assert_eq!(
            C2::from_knot_vector(&D7, kv).unwrap_err(),
            Error::KnotCount {
                expected: 10,
                found: 8
            }
        );
    }

    #[test]
    fn error_knots_unsorted() {
        assert_eq!(
            C2::new(3, &D7, &[0., 0., 0., 0., 2., 1., 3., 4., 4., 4., 4.]).unwrap_err(),
            Error::KnotsUnsorted { index: 5 }
        );
        assert_eq!(
            C2::closed(2, &D7[..3], Some(&[0., 2., 1., 3.])).unwrap_err(),
            Error::KnotsUnsorted { index: 2 }
        );
    }

    #[test]
    fn error_knot_multiplicity() {
        assert_eq!(
            C2::new(2, &D7, &[0., 0., 0., 1., 1., 1., 2., 3., 3., 3.]).unwrap_err(),
            Error::KnotMultiplicity { index: 3 }
        );
        // Closed quadratic: the seam run u_0 = u_1 plus u_{K−1} = u_K makes multiplicity 3 > g.
        assert_eq!(
            C2::closed(2, &D7[..4], Some(&[0., 0., 1., 2., 2.])).unwrap_err(),
            Error::KnotMultiplicity { index: 0 }
        );
    }

    #[test]
    fn error_zero_length_interval() {
        assert_eq!(
            C2::clamped_uniform(2, &D7, 1.0, 1.0).unwrap_err(),
            Error::ZeroLengthInterval { index: 2 }
        );
        assert_eq!(
            C2::closed(2, &D7[..3], Some(&[1., 1., 1., 1.])).unwrap_err(),
            Error::ZeroLengthInterval { index: 0 }
        );
    }

    #[test]
    fn error_out_of_range() {
        let big = [[I16F16::from_num(20000)], [I16F16::ZERO]];
        assert_eq!(
            BSpline::<[I16F16; 1], 4, 8>::clamped_uniform(1, &big, I16F16::ZERO, I16F16::ONE)
                .unwrap_err(),
            Error::OutOfRange
        );
        // Points fit, but the derivative 1000/(1/64) does not.
        let p = [[I16F16::from_num(-1000)], [I16F16::from_num(1000)]];
        assert_eq!(
            BSpline::<[I16F16; 1], 4, 8>::clamped_uniform(
                1,
                &p,
                I16F16::ZERO,
                I16F16::from_num(1.0 / 64.0)
            )
            .unwrap_err(),
            Error::OutOfRange
        );
    }

    #[test]
    fn error_degree_too_high_and_invalid() {
        let d = [[0.0, 0.0]; 9];
        assert_eq!(
            C2::clamped_uniform(8, &d, 0.0, 1.0).unwrap_err(),
            Error::DegreeTooHigh { max: 7, found: 8 }
        );
        assert_eq!(C2::closed(0, &d, None).unwrap_err(), Error::InvalidArgument);
        // Degree 7 works.
        let d: [[f64; 2]; 9] = core::array::from_fn(|i| [i as f64, 0.0]);
        let c = C2::clamped_uniform(7, &d, 0.0, 1.0).unwrap();
        assert!(close(c.eval(0.5), [4.0, 0.0], 1e-13));
    }

    #[test]
    fn degree_zero_piecewise_constant() {
        let c = C2::new(0, &D7[..3], &[0., 1., 2., 3.]).unwrap();
        assert_eq!(c.eval(0.5), D7[0]);
        assert_eq!(c.eval(1.0), D7[1]);
        assert_eq!(c.eval(3.0), D7[2]);
        assert_eq!(c.deriv(1.5, 1), [0.0, 0.0]);
    }
}

#[cfg(test)]
mod range_tests {
    use super::*;
    use crate::curve::{ParamCurve, ParamCurveDeriv};
    use crate::scalar::I16F16;

    /// Curves near the I16F16 limits: whatever the constructor accepts must evaluate (values
    /// and every derivative, inside and outside the domain) without an overflow panic (debug
    /// builds of `fixed` panic on overflow).
    #[test]
    fn accepted_fixed_point_curves_never_overflow() {
        let f = |x: f64| I16F16::from_num(x);
        let mut accepted = 0;
        for scale in [1.0, 100.0, 4000.0, 16000.0] {
            for span in [1.0 / 64.0, 0.25, 1.0, 8.0] {
                for g in 1..=4 {
                    let pts: [[I16F16; 2]; 7] = core::array::from_fn(|i| {
                        let s = if i % 2 == 0 { 1.0 } else { -1.0 };
                        [f(scale * s), f(scale * (i as f64 / 7.0))]
                    });
                    let Ok(c) = BSpline::<[I16F16; 2], 8, 16>::clamped_uniform(
                        g,
                        &pts,
                        f(-3.0),
                        f(-3.0 + span * 4.0),
                    ) else {
                        continue;
                    };
                    accepted += 1;
                    let (lo, hi) = c.domain();
                    for i in -10..=210 {
                        let u = lo + (hi - lo) * I16F16::from_num(i) / 200;
                        for k in 0..=g + 1 {
                            let _ = c.deriv(u, k);
                        }
                        let _ = c.eval(u);
                    }
                }
            }
        }
        assert!(accepted >= 20, "{accepted}");
    }
}
