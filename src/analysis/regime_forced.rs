//! The regime of a forced system ([`classify_forced`]): judged from its exact stroboscopic
//! section's tightness, with the simulator's own sensitivity — the impact model's exponent or
//! the DEM's two-replica test — where there is one, and the data exponent otherwise; the phase
//! lock and the chaos dimension travel with the verdict as qualifiers. Re-exported by
//! [`crate::analysis::regime`], which holds the verdict types and the plain-series classifier.

use super::regime::{Exponent, ExponentSign, Regime, Verdict};
use crate::analysis::phase_lock::PhaseLock;
use crate::analysis::replica_test::{ReplicaOutcome, ReplicaReport};
use crate::analysis::section::{Grouping, SectionAnalysis, SectionPattern};
use crate::analysis::section_dimension::ChaosDimension;

/// What the forced-system classifier [`classify_forced`] looks at.
#[derive(Debug, Clone, PartialEq)]
pub struct ForcedEvidence<'a> {
    /// The exact stroboscopic section's pattern ([`crate::analysis::section::analyze_section`]).
    pub section: &'a SectionAnalysis,
    /// Exponent of the stroboscopic map estimated from the data (the section's divergence).
    pub data_exponent: Option<Exponent>,
    /// Exponent computed from the model's equations (tangent dynamics), when the simulator
    /// knows them.
    pub model_exponent: Option<Exponent>,
    /// Neutral band of the exponents per period (default 0.01: slower divergence than
    /// e-fold per 100 forcing periods is not called chaos).
    pub zero_band: f64,
    /// Synchronous average of the motion relative to the container
    /// ([`crate::analysis::phase_lock`]): a qualifier of the verdict, never the verdict.
    pub phase_lock: Option<PhaseLock>,
    /// The simulation's own sensitivity test ([`crate::analysis::replica_test`]), when the
    /// simulator ran two replicas.
    pub replica: Option<&'a ReplicaReport>,
    /// The simulator holds a two-replica test it runs only if the verdict needs it
    /// (`replica` is then `None`): a section of n tight groups is periodic-n without it.
    pub replica_deferred: bool,
    /// Low- or high-dimensional section ([`crate::analysis::section_dimension`]), when
    /// estimated.
    pub dimension: Option<ChaosDimension>,
}

/// Revision of the verdict rules, carried by every analysis report
/// ([`crate::analysis::analyze::AnalysisReport::verdict_rules`]) so that verdicts judged by
/// different rules are never compared silently (the trade-off table refuses to). 1: tight
/// groups by their RMS scatter, replicas between the scales "inconclusive"; 2: tight groups
/// by their spread ([`crate::analysis::section::grouping`]), a *partial* replica outcome, a
/// tight section periodic whatever the replicas. Raise it with any change that can move a
/// verdict.
pub const VERDICT_RULES: u32 = 2;

/// Locked fraction Λ_p at and above which the motion relative to the container is called
/// phase-locked to the forcing: the mean waveform carries ≥ 90 % of the variance, i.e. the
/// RMS about it is ≤ 32 % of the motion's RMS. A qualifier that travels with the verdict
/// ("chaotic, phase-locked to the forcing"): the collective motion follows the drive, which
/// says nothing about whether it repeats.
pub const LOCKED_FRACTION_MIN: f64 = 0.9;

/// Returns the regime of a forced system, judged from its exact stroboscopic section and,
/// where the simulator provides them, its model exponent or its two-replica test.
///
/// # Formula
/// A section is *tight* with period n when its points fall into n groups visited cyclically
/// and, on every axis (position and velocity), a typical point lies within 5 % of the orbit's
/// extent of its group (1.4826 × the median distance; the RMS of all axes within 10 %), the groups
/// separated and not outdone by a longer separated period
/// ([`crate::analysis::section::grouping`]). 5 %: a group that small is one point of the
/// orbit to the eye and to every figure of merit the damper is designed for (the amplitude
/// and the energy per cycle move by about the square of the scatter), while a chaotic band or
/// a granular gas spreads over tens of per cent (≥ 6.5 % on the chapter-4 bed but for a
/// five-band motion whose bands are not separated).
/// 1. Too short: fewer section points than the pattern test needs → `too-short`.
/// 2. Model exponent (the impact model's tangent dynamics) decides chaos: positive (λ >
///    max(3σ, band)) → chaotic, unless the section is a finite set of points (an indicator
///    conflict → undetermined); not positive with a cloud → undetermined; otherwise the
///    section's pattern.
/// 3. Two-replica test (the DEM): a tight section is periodic-n whatever the replicas did
///    (the sensitive part is confined to the groups: d_sat, judged at the same phase, is
///    quoted). Otherwise: a closed curve is quasi-periodic unless the test is inconclusive; a
///    cloud is chaotic when the replicas are sensitive (d_sat ≈ D: the sensitive part is the
///    cloud) or partial (d_sat grew ≥ 10³ δ0 but stays below D/2: aperiodic and sensitive,
///    slowly mixing — said in the reason), undetermined when they are insensitive (a long
///    transient or a long period) or the test is inconclusive (too short, or two beds in
///    different macroscopic states); an exactly periodic section is periodic whatever the
///    test.
/// 4. Data only (a user's series): the section's pattern; a cloud is chaotic when the data
///    exponent is positive and the scatter deterministic (determinism ratio < 0.5),
///    undetermined when deterministic without resolved divergence, else irregular
///    (noise-like).
///
/// Qualifiers: `phase_locked` when Λ_p ≥ [`LOCKED_FRACTION_MIN`] and the verdict is not
/// periodic; `dimension` on chaotic and irregular verdicts.
///
/// # Units
/// Exponents per forcing period.
pub fn classify_forced(e: &ForcedEvidence<'_>) -> Verdict {
    let mut v = match (e.model_exponent, e.replica) {
        _ if matches!(e.section.pattern, SectionPattern::TooShort { .. }) => too_short(e.section),
        (Some(m), _) => by_model(e, m),
        (None, Some(r)) => by_replica(e, r),
        (None, None) => match &e.section.tight {
            Some(g) if e.replica_deferred => tight_groups(g, None),
            _ => by_data(e),
        },
    };
    if v.regime != Regime::Periodic && v.regime != Regime::TooShort {
        v.phase_locked = e
            .phase_lock
            .filter(|l| l.locked_fraction >= LOCKED_FRACTION_MIN);
    }
    if matches!(v.regime, Regime::Chaotic | Regime::Irregular) {
        v.dimension = e.dimension;
    }
    v
}

fn fmt_exp(x: &Exponent) -> String {
    format!(
        "{:+.4} ± {:.4} per period",
        x.per_period, x.stderr_per_period
    )
}

fn too_short(sec: &SectionAnalysis) -> Verdict {
    let SectionPattern::TooShort { points, needed } = sec.pattern else {
        unreachable!("called for a too-short section")
    };
    Verdict::new(
        Regime::TooShort,
        None,
        format!(
            "the analysed window holds {points} forcing periods; a verdict needs at least {needed}: analyse a longer record"
        ),
    )
}

/// The worst axis's scatter of the section's best grouping, in per cent of the orbit.
fn worst_axis_pct(sec: &SectionAnalysis) -> f64 {
    100.0 * crate::analysis::section::grouping::worst(&sec.axis_scatter)
}

/// Periodic-n from the section's own pattern (exact, converging or with noise).
fn periodic_from_section(sec: &SectionAnalysis, period: usize, noisy: bool) -> Verdict {
    let how = if noisy {
        format!(
            "with a non-deterministic scatter of {:.2} % of the extent (determinism ratio {:.2})",
            100.0 * sec.scatter,
            sec.determinism_ratio.unwrap_or(f64::NAN)
        )
    } else if let Some(rate) = sec.convergence_rate {
        format!("still converging in the window (return distance decays at {rate:.4} per period)")
    } else {
        format!("coinciding to {:.1e} of the extent", sec.scatter)
    };
    Verdict::new(
        Regime::Periodic,
        Some(period as f64),
        format!("the exact section visits {period} point(s) cyclically, {how}"),
    )
}

fn quasi_periodic(rotation_number: f64, extra: &str) -> Verdict {
    Verdict::new(
        Regime::QuasiPeriodic,
        None,
        format!(
            "the exact section is a closed curve rotated by the map (rotation number {rotation_number:.4}){extra}"
        ),
    )
}

/// Rule 2: the model's exponent decides chaos.
fn by_model(e: &ForcedEvidence<'_>, m: Exponent) -> Verdict {
    let sec = e.section;
    let sign = m.sign(e.zero_band);
    let data = e.data_exponent.map(|d| (d, d.sign(e.zero_band)));
    match sec.pattern {
        SectionPattern::Periodic { period, .. } if sign == ExponentSign::Positive => Verdict::new(
            Regime::Undetermined,
            None,
            format!(
                "indicators conflict: the section is periodic-{period} but the model exponent is {}",
                fmt_exp(&m)
            ),
        ),
        SectionPattern::Periodic { period, noisy } => periodic_from_section(sec, period, noisy),
        SectionPattern::QuasiPeriodic { rotation_number } => {
            let positive = [Some((m, sign)), data]
                .into_iter()
                .flatten()
                .find(|(_, s)| *s == ExponentSign::Positive);
            match positive {
                Some((x, _)) => Verdict::new(
                    Regime::Undetermined,
                    None,
                    format!(
                        "indicators conflict: the section is a closed curve (rotation number {rotation_number:.4}) but an exponent is {}",
                        fmt_exp(&x)
                    ),
                ),
                None => quasi_periodic(rotation_number, ""),
            }
        }
        _ if sign == ExponentSign::Positive => Verdict::new(
            Regime::Chaotic,
            None,
            format!(
                "the model exponent is {} and the section is a cloud{}",
                fmt_exp(&m),
                data.map_or(String::new(), |(d, _)| format!(
                    " (data estimate {})",
                    fmt_exp(&d)
                ))
            ),
        ),
        _ => Verdict::new(
            Regime::Undetermined,
            None,
            format!(
                "indicators conflict: the section shows no period ≤ the maximum but the model exponent is {} (a long transient or a longer period)",
                fmt_exp(&m)
            ),
        ),
    }
}

/// Rule 3: the simulation's two-replica test with the section's tightness.
fn by_replica(e: &ForcedEvidence<'_>, r: &ReplicaReport) -> Verdict {
    let sec = e.section;
    // n tight groups: the run is periodic-n whatever the replicas did — they can only say how
    // large its sensitive part is, judged at the same phase of the cycle
    if let Some(g) = &sec.tight {
        return tight_groups(g, Some(&r.at_period(g.period)));
    }
    let exact = matches!(sec.pattern, SectionPattern::Periodic { noisy: false, .. });
    match (&r.outcome, sec.pattern) {
        (_, SectionPattern::Periodic { period, noisy }) if exact => {
            periodic_from_section(sec, period, noisy)
        }
        (ReplicaOutcome::Inconclusive { why }, _) => Verdict::new(
            Regime::Undetermined,
            None,
            format!(
                "the two-replica test is inconclusive ({why}); the section alone is {}",
                section_words(sec)
            ),
        ),
        (ReplicaOutcome::Insensitive, SectionPattern::QuasiPeriodic { rotation_number }) => {
            quasi_periodic(rotation_number, "; two replicas stay together (insensitive)")
        }
        (ReplicaOutcome::Insensitive, _) => Verdict::new(
            Regime::Undetermined,
            None,
            format!(
                "the section is {} but two replicas do not separate (saturation {:.1e} of the orbit): a long transient or a period above the maximum",
                section_words(sec),
                r.saturation_rel
            ),
        ),
        (
            ReplicaOutcome::Sensitive {
                saturation_rel_orbit,
            }
            | ReplicaOutcome::Partial {
                saturation_rel_orbit,
                ..
            },
            SectionPattern::QuasiPeriodic { rotation_number },
        ) => quasi_periodic(
            rotation_number,
            &format!(
                "; two replicas separate to {:.2} % of the orbit (sensitive within the curve's thickness, {:.2} %)",
                100.0 * saturation_rel_orbit,
                100.0 * sec.thickness.unwrap_or(f64::NAN)
            ),
        ),
        (
            ReplicaOutcome::Sensitive {
                saturation_rel_orbit,
            },
            _,
        ) => Verdict::new(
            Regime::Chaotic,
            None,
            format!(
                "the exact section is a cloud (size {:.1} % of the orbit, worst axis scatter {:.1} %) and two replicas started 1e-9 apart separate to {:.1} % of the orbit, as two independent states of the section{}",
                100.0 * sec.size,
                worst_axis_pct(sec),
                100.0 * saturation_rel_orbit,
                rate_words(r)
            ),
        ),
        (
            ReplicaOutcome::Partial {
                saturation_rel_orbit,
                over_independent,
            },
            _,
        ) => Verdict::new(
            Regime::Chaotic,
            None,
            format!(
                "the exact section is a cloud (size {:.1} % of the orbit, worst axis scatter {:.1} %) with no period and no closed curve, and two replicas started 1e-9 apart separate by orders of magnitude, to {:.1} % of the orbit{} — aperiodic and sensitive; slowly mixing: over the window the replicas stay correlated on the section's larger motion ({:.2} × the separation of independent states)",
                100.0 * sec.size,
                worst_axis_pct(sec),
                100.0 * saturation_rel_orbit,
                rate_words(r),
                over_independent
            ),
        ),
    }
}

/// Periodic-n from n tight groups, with what the replicas did (judged at the same phase), or
/// that they were not needed (`r` = `None`: the simulator left its test unrun).
fn tight_groups(g: &Grouping, r: Option<&ReplicaReport>) -> Verdict {
    let what = match r.map(|r| (r, &r.outcome)) {
        None => "were not needed (n tight groups are periodic-n whatever they do; \
                 `run.replica = true` runs them)"
            .to_string(),
        Some((_, ReplicaOutcome::Insensitive)) => "stay together (insensitive)".to_string(),
        Some((r, ReplicaOutcome::Sensitive {
            saturation_rel_orbit,
        })) => format!(
            "separate to {:.2} % of the orbit{}, as two independent states of one group — sensitive, but only within the groups",
            100.0 * saturation_rel_orbit,
            rate_words(r)
        ),
        Some((r, ReplicaOutcome::Partial {
            saturation_rel_orbit,
            ..
        })) => format!(
            "separate to {:.2} % of the orbit{} — sensitive, within the groups",
            100.0 * saturation_rel_orbit,
            rate_words(r)
        ),
        Some((r, ReplicaOutcome::Inconclusive { why })) => format!(
            "stay within {:.2} % of the orbit ({why})",
            100.0 * r.saturation_rel
        ),
    };
    Verdict::new(
        Regime::Periodic,
        Some(g.period as f64),
        format!(
            "the exact section is {} tight group(s) visited cyclically (typical distance from the group {:.2} % of the orbit on the worst axis, RMS {:.2} %); two replicas {what}",
            g.period,
            100.0 * g.worst_spread(),
            100.0 * g.worst_scatter(),
        ),
    )
}

fn rate_words(r: &ReplicaReport) -> String {
    match r.growth_rate_per_s() {
        Some((g, Some(se))) => format!(" at {g:.3} ± {se:.3} 1/s"),
        Some((g, None)) => format!(" (initial rate {g:.3} 1/s)"),
        None => String::new(),
    }
}

fn section_words(sec: &SectionAnalysis) -> String {
    match sec.pattern {
        SectionPattern::Periodic { period, .. } => format!("periodic-{period}"),
        SectionPattern::QuasiPeriodic { .. } => "a closed curve".into(),
        _ => format!("a cloud of {:.1} % of the orbit", 100.0 * sec.size),
    }
}

/// Rule 4: the data alone.
fn by_data(e: &ForcedEvidence<'_>) -> Verdict {
    let sec = e.section;
    let data = e.data_exponent.map(|d| (d, d.sign(e.zero_band)));
    let ratio = sec.determinism_ratio;
    match sec.pattern {
        SectionPattern::Periodic { period, noisy } => periodic_from_section(sec, period, noisy),
        SectionPattern::QuasiPeriodic { rotation_number } => match data {
            Some((d, ExponentSign::Positive)) => Verdict::new(
                Regime::Undetermined,
                None,
                format!(
                    "indicators conflict: the section is a closed curve (rotation number {rotation_number:.4}) but an exponent is {}",
                    fmt_exp(&d)
                ),
            ),
            _ => quasi_periodic(rotation_number, ""),
        },
        _ => match data {
            Some((d, ExponentSign::Positive)) if ratio.is_none_or(|r| r < 0.5) => Verdict::new(
                Regime::Chaotic,
                None,
                format!(
                    "the section is a deterministic cloud (determinism ratio {:.2}) diverging at {}",
                    ratio.unwrap_or(f64::NAN),
                    fmt_exp(&d)
                ),
            ),
            d if ratio.is_some_and(|r| r < 0.5) => Verdict::new(
                Regime::Undetermined,
                None,
                format!(
                    "indicators conflict: the section is a deterministic cloud (determinism ratio {:.2}) but shows no resolved divergence{} (weak chaos, or a torus that is not star-shaped)",
                    ratio.unwrap_or(f64::NAN),
                    d.map_or(String::new(), |(d, _)| format!(": data exponent {}", fmt_exp(&d)))
                ),
            ),
            d => Verdict::new(
                Regime::Irregular,
                None,
                format!(
                    "the section is a cloud without low-dimensional determinism (determinism ratio {:.2}{}): noise, or chaos of more degrees of freedom than the section resolves — a simulation can tell with its two-replica test",
                    ratio.unwrap_or(f64::NAN),
                    d.map_or(String::new(), |(d, _)| format!(", data exponent {}", fmt_exp(&d)))
                ),
            ),
        },
    }
}

mod tests;
