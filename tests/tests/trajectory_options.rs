//! exploration
use strak_curves::{BSpline, Bezier, ParamCurveDeriv};
use strak_tests::big_stack;
use strak_trajectory::{
    CompileOptions, Limits, Path, PathTiming, PlanOptions, Sampler, Timing, compile,
};

const PIECES: usize = 4096;

fn norm<const A: usize>(x: &[f64; A]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>().sqrt()
}

#[derive(Debug, Default, Clone, Copy)]
struct Peaks {
    v: f64,
    a: f64,
    j: f64,
}

fn play<const A: usize, const P: usize>(path: &Path<f64, A, P>) -> Peaks {
    let mut s = Sampler::new(path);
    let t = path.period();
    let mut prev: Option<Sample3<A>> = None;
    let mut p = Peaks::default();
    while !s.is_finished() {
        let smp = s.next();
        let cur = (smp.position, smp.velocity, smp.acceleration);
        if let Some((x0, v0, a0)) = prev {
            let d = |x: &[f64; A], y: &[f64; A]| -> [f64; A] {
                core::array::from_fn(|i| (y[i] - x[i]) / t)
            };
            p.v = p.v.max(norm(&d(&x0, &cur.0)));
            p.a = p.a.max(norm(&d(&v0, &cur.1)));
            p.j = p.j.max(norm(&d(&a0, &cur.2)));
        }
        prev = Some(cur);
    }
    p
}
type Sample3<const A: usize> = ([f64; A], [f64; A], [f64; A]);

fn run<C: ParamCurveDeriv<Point = [f64; A]>, const A: usize>(
    name: &str,
    c: &C,
    limits: &Limits<A>,
    o: &PlanOptions,
    rate: f64,
) {
    let plan = match PathTiming::<_, 256, 512>::plan(c, limits, o) {
        Ok(p) => p,
        Err(e) => {
            println!("{name}: plan error {e}");
            return;
        }
    };
    let co = CompileOptions::new().with_path_limits(limits);
    let path: Path<f64, A, PIECES> = match compile(c, &plan, rate, &co) {
        Ok(p) => p,
        Err(e) => {
            println!("{name}: compile error {e}");
            return;
        }
    };
    let p = play(&path);
    println!(
        "{name}: T {:.4} zones {} pieces {} v {:.3} a {:.3} j {:.3}",
        plan.duration(),
        plan.motion().zones().len(),
        path.pieces().len(),
        p.v / limits.velocity(),
        p.a / limits.acceleration(),
        p.j / limits.jerk()
    );
}

fn polyline(turn_deg: f64) -> BSpline<[f64; 2], 8, 16> {
    let th = turn_deg.to_radians();
    let pts = [[0.0, 0.0], [50.0, 0.0], [50.0 + 50.0 * th.cos(), 50.0 * th.sin()]];
    BSpline::clamped_uniform(1, &pts, 0.0, 1.0).unwrap()
}

fn feed_run(k_reduce: f64, events: &[(u64, f32)]) {
    let curve = Bezier::new([[0.0, 0.0, 0.0], [100.0, 50.0, 20.0]]).unwrap();
    let full = Limits::<3>::new(200.0, 2_000.0, 50_000.0).unwrap();
    let red = Limits::<3>::new(200.0, 2_000.0 * k_reduce, 50_000.0 * k_reduce).unwrap();
    let timing = PathTiming::<_, 256, 64>::scurve(&curve, &red).unwrap();
    let options = CompileOptions::new().with_path_limits(&full);
    let path: Path<f64, 3, 128> = compile(&curve, &timing, 1_000.0, &options).unwrap();
    let mut s = Sampler::new(&path);
    let t = path.period();
    let mut prev: Option<Sample3<3>> = None;
    let mut p = Peaks::default();
    let mut k = 0u64;
    let mut worst_k = 0;
    while !s.is_finished() && k < 100_000 {
        for &(tick, f) in events { if tick == k { if f < 0.0 { s.hold() } else if f > 1.5 { s.resume() } else { s.set_feed(f) } } }
        let smp = s.next();
        let cur = (smp.position, smp.velocity, smp.acceleration);
        if let Some((x0, v0, a0)) = prev {
            let d = |x: &[f64; 3], y: &[f64; 3]| -> [f64; 3] { core::array::from_fn(|i| (y[i] - x[i]) / t) };
            p.v = p.v.max(norm(&d(&x0, &cur.0)));
            p.a = p.a.max(norm(&d(&v0, &cur.1)));
            let jj = norm(&d(&a0, &cur.2));
            if jj > p.j { p.j = jj; worst_k = k; }
        }
        prev = Some(cur);
        k += 1;
    }
    println!("reduce {k_reduce} events {events:?}: ticks {} peaks a {:.1} j {:.1} (at {worst_k}) v {:.2}  path a_peak {:.1} j_peak {:.1} v_peak {:.1}",
        path.ticks(), p.a, p.j, p.v, path.peak_acceleration(), path.peak_jerk(), path.peak_velocity());
}

#[test]
fn explore() {
    big_stack(|| {
        for k in [1.0, 0.75] {
            feed_run(k, &[]);
            for t0 in (0..400).step_by(10) {
                feed_run(k, &[(t0, 0.5)]);
                feed_run(k, &[(t0, -1.0), (t0 + 300, 2.0)]);
            }
        }
    });
}
