//! Bad input for the B-spline, NURBS, knot-vector and analysis constructors and fallible
//! functions: one test per typed error, asserting the exact [`Error`]; and property tests that
//! arbitrary input (NaN, ±∞, huge, unsorted, arbitrary fixed-point bit patterns) never makes a
//! constructor panic, and that after a successful construction evaluation at arbitrary
//! parameters (NaN, ±1e30, extreme fixed-point values) never panics either (the `fixed` types
//! panic on overflow in debug builds, so this also checks the fixed-point range rule).

use proptest::prelude::*;
use proptest::test_runner::{Config, TestCaseResult, TestRunner};
use strak_curves::{
    ArcLengthTable, BSpline, Bezier, Error, Homogeneous, I16F16, I32F32, KnotVector, Nurbs,
    ParamCurve, ParamCurveDeriv, PieceDeriv, Scalar, arc_length, arc_length_between,
    basis_function, bspline_basis, bspline_basis_derivs, classify_breaks, classify_derivatives,
    classify_join, flatten, flatten_count, param_at_length,
};

type Kv = KnotVector<f64, 16>;
type B2 = BSpline<[f64; 2], 8, 16>;
type R2 = Nurbs<[f64; 2], 8, 16>;

const NAN: f64 = f64::NAN;
const INF: f64 = f64::INFINITY;

fn i16f16(x: f64) -> I16F16 {
    I16F16::from_num(x)
}

/// Four de Boor points for the small curves of these tests.
const D4: [[f64; 2]; 4] = [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]];
/// The clamped quadratic knot vector for `D4`.
const T4: [f64; 7] = [0., 0., 0., 0.5, 1., 1., 1.];

fn bspline() -> B2 {
    B2::new(2, &D4, &T4).unwrap()
}

// ---------------------------------------------------------------------------------------------
// KnotVector::new
// ---------------------------------------------------------------------------------------------

#[test]
fn knot_vector_new_degree_too_high() {
    assert_eq!(
        Kv::new(8, &[0.0; 18]).unwrap_err(),
        Error::DegreeTooHigh { max: 7, found: 8 }
    );
}

#[test]
fn knot_vector_new_knot_count() {
    assert_eq!(
        Kv::new(2, &[0., 0., 0., 1., 1.]).unwrap_err(),
        Error::KnotCount {
            expected: 6,
            found: 5
        }
    );
}

#[test]
fn knot_vector_new_capacity_exceeded() {
    assert_eq!(
        KnotVector::<f64, 4>::new(1, &[0., 0., 1., 2., 2.]).unwrap_err(),
        Error::CapacityExceeded {
            capacity: 4,
            required: 5
        }
    );
}

#[test]
fn knot_vector_new_non_finite() {
    assert_eq!(
        Kv::new(1, &[0., 0., NAN, 1., 1.]).unwrap_err(),
        Error::NonFinite
    );
    assert_eq!(
        Kv::new(1, &[0., 0., 0.5, 1., INF]).unwrap_err(),
        Error::NonFinite
    );
    assert_eq!(
        Kv::new(1, &[-INF, 0., 0.5, 1., 1.]).unwrap_err(),
        Error::NonFinite
    );
}

#[test]
fn knot_vector_new_out_of_range() {
    // A knot above the I16F16 limit 16383, and knots that fit but span more than it.
    let (z, big) = (i16f16(0.0), i16f16(20000.0));
    assert_eq!(
        KnotVector::<I16F16, 8>::new(1, &[z, z, big, big]).unwrap_err(),
        Error::OutOfRange
    );
    let (a, b) = (i16f16(-10000.0), i16f16(10000.0));
    assert_eq!(
        KnotVector::<I16F16, 8>::new(1, &[a, a, b, b]).unwrap_err(),
        Error::OutOfRange
    );
    // f64 has headroom up to f64::MAX / 2.
    assert_eq!(
        Kv::new(1, &[0., 0., 1e308, 1e308]).unwrap_err(),
        Error::OutOfRange
    );
}

#[test]
fn knot_vector_new_knots_unsorted() {
    assert_eq!(
        Kv::new(2, &[0., 0., 0., 2., 1., 3., 3., 3.]).unwrap_err(),
        Error::KnotsUnsorted { index: 4 }
    );
}

#[test]
fn knot_vector_new_knot_multiplicity() {
    // Inner multiplicity g + 1 (a jump inside the domain) and end multiplicity g + 2.
    assert_eq!(
        Kv::new(2, &[0., 0., 0., 1., 1., 1., 2., 2., 2.]).unwrap_err(),
        Error::KnotMultiplicity { index: 3 }
    );
    assert_eq!(
        Kv::new(2, &[0., 0., 0., 0., 1., 2., 2., 2.]).unwrap_err(),
        Error::KnotMultiplicity { index: 0 }
    );
    assert_eq!(
        Kv::new(2, &[0., 0., 0., 1., 2., 2., 2., 2.]).unwrap_err(),
        Error::KnotMultiplicity { index: 4 }
    );
}

#[test]
fn knot_vector_new_zero_length_interval() {
    // g = 3, K = 4: the domain [u_3, u_4] is a single value.
    assert_eq!(
        Kv::new(3, &[0., 1., 2., 5., 5., 6., 7., 8.]).unwrap_err(),
        Error::ZeroLengthInterval { index: 3 }
    );
}

// ---------------------------------------------------------------------------------------------
// KnotVector generators: clamped_uniform, uniform, periodic
// ---------------------------------------------------------------------------------------------

#[test]
fn knot_vector_generators_degree_too_high() {
    let e = Error::DegreeTooHigh { max: 7, found: 8 };
    assert_eq!(Kv::clamped_uniform(8, 9, 0.0, 1.0).unwrap_err(), e);
    assert_eq!(Kv::uniform(8, 9, 0.0, 1.0).unwrap_err(), e);
    assert_eq!(Kv::periodic(8, 9, 0.0, 1.0).unwrap_err(), e);
}

#[test]
fn knot_vector_generators_too_few_points() {
    let e = Error::TooFewPoints {
        required: 4,
        found: 3,
    };
    assert_eq!(Kv::clamped_uniform(3, 3, 0.0, 1.0).unwrap_err(), e);
    assert_eq!(Kv::uniform(3, 3, 0.0, 1.0).unwrap_err(), e);
    assert_eq!(Kv::periodic(3, 3, 0.0, 1.0).unwrap_err(), e);
}

#[test]
fn knot_vector_generators_capacity_exceeded() {
    type K6 = KnotVector<f64, 6>;
    let e = Error::CapacityExceeded {
        capacity: 6,
        required: 7,
    };
    assert_eq!(K6::clamped_uniform(2, 4, 0.0, 1.0).unwrap_err(), e);
    assert_eq!(K6::uniform(2, 4, 0.0, 1.0).unwrap_err(), e);
    // periodic: count + 2g + 1 knots
    assert_eq!(
        K6::periodic(2, 3, 0.0, 1.0).unwrap_err(),
        Error::CapacityExceeded {
            capacity: 6,
            required: 8
        }
    );
}

#[test]
fn knot_vector_generators_non_finite() {
    assert_eq!(
        Kv::clamped_uniform(2, 4, NAN, 1.0).unwrap_err(),
        Error::NonFinite
    );
    assert_eq!(Kv::uniform(2, 4, 0.0, INF).unwrap_err(), Error::NonFinite);
    assert_eq!(Kv::periodic(2, 4, -INF, 0.0).unwrap_err(), Error::NonFinite);
}

#[test]
fn knot_vector_generators_zero_length_interval() {
    let e = Error::ZeroLengthInterval { index: 2 };
    assert_eq!(Kv::clamped_uniform(2, 4, 1.0, 1.0).unwrap_err(), e);
    assert_eq!(Kv::uniform(2, 4, 1.0, 1.0).unwrap_err(), e);
    assert_eq!(Kv::periodic(2, 4, 1.0, 1.0).unwrap_err(), e);
}

#[test]
fn knot_vector_generators_knots_unsorted() {
    // u1 < u0: the index of the domain end u_K.
    assert_eq!(
        Kv::clamped_uniform(2, 4, 1.0, 0.0).unwrap_err(),
        Error::KnotsUnsorted { index: 4 }
    );
    assert_eq!(
        Kv::uniform(2, 4, 1.0, 0.0).unwrap_err(),
        Error::KnotsUnsorted { index: 4 }
    );
    assert_eq!(
        Kv::periodic(2, 4, 1.0, 0.0).unwrap_err(),
        Error::KnotsUnsorted { index: 6 }
    );
}

#[test]
fn knot_vector_generators_out_of_range() {
    type K = KnotVector<I16F16, 16>;
    // The ends fit I16F16, the span 20000 does not.
    let (a, b) = (i16f16(-10000.0), i16f16(10000.0));
    assert_eq!(
        K::clamped_uniform(2, 4, a, b).unwrap_err(),
        Error::OutOfRange
    );
    // The unclamped / periodic extension leaves the range: u_0 = −3·16000.
    let (z, c) = (i16f16(0.0), i16f16(16000.0));
    assert_eq!(K::uniform(3, 4, z, c).unwrap_err(), Error::OutOfRange);
    assert_eq!(K::periodic(3, 4, z, c).unwrap_err(), Error::OutOfRange);
}

// ---------------------------------------------------------------------------------------------
// basis_function
// ---------------------------------------------------------------------------------------------

#[test]
fn basis_function_degree_too_high() {
    assert_eq!(
        basis_function(&[0.0; 20], 0, 8, 0.5).unwrap_err(),
        Error::DegreeTooHigh { max: 7, found: 8 }
    );
}

#[test]
fn basis_function_knot_count() {
    // N_i^g needs the knots u_i..u_{i+g+1}: i + g + 2 of them.
    assert_eq!(
        basis_function(&T4, 4, 2, 0.5).unwrap_err(),
        Error::KnotCount {
            expected: 8,
            found: 7
        }
    );
}

#[test]
fn basis_function_non_finite() {
    assert_eq!(
        basis_function(&T4, 0, 2, NAN).unwrap_err(),
        Error::NonFinite
    );
    assert_eq!(
        basis_function(&T4, 0, 2, INF).unwrap_err(),
        Error::NonFinite
    );
    assert_eq!(
        basis_function(&[0., 0., 0., NAN, 1., 1., 1.], 0, 2, 0.5).unwrap_err(),
        Error::NonFinite
    );
}

#[test]
fn basis_function_out_of_range() {
    let k: Vec<I16F16> = [0.0, 0.0, 20000.0, 20000.0].map(i16f16).to_vec();
    assert_eq!(
        basis_function(&k, 0, 1, i16f16(1.0)).unwrap_err(),
        Error::OutOfRange
    );
}

#[test]
fn basis_function_knots_unsorted() {
    assert_eq!(
        basis_function(&[0., 0., 0., 0.7, 0.5, 1., 1.], 0, 2, 0.5).unwrap_err(),
        Error::KnotsUnsorted { index: 4 }
    );
}

// ---------------------------------------------------------------------------------------------
// BSpline::new, from_knot_vector, clamped_uniform
// ---------------------------------------------------------------------------------------------

#[test]
fn bspline_new_degree_too_high() {
    assert_eq!(
        B2::new(8, &[[0.0; 2]; 9], &[0.0; 18]).unwrap_err(),
        Error::DegreeTooHigh { max: 7, found: 8 }
    );
}

#[test]
fn bspline_new_too_few_points() {
    assert_eq!(
        B2::new(2, &D4[..2], &[0., 0., 0., 1., 1.]).unwrap_err(),
        Error::TooFewPoints {
            required: 3,
            found: 2
        }
    );
}

#[test]
fn bspline_new_capacity_exceeded() {
    // Points beyond N = 8.
    let p = [[0.0; 2]; 9];
    let t: Vec<f64> = (0..11).map(f64::from).collect();
    assert_eq!(
        B2::new(1, &p, &t).unwrap_err(),
        Error::CapacityExceeded {
            capacity: 8,
            required: 9
        }
    );
    // Knots beyond M = 6.
    assert_eq!(
        BSpline::<[f64; 2], 8, 6>::new(2, &D4, &T4).unwrap_err(),
        Error::CapacityExceeded {
            capacity: 6,
            required: 7
        }
    );
}

#[test]
fn bspline_new_knot_count() {
    assert_eq!(
        B2::new(2, &D4, &T4[..6]).unwrap_err(),
        Error::KnotCount {
            expected: 7,
            found: 6
        }
    );
}

#[test]
fn bspline_new_non_finite() {
    let mut p = D4;
    p[2][1] = NAN;
    assert_eq!(B2::new(2, &p, &T4).unwrap_err(), Error::NonFinite);
    p[2][1] = -INF;
    assert_eq!(B2::new(2, &p, &T4).unwrap_err(), Error::NonFinite);
    let mut t = T4;
    t[3] = NAN;
    assert_eq!(B2::new(2, &D4, &t).unwrap_err(), Error::NonFinite);
}

#[test]
fn bspline_new_knots_unsorted() {
    assert_eq!(
        B2::new(2, &D4, &[0., 0., 0., 0.5, 0.4, 1., 1.]).unwrap_err(),
        Error::KnotsUnsorted { index: 4 }
    );
}

#[test]
fn bspline_new_knot_multiplicity() {
    let p = [[0.0; 2]; 5];
    assert_eq!(
        B2::new(1, &p, &[0., 0., 0.5, 0.5, 1., 1., 1.]).unwrap_err(),
        Error::KnotMultiplicity { index: 2 }
    );
}

#[test]
fn bspline_new_zero_length_interval() {
    // g = 2, K = 3: domain [u_2, u_3] = [1, 1].
    assert_eq!(
        B2::new(2, &D4[..3], &[0., 0.5, 1., 1., 1.5, 2.]).unwrap_err(),
        Error::ZeroLengthInterval { index: 2 }
    );
}

#[test]
fn bspline_new_out_of_range() {
    // The points fit I16F16, but the derivative 20000/0.5 = 40000 does not.
    let p = [[i16f16(-10000.0)], [i16f16(10000.0)], [i16f16(0.0)]];
    let t = [0.0, 0.0, 0.5, 1.0, 1.0].map(i16f16);
    assert_eq!(
        BSpline::<[I16F16; 1], 4, 8>::new(1, &p, &t).unwrap_err(),
        Error::OutOfRange
    );
    // A short knot interval: 1/Δu² for the second derivative of a quadratic.
    let p = [
        [i16f16(0.0)],
        [i16f16(100.0)],
        [i16f16(0.0)],
        [i16f16(100.0)],
    ];
    let t = [0.0, 0.0, 0.0, 0.001, 1.0, 1.0, 1.0].map(i16f16);
    assert_eq!(
        BSpline::<[I16F16; 1], 4, 8>::new(2, &p, &t).unwrap_err(),
        Error::OutOfRange
    );
}

#[test]
fn bspline_from_knot_vector_errors() {
    let kv = Kv::clamped_uniform(2, 4, 0.0, 1.0).unwrap();
    assert_eq!(
        BSpline::<[f64; 2], 8, 16>::from_knot_vector(&D4[..2], kv.clone()).unwrap_err(),
        Error::TooFewPoints {
            required: 3,
            found: 2
        }
    );
    assert_eq!(
        BSpline::<[f64; 2], 8, 16>::from_knot_vector(&D4[..3], kv.clone()).unwrap_err(),
        Error::KnotCount {
            expected: 6,
            found: 7
        }
    );
    assert_eq!(
        BSpline::<[f64; 2], 3, 16>::from_knot_vector(&D4, kv.clone()).unwrap_err(),
        Error::CapacityExceeded {
            capacity: 3,
            required: 4
        }
    );
    let mut p = D4;
    p[0][0] = NAN;
    assert_eq!(
        BSpline::<[f64; 2], 8, 16>::from_knot_vector(&p, kv).unwrap_err(),
        Error::NonFinite
    );
    let kv = KnotVector::<I16F16, 8>::new(1, &[0.0, 0.0, 0.5, 1.0, 1.0].map(i16f16)).unwrap();
    let p = [[i16f16(-10000.0)], [i16f16(10000.0)], [i16f16(0.0)]];
    assert_eq!(
        BSpline::<[I16F16; 1], 4, 8>::from_knot_vector(&p, kv).unwrap_err(),
        Error::OutOfRange
    );
}

#[test]
fn bspline_clamped_uniform_errors() {
    assert_eq!(
        B2::clamped_uniform(2, &D4, 1.0, 1.0).unwrap_err(),
        Error::ZeroLengthInterval { index: 2 }
    );
    assert_eq!(
        B2::clamped_uniform(2, &D4, 1.0, 0.0).unwrap_err(),
        Error::KnotsUnsorted { index: 4 }
    );
    assert_eq!(
        B2::clamped_uniform(2, &D4, NAN, 1.0).unwrap_err(),
        Error::NonFinite
    );
    assert_eq!(
        B2::clamped_uniform(4, &D4, 0.0, 1.0).unwrap_err(),
        Error::TooFewPoints {
            required: 5,
            found: 4
        }
    );
    assert_eq!(
        B2::clamped_uniform(9, &D4, 0.0, 1.0).unwrap_err(),
        Error::DegreeTooHigh { max: 7, found: 9 }
    );
    assert_eq!(
        BSpline::<[f64; 2], 3, 16>::clamped_uniform(2, &D4, 0.0, 1.0).unwrap_err(),
        Error::CapacityExceeded {
            capacity: 3,
            required: 4
        }
    );
    assert_eq!(
        BSpline::<[f64; 2], 8, 6>::clamped_uniform(2, &D4, 0.0, 1.0).unwrap_err(),
        Error::CapacityExceeded {
            capacity: 6,
            required: 7
        }
    );
}

// ---------------------------------------------------------------------------------------------
// BSpline::closed
// ---------------------------------------------------------------------------------------------

const SQUARE: [[f64; 2]; 4] = [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]];

#[test]
fn bspline_closed_invalid_argument_degree_zero() {
    assert_eq!(
        B2::closed(0, &SQUARE, None).unwrap_err(),
        Error::InvalidArgument
    );
}

#[test]
fn bspline_closed_degree_too_high() {
    assert_eq!(
        B2::closed(8, &SQUARE, None).unwrap_err(),
        Error::DegreeTooHigh { max: 7, found: 8 }
    );
}

#[test]
fn bspline_closed_too_few_points() {
    assert_eq!(
        B2::closed(3, &SQUARE[..3], None).unwrap_err(),
        Error::TooFewPoints {
            required: 4,
            found: 3
        }
    );
}

#[test]
fn bspline_closed_capacity_exceeded() {
    // N must hold K + g points, M the K + 2g + 1 extended knots.
    assert_eq!(
        BSpline::<[f64; 2], 6, 16>::closed(3, &SQUARE, None).unwrap_err(),
        Error::CapacityExceeded {
            capacity: 6,
            required: 7
        }
    );
    assert_eq!(
        BSpline::<[f64; 2], 8, 10>::closed(3, &SQUARE, None).unwrap_err(),
        Error::CapacityExceeded {
            capacity: 10,
            required: 11
        }
    );
}

#[test]
fn bspline_closed_knot_count() {
    assert_eq!(
        B2::closed(2, &SQUARE, Some(&[0., 1., 2., 3.])).unwrap_err(),
        Error::KnotCount {
            expected: 5,
            found: 4
        }
    );
}

#[test]
fn bspline_closed_zero_length_interval() {
    assert_eq!(
        B2::closed(2, &SQUARE, Some(&[1., 1., 1., 1., 1.])).unwrap_err(),
        Error::ZeroLengthInterval { index: 0 }
    );
}

#[test]
fn bspline_closed_knots_unsorted() {
    assert_eq!(
        B2::closed(2, &SQUARE, Some(&[0., 1., 0.5, 3., 4.])).unwrap_err(),
        Error::KnotsUnsorted { index: 2 }
    );
}

#[test]
fn bspline_closed_knot_multiplicity() {
    // An inner run of g + 1 = 3 equal knots.
    assert_eq!(
        B2::closed(2, &SQUARE, Some(&[0., 1., 1., 1., 4.])).unwrap_err(),
        Error::KnotMultiplicity { index: 1 }
    );
    // The seam: u_0 = u_1 and u_3 = u_4 make the knot u_0 ≅ u_4 three-fold around the circle.
    assert_eq!(
        B2::closed(2, &SQUARE, Some(&[0., 0., 1., 2., 2.])).unwrap_err(),
        Error::KnotMultiplicity { index: 0 }
    );
    // Two-fold at the seam is fine for g = 2.
    assert!(B2::closed(2, &SQUARE, Some(&[0., 1., 2., 3., 3.])).is_ok());
}

#[test]
fn bspline_closed_non_finite() {
    let mut p = SQUARE;
    p[1][0] = NAN;
    assert_eq!(B2::closed(2, &p, None).unwrap_err(), Error::NonFinite);
    assert_eq!(
        B2::closed(2, &SQUARE, Some(&[0., 1., NAN, 3., 4.])).unwrap_err(),
        Error::NonFinite
    );
}

#[test]
fn bspline_closed_out_of_range() {
    // The period 16000 extends the knots beyond the I16F16 range.
    let p = SQUARE.map(|q| q.map(i16f16));
    let t = [0.0, 4000.0, 8000.0, 12000.0, 16000.0].map(i16f16);
    assert_eq!(
        BSpline::<[I16F16; 2], 8, 16>::closed(2, &p, Some(&t)).unwrap_err(),
        Error::OutOfRange
    );
}

// ---------------------------------------------------------------------------------------------
// BSpline::insert_knot, to_bezier_segments
// ---------------------------------------------------------------------------------------------

#[test]
fn bspline_insert_knot_non_finite() {
    assert_eq!(bspline().insert_knot(NAN).unwrap_err(), Error::NonFinite);
    assert_eq!(bspline().insert_knot(INF).unwrap_err(), Error::NonFinite);
}

#[test]
fn bspline_insert_knot_invalid_argument_outside_domain() {
    assert_eq!(
        bspline().insert_knot(-0.1).unwrap_err(),
        Error::InvalidArgument
    );
    assert_eq!(
        bspline().insert_knot(1.5).unwrap_err(),
        Error::InvalidArgument
    );
}

#[test]
fn bspline_insert_knot_capacity_exceeded() {
    let full_n = BSpline::<[f64; 2], 4, 16>::new(2, &D4, &T4).unwrap();
    assert_eq!(
        full_n.insert_knot(0.25).unwrap_err(),
        Error::CapacityExceeded {
            capacity: 4,
            required: 5
        }
    );
    let full_m = BSpline::<[f64; 2], 8, 7>::new(2, &D4, &T4).unwrap();
    assert_eq!(
        full_m.insert_knot(0.25).unwrap_err(),
        Error::CapacityExceeded {
            capacity: 7,
            required: 8
        }
    );
}

#[test]
fn bspline_insert_knot_knot_multiplicity() {
    // 0.5 is simple; after one insertion it has multiplicity g = 2, the most for an inner knot.
    let twice = bspline().insert_knot(0.5).unwrap();
    assert_eq!(
        twice.insert_knot(0.5).unwrap_err(),
        Error::KnotMultiplicity { index: 3 }
    );
    // The clamped end already has multiplicity g + 1.
    assert_eq!(
        bspline().insert_knot(0.0).unwrap_err(),
        Error::KnotMultiplicity { index: 0 }
    );
}

#[test]
fn bspline_to_bezier_segments_length_mismatch() {
    assert_eq!(
        bspline().to_bezier_segments::<4, 8>().unwrap_err(),
        Error::LengthMismatch {
            expected: 3,
            found: 4
        }
    );
}

#[test]
fn bspline_to_bezier_segments_capacity_exceeded() {
    assert_eq!(
        bspline().to_bezier_segments::<3, 1>().unwrap_err(),
        Error::CapacityExceeded {
            capacity: 1,
            required: 2
        }
    );
}

// ---------------------------------------------------------------------------------------------
// Nurbs
// ---------------------------------------------------------------------------------------------

const W4: [f64; 4] = [1.0, 2.0, 0.5, 1.0];

#[test]
fn nurbs_new_length_mismatch() {
    assert_eq!(
        R2::new(2, &D4, &W4[..3], &T4).unwrap_err(),
        Error::LengthMismatch {
            expected: 4,
            found: 3
        }
    );
}

#[test]
fn nurbs_new_non_finite() {
    assert_eq!(
        R2::new(2, &D4, &[1.0, NAN, 1.0, 1.0], &T4).unwrap_err(),
        Error::NonFinite
    );
    assert_eq!(
        R2::new(2, &D4, &[1.0, INF, 1.0, 1.0], &T4).unwrap_err(),
        Error::NonFinite
    );
    let mut p = D4;
    p[3][1] = NAN;
    assert_eq!(R2::new(2, &p, &W4, &T4).unwrap_err(), Error::NonFinite);
}

#[test]
fn nurbs_new_non_positive_weight() {
    assert_eq!(
        R2::new(2, &D4, &[1.0, 1.0, 0.0, 1.0], &T4).unwrap_err(),
        Error::NonPositiveWeight { index: 2 }
    );
    assert_eq!(
        R2::new(2, &D4, &[-1.0, 1.0, 1.0, 1.0], &T4).unwrap_err(),
        Error::NonPositiveWeight { index: 0 }
    );
}

#[test]
fn nurbs_new_out_of_range() {
    type R = Nurbs<[I16F16; 2], 8, 16>;
    let p = D4.map(|q| q.map(i16f16));
    let t = T4.map(i16f16);
    // A weight too small for the I16F16 resolution (de Boor's rounding could reach zero).
    let w = [1.0, 1.0 / 8192.0, 1.0, 1.0].map(i16f16);
    assert_eq!(R::new(2, &p, &w, &t).unwrap_err(), Error::OutOfRange);
    // w·P out of range.
    let mut big = p;
    big[1] = [i16f16(10000.0), i16f16(0.0)];
    let w = [1.0, 2.0, 1.0, 1.0].map(i16f16);
    assert_eq!(R::new(2, &big, &w, &t).unwrap_err(), Error::OutOfRange);
}

#[test]
fn nurbs_new_capacity_exceeded() {
    assert_eq!(
        Nurbs::<[f64; 2], 3, 16>::new(2, &D4, &W4, &T4).unwrap_err(),
        Error::CapacityExceeded {
            capacity: 3,
            required: 4
        }
    );
}

#[test]
fn nurbs_new_passes_bspline_errors() {
    assert_eq!(
        R2::new(2, &D4, &W4, &T4[..6]).unwrap_err(),
        Error::KnotCount {
            expected: 7,
            found: 6
        }
    );
    assert_eq!(
        R2::new(8, &D4, &W4, &T4).unwrap_err(),
        Error::DegreeTooHigh { max: 7, found: 8 }
    );
    assert_eq!(
        R2::new(2, &D4, &W4, &[0., 0., 0., 0.5, 0.4, 1., 1.]).unwrap_err(),
        Error::KnotsUnsorted { index: 4 }
    );
}

#[test]
fn nurbs_clamped_uniform_errors() {
    assert_eq!(
        R2::clamped_uniform(2, &D4, &W4, 1.0, 1.0).unwrap_err(),
        Error::ZeroLengthInterval { index: 2 }
    );
    assert_eq!(
        R2::clamped_uniform(2, &D4, &[1.0, 1.0, -2.0, 1.0], 0.0, 1.0).unwrap_err(),
        Error::NonPositiveWeight { index: 2 }
    );
    assert_eq!(
        R2::clamped_uniform(2, &D4, &W4[..2], 0.0, 1.0).unwrap_err(),
        Error::LengthMismatch {
            expected: 4,
            found: 2
        }
    );
}

#[test]
fn nurbs_closed_errors() {
    assert_eq!(
        R2::closed(0, &SQUARE, &W4, None).unwrap_err(),
        Error::InvalidArgument
    );
    assert_eq!(
        R2::closed(2, &SQUARE, &[1.0, 0.0, 1.0, 1.0], None).unwrap_err(),
        Error::NonPositiveWeight { index: 1 }
    );
    assert_eq!(
        R2::closed(2, &SQUARE, &W4, Some(&[0., 1., 2.])).unwrap_err(),
        Error::KnotCount {
            expected: 5,
            found: 3
        }
    );
}

#[test]
fn nurbs_from_homogeneous_non_positive_weight() {
    let h = [
        Homogeneous {
            weighted: [0.0, 0.0],
            weight: 1.0,
        },
        Homogeneous {
            weighted: [1.0, 1.0],
            weight: -1.0,
        },
        Homogeneous {
            weighted: [2.0, 0.0],
            weight: 1.0,
        },
    ];
    let b = BSpline::<_, 8, 16>::clamped_uniform(2, &h, 0.0, 1.0).unwrap();
    assert_eq!(
        R2::from_homogeneous(b).unwrap_err(),
        Error::NonPositiveWeight { index: 1 }
    );
}

#[test]
fn nurbs_from_homogeneous_out_of_range() {
    // The projected point 10000 / 0.25 = 40000 does not fit I16F16.
    let hp = |x: f64, w: f64| Homogeneous {
        weighted: [i16f16(x)],
        weight: i16f16(w),
    };
    let h = [hp(0.0, 1.0), hp(10000.0, 0.25)];
    let b = BSpline::<_, 4, 8>::clamped_uniform(1, &h, i16f16(0.0), i16f16(4.0)).unwrap();
    assert_eq!(
        Nurbs::<[I16F16; 1], 4, 8>::from_homogeneous(b).unwrap_err(),
        Error::OutOfRange
    );
}

#[test]
fn nurbs_circle_invalid_argument() {
    // Fewer than two coordinates; radius not positive.
    assert_eq!(
        Nurbs::<[f64; 1], 9, 12>::circle([0.0], 1.0).unwrap_err(),
        Error::InvalidArgument
    );
    assert_eq!(
        Nurbs::<[f64; 2], 9, 12>::circle([0.0, 0.0], 0.0).unwrap_err(),
        Error::InvalidArgument
    );
    assert_eq!(
        Nurbs::<[f64; 2], 9, 12>::circle([0.0, 0.0], -1.0).unwrap_err(),
        Error::InvalidArgument
    );
}

#[test]
fn nurbs_circle_non_finite() {
    assert_eq!(
        Nurbs::<[f64; 2], 9, 12>::circle([NAN, 0.0], 1.0).unwrap_err(),
        Error::NonFinite
    );
    assert_eq!(
        Nurbs::<[f64; 2], 9, 12>::circle([0.0, 0.0], INF).unwrap_err(),
        Error::NonFinite
    );
}

#[test]
fn nurbs_circle_capacity_exceeded() {
    assert_eq!(
        Nurbs::<[f64; 2], 8, 12>::circle([0.0, 0.0], 1.0).unwrap_err(),
        Error::CapacityExceeded {
            capacity: 8,
            required: 9
        }
    );
    assert_eq!(
        Nurbs::<[f64; 2], 9, 11>::circle([0.0, 0.0], 1.0).unwrap_err(),
        Error::CapacityExceeded {
            capacity: 11,
            required: 12
        }
    );
}

#[test]
fn nurbs_circle_out_of_range() {
    let c = [i16f16(10000.0), i16f16(0.0)];
    assert_eq!(
        Nurbs::<[I16F16; 2], 9, 12>::circle(c, i16f16(10000.0)).unwrap_err(),
        Error::OutOfRange
    );
}

#[test]
fn nurbs_insert_knot_errors() {
    let c = R2::new(2, &D4, &W4, &T4).unwrap();
    assert_eq!(c.insert_knot(2.0).unwrap_err(), Error::InvalidArgument);
    assert_eq!(c.insert_knot(NAN).unwrap_err(), Error::NonFinite);
    assert_eq!(
        c.insert_knot(0.0).unwrap_err(),
        Error::KnotMultiplicity { index: 0 }
    );
    assert_eq!(
        Nurbs::<[f64; 2], 4, 16>::new(2, &D4, &W4, &T4)
            .unwrap()
            .insert_knot(0.3)
            .unwrap_err(),
        Error::CapacityExceeded {
            capacity: 4,
            required: 5
        }
    );
}

#[test]
fn nurbs_to_rational_bezier_segments_errors() {
    let c = R2::new(2, &D4, &W4, &T4).unwrap();
    assert_eq!(
        c.to_rational_bezier_segments::<2, 4>().unwrap_err(),
        Error::LengthMismatch {
            expected: 3,
            found: 2
        }
    );
    assert_eq!(
        c.to_rational_bezier_segments::<3, 1>().unwrap_err(),
        Error::CapacityExceeded {
            capacity: 1,
            required: 2
        }
    );
}

// ---------------------------------------------------------------------------------------------
// Analysis
// ---------------------------------------------------------------------------------------------

/// A curve whose derivatives are NaN: the analysis must report [`Error::NonFinite`] rather
/// than loop or return garbage.
#[derive(Debug)]
struct NanCurve;

impl ParamCurve for NanCurve {
    type Point = [f64; 2];
    fn domain(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn eval(&self, u: f64) -> [f64; 2] {
        [u, NAN]
    }
}

impl ParamCurveDeriv for NanCurve {
    fn deriv(&self, u: f64, k: usize) -> [f64; 2] {
        if k == 0 { self.eval(u) } else { [1.0, NAN] }
    }
}

const BAD_TOLERANCES: [f64; 5] = [0.0, -1.0, NAN, INF, -INF];

#[test]
fn classify_invalid_argument() {
    let c = bspline();
    let jet = [[0.0, 0.0]; 4];
    for tol in BAD_TOLERANCES {
        assert_eq!(
            classify_derivatives(&jet, &jet, tol).unwrap_err(),
            Error::InvalidArgument
        );
        assert_eq!(
            classify_join(&c, &c, tol).unwrap_err(),
            Error::InvalidArgument
        );
        assert_eq!(
            classify_breaks(&c, tol).unwrap_err(),
            Error::InvalidArgument
        );
    }
}

#[test]
fn flatten_invalid_argument() {
    let mut out = [[0.0; 2]; 64];
    for tol in BAD_TOLERANCES {
        assert_eq!(
            flatten(&bspline(), tol, &mut out).unwrap_err(),
            Error::InvalidArgument
        );
        assert_eq!(
            flatten_count(&bspline(), tol).unwrap_err(),
            Error::InvalidArgument
        );
    }
}

#[test]
fn flatten_capacity_exceeded() {
    let c = bspline();
    let n = flatten_count(&c, 1e-3).unwrap();
    assert!(n > 4);
    let mut out = [[0.0; 2]; 4];
    assert_eq!(
        flatten(&c, 1e-3, &mut out).unwrap_err(),
        Error::CapacityExceeded {
            capacity: 4,
            required: n
        }
    );
    // The first four vertices were stored.
    assert_eq!(out[0], c.eval(0.0));
    // A tolerance far below the curve's size: more than 2^16 segments in one piece.
    match flatten_count(&c, 1e-14).unwrap_err() {
        Error::CapacityExceeded { capacity, required } => {
            assert_eq!(capacity, 1 << 16);
            assert!(required > 1 << 16);
        }
        e => panic!("unexpected {e:?}"),
    }
    // Below the resolution of f64 at the curve's size: rejected before any segment is tried.
    assert_eq!(
        flatten_count(&c, 1e-300).unwrap_err(),
        Error::ToleranceBelowResolution { scalar: "f64" }
    );
}

#[test]
fn flatten_non_finite() {
    let mut out = [[0.0; 2]; 64];
    assert_eq!(
        flatten(&NanCurve, 1e-3, &mut out).unwrap_err(),
        Error::NonFinite
    );
    assert_eq!(
        flatten_count(&NanCurve, 1e-3).unwrap_err(),
        Error::NonFinite
    );
}

#[test]
fn arc_length_invalid_argument() {
    let c = bspline();
    for acc in BAD_TOLERANCES {
        assert_eq!(arc_length(&c, acc).unwrap_err(), Error::InvalidArgument);
        assert_eq!(
            arc_length_between(&c, 0.0, 1.0, acc).unwrap_err(),
            Error::InvalidArgument
        );
        assert_eq!(
            param_at_length(&c, 1.0, acc).unwrap_err(),
            Error::InvalidArgument
        );
        assert_eq!(
            ArcLengthTable::<f64, 8>::new(&c, acc).unwrap_err(),
            Error::InvalidArgument
        );
    }
    assert_eq!(
        ArcLengthTable::<f64, 1>::new(&c, 1e-9).unwrap_err(),
        Error::InvalidArgument
    );
}

#[test]
fn arc_length_non_finite() {
    assert_eq!(arc_length(&NanCurve, 1e-9).unwrap_err(), Error::NonFinite);
    assert_eq!(
        arc_length_between(&NanCurve, 0.0, 1.0, 1e-9).unwrap_err(),
        Error::NonFinite
    );
    assert_eq!(
        param_at_length(&NanCurve, 0.5, 1e-9).unwrap_err(),
        Error::NonFinite
    );
    assert_eq!(
        ArcLengthTable::<f64, 8>::new(&NanCurve, 1e-9).unwrap_err(),
        Error::NonFinite
    );
    // A NaN target length.
    assert_eq!(
        param_at_length(&bspline(), NAN, 1e-9).unwrap_err(),
        Error::NonFinite
    );
}

#[test]
fn arc_length_table_zero_length_interval() {
    // A B-spline standing still: all de Boor points equal.
    let c = B2::new(2, &[[1.0, 1.0]; 4], &T4).unwrap();
    assert_eq!(
        ArcLengthTable::<f64, 8>::new(&c, 1e-9).unwrap_err(),
        Error::ZeroLengthInterval { index: 0 }
    );
    // Standing still on the second half only (the last three points equal).
    let c = B2::new(
        1,
        &[[0.0, 0.0], [1.0, 0.0], [1.0, 0.0]],
        &[0., 0., 0.5, 1., 1.],
    )
    .unwrap();
    assert_eq!(
        ArcLengthTable::<f64, 5>::new(&c, 1e-9).unwrap_err(),
        Error::ZeroLengthInterval { index: 2 }
    );
}

#[test]
fn arc_length_table_out_of_range() {
    // A zig-zag of degree 1 between ±8000 in I16F16: every point and the speed 16000 fit, the
    // length 64000 does not.
    let p = [-8000.0, 8000.0, -8000.0, 8000.0, -8000.0].map(|x| [i16f16(x)]);
    let c =
        BSpline::<[I16F16; 1], 8, 16>::clamped_uniform(1, &p, i16f16(0.0), i16f16(4.0)).unwrap();
    assert_eq!(
        ArcLengthTable::<I16F16, 9>::new(&c, 1e-3).unwrap_err(),
        Error::OutOfRange
    );
}

// ---------------------------------------------------------------------------------------------
// Arbitrary input never panics
// ---------------------------------------------------------------------------------------------

fn run<S: Strategy>(cases: u32, strategy: S, test: impl Fn(S::Value) -> TestCaseResult)
where
    S::Value: std::fmt::Debug,
{
    let config = Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    };
    if let Err(e) = TestRunner::new(config).run(&strategy, test) {
        panic!("{e}");
    }
}

/// Any `f64`: NaN, ±∞, subnormals, huge values, and mostly ordinary small values.
fn wild() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => -4.0..4.0_f64,
        1 => prop::num::f64::ANY,
        1 => prop_oneof![Just(NAN), Just(INF), Just(-INF), Just(1e30), Just(-1e30), Just(f64::MAX), Just(f64::MIN_POSITIVE), Just(0.0)],
        1 => -1e12..1e12_f64,
    ]
}

/// Knots: sorted (so that many are valid), sometimes shuffled by leaving them unsorted.
fn knots(len: std::ops::Range<usize>) -> impl Strategy<Value = Vec<f64>> {
    (prop::collection::vec(wild(), len), any::<bool>()).prop_map(|(mut k, sort)| {
        if sort {
            k.sort_by(f64::total_cmp);
        }
        k
    })
}

/// Evaluates every path of a B-spline at the parameters `us` (results are discarded: only the
/// absence of a panic is checked, plus that finite inputs give values inside the domain's
/// clamping).
fn exercise_bspline<P: strak_curves::Point, const N: usize, const M: usize>(
    c: &BSpline<P, N, M>,
    us: &[P::Scalar],
) {
    let kv = c.knot_vector();
    let mut rows = [[P::Scalar::ZERO; 8]; 10];
    let mut out = [P::zero(); 10];
    for &u in us {
        let _ = c.eval(u);
        for k in 0..10 {
            let _ = c.deriv(u, k);
            for piece in [0, 1, c.piece_count(), usize::MAX] {
                let _ = c.piece_deriv(piece, u, k);
                let _ = PieceDeriv::piece_deriv(c, piece, u, k);
            }
        }
        c.derivatives(u, &mut out);
        let _ = bspline_basis(kv, u);
        let _ = bspline_basis_derivs(kv, u, &mut rows);
        let _ = kv.span(u);
        let _ = kv.span_with_hint(u, usize::MAX);
        let _ = kv.multiplicity(u);
        let _ = c.insert_knot(u);
    }
    let _ = c.piece_domain(usize::MAX);
}

fn exercise_nurbs<P: strak_curves::Point, const N: usize, const M: usize>(
    c: &Nurbs<P, N, M>,
    us: &[P::Scalar],
) {
    let mut out = [P::zero(); 10];
    for &u in us {
        let _ = c.eval(u);
        for k in 0..10 {
            let _ = c.deriv(u, k);
            for piece in [0, 1, c.piece_count(), usize::MAX] {
                let _ = c.piece_deriv(piece, u, k);
            }
        }
        c.derivatives(u, &mut out);
        let _ = c.insert_knot(u);
    }
}

/// f64: arbitrary degrees, points, knots, weights and parameters into every constructor and,
/// when one succeeds, into every evaluator.
#[test]
fn arbitrary_f64_input_never_panics() {
    let strategy = (
        0..=9_usize,
        prop::collection::vec([wild(), wild()], 0..12),
        knots(0..22),
        prop::collection::vec(wild(), 0..12),
        prop::collection::vec(wild(), 1..8),
        0..12_usize,
    );
    run(256, strategy, |(g, points, knots, weights, us, i)| {
        let mut us = us;
        us.extend([NAN, INF, -INF, 1e30, -1e30]);
        let _ = KnotVector::<f64, 24>::new(g, &knots);
        for &u in &us {
            let _ = basis_function(&knots, i, g, u);
        }
        if let Ok(c) = BSpline::<[f64; 2], 12, 24>::new(g, &points, &knots) {
            exercise_bspline(&c, &us);
            let _ = c.to_bezier_segments::<4, 12>();
        }
        if let Ok(c) =
            BSpline::<[f64; 2], 12, 24>::clamped_uniform(g, &points, us[0], us[1 % us.len()])
        {
            exercise_bspline(&c, &us);
        }
        let period = (knots.len() > points.len()).then(|| &knots[..=points.len()]);
        if let Ok(c) = BSpline::<[f64; 2], 24, 40>::closed(g, &points, period) {
            exercise_bspline(&c, &us);
        }
        if let Ok(c) = Nurbs::<[f64; 2], 12, 24>::new(g, &points, &weights, &knots) {
            exercise_nurbs(&c, &us);
            let _ = c.to_rational_bezier_segments::<3, 12>();
        }
        if let Ok(c) = Nurbs::<[f64; 2], 24, 40>::closed(g, &points, &weights, period) {
            exercise_nurbs(&c, &us);
        }
        let _ = Nurbs::<[f64; 2], 9, 12>::circle(
            [us[0], us[us.len() - 1]],
            weights.first().copied().unwrap_or(1.0),
        );
        Ok(())
    });
}

/// Arbitrary `I16F16` bit patterns (the whole range, including values near ±32768 that overflow
/// on any arithmetic): constructors must reject what does not fit, and accepted curves must
/// evaluate without overflow at every parameter, including the extremes.
#[test]
fn arbitrary_i16f16_input_never_panics() {
    let fx = || {
        prop_oneof![
            3 => (-4.0..4.0_f64).prop_map(i16f16),
            1 => any::<i32>().prop_map(I16F16::from_bits),
            1 => (-16000.0..16000.0_f64).prop_map(i16f16),
        ]
    };
    let strategy = (
        0..=8_usize,
        prop::collection::vec([fx(), fx()], 0..10),
        (prop::collection::vec(fx(), 0..20), any::<bool>()),
        prop::collection::vec(fx(), 0..10),
        prop::collection::vec(fx(), 1..6),
    );
    run(
        256,
        strategy,
        |(g, points, (mut knots, sort), weights, mut us)| {
            if sort {
                knots.sort();
            }
            us.extend([I16F16::MIN, I16F16::MAX, I16F16::ZERO, I16F16::DELTA]);
            let _ = KnotVector::<I16F16, 24>::new(g, &knots);
            for &u in &us {
                let _ = basis_function(&knots, 0, g, u);
            }
            if let Ok(c) = BSpline::<[I16F16; 2], 12, 24>::new(g, &points, &knots) {
                exercise_bspline(&c, &us);
            }
            if let Ok(c) =
                BSpline::<[I16F16; 2], 12, 24>::clamped_uniform(g, &points, us[0], us[1 % us.len()])
            {
                exercise_bspline(&c, &us);
            }
            let period = (knots.len() > points.len()).then(|| &knots[..=points.len()]);
            if let Ok(c) = BSpline::<[I16F16; 2], 24, 40>::closed(g, &points, period) {
                exercise_bspline(&c, &us);
            }
            if let Ok(c) = Nurbs::<[I16F16; 2], 12, 24>::new(g, &points, &weights, &knots) {
                exercise_nurbs(&c, &us);
            }
            if let Some(&r) = weights.first()
                && let Ok(c) = Nurbs::<[I16F16; 2], 9, 12>::circle([us[0], us[us.len() - 1]], r)
            {
                exercise_nurbs(&c, &us);
            }
            Ok(())
        },
    );
}

/// The same with `I32F32` and `f32` on clamped uniform knots of arbitrary extent (the
/// generators compute knots in `f64` and must range-check them).
#[test]
fn arbitrary_generated_knots_never_panic() {
    run(
        256,
        (
            0..=8_usize,
            prop::collection::vec(wild(), 1..10),
            wild(),
            wild(),
        ),
        |(g, xs, a, b)| {
            let us: Vec<f64> = xs.iter().copied().chain([a, b, NAN, 1e30, -1e30]).collect();
            let p32: Vec<[I32F32; 1]> = xs
                .iter()
                .filter_map(|&x| I32F32::from_f64(x))
                .map(|x| [x])
                .collect();
            let u32s: Vec<I32F32> = us
                .iter()
                .filter_map(|&x| I32F32::from_f64(x))
                .chain([I32F32::MIN, I32F32::MAX])
                .collect();
            if let (Some(a), Some(b)) = (I32F32::from_f64(a), I32F32::from_f64(b)) {
                for kv in [
                    KnotVector::<I32F32, 32>::clamped_uniform(g, p32.len(), a, b),
                    KnotVector::<I32F32, 32>::uniform(g, p32.len(), a, b),
                    KnotVector::<I32F32, 32>::periodic(g, p32.len(), a, b),
                ]
                .into_iter()
                .flatten()
                {
                    if let Ok(c) = BSpline::<[I32F32; 1], 24, 32>::from_knot_vector(
                        &p32[..kv.control_point_count().min(p32.len())],
                        kv,
                    ) {
                        exercise_bspline(&c, &u32s);
                    }
                }
            }
            let pf: Vec<[f32; 1]> = xs.iter().map(|&x| [x as f32]).collect();
            let uf: Vec<f32> = us.iter().map(|&x| x as f32).collect();
            if let Ok(c) = BSpline::<[f32; 1], 16, 32>::clamped_uniform(g, &pf, a as f32, b as f32)
            {
                exercise_bspline(&c, &uf);
            }
            if let Ok(c) = Bezier::new([[a, b], [b, a], [a, a]]) {
                let _ = c.eval(us[0]);
            }
            Ok(())
        },
    );
}

/// Well-shaped curves (sorted knots, multiplicities within the degree) at extreme scales: knot
/// spacing and coordinates from `10^-e` to `10^e`. Many of these construct (the rest must be
/// rejected with an error, not a panic), and every accepted curve must evaluate without a
/// panic at arbitrary parameters — in `f64`, `f32`, `I32F32` and `I16F16`, whose range rule
/// must catch every overflow the scale could cause.
#[test]
fn extreme_scales_never_panic() {
    let strategy = (1..=5_usize, 0..=4_usize).prop_flat_map(|(g, extra)| {
        let k = g + 1 + extra;
        (
            Just(g),
            prop::collection::vec(prop_oneof![1 => Just(0.0), 3 => 0.1..1.0_f64], k + g),
            prop::collection::vec([-1.0..1.0_f64, -1.0..1.0_f64], k),
            prop::collection::vec(0.1..4.0_f64, k),
            -6.0..6.0_f64,
            -6.0..6.0_f64,
            prop::collection::vec(wild(), 1..6),
        )
    });
    let counts = std::cell::Cell::new((0_usize, 0_usize));
    run(
        256,
        strategy,
        |(g, gaps, unit_points, weights, ek, ep, us)| {
            let (ks, ps) = (10f64.powf(ek), 10f64.powf(ep));
            // Clamped ends, inner runs ≤ g: zero gaps only where the run stays short.
            let mut knots = vec![0.0; g + 1];
            let mut run = 1;
            for &gp in &gaps[..gaps.len() - g] {
                let gp = if gp == 0.0 && run < g {
                    0.0
                } else {
                    gp.max(0.1)
                };
                run = if gp == 0.0 { run + 1 } else { 1 };
                knots.push(knots[knots.len() - 1] + gp * ks);
            }
            let last = knots[knots.len() - 1].max(ks);
            knots.truncate(unit_points.len());
            knots.resize(unit_points.len() + g + 1, last);
            knots.sort_by(f64::total_cmp);
            let points: Vec<[f64; 2]> =
                unit_points.iter().map(|p| [p[0] * ps, p[1] * ps]).collect();
            let us: Vec<f64> = us
                .iter()
                .copied()
                .chain(knots.iter().copied())
                .chain([NAN, 1e30, -1e30])
                .collect();
            fn go<S: Scalar>(
                g: usize,
                knots: &[f64],
                points: &[[f64; 2]],
                weights: &[f64],
                us: &[f64],
                counts: &std::cell::Cell<(usize, usize)>,
            ) {
                let conv =
                    |v: &[f64]| -> Option<Vec<S>> { v.iter().map(|&x| S::from_f64(x)).collect() };
                let (Some(k), Some(w)) = (conv(knots), conv(weights)) else {
                    return;
                };
                let Some(p): Option<Vec<[S; 2]>> = points
                    .iter()
                    .map(|q| Some([S::from_f64(q[0])?, S::from_f64(q[1])?]))
                    .collect()
                else {
                    return;
                };
                let u: Vec<S> = us.iter().filter_map(|&x| S::from_f64(x)).collect();
                let (mut tried, mut built) = counts.get();
                tried += 1;
                if let Ok(c) = BSpline::<[S; 2], 12, 24>::new(g, &p, &k) {
                    built += 1;
                    exercise_bspline(&c, &u);
                }
                if let Ok(c) = Nurbs::<[S; 2], 12, 24>::new(g, &p, &w, &k) {
                    exercise_nurbs(&c, &u);
                }
                counts.set((tried, built));
            }
            go::<f64>(g, &knots, &points, &weights, &us, &counts);
            go::<f32>(g, &knots, &points, &weights, &us, &counts);
            go::<I32F32>(g, &knots, &points, &weights, &us, &counts);
            go::<I16F16>(g, &knots, &points, &weights, &us, &counts);
            Ok(())
        },
    );
    let (tried, built) = counts.get();
    eprintln!("extreme scales: {built} of {tried} B-splines constructed and evaluated");
    assert!(
        built * 4 >= tried,
        "too few successful constructions: {built} of {tried}"
    );
}
