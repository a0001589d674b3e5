//! The checked-in budget files of `cargo xtask qemu`: one line per measured item and target,
//! `name target value…` (`# comments` and blank lines allowed), the values in a fixed order
//! per file.
//!
//! - `icount-budgets.txt`: `name target median max` (instructions, [`crate::icount`]);
//! - `stack-budgets.txt`: `name target stack` (bytes, [`crate::stack`]);
//! - `sizes.txt`: `name target text data bss` (bytes, [`crate::size`]).
//!
//! A measured value above its budget fails ([`check`]); `--bless` rewrites a budget file from
//! the measured values with [`MARGIN`] of headroom ([`blessed`], [`write()`]).

use std::fmt::Write as _;

/// Headroom of blessed budgets over the measured values.
pub(crate) const MARGIN: f64 = 0.05;

/// One line of a budget file: an item on a target and its `N` values.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Budget<const N: usize> {
    /// The measured item (case, operation or binary).
    pub(crate) name: String,
    /// Rust target triple.
    pub(crate) target: String,
    /// The values, in the order of the file's fields.
    pub(crate) values: [u64; N],
}

/// An item as measured: the same shape as its budget line.
pub(crate) type Measured<const N: usize> = Budget<N>;

/// Parses a budget file whose lines are `name target` and one value per entry of `fields`.
///
/// # Errors
/// The first bad line, named by its number: another number of fields, a value that is not a
/// whole number, or an item and target given twice.
pub(crate) fn parse<const N: usize>(
    text: &str,
    fields: [&str; N],
) -> Result<Vec<Budget<N>>, String> {
    let mut out: Vec<Budget<N>> = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let b = parse_line(line, fields).map_err(|e| format!("line {}: {e}", i + 1))?;
        if find(&out, &b.name, &b.target).is_some() {
            return Err(format!("line {}: {} {} twice", i + 1, b.name, b.target));
        }
        out.push(b);
    }
    Ok(out)
}

/// One line `name target value…` (trimmed, not a comment).
fn parse_line<const N: usize>(line: &str, fields: [&str; N]) -> Result<Budget<N>, String> {
    let words: Vec<&str> = line.split_whitespace().collect();
    let (Some(name), Some(target), values) = (words.first(), words.get(1), words.get(2..)) else {
        return Err(format!(
            "expected `name target {}`, found `{line}`",
            fields.join(" ")
        ));
    };
    let Some(values) = values.filter(|v| v.len() == N) else {
        return Err(format!(
            "expected `name target {}`, found `{line}`",
            fields.join(" ")
        ));
    };
    let mut out = [0_u64; N];
    for ((slot, word), field) in out.iter_mut().zip(values).zip(fields) {
        *slot = word
            .parse::<u64>()
            .map_err(|_| format!("{field} `{word}` is not a whole number"))?;
    }
    Ok(Budget {
        name: (*name).to_owned(),
        target: (*target).to_owned(),
        values: out,
    })
}

/// The budget of `name` on `target`.
pub(crate) fn find<'b, const N: usize>(
    budgets: &'b [Budget<N>],
    name: &str,
    target: &str,
) -> Option<&'b Budget<N>> {
    budgets
        .iter()
        .find(|b| b.name == name && b.target == target)
}

/// The budget a bless writes for a measured value: the value with [`MARGIN`] of headroom,
/// rounded up.
pub(crate) fn blessed(measured: u64) -> u64 {
    (measured as f64 * (1.0 + MARGIN)).ceil() as u64
}

/// A budget file: `header` (comment lines, each ending in a newline), then one line per
/// entry of `lines`, its values written as given.
pub(crate) fn write<const N: usize>(header: &str, lines: &[Budget<N>]) -> String {
    let mut s = header.to_owned();
    for b in lines {
        let _ = write!(s, "{} {}", b.name, b.target);
        for v in b.values {
            let _ = write!(s, " {v}");
        }
        s.push('\n');
    }
    s
}

/// The budget lines a bless writes for `measured`: every value [`blessed`].
pub(crate) fn bless<const N: usize>(measured: &[Measured<N>]) -> Vec<Budget<N>> {
    measured
        .iter()
        .map(|m| Budget {
            values: m.values.map(blessed),
            ..m.clone()
        })
        .collect()
}

/// The verdict: every measured item needs a budget line, none of its values may exceed the
/// budget's, and every budget line needs a measured item (a line nothing measures gates
/// nothing). `fields` names the values, `unit` their unit, `what` the file (for the
/// message). Lists every violation.
///
/// # Errors
/// The list of items without a budget or over it, and of budgets without an item.
pub(crate) fn check<const N: usize>(
    measured: &[Measured<N>],
    budgets: &[Budget<N>],
    fields: [&str; N],
    unit: &str,
    what: &str,
) -> Result<(), String> {
    let mut bad = Vec::new();
    for m in measured {
        let Some(b) = find(budgets, &m.name, &m.target) else {
            bad.push(format!(
                "{} ({}): no budget (add a line, or run `cargo xtask qemu --bless`)",
                m.name, m.target
            ));
            continue;
        };
        for ((field, v), limit) in fields.iter().zip(m.values).zip(b.values) {
            if v > limit {
                bad.push(format!(
                    "{} ({}): {field} {v} {unit} > budget {limit} {unit}",
                    m.name, m.target
                ));
            }
        }
    }
    for b in budgets {
        if find(measured, &b.name, &b.target).is_none() {
            bad.push(format!(
                "{} ({}): a budget, but not measured (remove the line, or run \
                 `cargo xtask qemu --bless`)",
                b.name, b.target
            ));
        }
    }
    if bad.is_empty() {
        Ok(())
    } else {
        Err(format!("{what} over budget:\n  {}", bad.join("\n  ")))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn b(name: &str, values: [u64; 2]) -> Budget<2> {
        Budget {
            name: name.to_owned(),
            target: "thumbv7m-none-eabi".to_owned(),
            values,
        }
    }

    const FIELDS: [&str; 2] = ["median", "max"];

    #[test]
    fn lines_parse_around_comments_and_blanks() {
        let text = "# c\n\na thumbv7m-none-eabi 120 200\n  x t 1 2  \n";
        let v = parse(text, FIELDS).unwrap();
        assert_eq!(v[0], b("a", [120, 200]));
        assert_eq!((v[1].name.as_str(), v[1].target.as_str()), ("x", "t"));
        assert_eq!(v[1].values, [1, 2]);
    }

    #[test]
    fn a_malformed_line_is_an_error_naming_the_line() {
        let e = parse("# c\na t 1\n", FIELDS).unwrap_err();
        assert_eq!(
            e,
            "line 2: expected `name target median max`, found `a t 1`"
        );
        let e = parse("a t 1 2 3\n", FIELDS).unwrap_err();
        assert!(e.starts_with("line 1: expected"), "{e}");
        let e = parse("a\n", FIELDS).unwrap_err();
        assert!(e.starts_with("line 1: expected"), "{e}");
        let e = parse("\n\n\na t 1 x\n", FIELDS).unwrap_err();
        assert_eq!(e, "line 4: max `x` is not a whole number");
        let e = parse("a t -1 2\n", FIELDS).unwrap_err();
        assert_eq!(e, "line 1: median `-1` is not a whole number");
        let e = parse("a t 1 2\nb t 1 2\na t 3 4\n", FIELDS).unwrap_err();
        assert_eq!(e, "line 3: a t twice");
        // The same item on another target is not a duplicate.
        assert_eq!(parse("a t 1 2\na u 1 2\n", FIELDS).unwrap().len(), 2);
    }

    #[test]
    fn blessing_adds_five_percent_rounded_up() {
        assert_eq!(blessed(100), 105);
        assert_eq!(blessed(1000), 1050);
        assert_eq!(blessed(1), 2);
        assert_eq!(blessed(0), 0);
        assert_eq!(blessed(2781), 2921);
    }

    #[test]
    fn a_blessed_file_reads_back() {
        let text = write("# h\n", &bless(&[b("a", [100, 200]), b("c", [1, 0])]));
        assert_eq!(
            text,
            "# h\na thumbv7m-none-eabi 105 210\nc thumbv7m-none-eabi 2 0\n"
        );
        let back = parse(&text, FIELDS).unwrap();
        assert_eq!(back, vec![b("a", [105, 210]), b("c", [2, 0])]);
    }

    #[test]
    fn the_verdict_names_the_item_the_field_the_value_and_the_budget() {
        let budgets = vec![b("a", [100, 150])];
        assert!(check(&[b("a", [100, 150])], &budgets, FIELDS, "instr", "counts").is_ok());
        let e = check(&[b("a", [101, 150])], &budgets, FIELDS, "instr", "counts").unwrap_err();
        assert_eq!(
            e,
            "counts over budget:\n  a (thumbv7m-none-eabi): median 101 instr > budget 100 instr"
        );
        let e = check(&[b("a", [90, 151])], &budgets, FIELDS, "instr", "counts").unwrap_err();
        assert!(e.contains("max 151 instr > budget 150 instr"), "{e}");
        let e = check(&[b("z", [1, 1])], &budgets, FIELDS, "instr", "counts").unwrap_err();
        assert!(e.contains("z (thumbv7m-none-eabi): no budget"), "{e}");
        let mut other = b("a", [1, 1]);
        other.target = "thumbv7em-none-eabihf".to_owned();
        assert!(check(&[other], &budgets, FIELDS, "instr", "counts").is_err());
    }

    #[test]
    fn a_budget_nothing_measured_fails() {
        let budgets = vec![b("a", [100, 150]), b("gone", [1, 1])];
        let e = check(&[b("a", [100, 150])], &budgets, FIELDS, "instr", "counts").unwrap_err();
        assert_eq!(
            e,
            "counts over budget:\n  gone (thumbv7m-none-eabi): a budget, but not measured \
             (remove the line, or run `cargo xtask qemu --bless`)"
        );
    }
}
