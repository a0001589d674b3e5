//! The claims of the overview table in `crates/curves/README.md`, checked on the curve types:
//! which families interpolate their points, keep to the convex hull of their control points,
//! follow the control polygon at the ends, have local control, how smooth their joins are,
//! which are affinely invariant, and that only NURBS hold an exact circle.
//!
//! Every "no" of the table is shown by a counterexample here, every "yes" by a check on a
//! curve that is not special (uneven points, non-uniform knots where the type allows them).

use strak_curves::basis::MonomialCurve;
use strak_curves::{
    BSpline, Bezier, BezierChain, Continuity, CubicSpline, HermiteSpline, LagrangeCurve, Nurbs,
    ParabolicBlend, ParamCurve, ParamCurveDeriv, Parameterization, PieceDeriv, PowerSpline,
    SplineBoundary, classify_breaks, quarter_circle_radial_error,
};

type P2 = [f64; 2];

/// Uneven points with a sharp turn (so that interpolants overshoot).
const PTS: [P2; 6] = [
    [0.0, 0.0],
    [1.0, 2.0],
    [2.5, 2.2],
    [3.0, 0.0],
    [4.5, -0.5],
    [6.0, 1.5],
];

fn sub(a: P2, b: P2) -> P2 {
    [a[0] - b[0], a[1] - b[1]]
}

fn dist(a: P2, b: P2) -> f64 {
    let d = sub(a, b);
    d[0].hypot(d[1])
}

fn cross(a: P2, b: P2) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// `count` parameters evenly over `[a, b]`, both ends included.
fn params(a: f64, b: f64, count: usize) -> impl Iterator<Item = f64> {
    (0..=count).map(move |i| a + (b - a) * i as f64 / count as f64)
}

/// Whether `p` lies in the convex hull of `pts` (within `tol`), by the half-planes of the
/// hull's edges (Andrew's monotone chain).
fn in_hull(p: P2, pts: &[P2], tol: f64) -> bool {
    let mut v: Vec<P2> = pts.to_vec();
    v.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let mut hull: Vec<P2> = Vec::new();
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &P2>> = if pass == 0 {
            Box::new(v.iter())
        } else {
            Box::new(v.iter().rev())
        };
        for &q in iter {
            while hull.len() >= start + 2 {
                let (a, b) = (hull[hull.len() - 2], hull[hull.len() - 1]);
                if cross(sub(b, a), sub(q, a)) <= 0.0 {
                    hull.pop();
                } else {
                    break;
                }
            }
            hull.push(q);
        }
        hull.pop();
    }
    (0..hull.len()).all(|i| {
        let (a, b) = (hull[i], hull[(i + 1) % hull.len()]);
        cross(sub(b, a), sub(p, a)) >= -tol * dist(a, b).max(1.0)
    })
}

/// The indices of the pieces on which two curves over the same parameter domain differ.
fn changed_pieces<C: ParamCurve<Point = P2>, D: ParamCurve<Point = P2>>(
    a: &C,
    b: &D,
) -> Vec<usize> {
    (0..a.piece_count())
        .filter(|&i| {
            let (u0, u1) = a.piece_domain(i);
            params(u0, u1, 32).any(|u| dist(a.eval(u), b.eval(u)) > 1e-12)
        })
        .collect()
}

fn moved(points: &[P2], i: usize) -> Vec<P2> {
    let mut p = points.to_vec();
    p[i] = [p[i][0] + 0.3, p[i][1] - 0.7];
    p
}

/// A non-uniform affine map (shear and unequal scaling) and its linear part.
fn affine(p: P2) -> P2 {
    [
        2.0 * p[0] + 0.5 * p[1] + 3.0,
        -0.25 * p[0] + 0.5 * p[1] - 1.0,
    ]
}

fn linear(v: P2) -> P2 {
    [2.0 * v[0] + 0.5 * v[1], -0.25 * v[0] + 0.5 * v[1]]
}

/// A similarity: rotation by 0.6 rad, scaling by 1.7, translation.
fn similarity(p: P2) -> P2 {
    let (s, c) = 0.6_f64.sin_cos();
    [
        1.7 * (c * p[0] - s * p[1]) + 2.0,
        1.7 * (s * p[0] + c * p[1]) - 1.0,
    ]
}

/// The largest distance between `map(a(u))` and `b(u)` over the domain.
fn image_error<C: ParamCurve<Point = P2>, D: ParamCurve<Point = P2>>(
    a: &C,
    b: &D,
    map: impl Fn(P2) -> P2,
) -> f64 {
    let (u0, u1) = a.domain();
    params(u0, u1, 400)
        .map(|u| dist(map(a.eval(u)), b.eval(u)))
        .fold(0.0, f64::max)
}

fn bezier() -> Bezier<P2, 6> {
    Bezier::new(PTS).unwrap()
}

fn chain() -> BezierChain<P2, 3, 4> {
    BezierChain::new(&[PTS[0], PTS[1], PTS[2], PTS[3], PTS[4]]).unwrap()
}

const KNOTS: [f64; 10] = [0.0, 0.0, 0.0, 0.0, 0.7, 1.9, 3.0, 3.0, 3.0, 3.0];

fn bspline(points: &[P2]) -> BSpline<P2, 8, 16> {
    BSpline::new(3, points, &KNOTS).unwrap()
}

const WEIGHTS: [f64; 6] = [1.0, 0.5, 2.0, 1.5, 0.8, 1.0];

fn nurbs(points: &[P2], weights: &[f64]) -> Nurbs<P2, 8, 16> {
    Nurbs::new(3, points, weights, &KNOTS).unwrap()
}

const U: [f64; 6] = [0.0, 1.0, 2.5, 3.0, 4.5, 6.0];

fn catmull_rom(points: &[P2]) -> HermiteSpline<P2, 8> {
    HermiteSpline::catmull_rom(points, Parameterization::Uniform).unwrap()
}

fn natural(points: &[P2]) -> CubicSpline<P2, 8> {
    CubicSpline::new(points, &U, SplineBoundary::Natural).unwrap()
}

// ---------------------------------------------------------------------------------------------
// Interpolating or approximating
// ---------------------------------------------------------------------------------------------

#[test]
fn interpolating_families_pass_through_every_point() {
    let lagrange = LagrangeCurve::<P2, 8>::new(&PTS, &U).unwrap();
    let tangents: Vec<P2> = PTS.iter().map(|p| [1.0, 0.1 * p[1]]).collect();
    let hermite = HermiteSpline::<P2, 8>::new(&PTS, &tangents, &U).unwrap();
    let cr = HermiteSpline::<P2, 8>::catmull_rom(&PTS, Parameterization::Centripetal).unwrap();
    let blend = ParabolicBlend::<P2, 8>::new(&PTS).unwrap();
    let clamped = CubicSpline::<P2, 8>::new(
        &PTS,
        &U,
        SplineBoundary::Clamped {
            start: [1.0, 0.0],
            end: [0.0, 1.0],
        },
    )
    .unwrap();
    for i in 0..PTS.len() {
        let q = PTS[i];
        assert!(dist(lagrange.eval(U[i]), q) < 1e-12);
        assert!(dist(hermite.eval(U[i]), q) < 1e-12);
        assert!(dist(cr.eval(cr.nodes()[i]), q) < 1e-12);
        assert!(dist(blend.eval(i as f64), q) < 1e-12);
        assert!(dist(natural(&PTS).eval(U[i]), q) < 1e-12);
        assert!(dist(clamped.eval(U[i]), q) < 1e-12);
    }
    // Hermite splines interpolate the tangents too.
    for i in 0..PTS.len() {
        assert!(dist(hermite.deriv(U[i], 1), tangents[i]) < 1e-12);
    }
}

#[test]
fn approximating_families_interpolate_their_end_points_only() {
    let (b, c, n) = (bezier(), bspline(&PTS), nurbs(&PTS, &WEIGHTS));
    for curve in [&b as &dyn ParamCurve<Point = P2>, &c, &n] {
        let (u0, u1) = curve.domain();
        assert!(dist(curve.eval(u0), PTS[0]) < 1e-12);
        assert!(dist(curve.eval(u1), PTS[5]) < 1e-12);
        // An inner point is not on the curve.
        let nearest = params(u0, u1, 4000)
            .map(|u| dist(curve.eval(u), PTS[2]))
            .fold(f64::INFINITY, f64::min);
        assert!(nearest > 0.05, "{nearest}");
    }
    // The chain interpolates its join points.
    let ch = chain();
    assert!(dist(ch.eval(1.0), PTS[2]) < 1e-15);
    // An unclamped B-spline does not even interpolate its end points.
    let open =
        BSpline::<P2, 8, 16>::new(3, &PTS, &[0., 1., 2., 3., 4., 5., 6., 7., 8., 9.]).unwrap();
    assert!(dist(open.eval(open.domain().0), PTS[0]) > 0.1);
    // An inner knot of multiplicity g = 3 makes the cubic pass through a de Boor point.
    let triple = [0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0, 2.0];
    let mut seven = PTS.to_vec();
    seven.push([7.0, 0.0]);
    let c = BSpline::<P2, 8, 16>::new(3, &seven, &triple).unwrap();
    assert!(dist(c.eval(1.0), seven[3]) < 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Convex hull
// ---------------------------------------------------------------------------------------------

#[test]
fn bezier_bspline_nurbs_and_chains_keep_to_the_convex_hull() {
    let b = bezier();
    for u in params(0.0, 1.0, 500) {
        assert!(in_hull(b.eval(u), &PTS, 1e-12));
    }
    // B-spline and NURBS (positive weights): each span in the hull of its g + 1 points.
    let (c, n) = (bspline(&PTS), nurbs(&PTS, &WEIGHTS));
    for i in 0..c.piece_count() {
        let (u0, u1) = c.piece_domain(i);
        let s = c.knot_vector().span(0.5 * (u0 + u1));
        let local = &PTS[s - 3..=s];
        for u in params(u0, u1, 200) {
            assert!(in_hull(c.eval(u), local, 1e-12), "B-spline span {s}");
            assert!(in_hull(n.eval(u), local, 1e-12), "NURBS span {s}");
        }
    }
    let ch = chain();
    for (i, seg) in ch.segments().iter().enumerate() {
        for u in params(0.0, 1.0, 200) {
            assert!(in_hull(ch.eval(i as f64 + u), seg.control_points(), 1e-12));
        }
    }
}

#[test]
fn interpolating_families_leave_the_convex_hull_of_their_points() {
    // A sharp turn: the interpolants overshoot past the points.
    let pts: [P2; 5] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.0, 2.0]];
    let u = [0.0, 1.0, 2.0, 3.0, 4.0];
    let outside = |c: &dyn ParamCurve<Point = P2>| {
        let (a, b) = c.domain();
        params(a, b, 2000).any(|t| !in_hull(c.eval(t), &pts, 1e-9))
    };
    let lagrange = LagrangeCurve::<P2, 8>::new(&pts, &u).unwrap();
    let cr = HermiteSpline::<P2, 8>::catmull_rom(&pts, &u).unwrap();
    let blend = ParabolicBlend::<P2, 8>::new(&pts).unwrap();
    let spline = CubicSpline::<P2, 8>::new(&pts, &u, SplineBoundary::Natural).unwrap();
    assert!(outside(&lagrange));
    assert!(outside(&cr));
    assert!(outside(&blend));
    assert!(outside(&spline));
}

// ---------------------------------------------------------------------------------------------
// End tangents along the control polygon
// ---------------------------------------------------------------------------------------------

#[test]
fn end_tangents_follow_the_control_polygon() {
    let b = bezier();
    assert!(dist(b.deriv(0.0, 1), [5.0 * 1.0, 5.0 * 2.0]) < 1e-12);
    assert!(dist(b.deriv(1.0, 1), [5.0 * 1.5, 5.0 * 2.0]) < 1e-12);
    // Clamped B-spline: c'(u_g) = g/(u_{g+1} − u_1)·(d_1 − d_0).
    let c = bspline(&PTS);
    let want = 3.0 / (KNOTS[4] - KNOTS[1]);
    assert!(dist(c.deriv(0.0, 1), [want * 1.0, want * 2.0]) < 1e-12);
    // Clamped NURBS: the direction of P_1 − P_0.
    let n = nurbs(&PTS, &WEIGHTS);
    assert!(cross(n.deriv(0.0, 1), sub(PTS[1], PTS[0])).abs() < 1e-12);
    assert!(cross(n.deriv(3.0, 1), sub(PTS[5], PTS[4])).abs() < 1e-12);
    // Catmull-Rom: the one-sided difference (q_1 − q_0)/(u_1 − u_0).
    let cr = HermiteSpline::<P2, 8>::catmull_rom(&PTS, &U).unwrap();
    assert!(dist(cr.deriv(0.0, 1), sub(PTS[1], PTS[0])) < 1e-12);
    // Parabolic blending and the natural spline: not along the first leg.
    let blend = ParabolicBlend::<P2, 8>::new(&PTS).unwrap();
    assert!(cross(blend.deriv(0.0, 1), sub(PTS[1], PTS[0])).abs() > 0.1);
    let s = CubicSpline::<P2, 8>::new(&PTS, Parameterization::Uniform, SplineBoundary::Natural)
        .unwrap();
    let x = cross(s.deriv(0.0, 1), sub(PTS[1], PTS[0])) / dist(PTS[1], PTS[0]);
    assert!(x.abs() > 0.1, "{x} {:?}", s.deriv(0.0, 1));
    assert!(dist(s.deriv(0.0, 2), [0.0, 0.0]) < 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Local control
// ---------------------------------------------------------------------------------------------

#[test]
fn local_control() {
    // Bézier and Lagrange: every piece (the one piece) changes; a cubic spline: every piece.
    let b2 = Bezier::new(<[P2; 6]>::try_from(moved(&PTS, 2)).unwrap()).unwrap();
    let (bez, b2) = (bezier(), b2);
    assert!(
        params(0.0, 1.0, 10)
            .skip(1)
            .take(9)
            .all(|u| dist(bez.eval(u), b2.eval(u)) > 1e-6)
    );
    let s = natural(&PTS);
    assert_eq!(changed_pieces(&s, &natural(&moved(&PTS, 2))).len(), 5);
    // Hermite: a point changes the two pieces next to it.
    let t: Vec<P2> = vec![[1.0, 0.0]; 6];
    let h = HermiteSpline::<P2, 8>::new(&PTS, &t, &U).unwrap();
    let h2 = HermiteSpline::<P2, 8>::new(&moved(&PTS, 3), &t, &U).unwrap();
    assert_eq!(changed_pieces(&h, &h2), vec![2, 3]);
    // Catmull-Rom and parabolic blending: at most four pieces.
    let cr = catmull_rom(&PTS);
    assert_eq!(
        changed_pieces(&cr, &catmull_rom(&moved(&PTS, 3))),
        vec![1, 2, 3, 4]
    );
    let blend = ParabolicBlend::<P2, 8>::new(&PTS).unwrap();
    let blend2 = ParabolicBlend::<P2, 8>::new(&moved(&PTS, 3)).unwrap();
    assert_eq!(changed_pieces(&blend, &blend2), vec![1, 2, 3, 4]);
    // B-spline and NURBS: d_i acts on [u_i, u_{i+g+1}) only; here d_0 and its weight.
    let c = bspline(&PTS);
    let changed = changed_pieces(&c, &bspline(&moved(&PTS, 0)));
    assert_eq!(changed, vec![0]);
    let changed = changed_pieces(&c, &bspline(&moved(&PTS, 2)));
    assert_eq!(changed, vec![0, 1, 2]);
    let n = nurbs(&PTS, &WEIGHTS);
    let mut w = WEIGHTS;
    w[0] = 3.0;
    assert_eq!(changed_pieces(&n, &nurbs(&PTS, &w)), vec![0]);
    // A Bézier chain: an inner point changes its segment only.
    let ch = chain();
    let mut p = [PTS[0], PTS[1], PTS[2], PTS[3], PTS[4]];
    p[3] = [9.0, 9.0];
    assert_eq!(
        changed_pieces(&ch, &BezierChain::<P2, 3, 4>::new(&p).unwrap()),
        vec![1]
    );
}

// ---------------------------------------------------------------------------------------------
// Continuity at joins
// ---------------------------------------------------------------------------------------------

fn cg(c: Continuity) -> (Option<u8>, Option<u8>) {
    (c.parametric, c.geometric)
}

#[test]
fn continuity_at_the_joins() {
    let tol = 1e-9;
    let t: Vec<P2> = PTS.iter().map(|p| [1.0, 0.3 * p[1]]).collect();
    let h = HermiteSpline::<P2, 8>::new(&PTS, &t, &U).unwrap();
    assert_eq!(classify_breaks(&h, tol).unwrap().parametric, Some(1));
    assert_eq!(
        classify_breaks(&catmull_rom(&PTS), tol).unwrap().parametric,
        Some(1)
    );
    let blend = ParabolicBlend::<P2, 8>::new(&PTS).unwrap();
    assert_eq!(classify_breaks(&blend, tol).unwrap().parametric, Some(1));
    assert_eq!(
        classify_breaks(&natural(&PTS), tol).unwrap().parametric,
        Some(2)
    );
    let closed = [PTS[0], PTS[1], PTS[2], PTS[3], PTS[4], PTS[0]];
    let periodic = CubicSpline::<P2, 8>::new(&closed, &U, SplineBoundary::Periodic).unwrap();
    assert_eq!(classify_breaks(&periodic, tol).unwrap().parametric, Some(2));
    for k in 0..=2 {
        assert!(
            dist(periodic.deriv(0.0, k), periodic.deriv(6.0, k)) < 1e-9,
            "seam C{k}"
        );
    }
    // B-splines: C^{g−μ} at a knot of multiplicity μ; the power form keeps it.
    let c = bspline(&PTS);
    assert_eq!(classify_breaks(&c, tol).unwrap().parametric, Some(2));
    let p = PowerSpline::<P2, 4, 8>::from_bspline(&c).unwrap();
    assert_eq!(classify_breaks(&p, tol).unwrap().parametric, Some(2));
    let double = [0.0, 0.0, 0.0, 0.0, 1.5, 1.5, 3.0, 3.0, 3.0, 3.0];
    let c1 = BSpline::<P2, 8, 16>::new(3, &PTS, &double).unwrap();
    assert_eq!(classify_breaks(&c1, tol).unwrap().parametric, Some(1));
    let n = nurbs(&PTS, &WEIGHTS);
    assert_eq!(classify_breaks(&n, tol).unwrap().parametric, Some(2));
    // The NURBS circle: C¹ (not C²) at its double knots, G³ (constant curvature).
    let circle = Nurbs::<P2, 9, 12>::circle([0.0, 0.0], 1.0).unwrap();
    assert_eq!(
        cg(classify_breaks(&circle, tol).unwrap()),
        (Some(1), Some(3))
    );
    // A Bézier chain: C⁰ in general, C¹ after join_c1, G¹ but not C¹ after join_g1.
    assert_eq!(
        cg(classify_breaks(&chain(), tol).unwrap()),
        (Some(0), Some(0))
    );
    let a = Bezier::new([PTS[0], PTS[1], PTS[2]]).unwrap();
    let next = Bezier::new([PTS[2], PTS[3], PTS[4]]).unwrap();
    let c1 = BezierChain::<P2, 3, 4>::from_segments(&[a, a.join_c1(&next).unwrap()]).unwrap();
    assert!(classify_breaks(&c1, tol).unwrap().is_c(1));
    let g1 = a.join_g1(&next, Some(0.25)).unwrap();
    let g1 = BezierChain::<P2, 3, 4>::from_segments(&[a, g1]).unwrap();
    let j = classify_breaks(&g1, tol).unwrap();
    assert!(j.is_g(1) && !j.is_c(1), "{j:?}");
    // One-piece families are C^∞ (reported as C³): nothing to join.
    assert_eq!(classify_breaks(&bezier(), tol).unwrap(), Continuity::SMOOTH);
}

// ---------------------------------------------------------------------------------------------
// Affine invariance
// ---------------------------------------------------------------------------------------------

#[test]
fn affine_invariance() {
    let img: Vec<P2> = PTS.iter().map(|&p| affine(p)).collect();
    let img6: [P2; 6] = img.clone().try_into().unwrap();
    assert!(image_error(&bezier(), &Bezier::new(img6).unwrap(), affine) < 1e-12);
    assert!(image_error(&bspline(&PTS), &bspline(&img), affine) < 1e-12);
    assert!(image_error(&nurbs(&PTS, &WEIGHTS), &nurbs(&img, &WEIGHTS), affine) < 1e-12);
    let l = LagrangeCurve::<P2, 8>::new(&PTS, &U).unwrap();
    let l2 = LagrangeCurve::<P2, 8>::new(&img, &U).unwrap();
    assert!(image_error(&l, &l2, affine) < 1e-10);
    // Hermite: tangents are vectors and map by the linear part.
    let t: Vec<P2> = PTS.iter().map(|p| [1.0, 0.3 * p[1]]).collect();
    let t2: Vec<P2> = t.iter().map(|&v| linear(v)).collect();
    let h = HermiteSpline::<P2, 8>::new(&PTS, &t, &U).unwrap();
    let h2 = HermiteSpline::<P2, 8>::new(&img, &t2, &U).unwrap();
    assert!(image_error(&h, &h2, affine) < 1e-12);
    assert!(image_error(&catmull_rom(&PTS), &catmull_rom(&img), affine) < 1e-12);
    let blend = ParabolicBlend::<P2, 8>::new(&PTS).unwrap();
    let blend2 = ParabolicBlend::<P2, 8>::new(&img).unwrap();
    assert!(image_error(&blend, &blend2, affine) < 1e-12);
    assert!(image_error(&natural(&PTS), &natural(&img), affine) < 1e-11);
    // Monomial coefficients: a_0 maps as a point, the others as vectors.
    let m = MonomialCurve::new([PTS[0], PTS[1], PTS[2], PTS[3]]).unwrap();
    let m2 = MonomialCurve::new([
        affine(PTS[0]),
        linear(PTS[1]),
        linear(PTS[2]),
        linear(PTS[3]),
    ])
    .unwrap();
    assert!(image_error(&m, &m2, affine) < 1e-12);
    // Chord-length nodes change under a non-uniform affine map, not under a similarity.
    let chord =
        |p: &[P2]| HermiteSpline::<P2, 8>::catmull_rom(p, Parameterization::ChordLength).unwrap();
    let sim: Vec<P2> = PTS.iter().map(|&p| similarity(p)).collect();
    let (a, b) = (chord(&PTS), chord(&sim));
    let scale = |u: f64| u * 1.7;
    let (u0, u1) = a.domain();
    let e = params(u0, u1, 400)
        .map(|u| dist(similarity(a.eval(u)), b.eval(scale(u))))
        .fold(0.0, f64::max);
    assert!(e < 1e-11, "{e}");
    let (c, d) = (chord(&PTS), chord(&img));
    let (c0, c1) = c.domain();
    let (d0, d1) = d.domain();
    let e = params(0.0, 1.0, 400)
        .map(|x| {
            dist(
                affine(c.eval(c0 + x * (c1 - c0))),
                d.eval(d0 + x * (d1 - d0)),
            )
        })
        .fold(0.0, f64::max);
    assert!(e > 1e-3, "{e}");
}

// ---------------------------------------------------------------------------------------------
// Exact conics
// ---------------------------------------------------------------------------------------------

#[test]
fn only_nurbs_hold_an_exact_circle() {
    let circle = Nurbs::<P2, 9, 12>::circle([1.0, -2.0], 3.0).unwrap();
    let worst = params(0.0, 4.0, 4000)
        .map(|u| (dist(circle.eval(u), [1.0, -2.0]) - 3.0).abs())
        .fold(0.0, f64::max);
    assert!(worst < 1e-14, "{worst}");
    // The best a cubic Bézier can do: a radial error of about 2·10⁻⁴ of the radius.
    let e = quarter_circle_radial_error(strak_curves::QUARTER_CIRCLE_KAPPA);
    assert!(e > 1e-4 && e < 3e-4, "{e}");
    let b = Bezier::<P2, 4>::quarter_circle(strak_curves::QUARTER_CIRCLE_KAPPA_MIDPOINT).unwrap();
    let worst = params(0.0, 1.0, 400)
        .map(|u| (dist(b.eval(u), [0.0, 0.0]) - 1.0).abs())
        .fold(0.0, f64::max);
    assert!(worst > 1e-4, "{worst}");
}

#[test]
fn the_power_form_is_the_same_curve() {
    let c = bspline(&PTS);
    let p = PowerSpline::<P2, 4, 8>::from_bspline(&c).unwrap();
    for u in params(0.0, 3.0, 600) {
        for k in 0..=3 {
            let (a, b) = (p.deriv(u, k), c.deriv(u, k));
            assert!(dist(a, b) < 1e-11 * (1.0 + b[0].hypot(b[1])), "u={u} k={k}");
        }
    }
    for i in 0..c.piece_count() {
        assert_eq!(p.piece_domain(i), c.piece_domain(i));
        let (_, end) = c.piece_domain(i);
        assert!(dist(p.piece_deriv(i, end, 1), c.piece_deriv(i, end, 1)) < 1e-11);
    }
}

/// The cells not covered above: Bézier chains follow their polygon at the ends and map
/// affinely; a Lagrange curve neither follows its polygon at the ends nor has local control;
/// a Hermite spline with long tangents leaves the hull of its points; NURBS map
/// projectively: `x ↦ (A x + b)/(c·x + d)` takes the curve of the points `P_i`, weights `w_i`
/// to the curve of the points `f(P_i)`, weights `w_i·(c·P_i + d)`.
#[test]
fn remaining_cells() {
    let ch = chain();
    assert!(dist(ch.deriv(0.0, 1), [2.0 * 1.0, 2.0 * 2.0]) < 1e-12);
    assert!(dist(ch.deriv(2.0, 1), [2.0 * 1.5, 2.0 * -0.5]) < 1e-12);
    let img: Vec<P2> = [PTS[0], PTS[1], PTS[2], PTS[3], PTS[4]]
        .iter()
        .map(|&p| affine(p))
        .collect();
    let ch2 = BezierChain::<P2, 3, 4>::new(&img).unwrap();
    assert!(image_error(&ch, &ch2, affine) < 1e-12);

    let l = LagrangeCurve::<P2, 8>::new(&PTS, &U).unwrap();
    assert!(cross(l.deriv(0.0, 1), sub(PTS[1], PTS[0])).abs() > 0.1);
    let l2 = LagrangeCurve::<P2, 8>::new(&moved(&PTS, 2), &U).unwrap();
    assert!(
        params(0.0, 6.0, 60)
            .filter(|u| !U.contains(u))
            .all(|u| dist(l.eval(u), l2.eval(u)) > 1e-9)
    );

    let long: Vec<P2> = vec![[0.0, 8.0]; 6];
    let h = HermiteSpline::<P2, 8>::new(&PTS, &long, &U).unwrap();
    assert!(params(0.0, 6.0, 600).any(|u| !in_hull(h.eval(u), &PTS, 1e-9)));

    let project = |p: P2| {
        let den = 0.1 * p[0] - 0.05 * p[1] + 1.0;
        [(2.0 * p[0] + p[1] + 1.0) / den, (p[1] - 0.5 * p[0]) / den]
    };
    let n = nurbs(&PTS, &WEIGHTS);
    let pts2: Vec<P2> = PTS.iter().map(|&p| project(p)).collect();
    let w2: Vec<f64> = PTS
        .iter()
        .zip(WEIGHTS)
        .map(|(p, w)| w * (0.1 * p[0] - 0.05 * p[1] + 1.0))
        .collect();
    assert!(image_error(&n, &nurbs(&pts2, &w2), project) < 1e-12);
    // The B-spline of the same points is not mapped projectively.
    let b = bspline(&PTS);
    assert!(image_error(&b, &bspline(&pts2), project) > 1e-3);
}
