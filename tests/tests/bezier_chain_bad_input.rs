//! Bad input for [`BezierChain`]: one test per typed error of both constructors (asserting the
//! exact [`Error`]), and a property that arbitrary input (NaN, ±∞, huge values, arbitrary
//! fixed-point bits) never panics — neither in the constructors nor, after a successful
//! construction, in evaluation at arbitrary parameters (NaN and ±∞ included). Tests run with
//! overflow checks in debug builds, so a fixed-point overflow would be a panic.

use proptest::prelude::*;
use strak_curves::{
    Bezier, BezierChain, Error, I16F16, I32F32, ParamCurve, ParamCurveDeriv, PieceDeriv,
};
use strak_tests::run;

fn x16(v: f64) -> [I16F16; 1] {
    [I16F16::from_num(v)]
}

#[test]
fn degree_zero_is_invalid_argument() {
    assert_eq!(
        BezierChain::<_, 1, 4>::new(&[[0.0_f64], [0.0]]),
        Err(Error::InvalidArgument)
    );
    let p = Bezier::new([[1.0_f64]]).expect("point");
    assert_eq!(
        BezierChain::<_, 1, 4>::from_segments(&[p, p]),
        Err(Error::InvalidArgument)
    );
}

#[test]
fn segments_that_do_not_meet_are_invalid_argument() {
    let a = Bezier::new([[0.0_f64, 0.0], [1.0, 0.0], [2.0, 0.0]]).expect("a");
    let b = Bezier::new([[2.0, 1e-12], [3.0, 0.0], [4.0, 0.0]]).expect("b");
    assert_eq!(
        BezierChain::<_, 3, 4>::from_segments(&[a, b]),
        Err(Error::InvalidArgument)
    );
    // a G¹ join from Bezier::join_g1 meets exactly
    let b = a.join_g1(&b, None).expect("join");
    assert!(BezierChain::<_, 3, 4>::from_segments(&[a, b]).is_ok());
}

#[test]
fn too_few_points() {
    assert_eq!(
        BezierChain::<[f32; 2], 4, 4>::new(&[]),
        Err(Error::TooFewPoints {
            required: 4,
            found: 0
        })
    );
    assert_eq!(
        BezierChain::<_, 3, 4>::new(&[[0.0_f32, 0.0], [1.0, 1.0]]),
        Err(Error::TooFewPoints {
            required: 3,
            found: 2
        })
    );
    assert_eq!(
        BezierChain::<[f64; 3], 3, 4>::from_segments(&[]),
        Err(Error::TooFewPoints {
            required: 1,
            found: 0
        })
    );
}

#[test]
fn count_not_of_the_composite_form_is_length_mismatch() {
    // quartic: valid counts 5, 9, 13
    let p = [[0.0_f64]; 13];
    for (found, expected) in [(6, 5), (7, 5), (8, 9), (10, 9), (11, 9), (12, 13)] {
        assert_eq!(
            BezierChain::<_, 5, 4>::new(&p[..found]),
            Err(Error::LengthMismatch { expected, found }),
            "{found} points"
        );
    }
}

#[test]
fn more_segments_than_capacity() {
    let p = [[0.0_f64, 1.0]; 10];
    assert_eq!(
        BezierChain::<_, 4, 2>::new(&p),
        Err(Error::CapacityExceeded {
            capacity: 2,
            required: 3
        })
    );
    assert_eq!(
        BezierChain::<_, 2, 0>::new(&p[..2]),
        Err(Error::CapacityExceeded {
            capacity: 0,
            required: 1
        })
    );
    let s = Bezier::new([[0.0_f64, 1.0]; 4]).expect("segment");
    assert_eq!(
        BezierChain::<_, 4, 2>::from_segments(&[s; 3]),
        Err(Error::CapacityExceeded {
            capacity: 2,
            required: 3
        })
    );
}

#[test]
fn non_finite_points() {
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        assert_eq!(
            BezierChain::<_, 3, 4>::new(&[
                [0.0, 0.0],
                [1.0, 1.0],
                [2.0, 0.0],
                [3.0, bad],
                [4.0, 0.0]
            ]),
            Err(Error::NonFinite)
        );
    }
    assert_eq!(
        BezierChain::<_, 2, 4>::new(&[[f32::NAN], [1.0]]),
        Err(Error::NonFinite)
    );
}

#[test]
fn out_of_range_segment_or_parameter() {
    // segment 2's hodograph 2 · (9000 − 0) leaves I16F16's limit 16 383
    assert_eq!(
        BezierChain::<_, 3, 4>::new(&[x16(0.0), x16(1.0), x16(2.0), x16(9000.0), x16(0.0)]),
        Err(Error::OutOfRange)
    );
    // f32: a difference beyond f32::MAX / 2
    assert_eq!(
        BezierChain::<_, 2, 4>::new(&[[-2.0e38_f32], [2.0e38]]),
        Err(Error::OutOfRange)
    );
    // the parameter n = 16 384 does not fit I16F16 (it fits I32F32)
    let pts = vec![x16(0.0); 16_385];
    assert_eq!(
        BezierChain::<_, 2, 16_384>::new(&pts),
        Err(Error::OutOfRange)
    );
    let seg = Bezier::new([x16(0.0), x16(0.0)]).expect("segment");
    let segs = vec![seg; 16_384];
    assert_eq!(
        BezierChain::<_, 2, 16_384>::from_segments(&segs),
        Err(Error::OutOfRange)
    );
    let pts = vec![[I32F32::ZERO]; 16_385];
    assert!(BezierChain::<_, 2, 16_384>::new(&pts).is_ok());
}

/// Any value, including NaN, ±∞ and huge magnitudes.
fn wild() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => -100.0..100.0_f64,
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
        1 => Just(f64::NEG_INFINITY),
        1 => -1e30..1e30_f64,
        1 => -20_000.0..20_000.0_f64,
    ]
}

#[test]
fn arbitrary_input_never_panics() {
    let strategy = (
        prop::collection::vec(prop::collection::vec(wild(), 2), 0..14),
        prop::collection::vec(wild(), 6),
        prop::collection::vec(any::<i32>(), 6),
    );
    run(
        "chain arbitrary input",
        256,
        strategy,
        |(points, params, bits), _| {
            let f: Vec<[f64; 2]> = points.iter().map(|p| [p[0], p[1]]).collect();
            let s: Vec<[f32; 2]> = points.iter().map(|p| [p[0] as f32, p[1] as f32]).collect();
            let q: Vec<[I16F16; 2]> = points
                .iter()
                .zip(bits.iter().cycle())
                .map(|(p, &b)| {
                    let x = I16F16::checked_from_num(p[0]).unwrap_or(I16F16::from_bits(b));
                    [x, I16F16::from_bits(b.rotate_left(7))]
                })
                .collect();
            if let Ok(c) = BezierChain::<_, 4, 4>::new(&f) {
                for &u in &params {
                    for k in 0..5 {
                        let _ = c.deriv(u, k);
                        let _ = c.piece_deriv(k, u, k);
                    }
                }
            }
            if let Ok(c) = BezierChain::<_, 3, 4>::new(&s) {
                for &u in &params {
                    for k in 0..4 {
                        let _ = c.deriv(u as f32, k);
                        let _ = c.piece_deriv(k, u as f32, k);
                    }
                }
            }
            if let Ok(c) = BezierChain::<_, 2, 16>::new(&q) {
                for (&u, &b) in params.iter().zip(&bits) {
                    let u = I16F16::checked_from_num(u).unwrap_or(I16F16::from_bits(b));
                    for k in 0..3 {
                        let _ = c.eval(u);
                        let _ = c.deriv(u, k);
                        let _ = c.piece_deriv(k, u, k);
                    }
                }
            }
            Ok(())
        },
    );
}
