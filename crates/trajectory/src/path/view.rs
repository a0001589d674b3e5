//! The borrowed view of a path that the sampler plays: the header and the pieces, either a
//! slice of [`Piece`]s in RAM or the piece records of a validated blob (in flash, read in
//! place).

use core::ops::Deref;

use super::header::PathHeader;
use super::sample::Sample;
use super::state::{AxisState, Newton, Piece};
use crate::num::Number;

/// The bytes of one piece record in a blob: the tick count and `9·A` values.
pub(crate) const fn piece_record_len<N: Number>(axes: usize) -> usize {
    4 + 9 * axes * N::BYTES
}

/// A path to play, without its capacity in the type: the header and the pieces, which are
/// either a [`Path`](crate::Path)'s pieces in RAM ([`Path::view`](crate::Path::view)) or the
/// piece records of a blob read in place, for example from flash
/// ([`PathBlob::view`](crate::PathBlob::view)). [`Sampler`](crate::Sampler) plays any view
/// the same way, with the same samples bit for bit; the view is small and `Copy` (a
/// reference to the header, a slice and a count).
///
/// It dereferences to the [`PathHeader`] (ticks, rate, end, bounds).
///
/// ```
/// use strak_trajectory::{compile, Along, CompileOptions, Path, PathBlob, PathView, Timing};
/// use strak_curves::Bezier;
/// struct Ramp;
/// impl Timing for Ramp {
///     fn duration(&self) -> f64 { 0.1 }
///     fn param(&self, t: f64) -> (f64, f64) { (t.clamp(0.0, 0.1) * 10.0, 10.0) }
/// }
/// let curve = Bezier::new([[0.0_f64, 1.0], [2.0, 3.0], [4.0, 1.0]])?;
/// let trajectory = Along::new(&curve, &Ramp);
/// let path: Path<f32, 2, 8> = compile(&trajectory, 1_000.0, &CompileOptions::new())?;
/// let mut bytes = [0_u8; 1024];
/// let len = path.to_bytes(&mut bytes)?;
/// let blob = PathBlob::<f32, 2>::from_bytes(&bytes[..len])?;
/// let (a, b): (PathView<'_, f32, 2>, PathView<'_, f32, 2>) = (path.view(), blob.view());
/// assert_eq!(a.piece_count(), b.piece_count());
/// assert_eq!(a.eval(37.5), b.eval(37.5)); // the same polynomial
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct PathView<'a, N: Number, const A: usize> {
    header: &'a PathHeader<N, A>,
    /// Decoded pieces (a [`Path`](crate::Path) in RAM), or empty.
    ram: &'a [Piece<N, A>],
    /// The piece records of a validated blob, [`piece_record_len`] bytes each: the length
    /// in ticks (`u32`), then the `9·A` state values, little-endian; or empty. At most one
    /// of `ram` and `records` holds pieces.
    records: &'a [u8],
    count: usize,
}

impl<N: Number, const A: usize> Deref for PathView<'_, N, A> {
    type Target = PathHeader<N, A>;

    fn deref(&self) -> &PathHeader<N, A> {
        self.header
    }
}

impl<'a, N: Number, const A: usize> PathView<'a, N, A> {
    /// The view of decoded pieces.
    pub(crate) fn of_pieces(header: &'a PathHeader<N, A>, pieces: &'a [Piece<N, A>]) -> Self {
        PathView {
            header,
            ram: pieces,
            records: &[],
            count: pieces.len(),
        }
    }

    /// The view of a blob's piece records (already validated against `header`).
    pub(crate) fn of_records(header: &'a PathHeader<N, A>, records: &'a [u8]) -> Self {
        PathView {
            header,
            ram: &[],
            records,
            count: records.len() / piece_record_len::<N>(A),
        }
    }

    /// The header (also reached through `Deref`), with the view's lifetime.
    pub fn header(&self) -> &'a PathHeader<N, A> {
        self.header
    }

    /// The number of pieces.
    pub fn piece_count(&self) -> usize {
        self.count
    }

    /// The pieces in order, decoded (for a blob: read from its records one by one).
    ///
    /// ```
    /// use strak_trajectory::{Path, PathView};
    /// let path: Path<f64, 1, 4> = Path::new();
    /// assert_eq!(path.view().pieces().count(), 0);
    /// ```
    pub fn pieces(&self) -> impl Iterator<Item = Piece<N, A>> + 'a {
        let view = *self;
        let mut start = 0_u32;
        (0..self.count).filter_map(move |j| {
            let (ticks, axes) = view.piece_at(j)?;
            let piece = Piece { start, ticks, axes };
            start = start.wrapping_add(ticks);
            Some(piece)
        })
    }

    /// The first tick of piece `j` (the path's tick count past the last piece): `O(1)` in
    /// RAM, a sum over the records before it for a blob (`O(j)`).
    pub(crate) fn piece_start(&self, j: usize) -> u32 {
        if self.records.is_empty() {
            return self.ram.get(j).map_or(self.header.ticks, |p| p.start);
        }
        (0..j.min(self.count)).fold(0_u32, |start, i| {
            start.wrapping_add(record::<N>(self.records, i, A).map_or(0, |(ticks, _)| ticks))
        })
    }

    /// Piece `j`'s length and state (`None` past the last piece).
    fn piece_at(&self, j: usize) -> Option<(u32, [AxisState<N>; A])> {
        let mut axes = [AxisState::ZERO; A];
        let ticks = self.load(j, &mut axes)?;
        Some((ticks, axes))
    }

    /// Copies piece `j`'s state into `state` and returns its length in ticks (`None`, state
    /// untouched, past the last piece).
    #[inline]
    pub(crate) fn load(&self, j: usize, state: &mut [AxisState<N>; A]) -> Option<u32> {
        if let Some(p) = self.ram.get(j) {
            *state = p.axes;
            return Some(p.ticks);
        }
        let (ticks, values) = record::<N>(self.records, j, A)?;
        decode_states(values, state);
        Some(ticks)
    }

    /// The length in ticks of piece `j` (`None` past the last piece).
    pub(crate) fn piece_ticks(&self, j: usize) -> Option<u32> {
        if let Some(p) = self.ram.get(j) {
            return Some(p.ticks);
        }
        record::<N>(self.records, j, A).map(|(ticks, _)| ticks)
    }

    /// `true` for the view of a path in RAM (or of no pieces), `false` for a blob's.
    pub(crate) fn in_ram(&self) -> bool {
        self.records.is_empty()
    }

    /// The index of the piece before `pieces` (a tail of this view's pieces in RAM, empty
    /// or not, at its place) or, for a blob, before `records` (a tail of its records).
    pub(crate) fn index_before(&self, pieces: &[Piece<N, A>], records: &[u8]) -> usize {
        let next = if self.in_ram() {
            let bytes = pieces
                .as_ptr()
                .addr()
                .wrapping_sub(self.ram.as_ptr().addr());
            bytes / size_of::<Piece<N, A>>().max(1)
        } else {
            self.count
                .saturating_sub(records.len() / piece_record_len::<N>(A))
        };
        next.saturating_sub(1)
    }

    /// The pieces in RAM after piece `j`, in order (empty for a blob and past the last
    /// piece): what the sampler's piece switch loads from.
    pub(crate) fn pieces_after(&self, j: usize) -> &'a [Piece<N, A>] {
        self.ram.get(j.saturating_add(1)..).unwrap_or(&[])
    }

    /// The blob's piece records after piece `j`, in order ([`piece_record_len`] bytes each;
    /// empty for a path in RAM and past the last piece).
    pub(crate) fn records_after(&self, j: usize) -> &'a [u8] {
        let at = j.saturating_add(1).saturating_mul(piece_record_len::<N>(A));
        self.records.get(at..).unwrap_or(&[])
    }

    /// The compiled polynomial at a (possibly fractional) tick, evaluated in `f64` from the
    /// stored states (Newton's forward-difference formula): position, velocity (units/s) and
    /// acceleration (units/s²). `tick` is clamped to `[0, ticks]`; at `ticks` the end values
    /// are returned. The returned sample's `tick` is `⌊tick⌋`. For tests and the simulator:
    /// a binary search over the pieces in RAM (`O(log P)`), a scan over a blob's records
    /// (`O(P)`).
    pub fn eval(&self, tick: f64) -> Sample<f64, A> {
        let last = f64::from(self.header.ticks);
        let t = if tick >= 0.0 { tick.min(last) } else { 0.0 };
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let whole = libm::floor(t) as u64;
        let piece = if self.records.is_empty() {
            let j = self
                .ram
                .partition_point(|p| f64::from(p.start) <= t)
                .saturating_sub(1);
            self.ram.get(j).copied()
        } else {
            self.pieces().take_while(|p| f64::from(p.start) <= t).last()
        };
        match piece {
            Some(piece) if t < last => {
                let c = Newton::at(t - f64::from(piece.start));
                let axes = piece.axes.map(|a| a.to_f64().shifted(&c));
                Sample {
                    tick: whole,
                    position: axes.map(|a| a.position),
                    velocity: axes.map(|a| a.velocity),
                    acceleration: axes.map(|a| a.acceleration),
                }
            }
            _ => self.header.end_sample(whole),
        }
    }
}

/// Record `j` of a blob's piece records: its length in ticks and its value bytes.
#[inline(always)]
fn record<N: Number>(bytes: &[u8], j: usize, axes: usize) -> Option<(u32, &[u8])> {
    let len = piece_record_len::<N>(axes);
    let at = j.checked_mul(len)?;
    let rec = bytes.get(at..at.checked_add(len)?)?;
    let (ticks, values) = rec.split_at_checked(4)?;
    let ticks = u32::from_le_bytes(ticks.try_into().ok()?);
    Some((ticks, values))
}

/// Decodes `9·A` little-endian values into the states (in the order of [`AxisState`]);
/// missing bytes read as 0. Each value is written where it lies (no state is returned by
/// value: this runs at a piece switch, below the sampler's frames).
pub(crate) fn decode_states<N: Number, const A: usize>(
    bytes: &[u8],
    state: &mut [AxisState<N>; A],
) {
    let mut chunks = bytes.chunks(9 * N::BYTES);
    for axis in state.iter_mut() {
        decode_into(chunks.next().unwrap_or(&[]), axis);
    }
}

/// Decodes one axis's 9 little-endian values (in the order of [`AxisState`]) into `axis`;
/// missing bytes read as 0.
#[inline]
pub(crate) fn decode_into<N: Number>(bytes: &[u8], axis: &mut AxisState<N>) {
    let mut values = bytes.chunks_exact(N::BYTES);
    let mut next = || values.next().map_or(N::ZERO, N::read_le);
    axis.position = next();
    axis.delta1 = next();
    axis.delta2 = next();
    axis.delta3 = next();
    axis.velocity = next();
    axis.velocity_delta1 = next();
    axis.velocity_delta2 = next();
    axis.acceleration = next();
    axis.acceleration_delta = next();
}
