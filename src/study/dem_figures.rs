//! The DEM part of the figure set (scene B with N spheres, SPEC §2): FRF, collision versus
//! friction energy, Z_res and energy versus Lz for several N, M_ef and C_ef versus Lz,
//! Z_res versus γ_n for several N, and the bed motion.

use crate::error::{SimError, StudyError};
use crate::model::RunOptions;
use crate::observe::NullObserver;
use crate::plot::energy::{energy_figure, energy_label};
use crate::plot::resonance::resonance_figure;
use crate::plot::Series;
use crate::scene::keys::{
    DAMPER_BOX, DAMPER_COUNT, DAMPER_GAMMA_N, DAMPER_GAMMA_S, DAMPER_RADIUS, DAMPER_YOUNGS_MODULUS,
    EXCITATION_FREQUENCY, RUN_DT_FRACTION, RUN_DURATION,
};
use crate::sweep::SweepPoints;

use super::check::EffectiveRow;
use super::command::Command;
use super::kit::{
    draw_bed_motion, draw_effective, effective_commands, fit_groups, lines, resonance_curve,
};
use super::pipeline::{
    record_run, scene_with, simulate_command, Ctx, FigureRecord, SweepResult, DEM_B,
};
use super::settings::{DemSettings, Settings};

/// Scene B's Lz (m) for the FRF, energy, γ_n and bed-motion figures.
const LZ_B: f64 = 0.1225;
/// Scene B's grain number and radius (m).
const N_B: usize = 250;
const R_B: f64 = 0.003;
/// Scene B's grain damping γ_n, γ_s (kg s⁻¹ m^-1/2) and Young's modulus (Pa), real steel.
pub(super) const GAMMA_N_B: f64 = 3660.0;
pub(super) const GAMMA_S_B: f64 = 10980.0;
pub(super) const E_B: f64 = 2.03e11;

/// Names of the DEM figures (besides the DEM curve in `frf`).
pub const NAMES: [&str; 7] = [
    "energy_vs_frequency_dem",
    "zres_vs_lz_dem",
    "energy_vs_lz_dem",
    "effective_dem",
    "zres_vs_gamma_dem",
    "bed_motion_dem",
    "dem",
];

/// What the DEM figures produced.
#[derive(Debug, Clone)]
pub struct DemOutput {
    /// The figures.
    pub figures: Vec<FigureRecord>,
    /// Fits per container height (N = 250).
    pub effective: Vec<EffectiveRow>,
    /// The FRF sweep (drawn with the impact model's in `frf.png`).
    pub frf: SweepResult,
}

/// `Ok` if the DEM model runs in this build (a 4-grain, 10 ms run), else the reason.
///
/// # Errors
/// The simulator's message (e.g. [`SimError::Unavailable`]).
pub fn available() -> Result<(), String> {
    let set = [
        (DAMPER_COUNT, "4".to_string()),
        (RUN_DURATION, "0.01".to_string()),
        (DAMPER_YOUNGS_MODULUS, "2.03e8".to_string()),
    ];
    let scene = scene_with("dem check", DEM_B, &set).map_err(|e| e.to_string())?;
    match crate::sweep::run_scene(&scene, &mut NullObserver, &RunOptions::summary_only()) {
        Ok(_) => Ok(()),
        Err(SimError::Unavailable(m)) => Err(m),
        Err(e) => Err(format!("the DEM check run failed: {e}")),
    }
}

/// `--set` of scene B's steel softened by `soften`: E/soften, γ_n and γ_s × soften^-3/5 (the
/// rule of [`crate::scene::dem::DemParams::softened`], which keeps e(v)).
pub(super) fn softened_steel_set(soften: f64) -> Vec<(&'static str, String)> {
    let g = crate::scene::dem::softening_damping_scale(soften);
    vec![
        (DAMPER_YOUNGS_MODULUS, (E_B / soften).to_string()),
        (DAMPER_GAMMA_N, (GAMMA_N_B * g).to_string()),
        (DAMPER_GAMMA_S, (GAMMA_S_B * g).to_string()),
    ]
}

/// The material and run overrides of the mode (softening, time step, duration).
fn base_set(d: &DemSettings, duration_s: f64) -> Vec<(&'static str, String)> {
    let mut set = softened_steel_set(d.soften);
    set.push((RUN_DT_FRACTION, d.dt_fraction.to_string()));
    set.push((RUN_DURATION, duration_s.to_string()));
    set
}

/// `--set` for N grains at scene B's total grain mass: R = R_B (N_B/N)^(1/3).
fn count_set(n: usize, lz: f64) -> Vec<(&'static str, String)> {
    let r = R_B * (N_B as f64 / n as f64).cbrt();
    vec![
        (DAMPER_COUNT, n.to_string()),
        (DAMPER_RADIUS, format!("{r:.6}")),
        (DAMPER_BOX, format!("[0.03675,0.03675,{lz}]")),
    ]
}

/// Runs every DEM sweep and draws the DEM figures.
///
/// # Errors
/// [`StudyError`] naming the sweep or figure that failed.
pub fn all(ctx: &Ctx, s: &Settings, d: &DemSettings) -> Result<DemOutput, StudyError> {
    let mut figures = Vec::new();
    let red = |keys: &[&str]| s.reductions(keys);

    // FRF and energy split at scene B's Lz
    let mut set = base_set(d, d.duration_s);
    set.extend(count_set(N_B, LZ_B));
    let frf = ctx.sweep(
        "dem_frf_n250",
        DEM_B,
        &set,
        &[(EXCITATION_FREQUENCY, d.freq.vary())],
        false,
    )?;
    figures.push(energy_vs_frequency(ctx, &frf, red(&["dem"]))?);

    // Lz × N around the resonance
    let mut per_n: Vec<(usize, Vec<(f64, SweepResult)>)> = Vec::new();
    for &n in &d.counts {
        let mut v = Vec::new();
        for &lz in &d.heights_m {
            let mut set = base_set(d, d.duration_s);
            set.extend(count_set(n, lz));
            let sw = ctx.sweep(
                &format!("dem_lz_n{n}_lz{lz}"),
                DEM_B,
                &set,
                &[(EXCITATION_FREQUENCY, d.res_freq.vary())],
                false,
            )?;
            v.push((lz, sw));
        }
        per_n.push((n, v));
    }
    let mut keys = vec!["dem", "dem_res", "dem_lz", "dem_n"];
    figures.extend(zres_energy_vs_lz(ctx, &per_n, red(&keys))?);
    let effective = effective_vs_lz(ctx, &per_n)?;
    let (rec_eff, rows) = effective;
    figures.push(FigureRecord {
        reductions: red(&["dem", "dem_res", "dem_lz"]),
        ..rec_eff
    });

    // γ_n × N at scene B's Lz
    let mut gamma_curves = Vec::new();
    for &n in &d.counts {
        let mut set = base_set(d, d.duration_s);
        set.extend(count_set(n, LZ_B));
        let g = crate::scene::dem::softening_damping_scale(d.soften);
        let values: Vec<String> = d.gamma_n.iter().map(|x| (x * g).to_string()).collect();
        let sw = ctx.sweep(
            &format!("dem_gamma_n{n}"),
            DEM_B,
            &set,
            &[
                (DAMPER_GAMMA_N, values.join(",")),
                (EXCITATION_FREQUENCY, d.res_freq.vary()),
            ],
            false,
        )?;
        gamma_curves.push((n, sw));
    }
    keys.push("dem_gamma");
    figures.push(zres_vs_gamma(ctx, d, &gamma_curves, red(&keys))?);

    // bed motion at 15 Hz
    figures.push(bed_motion(ctx, d, red(&["dem", "dem_bed"]))?);
    Ok(DemOutput {
        figures,
        effective: rows,
        frf,
    })
}

fn energy_vs_frequency(
    ctx: &Ctx,
    sw: &SweepResult,
    reductions: Vec<String>,
) -> Result<FigureRecord, StudyError> {
    let name = "energy_vs_frequency_dem";
    let f = sw.points.map(|s| s.frequency_hz);
    // the input (base work), the primary's viscous loss, then the grains' own (collision,
    // friction …): in a steady state the input is the sum of the others
    let mut cols = vec![
        "energy_input_j_per_cycle".to_string(),
        "energy_viscous_j_per_cycle".to_string(),
    ];
    cols.extend(grain_energy_keys(&sw.points));
    let mut values = vec![
        sw.points.map(|s| s.energy_input_j_per_cycle),
        sw.points.map(|s| s.energy_viscous_j_per_cycle),
    ];
    for c in &cols[2..] {
        values.push(extra_values(name, &sw.points, c)?);
    }
    let mut header = vec!["frequency_hz"];
    header.extend(cols.iter().map(|c| c.as_str()));
    let rows: Vec<Vec<f64>> = (0..f.len())
        .map(|i| {
            let mut r = vec![f[i]];
            r.extend(values.iter().map(|v| v[i]));
            r
        })
        .collect();
    ctx.write_csv(name, &header, &rows)?;
    let labels: Vec<String> = cols.iter().map(|c| energy_label(c)).collect();
    let pairs: Vec<(&str, &[f64])> = labels
        .iter()
        .zip(&values)
        .map(|(c, v)| (c.as_str(), v.as_slice()))
        .collect();
    let size = ctx.render(name, &energy_figure(&f, "frequency f (Hz)", &pairs))?;
    Ok(FigureRecord {
        name: name.into(),
        caption: "DEM, scene B (N = 250, Lz = 0.1225 m): energy put in per forcing cycle by the \
                  base, and dissipated by collisions (normal damping), friction (tangential) and \
                  the primary's damper C, versus frequency."
            .into(),
        spec_item: "collision vs friction energy per cycle versus f".into(),
        commands: sw.commands_then_plot("energy", &ctx.path(&format!("{name}.png"))),
        reductions,
        size_px: size,
    })
}

/// The DEM's own dissipation entries (collision, friction …) of the points' summaries: every
/// model-specific `energy_*_j_per_cycle`, by name.
fn grain_energy_keys(pts: &SweepPoints) -> Vec<String> {
    let keys: std::collections::BTreeSet<&str> = pts
        .iter()
        .filter_map(|p| p.summary.dem.as_ref())
        .flat_map(|d| d.dissipation_j_per_cycle())
        .filter(|(_, v)| !v.is_nan())
        .map(|(k, _)| k)
        .collect();
    keys.into_iter().map(String::from).collect()
}

/// Model-specific summary entry `key` of every point, or a study error naming the point.
fn extra_values(name: &str, pts: &SweepPoints, key: &str) -> Result<Vec<f64>, StudyError> {
    pts.iter()
        .map(|p| {
            p.summary
                .dem
                .as_ref()
                .and_then(|d| {
                    d.dissipation_j_per_cycle()
                        .into_iter()
                        .find_map(|(k, v)| (k == key).then_some(v))
                })
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    StudyError::step(name, format!("{}: point {}: no `{key}`", pts.dir, p.index))
                })
        })
        .collect()
}

/// The grains' dissipation per cycle (collision + friction …) of every point.
fn grain_dissipation(name: &str, sw: &SweepResult) -> Result<Vec<f64>, StudyError> {
    let mut total = vec![0.0; sw.points.len()];
    for c in grain_energy_keys(&sw.points) {
        for (t, v) in total.iter_mut().zip(extra_values(name, &sw.points, &c)?) {
            *t += v;
        }
    }
    Ok(total)
}

fn zres_energy_vs_lz(
    ctx: &Ctx,
    per_n: &[(usize, Vec<(f64, SweepResult)>)],
    reductions: Vec<String>,
) -> Result<Vec<FigureRecord>, StudyError> {
    let name = "zres_vs_lz_dem";
    let mut curves = Vec::new();
    let mut rows = Vec::new();
    for (n, v) in per_n {
        let (mut xs, mut zs, mut es) = (vec![], vec![], vec![]);
        for (lz, sw) in v {
            let z = sw.points.map(|s| s.amplitude_m);
            let e = grain_dissipation(name, sw)?;
            let i = (0..z.len())
                .max_by(|&a, &b| z[a].total_cmp(&z[b]))
                .unwrap_or(0);
            xs.push(*lz);
            zs.push(z[i]);
            es.push(e[i]);
            rows.push(vec![*n as f64, *lz, z[i], e[i]]);
        }
        curves.push((format!("N = {n}"), xs, zs, es));
    }
    ctx.write_csv(
        name,
        &[
            "count",
            "lz_m",
            "zres_m",
            "energy_grains_j_per_cycle_at_resonance",
        ],
        &rows,
    )?;
    // every length drawn in mm (Lz like the amplitude)
    let lz_mm: Vec<Vec<f64>> = curves
        .iter()
        .map(|(_, x, _, _)| super::impact_gap::to_mm(x))
        .collect();
    let series = curves
        .iter()
        .zip(&lz_mm)
        .map(|((l, _, z, _), x)| Series { label: l, x, y: z })
        .collect();
    let size = ctx.render(name, &resonance_figure(series, "container height Lz (mm)"))?;
    let ename = "energy_vs_lz_dem";
    ctx.write_csv(
        ename,
        &[
            "count",
            "lz_m",
            "zres_m",
            "energy_grains_j_per_cycle_at_resonance",
        ],
        &rows,
    )?;
    let series: Vec<Series> = curves
        .iter()
        .zip(&lz_mm)
        .map(|((l, _, _, e), x)| Series { label: l, x, y: e })
        .collect();
    let esize = ctx.render(
        ename,
        &lines(
            series,
            "container height Lz (mm)",
            "energy dissipated by the grains per cycle at resonance (J)",
            1.0,
            "Grain dissipation per cycle at the resonance versus Lz",
        ),
    )?;
    // one sweep per (N, Lz)
    let commands: Vec<Command> = per_n
        .iter()
        .flat_map(|(_, v)| v.iter().flat_map(|(_, s)| s.commands.iter().cloned()))
        .collect();
    ctx.write_text(
        "zres_vs_lz_dem.commands.txt",
        &commands
            .iter()
            .map(|c| format!("{c}\n"))
            .collect::<String>(),
    )?;
    let rec = FigureRecord {
        name: name.into(),
        caption: "DEM, scene B: resonance amplitude Z_res (largest Z over the frequencies near \
                  resonance) versus container height Lz for several N at the same total grain \
                  mass."
            .into(),
        spec_item: "Z_res versus Lz for several N".into(),
        commands: commands.clone(),
        reductions: reductions.clone(),
        size_px: size,
    };
    let energy = FigureRecord {
        name: ename.into(),
        caption: "DEM, scene B: energy dissipated by the grains (collision + friction) per \
                  cycle at the resonance versus Lz for several N."
            .into(),
        spec_item: "energy dissipated per cycle versus Lz for several N".into(),
        commands,
        reductions,
        size_px: esize,
    };
    Ok(vec![rec, energy])
}

fn effective_vs_lz(
    ctx: &Ctx,
    per_n: &[(usize, Vec<(f64, SweepResult)>)],
) -> Result<(FigureRecord, Vec<EffectiveRow>), StudyError> {
    let name = "effective_dem";
    let (n, v) = per_n
        .iter()
        .find(|(n, _)| *n == N_B)
        .or_else(|| per_n.first())
        .ok_or_else(|| StudyError::step(name, "no DEM sweeps"))?;
    let mut rows = Vec::new();
    for (lz, sw) in v {
        let fit = fit_groups(name, &sw.points, None)?;
        if let Some(f) = fit.first() {
            rows.push(EffectiveRow { x_m: *lz, ..*f });
        }
    }
    let size = draw_effective(ctx, name, &rows, "container height Lz (m)", "lz_m")?;
    Ok((
        FigureRecord {
            name: name.into(),
            caption: format!(
                "DEM, scene B (N = {n}): effective mass and damping of fits of (2.1.21) to the \
                 FRF near resonance, versus container height Lz, with standard errors."
            ),
            spec_item: "effective damping C_ef/C and effective mass M_ef versus Lz".into(),
            commands: [
                v.iter().flat_map(|(_, sw)| sw.commands.clone()).collect(),
                effective_commands(
                    ctx,
                    name,
                    &v.iter()
                        .flat_map(|(_, sw)| sw.csv.clone())
                        .collect::<Vec<_>>(),
                    "lz_m",
                ),
            ]
            .concat(),
            reductions: vec![],
            size_px: size,
        },
        rows,
    ))
}

fn zres_vs_gamma(
    ctx: &Ctx,
    d: &DemSettings,
    curves: &[(usize, SweepResult)],
    reductions: Vec<String>,
) -> Result<FigureRecord, StudyError> {
    let name = "zres_vs_gamma_dem";
    let g = crate::scene::dem::softening_damping_scale(d.soften);
    let mut data = Vec::new();
    let mut rows = Vec::new();
    for (n, sw) in curves {
        // γ_n of the softened runs, given as its real-steel equivalent
        let (xs, zs) = resonance_curve(name, &sw.points, DAMPER_GAMMA_N)?;
        let xs: Vec<f64> = xs.into_iter().map(|x| x / g).collect();
        for (x, z) in xs.iter().zip(&zs) {
            rows.push(vec![*n as f64, *x, *z]);
        }
        data.push((format!("N = {n}"), xs, zs));
    }
    ctx.write_csv(name, &["count", "gamma_n", "zres_m"], &rows)?;
    let series = data
        .iter()
        .map(|(l, x, y)| Series { label: l, x, y })
        .collect();
    let size = ctx.render(
        name,
        &resonance_figure(
            series,
            "normal damping γ_n (kg s⁻¹ m^-1/2, steel-equivalent)",
        ),
    )?;
    Ok(FigureRecord {
        name: name.into(),
        caption: "DEM, scene B (Lz = 0.1225 m): resonance amplitude versus the Kuwabara–Kono \
                  normal damping γ_n (γ_s fixed) for several N at the same grain mass; γ_n is \
                  given as its real-steel equivalent (the softened runs use γ_n × soften^-0.6)."
            .into(),
        spec_item: "Z_res versus γ_n, γ_s for several N".into(),
        commands: curves
            .iter()
            .flat_map(|(_, s)| s.commands.clone())
            .collect(),
        reductions,
        size_px: size,
    })
}

fn bed_motion(
    ctx: &Ctx,
    d: &DemSettings,
    reductions: Vec<String>,
) -> Result<FigureRecord, StudyError> {
    let name = "bed_motion_dem";
    let f = 15.0;
    let mut set = base_set(d, d.bed_duration_s);
    set.extend(count_set(N_B, LZ_B));
    set.push((EXCITATION_FREQUENCY, f.to_string()));
    let scene = scene_with(name, DEM_B, &set)?;
    let from = (d.bed_duration_s - 4.0 / f).max(0.0);
    let r = record_run(name, &scene, 2e-4, from)?;
    let size = draw_bed_motion(ctx, name, &r)?;
    Ok(FigureRecord {
        name: name.into(),
        caption: format!(
            "DEM, scene B (N = 250, Lz = 0.1225 m) at 15 Hz, last 4 periods of {} s: floor and \
             ceiling, the band between the lowest and highest grain, the centre of mass z_cm and \
             the grains' vertical force on the box F_gz.",
            d.bed_duration_s
        ),
        spec_item: "bed motion (floor and ceiling, grain band, centre of mass, grain force)".into(),
        commands: vec![
            simulate_command(DEM_B, &set, &ctx.path("data/bed_motion_dem")),
            Command::plot(
                "bed-motion",
                &[ctx.path("data/bed_motion_dem/series.csv")],
                &ctx.path(&format!("{name}.png")),
            )
            .opt("from-time", from),
        ],
        reductions,
        size_px: size,
    })
}
