//! The engine takes resolved objects (issue 11, step 1): an engine error that names a
//! scene-file key (`damper.count`) fails here: engine errors speak physics
//! ([`pdamp::error::ModelError`]) and `src/setup/` maps them to keys. That no engine file
//! imports the scene, the resolve step or the command line is checked on the module graph
//! itself (`tests/design_module_graph.rs`: the engine's layers lie beneath `scene` and
//! `setup`).

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
