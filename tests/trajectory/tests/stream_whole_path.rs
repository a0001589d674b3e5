//! A whole curve planned and compiled into a path by the stream ([`plan_path_into`]):
//! limits from the samples, the exact end, the same motion the stream plays, against the
//! whole-path planner ([`PathTiming::plan`]) on the same curves.

use strak_curves::heapless::Deque;
use strak_curves::{BSpline, Nurbs, ParamCurve, PieceDeriv, Scalar};
use strak_trajectory::{
    Error, Kernel, Limits, Move, Path, PathBlob, PathTiming, Piece, PlanOptions, Q40, Sampler,
    Stream, StreamOptions, plan_path_into,
};
use strak_trajectory_tests::compile_boxed;
use strak_trajectory_tests::limits_check::measure;

type AnyCurve<'a> = &'a dyn PieceDeriv<Point = [f64; 3]>;

/// The machine: v 200 units/s, a 3000 units/s², j 100 000 units/s³.
fn machine() -> Limits<3> {
    Limits::new(200.0, 3000.0, 100_000.0).unwrap()
}

/// Curves of strak-curves: a cubic B-spline wave of five pieces, a rational quarter circle
/// of radius 10, a cubic B-spline with a kink (an inner knot of multiplicity 3), and a
/// clamped cubic B-spline bump whose planned motion's arc length falls short of its end by
/// rounding (evaluated there, it misses its end point by about 10⁻¹⁴).
struct Curves {
    wave: BSpline<[f64; 3], 8, 12>,
    quarter: Nurbs<[f64; 3], 3, 6>,
    kinked: BSpline<[f64; 3], 7, 11>,
    bump: BSpline<[f64; 3], 5, 9>,
}

impl Curves {
    fn new() -> Self {
        let w = core::f64::consts::FRAC_1_SQRT_2;
        let wave = [
            [0.0, 0.0, 0.0],
            [6.0, 0.0, 0.0],
            [10.0, 8.0, 1.0],
            [16.0, -6.0, 2.0],
            [22.0, 8.0, 2.0],
            [28.0, -4.0, 1.0],
            [34.0, 0.0, 0.0],
            [40.0, 0.0, 0.0],
        ];
        let quarter = [[0.0, 0.0, 0.0], [10.0, 0.0, 0.0], [10.0, 10.0, 0.0]];
        let kinked = [
            [0.0, 0.0, 0.0],
            [-3.0, -8.0, 0.0],
            [-5.0, -12.0, 0.0],
            [-7.0, -16.0, 0.0],
            [-15.0, -16.0, 0.0],
            [-21.0, -18.0, 0.0],
            [-25.0, -20.0, 0.0],
        ];
        let bump = [
            [0.0, 0.0, 0.0],
            [20.0, 0.0, 0.0],
            [20.0, 20.0, 0.0],
            [40.0, 20.0, 0.0],
            [40.0, 0.0, 0.0],
        ];
        let uniform = [0., 0., 0., 0., 1., 2., 3., 4., 5., 5., 5., 5.];
        Curves {
            wave: BSpline::new(3, &wave, &uniform).unwrap(),
            quarter: Nurbs::new(2, &quarter, &[1.0, w, 1.0], &[0., 0., 0., 1., 1., 1.]).unwrap(),
            kinked: BSpline::new(3, &kinked, &[0., 0., 0., 0., 1., 1., 1., 2., 2., 2., 2.])
                .unwrap(),
            bump: BSpline::clamped_uniform(3, &bump, 0.0, 1.0).unwrap(),
        }
    }

    fn all(&self) -> [(&'static str, AnyCurve<'_>); 4] {
        [
            ("wave", &self.wave),
            ("quarter", &self.quarter),
            ("kinked", &self.kinked),
            ("bump", &self.bump),
        ]
    }
}

type WholeStream<'a> = Stream<3, 8, 64, AnyCurve<'a>>;

/// `curve` planned through a stream of 8 segments and 64 zones into a path in `N`.
fn streamed<N: Kernel>(curve: AnyCurve<'_>) -> Result<Box<Path<N, 3, 1024>>, Error> {
    let mut stream = Box::new(WholeStream::unset());
    let mut path = Box::new(Path::new());
    let options = StreamOptions::new(1000.0);
    plan_path_into(curve, machine(), options, &mut stream, &mut path)?;
    Ok(path)
}

/// The limits the stream promises for `machine`: the acceleration and jerk less the
/// default feed share.
fn promised() -> (f64, f64, f64) {
    let keep = 1.0 - PlanOptions::DEFAULT_FEED_SHARE;
    (200.0, keep * 3000.0, keep * 100_000.0)
}

/// Each curve planned through the stream into a path, in `f64`, `f32` and `Q40`: its samples
/// keep the limits the stream promises (from finite differences, with the playback
/// allowance of `limits_check`), the last sample is the curve's end exactly and at rest,
/// and the motion takes at most 5 % longer than the whole-path planner's on the same curve
/// (the stream plans in a window of 8 segments and 64 zones).
#[test]
fn whole_curves_plan_through_the_stream_within_the_limits() {
    fn check<N: Kernel>(name: &str, curve: AnyCurve<'_>) {
        let path = streamed::<N>(curve).unwrap();
        let (v, a, j) = promised();
        let measured = measure(&*path);
        let ratios = measured
            .check(v, a, j)
            .unwrap_or_else(|e| panic!("{name} {}: {e}", N::NAME));
        let end = curve.eval(curve.domain().1);
        assert_eq!(
            path.end_position().map(Scalar::to_f64),
            end.map(|x| { N::out_from_f64(x).unwrap().to_f64() })
        );
        let mut sampler = Sampler::new(&*path);
        let mut last = sampler.next();
        while !sampler.is_finished() {
            last = sampler.next();
        }
        assert_eq!(last.position, path.end_position(), "{name} {}", N::NAME);
        assert!(last.velocity.iter().all(|x| x.to_f64() == 0.0));
        let plan =
            PathTiming::<_, 256, 512>::plan(&curve, &machine(), &PlanOptions::new()).unwrap();
        let whole: Box<Path<N, 3, 1024>> =
            compile_boxed(&plan, 1000.0, &Default::default()).unwrap();
        let ratio = path.duration() / whole.duration();
        println!(
            "{name} {}: {} ticks in {} pieces (whole-path plan: {} ticks in {} pieces, x{ratio:.3}); {ratios:?}",
            N::NAME,
            path.ticks(),
            path.pieces().len(),
            whole.ticks(),
            whole.pieces().len(),
        );
        assert!(ratio <= 1.05, "{name} {}: {ratio}", N::NAME);
    }
    let curves = Curves::new();
    for (name, curve) in curves.all() {
        check::<f64>(name, curve);
        check::<f32>(name, curve);
        check::<Q40>(name, curve);
    }
}

/// A window of two segments and two zones holds less than the braking distance from the
/// speed the curve allows: the motion is slower than with the wide window, and keeps the
/// limits.
#[test]
fn a_narrow_window_plans_slower_within_the_limits() {
    let curves = Curves::new();
    let curve: AnyCurve<'_> = &curves.wave;
    let wide = streamed::<f64>(curve).unwrap();
    let mut narrow = Box::new(Stream::<3, 2, 2, AnyCurve<'_>>::unset());
    let mut path = Box::new(Path::<f64, 3, 1024>::new());
    let options = StreamOptions::new(1000.0);
    plan_path_into(curve, machine(), options, &mut narrow, &mut path).unwrap();
    let (v, a, j) = promised();
    measure(&*path).check(v, a, j).unwrap();
    println!(
        "narrow window: {} ticks, wide: {}",
        path.ticks(),
        wide.ticks()
    );
    assert!(f64::from(path.ticks()) > 1.2 * f64::from(wide.ticks()));
    assert_eq!(path.end_position(), wide.end_position());
}

/// The path ends exactly on the curve's end, under any limits: the stream rests at the end
/// of its last segment, not where the rounded arc length of its motion evaluates the curve.
#[test]
fn a_planned_path_ends_exactly_on_the_curve_end() {
    let points = [
        [0.0, 0.0],
        [20.0, 0.0],
        [20.0, 20.0],
        [40.0, 20.0],
        [40.0, 0.0],
    ];
    let bump = BSpline::<[f64; 2], 5, 9>::clamped_uniform(3, &points, 0.0, 1.0).unwrap();
    let end = bump.eval(1.0);
    let mut stream = Box::new(Stream::<2, 8, 64, &BSpline<[f64; 2], 5, 9>>::unset());
    let mut path = Box::new(Path::<f64, 2, 1024>::new());
    for v in [60.0, 100.0, 150.0, 200.0] {
        for (a, j) in [(1_000.0, 20_000.0), (3_000.0, 100_000.0)] {
            let limits = Limits::new(v, a, j).unwrap();
            let options = StreamOptions::new(1000.0);
            plan_path_into(&bump, limits, options, &mut stream, &mut path).unwrap();
            let mut sampler = Sampler::new(&*path);
            let mut last = sampler.next();
            while !sampler.is_finished() {
                last = sampler.next();
            }
            assert_eq!((last.position, path.end_position()), (end, end), "{v} {a}");
            assert_eq!(stream.position(), Ok(end));
        }
    }
}

/// The path holds the pieces the stream compiles when the same curve is streamed to a
/// sampler, bit for bit, but the stream's last piece (one tick at rest on the end, which is
/// the path's end sample).
#[test]
fn a_planned_path_is_the_motion_the_stream_plays() {
    fn check<N: Kernel>(curve: AnyCurve<'_>) {
        let path = streamed::<N>(curve).unwrap();
        let mut stream = Box::new(WholeStream::unset());
        let start = curve.eval(curve.domain().0);
        stream
            .reset(start, machine(), StreamOptions::new(1000.0))
            .unwrap();
        stream.push(&Move::curve(curve)).unwrap();
        let mut queue = Deque::<Piece<N, 3>, 64>::new();
        let (mut pieces, mut finished) = (Vec::new(), false);
        while !(finished && stream.is_idle()) {
            finished = finished || stream.finish().is_ok();
            stream.poll(&mut queue).unwrap();
            pieces.extend(queue.iter().copied());
            queue.clear();
        }
        let rest = pieces.pop().unwrap();
        assert_eq!((rest.start(), rest.ticks()), (path.ticks(), 1));
        assert_eq!(pieces.as_slice(), path.pieces(), "{}", N::NAME);
    }
    let curves = Curves::new();
    for (_, curve) in curves.all() {
        check::<f64>(curve);
        check::<f32>(curve);
        check::<Q40>(curve);
    }
}

/// The path serves as any path: it survives a round trip through its blob, and played
/// with a feed override, a hold and a resume its samples keep the machine's limits (the
/// feed ramps use the share the plan keeps free) and it ends on the curve's end.
#[test]
fn a_planned_path_round_trips_as_a_blob_and_takes_feed_changes() {
    let curves = Curves::new();
    let path = streamed::<f32>(&curves.kinked).unwrap();
    let mut bytes = vec![0_u8; path.blob_len()];
    path.to_bytes(&mut bytes).unwrap();
    let back = Path::<f32, 3, 1024>::from_bytes(&bytes).unwrap();
    assert_eq!(back, *path);
    let blob = PathBlob::<f32, 3>::from_bytes(&bytes).unwrap();
    assert_eq!(blob.ticks(), path.ticks());

    let mut sampler = Sampler::new(&*path);
    let mut samples = Vec::new();
    for tick in 0..100_000 {
        match tick {
            100 => sampler.set_feed(0.4),
            250 => sampler.hold(),
            500 => sampler.resume(),
            700 => sampler.set_feed(1.0),
            _ => {}
        }
        samples.push(sampler.next());
        if sampler.is_finished() {
            break;
        }
    }
    assert!(sampler.is_finished());
    assert!(
        samples.len() > path.ticks() as usize + 400,
        "{}",
        samples.len()
    );
    let held = samples
        .windows(2)
        .filter(|w| w[0].velocity == [0.0; 3] && w[1].velocity == [0.0; 3])
        .count();
    assert!(held > 100, "{held}");
    let (mut a_peak, mut j_peak) = (0.0_f64, 0.0_f64);
    for w in samples.windows(2) {
        let acc = |s: &strak_trajectory::Sample<f32, 3>| s.acceleration.map(f64::from);
        a_peak = a_peak.max(norm(acc(&w[1])));
        j_peak = j_peak.max(norm(sub(acc(&w[1]), acc(&w[0]))) * 1000.0);
    }
    println!("under feed changes: a {a_peak:.1}, j {j_peak:.0}");
    assert!(a_peak <= 3000.0 * (1.0 + 1e-4) && j_peak <= 100_000.0 * (1.0 + 1e-3));
    assert_eq!(samples.last().unwrap().position, path.end_position());
}

fn norm(x: [f64; 3]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>().sqrt()
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    core::array::from_fn(|i| a[i] - b[i])
}

/// A path too small for the pieces, a stream of one segment (a curve move is cut into
/// segments of at least two) and invalid options are errors, and the path is left empty.
#[test]
fn a_path_or_window_too_small_is_an_error() {
    let curves = Curves::new();
    let curve: AnyCurve<'_> = &curves.wave;
    let options = StreamOptions::new(1000.0);
    let mut stream = Box::new(WholeStream::unset());
    let mut small = Box::new(Path::<f64, 3, 64>::new());
    let r = plan_path_into(curve, machine(), options, &mut stream, &mut small);
    assert!(
        matches!(r, Err(Error::CapacityExceeded { capacity: 64, required }) if required > 64),
        "{r:?}"
    );
    assert_eq!((small.ticks(), small.pieces().len()), (0, 0));

    let mut path = Box::new(Path::<f64, 3, 1024>::new());
    let mut single = Box::new(Stream::<3, 1, 8, AnyCurve<'_>>::unset());
    let r = plan_path_into(curve, machine(), options, &mut single, &mut path);
    assert_eq!(
        r,
        Err(Error::CapacityExceeded {
            capacity: 1,
            required: 2
        })
    );
    assert_eq!((path.ticks(), path.pieces().len()), (0, 0));

    let bad = options.with_fit_tolerance(0.0);
    let r = plan_path_into(curve, machine(), bad, &mut stream, &mut path);
    assert_eq!(r, Err(Error::InvalidLimit));
    assert_eq!((path.ticks(), path.pieces().len()), (0, 0));
}
