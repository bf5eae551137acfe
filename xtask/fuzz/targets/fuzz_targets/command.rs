//! `cargo xtask fuzz command`: see the `fuzz` crate's `command` module.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| fuzz::command::check(data));
