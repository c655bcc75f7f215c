//! The engine takes resolved objects (issue 11, step 1): no file under `src/dem`,
//! `src/impact` or `src/model` imports the scene module (doc-comment examples excepted, they
//! show a user's code). A `use crate::scene` added to the engine fails here.

use std::path::Path;

mod common;
use common::rust_files;

#[test]
fn dem_impact_and_model_never_import_scene() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut offenders = Vec::new();
    for area in ["dem", "impact", "model"] {
        let mut files = Vec::new();
        rust_files(&root.join(area), &mut files);
        assert!(!files.is_empty(), "no sources under src/{area}");
        for f in files {
            let text = std::fs::read_to_string(&f).unwrap();
            for (i, line) in text.lines().enumerate() {
                let code = line.trim_start();
                if code.starts_with("//") {
                    continue;
                }
                if code.contains("crate::scene") || code.contains("pdamp::scene") {
                    offenders.push(format!("{}:{}: {}", f.display(), i + 1, code));
                }
            }
        }
    }
    assert!(
        offenders.is_empty(),
        "the engine imports the scene:\n{}",
        offenders.join("\n")
    );
}
