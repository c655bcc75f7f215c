//! Fixtures shared by the integration tests (each test file that needs them declares
//! `mod common;`).

use std::path::{Path, PathBuf};

/// Every `.rs` file below `dir`, recursively, appended to `out` (the design-rule tests read
/// the source tree with it).
pub fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}
