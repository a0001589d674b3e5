//! Blob loading: [`Path::from_bytes`] on any bytes, as they are and with the CRC resealed
//! over them (so that mutations reach the checks behind the checksum).
//!
//! The header's format id (byte 6) and axis count (byte 7) choose the `Path<N, A, P>` the
//! bytes are loaded as (f32, f64, Q40; 1, 2, 3, 4 or 6 axes; other values load as f64 with 3
//! axes and must be rejected), with room for [`PIECES`] pieces. For every load:
//!
//! * no panic, whatever the bytes;
//! * a capacity of [`SMALL`] pieces loads the same path or fails with an error;
//! * a path that loads serializes back to the same bytes ([`Path::to_bytes`]);
//! * played in full (up to [`MAX_PLAY`] ticks), every sample is finite and the last one is
//!   the end point exactly ([`check::play`]);
//! * the end position agrees with the last piece ([`check::check_end_agrees`]).

use strak_trajectory::{Kernel, Path, Q40, crc32};

use crate::check;
use crate::{Violation, violation};

/// The piece capacity blobs are loaded into.
pub const PIECES: usize = 16;
/// A capacity that many blobs exceed.
pub const SMALL: usize = 2;
/// Paths with more ticks are checked without playing them.
pub const MAX_PLAY: u32 = 1 << 16;

/// The harness: `data` as a blob, then resealed.
///
/// # Errors
/// The first broken invariant.
pub fn run(data: &[u8]) -> Result<(), Violation> {
    load_any(data)?;
    if data.len() >= 4 {
        let mut sealed = data.to_vec();
        reseal(&mut sealed);
        if sealed != data {
            load_any(&sealed)?;
        }
    }
    Ok(())
}

/// Writes the CRC-32 of all bytes but the last four into the last four (a blob's trailer).
pub fn reseal(bytes: &mut [u8]) {
    if let Some(n) = bytes.len().checked_sub(4) {
        let crc = crc32(&bytes[..n]);
        bytes[n..].copy_from_slice(&crc.to_le_bytes());
    }
}

fn load_any(bytes: &[u8]) -> Result<(), Violation> {
    let axes = bytes.get(7).copied().unwrap_or(0);
    match bytes.get(6).copied().unwrap_or(0) {
        1 => by_axes::<f32>(bytes, axes),
        3 => by_axes::<Q40>(bytes, axes),
        _ => by_axes::<f64>(bytes, axes),
    }
}

fn by_axes<N: Kernel>(bytes: &[u8], axes: u8) -> Result<(), Violation> {
    match axes {
        1 => load::<N, 1>(bytes),
        2 => load::<N, 2>(bytes),
        4 => load::<N, 4>(bytes),
        6 => load::<N, 6>(bytes),
        _ => load::<N, 3>(bytes),
    }
}

fn load<N: Kernel, const A: usize>(bytes: &[u8]) -> Result<(), Violation> {
    let small = Path::<N, A, SMALL>::from_bytes(bytes);
    let Ok(path) = Path::<N, A, PIECES>::from_bytes(bytes) else {
        return match small {
            Ok(_) => Err(violation!(
                "a blob loads with capacity {SMALL} but not with {PIECES}"
            )),
            Err(_) => Ok(()),
        };
    };
    if let Ok(s) = &small
        && s.pieces() != path.pieces()
    {
        return Err(violation!(
            "capacities {SMALL} and {PIECES} load other pieces"
        ));
    }
    let mut again = vec![0_u8; path.blob_len()];
    match path.to_bytes(&mut again) {
        Ok(n) if again[..n] == *bytes => {}
        other => {
            return Err(violation!(
                "a loaded {} path with {A} axes does not serialize back to its bytes ({other:?})",
                N::NAME
            ));
        }
    }
    check::check_end_agrees(&path)?;
    if path.ticks() <= MAX_PLAY {
        check::play(&path, &[], u64::from(MAX_PLAY) + 2)?;
    }
    Ok(())
}
