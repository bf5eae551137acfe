//! `cargo xtask fuzz upload`: see the `fuzz` crate's `upload` module.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| fuzz::upload::check(data));
