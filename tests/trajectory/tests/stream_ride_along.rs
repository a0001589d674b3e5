//! Axes that ride along a streamed path (an extruder E after X, Y, Z): checked from the
//! played ticks, the path's limits over the axes that shape it, the riding axis's own
//! velocity and acceleration limits, its proportion along each move, and the exact end.

use strak_curves::heapless::Deque;
use strak_curves::{Plane, Point, Turn};
use strak_trajectory::{
    AxisState, Error, Limits, Move, NoCurve, Number, Piece, PlanOptions, Q40, Shape, Stream,
    StreamOptions,
};

/// X, Y, Z shape the path; E rides along.
type Printer = Stream<4, 32, 256, NoCurve<4>, 1>;

const V: f64 = 200.0;
const A: f64 = 3000.0;
const J: f64 = 100_000.0;
const E_VELOCITY: f64 = 30.0;
const E_ACCELERATION: f64 = 1000.0;
const TOLERANCE: f64 = 0.05;

fn limits() -> Limits<4> {
    Limits::new(V, A, J)
        .and_then(|l| {
            l.with_axis_velocity([f64::INFINITY, f64::INFINITY, f64::INFINITY, E_VELOCITY])
        })
        .and_then(|l| {
            l.with_axis_acceleration([f64::INFINITY, f64::INFINITY, f64::INFINITY, E_ACCELERATION])
        })
        .unwrap()
}

/// A printed outline: lines, a half circle and a Bézier, extruding, then a travel move
/// that leaves E where it is.
fn outline() -> Vec<Move<4>> {
    let half = Shape::ArcCenter {
        center: [10.0, 20.0],
        plane: Plane::XY,
        turn: Turn::CounterClockwise,
    };
    let curve = Shape::Bezier {
        c1: [-5.0, 15.0, 0.2, 0.0],
        c2: [-5.0, 5.0, 0.4, 0.0],
    };
    vec![
        Move::line([20.0, 0.0, 0.0, 1.0]).with_feed(100.0),
        Move::line([20.0, 20.0, 0.0, 2.0]).with_feed(100.0),
        Move::new([0.0, 20.0, 0.0, 2.8], half).with_feed(80.0),
        Move::new([0.0, 0.0, 0.5, 3.5], curve).with_feed(80.0),
        Move::line([10.0, 0.0, 0.5, 3.5]),
    ]
}

/// The played ticks: positions, velocities and accelerations of the four axes.
#[derive(Default)]
struct Played {
    x: Vec<[f64; 4]>,
    v: Vec<[f64; 4]>,
    a: Vec<[f64; 4]>,
}

/// Streams `moves` (all pushed, then finished) and plays every piece by forward
/// differencing in `N`.
fn play<N: Number>(moves: &[Move<4>], limits: Limits<4>) -> (Played, Printer) {
    let options = StreamOptions::new(1000.0)
        .with_tolerance(TOLERANCE)
        .with_faster_stops(false);
    let mut stream = Printer::new([0.0; 4], limits, options).unwrap();
    let mut queue = Deque::<Piece<N, 4>, 64>::new();
    let (mut played, mut last, mut next) = (Played::default(), None, 0);
    for _ in 0..100_000 {
        while let Some(mv) = moves.get(next) {
            match stream.push(mv) {
                Ok(()) => next += 1,
                Err(Error::CapacityExceeded { .. } | Error::ZoneCapacityExceeded { .. }) => break,
                Err(e) => panic!("push {next}: {e:?}"),
            }
        }
        if next == moves.len() {
            let _ = stream.finish();
        }
        let ticks = stream.poll(&mut queue).unwrap();
        while let Some(piece) = queue.pop_front() {
            let mut state = *piece.axes();
            for _ in 0..piece.ticks() {
                played.x.push(state.map(|s| s.position.to_f64()));
                played.v.push(state.map(|s| s.velocity.to_f64()));
                played.a.push(state.map(|s| s.acceleration.to_f64()));
                state.iter_mut().for_each(AxisState::step);
            }
            last = Some(state);
        }
        if ticks == 0 && next == moves.len() && stream.is_idle() {
            let end = last.unwrap();
            played.x.push(end.map(|s| s.position.to_f64()));
            return (played, stream);
        }
    }
    panic!("the stream does not end");
}

fn xyz(p: [f64; 4]) -> [f64; 3] {
    [p[0], p[1], p[2]]
}

/// The largest path speed, acceleration and jerk (over X, Y, Z) and E velocity and
/// acceleration, from differences of the played ticks.
fn peaks(p: &Played) -> [f64; 5] {
    let mut out = [0.0_f64; 5];
    for k in 1..p.x.len().min(p.v.len()) {
        let dx = p.x[k].minus(p.x[k - 1]).times(1000.0);
        let dv = p.v[k].minus(p.v[k - 1]).times(1000.0);
        out[0] = out[0].max(xyz(dx).norm());
        out[1] = out[1].max(xyz(dv).norm());
        out[3] = out[3].max(dx[3].abs());
        out[4] = out[4].max(dv[3].abs());
    }
    for k in 1..p.a.len() {
        let da = p.a[k].minus(p.a[k - 1]).times(1000.0);
        out[2] = out[2].max(xyz(da).norm());
    }
    out
}

/// An outline with E riding along, in `f64`, `f32` and `Q40`: the path (X, Y, Z) keeps its
/// speed, acceleration and jerk limits, E its own velocity and acceleration limits, the
/// corners (blended, every one) stay within the tolerance, E never runs backwards while it extrudes (through the
/// blends too), and the motion ends exactly on the last move's end, E included.
#[test]
fn an_extruder_rides_along_within_its_limits() {
    fn check<N: Number>(slack: f64) {
        let moves = outline();
        let (played, stream) = play::<N>(&moves, limits());
        let keep = 1.0 - PlanOptions::DEFAULT_FEED_SHARE;
        let [v, a, j, ve, ae] = peaks(&played);
        println!(
            "{}: {} ticks, v {v:.3} a {a:.1} j {j:.0}, E v {ve:.3} a {ae:.2}, {:?}",
            N::NAME,
            played.x.len(),
            stream.stats()
        );
        assert!(v <= V * (1.0 + slack), "{} v {v}", N::NAME);
        assert!(a <= keep * A * (1.0 + slack), "{} a {a}", N::NAME);
        assert!(j <= keep * J * (1.0 + 100.0 * slack), "{} j {j}", N::NAME);
        assert!(ve <= E_VELOCITY * (1.0 + slack), "{} E v {ve}", N::NAME);
        assert!(
            ae <= keep * E_ACCELERATION * (1.0 + slack),
            "{} E a {ae}",
            N::NAME
        );
        let stats = stream.stats();
        assert!(
            stats.blends >= 3 && stats.max_deviation <= TOLERANCE,
            "{stats:?}"
        );
        let end = played.x.last().unwrap();
        assert_eq!(*end, moves[4].to.map(|x| N::from_f64(x).unwrap().to_f64()));
        let extruding = played.x.iter().take_while(|x| x[3] < 3.5 - 1e-9);
        let mut e = 0.0_f64;
        for x in extruding {
            assert!(
                x[3] >= e - 1e-6,
                "{}: E runs back to {} from {e}",
                N::NAME,
                x[3]
            );
            e = e.max(x[3]);
        }
    }
    check::<f64>(1e-9);
    check::<f32>(1e-3);
    check::<Q40>(1e-9);
}

/// Along a move, away from its blends, E is in proportion to the path's arc length: on the
/// first line (20 mm, E from 0 to 1) `E = x/20` at every tick between x = 2 and x = 15.
#[test]
fn the_extruder_goes_in_proportion_to_the_path() {
    let (played, _) = play::<f64>(&outline(), limits());
    let mut checked = 0;
    let first = played.x.iter().filter(|x| x[1] == 0.0 && x[2] == 0.0);
    for x in first.filter(|x| x[0] > 2.0 && x[0] < 15.0) {
        assert!((x[3] - x[0] / 20.0).abs() < 1e-12, "{x:?}");
        checked += 1;
    }
    assert!(checked > 50, "{checked}");
}

/// A move whose E travel is long for its path is slowed by E's limits: 10 mm of path with
/// 50 mm of E at most 30 mm/s of E moves the path at most 6 mm/s, and E's acceleration
/// limit bounds the path's acceleration to a fifth of it.
#[test]
fn the_extruder_limit_slows_the_path() {
    let moves = [Move::line([10.0, 0.0, 0.0, 50.0]).with_feed(100.0)];
    let (played, _) = play::<f64>(&moves, limits());
    let [v, a, _, ve, ae] = peaks(&played);
    println!(
        "{} ticks, path v {v:.3} a {a:.2}, E v {ve:.3} a {ae:.2}",
        played.x.len()
    );
    assert!(ve <= E_VELOCITY * (1.0 + 1e-9) && ve > 0.99 * E_VELOCITY);
    assert!(v <= E_VELOCITY / 5.0 * (1.0 + 1e-9));
    let keep = 1.0 - PlanOptions::DEFAULT_FEED_SHARE;
    assert!(ae <= keep * E_ACCELERATION * (1.0 + 1e-9) && ae > 0.9 * keep * E_ACCELERATION);
    assert!(a <= keep * E_ACCELERATION / 5.0 * (1.0 + 1e-9));
    assert!(played.x.len() > 1_666, "{}", played.x.len());
    assert_eq!(*played.x.last().unwrap(), [10.0, 0.0, 0.0, 50.0]);
}

/// A retraction and a prime, moves of E alone between extruding moves: the path stands
/// still while E moves at its feed (here 25 mm/s of E) within its limits, the motion comes
/// to rest before and after each, and it ends exactly where the program does.
#[test]
fn moves_of_the_riding_axis_alone_stand_the_path_still() {
    let moves = [
        Move::line([10.0, 0.0, 0.0, 0.5]).with_feed(100.0),
        Move::line([10.0, 0.0, 0.0, -1.5]).with_feed(25.0), // retract 2 mm
        Move::line([10.0, 10.0, 0.0, -1.5]),                // travel
        Move::line([10.0, 10.0, 0.0, 0.5]).with_feed(25.0), // prime
        Move::line([20.0, 10.0, 0.0, 1.0]).with_feed(100.0),
    ];
    for format in 0..3 {
        let (played, stream) = match format {
            0 => play::<f64>(&moves, limits()),
            1 => play::<f32>(&moves, limits()),
            _ => play::<Q40>(&moves, limits()),
        };
        let slack = if format == 1 { 1e-3 } else { 1e-9 };
        let keep = 1.0 - PlanOptions::DEFAULT_FEED_SHARE;
        let [v, a, j, ve, ae] = peaks(&played);
        println!(
            "{} ticks: v {v:.3} a {a:.1} j {j:.0}, E v {ve:.3} a {ae:.2}",
            played.x.len()
        );
        assert!(v <= V * (1.0 + slack) && a <= keep * A * (1.0 + slack));
        assert!(j <= keep * J * (1.0 + 100.0 * slack));
        assert!(ve <= 25.0 * (1.0 + slack) && ve > 24.0, "E v {ve}");
        assert!(ae <= keep * E_ACCELERATION * (1.0 + slack), "E a {ae}");
        assert_eq!(stream.stats().stops, 4);
        // while E retracts and primes (below 0) the path stands at (10, 0, 0) or (10, 10, 0)
        let moving_e = played
            .x
            .iter()
            .filter(|x| x[3] < -1e-6 && x[3] > -1.5 + 1e-6);
        let standing = |x: &[f64; 4]| {
            let on = |y: f64| (x[1] - y).abs() < 1e-5;
            (x[0] - 10.0).abs() < 1e-5 && x[2].abs() < 1e-5 && (on(0.0) || on(10.0))
        };
        assert!(moving_e.clone().count() > 50);
        assert!(moving_e.clone().all(standing));
        let end = *played.x.last().unwrap();
        assert!(end.minus([20.0, 10.0, 0.0, 1.0]).norm() < 1e-6, "{end:?}");
    }
}

/// A move that goes nowhere, a curve move (which shapes every axis) while E rides along,
/// and a stream whose axes all ride along (no path) are refused.
#[test]
fn moves_without_a_path_are_refused() {
    let options = StreamOptions::new(1000.0);
    let mut stream = Printer::new([0.0; 4], limits(), options).unwrap();
    assert_eq!(
        stream.push(&Move::line([0.0, 0.0, 0.0, 0.0])),
        Err(Error::DegenerateMove)
    );
    let all = Stream::<1, 8, 32, NoCurve<1>, 1>::new([0.0], Limits::new(V, A, J).unwrap(), options);
    assert!(matches!(all, Err(Error::AxisMismatch { .. })), "{all:?}");
}

/// Random extruding polylines (3 to 8 lines of 1 to 20 mm in X, Y, Z with 0 to 2 mm of E
/// each, some travel moves without E), in `f64`, `f32` and `Q40`: the path and E keep their
/// limits, E never runs backwards, and the motion ends exactly on the last point.
#[test]
fn random_extruding_polylines_keep_the_limits() {
    use proptest::prelude::*;
    use proptest::test_runner::{Config, TestRunner};
    let point = (
        -20.0..20.0_f64,
        -20.0..20.0_f64,
        0.0..2.0_f64,
        0.0..2.0_f64,
        any::<bool>(),
    );
    let strategy = proptest::collection::vec(point, 3..8);
    let mut runner = TestRunner::new(Config {
        cases: 24,
        ..Config::default()
    });
    runner
        .run(&strategy, |points| {
            let mut e = 0.0;
            let mut moves = Vec::new();
            for (x, y, z, de, travel) in points {
                if !travel {
                    e += de;
                }
                moves.push(Move::line([x, y, z, e]).with_feed(120.0));
            }
            for format in 0..3 {
                let (played, _) = match format {
                    0 => play::<f64>(&moves, limits()),
                    1 => play::<f32>(&moves, limits()),
                    _ => play::<Q40>(&moves, limits()),
                };
                let slack = if format == 1 { 1e-3 } else { 1e-9 };
                let keep = 1.0 - PlanOptions::DEFAULT_FEED_SHARE;
                let [v, a, j, ve, ae] = peaks(&played);
                prop_assert!(v <= V * (1.0 + slack), "v {}", v);
                prop_assert!(a <= keep * A * (1.0 + slack), "a {}", a);
                prop_assert!(j <= keep * J * (1.0 + 100.0 * slack), "j {}", j);
                prop_assert!(ve <= E_VELOCITY * (1.0 + slack), "E v {}", ve);
                prop_assert!(ae <= keep * E_ACCELERATION * (1.0 + slack), "E a {}", ae);
                let mut top = f64::NEG_INFINITY;
                for x in &played.x {
                    prop_assert!(x[3] >= top - 1e-5, "E runs back to {} from {}", x[3], top);
                    top = top.max(x[3]);
                }
                let want = moves.last().unwrap().to;
                let end = *played.x.last().unwrap();
                let dist = end.minus(want).norm();
                prop_assert!(dist <= 1e-5, "end {:?} want {:?}", end, want);
            }
            Ok(())
        })
        .unwrap();
}

/// The outline played by a [`StreamSampler`] with a feed override, a hold and a resume: the
/// feed ramps keep the path's machine limits over X, Y, Z and E's own limits (they use the
/// share of each the plan leaves free), and the motion ends on the last move's end.
#[test]
fn feed_changes_keep_the_riding_axis_within_its_limits() {
    use strak_curves::heapless::spsc::Queue;
    use strak_trajectory::StreamSampler;
    let moves = outline();
    let options = StreamOptions::new(1000.0)
        .with_tolerance(TOLERANCE)
        .with_faster_stops(false);
    let mut stream = Printer::new([0.0; 4], limits(), options).unwrap();
    for mv in &moves {
        stream.push(mv).unwrap();
    }
    stream.finish().unwrap();
    let mut queue = Queue::<Piece<f64, 4>, 64>::new();
    let (mut producer, consumer) = queue.split();
    let mut sampler = StreamSampler::new(consumer, &stream).unwrap();
    let mut samples = Vec::new();
    for tick in 0..20_000 {
        match tick {
            300 => sampler.set_feed(0.5),
            700 => sampler.hold(),
            1_000 => sampler.resume(),
            1_300 => sampler.set_feed(1.0),
            _ => {}
        }
        stream.poll(&mut producer).unwrap();
        samples.push(sampler.next());
        if tick > 1_300 && stream.is_idle() && sampler.is_holding() {
            break;
        }
    }
    let (mut v, mut a, mut j, mut ve, mut ae) = (0.0_f64, 0.0_f64, 0.0_f64, 0.0_f64, 0.0_f64);
    for w in samples.windows(2) {
        v = v.max(xyz(w[1].velocity).norm());
        a = a.max(xyz(w[1].acceleration).norm());
        j = j.max(xyz(w[1].acceleration.minus(w[0].acceleration)).norm() * 1000.0);
        ve = ve.max(w[1].velocity[3].abs());
        ae = ae.max(w[1].acceleration[3].abs());
    }
    println!(
        "{} ticks: v {v:.3} a {a:.1} j {j:.0}, E v {ve:.3} a {ae:.2}",
        samples.len()
    );
    assert!(v <= V * (1.0 + 1e-9) && a <= A * (1.0 + 1e-9) && j <= J * (1.0 + 1e-6));
    assert!(ve <= E_VELOCITY * (1.0 + 1e-9) && ae <= E_ACCELERATION * (1.0 + 1e-9));
    assert!(samples.len() > 2_000, "{}", samples.len());
    assert_eq!(samples.last().unwrap().position, moves[4].to);
}
