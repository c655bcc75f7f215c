//! Stable-toolchain mutation fuzzing of the targets in `fuzz/targets.rs` (the same targets as
//! the cargo-fuzz crate in `fuzz/`, which needs nightly).
//!
//! Ignored by default; CI runs it (`.ci/run`) with 20 000 executions per target:
//!
//! ```text
//! cargo test --release --test fuzz_mutation -- --ignored --nocapture
//! PDAMP_FUZZ_EXECS=1000000 cargo test --release --test fuzz_mutation -- --ignored --nocapture
//! PDAMP_FUZZ_TARGET=analysis PDAMP_FUZZ_REPLAY=target/fuzz-findings/analysis-hang-0 \
//!     cargo test --release --test fuzz_mutation -- --ignored --nocapture   # replay one input
//! ```
//!
//! Seeds: the files in `data/` (scenes, the series) and a few hand-written inputs per target.
//! Each execution mutates a seed (bit flips, byte insertions and deletions, spans duplicated
//! or spliced from another seed, "interesting" tokens such as `1e308`, `5e-324`, `nan`,
//! `-9223372036854775808`, `,`, `;`), deterministically from `PDAMP_FUZZ_SEED` (default 1).
//! A panic is caught, counted and its input printed; an execution slower than
//! [`HANG_S`] seconds counts as a hang. The test fails on any panic or hang. An execution
//! that has not ended after [`ABORT_S`] seconds (an endless loop) stops the run with its input
//! saved under `target/fuzz-findings/`.

#[path = "../fuzz/targets.rs"]
#[allow(dead_code)]
mod targets;

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::time::{Duration, Instant};

/// An execution slower than this counts as a hang (s).
const HANG_S: f64 = 2.0;

/// An execution still running after this long is a hang that may never end (an endless loop):
/// a watchdog saves its input, prints it and stops the process (s).
const ABORT_S: u64 = 60;

/// Tokens spliced into inputs.
const TOKENS: [&str; 30] = [
    "1e308",
    "1.8e308",
    "-1e308",
    "5e-324",
    "1e-300",
    "0",
    "-0",
    "nan",
    "inf",
    "-inf",
    "9223372036854775807",
    "-9223372036854775808",
    "18446744073709551616",
    "1e6",
    "0.5",
    ",",
    ";",
    ":",
    "=",
    "\n",
    "\t",
    " ",
    "#",
    "\"",
    "[",
    "]",
    "{",
    "}",
    "=auto",
    ",5e0",
];

/// The seeds of each target.
fn seeds(target: &str) -> Vec<Vec<u8>> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let read_dir = |dir: &str| -> Vec<Vec<u8>> {
        let mut files: Vec<_> = std::fs::read_dir(root.join(dir))
            .unwrap()
            .map(|e| e.unwrap().path())
            .collect();
        files.sort();
        files
            .into_iter()
            .map(|p| std::fs::read(p).unwrap())
            .collect()
    };
    let text = |v: &[&str]| v.iter().map(|s| s.as_bytes().to_vec()).collect::<Vec<_>>();
    match target {
        "scene_toml" => read_dir("data/scenes"),
        "set_assignment" => text(&[
            "excitation.frequency=12",
            "damper.gap=inf",
            "run.periods=200",
            "primary.mass=2.37",
            "primary.damping_ratio=0.01",
            "damper.restitution=0.5",
            "run.sample_interval=1e-3",
            "run.dt=",
        ]),
        "vary_range" => text(&[
            "excitation.frequency=10:20:2",
            "excitation.frequency=0:-9223372036854775808:-1",
            "damper.gap=0.001,0.002,inf",
            "run.periods=1:100:1",
            "excitation.frequency=9.5:10.5:0.25",
        ]),
        "series_reader" | "analysis" => {
            // the series of data/ cut to its first 300 lines, and small hand-written files
            let mut s: Vec<Vec<u8>> = read_dir("data/series")
                .into_iter()
                .map(|b| {
                    let t = String::from_utf8(b).unwrap();
                    t.lines()
                        .take(300)
                        .collect::<Vec<_>>()
                        .join("\n")
                        .into_bytes()
                })
                .collect();
            s.extend(text(&[
                "time_s,base_u_m,grain_z_m\n0,1,5\n0.5,2,6\n1.0,3,7\n",
                "t;x\n0;-4,408e0\n0,1;2,5e-1\n",
                "1 2\n3\t4\n",
                "# c\nx\n1.5\n2.5\n",
            ]));
            if target == "analysis" {
                // an accepted series long enough for the chain: a noisy sine
                let mut t = String::from("time_s,x\n");
                for i in 0..300 {
                    let x = (0.3 * i as f64).sin() + 0.01 * ((i * 7919) % 13) as f64;
                    t.push_str(&format!("{},{x}\n", i as f64 * 0.01));
                }
                s.push(t.into_bytes());
            }
            s
        }
        other => panic!("unknown target {other}"),
    }
}

/// One mutation of `input` (several with probability ½), splicing from `pool`.
fn mutate(rng: &mut ChaCha8Rng, input: &[u8], pool: &[Vec<u8>]) -> Vec<u8> {
    let mut v = input.to_vec();
    loop {
        let len = v.len();
        match rng.random_range(0..7) {
            0 if len > 0 => {
                let i = rng.random_range(0..len);
                v[i] ^= 1 << rng.random_range(0..8);
            }
            1 => {
                let i = rng.random_range(0..=len);
                v.insert(i, rng.random());
            }
            2 if len > 0 => {
                let a = rng.random_range(0..len);
                let b = (a + rng.random_range(1..=16)).min(len);
                v.drain(a..b);
            }
            3 if len > 0 => {
                let a = rng.random_range(0..len);
                let b = (a + rng.random_range(1..=32)).min(len);
                let span = v[a..b].to_vec();
                let at = rng.random_range(0..=v.len());
                v.splice(at..at, span);
            }
            4 | 5 => {
                let tok = TOKENS[rng.random_range(0..TOKENS.len())].as_bytes();
                let at = rng.random_range(0..=len);
                // replace the number-like run at `at`, or insert
                let end = (at..len)
                    .find(|&j| !(v[j].is_ascii_alphanumeric() || b".-+".contains(&v[j])))
                    .unwrap_or(len);
                v.splice(at..end, tok.iter().copied());
            }
            _ => {
                let other = &pool[rng.random_range(0..pool.len())];
                if !other.is_empty() {
                    let a = rng.random_range(0..other.len());
                    let b = (a + rng.random_range(1..=64)).min(other.len());
                    let at = rng.random_range(0..=len);
                    v.splice(at..at, other[a..b].iter().copied());
                }
            }
        }
        if v.len() > 64 * 1024 {
            v.truncate(64 * 1024);
        }
        if rng.random_bool(0.5) {
            return v;
        }
    }
}

/// Per-target result.
struct Outcome {
    execs: u64,
    panics: Vec<(String, Vec<u8>)>,
    hangs: Vec<(f64, Vec<u8>)>,
    elapsed: Duration,
}

/// The execution in progress, for the watchdog: its input and when it started.
struct Current {
    input: std::sync::Arc<Vec<u8>>,
    started: Instant,
    target: &'static str,
}

/// Starts a thread that stops the process when one execution runs longer than [`ABORT_S`],
/// saving and printing its input first.
fn watchdog(current: std::sync::Arc<std::sync::Mutex<Option<Current>>>) {
    std::thread::spawn(move || loop {
        std::thread::sleep(Duration::from_secs(1));
        let guard = current.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(c) = guard.as_ref() {
            let dt = c.started.elapsed();
            if dt > Duration::from_secs(ABORT_S) {
                let path = save_finding(c.target, "endless", 0, &c.input);
                eprintln!(
                    "{}: an execution has run for {:.0} s (endless loop?) on {:?} (whole input: {path})",
                    c.target,
                    dt.as_secs_f64(),
                    String::from_utf8_lossy(&c.input[..c.input.len().min(400)])
                );
                std::process::exit(101);
            }
        }
    });
}

fn run_target(
    name: &'static str,
    f: fn(&[u8]),
    execs: u64,
    seed: u64,
    current: &std::sync::Mutex<Option<Current>>,
) -> Outcome {
    let pool = seeds(name);
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ name.len() as u64);
    let mut out = Outcome {
        execs: 0,
        panics: Vec::new(),
        hangs: Vec::new(),
        elapsed: Duration::ZERO,
    };
    let start = Instant::now();
    for k in 0..execs {
        let base = &pool[(k as usize) % pool.len()];
        // shared with the watchdog without copying the bytes
        let input = std::sync::Arc::new(if k < pool.len() as u64 {
            base.clone()
        } else {
            mutate(&mut rng, base, &pool)
        });
        let t0 = Instant::now();
        *current.lock().unwrap_or_else(|e| e.into_inner()) = Some(Current {
            input: std::sync::Arc::clone(&input),
            started: t0,
            target: name,
        });
        let r = std::panic::catch_unwind(|| f(&input));
        let dt = t0.elapsed().as_secs_f64();
        if let Err(payload) = r {
            let msg = payload
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            out.panics.push((msg, input.to_vec()));
        }
        if dt > HANG_S {
            out.hangs.push((dt, input.to_vec()));
        }
        out.execs += 1;
        if out.execs.is_multiple_of(100_000) {
            eprintln!(
                "{name}: {} executions, {} panics, {} hangs, {:.0} s",
                out.execs,
                out.panics.len(),
                out.hangs.len(),
                start.elapsed().as_secs_f64()
            );
        }
    }
    *current.lock().unwrap_or_else(|e| e.into_inner()) = None;
    out.elapsed = start.elapsed();
    out
}

#[test]
#[ignore = "mutation fuzzing: CI runs it with --ignored (see the module documentation)"]
fn mutation_fuzz_every_target() {
    let execs: u64 = std::env::var("PDAMP_FUZZ_EXECS")
        .ok()
        .map(|s| s.parse().expect("PDAMP_FUZZ_EXECS is a number"))
        .unwrap_or(20_000);
    let seed: u64 = std::env::var("PDAMP_FUZZ_SEED")
        .ok()
        .map(|s| s.parse().expect("PDAMP_FUZZ_SEED is a number"))
        .unwrap_or(1);
    let only = std::env::var("PDAMP_FUZZ_TARGET").ok();
    if let Ok(path) = std::env::var("PDAMP_FUZZ_REPLAY") {
        // one saved input (e.g. from target/fuzz-findings/) through the chosen target, timed
        let input = std::fs::read(&path).expect("PDAMP_FUZZ_REPLAY names a readable file");
        let name = only
            .as_deref()
            .expect("PDAMP_FUZZ_REPLAY needs PDAMP_FUZZ_TARGET");
        let (_, f) = targets::TARGETS
            .iter()
            .find(|(n, _)| *n == name)
            .expect("PDAMP_FUZZ_TARGET names a target");
        for _ in 0..3 {
            let t0 = Instant::now();
            f(&input);
            println!("{name} on {path}: {:.3} s", t0.elapsed().as_secs_f64());
        }
        return;
    }
    // the panics are caught and reported below, not printed one by one
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let current = std::sync::Arc::new(std::sync::Mutex::new(None));
    watchdog(current.clone());
    let mut failed = Vec::new();
    println!("| target | executions | panics | hangs (> {HANG_S} s) | time |");
    println!("|---|---|---|---|---|");
    for (name, f) in targets::TARGETS {
        if only.as_deref().is_some_and(|o| o != name) {
            continue;
        }
        let o = run_target(name, f, execs, seed, &current);
        println!(
            "| {name} | {} | {} | {} | {:.1} s |",
            o.execs,
            o.panics.len(),
            o.hangs.len(),
            o.elapsed.as_secs_f64()
        );
        for (k, (msg, p)) in o.panics.iter().enumerate().take(3) {
            failed.push(format!(
                "{name}: panic `{}` on {:?} (whole input: {})",
                &msg[..msg.floor_char_boundary(600)],
                String::from_utf8_lossy(&p[..p.len().min(400)]),
                save_finding(name, "panic", k, p)
            ));
        }
        for (k, (dt, p)) in o.hangs.iter().enumerate().take(3) {
            failed.push(format!(
                "{name}: {dt:.1} s on {:?} (whole input: {})",
                String::from_utf8_lossy(&p[..p.len().min(400)]),
                save_finding(name, "hang", k, p)
            ));
        }
    }
    std::panic::set_hook(hook);
    assert!(failed.is_empty(), "{}", failed.join("\n"));
}

/// Saves the whole input of a finding to `target/fuzz-findings/<target>-<kind>-<n>` and
/// returns the path.
fn save_finding(target: &str, kind: &str, n: usize, input: &[u8]) -> String {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target/fuzz-findings");
    let _ = std::fs::create_dir_all(&dir);
    let path = dir.join(format!("{target}-{kind}-{n}"));
    let _ = std::fs::write(&path, input);
    path.display().to_string()
}
