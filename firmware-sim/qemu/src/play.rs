//! Playing a path: the control-tick handler a timer interrupt would call, and the output of
//! every sample.

use strak_curves::I32F32;
use strak_trajectory::{Error, Kernel, PathBlob, PathView, Sample, Sampler};

use crate::jobs::{Event, Format, TimedEvent};
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

/// Plays a path with its events, one [`Player::on_tick`] per control tick, exactly as
/// `strak-sim run` plays a job: the events of a tick apply before its sample; the run ends
/// when the sampler is finished, or after `10·(ticks + 1) + last event tick + 1` samples
/// (a hold without resume).
#[derive(Debug)]
pub struct Player<'a, N: Kernel, const A: usize> {
    sampler: Sampler<'a, N, A>,
    events: &'a [TimedEvent],
    next_event: usize,
    tick: u64,
    guard: u64,
}

impl<'a, N: Kernel, const A: usize> Player<'a, N, A> {
    /// A player at tick 0 of `path` (a `&Path` or a view of a blob in flash).
    ///
    /// Not inlined: the sampler it builds is moved into the player in this call's own frame,
    /// which is gone before the first tick, so the caller's frame holds one sampler only.
    #[inline(never)]
    pub fn new(path: impl Into<PathView<'a, N, A>>, events: &'a [TimedEvent]) -> Self {
        let path = path.into();
        let last_event = events.last().map_or(0, |e| e.tick);
        Player {
            sampler: Sampler::new(path),
            events,
            next_event: 0,
            tick: 0,
            guard: 10 * (u64::from(path.ticks()) + 1) + last_event + 1,
        }
    }

    /// One control tick — the body of the timer interrupt handler: apply the events due,
    /// then one [`Sampler::next`].
    #[inline]
    pub fn on_tick(&mut self) -> Sample<N::Out, A> {
        while let Some(e) = self.events.get(self.next_event) {
            if e.tick > self.tick {
                break;
            }
            match e.event {
                Event::Feed(f) => self.sampler.set_feed(f),
                Event::Hold => self.sampler.hold(),
                Event::Resume => self.sampler.resume(),
                Event::Abort => self.sampler.abort(),
            }
            self.next_event += 1;
        }
        self.tick += 1;
        self.sampler.next()
    }

    /// Whether the run is over (the sampler finished, or the guard stopped it).
    pub fn done(&self) -> bool {
        self.sampler.is_finished() || self.tick >= self.guard
    }
}

/// Plays `path` with `events` and logs the stream (`J`, one `S` per tick, `E`); returns the
/// number of samples.
pub fn play_and_log<'a, N, const A: usize>(
    name: &str,
    format: Format,
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
    let mut player = Player::new(path, events);
    let mut count: u32 = 0;
    let mut bits = [0_u64; 12];
    loop {
        let s = player.on_tick();
        for (b, v) in bits
            .iter_mut()
            .zip(s.position.iter().chain(&s.velocity).chain(&s.acceleration))
        {
            *b = v.out_bits();
        }
        let n = (3 * A).min(bits.len());
        defmt::println!("S {=u32} {=[?]}", count, bits.get(..n).unwrap_or(&[]));
        count = count.wrapping_add(1);
        if player.done() {
            break;
        }
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

/// What [`play_blob`] played: the number of samples and a hash of every sample's bits.
#[derive(Clone, Copy, Debug, PartialEq, Eq, defmt::Format)]
pub struct Played {
    /// Pieces of the path.
    pub pieces: usize,
    /// Samples played (the final one included).
    pub samples: u32,
    /// [`mix`] folded over every sample's positions, velocities and accelerations
    /// ([`OutBits`]), in the order `cargo xtask qemu` folds the host's bits.
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
    let mut player = Player::new(&path, events);
    let mut played = Played {
        pieces: path.view().piece_count(),
        samples: 0,
        hash: 0,
    };
    loop {
        let s = player.on_tick();
        for v in s.position.iter().chain(&s.velocity).chain(&s.acceleration) {
            played.hash = mix(played.hash, v.out_bits());
        }
        played.samples = played.samples.wrapping_add(1);
        if player.done() {
            return Ok(played);
        }
    }
}
