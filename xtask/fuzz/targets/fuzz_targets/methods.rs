//! `cargo xtask fuzz methods`: see the `fuzz` crate's `methods` module.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| fuzz::methods::check(data));
