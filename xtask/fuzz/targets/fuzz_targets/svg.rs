//! `cargo xtask fuzz svg`: see the `fuzz` crate's `svg` module.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| fuzz::svg::check(data));
