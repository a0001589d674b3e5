//! Building a strak-curves curve from a [`CurveFile`], in the requested number format.
//!
//! The file's points become `[S; D]` arrays (D = 1 to 4 coordinates, S = f64, f32 or I32F32);
//! each constructor's typed error is reported against the field it concerns.

use strak_curves::{
    BSpline, Bezier, BezierChain, CubicSpline, Error, HermiteSpline, LagrangeCurve, NodeSource,
    Nurbs, ParabolicBlend, Parameterization, PieceDeriv, Point, Scalar, SplineBoundary,
};

use crate::curve_file::{BoundaryName, CurveFile, FieldError, Kind};
use crate::sample::{FixedScalar, Number, Sampled};

/// The largest number of points (control points, interpolation points) a file may have.
pub const CAPACITY: usize = 256;

/// What to do with a built curve, whatever its concrete type: the builder hands each curve
/// (with points `[S; D]`) to [`CurveVisitor::visit`].
pub trait CurveVisitor {
    /// What the visit produces.
    type Output;

    /// Uses the curve.
    fn visit<S, const D: usize, C>(self, curve: C) -> Self::Output
    where
        S: Scalar,
        C: PieceDeriv<Point = [S; D]> + 'static;
}

/// The visitor behind `strak-sim sample`: the curve, boxed behind [`Sampled`].
#[derive(Debug, Clone, Copy)]
pub struct BoxSampled;

impl CurveVisitor for BoxSampled {
    type Output = Box<dyn Sampled>;

    fn visit<S, const D: usize, C>(self, curve: C) -> Self::Output
    where
        S: Scalar,
        C: PieceDeriv<Point = [S; D]> + 'static,
    {
        Box::new(curve)
    }
}

/// Builds the curve of `file` in the number format `number`, boxed for sampling.
pub fn build_curve(file: &CurveFile, number: Number) -> Result<Box<dyn Sampled>, FieldError> {
    visit_curve(file, number, BoxSampled)
}

/// Builds the curve of `file` in the number format `number` and hands it to `visitor`.
pub fn visit_curve<V: CurveVisitor>(
    file: &CurveFile,
    number: Number,
    visitor: V,
) -> Result<V::Output, FieldError> {
    check_finite(file)?;
    match number {
        Number::F64 => build_dim::<f64, V>(file, number, visitor),
        Number::F32 => build_dim::<f32, V>(file, number, visitor),
        Number::Fixed => build_dim::<FixedScalar, V>(file, number, visitor),
    }
}

fn build_dim<S: Scalar, V: CurveVisitor>(
    file: &CurveFile,
    number: Number,
    visitor: V,
) -> Result<V::Output, FieldError> {
    match file.dim() {
        1 => build::<S, 1, V>(file, number, visitor),
        2 => build::<S, 2, V>(file, number, visitor),
        3 => build::<S, 3, V>(file, number, visitor),
        4 => build::<S, 4, V>(file, number, visitor),
        d => Err(FieldError::new(
            "points",
            format!("points need 1 to 4 coordinates, not {d}"),
        )),
    }
}

/// Non-finite values are reported against their own field before any constructor runs.
fn check_finite(file: &CurveFile) -> Result<(), FieldError> {
    let all_finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
    let fields: [(&'static str, bool); 7] = [
        ("points", file.points.iter().all(|p| all_finite(p))),
        ("knots", file.knots.as_deref().is_none_or(all_finite)),
        ("weights", file.weights.as_deref().is_none_or(all_finite)),
        ("params", file.params.as_deref().is_none_or(all_finite)),
        (
            "tangents",
            file.tangents
                .as_ref()
                .is_none_or(|t| t.iter().all(|p| all_finite(p))),
        ),
        (
            "start_tangent",
            file.start_tangent.as_deref().is_none_or(all_finite),
        ),
        (
            "end_tangent",
            file.end_tangent.as_deref().is_none_or(all_finite),
        ),
    ];
    match fields.iter().find(|(_, ok)| !ok) {
        Some((field, _)) => Err(FieldError::new(field, "a value is NaN or infinite")),
        None => Ok(()),
    }
}

/// Converts a list of coordinate vectors to points of type `P`.
fn points_of<P: Point>(
    field: &'static str,
    coords: &[Vec<f64>],
    number: Number,
) -> Result<Vec<P>, FieldError> {
    coords
        .iter()
        .enumerate()
        .map(|(i, c)| {
            P::from_f64_slice(c)
                .ok_or_else(|| out_of_range(field, &format!("{field}[{i}]"), number))
        })
        .collect()
}

/// One point of type `P` from an optional field (checked present by [`CurveFile::check`]).
fn point_of<P: Point>(
    field: &'static str,
    coords: Option<&[f64]>,
    number: Number,
) -> Result<P, FieldError> {
    let coords = coords.ok_or_else(|| FieldError::new(field, "required"))?;
    P::from_f64_slice(coords).ok_or_else(|| out_of_range(field, field, number))
}

fn scalars_of<S: Scalar>(
    field: &'static str,
    values: &[f64],
    number: Number,
) -> Result<Vec<S>, FieldError> {
    values
        .iter()
        .enumerate()
        .map(|(i, v)| {
            S::from_f64(*v).ok_or_else(|| out_of_range(field, &format!("{field}[{i}]"), number))
        })
        .collect()
}

fn out_of_range(field: &'static str, what: &str, number: Number) -> FieldError {
    FieldError::new(
        field,
        format!(
            "{what} is out of range for --number {}",
            number_name(number)
        ),
    )
}

fn number_name(number: Number) -> &'static str {
    match number {
        Number::F64 => "f64",
        Number::F32 => "f32",
        Number::Fixed => "fixed (I32F32)",
    }
}

/// The field a constructor error is about, for the kind at hand.
fn field_of(kind: Kind, has_params: bool, error: Error) -> &'static str {
    match error {
        Error::KnotCount { .. } | Error::KnotsUnsorted { .. } | Error::KnotMultiplicity { .. } => {
            "knots"
        }
        Error::NodesNotIncreasing { .. } => "params",
        Error::ZeroLengthInterval { .. } => match kind {
            Kind::Bspline | Kind::Nurbs => "knots",
            _ if has_params => "params",
            _ => "points",
        },
        Error::NonPositiveWeight { .. } => "weights",
        Error::DegreeTooHigh { .. } => "degree",
        Error::LengthMismatch { .. } => match kind {
            Kind::Hermite => "tangents",
            Kind::Nurbs => "weights",
            Kind::Bspline => "knots",
            _ => "points",
        },
        _ => "points",
    }
}

fn constructor_error(file: &CurveFile, number: Number) -> impl Fn(Error) -> FieldError + '_ {
    move |e| {
        let field = field_of(file.kind, file.params.is_some(), e);
        let message = match e {
            Error::OutOfRange => format!(
                "a value of the curve (or one its evaluation produces) is out of range for --number {}",
                number_name(number)
            ),
            Error::InvalidArgument if file.boundary == Some(BoundaryName::Periodic) => {
                "a periodic cubic spline needs the last point to repeat the first".to_owned()
            }
            other => other.to_string(),
        };
        FieldError::new(field, message)
    }
}

fn build<S: Scalar, const D: usize, V: CurveVisitor>(
    file: &CurveFile,
    number: Number,
    visitor: V,
) -> Result<V::Output, FieldError> {
    let err = constructor_error(file, number);
    let points: Vec<[S; D]> = points_of("points", &file.points, number)?;
    let params: Option<Vec<S>> = file
        .params
        .as_deref()
        .map(|p| scalars_of("params", p, number))
        .transpose()?;
    let nodes = || -> NodeSource<'_, S> {
        match &params {
            Some(p) => NodeSource::Given(p),
            None => NodeSource::Computed(Parameterization::ChordLength),
        }
    };
    match file.kind {
        Kind::Lagrange => {
            Ok(visitor
                .visit(LagrangeCurve::<[S; D], CAPACITY>::new(&points, nodes()).map_err(&err)?))
        }
        Kind::Hermite => {
            let tangents: Vec<[S; D]> = points_of(
                "tangents",
                file.tangents.as_deref().unwrap_or_default(),
                number,
            )?;
            Ok(visitor.visit(
                HermiteSpline::<[S; D], CAPACITY>::new(&points, &tangents, nodes())
                    .map_err(&err)?,
            ))
        }
        Kind::CatmullRom => Ok(visitor.visit(
            HermiteSpline::<[S; D], CAPACITY>::catmull_rom(&points, nodes()).map_err(&err)?,
        )),
        Kind::CubicSpline => {
            let boundary = match file.boundary.unwrap_or_default() {
                BoundaryName::Natural => SplineBoundary::Natural,
                BoundaryName::Periodic => SplineBoundary::Periodic,
                BoundaryName::Clamped => SplineBoundary::Clamped {
                    start: point_of("start_tangent", file.start_tangent.as_deref(), number)?,
                    end: point_of("end_tangent", file.end_tangent.as_deref(), number)?,
                },
            };
            Ok(visitor.visit(
                CubicSpline::<[S; D], CAPACITY>::new(&points, nodes(), boundary).map_err(&err)?,
            ))
        }
        Kind::ParabolicBlend => {
            Ok(visitor.visit(ParabolicBlend::<[S; D], CAPACITY>::new(&points).map_err(&err)?))
        }
        Kind::Bezier => build_bezier(&points, &err, visitor),
        Kind::BezierChain => build_bezier_chain(file.degree.unwrap_or(0), &points, &err, visitor),
        Kind::Bspline | Kind::Nurbs => build_bspline(file, &points, number, &err, visitor),
    }
}

/// The largest number of control points of a Bézier curve in a file (degree 11).
pub const BEZIER_MAX_POINTS: usize = 12;

/// A Bézier curve with `N` control points, `N` being the length of `points`.
fn bezier<S: Scalar, const D: usize, const N: usize, V: CurveVisitor>(
    points: &[[S; D]],
    err: &dyn Fn(Error) -> FieldError,
    visitor: V,
) -> Result<V::Output, FieldError> {
    let array: [[S; D]; N] = points
        .try_into()
        .map_err(|_| FieldError::new("points", format!("expected {N} points")))?;
    Ok(visitor.visit(Bezier::new(array).map_err(err)?))
}

fn build_bezier<S: Scalar, const D: usize, V: CurveVisitor>(
    points: &[[S; D]],
    err: &dyn Fn(Error) -> FieldError,
    visitor: V,
) -> Result<V::Output, FieldError> {
    macro_rules! by_count {
        ($($n:literal)*) => {
            match points.len() {
                $($n => bezier::<S, D, $n, V>(points, err, visitor),)*
                n => Err(FieldError::new(
                    "points",
                    format!("a Bézier curve takes 1 to {BEZIER_MAX_POINTS} points, not {n}"),
                )),
            }
        };
    }
    by_count!(1 2 3 4 5 6 7 8 9 10 11 12)
}

/// The largest segment degree of a Bézier chain in a file.
pub const BEZIER_CHAIN_MAX_DEGREE: usize = 5;

/// The largest number of segments of a Bézier chain in a file (points: `n·degree + 1` ≤
/// [`CAPACITY`] + 1 at degree 1).
pub const BEZIER_CHAIN_MAX_SEGMENTS: usize = CAPACITY;

/// A Bézier chain of segments with `N` points each.
fn bezier_chain<S: Scalar, const D: usize, const N: usize, V: CurveVisitor>(
    points: &[[S; D]],
    err: &dyn Fn(Error) -> FieldError,
    visitor: V,
) -> Result<V::Output, FieldError> {
    let chain =
        BezierChain::<[S; D], N, BEZIER_CHAIN_MAX_SEGMENTS>::new(points).map_err(|e| match e {
            Error::CapacityExceeded { required, .. } => FieldError::new(
                "points",
                format!(
                    "a Bézier chain takes at most {BEZIER_CHAIN_MAX_SEGMENTS} segments, not {required}"
                ),
            ),
            e => err(e),
        })?;
    Ok(visitor.visit(chain))
}

fn build_bezier_chain<S: Scalar, const D: usize, V: CurveVisitor>(
    degree: usize,
    points: &[[S; D]],
    err: &dyn Fn(Error) -> FieldError,
    visitor: V,
) -> Result<V::Output, FieldError> {
    macro_rules! by_degree {
        ($($g:literal => $n:literal)*) => {
            match degree {
                $($g => bezier_chain::<S, D, $n, V>(points, err, visitor),)*
                g => Err(FieldError::new(
                    "degree",
                    format!(
                        "a Bézier chain takes segments of degree 1 to {BEZIER_CHAIN_MAX_DEGREE}, not {g}"
                    ),
                )),
            }
        };
    }
    by_degree!(1 => 2 2 => 3 3 => 4 4 => 5 5 => 6)
}

/// The largest degree of a B-spline or NURBS in a file.
pub use strak_curves::BSPLINE_MAX_DEGREE;

/// Knot capacity: the control points, plus the degree (closed curves repeat `g` points),
/// plus `2g + 1` knots.
const KNOT_CAPACITY: usize = CAPACITY + 3 * BSPLINE_MAX_DEGREE + 1;

fn build_bspline<S: Scalar, const D: usize, V: CurveVisitor>(
    file: &CurveFile,
    points: &[[S; D]],
    number: Number,
    err: &dyn Fn(Error) -> FieldError,
    visitor: V,
) -> Result<V::Output, FieldError> {
    let degree = file.degree.unwrap_or(0);
    let knots: Option<Vec<S>> = file
        .knots
        .as_deref()
        .map(|k| scalars_of("knots", k, number))
        .transpose()?;
    let (zero, one) = (S::ZERO, S::ONE);
    // Closed curves store g extra points.
    type Open<P> = BSpline<P, { CAPACITY + BSPLINE_MAX_DEGREE }, KNOT_CAPACITY>;
    if let Some(weights) = &file.weights {
        let w: Vec<S> = scalars_of("weights", weights, number)?;
        let curve = match &knots {
            Some(k) => Nurbs::<[S; D], { CAPACITY + BSPLINE_MAX_DEGREE }, KNOT_CAPACITY>::new(
                degree, points, &w, k,
            ),
            None => Nurbs::clamped_uniform(degree, points, &w, zero, one),
        };
        return Ok(visitor.visit(curve.map_err(err)?));
    }
    let curve: Result<Open<[S; D]>, Error> = if file.closed.unwrap_or(false) {
        BSpline::closed(degree, points, knots.as_deref())
    } else {
        match &knots {
            Some(k) => BSpline::new(degree, points, k),
            None => BSpline::clamped_uniform(degree, points, zero, one),
        }
    };
    Ok(visitor.visit(curve.map_err(err)?))
}
