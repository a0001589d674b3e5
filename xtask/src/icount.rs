//! Instructions per tick on Cortex-M under QEMU `-icount`, checked against budgets.
//!
//! These are **instruction counts, not cycles**: QEMU with `-icount shift=10` advances its
//! virtual clock 1024 ns per instruction, and the `icount` firmware
//! (`firmware-sim/qemu/src/bin/icount.rs`) reads SysTick around every call it measures; the
//! counts are exact and the same on every run (calibrated with straight runs of `nop`s).
//!
//! The budgets are checked in at `firmware-sim/qemu/icount-budgets.txt` (one line per case
//! and target: median and max); a measured count above its budget fails `cargo xtask qemu`
//! (and so `cargo xtask test`). `--bless` rewrites the file from the measured counts with
//! [`budget::MARGIN`] of headroom. The measured counts are written to `target/qemu/counts.json`.

use std::fmt::Write as _;

use crate::budget;

/// The `-icount` shift the firmware's conversion assumes (`strak_qemu::counter::ICOUNT_SHIFT`).
pub(crate) const ICOUNT_SHIFT: u32 = 10;

/// One measured case of one target.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Measured {
    /// Case name, e.g. `playback-f32-3axis`.
    pub(crate) name: String,
    /// Rust target triple.
    pub(crate) target: String,
    /// Fewest instructions of one call.
    pub(crate) min: u64,
    /// Median (the lower middle) over all calls.
    pub(crate) median: u64,
    /// Most instructions of one call.
    pub(crate) max: u64,
    /// Number of calls measured.
    pub(crate) calls: u64,
    /// Index (from 0) of the first call that took `max`.
    pub(crate) worst: u64,
}

/// The values of a line of `icount-budgets.txt`.
pub(crate) const FIELDS: [&str; 2] = ["median", "max"];

/// The header of `icount-budgets.txt`.
const HEADER: &str = "# Instruction budgets per call (instruction counts under QEMU -icount, NOT cycles),\n\
     # checked by `cargo xtask qemu`: a measured median or max above its budget fails.\n\
     # `cargo xtask qemu --bless` rewrites this file (measured + 5 %).\n\
     # name target median max\n";

/// The budget of one case on one target: most instructions of the median and of the worst
/// call.
pub(crate) type Budget = budget::Budget<2>;

impl Measured {
    /// The measured values in the shape of a budget line.
    fn line(&self) -> Budget {
        Budget {
            name: self.name.clone(),
            target: self.target.clone(),
            values: [self.median, self.max],
        }
    }
}

/// Parses the budget file (see [`crate::budget::parse`]).
///
/// # Errors
/// The first bad line.
pub(crate) fn parse_budgets(text: &str) -> Result<Vec<Budget>, String> {
    budget::parse(text, FIELDS)
}

/// The budget file for `measured`, each count blessed ([`budget::blessed`]).
pub(crate) fn write_budgets(measured: &[Measured]) -> String {
    let lines: Vec<Budget> = measured.iter().map(Measured::line).collect();
    budget::write(HEADER, &budget::bless(&lines))
}

/// Parses the `icount` firmware's decoded output for `target`: checks the calibration line
/// (64 `nop`s must measure exactly 64) and the `DONE` count.
///
/// # Errors
/// A malformed line, a failed calibration, a missing `DONE`, or a case count that differs.
pub(crate) fn parse_output(text: &str, target: &str) -> Result<Vec<Measured>, String> {
    let mut out = Vec::new();
    let mut calibrated = false;
    let mut done = None;
    for line in text.lines() {
        let f: Vec<&str> = line.split_whitespace().collect();
        let num = |s: &str| {
            s.parse::<u64>()
                .map_err(|_| format!("`{line}`: `{s}` is not a whole number"))
        };
        match f.as_slice() {
            ["CAL", empty, nops, nop64] => {
                let (e, n, c) = (num(empty)?, num(nops)?, num(nop64)?);
                if c != 64 || n <= e {
                    return Err(format!(
                        "the calibration failed: 64 nops measured as {c} instructions \
                         (empty {e} counts, 256 nops {n} counts); is QEMU running with \
                         -icount shift={ICOUNT_SHIFT}?"
                    ));
                }
                calibrated = true;
            }
            ["I", name, min, median, max, calls, worst] => {
                out.push(Measured {
                    name: (*name).to_owned(),
                    target: target.to_owned(),
                    min: num(min)?,
                    median: num(median)?,
                    max: num(max)?,
                    calls: num(calls)?,
                    worst: num(worst)?,
                });
            }
            ["SAMPLER", n] => {
                num(n)?;
            }
            // an online case's solves, checked against the host by `crate::online`
            ["O", _, moves, sum] => {
                num(moves)?;
                num(sum)?;
            }
            // the feed guard's holds: how many were counted and their delays in ticks
            ["G", name, holds, delays] => {
                println!(
                    "    {name}: {} holds scheduled, {} ticks of delay in all",
                    num(holds)?,
                    num(delays)?
                );
            }
            ["DONE", n] => done = Some(num(n)?),
            [] => {}
            _ => return Err(format!("unexpected icount output: `{line}`")),
        }
    }
    if !calibrated {
        return Err("the icount firmware printed no calibration line".to_owned());
    }
    match done {
        Some(n) if usize::try_from(n).ok() == Some(out.len()) => Ok(out),
        other => Err(format!(
            "the icount firmware reported {other:?} cases, printed {}",
            out.len()
        )),
    }
}

/// The ticks over which the `icount` firmware found the sampler's entry points to agree, bit
/// for bit (its `SAMPLER` line).
///
/// # Errors
/// No such line, or one of no ticks.
pub(crate) fn sampler_checked(text: &str) -> Result<u64, String> {
    text.lines()
        .find_map(|l| l.strip_prefix("SAMPLER "))
        .and_then(|n| n.trim().parse::<u64>().ok())
        .filter(|&n| n > 0)
        .ok_or_else(|| {
            "the icount firmware reported no check of the sampler's entry points".to_owned()
        })
}

/// The verdict: every measured case needs a budget, and neither its median nor its max may
/// exceed it. Lists every violation.
///
/// # Errors
/// The list of cases without a budget or over it.
pub(crate) fn check(measured: &[Measured], budgets: &[Budget]) -> Result<(), String> {
    let lines: Vec<Budget> = measured.iter().map(Measured::line).collect();
    budget::check(
        &lines,
        budgets,
        FIELDS,
        "instructions",
        "instruction counts (not cycles)",
    )
}

/// `counts.json`: a list of `{"name", "target", "min", "median", "max", "budget",
/// "budget_max", "calls"}` (`budget`: the median's budget; `null` without one).
pub(crate) fn counts_json(measured: &[Measured], budgets: &[Budget]) -> String {
    let mut s = String::from("[\n");
    for (i, m) in measured.iter().enumerate() {
        let b = budget::find(budgets, &m.name, &m.target);
        let opt = |x: Option<u64>| x.map_or_else(|| "null".to_owned(), |x| x.to_string());
        let _ = writeln!(
            s,
            "  {{\"name\": \"{}\", \"target\": \"{}\", \"min\": {}, \"median\": {}, \"max\": {}, \
             \"budget\": {}, \"budget_max\": {}, \"calls\": {}, \"unit\": \"instructions\"}}{}",
            m.name,
            m.target,
            m.min,
            m.median,
            m.max,
            opt(b.map(|b| b.values[0])),
            opt(b.map(|b| b.values[1])),
            m.calls,
            if i + 1 < measured.len() { "," } else { "" }
        );
    }
    s.push_str("]\n");
    s
}

/// One of the targets (median instructions per tick at most `limit`).
struct Target {
    case: &'static str,
    target: &'static str,
    limit: u64,
    what: &'static str,
}

const TARGETS: [Target; 5] = [
    Target {
        case: "playback-f32-3axis-position",
        target: "thumbv7em-none-eabihf",
        limit: 40,
        what: "Cortex-M4F, 3-axis f32, position only",
    },
    Target {
        case: "playback-f32-3axis",
        target: "thumbv7em-none-eabihf",
        limit: 72,
        what: "Cortex-M4F, 3-axis f32, position, velocity, acceleration",
    },
    Target {
        case: "playback-q40-3axis-position",
        target: "thumbv7m-none-eabi",
        limit: 60,
        what: "Cortex-M3, 3-axis fixed-point, position only",
    },
    Target {
        case: "playback-q40-3axis-into",
        target: "thumbv7m-none-eabi",
        limit: 110,
        what: "Cortex-M3, 3-axis fixed-point, position, velocity, acceleration (next_into)",
    },
    Target {
        case: "online-f32-3axis",
        target: "thumbv7em-none-eabihf",
        limit: 20_000,
        what: "Cortex-M4F, a 3-axis time-synchronized online move solved in f32",
    },
];

/// The online solve's target for its slowest move (the median's is in [`TARGETS`]).
const ONLINE_WORST: (&str, &str, u64) = ("online-f32-3axis", "thumbv7em-none-eabihf", 40_000);

/// The prefix of the playback cases (a sampler's ticks over a whole path), whose worst tick
/// is gated by [`check_constant_time`].
const PLAYBACK: &str = "playback-";

/// `true` when the worst call of `m` took at most 1.5 times its median (constant time).
fn constant_time(m: &Measured) -> bool {
    2 * m.max <= 3 * m.median
}

/// The constant-time gate: in every playback case the worst tick (a piece switch, the end
/// included) takes at most 1.5 times the median tick. Lists every case over it.
///
/// # Errors
/// The list of playback cases whose worst tick exceeds 1.5 × median.
pub(crate) fn check_constant_time(measured: &[Measured]) -> Result<(), String> {
    let slow: Vec<String> = measured
        .iter()
        .filter(|m| m.name.starts_with(PLAYBACK) && !constant_time(m))
        .map(|m| {
            format!(
                "{} ({}): worst tick {} > 1.5 × median {} (call {})",
                m.name, m.target, m.max, m.median, m.worst
            )
        })
        .collect();
    if slow.is_empty() {
        Ok(())
    } else {
        Err(format!(
            "not constant time (instruction counts):\n  {}",
            slow.join("\n  ")
        ))
    }
}

/// The targets, one line each, with `met` / `MISSED` (reported; the budgets and
/// [`check_constant_time`] are the checks).
pub(crate) fn target_report(measured: &[Measured]) -> Vec<String> {
    let find = |case: &str, target: &str| {
        measured
            .iter()
            .find(|m| m.name == case && m.target == target)
    };
    let mut lines = Vec::new();
    for t in &TARGETS {
        if let Some(m) = find(t.case, t.target) {
            lines.push(format!(
                "{}: median {} ≤ {}: {}",
                t.what,
                m.median,
                t.limit,
                if m.median <= t.limit { "met" } else { "MISSED" }
            ));
        }
    }
    if let Some(m) = find(ONLINE_WORST.0, ONLINE_WORST.1) {
        lines.push(format!(
            "Cortex-M4F, the slowest of those moves: {} ≤ {}: {}",
            m.max,
            ONLINE_WORST.2,
            if m.max <= ONLINE_WORST.2 {
                "met"
            } else {
                "MISSED"
            }
        ));
    }
    let mut playback = measured.iter().filter(|m| m.name.starts_with(PLAYBACK));
    if let Some(first) = playback.next() {
        let met = constant_time(first) && playback.all(constant_time);
        lines.push(format!(
            "every playback case: worst tick ≤ 1.5 × median: {}",
            if met { "met" } else { "MISSED" }
        ));
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    fn m(name: &str, median: u64, max: u64) -> Measured {
        Measured {
            name: name.to_owned(),
            target: "thumbv7m-none-eabi".to_owned(),
            min: 10,
            median,
            max,
            calls: 5,
            worst: 0,
        }
    }

    #[test]
    fn budgets_round_trip_with_the_header() {
        let written = write_budgets(&[m("x", 100, 200)]);
        assert!(written.starts_with("# Instruction budgets"), "{written}");
        assert!(written.contains("# name target median max\n"), "{written}");
        let back = parse_budgets(&written).unwrap();
        assert_eq!(back.len(), 1);
        assert_eq!((back[0].name.as_str(), back[0].values), ("x", [105, 210]));
        assert!(parse_budgets("a t 1\n").unwrap_err().contains("line 1"));
    }

    #[test]
    fn verdict_fails_over_budget_and_without_budget() {
        let b = parse_budgets("a thumbv7m-none-eabi 100 150\n").unwrap();
        assert!(check(&[m("a", 100, 150)], &b).is_ok());
        let e = check(&[m("a", 101, 150)], &b).unwrap_err();
        assert!(
            e.contains("median 101 instructions > budget 100 instructions"),
            "{e}"
        );
        assert!(
            e.starts_with("instruction counts (not cycles) over budget"),
            "{e}"
        );
        let e = check(&[m("a", 90, 151)], &b).unwrap_err();
        assert!(e.contains("max 151"), "{e}");
        let e = check(&[m("b", 1, 1)], &b).unwrap_err();
        assert!(e.contains("no budget"), "{e}");
    }

    #[test]
    fn output_parses_and_checks_the_calibration() {
        let ok = "SAMPLER 15000\nCAL 154 6707 64\nI a 1 2 3 10 4\nDONE 1\n";
        let v = parse_output(ok, "t").unwrap();
        assert_eq!(
            v,
            vec![Measured {
                name: "a".into(),
                target: "t".into(),
                min: 1,
                median: 2,
                max: 3,
                calls: 10,
                worst: 4
            }]
        );
        let e = parse_output("SAMPLER 1\nCAL 154 6707 66\nDONE 0\n", "t").unwrap_err();
        assert!(e.contains("calibration"), "{e}");
        assert!(parse_output("SAMPLER x\nCAL 154 6707 64\nDONE 0\n", "t").is_err());
        assert_eq!(sampler_checked(ok), Ok(15000));
        let e = sampler_checked("CAL 154 6707 64\nI a 1 2 3 10 4\nDONE 1\n").unwrap_err();
        assert!(e.contains("entry points"), "{e}");
        assert!(sampler_checked("SAMPLER 0\n").is_err());
        assert!(parse_output("I a 1 2 3 10 4\nDONE 1\n", "t").is_err());
        assert!(parse_output("CAL 1 9 64\nI a 1 2 3 10 4\nDONE 2\n", "t").is_err());
        assert!(parse_output("CAL 1 9 64\nhello\n", "t").is_err());
        // the feed guard's line: counts, not a case
        let guard = "CAL 154 6707 64\nG guard 70 0\nDONE 0\n";
        assert_eq!(parse_output(guard, "t"), Ok(vec![]));
        assert!(parse_output("CAL 154 6707 64\nG guard x 0\nDONE 0\n", "t").is_err());
    }

    #[test]
    fn json_lists_every_case_with_its_budget() {
        let b = parse_budgets("a thumbv7m-none-eabi 100 150\n").unwrap();
        let j = counts_json(&[m("a", 90, 120), m("b", 1, 2)], &b);
        assert!(j.starts_with("[\n") && j.ends_with("]\n"));
        assert!(j.contains(
            "{\"name\": \"a\", \"target\": \"thumbv7m-none-eabi\", \"min\": 10, \"median\": 90, \"max\": 120, \"budget\": 100, \"budget_max\": 150"
        ));
        assert!(j.contains("\"budget\": null"));
        assert_eq!(j.matches("},").count(), 1);
    }

    #[test]
    fn a_worst_playback_tick_over_one_and_a_half_medians_fails() {
        let ok = [m("playback-a", 20, 30), m("deboor-b", 10, 100)];
        assert!(check_constant_time(&ok).is_ok());
        let e =
            check_constant_time(&[m("playback-a", 20, 31), m("playback-c", 7, 10)]).unwrap_err();
        assert!(e.starts_with("not constant time"), "{e}");
        assert!(
            e.contains("playback-a (thumbv7m-none-eabi): worst tick 31 > 1.5 × median 20"),
            "{e}"
        );
        assert!(!e.contains("playback-c"), "{e}");
    }

    #[test]
    fn targets_are_reported_met_or_missed() {
        let mut a = m("playback-q40-3axis-into", 110, 120);
        let mut p = m("playback-q40-3axis-position", 61, 70);
        let lines = target_report(&[a.clone(), p.clone()]);
        assert_eq!(lines.len(), 3);
        assert!(lines[0].ends_with("MISSED"), "{}", lines[0]);
        assert!(lines[1].ends_with("met"), "{}", lines[1]);
        a.target = "thumbv7em-none-eabihf".into();
        a.name = "playback-f32-3axis".into();
        a.median = 70;
        a.max = 106;
        p.target = "x".into();
        let lines = target_report(&[a.clone(), p]);
        assert!(lines.iter().any(|l| l.contains("1.5 × median: MISSED")));
        a.max = 105;
        let lines = target_report(&[a]);
        assert!(lines.iter().any(|l| l.contains("1.5 × median: met")));
        let mut o = m("online-f32-3axis", 20_001, 40_000);
        o.target = "thumbv7em-none-eabihf".into();
        let lines = target_report(&[o.clone()]);
        assert_eq!(lines.len(), 2, "{lines:?}");
        assert!(
            lines[0].ends_with("MISSED") && lines[1].ends_with("met"),
            "{lines:?}"
        );
        o.median = 20_000;
        o.max = 40_001;
        let lines = target_report(&[o]);
        assert!(
            lines[0].ends_with("met") && lines[1].ends_with("MISSED"),
            "{lines:?}"
        );
    }
}
