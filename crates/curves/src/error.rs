//! The one error type of the crate: what a constructor found wrong with its input.

use core::fmt;

/// Why a constructor rejected its input.
///
/// Constructors validate everything once; after construction, evaluation has no error path.
/// Indices refer to the offending entry of the input (point, knot, node or weight).
///
/// ```
/// use strak_curves::Error;
/// let e = Error::KnotsUnsorted { index: 3 };
/// assert_eq!(e.to_string(), "knot 3 is smaller than knot 2: knots must be non-decreasing");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Error {
    /// A value (coordinate, knot, node, weight, tangent, tolerance) is NaN or infinite.
    NonFinite,
    /// Fewer points than the curve needs, for example fewer than `degree + 1`.
    TooFewPoints {
        /// The minimum number of points.
        required: usize,
        /// The number given.
        found: usize,
    },
    /// More items than the fixed storage holds.
    CapacityExceeded {
        /// The capacity of the storage.
        capacity: usize,
        /// The number of items that had to be stored.
        required: usize,
    },
    /// A knot vector has the wrong number of entries for its degree and control points.
    KnotCount {
        /// The required number of knots.
        expected: usize,
        /// The number given.
        found: usize,
    },
    /// Knot `index` is smaller than knot `index − 1`.
    KnotsUnsorted {
        /// Index of the first knot that breaks the order.
        index: usize,
    },
    /// A knot occurs more often than the degree allows (multiplicity above `degree + 1`, or
    /// above `degree` at an inner knot).
    KnotMultiplicity {
        /// Index of the first knot of the offending run.
        index: usize,
    },
    /// Interpolation nodes (parameter values) must be strictly increasing; node `index` is not
    /// larger than node `index − 1`.
    NodesNotIncreasing {
        /// Index of the first node that breaks the order.
        index: usize,
    },
    /// A parameter interval has zero length, for example between two equal consecutive points
    /// under chord-length parameterization, or a knot vector whose domain is a single value.
    ZeroLengthInterval {
        /// Index of the interval (the interval starts at node or knot `index`).
        index: usize,
    },
    /// A NURBS weight is zero or negative.
    NonPositiveWeight {
        /// Index of the weight.
        index: usize,
    },
    /// A value, or a value that evaluation would produce (a derivative, a spline coefficient),
    /// does not fit the scalar type's range with headroom ([`Scalar::LIMIT`](crate::Scalar::LIMIT)).
    OutOfRange,
    /// The degree is above what this curve type supports.
    DegreeTooHigh {
        /// The largest supported degree.
        max: usize,
        /// The degree asked for.
        found: usize,
    },
    /// Two inputs that must have equal lengths do not (tangents vs points, weights vs points,
    /// the capacity of a target type vs the size of a result).
    LengthMismatch {
        /// The required length.
        expected: usize,
        /// The length given.
        found: usize,
    },
    /// A tolerance, accuracy or count argument is zero, negative or otherwise unusable.
    InvalidArgument,
    /// An arc's start or end is its centre, its radius is zero, or (in the radius form)
    /// its start and end coincide so that no centre follows.
    DegenerateArc,
    /// An arc's end is not on the circle of its start within the tolerance (its distance
    /// from the centre differs, or the chord is longer than the diameter).
    ArcEndOffCircle,
    /// A tolerance or accuracy is finer than the number type `scalar` resolves at the curve's
    /// size: below the spacing of its values there (see [`resolution`](crate::resolution) and
    /// [`length_resolution`](crate::length_resolution)). Checked before any iteration starts.
    ToleranceBelowResolution {
        /// The name of the number type ([`Scalar::NAME`](crate::Scalar::NAME)), e.g. `"I16F16"`.
        scalar: &'static str,
    },
    /// An analysis routine did not reach its tolerance or accuracy within its documented
    /// iteration bound `limit` (interval splits of the arc-length quadrature, steps of the
    /// inverse arc length).
    IterationLimit {
        /// The bound that was reached.
        limit: usize,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Error::NonFinite => f.write_str("a value is NaN or infinite"),
            Error::TooFewPoints { required, found } => {
                write!(
                    f,
                    "too few points: {found} given, at least {required} required"
                )
            }
            Error::CapacityExceeded { capacity, required } => {
                write!(
                    f,
                    "capacity exceeded: {required} items do not fit into storage for {capacity}"
                )
            }
            Error::KnotCount { expected, found } => {
                write!(
                    f,
                    "wrong number of knots: {found} given, {expected} required"
                )
            }
            Error::KnotsUnsorted { index } => write!(
                f,
                "knot {index} is smaller than knot {}: knots must be non-decreasing",
                index.saturating_sub(1)
            ),
            Error::KnotMultiplicity { index } => {
                write!(
                    f,
                    "knot {index} has a multiplicity above what the degree allows"
                )
            }
            Error::NodesNotIncreasing { index } => write!(
                f,
                "node {index} is not larger than node {}: nodes must be strictly increasing",
                index.saturating_sub(1)
            ),
            Error::ZeroLengthInterval { index } => {
                write!(f, "parameter interval {index} has zero length")
            }
            Error::NonPositiveWeight { index } => {
                write!(f, "weight {index} is not positive")
            }
            Error::OutOfRange => {
                f.write_str("a value is out of the range of the number type (fixed-point range)")
            }
            Error::DegreeTooHigh { max, found } => {
                write!(f, "degree {found} is above the supported maximum {max}")
            }
            Error::LengthMismatch { expected, found } => {
                write!(f, "length mismatch: {found} given, {expected} required")
            }
            Error::InvalidArgument => f.write_str(
                "an argument (tolerance, accuracy, count) is zero, negative or unusable",
            ),
            Error::DegenerateArc => f.write_str(
                "degenerate arc: its start or end is its centre, or no centre follows from its radius",
            ),
            Error::ArcEndOffCircle => f.write_str(
                "the arc's end is not on the circle of its start within the tolerance",
            ),
            Error::ToleranceBelowResolution { scalar } => write!(
                f,
                "the tolerance is finer than {scalar} resolves at the curve's size"
            ),
            Error::IterationLimit { limit } => write!(
                f,
                "the accuracy was not reached within the iteration bound of {limit}"
            ),
        }
    }
}

impl core::error::Error for Error {}
