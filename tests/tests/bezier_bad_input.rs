//! Bad input for the `basis` module and Bézier curves: one test per typed error of every
//! constructor and fallible function (asserting the exact [`Error`]), and property tests that
//! arbitrary input (NaN, ±∞, huge, arbitrary fixed-point bits, curves at the edge of the
//! fixed-point range) never panics — neither in constructors nor, after a successful
//! construction, in evaluation at arbitrary parameters. (Tests run with overflow checks, so a
//! fixed-point overflow is a panic.)

use glam::{DVec2, Vec2, Vec3};
use proptest::prelude::*;
use proptest::test_runner::{Config, TestCaseError, TestCaseResult, TestRunner};
use strak_curves::basis::{self, LagrangeBasis, MAX_DEGREE, MonomialCurve};
use strak_curves::{
    Bezier, Error, I16F16, I32F32, ParamCurve, ParamCurveDeriv, Point, Scalar,
    quarter_circle_radial_error,
};

/// A one-coordinate I16F16 point.
fn x16(v: f64) -> [I16F16; 1] {
    [I16F16::from_num(v)]
}

/// A two-coordinate I16F16 point.
fn p16(x: f64, y: f64) -> [I16F16; 2] {
    [I16F16::from_num(x), I16F16::from_num(y)]
}

// =============================================================================================
// MonomialCurve

#[test]
fn monomial_curve_too_few_points() {
    assert_eq!(
        MonomialCurve::<[f64; 2], 0>::new([]),
        Err(Error::TooFewPoints {
            required: 1,
            found: 0
        })
    );
}

#[test]
fn monomial_curve_degree_too_high() {
    let r = MonomialCurve::new([x16(0.0); MAX_DEGREE + 2]).map(|_| ());
    assert_eq!(
        r,
        Err(Error::DegreeTooHigh {
            max: MAX_DEGREE,
            found: MAX_DEGREE + 1
        })
    );
}

#[test]
fn monomial_curve_non_finite() {
    assert_eq!(
        MonomialCurve::new([[1.0, 2.0], [f64::NAN, 0.0]]),
        Err(Error::NonFinite)
    );
    assert_eq!(
        MonomialCurve::new([Vec2::ZERO, Vec2::new(0.0, f32::NEG_INFINITY)]),
        Err(Error::NonFinite)
    );
    assert_eq!(
        MonomialCurve::with_domain([[1.0]], f64::NAN, 1.0),
        Err(Error::NonFinite)
    );
    assert_eq!(
        MonomialCurve::with_domain([[1.0]], 0.0, f64::INFINITY),
        Err(Error::NonFinite)
    );
}

#[test]
fn monomial_curve_zero_length_interval() {
    assert_eq!(
        MonomialCurve::with_domain([[1.0], [2.0]], 0.5, 0.5),
        Err(Error::ZeroLengthInterval { index: 0 })
    );
}

#[test]
fn monomial_curve_invalid_argument_for_reversed_domain() {
    assert_eq!(
        MonomialCurve::with_domain([[1.0], [2.0]], 1.0, 0.0),
        Err(Error::InvalidArgument)
    );
}

#[test]
fn monomial_curve_out_of_range() {
    // a coefficient beyond I16F16's LIMIT 16 383 cannot even be represented with headroom;
    // 3 × 6000 is the value bound on [0, 1]
    assert_eq!(
        MonomialCurve::new([x16(6000.0), x16(6000.0), x16(6000.0)]),
        Err(Error::OutOfRange)
    );
    // the derivative 3 · 6000 u² on [0, 1] does not fit, the value 6000 u³ does
    assert_eq!(
        MonomialCurve::new([x16(0.0), x16(0.0), x16(0.0), x16(6000.0)]),
        Err(Error::OutOfRange)
    );
    // a domain bound beyond LIMIT
    assert_eq!(
        MonomialCurve::with_domain([x16(1.0)], I16F16::ZERO, I16F16::from_num(20000)),
        Err(Error::OutOfRange)
    );
    // u³ on [0, 30] reaches 27 000
    assert_eq!(
        MonomialCurve::with_domain(
            [x16(0.0), x16(0.0), x16(0.0), x16(1.0)],
            I16F16::ZERO,
            I16F16::from_num(30)
        ),
        Err(Error::OutOfRange)
    );
    // f32: beyond f32::MAX / 2
    assert_eq!(MonomialCurve::new([[3.0e38_f32]]), Err(Error::OutOfRange));
    // f64: the derivative 2 · 1e308 u overflows
    assert_eq!(
        MonomialCurve::new([[0.0], [0.0], [1.0e308]]),
        Err(Error::OutOfRange)
    );
}

/// A constant curve has zero derivatives, which fit every type; the documented range check
/// ("unless each bound fits") should accept it at any degree.
#[test]
fn monomial_curve_of_high_degree_with_zero_coefficients_is_accepted() {
    assert!(
        MonomialCurve::new([[0.0_f64]; 171]).is_ok(),
        "degree 170 passes"
    );
    assert!(
        MonomialCurve::new([[0.0_f64]; 200]).is_ok(),
        "degree 199 fails"
    );
}

// =============================================================================================
// LagrangeBasis

#[test]
fn lagrange_too_few_points() {
    assert_eq!(
        LagrangeBasis::<f64, 0>::new([]),
        Err(Error::TooFewPoints {
            required: 1,
            found: 0
        })
    );
}

#[test]
fn lagrange_non_finite() {
    assert_eq!(
        LagrangeBasis::new([0.0, f64::NAN, 2.0]),
        Err(Error::NonFinite)
    );
    assert_eq!(
        LagrangeBasis::new([0.0_f32, 1.0, f32::INFINITY]),
        Err(Error::NonFinite)
    );
}

#[test]
fn lagrange_nodes_not_increasing() {
    assert_eq!(
        LagrangeBasis::new([0.0, 1.0, 1.0]),
        Err(Error::NodesNotIncreasing { index: 2 })
    );
    assert_eq!(
        LagrangeBasis::new([0.0, -1.0, 3.0]),
        Err(Error::NodesNotIncreasing { index: 1 })
    );
    assert_eq!(
        LagrangeBasis::new([0.0_f32, 1.0, 2.0, 1.5]),
        Err(Error::NodesNotIncreasing { index: 3 })
    );
    // nodes distinct in f64 that round to the same I16F16 value
    let n = [0.0, 1.0, 1.0 + 1e-6].map(I16F16::from_num);
    assert_eq!(
        LagrangeBasis::new(n),
        Err(Error::NodesNotIncreasing { index: 2 })
    );
}

#[test]
fn lagrange_out_of_range() {
    // a node beyond LIMIT
    let n = [0.0, 20000.0].map(I16F16::from_num);
    assert_eq!(LagrangeBasis::new(n), Err(Error::OutOfRange));
    // close nodes far from the rest: the ratios (t − u_k)/(u_i − u_k) explode
    let n = [0.0, 0.001, 0.002, 100.0].map(I16F16::from_num);
    assert_eq!(LagrangeBasis::new(n), Err(Error::OutOfRange));
    let n = [0.0, 1.0e-300, 2.0e-300, 1.0e300];
    assert_eq!(LagrangeBasis::new(n), Err(Error::OutOfRange));
}

// =============================================================================================
// Basis-change matrices and conversions

#[test]
fn basis_matrices_out_of_range() {
    // g = 12: the entry C(12,4) C(4,2)… up to 12!/(4!4!4!) = 34 650 > 16 383
    assert_eq!(
        basis::bernstein_to_monomial_matrix::<I16F16, 13>(),
        Err(Error::OutOfRange)
    );
    assert_eq!(
        basis::bernstein_basis_matrix::<I16F16, 13>(),
        Err(Error::OutOfRange)
    );
    assert!(basis::bernstein_to_monomial_matrix::<I16F16, 12>().is_ok());
    // I32F32 (LIMIT 2³⁰) reaches its limit at g = 22
    assert_eq!(
        basis::bernstein_to_monomial_matrix::<I32F32, 23>(),
        Err(Error::OutOfRange)
    );
}

/// `T_{B←M}` has entries `C(i, j)/C(g, j)` in `[0, 1]`; it fails only when `C(g, j)` overflows
/// `f64` (documented: "only for absurd degrees"), for example `g = 1030`
/// (`C(1030, 515) > f64::MAX`). At that degree the matrix is 4 MB even in `f32`, more than a
/// test thread's stack holds as a return value, so the entries are checked through the
/// coefficient transform that applies them to a vector (4 KB); the matrix itself is checked
/// at degrees it fits.
#[test]
fn monomial_to_bernstein_matrix_out_of_range_for_absurd_degree() {
    let r = basis::monomial_to_bernstein(&[[1.0_f32]; 1031]).map(|b| b[0]);
    assert_eq!(r, Err(Error::OutOfRange));
    assert!(basis::monomial_to_bernstein(&[[1.0_f32]; 1020]).is_ok());
    assert!(basis::monomial_to_bernstein_matrix::<I16F16, 40>().is_ok());
    assert!(basis::monomial_to_bernstein_matrix::<f32, 200>().is_ok());
}

#[test]
fn conversions_non_finite() {
    assert_eq!(
        basis::bernstein_to_monomial(&[[1.0], [f64::NAN]]),
        Err(Error::NonFinite)
    );
    assert_eq!(
        basis::monomial_to_bernstein(&[Vec3::ZERO, Vec3::new(0.0, f32::INFINITY, 0.0)]),
        Err(Error::NonFinite)
    );
}

#[test]
fn conversions_out_of_range() {
    // b = (10⁴, −10⁴, 10⁴): a_2 = Δ²b_0 = 4 · 10⁴
    let b = [10000.0, -10000.0, 10000.0].map(x16);
    assert_eq!(basis::bernstein_to_monomial(&b), Err(Error::OutOfRange));
    // a = (0, 0, 10⁴, 10⁴): b_3 = Σ a_j = 2 · 10⁴
    let a = [0.0, 0.0, 1.0e4, 1.0e4].map(x16);
    assert_eq!(basis::monomial_to_bernstein(&a), Err(Error::OutOfRange));
    // f32: the cubic's a_1 = 3 (b_1 − b_0) = 3 · 10³⁸ exceeds f32::MAX / 2
    assert_eq!(
        basis::bernstein_to_monomial(&[[0.0_f32], [1.0e38], [0.0], [0.0]]),
        Err(Error::OutOfRange)
    );
}

#[test]
fn binomial_and_pascal_row_overflow() {
    assert_eq!(basis::binomial(100, 50), None);
    assert_eq!(basis::binomial(68, 34), None);
    assert!(basis::binomial(67, 33).is_some());
    assert_eq!(basis::pascal_row::<69>(), None);
    assert!(basis::pascal_row::<68>().is_some());
}

// =============================================================================================
// Bezier::new

#[test]
fn bezier_too_few_points() {
    assert_eq!(
        Bezier::<DVec2, 0>::new([]),
        Err(Error::TooFewPoints {
            required: 1,
            found: 0
        })
    );
}

#[test]
fn bezier_degree_too_high() {
    let r = Bezier::new([x16(0.0); MAX_DEGREE + 2]).map(|_| ());
    assert_eq!(
        r,
        Err(Error::DegreeTooHigh {
            max: MAX_DEGREE,
            found: MAX_DEGREE + 1
        })
    );
}

#[test]
fn bezier_non_finite() {
    assert_eq!(
        Bezier::new([[0.0, 0.0], [f64::NAN, 1.0]]),
        Err(Error::NonFinite)
    );
    assert_eq!(
        Bezier::new([DVec2::ZERO, DVec2::new(0.0, f64::NEG_INFINITY)]),
        Err(Error::NonFinite)
    );
    assert_eq!(
        Bezier::new([Vec2::new(f32::INFINITY, 0.0)]),
        Err(Error::NonFinite)
    );
}

#[test]
fn bezier_out_of_range() {
    // a point beyond LIMIT
    assert_eq!(
        Bezier::new([x16(0.0), x16(20000.0)]),
        Err(Error::OutOfRange)
    );
    // points fit, the first derivative 2 · 10 000 does not
    assert_eq!(
        Bezier::new([x16(-5000.0), x16(5000.0), x16(-5000.0)]),
        Err(Error::OutOfRange)
    );
    // first and second derivative fit, the third 6 · |Δ³b| = 6 · 4000 does not
    assert_eq!(
        Bezier::new([x16(1000.0), x16(0.0), x16(1000.0), x16(0.0)]),
        Err(Error::OutOfRange)
    );
    // f32 beyond f32::MAX / 2, f64 derivative beyond f64::MAX / 2
    assert_eq!(Bezier::new([[0.0_f32], [3.0e38]]), Err(Error::OutOfRange));
    assert_eq!(Bezier::new([[-1.0e308], [1.0e308]]), Err(Error::OutOfRange));
}

/// A constant curve has zero derivatives, which fit every type; the documented range check
/// should accept it at any degree up to `MAX_DEGREE`.
#[test]
fn bezier_of_high_degree_with_equal_points_is_accepted() {
    assert!(Bezier::new([[0.0_f64]; 171]).is_ok(), "degree 170 passes");
    assert!(Bezier::new([[0.0_f64]; 172]).is_ok(), "degree 171 fails");
    assert!(
        Bezier::new([[1.0_f64, 2.0]; 200]).is_ok(),
        "degree 199 fails"
    );
}

// =============================================================================================
// hodograph, elevate

#[test]
fn hodograph_length_mismatch() {
    let c = Bezier::new([[0.0], [1.0], [3.0]]).unwrap();
    assert_eq!(
        c.hodograph::<3>(),
        Err(Error::LengthMismatch {
            expected: 2,
            found: 3
        })
    );
    assert_eq!(
        c.hodograph::<1>(),
        Err(Error::LengthMismatch {
            expected: 2,
            found: 1
        })
    );
}

#[test]
fn hodograph_too_few_points_for_degree_zero() {
    let c = Bezier::new([[1.0, 2.0]]).unwrap();
    assert_eq!(
        c.hodograph::<0>(),
        Err(Error::TooFewPoints {
            required: 1,
            found: 0
        })
    );
}

#[test]
fn elevate_length_mismatch() {
    let c = Bezier::new([[0.0], [1.0], [3.0]]).unwrap();
    assert_eq!(
        c.elevate::<5>(),
        Err(Error::LengthMismatch {
            expected: 4,
            found: 5
        })
    );
    assert_eq!(
        c.elevate::<3>(),
        Err(Error::LengthMismatch {
            expected: 4,
            found: 3
        })
    );
}

/// `elevate` of a valid I16F16 curve whose first-derivative bound is exactly at the limit:
/// `2 · 8191.5 = 16 383`. The elevated points use the weight `1/3` rounded to I16F16, so the
/// elevated first leg `3 · (e_1 − e_0)` exceeds 16 383 by a few units: `OutOfRange`.
///
/// (`elevate`'s documentation lists only `LengthMismatch` and `DegreeTooHigh`; the error comes
/// from the validation of the elevated curve by `Bezier::new`.)
#[test]
fn elevate_out_of_range_at_the_fixed_point_limit() {
    let c = Bezier::new([x16(0.0), x16(8191.5), x16(16383.0)]).unwrap();
    assert_eq!(c.elevate::<4>(), Err(Error::OutOfRange));
    // with headroom it works
    let c = Bezier::new([x16(0.0), x16(8000.0), x16(16000.0)]).unwrap();
    assert!(c.elevate::<4>().is_ok());
}

/// `elevate` reports `DegreeTooHigh` when `g + 1 > MAX_DEGREE`, which needs a curve of degree
/// `MAX_DEGREE`; with the bug above no such curve can be built (zero points are rejected, all
/// others exceed the range), so the error is unreachable today.
#[test]
fn elevate_degree_too_high() {
    let elevated = || {
        let c = Bezier::new([[0.0_f64]; MAX_DEGREE + 1]).map_err(|e| format!("new: {e:?}"))?;
        c.elevate::<{ MAX_DEGREE + 2 }>()
            .map(|_| ())
            .map_err(|e| format!("{e:?}"))
    };
    let r = elevated();
    assert_eq!(
        r,
        Err(format!(
            "{:?}",
            Error::DegreeTooHigh {
                max: MAX_DEGREE,
                found: MAX_DEGREE + 1
            }
        ))
    );
}

// =============================================================================================
// to_monomial, from_monomial

#[test]
fn to_monomial_out_of_range() {
    // b = (0, 500, 0, 500) is a valid I16F16 curve, but its monomial form 1500t − 3000t² + 2000t³
    // has the Horner bound 3000 · 2 + 2000 · 6 = 18 000 for the second derivative
    let c = Bezier::new([x16(0.0), x16(500.0), x16(0.0), x16(500.0)]).unwrap();
    assert_eq!(c.to_monomial(), Err(Error::OutOfRange));
}

#[test]
fn from_monomial_out_of_range() {
    // u² on [0, 100]: Bézier points 0, 0, 10 000 and the second derivative 2 · 10 000
    let m = MonomialCurve::with_domain(
        [x16(0.0), x16(0.0), x16(1.0)],
        I16F16::ZERO,
        I16F16::from_num(100),
    )
    .unwrap();
    assert_eq!(Bezier::from_monomial(&m), Err(Error::OutOfRange));
}

// =============================================================================================
// join_c1, join_g1

#[test]
fn join_c1_too_few_points() {
    let a = Bezier::new([DVec2::ZERO, DVec2::X]).unwrap();
    let k = Bezier::new([DVec2::Y]).unwrap();
    assert_eq!(
        a.join_c1(&k),
        Err(Error::TooFewPoints {
            required: 2,
            found: 1
        })
    );
}

#[test]
fn join_c1_out_of_range() {
    // c_1 = b_1 + (b_1 − b_0) = 20 000 does not fit I16F16
    let a = Bezier::new([p16(0.0, 0.0), p16(10000.0, 0.0)]).unwrap();
    let b = Bezier::new([p16(0.0, 0.0), p16(1.0, 0.0)]).unwrap();
    assert_eq!(a.join_c1(&b), Err(Error::OutOfRange));
    // quadratics: c_1 = 8000 + (2/2)(8000 − 6000) = 10 000 fits, but the adjusted curve
    // (8000, 10 000, −5000) has the derivative bound 2 · 15 000
    let a = Bezier::new([p16(0.0, 0.0), p16(6000.0, 0.0), p16(8000.0, 0.0)]).unwrap();
    let b = Bezier::new([p16(0.0, 0.0), p16(1.0, 0.0), p16(-5000.0, 0.0)]).unwrap();
    assert_eq!(a.join_c1(&b), Err(Error::OutOfRange));
}

#[test]
fn join_g1_too_few_points() {
    let a = Bezier::new([DVec2::ZERO, DVec2::X]).unwrap();
    let k = Bezier::new([DVec2::Y]).unwrap();
    assert_eq!(
        a.join_g1(&k, None),
        Err(Error::TooFewPoints {
            required: 2,
            found: 1
        })
    );
}

#[test]
fn join_g1_invalid_argument() {
    let b = Bezier::new([DVec2::ZERO, DVec2::Y, DVec2::X]).unwrap();
    // zero end tangent b_{g−1} = b_g: no direction
    let flat = Bezier::new([DVec2::ZERO, DVec2::X, DVec2::X]).unwrap();
    assert_eq!(flat.join_g1(&b, None), Err(Error::InvalidArgument));
    // degree 0: no end tangent at all
    let point = Bezier::new([DVec2::X]).unwrap();
    assert_eq!(point.join_g1(&b, Some(1.0)), Err(Error::InvalidArgument));
    // tangent length zero or negative
    let a = Bezier::new([DVec2::ZERO, DVec2::X]).unwrap();
    assert_eq!(a.join_g1(&b, Some(0.0)), Err(Error::InvalidArgument));
    assert_eq!(a.join_g1(&b, Some(-1.0)), Err(Error::InvalidArgument));
    // None, and next's own first leg is zero: no length to keep
    let zero_leg = Bezier::new([DVec2::ZERO, DVec2::ZERO, DVec2::X]).unwrap();
    assert_eq!(a.join_g1(&zero_leg, None), Err(Error::InvalidArgument));
}

#[test]
fn join_g1_non_finite() {
    let a = Bezier::new([DVec2::ZERO, DVec2::X]).unwrap();
    let b = Bezier::new([DVec2::ZERO, DVec2::Y, DVec2::X]).unwrap();
    assert_eq!(a.join_g1(&b, Some(f64::NAN)), Err(Error::NonFinite));
    assert_eq!(a.join_g1(&b, Some(f64::INFINITY)), Err(Error::NonFinite));
}

#[test]
fn join_g1_out_of_range() {
    let a = Bezier::new([p16(0.0, 0.0), p16(1.0, 0.0)]).unwrap();
    let b = Bezier::new([p16(0.0, 0.0), p16(0.0, 1.0), p16(2.0, 0.0)]).unwrap();
    // c_1 = (1 + 16 000, 0) does not fit
    assert_eq!(
        a.join_g1(&b, Some(I16F16::from_num(16000))),
        Err(Error::OutOfRange)
    );
    // c_1 = (8001, 0) fits, the derivative 2 · 8000 fits, 2 · |c_2 − c_1| = 15 998 fits, but
    // the second derivative 2 · |c_2 − 2 c_1 + c_0| = 2 · 15 999 does not
    assert_eq!(
        a.join_g1(&b, Some(I16F16::from_num(8000))),
        Err(Error::OutOfRange)
    );
}

// =============================================================================================
// Quarter circle

#[test]
fn quarter_circle_length_mismatch_for_one_dimension() {
    assert_eq!(
        Bezier::<[f64; 1], 4>::quarter_circle(0.5),
        Err(Error::LengthMismatch {
            expected: 2,
            found: 1
        })
    );
    assert_eq!(
        Bezier::<[I16F16; 1], 4>::quarter_circle_seed(),
        Err(Error::LengthMismatch {
            expected: 2,
            found: 1
        })
    );
}

#[test]
fn quarter_circle_non_finite() {
    assert_eq!(
        Bezier::<DVec2, 4>::quarter_circle(f64::NAN),
        Err(Error::NonFinite)
    );
    assert_eq!(
        Bezier::<Vec3, 4>::quarter_circle(f32::INFINITY),
        Err(Error::NonFinite)
    );
}

#[test]
fn quarter_circle_out_of_range() {
    // κ = 10 000 fits I16F16, the start derivative 3κ does not
    assert_eq!(
        Bezier::<[I16F16; 2], 4>::quarter_circle(I16F16::from_num(10000)),
        Err(Error::OutOfRange)
    );
    // quarter_circle_seed's OutOfRange (κ not representable) cannot happen: 0.551897 fits
    // every scalar type
    assert!(Bezier::<[I16F16; 2], 4>::quarter_circle_seed().is_ok());
    assert!(Bezier::<[I32F32; 3], 4>::quarter_circle_seed().is_ok());
    assert!(Bezier::<Vec2, 4>::quarter_circle_seed().is_ok());
}

#[test]
fn quarter_circle_radial_error_of_non_finite_kappa_is_nan() {
    assert!(quarter_circle_radial_error(f64::NAN).is_nan());
    assert!(quarter_circle_radial_error(f64::INFINITY).is_nan());
    assert!(quarter_circle_radial_error(f64::NEG_INFINITY).is_nan());
}

// =============================================================================================
// No panics on arbitrary input

/// Runs a no-panic property (proptest catches panics and reports the minimal input).
fn run<T: Strategy>(name: &str, cases: u32, strategy: T, body: impl Fn(T::Value) -> TestCaseResult)
where
    T::Value: std::fmt::Debug,
{
    let mut runner = TestRunner::new(Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    });
    if let Err(e) = runner.run(&strategy, body) {
        panic!("{name}: {e}");
    }
}

/// `Err` unless `cond`.
fn ensure(cond: bool, what: impl FnOnce() -> String) -> TestCaseResult {
    if cond {
        Ok(())
    } else {
        Err(TestCaseError::fail(what()))
    }
}

/// Any `f64`: mostly moderate values (so that constructions succeed), plus NaN, ±∞, ±1e30,
/// huge, tiny and arbitrary bit patterns.
fn any_f64() -> impl Strategy<Value = f64> {
    prop_oneof![
        6 => -10.0..10.0_f64,
        1 => any::<f64>(),
        1 => prop_oneof![
            Just(f64::NAN),
            Just(f64::INFINITY),
            Just(f64::NEG_INFINITY),
            Just(1.0e30),
            Just(-1.0e30),
            Just(f64::MAX),
            Just(-f64::MAX),
            Just(f64::MIN_POSITIVE),
            Just(0.0),
            Just(-0.0),
        ],
    ]
}

/// Any value of `S` from [`any_f64`]-like input: floats convert (NaN stays NaN), fixed-point
/// takes arbitrary bit patterns as well as moderate values.
fn any_scalar<S: Scalar + FromAny>() -> impl Strategy<Value = S> {
    S::strategy()
}

/// How to generate arbitrary values of a scalar type.
trait FromAny: Sized + std::fmt::Debug {
    /// The strategy.
    fn strategy() -> BoxedStrategy<Self>;
}

impl FromAny for f64 {
    fn strategy() -> BoxedStrategy<Self> {
        any_f64().boxed()
    }
}

impl FromAny for f32 {
    fn strategy() -> BoxedStrategy<Self> {
        any_f64().prop_map(|v| v as f32).boxed()
    }
}

impl FromAny for I16F16 {
    fn strategy() -> BoxedStrategy<Self> {
        prop_oneof![
            3 => (-10.0..10.0_f64).prop_map(I16F16::from_num),
            1 => any::<i32>().prop_map(I16F16::from_bits),
            1 => prop_oneof![Just(I16F16::MAX), Just(I16F16::MIN), Just(I16F16::DELTA)],
        ]
        .boxed()
    }
}

impl FromAny for I32F32 {
    fn strategy() -> BoxedStrategy<Self> {
        prop_oneof![
            3 => (-10.0..10.0_f64).prop_map(I32F32::from_num),
            1 => any::<i64>().prop_map(I32F32::from_bits),
            1 => prop_oneof![Just(I32F32::MAX), Just(I32F32::MIN), Just(I32F32::DELTA)],
        ]
        .boxed()
    }
}

/// For floats: `p` is finite (evaluation of a validated curve stays in range).
fn finite<P: Point>(p: P, what: impl FnOnce() -> String) -> TestCaseResult {
    ensure(p.is_finite(), || format!("{}: {p:?}", what()))
}

/// Everything that can be done with a Bézier curve, at arbitrary parameters. `NM1 = N − 1`,
/// `NP1 = N + 1`.
fn exercise_bezier<P: Point, const N: usize, const NM1: usize, const NP1: usize>(
    c: &Bezier<P, N>,
    other: &[P; 3],
    ts: &[P::Scalar],
    len: P::Scalar,
) -> TestCaseResult {
    for &t in ts {
        finite(c.eval(t), || format!("eval({t:?})"))?;
        for k in 0..=N + 1 {
            finite(c.deriv(t, k), || format!("deriv({t:?}, {k})"))?;
        }
        let (l, r) = c.subdivide(t);
        let s = c.segment(t, ts[0]);
        for part in [l, r, s, c.reverse()] {
            for &u in ts {
                for k in 0..=N {
                    finite(part.deriv(u, k), || format!("part deriv({u:?}, {k})"))?;
                }
            }
        }
    }
    if let Ok(h) = c.hodograph::<NM1>() {
        for &t in ts {
            finite(h.eval(t), || "hodograph".into())?;
        }
    }
    if let Ok(e) = c.elevate::<NP1>() {
        for &t in ts {
            for k in 0..=N + 1 {
                finite(e.deriv(t, k), || "elevated".into())?;
            }
        }
    }
    if let Ok(m) = c.to_monomial() {
        for &t in ts {
            for k in 0..=N {
                finite(m.deriv(t, k), || "monomial".into())?;
            }
        }
        if let Ok(b) = Bezier::from_monomial(&m) {
            finite(b.eval(ts[0]), || "from_monomial".into())?;
        }
    }
    if let Ok(next) = Bezier::new(*other) {
        let joined = [
            c.join_c1(&next),
            c.join_g1(&next, None),
            c.join_g1(&next, Some(len)),
        ];
        for j in joined.into_iter().flatten() {
            for &t in ts {
                for k in 0..=3 {
                    finite(j.deriv(t, k), || "joined".into())?;
                }
            }
        }
    }
    Ok(())
}

/// Arbitrary points, parameters and a tangent length for degrees 0..=5.
type BezierInput<S> = (Vec<Vec<S>>, Vec<S>, S);

fn bezier_input<S: Scalar + FromAny>() -> impl Strategy<Value = BezierInput<S>> {
    (
        prop::collection::vec(prop::collection::vec(any_scalar::<S>(), 3), 9),
        prop::collection::vec(any_scalar::<S>(), 4),
        any_scalar::<S>(),
    )
}

/// Constructs `Bezier<P, N>` from the first `N` points; if it succeeds, exercises it.
fn try_bezier<P: Point, const N: usize, const NM1: usize, const NP1: usize>(
    (pts, ts, len): &BezierInput<P::Scalar>,
) -> TestCaseResult {
    let point = |c: &Vec<P::Scalar>| P::from_coords(|i| c[i]);
    let ctrl: [P; N] = std::array::from_fn(|i| point(&pts[i]));
    let other: [P; 3] = std::array::from_fn(|i| point(&pts[6 + i]));
    match Bezier::new(ctrl) {
        Ok(c) => exercise_bezier::<P, N, NM1, NP1>(&c, &other, ts, *len),
        Err(Error::NonFinite | Error::OutOfRange) => Ok(()),
        Err(e) => Err(TestCaseError::fail(format!("unexpected {e:?}"))),
    }
}

macro_rules! bezier_no_panic {
    ($name:ident, $p:ty) => {
        #[test]
        fn $name() {
            run(
                stringify!($name),
                256,
                bezier_input::<<$p as Point>::Scalar>(),
                |i| {
                    try_bezier::<$p, 1, 0, 2>(&i)?;
                    try_bezier::<$p, 2, 1, 3>(&i)?;
                    try_bezier::<$p, 3, 2, 4>(&i)?;
                    try_bezier::<$p, 4, 3, 5>(&i)?;
                    try_bezier::<$p, 6, 5, 7>(&i)
                },
            );
        }
    };
}

bezier_no_panic!(bezier_f64_never_panics, [f64; 2]);
bezier_no_panic!(bezier_dvec2_never_panics, DVec2);
bezier_no_panic!(bezier_f32_never_panics, [f32; 3]);
bezier_no_panic!(bezier_vec2_never_panics, Vec2);
bezier_no_panic!(bezier_i16f16_never_panics, [I16F16; 2]);
bezier_no_panic!(bezier_i32f32_never_panics, [I32F32; 3]);

/// Curves at the edge of the fixed-point range: random points scaled so that the largest
/// hodograph bound `g!/(g−k)! max|Δᵏ b|` is within 1% of `LIMIT` (either side). Construction may
/// accept or reject; an accepted curve must evaluate everything without overflow.
fn try_near_limit<S: Scalar, const N: usize, const NM1: usize, const NP1: usize>(
    (unit, factor, ts, len): &(Vec<Vec<f64>>, f64, Vec<f64>, f64),
) -> TestCaseResult {
    let g = N - 1;
    let mut bound = 0.0_f64;
    for d in 0..2 {
        let mut diff: Vec<f64> = unit.iter().take(N).map(|p| p[d]).collect();
        for k in 0..=g {
            if k > 0 {
                diff = diff.windows(2).map(|w| w[1] - w[0]).collect();
            }
            let ff: f64 = (0..k).map(|m| (g - m) as f64).product();
            let m = diff.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
            bound = bound.max(m * ff);
        }
    }
    if bound == 0.0 {
        return Ok(());
    }
    let scale = S::LIMIT / bound * factor;
    let to_point = |p: &Vec<f64>| -> Option<[S; 2]> {
        Some([S::from_f64(p[0] * scale)?, S::from_f64(p[1] * scale)?])
    };
    let Some(ctrl) = unit
        .iter()
        .take(N)
        .map(to_point)
        .collect::<Option<Vec<_>>>()
    else {
        return Ok(());
    };
    let Some(other) = unit[6..9].iter().map(to_point).collect::<Option<Vec<_>>>() else {
        return Ok(());
    };
    let ctrl: [[S; 2]; N] = std::array::from_fn(|i| ctrl[i]);
    let other: [[S; 2]; 3] = std::array::from_fn(|i| other[i]);
    let ts: Vec<S> = ts
        .iter()
        .map(|&t| S::from_f64(t).unwrap_or(S::ZERO))
        .collect();
    let len = S::from_f64(len * scale).unwrap_or(S::ONE);
    match Bezier::new(ctrl) {
        Ok(c) => exercise_bezier::<[S; 2], N, NM1, NP1>(&c, &other, &ts, len),
        Err(Error::OutOfRange) => Ok(()),
        Err(e) => Err(TestCaseError::fail(format!("unexpected {e:?}"))),
    }
}

#[test]
fn fixed_point_curves_at_the_range_limit_never_overflow() {
    type Input = (Vec<Vec<f64>>, f64, Vec<f64>, f64);
    let strategy = || {
        (
            strak_tests::points(9..=9, 2, 1.0),
            0.99..1.01_f64,
            prop::collection::vec(
                prop_oneof![3 => 0.0..1.0_f64, 1 => Just(0.0), 1 => Just(1.0), 1 => Just(0.5)],
                4,
            ),
            0.01..2.0_f64,
        )
    };
    run("near limit I16F16", 256, strategy(), |i: Input| {
        try_near_limit::<I16F16, 2, 1, 3>(&i)?;
        try_near_limit::<I16F16, 3, 2, 4>(&i)?;
        try_near_limit::<I16F16, 4, 3, 5>(&i)?;
        try_near_limit::<I16F16, 6, 5, 7>(&i)
    });
    run("near limit I32F32", 256, strategy(), |i: Input| {
        try_near_limit::<I32F32, 2, 1, 3>(&i)?;
        try_near_limit::<I32F32, 4, 3, 5>(&i)?;
        try_near_limit::<I32F32, 6, 5, 7>(&i)
    });
    run("near limit f32", 256, strategy(), |i: Input| {
        try_near_limit::<f32, 3, 2, 4>(&i)?;
        try_near_limit::<f32, 6, 5, 7>(&i)
    });
}

/// `MonomialCurve::with_domain` with arbitrary coefficients and domain; evaluation at
/// arbitrary parameters, all derivative orders.
fn try_monomial<S: Scalar, const N: usize>(
    (coeffs, a, b, ts): &(Vec<S>, S, S, Vec<S>),
) -> TestCaseResult {
    let c: [[S; 1]; N] = std::array::from_fn(|i| [coeffs[i]]);
    let m = match MonomialCurve::with_domain(c, *a, *b) {
        Ok(m) => m,
        Err(
            Error::NonFinite
            | Error::OutOfRange
            | Error::ZeroLengthInterval { .. }
            | Error::InvalidArgument,
        ) => return Ok(()),
        Err(e) => return Err(TestCaseError::fail(format!("unexpected {e:?}"))),
    };
    for &t in ts {
        for k in 0..=N + 1 {
            finite(m.deriv(t, k), || format!("deriv({t:?}, {k})"))?;
        }
    }
    if let Ok(b) = Bezier::from_monomial(&m) {
        for &t in ts {
            finite(b.eval(t), || "from_monomial".into())?;
        }
    }
    Ok(())
}

#[test]
fn monomial_curve_never_panics() {
    fn all<S: Scalar + FromAny>(name: &str) {
        let strategy = (
            prop::collection::vec(any_scalar::<S>(), 6),
            any_scalar::<S>(),
            any_scalar::<S>(),
            prop::collection::vec(any_scalar::<S>(), 4),
        );
        run(name, 256, strategy, |i| {
            try_monomial::<S, 1>(&i)?;
            try_monomial::<S, 3>(&i)?;
            try_monomial::<S, 6>(&i)
        });
    }
    all::<f64>("monomial f64");
    all::<f32>("monomial f32");
    all::<I16F16>("monomial I16F16");
    all::<I32F32>("monomial I32F32");
}

/// `LagrangeBasis::new` with arbitrary (often unsorted) nodes; values at arbitrary parameters.
fn try_lagrange<S: Scalar, const N: usize>((nodes, ts): &(Vec<S>, Vec<S>)) -> TestCaseResult {
    // sorted input reaches the range check and the evaluation more often
    let mut sorted = nodes.clone();
    sorted.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
    for input in [nodes, &sorted] {
        let n: [S; N] = std::array::from_fn(|i| input[i]);
        let l = match LagrangeBasis::new(n) {
            Ok(l) => l,
            Err(Error::NonFinite | Error::OutOfRange | Error::NodesNotIncreasing { .. }) => {
                continue;
            }
            Err(e) => return Err(TestCaseError::fail(format!("unexpected {e:?}"))),
        };
        for &t in ts {
            let v = l.values(t);
            ensure(v.iter().all(|x| x.is_finite()), || format!("{v:?}"))?;
            let _ = l.value(N, t);
        }
    }
    Ok(())
}

#[test]
fn lagrange_basis_never_panics() {
    fn all<S: Scalar + FromAny>(name: &str) {
        let strategy = (
            prop::collection::vec(any_scalar::<S>(), 6),
            prop::collection::vec(any_scalar::<S>(), 4),
        );
        run(name, 256, strategy, |i| {
            try_lagrange::<S, 1>(&i)?;
            try_lagrange::<S, 2>(&i)?;
            try_lagrange::<S, 4>(&i)?;
            try_lagrange::<S, 6>(&i)
        });
    }
    all::<f64>("lagrange f64");
    all::<f32>("lagrange f32");
    all::<I16F16>("lagrange I16F16");
    all::<I32F32>("lagrange I32F32");
}

/// Basis functions at arbitrary parameters: values in their documented ranges, no panic.
fn try_basis_functions<S: Scalar>(t: S) -> TestCaseResult {
    let b = basis::bernstein_all::<S, 7>(t);
    ensure(b.iter().all(|v| *v >= S::ZERO && *v <= S::ONE), || {
        format!("Bernstein values {b:?} at {t:?}")
    })?;
    let d = basis::bernstein_deriv_all::<S, 7>(t);
    let six = S::from_i16(6);
    ensure(d.iter().all(|v| v.abs() <= six), || {
        format!("Bernstein derivatives {d:?} at {t:?}")
    })?;
    let _ = basis::bernstein::<S, 7>(9, t);
    let m = basis::monomials::<S, 7>(t);
    ensure(m.iter().all(|v| *v >= S::ZERO && *v <= S::ONE), || {
        format!("monomials {m:?} at {t:?}")
    })?;
    for k in 0..6 {
        let h = basis::hermite_deriv(t, k);
        ensure(h.iter().all(|v| v.is_finite()), || format!("Hermite {h:?}"))?;
    }
    Ok(())
}

#[test]
fn basis_functions_never_panic() {
    run(
        "basis f64",
        256,
        any_scalar::<f64>(),
        try_basis_functions::<f64>,
    );
    run(
        "basis f32",
        256,
        any_scalar::<f32>(),
        try_basis_functions::<f32>,
    );
    run(
        "basis I16F16",
        256,
        any_scalar::<I16F16>(),
        try_basis_functions::<I16F16>,
    );
    run(
        "basis I32F32",
        256,
        any_scalar::<I32F32>(),
        try_basis_functions::<I32F32>,
    );
}

/// Basis conversions of arbitrary points: an error or a finite result.
#[test]
fn basis_conversions_never_panic() {
    run(
        "conversions f64",
        256,
        prop::collection::vec(any_f64(), 5),
        |v| {
            let p: [[f64; 1]; 5] = std::array::from_fn(|i| [v[i]]);
            for r in [
                basis::bernstein_to_monomial(&p),
                basis::monomial_to_bernstein(&p),
            ] {
                match r {
                    Ok(a) => ensure(a.iter().all(|q| q[0].is_finite()), || format!("{a:?}"))?,
                    Err(Error::NonFinite | Error::OutOfRange) => {}
                    Err(e) => return Err(TestCaseError::fail(format!("unexpected {e:?}"))),
                }
            }
            Ok(())
        },
    );
    run(
        "conversions I16F16",
        256,
        prop::collection::vec(any_scalar::<I16F16>(), 5),
        |v| {
            let p: [[I16F16; 1]; 5] = std::array::from_fn(|i| [v[i]]);
            for r in [
                basis::bernstein_to_monomial(&p),
                basis::monomial_to_bernstein(&p),
            ] {
                match r {
                    Ok(_) | Err(Error::OutOfRange) => {}
                    Err(e) => return Err(TestCaseError::fail(format!("unexpected {e:?}"))),
                }
            }
            Ok(())
        },
    );
}

/// Quarter circles of arbitrary κ and their radial error.
#[test]
fn quarter_circle_never_panics() {
    run(
        "quarter circle f64",
        256,
        (any_f64(), prop::collection::vec(any_f64(), 3)),
        |(kappa, ts)| {
            let _ = quarter_circle_radial_error(kappa);
            if let Ok(c) = Bezier::<DVec2, 4>::quarter_circle(kappa) {
                for t in ts {
                    finite(c.deriv(t, 1), || "quarter circle".into())?;
                }
            }
            Ok(())
        },
    );
    run(
        "quarter circle I16F16",
        256,
        (
            any_scalar::<I16F16>(),
            prop::collection::vec(any_scalar::<I16F16>(), 3),
        ),
        |(kappa, ts)| {
            if let Ok(c) = Bezier::<[I16F16; 2], 4>::quarter_circle(kappa) {
                for t in ts {
                    let _ = c.eval(t);
                    let _ = c.deriv(t, 3);
                }
            }
            Ok(())
        },
    );
}
