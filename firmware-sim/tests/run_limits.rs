//! Every bundled `[path]` job (`examples/jobs/*.toml`) respects every limit of its job file,
//! checked from `samples.csv` alone: the velocity by finite differences of the positions, the
//! acceleration by finite differences of the velocity samples, the jerk by finite differences
//! of the acceleration samples, and the velocity and acceleration samples themselves — along
//! the path (Euclidean norms) and per axis. The summary agrees.

mod common;

use common::{bundled_path_jobs, stem};
use strak_sim::job::{Job, ProfileKind};
use strak_sim::run::{RunOptions, run_job};
use strak_sim::summary::Summary;

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Checks `value ≤ limit + slack`, remembering the worst ratio.
struct Check<'a> {
    job: &'a str,
    worst: Vec<(String, f64)>,
}

impl Check<'_> {
    fn le(&mut self, what: &str, value: f64, limit: f64, slack: f64) {
        if !limit.is_finite() {
            return;
        }
        assert!(
            value <= limit * (1.0 + 1e-9) + slack,
            "{}: {what} = {value} exceeds the limit {limit}",
            self.job
        );
        match self.worst.iter_mut().find(|(w, _)| w == what) {
            Some((_, r)) => *r = r.max(value / limit),
            None => self.worst.push((what.to_owned(), value / limit)),
        }
    }
}

#[test]
fn bundled_jobs_respect_every_limit() {
    for file in bundled_path_jobs() {
        let name = stem(&file);
        let job = Job::parse(&std::fs::read_to_string(&file).unwrap()).unwrap();
        check_job(&name, &job);
    }
}

/// A straight line cruising at an axis velocity limit (x moves twice as fast as y), and a
/// wavy spline whose y axis limits the speed: the compiled spline's fit error must not push
/// the samples over the velocity limits the plan cruises at.
#[test]
fn cruising_at_axis_velocity_limits() {
    let line = r#"
        rate_hz = 1000
        number = "f64"
        [path]
        kind = "bspline"
        degree = 3
        points = [[0, 0], [10, 5], [100, 50], [200, 100], [290, 145], [300, 150]]
        [limits]
        velocity = 400
        acceleration = 5000
        jerk = 100000
        axis_velocity = [300, 300]
        [profile]
        kind = "s-curve"
    "#;
    let wave = format!("number = \"f32\"\n{WAVE}\n[profile]\nkind = \"s-curve\"\n");
    for (name, text) in [("line", line), ("wave", &wave)] {
        check_job(name, &Job::parse(text).unwrap());
    }
}

/// A 6-axis cubic B-spline of `n` de Boor points: a circle of radius 100 in x–y rising in z,
/// the other three axes moving alongside.
fn six_axis_job(n: usize, number: &str) -> String {
    six_axis_curve_job(n, number, "kind = \"bspline\"\n        degree = 3")
}

/// [`six_axis_job`] with the curve kind's lines `kind`.
fn six_axis_curve_job(n: usize, number: &str, kind: &str) -> String {
    let points: Vec<String> = (0..n)
        .map(|i| {
            let t = i as f64 / (n - 1) as f64;
            let a = std::f64::consts::TAU * t;
            format!(
                "[{}, {}, {}, {}, {}, {}]",
                100.0 * a.cos(),
                100.0 * a.sin(),
                50.0 * t,
                20.0 * t,
                10.0 * (std::f64::consts::PI * t).sin(),
                -30.0 * t
            )
        })
        .collect();
    format!(
        r#"
        rate_hz = 1000
        number = "{number}"
        [path]
        {kind}
        points = [{}]
        [limits]
        velocity = 200
        acceleration = 2000
        jerk = 50000
        axis_velocity = [200, 200, 200, 100, 100, 100]
        [profile]
        kind = "s-curve"
    "#,
        points.join(", ")
    )
}

/// Six axes, and the largest path strak-sim builds (4096 de Boor points): every limit holds.
#[test]
fn six_axes_and_many_points() {
    for (n, number) in [(4096, "f64"), (600, "f32")] {
        let job = Job::parse(&six_axis_job(n, number)).unwrap();
        assert_eq!((job.axes(), job.path.points().len()), (6, n));
        check_job(&format!("six axes, {n} points, {number}"), &job);
    }
}

/// The interpolating kinds take six axes too, and pass through every point in all six.
#[test]
fn six_axes_through_interpolating_curves() {
    for kind in ["catmull-rom", "cubic-spline", "parabolic-blend"] {
        let job = Job::parse(&six_axis_curve_job(
            40,
            "f64",
            &format!("kind = \"{kind}\""),
        ))
        .unwrap();
        assert_eq!(job.axes(), 6, "{kind}");
        check_job(&format!("six axes through a {kind} curve"), &job);
    }
}

/// Runs `job` and checks every limit from its samples; the summary.
fn check_job(name: &str, job: &Job) -> Summary {
    {
        let name = name.to_owned();
        let dir = tempfile::tempdir().unwrap();
        let summary = run_job(
            job,
            &RunOptions {
                out_dir: dir.path().to_owned(),
                name: name.clone(),
                progress: false,
                velocity_factor: None,
            },
        )
        .unwrap();
        assert!(summary.finished, "{name}: {}", summary.stop);
        // (a trapezoid's jerk is reported, not enforced)
        let s_curve = job.profile.kind() == ProfileKind::SCurve;
        assert!(summary.limits_respected || !s_curve, "{name}: {summary}");
        assert!(summary.violations.is_empty(), "{name}: {summary}");
        let aborted = job.events.iter().any(|e| e.abort == Some(true));
        if !aborted {
            assert_eq!(summary.end_point.error_to_path_end, 0.0, "{name}");
        }

        let axes = job.axes();
        let rate = job.rate_hz;
        let l = &job.limits;
        let axis = |v: &Option<Vec<f64>>, i: usize| v.as_ref().map_or(f64::INFINITY, |v| v[i]);
        let text = std::fs::read_to_string(dir.path().join("samples.csv")).unwrap();
        let rows: Vec<Vec<f64>> = text
            .lines()
            .skip(1)
            .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
            .collect();
        assert_eq!(rows.len() as u64, summary.samples);
        let pos = |r: &Vec<f64>| r[2..2 + axes].to_vec();
        let vel = |r: &Vec<f64>| r[2 + axes..2 + 2 * axes].to_vec();
        let acc = |r: &Vec<f64>| r[2 + 2 * axes..2 + 3 * axes].to_vec();
        let max_of = |f: &dyn Fn(&Vec<f64>) -> Vec<f64>| {
            rows.iter().flat_map(f).fold(0.0_f64, |m, x| m.max(x.abs()))
        };
        // Finite-difference noise of each quantity in the job's number format.
        let slack_v = 2.0 * job.number.sample_resolution(max_of(&pos)) * rate;
        let slack_a = 2.0 * job.number.sample_resolution(max_of(&vel)) * rate;
        let slack_j = 2.0 * job.number.sample_resolution(max_of(&acc)) * rate;
        // A trapezoid is not planned under the jerk.
        let jerk_limit = if job.profile.kind() == ProfileKind::SCurve {
            l.jerk
        } else {
            f64::INFINITY
        };
        let mut check = Check {
            job: &name,
            worst: Vec::new(),
        };
        for r in &rows {
            check.le("|v| samples", norm(&vel(r)), l.velocity, 0.0);
            check.le("|a| samples", norm(&acc(r)), l.acceleration, 0.0);
            for i in 0..axes {
                check.le(
                    "v_i samples",
                    vel(r)[i].abs(),
                    axis(&l.axis_velocity, i),
                    0.0,
                );
                check.le(
                    "a_i samples",
                    acc(r)[i].abs(),
                    axis(&l.axis_acceleration, i),
                    0.0,
                );
            }
        }
        for w in rows.windows(2) {
            let d = |f: &dyn Fn(&Vec<f64>) -> Vec<f64>| -> Vec<f64> {
                f(&w[1])
                    .iter()
                    .zip(f(&w[0]))
                    .map(|(b, a)| (b - a) * rate)
                    .collect()
            };
            let (dv, da, dj) = (d(&pos), d(&vel), d(&acc));
            check.le("|Δx|·f", norm(&dv), l.velocity, slack_v);
            check.le("|Δv|·f", norm(&da), l.acceleration, slack_a);
            check.le("|Δa|·f", norm(&dj), jerk_limit, slack_j);
            for i in 0..axes {
                check.le("|Δx_i|·f", dv[i].abs(), axis(&l.axis_velocity, i), slack_v);
                check.le(
                    "|Δv_i|·f",
                    da[i].abs(),
                    axis(&l.axis_acceleration, i),
                    slack_a,
                );
            }
        }
        println!("{name}: worst ratios to the limits {:?}", check.worst);
        // The summary's maxima are the samples' maxima.
        let v_max = rows.iter().map(|r| norm(&vel(r))).fold(0.0, f64::max);
        let v_sum = summary.path.velocity.max;
        assert!(
            (v_sum - v_max).abs() <= 1e-6 * v_max,
            "{name}: {v_sum} vs {v_max}"
        );
        // The bundled example finishes on its last sample's tick, at rest.
        let last = rows.last().unwrap();
        assert!(norm(&vel(last)) < 1e-6 * l.velocity, "{name}: not at rest");
        summary
    }
}

/// A deterministic random stream (xorshift64*), for reproducible cases.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    /// Uniform in `[0, 1)`.
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1_u64 << 53) as f64
    }
}

/// The curved paths of the random feed test: the pick-and-place lift, transfer and set-down
/// (3 axes, axis limits), and a wave whose y axis limits the speed (2 axes, at 500 Hz).
const FEED_PATHS: [&str; 2] = [PICK_AND_PLACE, WAVE];

/// The pick-and-place path and limits (without number format and profile).
const PICK_AND_PLACE: &str = r#"
        rate_hz = 1000
        [path]
        kind = "bspline"
        degree = 3
        points = [[0, 0, 0], [0, 0, 40], [0, 0, 80], [60, 30, 80], [240, 120, 80], [300, 150, 80], [300, 150, 40], [300, 150, 0]]
        [limits]
        velocity = 500
        acceleration = 5000
        jerk = 100000
        axis_velocity = [500, 500, 400]
        axis_acceleration = [5000, 5000, 3000]
    "#;

/// A wavy natural cubic spline whose y axis limits the speed, at 500 Hz (without number
/// format and profile).
const WAVE: &str = r#"
        rate_hz = 500
        [path]
        kind = "cubic-spline"
        boundary = "natural"
        points = [[0, 0], [50, 30], [100, 0], [150, 40], [200, 0]]
        [limits]
        velocity = 300
        acceleration = 3000
        jerk = 50000
        axis_velocity = [250, 120]
        axis_acceleration = [2500, 2000]
    "#;

/// Feed overrides (1 % to 100 %), holds with their resumes and sometimes an abort at random
/// ticks, on curved paths planned at the full limits (no feed share, the default), S-curve
/// and trapezoid, in every number format: the feed guard schedules every event (none
/// refused), and every sample keeps every limit, checked from `samples.csv`.
#[test]
fn random_feed_events_on_curves_keep_every_limit() {
    let mut rng = Rng(0x5eed_feed_0b5e_55ed);
    let (mut late, mut shifts) = (Vec::new(), [0; 4]);
    for case in 0..36 {
        let number = ["f64", "f32", "fixed"][case % 3];
        let shape = if case % 4 == 3 {
            "trapezoid"
        } else {
            "s-curve"
        };
        let base = FEED_PATHS[(case / 3) % FEED_PATHS.len()];
        // the events fall in the first 1.6 s (both paths take about 1.7 s at full feed)
        let mut text = format!("number = \"{number}\"\n{base}\n[profile]\nkind = \"{shape}\"\n");
        let mut tick = 0;
        let n = 1 + rng.next() % 5;
        for i in 0..n {
            tick += 1 + rng.next() % 400;
            let action = match rng.next() % 10 {
                0..=4 => format!("feed = {:.3}", 0.01 + 0.99 * rng.unit()),
                5..=7 => {
                    let resume = tick + 1 + rng.next() % 300;
                    text += &format!("[[events]]\ntick = {tick}\nhold = true\n");
                    tick = resume;
                    "resume = true".to_owned()
                }
                _ if i == n - 1 => "abort = true".to_owned(),
                _ => "feed = 1.0".to_owned(),
            };
            text += &format!("[[events]]\ntick = {tick}\n{action}\n");
        }
        let job = Job::parse(&text).unwrap();
        assert_eq!(job.feed_share(), 0.0);
        let summary = check_job(&format!("random feed case {case}: {text}"), &job);
        assert_eq!(summary.events_refused, 0, "case {case}");
        assert_eq!(summary.feed_events.len(), job.events.len());
        for e in &summary.feed_events {
            let at = e.at.unwrap();
            assert!(at >= e.tick);
            late.push(at - e.tick);
            shifts[usize::from(e.ramp_shift)] += 1;
        }
    }
    late.sort_unstable();
    println!(
        "{} events: ticks late median {}, 90 % {}, max {}; ramp slow-downs 1, ½, ¼, ⅛: {shifts:?}",
        late.len(),
        late[late.len() / 2],
        late[late.len() * 9 / 10],
        late[late.len() - 1]
    );
}
