//! A whole list of moves with their corners blended, as one curve that the path planner
//! takes ([`PathTiming::plan`](crate::PathTiming::plan)).

use heapless::Vec;
use strak_curves::{ParamCurve, ParamCurveDeriv, PieceDeriv, Point};

use super::blend::{Junction, chain_junctions, has_span, junction};
use super::moves::{Move, MoveCurve};
use crate::error::Error;

/// Moves from a start point, each corner replaced by its [`Junction`], as one curve of
/// pieces: the part of each move between its blends, then the blend to the next move. Piece
/// `i` runs over the parameters `[i, i + 1]`; a move's piece maps them linearly onto its
/// own parameters, a blend's onto its Bézier's `[0, 1]`. Joins without a blend (a
/// [`Junction::Stop`] or [`Junction::Straight`]) meet at a piece boundary, where the planner
/// finds a corner (and stops) or passes straight on.
///
/// `M` is the capacity in moves. [`PathTiming`](crate::PathTiming) plans a toolpath like any
/// curve, under one set of limits: it does not apply the moves' own feeds.
///
/// ```
/// use strak_trajectory::{Move, Toolpath};
/// use strak_curves::ParamCurve;
/// let moves = [Move::line([10.0, 0.0]), Move::line([10.0, 10.0]), Move::line([0.0, 10.0])];
/// let path = Toolpath::<2, 8>::new([0.0, 0.0], &moves, 0.05, 1e-6)?;
/// assert_eq!((path.blends(), ParamCurve::piece_count(&path)), (2, 5));
/// assert_eq!(path.eval(5.0), [0.0, 10.0]);
/// # Ok::<(), strak_trajectory::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Toolpath<const D: usize, const M: usize> {
    moves: Vec<MoveCurve<D>, M>,
    /// The junction after each move but the last.
    junctions: Vec<Junction<D>, M>,
    /// Each move's parameters between its blends.
    spans: Vec<(f64, f64), M>,
    /// The index of each move's piece.
    first_piece: Vec<usize, M>,
    pieces: usize,
}

impl<const D: usize, const M: usize> Toolpath<D, M> {
    /// The moves `moves` from `start`, their corners blended within `tolerance` (0: exact
    /// stops) by [`junction`]; arcs' ends may lie off their circles by `arc_tolerance`.
    ///
    /// # Errors
    /// [`Error::EmptyPath`] for no moves; [`Error::CapacityExceeded`] for more than `M`;
    /// the errors of [`MoveCurve::new`] and [`junction`].
    ///
    /// ```
    /// use strak_trajectory::{Error, Move, Toolpath};
    /// let moves = [Move::line([1.0]), Move::line([2.0])];
    /// assert!(matches!(Toolpath::<1, 1>::new([0.0], &moves, 0.0, 0.0), Err(Error::CapacityExceeded { .. })));
    /// assert!(matches!(Toolpath::<1, 4>::new([0.0], &[], 0.0, 0.0), Err(Error::EmptyPath)));
    /// ```
    pub fn new(
        start: [f64; D],
        moves: &[Move<D>],
        tolerance: f64,
        arc_tolerance: f64,
    ) -> Result<Self, Error> {
        if moves.is_empty() {
            return Err(Error::EmptyPath);
        }
        let full = Error::CapacityExceeded {
            capacity: M,
            required: moves.len(),
        };
        let mut path = Toolpath {
            moves: Vec::new(),
            junctions: Vec::new(),
            spans: Vec::new(),
            first_piece: Vec::new(),
            pieces: 0,
        };
        let mut from = start;
        for mv in moves {
            let curve = MoveCurve::new(from, mv, arc_tolerance)?;
            from = curve.eval(1.0);
            if let Some(last) = path.moves.last() {
                let j = junction(last, &curve, tolerance)?;
                path.junctions.push(j).map_err(|_| full)?;
            }
            path.moves.push(curve).map_err(|_| full)?;
        }
        path.chain_blends(tolerance);
        for i in 0..path.moves.len() {
            let begin = match i.checked_sub(1).map(|j| &path.junctions[j]) {
                Some(Junction::Blend(b)) => b.join(),
                _ => 0.0,
            };
            let end = match path.junctions.get(i) {
                Some(Junction::Blend(b)) => b.leave(),
                _ => 1.0,
            };
            path.spans.push((begin, end)).map_err(|_| full)?;
            path.first_piece.push(path.pieces).map_err(|_| full)?;
            let blended = matches!(path.junctions.get(i), Some(Junction::Blend(_)));
            path.pieces += usize::from(has_span((begin, end))) + usize::from(blended);
        }
        Ok(path)
    }

    /// Joins the blends at both ends of each line they take all of between them, as a
    /// [`Stream`](crate::Stream) does ([`chain_junctions`]).
    fn chain_blends(&mut self, tolerance: f64) {
        chain_junctions(&self.moves, &mut self.junctions, tolerance);
    }

    /// The number of blended corners.
    ///
    /// ```
    /// use strak_trajectory::{Move, Toolpath};
    /// let moves = [Move::line([1.0, 0.0]), Move::line([1.0, 1.0])];
    /// assert_eq!(Toolpath::<2, 4>::new([0.0, 0.0], &moves, 0.0, 0.0)?.blends(), 0); // exact stop
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn blends(&self) -> usize {
        self.junctions
            .iter()
            .filter(|j| matches!(j, Junction::Blend(_)))
            .count()
    }

    /// The moves' curves.
    ///
    /// ```
    /// use strak_trajectory::{Move, Toolpath};
    /// let moves = [Move::line([3.0, 4.0]), Move::line([3.0, 5.0])];
    /// assert_eq!(Toolpath::<2, 4>::new([0.0, 0.0], &moves, 0.0, 0.0)?.moves()[0].length(), 5.0);
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn moves(&self) -> &[MoveCurve<D>] {
        &self.moves
    }

    /// The junction after each move but the last.
    ///
    /// ```
    /// use strak_trajectory::{Junction, Move, Toolpath};
    /// let moves = [Move::line([1.0, 0.0]), Move::line([2.0, 0.0])];
    /// let path = Toolpath::<2, 4>::new([0.0, 0.0], &moves, 0.1, 0.0)?;
    /// assert_eq!(path.junctions(), &[Junction::Straight]);
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn junctions(&self) -> &[Junction<D>] {
        &self.junctions
    }

    /// Piece `piece` as a move index and whether it is that move's blend (every move has
    /// a piece: its part between its blends, or, where the blends at both ends take half of
    /// it each, the blend after it alone).
    fn locate(&self, piece: usize) -> (usize, bool) {
        let i = self.first_piece.partition_point(|&p| p <= piece) - 1;
        (i, piece > self.first_piece[i] || !has_span(self.spans[i]))
    }

    /// The derivative of order `k` of piece `piece` at the piece-local parameter `t ∈ [0, 1]`.
    fn piece_value(&self, piece: usize, t: f64, k: usize) -> [f64; D] {
        let (i, is_blend) = self.locate(piece);
        if is_blend {
            let Junction::Blend(blend) = &self.junctions[i] else {
                return [0.0; D];
            };
            return blend.curve().deriv(t, k);
        }
        let (u0, u1) = self.spans[i];
        let width = u1 - u0;
        let u = if t >= 1.0 { u1 } else { u0 + width * t };
        let mut scale = 1.0;
        for _ in 0..k {
            scale *= width;
        }
        let d = self.moves[i].deriv(u, k);
        if k == 0 { d } else { d.times(scale) }
    }

    /// The piece of `u` and the local parameter in it.
    fn split(&self, u: f64) -> (usize, f64) {
        let u = u.clamp(0.0, self.pieces as f64);
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let piece = (libm::floor(u) as usize).min(self.pieces - 1);
        (piece, u - piece as f64)
    }
}

impl<const D: usize, const M: usize> ParamCurve for Toolpath<D, M> {
    type Point = [f64; D];

    fn domain(&self) -> (f64, f64) {
        (0.0, self.pieces as f64)
    }

    fn eval(&self, u: f64) -> [f64; D] {
        let (piece, t) = self.split(u);
        self.piece_value(piece, t, 0)
    }

    fn piece_count(&self) -> usize {
        self.pieces
    }

    fn piece_domain(&self, i: usize) -> (f64, f64) {
        let i = i.min(self.pieces - 1);
        (i as f64, (i + 1) as f64)
    }
}

impl<const D: usize, const M: usize> ParamCurveDeriv for Toolpath<D, M> {
    fn deriv(&self, u: f64, k: usize) -> [f64; D] {
        let (piece, t) = self.split(u);
        self.piece_value(piece, t, k)
    }
}

impl<const D: usize, const M: usize> PieceDeriv for Toolpath<D, M> {
    fn piece_deriv(&self, piece: usize, u: f64, k: usize) -> [f64; D] {
        let piece = piece.min(self.pieces - 1);
        let t = (u - piece as f64).clamp(0.0, 1.0);
        self.piece_value(piece, t, k)
    }
}
