//! Streams of moves: the moves' curves and the corner blends, checked from dense samples of
//! the programmed path (not from the blend's own bound).

use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};
use strak_curves::Scalar;
use strak_curves::heapless::Deque;
use strak_curves::heapless::spsc::Queue;
use strak_curves::{BSpline, Nurbs, ParamCurve, ParamCurveDeriv, PieceDeriv, Plane, Point, Turn};
use strak_trajectory::{
    Along, AxisState, CompileOptions, Error, Junction, Kernel, Limits, Move, MoveCurve, Number,
    Path, PathTiming, Piece, PlanOptions, Q40, REVERSAL_ANGLE, Sample, Sampler, Shape, Stream,
    StreamCurve, StreamOptions, StreamSampler, StreamStats, Stretches, Timing, Toolpath, junction,
};
use strak_trajectory_tests::compile_boxed;

/// Samples of each curve for the distance checks.
const CURVE_SAMPLES: usize = 400;
/// The relative allowance of the sampled distances: their bound of the polygons' departure
/// from the curves (a two-line blend passes the corner at exactly the tolerance).
const SAMPLING: f64 = 1e-6;

/// The distance of `p` from the segment `a`–`b`.
fn segment_distance<const D: usize>(p: [f64; D], a: [f64; D], b: [f64; D]) -> f64 {
    let ab = b.minus(a);
    let len2 = ab.dot(ab);
    let t = if len2 > 0.0 {
        (p.minus(a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.minus(a.plus(ab.times(t))).norm()
}

/// A part of a curve as the polygon of its samples, with the polygon's largest departure
/// from the curve (`M₂·h²/8` for the parameter step `h`; de Boor, *A Practical Guide to
/// Splines*, ch. 2): a point's distance from the polygon plus that departure bounds its
/// distance from the curve from above, independent of the blend's own bound. Searching a
/// part of the curve only makes the distance larger, so a check against it is stricter.
struct Polygon<const D: usize> {
    points: Vec<[f64; D]>,
    sag: f64,
}

impl<const D: usize> Polygon<D> {
    fn new<C: ParamCurveDeriv<Point = [f64; D]>>(
        curve: &C,
        (u0, u1): (f64, f64),
        m2: f64,
        n: usize,
    ) -> Self {
        let h = (u1 - u0) / n as f64;
        let points = (0..=n).map(|i| curve.eval(u0 + i as f64 * h)).collect();
        Polygon {
            points,
            sag: m2 * h * h / 8.0,
        }
    }

    fn distance(&self, p: [f64; D]) -> f64 {
        let chords = self
            .points
            .windows(2)
            .map(|w| segment_distance(p, w[0], w[1]));
        chords.fold(f64::INFINITY, f64::min) + self.sag
    }
}

/// The largest distance of the blend from the programmed path (both moves, within twice the
/// trim of the corner), and the distance of the junction from the blend: upper bounds from
/// samples.
fn measured_deviation<const D: usize>(
    blend: &strak_trajectory::Blend<D>,
    a: &MoveCurve<D>,
    b: &MoveCurve<D>,
) -> (f64, f64) {
    let near_a = Polygon::new(
        a,
        ((2.0 * blend.leave() - 1.0).max(0.0), 1.0),
        a.second_derivative_bound(),
        CURVE_SAMPLES,
    );
    let near_b = Polygon::new(
        b,
        (0.0, (2.0 * blend.join()).min(1.0)),
        b.second_derivative_bound(),
        CURVE_SAMPLES,
    );
    let p = blend.curve().control_points();
    let second = (0..4).map(|i| p[i + 2].minus(p[i + 1].times(2.0)).plus(p[i]).norm());
    let blend_m2 = 20.0 * second.fold(0.0, f64::max);
    let curve = Polygon::new(blend.curve(), (0.0, 1.0), blend_m2, CURVE_SAMPLES);
    let out = curve
        .points
        .iter()
        .map(|&q| near_a.distance(q).min(near_b.distance(q)));
    let fine = Polygon::new(blend.curve(), (0.0, 1.0), blend_m2, 100 * CURVE_SAMPLES);
    (out.fold(0.0, f64::max), fine.distance(a.eval(1.0)))
}

fn line<const D: usize>(from: [f64; D], to: [f64; D]) -> MoveCurve<D> {
    MoveCurve::new(from, &Move::line(to), 0.0).unwrap()
}

fn blended<const D: usize>(
    a: &MoveCurve<D>,
    b: &MoveCurve<D>,
    tol: f64,
) -> strak_trajectory::Blend<D> {
    match junction(a, b, tol).unwrap() {
        Junction::Blend(blend) => blend,
        other => panic!("expected a blend, got {other:?}"),
    }
}

/// The unit tangent and curvature vector of a curve at `u`, from its derivatives.
fn frame<C: ParamCurveDeriv<Point = [f64; D]>, const D: usize>(
    c: &C,
    u: f64,
) -> ([f64; D], [f64; D]) {
    let (d1, d2) = (c.deriv(u, 1), c.deriv(u, 2));
    let s = d1.norm();
    let t = d1.times(1.0 / s);
    (t, d2.minus(t.times(d2.dot(t))).times(1.0 / (s * s)))
}

/// Position, tangent and curvature of the blend agree with the moves where it leaves and
/// joins them.
fn assert_g2<const D: usize>(
    blend: &strak_trajectory::Blend<D>,
    a: &MoveCurve<D>,
    b: &MoveCurve<D>,
) {
    let c = blend.curve();
    for (u_blend, curve, u) in [(0.0, a, blend.leave()), (1.0, b, blend.join())] {
        assert_eq!(
            c.eval(u_blend),
            curve.eval(u),
            "the blend starts and ends on the moves"
        );
        let (t0, k0) = frame(c, u_blend);
        let (t1, k1) = frame(curve, u);
        assert!(t0.minus(t1).norm() < 1e-12, "tangent {t0:?} vs {t1:?}");
        let scale = k1.norm().max(1.0 / blend.trim());
        assert!(
            k0.minus(k1).norm() < 1e-9 * scale,
            "curvature {k0:?} vs {k1:?}"
        );
    }
}

#[test]
fn line_corners_meet_the_tolerance_at_the_corner() {
    let tol = 0.02;
    for degrees in [1.0, 5.0, 30.0, 60.0, 90.0, 120.0, 135.0, 160.0, 169.0] {
        let phi = f64::to_radians(degrees);
        let a = line([0.0, 0.0, 0.0], [10.0, 0.0, 0.0]);
        let b = line(
            [10.0, 0.0, 0.0],
            [10.0 + 10.0 * phi.cos(), 10.0 * phi.sin(), 0.0],
        );
        let blend = blended(&a, &b, tol);
        assert_g2(&blend, &a, &b);
        let (out, corner_gap) = measured_deviation(&blend, &a, &b);
        assert!(out <= tol * (1.0 + SAMPLING), "{degrees}°: deviation {out}");
        assert!(blend.deviation() <= tol);
        if blend.trim() < 5.0 {
            // not shortened by half a move: the corner is exactly the tolerance from the blend
            assert!(
                (corner_gap - tol).abs() < 1e-6 * tol,
                "{degrees}°: corner {corner_gap}"
            );
        } else {
            assert!(corner_gap <= tol * (1.0 + SAMPLING));
        }
    }
}

#[test]
fn blends_take_at_most_half_a_move() {
    let a = line([0.0, 0.0], [0.1, 0.0]);
    let b = line([0.1, 0.0], [0.1, 0.05]);
    for tol in [1e-4, 1e-3, 0.01, 1.0] {
        let blend = blended(&a, &b, tol);
        assert!(blend.trim() <= 0.025 + 1e-15, "{tol}: {}", blend.trim());
        assert!(blend.deviation() <= tol);
        assert_g2(&blend, &a, &b);
        let (out, _) = measured_deviation(&blend, &a, &b);
        assert!(out <= blend.deviation() * (1.0 + SAMPLING));
    }
}

#[test]
fn exact_stops_and_straight_joins() {
    let a = line([0.0, 0.0], [1.0, 0.0]);
    let right = line([1.0, 0.0], [1.0, 1.0]);
    assert_eq!(junction(&a, &right, 0.0).unwrap(), Junction::Stop);
    let on = line([1.0, 0.0], [3.0, 0.0]);
    assert_eq!(junction(&a, &on, 0.1).unwrap(), Junction::Straight);
    for degrees in [171.0, 179.0, 180.0] {
        let phi = f64::to_radians(degrees);
        let back = line([1.0, 0.0], [1.0 + phi.cos(), phi.sin()]);
        assert_eq!(
            junction(&a, &back, 0.1).unwrap(),
            Junction::Stop,
            "{degrees}°"
        );
    }
    assert!(REVERSAL_ANGLE < f64::to_radians(171.0));
    // an arc going on along the same circle
    let arc = |from: [f64; 2], to: [f64; 2]| {
        let shape = Shape::<2>::ArcCenter {
            center: [0.0, 0.0],
            plane: Plane::XY,
            turn: Turn::CounterClockwise,
        };
        MoveCurve::new(from, &Move::new(to, shape), 1e-12).unwrap()
    };
    let (p, q, r) = ([1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]);
    assert_eq!(
        junction(&arc(p, q), &arc(q, r), 0.01).unwrap(),
        Junction::Straight
    );
}

#[test]
fn bad_junctions_are_errors() {
    let a = line([0.0, 0.0], [1.0, 0.0]);
    let b = line([1.0, 0.0], [1.0, 1.0]);
    let apart = line([1.0, 0.1], [1.0, 1.0]);
    assert_eq!(junction(&a, &apart, 0.1), Err(Error::DegenerateMove));
    for tol in [-0.1, f64::NAN, f64::INFINITY] {
        assert_eq!(junction(&a, &b, tol), Err(Error::InvalidTolerance));
    }
    assert_eq!(
        MoveCurve::new([0.0, 0.0], &Move::<2>::line([0.0, 0.0]), 0.0),
        Err(Error::DegenerateMove)
    );
    let cusp = Move::<2>::new(
        [1.0, 0.0],
        Shape::Bezier {
            c1: [0.5, 1.0],
            c2: [1.0, 0.0],
        },
    );
    assert_eq!(
        MoveCurve::new([0.0, 0.0], &cusp, 0.0),
        Err(Error::DegenerateMove)
    );
    let bad_feed = Move::<2>::line([1.0, 0.0]).with_feed(0.0);
    assert_eq!(
        MoveCurve::new([0.0, 0.0], &bad_feed, 0.0),
        Err(Error::InvalidLimit)
    );
    let nan = Move::<2>::line([f64::NAN, 0.0]);
    assert!(matches!(
        MoveCurve::new([0.0, 0.0], &nan, 0.0),
        Err(Error::Curve(_))
    ));
}

/// The largest `|dκ/ds|·ε²` and `κ·ε` of a line-corner blend, from the blend's derivatives.
fn curvature_profile(degrees: f64, tol: f64) -> (f64, f64) {
    let phi = f64::to_radians(degrees);
    let a = line([0.0, 0.0], [100.0, 0.0]);
    let b = line([100.0, 0.0], [100.0 + 100.0 * phi.cos(), 100.0 * phi.sin()]);
    let blend = blended(&a, &b, tol);
    let c = blend.curve();
    let kappa = |u: f64| {
        let (d1, d2) = (c.deriv(u, 1), c.deriv(u, 2));
        (d1[0] * d2[1] - d1[1] * d2[0]) / d1.norm().powi(3)
    };
    let n = 4000;
    let (mut dk, mut k) = (0.0_f64, 0.0_f64);
    for i in 0..n {
        let (u0, u1) = (i as f64 / n as f64, (i + 1) as f64 / n as f64);
        let ds = c.eval(u1).minus(c.eval(u0)).norm();
        dk = dk.max((kappa(u1) - kappa(u0)).abs() / ds);
        k = k.max(kappa(u0).abs());
    }
    (dk * tol * tol, k * tol)
}

/// The curvature of line-corner blends grows with the turn, and at a right angle the blend's
/// legs (`a = 0.4·L`, `b = 0.325·L`) give the curvature derivative the module docs state:
/// `|dκ/ds|·ε² ≈ 0.22` and `κ·ε ≈ 0.505`. Printed with `--nocapture`.
#[test]
fn curvature_of_line_blends() {
    let mut last = (0.0, 0.0);
    for degrees in [5.0, 30.0, 60.0, 90.0, 120.0, 150.0, 170.0] {
        let (dk, k) = curvature_profile(degrees, 0.02);
        println!("{degrees:5}°  dκ/ds·ε² = {dk:10.4}  κ·ε = {k:8.4}");
        assert!(dk > last.0 && k > last.1, "{degrees}°");
        last = (dk, k);
        if degrees == 90.0 {
            assert!(
                (0.20..0.24).contains(&dk) && (0.49..0.52).contains(&k),
                "{dk} {k}"
            );
        }
    }
}

/// A move from `from` of the kind `kind` (0 line, 1 arc about a centre, with a helical rise,
/// 2 arc of a radius, 3 Bézier), shaped by the values `x` in `[0, 1)`.
fn random_move(from: [f64; 3], kind: u8, x: &[f64; 10]) -> Move<3> {
    let r = |i: usize, lo: f64, hi: f64| lo + (hi - lo) * x[i];
    let near = |i: usize| {
        [
            from[0] + r(i, -6.0, 6.0),
            from[1] + r(i + 1, -6.0, 6.0),
            from[2] + r(i + 2, -2.0, 2.0),
        ]
    };
    let turn = if x[9] < 0.5 {
        Turn::Clockwise
    } else {
        Turn::CounterClockwise
    };
    match kind {
        0 => Move::line(near(0)),
        1 => {
            let center = [from[0] + r(0, -5.0, 5.0), from[1] + r(1, -5.0, 5.0)];
            let radius = (from[0] - center[0]).hypot(from[1] - center[1]);
            let angle = r(3, -3.0, 3.0);
            let to = [
                center[0] + radius * angle.cos(),
                center[1] + radius * angle.sin(),
                from[2] + r(2, -2.0, 2.0),
            ];
            Move::new(
                to,
                Shape::ArcCenter {
                    center,
                    plane: Plane::XY,
                    turn,
                },
            )
        }
        2 => {
            let to = [
                from[0] + r(0, -6.0, 6.0),
                from[1] + r(1, -6.0, 6.0),
                from[2],
            ];
            let chord = (to[0] - from[0]).hypot(to[1] - from[1]);
            let radius = chord / 2.0 * r(3, 1.0, 4.0) * if x[4] < 0.5 { -1.0 } else { 1.0 };
            Move::new(
                to,
                Shape::ArcRadius {
                    radius,
                    plane: Plane::XY,
                    turn,
                },
            )
        }
        _ => Move::new(
            near(6),
            Shape::Bezier {
                c1: near(0),
                c2: near(3),
            },
        ),
    }
}

/// Checks the junction of two random moves: a blend is G² with both, takes at most half
/// of each, stays within the tolerance of the programmed path (from samples), and passes
/// the corner within it.
fn check_random_junction(
    kinds: (u8, u8),
    x: &[f64; 10],
    y: &[f64; 10],
    tol: f64,
) -> Result<bool, TestCaseError> {
    let start = [0.0, 0.0, 0.0];
    let Ok(a) = MoveCurve::new(start, &random_move(start, kinds.0, x), 1e-9) else {
        return Ok(false);
    };
    let corner = a.eval(1.0);
    let Ok(b) = MoveCurve::new(corner, &random_move(corner, kinds.1, y), 1e-9) else {
        return Ok(false);
    };
    let Junction::Blend(blend) = junction(&a, &b, tol).unwrap() else {
        return Ok(false);
    };
    assert_g2(&blend, &a, &b);
    prop_assert!(blend.trim() <= a.length() / 2.0 * (1.0 + 1e-12));
    prop_assert!(blend.trim() <= b.length() / 2.0 * (1.0 + 1e-12));
    prop_assert!(blend.deviation() <= tol);
    let (out, corner_gap) = measured_deviation(&blend, &a, &b);
    prop_assert!(out <= tol * (1.0 + SAMPLING), "deviation {out} > {tol}");
    prop_assert!(
        corner_gap <= tol * (1.0 + SAMPLING),
        "corner {corner_gap} > {tol}"
    );
    Ok(true)
}

fn unit10() -> impl Strategy<Value = [f64; 10]> {
    prop::array::uniform10(0.0..1.0_f64)
}

/// 300 random junctions of every pair of move kinds (random seeds per run; a failure is
/// reported with its inputs); at least two thirds of them are blends that get checked.
#[test]
fn random_junctions_blend_within_the_tolerance() {
    let checked = std::sync::atomic::AtomicUsize::new(0);
    let mut runner = TestRunner::new(Config {
        cases: 300,
        failure_persistence: None,
        ..Config::default()
    });
    let cases = ((0_u8..4, 0_u8..4), unit10(), unit10(), 1e-3..0.5_f64);
    let result = runner.run(&cases, |(kinds, x, y, tol)| {
        if check_random_junction(kinds, &x, &y, tol)? {
            checked.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        }
        Ok(())
    });
    if let Err(e) = result {
        panic!("{e}");
    }
    let checked = checked.into_inner();
    println!("{checked} of 300 random junctions were blends");
    assert!(
        checked >= 200,
        "only {checked} of 300 junctions were blends"
    );
}

#[test]
fn tangent_line_to_arc_is_blended_for_the_curvature_step() {
    // a line along +x into a counter-clockwise circle of radius 2 touching it
    let a = line([0.0, 0.0, 0.0], [5.0, 0.0, 0.0]);
    let arc = Move::new(
        [7.0, 2.0, 0.0],
        Shape::ArcCenter {
            center: [5.0, 2.0],
            plane: Plane::XY,
            turn: Turn::CounterClockwise,
        },
    );
    let b = MoveCurve::new([5.0, 0.0, 0.0], &arc, 1e-12).unwrap();
    for tol in [1e-3, 0.01, 0.1] {
        let blend = blended(&a, &b, tol);
        assert_g2(&blend, &a, &b);
        let (out, _) = measured_deviation(&blend, &a, &b);
        assert!(out <= tol && blend.deviation() <= tol, "{tol}: {out}");
        // the curvature step is spread over a length that grows as √ε
        assert!(
            blend.trim() > (tol * 2.0_f64).sqrt(),
            "{tol}: trim {}",
            blend.trim()
        );
    }
}

/// A toolpath of lines (corners of 5° to 150° and a reversal), a line into a tangent arc, a
/// helix and a Bézier, blended within 0.05, planned with the S-curve, compiled and played in
/// `f64`: every sample lies within the tolerance (plus the compile tolerance) of the
/// programmed moves, and the motion ends exactly at the last move's end.
#[test]
fn played_toolpath_stays_within_the_tolerance() {
    let tol = 0.05;
    let mut moves = vec![
        Move::line([20.0, 0.0, 0.0]),
        Move::line([40.0, 1.75, 0.0]), // 5°
        Move::line([50.0, 20.0, 0.0]), // about 56°
        Move::line([30.0, 10.0, 0.0]), // about 145°
        Move::line([50.0, 20.0, 0.0]), // a reversal: an exact stop
        Move::line([70.0, 20.0, 0.0]),
    ];
    let ccw = Shape::ArcCenter {
        center: [70.0, 30.0],
        plane: Plane::XY,
        turn: Turn::CounterClockwise,
    };
    moves.push(Move::new([80.0, 30.0, 5.0], ccw)); // tangent: only the curvature steps
    moves.push(Move::line([80.0, 50.0, 5.0]));
    moves.push(Move::new(
        [60.0, 60.0, 0.0],
        Shape::Bezier {
            c1: [80.0, 60.0, 5.0],
            c2: [70.0, 65.0, 0.0],
        },
    ));
    let start = [0.0, 0.0, 0.0];
    let path = Toolpath::<3, 16>::new(start, &moves, tol, 1e-9).unwrap();
    assert_eq!(
        path.junctions()
            .iter()
            .filter(|j| **j == Junction::Stop)
            .count(),
        1
    );
    assert_eq!(path.blends(), moves.len() - 2);
    let limits = Limits::<3>::new(200.0, 3000.0, 100_000.0).unwrap();
    let plan = PathTiming::<_, 1024, 1024>::plan(&path, &limits, &PlanOptions::new()).unwrap();
    let compile_tol = 1e-4;
    let options = CompileOptions::new()
        .with_tolerance(compile_tol)
        .with_path_limits(&limits);
    let played: Box<Path<f64, 3, 4096>> =
        compile_boxed(&Along::new(&path, &plan), 1000.0, &options).unwrap();
    let programmed: Vec<Polygon<3>> = path
        .moves()
        .iter()
        .map(|m| {
            Polygon::new(
                m,
                (0.0, 1.0),
                m.second_derivative_bound(),
                4 * CURVE_SAMPLES,
            )
        })
        .collect();
    let mut sampler = Sampler::new(&*played);
    let mut worst = 0.0_f64;
    loop {
        let x = sampler.next().position;
        let d = programmed
            .iter()
            .map(|p| p.distance(x))
            .fold(f64::INFINITY, f64::min);
        worst = worst.max(d);
        if sampler.is_finished() {
            assert_eq!(
                x,
                moves.last().unwrap().to,
                "the motion ends on the last move's end"
            );
            break;
        }
    }
    println!(
        "largest distance from the programmed moves {worst:.6} (tolerance {tol}), {:.3} s",
        played.duration()
    );
    assert!(
        worst <= tol + compile_tol + played.playback_bound(),
        "{worst}"
    );
    // the blends are used: the motion cuts corners by a good share of the tolerance
    assert!(worst > tol / 4.0, "{worst}");
}

/// The blended toolpath of `played_toolpath_stays_within_the_tolerance`, planned with the
/// S-curve at 1 kHz.
fn contour() -> (Toolpath<3, 16>, Limits<3>) {
    let ccw = Shape::ArcCenter {
        center: [70.0, 30.0],
        plane: Plane::XY,
        turn: Turn::CounterClockwise,
    };
    let moves = [
        Move::line([20.0, 0.0, 0.0]),
        Move::line([40.0, 1.75, 0.0]),
        Move::line([50.0, 20.0, 0.0]),
        Move::line([30.0, 10.0, 0.0]),
        Move::line([70.0, 20.0, 0.0]),
        Move::new([80.0, 30.0, 5.0], ccw),
        Move::line([80.0, 50.0, 5.0]),
    ];
    let path = Toolpath::<3, 16>::new([0.0, 0.0, 0.0], &moves, 0.05, 1e-9).unwrap();
    (path, Limits::<3>::new(200.0, 3000.0, 100_000.0).unwrap())
}

/// A motion compiled in stretches of 150 ticks plays as one path: every tick within the
/// tolerance of the exact motion, the stretches meeting in position, velocity and
/// acceleration, and the speed, acceleration and jerk measured from the played samples
/// within the limits the plan promises, the seams included, without the slow-down a whole
/// compile of this plan needs.
#[test]
fn stretches_join_without_a_seam() {
    let (path, limits) = contour();
    let rate = 1000.0;
    let plan =
        PathTiming::<_, 4096, 1024>::plan(&path, &limits, &PlanOptions::new().with_rate(rate))
            .unwrap();
    let tol = 1e-5;
    let mut stretches =
        Stretches::<_, 3>::new(&plan, rate, &CompileOptions::new().with_tolerance(tol)).unwrap();
    let ticks = stretches.ticks();
    let per_tick = plan.duration() / f64::from(ticks);
    let exact = |k: u32| path.eval(plan.param(f64::from(k) * per_tick).0);
    // play every piece, stretch after stretch
    let mut pieces: strak_curves::heapless::Vec<Piece<f64, 3>, 256> =
        strak_curves::heapless::Vec::new();
    let (mut x, mut v, mut a) = (Vec::new(), Vec::new(), Vec::new());
    let (mut seams, mut seam_step, mut most) = (0, [0.0_f64; 3], 0);
    let mut end: Option<[AxisState<f64>; 3]> = None;
    while stretches.remaining() > 0 {
        stretches.next_into(150, &mut pieces).unwrap();
        most = most.max(pieces.len());
        if let Some(end) = end {
            // the state the last stretch ended in and the state this one starts from
            seams += 1;
            for (e, s) in end.iter().zip(pieces[0].axes()) {
                seam_step[0] = seam_step[0].max((e.position - s.position).abs());
                seam_step[1] = seam_step[1].max((e.velocity - s.velocity).abs());
                seam_step[2] = seam_step[2].max((e.acceleration - s.acceleration).abs());
            }
        }
        for piece in &pieces {
            let mut state = *piece.axes();
            for _ in 0..piece.ticks() {
                x.push(state.map(|s| s.position));
                v.push(state.map(|s| s.velocity));
                a.push(state.map(|s| s.acceleration));
                state.iter_mut().for_each(AxisState::step);
            }
            end = Some(state);
        }
    }
    println!(
        "largest steps at the seams: position {:.1e}, velocity {:.1e}, acceleration {:.1e}",
        seam_step[0], seam_step[1], seam_step[2]
    );
    assert!(
        seam_step[0] < 1e-9 && seam_step[1] < 1e-7 && seam_step[2] < 1e-4,
        "{seam_step:?}"
    );
    assert!(seams >= 10, "{seams} seams");
    assert_eq!(x.len() as u32, ticks);
    let mut worst = 0.0_f64;
    for (k, p) in x.iter().enumerate() {
        worst = worst.max(p.minus(exact(k as u32)).norm());
    }
    assert!(worst <= tol * 1.000_001, "position error {worst}");
    let t = 1.0 / rate;
    let (mut vmax, mut amax, mut jmax) = (0.0_f64, 0.0_f64, 0.0_f64);
    for k in 1..x.len() {
        vmax = vmax.max(x[k].minus(x[k - 1]).norm() / t);
        amax = amax.max(v[k].minus(v[k - 1]).norm() / t);
        jmax = jmax.max(a[k].minus(a[k - 1]).norm() / t);
    }
    println!(
        "{seams} seams, at most {most} pieces a stretch; error {worst:.2e}; v {vmax:.3} a {amax:.2} j {jmax:.0}"
    );
    let whole: Box<Path<f64, 3, 4096>> =
        compile_boxed(&plan, rate, &CompileOptions::new().with_tolerance(tol)).unwrap();
    println!(
        "whole compile: {} ticks, {} pieces, time scale {:.4}; stretches: {ticks} ticks",
        whole.ticks(),
        whole.pieces().len(),
        whole.time_scale()
    );
    assert!(
        whole.ticks() > ticks,
        "the whole compile slows down, the stretches do not"
    );
    // within what the plan promises (the machine's limits less the feed reserve)
    let promised = plan.limits().unwrap();
    let slack = 1.0 + 1e-9;
    assert!(vmax <= promised.velocity * slack, "{vmax}");
    assert!(amax <= promised.acceleration * slack, "{amax}");
    assert!(jmax <= promised.jerk * slack, "{jmax}");
}

/// `PathTiming::param_acceleration` (exact, from the motion and the curve) agrees with the
/// central difference of `du/dt` along the blended toolpath, blends and arc included.
#[test]
fn param_acceleration_is_the_derivative_of_the_rate() {
    let (path, limits) = contour();
    let plan = PathTiming::<_, 4096, 1024>::plan(&path, &limits, &PlanOptions::new()).unwrap();
    let (duration, h) = (plan.duration(), 1e-7);
    let mut worst = 0.0_f64;
    let mut scale = 0.0_f64;
    for i in 1..2000 {
        let t = duration * f64::from(i) / 2000.0;
        let difference = (plan.param(t + h).1 - plan.param(t - h).1) / (2.0 * h);
        let exact = plan.param_acceleration(t);
        worst = worst.max((exact - difference).abs());
        scale = scale.max(exact.abs());
    }
    println!("largest difference {worst:.3e} of {scale:.3e}");
    assert!(scale > 0.0 && worst <= 1e-4 * scale, "{worst} of {scale}");
}

/// A dense chain: a circle of 0.2 mm chords blended within 0.02 mm, where every blend takes
/// half of each chord (the blends meet with no line between them, chained with a shared
/// curvature). It plans and plays within the tolerance of the chords, near the path
/// velocity, and more than twice as fast as exact stops.
#[test]
fn dense_chain_of_short_moves() {
    let points: Vec<[f64; 2]> = (0..=100)
        .map(|i| {
            let th = f64::from(i) * 0.02;
            [10.0 * th.cos(), 10.0 * th.sin()]
        })
        .collect();
    let moves: Vec<Move<2>> = points[1..].iter().map(|p| Move::line(*p)).collect();
    let limits = Limits::<2>::new(100.0, 3000.0, 100_000.0).unwrap();
    let time = |tol: f64| {
        let path = Toolpath::<2, 128>::new(points[0], &moves, tol, 1e-9).unwrap();
        let plan = PathTiming::<_, 4096, 1024>::plan(&path, &limits, &PlanOptions::new()).unwrap();
        (
            path.blends(),
            ParamCurve::piece_count(&path),
            plan.duration(),
        )
    };
    let (blends, pieces, blended) = time(0.02);
    assert_eq!(blends, 99);
    assert_eq!(
        pieces, 101,
        "the first and last chord's outer halves, and the blends"
    );
    let (_, _, stopping) = time(0.0);
    println!("0.2 mm chords: blended {blended:.3} s, exact stops {stopping:.3} s");
    assert!(2.0 * blended < stopping, "{blended} against {stopping}");
    let path = Toolpath::<2, 128>::new(points[0], &moves, 0.02, 1e-9).unwrap();
    // the blends are chained: the curvature stays near the circle's 0.1/mm between the
    // first and the last blend, where each blend alone would fall to 0 on every chord
    let (mut least, mut most) = (f64::INFINITY, 0.0_f64);
    for i in 200..=9_900 {
        let u = f64::from(i) * 0.01;
        let (d1, d2) = (path.deriv(u, 1), path.deriv(u, 2));
        let speed = d1[0].hypot(d1[1]);
        let k = (d1[0] * d2[1] - d1[1] * d2[0]) / (speed * speed * speed);
        (least, most) = (least.min(k), most.max(k));
    }
    println!("curvature of the chained blends: {least:.6} to {most:.6}");
    assert!(least > 0.099 && most < 0.101, "{least} {most}");
    // so the circle is crossed near the path velocity: its 20 mm at 100 mm/s, and the ramps
    // with what the turning leaves of the acceleration and jerk (about 0.12 s each)
    assert!(blended < 0.45, "{blended}");
    let plan = PathTiming::<_, 4096, 1024>::plan(&path, &limits, &PlanOptions::new()).unwrap();
    let played: Box<Path<f64, 2, 4096>> =
        compile_boxed(&plan, 1000.0, &CompileOptions::new().with_tolerance(1e-4)).unwrap();
    let chords: Vec<Polygon<2>> = path
        .moves()
        .iter()
        .map(|m| Polygon::new(m, (0.0, 1.0), 0.0, 1))
        .collect();
    let mut sampler = Sampler::new(&*played);
    let mut worst = 0.0_f64;
    while !sampler.is_finished() {
        let x = sampler.next().position;
        worst = worst.max(
            chords
                .iter()
                .map(|c| c.distance(x))
                .fold(f64::INFINITY, f64::min),
        );
    }
    assert!(worst <= 0.02 + 1e-4 + played.playback_bound(), "{worst}");
}

/// A whole toolpath of lines meeting arcs tangentially, planned with exact stops (tolerance
/// 0: no blends) and with blends: the joins where only the curvature steps are passed at a
/// capped speed, so the compiled motion keeps the jerk limit from the samples.
#[test]
fn tangent_arc_joins_of_a_whole_toolpath_keep_the_jerk() {
    let arc = |to: [f64; 2], center: [f64; 2]| {
        Move::new(
            to,
            Shape::ArcCenter {
                center,
                plane: Plane::XY,
                turn: Turn::CounterClockwise,
            },
        )
    };
    let moves = [
        Move::line([37.0, 0.0]),
        arc([40.0, 3.0], [37.0, 3.0]),
        Move::line([40.0, 17.0]),
        arc([37.0, 20.0], [37.0, 17.0]),
    ];
    let limits = Limits::<2>::new(200.0, 3000.0, 100_000.0).unwrap();
    let keep = 1.0 - PlanOptions::DEFAULT_FEED_SHARE;
    for tolerance in [0.0, 0.02] {
        let path = Toolpath::<2, 8>::new([0.0, 0.0], &moves, tolerance, 1e-9).unwrap();
        let plan = PathTiming::<_, 4096, 1024>::plan(&path, &limits, &PlanOptions::new()).unwrap();
        let played: Box<Path<f64, 2, 4096>> =
            compile_boxed(&plan, 1000.0, &CompileOptions::new().with_tolerance(1e-4)).unwrap();
        let mut sampler = Sampler::new(&*played);
        let (mut a_max, mut j_max) = (0.0_f64, 0.0_f64);
        let mut last: Option<[f64; 2]> = None;
        while !sampler.is_finished() {
            let a = sampler.next().acceleration;
            a_max = a_max.max(a.norm());
            if let Some(p) = last {
                j_max = j_max.max(a.minus(p).norm() * 1000.0);
            }
            last = Some(a);
        }
        println!("tolerance {tolerance}: a {a_max:.1}, j {j_max:.0}");
        assert!(a_max <= keep * 3000.0 * (1.0 + 1e-9), "{a_max}");
        assert!(j_max <= keep * 100_000.0 * (1.0 + 1e-9), "{j_max}");
    }
}

/// The ticks of a stream as played: positions, velocities and accelerations per tick, the
/// largest steps of position, velocity and acceleration where one piece meets the next,
/// and the number of pieces.
#[derive(Default)]
struct Played {
    x: Vec<[f64; 3]>,
    v: Vec<[f64; 3]>,
    a: Vec<[f64; 3]>,
    seam: [f64; 3],
    pieces: usize,
    /// The moves the stream refused (by index), but for a lack of room.
    refused: Vec<usize>,
}

impl Played {
    /// Plays `piece` after the ones before (forward differencing in `N`), recording where
    /// it meets them.
    fn play<N: Number>(&mut self, piece: &Piece<N, 3>, end: &mut Option<[AxisState<N>; 3]>) {
        let f = |x: N| x.to_f64();
        if let Some(end) = end {
            for (e, s) in end.iter().zip(piece.axes()) {
                self.seam[0] = self.seam[0].max((f(e.position) - f(s.position)).abs());
                self.seam[1] = self.seam[1].max((f(e.velocity) - f(s.velocity)).abs());
                self.seam[2] = self.seam[2].max((f(e.acceleration) - f(s.acceleration)).abs());
            }
        }
        let mut state = *piece.axes();
        for _ in 0..piece.ticks() {
            self.record(&state);
            state.iter_mut().for_each(AxisState::step);
        }
        self.pieces += 1;
        *end = Some(state);
    }

    /// Records the state of one tick.
    fn record<N: Number>(&mut self, state: &[AxisState<N>; 3]) {
        self.x.push(state.map(|s| s.position.to_f64()));
        self.v.push(state.map(|s| s.velocity.to_f64()));
        self.a.push(state.map(|s| s.acceleration.to_f64()));
    }

    /// The largest speed, acceleration and jerk from differences of the played ticks.
    fn peaks(&self, rate: f64) -> [f64; 3] {
        let mut peaks = [0.0_f64; 3];
        for k in 1..self.x.len() {
            peaks[0] = peaks[0].max(self.x[k].minus(self.x[k - 1]).norm() * rate);
            peaks[1] = peaks[1].max(self.v[k].minus(self.v[k - 1]).norm() * rate);
            peaks[2] = peaks[2].max(self.a[k].minus(self.a[k - 1]).norm() * rate);
        }
        peaks
    }
}

/// Runs a stream over `moves`: pushes up to `batch` moves before each poll (then finishes
/// it; a move refused for a lack of room is pushed again after the poll, one refused for
/// another reason is skipped and noted), and plays every piece the polls compile.
fn run_stream<N: Number, const Q: usize, const Z: usize, C: StreamCurve<3>>(
    stream: &mut Stream<3, Q, Z, C>,
    moves: &[Move<3, C>],
    batch: usize,
) -> Played {
    let mut pieces = Deque::<Piece<N, 3>, 64>::new();
    let (mut played, mut end, mut next) = (Played::default(), None, 0);
    for _ in 0..1_000_000 {
        for _ in 0..batch {
            let Some(mv) = moves.get(next) else { break };
            match stream.push(mv) {
                Ok(()) => next += 1,
                Err(Error::CapacityExceeded { .. } | Error::ZoneCapacityExceeded { .. }) => break,
                Err(_) => {
                    played.refused.push(next);
                    next += 1;
                }
            }
        }
        if next == moves.len() {
            match stream.finish() {
                // full: finished after a poll has made room
                Ok(())
                | Err(Error::CapacityExceeded { .. } | Error::ZoneCapacityExceeded { .. }) => {}
                Err(e) => panic!("finish: {e}"),
            }
        }
        let ticks = stream
            .poll(&mut pieces)
            .unwrap_or_else(|e| panic!("poll: {e:?}"));
        while let Some(piece) = pieces.pop_front() {
            played.play(&piece, &mut end);
        }
        if ticks == 0 && next == moves.len() && stream.is_idle() {
            if let Some(end) = end {
                played.record(&end); // where the last piece ends and the sampler holds still
            }
            return played;
        }
    }
    panic!("the stream does not end");
}

/// The moves of `contour`.
fn contour_moves() -> Vec<Move<3>> {
    let ccw = Shape::ArcCenter {
        center: [70.0, 30.0],
        plane: Plane::XY,
        turn: Turn::CounterClockwise,
    };
    vec![
        Move::line([20.0, 0.0, 0.0]),
        Move::line([40.0, 1.75, 0.0]),
        Move::line([50.0, 20.0, 0.0]).with_feed(80.0),
        Move::line([30.0, 10.0, 0.0]),
        Move::line([50.0, 20.0, 0.0]), // a reversal: an exact stop
        Move::line([70.0, 20.0, 0.0]),
        Move::new([80.0, 30.0, 5.0], ccw),
        Move::line([80.0, 50.0, 5.0]),
        Move::new(
            [60.0, 60.0, 0.0],
            Shape::Bezier {
                c1: [80.0, 60.0, 5.0],
                c2: [70.0, 65.0, 0.0],
            },
        ),
    ]
}

/// The moves from the origin as polygons of their samples (see [`Polygon`]).
fn programmed<C: StreamCurve<3>>(moves: &[Move<3, C>]) -> Vec<Polygon<3>> {
    let mut from = [0.0; 3];
    moves
        .iter()
        .map(|mv| {
            let m = MoveCurve::new(from, mv, 1e-9).unwrap();
            from = mv.to;
            Polygon::new(
                &m,
                (0.0, 1.0),
                m.second_derivative_bound(),
                4 * CURVE_SAMPLES,
            )
        })
        .collect()
}

/// The largest distance of the played ticks from the programmed moves: an upper bound,
/// which exceeds the distance by at most twice the [`largest_sag`] of the moves (a point of
/// a move lies within the sag of its polygon, and the polygon's distance gets the sag
/// added).
fn distance_from_moves<C: StreamCurve<3>>(moves: &[Move<3, C>], x: &[[f64; 3]]) -> f64 {
    let polygons = programmed(moves);
    x.iter()
        .map(|&p| {
            polygons
                .iter()
                .map(|g| g.distance(p))
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max)
}

/// The largest departure of the polygons of [`distance_from_moves`] from their moves.
fn largest_sag<C: StreamCurve<3>>(moves: &[Move<3, C>]) -> f64 {
    programmed(moves).iter().map(|p| p.sag).fold(0.0, f64::max)
}

/// A stream of lines (corners of 5° to 145°, a reversal), a tangent arc with a helical rise
/// and a Bézier, with a slower feed on one line, pushed at once and played: the pieces
/// meet without a seam, the speed, acceleration and jerk from the played ticks stay within
/// the promised limits, every tick lies within the tolerance of the programmed moves, and
/// the motion ends at rest on the last move's end (every corner blended that can be).
#[test]
fn a_stream_plays_within_the_limits_and_the_tolerance() {
    let (rate, tol, fit) = (1000.0, 0.05, 1e-5);
    let limits = Limits::<3>::new(200.0, 3000.0, 100_000.0).unwrap();
    let options = StreamOptions::new(rate)
        .with_tolerance(tol)
        .with_fit_tolerance(fit)
        .with_faster_stops(false);
    let mut stream = Stream::<3, 32, 256>::new([0.0; 3], limits, options).unwrap();
    let moves = contour_moves();
    let played = run_stream::<f64, 32, 256, _>(&mut stream, &moves, moves.len());
    let stats = stream.stats();
    let peaks = played.peaks(rate);
    let worst = distance_from_moves(&moves, &played.x);
    println!(
        "{} ticks, {} pieces, {stats:?}; seams {:.1e} {:.1e} {:.1e}; v {:.3} a {:.1} j {:.0}; distance {worst:.5}",
        played.x.len(),
        played.pieces,
        played.seam[0],
        played.seam[1],
        played.seam[2],
        peaks[0],
        peaks[1],
        peaks[2]
    );
    assert_eq!((stats.moves, stats.blends, stats.stops), (9, 7, 1));
    assert!(stats.max_deviation <= tol);
    let seam = played.seam;
    assert!(
        seam[0] < 1e-9 && seam[1] < 1e-7 && seam[2] < 1e-4,
        "{seam:?}"
    );
    let slack = 1.0 + 1e-9;
    let keep = 1.0 - PlanOptions::DEFAULT_FEED_SHARE;
    assert!(peaks[0] <= 200.0 * slack, "{peaks:?}");
    assert!(peaks[1] <= keep * 3000.0 * slack, "{peaks:?}");
    assert!(peaks[2] <= keep * 100_000.0 * slack, "{peaks:?}");
    assert!(worst <= tol + fit, "{worst}");
    assert!(worst > tol / 4.0, "the corners are blended: {worst}");
    let last = played.x.last().unwrap();
    assert!(last.minus(moves[8].to).norm() < 1e-9, "{last:?}");
    assert!(played.v.last().unwrap().norm() < 1e-9);
}

/// A zig-zag of lines of 8 to 12 mm whose producer pushes a move per poll (64 ms of motion)
/// for ten moves, then one per eight polls, slower than the motion needs: the stream
/// blends while it has moves, runs dry, rests at the end of what it has, and starts again
/// from rest when the next move arrives; through all of it the
/// speed, acceleration and jerk from the played ticks stay within the limits, every tick
/// lies within the tolerance of the moves, and the motion ends on the last move's end.
#[test]
fn a_starved_stream_rests_and_resumes_within_the_limits() {
    let (rate, tol) = (1000.0, 0.02);
    let limits = Limits::<3>::new(200.0, 3000.0, 100_000.0).unwrap();
    let options = StreamOptions::new(rate)
        .with_tolerance(tol)
        .with_faster_stops(false);
    let moves: Vec<Move<3>> = (1..=20)
        .map(|i| {
            let x = 7.5 * f64::from(i);
            let y = if i % 2 == 0 {
                0.0
            } else {
                5.0 + f64::from(i % 3)
            };
            Move::line([x, y, 0.0])
        })
        .collect();
    let mut stream = Stream::<3, 32, 256>::new([0.0; 3], limits, options).unwrap();
    let mut pieces = Deque::<Piece<f64, 3>, 64>::new();
    let (mut played, mut end, mut next) = (Played::default(), None, 0);
    for poll in 0.. {
        let every = if next < 10 { 1 } else { 8 };
        if poll % every == 0 && next < moves.len() {
            stream.push(&moves[next]).unwrap();
            next += 1;
        }
        let ticks = stream.poll(&mut pieces).unwrap();
        while let Some(piece) = pieces.pop_front() {
            played.play(&piece, &mut end);
        }
        if next == moves.len() {
            stream.finish().unwrap();
            if ticks == 0 && stream.is_idle() {
                break;
            }
        }
        assert!(poll < 100_000);
    }
    played.record(&end.unwrap());
    let stats = stream.stats();
    let peaks = played.peaks(rate);
    let rests = played
        .v
        .windows(2)
        .filter(|w| w[0].norm() > 1e-9 && w[1].norm() <= 1e-9)
        .count();
    let worst = distance_from_moves(&moves, &played.x);
    println!(
        "{} ticks, {stats:?}, {rests} rests; v {:.3} a {:.1} j {:.0}; distance {worst:.5}",
        played.x.len(),
        peaks[0],
        peaks[1],
        peaks[2]
    );
    assert!(stats.starved >= 3 && rests >= 3, "{stats:?} {rests}");
    assert!(stats.blends >= 5, "{stats:?}");
    assert_eq!(stats.blends + stats.starved, 20, "{stats:?}");
    let slack = 1.0 + 1e-9;
    let keep = 1.0 - PlanOptions::DEFAULT_FEED_SHARE;
    assert!(peaks[0] <= 200.0 * slack, "{peaks:?}");
    assert!(peaks[1] <= keep * 3000.0 * slack, "{peaks:?}");
    assert!(peaks[2] <= keep * 100_000.0 * slack, "{peaks:?}");
    assert!(worst <= tol + 1e-5, "{worst}");
    let seam = played.seam;
    assert!(
        seam[0] < 1e-9 && seam[1] < 1e-7 && seam[2] < 1e-4,
        "{seam:?}"
    );
    assert!(played.x.last().unwrap().minus(moves[19].to).norm() < 1e-9);
}

/// Each move's feed bounds the speed along it: two collinear lines at 150 and 50 units/s
/// pass straight, the speed comes down to 50 before the second begins and cruises there.
#[test]
fn each_move_keeps_its_feed() {
    let rate = 1000.0;
    let limits = Limits::<3>::new(200.0, 3000.0, 100_000.0).unwrap();
    let mut stream = Stream::<3, 8, 64>::new(
        [0.0; 3],
        limits,
        StreamOptions::new(rate).with_tolerance(0.01),
    )
    .unwrap();
    let moves = [
        Move::line([30.0, 0.0, 0.0]).with_feed(150.0),
        Move::line([60.0, 0.0, 0.0]).with_feed(50.0),
    ];
    let played = run_stream::<f64, 8, 64, _>(&mut stream, &moves, 2);
    let speeds: Vec<(f64, f64)> = played
        .x
        .windows(2)
        .map(|w| (w[0][0], w[1].minus(w[0]).norm() * rate))
        .collect();
    let first = speeds.iter().map(|s| s.1).fold(0.0, f64::max);
    let second = speeds
        .iter()
        .filter(|s| s.0 >= 30.0)
        .map(|s| s.1)
        .fold(0.0, f64::max);
    println!("fastest {first:.4} on the first line, {second:.6} on the second");
    assert!(first <= 150.0 * (1.0 + 1e-9) && first > 149.0, "{first}");
    assert!(second <= 50.0 * (1.0 + 1e-9) && second > 49.9, "{second}");
    assert_eq!(stream.stats().blends, 0);
}

/// The relative allowance of the played peaks over the limits in each number format:
/// forward differencing over a piece of up to 256 ticks adds up to `256·ε·|a|` to the
/// acceleration channel (`ε` the format's resolution relative to the value: `2⁻²⁴` in
/// `f32`), and a jerk from differences of that channel twice that over a tick; the speed
/// and acceleration channels stay within a tenth of that share. `Q40` rounds to `2⁻⁴⁰`
/// units, `f64` leaves the comparison's own rounding.
fn format_allowance<N: Number>() -> (f64, f64) {
    match N::NAME {
        "f32" => (1e-4, 4e-3),
        "Q40" => (1e-6, 1e-5),
        _ => (1e-9, 1e-9),
    }
}

/// Streams `moves` (bad ones skipped) blended within `tolerance` and checks the played
/// ticks in `N`: speed and acceleration from their channels and jerk from differences of
/// the acceleration channel within the promised limits (plus the format's allowance); in
/// `f64` the speed from differences of positions and the seams as well; every tick within
/// the tolerance of the moves (plus the fit's and the format's position error); the end
/// on the last move's end.
fn check_random_stream<N: Number, C: StreamCurve<3>>(
    moves: &[Move<3, C>],
    options: StreamOptions,
) -> Result<StreamStats, TestCaseError> {
    let limits = Limits::<3>::new(200.0, 3000.0, 100_000.0).unwrap();
    let tolerance = options.tolerance();
    let mut stream = Stream::<3, 32, 512, C>::new([0.0; 3], limits, options).unwrap();
    let played = run_stream::<N, 32, 512, _>(&mut stream, moves, moves.len());
    let accepted: Vec<Move<3, C>> = (0..moves.len())
        .filter(|i| !played.refused.contains(i))
        .map(|i| moves[i])
        .collect();
    prop_assume!(!accepted.is_empty());
    let (channel, jerk) = format_allowance::<N>();
    let keep = 1.0 - PlanOptions::DEFAULT_FEED_SHARE;
    let peak = |xs: &[[f64; 3]]| xs.iter().map(|x| x.norm()).fold(0.0, f64::max);
    let (v, a) = (peak(&played.v), peak(&played.a));
    let j = played
        .a
        .windows(2)
        .map(|w| w[1].minus(w[0]).norm() * 1000.0)
        .fold(0.0, f64::max);
    let what = || format!("{} {tolerance}: v {v} a {a} j {j}", N::NAME);
    prop_assert!(v <= 200.0 * (1.0 + channel), "{}", what());
    prop_assert!(a <= keep * 3000.0 * (1.0 + channel), "{}", what());
    prop_assert!(j <= keep * 100_000.0 * (1.0 + jerk), "{}", what());
    let far = peak(&played.x).max(1.0);
    let position = match N::NAME {
        "f64" => {
            let fd = played.peaks(1000.0)[0];
            prop_assert!(fd <= 200.0 * (1.0 + 1e-9), "{} {fd}", what());
            let seam = played.seam;
            prop_assert!(seam[0] < 1e-9 && seam[1] < 1e-7, "{seam:?}");
            1e-9
        }
        "Q40" => 1e-9,
        _ => 256.0 * f64::from(f32::EPSILON) * far,
    };
    let sampled: Vec<[f64; 3]> = played.x.iter().step_by(3).copied().collect();
    let worst = distance_from_moves(&accepted, &sampled);
    let bound = tolerance + 1e-5 + position + 2.0 * largest_sag(&accepted);
    prop_assert!(worst <= bound, "{} distance {worst} > {bound}", what());
    let last = played.x.last().unwrap();
    let end = accepted.last().unwrap().to;
    prop_assert!(
        last.minus(end).norm() <= 1e-9 + position,
        "{} end {last:?}",
        what()
    );
    Ok(stream.stats())
}

/// A stream at 1 kHz with corners blended within `tolerance` (or stopped where faster).
fn within(tolerance: f64) -> StreamOptions {
    StreamOptions::new(1000.0).with_tolerance(tolerance)
}

/// The moves of `kinds` from the origin: kind 4 a line of 0.05 to 0.5 mm, the others
/// [`random_move`]; with a feed of 20 to 200 where `x[8] < 0.3`.
fn random_moves(kinds: &[(u8, [f64; 10])]) -> Vec<Move<3>> {
    let mut from = [0.0; 3];
    let mut moves = Vec::new();
    for (kind, x) in kinds {
        let mut mv = if *kind == 4 {
            let d = 0.05 + 0.45 * x[0];
            let heading = std::f64::consts::TAU * x[1];
            Move::line([
                from[0] + d * heading.cos(),
                from[1] + d * heading.sin(),
                from[2],
            ])
        } else {
            random_move(from, *kind, x)
        };
        if x[8] < 0.3 {
            mv = mv.with_feed(20.0 + 180.0 * x[7]);
        }
        from = mv.to;
        moves.push(mv);
    }
    moves
}

/// Two lines of 10 mm meeting at a turn of 5°, 90°, 135°, 179° and 180° (a reversal),
/// played in `f64`, `f32` and `Q40` ([`check_random_stream`]: the limits from the played
/// ticks, the tolerance of 0.05 mm, the exact end): with every corner blended that can be,
/// the corners up to 135° are blended, the near-reversal and the reversal are exact stops.
#[test]
fn every_corner_angle_keeps_the_limits_and_the_tolerance() {
    for degrees in [5.0, 90.0, 135.0, 179.0, 180.0] {
        let turn = f64::to_radians(degrees);
        let corner = [10.0, 0.0, 0.0];
        let moves = [
            Move::<3>::line(corner),
            Move::line([10.0 + 10.0 * turn.cos(), 10.0 * turn.sin(), 0.0]),
        ];
        let blending = within(0.05).with_faster_stops(false);
        let stats = [
            check_random_stream::<f64, _>(&moves, blending),
            check_random_stream::<f32, _>(&moves, blending),
            check_random_stream::<Q40, _>(&moves, blending),
        ]
        .map(|checked| checked.unwrap_or_else(|e| panic!("{degrees}°: {e}")));
        let blended = degrees < 170.0;
        for s in stats {
            assert_eq!(
                (s.blends, s.stops),
                (usize::from(blended), usize::from(!blended)),
                "{degrees}°: {s:?}"
            );
            assert!(s.max_deviation <= 0.05, "{degrees}°: {s:?}");
        }
        println!("{degrees}°: {:?}", stats[0]);
    }
}

/// The ticks of `moves` streamed from the origin under the bench's limits (200 mm/s,
/// 3 000 mm/s², 100 000 mm/s³) with `options`, and the stream's counts.
fn streamed_ticks(moves: &[Move<3>], options: StreamOptions) -> (usize, StreamStats) {
    let limits = Limits::<3>::new(200.0, 3000.0, 100_000.0).unwrap();
    let mut stream = Stream::<3, 32, 512>::new([0.0; 3], limits, options).unwrap();
    let played = run_stream::<f64, 32, 512, _>(&mut stream, moves, moves.len());
    (played.x.len(), stream.stats())
}

/// A right angle between lines of 20 mm within 0.02 mm: its blend is passed at about
/// 4.5 mm/s, so the stream stops at the corner instead, and is faster for it than when it
/// blends every corner; a turn of 5° keeps its blend. A zig-zag of 40 lines of 1 to 5 mm
/// turning by 10° to 120° takes less time with the choice than both with every corner
/// blended and with every corner stopped.
#[test]
fn a_corner_stops_where_a_stop_is_faster_than_its_blend() {
    let blending = within(0.02).with_faster_stops(false);
    let turn = |degrees: f64| {
        let t = f64::to_radians(degrees);
        [
            Move::line([20.0, 0.0, 0.0]),
            Move::line([20.0 + 20.0 * t.cos(), 20.0 * t.sin(), 0.0]),
        ]
    };
    let (chosen, stats) = streamed_ticks(&turn(90.0), within(0.02));
    let (blended, blend_stats) = streamed_ticks(&turn(90.0), blending);
    assert_eq!((stats.blends, stats.stops, blend_stats.blends), (0, 1, 1));
    assert!(chosen < blended, "{chosen} {blended}");
    assert_eq!(streamed_ticks(&turn(5.0), within(0.02)).1.blends, 1);
    let (mut from, mut heading) = ([0.0; 3], 0.0_f64);
    let zigzag: Vec<Move<3>> = (0..40_u32)
        .map(|i| {
            let sign = if i % 2 == 0 { 1.0 } else { -1.0 };
            heading += sign * f64::to_radians(10.0 + f64::from(i * 37 % 111));
            let d = 1.0 + f64::from(i * 13 % 41) / 10.0;
            from = [
                from[0] + d * heading.cos(),
                from[1] + d * heading.sin(),
                0.0,
            ];
            Move::line(from)
        })
        .collect();
    let (chosen, stats) = streamed_ticks(&zigzag, within(0.02));
    let (blended, _) = streamed_ticks(&zigzag, blending);
    let (stopped, _) = streamed_ticks(&zigzag, within(0.0));
    println!(
        "zig-zag: {chosen} ticks, every corner blended {blended}, stopped {stopped}; {stats:?}"
    );
    assert!(stats.blends > 0 && stats.stops > 0, "{stats:?}");
    assert!(
        chosen < blended.min(stopped),
        "{chosen} {blended} {stopped}"
    );
}

/// Chains of short lines as a slicer writes curved walls, blended within 0.02 mm and
/// played in `f64`, `f32` and `Q40` ([`check_random_stream`]: the limits from the played
/// ticks, the tolerance, the exact end): 0.05 mm chords on a wall of 2 mm radius, 0.5 mm
/// chords on one of 5 mm, and 0.2 mm chords along a wave whose curvature changes sign (as
/// many of each as a stream of 32 segments takes at once). Every corner is blended.
#[test]
fn chains_of_short_lines_keep_the_limits_and_the_tolerance() {
    let circle = |r: f64, chord: f64, n: usize| -> Vec<Move<3>> {
        let step = 2.0 * (chord / (2.0 * r)).asin();
        (1..=n)
            .map(|i| {
                let th = step * i as f64;
                Move::line([r * th.sin(), r - r * th.cos(), 0.0])
            })
            .collect()
    };
    let wave: Vec<Move<3>> = (1..=30)
        .map(|i| {
            let x = 0.2 * f64::from(i);
            Move::line([x, 0.5 * (x * 1.5).sin(), 0.0])
        })
        .collect();
    for (name, moves) in [
        ("0.05 mm chords, r = 2 mm", circle(2.0, 0.05, 30)),
        ("0.5 mm chords, r = 5 mm", circle(5.0, 0.5, 30)),
        ("0.2 mm chords along a wave", wave),
    ] {
        let stats = [
            check_random_stream::<f64, _>(&moves, within(0.02)),
            check_random_stream::<f32, _>(&moves, within(0.02)),
            check_random_stream::<Q40, _>(&moves, within(0.02)),
        ]
        .map(|checked| checked.unwrap_or_else(|e| panic!("{name}: {e}")));
        for s in stats {
            assert_eq!((s.blends, s.stops), (s.moves - 1, 0), "{name}: {s:?}");
            assert!(s.max_deviation <= 0.02, "{name}: {s:?}");
        }
        println!("{name}: {:?}", stats[0]);
    }
}

/// Random streams of lines (some of 0.05 to 0.5 mm), arcs about a centre with a helical
/// rise, arcs of a radius and Béziers, some with a feed of their own, blended within 0,
/// 0.01 or 0.05 mm and played in `f64`, `f32` and `Q40` (random seeds per run; a failure
/// is reported with its inputs).
#[test]
fn random_streams_keep_the_limits_in_every_number_format() {
    let strategy = (
        proptest::collection::vec((0_u8..5, unit10()), 2..10),
        0_usize..3,
        0_usize..3,
    );
    let config = Config {
        cases: 16,
        failure_persistence: None,
        ..Config::default()
    };
    TestRunner::new(config)
        .run(&strategy, |(kinds, t, format)| {
            let moves = random_moves(&kinds);
            let tolerance = [0.0, 0.01, 0.05][t];
            let checked = match format {
                0 => check_random_stream::<f64, _>(&moves, within(tolerance)),
                1 => check_random_stream::<f32, _>(&moves, within(tolerance)),
                _ => check_random_stream::<Q40, _>(&moves, within(tolerance)),
            };
            checked.map(|_| ())
        })
        .unwrap();
}

/// Plays `moves` through a stream into a queue that a [`StreamSampler`] drains, one poll
/// (when the queue has room) and one sample per tick, pushing `batch` moves every `every`
/// ticks: the samples of every tick, until the stream is idle and the sampler holds.
fn sample_stream<N: Kernel>(
    moves: &[Move<3>],
    tolerance: f64,
    (batch, every): (usize, usize),
) -> (Vec<Sample<N::Out, 3>>, StreamStats, u32) {
    sample_controlled::<N>(moves, tolerance, (batch, every), |_, _, _| {})
}

/// [`sample_stream`] with `control(tick, stream, sampler)` called before each sample.
fn sample_controlled<N: Kernel>(
    moves: &[Move<3>],
    tolerance: f64,
    (batch, every): (usize, usize),
    mut control: impl FnMut(usize, &mut Stream<3, 32, 256>, &mut StreamSampler<'_, N, 3>),
) -> (Vec<Sample<N::Out, 3>>, StreamStats, u32) {
    let limits = Limits::<3>::new(200.0, 3000.0, 100_000.0).unwrap();
    let options = StreamOptions::new(1000.0).with_tolerance(tolerance);
    let mut stream = Stream::<3, 32, 256>::new([0.0; 3], limits, options).unwrap();
    let mut queue = Queue::<Piece<N, 3>, 64>::new();
    let (mut producer, consumer) = queue.split();
    let mut sampler = StreamSampler::new(consumer, &stream).unwrap();
    let (mut samples, mut next) = (Vec::new(), 0);
    for tick in 0..1_000_000 {
        control(tick, &mut stream, &mut sampler);
        if tick % every == 0 {
            for mv in moves.iter().skip(next).take(batch) {
                stream.push(mv).unwrap();
                next += 1;
            }
            if next == moves.len() {
                stream.finish().unwrap();
            }
        }
        stream.poll(&mut producer).unwrap();
        samples.push(sampler.next());
        if next == moves.len() && stream.is_idle() && sampler.is_holding() {
            samples.extend((0..3).map(|_| sampler.next())); // holding on
            return (samples, stream.stats(), sampler.underruns());
        }
    }
    panic!("the stream does not end");
}

/// The sampler plays the stream's pieces as they come, bit for bit as forward differencing
/// of the pieces does (`f64`, `f32`), holds exactly on the last move's end, and never runs
/// dry while the main loop polls every tick.
#[test]
fn a_stream_sampler_plays_the_pieces_as_they_come() {
    fn check<N: Kernel>() {
        let moves = contour_moves();
        let (samples, stats, underruns) = sample_stream::<N>(&moves, 0.05, (moves.len(), 1));
        let limits = Limits::<3>::new(200.0, 3000.0, 100_000.0).unwrap();
        let mut stream = Stream::<3, 32, 256>::new(
            [0.0; 3],
            limits,
            StreamOptions::new(1000.0).with_tolerance(0.05),
        )
        .unwrap();
        let played = run_stream::<N, 32, 256, _>(&mut stream, &moves, moves.len());
        assert_eq!(underruns, 0);
        assert_eq!(stats.starved, 0);
        assert!(samples.len() >= played.x.len());
        for (k, s) in samples.iter().enumerate() {
            let want = played.x[k.min(played.x.len() - 1)];
            let got = s.position.map(Scalar::to_f64);
            assert_eq!(got, want, "{} tick {k}", N::NAME);
        }
        let end = samples.last().unwrap();
        assert_eq!(end.position.map(Scalar::to_f64), moves[8].to);
        assert_eq!(end.velocity.map(Scalar::to_f64), [0.0; 3]);
    }
    check::<f64>();
    check::<f32>();
}

/// A producer that pushes a move every 250 ticks, slower than the motion: the sampler holds
/// still at every rest the stream makes (never mid-motion), and the samples of the wall
/// clock, holds included, keep the limits (jerk from differences of the acceleration).
#[test]
fn a_starved_stream_sampler_holds_at_rest() {
    let moves: Vec<Move<3>> = (1..=12)
        .map(|i| {
            let y = if i % 2 == 0 { 0.0 } else { 6.0 };
            Move::line([8.0 * f64::from(i), y, 0.0])
        })
        .collect();
    let (samples, stats, underruns) = sample_stream::<f64>(&moves, 0.02, (1, 250));
    assert_eq!(underruns, 0);
    assert!(stats.starved >= 3, "{stats:?}");
    let keep = 1.0 - PlanOptions::DEFAULT_FEED_SHARE;
    let mut holds = 0;
    for w in samples.windows(2) {
        let (a0, a1) = (w[0].acceleration, w[1].acceleration);
        let j = a1.minus(a0).norm() * 1000.0;
        assert!(
            j <= keep * 100_000.0 * (1.0 + 1e-9),
            "tick {}: jerk {j}",
            w[1].tick
        );
        assert!(w[1].velocity.norm() <= 200.0 * (1.0 + 1e-9));
        if w[0].velocity == [0.0; 3] && w[1].velocity == [0.0; 3] {
            holds += 1;
        }
    }
    println!("{} samples, {holds} held, {stats:?}", samples.len());
    assert!(holds > 100);
    assert_eq!(samples.last().unwrap().position, moves[11].to);
}

/// The largest speed, acceleration and jerk of sampler output: the speed and acceleration
/// from their channels, the jerk from differences of the acceleration channel.
fn sample_peaks<N: Kernel>(samples: &[Sample<N::Out, 3>]) -> [f64; 3] {
    let f = |x: [N::Out; 3]| x.map(Scalar::to_f64);
    let mut peaks = [0.0_f64; 3];
    for (k, s) in samples.iter().enumerate() {
        peaks[0] = peaks[0].max(f(s.velocity).norm());
        peaks[1] = peaks[1].max(f(s.acceleration).norm());
        if let Some(p) = k.checked_sub(1).and_then(|i| samples.get(i)) {
            let j = f(s.acceleration).minus(f(p.acceleration)).norm() * 1000.0;
            peaks[2] = peaks[2].max(j);
        }
    }
    peaks
}

/// Checks sampler output under feed ramps against the machine's limits (v 200, a 3000,
/// j 100 000: the ramps use the feed share the plan leaves free) with the format's
/// allowance, and in `f64` the speed from differences of positions.
fn assert_machine_limits<N: Kernel>(samples: &[Sample<N::Out, 3>], what: &str) {
    let (channel, jerk) = format_allowance::<N>();
    let [v, a, j] = sample_peaks::<N>(samples);
    println!("{what} {}: v {v:.3} a {a:.1} j {j:.0}", N::NAME);
    assert!(v <= 200.0 * (1.0 + channel), "{what} {}: v {v}", N::NAME);
    assert!(a <= 3000.0 * (1.0 + channel), "{what} {}: a {a}", N::NAME);
    assert!(j <= 100_000.0 * (1.0 + jerk), "{what} {}: j {j}", N::NAME);
    if N::NAME == "f64" {
        for w in samples.windows(2) {
            let d = w[1]
                .position
                .map(Scalar::to_f64)
                .minus(w[0].position.map(Scalar::to_f64));
            assert!(
                d.norm() * 1000.0 <= 200.0 * (1.0 + 1e-9),
                "{what}: step {d:?}"
            );
        }
    }
}

/// Feed override, hold and resume on a stream: the samples keep the machine's limits and
/// the tolerance of the moves, the hold stands still on the path, the motion takes longer
/// than at full feed and ends exactly on the last move's end (every number format).
#[test]
fn feed_override_hold_and_resume_on_a_stream() {
    fn check<N: Kernel>() {
        let moves = contour_moves();
        let all = (moves.len(), 1);
        let (plain, _, _) = sample_stream::<N>(&moves, 0.05, all);
        let (samples, _, underruns) =
            sample_controlled::<N>(&moves, 0.05, all, |tick, _, s| match tick {
                300 => s.set_feed(0.4),
                800 => s.hold(),
                1400 => s.resume(),
                1700 => s.set_feed(1.0),
                _ => {}
            });
        assert_eq!(underruns, 0);
        assert!(
            samples.len() > plain.len() + 600,
            "{} vs {}",
            samples.len(),
            plain.len()
        );
        assert_machine_limits::<N>(&samples, "override and hold");
        let x: Vec<[f64; 3]> = samples
            .iter()
            .map(|s| s.position.map(Scalar::to_f64))
            .collect();
        let held = x[800..1400].windows(2).filter(|w| w[0] == w[1]).count();
        assert!(held > 300, "{} held {held} ticks", N::NAME);
        let far = 256.0 * f64::from(f32::EPSILON) * 100.0;
        let bound = 0.05 + 1e-5 + far + 2.0 * largest_sag(&moves);
        let worst = distance_from_moves(&moves, &x);
        assert!(worst <= bound, "{} distance {worst}", N::NAME);
        assert_eq!(*x.last().unwrap(), moves[8].to);
    }
    check::<f64>();
    check::<f32>();
    check::<Q40>();
}

/// A quick stop and an abort (with ramps slowed to a quarter) at full speed on a long line:
/// both stop on the line within the limits, the quick stop sooner; then the stream aborts
/// at the sampler's position, the sampler restarts, and a move back ends exactly at the
/// start, the limits held throughout.
#[test]
fn quick_stop_and_abort_on_a_stream() {
    fn stop<N: Kernel>(quick: bool) -> usize {
        let limits = Limits::<3>::new(200.0, 3000.0, 100_000.0).unwrap();
        let options = StreamOptions::new(1000.0);
        let mut stream = Stream::<3, 8, 64>::new([0.0; 3], limits, options).unwrap();
        stream.push(&Move::line([300.0, 0.0, 0.0])).unwrap();
        stream.push(&Move::line([300.0, 1.0, 0.0])).unwrap();
        let mut queue = Queue::<Piece<N, 3>, 64>::new();
        let (mut producer, consumer) = queue.split();
        let mut sampler = StreamSampler::new(consumer, &stream).unwrap();
        let mut samples = Vec::new();
        let mut stopped = None;
        for tick in 0..20_000 {
            match (tick, quick) {
                (600, true) => sampler.quick_stop(),
                (600, false) => sampler.abort(),
                (0, false) => assert!(sampler.scale_feed_ramp(2)),
                _ => {}
            }
            if !sampler.is_finished() {
                stream.poll(&mut producer).unwrap();
            } else if stopped.is_none() {
                stopped = Some(tick);
                let here = sampler.position();
                assert!(
                    here[0] > 50.0 && here[0] < 300.0 && here[1] == 0.0,
                    "{here:?}"
                );
                stream.abort(here).unwrap();
                assert!(sampler.restart());
                stream.push(&Move::line([0.0; 3])).unwrap();
                stream.finish().unwrap();
            } else {
                stream.poll(&mut producer).unwrap();
            }
            samples.push(sampler.next());
            if stopped.is_some() && stream.is_idle() && sampler.is_holding() {
                break;
            }
        }
        let stopped = stopped.expect("stops");
        assert_machine_limits::<N>(&samples, if quick { "quick stop" } else { "abort" });
        let v = samples[599].velocity.map(Scalar::to_f64).norm();
        assert!(v > 199.0, "at full speed before the stop: {v}");
        assert_eq!(
            samples.last().unwrap().position.map(Scalar::to_f64),
            [0.0; 3]
        );
        assert_eq!(sampler.underruns(), 0);
        stopped - 600
    }
    fn check<N: Kernel>() {
        let (quick, abort) = (stop::<N>(true), stop::<N>(false));
        println!("{}: quick stop in {quick} ticks, abort in {abort}", N::NAME);
        assert!(quick * 2 < abort, "{quick} {abort}");
    }
    check::<f64>();
    check::<f32>();
    check::<Q40>();
}

/// A feed override above 100 % raises the feeds of the moves not yet compiled, never the
/// machine's limits: moves at feed 60 (and one rapid) run up to 120 at 200 %, the rapid
/// at the machine's 200 at most; back at 100 % the end runs at 60 again; the samples keep
/// the promised limits and the tolerance throughout, and the motion is faster.
#[test]
fn feed_override_above_full_feed_raises_the_feeds() {
    let mut moves: Vec<Move<3>> = contour_moves()
        .into_iter()
        .map(|m| m.with_feed(60.0))
        .collect();
    moves[4].feed = None;
    let all = (moves.len(), 1);
    let (plain, _, _) = sample_stream::<f64>(&moves, 0.05, all);
    let (samples, _, underruns) = sample_controlled::<f64>(&moves, 0.05, all, |tick, stream, s| {
        let f = match tick {
            0 => 2.0,
            1000 => 1.0,
            _ => return,
        };
        s.set_feed(stream.set_feed_override(f));
    });
    assert_eq!(underruns, 0);
    // speeds from differences of positions
    let speeds: Vec<f64> = samples
        .windows(2)
        .map(|w| w[1].position.minus(w[0].position).norm() * 1000.0)
        .collect();
    let fast = speeds[..1000].iter().copied().fold(0.0, f64::max);
    let end = speeds[speeds.len() * 4 / 5..]
        .iter()
        .copied()
        .fold(0.0, f64::max);
    println!(
        "ticks {} (at 100 %: {}), fastest {fast:.2}, at the end {end:.2}",
        samples.len(),
        plain.len()
    );
    assert!(fast > 100.0 && fast <= 200.0 * (1.0 + 1e-9), "{fast}");
    // within the fit's tolerance (1e-5 units) of the planned positions at both ends of a tick
    let fit = 2.0 * 1e-5 * 1000.0;
    assert!(end <= 60.0 + fit, "{end}");
    assert!(samples.len() + 300 < plain.len());
    let keep = 1.0 - PlanOptions::DEFAULT_FEED_SHARE;
    let [v, a, j] = sample_peaks::<f64>(&samples);
    assert!(
        v <= 200.0 * (1.0 + 1e-9) && a <= keep * 3000.0 * (1.0 + 1e-9),
        "{v} {a}"
    );
    assert!(j <= keep * 100_000.0 * (1.0 + 1e-9), "{j}");
    let x: Vec<[f64; 3]> = samples.iter().map(|s| s.position).collect();
    let worst = distance_from_moves(&moves, &x);
    assert!(worst <= 0.05 + 1e-5 + 2.0 * largest_sag(&moves), "{worst}");
    assert_eq!(*x.last().unwrap(), moves[8].to);
}

/// A full stream refuses a move with a typed error and changes nothing: the segments
/// (checked before any work) and the window's zones; after polls it takes the move, and the
/// motion ends on the last move's end.
#[test]
fn a_full_stream_refuses_moves_and_changes_nothing() {
    let limits = Limits::<2>::new(100.0, 2000.0, 50_000.0).unwrap();
    let options = StreamOptions::new(1000.0).with_tolerance(0.05);
    let zigzag = |i: usize| {
        let y = if i.is_multiple_of(2) { 0.0 } else { 5.0 };
        Move::line([5.0 * (i + 1) as f64, y])
    };
    // segments: 4 hold a move and its blend twice
    let mut stream = Stream::<2, 4, 64>::new([0.0; 2], limits, options).unwrap();
    let mut pushed = 0;
    let refused = loop {
        match stream.push(&zigzag(pushed)) {
            Ok(()) => pushed += 1,
            Err(e) => break e,
        }
    };
    assert!(
        matches!(refused, Error::CapacityExceeded { capacity: 4, .. }),
        "{refused:?}"
    );
    let before = stream.stats();
    assert_eq!(stream.push(&zigzag(pushed)), Err(refused));
    assert_eq!(stream.stats(), before);
    // zones: a window of 3 zones fills before the segments do
    let mut narrow = Stream::<2, 16, 3>::new([0.0; 2], limits, options).unwrap();
    let mut n = 0;
    let refused = loop {
        match narrow.push(&zigzag(n)) {
            Ok(()) => n += 1,
            Err(e) => break e,
        }
    };
    assert!(
        matches!(refused, Error::ZoneCapacityExceeded { capacity: 3, .. }),
        "{refused:?}"
    );
    let before = narrow.stats();
    assert_eq!(narrow.push(&zigzag(n)), Err(refused));
    assert_eq!(narrow.stats(), before);
    // polling frees room: every move is taken in the end
    let mut pieces = Deque::<Piece<f64, 2>, 64>::new();
    let mut last = [0.0; 2];
    for _ in 0..100_000 {
        if pushed < 12 && stream.push(&zigzag(pushed)).is_ok() {
            pushed += 1;
        }
        if pushed == 12 {
            match stream.finish() {
                Ok(()) | Err(Error::CapacityExceeded { .. }) => {} // full: after a poll
                Err(e) => panic!("{e}"),
            }
        }
        stream.poll(&mut pieces).unwrap();
        while let Some(p) = pieces.pop_front() {
            last = p.axes().map(|a| a.position);
        }
        if pushed == 12 && stream.is_idle() {
            break;
        }
    }
    assert_eq!(last, zigzag(11).to);
    assert_eq!(stream.stats().moves, 12);
}

/// A Bézier rapid with a near-cusp between two slow lines, exact stop: the motion crawls
/// through a curvature peak narrower than the speed-limit samples, and the turning jerk
/// there stays within the promised limit (found by the random streams).
#[test]
fn a_bezier_near_cusp_keeps_the_jerk() {
    let x = [
        0.8307072166133039,
        0.0810093519871286,
        0.15888489906249206,
        0.18986581364953495,
        0.8854555299410828,
        0.66418581809838,
        0.3872894109698018,
        0.797850928581325,
        0.6034628233950906,
        0.0,
    ];
    let moves = random_moves(&[(0, [0.0; 10]), (3, x), (0, [0.0; 10])]);
    check_random_stream::<f64, _>(&moves, within(0.0)).unwrap();
}

/// Arcs and lines with exact stops, one of which comes to rest just before a tick: the
/// motion leaves the corner along the next move from the first tick, with the jerk of its
/// plan (the frame of the move it left gave that tick's acceleration a jump across the
/// corner; found by the random streams).
#[test]
fn an_exact_stop_leaves_along_the_next_move() {
    let kinds = [
        (
            2,
            [
                0.9413624251171844,
                0.8331510748599859,
                0.0,
                0.602965777378459,
                0.0,
                0.0,
                0.0,
                0.5495658994742861,
                0.0,
                0.6845733306261141,
            ],
        ),
        (
            0,
            [
                0.27008082559781665,
                0.8902600779079188,
                0.4878866953048279,
                0.0,
                0.0,
                0.0,
                0.0,
                0.0,
                0.8553410947818464,
                0.0,
            ],
        ),
        (
            2,
            [
                0.5328872795895289,
                0.31651903400366244,
                0.0,
                0.01565451153803424,
                0.0,
                0.0,
                0.0,
                0.047407045882298805,
                0.0,
                0.0,
            ],
        ),
        (
            1,
            [
                0.9934561048823541,
                0.11965639849018711,
                0.25401308953561935,
                0.8024985487346008,
                0.0,
                0.0,
                0.0,
                0.0,
                0.5108951504409003,
                0.8987655877740335,
            ],
        ),
        (
            0,
            [
                0.6653788634309662,
                0.32800045776304415,
                0.7805444204314381,
                0.0,
                0.0,
                0.0,
                0.0,
                0.8585092673062545,
                0.0,
                0.0,
            ],
        ),
        (4, [0.0; 10]),
    ];
    let stats = check_random_stream::<f64, _>(&random_moves(&kinds), within(0.0)).unwrap();
    assert_eq!((stats.moves, stats.stops), (6, 5));
}

/// A square of 20 mm lines at a feed of 150 mm/s with exact stops, in `f64`, `f32` and
/// `Q40`: the motion comes to rest at each corner a sliver after a tick, where the spline of
/// a stretch would pass the jerk limit by parts in 10⁵; its pieces there are one tick long
/// and keep the limits ([`check_random_stream`]).
#[test]
fn a_square_of_exact_stops_keeps_the_limits() {
    let square = [
        [20.0, 0.0, 0.0],
        [20.0, 20.0, 0.0],
        [0.0, 20.0, 0.0],
        [0.0, 0.0, 0.0],
    ];
    let moves = square.map(|corner| Move::<3>::line(corner).with_feed(150.0));
    for stats in [
        check_random_stream::<f64, _>(&moves, within(0.0)),
        check_random_stream::<f32, _>(&moves, within(0.0)),
        check_random_stream::<Q40, _>(&moves, within(0.0)),
    ] {
        assert_eq!(stats.unwrap().stops, 3);
    }
}

/// A curve of strak-curves as the stream traces it, whatever its type.
type AnyCurve<'a> = &'a dyn PieceDeriv<Point = [f64; 3]>;

/// Curves of strak-curves for [`curve_moves`]: a cubic B-spline wave (five pieces,
/// curvature-continuous), a rational quarter circle, a quadratic B-spline (its curvature
/// steps at its knots) and a cubic B-spline with a kink (an inner knot of multiplicity 3).
struct Curves {
    wave: BSpline<[f64; 3], 8, 12>,
    quarter: Nurbs<[f64; 3], 3, 6>,
    quadratic: BSpline<[f64; 3], 5, 8>,
    kinked: BSpline<[f64; 3], 7, 11>,
}

impl Curves {
    fn new() -> Self {
        let w = core::f64::consts::FRAC_1_SQRT_2;
        let wave = [
            [20.0, 0.0, 0.0],
            [26.0, 0.0, 0.0],
            [30.0, 8.0, 1.0],
            [36.0, -6.0, 2.0],
            [42.0, 8.0, 2.0],
            [48.0, -4.0, 1.0],
            [54.0, 0.0, 0.0],
            [60.0, 0.0, 0.0],
        ];
        let quarter = [[70.0, 10.0, 0.0], [80.0, 10.0, 0.0], [80.0, 20.0, 0.0]];
        let quadratic = [
            [80.0, 20.0, 0.0],
            [80.0, 30.0, 0.0],
            [70.0, 35.0, 1.0],
            [60.0, 30.0, 2.0],
            [55.0, 20.0, 2.0],
        ];
        let kinked = [
            [55.0, 20.0, 2.0],
            [52.0, 12.0, 2.0],
            [50.0, 8.0, 2.0],
            [48.0, 4.0, 2.0],
            [40.0, 4.0, 2.0],
            [34.0, 2.0, 2.0],
            [30.0, 0.0, 2.0],
        ];
        let uniform = [0., 0., 0., 0., 1., 2., 3., 4., 5., 5., 5., 5.];
        Curves {
            wave: BSpline::new(3, &wave, &uniform).unwrap(),
            quarter: Nurbs::new(2, &quarter, &[1.0, w, 1.0], &[0., 0., 0., 1., 1., 1.]).unwrap(),
            quadratic: BSpline::new(2, &quadratic, &[0., 0., 0., 1., 2., 3., 3., 3.]).unwrap(),
            kinked: BSpline::new(3, &kinked, &[0., 0., 0., 0., 1., 1., 1., 2., 2., 2., 2.])
                .unwrap(),
        }
    }

    /// Lines and the curves as one move each, from the origin: every join a corner or a
    /// curvature step but the last.
    fn moves(&self) -> Vec<Move<3, AnyCurve<'_>>> {
        vec![
            Move::line([20.0, 0.0, 0.0]),
            Move::curve(&self.wave as AnyCurve),
            Move::line([70.0, 10.0, 0.0]).with_feed(120.0),
            Move::curve(&self.quarter as AnyCurve),
            Move::curve(&self.quadratic as AnyCurve).with_feed(150.0),
            Move::curve(&self.kinked as AnyCurve),
            Move::line([0.0, 0.0, 0.0]),
        ]
    }
}

/// Curves of strak-curves streamed as moves among lines, in `f64`, `f32` and `Q40`: the
/// speed, acceleration and jerk from the played ticks stay within the limits, every tick
/// lies within the tolerance of the programmed curves, the motion ends on the last move's
/// end, and it comes to rest at the kink inside the last curve (a join of its pieces that
/// turns) and nowhere else but the ends.
#[test]
fn curves_of_strak_curves_stream_as_moves() {
    let curves = Curves::new();
    let moves = curves.moves();
    for stats in [
        check_random_stream::<f64, _>(&moves, within(0.02)),
        check_random_stream::<f32, _>(&moves, within(0.02)),
        check_random_stream::<Q40, _>(&moves, within(0.02)),
    ] {
        let stats = stats.unwrap();
        assert_eq!(stats.moves, 7, "{stats:?}");
        assert!(
            stats.blends >= 3 && stats.max_deviation <= 0.02,
            "{stats:?}"
        );
    }
    let limits = Limits::<3>::new(200.0, 3000.0, 100_000.0).unwrap();
    let mut stream = Stream::new([0.0; 3], limits, within(0.02)).unwrap();
    let played = run_stream::<f64, 32, 512, _>(&mut stream, &moves, moves.len());
    // the rest falls between ticks: the tick nearest the kink is within one tick of a
    // jerk-limited rest (x ≤ j·T³/6, v ≤ j·T²/2)
    let kink = [48.0, 4.0, 2.0];
    let (gap, speed) = played
        .x
        .iter()
        .zip(&played.v)
        .map(|(x, v)| (x.minus(kink).norm(), v.norm()))
        .fold((f64::INFINITY, 0.0), |a, b| if b.0 < a.0 { b } else { a });
    assert!(
        gap < 1e5 * 1e-9 / 6.0 && speed < 1e5 * 1e-6 / 2.0,
        "{gap} {speed}"
    );
    let rests = played
        .x
        .iter()
        .zip(&played.v)
        .filter(|(_, v)| v.norm() < 1e-9);
    let elsewhere = rests.filter(|(x, _)| [[0.0; 3]].iter().all(|p| x.minus(*p).norm() > 1e-6));
    assert_eq!(elsewhere.count(), 0);
}

/// A curve move that does not start where the stream is, or whose end is not its `to`, is
/// refused and changes nothing.
#[test]
fn a_curve_move_off_the_path_is_refused() {
    let curves = Curves::new();
    let limits = Limits::<3>::new(200.0, 3000.0, 100_000.0).unwrap();
    let mut stream = Stream::<3, 8, 64, AnyCurve>::new([0.0; 3], limits, within(0.02)).unwrap();
    let wave = Move::curve(&curves.wave as AnyCurve);
    assert_eq!(stream.push(&wave), Err(Error::DegenerateMove));
    stream.push(&Move::line([20.0, 0.0, 0.0])).unwrap();
    let mut off = wave;
    off.to = [60.0, 0.0, 1e-3];
    assert_eq!(stream.push(&off), Err(Error::DegenerateMove));
    stream.push(&wave).unwrap();
    assert_eq!(stream.stats().moves, 2);
}

/// B-splines of degree 2 or 3 through random control points (steps of up to 6 mm, 2 mm in
/// z) with random inner knots, each from the end of the one before, or lines where the kind
/// is `false`: the curves and, for each line, its end.
fn random_curves(kinds: &[(bool, [f64; 10])]) -> Vec<Result<BSpline<[f64; 3], 5, 9>, [f64; 3]>> {
    let mut from = [0.0; 3];
    let mut out = Vec::new();
    for (is_curve, x) in kinds {
        if !is_curve {
            let Move { to, .. } = random_move(from, 0, x);
            out.push(Err(to));
            from = to;
            continue;
        }
        let mut points = [from; 5];
        for i in 1..5 {
            let step = [x[2 * i - 2] - 0.5, x[2 * i - 1] - 0.5, 0.2 * (x[8] - 0.5)];
            points[i] = points[i - 1].plus(step.times(12.0));
        }
        let t = 0.1 + 0.4 * x[8];
        let knots: &[f64] = if x[9] < 0.5 {
            &[0.0, 0.0, 0.0, t, t + 0.4, 1.0, 1.0, 1.0]
        } else {
            &[0.0, 0.0, 0.0, 0.0, t, 1.0, 1.0, 1.0, 1.0]
        };
        let degree = knots.len() - 6;
        out.push(Ok(BSpline::new(degree, &points, knots).unwrap()));
        from = points[4];
    }
    out
}

/// Random mixes of B-spline moves and lines, blended within 0.02 or stopped exactly, in
/// `f64`, `f32` and `Q40` (see [`check_random_stream`]): within the limits and the
/// tolerance, ending on the last move's end.
#[test]
fn random_curve_moves_keep_the_limits_in_every_number_format() {
    let strategy = (
        proptest::collection::vec((any::<bool>(), unit10()), 2..6),
        0_usize..2,
        0_usize..3,
    );
    let config = Config {
        cases: 12,
        failure_persistence: None,
        ..Config::default()
    };
    TestRunner::new(config)
        .run(&strategy, |(kinds, t, format)| {
            let curves = random_curves(&kinds);
            let moves: Vec<Move<3, AnyCurve>> = curves
                .iter()
                .map(|c| match c {
                    Ok(curve) => Move::curve(curve as AnyCurve),
                    Err(to) => Move::line(*to),
                })
                .collect();
            let options = [within(0.0), within(0.02).with_faster_stops(false)][t];
            let checked = match format {
                0 => check_random_stream::<f64, _>(&moves, options),
                1 => check_random_stream::<f32, _>(&moves, options),
                _ => check_random_stream::<Q40, _>(&moves, options),
            };
            checked.map(|_| ())
        })
        .unwrap();
}

/// A rapid semicircle of radius 50 and one of radius 200, where the motion cruises at the
/// velocity limit along the arc (its curvature allows more), in `f64`, `f32` and `Q40`:
/// the pieces fitted to it keep the velocity limit.
#[test]
fn a_large_arc_at_the_velocity_limit_keeps_it() {
    for r in [50.0, 200.0] {
        let arc = Move::<3>::new(
            [2.0 * r, 0.0, 0.0],
            Shape::ArcCenter {
                center: [r, 0.0],
                plane: Plane::XY,
                turn: Turn::Clockwise,
            },
        );
        let moves = [arc, Move::line([2.0 * r, -10.0, 0.0])];
        check_random_stream::<f64, _>(&moves, within(0.02)).unwrap();
        check_random_stream::<f32, _>(&moves, within(0.02)).unwrap();
        check_random_stream::<Q40, _>(&moves, within(0.02)).unwrap();
    }
}

/// A B-spline of 200 pieces (a spiral of growing radius, in z rising) as one move between
/// two lines, through a window of 8 segments and 64 zones: its pieces go through as the
/// played ones make room; the speed, acceleration and jerk from the played ticks stay within
/// the limits, the pieces meet without a seam, and the motion ends on the last line's end.
#[test]
fn a_curve_of_many_pieces_streams_through_a_small_window() {
    let points: Vec<[f64; 3]> = (0..203)
        .map(|i| {
            let t = f64::from(i) * 0.3;
            let r = 10.0 + 0.2 * t;
            [r * t.cos(), r * t.sin(), 0.05 * t]
        })
        .collect();
    let mut knots = vec![0.0; 4];
    knots.extend((1..200).map(f64::from));
    knots.extend([200.0; 4]);
    let spiral = BSpline::<[f64; 3], 203, 207>::new(3, &points, &knots).unwrap();
    let moves: Vec<Move<3, AnyCurve>> = vec![
        Move::line(points[0]),
        Move::curve(&spiral as AnyCurve),
        Move::line([0.0, 0.0, 0.0]),
    ];
    let limits = Limits::<3>::new(200.0, 3000.0, 100_000.0).unwrap();
    let mut stream = Stream::<3, 8, 64, AnyCurve>::new([0.0; 3], limits, within(0.02)).unwrap();
    // until the curve is appended up to its last piece, the next move waits for room
    let mut full = stream.clone();
    full.push(&moves[0]).unwrap();
    full.push(&moves[1]).unwrap();
    let behind = full.push(&moves[2]);
    assert!(
        matches!(behind, Err(Error::CapacityExceeded { capacity: 8, required }) if required > 8),
        "{behind:?}"
    );
    assert_eq!(full.finish(), behind);
    assert_eq!(full.stats().moves, 2);
    let played = run_stream::<f64, 8, 64, _>(&mut stream, &moves, moves.len());
    let peaks = played.peaks(1000.0);
    let keep = 1.0 - PlanOptions::DEFAULT_FEED_SHARE;
    let slack = 1.0 + 1e-9;
    assert!(peaks[0] <= 200.0 * slack, "{peaks:?}");
    assert!(peaks[1] <= keep * 3000.0 * slack, "{peaks:?}");
    assert!(peaks[2] <= keep * 100_000.0 * slack, "{peaks:?}");
    assert!(
        played.seam[0] < 1e-9 && played.seam[1] < 1e-7,
        "{:?}",
        played.seam
    );
    assert_eq!((stream.stats().moves, stream.stats().starved), (3, 0));
    let length = strak_curves::arc_length(&spiral, 1e-9).unwrap();
    assert!(played.x.len() as f64 > length / 200.0 * 1000.0); // no faster than the limit
    assert!(played.x.last().unwrap().norm() < 1e-9);
}
