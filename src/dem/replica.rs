//! The DEM two-replica test (issue 9, item 2; reworked in issue 39): is the bed's motion
//! sensitive to its initial state, and how large is the sensitive part against the orbit?
//!
//! **What it runs.** Replica A is the run itself. When the analysis window starts
//! (t_p = duration × (1 − max(analysis_fraction, steady_fraction))), replica B is cloned from
//! A with every grain's height raised by δ0 (default 1e-9 m; velocities, the box and the
//! contact state unchanged). A's section states (z_cm, ż_cm, z_box, ż_box) at every forcing
//! period t_k = kT are interpolated linearly between the two steps around t_k, exactly as the
//! run's own stroboscopic section ([`crate::model::StrobePoint`]), so replica A's columns equal
//! `strobe.csv`; over the window the tracker also records the extent of A's continuous motion
//! on each axis (the orbit's size), so that every separation is a fraction of the orbit.
//! B is stepped after A's run, alone, over the same number of steps of the same size from the
//! same time ([`DeferredReplica::complete`]), and its section states are formed the same way:
//! B's trajectory does not depend on A's after the clone, so this is what stepping the two in
//! lockstep gives, bit for bit. A caller that finds the section to be n tight groups — periodic
//! whatever B does ([`crate::analysis::regime_forced`]) — need not step B at all (the default
//! of an analysed run, `run.replica` left out; `run.replica = true` always steps it).
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
//! or stretches differences. It also costs only the analysis window twice, not the whole run
//! (and nothing more when B is not needed).

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

/// Replica A's side of the test, fed with A's state after each of its steps: clones and
/// perturbs B when A reaches `perturb_at_s`, then records A's section states at t = kT and the
/// extents of A's motion. B itself is stepped afterwards, alone ([`DeferredReplica`]): its
/// trajectory does not depend on A's after the clone, and both take the same steps from the
/// same time, so its states at t = kT are those a lockstep run would give, bit for bit — and a
/// caller that finds the section periodic need not step it at all.
#[derive(Debug, Clone)]
pub struct ReplicaTracker {
    opts: ReplicaOptions,
    frequency_hz: f64,
    /// B as cloned and perturbed.
    b0: Option<DemWorld>,
    /// A's steps since the clone.
    steps: u64,
    /// (cycle, A's state) before a step that lands on a strobe time.
    before: Option<(u64, [f64; 5])>,
    perturbed_at_s: Option<f64>,
    /// Lowest and highest value of A's section coordinates since the perturbation.
    lo: [f64; AXES],
    hi: [f64; AXES],
    /// (cycle, A's section state) at every strobe time since the perturbation.
    a_rows: Vec<(u64, [f64; AXES])>,
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

/// The strobe cycle the step after the state `w` lands on, if it crosses t = kT (the run's
/// own test, run.rs).
fn next_strobe(w: &DemWorld, f: f64) -> Option<u64> {
    let next = ((w.t + w.dt) * f).floor();
    (f > 0.0 && next > (w.t * f).floor()).then_some(next as u64)
}

impl ReplicaTracker {
    /// A tracker for a drive at `frequency_hz` (Hz).
    pub fn new(opts: ReplicaOptions, frequency_hz: f64) -> ReplicaTracker {
        ReplicaTracker {
            opts,
            frequency_hz,
            b0: None,
            steps: 0,
            before: None,
            perturbed_at_s: None,
            lo: [f64::INFINITY; AXES],
            hi: [f64::NEG_INFINITY; AXES],
            a_rows: Vec::new(),
        }
    }

    /// Call after every step of replica A: clones and perturbs B when A reaches
    /// `perturb_at_s`, afterwards widens A's orbit extents and records A's section state
    /// when the step landed on t = kT.
    pub fn observe(&mut self, a: &DemWorld) {
        let f = self.frequency_hz;
        if self.b0.is_none() && a.t < self.opts.perturb_at_s - 0.5 * a.dt {
            return;
        }
        let sa_now = strobe_state(a);
        for d in 0..AXES {
            self.lo[d] = self.lo[d].min(sa_now[d + 1]);
            self.hi[d] = self.hi[d].max(sa_now[d + 1]);
        }
        if self.b0.is_none() {
            let mut b = a.clone();
            for p in &mut b.pos {
                p[2] += self.opts.delta_m;
            }
            self.perturbed_at_s = Some(a.t);
            self.b0 = Some(b);
        } else {
            self.steps += 1;
            if let Some((cycle, sa)) = self.before.take() {
                let t_s = cycle as f64 / f;
                self.a_rows
                    .push((cycle, section_state(cycle, t_s, sa, sa_now)));
            }
        }
        self.before = next_strobe(a, f).map(|cycle| (cycle, sa_now));
    }

    /// A's side done: B, when it was cloned, waits in the returned [`DeferredReplica`].
    pub fn finish(self) -> DeferredReplica {
        DeferredReplica { tracker: self }
    }
}

/// The two-replica test with A's run done and B not yet stepped ([`ReplicaTracker`]):
/// [`DeferredReplica::complete`] steps B alone over the same steps and forms the report.
#[derive(Debug, Clone)]
pub struct DeferredReplica {
    tracker: ReplicaTracker,
}

impl DeferredReplica {
    /// Steps replica B from its clone over the steps A took after it, records B's section
    /// state at each t = kT A recorded, and forms the report ([`report`]).
    pub fn complete(self) -> ReplicaReport {
        let t = self.tracker;
        let f = t.frequency_hz;
        let extent: [f64; AXES] = std::array::from_fn(|d| {
            let e = t.hi[d] - t.lo[d];
            if e.is_finite() && e > 0.0 {
                e
            } else {
                0.0
            }
        });
        let (rows, failure) = match t.b0 {
            Some(b) => step_b(b, t.steps, f, &t.a_rows),
            None => (
                Vec::new(),
                Some(format!(
                    "the run ended before the perturbation time {} s",
                    t.opts.perturb_at_s
                )),
            ),
        };
        let mut r = report(
            t.opts.delta_m,
            t.perturbed_at_s.unwrap_or(f64::NAN),
            f,
            extent,
            rows,
        );
        r.failure = failure;
        if let Some(why) = &r.failure {
            r.outcome = ReplicaOutcome::Inconclusive { why: why.clone() };
        }
        r
    }
}

/// Steps B `steps` times from its clone and pairs its section states with A's (`a_rows`, in
/// cycle order); stops at a non-finite state (the failure says when).
fn step_b(
    mut b: DemWorld,
    steps: u64,
    f: f64,
    a_rows: &[(u64, [f64; AXES])],
) -> (Vec<ReplicaRow>, Option<String>) {
    let mut rows = Vec::with_capacity(a_rows.len());
    let mut a_next = a_rows.iter();
    let mut before = next_strobe(&b, f).map(|cycle| (cycle, strobe_state(&b)));
    for _ in 0..steps {
        b.step();
        let sb_now = strobe_state(&b);
        if let Some((cycle, sb)) = before.take() {
            let t_s = cycle as f64 / f;
            let row_b = section_state(cycle, t_s, sb, sb_now);
            if row_b.iter().any(|x| !x.is_finite()) {
                return (
                    rows,
                    Some(format!("replica B turned non-finite at t = {:.4} s", b.t)),
                );
            }
            match a_next.next() {
                Some(&(c, a)) if c == cycle => rows.push(ReplicaRow {
                    cycle,
                    time_s: t_s,
                    a,
                    b: row_b,
                }),
                other => {
                    let why = format!(
                        "replica B reached strobe {cycle} where A recorded {:?}",
                        other.map(|r| r.0)
                    );
                    return (rows, Some(why));
                }
            }
        }
        before = next_strobe(&b, f).map(|cycle| (cycle, sb_now));
    }
    (rows, None)
}

/// Runs the DEM ([`super::run::run_dem_with_step`], time step `step`) as replica A with a
/// perturbed replica B (see the module documentation), and completes the test. Samples and
/// snapshots of A go to `obs`.
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
    let (s, deferred) = run_replica_deferred(model, drive, cfg, step, opts, obs)?;
    Ok((s, deferred.complete()))
}

/// [`run_replica`] with replica B left unstepped: the caller completes the test
/// ([`DeferredReplica::complete`]) only if it needs it — a section of n tight groups is
/// periodic whatever B does.
///
/// # Errors
/// As [`run_replica`].
pub fn run_replica_deferred(
    model: &DemModel,
    drive: BoxDrive,
    cfg: &DemRunConfig,
    step: TimeStep,
    opts: &ReplicaOptions,
    obs: &mut dyn Observer,
) -> Result<(DemSummary, DeferredReplica), SimError> {
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
