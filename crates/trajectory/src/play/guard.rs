//! The feed guard: when, and how slowly, a feed change can ramp on a path planned at the full
//! limits, found by playing it ahead on a copy of the sampler.
//!
//! Played with the feed factor `φ`, the motion is `ẍ = φ²·p″ + φ̇·p′` and
//! `x⃛ = φ³·p‴ + 3·φ·φ̇·p″ + φ̈·p′` (see [`CompileOptions`](crate::CompileOptions)): a ramp
//! adds `φ̇·p′` and `3·φ·φ̇·p″ + φ̈·p′`, and takes back `(1 − φ²)·p″` and `(1 − φ³)·p‴`. On a
//! path that leaves none of the limits free this fits where the motion does not use them
//! all (a cruise, a constant acceleration with jerk to spare, a slower stretch) and not
//! where it does (braking at the limit). The guard tries delays `d` (every tick up to 16,
//! then growing by an eighth) and, for each, ramps slowed by `2⁻ˢ` (`s = 0 ..= max_shift`;
//! see [`Sampler::scale_feed_ramp`]); for each candidate it plays a copy of the sampler until
//! the ramp has ended and checks every sample as a run's samples are checked: `|v|`, `|a|`
//! (path norms and per axis) and the finite differences `|Δx|·f`, `|Δv|·f`, `|Δa|·f`
//! against the limits, allowing [`LIMIT_CHECK_RELATIVE`] and
//! [`NumberFormat::difference_allowance`] (`√A` times that for a norm) at the larger
//! magnitude of the two samples for their rounding. The first candidate that passes is the schedule. Every
//! candidate's ramp is checked to its end, so a later change is checked from the state this
//! one leaves, and the motion after a ramp is the plan's at a constant feed (within the
//! limits). The work is bounded: at most [`MAX_DELAY`] ticks of delay, `max_shift + 1`
//! ramps of at most [`MAX_RAMP_TICKS`] ticks for each of about 110 delays, a sampler tick and
//! one check each; cheap on a host, and on a device a job for the main loop, not the
//! interrupt.

use super::events::{Event, Playable};
use super::{Kernel, Sampler, SamplerState};
use crate::num::{LIMIT_CHECK_RELATIVE, NumberFormat};
use crate::path::Sample;
use crate::plan::Limits;

/// The longest delay the guard tries, in ticks.
pub const MAX_DELAY: u32 = 1 << 20;

/// The longest ramp the guard plays ahead, in ticks; a candidate whose ramp is longer fails.
pub const MAX_RAMP_TICKS: u32 = 1 << 18;

/// When and how slowly a feed change ramps: [`FeedGuard::schedule`]'s answer.
///
/// ```
/// use strak_trajectory::Schedule;
/// let s = Schedule { delay: 3, shift: Some(1) };
/// assert_eq!(s.delay, 3);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Schedule {
    /// Ticks to wait: the change applies before the sample `delay` ticks after the one it
    /// was asked before.
    pub delay: u32,
    /// The ramp's slow-down [`Event::RampScale`] to apply just before it; `None` while an
    /// earlier ramp still runs (its scale stays).
    pub shift: Option<u8>,
}

/// Checks feed changes on a path planned without a feed reserve (see the module docs):
/// [`schedule`](Self::schedule) finds when and how slowly a change can ramp within the
/// machine's limits.
///
/// ```
/// use strak_curves::Bezier;
/// use strak_trajectory::{
///     CompileOptions, Event, FeedGuard, Limits, Path, PathTiming, PlanOptions, Sampler,
/// };
/// let line = Bezier::new([[0.0_f64, 0.0], [100.0, 50.0]])?;
/// let limits = Limits::<2>::new(200.0, 2_000.0, 50_000.0)?;
/// // planned at the full limits: nothing held back for feed changes
/// let options = PlanOptions::new().with_feed_share(0.0);
/// let timing = PathTiming::<_, 64, 16>::plan(&line, &limits, &options)?;
/// let path: Path<f64, 2, 256> = timing.compile(&CompileOptions::new())?;
/// assert_eq!(path.feed_share(), 0.0);
/// let mut sampler = Sampler::new(&path);
/// let mut last = sampler.next();
/// for _ in 0..150 {
///     last = sampler.next(); // accelerating at the limits
/// }
/// let guard = FeedGuard::new(&limits);
/// let when = guard.schedule(&sampler, Some(&last), Event::Hold).unwrap();
/// assert!(when.delay < 1_000);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FeedGuard<const A: usize> {
    velocity: f64,
    acceleration: f64,
    jerk: f64,
    axis_velocity: [f64; A],
    axis_acceleration: [f64; A],
    /// `√A`: a norm's allowance in multiples of one axis's.
    root_axes: f64,
    max_shift: u8,
}

impl<const A: usize> FeedGuard<A> {
    /// The default largest slow-down of a ramp: `2⁻³`.
    pub const DEFAULT_MAX_SHIFT: u8 = 3;

    /// A guard of `limits` (path and per axis); the differences are taken at the rate of the
    /// path each sampler plays.
    pub fn new(limits: &Limits<A>) -> Self {
        FeedGuard {
            velocity: limits.velocity(),
            acceleration: limits.acceleration(),
            jerk: limits.jerk(),
            axis_velocity: limits.axis_velocity(),
            axis_acceleration: limits.axis_acceleration(),
            #[allow(clippy::cast_precision_loss)]
            root_axes: libm::sqrt(A as f64),
            max_shift: Self::DEFAULT_MAX_SHIFT,
        }
    }

    /// Without the jerk check (for a motion not planned under the jerk, such as a
    /// trapezoid).
    ///
    /// ```
    /// use strak_trajectory::{FeedGuard, Limits};
    /// let g = FeedGuard::new(&Limits::<1>::new(1.0, 1.0, 1.0)?).without_jerk();
    /// assert_ne!(g, FeedGuard::new(&Limits::<1>::new(1.0, 1.0, 1.0)?));
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub const fn without_jerk(mut self) -> Self {
        self.jerk = f64::INFINITY;
        self
    }

    /// The largest slow-down `2⁻ˢʰⁱᶠᵗ` of a ramp the guard tries (default
    /// [`DEFAULT_MAX_SHIFT`](Self::DEFAULT_MAX_SHIFT)).
    ///
    /// ```
    /// use strak_trajectory::{FeedGuard, Limits};
    /// let g = FeedGuard::new(&Limits::<1>::new(1.0, 1.0, 1.0)?).with_max_shift(0);
    /// assert_eq!(g.max_shift(), 0);
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub const fn with_max_shift(mut self, shift: u8) -> Self {
        self.max_shift = shift;
        self
    }

    /// The largest slow-down tried.
    pub const fn max_shift(&self) -> u8 {
        self.max_shift
    }

    /// When and how slowly `event` can apply to `sampler` (whose last sample was `last`,
    /// `None` before the first) so that every sample keeps the limits; `None` when no delay
    /// up to [`MAX_DELAY`] ticks or the end of the motion and no slow-down up to
    /// `2⁻ᵐᵃˣ_ˢʰⁱᶠᵗ` does (while held at rest, when none does now: waiting changes nothing). An event that starts no ramp (a resume while not held, a feed
    /// change while held) applies at once. Apply [`Schedule::shift`] as an
    /// [`Event::RampScale`] and then `event` before the sample `delay` ticks on.
    pub fn schedule<N: Kernel>(
        &self,
        sampler: &Sampler<'_, N, A>,
        last: Option<&Sample<N::Out, A>>,
        event: Event,
    ) -> Option<Schedule> {
        if matches!(event, Event::RampScale(_)) {
            return Some(Schedule {
                delay: 0,
                shift: None,
            });
        }
        let mut base = sampler.clone();
        let mut prev = last.copied();
        let mut delay = 0_u32;
        loop {
            if let Some(shift) = self.first_passing(&base, prev.as_ref(), event) {
                return Some(Schedule { delay, shift });
            }
            // Held at rest, every later tick is this one: waiting changes nothing.
            let resting =
                base.state() == SamplerState::Holding && base.feed() == 0.0 && !base.is_ramping();
            if base.is_finished() || resting || delay >= MAX_DELAY {
                return None;
            }
            let next = if delay < 16 {
                delay + 1
            } else {
                delay + delay / 8
            };
            while delay < next && !base.is_finished() {
                prev = Some(base.next());
                delay += 1;
            }
        }
    }

    /// The first slow-down with which `event` passes now (`Some(None)`: with the running
    /// ramp's).
    #[allow(clippy::option_option)]
    fn first_passing<N: Kernel>(
        &self,
        base: &Sampler<'_, N, A>,
        prev: Option<&Sample<N::Out, A>>,
        event: Event,
    ) -> Option<Option<u8>> {
        if base.is_ramping() {
            return self.passes(base, prev, event, None).then_some(None);
        }
        (0..=self.max_shift)
            .find(|&shift| self.passes(base, prev, event, Some(shift)))
            .map(Some)
    }

    /// Plays `event` (after the slow-down `shift`) on a copy of `base` until its ramp has
    /// ended; `true` when every sample keeps the limits.
    fn passes<N: Kernel>(
        &self,
        base: &Sampler<'_, N, A>,
        prev: Option<&Sample<N::Out, A>>,
        event: Event,
        shift: Option<u8>,
    ) -> bool {
        let mut s = base.clone();
        if let Some(shift) = shift
            && !s.scale_feed_ramp(shift)
        {
            return false;
        }
        s.apply(event);
        let rate = s.path().header().rate();
        let mut prev = prev.map(to_f64::<N, A>);
        for _ in 0..MAX_RAMP_TICKS {
            let ramping = s.is_ramping();
            let sample = to_f64::<N, A>(&s.next());
            if !self.keeps(prev.as_ref(), &sample, N::FORMAT, rate) {
                return false;
            }
            // The sample after the ramp's end is checked too: its jump in φ̇ is in it.
            if !ramping || s.is_finished() {
                return true;
            }
            prev = Some(sample);
        }
        false
    }

    /// `true` when `s` (after `p`, one tick of a path at `rate` earlier) keeps the limits, as
    /// the module docs say.
    fn keeps(
        &self,
        p: Option<&Kinematics<A>>,
        s: &Kinematics<A>,
        format: NumberFormat,
        rate: f64,
    ) -> bool {
        let within =
            |x: f64, limit: f64, slack: f64| x <= limit * (1.0 + LIMIT_CHECK_RELATIVE) + slack;
        let norms =
            within(norm(&s.v), self.velocity, 0.0) && within(norm(&s.a), self.acceleration, 0.0);
        let per_axis = (0..A).all(|i| {
            within(s.v[i].abs(), self.axis_velocity[i], 0.0)
                && within(s.a[i].abs(), self.axis_acceleration[i], 0.0)
        });
        let Some(p) = p else {
            return norms && per_axis;
        };
        let f = rate;
        let slack = |a: &[f64; A], b: &[f64; A]| {
            format.difference_allowance(magnitude(a).max(magnitude(b)), f)
        };
        let diff = |a: &[f64; A], b: &[f64; A]| {
            let mut d = [0.0; A];
            for ((d, x), y) in d.iter_mut().zip(a).zip(b) {
                *d = (x - y) * f;
            }
            d
        };
        let (dx, dv, da) = (diff(&s.x, &p.x), diff(&s.v, &p.v), diff(&s.a, &p.a));
        let (sx, sv, sa) = (slack(&s.x, &p.x), slack(&s.v, &p.v), slack(&s.a, &p.a));
        let axes = self.root_axes;
        let differences = within(norm(&dx), self.velocity, sx * axes)
            && within(norm(&dv), self.acceleration, sv * axes)
            && within(norm(&da), self.jerk, sa * axes)
            && (0..A).all(|i| {
                within(dx[i].abs(), self.axis_velocity[i], sx)
                    && within(dv[i].abs(), self.axis_acceleration[i], sv)
            });
        norms && per_axis && differences
    }
}

/// A sample in `f64`.
struct Kinematics<const A: usize> {
    x: [f64; A],
    v: [f64; A],
    a: [f64; A],
}

fn to_f64<N: Kernel, const A: usize>(s: &Sample<N::Out, A>) -> Kinematics<A> {
    let f = |v: &[N::Out; A]| v.map(|x| N::from_out(x).to_f64());
    Kinematics {
        x: f(&s.position),
        v: f(&s.velocity),
        a: f(&s.acceleration),
    }
}

fn norm<const A: usize>(v: &[f64; A]) -> f64 {
    libm::sqrt(v.iter().map(|x| x * x).sum())
}

fn magnitude<const A: usize>(v: &[f64; A]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}
