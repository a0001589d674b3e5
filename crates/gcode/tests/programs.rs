//! Whole programs read and streamed end to end: a printed part (perimeters with rounded
//! corners, zigzag infill, retractions, layer changes; E relative, riding along) and a
//! milled contour (lines and arcs, path modes, a dwell). From the played ticks: the path's
//! limits over X, Y, Z, E's own limits, the corners within the tolerance, and the end
//! exactly at the program's last position, E included.

use std::fmt::Write;

use strak_curves::Point;
use strak_curves::heapless::Deque;
use strak_gcode::{Feeder, Reader, lines};
use strak_trajectory::{
    AxisState, Limits, NoCurve, Number, Piece, PlanOptions, Q40, Stream, StreamOptions,
};

const V: f64 = 150.0;
const A: f64 = 3000.0;
const J: f64 = 100_000.0;
const TOLERANCE: f64 = 0.02;

/// A printed part: `layers` layers of a 40 mm square perimeter with corners rounded by
/// quarter arcs (`G3 … R`), a retraction, a travel and a prime, and a zigzag infill of
/// 2 mm spacing; E relative (`M83`), 0.05 mm of E per mm of path.
fn printed(layers: u32) -> String {
    let mut g = String::from("; a sliced-looking part\nG21 G90 M83\nM104 S210\nG92 E0\n");
    let e = |mm: f64| mm * 0.05;
    for layer in 0..layers {
        let z = 0.2 * f64::from(layer + 1);
        writeln!(g, "G0 X25 Y20 Z{z:.2} F9000").unwrap();
        writeln!(g, "G1 X55 E{:.5} F2400", e(30.0)).unwrap();
        writeln!(g, "G3 X60 Y25 R5 E{:.5}", e(7.854)).unwrap();
        writeln!(g, "G1 Y55 E{:.5}", e(30.0)).unwrap();
        writeln!(g, "G3 X55 Y60 R5 E{:.5}", e(7.854)).unwrap();
        writeln!(g, "G1 X25 E{:.5}", e(30.0)).unwrap();
        writeln!(g, "G3 X20 Y55 R5 E{:.5}", e(7.854)).unwrap();
        writeln!(g, "G1 Y25 E{:.5}", e(30.0)).unwrap();
        writeln!(g, "G3 X25 Y20 I5 J0 E{:.5}", e(7.854)).unwrap();
        g.push_str("G1 E-0.8 F2100 ; retract\nG0 X24 Y24\nG1 E0.8 F2100 ; prime\n");
        let mut y = 24.0;
        let mut right = true;
        while y <= 56.0 {
            let x = if right { 56.0 } else { 24.0 };
            writeln!(g, "G1 X{x} Y{y} E{:.5} F3000", e(32.0)).unwrap();
            y += 2.0;
            if y <= 56.0 {
                writeln!(g, "G1 Y{y} E{:.5}", e(2.0)).unwrap();
            }
            right = !right;
        }
        g.push_str("G1 E-0.8 F2100\n");
    }
    g.push_str("G0 Z10\nM107\n");
    g
}

/// A milled contour in three axes: lines and arcs, a plunge, a dwell, blended corners under
/// `G64 P`, exact stops under `G61`.
fn contour() -> &'static str {
    "G21 G90 G17 G64 P0.02\n\
     G0 X0 Y0 Z5\n\
     G1 Z-1 F300\n\
     G4 P0.2\n\
     G1 X40 F1800\n\
     G2 X50 Y-10 I0 J-10\n\
     G1 Y-30\n\
     G3 X40 Y-40 R10\n\
     G1 X10\n\
     G61\n\
     G1 X0 Y-30\n\
     G64 P0.05\n\
     G1 Y0\n\
     G0 Z5\n"
}

/// The played ticks of a program read for the axes `axes` and streamed through a
/// `Stream<D, 32, 128, NoCurve<D>, R>`, in `N`; with the reader and the stream after it.
struct Run<const D: usize, const R: usize> {
    x: Vec<[f64; D]>,
    v: Vec<[f64; D]>,
    a: Vec<[f64; D]>,
    reader: Reader<D>,
    stream: Box<Stream<D, 32, 128, NoCurve<D>, R>>,
}

fn run<N: Number, const D: usize, const R: usize>(
    program: &str,
    axes: [u8; D],
    limits: Limits<D>,
) -> Run<D, R> {
    let options = StreamOptions::new(1000.0)
        .with_tolerance(TOLERANCE)
        .with_arc_tolerance(0.002);
    run_with::<N, D, R>(program, axes, limits, options)
}

fn run_with<N: Number, const D: usize, const R: usize>(
    program: &str,
    axes: [u8; D],
    limits: Limits<D>,
    options: StreamOptions,
) -> Run<D, R> {
    let mut stream = Box::new(Stream::new([0.0; D], limits, options).unwrap());
    let mut reader = Reader::new(axes).unwrap();
    let mut feeder = Feeder::new(TOLERANCE);
    let mut queue = Deque::<Piece<N, D>, 64>::new();
    let (mut x, mut v, mut a) = (Vec::new(), Vec::new(), Vec::new());
    let mut text = lines(program.as_bytes());
    let mut handed = false;
    let mut last = None;
    for _ in 0..10_000_000 {
        if !handed {
            if feeder.is_ready() {
                match text.next() {
                    Some(line) => {
                        let block = reader.read_line(line).unwrap();
                        feeder.offer(block, &mut stream).unwrap();
                    }
                    None => handed = feeder.finish(&mut stream).unwrap(),
                }
            } else {
                feeder.retry(&mut stream).unwrap();
            }
        }
        stream.poll(&mut queue).unwrap();
        while let Some(p) = queue.pop_front() {
            let mut s = *p.axes();
            for _ in 0..p.ticks() {
                x.push(s.map(|c| c.position.to_f64()));
                v.push(s.map(|c| c.velocity.to_f64()));
                a.push(s.map(|c| c.acceleration.to_f64()));
                s.iter_mut().for_each(AxisState::step);
            }
            last = Some(s);
        }
        if handed && stream.is_idle() {
            x.push(last.unwrap().map(|c| c.position.to_f64()));
            return Run {
                x,
                v,
                a,
                reader,
                stream,
            };
        }
    }
    panic!("the program does not end");
}

impl<const D: usize, const R: usize> Run<D, R> {
    /// The largest path speed, acceleration and jerk over the first `D − R` axes, and
    /// each axis's largest velocity and acceleration, from differences of the ticks.
    fn peaks(&self) -> ([f64; 3], [[f64; 2]; D]) {
        let path = |p: [f64; D]| -> f64 { p[..D - R].iter().map(|c| c * c).sum::<f64>().sqrt() };
        let (mut norms, mut axes) = ([0.0_f64; 3], [[0.0_f64; 2]; D]);
        for k in 1..self.v.len() {
            let dx = self.x[k].minus(self.x[k - 1]).times(1000.0);
            let dv = self.v[k].minus(self.v[k - 1]).times(1000.0);
            let da = self.a[k].minus(self.a[k - 1]).times(1000.0);
            norms[0] = norms[0].max(path(dx));
            norms[1] = norms[1].max(path(dv));
            norms[2] = norms[2].max(path(da));
            for i in 0..D {
                axes[i][0] = axes[i][0].max(dx[i].abs());
                axes[i][1] = axes[i][1].max(dv[i].abs());
            }
        }
        (norms, axes)
    }
}

/// The printed part in `f64`, `f32` and `Q40`: the path keeps its limits over X, Y, Z, E
/// its own (40 mm/s, 1000 mm/s²), the corners stay within the tolerance, and the motion
/// ends exactly at the program's last position with E at its last value.
#[test]
fn a_printed_part_streams_within_the_limits() {
    fn check<N: Number>(slack: f64) {
        let limits = Limits::new(V, A, J)
            .and_then(|l| l.with_axis_velocity([f64::INFINITY, f64::INFINITY, 20.0, 40.0]))
            .and_then(|l| l.with_axis_acceleration([f64::INFINITY, f64::INFINITY, 500.0, 1000.0]))
            .unwrap();
        let program = printed(2);
        let r: Run<4, 1> = run::<N, 4, 1>(&program, *b"XYZE", limits);
        let keep = 1.0 - PlanOptions::DEFAULT_FEED_SHARE;
        let ([v, a, j], axes) = r.peaks();
        let stats = r.stream.stats();
        println!(
            "{}: {} ticks, {} moves, v {v:.2} a {a:.1} j {j:.0}, Z {:?}, E {:?}, {stats:?}",
            N::NAME,
            r.x.len(),
            stats.moves,
            axes[2],
            axes[3]
        );
        assert!(
            v <= V * (1.0 + slack) && a <= keep * A * (1.0 + slack),
            "{v} {a}"
        );
        assert!(j <= keep * J * (1.0 + 100.0 * slack), "{j}");
        assert!(axes[2][0] <= 20.0 * (1.0 + slack) && axes[2][1] <= keep * 500.0 * (1.0 + slack));
        assert!(axes[3][0] <= 40.0 * (1.0 + slack) && axes[3][1] <= keep * 1000.0 * (1.0 + slack));
        assert!(
            stats.max_deviation <= TOLERANCE && stats.blends > 10,
            "{stats:?}"
        );
        let end = *r.x.last().unwrap();
        let want = r
            .reader
            .position()
            .map(|c| N::from_f64(c).unwrap().to_f64());
        assert_eq!(end, want, "{}", N::NAME);
        // E in relative steps of five decimals: per layer the perimeter, the infill, and
        // a retraction left at the end
        let per_layer = (4.0 * 30.0 + 4.0 * 7.854 + 17.0 * 32.0 + 16.0 * 2.0) * 0.05 - 0.8;
        assert!((end[3] - 2.0 * per_layer).abs() < 1e-3, "E {}", end[3]);
        let ignored = r.reader.ignored().kinds();
        assert_eq!(ignored.len(), 3, "{ignored:?}"); // M104, S, M107
    }
    check::<f64>(1e-9);
    check::<f32>(1e-3);
    check::<Q40>(1e-9);
}

/// A printed layer with a dense zigzag infill (0.5 mm steps between 32 mm lines, E riding
/// along) with every corner blended that can be: spans of a few ticks between the jerk's breaks near the jerk limit,
/// where a clamped spline overshoots the jerk by parts in 10⁴, are compiled as pieces of
/// one tick, and the ticks keep the limits.
#[test]
fn a_dense_blended_infill_keeps_the_jerk() {
    let mut g = String::from("G21 G90 M83\nG0 X25 Y20 Z0.2\n");
    for (x, y, arc) in [
        (55.0, 20.0, "G3 X60 Y25 R5"),
        (60.0, 55.0, "G3 X55 Y60 R5"),
        (25.0, 60.0, "G3 X20 Y55 R5"),
        (20.0, 25.0, "G3 X25 Y20 R5"),
    ] {
        writeln!(g, "G1 X{x} Y{y} E1.5 F2400\n{arc} E0.39270").unwrap();
    }
    g.push_str("G1 E-0.8 F2100\nG0 X24 Y24\nG1 E0.8 F2100\n");
    let (mut y, mut right) = (24.0, true);
    while y <= 56.0 {
        let x = if right { 56.0 } else { 24.0 };
        writeln!(g, "G1 X{x} Y{y:.1} E1.6 F3000").unwrap();
        y += 0.5;
        if y <= 56.0 {
            writeln!(g, "G1 Y{y:.1} E0.025").unwrap();
        }
        right = !right;
    }
    let limits = Limits::new(V, A, J)
        .and_then(|l| l.with_axis_velocity([f64::INFINITY, f64::INFINITY, 20.0, 40.0]))
        .and_then(|l| l.with_axis_acceleration([f64::INFINITY, f64::INFINITY, 500.0, 1000.0]))
        .unwrap();
    let options = StreamOptions::new(1000.0)
        .with_tolerance(TOLERANCE)
        .with_faster_stops(false);
    let r: Run<4, 1> = run_with::<f64, 4, 1>(&g, *b"XYZE", limits, options);
    let keep = 1.0 - PlanOptions::DEFAULT_FEED_SHARE;
    let ([v, a, j], axes) = r.peaks();
    let stats = r.stream.stats();
    println!(
        "{} ticks, v {v:.2} a {a:.1} j {j:.1}, E {:?}, {stats:?}",
        r.x.len(),
        axes[3]
    );
    assert!(v <= V * (1.0 + 1e-9) && a <= keep * A * (1.0 + 1e-9) && j <= keep * J * (1.0 + 1e-9));
    assert!(stats.blends > 120, "{stats:?}");
    assert_eq!(*r.x.last().unwrap(), r.reader.position());
}

/// The milled contour: the limits from the ticks, the dwell at the plunge, the corners
/// blended within their `G64 P` and stopped under `G61`, and the end exactly at the
/// program's last position.
#[test]
fn a_milled_contour_streams_within_the_limits() {
    fn check<N: Number>(slack: f64) {
        let limits = Limits::new(V, A, J).unwrap();
        let r: Run<3, 0> = run::<N, 3, 0>(contour(), *b"XYZ", limits);
        let keep = 1.0 - PlanOptions::DEFAULT_FEED_SHARE;
        let ([v, a, j], _) = r.peaks();
        let stats = r.stream.stats();
        println!(
            "{}: {} ticks, v {v:.2} a {a:.1} j {j:.0}, {stats:?}",
            N::NAME,
            r.x.len()
        );
        assert!(v <= V * (1.0 + slack) && a <= keep * A * (1.0 + slack));
        assert!(j <= keep * J * (1.0 + 100.0 * slack));
        assert!(
            stats.max_deviation <= 0.05 && stats.blends >= 2 && stats.stops >= 1,
            "{stats:?}"
        );
        let plunge = [0.0, 0.0, -1.0].map(|c| N::from_f64(c).unwrap().to_f64());
        let held = r.x.iter().filter(|p| **p == plunge).count();
        assert!(held >= 200, "{held} ticks at the plunge");
        let want = [0.0, 0.0, 5.0].map(|c| N::from_f64(c).unwrap().to_f64());
        assert_eq!(*r.x.last().unwrap(), want);
    }
    check::<f64>(1e-9);
    check::<f32>(1e-3);
    check::<Q40>(1e-9);
}
