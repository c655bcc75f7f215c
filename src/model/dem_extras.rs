//! The DEM's own figures of a run ([`DemExtras`]): written into `summary.json` beside the
//! figures every model reports ([`super::RunSummary`], field `dem`, flattened), under the
//! same keys as before they had a type.

use serde::{Deserialize, Deserializer, Serialize};

/// The DEM's own figures of a run, flattened into `summary.json` (one key per field, named
/// as the field). The fields are in alphabetical order, the order the keys were written in
/// before they had a type. A value that is not a number (e.g. `energy_collision_j_per_cycle`
/// without the energy ledger) is written as JSON `null` and read back as NaN. Counts are
/// stored as floating-point numbers (`summary.json` writes them as `12345.0`). A summary
/// of an earlier version that lacks a figure added since reads it as NaN; one without
/// `grains` and `dt_s` (another model's) has none ([`super::RunSummary::dem`] is `None`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DemExtras {
    /// Collective impacts of the bed on the ceiling per forcing cycle in the steady window
    /// (1/cycle).
    #[serde(default = "nan", deserialize_with = "nan_if_null")]
    pub bed_ceiling_impacts_per_cycle: f64,
    /// Collective impacts of the bed on the floor per forcing cycle in the steady window
    /// (1/cycle).
    #[serde(default = "nan", deserialize_with = "nan_if_null")]
    pub bed_floor_impacts_per_cycle: f64,
    /// Settled bed height estimate 2 (z_cm − floor) (m).
    #[serde(default = "nan", deserialize_with = "nan_if_null")]
    pub bed_height_m: f64,
    /// Candidate pairs of the neighbour list per grain, mean over the steady window's
    /// samples (–).
    #[serde(default = "nan", deserialize_with = "nan_if_null")]
    pub candidate_pairs_per_grain: f64,
    /// Shortest Hertz contact time at the design impact speed (s).
    #[serde(default = "nan", deserialize_with = "nan_if_null")]
    pub contact_time_s: f64,
    /// Time step (s).
    #[serde(deserialize_with = "nan_if_null")]
    pub dt_s: f64,
    /// 1 when the energy ledger's residual exceeds 1 % (the run also warned), else 0 (–).
    #[serde(default = "nan", deserialize_with = "nan_if_null")]
    pub energy_balance_warning: f64,
    /// Collision dissipation (normal damping) per forcing cycle in the steady window (J);
    /// NaN without the energy ledger.
    #[serde(default = "nan", deserialize_with = "nan_if_null")]
    pub energy_collision_j_per_cycle: f64,
    /// Dissipation in a bean bag's film (its bonds) per forcing cycle in the steady window
    /// (J); absent without a bag.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub energy_bag_j_per_cycle: Option<f64>,
    /// Friction dissipation (tangential) per forcing cycle in the steady window (J); NaN
    /// without the energy ledger.
    #[serde(default = "nan", deserialize_with = "nan_if_null")]
    pub energy_friction_j_per_cycle: f64,
    /// Total grain mass m_p (kg).
    #[serde(default = "nan", deserialize_with = "nan_if_null")]
    pub grain_mass_kg: f64,
    /// Number of grains (a count).
    #[serde(deserialize_with = "nan_if_null")]
    pub grains: f64,
    /// Neighbour-list builds during the driven run (a count).
    #[serde(default = "nan", deserialize_with = "nan_if_null")]
    pub neighbor_builds: f64,
    /// Grain–grain pairs in contact per grain, mean over the steady window's samples (half
    /// the mean coordination number; –).
    #[serde(default = "nan", deserialize_with = "nan_if_null")]
    pub pair_contacts_per_grain: f64,
    /// Grains × steps / CPU time of the driven run (particle-steps per CPU second); absent
    /// where the thread's CPU time could not be measured (a machine figure).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub particle_steps_per_cpu_s: Option<f64>,
    /// Grains × steps / wall-clock time of the driven run (particle-steps/s; a machine
    /// figure).
    #[serde(default = "nan", deserialize_with = "nan_if_null")]
    pub particle_steps_per_s: f64,
    /// Settling steps (a count).
    #[serde(default = "nan", deserialize_with = "nan_if_null")]
    pub settle_steps: f64,
    /// Simulated settling time before the drive (s).
    #[serde(default = "nan", deserialize_with = "nan_if_null")]
    pub settle_time_s: f64,
    /// Time steps of the driven run, settling excluded (a count).
    #[serde(default = "nan", deserialize_with = "nan_if_null")]
    pub steps: f64,
    /// Shorter of the contacts' normal and tangential viscous times at the design impact
    /// speed (s).
    #[serde(default = "nan", deserialize_with = "nan_if_null")]
    pub viscous_time_s: f64,
    /// Settled volume fraction Σ V_i / (Lx Ly · bed height) (–).
    #[serde(default = "nan", deserialize_with = "nan_if_null")]
    pub volume_fraction: f64,
    /// Grain–wall contacts per grain, mean over the steady window's samples (–).
    #[serde(default = "nan", deserialize_with = "nan_if_null")]
    pub wall_contacts_per_grain: f64,
    /// Wall-clock time of the driven run (s; a machine figure).
    #[serde(default = "nan", deserialize_with = "nan_if_null")]
    pub wall_time_s: f64,
}

impl DemExtras {
    /// The grains' own dissipation per forcing cycle (J) by its `summary.json` key: collision
    /// and friction.
    pub fn dissipation_j_per_cycle(&self) -> [(&'static str, f64); 2] {
        [
            (
                "energy_collision_j_per_cycle",
                self.energy_collision_j_per_cycle,
            ),
            (
                "energy_friction_j_per_cycle",
                self.energy_friction_j_per_cycle,
            ),
        ]
    }
}

/// NaN: a figure the summary does not have.
fn nan() -> f64 {
    f64::NAN
}

/// A number, or NaN for a JSON `null` (how a value that is not a number is written).
fn nan_if_null<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::NAN))
}
