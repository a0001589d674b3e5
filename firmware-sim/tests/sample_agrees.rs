//! `strak-sim sample` against an independent f64 evaluation (strak-ref) for every curve kind.
//!
//! Tolerances (issue: "max error ≤ 1e−10 × the extent of the points in f64, ≤ 1e−5 × the
//! extent in f32, and the documented bound in fixed-point"). Positions are compared against the
//! extent of the points (the largest coordinate range); the derivative of order k against the
//! larger of the extent and the largest |coordinate| of the reference's k-th derivative, because
//! derivatives scale with 1/Δu^k and their rounding errors with them.
//! Fixed-point (`I32F32`, resolution 2⁻³² ≈ 2.3·10⁻¹⁰): the documented bound is 1e−8 relative
//! (about 40 units in the last place at unit scale); measured: at most 1.3e−9 (NURBS circle,
//! second derivative), 5e−10 for positions.

use std::path::{Path, PathBuf};
use std::process::Command;

use strak_ref as r;
use strak_sim::curve_file::{BoundaryName, CurveFile};
use strak_sim::number::NumberFormat;
use strak_sim::sample::{SampleOptions, header, sample_rows};

const DERIVATIVES: usize = 2;
const COUNT: usize = 257;

fn examples() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    files
}

/// The reference evaluation of a curve file: domain and k-th derivative at u.
struct Reference {
    domain: (f64, f64),
    eval: Box<dyn Fn(f64, usize) -> Vec<f64>>,
}

fn nodes_or_chord(file: &CurveFile) -> Vec<f64> {
    file.params()
        .map(<[f64]>::to_vec)
        .unwrap_or_else(|| r::chord_length_nodes(file.points()))
}

/// A B-spline or NURBS: degree, knots, closed, weights.
fn bspline_reference(
    pts: Vec<Vec<f64>>,
    g: usize,
    knots: Option<Vec<f64>>,
    closed: bool,
    weights: Option<Vec<f64>>,
) -> Reference {
    let n = pts.len();
    if closed {
        let knots = knots.unwrap_or_else(|| r::periodic_uniform_knots(n));
        let domain = (knots[0], knots[n]);
        return Reference {
            domain,
            eval: Box::new(move |u, k| r::closed_bspline_deriv(g, &pts, &knots, u, k)),
        };
    }
    let knots = knots.unwrap_or_else(|| r::clamped_uniform_knots(g, n, 0.0, 1.0));
    let domain = r::bspline_domain(&knots, g);
    Reference {
        domain,
        eval: Box::new(move |u, k| match &weights {
            Some(w) => r::nurbs_deriv(&knots, g, &pts, w, u, k),
            None => r::bspline_deriv(&knots, g, &pts, u, k),
        }),
    }
}

/// A Hermite spline through the nodes with the given (or Catmull-Rom) tangents.
fn hermite_reference(file: &CurveFile, tangents: Option<Vec<Vec<f64>>>) -> Reference {
    let pts = file.points().to_vec();
    let nodes = nodes_or_chord(file);
    let n = pts.len();
    let tangents = tangents.unwrap_or_else(|| r::catmull_rom_tangents(&nodes, &pts));
    Reference {
        domain: (nodes[0], nodes[n - 1]),
        eval: Box::new(move |u, k| r::hermite_spline_deriv(&nodes, &pts, &tangents, u, k)),
    }
}

fn reference(file: &CurveFile) -> Reference {
    let pts = file.points().to_vec();
    let n = pts.len();
    match file {
        CurveFile::Bezier(_) => Reference {
            domain: (0.0, 1.0),
            eval: Box::new(move |u, k| r::bezier_deriv(&pts, u, k)),
        },
        CurveFile::BezierChain(c) => {
            let g = c.degree;
            Reference {
                domain: (0.0, ((n - 1) / g) as f64),
                eval: Box::new(move |u, k| r::bezier_chain_deriv(&pts, g, u, k)),
            }
        }
        CurveFile::Bspline(b) => bspline_reference(pts, b.degree, b.knots.clone(), b.closed, None),
        CurveFile::Nurbs(f) => bspline_reference(
            pts,
            f.degree,
            f.knots.clone(),
            false,
            Some(f.weights.clone()),
        ),
        CurveFile::Lagrange(_) => {
            let nodes = nodes_or_chord(file);
            Reference {
                domain: (nodes[0], nodes[n - 1]),
                eval: Box::new(move |u, k| {
                    r::lagrange_deriv(&nodes, &pts, u.clamp(nodes[0], nodes[n - 1]), k)
                }),
            }
        }
        CurveFile::Hermite(h) => hermite_reference(file, Some(h.tangents.clone())),
        CurveFile::CatmullRom(_) => hermite_reference(file, None),
        CurveFile::CubicSpline(c) => {
            let nodes = nodes_or_chord(file);
            let spline = match c.boundary {
                BoundaryName::Natural => r::CubicSplineRef::natural(&nodes, &pts),
                BoundaryName::Clamped => r::CubicSplineRef::clamped(
                    &nodes,
                    &pts,
                    c.start_tangent.as_ref().unwrap(),
                    c.end_tangent.as_ref().unwrap(),
                ),
                BoundaryName::Periodic => r::CubicSplineRef::periodic(&nodes, &pts),
            };
            Reference {
                domain: (nodes[0], nodes[n - 1]),
                eval: Box::new(move |u, k| spline.deriv(u, k)),
            }
        }
        CurveFile::ParabolicBlend(_) => Reference {
            domain: (0.0, (n - 1) as f64),
            eval: Box::new(move |u, k| r::parabolic_blend_deriv(&pts, u, k)),
        },
    }
}

fn extent(points: &[Vec<f64>]) -> f64 {
    let dim = points[0].len();
    (0..dim)
        .map(|i| {
            let lo = points.iter().map(|p| p[i]).fold(f64::INFINITY, f64::min);
            let hi = points
                .iter()
                .map(|p| p[i])
                .fold(f64::NEG_INFINITY, f64::max);
            hi - lo
        })
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE)
}

/// Largest error of each derivative order, relative to its scale.
fn relative_errors(file: &CurveFile, number: NumberFormat) -> Vec<f64> {
    let options = SampleOptions {
        count: COUNT,
        derivatives: DERIVATIVES,
        number,
    };
    let rows = sample_rows(file, &options).unwrap();
    let reference = reference(file);
    let dim = file.dim();
    let ext = extent(file.points());
    let (a, b) = reference.domain;
    assert_eq!(rows.len(), COUNT);
    // The domain ends are computed in the curve's own number type (chord lengths, knots), so
    // they agree with the f64 reference to that type's resolution.
    let u_tol = match number {
        NumberFormat::F64 => 1e-12,
        NumberFormat::F32 => 1e-6,
        NumberFormat::Q40 => 1e-8,
    } * (b - a).abs().max(1.0);
    assert!(
        (rows[0][0] - a).abs() <= u_tol,
        "first u {} vs {a}",
        rows[0][0]
    );
    assert!(
        (rows[COUNT - 1][0] - b).abs() <= u_tol,
        "last u {} vs {b}",
        rows[COUNT - 1][0]
    );
    (0..=DERIVATIVES)
        .map(|k| {
            let refs: Vec<Vec<f64>> = rows.iter().map(|row| (reference.eval)(row[0], k)).collect();
            let scale = refs.iter().flatten().fold(ext, |m, v| m.max(v.abs()));
            rows.iter()
                .zip(&refs)
                .flat_map(|(row, want)| {
                    let got = &row[1 + k * dim..1 + (k + 1) * dim];
                    got.iter().zip(want).map(|(g, w)| (g - w).abs())
                })
                .fold(0.0, f64::max)
                / scale
        })
        .collect()
}

fn check(number: NumberFormat, tolerance: f64) {
    let files = examples();
    assert!(files.len() >= 10, "examples missing: {files:?}");
    for path in files {
        let file = CurveFile::parse(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let errors = relative_errors(&file, number);
        eprintln!(
            "{number:?} {}: relative errors by derivative order {errors:?}",
            path.file_name().unwrap_or_default().to_string_lossy()
        );
        for (k, e) in errors.iter().enumerate() {
            assert!(
                *e <= tolerance,
                "{}: derivative {k} in {number:?}: relative error {e:e} > {tolerance:e}",
                path.display()
            );
        }
    }
}

#[test]
fn f64_agrees_with_the_reference_within_1e_10() {
    check(NumberFormat::F64, 1e-10);
}

#[test]
fn f32_agrees_with_the_reference_within_1e_5() {
    check(NumberFormat::F32, 1e-5);
}

#[test]
fn fixed_point_agrees_with_the_reference_within_1e_8() {
    check(NumberFormat::Q40, 1e-8);
}

#[test]
fn one_and_four_coordinates() {
    for text in [
        "kind = \"bezier\"\npoints = [[0.0], [2.0], [1.0]]",
        "kind = \"bezier-chain\"\ndegree = 2\npoints = [[0.0], [2.0], [1.0], [0.0], [3.0]]",
        "kind = \"bezier-chain\"\ndegree = 1\npoints = [[0,0,0,0],[1,2,3,4],[2,0,1,0]]",
        "kind = \"bspline\"\ndegree = 2\npoints = [[0,0,0,0],[1,2,3,4],[2,0,1,0],[3,1,0,2]]",
        "kind = \"bspline\"\ndegree = 2\npoints = [[0,0,0,0,0],[1,2,3,4,5],[2,0,1,0,2],[3,1,0,2,0]]",
        "kind = \"bezier-chain\"\ndegree = 3\npoints = [[0,0,0,0,0,0],[1,2,3,4,5,6],[2,0,1,0,2,1],[3,1,0,2,0,3]]",
        "kind = \"nurbs\"\ndegree = 2\npoints = [[0,0,0,0,0,0],[1,2,3,4,5,6],[2,0,1,0,2,1]]\nweights = [1, 0.5, 1]",
    ] {
        let file = CurveFile::parse(text).unwrap();
        for (number, tol) in [
            (NumberFormat::F64, 1e-10),
            (NumberFormat::F32, 1e-5),
            (NumberFormat::Q40, 1e-8),
        ] {
            for (k, e) in relative_errors(&file, number).iter().enumerate() {
                assert!(*e <= tol, "{text}: derivative {k} {number:?}: {e:e}");
            }
        }
    }
}

/// More points than the small capacity (256), within the bounds of the example files: a wavy
/// cubic B-spline of 300 de Boor points and a Catmull-Rom spline through 300 points, in every
/// format. Knots and nodes are integers, exact in every format (fine knots of a unit domain
/// would add their own rounding, `~n·ε` relative in the derivatives).
#[test]
fn more_than_256_points() {
    let n = 300;
    let list = |v: Vec<String>| v.join(", ");
    let wave = list(
        (0..n)
            .map(|i| format!("[{i}, {}]", (i as f64 * 0.3).sin()))
            .collect(),
    );
    let knots = list(
        (0..n + 4)
            .map(|i| (i.clamp(3, n) - 3).to_string())
            .collect(),
    );
    let nodes = list((0..n).map(|i| i.to_string()).collect());
    for text in [
        format!("kind = \"bspline\"\ndegree = 3\npoints = [{wave}]\nknots = [{knots}]"),
        format!("kind = \"catmull-rom\"\npoints = [{wave}]\nparams = [{nodes}]"),
    ] {
        let file = CurveFile::parse(&text).unwrap();
        assert_eq!(file.points().len(), n);
        for (number, tol) in [
            (NumberFormat::F64, 1e-10),
            (NumberFormat::F32, 1e-5),
            (NumberFormat::Q40, 1e-8),
        ] {
            for (k, e) in relative_errors(&file, number).iter().enumerate() {
                assert!(*e <= tol, "{n} points: derivative {k} {number:?}: {e:e}");
            }
        }
    }
}

/// The command line writes the same numbers as the library, with the documented header.
#[test]
fn command_line_writes_the_library_rows() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/hermite.toml");
    let out = Command::new(env!("CARGO_BIN_EXE_strak-sim"))
        .args([
            "sample",
            path.to_str().unwrap(),
            "--count",
            "9",
            "--derivatives",
            "1",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some(header(3, 1).join(",").as_str()));
    let file = CurveFile::parse(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let rows = sample_rows(
        &file,
        &SampleOptions {
            count: 9,
            derivatives: 1,
            number: NumberFormat::F64,
        },
    )
    .unwrap();
    let parsed: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
        .collect();
    assert_eq!(parsed, rows);
}

fn run_bad(text: &str) -> String {
    let dir = std::env::temp_dir().join(format!("strak-sim-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(format!(
        "{:x}.toml",
        text.len() * 31 + text.bytes().map(usize::from).sum::<usize>()
    ));
    std::fs::write(&path, text).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_strak-sim"))
        .args(["sample", path.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(!out.status.success(), "accepted a bad file: {text}");
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(!stderr.contains("panicked"), "panic for {text}: {stderr}");
    assert_eq!(
        stderr.trim_end().lines().count(),
        1,
        "one error line: {stderr}"
    );
    stderr
}

/// Bad files: one clear error line naming the field and a non-zero exit; never a panic.
#[test]
fn bad_files_name_the_field() {
    let cases = [
        (
            "kind = \"bspline\"\ndegree = 3\npoints = [[0,0],[1,1],[2,0],[3,1]]\nknots = [0,0,0,0,2,1,1,1]",
            "knots",
        ),
        (
            "kind = \"bspline\"\ndegree = 3\npoints = [[0,0],[1,1],[2,0],[3,1]]\nknots = [0,0,0,1,1,1]",
            "knots",
        ),
        (
            "kind = \"bspline\"\ndegree = 3\npoints = [[0,0],[1,1]]",
            "points",
        ),
        (
            "kind = \"nurbs\"\ndegree = 1\npoints = [[0,0],[1,1]]\nweights = [1, -1]",
            "weights",
        ),
        (
            "kind = \"lagrange\"\npoints = [[0,0],[1,1],[2,2]]\nparams = [0, 2, 1]",
            "params",
        ),
        (
            "kind = \"cubic-spline\"\npoints = [[0,0],[0,0],[2,2]]",
            "points",
        ),
        (
            "kind = \"cubic-spline\"\npoints = [[0,0],[1,1],[2,2]]\nboundary = \"periodic\"",
            "points",
        ),
        (
            "kind = \"hermite\"\npoints = [[0,0],[1,1]]\ntangents = [[1,0]]",
            "tangents",
        ),
        (
            "kind = \"bezier\"\npoints = [[0,0],[1,1]]\nknots = [0,1]",
            "knots",
        ),
        ("kind = \"bezier\"\npoints = [[0, 0],[1, nan]]", "points"),
        (
            "kind = \"bezier-chain\"\ndegree = 2\npoints = [[0,0],[1,1],[2,0],[3,1]]",
            "points",
        ),
        ("kind = \"bezier-chain\"\npoints = [[0,0],[1,1]]", "degree"),
        (
            "kind = \"bezier-chain\"\ndegree = 6\npoints = [[0],[1],[2],[3],[4],[5],[6]]",
            "degree",
        ),
        ("kind = \"bezier\"\npoints = [[0, 0],[1, 1e308]]", "points"),
        (
            "kind = \"parabolic-blend\"\npoints = [[0,0],[1,1]]",
            "points",
        ),
        ("kind = \"bezier\"\npoints = []", "points"),
        ("kind = \"bezier\"", "points"),
        ("kind = 3\npoints = [[0]]", "kind"),
    ];
    for (text, field) in cases {
        let err = run_bad(text);
        assert!(
            err.contains(field),
            "{text}: error does not name `{field}`: {err}"
        );
    }
}
