//! The interpolating families in six dimensions (a six-joint robot arm): every coordinate is
//! interpolated, not only the first four.
//!
//! For given nodes each family is built coordinate by coordinate, so coordinates 4 and 5 of
//! the 6-D curve equal the 2-D curve through those two coordinates alone, at every parameter;
//! chord-length nodes measure all six coordinates; and the range checks of fixed-point
//! constructors see every coordinate.

use strak_curves::{
    CubicSpline, Error, HermiteSpline, I32F32, LagrangeCurve, ParabolicBlend, ParamCurve,
    Parameterization, SplineBoundary,
};

type P6 = [f64; 6];
type P2 = [f64; 2];

const U: [f64; 5] = [0.0, 1.0, 2.5, 3.0, 4.5];

/// Five 6-D points whose coordinates 4 and 5 move unlike the first four.
fn points() -> [P6; 5] {
    core::array::from_fn(|i| {
        let i = i as f64;
        [i, 0.5 * i, 0.0, 1.0, (1.7 * i).sin() * 3.0, i * i - 2.0 * i]
    })
}

/// Coordinates 4 and 5.
fn tail(p: &P6) -> P2 {
    [p[4], p[5]]
}

/// Coordinates 4 and 5 of `six` equal `two` at 41 parameters over the domain.
fn agree(name: &str, six: &impl ParamCurve<Point = P6>, two: &impl ParamCurve<Point = P2>) {
    let (lo, hi) = six.domain();
    assert_eq!((lo, hi), two.domain(), "{name}: domains");
    for k in 0..=40 {
        let u = lo + (hi - lo) * f64::from(k) / 40.0;
        let (a, b) = (tail(&six.eval(u)), two.eval(u));
        let d = (a[0] - b[0]).abs().max((a[1] - b[1]).abs());
        assert!(d <= 1e-12, "{name} at u = {u}: {a:?} against {b:?}");
    }
}

#[test]
fn every_coordinate_is_interpolated() {
    let p6 = points();
    let p2 = p6.map(|p| tail(&p));
    let t6: [P6; 5] = core::array::from_fn(|i| p6[(i + 1) % 5]);
    let t2 = t6.map(|p| tail(&p));

    let spline6 = CubicSpline::<P6, 8>::new(&p6, &U, SplineBoundary::Natural).unwrap();
    let spline2 = CubicSpline::<P2, 8>::new(&p2, &U, SplineBoundary::Natural).unwrap();
    agree("natural cubic spline", &spline6, &spline2);

    let cr6 = HermiteSpline::<P6, 8>::catmull_rom(&p6, &U).unwrap();
    let cr2 = HermiteSpline::<P2, 8>::catmull_rom(&p2, &U).unwrap();
    agree("Catmull-Rom", &cr6, &cr2);

    let h6 = HermiteSpline::<P6, 8>::new(&p6, &t6, &U).unwrap();
    let h2 = HermiteSpline::<P2, 8>::new(&p2, &t2, &U).unwrap();
    agree("Hermite", &h6, &h2);

    let l6 = LagrangeCurve::<P6, 8>::new(&p6, &U).unwrap();
    let l2 = LagrangeCurve::<P2, 8>::new(&p2, &U).unwrap();
    agree("Lagrange", &l6, &l2);

    let b6 = ParabolicBlend::<P6, 8>::new(&p6).unwrap();
    let b2 = ParabolicBlend::<P2, 8>::new(&p2).unwrap();
    agree("parabolic blend", &b6, &b2);

    for (i, (q, u)) in p6.iter().zip(U).enumerate() {
        let got = spline6.eval(u);
        assert!(
            got.iter().zip(q).all(|(a, b)| (a - b).abs() <= 1e-12),
            "node {i}: {got:?} against {q:?}"
        );
    }
}

#[test]
fn chord_length_nodes_measure_every_coordinate() {
    // The points differ only in coordinate 5: their chords are 1, 2, 3 long.
    let p: [P6; 4] = core::array::from_fn(|i| {
        let mut q = [0.0; 6];
        q[5] = [0.0, 1.0, 3.0, 6.0][i];
        q
    });
    let c = CubicSpline::<P6, 8>::new(&p, Parameterization::ChordLength, SplineBoundary::Natural)
        .unwrap();
    assert_eq!(c.domain(), (0.0, 6.0));
    assert_eq!(c.eval(3.0)[5], 3.0);
}

#[test]
fn fixed_point_range_checks_see_every_coordinate() {
    // A tangent that drives coordinate 5 past I32F32's ±2³¹ between the nodes: the 6-D
    // constructor rejects it as the 2-D one through coordinates 4 and 5 does.
    let f = |x: f64| I32F32::from_num(x);
    let q = |x: f64| [f(0.0), f(0.0), f(0.0), f(0.0), f(0.0), f(x)];
    let points = [q(0.0), q(2.0e9), q(0.0)];
    let tangents = [q(2.0e9), q(2.0e9), q(2.0e9)];
    let nodes = [f(0.0), f(1.0), f(2.0)];
    let tail = |p: &[I32F32; 6]| [p[4], p[5]];
    let two = HermiteSpline::<[I32F32; 2], 4>::new(
        &points.map(|p| tail(&p)),
        &tangents.map(|p| tail(&p)),
        &nodes,
    );
    assert_eq!(two.err(), Some(Error::OutOfRange));
    let six = HermiteSpline::<[I32F32; 6], 4>::new(&points, &tangents, &nodes);
    assert_eq!(six.err(), Some(Error::OutOfRange));
}
