//! The number types curves are computed in: `f32`, `f64` and fixed-point.
//!
//! [`Scalar`] is the one trait every evaluator is written against. It is implemented for
//! `f32`, `f64` and the signed fixed-point types of the [`fixed`] crate listed below.
//! `num_traits::Float` cannot express fixed-point, which is why this crate has its own trait.
//!
//! # Fixed-point Q formats
//!
//! | type      | Q format | storage | range                         | resolution      |
//! |-----------|----------|---------|-------------------------------|-----------------|
//! | [`I16F16`]| Q15.16   | `i32`   | −32 768 ≤ x < 32 768          | 2⁻¹⁶ ≈ 1.5·10⁻⁵ |
//! | [`I32F32`]| Q31.32   | `i64`   | −2 147 483 648 ≤ x < 2³¹      | 2⁻³² ≈ 2.3·10⁻¹⁰|
//!
//! Fixed-point arithmetic wraps (release) or panics (debug) on overflow, so constructors
//! check that every value an evaluation can produce stays within [`Scalar::LIMIT`], half the
//! representable range, and return [`Error::OutOfRange`](crate::Error::OutOfRange) otherwise.
//! After construction, evaluation cannot overflow.

use core::fmt::Debug;
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

pub use fixed::types::{I16F16, I32F32};

mod sealed {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
    impl Sealed for super::I16F16 {}
    impl Sealed for super::I32F32 {}
}

/// A real number type: `f32`, `f64`, [`I16F16`] or [`I32F32`].
///
/// The arithmetic operators are the type's own (IEEE 754 for floats, truncating
/// fixed-point for `fixed`). No operation is fused, so the same expression gives the same
/// bits on the host and on a Cortex-M.
///
/// ```
/// use strak_curves::{Scalar, I16F16};
///
/// fn midpoint<S: Scalar>(a: S, b: S) -> S {
///     (a + b) * S::HALF
/// }
/// assert_eq!(midpoint(1.0_f64, 2.0), 1.5);
/// assert_eq!(midpoint(I16F16::from_num(1), I16F16::from_num(2)), I16F16::from_num(1.5));
/// ```
pub trait Scalar:
    sealed::Sealed
    + Copy
    + PartialEq
    + PartialOrd
    + Debug
    + Default
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
{
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// 1/2.
    const HALF: Self;
    /// 2.
    const TWO: Self;
    /// Largest magnitude a constructor accepts for a value that evaluation will produce:
    /// half the representable range, so that one addition of two such values cannot overflow.
    const LIMIT: f64;
    /// The spacing of representable values near 1 (machine epsilon; 2⁻ᶠ for fixed-point
    /// with f fractional bits).
    const EPSILON: f64;
    /// A short name for messages and benchmark tables: `"f32"`, `"f64"`, `"I16F16"`, ….
    const NAME: &'static str;
    /// `true` for the fixed-point types.
    const IS_FIXED: bool;

    /// The nearest value to `v`, or `None` when `v` is not finite or its magnitude exceeds
    /// [`Scalar::LIMIT`].
    ///
    /// ```
    /// use strak_curves::{Scalar, I16F16};
    /// assert_eq!(<f32 as Scalar>::from_f64(0.5), Some(0.5));
    /// assert_eq!(<I16F16 as Scalar>::from_f64(1.0e6), None);
    /// assert_eq!(<f64 as Scalar>::from_f64(f64::NAN), None);
    /// ```
    fn from_f64(v: f64) -> Option<Self>;

    /// The value as `f64` (exact for every supported type).
    fn to_f64(self) -> f64;

    /// A small integer as this type (exact: every `i16` is representable in every type).
    fn from_i16(n: i16) -> Self;

    /// `|self|`.
    fn abs(self) -> Self;

    /// The square root; `0` for negative input.
    fn sqrt(self) -> Self;

    /// `false` for NaN and ±∞; always `true` for fixed-point.
    fn is_finite(self) -> bool;

    /// The smaller of two values (`self` when they compare equal or are unordered).
    #[inline]
    fn min_of(self, other: Self) -> Self {
        if other < self { other } else { self }
    }

    /// The larger of two values (`self` when they compare equal or are unordered).
    #[inline]
    fn max_of(self, other: Self) -> Self {
        if other > self { other } else { self }
    }

    /// `self` clamped to `[lo, hi]` (assumes `lo <= hi`; NaN maps to `lo`).
    #[inline]
    fn clamp_to(self, lo: Self, hi: Self) -> Self {
        if self >= lo {
            if self > hi { hi } else { self }
        } else {
            lo
        }
    }

    /// Whether a magnitude computed in `f64` (for example a bound on a derivative) is
    /// representable with headroom: finite and at most [`Scalar::LIMIT`].
    #[inline]
    fn fits(magnitude: f64) -> bool {
        magnitude.is_finite() && magnitude.abs() <= Self::LIMIT
    }
}

macro_rules! impl_float {
    ($t:ty, $name:literal, $libm_sqrt:path) => {
        impl Scalar for $t {
            const ZERO: Self = 0.0;
            const ONE: Self = 1.0;
            const HALF: Self = 0.5;
            const TWO: Self = 2.0;
            const LIMIT: f64 = <$t>::MAX as f64 / 2.0;
            const EPSILON: f64 = <$t>::EPSILON as f64;
            const NAME: &'static str = $name;
            const IS_FIXED: bool = false;

            #[inline]
            fn from_f64(v: f64) -> Option<Self> {
                #[allow(clippy::cast_possible_truncation)]
                (v.is_finite() && v.abs() <= Self::LIMIT).then_some(v as $t)
            }
            #[inline]
            fn to_f64(self) -> f64 {
                f64::from(self)
            }
            #[inline]
            fn from_i16(n: i16) -> Self {
                <$t>::from(n)
            }
            #[inline]
            fn abs(self) -> Self {
                if self < 0.0 { -self } else { self }
            }
            #[inline]
            fn sqrt(self) -> Self {
                if self > 0.0 { $libm_sqrt(self) } else { 0.0 }
            }
            #[inline]
            fn is_finite(self) -> bool {
                <$t>::is_finite(self)
            }
        }
    };
}

impl_float!(f32, "f32", libm::sqrtf);
impl_float!(f64, "f64", libm::sqrt);

macro_rules! impl_fixed {
    ($t:ty, $name:literal, $bits:ty, $wide:ty, $frac:expr) => {
        impl Scalar for $t {
            const ZERO: Self = <$t>::ZERO;
            const ONE: Self = <$t>::ONE;
            const HALF: Self = <$t>::from_bits(1 << ($frac - 1));
            const TWO: Self = <$t>::from_bits(2 << $frac);
            const LIMIT: f64 = (<$bits>::MAX >> ($frac + 1)) as f64;
            const EPSILON: f64 = 1.0 / (1_u64 << $frac) as f64;
            const NAME: &'static str = $name;
            const IS_FIXED: bool = true;

            #[inline]
            fn from_f64(v: f64) -> Option<Self> {
                if v.is_finite() && v.abs() <= Self::LIMIT {
                    <$t>::checked_from_num(v)
                } else {
                    None
                }
            }
            #[inline]
            fn to_f64(self) -> f64 {
                self.to_num::<f64>()
            }
            #[inline]
            fn from_i16(n: i16) -> Self {
                <$t>::from_bits(<$bits>::from(n) << $frac)
            }
            #[inline]
            fn abs(self) -> Self {
                self.saturating_abs()
            }
            #[inline]
            fn sqrt(self) -> Self {
                // sqrt(x) in Q(f) is isqrt(raw << f) in integers, computed in a type twice as wide.
                let raw = self.to_bits();
                if raw <= 0 {
                    return <$t>::ZERO;
                }
                #[allow(clippy::cast_sign_loss)]
                let wide = (raw as $wide) << $frac;
                #[allow(clippy::cast_possible_truncation, clippy::cast_possible_wrap)]
                <$t>::from_bits(wide.isqrt() as $bits)
            }
            #[inline]
            fn is_finite(self) -> bool {
                true
            }
        }
    };
}

impl_fixed!(I16F16, "I16F16", i32, u64, 16);
impl_fixed!(I32F32, "I32F32", i64, u128, 32);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constants_are_exact() {
        assert_eq!(<I16F16 as Scalar>::HALF.to_f64(), 0.5);
        assert_eq!(<I32F32 as Scalar>::TWO.to_f64(), 2.0);
        assert_eq!(<I16F16 as Scalar>::LIMIT, 16383.0);
        assert_eq!(<I16F16 as Scalar>::EPSILON, 1.0 / 65536.0);
        assert_eq!(<f32 as Scalar>::from_i16(-7), -7.0);
        assert_eq!(<I32F32 as Scalar>::from_i16(-7).to_f64(), -7.0);
    }

    #[test]
    fn fixed_sqrt_is_floor_of_exact_root() {
        // `fixed` has inherent `sqrt`/`abs` that panic on bad input: call the trait's.
        let four = <I16F16 as Scalar>::from_i16(4);
        assert_eq!(Scalar::sqrt(four).to_f64(), 2.0);
        let two = <I32F32 as Scalar>::TWO;
        let r = Scalar::sqrt(two).to_f64();
        assert!((r - core::f64::consts::SQRT_2).abs() <= <I32F32 as Scalar>::EPSILON);
        assert_eq!(Scalar::sqrt(<I16F16 as Scalar>::from_i16(-1)), I16F16::ZERO);
    }

    #[test]
    fn range_checks() {
        assert!(<I16F16 as Scalar>::from_f64(16383.0).is_some());
        assert!(<I16F16 as Scalar>::from_f64(16384.0).is_none());
        assert!(<f32 as Scalar>::from_f64(1e300).is_none());
        assert!(<f64 as Scalar>::from_f64(f64::INFINITY).is_none());
        assert!(f64::fits(1e300));
        assert!(!I16F16::fits(20000.0));
    }
}
