//! The error type of the trajectory layer.

use core::fmt;

use crate::num::{Number, NumberFormat};

/// Why a path could not be planned, compiled or loaded.
///
/// Everything is checked when a path is built; afterwards the sampler's `next()`
/// has no error path.
///
/// ```
/// use strak_trajectory::Error;
/// assert_eq!(Error::InvalidRate.to_string(), "control rate must be between 100 Hz and 100 kHz");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Error {
    /// The curve rejected its input, or a curve operation failed.
    Curve(strak_curves::Error),
    /// A limit (velocity, acceleration, jerk, per-axis) is zero, negative or not finite.
    InvalidLimit,
    /// The control rate is outside 100 Hz ..= 100 kHz, or not finite.
    InvalidRate,
    /// The path has zero length (or the parameter law a zero duration): nothing to play.
    EmptyPath,
    /// A move of a stream has zero length, its tangent vanishes at an end (a Bézier control
    /// point on its end point), or it does not start where the move before it ends.
    DegenerateMove,
    /// A corner-blend tolerance is negative or not finite.
    InvalidTolerance,
    /// The number of axes of the sampler does not match the curve's point dimension.
    AxisMismatch {
        /// Axes of the curve's points.
        curve: usize,
        /// Axes the path was asked for.
        path: usize,
    },
    /// More pieces than the fixed storage holds.
    CapacityExceeded {
        /// The capacity.
        capacity: usize,
        /// What would have been needed (a lower bound when compilation stopped early).
        required: usize,
    },
    /// The speed limit along the path needs more planning zones than the plan holds (the `Z`
    /// of [`PathTiming`](crate::PathTiming)`<_, N, Z>` and
    /// [`MotionProfile`](crate::MotionProfile)`<Z>`; the table size `N` is not concerned).
    ZoneCapacityExceeded {
        /// The zones the plan holds (`Z`).
        capacity: usize,
        /// The zones the speed limit needs.
        required: usize,
    },
    /// A value does not fit the number format of the path (fixed-point range), with the
    /// axis concerned.
    OutOfRange,
    /// The path would take more ticks than a `u32` counts.
    TooLong,
    /// A serialized path is truncated, has a bad checksum or a foreign header.
    CorruptBlob,
    /// A serialized path has a format version this build does not read.
    UnsupportedVersion {
        /// The version found.
        found: u16,
    },
    /// A serialized path records a number format id that no [`NumberFormat`] has.
    UnknownNumberFormat {
        /// The id found (the formats have 1, 2 and 3: [`NumberFormat::id`]).
        id: u8,
    },
    /// A serialized path was made for another number format or axis count.
    FormatMismatch {
        /// The format the reader asked for.
        expected: BlobFormat,
        /// The format the blob holds.
        found: BlobFormat,
    },
    /// The compiled pieces would exceed a limit the time law promises
    /// ([`Timing::limits`](crate::Timing::limits)) even after the largest slow-down the
    /// compiler applies to absorb its fit (see [`compile`](crate::compile)).
    LimitExceeded {
        /// The quantity whose limit the compiled motion exceeds.
        quantity: Quantity,
    },
    /// The motion uses more of a limit given for feed changes than `1 − share`
    /// ([`CompileOptions`](crate::CompileOptions)): the plan did not leave the feed share
    /// free, so a feed override, hold or resume could take it beyond the limit. Plan with
    /// the same feed share (or a larger one) and limits, or compile with a smaller share.
    FeedReserveExceeded {
        /// The quantity whose limit the motion leaves too little of.
        quantity: Quantity,
    },
    /// A start or target state of an online move has a value that is NaN or infinite.
    NonFiniteState,
    /// The target of an online move is outside the axis's limits: its velocity or
    /// acceleration, or a velocity it cannot be arrived at without passing.
    TargetOutsideLimits {
        /// The quantity whose limit the target breaks.
        quantity: Quantity,
    },
    /// An axis of an unsynchronized online move
    /// ([`Synchronization::None`](crate::Synchronization::None)) arrives before the slowest
    /// one with a target acceleration: going on at that acceleration until the move ends
    /// would carry its velocity beyond its limit. Give such axes a target acceleration of
    /// zero, or synchronize the axes.
    AccelerationAfterArrival {
        /// The axis (0 for the first).
        axis: usize,
    },
    /// The online solver found no profile that passes its checks: a numerical failure (for
    /// example limits and states many orders of magnitude apart, in `f32`).
    NoProfile,
    /// The error that playback in the path's number format may add
    /// ([`PathHeader::playback_bound`](crate::PathHeader::playback_bound): rounding of the
    /// stored states, propagated over a piece) exceeds the position tolerance the path was
    /// compiled to: far from the origin a float's spacing is coarse (`f32` at 4.5·10⁶ units
    /// has a spacing of 0.5). Compile in a wider format, nearer the origin (offsets), with
    /// shorter pieces, or to a wider tolerance.
    PlaybackBoundExceeded {
        /// The playback bound of the compiled path, in the path's units.
        bound: Units,
        /// The requested position tolerance, in the path's units.
        tolerance: Units,
    },
}

/// A length in the path's units, as an error reports it. Compared bit for bit, so that
/// [`Error`] stays `Eq`.
///
/// ```
/// use strak_trajectory::Units;
/// assert_eq!(Units(1.5), Units(1.5));
/// assert_eq!(Units(1.5).to_string(), "1.5");
/// ```
#[derive(Clone, Copy, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Units(pub f64);

impl PartialEq for Units {
    fn eq(&self, other: &Self) -> bool {
        self.0.to_bits() == other.0.to_bits()
    }
}

impl Eq for Units {}

impl fmt::Display for Units {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&self.0, f)
    }
}

/// The number format and axis count of a serialized path.
///
/// ```
/// use strak_trajectory::{BlobFormat, NumberFormat, Q40};
/// let f = BlobFormat::of::<Q40>(3);
/// assert_eq!((f.number, f.axes), (NumberFormat::Q40, 3));
/// assert_eq!(f.to_string(), "Q40 with 3 axes");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct BlobFormat {
    /// The number format.
    pub number: NumberFormat,
    /// The number of axes.
    pub axes: usize,
}

impl BlobFormat {
    /// The format of paths in `N` with `axes` axes.
    pub fn of<N: Number>(axes: usize) -> Self {
        BlobFormat {
            number: N::FORMAT,
            axes,
        }
    }
}

impl fmt::Display for BlobFormat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} with {} axes", self.number, self.axes)
    }
}

/// A kinematic quantity of a motion in space.
///
/// ```
/// use strak_trajectory::Quantity;
/// assert_eq!(Quantity::Jerk.to_string(), "jerk");
/// assert_eq!(Quantity::AxisVelocity { axis: 2 }.to_string(), "axis 2 velocity");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Quantity {
    /// The speed `|ẋ|`.
    Velocity,
    /// The acceleration `|ẍ|`.
    Acceleration,
    /// The jerk `|x⃛|`.
    Jerk,
    /// The tangential acceleration `d|ẋ|/dt`.
    TangentialAcceleration,
    /// The velocity `|ẋᵢ|` of one axis.
    AxisVelocity {
        /// The axis (0 for the first).
        axis: usize,
    },
    /// The acceleration `|ẍᵢ|` of one axis.
    AxisAcceleration {
        /// The axis (0 for the first).
        axis: usize,
    },
}

impl fmt::Display for Quantity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Quantity::Velocity => f.write_str("velocity"),
            Quantity::Acceleration => f.write_str("acceleration"),
            Quantity::Jerk => f.write_str("jerk"),
            Quantity::TangentialAcceleration => f.write_str("tangential acceleration"),
            Quantity::AxisVelocity { axis } => write!(f, "axis {axis} velocity"),
            Quantity::AxisAcceleration { axis } => write!(f, "axis {axis} acceleration"),
        }
    }
}

impl From<strak_curves::Error> for Error {
    fn from(e: strak_curves::Error) -> Self {
        Error::Curve(e)
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Error::Curve(e) => write!(f, "curve: {e}"),
            Error::InvalidLimit => f.write_str("a limit is zero, negative or not finite"),
            Error::InvalidRate => f.write_str("control rate must be between 100 Hz and 100 kHz"),
            Error::EmptyPath => f.write_str("the path has zero length or zero duration"),
            Error::DegenerateMove => f.write_str(
                "a move has zero length, no tangent at an end, or does not start where the \
                 move before it ends",
            ),
            Error::InvalidTolerance => f.write_str("a blend tolerance is negative or not finite"),
            Error::AxisMismatch { curve, path } => {
                write!(f, "the curve has {curve} axes, the path {path}")
            }
            Error::CapacityExceeded { capacity, required } => write!(
                f,
                "capacity exceeded: {required} pieces needed, storage for {capacity}"
            ),
            Error::ZoneCapacityExceeded { capacity, required } => write!(
                f,
                "the speed limit along the path needs {required} planning zones, the plan holds \
                 {capacity} (raise Z of PathTiming<_, N, Z> or the zone tolerance)"
            ),
            Error::OutOfRange => f.write_str("a value does not fit the path's number format"),
            Error::TooLong => f.write_str("the path takes more ticks than fit a u32"),
            Error::CorruptBlob => {
                f.write_str("serialized path is corrupt (truncated, checksum, header)")
            }
            Error::UnsupportedVersion { found } => {
                write!(f, "serialized path has unsupported format version {found}")
            }
            Error::UnknownNumberFormat { id } => write!(
                f,
                "serialized path has number format id {id}, which no format has (1 f32, 2 f64, \
                 3 Q40)"
            ),
            Error::FormatMismatch { expected, found } => {
                write!(f, "serialized path is for {found}, expected {expected}")
            }
            Error::LimitExceeded { quantity } => write!(
                f,
                "the compiled path would exceed the time law's {quantity} limit even slowed down"
            ),
            Error::FeedReserveExceeded { quantity } => write!(
                f,
                "the motion uses more than 1 − feed share of the {quantity} limit: the plan left \
                 too little for feed changes (plan with the compile's feed share and limits)"
            ),
            Error::NonFiniteState => f.write_str("a start or target value is not finite"),
            Error::TargetOutsideLimits { quantity } => {
                write!(f, "the target {quantity} is outside the axis's limits")
            }
            Error::NoProfile => f.write_str("no motion profile passed the solver's checks"),
            Error::AccelerationAfterArrival { axis } => write!(
                f,
                "axis {axis} arrives early with a target acceleration (unsynchronized move)"
            ),
            Error::PlaybackBoundExceeded { bound, tolerance } => write!(
                f,
                "playback in the path's number format may add an error of {bound} units, more \
                 than the position tolerance {tolerance} (compile in a wider format, nearer the \
                 origin, or to a wider tolerance)"
            ),
        }
    }
}

impl core::error::Error for Error {}
