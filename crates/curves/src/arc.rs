//! Circular arcs and helices: the arcs of G-code's `G2`/`G3`, evaluated exactly from the
//! angle rather than approximated by polynomials.
//!
//! An [`CircularArc`] turns in the plane of two coordinates ([`Plane`]) about a centre, while every
//! other coordinate moves linearly with the angle (a helix when one of them moves). With
//! the parameter `u ∈ [0, 1]`, the angle `θ(u) = θ₀ + Δθ·u` and the radius
//! `r(u) = r₀ + (r₁ − r₀)·u`,
//!
//! ```text
//! p(u) = c + r(u)·(cos θ(u), sin θ(u))     in the plane,
//! q(u) = q₀ + (q₁ − q₀)·u                  in every other coordinate,
//! ```
//!
//! and the derivatives follow from `dᵏ/duᵏ cos θ = Δθᵏ·cos(θ + kπ/2)` and the product rule:
//! `dᵏ/duᵏ [r·cos θ] = r·Δθᵏ·cos(θ + kπ/2) + k·r′·Δθᵏ⁻¹·cos(θ + (k−1)π/2)` (`sin` alike).
//! When the start and the end lie on one circle about the centre (`r₀ = r₁`, always for
//! the radius form) this is the circle or the circular helix exactly, at constant speed
//! `√((r·Δθ)² + |q₁ − q₀|²)`. A programmed end a little off the circle of the start (G-code
//! rounds its coordinates) is reached by letting the radius change linearly along the
//! turn, which departs from either circle by at most `|r₁ − r₀|`, the tolerance the
//! constructor enforces.
//!
//! The sense of a turn is that of G-code (ISO 6983-1, §4.3.2 "circular interpolation"):
//! counter-clockwise turns from the plane's first axis towards its second, as seen from the
//! positive third axis (`G17`: x → y, `G18`: z → x, `G19`: y → z).

use core::f64::consts::{FRAC_PI_2, TAU};

use crate::curve::{ParamCurve, ParamCurveDeriv, PieceDeriv};
use crate::error::Error;
use crate::point::{MAX_DIM, Point};
use crate::scalar::Scalar;

/// The plane an [`CircularArc`] turns in: its two coordinates, ordered so that a counter-clockwise
/// turn goes from `first` towards `second`.
///
/// ```
/// use strak_curves::Plane;
/// assert_eq!(Plane::ZX, Plane { first: 2, second: 0 });
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Plane {
    /// The coordinate a counter-clockwise turn leaves first (its angle 0).
    pub first: usize,
    /// The coordinate at angle `π/2`.
    pub second: usize,
}

impl Plane {
    /// `G17`: x and y.
    pub const XY: Plane = Plane {
        first: 0,
        second: 1,
    };
    /// `G18`: z and x (counter-clockwise seen from +y).
    pub const ZX: Plane = Plane {
        first: 2,
        second: 0,
    };
    /// `G19`: y and z.
    pub const YZ: Plane = Plane {
        first: 1,
        second: 2,
    };
}

/// The sense of an [`CircularArc`]'s turn in its [`Plane`].
///
/// ```
/// use strak_curves::Turn;
/// assert_ne!(Turn::Clockwise, Turn::CounterClockwise);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Turn {
    /// `G2`.
    Clockwise,
    /// `G3`.
    CounterClockwise,
}

/// A circular arc or helix from `start` to `end` (see the module docs), on the parameter
/// domain `[0, 1]`; `eval(0)` is `start` and `eval(1)` is `end`, exactly.
///
/// ```
/// use strak_curves::{CircularArc, ParamCurve, Plane, Turn};
/// // A quarter turn about the origin, rising 2 in z.
/// let arc = CircularArc::with_center([1.0_f64, 0.0, 0.0], [0.0, 1.0, 2.0], [0.0, 0.0], Plane::XY,
///     Turn::CounterClockwise, 1e-9)?;
/// let mid = arc.eval(0.5);
/// assert!((mid[0] - core::f64::consts::FRAC_1_SQRT_2).abs() < 1e-15);
/// assert_eq!(mid[2], 1.0);
/// assert!((arc.sweep() - core::f64::consts::FRAC_PI_2).abs() < 1e-15);
/// # Ok::<(), strak_curves::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CircularArc<P: Point> {
    start: P,
    end: P,
    plane: Plane,
    center: [f64; 2],
    /// `r₀` and `r₁ − r₀`.
    radius: f64,
    radius_change: f64,
    start_angle: f64,
    /// `Δθ`, positive counter-clockwise.
    sweep: f64,
    /// `q₀` and `q₁ − q₀` of every coordinate outside the plane (zero in the plane).
    offset: [f64; MAX_DIM],
    rise: [f64; MAX_DIM],
}

impl<P: Point> CircularArc<P> {
    /// The arc about `center` (its two coordinates in `plane`), in the sense `turn`, as
    /// `G2`/`G3` with `I J K` give it: a full turn when `start` and `end` coincide in the
    /// plane. The end may lie off the circle of the start by at most `tolerance` (the
    /// radius then changes linearly along the turn).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a plane whose coordinates are equal or not below
    /// `P::DIM`, or a negative or non-finite tolerance; [`Error::NonFinite`] for a NaN or
    /// infinite coordinate; [`Error::DegenerateArc`] when the start or the end is the
    /// centre; [`Error::ArcEndOffCircle`] when the radii of the start and the end differ by
    /// more than `tolerance`; [`Error::OutOfRange`] when a value or a derivative up to the
    /// third does not fit the scalar type.
    ///
    /// ```
    /// use strak_curves::{CircularArc, Error, Plane, Turn};
    /// let off = CircularArc::with_center([1.0_f64, 0.0], [0.0, 1.1], [0.0, 0.0], Plane::XY,
    ///     Turn::CounterClockwise, 0.01);
    /// assert_eq!(off, Err(Error::ArcEndOffCircle));
    /// ```
    pub fn with_center(
        start: P,
        end: P,
        center: [P::Scalar; 2],
        plane: Plane,
        turn: Turn,
        tolerance: P::Scalar,
    ) -> Result<Self, Error> {
        check_plane::<P>(plane)?;
        let tolerance = tolerance.to_f64();
        if !(tolerance.is_finite() && tolerance >= 0.0) {
            return Err(Error::InvalidArgument);
        }
        let (s, e) = (coords(&start)?, coords(&end)?);
        let c = [center[0].to_f64(), center[1].to_f64()];
        if !(c[0].is_finite() && c[1].is_finite()) {
            return Err(Error::NonFinite);
        }
        let (sp, ep) = (in_plane(&s, plane), in_plane(&e, plane));
        let (r0, r1) = (distance(sp, c), distance(ep, c));
        if r0 == 0.0 || r1 == 0.0 {
            return Err(Error::DegenerateArc);
        }
        if (r0 - r1).abs() > tolerance {
            return Err(Error::ArcEndOffCircle);
        }
        let start_angle = angle(sp, c);
        let sweep = if sp == ep {
            full_turn(turn)
        } else {
            sweep_between(start_angle, angle(ep, c), turn)
        };
        Self::build(start, end, plane, c, [r0, r1], start_angle, sweep, [s, e])
    }

    /// The arc of radius `|radius|` from `start` to `end` in the sense `turn`, as
    /// `G2`/`G3` with `R` give it: the shorter of the two arcs (at most a half turn) for a
    /// positive radius, the longer for a negative one. A chord longer than the diameter by
    /// at most `tolerance` is taken as the diameter.
    ///
    /// # Errors
    /// As [`with_center`](Self::with_center); [`Error::DegenerateArc`] for a zero radius or
    /// a start equal to the end in the plane (no centre follows from the radius);
    /// [`Error::ArcEndOffCircle`] for a chord longer than the diameter plus `tolerance`.
    ///
    /// ```
    /// use strak_curves::{CircularArc, ParamCurve, Plane, Turn};
    /// let half = CircularArc::with_radius([0.0_f64, 0.0], [2.0, 0.0], 1.0, Plane::XY, Turn::Clockwise, 1e-9)?;
    /// assert!((half.eval(0.5)[1] - 1.0).abs() < 1e-15); // clockwise from (0, 0): over the top
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn with_radius(
        start: P,
        end: P,
        radius: P::Scalar,
        plane: Plane,
        turn: Turn,
        tolerance: P::Scalar,
    ) -> Result<Self, Error> {
        check_plane::<P>(plane)?;
        let (s, e) = (coords(&start)?, coords(&end)?);
        let (r, tol) = (radius.to_f64(), tolerance.to_f64());
        if !(tol.is_finite() && tol >= 0.0) {
            return Err(Error::InvalidArgument);
        }
        if !r.is_finite() {
            return Err(Error::NonFinite);
        }
        let (sp, ep) = (in_plane(&s, plane), in_plane(&e, plane));
        let chord = distance(sp, ep);
        if r == 0.0 || chord == 0.0 {
            return Err(Error::DegenerateArc);
        }
        let half = chord / 2.0;
        if half > r.abs() + tol / 2.0 {
            return Err(Error::ArcEndOffCircle);
        }
        // The centre on the chord's bisector, `h` from its midpoint: to the left of the
        // chord for a counter-clockwise turn of at most a half turn, and to the right for
        // a clockwise one; the other side for the longer arc.
        let h = libm::sqrt((r * r - half * half).max(0.0));
        let left = (turn == Turn::CounterClockwise) == (r > 0.0);
        let side = if left { h } else { -h };
        let (dx, dy) = ((ep[0] - sp[0]) / chord, (ep[1] - sp[1]) / chord);
        let c = [
            (sp[0] + ep[0]) / 2.0 - dy * side,
            (sp[1] + ep[1]) / 2.0 + dx * side,
        ];
        let scalar = |x: f64| P::Scalar::from_f64(x).ok_or(Error::OutOfRange);
        Self::with_center(
            start,
            end,
            [scalar(c[0])?, scalar(c[1])?],
            plane,
            turn,
            tolerance.max_of(
                P::Scalar::from_f64(4.0 * P::Scalar::EPSILON * r.abs()).unwrap_or(P::Scalar::ZERO),
            ),
        )
    }

    /// Checks the range and stores the arc.
    #[allow(clippy::too_many_arguments)]
    fn build(
        start: P,
        end: P,
        plane: Plane,
        center: [f64; 2],
        radii: [f64; 2],
        start_angle: f64,
        sweep: f64,
        [s, e]: [[f64; MAX_DIM]; 2],
    ) -> Result<Self, Error> {
        let mut offset = [0.0; MAX_DIM];
        let mut rise = [0.0; MAX_DIM];
        for i in (0..P::DIM).filter(|&i| i != plane.first && i != plane.second) {
            offset[i] = s[i];
            rise[i] = e[i] - s[i];
        }
        let arc = CircularArc {
            start,
            end,
            plane,
            center,
            radius: radii[0],
            radius_change: radii[1] - radii[0],
            start_angle,
            sweep,
            offset,
            rise,
        };
        // Every value and derivative up to the third, bounded coordinate by coordinate.
        let r = radii[0].max(radii[1]);
        let (w, dr) = (sweep.abs(), arc.radius_change.abs());
        let plane_bound = center[0].abs().max(center[1].abs()) + r;
        // |dᵏp/duᵏ| ≤ r·wᵏ + k·|r′|·wᵏ⁻¹ for k = 1, 2, 3.
        let derivative = (r * w + dr)
            .max(r * w * w + 2.0 * dr * w)
            .max(r * w * w * w + 3.0 * dr * w * w);
        let mut fits = P::Scalar::fits(plane_bound) && P::Scalar::fits(derivative);
        for i in 0..P::DIM {
            fits &= P::Scalar::fits(s[i].abs().max(e[i].abs()) + rise[i].abs());
        }
        if fits {
            Ok(arc)
        } else {
            Err(Error::OutOfRange)
        }
    }

    /// The signed angle turned, `Δθ` (positive counter-clockwise), in radians.
    ///
    /// ```
    /// use strak_curves::{CircularArc, Plane, Turn};
    /// let a = CircularArc::with_center([1.0_f64, 0.0], [0.0, 1.0], [0.0, 0.0], Plane::XY,
    ///     Turn::Clockwise, 0.0)?;
    /// assert!((a.sweep() + 1.5 * core::f64::consts::PI).abs() < 1e-15);
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn sweep(&self) -> f64 {
        self.sweep
    }

    /// The radius at the start and at the end (equal on a circle).
    ///
    /// ```
    /// use strak_curves::{CircularArc, Plane, Turn};
    /// let spiral = CircularArc::with_center([2.0_f64, 0.0], [-2.1, 0.0], [0.0, 0.0], Plane::XY,
    ///     Turn::Clockwise, 0.2)?;
    /// assert_eq!(spiral.radii(), (2.0, 2.1));
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn radii(&self) -> (f64, f64) {
        (self.radius, self.radius + self.radius_change)
    }

    /// The centre's two coordinates in the plane.
    ///
    /// ```
    /// use strak_curves::{CircularArc, Plane, Turn};
    /// let a = CircularArc::with_radius([0.0_f64, 0.0], [2.0, 0.0], 1.0, Plane::XY,
    ///     Turn::Clockwise, 0.0)?;
    /// assert_eq!(a.center(), [1.0, 0.0]);
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn center(&self) -> [f64; 2] {
        self.center
    }

    /// The plane of the turn.
    ///
    /// ```
    /// use strak_curves::{CircularArc, Plane, Turn};
    /// let a = CircularArc::with_center([0.0_f64, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 0.0],
    ///     Plane::ZX, Turn::CounterClockwise, 0.0)?;
    /// assert_eq!(a.plane(), Plane::ZX);
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn plane(&self) -> Plane {
        self.plane
    }

    /// The `k`-th derivative at `u` in `f64`, every coordinate.
    fn deriv_f64(&self, u: f64, k: usize) -> [f64; MAX_DIM] {
        let mut out = [0.0; MAX_DIM];
        let theta = self.start_angle + self.sweep * u;
        let r = self.radius + self.radius_change * u;
        // dᵏ/duᵏ (cos θ, sin θ) = Δθᵏ·(cos, sin)(θ + kπ/2).
        let turned = |k: usize| {
            #[allow(clippy::cast_precision_loss)]
            let phase = theta + FRAC_PI_2 * (k % 4) as f64;
            let mut scale = 1.0;
            for _ in 0..k {
                scale *= self.sweep;
            }
            (scale * libm::cos(phase), scale * libm::sin(phase))
        };
        let (c, s) = turned(k);
        let (mut x, mut y) = (r * c, r * s);
        if k > 0 {
            let (c1, s1) = turned(k - 1);
            #[allow(clippy::cast_precision_loss)]
            let kk = k as f64;
            x += kk * self.radius_change * c1;
            y += kk * self.radius_change * s1;
        }
        if k == 0 {
            x += self.center[0];
            y += self.center[1];
        }
        out[self.plane.first] = x;
        out[self.plane.second] = y;
        for i in (0..P::DIM).filter(|&i| i != self.plane.first && i != self.plane.second) {
            out[i] = match k {
                0 => self.offset[i] + self.rise[i] * u,
                1 => self.rise[i],
                _ => 0.0,
            };
        }
        out
    }
}

impl<P: Point> ParamCurve for CircularArc<P> {
    type Point = P;

    fn domain(&self) -> (P::Scalar, P::Scalar) {
        (P::Scalar::ZERO, P::Scalar::ONE)
    }

    /// The point at `u`, clamped to `[0, 1]`; the start and the end exactly at the ends.
    fn eval(&self, u: P::Scalar) -> P {
        if u <= P::Scalar::ZERO {
            return self.start;
        }
        if u >= P::Scalar::ONE {
            return self.end;
        }
        to_point(&self.deriv_f64(u.to_f64(), 0))
    }
}

impl<P: Point> ParamCurveDeriv for CircularArc<P> {
    /// The `k`-th derivative at `u` (clamped to `[0, 1]`); `k = 0` is [`eval`](ParamCurve::eval).
    /// Derivatives above the third saturate at the scalar type's range.
    fn deriv(&self, u: P::Scalar, k: usize) -> P {
        if k == 0 {
            return self.eval(u);
        }
        let u = u.to_f64().clamp(0.0, 1.0);
        to_point(&self.deriv_f64(u, k))
    }
}

/// An arc is one piece: its derivatives are those of [`ParamCurveDeriv::deriv`].
impl<P: Point> PieceDeriv for CircularArc<P> {
    fn piece_deriv(&self, _piece: usize, u: P::Scalar, k: usize) -> P {
        self.deriv(u, k)
    }
}

/// The point of `v`'s first `P::DIM` values; the constructor checked that they fit
/// (saturated beyond, for derivatives above the third).
fn to_point<P: Point>(v: &[f64; MAX_DIM]) -> P {
    P::from_coords(|i| {
        let x = v[i].clamp(-P::Scalar::LIMIT, P::Scalar::LIMIT);
        P::Scalar::from_f64(x).unwrap_or(P::Scalar::ZERO)
    })
}

fn check_plane<P: Point>(plane: Plane) -> Result<(), Error> {
    if plane.first == plane.second || plane.first >= P::DIM || plane.second >= P::DIM {
        Err(Error::InvalidArgument)
    } else {
        Ok(())
    }
}

/// The coordinates in `f64`, checked finite.
fn coords<P: Point>(p: &P) -> Result<[f64; MAX_DIM], Error> {
    let mut out = [0.0; MAX_DIM];
    for (i, o) in out.iter_mut().enumerate().take(P::DIM) {
        *o = p.coord(i).to_f64();
        if !o.is_finite() {
            return Err(Error::NonFinite);
        }
    }
    Ok(out)
}

fn in_plane(v: &[f64; MAX_DIM], plane: Plane) -> [f64; 2] {
    [v[plane.first], v[plane.second]]
}

fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
    libm::hypot(a[0] - b[0], a[1] - b[1])
}

/// The angle of `p` about `c`.
fn angle(p: [f64; 2], c: [f64; 2]) -> f64 {
    libm::atan2(p[1] - c[1], p[0] - c[0])
}

fn full_turn(turn: Turn) -> f64 {
    match turn {
        Turn::CounterClockwise => TAU,
        Turn::Clockwise => -TAU,
    }
}

/// The angle from `from` to `to` in the sense `turn`: in `(0, 2π]` counter-clockwise, in
/// `[−2π, 0)` clockwise (a full turn only where the two angles are equal).
fn sweep_between(from: f64, to: f64, turn: Turn) -> f64 {
    // `to − from` lies in [−2π, 2π] (both from `atan2`): one or two turns added at most.
    let d = to - from;
    match turn {
        Turn::CounterClockwise if d <= -TAU => d + 2.0 * TAU,
        Turn::CounterClockwise if d <= 0.0 => d + TAU,
        Turn::Clockwise if d >= TAU => d - 2.0 * TAU,
        Turn::Clockwise if d >= 0.0 => d - TAU,
        _ => d,
    }
}

#[cfg(test)]
mod tests {
    use core::f64::consts::{FRAC_1_SQRT_2, PI};

    use super::*;
    use crate::I16F16;
    use crate::I32F32;

    type Arc3 = CircularArc<[f64; 3]>;

    fn quarter() -> Arc3 {
        CircularArc::with_center(
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 2.0],
            [0.0, 0.0],
            Plane::XY,
            Turn::CounterClockwise,
            1e-9,
        )
        .unwrap()
    }

    fn dist2(p: [f64; 3], c: [f64; 2]) -> f64 {
        libm::hypot(p[0] - c[0], p[1] - c[1])
    }

    #[test]
    fn ends_are_exact_and_points_lie_on_the_helix() {
        let a = quarter();
        assert_eq!(a.eval(0.0), [1.0, 0.0, 0.0]);
        assert_eq!(a.eval(1.0), [0.0, 1.0, 2.0]);
        for i in 1..100 {
            let u = f64::from(i) / 100.0;
            let p = a.eval(u);
            assert!((dist2(p, [0.0, 0.0]) - 1.0).abs() < 1e-15);
            assert!((p[2] - 2.0 * u).abs() < 1e-15);
            // counter-clockwise: the angle grows with u
            assert!((libm::atan2(p[1], p[0]) - FRAC_PI_2 * u).abs() < 1e-14);
        }
    }

    /// Central differences of the previous derivative (step h, error O(h²)).
    fn check_derivatives(a: &Arc3, tol: f64) {
        let h = 1e-5;
        for i in 1..20 {
            let u = f64::from(i) / 20.0;
            for k in 1..=3 {
                let d = a.deriv(u, k);
                let (hi, lo) = (a.deriv(u + h, k - 1), a.deriv(u - h, k - 1));
                for j in 0..3 {
                    let fd = (hi[j] - lo[j]) / (2.0 * h);
                    let scale = 1.0 + d[j].abs();
                    assert!(
                        (d[j] - fd).abs() < tol * scale,
                        "k {k} u {u} axis {j}: {} vs {fd}",
                        d[j]
                    );
                }
            }
        }
    }

    #[test]
    fn derivatives_agree_with_differences_of_the_points() {
        check_derivatives(&quarter(), 1e-7);
        // a spiral: the end off the circle of the start
        let spiral = CircularArc::with_center(
            [3.0, 0.0, 1.0],
            [-2.9, 0.0, -1.0],
            [0.0, 0.0],
            Plane::XY,
            Turn::Clockwise,
            0.2,
        )
        .unwrap();
        assert_eq!(spiral.radii(), (3.0, 2.9));
        check_derivatives(&spiral, 1e-7);
    }

    #[test]
    fn a_helix_moves_at_constant_speed() {
        let a = quarter();
        let want = libm::hypot(FRAC_PI_2, 2.0);
        for i in 0..=10 {
            let d = a.deriv(f64::from(i) / 10.0, 1);
            let speed = libm::sqrt(d.iter().map(|x| x * x).sum());
            assert!((speed - want).abs() < 1e-14);
        }
    }

    #[test]
    fn planes_and_senses_follow_g_code() {
        // G18: counter-clockwise from +z towards +x (seen from +y).
        let zx = CircularArc::with_center(
            [0.0, 5.0, 1.0],
            [1.0, 5.0, 0.0],
            [0.0, 0.0],
            Plane::ZX,
            Turn::CounterClockwise,
            0.0,
        )
        .unwrap();
        assert!((zx.sweep() - FRAC_PI_2).abs() < 1e-15);
        let m = zx.eval(0.5);
        assert!((m[0] - FRAC_1_SQRT_2).abs() < 1e-15 && (m[2] - FRAC_1_SQRT_2).abs() < 1e-15);
        assert_eq!(m[1], 5.0);
        // The same ends clockwise: three quarters, through −x.
        let cw = CircularArc::with_center(
            [0.0, 5.0, 1.0],
            [1.0, 5.0, 0.0],
            [0.0, 0.0],
            Plane::ZX,
            Turn::Clockwise,
            0.0,
        )
        .unwrap();
        assert!((cw.sweep() + 1.5 * PI).abs() < 1e-15);
        assert!((cw.eval(0.5)[0] + FRAC_1_SQRT_2).abs() < 1e-15);
        // G19: y towards z.
        let yz = CircularArc::with_center(
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0],
            Plane::YZ,
            Turn::CounterClockwise,
            0.0,
        )
        .unwrap();
        assert!((yz.sweep() - FRAC_PI_2).abs() < 1e-15);
    }

    #[test]
    fn a_full_turn_when_the_ends_coincide() {
        for (turn, sign) in [(Turn::CounterClockwise, 1.0), (Turn::Clockwise, -1.0)] {
            let a = CircularArc::<[f64; 2]>::with_center(
                [2.0, 0.0],
                [2.0, 0.0],
                [0.0, 0.0],
                Plane::XY,
                turn,
                0.0,
            )
            .unwrap();
            assert_eq!(a.sweep(), sign * TAU);
            let m = a.eval(0.5);
            assert!((m[0] + 2.0).abs() < 1e-15 && m[1].abs() < 1e-14);
            assert!((a.eval(0.25)[1] - sign * 2.0).abs() < 1e-15);
        }
    }

    #[test]
    fn the_radius_form_takes_the_shorter_or_the_longer_arc() {
        let r = |radius: f64, turn| {
            CircularArc::<[f64; 2]>::with_radius(
                [0.0, 0.0],
                [1.0, 1.0],
                radius,
                Plane::XY,
                turn,
                1e-9,
            )
        };
        for turn in [Turn::Clockwise, Turn::CounterClockwise] {
            let short = r(1.0, turn).unwrap();
            let long = r(-1.0, turn).unwrap();
            assert!(
                (short.sweep().abs() - FRAC_PI_2).abs() < 1e-14,
                "{}",
                short.sweep()
            );
            assert!(
                (long.sweep().abs() - 1.5 * PI).abs() < 1e-14,
                "{}",
                long.sweep()
            );
            assert_eq!(short.sweep() > 0.0, turn == Turn::CounterClockwise);
            for a in [short, long] {
                let (r0, r1) = a.radii();
                assert!((r0 - 1.0).abs() < 1e-15 && (r1 - 1.0).abs() < 1e-15);
                assert_eq!(a.eval(1.0), [1.0, 1.0]);
            }
        }
        // counter-clockwise and short: the centre is left of the chord, at (0, 1)
        let c = r(1.0, Turn::CounterClockwise).unwrap().center();
        assert!(c[0].abs() < 1e-15 && (c[1] - 1.0).abs() < 1e-15);
        // a chord a little longer than the diameter, within the tolerance
        let d = CircularArc::<[f64; 2]>::with_radius(
            [0.0, 0.0],
            [2.0 + 1e-6, 0.0],
            1.0,
            Plane::XY,
            Turn::Clockwise,
            1e-5,
        )
        .unwrap();
        assert!((d.sweep() + PI).abs() < 1e-12);
        assert_eq!(
            CircularArc::<[f64; 2]>::with_radius(
                [0.0, 0.0],
                [2.1, 0.0],
                1.0,
                Plane::XY,
                Turn::Clockwise,
                1e-5
            ),
            Err(Error::ArcEndOffCircle)
        );
    }

    #[test]
    fn bad_input_is_an_error() {
        let arc = |s: [f64; 2], e: [f64; 2], c: [f64; 2], plane, tol| {
            CircularArc::with_center(s, e, c, plane, Turn::Clockwise, tol)
        };
        assert_eq!(
            arc([1.0, 0.0], [0.0, 1.0], [0.0, 0.0], Plane::ZX, 0.0),
            Err(Error::InvalidArgument)
        );
        assert_eq!(
            arc(
                [1.0, 0.0],
                [0.0, 1.0],
                [0.0, 0.0],
                Plane {
                    first: 1,
                    second: 1
                },
                0.0
            ),
            Err(Error::InvalidArgument)
        );
        assert_eq!(
            arc([1.0, 0.0], [0.0, 1.0], [0.0, 0.0], Plane::XY, -1.0),
            Err(Error::InvalidArgument)
        );
        assert_eq!(
            arc([1.0, 0.0], [0.0, 1.0], [0.0, 0.0], Plane::XY, f64::NAN),
            Err(Error::InvalidArgument)
        );
        assert_eq!(
            arc([f64::NAN, 0.0], [0.0, 1.0], [0.0, 0.0], Plane::XY, 0.0),
            Err(Error::NonFinite)
        );
        assert_eq!(
            arc([1.0, 0.0], [0.0, 1.0], [f64::INFINITY, 0.0], Plane::XY, 0.0),
            Err(Error::NonFinite)
        );
        assert_eq!(
            arc([0.0, 0.0], [0.0, 1.0], [0.0, 0.0], Plane::XY, 0.0),
            Err(Error::DegenerateArc)
        );
        assert_eq!(
            arc([1.0, 0.0], [0.0, 1.5], [0.0, 0.0], Plane::XY, 0.4),
            Err(Error::ArcEndOffCircle)
        );
        assert!(arc([1.0, 0.0], [0.0, 1.5], [0.0, 0.0], Plane::XY, 0.5).is_ok());
        let radius = |r: f64| {
            CircularArc::<[f64; 2]>::with_radius(
                [0.0, 0.0],
                [1.0, 0.0],
                r,
                Plane::XY,
                Turn::Clockwise,
                0.0,
            )
        };
        assert_eq!(radius(0.0), Err(Error::DegenerateArc));
        assert_eq!(radius(f64::NAN), Err(Error::NonFinite));
        assert_eq!(
            CircularArc::<[f64; 2]>::with_radius(
                [1.0, 0.0],
                [1.0, 0.0],
                1.0,
                Plane::XY,
                Turn::Clockwise,
                0.0
            ),
            Err(Error::DegenerateArc)
        );
        // 16 integer bits: a radius of 2 000 fits, the third derivative of its full turn
        // (r·(2π)³ ≈ 500 000) does not
        let big = I16F16::from_num(2_000);
        let zero = I16F16::from_num(0);
        assert_eq!(
            CircularArc::<[I16F16; 2]>::with_center(
                [big, zero],
                [big, zero],
                [zero, zero],
                Plane::XY,
                Turn::Clockwise,
                zero
            ),
            Err(Error::OutOfRange)
        );
    }

    #[test]
    fn fixed_point_follows_the_float_arc() {
        let f = |x: f64| I32F32::from_num(x);
        let a = CircularArc::<[I32F32; 3]>::with_center(
            [f(1.0), f(0.0), f(0.0)],
            [f(0.0), f(1.0), f(2.0)],
            [f(0.0), f(0.0)],
            Plane::XY,
            Turn::CounterClockwise,
            f(1e-9),
        )
        .unwrap();
        let b = quarter();
        for i in 0..=16 {
            let u = f64::from(i) / 16.0;
            for k in 0..=3 {
                let (p, q) = (a.deriv(f(u), k), b.deriv(u, k));
                for j in 0..3 {
                    assert!((p[j].to_num::<f64>() - q[j]).abs() < 1e-9, "u {u} k {k}");
                }
            }
        }
        assert_eq!(a.eval(f(1.0)), [f(0.0), f(1.0), f(2.0)]);
    }
}
