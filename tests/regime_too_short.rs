//! A run whose analysis window is too short for a verdict says so, with the number of forcing
//! periods needed and — from `simulate`, which knows the scene — the keys that lengthen it; the
//! analysis itself speaks of records, not scene files.

mod scratch;

use std::process::Command;

#[test]
fn a_short_run_is_too_short_and_names_the_keys_that_lengthen_it() {
    let scene = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/data/scenes/thesis_b_impact.toml"
    );
    let dir = scratch::tempdir().unwrap();
    let out = dir.path().join("run");
    // 3 s at 10 Hz: 30 forcing periods, of which the analysed half holds 15
    let st = Command::new(env!("CARGO_BIN_EXE_pdamp"))
        .args(["simulate", scene, "--out", out.to_str().unwrap()])
        .args([
            "--set",
            "run.duration=3",
            "--set",
            "excitation.frequency=10",
        ])
        .output()
        .unwrap();
    assert!(
        st.status.success(),
        "{}",
        String::from_utf8_lossy(&st.stderr)
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let a = &summary["analysis"];
    assert_eq!(a["regime"], "too-short", "{a}");
    let reason = a["reason"].as_str().unwrap();
    assert!(reason.contains("needs at least 48"), "{reason}");
    for key in ["run.periods", "run.duration", "run.analysis_fraction"] {
        assert!(reason.contains(key), "{key} missing: {reason}");
    }
}
