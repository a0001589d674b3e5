//! The curve file of `strak-sim sample`: one curve in TOML, a serde enum tagged by `kind`.
//!
//! ```toml
//! kind = "bspline"   # bezier | bezier-chain | bspline | nurbs | lagrange | hermite | catmull-rom | cubic-spline | parabolic-blend
//! points = [[0.0, 0.0, 0.0], [1.0, 2.0, 0.5], [2.0, 0.0, 1.0], [3.0, 1.0, 0.0]]
//! degree = 3
//! ```
//!
//! Each kind takes its own fields; serde rejects a missing, unknown or mistyped field. What
//! serde cannot say (the lengths and dimensions of the lists, finite values, the capacities)
//! is [`CurveFile::check`]. Every problem is reported as a [`FieldError`] naming the field
//! (`points[3][1]`, `knots`, …), so that the command line prints one clear line.

use std::fmt;

use serde::Deserialize;
use strak_curves::BSPLINE_MAX_DEGREE;

use crate::axes::MAX_AXES;
use crate::toml_error::{Tagged, locate};

/// The largest number of points (control points, interpolation points) of a curve.
pub const MAX_POINTS: usize = 4_096;

/// The largest number of control points of a Bézier curve (degree 11).
pub const BEZIER_MAX_POINTS: usize = 12;

/// The largest segment degree of a Bézier chain.
pub const BEZIER_CHAIN_MAX_DEGREE: usize = 5;

// Every curve kind takes up to MAX_AXES coordinates; strak-curves' points hold up to MAX_DIM.
const _: () = assert!(MAX_AXES <= strak_curves::MAX_DIM);

/// The longest knot vector: an open B-spline of [`MAX_POINTS`] points and the highest degree.
pub const MAX_KNOTS: usize = MAX_POINTS + BSPLINE_MAX_DEGREE + 1;

/// The curve kinds of the file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// One Bézier curve; the degree is the number of points minus one.
    Bezier,
    /// A piecewise Bézier curve: `n` segments of the given degree in the composite
    /// representation, `n·degree + 1` points, consecutive segments sharing their join point.
    BezierChain,
    /// A B-spline with de Boor points.
    Bspline,
    /// A NURBS curve (B-spline with weights).
    Nurbs,
    /// The Lagrange interpolation polynomial through the points.
    Lagrange,
    /// A cubic Hermite spline with given tangents.
    Hermite,
    /// A Catmull-Rom spline (Hermite spline with central-difference tangents).
    CatmullRom,
    /// An interpolating C² cubic spline.
    CubicSpline,
    /// Parabolic blending (Overhauser), node i at u = i.
    ParabolicBlend,
}

impl Kind {
    /// The name used in the file.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Bezier => "bezier",
            Kind::BezierChain => "bezier-chain",
            Kind::Bspline => "bspline",
            Kind::Nurbs => "nurbs",
            Kind::Lagrange => "lagrange",
            Kind::Hermite => "hermite",
            Kind::CatmullRom => "catmull-rom",
            Kind::CubicSpline => "cubic-spline",
            Kind::ParabolicBlend => "parabolic-blend",
        }
    }
}

/// End conditions of an interpolating cubic spline.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum BoundaryName {
    /// f'' = 0 at both ends.
    #[default]
    Natural,
    /// Given end tangents `start_tangent` and `end_tangent`.
    Clamped,
    /// Closed curve; the last point repeats the first.
    Periodic,
}

/// `kind = "bezier"`.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BezierFields {
    /// 1 to [`BEZIER_MAX_POINTS`] control points.
    pub points: Vec<Vec<f64>>,
    /// Optional; must equal points − 1.
    pub degree: Option<usize>,
}

/// `kind = "bezier-chain"`.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BezierChainFields {
    /// `n·degree + 1` points, consecutive segments sharing their join point.
    pub points: Vec<Vec<f64>>,
    /// The segments' degree, 1 to [`BEZIER_CHAIN_MAX_DEGREE`].
    pub degree: usize,
}

/// `kind = "bspline"`.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BsplineFields {
    /// The de Boor points.
    pub points: Vec<Vec<f64>>,
    /// The degree.
    pub degree: usize,
    /// The knot vector (default: clamped uniform over `[0, 1]`; closed: uniform periodic).
    pub knots: Option<Vec<f64>>,
    /// A closed (periodic) B-spline.
    #[serde(default)]
    pub closed: bool,
}

/// `kind = "nurbs"`.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NurbsFields {
    /// The control points.
    pub points: Vec<Vec<f64>>,
    /// The degree.
    pub degree: usize,
    /// The knot vector (default: clamped uniform over `[0, 1]`).
    pub knots: Option<Vec<f64>>,
    /// One weight per point, all > 0.
    pub weights: Vec<f64>,
}

/// `kind = "lagrange"` and `kind = "catmull-rom"`: points and optional nodes.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InterpolationFields {
    /// The points the curve passes through.
    pub points: Vec<Vec<f64>>,
    /// The nodes, one per point, increasing (default: chord length).
    pub params: Option<Vec<f64>>,
}

/// `kind = "hermite"`.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HermiteFields {
    /// The points the curve passes through.
    pub points: Vec<Vec<f64>>,
    /// The nodes, one per point, increasing (default: chord length).
    pub params: Option<Vec<f64>>,
    /// The tangents (derivatives with respect to u), one per point.
    pub tangents: Vec<Vec<f64>>,
}

/// `kind = "cubic-spline"`.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CubicSplineFields {
    /// The points the curve passes through.
    pub points: Vec<Vec<f64>>,
    /// The nodes, one per point, increasing (default: chord length).
    pub params: Option<Vec<f64>>,
    /// The end condition (default natural).
    #[serde(default)]
    pub boundary: BoundaryName,
    /// Clamped: the derivative at the start.
    pub start_tangent: Option<Vec<f64>>,
    /// Clamped: the derivative at the end.
    pub end_tangent: Option<Vec<f64>>,
}

/// `kind = "parabolic-blend"`.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointsFields {
    /// The points the curve passes through, node i at u = i.
    pub points: Vec<Vec<f64>>,
}

/// A curve file: the fields of its `kind`.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum CurveFile {
    /// [`Kind::Bezier`].
    Bezier(BezierFields),
    /// [`Kind::BezierChain`].
    BezierChain(BezierChainFields),
    /// [`Kind::Bspline`].
    Bspline(BsplineFields),
    /// [`Kind::Nurbs`].
    Nurbs(NurbsFields),
    /// [`Kind::Lagrange`].
    Lagrange(InterpolationFields),
    /// [`Kind::Hermite`].
    Hermite(HermiteFields),
    /// [`Kind::CatmullRom`].
    CatmullRom(InterpolationFields),
    /// [`Kind::CubicSpline`].
    CubicSpline(CubicSplineFields),
    /// [`Kind::ParabolicBlend`].
    ParabolicBlend(PointsFields),
}

/// A problem with one field of the file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FieldError {
    /// The field's path in the file (`points`, `points[3][1]`, `knots`, …).
    pub field: String,
    /// What is wrong with it.
    pub message: String,
}

impl FieldError {
    /// A new error for `field`.
    pub fn new(field: impl Into<String>, message: impl Into<String>) -> Self {
        FieldError {
            field: field.into(),
            message: message.into(),
        }
    }
}

impl fmt::Display for FieldError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "field `{}`: {}", self.field, self.message)
    }
}

impl std::error::Error for FieldError {}

fn fail<T>(field: impl Into<String>, message: impl Into<String>) -> Result<T, FieldError> {
    Err(FieldError::new(field, message))
}

/// Every value of `values` is finite (the error names the entry `field[i]`).
fn finite(field: &str, values: &[f64]) -> Result<(), FieldError> {
    match values.iter().position(|v| !v.is_finite()) {
        Some(i) => fail(
            format!("{field}[{i}]"),
            format!("{} is not a finite number", values[i]),
        ),
        None => Ok(()),
    }
}

/// One entry of `field` per point.
fn per_point(field: &str, len: usize, n: usize, entry: &str) -> Result<(), FieldError> {
    if len == n {
        Ok(())
    } else {
        fail(
            field,
            format!("one {entry} per point: {n} points, {len} {entry}s"),
        )
    }
}

/// Vectors of `dim` finite coordinates (`field[i][j]` named on error).
fn vectors(field: &str, rows: &[Vec<f64>], dim: usize) -> Result<(), FieldError> {
    for (i, row) in rows.iter().enumerate() {
        if row.len() != dim {
            return fail(
                format!("{field}[{i}]"),
                format!("has {} coordinates, points have {dim}", row.len()),
            );
        }
        finite(&format!("{field}[{i}]"), row)?;
    }
    Ok(())
}

/// The points: 1 to [`MAX_POINTS`] of them, 1 to [`MAX_AXES`] finite coordinates each, all
/// of the same dimension.
fn check_points(points: &[Vec<f64>]) -> Result<(), FieldError> {
    let Some(first) = points.first() else {
        return fail("points", "the path is empty: give at least one point");
    };
    if points.len() > MAX_POINTS {
        return fail(
            "points",
            format!(
                "{} points: strak-sim builds curves of at most {MAX_POINTS} points (its curves \
                 live in fixed-capacity storage, as on the device)",
                points.len()
            ),
        );
    }
    let dim = first.len();
    if !(1..=MAX_AXES).contains(&dim) {
        return fail(
            "points[0]",
            format!("points need 1 to {MAX_AXES} coordinates (axes), the first has {dim}"),
        );
    }
    vectors("points", points, dim)
}

fn check_knots(knots: Option<&[f64]>) -> Result<(), FieldError> {
    let Some(knots) = knots else { return Ok(()) };
    if knots.len() > MAX_KNOTS {
        return fail(
            "knots",
            format!(
                "{} knots: a B-spline takes at most {MAX_KNOTS} ({MAX_POINTS} points + degree \
                 {BSPLINE_MAX_DEGREE} + 1)",
                knots.len()
            ),
        );
    }
    finite("knots", knots)
}

fn check_params(params: Option<&[f64]>, n: usize) -> Result<(), FieldError> {
    let Some(params) = params else { return Ok(()) };
    per_point("params", params.len(), n, "node")?;
    finite("params", params)
}

fn check_bezier_chain(degree: usize, n: usize) -> Result<(), FieldError> {
    if !(1..=BEZIER_CHAIN_MAX_DEGREE).contains(&degree) {
        return fail(
            "degree",
            format!(
                "a Bézier chain takes segments of degree 1 to {BEZIER_CHAIN_MAX_DEGREE}, not \
                 {degree}"
            ),
        );
    }
    if n < degree + 1 || !(n - 1).is_multiple_of(degree) {
        let g = degree;
        return fail(
            "points",
            format!(
                "a Bézier chain of degree {g} has n·{g} + 1 points ({}, {}, {}, …), not {n}",
                g + 1,
                2 * g + 1,
                3 * g + 1
            ),
        );
    }
    Ok(())
}

fn check_bezier(b: &BezierFields) -> Result<(), FieldError> {
    let n = b.points.len();
    if n > BEZIER_MAX_POINTS {
        return fail(
            "points",
            format!("a Bézier curve takes 1 to {BEZIER_MAX_POINTS} points, not {n}"),
        );
    }
    match b.degree {
        Some(g) if g + 1 != n => fail(
            "degree",
            format!(
                "a Bézier curve with {n} points has degree {}, not {g}",
                n - 1
            ),
        ),
        _ => Ok(()),
    }
}

fn check_cubic_spline(c: &CubicSplineFields, dim: usize) -> Result<(), FieldError> {
    let clamped = c.boundary == BoundaryName::Clamped;
    for (field, v) in [
        ("start_tangent", &c.start_tangent),
        ("end_tangent", &c.end_tangent),
    ] {
        match v {
            Some(_) if !clamped => return fail(field, "only with boundary = \"clamped\""),
            None if clamped => return fail(field, "required with boundary = \"clamped\""),
            Some(v) if v.len() != dim => {
                return fail(
                    field,
                    format!("has {} coordinates, points have {dim}", v.len()),
                );
            }
            Some(v) => finite(field, v)?,
            None => {}
        }
    }
    Ok(())
}

impl CurveFile {
    /// Parses TOML text and checks it ([`CurveFile::check`]); the error names the field.
    ///
    /// ```
    /// use strak_sim::curve_file::{CurveFile, Kind};
    /// let file = CurveFile::parse("kind = \"bezier\"\npoints = [[0, 0], [1, 2]]").unwrap();
    /// assert_eq!((file.kind(), file.dim()), (Kind::Bezier, 2));
    /// let e = CurveFile::parse("kind = \"bezier\"\npoints = [[0, 0], [1, inf]]").unwrap_err();
    /// assert_eq!(e.field, "points[1][1]");
    /// ```
    pub fn parse(text: &str) -> Result<Self, FieldError> {
        let file: CurveFile = toml::from_str(text).map_err(|e| {
            let at = locate(text, &e, &[Self::TAGGED]);
            FieldError::new(at.field, at.message)
        })?;
        file.check()?;
        Ok(file)
    }

    /// The whole file as a table tagged by `kind` (for [`locate`]).
    pub(crate) const TAGGED: Tagged = Tagged {
        table: "",
        diagnose: Self::diagnose,
    };

    /// Deserializes the fields of `kind` from `text` (the table without its `kind`).
    pub(crate) fn diagnose(kind: &str, text: &str) -> Option<toml::de::Error> {
        fn err<T: serde::de::DeserializeOwned>(text: &str) -> Option<toml::de::Error> {
            toml::from_str::<T>(text).err()
        }
        match kind {
            "bezier" => err::<BezierFields>(text),
            "bezier-chain" => err::<BezierChainFields>(text),
            "bspline" => err::<BsplineFields>(text),
            "nurbs" => err::<NurbsFields>(text),
            "lagrange" | "catmull-rom" => err::<InterpolationFields>(text),
            "hermite" => err::<HermiteFields>(text),
            "cubic-spline" => err::<CubicSplineFields>(text),
            "parabolic-blend" => err::<PointsFields>(text),
            _ => None,
        }
    }

    /// The curve kind.
    pub fn kind(&self) -> Kind {
        match self {
            CurveFile::Bezier(_) => Kind::Bezier,
            CurveFile::BezierChain(_) => Kind::BezierChain,
            CurveFile::Bspline(_) => Kind::Bspline,
            CurveFile::Nurbs(_) => Kind::Nurbs,
            CurveFile::Lagrange(_) => Kind::Lagrange,
            CurveFile::Hermite(_) => Kind::Hermite,
            CurveFile::CatmullRom(_) => Kind::CatmullRom,
            CurveFile::CubicSpline(_) => Kind::CubicSpline,
            CurveFile::ParabolicBlend(_) => Kind::ParabolicBlend,
        }
    }

    /// The points (control points or interpolation points).
    pub fn points(&self) -> &[Vec<f64>] {
        match self {
            CurveFile::Bezier(f) => &f.points,
            CurveFile::BezierChain(f) => &f.points,
            CurveFile::Bspline(f) => &f.points,
            CurveFile::Nurbs(f) => &f.points,
            CurveFile::Lagrange(f) | CurveFile::CatmullRom(f) => &f.points,
            CurveFile::Hermite(f) => &f.points,
            CurveFile::CubicSpline(f) => &f.points,
            CurveFile::ParabolicBlend(f) => &f.points,
        }
    }

    /// The interpolation nodes, where the kind takes them and the file gives them.
    pub fn params(&self) -> Option<&[f64]> {
        match self {
            CurveFile::Lagrange(f) | CurveFile::CatmullRom(f) => f.params.as_deref(),
            CurveFile::Hermite(f) => f.params.as_deref(),
            CurveFile::CubicSpline(f) => f.params.as_deref(),
            _ => None,
        }
    }

    /// The knot vector, where the kind takes one and the file gives it.
    pub fn knots(&self) -> Option<&[f64]> {
        match self {
            CurveFile::Bspline(f) => f.knots.as_deref(),
            CurveFile::Nurbs(f) => f.knots.as_deref(),
            _ => None,
        }
    }

    /// The number of coordinates per point (1 to [`MAX_AXES`]).
    pub fn dim(&self) -> usize {
        self.points().first().map_or(0, Vec::len)
    }

    /// Checks what serde cannot: 1 to [`MAX_POINTS`] points of 1 to [`MAX_AXES`] finite
    /// coordinates each, lists of one entry per point, the degree against the points, and the
    /// end tangents of a clamped cubic spline. The curve constructors check the mathematics.
    pub fn check(&self) -> Result<(), FieldError> {
        let points = self.points();
        check_points(points)?;
        let (n, dim) = (points.len(), self.dim());
        check_knots(self.knots())?;
        check_params(self.params(), n)?;
        match self {
            CurveFile::Bezier(b) => check_bezier(b),
            CurveFile::BezierChain(c) => check_bezier_chain(c.degree, n),
            CurveFile::Nurbs(f) => {
                per_point("weights", f.weights.len(), n, "weight")?;
                finite("weights", &f.weights)
            }
            CurveFile::Hermite(h) => {
                per_point("tangents", h.tangents.len(), n, "tangent")?;
                vectors("tangents", &h.tangents, dim)
            }
            CurveFile::CubicSpline(c) => check_cubic_spline(c, dim),
            _ => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> FieldError {
        CurveFile::parse(text).unwrap_err()
    }

    #[test]
    fn parses_the_documented_example() {
        let f = CurveFile::parse(
            "kind = \"bspline\"\npoints = [[0.0, 0.0, 0.0], [1.0, 2.0, 0.5], [2.0, 0.0, 1.0], [3.0, 1.0, 0.0]]\ndegree = 3\nknots = [0, 0, 0, 0, 1, 1, 1, 1]\n",
        )
        .unwrap();
        assert_eq!(f.kind(), Kind::Bspline);
        assert_eq!(f.dim(), 3);
        assert_eq!(
            f.knots(),
            Some(&[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0][..])
        );
        let CurveFile::Bspline(b) = f else {
            panic!("not a B-spline")
        };
        assert!(!b.closed);
    }

    #[test]
    fn serde_names_the_field() {
        assert!(
            err("kind = \"spiral\"\npoints = [[0.0]]")
                .message
                .contains("spiral")
        );
        assert_eq!(err("kind = \"bezier\"").field, "points");
        assert_eq!(err("points = [[0.0]]").field, "kind");
        assert_eq!(err("kind = 3\npoints = [[0.0]]").field, "kind");
        assert_eq!(
            err("kind = \"bspline\"\npoints = [[0.0], [1.0]]").field,
            "degree"
        );
        assert_eq!(
            err("kind = \"bspline\"\npoints = [[0.0], [1.0]]\ndegree = \"three\"").field,
            "degree"
        );
        assert_eq!(
            err("kind = \"bezier\"\npoints = [[0.0], [1.0]]\nweights = [1, 1]").field,
            "weights"
        );
        assert_eq!(
            err("kind = \"hermite\"\npoints = [[0.0], [1.0]]").field,
            "tangents"
        );
        assert_eq!(
            err("kind = \"bezier\"\npoints = [[0.0], [1.0]]\ncolour = 3").field,
            "colour"
        );
        assert_eq!(
            err("kind = \"bezier-chain\"\npoints = [[0.0], [1.0], [2.0]]").field,
            "degree"
        );
        assert_eq!(
            err("kind = \"cubic-spline\"\npoints = [[0.0], [1.0]]\nboundary = \"round\"").field,
            "boundary"
        );
    }

    #[test]
    fn checks_name_the_field() {
        assert_eq!(err("kind = \"bezier\"\npoints = []").field, "points");
        assert_eq!(
            err("kind = \"bezier\"\npoints = [[0.0], [1.0, 2.0]]").field,
            "points[1]"
        );
        assert_eq!(
            err("kind = \"bezier\"\npoints = [[1,2,3,4,5,6,7]]").field,
            "points[0]"
        );
        assert_eq!(
            err("kind = \"bezier\"\npoints = [[0, 0], [1, nan]]").field,
            "points[1][1]"
        );
        assert_eq!(
            err("kind = \"nurbs\"\npoints = [[0.0], [1.0]]\ndegree = 1\nweights = [1]").field,
            "weights"
        );
        assert_eq!(
            err("kind = \"cubic-spline\"\npoints = [[0.0], [1.0]]\nboundary = \"clamped\"").field,
            "start_tangent"
        );
        assert_eq!(
            err("kind = \"lagrange\"\npoints = [[0.0], [1.0]]\nparams = [0]").field,
            "params"
        );
        assert_eq!(
            err("kind = \"bezier-chain\"\npoints = [[0.0], [1.0]]\ndegree = 0").field,
            "degree"
        );
        assert_eq!(
            err("kind = \"bezier-chain\"\npoints = [[0.0], [1.0], [2.0]]\ndegree = 3").field,
            "points"
        );
        assert!(
            err(
                "kind = \"bezier-chain\"\npoints = [[0.0], [1.0], [2.0], [3.0], [4.0]]\ndegree = 3"
            )
            .message
            .contains("n·3 + 1 points (4, 7, 10, …), not 5")
        );
        let chain = CurveFile::parse(
            "kind = \"bezier-chain\"\npoints = [[0.0], [1.0], [2.0], [3.0], [4.0]]\ndegree = 2",
        )
        .unwrap();
        assert_eq!(chain.kind(), Kind::BezierChain);
        assert_eq!(
            err("kind = \"bezier\"\npoints = [[0.0], [1.0]]\ndegree = 3").field,
            "degree"
        );
    }

    #[test]
    fn capacities_say_which_and_why() {
        let many = |n: usize| {
            let points: Vec<String> = (0..n).map(|i| format!("[{i}, 0]")).collect();
            format!(
                "kind = \"bspline\"\ndegree = 1\npoints = [{}]",
                points.join(", ")
            )
        };
        assert_eq!(
            CurveFile::parse(&many(MAX_POINTS)).unwrap().points().len(),
            4096
        );
        let e = err(&many(MAX_POINTS + 1));
        assert_eq!(e.field, "points");
        assert!(e.message.contains("4097 points") && e.message.contains("at most 4096"));
        let six = CurveFile::parse("kind = \"bezier\"\npoints = [[1,2,3,4,5,6]]").unwrap();
        assert_eq!(six.dim(), 6);
        let five = CurveFile::parse("kind = \"cubic-spline\"\npoints = [[1,2,3,4,5], [2,3,4,5,6]]");
        assert_eq!(five.unwrap().dim(), 5);
        let e = err("kind = \"cubic-spline\"\npoints = [[1,2,3,4,5,6,7], [2,3,4,5,6,7,8]]");
        assert_eq!(e.field, "points[0]");
        assert!(e.message.contains("1 to 6 coordinates"), "{e}");
    }
}
