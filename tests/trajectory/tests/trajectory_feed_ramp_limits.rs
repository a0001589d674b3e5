//! A feed change keeps the machine's acceleration when the ramp's jerk limit is so high
//! that the feed rate could reach its largest value within one tick: the smallest form of
//! the `pipeline` fuzz input `fuzz/artifacts-kept/pipeline/feed-ramp-jerk-within-a-tick-q40`.
//! The ramp's rate of the feed factor is a whole multiple of its per-tick step `α`, at
//! least one; with `α` above the rate limit `ω_max` one step was already `6.8·ω_max`, and
//! the feed change from 1 to 0.784 took two ticks at 3.1 times the acceleration limit.
//!
//! Measured from the samples: `|v_{k+1} − v_k|/T`, the mean acceleration over a tick, which
//! adds nothing above the motion's peak; the allowance is `f64` rounding, `10⁻⁶` of the
//! limit.

use strak_curves::Bezier;
use strak_trajectory::{
    Along, CompileOptions, Kernel, Limits, Path, PathTiming, PlanOptions, Q40, Sampler, compile,
};

/// The largest mean acceleration over a tick with the feed set to `feed` at tick `at`, and
/// back to 1 after the end.
fn peak_acceleration_with_a_feed_change<N: Kernel>(at: u64, feed: f32) -> (f64, f64) {
    let line = Bezier::new([[0.3_f64], [0.13]]).unwrap();
    let (v, a, j) = (60.86, 48.44456, 170_040.405_6);
    let share = 0.339;
    let keep = 1.0 - share;
    let planned = Limits::<1>::new(v, a * keep, j * keep).unwrap();
    let options = PlanOptions::new()
        .with_samples(274)
        .with_centripetal_share(0.075)
        .with_corner_angle(1.3e-5);
    let law = PathTiming::<_, 16, 64>::plan(&line, &planned, &options).unwrap();
    let compile_options = CompileOptions::new()
        .with_limits(a, j)
        .with_feed_share(share);
    let rate = 1_000.0;
    let path: Path<N, 1, 64> = compile(&Along::new(&line, &law), rate, &compile_options).unwrap();
    let mut sampler = Sampler::new(&path);
    let mut prev: Option<f64> = None;
    let mut peak = 0.0_f64;
    for k in 0..100_000_u64 {
        if k == at {
            sampler.set_feed(feed);
        }
        if k == u64::from(path.ticks()) + 1 {
            sampler.set_feed(1.0);
        }
        let s = sampler.next();
        let velocity = strak_curves::Scalar::to_f64(s.velocity[0]);
        if let Some(p) = prev {
            peak = peak.max((velocity - p).abs() * rate);
        }
        prev = Some(velocity);
        if sampler.is_finished() {
            break;
        }
    }
    assert!(sampler.is_finished());
    (peak, a)
}

#[test]
fn a_feed_change_keeps_the_acceleration_when_the_jerk_limit_is_high() {
    for (peak, limit) in [
        peak_acceleration_with_a_feed_change::<f64>(90, 0.784),
        peak_acceleration_with_a_feed_change::<Q40>(90, 0.784),
        peak_acceleration_with_a_feed_change::<f32>(90, 0.784),
        peak_acceleration_with_a_feed_change::<f64>(40, 0.2),
    ] {
        println!("peak acceleration {peak:.4} of {limit}");
        assert!(peak <= limit * (1.0 + 1e-6), "{peak} > {limit}");
    }
}
