//! `pdamp analyze --json`, `pdamp spectrum` and `pdamp poincare` end to end: the binary reads a
//! series file and prints the documented JSON keys / CSV headers with the reference values.

mod scratch;

use pdamp::systems::logistic::logistic_series;
use std::f64::consts::TAU;
use std::io::Write;
use std::process::Command;

fn write_series(dir: &tempfile::TempDir, name: &str, x: &[f64]) -> String {
    let path = dir.path().join(name);
    let mut f = std::fs::File::create(&path).unwrap();
    writeln!(f, "# test series").unwrap();
    for v in x {
        writeln!(f, "{v:.17e}").unwrap();
    }
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

#[test]
fn analyze_json_periodic_and_chaotic() {
    let dir = scratch::tempdir().unwrap();
    // Logistic r = 3.5: period 4 (SPEC §9: between r₂ = 3.4495 and r₃ = 3.5441).
    let file = write_series(&dir, "p4.txt", &logistic_series(3.5, 0.3, 3000, 1000));
    let (out, err, ok) = pdamp(&["analyze", &file, "--json"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    for key in [
        "lag",
        "embedding_dim",
        "mle_per_sample",
        "mle_per_time",
        "regime",
        "period",
        "spectral_lines",
        "poincare_distinct_points",
        "kantz_fit",
        "zero_one_k",
    ] {
        assert!(v.get(key).is_some(), "missing key {key}");
    }
    assert_eq!(v["regime"], "periodic");
    assert_eq!(v["period"], 4.0);
    assert!(v["mle_per_time"].is_null()); // no --dt
                                          // Logistic r = 4 with dt = 0.5 s: chaotic, λ per second = λ per sample / 0.5 exactly.
    let file = write_series(&dir, "chaos.txt", &logistic_series(4.0, 0.3, 8000, 100));
    let (out, err, ok) = pdamp(&["analyze", &file, "--json", "--dt", "0.5"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["regime"], "chaotic");
    assert!(v["period"].is_null());
    let per_sample = v["mle_per_sample"].as_f64().unwrap();
    assert!((v["mle_per_time"].as_f64().unwrap() - per_sample / 0.5).abs() < 1e-12);
    assert!(v["zero_one_k"].as_f64().unwrap() > 0.8);
}

#[test]
fn analyze_forced_sine_text_and_errors() {
    let dir = scratch::tempdir().unwrap();
    let (dt, f) = (1e-3, 1.0 / (37.3e-3));
    let x: Vec<f64> = (0..10_000)
        .map(|n| (TAU * f * n as f64 * dt).sin())
        .collect();
    let file = write_series(&dir, "sine.txt", &x);
    let fs = format!("{f}");
    let (out, err, ok) = pdamp(&[
        "analyze",
        &file,
        "--dt",
        "0.001",
        "--forcing-hz",
        &fs,
        "--json",
    ]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["regime"], "periodic");
    assert_eq!(v["period"], 1.0); // one point per forcing period
    assert_eq!(v["poincare_distinct_points"], 1);
    // Text report names the regime and period unit.
    let (out, _, ok) = pdamp(&["analyze", &file, "--dt", "0.001", "--forcing-hz", &fs]);
    assert!(ok);
    assert!(out.contains("periodic, period 1 forcing periods"), "{out}");
    // --forcing-hz without --dt is an error that says what to add.
    let (_, err, ok) = pdamp(&["analyze", &file, "--forcing-hz", &fs]);
    assert!(!ok);
    assert!(err.contains("--dt"), "{err}");
}

#[test]
fn spectrum_and_poincare_csv() {
    let dir = scratch::tempdir().unwrap();
    let x: Vec<f64> = (0..4096)
        .map(|n| 2.0 * (TAU * 0.1 * n as f64).sin())
        .collect();
    let file = write_series(&dir, "s.txt", &x);
    let (out, _, ok) = pdamp(&["spectrum", &file, "--dt", "0.01"]);
    assert!(ok);
    assert!(out.starts_with("frequency_hz,power\n"));
    assert_eq!(out.lines().count(), 1 + 4096 / 2 + 1);
    // The line: 0.1 cycles/sample = 10 Hz, power A²/2 = 2 (Hann main lobe, ≤ 0.1 % leakage).
    let (out, _, ok) = pdamp(&["spectrum", &file, "--dt", "0.01", "--lines"]);
    assert!(ok);
    let rows: Vec<&str> = out.lines().collect();
    assert_eq!(rows[0], "frequency_hz,line_power,peak_power,prominence");
    assert_eq!(rows.len(), 2, "{out}");
    let cols: Vec<f64> = rows[1].split(',').map(|c| c.parse().unwrap()).collect();
    assert!((cols[0] - 10.0).abs() < 0.1 * 100.0 / 4096.0); // 0.1 bin
    assert!((cols[1] - 2.0).abs() < 2e-3 * 2.0);
    // Poincaré at 10 samples per period: every point is (0, 2 sin(2π·0.1·3)).
    let (out, err, ok) = pdamp(&["poincare", &file, "--period-samples", "10", "--delay", "3"]);
    assert!(ok);
    assert!(out.starts_with("cycle,time_samples,s,s_delayed\n"));
    assert!(err.contains("1 distinct point"), "{err}");
}

#[test]
fn tisean_verbs_name_bad_input() {
    // mutual, fnn and lyap-k on a time column, a constant series, a NaN and a too short
    // series: an error that names the problem, never output.
    let dir = scratch::tempdir().unwrap();
    let x: Vec<f64> = (0..3000).map(|i| (i as f64 * 0.37).sin()).collect();
    let two = dir.path().join("t_x.txt");
    let mut f = std::fs::File::create(&two).unwrap();
    for (i, v) in x.iter().enumerate() {
        writeln!(f, "{} {v}", i as f64 * 0.01).unwrap();
    }
    let two = two.to_str().unwrap();
    let constant = write_series(&dir, "c.txt", &[2.5; 3000]);
    let mut with_nan = x.clone();
    with_nan[1234] = f64::NAN;
    let nan = write_series(&dir, "nan.txt", &with_nan);
    let short = write_series(&dir, "short.txt", &x[..12]);
    for verb in [
        vec!["mutual"],
        vec!["fnn", "--tisean", "-M1,4", "-d5"],
        vec!["lyap-k", "--tisean", "-m2", "-M4", "-d5", "-s30"],
    ] {
        let run = |file: &str, extra: &[&str]| {
            let mut args: Vec<&str> = verb.clone();
            args.insert(1, file);
            args.extend_from_slice(extra);
            pdamp(&args)
        };
        let (_, err, ok) = run(two, &[]);
        assert!(
            !ok && err.contains("time or index column"),
            "{verb:?}: {err}"
        );
        // the second column of the same file is fine
        let (_, err, ok) = run(two, &["-c", "2"]);
        assert!(ok, "{verb:?} -c 2: {err}");
        let (_, err, ok) = run(&constant, &[]);
        assert!(!ok && err.contains("constant"), "{verb:?}: {err}");
        let (_, err, ok) = run(&nan, &[]);
        // the reader refuses it, naming the line (1234 + the comment line + 1)
        assert!(
            !ok && err.contains("non-finite value") && err.contains(":1236:"),
            "{verb:?}: {err}"
        );
        if verb[0] != "mutual" {
            let (_, err, ok) = run(&short, &[]);
            assert!(!ok && err.contains("too short"), "{verb:?}: {err}");
        }
    }
    // mutual on 12 points: it prints I(τ), but any first minimum comes with a warning
    let (_, err, ok) = pdamp(&["mutual", &short]);
    assert!(ok, "{err}");
    assert!(err.contains("warning") && err.contains("too few"), "{err}");
    for line in err.lines().filter(|l| l.contains("first minimum")) {
        assert!(line.contains("unreliable"), "{err}");
    }
}

#[test]
fn every_estimator_verb_refuses_a_time_column() {
    // a strictly increasing column (time or index) is not a signal: every estimator verb says
    // so instead of printing an estimate of it
    let dir = scratch::tempdir().unwrap();
    let t: Vec<f64> = (0..5000).map(|i| i as f64 * 0.01).collect();
    let file = write_series(&dir, "time.txt", &t);
    for verb in [
        "mutual",
        "fnn",
        "lyap-k",
        "lyap-r",
        "d2",
        "cao",
        "rqa",
        "surrogates",
        "nrlazy",
    ] {
        let (_, err, ok) = pdamp(&[verb, &file]);
        assert!(!ok, "{verb} accepted a time column");
        assert!(
            err.contains("time or index column"),
            "{verb}: unclear message: {err}"
        );
    }
}

#[test]
fn tisean_verbs_write_the_o_file_and_d2_takes_n0_only() {
    // every TISEAN-like verb: `-o FILE` holds exactly what stdout would (written atomically);
    // d2's TISEAN -N: 0 (all pairs) accepted, any other count refused naming -N0.
    let dir = scratch::tempdir().unwrap();
    let x: Vec<f64> = (0..3000)
        .map(|i| (i as f64 * 0.37).sin() + 0.3 * (i as f64 * 0.113).cos())
        .collect();
    let file = write_series(&dir, "x.txt", &x);
    for verb in [
        vec!["mutual", "-D30"],
        vec!["fnn", "--tisean", "-M1,4", "-d5"],
        vec!["lyap-k", "--tisean", "-m2", "-M3", "-d5", "-s30"],
        vec!["lyap-r", "-m3", "-d5", "-s20"],
        vec!["d2", "-M1,3", "-d5", "-#10"],
        vec!["nrlazy", "-m3", "-r0.2"],
        vec!["surrogates", "-n2", "-I3"],
    ] {
        let mut args = verb.clone();
        args.insert(1, &file);
        let (stdout, err, ok) = pdamp(&args);
        assert!(ok && !stdout.is_empty(), "{verb:?}: {err}");
        let out = dir.path().join(format!("{}.out", verb[0]));
        let out_s = out.to_str().unwrap().to_string();
        args.extend_from_slice(&["-o", &out_s]);
        let (printed, err, ok) = pdamp(&args);
        assert!(ok, "{verb:?} -o: {err}");
        assert!(printed.is_empty(), "{verb:?} -o printed {printed}");
        assert_eq!(std::fs::read_to_string(&out).unwrap(), stdout, "{verb:?}");
    }
    let (_, err, ok) = pdamp(&["d2", &file, "-M1,3", "-#10", "-N1000"]);
    assert!(
        !ok && err.contains("-N0") && err.contains("every pair"),
        "{err}"
    );
    let (with_n0, err, ok) = pdamp(&["d2", &file, "-M1,3", "-#10", "-N0"]);
    assert!(ok, "{err}");
    assert_eq!(with_n0, pdamp(&["d2", &file, "-M1,3", "-#10"]).0);
    // -E: the same pairs at ε / interval, so C at the rescaled radii is C at the data radii
    let (rescaled, err, ok) = pdamp(&["d2", &file, "-M1,2", "-r0.01", "-R0.5", "-#5", "-E"]);
    assert!(ok, "{err}");
    let (lo, hi) = x
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &v| (a.min(v), b.max(v)));
    let r = |e: f64| format!("{}", e * (hi - lo));
    let (plain, _, ok) = pdamp(&["d2", &file, "-M1,2", "-r", &r(0.01), "-R", &r(0.5), "-#5"]);
    assert!(ok);
    let pairs = |t: &str| -> Vec<String> {
        t.lines()
            .skip(1)
            .map(|l| l.split(',').nth(3).unwrap().to_string())
            .collect()
    };
    assert_eq!(pairs(&rescaled), pairs(&plain));
}
