//! Every curve constructor of strak-curves, from fuzzed input, then evaluation, derivatives
//! and analysis at fuzzed parameters.
//!
//! The input chooses the scalar (`f64`, `f32`, `I16F16`, `I32F32`), the dimension (1 to 3),
//! a constructor and its arguments: up to [`MAX_POINTS`] points, knots, nodes, weights and
//! tangents, mostly well-formed (sorted knots, increasing nodes, positive weights) and now
//! and then anything (NaN, infinities, huge values). Invariants:
//!
//! * constructors and every later call never panic (fixed-point overflow panics in these
//!   builds, so an overflow is found too);
//! * a curve that builds has a finite domain with `lo ≤ hi`, at least one piece, and
//!   finite points and first and second derivatives at every parameter in and outside its
//!   domain ("evaluation has no error path"; constructors reject what could overflow);
//! * arc length, arc-length tables, flattening and continuity classification return (an
//!   error or a value) within the work bound each documents, counted in evaluations of the
//!   curve ([`Counted`]; counts, unlike times, do not depend on the machine's load), at
//!   tolerances relative to the curve's size (`10⁻⁵..1` for flattening, `10⁻⁹..10⁻¹` for
//!   arc length);
//! * a tolerance below the curve's resolution is an error at once
//!   (`ToleranceBelowResolution` after the resolution check's evaluations).

use strak_curves::{
    ArcLengthTable, BSpline, Bezier, BezierChain, Counted, CubicSpline, Error, HermiteSegment,
    HermiteSpline, I16F16, I32F32, KnotVector, LagrangeCurve, NodeSource, Nurbs, ParabolicBlend,
    ParamCurve, Parameterization, PieceDeriv, Point, PowerSpline, Scalar, ScalarOf, SplineBoundary,
    arc_length, basis::MonomialCurve, classify_breaks, flatten, flatten_count, length_resolution,
    resolution,
};

use crate::decode::Bytes;
use crate::dyn_curve::Dyn;
use crate::{Violation, violation};

/// The most points (control points, interpolation points) of a fuzzed curve.
pub const MAX_POINTS: usize = 10;
/// Capacities: points and knots of B-splines and NURBS.
const N: usize = 12;
const M: usize = 20;
/// Speed evaluations of one piece's arc-length quadrature at most: 16 parts, 16 + 2·(2·2¹²
/// + 16) Gauss rules of 16 nodes (the work bound of `arc_length`).
const ARC_LENGTH_PER_PIECE: u64 = 16 * (16 + 2 * (2 * (1 << 12) + 16));
/// Evaluations of flattening at most: 2¹² intervals of 2 evaluations and 12·64 chord
/// certificates of 8 evaluations each (the work bound of `flatten`).
const FLATTEN_CERTIFICATES: u64 = (1 << 12) * (2 + 12 * 64 * 8);

/// A scalar the harness builds from any `f64` (floats by a cast, so NaN and infinities
/// reach the constructors; fixed-point saturating, NaN as 0).
pub trait FuzzScalar: Scalar {
    /// The value nearest to `v` that the type can hold.
    fn from_fuzz(v: f64) -> Self;
}

impl FuzzScalar for f64 {
    fn from_fuzz(v: f64) -> Self {
        v
    }
}

impl FuzzScalar for f32 {
    fn from_fuzz(v: f64) -> Self {
        #[allow(clippy::cast_possible_truncation)]
        let x = v as f32;
        x
    }
}

impl FuzzScalar for I16F16 {
    fn from_fuzz(v: f64) -> Self {
        if v.is_nan() {
            I16F16::ZERO
        } else {
            I16F16::saturating_from_num(v)
        }
    }
}

impl FuzzScalar for I32F32 {
    fn from_fuzz(v: f64) -> Self {
        if v.is_nan() {
            I32F32::ZERO
        } else {
            I32F32::saturating_from_num(v)
        }
    }
}

/// The harness.
///
/// # Errors
/// The first broken invariant, naming the constructor.
pub fn run(data: &[u8]) -> Result<(), Violation> {
    let mut b = Bytes::new(data);
    let scalar = b.choice(4);
    let dim = b.choice(3);
    macro_rules! by_dim {
        ($s:ty) => {
            match dim {
                0 => case::<$s, 1>(&mut b),
                1 => case::<$s, 2>(&mut b),
                _ => case::<$s, 3>(&mut b),
            }
        };
    }
    match scalar {
        0 => by_dim!(f64),
        1 => by_dim!(f32),
        2 => by_dim!(I16F16),
        _ => by_dim!(I32F32),
    }
}

/// The decoded arguments of one constructor call.
struct Args<S, const D: usize> {
    points: Vec<[S; D]>,
    tangents: Vec<[S; D]>,
    knots: Vec<S>,
    nodes: Vec<S>,
    weights: Vec<S>,
    degree: usize,
    scale: f64,
}

fn scalar<S: FuzzScalar>(b: &mut Bytes<'_>, scale: f64) -> S {
    S::from_fuzz(b.coord(scale))
}

fn point<S: FuzzScalar, const D: usize>(b: &mut Bytes<'_>, scale: f64) -> [S; D] {
    core::array::from_fn(|_| scalar(b, scale))
}

/// Non-decreasing values from a start, steps of 0 to 1 (multiplicities) or strictly
/// increasing (`min_step` 1), now and then in any order.
fn sorted<S: FuzzScalar>(b: &mut Bytes<'_>, count: usize, min_step: i64) -> Vec<S> {
    let unsorted = b.one_in(16);
    let mut u = b.int(-4, 4) as f64 / 4.0;
    (0..count)
        .map(|_| {
            let v = if unsorted { b.coord(1.0) } else { u };
            u += b.int(min_step, 4) as f64 / 4.0;
            S::from_fuzz(v)
        })
        .collect()
}

impl<S: FuzzScalar, const D: usize> Args<S, D> {
    fn decode(b: &mut Bytes<'_>) -> Self {
        let scale = if b.one_in(16) {
            b.magnitude(4, 12)
        } else {
            b.magnitude(-3, 2)
        };
        let n = b.int(0, MAX_POINTS as i64) as usize;
        let points = (0..n).map(|_| point(b, scale)).collect();
        let tangents = (0..n).map(|_| point(b, scale)).collect();
        let k = b.int(0, M as i64) as usize;
        let knots = sorted(b, k, 0);
        let nodes = sorted(b, n, 1);
        let weights = (0..n)
            .map(|_| {
                S::from_fuzz(if b.one_in(16) {
                    b.coord(1.0)
                } else {
                    b.positive(-2, 2)
                })
            })
            .collect();
        let degree = b.int(0, 6) as usize;
        Args {
            points,
            tangents,
            knots,
            nodes,
            weights,
            degree,
            scale,
        }
    }

    fn point(&self, i: usize) -> [S; D] {
        self.points.get(i).copied().unwrap_or([S::ZERO; D])
    }

    fn nodes<'a>(&'a self, b: &mut Bytes<'_>) -> NodeSource<'a, S> {
        match b.choice(4) {
            0 => NodeSource::Given(&self.nodes),
            1 => NodeSource::Computed(Parameterization::Uniform),
            2 => NodeSource::Computed(Parameterization::ChordLength),
            _ => NodeSource::Computed(Parameterization::Centripetal),
        }
    }
}

fn case<S: FuzzScalar, const D: usize>(b: &mut Bytes<'_>) -> Result<(), Violation> {
    let a = Args::<S, D>::decode(b);
    match b.choice(12) {
        0 => bezier(&a, b),
        1 => chain(&a, b),
        2 => bspline(&a, b),
        3 => nurbs(&a, b),
        4 => hermite(&a, b),
        5 => {
            let c = CubicSpline::<_, N>::new(&a.points, a.nodes(b), boundary(&a, b));
            exercise_result("CubicSpline::new", c, b)
        }
        6 => {
            let c = LagrangeCurve::<_, 8>::new(&a.points, a.nodes(b));
            exercise_result("LagrangeCurve::new", c, b)
        }
        7 => exercise_result(
            "ParabolicBlend::new",
            ParabolicBlend::<_, N>::new(&a.points),
            b,
        ),
        8 => monomial(&a, b),
        9 => {
            let c = Nurbs::<[S; D], 9, 12>::circle(a.point(0), scalar(b, a.scale));
            exercise_result("Nurbs::circle", c, b)
        }
        10 => {
            let c = Bezier::<[S; D], 4>::quarter_circle(S::from_fuzz(b.unit()));
            exercise_result("Bezier::quarter_circle", c, b)
        }
        _ => bases(&a, b),
    }
}

fn boundary<S: FuzzScalar, const D: usize>(
    a: &Args<S, D>,
    b: &mut Bytes<'_>,
) -> SplineBoundary<[S; D]> {
    match b.choice(3) {
        0 => SplineBoundary::Natural,
        1 => SplineBoundary::Periodic,
        _ => SplineBoundary::Clamped {
            start: point(b, a.scale),
            end: point(b, a.scale),
        },
    }
}

fn array<S: FuzzScalar, const D: usize, const K: usize>(a: &Args<S, D>) -> [[S; D]; K] {
    core::array::from_fn(|i| a.point(i))
}

fn bezier<S: FuzzScalar, const D: usize>(
    a: &Args<S, D>,
    b: &mut Bytes<'_>,
) -> Result<(), Violation> {
    match a.degree {
        0 | 1 => bezier_of::<S, D, 2>(a, b),
        2 => bezier_of::<S, D, 3>(a, b),
        3 | 4 => bezier_of::<S, D, 4>(a, b),
        _ => bezier_of::<S, D, 6>(a, b),
    }
}

/// `Bezier<_, K>` and what derives new curves from one: reverse, subdivide, segment, degree
/// elevation, hodograph, monomial form and back, C¹ and G¹ joins.
fn bezier_of<S: FuzzScalar, const D: usize, const K: usize>(
    a: &Args<S, D>,
    b: &mut Bytes<'_>,
) -> Result<(), Violation> {
    let Ok(c) = Bezier::<[S; D], K>::new(array(a)) else {
        return Ok(());
    };
    exercise("Bezier::new", &c, b)?;
    let t = S::from_fuzz(b.unit());
    exercise("Bezier::reverse", &c.reverse(), b)?;
    let (l, r) = c.subdivide(t);
    exercise("Bezier::subdivide (left)", &l, b)?;
    exercise("Bezier::subdivide (right)", &r, b)?;
    exercise("Bezier::segment", &c.segment(S::from_fuzz(b.unit()), t), b)?;
    exercise_result("Bezier::elevate", c.elevate::<7>(), b)?;
    exercise_result("Bezier::hodograph", c.hodograph::<3>(), b)?;
    if let Ok(m) = c.to_monomial() {
        exercise("Bezier::to_monomial", &m, b)?;
        exercise_result("Bezier::from_monomial", Bezier::from_monomial(&m), b)?;
    }
    let next = Bezier::<[S; D], 4>::new(core::array::from_fn(|i| a.point(K + i)));
    if let Ok(next) = next {
        exercise_result("Bezier::join_c1", c.join_c1(&next), b)?;
        let len = b.one_in(2).then(|| scalar(b, a.scale));
        exercise_result("Bezier::join_g1", c.join_g1(&next, len), b)?;
    }
    Ok(())
}

fn chain<S: FuzzScalar, const D: usize>(
    a: &Args<S, D>,
    b: &mut Bytes<'_>,
) -> Result<(), Violation> {
    if b.one_in(2) {
        exercise_result(
            "BezierChain::new (linear)",
            BezierChain::<_, 2, 8>::new(&a.points),
            b,
        )
    } else {
        exercise_result(
            "BezierChain::new (cubic)",
            BezierChain::<_, 4, 4>::new(&a.points),
            b,
        )?;
        let segments: Vec<Bezier<[S; D], 4>> = a
            .points
            .chunks_exact(4)
            .filter_map(|p| Bezier::new([p[0], p[1], p[2], p[3]]).ok())
            .collect();
        let c = BezierChain::<_, 4, 4>::from_segments(&segments);
        exercise_result("BezierChain::from_segments", c, b)
    }
}

fn bspline<S: FuzzScalar, const D: usize>(
    a: &Args<S, D>,
    b: &mut Bytes<'_>,
) -> Result<(), Violation> {
    let (p, g) = (&a.points[..], a.degree);
    let (u0, u1) = (scalar::<S>(b, 1.0), scalar::<S>(b, 1.0));
    let (what, c) = match b.choice(8) {
        0 => ("BSpline::new", BSpline::<_, N, M>::new(g, p, &a.knots)),
        1 => (
            "BSpline::clamped_uniform",
            BSpline::clamped_uniform(g, p, u0, u1),
        ),
        2 => ("BSpline::closed", BSpline::closed(g, p, None)),
        3 => (
            "BSpline::closed (knots)",
            BSpline::closed(g, p, Some(&a.knots)),
        ),
        4 => (
            "KnotVector::new",
            KnotVector::new(g, &a.knots).and_then(|k| BSpline::from_knot_vector(p, k)),
        ),
        5 => (
            "KnotVector::uniform",
            KnotVector::uniform(g, p.len(), u0, u1).and_then(|k| BSpline::from_knot_vector(p, k)),
        ),
        6 => (
            "KnotVector::periodic",
            KnotVector::periodic(g, p.len(), u0, u1).and_then(|k| BSpline::from_knot_vector(p, k)),
        ),
        _ => (
            "KnotVector::clamped_uniform",
            KnotVector::clamped_uniform(g, p.len(), u0, u1)
                .and_then(|k| BSpline::from_knot_vector(p, k)),
        ),
    };
    let Ok(c) = c else { return Ok(()) };
    exercise(what, &c, b)?;
    derivatives_agree(what, &c, &|u, out| c.derivatives(u, out), b)?;
    let u = scalar::<S>(b, 1.0);
    exercise_result("BSpline::insert_knot", c.insert_knot(u), b)?;
    if let Ok(segments) = c.to_bezier_segments::<7, 16>() {
        for s in segments.iter().take(4) {
            exercise_result("BSpline::to_bezier_segments", Bezier::new(*s), b)?;
        }
    }
    exercise_result(
        "PowerSpline::from_bspline",
        PowerSpline::<_, 6, 16>::from_bspline(&c),
        b,
    )
}

fn nurbs<S: FuzzScalar, const D: usize>(
    a: &Args<S, D>,
    b: &mut Bytes<'_>,
) -> Result<(), Violation> {
    let (p, w, g) = (&a.points[..], &a.weights[..], a.degree);
    let (u0, u1) = (scalar::<S>(b, 1.0), scalar::<S>(b, 1.0));
    let (what, c) = match b.choice(4) {
        0 => ("Nurbs::new", Nurbs::<_, N, M>::new(g, p, w, &a.knots)),
        1 => (
            "Nurbs::clamped_uniform",
            Nurbs::clamped_uniform(g, p, w, u0, u1),
        ),
        2 => ("Nurbs::closed", Nurbs::closed(g, p, w, None)),
        _ => (
            "Nurbs::closed (knots)",
            Nurbs::closed(g, p, w, Some(&a.knots)),
        ),
    };
    let Ok(c) = c else { return Ok(()) };
    exercise(what, &c, b)?;
    derivatives_agree(what, &c, &|u, out| c.derivatives(u, out), b)?;
    exercise_result("Nurbs::insert_knot", c.insert_knot(scalar::<S>(b, 1.0)), b)?;
    let _ = c.to_rational_bezier_segments::<7, 16>();
    Ok(())
}

fn hermite<S: FuzzScalar, const D: usize>(
    a: &Args<S, D>,
    b: &mut Bytes<'_>,
) -> Result<(), Violation> {
    let (p, m) = (&a.points[..], &a.tangents[..]);
    match b.choice(4) {
        0 => {
            let (u0, u1) = (scalar::<S>(b, 1.0), scalar::<S>(b, 1.0));
            let c = HermiteSegment::new(
                u0,
                u1,
                a.point(0),
                a.point(1),
                point(b, a.scale),
                point(b, a.scale),
            );
            exercise_result("HermiteSegment::new", c, b)
        }
        1 => {
            let c = HermiteSpline::<_, N>::new(p, m, a.nodes(b));
            exercise_result("HermiteSpline::new", c, b)
        }
        2 => {
            let c = HermiteSpline::<_, N>::catmull_rom(p, a.nodes(b));
            exercise_result("HermiteSpline::catmull_rom", c, b)
        }
        _ => {
            let tension = S::from_fuzz(if b.one_in(8) { b.raw() } else { b.unit() });
            let c = HermiteSpline::<_, N>::cardinal(p, a.nodes(b), tension);
            exercise_result("HermiteSpline::cardinal", c, b)
        }
    }
}

fn monomial<S: FuzzScalar, const D: usize>(
    a: &Args<S, D>,
    b: &mut Bytes<'_>,
) -> Result<(), Violation> {
    let coeffs: [[S; D]; 4] = array(a);
    if b.one_in(2) {
        exercise_result("MonomialCurve::new", MonomialCurve::new(coeffs), b)
    } else {
        let (s, e) = (scalar::<S>(b, 1.0), scalar::<S>(b, 1.0));
        exercise_result(
            "MonomialCurve::with_domain",
            MonomialCurve::with_domain(coeffs, s, e),
            b,
        )
    }
}

/// The basis functions at a fuzzed parameter: finite wherever the parameter is finite.
fn bases<S: FuzzScalar, const D: usize>(
    a: &Args<S, D>,
    b: &mut Bytes<'_>,
) -> Result<(), Violation> {
    use strak_curves::basis::{
        LagrangeBasis, bernstein_all, bernstein_deriv_all, hermite, hermite_deriv,
    };
    let t = S::from_fuzz(b.coord(1.0));
    let finite = |what: &str, v: &[S]| {
        if t.is_finite() && !v.iter().all(|x| x.is_finite()) {
            Err(violation!("{what} at t = {t:?} is not finite: {v:?}"))
        } else {
            Ok(())
        }
    };
    finite("bernstein_all::<6>", &bernstein_all::<S, 6>(t))?;
    finite("bernstein_deriv_all::<6>", &bernstein_deriv_all::<S, 6>(t))?;
    finite("hermite", &hermite(t))?;
    finite("hermite_deriv", &hermite_deriv(t, a.degree))?;
    let nodes: [S; 4] = core::array::from_fn(|i| a.nodes.get(i).copied().unwrap_or(S::ZERO));
    if let Ok(l) = LagrangeBasis::new(nodes) {
        let (lo, hi) = l.domain();
        let t = t.clamp_to(lo, hi);
        finite("LagrangeBasis::values", &l.values(t))?;
    }
    let _ = strak_curves::basis_function(&a.knots, a.degree, a.degree, t);
    Ok(())
}

/// `curve` when it built, else nothing to check.
fn exercise_result<C, E, S: FuzzScalar, const D: usize>(
    what: &str,
    c: Result<C, E>,
    b: &mut Bytes<'_>,
) -> Result<(), Violation>
where
    C: PieceDeriv<Point = [S; D]>,
{
    match c {
        Ok(c) => exercise(what, &c, b),
        Err(_) => Ok(()),
    }
}

/// [`check`] of a built curve, through a trait object.
fn exercise<S: FuzzScalar, const D: usize>(
    what: &str,
    c: &dyn PieceDeriv<Point = [S; D]>,
    b: &mut Bytes<'_>,
) -> Result<(), Violation> {
    check(what, &Dyn(c), b)
}

/// Evaluation, derivatives, pieces and analysis of a built curve.
fn check<C: PieceDeriv>(what: &str, c: &C, b: &mut Bytes<'_>) -> Result<(), Violation>
where
    ScalarOf<C>: FuzzScalar,
{
    let (lo, hi) = c.domain();
    if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
        return Err(violation!("{what}: domain [{lo:?}, {hi:?}]"));
    }
    let pieces = c.piece_count();
    if pieces == 0 {
        return Err(violation!("{what}: no pieces"));
    }
    let width = (hi.to_f64() - lo.to_f64()).max(1e-3);
    let mut params = vec![lo, hi, mid(lo, hi)];
    for _ in 0..3 {
        params.push(ScalarOf::<C>::from_fuzz(lo.to_f64() + b.coord(width / 8.0)));
    }
    for &u in &params {
        for k in 0..=4 {
            let p = c.deriv(u, k);
            if k <= 2 && !p.is_finite() {
                return Err(violation!(
                    "{what}: derivative {k} at u = {u:?} is not finite: {p:?}"
                ));
            }
        }
        let p = c.eval(u);
        if !p.is_finite() {
            return Err(violation!(
                "{what}: point at u = {u:?} is not finite: {p:?}"
            ));
        }
    }
    for i in 0..pieces.min(8) {
        let (a, z) = c.piece_domain(i);
        if !(a.is_finite() && z.is_finite() && lo <= a && a <= z && z <= hi) {
            return Err(violation!(
                "{what}: piece {i} domain [{a:?}, {z:?}] outside [{lo:?}, {hi:?}]"
            ));
        }
        for u in [a, z, mid(a, z)] {
            let p = c.piece_deriv(i, u, b.choice(4));
            if !p.is_finite() {
                return Err(violation!(
                    "{what}: piece {i} derivative at u = {u:?} is not finite"
                ));
            }
        }
    }
    analysis(what, c, b)
}

/// Runs `f` on the counted curve and fails when it evaluates the curve more than `bound`
/// times.
fn bounded<C, T>(
    counted: &Counted<'_, C>,
    what: &str,
    call: &str,
    bound: u64,
    f: impl FnOnce(&Counted<'_, C>) -> T,
) -> Result<T, Violation> {
    counted.take();
    let v = f(counted);
    let calls = counted.take();
    if calls > bound {
        return Err(violation!(
            "{what}: {call} evaluated the curve {calls} times, more than its bound {bound}"
        ));
    }
    Ok(v)
}

/// `size · 10^lo ..= size · 10^hi`, now and then any `f64`.
fn relative(b: &mut Bytes<'_>, size: f64, lo: i32, hi: i32) -> f64 {
    if b.one_in(32) {
        b.raw()
    } else {
        size * b.magnitude(lo, hi)
    }
}

/// The largest coordinate of the curve at its piece boundaries and midpoints.
fn size<C: ParamCurve>(c: &C) -> f64
where
    ScalarOf<C>: FuzzScalar,
{
    let mut m = 0.0_f64;
    for i in 0..c.piece_count() {
        let (lo, hi) = c.piece_domain(i);
        let mid = ScalarOf::<C>::from_fuzz((lo.to_f64() + hi.to_f64()) / 2.0);
        for u in [lo, mid, hi] {
            let p = c.eval(u);
            for k in 0..<C::Point as Point>::DIM {
                m = m.max(p.coord(k).to_f64().abs());
            }
        }
    }
    m
}

/// A tolerance below the curve's resolution (a share `0.001 + 0.998·t` of it) is an error
/// at once: flattening and arc length return `ToleranceBelowResolution` after the
/// resolution check.
fn below_resolution<C: PieceDeriv>(
    what: &str,
    counted: &Counted<'_, C>,
    check: u64,
    t: f64,
) -> Result<(), Violation>
where
    ScalarOf<C>: FuzzScalar,
{
    let share = 0.001 + 0.998 * t;
    // Below it: a subnormal resolution times the share may round back onto it.
    let below = |r: f64| if r * share < r { r * share } else { 0.5 * r };
    let tolerance = below(resolution(counted));
    let accuracy = below(length_resolution(counted));
    let flat = bounded(
        counted,
        what,
        &format!("flatten_count({tolerance:e})"),
        check,
        |c| flatten_count(c, tolerance),
    )?;
    let length = bounded(
        counted,
        what,
        &format!("arc_length({accuracy:e})"),
        check,
        |c| arc_length(c, accuracy),
    )?;
    let cases = [
        ("flatten_count", tolerance, flat.map(|_| ())),
        ("arc_length", accuracy, length.map(|_| ())),
    ];
    for (call, tol, r) in cases {
        // A curve of zero size has a resolution of 0, one whose length overflows an infinite
        // length resolution: then `tol` itself is invalid.
        let expected = if tol.is_finite() && tol > 0.0 {
            matches!(r, Err(Error::ToleranceBelowResolution { .. }))
        } else {
            r == Err(Error::InvalidArgument)
        };
        if !expected {
            return Err(violation!(
                "{what}: {call}({tol:e}) below the resolution (share {share}) returned {r:?}"
            ));
        }
    }
    Ok(())
}

fn analysis<C: PieceDeriv>(what: &str, c: &C, b: &mut Bytes<'_>) -> Result<(), Violation>
where
    ScalarOf<C>: FuzzScalar,
{
    let counted = Counted::new(c);
    let pieces = c.piece_count() as u64;
    // The resolution check every routine starts with.
    let check = 2 * pieces + 2;
    if b.one_in(8) {
        return below_resolution(what, &counted, check, b.unit());
    }
    // Tolerances relative to the curve's size. Finer ones (down to the resolution) have the
    // same work bounds, but one call may then take seconds; the tests of the bounds
    // (tests/tests/analysis_on_curves.rs) run those.
    let size = size(c).max(1e-6);
    let accuracy = relative(b, size, -9, -1);
    let tolerance = relative(b, size, -5, 0);
    let length_bound = check + pieces * ARC_LENGTH_PER_PIECE;
    if b.one_in(2) {
        let length = bounded(
            &counted,
            what,
            &format!("arc_length({accuracy:e})"),
            length_bound,
            |c| arc_length(c, accuracy),
        )?;
        if let Ok(l) = length
            && !(l.is_finite() && l >= 0.0)
        {
            return Err(violation!("{what}: arc length {l}"));
        }
        const SAMPLES: usize = 16;
        let table_bound = check + 2 * (SAMPLES as u64 - 1) * length_bound + 3 * SAMPLES as u64;
        let table = bounded(
            &counted,
            what,
            &format!("ArcLengthTable::new({accuracy:e})"),
            table_bound,
            |c| ArcLengthTable::<ScalarOf<C>, SAMPLES>::new(c, accuracy),
        )?;
        if let Ok(t) = table {
            let s = ScalarOf::<C>::from_fuzz(t.length().to_f64() * b.unit());
            let u = t.param_at(s);
            let (lo, hi) = c.domain();
            if !(u.is_finite() && lo <= u && u <= hi) {
                return Err(violation!(
                    "{what}: param_at({s:?}) = {u:?} outside the domain"
                ));
            }
        }
    } else {
        let flatten_bound = check + FLATTEN_CERTIFICATES;
        let _ = bounded(
            &counted,
            what,
            &format!("flatten_count({tolerance:e})"),
            flatten_bound,
            |c| flatten_count(c, tolerance),
        )?;
        let mut out = [<C::Point as Point>::zero(); 32];
        let n = bounded(
            &counted,
            what,
            &format!("flatten({tolerance:e})"),
            flatten_bound + out.len() as u64,
            |c| flatten(c, tolerance, &mut out),
        )?;
        if let Ok(n) = n
            && !(n <= out.len() && out[..n].iter().all(|p| p.is_finite()))
        {
            return Err(violation!(
                "{what}: flatten wrote {n} points, not all finite"
            ));
        }
        let joins = pieces.saturating_sub(1);
        let _ = bounded(
            &counted,
            what,
            &format!("classify_breaks({tolerance:e})"),
            8 * joins,
            |c| classify_breaks(c, tolerance),
        )?;
    }
    Ok(())
}

/// `derivatives(u, out)` of B-splines and NURBS: finite where `deriv` is.
fn derivatives_agree<S: FuzzScalar, const D: usize>(
    what: &str,
    c: &dyn PieceDeriv<Point = [S; D]>,
    derivatives: &dyn Fn(S, &mut [[S; D]]),
    b: &mut Bytes<'_>,
) -> Result<(), Violation> {
    let (lo, hi) = c.domain();
    let u = S::from_fuzz(lo.to_f64() + b.unit() * (hi.to_f64() - lo.to_f64()));
    let mut out = [[S::ZERO; D]; 3];
    derivatives(u, &mut out);
    if !out.iter().all(|p| p.is_finite()) {
        return Err(violation!(
            "{what}: derivatives at u = {u:?} not finite: {out:?}"
        ));
    }
    Ok(())
}

/// The midpoint of two scalars, through `f64` (no overflow).
fn mid<S: FuzzScalar>(a: S, b: S) -> S {
    S::from_fuzz((a.to_f64() + b.to_f64()) / 2.0)
}
