//! Puts `memory.x` on the linker's search path and copies the generated `jobs.rs` from the
//! folder `STRAK_BLOBS` (written by `cargo xtask qemu`) into `OUT_DIR`.

use std::env;
use std::fs;
use std::path::PathBuf;

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    fs::copy("memory.x", out.join("memory.x")).expect("memory.x is readable");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=memory.x");
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
