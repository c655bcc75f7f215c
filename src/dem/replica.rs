//! The DEM two-replica test (issue 9, item 2): is the bed's collective motion periodic with
//! granular noise, or collectively chaotic?
//!
//! **What it measures.** Replica A is the run itself. When the analysis window starts
//! (t_p = duration × (1 − max(analysis_fraction, steady_fraction)), see below), replica B is
//! cloned from A with every grain's height raised by δ0 (default 1e-9 m; velocities, the box
//! and the contact state unchanged), and the two worlds are stepped in lockstep with the same
//! time step. At every forcing period t_k = kT, T = 1/f, both replicas' grain centre of mass
//! z_cm is interpolated linearly between the two steps around t_k, exactly as the run's own
//! stroboscopic section ([`crate::model::StrobePoint`]), so replica A's column equals `strobe.csv`.
//!
//! **Why the perturbation waits for the analysis window.** By then the transient is over and
//! A is on its attractor: the separation then measures the attractor's stability, the thing
//! the regime verdict is about, and not how a transient contracts or stretches differences.
//! It also costs only the analysis window twice, not the whole run.
//!
//! **What a granular bed does.** The grains' micro-state always diverges (collisions of
//! spheres are chaotic, at rates of tens to hundreds per second), so B never tracks A grain by
//! grain. What matters is the *collective* strobed z_cm:
//! - periodic motion with granular noise: once the micro-states have decorrelated the two
//!   replicas are two independent noise realisations about the same orbit, and the strobed
//!   separation saturates at the noise band: |z_A − z_B| of two independent draws of sd σ has
//!   median 0.954 σ;
//! - collective chaos: the collective state itself separates, until the replicas are
//!   independent points of the attractor, at the attractor's scale.
//!
//! The noise band must therefore be the scatter of the section that the collective dynamics
//! does *not* explain — not the sd of the whole section cloud, which in chaos is the
//! attractor itself. It is estimated on replica A's strobes by one-step nearest-neighbour
//! prediction (Lorenz's analogues): in delay coordinates (z_k, …, z_{k−m+1}), m = 1, 2, 3,
//! the K = 8 nearest other points (max norm, temporal neighbours |j − k| ≤ m excluded) predict
//! z_{k+1} by the mean of their successors; σ_m² = mean squared error / (1 + 1/K) (the
//! successors' own noise), and the noise band is min_m σ_m. For a period-n orbit with white
//! noise this is the sd of the n groups about their centres (the period-1 case: the sd about
//! the mean); for a deterministic map it is the noise about the map.
//!
//! **Outputs** (all lengths in m, rates in 1/s):
//! - d_k = |z_A(t_k) − z_B(t_k)| for every strobe after t_p;
//! - noise band σ_n (above), the section's sd about its mean, the attractor size R = range of
//!   A's strobed z_cm, and the fully separated scale D = median over all pairs i < j of A's
//!   strobes in the last third of |z_A,i − z_A,j| (what d_k saturates at when the replicas are
//!   independent points of the attractor; the last third, as d_sat, so that a drift of A
//!   earlier in the window does not inflate it);
//! - saturation level d_sat = median of d_k over the last third of the strobes, and its trend
//!   d_sat / (median over the middle third): well above 1, the separation is still growing;
//! - growth rate λ at the attractor's scale: least-squares slope of ln d_k against t_k over the
//!   growth phase — from the first strobe with d_k ≥ max(10 δ0, σ_n) up to (excluding) the
//!   first one reaching min(0.3 R, d_sat) — with its standard error
//!   sqrt(SSR / (n − 2) / Σ(t − t̄)²); also per forcing period, λ T. Below the noise band the
//!   strobed separation is grain-scale chaos, which in the softened scene B carries 1e-9 m to
//!   the noise band within one to three forcing periods (60–130 1/s over the first period at
//!   7.5–14.5 Hz): too few strobes to fit, and one such point would dominate the slope. When fewer than 3 strobes lie in that
//!   window, or it spans less than one e-fold, the fit falls back to the window from 10 δ0;
//!   the window used is in the report;
//! - initial growth rate ln(d_1 / δ0) / (t_1 − t_p) over the first strobe interval (1/s): the
//!   grain-scale divergence, a two-point figure without error bar;
//! - verdict: [`ReplicaVerdict::StaysInNoiseBand`] if d_sat ≤ 2 σ_n;
//!   [`ReplicaVerdict::SeparatesToAttractor`] if d_sat > 2 σ_n and 0.5 D ≤ d_sat ≤ 2 D (with
//!   λ); [`ReplicaVerdict::Inconclusive`] otherwise: with fewer than 30 strobes, when the
//!   growth phase holds fewer than 3 strobes, between the two scales, or when d_sat > 2 D —
//!   the replicas are further apart than two points of A's own attractor, so they ended in
//!   different states (one bed rearranged or compacted, coexisting states), which is not
//!   chaos. Measured on the softened scene B at 7.5 Hz: replica A's z_cm stepped down by
//!   0.27 mm within one second and stayed there, B's did not (d_sat = 5 D).

use serde::{Deserialize, Serialize};

use crate::error::{ModelError, Quantity, SimError};

use super::model::DemModel;
use super::run::{interpolate_strobe, run_dem_stepped, DemRunConfig, DemSummary};
use super::world::{BoxDrive, DemWorld};
use crate::observe::Observer;

/// Default perturbation δ0 of every grain's height (m).
pub const DEFAULT_DELTA_M: f64 = 1e-9;
/// Fewest strobes after the perturbation for a verdict.
pub const MIN_STROBES: usize = 30;
/// d_sat ≤ this × noise band: the replicas stay in the noise band (two independent noise
/// draws differ by a median 0.954 σ; the factor leaves room for the estimate's error).
pub const NOISE_FACTOR: f64 = 2.0;
/// d_sat ≥ this × the fully separated scale D: the replicas separated to the attractor's size.
pub const ATTRACTOR_FACTOR: f64 = 0.5;
/// d_sat > this × D: the replicas ended in different states (not separated on one attractor).
pub const DIFFERENT_STATES_FACTOR: f64 = 2.0;
/// Neighbours of the noise-band predictor.
const NEIGHBOURS: usize = 8;

/// Settings of the two-replica test.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReplicaOptions {
    /// Shift δ0 of every grain's z in replica B (m), ≥ 0; 0 checks determinism.
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

/// One strobe of the two replicas (a row of `replica.csv`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ReplicaRow {
    /// Forcing period index k (t = k T).
    pub cycle: u64,
    /// Time t_k = k T (s).
    pub time_s: f64,
    /// Replica A's grain centre of mass z_cm at t_k (m).
    pub grain_z_a_m: f64,
    /// Replica B's grain centre of mass z_cm at t_k (m).
    pub grain_z_b_m: f64,
    /// d_k = |z_A − z_B| (m).
    pub separation_m: f64,
}

/// Least-squares fit of ln d_k against t_k over the growth phase.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GrowthFit {
    /// Growth rate λ (1/s).
    pub per_s: f64,
    /// Standard error of λ (1/s).
    pub stderr_per_s: f64,
    /// λ T: growth per forcing period (–).
    pub per_period: f64,
    /// Strobes in the fit.
    pub points: usize,
    /// First and last fitted times (s).
    pub from_s: f64,
    /// Last fitted time (s).
    pub to_s: f64,
    /// Lower bound of the window, 10 δ0 (m).
    pub lower_m: f64,
    /// Upper bound of the window, min(0.3 R, d_sat) (m).
    pub upper_m: f64,
}

/// What the two replicas' strobed z_cm did.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum ReplicaVerdict {
    /// The separation saturates within the noise band: periodic collective motion with
    /// granular noise (or bit-identical replicas, δ0 = 0).
    StaysInNoiseBand,
    /// The separation grows to the attractor's scale: collective chaos, at rate λ.
    SeparatesToAttractor {
        /// Growth rate of the separation (1/s).
        growth_per_s: f64,
        /// Its standard error (1/s).
        stderr_per_s: f64,
    },
    /// Neither, and why.
    Inconclusive {
        /// What is missing or in between.
        why: String,
    },
}

/// The two-replica report (`summary.json` block `replica`; the rows go to `replica.csv`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReplicaReport {
    /// Perturbation δ0 of every grain's height (m).
    pub delta0_m: f64,
    /// Drive time at which B was perturbed (s).
    pub perturbed_at_s: f64,
    /// Strobes after the perturbation.
    pub strobes: usize,
    /// Separation at the first strobe after the perturbation (m).
    pub first_separation_m: f64,
    /// ln(d_1 / δ0) / (t_1 − t_p): growth over the first strobe interval (1/s); none for
    /// δ0 = 0 or no separation.
    pub initial_growth_per_s: Option<f64>,
    /// Largest separation (m).
    pub max_separation_m: f64,
    /// Noise band σ_n: scatter of A's strobed z_cm about its one-step nearest-neighbour
    /// prediction (m).
    pub noise_band_m: f64,
    /// Sd of A's strobed z_cm about its mean (m).
    pub strobe_sd_m: f64,
    /// Attractor size R: range of A's strobed z_cm (m).
    pub attractor_size_m: f64,
    /// Fully separated scale D: median |z_A,i − z_A,j| over all pairs of A's strobes in the
    /// last third (m).
    pub independent_separation_m: f64,
    /// Saturation level d_sat: median d_k over the last third (m).
    pub saturation_m: f64,
    /// d_sat / median d_k over the middle third (–): well above 1, still growing.
    pub saturation_trend: f64,
    /// d_sat / σ_n (–).
    pub saturation_over_noise: f64,
    /// d_sat / D (–).
    pub saturation_over_independent: f64,
    /// Growth of ln d_k over the growth phase (none: fewer than 3 strobes in it).
    pub growth: Option<GrowthFit>,
    /// Verdict.
    pub verdict: ReplicaVerdict,
    /// Per-strobe rows (`replica.csv`).
    #[serde(skip)]
    pub rows: Vec<ReplicaRow>,
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
    rows: Vec<ReplicaRow>,
    failure: Option<String>,
}

/// (t, z_cm, v_cm, box z, box v): the state the run's strobes interpolate.
fn strobe_state(w: &DemWorld) -> [f64; 5] {
    let (z, v) = w.z_cm_state();
    [w.t, z, v, w.box_z, w.box_v]
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
            rows: Vec::new(),
            failure: None,
        }
    }

    /// Call after every step of replica A: clones and perturbs B when A reaches
    /// `perturb_at_s`, afterwards steps B once and records both strobes when the step landed
    /// on t = kT.
    pub fn observe(&mut self, a: &DemWorld) {
        if self.failure.is_some() {
            return;
        }
        let f = self.frequency_hz;
        let b = match &mut self.b {
            None => {
                if a.t < self.opts.perturb_at_s - 0.5 * a.dt {
                    return;
                }
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
                    let za = interpolate_strobe(cycle, t_s, sa, strobe_state(a)).grain_z_m;
                    let zb = interpolate_strobe(cycle, t_s, sb, strobe_state(b)).grain_z_m;
                    if !zb.is_finite() || !b.box_z.is_finite() {
                        self.failure =
                            Some(format!("replica B turned non-finite at t = {:.4} s", b.t));
                        self.b = None;
                        return;
                    }
                    self.rows.push(ReplicaRow {
                        cycle,
                        time_s: t_s,
                        grain_z_a_m: za,
                        grain_z_b_m: zb,
                        separation_m: (za - zb).abs(),
                    });
                }
                b
            }
        };
        // does the next step land on a strobe time? (the run's own test, run.rs)
        if f > 0.0 {
            let next = ((a.t + a.dt) * f).floor();
            if next > (a.t * f).floor() {
                self.before = Some((next as u64, strobe_state(a), strobe_state(b)));
            }
        }
    }

    /// The strobes so far.
    pub fn rows(&self) -> &[ReplicaRow] {
        &self.rows
    }

    /// The report of the strobes recorded.
    pub fn finish(self) -> ReplicaReport {
        let mut r = report(
            self.opts.delta_m,
            self.perturbed_at_s.unwrap_or(f64::NAN),
            self.frequency_hz,
            self.rows,
        );
        if let Some(why) = self.failure {
            r.verdict = ReplicaVerdict::Inconclusive { why };
        } else if self.perturbed_at_s.is_none() {
            r.verdict = ReplicaVerdict::Inconclusive {
                why: format!(
                    "the run ended before the perturbation time {} s",
                    self.opts.perturb_at_s
                ),
            };
        }
        r
    }
}

/// Runs the DEM ([`super::run::run_dem`]) as replica A with a perturbed replica B stepped in lockstep
/// (see the module documentation). Samples and snapshots of A go to `obs`.
///
/// # Errors
/// [`SimError::Model`] for δ0 negative or not finite; the errors of [`super::run::run_dem`].
pub fn run_replica(
    model: &DemModel,
    drive: BoxDrive,
    cfg: &DemRunConfig,
    opts: &ReplicaOptions,
    obs: &mut dyn Observer,
) -> Result<(DemSummary, ReplicaReport), SimError> {
    if !(opts.delta_m >= 0.0 && opts.delta_m.is_finite()) {
        return Err(ModelError::new(
            Quantity::ReplicaPerturbation,
            opts.delta_m,
            "the perturbation δ0 must be finite and ≥ 0 (m)",
        )
        .into());
    }
    let mut tracker = ReplicaTracker::new(*opts, drive.frequency_hz);
    let summary = run_dem_stepped(model, drive, cfg, obs, &mut |world| {
        tracker.observe(world);
        Ok(())
    })?;
    Ok((summary, tracker.finish()))
}

fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if !n.is_multiple_of(2) {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Sd of `z` about its mean (n − 1).
fn sd(z: &[f64]) -> f64 {
    let n = z.len() as f64;
    let m = z.iter().sum::<f64>() / n;
    (z.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (n - 1.0)).sqrt()
}

/// Noise about the section's one-step dynamics (module documentation): min over m = 1..=3 of
/// the nearest-neighbour prediction error, corrected for the neighbours' own noise.
pub fn noise_band(z: &[f64]) -> f64 {
    let n = z.len();
    let mut best = f64::INFINITY;
    for m in 1..=3usize {
        // points k = m−1 … n−2 (each needs a successor)
        let pts: Vec<usize> = (m - 1..n.saturating_sub(1)).collect();
        let dist = |k: usize, j: usize| {
            (0..m)
                .map(|i| (z[k - i] - z[j - i]).abs())
                .fold(0.0, f64::max)
        };
        let (mut sum, mut count) = (0.0, 0usize);
        let mut cand: Vec<(f64, usize)> = Vec::with_capacity(pts.len());
        for &k in &pts {
            cand.clear();
            cand.extend(
                pts.iter()
                    .filter(|&&j| j.abs_diff(k) > m)
                    .map(|&j| (dist(k, j), j)),
            );
            if cand.len() < NEIGHBOURS {
                continue;
            }
            cand.select_nth_unstable_by(NEIGHBOURS - 1, |a, b| a.0.total_cmp(&b.0));
            let pred = cand[..NEIGHBOURS]
                .iter()
                .map(|&(_, j)| z[j + 1])
                .sum::<f64>()
                / NEIGHBOURS as f64;
            let e = z[k + 1] - pred;
            sum += e * e;
            count += 1;
        }
        if count > 0 {
            let s = (sum / count as f64 / (1.0 + 1.0 / NEIGHBOURS as f64)).sqrt();
            best = best.min(s);
        }
    }
    if best.is_finite() {
        best
    } else {
        f64::NAN
    }
}

/// Median |z_i − z_j| over all pairs i < j.
fn independent_separation(z: &[f64]) -> f64 {
    let mut d = Vec::with_capacity(z.len() * z.len().saturating_sub(1) / 2);
    for (i, a) in z.iter().enumerate() {
        d.extend(z[i + 1..].iter().map(|b| (a - b).abs()));
    }
    median(&mut d)
}

/// Slope of ln d against t over the growth phase (module documentation).
fn growth_fit(rows: &[ReplicaRow], lower: f64, upper: f64, period_s: f64) -> Option<GrowthFit> {
    if upper.is_nan() || lower.is_nan() || upper < std::f64::consts::E * lower {
        return None; // less than one e-fold between the bounds
    }
    let k0 = rows.iter().position(|r| r.separation_m >= lower)?;
    let k1 = rows[k0..]
        .iter()
        .position(|r| r.separation_m >= upper)
        .map_or(rows.len(), |i| k0 + i);
    let pts: Vec<(f64, f64)> = rows[k0..k1]
        .iter()
        .filter(|r| r.separation_m > 0.0)
        .map(|r| (r.time_s, r.separation_m.ln()))
        .collect();
    let n = pts.len();
    if n < 3 {
        return None;
    }
    let nf = n as f64;
    let tm = pts.iter().map(|p| p.0).sum::<f64>() / nf;
    let ym = pts.iter().map(|p| p.1).sum::<f64>() / nf;
    let sxx: f64 = pts.iter().map(|p| (p.0 - tm).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - tm) * (p.1 - ym)).sum();
    let slope = sxy / sxx;
    let ssr: f64 = pts
        .iter()
        .map(|p| (p.1 - ym - slope * (p.0 - tm)).powi(2))
        .sum();
    Some(GrowthFit {
        per_s: slope,
        stderr_per_s: (ssr / (nf - 2.0) / sxx).sqrt(),
        per_period: slope * period_s,
        points: n,
        from_s: pts[0].0,
        to_s: pts[n - 1].0,
        lower_m: lower,
        upper_m: upper,
    })
}

/// The report of two replicas' strobes (`rows` in time order) after a perturbation of
/// `delta0_m` (m) at `perturbed_at_s` (s), forcing `frequency_hz` (Hz).
pub fn report(
    delta0_m: f64,
    perturbed_at_s: f64,
    frequency_hz: f64,
    rows: Vec<ReplicaRow>,
) -> ReplicaReport {
    let z: Vec<f64> = rows.iter().map(|r| r.grain_z_a_m).collect();
    let n = rows.len();
    let (lo, hi) = z
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &x| {
            (l.min(x), h.max(x))
        });
    let range = if n > 0 { hi - lo } else { f64::NAN };
    let noise = noise_band(&z);
    let third = n / 3;
    let indep = independent_separation(&z[n - third..]);
    let mut tail: Vec<f64> = rows[n - third..].iter().map(|r| r.separation_m).collect();
    let sat = median(&mut tail);
    let mut middle: Vec<f64> = rows[third..n - third]
        .iter()
        .map(|r| r.separation_m)
        .collect();
    let trend = sat / median(&mut middle);
    let upper = (0.3 * range).min(sat);
    let period = 1.0 / frequency_hz;
    let growth = growth_fit(&rows, (10.0 * delta0_m).max(noise), upper, period)
        .or_else(|| growth_fit(&rows, 10.0 * delta0_m, upper, period));
    let initial_growth_per_s = rows
        .first()
        .filter(|r| delta0_m > 0.0 && r.separation_m > 0.0 && r.time_s > perturbed_at_s)
        .map(|r| (r.separation_m / delta0_m).ln() / (r.time_s - perturbed_at_s));
    let verdict = if n < MIN_STROBES {
        ReplicaVerdict::Inconclusive {
            why: format!("{n} strobes after the perturbation; the test needs ≥ {MIN_STROBES}"),
        }
    } else if sat <= NOISE_FACTOR * noise {
        ReplicaVerdict::StaysInNoiseBand
    } else if sat > DIFFERENT_STATES_FACTOR * indep {
        ReplicaVerdict::Inconclusive {
            why: format!(
                "the replicas ended in different states: d_sat = {sat:.3e} m is more than \
                 {DIFFERENT_STATES_FACTOR} × the spread of A's own strobes over the last third \
                 (D = {indep:.3e} m) — one bed rearranged (e.g. compacted) or the states \
                 coexist; not chaos"
            ),
        }
    } else if sat >= ATTRACTOR_FACTOR * indep {
        match growth {
            Some(g) => ReplicaVerdict::SeparatesToAttractor {
                growth_per_s: g.per_s,
                stderr_per_s: g.stderr_per_s,
            },
            None => ReplicaVerdict::Inconclusive {
                why: format!(
                    "the replicas separate to the attractor's scale, but fewer than 3 strobes \
                     lie between 10 δ0 and min(0.3 R, d_sat) = {upper:.3e} m: growth faster \
                     than the strobes resolve (first interval: {} 1/s)",
                    initial_growth_per_s.map_or("n/a".into(), |g| format!("{g:.3}"))
                ),
            },
        }
    } else {
        ReplicaVerdict::Inconclusive {
            why: format!(
                "the separation saturates at {sat:.3e} m, above {NOISE_FACTOR} × the noise band \
                 ({noise:.3e} m) but below {ATTRACTOR_FACTOR} × the fully separated scale \
                 ({indep:.3e} m): run longer"
            ),
        }
    };
    ReplicaReport {
        delta0_m,
        perturbed_at_s,
        strobes: n,
        first_separation_m: rows.first().map_or(f64::NAN, |r| r.separation_m),
        initial_growth_per_s,
        max_separation_m: rows.iter().map(|r| r.separation_m).fold(f64::NAN, f64::max),
        noise_band_m: noise,
        strobe_sd_m: if n > 1 { sd(&z) } else { f64::NAN },
        attractor_size_m: range,
        independent_separation_m: indep,
        saturation_m: sat,
        saturation_trend: trend,
        saturation_over_noise: sat / noise,
        saturation_over_independent: sat / indep,
        growth,
        verdict,
        rows,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn gauss(rng: &mut ChaCha8Rng) -> f64 {
        // Box–Muller
        let u: f64 = rng.random::<f64>().max(1e-300);
        let v: f64 = rng.random();
        (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    }

    fn rows_of(za: &[f64], zb: &[f64], f: f64) -> Vec<ReplicaRow> {
        za.iter()
            .zip(zb)
            .enumerate()
            .map(|(k, (&a, &b))| ReplicaRow {
                cycle: k as u64 + 1,
                time_s: (k + 1) as f64 / f,
                grain_z_a_m: a,
                grain_z_b_m: b,
                separation_m: (a - b).abs(),
            })
            .collect()
    }

    #[test]
    fn noise_band_of_period_two_with_noise_is_the_group_sd() {
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let z: Vec<f64> = (0..400)
            .map(|k| 0.05 + if k % 2 == 0 { 2e-3 } else { -2e-3 } + 1e-4 * gauss(&mut rng))
            .collect();
        let s = noise_band(&z);
        assert!((0.8e-4..1.2e-4).contains(&s), "{s}");
        assert!(sd(&z) > 1.5e-3);
    }

    #[test]
    fn noise_band_of_a_chaotic_map_is_its_noise() {
        // logistic map r = 4 (attractor [0, 1]) scaled to mm, with 1 % observational noise
        let mut rng = ChaCha8Rng::seed_from_u64(2);
        let mut x = 0.3;
        let z: Vec<f64> = (0..400)
            .map(|_| {
                x = 4.0 * x * (1.0 - x);
                1e-3 * (x + 0.01 * gauss(&mut rng))
            })
            .collect();
        let s = noise_band(&z);
        assert!(s < 0.1 * sd(&z), "noise {s}, sd {}", sd(&z));
    }

    #[test]
    fn period_one_noise_stays_in_band() {
        // separation grows e-fold per period from 1e-9 m, then two independent noise draws
        let (f, sigma) = (14.5, 3.5e-4);
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let za: Vec<f64> = (0..300).map(|_| 0.05 + sigma * gauss(&mut rng)).collect();
        let zb: Vec<f64> = za
            .iter()
            .enumerate()
            .map(|(k, &a)| {
                let d = 1e-9 * (k as f64).exp();
                if d < sigma {
                    a + d
                } else {
                    0.05 + sigma * gauss(&mut rng)
                }
            })
            .collect();
        let r = report(1e-9, 0.0, f, rows_of(&za, &zb, f));
        assert_eq!(r.verdict, ReplicaVerdict::StaysInNoiseBand, "{r:?}");
        let g = r.growth.expect("growth phase");
        assert!((g.per_period - 1.0).abs() < 0.1, "{g:?}");
    }

    #[test]
    fn chaotic_map_separates_with_its_exponent() {
        // logistic map r = 4: λ = ln 2 per iteration; B starts 1e-9 away
        let f = 10.0;
        let (mut a, mut b) = (0.3f64, 0.3 + 1e-9);
        let (mut za, mut zb) = (Vec::new(), Vec::new());
        for _ in 0..300 {
            a = 4.0 * a * (1.0 - a);
            b = 4.0 * b * (1.0 - b);
            za.push(1e-3 * a);
            zb.push(1e-3 * b);
        }
        // δ0 in the scaled units: 1e-12 m
        let rows = rows_of(&za, &zb, f);
        let r = report(1e-12, 0.0, f, rows.clone());
        let ReplicaVerdict::SeparatesToAttractor { growth_per_s, .. } = r.verdict else {
            panic!("{r:?}");
        };
        // the attractor-scale window holds a few iterations only: a loose check
        let per_period = growth_per_s / f;
        assert!((0.3..1.2).contains(&per_period), "{per_period} {r:?}");
        // from 10 δ0 to 0.3 R: ~25 iterations, the map's exponent ln 2
        let g = growth_fit(&rows, 1e-11, 0.3e-3, 1.0 / f).unwrap();
        assert!((g.per_period - 2f64.ln()).abs() < 0.1, "{g:?}");
        assert!(
            g.stderr_per_s > 0.0 && g.stderr_per_s < 0.1 * g.per_s,
            "{g:?}"
        );
    }

    #[test]
    fn a_step_in_one_replica_is_not_chaos() {
        // A compacts by 20 σ at two thirds of the window, B does not (the 7.5 Hz case)
        let (f, sigma) = (7.5, 2e-5);
        let mut rng = ChaCha8Rng::seed_from_u64(4);
        let za: Vec<f64> = (0..120)
            .map(|k| 0.026 - if k > 70 { 20.0 * sigma } else { 0.0 } + sigma * gauss(&mut rng))
            .collect();
        let zb: Vec<f64> = (0..120).map(|_| 0.026 + sigma * gauss(&mut rng)).collect();
        let r = report(1e-9, 0.0, f, rows_of(&za, &zb, f));
        let ReplicaVerdict::Inconclusive { why } = &r.verdict else {
            panic!("{r:?}");
        };
        assert!(why.contains("different states"), "{why}");
    }

    #[test]
    fn too_few_strobes_is_inconclusive() {
        let z = [0.05; 10];
        let r = report(1e-9, 0.0, 10.0, rows_of(&z, &z, 10.0));
        assert!(matches!(r.verdict, ReplicaVerdict::Inconclusive { .. }));
    }
}
