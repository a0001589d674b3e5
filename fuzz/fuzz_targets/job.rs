//! libFuzzer entry point of the `job` harness: [`strak_fuzz::job::run`] on every input; a
//! violated invariant is a panic, which libFuzzer reports with the input (unless
//! [`strak_fuzz::IGNORE_VAR`] masks it).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    if let Err(violation) = strak_fuzz::job::run(data)
        && !strak_fuzz::ignored(&violation)
    {
        panic!("job: {violation}");
    }
});
