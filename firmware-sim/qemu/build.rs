//! Gives every firmware binary its memory layout and copies the generated `jobs.rs` from the
//! folder `STRAK_BLOBS` (written by `cargo xtask qemu`) into `OUT_DIR`.
//!
//! cortex-m-rt's `link.x` includes `memory.x` from the linker's search path (and first from
//! the linker's working folder, this crate's root, which therefore holds none). Each binary
//! gets a folder of its own on that path (`-L`, a link argument of that binary only) holding
//! the `memory.x` it is linked with: [`LARGE_RAM`] binaries the QEMU boards' 4 MiB
//! (`memory/boards.x`), the flash-playback firmware [`FLASH_PLAY`] the memory of a real part
//! of its target's class (`memory/flash-<target>.x`).

use std::env;
use std::fs;
use std::path::{Path, PathBuf};

/// The binaries linked with `memory/boards.x` (4 MiB of RAM).
const LARGE_RAM: [&str; 6] = [
    "strak-qemu",
    "size-sampler",
    "size-baseline",
    "icount",
    "stack",
    "gcode",
];

/// The flash-playback firmware, linked with `memory/flash-<target>.x`.
const FLASH_PLAY: &str = "flash-play";

/// Copies `file` to `<out>/<folder>/memory.x` and puts that folder on the linker's search
/// path of each of `bins`.
fn layout(out: &Path, folder: &str, file: &str, bins: &[&str]) {
    let dir = out.join(folder);
    fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("cannot create {}: {e}", dir.display()));
    fs::copy(file, dir.join("memory.x")).unwrap_or_else(|e| panic!("cannot copy {file}: {e}"));
    println!("cargo:rerun-if-changed={file}");
    for bin in bins {
        println!("cargo:rustc-link-arg-bin={bin}=-L{}", dir.display());
    }
}

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    let target = env::var("TARGET").expect("cargo sets TARGET");
    layout(&out, "large-ram", "memory/boards.x", &LARGE_RAM);
    let part = format!("memory/flash-{target}.x");
    if Path::new(&part).exists() {
        layout(&out, "flash-part", &part, &[FLASH_PLAY]);
    } else {
        println!("cargo:warning={part} is missing: {FLASH_PLAY} has no memory layout for {target}");
    }
    println!("cargo:rerun-if-env-changed=STRAK_BLOBS");
    let Some(blobs) = env::var_os("STRAK_BLOBS") else {
        panic!(
            "STRAK_BLOBS is not set: build this firmware through `cargo xtask qemu` (it compiles \
             the jobs on the host and sets STRAK_BLOBS to the folder of blobs and jobs.rs)"
        );
    };
    let jobs = PathBuf::from(blobs).join("jobs.rs");
    println!("cargo:rerun-if-changed={}", jobs.display());
    fs::copy(&jobs, out.join("jobs.rs"))
        .unwrap_or_else(|e| panic!("cannot copy {}: {e}", jobs.display()));
}
