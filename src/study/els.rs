//! The linear-DEM paper's §3.3 (`../shared/seeds`): a particle damper under centrifugal load
//! (Els, Stellenbosch 2009) — 26 steel balls of 4 mm in a cylindrical cavity turning at 138 rpm
//! 0.4 m from the axis, in free decay from −6.5 mm. The paper finds three zones: high damping
//! while the grains move like a liquid (I), a transition (II), then almost none once the bed
//! moves as a solid (III), the system's damping that of the primary alone.

use crate::analysis::decay_zones::{decay_zones, LIQUID_FRACTION, SOLID_FRACTION};
use crate::error::StudyError;
use crate::plot::decay::DecayFigure;

use super::pipeline::{BundledScene, Ctx, FigureRecord};

/// The figures of this module (for `--only`).
pub(super) const NAMES: [&str; 1] = ["els_decay"];

/// `data/scenes/els_2009_centrifugal.toml`.
pub const ELS: BundledScene = BundledScene {
    path: "data/scenes/els_2009_centrifugal.toml",
    text: include_str!("../../data/scenes/els_2009_centrifugal.toml"),
};

/// ζ per cycle against amplitude for the decay at 138 rpm, with the zones and the primary's
/// own damping ratio.
pub(super) fn els_decay(ctx: &Ctx) -> Result<FigureRecord, StudyError> {
    let name = "els_decay";
    let (_, p) = ELS.with_primary(name)?;
    let zeta0 = p.damping_ratio();
    let sweep = ctx.sweep(
        "els_2009",
        ELS,
        &[],
        &[("environment.rotation.rpm", "138".into())],
        false,
    )?;
    let point = sweep.first_point(name)?;
    let envelope = point.summary.decay.as_ref().ok_or_else(|| {
        StudyError::step(
            name,
            "the run wrote no decay envelope (is the scene a free decay?)",
        )
    })?;
    let zones = decay_zones(envelope, zeta0);
    let amplitude: Vec<f64> = envelope.cycles.iter().map(|c| c.amplitude_m).collect();
    let ratio: Vec<f64> = envelope.cycles.iter().map(|c| c.damping_ratio).collect();
    let rows: Vec<Vec<f64>> = envelope
        .cycles
        .iter()
        .enumerate()
        .map(|(k, c)| {
            vec![
                c.cycle as f64,
                c.time_s,
                c.amplitude_m,
                c.damping_ratio,
                zones.smoothed[k],
                zones.added_fraction[k],
                f64::from(zones.zone(k)),
            ]
        })
        .collect();
    ctx.write_csv(
        name,
        &[
            "cycle",
            "time_s",
            "amplitude_m",
            "damping_ratio",
            "damping_ratio_median5",
            "added_fraction",
            "zone",
        ],
        &rows,
    )?;
    // the zone edges: the amplitudes midway (geometric) between the last cycle of a zone and
    // the first of the next
    let edge = |k: usize| -> f64 {
        match (
            k.checked_sub(1).and_then(|j| amplitude.get(j)),
            amplitude.get(k),
        ) {
            (Some(a), Some(b)) => (a * b).sqrt(),
            (None, Some(b)) => *b,
            (Some(a), None) => *a,
            (None, None) => f64::NAN,
        }
    };
    let edges = [edge(zones.liquid_end), edge(zones.solid_start)];
    let size = ctx.render(
        name,
        &DecayFigure {
            amplitude_m: &amplitude,
            damping_ratio: &ratio,
            primary_damping_ratio: Some(zeta0),
            zone_edges_m: Some(edges),
        },
    )?;
    let count = |z: u8| (0..amplitude.len()).filter(|&k| zones.zone(k) == z).count();
    Ok(FigureRecord {
        name: name.into(),
        caption: format!(
            "DEM, Els's damper under centrifugal load (linear-DEM paper §3.3): 26 steel balls of \
             4 mm in a cylinder (D = 12.5 mm, L = 37 mm, axis along the decay) turning at \
             138 rpm 0.4 m from the axis (ω²r = 8.5 g, Coriolis included), linear \
             spring–dashpot contacts from the steel's yield strength, free decay of the primary \
             (ours: f0 = 20 Hz, M = 0.1 kg, ζ₀ = {zeta0:.4}) from −6.5 mm. Equivalent damping \
             ratio per cycle against its amplitude; zone I (added damping ≥ {LIQUID_FRACTION} \
             of its peak, median of 5 cycles): {} cycles down to {:.2} mm; zone II: {} cycles; \
             zone III (below {SOLID_FRACTION} for good): {} cycles from {:.2} mm, ζ back to the \
             primary's own.",
            count(1),
            edges[0] * 1e3,
            count(2),
            count(3),
            edges[1] * 1e3,
        ),
        spec_item: "linear-DEM paper §3.3: ζ against amplitude, three zones".into(),
        commands: sweep.commands.clone(),
        reductions: Vec::new(),
        size_px: size,
    })
}
