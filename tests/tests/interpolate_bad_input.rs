//! Bad input for every constructor of strak-curves' interpolate module: one test per typed
//! error (the exact `Error` value), and a property test that arbitrary input, finite or not,
//! never panics: constructors return `Ok` or `Err`, and on `Ok` evaluation at any parameter
//! (±huge, ±∞, NaN) and any derivative order returns finite values.

use proptest::prelude::*;
use strak_curves::glam::Vec3;
use strak_curves::{
    CubicSpline, Error, HermiteSegment, HermiteSpline, I16F16, I32F32, LagrangeCurve, NodeSource,
    ParabolicBlend, ParamCurve, ParamCurveDeriv, Parameterization, Point, Scalar, SplineBoundary,
    solve_cyclic_tridiagonal, solve_tridiagonal, validate_interpolation_nodes,
};

const UNIFORM: Parameterization = Parameterization::Uniform;
const CHORD: Parameterization = Parameterization::ChordLength;
const CENTRIPETAL: Parameterization = Parameterization::Centripetal;
const NAN: f64 = f64::NAN;
const INF: f64 = f64::INFINITY;

/// Three well-behaved 2-D points.
const P3: [[f64; 2]; 3] = [[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]];
/// Their tangents.
const M3: [[f64; 2]; 3] = [[1.0, 1.0], [1.0, 0.0], [1.0, -1.0]];
/// Nodes for them.
const U3: [f64; 3] = [0.0, 1.0, 3.0];

/// An `I16F16` from `f64` (exact for the values used here).
fn fx(x: f64) -> I16F16 {
    I16F16::from_num(x)
}

fn fx1(x: f64) -> [I16F16; 1] {
    [fx(x)]
}

/// Two points at distance 100 whose nodes are `2^-12` apart: slopes of 409 600 do not fit
/// `I16F16` (limit 16 383).
fn steep_i16() -> ([[I16F16; 1]; 3], [I16F16; 3]) {
    (
        [fx1(0.0), fx1(100.0), fx1(0.0)],
        [fx(0.0), fx(1.0 / 4096.0), fx(16.0)],
    )
}

/// `f32` points of magnitude 10³⁸ with a short interval: slopes far beyond `f32::MAX / 2`.
fn steep_f32() -> ([[f32; 1]; 3], [f32; 3]) {
    ([[0.0], [1.0e38], [0.0]], [0.0, 1.0e-3, 1.0])
}

mod lagrange {
    use super::*;

    type L<P> = LagrangeCurve<P, 4>;

    #[test]
    fn too_few_points() {
        assert_eq!(
            L::new(&P3[..1], UNIFORM),
            Err(Error::TooFewPoints {
                required: 2,
                found: 1
            })
        );
        assert_eq!(
            L::<[f64; 2]>::new(&[], UNIFORM),
            Err(Error::TooFewPoints {
                required: 2,
                found: 0
            })
        );
    }

    #[test]
    fn capacity_exceeded() {
        let pts = [[0.0_f32], [1.0], [2.0], [3.0], [4.0]];
        assert_eq!(
            L::new(&pts, UNIFORM),
            Err(Error::CapacityExceeded {
                capacity: 4,
                required: 5
            })
        );
    }

    #[test]
    fn length_mismatch() {
        assert_eq!(
            L::new(&P3, &U3[..2]),
            Err(Error::LengthMismatch {
                expected: 3,
                found: 2
            })
        );
        assert_eq!(
            L::new(&P3[..2], &U3),
            Err(Error::LengthMismatch {
                expected: 2,
                found: 3
            })
        );
    }

    #[test]
    fn non_finite() {
        assert_eq!(
            L::new(&[[0.0, 0.0], [NAN, 1.0]], UNIFORM),
            Err(Error::NonFinite)
        );
        assert_eq!(
            L::new(&[[0.0_f32, f32::NEG_INFINITY], [1.0, 1.0]], CHORD),
            Err(Error::NonFinite)
        );
        assert_eq!(L::new(&P3, &[0.0, NAN, 3.0]), Err(Error::NonFinite));
        assert_eq!(L::new(&P3, &[0.0, 1.0, INF]), Err(Error::NonFinite));
    }

    #[test]
    fn nodes_not_increasing() {
        assert_eq!(
            L::new(&P3, &[0.0, 3.0, 1.0]),
            Err(Error::NodesNotIncreasing { index: 2 })
        );
        assert_eq!(
            L::new(&P3, &[1.0, 1.0, 3.0]),
            Err(Error::NodesNotIncreasing { index: 1 })
        );
    }

    #[test]
    fn zero_length_interval() {
        let pts = [[1.0, 2.0], [1.0, 2.0], [3.0, 0.0]];
        for p in [CHORD, CENTRIPETAL] {
            assert_eq!(L::new(&pts, p), Err(Error::ZeroLengthInterval { index: 0 }));
        }
        assert!(L::new(&pts, UNIFORM).is_ok());
    }

    #[test]
    fn out_of_range() {
        let (pts, u) = steep_i16();
        assert_eq!(L::new(&pts, &u), Err(Error::OutOfRange));
        let (pts, u) = steep_f32();
        assert_eq!(L::new(&pts, &u), Err(Error::OutOfRange));
        // a node beyond I16F16's limit (representable, but no headroom)
        let pts = [fx1(0.0), fx1(1.0)];
        assert_eq!(
            L::new(&pts, &[fx(0.0), fx(20000.0)]),
            Err(Error::OutOfRange)
        );
        // chord-length nodes summing beyond the limit
        let pts = [fx1(-10000.0), fx1(10000.0)];
        assert_eq!(L::new(&pts, CHORD), Err(Error::OutOfRange));
        // the same data in I32F32 is fine
        let pts = [[I32F32::from_num(-10000)], [I32F32::from_num(10000)]];
        assert!(L::new(&pts, CHORD).is_ok());
    }
}

mod hermite_segment {
    use super::*;

    #[test]
    fn non_finite() {
        let (q, m) = ([0.0_f64, 0.0], [1.0, 1.0]);
        assert_eq!(
            HermiteSegment::new(NAN, 1.0, q, q, m, m),
            Err(Error::NonFinite)
        );
        assert_eq!(
            HermiteSegment::new(0.0, INF, q, q, m, m),
            Err(Error::NonFinite)
        );
        assert_eq!(
            HermiteSegment::new(0.0, 1.0, q, [INF, 0.0], m, m),
            Err(Error::NonFinite)
        );
        assert_eq!(
            HermiteSegment::new(0.0, 1.0, q, q, m, [0.0, NAN]),
            Err(Error::NonFinite)
        );
        let v = Vec3::new(f32::NAN, 0.0, 0.0);
        assert_eq!(
            HermiteSegment::new(0.0, 1.0, Vec3::ZERO, Vec3::X, v, Vec3::Y),
            Err(Error::NonFinite)
        );
    }

    #[test]
    fn nodes_not_increasing() {
        let (q, m) = ([0.0_f32], [1.0]);
        assert_eq!(
            HermiteSegment::new(1.0, 1.0, q, q, m, m),
            Err(Error::NodesNotIncreasing { index: 1 })
        );
        assert_eq!(
            HermiteSegment::new(2.0, 1.0, q, q, m, m),
            Err(Error::NodesNotIncreasing { index: 1 })
        );
    }

    #[test]
    fn out_of_range() {
        // I16F16: Δ = 2^-16 and a rise of 1: the hodograph is 3·2^16.
        let (z, one) = (fx1(0.0), fx1(1.0));
        assert_eq!(
            HermiteSegment::new(fx(0.0), I16F16::DELTA, z, one, z, z),
            Err(Error::OutOfRange)
        );
        // a node beyond the limit
        assert_eq!(
            HermiteSegment::new(fx(0.0), fx(20000.0), z, z, z, z),
            Err(Error::OutOfRange)
        );
        // f32: Δ·m = 10³⁹ overflows the Bézier points
        assert_eq!(
            HermiteSegment::new(0.0_f32, 10.0, [0.0], [0.0], [1.0e38], [0.0]),
            Err(Error::OutOfRange)
        );
        // modest data is fine in I16F16
        assert!(HermiteSegment::new(fx(0.0), fx(1.0), z, one, one, z).is_ok());
    }
}

mod hermite_spline {
    use super::*;

    type H<P> = HermiteSpline<P, 4>;

    #[test]
    fn too_few_points() {
        assert_eq!(
            H::new(&P3[..1], &M3[..1], UNIFORM),
            Err(Error::TooFewPoints {
                required: 2,
                found: 1
            })
        );
    }

    #[test]
    fn capacity_exceeded() {
        let pts = [[0.0_f64]; 5];
        assert_eq!(
            H::new(&pts, &pts, UNIFORM),
            Err(Error::CapacityExceeded {
                capacity: 4,
                required: 5
            })
        );
    }

    #[test]
    fn length_mismatch() {
        assert_eq!(
            H::new(&P3, &M3[..2], UNIFORM),
            Err(Error::LengthMismatch {
                expected: 3,
                found: 2
            })
        );
        assert_eq!(
            H::new(&P3, &M3, &[0.0, 1.0, 2.0, 3.0]),
            Err(Error::LengthMismatch {
                expected: 3,
                found: 4
            })
        );
    }

    #[test]
    fn non_finite() {
        let bad = [[0.0, 0.0], [1.0, NAN], [2.0, 0.0]];
        assert_eq!(H::new(&bad, &M3, UNIFORM), Err(Error::NonFinite));
        assert_eq!(H::new(&P3, &bad, UNIFORM), Err(Error::NonFinite));
        assert_eq!(H::new(&P3, &M3, &[0.0, 1.0, -INF]), Err(Error::NonFinite));
    }

    #[test]
    fn nodes_not_increasing() {
        assert_eq!(
            H::new(&P3, &M3, &[0.0, 1.0, 1.0]),
            Err(Error::NodesNotIncreasing { index: 2 })
        );
    }

    #[test]
    fn zero_length_interval() {
        let pts = [[0.0, 0.0], [1.0, 1.0], [1.0, 1.0]];
        assert_eq!(
            H::new(&pts, &M3, CHORD),
            Err(Error::ZeroLengthInterval { index: 1 })
        );
    }

    #[test]
    fn out_of_range() {
        let (pts, u) = steep_i16();
        let m = [fx1(0.0); 3];
        assert_eq!(H::new(&pts, &m, &u), Err(Error::OutOfRange));
        let (pts, u) = steep_f32();
        assert_eq!(H::new(&pts, &[[0.0]; 3], &u), Err(Error::OutOfRange));
        // tangents too long for the interval in I16F16: Δ·m = 2·10000
        let pts = [fx1(0.0), fx1(1.0)];
        let m = [fx1(10000.0), fx1(0.0)];
        assert_eq!(
            H::new(&pts, &m, &[fx(0.0), fx(2.0)]),
            Err(Error::OutOfRange)
        );
    }
}

mod catmull_rom_and_cardinal {
    use super::*;

    type H<P> = HermiteSpline<P, 4>;

    #[test]
    fn too_few_points() {
        let e = Err(Error::TooFewPoints {
            required: 2,
            found: 1,
        });
        assert_eq!(H::catmull_rom(&P3[..1], UNIFORM), e);
        assert_eq!(H::cardinal(&P3[..1], UNIFORM, 0.5), e);
    }

    #[test]
    fn capacity_exceeded() {
        let pts = [
            [0.0_f32, 0.0],
            [1.0, 0.0],
            [2.0, 0.0],
            [3.0, 0.0],
            [4.0, 0.0],
        ];
        let e = Err(Error::CapacityExceeded {
            capacity: 4,
            required: 5,
        });
        assert_eq!(H::catmull_rom(&pts, CHORD), e);
        assert_eq!(H::cardinal(&pts, CHORD, 0.5), e);
    }

    #[test]
    fn length_mismatch() {
        let e = Err(Error::LengthMismatch {
            expected: 3,
            found: 2,
        });
        assert_eq!(H::catmull_rom(&P3, &U3[..2]), e);
        assert_eq!(H::cardinal(&P3, &U3[..2], 0.0), e);
    }

    #[test]
    fn non_finite() {
        let bad = [[0.0, 0.0], [INF, 1.0], [2.0, 0.0]];
        assert_eq!(H::catmull_rom(&bad, UNIFORM), Err(Error::NonFinite));
        assert_eq!(H::cardinal(&bad, UNIFORM, 0.0), Err(Error::NonFinite));
        assert_eq!(H::catmull_rom(&P3, &[NAN, 1.0, 2.0]), Err(Error::NonFinite));
        assert_eq!(H::cardinal(&P3, UNIFORM, NAN), Err(Error::NonFinite));
        assert_eq!(H::cardinal(&P3, UNIFORM, INF), Err(Error::NonFinite));
    }

    #[test]
    fn nodes_not_increasing() {
        let e = Err(Error::NodesNotIncreasing { index: 1 });
        assert_eq!(H::catmull_rom(&P3, &[0.0, -1.0, 2.0]), e);
        assert_eq!(H::cardinal(&P3, &[0.0, -1.0, 2.0], 0.5), e);
    }

    #[test]
    fn zero_length_interval() {
        let pts = [[0.0, 0.0], [0.0, 0.0], [1.0, 1.0]];
        let e = Err(Error::ZeroLengthInterval { index: 0 });
        assert_eq!(H::catmull_rom(&pts, CENTRIPETAL), e);
        assert_eq!(H::cardinal(&pts, CHORD, 0.5), e);
    }

    #[test]
    fn out_of_range() {
        // I16F16: the one-sided tangent at node 0 is 100·4096 = 409 600
        let (pts, u) = steep_i16();
        assert_eq!(H::catmull_rom(&pts, &u), Err(Error::OutOfRange));
        assert_eq!(H::cardinal(&pts, &u, fx(0.5)), Err(Error::OutOfRange));
        let (pts, u) = steep_f32();
        assert_eq!(H::catmull_rom(&pts, &u), Err(Error::OutOfRange));
        // a huge tension scales fine data out of range
        let pts = [fx1(0.0), fx1(1.0), fx1(2.0)];
        assert_eq!(
            H::cardinal(&pts, UNIFORM, fx(-15000.0)),
            Err(Error::OutOfRange)
        );
    }
}

mod parabolic_blend {
    use super::*;

    type B<P> = ParabolicBlend<P, 4>;

    #[test]
    fn too_few_points() {
        assert_eq!(
            B::new(&P3[..2]),
            Err(Error::TooFewPoints {
                required: 3,
                found: 2
            })
        );
    }

    #[test]
    fn capacity_exceeded() {
        let pts = [[0.0_f64], [1.0], [2.0], [3.0], [4.0]];
        assert_eq!(
            B::new(&pts),
            Err(Error::CapacityExceeded {
                capacity: 4,
                required: 5
            })
        );
    }

    #[test]
    fn non_finite() {
        assert_eq!(
            B::new(&[[0.0_f32], [f32::NAN], [1.0]]),
            Err(Error::NonFinite)
        );
        assert_eq!(
            B::new(&[Vec3::ZERO, Vec3::X, Vec3::splat(f32::INFINITY)]),
            Err(Error::NonFinite)
        );
    }

    #[test]
    fn out_of_range() {
        // I16F16: the end tangent (−3P0 + 4P1 − P2)/2 = 40 000 exceeds the limit 16 383
        let pts = [fx1(-10000.0), fx1(10000.0), fx1(-10000.0)];
        assert_eq!(B::new(&pts), Err(Error::OutOfRange));
        assert!(B::new(&[fx1(-100.0), fx1(100.0), fx1(-100.0)]).is_ok());
        let pts = [[-1.0e38_f32], [1.0e38], [-1.0e38]];
        assert_eq!(B::new(&pts), Err(Error::OutOfRange));
    }
}

mod cubic_spline {
    use super::*;

    type C<P> = CubicSpline<P, 4>;
    const NAT: SplineBoundary<[f64; 2]> = SplineBoundary::Natural;

    #[test]
    fn too_few_points() {
        assert_eq!(
            C::new(&P3[..1], UNIFORM, NAT),
            Err(Error::TooFewPoints {
                required: 2,
                found: 1
            })
        );
        let clamped = SplineBoundary::Clamped {
            start: [0.0, 0.0],
            end: [0.0, 0.0],
        };
        assert_eq!(
            C::new(&P3[..1], UNIFORM, clamped),
            Err(Error::TooFewPoints {
                required: 2,
                found: 1
            })
        );
        // periodic: at least two distinct points and the repeated first
        assert_eq!(
            C::new(&[[0.0, 0.0], [0.0, 0.0]], UNIFORM, SplineBoundary::Periodic),
            Err(Error::TooFewPoints {
                required: 3,
                found: 2
            })
        );
    }

    #[test]
    fn capacity_exceeded() {
        let pts = [
            [0.0_f64, 0.0],
            [1.0, 0.0],
            [2.0, 0.0],
            [3.0, 0.0],
            [0.0, 0.0],
        ];
        for b in [NAT, SplineBoundary::Periodic] {
            assert_eq!(
                C::new(&pts, CHORD, b),
                Err(Error::CapacityExceeded {
                    capacity: 4,
                    required: 5
                })
            );
        }
    }

    #[test]
    fn length_mismatch() {
        assert_eq!(
            C::new(&P3, &[0.0, 1.0], NAT),
            Err(Error::LengthMismatch {
                expected: 3,
                found: 2
            })
        );
    }

    #[test]
    fn non_finite() {
        assert_eq!(
            C::new(&[[0.0, 0.0], [NAN, 0.0]], CHORD, NAT),
            Err(Error::NonFinite)
        );
        assert_eq!(C::new(&P3, &[0.0, INF, 2.0], NAT), Err(Error::NonFinite));
        for (start, end) in [([NAN, 0.0], [0.0, 0.0]), ([0.0, 0.0], [0.0, -INF])] {
            assert_eq!(
                C::new(&P3, UNIFORM, SplineBoundary::Clamped { start, end }),
                Err(Error::NonFinite)
            );
        }
        let closed = [[0.0_f32, 0.0], [f32::NAN, 1.0], [0.0, 0.0]];
        assert_eq!(
            C::new(&closed, UNIFORM, SplineBoundary::Periodic),
            Err(Error::NonFinite)
        );
    }

    #[test]
    fn nodes_not_increasing() {
        assert_eq!(
            C::new(&P3, &[0.0, 2.0, 2.0], NAT),
            Err(Error::NodesNotIncreasing { index: 2 })
        );
        let closed = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 0.0]];
        assert_eq!(
            C::new(&closed, &[0.0, 1.0, 0.5, 2.0], SplineBoundary::Periodic),
            Err(Error::NodesNotIncreasing { index: 2 })
        );
    }

    #[test]
    fn zero_length_interval() {
        let pts = [[0.0, 0.0], [1.0, 1.0], [1.0, 1.0]];
        assert_eq!(
            C::new(&pts, CHORD, NAT),
            Err(Error::ZeroLengthInterval { index: 1 })
        );
        // a closed curve that doubles back onto its start point before the end
        let closed = [[0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [0.0, 0.0]];
        assert_eq!(
            C::new(&closed, CENTRIPETAL, SplineBoundary::Periodic),
            Err(Error::ZeroLengthInterval { index: 1 })
        );
    }

    #[test]
    fn invalid_argument_periodic_not_closed() {
        let open = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0e-300]];
        assert_eq!(
            C::new(&open, CHORD, SplineBoundary::Periodic),
            Err(Error::InvalidArgument)
        );
        let open = [fx1(0.0), fx1(1.0), [I16F16::DELTA]];
        assert_eq!(
            C::new(&open, UNIFORM, SplineBoundary::Periodic),
            Err(Error::InvalidArgument)
        );
        // the same point closed exactly is fine
        assert!(
            C::new(
                &[fx1(0.0), fx1(1.0), fx1(0.0)],
                UNIFORM,
                SplineBoundary::Periodic
            )
            .is_ok()
        );
    }

    #[test]
    fn out_of_range() {
        let (pts, u) = steep_i16();
        assert_eq!(
            C::new(&pts, &u, SplineBoundary::Natural),
            Err(Error::OutOfRange)
        );
        let (pts, u) = steep_f32();
        assert_eq!(
            C::new(&pts, &u, SplineBoundary::Natural),
            Err(Error::OutOfRange)
        );
        // clamped end tangent too long for the interval: Δ·m = 2·10 000
        let pts = [fx1(0.0), fx1(1.0)];
        let b = SplineBoundary::Clamped {
            start: fx1(10000.0),
            end: fx1(0.0),
        };
        assert_eq!(C::new(&pts, &[fx(0.0), fx(2.0)], b), Err(Error::OutOfRange));
        // periodic in I16F16 with a short closing interval
        let closed = [fx1(0.0), fx1(100.0), fx1(0.0)];
        assert_eq!(
            C::new(
                &closed,
                &[fx(0.0), fx(1.0), fx(1.0 + 1.0 / 4096.0)],
                SplineBoundary::Periodic
            ),
            Err(Error::OutOfRange)
        );
    }
}

mod parameterization {
    use super::*;

    #[test]
    fn capacity_exceeded() {
        let pts = [[0.0_f64], [1.0], [2.0]];
        for p in [UNIFORM, CHORD, CENTRIPETAL] {
            assert_eq!(
                p.nodes::<_, 2>(&pts),
                Err(Error::CapacityExceeded {
                    capacity: 2,
                    required: 3
                })
            );
        }
    }

    #[test]
    fn non_finite() {
        let pts = [[0.0_f32, 0.0], [1.0, f32::NAN]];
        for p in [UNIFORM, CHORD, CENTRIPETAL] {
            assert_eq!(p.nodes::<_, 4>(&pts), Err(Error::NonFinite));
        }
    }

    #[test]
    fn zero_length_interval() {
        let pts = [[0.0_f64, 0.0], [1.0, 0.0], [2.0, 0.0], [2.0, 0.0]];
        for p in [CHORD, CENTRIPETAL] {
            assert_eq!(
                p.nodes::<_, 4>(&pts),
                Err(Error::ZeroLengthInterval { index: 2 })
            );
        }
        // an interval that rounds away in f32: the node 1e8 + 1 rounds to 1e8 (spacing 8
        // there), while 1e8 + 8 is the next f32
        let pts = [[0.0_f32], [1.0e8], [1.0e8 + 8.0]];
        assert!(CHORD.nodes::<_, 4>(&pts).is_ok());
        let pts = [[0.0_f32, 0.0], [1.0e8, 0.0], [1.0e8, 1.0]];
        assert_eq!(
            CHORD.nodes::<_, 4>(&pts),
            Err(Error::ZeroLengthInterval { index: 1 })
        );
    }

    #[test]
    fn out_of_range() {
        let pts = [fx1(-10000.0), fx1(10000.0)];
        assert_eq!(CHORD.nodes::<_, 4>(&pts), Err(Error::OutOfRange));
        // uniform nodes beyond I16F16's limit would need 16 385 points; centripetal:
        // √20 000 ≈ 141 fits
        assert!(CENTRIPETAL.nodes::<_, 4>(&pts).is_ok());
    }
}

mod node_source {
    use super::*;

    #[test]
    fn length_mismatch() {
        let src = NodeSource::Given(&[0.0_f64, 1.0][..]);
        assert_eq!(
            src.resolve::<_, 4>(&P3),
            Err(Error::LengthMismatch {
                expected: 3,
                found: 2
            })
        );
    }

    #[test]
    fn capacity_exceeded() {
        assert_eq!(
            NodeSource::Given(&U3[..]).resolve::<_, 2>(&P3),
            Err(Error::CapacityExceeded {
                capacity: 2,
                required: 3
            })
        );
        assert_eq!(
            NodeSource::<f64>::Computed(CHORD).resolve::<_, 2>(&P3),
            Err(Error::CapacityExceeded {
                capacity: 2,
                required: 3
            })
        );
    }

    #[test]
    fn non_finite_not_increasing_out_of_range() {
        assert_eq!(
            NodeSource::Given(&[0.0, NAN, 1.0][..]).resolve::<_, 4>(&P3),
            Err(Error::NonFinite)
        );
        assert_eq!(
            NodeSource::Given(&[0.0, 2.0, 1.0][..]).resolve::<_, 4>(&P3),
            Err(Error::NodesNotIncreasing { index: 2 })
        );
        let pts = [fx1(0.0), fx1(1.0)];
        assert_eq!(
            NodeSource::Given(&[fx(-10000.0), fx(10000.0)][..]).resolve::<_, 4>(&pts),
            Err(Error::OutOfRange)
        );
    }

    #[test]
    fn zero_length_interval() {
        assert_eq!(
            NodeSource::<f64>::Computed(CHORD).resolve::<_, 4>(&[[1.0], [1.0]]),
            Err(Error::ZeroLengthInterval { index: 0 })
        );
    }
}

mod validate_nodes {
    use super::*;

    #[test]
    fn non_finite() {
        assert_eq!(validate_interpolation_nodes(&[NAN]), Err(Error::NonFinite));
        assert_eq!(
            validate_interpolation_nodes(&[0.0_f32, f32::INFINITY]),
            Err(Error::NonFinite)
        );
    }

    #[test]
    fn nodes_not_increasing() {
        assert_eq!(
            validate_interpolation_nodes(&[0.0, 1.0, 2.0, 1.5]),
            Err(Error::NodesNotIncreasing { index: 3 })
        );
        assert_eq!(
            validate_interpolation_nodes(&[fx(0.0), fx(0.0)]),
            Err(Error::NodesNotIncreasing { index: 1 })
        );
    }

    #[test]
    fn out_of_range() {
        // a node beyond f64::MAX / 2, and a span beyond it
        assert_eq!(
            validate_interpolation_nodes(&[0.0, 1.0e308]),
            Err(Error::OutOfRange)
        );
        assert_eq!(
            validate_interpolation_nodes(&[-8.0e307, 8.0e307]),
            Err(Error::OutOfRange)
        );
        assert_eq!(
            validate_interpolation_nodes(&[I16F16::MIN, fx(0.0)]),
            Err(Error::OutOfRange)
        );
        assert_eq!(validate_interpolation_nodes::<f64>(&[]), Ok(()));
    }
}

mod tridiagonal {
    use super::*;

    #[test]
    fn length_mismatch() {
        let (d, mut rhs, mut s) = ([2.0_f64; 3], [[1.0_f64]; 3], [0.0; 3]);
        let short = [1.0; 2];
        let e = |found| Err(Error::LengthMismatch { expected: 3, found });
        assert_eq!(solve_tridiagonal(&short, &d, &d, &mut rhs, &mut s), e(2));
        assert_eq!(solve_tridiagonal(&d, &d, &short, &mut rhs, &mut s), e(2));
        assert_eq!(solve_tridiagonal(&d, &d, &d, &mut rhs[..1], &mut s), e(1));
        assert_eq!(solve_tridiagonal(&d, &d, &d, &mut rhs, &mut s[..2]), e(2));
        let mut c = [0.0; 3];
        assert_eq!(
            solve_cyclic_tridiagonal(&d, &d, &d, &mut rhs, &mut s, &mut c[..1]),
            e(1)
        );
        assert_eq!(
            solve_cyclic_tridiagonal(&short, &d, &d, &mut rhs, &mut s, &mut c),
            e(2)
        );
    }

    #[test]
    fn non_finite() {
        let (d, mut s, mut c) = ([2.0_f64; 3], [0.0; 3], [0.0; 3]);
        let bad = [2.0, NAN, 2.0];
        let mut rhs = [[1.0_f64]; 3];
        assert_eq!(
            solve_tridiagonal(&d, &bad, &d, &mut rhs, &mut s),
            Err(Error::NonFinite)
        );
        let mut bad_rhs = [[1.0], [INF], [1.0]];
        assert_eq!(
            solve_cyclic_tridiagonal(&d, &d, &d, &mut bad_rhs, &mut s, &mut c),
            Err(Error::NonFinite)
        );
    }

    #[test]
    fn invalid_argument_zero_pivot() {
        let (mut s, mut c) = ([0.0; 3], [0.0; 3]);
        // first pivot zero
        let mut rhs = [[1.0_f64]; 2];
        assert_eq!(
            solve_tridiagonal(&[0.0, 1.0], &[0.0, 1.0], &[1.0, 0.0], &mut rhs, &mut s),
            Err(Error::InvalidArgument)
        );
        // singular [1 1; 1 1]: second pivot 1 − 1·1 = 0
        let mut rhs = [[1.0_f64]; 2];
        assert_eq!(
            solve_tridiagonal(&[1.0; 2], &[1.0; 2], &[1.0; 2], &mut rhs, &mut s),
            Err(Error::InvalidArgument)
        );
        // cyclic: diag[0] = 0 (the Sherman–Morrison γ = −diag[0] divides)
        let mut rhs = [[1.0_f64]; 3];
        assert_eq!(
            solve_cyclic_tridiagonal(
                &[1.0; 3],
                &[0.0, 4.0, 4.0],
                &[1.0; 3],
                &mut rhs,
                &mut s,
                &mut c
            ),
            Err(Error::InvalidArgument)
        );
        // cyclic, singular: the all-ones 3×3 matrix
        let mut rhs = [[1.0_f64]; 3];
        assert_eq!(
            solve_cyclic_tridiagonal(&[1.0; 3], &[1.0; 3], &[1.0; 3], &mut rhs, &mut s, &mut c),
            Err(Error::InvalidArgument)
        );
        // cyclic 1×1: sub + diag + sup = 0
        let mut rhs = [[1.0_f64]];
        assert_eq!(
            solve_cyclic_tridiagonal(&[1.0], &[-2.0], &[1.0], &mut rhs, &mut s, &mut c),
            Err(Error::InvalidArgument)
        );
    }

    #[test]
    fn out_of_range() {
        let (mut s, mut c) = ([fx(0.0); 2], [fx(0.0); 2]);
        let tiny = I16F16::DELTA;
        let mut rhs = [fx1(10000.0), fx1(1.0)];
        assert_eq!(
            solve_tridiagonal(
                &[fx(0.0); 2],
                &[tiny, fx(1.0)],
                &[fx(0.0); 2],
                &mut rhs,
                &mut s
            ),
            Err(Error::OutOfRange)
        );
        let mut rhs = [fx1(10000.0), fx1(1.0)];
        assert_eq!(
            solve_cyclic_tridiagonal(
                &[fx(0.0); 2],
                &[tiny, fx(1.0)],
                &[fx(0.0); 2],
                &mut rhs,
                &mut s,
                &mut c
            ),
            Err(Error::OutOfRange)
        );
    }

    /// Found by `arbitrary_input_never_panics`: `solve_cyclic_tridiagonal` computes the
    /// Sherman–Morrison `γ = −diag[0]`: the negation of the most negative fixed-point value
    /// overflows; it is checked and reported as `OutOfRange` (it once panicked in debug builds).
    #[test]
    fn cyclic_most_negative_diagonal() {
        let (mut s, mut c) = ([fx(0.0); 2], [fx(0.0); 2]);
        let mut rhs = [fx1(1.0), fx1(1.0)];
        let zero = [fx(0.0); 2];
        let r = solve_cyclic_tridiagonal(
            &zero,
            &[I16F16::MIN, fx(1.0)],
            &zero,
            &mut rhs,
            &mut s,
            &mut c,
        );
        assert_eq!(r, Err(Error::OutOfRange));
    }
}

// ---------------------------------------------------------------------------------------------
// Arbitrary input never panics
// ---------------------------------------------------------------------------------------------

/// Any `f64`: ordinary values, small integers (so that points repeat), extremes, ±∞ and NaN.
fn wild() -> impl Strategy<Value = f64> {
    prop_oneof![
        8 => -10.0..10.0_f64,
        4 => (-2_i32..=2).prop_map(f64::from),
        1 => any::<f64>(),
        1 => prop::sample::select(vec![
            NAN,
            INF,
            -INF,
            f64::MAX,
            -f64::MAX,
            1.0e300,
            -1.0e300,
            1.0e-300,
            f64::MIN_POSITIVE,
            1.0e38,
            4.0e4,
            -4.0e4,
            1.6e4,
            1.0 / 65536.0,
        ]),
    ]
}

/// Conversion of a wild `f64` to each scalar type: floats keep every value (huge → ±∞ in
/// `f32`), fixed-point saturates at its representable range (NaN → 0).
trait Wild: Scalar {
    fn wild(x: f64) -> Self;
}

impl Wild for f64 {
    fn wild(x: f64) -> Self {
        x
    }
}

impl Wild for f32 {
    fn wild(x: f64) -> Self {
        x as f32
    }
}

impl Wild for I16F16 {
    fn wild(x: f64) -> Self {
        if x.is_nan() {
            I16F16::ZERO
        } else {
            I16F16::saturating_from_num(x)
        }
    }
}

impl Wild for I32F32 {
    fn wild(x: f64) -> Self {
        if x.is_nan() {
            I32F32::ZERO
        } else {
            I32F32::saturating_from_num(x)
        }
    }
}

/// Raw input of one constructor call.
#[derive(Clone, Debug)]
struct Raw {
    pts: Vec<Vec<f64>>,
    tangents: Vec<Vec<f64>>,
    nodes: Option<Vec<f64>>,
    param: Parameterization,
    tension: f64,
    ends: (Vec<f64>, Vec<f64>),
    close: bool,
    us: Vec<f64>,
}

fn raw() -> impl Strategy<Value = Raw> {
    let point = || prop::collection::vec(wild(), 3);
    (0_usize..=10).prop_flat_map(move |n| {
        (
            prop::collection::vec(point(), n),
            prop::collection::vec(point(), n.saturating_sub(1)..=n + 1),
            prop_oneof![
                Just(None),
                prop::collection::vec(wild(), n.saturating_sub(1)..=n + 1).prop_map(Some),
                // sorted: mostly increasing, equal neighbours now and then
                prop::collection::vec(wild(), n..=n).prop_map(|mut u| {
                    u.sort_by(f64::total_cmp);
                    Some(u)
                }),
            ],
            prop::sample::select(vec![UNIFORM, CHORD, CENTRIPETAL]),
            wild(),
            (point(), point()),
            any::<bool>(),
            prop::collection::vec(wild(), 6),
        )
            .prop_map(
                |(pts, tangents, nodes, param, tension, ends, close, us)| Raw {
                    pts,
                    tangents,
                    nodes,
                    param,
                    tension,
                    ends,
                    close,
                    us,
                },
            )
    })
}

/// Evaluates `c` at wild parameters, at its domain ends and piece boundaries, for every
/// derivative order up to 5, checking that the results are finite.
fn exercise<C>(c: &C, us: &[f64])
where
    C: ParamCurveDeriv,
    <C::Point as Point>::Scalar: Wild,
{
    type S<C> = <<C as ParamCurve>::Point as Point>::Scalar;
    let (a, b) = c.domain();
    assert!(a < b, "empty domain");
    let mut params: Vec<S<C>> = us.iter().map(|&u| S::<C>::wild(u)).collect();
    params.extend([a, b]);
    for i in 0..c.piece_count() + 2 {
        let (x, y) = c.piece_domain(i);
        assert!(x <= y, "piece {i}");
        params.extend([x, y]);
    }
    params.extend([NAN, INF, -INF].map(S::<C>::wild));
    for u in params {
        for k in 0..=5 {
            let p = c.deriv(u, k);
            assert!(p.is_finite(), "deriv({u:?}, {k}) = {p:?}");
        }
        assert!(c.eval(u).is_finite());
    }
}

/// Every constructor of the module on the raw input, in the point type `P`.
fn try_all<P: Point>(raw: &Raw)
where
    P::Scalar: Wild,
{
    let cut = |v: &Vec<f64>| -> P { P::from_coords(|i| Wild::wild(v[i])) };
    let mut pts: Vec<P> = raw.pts.iter().map(cut).collect();
    if raw.close
        && let Some(&first) = pts.first()
    {
        pts.push(first);
    }
    let tangents: Vec<P> = raw.tangents.iter().map(cut).collect();
    let given: Vec<P::Scalar> = raw.nodes.iter().flatten().map(|&u| Wild::wild(u)).collect();
    let src = || match raw.nodes {
        Some(_) => NodeSource::Given(given.as_slice()),
        None => NodeSource::Computed(raw.param),
    };
    let tension: P::Scalar = Wild::wild(raw.tension);
    let (start, end) = (cut(&raw.ends.0), cut(&raw.ends.1));
    let us = &raw.us;

    let _ = raw.param.nodes::<P, 8>(&pts);
    let _ = src().resolve::<P, 8>(&pts);
    let _ = validate_interpolation_nodes(&given);
    if let Ok(c) = LagrangeCurve::<P, 8>::new(&pts, src()) {
        exercise(&c, us);
        assert_eq!(c.nodes().len(), c.points().len());
    }
    let hermites = [
        HermiteSpline::<P, 8>::new(&pts, &tangents, src()),
        HermiteSpline::<P, 8>::catmull_rom(&pts, src()),
        HermiteSpline::<P, 8>::cardinal(&pts, src(), tension),
    ];
    for h in hermites.into_iter().flatten() {
        exercise(&h, us);
        for i in 0..h.piece_count() + 2 {
            if let Some(s) = h.segment(i) {
                exercise(&s, us);
            }
        }
        for &u in us {
            let i = h.piece_index(Wild::wild(u));
            assert!(i < h.piece_count());
        }
    }
    if let Ok(c) = ParabolicBlend::<P, 8>::new(&pts) {
        exercise(&c, us);
    }
    for b in [
        SplineBoundary::Natural,
        SplineBoundary::Clamped { start, end },
        SplineBoundary::Periodic,
    ] {
        if let Ok(c) = CubicSpline::<P, 8>::new(&pts, src(), b) {
            exercise(&c, us);
        }
    }
    if let (Some(&u0), Some(&u1)) = (given.first(), given.last())
        && let &[q0, q1, ..] = pts.as_slice()
        && let &[m0, m1, ..] = tangents.as_slice()
        && let Ok(s) = HermiteSegment::new(u0, u1, q0, q1, m0, m1)
    {
        exercise(&s, us);
    }
    // The solvers on the same numbers: sub = x, diag = y, sup = z of the points.
    let n = pts.len();
    let col = |c: usize| -> Vec<P::Scalar> { pts.iter().map(|p| p.coord(c)).collect() };
    let (sub, diag, sup) = (col(0), col(1), col(2.min(P::DIM - 1)));
    let mut rhs = tangents.clone();
    rhs.resize(n, P::zero());
    let (mut scratch, mut correction) = (vec![P::Scalar::ZERO; n], vec![P::Scalar::ZERO; n]);
    let _ = solve_tridiagonal(&sub, &diag, &sup, &mut rhs, &mut scratch);
    let mut rhs = tangents.clone();
    rhs.resize(n, P::zero());
    let _ = solve_cyclic_tridiagonal(&sub, &diag, &sup, &mut rhs, &mut scratch, &mut correction);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn arbitrary_input_never_panics(raw in raw()) {
        try_all::<[f64; 2]>(&raw);
        try_all::<[f64; 3]>(&raw);
        try_all::<[f32; 2]>(&raw);
        try_all::<Vec3>(&raw);
        try_all::<[I16F16; 2]>(&raw);
        try_all::<[I32F32; 3]>(&raw);
    }
}

/// `±m·2^e` with `m ∈ [1, 2)` and `e ∈ [emin, emax]`: magnitudes spread evenly over the
/// exponent range of a scalar type, up to its limit.
fn log_value(emin: i32, emax: i32) -> impl Strategy<Value = f64> {
    (any::<bool>(), emin..=emax, 1.0..2.0_f64).prop_map(|(negative, e, m)| {
        let v = m * 2.0_f64.powi(e);
        if negative { -v } else { v }
    })
}

/// Finite input of every magnitude the scalar type can hold (exponents `emin..=emax`), with
/// increasing given nodes (gaps of every magnitude too): exercises the fixed-point range
/// checks near their limits, where an evaluation that the constructor let through could
/// overflow.
fn scaled_raw(emin: i32, emax: i32) -> impl Strategy<Value = Raw> {
    let point = move || prop::collection::vec(log_value(emin, emax), 3);
    (2_usize..=8).prop_flat_map(move |n| {
        (
            prop::collection::vec(point(), n),
            prop::collection::vec(point(), n),
            prop_oneof![
                Just(None),
                (
                    log_value(emin, emax),
                    prop::collection::vec(log_value(emin, emax), n - 1)
                )
                    .prop_map(|(start, gaps)| {
                        let mut u = vec![start];
                        for g in gaps {
                            u.push(u[u.len() - 1] + g.abs());
                        }
                        Some(u)
                    }),
            ],
            prop::sample::select(vec![UNIFORM, CHORD, CENTRIPETAL]),
            prop_oneof![-1.0..2.0_f64, log_value(emin, emax)],
            (point(), point()),
            any::<bool>(),
            prop::collection::vec(log_value(emin, emax), 6),
        )
            .prop_map(
                |(pts, tangents, nodes, param, tension, ends, close, us)| Raw {
                    pts,
                    tangents,
                    nodes,
                    param,
                    tension,
                    ends,
                    close,
                    us,
                },
            )
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn input_near_the_range_limits_never_panics(
        f64_raw in scaled_raw(-40, 1023),
        f32_raw in scaled_raw(-40, 127),
        i16_raw in scaled_raw(-17, 15),
        i32_raw in scaled_raw(-33, 31),
    ) {
        try_all::<[f64; 3]>(&f64_raw);
        try_all::<[f32; 2]>(&f32_raw);
        try_all::<[I16F16; 2]>(&i16_raw);
        try_all::<[I16F16; 1]>(&i16_raw);
        try_all::<[I32F32; 3]>(&i32_raw);
    }
}
