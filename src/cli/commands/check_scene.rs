//! `pdamp check-scene SCENE [--set key=value …]`: validate a scene without running it and print
//! its derived quantities — exactly the checks `pdamp simulate` runs before it starts
//! (resolve, time-step guard, packing, step/sample/snapshot bounds, output size).

use pdamp::scene::{Damper, DriveKind};
use std::path::PathBuf;

/// Arguments of `pdamp check-scene`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Scene file (TOML).
    pub scene: PathBuf,
    /// Override a scene key, dotted (as in `simulate`). Repeatable.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Largest output (bytes) `simulate` may write (as in `simulate`).
    #[arg(long, value_name = "BYTES", default_value_t = pdamp::setup::plan::DEFAULT_MAX_OUTPUT_BYTES)]
    pub max_output: f64,
}

/// Run `pdamp check-scene`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let (_, _, scene) = super::simulate::load_scene(&args.scene, &args.set)?;
    // the resolve step checks what validation alone cannot (e.g. run.dt against the contact
    // time) and makes the `kind = "auto"` choice
    let resolved = scene.resolve()?;
    let plan = super::simulate::plan_full_run(&resolved, args.max_output)?;
    let f = scene.frequency_hz();
    let omega = scene.excitation.omega_rad_s();
    println!("{}: valid", args.scene.display());
    match &scene.primary {
        Some(p) => println!(
            "primary: M = {} kg, K = {} N/m, C = {:.6} N s/m, ξ = {:.6}, f0 = {:.6} Hz",
            p.mass,
            p.stiffness,
            p.damping_n_s_m(),
            p.damping_ratio(),
            p.natural_frequency_hz()
        ),
        None => println!("primary: none (container moves with the base)"),
    }
    let g = scene.gravity_vector();
    let g_abs = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
    let gamma = if g_abs > 0.0 {
        format!("{:.6}", scene.excitation.amplitude * omega * omega / g_abs)
    } else {
        "inf (g = 0)".into()
    };
    let e = &scene.excitation;
    let drive = match e.kind {
        DriveKind::Base => format!(
            "base, U = {} m, f = {f} Hz, Γ = UΩ²/g = {gamma}",
            e.amplitude
        ),
        DriveKind::Force => format!(
            "force F0 sin(2π f t), F0 = {} N, f = {f} Hz{}",
            e.force_n(),
            scene
                .primary
                .as_ref()
                .map(|p| format!(
                    ", primary alone: Z = {:.6e} m",
                    p.system().force_amplitude_m(e.force_n(), omega)
                ))
                .unwrap_or_default()
        ),
        DriveKind::Free => {
            let p = scene.primary.as_ref();
            format!(
                "free decay from z0 = {} m, v0 = {} m/s (clock f = {f} Hz)",
                p.and_then(|p| p.initial_displacement).unwrap_or(0.0),
                p.and_then(|p| p.initial_velocity).unwrap_or(0.0)
            )
        }
    };
    println!(
        "excitation: {drive}, along {:?}, gravity {g:?} m/s²; run: {:.6} s ({:.1} periods), steady from {:.6} s",
        e.unit_direction(),
        scene.duration_s(),
        scene.duration_s() * f,
        scene.steady_start_s()
    );
    match &scene.damper {
        Damper::None => println!("damper: none"),
        Damper::Impact(p) => println!(
            "damper: impact, m_p = {} kg, gap = {} m, e = {}",
            p.mass, p.gap, p.restitution
        ),
        Damper::Dem(d) => {
            match d.container_shape() {
                pdamp::model::Container::Box => {
                    println!("damper: dem, {} grains, box {:?} m", d.count, d.r#box)
                }
                pdamp::model::Container::Cylinder(c) => println!(
                    "damper: dem, {} grains, cylinder D = {} m, L = {} m along {} (box {:?} m)",
                    d.count,
                    2.0 * c.radius_m,
                    c.length_m,
                    ["x", "y", "z"][c.axis],
                    d.r#box
                ),
            }
            println!(
                "grains: {}ρ = {} kg/m³, E = {:e} Pa, ν = {}, μ = {}",
                d.material
                    .map(|m| format!("material {} (keys not in the scene), ", m.name()))
                    .unwrap_or_default(),
                d.density,
                d.youngs_modulus,
                d.poisson,
                d.friction
            );
            if d.contact == pdamp::scene::dem::ContactKind::HertzKk {
                let gamma = |wall| pdamp::setup::dem::hertz_kk_gamma_n(d, wall);
                println!(
                    "contact: hertz-kk, γ_n = {:.6e} (grain–grain), {:.6e} (grain–wall) kg s⁻¹ m^-1/2{}",
                    gamma(false)?,
                    gamma(true)?,
                    match d.restitution {
                        Some(e) => format!(
                            " — from e = {e} at {} m/s",
                            d.restitution_speed
                                .unwrap_or(pdamp::setup::dem::DEFAULT_RESTITUTION_SPEED)
                        ),
                        None => String::new(),
                    }
                );
                let gamma_s = |wall| pdamp::setup::dem::hertz_kk_gamma_s(d, wall);
                println!(
                    "tangential: γ_s = {:.6e} (grain–grain), {:.6e} (grain–wall) kg s⁻¹ m^-1/2",
                    gamma_s(false)?,
                    gamma_s(true)?
                );
            }
        }
        Damper::Auto(_) => {
            if let Some(c) = &resolved.auto {
                println!("damper: {}", pdamp::choice::auto::describe(c));
            }
        }
    }
    println!("plan: {}", plan.describe());
    Ok(())
}
