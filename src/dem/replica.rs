//! The DEM two-replica test (issue 9, item 2; reworked in issue 39): is the bed's motion
//! sensitive to its initial state, and how large is the sensitive part against the orbit?
//!
//! **What it runs.** Replica A is the run itself. When the analysis window starts
//! (t_p = duration × (1 − max(analysis_fraction, steady_fraction))), replica B is cloned from
//! A with every grain's height raised by δ0 (default 1e-9 m; velocities, the box and the
//! contact state unchanged), and the two worlds are stepped in lockstep with the same time
//! step. At every forcing period t_k = kT both replicas' section states (z_cm, ż_cm, z_box,
//! ż_box) are interpolated linearly between the two steps around t_k, exactly as the run's own
//! stroboscopic section ([`crate::model::StrobePoint`]), so replica A's columns equal
//! `strobe.csv`. Over the window the tracker also records the extent of A's continuous motion
//! on each axis (the orbit's size), so that every separation is a fraction of the orbit.
//!
//! **What it means.** [`crate::analysis::replica_test`] turns the strobes into the outcome:
//! sensitive (the separation grows to that of two independent section states, with its rate
//! and the size it saturates at relative to the orbit), insensitive (it stays orders of
//! magnitude below), or inconclusive (too short, or the two beds ended in different
//! macroscopic states — never called chaos). A granular bed is always sensitive at the grain
//! scale; the regime classifier calls it chaotic only when that sensitive part is large
//! against the orbit (the section is not n tight groups).
//!
//! **Why the perturbation waits for the analysis window.** By then the transient is over and
//! A is on its attractor: the separation measures the attractor, not how a transient contracts
//! or stretches differences. It also costs only the analysis window twice, not the whole run.

use crate::error::{ModelError, Quantity, SimError};

use super::model::DemModel;
use super::run::{interpolate_strobe, run_dem_stepped, DemRunConfig, DemSummary};
use super::stability::TimeStep;
use super::world::{BoxDrive, DemWorld};
use crate::observe::Observer;

pub use crate::analysis::replica_test::{
    report, GrowthFit, ReplicaOutcome, ReplicaReport, ReplicaRow, AXES,
};

/// Default perturbation δ0 of every grain's height (m).
pub const DEFAULT_DELTA_M: f64 = 1e-9;

/// Settings of the two-replica test.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReplicaOptions {
    /// Shift δ0 of every grain's z in replica B (m), > 0 and below the smallest grain radius.
    pub delta_m: f64,
    /// Drive time at which B is cloned from A and perturbed (s); the first step reaching it.
    pub perturb_at_s: f64,
}

impl ReplicaOptions {
    /// Perturbation `delta_m` at the start of the run's analysis window,
    /// duration × (1 − max(analysis_fraction, steady_fraction)).
    pub fn at_analysis_start(cfg: &DemRunConfig, delta_m: f64) -> ReplicaOptions {
        ReplicaOptions {
            delta_m,
            perturb_at_s: cfg.duration_s * (1.0 - cfg.analysis_fraction.max(cfg.steady_fraction)),
        }
    }
}

/// Replica B and the strobes of both, fed with replica A's state after each of its steps.
#[derive(Debug, Clone)]
pub struct ReplicaTracker {
    opts: ReplicaOptions,
    frequency_hz: f64,
    b: Option<DemWorld>,
    /// (cycle, A's state, B's state) before a step that lands on a strobe time.
    before: Option<(u64, [f64; 5], [f64; 5])>,
    perturbed_at_s: Option<f64>,
    /// Lowest and highest value of A's section coordinates since the perturbation.
    lo: [f64; AXES],
    hi: [f64; AXES],
    rows: Vec<ReplicaRow>,
    failure: Option<String>,
}

/// (t, z_cm, v_cm, box z, box v): the state the run's strobes interpolate.
fn strobe_state(w: &DemWorld) -> [f64; 5] {
    let (z, v) = w.z_cm_state();
    [w.t, z, v, w.box_z, w.box_v]
}

/// The section state (z_cm, ż_cm, z_box, ż_box) of an interpolated strobe.
fn section_state(cycle: u64, t_s: f64, before: [f64; 5], after: [f64; 5]) -> [f64; AXES] {
    let p = interpolate_strobe(cycle, t_s, before, after);
    [p.grain_z_m, p.grain_v_m_s, p.box_z_m, p.box_v_m_s]
}

impl ReplicaTracker {
    /// A tracker for a drive at `frequency_hz` (Hz).
    pub fn new(opts: ReplicaOptions, frequency_hz: f64) -> ReplicaTracker {
        ReplicaTracker {
            opts,
            frequency_hz,
            b: None,
            before: None,
            perturbed_at_s: None,
            lo: [f64::INFINITY; AXES],
            hi: [f64::NEG_INFINITY; AXES],
            rows: Vec::new(),
            failure: None,
        }
    }

    /// Call after every step of replica A: clones and perturbs B when A reaches
    /// `perturb_at_s`, afterwards steps B once, widens A's orbit extents and records both
    /// section states when the step landed on t = kT.
    pub fn observe(&mut self, a: &DemWorld) {
        if self.failure.is_some() {
            return;
        }
        let f = self.frequency_hz;
        let sa_now = match &self.b {
            None if a.t < self.opts.perturb_at_s - 0.5 * a.dt => return,
            _ => strobe_state(a),
        };
        for d in 0..AXES {
            self.lo[d] = self.lo[d].min(sa_now[d + 1]);
            self.hi[d] = self.hi[d].max(sa_now[d + 1]);
        }
        let b = match &mut self.b {
            None => {
                let mut b = a.clone();
                for p in &mut b.pos {
                    p[2] += self.opts.delta_m;
                }
                self.perturbed_at_s = Some(a.t);
                self.b.insert(b)
            }
            Some(b) => {
                b.step();
                debug_assert_eq!(a.t, b.t, "replicas out of lockstep");
                if let Some((cycle, sa, sb)) = self.before.take() {
                    let t_s = cycle as f64 / f;
                    let row = ReplicaRow {
                        cycle,
                        time_s: t_s,
                        a: section_state(cycle, t_s, sa, sa_now),
                        b: section_state(cycle, t_s, sb, strobe_state(b)),
                    };
                    if row.b.iter().any(|x| !x.is_finite()) {
                        self.failure =
                            Some(format!("replica B turned non-finite at t = {:.4} s", b.t));
                        self.b = None;
                        return;
                    }
                    self.rows.push(row);
                }
                b
            }
        };
        // does the next step land on a strobe time? (the run's own test, run.rs)
        if f > 0.0 {
            let next = ((a.t + a.dt) * f).floor();
            if next > (a.t * f).floor() {
                self.before = Some((next as u64, sa_now, strobe_state(b)));
            }
        }
    }

    /// The strobes so far.
    pub fn rows(&self) -> &[ReplicaRow] {
        &self.rows
    }

    /// The report of the strobes recorded.
    pub fn finish(self) -> ReplicaReport {
        let extent: [f64; AXES] = std::array::from_fn(|d| {
            let e = self.hi[d] - self.lo[d];
            if e.is_finite() && e > 0.0 {
                e
            } else {
                0.0
            }
        });
        let mut r = report(
            self.opts.delta_m,
            self.perturbed_at_s.unwrap_or(f64::NAN),
            self.frequency_hz,
            extent,
            self.rows,
        );
        r.failure = self.failure.or_else(|| {
            self.perturbed_at_s.is_none().then(|| {
                format!(
                    "the run ended before the perturbation time {} s",
                    self.opts.perturb_at_s
                )
            })
        });
        if let Some(why) = &r.failure {
            r.outcome = ReplicaOutcome::Inconclusive { why: why.clone() };
        }
        r
    }
}

/// Runs the DEM ([`super::run::run_dem_with_step`], time step `step`) as replica A with a perturbed replica B stepped in
/// lockstep (see the module documentation). Samples and snapshots of A go to `obs`.
///
/// # Errors
/// [`SimError::Model`] for δ0 not finite, ≤ 0 or not below the smallest grain radius (a
/// perturbation that large is a different initial state, not a perturbation); the errors of
/// [`super::run::run_dem`].
pub fn run_replica(
    model: &DemModel,
    drive: BoxDrive,
    cfg: &DemRunConfig,
    step: TimeStep,
    opts: &ReplicaOptions,
    obs: &mut dyn Observer,
) -> Result<(DemSummary, ReplicaReport), SimError> {
    let r_min = model.grains.r_min_m;
    if !(opts.delta_m.is_finite() && opts.delta_m > 0.0 && opts.delta_m < r_min) {
        return Err(ModelError::new(
            Quantity::ReplicaPerturbation,
            opts.delta_m,
            format!(
                "the perturbation δ0 must be finite, > 0 and below the smallest grain radius \
                 ({r_min:e} m); the default is {DEFAULT_DELTA_M:e} m"
            ),
        )
        .into());
    }
    let mut tracker = ReplicaTracker::new(*opts, drive.frequency_hz);
    let summary = run_dem_stepped(model, drive, cfg, step, obs, &mut |world| {
        tracker.observe(world);
        Ok(())
    })?;
    Ok((summary, tracker.finish()))
}
