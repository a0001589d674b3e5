//! The header of a path whose pieces a stream compiled ([`plan_path_into`]): its peaks
//! read from the pieces, the feed limits derived from them as [`compile`](super::compile)
//! derives them, and its end at rest.
//!
//! [`plan_path_into`]: crate::plan_path_into

use super::options::CompileOptions;
use super::peaks::Peaks;
use super::{LawPeaks, path_meta};
use crate::error::Error;
use crate::num::Number;
use crate::path::{AxisState, Path};
use crate::plan::{Limits, MotionLimits};

/// What a stream planned and compiled a path under: the control rate, the tolerance its
/// pieces were fitted to, the limits its motion keeps to (the feed reserve taken off) and
/// the machine's limits with the share of them reserved for feed changes.
pub(crate) struct StreamedPlan<'a, const A: usize> {
    pub(crate) rate: f64,
    pub(crate) tolerance: f64,
    pub(crate) promised: &'a MotionLimits,
    pub(crate) limits: &'a Limits<A>,
    pub(crate) feed_share: f64,
}

/// Completes the header of `path`, whose pieces (from tick 0 on, ending at rest at `end`)
/// a stream compiled under `plan`, and validates it ([`Path`]'s checks: pieces that follow
/// on, values in the range of `N`, the end continuing the last piece).
///
/// # Errors
/// [`Error::FeedReserveExceeded`] when the pieces use more than the promised share of a
/// limit; the validation's errors ([`Error::EmptyPath`] without pieces,
/// [`Error::OutOfRange`], [`Error::CorruptBlob`] for an end the last piece does not reach).
pub(crate) fn seal_streamed<N: Number, const A: usize, const P: usize>(
    path: &mut Path<N, A, P>,
    end: &[f64; A],
    plan: &StreamedPlan<'_, A>,
) -> Result<(), Error> {
    let period = 1.0 / plan.rate;
    let peaks = path.pieces.iter().fold(Peaks::default(), |m, piece| {
        let coeffs = piece.axes.map(|s| monomial(&s));
        m.max(Peaks::of_piece(&coeffs, f64::from(piece.ticks), period))
    });
    let ticks = path.pieces.last().map_or(0, |p| p.start + p.ticks);
    let law = LawPeaks {
        peaks,
        promised: Some(plan.promised),
        axes: A,
    };
    let options = CompileOptions::new()
        .with_path_limits(plan.limits)
        .with_feed_share(plan.feed_share);
    let duration = f64::from(ticks) * period;
    path.header.meta = path_meta(
        &law,
        &|| None,
        plan.rate,
        duration,
        plan.tolerance,
        &options,
    )?;
    let out = |v: f64| N::out_from_f64(v).ok_or(Error::OutOfRange);
    let zero = out(0.0)?;
    let e = &mut path.header.end;
    for (slot, &x) in e.position.iter_mut().zip(end) {
        *slot = out(x)?;
    }
    e.velocity = [zero; A];
    e.acceleration = [zero; A];
    path.seal()
}

/// The position polynomial `a + b·i + c·i² + d·i³` (`i` in ticks) of a stored piece state,
/// from its forward differences `Δ¹ = b + c + d`, `Δ² = 2c + 6d`, `Δ³ = 6d`.
fn monomial<N: Number>(state: &AxisState<N>) -> [f64; 4] {
    let s = state.to_f64();
    let d = s.delta3 / 6.0;
    let c = 0.5 * (s.delta2 - s.delta3);
    [s.position, s.delta1 - c - d, c, d]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_state_gives_back_its_polynomial() {
        let (a, b, c, d) = (1.5, -0.25, 0.125, 0.0625);
        let p = |i: f64| a + b * i + c * i * i + d * i * i * i;
        let state = AxisState::<f64> {
            position: p(0.0),
            delta1: p(1.0) - p(0.0),
            delta2: p(2.0) - 2.0 * p(1.0) + p(0.0),
            delta3: p(3.0) - 3.0 * p(2.0) + 3.0 * p(1.0) - p(0.0),
            ..AxisState::ZERO
        };
        assert_eq!(monomial(&state), [a, b, c, d]);
    }
}
