//! The owned path: the header and up to `P` pieces in a fixed-capacity vector.

use core::ops::Deref;

use heapless::Vec;

use super::header::{PathHeader, Validator};
use super::sample::Sample;
use super::state::{AxisState, Piece};
use super::view::PathView;
use crate::error::Error;
use crate::num::Number;

/// A compiled path with `A` axes and room for `P` pieces, played back in the number format
/// `N` (see [`Number`]): what [`compile`](crate::compile) produces, [`Sampler`](crate::Sampler)
/// plays and [`Path::to_bytes`] / [`Path::from_bytes`] serialize. It dereferences to its
/// [`PathHeader`] (rate, duration, end, bounds); [`Path::view`] gives the capacity-free view
/// the sampler plays.
///
/// Tick `k` of the path is at time `k·T` (`T = 1/rate`), `k = 0 ..= ticks()`. The time law
/// was stretched by [`time_scale`](crate::PathHeader::time_scale) ≤ 1 so that the motion ends exactly on
/// tick [`ticks()`](crate::PathHeader::ticks): path time `t` corresponds to time `t · time_scale` of the
/// [`Timing`](crate::Timing).
///
/// # Accuracy
/// At every tick the position of the compiled spline is within
/// [`tolerance()`](crate::PathHeader::tolerance) of the exact `c(u(t))` (the compiler checks the quarter
/// points of every piece against half the tolerance; tests check every tick), and playback in
/// the number format adds at most [`playback_bound()`](crate::PathHeader::playback_bound).
///
/// # Range
/// Every path was checked, in `f64`, to keep every value and partial sum playback forms
/// (forward differencing, Newton evaluation at a fractional tick, feed scaling) within
/// [`Number::LIMIT`]; [`Error::OutOfRange`] otherwise.
///
/// ```
/// use strak_trajectory::{compile, Along, CompileOptions, Path, Q40, Timing};
/// use strak_curves::Bezier;
/// struct Ramp;
/// impl Timing for Ramp {
///     fn duration(&self) -> f64 { 0.5 }
///     fn param(&self, t: f64) -> (f64, f64) { (t.clamp(0.0, 0.5) * 2.0, 2.0) }
/// }
/// let curve = Bezier::new([[0.0_f64, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]])?;
/// let trajectory = Along::new(&curve, &Ramp);
/// let path: Path<Q40, 2, 16> = compile(&trajectory, 1_000.0, &CompileOptions::default())?;
/// assert_eq!(path.ticks(), 500);
/// assert_eq!(path.end_position()[0].to_num::<f64>(), 4.0);
/// let mid = path.eval(250.0); // the compiled polynomial, in f64
/// assert!((mid.position[0] - 2.0).abs() < 1e-3 && (mid.position[1] - 1.5).abs() < 1e-3);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
// The pieces last (`repr(C)` keeps the declared order): an empty path is then the header
// followed by unwritten storage, so that `Box::new(Path::new())` in an optimized build writes
// the header and the length into the allocation and never the storage, and never needs a
// stack frame the size of the path.
#[repr(C)]
pub struct Path<N: Number, const A: usize, const P: usize> {
    pub(crate) header: PathHeader<N, A>,
    pub(crate) pieces: Vec<Piece<N, A>, P>,
}

impl<N: Number, const A: usize, const P: usize> Default for Path<N, A, P> {
    #[inline]
    fn default() -> Self {
        Self::new()
    }
}

impl<N: Number, const A: usize, const P: usize> Deref for Path<N, A, P> {
    type Target = PathHeader<N, A>;

    fn deref(&self) -> &PathHeader<N, A> {
        &self.header
    }
}

impl<N: Number, const A: usize, const P: usize> Path<N, A, P> {
    /// An empty path (no pieces, no ticks): storage that can sit in a `static` (filled by
    /// [`Path::read_bytes`]). Played, it gives one sample at the
    /// origin and is finished.
    ///
    /// ```
    /// use strak_trajectory::Path;
    /// static mut PATH: Path<f32, 3, 256> = Path::new();
    /// let empty: Path<f64, 2, 8> = Path::new();
    /// assert_eq!((empty.ticks(), empty.pieces().len()), (0, 0));
    /// ```
    // Inlined into the caller (never a shared out-of-line copy), so that `Box::new(Path::new())`
    // writes the header and the length straight into the allocation.
    #[inline]
    pub const fn new() -> Self {
        Path {
            header: PathHeader::EMPTY,
            pieces: Vec::new(),
        }
    }

    /// Validates the pieces in `self.pieces` with the description and end already in the
    /// header (the checks of [`Validator`]) and completes the header in place; on an error
    /// the path is left empty.
    ///
    /// # Errors
    /// See [`Validator`]: [`Error::InvalidRate`], [`Error::InvalidLimit`],
    /// [`Error::CorruptBlob`], [`Error::OutOfRange`], [`Error::EmptyPath`].
    pub(crate) fn seal(&mut self) -> Result<(), Error> {
        let result = self.validate();
        if result.is_err() {
            self.clear();
        }
        result
    }

    fn validate(&mut self) -> Result<(), Error> {
        let mut check = Validator::begin(&mut self.header)?;
        for piece in &self.pieces {
            check.piece(piece.start, piece.ticks, &piece.axes)?;
        }
        let last = self.pieces.last().map(|p| {
            (p.ticks, |a: usize| {
                p.axes.get(a).copied().unwrap_or(AxisState::ZERO)
            })
        });
        check.finish(last)
    }

    /// Empties the path (no pieces, the header of [`Path::new`]).
    pub(crate) fn clear(&mut self) {
        self.pieces.clear();
        self.header = PathHeader::EMPTY;
    }

    /// The pieces, in order.
    pub fn pieces(&self) -> &[Piece<N, A>] {
        &self.pieces
    }

    /// The path as the capacity-free view that [`Sampler`](crate::Sampler) plays.
    ///
    /// ```
    /// use strak_trajectory::{Path, PathView};
    /// let path: Path<f32, 2, 16> = Path::new();
    /// let view: PathView<'_, f32, 2> = path.view();
    /// assert_eq!(view.piece_count(), 0);
    /// ```
    pub fn view(&self) -> PathView<'_, N, A> {
        PathView::of_pieces(&self.header, &self.pieces)
    }

    /// The compiled polynomial at a (possibly fractional) tick, evaluated in `f64` from the
    /// stored states: see [`PathView::eval`].
    pub fn eval(&self, tick: f64) -> Sample<f64, A> {
        self.view().eval(tick)
    }
}

impl<'a, N: Number, const A: usize, const P: usize> From<&'a Path<N, A, P>> for PathView<'a, N, A> {
    fn from(path: &'a Path<N, A, P>) -> Self {
        path.view()
    }
}
