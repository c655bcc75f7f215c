//! `damper.material` presets (issue 15): a user's own damper — 500 glass beads of 2 mm in a
//! 40 × 40 × 60 mm box — from the preset alone, its keys overridable, and the derived
//! Kuwabara–Kono damping reproducing the preset's restitution in a simulated collision.

mod scratch;

use pdamp::scene::material::MaterialPreset;
use pdamp::scene::{Damper, Scene};

const BEADS: &str = r#"
[primary]
mass = 2.37
stiffness = 21500.0
damping = 7.6

[excitation]
amplitude = 0.0045
frequency = 15.0

[damper]
kind = "dem"
material = "glass"
box = [0.04, 0.04, 0.06]
count = 500
radius = 0.001

[run]
duration = 0.05
"#;

fn dem(scene: &Scene) -> &pdamp::scene::dem::DemParams {
    match &scene.damper {
        Damper::Dem(d) => d,
        other => panic!("not a DEM damper: {other:?}"),
    }
}

#[test]
fn the_glass_preset_fills_every_material_key() {
    let scene = Scene::from_toml(BEADS).unwrap();
    let d = dem(&scene);
    let v = MaterialPreset::Glass.values();
    assert_eq!(d.material, Some(MaterialPreset::Glass));
    assert_eq!(
        (
            d.density,
            d.youngs_modulus,
            d.poisson,
            d.friction,
            d.restitution
        ),
        (
            v.density,
            v.youngs_modulus,
            v.poisson,
            v.friction,
            Some(v.restitution)
        )
    );
    // γ_n comes from e; γ_s = 3 γ_n so that the friction acts
    let gn = pdamp::setup::dem::hertz_kk_gamma_n(d, false).unwrap();
    let gs = pdamp::setup::dem::hertz_kk_gamma_s(d, false).unwrap();
    assert!(
        gn > 0.0 && (gs / gn - 3.0).abs() < 1e-12,
        "γ_n {gn}, γ_s {gs}"
    );
    // the scene stored next to results parses back to the same scene
    let again = Scene::from_toml(&scene.to_toml().unwrap()).unwrap();
    assert_eq!(dem(&again), d);
}

#[test]
fn keys_of_the_scene_and_set_overrides_win_over_the_preset() {
    let text = BEADS.replace("radius = 0.001", "radius = 0.001\nfriction = 0.25");
    let d = Scene::from_toml(&text).unwrap();
    assert_eq!(dem(&d).friction, 0.25);
    let src = pdamp::scene::overrides::SceneSource::parse(BEADS).unwrap();
    let lead = src
        .scene(&[
            ("damper.material".into(), toml::Value::String("lead".into())),
            ("damper.density".into(), toml::Value::Float(11000.0)),
        ])
        .unwrap();
    let d = dem(&lead);
    assert_eq!(d.density, 11000.0);
    assert_eq!(
        d.youngs_modulus,
        MaterialPreset::Lead.values().youngs_modulus
    );
}

#[test]
fn an_unknown_material_is_refused_naming_the_key_and_the_choices() {
    let e = Scene::from_toml(&BEADS.replace("\"glass\"", "\"granite\""))
        .unwrap_err()
        .to_string();
    assert!(e.contains("damper.material") && e.contains("steel"), "{e}");
}

/// Independent check of the derived γ_n: a head-on grain–grain collision at the reference
/// speed (1 m/s) integrated with the contact law's own force, against the preset's e.
#[test]
fn a_collision_at_1_m_per_s_has_the_presets_restitution() {
    for m in MaterialPreset::ALL {
        let text = BEADS.replace("\"glass\"", &format!("\"{}\"", m.name()));
        let scene = Scene::from_toml(&text).unwrap();
        let d = dem(&scene);
        let gamma_n = pdamp::setup::dem::hertz_kk_gamma_n(d, false).unwrap();
        let r = 0.001;
        let mass = d.density * 4.0 / 3.0 * std::f64::consts::PI * r * r * r;
        // two equal spheres: R* = r/2, m* = m/2, 1/E* = 2 (1 − ν²)/E
        let e_star = d.youngs_modulus / (2.0 * (1.0 - d.poisson * d.poisson));
        let k = 4.0 / 3.0 * e_star * (r / 2.0_f64).sqrt();
        let m_star = mass / 2.0;
        // relative coordinate: m* ξ'' = −k ξ^{3/2} − γ_n ξ^{1/2} ξ', force clamped ≥ 0
        let (mut xi, mut v) = (0.0_f64, 1.0_f64);
        let t_s = 3.21 * (m_star / k).powf(0.4) * 1.0_f64.powf(-0.2);
        let dt = t_s / 200_000.0;
        let acc = |xi: f64, v: f64| -> f64 {
            let xi = xi.max(0.0);
            -(k * xi.powf(1.5) + gamma_n * xi.sqrt() * v).max(0.0) / m_star
        };
        loop {
            // classical RK4 on (ξ, v)
            let (k1x, k1v) = (v, acc(xi, v));
            let (k2x, k2v) = (
                v + 0.5 * dt * k1v,
                acc(xi + 0.5 * dt * k1x, v + 0.5 * dt * k1v),
            );
            let (k3x, k3v) = (
                v + 0.5 * dt * k2v,
                acc(xi + 0.5 * dt * k2x, v + 0.5 * dt * k2v),
            );
            let (k4x, k4v) = (v + dt * k3v, acc(xi + dt * k3x, v + dt * k3v));
            xi += dt / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
            v += dt / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
            if xi < 0.0 {
                break;
            }
        }
        let e = -v;
        let want = m.values().restitution;
        assert!(
            (e - want).abs() < 2e-3,
            "{}: e = {e}, preset {want}",
            m.name()
        );
    }
}

#[test]
fn check_scene_prints_the_material_and_the_derived_damping() {
    let dir = scratch::tempdir().unwrap();
    let f = dir.path().join("beads.toml");
    std::fs::write(&f, BEADS).unwrap();
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_pdamp"))
        .arg("check-scene")
        .arg(&f)
        .output()
        .unwrap();
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(out.contains("material glass"), "{out}");
    assert!(out.contains("from e = 0.97"), "{out}");
    assert!(out.contains("γ_s ="), "{out}");
}

/// `mass` instead of `count` (issue 41, Saeki's materials at one mass ratio): the count is
/// round(mass / (ρ 4/3 π R³)) of the preset's density, so that a material change keeps the
/// grain mass; both keys must agree; a mass without a single radius is refused by name.
#[test]
fn a_grain_mass_gives_the_count_of_each_material() {
    let by_mass = |material: &str, extra: &str| {
        Scene::from_toml(&BEADS.replace(
            "material = \"glass\"\nbox = [0.04, 0.04, 0.06]\ncount = 500\nradius = 0.001",
            &format!(
                "material = \"{material}\"\nbox = [0.058, 0.038, 0.038]\nradius = 0.003\nmass = 0.026956\n{extra}"
            ),
        ))
    };
    let grain = |rho: f64| rho * 4.0 / 3.0 * std::f64::consts::PI * 0.003f64.powi(3);
    for (m, rho, want) in [
        ("lead", 11340.0, 21),
        ("sus304", 7930.0, 30),
        ("steel", 8030.0, 30),
        ("acrylic", 1190.0, 200),
    ] {
        let s = by_mass(m, "").unwrap();
        let d = dem(&s);
        assert_eq!(d.count, want, "{m}");
        // the nearest whole number of grains: within half a grain of the mass
        assert!((d.count as f64 * grain(rho) - 0.026956).abs() <= 0.5 * grain(rho));
        // saved and read again: count and mass agree
        assert_eq!(Scene::from_toml(&s.to_toml().unwrap()).unwrap(), s);
    }
    let e = by_mass("steel", "count = 40").unwrap_err().to_string();
    assert!(e.contains("damper.mass") && e.contains("count"), "{e}");
    let e = Scene::from_toml(&BEADS.replace(
        "count = 500\nradius = 0.001",
        "mass = 0.01\nradius_min = 0.001\nradius_max = 0.002",
    ))
    .unwrap_err()
    .to_string();
    assert!(e.contains("damper.mass"), "{e}");
    let e = by_mass("steel", "")
        .map(|_| ())
        .and(Scene::from_toml(&BEADS.replace("count = 500", "mass = -1.0")).map(|_| ()));
    assert!(e.unwrap_err().to_string().contains("damper.mass"));
}

/// The linear law takes its stiffness from the yield strength: the presets fill it for
/// `contact = "linear"` only (a Hertz scene is left as it was).
#[test]
fn presets_fill_the_yield_strength_of_the_linear_law_only() {
    let linear = Scene::from_toml(&BEADS.replace(
        "material = \"glass\"",
        "material = \"sus304\"\ncontact = \"linear\"",
    ))
    .unwrap();
    assert_eq!(dem(&linear).yield_strength, Some(2.05e8));
    let hertz =
        Scene::from_toml(&BEADS.replace("material = \"glass\"", "material = \"sus304\"")).unwrap();
    assert_eq!(dem(&hertz).yield_strength, None);
}
