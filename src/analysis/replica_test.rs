//! The two-replica sensitivity test of a simulated forced system: does a tiny perturbation of
//! the state grow until the two copies are as far apart as two independent states of the
//! stroboscopic section, and how large is that sensitive part against the orbit?
//!
//! The simulator runs two copies over the same steps: replica A (the run itself) and replica B,
//! a copy of A perturbed by δ0 when the analysis window starts. At every forcing period t_k = kT both
//! section states are recorded: s = (z_cm, ż_cm, z_box, ż_box) for a granular bed, (x, ẋ) for a
//! one-degree-of-freedom oscillator. This module turns those strobes into the outcome; it knows
//! no simulator.
//!
//! # Formula
//! Every axis d is divided by the orbit's extent E_d (the range of that coordinate along A's
//! continuous trajectory over the window), so that all figures below are fractions of the
//! orbit, comparable between position and velocity:
//! - separation of the replicas d_k = max_d |s_A,k,d − s_B,k,d| / E_d (the worst axis);
//! - the judged span: the replicas are compared once they have separated, over as long a
//!   stretch as the record gives. With D_q^half = median over pairs i < j, i ≡ j (mod q), of
//!   A's strobes in the last half of max_d |s_A,i,d − s_A,j,d| / E_d (the same-phase
//!   separation of independent states; q = 1 … 8), the span of phase period q starts at the
//!   first strobe k*_q with d_k ≥ ½ D_q^half (the separation reached the scale of independent
//!   states), or at the last third when it never did or did later — whichever is longer;
//! - independent separation D_q: the same median over A's strobes in the span of q; D = D_1 (the
//!   whole section) as the simulator reports it, and D = D_n when the regime classifier finds
//!   the section to be n tight groups ([`ReplicaReport::at_period`]): two replicas locked to
//!   the same period-n cycle sit in the same group, so they can only become independent
//!   *within* it — comparing with the spread across groups would call a fully decorrelated
//!   period-3 bed "not yet separated";
//! - saturation d_sat = median of d_k over the span; trend d_sat(second half of the span) /
//!   d_sat(first half) (well above 1: still growing; well below: the replicas re-approached);
//! - macroscopic offset M = max_d |mean_A − mean_B| / E_d over the span, in units of D:
//!   two copies of one attractor have the same mean up to D √(6/n); an offset of D or more
//!   means the beds ended in different states (one compacted, coexisting attractors);
//! - growth rate λ: least squares of ln d_k on t_k from the first strobe with d_k ≥ 10 δ0/E_z
//!   up to (excluding) the first one reaching 0.3 d_sat, with its standard error; and the
//!   two-point initial rate ln(d_1 E_z / δ0) / (t_1 − t_p).
//!
//! Why a span from the first reach and not a fixed last third: once separated, a chaotic
//! bed's replicas stay independent on average but can re-approach for tens of periods (the
//! bed passes through a contracting episode, both copies follow it, and separate again). A
//! median over a fixed last third then depends on where such an episode falls — at 16 Hz on
//! `thesis_b_ch4.toml` it read 1.04, 0.39 and 1.35 × D over 200, 400 and 800 periods; over the
//! span from the first reach it reads 0.88, 1.04 and 1.31 × D.
//!
//! # Outcome
//! - **sensitive**: D/2 ≤ d_sat ≤ 2 D: the perturbation grew to the separation of independent
//!   states; the size of that sensitive part against the orbit is d_sat (and D);
//! - **insensitive**: d_sat ≤ max(10⁻² D, 10⁻⁶): the separation stays orders of magnitude
//!   below the section's spread (or the orbit's size when the section is a point);
//! - **partial**: 10⁻² D < d_sat < D/2 and d_sat ≥ 10³ δ0/E_z: the perturbation grew by
//!   three decades or more, but the replicas stay correlated on the section's larger motion
//!   over the window (a slowly mixing motion: at 11 Hz on `thesis_b_ch4.toml` d_sat/D reads
//!   0.32, 0.34 and 0.69 over 200, 400 and 800 periods while d_sat is 4–9 % of the orbit);
//!   sensitive, at a scale d_sat smaller than the section's spread;
//! - **inconclusive**: fewer than [`MIN_STROBES`] strobes, different macroscopic states
//!   (M ≥ 1 or d_sat > 2 D: never called chaos), or a separation between the two scales that
//!   grew less than three decades.
//!
//! # Units
//! δ0 in m (on z), times in s, rates in 1/s; separations and D relative to the orbit (–).
//!
//! # Pitfalls
//! The test says whether the motion is sensitive, not whether it is chaotic: a granular bed is
//! always sensitive at the grain scale (collisions of spheres diverge at tens to hundreds per
//! second); what separates a periodic bed from a chaotic one is whether d_sat is small against
//! the orbit. The regime classifier ([`crate::analysis::regime::classify_forced`]) combines
//! the two.

use serde::{Deserialize, Serialize};

/// Fewest strobes after the perturbation for an outcome.
pub const MIN_STROBES: usize = 30;
/// d_sat ≥ this × D: the replicas separated to the separation of independent states.
pub const SEPARATED_FACTOR: f64 = 0.5;
/// d_sat > this × D: the replicas ended in different states.
pub const DIFFERENT_STATES_FACTOR: f64 = 2.0;
/// d_sat ≤ this × D (or ≤ [`INSENSITIVE_FLOOR`]): the separation stays orders of magnitude
/// below the section's spread.
pub const INSENSITIVE_FACTOR: f64 = 1e-2;
/// d_sat ≤ this fraction of the orbit is insensitive whatever D (a section that is one point).
pub const INSENSITIVE_FLOOR: f64 = 1e-6;
/// d_sat ≥ this × δ0 (relative to the orbit) between the two scales: the separation grew by
/// three decades — more than rounding, a transient's convergence or a neutral drift along a
/// torus give — so the motion is sensitive, at a scale below the section's spread.
pub const GROWN_MIN: f64 = 1e3;
/// Number of section axes recorded (z_cm, ż_cm, z_box, ż_box; unused axes are 0).
pub const AXES: usize = 4;

/// One strobe of the two replicas (a row of `replica.csv`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ReplicaRow {
    /// Forcing period index k (t = k T).
    pub cycle: u64,
    /// Time t_k = k T (s).
    pub time_s: f64,
    /// Replica A's section state at t_k (SI units per axis).
    pub a: [f64; AXES],
    /// Replica B's section state at t_k.
    pub b: [f64; AXES],
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
    /// First fitted time (s).
    pub from_s: f64,
    /// Last fitted time (s).
    pub to_s: f64,
}

/// The span a phase period q is judged on and what it gives (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PhaseSpan {
    /// First strobe of the span (index into the strobes after the perturbation).
    pub start: usize,
    /// D_q: median same-phase separation of A's states in the span (relative to the orbit).
    pub independent_rel: f64,
    /// d_sat: median d_k over the span (relative).
    pub saturation_rel: f64,
    /// d_sat over the span's second half / over its first half.
    pub trend: f64,
    /// Largest offset of the replicas' mean section states over the span (relative).
    pub mean_offset_rel: f64,
}

/// What the separation did.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum ReplicaOutcome {
    /// The separation grew to that of independent states of the section.
    Sensitive {
        /// d_sat: the sensitive part's size as a fraction of the orbit (worst axis).
        saturation_rel_orbit: f64,
    },
    /// The separation stays orders of magnitude below the section's spread.
    Insensitive,
    /// The separation grew by orders of magnitude from δ0 but saturates below the separation
    /// of independent states: sensitive at a scale smaller than the section, the replicas
    /// still correlated on its larger (slower) motion over the window.
    Partial {
        /// d_sat as a fraction of the orbit (worst axis).
        saturation_rel_orbit: f64,
        /// d_sat / D.
        over_independent: f64,
    },
    /// Neither, and why.
    Inconclusive {
        /// What is missing or in between.
        why: String,
    },
}

impl ReplicaOutcome {
    /// `sensitive`, `insensitive`, `partial` or `inconclusive` (the `replica` column of
    /// `sweep.csv`).
    pub fn as_str(&self) -> &'static str {
        match self {
            ReplicaOutcome::Sensitive { .. } => "sensitive",
            ReplicaOutcome::Insensitive => "insensitive",
            ReplicaOutcome::Partial { .. } => "partial",
            ReplicaOutcome::Inconclusive { .. } => "inconclusive",
        }
    }
}

/// The two-replica report (`summary.json` block `replica`; the rows go to `replica.csv`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReplicaReport {
    /// Perturbation δ0 (m, on the first axis).
    pub delta0_m: f64,
    /// Time at which B was perturbed (s).
    pub perturbed_at_s: f64,
    /// Strobes after the perturbation.
    pub strobes: usize,
    /// Orbit extents E_d of A over the window (SI units per axis; 0: the axis is unused).
    pub orbit_extent: [f64; AXES],
    /// d_1: separation at the first strobe, relative to the orbit.
    pub first_separation_rel: f64,
    /// ln(d_1 E_z / δ0) / (t_1 − t_p): growth over the first strobe interval (1/s).
    pub initial_growth_per_s: Option<f64>,
    /// Largest d_k (relative to the orbit).
    pub max_separation_rel: f64,
    /// D: median separation of two independent states of A's section at the same phase of a
    /// `phase_period`-cycle (relative): D_q of `independent_by_period`.
    pub independent_separation_rel: f64,
    /// D_q for q = 1 ..= 8: pairs of A's states k ≡ k' (mod q) in the span judged at q
    /// (relative).
    #[serde(default)]
    pub independent_by_period: Vec<f64>,
    /// What the test is judged on at each phase period q = 1 ..= 8 (module docs: the span from
    /// the first reach); empty in reports written before the spans (then `at_period` re-judges
    /// with `independent_by_period` and the last third's saturation).
    #[serde(default)]
    pub spans: Vec<PhaseSpan>,
    /// The period q whose same-phase separation D is (1 from the simulator: the whole
    /// section; the regime classifier re-judges with the section's tight period n, because two
    /// replicas locked to a period-n cycle can only become independent within its groups).
    #[serde(default = "one")]
    pub phase_period: usize,
    /// Largest offset of the replicas' mean section states over the judged span (relative).
    #[serde(default)]
    pub mean_offset_rel: f64,
    /// Why the test could not run to its end (replica B non-finite, the run too short), when so.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub failure: Option<String>,
    /// d_sat: median d_k over the judged span (relative).
    pub saturation_rel: f64,
    /// d_sat over the second half of the judged span / d_sat over its first half.
    pub saturation_trend: f64,
    /// d_sat / D.
    pub saturation_over_independent: f64,
    /// M: largest offset of the replicas' mean section states over the judged span, / D.
    pub mean_offset_over_independent: f64,
    /// Growth of ln d_k over the growth phase (none: fewer than 3 strobes in it).
    pub growth: Option<GrowthFit>,
    /// The outcome.
    pub outcome: ReplicaOutcome,
    /// d_k at every strobe after the perturbation (relative to the orbit): stored with the
    /// report so that the outcome can be re-judged from a stored sweep point (A's states are
    /// its strobe rows) and the growth drawn without `replica.csv`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub separation_rel: Vec<f64>,
    /// Per-strobe rows (`replica.csv`).
    #[serde(skip)]
    pub rows: Vec<ReplicaRow>,
}

fn one() -> usize {
    1
}

impl ReplicaReport {
    /// The report judged against the same-phase separation D_q of a period-q cycle (the
    /// section's tight period; module docs), or `self` unchanged when D_q was not measured.
    pub fn at_period(&self, q: usize) -> ReplicaReport {
        let Some(&indep) = self.independent_by_period.get(q.wrapping_sub(1)) else {
            return self.clone();
        };
        let mut r = self.clone();
        r.phase_period = q;
        r.independent_separation_rel = indep;
        if let Some(span) = self.spans.get(q - 1) {
            r.saturation_rel = span.saturation_rel;
            r.saturation_trend = span.trend;
            r.mean_offset_rel = span.mean_offset_rel;
        }
        r.saturation_over_independent = r.saturation_rel / indep;
        r.mean_offset_over_independent = r.mean_offset_rel / indep;
        r.outcome = match &r.failure {
            Some(why) => ReplicaOutcome::Inconclusive { why: why.clone() },
            None => outcome(
                r.strobes,
                r.saturation_rel,
                indep,
                r.mean_offset_over_independent,
                self.delta_rel(),
            ),
        };
        r
    }

    /// δ0 relative to the orbit's extent on its axis (NaN when that axis never moved).
    pub fn delta_rel(&self) -> f64 {
        if self.orbit_extent[0] > 0.0 {
            self.delta0_m / self.orbit_extent[0]
        } else {
            f64::NAN
        }
    }

    /// The separation d_k of a row relative to the orbit (worst axis).
    pub fn separation(&self, row: &ReplicaRow) -> f64 {
        separation(&row.a, &row.b, &self.orbit_extent)
    }

    /// The growth rate the verdict quotes: the fit when there is one, else the initial rate
    /// (1/s) when the first strobe interval shows at least one e-fold of growth (d_1 ≥ e δ0;
    /// a first strobe a few steps after the perturbation shows none, and its two-point rate
    /// means nothing); with its standard error when fitted.
    pub fn growth_rate_per_s(&self) -> Option<(f64, Option<f64>)> {
        match self.growth {
            Some(g) => Some((g.per_s, Some(g.stderr_per_s))),
            None => {
                let grown = self.first_separation_rel * self.orbit_extent[0] / self.delta0_m;
                self.initial_growth_per_s
                    .filter(|_| grown >= std::f64::consts::E)
                    .map(|r| (r, None))
            }
        }
    }

    /// One line for humans: the outcome with its sizes and rate.
    pub fn describe(&self) -> String {
        let rate = match self.growth_rate_per_s() {
            Some((r, Some(se))) => format!(", growth {r:.3} ± {se:.3} 1/s"),
            Some((r, None)) => format!(", initial growth {r:.3} 1/s"),
            None => String::new(),
        };
        match &self.outcome {
            ReplicaOutcome::Sensitive {
                saturation_rel_orbit,
            } => format!(
                "sensitive: the replicas separate to {:.2} % of the orbit, as two independent section states ({:.2} %){rate}",
                100.0 * saturation_rel_orbit,
                100.0 * self.independent_separation_rel
            ),
            ReplicaOutcome::Insensitive => format!(
                "insensitive: the separation stays at {:.1e} of the orbit, orders of magnitude below the section's spread ({:.1e})",
                self.saturation_rel, self.independent_separation_rel
            ),
            ReplicaOutcome::Partial {
                saturation_rel_orbit,
                over_independent,
            } => format!(
                "partial: the replicas separate by orders of magnitude, to {:.2} % of the orbit, but only {:.2} × the separation of independent section states ({:.2} %){rate}",
                100.0 * saturation_rel_orbit,
                over_independent,
                100.0 * self.independent_separation_rel
            ),
            ReplicaOutcome::Inconclusive { why } => format!("inconclusive: {why}"),
        }
    }
}

/// max_d |a_d − b_d| / E_d over the axes with E_d > 0.
fn separation(a: &[f64; AXES], b: &[f64; AXES], extent: &[f64; AXES]) -> f64 {
    (0..AXES)
        .filter(|&d| extent[d] > 0.0)
        .map(|d| (a[d] - b[d]).abs() / extent[d])
        .fold(0.0, f64::max)
}

fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Largest residue period q of the same-phase separations D_q.
pub const MAX_PHASES: usize = 8;

/// The median separation of pairs of states at the same residue k mod q (module docs: D_q).
fn same_phase_median(states: &[[f64; AXES]], extent: &[f64; AXES], q: usize) -> f64 {
    let n = states.len();
    let mut d = Vec::with_capacity(n * n / (2 * q));
    for (i, a) in states.iter().enumerate() {
        let later = states.get(i + q..).unwrap_or_default();
        d.extend(later.iter().step_by(q).map(|b| separation(a, b, extent)));
    }
    median(&mut d)
}

/// The judged span of phase period q and its figures (module docs): from the first strobe at
/// which the separation `d` reached half the same-phase separation of A's last half, or the
/// last third when that is shorter. `a`, `b`: the replicas' states at the strobes of `d`.
fn phase_span(
    a: &[[f64; AXES]],
    b: &[[f64; AXES]],
    d: &[f64],
    extent: &[f64; AXES],
    q: usize,
) -> PhaseSpan {
    let n = d.len();
    let scale = same_phase_median(&a[n - n / 2..], extent, q);
    let last_third = n - n / 3;
    let start = d
        .iter()
        .position(|&x| x >= SEPARATED_FACTOR * scale)
        .map_or(last_third, |k| k.min(last_third));
    let mid = start + (n - start) / 2;
    let saturation_rel = median(&mut d[start..].to_vec());
    PhaseSpan {
        start,
        independent_rel: same_phase_median(&a[start..], extent, q),
        saturation_rel,
        trend: median(&mut d[mid..].to_vec()) / median(&mut d[start..mid].to_vec()),
        mean_offset_rel: mean_offset(&a[start..], &b[start..], extent),
    }
}

/// Largest per-axis offset of the two sets' means, relative to the orbit.
fn mean_offset(a: &[[f64; AXES]], b: &[[f64; AXES]], extent: &[f64; AXES]) -> f64 {
    let n = a.len().max(1) as f64;
    (0..AXES)
        .filter(|&d| extent[d] > 0.0)
        .map(|d| {
            let ma = a.iter().map(|s| s[d]).sum::<f64>() / n;
            let mb = b.iter().map(|s| s[d]).sum::<f64>() / n;
            (ma - mb).abs() / extent[d]
        })
        .fold(0.0, f64::max)
}

/// Slope of ln d against t from the first d ≥ `lower` up to (excluding) the first d ≥ `upper`.
fn growth_fit(t: &[f64], d: &[f64], lower: f64, upper: f64, period_s: f64) -> Option<GrowthFit> {
    // less than one e-fold between the bounds (or a bound not a number)
    if upper.is_nan() || lower.is_nan() || upper < std::f64::consts::E * lower {
        return None;
    }
    let k0 = d.iter().position(|&x| x >= lower)?;
    let k1 = d[k0..]
        .iter()
        .position(|&x| x >= upper)
        .map_or(d.len(), |i| k0 + i);
    let pts: Vec<(f64, f64)> = (k0..k1)
        .filter(|&k| d[k] > 0.0)
        .map(|k| (t[k], d[k].ln()))
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
    })
}

/// The report of two replicas' strobes (`rows` in time order) after a perturbation of
/// `delta0_m` (m, on axis 0) at `perturbed_at_s` (s), forcing `frequency_hz` (Hz), with the
/// orbit extents `orbit_extent` of replica A over the window (see the module docs).
pub fn report(
    delta0_m: f64,
    perturbed_at_s: f64,
    frequency_hz: f64,
    orbit_extent: [f64; AXES],
    rows: Vec<ReplicaRow>,
) -> ReplicaReport {
    let n = rows.len();
    let d: Vec<f64> = rows
        .iter()
        .map(|r| separation(&r.a, &r.b, &orbit_extent))
        .collect();
    let t: Vec<f64> = rows.iter().map(|r| r.time_s).collect();
    let a: Vec<[f64; AXES]> = rows.iter().map(|r| r.a).collect();
    let b: Vec<[f64; AXES]> = rows.iter().map(|r| r.b).collect();
    // q up to MAX_PHASES while the last half holds at least four strobes per phase
    let spans: Vec<PhaseSpan> = (1..=MAX_PHASES.min(n / 8).max(1))
        .map(|q| phase_span(&a, &b, &d, &orbit_extent, q))
        .collect();
    let whole = spans[0];
    let (indep, sat, offset_rel) = (
        whole.independent_rel,
        whole.saturation_rel,
        whole.mean_offset_rel,
    );
    let offset = offset_rel / indep;
    let delta_rel = if orbit_extent[0] > 0.0 {
        delta0_m / orbit_extent[0]
    } else {
        f64::NAN
    };
    let growth = growth_fit(&t, &d, 10.0 * delta_rel, 0.3 * sat, 1.0 / frequency_hz);
    let initial_growth_per_s = rows
        .first()
        .filter(|r| delta0_m > 0.0 && d[0] > 0.0 && r.time_s > perturbed_at_s)
        .map(|r| (d[0] / delta_rel).ln() / (r.time_s - perturbed_at_s));
    let outcome = outcome(n, sat, indep, offset, delta_rel);
    ReplicaReport {
        delta0_m,
        perturbed_at_s,
        strobes: n,
        orbit_extent,
        first_separation_rel: d.first().copied().unwrap_or(f64::NAN),
        initial_growth_per_s,
        max_separation_rel: d.iter().copied().fold(f64::NAN, f64::max),
        independent_separation_rel: indep,
        independent_by_period: spans.iter().map(|s| s.independent_rel).collect(),
        spans,
        phase_period: 1,
        mean_offset_rel: offset_rel,
        failure: None,
        saturation_rel: sat,
        saturation_trend: whole.trend,
        saturation_over_independent: sat / indep,
        mean_offset_over_independent: offset,
        growth,
        outcome,
        separation_rel: d,
        rows,
    }
}

/// The outcome rules of the module docs.
fn outcome(n: usize, sat: f64, indep: f64, offset: f64, delta_rel: f64) -> ReplicaOutcome {
    let inconclusive = |why: String| ReplicaOutcome::Inconclusive { why };
    if n < MIN_STROBES {
        return inconclusive(format!(
            "{n} strobes after the perturbation; the test needs ≥ {MIN_STROBES}"
        ));
    }
    if !(sat.is_finite() && indep.is_finite()) {
        return inconclusive("a separation is not finite".into());
    }
    if sat <= (INSENSITIVE_FACTOR * indep).max(INSENSITIVE_FLOOR) {
        return ReplicaOutcome::Insensitive;
    }
    if offset >= 1.0 || sat > DIFFERENT_STATES_FACTOR * indep {
        return inconclusive(format!(
            "the replicas ended in different macroscopic states: their mean section states \
             differ by {offset:.2} × the spread of one replica's section (D = {:.2} % of the \
             orbit; saturated separation {:.2} %) — one bed rearranged (e.g. compacted) or two \
             states coexist; not chaos",
            100.0 * indep,
            100.0 * sat
        ));
    }
    if sat >= SEPARATED_FACTOR * indep {
        return ReplicaOutcome::Sensitive {
            saturation_rel_orbit: sat,
        };
    }
    if sat >= GROWN_MIN * delta_rel {
        return ReplicaOutcome::Partial {
            saturation_rel_orbit: sat,
            over_independent: sat / indep,
        };
    }
    inconclusive(format!(
        "the separation saturates at {:.2e} of the orbit, between {INSENSITIVE_FACTOR} and \
         {SEPARATED_FACTOR} × the separation of independent states ({:.2e}), less than \
         {GROWN_MIN} × δ0 ({:.2e}): run longer",
        sat, indep, delta_rel
    ))
}

#[cfg(test)]
pub(crate) mod fixtures;
mod tests;
