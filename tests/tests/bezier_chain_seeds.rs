//! The seeds' composite Bézier examples on [`BezierChain`]:
//! * seeds/004 "Bezier-Viertelkreis" / "Bézier-Kurven aneinandersetzen": four copies of the
//!   quarter circle (κ = 0.551897), each turned by −90°, make a closed C¹ chain around the
//!   unit circle with the quarter circle's radial error (strak-ref's
//!   `quarter_circle_radial_error`, 2.0564·10⁻⁴ at each segment's midpoint);
//! * seeds/002 "C¹-stetiger Bézier Spline" / "G¹-stetiger Bézier Spline" and seeds/003
//!   "Übergangsstellen": the same polygon with the tangent point after the join moved along
//!   the tangent is G¹ but only C⁰ (`TV_1 = k TV_2`, `k ≠ 1`).

use glam::DVec2;
use strak_curves::{
    Bezier, BezierChain, ParamCurve, ParamCurveDeriv, PieceDeriv, QUARTER_CIRCLE_KAPPA,
    classify_breaks,
};

/// The seed's quarter circle `(0, 1), (κ, 1), (1, κ), (1, 0)` turned by `−90° · q`.
fn quarter(q: usize) -> Vec<DVec2> {
    strak_ref::quarter_circle_bezier(QUARTER_CIRCLE_KAPPA)
        .iter()
        .map(|p| {
            let mut v = DVec2::new(p[0], p[1]);
            for _ in 0..q {
                v = DVec2::new(v.y, -v.x);
            }
            v
        })
        .collect()
}

fn circle() -> BezierChain<DVec2, 4, 4> {
    let mut pts = quarter(0);
    for q in 1..4 {
        pts.extend(&quarter(q)[1..]);
    }
    BezierChain::new(&pts).expect("circle")
}

#[test]
fn seed_004_four_quarter_circles_make_a_c1_circle() {
    let c = circle();
    assert_eq!(c.segment_count(), 4);
    assert_eq!(c.domain(), (0.0, 4.0));
    assert_eq!(c.eval(0.0), DVec2::new(0.0, 1.0));
    assert_eq!(c.eval(4.0), c.eval(0.0)); // closed
    for (i, want) in [(1.0, DVec2::X), (2.0, -DVec2::Y), (3.0, -DVec2::X)] {
        assert!((c.eval(i) - want).length() < 1e-15, "join {i}");
    }
    // the joins are C¹ (equal tangent vectors 3κ), not C²; G¹ too
    let cont = classify_breaks(&c, 1e-12).expect("classify");
    assert!(cont.is_c(1) && !cont.is_c(2), "{cont:?}");
    for i in 1..4 {
        let u = f64::from(i);
        let (left, right) = (c.piece_deriv(i as usize - 1, u, 1), c.deriv(u, 1));
        assert!((left - right).length() < 1e-15);
        assert!((right.length() - 3.0 * QUARTER_CIRCLE_KAPPA).abs() < 1e-15);
    }
    // the radial error of the chain is the quarter circle's (seeds/004), at the midpoints
    let want = strak_ref::quarter_circle_radial_error(QUARTER_CIRCLE_KAPPA);
    assert!((want - 2.0564e-4).abs() < 1e-8, "{want}");
    let steps = 40_000;
    let worst = (0..=steps)
        .map(|j| (c.eval(4.0 * f64::from(j) / f64::from(steps)).length() - 1.0).abs())
        .fold(0.0, f64::max);
    assert!((worst - want).abs() < 1e-12, "{worst} vs {want}");
    for i in 0..4 {
        let r = c.eval(f64::from(i) + 0.5).length();
        assert!((r - (1.0 - want)).abs() < 1e-12, "midpoint {i}: {r}");
    }
    // and it agrees with strak-ref's composite Bernstein evaluation
    let ctrl: Vec<Vec<f64>> = c
        .segments()
        .iter()
        .enumerate()
        .flat_map(|(i, s)| s.control_points()[usize::from(i > 0)..].to_vec())
        .map(|p| vec![p.x, p.y])
        .collect();
    for j in 0..=64 {
        let u = f64::from(j) / 16.0;
        for k in 0..=3 {
            let got = c.deriv(u, k);
            let r = strak_ref::bezier_chain_deriv(&ctrl, 3, u, k);
            assert!((got.x - r[0]).abs() < 1e-13 && (got.y - r[1]).abs() < 1e-13);
        }
    }
}

#[test]
fn seed_002_c1_versus_g1_bezier_spline() {
    let a = Bezier::new([
        DVec2::new(0.0, 0.0),
        DVec2::new(1.0, 2.0),
        DVec2::new(3.0, 2.0),
        DVec2::new(4.0, 1.0),
    ])
    .expect("a");
    let b = Bezier::new([
        DVec2::new(4.0, 1.0),
        DVec2::new(0.0, 0.0),
        DVec2::new(7.0, 0.0),
        DVec2::new(8.0, 2.0),
    ])
    .expect("b");
    // C¹: c_1 = b_3 + (b_3 − b_2) = (5, 0)
    let c1 = a.join_c1(&b).expect("c1");
    assert_eq!(c1.control_points()[1], DVec2::new(5.0, 0.0));
    let chain = BezierChain::<_, 4, 2>::from_segments(&[a, c1]).expect("chain");
    let cont = classify_breaks(&chain, 1e-12).expect("classify");
    assert!(cont.is_c(1), "{cont:?}");
    // G¹: the tangent vector after the join is k = 2 times as long (TV_1 = k TV_2)
    let g1 = a.join_g1(&b, Some(2.0 * 2f64.sqrt())).expect("g1");
    assert!((g1.control_points()[1] - DVec2::new(6.0, -1.0)).length() < 1e-15);
    let chain = BezierChain::<_, 4, 2>::from_segments(&[a, g1]).expect("chain");
    let cont = classify_breaks(&chain, 1e-12).expect("classify");
    assert!(cont.is_g(1) && !cont.is_c(1), "{cont:?}");
    let (left, right) = (chain.piece_deriv(0, 1.0, 1), chain.deriv(1.0, 1));
    assert!(
        (right - left * 2.0).length() < 1e-14,
        "right tangent = 2 × left tangent"
    );
}
