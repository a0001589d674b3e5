//! Arc length by adaptive Simpson quadrature, and point-to-segment / point-to-polyline
//! distances (for checking flattening and sampling).

use crate::vecops::{vec_add_scaled, vec_dist, vec_dot, vec_norm, vec_sub};

fn simpson(f: &dyn Fn(f64) -> f64, a: f64, fa: f64, b: f64, fb: f64) -> (f64, f64, f64) {
    let m = 0.5 * (a + b);
    let fm = f(m);
    ((b - a) / 6.0 * (fa + 4.0 * fm + fb), m, fm)
}

#[allow(clippy::too_many_arguments)]
fn adaptive(
    f: &dyn Fn(f64) -> f64,
    a: f64,
    fa: f64,
    b: f64,
    fb: f64,
    whole: f64,
    m: f64,
    fm: f64,
    tol: f64,
    depth: u32,
) -> f64 {
    let (left, lm, flm) = simpson(f, a, fa, m, fm);
    let (right, rm, frm) = simpson(f, m, fm, b, fb);
    let both = left + right;
    if depth == 0 || (both - whole).abs() <= 15.0 * tol {
        return both + (both - whole) / 15.0;
    }
    adaptive(f, a, fa, m, fm, left, lm, flm, 0.5 * tol, depth - 1)
        + adaptive(f, m, fm, b, fb, right, rm, frm, 0.5 * tol, depth - 1)
}

/// The arc length `∫_a^b ‖c'(t)‖ dt` of a curve given by its first derivative `deriv`, by
/// adaptive Simpson quadrature: `[a, b]` is split into 16 equal parts (so that a symmetric
/// integrand cannot fool the first error estimate), each refined recursively until
/// `|S_left + S_right − S| ≤ 15 tol_part` (Richardson-corrected result, recursion depth ≤ 50).
/// `tol` is the requested absolute error. Returns `−L` if `b < a`.
///
/// ```
/// // Quarter of the unit circle: π/2.
/// let len = strak_ref::arc_length(&|t: f64| vec![-t.sin(), t.cos()], 0.0, std::f64::consts::FRAC_PI_2, 1e-12);
/// assert!((len - std::f64::consts::FRAC_PI_2).abs() < 1e-11);
/// ```
pub fn arc_length(deriv: &dyn Fn(f64) -> Vec<f64>, a: f64, b: f64, tol: f64) -> f64 {
    let speed = |t: f64| vec_norm(&deriv(t));
    let parts = 16;
    let h = (b - a) / parts as f64;
    let part_tol = tol.abs() / parts as f64;
    let mut total = 0.0;
    for p in 0..parts {
        let lo = a + h * p as f64;
        let hi = if p + 1 == parts { b } else { lo + h };
        let (flo, fhi) = (speed(lo), speed(hi));
        let (whole, m, fm) = simpson(&speed, lo, flo, hi, fhi);
        total += adaptive(&speed, lo, flo, hi, fhi, whole, m, fm, part_tol, 50);
    }
    total
}

/// The Euclidean distance from point `p` to the segment `[a, b]`: projection parameter
/// `s = ⟨p − a, b − a⟩ / ‖b − a‖²` clamped to `[0, 1]`; a degenerate segment (`a = b`) gives
/// `‖p − a‖`.
///
/// ```
/// assert_eq!(strak_ref::point_segment_distance(&[1.0, 1.0], &[0.0, 0.0], &[2.0, 0.0]), 1.0);
/// assert_eq!(strak_ref::point_segment_distance(&[5.0, 4.0], &[0.0, 0.0], &[2.0, 0.0]), 5.0);
/// ```
pub fn point_segment_distance(p: &[f64], a: &[f64], b: &[f64]) -> f64 {
    let ab = vec_sub(b, a);
    let len2 = vec_dot(&ab, &ab);
    if len2 == 0.0 {
        return vec_dist(p, a);
    }
    let s = (vec_dot(&vec_sub(p, a), &ab) / len2).clamp(0.0, 1.0);
    let mut foot = a.to_vec();
    vec_add_scaled(&mut foot, &ab, s);
    vec_dist(p, &foot)
}

/// The distance from `p` to a polyline (minimum over its segments; a single vertex gives the
/// distance to that vertex).
///
/// # Panics
/// If `polyline` is empty.
///
/// ```
/// let poly = [vec![0.0, 0.0], vec![2.0, 0.0], vec![2.0, 2.0]];
/// assert_eq!(strak_ref::polyline_distance(&[3.0, 1.0], &poly), 1.0);
/// ```
pub fn polyline_distance(p: &[f64], polyline: &[Vec<f64>]) -> f64 {
    assert!(!polyline.is_empty(), "polyline_distance: empty polyline");
    if polyline.len() == 1 {
        return vec_dist(p, &polyline[0]);
    }
    polyline
        .windows(2)
        .map(|w| point_segment_distance(p, &w[0], &w[1]))
        .fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_and_parabola_lengths() {
        // Straight line (3t, 4t) on [0, 2]: length 10.
        let l = arc_length(&|_t| vec![3.0, 4.0], 0.0, 2.0, 1e-12);
        assert!((l - 10.0).abs() < 1e-12);
        // Parabola (t, t²) on [0, 1]: (2√5 + asinh 2)/4.
        let exact = (2.0 * 5f64.sqrt() + 2f64.asinh()) / 4.0;
        let l = arc_length(&|t| vec![1.0, 2.0 * t], 0.0, 1.0, 1e-12);
        assert!((l - exact).abs() < 1e-11, "{l} vs {exact}");
        // Reversed limits give the negative.
        let r = arc_length(&|t| vec![1.0, 2.0 * t], 1.0, 0.0, 1e-12);
        assert!((r + exact).abs() < 1e-11);
    }

    #[test]
    fn full_circle_and_nurbs_circle_length() {
        let l = arc_length(
            &|t: f64| vec![-2.0 * t.sin(), 2.0 * t.cos()],
            0.0,
            std::f64::consts::TAU,
            1e-10,
        );
        assert!((l - 4.0 * std::f64::consts::PI).abs() < 1e-9);
        let (k, c, w) = crate::nurbs::nurbs_circle();
        let d = |t: f64| crate::nurbs::nurbs_deriv(&k, 2, &c, &w, t, 1);
        // Integrate per quarter (the derivative is only piecewise smooth).
        let l: f64 = (0..4)
            .map(|q| arc_length(&d, q as f64, q as f64 + 1.0, 1e-11))
            .sum();
        assert!((l - std::f64::consts::TAU).abs() < 1e-9, "{l}");
    }

    #[test]
    fn distances() {
        let a = [0.0, 0.0, 0.0];
        let b = [0.0, 0.0, 4.0];
        assert_eq!(point_segment_distance(&[3.0, 4.0, 2.0], &a, &b), 5.0);
        assert_eq!(point_segment_distance(&[0.0, 0.0, -2.0], &a, &b), 2.0);
        assert_eq!(point_segment_distance(&[0.0, 3.0, 0.0], &a, &a), 3.0);
        let poly = vec![
            vec![0.0, 0.0],
            vec![4.0, 0.0],
            vec![4.0, 4.0],
            vec![0.0, 4.0],
        ];
        assert_eq!(polyline_distance(&[2.0, 1.0], &poly), 1.0);
        assert_eq!(polyline_distance(&[2.0, 3.5], &poly), 0.5);
        assert_eq!(polyline_distance(&[1.0, 1.0], &poly[..1]), 2f64.sqrt());
    }
}
