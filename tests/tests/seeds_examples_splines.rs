//! The seeds' worked examples for B-splines and NURBS as exact tests (seeds/000, 002
//! "Basis-Splines", seeds/004 "B-Splines", "NURBS", "NURBS-Kreis", "Viertelkreis durch NURBS").
//!
//! Where a value is exactly representable and every step of the algorithm is exact (dyadic
//! parameters, knot differences 1 and 2), the test asserts bit equality; elsewhere it states
//! its bound in units of `f64::EPSILON` (ulp of 1).

use core::f64::consts::{FRAC_1_SQRT_2, SQRT_2};

use strak_curves::{
    BSpline, KnotVector, Nurbs, ParamCurve, ParamCurveDeriv, basis_function, bspline_basis,
    classify_breaks,
};

const EPS: f64 = f64::EPSILON;

/// seeds/004 "Beispiel für Knotenvektor": `t_j = 0` for `j < k`, `j − k + 1` for `k ≤ j ≤ n`,
/// `n − k + 2` for `j > n`, `j = 0, …, n + k` (order `k = g + 1`, `n + 1` points).
fn seed_knots(n: usize, k: usize) -> Vec<f64> {
    (0..=n + k)
        .map(|j| {
            if j < k {
                0.0
            } else if j <= n {
                (j + 1 - k) as f64
            } else {
                (n + 2 - k) as f64
            }
        })
        .collect()
}

/// seeds/004: `T = (0, 0, 0, 1, 2, 3, 3, 3)` for `n = 4, k = 3` and
/// `T = (0, 0, 0, 0, 1, 2, 3, 4, 5, 6, 6, 6, 6)` for `n = 8, k = 4`, parameter range
/// `t ∈ [0, n − k + 2]`: the seed's formula, strak's clamped uniform knot vector and
/// strak-ref's generator agree with the listed vectors.
#[test]
fn seed_004_knot_vector_examples() {
    let t3 = [0., 0., 0., 1., 2., 3., 3., 3.];
    let t4 = [0., 0., 0., 0., 1., 2., 3., 4., 5., 6., 6., 6., 6.];
    for (n, k, listed) in [(4, 3, &t3[..]), (8, 4, &t4[..])] {
        assert_eq!(seed_knots(n, k), listed);
        let top = (n + 2 - k) as f64;
        let kv = KnotVector::<f64, 16>::clamped_uniform(k - 1, n + 1, 0.0, top).unwrap();
        assert_eq!(kv.as_slice(), listed);
        assert_eq!(kv.domain(), (0.0, top));
        assert_eq!(kv.control_point_count(), n + 1); // "n+1 Gewichtsfunktionen"
        assert_eq!(
            strak_ref::clamped_uniform_knots(k - 1, n + 1, 0.0, top),
            listed
        );
    }
}

/// The quadratic B-spline basis on `T = (0,0,0,1,2,3,3,3)` (seeds/004 "Gewichtspolynome für
/// n=4, k=3") in closed form, derived with Cox–de Boor: `(N_0, …, N_4)(t)`.
fn seed_quadratic_basis(t: f64) -> [f64; 5] {
    if t < 1.0 {
        [
            (1.0 - t) * (1.0 - t),
            2.0 * t - 1.5 * t * t,
            t * t / 2.0,
            0.0,
            0.0,
        ]
    } else if t < 2.0 {
        [
            0.0,
            (2.0 - t) * (2.0 - t) / 2.0,
            (-2.0 * t * t + 6.0 * t - 3.0) / 2.0,
            (t - 1.0) * (t - 1.0) / 2.0,
            0.0,
        ]
    } else {
        let s = 3.0 - t;
        [
            0.0,
            0.0,
            s * s / 2.0,
            2.0 * s - 1.5 * s * s,
            (t - 2.0) * (t - 2.0),
        ]
    }
}

/// seeds/004, `n = 4, k = 3`: the five weight functions `N_{i,3}` on `T = (0,0,0,1,2,3,3,3)`
/// are the piecewise quadratics above, bit for bit at the dyadic parameters `t = j/16` (every
/// knot difference is 1 or 2, so each Cox–de Boor step is exact), with `bspline_basis`
/// (triangular scheme), `basis_function` (the literal recursion) and strak-ref.
/// At `t = 3` the right end uses the last piece (`N_4(3) = 1`).
#[test]
fn seed_004_quadratic_basis_values() {
    let t = [0., 0., 0., 1., 2., 3., 3., 3.];
    let kv = KnotVector::<f64, 8>::new(2, &t).unwrap();
    for j in 0..=48 {
        let x = f64::from(j) / 16.0;
        let want = seed_quadratic_basis(x);
        let (s, n) = bspline_basis(&kv, x);
        for i in 0..5 {
            let from_span = if (s - 2..=s).contains(&i) {
                n[i + 2 - s]
            } else {
                0.0
            };
            assert_eq!(from_span, want[i], "bspline_basis N_{i}({x})");
            assert_eq!(
                basis_function(&t, i, 2, x).unwrap(),
                want[i],
                "basis_function N_{i}({x})"
            );
            assert_eq!(
                strak_ref::cox_de_boor(&t, i, 2, x),
                want[i],
                "cox_de_boor N_{i}({x})"
            );
        }
    }
    // The seed's example value: N_{2,3}(1) = 1/2.
    assert_eq!(basis_function(&t, 2, 2, 1.0).unwrap(), 0.5);
}

/// seeds/004 "Konstruktion von N3,2": `N_{3,2} = (t − 1)·N_{3,1} + (3 − t)·N_{4,1}`, and
/// "Konstruktion von N2,3": `N_{2,3} = t/2·N_{2,2} + (3 − t)/2·N_{3,2}` on
/// `T = (0,0,0,1,2,3,3,3)`. The seed's `N_{j,i}` has order `i` (degree `i − 1`). Bit equality
/// at `t = j/16`: both sides are the same exact dyadic arithmetic.
#[test]
fn seed_004_cox_de_boor_construction_of_n23() {
    let t = [0., 0., 0., 1., 2., 3., 3., 3.];
    let n = |j: usize, order: usize, x: f64| basis_function(&t, j, order - 1, x).unwrap();
    for j in 0..48 {
        let x = f64::from(j) / 16.0;
        assert_eq!(
            n(3, 2, x),
            (x - 1.0) * n(3, 1, x) + (3.0 - x) * n(4, 1, x),
            "N_3,2({x})"
        );
        assert_eq!(
            n(2, 3, x),
            x / 2.0 * n(2, 2, x) + (3.0 - x) / 2.0 * n(3, 2, x),
            "N_2,3({x})"
        );
    }
    // "n+k Ausgangsfunktionen": seven indicator functions N_{j,1}, one per knot interval; only
    // the non-empty intervals [0,1), [1,2), [2,3) are ever on, and exactly one at a time.
    for j in 0..48 {
        let x = f64::from(j) / 16.0;
        let on: Vec<usize> = (0..7).filter(|&i| n(i, 1, x) == 1.0).collect();
        assert_eq!(on, vec![2 + (x as usize)], "N_j,1 at {x}");
    }
}

/// seeds/004, `n = 8, k = 4` (cubic, `T = (0,0,0,0,1,2,3,4,5,6,6,6,6)`): in the uniform middle
/// the basis is the uniform cubic B-spline, `(1/6, 4/6, 1/6)` at a knot and
/// `(1/48, 23/48, 23/48, 1/48)` in the middle of a span; divisions by 3 round, so within
/// `2ε`. The nine functions sum to one everywhere (within `4ε`).
#[test]
fn seed_004_cubic_basis_values() {
    let t = [0., 0., 0., 0., 1., 2., 3., 4., 5., 6., 6., 6., 6.];
    let kv = KnotVector::<f64, 16>::new(3, &t).unwrap();
    let (s, n) = bspline_basis(&kv, 3.0);
    assert_eq!(s, 6);
    for (got, want) in n[..4].iter().zip([1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0, 0.0]) {
        assert!((got - want).abs() <= 2.0 * EPS, "{got} vs {want}");
    }
    let (s, n) = bspline_basis(&kv, 3.5);
    assert_eq!(s, 6);
    for (got, want) in n[..4].iter().zip([1.0, 23.0, 23.0, 1.0].map(|x| x / 48.0)) {
        assert!((got - want).abs() <= 2.0 * EPS, "{got} vs {want}");
    }
    for j in 0..=96 {
        let x = f64::from(j) / 16.0;
        let sum: f64 = (0..9).map(|i| basis_function(&t, i, 3, x).unwrap()).sum();
        assert!((sum - 1.0).abs() <= 4.0 * EPS, "Σ N({x}) = {sum}");
    }
}

/// seeds/004 "Sonderfall k = n + 1": on `T = (0,…,0, 1,…,1)` (each `k` times)
/// `N_{i,k}(t) = (k−1)!/(i!(k−1−i)!) · t^i (1−t)^{k−1−i} = B_{i,n}(t)`: Bernstein polynomials
/// are a special case of B-splines. Orders `k = 2..=8`, `t = j/16`, within `8ε` (the two
/// formulas round differently), and against `strak_ref::bernstein`.
#[test]
fn seed_004_bernstein_special_case() {
    for k in 2..=8_usize {
        let g = k - 1;
        let t: Vec<f64> = (0..2 * k).map(|j| if j < k { 0.0 } else { 1.0 }).collect();
        let kv = KnotVector::<f64, 16>::new(g, &t).unwrap();
        for j in 0..=16 {
            let x = f64::from(j) / 16.0;
            let (s, n) = bspline_basis(&kv, x);
            assert_eq!(s, g);
            for (i, &ni) in n.iter().enumerate().take(g + 1) {
                let fact = |m: usize| (1..=m).map(|v| v as f64).product::<f64>();
                let seed = fact(g) / (fact(i) * fact(g - i))
                    * x.powi(i as i32)
                    * (1.0 - x).powi((g - i) as i32);
                assert!((ni - seed).abs() <= 8.0 * EPS, "k = {k}, N_{i}({x})");
                assert!((ni - strak_ref::bernstein(i, g, x)).abs() <= 8.0 * EPS);
            }
        }
    }
}

/// seeds/000 and 002 "Multiplizität": `n = 4, g = 3, K = 7, m = 11,
/// U = [0,0,0,0,1,2,3,4,4,4,4]`. The end knots have multiplicity `g + 1` (the curve
/// interpolates `d_0` and `d_6`), the simple inner knots give `C^{g−1} = C²` but not `C³`.
/// Doubling the knot 2 (`μ = 2`, one more de Boor point) lowers the continuity there to
/// `C^{g−μ} = C¹`; at `μ = g = 3` the curve is only `C⁰` and passes through a de Boor point
/// ("bei μ = g wird d_i interpoliert"): `u_5 = u_6 = u_7 = 2` gives `c(2) = d_4`.
#[test]
fn seed_000_multiplicity_example() {
    let u = [0., 0., 0., 0., 1., 2., 3., 4., 4., 4., 4.];
    let d = [
        [0.0, 0.0],
        [1.0, 3.0],
        [3.0, 4.0],
        [5.0, 1.0],
        [6.0, -2.0],
        [8.0, 0.5],
        [9.0, 2.0],
        [11.0, 3.0],
        [12.0, -1.0],
    ];
    let kv = KnotVector::<f64, 16>::new(3, &u).unwrap();
    assert_eq!(
        (kv.control_point_count(), u.len(), kv.piece_count()),
        (7, 11, 4)
    );
    assert_eq!(
        (
            kv.multiplicity(0.0),
            kv.multiplicity(2.0),
            kv.multiplicity(4.0)
        ),
        (4, 1, 4)
    );
    let c = BSpline::<[f64; 2], 16, 16>::new(3, &d[..7], &u).unwrap();
    assert_eq!(c.domain(), (0.0, 4.0));
    assert_eq!(c.eval(0.0), d[0]);
    assert_eq!(c.eval(4.0), d[6]);
    assert_eq!(classify_breaks(&c, 1e-9).unwrap().parametric, Some(2));

    // μ = 2 at u = 2: C¹, the second derivative jumps there.
    let u2 = [0., 0., 0., 0., 1., 2., 2., 3., 4., 4., 4., 4.];
    let c2 = BSpline::<[f64; 2], 16, 16>::new(3, &d[..8], &u2).unwrap();
    assert_eq!(classify_breaks(&c2, 1e-9).unwrap().parametric, Some(1));
    let (l, r) = (c2.piece_deriv(1, 2.0, 1), c2.piece_deriv(2, 2.0, 1));
    assert!((l[0] - r[0]).abs() <= 1e-13 && (l[1] - r[1]).abs() <= 1e-13);
    assert_ne!(c2.piece_deriv(1, 2.0, 2), c2.piece_deriv(2, 2.0, 2));

    // μ = g = 3 at u = 2: C⁰ only, through d_4.
    let u3 = [0., 0., 0., 0., 1., 2., 2., 2., 3., 4., 4., 4., 4.];
    let c3 = BSpline::<[f64; 2], 16, 16>::new(3, &d, &u3).unwrap();
    assert_eq!(classify_breaks(&c3, 1e-9).unwrap().parametric, Some(0));
    assert_eq!(c3.eval(2.0), d[4]);
    assert_eq!(c3.piece_deriv(1, 2.0, 0), d[4]);

    // A fourth copy would be a jump inside the domain: "nur an den Endpunkten erlaubt".
    let u4 = [0., 0., 0., 0., 1., 2., 2., 2., 2., 3., 4., 4., 4., 4.];
    let mut d4 = d.to_vec();
    d4.push([13.0, 0.0]);
    assert_eq!(
        BSpline::<[f64; 2], 16, 16>::new(3, &d4, &u4).unwrap_err(),
        strak_curves::Error::KnotMultiplicity { index: 5 }
    );

    // Knot insertion (Boehm) up to μ = g keeps the curve, which then passes through the new
    // de Boor point d_4 at u = 2; a fourth copy is refused.
    let i3 = c.insert_knot(2.0).unwrap().insert_knot(2.0).unwrap();
    assert_eq!(i3.knots(), &u3);
    let (p, q) = (i3.eval(2.0), i3.control_points()[4]);
    assert!((p[0] - q[0]).abs() <= 8.0 * EPS * 8.0 && (p[1] - q[1]).abs() <= 8.0 * EPS * 8.0);
    assert_eq!(classify_breaks(&i3, 1e-9).unwrap().parametric, Some(2)); // same C² curve
    assert_eq!(
        i3.insert_knot(2.0).unwrap_err(),
        strak_curves::Error::KnotMultiplicity { index: 5 }
    );
}

/// seeds/002 "Symbolübersicht" examples: `g = 0, n = 4, K = 4, m = 5, U = 01234`;
/// `g = 1, n = 4, K = 5, m = 7, U = 0012344`; `g = 3, n = 4, K = 7, m = 11, U = 00001234444`;
/// seeds/000: `g = 3, n = 5, m = 12, K = 8, U = 000012345555` — `m = K + g + 1` for open
/// splines, `K = n + g` points for `n` segments.
#[test]
fn seed_002_knot_vector_table() {
    let cases: [(usize, usize, &[f64]); 4] = [
        (0, 4, &[0., 1., 2., 3., 4.]),
        (1, 4, &[0., 0., 1., 2., 3., 4., 4.]),
        (3, 4, &[0., 0., 0., 0., 1., 2., 3., 4., 4., 4., 4.]),
        (3, 5, &[0., 0., 0., 0., 1., 2., 3., 4., 5., 5., 5., 5.]),
    ];
    for (g, n, u) in cases {
        let k = n + g;
        let kv = KnotVector::<f64, 16>::clamped_uniform(g, k, 0.0, n as f64).unwrap();
        assert_eq!(kv.as_slice(), u, "g = {g}, n = {n}");
        assert_eq!(u.len(), k + g + 1);
        assert_eq!(kv.piece_count(), n);
    }
}

/// seeds/004 "NURBS-Kreis": the homogeneous control points `(x, y, h)` listed in the seed —
/// `(1,0,1), (1,1,√2/2), (0,1,1), (−1,1,√2/2), (−1,0,1), (−1,−1,√2/2), (0,−1,1), (1,−1,√2/2),
/// (1,0,1)` — and the knot vector `0,0,0,1,1,2,2,3,3,4,4,4`, exactly. In homogeneous
/// coordinates ("NURBS + homogene Koordinaten") the B-spline carries `(h·x, h·y, h)`.
#[test]
fn seed_004_nurbs_circle_definition() {
    let c = Nurbs::<[f64; 2], 9, 12>::circle([0.0, 0.0], 1.0).unwrap();
    let s = FRAC_1_SQRT_2;
    let seed = [
        (1.0, 0.0, 1.0),
        (1.0, 1.0, s),
        (0.0, 1.0, 1.0),
        (-1.0, 1.0, s),
        (-1.0, 0.0, 1.0),
        (-1.0, -1.0, s),
        (0.0, -1.0, 1.0),
        (1.0, -1.0, s),
        (1.0, 0.0, 1.0),
    ];
    assert_eq!(c.knots(), &[0., 0., 0., 1., 1., 2., 2., 3., 3., 4., 4., 4.]);
    assert_eq!(c.degree(), 2);
    for (i, &(x, y, h)) in seed.iter().enumerate() {
        assert_eq!(c.control_points()[i], [x, y], "P_{i}");
        assert_eq!(c.weights()[i], h, "h_{i}");
        let hp = c.homogeneous().control_points()[i];
        assert_eq!(
            (hp.weighted, hp.weight),
            ([h * x, h * y], h),
            "homogeneous P_{i}"
        );
    }
}

/// seeds/004 "korrekter Kreis, denn P_x² + P_y² = 1": the NURBS circle has radius 1 up to
/// `f64` rounding. Over 10⁵ + 1 parameters spread over `[0, 4]` the distance from the center
/// differs from 1 by at most 2 ulp (`2ε`; measured: 1 ulp, from the weight √2/2 rounded once,
/// de Boor's rounding and the final division); the radius is exact at the quarter points.
#[test]
fn seed_004_nurbs_circle_radius() {
    let c = Nurbs::<[f64; 2], 9, 12>::circle([0.0, 0.0], 1.0).unwrap();
    let mut worst = 0.0_f64;
    for i in 0..=100_000 {
        let u = 4.0 * f64::from(i) / 100_000.0;
        let p = c.eval(u);
        worst = worst.max((p[0].hypot(p[1]) - 1.0).abs());
    }
    eprintln!("NURBS circle: largest |r − 1| = {:.2} ulp", worst / EPS);
    assert!(worst <= 2.0 * EPS, "|r − 1| up to {} ulp", worst / EPS);
    for (u, want) in [
        (0.0, [1.0, 0.0]),
        (1.0, [0.0, 1.0]),
        (2.0, [-1.0, 0.0]),
        (3.0, [0.0, -1.0]),
        (4.0, [1.0, 0.0]),
    ] {
        assert_eq!(c.eval(u), want);
    }
}

/// seeds/004 "Viertelkreis durch NURBS", with `s = √2/2` and `t ∈ [0, 1/4]` (the full circle's
/// parameter scaled to `[0, 1]`, so the first quarter is `u = 4t`):
///
/// ```text
/// P_x(t) = (16t² − 8t + 1 + s(−32t² + 8t)) / (16t² − 8t + 1 + s(−32t² + 8t) + 16t²)
/// P_y(t) = (s(−32t² + 8t) + 16t²)          / (16t² − 8t + 1 + s(−32t² + 8t) + 16t²)
/// ```
///
/// The curve's first quarter equals the formula within `4ε` over 10⁴ samples (two different
/// roundings of the same rational function; measured 2.5ε), and so does strak-ref's
/// `nurbs_quarter_circle_seed`. The other quarters are the first one turned by 90°, 180°, 270°.
#[test]
fn seed_004_nurbs_quarter_circle_formula() {
    let s = SQRT_2 / 2.0;
    let seed = |t: f64| {
        let a = 16.0 * t * t - 8.0 * t + 1.0 + s * (-32.0 * t * t + 8.0 * t);
        let y = s * (-32.0 * t * t + 8.0 * t) + 16.0 * t * t;
        let d = a + 16.0 * t * t;
        [a / d, y / d]
    };
    let c = Nurbs::<[f64; 2], 9, 12>::circle([0.0, 0.0], 1.0).unwrap();
    let mut worst = 0.0_f64;
    for i in 0..=10_000 {
        let t = 0.25 * f64::from(i) / 10_000.0;
        let want = seed(t);
        let r = strak_ref::nurbs_quarter_circle_seed(t);
        assert!((r[0] - want[0]).abs() <= 4.0 * EPS && (r[1] - want[1]).abs() <= 4.0 * EPS);
        // The quarters q = 0..3: rotation by q·90° maps (x, y) to (−y, x) q times.
        let mut rot = want;
        for q in 0..4 {
            let p = c.eval(4.0 * t + f64::from(q));
            worst = worst.max((p[0] - rot[0]).abs()).max((p[1] - rot[1]).abs());
            rot = [-rot[1], rot[0]];
        }
    }
    eprintln!(
        "quarter-circle formula: largest difference = {:.2} ulp",
        worst / EPS
    );
    assert!(worst <= 4.0 * EPS, "difference up to {} ulp", worst / EPS);
}

/// seeds/004 NURBS circle: "2 Kreise, Bezier / NURBS" — the rational curve is exact, and its
/// quarters meet with equal velocity `√2·r` (C¹), the tangent perpendicular to the radius.
#[test]
fn seed_004_nurbs_circle_velocity() {
    let r = 2.5;
    let c = Nurbs::<[f64; 2], 9, 12>::circle([1.0, -1.0], r).unwrap();
    for q in 0..4 {
        let u = f64::from(q);
        let v = c.deriv(u, 1);
        let speed = v[0].hypot(v[1]);
        assert!(
            (speed - SQRT_2 * r).abs() <= 8.0 * EPS * r,
            "speed {speed} at {u}"
        );
        let p = c.eval(u);
        let radial = (p[0] - 1.0) * v[0] + (p[1] + 1.0) * v[1];
        assert!(
            radial.abs() <= 8.0 * EPS * r * r,
            "tangent not ⟂ radius at {u}"
        );
    }
}
