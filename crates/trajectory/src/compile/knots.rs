//! Where the spline fit keeps its knots: [`Knots`], implemented by the pieces of the path
//! being compiled ([`PieceKnots`]), so that compiling needs no storage beside the path's own.

use heapless::Vec;

use crate::num::Number;
use crate::path::{AxisState, Piece};

/// The storage of a spline fit's knots `1 ..= m` (knot `i + 1` in slot `i`): per knot its
/// tick, its position and slope per axis, one value of the elimination's scratch and a
/// split mark. Reading a slot that was never written gives some value, never a panic.
pub(crate) trait Knots<const A: usize> {
    /// How many knots fit.
    fn capacity(&self) -> usize;
    /// Makes room for `m ≤ capacity()` knots; the slots below the old length keep their
    /// contents.
    fn set_len(&mut self, m: usize);
    /// The tick of the knot in slot `i`.
    fn end(&self, i: usize) -> u32;
    /// Sets the tick of slot `i`.
    fn set_end(&mut self, i: usize, k: u32);
    /// The position at the knot in slot `i`.
    fn value(&self, i: usize) -> [f64; A];
    /// Sets the position of slot `i`.
    fn set_value(&mut self, i: usize, v: [f64; A]);
    /// The slope at the knot in slot `i`.
    fn slope(&self, i: usize) -> [f64; A];
    /// Sets the slope of slot `i`.
    fn set_slope(&mut self, i: usize, s: [f64; A]);
    /// The scratch value of slot `i`.
    fn scratch(&self, i: usize) -> f64;
    /// Sets the scratch value of slot `i`.
    fn set_scratch(&mut self, i: usize, c: f64);
    /// The split mark of slot `i`.
    fn split(&self, i: usize) -> bool;
    /// Sets the split mark of slot `i`.
    fn set_split(&mut self, i: usize, s: bool);
}

/// The knots of a fit kept in the piece storage of the path it is compiled into: knot
/// `i + 1` in piece slot `i`, its tick in the piece's `start`, its split mark in `ticks`,
/// and its `2A + 1` `f64` values bit for bit in the piece's state values: one `f64` in one
/// 8-byte value (`f64`, `Q40`) or in two 4-byte values (`f32`), through the values'
/// little-endian bytes. Axis `a`'s position at the knot lies in its `position` (and
/// `delta1`), its slope in its `delta2` (and `delta3`), and the scratch value in the first
/// axis's `velocity` (and `velocity_delta1`), so that a row of values is read field by
/// field. When the fit is done,
/// [`SplineFit::write_pieces`](super::spline_fit::SplineFit::write_pieces) overwrites each
/// slot with its piece. The slots start at `offset` (a fit after pieces already written, as
/// the stretches of [`Stretches`](crate::Stretches) write several fits into one storage).
#[derive(Debug)]
pub(crate) struct PieceKnots<'p, N: Number, const A: usize, const P: usize> {
    pub(crate) pieces: &'p mut Vec<Piece<N, A>, P>,
    pub(crate) offset: usize,
}

impl<'p, N: Number, const A: usize, const P: usize> PieceKnots<'p, N, A, P> {
    /// The knots in `pieces`, from its first slot.
    pub(crate) fn new(pieces: &'p mut Vec<Piece<N, A>, P>) -> Self {
        PieceKnots { pieces, offset: 0 }
    }

    /// Slot `j`'s piece, to overwrite with the piece of the fit.
    pub(crate) fn piece_mut(&mut self, j: usize) -> Option<&mut Piece<N, A>> {
        self.pieces.get_mut(self.offset + j)
    }
}

/// Which of a knot's values a pair of state fields holds.
#[derive(Clone, Copy)]
enum Row {
    /// The position (per axis).
    Value,
    /// The slope (per axis).
    Slope,
    /// The elimination's scratch value (in the first axis).
    Scratch,
}

/// The pair of fields of an axis's state that holds `row`.
#[inline(always)]
fn fields<N>(s: &AxisState<N>, row: Row) -> (&N, &N) {
    match row {
        Row::Value => (&s.position, &s.delta1),
        Row::Slope => (&s.delta2, &s.delta3),
        Row::Scratch => (&s.velocity, &s.velocity_delta1),
    }
}

/// The pair of fields of an axis's state that holds `row`, to write.
#[inline(always)]
fn fields_mut<N>(s: &mut AxisState<N>, row: Row) -> (&mut N, &mut N) {
    match row {
        Row::Value => (&mut s.position, &mut s.delta1),
        Row::Slope => (&mut s.delta2, &mut s.delta3),
        Row::Scratch => (&mut s.velocity, &mut s.velocity_delta1),
    }
}

/// Stores `x` in one value of `N` (8 bytes) or two (4 bytes each): its little-endian bytes
/// in order.
#[inline(always)]
fn put<N: Number>((lo, hi): (&mut N, &mut N), x: f64) {
    let bytes = x.to_le_bytes();
    let mut chunks = bytes.chunks_exact(N::BYTES);
    if let Some(c) = chunks.next() {
        *lo = N::read_le(c);
    }
    if let Some(c) = chunks.next() {
        *hi = N::read_le(c);
    }
}

/// The `f64` that [`put`] stored.
#[inline(always)]
fn get<N: Number>((lo, hi): (&N, &N)) -> f64 {
    let mut bytes = [0_u8; 8];
    let mut chunks = bytes.chunks_exact_mut(N::BYTES);
    if let Some(c) = chunks.next() {
        lo.write_le(c);
    }
    if let Some(c) = chunks.next() {
        hi.write_le(c);
    }
    f64::from_le_bytes(bytes)
}

impl<N: Number, const A: usize, const P: usize> PieceKnots<'_, N, A, P> {
    fn axes(&self, i: usize) -> Option<&[AxisState<N>; A]> {
        self.pieces.get(self.offset + i).map(|p| &p.axes)
    }

    fn axes_mut(&mut self, i: usize) -> Option<&mut [AxisState<N>; A]> {
        self.pieces.get_mut(self.offset + i).map(|p| &mut p.axes)
    }

    /// The values `row` of slot `i`, one per axis.
    #[inline(always)]
    fn row(&self, i: usize, row: Row) -> [f64; A] {
        match self.axes(i) {
            Some(axes) => {
                core::array::from_fn(|a| axes.get(a).map_or(0.0, |s| get(fields(s, row))))
            }
            None => [0.0; A],
        }
    }

    #[inline(always)]
    fn set_row(&mut self, i: usize, row: Row, x: [f64; A]) {
        if let Some(axes) = self.axes_mut(i) {
            for (s, v) in axes.iter_mut().zip(x) {
                put(fields_mut(s, row), v);
            }
        }
    }
}

impl<N: Number, const A: usize, const P: usize> Knots<A> for PieceKnots<'_, N, A, P> {
    fn capacity(&self) -> usize {
        P.saturating_sub(self.offset)
    }
    fn set_len(&mut self, m: usize) {
        let empty = Piece {
            start: 0,
            ticks: 0,
            axes: [AxisState::ZERO; A],
        };
        let len = self.offset + m;
        if len <= self.pieces.len() {
            self.pieces.truncate(len);
        } else {
            while self.pieces.len() < len && self.pieces.push(empty).is_ok() {}
        }
    }
    fn end(&self, i: usize) -> u32 {
        self.pieces.get(self.offset + i).map_or(0, |p| p.start)
    }
    fn set_end(&mut self, i: usize, k: u32) {
        if let Some(p) = self.pieces.get_mut(self.offset + i) {
            p.start = k;
        }
    }
    fn value(&self, i: usize) -> [f64; A] {
        self.row(i, Row::Value)
    }
    fn set_value(&mut self, i: usize, v: [f64; A]) {
        self.set_row(i, Row::Value, v);
    }
    fn slope(&self, i: usize) -> [f64; A] {
        self.row(i, Row::Slope)
    }
    fn set_slope(&mut self, i: usize, s: [f64; A]) {
        self.set_row(i, Row::Slope, s);
    }
    fn scratch(&self, i: usize) -> f64 {
        self.axes(i)
            .and_then(|axes| axes.first())
            .map_or(0.0, |s| get(fields(s, Row::Scratch)))
    }
    fn set_scratch(&mut self, i: usize, c: f64) {
        if let Some(s) = self.axes_mut(i).and_then(|axes| axes.first_mut()) {
            put(fields_mut(s, Row::Scratch), c);
        }
    }
    fn split(&self, i: usize) -> bool {
        self.pieces
            .get(self.offset + i)
            .is_some_and(|p| p.ticks != 0)
    }
    fn set_split(&mut self, i: usize, s: bool) {
        if let Some(p) = self.pieces.get_mut(self.offset + i) {
            p.ticks = u32::from(s);
        }
    }
}

/// Knots in arrays of their own (the fit's tests).
#[cfg(test)]
#[derive(Debug)]
pub(crate) struct ArrayKnots<const A: usize, const P: usize> {
    ends: [u32; P],
    values: [[f64; A]; P],
    slopes: [[f64; A]; P],
    scratch: [f64; P],
    split: [bool; P],
}

#[cfg(test)]
impl<const A: usize, const P: usize> ArrayKnots<A, P> {
    pub(crate) const fn new() -> Self {
        ArrayKnots {
            ends: [0; P],
            values: [[0.0; A]; P],
            slopes: [[0.0; A]; P],
            scratch: [0.0; P],
            split: [false; P],
        }
    }
}

#[cfg(test)]
impl<const A: usize, const P: usize> Knots<A> for ArrayKnots<A, P> {
    fn capacity(&self) -> usize {
        P
    }
    fn set_len(&mut self, _m: usize) {}
    fn end(&self, i: usize) -> u32 {
        self.ends.get(i).copied().unwrap_or(0)
    }
    fn set_end(&mut self, i: usize, k: u32) {
        if let Some(e) = self.ends.get_mut(i) {
            *e = k;
        }
    }
    fn value(&self, i: usize) -> [f64; A] {
        self.values.get(i).copied().unwrap_or([0.0; A])
    }
    fn set_value(&mut self, i: usize, v: [f64; A]) {
        if let Some(x) = self.values.get_mut(i) {
            *x = v;
        }
    }
    fn slope(&self, i: usize) -> [f64; A] {
        self.slopes.get(i).copied().unwrap_or([0.0; A])
    }
    fn set_slope(&mut self, i: usize, s: [f64; A]) {
        if let Some(x) = self.slopes.get_mut(i) {
            *x = s;
        }
    }
    fn scratch(&self, i: usize) -> f64 {
        self.scratch.get(i).copied().unwrap_or(0.0)
    }
    fn set_scratch(&mut self, i: usize, c: f64) {
        if let Some(x) = self.scratch.get_mut(i) {
            *x = c;
        }
    }
    fn split(&self, i: usize) -> bool {
        self.split.get(i).copied().unwrap_or(false)
    }
    fn set_split(&mut self, i: usize, s: bool) {
        if let Some(x) = self.split.get_mut(i) {
            *x = s;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::Q40;

    /// Every `f64` bit pattern round-trips through the piece values of every format, and the
    /// rows of one slot do not overlap.
    fn round_trip<N: Number>() {
        let mut pieces: Vec<Piece<N, 1>, 2> = Vec::new();
        let mut knots = PieceKnots::new(&mut pieces);
        knots.set_len(2);
        let patterns = [
            0.1_f64,
            -3.5e300,
            f64::from_bits(0x7FF8_0000_0000_0001),
            f64::from_bits(0xFFF0_0000_0000_0001),
            f64::MIN_POSITIVE / 3.0,
        ];
        for (i, &x) in patterns.iter().enumerate() {
            let (v, s, c) = (x, -x * 0.5, f64::from_bits(x.to_bits() ^ 0x55));
            knots.set_value(1, [v]);
            knots.set_slope(1, [s]);
            knots.set_scratch(1, c);
            knots.set_end(1, 7 + i as u32);
            knots.set_split(1, i % 2 == 0);
            assert_eq!(knots.value(1)[0].to_bits(), v.to_bits());
            assert_eq!(knots.slope(1)[0].to_bits(), s.to_bits());
            assert_eq!(knots.scratch(1).to_bits(), c.to_bits());
            assert_eq!(knots.end(1), 7 + i as u32);
            assert_eq!(knots.split(1), i % 2 == 0);
            assert_eq!(knots.value(0), [0.0]); // the other slot untouched
        }
        assert_eq!(knots.value(2), [0.0]); // past the end: a value, no panic
        knots.set_len(1);
        assert_eq!(pieces.len(), 1);
    }

    #[test]
    fn knots_round_trip_bit_for_bit_in_every_format() {
        round_trip::<f32>();
        round_trip::<f64>();
        round_trip::<Q40>();
    }
}
