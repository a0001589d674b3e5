//! strak-curves' interpolating curves against strak-ref's independent `f64` textbook
//! implementations, plus the seeds' invariants (interpolation at the nodes, end tangents,
//! C¹/C² continuity, affine invariance, reproduction of straight lines).
//!
//! Every comparison runs in `f64`, `f32` and fixed-point (`I16F16` with small coordinates,
//! `I32F32`), on the point types `[S; 2]`, `[S; 3]`, glam `Vec3` and `DVec3`. The input is
//! first rounded to the scalar type; the reference then gets exactly the rounded points, the
//! curve's own nodes and the rounded parameter, so that only the arithmetic of strak-curves
//! (and of the reference, ~1e−16 relative) is measured, not the rounding of the input.
//!
//! # Tolerances
//! The error of the `k`-th derivative is compared against `K · ε_S · scale_k`, with `ε_S` the
//! scalar's [`Scalar::EPSILON`] (relative spacing for floats, absolute resolution 2⁻ᶠ for
//! fixed-point) and a condition factor `scale_k` computed from the data:
//! - piecewise cubic curves (Hermite, Catmull-Rom, cardinal, parabolic blend, cubic splines):
//!   `scale_k = (1 + M)·(1 + U/Δ_min)/Δ_min^k`, with `M` the largest magnitude of a Bézier
//!   point (`|q| + Δ·|m|`), `U` the largest `|u|` (rounding `u − u_i` costs `ε·U`, divided by
//!   `Δ` in the local parameter) and `Δ_min` the shortest interval (each derivative divides
//!   by `Δ` once more). The `1 +` terms cover fixed-point's absolute rounding.
//! - Lagrange curves (Neville for points, Horner on the Newton form for derivatives):
//!   `scale_k = (1 + U)·Σ_{l≥k} (1 + |c_l|)·l!/(l−k)!·(1 + A)^{l−k}`, with `c_l` the Newton
//!   coefficients (divided differences) and `A` the domain length: the magnitude of the terms
//!   of the `k`-th derivative of the Newton form, i.e. what its rounding errors scale with.
//!
//! `K` ([`K_LAGRANGE`], [`K_CUBIC`]) is a small multiple of the largest `error/(ε·scale)` measured over
//! thousands of random cases (`cargo test -p strak-tests --test interpolate_vs_ref --
//! --nocapture measured` prints the table).

// Textbook index notation (nodes[i], tol[k]) reads closer to the seeds than iterator chains.
#![allow(clippy::needless_range_loop)]

use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::TestRunner;
use strak_curves::glam::{DVec3, Vec3};
use strak_curves::{
    CubicSpline, HermiteSpline, I16F16, I32F32, LagrangeCurve, NodeSource, ParabolicBlend,
    ParamCurve, ParamCurveDeriv, Parameterization, Point, Scalar, ScalarOf, SplineBoundary,
};
use strak_ref as r;
use strak_tests::{linspace, max_diff, pt, pts, to_vec, to_vecs};

/// Capacity of every curve in this file.
const CAP: usize = 8;

// ---------------------------------------------------------------------------------------------
// Input data
// ---------------------------------------------------------------------------------------------

/// Where the nodes come from.
#[derive(Clone, Debug)]
enum Nodes {
    /// Given nodes (same count as the points).
    Given(Vec<f64>),
    /// Computed by a parameterization.
    Param(Parameterization),
}

/// An open interpolation problem: points (3 coordinates; 2-D types use the first two),
/// tangents (for Hermite splines and clamped ends), nodes, and a tension.
#[derive(Clone, Debug)]
struct Case {
    pts: Vec<Vec<f64>>,
    tangents: Vec<Vec<f64>>,
    nodes: Nodes,
    tension: f64,
}

/// A random walk of `n` points with steps of length in `[lo, hi]` in the xy-plane (so the
/// 2-D projection has the same chord lengths, bounded away from zero) and a z-slope of at most
/// 1/2: chord-length and centripetal nodes are well separated.
fn walk(n: usize, lo: f64, hi: f64) -> impl Strategy<Value = Vec<Vec<f64>>> {
    (
        prop::collection::vec(-2.0..2.0_f64, 3),
        prop::collection::vec((0.0..std::f64::consts::TAU, lo..hi, -0.5..0.5_f64), n - 1),
    )
        .prop_map(|(start, steps)| {
            let mut out = vec![start];
            for (angle, len, slope) in steps {
                let last = out[out.len() - 1].clone();
                out.push(vec![
                    last[0] + len * angle.cos(),
                    last[1] + len * angle.sin(),
                    last[2] + len * slope,
                ]);
            }
            out
        })
}

/// A closed loop: `m` distinct points around a centre at increasing angles (jittered), radii
/// in `[1.5, 3]`, followed by an exact copy of the first point.
fn closed_loop(m: usize) -> impl Strategy<Value = Vec<Vec<f64>>> {
    (
        prop::collection::vec(-2.0..2.0_f64, 3),
        prop::collection::vec((-0.3..0.3_f64, 1.5..3.0_f64, -0.5..0.5_f64), m),
    )
        .prop_map(move |(centre, spokes)| {
            let step = std::f64::consts::TAU / m as f64;
            let mut out: Vec<Vec<f64>> = spokes
                .iter()
                .enumerate()
                .map(|(i, &(jitter, radius, z))| {
                    let angle = step * (i as f64 + jitter);
                    vec![
                        centre[0] + radius * angle.cos(),
                        centre[1] + radius * angle.sin(),
                        centre[2] + z,
                    ]
                })
                .collect();
            out.push(out[0].clone());
            out
        })
}

/// Node choices for `n` points: given nodes with gaps in `[1/2, 2]` (starting anywhere in
/// `[−3, 3]`) or one of the three parameterizations.
fn node_choice(n: usize) -> impl Strategy<Value = Nodes> {
    prop_oneof![
        (-3.0..3.0_f64)
            .prop_flat_map(move |start| strak_tests::increasing_nodes(n, start, 0.5, 2.0))
            .prop_map(Nodes::Given),
        Just(Nodes::Param(Parameterization::Uniform)),
        Just(Nodes::Param(Parameterization::ChordLength)),
        Just(Nodes::Param(Parameterization::Centripetal)),
    ]
}

/// An open case with `n ∈ count` points.
fn open_case(count: std::ops::RangeInclusive<usize>) -> impl Strategy<Value = Case> {
    count.prop_flat_map(|n| {
        (
            walk(n, 0.5, 2.0),
            strak_tests::points(n..=n, 3, 3.0),
            node_choice(n),
            -0.5..1.5_f64,
        )
            .prop_map(|(pts, tangents, nodes, tension)| Case {
                pts,
                tangents,
                nodes,
                tension,
            })
    })
}

/// A closed case (`m + 1` points, the last equal to the first) for periodic splines.
fn closed_case(distinct: std::ops::RangeInclusive<usize>) -> impl Strategy<Value = Case> {
    distinct.prop_flat_map(|m| {
        (closed_loop(m), node_choice(m + 1)).prop_map(|(pts, nodes)| Case {
            tangents: vec![vec![0.0; 3]; pts.len()],
            pts,
            nodes,
            tension: 0.0,
        })
    })
}

// ---------------------------------------------------------------------------------------------
// Conversions and measures
// ---------------------------------------------------------------------------------------------

/// The first `P::DIM` coordinates of each point, rounded to `P`.
fn round_pts<P: Point>(data: &[Vec<f64>]) -> Vec<P> {
    let cut: Vec<Vec<f64>> = data.iter().map(|p| p[..P::DIM].to_vec()).collect();
    pts::<P>(&cut)
}

/// A scalar from `f64` (test input is always in range).
fn sc<S: Scalar>(x: f64) -> S {
    S::from_f64(x).expect("test scalar out of range")
}

/// The node source for the case's nodes, rounded to `S` (`given` holds the rounded nodes).
fn node_source<'a, S: Scalar>(nodes: &Nodes, given: &'a [S]) -> NodeSource<'a, S> {
    match nodes {
        Nodes::Given(_) => NodeSource::Given(given),
        Nodes::Param(p) => NodeSource::Computed(*p),
    }
}

/// The given nodes rounded to `S` (empty for a parameterization).
fn given_nodes<S: Scalar>(nodes: &Nodes) -> Vec<S> {
    match nodes {
        Nodes::Given(u) => u.iter().map(|&x| sc::<S>(x)).collect(),
        Nodes::Param(_) => Vec::new(),
    }
}

/// The tolerance multiplier `K` for Lagrange curves: the largest measured `error/(ε·scale)`
/// is 1.8 (f64; f32 and fixed-point ≤ 0.4, the scale being pessimistic there).
const K_LAGRANGE: f64 = 16.0;

/// The tolerance multiplier `K` for the piecewise cubic curves: the largest measured
/// `error/(ε·scale)` is 14 (periodic spline, f64, third derivative; the reference's dense
/// solve contributes), 10 in f32, 7 in fixed-point.
const K_CUBIC: f64 = 64.0;

/// Largest errors of one comparison, per derivative order 0..=3: absolute, and relative to
/// `ε_S · scale_k`.
#[derive(Clone, Debug)]
struct Measure {
    label: String,
    abs: [f64; 4],
    ratio: [f64; 4],
    limit: f64,
}

impl Measure {
    fn assert_ok(&self) {
        for k in 0..4 {
            assert!(
                self.ratio[k] <= self.limit,
                "{}: derivative {k}: error {:e} = {:.2}·ε·scale > {}·ε·scale",
                self.label,
                self.abs[k],
                self.ratio[k],
                self.limit
            );
        }
    }
}

/// Compares `curve` with `reference(u, k)` at evenly spaced parameters, at every node, between
/// nodes and outside the domain (clamping), for `k = 0..=3`.
fn compare<C: ParamCurveDeriv>(
    label: &str,
    curve: &C,
    nodes: &[f64],
    scale: [f64; 4],
    limit: f64,
    reference: impl Fn(f64, usize) -> Vec<f64>,
) -> Measure {
    let (a, b) = (nodes[0], nodes[nodes.len() - 1]);
    let mut params = linspace(a, b, 33);
    params.extend_from_slice(nodes);
    params.extend(nodes.windows(2).map(|w| 0.5 * (w[0] + w[1])));
    params.extend([a - 1.0, b + 1.0]);
    let eps = <ScalarOf<C> as Scalar>::EPSILON;
    let mut m = Measure {
        label: format!("{label} {}", type_label::<C::Point>()),
        abs: [0.0; 4],
        ratio: [0.0; 4],
        limit,
    };
    for u in params {
        let us: ScalarOf<C> = sc(u);
        let uf = us.to_f64();
        for k in 0..4 {
            let got = to_vec(curve.deriv(us, k));
            let want = reference(uf, k);
            let err = max_diff(&got, &want);
            assert!(
                err.is_finite(),
                "{}: non-finite at u = {uf}, k = {k}",
                m.label
            );
            m.abs[k] = m.abs[k].max(err);
            m.ratio[k] = m.ratio[k].max(err / (eps * scale[k]));
        }
    }
    m
}

/// A short name of a point type: `[f64; 2]`, `Vec3`, ….
fn type_label<P: Point>() -> String {
    let name = std::any::type_name::<P>();
    if name.contains("glam") {
        name.rsplit("::").next().unwrap_or(name).to_string()
    } else {
        format!("[{}; {}]", <P::Scalar as Scalar>::NAME, P::DIM)
    }
}

/// Condition factors of a piecewise cubic through `pts` at `nodes` with node derivatives
/// `tangents` (module docs).
fn cubic_scale(nodes: &[f64], pts: &[Vec<f64>], tangents: &[Vec<f64>]) -> [f64; 4] {
    let dmin = nodes
        .windows(2)
        .map(|w| w[1] - w[0])
        .fold(f64::INFINITY, f64::min);
    let dmax = nodes.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max);
    let umax = nodes.iter().fold(0.0_f64, |m, u| m.max(u.abs()));
    let amax = |v: &[Vec<f64>]| v.iter().flatten().fold(0.0_f64, |m, x| m.max(x.abs()));
    let mag = amax(pts) + dmax * amax(tangents);
    // Fixed-point rounds absolutely (ε per operation), so long intervals do not make the
    // derivatives' errors smaller than ε: the factor 1/Δ^k is taken at Δ ≤ 1.
    std::array::from_fn(|k| (1.0 + mag) * (1.0 + umax / dmin) / dmin.min(1.0).powi(k as i32))
}

/// Condition factors of the Lagrange curve through `pts` at `nodes` (module docs).
fn lagrange_scale(nodes: &[f64], pts: &[Vec<f64>]) -> [f64; 4] {
    let n = nodes.len() - 1;
    let dim = pts[0].len();
    // Divided differences per coordinate, in place.
    let mut coef: Vec<Vec<f64>> = pts.to_vec();
    for w in 1..=n {
        for i in (w..=n).rev() {
            let du = nodes[i] - nodes[i - w];
            for c in 0..dim {
                coef[i][c] = (coef[i][c] - coef[i - 1][c]) / du;
            }
        }
    }
    let c: Vec<f64> = coef
        .iter()
        .map(|v| v.iter().fold(0.0_f64, |m, x| m.max(x.abs())))
        .collect();
    let span = nodes[n] - nodes[0];
    let umax = nodes.iter().fold(0.0_f64, |m, u| m.max(u.abs()));
    std::array::from_fn(|k| {
        let mut sum = 0.0;
        for (l, cl) in c.iter().enumerate().skip(k) {
            let falling: f64 = ((l - k + 1)..=l).map(|x| x as f64).product();
            sum += (1.0 + cl) * falling * (1.0 + span).powi((l - k) as i32);
        }
        (1.0 + umax) * sum.max(1.0)
    })
}

/// The curve's nodes as `f64`, after checking them against the reference parameterization of
/// the rounded points (or the rounded given nodes).
fn checked_nodes<S: Scalar>(
    label: &str,
    nodes: &Nodes,
    got: &[S],
    rounded: &[Vec<f64>],
) -> Vec<f64> {
    let got: Vec<f64> = got.iter().map(|u| u.to_f64()).collect();
    let want = match nodes {
        Nodes::Given(u) => u.iter().map(|&x| sc::<S>(x).to_f64()).collect(),
        Nodes::Param(Parameterization::Uniform) => r::uniform_nodes(rounded.len()),
        Nodes::Param(Parameterization::ChordLength) => r::chord_length_nodes(rounded),
        Nodes::Param(Parameterization::Centripetal) => r::centripetal_nodes(rounded),
    };
    // Both sum the same distances in f64 (a few ulps apart); strak then rounds each node once
    // to S (half an ulp of S, absolute 2^-f/2 for fixed-point).
    let umax = want.iter().fold(1.0_f64, |m, u| m.max(u.abs()));
    let tol = (S::EPSILON + 16.0 * f64::EPSILON) * umax;
    assert_eq!(got.len(), want.len(), "{label}: node count");
    let err = max_diff(&got, &want);
    assert!(err <= tol, "{label}: nodes {got:?} vs reference {want:?}");
    got
}

// ---------------------------------------------------------------------------------------------
// One comparison per curve type, generic over the point type
// ---------------------------------------------------------------------------------------------

fn lagrange<P: Point>(case: &Case) -> Measure {
    let p: Vec<P> = round_pts(&case.pts);
    let given = given_nodes::<P::Scalar>(&case.nodes);
    let c = LagrangeCurve::<P, CAP>::new(&p, node_source(&case.nodes, &given))
        .unwrap_or_else(|e| panic!("Lagrange {case:?}: {e:?}"));
    let q = to_vecs(&p);
    let u = checked_nodes("Lagrange", &case.nodes, c.nodes(), &q);
    let (a, b) = (u[0], u[u.len() - 1]);
    compare(
        "Lagrange",
        &c,
        &u,
        lagrange_scale(&u, &q),
        K_LAGRANGE,
        |t, k| r::lagrange_deriv(&u, &q, t.clamp(a, b), k),
    )
}

fn hermite<P: Point>(case: &Case) -> Measure {
    let p: Vec<P> = round_pts(&case.pts);
    let m: Vec<P> = round_pts(&case.tangents);
    let given = given_nodes::<P::Scalar>(&case.nodes);
    let c = HermiteSpline::<P, CAP>::new(&p, &m, node_source(&case.nodes, &given))
        .unwrap_or_else(|e| panic!("Hermite {case:?}: {e:?}"));
    let (q, mt) = (to_vecs(&p), to_vecs(&m));
    let u = checked_nodes("Hermite", &case.nodes, c.nodes(), &q);
    compare(
        "Hermite",
        &c,
        &u,
        cubic_scale(&u, &q, &mt),
        K_CUBIC,
        |t, k| r::hermite_spline_deriv(&u, &q, &mt, t, k),
    )
}

/// Catmull-Rom (`cardinal == false`) or cardinal with the case's tension.
fn cardinal<P: Point>(case: &Case, with_tension: bool) -> Measure {
    let p: Vec<P> = round_pts(&case.pts);
    let given = given_nodes::<P::Scalar>(&case.nodes);
    let src = node_source(&case.nodes, &given);
    let (label, tension) = if with_tension {
        ("cardinal", sc::<P::Scalar>(case.tension))
    } else {
        ("Catmull-Rom", P::Scalar::ZERO)
    };
    let c = if with_tension {
        HermiteSpline::<P, CAP>::cardinal(&p, src, tension)
    } else {
        HermiteSpline::<P, CAP>::catmull_rom(&p, src)
    }
    .unwrap_or_else(|e| panic!("{label} {case:?}: {e:?}"));
    let q = to_vecs(&p);
    let u = checked_nodes(label, &case.nodes, c.nodes(), &q);
    let scale = 1.0 - tension.to_f64();
    let mt: Vec<Vec<f64>> = r::catmull_rom_tangents(&u, &q)
        .iter()
        .map(|m| r::vec_scale(m, scale))
        .collect();
    compare(label, &c, &u, cubic_scale(&u, &q, &mt), K_CUBIC, |t, k| {
        r::hermite_spline_deriv(&u, &q, &mt, t, k)
    })
}

fn parabolic<P: Point>(case: &Case) -> Measure {
    let p: Vec<P> = round_pts(&case.pts);
    let c =
        ParabolicBlend::<P, CAP>::new(&p).unwrap_or_else(|e| panic!("parabolic {case:?}: {e:?}"));
    let q = to_vecs(&p);
    let u = checked_nodes(
        "parabolic",
        &Nodes::Param(Parameterization::Uniform),
        c.as_hermite().nodes(),
        &q,
    );
    let mt: Vec<Vec<f64>> = u
        .iter()
        .map(|&t| r::parabolic_blend_deriv(&q, t, 1))
        .collect();
    compare(
        "parabolic blend",
        &c,
        &u,
        cubic_scale(&u, &q, &mt),
        K_CUBIC,
        |t, k| r::parabolic_blend_deriv(&q, t, k),
    )
}

#[derive(Clone, Copy, Debug)]
enum Ends {
    Natural,
    Clamped,
    Periodic,
}

fn spline<P: Point>(case: &Case, ends: Ends) -> Measure {
    let p: Vec<P> = round_pts(&case.pts);
    let given = given_nodes::<P::Scalar>(&case.nodes);
    let (start, end): (P, P) = (
        pt(&case.tangents[0][..P::DIM]),
        pt(&case.tangents[case.tangents.len() - 1][..P::DIM]),
    );
    let boundary = match ends {
        Ends::Natural => SplineBoundary::Natural,
        Ends::Clamped => SplineBoundary::Clamped { start, end },
        Ends::Periodic => SplineBoundary::Periodic,
    };
    let label = format!("{ends:?} spline");
    let c = CubicSpline::<P, CAP>::new(&p, node_source(&case.nodes, &given), boundary)
        .unwrap_or_else(|e| panic!("{label} {case:?}: {e:?}"));
    let q = to_vecs(&p);
    let u = checked_nodes(&label, &case.nodes, c.nodes(), &q);
    let reference = match ends {
        Ends::Natural => r::CubicSplineRef::natural(&u, &q),
        Ends::Clamped => r::CubicSplineRef::clamped(&u, &q, &to_vec(start), &to_vec(end)),
        Ends::Periodic => r::CubicSplineRef::periodic(&u, &q),
    };
    let mt: Vec<Vec<f64>> = u.iter().map(|&t| reference.deriv(t, 1)).collect();
    compare(&label, &c, &u, cubic_scale(&u, &q, &mt), K_CUBIC, |t, k| {
        reference.deriv(t, k)
    })
}

/// Runs `$f` for every point type (f64, f32, I32F32, I16F16; arrays and glam) and returns the
/// measures.
macro_rules! all_types {
    ($f:ident $(, $arg:expr)*) => {
        [
            $f::<[f64; 2]>($($arg),*),
            $f::<[f64; 3]>($($arg),*),
            $f::<DVec3>($($arg),*),
            $f::<[f32; 2]>($($arg),*),
            $f::<Vec3>($($arg),*),
            $f::<[I32F32; 3]>($($arg),*),
            $f::<[I16F16; 2]>($($arg),*),
        ]
    };
}

fn assert_all(measures: &[Measure]) {
    for m in measures {
        m.assert_ok();
    }
}

// ---------------------------------------------------------------------------------------------
// Properties: strak-curves against strak-ref
// ---------------------------------------------------------------------------------------------

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn lagrange_matches_reference(case in open_case(2..=6)) {
        assert_all(&all_types!(lagrange, &case));
    }

    #[test]
    fn hermite_matches_reference(case in open_case(2..=CAP)) {
        assert_all(&all_types!(hermite, &case));
    }

    #[test]
    fn catmull_rom_matches_reference(case in open_case(2..=CAP)) {
        assert_all(&all_types!(cardinal, &case, false));
    }

    #[test]
    fn cardinal_matches_reference(case in open_case(2..=CAP)) {
        assert_all(&all_types!(cardinal, &case, true));
    }

    #[test]
    fn parabolic_blend_matches_reference(case in open_case(3..=CAP)) {
        assert_all(&all_types!(parabolic, &case));
    }

    #[test]
    fn natural_spline_matches_reference(case in open_case(2..=CAP)) {
        assert_all(&all_types!(spline, &case, Ends::Natural));
    }

    #[test]
    fn clamped_spline_matches_reference(case in open_case(2..=CAP)) {
        assert_all(&all_types!(spline, &case, Ends::Clamped));
    }

    #[test]
    fn periodic_spline_matches_reference(case in closed_case(2..=CAP - 1)) {
        assert_all(&all_types!(spline, &case, Ends::Periodic));
    }
}

/// Prints the largest measured errors per curve type, point type and derivative order
/// (absolute, and as a multiple of `ε·scale`). Run with `--nocapture` to see the table.
#[test]
fn measured_errors() {
    // STRAK_CASES=5000 for a longer run (the tolerances were set from such runs).
    let cases: usize = std::env::var("STRAK_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(64);
    let mut runner = TestRunner::deterministic();
    let mut table: Vec<Measure> = Vec::new();
    let mut merge = |ms: [Measure; 7]| {
        for m in ms {
            m.assert_ok();
            match table.iter_mut().find(|t| t.label == m.label) {
                Some(t) => {
                    for k in 0..4 {
                        t.abs[k] = t.abs[k].max(m.abs[k]);
                        t.ratio[k] = t.ratio[k].max(m.ratio[k]);
                    }
                }
                None => table.push(m),
            }
        }
    };
    let open = open_case(2..=CAP);
    let short = open_case(2..=6);
    let blend = open_case(3..=CAP);
    let closed = closed_case(2..=CAP - 1);
    for _ in 0..cases {
        let case = short.new_tree(&mut runner).unwrap().current();
        merge(all_types!(lagrange, &case));
        let case = open.new_tree(&mut runner).unwrap().current();
        merge(all_types!(hermite, &case));
        merge(all_types!(cardinal, &case, false));
        merge(all_types!(cardinal, &case, true));
        merge(all_types!(spline, &case, Ends::Natural));
        merge(all_types!(spline, &case, Ends::Clamped));
        let case = blend.new_tree(&mut runner).unwrap().current();
        merge(all_types!(parabolic, &case));
        let case = closed.new_tree(&mut runner).unwrap().current();
        merge(all_types!(spline, &case, Ends::Periodic));
    }
    println!(
        "{:<48} {:>40}   {:>28}",
        "curve / point type", "max |error|, k = 0..3", "max error/(ε·scale)"
    );
    for m in &table {
        println!(
            "{:<48} {:>9.2e} {:>9.2e} {:>9.2e} {:>9.2e}   {:>6.3} {:>6.3} {:>6.3} {:>6.3}",
            m.label,
            m.abs[0],
            m.abs[1],
            m.abs[2],
            m.abs[3],
            m.ratio[0],
            m.ratio[1],
            m.ratio[2],
            m.ratio[3]
        );
    }
}

// ---------------------------------------------------------------------------------------------
// Invariants of the seeds
// ---------------------------------------------------------------------------------------------

/// The curve types of this module, for the invariant tests.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    Lagrange,
    Hermite,
    CatmullRom,
    Cardinal,
    Parabolic,
    Natural,
    Clamped,
    Periodic,
}

const OPEN_KINDS: [Kind; 7] = [
    Kind::Lagrange,
    Kind::Hermite,
    Kind::CatmullRom,
    Kind::Cardinal,
    Kind::Parabolic,
    Kind::Natural,
    Kind::Clamped,
];

/// A curve of kind `kind` through the case's points (rounded to `P`), as a function
/// `(u, k) ↦ c^{(k)}(u)` in `f64`, with its nodes and tolerance data.
struct Built {
    deriv: Box<dyn Fn(f64, usize) -> Vec<f64>>,
    nodes: Vec<f64>,
    /// The tolerance of derivative `k`: `K·ε·scale_k`.
    tol: [f64; 4],
}

fn build<P: Point>(kind: Kind, case: &Case) -> Built {
    fn wrap<C: ParamCurveDeriv + 'static>(c: C) -> Box<dyn Fn(f64, usize) -> Vec<f64>> {
        Box::new(move |u, k| to_vec(c.deriv(sc(u), k)))
    }
    let p: Vec<P> = round_pts(&case.pts);
    let m: Vec<P> = round_pts(&case.tangents);
    let q = to_vecs(&p);
    let given = given_nodes::<P::Scalar>(&case.nodes);
    let src = node_source(&case.nodes, &given);
    let tension: P::Scalar = sc(case.tension);
    let (start, end) = (m[0], m[m.len() - 1]);
    let fail = |e: strak_curves::Error| format!("{kind:?} {case:?}: {e:?}");
    let (deriv, nodes, tangents) = match kind {
        Kind::Lagrange => {
            let c = LagrangeCurve::<P, CAP>::new(&p, src).map_err(fail).unwrap();
            let u = to_f64s(c.nodes());
            (wrap(c), u, Vec::new())
        }
        Kind::Parabolic => {
            let c = ParabolicBlend::<P, CAP>::new(&p).map_err(fail).unwrap();
            let (u, t) = (
                to_f64s(c.as_hermite().nodes()),
                to_vecs(c.as_hermite().tangents()),
            );
            (wrap(c), u, t)
        }
        Kind::Hermite | Kind::CatmullRom | Kind::Cardinal => {
            let c = match kind {
                Kind::Hermite => HermiteSpline::<P, CAP>::new(&p, &m, src),
                Kind::CatmullRom => HermiteSpline::<P, CAP>::catmull_rom(&p, src),
                _ => HermiteSpline::<P, CAP>::cardinal(&p, src, tension),
            }
            .map_err(fail)
            .unwrap();
            let (u, t) = (to_f64s(c.nodes()), to_vecs(c.tangents()));
            (wrap(c), u, t)
        }
        Kind::Natural | Kind::Clamped | Kind::Periodic => {
            let boundary = match kind {
                Kind::Natural => SplineBoundary::Natural,
                Kind::Clamped => SplineBoundary::Clamped { start, end },
                _ => SplineBoundary::Periodic,
            };
            let c = CubicSpline::<P, CAP>::new(&p, src, boundary)
                .map_err(fail)
                .unwrap();
            let (u, t) = (to_f64s(c.nodes()), to_vecs(c.tangents()));
            (wrap(c), u, t)
        }
    };
    let eps = <P::Scalar as Scalar>::EPSILON;
    let tol = if kind == Kind::Lagrange {
        lagrange_scale(&nodes, &q).map(|s| K_LAGRANGE * eps * s)
    } else {
        cubic_scale(&nodes, &q, &tangents).map(|s| K_CUBIC * eps * s)
    };
    Built { deriv, nodes, tol }
}

fn to_f64s<S: Scalar>(v: &[S]) -> Vec<f64> {
    v.iter().map(|x| x.to_f64()).collect()
}

/// Parameters for the invariant checks: evenly spaced, the nodes, and outside the domain.
fn sample_params(nodes: &[f64]) -> Vec<f64> {
    let (a, b) = (nodes[0], nodes[nodes.len() - 1]);
    let mut u = linspace(a, b, 25);
    u.extend_from_slice(nodes);
    u.extend([a - 0.5, b + 0.5]);
    u
}

/// Interpolation at the nodes: exact for the piecewise cubics in every scalar type (de
/// Casteljau at `s = 0` or `s = 1` returns the end point unchanged), within rounding for
/// Lagrange curves (Neville mixes equal values with weights `λ`, `1 − λ`).
fn check_interpolation<P: Point>(case: &Case, kinds: &[Kind]) {
    let p: Vec<P> = round_pts(&case.pts);
    for &kind in kinds {
        let c = build::<P>(kind, case);
        for (i, (&u, q)) in c.nodes.iter().zip(&p).enumerate() {
            let got = (c.deriv)(u, 0);
            let want = to_vec(*q);
            if kind == Kind::Lagrange {
                let err = max_diff(&got, &want);
                assert!(
                    err <= c.tol[0],
                    "{kind:?}: node {i}: {got:?} vs {want:?} ({err:e})"
                );
            } else {
                assert_eq!(got, want, "{kind:?} {}: node {i}", type_label::<P>());
            }
        }
    }
}

/// Hermite splines take their tangents at the nodes from both sides (exact: the hodograph's
/// de Casteljau at `s = 0, 1`), so they are C¹; a clamped spline takes its end tangents; the
/// Catmull-Rom, cardinal and natural splines are C¹ at every inner node (left piece via
/// `segment(i − 1)`).
fn check_tangents<P: Point>(case: &Case) {
    let p: Vec<P> = round_pts(&case.pts);
    let m: Vec<P> = round_pts(&case.tangents);
    let given = given_nodes::<P::Scalar>(&case.nodes);
    let h = HermiteSpline::<P, CAP>::new(&p, &m, node_source(&case.nodes, &given)).unwrap();
    let nodes = h.nodes().to_vec();
    for (i, &u) in nodes.iter().enumerate() {
        assert_eq!(h.deriv(u, 1), m[i], "Hermite tangent at node {i}");
        if i > 0 {
            let left = h.segment(i - 1).unwrap();
            assert_eq!(left.deriv(u, 1), m[i], "Hermite left tangent at node {i}");
            assert_eq!(left.eval(u), p[i], "Hermite left piece end at node {i}");
        }
    }
    let (start, end) = (m[0], m[m.len() - 1]);
    let src = node_source(&case.nodes, &given);
    let c = CubicSpline::<P, CAP>::new(&p, src, SplineBoundary::Clamped { start, end }).unwrap();
    let (a, b) = c.domain();
    assert_eq!(c.deriv(a, 1), start, "clamped start tangent");
    assert_eq!(c.deriv(b, 1), end, "clamped end tangent");
    let splines = [
        HermiteSpline::<P, CAP>::catmull_rom(&p, src).unwrap(),
        HermiteSpline::<P, CAP>::cardinal(&p, src, sc(case.tension)).unwrap(),
        CubicSpline::<P, CAP>::new(&p, src, SplineBoundary::Natural)
            .unwrap()
            .as_hermite()
            .clone(),
    ];
    for s in &splines {
        for i in 1..s.nodes().len() - 1 {
            let u = s.nodes()[i];
            let left = s.segment(i - 1).unwrap();
            assert_eq!(left.deriv(u, 1), s.deriv(u, 1), "C¹ at node {i}");
        }
    }
}

/// C² at the inner nodes of cubic splines (left limit from the piece ending there), the
/// natural end conditions, and the seam of periodic splines (C⁰, C¹ exactly, C² within
/// rounding).
fn check_c2<P: Point>(case: &Case, ends: Ends) {
    let p: Vec<P> = round_pts(&case.pts);
    let m: Vec<P> = round_pts(&case.tangents);
    let given = given_nodes::<P::Scalar>(&case.nodes);
    let boundary = match ends {
        Ends::Natural => SplineBoundary::Natural,
        Ends::Clamped => SplineBoundary::Clamped {
            start: m[0],
            end: m[m.len() - 1],
        },
        Ends::Periodic => SplineBoundary::Periodic,
    };
    let c = CubicSpline::<P, CAP>::new(&p, node_source(&case.nodes, &given), boundary).unwrap();
    let u = to_f64s(c.nodes());
    let eps = <P::Scalar as Scalar>::EPSILON;
    let tol = cubic_scale(&u, &to_vecs(&p), &to_vecs(c.tangents())).map(|s| K_CUBIC * eps * s);
    let h = c.as_hermite();
    let nodes = c.nodes().to_vec();
    for i in 1..nodes.len() - 1 {
        let left = h.segment(i - 1).unwrap();
        for k in 0..=2 {
            let (l, r) = (
                to_vec(left.deriv(nodes[i], k)),
                to_vec(c.deriv(nodes[i], k)),
            );
            let err = max_diff(&l, &r);
            assert!(
                err <= tol[k],
                "{ends:?}: jump {err:e} of derivative {k} at node {i}"
            );
        }
    }
    let (a, b) = c.domain();
    match ends {
        Ends::Natural => {
            for x in [a, b] {
                let d2 = to_vec(c.deriv(x, 2));
                let err = max_diff(&d2, &vec![0.0; P::DIM]);
                assert!(err <= tol[2], "natural end: c'' = {d2:?}");
            }
        }
        Ends::Periodic => {
            assert_eq!(c.eval(a), c.eval(b), "periodic seam C⁰");
            assert_eq!(c.deriv(a, 1), c.deriv(b, 1), "periodic seam C¹");
            let err = max_diff(&to_vec(c.deriv(a, 2)), &to_vec(c.deriv(b, 2)));
            assert!(err <= tol[2], "periodic seam C²: jump {err:e}");
        }
        Ends::Clamped => {}
    }
}

/// Parabolic blending is C¹: the left piece's end derivative equals the right piece's start
/// derivative, and both match the reference's limits from the left (seeds/003 formulas
/// evaluated just before the node, extrapolated to it by a first-order Taylor step).
fn check_parabolic_c1<P: Point>(case: &Case) {
    let p: Vec<P> = round_pts(&case.pts);
    let q = to_vecs(&p);
    let c = ParabolicBlend::<P, CAP>::new(&p).unwrap();
    let u = to_f64s(c.as_hermite().nodes());
    let eps = <P::Scalar as Scalar>::EPSILON;
    let tol = cubic_scale(&u, &q, &to_vecs(c.as_hermite().tangents())).map(|s| K_CUBIC * eps * s);
    // Taylor error h²/2·|c'''| with |c'''| ≲ 100 on these inputs, plus cancellation ε/h.
    let h = 1e-6;
    for i in 1..p.len() - 1 {
        let x: P::Scalar = sc(u[i]);
        let left = c.as_hermite().segment(i - 1).unwrap();
        assert_eq!(
            to_vec(left.deriv(x, 1)),
            to_vec(c.deriv(x, 1)),
            "C¹ at node {i}"
        );
        for k in 0..=1 {
            let before = r::parabolic_blend_deriv(&q, u[i] - h, k);
            let slope = r::parabolic_blend_deriv(&q, u[i] - h, k + 1);
            let ref_left: Vec<f64> = before.iter().zip(&slope).map(|(a, b)| a + h * b).collect();
            let ref_right = r::parabolic_blend_deriv(&q, u[i], k);
            let strak_left = to_vec(left.deriv(x, k));
            assert!(
                max_diff(&ref_left, &ref_right) <= 1e-9,
                "reference not C¹ at {i}"
            );
            let err = max_diff(&strak_left, &ref_left);
            assert!(
                err <= tol[k] + 1e-9,
                "left limit of derivative {k} at node {i}: {err:e}"
            );
        }
    }
}

/// A transformation `x ↦ A·x + b` of 3-D coordinates (2-D points use the upper-left block).
#[derive(Clone, Debug)]
struct Affine {
    a: [[f64; 3]; 3],
    b: [f64; 3],
}

impl Affine {
    fn linear(&self, x: &[f64]) -> Vec<f64> {
        (0..x.len())
            .map(|i| (0..x.len()).map(|j| self.a[i][j] * x[j]).sum())
            .collect()
    }
    fn apply(&self, x: &[f64]) -> Vec<f64> {
        self.linear(x)
            .iter()
            .zip(&self.b)
            .map(|(y, b)| y + b)
            .collect()
    }
    /// The largest row sum of `|A|` (the ∞-norm, how much `A` magnifies errors).
    fn norm(&self) -> f64 {
        self.a
            .iter()
            .map(|row| row.iter().map(|x| x.abs()).sum::<f64>())
            .fold(0.0, f64::max)
    }
}

/// A general affine map (entries of `A` in `[−1.5, 1.5]`) or, when `rigid`, a rotation about
/// a random axis followed by a translation (which preserves chord lengths).
fn affine(rigid: bool) -> impl Strategy<Value = Affine> {
    (
        prop::collection::vec(-1.5..1.5_f64, 9),
        prop::collection::vec(-3.0..3.0_f64, 3),
        (
            0.0..std::f64::consts::TAU,
            0.0..std::f64::consts::PI,
            0.0..std::f64::consts::TAU,
        ),
    )
        .prop_map(move |(m, b, (alpha, beta, gamma))| {
            let a = if rigid {
                // Rotation R_z(α)·R_x(β)·R_z(γ): the xy-block of a 2-D point is a rotation only
                // when β = 0, so 2-D cases use R_z(α) (see `check_affine`).
                let rz = |t: f64| {
                    [
                        [t.cos(), -t.sin(), 0.0],
                        [t.sin(), t.cos(), 0.0],
                        [0.0, 0.0, 1.0],
                    ]
                };
                let rx = [
                    [1.0, 0.0, 0.0],
                    [0.0, beta.cos(), -beta.sin()],
                    [0.0, beta.sin(), beta.cos()],
                ];
                mat_mul(mat_mul(rz(alpha), rx), rz(gamma))
            } else {
                [[m[0], m[1], m[2]], [m[3], m[4], m[5]], [m[6], m[7], m[8]]]
            };
            Affine {
                a,
                b: [b[0], b[1], b[2]],
            }
        })
}

fn mat_mul(x: [[f64; 3]; 3], y: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|l| x[i][l] * y[l][j]).sum()))
}

/// Affine invariance (seeds/000): the curve through the transformed points (tangents
/// transformed by the linear part) is the transformed curve, `c_T(u) = A·c(u) + b` and
/// `c_T^{(k)}(u) = A·c^{(k)}(u)`. With chord-length or centripetal nodes only rigid motions
/// keep the nodes, so only those are used there. In `f64`.
fn check_affine<P: Point<Scalar = f64>>(case: &Case, t: &Affine, kinds: &[Kind]) {
    let mut t = t.clone();
    if P::DIM == 2 {
        // keep the 2-D block a rotation for rigid maps: use R_z(α) only
        let (c, s) = (t.a[0][0], t.a[1][0]);
        let norm = (c * c + s * s).sqrt();
        if matches!(
            case.nodes,
            Nodes::Param(Parameterization::ChordLength | Parameterization::Centripetal)
        ) {
            t.a = [
                [c / norm, -s / norm, 0.0],
                [s / norm, c / norm, 0.0],
                [0.0, 0.0, 1.0],
            ];
        }
    }
    let cut = |v: &Vec<f64>| v[..P::DIM].to_vec();
    let moved = Case {
        pts: case.pts.iter().map(|p| t.apply(&cut(p))).collect(),
        tangents: case.tangents.iter().map(|m| t.linear(&cut(m))).collect(),
        nodes: case.nodes.clone(),
        tension: case.tension,
    };
    for &kind in kinds {
        let c = build::<P>(kind, case);
        let ct = build::<P>(kind, &moved);
        // Rigid motions reproduce computed nodes only up to rounding, so a parameter exactly
        // at an inner node may fall into different pieces of the two curves (whose second and
        // third derivatives jump there): parameters near inner nodes are skipped.
        let inner = &c.nodes[1..c.nodes.len() - 1];
        let params = sample_params(&c.nodes)
            .into_iter()
            .filter(|u| inner.iter().all(|x| (u - x).abs() > 1e-9 * (1.0 + x.abs())));
        for u in params {
            for k in 0..4 {
                let d = (c.deriv)(u, k);
                let want = if k == 0 { t.apply(&d) } else { t.linear(&d) };
                let got = (ct.deriv)(u, k);
                let err = max_diff(&got, &want);
                let tol = t.norm() * c.tol[k] + ct.tol[k];
                assert!(
                    err <= tol,
                    "{kind:?}: u = {u}, k = {k}: {got:?} vs {want:?} ({err:e} > {tol:e})"
                );
            }
        }
    }
}

/// Points on a straight line `p + s_i·d` (`|d| = 1`, gaps in `[1/2, 2]`).
fn line() -> impl Strategy<Value = (Vec<f64>, Vec<f64>, Vec<f64>)> {
    (2..=CAP).prop_flat_map(|n| {
        (
            prop::collection::vec(-3.0..3.0_f64, 3),
            (0.0..std::f64::consts::TAU, -0.5..0.5_f64),
            strak_tests::increasing_nodes(n, 0.0, 0.5, 2.0),
        )
            .prop_map(|(p, (angle, slope), s)| {
                let norm = (1.0 + slope * slope).sqrt();
                (
                    p,
                    vec![angle.cos() / norm, angle.sin() / norm, slope / norm],
                    s,
                )
            })
    })
}

/// A straight line is reproduced exactly (up to rounding) by the natural and clamped (end
/// tangents `d`) cubic splines, the Catmull-Rom spline and the Lagrange curve under
/// chord-length parameterization: `c(u) = q_0 + u·d`, `c' = d`, `c'' = c''' = 0`. Under
/// uniform parameterization the curve still stays on the line (its derivatives are parallel
/// to `d`).
fn check_line<P: Point>(p0: &[f64], d: &[f64], s: &[f64]) {
    let dim = P::DIM;
    let d: Vec<f64> = {
        let v = d[..dim].to_vec();
        let n = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        v.iter().map(|x| x / n).collect()
    };
    let data: Vec<Vec<f64>> = s
        .iter()
        .map(|&si| (0..dim).map(|i| p0[i] + si * d[i]).collect())
        .collect();
    let pd: Vec<P> = round_pts(&data);
    let q0 = to_vec(pd[0]);
    let mut kinds = vec![Kind::Natural, Kind::Clamped, Kind::CatmullRom];
    if s.len() <= 6 {
        kinds.push(Kind::Lagrange);
    }
    for param in [Parameterization::ChordLength, Parameterization::Uniform] {
        let case = Case {
            pts: data.clone(),
            tangents: vec![d.clone(); s.len()],
            nodes: Nodes::Param(param),
            tension: 0.0,
        };
        for &kind in &kinds {
            if param == Parameterization::Uniform && kind == Kind::Clamped {
                continue; // end tangents d do not match the uniform speed
            }
            let c = build::<P>(kind, &case);
            // The rounded points lie on the line only up to ε·|p| (fixed-point: 2^-f), so the
            // line is checked with the curve's own tolerance.
            for u in sample_params(&c.nodes) {
                let uc = u.clamp(c.nodes[0], c.nodes[c.nodes.len() - 1]);
                for k in 0..4 {
                    let got = (c.deriv)(u, k);
                    let err = if param == Parameterization::ChordLength {
                        let want: Vec<f64> = match k {
                            0 => q0.iter().zip(&d).map(|(a, b)| a + uc * b).collect(),
                            1 => d.clone(),
                            _ => vec![0.0; dim],
                        };
                        max_diff(&got, &want)
                    } else {
                        // distance from the line (k = 0) or the component normal to d
                        let v: Vec<f64> = if k == 0 {
                            got.iter().zip(&q0).map(|(a, b)| a - b).collect()
                        } else {
                            got.clone()
                        };
                        let along: f64 = v.iter().zip(&d).map(|(a, b)| a * b).sum();
                        let normal: Vec<f64> =
                            v.iter().zip(&d).map(|(a, b)| a - along * b).collect();
                        max_diff(&normal, &vec![0.0; dim])
                    };
                    // Chord-length nodes of the rounded points are off the line's arc length by
                    // ~ε·|p|; that shifts c(u) along d by as much: a few ε·scale_0 more.
                    let tol = c.tol[k] * if k == 0 { 4.0 } else { 1.0 };
                    assert!(
                        err <= tol,
                        "{kind:?} {param:?} {}: u = {u}, k = {k}: {got:?} ({err:e} > {tol:e})",
                        type_label::<P>()
                    );
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn interpolates_at_nodes(case in open_case(3..=6)) {
        check_interpolation::<[f64; 2]>(&case, &OPEN_KINDS);
        check_interpolation::<DVec3>(&case, &OPEN_KINDS);
        check_interpolation::<Vec3>(&case, &OPEN_KINDS);
        check_interpolation::<[I32F32; 3]>(&case, &OPEN_KINDS);
        check_interpolation::<[I16F16; 2]>(&case, &OPEN_KINDS);
    }

    #[test]
    fn periodic_interpolates_at_nodes(case in closed_case(2..=CAP - 1)) {
        check_interpolation::<[f64; 3]>(&case, &[Kind::Periodic]);
        check_interpolation::<[f32; 2]>(&case, &[Kind::Periodic]);
        check_interpolation::<[I16F16; 2]>(&case, &[Kind::Periodic]);
    }

    #[test]
    fn hermite_tangents_and_c1(case in open_case(2..=CAP)) {
        check_tangents::<[f64; 3]>(&case);
        check_tangents::<Vec3>(&case);
        check_tangents::<[I32F32; 2]>(&case);
        check_tangents::<[I16F16; 2]>(&case);
    }

    #[test]
    fn cubic_spline_is_c2(case in open_case(2..=CAP), closed in closed_case(2..=CAP - 1)) {
        for ends in [Ends::Natural, Ends::Clamped] {
            check_c2::<[f64; 2]>(&case, ends);
            check_c2::<DVec3>(&case, ends);
            check_c2::<[f32; 3]>(&case, ends);
            check_c2::<[I32F32; 2]>(&case, ends);
            check_c2::<[I16F16; 2]>(&case, ends);
        }
        check_c2::<[f64; 3]>(&closed, Ends::Periodic);
        check_c2::<Vec3>(&closed, Ends::Periodic);
        check_c2::<[I16F16; 2]>(&closed, Ends::Periodic);
    }

    #[test]
    fn parabolic_blend_is_c1(case in open_case(3..=CAP)) {
        check_parabolic_c1::<[f64; 2]>(&case);
        check_parabolic_c1::<DVec3>(&case);
        check_parabolic_c1::<[f32; 2]>(&case);
        check_parabolic_c1::<[I32F32; 3]>(&case);
    }

    #[test]
    fn affine_invariance(case in open_case(3..=6), general in affine(false), rigid in affine(true)) {
        let t = match case.nodes {
            Nodes::Param(Parameterization::ChordLength | Parameterization::Centripetal) => &rigid,
            _ => &general,
        };
        check_affine::<[f64; 2]>(&case, t, &OPEN_KINDS);
        check_affine::<DVec3>(&case, t, &OPEN_KINDS);
    }

    #[test]
    fn periodic_affine_invariance(case in closed_case(2..=CAP - 1), general in affine(false), rigid in affine(true)) {
        let t = match case.nodes {
            Nodes::Param(Parameterization::ChordLength | Parameterization::Centripetal) => &rigid,
            _ => &general,
        };
        check_affine::<[f64; 3]>(&case, t, &[Kind::Periodic]);
    }

    #[test]
    fn straight_line_is_reproduced((p, d, s) in line()) {
        check_line::<[f64; 2]>(&p, &d, &s);
        check_line::<DVec3>(&p, &d, &s);
        check_line::<[f32; 3]>(&p, &d, &s);
        check_line::<[I32F32; 2]>(&p, &d, &s);
        check_line::<[I16F16; 3]>(&p, &d, &s);
    }
}
