//! `pdamp scene --template …` writes a scene that `check-scene` accepts, with units in its
//! comments, and never overwrites a file.

use std::process::Command;

fn pdamp(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_pdamp"))
        .args(args)
        .output()
        .expect("the pdamp binary runs")
}

#[test]
fn every_template_is_a_valid_commented_scene() {
    let dir = std::env::temp_dir().join(format!("pdamp_templates_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for (name, kind) in [("primary", "none"), ("impact", "impact"), ("dem", "dem")] {
        let path = dir.join(format!("{name}.toml"));
        let p = path.to_str().unwrap();
        let out = pdamp(&["scene", "--template", name, "-o", p]);
        assert!(
            out.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.contains(&format!("kind = \"{kind}\"")), "{name}");
        assert!(text.contains("# kg"), "{name}: units in the comments");
        let check = pdamp(&["check-scene", p]);
        assert!(
            check.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&check.stderr)
        );
        assert!(String::from_utf8_lossy(&check.stdout).contains("valid"));
        // never overwritten
        let again = pdamp(&["scene", "--template", name, "-o", p]);
        assert!(!again.status.success(), "{name}: overwrote");
        assert!(String::from_utf8_lossy(&again.stderr).contains("exists"));
        // stdout form is the same text
        let stdout = pdamp(&["scene", "--template", name]);
        assert_eq!(String::from_utf8_lossy(&stdout.stdout), text);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
