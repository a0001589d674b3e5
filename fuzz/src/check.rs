//! Playing a path in full and checking what playback promises: finite samples, the exact
//! end, an end that agrees with the last piece, and the kinematic limits measured from the
//! samples by finite differences.

use strak_curves::Scalar;
use strak_trajectory::{END_AGREEMENT_SLACK, Kernel, Number, Path, Sample, Sampler};

use crate::{Violation, violation};

/// The pipeline and job harnesses play only plans of at most this many ticks (larger ones
/// are skipped after planning), so that one execution stays within milliseconds.
pub const MAX_TICKS: f64 = 20_000.0;

/// The most samples one playback takes (feed changes stretch a motion).
pub const MAX_SAMPLES: u64 = 200_000;

/// A feed event, applied before the sample of its tick.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FeedEvent {
    /// [`Sampler::set_feed`].
    Feed(f32),
    /// [`Sampler::hold`].
    Hold,
    /// [`Sampler::resume`].
    Resume,
    /// [`Sampler::scale_feed_ramp`] (what a feed guard puts before an event).
    RampScale(u8),
}

/// The samples of one playback, in `f64`.
#[derive(Clone, Debug)]
pub struct Played<const A: usize> {
    /// Every sample, the first at tick 0.
    pub samples: Vec<Sample<f64, A>>,
    /// `true` when the sampler finished within [`MAX_SAMPLES`].
    pub finished: bool,
}

fn to_f64<T: Scalar, const A: usize>(s: &Sample<T, A>) -> Sample<f64, A> {
    Sample {
        tick: s.tick,
        position: s.position.map(Scalar::to_f64),
        velocity: s.velocity.map(Scalar::to_f64),
        acceleration: s.acceleration.map(Scalar::to_f64),
    }
}

fn finite<T: Scalar, const A: usize>(s: &Sample<T, A>) -> bool {
    s.position
        .iter()
        .chain(&s.velocity)
        .chain(&s.acceleration)
        .all(|v| v.is_finite())
}

fn apply<N: Kernel, const A: usize>(sampler: &mut Sampler<'_, N, A>, event: FeedEvent) {
    match event {
        FeedEvent::Feed(f) => sampler.set_feed(f),
        FeedEvent::Hold => sampler.hold(),
        FeedEvent::Resume => sampler.resume(),
        FeedEvent::RampScale(shift) => {
            sampler.scale_feed_ramp(shift);
        }
    }
}

/// Plays `path` with the feed `events` (sorted by tick) until it finishes or after
/// `max_samples` samples. Checks every sample's tick and finiteness; at the end, the exact
/// end position (and, without events, the exact end velocity and acceleration and the
/// sample count `ticks + 1`), then one standstill sample at the end.
///
/// # Errors
/// The first broken invariant.
pub fn play<N: Kernel, const A: usize, const P: usize>(
    path: &Path<N, A, P>,
    events: &[(u64, FeedEvent)],
    max_samples: u64,
) -> Result<Played<A>, Violation> {
    let mut sampler = Sampler::new(path);
    let mut samples = Vec::new();
    let mut pending = events.iter().peekable();
    let mut last = None;
    for k in 0..max_samples {
        while let Some((_, e)) = pending.next_if(|(t, _)| *t <= k) {
            apply(&mut sampler, *e);
        }
        let s = sampler.next();
        if s.tick != k {
            return Err(violation!("sample {k} carries tick {}", s.tick));
        }
        if !finite(&s) {
            return Err(violation!("sample at tick {k} is not finite: {s:?}"));
        }
        samples.push(to_f64(&s));
        last = Some(s);
        if sampler.is_finished() {
            break;
        }
    }
    let finished = sampler.is_finished();
    if let (true, Some(last)) = (finished, last) {
        check_end(path, &mut sampler, &last, events.is_empty())?;
    } else if events.is_empty() {
        return Err(violation!(
            "not finished after {} samples for a path of {} ticks",
            samples.len(),
            path.ticks()
        ));
    }
    Ok(Played { samples, finished })
}

fn check_end<N: Kernel, const A: usize, const P: usize>(
    path: &Path<N, A, P>,
    sampler: &mut Sampler<'_, N, A>,
    last: &Sample<N::Out, A>,
    feed_one: bool,
) -> Result<(), Violation> {
    if last.position != path.end_position() {
        return Err(violation!(
            "last sample {:?} at tick {} is not the end point {:?}",
            last.position,
            last.tick,
            path.end_position()
        ));
    }
    if feed_one {
        if last.tick != u64::from(path.ticks()) {
            return Err(violation!(
                "finished at tick {} on a path of {} ticks",
                last.tick,
                path.ticks()
            ));
        }
        if last.velocity != path.end_velocity() || last.acceleration != path.end_acceleration() {
            return Err(violation!(
                "end sample v {:?}, a {:?} differ from the path's end v {:?}, a {:?}",
                last.velocity,
                last.acceleration,
                path.end_velocity(),
                path.end_acceleration()
            ));
        }
    }
    let rest = sampler.next();
    let zero = <N::Out as Scalar>::ZERO;
    if rest.position != path.end_position()
        || rest
            .velocity
            .iter()
            .chain(&rest.acceleration)
            .any(|v| *v != zero)
    {
        return Err(violation!(
            "after the end the sampler does not stand still at the end: {rest:?}"
        ));
    }
    Ok(())
}

/// The position of the last piece at its last tick, in `f64` from the stored states
/// (Newton's forward-difference formula: `p(n) = p + n·Δ¹ + C(n,2)·Δ² + C(n,3)·Δ³`).
/// With each axis's position comes the sum of the terms' magnitudes, which bounds the f64
/// rounding of the sum.
pub fn last_piece_end<N: Number, const A: usize, const P: usize>(
    path: &Path<N, A, P>,
) -> Option<[(f64, f64); A]> {
    let piece = path.pieces().last()?;
    let n = f64::from(piece.ticks());
    let (c2, c3) = (n * (n - 1.0) / 2.0, n * (n - 1.0) * (n - 2.0) / 6.0);
    Some(piece.axes().map(|s| {
        let terms = [
            s.position.to_f64(),
            n * s.delta1.to_f64(),
            c2 * s.delta2.to_f64(),
            c3 * s.delta3.to_f64(),
        ];
        (terms.iter().sum(), terms.iter().map(|t| t.abs()).sum())
    }))
}

/// The end position agrees with the last piece: `|p(n) − x_end| ≤ tolerance + 2·bound` plus
/// four units of the sample format's resolution at the end's magnitude and the documented
/// slack for the f64 rounding of the fit and of the sum `p(n)`
/// ([`END_AGREEMENT_SLACK`] times `1 +` its terms' magnitudes): a compiled path's last piece
/// ends on the curve's end within its tolerance and playback bound.
///
/// # Errors
/// The axis and the gap when they disagree.
pub fn check_end_agrees<N: Number, const A: usize, const P: usize>(
    path: &Path<N, A, P>,
) -> Result<(), Violation> {
    let Some(end) = last_piece_end(path) else {
        return Err(violation!("a loaded path without pieces"));
    };
    for (i, ((p, terms), x)) in end.iter().zip(path.end_position()).enumerate() {
        let x = x.to_f64();
        let allowed = path.tolerance()
            + 2.0 * path.playback_bound()
            + 4.0 * resolution::<N>(x.abs().max(p.abs()))
            + END_AGREEMENT_SLACK * (1.0 + terms.max(x.abs()));
        let gap = (p - x).abs();
        if !(gap <= allowed) {
            return Err(violation!(
                "axis {i}: the end position {x} is {gap:e} from the last piece's end {p} \
                 (allowed {allowed:e}: tolerance {:e}, playback bound {:e})",
                path.tolerance(),
                path.playback_bound()
            ));
        }
    }
    Ok(())
}

/// The resolution of the sample format at magnitude `m`: `ε·m` for floats, the fixed-point
/// step for `Q40` samples (`I32F32`, 2⁻³²).
pub fn resolution<N: Number>(m: f64) -> f64 {
    let eps = <N::Out as Scalar>::EPSILON;
    if <N::Out as Scalar>::IS_FIXED {
        eps
    } else {
        eps * m
    }
}

/// What the samples of a planned motion must keep.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds<const A: usize> {
    /// The speed `|ẋ|`.
    pub velocity: f64,
    /// The acceleration: its norm `|ẍ|`, or only its tangential part when `tangential`.
    pub acceleration: f64,
    /// The jerk vector `|x⃛|` (`None`: not limited, as for trapezoids).
    pub jerk: Option<f64>,
    /// Per axis `|ẋᵢ|` (`∞`: none).
    pub axis_velocity: [f64; A],
    /// Per axis `|ẍᵢ|` (`∞`: none).
    pub axis_acceleration: [f64; A],
    /// Only the tangential acceleration `d|ẋ|/dt = ẍ·ẋ/|ẋ|` is limited
    /// ([`PathTiming::trapezoid`](strak_trajectory::PathTiming::trapezoid): no curvature
    /// limits), measured as `(|ẋ_{k+1}| − |ẋ_k|)/T` from the sampled velocities: its mean
    /// over the tick, exactly. (The mean of `ẍ` projected on the direction at the tick's
    /// start is not the tangential acceleration: it adds the centripetal part times the
    /// turn within the tick, `|ẍ_n|·θ/2`.)
    pub tangential: bool,
}

/// The allowance of the finite differences over the limits, per measured quantity.
///
/// A difference quotient over one tick, `(c_{k+1} − c_k)/T`, is the mean of the channel's
/// derivative over the tick (the compiled motion is one cubic between two ticks, and the
/// sampled velocity and acceleration are the exact derivatives of the sampled position's
/// cubic), and the norm of a mean is at most the largest norm inside the tick: the
/// differences add nothing upward but rounding. So the allowance is rounding only:
///
/// * `1e-6` of the limit: the `f64` arithmetic of the planner and of the differences;
/// * `(4 + 2·n)·u/T` with `u` the resolution of the channel's sample format at its largest
///   magnitude ([`resolution`]) and `n` the longest piece in ticks: two samples rounded
///   once each, and the drift of forward differencing that a piece switch resets (one
///   rounding per addition per tick, at most `n` of them);
/// * for velocities also `2·b/T`, `b` the path's playback bound (the position error a piece
///   switch resets).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Allowance {
    /// For the velocities (differences of positions).
    pub velocity: f64,
    /// For the accelerations (differences of velocities).
    pub acceleration: f64,
    /// For the jerk (differences of accelerations).
    pub jerk: f64,
}

/// The relative allowance of the limits (the `f64` arithmetic).
pub const RELATIVE: f64 = 1e-6;

impl Allowance {
    /// The allowance for the samples of `path` (see the type's docs).
    pub fn of<N: Number, const A: usize, const P: usize>(
        path: &Path<N, A, P>,
        samples: &[Sample<f64, A>],
    ) -> Self {
        let largest = |f: fn(&Sample<f64, A>) -> [f64; A]| {
            samples
                .iter()
                .flat_map(f)
                .fold(0.0_f64, |m, v| m.max(v.abs()))
        };
        let n = path.pieces().iter().map(|p| p.ticks()).max().unwrap_or(1);
        let steps = 4.0 + 2.0 * f64::from(n);
        let rate = path.rate();
        let per = |m: f64| steps * resolution::<N>(m) * rate;
        Allowance {
            velocity: per(largest(|s| s.position)) + 2.0 * path.playback_bound() * rate,
            acceleration: per(largest(|s| s.velocity)),
            jerk: per(largest(|s| s.acceleration)),
        }
    }
}

/// The worst excess of one quantity over its limit.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Excess {
    quantity: &'static str,
    tick: u64,
    value: f64,
    limit: f64,
    allowance: f64,
}

impl Excess {
    fn ratio(&self) -> f64 {
        self.value / self.limit - 1.0
    }
}

/// The Euclidean norm, scaled by the largest magnitude so that the squares cannot overflow
/// (a jerk near 10¹⁵⁶ would square to infinity).
fn norm(v: impl Iterator<Item = f64> + Clone) -> f64 {
    let m = v.clone().fold(0.0_f64, |m, x| m.max(x.abs()));
    if m == 0.0 || !m.is_finite() {
        return m;
    }
    m * v.map(|x| (x / m) * (x / m)).sum::<f64>().sqrt()
}

/// Collects the excesses of the quantities at one tick pair.
struct Meter {
    worst: Vec<Excess>,
}

impl Meter {
    fn measure(
        &mut self,
        quantity: &'static str,
        tick: u64,
        value: f64,
        limit: f64,
        allowance: f64,
    ) {
        if !(value <= limit * (1.0 + RELATIVE) + allowance) {
            let e = Excess {
                quantity,
                tick,
                value,
                limit,
                allowance,
            };
            match self.worst.iter_mut().find(|w| w.quantity == quantity) {
                Some(w) if e.ratio() > w.ratio() || e.value.is_nan() => *w = e,
                Some(_) => {}
                None => self.worst.push(e),
            }
        }
    }
}

/// Checks `bounds` in `samples` by finite differences (rate `rate`) with `allow`.
///
/// # Errors
/// The quantities over their limits, worst relative excess first, each with its tick.
pub fn check_limits<const A: usize>(
    samples: &[Sample<f64, A>],
    rate: f64,
    bounds: &Bounds<A>,
    allow: &Allowance,
) -> Result<(), Violation> {
    let mut m = Meter { worst: Vec::new() };
    for w in samples.windows(2) {
        let (s, t) = (&w[0], &w[1]);
        let k = s.tick;
        let d = |f: fn(&Sample<f64, A>) -> [f64; A], i: usize| (f(t)[i] - f(s)[i]) * rate;
        let dx: [f64; A] = core::array::from_fn(|i| d(|s| s.position, i));
        let dv: [f64; A] = core::array::from_fn(|i| d(|s| s.velocity, i));
        let da: [f64; A] = core::array::from_fn(|i| d(|s| s.acceleration, i));
        m.measure(
            "speed |v|",
            k,
            norm(dx.into_iter()),
            bounds.velocity,
            allow.velocity,
        );
        let acc = if bounds.tangential {
            ((norm(t.velocity.into_iter()) - norm(s.velocity.into_iter())) * rate).abs()
        } else {
            norm(dv.into_iter())
        };
        m.measure(
            if bounds.tangential {
                "tangential acceleration d|v|/dt"
            } else {
                "acceleration |a|"
            },
            k,
            acc,
            bounds.acceleration,
            allow.acceleration,
        );
        if let Some(j) = bounds.jerk {
            m.measure("jerk |j|", k, norm(da.into_iter()), j, allow.jerk);
        }
        for i in 0..A {
            m.measure(
                "axis velocity",
                k,
                dx[i].abs(),
                bounds.axis_velocity[i],
                allow.velocity,
            );
            m.measure(
                "axis acceleration",
                k,
                dv[i].abs(),
                bounds.axis_acceleration[i],
                allow.acceleration,
            );
        }
    }
    if m.worst.is_empty() {
        return Ok(());
    }
    m.worst.sort_by(|a, b| b.ratio().total_cmp(&a.ratio()));
    let text: Vec<String> = m
        .worst
        .iter()
        .map(|e| {
            format!(
                "{} {:.6e} at tick {} exceeds the limit {:.6e} by {:+.3} % (allowance {:.3e})",
                e.quantity,
                e.value,
                e.tick,
                e.limit,
                100.0 * e.ratio(),
                e.allowance
            )
        })
        .collect();
    Err(violation!("limits exceeded: {}", text.join("; ")))
}
