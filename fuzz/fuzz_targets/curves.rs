//! libFuzzer entry point of the `curves` harness: [`strak_fuzz::curves::run`] on every input; a
//! violated invariant is a panic, which libFuzzer reports with the input (unless
//! [`strak_fuzz::IGNORE_VAR`] masks it).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    if let Err(violation) = strak_fuzz::curves::run(data)
        && !strak_fuzz::ignored(&violation)
    {
        panic!("curves: {violation}");
    }
});
