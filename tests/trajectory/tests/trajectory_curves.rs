//! The curve kinds of strak-curves — B-spline, NURBS, Hermite spline, interpolating cubic
//! spline, Bézier chain, and the helix of a G-code arc — planned with the jerk-limited
//! S-curve (`PathTiming::scurve`), compiled (`strak_trajectory::compile`) and played
//! (`Sampler`) in `f64` and `f32`.
//!
//! Checked for each (see `strak_trajectory_tests::check_playback`): `ticks + 1` samples; the last
//! sample equals `Path::end_position` bit for bit (and, in `f64`, the curve's own end point);
//! every sample within the path's documented bound `tolerance + playback_bound + output
//! rounding` of the exact `f64` curve at the planned parameter, `c(u(t_k))` (the approach of
//! `trajectory_accuracy.rs`, position channel). Measured errors are printed with
//! `--nocapture`.

use strak_curves::{
    BSpline, BezierChain, CircularArc, CubicSpline, HermiteSpline, Nurbs, ParamCurveDeriv,
    Parameterization, Plane, SplineBoundary, Turn,
};
use strak_trajectory::{Along, CompileOptions, Limits, Path, PathTiming, Sampler};
use strak_trajectory_tests::{Unpromised, check_playback, compile_boxed};

/// Control rate (Hz).
const RATE: f64 = 10_000.0;
/// Piece capacity of the compiled paths.
const PIECES: usize = 1024;

/// Waypoints of a 3-axis move (mm): up, across, down.
const WAYPOINTS: [[f64; 3]; 6] = [
    [0.0, 0.0, 0.0],
    [5.0, 2.0, 20.0],
    [30.0, 15.0, 30.0],
    [60.0, 35.0, 30.0],
    [85.0, 48.0, 20.0],
    [90.0, 50.0, 0.0],
];

fn limits() -> Limits<3> {
    Limits::<3>::new(120.0, 1_500.0, 40_000.0).expect("limits")
}

/// Plans, compiles in `f64` and `f32`, plays both and checks them.
fn plan_compile_play<C>(name: &str, curve: &C)
where
    C: ParamCurveDeriv<Point = [f64; 3]>,
{
    let scurve = PathTiming::<_, 256, 128>::scurve(curve, &limits()).expect("plan");
    // The plan without the limits it promises. The S-curve's jerk bound assumes a
    // curvature-continuous path; at the C¹ joins of the Hermite spline, the Bézier chain and
    // the quadratic NURBS the acceleration steps by `v²·Δκ`, which a tight fit resolves into
    // many times the jerk limit, and `compile` would report `Error::LimitExceeded` (the limits
    // are checked in `trajectory_limits_matrix.rs`). Positions are checked here.
    let plan = Unpromised(&scurve);
    let options = CompileOptions::new().with_tolerance(1e-6);
    let p64: Box<Path<f64, 3, PIECES>> =
        compile_boxed(&Along::new(curve, &plan), RATE, &options).expect("compile f64");
    // f32 to what its playback holds on these paths (bounds 4·10⁻⁴ … 1.3·10⁻³)
    let options32 = CompileOptions::new().with_tolerance(2e-3);
    let p32: Box<Path<f32, 3, PIECES>> =
        compile_boxed(&Along::new(curve, &plan), RATE, &options32).expect("compile f32");
    assert_eq!(p32.ticks(), p64.ticks(), "{name}: same tick count");
    let r64 = check_playback(name, curve, &plan, &p64);
    let r32 = check_playback(name, curve, &plan, &p32);
    // f64: the end point is the curve's own, bit for bit; f32: that point rounded once
    let end = curve.eval(curve.domain().1);
    for (i, e) in end.into_iter().enumerate() {
        assert_eq!(p64.end_position()[i].to_bits(), e.to_bits(), "{name}");
        #[allow(clippy::cast_possible_truncation)]
        let e32 = e as f32;
        assert_eq!(p32.end_position()[i].to_bits(), e32.to_bits(), "{name}");
    }
    println!(
        "{name:>22}: {} ticks ({:.3} s), {} pieces; f64 error {:.2e} ({:.3} of bound {:.2e}), \
         f32 error {:.2e} ({:.3} of bound {:.2e})",
        p64.ticks(),
        p64.duration(),
        p64.pieces().len(),
        r64.err,
        r64.ratio,
        p64.tolerance() + p64.playback_bound(),
        r32.err,
        r32.ratio,
        p32.tolerance() + p32.playback_bound(),
    );
}

#[test]
fn bspline() {
    let c = BSpline::<[f64; 3], 8, 12>::clamped_uniform(3, &WAYPOINTS, 0.0, 1.0).expect("B-spline");
    plan_compile_play("B-spline", &c);
}

#[test]
fn nurbs() {
    let w = [1.0, 2.0, 0.5, 1.5, 1.0, 1.0];
    let c = Nurbs::<[f64; 3], 8, 12>::clamped_uniform(2, &WAYPOINTS, &w, 0.0, 1.0).expect("NURBS");
    plan_compile_play("NURBS", &c);
}

#[test]
fn hermite_spline() {
    // tangents with respect to chord length (|c'| ≈ 1): vertical at the ends
    let tangents = [
        [0.0, 0.0, 1.0],
        [0.5, 0.2, 0.8],
        [0.85, 0.5, 0.1],
        [0.85, 0.5, -0.1],
        [0.5, 0.2, -0.8],
        [0.0, 0.0, -1.0],
    ];
    let c = HermiteSpline::<[f64; 3], 8>::new(&WAYPOINTS, &tangents, Parameterization::ChordLength)
        .expect("Hermite spline");
    plan_compile_play("Hermite spline", &c);
}

#[test]
fn interpolating_cubic_spline() {
    let c = CubicSpline::<[f64; 3], 8>::new(
        &WAYPOINTS,
        Parameterization::ChordLength,
        SplineBoundary::Natural,
    )
    .expect("cubic spline");
    plan_compile_play("cubic spline", &c);
}

#[test]
fn helix() {
    // half a turn of radius 20, rising 30
    let c = CircularArc::with_center(
        [65.0, 25.0, 0.0],
        [25.0, 25.0, 30.0],
        [45.0, 25.0],
        Plane::XY,
        Turn::CounterClockwise,
        1e-9,
    )
    .expect("helix");
    plan_compile_play("helix", &c);
}

#[test]
fn bezier_chain() {
    // three cubic segments joined C¹ (firmware-sim/examples/bezier-chain.toml)
    let c = BezierChain::<[f64; 3], 4, 4>::new(&[
        [0.0, 0.0, 0.0],
        [10.0, 0.0, 5.0],
        [20.0, 10.0, 10.0],
        [30.0, 10.0, 10.0],
        [40.0, 10.0, 10.0],
        [45.0, 20.0, 5.0],
        [50.0, 30.0, 5.0],
        [55.0, 40.0, 5.0],
        [60.0, 50.0, 0.0],
        [70.0, 50.0, 0.0],
    ])
    .expect("Bézier chain");
    plan_compile_play("Bézier chain", &c);
    // and with a corner (a C⁰, not G¹, join at (30, 10, 10)): the motion stops there, so
    // the acceleration in space stays within the limit (before the planner detected
    // corners it passed this one at about 71 mm/s: 2.4·10⁶ mm/s² in the samples)
    let corner = BezierChain::<[f64; 3], 4, 4>::new(&[
        [0.0, 0.0, 0.0],
        [10.0, 0.0, 5.0],
        [20.0, 10.0, 10.0],
        [30.0, 10.0, 10.0],
        [30.0, 20.0, 10.0],
        [40.0, 30.0, 5.0],
        [50.0, 30.0, 5.0],
    ])
    .expect("Bézier chain with a corner");
    plan_compile_play("Bézier chain (corner)", &corner);
    let plan = PathTiming::<_, 256, 128>::scurve(&corner, &limits()).expect("plan");
    let zones = plan.motion().zones();
    let stop = zones
        .iter()
        .position(|z| z.stops_at_end())
        .expect("a zone ends at the corner");
    assert_eq!(zones[stop].v_end(), 0.0);
    assert_eq!(zones.iter().filter(|z| z.stops_at_end()).count(), 1);
    let corner_s = plan.table().length_at(1.0);
    assert!((zones[stop].end() - corner_s).abs() < 1e-9 * corner_s);
    let options = CompileOptions::new().with_tolerance(1e-6);
    let path: Box<Path<f64, 3, PIECES>> =
        compile_boxed(&Along::new(&corner, &plan), RATE, &options).expect("compile");
    let mut sampler = Sampler::new(&*path);
    let (mut prev, mut a_max) = (sampler.next().velocity, 0.0_f64);
    while !sampler.is_finished() {
        let v = sampler.next().velocity;
        let dv = (0..3).map(|i| (v[i] - prev[i]).powi(2)).sum::<f64>().sqrt();
        a_max = a_max.max(dv * RATE);
        prev = v;
    }
    println!("Bézier chain (corner): |a| ≤ {a_max:.1} (limit 1500)");
    // the compiled spline's fit may exceed the planned acceleration by a few percent
    assert!(a_max <= 1.1 * limits().acceleration(), "{a_max}");
}
