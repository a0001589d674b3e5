//! NURBS: non-uniform rational B-splines (Piegl & Tiller, *The NURBS Book*, 2nd ed., §4.2
//! "Definition and Properties of NURBS Curves", §4.3 "Derivatives of a NURBS Curve").
//!
//! ```text
//! R_i(u) = h_i N_i^g(u) / Σ_j h_j N_j^g(u),      c(u) = Σ_i R_i(u) · P_i
//! ```
//!
//! with positive weights `h_i`. In homogeneous coordinates `(h_i·P_i, h_i)` the numerator
//! `A(u) = Σ h_i P_i N_i(u)` and the denominator `w(u) = Σ h_i N_i(u)` are one ordinary
//! B-spline, evaluated with de Boor's algorithm; then `c = A / w`, the projection from
//! homogeneous to Cartesian coordinates. Derivatives follow from `A = w·c` by Leibniz's rule
//! (Piegl & Tiller §4.3):
//!
//! ```text
//! c^{(k)} = ( A^{(k)} − Σ_{i=1}^{k} C(k, i) · w^{(i)} · c^{(k−i)} ) / w
//! ```

use heapless::Vec;

use crate::bspline::{
    BSPLINE_MAX_DEGREE, BSpline, KnotVector, LOCAL, local_coords, ratio, span_coord_bounds,
};
use crate::curve::{ParamCurve, ParamCurveDeriv, PieceDeriv};
use crate::error::Error;
use crate::point::Point;
use crate::scalar::Scalar;

/// A point in homogeneous coordinates `(w·P, w)`: the control points of the B-spline that
/// carries a [`Nurbs`] curve (Piegl & Tiller §4.2). It is itself a [`Point`] with `P::DIM + 1`
/// coordinates (the weight last), so every B-spline algorithm applies to it unchanged.
///
/// ```
/// use strak_curves::{Homogeneous, Point};
/// let h = Homogeneous { weighted: [2.0, 4.0], weight: 2.0 };
/// assert_eq!(<Homogeneous<[f64; 2]> as Point>::DIM, 3);
/// assert_eq!(h.coord(2), 2.0);
/// assert_eq!(h.lerp(Homogeneous { weighted: [0.0, 0.0], weight: 1.0 }, 0.5).weight, 1.5);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Homogeneous<P: Point> {
    /// The weighted point `w·P`.
    pub weighted: P,
    /// The weight `w`.
    pub weight: P::Scalar,
}

impl<P: Point> Point for Homogeneous<P> {
    type Scalar = P::Scalar;
    const DIM: usize = P::DIM + 1;

    fn from_coords(mut f: impl FnMut(usize) -> P::Scalar) -> Self {
        let weighted = P::from_coords(&mut f);
        let weight = f(P::DIM);
        Homogeneous { weighted, weight }
    }

    fn coord(&self, i: usize) -> P::Scalar {
        if i < P::DIM {
            self.weighted.coord(i)
        } else if i == P::DIM {
            self.weight
        } else {
            P::Scalar::ZERO
        }
    }

    #[inline]
    fn plus(self, other: Self) -> Self {
        Homogeneous {
            weighted: self.weighted.plus(other.weighted),
            weight: self.weight + other.weight,
        }
    }

    #[inline]
    fn minus(self, other: Self) -> Self {
        Homogeneous {
            weighted: self.weighted.minus(other.weighted),
            weight: self.weight - other.weight,
        }
    }

    #[inline]
    fn times(self, s: P::Scalar) -> Self {
        Homogeneous {
            weighted: self.weighted.times(s),
            weight: self.weight * s,
        }
    }

    #[inline]
    fn lerp(self, other: Self, t: P::Scalar) -> Self {
        let s = P::Scalar::ONE - t;
        Homogeneous {
            weighted: self.weighted.lerp(other.weighted, t),
            weight: self.weight * s + other.weight * t,
        }
    }
}

/// Binomial coefficients `C(n, i)` for `n ≤ 7` (Leibniz's rule).
const BINOM: [[i16; LOCAL]; LOCAL] = [
    [1, 0, 0, 0, 0, 0, 0, 0],
    [1, 1, 0, 0, 0, 0, 0, 0],
    [1, 2, 1, 0, 0, 0, 0, 0],
    [1, 3, 3, 1, 0, 0, 0, 0],
    [1, 4, 6, 4, 1, 0, 0, 0],
    [1, 5, 10, 10, 5, 1, 0, 0],
    [1, 6, 15, 20, 15, 6, 1, 0],
    [1, 7, 21, 35, 35, 21, 7, 1],
];

/// A NURBS curve of degree `g ≤` [`BSPLINE_MAX_DEGREE`] with up to `N` control points (and
/// weights) and up to `M` knots (Piegl & Tiller §4.2). Open and closed variants share the
/// storage rules of [`BSpline`].
///
/// `c(u) = Σ h_i N_i^g(u) P_i / Σ h_j N_j^g(u)`. Weights are positive; equal weights give the
/// B-spline with the same control points. Conic sections — the exact circle
/// ([`Nurbs::circle`]) — need rational curves. With positive weights each piece lies in the
/// convex hull of its `g + 1` control points, moving a point or changing a weight changes
/// `g + 1` pieces only, and the curve is invariant under affine (indeed projective) maps of
/// its control points (Piegl & Tiller §4.2).
///
/// Evaluation runs de Boor's algorithm on the homogeneous points `(h_i·P_i, h_i)` and divides
/// by the weight `w(u) = Σ h_j N_j^g(u) ≥ min h_j > 0`. Parameters outside the domain are
/// clamped. Derivatives use Leibniz's rule on `A = w·c` (module docs) up to order
/// [`Nurbs::max_deriv_order`] `≤` [`BSPLINE_MAX_DEGREE`]; note that the derivatives of a
/// rational curve do not vanish above the degree.
///
/// Fixed-point range: besides the checks of [`BSpline`] on the homogeneous points, the
/// constructor requires the smallest weight to stay a safe divisor after the rounding of de
/// Boor's algorithm (`w(u) ≥ min h − (4g + 4)·ε ≥ min h / 2`; evaluation clamps `w` to that
/// floor), and bounds every rational derivative `|c^{(k)}| ≤ (|A^{(k)}| + Σ C(k,i)
/// |w^{(i)}| |c^{(k−i)}|) / w_min` span by span. Orders up to `g` must fit (otherwise
/// [`Error::OutOfRange`]); the highest fitting order up to 7 is [`Nurbs::max_deriv_order`].
///
/// ```
/// use strak_curves::{Nurbs, ParamCurve};
///
/// // A rational quadratic Bézier arc: weight cos(45°) on the middle point gives a quarter circle.
/// let p = [[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
/// let w = [1.0, core::f64::consts::FRAC_1_SQRT_2, 1.0];
/// let c = Nurbs::<[f64; 2], 4, 8>::new(2, &p, &w, &[0., 0., 0., 1., 1., 1.]).unwrap();
/// let q = c.eval(0.3);
/// assert!((q[0] * q[0] + q[1] * q[1] - 1.0).abs() < 1e-15);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Nurbs<P: Point, const N: usize, const M: usize> {
    curve: BSpline<Homogeneous<P>, N, M>,
    points: Vec<P, N>,
    weights: Vec<P::Scalar, N>,
    weight_floor: P::Scalar,
    max_deriv: usize,
}

impl<P: Point, const N: usize, const M: usize> Nurbs<P, N, M> {
    /// An open NURBS curve with control points `points`, weights `weights` (one per point,
    /// positive) and knot vector `knots` (`K + g + 1` knots, as [`BSpline::new`]).
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] (weights vs points), [`Error::NonFinite`],
    /// [`Error::NonPositiveWeight`], [`Error::OutOfRange`], and every error of
    /// [`BSpline::new`].
    ///
    /// ```
    /// use strak_curves::{Error, Nurbs, ParamCurve};
    ///
    /// let p = [[0.0], [1.0], [2.0]];
    /// let t = [0., 0., 0., 1., 1., 1.];
    /// let c = Nurbs::<[f64; 1], 4, 8>::new(2, &p, &[1.0, 3.0, 1.0], &t).unwrap();
    /// assert_eq!(c.eval(0.5), [1.0]);
    /// assert_eq!(
    ///     Nurbs::<[f64; 1], 4, 8>::new(2, &p, &[1.0, 0.0, 1.0], &t).unwrap_err(),
    ///     Error::NonPositiveWeight { index: 1 }
    /// );
    /// ```
    pub fn new(
        degree: usize,
        points: &[P],
        weights: &[P::Scalar],
        knots: &[P::Scalar],
    ) -> Result<Self, Error> {
        let h = homogeneous::<P, N>(points, weights)?;
        Self::from_homogeneous(BSpline::new(degree, &h, knots)?)
    }

    /// An open NURBS curve on the clamped uniform knot vector over `[u0, u1]`: it starts at the
    /// first and ends at the last control point.
    ///
    /// # Errors
    /// As [`Nurbs::new`] and [`BSpline::clamped_uniform`].
    ///
    /// ```
    /// use strak_curves::{Nurbs, ParamCurve};
    /// let p = [[0.0, 0.0], [1.0, 1.0], [2.0, 0.0], [3.0, 1.0]];
    /// let c = Nurbs::<[f64; 2], 4, 8>::clamped_uniform(2, &p, &[1.0, 2.0, 0.5, 1.0], 0.0, 1.0)
    ///     .unwrap();
    /// assert_eq!(c.eval(1.0), [3.0, 1.0]);
    /// ```
    pub fn clamped_uniform(
        degree: usize,
        points: &[P],
        weights: &[P::Scalar],
        u0: P::Scalar,
        u1: P::Scalar,
    ) -> Result<Self, Error> {
        let h = homogeneous::<P, N>(points, weights)?;
        Self::from_homogeneous(BSpline::clamped_uniform(degree, &h, u0, u1)?)
    }

    /// A closed NURBS curve through `K` control points with weights (knots as
    /// [`BSpline::closed`]: `None` for uniform knots with period `[0, 1]`, or the `K + 1`
    /// knots of one period). Needs `N ≥ K + g`, `M ≥ K + 2g + 1`.
    ///
    /// # Errors
    /// As [`Nurbs::new`] and [`BSpline::closed`].
    ///
    /// ```
    /// use strak_curves::{Nurbs, ParamCurve};
    /// let p = [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]];
    /// let c = Nurbs::<[f64; 2], 8, 16>::closed(2, &p, &[1.0, 2.0, 1.0, 2.0], None).unwrap();
    /// let (a, b) = (c.eval(0.0), c.eval(1.0));
    /// assert!((a[0] - b[0]).abs() < 1e-15 && (a[1] - b[1]).abs() < 1e-15);
    /// ```
    pub fn closed(
        degree: usize,
        points: &[P],
        weights: &[P::Scalar],
        knots: Option<&[P::Scalar]>,
    ) -> Result<Self, Error> {
        let h = homogeneous::<P, N>(points, weights)?;
        Self::from_homogeneous(BSpline::closed(degree, &h, knots)?)
    }

    /// A NURBS curve from its homogeneous B-spline (control points `(h_i·P_i, h_i)`).
    ///
    /// # Errors
    /// [`Error::NonPositiveWeight`], [`Error::OutOfRange`] (weights too small for the
    /// scalar's resolution, projected points or rational derivatives up to order `g` out of
    /// range).
    ///
    /// ```
    /// use strak_curves::{BSpline, Homogeneous, Nurbs, ParamCurve};
    /// let h = [
    ///     Homogeneous { weighted: [0.0], weight: 1.0 },
    ///     Homogeneous { weighted: [2.0], weight: 2.0 },
    /// ];
    /// let b = BSpline::<_, 4, 8>::clamped_uniform(1, &h, 0.0, 1.0).unwrap();
    /// let c = Nurbs::<[f64; 1], 4, 8>::from_homogeneous(b).unwrap();
    /// assert_eq!(c.eval(0.5), [2.0 / 3.0]);
    /// ```
    pub fn from_homogeneous(curve: BSpline<Homogeneous<P>, N, M>) -> Result<Self, Error> {
        let g = curve.degree();
        let hp = curve.control_points();
        let mut w_min = f64::INFINITY;
        let mut w_max = 0.0_f64;
        for (i, h) in hp.iter().enumerate() {
            if h.weight <= P::Scalar::ZERO {
                return Err(Error::NonPositiveWeight { index: i });
            }
            w_min = w_min.min(h.weight.to_f64());
            w_max = w_max.max(h.weight.to_f64());
        }
        let margin = weight_margin::<P::Scalar>(g, w_max);
        let floor = w_min - margin;
        if floor <= 0.5 * w_min {
            return Err(Error::OutOfRange);
        }
        let weight_floor = P::Scalar::from_f64(floor).ok_or(Error::OutOfRange)?;
        let mut points: Vec<P, N> = Vec::new();
        let mut weights: Vec<P::Scalar, N> = Vec::new();
        for h in hp {
            let w = h.weight.to_f64();
            for c in 0..P::DIM {
                if !<P::Scalar as Scalar>::fits(h.weighted.coord(c).to_f64() / w) {
                    return Err(Error::OutOfRange);
                }
            }
            let p = P::from_coords(|c| ratio(h.weighted.coord(c), h.weight));
            let cap = Error::CapacityExceeded {
                capacity: N,
                required: hp.len(),
            };
            points.push(p).map_err(|_| cap)?;
            weights.push(h.weight).map_err(|_| cap)?;
        }
        let max_deriv = rational_orders(&curve, &points, floor, margin);
        if max_deriv < g {
            return Err(Error::OutOfRange);
        }
        Ok(Nurbs {
            curve,
            points,
            weights,
            weight_floor,
            max_deriv,
        })
    }

    /// The degree `g`.
    #[inline]
    pub fn degree(&self) -> usize {
        self.curve.degree()
    }

    /// The control points `P_i` (for a closed curve the extended list, as
    /// [`BSpline::control_points`]).
    #[inline]
    pub fn control_points(&self) -> &[P] {
        &self.points
    }

    /// The weights `h_i`, one per control point.
    #[inline]
    pub fn weights(&self) -> &[P::Scalar] {
        &self.weights
    }

    /// The knots.
    #[inline]
    pub fn knots(&self) -> &[P::Scalar] {
        self.curve.knots()
    }

    /// The validated knot vector.
    #[inline]
    pub fn knot_vector(&self) -> &KnotVector<P::Scalar, M> {
        self.curve.knot_vector()
    }

    /// The parameter domain `[u_g, u_K]`.
    #[inline]
    pub fn domain(&self) -> (P::Scalar, P::Scalar) {
        self.curve.domain()
    }

    /// `true` for a curve made by [`Nurbs::closed`].
    #[inline]
    pub fn is_closed(&self) -> bool {
        self.curve.is_closed()
    }

    /// The homogeneous B-spline `(h_i·P_i, h_i)` that carries the curve.
    #[inline]
    pub fn homogeneous(&self) -> &BSpline<Homogeneous<P>, N, M> {
        &self.curve
    }

    /// The highest derivative order [`ParamCurveDeriv::deriv`] computes: 7
    /// ([`BSPLINE_MAX_DEGREE`]) unless a rational derivative bound exceeds the scalar's range
    /// (fixed-point), and never below the degree. Orders above it return the zero vector —
    /// *not* the true derivative, which for a rational curve is non-zero at every order.
    #[inline]
    pub fn max_deriv_order(&self) -> usize {
        self.max_deriv
    }

    /// The same curve with the knot `u` inserted (Boehm's algorithm on the homogeneous
    /// points, see [`BSpline::insert_knot`]).
    ///
    /// # Errors
    /// As [`BSpline::insert_knot`].
    ///
    /// ```
    /// use strak_curves::{Nurbs, ParamCurve};
    /// let c = Nurbs::<[f64; 2], 12, 16>::circle([0.0, 0.0], 1.0).unwrap();
    /// let r = c.insert_knot(0.5).unwrap();
    /// let (a, b) = (c.eval(0.7), r.eval(0.7));
    /// assert!((a[0] - b[0]).abs() < 1e-15 && (a[1] - b[1]).abs() < 1e-15);
    /// ```
    pub fn insert_knot(&self, u: P::Scalar) -> Result<Self, Error> {
        Self::from_homogeneous(self.curve.insert_knot(u)?)
    }

    /// The rational Bézier segments of the pieces, in order: for piece `i` the control points
    /// and weights of a rational Bézier curve of degree `g` (`NB = g + 1`) on
    /// [`piece_domain(i)`](crate::ParamCurve::piece_domain) mapped to `[0, 1]`. Computed on
    /// the homogeneous points as [`BSpline::to_bezier_segments`].
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] when `NB ≠ g + 1`, [`Error::CapacityExceeded`] when there
    /// are more than `K` pieces.
    ///
    /// ```
    /// use strak_curves::Nurbs;
    /// let c = Nurbs::<[f64; 2], 12, 16>::circle([0.0, 0.0], 1.0).unwrap();
    /// let segs = c.to_rational_bezier_segments::<3, 4>().unwrap();
    /// assert_eq!(segs.len(), 4);
    /// assert_eq!(segs[1].0, [[0.0, 1.0], [-1.0, 1.0], [-1.0, 0.0]]);
    /// assert_eq!(segs[1].1[1], core::f64::consts::FRAC_1_SQRT_2);
    /// ```
    #[allow(clippy::type_complexity)]
    pub fn to_rational_bezier_segments<const NB: usize, const K: usize>(
        &self,
    ) -> Result<Vec<([P; NB], [P::Scalar; NB]), K>, Error> {
        let segs = self.curve.to_bezier_segments::<NB, K>()?;
        let mut out = Vec::new();
        for seg in &segs {
            let w: [P::Scalar; NB] =
                core::array::from_fn(|j| seg.get(j).map_or(self.weight_floor, |h| h.weight));
            let p: [P; NB] = core::array::from_fn(|j| match seg.get(j) {
                Some(h) => self.project(*h),
                None => P::zero(),
            });
            out.push((p, w)).map_err(|_| Error::CapacityExceeded {
                capacity: K,
                required: segs.len(),
            })?;
        }
        Ok(out)
    }

    /// The point and its derivatives at `u` (clamped) in one pass: `out[k] = c^{(k)}(u)` for
    /// `k < out.len()`, zero above [`Nurbs::max_deriv_order`].
    ///
    /// ```
    /// use strak_curves::Nurbs;
    /// let c = Nurbs::<[f64; 2], 12, 16>::circle([0.0, 0.0], 2.0).unwrap();
    /// let mut d = [[0.0; 2]; 3];
    /// c.derivatives(0.0, &mut d);
    /// assert_eq!(d[0], [2.0, 0.0]);
    /// assert!(d[1][0].abs() < 1e-15 && d[1][1] > 0.0); // tangent ⟂ radius
    /// ```
    pub fn derivatives(&self, u: P::Scalar, out: &mut [P]) {
        let mut all = [P::zero(); LOCAL];
        self.rational_derivs(u, out.len().saturating_sub(1), &mut all);
        for (k, o) in out.iter_mut().enumerate() {
            *o = all.get(k).copied().unwrap_or_else(P::zero);
        }
    }

    /// `A / w` with `w` clamped to the validated floor.
    #[inline]
    fn project(&self, h: Homogeneous<P>) -> P {
        let w = h.weight.max_of(self.weight_floor);
        P::from_coords(|c| ratio(h.weighted.coord(c), w))
    }

    /// The derivative of order `k` of the rational function of piece `piece` (the last piece
    /// for `piece ≥ piece_count()`) at `u` clamped to
    /// [`piece_domain(piece)`](crate::ParamCurve::piece_domain): at the end of a piece this is
    /// the limit from the left. Zero for `k >` [`Nurbs::max_deriv_order`].
    ///
    /// ```
    /// use strak_curves::{Nurbs, ParamCurveDeriv};
    /// let c = Nurbs::<[f64; 2], 9, 12>::circle([0.0, 0.0], 1.0).unwrap();
    /// // At the double knot u = 1 the quarters meet C¹ but not C²:
    /// assert_eq!(c.piece_deriv(0, 1.0, 1), c.deriv(1.0, 1));
    /// let (left, right) = (c.piece_deriv(0, 1.0, 2), c.deriv(1.0, 2));
    /// assert!(left[0] > 0.8 && right[0] < -0.8);
    /// ```
    pub fn piece_deriv(&self, piece: usize, u: P::Scalar, k: usize) -> P {
        let kv = self.curve.knot_vector();
        let s = kv.piece_span(piece);
        let u = u.clamp_to(kv.knot(s), kv.knot(s + 1));
        if k > self.max_deriv {
            return P::zero();
        }
        let mut all = [P::zero(); LOCAL];
        self.rational_derivs_in_span(s, u, k, &mut all);
        all.get(k).copied().unwrap_or_else(P::zero)
    }

    /// `out[j] = c^{(j)}(u)` for `j ≤ min(kmax, max_deriv)`; zero above.
    fn rational_derivs(&self, u: P::Scalar, kmax: usize, out: &mut [P; LOCAL]) {
        let (lo, hi) = self.domain();
        let u = u.clamp_to(lo, hi);
        let s = self.curve.knot_vector().span(u);
        self.rational_derivs_in_span(s, u, kmax, out);
    }

    /// Leibniz's rule on span `s`.
    fn rational_derivs_in_span(&self, s: usize, u: P::Scalar, kmax: usize, out: &mut [P; LOCAL]) {
        let kmax = kmax.min(self.max_deriv).min(BSPLINE_MAX_DEGREE);
        let g = self.degree().min(BSPLINE_MAX_DEGREE);
        let zero = Homogeneous {
            weighted: P::zero(),
            weight: P::Scalar::ZERO,
        };
        let mut h = [zero; LOCAL];
        self.curve.derivs_in_span(s, u, kmax, &mut h);
        let w = h[0].weight.max_of(self.weight_floor);
        *out = [P::zero(); LOCAL];
        for j in 0..=kmax {
            let mut acc = if j <= g { h[j].weighted } else { P::zero() };
            for i in 1..=j.min(g) {
                let f = h[i].weight * P::Scalar::from_i16(BINOM[j][i]);
                acc = acc.minus(out[j - i].times(f));
            }
            out[j] = P::from_coords(|c| ratio(acc.coord(c), w));
        }
    }
}

/// The homogeneous points `(h_i·P_i, h_i)`, validated.
fn homogeneous<P: Point, const N: usize>(
    points: &[P],
    weights: &[P::Scalar],
) -> Result<Vec<Homogeneous<P>, N>, Error> {
    if weights.len() != points.len() {
        return Err(Error::LengthMismatch {
            expected: points.len(),
            found: weights.len(),
        });
    }
    if points.len() > N {
        return Err(Error::CapacityExceeded {
            capacity: N,
            required: points.len(),
        });
    }
    if points.iter().any(|p| !p.is_finite()) || weights.iter().any(|w| !w.is_finite()) {
        return Err(Error::NonFinite);
    }
    let mut out = Vec::new();
    for (i, (p, &w)) in points.iter().zip(weights).enumerate() {
        if w <= P::Scalar::ZERO {
            return Err(Error::NonPositiveWeight { index: i });
        }
        let wf = w.to_f64();
        if !<P::Scalar as Scalar>::fits(wf) || !<P::Scalar as Scalar>::fits(p.max_abs() * wf) {
            return Err(Error::OutOfRange);
        }
        out.push(Homogeneous {
            weighted: p.times(w),
            weight: w,
        })
        .map_err(|_| Error::CapacityExceeded {
            capacity: N,
            required: points.len(),
        })?;
    }
    Ok(out)
}

/// How far de Boor's rounding can pull `w(u)` below the smallest weight: `(4g + 4)` units of
/// `ε` (absolute for fixed-point, relative to the largest weight for floats).
fn weight_margin<S: Scalar>(degree: usize, w_max: f64) -> f64 {
    let units = (4 * degree + 4) as f64 * S::EPSILON;
    if S::IS_FIXED { units } else { units * w_max }
}

/// The highest order `k ≤ 7` such that, on every non-empty span, the Leibniz-rule bound of
/// every rational derivative up to `k` (and every intermediate product and sum) fits.
fn rational_orders<P: Point, const N: usize, const M: usize>(
    curve: &BSpline<Homogeneous<P>, N, M>,
    points: &[P],
    floor: f64,
    margin: f64,
) -> usize {
    let kv = curve.knot_vector();
    let hp = curve.control_points();
    let g = kv.degree().min(BSPLINE_MAX_DEGREE);
    let fits = <P::Scalar as Scalar>::fits;
    let mut orders = BSPLINE_MAX_DEGREE;
    for s in g..kv.control_point_count() {
        if kv.knot(s) >= kv.knot(s + 1) {
            continue;
        }
        // |A^{(r)}|, |w^{(r)}| from the local derivative de Boor points.
        let mut a = [0.0_f64; LOCAL];
        for c in 0..P::DIM {
            let (m, _) = span_coord_bounds(kv, s, local_coords(hp, s, g, c));
            for (x, y) in a.iter_mut().zip(m) {
                *x = x.max(y);
            }
        }
        let local_w = local_coords(hp, s, g, P::DIM);
        let (wb, _) = span_coord_bounds(kv, s, local_w);
        let w_local_min = local_w
            .iter()
            .take(g + 1)
            .fold(f64::INFINITY, |m, x| m.min(*x));
        let w_lo = (w_local_min - margin).max(floor);
        // |c| ≤ max |P_i| over the span's control points (convex hull).
        let mut cb = [0.0_f64; LOCAL];
        for j in 0..=g {
            let p = points.get(s + j - g).map_or(0.0, |p| p.max_abs());
            cb[0] = cb[0].max(p);
        }
        let mut span_orders = BSPLINE_MAX_DEGREE;
        for j in 1..=BSPLINE_MAX_DEGREE {
            let mut num = if j <= g { a[j] } else { 0.0 };
            let mut ok = true;
            for i in 1..=j.min(g) {
                let f = f64::from(BINOM[j][i]) * wb[i];
                let term = f * cb[j - i];
                ok &= fits(f) && fits(term);
                num += term;
            }
            cb[j] = num / w_lo;
            ok &= fits(num) && fits(cb[j]);
            if !ok {
                span_orders = j - 1;
                break;
            }
        }
        orders = orders.min(span_orders);
    }
    orders
}

impl<P: Point, const N: usize, const M: usize> ParamCurve for Nurbs<P, N, M> {
    type Point = P;

    fn domain(&self) -> (P::Scalar, P::Scalar) {
        self.curve.domain()
    }

    /// `c(u) = A(u) / w(u)` from de Boor's algorithm on the homogeneous points.
    fn eval(&self, u: P::Scalar) -> P {
        self.project(self.curve.eval(u))
    }

    fn piece_count(&self) -> usize {
        self.curve.piece_count()
    }

    fn piece_domain(&self, i: usize) -> (P::Scalar, P::Scalar) {
        self.curve.piece_domain(i)
    }
}

impl<P: Point, const N: usize, const M: usize> ParamCurveDeriv for Nurbs<P, N, M> {
    /// `c^{(k)}(u)` by Leibniz's rule for `k ≤` [`Nurbs::max_deriv_order`] (normally 7 =
    /// [`BSPLINE_MAX_DEGREE`]); the zero vector above it (not the true, non-zero derivative).
    fn deriv(&self, u: P::Scalar, k: usize) -> P {
        if k == 0 {
            return self.eval(u);
        }
        if k > self.max_deriv {
            return P::zero();
        }
        let mut all = [P::zero(); LOCAL];
        self.rational_derivs(u, k, &mut all);
        all.get(k).copied().unwrap_or_else(P::zero)
    }
}

/// Forwards to the inherent [`Nurbs::piece_deriv`] (one-sided limits at knots).
impl<P: Point, const N: usize, const M: usize> PieceDeriv for Nurbs<P, N, M> {
    fn piece_deriv(&self, piece: usize, u: P::Scalar, k: usize) -> P {
        Nurbs::piece_deriv(self, piece, u, k)
    }
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;
    use crate::scalar::{I16F16, I32F32};
    use glam::DVec3;

    type C2 = BSpline<[f64; 2], 16, 32>;
    type R2 = Nurbs<[f64; 2], 16, 32>;
    const D: [[f64; 2]; 6] = [
        [0.0, 0.0],
        [1.0, 3.0],
        [3.0, 4.0],
        [5.0, 1.0],
        [6.0, -2.0],
        [8.0, 0.5],
    ];
    const W: [f64; 6] = [1.0, 2.5, 0.5, 1.0, 3.0, 1.5];
    const T: [f64; 10] = [0., 0., 0., 0., 0.7, 1.2, 2., 2., 2., 2.];

    fn close(a: [f64; 2], b: [f64; 2], tol: f64) -> bool {
        (a[0] - b[0]).abs() <= tol && (a[1] - b[1]).abs() <= tol
    }

    #[test]
    fn equal_weights_give_the_bspline() {
        let b = C2::new(3, &D, &T).unwrap();
        let r = R2::new(3, &D, &[2.0; 6], &T).unwrap();
        for i in 0..=200 {
            let u = 2.0 * f64::from(i) / 200.0;
            for k in 0..=3 {
                let (x, y) = (b.deriv(u, k), r.deriv(u, k));
                assert!(
                    close(x, y, 1e-11 * (1.0 + x[0].abs() + x[1].abs())),
                    "u={u} k={k}"
                );
            }
            // Higher derivatives of a polynomial NURBS are zero.
            assert!(close(r.deriv(u, 5), [0.0, 0.0], 1e-6));
        }
    }

    #[test]
    fn rational_basis_definition() {
        // c(u) = Σ h_i N_i P_i / Σ h_j N_j with the literal Cox–de Boor basis.
        let r = R2::new(3, &D, &W, &T).unwrap();
        for i in 0..=200 {
            let u = 2.0 * f64::from(i) / 200.0;
            let mut num = [0.0; 2];
            let mut den = 0.0;
            for j in 0..6 {
                let n = crate::bspline::basis_function(&T, j, 3, u).unwrap() * W[j];
                num[0] += n * D[j][0];
                num[1] += n * D[j][1];
                den += n;
            }
            assert!(
                close(r.eval(u), [num[0] / den, num[1] / den], 1e-13),
                "u={u}"
            );
        }
        assert_eq!(r.eval(0.0), D[0]);
        assert_eq!(r.eval(2.0), D[5]);
    }

    #[test]
    fn rational_derivatives_match_finite_differences() {
        let r = R2::new(3, &D, &W, &T).unwrap();
        assert_eq!(r.max_deriv_order(), 7);
        for i in 1..100 {
            let u = 2.0 * f64::from(i) / 100.0;
            if T.iter().any(|&t| (t - u).abs() < 1e-3) {
                continue;
            }
            let mut all = [[0.0; 2]; 8];
            r.derivatives(u, &mut all);
            for k in 1..=7 {
                let h = 1e-5;
                let (a, b) = (r.deriv(u - h, k - 1), r.deriv(u + h, k - 1));
                let fd = [(b[0] - a[0]) / (2.0 * h), (b[1] - a[1]) / (2.0 * h)];
                let ex = r.deriv(u, k);
                assert_eq!(ex, all[k]);
                let scale = 1.0 + ex[0].abs() + ex[1].abs();
                assert!(
                    close(fd, ex, 1e-5 * scale),
                    "u={u} k={k} fd={fd:?} ex={ex:?}"
                );
            }
            // Above BSPLINE_MAX_DEGREE: zero by definition.
            assert_eq!(r.deriv(u, 8), [0.0, 0.0]);
        }
    }

    #[test]
    fn closed_nurbs_is_periodic() {
        let r = R2::closed(3, &D, &W, None).unwrap();
        assert!(r.is_closed());
        for k in 0..3 {
            let (a, b) = (r.deriv(0.0, k), r.deriv(1.0, k));
            assert!(
                close(a, b, 1e-10 * (1.0 + a[0].abs() + a[1].abs())),
                "k={k}"
            );
        }
    }

    #[test]
    fn insertion_and_bezier_segments() {
        let r = R2::new(3, &D, &W, &T).unwrap();
        let q = r.insert_knot(0.3).unwrap().insert_knot(1.5).unwrap();
        let segs = r.to_rational_bezier_segments::<4, 4>().unwrap();
        assert_eq!(segs.len(), 3);
        for i in 0..=100 {
            let u = 2.0 * f64::from(i) / 100.0;
            assert!(close(r.eval(u), q.eval(u), 1e-12));
        }
        for (i, (p, w)) in segs.iter().enumerate() {
            let (a, b) = r.piece_domain(i);
            for j in 0..=10 {
                let t = f64::from(j) / 10.0;
                // Rational Bernstein sum.
                let bern = [
                    (1.0 - t).powi(3),
                    3.0 * t * (1.0 - t).powi(2),
                    3.0 * t * t * (1.0 - t),
                    t.powi(3),
                ];
                let (mut x, mut y, mut d) = (0.0, 0.0, 0.0);
                for k in 0..4 {
                    x += bern[k] * w[k] * p[k][0];
                    y += bern[k] * w[k] * p[k][1];
                    d += bern[k] * w[k];
                }
                assert!(close([x / d, y / d], r.eval(a + (b - a) * t), 1e-12));
            }
        }
    }

    #[test]
    fn fixed_point_matches_f64() {
        // Milder weights than W: the I16F16 range (±16383) must hold the bound of the third
        // rational derivative.
        const W: [f64; 6] = [1.0, 1.5, 0.8, 1.0, 1.25, 1.0];
        let r = R2::new(3, &D, &W, &T).unwrap();
        let d16 = D.map(|p| p.map(I16F16::from_num));
        let d32 = D.map(|p| p.map(I32F32::from_num));
        let r16 = Nurbs::<[I16F16; 2], 8, 16>::new(
            3,
            &d16,
            &W.map(I16F16::from_num),
            &T.map(I16F16::from_num),
        )
        .unwrap();
        let r32 = Nurbs::<[I32F32; 2], 8, 16>::new(
            3,
            &d32,
            &W.map(I32F32::from_num),
            &T.map(I32F32::from_num),
        )
        .unwrap();
        assert!(r16.max_deriv_order() >= 3);
        let mut worst = [[0.0_f64; 2]; 3];
        for i in 0..=200 {
            let u = 2.0 * f64::from(i) / 200.0;
            for k in 0..3 {
                let e = r.deriv(u, k);
                let a = r16.deriv(I16F16::from_num(u), k);
                let b = r32.deriv(I32F32::from_num(u), k);
                for j in 0..2 {
                    worst[k][0] = worst[k][0].max((a[j].to_f64() - e[j]).abs());
                    worst[k][1] = worst[k][1].max((b[j].to_f64() - e[j]).abs());
                }
            }
        }
        assert!(
            worst[0][0] < 5e-4 && worst[1][0] < 5e-3 && worst[2][0] < 5e-2,
            "{worst:?}"
        );
        assert!(
            worst[0][1] < 1e-8 && worst[1][1] < 1e-7 && worst[2][1] < 1e-6,
            "{worst:?}"
        );
    }

    #[test]
    fn glam_points() {
        let p = [DVec3::ZERO, DVec3::new(1.0, 2.0, 3.0), DVec3::X, DVec3::Y];
        let r =
            Nurbs::<DVec3, 4, 8>::clamped_uniform(3, &p, &[1.0, 0.5, 2.0, 1.0], 0.0, 1.0).unwrap();
        assert_eq!(r.eval(1.0), DVec3::Y);
        assert_eq!(r.weights(), &[1.0, 0.5, 2.0, 1.0]);
        assert_eq!(r.control_points(), &p);
    }

    #[test]
    fn error_non_positive_weight() {
        assert_eq!(
            R2::new(3, &D, &[1.0, 1.0, -0.5, 1.0, 1.0, 1.0], &T).unwrap_err(),
            Error::NonPositiveWeight { index: 2 }
        );
        assert_eq!(
            R2::new(3, &D, &[1.0, 1.0, 1.0, 1.0, 1.0, 0.0], &T).unwrap_err(),
            Error::NonPositiveWeight { index: 5 }
        );
        let h = [
            Homogeneous {
                weighted: [0.0],
                weight: 1.0,
            },
            Homogeneous {
                weighted: [0.0],
                weight: -1.0,
            },
        ];
        let b = BSpline::<_, 4, 8>::clamped_uniform(1, &h, 0.0, 1.0).unwrap();
        assert_eq!(
            Nurbs::<[f64; 1], 4, 8>::from_homogeneous(b).unwrap_err(),
            Error::NonPositiveWeight { index: 1 }
        );
    }

    #[test]
    fn error_weights_mismatch_non_finite_and_capacity() {
        assert_eq!(
            R2::new(3, &D, &W[..5], &T).unwrap_err(),
            Error::LengthMismatch {
                expected: 6,
                found: 5
            }
        );
        let mut w = W;
        w[1] = f64::NAN;
        assert_eq!(R2::new(3, &D, &w, &T).unwrap_err(), Error::NonFinite);
        assert_eq!(
            Nurbs::<[f64; 2], 5, 32>::new(3, &D, &W, &T).unwrap_err(),
            Error::CapacityExceeded {
                capacity: 5,
                required: 6
            }
        );
        assert_eq!(
            R2::new(3, &D, &W, &T[..9]).unwrap_err(),
            Error::KnotCount {
                expected: 10,
                found: 9
            }
        );
    }

    #[test]
    fn error_out_of_range_in_fixed_point() {
        let d = D.map(|p| p.map(I16F16::from_num));
        let t = T.map(I16F16::from_num);
        // A weight of a few ε is not a safe divisor after rounding.
        let mut w = W.map(I16F16::from_num);
        w[3] = I16F16::from_bits(8);
        assert_eq!(
            Nurbs::<[I16F16; 2], 8, 16>::new(3, &d, &w, &t).unwrap_err(),
            Error::OutOfRange
        );
        // w·P out of range.
        let mut w = W.map(I16F16::from_num);
        w[2] = I16F16::from_num(5000);
        assert_eq!(
            Nurbs::<[I16F16; 2], 8, 16>::new(3, &d, &w, &t).unwrap_err(),
            Error::OutOfRange
        );
        // Rational derivatives up to the degree too large: tiny weight next to a huge one.
        let mut w = W.map(I16F16::from_num);
        w[2] = I16F16::from_num(0.01);
        w[3] = I16F16::from_num(100);
        assert_eq!(
            Nurbs::<[I16F16; 2], 8, 16>::new(3, &d, &w, &t).unwrap_err(),
            Error::OutOfRange
        );
    }
}

#[cfg(test)]
mod range_tests {
    use super::*;
    use crate::scalar::I16F16;

    /// Whatever the constructor accepts evaluates every rational derivative up to 8 without an
    /// overflow panic (debug builds of `fixed` panic on overflow) or a division by zero.
    #[test]
    fn accepted_fixed_point_nurbs_never_overflow() {
        let f = |x: f64| I16F16::from_num(x);
        let mut accepted = 0;
        let mut limited = 0;
        for scale in [1.0, 50.0, 2000.0] {
            for span in [1.0 / 16.0, 1.0, 4.0] {
                for wmax in [1.0, 3.0, 40.0] {
                    for g in 1..=3 {
                        let pts: [[I16F16; 2]; 6] = core::array::from_fn(|i| {
                            let s = if i % 2 == 0 { 1.0 } else { -1.0 };
                            [f(scale * s), f(scale * (i as f64 / 6.0))]
                        });
                        let w: [I16F16; 6] =
                            core::array::from_fn(|i| if i % 3 == 1 { f(wmax) } else { f(0.5) });
                        let Ok(c) = Nurbs::<[I16F16; 2], 8, 16>::clamped_uniform(
                            g,
                            &pts,
                            &w,
                            f(0.0),
                            f(span * 3.0),
                        ) else {
                            continue;
                        };
                        accepted += 1;
                        if c.max_deriv_order() < BSPLINE_MAX_DEGREE {
                            limited += 1;
                        }
                        let (lo, hi) = c.domain();
                        let mut all = [[I16F16::ZERO; 2]; 9];
                        for i in -10..=210 {
                            let u = lo + (hi - lo) * I16F16::from_num(i) / 200;
                            c.derivatives(u, &mut all);
                            for (k, d) in all.iter().enumerate() {
                                assert_eq!(c.deriv(u, k), *d);
                            }
                        }
                    }
                }
            }
        }
        assert!(accepted >= 20 && limited >= 5, "{accepted} {limited}");
    }
}
