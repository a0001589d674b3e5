//! The crate is laid out by pipeline stage, and data flows one way through the stages:
//! `error` and `num` (the number formats), then `online` (the state-to-state solver, which
//! the planner uses between zones), `path` (what a compiled path is), `plan` (limits and time
//! laws), `stream` (moves and their corner blends), `compile` (plan → path), `play` (the
//! sampler and its kernels).
//! A module of one layer names only its own layer and the layers before it, outside its
//! `#[cfg(test)]` items (tests may use the whole pipeline). Inside `plan`, whose modules
//! once formed a circle, the modules are ordered as well (`PLAN_ORDER`).
//!
//! The check reads the source tree, strips comments, string literals and `#[cfg(test)]`
//! items, and resolves every `crate::…` path (and every `super::…` chain that climbs to the
//! crate root) to the layer of the module or public item it names.

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};

/// The layers in the order data flows through them, with their rank (a layer may name the
/// layers of lower or equal rank).
const LAYERS: [(&str, u8); 8] = [
    ("error", 0),
    ("num", 0),
    ("online", 1),
    ("path", 2),
    ("plan", 3),
    ("compile", 4),
    ("stream", 5),
    ("play", 6),
];

/// The modules of `plan` in dependency order (`mod` is the layer's own helpers): a module
/// names only the modules before it.
const PLAN_ORDER: [&str; 17] = [
    "mod",
    "arc_inverse",
    "limits",
    "timing",
    "trajectory",
    "motion",
    "scurve",
    "trapezoid",
    "constant_speed",
    "options",
    "joins",
    "speed_limit",
    "transitions",
    "window",
    "planner",
    "parameter",
    "path_timing",
];

fn rank(layer: &str) -> Option<u8> {
    LAYERS.iter().find(|(l, _)| *l == layer).map(|(_, r)| *r)
}

/// A source file of the crate: its layer, its module path below the crate root, its text.
struct Source {
    file: String,
    layer: String,
    /// The file's module below its layer (`mod` for the layer's `mod.rs` or a layer file).
    module: String,
    /// How many `super::` lead from the file's module to the crate root.
    depth: usize,
    text: String,
}

fn rs_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            rs_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

/// Every source file of the crate except `lib.rs` and the files of `#[cfg(test)] mod x;`.
fn sources(src: &Path) -> Vec<Source> {
    let mut files = Vec::new();
    rs_files(src, &mut files);
    let texts: Vec<(PathBuf, String)> = files
        .into_iter()
        .map(|p| {
            let t = fs::read_to_string(&p).unwrap();
            (p, t)
        })
        .collect();
    let test_only: Vec<PathBuf> = texts
        .iter()
        .flat_map(|(p, t)| test_module_files(p, t))
        .collect();
    let mut out = Vec::new();
    for (p, text) in texts {
        let rel = p.strip_prefix(src).unwrap();
        let parts: Vec<String> = rel
            .iter()
            .map(|c| c.to_string_lossy().trim_end_matches(".rs").to_string())
            .collect();
        if parts == ["lib"] || test_only.contains(&p) {
            continue;
        }
        let layer = parts[0].clone();
        let module = if parts.len() == 1 {
            "mod".to_string()
        } else {
            parts[1].clone()
        };
        let depth = parts.iter().filter(|c| c.as_str() != "mod").count();
        out.push(Source {
            file: rel.display().to_string(),
            layer,
            module,
            depth,
            text,
        });
    }
    out
}

/// The files of the `#[cfg(test)] mod name;` declarations in `text` (a file at `path`).
fn test_module_files(path: &Path, text: &str) -> Vec<PathBuf> {
    let code = strip_comments_and_strings(text);
    let dir = if path
        .file_name()
        .is_some_and(|n| n == "mod.rs" || n == "lib.rs")
    {
        path.parent().unwrap().to_path_buf()
    } else {
        path.with_extension("")
    };
    let mut out = Vec::new();
    let mut rest = code.as_str();
    while let Some(i) = rest.find("#[cfg(test)]") {
        rest = &rest[i + "#[cfg(test)]".len()..];
        let item = rest.trim_start();
        let item = item.strip_prefix("pub(crate) ").unwrap_or(item);
        if let Some(decl) = item.strip_prefix("mod ") {
            let name: String = decl.chars().take_while(|c| is_ident(*c)).collect();
            if decl[name.len()..].trim_start().starts_with(';') {
                out.push(dir.join(format!("{name}.rs")));
                out.push(dir.join(&name).join("mod.rs"));
            }
        }
    }
    out
}

fn is_ident(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

/// `text` without comments (doc comments included) and with string and char literals
/// emptied; line breaks kept.
fn strip_comments_and_strings(text: &str) -> String {
    let b: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        let next = b.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < b.len() && b[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            while i < b.len() {
                if b[i] == '/' && b.get(i + 1) == Some(&'*') {
                    depth += 1;
                    i += 2;
                } else if b[i] == '*' && b.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
        } else if c == '"' {
            i += 1;
            while i < b.len() && b[i] != '"' {
                i += if b[i] == '\\' { 2 } else { 1 };
            }
            i += 1;
            out.push_str("\"\"");
        } else if c == '\'' && b.get(i + 2) == Some(&'\'') {
            // a char literal 'x' (lifetimes have no closing quote)
            i += 3;
            out.push_str("' '");
        } else if c == '\'' && next == Some('\\') {
            i += 2;
            while i < b.len() && b[i] != '\'' {
                i += 1;
            }
            i += 1;
            out.push_str("' '");
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

/// `code` without the items marked `#[cfg(test)]` (a `mod tests { … }`, a `use`, a `fn`):
/// from the attribute to the end of the item's braces or its `;`.
fn strip_test_items(code: &str) -> String {
    let mut out = String::with_capacity(code.len());
    let mut rest = code;
    while let Some(i) = rest.find("#[cfg(test)]") {
        out.push_str(&rest[..i]);
        rest = &rest[i + "#[cfg(test)]".len()..];
        let b = rest.as_bytes();
        let mut j = 0;
        let mut depth = 0_i32;
        while j < b.len() {
            match b[j] {
                b'{' => depth += 1,
                b'}' => {
                    depth -= 1;
                    if depth == 0 {
                        j += 1;
                        break;
                    }
                }
                b';' if depth == 0 => {
                    j += 1;
                    break;
                }
                _ => {}
            }
            j += 1;
        }
        rest = &rest[j..];
    }
    out.push_str(rest);
    out
}

/// The public items a file defines at its top level (`pub struct|enum|trait|fn|const|type|
/// static NAME` at the start of a line): what a `crate::NAME` through the root's
/// re-exports names.
fn public_items(sources: &[Source]) -> BTreeMap<String, String> {
    let mut map = BTreeMap::new();
    for s in sources {
        let code = strip_test_items(&strip_comments_and_strings(&s.text));
        for line in code.lines() {
            let Some(rest) = line.strip_prefix("pub ") else {
                continue;
            };
            let mut words = rest.split_whitespace();
            let kind = words.next().unwrap_or("");
            if ["struct", "enum", "trait", "fn", "const", "type", "static"].contains(&kind) {
                let name: String = words
                    .next()
                    .unwrap_or("")
                    .chars()
                    .take_while(|c| is_ident(*c))
                    .collect();
                map.insert(name, s.layer.clone());
            }
        }
    }
    map
}

/// The first path segments after every `crate::` in `code` (each of a `crate::{a, b::c}`
/// group), and after every `super::` chain at least `depth` long (it reaches the root).
fn root_paths(code: &str, depth: usize) -> Vec<String> {
    let mut out = Vec::new();
    let b = code.as_bytes();
    let mut i = 0;
    while i < b.len() {
        let starts_word = i == 0 || !is_ident(b[i - 1] as char);
        let rest = &code[i..];
        let after = if starts_word && rest.starts_with("crate::") {
            Some("crate::".len())
        } else if starts_word && rest.starts_with("super::") {
            let mut n = 0;
            let mut k = 0;
            while rest[k..].starts_with("super::") {
                n += 1;
                k += "super::".len();
            }
            if n >= depth {
                Some(k)
            } else {
                i += k;
                continue;
            }
        } else {
            None
        };
        let Some(k) = after else {
            i += 1;
            continue;
        };
        let tail = rest[k..].trim_start();
        if let Some(group) = tail.strip_prefix('{') {
            let mut level = 0;
            let mut item = String::new();
            let mut first = true;
            for c in group.chars() {
                match c {
                    '{' => level += 1,
                    '}' if level == 0 => break,
                    '}' => level -= 1,
                    ',' if level == 0 => {
                        first = true;
                        continue;
                    }
                    _ => {}
                }
                if level == 0 && first && is_ident(c) {
                    item.push(c);
                } else if !item.is_empty() {
                    out.push(std::mem::take(&mut item));
                    first = false;
                }
            }
            if !item.is_empty() {
                out.push(item);
            }
        } else {
            out.push(tail.chars().take_while(|c| is_ident(*c)).collect());
        }
        i += k;
    }
    out
}

/// The `super::NAME` (one level) and `crate::plan::NAME` references of a `plan` module.
fn plan_siblings(code: &str, depth: usize) -> Vec<String> {
    let mut out = Vec::new();
    for (prefix, needed) in [("super::", depth == 2), ("crate::plan::", true)] {
        if !needed {
            continue;
        }
        let mut rest = code;
        while let Some(i) = rest.find(prefix) {
            let before = rest[..i].chars().last();
            rest = &rest[i + prefix.len()..];
            if before.is_some_and(|c| is_ident(c) || c == ':') || rest.starts_with("super::") {
                continue;
            }
            let tail = rest.trim_start();
            if let Some(group) = tail.strip_prefix('{') {
                let inner = &group[..group.find('}').unwrap_or(group.len())];
                out.extend(inner.split(',').map(|s| {
                    s.trim()
                        .chars()
                        .take_while(|c| is_ident(*c))
                        .collect::<String>()
                }));
            } else {
                out.push(tail.chars().take_while(|c| is_ident(*c)).collect());
            }
        }
    }
    out.retain(|s| !s.is_empty());
    out
}

/// Every reference of a lower layer to a higher one (and of a `plan` module to a later
/// one), as `file: names layer (path)` lines.
fn violations(sources: &[Source]) -> Vec<String> {
    let items = public_items(sources);
    let mut found = Vec::new();
    for s in sources {
        let own = rank(&s.layer).unwrap_or_else(|| panic!("{}: unknown layer {}", s.file, s.layer));
        let code = strip_test_items(&strip_comments_and_strings(&s.text));
        for name in root_paths(&code, s.depth) {
            let layer = if rank(&name).is_some() {
                name.clone()
            } else if let Some(l) = items.get(&name) {
                l.clone()
            } else {
                found.push(format!("{}: crate::{name} names no layer", s.file));
                continue;
            };
            if rank(&layer).unwrap() > own {
                found.push(format!(
                    "{} (layer {}) names layer {layer} (crate::{name})",
                    s.file, s.layer
                ));
            }
        }
        if s.layer == "plan" && s.module != "mod" {
            let pos = |m: &str| PLAN_ORDER.iter().position(|p| *p == m);
            let me = pos(&s.module)
                .unwrap_or_else(|| panic!("{}: {} is not in PLAN_ORDER", s.file, s.module));
            for name in plan_siblings(&code, s.depth) {
                if pos(&name).is_some_and(|p| p >= me) {
                    found.push(format!(
                        "{}: plan::{} names the later plan::{name}",
                        s.file, s.module
                    ));
                }
            }
        }
    }
    found
}

#[test]
fn lower_layers_never_name_higher_ones() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let sources = sources(&src);
    // every layer is there, and the test-only helpers are left out
    for (layer, _) in LAYERS {
        assert!(
            sources.iter().any(|s| s.layer == layer),
            "no files of layer {layer}"
        );
    }
    assert!(!sources.iter().any(|s| s.file.ends_with("testing.rs")));
    let found = violations(&sources);
    assert!(
        found.is_empty(),
        "layering violations:\n{}",
        found.join("\n")
    );
}

fn source(file: &str, text: &str) -> Source {
    let parts: Vec<&str> = file.trim_end_matches(".rs").split('/').collect();
    Source {
        file: file.to_string(),
        layer: parts[0].to_string(),
        module: parts.get(1).map_or("mod", |m| m).to_string(),
        depth: parts.iter().filter(|c| **c != "mod").count(),
        text: text.to_string(),
    }
}

#[test]
fn the_check_finds_violations() {
    let compile = source(
        "compile/mod.rs",
        "pub fn compile() {}\npub struct CompileOptions;",
    );
    let num = source("num/mod.rs", "pub trait Number {}");
    let ok = source(
        "path/blob.rs",
        "use crate::num::Number;\n\
         /// See [`compile`](crate::compile) and \"crate::play\".\n\
         fn f() {}\n\
         #[cfg(test)]\nmod tests {\n    use crate::compile::compile;\n    fn g() { { } }\n}\n",
    );
    assert!(violations(&[compile, num, ok]).is_empty());

    let cases = [
        ("path/blob.rs", "use crate::compile::compile;"),
        ("path/blob.rs", "fn f() { crate::compile(); }"),
        ("path/blob.rs", "use crate::{num::Number, CompileOptions};"),
        ("path/blob.rs", "use super::super::compile::CompileOptions;"),
        ("num/mod.rs", "use crate::path::Path;"),
        ("plan/planner.rs", "use super::path_timing::to_param;"),
        ("plan/speed_limit.rs", "use crate::plan::planner::x;"),
        (
            "path/blob.rs",
            "#[cfg(test)]\nuse crate::num::Q40;\nuse crate::play::Sampler;",
        ),
    ];
    for (file, text) in cases {
        let sources = [
            source(
                "compile/mod.rs",
                "pub fn compile() {}\npub struct CompileOptions;",
            ),
            source("path/mod.rs", "pub struct Path;"),
            source(file, text),
        ];
        assert!(
            !violations(&sources).is_empty(),
            "not found in {file}: {text}"
        );
    }
}
