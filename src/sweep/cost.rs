//! A sweep's estimated cost, from its scenes alone (nothing is run): CPU time and memory per
//! point, which `pdamp slurm` turns into the `--time` and `--mem` of each job-array task.
//!
//! # Formula
//! - Impact model (SPEC §3): t = P · c_impact, with P forcing periods and c_impact the cost of a
//!   period in the slowest band measured (below the primary's resonance with an impact per
//!   period, ~40 segments per period: [`IMPACT_S_PER_PERIOD`]), plus [`ANALYSIS_S`] per point
//!   with the analysis.
//! - DEM (SPEC §2): t = N · (T/dt + T_settle/dt) / r, with N grains, dt the scene's time step
//!   (automatic: the fraction of the Hertz contact time at the largest expected impact speed,
//!   [`crate::setup::DemSetup::time_step`]) and r = [`DEM_PARTICLE_STEPS_PER_S`].
//!
//! # Units
//! Seconds of one core, bytes.
//!
//! # Pitfalls
//! The constants were measured on one machine (2 cores, 2026; `figures/TRADEOFF.md` for the
//! DEM rate); a cluster's cores may be faster or slower. `pdamp slurm` adds a safety factor.

use super::continuation::{shard_value_runs, Continuation};
use super::runner::SweepSpec;
use super::shard::Shard;
use crate::error::SceneError;
use crate::scene::Scene;
use crate::setup::Setup;

/// CPU seconds per forcing period of the impact model in its slowest band (measured: 2000
/// periods in 16–31 ms at 6–10 Hz for scene B's one-particle model, e = 0).
pub const IMPACT_S_PER_PERIOD: f64 = 20e-6;
/// CPU seconds of the nonlinear analysis of one point (measured: 43 ms mean, 2000 periods).
pub const ANALYSIS_S: f64 = 0.1;
/// DEM particle-steps per CPU second of the driven run, one thread: the slowest measured on
/// scene B's 250 grains (2.5e7 at 12 Hz, softened 1000×, `figures/data/dem_ch4_p200`; 4.1–4.6e7
/// with real steel at 14–16 Hz, `figures/data/tradeoff_thesis_b_reference/reference`,
/// 2026-12-06); `pdamp slurm` adds its safety factor.
pub const DEM_PARTICLE_STEPS_PER_S: f64 = 2.5e7;
/// Memory of a process besides the DEM's particles (bytes).
const BASE_MEMORY: f64 = 200e6;
/// Memory per DEM grain (state, neighbour lists, contacts) (bytes).
const GRAIN_MEMORY: f64 = 20e3;

/// The estimated cost of one sweep point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointCost {
    /// CPU seconds.
    pub cpu_s: f64,
    /// Peak memory (bytes).
    pub memory_bytes: f64,
}

/// The cost of running `scene` (with the analysis if `analyze`).
///
/// # Errors
/// The scene's resolve errors (naming the key).
pub fn point_cost(scene: &Scene, analyze: bool) -> Result<PointCost, SceneError> {
    let resolved = scene.resolve()?;
    let analysis = if analyze { ANALYSIS_S } else { 0.0 };
    Ok(match &resolved.setup {
        Setup::Impact(_) => PointCost {
            cpu_s: scene.duration_s() * scene.frequency_hz() * IMPACT_S_PER_PERIOD + analysis,
            memory_bytes: BASE_MEMORY,
        },
        Setup::Dem(d) => {
            // the step every run of the scene takes, whatever it samples
            let dt = d.time_step.dt_s;
            let grains = d.model.grains.len() as f64;
            let steps = (d.window.duration_s + d.model.settle_time_s) / dt;
            PointCost {
                cpu_s: grains * steps / DEM_PARTICLE_STEPS_PER_S + analysis,
                memory_bytes: BASE_MEMORY + grains * GRAIN_MEMORY,
            }
        }
    })
}

/// The cost of every point of shard `k` of `n` (interleaved, as [`super::Shard`]) summed, the
/// largest over the shards, and the whole sweep's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SweepCost {
    /// Points in the grid.
    pub points: usize,
    /// CPU seconds of the whole sweep.
    pub total_cpu_s: f64,
    /// CPU seconds of the most expensive shard.
    pub max_shard_cpu_s: f64,
    /// Largest memory of a point (bytes).
    pub memory_bytes: f64,
}

/// The cost of `spec` split into `shards` interleaved shards.
///
/// # Errors
/// A point's scene errors (naming the key and the point).
pub fn sweep_cost(spec: &SweepSpec, shards: usize) -> Result<SweepCost, SceneError> {
    let n = super::vary::grid_len(&spec.varies).unwrap_or(0);
    let shards = shards.max(1);
    let mut per_shard = vec![0.0; shards];
    let mut memory: f64 = 0.0;
    for i in 0..n {
        let c = point_cost(&super::point::point_scene(spec, i)?, spec.analyze)?;
        per_shard[i % shards] += c.cpu_s;
        memory = memory.max(c.memory_bytes);
    }
    Ok(SweepCost {
        points: n,
        total_cpu_s: per_shard.iter().sum(),
        max_shard_cpu_s: per_shard.iter().copied().fold(0.0, f64::max),
        memory_bytes: memory,
    })
}

/// The cost of `spec` split into `shards` shards: interleaved for an ordinary sweep
/// ([`sweep_cost`]), contiguous ranges of blocks for a continuation sweep `c` (every branch's
/// points and every block's warm-up points, [`super::continuation`]).
///
/// # Errors
/// A point's scene errors (naming the key and the point).
pub fn sweep_cost_of(
    spec: &SweepSpec,
    c: Option<&Continuation>,
    shards: usize,
) -> Result<SweepCost, SceneError> {
    let (Some(c), Some(vary)) = (c, spec.varies.first()) else {
        return sweep_cost(spec, shards);
    };
    let values = vary.values.len();
    let mut per_value = Vec::with_capacity(values);
    for v in 0..values {
        per_value.push(point_cost(
            &super::point::point_scene(spec, v)?,
            spec.analyze,
        )?);
    }
    let per_shard: Vec<f64> = (0..shards.max(1))
        .map(|index| {
            let shard = Shard {
                index,
                count: shards.max(1),
            };
            shard_value_runs(&vary.values, c, shard)
                .iter()
                .map(|&v| per_value[v].cpu_s)
                .sum()
        })
        .collect();
    Ok(SweepCost {
        points: c.points(values),
        total_cpu_s: per_shard.iter().sum(),
        max_shard_cpu_s: per_shard.iter().copied().fold(0.0, f64::max),
        memory_bytes: per_value.iter().map(|p| p.memory_bytes).fold(0.0, f64::max),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn impact_cost_scales_with_periods_and_dem_with_grain_steps() {
        let mut s = Scene::thesis_b_impact();
        s.run.duration = None;
        s.run.periods = Some(2000.0);
        let c = point_cost(&s, false).unwrap();
        // 2000 periods × 20 µs = 40 ms
        assert!((c.cpu_s - 0.04).abs() < 1e-9, "{c:?}");
        let a = point_cost(&s, true).unwrap();
        assert!((a.cpu_s - c.cpu_s - ANALYSIS_S).abs() < 1e-12);
        // the DEM: twice the duration costs twice the driven steps (settling aside)
        let dem = |d: f64| {
            let mut s =
                Scene::from_toml(include_str!("../../data/scenes/thesis_b_soft.toml")).unwrap();
            s.run.periods = None;
            s.run.duration = Some(d);
            point_cost(&s, false).unwrap().cpu_s
        };
        let (one, two, three) = (dem(1.0), dem(2.0), dem(3.0));
        assert!(one > 0.0 && ((three - two) - (two - one)).abs() < 1e-9 * three);
    }

    #[test]
    fn continuation_cost_counts_both_branches_and_the_warm_up() {
        use crate::sweep::{Direction, Vary};
        let base = crate::scene::SceneSource::parse(include_str!(
            "../../data/scenes/thesis_b_impact.toml"
        ))
        .unwrap();
        let spec = SweepSpec {
            base,
            set: vec![("run.periods".into(), toml::Value::Integer(1000))],
            varies: vec![Vary::parse("excitation.frequency=10:15:0.5").unwrap()],
            analyze: false,
        };
        // 11 values, both branches, blocks of 4, 4, 3 (3 blocks a branch), warm-up 2 before
        // the second and third: 22 points plus 2 × 2 warm-up points a branch, each 1000
        // periods × 20 µs
        let c = Continuation {
            block: Some(4),
            overlap: 2,
            ..Continuation::new(Direction::Both)
        };
        let cost = sweep_cost_of(&spec, Some(&c), 3).unwrap();
        assert_eq!(cost.points, 22);
        assert!((cost.total_cpu_s - 30.0 * 0.02).abs() < 1e-9, "{cost:?}");
        // 6 blocks in 3 shards of 2: the largest (the down branch's last two blocks) runs
        // 2 + 4 and 2 + 3 points
        assert!(
            (cost.max_shard_cpu_s - 11.0 * 0.02).abs() < 1e-9,
            "{cost:?}"
        );
        // no continuation: the interleaved split
        assert_eq!(
            sweep_cost_of(&spec, None, 3).unwrap(),
            sweep_cost(&spec, 3).unwrap()
        );
    }
}
