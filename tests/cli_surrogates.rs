//! `pdamp surrogates`, `pdamp surrogate-test` and `pdamp nrlazy` end to end: output format,
//! determinism for a seed, and clear errors for a time column, NaN, constant or short input.

mod scratch;

use std::io::Write;
use std::process::Command;

use pdamp::systems::henon::henon_x;

fn write(dir: &tempfile::TempDir, name: &str, text: &str) -> String {
    let path = dir.path().join(name);
    std::fs::File::create(&path)
        .unwrap()
        .write_all(text.as_bytes())
        .unwrap();
    path.to_str().unwrap().to_string()
}

fn pdamp(args: &[&str]) -> (String, String, bool) {
    let out = Command::new(env!("CARGO_BIN_EXE_pdamp"))
        .args(args)
        .output()
        .unwrap();
    (
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
        out.status.success(),
    )
}

fn henon_file(dir: &tempfile::TempDir, n: usize) -> String {
    let text: String = henon_x(n).iter().map(|v| format!("{v:.17e}\n")).collect();
    write(dir, "henon.txt", &text)
}

#[test]
fn surrogates_are_columns_and_deterministic() {
    let dir = scratch::tempdir().unwrap();
    let f = henon_file(&dir, 500);
    let (a, err, ok) = pdamp(&["surrogates", &f, "-n", "3", "-I", "5"]);
    assert!(ok, "{err}");
    assert!(err.contains("converged"), "{err}");
    let (b, _, _) = pdamp(&["surrogates", &f, "-n", "3", "-I", "5"]);
    assert_eq!(a, b);
    let mut lines = a.lines();
    assert_eq!(lines.next(), Some("# surrogate_1 surrogate_2 surrogate_3"));
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split_whitespace().map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 500);
    assert!(rows.iter().all(|r| r.len() == 3));
    // -o writes the same text to a file
    let o = dir.path().join("s.txt");
    let (_, err, ok) = pdamp(&[
        "surrogates",
        &f,
        "-n",
        "3",
        "-I",
        "5",
        "-o",
        o.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    assert_eq!(std::fs::read_to_string(o).unwrap(), a);
}

#[test]
fn surrogate_test_json_rejects_henon() {
    let dir = scratch::tempdir().unwrap();
    let f = henon_file(&dir, 2000);
    let (out, err, ok) = pdamp(&["surrogate-test", &f, "-m", "2", "--json"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["rank"], 1);
    assert_eq!(v["p_value"], 0.05);
    assert_eq!(v["rejected"], true);
    assert_eq!(v["surrogate_values"].as_array().unwrap().len(), 19);
    let (out, err, ok) = pdamp(&[
        "surrogate-test",
        &f,
        "--statistic",
        "time-reversal",
        "-n",
        "39",
    ]);
    assert!(ok, "{err}");
    assert!(out.contains("null hypothesis rejected"), "{out}");
}

#[test]
fn nrlazy_writes_one_column() {
    let dir = scratch::tempdir().unwrap();
    let f = henon_file(&dir, 1000);
    let (out, err, ok) = pdamp(&["nrlazy", &f, "-m", "5", "--radius-sd", "0.1", "-i", "2"]);
    assert!(ok, "{err}");
    assert!(err.contains("neighbours per vector"), "{err}");
    assert_eq!(out.lines().count(), 1000);
    assert!(out.lines().all(|l| l.parse::<f64>().is_ok()));
}

#[test]
fn bad_input_gives_clear_errors() {
    let dir = scratch::tempdir().unwrap();
    let timed: String = henon_x(100)
        .iter()
        .enumerate()
        .map(|(i, v)| format!("{},{v}\n", i as f64 * 0.01))
        .collect();
    let timed = write(&dir, "timed.csv", &format!("time_s,x\n{timed}"));
    for verb in ["surrogates", "surrogate-test", "nrlazy"] {
        // the time column selected explicitly: refused
        let (_, err, ok) = pdamp(&[verb, &timed, "-c", "1"]);
        assert!(
            !ok && err.contains("time or index column") && err.contains("-c"),
            "{verb}: {err}"
        );
        // by default the column after the time column is read, and said so (issue 14)
        let mut args = vec![verb, &timed];
        if verb != "surrogates" {
            args.extend(["-m", "2"]);
        }
        let (_, err, ok) = pdamp(&args);
        assert!(ok && err.contains("reading column 2 `x`"), "{verb}: {err}");
        // selecting the signal column works
        let mut args = vec![verb, &timed, "-c", "x"];
        if verb != "surrogates" {
            args.extend(["-m", "2"]);
        }
        let (_, err, ok) = pdamp(&args);
        assert!(ok, "{verb}: {err}");
    }
    let nan = write(&dir, "nan.txt", "1\n2\nnan\n3\n");
    let (_, err, ok) = pdamp(&["surrogates", &nan]);
    assert!(
        !ok && err.contains("nan.txt:3") && err.contains("non-finite"),
        "{err}"
    );
    let constant = write(&dir, "c.txt", &"2.5\n".repeat(50));
    for verb in ["surrogates", "surrogate-test", "nrlazy"] {
        let (_, err, ok) = pdamp(&[verb, &constant]);
        assert!(!ok && err.contains("constant"), "{verb}: {err}");
    }
    let short = write(&dir, "short.txt", "1\n3\n2\n");
    let (_, err, ok) = pdamp(&["surrogate-test", &short]);
    assert!(!ok && err.contains("too short"), "{err}");
    let (_, err, ok) = pdamp(&["surrogates", &short]);
    assert!(!ok && err.contains("too short"), "{err}");
}
