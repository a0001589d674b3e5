//! Analysis written once against the curve traits [`ParamCurve`](crate::ParamCurve) and
//! [`ParamCurveDeriv`](crate::ParamCurveDeriv), so that it works for every curve type of the
//! crate (Bézier, B-spline, NURBS, Hermite, cubic splines, …):
//!
//! - continuity of joins, parametric `C^k` and geometric `G^k` (Farin, *Curves and Surfaces
//!   for CAGD*, 5th ed., §7.2 "Smoothness Conditions"; Barsky & DeRose, "Geometric Continuity
//!   of Parametric Curves", IEEE CG&A 9(6), 1989),
//! - flattening into a polyline within a distance tolerance (the error of linear
//!   interpolation, de Boor, *A Practical Guide to Splines*, ch. III "Piecewise Linear
//!   Approximation"),
//! - arc length, its inverse `u(s)`, and an arc-length table with C¹ cubic Hermite
//!   interpolation for time laws.
//!
//! The analysis computes in `f64` internally (curve values are converted with
//! [`Scalar::to_f64`]) and returns curve parameters and points in the curve's own types.
//!
//! # Resolution and iteration bounds
//!
//! Every routine validates its tolerance before it iterates: a tolerance that is not finite
//! and positive is [`Error::InvalidArgument`], one finer than the curve's number type
//! resolves at the curve's size is [`Error::ToleranceBelowResolution`] ([`resolution`] for
//! distances, [`length_resolution`] for lengths). Every loop has a bound that does not depend
//! on the data beyond the stated quantities:
//!
//! | routine | work |
//! |---------|------|
//! | [`classify_derivatives`] | constant: four derivatives per side, three vector comparisons |
//! | [`classify_join`], [`classify_breaks`] | 8 derivative evaluations per join; `piece_count − 1` joins |
//! | [`flatten`], [`flatten_count`] | at most 2¹² intervals (else [`Error::IterationLimit`]), each 2 derivative evaluations and at most `12·64` chord certificates of 8 evaluations; the counts of all pieces together ≤ 2¹⁶ segments (else [`Error::CapacityExceeded`]) |
//! | [`arc_length`], [`arc_length_between`] | per piece 16 parts, bisection depth ≤ 32 and at most 2¹² interval splits, so at most `16·(16 + 2·(2·2¹² + 16))` speed evaluations (else [`Error::IterationLimit`]) |
//! | [`second_derivative_bound`] | a binary search for the first piece, then 28 derivative evaluations per piece the interval touches |
//! | [`param_at_length`] | the piece lengths, then at most 128 Newton or bisection steps, each one arc-length integral |
//! | [`ArcLengthTable::new`] | `2(N − 1)` arc-length integrals and `3N` speed evaluations |
//!
//! Before any of this, [`resolution`] and [`length_resolution`] evaluate the curve at every
//! piece boundary and piece midpoint (`2·piece_count + 2` evaluations).

mod arclength;
mod bound;
mod continuity;
mod counted;
mod flatten;

pub use arclength::*;
pub use bound::second_derivative_bound;
pub use continuity::*;
pub use counted::Counted;
pub use flatten::*;

use crate::curve::{ParamCurve, ScalarOf};
use crate::error::Error;
use crate::point::Point;
use crate::scalar::Scalar;

/// Coordinate `i` of `p` as `f64`.
#[inline]
fn c64<P: Point>(p: &P, i: usize) -> f64 {
    p.coord(i).to_f64()
}

/// `|p|` computed in `f64`.
#[inline]
fn norm64<P: Point>(p: &P) -> f64 {
    let mut acc = 0.0;
    for i in 0..P::DIM {
        let x = c64(p, i);
        acc += x * x;
    }
    libm::sqrt(acc)
}

/// The parameter `u` (an `f64`) as the curve's scalar, rounded to nearest and clamped to
/// `[lo, hi]`.
#[inline]
fn param<S: Scalar>(u: f64, lo: S, hi: S) -> S {
    if u <= lo.to_f64() {
        return lo;
    }
    if u >= hi.to_f64() {
        return hi;
    }
    S::from_f64(u).unwrap_or(lo).clamp_to(lo, hi)
}

/// `a > b`, false when the two are unordered (NaN).
#[inline]
fn greater<T: PartialOrd>(a: T, b: T) -> bool {
    a.partial_cmp(&b) == Some(core::cmp::Ordering::Greater)
}

/// A tolerance or accuracy must be finite and positive.
#[inline]
fn check_positive(tolerance: f64) -> Result<(), Error> {
    if tolerance.is_finite() && tolerance > 0.0 {
        Ok(())
    } else {
        Err(Error::InvalidArgument)
    }
}

/// The spacing of values of magnitude `x` in `S`, and never finer than `f64`'s spacing
/// there (the analysis computes in `f64`): `ε_S` for fixed-point (its values are equally
/// spaced), `ε_S·|x|` for floats.
#[inline]
fn spacing<S: Scalar>(x: f64) -> f64 {
    let x = x.abs();
    let own = if S::IS_FIXED {
        S::EPSILON
    } else {
        S::EPSILON * x
    };
    own.max(f64::EPSILON * x)
}

/// The largest coordinate magnitude and the length of the polyline through the curve's
/// points at every piece boundary and piece midpoint (in parameter order). Both are lower
/// bounds: of the curve's extent and of its arc length.
fn size<C: ParamCurve>(curve: &C) -> (f64, f64) {
    let (start, end) = curve.domain();
    let first = curve.eval(start);
    let (mut extent, mut length, mut prev) = (first.max_abs(), 0.0_f64, first);
    let mut visit = |u: ScalarOf<C>| {
        let p = curve.eval(u);
        extent = extent.max(p.max_abs());
        length += norm64(&p.minus(prev));
        prev = p;
    };
    for i in 0..curve.piece_count() {
        let (a, b) = curve.piece_domain(i);
        let (a, b) = (a.max_of(start), b.min_of(end));
        visit(param(
            0.5 * (a.to_f64() + b.to_f64()),
            a.min_of(b),
            b.max_of(a),
        ));
        visit(b);
    }
    visit(end);
    (extent, length)
}

/// The finest distance the curve's number type resolves on this curve: the spacing of its
/// coordinates at the curve's largest coordinate magnitude, `ε_S` for fixed-point and
/// `ε_S·max|x|` for floats (never below `f64`'s spacing there). The magnitude is taken over
/// the points at every piece boundary and piece midpoint.
///
/// [`flatten`] and [`flatten_count`] reject a tolerance below it with
/// [`Error::ToleranceBelowResolution`]: the vertices themselves are rounded to the point
/// type, so no polyline can be certified closer than that.
///
/// ```
/// use strak_curves::{resolution, BezierChain, I16F16};
/// let p = |x: f64, y: f64| [I16F16::from_num(x), I16F16::from_num(y)];
/// let c = BezierChain::<_, 3, 4>::new(&[p(0.0, 0.0), p(1.0, 2.0), p(2.0, 0.0)])?;
/// assert_eq!(resolution(&c), 1.0 / 65536.0); // I16F16: equally spaced values
/// let f = BezierChain::<_, 3, 4>::new(&[[0.0_f32, 0.0], [1.0, 2.0], [4.0, 0.0]])?;
/// assert_eq!(resolution(&f), 4.0 * f64::from(f32::EPSILON)); // ε·max|x|
/// # Ok::<(), strak_curves::Error>(())
/// ```
pub fn resolution<C: ParamCurve>(curve: &C) -> f64 {
    spacing::<ScalarOf<C>>(size(curve).0)
}

/// The finest arc-length accuracy the curve's number type resolves: the spacing of a value
/// of the curve's length in it, `ε_S` for fixed-point and `ε_S·L` for floats (never below
/// `f64`'s spacing), with `L` the length of the polyline through the points at every piece
/// boundary and piece midpoint (a lower bound of the arc length).
///
/// [`arc_length`], [`arc_length_between`], [`param_at_length`] and [`ArcLengthTable::new`]
/// reject an accuracy below it with [`Error::ToleranceBelowResolution`].
///
/// ```
/// use strak_curves::{length_resolution, Bezier};
/// let line = Bezier::new([[0.0_f32, 0.0], [3.0, 4.0]])?;
/// assert_eq!(length_resolution(&line), 5.0 * f64::from(f32::EPSILON));
/// # Ok::<(), strak_curves::Error>(())
/// ```
pub fn length_resolution<C: ParamCurve>(curve: &C) -> f64 {
    spacing::<ScalarOf<C>>(size(curve).1)
}

/// An arc-length `accuracy` for `curve`: finite, positive and at least
/// [`length_resolution`].
fn check_length_accuracy<C: ParamCurve>(curve: &C, accuracy: f64) -> Result<(), Error> {
    check_positive(accuracy)?;
    check_resolvable::<ScalarOf<C>>(accuracy, length_resolution(curve))
}

/// `tolerance` finite, positive and at least `floor`; the error names the scalar `S`.
#[inline]
fn check_resolvable<S: Scalar>(tolerance: f64, floor: f64) -> Result<(), Error> {
    check_positive(tolerance)?;
    if tolerance < floor {
        Err(Error::ToleranceBelowResolution { scalar: S::NAME })
    } else {
        Ok(())
    }
}

/// Small curves used by the tests of the analysis modules (the real curve types are built in
/// other modules).
#[cfg(test)]
pub(crate) mod testcurves {
    extern crate std;
    use std::vec::Vec;

    use crate::curve::{ParamCurve, ParamCurveDeriv};
    use crate::scalar::Scalar;

    use crate::curve::PieceDeriv;

    /// A piecewise polynomial in monomial form: piece `i` on `[breaks[i], breaks[i+1]]` is
    /// `Σ_j coeffs[i][j] (u − breaks[i])^j`; evaluated in `f64`, returned as `[S; 2]`.
    #[derive(Clone, Debug)]
    pub(crate) struct PolyCurve<S> {
        pub(crate) breaks: Vec<f64>,
        pub(crate) coeffs: Vec<Vec<[f64; 2]>>,
        _s: core::marker::PhantomData<S>,
    }

    impl<S: Scalar> PolyCurve<S> {
        pub(crate) fn new(breaks: &[f64], coeffs: &[&[[f64; 2]]]) -> Self {
            assert_eq!(breaks.len(), coeffs.len() + 1);
            Self {
                breaks: breaks.to_vec(),
                coeffs: coeffs.iter().map(|c| c.to_vec()).collect(),
                _s: core::marker::PhantomData,
            }
        }

        /// One polynomial piece `Σ_j coeffs[j] u^j` (global monomial form) on `[a, b]`.
        pub(crate) fn single(a: f64, b: f64, coeffs: &[[f64; 2]]) -> Self {
            // Shift the global monomial form to the local form around `a` (Taylor at `a`).
            let n = coeffs.len();
            let mut local = std::vec![[0.0; 2]; n];
            for (j, l) in local.iter_mut().enumerate() {
                for d in 0..2 {
                    let mut acc = 0.0;
                    for (m, c) in coeffs.iter().enumerate().skip(j) {
                        acc += c[d] * binom(m, j) * a.powi((m - j) as i32);
                    }
                    l[d] = acc;
                }
            }
            Self::new(&[a, b], &[&local])
        }

        fn piece_of(&self, u: f64) -> usize {
            let n = self.coeffs.len();
            (0..n).rev().find(|&i| u >= self.breaks[i]).unwrap_or(0)
        }

        pub(crate) fn piece_eval(&self, i: usize, u: f64, k: usize) -> [f64; 2] {
            let u = u.clamp(self.breaks[i], self.breaks[i + 1]);
            let x = u - self.breaks[i];
            let mut out = [0.0; 2];
            for (j, c) in self.coeffs[i].iter().enumerate().skip(k) {
                let f = falling(j, k) * x.powi((j - k) as i32);
                out[0] += c[0] * f;
                out[1] += c[1] * f;
            }
            out
        }

        fn to_s(p: [f64; 2]) -> [S; 2] {
            [S::from_f64(p[0]).unwrap(), S::from_f64(p[1]).unwrap()]
        }
    }

    fn binom(n: usize, k: usize) -> f64 {
        (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
    }

    fn falling(j: usize, k: usize) -> f64 {
        (0..k).fold(1.0, |acc, i| acc * (j - i) as f64)
    }

    impl<S: Scalar> ParamCurve for PolyCurve<S> {
        type Point = [S; 2];
        fn domain(&self) -> (S, S) {
            let b = &self.breaks;
            (
                S::from_f64(b[0]).unwrap(),
                S::from_f64(b[b.len() - 1]).unwrap(),
            )
        }
        fn eval(&self, u: S) -> [S; 2] {
            self.deriv(u, 0)
        }
        fn piece_count(&self) -> usize {
            self.coeffs.len()
        }
        fn piece_domain(&self, i: usize) -> (S, S) {
            let i = i.min(self.coeffs.len() - 1);
            (
                S::from_f64(self.breaks[i]).unwrap(),
                S::from_f64(self.breaks[i + 1]).unwrap(),
            )
        }
    }

    impl<S: Scalar> ParamCurveDeriv for PolyCurve<S> {
        fn deriv(&self, u: S, k: usize) -> [S; 2] {
            let u = u.to_f64();
            Self::to_s(self.piece_eval(self.piece_of(u), u, k))
        }
    }

    impl<S: Scalar> PieceDeriv for PolyCurve<S> {
        fn piece_deriv(&self, piece: usize, u: S, k: usize) -> [S; 2] {
            let i = piece.min(self.coeffs.len() - 1);
            Self::to_s(self.piece_eval(i, u.to_f64(), k))
        }
    }

    /// A curve given by a closure `f(u, k)` returning the `k`-th derivative, on `[a, b]`.
    #[derive(Clone, Copy, Debug)]
    pub(crate) struct FnCurve<F, const D: usize> {
        pub(crate) f: F,
        pub(crate) a: f64,
        pub(crate) b: f64,
    }

    impl<F: Fn(f64, usize) -> [f64; D], const D: usize> ParamCurve for FnCurve<F, D> {
        type Point = [f64; D];
        fn domain(&self) -> (f64, f64) {
            (self.a, self.b)
        }
        fn eval(&self, u: f64) -> [f64; D] {
            (self.f)(u.clamp(self.a, self.b), 0)
        }
    }

    impl<F: Fn(f64, usize) -> [f64; D], const D: usize> ParamCurveDeriv for FnCurve<F, D> {
        fn deriv(&self, u: f64, k: usize) -> [f64; D] {
            (self.f)(u.clamp(self.a, self.b), k)
        }
    }

    /// The circle `c(t) = r (cos t, sin t)` and its derivatives.
    pub(crate) fn circle(r: f64) -> impl Fn(f64, usize) -> [f64; 2] + Copy {
        move |t, k| {
            let phase = t + k as f64 * core::f64::consts::FRAC_PI_2;
            [r * libm::cos(phase), r * libm::sin(phase)]
        }
    }

    /// A circle arc of radius `r` on `[a, b]`.
    pub(crate) fn arc(
        r: f64,
        a: f64,
        b: f64,
    ) -> FnCurve<impl Fn(f64, usize) -> [f64; 2] + Copy, 2> {
        FnCurve { f: circle(r), a, b }
    }
}
