//! The worked examples of the lecture notes (seeds/000, 002, 003, 004) on bases and Bézier
//! curves, as exact tests through the public API of strak-curves.
//!
//! Results are compared with `==` in `f64` wherever the computation is exact (integers, dyadic
//! fractions); where a division by 3 or a rounding of `1/3` is involved the bound is stated in
//! ulps (units in the last place, see [`ulps`]) next to the assertion.

use glam::DVec2;
use strak_curves::basis::{self, LagrangeBasis, MonomialCurve};
use strak_curves::{
    Bezier, I16F16, ParamCurve, ParamCurveDeriv, QUARTER_CIRCLE_KAPPA,
    QUARTER_CIRCLE_KAPPA_MIDPOINT, Scalar, quarter_circle_radial_error,
};

/// The distance between two `f64` values in units of the last place of the larger one.
fn ulps(a: f64, b: f64) -> f64 {
    let m = a.abs().max(b.abs());
    if m == 0.0 {
        return 0.0;
    }
    // the spacing of f64 values at m: 2^(exponent(m) − 52)
    let spacing = f64::EPSILON * 2f64.powi(m.log2().floor() as i32);
    (a - b).abs() / spacing
}

/// seeds/000 "Polynombasen Vergleich": `f(t) = 2B₀³ − 2B₁³ + 5B₂³ + 1B₃³ ⟺ (2 −2 5 1)` is, in
/// the monomial basis, `2 − 12t + 33t² − 22t³`.
///
/// **Erratum.** The seed prints `2 − 12t + 33t² − 23t³` and `(2 −12 33 −23)`. Its own
/// intermediate lines give the cubic terms `−2t³ − 6t³ − 15t³ + t³ = −22t³`, and a Bézier curve
/// interpolates its last point, `f(1) = b₃ = 1`, which holds for `−22` (`2 − 12 + 33 − 22 = 1`)
/// but not for `−23` (which gives `0`). The correct vector is `(2, −12, 33, −22)`.
#[test]
fn seed000_bernstein_2_m2_5_1_to_monomial() {
    let b = [[2.0], [-2.0], [5.0], [1.0]];
    let a = basis::bernstein_to_monomial(&b).unwrap();
    assert_eq!(a, [[2.0], [-12.0], [33.0], [-22.0]]);
    // the seed's intermediate lines: each Bernstein term expanded (rows of A_{B←M} times b_i)
    let rows = basis::bernstein_basis_matrix::<f64, 4>().unwrap();
    let lines: Vec<[f64; 4]> = (0..4).map(|i| rows[i].map(|v| v * b[i][0])).collect();
    assert_eq!(lines[0], [2.0, -6.0, 6.0, -2.0]); // 2(1−t)³
    assert_eq!(lines[1], [0.0, -6.0, 12.0, -6.0]); // −2·3t(1−t)²
    assert_eq!(lines[2], [0.0, 0.0, 15.0, -15.0]); // 5·3t²(1−t)
    assert_eq!(lines[3], [0.0, 0.0, 0.0, 1.0]); // 1·t³
    let cubic: f64 = lines.iter().map(|l| l[3]).sum();
    assert_eq!(cubic, -22.0, "the seed's own lines sum to −22, not −23");
    // f(1) = b₃ = 1 decides: −22 is right, the printed −23 is not
    assert_eq!(basis::horner(&[2.0, -12.0, 33.0, -22.0], 1.0), 1.0);
    assert_eq!(basis::horner(&[2.0, -12.0, 33.0, -23.0], 1.0), 0.0);
    // the same through Bézier curves and monomial curves, and back
    let c = Bezier::new(b).unwrap();
    let m = c.to_monomial().unwrap();
    assert_eq!(m.coefficients(), &[[2.0], [-12.0], [33.0], [-22.0]]);
    assert_eq!(Bezier::from_monomial(&m).unwrap(), c);
    assert_eq!(basis::monomial_to_bernstein(&a).unwrap(), b);
    assert_eq!(c.eval(1.0), [1.0]);
    // in fixed-point the conversion of these integers is exact as well
    let bx = b.map(|p| [I16F16::from_num(p[0])]);
    let ax = basis::bernstein_to_monomial(&bx).unwrap();
    assert_eq!(ax.map(|p| p[0].to_f64()), [2.0, -12.0, 33.0, -22.0]);
}

/// seeds/000 "Polynombasen Vergleich": `a⃗ = T_{M←B} b⃗`, and the seed's row form
/// `(2 −2 5 1) · A_{B←M} = a⃗ᵀ` with the printed matrix `A_{B←M}`.
#[test]
fn seed000_coefficients_through_the_matrices() {
    let b = [2.0, -2.0, 5.0, 1.0];
    let t_mb = basis::bernstein_to_monomial_matrix::<f64, 4>().unwrap();
    let a: Vec<f64> = (0..4)
        .map(|j| (0..4).map(|i| t_mb[j][i] * b[i]).sum())
        .collect();
    assert_eq!(a, [2.0, -12.0, 33.0, -22.0]);
    let a_bm = basis::bernstein_basis_matrix::<f64, 4>().unwrap();
    let row: Vec<f64> = (0..4)
        .map(|j| (0..4).map(|i| b[i] * a_bm[i][j]).sum())
        .collect();
    assert_eq!(row, [2.0, -12.0, 33.0, -22.0]);
}

/// seeds/000 "Beispieltransformation": `B⃗³(t) = A_{B←M} M⃗³(t)` with
/// `A_{B←M} = [[1,−3,3,−1],[0,3,−6,3],[0,0,3,−3],[0,0,0,1]]`,
/// `T_{B←M} = ((A_{B←M})ᵀ)⁻¹ = [[1,0,0,0],[1,1/3,0,0],[1,2/3,1/3,0],[1,1,1,1]]` and
/// `T_{M←B} = A_{B←M}ᵀ`.
///
/// `1/3` and `2/3` are single correctly rounded divisions `C(i,j)/C(g,j)`, so they equal the
/// `f64` literals `1.0 / 3.0` and `2.0 / 3.0` exactly (≤ ½ ulp from the true value).
#[test]
fn seed000_matrices_degree_3() {
    let a = basis::bernstein_basis_matrix::<f64, 4>().unwrap();
    assert_eq!(
        a,
        [
            [1.0, -3.0, 3.0, -1.0],
            [0.0, 3.0, -6.0, 3.0],
            [0.0, 0.0, 3.0, -3.0],
            [0.0, 0.0, 0.0, 1.0],
        ]
    );
    let t_bm = basis::monomial_to_bernstein_matrix::<f64, 4>().unwrap();
    assert_eq!(
        t_bm,
        [
            [1.0, 0.0, 0.0, 0.0],
            [1.0, 1.0 / 3.0, 0.0, 0.0],
            [1.0, 2.0 / 3.0, 1.0 / 3.0, 0.0],
            [1.0, 1.0, 1.0, 1.0],
        ]
    );
    let t_mb = basis::bernstein_to_monomial_matrix::<f64, 4>().unwrap();
    for i in 0..4 {
        for j in 0..4 {
            assert_eq!(t_mb[i][j], a[j][i], "T_(M←B) = A_(B←M)ᵀ");
        }
    }
    // B⃗³(t) = A M⃗³(t), exactly at dyadic t (all products and sums are exact)
    for t in [0.0, 0.25, 0.5, 0.75, 1.0] {
        let m = basis::monomials::<f64, 4>(t);
        let via_a: Vec<f64> = (0..4)
            .map(|i| (0..4).map(|j| a[i][j] * m[j]).sum())
            .collect();
        assert_eq!(via_a, basis::bernstein_all::<f64, 4>(t), "t = {t}");
    }
    // fixed-point: 1/3 is rounded once, within half a unit of I16F16
    let tx = basis::monomial_to_bernstein_matrix::<I16F16, 4>().unwrap();
    assert!((tx[1][1].to_f64() - 1.0 / 3.0).abs() <= <I16F16 as Scalar>::EPSILON / 2.0);
    assert!((tx[2][1].to_f64() - 2.0 / 3.0).abs() <= <I16F16 as Scalar>::EPSILON / 2.0);
}

/// seeds/000 "Pascal'sches Dreieck" rows `n = 0..4` and the binomial coefficient
/// `C(n, i) = n!/(i!(n−i)!)`.
#[test]
fn seed000_pascal_triangle() {
    assert_eq!(basis::pascal_row::<1>(), Some([1]));
    assert_eq!(basis::pascal_row::<2>(), Some([1, 1]));
    assert_eq!(basis::pascal_row::<3>(), Some([1, 2, 1]));
    assert_eq!(basis::pascal_row::<4>(), Some([1, 3, 3, 1]));
    assert_eq!(basis::pascal_row::<5>(), Some([1, 4, 6, 4, 1]));
    let fact = |n: u64| (1..=n).product::<u64>();
    for n in 0..=4_u64 {
        for i in 0..=n {
            let c = fact(n) / (fact(i) * fact(n - i));
            assert_eq!(basis::binomial(n as usize, i as usize), Some(c));
        }
    }
}

/// seeds/000 "Bernsteinbasis": `B⃗²(t) = ((1−t)², 2(1−t)t, t²)` and
/// `B⃗³(t) = ((1−t)³, 3(1−t)²t, 3(1−t)t², t³)`, exactly at dyadic `t`.
#[test]
fn seed000_bernstein_vectors() {
    for t in [0.0, 0.125, 0.25, 0.5, 0.75, 1.0] {
        let s = 1.0 - t;
        assert_eq!(
            basis::bernstein_all::<f64, 3>(t),
            [s * s, 2.0 * s * t, t * t]
        );
        assert_eq!(
            basis::bernstein_all::<f64, 4>(t),
            [s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t]
        );
    }
}

/// seeds/000 "Effiziente Auswertung": Horner scheme `f = a_g; f = a_i + t f` and the
/// "Standardauswertung" with powers `M_i = tⁱ` agree (exactly for these integers).
#[test]
fn seed000_horner_scheme() {
    let a = [2.0, -12.0, 33.0, -22.0];
    for t in [-2.0, -0.5, 0.0, 0.5, 1.0, 3.0] {
        let m = [1.0, t, t * t, t * t * t];
        let standard: f64 = a.iter().zip(m).map(|(x, y)| x * y).sum();
        assert_eq!(basis::horner(&a, t), standard, "t = {t}");
    }
    // a monomial curve of the same coefficients, and its derivatives f', f'', f'''
    let f = MonomialCurve::new(a.map(|v| [v])).unwrap();
    assert_eq!(f.eval(0.5), [2.0 - 6.0 + 33.0 / 4.0 - 22.0 / 8.0]);
    assert_eq!(f.deriv(0.5, 1), [-12.0 + 33.0 - 3.0 * 22.0 / 4.0]);
    assert_eq!(f.deriv(0.5, 2), [66.0 - 66.0]);
    assert_eq!(f.deriv(0.5, 3), [-132.0]);
}

/// seeds/002 "Aufstellen der Lagrange Basis": nodes `{0, 1, 3}`,
/// `L₀ = (t² − 4t + 3)/3`, `L₁ = t(t − 3)/−2`, `L₂ = t(t − 1)/6`.
///
/// The product formula divides twice per function, the seed's form once, so the two may round
/// differently: the values agree to 1 ulp (exactly at the nodes, where `L_i(u_j) = δ_ij`).
#[test]
fn seed002_lagrange_basis_nodes_0_1_3() {
    let l = LagrangeBasis::new([0.0, 1.0, 3.0]).unwrap();
    let seed = |t: f64| {
        [
            (t * t - 4.0 * t + 3.0) / 3.0,
            t * (t - 3.0) / -2.0,
            t * (t - 1.0) / 6.0,
        ]
    };
    assert_eq!(l.values(0.0), [1.0, 0.0, 0.0]);
    assert_eq!(l.values(1.0), [0.0, 1.0, 0.0]);
    assert_eq!(l.values(3.0), [0.0, 0.0, 1.0]);
    // at t = 2: (−1/3, 1, 1/3), the example of the strak-curves docs
    assert_eq!(l.values(2.0), [-1.0 / 3.0, 1.0, 1.0 / 3.0]);
    for k in 0..=12 {
        let t = f64::from(k) / 4.0;
        let v = l.values(t);
        let s = seed(t);
        for i in 0..3 {
            assert!(ulps(v[i], s[i]) <= 1.0, "L_{i}({t}) = {} vs {}", v[i], s[i]);
        }
    }
}

/// seeds/002: the Lagrange curve through `(1, 0), (−1, 0), (3, 3)` at the nodes `{0, 1, 3}`,
/// `c(t) = (1,0)ᵀ (t² − 4t + 3)/3 + (−1,0)ᵀ t(t − 3)/−2 + (3,3)ᵀ t(t − 1)/6`.
#[test]
fn seed002_lagrange_curve_nodes_0_1_3() {
    let l = LagrangeBasis::new([0.0, 1.0, 3.0]).unwrap();
    let q = [
        DVec2::new(1.0, 0.0),
        DVec2::new(-1.0, 0.0),
        DVec2::new(3.0, 3.0),
    ];
    let curve = |t: f64| -> DVec2 {
        let w = l.values(t);
        q[0] * w[0] + q[1] * w[1] + q[2] * w[2]
    };
    // interpolation: exactly the points at the nodes
    assert_eq!(curve(0.0), q[0]);
    assert_eq!(curve(1.0), q[1]);
    assert_eq!(curve(3.0), q[2]);
    // the seed's formula; multiplied out: x = (t² − 4t + 3)/3 + t(t − 3)/2 + t(t − 1)/2,
    // y = t(t − 1)/2 — both exactly 1 at t = 2 for y, −1/3 for x
    let seed = |t: f64| {
        DVec2::new(1.0, 0.0) * ((t * t - 4.0 * t + 3.0) / 3.0)
            + DVec2::new(-1.0, 0.0) * (t * (t - 3.0) / -2.0)
            + DVec2::new(3.0, 3.0) * (t * (t - 1.0) / 6.0)
    };
    let c2 = curve(2.0);
    assert_eq!(c2.y, 1.0);
    assert!(ulps(c2.x, -1.0 / 3.0) <= 1.0, "{}", c2.x);
    for k in 0..=12 {
        let t = f64::from(k) / 4.0;
        let (c, s) = (curve(t), seed(t));
        // three terms of ≤ 2 ulps each (see the basis test), summed: 8 ulps of the largest term
        // (≤ 3 · 3 = 9 here)
        assert!(
            (c - s).abs().max_element() <= 8.0 * 9.0 * f64::EPSILON,
            "t = {t}"
        );
    }
}

/// seeds/002 "Hermite-Basis" `H₀ = (1−t)²(1+2t)`, `H₁ = t(1−t)²`, `H₂ = −t²(1−t)`,
/// `H₃ = (3−2t)t²` at `t = 0, 1/2, 1`, and the interpolation conditions of seeds/003
/// (`dʳ/dtʳ H_{i,k}(t_j) = δ_ij δ_kr`).
#[test]
fn seed002_hermite_basis_values() {
    assert_eq!(basis::hermite(0.0_f64), [1.0, 0.0, 0.0, 0.0]);
    assert_eq!(basis::hermite(0.5_f64), [0.5, 0.125, -0.125, 0.5]);
    assert_eq!(basis::hermite(1.0_f64), [0.0, 0.0, 0.0, 1.0]);
    assert_eq!(basis::hermite_deriv(0.0_f64, 1), [0.0, 1.0, 0.0, 0.0]);
    assert_eq!(basis::hermite_deriv(1.0_f64, 1), [0.0, 0.0, 1.0, 0.0]);
    // the same values in fixed-point (all dyadic)
    let h = basis::hermite(I16F16::from_num(0.5));
    assert_eq!(h.map(|v| v.to_f64()), [0.5, 0.125, -0.125, 0.5]);
}

/// seeds/003 "Hermite-Matrix": `K = [[0,0,0,1],[1,1,1,1],[0,0,1,0],[3,2,1,0]]` and
/// `K⁻¹ = [[2,−2,1,1],[−3,3,−2,−1],[0,0,1,0],[1,0,0,0]]`; `Q(t) = [t³ t² t 1] K⁻¹ G` blends
/// `G = (P_r, P_{r+1}, P'_r, P'_{r+1})` with `(H₀, H₃, H₁, H₂)` of seeds/002.
#[test]
fn seed003_hermite_matrix_k_inverse() {
    let k_inv = [[2, -2, 1, 1], [-3, 3, -2, -1], [0, 0, 1, 0], [1, 0, 0, 0]];
    assert_eq!(basis::HERMITE_K_INV, k_inv);
    let kf: [[f64; 4]; 4] = basis::hermite_k_inv();
    assert_eq!(kf, k_inv.map(|r| r.map(f64::from)));
    let k = [[0, 0, 0, 1], [1, 1, 1, 1], [0, 0, 1, 0], [3, 2, 1, 0]];
    for (i, k_row) in k.iter().enumerate() {
        for j in 0..4 {
            let p: i32 = (0..4)
                .map(|m| k_row[m] * i32::from(basis::HERMITE_K_INV[m][j]))
                .sum();
            assert_eq!(p, i32::from(i == j), "K K⁻¹ = I at ({i}, {j})");
        }
    }
    for t in [0.0, 0.25, 0.5, 0.75, 1.0_f64] {
        let row = [t * t * t, t * t, t, 1.0];
        let blend: Vec<f64> = (0..4)
            .map(|j| (0..4).map(|i| row[i] * kf[i][j]).sum())
            .collect();
        let h = basis::hermite(t);
        assert_eq!(blend, [h[0], h[3], h[1], h[2]], "t = {t}");
    }
}

/// seeds/004 "Bézier-Kurve nach de Casteljau", "Berechne P(1/3)":
/// `P_{0,3}(1/3) = 2/3 · P_{0,2}(1/3) + 1/3 · P_{1,3}(1/3)`, recursively; equals the Bernstein
/// sum `Σ B_{i,3}(1/3) P_i = (8 P₀ + 12 P₁ + 6 P₂ + P₃)/27`.
///
/// The seed gives no coordinates; the points here are `(0,0), (1,3), (4,3), (5,0)` and the
/// seeds/000 coefficients `(2, −2, 5, 1)`. Replaying the seed's recursion with the same
/// operations (weights `1 − t` and `t` for the seed's `2/3` and `1/3`) gives the same bits;
/// the Bernstein sum and the exact rational values `(41/27, 2)` and `23/27` agree to 1 ulp
/// (`1/3` itself is rounded).
#[test]
fn seed004_de_casteljau_p_one_third() {
    let p = [
        DVec2::new(0.0, 0.0),
        DVec2::new(1.0, 3.0),
        DVec2::new(4.0, 3.0),
        DVec2::new(5.0, 0.0),
    ];
    let c = Bezier::new(p).unwrap();
    let t = 1.0 / 3.0;
    let got = c.eval(t);
    // the seed's recursion P_{i,r} = (1 − t) P_{i,r−1} + t P_{i+1,r−1}, level by level
    let step = |a: DVec2, b: DVec2| a * (1.0 - t) + b * t;
    let l1 = [step(p[0], p[1]), step(p[1], p[2]), step(p[2], p[3])];
    let l2 = [step(l1[0], l1[1]), step(l1[1], l1[2])];
    assert_eq!(got, step(l2[0], l2[1]));
    // the Bernstein sum with strak-curves' basis values
    let b = basis::bernstein_all::<f64, 4>(t);
    let sum = p[0] * b[0] + p[1] * b[1] + p[2] * b[2] + p[3] * b[3];
    assert!(
        ulps(got.x, sum.x) <= 1.0 && ulps(got.y, sum.y) <= 1.0,
        "{got} vs {sum}"
    );
    // the exact value (8 P₀ + 12 P₁ + 6 P₂ + P₃)/27 = (41/27, 54/27)
    assert!(ulps(got.x, 41.0 / 27.0) <= 1.0, "{}", got.x);
    assert!(ulps(got.y, 2.0) <= 1.0, "{}", got.y);
    // the seeds/000 polynomial: f(1/3) = 2 − 4 + 11/3 − 22/27 = 23/27
    let f = Bezier::new([[2.0], [-2.0], [5.0], [1.0]]).unwrap();
    assert!(ulps(f.eval(t)[0], 23.0 / 27.0) <= 1.0, "{}", f.eval(t)[0]);
}

/// seeds/004 "Rekursion nach de Casteljau" (`halbiere`): subdividing at `t = 1/2` gives
/// `bezier(P0, P01, P012, P0123)` and `bezier(P0123, P123, P23, P3)` of midpoints, exactly.
#[test]
fn seed004_halving_recursion() {
    let p = [
        DVec2::new(0.0, 0.0),
        DVec2::new(1.0, 3.0),
        DVec2::new(4.0, 3.0),
        DVec2::new(5.0, 0.0),
    ];
    let h = |a: DVec2, b: DVec2| DVec2::new((a.x + b.x) / 2.0, (a.y + b.y) / 2.0);
    let (p01, p12, p23) = (h(p[0], p[1]), h(p[1], p[2]), h(p[2], p[3]));
    let (p012, p123) = (h(p01, p12), h(p12, p23));
    let p0123 = h(p012, p123);
    let (l, r) = Bezier::new(p).unwrap().subdivide(0.5);
    assert_eq!(l.control_points(), &[p[0], p01, p012, p0123]);
    assert_eq!(r.control_points(), &[p0123, p123, p23, p[3]]);
}

/// seeds/004 "Eigenschaften der Bernstein-Polynome": maxima of `B_{i,n}` at `t = i/n` (the
/// derivative vanishes there), shown for `n = 4`.
#[test]
fn seed004_bernstein_maxima_at_i_over_n() {
    for i in 1..4 {
        let t = i as f64 / 4.0;
        assert_eq!(basis::bernstein_deriv_all::<f64, 5>(t)[i], 0.0, "i = {i}");
    }
}

/// seeds/004 "Approximation von Viertelkreis", "Bezier-Viertelkreis": Bézier points
/// `(0,1), (0.551897,1), (1,0.551897), (1,0)`; end points `(0,1)`, `(1,0)`; horizontal start
/// and vertical end tangent; the seed's `f₁, f₂`.
#[test]
fn seed004_quarter_circle_0_551897() {
    assert_eq!(QUARTER_CIRCLE_KAPPA, 0.551897);
    let k = QUARTER_CIRCLE_KAPPA;
    let c = Bezier::<DVec2, 4>::quarter_circle_seed().unwrap();
    assert_eq!(
        c.control_points(),
        &[
            DVec2::new(0.0, 1.0),
            DVec2::new(k, 1.0),
            DVec2::new(1.0, k),
            DVec2::new(1.0, 0.0)
        ]
    );
    assert_eq!(c.eval(0.0), DVec2::new(0.0, 1.0));
    assert_eq!(c.eval(1.0), DVec2::new(1.0, 0.0));
    // c'(0) = 3 (b₁ − b₀) = (3κ, 0), c'(1) = 3 (b₃ − b₂) = (0, −3κ): tangent to the circle
    assert_eq!(c.deriv(0.0, 1), DVec2::new(3.0 * k, 0.0));
    assert_eq!(c.deriv(1.0, 1), DVec2::new(0.0, -3.0 * k));
    // f₁(t) = 3t(1−t)²κ + 3t²(1−t) + t³, f₂(t) = (1−t)³ + 3t(1−t)² + 3t²(1−t)κ: a few roundings
    // on each side of values ≤ 1
    let f1 = |t: f64| 3.0 * t * (1.0 - t) * (1.0 - t) * k + 3.0 * t * t * (1.0 - t) + t * t * t;
    let f2 = |t: f64| {
        (1.0 - t) * (1.0 - t) * (1.0 - t)
            + 3.0 * t * (1.0 - t) * (1.0 - t)
            + 3.0 * t * t * (1.0 - t) * k
    };
    for j in 0..=16 {
        let t = f64::from(j) / 16.0;
        let p = c.eval(t);
        assert!((p.x - f1(t)).abs() <= 8.0 * f64::EPSILON, "t = {t}");
        assert!((p.y - f2(t)).abs() <= 8.0 * f64::EPSILON, "t = {t}");
    }
}

/// seeds/004: the radial error of the `0.551897` quarter circle is `2.0564·10⁻⁴`, attained at
/// `t = 1/2` (inside the circle). The seed's `P(0.5) = (cos 45°, sin 45°)` holds only for
/// `κ = 4/3 (√2 − 1)`, whose maximal radial error is `2.7253·10⁻⁴` (at `t = 1/2 ± √3/6`).
#[test]
fn seed004_quarter_circle_radial_errors() {
    let c = Bezier::<DVec2, 4>::quarter_circle(QUARTER_CIRCLE_KAPPA).unwrap();
    let at_half = 1.0 - c.eval(0.5).length();
    assert!((at_half - 2.0564e-4).abs() <= 1e-8, "{at_half}");
    let e = quarter_circle_radial_error(QUARTER_CIRCLE_KAPPA);
    assert!((e - 2.0564e-4).abs() <= 1e-8, "{e}");
    // the maximum is at t = 1/2 (the search evaluates the curve by its own Bernstein sum)
    assert!((e - at_half).abs() <= 1e-15, "{e} vs {at_half}");
    // with 0.551897 the midpoint is off (cos 45°, sin 45°) by 1.5·10⁻⁴ per coordinate
    let off = c.eval(0.5).x - std::f64::consts::FRAC_1_SQRT_2;
    assert!((off + 1.454e-4).abs() <= 1e-6, "{off}");

    // κ = 4/3 (√2 − 1): P(1/2) = (3κ + 4)/8 (1, 1) = (cos 45°, sin 45°) up to rounding
    assert!(
        ulps(
            QUARTER_CIRCLE_KAPPA_MIDPOINT,
            4.0 / 3.0 * (2f64.sqrt() - 1.0)
        ) <= 1.0
    );
    let m = Bezier::<DVec2, 4>::quarter_circle(QUARTER_CIRCLE_KAPPA_MIDPOINT).unwrap();
    let p = m.eval(0.5);
    let (cos45, sin45) = (45f64.to_radians().cos(), 45f64.to_radians().sin());
    // de Casteljau at t = 1/2 halves exactly; the sums round: ≤ 1 ulp
    assert!(ulps(p.x, cos45) <= 1.0 && ulps(p.y, sin45) <= 1.0, "{p}");
    let e = quarter_circle_radial_error(QUARTER_CIRCLE_KAPPA_MIDPOINT);
    assert!((e - 2.7253e-4).abs() <= 1e-8, "{e}");
    let t = 0.5 - 3f64.sqrt() / 6.0;
    assert!((m.eval(t).length() - 1.0 - e).abs() <= 1e-12);
}
