//! Every curve kind in every number format, planned at the limits, compiled and played in
//! full: the speed, acceleration and jerk measured from the samples stay within the limits
//! the plan was made with.
//!
//! * **Curves:** degree-1 B-spline polylines with corners of 5° to 179° (unequal segments),
//!   a cubic Bézier curve, a Bézier chain, a cubic B-spline, NURBS (a weighted spline and the
//!   circle), a Hermite spline and a Catmull-Rom spline (C¹ joins), an interpolating cubic
//!   spline, a Lagrange curve, a parabolic blend and a power-basis spline.
//! * **Number formats:** the curve in `f64` played in `f64`, `f32` and `Q40`; the curve in
//!   `f32` played in `f32`; the curve in `I32F32` played in `Q40` (the pairs `strak-sim`
//!   uses).
//! * **Laws:** [`PathTiming::plan`] with the S-curve (limits `v`, `a`, `j`) and with the
//!   trapezoid (`v`, `a`; no jerk limit), at 1 kHz and 10 kHz, compiled with the default
//!   options.
//!
//! Measured by [`strak_trajectory_tests::limits_check`]: `‖v_k‖`, `‖x_{k+1} − x_k‖/T`, `‖a_k‖`,
//! `‖v_{k+1} − v_k‖/T` and `‖a_{k+1} − a_k‖/T` over every tick, against the limits plus the
//! playback-rounding allowance of the path's number format (finite differences of one tick
//! add nothing above the motion's own peaks, see the module docs there for the derivation).
//! The compiled time scale (the slow-down the compiler applied to keep the limits) is
//! printed with `--nocapture`.
//!
//! The cases the issue measured are reproduced first (`line_with_short_jerk_phases`,
//! `polyline_in_f32_and_fixed_point`, `jerk_phases_shorter_than_a_tick`,
//! `velocity_limit_that_overflows_the_ticks`).

use std::fmt::Write as _;

use strak_curves::{
    BSpline, Bezier, BezierChain, CircularArc, CubicSpline, HermiteSpline, I32F32, LagrangeCurve,
    Nurbs, ParabolicBlend, ParamCurveDeriv, Parameterization, Plane, Point, PowerSpline, Scalar,
    SplineBoundary, Turn,
};
use strak_trajectory::{
    Along, CompileOptions, Error, Kernel, Limits, Move, Path, PathTiming, PlanOptions,
    ProfileShape, Q40, Quantity, Shape, Toolpath,
};
use strak_trajectory_tests::compile_boxed;
use strak_trajectory_tests::limits_check::measure;

/// Piece capacity of the compiled paths.
const PIECES: usize = 4096;
/// Arc-length table size and zone capacity of the plans.
const TABLE: usize = 512;
const ZONES: usize = 256;
/// The control rates.
const RATES: [f64; 2] = [1_000.0, 10_000.0];
/// The path limits (mm, s): speed, acceleration, jerk.
const LIMITS: (f64, f64, f64) = (200.0, 2_000.0, 50_000.0);

/// Waypoints of a 3-axis move (mm).
const WAYPOINTS: [[f64; 3]; 6] = [
    [0.0, 0.0, 0.0],
    [5.0, 2.0, 20.0],
    [30.0, 15.0, 30.0],
    [60.0, 35.0, 30.0],
    [85.0, 48.0, 20.0],
    [90.0, 50.0, 0.0],
];

/// The points as `[S; D]`.
fn points<S: Scalar, const D: usize>(points: &[[f64; D]]) -> Vec<[S; D]> {
    points
        .iter()
        .map(|p| <[S; D]>::from_f64_slice(p).expect("test point fits the scalar"))
        .collect()
}

/// A zig-zag polyline in the plane: 9 points, the heading turning by `±angle` (degrees) at
/// every corner, segments of unequal length, away from the origin.
fn zigzag(angle: f64) -> Vec<[f64; 2]> {
    const LENGTHS: [f64; 8] = [40.0, 12.0, 55.0, 25.0, 7.0, 48.0, 30.0, 18.0];
    let mut p = vec![[120.0, -35.0]];
    let mut heading = 0.3_f64;
    for (i, len) in LENGTHS.into_iter().enumerate() {
        let last = p[i];
        p.push([last[0] + len * heading.cos(), last[1] + len * heading.sin()]);
        let turn = if i % 2 == 0 { angle } else { -angle };
        heading += turn.to_radians();
    }
    p
}

/// One measured run, or why there is none.
struct Run {
    line: String,
    failure: Option<String>,
    /// The compiler refused the S-curve: its pieces would exceed the jerk limit.
    jerk_refused: bool,
}

/// Plans `shape` on `curve` at `rate`, compiles into `N`, plays, measures and checks.
fn run<N: Kernel, C, const D: usize>(name: &str, curve: &C, shape: ProfileShape, rate: f64) -> Run
where
    C: ParamCurveDeriv,
    C::Point: Point,
{
    run_zones::<N, C, D, ZONES>(name, curve, shape, rate)
}

/// [`run`] with a plan of `Z` zones.
fn run_zones<N: Kernel, C, const D: usize, const Z: usize>(
    name: &str,
    curve: &C,
    shape: ProfileShape,
    rate: f64,
) -> Run
where
    C: ParamCurveDeriv,
    C::Point: Point,
{
    let (v, a, j) = LIMITS;
    let limits = Limits::<D>::new(v, a, j).expect("limits");
    let what = format!(
        "{name:>22} {:>6}/{:<3} {shape:?} {rate} Hz",
        <<C::Point as Point>::Scalar as Scalar>::NAME,
        N::NAME
    );
    let options = PlanOptions::new().with_shape(shape);
    let plan = match PathTiming::<_, TABLE, Z>::plan(curve, &limits, &options) {
        Ok(p) => p,
        Err(e) => return failed(what, format!("plan: {e:?}")),
    };
    let compiled: Result<Box<Path<N, D, PIECES>>, Error> = compile_boxed(
        &Along::new(curve, &plan),
        rate,
        &CompileOptions::new().with_path_limits(&limits),
    );
    let path = match compiled {
        Ok(p) => p,
        Err(e) => {
            let mut run = failed(what, format!("compile: {e:?}"));
            run.jerk_refused = e
                == Error::LimitExceeded {
                    quantity: Quantity::Jerk,
                };
            return run;
        }
    };
    let jerk = match shape {
        ProfileShape::SCurve => j,
        ProfileShape::Trapezoid => f64::INFINITY,
    };
    let k = measure(&path);
    let r = k.ratios(v, a, jerk);
    let line = format!(
        "{what}: time scale {:.5}, v {:.5} a {:.5} j {:.5} of the limits ({} pieces)",
        path.time_scale(),
        r.velocity,
        r.acceleration,
        r.jerk,
        path.pieces().len()
    );
    let failure = k.check(v, a, jerk).err().map(|e| format!("{what}:\n{e}"));
    Run {
        line,
        failure,
        jerk_refused: false,
    }
}

fn failed(what: String, why: String) -> Run {
    Run {
        line: format!("{what}: {why}"),
        failure: Some(format!("{what}: {why}")),
        jerk_refused: false,
    }
}

/// Collects the runs of one curve kind; panics with every failure at the end.
#[derive(Default)]
struct Report {
    failures: String,
    /// The curves have C¹ joins where the curvature jumps: the S-curve's jerk bound assumes
    /// a curvature-continuous path ([`PathTiming::plan`]), and at a join the acceleration
    /// steps by `v²·Δκ`; the compiler either keeps the limits (slowing down) or refuses
    /// with [`Error::LimitExceeded`] for the jerk, never exceeds them.
    c1_joins: bool,
    refused: usize,
}

impl Report {
    fn with_c1_joins() -> Self {
        Report {
            c1_joins: true,
            ..Report::default()
        }
    }

    fn add(&mut self, run: Run) {
        println!("{}", run.line);
        if run.jerk_refused && self.c1_joins {
            self.refused += 1;
        } else if let Some(f) = run.failure {
            let _ = writeln!(self.failures, "{f}");
        }
    }

    fn finish(self) {
        if self.refused > 0 {
            println!(
                "{} S-curve runs refused for the jerk at C¹ joins",
                self.refused
            );
        }
        assert!(
            self.failures.is_empty(),
            "limits exceeded:\n{}",
            self.failures
        );
    }
}

/// Runs both laws at both rates for the curve built in each format pair: `$build` is an
/// expression of the curve's scalar type `$s` and of the number `$arg` (given as `$value`).
macro_rules! every_format {
    ($report:expr, $name:expr, $dim:literal, $value:expr, |$s:ident, $arg:ident| $build:expr) => {{
        fn all<$s: Scalar, N: Kernel>(report: &mut Report, name: &str, $arg: f64) {
            let curve = $build;
            for shape in [ProfileShape::SCurve, ProfileShape::Trapezoid] {
                for rate in RATES {
                    report.add(run::<N, _, $dim>(name, &curve, shape, rate));
                }
            }
        }
        all::<f64, f64>(&mut $report, $name, $value);
        all::<f64, f32>(&mut $report, $name, $value);
        all::<f64, Q40>(&mut $report, $name, $value);
        all::<f32, f32>(&mut $report, $name, $value);
        all::<I32F32, Q40>(&mut $report, $name, $value);
    }};
    ($report:expr, $name:expr, $dim:literal, |$s:ident| $build:expr) => {
        every_format!($report, $name, $dim, 0.0, |$s, _unused| $build)
    };
}

// ---------------------------------------------------------------------------------------------
// The cases measured in the issue
// ---------------------------------------------------------------------------------------------

/// A straight line of 73.9 units with jerk phases of 4.25 ticks at 1 kHz: the compiled
/// spline reached 21.67 units/s against 21.23 (knots only on breaks 8 ticks apart).
#[test]
fn line_with_short_jerk_phases() {
    let d = 73.9 / 3f64.sqrt();
    let line = Bezier::new([[0.0, 0.0, 0.0], [d, d, d]]).expect("line");
    let (v, a, j) = (21.23, 823.0, 193_600.0);
    let limits = Limits::<3>::new(v, a, j).expect("limits");
    let plan = PathTiming::<_, TABLE, ZONES>::scurve(&line, &limits).expect("plan");
    let options = CompileOptions::new().with_path_limits(&limits);
    let path: Box<Path<f64, 3, PIECES>> =
        compile_boxed(&Along::new(&line, &plan), 1_000.0, &options).expect("compile");
    let k = measure(&path);
    println!(
        "line: {:?}, time scale {}",
        k.ratios(v, a, j),
        path.time_scale()
    );
    if let Err(e) = k.check(v, a, j) {
        panic!("{e}");
    }
}

/// The polyline of the issue (a degree-1 B-spline through 21 points with 90° and 30°
/// corners and unequal segments), with the curve in `f32` and in `I32F32`: the arc-length
/// table took the left-sided speed at a knot from the wrong piece (two `f64` units below
/// the knot round back onto it in the coarser scalar), and the time law's acceleration
/// reached 5–6 × the limit, its jerk 50–200 ×.
#[test]
fn polyline_in_f32_and_fixed_point() {
    let mut p = vec![[137.25, 81.5]];
    let mut heading = 0.0_f64;
    let mut seed = 0x2545_f491_4f6c_dd1d_u64;
    for i in 1..21 {
        seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        #[allow(clippy::cast_precision_loss)]
        let len = 2.0 + 98.0 * ((seed >> 11) as f64 / (1_u64 << 53) as f64);
        let last: [f64; 2] = p[i - 1];
        p.push([last[0] + len * heading.cos(), last[1] + len * heading.sin()]);
        heading += if i % 2 == 1 { 90.0_f64 } else { -30.0 }.to_radians();
    }
    let mut report = Report::default();
    fn one<S: Scalar, N: Kernel>(report: &mut Report, p: &[[f64; 2]]) {
        let pts = points::<S, 2>(p);
        let c =
            BSpline::<[S; 2], 32, 40>::clamped_uniform(1, &pts, S::ZERO, S::ONE).expect("polyline");
        report.add(run::<N, _, 2>(
            "issue polyline",
            &c,
            ProfileShape::SCurve,
            1_000.0,
        ));
    }
    one::<f32, f32>(&mut report, &p);
    one::<I32F32, Q40>(&mut report, &p);
    one::<f64, f32>(&mut report, &p);
    report.finish();
}

/// A jerk limit so high that the jerk phases last far less than a tick: the compiled
/// acceleration reached 1.4 × its limit.
#[test]
fn jerk_phases_shorter_than_a_tick() {
    let line = Bezier::new([[0.0, 0.0], [30.0, 40.0]]).expect("line");
    let (v, a, j) = (100.0, 1_000.0, 1e9);
    let limits = Limits::<2>::new(v, a, j).expect("limits");
    let plan = PathTiming::<_, TABLE, ZONES>::scurve(&line, &limits).expect("plan");
    for rate in RATES {
        let options = CompileOptions::new().with_path_limits(&limits);
        let path: Box<Path<f64, 2, PIECES>> =
            compile_boxed(&Along::new(&line, &plan), rate, &options).expect("compile");
        let k = measure(&path);
        println!(
            "{rate} Hz: {:?}, time scale {}",
            k.ratios(v, a, j),
            path.time_scale()
        );
        if let Err(e) = k.check(v, a, j) {
            panic!("{rate} Hz: {e}");
        }
    }
}

/// A velocity limit of 1.5·10⁻³⁰⁴: the plan's duration times the rate overflows, which
/// compiled to a one-tick path; it is too long for a `u32` tick count, and the planner says
/// so (it knows its rate).
#[test]
fn velocity_limit_that_overflows_the_ticks() {
    let line = Bezier::new([[0.0, 0.0], [30.0, 40.0]]).expect("line");
    let limits = Limits::<2>::new(1.5e-304, 1_000.0, 10_000.0).expect("limits");
    let plan = PathTiming::<_, TABLE, ZONES>::scurve(&line, &limits);
    assert_eq!(plan.err(), Some(Error::TooLong));
}

// ---------------------------------------------------------------------------------------------
// Every curve kind
// ---------------------------------------------------------------------------------------------

#[test]
fn polylines_with_corners_from_5_to_179_degrees() {
    let mut report = Report::default();
    for angle in [
        5.0, 15.0, 30.0, 45.0, 60.0, 90.0, 120.0, 150.0, 170.0, 179.0,
    ] {
        let name = format!("polyline {angle}°");
        every_format!(report, &name, 2, angle, |S, angle| {
            let pts = points::<S, 2>(&zigzag(angle));
            BSpline::<[S; 2], 16, 24>::clamped_uniform(1, &pts, S::ZERO, S::ONE).expect("polyline")
        });
    }
    report.finish();
}

#[test]
fn helix_and_full_circle() {
    let mut report = Report::default();
    every_format!(report, "helix", 3, |S| {
        let p = points::<S, 3>(&[[65.0, 25.0, 0.0], [25.0, 25.0, 30.0]]);
        let center = points::<S, 2>(&[[45.0, 25.0]])[0];
        let tolerance = S::from_f64(1e-6).expect("tolerance");
        CircularArc::with_center(
            p[0],
            p[1],
            center,
            Plane::XY,
            Turn::CounterClockwise,
            tolerance,
        )
        .expect("helix")
    });
    every_format!(report, "full circle", 2, |S| {
        let p = points::<S, 2>(&[[40.0, 5.0], [40.0, -20.0]]);
        CircularArc::with_center(p[0], p[0], p[1], Plane::XY, Turn::Clockwise, S::ZERO)
            .expect("circle")
    });
    report.finish();
}

/// Moves with their corners blended within 0.05 mm (`strak_trajectory::Toolpath`, an `f64`
/// curve, played in every number format): lines turning by 5°, 150° and between, a line
/// into a tangent arc (a curvature step), a helix, a Bézier, a reversal (an exact stop).
#[test]
fn blended_moves() {
    let mut moves: Vec<Move<3>> = zigzag(5.0)[1..5]
        .iter()
        .chain(&zigzag(150.0)[3..7])
        .map(|p| Move::line([p[0], p[1], 0.0]))
        .collect();
    let corner = moves.last().expect("moves").to;
    let arc_end = [corner[0] + 10.0, corner[1] + 10.0, 5.0];
    let center = [corner[0], corner[1] + 10.0];
    let ccw = Shape::ArcCenter {
        center,
        plane: Plane::XY,
        turn: Turn::CounterClockwise,
    };
    moves.push(Move::new(arc_end, ccw));
    moves.push(Move::line([arc_end[0], arc_end[1] + 20.0, 5.0]));
    let b = [arc_end[0] + 10.0, arc_end[1] + 30.0, 0.0];
    moves.push(Move::new(
        b,
        Shape::Bezier {
            c1: [arc_end[0], arc_end[1] + 30.0, 5.0],
            c2: [b[0] - 5.0, b[1], 0.0],
        },
    ));
    moves.push(Move::line([b[0] - 10.0, b[1], 0.0]));
    let path = Toolpath::<3, 32>::new([120.0, -35.0, 0.0], &moves, 0.05, 1e-9).expect("toolpath");
    assert!(path.blends() >= moves.len() - 3, "{} blends", path.blends());
    let mut report = Report::default();
    for shape in [ProfileShape::SCurve, ProfileShape::Trapezoid] {
        for rate in RATES {
            report.add(run_zones::<f64, _, 3, 1024>(
                "blended moves",
                &path,
                shape,
                rate,
            ));
            report.add(run_zones::<f32, _, 3, 1024>(
                "blended moves",
                &path,
                shape,
                rate,
            ));
            report.add(run_zones::<Q40, _, 3, 1024>(
                "blended moves",
                &path,
                shape,
                rate,
            ));
        }
    }
    report.finish();
}

#[test]
fn bezier() {
    let mut report = Report::default();
    every_format!(report, "Bézier", 3, |S| {
        let pts = points::<S, 3>(&WAYPOINTS[..4]);
        Bezier::<[S; 3], 4>::new([pts[0], pts[1], pts[2], pts[3]]).expect("Bézier")
    });
    report.finish();
}

#[test]
fn bezier_chain() {
    let mut report = Report::with_c1_joins();
    every_format!(report, "Bézier chain", 3, |S| {
        // two cubic segments joined C¹ at the fourth point
        let w = [
            WAYPOINTS[0],
            WAYPOINTS[1],
            WAYPOINTS[2],
            [45.0, 25.0, 30.0],
            [60.0, 35.0, 30.0],
            WAYPOINTS[4],
            WAYPOINTS[5],
        ];
        BezierChain::<[S; 3], 4, 4>::new(&points::<S, 3>(&w)).expect("chain")
    });
    report.finish();
}

#[test]
fn bspline() {
    let mut report = Report::default();
    every_format!(report, "cubic B-spline", 3, |S| {
        BSpline::<[S; 3], 8, 12>::clamped_uniform(3, &points::<S, 3>(&WAYPOINTS), S::ZERO, S::ONE)
            .expect("B-spline")
    });
    report.finish();
}

#[test]
fn nurbs() {
    let mut report = Report::with_c1_joins();
    every_format!(report, "NURBS", 3, |S| {
        let w: Vec<S> = points::<S, 1>(&[[1.0], [2.0], [0.5], [1.5], [1.0], [1.0]])
            .into_iter()
            .map(|[x]| x)
            .collect();
        Nurbs::<[S; 3], 8, 12>::clamped_uniform(2, &points::<S, 3>(&WAYPOINTS), &w, S::ZERO, S::ONE)
            .expect("NURBS")
    });
    every_format!(report, "NURBS circle", 2, |S| {
        let center = points::<S, 2>(&[[40.0, -20.0]])[0];
        Nurbs::<[S; 2], 9, 12>::circle(center, S::from_f64(25.0).expect("radius")).expect("circle")
    });
    report.finish();
}

#[test]
fn hermite_spline_c1_joins() {
    let mut report = Report::with_c1_joins();
    every_format!(report, "Hermite spline", 3, |S| {
        let tangents = [
            [0.0, 0.0, 1.0],
            [0.5, 0.2, 0.8],
            [0.85, 0.5, 0.1],
            [0.85, 0.5, -0.1],
            [0.5, 0.2, -0.8],
            [0.0, 0.0, -1.0],
        ];
        HermiteSpline::<[S; 3], 8>::new(
            &points::<S, 3>(&WAYPOINTS),
            &points::<S, 3>(&tangents),
            Parameterization::ChordLength,
        )
        .expect("Hermite spline")
    });
    report.finish();
}

#[test]
fn catmull_rom_c1_joins() {
    let mut report = Report::with_c1_joins();
    every_format!(report, "Catmull-Rom", 3, |S| {
        HermiteSpline::<[S; 3], 8>::catmull_rom(
            &points::<S, 3>(&WAYPOINTS),
            Parameterization::Centripetal,
        )
        .expect("Catmull-Rom")
    });
    report.finish();
}

#[test]
fn interpolating_cubic_spline() {
    let mut report = Report::default();
    every_format!(report, "cubic spline", 3, |S| {
        CubicSpline::<[S; 3], 8>::new(
            &points::<S, 3>(&WAYPOINTS),
            Parameterization::ChordLength,
            SplineBoundary::Natural,
        )
        .expect("cubic spline")
    });
    report.finish();
}

#[test]
fn lagrange_and_power_basis() {
    let mut report = Report::default();
    every_format!(report, "Lagrange", 3, |S| {
        LagrangeCurve::<[S; 3], 8>::new(
            &points::<S, 3>(&WAYPOINTS[..4]),
            Parameterization::ChordLength,
        )
        .expect("Lagrange")
    });
    every_format!(report, "power-basis spline", 3, |S| {
        let b = BSpline::<[S; 3], 8, 12>::clamped_uniform(
            3,
            &points::<S, 3>(&WAYPOINTS),
            S::ZERO,
            S::ONE,
        )
        .expect("B-spline");
        PowerSpline::<[S; 3], 4, 8>::from_bspline(&b).expect("power spline")
    });
    report.finish();
}

#[test]
fn parabolic_blend_c1_joins() {
    let mut report = Report::with_c1_joins();
    every_format!(report, "parabolic blend", 3, |S| {
        ParabolicBlend::<[S; 3], 8>::new(&points::<S, 3>(&WAYPOINTS)).expect("blend")
    });
    report.finish();
}
