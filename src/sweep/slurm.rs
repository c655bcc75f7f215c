//! A Slurm submission for a sweep: one job-array task per shard (`--array=0-(N-1)%P`, each
//! running `pdamp sweep … --shard $SLURM_ARRAY_TASK_ID/N` into the shared output directory)
//! and the merge (`pdamp merge DIR`) as a job that starts when every task has succeeded
//! (`--dependency=afterok:<array>`). Time and memory per task come from the scenes' cost
//! ([`super::cost`]).
//!
//! The script is plain bash: `bash submit.sh` submits both jobs and prints their ids. A task
//! that is killed (time limit, node failure) is resubmitted with the same script: the shard
//! resumes, skipping its finished points.

use super::continuation::{Continuation, Direction};
use super::cost::SweepCost;

/// What the submission asks of Slurm.
#[derive(Debug, Clone, PartialEq)]
pub struct SlurmJob {
    /// The `pdamp` executable the tasks run (an absolute path, or a name on the nodes' PATH).
    pub pdamp: String,
    /// `pdamp sweep` arguments besides `--shard` (scene, --set, --vary, --no-analysis, --out),
    /// each one shell word.
    pub sweep_args: Vec<String>,
    /// The shared output directory (on a file system every node sees).
    pub out: String,
    /// Number of shards N (array tasks).
    pub shards: usize,
    /// Most tasks running at once P (`%P`); `None`: no limit.
    pub parallel: Option<usize>,
    /// CPUs per task (the sweep's threads).
    pub cpus_per_task: usize,
    /// Safety factor on the estimated time (≥ 1).
    pub time_factor: f64,
    /// `--job-name`.
    pub name: String,
    /// `--partition`, if given.
    pub partition: Option<String>,
    /// `--account`, if given.
    pub account: Option<String>,
    /// A continuation sweep's settings (its flags are in `sweep_args`; the merge job reads
    /// them from the shards' manifest `sweep.json`): the shards are contiguous ranges of
    /// blocks instead of interleaved points.
    pub continuation: Option<Continuation>,
}

/// How the points are split over the tasks, for the script's header (one line).
fn split_note(job: &SlurmJob) -> String {
    let Some(c) = &job.continuation else {
        return format!(
            "interleaved shards (task K runs points i with i mod {} = K)",
            job.shards
        );
    };
    let branches = match c.direction {
        Direction::Up => "the up branch",
        Direction::Down => "the down branch",
        Direction::Both => "the up and down branches",
    };
    let block = c.block.map_or_else(
        || "one block a branch".to_string(),
        |b| format!("--block {b}"),
    );
    format!(
        "shards of contiguous blocks of a continuation sweep ({branches}, {block}, --overlap {} \
         warm-up points before each block after the first, --hysteresis-tol {}; the merge \
         reads these settings from the shards' sweep.json)",
        c.overlap, c.tolerance
    )
}

/// Shortest time limit asked for (s): Slurm schedules minutes.
const MIN_TIME_S: f64 = 120.0;

/// `D-HH:MM:SS` for Slurm's `--time`.
pub fn slurm_time(seconds: f64) -> String {
    let s = seconds.ceil().max(0.0) as u64;
    let (d, h, m, sec) = (s / 86_400, s / 3_600 % 24, s / 60 % 60, s % 60);
    format!("{d}-{h:02}:{m:02}:{sec:02}")
}

/// Quotes `word` for bash (single quotes unless it is plainly safe).
pub fn shell_word(word: &str) -> String {
    let safe = !word.is_empty()
        && word
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "-_./=:,+@%".contains(c));
    if safe {
        word.to_string()
    } else {
        format!("'{}'", word.replace('\'', r"'\''"))
    }
}

/// The submission script for `job` with the estimated `cost`.
pub fn submit_script(job: &SlurmJob, cost: &SweepCost) -> String {
    let cpus = job.cpus_per_task.max(1);
    // a shard's points run on `cpus` threads; wall ≈ CPU / cpus, times the safety factor
    let task_s = (cost.max_shard_cpu_s / cpus as f64 * job.time_factor.max(1.0)).max(MIN_TIME_S);
    let merge_s = (cost.points as f64 * 0.01 * job.time_factor.max(1.0)).max(MIN_TIME_S);
    let mem_mb = (cost.memory_bytes * 1.5 / 1e6).ceil().max(256.0) as u64;
    let array = match job.parallel {
        Some(p) => format!("0-{}%{p}", job.shards - 1),
        None => format!("0-{}", job.shards - 1),
    };
    let mut common = format!("#SBATCH --job-name={}\n", shell_word(&job.name));
    if let Some(p) = &job.partition {
        common += &format!("#SBATCH --partition={}\n", shell_word(p));
    }
    if let Some(a) = &job.account {
        common += &format!("#SBATCH --account={}\n", shell_word(a));
    }
    let out = shell_word(&job.out);
    let pdamp = shell_word(&job.pdamp);
    let args: Vec<String> = job.sweep_args.iter().map(|a| shell_word(a)).collect();
    format!(
        r#"#!/usr/bin/env bash
# Slurm submission of a pdamp sweep, written by `pdamp slurm`. Run it with: bash THIS_FILE
# {points} points in {shards} {split}.
# Estimated cost: {total_h:.3} core-hours in all; the largest shard {shard_s:.0} CPU-seconds
# (time limit below: that on {cpus} CPU(s) × {factor} safety factor, at least 2 min);
# memory {mem_mb} MB per task. A task killed before it finished: run this script again — the
# shards resume, skipping their finished points, and the merge runs once all have succeeded.
set -euo pipefail
mkdir -p {out}
array_id=$(sbatch --parsable <<'PDAMP_ARRAY'
#!/usr/bin/env bash
{common}#SBATCH --array={array}
#SBATCH --cpus-per-task={cpus}
#SBATCH --time={task_time}
#SBATCH --mem={mem_mb}M
#SBATCH --output={out}/slurm-%A_%a.out
export RAYON_NUM_THREADS="${{SLURM_CPUS_PER_TASK:-{cpus}}}"
exec {pdamp} sweep {args} --shard "$SLURM_ARRAY_TASK_ID/{shards}"
PDAMP_ARRAY
)
array_id=${{array_id%%;*}}
merge_id=$(sbatch --parsable --dependency=afterok:"$array_id" <<'PDAMP_MERGE'
#!/usr/bin/env bash
{common}#SBATCH --cpus-per-task=1
#SBATCH --time={merge_time}
#SBATCH --mem={mem_mb}M
#SBATCH --output={out}/slurm-merge-%j.out
exec {pdamp} merge {out}
PDAMP_MERGE
)
merge_id=${{merge_id%%;*}}
echo "array job $array_id ({shards} tasks), merge job $merge_id (after all succeed)"
"#,
        points = cost.points,
        shards = job.shards,
        split = split_note(job),
        total_h = cost.total_cpu_s / 3600.0,
        shard_s = cost.max_shard_cpu_s,
        factor = job.time_factor,
        task_time = slurm_time(task_s),
        merge_time = slurm_time(merge_s),
        args = args.join(" "),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn job() -> SlurmJob {
        SlurmJob {
            pdamp: "/opt/pdamp".into(),
            sweep_args: vec![
                "scene b.toml".into(),
                "--vary".into(),
                "excitation.frequency=1:30:0.5".into(),
                "--out".into(),
                "/scratch/o".into(),
            ],
            out: "/scratch/o".into(),
            shards: 8,
            parallel: Some(4),
            cpus_per_task: 2,
            time_factor: 2.0,
            name: "b".into(),
            partition: None,
            account: Some("proj".into()),
            continuation: None,
        }
    }

    #[test]
    fn script_has_the_array_the_dependency_and_the_estimates() {
        let cost = SweepCost {
            points: 59,
            total_cpu_s: 36_000.0,
            max_shard_cpu_s: 4_600.0,
            memory_bytes: 1e9,
        };
        let s = submit_script(&job(), &cost);
        for want in [
            "#SBATCH --array=0-7%4",
            "--dependency=afterok:\"$array_id\"",
            "--shard \"$SLURM_ARRAY_TASK_ID/8\"",
            // 4600 s / 2 CPUs × 2 = 4600 s = 1 h 16 min 40 s
            "#SBATCH --time=0-01:16:40",
            "#SBATCH --mem=1500M",
            "#SBATCH --account=proj",
            "'scene b.toml'",
            "exec /opt/pdamp merge /scratch/o",
            "10.000 core-hours",
        ] {
            assert!(s.contains(want), "missing {want:?} in\n{s}");
        }
        assert!(s.contains("8 interleaved shards (task K runs points i with i mod 8 = K)"));
        assert_eq!(slurm_time(90_061.2), "1-01:01:02");
        assert_eq!(shell_word("it's"), r"'it'\''s'");
    }
}
