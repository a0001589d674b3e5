//! Tells the sampler which hand-scheduled tick kernels the target can run
//! (`src/play/kernel/`): `strak_thumb2` for Armv7-M/Armv8-M Mainline (Thumb-2:
//! `ldm`/`stm` with any registers, `adds`/`adc` pairs), `strak_vfp` when the target also has a
//! single-precision FPU in the hard-float ABI (Cortex-M4F/M7/M33F: `vldm`/`vstm`, `vadd.f32`).
//! Every other target (the host included) uses the portable Rust kernel.

fn main() {
    println!("cargo::rustc-check-cfg=cfg(strak_thumb2)");
    println!("cargo::rustc-check-cfg=cfg(strak_vfp)");
    println!("cargo::rerun-if-changed=build.rs");
    let target = std::env::var("TARGET").unwrap_or_default();
    let thumb2 = ["thumbv7m-", "thumbv7em-", "thumbv8m.main-"]
        .iter()
        .any(|p| target.starts_with(p));
    if thumb2 {
        println!("cargo::rustc-cfg=strak_thumb2");
        if target.ends_with("eabihf") {
            println!("cargo::rustc-cfg=strak_vfp");
        }
    }
}
