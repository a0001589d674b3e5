//! The programmed path of a moves job, for measuring how far the samples stray from it:
//! each move as a polygon (a line as its chord, a curved move as [`CHORDS`] chords of equal
//! parameter steps), and the nearest point of the polygons to a sample.
//!
//! A chord of a curve `c` over a parameter step `h` lies within `h²·max|c''| / 8` of the
//! curve (the sag of linear interpolation; de Boor, *A Practical Guide to Splines*, ch. II),
//! so the distance from the polygons is the distance from the moves within
//! [`Programmed::sag`]. The samples move along the path, so the search looks at the move
//! of the last nearest point and the few after it.

use strak_curves::ParamCurve;
use strak_trajectory::{Move, MoveCurve, Shape};

/// The chords of a curved move's polygon.
pub const CHORDS: usize = 256;

/// The moves searched after the one of the last nearest point.
const AHEAD: usize = 3;

/// The programmed moves as polygons.
#[derive(Clone, Debug)]
pub struct Programmed<const D: usize> {
    polygons: Vec<Vec<[f64; D]>>,
    /// The largest sag of a chord under its move.
    pub sag: f64,
    /// The arc length of the moves.
    pub length: f64,
    /// The end of the last move.
    pub end: [f64; D],
    /// The largest coordinate of the polygons.
    pub far: f64,
    cursor: usize,
}

/// The point of the segment `a b` nearest to `p`.
fn nearest_on<const D: usize>(a: &[f64; D], b: &[f64; D], p: &[f64; D]) -> [f64; D] {
    let mut ab = 0.0;
    let mut ap = 0.0;
    for i in 0..D {
        let d = b[i] - a[i];
        ab += d * d;
        ap += d * (p[i] - a[i]);
    }
    let u = if ab > 0.0 {
        (ap / ab).clamp(0.0, 1.0)
    } else {
        0.0
    };
    core::array::from_fn(|i| a[i] + u * (b[i] - a[i]))
}

fn dist2<const D: usize>(a: &[f64; D], b: &[f64; D]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

impl<const D: usize> Programmed<D> {
    /// The polygons of `program` from `start`; moves whose curve cannot be built (checked
    /// before: none) are taken as lines.
    pub fn new(start: [f64; D], program: &[Move<D>], arc_tolerance: f64) -> Self {
        let mut from = start;
        let (mut polygons, mut sag, mut length) = (Vec::new(), 0.0_f64, 0.0);
        for mv in program {
            let curve = MoveCurve::new(from, mv, arc_tolerance);
            let polygon = match (&mv.shape, &curve) {
                (Shape::Line, _) | (_, Err(_)) => vec![from, mv.to],
                (_, Ok(c)) => {
                    let h = 1.0 / CHORDS as f64;
                    sag = sag.max(h * h * c.second_derivative_bound() / 8.0);
                    (0..=CHORDS).map(|k| c.eval(k as f64 * h)).collect()
                }
            };
            length += curve.map_or(0.0, |c| c.length());
            polygons.push(polygon);
            from = mv.to;
        }
        let far = polygons
            .iter()
            .flatten()
            .flatten()
            .fold(0.0_f64, |m, x| m.max(x.abs()));
        Programmed {
            polygons,
            sag,
            length,
            end: from,
            far,
            cursor: 0,
        }
    }

    /// The point of the moves nearest to `p`, among the move of the last nearest point and
    /// the three after it.
    pub fn nearest(&mut self, p: &[f64; D]) -> [f64; D] {
        let mut best = (f64::INFINITY, *p, self.cursor);
        let last = (self.cursor + AHEAD).min(self.polygons.len().saturating_sub(1));
        for m in self.cursor..=last {
            let Some(polygon) = self.polygons.get(m) else {
                break;
            };
            for w in polygon.windows(2) {
                let q = nearest_on(&w[0], &w[1], p);
                let d = dist2(&q, p);
                if d < best.0 {
                    best = (d, q, m);
                }
            }
        }
        self.cursor = best.2;
        best.1
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use strak_curves::{Plane, Turn};

    #[test]
    fn nearest_points_of_a_line_and_an_arc() {
        let arc = Shape::ArcCenter {
            center: [10.0, 10.0],
            plane: Plane::XY,
            turn: Turn::CounterClockwise,
        };
        let program = [Move::line([10.0, 0.0]), Move::new([20.0, 10.0], arc)];
        let mut p = Programmed::new([0.0, 0.0], &program, 1e-9);
        assert_eq!(p.nearest(&[5.0, 1.0]), [5.0, 0.0]);
        let q = p.nearest(&[30.0, 10.0]);
        assert!(dist2(&q, &[20.0, 10.0]) < 1e-20, "{q:?}");
        let length = 10.0 + 10.0 * core::f64::consts::FRAC_PI_2;
        assert!((p.length - length).abs() < 1e-12);
        assert!(p.sag > 0.0 && p.sag < 1e-3);
        assert_eq!((p.end, p.far), ([20.0, 10.0], 20.0));
    }
}
