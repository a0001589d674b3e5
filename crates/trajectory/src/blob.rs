//! Serializing a compiled [`Path`] to bytes (on the host) and reading it back from a `&[u8]`
//! (in firmware, without allocation).

use heapless::Vec;

use crate::error::Error;
use crate::number::Number;
use crate::path::{AxisState, Path, PathEnd, PathMeta, Piece};

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
    fn number<N: Number>(&mut self) -> N {
        let v = N::read_le(self.bytes.get(self.pos..).unwrap_or(&[]));
        self.pos += N::BYTES;
        v
    }
    fn out<N: Number>(&mut self) -> N::Out {
        let v = N::read_out_le(self.bytes.get(self.pos..).unwrap_or(&[]));
        self.pos += N::BYTES;
        v
    }
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
    /// | 6      | 1               | number format id ([`Number::FORMAT_ID`]: 1 f32, 2 f64, 3 Q40) |
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
    /// ([`Error::CorruptBlob`]), number format and axes ([`Error::FormatMismatch`]), piece count
    /// against the capacity ([`Error::CapacityExceeded`]), exact length and consistent tick
    /// counts ([`Error::CorruptBlob`]); then the decoded path is validated like a freshly compiled
    /// one (range of every value: [`Error::OutOfRange`]), so a blob that passes cannot make the
    /// sampler overflow. A round trip is bit-exact.
    ///
    /// # Errors
    /// [`Error::CapacityExceeded`] when `out` is shorter than [`Path::blob_len`]
    /// (`capacity` and `required` in bytes); [`Error::FormatMismatch`] for more than 255 axes.
    ///
    /// ```
    /// use strak_trajectory::{compile, CompileOptions, Path, Timing};
    /// use strak_curves::Bezier;
    /// struct Ramp;
    /// impl Timing for Ramp {
    ///     fn duration(&self) -> f64 { 0.1 }
    ///     fn param(&self, t: f64) -> (f64, f64) { (t.clamp(0.0, 0.1) * 10.0, 10.0) }
    /// }
    /// let curve = Bezier::new([[0.0_f64, 1.0], [2.0, 3.0], [4.0, 1.0]])?;
    /// let path: Path<f32, 2, 8> = compile(&curve, &Ramp, 1_000.0, &CompileOptions::new())?;
    /// let mut buf = [0_u8; 1024];
    /// let len = path.to_bytes(&mut buf)?;
    /// assert_eq!(&buf[..4], b"STRK");
    /// let back = Path::<f32, 2, 8>::from_bytes(&buf[..len])?;
    /// assert_eq!(back, path); // bit-exact
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn to_bytes(&self, out: &mut [u8]) -> Result<usize, Error> {
        let axes = u8::try_from(A).map_err(|_| Error::FormatMismatch)?;
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
        w.bytes(&self.ticks.to_le_bytes());
        let meta = &self.meta;
        for v in [
            meta.rate,
            meta.plan_duration,
            meta.tolerance,
            meta.peak_velocity,
            meta.peak_acceleration,
            meta.peak_jerk,
            meta.acceleration_limit,
            meta.jerk_limit,
            meta.feed_share,
        ] {
            w.bytes(&v.to_le_bytes());
        }
        for values in [
            &self.end.position,
            &self.end.velocity,
            &self.end.acceleration,
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
    /// pieces are decoded into the fixed-capacity path.
    ///
    /// # Errors
    /// [`Error::CorruptBlob`] (truncated, bad magic, bad CRC, inconsistent content),
    /// [`Error::UnsupportedVersion`], [`Error::FormatMismatch`] (other number format or axis
    /// count), [`Error::CapacityExceeded`] (more pieces than `P`), [`Error::OutOfRange`] or
    /// [`Error::InvalidRate`] / [`Error::InvalidLimit`] (content a compiler would not have
    /// produced).
    ///
    /// ```
    /// use strak_trajectory::{Error, Path};
    /// assert_eq!(Path::<f32, 2, 8>::from_bytes(b"STRK"), Err(Error::CorruptBlob));
    /// ```
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, Error> {
        if bytes.len() < HEADER + 4 || bytes.get(..4) != Some(&BLOB_MAGIC[..]) {
            return Err(Error::CorruptBlob);
        }
        let mut r = Reader { bytes, pos: 4 };
        let version = u16::from_le_bytes(r.take());
        if version != BLOB_VERSION {
            return Err(Error::UnsupportedVersion { found: version });
        }
        let body_len = bytes.len() - 4;
        let (body, tail) = bytes.split_at(body_len);
        let mut stored = [0_u8; 4];
        stored.copy_from_slice(tail);
        if crc32(body) != u32::from_le_bytes(stored) {
            return Err(Error::CorruptBlob);
        }
        let [format, axes] = r.take();
        if format != N::FORMAT_ID || usize::from(axes) != A {
            return Err(Error::FormatMismatch);
        }
        let m = r.u32() as usize;
        if m > P {
            return Err(Error::CapacityExceeded {
                capacity: P,
                required: m,
            });
        }
        if m == 0 || blob_len(m, A, N::BYTES) != Some(bytes.len()) {
            return Err(Error::CorruptBlob);
        }
        let ticks = r.u32();
        let meta = PathMeta {
            rate: r.f64(),
            plan_duration: r.f64(),
            tolerance: r.f64(),
            peak_velocity: r.f64(),
            peak_acceleration: r.f64(),
            peak_jerk: r.f64(),
            acceleration_limit: r.f64(),
            jerk_limit: r.f64(),
            feed_share: r.f64(),
        };
        let mut end_values = [[N::Out::default(); A]; 3];
        for values in &mut end_values {
            for v in values.iter_mut() {
                *v = r.out::<N>();
            }
        }
        let [position, velocity, acceleration] = end_values;
        let end = PathEnd {
            position,
            velocity,
            acceleration,
        };
        let mut pieces: Vec<Piece<N, A>, P> = Vec::new();
        let mut start = 0_u32;
        for _ in 0..m {
            let n = r.u32();
            let mut axes = [AxisState::default(); A];
            for axis in &mut axes {
                let mut v = [N::ZERO; 9];
                for x in &mut v {
                    *x = r.number();
                }
                *axis = AxisState::from_values(v);
            }
            let piece = Piece {
                start,
                ticks: n,
                axes,
            };
            start = start.checked_add(n).ok_or(Error::CorruptBlob)?;
            pieces.push(piece).map_err(|_| Error::CapacityExceeded {
                capacity: P,
                required: m,
            })?;
        }
        let path = Path::from_parts(pieces, meta, end)?;
        if path.ticks != ticks {
            return Err(Error::CorruptBlob);
        }
        Ok(path)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::compile::testing::{Smoothstep, helix};
    use crate::compile::{CompileOptions, compile};
    use crate::number::Q40;
    use std::vec;

    fn sample_path<N: Number>() -> Path<N, 3, 64> {
        let curve = helix(2.0, 1.5, 3.0);
        compile(
            &curve,
            &Smoothstep::new(0.3),
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
        assert_eq!(
            Path::<f64, 3, 64>::from_bytes(&b),
            Err(Error::FormatMismatch)
        );
        assert_eq!(
            Path::<Q40, 2, 64>::from_bytes(&b),
            Err(Error::FormatMismatch)
        );
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
            Err(Error::FormatMismatch)
        );
    }
}
