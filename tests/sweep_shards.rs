//! Sweeps at scale (issue 13): shards of one sweep (`--shard K/N`, in a shared directory or
//! each in its own) merged by `pdamp merge` give sweep.csv and strobe.csv byte-identical to a
//! single-process run; a missing shard is reported by its points and nothing is written; a
//! different sweep is refused; timings stay out of sweep.csv; sweeps too large for the disk or
//! memory and overflowing ranges are refused up front; `pdamp slurm` writes the job array and
//! its dependent merge.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const SCENE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/data/scenes/thesis_b_impact.toml"
);
const ARGS: [&str; 7] = [
    "--no-analysis",
    "--set",
    "run.periods=80",
    "--set",
    "damper.restitution=0.8",
    "--vary",
    "excitation.frequency=3:27:2",
];

fn pdamp(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_pdamp"))
        .args(args)
        .env("RAYON_NUM_THREADS", "2")
        .output()
        .unwrap()
}

fn sweep(out: &Path, extra: &[&str]) -> Output {
    let mut a = vec!["sweep", SCENE, "--out", out.to_str().unwrap()];
    a.extend(ARGS);
    a.extend(extra);
    pdamp(&a)
}

fn read(p: PathBuf) -> Vec<u8> {
    std::fs::read(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

#[test]
fn shards_merge_to_the_single_process_files() {
    let dir = tempfile::tempdir().unwrap();
    let single = dir.path().join("single");
    assert!(sweep(&single, &[]).status.success());
    let csv = read(single.join("sweep.csv"));
    assert_eq!(String::from_utf8_lossy(&csv).lines().count(), 13 + 1);

    // three shards sharing one directory; a shard writes no sweep.csv of its own
    let shared = dir.path().join("shared");
    for k in 0..3 {
        let o = sweep(&shared, &["--shard", &format!("{k}/3")]);
        assert!(o.status.success(), "{}", text(&o));
        assert!(!shared.join("sweep.csv").exists());
    }
    let m = pdamp(&["merge", shared.to_str().unwrap()]);
    assert!(m.status.success(), "{}", text(&m));
    assert_eq!(read(shared.join("sweep.csv")), csv);
    assert_eq!(
        read(shared.join("strobe.csv")),
        read(single.join("strobe.csv"))
    );

    // two shards in their own directories, merged into a third
    let (a, b, merged) = (
        dir.path().join("a"),
        dir.path().join("b"),
        dir.path().join("m"),
    );
    assert!(sweep(&a, &["--shard", "0/2"]).status.success());
    // shard 1 of 2 is missing: the merge names its points and writes nothing
    let m = pdamp(&[
        "merge",
        a.to_str().unwrap(),
        "--out",
        merged.to_str().unwrap(),
    ]);
    assert!(!m.status.success());
    let msg = text(&m);
    assert!(
        msg.contains("6 of 13 points") && msg.contains("1, 3, 5"),
        "{msg}"
    );
    assert!(!merged.join("sweep.csv").exists());
    assert!(sweep(&b, &["--shard", "1/2"]).status.success());
    let m = pdamp(&[
        "merge",
        a.to_str().unwrap(),
        b.to_str().unwrap(),
        "--out",
        merged.to_str().unwrap(),
    ]);
    assert!(m.status.success(), "{}", text(&m));
    assert!(text(&m).contains("7 from") && text(&m).contains("6 from"));
    assert_eq!(read(merged.join("sweep.csv")), csv);
    assert_eq!(
        read(merged.join("strobe.csv")),
        read(single.join("strobe.csv"))
    );

    // a shard whose points were lost resumes them and the merge is the same again
    for i in [1, 7] {
        std::fs::remove_file(b.join(format!("points/{i}.json"))).unwrap();
    }
    let again = sweep(&b, &["--shard", "1/2"]);
    assert!(
        text(&again).contains("2 computed, 4 already done"),
        "{}",
        text(&again)
    );
    assert!(pdamp(&[
        "merge",
        a.to_str().unwrap(),
        b.to_str().unwrap(),
        "--out",
        merged.to_str().unwrap()
    ])
    .status
    .success());
    assert_eq!(read(merged.join("sweep.csv")), csv);

    // shards of another sweep are not merged with these
    let other = dir.path().join("other");
    let mut o_args = vec!["sweep", SCENE, "--out", other.to_str().unwrap()];
    o_args.extend(["--no-analysis", "--vary", "excitation.frequency=3:5:1"]);
    assert!(pdamp(&o_args).status.success());
    let m = pdamp(&["merge", a.to_str().unwrap(), other.to_str().unwrap()]);
    assert!(!m.status.success());
    assert!(text(&m).contains("different sweep"), "{}", text(&m));
}

#[test]
fn timings_are_kept_out_of_sweep_csv() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o");
    assert!(sweep(&out, &[]).status.success());
    let csv = String::from_utf8(read(out.join("sweep.csv"))).unwrap();
    assert!(
        !csv.contains("wall_time") && !csv.contains("particle_steps"),
        "{csv}"
    );
    let timings = String::from_utf8(read(out.join("timings.csv"))).unwrap();
    let lines: Vec<&str> = timings.lines().collect();
    assert_eq!(lines[0], "point,wall_time_s");
    assert_eq!(lines.len(), 1 + 13);
    // every point has a positive wall time, in point order
    for (i, l) in lines[1..].iter().enumerate() {
        let (p, w) = l.split_once(',').unwrap();
        assert_eq!(p.parse::<usize>().unwrap(), i);
        assert!(w.parse::<f64>().unwrap() > 0.0, "{l}");
    }
    // the stream log has one line per finished point
    let stream = String::from_utf8(read(out.join("stream.csv"))).unwrap();
    assert_eq!(stream.lines().count(), 1 + 13);
}

#[test]
fn oversized_and_overflowing_grids_are_refused_up_front() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o");
    let t0 = std::time::Instant::now();
    let o = pdamp(&[
        "sweep",
        SCENE,
        "--out",
        out.to_str().unwrap(),
        "--vary",
        "excitation.frequency=1:30:0.000003",
    ]);
    assert!(!o.status.success());
    let msg = text(&o);
    // 9 666 667 values of one key: refused by the per-key limit (10⁶) with the count and the
    // key, before any value is made (the disk/memory estimate of a grid that large is checked
    // in `sweep::budget`'s unit test)
    assert!(
        msg.contains("excitation.frequency") && msg.contains("9666667"),
        "{msg}"
    );
    // refused before any point ran or any file was written (it took 43 s to fail before)
    assert!(t0.elapsed().as_secs() < 20, "{:?}", t0.elapsed());
    assert!(!out.join("points").exists());
    let o = pdamp(&[
        "sweep",
        SCENE,
        "--out",
        out.to_str().unwrap(),
        "--vary",
        "run.periods=0:-9223372036854775808:-1",
    ]);
    assert!(!o.status.success());
    let msg = text(&o);
    assert!(
        msg.contains("run.periods") && !msg.contains("panicked"),
        "{msg}"
    );
}

#[test]
fn slurm_script_has_the_array_and_the_dependent_merge() {
    let dir = tempfile::tempdir().unwrap();
    let script = dir.path().join("submit.sh");
    let out = dir.path().join("o");
    let mut a = vec![
        "slurm",
        SCENE,
        "--out",
        out.to_str().unwrap(),
        "--shards",
        "4",
        "--parallel",
        "2",
        "--script",
        script.to_str().unwrap(),
    ];
    a.extend(ARGS);
    let o = pdamp(&a);
    assert!(o.status.success(), "{}", text(&o));
    let s = String::from_utf8(read(script)).unwrap();
    for want in [
        "#SBATCH --array=0-3%2",
        "--dependency=afterok:",
        "--shard \"$SLURM_ARRAY_TASK_ID/4\"",
        "merge ",
        "#SBATCH --time=",
        "#SBATCH --mem=",
    ] {
        assert!(s.contains(want), "missing {want:?}:\n{s}");
    }
    // bash accepts it
    let n = Command::new("bash")
        .arg("-n")
        .arg(dir.path().join("submit.sh"))
        .status();
    if let Ok(st) = n {
        assert!(st.success());
    }
}
