//! `cargo xtask fuzz scene_file`: see the `fuzz` crate's `scene_file` module.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| fuzz::scene_file::check(data));
