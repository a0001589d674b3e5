//! Instructions per tick under QEMU `-icount` (**instruction counts, not cycles**): for every
//! tick of a whole path — piece switches and the final tick included — the instructions of
//! one `Sampler::next()` (and of one `Sampler::next_position()`, and of one
//! `Sampler::next_into()` into a sample in the accumulator's format) call, and for comparison the
//! instructions of one direct evaluation of a cubic curve (de Boor, Horner).
//!
//! On the Cortex-M4F (`thumbv7em-none-eabihf`, `mps2-an386`) the cases are in `f32`; on the
//! Cortex-M3 (`thumbv7m-none-eabi`, `mps2-an385`) in fixed-point (playback `Q40`, curves
//! `I32F32`). The paths (1, 3 and 6 axes) are compiled on the device at start-up from a cubic
//! B-spline of 10 de Boor points under a quintic rest-to-rest time law, 0.25 s at 10 kHz
//! (2 501 samples, several pieces each).
//!
//! Then the online solver: the host benchmark's random 3-axis moves, each solved in place
//! (`strak_qemu::online`), in `f32` and `f64`; on the Cortex-M4F also their first step alone
//! in `f32` (each axis's time-optimal motion and feasible durations, `solve_axis`), which
//! splits a solve's count between that step and the synchronization.
//!
//! Before measuring, it checks every tick kernel entry point against the portable kernel, bit
//! for bit, on random states of 1 to 8 axes (`strak_qemu::kernel_check`), the solver's `f32`
//! square root against the software one (`strak_qemu::online::check_root`), and the sampler's
//! entry points against each other over the measured paths, in RAM and from blobs
//! (`strak_qemu::sampler_check`): a difference is logged and fails the run.
//!
//! # Output protocol (defmt, read by `cargo xtask qemu`)
//! ```text
//! SAMPLER <ticks>                                the sampler's entry points agreed, bit for
//!                                                bit, over <ticks> ticks
//! CAL <empty> <nops> <nop64>                     calibration: SysTick counts of an empty
//!                                                measurement and of 256 nops; 64 nops
//!                                                measured again, in instructions
//! I <case> <min> <median> <max> <calls> <worst>  instructions per call over <calls> calls;
//!                                                <worst>: the index of the first call at max
//! O <case> <moves> <sum>                         an online case: <moves> moves solved, the
//!                                                sum of their durations' bits (wrapping)
//! DONE <cases>
//! ```

#![no_std]
#![no_main]
#![deny(unsafe_code)]

use core::hint::black_box;

use cortex_m_rt::{ExceptionFrame, entry, exception};
use strak_curves::basis::MonomialCurve;
use strak_curves::{BSpline, ParamCurve, Point, Scalar};
use strak_qemu::counter::{Calibration, Counter, WideCounter};
use strak_qemu::online::{self, cases::OnlineCase};
use strak_qemu::{exit_failure, exit_success, sampler_check};
use strak_trajectory::{
    AlignedBlob, Along, CompileOptions, Kernel, Path, PathBlob, Sample, Sampler, Timing, compile,
};

/// Control rate of the measured paths.
const RATE_HZ: f64 = 10_000.0;
/// Duration of the measured paths: 2 500 ticks, 2 501 samples.
const DURATION: f64 = 0.25;
/// Room for the counts of one case.
const MAX_CALLS: usize = 4_096;
/// Path capacity.
const PIECES: usize = 128;
/// Direct evaluations per case (at `k / EVALS`, `k = 0 ..= EVALS`).
const EVALS: usize = 1_000;
/// Online moves solved for the gated case (`f32` on the Cortex-M4F).
const ONLINE_CASES: usize = 10_000;
/// Online moves solved for the reported cases (`f64`, and every format on the Cortex-M3,
/// in software floating point): fewer, to keep the QEMU run short.
const ONLINE_OTHER: usize = 2_000;
/// Room for the blob of a measured path (at most [`PIECES`] pieces of 6 axes in `Q40`).
const BLOB_BYTES: usize = 64 * 1024;

/// Rest to rest: `u = 10s³ − 15s⁴ + 6s⁵`, `s = t / duration`.
struct Quintic(f64);

impl Timing for Quintic {
    fn duration(&self) -> f64 {
        self.0
    }
    fn param(&self, t: f64) -> (f64, f64) {
        let s = t.clamp(0.0, self.0) / self.0;
        let u = s * s * s * (10.0 + s * (-15.0 + 6.0 * s));
        let du = 30.0 * s * s * (1.0 - s) * (1.0 - s) / self.0;
        (u, du)
    }
}

/// A wiggly profile (units) the axes take shifted and scaled copies of.
const PROFILE: [f64; 10] = [0.0, 8.0, -3.0, 12.0, 5.0, 20.0, 9.0, 2.0, 15.0, 11.0];

/// The `D`-axis cubic clamped uniform B-spline of the measured paths, in `S`.
fn bspline<S: Scalar, const D: usize>() -> Option<BSpline<[S; D], 16, 24>>
where
    [S; D]: Point<Scalar = S>,
{
    let mut points = [[S::ZERO; D]; 10];
    for (i, p) in points.iter_mut().enumerate() {
        for (a, x) in p.iter_mut().enumerate() {
            let v = PROFILE.get((i + 3 * a) % PROFILE.len()).copied()? * (1.0 + 0.25 * a as f64);
            *x = S::from_f64(v)?;
        }
    }
    BSpline::clamped_uniform(3, &points, S::ZERO, S::ONE).ok()
}

/// One tick: one `next()` call, as a tick handler makes it.
#[inline(never)]
fn tick<N: Kernel, const A: usize>(s: &mut Sampler<'_, N, A>) -> Sample<N::Out, A> {
    s.next()
}

/// One tick in the accumulator's format, written in place (`next_into`).
#[inline(never)]
fn tick_into<N: Kernel, const A: usize>(s: &mut Sampler<'_, N, A>, out: &mut Sample<N::Native, A>) {
    s.next_into(out);
}

/// One tick, positions only.
#[inline(never)]
fn tick_position<N: Kernel, const A: usize>(s: &mut Sampler<'_, N, A>) -> [N::Out; A] {
    s.next_position()
}

/// min, median (the lower middle), max and the first index at max of `counts`; sorts it.
fn stats(counts: &mut [u32]) -> (u32, u32, u32, usize) {
    let max = counts.iter().copied().max().unwrap_or(0);
    let worst = counts.iter().position(|&c| c == max).unwrap_or(0);
    counts.sort_unstable();
    let min = counts.first().copied().unwrap_or(0);
    let median = counts
        .get(counts.len().saturating_sub(1) / 2)
        .copied()
        .unwrap_or(0);
    (min, median, max, worst)
}

fn report(name: &str, counts: &mut [u32]) {
    let n = counts.len();
    let (min, median, max, worst) = stats(counts);
    defmt::println!(
        "I {=str} {=u32} {=u32} {=u32} {=usize} {=usize}",
        name,
        min,
        median,
        max,
        n,
        worst
    );
}

/// The measured `A`-axis path in `N`, compiled on the device (fails the run if it does not
/// compile into several pieces).
fn measured_path<N: Kernel, const A: usize>(name: &str) -> Path<N, A, PIECES> {
    let Some(curve) = bspline::<f64, A>() else {
        defmt::error!("{=str}: the B-spline does not build", name);
        exit_failure()
    };
    let path: Path<N, A, PIECES> = match compile(
        &Along::new(&curve, &Quintic(DURATION)),
        RATE_HZ,
        &CompileOptions::new(),
    ) {
        Ok(p) => p,
        Err(e) => {
            defmt::error!("{=str}: compiling failed: {}", name, e);
            exit_failure()
        }
    };
    if path.pieces().len() < 4 {
        defmt::error!("{=str}: only {=usize} pieces", name, path.pieces().len());
        exit_failure()
    }
    path
}

/// Checks the sampler's entry points against each other on the measured `A`-axis path in
/// `N` (`strak_qemu::sampler_check`), in RAM and read from a blob at an aligned and at an
/// odd address; a difference fails the run. Returns the ticks compared.
#[inline(never)]
fn check_sampler<N: Kernel, const A: usize>(name: &str) -> u32 {
    let path = measured_path::<N, A>(name);
    let mut buf = AlignedBlob([0_u8; BLOB_BYTES + 1]);
    let mut ticks = 0;
    for (source, at) in [
        ("RAM", None),
        ("aligned blob", Some(0)),
        ("odd blob", Some(1)),
    ] {
        let result = match at {
            None => sampler_check::check(path.view()),
            Some(at) => {
                let bytes = buf.0.get_mut(at..).unwrap_or(&mut []);
                let Ok(len) = path.to_bytes(bytes) else {
                    defmt::error!("{=str}: the blob does not fit", name);
                    exit_failure()
                };
                match PathBlob::<N, A>::from_bytes(buf.0.get(at..at + len).unwrap_or(&[])) {
                    Ok(blob) => sampler_check::check(blob.view()),
                    Err(e) => {
                        defmt::error!("{=str}: the blob does not load: {}", name, e);
                        exit_failure()
                    }
                }
            }
        };
        match result {
            Ok(n) => ticks += n,
            Err(entry) => {
                defmt::error!(
                    "{=str} ({=str}): {=str} differs from next(), bit for bit",
                    name,
                    source,
                    entry
                );
                exit_failure()
            }
        }
    }
    ticks
}

/// Plays the `A`-axis path in `N` to its end, counting every call of `f`.
#[inline(never)]
fn playback<N: Kernel, const A: usize, R>(
    name: &str,
    counter: &Counter,
    cal: &Calibration,
    mut f: impl FnMut(&mut Sampler<'_, N, A>) -> R,
) {
    let path = measured_path::<N, A>(name);
    let mut sampler = Sampler::new(&path);
    let mut counts = [0_u32; MAX_CALLS];
    let mut n = 0;
    for slot in counts.iter_mut() {
        let s = black_box(&mut sampler);
        let (c, out) = counter.counts(|| black_box(f(s)));
        *slot = cal.instructions(c);
        drop(black_box(out));
        n += 1;
        if sampler.is_finished() {
            break;
        }
    }
    if !sampler.is_finished() || n != path.ticks() as usize + 1 {
        defmt::error!("{=str}: {=usize} calls, the path did not end", name, n);
        exit_failure()
    }
    report(name, counts.get_mut(..n).unwrap_or(&mut []));
}

/// Evaluates `f` at `k / EVALS` for `k = 0 ..= EVALS`, counting every call.
#[inline(never)]
fn direct<S: Scalar, R>(name: &str, counter: &Counter, cal: &Calibration, f: impl Fn(S) -> R) {
    let mut counts = [0_u32; EVALS + 1];
    for (k, slot) in counts.iter_mut().enumerate() {
        let Some(u) = S::from_f64(k as f64 / EVALS as f64) else {
            exit_failure()
        };
        let u = black_box(u);
        let (c, out) = counter.counts(|| black_box(f(u)));
        drop(black_box(out));
        *slot = cal.instructions(c);
    }
    report(name, &mut counts);
}

#[inline(never)]
fn eval_bspline<S: Scalar>(c: &BSpline<[S; 3], 16, 24>, u: S) -> [S; 3]
where
    [S; 3]: Point<Scalar = S>,
{
    c.eval(u)
}

#[inline(never)]
fn eval_monomial<S: Scalar>(c: &MonomialCurve<[S; 3], 4>, u: S) -> [S; 3]
where
    [S; 3]: Point<Scalar = S>,
{
    c.eval(u)
}

/// The direct-evaluation cases in `S`: de Boor on the 3-axis B-spline, Horner on one cubic.
fn direct_cases<S: Scalar>(names: [&str; 2], counter: &Counter, cal: &Calibration)
where
    [S; 3]: Point<Scalar = S>,
{
    let Some(spline) = bspline::<S, 3>() else {
        defmt::error!("{=str}: the B-spline does not build", names[0]);
        exit_failure()
    };
    let spline = black_box(spline);
    direct(names[0], counter, cal, |u: S| eval_bspline(&spline, u));
    let q = |x: f64| S::from_f64(x).unwrap_or(S::ZERO);
    let coeffs = [
        [q(1.0), q(-2.0), q(0.5)],
        [q(3.0), q(1.5), q(-1.0)],
        [q(-2.0), q(0.25), q(4.0)],
        [q(0.75), q(-1.25), q(2.0)],
    ];
    let Ok(cubic) = MonomialCurve::new(coeffs) else {
        defmt::error!("{=str}: the cubic does not build", names[1]);
        exit_failure()
    };
    let cubic = black_box(cubic);
    direct(names[1], counter, cal, |u: S| eval_monomial(&cubic, u));
}

#[entry]
fn main() -> ! {
    let Some(p) = cortex_m::Peripherals::take() else {
        exit_failure()
    };
    if let Err(m) = strak_qemu::kernel_check::check() {
        defmt::error!(
            "the {=str} tick kernels differ from the portable kernel: {=usize} axes, {=str}, random state {=u32}",
            m.format,
            m.axes,
            m.entry,
            m.state
        );
        exit_failure()
    }
    if let Err(bits) = online::check_root() {
        defmt::error!(
            "the solver's f32 square root differs from the software one at {=u32:#x}",
            bits
        );
        exit_failure()
    }
    let mut compared = 0;
    #[cfg(target_abi = "eabihf")]
    {
        compared += check_sampler::<f32, 1>("playback-f32-1axis");
        compared += check_sampler::<f32, 3>("playback-f32-3axis");
        compared += check_sampler::<f32, 6>("playback-f32-6axis");
    }
    #[cfg(not(target_abi = "eabihf"))]
    {
        use strak_trajectory::Q40;
        compared += check_sampler::<Q40, 1>("playback-q40-1axis");
        compared += check_sampler::<Q40, 3>("playback-q40-3axis");
        compared += check_sampler::<Q40, 6>("playback-q40-6axis");
    }
    defmt::println!("SAMPLER {=u32}", compared);
    let counter = Counter::start(p.SYST);
    let cal = Calibration::measure(&counter);
    let check = cal.check_nop64(&counter);
    defmt::println!("CAL {=u32} {=u32} {=u32}", cal.empty, cal.nops, check);
    let mut cases: u32 = 0;
    macro_rules! play {
        ($n:ty, $a:literal, $full:literal, $pos:literal, $into:literal) => {
            playback::<$n, $a, _>($full, &counter, &cal, |s| tick(s));
            playback::<$n, $a, _>($pos, &counter, &cal, |s| tick_position(s));
            let mut out = Sample::splat(<$n as Kernel>::NATIVE_ZERO);
            playback::<$n, $a, _>($into, &counter, &cal, |s| tick_into(s, &mut out));
            cases += 3;
        };
    }
    #[cfg(target_abi = "eabihf")]
    {
        play!(
            f32,
            1,
            "playback-f32-1axis",
            "playback-f32-1axis-position",
            "playback-f32-1axis-into"
        );
        play!(
            f32,
            3,
            "playback-f32-3axis",
            "playback-f32-3axis-position",
            "playback-f32-3axis-into"
        );
        play!(
            f32,
            6,
            "playback-f32-6axis",
            "playback-f32-6axis-position",
            "playback-f32-6axis-into"
        );
        direct_cases::<f32>(["deboor-f32-3d", "horner-f32-3d"], &counter, &cal);
        cases += 2;
    }
    #[cfg(not(target_abi = "eabihf"))]
    {
        use strak_curves::I32F32;
        use strak_trajectory::Q40;
        play!(
            Q40,
            1,
            "playback-q40-1axis",
            "playback-q40-1axis-position",
            "playback-q40-1axis-into"
        );
        play!(
            Q40,
            3,
            "playback-q40-3axis",
            "playback-q40-3axis-position",
            "playback-q40-3axis-into"
        );
        play!(
            Q40,
            6,
            "playback-q40-6axis",
            "playback-q40-6axis-position",
            "playback-q40-6axis-into"
        );
        direct_cases::<I32F32>(["deboor-i32f32-3d", "horner-i32f32-3d"], &counter, &cal);
        cases += 2;
    }
    let counter = WideCounter::start(counter.stop());
    let cal = counter.calibrate();
    #[cfg(target_abi = "eabihf")]
    let solves = [
        ("online-f32-3axis", ONLINE_CASES),
        ("online-f64-3axis", ONLINE_OTHER),
    ];
    #[cfg(not(target_abi = "eabihf"))]
    let solves = [
        ("online-f32-3axis", ONLINE_OTHER),
        ("online-f64-3axis", ONLINE_OTHER),
    ];
    let mut counts = [0_u32; ONLINE_CASES];
    for (name, n) in solves {
        let counts = counts.get_mut(..n).unwrap_or(&mut []);
        let solved = if name.contains("f32") {
            online::count_solves::<f32>(&counter, &cal, OnlineCase::in_f32, counts)
        } else {
            online::count_solves::<f64>(&counter, &cal, |c| Some(*c), counts)
        };
        match solved {
            Ok(bits) => defmt::println!("O {=str} {=usize} {=u64}", name, n, bits),
            Err(i) => {
                defmt::error!("{=str}: move {=usize} did not solve", name, i);
                exit_failure()
            }
        }
        report(name, counts);
        cases += 1;
    }
    // The first step alone (each axis solved on its own), in `f32` on the FPU.
    #[cfg(target_abi = "eabihf")]
    {
        let counts = counts.get_mut(..ONLINE_CASES).unwrap_or(&mut []);
        let name = "online-f32-3axis-step1";
        if let Err(i) = online::count_axis_solves::<f32>(&counter, &cal, OnlineCase::in_f32, counts)
        {
            defmt::error!("{=str}: move {=usize} did not solve", name, i);
            exit_failure()
        }
        report(name, counts);
        cases += 1;
    }
    // The feed guard: a hold scheduled at every 25th tick of the pick-and-place path.
    #[cfg(target_abi = "eabihf")]
    {
        let name = "guard-hold-f32-3axis";
        let mut holds = [0_u32; 128];
        match strak_qemu::guard::count_holds(&counter, &cal, &mut holds) {
            Ok((n, delays)) => {
                defmt::println!("G {=str} {=usize} {=u64}", name, n, delays);
                report(name, holds.get_mut(..n).unwrap_or(&mut []));
            }
            Err(why) => {
                defmt::error!("{=str}: {=str}", name, why);
                exit_failure()
            }
        }
        cases += 1;
    }
    defmt::println!("DONE {=u32}", cases);
    exit_success()
}

/// Counts SysTick's wraps for [`WideCounter`] (the online solves).
#[exception]
fn SysTick() {
    WideCounter::on_wrap();
}

/// A fault is logged and fails the run.
#[allow(unsafe_code)]
#[exception]
unsafe fn HardFault(frame: &ExceptionFrame) -> ! {
    defmt::error!("hard fault at pc {=u32:#x}", frame.pc());
    exit_failure()
}
