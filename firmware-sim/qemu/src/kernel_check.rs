//! The tick kernels against the portable kernel on the target, bit for bit: for 1 to 8 axes,
//! on random states (xorshift), every entry point (a tick with the full sample, positions
//! only, in the accumulator's format; a piece switch of each, from RAM and from a blob
//! record) through `Kernel::check_kernels`. Run by the `icount` firmware before it
//! measures; a difference fails the run, and so `cargo xtask qemu`.

use strak_trajectory::{AxisState, Kernel, Q40};

/// Random states per format and number of axes.
pub const STATES: u32 = 64;

/// Marsaglia's xorshift64 (*Xorshift RNGs*, J. Stat. Softw. 8(14), 2003: shifts 13, 7, 17).
#[derive(Clone, Copy, Debug)]
pub struct XorShift(u64);

impl XorShift {
    /// A generator from a non-zero seed.
    pub const fn new(seed: u64) -> Self {
        XorShift(if seed == 0 { 1 } else { seed })
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        self.0 = x;
        x
    }
}

/// A random value of a number format.
pub trait Random: Kernel {
    /// A value from 64 random bits.
    fn random(bits: u64) -> Self;
}

impl Random for Q40 {
    /// Any bits (the additions wrap, as the assembly's `adds`/`adc` do).
    fn random(bits: u64) -> Q40 {
        Q40::from_bits(bits.cast_signed())
    }
}

impl Random for f32 {
    /// A finite value of magnitude below 2¹²⁸ with a random sign, exponent and mantissa
    /// (subnormals included); the exponent 255 (infinity, NaN) is left out.
    fn random(bits: u64) -> f32 {
        #[allow(clippy::cast_possible_truncation)]
        let b = bits as u32;
        let exp = ((b >> 23) & 0xff) % 255;
        f32::from_bits((b & 0x807f_ffff) | (exp << 23))
    }
}

/// `A` random axis states.
fn states<N: Random, const A: usize>(rng: &mut XorShift) -> [AxisState<N>; A] {
    let mut s = [AxisState::ZERO; A];
    for axis in &mut s {
        *axis = AxisState {
            position: N::random(rng.next_u64()),
            delta1: N::random(rng.next_u64()),
            delta2: N::random(rng.next_u64()),
            delta3: N::random(rng.next_u64()),
            velocity: N::random(rng.next_u64()),
            velocity_delta1: N::random(rng.next_u64()),
            velocity_delta2: N::random(rng.next_u64()),
            acceleration: N::random(rng.next_u64()),
            acceleration_delta: N::random(rng.next_u64()),
        };
    }
    s
}

/// A difference: the format, the number of axes, the entry point and the state's index.
#[derive(Clone, Copy, Debug)]
pub struct Mismatch {
    /// The number format.
    pub format: &'static str,
    /// The number of axes.
    pub axes: usize,
    /// The kernel entry point.
    pub entry: &'static str,
    /// Which random state (from 0).
    pub state: u32,
}

/// [`STATES`] random states of `A` axes in `N`.
fn check_axes<N: Random, const A: usize>(rng: &mut XorShift) -> Result<(), Mismatch> {
    for i in 0..STATES {
        let (state, next) = (states::<N, A>(rng), states::<N, A>(rng));
        N::check_kernels(&state, &next, rng.next_u64()).map_err(|entry| Mismatch {
            format: N::NAME,
            axes: A,
            entry,
            state: i,
        })?;
    }
    Ok(())
}

/// 1 to 8 axes in `N`; returns the states checked.
fn check_format<N: Random>(rng: &mut XorShift) -> Result<u32, Mismatch> {
    check_axes::<N, 1>(rng)?;
    check_axes::<N, 2>(rng)?;
    check_axes::<N, 3>(rng)?;
    check_axes::<N, 4>(rng)?;
    check_axes::<N, 5>(rng)?;
    check_axes::<N, 6>(rng)?;
    check_axes::<N, 7>(rng)?;
    check_axes::<N, 8>(rng)?;
    Ok(8 * STATES)
}

/// Every format with a kernel of its own on this target (`Q40` on every Thumb-2 core, `f32`
/// where there is a single-precision FPU); returns the states checked.
///
/// # Errors
/// The first difference.
pub fn check() -> Result<u32, Mismatch> {
    let mut rng = XorShift::new(0x9e37_79b9_7f4a_7c15);
    let mut n = check_format::<Q40>(&mut rng)?;
    if cfg!(target_abi = "eabihf") {
        n += check_format::<f32>(&mut rng)?;
    }
    Ok(n)
}
