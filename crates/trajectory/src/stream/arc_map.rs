//! The arc length along a curved segment (a blend, a Bézier move) as a function of its
//! parameter, cheap to invert at every tick.
//!
//! `[u₀, u₁]` is cut into [`PANELS`] equal panels. Each panel's length is one 8-point
//! Gauss–Legendre rule ([`gauss_length`]; Davis & Rabinowitz, *Methods of Numerical
//! Integration*, §2.7), kept only where the same rule on each pair of panels agrees with
//! the sum of the pair's rules within [`PANEL_ACCURACY`] of the segment's length: the rule
//! on a panel, half as wide, is then closer still (its error falls as the width to the
//! sixteenth power), and so is the rule on a part of a panel from the panel's start. The parameter at an arc length is the
//! root of `s(u) = s`, found by Newton's method inside its panel (`s′(u) = |c′(u)|`): from
//! the cubic Hermite interpolant of `u(s)` on the panel (slopes `1/|c′|` at its ends), with
//! the rule on the panel's part once and each correction's length by the 3-point rule on
//! the short step it makes (exact for a quintic's speed to within rounding there).

use strak_curves::{ParamCurveDeriv, Point, gauss_length};

/// Equal parameter panels of a segment (checked in pairs).
const PANELS: usize = 8;
const _: () = assert!(PANELS.is_multiple_of(2));

/// How closely a panel's rule must agree with its halves, relative to the segment's length.
const PANEL_ACCURACY: f64 = 1e-12;

/// Newton steps at most per inversion (from the Hermite guess inside a panel it converges in
/// one or two).
const NEWTON_STEPS: usize = 12;

/// The speed `|c′(u)|`.
fn speed<C, const D: usize>(curve: &C, u: f64) -> f64
where
    C: ParamCurveDeriv<Point = [f64; D]>,
{
    curve.deriv(u, 1).norm()
}

/// The arc length from `a` to `b` (negative for `b < a`) by the 3-point Gauss–Legendre rule,
/// for the short steps of Newton's method.
fn short_length<C, const D: usize>(curve: &C, a: f64, b: f64) -> f64
where
    C: ParamCurveDeriv<Point = [f64; D]>,
{
    // ±√(3/5) and 0, weights 5/9, 8/9, 5/9
    const NODE: f64 = 0.774_596_669_241_483_4;
    let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
    half * (5.0 / 9.0 * (speed(curve, mid - half * NODE) + speed(curve, mid + half * NODE))
        + 8.0 / 9.0 * speed(curve, mid))
}

/// The cubic Hermite interpolant of `u(s)` on a panel from `(sa, a)` to `(sb, b)` with the
/// slopes `1/va`, `1/vb` (`va`, `vb` the speeds there) at `s`; the linear one where a speed
/// is not positive.
fn hermite_guess((a, b): (f64, f64), (sa, sb): (f64, f64), (va, vb): (f64, f64), s: f64) -> f64 {
    let h = sb - sa;
    let t = (s - sa) / h;
    if !(va > 0.0 && vb > 0.0 && va.is_finite() && vb.is_finite()) {
        return a + (b - a) * t;
    }
    let (t2, t3) = (t * t, t * t * t);
    let guess = (2.0 * t3 - 3.0 * t2 + 1.0) * a
        + (t3 - 2.0 * t2 + t) * h / va
        + (3.0 * t2 - 2.0 * t3) * b
        + (t3 - t2) * h / vb;
    guess.clamp(a, b)
}

/// The arc lengths at the ends of the panels of `[u0, u1]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct ArcMap {
    u0: f64,
    u1: f64,
    s: [f64; PANELS + 1],
}

impl ArcMap {
    /// The map of `curve` over `[u0, u1]`; `None` where a panel's rule is not accurate enough
    /// (a near-cusp, a sharp turn of the parameterization).
    pub(super) fn new<C, const D: usize>(curve: &C, (u0, u1): (f64, f64)) -> Option<Self>
    where
        C: ParamCurveDeriv<Point = [f64; D]>,
    {
        let mut map = ArcMap {
            u0,
            u1,
            s: [0.0; PANELS + 1],
        };
        let mut disagreement = 0.0_f64;
        for pair in 0..PANELS / 2 {
            let ((a, mid), (_, b)) = (map.panel(2 * pair), map.panel(2 * pair + 1));
            let halves = [gauss_length(curve, a, mid), gauss_length(curve, mid, b)];
            let whole = gauss_length(curve, a, b);
            disagreement = disagreement.max((whole - (halves[0] + halves[1])).abs());
            map.s[2 * pair + 1] = map.s[2 * pair] + halves[0];
            map.s[2 * pair + 2] = map.s[2 * pair + 1] + halves[1];
        }
        let length = map.length();
        (length > 0.0 && length.is_finite() && disagreement <= PANEL_ACCURACY * length)
            .then_some(map)
    }

    /// The parameters at the ends of panel `i`.
    fn panel(&self, i: usize) -> (f64, f64) {
        #[allow(clippy::cast_precision_loss)]
        let at = |k: usize| self.u0 + (self.u1 - self.u0) * (k as f64 / PANELS as f64);
        (at(i), if i + 1 == PANELS { self.u1 } else { at(i + 1) })
    }

    /// The arc length of the segment.
    pub(super) fn length(&self) -> f64 {
        self.s[PANELS]
    }

    /// The arc length at the parameter `u` (clamped to the segment).
    pub(super) fn length_at<C, const D: usize>(&self, curve: &C, u: f64) -> f64
    where
        C: ParamCurveDeriv<Point = [f64; D]>,
    {
        let u = u.clamp(self.u0, self.u1);
        let i = (0..PANELS)
            .find(|&i| u <= self.panel(i).1)
            .unwrap_or(PANELS - 1);
        self.s[i] + gauss_length(curve, self.panel(i).0, u)
    }

    /// The parameter at the arc length `s` (clamped to the segment; its ends exactly).
    pub(super) fn param<C, const D: usize>(&self, curve: &C, s: f64) -> f64
    where
        C: ParamCurveDeriv<Point = [f64; D]>,
    {
        if s <= 0.0 {
            return self.u0;
        }
        if s >= self.length() {
            return self.u1;
        }
        let i = (0..PANELS)
            .find(|&i| s <= self.s[i + 1])
            .unwrap_or(PANELS - 1);
        let ((a, b), (sa, sb)) = (self.panel(i), (self.s[i], self.s[i + 1]));
        if sb <= sa {
            return a;
        }
        let ends = (speed(curve, a), speed(curve, b));
        let mut u = hermite_guess((a, b), (sa, sb), ends, s);
        let mut miss = sa + gauss_length(curve, a, u) - s;
        for _ in 0..NEWTON_STEPS {
            let v = speed(curve, u);
            if v.is_nan() || v <= 0.0 {
                break;
            }
            let next = (u - miss / v).clamp(a, b);
            if next == u {
                break;
            }
            miss += short_length(curve, u, next);
            u = next;
        }
        u
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use strak_curves::{Bezier, param_at_length};

    /// Against the adaptive inversion of strak-curves on a quintic blend-like curve: within
    /// `1e-12` of its length in parameter times speed.
    #[test]
    fn inverts_like_the_adaptive_quadrature() {
        let b = crate::plan::testcurves::blend_like_quintic();
        let map = ArcMap::new(&b, (0.0, 1.0)).unwrap();
        let length = strak_curves::arc_length(&b, 1e-13).unwrap();
        assert!((map.length() - length).abs() < 1e-12 * length);
        for k in 0..=50 {
            let s = length * f64::from(k) / 50.0;
            let fast = map.param(&b, s);
            let exact = param_at_length(&b, s, 1e-13).unwrap();
            assert!((fast - exact).abs() < 1e-11, "{k}: {fast} {exact}");
        }
        // a part of a curve
        let part = ArcMap::new(&b, (0.3, 0.7)).unwrap();
        let s0 = strak_curves::arc_length_between(&b, 0.0, 0.3, 1e-13).unwrap();
        let u = part.param(&b, 0.1);
        assert!((u - param_at_length(&b, s0 + 0.1, 1e-13).unwrap()).abs() < 1e-11);
    }

    /// A cubic with a cusp at `u = 0.3`, inside a panel: the speed has a kink there, the
    /// rule disagrees with its halves, and the map is refused.
    #[test]
    fn refuses_a_cusp_inside_a_panel() {
        let end = [-7.0 / 9.0, 1.0 - 49.0 / 9.0];
        let b = Bezier::new([[0.0, 0.0], [1.0, 1.0], [0.0, 1.0], end]).unwrap();
        assert!(b.deriv(0.3, 1).norm() < 1e-12);
        assert!(ArcMap::new(&b, (0.0, 1.0)).is_none());
    }
}
