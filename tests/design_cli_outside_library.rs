//! The CLI is part of the binary, not of the library (issue 11, step 4): `src/lib.rs` declares
//! no `cli` module, and no library file (everything under `src/` except `src/main.rs` and
//! `src/cli/`) uses clap, anyhow or indicatif, the optional dependencies of the `cli` feature.

use std::path::Path;

mod common;
use common::rust_files;

#[test]
fn the_library_has_no_cli_and_no_cli_dependencies() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let lib = std::fs::read_to_string(src.join("lib.rs")).unwrap();
    assert!(
        !lib.lines().any(|l| {
            let l = l.trim_start();
            !l.starts_with("//") && l.contains("mod cli")
        }),
        "src/lib.rs declares the cli module"
    );
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut offenders = Vec::new();
    for f in files {
        if f == src.join("main.rs") || f.starts_with(src.join("cli")) {
            continue;
        }
        let text = std::fs::read_to_string(&f).unwrap();
        for (i, line) in text.lines().enumerate() {
            let code = line.trim_start();
            if code.starts_with("//") {
                continue;
            }
            if ["clap::", "anyhow", "indicatif"]
                .iter()
                .any(|d| code.contains(d))
            {
                offenders.push(format!("{}:{}: {}", f.display(), i + 1, code));
            }
        }
    }
    assert!(
        offenders.is_empty(),
        "library files use the CLI's dependencies:\n{}",
        offenders.join("\n")
    );
}
