//! The engine takes resolved objects (issue 11, step 1): no file under the engine's folders
//! (`src/dem`, `src/impact`, `src/model`, `src/analysis`, `src/contact`, `src/integrate`,
//! `src/neighbor`, `src/packing`, `src/observe`) imports the scene module, the resolve step
//! (`setup`), the command line (`cli`) or clap (doc-comment examples excepted, they show a
//! user's code). A `use crate::scene` added to the engine fails here, and so does an engine
//! error that names a scene-file key (`damper.count`): engine errors speak physics
//! ([`pdamp::error::ModelError`]) and `src/setup/` maps them to keys.

use std::path::Path;

mod common;
use common::rust_files;

/// The engine's folders below `src/`.
const ENGINE: [&str; 9] = [
    "dem",
    "impact",
    "model",
    "analysis",
    "contact",
    "integrate",
    "neighbor",
    "packing",
    "observe",
];

/// Lines of code (comments skipped) under the engine's folders that contain any of `needles`.
fn offenders(needles: &[&str]) -> Vec<String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut out = Vec::new();
    for area in ENGINE {
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
                if needles.iter().any(|n| code.contains(n)) {
                    out.push(format!("{}:{}: {}", f.display(), i + 1, code));
                }
            }
        }
    }
    out
}

#[test]
fn engine_never_imports_scene_setup_or_cli() {
    let found = offenders(&[
        "crate::scene",
        "pdamp::scene",
        "crate::setup",
        "pdamp::setup",
        "crate::cli",
        "pdamp::cli",
        "clap::",
        "use clap",
    ]);
    assert!(
        found.is_empty(),
        "the engine imports the scene, the resolve step or the CLI:\n{}",
        found.join("\n")
    );
}

#[test]
fn engine_errors_name_no_scene_keys() {
    // scene-file keys as a key-naming message would spell them ("damper.count = 5000: …",
    // "lower damper.box"); the engine says Quantity::GrainCount instead. `run.` alone would
    // match the engine's own `run.dt_s` fields, so the run keys are listed one by one.
    let found = offenders(&[
        "damper.",
        "run.dt_fraction",
        "run.duration",
        "run.periods",
        "run.steady_fraction",
        "run.analysis_fraction",
        "run.sample_interval",
        "excitation.frequency",
        "excitation.amplitude",
        "primary.mass",
        "primary.stiffness",
        "primary.damping",
    ]);
    assert!(
        found.is_empty(),
        "engine code names scene-file keys (map a ModelError in src/setup/ instead):\n{}",
        found.join("\n")
    );
}
