//! Stack and RAM of the firmware's operations on Cortex-M under QEMU, checked against budgets.
//!
//! The `stack` firmware (`firmware-sim/qemu/src/bin/stack.rs`, 4 MiB of RAM) and the
//! flash-playback firmware (`flash_play.rs`, the RAM of a real part) paint the unused stack,
//! run an operation and report how deep it wrote (`STACK <operation> <stack> <ram>`), the
//! sizes of the values of planning and playback (`SIZE`), and the hash of every blob they
//! played (`H`), which must equal the hash of the host's samples.
//!
//! The budgets are checked in at `firmware-sim/qemu/stack-budgets.txt` (one line per
//! operation and target: the stack in bytes); a measured stack above its budget fails
//! `cargo xtask qemu`. `--bless` rewrites the file from the measured values with [`MARGIN`]
//! of headroom. The measurements are written to `target/qemu/stack.json`.

use std::fmt::Write as _;

/// Headroom of blessed budgets over the measured stack.
pub(crate) const MARGIN: f64 = 0.05;

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
    pub(crate) format: String,
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

/// The budget of one operation on one target.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Budget {
    pub(crate) name: String,
    pub(crate) target: String,
    /// Most bytes of stack the operation may use.
    pub(crate) stack: u64,
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
                format: (*format).to_owned(),
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

/// Parses the budget file: `# comments`, blank lines, and lines `name target stack`.
///
/// # Errors
/// A line with another number of fields, a size that is not an integer, or a duplicate.
pub(crate) fn parse_budgets(text: &str) -> Result<Vec<Budget>, String> {
    let mut out: Vec<Budget> = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let f: Vec<&str> = line.split_whitespace().collect();
        let [name, target, stack] = f.as_slice() else {
            return Err(format!(
                "line {}: expected `name target stack`, found `{line}`",
                i + 1
            ));
        };
        let b = Budget {
            name: (*name).to_owned(),
            target: (*target).to_owned(),
            stack: stack
                .parse::<u64>()
                .map_err(|_| format!("line {}: `{stack}` is not a whole number", i + 1))?,
        };
        if out.iter().any(|o| o.name == b.name && o.target == b.target) {
            return Err(format!("line {}: {} {} twice", i + 1, b.name, b.target));
        }
        out.push(b);
    }
    Ok(out)
}

/// The budget file for `measured`, each stack with [`MARGIN`] of headroom (rounded up).
pub(crate) fn write_budgets(measured: &[Measured]) -> String {
    let mut s = String::from(
        "# Stack budgets in bytes per operation, measured on the core under QEMU by painting the\n\
         # stack (firmware-sim/qemu/src/stack.rs), checked by `cargo xtask qemu`: a measured\n\
         # stack above its budget fails. `cargo xtask qemu --bless` rewrites this file\n\
         # (measured + 5 %).\n\
         # name target stack\n",
    );
    for m in measured {
        let up = (m.stack as f64 * (1.0 + MARGIN)).ceil() as u64;
        let _ = writeln!(s, "{} {} {up}", m.name, m.target);
    }
    s
}

/// The verdict: every measured operation needs a budget, and its stack may not exceed it.
/// Lists every violation.
///
/// # Errors
/// The list of operations without a budget or over it.
pub(crate) fn check(measured: &[Measured], budgets: &[Budget]) -> Result<(), String> {
    let mut bad = Vec::new();
    for m in measured {
        match budgets
            .iter()
            .find(|b| b.name == m.name && b.target == m.target)
        {
            None => bad.push(format!(
                "{} ({}): no stack budget (add a line, or run `cargo xtask qemu --bless`)",
                m.name, m.target
            )),
            Some(b) if m.stack > b.stack => bad.push(format!(
                "{} ({}): stack {} bytes > budget {} bytes",
                m.name, m.target, m.stack, b.stack
            )),
            Some(_) => {}
        }
    }
    if bad.is_empty() {
        Ok(())
    } else {
        Err(format!(
            "stack over budget (stack-budgets.txt):\n  {}",
            bad.join("\n  ")
        ))
    }
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
        let b = budgets
            .iter()
            .find(|b| b.name == m.name && b.target == m.target)
            .map_or_else(|| "null".to_owned(), |b| b.stack.to_string());
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
                    H pick-and-place fixed 1003 42\nC compile-x 50 2500\nI a 1 1 1 1 0\n\
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
                format: "fixed".into(),
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
    fn budgets_parse_and_round_trip() {
        let b = parse_budgets("# c\n\nflash-play-q40 thumbv7m-none-eabi 2048\n").unwrap();
        assert_eq!(
            b,
            vec![Budget {
                name: "flash-play-q40".into(),
                target: "thumbv7m-none-eabi".into(),
                stack: 2048
            }]
        );
        let back = parse_budgets(&write_budgets(&[m("x", 1000), m("y", 1)])).unwrap();
        assert_eq!((back[0].stack, back[1].stack), (1050, 2));
        assert!(parse_budgets("a t\n").unwrap_err().contains("line 1"));
        assert!(parse_budgets("a t x\n").unwrap_err().contains("`x`"));
        assert!(
            parse_budgets("a t 1\na t 2\n")
                .unwrap_err()
                .contains("twice")
        );
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
        assert!(e.contains("b (thumbv7m-none-eabi): no stack budget"), "{e}");
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
