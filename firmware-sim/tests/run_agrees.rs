//! `strak-sim run` (the binary) against a direct library call: the curve built with
//! strak-curves' own constructors, planned with `PathTiming::plan_into` under the job's limits
//! (no feed share), compiled with `compile_into` and played with `Sampler`, each event where
//! and as slowly as a `FeedGuard` of the job's limits schedules it — every sample
//! bit for bit (the CSV holds the shortest text that reads back to the same bits). Also: the
//! last sample is the path's end point exactly, and every output file exists and is not empty.

mod common;

use std::path::Path as FsPath;
use std::process::Command;

use common::jobs_dir;

use strak_curves::{
    BSpline, CubicSpline, I32F32, Nurbs, ParamCurveDeriv, Parameterization, Point, Scalar,
    SplineBoundary,
};
use strak_trajectory::{
    Along, CompileOptions, Event as LibEvent, FeedGuard, Kernel, Limits, PlanOptions, Playable,
    Q40, Sampler, compile_into,
};

use strak_sim::pipeline::{TABLE, ZONES, boxed_path, boxed_plan};

/// Runs the binary; `job` `None` runs the bundled example. Returns the output folder.
fn run_binary(job: Option<&str>, out: &FsPath) -> String {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_strak-sim"));
    cmd.arg("run");
    if let Some(job) = job {
        cmd.arg(jobs_dir().join(job));
    }
    let output = cmd.arg("--out").arg(out).output().unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
    assert!(
        output.status.success(),
        "strak-sim run failed: {}\n{stdout}",
        String::from_utf8_lossy(&output.stderr)
    );
    for file in ["samples.csv", "summary.json", "path.svg", "motion.svg"] {
        let meta = std::fs::metadata(out.join(file)).unwrap();
        assert!(meta.len() > 100, "{file} is (nearly) empty");
    }
    let svg = std::fs::read_to_string(out.join("motion.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("<text") && svg.contains("velocity"));
    stdout
}

/// The CSV rows as text cells (header checked).
fn csv_rows(out: &FsPath, axes: usize) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(out.join("samples.csv")).unwrap();
    let mut lines = text.lines();
    let names = &["x", "y", "z", "w"][..axes];
    let mut header = vec!["tick".to_owned(), "t".to_owned()];
    for prefix in ["", "v", "a"] {
        header.extend(names.iter().map(|n| format!("{prefix}{n}")));
    }
    assert_eq!(lines.next().unwrap(), header.join(","));
    lines
        .map(|l| l.split(',').map(str::to_owned).collect())
        .collect()
}

/// A sample type read back from its CSV text, compared bit for bit.
trait Cell: Scalar {
    fn parse_cell(s: &str) -> Self;
    fn same_bits(self, other: Self) -> bool;
}

impl Cell for f64 {
    fn parse_cell(s: &str) -> Self {
        s.parse().unwrap()
    }
    fn same_bits(self, other: Self) -> bool {
        self.to_bits() == other.to_bits()
    }
}

impl Cell for f32 {
    fn parse_cell(s: &str) -> Self {
        s.parse().unwrap()
    }
    fn same_bits(self, other: Self) -> bool {
        self.to_bits() == other.to_bits()
    }
}

impl Cell for I32F32 {
    fn parse_cell(s: &str) -> Self {
        s.parse().unwrap()
    }
    fn same_bits(self, other: Self) -> bool {
        self.to_bits() == other.to_bits()
    }
}

/// An event of the direct run.
#[derive(Clone, Copy)]
enum Event {
    Feed(f32),
    Hold,
    Resume,
}

/// What the job file says: path limits (v, a, j), axis limits, feed share, rate.
#[derive(Clone, Copy)]
struct Spec<const A: usize> {
    limits: [f64; 3],
    axis_v: [f64; A],
    axis_a: [f64; A],
    feed_share: f64,
    rate: f64,
}

/// Plans, compiles and plays `curve` directly with the library, as the job describes it, and
/// compares every sample with the CSV rows; returns the number of samples.
fn direct_run<N, C, const A: usize>(
    curve: &C,
    spec: &Spec<A>,
    events: &[(u64, Event)],
    rows: &[Vec<String>],
) -> usize
where
    N: Kernel,
    N::Out: Cell,
    C: ParamCurveDeriv,
    C::Point: Point,
{
    let Spec {
        limits,
        axis_v,
        axis_a,
        feed_share,
        rate,
    } = *spec;
    // the documented planning of `strak-sim run`: velocities reduced by 0.5 %, the feed
    // share of a and j reserved by the planner, at the job's rate
    let v_keep = 1.0 - 0.005;
    let plan_limits = Limits::<A>::new(limits[0] * v_keep, limits[1], limits[2])
        .unwrap()
        .with_axis_velocity(axis_v.map(|v| v * v_keep))
        .unwrap()
        .with_axis_acceleration(axis_a)
        .unwrap();
    let plan = PlanOptions::new()
        .with_rate(rate)
        .with_feed_share(feed_share);
    // boxed and filled in place, as strak-sim does (on the test's default thread stack)
    let mut timing = boxed_plan::<_, TABLE, ZONES>(curve);
    timing.plan_into(&plan_limits, &plan).unwrap();
    let options = CompileOptions::new()
        .with_feed_share(feed_share)
        .with_limits(limits[1], limits[2])
        .with_axis_acceleration(axis_a);
    let mut path = boxed_path::<N, A>();
    compile_into(&Along::new(curve, &*timing), rate, &options, &mut path).unwrap();
    let mut sampler = Sampler::new(&*path);
    // without a feed share, each event applies when and as slowly as the feed guard of the
    // job's limits schedules it
    let guard = (feed_share == 0.0).then(|| {
        let limits = Limits::<A>::new(limits[0], limits[1], limits[2])
            .unwrap()
            .with_axis_velocity(axis_v)
            .unwrap()
            .with_axis_acceleration(axis_a)
            .unwrap();
        FeedGuard::new(&limits)
    });
    let mut k = 0_u64;
    let mut next = 0;
    let (mut last, mut last_sample, mut pending) = (None, None, None);
    while !sampler.is_finished() {
        while let Some(&(tick, e)) = events.get(next) {
            if tick > k {
                break;
            }
            let e = match e {
                Event::Feed(f) => LibEvent::Feed(f),
                Event::Hold => LibEvent::Hold,
                Event::Resume => LibEvent::Resume,
            };
            let (at, shift) = match (&guard, pending) {
                (_, Some(_)) => break,
                (None, None) => (k, None),
                (Some(g), None) => {
                    let when = g.schedule(&sampler, last_sample.as_ref(), e).unwrap();
                    (k + u64::from(when.delay), when.shift)
                }
            };
            pending = Some((at, shift, e));
            next += 1;
        }
        if let Some((at, shift, e)) = pending
            && at == k
        {
            if let Some(shift) = shift {
                assert!(sampler.scale_feed_ramp(shift));
            }
            sampler.apply(e);
            pending = None;
            continue;
        }
        let s = sampler.next();
        last_sample = Some(s);
        let row = &rows[usize::try_from(k).unwrap()];
        assert_eq!(row[0], k.to_string());
        assert_eq!(
            row[1].parse::<f64>().unwrap().to_bits(),
            (k as f64 / rate).to_bits()
        );
        let values = s.position.iter().chain(&s.velocity).chain(&s.acceleration);
        for (i, v) in values.enumerate() {
            let csv = N::Out::parse_cell(&row[2 + i]);
            assert!(
                csv.same_bits(*v),
                "tick {k}, column {}: CSV {} vs library {v:?}",
                2 + i,
                row[2 + i]
            );
        }
        last = Some(s.position);
        k += 1;
    }
    assert_eq!(rows.len() as u64, k, "the CSV has extra rows");
    // The end point is exact, bit for bit, in the path's number format.
    let last = last.unwrap();
    for (a, b) in last.iter().zip(path.end_position().iter()) {
        assert!(a.same_bits(*b), "last sample {a:?} vs path end {b:?}");
    }
    k as usize
}

const PICK_POINTS: [[f64; 3]; 8] = [
    [0.0, 0.0, 0.0],
    [0.0, 0.0, 40.0],
    [0.0, 0.0, 80.0],
    [60.0, 30.0, 80.0],
    [240.0, 120.0, 80.0],
    [300.0, 150.0, 80.0],
    [300.0, 150.0, 40.0],
    [300.0, 150.0, 0.0],
];

fn pick_and_place(job: Option<&str>, events: &[(u64, Event)]) {
    let dir = tempfile::tempdir().unwrap();
    let stdout = run_binary(job, dir.path());
    assert!(stdout.contains("limits     all respected"), "{stdout}");
    let rows = csv_rows(dir.path(), 3);
    let curve = BSpline::<[f64; 3], 16, 24>::clamped_uniform(3, &PICK_POINTS, 0.0, 1.0).unwrap();
    let n = direct_run::<f64, _, 3>(
        &curve,
        &Spec {
            limits: [500.0, 5000.0, 100_000.0],
            axis_v: [500.0, 500.0, 400.0],
            axis_a: [5000.0, 5000.0, 3000.0],
            feed_share: 0.0,
            rate: 1000.0,
        },
        events,
        &rows,
    );
    assert!(n > 1000);
}

#[test]
fn bundled_example_matches_the_library_bit_for_bit() {
    pick_and_place(None, &[]);
}

#[test]
fn feed_hold_resume_match_the_library_bit_for_bit() {
    const EVENTS: [(u64, Event); 4] = [
        (100, Event::Feed(0.5)),
        (900, Event::Hold),
        (1400, Event::Resume),
        (1700, Event::Feed(1.0)),
    ];
    pick_and_place(Some("feed-hold.toml"), &EVENTS);
}

#[test]
fn f32_circle_matches_the_library_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    run_binary(Some("circle-f32.toml"), dir.path());
    let rows = csv_rows(dir.path(), 2);
    let w = std::f64::consts::FRAC_1_SQRT_2 as f32; // the file's 0.7071067811865476
    let points: [[f32; 2]; 9] = [
        [50.0, 0.0],
        [50.0, 50.0],
        [0.0, 50.0],
        [-50.0, 50.0],
        [-50.0, 0.0],
        [-50.0, -50.0],
        [0.0, -50.0],
        [50.0, -50.0],
        [50.0, 0.0],
    ];
    let weights = [1.0, w, 1.0, w, 1.0, w, 1.0, w, 1.0];
    let knots = [0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 3.0, 3.0, 4.0, 4.0, 4.0];
    let curve = Nurbs::<[f32; 2], 16, 24>::new(2, &points, &weights, &knots).unwrap();
    let inf = f64::INFINITY;
    direct_run::<f32, _, 2>(
        &curve,
        &Spec {
            limits: [500.0, 5000.0, 100_000.0],
            axis_v: [inf, inf],
            axis_a: [inf, inf],
            feed_share: 0.0,
            rate: 2000.0,
        },
        &[],
        &rows,
    );
}

#[test]
fn fixed_point_contour_matches_the_library_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    run_binary(Some("contour-fixed.toml"), dir.path());
    let rows = csv_rows(dir.path(), 2);
    let p = |x: f64, y: f64| [I32F32::from_num(x), I32F32::from_num(y)];
    let points = [
        p(0.0, 0.0),
        p(120.0, -10.0),
        p(160.0, 60.0),
        p(100.0, 110.0),
        p(20.0, 90.0),
        p(-20.0, 40.0),
        p(0.0, 0.0),
    ];
    let curve = CubicSpline::<_, 16>::new(
        &points,
        Parameterization::ChordLength,
        SplineBoundary::Periodic,
    )
    .unwrap();
    direct_run::<Q40, _, 2>(
        &curve,
        &Spec {
            limits: [300.0, 3000.0, 60_000.0],
            axis_v: [250.0, 250.0],
            axis_a: [2500.0, 2500.0],
            feed_share: 0.0,
            rate: 10_000.0,
        },
        &[],
        &rows,
    );
}

#[test]
fn summary_reports_an_exact_end() {
    let dir = tempfile::tempdir().unwrap();
    for job in ["circle-f32.toml", "contour-fixed.toml"] {
        let out = dir.path().join(job);
        run_binary(Some(job), &out);
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        assert_eq!(json["end_point"]["error_to_path_end"], 0.0, "{job}");
        assert_eq!(json["finished"], true);
        assert_eq!(json["stop"], "end of path");
    }
}
