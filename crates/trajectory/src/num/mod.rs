//! The number formats a compiled path is played back in: `f32`, `f64` and the fixed-point
//! accumulator [`Q40`].

use core::fmt;
use core::ops::{Add, Mul, Neg, Sub};

use strak_curves::{I32F32, Scalar};

mod format;

pub use format::{LIMIT_CHECK_RELATIVE, NumberFormat, ParseNumberFormatError};

/// The lowest and highest control rates in Hz.
pub(crate) const RATE_RANGE: (f64, f64) = (100.0, 100_000.0);

mod sealed {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
    impl Sealed for super::Q40 {}
}

/// A fixed-point number with 40 fractional bits in an `i64` (Q23.40): range ±2²³ units,
/// resolution 2⁻⁴⁰ ≈ 9.1·10⁻¹³ units.
///
/// It is the accumulator of fixed-point playback: additions are exact integer additions,
/// products are rounded to nearest (computed in `i128`). The arithmetic operators wrap
/// instead of panicking; the compiler proves, for every path, that no value playback forms
/// exceeds [`Number::LIMIT`] = 2²², so they never do.
///
/// ```
/// use strak_trajectory::{Number, Q40};
///
/// let x = Q40::from_f64(1.5).unwrap();
/// assert_eq!(x.to_bits(), 3 << 39);
/// assert_eq!((x * x).to_f64(), 2.25);
/// assert_eq!(x.to_out().to_num::<f64>(), 1.5); // as `I32F32`
/// assert_eq!(Q40::from_f64(5.0e6), None); // beyond the checked range ±2²²
/// ```
#[derive(Clone, Copy, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[repr(transparent)]
pub struct Q40(i64);

impl Q40 {
    /// Fractional bits.
    pub const FRAC_BITS: u32 = 40;

    /// The number with the given raw bits (value = `bits / 2⁴⁰`).
    ///
    /// ```
    /// use strak_trajectory::{Number, Q40};
    /// assert_eq!(Q40::from_bits(1 << 40).to_f64(), 1.0);
    /// ```
    pub const fn from_bits(bits: i64) -> Self {
        Q40(bits)
    }

    /// The raw bits (value · 2⁴⁰).
    ///
    /// ```
    /// use strak_trajectory::{Number, Q40};
    /// assert_eq!(Q40::from_f64(-0.25).unwrap().to_bits(), -(1 << 38));
    /// ```
    pub const fn to_bits(self) -> i64 {
        self.0
    }
}

impl fmt::Debug for Q40 {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Q40({})", self.to_f64())
    }
}

impl fmt::Display for Q40 {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&self.to_f64(), f)
    }
}

impl Add for Q40 {
    type Output = Q40;
    /// Exact integer addition (wrapping; the compiler's range check excludes overflow).
    #[inline]
    fn add(self, rhs: Q40) -> Q40 {
        Q40(self.0.wrapping_add(rhs.0))
    }
}

impl Sub for Q40 {
    type Output = Q40;
    /// Exact integer subtraction (wrapping; the compiler's range check excludes overflow).
    #[inline]
    fn sub(self, rhs: Q40) -> Q40 {
        Q40(self.0.wrapping_sub(rhs.0))
    }
}

impl Neg for Q40 {
    type Output = Q40;
    #[inline]
    fn neg(self) -> Q40 {
        Q40(self.0.wrapping_neg())
    }
}

impl Mul for Q40 {
    type Output = Q40;
    /// The product rounded to nearest (ties up), computed in `i128`.
    #[inline]
    fn mul(self, rhs: Q40) -> Q40 {
        let wide = i128::from(self.0) * i128::from(rhs.0) + (1_i128 << 39);
        #[allow(clippy::cast_possible_truncation)]
        Q40((wide >> 40) as i64)
    }
}

/// 2⁴⁰ as `f64`.
const Q40_SCALE: f64 = (1_u64 << 40) as f64;

/// The number format of a compiled path's playback: `f32`, `f64` or [`Q40`] (sealed).
///
/// Everything the sampler computes per tick is written against this trait: the
/// forward-difference additions ([`Add`]), and for feed override the products ([`Mul`]) of
/// Newton's forward-difference formula and of the feed factor.
///
/// Planning and compiling run in `f64`. The compiler rounds every stored value of a path
/// (the forward-difference states of each piece) **once** into the path's [`Number`] format;
/// playback then only adds (and, while the feed factor is not 1, multiplies) in that format.
///
/// # Formats
///
/// | format  | accumulator            | range (checked: [`Number::LIMIT`])  | resolution         | sample type      |
/// |---------|------------------------|-------------------------------------|--------------------|------------------|
/// | `f32`   | IEEE binary32          | ±1.7·10³⁸                           | 2⁻²⁴ relative      | `f32`            |
/// | `f64`   | IEEE binary64          | ±9·10³⁰⁷                            | 2⁻⁵³ relative      | `f64`            |
/// | [`Q40`] | `i64`, Q23.40          | ±2²² = ±4 194 304 (of ±2²³)         | 2⁻⁴⁰ ≈ 9.1·10⁻¹³   | [`I32F32`]       |
///
/// In `Q40` the additions of forward differencing are exact integer additions, so the only
/// error of a piece is the rounding of its start state (at most ½ ulp per value), propagated
/// over the piece: after `i` ticks the position is off by at most
/// `½·2⁻⁴⁰·(1 + i + C(i,2) + C(i,3))`, about 1.3·10⁻⁶ units at `i = 256`. A piece switch loads
/// the next piece's state, so the error does not grow from piece to piece. In `f32` and `f64`
/// every addition rounds as well; [`Path::playback_bound`](crate::PathHeader::playback_bound) states
/// the resulting bound of each path. In `f32` it is dominated by the `n` position additions
/// per piece, about `½ε·|x|·(n + 1)` ≈ 1.5·10⁻⁵·|x| at `n = 256` for positions of magnitude
/// `|x|` (a worst case; measured errors are about a quarter of it). For positions of more
/// than a few units at tight tolerances use `Q40` (or `f64`).
///
/// `Q40` samples are delivered as [`I32F32`] (the raw value rounded to nearest and shifted
/// right by 8 bits), the fixed-point type the curves of `strak-curves` use.
///
/// ```
/// use strak_trajectory::{Number, Q40};
///
/// fn tick<N: Number>(f: N, d1: N) -> N { f + d1 }
/// assert_eq!(tick(1.0_f32, 0.5), 1.5);
/// let q = tick(Q40::from_f64(1.0).unwrap(), Q40::from_f64(0.5).unwrap());
/// assert_eq!(q.to_f64(), 1.5);
/// assert_eq!(<Q40 as Number>::NAME, "Q40");
/// ```
pub trait Number:
    sealed::Sealed
    + Copy
    + fmt::Debug
    + Default
    + PartialEq
    + PartialOrd
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Neg<Output = Self>
{
    /// The type samples are delivered in: `f32`, `f64` or [`I32F32`].
    type Out: Scalar;
    /// The format as a value ([`NumberFormat::F32`], [`NumberFormat::F64`],
    /// [`NumberFormat::Q40`]).
    const FORMAT: NumberFormat;
    /// The format id written into serialized paths ([`NumberFormat::id`]: 1 = `f32`,
    /// 2 = `f64`, 3 = `Q40`).
    const FORMAT_ID: u8 = Self::FORMAT.id();
    /// A short name ([`NumberFormat::name`]): `"f32"`, `"f64"`, `"Q40"`.
    const NAME: &'static str = Self::FORMAT.name();
    /// `true` for [`Q40`].
    const IS_FIXED: bool;
    /// Bytes per value in a serialized path ([`NumberFormat::bytes`]).
    const BYTES: usize = Self::FORMAT.bytes();
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// 1/2 (exact).
    const HALF: Self;
    /// 1/3 (rounded to nearest).
    const THIRD: Self;
    /// The spacing of representable values at 1 (machine epsilon; 2⁻⁴⁰ for `Q40`).
    const EPSILON: Self;
    /// The largest magnitude the compiler lets any value of playback reach: half the
    /// representable range, so that the sum of two such values cannot overflow.
    const LIMIT: f64;
    /// The smallest positive value (the resolution of fixed-point; the smallest normal
    /// float).
    const MIN_POSITIVE: f64;

    /// The nearest value to `v`, or `None` when `v` is not finite or `|v| > LIMIT`.
    ///
    /// ```
    /// use strak_trajectory::Number;
    /// assert_eq!(<f32 as Number>::from_f64(0.1), Some(0.1_f32));
    /// assert_eq!(<f64 as Number>::from_f64(f64::NAN), None);
    /// ```
    fn from_f64(v: f64) -> Option<Self>;

    /// The value as `f64` (exact for `f32`, `f64` and `Q40` values below 2¹³ in magnitude;
    /// rounded to nearest above).
    fn to_f64(self) -> f64;

    /// The value in the sample type: itself for floats, [`I32F32`] rounded to nearest for
    /// `Q40` (raw `+ 2⁷`, shifted right by 8).
    fn to_out(self) -> Self::Out;

    /// The sample-type value nearest to `v`, or `None` when `v` is not finite or out of range.
    fn out_from_f64(v: f64) -> Option<Self::Out> {
        <Self::Out as Scalar>::from_f64(v)
    }

    /// A bound on the error of rounding a value of magnitude at most `magnitude` into this
    /// format (storage, products): `½ε·magnitude` plus the smallest subnormal for floats
    /// (below the normal range the spacing no longer shrinks with the value: a value under
    /// half the smallest subnormal rounds to 0), `2⁻⁴¹` for `Q40`.
    fn rounding_error(magnitude: f64) -> f64;

    /// A bound on the rounding error of one addition whose result has magnitude at most
    /// `magnitude`: as [`Number::rounding_error`] for floats, `0` for `Q40` (exact).
    fn addition_error(magnitude: f64) -> f64;

    /// A bound on the error of converting a value to [`Number::Out`]: 0 for floats,
    /// `2⁻³³` for `Q40` → `I32F32`.
    const OUT_ERROR: f64;

    /// Writes the value, little-endian, into the first [`Number::BYTES`] bytes of `out`
    /// (fewer when `out` is shorter).
    fn write_le(self, out: &mut [u8]);

    /// Reads a value written by [`Number::write_le`] (missing bytes read as 0).
    fn read_le(bytes: &[u8]) -> Self;

    /// Writes a sample-type value, little-endian, into the first [`Number::BYTES`] bytes.
    fn write_out_le(v: Self::Out, out: &mut [u8]);

    /// Reads a sample-type value written by [`Number::write_out_le`].
    fn read_out_le(bytes: &[u8]) -> Self::Out;

    /// `true` unless NaN or infinite (always for `Q40`).
    fn is_finite(self) -> bool;

    /// The product with an integer: exact in `Q40` (an integer multiplication, wrapping; the
    /// callers keep it in range), rounded once in floats.
    fn mul_int(self, k: i64) -> Self;

    /// Crate-internal (the trait is sealed): the accumulator value whose sample value is `v`
    /// (exact: `from_out(v).to_out() == v` for every `v` in range; the path checks it).
    #[doc(hidden)]
    fn from_out(v: Self::Out) -> Self;
}

#[inline]
fn write_bytes(src: &[u8], out: &mut [u8]) {
    for (o, s) in out.iter_mut().zip(src) {
        *o = *s;
    }
}

#[inline]
fn read_bytes<const B: usize>(bytes: &[u8]) -> [u8; B] {
    let mut b = [0_u8; B];
    for (o, s) in b.iter_mut().zip(bytes) {
        *o = *s;
    }
    b
}

impl Number for f32 {
    type Out = f32;
    const FORMAT: NumberFormat = NumberFormat::F32;
    const IS_FIXED: bool = false;
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const HALF: Self = 0.5;
    const THIRD: Self = 1.0 / 3.0;
    const EPSILON: Self = f32::EPSILON;
    const LIMIT: f64 = f32::MAX as f64 / 2.0;
    const MIN_POSITIVE: f64 = f32::MIN_POSITIVE as f64;
    const OUT_ERROR: f64 = 0.0;

    #[inline]
    fn from_f64(v: f64) -> Option<Self> {
        #[allow(clippy::cast_possible_truncation)]
        (v.is_finite() && v.abs() <= <Self as Number>::LIMIT).then_some(v as f32)
    }
    #[inline]
    fn to_f64(self) -> f64 {
        f64::from(self)
    }
    #[inline]
    fn to_out(self) -> f32 {
        self
    }
    fn from_out(v: f32) -> f32 {
        v
    }
    fn rounding_error(magnitude: f64) -> f64 {
        0.5 * f64::from(f32::EPSILON) * magnitude.abs() + f64::from(f32::from_bits(1))
    }
    fn addition_error(magnitude: f64) -> f64 {
        Self::rounding_error(magnitude)
    }
    #[inline]
    fn write_le(self, out: &mut [u8]) {
        write_bytes(&self.to_bits().to_le_bytes(), out);
    }
    #[inline]
    fn read_le(bytes: &[u8]) -> Self {
        f32::from_bits(u32::from_le_bytes(read_bytes(bytes)))
    }
    fn write_out_le(v: f32, out: &mut [u8]) {
        v.write_le(out);
    }
    fn read_out_le(bytes: &[u8]) -> f32 {
        Self::read_le(bytes)
    }
    #[inline]
    fn is_finite(self) -> bool {
        f32::is_finite(self)
    }
    #[inline]
    fn mul_int(self, k: i64) -> Self {
        #[allow(clippy::cast_precision_loss)]
        let k = k as f32;
        self * k
    }
}

impl Number for f64 {
    type Out = f64;
    const FORMAT: NumberFormat = NumberFormat::F64;
    const IS_FIXED: bool = false;
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const HALF: Self = 0.5;
    const THIRD: Self = 1.0 / 3.0;
    const EPSILON: Self = f64::EPSILON;
    const LIMIT: f64 = f64::MAX / 2.0;
    const MIN_POSITIVE: f64 = f64::MIN_POSITIVE;
    const OUT_ERROR: f64 = 0.0;

    #[inline]
    fn from_f64(v: f64) -> Option<Self> {
        (v.is_finite() && v.abs() <= <Self as Number>::LIMIT).then_some(v)
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self
    }
    #[inline]
    fn to_out(self) -> f64 {
        self
    }
    fn from_out(v: f64) -> f64 {
        v
    }
    fn rounding_error(magnitude: f64) -> f64 {
        0.5 * f64::EPSILON * magnitude.abs() + f64::from_bits(1)
    }
    fn addition_error(magnitude: f64) -> f64 {
        Self::rounding_error(magnitude)
    }
    #[inline]
    fn write_le(self, out: &mut [u8]) {
        write_bytes(&self.to_bits().to_le_bytes(), out);
    }
    #[inline]
    fn read_le(bytes: &[u8]) -> Self {
        f64::from_bits(u64::from_le_bytes(read_bytes(bytes)))
    }
    fn write_out_le(v: f64, out: &mut [u8]) {
        v.write_le(out);
    }
    fn read_out_le(bytes: &[u8]) -> f64 {
        Self::read_le(bytes)
    }
    #[inline]
    fn is_finite(self) -> bool {
        f64::is_finite(self)
    }
    #[inline]
    fn mul_int(self, k: i64) -> Self {
        #[allow(clippy::cast_precision_loss)]
        let k = k as f64;
        self * k
    }
}

impl Number for Q40 {
    type Out = I32F32;
    const FORMAT: NumberFormat = NumberFormat::Q40;
    const IS_FIXED: bool = true;
    const ZERO: Self = Q40(0);
    const ONE: Self = Q40(1 << 40);
    const HALF: Self = Q40(1 << 39);
    // round(2⁴⁰ / 3)
    const THIRD: Self = Q40(((1_i64 << 40) + 1) / 3);
    const EPSILON: Self = Q40(1);
    const LIMIT: f64 = (1_u64 << 22) as f64;
    const MIN_POSITIVE: f64 = 1.0 / Q40_SCALE;
    const OUT_ERROR: f64 = 1.0 / (1_u64 << 33) as f64;

    #[inline]
    fn from_f64(v: f64) -> Option<Self> {
        if v.is_finite() && v.abs() <= Self::LIMIT {
            // |v·2⁴⁰| ≤ 2⁶², exactly scaled (power of two), then rounded: fits an i64.
            #[allow(clippy::cast_possible_truncation)]
            Some(Q40(libm::round(v * Q40_SCALE) as i64))
        } else {
            None
        }
    }
    #[inline]
    fn to_f64(self) -> f64 {
        #[allow(clippy::cast_precision_loss)]
        let raw = self.0 as f64;
        raw / Q40_SCALE
    }
    #[inline]
    fn to_out(self) -> I32F32 {
        I32F32::from_bits(self.0.wrapping_add(1 << 7) >> 8)
    }
    fn from_out(v: I32F32) -> Q40 {
        Q40(v.to_bits().wrapping_shl(8))
    }
    fn rounding_error(_magnitude: f64) -> f64 {
        0.5 / Q40_SCALE
    }
    fn addition_error(_magnitude: f64) -> f64 {
        0.0
    }
    #[inline]
    fn write_le(self, out: &mut [u8]) {
        write_bytes(&self.0.to_le_bytes(), out);
    }
    #[inline]
    fn read_le(bytes: &[u8]) -> Self {
        Q40(i64::from_le_bytes(read_bytes(bytes)))
    }
    fn write_out_le(v: I32F32, out: &mut [u8]) {
        write_bytes(&v.to_bits().to_le_bytes(), out);
    }
    fn read_out_le(bytes: &[u8]) -> I32F32 {
        I32F32::from_bits(i64::from_le_bytes(read_bytes(bytes)))
    }
    #[inline]
    fn is_finite(self) -> bool {
        true
    }
    #[inline]
    fn mul_int(self, k: i64) -> Self {
        Q40(self.0.wrapping_mul(k))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn q40_constants_and_conversions() {
        assert_eq!(Q40::ONE.to_f64(), 1.0);
        assert_eq!(Q40::HALF.to_f64(), 0.5);
        assert!((Q40::THIRD.to_f64() - 1.0 / 3.0).abs() <= 0.5 / Q40_SCALE);
        assert_eq!(Q40::from_f64(4_194_304.0).map(Q40::to_bits), Some(1 << 62));
        assert_eq!(Q40::from_f64(4_194_304.5), None);
        assert_eq!(Q40::from_f64(f64::INFINITY), None);
        // rounding to nearest
        assert_eq!(Q40::from_f64(0.7 / Q40_SCALE).map(Q40::to_bits), Some(1));
        assert_eq!(Q40::from_f64(-0.7 / Q40_SCALE).map(Q40::to_bits), Some(-1));
        assert_eq!(Q40::MIN_POSITIVE, 1.0 / Q40_SCALE);
    }

    #[test]
    fn q40_arithmetic_is_exact_or_rounded_to_nearest() {
        let a = Q40::from_bits(3);
        let b = Q40::from_bits(-5);
        assert_eq!((a + b).to_bits(), -2);
        assert_eq!((a - b).to_bits(), 8);
        assert_eq!((-a).to_bits(), -3);
        // 1.5 · 2.5 = 3.75 exactly
        let x = Q40::from_f64(1.5).unwrap() * Q40::from_f64(2.5).unwrap();
        assert_eq!(x.to_f64(), 3.75);
        // (3 ulp) · 0.5 = 1.5 ulp → 2 ulp (ties up); (−3 ulp) · 0.5 → −1 ulp (ties up)
        assert_eq!((a * Q40::HALF).to_bits(), 2);
        assert_eq!((Q40::from_bits(-3) * Q40::HALF).to_bits(), -1);
        // multiplying by one is exact
        let y = Q40::from_bits(-123_456_789_012_345);
        assert_eq!(y * Q40::ONE, y);
        assert_eq!(Q40::from_bits(-7).mul_int(3).to_bits(), -21);
        assert_eq!(0.25_f32.mul_int(-6), -1.5);
    }

    #[test]
    fn q40_output_rounds_to_nearest_i32f32() {
        assert_eq!(Q40::from_bits(127).to_out().to_bits(), 0);
        assert_eq!(Q40::from_bits(128).to_out().to_bits(), 1);
        assert_eq!(Q40::from_bits(-129).to_out().to_bits(), -1);
        assert_eq!(Q40::from_bits(-128).to_out().to_bits(), 0);
        let x = Q40::from_f64(-1234.5678).unwrap();
        let out = x.to_out().to_num::<f64>();
        assert!((out - x.to_f64()).abs() <= Q40::OUT_ERROR);
        // I32F32 → f64 → Q40 → I32F32 is the identity
        let p = I32F32::from_bits(0x1234_5678_9abc);
        let q = Q40::from_f64(p.to_num::<f64>()).unwrap();
        assert_eq!(q.to_out(), p);
    }

    #[test]
    fn float_formats() {
        assert_eq!(<f32 as Number>::from_f64(1.0e39), None);
        assert_eq!(<f32 as Number>::from_f64(0.1), Some(0.1_f32));
        assert_eq!(<f64 as Number>::from_f64(-2.5), Some(-2.5));
        assert_eq!(
            f32::rounding_error(2.0),
            f64::from(f32::EPSILON) + f64::from(f32::from_bits(1))
        );
        assert_eq!(
            <f64 as Number>::addition_error(1.0),
            f64::EPSILON / 2.0 + f64::from_bits(1)
        );
        // below the normal range the error is absolute: 5.7e-49 rounds to 0 in f32
        let tiny = 5.665_177_660_311_074e-49;
        #[allow(clippy::cast_possible_truncation)]
        let rounded = f64::from(tiny as f32);
        assert!((rounded - tiny).abs() <= f32::rounding_error(tiny));
        assert!((rounded - tiny).abs() > 0.5 * f64::from(f32::EPSILON) * tiny);
        assert_eq!(Q40::addition_error(1.0e6), 0.0);
    }

    #[test]
    fn byte_round_trips() {
        let mut buf = [0_u8; 8];
        let v = -3.25e-7_f32;
        v.write_le(&mut buf);
        assert_eq!(f32::read_le(&buf).to_bits(), v.to_bits());
        let w = core::f64::consts::PI;
        w.write_le(&mut buf);
        assert_eq!(f64::read_le(&buf), w);
        let q = Q40::from_bits(-0x0123_4567_89ab_cdef);
        q.write_le(&mut buf);
        assert_eq!(Q40::read_le(&buf), q);
        let o = I32F32::from_bits(-77);
        Q40::write_out_le(o, &mut buf);
        assert_eq!(Q40::read_out_le(&buf), o);
        // short buffers neither panic nor invent bytes
        let mut short = [0_u8; 3];
        q.write_le(&mut short);
        assert_eq!(short, [0x11, 0x32, 0x54]);
        assert_eq!(Q40::read_le(&short).to_bits(), 0x54_3211);
    }
}
