//! Writes `BENCHMARKS.md` at the repository root from criterion's results.
//!
//! ```text
//! report [--criterion DIR] [--qemu DIR] [--out FILE]
//! ```
//! Defaults: `target/criterion`, `target/qemu` (in `CARGO_TARGET_DIR` if set) and
//! `BENCHMARKS.md`, relative to the workspace root.

use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use strak_bench::report::{Inputs, Machine, generate};

fn main() -> Result<()> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map(PathBuf::from)
        .context("workspace root")?;
    let target =
        std::env::var_os("CARGO_TARGET_DIR").map_or_else(|| root.join("target"), PathBuf::from);
    let mut inputs = Inputs {
        criterion: target.join("criterion"),
        qemu: target.join("qemu"),
    };
    let mut out = root.join("BENCHMARKS.md");
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let mut value = || {
            args.next()
                .map(PathBuf::from)
                .context(format!("{a} needs a value"))
        };
        match a.as_str() {
            "--criterion" => inputs.criterion = value()?,
            "--qemu" => inputs.qemu = value()?,
            "--out" => out = value()?,
            _ => bail!("unknown argument {a} (expected --criterion DIR, --qemu DIR, --out FILE)"),
        }
    }
    let mut md = generate(&inputs, &Machine::detect())?;
    // the corner comparison is computed here, not read from criterion's results
    let at = md.find("## Machine").unwrap_or(md.len());
    md.insert_str(at, &strak_bench::corners::section());
    std::fs::write(&out, md).with_context(|| format!("writing {}", out.display()))?;
    println!("wrote {}", out.display());
    Ok(())
}
