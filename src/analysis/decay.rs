//! Free-decay envelope: the cycles of a decaying oscillation of the primary's displacement
//! z(t) and, per cycle, its amplitude, period, logarithmic decrement and equivalent damping
//! ratio.
//!
//! A free-decay test (the primary released from an initial displacement, no drive) is how
//! damping is measured in the lab. For a linear viscous oscillator the decrement is the same
//! every cycle; for a particle damper (or dry friction) it changes with the amplitude, and the
//! curve ζ(amplitude) is the damper's signature. [`decay_envelope`] computes it.
//!
//! # Formula
//! The extrema of z (m) are found in turn, maximum after minimum, with a hysteresis: an
//! extremum counts once the signal has swung back from it by more than half the amplitude
//! floor (so an oscillation that no longer crosses its mean with an amplitude above the floor,
//! because it has come to rest, sticks, or creeps to equilibrium, gives no more extrema). The
//! first and last samples are never extrema: a record that starts at a release point has its
//! first maximum one period later. Each sampled extremum i is refined to the vertex of the
//! parabola through (t_{i−1}, z_{i−1}), (t_i, z_i), (t_{i+1}, z_{i+1}).
//!
//! Cycle k is a maximum z⁺_k (at t⁺_k) and the following minimum z⁻_k (at t⁻_k):
//! - peak-to-peak P_k = z⁺_k − z⁻_k (m), amplitude a_k = P_k / 2 (m);
//! - time t_k = (t⁺_k + t⁻_k) / 2 (s), period T_k = t⁺_{k+1} − t⁺_k (s);
//! - logarithmic decrement δ_k = ln(P_k / P_{k+1}) (–);
//! - equivalent damping ratio ζ_k = δ_k / sqrt(4π² + δ_k²) (–), the inverse of
//!   δ = 2πζ / sqrt(1 − ζ²).
//!
//! δ_k needs the next cycle's peak-to-peak, so N (maximum, minimum) pairs give N − 1 cycles.
//!
//! For the linear oscillator m z'' + c z' + k z = 0, z = c₀ + A e^{−σt} cos(ω_d t + φ) with
//! σ = ζω₀ and ω_d = ω₀ sqrt(1 − ζ²): the extrema are exactly T_d/2 = π/ω_d apart with values
//! c₀ ± A sqrt(1 − ζ²) e^{−σt}, so P_k / P_{k+1} = e^{σT_d} exactly and ζ_k = ζ for every
//! cycle (Inman, *Engineering Vibration*, 4th ed., §1.6, logarithmic decrement). The
//! peak-to-peak value is used so that a static offset c₀ (the equilibrium shifted by the
//! grains' weight) does not bias δ. For a nonlinear damper ζ_k is the damping ratio of the
//! linear oscillator that loses the same fraction of its amplitude over that cycle. Under dry
//! (Coulomb) friction F, m z'' + k z = −F sign(z'), the amplitude drops by exactly 4F/k per
//! cycle (Den Hartog, *Mechanical Vibrations*, Coulomb damping), so δ = ln(a / (a − 4F/k))
//! rises as the amplitude a falls, and the motion stops (sticks) at the first extremum within
//! F/k of the spring's rest position.
//!
//! The list stops at the first cycle whose amplitude is below the floor
//! ([`DecayOptions::min_amplitude_m`], by default `relative_floor` × the first amplitude, and
//! never below `absolute_floor_m`), or when no further extremum is found.

use serde::Serialize;

use super::validate_series;
use crate::error::AnalysisError;
use crate::units::TWO_PI;

/// Fewest samples of a free-decay record (two full cycles need at least this many turning
/// points and their neighbours).
const MIN_SAMPLES: usize = 8;

/// Options of [`decay_envelope`]; [`Default`] holds the defaults.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DecayOptions {
    /// Amplitude floor (m): cycles of smaller amplitude end the envelope. `None` (default):
    /// `relative_floor` × the first cycle's amplitude. Set it above the noise of a measured
    /// record, so that noise is not read as cycles.
    pub min_amplitude_m: Option<f64>,
    /// Floor relative to the first amplitude when `min_amplitude_m` is `None` (default 1e−6).
    pub relative_floor: f64,
    /// Absolute floor (m) below which no amplitude is trusted (default 1e−12 m: far above the
    /// rounding of positions of order 1 m).
    pub absolute_floor_m: f64,
    /// Refine each sampled extremum by the parabola through it and its two neighbours (default
    /// `true`). `false` uses the sampled values: only for comparisons.
    pub refine_extrema: bool,
}

impl Default for DecayOptions {
    fn default() -> Self {
        DecayOptions {
            min_amplitude_m: None,
            relative_floor: 1e-6,
            absolute_floor_m: 1e-12,
            refine_extrema: true,
        }
    }
}

/// Why the envelope ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum DecayStop {
    /// The record ends while the oscillation goes on.
    EndOfRecord,
    /// The amplitude fell below the floor.
    AmplitudeFloor,
    /// No turning point during more than a period before the end of the record: the
    /// oscillation no longer crosses its mean by more than half the floor (at rest, stuck by
    /// friction, or overdamped).
    AtRest,
}

/// One cycle of a free decay.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize)]
pub struct DecayCycle {
    /// Cycle number, from 1.
    pub cycle: usize,
    /// Time t_k (s): midway between the cycle's maximum and the following minimum.
    pub time_s: f64,
    /// Amplitude a_k = (z⁺_k − z⁻_k) / 2 (m).
    pub amplitude_m: f64,
    /// Period T_k = t⁺_{k+1} − t⁺_k between this cycle's maximum and the next (s).
    pub period_s: f64,
    /// Logarithmic decrement δ_k = ln(P_k / P_{k+1}) (–).
    pub log_decrement: f64,
    /// Equivalent damping ratio ζ_k = δ_k / sqrt(4π² + δ_k²) (–).
    pub damping_ratio: f64,
}

/// The decay envelope: the cycles and summary figures (the `decay` block of a run's
/// `summary.json`).
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
pub struct DecayEnvelope {
    /// Amplitude of the first cycle (m).
    pub initial_amplitude_m: f64,
    /// Number of cycles (≥ 1).
    pub cycle_count: usize,
    /// ζ of the first cycle (–).
    pub first_damping_ratio: f64,
    /// ζ of the last cycle (–).
    pub last_damping_ratio: f64,
    /// Mean of ζ_k over all cycles (–).
    pub mean_damping_ratio: f64,
    /// The amplitude floor that was applied (m).
    pub floor_m: f64,
    /// Why the list of cycles ends.
    pub stop: DecayStop,
    /// The cycles, in time order.
    pub cycles: Vec<DecayCycle>,
}

/// Equivalent damping ratio ζ = δ / sqrt(4π² + δ²) of a logarithmic decrement δ (–): exact
/// for a linear viscous oscillator, whose δ = 2πζ / sqrt(1 − ζ²).
pub fn damping_ratio_of_decrement(log_decrement: f64) -> f64 {
    log_decrement / (TWO_PI * TWO_PI + log_decrement * log_decrement).sqrt()
}

/// The free-decay envelope of the displacement `z_m` (m) sampled at times `t_s` (s): per
/// cycle its time, amplitude, period, logarithmic decrement and equivalent damping ratio
/// (module documentation for the formulas).
///
/// # Errors
/// - [`AnalysisError::BadParameter`] naming `z_m` (length differs from `t_s`), `t_s` (a
///   non-finite, repeated or decreasing time, with its index) or an option;
/// - [`AnalysisError::NonFinite`] with the index of the first non-finite displacement;
/// - [`AnalysisError::TooShort`] for fewer than 8 samples, or fewer than 2 full cycles above
///   the amplitude floor (run longer, or release from a larger initial displacement);
/// - [`AnalysisError::Constant`] for a constant displacement.
pub fn decay_envelope(
    t_s: &[f64],
    z_m: &[f64],
    opts: &DecayOptions,
) -> Result<DecayEnvelope, AnalysisError> {
    validate_input(t_s, z_m, opts)?;
    let floor_m = amplitude_floor(t_s, z_m, opts);
    let extrema = extrema(t_s, z_m, floor_m, opts);
    let mut pairs = cycle_pairs(&extrema);
    let below = pairs.iter().position(|p| p.amplitude() < floor_m);
    if let Some(k) = below {
        pairs.truncate(k);
    }
    if pairs.len() < 2 {
        return Err(too_few_cycles(pairs.len(), floor_m));
    }
    let cycles = cycles_of(&pairs);
    let stop = if below.is_some() {
        DecayStop::AmplitudeFloor
    } else {
        end_reason(&extrema, &cycles, t_s[t_s.len() - 1])
    };
    Ok(envelope(cycles, floor_m, stop))
}

/// The amplitude floor (m): the given one, else `relative_floor` × the first amplitude (from
/// turning points found with a hysteresis of `relative_floor` × half the record's range).
fn amplitude_floor(t_s: &[f64], z_m: &[f64], opts: &DecayOptions) -> f64 {
    if opts.min_amplitude_m.is_some() {
        return floor(opts, 0.0);
    }
    let (lo, hi) = super::min_max(z_m);
    let coarse = floor(opts, (hi - lo) / 2.0);
    let first = cycle_pairs(&extrema(t_s, z_m, coarse, opts))
        .first()
        .map_or(hi - lo, Pair::amplitude);
    floor(opts, first)
}

/// The turning points of `z_m`, refined as the options say, with a hysteresis of half
/// `floor_m`, so that the first pair below the floor is found (and ends the envelope) even
/// under heavy damping, where the swing back from a minimum is about the pair's amplitude.
fn extrema(t_s: &[f64], z_m: &[f64], floor_m: f64, opts: &DecayOptions) -> Vec<Extremum> {
    turning_points(z_m, 0.5 * floor_m)
        .into_iter()
        .map(|(i, is_max)| refine(t_s, z_m, i, is_max, opts.refine_extrema))
        .collect()
}

/// The floor (m) for a first amplitude `first_m`: the given one or the relative one, never
/// below the absolute one.
fn floor(opts: &DecayOptions, first_m: f64) -> f64 {
    opts.min_amplitude_m
        .unwrap_or(opts.relative_floor * first_m)
        .max(opts.absolute_floor_m)
}

/// Checks lengths, finiteness, time order and options.
fn validate_input(t_s: &[f64], z_m: &[f64], opts: &DecayOptions) -> Result<(), AnalysisError> {
    if t_s.len() != z_m.len() {
        return Err(AnalysisError::bad(
            "z_m",
            format!("{} samples", z_m.len()),
            format!(
                "t_s has {} samples: give one displacement per time",
                t_s.len()
            ),
        ));
    }
    validate_series(z_m, MIN_SAMPLES, "the free-decay envelope")?;
    validate_times(t_s)?;
    validate_options(opts)
}

/// Times finite and strictly increasing.
fn validate_times(t_s: &[f64]) -> Result<(), AnalysisError> {
    if let Some(i) = t_s.iter().position(|t| !t.is_finite()) {
        return Err(AnalysisError::bad(
            "t_s",
            format!("{} at index {i}", t_s[i]),
            "every time must be a finite number of seconds",
        ));
    }
    if let Some(i) = (1..t_s.len()).find(|&i| t_s[i] <= t_s[i - 1]) {
        return Err(AnalysisError::bad(
            "t_s",
            format!("{} at index {i}", t_s[i]),
            format!(
                "not after t_s[{}] = {}: sort the samples by time and drop repeated times",
                i - 1,
                t_s[i - 1]
            ),
        ));
    }
    Ok(())
}

/// Floors finite and non-negative (the given one positive), relative floor below 1.
fn validate_options(opts: &DecayOptions) -> Result<(), AnalysisError> {
    if let Some(m) = opts.min_amplitude_m {
        if !(m.is_finite() && m > 0.0) {
            return Err(AnalysisError::bad(
                "min_amplitude_m",
                m,
                "the amplitude floor must be a positive number of metres",
            ));
        }
    }
    if !(opts.relative_floor.is_finite() && (0.0..1.0).contains(&opts.relative_floor)) {
        return Err(AnalysisError::bad(
            "relative_floor",
            opts.relative_floor,
            "must be in [0, 1), e.g. 1e-6 of the first amplitude",
        ));
    }
    if !(opts.absolute_floor_m.is_finite() && opts.absolute_floor_m >= 0.0) {
        return Err(AnalysisError::bad(
            "absolute_floor_m",
            opts.absolute_floor_m,
            "must be a non-negative number of metres",
        ));
    }
    Ok(())
}

/// The error for fewer than 2 full cycles above the floor.
fn too_few_cycles(found: usize, floor_m: f64) -> AnalysisError {
    AnalysisError::TooShort(format!(
        "the free-decay envelope needs at least 2 full cycles (a maximum and the following \
         minimum, twice) with an amplitude above {floor_m:e} m; the record has {found}: run \
         longer, or release from a larger initial displacement (an overdamped motion does not \
         oscillate at all)"
    ))
}

/// Indices of the confirmed turning points of `z`, alternating, with `true` for a maximum:
/// an extremum counts once the signal has swung back from it by more than `swing`. The first
/// and last samples are never turning points.
fn turning_points(z: &[f64], swing: f64) -> Vec<(usize, bool)> {
    let mut out = Vec::new();
    let (mut hi, mut lo) = (0, 0);
    // None until the first extremum: then whether a maximum is being looked for
    let mut want_max: Option<bool> = None;
    for (i, &v) in z.iter().enumerate().skip(1) {
        if want_max != Some(false) && v > z[hi] {
            hi = i;
        }
        if want_max != Some(true) && v < z[lo] {
            lo = i;
        }
        if want_max != Some(false) && z[hi] - v > swing {
            out.push((hi, true));
            want_max = Some(false);
            lo = i;
        } else if want_max != Some(true) && v - z[lo] > swing {
            out.push((lo, false));
            want_max = Some(true);
            hi = i;
        }
    }
    out.retain(|&(i, _)| i > 0 && i + 1 < z.len());
    out
}

/// A turning point: time (s), displacement (m), maximum or minimum.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Extremum {
    t: f64,
    z: f64,
    is_max: bool,
}

/// The extremum at sample `i`, refined (if `refine`) to the vertex of the parabola through
/// samples i−1, i, i+1. Falls back to the sample when the parabola is flat or curves the wrong
/// way.
fn refine(t: &[f64], z: &[f64], i: usize, is_max: bool, refine: bool) -> Extremum {
    let sampled = Extremum {
        t: t[i],
        z: z[i],
        is_max,
    };
    if !refine || i == 0 || i + 1 >= z.len() {
        return sampled;
    }
    // p(u) = z_i + b u + a u², u = t − t_i, through the three samples
    let (u0, u2) = (t[i - 1] - t[i], t[i + 1] - t[i]);
    let (s0, s2) = ((z[i - 1] - z[i]) / u0, (z[i + 1] - z[i]) / u2);
    let a = (s2 - s0) / (u2 - u0);
    let b = s0 - a * u0;
    let curves_right_way = if is_max { a < 0.0 } else { a > 0.0 };
    if !(curves_right_way && a.is_finite() && b.is_finite()) {
        return sampled;
    }
    let u = (-b / (2.0 * a)).clamp(u0, u2);
    Extremum {
        t: t[i] + u,
        z: z[i] + b * u + a * u * u,
        is_max,
    }
}

/// A maximum and the following minimum.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Pair {
    max: Extremum,
    min: Extremum,
}

impl Pair {
    /// Half the peak-to-peak value (m).
    fn amplitude(&self) -> f64 {
        0.5 * (self.max.z - self.min.z)
    }
}

/// The (maximum, following minimum) pairs of the alternating turning points, from the first
/// maximum.
fn cycle_pairs(extrema: &[Extremum]) -> Vec<Pair> {
    let start = extrema
        .iter()
        .position(|e| e.is_max)
        .unwrap_or(extrema.len());
    extrema[start..]
        .chunks_exact(2)
        .map(|c| Pair {
            max: c[0],
            min: c[1],
        })
        .collect()
}

/// One cycle per pair that has a next pair (δ needs both).
fn cycles_of(pairs: &[Pair]) -> Vec<DecayCycle> {
    pairs
        .windows(2)
        .enumerate()
        .map(|(k, w)| {
            let log_decrement = (w[0].amplitude() / w[1].amplitude()).ln();
            DecayCycle {
                cycle: k + 1,
                time_s: 0.5 * (w[0].max.t + w[0].min.t),
                amplitude_m: w[0].amplitude(),
                period_s: w[1].max.t - w[0].max.t,
                log_decrement,
                damping_ratio: damping_ratio_of_decrement(log_decrement),
            }
        })
        .collect()
}

/// At rest when the record goes on for more than the last period after the last turning
/// point, else the end of the record.
fn end_reason(extrema: &[Extremum], cycles: &[DecayCycle], t_end: f64) -> DecayStop {
    let last_t = extrema.last().map_or(t_end, |e| e.t);
    let period = cycles.last().map_or(f64::INFINITY, |c| c.period_s);
    if t_end - last_t > period {
        DecayStop::AtRest
    } else {
        DecayStop::EndOfRecord
    }
}

/// The envelope with its summary figures (`cycles` not empty).
fn envelope(cycles: Vec<DecayCycle>, floor_m: f64, stop: DecayStop) -> DecayEnvelope {
    let n = cycles.len();
    let zeta = |k: usize| cycles.get(k).map_or(f64::NAN, |c| c.damping_ratio);
    DecayEnvelope {
        initial_amplitude_m: cycles.first().map_or(f64::NAN, |c| c.amplitude_m),
        cycle_count: n,
        first_damping_ratio: zeta(0),
        last_damping_ratio: zeta(n.saturating_sub(1)),
        mean_damping_ratio: cycles.iter().map(|c| c.damping_ratio).sum::<f64>() / n as f64,
        floor_m,
        stop,
        cycles,
    }
}

#[cfg(test)]
mod tests;
