//! The check that firmware runs on its target (`cargo xtask qemu`): every entry point of a
//! format's tick kernels against the portable kernel, bit for bit, on given states.

use super::{Kernel, portable};
use crate::num::Number;
use crate::path::{AxisState, Sample};

/// The most axes a record buffer holds (the assembly kernels' [`UNROLLED`](super::UNROLLED)).
const MAX_AXES: usize = 8;

/// Room for one piece record's values (8-byte values, [`MAX_AXES`] axes) and one more byte,
/// for a copy at an odd address; aligned to 8 bytes as a blob in flash may be.
#[repr(C, align(8))]
struct Record([u8; 9 * 8 * MAX_AXES + 1]);

/// The little-endian bytes of a value.
fn bits<N: Number>(x: N) -> [u8; 8] {
    let mut b = [0; 8];
    x.write_le(&mut b);
    b
}

/// The little-endian bytes of a sample-type value.
fn out_bits<N: Number>(x: N::Out) -> [u8; 8] {
    let mut b = [0; 8];
    N::write_out_le(x, &mut b);
    b
}

fn same_states<N: Number, const A: usize>(a: &[AxisState<N>; A], b: &[AxisState<N>; A]) -> bool {
    a.iter()
        .zip(b)
        .all(|(x, y)| x.values().map(bits) == y.values().map(bits))
}

fn same_out<N: Number, const A: usize>(a: &[N::Out; A], b: &[N::Out; A]) -> bool {
    a.map(out_bits::<N>) == b.map(out_bits::<N>)
}

fn same_sample<N: Number, const A: usize>(a: &Sample<N::Out, A>, b: &Sample<N::Out, A>) -> bool {
    a.tick == b.tick
        && same_out::<N, A>(&a.position, &b.position)
        && same_out::<N, A>(&a.velocity, &b.velocity)
        && same_out::<N, A>(&a.acceleration, &b.acceleration)
}

fn same_native<N: Kernel, const A: usize>(
    a: &Sample<N::Native, A>,
    b: &Sample<N::Native, A>,
) -> bool {
    let v = |x: &[N::Native; A]| x.map(|v| bits(N::from_native(v)));
    a.tick == b.tick
        && v(&a.position) == v(&b.position)
        && v(&a.velocity) == v(&b.velocity)
        && v(&a.acceleration) == v(&b.acceleration)
}

/// Runs every entry point of `N`'s kernels and of the portable kernel on `state` (with
/// `next` as the next piece: in RAM, and as a blob record at an 8-byte aligned and at an odd
/// address) and names the first entry point whose output or resulting state differs.
pub(crate) fn run<N: Kernel, const A: usize>(
    state: &[AxisState<N>; A],
    next: &[AxisState<N>; A],
    tick: u64,
) -> Result<(), &'static str> {
    let len = 9 * A * N::BYTES;
    let mut rec = Record([0; 9 * 8 * MAX_AXES + 1]);
    let mut odd = Record([0; 9 * 8 * MAX_AXES + 1]);
    if A > MAX_AXES {
        return Err("more axes than the check holds");
    }
    let values = next.iter().flat_map(AxisState::values);
    for (i, v) in values.enumerate() {
        let at = i * N::BYTES;
        v.write_le(rec.0.get_mut(at..).unwrap_or(&mut []));
        v.write_le(odd.0.get_mut(at + 1..).unwrap_or(&mut []));
    }
    let aligned = rec.0.get(..len).unwrap_or(&[]);
    let unaligned = odd.0.get(1..=len).unwrap_or(&[]);
    let mut errors = ticks::<N, A>(state, tick).err();
    for (bytes, name) in [(aligned, "aligned"), (unaligned, "unaligned")] {
        if errors.is_none() {
            errors = switches::<N, A>(state, next, bytes, tick)
                .err()
                .map(|e| if name == "aligned" { e.0 } else { e.1 });
        }
    }
    errors.map_or(Ok(()), Err)
}

/// The plain ticks: full, position only, in the accumulator's format.
fn ticks<N: Kernel, const A: usize>(
    state: &[AxisState<N>; A],
    tick: u64,
) -> Result<(), &'static str> {
    let (mut a, mut b) = (*state, *state);
    let (x, y) = (
        N::tick_sample(&mut a, tick),
        portable::tick_sample(&mut b, tick),
    );
    if !same_sample::<N, A>(&x, &y) || !same_states(&a, &b) {
        return Err("tick_sample");
    }
    let (mut a, mut b) = (*state, *state);
    let (x, y) = (N::tick_position(&mut a), portable::tick_position(&mut b));
    if !same_out::<N, A>(&x, &y) || !same_states(&a, &b) {
        return Err("tick_position");
    }
    let (mut a, mut b) = (*state, *state);
    let (mut x, mut y) = (Sample::splat(N::NATIVE_ZERO), Sample::splat(N::NATIVE_ZERO));
    N::tick_native(&mut a, tick, &mut x);
    portable::tick_native(&mut b, tick, &mut y);
    if !same_native::<N, A>(&x, &y) || !same_states(&a, &b) {
        return Err("tick_native");
    }
    Ok(())
}

/// The piece switches from RAM and from `bytes` (the names for an aligned and an unaligned
/// record).
fn switches<N: Kernel, const A: usize>(
    state: &[AxisState<N>; A],
    next: &[AxisState<N>; A],
    bytes: &[u8],
    tick: u64,
) -> Result<(), (&'static str, &'static str)> {
    let (mut a, mut b, mut c) = (*state, *state, *state);
    let x = N::switch_sample(&mut a, next, tick);
    let y = N::switch_sample_bytes(&mut b, bytes, tick);
    let z = portable::switch_sample(&mut c, next, tick);
    if !same_sample::<N, A>(&x, &z) || !same_states(&a, &c) {
        return Err(("switch_sample", "switch_sample"));
    }
    if !same_sample::<N, A>(&y, &z) || !same_states(&b, &c) {
        return Err((
            "switch_sample_bytes (aligned)",
            "switch_sample_bytes (unaligned)",
        ));
    }
    let (mut a, mut b, mut c) = (*state, *state, *state);
    let x = N::switch_position(&mut a, next);
    let y = N::switch_position_bytes(&mut b, bytes);
    let z = portable::switch_position(&mut c, next);
    if !same_out::<N, A>(&x, &z) || !same_states(&a, &c) {
        return Err(("switch_position", "switch_position"));
    }
    if !same_out::<N, A>(&y, &z) || !same_states(&b, &c) {
        return Err((
            "switch_position_bytes (aligned)",
            "switch_position_bytes (unaligned)",
        ));
    }
    let (mut a, mut b, mut c) = (*state, *state, *state);
    let mut x = Sample::splat(N::NATIVE_ZERO);
    let (mut y, mut z) = (x, x);
    N::switch_native(&mut a, next, tick, &mut x);
    N::switch_native_bytes(&mut b, bytes, tick, &mut y);
    portable::switch_native(&mut c, next, tick, &mut z);
    if !same_native::<N, A>(&x, &z) || !same_states(&a, &c) {
        return Err(("switch_native", "switch_native"));
    }
    if !same_native::<N, A>(&y, &z) || !same_states(&b, &c) {
        return Err((
            "switch_native_bytes (aligned)",
            "switch_native_bytes (unaligned)",
        ));
    }
    Ok(())
}
