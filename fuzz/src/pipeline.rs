//! Plan → compile → play with fuzzed curves, limits, planner and compiler options, control
//! rates, number formats and feed events.
//!
//! The input chooses a small curve in `f64` (a line, a cubic Bézier curve, a polyline as a
//! degree-1 B-spline, a cubic B-spline, a Catmull-Rom spline, a natural cubic spline, a
//! NURBS circle; up to 8 points), a time law (S-curve and trapezoid plans, the global
//! trapezoid, constant speed, the parameter law), limits scaled to the curve's size (and
//! now and then of any magnitude), [`PlanOptions`], [`CompileOptions`], the rate and the
//! number format of the path (`f32`, `f64`, `Q40`) and up to four feed events. Plans of
//! more than [`MAX_TICKS`] ticks are not compiled. Invariants:
//!
//! * planning, compiling and playing never panic; a compile never fails with a blob's
//!   error ([`Error::CorruptBlob`]: its own path rejected by the path's validation);
//! * every sample is finite; the last is the curve's end point converted once into the
//!   sample type, with the path's end velocity (zero for planned laws) and acceleration;
//! * at feed 1 every sample is within the path's tolerance and playback bound of the exact
//!   `c(u(t))` at its tick (the time law stretched onto whole ticks);
//! * for the planned laws the limits hold in the samples ([`check::check_limits`] with
//!   [`Allowance`]): at feed 1 the planned limits; with feed events the machine's: the
//!   case's limits, or the compile's where those are higher (the feed ramp may use them;
//!   per axis the compile's path limit for an axis it gives no limit of its own). A compile
//!   whose plan left less than its feed share free fails
//!   ([`Error::FeedReserveExceeded`]), whether or not the plan reserved the share.

use strak_curves::{
    BSpline, Bezier, CubicSpline, HermiteSpline, Nurbs, ParamCurveDeriv, Parameterization, Point,
    Scalar, ScalarOf, SplineBoundary,
};
use strak_trajectory::{
    Along, CompileOptions, Error, Kernel, Limits, Number, ParameterTiming, Path, PathTiming,
    PlanOptions, ProfileShape, Q40, Sample, Timing, compile,
};

use crate::check::{self, Allowance, Bounds, FeedEvent, MAX_SAMPLES};
use crate::decode::Bytes;
use crate::dyn_curve::Dyn;
use crate::{Violation, violation};

/// Arc-length table size of the plans: more intervals than any curve here has pieces (at
/// most 7), and building the table is most of an execution (each interval costs two
/// adaptive integrals), so 16 samples run about 2.6 times as many executions as 64.
const TABLE: usize = 16;
/// Zone capacity of the plans.
const ZONES: usize = 64;
/// Piece capacity of the compiled paths.
pub const PIECES: usize = 64;

/// Plans of more ticks than this are not compiled: the compiler's check of every tick and
/// the harness's own (the accuracy against `c(u(t))`) each evaluate the time law once per
/// tick.
pub const MAX_TICKS: f64 = 5_000.0;

/// The harness.
///
/// # Errors
/// The first broken invariant, with the decoded case.
pub fn run(data: &[u8]) -> Result<(), Violation> {
    let mut b = Bytes::new(data);
    match b.choice(3) {
        0 => case::<1>(&mut b),
        1 => case::<2>(&mut b),
        _ => case::<3>(&mut b),
    }
}

/// The time laws.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Law {
    /// [`PathTiming::plan`] with [`ProfileShape::SCurve`].
    SCurve,
    /// [`PathTiming::plan`] with [`ProfileShape::Trapezoid`].
    PlannedTrapezoid,
    /// [`PathTiming::trapezoid`]: global speed and tangential acceleration only.
    Trapezoid,
    /// [`PathTiming::constant_speed`] (no limits promised).
    ConstantSpeed,
    /// [`ParameterTiming::over`] (no limits promised).
    Parameter,
}

/// One decoded case (printed with a violation).
#[derive(Clone, Debug)]
pub struct Case<const A: usize> {
    /// The curve kind (0 line … 6 circle) and its points.
    pub curve: (usize, Vec<[f64; A]>),
    /// The time law.
    pub law: Law,
    /// Velocity, acceleration and jerk limits.
    pub limits: (f64, f64, f64),
    /// Per-axis velocity limits.
    pub axis_velocity: Option<[f64; A]>,
    /// Per-axis acceleration limits.
    pub axis_acceleration: Option<[f64; A]>,
    /// Planner settings.
    pub plan: PlanOptions,
    /// Compiler settings (the feed share is also the reserve).
    pub compile: CompileOptions,
    /// The plan keeps `(1 − share)` of acceleration and jerk for feed changes.
    pub reserve: bool,
    /// Control rate.
    pub rate: f64,
    /// Number format: 0 f32, 1 f64, 2 Q40.
    pub number: usize,
    /// Feed events at fractions of the path's ticks.
    pub events: Vec<(f64, FeedEvent)>,
    /// Duration of the parameter law.
    pub duration: f64,
}

fn points<const A: usize>(b: &mut Bytes<'_>) -> Vec<[f64; A]> {
    let scale = b.magnitude(-2, 3);
    let offset = if b.one_in(16) { b.magnitude(3, 7) } else { 0.0 };
    let n = b.int(2, 8) as usize;
    (0..n)
        .map(|_| core::array::from_fn(|_| offset + b.coord(scale)))
        .collect()
}

fn extent<const A: usize>(p: &[[f64; A]]) -> f64 {
    (0..A)
        .map(|i| {
            let (lo, hi) = p
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), q| {
                    (l.min(q[i]), h.max(q[i]))
                });
            hi - lo
        })
        .fold(0.0, f64::max)
}

fn axis<const A: usize>(b: &mut Bytes<'_>, base: f64) -> Option<[f64; A]> {
    b.one_in(3).then(|| {
        core::array::from_fn(|_| match b.choice(8) {
            0 => f64::INFINITY,
            1 => b.raw(),
            _ => base * b.magnitude(-1, 0),
        })
    })
}

fn plan_options(b: &mut Bytes<'_>) -> PlanOptions {
    let mut o = PlanOptions::new().with_samples(b.int(0, 300) as usize);
    if b.one_in(2) {
        o = o.with_zone_tolerance(if b.one_in(8) {
            b.raw()
        } else {
            b.magnitude(-4, 0)
        });
    }
    if b.one_in(2) {
        o = o.with_centripetal_share(if b.one_in(8) { b.raw() } else { b.unit() });
    }
    if b.one_in(2) {
        o = o.with_corner_angle(b.positive(-6, 0));
    }
    o
}

fn compile_options<const A: usize>(
    b: &mut Bytes<'_>,
    size: f64,
    limits: (f64, f64, f64),
    axis_acceleration: Option<[f64; A]>,
) -> CompileOptions {
    let mut o = CompileOptions::new();
    // Mostly the tolerances of machining (10⁻⁹ to 10⁻³ of the size), now and then coarse.
    let coarse = if b.one_in(16) { 2 } else { 0 };
    match b.choice(3) {
        0 => o = o.with_tolerance(size * b.positive(-9, -3 + coarse)),
        1 => o = o.with_relative_tolerance(b.positive(-9, -3 + coarse)),
        _ => {}
    }
    if b.one_in(2) {
        o = o.with_max_piece_ticks(b.int(0, 600) as u32);
    }
    if b.one_in(2) {
        o = o.with_feed_share(if b.one_in(8) { b.raw() } else { b.unit() });
    }
    match b.choice(3) {
        // The machine's limits, as `CompileOptions::with_path_limits` gives them.
        0 => o
            .with_limits(limits.1, limits.2)
            .with_axis_acceleration(axis_acceleration.unwrap_or([f64::INFINITY; A])),
        1 => o.with_limits(b.positive(-3, 6), b.positive(-3, 9)),
        _ => o,
    }
}

fn events(b: &mut Bytes<'_>) -> Vec<(f64, FeedEvent)> {
    let n = if b.one_in(2) { b.int(1, 4) } else { 0 };
    let mut e: Vec<(f64, FeedEvent)> = (0..n)
        .map(|_| {
            let at = b.unit();
            let ev = match b.choice(4) {
                0 => FeedEvent::Hold,
                1 => FeedEvent::Resume,
                2 if b.one_in(4) => {
                    #[allow(clippy::cast_possible_truncation)]
                    let f = b.raw() as f32;
                    FeedEvent::Feed(f)
                }
                _ => {
                    #[allow(clippy::cast_possible_truncation)]
                    let f = b.unit() as f32;
                    FeedEvent::Feed(f)
                }
            };
            (at, ev)
        })
        .collect();
    e.sort_by(|x, y| x.0.total_cmp(&y.0));
    e
}

fn decode<const A: usize>(b: &mut Bytes<'_>) -> Case<A> {
    let kind = b.choice(7);
    let pts = points::<A>(b);
    let size = extent(&pts).max(1e-9);
    let law = match b.choice(5) {
        0 | 1 => Law::SCurve,
        2 => Law::PlannedTrapezoid,
        3 => Law::Trapezoid,
        _ => [Law::ConstantSpeed, Law::Parameter][b.choice(2)],
    };
    let limits = if b.one_in(16) {
        (
            b.positive(-300, 300),
            b.positive(-300, 300),
            b.positive(-300, 300),
        )
    } else {
        let v = size * b.positive(-1, 3);
        let a = v * b.positive(-1, 3);
        (v, a, a * b.positive(-1, 4))
    };
    let axis_velocity = axis(b, limits.0);
    let axis_acceleration = axis(b, limits.1);
    let plan = plan_options(b);
    let compile = compile_options(b, size, limits, axis_acceleration);
    let rate = match b.choice(6) {
        0 => 1_000.0,
        1 => 10_000.0,
        2 => 100.0,
        3 => 100_000.0,
        4 if b.one_in(4) => b.raw(),
        _ => b.int(100, 100_000) as f64,
    };
    Case {
        curve: (kind, pts),
        law,
        limits,
        axis_velocity,
        axis_acceleration,
        plan,
        compile,
        reserve: b.one_in(2),
        rate,
        number: b.choice(3),
        events: events(b),
        duration: b.positive(-3, 1),
    }
}

fn case<const A: usize>(b: &mut Bytes<'_>) -> Result<(), Violation> {
    let case = decode::<A>(b);
    with_curve(&case).map_err(|v| violation!("{v}\n  case: {case:?}"))
}

/// Builds the case's curve (a rejected curve is no case) and runs the pipeline on it.
fn with_curve<const A: usize>(case: &Case<A>) -> Result<(), Violation> {
    let p = &case.curve.1;
    let chord = Parameterization::ChordLength;
    match case.curve.0 {
        0 => Bezier::new([p[0], p[1]]).map_or(Ok(()), |c| by_number(&Dyn(&c), case)),
        1 => {
            let q: [[f64; A]; 4] = core::array::from_fn(|i| p[i.min(p.len() - 1)]);
            Bezier::new(q).map_or(Ok(()), |c| by_number(&Dyn(&c), case))
        }
        2 => BSpline::<_, 8, 12>::clamped_uniform(1, p, 0.0, 1.0)
            .map_or(Ok(()), |c| by_number(&Dyn(&c), case)),
        3 => BSpline::<_, 8, 12>::clamped_uniform(3, p, 0.0, 1.0)
            .map_or(Ok(()), |c| by_number(&Dyn(&c), case)),
        4 => HermiteSpline::<_, 8>::catmull_rom(p, chord)
            .map_or(Ok(()), |c| by_number(&Dyn(&c), case)),
        5 => CubicSpline::<_, 8>::new(p, chord, SplineBoundary::Natural)
            .map_or(Ok(()), |c| by_number(&Dyn(&c), case)),
        _ => {
            let r = p[1][0].abs();
            Nurbs::<[f64; A], 9, 12>::circle(p[0], r).map_or(Ok(()), |c| by_number(&Dyn(&c), case))
        }
    }
}

fn by_number<const A: usize>(curve: &Dyn<'_, [f64; A]>, case: &Case<A>) -> Result<(), Violation> {
    match case.number {
        0 => pipeline::<f32, A>(curve, case),
        1 => pipeline::<f64, A>(curve, case),
        _ => pipeline::<Q40, A>(curve, case),
    }
}

/// The planned limits and what the samples must keep (the machine's limits).
fn limits<const A: usize>(case: &Case<A>) -> Option<(Limits<A>, Bounds<A>)> {
    let (v, a, j) = case.limits;
    let share = case.compile.feed_share();
    let keep = if case.reserve { 1.0 - share } else { 1.0 };
    let axis_v = case.axis_velocity.unwrap_or([f64::INFINITY; A]);
    let axis_a = case.axis_acceleration.unwrap_or([f64::INFINITY; A]);
    let planned = Limits::new(v, a * keep, j * keep)
        .and_then(|l| l.with_axis_velocity(axis_v))
        .and_then(|l| l.with_axis_acceleration(axis_a.map(|x| x * keep)))
        .ok()?;
    Limits::<A>::new(v, a, j).ok()?;
    let bounds = Bounds {
        velocity: v,
        acceleration: a,
        jerk: (case.law == Law::SCurve).then_some(j),
        axis_velocity: axis_v,
        axis_acceleration: axis_a,
        tangential: false,
    };
    Some((planned, bounds))
}

fn pipeline<N: Kernel, const A: usize>(
    curve: &Dyn<'_, [f64; A]>,
    case: &Case<A>,
) -> Result<(), Violation> {
    let Some((planned, mut bounds)) = limits(case) else {
        return Ok(());
    };
    let v = case.limits.0;
    let timing: Box<dyn Timing + '_> = match case.law {
        Law::SCurve | Law::PlannedTrapezoid => {
            let shape = if case.law == Law::SCurve {
                ProfileShape::SCurve
            } else {
                ProfileShape::Trapezoid
            };
            let options = case.plan.with_shape(shape);
            match PathTiming::<_, TABLE, ZONES>::plan(curve, &planned, &options) {
                Ok(t) => Box::new(t),
                Err(_) => return Ok(()),
            }
        }
        Law::Trapezoid => {
            bounds.axis_velocity = [f64::INFINITY; A];
            bounds.axis_acceleration = [f64::INFINITY; A];
            bounds.tangential = true;
            match PathTiming::<_, TABLE, ZONES>::trapezoid(curve, v, planned.acceleration()) {
                Ok(t) => Box::new(t),
                Err(_) => return Ok(()),
            }
        }
        Law::ConstantSpeed => match PathTiming::<_, TABLE, ZONES>::constant_speed(curve, v) {
            Ok(t) => Box::new(t),
            Err(_) => return Ok(()),
        },
        Law::Parameter => match ParameterTiming::over(curve, case.duration) {
            Ok(t) => Box::new(t),
            Err(_) => return Ok(()),
        },
    };
    let duration = timing.duration();
    if !(duration.is_finite() && duration > 0.0) {
        return Err(violation!("a planned time law of duration {duration}"));
    }
    if !(duration * case.rate <= MAX_TICKS) {
        return Ok(());
    }
    let path =
        match compile::<N, A, PIECES, _>(&Along::new(curve, &*timing), case.rate, &case.compile) {
            Ok(path) => path,
            // A serialized blob's error: a compile that returns it names the wrong cause.
            Err(e @ Error::CorruptBlob) => {
                return Err(violation!("{}: compile returned {e:?} ({e})", N::NAME));
            }
            Err(_) => return Ok(()),
        };
    let limited = matches!(
        case.law,
        Law::SCurve | Law::PlannedTrapezoid | Law::Trapezoid
    );
    let rest_to_rest = limited;
    let ticks = f64::from(path.ticks());
    // A path without a feed reserve takes its feed changes when a `FeedGuard` schedules
    // them (tested in `tests/trajectory/tests/trajectory_feed_guard.rs` and by strak-sim's
    // random feed jobs), not at the case's ticks: it plays without events here.
    let reserved = path.feed_share() > 0.0;
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let events: Vec<(u64, FeedEvent)> = case
        .events
        .iter()
        .filter(|_| reserved)
        .map(|(at, e)| ((at * ticks) as u64, *e))
        .collect();
    // With feed events the machine's limits hold: the case's, or the compile's where those
    // are higher (the feed ramp may use them; per axis the compile's path limit where it
    // gives none for the axis).
    if !events.is_empty()
        && let Some((a, j)) = case.compile.limits()
    {
        bounds.acceleration = bounds.acceleration.max(a);
        bounds.jerk = bounds.jerk.map(|b| b.max(j));
        let given = case.compile.axis_acceleration();
        for (b, g) in bounds.axis_acceleration.iter_mut().zip(given) {
            *b = b.max(if g.is_finite() { g } else { a });
        }
    }
    let bounds = limited.then_some(&bounds);
    check_compiled(curve, &*timing, &path, &events, bounds, rest_to_rest)
}

/// The coordinates of a point in `f64`.
fn coords<P: Point, const A: usize>(p: P) -> [f64; A] {
    core::array::from_fn(|i| p.coord(i).to_f64())
}

/// Checks a compiled path against its curve and time law, then plays it with `events`
/// (wall-clock ticks; a resume and feed 1 are appended after the last, so that the motion
/// finishes): the exact end (the curve's end point converted once into the sample type; at
/// rest when `rest_to_rest`), the end's agreement with the last piece, finite samples, at
/// feed 1 the accuracy against `c(u(t))`, and `bounds` in the samples.
///
/// # Errors
/// The first broken invariant.
pub fn check_compiled<N: Kernel, C: ParamCurveDeriv, const A: usize, const P: usize>(
    curve: &C,
    timing: &dyn Timing,
    path: &Path<N, A, P>,
    events: &[(u64, FeedEvent)],
    bounds: Option<&Bounds<A>>,
    rest_to_rest: bool,
) -> Result<(), Violation> {
    let end: [f64; A] = coords(curve.eval(curve.domain().1));
    if path.end_position().map(Some) != end.map(N::out_from_f64) {
        return Err(violation!(
            "{}: the path's end {:?} is not the curve's end {end:?}",
            N::NAME,
            path.end_position()
        ));
    }
    let zero = <N::Out as Scalar>::ZERO;
    if rest_to_rest && path.end_velocity() != [zero; A] {
        return Err(violation!(
            "{}: a rest-to-rest path ends at v {:?}",
            N::NAME,
            path.end_velocity()
        ));
    }
    check::check_end_agrees(path)?;
    let last = events
        .iter()
        .map(|e| e.0)
        .max()
        .unwrap_or(0)
        .max(u64::from(path.ticks()));
    let mut all = events.to_vec();
    all.extend([
        (last + 1, FeedEvent::Resume),
        (last + 1, FeedEvent::Feed(1.0)),
    ]);
    let all = if events.is_empty() { &[][..] } else { &all[..] };
    let played = check::play(path, all, MAX_SAMPLES)?;
    if events.is_empty() {
        accuracy(curve, timing, path, &played.samples)?;
    }
    match bounds {
        Some(bounds) => {
            let allow = Allowance::of(path, &played.samples);
            check::check_limits(&played.samples, path.rate(), bounds, &allow)
                .map_err(|v| violation!("{} path of {} ticks: {v}", N::NAME, path.ticks()))
        }
        None => Ok(()),
    }
}

/// Every sample within `tolerance + playback bound` (and the rounding of the sample type)
/// of `c(u(k·D/N))`, the time law stretched by the compiler onto `N` whole ticks.
fn accuracy<N: Number, C: ParamCurveDeriv, const A: usize, const P: usize>(
    curve: &C,
    timing: &dyn Timing,
    path: &Path<N, A, P>,
    samples: &[Sample<f64, A>],
) -> Result<(), Violation> {
    let n = f64::from(path.ticks());
    let d = timing.duration();
    for s in samples {
        #[allow(clippy::cast_precision_loss)]
        let t = d * (s.tick as f64) / n;
        let u = ScalarOf::<C>::from_f64(timing.param(t).0).unwrap_or(curve.domain().1);
        let want: [f64; A] = coords(curve.eval(u));
        for (i, (x, w)) in s.position.iter().zip(want).enumerate() {
            let allowed =
                path.tolerance() + path.playback_bound() + 2.0 * check::resolution::<N>(w.abs());
            let err = (x - w).abs();
            if !(err <= allowed * (1.0 + 1e-9)) {
                return Err(violation!(
                    "{}: tick {} axis {i}: position {x} is {err:e} from c(u(t)) = {w} \
                     (tolerance {:e}, playback bound {:e})",
                    N::NAME,
                    s.tick,
                    path.tolerance(),
                    path.playback_bound()
                ));
            }
        }
    }
    Ok(())
}
