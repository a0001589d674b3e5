//! The two forms in which a tick's values reach the caller: rounded into the sample type
//! ([`Sampler::next`](crate::Sampler::next)) or in the accumulator's own format
//! ([`Sampler::next_into`](crate::Sampler::next_into)). The ticks off the fast path are
//! written once, generic over the form.

use strak_curves::Scalar;

use super::Kernel;
use crate::path::{AxisState, Sample};

/// How the values of a tick in `N` become sample values.
pub(crate) trait Form<N: Kernel> {
    /// The sample value type.
    type T: Copy;
    /// Zero.
    const ZERO: Self::T;
    /// A value of the accumulator.
    fn of(x: N) -> Self::T;
    /// A value already in the sample type [`Number::Out`](crate::Number::Out) (the path's
    /// end): kept as it is, or embedded exactly.
    fn of_out(x: N::Out) -> Self::T;
    /// The sample of `state` at `tick`, then one step (the format's tick kernel).
    fn tick<const A: usize>(state: &mut [AxisState<N>; A], tick: u64) -> Sample<Self::T, A>;
}

/// Rounded into [`Number::Out`](crate::Number::Out), as [`Sampler::next`](crate::Sampler::next)
/// delivers.
pub(crate) struct Rounded;

/// In [`Kernel::Native`], as [`Sampler::next_into`](crate::Sampler::next_into) delivers.
pub(crate) struct Native;

impl<N: Kernel> Form<N> for Rounded {
    type T = N::Out;
    const ZERO: N::Out = <N::Out as Scalar>::ZERO;
    #[inline(always)]
    fn of(x: N) -> N::Out {
        x.to_out()
    }
    #[inline(always)]
    fn of_out(x: N::Out) -> N::Out {
        x
    }
    #[inline(always)]
    fn tick<const A: usize>(state: &mut [AxisState<N>; A], tick: u64) -> Sample<N::Out, A> {
        N::tick_sample(state, tick)
    }
}

impl<N: Kernel> Form<N> for Native {
    type T = N::Native;
    const ZERO: N::Native = N::NATIVE_ZERO;
    #[inline(always)]
    fn of(x: N) -> N::Native {
        x.to_native()
    }
    #[inline(always)]
    fn of_out(x: N::Out) -> N::Native {
        N::native_from_out(x)
    }
    #[inline(always)]
    fn tick<const A: usize>(state: &mut [AxisState<N>; A], tick: u64) -> Sample<N::Native, A> {
        let mut s = Sample::splat(N::NATIVE_ZERO);
        N::tick_native(state, tick, &mut s);
        s
    }
}
