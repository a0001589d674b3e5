//! The floating-point formats the online solver computes in.

use strak_curves::Scalar;

mod sealed {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
}

/// A floating-point format of the online solver: `f32` (single precision, fast on a
/// Cortex-M4F's FPU) or `f64`. Fixed-point formats are not solver formats: a move solved in
/// `f32` or `f64` is played in any [`Number`](crate::Number) format, `Q40` included.
///
/// ```
/// use strak_trajectory::Real;
/// assert_eq!(<f32 as Real>::lit(0.5), 0.5_f32);
/// assert_eq!(<f64 as Real>::EPS, f64::EPSILON);
/// ```
pub trait Real: Scalar + sealed::Sealed {
    /// The spacing of representable values near 1.
    const EPS: Self;
    /// The largest finite value.
    const MAX: Self;
    /// −1.
    const MINUS_ONE: Self;

    /// `x` rounded to this format (a literal of the solver's formulas).
    fn lit(x: f64) -> Self;

    /// `true` when `self` is negative (the sign bit of a non-NaN value aside: `-0.0` is not).
    #[inline]
    fn is_negative(self) -> bool {
        self < Self::ZERO
    }
}

impl Real for f32 {
    const EPS: Self = f32::EPSILON;
    const MAX: Self = f32::MAX;
    const MINUS_ONE: Self = -1.0;

    #[inline]
    fn lit(x: f64) -> Self {
        #[allow(clippy::cast_possible_truncation)]
        let y = x as f32;
        y
    }
}

impl Real for f64 {
    const EPS: Self = f64::EPSILON;
    const MAX: Self = f64::MAX;
    const MINUS_ONE: Self = -1.0;

    #[inline]
    fn lit(x: f64) -> Self {
        x
    }
}
