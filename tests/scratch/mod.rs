//! Scratch directories of the integration tests: `tempfile::tempdir()`, except that with
//! `PDAMP_TEST_OUTPUT=DIR` set they are created under `DIR` and kept, so that
//! `tests/output_scan.rs` can check every file the test suite wrote (`.ci/run` does this).
//! Each test binary uses a part of it, hence `dead_code` is allowed.

#![allow(dead_code)]

/// Environment variable naming the directory that keeps the tests' outputs.
pub const OUTPUT_ENV: &str = "PDAMP_TEST_OUTPUT";

/// A scratch directory (see the module documentation).
///
/// # Errors
/// The file system's error.
pub fn tempdir() -> std::io::Result<tempfile::TempDir> {
    match std::env::var_os(OUTPUT_ENV) {
        Some(root) => {
            std::fs::create_dir_all(&root)?;
            tempfile::Builder::new()
                .prefix("pdamp-test-")
                .disable_cleanup(true)
                .tempdir_in(root)
        }
        None => tempfile::tempdir(),
    }
}
