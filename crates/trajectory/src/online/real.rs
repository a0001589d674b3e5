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

    /// The square root of a positive value, correctly rounded (IEEE 754); 0 for any other,
    /// NaN included: [`Scalar::sqrt`], with the same bits. In `f32` on a core with a
    /// single-precision FPU (Cortex-M4F/M7/M33F) it is the FPU's `vsqrt.f32` instead of the
    /// software square root.
    ///
    /// ```
    /// use strak_trajectory::Real;
    /// assert_eq!((2.0_f32.root(), 0.0_f32.root(), (-1.0_f32).root()), (2.0_f32.sqrt(), 0.0, 0.0));
    /// assert_eq!(f64::NAN.root(), 0.0);
    /// ```
    #[inline]
    fn root(self) -> Self {
        Scalar::sqrt(self)
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

    #[cfg(strak_vfp)]
    #[inline]
    fn root(self) -> Self {
        if self > 0.0 { vfp::sqrt(self) } else { 0.0 }
    }
}

/// The FPU's square root (`strak_vfp`, set by `build.rs`).
#[cfg(strak_vfp)]
#[allow(unsafe_code)]
mod vfp {
    /// `vsqrt.f32`: the IEEE-754 square root, correctly rounded to nearest like the software
    /// one (`libm::sqrtf`); the firmware checks the two against each other, bit for bit.
    #[inline]
    pub(super) fn sqrt(x: f32) -> f32 {
        let bits: u32;
        // SAFETY: three register instructions (the value into `s0`, its square root, back
        // into a core register): no memory, no stack; `s0` is declared clobbered. The
        // FPSCR's rounding mode is the runtime's (round to nearest), as for every `f32`
        // operation the compiler emits.
        unsafe {
            core::arch::asm!(
                "vmov s0, {x}",
                "vsqrt.f32 s0, s0",
                "vmov {root}, s0",
                x = in(reg) x.to_bits(),
                root = lateout(reg) bits,
                out("s0") _,
                options(pure, nomem, nostack),
            );
        }
        f32::from_bits(bits)
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
