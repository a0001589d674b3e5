//! How fast a sliced print's G-code is read, planned and compiled on the host: a generated
//! part of `LAYERS` layers (each a 40 mm perimeter with rounded corners, a retraction, a
//! travel and a prime, and a zigzag infill of 0.5 mm spacing; E relative and riding along)
//! read by `strak_gcode::Reader` and handed by a `Feeder` to a `Stream<4, 32, 128>` with E
//! riding along, polled into `f32` pieces as a firmware's main loop would (one line per
//! poll), release build, one run on this machine.
//!
//! ```text
//! cargo run --release -p strak-bench --bin gcode [LAYERS]
//! ```

use std::fmt::Write;
use std::time::Instant;

use strak_curves::heapless::Deque;
use strak_gcode::{Feeder, Reader, lines};
use strak_trajectory::{Limits, NoCurve, Piece, Stream, StreamOptions};

/// The program of `layers` layers.
fn program(layers: u32) -> String {
    let mut g = String::from("G21 G90 M83\nM104 S210\nG92 E0\n");
    let e = |mm: f64| mm * 0.05;
    for layer in 0..layers {
        let z = 0.2 * f64::from(layer + 1);
        writeln!(g, "G0 X25 Y20 Z{z:.2} F9000").unwrap();
        for (x, y, arc) in [
            (55.0, 20.0, "G3 X60 Y25 R5"),
            (60.0, 55.0, "G3 X55 Y60 R5"),
            (25.0, 60.0, "G3 X20 Y55 R5"),
            (20.0, 25.0, "G3 X25 Y20 R5"),
        ] {
            writeln!(g, "G1 X{x} Y{y} E{:.5} F2400", e(30.0)).unwrap();
            writeln!(g, "{arc} E{:.5}", e(7.854)).unwrap();
        }
        g.push_str("G1 E-0.8 F2100\nG0 X24 Y24\nG1 E0.8 F2100\n");
        let (mut y, mut right) = (24.0, true);
        while y <= 56.0 {
            let x = if right { 56.0 } else { 24.0 };
            writeln!(g, "G1 X{x} Y{y:.1} E{:.5} F3000", e(32.0)).unwrap();
            y += 0.5;
            if y <= 56.0 {
                writeln!(g, "G1 Y{y:.1} E{:.5}", e(0.5)).unwrap();
            }
            right = !right;
        }
        g.push_str("G1 E-0.8 F2100\n");
    }
    g
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let layers = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(100);
    let text = program(layers);
    let limits = Limits::new(150.0, 3_000.0, 100_000.0)?
        .with_axis_velocity([f64::INFINITY, f64::INFINITY, 20.0, 40.0])?
        .with_axis_acceleration([f64::INFINITY, f64::INFINITY, 500.0, 1_000.0])?;
    let options = StreamOptions::new(1_000.0)
        .with_tolerance(0.02)
        .with_arc_tolerance(0.002);
    let mut stream = Box::new(Stream::<4, 32, 128, NoCurve<4>, 1>::new(
        [0.0; 4], limits, options,
    )?);
    let mut reader = Reader::new(*b"XYZE")?;
    let mut feeder = Feeder::new(0.02);
    let mut pieces = Deque::<Piece<f32, 4>, 64>::new();
    let started = Instant::now();
    let mut read = std::time::Duration::ZERO;
    let (mut text_lines, mut handed) = (lines(text.as_bytes()), false);
    while !(handed && stream.is_idle()) {
        if !handed {
            if feeder.is_ready() {
                let clock = Instant::now();
                let next = text_lines.next();
                let block = next.map(|line| reader.read_line(line)).transpose()?;
                read += clock.elapsed();
                match block {
                    Some(block) => feeder.offer(block, &mut stream)?,
                    None => handed = feeder.finish(&mut stream)?,
                }
            } else {
                feeder.retry(&mut stream)?;
            }
        }
        stream.poll(&mut pieces)?;
        pieces.clear();
    }
    let total = started.elapsed().as_secs_f64();
    let stats = stream.stats();
    println!(
        "{layers} layers: {} bytes, {} lines, {} moves ({} blends, {} stops); motion {:.1} s",
        text.len(),
        reader.lines(),
        stats.moves,
        stats.blends,
        stats.stops,
        f64::from(stream.ticks()) / 1_000.0
    );
    println!(
        "read {:.3} s, read + plan + compile {total:.2} s: {:.0} moves/s",
        read.as_secs_f64(),
        stats.moves as f64 / total
    );
    Ok(())
}
