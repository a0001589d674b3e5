//! Stack and RAM of the firmware's operations on Cortex-M under QEMU, checked against budgets.
//!
//! The `stack` firmware (`firmware-sim/qemu/src/bin/stack.rs`, 4 MiB of RAM) and the
//! flash-playback firmware (`flash_play.rs`, the RAM of a real part) paint the unused stack,
//! run an operation and report how deep it wrote (`STACK <operation> <stack> <ram>`), the
//! sizes of the values of planning and playback (`SIZE`), and the hash of every blob and
//! G-code program they played (`H`), which must equal the hash of the host's samples.
//!
//! The budgets are checked in at `firmware-sim/qemu/stack-budgets.txt` (one line per
//! operation and target: the stack in bytes); a measured stack above its budget fails
//! `cargo xtask qemu`. `--bless` rewrites the file from the measured values with
//! [`budget::MARGIN`] of headroom. The measurements are written to `target/qemu/stack.json`.

use std::fmt::Write as _;

use strak_trajectory::NumberFormat;

use crate::budget;

/// One operation measured on one target.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Measured {
    /// Operation, e.g. `flash-play-q40`.
    pub(crate) name: String,
    /// Rust target triple.
    pub(crate) target: String,
    /// Stack high-water mark in bytes.
    pub(crate) stack: u64,
    /// RAM the firmware needed while the operation ran (statics, the stack above the
    /// measurement, the operation's stack), in bytes.
    pub(crate) ram: u64,
}

/// A blob the firmware played: its samples and the hash of their bits.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Played {
    pub(crate) job: String,
    pub(crate) format: NumberFormat,
    pub(crate) samples: u64,
    pub(crate) hash: u64,
}

/// What a stack-measuring firmware printed.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct Report {
    /// The `STACK` lines.
    pub(crate) stacks: Vec<Measured>,
    /// The `SIZE` lines: value and bytes.
    pub(crate) sizes: Vec<(String, u64)>,
    /// The `H` lines.
    pub(crate) played: Vec<Played>,
    /// The `C` lines: operation, pieces, ticks.
    pub(crate) compiled: Vec<(String, u64, u64)>,
    /// The `RAM` line: the RAM of the part.
    pub(crate) part_ram: Option<u64>,
    /// Every other line (the instruction counts: `CAL`, `I`, `DONE`), for
    /// [`crate::icount::parse_output`].
    pub(crate) rest: String,
}

/// The value of a line of `stack-budgets.txt`.
pub(crate) const FIELDS: [&str; 1] = ["stack"];

/// The header of `stack-budgets.txt`.
const HEADER: &str = "# Stack budgets in bytes per operation, measured on the core under QEMU by painting the\n\
     # stack (firmware-sim/qemu/src/stack.rs), checked by `cargo xtask qemu`: a measured\n\
     # stack above its budget fails. `cargo xtask qemu --bless` rewrites this file\n\
     # (measured + 5 %).\n\
     # name target stack\n";

/// The budget of one operation on one target: most bytes of stack it may use.
pub(crate) type Budget = budget::Budget<1>;

impl Measured {
    /// The measured stack in the shape of a budget line.
    fn line(&self) -> Budget {
        Budget {
            name: self.name.clone(),
            target: self.target.clone(),
            values: [self.stack],
        }
    }
}

/// One step of the firmware's hash (`strak_qemu::mix`): 64-bit FNV-1a-style over words.
pub(crate) fn mix(hash: u64, word: u64) -> u64 {
    (hash ^ word).wrapping_mul(0x0000_0100_0000_01b3)
}

/// The hash of a stream of sample bits, as the firmware folds it.
pub(crate) fn hash(bits: &[u64]) -> u64 {
    bits.iter().fold(0, |h, &w| mix(h, w))
}

/// Parses a stack-measuring firmware's decoded output for `target`: checks that the
/// `STACKS` count equals the `STACK` lines.
///
/// # Errors
/// A malformed `STACK`, `SIZE`, `H`, `C` or `RAM` line, a missing `STACKS` or a count that
/// differs.
pub(crate) fn parse_output(text: &str, target: &str) -> Result<Report, String> {
    let mut r = Report::default();
    let mut count = None;
    for line in text.lines() {
        let f: Vec<&str> = line.split_whitespace().collect();
        let num = |s: &str| {
            s.parse::<u64>()
                .map_err(|_| format!("`{line}`: `{s}` is not a whole number"))
        };
        match f.as_slice() {
            ["STACK", name, stack, ram] => r.stacks.push(Measured {
                name: (*name).to_owned(),
                target: target.to_owned(),
                stack: num(stack)?,
                ram: num(ram)?,
            }),
            ["SIZE", name, bytes] => r.sizes.push(((*name).to_owned(), num(bytes)?)),
            ["H", job, format, samples, hash] => r.played.push(Played {
                job: (*job).to_owned(),
                format: format
                    .parse()
                    .map_err(|e| format!("`{line}`: `{format}`: {e}"))?,
                samples: num(samples)?,
                hash: num(hash)?,
            }),
            ["C", name, pieces, ticks] => {
                r.compiled
                    .push(((*name).to_owned(), num(pieces)?, num(ticks)?));
            }
            ["RAM", bytes] => r.part_ram = Some(num(bytes)?),
            ["STACKS", n] => count = Some(num(n)?),
            ["STACK" | "SIZE" | "H" | "C" | "RAM" | "STACKS", ..] => {
                return Err(format!("malformed line: `{line}`"));
            }
            _ => {
                r.rest.push_str(line);
                r.rest.push('\n');
            }
        }
    }
    match count {
        Some(n) if usize::try_from(n).ok() == Some(r.stacks.len()) => Ok(r),
        other => Err(format!(
            "the firmware reported {other:?} stack measurements, printed {}",
            r.stacks.len()
        )),
    }
}

/// Parses the budget file (see [`crate::budget::parse`]).
///
/// # Errors
/// The first bad line.
pub(crate) fn parse_budgets(text: &str) -> Result<Vec<Budget>, String> {
    budget::parse(text, FIELDS)
}

/// The budget file for `measured`, each stack blessed ([`budget::blessed`]).
pub(crate) fn write_budgets(measured: &[Measured]) -> String {
    let lines: Vec<Budget> = measured.iter().map(Measured::line).collect();
    budget::write(HEADER, &budget::bless(&lines))
}

/// The verdict: every measured operation needs a budget, and its stack may not exceed it.
/// Lists every violation.
///
/// # Errors
/// The list of operations without a budget or over it.
pub(crate) fn check(measured: &[Measured], budgets: &[Budget]) -> Result<(), String> {
    let lines: Vec<Budget> = measured.iter().map(Measured::line).collect();
    budget::check(
        &lines,
        budgets,
        FIELDS,
        "bytes",
        "stack (stack-budgets.txt)",
    )
}

/// `stack.json`: the operations (`name`, `target`, `stack`, `ram`, `budget`) and the sizes
/// of the values (`name`, `target`, `bytes`).
pub(crate) fn stack_json(
    measured: &[Measured],
    budgets: &[Budget],
    sizes: &[(String, String, u64)],
) -> String {
    let mut s = String::from("{\n  \"operations\": [\n");
    for (i, m) in measured.iter().enumerate() {
        let b = budget::find(budgets, &m.name, &m.target)
            .map_or_else(|| "null".to_owned(), |b| b.values[0].to_string());
        let _ = writeln!(
            s,
            "    {{\"name\": \"{}\", \"target\": \"{}\", \"stack\": {}, \"ram\": {}, \
             \"budget\": {b}, \"unit\": \"bytes\"}}{}",
            m.name,
            m.target,
            m.stack,
            m.ram,
            if i + 1 < measured.len() { "," } else { "" }
        );
    }
    s.push_str("  ],\n  \"sizes\": [\n");
    for (i, (name, target, bytes)) in sizes.iter().enumerate() {
        let _ = writeln!(
            s,
            "    {{\"name\": \"{name}\", \"target\": \"{target}\", \"bytes\": {bytes}}}{}",
            if i + 1 < sizes.len() { "," } else { "" }
        );
    }
    s.push_str("  ]\n}\n");
    s
}

/// The stack target: validating and playing a 256-piece 3-axis Q40 blob from flash
/// (the flash-playback firmware's operation) in at most this many bytes of stack, on every
/// core.
pub(crate) const FLASH_PLAY_TARGET: u64 = 2048;

/// The stack target of the flash-playback firmware, one line per target with `met` /
/// `MISSED` (reported, not enforced: the budgets are the check).
pub(crate) fn target_report(measured: &[Measured]) -> Vec<String> {
    measured
        .iter()
        .filter(|m| m.name == "flash-play-q40")
        .map(|m| {
            format!(
                "{}: validate and play a 256-piece 3-axis Q40 blob from flash: stack {} ≤ {}: {}",
                m.target,
                m.stack,
                FLASH_PLAY_TARGET,
                if m.stack <= FLASH_PLAY_TARGET {
                    "met"
                } else {
                    "MISSED"
                }
            )
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn m(name: &str, stack: u64) -> Measured {
        Measured {
            name: name.to_owned(),
            target: "thumbv7m-none-eabi".to_owned(),
            stack,
            ram: stack + 100,
        }
    }

    #[test]
    fn output_parses_and_keeps_the_other_lines() {
        let text = "CAL 154 6707 64\nSIZE Path<Q40,3,256> 57400\nSTACK load-play-q40 1200 70000\n\
                    H pick-and-place Q40 1003 42\nC compile-x 50 2500\nI a 1 1 1 1 0\n\
                    STACKS 1\nDONE 1\n";
        let r = parse_output(text, "t").unwrap();
        assert_eq!(
            r.stacks,
            vec![Measured {
                name: "load-play-q40".into(),
                target: "t".into(),
                stack: 1200,
                ram: 70000
            }]
        );
        assert_eq!(r.sizes, vec![("Path<Q40,3,256>".to_owned(), 57400)]);
        assert_eq!(
            r.played,
            vec![Played {
                job: "pick-and-place".into(),
                format: NumberFormat::Q40,
                samples: 1003,
                hash: 42
            }]
        );
        assert_eq!(r.compiled, vec![("compile-x".to_owned(), 50, 2500)]);
        assert_eq!(r.part_ram, None);
        assert_eq!(r.rest, "CAL 154 6707 64\nI a 1 1 1 1 0\nDONE 1\n");
    }

    #[test]
    fn bad_output_is_an_error() {
        assert!(parse_output("STACK a 1\nSTACKS 1\n", "t").is_err());
        assert!(parse_output("STACK a 1 x\nSTACKS 1\n", "t").is_err());
        let e = parse_output("STACK a 1 2\n", "t").unwrap_err();
        assert!(e.contains("None"), "{e}");
        assert!(parse_output("STACK a 1 2\nSTACKS 2\n", "t").is_err());
        assert_eq!(
            parse_output("RAM 65536\nSTACKS 0\n", "t").unwrap().part_ram,
            Some(65536)
        );
    }

    #[test]
    fn budgets_round_trip_with_the_header() {
        let written = write_budgets(&[m("x", 1000), m("y", 1)]);
        assert!(written.starts_with("# Stack budgets"), "{written}");
        let back = parse_budgets(&written).unwrap();
        assert_eq!((back[0].values, back[1].values), ([1050], [2]));
        assert!(parse_budgets("a t\n").unwrap_err().contains("line 1"));
    }

    #[test]
    fn verdict_names_the_operation_the_measured_and_the_budget() {
        let b = parse_budgets("a thumbv7m-none-eabi 2048\n").unwrap();
        assert!(check(&[m("a", 2048)], &b).is_ok());
        let e = check(&[m("a", 2049)], &b).unwrap_err();
        assert!(
            e.contains("a (thumbv7m-none-eabi): stack 2049 bytes > budget 2048 bytes"),
            "{e}"
        );
        let e = check(&[m("b", 1)], &b).unwrap_err();
        assert!(e.contains("b (thumbv7m-none-eabi): no budget"), "{e}");
    }

    #[test]
    fn the_flash_target_is_reported_met_or_missed() {
        let lines = target_report(&[m("flash-play-q40", 2048), m("x", 1)]);
        assert_eq!(lines.len(), 1);
        assert!(lines[0].ends_with("stack 2048 ≤ 2048: met"), "{}", lines[0]);
        let lines = target_report(&[m("flash-play-q40", 2536)]);
        assert!(
            lines[0].ends_with("stack 2536 ≤ 2048: MISSED"),
            "{}",
            lines[0]
        );
    }

    #[test]
    fn hash_folds_every_word_in_order() {
        assert_eq!(hash(&[]), 0);
        assert_eq!(hash(&[1]), 0x0000_0100_0000_01b3);
        assert_ne!(hash(&[1, 2]), hash(&[2, 1]));
        assert_eq!(hash(&[1, 2]), mix(mix(0, 1), 2));
    }

    #[test]
    fn json_lists_operations_with_budgets_and_sizes() {
        let b = parse_budgets("a thumbv7m-none-eabi 2048\n").unwrap();
        let j = stack_json(
            &[m("a", 1000), m("b", 5)],
            &b,
            &[("Path".into(), "t".into(), 9)],
        );
        assert!(j.contains(
            "{\"name\": \"a\", \"target\": \"thumbv7m-none-eabi\", \"stack\": 1000, \"ram\": 1100, \"budget\": 2048"
        ));
        assert!(j.contains("\"budget\": null"));
        assert!(j.contains("{\"name\": \"Path\", \"target\": \"t\", \"bytes\": 9}"));
        assert!(j.ends_with("  ]\n}\n"));
    }
}
