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

    /// Bounds `(e_v, e_a)` on the error that playback in the number format adds to the
    /// velocity and acceleration channels of any sample at feed 1, as
    /// [`playback_bound`](PathHeader::playback_bound) bounds the position's: per piece of
    /// `n` ticks and axis, with the stored values `v, Δv¹, Δv²` and `a, Δa` (magnitudes
    /// with their growth over the piece), `e_v = r(v) + n·(r(Δv¹) + add(v)) +
    /// C(n,2)·(r(Δv²) + add(Δv¹)) + out` and `e_a = r(a) + n·(r(Δa) + add(a)) + out`
    /// (`r`, `add`: [`Number::rounding_error`], [`Number::addition_error`]; `out`:
    /// [`Number::OUT_ERROR`]), the largest over the pieces. A check of the limits from the
    /// samples' finite differences allows twice these per tick: in `f32` the velocity
    /// channel drifts by up to about `n·½ε·|v|` over a piece and steps back at its end.
    ///
    /// ```
    /// use strak_trajectory::{AxisLimits, Kinematics, MoveOptions, OnlineMove, Path, Q40, compile_move};
    /// let l = [AxisLimits::new(500.0_f64, 5_000.0, 100_000.0)?];
    /// let options = MoveOptions::new().with_rate(1_000.0);
    /// let m = OnlineMove::solve(&[Kinematics::at_rest(0.0)], &[Kinematics::at_rest(300.0)], &l, &options)?;
    /// let (f32_path, q40_path): (Path<f32, 1, 64>, Path<Q40, 1, 64>) = (compile_move(&m)?, compile_move(&m)?);
    /// let (e_v, e_a) = f32_path.channel_bounds();
    /// // f32: about 10⁻⁵ of the velocity and acceleration limits
    /// assert!(e_v < 1e-4 * 500.0 && e_a < 1e-4 * 5_000.0, "{e_v} {e_a}");
    /// // Q40: exact additions; the stored differences rounded to 2⁻⁴⁰
    /// let (q_v, q_a) = q40_path.channel_bounds();
    /// assert!(q_v < 1e-6 && q_a < 1e-6, "{q_v} {q_a}");
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn channel_bounds(&self) -> (f64, f64) {
        let (r, add) = (N::rounding_error, N::addition_error);
        let (mut e_v, mut e_a) = (N::OUT_ERROR, N::OUT_ERROR);
        for piece in &self.pieces {
            let n = f64::from(piece.ticks);
            let pairs = 0.5 * n * (n - 1.0).max(0.0);
            for s in &piece.axes {
                let v2 = s.velocity_delta2.to_f64().abs();
                let v1 = s.velocity_delta1.to_f64().abs() + n * v2;
                let v0 =
                    s.velocity.to_f64().abs() + n * s.velocity_delta1.to_f64().abs() + pairs * v2;
                let a1 = s.acceleration_delta.to_f64().abs();
                let a0 = s.acceleration.to_f64().abs() + n * a1;
                let v = r(v0) + n * (r(v1) + add(v0)) + pairs * (r(v2) + add(v1)) + N::OUT_ERROR;
                let a = r(a0) + n * (r(a1) + add(a0)) + N::OUT_ERROR;
                e_v = e_v.max(v);
                e_a = e_a.max(a);
            }
        }
        (e_v, e_a)
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
