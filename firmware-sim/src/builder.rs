//! Building a strak-curves curve from a [`CurveFile`], in the requested number format.
//!
//! The file's points become `[S; D]` arrays (D = 1 to [`MAX_AXES`](crate::axes::MAX_AXES)
//! coordinates, S = f64, f32 or I32F32); each constructor's typed error is reported against
//! the field it concerns. The curves live in fixed-capacity storage as on the device: files
//! of up to [`SMALL_CAPACITY`] points (and knots) are built with that capacity, larger ones
//! with [`MAX_POINTS`], so that the common small curve stays small on the stack.

use strak_curves::{
    BSpline, Bezier, BezierChain, CubicSpline, Error, HermiteSpline, LagrangeCurve, NodeSource,
    Nurbs, ParabolicBlend, ParamCurveDeriv, Parameterization, PieceDeriv, Point, Scalar, ScalarOf,
    SplineBoundary,
};

use crate::curve_file::{
    BEZIER_MAX_POINTS, BoundaryName, BsplineFields, CubicSplineFields, CurveFile, FieldError, Kind,
    MAX_POINTS, NurbsFields,
};
use crate::number::{FixedScalar, NumberFormat};
use crate::summary::num;

/// The point capacity of the curves of files with at most this many points and knots.
pub const SMALL_CAPACITY: usize = 256;

/// The largest degree of a B-spline or NURBS in a file.
pub use strak_curves::BSPLINE_MAX_DEGREE;

/// The largest number of segments of a Bézier chain (points: `n·degree + 1`, at most
/// [`MAX_POINTS`]; degree 1).
pub const BEZIER_CHAIN_MAX_SEGMENTS: usize = MAX_POINTS - 1;

/// A built curve, seen through `f64` at the boundary of the simulator.
pub trait Sampled {
    /// The parameter domain.
    fn domain_f64(&self) -> (f64, f64);
    /// The parameter value this curve's scalar type uses for `u` (rounded to the type).
    fn param(&self, u: f64) -> f64;
    /// Appends the coordinates of the derivative of order `k` at `u` (k = 0: the point).
    fn push_deriv(&self, u: f64, k: usize, row: &mut Vec<f64>);
}

impl<C> Sampled for C
where
    C: ParamCurveDeriv,
{
    fn domain_f64(&self) -> (f64, f64) {
        let (a, b) = self.domain();
        (a.to_f64(), b.to_f64())
    }

    fn param(&self, u: f64) -> f64 {
        to_scalar::<ScalarOf<C>>(u).to_f64()
    }

    fn push_deriv(&self, u: f64, k: usize, row: &mut Vec<f64>) {
        let p = self.deriv(to_scalar::<ScalarOf<C>>(u), k);
        row.extend((0..C::Point::DIM).map(|i| p.coord(i).to_f64()));
    }
}

/// `u` in the scalar type; parameters come from the curve's own domain, so they are in range.
fn to_scalar<S: Scalar>(u: f64) -> S {
    S::from_f64(u).unwrap_or(S::ZERO)
}

/// What to do with a built curve, whatever its concrete type: the builder hands each curve
/// (with points `[S; D]`) to [`CurveVisitor::visit`], boxed (a curve of [`MAX_POINTS`]
/// points holds up to about 0.5 MB, so it is moved once, from its constructor to the heap).
pub trait CurveVisitor {
    /// What the visit produces.
    type Output;

    /// Uses the curve.
    fn visit<S, const D: usize, C>(self, curve: Box<C>) -> Self::Output
    where
        S: Scalar,
        C: PieceDeriv<Point = [S; D]> + 'static;
}

/// The visitor behind `strak-sim sample`: the curve, boxed behind [`Sampled`].
#[derive(Debug, Clone, Copy)]
pub struct BoxSampled;

impl CurveVisitor for BoxSampled {
    type Output = Box<dyn Sampled>;

    fn visit<S, const D: usize, C>(self, curve: Box<C>) -> Self::Output
    where
        S: Scalar,
        C: PieceDeriv<Point = [S; D]> + 'static,
    {
        curve
    }
}

/// Builds the curve of `file` in the number format `number`, boxed for sampling.
///
/// # Errors
/// A [`FieldError`] naming the field the constructor rejected.
pub fn build_curve(file: &CurveFile, number: NumberFormat) -> Result<Box<dyn Sampled>, FieldError> {
    visit_curve(file, number, BoxSampled)
}

/// Builds the curve of `file` in the number format `number` and hands it to `visitor`.
///
/// # Errors
/// A [`FieldError`] naming the field: a coordinate out of the format's range
/// (`points[3][1]`), or the field a constructor rejected.
pub fn visit_curve<V: CurveVisitor>(
    file: &CurveFile,
    number: NumberFormat,
    visitor: V,
) -> Result<V::Output, FieldError> {
    file.check()?;
    match number {
        NumberFormat::F64 => by_capacity::<f64, V>(file, number, visitor),
        NumberFormat::F32 => by_capacity::<f32, V>(file, number, visitor),
        NumberFormat::Q40 => by_capacity::<FixedScalar, V>(file, number, visitor),
    }
}

/// Closed B-splines store `g` more points; knot vectors hold up to `3g + 1` more entries.
const G: usize = BSPLINE_MAX_DEGREE;

fn by_capacity<S: Scalar, V: CurveVisitor>(
    file: &CurveFile,
    number: NumberFormat,
    visitor: V,
) -> Result<V::Output, FieldError> {
    let items = file
        .points()
        .len()
        .max(file.knots().map_or(0, <[f64]>::len));
    let err = || FieldError::new("points", "points need 1 to 6 coordinates");
    if items <= SMALL_CAPACITY {
        const C: usize = SMALL_CAPACITY;
        crate::with_axes!(
            file.dim(),
            build::<S, V, C, { C + G }, { C + 3 * G + 1 }>(file, number, visitor),
            Err(err())
        )
    } else {
        const C: usize = MAX_POINTS;
        crate::with_axes!(
            file.dim(),
            build::<S, V, C, { C + G }, { C + 3 * G + 1 }>(file, number, visitor),
            Err(err())
        )
    }
}

fn number_name(number: NumberFormat) -> &'static str {
    match number {
        NumberFormat::F64 => "f64",
        NumberFormat::F32 => "f32",
        NumberFormat::Q40 => "fixed (I32F32)",
    }
}

/// `±limit` of a scalar type in full (integers for the fixed-point ranges).
fn range_text(limit: f64) -> String {
    if limit < 1e15 {
        format!("±{limit:.0}")
    } else {
        format!("±{limit:e}")
    }
}

/// `value` of `field` does not fit `S`.
fn out_of_range<S: Scalar>(field: &str, value: f64, number: NumberFormat) -> FieldError {
    FieldError::new(
        field,
        format!(
            "{} is out of range for --number {}, which holds values within {} (half its \
             range, kept as headroom for evaluation)",
            num(value),
            number_name(number),
            range_text(S::LIMIT)
        ),
    )
}

/// One vector of `field` as a point `[S; D]`.
fn vector<S: Scalar, const D: usize>(
    field: &str,
    coords: &[f64],
    number: NumberFormat,
) -> Result<[S; D], FieldError> {
    let mut p = [S::ZERO; D];
    for (j, c) in p.iter_mut().enumerate() {
        let v = coords.get(j).copied().unwrap_or(0.0);
        *c =
            S::from_f64(v).ok_or_else(|| out_of_range::<S>(&format!("{field}[{j}]"), v, number))?;
    }
    Ok(p)
}

/// The vectors of `field` as points (`field[i][j]` named when out of range).
fn vectors<S: Scalar, const D: usize>(
    field: &str,
    rows: &[Vec<f64>],
    number: NumberFormat,
) -> Result<Vec<[S; D]>, FieldError> {
    rows.iter()
        .enumerate()
        .map(|(i, row)| vector(&format!("{field}[{i}]"), row, number))
        .collect()
}

fn scalars<S: Scalar>(
    field: &str,
    values: &[f64],
    number: NumberFormat,
) -> Result<Vec<S>, FieldError> {
    values
        .iter()
        .enumerate()
        .map(|(i, v)| {
            S::from_f64(*v).ok_or_else(|| out_of_range::<S>(&format!("{field}[{i}]"), *v, number))
        })
        .collect()
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

/// The storage a curve is built with, by the size class of its file (see the module docs):
/// `points` entries for the points (the segments of a Bézier chain), `control_points` for
/// the control points of a B-spline or NURBS, `knots` for its knot vector.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Storage {
    points: usize,
    control_points: usize,
    knots: usize,
}

impl Storage {
    /// The storage of the size class of `points` points: a B-spline or NURBS stores [`G`] more
    /// control points (a closed curve repeats up to `degree` of its points after the last)
    /// and `3·G + 1` more knots than points.
    const fn of_class(points: usize) -> Self {
        Storage {
            points,
            control_points: points + G,
            knots: points + 3 * G + 1,
        }
    }
}

/// The message of `CapacityExceeded { capacity, required }` from the constructor of a
/// `kind` built with `storage`: which storage ran out, and why it holds `capacity`.
fn capacity_message(kind: Kind, storage: Storage, capacity: usize, required: usize) -> String {
    let spline = matches!(kind, Kind::Bspline | Kind::Nurbs);
    let (what, why) = if spline && capacity == storage.control_points {
        (
            "control points",
            format!(
                "{} + {G}: the file's size class plus the highest degree, as a closed curve \
                 repeats up to `degree` points",
                storage.points
            ),
        )
    } else if spline && capacity == storage.knots {
        (
            "knots",
            format!(
                "{} + 3·{G} + 1: the file's size class plus the knots the highest degree {G} \
                 adds, as a closed curve of k points takes k + 2·degree + 1",
                storage.points
            ),
        )
    } else {
        let what = if kind == Kind::BezierChain {
            "segments"
        } else {
            "points"
        };
        (what, "the file's size class".to_owned())
    };
    format!(
        "the {} needs storage for {required} {what}, strak-sim holds {capacity} ({why}; files \
         of up to {SMALL_CAPACITY} points and knots are built in the class of \
         {SMALL_CAPACITY}, larger ones in the class of {MAX_POINTS})",
        kind.name()
    )
}

/// The message of a constructor error `e` in a file of `kind`, built with `storage`.
fn constructor_message<S: Scalar>(
    kind: Kind,
    periodic: bool,
    e: Error,
    number: NumberFormat,
    storage: Storage,
) -> String {
    match e {
        Error::OutOfRange => format!(
            "a value of the curve (or one its evaluation produces) is out of range for --number \
             {}, which holds values within {}{}",
            number_name(number),
            range_text(S::LIMIT),
            if matches!(kind, Kind::Bspline | Kind::Nurbs) {
                " (the k-th derivative grows with the number of pieces to the k-th power over \
                 the default knots in [0, 1]: give `knots` over a longer domain)"
            } else {
                ""
            }
        ),
        Error::InvalidArgument if periodic => {
            "a periodic cubic spline needs the last point to repeat the first".to_owned()
        }
        Error::CapacityExceeded { capacity, required } => {
            capacity_message(kind, storage, capacity, required)
        }
        other => other.to_string(),
    }
}

fn constructor_error<S: Scalar>(
    file: &CurveFile,
    number: NumberFormat,
    storage: Storage,
) -> impl Fn(Error) -> FieldError + '_ {
    let periodic = matches!(
        file,
        CurveFile::CubicSpline(CubicSplineFields {
            boundary: BoundaryName::Periodic,
            ..
        })
    );
    move |e| {
        let field = field_of(file.kind(), file.params().is_some(), e);
        FieldError::new(
            field,
            constructor_message::<S>(file.kind(), periodic, e, number, storage),
        )
    }
}

// Not inlined: the frame of each capacity class holds its own curves only, so that a small
// curve needs a small stack.
#[inline(never)]
fn build<S, V, const C: usize, const CP: usize, const K: usize, const D: usize>(
    file: &CurveFile,
    number: NumberFormat,
    visitor: V,
) -> Result<V::Output, FieldError>
where
    S: Scalar,
    V: CurveVisitor,
{
    const { assert!(CP == C + G && K == C + 3 * G + 1) };
    let storage = Storage::of_class(C);
    let err = constructor_error::<S>(file, number, storage);
    let points: Vec<[S; D]> = vectors("points", file.points(), number)?;
    let params: Option<Vec<S>> = file
        .params()
        .map(|p| scalars("params", p, number))
        .transpose()?;
    let nodes = || -> NodeSource<'_, S> {
        match &params {
            Some(p) => NodeSource::Given(p),
            None => NodeSource::Computed(Parameterization::ChordLength),
        }
    };
    type Hermite<S, const D: usize, const C: usize> = HermiteSpline<[S; D], C>;
    match file {
        CurveFile::Lagrange(_) => visit_built(
            || LagrangeCurve::<[S; D], C>::new(&points, nodes()),
            &err,
            visitor,
        ),
        CurveFile::Hermite(h) => {
            let tangents: Vec<[S; D]> = vectors("tangents", &h.tangents, number)?;
            visit_built(
                || Hermite::<S, D, C>::new(&points, &tangents, nodes()),
                &err,
                visitor,
            )
        }
        CurveFile::CatmullRom(_) => visit_built(
            || Hermite::<S, D, C>::catmull_rom(&points, nodes()),
            &err,
            visitor,
        ),
        CurveFile::CubicSpline(c) => {
            let boundary = cubic_boundary(c, number)?;
            visit_built(
                || CubicSpline::<[S; D], C>::new(&points, nodes(), boundary),
                &err,
                visitor,
            )
        }
        CurveFile::ParabolicBlend(_) => {
            visit_built(|| ParabolicBlend::<[S; D], C>::new(&points), &err, visitor)
        }
        CurveFile::Bezier(_) => build_bezier(&points, &err, visitor),
        CurveFile::BezierChain(c) => {
            build_bezier_chain::<S, D, V>(c.degree, &points, &err, visitor)
        }
        CurveFile::Bspline(b) => build_bspline::<S, D, CP, K, V>(b, &points, number, &err, visitor),
        CurveFile::Nurbs(f) => build_nurbs::<S, D, CP, K, V>(f, &points, number, &err, visitor),
    }
}

/// Builds a curve with `make`, boxes it and hands it to `visitor`. Not inlined: the curve (up
/// to about 0.5 MB in the class of [`MAX_POINTS`], returned by value by its constructor) lies
/// in this frame once, one frame per kind, so that a run needs the stack of its own kind only.
#[inline(never)]
fn visit_built<S, const D: usize, C, V>(
    make: impl FnOnce() -> Result<C, Error>,
    err: &dyn Fn(Error) -> FieldError,
    visitor: V,
) -> Result<V::Output, FieldError>
where
    S: Scalar,
    C: PieceDeriv<Point = [S; D]> + 'static,
    V: CurveVisitor,
{
    let curve = match make() {
        Ok(curve) => Box::new(curve),
        Err(e) => return Err(err(e)),
    };
    Ok(visitor.visit(curve))
}

fn cubic_boundary<S: Scalar, const D: usize>(
    c: &CubicSplineFields,
    number: NumberFormat,
) -> Result<SplineBoundary<[S; D]>, FieldError> {
    let tangent = |field: &str, v: &Option<Vec<f64>>| match v {
        Some(v) => vector::<S, D>(field, v, number),
        None => Err(FieldError::new(
            field,
            "required with boundary = \"clamped\"",
        )),
    };
    Ok(match c.boundary {
        BoundaryName::Natural => SplineBoundary::Natural,
        BoundaryName::Periodic => SplineBoundary::Periodic,
        BoundaryName::Clamped => SplineBoundary::Clamped {
            start: tangent("start_tangent", &c.start_tangent)?,
            end: tangent("end_tangent", &c.end_tangent)?,
        },
    })
}

/// A Bézier curve with `N` control points, `N` being the length of `points`.
#[inline(never)]
fn bezier<S: Scalar, const D: usize, const N: usize, V: CurveVisitor>(
    points: &[[S; D]],
    err: &dyn Fn(Error) -> FieldError,
    visitor: V,
) -> Result<V::Output, FieldError> {
    let array: [[S; D]; N] = points
        .try_into()
        .map_err(|_| FieldError::new("points", format!("expected {N} points")))?;
    visit_built(|| Bezier::new(array), err, visitor)
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

/// A Bézier chain of at most `C` segments with `N` points each.
#[inline(never)]
fn bezier_chain<S: Scalar, const D: usize, const N: usize, const C: usize, V: CurveVisitor>(
    points: &[[S; D]],
    err: &dyn Fn(Error) -> FieldError,
    visitor: V,
) -> Result<V::Output, FieldError> {
    visit_built(|| BezierChain::<[S; D], N, C>::new(points), err, visitor)
}

/// A Bézier chain of `degree` with room for the segments of its size class: `n·degree + 1`
/// points of at most [`SMALL_CAPACITY`] or [`MAX_POINTS`] are `(class − 1)/degree` segments
/// at most.
fn build_bezier_chain<S: Scalar, const D: usize, V: CurveVisitor>(
    degree: usize,
    points: &[[S; D]],
    err: &dyn Fn(Error) -> FieldError,
    visitor: V,
) -> Result<V::Output, FieldError> {
    const SMALL: usize = SMALL_CAPACITY - 1;
    const LARGE: usize = MAX_POINTS - 1;
    let small = points.len() <= SMALL_CAPACITY;
    macro_rules! by_degree {
        ($($g:literal => $n:literal)*) => {
            match degree {
                $($g if small => bezier_chain::<S, D, $n, { SMALL / $g }, V>(points, err, visitor),
                $g => bezier_chain::<S, D, $n, { LARGE / $g }, V>(points, err, visitor),)*
                g => Err(FieldError::new(
                    "degree",
                    format!("a Bézier chain takes segments of degree 1 to 5, not {g}"),
                )),
            }
        };
    }
    by_degree!(1 => 2 2 => 3 3 => 4 4 => 5 5 => 6)
}

fn knots_of<S: Scalar>(
    knots: Option<&[f64]>,
    number: NumberFormat,
) -> Result<Option<Vec<S>>, FieldError> {
    knots.map(|k| scalars("knots", k, number)).transpose()
}

#[inline(never)]
fn build_bspline<S: Scalar, const D: usize, const CP: usize, const K: usize, V: CurveVisitor>(
    b: &BsplineFields,
    points: &[[S; D]],
    number: NumberFormat,
    err: &dyn Fn(Error) -> FieldError,
    visitor: V,
) -> Result<V::Output, FieldError> {
    let knots = knots_of::<S>(b.knots.as_deref(), number)?;
    let make = || -> Result<BSpline<[S; D], CP, K>, Error> {
        if b.closed {
            BSpline::closed(b.degree, points, knots.as_deref())
        } else {
            match &knots {
                Some(k) => BSpline::new(b.degree, points, k),
                None => BSpline::clamped_uniform(b.degree, points, S::ZERO, S::ONE),
            }
        }
    };
    visit_built(make, err, visitor)
}

#[inline(never)]
fn build_nurbs<S: Scalar, const D: usize, const CP: usize, const K: usize, V: CurveVisitor>(
    f: &NurbsFields,
    points: &[[S; D]],
    number: NumberFormat,
    err: &dyn Fn(Error) -> FieldError,
    visitor: V,
) -> Result<V::Output, FieldError> {
    let knots = knots_of::<S>(f.knots.as_deref(), number)?;
    let w: Vec<S> = scalars("weights", &f.weights, number)?;
    let make = || -> Result<Nurbs<[S; D], CP, K>, Error> {
        match &knots {
            Some(k) => Nurbs::new(f.degree, points, &w, k),
            None => Nurbs::clamped_uniform(f.degree, points, &w, S::ZERO, S::ONE),
        }
    };
    visit_built(make, err, visitor)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_capacity_error_says_which_storage_and_why_it_holds_that_many() {
        let small = Storage::of_class(SMALL_CAPACITY);
        let m = capacity_message(Kind::Bspline, small, small.control_points, 265);
        let holds = SMALL_CAPACITY + BSPLINE_MAX_DEGREE;
        assert!(
            m.starts_with(&format!(
                "the bspline needs storage for 265 control points, strak-sim holds {holds} \
                 ({SMALL_CAPACITY} + {BSPLINE_MAX_DEGREE}: the file's size class plus the \
                 highest degree"
            )),
            "{m}"
        );
        assert!(
            m.contains(&format!("larger ones in the class of {MAX_POINTS}")),
            "{m}"
        );
        let m = capacity_message(Kind::Nurbs, small, small.knots, 300);
        assert!(
            m.contains(&format!("300 knots, strak-sim holds {}", small.knots)),
            "{m}"
        );
        let large = Storage::of_class(MAX_POINTS);
        let m = capacity_message(Kind::BezierChain, large, MAX_POINTS, MAX_POINTS + 1);
        assert!(
            m.contains(&format!(
                "{} segments, strak-sim holds {MAX_POINTS}",
                MAX_POINTS + 1
            )),
            "{m}"
        );
        let m = capacity_message(Kind::Lagrange, small, SMALL_CAPACITY, 300);
        assert!(m.contains("300 points"), "{m}");
    }

    struct Domain;

    impl CurveVisitor for Domain {
        type Output = (f64, f64, usize);

        fn visit<S, const D: usize, C>(self, curve: Box<C>) -> Self::Output
        where
            S: Scalar,
            C: PieceDeriv<Point = [S; D]> + 'static,
        {
            let (a, b) = curve.domain();
            (a.to_f64(), b.to_f64(), D)
        }
    }

    fn build(text: &str, number: NumberFormat) -> Result<(f64, f64, usize), FieldError> {
        visit_curve(&CurveFile::parse(text).unwrap(), number, Domain)
    }

    #[test]
    fn out_of_range_names_the_coordinate_and_the_range() {
        let e = build(
            "kind = \"bezier\"\npoints = [[0, 0], [1, 2], [3, 5e10]]",
            NumberFormat::Q40,
        )
        .unwrap_err();
        assert_eq!(e.field, "points[2][1]");
        assert!(
            e.message.contains("5.000e10") && e.message.contains("1073741823"),
            "{e}"
        );
        let e = build(
            "kind = \"nurbs\"\ndegree = 1\npoints = [[0], [1]]\nweights = [1, 1e40]",
            NumberFormat::F32,
        )
        .unwrap_err();
        assert_eq!(e.field, "weights[1]");
    }

    #[test]
    fn six_axes_and_many_points() {
        assert_eq!(
            build(
                "kind = \"bezier\"\npoints = [[0,0,0,0,0,0], [1,2,3,4,5,6]]",
                NumberFormat::F64
            )
            .unwrap()
            .2,
            6
        );
        let points: Vec<String> = (0..MAX_POINTS).map(|i| format!("[{i}, 0]")).collect();
        let text = format!(
            "kind = \"bspline\"\ndegree = 1\npoints = [{}]",
            points.join(", ")
        );
        assert_eq!(build(&text, NumberFormat::F32).unwrap(), (0.0, 1.0, 2));
    }
}
