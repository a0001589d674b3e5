//! `strak-sim run` on a straight line with an S-curve profile, the job's full limits, in
//! every number format: random lines (direction, length from 0.01 to 1 000 units, path and
//! axis limits), each run through the job pipeline's line route ([`line_move`], then
//! [`play_moves`], as the command does).
//!
//! * Without events the motion takes the time-optimal duration at the job's limits within
//!   0.1 % plus one tick (and never less). The optimum is the closed form of the
//!   rest-to-rest jerk-limited profile ("double S", Biagiotti & Melchiorri, *Trajectory
//!   Planning for Automatic Machines and Robots*, Springer 2008, §3.4) under the limits of
//!   the line: `min(V, Vᵢ/|uᵢ|)`, `min(A, Aᵢ/|uᵢ|)`, `J`.
//! * With random feed overrides (0 and 1 % to 100 %), holds, resumes and aborts at random
//!   ticks, every sample keeps every limit of the job: the norms of the velocity and
//!   acceleration and of the finite differences `Δx·f`, `Δv·f`, `Δa·f` (path limits), and
//!   each axis's velocity and acceleration, within the playback's rounding and the solver's
//!   rounding of the acceleration at its switching times (see `online_take_over.rs`); the
//!   samples stay on the line (within 8 times the position's playback rounding and the
//!   solver's relative tolerance of the coordinates); and a run that is not held, stopped by
//!   feed 0 or aborted at its end reaches the end point, at rest.

#[path = "../../bench/src/online_cases.rs"]
#[allow(dead_code)]
pub mod online_cases;

use online_cases::Rng;
use strak_curves::Scalar;
use strak_sim::job::Job;
use strak_sim::line::line_move;
use strak_sim::online_move::{MoveJob, play_moves};
use strak_trajectory::{Kernel, Q40, Real};

const RATE: f64 = 1_000.0;

// The largest distance from the line, relative to the coordinates' extent, of a test's run.
thread_local!(static ACROSS: std::cell::Cell<f64> = const { std::cell::Cell::new(0.0) });
const CASES: usize = 300;

/// A random line job and what the checks need of it.
struct Line {
    text: String,
    from: [f64; 3],
    to: [f64; 3],
    /// Path `(V, A, J)`.
    path: [f64; 3],
    /// Per axis `(Vᵢ, Aᵢ)`, `inf` where none.
    axis: [[f64; 2]; 3],
    /// Whether the events leave the motion free to reach the end.
    reaches_end: bool,
}

impl Line {
    fn random(rng: &mut Rng, with_events: bool) -> Self {
        let from = [0; 3].map(|_| rng.range(-200.0, 200.0));
        let length = 10f64.powf(rng.range(-2.0, 3.0));
        let dir = loop {
            let d = [0; 3].map(|_| {
                if rng.unit() < 0.2 {
                    0.0
                } else {
                    rng.range(-1.0, 1.0)
                }
            });
            let n = d.iter().map(|x| x * x).sum::<f64>().sqrt();
            if n > 0.1 {
                break d.map(|x| x / n);
            }
        };
        let to: [f64; 3] = core::array::from_fn(|i| from[i] + length * dir[i]);
        let path = [
            rng.range(10.0, 1_000.0),
            rng.range(100.0, 20_000.0),
            10f64.powf(rng.range(3.0, 6.0)),
        ];
        let axis = [0; 3].map(|_| {
            let mut own = |limit: f64| {
                if rng.unit() < 0.5 {
                    f64::INFINITY
                } else {
                    rng.range(0.3, 1.0) * limit
                }
            };
            [own(path[0]), own(path[1])]
        });
        let list = |q: usize| {
            let v: Vec<String> = axis.iter().map(|a| format!("{:?}", a[q])).collect();
            v.join(", ")
        };
        let mut text = format!(
            "rate_hz = {RATE}\nnumber = \"f64\"\n[path]\nkind = \"bezier\"\n\
             points = [{from:?}, {to:?}]\n[limits]\nvelocity = {:?}\nacceleration = {:?}\n\
             jerk = {:?}\naxis_velocity = [{}]\naxis_acceleration = [{}]\n\
             [profile]\nkind = \"s-curve\"\n",
            path[0],
            path[1],
            path[2],
            list(0),
            list(1)
        );
        let mut reaches_end = true;
        if with_events {
            let (mut feed, mut held, mut aborted) = (1.0, false, false);
            let span = (2.0 * length / path[0] * RATE) as u64 + 50;
            let mut ticks: Vec<u64> = (0..rng.range(1.0, 7.0) as usize)
                .map(|_| 1 + (rng.unit() * span as f64) as u64)
                .collect();
            ticks.sort_unstable();
            for tick in ticks {
                let action = match (rng.unit() * 4.0) as u32 {
                    0 => {
                        feed = if rng.unit() < 0.15 {
                            0.0
                        } else {
                            rng.range(0.01, 1.0)
                        };
                        format!("feed = {feed:?}")
                    }
                    1 => {
                        held = true;
                        "hold = true".to_owned()
                    }
                    2 => {
                        held = false;
                        "resume = true".to_owned()
                    }
                    _ => {
                        aborted = true;
                        "abort = true".to_owned()
                    }
                };
                text += &format!("[[events]]\ntick = {tick}\n{action}\n");
            }
            reaches_end = !aborted && !held && feed > 0.0;
        }
        Line {
            text,
            from,
            to,
            path,
            axis,
            reaches_end,
        }
    }

    /// The limits along the line: `(V, A, J)` of `s`.
    fn along(&self) -> [f64; 3] {
        let d: [f64; 3] = core::array::from_fn(|i| self.to[i] - self.from[i]);
        let n = d.iter().map(|x| x * x).sum::<f64>().sqrt();
        let mut l = self.path;
        for (i, di) in d.iter().enumerate() {
            let u = di.abs() / n;
            if u > 0.0 {
                l[0] = l[0].min(self.axis[i][0] / u);
                l[1] = l[1].min(self.axis[i][1] / u);
            }
        }
        l
    }

    fn length(&self) -> f64 {
        (0..3)
            .map(|i| (self.to[i] - self.from[i]).powi(2))
            .sum::<f64>()
            .sqrt()
    }
}

/// The time-optimal rest-to-rest duration over `l` under `v`, `a`, `j` (closed form).
fn optimal(l: f64, [v, a, j]: [f64; 3]) -> f64 {
    // Time to reach speed w from rest (and to stop from it).
    let t_acc = |w: f64| {
        if w * j >= a * a {
            w / a + a / j
        } else {
            2.0 * (w / j).sqrt()
        }
    };
    if l >= v * t_acc(v) {
        return l / v + t_acc(v);
    }
    // No cruise: the peak speed w covers l = w·t_acc(w).
    let w_a = (-a * a / j + (a.powi(4) / (j * j) + 4.0 * a * l).sqrt()) / 2.0;
    let w = if w_a * j >= a * a {
        w_a
    } else {
        (l * j.sqrt() / 2.0).powf(2.0 / 3.0)
    };
    2.0 * t_acc(w)
}

/// The samples as `f64`: per tick positions, velocities, accelerations.
type Rows = Vec<[[f64; 3]; 3]>;

/// The samples, and the playback rounding of the paths played (position, velocity,
/// acceleration).
fn play<N: Kernel, R: Real>(job: &MoveJob) -> Result<(Rows, [f64; 3]), String> {
    let mut rows = Vec::new();
    let moves = play_moves::<N, R, 3>(job, &mut |s| {
        let f = |x: &[N::Out; 3]| x.map(|v| v.to_f64());
        rows.push([f(&s.position), f(&s.velocity), f(&s.acceleration)]);
        Ok(())
    })
    .map_err(|e| e.to_string())?;
    Ok((rows, moves.rounding))
}

/// The playback's resolution at magnitude `m`, and the solver's relative tolerance.
fn resolution(number: &str, m: f64) -> (f64, f64) {
    match number {
        "f32" => (f64::from(f32::EPSILON) * m, 64.0 * f64::from(f32::EPSILON)),
        "f64" => (f64::EPSILON * m, 1024.0 * f64::EPSILON),
        _ => (2f64.powi(-32) + f64::EPSILON * m, 1024.0 * f64::EPSILON),
    }
}

fn norm(x: [f64; 3]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>().sqrt()
}

/// Every limit of the job, from the samples; the samples stay on the line. A sampled value
/// may differ from the motion by its channel's playback rounding `e` (`rounding`, at least
/// the samples' resolution), a finite difference by `2e` per tick, a norm over the axes by
/// `√3` times that; the jerk also by twice the solver's rounding of the acceleration at a
/// switching time; and `10⁻⁹` relative for the comparison's arithmetic.
fn assert_keeps(line: &Line, number: &str, (rows, rounding): &(Rows, [f64; 3]), what: &str) {
    let [v_max, a_max, j_max] = line.path;
    let extent = line
        .from
        .iter()
        .chain(&line.to)
        .fold(1.0_f64, |m, x| m.max(x.abs()));
    let (res_x, ulps) = resolution(number, extent);
    let e_x = res_x.max(rounding[0]);
    let e_v = resolution(number, v_max).0.max(rounding[1]);
    let e_a = resolution(number, a_max).0.max(rounding[2]);
    let root = 3f64.sqrt();
    let within = |limit: f64, e: f64| limit * (1.0 + 1e-9) + root * e;
    let slack = |limit: f64, e: f64| limit * (1.0 + 1e-9) + 2.0 * root * e * RATE;
    let d: [f64; 3] = core::array::from_fn(|i| (line.to[i] - line.from[i]) / line.length());
    for (k, w) in rows.windows(2).enumerate() {
        let diff =
            |q: usize| core::array::from_fn::<f64, 3, _>(|i| (w[1][q][i] - w[0][q][i]) * RATE);
        let at = format!("{what}: tick {}", k + 1);
        assert!(
            norm(w[1][1]) <= within(v_max, e_v),
            "{at}: |v| {:?}",
            w[1][1]
        );
        assert!(
            norm(w[1][2]) <= within(a_max, e_a),
            "{at}: |a| {:?}",
            w[1][2]
        );
        assert!(
            norm(diff(0)) <= slack(v_max, e_x),
            "{at}: |Δx·f| {:?}",
            diff(0)
        );
        assert!(
            norm(diff(1)) <= slack(a_max, e_v),
            "{at}: |Δv·f| {:?}",
            diff(1)
        );
        let jerk = slack(j_max, e_a) + 2.0 * ulps * a_max * RATE;
        assert!(norm(diff(2)) <= jerk, "{at}: |Δa·f| {:?}", diff(2));
        for (i, [v_i, a_i]) in line.axis.iter().enumerate() {
            assert!(
                w[1][1][i].abs() <= within(*v_i, e_v),
                "{at}: v{i} {}",
                w[1][1][i]
            );
            assert!(
                w[1][2][i].abs() <= within(*a_i, e_a),
                "{at}: a{i} {}",
                w[1][2][i]
            );
        }
        // On the line: the offset from the start has no part across the direction.
        let off: [f64; 3] = core::array::from_fn(|i| w[1][0][i] - line.from[i]);
        let along: f64 = (0..3).map(|i| off[i] * d[i]).sum();
        let across = norm(core::array::from_fn(|i| off[i] - along * d[i]));
        let tolerance = 8.0 * (e_x + ulps * extent);
        assert!(across <= tolerance, "{at}: {across} off the line");
        ACROSS.with(|c| c.set(c.get().max(across / extent)));
    }
}

fn run_all<N: Kernel, R: Real>(number: &str, seed: u64) {
    let mut rng = Rng(seed);
    let mut worst = 0.0_f64;
    for case in 0..CASES {
        let with_events = case % 2 == 1;
        let line = Line::random(&mut rng, with_events);
        let text = line
            .text
            .replace("number = \"f64\"", &format!("number = \"{number}\""));
        let job = Job::parse(&text).unwrap_or_else(|e| panic!("{e}\n{text}"));
        let moves = line_move(&job).expect("a line").unwrap();
        let what = format!("{number} case {case}");
        let played = play::<N, R>(&moves).unwrap_or_else(|e| panic!("{what}: {e}\n{text}"));
        assert_keeps(&line, number, &played, &format!("{what}\n{text}"));
        let rows = &played.0;
        let last = rows.last().unwrap();
        if line.reaches_end {
            let (res, _) = resolution(number, line.to.iter().fold(0.0, |m: f64, x| m.max(x.abs())));
            for i in 0..3 {
                assert!(
                    (last[0][i] - line.to[i]).abs() <= res,
                    "{what}: end {:?}",
                    last[0]
                );
            }
        }
        if line.reaches_end || !with_events {
            assert_eq!((last[1], last[2]), ([0.0; 3], [0.0; 3]), "{what}: at rest");
        }
        if !with_events {
            let t_opt = optimal(line.length(), line.along());
            let t = (rows.len() - 1) as f64 / RATE;
            assert!(
                t >= t_opt * (1.0 - 1e-5) && t <= t_opt * 1.001 + 1.0 / RATE,
                "{what}: {t} s, optimal {t_opt} s\n{text}"
            );
            worst = worst.max((t - t_opt) * RATE);
        }
    }
    let across = ACROSS.with(std::cell::Cell::get);
    println!(
        "{number}: at most {worst:.4} ticks over the optimum; at most {across:.1e} of the extent off the line"
    );
}

#[test]
fn lines_take_the_optimal_duration_and_feed_events_keep_every_limit_in_f64() {
    run_all::<f64, f64>("f64", 0x11AE_2026_1203_0001);
}

#[test]
fn lines_take_the_optimal_duration_and_feed_events_keep_every_limit_in_f32() {
    run_all::<f32, f32>("f32", 0x11AE_2026_1203_0002);
}

#[test]
fn lines_take_the_optimal_duration_and_feed_events_keep_every_limit_in_q40() {
    run_all::<Q40, f64>("fixed", 0x11AE_2026_1203_0003);
}
