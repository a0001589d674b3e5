//! Playing a path with its events through the library's [`EventPlayer`] (the player of
//! `strak-sim run` and `strak-sim compile`: the events of a tick apply before its sample, the
//! guard ends a hold without resume), and the output of every sample.

use strak_curves::I32F32;
use strak_trajectory::{
    Error, EventPlayer, Kernel, NumberFormat, PathBlob, PathView, Sample, Sampler,
};

use crate::jobs::TimedEvent;
use crate::mix;

/// A sample value's raw bits, widened to `u64` (as the host's `strak_sim::export::OutBits`).
pub trait OutBits: Copy {
    /// The bits.
    fn out_bits(self) -> u64;
}

impl OutBits for f32 {
    fn out_bits(self) -> u64 {
        u64::from(self.to_bits())
    }
}

impl OutBits for I32F32 {
    fn out_bits(self) -> u64 {
        self.to_bits().cast_unsigned()
    }
}

/// Plays `path` with `events` and logs the stream (`J`, one `S` per tick, `E`); returns the
/// number of samples.
pub fn play_and_log<'a, N, const A: usize>(
    name: &str,
    format: NumberFormat,
    source: &str,
    path: impl Into<PathView<'a, N, A>>,
    events: &'a [TimedEvent],
) -> u32
where
    N: Kernel,
    N::Out: OutBits,
{
    defmt::println!(
        "J {=str} {=str} {=str} {=usize}",
        name,
        format.name(),
        source,
        A
    );
    let path: PathView<'a, N, A> = path.into();
    let mut player = EventPlayer::new(events, path.ticks());
    let mut sampler = Sampler::new(path);
    let mut count: u32 = 0;
    while let Some(s) = player.step(&mut sampler) {
        log_sample(count, &s);
        count = count.wrapping_add(1);
    }
    defmt::println!(
        "E {=str} {=str} {=str} {=u32}",
        name,
        format.name(),
        source,
        count
    );
    count
}

/// Logs sample `count` as an `S` line: every position's, velocity's and acceleration's bits.
pub fn log_sample<T: OutBits, const A: usize>(count: u32, s: &Sample<T, A>) {
    let mut bits = [0_u64; 18];
    for (b, v) in bits
        .iter_mut()
        .zip(s.position.iter().chain(&s.velocity).chain(&s.acceleration))
    {
        *b = v.out_bits();
    }
    let n = (3 * A).min(bits.len());
    defmt::println!("S {=u32} {=[?]}", count, bits.get(..n).unwrap_or(&[]));
}

/// `hash` with every position's, velocity's and acceleration's bits of `s` folded in
/// ([`mix`]), in the order `cargo xtask qemu` folds the host's bits.
#[inline]
pub fn fold_sample<T: OutBits, const A: usize>(hash: u64, s: &Sample<T, A>) -> u64 {
    let values = s.position.iter().chain(&s.velocity).chain(&s.acceleration);
    values.fold(hash, |h, v| mix(h, v.out_bits()))
}

/// What [`play_blob`] played: the number of samples and a hash of every sample's bits.
#[derive(Clone, Copy, Debug, PartialEq, Eq, defmt::Format)]
pub struct Played {
    /// Pieces of the path.
    pub pieces: usize,
    /// Samples played (the final one included).
    pub samples: u32,
    /// Every sample folded in with [`fold_sample`].
    pub hash: u64,
}

/// Validates the blob `blob` (a path of `A` axes in `N`) and plays it with `events` to its
/// end, as the tick handler would, folding every sample into a hash: the whole work of a
/// firmware that plays a path from flash.
///
/// The blob is validated in place ([`PathBlob::read_bytes`] into a blob in this frame) and
/// its pieces are read from flash at each piece switch: no copy of them in RAM.
///
/// # Errors
/// The error of [`PathBlob::from_bytes`].
#[inline(never)]
pub fn play_blob<N, const A: usize>(
    blob: &'static [u8],
    events: &'static [TimedEvent],
) -> Result<Played, Error>
where
    N: Kernel,
    N::Out: OutBits,
{
    let mut path = PathBlob::<N, A>::new();
    path.read_bytes(blob)?;
    let view = path.view();
    let mut player = EventPlayer::new(events, view.ticks());
    let mut sampler = sampler_of(view);
    let mut played = Played {
        pieces: view.piece_count(),
        samples: 0,
        hash: 0,
    };
    while let Some(s) = player.step(&mut sampler) {
        played.hash = fold_sample(played.hash, &s);
        played.samples = played.samples.wrapping_add(1);
    }
    Ok(played)
}

/// The sampler at tick 0 of `view`, built in the caller's slot.
///
/// Not inlined: the values [`Sampler::new`] builds live in this call's own frame, which is gone
/// before the first tick, so the caller's frame holds one sampler only.
#[inline(never)]
fn sampler_of<N: Kernel, const A: usize>(view: PathView<'_, N, A>) -> Sampler<'_, N, A> {
    Sampler::new(view)
}
