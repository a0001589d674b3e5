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
//! [`MARGIN`] of headroom. The measured counts are written to `target/qemu/counts.json`.

use std::fmt::Write as _;

/// The `-icount` shift the firmware's conversion assumes (`strak_qemu::counter::ICOUNT_SHIFT`).
pub(crate) const ICOUNT_SHIFT: u32 = 10;

/// Headroom of blessed budgets over the measured counts.
pub(crate) const MARGIN: f64 = 0.05;

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

/// The budget of one case on one target.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Budget {
    pub(crate) name: String,
    pub(crate) target: String,
    /// Most instructions the median may take.
    pub(crate) median: u64,
    /// Most instructions the worst call may take.
    pub(crate) max: u64,
}

/// Parses the budget file: `# comments`, blank lines, and lines `name target median max`.
///
/// # Errors
/// A line with another number of fields, a count that is not an integer, or a duplicate.
pub(crate) fn parse_budgets(text: &str) -> Result<Vec<Budget>, String> {
    let mut out: Vec<Budget> = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let f: Vec<&str> = line.split_whitespace().collect();
        let [name, target, median, max] = f.as_slice() else {
            return Err(format!(
                "line {}: expected `name target median max`, found `{line}`",
                i + 1
            ));
        };
        let num = |s: &str| {
            s.parse::<u64>()
                .map_err(|_| format!("line {}: `{s}` is not a whole number", i + 1))
        };
        let b = Budget {
            name: (*name).to_owned(),
            target: (*target).to_owned(),
            median: num(median)?,
            max: num(max)?,
        };
        if out.iter().any(|o| o.name == b.name && o.target == b.target) {
            return Err(format!("line {}: {} {} twice", i + 1, b.name, b.target));
        }
        out.push(b);
    }
    Ok(out)
}

/// The budget file for `measured`, each count with [`MARGIN`] of headroom (rounded up).
pub(crate) fn write_budgets(measured: &[Measured]) -> String {
    let mut s = String::from(
        "# Instruction budgets per call (instruction counts under QEMU -icount, NOT cycles),\n\
         # checked by `cargo xtask qemu`: a measured median or max above its budget fails.\n\
         # `cargo xtask qemu --bless` rewrites this file (measured + 5 %).\n\
         # name target median max\n",
    );
    let up = |x: u64| (x as f64 * (1.0 + MARGIN)).ceil() as u64;
    for m in measured {
        let _ = writeln!(s, "{} {} {} {}", m.name, m.target, up(m.median), up(m.max));
    }
    s
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

/// The verdict: every measured case needs a budget, and neither its median nor its max may
/// exceed it. Lists every violation.
///
/// # Errors
/// The list of cases without a budget or over it.
pub(crate) fn check(measured: &[Measured], budgets: &[Budget]) -> Result<(), String> {
    let mut bad = Vec::new();
    for m in measured {
        match budgets
            .iter()
            .find(|b| b.name == m.name && b.target == m.target)
        {
            None => bad.push(format!(
                "{} ({}): no budget (add a line, or run `cargo xtask qemu --bless`)",
                m.name, m.target
            )),
            Some(b) => {
                if m.median > b.median {
                    bad.push(format!(
                        "{} ({}): median {} instructions > budget {}",
                        m.name, m.target, m.median, b.median
                    ));
                }
                if m.max > b.max {
                    bad.push(format!(
                        "{} ({}): max {} instructions > budget {}",
                        m.name, m.target, m.max, b.max
                    ));
                }
            }
        }
    }
    if bad.is_empty() {
        Ok(())
    } else {
        Err(format!(
            "instruction counts over budget (instruction counts, not cycles):\n  {}",
            bad.join("\n  ")
        ))
    }
}

/// `counts.json`: a list of `{"name", "target", "min", "median", "max", "budget",
/// "budget_max", "calls"}` (`budget`: the median's budget; `null` without one).
pub(crate) fn counts_json(measured: &[Measured], budgets: &[Budget]) -> String {
    let mut s = String::from("[\n");
    for (i, m) in measured.iter().enumerate() {
        let b = budgets
            .iter()
            .find(|b| b.name == m.name && b.target == m.target);
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
            opt(b.map(|b| b.median)),
            opt(b.map(|b| b.max)),
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

const TARGETS: [Target; 4] = [
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
        case: "playback-q40-3axis",
        target: "thumbv7m-none-eabi",
        limit: 110,
        what: "Cortex-M3, 3-axis fixed-point, position, velocity, acceleration",
    },
];

/// The targets, one line each, with `met` / `MISSED` (reported, not enforced: the
/// budgets are the check).
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
    if let Some(m) = find("playback-f32-3axis", "thumbv7em-none-eabihf") {
        let ok = 2 * m.max <= 3 * m.median;
        lines.push(format!(
            "Cortex-M4F, 3-axis f32: worst tick {} ≤ 1.5 × median {}: {}",
            m.max,
            m.median,
            if ok { "met" } else { "MISSED" }
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
    fn budgets_parse_and_round_trip() {
        let text = "# c\n\nplayback-q40-3axis thumbv7m-none-eabi 120 200\n  a t 1 2  \n";
        let b = parse_budgets(text).unwrap();
        assert_eq!(b.len(), 2);
        assert_eq!(
            b[0],
            Budget {
                name: "playback-q40-3axis".into(),
                target: "thumbv7m-none-eabi".into(),
                median: 120,
                max: 200
            }
        );
        let written = write_budgets(&[m("x", 100, 200)]);
        let back = parse_budgets(&written).unwrap();
        assert_eq!((back[0].median, back[0].max), (105, 210));
    }

    #[test]
    fn bad_budget_lines_are_errors() {
        assert!(parse_budgets("a t 1\n").unwrap_err().contains("line 1"));
        assert!(parse_budgets("a t 1 x\n").unwrap_err().contains("`x`"));
        assert!(
            parse_budgets("a t 1 2\na t 3 4\n")
                .unwrap_err()
                .contains("twice")
        );
    }

    #[test]
    fn verdict_fails_over_budget_and_without_budget() {
        let b = parse_budgets("a thumbv7m-none-eabi 100 150\n").unwrap();
        assert!(check(&[m("a", 100, 150)], &b).is_ok());
        let e = check(&[m("a", 101, 150)], &b).unwrap_err();
        assert!(e.contains("median 101 instructions > budget 100"), "{e}");
        let e = check(&[m("a", 90, 151)], &b).unwrap_err();
        assert!(e.contains("max 151"), "{e}");
        let e = check(&[m("b", 1, 1)], &b).unwrap_err();
        assert!(e.contains("no budget"), "{e}");
    }

    #[test]
    fn output_parses_and_checks_the_calibration() {
        let ok = "CAL 154 6707 64\nI a 1 2 3 10 4\nDONE 1\n";
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
        let e = parse_output("CAL 154 6707 66\nDONE 0\n", "t").unwrap_err();
        assert!(e.contains("calibration"), "{e}");
        assert!(parse_output("I a 1 2 3 10 4\nDONE 1\n", "t").is_err());
        assert!(parse_output("CAL 1 9 64\nI a 1 2 3 10 4\nDONE 2\n", "t").is_err());
        assert!(parse_output("CAL 1 9 64\nhello\n", "t").is_err());
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
    fn targets_are_reported_met_or_missed() {
        let mut a = m("playback-q40-3axis", 110, 120);
        let mut p = m("playback-q40-3axis-position", 61, 70);
        let lines = target_report(&[a.clone(), p.clone()]);
        assert_eq!(lines.len(), 2);
        assert!(lines[0].ends_with("MISSED"), "{}", lines[0]);
        assert!(lines[1].ends_with("met"), "{}", lines[1]);
        a.target = "thumbv7em-none-eabihf".into();
        a.name = "playback-f32-3axis".into();
        a.median = 70;
        a.max = 106;
        p.target = "x".into();
        let lines = target_report(&[a, p]);
        assert!(lines.iter().any(|l| l.contains("1.5 × median 70: MISSED")));
    }
}
