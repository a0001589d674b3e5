//! Circular arcs and helices as G-code's `G2`/`G3` describe them (ISO 6983-1, circular
//! interpolation), written from the definitions: the start's radius vector rotated by the
//! rotation matrix `R(θ)` and scaled from the start's radius to the end's, the other
//! coordinates linear. The turn is read from the cross and dot products of the start's and
//! the end's radius vectors, and the centre of the radius form is an intersection of the
//! two circles of radius `|r|` about the start and the end.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// An arc in the plane of the coordinates `plane.0` (angle 0) and `plane.1` (angle `π/2`).
#[derive(Clone, Debug, PartialEq)]
pub struct GcodeArc {
    /// The start and end points, every coordinate.
    pub start: Vec<f64>,
    /// See `start`.
    pub end: Vec<f64>,
    /// The centre's two plane coordinates.
    pub center: [f64; 2],
    /// The plane's coordinates.
    pub plane: (usize, usize),
    /// The signed angle turned, positive counter-clockwise.
    pub sweep: f64,
}

fn plane_vector(p: &[f64], c: [f64; 2], plane: (usize, usize)) -> [f64; 2] {
    [p[plane.0] - c[0], p[plane.1] - c[1]]
}

/// The signed angle from the start's radius vector to the end's, in the sense of the turn:
/// `atan2(a × b, a · b)` in `(−π, π]`, moved into `(0, 2π]` counter-clockwise or `[−2π, 0)`
/// clockwise; a full turn when the vectors are equal.
///
/// ```
/// let s = strak_ref::gcode_sweep([1.0, 0.0], [0.0, 1.0], true);
/// assert!((s + 1.5 * std::f64::consts::PI).abs() < 1e-15);
/// ```
pub fn gcode_sweep(a: [f64; 2], b: [f64; 2], clockwise: bool) -> f64 {
    if a == b {
        return if clockwise { -TAU } else { TAU };
    }
    let angle = (a[0] * b[1] - a[1] * b[0]).atan2(a[0] * b[0] + a[1] * b[1]);
    match (clockwise, angle) {
        (false, x) if x <= 0.0 => x + TAU,
        (true, x) if x >= 0.0 => x - TAU,
        (_, x) => x,
    }
}

impl GcodeArc {
    /// The arc about `center` (`G2`/`G3` with `I J K`).
    pub fn with_center(
        start: &[f64],
        end: &[f64],
        center: [f64; 2],
        plane: (usize, usize),
        clockwise: bool,
    ) -> Self {
        let (a, b) = (
            plane_vector(start, center, plane),
            plane_vector(end, center, plane),
        );
        let sweep = if start[plane.0] == end[plane.0] && start[plane.1] == end[plane.1] {
            if clockwise { -TAU } else { TAU }
        } else {
            gcode_sweep(a, b, clockwise)
        };
        GcodeArc {
            start: start.to_vec(),
            end: end.to_vec(),
            center,
            plane,
            sweep,
        }
    }

    /// The arc of radius `|r|` (`G2`/`G3` with `R`): of the two intersections of the circles
    /// of radius `|r|` about the start and the end, the centre whose arc in the turn's sense
    /// is at most a half turn for `r > 0`, more for `r < 0`.
    pub fn with_radius(
        start: &[f64],
        end: &[f64],
        r: f64,
        plane: (usize, usize),
        clockwise: bool,
    ) -> Self {
        let (s, e) = (
            [start[plane.0], start[plane.1]],
            [end[plane.0], end[plane.1]],
        );
        let d = ((e[0] - s[0]).powi(2) + (e[1] - s[1]).powi(2)).sqrt();
        let h = (r * r - d * d / 4.0).max(0.0).sqrt();
        let m = [(s[0] + e[0]) / 2.0, (s[1] + e[1]) / 2.0];
        let n = [-(e[1] - s[1]) / d, (e[0] - s[0]) / d];
        let candidates = [
            [m[0] + h * n[0], m[1] + h * n[1]],
            [m[0] - h * n[0], m[1] - h * n[1]],
        ];
        let arcs = candidates.map(|c| Self::with_center(start, end, c, plane, clockwise));
        let short = |a: &GcodeArc| a.sweep.abs() <= PI;
        let pick = arcs.iter().position(|a| short(a) == (r > 0.0)).unwrap_or(0);
        arcs[pick].clone()
    }

    /// The `k`-th derivative at `u ∈ [0, 1]`: `p(u) = c + (r(u)/r₀)·R(θ(u))·a` with `a` the
    /// start's radius vector, `θ(u) = sweep·u`, `r(u)` linear from the start's radius to the
    /// end's; `dᵏ/duᵏ R(θ) = sweepᵏ·R(θ + kπ/2)` and the product rule with the linear scale.
    pub fn deriv(&self, u: f64, k: usize) -> Vec<f64> {
        let (p0, p1) = self.plane;
        let a = plane_vector(&self.start, self.center, self.plane);
        let b = plane_vector(&self.end, self.center, self.plane);
        let (r0, r1) = (a[0].hypot(a[1]), b[0].hypot(b[1]));
        let scale = |u: f64| (r0 + (r1 - r0) * u) / r0;
        let rotated = |k: usize| {
            let phi = self.sweep * u + FRAC_PI_2 * k as f64;
            let f = self.sweep.powi(k as i32);
            let (c, s) = (phi.cos(), phi.sin());
            [f * (c * a[0] - s * a[1]), f * (s * a[0] + c * a[1])]
        };
        let mut v = rotated(k).map(|x| x * scale(u));
        if k > 0 {
            let w = rotated(k - 1);
            for i in 0..2 {
                v[i] += k as f64 * (r1 - r0) / r0 * w[i];
            }
        }
        let mut out: Vec<f64> = (0..self.start.len())
            .map(|i| match k {
                0 => self.start[i] + (self.end[i] - self.start[i]) * u,
                1 => self.end[i] - self.start[i],
                _ => 0.0,
            })
            .collect();
        out[p0] = v[0] + if k == 0 { self.center[0] } else { 0.0 };
        out[p1] = v[1] + if k == 0 { self.center[1] } else { 0.0 };
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_quarter_turn_and_its_derivative() {
        let arc = GcodeArc::with_center(
            &[1.0, 0.0, 0.0],
            &[0.0, 1.0, 4.0],
            [0.0, 0.0],
            (0, 1),
            false,
        );
        assert!((arc.sweep - FRAC_PI_2).abs() < 1e-15);
        let m = arc.deriv(0.5, 0);
        assert!((m[0] - 0.5_f64.sqrt()).abs() < 1e-15 && (m[2] - 2.0).abs() < 1e-15);
        let d = arc.deriv(0.0, 1);
        assert!(d[0].abs() < 1e-15 && (d[1] - FRAC_PI_2).abs() < 1e-15 && d[2] == 4.0);
        // the radius form's longer arc
        let long = GcodeArc::with_radius(&[1.0, 0.0], &[0.0, 1.0], -1.0, (0, 1), false);
        assert!((long.sweep - 1.5 * PI).abs() < 1e-14);
    }
}
