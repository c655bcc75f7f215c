//! cargo-fuzz target `scene_toml` (see fuzz/targets.rs and fuzz/README.md).
#![no_main]

#[path = "../targets.rs"]
mod targets;

libfuzzer_sys::fuzz_target!(|data: &[u8]| targets::scene_toml(data));
