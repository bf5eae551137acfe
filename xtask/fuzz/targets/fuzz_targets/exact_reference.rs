//! `cargo xtask fuzz exact_reference`: see the `fuzz` crate's `exact_reference` module.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| fuzz::exact_reference::check(data));
