//! Online moves on the device: a move file of `firmware-sim/examples/moves` (bundled by
//! `cargo xtask qemu` as a [`MoveJob`]) solved, compiled and played with its new targets and
//! quick stops exactly as `strak-sim move` plays it (`strak_sim::online_move::play_moves`):
//! an event at tick `k` takes over from the sample of tick `k − 1`
//! ([`take_over_into`]), a quick stop is a take-over to rest with
//! [`MoveOptions::quick_stop`], and every sample is logged for the comparison with the host.

use strak_curves::Scalar;
use strak_trajectory::{
    AxisLimits, Error, Interface, Kernel, Kinematics, MoveOptions, NumberFormat, OnlineMove, Path,
    Real, Sample, Sampler, compile_move_into, take_over_into,
};

use crate::PIECES;
use crate::jobs::{MoveEvent, MoveJob, MoveTarget};
use crate::play::{OutBits, log_sample};

/// Per axis `(position, velocity, acceleration)` in the solver's format.
fn states<R: Real, const D: usize>(states: &[[f64; 3]; D]) -> [Kinematics<R>; D] {
    states.map(|[p, v, a]| Kinematics::new(R::lit(p), R::lit(v), R::lit(a)))
}

/// The solver's options for a move to `target` (a quick stop for `stop`).
fn options<const D: usize>(job: &MoveJob<D>, target: &MoveTarget<D>, stop: bool) -> MoveOptions {
    let options = MoveOptions::new()
        .with_rate(job.rate_hz)
        .with_synchronization(job.sync);
    match (stop, target.position) {
        (true, _) => options.quick_stop(),
        (false, true) => options.with_interface(Interface::Position),
        (false, false) => options.with_interface(Interface::Velocity),
    }
}

/// Plays `job` with the solver in `R` and the paths in `N`, logging the stream (`J`, one
/// `S` per tick, `E`, source `online`). `m` and `paths` are the caller's, written in place:
/// the move, the path playing and the path the next move is compiled into. Returns the
/// number of samples.
///
/// # Errors
/// A limit the solver rejects; the error of a move the solver or the compiler rejects.
#[inline(never)]
pub fn play_move<N, R, const D: usize>(
    job: &MoveJob<D>,
    format: NumberFormat,
    m: &mut OnlineMove<R, D>,
    paths: &mut [Path<N, D, PIECES>; 2],
) -> Result<u32, Error>
where
    N: Kernel,
    N::Out: OutBits,
    R: Real,
{
    let mut limits = [AxisLimits::new(R::ONE, R::ONE, R::ONE)?; D];
    for (l, &[v, a, j]) in limits.iter_mut().zip(&job.limits) {
        *l = AxisLimits::new(R::lit(v), R::lit(a), R::lit(j))?;
    }
    defmt::println!(
        "J {=str} {=str} online {=usize}",
        job.name,
        format.name(),
        D
    );
    let first = options(job, &job.target, false);
    m.solve_in_place(
        &states(&job.start),
        &states(&job.target.states),
        &limits,
        &first,
    )?;
    let [mut current, mut spare] = paths.each_mut();
    compile_move_into(m, current)?;
    let mut sampler = Sampler::new(&*current);
    let mut events = job.events.iter().peekable();
    let mut k: u32 = 0;
    let mut last: Option<Sample<N::Out, D>> = None;
    loop {
        if let (Some(&&(tick, event)), Some(prev)) = (events.peek(), last.as_ref())
            && tick == u64::from(k)
        {
            events.next();
            let (target, stop) = match event {
                MoveEvent::Target(t) => (t, false),
                MoveEvent::Stop => (
                    MoveTarget {
                        states: [[0.0; 3]; D],
                        position: false,
                    },
                    true,
                ),
            };
            let options = options(job, &target, stop);
            take_over_into(prev, &states(&target.states), &limits, &options, m, spare)?;
            core::mem::swap(&mut current, &mut spare);
            sampler = Sampler::new(&*current);
            // Its first sample is the one just played.
            let _ = sampler.next();
        }
        // The end of the last move, or of a move that ends moving (as on the host).
        let moving = last
            .as_ref()
            .is_some_and(|l| l.velocity.iter().any(|v| v.to_f64() != 0.0));
        if sampler.is_finished() && (events.peek().is_none() || moving) {
            break;
        }
        let s = sampler.next();
        log_sample(k, &s);
        last = Some(s);
        k = k.wrapping_add(1);
    }
    defmt::println!("E {=str} {=str} online {=u32}", job.name, format.name(), k);
    Ok(k)
}
