//! cargo-fuzz target `set_assignment` (see fuzz/targets.rs and fuzz/README.md).
#![no_main]

#[path = "../targets.rs"]
mod targets;

libfuzzer_sys::fuzz_target!(|data: &[u8]| targets::set_assignment(data));
