//! What a driven DEM run measures while it steps, besides the samples it sends to its
//! observer: the steady window's statistics, the stroboscopic clock and the energy watch.
//!
//! - [`SteadyWindow`]: over the last `steady_fraction` of the run, the box's extremes (the
//!   amplitude Z = (z_max − z_min)/2, m), the energy ledger at the window's start (so that
//!   dissipation and input are reported per forcing cycle, J/cycle), the bed's collective
//!   impacts ([`BedImpacts`]) and the mean contact counts per grain at the window's samples;
//! - [`StrobeClock`]: whether a forcing phase t = nT (T = 1/f) falls inside the coming step,
//!   and the state before it, so that the strobe point is interpolated between the two states
//!   around nT ([`super::run::interpolate_strobe`]) — never read off a resampled series;
//! - [`EnergyWatch`]: the sample of the current state with its energy ledger (SPEC §6: stored
//!   energy E − E₀ − W_base + D = residual), and the stability check that stops a run whose
//!   state turns non-finite, whose grains leave the box or whose energy grows without input.

use crate::error::SimError;
use crate::observe::{DemSampleState, ModelSample, Sample};

use super::bed_impacts::BedImpacts;
use super::energy::{balance, EnergyLedger, EnergyState};
use super::stability::check;
use super::world::{ContactCounts, ContactsPerGrain, DemWorld};

/// The steady window's running statistics (from step `from_step` on).
#[derive(Debug, Clone)]
pub(crate) struct SteadyWindow {
    /// First step of the window.
    pub from_step: u64,
    /// Time (s) and ledger when the window started.
    start: Option<(f64, EnergyLedger)>,
    /// Smallest and largest box position in the window (m).
    pub z_min_m: f64,
    pub z_max_m: f64,
    /// Collective bed–floor and bed–ceiling impacts in the window.
    pub impacts: BedImpacts,
    /// Sum of the contact counts at the window's samples, and how many samples.
    contacts: (ContactCounts, usize),
}

impl SteadyWindow {
    /// A window from step `from_step` for a bed of mass `m_p` (kg) under gravity `g` (m/s²)
    /// forced at `frequency_hz` (Hz).
    pub fn new(from_step: u64, m_p: f64, g: f64, frequency_hz: f64) -> Self {
        SteadyWindow {
            from_step,
            start: None,
            z_min_m: f64::INFINITY,
            z_max_m: f64::NEG_INFINITY,
            impacts: BedImpacts::new(m_p, g, frequency_hz),
            contacts: (ContactCounts::default(), 0),
        }
    }

    /// Counts the contacts of the state after step `k` (a sample step; nothing before the
    /// window). A count passes over every candidate pair and grain, so it is taken at the
    /// samples only, not at every step.
    pub fn count_contacts(&mut self, k: u64, w: &DemWorld) {
        if k < self.from_step {
            return;
        }
        let (sum, count) = &mut self.contacts;
        *sum += w.contact_counts();
        *count += 1;
    }

    /// Mean contact counts per grain over the window's samples; those of the state `w` when
    /// the window holds no sample.
    pub fn contacts_per_grain(&self, w: &DemWorld) -> ContactsPerGrain {
        match self.contacts {
            (_, 0) => ContactsPerGrain::of(w.contact_counts(), w.len()),
            (sum, count) => ContactsPerGrain::of(sum, count * w.len()),
        }
    }

    /// Takes the state after step `k`.
    pub fn observe(&mut self, k: u64, w: &DemWorld) {
        if k < self.from_step {
            return;
        }
        if self.start.is_none() {
            self.start = Some((w.t, w.ledger));
        }
        self.z_min_m = self.z_min_m.min(w.box_z);
        self.z_max_m = self.z_max_m.max(w.box_z);
        let (_, v_cm) = w.step_cm();
        self.impacts.observe(v_cm - w.box_v, w.grain_force_n);
    }

    /// Forcing cycles since the window started, at the state `w` (0 before).
    pub fn cycles(&self, w: &DemWorld, frequency_hz: f64) -> f64 {
        self.start.map_or(0.0, |(t0, _)| (w.t - t0) * frequency_hz)
    }

    /// The change of one ledger entry per forcing cycle over the window (J/cycle); `None`
    /// when the window holds no cycle.
    pub fn per_cycle(
        &self,
        w: &DemWorld,
        frequency_hz: f64,
        entry: fn(&EnergyLedger) -> f64,
    ) -> Option<f64> {
        let (_, l0) = self.start?;
        let cycles = self.cycles(w, frequency_hz);
        (cycles > 0.0).then(|| (entry(&w.ledger) - entry(&l0)) / cycles)
    }
}

/// Stroboscopic clock: the forcing phases t = nT of the analysis window (from step
/// `from_step` on).
#[derive(Debug, Clone, Copy)]
pub(crate) struct StrobeClock {
    pub from_step: u64,
    pub frequency_hz: f64,
}

/// The state a strobe point is interpolated from: [t, z_cm, ż_cm, z_box, ż_box] (s, m, m/s).
pub(crate) type StrobeState = [f64; 5];

/// The strobed state of `w`.
pub(crate) fn strobe_state(w: &DemWorld) -> StrobeState {
    let (z, v) = w.z_cm_state();
    [w.t, z, v, w.box_z, w.box_v]
}

impl StrobeClock {
    /// Before step `k` (from t to t + dt): the cycle n and the state now when nT lies in
    /// (t, t + dt], else `None`.
    pub fn before_step(&self, k: u64, w: &DemWorld) -> Option<(f64, StrobeState)> {
        if k < self.from_step || self.frequency_hz <= 0.0 {
            return None;
        }
        let next = ((w.t + w.dt) * self.frequency_hz).floor();
        let now = (w.t * self.frequency_hz).floor();
        (next > now).then(|| (next, strobe_state(w)))
    }
}

/// The energy ledger at the start of the drive and the floor below which a residual is
/// round-off (J).
#[derive(Debug, Clone, Copy)]
pub(crate) struct EnergyWatch {
    /// Stored energy when the drive started.
    pub start: EnergyState,
    /// Absolute residual floor 10⁻³ m_p g r (J).
    pub abs_floor_j: f64,
}

impl EnergyWatch {
    /// The watch of a bed of mass `m_p` (kg) and grain radius `r` (m) at the state `w`.
    pub fn new(w: &DemWorld, m_p: f64, g: f64, r: f64) -> Self {
        EnergyWatch {
            start: w.energy_state(),
            abs_floor_j: 1e-3 * m_p * g * r,
        }
    }

    /// The sample of the state `w`, with its energies (cumulative since the drive started).
    pub fn sample(&self, w: &DemWorld) -> Sample {
        self.sample_and_residual(w).0
    }

    /// [`EnergyWatch::sample`] and the ledger's residual E − E₀ − W_base + D (J) in it.
    /// Without a ledger ([`DemWorld::energy_ledger`] off) the flows and the residual are 0
    /// (nothing booked; the series stays finite).
    fn sample_and_residual(&self, w: &DemWorld) -> (Sample, f64) {
        let e0 = &self.start;
        let (_, lo, hi) = w.z_stats();
        let (zcm, _) = w.z_cm_state();
        let o = w.box_origin();
        let (u, _) = w.base_now();
        let st = w.energy_state();
        let (res, l) = if w.energy_ledger {
            (balance(&st, e0, &w.ledger).0, w.ledger)
        } else {
            (0.0, EnergyLedger::default())
        };
        let sample = Sample {
            time_s: w.t,
            base_u_m: u,
            box_z_m: w.box_z,
            box_v_m_s: w.box_v,
            floor_z_m: o[2],
            ceiling_z_m: o[2] + w.box_size[2],
            grain_z_m: zcm,
            model: ModelSample::Dem(DemSampleState {
                grain_zmin_m: lo,
                grain_zmax_m: hi,
                e_collision_j: l.collision_j,
                e_friction_j: l.friction_j,
                e_viscous_j: l.viscous_j,
                e_base_work_j: l.base_work_j,
                e_kinetic_j: st.kinetic_j + st.rotational_j,
                e_potential_j: st.potential_j - e0.potential_j,
                e_elastic_j: st.elastic_j,
                e_primary_j: st.primary_j,
                e_balance_residual_j: res,
            }),
            grain_force_n: w.grain_force_n,
        };
        (sample, res)
    }

    /// The sample of `w` after checking the state: the residual is measured against the
    /// larger of the base work, the dissipation and the floor.
    ///
    /// # Errors
    /// [`SimError::Unstable`] from [`check`].
    pub fn checked_sample(&self, w: &DemWorld) -> Result<Sample, SimError> {
        let (s, residual) = self.sample_and_residual(w);
        if !w.energy_ledger {
            // no ledger: only the finite-state and escape checks
            check(w, -1.0, 0.0)?;
            return Ok(s);
        }
        let scale = w
            .ledger
            .base_work_j
            .abs()
            .max(w.ledger.dissipated_j())
            .max(self.abs_floor_j);
        check(w, residual - self.abs_floor_j, residual.abs() / scale)?;
        Ok(s)
    }
}
