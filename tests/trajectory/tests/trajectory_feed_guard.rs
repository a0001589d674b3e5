//! The feed guard on a path planned at the full limits (no feed share): a 3-axis line long
//! enough to cruise, with the acceleration limit reached on both ends.
//!
//! Unguarded, a hold applied at some ticks takes the motion past the limits (it brakes on
//! top of a braking motion): the check below can fail. Guarded (each hold scheduled by
//! [`FeedGuard::schedule`], then its ramp slow-down and the hold applied at the scheduled
//! tick), every sample keeps every limit in f64, f32 and Q40, checked here independently:
//! `|v|`, `|a|` and the finite differences `|Δx|·f`, `|Δv|·f`, `|Δa|·f` (norms and per
//! axis), allowing `10⁻⁹` relative and `2·u(M)·f` (`√3` times that for a norm) for the
//! rounding of the samples.

use strak_curves::{Bezier, Scalar};
use strak_trajectory::{
    CompileOptions, Event, FeedGuard, Kernel, Limits, Path, PathTiming, PlanOptions, Playable, Q40,
    Sample, Sampler,
};

const RATE: f64 = 1_000.0;

fn limits() -> Limits<3> {
    Limits::<3>::new(400.0, 2_000.0, 60_000.0)
        .unwrap()
        .with_axis_acceleration([1_800.0, f64::INFINITY, 1_000.0])
        .unwrap()
}

fn path<N: Kernel>() -> Box<Path<N, 3, 256>> {
    let line = Bezier::new([[0.0_f64, 0.0, 0.0], [300.0, 100.0, 80.0]]).unwrap();
    let options = PlanOptions::new().with_feed_share(0.0).with_rate(RATE);
    let timing = PathTiming::<_, 64, 16>::plan(&line, &limits(), &options).unwrap();
    let mut path = Box::new(Path::new());
    timing
        .compile_into(&CompileOptions::new(), &mut path)
        .unwrap();
    assert_eq!(path.feed_share(), 0.0);
    path
}

fn f64s<T: Scalar>(x: [T; 3]) -> [f64; 3] {
    x.map(Scalar::to_f64)
}

fn norm(x: &[f64; 3]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>().sqrt()
}

/// The largest ratio to the limits over the samples (above 1: exceeded).
struct Worst {
    ratio: f64,
    prev: Option<[[f64; 3]; 3]>,
    format: strak_trajectory::NumberFormat,
}

impl Worst {
    fn push<O: Scalar>(&mut self, s: &Sample<O, 3>) {
        let l = limits();
        let now = [f64s(s.position), f64s(s.velocity), f64s(s.acceleration)];
        let (va, aa) = (l.axis_velocity(), l.axis_acceleration());
        let mut ratio = |x: f64, limit: f64, slack: f64| {
            self.ratio = self.ratio.max(x / (limit * (1.0 + 1e-9) + slack));
        };
        ratio(norm(&now[1]), l.velocity(), 0.0);
        ratio(norm(&now[2]), l.acceleration(), 0.0);
        for i in 0..3 {
            ratio(now[1][i].abs(), va[i], 0.0);
            ratio(now[2][i].abs(), aa[i], 0.0);
        }
        if let Some(p) = self.prev {
            let d =
                |k: usize| -> [f64; 3] { std::array::from_fn(|i| (now[k][i] - p[k][i]) * RATE) };
            let u = |k: usize| {
                let m = now[k]
                    .iter()
                    .chain(&p[k])
                    .fold(0.0_f64, |m, x| m.max(x.abs()));
                2.0 * self.format.sample_resolution(m) * RATE
            };
            let (dx, dv, da) = (d(0), d(1), d(2));
            let r3 = 3.0_f64.sqrt();
            ratio(norm(&dx), l.velocity(), u(0) * r3);
            ratio(norm(&dv), l.acceleration(), u(1) * r3);
            ratio(norm(&da), l.jerk(), u(2) * r3);
            for i in 0..3 {
                ratio(dx[i].abs(), va[i], u(0));
                ratio(dv[i].abs(), aa[i], u(1));
            }
        }
        self.prev = Some(now);
    }
}

/// A run: the sampler, its last sample, its tick, and the worst ratio to the limits.
struct Run<'p, N: Kernel> {
    sampler: Sampler<'p, N, 3>,
    last: Option<Sample<N::Out, 3>>,
    tick: u64,
    worst: Worst,
}

impl<N: Kernel> Run<'_, N> {
    fn step(&mut self) {
        let s = self.sampler.next();
        self.worst.push(&s);
        self.last = Some(s);
        self.tick += 1;
    }

    /// Applies `event` now, or when and as slowly as the guard schedules it; the ticks it
    /// waited.
    fn apply(&mut self, event: Event, guarded: bool) -> u64 {
        let mut waited = 0;
        if guarded {
            let guard = FeedGuard::new(&limits());
            let when = guard
                .schedule(&self.sampler, self.last.as_ref(), event)
                .unwrap();
            for _ in 0..when.delay {
                self.step();
            }
            if let Some(shift) = when.shift {
                assert!(self.sampler.scale_feed_ramp(shift));
            }
            waited = u64::from(when.delay);
        }
        self.sampler.apply(event);
        waited
    }
}

/// Plays the path with a hold asked before sample `at` (guarded or not) and a resume asked
/// 400 ticks after the hold applied; the worst ratio to the limits and the ticks the hold
/// waited.
fn hold_at<N: Kernel>(path: &Path<N, 3, 256>, at: u64, guarded: bool) -> (f64, u64) {
    let mut run = Run {
        sampler: Sampler::new(path),
        last: None,
        tick: 0,
        worst: Worst {
            ratio: 0.0,
            prev: None,
            format: N::FORMAT,
        },
    };
    let (mut held_at, mut waited) = (None, 0);
    while !run.sampler.is_finished() {
        if run.tick == at {
            waited = run.apply(Event::Hold, guarded);
            held_at = Some(run.tick);
        }
        if held_at.is_some_and(|h| run.tick == h + 400) {
            run.apply(Event::Resume, guarded);
        }
        run.step();
    }
    (run.worst.ratio, waited)
}

fn holds<N: Kernel>() {
    let path = path::<N>();
    let ticks = u64::from(path.ticks());
    let (mut unguarded_over, mut latest, mut late) = (0, 0, 0);
    let mut guarded_worst = 0.0_f64;
    for at in (0..ticks).step_by(5) {
        let (ratio, _) = hold_at(&*path, at, false);
        if ratio > 1.0 {
            unguarded_over += 1;
        }
        let (ratio, delay) = hold_at(&*path, at, true);
        assert!(
            ratio <= 1.0,
            "{}: hold at {at} (+{delay}): {ratio}",
            N::NAME
        );
        guarded_worst = guarded_worst.max(ratio);
        latest = latest.max(delay);
        late += usize::from(delay > 0);
    }
    println!(
        "{}: {} holds over {ticks} ticks: unguarded {unguarded_over} exceed a limit; guarded none \
         (worst ratio {guarded_worst:.6}), {late} waited, the longest {latest} ticks",
        N::NAME,
        ticks.div_ceil(5)
    );
    assert!(
        unguarded_over > 0,
        "the unguarded holds should exceed a limit somewhere"
    );
}

#[test]
fn guarded_holds_keep_every_limit_in_every_format() {
    holds::<f64>();
    holds::<f32>();
    holds::<Q40>();
}

/// A guard whose velocity limit the cruise exceeds finds no tick before the motion has slowed
/// below it: the hold waits for that.
#[test]
fn a_guard_below_the_cruise_waits_for_the_slowdown() {
    let path = path::<f64>();
    let tight = Limits::<3>::new(100.0, 2_000.0, 60_000.0).unwrap();
    let guard = FeedGuard::new(&tight);
    let mut sampler = Sampler::new(&*path);
    let mut last = None;
    for _ in 0..200 {
        last = Some(sampler.next());
    }
    let when = guard
        .schedule(&sampler, last.as_ref(), Event::Hold)
        .unwrap();
    assert!(when.delay > 0);
    // it applies once the motion has slowed below the guard's velocity limit
    for _ in 0..when.delay - 1 {
        sampler.next();
    }
    let before = sampler.next();
    assert!(norm(&f64s(before.velocity)) <= 100.0, "{when:?}");
    assert!(norm(&f64s(last.unwrap().velocity)) > 100.0);
}

/// Held at rest, a resume that no slow-down keeps within the guard's limits is refused at
/// once (every later tick is the same standstill): here a guard whose jerk limit no ramp
/// can keep.
#[test]
fn a_resume_no_ramp_can_keep_is_refused() {
    let path = path::<f64>();
    let mut sampler = Sampler::new(&*path);
    for _ in 0..300 {
        sampler.next();
    }
    sampler.hold();
    let mut last = sampler.next();
    while sampler.is_ramping() {
        last = sampler.next();
    }
    assert_eq!(sampler.feed(), 0.0);
    let strict = Limits::<3>::new(400.0, 2_000.0, 1e-6).unwrap();
    let guard = FeedGuard::new(&strict);
    assert_eq!(guard.schedule(&sampler, Some(&last), Event::Resume), None);
    // the machine's guard resumes at once
    let when = FeedGuard::new(&limits()).schedule(&sampler, Some(&last), Event::Resume);
    assert_eq!(when.map(|w| w.delay), Some(0));
}
