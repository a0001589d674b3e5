//! The sampler's entry points against each other on the target, bit for bit: over a whole
//! path, `next_position()` gives `next().position` and `next_into()` the values of `next()`
//! in the accumulator's format, and a sampler that mixes the three gives the same, through
//! every kind of tick the target runs — the piece switch inline (from the pieces in RAM, into
//! the end state, the end sample's own tick), from a blob's records (aligned or not), off the
//! tick grid after a feed override, and the standstill after the end. Run by the `icount`
//! firmware before it measures; a difference fails the run, and so `cargo xtask qemu`.
//!
//! The kernels themselves are checked against the portable kernel by
//! [`kernel_check`](crate::kernel_check); this check covers the sampler's code around them
//! as the target compiles it (the host's tests run the same comparisons with the portable
//! kernel).

use strak_trajectory::{Kernel, PathView, Sample, Sampler};

/// Ticks played after the end (the standstill).
const AFTER_END: u32 = 3;

/// The little-endian bits of a sample value.
fn bits<N: Kernel>(v: N::Out) -> [u8; 8] {
    let mut b = [0; 8];
    N::write_out_le(v, &mut b);
    b
}

/// `true` when the two value arrays hold the same bits.
fn same<N: Kernel, const A: usize>(a: &[N::Out; A], b: &[N::Out; A]) -> bool {
    a.iter().zip(b).all(|(x, y)| bits::<N>(*x) == bits::<N>(*y))
}

/// `true` when the sample in the accumulator's format rounds to `want`, bit for bit.
fn same_native<N: Kernel, const A: usize>(
    got: &Sample<N::Native, A>,
    want: &Sample<N::Out, A>,
) -> bool {
    got.tick == want.tick
        && same::<N, A>(&got.position.map(N::native_to_out), &want.position)
        && same::<N, A>(&got.velocity.map(N::native_to_out), &want.velocity)
        && same::<N, A>(&got.acceleration.map(N::native_to_out), &want.acceleration)
}

/// The control events of a run with events: a feed override at tick 300, full feed again at
/// 600 (off the tick grid from then on), a hold at 900 and the resume at 1 400.
fn events<N: Kernel, const A: usize>(k: u32, s: &mut Sampler<'_, N, A>) {
    match k {
        300 => s.set_feed(0.5),
        600 => s.set_feed(1.0),
        900 => s.hold(),
        1_400 => s.resume(),
        _ => {}
    }
}

/// Plays `path` to its end and [`AFTER_END`] ticks on with every entry point, with or
/// without [`events`]; returns the ticks compared or the first entry point that differs
/// from `next()`.
fn run<N: Kernel, const A: usize>(
    path: PathView<'_, N, A>,
    with_events: bool,
) -> Result<u32, &'static str> {
    let mut full = Sampler::new(path);
    let mut position = Sampler::new(path);
    let mut native = Sampler::new(path);
    let mut mixed = Sampler::new(path);
    let mut out = Sample::splat(N::NATIVE_ZERO);
    let (mut k, mut after) = (0_u32, 0);
    while after < AFTER_END {
        if with_events {
            for s in [&mut full, &mut position, &mut native, &mut mixed] {
                events(k, s);
            }
        }
        let want = full.next();
        if !same::<N, A>(&position.next_position(), &want.position) {
            return Err("next_position");
        }
        native.next_into(&mut out);
        if !same_native::<N, A>(&out, &want) {
            return Err("next_into");
        }
        let agrees = match k % 3 {
            0 => same::<N, A>(&mixed.next_position(), &want.position),
            1 => {
                let s = mixed.next();
                s.tick == want.tick
                    && same::<N, A>(&s.position, &want.position)
                    && same::<N, A>(&s.velocity, &want.velocity)
                    && same::<N, A>(&s.acceleration, &want.acceleration)
            }
            _ => {
                mixed.next_into(&mut out);
                same_native::<N, A>(&out, &want)
            }
        };
        if !agrees {
            return Err("mixed next_position, next and next_into");
        }
        let finished = full.is_finished();
        if [&position, &native, &mixed]
            .iter()
            .any(|s| s.is_finished() != finished)
        {
            return Err("is_finished");
        }
        if finished {
            after += 1;
        }
        k = k.wrapping_add(1);
        if k > 8 * path.ticks() + 10_000 {
            return Err("the end (never finished)");
        }
    }
    Ok(k)
}

/// [`run`] without and with events; returns the ticks compared.
///
/// # Errors
/// The first entry point that differs from `next()`.
pub fn check<N: Kernel, const A: usize>(path: PathView<'_, N, A>) -> Result<u32, &'static str> {
    Ok(run(path, false)? + run(path, true)?)
}
