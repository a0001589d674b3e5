//! A sliced print's G-code, generated, and how fast it is read, planned and compiled on the
//! host: a round part of `LAYERS` layers of 0.2 mm as a slicer writes it (two perimeters of
//! a 20 mm radius in 120 chords each, a hole of 6 mm radius as one `G2` circle, a sparse
//! 45° infill alternating per layer, retractions and travels between them, `M83` relative
//! E, fan and temperature codes). `strak_gcode::Program` hands it to a
//! `Stream<4, 32, 128>` with E riding along, polled into `f32` pieces as a firmware's main
//! loop would, release build, one run on this machine. With `--write FILE` the program is
//! also written to `FILE`, for `strak-sim gcode FILE --machine
//! firmware-sim/examples/machines/printer.toml`.
//!
//! ```text
//! cargo run --release -p strak-bench --bin gcode [LAYERS] [--write FILE]
//! ```

use std::fmt::Write;
use std::time::Instant;

use strak_curves::heapless::Deque;
use strak_gcode::{Program, Reader};
use strak_trajectory::{Limits, NoCurve, Piece, Stream, StreamOptions};

/// The part's centre, outer radius, hole radius (mm).
const CENTRE: (f64, f64) = (100.0, 100.0);
const RADIUS: f64 = 20.0;
const HOLE: f64 = 6.0;
/// Chords of a perimeter.
const CHORDS: u32 = 120;
/// Filament per mm of path: a 0.45 mm line of 0.2 mm layers from 1.75 mm filament.
const E_PER_MM: f64 = 0.45 * 0.2 / (std::f64::consts::PI * 1.75 * 1.75 / 4.0);

/// A program being written, its position kept for the E of each line.
struct Writer {
    g: String,
    at: (f64, f64),
}

impl Writer {
    fn travel(&mut self, x: f64, y: f64) {
        self.g += "G1 E-0.8 F2400\n";
        writeln!(self.g, "G0 X{x:.3} Y{y:.3} F9000").unwrap();
        self.g += "G1 E0.8 F2400\n";
        self.at = (x, y);
    }

    fn extrude(&mut self, x: f64, y: f64, feed: Option<u32>) {
        let d = (x - self.at.0).hypot(y - self.at.1);
        write!(self.g, "G1 X{x:.3} Y{y:.3} E{:.5}", d * E_PER_MM).unwrap();
        if let Some(f) = feed {
            write!(self.g, " F{f}").unwrap();
        }
        self.g.push('\n');
        self.at = (x, y);
    }

    /// A perimeter of radius `r` in chords, starting at angle `phase`.
    fn perimeter(&mut self, r: f64, phase: f64, feed: u32) {
        let point = |k: u32| {
            let a = phase + std::f64::consts::TAU * f64::from(k) / f64::from(CHORDS);
            (CENTRE.0 + r * a.cos(), CENTRE.1 + r * a.sin())
        };
        let (x, y) = point(0);
        self.travel(x, y);
        for k in 1..=CHORDS {
            let (x, y) = point(k);
            self.extrude(x, y, (k == 1).then_some(feed));
        }
    }

    /// The hole's wall: one clockwise circle.
    fn hole(&mut self) {
        let (x, y) = (CENTRE.0 + HOLE + 0.225, CENTRE.1);
        self.travel(x, y);
        let e = std::f64::consts::TAU * (HOLE + 0.225) * E_PER_MM;
        writeln!(
            self.g,
            "G2 X{x:.3} Y{y:.3} I{:.3} J0 E{e:.5} F2400",
            -(HOLE + 0.225)
        )
        .unwrap();
    }

    /// Lines at 45° (−45° on odd layers) 3 mm apart inside the inner perimeter and outside
    /// the hole, joined in a zigzag along the wall.
    fn infill(&mut self, layer: u32) {
        let (r, gap) = (RADIUS - 1.0, 3.0);
        let sign = if layer.is_multiple_of(2) { 1.0 } else { -1.0 };
        let (u, v) = (
            (
                std::f64::consts::FRAC_1_SQRT_2,
                sign * std::f64::consts::FRAC_1_SQRT_2,
            ),
            (
                -sign * std::f64::consts::FRAC_1_SQRT_2,
                std::f64::consts::FRAC_1_SQRT_2,
            ),
        );
        let mut first = true;
        let mut c = -r + gap / 2.0;
        let mut k = 0;
        while c < r {
            let half = (r * r - c * c).sqrt();
            // skip the lines through the hole
            if c.abs() > HOLE + 1.0 {
                let ends = [-half, half];
                let ends = if k % 2 == 0 { ends } else { [half, -half] };
                let at = |t: f64| (CENTRE.0 + c * v.0 + t * u.0, CENTRE.1 + c * v.1 + t * u.1);
                let (x0, y0) = at(ends[0]);
                let (x1, y1) = at(ends[1]);
                if first {
                    self.travel(x0, y0);
                } else {
                    self.extrude(x0, y0, None);
                }
                self.extrude(x1, y1, first.then_some(4800));
                first = false;
                k += 1;
            }
            c += gap;
        }
    }
}

/// The program of `layers` layers.
fn program(layers: u32) -> String {
    let mut w = Writer {
        g: String::from(
            "; generated: a round part with a hole, sliced at 0.2 mm\n\
             M140 S60\nM104 S210\nM190 S60\nM109 S210\nG28\nG21 G90\nM83\nG92 E0\n",
        ),
        at: (0.0, 0.0),
    };
    for layer in 0..layers {
        writeln!(
            w.g,
            ";LAYER:{layer}\nG0 Z{:.2} F600",
            0.2 * f64::from(layer + 1)
        )
        .unwrap();
        if layer == 1 {
            w.g += "M106 S255\n";
        }
        let phase = 0.37 * f64::from(layer);
        w.perimeter(RADIUS - 0.675, phase, 3600);
        w.perimeter(RADIUS - 0.225, phase, 2400);
        w.hole();
        w.infill(layer);
    }
    w.g += "G1 E-0.8 F2400\nG0 Z100 F600\nG0 X0 Y200 F9000\nM104 S0\nM140 S0\nM107\nM84\n";
    w.g
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let layers = args.first().and_then(|a| a.parse().ok()).unwrap_or(100);
    let text = program(layers);
    if let Some(i) = args.iter().position(|a| a == "--write") {
        let file = args.get(i + 1).ok_or("--write needs a file")?;
        std::fs::write(file, &text)?;
    }
    let limits = Limits::new(150.0, 3_000.0, 100_000.0)?
        .with_axis_velocity([300.0, 300.0, 20.0, 60.0])?
        .with_axis_acceleration([5_000.0, 5_000.0, 300.0, 5_000.0])?;
    let options = StreamOptions::new(1_000.0)
        .with_tolerance(0.02)
        .with_arc_tolerance(0.002);
    let mut stream = Box::new(Stream::<4, 32, 128, NoCurve<4>, 1>::new(
        [0.0; 4], limits, options,
    )?);
    let reader = Reader::new(*b"XYZE")?.with_arc_tolerance(0.002);
    let mut program = Program::new(text.as_bytes(), reader, 0.02);
    let mut pieces = Deque::<Piece<f32, 4>, 64>::new();
    let started = Instant::now();
    while !(program.is_finished() && stream.is_idle()) {
        program.feed(&mut stream, usize::MAX)?;
        stream.poll(&mut pieces)?;
        pieces.clear();
    }
    let total = started.elapsed().as_secs_f64();
    let stats = stream.stats();
    println!(
        "{layers} layers: {} bytes, {} lines, {} moves ({} blends, {} stops); motion {:.1} s",
        text.len(),
        program.reader().lines(),
        stats.moves,
        stats.blends,
        stats.stops,
        f64::from(stream.ticks()) / 1_000.0
    );
    println!(
        "read + plan + compile {total:.2} s: {:.0} moves/s",
        stats.moves as f64 / total
    );
    Ok(())
}
