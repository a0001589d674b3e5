//! Bad input for the trajectory layer: every typed [`Error`] from planning, compiling and
//! loading a path, with the exact error asserted; the blob round trip; and property tests
//! that arbitrary input (finite, NaN, ±∞, huge, tiny) never makes planning or compiling
//! panic, and that sampling any successfully compiled path never panics and always ends.

use std::cell::Cell;

use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed, TestCaseResult, TestRunner};
use strak_curves::{Bezier, CubicSpline, I32F32, Nurbs, Parameterization, Scalar, SplineBoundary};
use strak_trajectory::{
    Along, BLOB_MAGIC, BLOB_VERSION, BlobFormat, CompileOptions, Error, Kernel, Limits,
    MotionProfile, NumberFormat, ParameterTiming, Path, PathTiming, PlanOptions, ProfileShape, Q40,
    Sampler, SamplerState, Timing, compile, crc32,
};
use strak_trajectory_tests::compile_within_bound;

const NAN: f64 = f64::NAN;
const INF: f64 = f64::INFINITY;

/// Values that are not a valid limit.
const BAD: [f64; 6] = [0.0, -0.0, -1.0, NAN, INF, -INF];

fn line2() -> Bezier<[f64; 2], 2> {
    Bezier::new([[0.0, 0.0], [30.0, 40.0]]).expect("line")
}

fn line3() -> Bezier<[f64; 3], 2> {
    Bezier::new([[0.0, 0.0, 0.0], [30.0, 40.0, 120.0]]).expect("line")
}

fn limits3() -> Limits<3> {
    Limits::new(200.0, 2_000.0, 50_000.0).expect("limits")
}

/// A time law of any duration, `u = t/d` on `[0, 1]`.
struct Linear(f64);

impl Timing for Linear {
    fn duration(&self) -> f64 {
        self.0
    }
    fn param(&self, t: f64) -> (f64, f64) {
        ((t / self.0).clamp(0.0, 1.0), 1.0 / self.0)
    }
}

// ---------------------------------------------------------------------------------------------
// InvalidLimit
// ---------------------------------------------------------------------------------------------

#[test]
fn invalid_limit_path_limits() {
    for bad in BAD {
        assert_eq!(
            Limits::<3>::new(bad, 1.0, 1.0),
            Err(Error::InvalidLimit),
            "v {bad}"
        );
        assert_eq!(
            Limits::<3>::new(1.0, bad, 1.0),
            Err(Error::InvalidLimit),
            "a {bad}"
        );
        assert_eq!(
            Limits::<3>::new(1.0, 1.0, bad),
            Err(Error::InvalidLimit),
            "j {bad}"
        );
    }
    assert!(Limits::<3>::new(1e-300, 1e300, f64::MIN_POSITIVE).is_ok());
}

#[test]
fn invalid_limit_axis_arrays() {
    let l = limits3();
    for bad in [0.0, -0.0, -1.0, NAN, -INF] {
        for axis in 0..3 {
            let mut x = [100.0; 3];
            x[axis] = bad;
            assert_eq!(
                l.with_axis_velocity(x),
                Err(Error::InvalidLimit),
                "v{axis} {bad}"
            );
            assert_eq!(
                l.with_axis_acceleration(x),
                Err(Error::InvalidLimit),
                "a{axis} {bad}"
            );
        }
    }
    // +∞: no limit of its own
    let ok = l.with_axis_velocity([INF, 1.0, INF]).expect("∞ allowed");
    assert_eq!(ok.axis_velocity(), [INF, 1.0, INF]);
    assert!(l.with_axis_acceleration([INF; 3]).is_ok());
}

#[test]
fn invalid_limit_motion_profiles() {
    for bad in BAD {
        assert_eq!(
            MotionProfile::<1>::scurve(1.0, bad, 1.0, 1.0),
            Err(Error::InvalidLimit)
        );
        assert_eq!(
            MotionProfile::<1>::scurve(1.0, 1.0, bad, 1.0),
            Err(Error::InvalidLimit)
        );
        assert_eq!(
            MotionProfile::<1>::scurve(1.0, 1.0, 1.0, bad),
            Err(Error::InvalidLimit)
        );
        assert_eq!(
            MotionProfile::<1>::trapezoid(1.0, bad, 1.0),
            Err(Error::InvalidLimit)
        );
        assert_eq!(
            MotionProfile::<1>::trapezoid(1.0, 1.0, bad),
            Err(Error::InvalidLimit)
        );
        assert_eq!(
            MotionProfile::<1>::constant_speed(1.0, bad),
            Err(Error::InvalidLimit)
        );
    }
    // limits so small that the duration is infinite: more ticks than a u32 counts
    assert_eq!(
        MotionProfile::<1>::constant_speed(1e300, 1e-300),
        Err(Error::TooLong)
    );
    assert_eq!(
        MotionProfile::<1>::scurve(1e300, 1e-300, 1.0, 1.0),
        Err(Error::TooLong)
    );
}

#[test]
fn invalid_limit_time_laws() {
    let c = line3();
    for bad in [-1.0, NAN, INF, -INF] {
        assert_eq!(
            ParameterTiming::over(&c, bad),
            Err(Error::InvalidLimit),
            "{bad}"
        );
    }
    for bad in BAD {
        assert_eq!(
            ParameterTiming::at_rate(&c, bad),
            Err(Error::InvalidLimit),
            "{bad}"
        );
        assert!(matches!(
            PathTiming::<_, 16, 1>::constant_speed(&c, bad),
            Err(Error::InvalidLimit)
        ));
        assert!(matches!(
            PathTiming::<_, 16, 1>::trapezoid(&c, bad, 1.0),
            Err(Error::InvalidLimit)
        ));
        assert!(matches!(
            PathTiming::<_, 16, 1>::trapezoid(&c, 1.0, bad),
            Err(Error::InvalidLimit)
        ));
    }
    // a duration that underflows the rate
    assert_eq!(ParameterTiming::over(&c, 1e-320), Err(Error::InvalidLimit));
}

#[test]
fn invalid_limit_plan_options() {
    let c = line3();
    let l = limits3();
    let bad_options = [
        PlanOptions::new().with_samples(0),
        PlanOptions::new().with_samples((1 << 20) + 1),
        PlanOptions::new().with_zone_tolerance(-0.1),
        PlanOptions::new().with_zone_tolerance(NAN),
        PlanOptions::new().with_zone_tolerance(INF),
        PlanOptions::new().with_centripetal_share(0.0),
        PlanOptions::new().with_centripetal_share(1.0),
        PlanOptions::new().with_centripetal_share(NAN),
        PlanOptions::new().with_centripetal_share(-0.5),
        PlanOptions::new().with_corner_angle(0.0),
        PlanOptions::new().with_corner_angle(-1e-3),
        PlanOptions::new().with_corner_angle(NAN),
        PlanOptions::new().with_corner_angle(INF),
    ];
    for o in bad_options {
        assert!(
            matches!(
                PathTiming::<_, 16, 4>::plan(&c, &l, &o),
                Err(Error::InvalidLimit)
            ),
            "{o:?}"
        );
    }
    // the extremes that are allowed
    for o in [
        PlanOptions::new().with_samples(1),
        PlanOptions::new().with_zone_tolerance(0.0),
        PlanOptions::new().with_centripetal_share(0.999),
        PlanOptions::new().with_corner_angle(3.0),
        PlanOptions::new().with_shape(ProfileShape::Trapezoid),
    ] {
        assert!(PathTiming::<_, 16, 4>::plan(&c, &l, &o).is_ok(), "{o:?}");
    }
}

#[test]
fn invalid_limit_compile_options() {
    let c = line2();
    let t = Linear(0.1);
    let bad_options = [
        CompileOptions::new().with_tolerance(0.0),
        CompileOptions::new().with_tolerance(-1e-3),
        CompileOptions::new().with_tolerance(NAN),
        CompileOptions::new().with_tolerance(INF),
        CompileOptions::new().with_relative_tolerance(0.0),
        CompileOptions::new().with_relative_tolerance(NAN),
        CompileOptions::new().with_max_piece_ticks(0),
        CompileOptions::new().with_limits(0.0, 1.0),
        CompileOptions::new().with_limits(1.0, -1.0),
        CompileOptions::new().with_limits(NAN, 1.0),
        CompileOptions::new().with_limits(1.0, INF),
        CompileOptions::new().with_feed_share(1.0),
        CompileOptions::new().with_feed_share(-0.25),
        CompileOptions::new().with_feed_share(NAN),
    ];
    for o in bad_options {
        let r: Result<Path<f64, 2, 8>, _> = compile(&Along::new(&c, &t), 1_000.0, &o);
        assert_eq!(r, Err(Error::InvalidLimit), "{o:?}");
    }
}

// ---------------------------------------------------------------------------------------------
// InvalidRate
// ---------------------------------------------------------------------------------------------

#[test]
fn invalid_rate() {
    let c = line2();
    let t = Linear(0.1);
    let o = CompileOptions::new();
    for rate in [99.999, 100_000.001, 0.0, -1_000.0, NAN, INF, -INF, 1e300] {
        let r: Result<Path<f64, 2, 64>, _> = compile(&Along::new(&c, &t), rate, &o);
        assert_eq!(r, Err(Error::InvalidRate), "{rate} Hz");
        let r: Result<Path<Q40, 2, 64>, _> = compile(&Along::new(&c, &t), rate, &o);
        assert_eq!(r, Err(Error::InvalidRate), "{rate} Hz");
    }
    for rate in [100.0, 100_000.0] {
        let r: Result<Path<f64, 2, 64>, _> = compile(&Along::new(&c, &t), rate, &o);
        assert!(r.is_ok(), "{rate} Hz is allowed");
    }
}

// ---------------------------------------------------------------------------------------------
// EmptyPath
// ---------------------------------------------------------------------------------------------

#[test]
fn empty_path_zero_length_curve() {
    let still = Bezier::new([[5.0, -1.0, 2.0]; 4]).expect("a curve that stands still");
    let l = limits3();
    assert!(matches!(
        PathTiming::<_, 16, 4>::constant_speed(&still, 1.0),
        Err(Error::EmptyPath)
    ));
    assert!(matches!(
        PathTiming::<_, 16, 4>::trapezoid(&still, 1.0, 1.0),
        Err(Error::EmptyPath)
    ));
    assert!(matches!(
        PathTiming::<_, 16, 4>::scurve(&still, &l),
        Err(Error::EmptyPath)
    ));
    let o = PlanOptions::new().with_shape(ProfileShape::Trapezoid);
    assert!(matches!(
        PathTiming::<_, 16, 4>::plan(&still, &l, &o),
        Err(Error::EmptyPath)
    ));
    for bad in [0.0, -0.0, -1.0, NAN] {
        assert_eq!(
            MotionProfile::<1>::scurve(bad, 1.0, 1.0, 1.0),
            Err(Error::EmptyPath)
        );
        assert_eq!(
            MotionProfile::<1>::trapezoid(bad, 1.0, 1.0),
            Err(Error::EmptyPath)
        );
        assert_eq!(
            MotionProfile::<1>::constant_speed(bad, 1.0),
            Err(Error::EmptyPath)
        );
    }
    // a standing curve under the parameter law is a valid (still) motion
    let t = ParameterTiming::over(&still, 0.01).expect("law");
    let path: Path<f64, 3, 8> =
        compile(&Along::new(&still, &t), 1_000.0, &CompileOptions::new()).expect("still");
    let mut s = Sampler::new(&path);
    while !s.is_finished() {
        assert_eq!(s.next().position, [5.0, -1.0, 2.0]);
    }
}

#[test]
fn empty_path_zero_duration() {
    let c = line2();
    assert_eq!(ParameterTiming::over(&c, 0.0), Err(Error::EmptyPath));
    for d in [0.0, -0.0, -1.0, NAN, -INF] {
        let r: Result<Path<f64, 2, 8>, _> =
            compile(&Along::new(&c, &Linear(d)), 1_000.0, &CompileOptions::new());
        assert_eq!(r, Err(Error::EmptyPath), "duration {d}");
    }
}

// ---------------------------------------------------------------------------------------------
// AxisMismatch
// ---------------------------------------------------------------------------------------------

#[test]
fn axis_mismatch() {
    let c = line2();
    let l3 = limits3();
    assert!(matches!(
        PathTiming::<_, 16, 4>::scurve(&c, &l3),
        Err(Error::AxisMismatch { curve: 2, path: 3 })
    ));
    let l1 = Limits::<1>::new(1.0, 1.0, 1.0).expect("limits");
    assert!(matches!(
        PathTiming::<_, 16, 4>::plan(&c, &l1, &PlanOptions::new()),
        Err(Error::AxisMismatch { curve: 2, path: 1 })
    ));
    let t = Linear(0.1);
    let r: Result<Path<f64, 3, 8>, _> =
        compile(&Along::new(&c, &t), 1_000.0, &CompileOptions::new());
    assert_eq!(r, Err(Error::AxisMismatch { curve: 2, path: 3 }));
    let r: Result<Path<Q40, 1, 8>, _> =
        compile(&Along::new(&line3(), &t), 1_000.0, &CompileOptions::new());
    assert_eq!(r, Err(Error::AxisMismatch { curve: 3, path: 1 }));
}

// ---------------------------------------------------------------------------------------------
// CapacityExceeded
// ---------------------------------------------------------------------------------------------

#[test]
fn capacity_exceeded_pieces() {
    let c = line2();
    // 1000 ticks in pieces of at most 256: 4 pieces
    let r: Result<Path<f64, 2, 3>, _> = compile(
        &Along::new(&c, &Linear(1.0)),
        1_000.0,
        &CompileOptions::new(),
    );
    assert_eq!(
        r,
        Err(Error::CapacityExceeded {
            capacity: 3,
            required: 4
        })
    );
    // the adaptive refinement needs more pieces than the grid
    let circle = Nurbs::<[f64; 2], 9, 12>::circle([0.0, 0.0], 10.0).expect("circle");
    let plan = PathTiming::<_, 64, 64>::scurve(
        &circle,
        &Limits::<2>::new(100.0, 1_000.0, 1e5).expect("l"),
    )
    .expect("plan");
    let r: Result<Path<f64, 2, 4>, _> = compile(
        &Along::new(&circle, &plan),
        1_000.0,
        &CompileOptions::new().with_tolerance(1e-9),
    );
    assert!(
        matches!(r, Err(Error::CapacityExceeded { capacity: 4, required }) if required > 4),
        "{r:?}"
    );
}

#[test]
fn capacity_exceeded_zones() {
    // the circle with an x-axis velocity limit: the speed limit varies, many zones
    let circle = Nurbs::<[f64; 2], 9, 12>::circle([0.0, 0.0], 10.0).expect("circle");
    let l = Limits::new(200.0, 2_000.0, 50_000.0)
        .and_then(|l| l.with_axis_velocity([60.0, INF]))
        .expect("limits");
    let r = PathTiming::<_, 64, 2>::scurve(&circle, &l);
    assert!(
        matches!(r, Err(Error::ZoneCapacityExceeded { capacity: 2, required }) if required > 2),
        "{:?}",
        r.err()
    );
    assert!(PathTiming::<_, 64, 256>::scurve(&circle, &l).is_ok());
    assert_eq!(
        MotionProfile::<0>::scurve(1.0, 1.0, 1.0, 1.0),
        Err(Error::ZoneCapacityExceeded {
            capacity: 0,
            required: 1
        })
    );
    assert!(matches!(
        PathTiming::<_, 16, 0>::constant_speed(&line2(), 1.0),
        Err(Error::ZoneCapacityExceeded {
            capacity: 0,
            required: 1
        })
    ));
}

#[test]
fn capacity_exceeded_blob_buffer_and_path() {
    let path = small_path::<f64, 2>();
    let len = path.blob_len();
    let mut short = vec![0_u8; len - 1];
    assert_eq!(
        path.to_bytes(&mut short),
        Err(Error::CapacityExceeded {
            capacity: len - 1,
            required: len
        })
    );
    let mut buf = vec![0_u8; len];
    assert_eq!(path.to_bytes(&mut buf), Ok(len));
    let m = path.pieces().len();
    assert!(m >= 2);
    assert_eq!(
        Path::<f64, 2, 1>::from_bytes(&buf),
        Err(Error::CapacityExceeded {
            capacity: 1,
            required: m
        })
    );
}

// ---------------------------------------------------------------------------------------------
// OutOfRange
// ---------------------------------------------------------------------------------------------

#[test]
fn out_of_range_fixed_point_coordinates() {
    let o = CompileOptions::new();
    let t = Linear(1.0);
    // beyond ±8 388 608 = 2²³ (Q23.40 cannot hold it at all), both signs, any axis
    for x in [8_388_609.0, 1.0e7, -8_388_609.0, -1.0e9] {
        let far = Bezier::new([[0.0, x], [1.0, x + 1.0]]).expect("curve");
        let r: Result<Path<Q40, 2, 8>, _> = compile(&Along::new(&far, &t), 1_000.0, &o);
        assert_eq!(r, Err(Error::OutOfRange), "{x}");
        // f64 takes them; f32 holds them, but its spacing there (≥ 1) puts the playback
        // bound above the tolerance, which is an error naming both
        let r: Result<Path<f64, 2, 8>, _> = compile(&Along::new(&far, &t), 1_000.0, &o);
        assert!(r.is_ok(), "{x} in f64");
        let r: Result<Path<f32, 2, 8>, _> = compile(&Along::new(&far, &t), 1_000.0, &o);
        assert!(
            matches!(r, Err(Error::PlaybackBoundExceeded { bound, tolerance })
                if bound.0 > 0.5 && tolerance.0 < 1.0),
            "{x} in f32: {r:?}"
        );
    }
    // beyond the checked range 2²² = 4 194 304 (half the representable, so that sums cannot
    // overflow) is rejected as well
    let half = Bezier::new([[5.0e6], [5.0e6 + 1.0]]).expect("curve");
    let r: Result<Path<Q40, 1, 8>, _> = compile(&Along::new(&half, &t), 1_000.0, &o);
    assert_eq!(r, Err(Error::OutOfRange));
    // inside: fine
    let inside = Bezier::new([[4.0e6], [4.0e6 + 1.0]]).expect("curve");
    let r: Result<Path<Q40, 1, 8>, _> = compile(&Along::new(&inside, &t), 1_000.0, &o);
    assert!(r.is_ok());
    // a fixed-point curve beyond the range (I32F32 holds it, Q40 does not)
    let q = |x: f64| I32F32::from_num(x);
    let fixed = Bezier::new([[q(9.0e6)], [q(9.0e6 + 10.0)]]).expect("curve");
    let r: Result<Path<Q40, 1, 8>, _> = compile(&Along::new(&fixed, &t), 1_000.0, &o);
    assert_eq!(r, Err(Error::OutOfRange));
    // a velocity beyond the range: 10⁷ units in 10 ms
    let fast = Bezier::new([[-2.0e6], [2.0e6]]).expect("curve");
    let r: Result<Path<Q40, 1, 8>, _> = compile(&Along::new(&fast, &Linear(0.4)), 1_000.0, &o);
    assert_eq!(r, Err(Error::OutOfRange));
}

#[test]
fn out_of_range_f32() {
    // beyond half of f32::MAX
    let huge = Bezier::new([[0.0], [3.0e38]]).expect("curve");
    let r: Result<Path<f32, 1, 8>, _> = compile(
        &Along::new(&huge, &Linear(1.0)),
        1_000.0,
        &CompileOptions::new(),
    );
    assert_eq!(r, Err(Error::OutOfRange));
    let r: Result<Path<f64, 1, 8>, _> = compile(
        &Along::new(&huge, &Linear(1.0)),
        1_000.0,
        &CompileOptions::new(),
    );
    assert!(r.is_ok());
}

// ---------------------------------------------------------------------------------------------
// TooLong
// ---------------------------------------------------------------------------------------------

#[test]
fn too_long() {
    let c = line2();
    let o = CompileOptions::new();
    // 10⁵ s at 100 kHz: 10¹⁰ ticks > u32::MAX
    let t = ParameterTiming::over(&c, 1.0e5).expect("law");
    let r: Result<Path<f64, 2, 8>, _> = compile(&Along::new(&c, &t), 100_000.0, &o);
    assert_eq!(r, Err(Error::TooLong));
    // just above: u32::MAX + 1 ticks at 100 Hz
    let t = Linear((f64::from(u32::MAX) + 1.0) / 100.0);
    let r: Result<Path<f64, 2, 8>, _> = compile(&Along::new(&c, &t), 100.0, &o);
    assert_eq!(r, Err(Error::TooLong));
    // an infinite duration
    let r: Result<Path<f64, 2, 8>, _> = compile(&Along::new(&c, &Linear(INF)), 1_000.0, &o);
    assert_eq!(r, Err(Error::TooLong));
    // a slow constant speed: 50 units at 10⁻⁵ units/s, 5·10⁶ s
    let slow = PathTiming::<_, 16, 1>::constant_speed(&c, 1e-5).expect("plan");
    let r: Result<Path<f64, 2, 8>, _> = compile(&Along::new(&c, &slow), 1_000.0, &o);
    assert_eq!(r, Err(Error::TooLong));
}

// ---------------------------------------------------------------------------------------------
// Curve errors
// ---------------------------------------------------------------------------------------------

/// A time law that breaks half-way.
struct Broken;

impl Timing for Broken {
    fn duration(&self) -> f64 {
        0.1
    }
    fn param(&self, t: f64) -> (f64, f64) {
        if t > 0.05 {
            (NAN, 1.0)
        } else {
            (t * 10.0, INF)
        }
    }
}

#[test]
fn curve_errors() {
    let c = line2();
    // an arc-length table of one sample
    assert!(matches!(
        PathTiming::<_, 1, 1>::constant_speed(&c, 1.0),
        Err(Error::Curve(strak_curves::Error::InvalidArgument))
    ));
    // a time law with non-finite values
    let r: Result<Path<f64, 2, 8>, _> =
        compile(&Along::new(&c, &Broken), 1_000.0, &CompileOptions::new());
    assert_eq!(r, Err(Error::Curve(strak_curves::Error::NonFinite)));
    // a curve that stands still over a whole table interval (degree 1, a repeated point)
    let pause = strak_curves::BSpline::<[f64; 2], 4, 8>::clamped_uniform(
        1,
        &[[0.0, 0.0], [0.0, 0.0], [3.0, 4.0]],
        0.0,
        1.0,
    )
    .expect("curve");
    assert!(matches!(
        PathTiming::<_, 16, 1>::constant_speed(&pause, 1.0),
        Err(Error::Curve(strak_curves::Error::ZeroLengthInterval { .. }))
    ));
}

// ---------------------------------------------------------------------------------------------
// Blobs
// ---------------------------------------------------------------------------------------------

/// A small compiled path of `A` axes (a few pieces).
fn small_path<N: Kernel, const A: usize>() -> Path<N, A, 16> {
    let a: [f64; A] = core::array::from_fn(|i| i as f64);
    let b: [f64; A] = core::array::from_fn(|i| 10.0 - 3.0 * i as f64);
    let c: [f64; A] = core::array::from_fn(|i| (i as f64).sqrt() - 1.0);
    let curve = Bezier::new([a, b, c]).expect("curve");
    // 10⁻⁴: within what f32 playback holds here (its bound: 4.7·10⁻⁵)
    let options = CompileOptions::new()
        .with_max_piece_ticks(64)
        .with_tolerance(1e-4);
    compile(&Along::new(&curve, &Linear(0.15)), 1_000.0, &options).expect("small path")
}

fn blob<N: Kernel, const A: usize>(path: &Path<N, A, 16>) -> Vec<u8> {
    let mut buf = vec![0_u8; path.blob_len()];
    let n = path.to_bytes(&mut buf).expect("to_bytes");
    assert_eq!(n, buf.len());
    buf
}

/// Replaces the CRC so that only the content check can reject the blob.
fn fix_crc(bytes: &mut [u8]) {
    let n = bytes.len() - 4;
    let crc = crc32(&bytes[..n]);
    bytes[n..].copy_from_slice(&crc.to_le_bytes());
}

fn round_trip<N: Kernel, const A: usize>() {
    let path = small_path::<N, A>();
    let bytes = blob(&path);
    assert_eq!(&bytes[..4], &BLOB_MAGIC);
    assert_eq!(u16::from_le_bytes([bytes[4], bytes[5]]), BLOB_VERSION);
    assert_eq!(bytes[6], N::FORMAT_ID);
    assert_eq!(usize::from(bytes[7]), A);
    let back = Path::<N, A, 16>::from_bytes(&bytes).expect("from_bytes");
    assert_eq!(back, path, "bit-exact round trip");
    assert_eq!(blob(&back), bytes, "the same bytes again");
    // the same samples, bit for bit
    let (mut s1, mut s2) = (Sampler::new(&path), Sampler::new(&back));
    while !s1.is_finished() {
        let (a, b) = (s1.next(), s2.next());
        assert_eq!(a, b);
    }
    assert!(s2.next().position == path.end_position() && s2.is_finished());
}

#[test]
fn blob_round_trip_is_bit_exact() {
    round_trip::<f32, 1>();
    round_trip::<f32, 2>();
    round_trip::<f64, 3>();
    round_trip::<Q40, 2>();
    round_trip::<Q40, 6>();
}

fn flipped_bytes<N: Kernel>() {
    let path = small_path::<N, 2>();
    let good = blob(&path);
    for i in 0..good.len() {
        for flip in [0x01_u8, 0x80, 0xFF] {
            let mut bad = good.clone();
            bad[i] ^= flip;
            let r = Path::<N, 2, 16>::from_bytes(&bad);
            let want = if (4..6).contains(&i) {
                Error::UnsupportedVersion {
                    found: u16::from_le_bytes([bad[4], bad[5]]),
                }
            } else {
                Error::CorruptBlob
            };
            assert_eq!(r, Err(want), "{} byte {i} ^ {flip:#x}", N::NAME);
        }
    }
}

#[test]
fn corrupt_blob_flipped_byte_anywhere() {
    flipped_bytes::<f32>();
    flipped_bytes::<f64>();
    flipped_bytes::<Q40>();
}

#[test]
fn corrupt_blob_truncated_or_extended() {
    let good = blob(&small_path::<Q40, 2>());
    for len in 0..good.len() {
        assert_eq!(
            Path::<Q40, 2, 16>::from_bytes(&good[..len]),
            Err(Error::CorruptBlob),
            "truncated to {len}"
        );
    }
    let mut longer = good.clone();
    longer.push(0);
    assert_eq!(
        Path::<Q40, 2, 16>::from_bytes(&longer),
        Err(Error::CorruptBlob)
    );
    fix_crc(&mut longer);
    assert_eq!(
        Path::<Q40, 2, 16>::from_bytes(&longer),
        Err(Error::CorruptBlob)
    );
    assert_eq!(Path::<Q40, 2, 16>::from_bytes(&[]), Err(Error::CorruptBlob));
}

/// Content a compiler never writes, behind a valid CRC: rejected by the content checks.
#[test]
fn corrupt_blob_with_valid_checksum() {
    let path = small_path::<f64, 2>();
    let good = blob(&path);
    let m = path.pieces().len();
    let header = 16 + 9 * 8 + 3 * 2 * 8; // magic … meta, end states
    // the tick count in the header disagrees with the pieces
    let mut bad = good.clone();
    bad[12] ^= 1;
    fix_crc(&mut bad);
    assert_eq!(
        Path::<f64, 2, 16>::from_bytes(&bad),
        Err(Error::CorruptBlob)
    );
    // one piece less than the header says (length mismatch)
    let mut bad = good.clone();
    bad[8..12].copy_from_slice(&(m as u32 - 1).to_le_bytes());
    fix_crc(&mut bad);
    assert_eq!(
        Path::<f64, 2, 16>::from_bytes(&bad),
        Err(Error::CorruptBlob)
    );
    // no pieces at all
    let mut bad = good[..header].to_vec();
    bad[8..12].copy_from_slice(&0_u32.to_le_bytes());
    bad.extend_from_slice(&[0; 4]);
    fix_crc(&mut bad);
    assert_eq!(
        Path::<f64, 2, 16>::from_bytes(&bad),
        Err(Error::CorruptBlob)
    );
    // a piece of zero ticks
    let mut bad = good.clone();
    bad[header..header + 4].copy_from_slice(&0_u32.to_le_bytes());
    fix_crc(&mut bad);
    assert_eq!(
        Path::<f64, 2, 16>::from_bytes(&bad),
        Err(Error::CorruptBlob)
    );
    // a NaN in the first state value
    let mut bad = good.clone();
    bad[header + 4..header + 12].copy_from_slice(&NAN.to_le_bytes());
    fix_crc(&mut bad);
    assert_eq!(
        Path::<f64, 2, 16>::from_bytes(&bad),
        Err(Error::CorruptBlob)
    );
    // a NaN end point
    let mut bad = good.clone();
    bad[88..96].copy_from_slice(&NAN.to_le_bytes());
    fix_crc(&mut bad);
    assert_eq!(
        Path::<f64, 2, 16>::from_bytes(&bad),
        Err(Error::CorruptBlob)
    );
    // a foreign magic
    let mut bad = good.clone();
    bad[..4].copy_from_slice(b"STRX");
    fix_crc(&mut bad);
    assert_eq!(
        Path::<f64, 2, 16>::from_bytes(&bad),
        Err(Error::CorruptBlob)
    );
    // a rate out of range (meta field 0)
    let mut bad = good.clone();
    bad[16..24].copy_from_slice(&1.0e6_f64.to_le_bytes());
    fix_crc(&mut bad);
    assert_eq!(
        Path::<f64, 2, 16>::from_bytes(&bad),
        Err(Error::InvalidRate)
    );
    // a negative tolerance (meta field 2)
    let mut bad = good.clone();
    bad[32..40].copy_from_slice(&(-1.0_f64).to_le_bytes());
    fix_crc(&mut bad);
    assert_eq!(
        Path::<f64, 2, 16>::from_bytes(&bad),
        Err(Error::InvalidLimit)
    );
}

/// A Q40 blob whose states would overflow during playback is rejected by the range check.
#[test]
fn out_of_range_blob() {
    let path = small_path::<Q40, 2>();
    let mut bad = blob(&path);
    let header = 16 + 9 * 8 + 3 * 2 * 8;
    // the first position of the first piece: 2⁶² raw = 2²² units, the checked limit
    bad[header + 4..header + 12].copy_from_slice(&(1_i64 << 62).to_le_bytes());
    fix_crc(&mut bad);
    assert_eq!(Path::<Q40, 2, 16>::from_bytes(&bad), Err(Error::OutOfRange));
}

#[test]
fn unsupported_version() {
    let good = blob(&small_path::<f32, 2>());
    for version in [0_u16, 2, BLOB_VERSION + 1, u16::MAX] {
        let mut bad = good.clone();
        bad[4..6].copy_from_slice(&version.to_le_bytes());
        assert_eq!(
            Path::<f32, 2, 16>::from_bytes(&bad),
            Err(Error::UnsupportedVersion { found: version })
        );
        // not a checksum matter: the same with a valid CRC
        fix_crc(&mut bad);
        assert_eq!(
            Path::<f32, 2, 16>::from_bytes(&bad),
            Err(Error::UnsupportedVersion { found: version })
        );
    }
}

#[test]
fn format_mismatch() {
    let f32_blob = blob(&small_path::<f32, 2>());
    let f64_blob = blob(&small_path::<f64, 2>());
    let q40_blob = blob(&small_path::<Q40, 2>());
    let mismatch = |expected: BlobFormat, id: u8, axes: usize| {
        Some(Error::FormatMismatch {
            expected,
            found: BlobFormat {
                number: NumberFormat::from_id(id).unwrap(),
                axes,
            },
        })
    };
    let of = BlobFormat::of::<f32>;
    assert_eq!(
        Path::<Q40, 2, 16>::from_bytes(&f32_blob).err(),
        mismatch(BlobFormat::of::<Q40>(2), 1, 2)
    );
    assert_eq!(
        Path::<f64, 2, 16>::from_bytes(&f32_blob).err(),
        mismatch(BlobFormat::of::<f64>(2), 1, 2)
    );
    // same value width (8 bytes), other format
    assert_eq!(
        Path::<Q40, 2, 16>::from_bytes(&f64_blob).err(),
        mismatch(BlobFormat::of::<Q40>(2), 2, 2)
    );
    assert_eq!(
        Path::<f64, 2, 16>::from_bytes(&q40_blob).err(),
        mismatch(BlobFormat::of::<f64>(2), 3, 2)
    );
    assert_eq!(
        Path::<f32, 2, 16>::from_bytes(&q40_blob).err(),
        mismatch(of(2), 3, 2)
    );
    // wrong axis count
    assert_eq!(
        Path::<f32, 3, 16>::from_bytes(&f32_blob).err(),
        mismatch(of(3), 1, 2)
    );
    assert_eq!(
        Path::<f32, 1, 16>::from_bytes(&f32_blob).err(),
        mismatch(of(1), 1, 2)
    );
    assert_eq!(
        Path::<Q40, 6, 16>::from_bytes(&q40_blob).err(),
        mismatch(BlobFormat::of::<Q40>(6), 3, 2)
    );
    // a format id that no format has
    let mut bad = f32_blob.clone();
    bad[6] = 9;
    fix_crc(&mut bad);
    let err = Path::<f32, 2, 16>::from_bytes(&bad).err();
    assert_eq!(err, Some(Error::UnknownNumberFormat { id: 9 }));
    assert_eq!(
        err.unwrap().to_string(),
        "serialized path has number format id 9, which no format has (1 f32, 2 f64, 3 Q40)"
    );
}

#[test]
fn errors_display() {
    for e in [
        Error::InvalidLimit,
        Error::InvalidRate,
        Error::EmptyPath,
        Error::AxisMismatch { curve: 2, path: 3 },
        Error::CapacityExceeded {
            capacity: 1,
            required: 2,
        },
        Error::OutOfRange,
        Error::TooLong,
        Error::CorruptBlob,
        Error::UnsupportedVersion { found: 7 },
        Error::UnknownNumberFormat { id: 0 },
        Error::FormatMismatch {
            expected: BlobFormat::of::<f32>(3),
            found: BlobFormat::of::<Q40>(3),
        },
        Error::Curve(strak_curves::Error::NonFinite),
    ] {
        assert!(!e.to_string().is_empty(), "{e:?}");
    }
}

// ---------------------------------------------------------------------------------------------
// Property tests: no panic, and every compiled path plays to its end
// ---------------------------------------------------------------------------------------------

/// A value from a mix of ordinary, tiny, huge and non-finite ones.
fn wild() -> impl Strategy<Value = f64> {
    prop_oneof![
        6 => -100.0_f64..100.0,
        1 => Just(0.0),
        1 => Just(NAN),
        1 => Just(INF),
        1 => Just(-INF),
        1 => prop_oneof![Just(1e-300), Just(-1e-300), Just(f64::MIN_POSITIVE), Just(5e-324)],
        1 => prop_oneof![Just(1e300), Just(-1e300), Just(f64::MAX), Just(9.0e6), Just(-4.2e6)],
        1 => (-30.0_f64..30.0).prop_map(|e| 10f64.powf(e)),
    ]
}

/// A limit from a mix (mostly positive).
fn wild_limit() -> impl Strategy<Value = f64> {
    prop_oneof![
        6 => (-1.0_f64..5.0).prop_map(|e| 10f64.powf(e)),
        1 => wild(),
    ]
}

/// `n` points of dimension `D`: mostly ordinary, sometimes with wild coordinates.
fn points<const D: usize>(n: std::ops::Range<usize>) -> impl Strategy<Value = Vec<[f64; D]>> {
    prop_oneof![
        3 => prop::collection::vec(prop::array::uniform::<_, D>(-100.0_f64..100.0), n.clone()),
        1 => prop::collection::vec(prop::array::uniform::<_, D>(wild()), n),
    ]
}

fn wild_rate() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => 100.0_f64..=5_000.0,
        1 => 5_000.0_f64..=100_000.0,
        1 => wild(),
        1 => prop_oneof![Just(99.999), Just(100.0), Just(100_000.0), Just(100_000.01)],
    ]
}

/// Plays a path to its end at feed 1 (exactly `ticks + 1` samples), and once more with an
/// override, a hold and a resume, and once with an abort; nothing may panic, every run ends.
fn play_everything<N: Kernel, const A: usize, const P: usize>(
    path: &Path<N, A, P>,
) -> TestCaseResult {
    let ticks = u64::from(path.ticks());
    let mut s = Sampler::new(path);
    let mut n = 0_u64;
    let mut last = None;
    while !s.is_finished() {
        last = Some(s.next());
        n += 1;
        prop_assert!(n <= ticks + 1, "more samples than ticks");
    }
    prop_assert_eq!(n, ticks + 1);
    prop_assert_eq!(last.map(|l| l.position), Some(path.end_position()));
    // with feed changes: the ramps are bounded (α ≥ 2⁻⁴⁰, ω ≤ 2²⁰ α), so it ends
    let limit = 4 * ticks + 50_000_000;
    let mut s = Sampler::new(path);
    let mut n = 0_u64;
    while !s.is_finished() {
        match n {
            3 => s.set_feed(0.3),
            9 => s.hold(),
            20 => s.resume(),
            25 => s.set_feed(1.0),
            _ => {}
        }
        s.next();
        n += 1;
        prop_assert!(n <= limit, "does not end with feed changes");
    }
    let mut s = Sampler::new(path);
    let mut n = 0_u64;
    while !s.is_finished() {
        if n == 2 {
            s.abort();
        }
        s.next();
        n += 1;
        prop_assert!(n <= limit, "does not end after an abort");
    }
    prop_assert_eq!(s.state(), SamplerState::Finished);
    Ok(())
}

/// What to plan.
#[derive(Clone, Copy, Debug)]
enum Law {
    Parameter(f64),
    ConstantSpeed(f64),
    Trapezoid(f64, f64),
    SCurve(f64, f64, f64),
    Custom(f64, f64, f64),
}

fn law() -> impl Strategy<Value = Law> {
    prop_oneof![
        wild_limit().prop_map(Law::Parameter),
        wild_limit().prop_map(Law::ConstantSpeed),
        (wild_limit(), wild_limit()).prop_map(|(v, a)| Law::Trapezoid(v, a)),
        (wild_limit(), wild_limit(), wild_limit()).prop_map(|(v, a, j)| Law::SCurve(v, a, j)),
        (wild_limit(), wild(), wild()).prop_map(|(d, u, du)| Law::Custom(d, u, du)),
    ]
}

/// A time law with arbitrary values: `u = off + t/d`, `du/dt = rate`.
struct Wild {
    d: f64,
    off: f64,
    rate: f64,
}

impl Timing for Wild {
    fn duration(&self) -> f64 {
        self.d
    }
    fn param(&self, t: f64) -> (f64, f64) {
        (self.off + t / self.d, self.rate)
    }
}

/// The seed of every property test of this file.
const SEED: u64 = 1;

thread_local! {
    /// Compile attempts and successes (any format) of a property test, to show that it is
    /// not vacuous.
    static ATTEMPTS: Cell<u64> = const { Cell::new(0) };
    static COMPILED: Cell<u64> = const { Cell::new(0) };
}

fn count(cell: &'static std::thread::LocalKey<Cell<u64>>, n: u64) {
    cell.with(|c| c.set(c.get() + n));
}

/// The longest path a property case compiles, in ticks. Compiling checks the fit at every
/// tick (about 0.2 µs each here), so the wild durations and rates (up to 10⁸ ticks and more)
/// would take a minute per case; longer paths are left to [`too_long`] and the fuzzers.
const MAX_TICKS: f64 = 4.0e6;

/// Compiles `timing` along `curve` in every format and plays what compiles.
fn compile_all<C, T, const A: usize>(
    curve: &C,
    timing: &T,
    rate: f64,
    o: &CompileOptions,
) -> TestCaseResult
where
    C: strak_curves::ParamCurveDeriv,
    T: Timing,
{
    if timing.duration() * rate > MAX_TICKS {
        return Ok(());
    }
    count(&ATTEMPTS, 3);
    if let Ok(path) = compile_within_bound::<f32, A, 512, _>(&Along::new(curve, timing), rate, o) {
        count(&COMPILED, 1);
        play_everything(&path)?;
    }
    if let Ok(path) = compile_within_bound::<f64, A, 512, _>(&Along::new(curve, timing), rate, o) {
        count(&COMPILED, 1);
        play_everything(&path)?;
    }
    if let Ok(path) = compile_within_bound::<Q40, A, 512, _>(&Along::new(curve, timing), rate, o) {
        count(&COMPILED, 1);
        play_everything(&path)?;
    }
    Ok(())
}

fn plan_and_compile<C, const A: usize>(
    curve: &C,
    law: Law,
    rate: f64,
    o: &CompileOptions,
) -> TestCaseResult
where
    C: strak_curves::ParamCurveDeriv,
{
    match law {
        Law::Parameter(d) => {
            if let Ok(t) = ParameterTiming::over(curve, d) {
                compile_all::<_, _, A>(curve, &t, rate, o)?;
            }
        }
        Law::ConstantSpeed(v) => {
            if let Ok(t) = PathTiming::<_, 32, 1>::constant_speed(curve, v) {
                compile_all::<_, _, A>(curve, &t, rate, o)?;
            }
        }
        Law::Trapezoid(v, a) => {
            if let Ok(t) = PathTiming::<_, 32, 1>::trapezoid(curve, v, a) {
                compile_all::<_, _, A>(curve, &t, rate, o)?;
            }
        }
        Law::SCurve(v, a, j) => {
            let Ok(limits) = Limits::<A>::new(v, a, j) else {
                return Ok(());
            };
            let limits = limits.with_axis_velocity([v * 0.7; A]).unwrap_or(limits);
            let options = PlanOptions::new().with_samples(64);
            if let Ok(t) = PathTiming::<_, 32, 64>::plan(curve, &limits, &options) {
                compile_all::<_, _, A>(curve, &t, rate, o)?;
            }
        }
        Law::Custom(d, off, du) => {
            let t = Wild { d, off, rate: du };
            compile_all::<_, _, A>(curve, &t, rate, o)?;
        }
    }
    Ok(())
}

fn options() -> impl Strategy<Value = CompileOptions> {
    (
        prop_oneof![
            3 => Just(CompileOptions::new()),
            1 => wild().prop_map(|t| CompileOptions::new().with_tolerance(t)),
            1 => wild().prop_map(|t| CompileOptions::new().with_relative_tolerance(t)),
        ],
        prop_oneof![3 => Just(256_u32), 1 => 0_u32..4, 1 => Just(u32::MAX)],
        prop_oneof![3 => Just(None), 1 => (wild_limit(), wild_limit()).prop_map(Some)],
        prop_oneof![3 => Just(0.25), 1 => wild()],
    )
        .prop_map(|(o, ticks, limits, share)| {
            let o = o.with_max_piece_ticks(ticks).with_feed_share(share);
            match limits {
                Some((a, j)) => o.with_limits(a, j),
                None => o,
            }
        })
}

/// Runs a property test on a fixed seed and asserts that at least a tenth of its compile
/// attempts succeeded. The seed is fixed because the share that succeeds varies widely from
/// seed to seed (8 % to 18 % in three random runs of the spline test): a random seed would
/// make that check fail at random. The coverage-guided fuzzers (`fuzz/`) explore further.
fn run_property(cases: u32, test: impl Fn(&mut TestRunner) -> Result<(), String> + Send + 'static) {
    let mut runner = TestRunner::new(Config {
        cases,
        failure_persistence: None,
        rng_seed: RngSeed::Fixed(SEED),
        ..Config::default()
    });
    if let Err(e) = test(&mut runner) {
        panic!("{e}");
    }
    let (attempts, compiled) = (ATTEMPTS.with(Cell::get), COMPILED.with(Cell::get));
    if attempts > 0 {
        println!("{compiled} of {attempts} compile attempts succeeded and played to the end");
    }
    assert!(
        attempts == 0 || compiled * 10 >= attempts,
        "mostly rejected: {compiled}/{attempts}"
    );
}

#[test]
fn arbitrary_input_never_panics_bezier() {
    run_property(160, |runner| {
        let strategy = (points::<3>(4..5), law(), wild_rate(), options());
        runner
            .run(&strategy, |(pts, law, rate, o)| {
                let pts: [[f64; 3]; 4] = [pts[0], pts[1], pts[2], pts[3]];
                if let Ok(curve) = Bezier::new(pts) {
                    plan_and_compile::<_, 3>(&curve, law, rate, &o)?;
                }
                Ok(())
            })
            .map_err(|e| e.to_string())
    });
}

#[test]
fn arbitrary_input_never_panics_spline_and_fixed_point() {
    run_property(96, |runner| {
        let strategy = (points::<2>(3..6), law(), wild_rate(), options());
        runner
            .run(&strategy, |(pts, law, rate, o)| {
                if let Ok(curve) = CubicSpline::<[f64; 2], 8>::new(
                    &pts,
                    Parameterization::ChordLength,
                    SplineBoundary::Natural,
                ) {
                    plan_and_compile::<_, 2>(&curve, law, rate, &o)?;
                }
                // the same points as a fixed-point Bézier, where they fit
                let fixed: Option<Vec<[I32F32; 2]>> = pts
                    .iter()
                    .map(|p| Some([I32F32::from_f64(p[0])?, I32F32::from_f64(p[1])?]))
                    .collect();
                if let Some(Ok(curve)) = fixed.map(|f| Bezier::new([f[0], f[1], f[2]])) {
                    plan_and_compile::<_, 2>(&curve, law, rate, &o)?;
                }
                Ok(())
            })
            .map_err(|e| e.to_string())
    });
}

/// Arbitrary bytes and arbitrary corruptions of a valid blob never make `from_bytes` panic;
/// whatever it accepts plays to its end.
#[test]
fn arbitrary_blobs_never_panic() {
    let good = blob(&small_path::<Q40, 2>());
    run_property(512, move |runner| {
        let g = good.clone();
        let strategy = (
            prop::collection::vec(any::<u8>(), 0..400),
            prop::collection::vec((0..g.len(), any::<u8>()), 0..6),
            any::<bool>(),
        );
        runner
            .run(&strategy, |(random, edits, fix)| {
                let _ = Path::<Q40, 2, 16>::from_bytes(&random);
                let _ = Path::<f32, 2, 16>::from_bytes(&random);
                let mut bad = g.clone();
                for (i, b) in edits {
                    bad[i] = b;
                }
                if fix {
                    fix_crc(&mut bad);
                }
                if let Ok(path) = Path::<Q40, 2, 16>::from_bytes(&bad) {
                    play_everything(&path)?;
                }
                Ok(())
            })
            .map_err(|e| e.to_string())
    });
}
