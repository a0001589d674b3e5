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

/// How much nearer (units) a later move's point must be to take over, besides the sag.
const TIE: f64 = 1e-9;

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
    /// The chord of the last nearest point in its polygon.
    chord: usize,
    path_axes: usize,
    /// Each polygon's length in the path axes.
    lengths: Vec<f64>,
    skip: f64,
}

/// The point of the segment `a b` nearest to `p` in the first `axes` axes (its end `b` for
/// a segment of no length in those axes).
fn nearest_on<const D: usize>(a: &[f64; D], b: &[f64; D], p: &[f64; D], axes: usize) -> [f64; D] {
    let mut ab = 0.0;
    let mut ap = 0.0;
    for i in 0..axes {
        let d = b[i] - a[i];
        ab += d * d;
        ap += d * (p[i] - a[i]);
    }
    let u = if ab > 0.0 {
        (ap / ab).clamp(0.0, 1.0)
    } else {
        1.0
    };
    core::array::from_fn(|i| a[i] + u * (b[i] - a[i]))
}

/// `|a − b|²` in the first `axes` axes.
fn dist2<const D: usize>(a: &[f64; D], b: &[f64; D], axes: usize) -> f64 {
    a[..axes]
        .iter()
        .zip(&b[..axes])
        .map(|(x, y)| (x - y) * (x - y))
        .sum()
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
            chord: 0,
            path_axes: D,
            lengths: Vec::new(),
            skip: f64::INFINITY,
        }
        .measured()
    }

    /// Each polygon's length in the path axes.
    fn measured(mut self) -> Self {
        let axes = self.path_axes;
        self.lengths = self
            .polygons
            .iter()
            .map(|p| p.windows(2).map(|w| dist2(&w[0], &w[1], axes).sqrt()).sum())
            .collect();
        self
    }

    /// The same polygons, a sample passing in one step over moves no longer than `length`
    /// (in the path axes): a chain of short moves a blend cuts across, or moves of the
    /// riding axes alone; and moving at most `length` along a move between two samples, so
    /// that a search looks that far along from the last nearest point. Longer moves are
    /// never passed over (default: the search looks at whole moves and passes over any).
    pub fn with_skip(mut self, length: f64) -> Self {
        self.skip = length;
        self
    }

    /// The same polygons, measured in the first `path_axes` axes only (1 to `D`): the
    /// nearest point is nearest in those axes, the axes after them riding along.
    pub fn with_path_axes(mut self, path_axes: usize) -> Self {
        self.path_axes = path_axes.clamp(1, D.max(1));
        self.measured()
    }

    /// The point of the moves nearest to `p` (in the path axes), among the move of the
    /// last nearest point, the next one, and up to two more after it where the moves
    /// between are no longer than the skip length ([`with_skip`](Self::with_skip)): the
    /// samples follow the moves in order, and where a later move passes near the one
    /// being played (a full circle's start, a retraction up through the corner of a
    /// blend), the move being played keeps them. A later move takes over only when its
    /// point is nearer by more than twice the chords' sag (and rounding), which the
    /// polygon of the move being played may lie farther than its move.
    pub fn nearest(&mut self, p: &[f64; D]) -> [f64; D] {
        let margin = 2.0 * self.sag + TIE;
        let (d, q, k) = self.nearest_in(self.cursor, self.chord, p, None);
        let mut best = (d, q, self.cursor, k);
        let last = (self.cursor + AHEAD).min(self.polygons.len().saturating_sub(1));
        for m in self.cursor + 1..=last {
            let (d, q, k) = self.nearest_in(m, 0, p, Some(self.skip + best.0));
            if d + margin < best.0 {
                best = (d, q, m, k);
            }
            if self.lengths.get(m).is_some_and(|&l| l > self.skip) {
                break;
            }
        }
        (self.cursor, self.chord) = (best.2, best.3);
        best.1
    }

    /// The distance of `p` from the polygon of move `m`, its nearest point and that
    /// point's chord, searched from the chord before `from` on as far as `reach` along the
    /// polygon (`None`: the skip length plus the distance found).
    fn nearest_in(
        &self,
        m: usize,
        from: usize,
        p: &[f64; D],
        reach: Option<f64>,
    ) -> (f64, [f64; D], usize) {
        let mut here = (f64::INFINITY, *p, from);
        let Some(polygon) = self.polygons.get(m) else {
            return here;
        };
        let axes = self.path_axes;
        let mut walked = 0.0;
        for k in from.saturating_sub(1)..polygon.len().saturating_sub(1) {
            let (a, b) = (&polygon[k], &polygon[k + 1]);
            let q = nearest_on(a, b, p, axes);
            let d = dist2(&q, p, axes);
            if d < here.0 {
                here = (d, q, k);
            }
            if k >= from {
                walked += dist2(a, b, axes).sqrt();
                if walked > reach.unwrap_or_else(|| self.skip + here.0.sqrt()) {
                    break;
                }
            }
        }
        (here.0.sqrt(), here.1, here.2)
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
        assert!(dist2(&q, &[20.0, 10.0], 2) < 1e-20, "{q:?}");
        let length = 10.0 + 10.0 * core::f64::consts::FRAC_PI_2;
        assert!((p.length - length).abs() < 1e-12);
        assert!(p.sag > 0.0 && p.sag < 1e-3);
        assert_eq!((p.end, p.far), ([20.0, 10.0], 20.0));
    }

    /// A line, a full circle from its end and a line up through the same point: a sample
    /// near the corner (as a blend passes it) lies nearer the last line, but the circle
    /// (too long to pass over) keeps the samples that follow along it.
    #[test]
    fn a_later_move_through_the_corner_does_not_take_over() {
        let circle = Shape::ArcCenter {
            center: [0.0, 0.0],
            plane: Plane::XY,
            turn: Turn::CounterClockwise,
        };
        let program = [
            Move::line([10.0, 0.0, 0.0]),
            Move::new([10.0, 0.0, 0.0], circle),
            Move::line([10.0, 0.0, 5.0]),
        ];
        let mut p = Programmed::new([0.0; 3], &program, 1e-9).with_skip(0.1);
        let q = p.nearest(&[9.99, 0.0, 0.0]);
        assert!(dist2(&q, &[9.99, 0.0, 0.0], 3) < 1e-20, "{q:?}");
        let q = p.nearest(&[10.0, 0.0005, 0.003]);
        assert!(dist2(&q, &[10.0, 0.0005, 0.003], 3).sqrt() > 0.002, "{q:?}");
        let along = [10.0 * 0.005_f64.cos(), 10.0 * 0.005_f64.sin(), 0.0];
        let on_circle = p.nearest(&along);
        assert!(dist2(&on_circle, &along, 3).sqrt() < 1e-3, "{on_circle:?}");
        // a short line may be passed over
        let program = [
            Move::line([10.0, 0.0, 0.0]),
            Move::line([10.0, 0.05, 0.0]),
            Move::line([0.0, 0.05, 0.0]),
        ];
        let mut p = Programmed::new([0.0; 3], &program, 1e-9).with_skip(0.1);
        let q = p.nearest(&[5.0, 0.05, 0.0]);
        assert!(dist2(&q, &[5.0, 0.05, 0.0], 3) < 1e-20, "{q:?}");
    }
}
