//! libFuzzer entry point of the `pipeline` harness: [`strak_fuzz::pipeline::run`] on every input; a
//! violated invariant is a panic, which libFuzzer reports with the input (unless
//! [`strak_fuzz::IGNORE_VAR`] masks it).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    if let Err(violation) = strak_fuzz::pipeline::run(data)
        && !strak_fuzz::ignored(&violation)
    {
        panic!("pipeline: {violation}");
    }
});
