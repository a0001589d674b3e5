//! Prints the comparison of `BENCHMARKS.md`, "A whole curve through the stream": the
//! 16-point B-spline of the firmware's planning case planned and compiled into an `f32` path
//! by the whole-path planner (`PathTiming::plan` + `compile_into`) and by the stream
//! (`plan_path_into`, a window of 8 segments and 64 zones), at 1 kHz under v 300 mm/s,
//! a 3000 mm/s², j 60000 mm/s³: the motion's ticks, the pieces, the blob's bytes and the
//! median wall-clock time of 21 runs on this machine.
//!
//! ```text
//! cargo run --release -p strak-bench --bin whole
//! ```

use std::time::Instant;

use strak_curves::BSpline;
use strak_trajectory::{
    CompileOptions, Limits, Path, PathTiming, PlanOptions, Stream, StreamOptions, plan_path_into,
};

/// The de Boor points of the firmware's planning case (mm): a helix of 1¼ turns.
const POINTS: [[f64; 3]; 16] = [
    [270.0, 75.0, 0.0],
    [262.7, 95.6, 4.0],
    [241.8, 113.7, 8.0],
    [209.7, 127.0, 12.0],
    [170.4, 134.1, 16.0],
    [128.6, 134.0, 20.0],
    [89.4, 126.8, 24.0],
    [57.6, 113.3, 28.0],
    [36.9, 95.1, 32.0],
    [30.0, 74.5, 36.0],
    [37.6, 54.0, 40.0],
    [58.9, 36.0, 44.0],
    [91.2, 22.7, 48.0],
    [130.6, 15.8, 52.0],
    [172.4, 16.1, 56.0],
    [211.5, 23.5, 60.0],
];

type Curve = BSpline<[f64; 3], 16, 20>;
type WholePath = Path<f32, 3, 1024>;

/// The median of `runs` timings of `work`, in milliseconds.
fn median_ms(runs: usize, mut work: impl FnMut()) -> f64 {
    let mut times: Vec<f64> = (0..runs)
        .map(|_| {
            let t = Instant::now();
            work();
            t.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[runs / 2]
}

fn row(name: &str, path: &WholePath, ms: f64) {
    println!(
        "| {name} | {} | {} | {} | {ms:.1} |",
        path.ticks(),
        path.pieces().len(),
        path.blob_len()
    );
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let curve = Curve::clamped_uniform(3, &POINTS, 0.0, 1.0)?;
    let limits = Limits::new(300.0, 3_000.0, 60_000.0)?;
    let mut path = Box::new(WholePath::new());
    let ms = median_ms(21, || {
        let plan =
            PathTiming::<_, 256, 64>::plan(&curve, &limits, &PlanOptions::new()).expect("plan");
        plan.compile_into(&CompileOptions::new(), &mut path)
            .expect("compile");
    });
    println!("| planner | ticks | pieces | blob bytes | host time (ms) |");
    println!("|---|---:|---:|---:|---:|");
    row("PathTiming::plan + compile_into", &path, ms);
    let mut stream = Box::new(Stream::<3, 8, 64, &Curve>::unset());
    let options = StreamOptions::new(1_000.0);
    let ms = median_ms(21, || {
        plan_path_into(&curve, limits, options, &mut stream, &mut path).expect("stream");
    });
    row("plan_path_into, Stream<3, 8, 64>", &path, ms);
    Ok(())
}
