//! No NaN or infinity in any output file: scans every file the test suite wrote under
//! `PDAMP_TEST_OUTPUT` (see `tests/scratch/mod.rs`) and fails naming the file, line and cell.
//!
//! Run by `.ci/run` after the suite:
//!
//! ```text
//! PDAMP_TEST_OUTPUT=$PWD/target/test-output cargo test --release
//! PDAMP_TEST_OUTPUT=$PWD/target/test-output cargo test --release --test output_scan -- --ignored
//! ```
//!
//! Scanned: `.csv`, `.txt`, `.dat`, `.vtk` (cells split on `,`, `;` and whitespace) and
//! `.json` (must parse: JSON cannot hold NaN or infinity, so a file with a bare `NaN` token
//! does not). Not scanned: images, and `scene.toml`, which echoes the input
//! (`damper.gap = inf` is how a scene says "no ceiling"), and the tests' own inputs that hold
//! NaN on purpose (to check that readers refuse it), named `nan*`.

mod scratch;

use std::path::{Path, PathBuf};

/// Every file under `dir`, recursively.
fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        let p = e.path();
        if p.is_dir() {
            files(&p, out);
        } else {
            out.push(p);
        }
    }
}

/// A cell that is a non-finite number.
fn non_finite(cell: &str) -> bool {
    let c = cell.trim().trim_matches('"').to_ascii_lowercase();
    let c = c.trim_start_matches(['+', '-']);
    matches!(c, "nan" | "inf" | "infinity")
}

/// The first non-finite cell of a text file: (line, cell).
fn first_non_finite(path: &Path) -> Option<(usize, String)> {
    // inputs the tests write to check that NaN is refused are named nan*
    if path.file_name()?.to_str()?.starts_with("nan") {
        return None;
    }
    let ext = path.extension()?.to_str()?;
    let text = std::fs::read_to_string(path).ok()?;
    if ext == "json" {
        // JSON has no NaN or infinity: a file holding one does not parse
        return serde_json::from_str::<serde_json::Value>(&text)
            .err()
            .map(|e| (e.line(), format!("not JSON ({e})")));
    }
    if !matches!(ext, "csv" | "txt" | "dat" | "vtk") {
        return None;
    }
    for (i, line) in text.lines().enumerate() {
        let cells = line.split(|c: char| c == ',' || c == ';' || c.is_whitespace());
        for cell in cells {
            if non_finite(cell) {
                return Some((i + 1, cell.trim().to_string()));
            }
        }
    }
    None
}

#[test]
fn cells_are_recognised() {
    assert!(non_finite("NaN") && non_finite(" -inf") && non_finite("Infinity"));
    assert!(!non_finite("1e308") && !non_finite("info") && !non_finite(""));
}

#[test]
#[ignore = "scans PDAMP_TEST_OUTPUT after the suite ran (see the module documentation)"]
fn no_output_file_of_the_test_suite_holds_nan_or_inf() {
    let root = std::env::var_os(scratch::OUTPUT_ENV)
        .expect("set PDAMP_TEST_OUTPUT to the directory the suite wrote into");
    let mut all = Vec::new();
    files(Path::new(&root), &mut all);
    all.sort();
    let bad: Vec<String> = all
        .iter()
        .filter_map(|p| first_non_finite(p).map(|(l, c)| format!("{}:{l}: `{c}`", p.display())))
        .collect();
    println!(
        "scanned {} files under {}",
        all.len(),
        Path::new(&root).display()
    );
    assert!(
        bad.is_empty(),
        "{} output files hold NaN or infinity:\n{}",
        bad.len(),
        bad.join("\n")
    );
}
