//! Naming the field of a toml error in the curve and job files.
//!
//! toml reports a type or range error with the span of the offending value, so the key of that
//! line (and the table the line is in) names the field. Tables tagged by `kind` (the curve, the
//! time law) are buffered by serde before the variant is chosen and lose the spans of their
//! values: an error inside one carries the span of the whole table, or none. For those the
//! table is deserialized once more into the chosen variant's own struct, which keeps its
//! spans.

/// A field and what is wrong with it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Located {
    /// The field's path (`limits.velocity`, `events[1].feed`, `path.degree`, or `job` when
    /// no field can be named).
    pub field: String,
    /// toml's or serde's message (its first line), prefixed by the line number when known.
    pub message: String,
}

/// Deserializes a tagged table's content (without its `kind`) into the struct of variant
/// `kind`; the error, if any.
pub type Diagnose = fn(kind: &str, text: &str) -> Option<toml::de::Error>;

/// A table tagged by `kind`: its path (`""`: the whole file) and how to diagnose it.
#[derive(Clone, Copy, Debug)]
pub struct Tagged {
    /// The table's path, `""` for the top level.
    pub table: &'static str,
    /// The variant's own deserialization.
    pub diagnose: Diagnose,
}

/// `table.key`, or `key` at the top level.
pub fn join(table: &str, key: &str) -> String {
    if table.is_empty() {
        key.to_owned()
    } else {
        format!("{table}.{key}")
    }
}

/// A key as TOML spells it: bare (`rate_hz`) when it may be, else a quoted string (`""`,
/// `" "`, `"a.b"`), with `"`, `\` and control characters escaped.
fn toml_key(key: &str) -> String {
    let bare = |c: char| c.is_ascii_alphanumeric() || c == '_' || c == '-';
    if !key.is_empty() && key.chars().all(bare) {
        return key.to_owned();
    }
    let mut quoted = String::from("\"");
    for c in key.chars() {
        match c {
            '"' => quoted.push_str("\\\""),
            '\\' => quoted.push_str("\\\\"),
            c if c.is_control() => quoted.push_str(&format!("\\u{:04X}", u32::from(c))),
            c => quoted.push(c),
        }
    }
    quoted.push('"');
    quoted
}

fn first_line(e: &toml::de::Error) -> String {
    e.message()
        .trim()
        .lines()
        .next()
        .unwrap_or_default()
        .to_owned()
}

/// The name quoted after `prefix` in `msg` (`missing field `x``: `x`).
fn quoted(msg: &str, prefix: &str) -> Option<String> {
    msg.strip_prefix(prefix)
        .and_then(|r| r.split('`').next())
        .map(str::to_owned)
}

/// The table the line ending at `end` belongs to, from the headers up to and including it
/// (`limits`, `events[2]`, or "" at the top).
fn table_at(text: &str, end: usize) -> String {
    let mut table = String::new();
    let mut counts: Vec<(String, usize)> = Vec::new();
    for line in text[..end].lines() {
        let l = line.trim();
        if let Some(name) = l.strip_prefix("[[").and_then(|r| r.split("]]").next()) {
            let name = name.trim().to_owned();
            let index = match counts.iter_mut().find(|(n, _)| *n == name) {
                Some((_, count)) => {
                    *count += 1;
                    *count - 1
                }
                None => {
                    counts.push((name.clone(), 1));
                    0
                }
            };
            table = format!("{name}[{index}]");
        } else if let Some(name) = l.strip_prefix('[').and_then(|r| r.split(']').next()) {
            table = name.trim().to_owned();
        }
    }
    table
}

/// The line of `text` around byte `start`: its number (from 1), its end and its key (if it is
/// a `key = value` line).
fn line_at(text: &str, start: usize) -> (usize, usize, Option<String>) {
    let start = start.min(text.len());
    let number = text[..start].matches('\n').count() + 1;
    let begin = text[..start].rfind('\n').map_or(0, |i| i + 1);
    let end = text[start..].find('\n').map_or(text.len(), |i| start + i);
    let key = text[begin..end]
        .split_once('=')
        .map(|(k, _)| k.trim())
        .filter(|k| !k.is_empty() && !k.starts_with('['))
        .map(str::to_owned);
    (number, end, key)
}

/// The field of a tagged table's error, from its own deserialization.
fn diagnose(text: &str, tagged: &Tagged) -> Option<Located> {
    let doc: toml::Table = toml::from_str(text).ok()?;
    let mut table = if tagged.table.is_empty() {
        doc
    } else {
        doc.get(tagged.table)?.as_table()?.clone()
    };
    let kind = table.remove("kind")?.as_str()?.to_owned();
    let content = toml::to_string(&table).ok()?;
    let e = (tagged.diagnose)(&kind, &content)?;
    let msg = first_line(&e);
    let key = quoted(&msg, "missing field `")
        .or_else(|| quoted(&msg, "unknown field `"))
        .or_else(|| e.span().and_then(|s| line_at(&content, s.start).2));
    Some(Located {
        field: key.map_or_else(|| tagged.table.to_owned(), |k| join(tagged.table, &k)),
        message: msg,
    })
}

/// The field `e` is about, in the file `text` whose tables `tagged` are tagged by `kind`.
pub fn locate(text: &str, e: &toml::de::Error, tagged: &[Tagged]) -> Located {
    let msg = first_line(e);
    let (number, table, key) = match e.span() {
        // An empty span at the start: the whole document.
        Some(span) if span.is_empty() => (None, String::new(), None),
        Some(span) => {
            let (number, end, key) = line_at(text, span.start);
            (Some(number), table_at(text, end), key)
        }
        None => (None, String::new(), None),
    };
    // A whole tagged table (its header, or an inline table's key) or an error without a
    // place: ask the variant.
    let whole = key.as_deref().map_or(table.clone(), |k| join(&table, k));
    if let Some(found) = tagged
        .iter()
        .filter(|t| t.table == whole || e.span().is_none())
        .find_map(|t| diagnose(text, t))
    {
        return found;
    }
    let with_line = |m: String| match number {
        Some(n) => format!("line {n}: {m}"),
        None => m,
    };
    if let Some(field) = quoted(&msg, "missing field `") {
        return Located {
            field: join(&whole, &field),
            message: msg,
        };
    }
    if let Some(field) = quoted(&msg, "unknown field `") {
        return Located {
            field: join(&table, &toml_key(&field)),
            message: with_line(msg),
        };
    }
    let field = if whole.is_empty() {
        "job".to_owned()
    } else {
        whole
    };
    Located {
        field,
        message: with_line(msg),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_and_tables() {
        let text = "a = 1\n[t]\nb = 2\n[[e]]\nc = 3\n[[e]]\nd = 4\n";
        assert_eq!(line_at(text, 0), (1, 5, Some("a".to_owned())));
        assert_eq!(table_at(text, 5), "");
        let d = text.find("d =").unwrap();
        let (n, end, key) = line_at(text, d);
        assert_eq!((n, key.as_deref()), (7, Some("d")));
        assert_eq!(table_at(text, end), "e[1]");
        let header = text.find("[t]").unwrap();
        let (_, end, key) = line_at(text, header);
        assert_eq!((key, table_at(text, end)), (None, "t".to_owned()));
        assert_eq!(join("", "x"), "x");
        assert_eq!(join("t", "x"), "t.x");
    }

    #[test]
    fn an_unknown_key_is_named_as_toml_spells_it() {
        #[derive(Debug, serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        #[allow(dead_code)]
        struct T {
            a: Option<i32>,
        }
        let cases = [
            ("\"\" = 1\n", "\"\""),
            ("'' = 1\n", "\"\""),
            ("\" \" = \"\"\n", "\" \""),
            ("\"a.b\" = 1\n", "\"a.b\""),
            ("\"q\\\"\\\\\\t\" = 1\n", "\"q\\\"\\\\\\u0009\""),
            ("b-c_1 = 1\n", "b-c_1"),
        ];
        for (text, name) in cases {
            let e = toml::from_str::<T>(text).unwrap_err();
            let at = locate(text, &e, &[]);
            assert_eq!(at.field, name, "{text}: {}", at.message);
        }
    }
}
