//! A curve adapter that counts evaluations, so that the work bounds of the analysis routines
//! can be checked by counting rather than by timing.

use core::cell::Cell;

use crate::curve::{ParamCurve, ParamCurveDeriv, PieceDeriv, ScalarOf};

/// A curve that counts its evaluations: every [`ParamCurve::eval`],
/// [`ParamCurveDeriv::deriv`] and [`PieceDeriv::piece_deriv`] call adds one, whatever the
/// derivative order. The curve itself is evaluated unchanged.
///
/// The analysis routines document their work in evaluations of the curve; wrapping the curve
/// checks such a bound on a given input. Counts, unlike times, do not depend on the machine
/// or its load.
///
/// ```
/// use strak_curves::{Bezier, Counted, flatten_count};
///
/// let arc = Bezier::new([[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]]).unwrap();
/// let counted = Counted::new(&arc);
/// let n = flatten_count(&counted, 1e-3).unwrap();
/// // The resolution check (2·pieces + 2), the first estimate, then at most 12 chord
/// // certificates of 8 evaluations per segment.
/// assert!(counted.take() <= 4 + 2 + 12 * 8 * n as u64);
/// assert_eq!(counted.calls(), 0); // `take` resets the count
/// ```
#[derive(Debug)]
pub struct Counted<'a, C> {
    curve: &'a C,
    calls: Cell<u64>,
}

impl<'a, C> Counted<'a, C> {
    /// Wraps `curve` with a count of zero.
    pub const fn new(curve: &'a C) -> Self {
        Self {
            curve,
            calls: Cell::new(0),
        }
    }

    /// The evaluations since construction or the last [`take`](Self::take).
    pub fn calls(&self) -> u64 {
        self.calls.get()
    }

    /// The evaluations so far, and the count reset to zero.
    pub fn take(&self) -> u64 {
        self.calls.replace(0)
    }

    fn count(&self) {
        self.calls.set(self.calls.get().saturating_add(1));
    }
}

impl<C: ParamCurve> ParamCurve for Counted<'_, C> {
    type Point = C::Point;
    fn domain(&self) -> (ScalarOf<C>, ScalarOf<C>) {
        self.curve.domain()
    }
    fn eval(&self, u: ScalarOf<C>) -> C::Point {
        self.count();
        self.curve.eval(u)
    }
    fn piece_count(&self) -> usize {
        self.curve.piece_count()
    }
    fn piece_domain(&self, i: usize) -> (ScalarOf<C>, ScalarOf<C>) {
        self.curve.piece_domain(i)
    }
}

impl<C: ParamCurveDeriv> ParamCurveDeriv for Counted<'_, C> {
    fn deriv(&self, u: ScalarOf<C>, k: usize) -> C::Point {
        self.count();
        self.curve.deriv(u, k)
    }
}

impl<C: PieceDeriv> PieceDeriv for Counted<'_, C> {
    fn piece_deriv(&self, piece: usize, u: ScalarOf<C>, k: usize) -> C::Point {
        self.count();
        self.curve.piece_deriv(piece, u, k)
    }
}
