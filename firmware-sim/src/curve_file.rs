//! The curve file of `strak-sim sample`: one curve in TOML, checked field by field.
//!
//! ```toml
//! kind = "bspline"   # bezier | bezier-chain | bspline | nurbs | lagrange | hermite | catmull-rom | cubic-spline | parabolic-blend
//! points = [[0.0, 0.0, 0.0], [1.0, 2.0, 0.5], [2.0, 0.0, 1.0], [3.0, 1.0, 0.0]]
//! degree = 3
//! ```
//!
//! Every problem is reported as a [`FieldError`] naming the field, so that the command line
//! prints one clear line.

use std::fmt;

use serde::Deserialize;

/// The curve kinds of the file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
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
    /// Parabolic blending (seeds/003), node i at u = i.
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

/// The file as written (every field optional but `kind` and `points`).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CurveFile {
    /// The curve kind.
    pub kind: Kind,
    /// 1 to 4 coordinates per point.
    pub points: Vec<Vec<f64>>,
    /// Degree (bspline, nurbs, bezier-chain; optional for bezier, where it must equal
    /// points − 1).
    pub degree: Option<usize>,
    /// Knot vector (bspline, nurbs).
    pub knots: Option<Vec<f64>>,
    /// Closed (periodic) B-spline.
    pub closed: Option<bool>,
    /// NURBS weights, one per point.
    pub weights: Option<Vec<f64>>,
    /// Interpolation nodes (lagrange, hermite, catmull-rom, cubic-spline).
    pub params: Option<Vec<f64>>,
    /// Hermite tangents (derivatives with respect to u), one per point.
    pub tangents: Option<Vec<Vec<f64>>>,
    /// Cubic-spline end condition.
    pub boundary: Option<BoundaryName>,
    /// Clamped cubic spline: derivative at the start.
    pub start_tangent: Option<Vec<f64>>,
    /// Clamped cubic spline: derivative at the end.
    pub end_tangent: Option<Vec<f64>>,
}

/// A problem with one field of the file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FieldError {
    /// The field's name as written in the file (`points`, `knots`, …).
    pub field: &'static str,
    /// What is wrong with it.
    pub message: String,
}

impl FieldError {
    /// A new error for `field`.
    pub fn new(field: &'static str, message: impl Into<String>) -> Self {
        FieldError {
            field,
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

impl CurveFile {
    /// Parses TOML text; syntax, type and unknown-field errors name the field (from toml).
    pub fn parse(text: &str) -> Result<Self, String> {
        let file: CurveFile = toml::from_str(text).map_err(|e| {
            // toml's message spans several lines (with a source excerpt): keep the first.
            let msg = e.message().trim().to_owned();
            match e.span() {
                Some(span) => {
                    let start = span.start.min(text.len());
                    let line = text[..start].lines().count().max(1);
                    // Name the key of the offending line, as the semantic checks do.
                    let line_text = text[..start].rsplit('\n').next().unwrap_or_default();
                    match line_text.split_once('=') {
                        Some((key, _)) if !key.trim().is_empty() => {
                            format!("line {line}, field `{}`: {msg}", key.trim())
                        }
                        _ => format!("line {line}: {msg}"),
                    }
                }
                None => msg,
            }
        })?;
        file.check().map_err(|e| e.to_string())?;
        Ok(file)
    }

    /// The number of coordinates per point (1 to 4).
    pub fn dim(&self) -> usize {
        self.points.first().map_or(0, Vec::len)
    }

    /// Checks the fields that do not depend on the mathematics: presence, lengths, dimensions,
    /// and fields that do not apply to the kind. The curve constructors check the rest.
    pub fn check(&self) -> Result<(), FieldError> {
        let k = self.kind;
        if self.points.is_empty() {
            return Err(FieldError::new(
                "points",
                "the path is empty: give at least one point",
            ));
        }
        let dim = self.dim();
        if !(1..=4).contains(&dim) {
            return Err(FieldError::new(
                "points",
                format!("points need 1 to 4 coordinates, the first has {dim}"),
            ));
        }
        if let Some(i) = self.points.iter().position(|p| p.len() != dim) {
            return Err(FieldError::new(
                "points",
                format!(
                    "point {i} has {} coordinates, point 0 has {dim}",
                    self.points[i].len()
                ),
            ));
        }
        let uses = |field: &'static str, present: bool, allowed: &[Kind]| {
            if present && !allowed.contains(&k) {
                Err(FieldError::new(
                    field,
                    format!("does not apply to kind `{}`", k.name()),
                ))
            } else {
                Ok(())
            }
        };
        use Kind::*;
        uses(
            "degree",
            self.degree.is_some(),
            &[Bezier, BezierChain, Bspline, Nurbs],
        )?;
        uses("knots", self.knots.is_some(), &[Bspline, Nurbs])?;
        uses("closed", self.closed.is_some(), &[Bspline])?;
        uses("weights", self.weights.is_some(), &[Nurbs])?;
        uses(
            "params",
            self.params.is_some(),
            &[Lagrange, Hermite, CatmullRom, CubicSpline],
        )?;
        uses("tangents", self.tangents.is_some(), &[Hermite])?;
        uses("boundary", self.boundary.is_some(), &[CubicSpline])?;
        uses(
            "start_tangent",
            self.start_tangent.is_some(),
            &[CubicSpline],
        )?;
        uses("end_tangent", self.end_tangent.is_some(), &[CubicSpline])?;

        let n = self.points.len();
        if matches!(k, Bspline | Nurbs | BezierChain) && self.degree.is_none() {
            return Err(FieldError::new(
                "degree",
                format!("required for kind `{}`", k.name()),
            ));
        }
        if let (Bezier, Some(g)) = (k, self.degree)
            && g + 1 != n
        {
            return Err(FieldError::new(
                "degree",
                format!(
                    "a Bézier curve with {n} points has degree {}, not {g}",
                    n - 1
                ),
            ));
        }
        if let (BezierChain, Some(g)) = (k, self.degree) {
            if g == 0 {
                return Err(FieldError::new(
                    "degree",
                    "a Bézier chain needs segments of degree 1 or more",
                ));
            }
            if n < g + 1 || !(n - 1).is_multiple_of(g) {
                return Err(FieldError::new(
                    "points",
                    format!(
                        "a Bézier chain of degree {g} has n·{g} + 1 points ({}, {}, {}, …), not {n}",
                        g + 1,
                        2 * g + 1,
                        3 * g + 1
                    ),
                ));
            }
        }
        if k == Nurbs {
            match &self.weights {
                None => return Err(FieldError::new("weights", "required for kind `nurbs`")),
                Some(w) if w.len() != n => {
                    return Err(FieldError::new(
                        "weights",
                        format!("one weight per point: {n} points, {} weights", w.len()),
                    ));
                }
                Some(_) => {}
            }
        }
        if let Some(p) = &self.params
            && p.len() != n
        {
            return Err(FieldError::new(
                "params",
                format!("one node per point: {n} points, {} nodes", p.len()),
            ));
        }
        if k == Hermite {
            let Some(t) = &self.tangents else {
                return Err(FieldError::new("tangents", "required for kind `hermite`"));
            };
            if t.len() != n {
                return Err(FieldError::new(
                    "tangents",
                    format!("one tangent per point: {n} points, {} tangents", t.len()),
                ));
            }
            if let Some(i) = t.iter().position(|v| v.len() != dim) {
                return Err(FieldError::new(
                    "tangents",
                    format!(
                        "tangent {i} has {} coordinates, points have {dim}",
                        t[i].len()
                    ),
                ));
            }
        }
        if k == CubicSpline {
            let clamped = self.boundary == Some(BoundaryName::Clamped);
            for (field, v) in [
                ("start_tangent", &self.start_tangent),
                ("end_tangent", &self.end_tangent),
            ] {
                match v {
                    Some(_) if !clamped => {
                        return Err(FieldError::new(field, "only with boundary = \"clamped\""));
                    }
                    None if clamped => {
                        return Err(FieldError::new(
                            field,
                            "required with boundary = \"clamped\"",
                        ));
                    }
                    Some(v) if v.len() != dim => {
                        return Err(FieldError::new(
                            field,
                            format!("has {} coordinates, points have {dim}", v.len()),
                        ));
                    }
                    _ => {}
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> String {
        CurveFile::parse(text).unwrap_err()
    }

    #[test]
    fn parses_the_documented_example() {
        let f = CurveFile::parse(
            "kind = \"bspline\"\npoints = [[0.0, 0.0, 0.0], [1.0, 2.0, 0.5], [2.0, 0.0, 1.0], [3.0, 1.0, 0.0]]\ndegree = 3\nknots = [0, 0, 0, 0, 1, 1, 1, 1]\n",
        )
        .unwrap();
        assert_eq!(f.kind, Kind::Bspline);
        assert_eq!(f.dim(), 3);
        assert_eq!(
            f.knots.as_deref(),
            Some(&[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0][..])
        );
    }

    #[test]
    fn errors_name_the_field() {
        assert!(err("kind = \"spiral\"\npoints = [[0.0]]").contains("spiral"));
        assert!(err("kind = \"bezier\"").contains("points"));
        assert!(err("kind = \"bezier\"\npoints = []").contains("field `points`"));
        assert!(err("kind = \"bezier\"\npoints = [[0.0], [1.0, 2.0]]").contains("field `points`"));
        assert!(err("kind = \"bezier\"\npoints = [[1,2,3,4,5]]").contains("field `points`"));
        assert!(err("kind = \"bspline\"\npoints = [[0.0], [1.0]]").contains("field `degree`"));
        assert!(
            err("kind = \"bezier\"\npoints = [[0.0], [1.0]]\nweights = [1, 1]")
                .contains("field `weights`")
        );
        assert!(
            err("kind = \"nurbs\"\npoints = [[0.0], [1.0]]\ndegree = 1\nweights = [1]")
                .contains("field `weights`")
        );
        assert!(err("kind = \"hermite\"\npoints = [[0.0], [1.0]]").contains("field `tangents`"));
        assert!(
            err("kind = \"cubic-spline\"\npoints = [[0.0], [1.0]]\nboundary = \"clamped\"")
                .contains("field `start_tangent`")
        );
        assert!(
            err("kind = \"lagrange\"\npoints = [[0.0], [1.0]]\nparams = [0]")
                .contains("field `params`")
        );
        assert!(err("kind = \"bezier\"\npoints = [[0.0], [1.0]]\ncolour = 3").contains("colour"));
        assert!(
            err("kind = \"bezier-chain\"\npoints = [[0.0], [1.0], [2.0]]")
                .contains("field `degree`")
        );
        assert!(
            err("kind = \"bezier-chain\"\npoints = [[0.0], [1.0]]\ndegree = 0")
                .contains("field `degree`")
        );
        assert!(
            err("kind = \"bezier-chain\"\npoints = [[0.0], [1.0], [2.0]]\ndegree = 3")
                .contains("field `points`")
        );
        assert!(
            err(
                "kind = \"bezier-chain\"\npoints = [[0.0], [1.0], [2.0], [3.0], [4.0]]\ndegree = 3"
            )
            .contains("n·3 + 1 points (4, 7, 10, …), not 5")
        );
        let chain = CurveFile::parse(
            "kind = \"bezier-chain\"\npoints = [[0.0], [1.0], [2.0], [3.0], [4.0]]\ndegree = 2",
        )
        .unwrap();
        assert_eq!(chain.kind, Kind::BezierChain);
        assert!(
            err("kind = \"bezier\"\npoints = [[0.0], [1.0]]\ndegree = 3")
                .contains("field `degree`")
        );
    }
}
