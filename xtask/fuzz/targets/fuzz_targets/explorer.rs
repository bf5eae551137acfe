//! `cargo xtask fuzz explorer`: see the `fuzz` crate's `explore` module.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| fuzz::explore::check(data));
