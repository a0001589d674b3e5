//! Serializing a compiled [`Path`] to bytes (on the host) and reading it back from a `&[u8]`
//! (in firmware, without allocation): validated once, then played in place
//! ([`PathBlob`]) or decoded into a [`Path`].

use core::ops::Deref;

use super::header::{PathHeader, Validator};
use super::owned::Path;
use super::state::{AxisState, Piece};
use super::view::{PathView, decode_into, decode_states, piece_record_len};
use crate::error::{BlobFormat, Error};
use crate::num::{Number, NumberFormat};

/// The magic bytes at the start of a serialized path.
pub const BLOB_MAGIC: [u8; 4] = *b"STRK";
/// The format version this build writes and reads.
pub const BLOB_VERSION: u16 = 1;
/// Bytes before the end states: magic, version, format, axes, counts, nine `f64`.
const HEADER: usize = 16 + 9 * 8;

/// The CRC-32 (IEEE 802.3, as in zlib and Ethernet) of `bytes`, bitwise without a table.
///
/// ```
/// assert_eq!(strak_trajectory::crc32(b"123456789"), 0xCBF4_3926);
/// ```
pub fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = 0xFFFF_FFFF_u32;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            let mask = (crc & 1).wrapping_neg();
            crc = (crc >> 1) ^ (0xEDB8_8320 & mask);
        }
    }
    !crc
}

/// Writes sequentially into a byte slice; never panics (the length is checked up front).
struct Writer<'b> {
    out: &'b mut [u8],
    pos: usize,
}

impl Writer<'_> {
    fn bytes(&mut self, b: &[u8]) {
        if let Some(dst) = self.out.get_mut(self.pos..self.pos + b.len()) {
            dst.copy_from_slice(b);
        }
        self.pos += b.len();
    }
    fn number<N: Number>(&mut self, v: N) {
        if let Some(dst) = self.out.get_mut(self.pos..) {
            v.write_le(dst);
        }
        self.pos += N::BYTES;
    }
    fn out<N: Number>(&mut self, v: N::Out) {
        if let Some(dst) = self.out.get_mut(self.pos..) {
            N::write_out_le(v, dst);
        }
        self.pos += N::BYTES;
    }
}

/// Reads sequentially from a byte slice; missing bytes read as 0 (the length is checked up
/// front).
struct Reader<'b> {
    bytes: &'b [u8],
    pos: usize,
}

impl Reader<'_> {
    fn take<const K: usize>(&mut self) -> [u8; K] {
        let mut b = [0_u8; K];
        if let Some(src) = self.bytes.get(self.pos..self.pos + K) {
            b.copy_from_slice(src);
        }
        self.pos += K;
        b
    }
    fn u32(&mut self) -> u32 {
        u32::from_le_bytes(self.take())
    }
    fn f64(&mut self) -> f64 {
        f64::from_le_bytes(self.take())
    }
    fn out<N: Number>(&mut self) -> N::Out {
        let v = N::read_out_le(self.bytes.get(self.pos..).unwrap_or(&[]));
        self.pos += N::BYTES;
        v
    }
}

/// The offset of the first piece record in a blob with `A` axes and `B`-byte values.
const fn records_at(axes: usize, b: usize) -> usize {
    HEADER + 3 * axes * b
}

/// The serialized length of a path with `m` pieces, `A` axes and `B`-byte values (`None` on
/// overflow).
fn blob_len(m: usize, axes: usize, b: usize) -> Option<usize> {
    let piece = axes.checked_mul(9 * b)?.checked_add(4)?;
    HEADER
        .checked_add(axes.checked_mul(3 * b)?)?
        .checked_add(m.checked_mul(piece)?)?
        .checked_add(4)
}

impl<N: Number, const A: usize, const P: usize> Path<N, A, P> {
    /// The number of bytes [`Path::to_bytes`] writes.
    pub fn blob_len(&self) -> usize {
        blob_len(self.pieces.len(), A, N::BYTES).unwrap_or(usize::MAX)
    }

    /// Serializes the path into `out`; returns the number of bytes written
    /// ([`Path::blob_len`]).
    ///
    /// # Layout (format version 1, little-endian)
    ///
    /// | offset | size            | field                                                     |
    /// |--------|-----------------|-----------------------------------------------------------|
    /// | 0      | 4               | magic `"STRK"`                                            |
    /// | 4      | 2               | format version (`u16`) = 1                                |
    /// | 6      | 1               | number format id ([`NumberFormat::id`]: 1 f32, 2 f64, 3 Q40) |
    /// | 7      | 1               | axes `A`                                                  |
    /// | 8      | 4               | piece count `m` (`u32`)                                   |
    /// | 12     | 4               | tick count (`u32`)                                        |
    /// | 16     | 8 × 9           | `f64`: rate, plan duration, tolerance, peak velocity, peak acceleration, peak jerk, acceleration limit, jerk limit, feed share |
    /// | 88     | 3·A·B           | end position, end velocity, end acceleration (sample type, `B` = [`Number::BYTES`] bytes each) |
    /// | …      | m·(4 + 9·A·B)   | per piece: length in ticks (`u32`), then per axis the 9 state values in the order of [`AxisState`](crate::AxisState) |
    /// | len−4  | 4               | CRC-32 (IEEE 802.3: reflected polynomial `0xEDB88320`, init and final xor `0xFFFFFFFF`) of all preceding bytes |
    ///
    /// Reading checks, in this order: length of the fixed header and magic
    /// ([`Error::CorruptBlob`]), version ([`Error::UnsupportedVersion`]), CRC
    /// ([`Error::CorruptBlob`]), number format ([`Error::UnknownNumberFormat`] for an id no
    /// format has) and axes ([`Error::FormatMismatch`]), exact
    /// length ([`Error::CorruptBlob`]), piece count against the capacity
    /// ([`Error::CapacityExceeded`], [`Path::from_bytes`] only); then the pieces and the end are
    /// validated like a freshly compiled path: the range of every value playback forms
    /// ([`Error::OutOfRange`]), consecutive pieces and the tick count, and an end that is in
    /// range and continues the last piece within the path's bounds ([`Error::CorruptBlob`]).
    /// So a blob that passes cannot make the sampler overflow or jump. A round trip is
    /// bit-exact.
    ///
    /// # Errors
    /// [`Error::CapacityExceeded`] when `out` is shorter than [`Path::blob_len`]
    /// (`capacity` and `required` in bytes); [`Error::FormatMismatch`] for more than 255 axes.
    ///
    /// ```
    /// use strak_trajectory::{compile, Along, CompileOptions, Path, Timing};
    /// use strak_curves::Bezier;
    /// struct Ramp;
    /// impl Timing for Ramp {
    ///     fn duration(&self) -> f64 { 0.1 }
    ///     fn param(&self, t: f64) -> (f64, f64) { (t.clamp(0.0, 0.1) * 10.0, 10.0) }
    /// }
    /// let curve = Bezier::new([[0.0_f64, 1.0], [2.0, 3.0], [4.0, 1.0]])?;
    /// let trajectory = Along::new(&curve, &Ramp);
    /// let path: Path<f32, 2, 8> = compile(&trajectory, 1_000.0, &CompileOptions::new())?;
    /// let mut buf = [0_u8; 1024];
    /// let len = path.to_bytes(&mut buf)?;
    /// assert_eq!(&buf[..4], b"STRK");
    /// let back = Path::<f32, 2, 8>::from_bytes(&buf[..len])?;
    /// assert_eq!(back, path); // bit-exact
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn to_bytes(&self, out: &mut [u8]) -> Result<usize, Error> {
        let axes = u8::try_from(A).map_err(|_| Error::FormatMismatch {
            expected: BlobFormat::of::<N>(usize::from(u8::MAX)),
            found: BlobFormat::of::<N>(A),
        })?;
        let len = self.blob_len();
        if out.len() < len {
            return Err(Error::CapacityExceeded {
                capacity: out.len(),
                required: len,
            });
        }
        #[allow(clippy::cast_possible_truncation)]
        let m = self.pieces.len() as u32;
        let mut w = Writer { out, pos: 0 };
        w.bytes(&BLOB_MAGIC);
        w.bytes(&BLOB_VERSION.to_le_bytes());
        w.bytes(&[N::FORMAT_ID, axes]);
        w.bytes(&m.to_le_bytes());
        w.bytes(&self.header.ticks.to_le_bytes());
        let meta = &self.header.meta;
        for v in [
            meta.ramp.rate,
            meta.plan_duration,
            meta.tolerance,
            meta.ramp.peak_velocity,
            meta.ramp.peak_acceleration,
            meta.ramp.peak_jerk,
            meta.ramp.acceleration_limit,
            meta.ramp.jerk_limit,
            meta.ramp.feed_share,
        ] {
            w.bytes(&v.to_le_bytes());
        }
        for values in [
            &self.header.end.position,
            &self.header.end.velocity,
            &self.header.end.acceleration,
        ] {
            for v in values {
                w.out::<N>(*v);
            }
        }
        for piece in &self.pieces {
            w.bytes(&piece.ticks.to_le_bytes());
            for axis in &piece.axes {
                for v in axis.values() {
                    w.number(v);
                }
            }
        }
        let crc = crc32(w.out.get(..w.pos).unwrap_or(&[]));
        w.bytes(&crc.to_le_bytes());
        Ok(w.pos)
    }

    /// Reads a path written by [`Path::to_bytes`] (for the same `N` and `A`, with room for
    /// its pieces), checking everything (see [`Path::to_bytes`]). No allocation: the
    /// pieces are decoded into the fixed-capacity path. To play a blob without copying its
    /// pieces, use [`PathBlob`]; to decode into a path in place (a `static`), use
    /// [`Path::read_bytes`].
    ///
    /// # Errors
    /// [`Error::CorruptBlob`] (truncated, bad magic, bad CRC, inconsistent content),
    /// [`Error::UnsupportedVersion`], [`Error::UnknownNumberFormat`] (a format id no format
    /// has), [`Error::FormatMismatch`] (other number format or axis count), [`Error::CapacityExceeded`] (more pieces than `P`), [`Error::OutOfRange`] or
    /// [`Error::InvalidRate`] / [`Error::InvalidLimit`] (content a compiler would not have
    /// produced).
    ///
    /// ```
    /// use strak_trajectory::{Error, Path};
    /// assert_eq!(Path::<f32, 2, 8>::from_bytes(b"STRK"), Err(Error::CorruptBlob));
    /// ```
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, Error> {
        let mut path = Path::new();
        path.read_bytes(bytes)?;
        Ok(path)
    }

    /// [`Path::from_bytes`] into this path, in place; on an error the path is left empty.
    ///
    /// # Errors
    /// As [`Path::from_bytes`].
    pub fn read_bytes(&mut self, bytes: &[u8]) -> Result<(), Error> {
        self.clear();
        let result = self.decode(bytes);
        if result.is_err() {
            self.clear();
        }
        result
    }

    fn decode(&mut self, bytes: &[u8]) -> Result<(), Error> {
        let (ticks, records) = read_fixed(bytes, &mut self.header)?;
        let m = records.len() / piece_record_len::<N>(A);
        if m > P {
            return Err(Error::CapacityExceeded {
                capacity: P,
                required: m,
            });
        }
        let pieces = &mut self.pieces;
        validate_records(&mut self.header, records, ticks, |start, ticks, values| {
            let piece = Piece {
                start,
                ticks,
                axes: [AxisState::ZERO; A],
            };
            pieces.push(piece).map_err(|_| Error::CapacityExceeded {
                capacity: P,
                required: m,
            })?;
            if let Some(last) = pieces.last_mut() {
                decode_states(values, &mut last.axes);
            }
            Ok(())
        })
    }
}

/// Reads the fixed part of a blob into `header` (its description and end; see
/// [`Path::to_bytes`] for the layout and the order of the checks): the structure (magic,
/// version, CRC, format, count, length). Returns the stored tick count and the piece
/// records, which [`validate_records`] checks.
#[inline(never)] // its frame is gone before playing starts
fn read_fixed<'b, N: Number, const A: usize>(
    bytes: &'b [u8],
    header: &mut PathHeader<N, A>,
) -> Result<(u32, &'b [u8]), Error> {
    if bytes.len() < HEADER + 4 || bytes.get(..4) != Some(&BLOB_MAGIC[..]) {
        return Err(Error::CorruptBlob);
    }
    let mut r = Reader { bytes, pos: 4 };
    let version = u16::from_le_bytes(r.take());
    if version != BLOB_VERSION {
        return Err(Error::UnsupportedVersion { found: version });
    }
    let (body, tail) = bytes.split_at(bytes.len() - 4);
    let mut stored = [0_u8; 4];
    stored.copy_from_slice(tail);
    if crc32(body) != u32::from_le_bytes(stored) {
        return Err(Error::CorruptBlob);
    }
    let [id, axes] = r.take();
    let number = NumberFormat::from_id(id).ok_or(Error::UnknownNumberFormat { id })?;
    if number != N::FORMAT || usize::from(axes) != A {
        return Err(Error::FormatMismatch {
            expected: BlobFormat::of::<N>(A),
            found: BlobFormat {
                number,
                axes: usize::from(axes),
            },
        });
    }
    let m = r.u32() as usize;
    if m == 0 || blob_len(m, A, N::BYTES) != Some(bytes.len()) {
        return Err(Error::CorruptBlob);
    }
    let ticks = r.u32();
    let meta = &mut header.meta;
    for field in [
        &mut meta.ramp.rate,
        &mut meta.plan_duration,
        &mut meta.tolerance,
        &mut meta.ramp.peak_velocity,
        &mut meta.ramp.peak_acceleration,
        &mut meta.ramp.peak_jerk,
        &mut meta.ramp.acceleration_limit,
        &mut meta.ramp.jerk_limit,
        &mut meta.ramp.feed_share,
    ] {
        *field = r.f64();
    }
    let end = &mut header.end;
    for values in [&mut end.position, &mut end.velocity, &mut end.acceleration] {
        for v in values.iter_mut() {
            *v = r.out::<N>();
        }
    }
    Ok((ticks, body.get(records_at(A, N::BYTES)..).unwrap_or(&[])))
}

/// Validates every piece record (as [`Validator::piece`], one axis at a time), calling
/// `each` with each piece's start, length and value bytes, then the end and the tick count
/// `ticks`, completing `header` (whose description and end [`read_fixed`] wrote).
#[inline(never)] // its frame is gone before playing starts
fn validate_records<N: Number, const A: usize>(
    header: &mut PathHeader<N, A>,
    records: &[u8],
    ticks: u32,
    mut each: impl FnMut(u32, u32, &[u8]) -> Result<(), Error>,
) -> Result<(), Error> {
    let mut check = Validator::begin(header)?;
    let mut last = None;
    for rec in records.chunks_exact(piece_record_len::<N>(A)) {
        let (length, values) = rec.split_at(4);
        let mut t = [0_u8; 4];
        t.copy_from_slice(length);
        let length = u32::from_le_bytes(t);
        let start = check.next_start();
        check.piece_start(start, length)?;
        let mut state = AxisState::ZERO;
        for axis in values.chunks_exact(9 * N::BYTES) {
            decode_into(axis, &mut state);
            check.axis(length, &state)?;
        }
        each(start, length, values)?;
        last = Some((length, values));
    }
    let last = last.map(|(length, values)| {
        let axis = move |a: usize| {
            let mut state = AxisState::ZERO;
            decode_into(values.get(a * 9 * N::BYTES..).unwrap_or(&[]), &mut state);
            state
        };
        (length, axis)
    });
    check.finish(last)?;
    if header.ticks != ticks {
        return Err(Error::CorruptBlob);
    }
    Ok(())
}

/// A serialized path validated in place: its header decoded into RAM, its pieces left where
/// the bytes are (flash, typically) and read by the sampler at each piece switch, so playing
/// a blob needs no RAM for its pieces. [`PathBlob::view`] gives the [`PathView`] to play; it
/// dereferences to the [`PathHeader`].
///
/// # Alignment
/// Any byte slice is read correctly (values are read byte-wise, little-endian). On
/// Cortex-M cores with Thumb-2, a blob whose first byte is 4-byte aligned is read by the
/// tick kernels with word loads (`ldm`/`vldm`) at a piece switch, as fast as a path in RAM;
/// an unaligned one is decoded value by value there. [`AlignedBlob`] aligns an
/// `include_bytes!`:
///
/// ```
/// use strak_trajectory::{
///     compile, AlignedBlob, Along, CompileOptions, Path, PathBlob, Sampler, Timing,
/// };
/// use strak_curves::Bezier;
/// struct Ramp;
/// impl Timing for Ramp {
///     fn duration(&self) -> f64 { 0.1 }
///     fn param(&self, t: f64) -> (f64, f64) { (t.clamp(0.0, 0.1) * 10.0, 10.0) }
/// }
/// // On the host: compile and serialize (in firmware the bytes come from
/// // `static BLOB: &AlignedBlob<[u8]> = &AlignedBlob(*include_bytes!("path.bin"));`).
/// let curve = Bezier::new([[0.0_f64, 1.0], [2.0, 3.0], [4.0, 1.0]])?;
/// let trajectory = Along::new(&curve, &Ramp);
/// let path: Path<f32, 2, 8> = compile(&trajectory, 1_000.0, &CompileOptions::new())?;
/// let mut bytes = AlignedBlob([0_u8; 1024]);
/// let len = path.to_bytes(&mut bytes.0)?;
///
/// // In firmware: validate once, then play from the bytes.
/// let blob = PathBlob::<f32, 2>::from_bytes(&bytes.0[..len])?;
/// let mut sampler = Sampler::new(blob.view());
/// let mut last = sampler.next();
/// while !sampler.is_finished() {
///     last = sampler.next();
/// }
/// assert_eq!(last.position, [4.0, 1.0]); // the exact end
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct PathBlob<'a, N: Number, const A: usize> {
    header: PathHeader<N, A>,
    records: &'a [u8],
}

impl<N: Number, const A: usize> Default for PathBlob<'_, N, A> {
    fn default() -> Self {
        Self::new()
    }
}

impl<N: Number, const A: usize> Deref for PathBlob<'_, N, A> {
    type Target = PathHeader<N, A>;

    fn deref(&self) -> &PathHeader<N, A> {
        &self.header
    }
}

impl<'a, N: Number, const A: usize> PathBlob<'a, N, A> {
    /// Validates a blob written by [`Path::to_bytes`] for the same `N` and `A` (every check
    /// of [`Path::to_bytes`], the pieces and the end included, as for a freshly compiled
    /// path) and keeps a reference to its pieces. Reads the blob twice (CRC, then the
    /// pieces); its stack use does not depend on the number of pieces.
    ///
    /// # Errors
    /// As [`Path::from_bytes`], without the capacity check.
    ///
    /// ```
    /// use strak_trajectory::{Error, PathBlob};
    /// assert_eq!(PathBlob::<f32, 2>::from_bytes(b"STRK").err(), Some(Error::CorruptBlob));
    /// ```
    pub fn from_bytes(bytes: &'a [u8]) -> Result<Self, Error> {
        let mut blob = PathBlob::new();
        blob.read_bytes(bytes)?;
        Ok(blob)
    }

    /// A blob without pieces (no ticks, at rest at the origin): storage that can sit in a
    /// `static` or in the caller's frame, filled in place by [`PathBlob::read_bytes`].
    ///
    /// ```
    /// use strak_trajectory::PathBlob;
    /// let blob = PathBlob::<f32, 3>::new();
    /// assert_eq!((blob.ticks(), blob.view().piece_count()), (0, 0));
    /// ```
    pub const fn new() -> Self {
        PathBlob {
            header: PathHeader::EMPTY,
            records: &[],
        }
    }

    /// [`PathBlob::from_bytes`] into this blob, in place: the header is decoded and
    /// completed where it lies (no value larger than one axis state is returned or passed
    /// by value), so the stack this needs is the validation's frames alone. On an error the
    /// blob is left empty ([`PathBlob::new`]).
    ///
    /// # Errors
    /// As [`PathBlob::from_bytes`].
    ///
    /// ```
    /// use strak_trajectory::{Error, PathBlob};
    /// let mut blob = PathBlob::<f32, 2>::new();
    /// assert_eq!(blob.read_bytes(b"STRK"), Err(Error::CorruptBlob));
    /// assert_eq!(blob.ticks(), 0);
    /// ```
    pub fn read_bytes(&mut self, bytes: &'a [u8]) -> Result<(), Error> {
        let result = read_fixed(bytes, &mut self.header).and_then(|(ticks, records)| {
            validate_records(&mut self.header, records, ticks, |_, _, _| Ok(()))?;
            Ok(records)
        });
        match result {
            Ok(records) => {
                self.records = records;
                Ok(())
            }
            Err(e) => {
                self.header = PathHeader::EMPTY;
                self.records = &[];
                Err(e)
            }
        }
    }

    /// The view the sampler plays: the pieces read from the blob's bytes.
    pub fn view(&self) -> PathView<'_, N, A> {
        PathView::of_records(&self.header, self.records)
    }
}

impl<'a, N: Number, const A: usize> From<&'a PathBlob<'_, N, A>> for PathView<'a, N, A> {
    fn from(blob: &'a PathBlob<'_, N, A>) -> Self {
        blob.view()
    }
}

/// A value aligned to 8 bytes, for blobs in flash: `static BLOB: &AlignedBlob<[u8]> =
/// &AlignedBlob(*include_bytes!("path.bin"));` gives `BLOB.0`, a `&[u8]` whose start is
/// aligned (see [`PathBlob`]'s alignment rule).
///
/// ```
/// use strak_trajectory::AlignedBlob;
/// static BLOB: &AlignedBlob<[u8]> = &AlignedBlob(*b"STRK....");
/// assert_eq!(BLOB.0.as_ptr() as usize % 8, 0);
/// ```
#[derive(Debug)]
#[repr(C, align(8))]
pub struct AlignedBlob<T: ?Sized>(pub T);

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::compile::testing::{Smoothstep, helix};
    use crate::compile::{CompileOptions, compile};
    use crate::num::Q40;
    use crate::plan::Along;
    use std::string::ToString;
    use std::vec;
    use strak_curves::I32F32;

    fn sample_path<N: Number>() -> Path<N, 3, 64> {
        let curve = helix(2.0, 1.5, 3.0);
        compile(
            &Along::new(&curve, &Smoothstep::new(0.3)),
            5_000.0,
            &CompileOptions::new().with_tolerance(1e-4),
        )
        .unwrap()
    }

    fn round_trip<N: Number>() {
        let path = sample_path::<N>();
        let mut buf = vec![0_u8; path.blob_len()];
        assert_eq!(path.to_bytes(&mut buf), Ok(buf.len()));
        assert_eq!(
            buf.len(),
            HEADER + 3 * 3 * N::BYTES + path.pieces().len() * (4 + 27 * N::BYTES) + 4
        );
        let back = Path::<N, 3, 64>::from_bytes(&buf).unwrap();
        assert_eq!(back, path);
        // bit for bit: serialize again
        let mut again = vec![0_u8; buf.len()];
        back.to_bytes(&mut again).unwrap();
        assert_eq!(again, buf);
    }

    #[test]
    fn round_trips_are_bit_exact() {
        round_trip::<f32>();
        round_trip::<f64>();
        round_trip::<Q40>();
    }

    #[test]
    fn crc_of_known_strings() {
        assert_eq!(crc32(b""), 0);
        assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
        assert_eq!(
            crc32(b"The quick brown fox jumps over the lazy dog"),
            0x414F_A339
        );
    }

    #[test]
    fn short_output_buffer() {
        let path = sample_path::<f32>();
        let mut buf = [0_u8; 100];
        assert_eq!(
            path.to_bytes(&mut buf),
            Err(Error::CapacityExceeded {
                capacity: 100,
                required: path.blob_len()
            })
        );
    }

    fn blob() -> std::vec::Vec<u8> {
        let path = sample_path::<Q40>();
        let mut buf = vec![0_u8; path.blob_len()];
        path.to_bytes(&mut buf).unwrap();
        buf
    }

    fn reseal(buf: &mut [u8]) {
        let n = buf.len() - 4;
        let crc = crc32(&buf[..n]);
        buf[n..].copy_from_slice(&crc.to_le_bytes());
    }

    #[test]
    fn corrupt_blobs_are_rejected() {
        let good = blob();
        // every single flipped bit (sampled) is caught by the CRC or the header checks
        for i in (0..good.len()).step_by(7) {
            let mut b = good.clone();
            b[i] ^= 0x10;
            let r = Path::<Q40, 3, 64>::from_bytes(&b);
            assert!(
                matches!(
                    r,
                    Err(Error::CorruptBlob | Error::UnsupportedVersion { .. })
                ),
                "byte {i}: {r:?}"
            );
        }
        // truncated anywhere
        for len in [0, 3, 10, HEADER, good.len() / 2, good.len() - 1] {
            assert_eq!(
                Path::<Q40, 3, 64>::from_bytes(&good[..len]),
                Err(Error::CorruptBlob),
                "length {len}"
            );
        }
        // bad magic
        let mut b = good.clone();
        b[0] = b'X';
        reseal(&mut b);
        assert_eq!(Path::<Q40, 3, 64>::from_bytes(&b), Err(Error::CorruptBlob));
        // a valid CRC over inconsistent content: a piece length changed
        let mut b = good.clone();
        let first_piece = HEADER + 9 * 8;
        b[first_piece] ^= 1;
        reseal(&mut b);
        assert_eq!(Path::<Q40, 3, 64>::from_bytes(&b), Err(Error::CorruptBlob));
        // a valid CRC over a state value far out of range
        let mut b = good.clone();
        b[first_piece + 4..first_piece + 12].copy_from_slice(&i64::MAX.to_le_bytes());
        reseal(&mut b);
        assert_eq!(Path::<Q40, 3, 64>::from_bytes(&b), Err(Error::OutOfRange));
        // a valid CRC over an end position the accumulator cannot hold (the sampler plays
        // the end as a piece of `Q40` values: `I32F32` beyond ±2²³ has none)
        let mut b = good.clone();
        b[HEADER..HEADER + 8].copy_from_slice(&(i64::MAX - 5).to_le_bytes());
        reseal(&mut b);
        assert_eq!(Path::<Q40, 3, 64>::from_bytes(&b), Err(Error::OutOfRange));
    }

    #[test]
    fn foreign_version_is_rejected() {
        let mut b = blob();
        b[4..6].copy_from_slice(&2_u16.to_le_bytes());
        reseal(&mut b);
        assert_eq!(
            Path::<Q40, 3, 64>::from_bytes(&b),
            Err(Error::UnsupportedVersion { found: 2 })
        );
    }

    #[test]
    fn other_formats_and_capacities_are_rejected() {
        let b = blob();
        let q40 = BlobFormat::of::<Q40>(3);
        assert_eq!(
            Path::<f64, 3, 64>::from_bytes(&b),
            Err(Error::FormatMismatch {
                expected: BlobFormat::of::<f64>(3),
                found: q40
            })
        );
        assert_eq!(
            Path::<Q40, 2, 64>::from_bytes(&b),
            Err(Error::FormatMismatch {
                expected: BlobFormat::of::<Q40>(2),
                found: q40
            })
        );
        for id in [0_u8, 4, 255] {
            let mut u = b.clone();
            u[6] = id;
            reseal(&mut u);
            assert_eq!(
                Path::<Q40, 3, 64>::from_bytes(&u),
                Err(Error::UnknownNumberFormat { id })
            );
        }
        let path = sample_path::<Q40>();
        let m = path.pieces().len();
        assert_eq!(
            Path::<Q40, 3, 4>::from_bytes(&b),
            Err(Error::CapacityExceeded {
                capacity: 4,
                required: m
            })
        );
        let mut f = vec![0_u8; sample_path::<f32>().blob_len()];
        sample_path::<f32>().to_bytes(&mut f).unwrap();
        assert_eq!(
            Path::<Q40, 3, 64>::from_bytes(&f),
            Err(Error::FormatMismatch {
                expected: q40,
                found: BlobFormat::of::<f32>(3)
            })
        );
        assert_eq!(
            Error::FormatMismatch {
                expected: q40,
                found: BlobFormat::of::<f32>(3)
            }
            .to_string(),
            "serialized path is for f32 with 3 axes, expected Q40 with 3 axes"
        );
    }

    /// Plays `view` to the end, with a feed change, a hold and a resume on the way (so the
    /// interpolation mode's piece loads run too), collecting every sample.
    fn play<N: crate::Kernel>(
        view: PathView<'_, N, 3>,
    ) -> std::vec::Vec<(crate::Sample<N::Out, 3>, f64)> {
        let mut sampler = crate::Sampler::new(view);
        let mut out = std::vec::Vec::new();
        for k in 0..5 * u64::from(view.ticks()) {
            match k {
                200 => sampler.set_feed(0.6),
                700 => sampler.hold(),
                900 => sampler.resume(),
                _ => {}
            }
            let progress = sampler.progress();
            out.push((sampler.next(), progress));
            if sampler.is_finished() {
                break;
            }
        }
        assert!(sampler.is_finished());
        out
    }

    fn blob_plays_as_the_path<N: crate::Kernel>() {
        let path = sample_path::<N>();
        // room for the blob at every offset 0..8 from an 8-byte aligned start
        let len = path.blob_len();
        let mut buf = AlignedBlob([0_u8; 16_384]);
        assert!(len + 8 <= buf.0.len());
        let want = play(path.view());
        let mut plain = crate::Sampler::new(&path);
        let full: std::vec::Vec<_> = (0..=path.ticks()).map(|_| plain.next()).collect();
        for offset in 0..8 {
            let bytes = &mut buf.0[offset..offset + len];
            path.to_bytes(bytes).unwrap();
            let blob = PathBlob::<N, 3>::from_bytes(bytes).unwrap();
            assert_eq!(*blob, *path, "header, offset {offset}");
            assert_eq!(
                blob.view().pieces().collect::<std::vec::Vec<_>>(),
                path.pieces()
            );
            assert_eq!(play(blob.view()), want, "offset {offset}");
            let mut s = crate::Sampler::new(&blob);
            let got: std::vec::Vec<_> = (0..=blob.ticks()).map(|_| s.next()).collect();
            assert_eq!(got, full, "full feed, offset {offset}");
            for k in [0.0, 0.5, 17.25, 1000.0, f64::from(path.ticks())] {
                assert_eq!(blob.view().eval(k), path.eval(k));
            }
        }
    }

    #[test]
    fn blobs_play_in_place_bit_for_bit_at_any_alignment() {
        blob_plays_as_the_path::<f32>();
        blob_plays_as_the_path::<f64>();
        blob_plays_as_the_path::<Q40>();
    }

    #[test]
    fn read_bytes_decodes_in_place_and_empties_on_error() {
        let b = blob();
        let mut path: Path<Q40, 3, 64> = Path::new();
        path.read_bytes(&b).unwrap();
        assert_eq!(path, sample_path::<Q40>());
        assert_eq!(path.read_bytes(&b[..10]), Err(Error::CorruptBlob));
        assert_eq!((path.ticks(), path.pieces().len()), (0, 0));
        // a blob read in place: the header as the path's, emptied again by a bad blob
        let want = sample_path::<Q40>();
        let mut blob = PathBlob::<Q40, 3>::new();
        blob.read_bytes(&b).unwrap();
        assert_eq!(*blob, *want);
        assert_eq!(blob.view().piece_count(), want.pieces().len());
        let mut bad = b.clone();
        let last = bad.len() - 12;
        bad[last] ^= 0x40;
        reseal(&mut bad);
        assert!(blob.read_bytes(&bad).is_err());
        assert_eq!(*blob, PathHeader::EMPTY);
        assert_eq!(blob.view().piece_count(), 0);
    }

    /// The offset of the end position in a blob, and of the last piece's first value.
    fn end_offsets<N: Number>(buf: &[u8]) -> (usize, usize) {
        let last = buf.len() - 4 - 27 * N::BYTES;
        (HEADER, last)
    }

    #[test]
    fn blob_ends_are_validated() {
        let good = blob();
        let (end, last) = end_offsets::<Q40>(&good);
        // an end that does not continue the last piece (checksum resealed): the last tick
        // would jump from the piece's end to z = 4·10⁶ (in range)
        let mut b = good.clone();
        let far = I32F32::from_num(4_000_000);
        b[end + 16..end + 24].copy_from_slice(&far.to_bits().to_le_bytes());
        reseal(&mut b);
        assert_eq!(Path::<Q40, 3, 64>::from_bytes(&b), Err(Error::CorruptBlob));
        assert_eq!(
            PathBlob::<Q40, 3>::from_bytes(&b).err(),
            Some(Error::CorruptBlob)
        );
        // an end velocity that does not continue the last piece
        let mut b = good.clone();
        let v = end + 3 * 8;
        b[v..v + 8].copy_from_slice(&I32F32::from_num(3).to_bits().to_le_bytes());
        reseal(&mut b);
        assert_eq!(
            PathBlob::<Q40, 3>::from_bytes(&b).err(),
            Some(Error::CorruptBlob)
        );
        // an end position beyond the format's range (up to twice it would fit an I32F32)
        let mut b = good.clone();
        let huge = I32F32::from_num(6_000_000);
        b[end..end + 8].copy_from_slice(&huge.to_bits().to_le_bytes());
        reseal(&mut b);
        assert_eq!(
            PathBlob::<Q40, 3>::from_bytes(&b).err(),
            Some(Error::OutOfRange)
        );
        // the last piece moved instead (its position value): the end no longer continues it
        let mut b = good.clone();
        let x = Q40::from_f64(1.0).unwrap().to_bits();
        b[last..last + 8].copy_from_slice(&x.to_le_bytes());
        reseal(&mut b);
        assert_eq!(
            PathBlob::<Q40, 3>::from_bytes(&b).err(),
            Some(Error::CorruptBlob)
        );
        // the untouched blob passes
        assert!(PathBlob::<Q40, 3>::from_bytes(&good).is_ok());
    }

    #[test]
    fn the_end_continues_the_last_piece_within_one_tolerance() {
        let path = sample_path::<f64>();
        let mut good = vec![0_u8; path.blob_len()];
        path.to_bytes(&mut good).unwrap();
        let piece = path.pieces().last().unwrap();
        let s = &piece.axes()[0];
        let n = f64::from(piece.ticks());
        let (c2, c3) = (n * (n - 1.0) / 2.0, n * (n - 1.0) * (n - 2.0) / 6.0);
        let piece_end = s.position + n * s.delta1 + c2 * s.delta2 + c3 * s.delta3;
        let tolerance = path.tolerance();
        // the end's x, `k` tolerances from where the last piece ends
        let moved = |k: f64| {
            let mut b = good.clone();
            let x = piece_end + k * tolerance;
            b[HEADER..HEADER + 8].copy_from_slice(&x.to_le_bytes());
            reseal(&mut b);
            Path::<f64, 3, 64>::from_bytes(&b).map(|_| ())
        };
        assert_eq!(moved(0.9), Ok(()));
        assert_eq!(moved(-0.9), Ok(()));
        assert_eq!(moved(1.1), Err(Error::CorruptBlob));
        assert_eq!(moved(-1.5), Err(Error::CorruptBlob));
    }
}
