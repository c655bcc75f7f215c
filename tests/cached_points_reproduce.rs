//! The committed figure data are what today's code makes: a few cached sweep points
//! (`figures/data/*/points/<i>.json`) are recomputed from their own `sweep.json` and compared
//! bit for bit — every value of the stored summary (amplitudes, energies, the analysis, the
//! replica test) and every strobe row; only the machine's timings (and the
//! prose around the numbers) may differ. When an engine change moves a trajectory, this test
//! says so (and the committed points, and `pdamp::model::PHYSICS_REVISION`, must then be renewed).

mod scratch;

use pdamp::scene::{parse_assignment, SceneSource};
use pdamp::sweep::{run_shard, Shard, SweepSpec, Vary};
use serde_json::Value;
use std::path::Path;

/// Values that measure the machine, not the system, and prose that words a verdict (its
/// numbers are compared where they are stored as numbers).
const SKIP: [&str; 6] = [
    "wall_time_s",
    "particle_steps_per_s",
    "particle_steps_per_cpu_s",
    "reason",
    "notes",
    "why",
];

fn read(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// Collects the paths where `a` and `b` differ, over the keys both have (a field added since
/// the point was written is not a difference) and leaving out the machine's timings and the prose.
fn diff(path: &str, a: &Value, b: &Value, out: &mut Vec<String>) {
    match (a, b) {
        (Value::Object(x), Value::Object(y)) => {
            for (k, v) in x {
                if let (Some(w), false) = (y.get(k), SKIP.contains(&k.as_str())) {
                    diff(&format!("{path}.{k}"), v, w, out);
                }
            }
        }
        (Value::Array(x), Value::Array(y)) if x.len() == y.len() => {
            for (n, (v, w)) in x.iter().zip(y).enumerate() {
                diff(&format!("{path}[{n}]"), v, w, out);
            }
        }
        _ if a != b => out.push(format!("{path}: {a} → {b}")),
        _ => {}
    }
}

/// Recomputes point `i` of the committed sweep in `figures/data/<dir>` and compares it.
fn recompute(dir: &str, i: usize) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("figures/data")
        .join(dir);
    let manifest = read(&root.join("sweep.json"));
    let set = manifest["set"]
        .as_array()
        .unwrap()
        .iter()
        .map(|kv| {
            parse_assignment(&format!(
                "{}={}",
                kv[0].as_str().unwrap(),
                kv[1].as_str().unwrap()
            ))
            .unwrap()
        })
        .collect();
    let varies: Vec<Vary> = manifest["vary"]
        .as_array()
        .unwrap()
        .iter()
        .map(|kv| {
            let values: Vec<&str> = kv[1]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_str().unwrap())
                .collect();
            Vary::parse(&format!("{}={}", kv[0].as_str().unwrap(), values.join(","))).unwrap()
        })
        .collect();
    let n: usize = varies.iter().map(|v| v.values.len()).product();
    let spec = SweepSpec {
        base: SceneSource::parse(manifest["scene"].as_str().unwrap()).unwrap(),
        set,
        varies,
        analyze: manifest["analysis"].as_bool().unwrap(),
    };
    let out = scratch::tempdir().unwrap();
    let report = run_shard(&spec, out.path(), Shard { index: i, count: n }, &|_| {}).unwrap();
    assert_eq!((report.computed, report.failed.len()), (1, 0), "{report:?}");
    let name = format!("points/{i}.json");
    let (old, new) = (read(&root.join(&name)), read(&out.path().join(&name)));
    assert_eq!(old["values"], new["values"]);
    let mut moved = Vec::new();
    diff("summary", &old["summary"], &new["summary"], &mut moved);
    assert!(moved.is_empty(), "{dir} point {i} moved: {moved:#?}");
    assert_eq!(
        old["strobe"], new["strobe"],
        "{dir} point {i}: the strobed states moved"
    );
}

#[test]
fn a_cached_impact_point_is_recomputed_bit_for_bit() {
    // the e = 0 model at 18 Hz, 13.12 s (the chapter-5 FRF)
    recompute("impact_frf_e0", 70);
}

#[test]
fn a_cached_dem_point_is_recomputed_bit_for_bit() {
    // the chapter-4 bed at 26 Hz, 200 periods, with its analysis and two-replica test (the
    // cheapest point of that sweep: ~20 s)
    recompute("dem_ch4_p200", 25);
}

#[test]
fn a_cached_point_of_the_main_jobs_chapter4_study_is_recomputed_bit_for_bit() {
    // the same bed and frequency at the main job's t_s/20 (`figures/data/dem_ch4_p200_dt20`,
    // what `pdamp reproduce --quick` computes)
    recompute("dem_ch4_p200_dt20", 25);
}
