//! Continuation sweeps (issue 13, item 7): `pdamp sweep --continuation up|down|both`.
//!
//! - Scene B's impact damper at e = 0.8 is multistable near 13 Hz: continued upward from
//!   12.5 Hz the periodic orbit with two impacts per forcing period persists to about 13.3 Hz,
//!   continued downward from 13.6 Hz the orbit with three impacts (5–11 % larger amplitude)
//!   persists to about 13.1 Hz; `hysteresis.csv` marks that interval.
//! - Point k of a chain starts from point k − 1's state at its last stroboscopic time: the
//!   same point run alone from that state (`--set` of the four initial-state keys) gives the
//!   same bytes.
//! - Sharded by blocks of the parameter range with warm-up overlap, the merged sweep.csv,
//!   strobe.csv, hysteresis.csv and seams.csv equal the single-process run's byte for byte;
//!   a rerun resumes (nothing recomputed, same files); bad requests are refused.
//! - `pdamp slurm` with a continuation sweep: the emitted script passes `--continuation`,
//!   `--block`, `--overlap` and `--hysteresis-tol` to every shard task, and the merge job finds
//!   them in the shards' manifest; run through a stand-in `sbatch` (each array task, then the
//!   dependent merge, executed in order by bash), the merged files equal the single run's.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const SCENE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/data/scenes/thesis_b_impact.toml"
);

fn pdamp(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_pdamp"))
        .args(args)
        .env("RAYON_NUM_THREADS", "2")
        .output()
        .unwrap()
}

fn sweep(out: &Path, args: &[&str]) -> Output {
    let mut a = vec![
        "sweep",
        SCENE,
        "--out",
        out.to_str().unwrap(),
        "--set",
        "damper.restitution=0.8",
    ];
    a.extend(args);
    let o = pdamp(&a);
    assert!(o.status.success(), "{}", text(&o));
    o
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

/// Rows of a CSV file as column → cell maps.
fn rows(p: PathBuf) -> Vec<std::collections::BTreeMap<String, String>> {
    let t = String::from_utf8(read(p)).unwrap();
    let mut lines = t.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    lines
        .map(|l| {
            head.iter()
                .zip(l.split(','))
                .map(|(h, c)| (h.to_string(), c.to_string()))
                .collect()
        })
        .collect()
}

fn num(r: &std::collections::BTreeMap<String, String>, c: &str) -> f64 {
    r[c].parse()
        .unwrap_or_else(|_| panic!("{c}: {:?}", r.get(c)))
}

#[test]
fn up_and_down_branches_differ_near_13_hz_at_e_0_8() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("hyst");
    let o = sweep(
        &out,
        &[
            "--set",
            "run.periods=500",
            "--vary",
            "excitation.frequency=12.5:13.6:0.05",
            "--continuation",
            "both",
        ],
    );
    let h = rows(out.join("hysteresis.csv"));
    println!("{}", text(&o));
    println!("f (Hz)   A_up (mm)  A_down (mm)  impacts/T up, down  regime up / down  hysteresis");
    for r in &h {
        println!(
            "{:7.3}  {:9.4}  {:11.4}  {:5.2} {:5.2}  {} / {}  {}",
            num(r, "excitation.frequency"),
            1e3 * num(r, "amplitude_up_m"),
            1e3 * num(r, "amplitude_down_m"),
            num(r, "impacts_per_cycle_up"),
            num(r, "impacts_per_cycle_down"),
            r["regime_up"],
            r["regime_down"],
            r["hysteresis"]
        );
    }
    assert_eq!(h.len(), 23);
    // below 13 Hz one periodic orbit with two impacts per period: nothing marked
    for r in h.iter().filter(|r| num(r, "excitation.frequency") < 12.99) {
        assert_eq!(r["hysteresis"], "0", "{r:?}");
        assert_eq!(r["regime_up"], "periodic", "{r:?}");
    }
    // the hysteresis interval: going up the 2-impact orbit persists, coming down the 3-impact
    // orbit (larger amplitude); both periodic
    let marked: Vec<f64> = h
        .iter()
        .filter(|r| r["hysteresis"] == "1")
        .map(|r| num(r, "excitation.frequency"))
        .collect();
    let two_three: Vec<f64> = h
        .iter()
        .filter(|r| {
            r["hysteresis"] == "1"
                && num(r, "impacts_per_cycle_up").round() == 2.0
                && num(r, "impacts_per_cycle_down").round() == 3.0
                && r["regime_up"] == "periodic"
                && r["regime_down"] == "periodic"
                && num(r, "amplitude_down_m") > num(r, "amplitude_up_m")
        })
        .map(|r| num(r, "excitation.frequency"))
        .collect();
    assert!(
        two_three.len() >= 3,
        "marked {marked:?}, 2-vs-3 {two_three:?}"
    );
    assert!(
        two_three.iter().all(|f| (13.0..13.35).contains(f)),
        "{two_three:?}"
    );
    assert!(text(&o).contains("hysteresis ("), "{}", text(&o));
    // sweep.csv: 2 × 23 points, a branch column, the down branch in points 23..45
    let s = rows(out.join("sweep.csv"));
    assert_eq!(s.len(), 46);
    assert_eq!(s[0]["branch"], "up");
    assert_eq!(s[23]["branch"], "down");
    assert_eq!(s[23]["excitation.frequency"], s[0]["excitation.frequency"]);
}

#[test]
fn each_point_starts_from_the_previous_points_last_strobe_state() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("up");
    let args = [
        "--no-analysis",
        "--set",
        "run.periods=200",
        "--vary",
        "excitation.frequency=14:15:0.25",
    ];
    let mut a = args.to_vec();
    a.extend(["--continuation", "up"]);
    sweep(&out, &a);
    let s = rows(out.join("sweep.csv"));
    let strobe = rows(out.join("strobe.csv"));
    assert_eq!(s.len(), 5);
    for (k, point) in s.iter().enumerate().skip(1) {
        let prev = strobe
            .iter()
            .rfind(|r| r["point"] == (k - 1).to_string())
            .unwrap();
        let (gz, bz, gv, bv) = (
            num(prev, "grain_z_m"),
            num(prev, "box_z_m"),
            num(prev, "grain_v_m_s"),
            num(prev, "box_v_m_s"),
        );
        let h = (gz - bz).max(0.0);
        let f = &point["excitation.frequency"];
        let alone = dir.path().join(format!("alone{k}"));
        let sets = [
            format!("primary.initial_displacement={bz:?}"),
            format!("primary.initial_velocity={bv:?}"),
            format!("damper.initial_height={h:?}"),
            format!("damper.initial_velocity={gv:?}"),
            format!("excitation.frequency={f}"),
        ];
        let mut b: Vec<&str> = vec!["--no-analysis", "--set", "run.periods=200"];
        for x in &sets[..4] {
            b.extend(["--set", x.as_str()]);
        }
        b.extend(["--vary", sets[4].as_str()]);
        sweep(&alone, &b);
        let one = rows(alone.join("sweep.csv"));
        for c in [
            "amplitude_m",
            "energy_input_j_per_cycle",
            "impacts_per_cycle",
        ] {
            assert_eq!(one[0][c], point[c], "point {k} ({f} Hz), {c}");
        }
    }
    // the chain differs from independent runs from rest somewhere (else this proves nothing)
    let plain = dir.path().join("plain");
    sweep(&plain, &args);
    let p = rows(plain.join("sweep.csv"));
    assert!((1..5).any(|k| p[k]["energy_input_j_per_cycle"] != s[k]["energy_input_j_per_cycle"]));
}

#[test]
fn block_shards_with_overlap_merge_to_the_single_process_files() {
    let dir = tempfile::tempdir().unwrap();
    let args = [
        "--no-analysis",
        "--set",
        "run.periods=120",
        "--vary",
        "excitation.frequency=12:18:0.5",
        "--continuation",
        "both",
        "--block",
        "4",
        "--overlap",
        "2",
    ];
    let single = dir.path().join("single");
    sweep(&single, &args);
    let files = ["sweep.csv", "strobe.csv", "hysteresis.csv", "seams.csv"];
    // 13 values, blocks of 4: 4 blocks a branch; seams: 3 per branch × 2 warm-up points
    assert_eq!(rows(single.join("seams.csv")).len(), 12);
    assert_eq!(rows(single.join("sweep.csv")).len(), 26);
    assert!(single.join("points/warmup").is_dir());

    // 3 shards in one directory, then merge
    let shared = dir.path().join("shared");
    for k in 0..3 {
        let mut a = args.to_vec();
        let s = format!("{k}/3");
        a.extend(["--shard", s.as_str()]);
        sweep(&shared, &a);
        assert!(!shared.join("sweep.csv").exists());
    }
    let m = pdamp(&["merge", shared.to_str().unwrap()]);
    assert!(m.status.success(), "{}", text(&m));
    for f in files {
        assert_eq!(read(shared.join(f)), read(single.join(f)), "{f}");
    }
    // 5 shards each in its own directory, merged into another
    let dirs: Vec<PathBuf> = (0..5).map(|k| dir.path().join(format!("d{k}"))).collect();
    for (k, d) in dirs.iter().enumerate() {
        let mut a = args.to_vec();
        let s = format!("{k}/5");
        a.extend(["--shard", s.as_str()]);
        sweep(d, &a);
    }
    let merged = dir.path().join("merged");
    let mut m = vec!["merge"];
    m.extend(dirs.iter().map(|d| d.to_str().unwrap()));
    m.extend(["--out", merged.to_str().unwrap()]);
    let o = pdamp(&m);
    assert!(o.status.success(), "{}", text(&o));
    for f in files {
        assert_eq!(read(merged.join(f)), read(single.join(f)), "{f}");
    }
    // a rerun resumes: nothing computed, the same files
    let o = sweep(&single, &args);
    assert!(
        text(&o).contains("0 computed, 26 already done"),
        "{}",
        text(&o)
    );
    assert_eq!(
        read(single.join("sweep.csv")),
        read(shared.join("sweep.csv"))
    );
}

#[test]
fn bad_continuation_requests_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let run = |extra: &[&str]| {
        let out = dir.path().join("bad");
        let mut a = vec![
            "sweep",
            SCENE,
            "--out",
            out.to_str().unwrap(),
            "--no-analysis",
            "--set",
            "run.periods=50",
        ];
        a.extend(extra);
        let o = pdamp(&a);
        assert!(!o.status.success(), "{extra:?}");
        text(&o)
    };
    let e = run(&[
        "--vary",
        "excitation.frequency=10,11",
        "--vary",
        "damper.restitution=0.5,0.8",
        "--continuation",
        "up",
    ]);
    assert!(e.contains("exactly one key"), "{e}");
    let e = run(&[
        "--vary",
        "excitation.frequency=10:12:1",
        "--continuation",
        "sideways",
    ]);
    assert!(e.contains("--continuation"), "{e}");
    let e = run(&[
        "--vary",
        "excitation.frequency=10:12:1",
        "--continuation",
        "up",
        "--shard",
        "1/2",
    ]);
    assert!(e.contains("--block"), "{e}");
    let e = run(&[
        "--vary",
        "excitation.frequency=10:12:1",
        "--continuation",
        "up",
        "--block",
        "2",
        "--overlap",
        "2",
    ]);
    assert!(e.contains("--overlap"), "{e}");
}

/// The sweep: 13 values, both branches, blocks of 4 with 2 warm-up points, a non-default
/// tolerance (so that a dropped flag shows in hysteresis.csv's header or marks).
const SLURM_ARGS: [&str; 16] = [
    "--set",
    "damper.restitution=0.8",
    "--set",
    "run.periods=120",
    "--no-analysis",
    "--vary",
    "excitation.frequency=12:18:0.5",
    "--continuation",
    "both",
    "--block",
    "4",
    "--overlap",
    "2",
    "--hysteresis-tol",
    "0.07",
    "-q",
];

/// A stand-in `sbatch --parsable [--dependency=…]` reading the job script on stdin: an array
/// job (`#SBATCH --array=0-M[%P]`) runs every task in order with `SLURM_ARRAY_TASK_ID` set,
/// any other job runs once; prints a job id. A failing task fails the submission.
const FAKE_SBATCH: &str = r#"#!/usr/bin/env bash
set -euo pipefail
script=$(mktemp)
cat > "$script"
echo "$*" >> "$(dirname "$0")/sbatch.log"
range=$(sed -n 's/^#SBATCH --array=0-\([0-9]*\).*/\1/p' "$script")
if [ -n "$range" ]; then
  for k in $(seq 0 "$range"); do
    SLURM_ARRAY_TASK_ID=$k SLURM_CPUS_PER_TASK=1 bash "$script" >> "$(dirname "$0")/tasks.log" 2>&1
  done
  echo 101
else
  bash "$script" >> "$(dirname "$0")/tasks.log" 2>&1
  echo 102
fi
rm -f "$script"
"#;

fn slurm_script(dir: &Path, out: &Path, shards: &str, extra: &[&str]) -> Output {
    let script = dir.join("submit.sh");
    let mut a = vec![
        "slurm",
        SCENE,
        "--out",
        out.to_str().unwrap(),
        "--shards",
        shards,
        "--script",
        script.to_str().unwrap(),
    ];
    a.extend(SLURM_ARGS);
    a.extend(extra);
    pdamp(&a)
}

#[test]
fn slurm_continuation_shards_and_merge_equal_the_single_run() {
    let dir = tempfile::tempdir().unwrap();
    let single = dir.path().join("single");
    let mut a = vec!["sweep", SCENE, "--out", single.to_str().unwrap()];
    a.extend(SLURM_ARGS);
    let o = pdamp(&a);
    assert!(o.status.success(), "{}", text(&o));

    let out = dir.path().join("shared");
    let o = slurm_script(dir.path(), &out, "3", &[]);
    assert!(o.status.success(), "{}", text(&o));
    let s = String::from_utf8(read(dir.path().join("submit.sh"))).unwrap();
    let task = s
        .lines()
        .find(|l| l.contains(" sweep ") && l.contains("--shard"))
        .unwrap_or_else(|| panic!("no task line in\n{s}"));
    for want in [
        "--continuation both",
        "--block 4",
        "--overlap 2",
        "--hysteresis-tol 0.07",
        "--no-analysis",
        "--shard \"$SLURM_ARRAY_TASK_ID/3\"",
    ] {
        assert!(
            task.contains(want),
            "missing {want:?} in the task line {task:?}"
        );
    }
    for want in [
        "#SBATCH --array=0-2",
        "--dependency=afterok:",
        "shards of contiguous blocks of a continuation sweep",
        // 13 values × 2 branches
        "# 26 points in 3 shards",
    ] {
        assert!(s.contains(want), "missing {want:?} in\n{s}");
    }

    // run it: the three shard tasks, then the merge
    let bin = dir.path().join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    let sbatch = bin.join("sbatch");
    std::fs::write(&sbatch, FAKE_SBATCH).unwrap();
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&sbatch, std::fs::Permissions::from_mode(0o755)).unwrap();
    }
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let run = Command::new("bash")
        .arg(dir.path().join("submit.sh"))
        .env("PATH", path)
        .env("RAYON_NUM_THREADS", "2")
        .output()
        .unwrap();
    let log = std::fs::read_to_string(bin.join("tasks.log")).unwrap_or_default();
    assert!(run.status.success(), "{}\n{log}", text(&run));
    assert!(
        text(&run).contains("array job 101 (3 tasks), merge job 102"),
        "{}",
        text(&run)
    );
    let calls = std::fs::read_to_string(bin.join("sbatch.log")).unwrap();
    assert!(calls.contains("--dependency=afterok:101"), "{calls}");
    for f in ["sweep.csv", "strobe.csv", "hysteresis.csv", "seams.csv"] {
        assert_eq!(read(out.join(f)), read(single.join(f)), "{f}\n{log}");
    }
}

#[test]
fn slurm_continuation_refusals_name_the_flag() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o");
    // 13 values, blocks of 4: 8 blocks in all, 9 shards are too many
    let o = slurm_script(dir.path(), &out, "9", &[]);
    assert!(!o.status.success());
    let e = text(&o);
    assert!(e.contains("--shards") && e.contains("8"), "{e}");
    // the continuation flags still need --continuation
    let o = pdamp(&[
        "slurm",
        SCENE,
        "--out",
        out.to_str().unwrap(),
        "--shards",
        "2",
        "--vary",
        "excitation.frequency=12:18:0.5",
        "--block",
        "4",
    ]);
    assert!(!o.status.success());
    assert!(text(&o).contains("--continuation"), "{}", text(&o));
    // a bad direction
    let o = pdamp(&[
        "slurm",
        SCENE,
        "--out",
        out.to_str().unwrap(),
        "--shards",
        "2",
        "--vary",
        "excitation.frequency=12:18:0.5",
        "--continuation",
        "sideways",
    ]);
    assert!(!o.status.success());
    assert!(text(&o).contains("--continuation"), "{}", text(&o));
    assert!(!dir.path().join("submit.sh").exists());
}
