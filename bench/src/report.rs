//! The generator of `BENCHMARKS.md`: reads criterion's results
//! (`target/criterion/**/new/{benchmark,estimates}.json`), the optional Cortex-M counts
//! (`target/qemu/counts.json`) and firmware sizes (`target/qemu/sizes.json`), and writes the
//! tables, the ratios to each peer and the verdict on each target of issue 5.
//!
//! # The Cortex-M files (written by the QEMU runs)
//! `counts.json`: a JSON list of `{"name": str, "min": int, "median": int, "max": int,
//! "budget": int | null}` (instructions per tick over a whole path; `budget` from the
//! checked-in budget file). `sizes.json`: a JSON list of `{"name": str, "text": int,
//! "data": int, "bss": int}` (bytes). Either file may be missing: the section then says
//! "not measured in this run".

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, anyhow};
use serde::Deserialize;

use crate::fixture::{RATE_HZ, SIZES, TABLE_LEN, TOLERANCE_MM};

/// Playback must be at least this many times faster per sample than the fastest peer's
/// evaluation of the same curve.
pub const PLAYBACK_TARGET: f64 = 20.0;
/// Random-access evaluation must be at least this many times faster than the fastest peer.
pub const EVAL_TARGET: f64 = 3.0;
/// The per-tick playback cost may vary by at most this fraction from 8 to 8192 points.
pub const FLATNESS_TARGET: f64 = 0.20;

/// The command that runs the benchmarks.
pub const BENCH_COMMAND: &str = "cargo bench -p strak-bench --bench peers";
/// The command that writes `BENCHMARKS.md` from their results.
pub const REPORT_COMMAND: &str = "cargo run --release -p strak-bench --bin report";

/// One criterion benchmark: its id and the median time per element.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurement {
    /// Criterion's group id (`eval_even`, `playback`, `flatness_f32`, …).
    pub group: String,
    /// The function id (`strak_f32`, `bspline_f64`, `middle`, …).
    pub function: String,
    /// The parameter (the control-point count), if any.
    pub value: Option<String>,
    /// Median time of one iteration divided by the throughput's elements, in ns.
    pub ns: f64,
}

#[derive(Deserialize)]
struct BenchmarkJson {
    group_id: String,
    function_id: Option<String>,
    value_str: Option<String>,
    throughput: Option<ThroughputJson>,
}

#[derive(Deserialize)]
enum ThroughputJson {
    Elements(u64),
    Bytes(serde::de::IgnoredAny),
    BytesDecimal(serde::de::IgnoredAny),
    ElementsAndBytes { elements: u64 },
}

#[derive(Deserialize)]
struct Estimate {
    point_estimate: f64,
}

#[derive(Deserialize)]
struct EstimatesJson {
    median: Estimate,
}

/// One line of `counts.json`.
#[derive(Clone, Debug, Deserialize, PartialEq)]
pub struct QemuCount {
    /// What was counted (e.g. `m4f_f32_3axis_position`).
    pub name: String,
    /// Fewest instructions of a tick.
    pub min: u64,
    /// Median over the ticks.
    pub median: u64,
    /// Most instructions of a tick.
    pub max: u64,
    /// The checked-in budget of the median, if any.
    pub budget: Option<u64>,
    /// The checked-in budget of the worst tick, if any.
    #[serde(default)]
    pub budget_max: Option<u64>,
}

/// The Cortex-M targets of issue 5: (description, counted run, limit of its median;
/// `None`: the worst tick ≤ 1.5 × the median).
pub const CORTEX_M_TARGETS: [(&str, &str, Option<u64>); 5] = [
    (
        "Cortex-M4F, 3-axis f32, position only: median ≤ 40",
        "playback-f32-3axis-position",
        Some(40),
    ),
    (
        "Cortex-M4F, 3-axis f32, position, velocity, acceleration: median ≤ 72",
        "playback-f32-3axis",
        Some(72),
    ),
    (
        "Cortex-M4F, 3-axis f32: worst tick ≤ 1.5 × median",
        "playback-f32-3axis",
        None,
    ),
    (
        "Cortex-M3, 3-axis fixed-point (Q40), position only: median ≤ 60",
        "playback-q40-3axis-position",
        Some(60),
    ),
    (
        "Cortex-M3, 3-axis fixed-point (Q40), position, velocity, acceleration (`next_into`, the sample in the accumulator's format): median ≤ 110",
        "playback-q40-3axis-into",
        Some(110),
    ),
];

/// The Cortex-M target checks from the instruction counts (a target whose run is missing
/// is left out).
pub fn cortex_m_checks(counts: &[QemuCount]) -> Vec<Check> {
    CORTEX_M_TARGETS
        .iter()
        .filter_map(|&(what, run, limit)| {
            let c = counts.iter().find(|c| c.name == run)?;
            let (value, met) = match limit {
                Some(l) => (c.median as f64, c.median <= l),
                None => {
                    let ratio = c.max as f64 / c.median.max(1) as f64;
                    (ratio, 2 * c.max <= 3 * c.median)
                }
            };
            Some(Check {
                what: what.to_string(),
                value,
                met,
            })
        })
        .collect()
}

/// One line of `sizes.json`.
#[derive(Clone, Debug, Deserialize, PartialEq)]
pub struct FirmwareSize {
    /// The firmware image.
    pub name: String,
    /// Code and read-only data (bytes).
    pub text: u64,
    /// Initialized data (bytes).
    pub data: u64,
    /// Zero-initialized data (bytes).
    pub bss: u64,
}

/// Every `new/benchmark.json` (with its `estimates.json`) below `dir`, sorted by id.
///
/// # Errors
/// When `dir` cannot be read or a file is malformed.
pub fn read_criterion(dir: &Path) -> Result<Vec<Measurement>> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let entries = fs::read_dir(&d).with_context(|| format!("reading {}", d.display()))?;
        for e in entries {
            let p = e?.path();
            if p.is_dir() {
                if p.file_name().is_some_and(|n| n == "new") {
                    if p.join("benchmark.json").is_file() {
                        out.push(read_one(&p)?);
                    }
                } else {
                    stack.push(p);
                }
            }
        }
    }
    out.sort_by(|a, b| (&a.group, &a.function, &a.value).cmp(&(&b.group, &b.function, &b.value)));
    Ok(out)
}

fn read_one(new_dir: &Path) -> Result<Measurement> {
    let read = |name: &str| -> Result<String> {
        let p = new_dir.join(name);
        fs::read_to_string(&p).with_context(|| format!("reading {}", p.display()))
    };
    let b: BenchmarkJson = serde_json::from_str(&read("benchmark.json")?)
        .with_context(|| format!("parsing {}/benchmark.json", new_dir.display()))?;
    let e: EstimatesJson = serde_json::from_str(&read("estimates.json")?)
        .with_context(|| format!("parsing {}/estimates.json", new_dir.display()))?;
    let elements = match b.throughput {
        Some(
            ThroughputJson::Elements(n) | ThroughputJson::ElementsAndBytes { elements: n, .. },
        ) => n.max(1),
        Some(ThroughputJson::Bytes(_) | ThroughputJson::BytesDecimal(_)) | None => 1,
    };
    // `bench_function("name/param")` stores the parameter inside the function id.
    let function = b.function_id.unwrap_or_default();
    let (function, value) = match (b.value_str, function.rsplit_once('/')) {
        (Some(v), _) => (function, Some(v)),
        (None, Some((f, v))) => (f.to_string(), Some(v.to_string())),
        (None, None) => (function, None),
    };
    Ok(Measurement {
        group: b.group_id,
        function,
        value,
        ns: e.median.point_estimate / elements as f64,
    })
}

/// The measurements by `(group, function, value)`.
#[derive(Clone, Debug, Default)]
pub struct Results {
    map: BTreeMap<(String, String, String), f64>,
}

impl Results {
    /// Indexes `ms`.
    pub fn new(ms: &[Measurement]) -> Self {
        let map = ms
            .iter()
            .map(|m| {
                let key = (
                    m.group.clone(),
                    m.function.clone(),
                    m.value.clone().unwrap_or_default(),
                );
                (key, m.ns)
            })
            .collect();
        Results { map }
    }

    /// ns per element of `group/function/value` (`value` empty for none).
    pub fn get(&self, group: &str, function: &str, value: &str) -> Option<f64> {
        self.map
            .get(&(group.to_string(), function.to_string(), value.to_string()))
            .copied()
    }

    /// ns per sample of a random-access evaluation.
    pub fn eval(&self, pattern: Pattern, function: &str, n: usize) -> Option<f64> {
        self.get(pattern.group(), function, &n.to_string())
    }

    /// ns per tick of playback in `format` (`f32`, `f64`, `q40`).
    pub fn playback(&self, format: &str, n: usize) -> Option<f64> {
        self.get("playback", &format!("strak_{format}"), &n.to_string())
    }

    /// ns per sample of batch playback (`Sampler::fill`) in `format`.
    pub fn fill(&self, format: &str, n: usize) -> Option<f64> {
        self.get("fill", &format!("strak_{format}"), &n.to_string())
    }

    /// ns per sample of batch playback of positions (`Sampler::fill_positions`) in `format`.
    pub fn fill_positions(&self, format: &str, n: usize) -> Option<f64> {
        self.get("fill_positions", &format!("strak_{format}"), &n.to_string())
    }
}

/// The batch rows: `fill` and `fill_positions` per format and `n`, and the positions' speed-up
/// against the fastest same-curve peer (nothing when neither group was measured).
fn batch_table(o: &mut String, r: &Results) {
    if SIZES
        .iter()
        .all(|&n| r.fill("f64", n).is_none() && r.fill_positions("f64", n).is_none())
    {
        return;
    }
    let _ = writeln!(
        o,
        "### Batch playback (ns per sample)\n\n\
         `fill`: whole samples (position, velocity, acceleration), bit for bit `next()`'s; \
         `positions`: `fill_positions`, bit for bit `next_position()`'s, the peers' job.\n\n\
         | n | fill f32 | fill f64 | fill Q40 | positions f32 | positions f64 | positions Q40 | \
         speed-up f32 (positions) | speed-up f64 (positions) |\n\
         |---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    for n in SIZES {
        let peer =
            |precision| fastest_peer(r, &Pattern::ALL, precision, n, |p| p.same_curve).map(|p| p.0);
        let _ = writeln!(
            o,
            "| {n} | {} | {} | {} | {} | {} | {} | {} | {} |",
            ns(r.fill("f32", n)),
            ns(r.fill("f64", n)),
            ns(r.fill("q40", n)),
            ns(r.fill_positions("f32", n)),
            ns(r.fill_positions("f64", n)),
            ns(r.fill_positions("q40", n)),
            ratio(r.fill_positions("f32", n), peer("f32")),
            ratio(r.fill_positions("f64", n), peer("f64")),
        );
    }
    let _ = writeln!(o);
}

/// Why the host speed targets are missed: the analysis behind the numbers (disassembly of
/// the bench binary, `objdump -d`), printed when a host speed target is not met.
const MISSED: &str = "## Why host speed targets are missed (analysis)

Evidence from the disassembly of the bench binary (`objdump -d --no-show-raw-insn -C \
target/release/deps/peers-*`) and from the flatness benches above:

- **Random-access evaluation (3×).** strak has two evaluators. `BSpline::eval` is de
  Boor's algorithm: 6 knot-ratio divisions `α = (u − u_i)/(u_{i+4−r} − u_i)` and 6 convex
  combinations per sample (`divsd`/`divss` × 6), the exact evaluator that compiled paths and
  the firmware bit-identity check depend on (it must stay bit for bit as it is); enterpolation
  and bspline run the same algorithm, so it leads them by 1.3–3× only. `PowerSpline::eval`
  (the `strak power` columns) is the same B-spline converted once into per-span power-basis
  polynomials in the normalised parameter `t = (u − u_s)·r_s`: an O(1) span guess for
  uniform knots (one multiplication, a float→int conversion, at most one correction against
  the stored span start/end, all in one record), then Horner (3 multiplications and 3
  additions per coordinate), no division. The verdict uses the faster of the two per
  precision. Where it is still short of 3× the remaining cost is the fixed per-sample work
  (clamping `u`, the index conversion, the bounds-checked record load) against splines'
  Catmull-Rom at small n, which is a different curve with no de Boor step at all.
- **Playback (20×).** An ordinary tick is one counter test and the format's tick kernel:
  per axis the sample values and six additions (`p += Δ¹, Δ¹ += Δ², Δ² += Δ³, v += Δv¹,
  Δv¹ += Δv², a += Δa`), the state read from and written back to the sampler. The floor
  table above measures that step alone on a state kept in memory, with nothing of the sampler
  around it: the playback tick is within a small factor of it, and the floor itself is
  several times longer than the 20× target allows. What sets the floor is the chain
  `p(k+1) = p(k) + Δ¹(k)`: each tick's addition needs the previous tick's result, which a
  per-call sampler must store and reload between calls (store-to-load forwarding plus the
  addition's latency, a dozen or more cycles per tick), whereas a peer's random-access
  evaluation has no dependency between samples and overlaps consecutive calls. Meeting 20×
  would need a tick without that chain (e.g. evaluating each tick's polynomial from a tick
  counter, which costs more instructions on the Cortex-M, where the instruction targets are
  met) or a batch interface that keeps the state in registers over many ticks (`fill` and
  `fill_positions`, below).
- **Batch playback (`Sampler::fill` and `Sampler::fill_positions`, the batch rows).** The
  batch calls keep the chains of a piece in locals across its ticks, with the same additions
  in the same order (the samples are `next()`'s and `next_position()`'s, bit for bit).
  Instructions per sample under `valgrind --tool=callgrind` (`src/bin/ticks.rs`, n = 1024,
  3 axes, whole path 20 times; repeatable, unlike the times on a shared machine): `next()`
  f32 75.5, f64 80.5, Q40 100.5; `fill` 33.2, 31.6, 92.8; `fill_positions` 15.1, 15.9,
  26.9. `fill_positions` does the peers' job, positions only: 9 additions per tick, which
  the compiler groups by difference order into vector additions (f32: the x–y pair in one
  `addps`, z in an `addss`), 3 stores, and a piece switch every 18 ticks of this path on
  average (3 593 pieces in 65 672 ticks). Each tick still waits for the previous tick's
  additions (one add latency per tick), which bounds it at about 3 cycles.
  What keeps `fill` short of 20×, from the listing of its loop (x86-64 baseline, SSE2, so
  at most 16 bytes per store and 2 doubles or 4 floats per addition). An f64 tick is 23
  instructions: 6 stores (the 80-byte sample: the tick, and position, velocity and
  acceleration of 3 axes), 10 additions (8 `addpd`, 2 `addsd` for the 18 additions of the
  chains), 3 register moves and 4 of loop control. An f32 tick is 25: 4 stores, 5 `addps`,
  and 12 shuffles and moves, because the compiler packs the values in the order the sample
  stores them (position x, y, z, velocity x, …), which puts different difference orders in
  one register and reorders them every tick. The other 8–9 instructions per sample are paid
  once per run of ticks, at every piece switch: the state is gathered from its per-axis
  records into per-order registers and written back (about 100 instructions), and the
  switch tick is `next()`. 20× asks for a half to two thirds of today's time per sample
  (the worst case is f64 at small n; runs on a shared machine differ by that much).
  Holding the chains as levels in the sample's order instead (`[p, v, a]`,
  `[Δp, Δv, Δa]`, …, the missing differences of the velocity and acceleration padded with
  −0.0, whose addition changes no bit) cuts the f32 tick to 17 instructions (26.4 per
  sample) but measured no faster beyond the noise of a loaded machine, and costs f64 14 %
  and Q40 36 % more instructions (more values than registers), so `fill` keeps its
  per-order chains. Fewer, wider stores need 32-byte registers (AVX), which the x86-64
  baseline does not have: runtime detection and `unsafe` code in the trajectory crate for
  a host-only call. Q40 `fill` is 86 instructions per tick: 27 `i64` chain values against
  16 general registers, so about 36 of them are spill stores and reloads, besides the 18
  additions, 10 stores and 18 instructions (`lea`, `sar`) of the rounding to `I32F32`.
- **Flatness across n**: the work of a tick does not depend on n (no search; the same
  additions; one piece load per at most 256 ticks, and the piece density along the path is
  the same for every n). The spread over n measured in one run is therefore timing noise
  of the machine (see the load average above; on a shared 2-core machine the same bench
  varies by 10–30 % between runs); read it together with the one-tick table.
";

const CORTEX_M_MISSED: &str = "### A Cortex-M target is missed

The ordinary tick is a hand-scheduled kernel (`vldm`/`vstm` per axis in f32; `ldm`/`stm` and
`adds`/`adc` pairs in Q40), so a miss is read from the listing: the instruction-by-instruction
accounting of each entry point is in firmware-sim/qemu/ICOUNT.md.
";

/// Where the evaluation parameters lie.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pattern {
    /// Evenly spaced over the domain.
    Even,
    /// Pseudo-random (a fixed table).
    Random,
}

impl Pattern {
    /// Both patterns.
    pub const ALL: [Pattern; 2] = [Pattern::Even, Pattern::Random];

    /// The criterion group.
    pub fn group(self) -> &'static str {
        match self {
            Pattern::Even => "eval_even",
            Pattern::Random => "eval_random",
        }
    }

    fn label(self) -> &'static str {
        match self {
            Pattern::Even => "evenly spaced",
            Pattern::Random => "random",
        }
    }
}

/// A peer evaluating a curve: its benchmark function prefix and what it computes.
#[derive(Clone, Copy, Debug)]
pub struct Peer {
    /// Function id prefix (followed by `_f32` / `_f64`).
    pub id: &'static str,
    /// Table heading.
    pub label: &'static str,
    /// `true` when it does the same job: a 3-D curve through/for the same points with a span
    /// search (the targets compare against these); `false` for kurbo's single 2-D Bézier.
    pub same_job: bool,
    /// `true` when it evaluates the same B-spline (enterpolation, bspline).
    pub same_curve: bool,
}

/// The peers measured.
pub const PEERS: [Peer; 4] = [
    Peer {
        id: "enterpolation",
        label: "enterpolation 0.3 (B-spline)",
        same_job: true,
        same_curve: true,
    },
    Peer {
        id: "bspline",
        label: "bspline 1.1 (B-spline)",
        same_job: true,
        same_curve: true,
    },
    Peer {
        id: "splines_catmull_rom",
        label: "splines 5 (Catmull-Rom, same points: a different curve, same cost class)",
        same_job: true,
        same_curve: false,
    },
    Peer {
        id: "kurbo_cubicbez",
        label: "kurbo 0.13 (one 2-D cubic Bézier, no span search: a lower bound, f64 only)",
        same_job: false,
        same_curve: false,
    },
];

/// The fastest evaluation (ns) of `precision` among the peers selected by `pick`, over the
/// given patterns, with the peer's id.
pub fn fastest_peer(
    r: &Results,
    patterns: &[Pattern],
    precision: &str,
    n: usize,
    pick: impl Fn(&Peer) -> bool,
) -> Option<(f64, &'static str)> {
    let mut best: Option<(f64, &'static str)> = None;
    for p in PEERS.iter().filter(|p| pick(p)) {
        for &pat in patterns {
            if let Some(t) = r.eval(pat, &format!("{}_{precision}", p.id), n)
                && best.is_none_or(|(b, _)| t < b)
            {
                best = Some((t, p.id));
            }
        }
    }
    best
}

/// One checked comparison of a target.
#[derive(Clone, Debug, PartialEq)]
pub struct Check {
    /// What was compared.
    pub what: String,
    /// The measured factor (speed-up, or spread for flatness).
    pub value: f64,
    /// Whether it meets the target.
    pub met: bool,
}

/// strak's random-access evaluators of the same B-spline, as function id prefixes (followed
/// by `_<format>`): de Boor (`BSpline::eval`) and the power basis (`PowerSpline::eval`).
pub const STRAK_EVALUATORS: [&str; 2] = ["strak", "strak_power"];

/// strak's fastest random-access evaluator of `precision` (`f32`, `f64`, …) for `pattern`
/// and `n`: its time and its function id (`strak_f32`, `strak_power_f32`, …).
pub fn fastest_strak(
    r: &Results,
    pattern: Pattern,
    precision: &str,
    n: usize,
) -> Option<(f64, String)> {
    let mut best: Option<(f64, String)> = None;
    for prefix in STRAK_EVALUATORS {
        let id = format!("{prefix}_{precision}");
        if let Some(t) = r.eval(pattern, &id, n)
            && best.as_ref().is_none_or(|(b, _)| t < *b)
        {
            best = Some((t, id));
        }
    }
    best
}

/// Random-access evaluation: strak's fastest evaluator of each precision (`f32`/`f64`; de
/// Boor or power basis, see [`fastest_strak`]) against the fastest same-job peer of the same
/// precision, per pattern and `n`; met when strak is at least [`EVAL_TARGET`]× faster.
pub fn eval_checks(r: &Results) -> Vec<Check> {
    let mut out = Vec::new();
    for pat in Pattern::ALL {
        for precision in ["f32", "f64"] {
            for n in SIZES {
                let (Some((s, strak)), Some((p, id))) = (
                    fastest_strak(r, pat, precision, n),
                    fastest_peer(r, &[pat], precision, n, |p| p.same_job),
                ) else {
                    continue;
                };
                let speedup = p / s;
                out.push(Check {
                    what: format!("{} {precision} n = {n} ({strak} vs {id})", pat.label()),
                    value: speedup,
                    met: speedup >= EVAL_TARGET,
                });
            }
        }
    }
    out
}

/// Playback: strak's per-tick cost against the fastest evaluation of the same curve by a
/// peer (enterpolation, bspline; either pattern), per precision and `n`; met when playback
/// is at least [`PLAYBACK_TARGET`]× faster.
pub fn playback_checks(r: &Results) -> Vec<Check> {
    speed_checks(r, Results::playback)
}

/// Batch playback (`Sampler::fill`): as [`playback_checks`], per sample.
pub fn fill_checks(r: &Results) -> Vec<Check> {
    speed_checks(r, Results::fill)
}

/// Batch playback of positions (`Sampler::fill_positions`), the peers' own job: as
/// [`playback_checks`], per sample.
pub fn fill_positions_checks(r: &Results) -> Vec<Check> {
    speed_checks(r, Results::fill_positions)
}

/// `time(r, precision, n)` against the fastest same-curve peer, per precision and `n`.
fn speed_checks(r: &Results, time: fn(&Results, &str, usize) -> Option<f64>) -> Vec<Check> {
    let mut out = Vec::new();
    for precision in ["f32", "f64"] {
        for n in SIZES {
            let (Some(s), Some((p, id))) = (
                time(r, precision, n),
                fastest_peer(r, &Pattern::ALL, precision, n, |p| p.same_curve),
            ) else {
                continue;
            };
            let speedup = p / s;
            out.push(Check {
                what: format!("{precision} n = {n} (vs {id})"),
                value: speedup,
                met: speedup >= PLAYBACK_TARGET,
            });
        }
    }
    out
}

/// The online solver's targets: at least this many times faster than the faster peer on
/// the mean of a random 3-axis synchronized move.
pub const ONLINE_TARGET: f64 = 5.0;
/// …and its slowest case at most this many times its median case.
pub const ONLINE_SPREAD_TARGET: f64 = 3.0;

/// The online solver against Ruckig and rsruckig (speed-up on the mean, strak f64 and f32),
/// and strak's slowest case against its median.
pub fn online_checks(r: &Results) -> Vec<Check> {
    let mut out = Vec::new();
    let peers = ["ruckig", "rsruckig"]
        .into_iter()
        .filter_map(|p| r.get("online", p, "").map(|t| (t, p)));
    let fastest = peers.min_by(|a, b| a.0.total_cmp(&b.0));
    for format in ["f64", "f32"] {
        if let (Some(s), Some((p, id))) = (r.get("online", &format!("strak_{format}"), ""), fastest)
        {
            let speedup = p / s;
            out.push(Check {
                what: format!("strak {format} vs {id} (mean)"),
                value: speedup,
                met: speedup >= ONLINE_TARGET,
            });
        }
    }
    if let (Some(median), Some(worst)) = (
        r.get("online_case", "median", ""),
        r.get("online_case", "worst", ""),
    ) {
        let spread = worst / median;
        out.push(Check {
            what: "strak f64 slowest case / median case".to_owned(),
            value: spread,
            met: spread <= ONLINE_SPREAD_TARGET,
        });
    }
    out
}

/// Why the online solver misses its speed target (from the profile of a random 3-axis
/// move under callgrind).
const ONLINE_MISSED: &str = "Where the time of a random 3-axis synchronized move goes \
(callgrind on `src/bin/solves.rs`, the first 2 000 moves: about 27 400 x86-64 instructions per move in f32, 30 100 in f64): 60 \
% is the time-optimal search of each axis (both directions, five forms each: the closed form \
with a cruise, three quartics and a quadratic, each root isolated on its interval and \
checked by integrating the seven phases); 38 % is the motion of the common duration for the \
two axes that are not the slowest (the farthest motions in either direction, 23 %, and their \
blend, 14 %). Across both steps the root finding takes 25 %, the integration that checks \
each candidate profile 25 %, and writing the profiles 7 %. The search narrows each quartic's \
interval to the roots whose profile can keep its acceleration limits and non-negative holds \
before it isolates any root: of the 32 700 quartic forms tried on the first 2 000 moves only \
659 yield a profile (the cruise form gives 4 762 of the 6 064 profiles), and the narrowing \
cut the instructions by a fifth. Of the 17 781 quartics solved for these moves in f32, \
8 561 pass the quick test that the polynomial cannot vanish on its interval, and only \
1 666 roots are found in them: most isolations find the derivative's roots only to find no \
sign change. Ruckig does the same search, with closed-form quartic roots, and stops at the \
first profile in more cases. What would close more of the gap: closed-form roots of the \
quartics (Ferrari) polished by one Newton step instead of isolation, or a sign test of the \
quartic's Bernstein coefficients on its interval before any isolation (no sign change: no \
root); end positions of the common-duration forms in closed form instead of integrating \
each; and solving the common duration only where the slowest axis's gaps allow.";

/// The online section: peers' and strak's mean time per move, the checks.
fn online_section(o: &mut String, r: &Results) {
    let checks = online_checks(r);
    if checks.is_empty() {
        return;
    }
    let _ = writeln!(o, "## Online moves (issue 11)\n");
    let _ = writeln!(
        o,
        "One time-synchronized move of 3 axes from a random state (velocity and acceleration \
         inside the limits) to a random target (with velocity and acceleration), mean over \
         the same 1 000 moves for every solver (`online`), and strak's median and slowest of \
         them solved alone (`online_case`).\n"
    );
    let _ = writeln!(o, "| solver | time per move (ns) |\n|---|---:|");
    for (id, label) in [
        ("strak_f64", "strak, f64"),
        ("strak_f32", "strak, f32"),
        ("ruckig", "Ruckig (C++, `ruckig` crate)"),
        ("rsruckig", "rsruckig"),
    ] {
        let _ = writeln!(o, "| {label} | {} |", ns(r.get("online", id, "")));
    }
    for (id, label) in [
        ("median", "strak f64, median case"),
        ("worst", "strak f64, slowest case"),
    ] {
        let _ = writeln!(o, "| {label} | {} |", ns(r.get("online_case", id, "")));
    }
    let _ = writeln!(o, "\n| target | value | verdict |\n|---|---:|---|");
    for c in &checks {
        let target = if c.what.contains("median") {
            format!("≤ {ONLINE_SPREAD_TARGET}×")
        } else {
            format!("≥ {ONLINE_TARGET}×")
        };
        let _ = writeln!(
            o,
            "| {} ({target}) | {:.2}× | {} |",
            c.what,
            c.value,
            if c.met { "met" } else { "not met" }
        );
    }
    let _ = writeln!(o);
    if checks.iter().any(|c| !c.met) {
        let _ = writeln!(o, "{ONLINE_MISSED}\n");
    }
}

/// Flatness over `n`: per format, `max/min − 1` of the per-tick playback cost over the
/// sizes; met when at most [`FLATNESS_TARGET`].
pub fn flatness_checks(r: &Results) -> Vec<Check> {
    let mut out = Vec::new();
    for format in ["f32", "f64", "q40"] {
        let ts: Vec<f64> = SIZES
            .iter()
            .filter_map(|&n| r.playback(format, n))
            .collect();
        if ts.len() < 2 {
            continue;
        }
        let lo = ts.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = ts.iter().copied().fold(0.0, f64::max);
        let spread = hi / lo - 1.0;
        out.push(Check {
            what: format!("{format}: n = 8 … 8192"),
            value: spread,
            met: spread <= FLATNESS_TARGET,
        });
    }
    out
}

/// The machine the run was on.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Machine {
    /// CPU model name.
    pub cpu: String,
    /// Logical cores available.
    pub cores: usize,
    /// Operating system and kernel.
    pub os: String,
    /// `rustc -V`.
    pub rustc: String,
    /// The 1-minute load average at report time (others may have shared the cores).
    pub load: String,
}

impl Machine {
    /// Reads `/proc/cpuinfo`, `/etc/os-release`, `/proc/sys/kernel/osrelease`,
    /// `/proc/loadavg` and runs `rustc -V` (each "unknown" when not available).
    pub fn detect() -> Self {
        let read = |p: &str| fs::read_to_string(p).unwrap_or_default();
        let cpu = read("/proc/cpuinfo")
            .lines()
            .find(|l| l.starts_with("model name"))
            .and_then(|l| l.split(':').nth(1))
            .map_or_else(|| "unknown".to_string(), |s| s.trim().to_string());
        let os_name = read("/etc/os-release")
            .lines()
            .find_map(|l| l.strip_prefix("PRETTY_NAME="))
            .map_or_else(
                || std::env::consts::OS.to_string(),
                |s| s.trim_matches('"').to_string(),
            );
        let kernel = read("/proc/sys/kernel/osrelease").trim().to_string();
        let rustc = std::process::Command::new(std::env::var("RUSTC").unwrap_or("rustc".into()))
            .arg("-V")
            .output()
            .ok()
            .map_or_else(
                || "unknown".to_string(),
                |o| String::from_utf8_lossy(&o.stdout).trim().to_string(),
            );
        Machine {
            cpu,
            cores: std::thread::available_parallelism().map_or(0, usize::from),
            os: format!("{os_name}, Linux {kernel} ({})", std::env::consts::ARCH),
            rustc,
            load: read("/proc/loadavg")
                .split_whitespace()
                .next()
                .unwrap_or("unknown")
                .to_string(),
        }
    }
}

/// The host speed targets' worst cases in one run: the smallest speed-up of each.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HostRun {
    /// The processor (`model name` of `/proc/cpuinfo`).
    pub cpu: &'static str,
    /// The commit measured.
    pub commit: &'static str,
    /// Fixed-rate playback (`next()`).
    pub playback: f64,
    /// Batch playback (`fill`).
    pub fill: f64,
    /// Batch playback of positions (`fill_positions`).
    pub fill_positions: f64,
    /// Random-access evaluation.
    pub eval: f64,
}

/// Earlier runs on the other kind of processor that the development machines come in, kept
/// by hand (a report reads one run): the targets must hold on both.
pub const EARLIER_RUNS: [HostRun; 1] = [HostRun {
    cpu: "AMD EPYC",
    commit: "068ec98",
    playback: 2.7,
    fill: 11.8,
    fill_positions: 20.7,
    eval: 3.5,
}];

/// The smallest speed-up of `checks` (`–` when none was measured).
fn smallest(checks: &[Check]) -> String {
    weakest(checks).map_or_else(|| "–".to_string(), |c| format!("{:.1}×", c.value))
}

/// The host targets' worst cases on each processor: this run's, then [`EARLIER_RUNS`].
fn processor_table(o: &mut String, m: &Machine, this: [&[Check]; 4]) {
    let _ = writeln!(
        o,
        "### Each processor\n\nThe smallest speed-up of each host target, in this run and in \
         earlier runs on the other kind of processor (kept in `bench/src/report.rs`):\n\n\
         | processor | run | playback (`next`) | `fill` | `fill_positions` | random access |\n\
         |---|---|---:|---:|---:|---:|"
    );
    let [play, fill, positions, eval] = this.map(smallest);
    let _ = writeln!(
        o,
        "| {} | this one | {play} | {fill} | {positions} | {eval} |",
        m.cpu
    );
    for e in EARLIER_RUNS {
        let _ = writeln!(
            o,
            "| {} | commit {} | {:.1}× | {:.1}× | {:.1}× | {:.1}× |",
            e.cpu, e.commit, e.playback, e.fill, e.fill_positions, e.eval
        );
    }
    let _ = writeln!(o);
}

/// Where the inputs are.
#[derive(Clone, Debug)]
pub struct Inputs {
    /// criterion's output folder (`target/criterion`).
    pub criterion: PathBuf,
    /// The QEMU results folder (`target/qemu`, holding `counts.json` and `sizes.json`).
    pub qemu: PathBuf,
}

/// Reads everything and returns the Markdown of `BENCHMARKS.md`.
///
/// # Errors
/// When criterion's folder holds no results or a file is malformed.
pub fn generate(inputs: &Inputs, machine: &Machine) -> Result<String> {
    let ms = read_criterion(&inputs.criterion)?;
    if ms.is_empty() {
        return Err(anyhow!(
            "no criterion results in {} (run `{BENCH_COMMAND}` first)",
            inputs.criterion.display()
        ));
    }
    let counts = read_optional::<QemuCount>(&inputs.qemu.join("counts.json"))?;
    let sizes = read_optional::<FirmwareSize>(&inputs.qemu.join("sizes.json"))?;
    Ok(render(
        &Results::new(&ms),
        machine,
        counts.as_deref(),
        sizes.as_deref(),
    ))
}

fn read_optional<T: for<'de> Deserialize<'de>>(p: &Path) -> Result<Option<Vec<T>>> {
    if !p.is_file() {
        return Ok(None);
    }
    let s = fs::read_to_string(p).with_context(|| format!("reading {}", p.display()))?;
    let v = serde_json::from_str(&s).with_context(|| format!("parsing {}", p.display()))?;
    Ok(Some(v))
}

fn ns(t: Option<f64>) -> String {
    match t {
        Some(t) if t < 10.0 => format!("{t:.2}"),
        Some(t) if t < 100.0 => format!("{t:.1}"),
        Some(t) => format!("{t:.0}"),
        None => "–".to_string(),
    }
}

/// `speed-up× (ratio)`: how many times faster strak is, and strak's time over the peer's.
fn ratio(strak: Option<f64>, peer: Option<f64>) -> String {
    match (strak, peer) {
        (Some(s), Some(p)) if s > 0.0 => format!("{:.1}× ({:.3})", p / s, s / p),
        _ => "–".to_string(),
    }
}

fn verdict(checks: &[Check]) -> &'static str {
    if checks.is_empty() {
        "not measured"
    } else if checks.iter().all(|c| c.met) {
        "**met**"
    } else {
        "**not met**"
    }
}

/// The check with the smallest speed-up.
fn weakest(checks: &[Check]) -> Option<&Check> {
    checks.iter().min_by(|a, b| a.value.total_cmp(&b.value))
}

fn worst(checks: &[Check], spread: bool) -> String {
    let w = if spread {
        checks.iter().max_by(|a, b| a.value.total_cmp(&b.value))
    } else {
        weakest(checks)
    };
    match w {
        Some(c) if spread => format!("largest spread {:.1} % ({})", 100.0 * c.value, c.what),
        Some(c) => format!("smallest speed-up {:.1}× ({})", c.value, c.what),
        None => "–".to_string(),
    }
}

/// The Markdown report from indexed results.
#[allow(clippy::too_many_lines)]
pub fn render(
    r: &Results,
    m: &Machine,
    counts: Option<&[QemuCount]>,
    sizes: Option<&[FirmwareSize]>,
) -> String {
    let mut o = String::new();
    let eval = eval_checks(r);
    let play = playback_checks(r);
    let fill = fill_checks(r);
    let fill_positions = fill_positions_checks(r);
    let flat = flatness_checks(r);
    let _ = writeln!(o, "# Benchmarks\n");
    let _ = writeln!(
        o,
        "Generated by `{REPORT_COMMAND}` from criterion's results (median time per sample) and, \
         for the Cortex-M section, the QEMU runs. Do not edit by hand.\n"
    );
    let _ = writeln!(o, "## Targets (issue 5)\n");
    let _ = writeln!(o, "| target | verdict | worst case |\n|---|---|---|");
    let _ = writeln!(
        o,
        "| fixed-rate playback ≥ {PLAYBACK_TARGET}× faster per sample than the fastest peer's \
         evaluation of the same curve (enterpolation, bspline; f32 and f64, every n) | {} | {} |",
        verdict(&play),
        worst(&play, false)
    );
    if !fill.is_empty() {
        let _ = writeln!(
            o,
            "| batch playback (`Sampler::fill`) ≥ {PLAYBACK_TARGET}× faster per sample than the \
             fastest peer's evaluation of the same curve (f32 and f64, every n) | {} | {} |",
            verdict(&fill),
            worst(&fill, false)
        );
    }
    if !fill_positions.is_empty() {
        let _ = writeln!(
            o,
            "| batch playback of positions (`Sampler::fill_positions`: the peers' job, \
             positions only) ≥ {PLAYBACK_TARGET}× faster per sample than the fastest peer's \
             evaluation of the same curve (f32 and f64, every n) | {} | {} |",
            verdict(&fill_positions),
            worst(&fill_positions, false)
        );
    }
    let _ = writeln!(
        o,
        "| random-access evaluation ≥ {EVAL_TARGET}× faster than the fastest peer \
         (enterpolation, bspline, splines; f32 and f64, both patterns, every n; strak's \
         fastest evaluator of the precision: `PowerSpline` or `BSpline`) | {} | {} |",
        verdict(&eval),
        worst(&eval, false)
    );
    let _ = writeln!(
        o,
        "| per-sample playback cost independent of n: within {:.0} % from 8 to 8192 points \
         (f32, f64, Q40) | {} | {} |",
        100.0 * FLATNESS_TARGET,
        verdict(&flat),
        worst(&flat, true)
    );
    match counts {
        Some(cs) if !cs.is_empty() => {
            for c in cortex_m_checks(cs) {
                let value = if c.what.contains("worst") {
                    format!("max / median {:.2}", c.value)
                } else {
                    format!("median {:.0} instructions", c.value)
                };
                let _ = writeln!(
                    o,
                    "| {} (instruction counts under QEMU, not cycles) | {} | {value} |",
                    c.what,
                    if c.met { "met" } else { "**not met**" }
                );
            }
            let _ = writeln!(o);
        }
        _ => {
            let _ = writeln!(
                o,
                "| Cortex-M instruction counts (M4F f32 ≤ 40 / ≤ 72, M3 fixed ≤ 60 / ≤ 110, \
                 worst ≤ 1.5× median) | not measured in this run | – |\n"
            );
        }
    }

    online_section(&mut o, r);
    let _ = writeln!(o, "## Machine\n");
    let _ = writeln!(o, "- CPU: {} ({} logical cores available)", m.cpu, m.cores);
    let _ = writeln!(o, "- OS: {}", m.os);
    let _ = writeln!(o, "- Rust: {}", m.rustc);
    let _ = writeln!(
        o,
        "- Load average (1 min) when the report was written: {} — the cores may have been \
         shared with other work; compare ratios from one run, not absolute times across runs.\n",
        m.load
    );
    processor_table(&mut o, m, [&play, &fill, &fill_positions, &eval]);
    let _ = writeln!(o, "## Reproduce\n");
    let _ = writeln!(o, "```sh\n{BENCH_COMMAND}\n{REPORT_COMMAND}\n```\n");
    let _ = writeln!(
        o,
        "Both are run by `cargo xtask bench`. The report reads `target/criterion/` and, if \
         present, `target/qemu/counts.json` and `target/qemu/sizes.json`.\n"
    );

    let _ = writeln!(o, "## The work\n");
    let _ = writeln!(
        o,
        "- The curve: a 3-D clamped uniform cubic B-spline of n = {} de Boor points on a helix \
         (radius 50 mm, 16 points per turn, rising 0.5 mm per turn), knots 0, 0, 0, 0, 1, …, \
         n − 3 (×4); every library gets the same points (the bench checks that strak, \
         enterpolation and bspline agree on every sample).",
        SIZES.map(|n| n.to_string()).join(", ")
    );
    let _ = writeln!(
        o,
        "- Random access: {TABLE_LEN} parameters per size, evenly spaced (both ends included) \
         or pseudo-random (a fixed xorshift table), the same for every library, each through \
         `black_box`; the time is per sample. strak is measured with two evaluators of the \
         same curve: `strak` = de Boor's algorithm (`BSpline::eval`, the exact evaluator the \
         compiled paths use) and `strak power` = the per-span power-basis polynomials \
         (`PowerSpline::eval`: O(1) span lookup and Horner, within a few roundings of de Boor; \
         the bench checks both against the same table)."
    );
    let _ = writeln!(
        o,
        "- Playback: the path compiled from the f64 B-spline with the jerk-limited S-curve \
         (`PathTiming::scurve`, v 500 mm/s, a 5000 mm/s², j 100 000 mm/s³; `compile` at \
         {RATE_HZ} Hz, tolerance {TOLERANCE_MM} mm, at most 256 ticks per piece), one \
         `Sampler::next()` (position, velocity and acceleration of 3 axes) per iteration over \
         the whole path, restarting at the end: the amortized cost per tick, piece switches \
         included. The peers evaluate position only.\n"
    );

    let _ = writeln!(o, "## Random-access evaluation (ns per sample)\n");
    for pat in Pattern::ALL {
        let _ = writeln!(o, "### {} parameters\n", pat.label());
        let cols: [(&str, &str); 15] = [
            ("strak_f32", "strak f32"),
            ("strak_f64", "strak f64"),
            ("strak_i32f32", "strak I32F32"),
            ("strak_i16f16", "strak I16F16"),
            ("strak_power_f32", "strak power f32"),
            ("strak_power_f64", "strak power f64"),
            ("strak_power_i32f32", "strak power I32F32"),
            ("strak_power_i16f16", "strak power I16F16"),
            ("enterpolation_f32", "enterpolation f32"),
            ("enterpolation_f64", "enterpolation f64"),
            ("bspline_f32", "bspline f32"),
            ("bspline_f64", "bspline f64"),
            ("splines_catmull_rom_f32", "splines CR¹ f32"),
            ("splines_catmull_rom_f64", "splines CR¹ f64"),
            ("kurbo_cubicbez_f64", "kurbo² f64"),
        ];
        let _ = write!(o, "| n |");
        for (_, l) in cols {
            let _ = write!(o, " {l} |");
        }
        let _ = writeln!(o, "\n|---:|{}", "---:|".repeat(cols.len()));
        for n in SIZES {
            let _ = write!(o, "| {n} |");
            for (f, _) in cols {
                let _ = write!(o, " {} |", ns(r.eval(pat, f, n)));
            }
            let _ = writeln!(o);
        }
        let _ = writeln!(
            o,
            "\nRatio to each peer, same precision: speed-up × (strak's time / peer's time), \
             for each strak evaluator: `f32`/`f64` rows are de Boor (`BSpline`), `… power` rows \
             the power basis (`PowerSpline`).\n"
        );
        let _ = write!(o, "| n | precision |");
        for p in PEERS {
            let _ = write!(o, " {} |", p.label);
        }
        let _ = writeln!(o, "\n|---:|---|{}", "---:|".repeat(PEERS.len()));
        for n in SIZES {
            for precision in ["f32", "f64"] {
                for (prefix, suffix) in [("strak", ""), ("strak_power", " power")] {
                    let s = r.eval(pat, &format!("{prefix}_{precision}"), n);
                    if s.is_none() && !suffix.is_empty() {
                        continue;
                    }
                    let _ = write!(o, "| {n} | {precision}{suffix} |");
                    for p in PEERS {
                        let peer = r
                            .eval(pat, &format!("{}_{precision}", p.id), n)
                            .or_else(|| r.eval(pat, &format!("{}_f64", p.id), n));
                        let _ = write!(o, " {} |", ratio(s, peer));
                    }
                    let _ = writeln!(o);
                }
            }
        }
        let _ = writeln!(o);
    }
    let _ = writeln!(
        o,
        "¹ splines: Catmull-Rom through the same points (keys at u = −1, 0, …, n − 2) — a \
         different curve of the same cost class (binary search, one cubic).  \n\
         ² kurbo: a single 2-D cubic Bézier (f64 only; kurbo has no f32 and no 3-D curve) — no \
         span search, a lower bound for any piecewise curve; its f64 time is also used in the \
         f32 rows. Not counted for the targets (not the same job).  \n\
         stroke: not measured — every published version (0.3, 0.4.1) needs \
         `#![feature(generic_const_exprs)]`, i.e. a nightly compiler (E0554 on stable).\n"
    );

    let _ = writeln!(o, "## Fixed-rate playback (ns per tick)\n");
    let _ = writeln!(
        o,
        "| n | f32 | f64 | Q40 | fastest same-curve peer f32 | speed-up f32 | fastest \
         same-curve peer f64 | speed-up f64 | Q40 vs fastest f64 peer |\n\
         |---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    for n in SIZES {
        let p32 = fastest_peer(r, &Pattern::ALL, "f32", n, |p| p.same_curve);
        let p64 = fastest_peer(r, &Pattern::ALL, "f64", n, |p| p.same_curve);
        let show = |p: Option<(f64, &str)>| {
            p.map_or("–".into(), |(t, id)| format!("{} ({id})", ns(Some(t))))
        };
        let _ = writeln!(
            o,
            "| {n} | {} | {} | {} | {} | {} | {} | {} | {} |",
            ns(r.playback("f32", n)),
            ns(r.playback("f64", n)),
            ns(r.playback("q40", n)),
            show(p32),
            ratio(r.playback("f32", n), p32.map(|p| p.0)),
            show(p64),
            ratio(r.playback("f64", n), p64.map(|p| p.0)),
            ratio(r.playback("q40", n), p64.map(|p| p.0)),
        );
    }
    let _ = writeln!(
        o,
        "\nRatio to every peer (playback time / the peer's fastest evaluation of either \
         pattern, same precision; Q40 against f64):\n"
    );
    let _ = write!(o, "| n | format |");
    for p in PEERS {
        let _ = write!(o, " {} |", p.label);
    }
    let _ = writeln!(o, "\n|---:|---|{}", "---:|".repeat(PEERS.len()));
    for n in SIZES {
        for (format, precision) in [("f32", "f32"), ("f64", "f64"), ("q40", "f64")] {
            let _ = write!(o, "| {n} | {format} |");
            for p in PEERS {
                let best = fastest_peer(r, &Pattern::ALL, precision, n, |q| q.id == p.id)
                    .or_else(|| fastest_peer(r, &Pattern::ALL, "f64", n, |q| q.id == p.id));
                let _ = write!(o, " {} |", ratio(r.playback(format, n), best.map(|b| b.0)));
            }
            let _ = writeln!(o);
        }
    }
    let _ = writeln!(o);
    batch_table(&mut o, r);
    let _ = writeln!(
        o,
        "### The floor of a tick: the forward-differencing step alone\n\n\
         `AxisState::step` on 3 axes with the state passed through `black_box` every tick \
         (stored and reloaded, as a sampler's state must be between interrupts), no sampler \
         bookkeeping, no sample built (group `floor`). The playback tick above cannot be \
         faster than this; the 20× target needs a tick of (fastest same-curve peer) / 20.\n"
    );
    let _ = writeln!(
        o,
        "| format | floor (ns per tick) | playback at n = 1024 | playback / floor | 20× target at n = 1024 needs |\n|---|---:|---:|---:|---:|"
    );
    for (format, precision) in [("f32", "f32"), ("f64", "f64"), ("q40", "f64")] {
        let floor = r.get("floor", &format!("strak_{format}"), "");
        let play = r.playback(format, 1024);
        let peer = fastest_peer(r, &Pattern::ALL, precision, 1024, |p| p.same_curve);
        let rel = match (play, floor) {
            (Some(p), Some(f)) if f > 0.0 => format!("{:.2}", p / f),
            _ => "–".into(),
        };
        let _ = writeln!(
            o,
            "| {format} | {} | {} | {rel} | ≤ {} |",
            ns(floor),
            ns(play),
            ns(peer.map(|p| p.0 / PLAYBACK_TARGET)),
        );
    }
    let _ = writeln!(o);

    let _ = writeln!(o, "## Flatness\n");
    let _ = writeln!(o, "### Per-tick playback cost across n\n");
    let _ = writeln!(
        o,
        "| format | {} | max / min |\n|---|{}---:|",
        SIZES.map(|n| format!("n = {n}")).join(" | "),
        "---:|".repeat(SIZES.len())
    );
    for format in ["f32", "f64", "q40"] {
        let ts: Vec<Option<f64>> = SIZES.iter().map(|&n| r.playback(format, n)).collect();
        let got: Vec<f64> = ts.iter().flatten().copied().collect();
        let spread = if got.len() >= 2 {
            let lo = got.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = got.iter().copied().fold(0.0, f64::max);
            format!("{:.3}", hi / lo)
        } else {
            "–".into()
        };
        let _ = writeln!(
            o,
            "| {format} | {} | {spread} |",
            ts.iter().map(|&t| ns(t)).collect::<Vec<_>>().join(" | ")
        );
    }
    let _ = writeln!(
        o,
        "\n### One tick at chosen positions (1024-point path)\n\n\
         Each is one `next()` on a clone of a sampler advanced to just before that tick \
         (criterion `iter_batched_ref`); `baseline` is the same harness with an empty routine, \
         `net` = measured − baseline. `*_switch` is the tick whose `next()` loads the next \
         piece; `before_end` the last tick of the last piece (it marks the end), `end` the \
         final sample (the path's end point).\n"
    );
    let points = [
        "start",
        "first_switch",
        "middle",
        "middle_switch",
        "last_switch",
        "before_end",
        "end",
    ];
    let _ = writeln!(
        o,
        "| position | f32 | f32 net | f64 | f64 net | Q40 | Q40 net |\n|---|---:|---:|---:|---:|---:|---:|"
    );
    for p in std::iter::once("baseline").chain(points) {
        let _ = write!(o, "| {p} |");
        for format in ["f32", "f64", "q40"] {
            let g = format!("flatness_{format}");
            let t = r.get(&g, p, "");
            let base = r.get(&g, "baseline", "");
            let net = match (t, base) {
                (Some(t), Some(b)) if p != "baseline" => ns(Some(t - b)),
                _ => "–".into(),
            };
            let _ = write!(o, " {} | {net} |", ns(t));
        }
        let _ = writeln!(o);
    }
    let _ = writeln!(o);

    let _ = writeln!(o, "## Target checks in detail\n");
    for (title, checks, unit) in [
        ("Playback vs the fastest same-curve peer", &play, "×"),
        ("Batch playback vs the fastest same-curve peer", &fill, "×"),
        (
            "Batch playback of positions vs the fastest same-curve peer",
            &fill_positions,
            "×",
        ),
        (
            "Random-access evaluation vs the fastest same-job peer",
            &eval,
            "×",
        ),
        ("Playback spread across n", &flat, "%"),
    ] {
        let _ = writeln!(o, "{title}:\n");
        for c in checks {
            let v = if unit == "%" {
                format!("{:.1} %", 100.0 * c.value)
            } else {
                format!("{:.1}×", c.value)
            };
            let _ = writeln!(
                o,
                "- {}: {v} — {}",
                c.what,
                if c.met { "met" } else { "NOT met" }
            );
        }
        let _ = writeln!(o);
    }

    if !(play.iter().all(|c| c.met) && eval.iter().all(|c| c.met)) {
        let _ = writeln!(o, "{MISSED}");
    }
    let _ = writeln!(
        o,
        "## Cortex-M under QEMU: instructions per tick and firmware sizes\n"
    );
    let _ = writeln!(
        o,
        "Instruction counts (QEMU `-icount`), not cycles. Filled from `target/qemu/counts.json` \
         and `target/qemu/sizes.json` by the QEMU runs (`cargo xtask bench`).\n"
    );
    match counts {
        Some(cs) if !cs.is_empty() => {
            let _ = writeln!(
                o,
                "| run | min | median | max | max / median | budget median / max | within budget |\n|---|---:|---:|---:|---:|---:|---|"
            );
            for c in cs {
                let within = match (c.budget, c.budget_max) {
                    (Some(b), Some(bm)) if c.median <= b && c.max <= bm => "yes",
                    (Some(b), None) if c.median <= b => "yes",
                    (None, _) => "–",
                    _ => "**no**",
                };
                let show = |b: Option<u64>| b.map_or("–".to_string(), |b| b.to_string());
                let _ = writeln!(
                    o,
                    "| {} | {} | {} | {} | {:.2} | {} / {} | {within} |",
                    c.name,
                    c.min,
                    c.median,
                    c.max,
                    c.max as f64 / c.median.max(1) as f64,
                    show(c.budget),
                    show(c.budget_max),
                );
            }
            let missed: Vec<Check> = cortex_m_checks(cs).into_iter().filter(|c| !c.met).collect();
            if !missed.is_empty() {
                let _ = writeln!(o, "\n{CORTEX_M_MISSED}");
                for c in &missed {
                    let _ = writeln!(o, "- not met: {}", c.what);
                }
            }
            let _ = writeln!(
                o,
                "\nThe listings and the instruction-by-instruction accounting: \
                 [firmware-sim/qemu/ICOUNT.md](firmware-sim/qemu/ICOUNT.md)."
            );
        }
        _ => {
            let _ = writeln!(o, "Instruction counts: not measured in this run.");
        }
    }
    let _ = writeln!(o);
    match sizes {
        Some(ss) if !ss.is_empty() => {
            let _ = writeln!(o, "| firmware | text | data | bss |\n|---|---:|---:|---:|");
            for s in ss {
                let _ = writeln!(o, "| {} | {} | {} | {} |", s.name, s.text, s.data, s.bss);
            }
        }
        _ => {
            let _ = writeln!(o, "Firmware sizes: not measured in this run.");
        }
    }
    o
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Writes one criterion-like result below `root`.
    fn put(
        root: &Path,
        group: &str,
        function: &str,
        value: Option<&str>,
        median: f64,
        elements: u64,
    ) {
        let mut dir = root.join(group).join(function);
        if let Some(v) = value {
            dir = dir.join(v);
        }
        let dir = dir.join("new");
        fs::create_dir_all(&dir).unwrap();
        let b = serde_json::json!({
            "group_id": group,
            "function_id": function,
            "value_str": value,
            "throughput": { "Elements": elements },
            "full_id": "x", "directory_name": "x", "title": "x"
        });
        fs::write(dir.join("benchmark.json"), b.to_string()).unwrap();
        let e = serde_json::json!({
            "mean": {"confidence_interval": {"confidence_level": 0.95, "lower_bound": 1.0, "upper_bound": 2.0}, "point_estimate": 999.0, "standard_error": 1.0},
            "median": {"confidence_interval": {"confidence_level": 0.95, "lower_bound": 1.0, "upper_bound": 2.0}, "point_estimate": median, "standard_error": 1.0},
            "median_abs_dev": null, "slope": null, "std_dev": null
        });
        fs::write(dir.join("estimates.json"), e.to_string()).unwrap();
    }

    /// A fixture: strak 10 ns/sample, enterpolation 40, bspline 25 (f32) / 35 (f64) for
    /// every n and pattern (table of 1024 → medians ×1024); playback 1.0 ns at every n but
    /// 1.3 ns (f64) at 8192; kurbo 2 ns.
    fn fixture(root: &Path) {
        for g in ["eval_even", "eval_random"] {
            for n in SIZES {
                let v = n.to_string();
                let v = Some(v.as_str());
                put(root, g, "strak_f32", v, 10.0 * 1024.0, 1024);
                put(root, g, "strak_f64", v, 10.0 * 1024.0, 1024);
                put(root, g, "enterpolation_f32", v, 40.0 * 1024.0, 1024);
                put(root, g, "enterpolation_f64", v, 40.0 * 1024.0, 1024);
                put(root, g, "bspline_f32", v, 25.0 * 1024.0, 1024);
                put(root, g, "bspline_f64", v, 35.0 * 1024.0, 1024);
                put(root, g, "splines_catmull_rom_f64", v, 50.0 * 1024.0, 1024);
                put(root, g, "kurbo_cubicbez_f64", v, 2.0 * 1024.0, 1024);
            }
        }
        for n in SIZES {
            let v = n.to_string();
            let slow = if n == 8192 { 1.3 } else { 1.0 };
            put(root, "playback", "strak_f32", Some(&v), 1.0, 1);
            put(root, "playback", "strak_f64", Some(&v), slow, 1);
            if n != 64 {
                put(root, "playback", "strak_q40", Some(&v), 2.0, 1);
            }
        }
        // as `bench_function("strak_q40/64")` stores it: the parameter in the function id
        put(root, "playback", "strak_q40/64", None, 2.5, 1);
        put(root, "flatness_f32", "baseline", None, 0.5, 1);
        put(root, "flatness_f32", "middle", None, 2.0, 1);
    }

    fn results() -> (tempfile::TempDir, Results) {
        let dir = tempfile::tempdir().unwrap();
        fixture(dir.path());
        let ms = read_criterion(dir.path()).unwrap();
        (dir, Results::new(&ms))
    }

    #[test]
    fn reads_medians_per_element() {
        let dir = tempfile::tempdir().unwrap();
        fixture(dir.path());
        let ms = read_criterion(dir.path()).unwrap();
        // 2 patterns × 4 sizes × 8 functions + 3 × 4 playback + 2 flatness
        assert_eq!(ms.len(), 2 * 4 * 8 + 12 + 2);
        let r = Results::new(&ms);
        assert_eq!(r.eval(Pattern::Random, "bspline_f64", 64), Some(35.0));
        assert_eq!(r.playback("f64", 8192), Some(1.3));
        assert_eq!(r.playback("q40", 64), Some(2.5));
        assert_eq!(r.get("flatness_f32", "middle", ""), Some(2.0));
        assert_eq!(r.eval(Pattern::Even, "bspline_f32", 7), None);
    }

    #[test]
    fn fastest_peer_and_ratios() {
        let (_d, r) = results();
        assert_eq!(
            fastest_peer(&r, &Pattern::ALL, "f32", 64, |p| p.same_curve),
            Some((25.0, "bspline"))
        );
        // kurbo is only chosen when asked for (not the same job)
        assert_eq!(
            fastest_peer(&r, &Pattern::ALL, "f64", 64, |_| true),
            Some((2.0, "kurbo_cubicbez"))
        );
        assert_eq!(ratio(Some(10.0), Some(25.0)), "2.5× (0.400)");
        assert_eq!(ratio(None, Some(25.0)), "–");
    }

    #[test]
    fn target_verdicts() {
        let (_d, r) = results();
        // Evaluation: 25/10 = 2.5× (f32) and 35/10 = 3.5× (f64): f32 misses 3×.
        let e = eval_checks(&r);
        assert_eq!(e.len(), 2 * 2 * 4);
        assert!(e.iter().filter(|c| c.what.contains("f32")).all(|c| !c.met));
        assert!(e.iter().filter(|c| c.what.contains("f64")).all(|c| c.met));
        assert!((e[0].value - 2.5).abs() < 1e-12);
        // Playback: 25/1 = 25× (f32) met; f64 35/1.3 = 26.9× met.
        let p = playback_checks(&r);
        assert_eq!(p.len(), 8);
        assert!(p.iter().all(|c| c.met));
        // Flatness: f64 spreads 30 % > 20 %, q40 25 % (2.5 at n = 64); f32 is flat.
        let f = flatness_checks(&r);
        assert_eq!(f.len(), 3);
        assert!(f[0].met && !f[1].met && !f[2].met);
        assert!((f[1].value - 0.3).abs() < 1e-12);
        assert_eq!(verdict(&f), "**not met**");
        assert_eq!(verdict(&p), "**met**");
        assert_eq!(verdict(&[]), "not measured");
    }

    #[test]
    fn online_checks_and_section() {
        let d = tempfile::tempdir().unwrap();
        // Per move: strak 1 000 ns (f64) and 900 ns (f32), Ruckig 6 000, rsruckig 4 000:
        // 4× and 4.4× the faster peer (not met); slowest/median 2.5× (met).
        for (f, t) in [
            ("strak_f64", 1e6),
            ("strak_f32", 9e5),
            ("ruckig", 6e6),
            ("rsruckig", 4e6),
        ] {
            put(d.path(), "online", f, None, t, 1_000);
        }
        put(d.path(), "online_case", "median", None, 800.0, 1);
        put(d.path(), "online_case", "worst", None, 2_000.0, 1);
        let r = Results::new(&read_criterion(d.path()).unwrap());
        let c = online_checks(&r);
        assert_eq!(c.len(), 3);
        assert!((c[0].value - 4.0).abs() < 1e-12 && !c[0].met && c[0].what.contains("rsruckig"));
        assert!((c[1].value - 4.0 / 0.9).abs() < 1e-12 && !c[1].met);
        assert!((c[2].value - 2.5).abs() < 1e-12 && c[2].met);
        let mut o = String::new();
        online_section(&mut o, &r);
        assert!(
            o.contains("## Online moves") && o.contains("| strak, f64 | 1000 |"),
            "{o}"
        );
        assert!(
            o.contains("not met") && o.contains("Where the time of a random 3-axis"),
            "{o}"
        );
        // Without the online groups: no section.
        let (_d2, r) = results();
        let mut o = String::new();
        online_section(&mut o, &r);
        assert!(o.is_empty());
    }

    #[test]
    fn report_with_and_without_qemu_counts() {
        let (d, r) = results();
        let m = Machine {
            cpu: "Test CPU".into(),
            cores: 2,
            os: "TestOS".into(),
            rustc: "rustc 1.0".into(),
            load: "0.1".into(),
        };
        let md = render(&r, &m, None, None);
        assert!(md.contains("Test CPU (2 logical cores"));
        assert!(md.contains("Instruction counts: not measured in this run."));
        assert!(md.contains("| 64 | f32 | 4.0× (0.250) | 2.5× (0.400) |"));
        assert!(md.contains(BENCH_COMMAND));
        // the QEMU files, through `generate`
        let qemu = d.path().join("qemu");
        fs::create_dir_all(&qemu).unwrap();
        fs::write(
            qemu.join("counts.json"),
            r#"[{"name":"playback-f32-3axis-position","min":30,"median":32,"max":47,"budget":40,"budget_max":50},
                {"name":"playback-f32-3axis","min":70,"median":80,"max":130,"budget":84,"budget_max":120}]"#,
        )
        .unwrap();
        let inputs = Inputs {
            criterion: d.path().to_path_buf(),
            qemu,
        };
        let md = generate(&inputs, &m).unwrap();
        assert!(
            md.contains("| playback-f32-3axis-position | 30 | 32 | 47 | 1.47 | 40 / 50 | yes |")
        );
        assert!(md.contains("| playback-f32-3axis | 70 | 80 | 130 | 1.62 | 84 / 120 | **no** |"));
        // the target rows: met, missed on the median, missed on the worst tick
        assert!(md.contains("position only: median ≤ 40 (instruction counts under QEMU, not cycles) | met | median 32 instructions |"), "{md}");
        assert!(md.contains("acceleration: median ≤ 72 (instruction counts under QEMU, not cycles) | **not met** | median 80 instructions |"));
        assert!(md.contains("worst tick ≤ 1.5 × median (instruction counts under QEMU, not cycles) | **not met** | max / median 1.62 |"));
        // a missed target brings the pointer to the listings and names the target
        assert!(md.contains("### A Cortex-M target is missed"));
        assert!(md.contains("- not met: Cortex-M4F, 3-axis f32: worst tick ≤ 1.5 × median"));
        assert!(!md.contains("- not met: Cortex-M4F, 3-axis f32, position only"));
        // runs that were not counted give no rows
        assert!(!md.contains("Cortex-M3, 3-axis fixed-point (Q40), position only"));
        assert!(md.contains("Firmware sizes: not measured in this run."));
    }

    /// The power-basis evaluator: its columns and ratio rows appear, and the evaluation
    /// verdict uses strak's fastest evaluator of each precision, named in the check.
    #[test]
    fn power_evaluator_columns_and_verdict() {
        let d = tempfile::tempdir().unwrap();
        fixture(d.path());
        for g in ["eval_even", "eval_random"] {
            for n in SIZES {
                let v = n.to_string();
                let v = Some(v.as_str());
                put(d.path(), g, "strak_power_f32", v, 5.0 * 1024.0, 1024);
                // slower than de Boor in f64: the verdict must keep de Boor there
                put(d.path(), g, "strak_power_f64", v, 20.0 * 1024.0, 1024);
                put(d.path(), g, "strak_power_i32f32", v, 7.5 * 1024.0, 1024);
            }
        }
        let r = Results::new(&read_criterion(d.path()).unwrap());
        assert_eq!(
            fastest_strak(&r, Pattern::Even, "f32", 64),
            Some((5.0, "strak_power_f32".to_string()))
        );
        assert_eq!(
            fastest_strak(&r, Pattern::Random, "f64", 8),
            Some((10.0, "strak_f64".to_string()))
        );
        assert_eq!(fastest_strak(&r, Pattern::Random, "f16", 8), None);
        // f32: bspline 25 / power 5 = 5× (met, was 2.5× with de Boor); f64: 35/10 = 3.5×.
        let e = eval_checks(&r);
        assert_eq!(e.len(), 2 * 2 * 4);
        assert!(e.iter().all(|c| c.met));
        assert!((e[0].value - 5.0).abs() < 1e-12);
        assert!(
            e[0].what.contains("f32 n = 8 (strak_power_f32 vs bspline)"),
            "{}",
            e[0].what
        );
        let f64_check = e.iter().find(|c| c.what.contains("f64")).unwrap();
        assert!(f64_check.what.contains("(strak_f64 vs bspline)"));
        let md = render(&r, &Machine::default(), None, None);
        assert!(md.contains(
            "| strak f32 | strak f64 | strak I32F32 | strak I16F16 | strak power f32 | \
             strak power f64 | strak power I32F32 | strak power I16F16 |"
        ));
        // n = 8: de Boor 10, 10, I16F16 missing; power 5, 20, 7.5, missing.
        assert!(md.contains("| 8 | 10.0 | 10.0 | – | – | 5.00 | 20.0 | 7.50 | – | 40.0 |"));
        // ratio rows: de Boor as before, then the power basis (40/5 = 8×, 25/5 = 5×)
        assert!(md.contains("| 64 | f32 | 4.0× (0.250) | 2.5× (0.400) |"));
        assert!(md.contains("| 64 | f32 power | 8.0× (0.125) | 5.0× (0.200) |"));
        assert!(md.contains("| 64 | f64 power | 2.0× (0.500) | 1.8× (0.571) |"));
        // the fixture without power results has no power rows
        let (_d, r0) = results();
        assert!(!render(&r0, &Machine::default(), None, None).contains("f32 power"));
    }

    #[test]
    fn empty_results_are_an_error() {
        let d = tempfile::tempdir().unwrap();
        let inputs = Inputs {
            criterion: d.path().to_path_buf(),
            qemu: d.path().join("q"),
        };
        assert!(generate(&inputs, &Machine::default()).is_err());
    }
}
