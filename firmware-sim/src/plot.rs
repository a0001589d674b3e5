//! The plots of `strak-sim run`, as SVG: the path, and position, velocity, acceleration and
//! jerk over time.
//!
//! plotters is used with its SVG backend only and without its font features: text is written
//! as SVG `<text>` elements (the viewer renders it), so building needs no system font
//! libraries. Long runs are reduced to at most about [`PLOT_BUCKETS`] buckets per series; each
//! bucket keeps its minimum and maximum, so that peaks (jerk spikes) stay visible.

use std::path::Path as FsPath;

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

/// The number of buckets a series is reduced to (about; holds can add more).
pub const PLOT_BUCKETS: u64 = 2_000;

use crate::axes::{AXIS_NAMES, MAX_AXES};

const AXIS_COLORS: [RGBColor; MAX_AXES] = [
    RGBColor(31, 119, 180),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(23, 190, 207),
];
const NORM_COLOR: RGBColor = RGBColor(0, 0, 0);
const LIMIT_COLOR: RGBColor = RGBColor(214, 39, 40);
const BLEND_COLOR: RGBColor = RGBColor(255, 127, 14);

/// One bucket of consecutive samples: time span and, per channel, minimum and maximum.
#[derive(Clone, Debug)]
struct Bucket {
    t0: f64,
    t1: f64,
    count: u64,
    min: Vec<f64>,
    max: Vec<f64>,
}

/// The quantities of one sample, in channel order: position per axis, velocity per axis and
/// `|v|`, acceleration per axis and `|a|`, jerk per axis and `|j|` (NaN where unknown: the
/// first sample's jerk).
#[derive(Clone, Debug)]
pub struct Recorder {
    axes: usize,
    names: Vec<String>,
    path_axes: usize,
    width: u64,
    buckets: Vec<Bucket>,
    path: Vec<Vec<f64>>,
    since_path_point: u64,
    last_position: Vec<f64>,
}

/// Which channels a quantity occupies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Quantity {
    Position,
    Velocity,
    Acceleration,
    Jerk,
}

impl Recorder {
    /// A recorder for `axes` axes and about `expected` samples.
    pub fn new(axes: usize, expected: u64) -> Self {
        Recorder {
            axes,
            names: (0..axes)
                .map(|a| {
                    AXIS_NAMES
                        .get(a)
                        .map_or(format!("x{}", a + 1), |n| (*n).to_owned())
                })
                .collect(),
            path_axes: axes,
            width: expected.div_ceil(PLOT_BUCKETS).max(1),
            buckets: Vec::new(),
            path: Vec::new(),
            since_path_point: 0,
            last_position: Vec::new(),
        }
    }

    /// The same recorder with the axes named `names` (one per axis), of which the first
    /// `path_axes` make the path (the path plot's projections; the norms of the motion
    /// plot are recorded over them).
    pub fn with_axes<S: AsRef<str>>(mut self, names: &[S], path_axes: usize) -> Self {
        for (n, name) in self.names.iter_mut().zip(names) {
            name.as_ref().clone_into(n);
        }
        self.path_axes = path_axes.clamp(1, self.axes.max(1));
        self
    }

    fn channels(&self) -> usize {
        4 * self.axes + 3
    }

    /// The first channel of a quantity and whether a norm follows the axes.
    fn channel(&self, q: Quantity) -> (usize, bool) {
        let a = self.axes;
        match q {
            Quantity::Position => (0, false),
            Quantity::Velocity => (a, true),
            Quantity::Acceleration => (2 * a + 1, true),
            Quantity::Jerk => (3 * a + 2, true),
        }
    }

    /// Records one sample at time `t` (`values` in channel order, see [`Recorder`]).
    pub fn push(&mut self, t: f64, values: &[f64]) {
        let n = self.channels();
        let start_new = self.buckets.last().is_none_or(|b| b.count >= self.width);
        if start_new {
            self.buckets.push(Bucket {
                t0: t,
                t1: t,
                count: 0,
                min: vec![f64::NAN; n],
                max: vec![f64::NAN; n],
            });
        }
        if let Some(b) = self.buckets.last_mut() {
            b.t1 = t;
            b.count += 1;
            for (i, v) in values.iter().enumerate().take(n) {
                if v.is_finite() {
                    b.min[i] = if b.min[i].is_nan() {
                        *v
                    } else {
                        b.min[i].min(*v)
                    };
                    b.max[i] = if b.max[i].is_nan() {
                        *v
                    } else {
                        b.max[i].max(*v)
                    };
                }
            }
        }
        let position = &values[..self.axes.min(values.len())];
        if self.since_path_point == 0 {
            self.path.push(position.to_vec());
        }
        self.since_path_point = (self.since_path_point + 1) % self.width;
        self.last_position = position.to_vec();
    }

    /// The points of channel `c` over time (min and max of each bucket).
    fn series(&self, c: usize) -> Vec<(f64, f64)> {
        let mut out = Vec::with_capacity(2 * self.buckets.len());
        for b in &self.buckets {
            let t = 0.5 * (b.t0 + b.t1);
            let (lo, hi) = (b.min[c], b.max[c]);
            if lo.is_nan() {
                continue;
            }
            out.push((t, lo));
            if hi != lo {
                out.push((t, hi));
            }
        }
        out
    }

    /// The path's positions (every `width`-th sample and the last).
    fn path_points(&self) -> Vec<Vec<f64>> {
        let mut p = self.path.clone();
        if p.last() != Some(&self.last_position) && !self.last_position.is_empty() {
            p.push(self.last_position.clone());
        }
        p
    }

    fn time_range(&self) -> (f64, f64) {
        let t0 = self.buckets.first().map_or(0.0, |b| b.t0);
        let t1 = self.buckets.last().map_or(1.0, |b| b.t1);
        if t1 > t0 { (t0, t1) } else { (t0, t0 + 1.0) }
    }
}

/// Limits drawn as dashed lines (`None`: no line).
#[derive(Clone, Copy, Debug)]
pub struct PlotLimits {
    /// Path velocity limit.
    pub velocity: Option<f64>,
    /// Path acceleration limit.
    pub acceleration: Option<f64>,
    /// Path jerk limit.
    pub jerk: Option<f64>,
}

type PlotResult = Result<(), String>;

/// A named, coloured series of points.
type Line = (String, RGBColor, Vec<(f64, f64)>);

fn err<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

/// A range containing `lo..hi` with a margin of 5 % (at least ±1e-9 around a constant).
fn padded(lo: f64, hi: f64) -> (f64, f64) {
    if !(lo.is_finite() && hi.is_finite()) {
        return (-1.0, 1.0);
    }
    let span = hi - lo;
    let pad = if span > 0.0 {
        0.05 * span
    } else {
        (lo.abs() * 0.05).max(1e-9)
    };
    (lo - pad, hi + pad)
}

/// Writes `motion.svg`: position, velocity, acceleration and jerk over time, one panel each,
/// per axis and (for v, a, j) the path norm, with the path limits as dashed lines.
pub fn write_motion(
    file: &FsPath,
    rec: &Recorder,
    unit: &str,
    limits: PlotLimits,
    title: &str,
) -> PlotResult {
    let root = SVGBackend::new(file, (1200, 1500)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let root = root.titled(title, ("sans-serif", 24)).map_err(err)?;
    let panels = root.split_evenly((4, 1));
    let specs = [
        (Quantity::Position, format!("position [{unit}]"), None),
        (
            Quantity::Velocity,
            format!("velocity [{unit}/s]"),
            limits.velocity,
        ),
        (
            Quantity::Acceleration,
            format!("acceleration [{unit}/s²]"),
            limits.acceleration,
        ),
        (
            Quantity::Jerk,
            format!("jerk [{unit}/s³] (finite differences)"),
            limits.jerk,
        ),
    ];
    for (panel, (q, label, limit)) in panels.iter().zip(specs) {
        motion_panel(panel, rec, q, &label, limit)?;
    }
    root.present().map_err(err)
}

/// The lines of a quantity's panel: each axis and (for v, a, j) the norm.
fn panel_lines(rec: &Recorder, q: Quantity) -> Vec<Line> {
    let (first, norm) = rec.channel(q);
    let axes = rec.axes.min(AXIS_COLORS.len());
    let mut lines: Vec<Line> = (0..axes)
        .map(|a| (rec.names[a].clone(), AXIS_COLORS[a], rec.series(first + a)))
        .collect();
    if norm {
        lines.push((
            "|path|".to_owned(),
            NORM_COLOR,
            rec.series(first + rec.axes),
        ));
    }
    lines
}

/// The value range of `lines`, widened to show the limit when the data comes near it (within
/// a factor of 3), and padded.
fn value_range(lines: &[Line], limit: Option<f64>) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for (_, _, pts) in lines {
        for (_, v) in pts {
            lo = lo.min(*v);
            hi = hi.max(*v);
        }
    }
    if let Some(l) = limit
        && hi.abs().max(lo.abs()) * 3.0 >= l
    {
        hi = hi.max(l);
        lo = lo.min(if lo < 0.0 { -l } else { lo });
    }
    padded(lo, hi)
}

type Chart<'a> = ChartContext<'a, SVGBackend<'a>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// The dashed lines at `±limit` that fall within `y0 ..= y1`.
fn draw_limit(chart: &mut Chart<'_>, limit: f64, t: (f64, f64), y: (f64, f64)) -> PlotResult {
    for (i, v) in [limit, -limit].into_iter().enumerate() {
        if v >= y.0 && v <= y.1 {
            let series = chart
                .draw_series(DashedLineSeries::new(
                    vec![(t.0, v), (t.1, v)],
                    8,
                    6,
                    LIMIT_COLOR.stroke_width(1),
                ))
                .map_err(err)?;
            if i == 0 {
                series.label("limit").legend(|(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], LIMIT_COLOR.stroke_width(1))
                });
            }
        }
    }
    Ok(())
}

fn motion_panel(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    rec: &Recorder,
    q: Quantity,
    label: &str,
    limit: Option<f64>,
) -> PlotResult {
    let lines = panel_lines(rec, q);
    let (y0, y1) = value_range(&lines, limit);
    let (t0, t1) = rec.time_range();
    let mut chart = ChartBuilder::on(area)
        .margin(8)
        .x_label_area_size(32)
        .y_label_area_size(80)
        .build_cartesian_2d(t0..t1, y0..y1)
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("t [s]")
        .y_desc(label)
        .label_style(("sans-serif", 13))
        .axis_desc_style(("sans-serif", 15))
        .draw()
        .map_err(err)?;
    for (name, color, pts) in lines {
        chart
            .draw_series(LineSeries::new(
                pts,
                color.stroke_width(if name.starts_with('|') { 2 } else { 1 }),
            ))
            .map_err(err)?
            .label(name)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
    }
    if let Some(l) = limit {
        draw_limit(&mut chart, l, (t0, t1), (y0, y1))?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.4))
        .label_font(("sans-serif", 13))
        .draw()
        .map_err(err)
}

/// Expands the ranges so that one unit has the same length on both axes of a panel of
/// `w × h` pixels (approximately: the label areas are estimated).
fn equal_aspect(x: (f64, f64), y: (f64, f64), w: f64, h: f64) -> ((f64, f64), (f64, f64)) {
    let (x, y) = (padded(x.0, x.1), padded(y.0, y.1));
    let (dx, dy) = (x.1 - x.0, y.1 - y.0);
    let scale = (dx / w).max(dy / h);
    let (cx, cy) = (0.5 * (x.0 + x.1), 0.5 * (y.0 + y.1));
    let (hx, hy) = (0.5 * scale * w, 0.5 * scale * h);
    ((cx - hx, cx + hx), (cy - hy, cy + hy))
}

fn bounds(points: &[Vec<f64>], axis: usize) -> (f64, f64) {
    points
        .iter()
        .filter_map(|p| p.get(axis).copied())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        })
}

/// What the path plot marks besides the path: the blends that replaced corners (drawn in
/// another colour over the path), blended corners (small circles, where the blends are not
/// drawn) and the corners where the motion stopped (squares).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PathMarks {
    /// Each blend as points along it.
    pub blends: Vec<Vec<Vec<f64>>>,
    /// Each corner a blend replaced.
    pub corners: Vec<Vec<f64>>,
    /// Each corner where the motion came to rest.
    pub stops: Vec<Vec<f64>>,
}

/// Writes `path.svg`: the path in the x–y plane (one axis: x over t; three or more axes: the
/// x–y, x–z and y–z projections side by side), start marked by a circle and end by a cross,
/// equal scales on both axes of each projection, and the `marks` (in the projections).
pub fn write_path(
    file: &FsPath,
    rec: &Recorder,
    unit: &str,
    title: &str,
    marks: &PathMarks,
) -> PlotResult {
    let points = rec.path_points();
    let size = if rec.path_axes >= 3 {
        (1800, 680)
    } else {
        (900, 800)
    };
    let root = SVGBackend::new(file, size).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let root = root.titled(title, ("sans-serif", 24)).map_err(err)?;
    let names = &rec.names;
    match rec.path_axes {
        1 => {
            let pts: Vec<(f64, f64)> = rec.series(0);
            let (t0, t1) = rec.time_range();
            let (lo, hi) = pts
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), (_, v)| {
                    (l.min(*v), h.max(*v))
                });
            let (y0, y1) = padded(lo, hi);
            let mut chart = ChartBuilder::on(&root)
                .margin(10)
                .x_label_area_size(35)
                .y_label_area_size(80)
                .build_cartesian_2d(t0..t1, y0..y1)
                .map_err(err)?;
            chart
                .configure_mesh()
                .x_desc("t [s]")
                .y_desc(format!("{} [{unit}]", names[0]))
                .draw()
                .map_err(err)?;
            chart
                .draw_series(LineSeries::new(pts, AXIS_COLORS[0].stroke_width(2)))
                .map_err(err)?;
        }
        2 => projection(&root, &points, marks, (names, (0, 1)), unit, size)?,
        _ => {
            let panels = root.split_evenly((1, 3));
            let third = (size.0 / 3, size.1);
            for (panel, pair) in panels.iter().zip([(0, 1), (0, 2), (1, 2)]) {
                projection(panel, &points, marks, (names, pair), unit, third)?;
            }
        }
    }
    root.present().map_err(err)
}

fn projection(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    points: &[Vec<f64>],
    marks: &PathMarks,
    (names, (i, j)): (&[String], (usize, usize)),
    unit: &str,
    size: (u32, u32),
) -> PlotResult {
    let (xr, yr) = equal_aspect(
        bounds(points, i),
        bounds(points, j),
        f64::from(size.0) - 100.0,
        f64::from(size.1) - 90.0,
    );
    let mut chart = ChartBuilder::on(area)
        .margin(10)
        .caption(format!("{}–{}", names[i], names[j]), ("sans-serif", 18))
        .x_label_area_size(35)
        .y_label_area_size(65)
        .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc(format!("{} [{unit}]", names[i]))
        .y_desc(format!("{} [{unit}]", names[j]))
        .draw()
        .map_err(err)?;
    let xy = |p: &Vec<f64>| {
        (
            p.get(i).copied().unwrap_or(0.0),
            p.get(j).copied().unwrap_or(0.0),
        )
    };
    chart
        .draw_series(LineSeries::new(
            points.iter().map(xy),
            AXIS_COLORS[0].stroke_width(2),
        ))
        .map_err(err)?;
    draw_marks(&mut chart, marks, &xy)?;
    if let (Some(first), Some(last)) = (points.first(), points.last()) {
        chart
            .draw_series(std::iter::once(Circle::new(
                xy(first),
                5,
                AXIS_COLORS[1].filled(),
            )))
            .map_err(err)?;
        chart
            .draw_series(std::iter::once(Cross::new(
                xy(last),
                6,
                LIMIT_COLOR.stroke_width(2),
            )))
            .map_err(err)?;
    }
    Ok(())
}

/// The blends (orange over the path, labelled) and the stops (hollow squares).
fn draw_marks(
    chart: &mut Chart<'_>,
    marks: &PathMarks,
    xy: &dyn Fn(&Vec<f64>) -> (f64, f64),
) -> PlotResult {
    for (k, blend) in marks.blends.iter().enumerate() {
        let series = chart
            .draw_series(LineSeries::new(
                blend.iter().map(xy),
                BLEND_COLOR.stroke_width(3),
            ))
            .map_err(err)?;
        if k == 0 {
            series.label("corner blends").legend(|(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], BLEND_COLOR.stroke_width(3))
            });
        }
    }
    for (k, corner) in marks.corners.iter().enumerate() {
        let series = chart
            .draw_series(std::iter::once(Circle::new(
                xy(corner),
                3,
                BLEND_COLOR.stroke_width(1),
            )))
            .map_err(err)?;
        if k == 0 {
            series
                .label("blended corners")
                .legend(|(x, y)| Circle::new((x + 10, y), 3, BLEND_COLOR.stroke_width(1)));
        }
    }
    for (k, stop) in marks.stops.iter().enumerate() {
        let (x, y) = xy(stop);
        let series = chart
            .draw_series(std::iter::once(
                EmptyElement::at((x, y))
                    + Rectangle::new([(-5, -5), (5, 5)], LIMIT_COLOR.stroke_width(1)),
            ))
            .map_err(err)?;
        if k == 0 {
            series.label("stops").legend(|(x, y)| {
                Rectangle::new(
                    [(x + 5, y - 5), (x + 15, y + 5)],
                    LIMIT_COLOR.stroke_width(1),
                )
            });
        }
    }
    if !(marks.blends.is_empty() && marks.corners.is_empty() && marks.stops.is_empty()) {
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK.mix(0.4))
            .label_font(("sans-serif", 13))
            .draw()
            .map_err(err)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn buckets_keep_minima_and_maxima() {
        let mut r = Recorder::new(1, 4 * PLOT_BUCKETS);
        // 4 samples per bucket
        for k in 0..8 {
            let v = if k == 5 { 10.0 } else { k as f64 };
            r.push(k as f64, &[v, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
        }
        assert_eq!(r.buckets.len(), 2);
        let s = r.series(0);
        assert_eq!(s, vec![(1.5, 0.0), (1.5, 3.0), (5.5, 4.0), (5.5, 10.0)]);
        assert_eq!(r.path_points(), vec![vec![0.0], vec![4.0], vec![7.0]]);
    }

    #[test]
    fn equal_aspect_expands_the_short_side() {
        let ((x0, x1), (y0, y1)) = equal_aspect((0.0, 10.0), (0.0, 1.0), 100.0, 100.0);
        assert!(((x1 - x0) - (y1 - y0)).abs() < 1e-9);
        assert!(x0 < 0.0 && x1 > 10.0);
    }
}
