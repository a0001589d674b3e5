//! Continuity of a join between two curve segments: parametric `C^k` and geometric `G^k`
//! (Farin, *Curves and Surfaces for CAGD*, 5th ed., §7.2 "Smoothness Conditions"; Barsky &
//! DeRose, "Geometric Continuity of Parametric Curves: Three Equivalent Characterizations",
//! *IEEE Computer Graphics and Applications* 9(6), 1989).
//!
//! A join is classified by how many derivatives of the two segments agree at the joint:
//!
//! - **`C^k`** (parametric continuity): the derivatives `c, c', …, c^(k)` *with respect to the
//!   parameter* are equal, in direction and length.
//! - **`G^k`** (geometric continuity): the derivatives *with respect to arc length* are equal.
//!   `G⁰`: the same point. `G¹`: the same unit tangent `T = c'/|c'|`.
//!   `G²`: in addition the same curvature vector `κN`. `G³`: in addition the same `d(κN)/ds`
//!   (the Frenet–Serret frame: do Carmo, *Differential Geometry of Curves and Surfaces*, §1-5).
//!
//! The two notions differ: the curve `(t³, t²)` is `C^∞` at `t = 0` but not even
//! `G¹` — its tangent vanishes and its direction flips (a cusp); a circle continued with a
//! faster parameterization is `G¹` (indeed `G³`) but only `C⁰`. When the tangent is not zero,
//! `C^k` implies `G^k`.
//!
//! The formulas and the tolerance rule are documented at [`classify_derivatives`]. The work
//! is constant per join (four derivatives on each side); [`classify_breaks`] visits the
//! `piece_count − 1` inner joins once.

use crate::curve::{ParamCurveDeriv, PieceDeriv, ScalarOf};
use crate::error::Error;
use crate::point::Point;

use super::{c64, check_resolvable, greater, norm64};
use crate::scalar::Scalar;

/// The highest derivative order compared by the classification.
const MAX_ORDER: u8 = 3;

/// A comparison tolerance for values of `S`: finite, positive and not below the finest
/// relative spacing of `S` (`ε_S` for floats, `ε_S / LIMIT` for fixed-point, whose values
/// are equally spaced up to [`Scalar::LIMIT`]; never below `f64`'s `ε`).
fn check_tolerance<S: Scalar>(tolerance: f64) -> Result<(), Error> {
    let floor = if S::IS_FIXED {
        (S::EPSILON / S::LIMIT).max(f64::EPSILON)
    } else {
        S::EPSILON
    };
    check_resolvable::<S>(tolerance, floor)
}

/// How smoothly two curve segments join: the highest parametric (`C^k`) and geometric
/// (`G^k`) order that holds, up to order 3 (Farin, *Curves and Surfaces for CAGD*, 5th ed.,
/// §7.2; Barsky & DeRose, *IEEE CG&A* 9(6), 1989).
///
/// A join is classified by how many derivatives of the two segments agree at the joint:
///
/// - **`C^k`** (parametric continuity): the derivatives `c, c', …, c^(k)` *with respect to the
///   parameter* are equal, in direction and length.
/// - **`G^k`** (geometric continuity): the derivatives *with respect to arc length* are equal.
///   `G⁰`: the same point. `G¹`: the same unit tangent `T = c'/|c'|`.
///   `G²`: in addition the same curvature vector `κN`. `G³`: in addition the same `d(κN)/ds`.
///
/// The two notions differ: the curve `(t³, t²)` is `C^∞` at `t = 0` but not even
/// `G¹` — its tangent vanishes and its direction flips (a cusp); a circle continued with a
/// faster parameterization is `G¹` (indeed `G³`) but only `C⁰`. When the tangent is not zero,
/// `C^k` implies `G^k`.
///
/// `None` means the segments do not even meet (not `C⁰`, not `G⁰`); `Some(3)` means "order 3
/// or higher" — derivatives above the third are not compared, so a `C^∞` join reports
/// `Some(3)`. Obtained from [`classify_join`], [`classify_derivatives`] or
/// [`classify_breaks`].
///
/// ```
/// use strak_curves::Continuity;
///
/// // The cusp (t³, t²) at t = 0: C^∞ (reported as C³) but only G⁰.
/// let cusp = Continuity { parametric: Some(3), geometric: Some(0) };
/// assert!(cusp.is_c(3) && cusp.is_g(0) && !cusp.is_g(1));
/// assert!(!Continuity::DISCONNECTED.is_g(0));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Continuity {
    /// The largest `k ≤ 3` such that the join is `C^k` (derivatives with respect to the
    /// parameter agree up to order `k`); `None` if the end points differ.
    pub parametric: Option<u8>,
    /// The largest `k ≤ 3` such that the join is `G^k` (derivatives with respect to arc
    /// length agree up to order `k`); `None` if the end points differ.
    pub geometric: Option<u8>,
}

impl Continuity {
    /// The highest order the classification reports (`3`).
    pub const MAX_ORDER: u8 = MAX_ORDER;

    /// Segments that do not meet: neither `C⁰` nor `G⁰`.
    pub const DISCONNECTED: Self = Self {
        parametric: None,
        geometric: None,
    };

    /// The best result, `C³` and `G³` (or higher); what [`classify_breaks`] reports for a
    /// curve without inner piece boundaries.
    pub const SMOOTH: Self = Self {
        parametric: Some(MAX_ORDER),
        geometric: Some(MAX_ORDER),
    };

    /// Whether the join is at least `C^k`. Always `false` for `k > 3`, which is not checked.
    #[inline]
    pub fn is_c(self, k: u8) -> bool {
        k <= MAX_ORDER && matches!(self.parametric, Some(p) if p >= k)
    }

    /// Whether the join is at least `G^k`. Always `false` for `k > 3`, which is not checked.
    #[inline]
    pub fn is_g(self, k: u8) -> bool {
        k <= MAX_ORDER && matches!(self.geometric, Some(g) if g >= k)
    }

    /// The weaker of two classifications, order by order (used for the minimum over several
    /// joins).
    #[inline]
    pub fn min(self, other: Self) -> Self {
        Self {
            parametric: self.parametric.min(other.parametric),
            geometric: self.geometric.min(other.geometric),
        }
    }
}

/// `|x − y| ≤ tol · max(|x|, |y|, 1)` for two vectors given coordinate-wise.
fn close(dim: usize, x: impl Fn(usize) -> f64, y: impl Fn(usize) -> f64, tol: f64) -> bool {
    let (mut dd, mut xx, mut yy) = (0.0, 0.0, 0.0);
    for i in 0..dim {
        let (a, b) = (x(i), y(i));
        dd += (a - b) * (a - b);
        xx += a * a;
        yy += b * b;
    }
    let scale = libm::sqrt(xx).max(libm::sqrt(yy)).max(1.0);
    libm::sqrt(dd) <= tol * scale
}

/// The arc-length quantities of one side of a join, in `f64`, from `c, c', c'', c'''`.
struct Frame<'a, P> {
    d: &'a [P; 4],
    /// `v = |c'|`.
    v: f64,
    /// `c''·T`.
    at: f64,
    /// `c'''·T`.
    bt: f64,
    /// `|κN|²`.
    kappa2: f64,
}

impl<'a, P: Point> Frame<'a, P> {
    fn new(d: &'a [P; 4]) -> Self {
        let v = norm64(&d[1]);
        let (mut at, mut bt) = (0.0, 0.0);
        for i in 0..P::DIM {
            let t = c64(&d[1], i) / v;
            at += c64(&d[2], i) * t;
            bt += c64(&d[3], i) * t;
        }
        let mut f = Self {
            d,
            v,
            at,
            bt,
            kappa2: 0.0,
        };
        f.kappa2 = (0..P::DIM).map(|i| f.curvature(i) * f.curvature(i)).sum();
        f
    }

    /// Coordinate `i` of the unit tangent `T = c'/v`.
    fn tangent(&self, i: usize) -> f64 {
        c64(&self.d[1], i) / self.v
    }

    /// Coordinate `i` of the curvature vector `κN = (c'' − (c''·T)T)/v²`.
    fn curvature(&self, i: usize) -> f64 {
        (c64(&self.d[2], i) - self.at * self.tangent(i)) / (self.v * self.v)
    }

    /// Coordinate `i` of `d(κN)/ds = (c''' − (c'''·T)T)/v³ − 3(c''·T)/v² κN − |κN|² T`.
    fn curvature_rate(&self, i: usize) -> f64 {
        let v2 = self.v * self.v;
        let t = self.tangent(i);
        (c64(&self.d[3], i) - self.bt * t) / (v2 * self.v)
            - 3.0 * self.at / v2 * self.curvature(i)
            - self.kappa2 * t
    }
}

/// Classifies a join from the derivatives at the joint: `left = [c, c', c'', c''']` of the
/// first segment at its end, `right` the same for the second segment at its start
/// (derivatives with respect to each segment's own parameter).
///
/// Returns [`Error::InvalidArgument`] when `tolerance` is not finite and positive. `G^k` is
/// reported at least as high as `C^k` whenever both tangents are non-zero (`C^k ⇒ G^k`), and
/// at most `0` when a tangent is zero.
///
/// # Formulas (any dimension)
///
/// With `v = |c'|` and `T = c'/v`, the derivatives with respect to arc length `s`
/// (`d/ds = (1/v) d/du`) are
///
/// ```text
/// dc/ds       = T
/// d²c/ds²     = κN = (c'' − (c''·T) T) / v²
/// d³c/ds³     = d(κN)/ds = (c''' − (c'''·T) T) / v³ − 3 (c''·T)/v² · κN − |κN|² T
/// ```
///
/// Derivation of the last line: put `P = c'' − (c''·T)T`, so `κN = P/v²`. With
/// `dv/du = c''·T` and `dT/du = P/v`, differentiating gives
/// `dP/du = c''' − (c'''·T)T − (|P|²/v) T − (c''·T) P/v`, hence
/// `d(κN)/du = dP/du / v² − 2 (c''·T) P / v³`, and dividing by `v` gives the formula above.
/// Its tangential part `−κ² T` and normal part agree with Frenet–Serret
/// (`d(κN)/ds = −κ²T + κ'N + κτB`).
///
/// # Tolerance
///
/// Every comparison of two vectors `x` (end of the first segment) and `y` (start of the
/// second) is relative to their magnitude with an absolute floor of one coordinate unit:
/// they count as equal when `|x − y| ≤ tolerance · max(|x|, |y|, 1)`. Unit tangents have
/// magnitude one, so they are compared absolutely. A tangent counts as zero — and the join
/// as not `G¹` — when `|c'| ≤ tolerance · max(|c'_a|, |c'_b|, 1)` on either side.
/// All of this is computed in `f64` from the curves' derivatives.
///
/// ```
/// use strak_curves::classify_derivatives;
///
/// // Unit circle at angle 0, continued at twice the speed: G³ but only C⁰.
/// let left = [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]];
/// let right = [[1.0, 0.0], [0.0, 2.0], [-4.0, 0.0], [0.0, -8.0]];
/// let c = classify_derivatives(&left, &right, 1e-12)?;
/// assert_eq!((c.parametric, c.geometric), (Some(0), Some(3)));
/// # Ok::<(), strak_curves::Error>(())
/// ```
pub fn classify_derivatives<P: Point>(
    left: &[P; 4],
    right: &[P; 4],
    tolerance: f64,
) -> Result<Continuity, Error> {
    check_tolerance::<P::Scalar>(tolerance)?;
    let dim = P::DIM;
    let same = |k: usize| close(dim, |i| c64(&left[k], i), |i| c64(&right[k], i), tolerance);
    if !same(0) {
        return Ok(Continuity::DISCONNECTED);
    }

    let mut parametric = 0;
    while parametric < MAX_ORDER && same(usize::from(parametric) + 1) {
        parametric += 1;
    }

    let (l, r) = (Frame::new(left), Frame::new(right));
    let zero = tolerance * l.v.max(r.v).max(1.0);
    // A NaN speed counts as zero.
    if !greater(l.v, zero) || !greater(r.v, zero) {
        return Ok(Continuity {
            parametric: Some(parametric),
            geometric: Some(0),
        });
    }
    let mut geometric = 0;
    if close(dim, |i| l.tangent(i), |i| r.tangent(i), tolerance) {
        geometric = 1;
        if close(dim, |i| l.curvature(i), |i| r.curvature(i), tolerance) {
            geometric = 2;
            if close(
                dim,
                |i| l.curvature_rate(i),
                |i| r.curvature_rate(i),
                tolerance,
            ) {
                geometric = 3;
            }
        }
    }
    Ok(Continuity {
        parametric: Some(parametric),
        geometric: Some(geometric.max(parametric)),
    })
}

/// The derivatives `[c, c', c'', c''']` of `curve` at `u`.
fn jet<C: ParamCurveDeriv>(curve: &C, u: ScalarOf<C>) -> [C::Point; 4] {
    core::array::from_fn(|k| curve.deriv(u, k))
}

/// Classifies the join of segment `a` (at the end of its domain) to segment `b` (at the
/// start of its domain) as `C^k` / `G^k` for `k ≤ 3` (see [`Continuity`]).
///
/// The two curves may be of different types; each is differentiated with respect to its own
/// parameter. The derivatives of `a` are taken at its domain end (its last piece), those of
/// `b` at its domain start. Tolerance as in [`classify_derivatives`]: relative to the
/// magnitude of the compared derivatives with an absolute floor of one unit; a non-finite or
/// non-positive `tolerance` gives [`Error::InvalidArgument`].
///
/// ```
/// use strak_curves::{classify_join, ParamCurve, ParamCurveDeriv};
///
/// /// The cusp curve c(t) = (t³, t²) on [a, b].
/// struct Cusp(f64, f64);
/// impl ParamCurve for Cusp {
///     type Point = [f64; 2];
///     fn domain(&self) -> (f64, f64) { (self.0, self.1) }
///     fn eval(&self, t: f64) -> [f64; 2] { self.deriv(t, 0) }
/// }
/// impl ParamCurveDeriv for Cusp {
///     fn deriv(&self, t: f64, k: usize) -> [f64; 2] {
///         let t = t.clamp(self.0, self.1);
///         match k {
///             0 => [t * t * t, t * t],
///             1 => [3.0 * t * t, 2.0 * t],
///             2 => [6.0 * t, 2.0],
///             3 => [6.0, 0.0],
///             _ => [0.0, 0.0],
///         }
///     }
/// }
///
/// // Split at t = 0: C^∞ (reported as C³) but not even G¹.
/// let c = classify_join(&Cusp(-1.0, 0.0), &Cusp(0.0, 1.0), 1e-9)?;
/// assert!(c.is_c(3) && !c.is_g(1));
/// # Ok::<(), strak_curves::Error>(())
/// ```
pub fn classify_join<A, B>(a: &A, b: &B, tolerance: f64) -> Result<Continuity, Error>
where
    A: ParamCurveDeriv,
    B: ParamCurveDeriv<Point = A::Point>,
{
    check_tolerance::<ScalarOf<A>>(tolerance)?;
    let left = jet(a, a.domain().1);
    let right = jet(b, b.domain().0);
    classify_derivatives(&left, &right, tolerance)
}

/// The weakest continuity over the inner piece boundaries of a piecewise curve: the minimum
/// of [`classify_derivatives`] over every boundary between piece `i` (left limit, from
/// [`PieceDeriv::piece_deriv`] at its end) and piece `i + 1` (at its start).
///
/// A curve with a single piece has no inner boundary and gives [`Continuity::SMOOTH`].
/// Tolerance as in [`classify_derivatives`]; a non-finite or non-positive `tolerance` gives
/// [`Error::InvalidArgument`].
///
/// ```
/// use strak_curves::{classify_breaks, ParamCurve, ParamCurveDeriv, PieceDeriv};
///
/// /// (u, |u|³) on [-1, 1] with pieces [-1, 0] and [0, 1]: C² but not C³ at u = 0.
/// struct Kink;
/// impl ParamCurve for Kink {
///     type Point = [f64; 2];
///     fn domain(&self) -> (f64, f64) { (-1.0, 1.0) }
///     fn eval(&self, u: f64) -> [f64; 2] { self.deriv(u, 0) }
///     fn piece_count(&self) -> usize { 2 }
///     fn piece_domain(&self, i: usize) -> (f64, f64) {
///         if i == 0 { (-1.0, 0.0) } else { (0.0, 1.0) }
///     }
/// }
/// impl ParamCurveDeriv for Kink {
///     fn deriv(&self, u: f64, k: usize) -> [f64; 2] {
///         self.piece_deriv(usize::from(u >= 0.0), u, k)
///     }
/// }
/// impl PieceDeriv for Kink {
///     fn piece_deriv(&self, i: usize, u: f64, k: usize) -> [f64; 2] {
///         let (a, b) = self.piece_domain(i);
///         let (u, s) = (u.clamp(a, b), if i == 0 { -1.0 } else { 1.0 });
///         match k {
///             0 => [u, s * u * u * u],
///             1 => [1.0, s * 3.0 * u * u],
///             2 => [0.0, s * 6.0 * u],
///             3 => [0.0, s * 6.0],
///             _ => [0.0, 0.0],
///         }
///     }
/// }
/// let c = classify_breaks(&Kink, 1e-9)?;
/// assert_eq!((c.parametric, c.geometric), (Some(2), Some(2)));
/// # Ok::<(), strak_curves::Error>(())
/// ```
pub fn classify_breaks<C: PieceDeriv>(curve: &C, tolerance: f64) -> Result<Continuity, Error> {
    check_tolerance::<ScalarOf<C>>(tolerance)?;
    let mut worst = Continuity::SMOOTH;
    for i in 1..curve.piece_count() {
        let (_, end) = curve.piece_domain(i - 1);
        let (start, _) = curve.piece_domain(i);
        let left: [C::Point; 4] = core::array::from_fn(|k| curve.piece_deriv(i - 1, end, k));
        let right: [C::Point; 4] = core::array::from_fn(|k| curve.piece_deriv(i, start, k));
        worst = worst.min(classify_derivatives(&left, &right, tolerance)?);
    }
    Ok(worst)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::testcurves::{FnCurve, PolyCurve, arc};
    use crate::curve::ParamCurve;
    use core::f64::consts::{FRAC_PI_2, PI};

    fn cg(c: Continuity) -> (Option<u8>, Option<u8>) {
        (c.parametric, c.geometric)
    }

    /// The cusp curve c2(t) = (t³, t²) split at t = 0.
    fn cusp(a: f64, b: f64) -> PolyCurve<f64> {
        PolyCurve::single(a, b, &[[0.0, 0.0], [0.0, 0.0], [0.0, 1.0], [1.0, 0.0]])
    }

    /// The circle c1(t) = (2 cos t − 2, −2 sin t), optionally reparameterized
    /// t = speed · τ.
    fn c1(speed: f64, a: f64, b: f64) -> FnCurve<impl Fn(f64, usize) -> [f64; 2], 2> {
        FnCurve {
            f: move |tau: f64, k: usize| {
                let t = speed * tau;
                let f = speed.powi(k as i32);
                let ph = t + k as f64 * FRAC_PI_2;
                let off = if k == 0 { 2.0 } else { 0.0 };
                [f * 2.0 * libm::cos(ph) - off, -f * 2.0 * libm::sin(ph)]
            },
            a,
            b,
        }
    }

    #[test]
    fn cusp_is_c_infinity_but_not_g1() {
        let c = classify_join(&cusp(-1.0, 0.0), &cusp(0.0, 1.0), 1e-12).unwrap();
        assert_eq!(cg(c), (Some(3), Some(0)));
        assert!(c.is_c(3) && c.is_g(0) && !c.is_g(1));
    }

    #[test]
    fn circle_reparameterized_is_g1_but_only_c0() {
        // c1 on [-π/2, 0], continued by c1(2τ) on [0, π/4]: same point (0, 0), tangent
        // (0, −2) vs (0, −4), the same circle — G³ (hence G¹) but only C⁰.
        let a = c1(1.0, -FRAC_PI_2, 0.0);
        let b = c1(2.0, 0.0, PI / 4.0);
        assert_eq!(a.eval(0.0), [0.0, 0.0]);
        let c = classify_join(&a, &b, 1e-12).unwrap();
        assert_eq!(cg(c), (Some(0), Some(3)));
        assert!(c.is_g(1) && !c.is_c(1));
        // The same continuation at the same speed is C³.
        let c = classify_join(&a, &c1(1.0, 0.0, 1.0), 1e-12).unwrap();
        assert_eq!(cg(c), (Some(3), Some(3)));
    }

    #[test]
    fn disconnected_segments() {
        let c = classify_join(&cusp(-1.0, 0.0), &cusp(0.5, 1.0), 1e-9).unwrap();
        assert_eq!(c, Continuity::DISCONNECTED);
        assert!(!c.is_c(0) && !c.is_g(0));
    }

    #[test]
    fn cubic_c1_versus_g1() {
        // a(u) = (u, u³) on [-1, 0]; at 0: c' = (1, 0), c'' = 0.
        let a =
            PolyCurve::<f64>::single(-1.0, 0.0, &[[0.0, 0.0], [1.0, 0.0], [0.0, 0.0], [0.0, 1.0]]);
        // b(u) = (u + u², u²): c' = (1, 0), c'' = (2, 2) — C¹, not C²; κN = (0, 2) ≠ 0: G¹.
        let b = PolyCurve::<f64>::single(0.0, 1.0, &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]);
        assert_eq!(
            cg(classify_join(&a, &b, 1e-12).unwrap()),
            (Some(1), Some(1))
        );
        // b2(u) = (2u, u³): tangent (2, 0), same direction, twice as long: G¹ (and G², as
        // both curvatures are zero; G³: d(κN)/ds = c'''⊥/v³ = (0,6)/8 vs (0,6)) → G².
        let b2 =
            PolyCurve::<f64>::single(0.0, 1.0, &[[0.0, 0.0], [2.0, 0.0], [0.0, 0.0], [0.0, 1.0]]);
        assert_eq!(
            cg(classify_join(&a, &b2, 1e-12).unwrap()),
            (Some(0), Some(2))
        );
        // b3(u) = (u, u² ): tangent (1, 0), c'' = (0, 2): C¹, G¹, curvature 2 vs 0 → not G².
        let b3 = PolyCurve::<f64>::single(0.0, 1.0, &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
        assert_eq!(
            cg(classify_join(&a, &b3, 1e-12).unwrap()),
            (Some(1), Some(1))
        );
        // b4(u) = (u, −u²·0 + u): tangent (1, 1): not G¹, only C⁰ / G⁰.
        let b4 = PolyCurve::<f64>::single(0.0, 1.0, &[[0.0, 0.0], [1.0, 1.0]]);
        assert_eq!(
            cg(classify_join(&a, &b4, 1e-12).unwrap()),
            (Some(0), Some(0))
        );
        // The same cubic continued: C³.
        let a2 =
            PolyCurve::<f64>::single(0.0, 1.0, &[[0.0, 0.0], [1.0, 0.0], [0.0, 0.0], [0.0, 1.0]]);
        assert_eq!(
            cg(classify_join(&a, &a2, 1e-12).unwrap()),
            (Some(3), Some(3))
        );
    }

    #[test]
    fn opposite_tangent_is_not_g1() {
        // a(u) = (u, 0) on [-1, 0] followed by b(u) = (−u, 0): the path turns back.
        let a = PolyCurve::<f64>::single(-1.0, 0.0, &[[0.0, 0.0], [1.0, 0.0]]);
        let b = PolyCurve::<f64>::single(0.0, 1.0, &[[0.0, 0.0], [-1.0, 0.0]]);
        assert_eq!(cg(classify_join(&a, &b, 1e-9).unwrap()), (Some(0), Some(0)));
    }

    #[test]
    fn arc_to_arc_g2_joins() {
        // Radius 1 arc ending at angle 0, continued by the same circle at another speed: G³;
        // by a radius-2 circle tangent at (1, 0) (centre (−1, 0)): G¹ only (κ 1 vs 1/2).
        let a = arc(1.0, -1.0, 0.0);
        let b = FnCurve {
            f: |t: f64, k: usize| {
                let r = 2.0;
                let ph = t + k as f64 * FRAC_PI_2;
                let off = if k == 0 { -1.0 } else { 0.0 };
                [r * libm::cos(ph) + off, r * libm::sin(ph)]
            },
            a: 0.0,
            b: 1.0,
        };
        assert_eq!(
            cg(classify_join(&a, &b, 1e-12).unwrap()),
            (Some(0), Some(1))
        );
        // A radius-1 arc of a differently parameterized circle, t = 3τ + τ² (not uniform):
        // speeds and accelerations differ, geometry is identical: G³, C⁰.
        let c = FnCurve {
            f: |tau: f64, k: usize| {
                // c(τ) = (cos φ, sin φ), φ = 3τ + τ²; derivatives by the chain rule.
                let (p, p1, p2) = (3.0 * tau + tau * tau, 3.0 + 2.0 * tau, 2.0);
                let (c, s) = (libm::cos(p), libm::sin(p));
                match k {
                    0 => [c, s],
                    1 => [-s * p1, c * p1],
                    2 => [-c * p1 * p1 - s * p2, -s * p1 * p1 + c * p2],
                    3 => [
                        s * p1 * p1 * p1 - 3.0 * c * p1 * p2,
                        -c * p1 * p1 * p1 - 3.0 * s * p1 * p2,
                    ],
                    _ => [0.0, 0.0],
                }
            },
            a: 0.0,
            b: 1.0,
        };
        assert_eq!(
            cg(classify_join(&a, &c, 1e-12).unwrap()),
            (Some(0), Some(3))
        );
    }

    #[test]
    fn g2_but_not_g3() {
        // a(u) = (u, u²) on [-1, 0], b(u) = (u, u² + u³): C², G², c''' differs.
        let a = PolyCurve::<f64>::single(-1.0, 0.0, &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
        let b =
            PolyCurve::<f64>::single(0.0, 1.0, &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.0, 1.0]]);
        assert_eq!(
            cg(classify_join(&a, &b, 1e-12).unwrap()),
            (Some(2), Some(2))
        );
        // b reparameterized u = 2w: (2w, 4w² + 8w³) — only C⁰, still G² and not G³.
        let b2 =
            PolyCurve::<f64>::single(0.0, 0.5, &[[0.0, 0.0], [2.0, 0.0], [0.0, 4.0], [0.0, 8.0]]);
        assert_eq!(
            cg(classify_join(&a, &b2, 1e-12).unwrap()),
            (Some(0), Some(2))
        );
        // a reparameterized u = 2w, w ∈ [-1/2, 0]: (2w, 4w²) followed by b2: G² (C²? no:
        // c' = (2,0) both, c'' = (0,8) both, c''' = 0 vs (0,48)) → C², G².
        let a2 = PolyCurve::<f64>::single(-0.5, 0.0, &[[0.0, 0.0], [2.0, 0.0], [0.0, 4.0]]);
        assert_eq!(
            cg(classify_join(&a2, &b2, 1e-12).unwrap()),
            (Some(2), Some(2))
        );
    }

    #[test]
    fn g3_join_of_a_helix_with_nonuniform_parameter() {
        // Helix (cos t, sin t, t/2) in 3-D, second half reparameterized t = 2τ + τ²:
        // G³ but only C⁰, checks the formula in three dimensions.
        let helix = |t: f64, k: usize| -> [f64; 3] {
            let ph = t + k as f64 * FRAC_PI_2;
            let z = match k {
                0 => t / 2.0,
                1 => 0.5,
                _ => 0.0,
            };
            [libm::cos(ph), libm::sin(ph), z]
        };
        let a = FnCurve {
            f: helix,
            a: -1.0,
            b: 0.0,
        };
        let b = FnCurve {
            f: move |tau: f64, k: usize| -> [f64; 3] {
                // Faà di Bruno up to order 3 for t = 2τ + τ²: t' = 2 + 2τ, t'' = 2, t''' = 0.
                let (t, t1, t2) = (2.0 * tau + tau * tau, 2.0 + 2.0 * tau, 2.0);
                let d = |j: usize| helix(t, j);
                let comb = |f: &dyn Fn(usize) -> f64| match k {
                    0 => f(0),
                    1 => f(1) * t1,
                    2 => f(2) * t1 * t1 + f(1) * t2,
                    3 => f(3) * t1 * t1 * t1 + 3.0 * f(2) * t1 * t2,
                    _ => 0.0,
                };
                core::array::from_fn(|i| comb(&|j| d(j)[i]))
            },
            a: 0.0,
            b: 1.0,
        };
        assert_eq!(
            cg(classify_join(&a, &b, 1e-12).unwrap()),
            (Some(0), Some(3))
        );
        // A helix with another pitch: same tangent? No — tangent (0, 1, 1/2) vs (0, 1, 1):
        // not G¹.
        let c = FnCurve {
            f: |t: f64, k: usize| -> [f64; 3] {
                let ph = t + k as f64 * FRAC_PI_2;
                let z = if k == 1 {
                    1.0
                } else if k == 0 {
                    t
                } else {
                    0.0
                };
                [libm::cos(ph), libm::sin(ph), z]
            },
            a: 0.0,
            b: 1.0,
        };
        assert_eq!(
            cg(classify_join(&a, &c, 1e-12).unwrap()),
            (Some(0), Some(0))
        );
    }

    #[test]
    fn curvature_rate_matches_finite_differences() {
        // A 2-D polynomial curve with non-constant speed; compare d(κN)/ds from the formula
        // with a central difference of κN in u divided by the speed.
        let c = PolyCurve::<f64>::single(
            -1.0,
            1.0,
            &[[0.1, 0.0], [1.0, 0.3], [0.4, -0.7], [0.2, 0.5], [-0.3, 0.1]],
        );
        let frame_at = |u: f64| jet(&c, u);
        let u = 0.3;
        let h = 1e-5;
        let (jm, j0, jp) = (frame_at(u - h), frame_at(u), frame_at(u + h));
        let (fm, f0, fp) = (Frame::new(&jm), Frame::new(&j0), Frame::new(&jp));
        for i in 0..2 {
            let fd = (fp.curvature(i) - fm.curvature(i)) / (2.0 * h) / f0.v;
            assert!(
                (fd - f0.curvature_rate(i)).abs() < 1e-6,
                "{fd} vs {}",
                f0.curvature_rate(i)
            );
        }
        // And κN against the textbook signed curvature (x'y'' − y'x'')/v³ in 2-D.
        let [_, d1, d2, _] = j0;
        let kappa = (d1[0] * d2[1] - d1[1] * d2[0]) / f0.v.powi(3);
        let kn = libm::sqrt(f0.kappa2);
        assert!((kn - kappa.abs()).abs() < 1e-12);
    }

    #[test]
    fn tolerance_behaviour() {
        // Tangent (1, 0) against (1, δ): G¹/C¹ exactly when δ is within the tolerance.
        let left = [[0.0, 0.0], [1.0, 0.0], [0.0, 0.0], [0.0, 0.0]];
        let right = |d: f64| [[0.0, 0.0], [1.0, d], [0.0, 0.0], [0.0, 0.0]];
        let c = classify_derivatives(&left, &right(1e-7), 1e-6).unwrap();
        assert!(c.is_c(1) && c.is_g(1));
        let c = classify_derivatives(&left, &right(1e-5), 1e-6).unwrap();
        assert!(!c.is_c(1) && !c.is_g(1) && c.is_g(0));
        // Relative: a tangent of length 1e6 tolerates an absolute difference of 1e6·tol.
        let big_l = [[0.0, 0.0], [1e6, 0.0], [0.0, 0.0], [0.0, 0.0]];
        let big_r = [[0.0, 0.0], [1e6, 0.5], [0.0, 0.0], [0.0, 0.0]];
        assert!(classify_derivatives(&big_l, &big_r, 1e-6).unwrap().is_c(1));
        assert!(!classify_derivatives(&big_l, &big_r, 1e-7).unwrap().is_c(1));
        // Absolute floor: tiny values are compared with an absolute tolerance.
        let p = [[1e-9, 0.0], [1.0, 0.0], [0.0, 0.0], [0.0, 0.0]];
        assert!(classify_derivatives(&left, &p, 1e-8).unwrap().is_c(3));
        assert!(!classify_derivatives(&left, &p, 1e-10).unwrap().is_c(0));
        // Positions: a gap of 1e-3 at coordinates near 1e4 is within 1e-6 relative.
        let far_l = [[1e4, 0.0], [1.0, 0.0], [0.0, 0.0], [0.0, 0.0]];
        let far_r = [[1e4 + 1e-3, 0.0], [1.0, 0.0], [0.0, 0.0], [0.0, 0.0]];
        assert!(classify_derivatives(&far_l, &far_r, 1e-6).unwrap().is_c(3));
        assert!(!classify_derivatives(&far_l, &far_r, 1e-8).unwrap().is_c(0));
    }

    #[test]
    fn c_implies_g_for_nonzero_tangent() {
        // A tangent of length 0.01 compared with tolerance 0.1: the parameter derivatives
        // agree within the absolute floor, so C¹ holds; the tangent counts as zero → G⁰.
        let l = [[0.0, 0.0], [0.01, 0.0], [0.0, 0.0], [0.0, 0.0]];
        let r = [[0.0, 0.0], [0.0, 0.01], [0.0, 0.0], [0.0, 0.0]];
        assert_eq!(
            cg(classify_derivatives(&l, &r, 0.1).unwrap()),
            (Some(3), Some(0))
        );
        // Tangent of length 0.5 and 0.5 + small, directions off by a bit less than the
        // tolerance after normalization: C¹ holds, so G¹ is reported too.
        let l = [[0.0, 0.0], [0.5, 0.0], [0.0, 0.0], [0.0, 0.0]];
        let r = [[0.0, 0.0], [0.5, 0.009], [0.0, 0.0], [0.0, 0.0]];
        let c = classify_derivatives(&l, &r, 0.01).unwrap();
        assert_eq!(cg(c), (Some(3), Some(3)));
        assert!(!classify_derivatives(&l, &r, 0.001).unwrap().is_g(1));
    }

    #[test]
    fn works_for_f32_and_fixed_point() {
        use crate::scalar::I32F32;
        let a = PolyCurve::<f32>::single(-1.0, 0.0, &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
        let b =
            PolyCurve::<f32>::single(0.0, 1.0, &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.0, 1.0]]);
        assert_eq!(cg(classify_join(&a, &b, 1e-6).unwrap()), (Some(2), Some(2)));
        let a = PolyCurve::<I32F32>::single(-1.0, 0.0, &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
        let b = PolyCurve::<I32F32>::single(0.0, 1.0, &[[0.0, 0.0], [2.0, 0.0], [0.0, 4.0]]);
        assert_eq!(cg(classify_join(&a, &b, 1e-6).unwrap()), (Some(0), Some(3)));
    }

    #[test]
    fn bad_tolerance_is_invalid_argument() {
        let a = cusp(-1.0, 0.0);
        for tol in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert_eq!(classify_join(&a, &a, tol), Err(Error::InvalidArgument));
            assert_eq!(classify_breaks(&a, tol), Err(Error::InvalidArgument));
        }
    }

    #[test]
    fn tolerance_below_the_scalar_spacing_is_an_error() {
        use crate::scalar::I16F16;
        let jet = [[0.0, 0.0], [1.0, 0.0], [0.0, 0.0], [0.0, 0.0]];
        let below = Err(Error::ToleranceBelowResolution { scalar: "f64" });
        assert_eq!(classify_derivatives(&jet, &jet, 1e-17), below);
        assert!(classify_derivatives(&jet, &jet, 4e-16).unwrap().is_c(3));
        let jet32 = jet.map(|p| p.map(|x| x as f32));
        let below = Err(Error::ToleranceBelowResolution { scalar: "f32" });
        assert_eq!(classify_derivatives(&jet32, &jet32, 1e-8), below);
        assert!(classify_derivatives(&jet32, &jet32, 2e-7).unwrap().is_c(3));
        // I16F16 values are 2⁻¹⁶ apart up to 16 383: relative spacing down to 9.3·10⁻¹⁰.
        let fixed = jet.map(|p| p.map(I16F16::from_num));
        let below = Err(Error::ToleranceBelowResolution { scalar: "I16F16" });
        assert_eq!(classify_derivatives(&fixed, &fixed, 1e-10), below);
        assert!(classify_derivatives(&fixed, &fixed, 1e-9).unwrap().is_c(3));
        let a = cusp(-1.0, 0.0);
        assert!(classify_join(&a, &a, 1e-17).is_err());
        assert!(classify_breaks(&a, 1e-17).is_err());
    }

    #[test]
    fn breaks_of_piecewise_curves() {
        // Three pieces: (u, u²) on [0,1], its C¹ continuation with another curvature on
        // [1, 2], then a C⁰ corner on [2, 3].
        let c = PolyCurve::<f64>::new(
            &[0.0, 1.0, 2.0, 3.0],
            &[
                &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
                &[[1.0, 1.0], [1.0, 2.0], [0.0, -1.0]],
                &[[2.0, 2.0], [1.0, 0.0]],
            ],
        );
        // Boundary 1: C¹ (c'' (0,2) vs (0,−2)), G¹. Boundary 2: c' (1, 0) vs (1, 0) — C¹;
        // c'' (0, -2) vs 0 → C¹, G¹. Minimum: C¹, G¹.
        assert_eq!(cg(classify_breaks(&c, 1e-12).unwrap()), (Some(1), Some(1)));
        // Left limit matters: `deriv` at the boundary would see the right piece only.
        let c = PolyCurve::<f64>::new(
            &[0.0, 1.0, 2.0],
            &[&[[0.0, 0.0], [1.0, 0.0]], &[[1.0, 0.0], [0.0, 1.0]]],
        );
        assert_eq!(cg(classify_breaks(&c, 1e-12).unwrap()), (Some(0), Some(0)));
        let single = cusp(0.0, 1.0);
        assert_eq!(classify_breaks(&single, 1e-9).unwrap(), Continuity::SMOOTH);
    }

    #[test]
    fn min_and_predicates() {
        let a = Continuity {
            parametric: Some(2),
            geometric: Some(3),
        };
        let b = Continuity {
            parametric: Some(0),
            geometric: Some(3),
        };
        assert_eq!(a.min(b), b);
        assert_eq!(a.min(Continuity::DISCONNECTED), Continuity::DISCONNECTED);
        assert!(!Continuity::SMOOTH.is_c(4));
        assert!(Continuity::SMOOTH.is_g(3));
    }
}
