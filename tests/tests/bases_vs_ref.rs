//! Property tests: strak-curves' `basis` module (monomial/Horner, Bernstein, basis-change
//! matrices and conversions, Lagrange, Hermite) against strak-ref's textbook formulas, in f64,
//! f32, I16F16 and I32F32, plus the Bernstein invariants of seeds/000 and 004 (partition of
//! unity, non-negativity, symmetry, derivative formula).
//!
//! # Tolerances
//! One rounding unit of a value of magnitude `m` is `EPSILON · m` for floats and `EPSILON`
//! (absolute) for fixed-point, plus `f64::EPSILON · m` for the reference (see [`unit`]). Every
//! tolerance is a small multiple of the algorithm's error bound, derived next to it.
//!
//! Each property prints its largest measured error and error/tolerance ratio
//! (`cargo test -p strak-tests --test bases_vs_ref -- --nocapture`).

use glam::{DVec2, DVec3, Vec2, Vec3};
use proptest::prelude::*;
use proptest::test_runner::{TestCaseError, TestCaseResult};
use strak_curves::basis::{self, LagrangeBasis, MonomialCurve};
use strak_curves::{Error, I16F16, I32F32, ParamCurve, ParamCurveDeriv, Point, Scalar};
use strak_tests::{Stats, ensure, max_diff, pt, run, to_vec};

/// Cases per property (each case covers all degrees).
const CASES: u32 = 64;

// ---------------------------------------------------------------------------------------------
// Infrastructure (the harness `run`/`Stats`/`ensure` is shared in strak_tests)

/// One rounding unit of a value of magnitude `m` in `S`, plus the reference's own `f64` unit.
fn unit<S: Scalar>(m: f64) -> f64 {
    let own = if S::IS_FIXED {
        S::EPSILON
    } else {
        S::EPSILON * m
    };
    own + f64::EPSILON * m
}

/// `v` rounded to `S`, and its exact value.
fn round<S: Scalar>(v: f64) -> (S, f64) {
    let s = S::from_f64(v).expect("value in range");
    (s, s.to_f64())
}

/// The falling factorial `n (n − 1) ⋯ (n − k + 1)` (0 for `k > n`).
fn ff(n: usize, k: usize) -> f64 {
    if k > n {
        return 0.0;
    }
    (0..k).map(|m| (n - m) as f64).product()
}

/// Applies `f::<S, N>` for `N = 1..=9` (degrees 0..=8).
macro_rules! sizes {
    ($f:ident, $s:ty, $($arg:expr),*) => {{
        $f::<$s, 1>($($arg),*)?;
        $f::<$s, 2>($($arg),*)?;
        $f::<$s, 3>($($arg),*)?;
        $f::<$s, 4>($($arg),*)?;
        $f::<$s, 5>($($arg),*)?;
        $f::<$s, 6>($($arg),*)?;
        $f::<$s, 7>($($arg),*)?;
        $f::<$s, 8>($($arg),*)?;
        $f::<$s, 9>($($arg),*)?;
    }};
}

/// Applies `f::<S, N, N − 1>` for `N = 2..=9` (degrees 1..=8).
macro_rules! sizes2 {
    ($f:ident, $s:ty, $($arg:expr),*) => {{
        $f::<$s, 2, 1>($($arg),*)?;
        $f::<$s, 3, 2>($($arg),*)?;
        $f::<$s, 4, 3>($($arg),*)?;
        $f::<$s, 5, 4>($($arg),*)?;
        $f::<$s, 6, 5>($($arg),*)?;
        $f::<$s, 7, 6>($($arg),*)?;
        $f::<$s, 8, 7>($($arg),*)?;
        $f::<$s, 9, 8>($($arg),*)?;
    }};
}

// ---------------------------------------------------------------------------------------------
// Monomial basis and Horner

/// `horner` against the naive power sum `strak_ref::poly_eval` (seeds/000 "Effiziente
/// Auswertung"). Fixed-point: coefficients in [-100, 100] and `|t| ≤ 1`, so every partial
/// Horner sum stays below 900 (horner has no range check of its own).
fn check_horner<S: Scalar>((coeffs, t): &(Vec<f64>, f64), stats: &Stats) -> TestCaseResult {
    let a: Vec<S> = coeffs.iter().map(|&c| round::<S>(c).0).collect();
    let af: Vec<f64> = a.iter().map(|c| c.to_f64()).collect();
    let t = if S::IS_FIXED { t.clamp(-1.0, 1.0) } else { *t };
    let (ts, tf) = round::<S>(t);
    let got = basis::horner(&a, ts).to_f64();
    let want = strak_ref::poly_eval(&af, tf);
    let g = af.len() - 1;
    // Horner and the power sum both err by ≤ 2g roundings of Σ |a_i| |t|ⁱ (floats); fixed-point
    // truncates g products, each error ≤ 1 unit and damped by |t| ≤ 1; factor 2 slack
    let size: f64 = af
        .iter()
        .enumerate()
        .map(|(i, c)| c.abs() * tf.abs().powi(i as i32))
        .sum();
    let tol = 4.0 * (g + 1) as f64 * unit::<S>(size);
    stats.check((got - want).abs(), tol, || format!("degree {g}, t = {tf}"))
}

/// `horner_points` against `poly_eval` per coordinate.
fn check_horner_points<P: Point>(
    (coeffs, t): &(Vec<Vec<f64>>, f64),
    stats: &Stats,
) -> TestCaseResult {
    let a: Vec<P> = coeffs
        .iter()
        .map(|c| pt(&c.iter().take(P::DIM).copied().collect::<Vec<_>>()))
        .collect();
    let t = if P::Scalar::IS_FIXED {
        t.clamp(-1.0, 1.0)
    } else {
        *t
    };
    let (ts, tf) = round::<P::Scalar>(t);
    let got = to_vec(basis::horner_points(&a, ts));
    let g = a.len() - 1;
    for (d, &gd) in got.iter().enumerate() {
        let ad: Vec<f64> = a.iter().map(|p| p.coord(d).to_f64()).collect();
        let want = strak_ref::poly_eval(&ad, tf);
        let size: f64 = ad
            .iter()
            .enumerate()
            .map(|(i, c)| c.abs() * tf.abs().powi(i as i32))
            .sum();
        // as in check_horner
        let tol = 4.0 * (g + 1) as f64 * unit::<P::Scalar>(size);
        stats.check((gd - want).abs(), tol, || {
            format!("degree {g}, coordinate {d}, t = {tf}")
        })?;
    }
    Ok(())
}

/// `monomials` is `(1, t, …, t^g)` with `t` clamped to `[0, 1]`.
fn check_monomials<S: Scalar, const N: usize>(t: f64, stats: &Stats) -> TestCaseResult {
    let (ts, tf) = round::<S>(t);
    let m = basis::monomials::<S, N>(ts);
    let tc = tf.clamp(0.0, 1.0);
    for (i, v) in m.iter().enumerate() {
        // i − 1 rounded products of numbers in [0, 1]
        let tol = (i as f64).max(1.0) * unit::<S>(1.0);
        stats.check((v.to_f64() - tc.powi(i as i32)).abs(), tol, || {
            format!("t^{i}, t = {tf}")
        })?;
    }
    Ok(())
}

/// `MonomialCurve::with_domain` evaluates `Σ a_i uⁱ` and its derivatives like
/// `strak_ref::Poly::nth_derivative`, `u` clamped to the domain.
fn check_monomial_curve<P: Point, const N: usize>(
    (unit_coeffs, u0, len, us): &(Vec<Vec<f64>>, f64, f64, Vec<f64>),
    stats: &Stats,
) -> TestCaseResult {
    let g = N - 1;
    let (u0s, u0f) = round::<P::Scalar>(*u0);
    let (u1s, u1f) = round::<P::Scalar>(u0 + len);
    let r = u0f.abs().max(u1f.abs());
    // the constructor's bound: Σ_{i≥k} |a_i| i!/(i−k)! R^(i−k) for every k; scale the unit
    // coefficients so that it fits (and at most 100)
    let worst = (0..=g)
        .map(|k| {
            (k..=g)
                .map(|i| ff(i, k) * r.powi((i - k) as i32))
                .sum::<f64>()
        })
        .fold(1.0, f64::max);
    let scale = (0.9 * P::Scalar::LIMIT / worst).min(100.0);
    let coeffs: [P; N] = std::array::from_fn(|i| {
        let c: Vec<f64> = unit_coeffs[i]
            .iter()
            .take(P::DIM)
            .map(|v| v * scale)
            .collect();
        pt(&c)
    });
    let c = MonomialCurve::with_domain(coeffs, u0s, u1s)
        .map_err(|e| TestCaseError::fail(format!("with_domain: {e:?}")))?;
    ensure(c.domain() == (u0s, u1s), || "domain".into())?;
    for &u in us {
        let (us_, uf) = round::<P::Scalar>(u0f - 0.5 + u * (len + 1.0));
        let uc = uf.clamp(u0f, u1f);
        for k in 0..=g + 1 {
            let got = to_vec(c.deriv(us_, k));
            for (d, &gd) in got.iter().enumerate() {
                let ad: Vec<f64> = coeffs.iter().map(|p| p.coord(d).to_f64()).collect();
                let want = strak_ref::Poly::new(ad.clone()).nth_derivative(k).eval(uc);
                // Horner on partial sums ≤ H = Σ |a_i| i!/(i−k)! |u|^(i−k): ≤ 1 rounding per
                // step (g steps), relative for floats; fixed-point's absolute step errors (and
                // the coefficient rounding) are amplified like the terms, by Σ i!/(i−k)!
                // |u|^(i−k); the reference's expanded polynomial errs like floats; slack 2
                let weight = |i: usize| ff(i, k) * uc.abs().powi((i - k) as i32);
                let h: f64 = (k..=g).map(|i| ad[i].abs() * weight(i)).sum();
                let own = if P::Scalar::IS_FIXED {
                    (k..=g).map(weight).sum::<f64>()
                } else {
                    h
                };
                let tol = 4.0 * (g + 1) as f64 * (P::Scalar::EPSILON * own + f64::EPSILON * h);
                stats.check((gd - want).abs(), tol, || {
                    format!("degree {g}, k = {k}, u = {uf}, coordinate {d}")
                })?;
            }
        }
        ensure(c.eval(us_) == c.deriv(us_, 0), || {
            "eval ≠ deriv(·, 0)".into()
        })?;
    }
    Ok(())
}

/// Coefficients in `[-100, 100]` (1 to 9 of them) and a parameter in `[-2, 2]`.
fn coeffs_and_param() -> impl Strategy<Value = (Vec<f64>, f64)> {
    (
        prop::collection::vec(-100.0..100.0_f64, 1..=9),
        -2.0..2.0_f64,
    )
}

/// Point coefficients (1 to 9, three coordinates in `[-100, 100]`) and a parameter.
fn point_coeffs_and_param() -> impl Strategy<Value = (Vec<Vec<f64>>, f64)> {
    (strak_tests::points(1..=9, 3, 100.0), -2.0..2.0_f64)
}

/// Unit coefficients, a domain start in `[-2, 2]`, a length in `[0.25, 2]` and parameters.
type MonomialInput = (Vec<Vec<f64>>, f64, f64, Vec<f64>);

fn monomial_curve_input() -> impl Strategy<Value = MonomialInput> {
    (
        strak_tests::points(9..=9, 3, 1.0),
        -2.0..2.0_f64,
        0.25..2.0_f64,
        prop::collection::vec(0.0..1.0_f64, 5),
    )
}

#[test]
fn horner_matches_power_sum() {
    run("horner f64", CASES, coeffs_and_param(), |i, st| {
        check_horner::<f64>(&i, st)
    });
    run("horner f32", CASES, coeffs_and_param(), |i, st| {
        check_horner::<f32>(&i, st)
    });
    run("horner I16F16", CASES, coeffs_and_param(), |i, st| {
        check_horner::<I16F16>(&i, st)
    });
    run("horner I32F32", CASES, coeffs_and_param(), |i, st| {
        check_horner::<I32F32>(&i, st)
    });
    assert_eq!(basis::horner::<f64>(&[], 3.0), 0.0);
    assert_eq!(basis::horner_points::<DVec2>(&[], 3.0), DVec2::ZERO);
}

#[test]
fn horner_points_matches_power_sum() {
    let s = point_coeffs_and_param;
    run("horner_points [f64; 3]", CASES, s(), |i, st| {
        check_horner_points::<[f64; 3]>(&i, st)
    });
    run("horner_points DVec2", CASES, s(), |i, st| {
        check_horner_points::<DVec2>(&i, st)
    });
    run("horner_points DVec3", CASES, s(), |i, st| {
        check_horner_points::<DVec3>(&i, st)
    });
    run("horner_points Vec2", CASES, s(), |i, st| {
        check_horner_points::<Vec2>(&i, st)
    });
    run("horner_points Vec3", CASES, s(), |i, st| {
        check_horner_points::<Vec3>(&i, st)
    });
    run("horner_points [f32; 2]", CASES, s(), |i, st| {
        check_horner_points::<[f32; 2]>(&i, st)
    });
    run("horner_points [I16F16; 2]", CASES, s(), |i, st| {
        check_horner_points::<[I16F16; 2]>(&i, st)
    });
    run("horner_points [I32F32; 3]", CASES, s(), |i, st| {
        check_horner_points::<[I32F32; 3]>(&i, st)
    });
}

#[test]
fn monomials_are_clamped_powers() {
    let s = || -0.5..1.5_f64;
    run("monomials f64", CASES, s(), |t, st| {
        sizes!(check_monomials, f64, t, st);
        Ok(())
    });
    run("monomials f32", CASES, s(), |t, st| {
        sizes!(check_monomials, f32, t, st);
        Ok(())
    });
    run("monomials I16F16", CASES, s(), |t, st| {
        sizes!(check_monomials, I16F16, t, st);
        Ok(())
    });
    run("monomials I32F32", CASES, s(), |t, st| {
        sizes!(check_monomials, I32F32, t, st);
        Ok(())
    });
}

#[test]
fn monomial_curve_matches_reference_polynomial() {
    let s = monomial_curve_input;
    run("MonomialCurve [f64; 2]", CASES, s(), |i, st| {
        sizes!(check_monomial_curve, [f64; 2], &i, st);
        Ok(())
    });
    run("MonomialCurve DVec3", CASES, s(), |i, st| {
        sizes!(check_monomial_curve, DVec3, &i, st);
        Ok(())
    });
    run("MonomialCurve Vec2", CASES, s(), |i, st| {
        sizes!(check_monomial_curve, Vec2, &i, st);
        Ok(())
    });
    run("MonomialCurve [I16F16; 2]", CASES, s(), |i, st| {
        sizes!(check_monomial_curve, [I16F16; 2], &i, st);
        Ok(())
    });
    run("MonomialCurve [I32F32; 3]", CASES, s(), |i, st| {
        sizes!(check_monomial_curve, [I32F32; 3], &i, st);
        Ok(())
    });
}

// ---------------------------------------------------------------------------------------------
// Bernstein basis

/// Bernstein values and first derivatives against the binomial formula of strak-ref
/// (`C(g,i) (1−t)^{g−i} tⁱ` and the seeds/004 derivative rule), `t` clamped to `[0, 1]`; plus
/// partition of unity, non-negativity and `bernstein(i, t) = bernstein_all(t)[i]`.
fn check_bernstein<S: Scalar, const N: usize>(t: f64, stats: &Stats) -> TestCaseResult {
    let g = N - 1;
    let (ts, tf) = round::<S>(t);
    let tc = tf.clamp(0.0, 1.0);
    let b = basis::bernstein_all::<S, N>(ts);
    let db = basis::bernstein_deriv_all::<S, N>(ts);
    let mut sum = 0.0;
    for i in 0..N {
        let v = b[i].to_f64();
        // the triangle: g levels of convex combinations of values in [0, 1], ≤ 2 units each;
        // the reference multiplies g + 1 factors (≤ g + 1 roundings); slack 2
        let tol = 4.0 * (g + 1) as f64 * unit::<S>(1.0);
        stats.check((v - strak_ref::bernstein(i, g, tc)).abs(), tol, || {
            format!("B_{i}^{g}({tf})")
        })?;
        // g × (difference of two degree-(g−1) values, each within the bound above)
        let tol = 8.0 * (g * g) as f64 * unit::<S>(1.0);
        let want = strak_ref::bernstein_deriv(i, g, tc, 1);
        stats.check((db[i].to_f64() - want).abs(), tol, || {
            format!("d/dt B_{i}^{g}({tf})")
        })?;
        ensure(v >= 0.0, || format!("B_{i}^{g}({tf}) = {v} < 0"))?;
        ensure(basis::bernstein::<S, N>(i, ts) == b[i], || {
            format!("bernstein({i}) ≠ bernstein_all[{i}]")
        })?;
        // closed form in f64: g + 1 roundings on each side
        let tol = 4.0 * (g + 1) as f64 * f64::EPSILON;
        stats.check(
            (basis::bernstein_f64(g, i, tc) - strak_ref::bernstein(i, g, tc)).abs(),
            tol,
            || format!("bernstein_f64({g}, {i}, {tc})"),
        )?;
        sum += v;
    }
    ensure(basis::bernstein::<S, N>(N, ts) == S::ZERO, || {
        "i > g".into()
    })?;
    // partition of unity (seeds/004 "Σ B_{i,n}(t) = 1"): every level of the triangle loses
    // ≤ 2 units per entry, (g + 1)(g + 2) units in all; plus the f64 summation
    let tol = ((g + 1) * (g + 2)) as f64 * unit::<S>(1.0) + N as f64 * f64::EPSILON;
    stats.check((sum - 1.0).abs(), tol, || {
        format!("Σ B_i^{g}({tf}) = {sum}")
    })
}

/// Symmetry `B_{i,n}(t) = B_{n−i,n}(1 − t)` (seeds/004), bit for bit: `1 − t` is exact for
/// fixed-point and, for floats, when `t ∈ [1/2, 1]`, and the triangle then runs the same
/// products mirrored.
fn check_symmetry<S: Scalar, const N: usize>(t: f64, _stats: &Stats) -> TestCaseResult {
    let t = t.clamp(0.0, 1.0);
    let t = if S::IS_FIXED { t } else { t.max(1.0 - t) };
    let (ts, tf) = round::<S>(t);
    let b = basis::bernstein_all::<S, N>(ts);
    let r = basis::bernstein_all::<S, N>(S::ONE - ts);
    for i in 0..N {
        ensure(b[i] == r[N - 1 - i], || {
            format!(
                "B_{i}({tf}) = {:?} ≠ B_(n−i)(1 − t) = {:?}",
                b[i],
                r[N - 1 - i]
            )
        })?;
    }
    Ok(())
}

/// The derivative formula `dB_{i,n}/dt = n (B_{i−1,n−1}(t) − B_{i,n−1}(t))` (seeds/004),
/// exactly: `bernstein_deriv_all` against `bernstein_all` of degree `n − 1` (`M = N − 1`).
fn check_deriv_formula<S: Scalar, const N: usize, const M: usize>(
    t: f64,
    _stats: &Stats,
) -> TestCaseResult {
    let (ts, tf) = round::<S>(t);
    let d = basis::bernstein_deriv_all::<S, N>(ts);
    let low = basis::bernstein_all::<S, M>(ts);
    let n = S::from_i16(M as i16);
    for i in 0..N {
        let prev = if i == 0 { S::ZERO } else { low[i - 1] };
        let cur = low.get(i).copied().unwrap_or(S::ZERO);
        ensure(d[i] == n * (prev - cur), || {
            format!("dB_{i},{M}({tf}): {:?} ≠ {:?}", d[i], n * (prev - cur))
        })?;
    }
    Ok(())
}

#[test]
fn bernstein_matches_binomial_formula() {
    let s = || -0.5..1.5_f64;
    run("bernstein f64", CASES, s(), |t, st| {
        sizes!(check_bernstein, f64, t, st);
        Ok(())
    });
    run("bernstein f32", CASES, s(), |t, st| {
        sizes!(check_bernstein, f32, t, st);
        Ok(())
    });
    run("bernstein I16F16", CASES, s(), |t, st| {
        sizes!(check_bernstein, I16F16, t, st);
        Ok(())
    });
    run("bernstein I32F32", CASES, s(), |t, st| {
        sizes!(check_bernstein, I32F32, t, st);
        Ok(())
    });
}

#[test]
fn bernstein_symmetry_is_exact() {
    let s = || 0.0..1.0_f64;
    run("symmetry f64", CASES, s(), |t, st| {
        sizes!(check_symmetry, f64, t, st);
        Ok(())
    });
    run("symmetry f32", CASES, s(), |t, st| {
        sizes!(check_symmetry, f32, t, st);
        Ok(())
    });
    run("symmetry I16F16", CASES, s(), |t, st| {
        sizes!(check_symmetry, I16F16, t, st);
        Ok(())
    });
    run("symmetry I32F32", CASES, s(), |t, st| {
        sizes!(check_symmetry, I32F32, t, st);
        Ok(())
    });
}

#[test]
fn bernstein_derivative_formula_is_exact() {
    let s = || -0.5..1.5_f64;
    run("deriv formula f64", CASES, s(), |t, st| {
        sizes2!(check_deriv_formula, f64, t, st);
        Ok(())
    });
    run("deriv formula f32", CASES, s(), |t, st| {
        sizes2!(check_deriv_formula, f32, t, st);
        Ok(())
    });
    run("deriv formula I16F16", CASES, s(), |t, st| {
        sizes2!(check_deriv_formula, I16F16, t, st);
        Ok(())
    });
    run("deriv formula I32F32", CASES, s(), |t, st| {
        sizes2!(check_deriv_formula, I32F32, t, st);
        Ok(())
    });
}

#[test]
fn binomials_match_factorial_formula() {
    // strak-ref's n!/(k!(n−k)!) in f64 is exact while n! < 2⁵³ (n ≤ 18)
    for n in 0..=18_u32 {
        for k in 0..=n + 1 {
            let want = strak_ref::binomial(n, k);
            assert_eq!(
                basis::binomial(n as usize, k as usize).map(|v| v as f64),
                Some(want),
                "C({n}, {k})"
            );
        }
    }
    fn row<const N: usize>() {
        let row = basis::pascal_row::<N>().expect("no overflow");
        for (k, &c) in row.iter().enumerate() {
            assert_eq!(basis::binomial(N - 1, k), Some(c), "C({}, {k})", N - 1);
        }
    }
    row::<1>();
    row::<2>();
    row::<9>();
    row::<30>();
    row::<68>();
}

// ---------------------------------------------------------------------------------------------
// Basis-change matrices and conversions

/// `T_{M←B}` and `A_{B←M}` equal strak-ref's (integer entries: exactly, in every type);
/// `T_{B←M}` equals strak-ref's inverted `(A_{B←M}ᵀ)⁻¹` to rounding.
fn check_matrices<S: Scalar, const N: usize>(stats: &Stats) -> TestCaseResult {
    let g = N - 1;
    let to_f = |m: [[S; N]; N]| -> Vec<Vec<f64>> {
        m.iter()
            .map(|r| r.iter().map(|v| v.to_f64()).collect())
            .collect()
    };
    let tmb = to_f(basis::bernstein_to_monomial_matrix::<S, N>().expect("fits"));
    ensure(tmb == strak_ref::t_monomial_from_bernstein(g), || {
        format!("T_(M←B), degree {g}")
    })?;
    let a = to_f(basis::bernstein_basis_matrix::<S, N>().expect("fits"));
    ensure(a == strak_ref::a_bernstein_from_monomial(g), || {
        format!("A_(B←M), degree {g}")
    })?;
    let tbm = to_f(basis::monomial_to_bernstein_matrix::<S, N>().expect("fits"));
    let want = strak_ref::t_bernstein_from_monomial(g);
    for (r, w) in tbm.iter().zip(&want) {
        // entries in [0, 1] rounded once (½ unit); the reference's Gauss–Jordan inversion of a
        // triangular integer matrix with entries ≤ 70 errs by a few f64 units
        let tol = 0.5 * unit::<S>(1.0) + 64.0 * f64::EPSILON;
        stats.check(max_diff(r, w), tol, || format!("T_(B←M), degree {g}"))?;
    }
    // T_{M←B} T_{B←M} = I (in f64, from the S matrices)
    let prod = strak_ref::mat_mul(&tmb, &tbm);
    for (i, r) in prod.iter().enumerate() {
        let e: Vec<f64> = (0..N).map(|j| if i == j { 1.0 } else { 0.0 }).collect();
        // row i of T_{M←B} has Σ|entries| ≤ 2^g C(g, i) ≤ 2^8 · 70: times ½ unit each
        let tol = 0.5 * 256.0 * 70.0 * unit::<S>(1.0);
        stats.check(max_diff(r, &e), tol, || format!("T T⁻¹ = I, degree {g}"))?;
    }
    Ok(())
}

#[test]
fn basis_change_matrices_match_reference() {
    fn all<S: Scalar>(name: &str) {
        let stats = Stats::default();
        let check = || -> TestCaseResult {
            sizes!(check_matrices, S, &stats);
            Ok(())
        };
        if let Err(e) = check() {
            panic!("{name}: {e}");
        }
        eprintln!(
            "{name}: max error {:.3e}, max error/tolerance {:.3}",
            stats.err.get(),
            stats.ratio.get()
        );
    }
    all::<f64>("matrices f64");
    all::<f32>("matrices f32");
    all::<I16F16>("matrices I16F16");
    all::<I32F32>("matrices I32F32");
}

/// `bernstein_to_monomial` / `monomial_to_bernstein` of random points against strak-ref's
/// `monomial_from_bernstein` / `bernstein_from_monomial`, coordinate-wise, and the round trip.
fn check_conversion<P: Point, const N: usize>(
    unit_points: &[Vec<f64>],
    stats: &Stats,
) -> TestCaseResult {
    let g = N - 1;
    // |a_j| = C(g, j) |Δʲ b_0| ≤ C(g, j) 2ʲ max|b| ≤ 3^g max|b|: fits fixed-point
    let three_g = 3f64.powi(g as i32);
    let scale = (0.9 * P::Scalar::LIMIT / three_g).min(100.0);
    let b: [P; N] = std::array::from_fn(|i| {
        pt(&unit_points[i]
            .iter()
            .take(P::DIM)
            .map(|v| v * scale)
            .collect::<Vec<_>>())
    });
    let a = basis::bernstein_to_monomial(&b)
        .map_err(|e| TestCaseError::fail(format!("bernstein_to_monomial: {e:?}")))?;
    let a_m = basis::monomial_to_bernstein(&b)
        .map_err(|e| TestCaseError::fail(format!("monomial_to_bernstein: {e:?}")))?;
    let back = basis::monomial_to_bernstein(&a)
        .map_err(|e| TestCaseError::fail(format!("round trip: {e:?}")))?;
    for d in 0..P::DIM {
        let bd: Vec<f64> = b.iter().map(|p| p.coord(d).to_f64()).collect();
        let m = bd.iter().fold(1e-300_f64, |m, v| m.max(v.abs()));
        let want = strak_ref::monomial_from_bernstein(&bd);
        let got: Vec<f64> = a.iter().map(|p| p.coord(d).to_f64()).collect();
        // f64 sums of g + 1 integer-weighted terms ≤ 3^g m (both sides), rounded once to S
        let tol =
            unit::<P::Scalar>(three_g * m) + 4.0 * (g + 1) as f64 * f64::EPSILON * three_g * m;
        stats.check(max_diff(&got, &want), tol, || {
            format!("B→M degree {g}, coordinate {d}")
        })?;
        // b treated as monomial coefficients: T_{B←M} entries in [0, 1], rows sum to ≤ g + 1;
        // the reference's inverted matrix errs by a few f64 units per entry
        let want = strak_ref::bernstein_from_monomial(&bd);
        let got: Vec<f64> = a_m.iter().map(|p| p.coord(d).to_f64()).collect();
        let size = (g + 1) as f64 * m;
        let tol = unit::<P::Scalar>(size) + 64.0 * (g + 1) as f64 * f64::EPSILON * size;
        stats.check(max_diff(&got, &want), tol, || {
            format!("M→B degree {g}, coordinate {d}")
        })?;
        // round trip: a carries ½ unit of 3^g m per entry, mapped by rows summing to ≤ g + 1
        let got: Vec<f64> = back.iter().map(|p| p.coord(d).to_f64()).collect();
        let tol = (g + 2) as f64 * unit::<P::Scalar>(three_g * m);
        stats.check(max_diff(&got, &bd), tol, || {
            format!("round trip degree {g}, coordinate {d}")
        })?;
    }
    Ok(())
}

#[test]
fn point_conversions_match_reference() {
    let s = || strak_tests::points(9..=9, 3, 1.0);
    run("conversion [f64; 2]", CASES, s(), |p, st| {
        sizes!(check_conversion, [f64; 2], &p, st);
        Ok(())
    });
    run("conversion DVec3", CASES, s(), |p, st| {
        sizes!(check_conversion, DVec3, &p, st);
        Ok(())
    });
    run("conversion Vec3", CASES, s(), |p, st| {
        sizes!(check_conversion, Vec3, &p, st);
        Ok(())
    });
    run("conversion [f32; 2]", CASES, s(), |p, st| {
        sizes!(check_conversion, [f32; 2], &p, st);
        Ok(())
    });
    run("conversion [I16F16; 2]", CASES, s(), |p, st| {
        sizes!(check_conversion, [I16F16; 2], &p, st);
        Ok(())
    });
    run("conversion [I32F32; 3]", CASES, s(), |p, st| {
        sizes!(check_conversion, [I32F32; 3], &p, st);
        Ok(())
    });
}

// ---------------------------------------------------------------------------------------------
// Lagrange basis

/// `LagrangeBasis` against strak-ref's product formula `Π_{k≠i} (t − u_k)/(u_i − u_k)`
/// (seeds/000), `t` clamped to `[u_0, u_g]`; the Kronecker property `L_i(u_j) = δ_ij` exactly;
/// partition of unity. Fixed-point may reject the nodes with `OutOfRange` exactly when the
/// documented bound `Π_{k≠i} max(1, span_k / |u_i − u_k|)` does not fit.
fn check_lagrange<S: Scalar, const N: usize>(
    (start, gaps, ts): &(f64, Vec<f64>, Vec<f64>),
    stats: &Stats,
) -> TestCaseResult {
    let g = N - 1;
    let mut u = vec![*start];
    for gap in gaps.iter().take(g) {
        u.push(u[u.len() - 1] + gap);
    }
    let nodes: [S; N] = std::array::from_fn(|i| round::<S>(u[i]).0);
    let uf: Vec<f64> = nodes.iter().map(|v| v.to_f64()).collect();
    let (first, last) = (uf[0], uf[g]);
    let bound = (0..N)
        .map(|i| {
            (0..N)
                .filter(|&k| k != i)
                .map(|k| {
                    let span = (first - uf[k]).abs().max((last - uf[k]).abs());
                    (span / (uf[i] - uf[k]).abs()).max(1.0)
                })
                .product::<f64>()
        })
        .fold(1.0, f64::max);
    let l = match LagrangeBasis::new(nodes) {
        Ok(l) => l,
        Err(Error::OutOfRange) if !S::fits(bound) => return Ok(()),
        Err(e) => return Err(TestCaseError::fail(format!("new: {e:?}, bound {bound}"))),
    };
    ensure(S::fits(bound), || {
        format!("accepted nodes with bound {bound}")
    })?;
    ensure(
        l.degree() == g && l.domain() == (nodes[0], nodes[g]),
        || "degree/domain".into(),
    )?;
    for (j, &uj) in nodes.iter().enumerate() {
        let v = l.values(uj);
        for (i, vi) in v.iter().enumerate() {
            let want = if i == j { S::ONE } else { S::ZERO };
            ensure(*vi == want, || format!("L_{i}(u_{j}) = {vi:?}"))?;
        }
    }
    for &t in ts {
        let (ts_, tf) = round::<S>(first - 1.0 + t * (last - first + 2.0));
        let tc = tf.clamp(first, last);
        let v = l.values(ts_);
        let mut sum = 0.0;
        for (i, vi) in v.iter().enumerate() {
            let want = strak_ref::lagrange_basis(&uf, i, tc);
            // g factors, each a rounded quotient (≤ 1 unit relative to the partial product
            // ≤ bound, also in fixed-point) and a rounded product; slack 2
            let tol = 4.0 * (g + 1) as f64 * (S::EPSILON + f64::EPSILON) * bound;
            stats.check((vi.to_f64() - want).abs(), tol, || {
                format!("L_{i}^{g}({tf}), nodes {uf:?}")
            })?;
            ensure(l.value(i, ts_) == *vi, || "value ≠ values".into())?;
            sum += vi.to_f64();
        }
        ensure(l.value(N, ts_) == S::ZERO, || "i > g".into())?;
        // seeds/000 "affin invariant": Σ L_i = 1, each value within the bound above
        let tol = 4.0 * ((g + 1) * (g + 1)) as f64 * (S::EPSILON + f64::EPSILON) * bound;
        stats.check((sum - 1.0).abs(), tol, || format!("Σ L_i({tf}) = {sum}"))?;
    }
    Ok(())
}

#[test]
fn lagrange_basis_matches_product_formula() {
    let s = || {
        (
            -5.0..5.0_f64,
            prop::collection::vec(0.25..2.0_f64, 8),
            prop::collection::vec(0.0..1.0_f64, 6),
        )
    };
    run("lagrange f64", CASES, s(), |i, st| {
        sizes!(check_lagrange, f64, &i, st);
        Ok(())
    });
    run("lagrange f32", CASES, s(), |i, st| {
        sizes!(check_lagrange, f32, &i, st);
        Ok(())
    });
    run("lagrange I16F16", CASES, s(), |i, st| {
        sizes!(check_lagrange, I16F16, &i, st);
        Ok(())
    });
    run("lagrange I32F32", CASES, s(), |i, st| {
        sizes!(check_lagrange, I32F32, &i, st);
        Ok(())
    });
}

// ---------------------------------------------------------------------------------------------
// Hermite basis

/// `hermite_deriv` against strak-ref's basis derived by inverting the matrix `K` of seeds/003
/// (`hermite_basis_deriv`), `t` clamped to `[0, 1]`, for `k = 0..=4`; `H_0 + H_3 = 1`.
fn check_hermite<S: Scalar>(t: f64, stats: &Stats) -> TestCaseResult {
    let (ts, tf) = round::<S>(t);
    let tc = tf.clamp(0.0, 1.0);
    ensure(basis::hermite(ts) == basis::hermite_deriv(ts, 0), || {
        "hermite ≠ hermite_deriv(·, 0)".into()
    })?;
    for k in 0..=4 {
        let got: Vec<f64> = basis::hermite_deriv(ts, k)
            .iter()
            .map(|v| v.to_f64())
            .collect();
        let want = strak_ref::hermite_basis_deriv(tc, k);
        // at most 4 rounded operations on intermediates ≤ 12 in magnitude (12t, 1 + 2t, …),
        // and the reference's K⁻¹ from Gauss–Jordan (a few f64 units); slack 4
        let tol = 16.0 * unit::<S>(12.0);
        stats.check(max_diff(&got, &want), tol, || format!("k = {k}, t = {tf}"))?;
    }
    let h = basis::hermite(ts);
    // the point weights are a partition of unity: two values, 4 units each
    let tol = 8.0 * unit::<S>(3.0);
    stats.check((h[0].to_f64() + h[3].to_f64() - 1.0).abs(), tol, || {
        format!("H_0 + H_3 at {tf}")
    })
}

#[test]
fn hermite_basis_matches_k_inverse() {
    let s = || -0.5..1.5_f64;
    run("hermite f64", CASES, s(), |t, st| {
        check_hermite::<f64>(t, st)
    });
    run("hermite f32", CASES, s(), |t, st| {
        check_hermite::<f32>(t, st)
    });
    run("hermite I16F16", CASES, s(), |t, st| {
        check_hermite::<I16F16>(t, st)
    });
    run("hermite I32F32", CASES, s(), |t, st| {
        check_hermite::<I32F32>(t, st)
    });
    // K⁻¹ of seeds/003 against strak-ref's inverse of K(0, 1)
    let want = strak_ref::hermite_k_inverse();
    let kf: [[f64; 4]; 4] = basis::hermite_k_inv();
    let kx: [[I16F16; 4]; 4] = basis::hermite_k_inv();
    for i in 0..4 {
        for j in 0..4 {
            assert!((kf[i][j] - want[i][j]).abs() <= 8.0 * f64::EPSILON);
            assert_eq!(kf[i][j], f64::from(basis::HERMITE_K_INV[i][j]));
            assert_eq!(kx[i][j].to_f64(), kf[i][j]);
        }
    }
}
