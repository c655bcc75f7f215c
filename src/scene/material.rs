//! `damper.material`: presets of common grain materials for a DEM damper.
//!
//! A preset fills the keys a scene leaves out — `density` (kg/m³), `youngs_modulus` (Pa),
//! `poisson` (–), `friction` (–), `restitution` (–, grain–grain at `restitution_speed`,
//! default 1 m/s; only when the scene gives neither `gamma_n` nor `restitution`) and, for the
//! linear law (`contact = "linear"`), `yield_strength` (Pa). Every key the scene sets itself
//! wins, so a preset is a starting point:
//!
//! ```toml
//! [damper]
//! kind = "dem"
//! material = "glass"     # E, ν, ρ, e, μ of soda-lime glass beads
//! friction = 0.2         # … except the friction, given here
//! ```
//!
//! The elastic constants and densities are handbook values; restitution and friction depend on
//! the impact speed, the surfaces and the alloy, so theirs are typical values for a first
//! estimate — measure or override them for a design.
//!
//! | preset | ρ (kg/m³) | E (Pa) | ν | e | μ | Y (Pa) | sources |
//! |---|---|---|---|---|---|---|---|
//! | `steel` | 8030 | 2.03e11 | 0.28 | 0.90 | 0.30 | 2.35e8 | ρ, E, ν, μ: the thesis's scene B (Sánchez 2012 §3.2); e: hardened steel spheres at ~1 m/s, Goldsmith, *Impact* (1960); Y: ordinary structural carbon steel (S235 / Q235, EN 10025 / GB/T 700 minimum) |
//! | `sus304` | 7930 | 1.93e11 | 0.29 | 0.90 | 0.30 | 2.05e8 | ρ, E, ν: AISI 304 austenitic stainless, ASM Handbook vol. 1; Y: 0.2 % proof stress minimum of SUS304, JIS G 4303; e, μ: as `steel` |
//! | `glass` | 2500 | 6.3e10 | 0.23 | 0.97 | 0.092 | — | ρ, E, ν: soda-lime glass, CRC Handbook of Chemistry and Physics (elastic constants); e, μ: glass spheres, Foerster, Louge, Chang & Allia, Phys. Fluids 6, 1108 (1994); brittle: no yield strength |
//! | `lead` | 11340 | 1.6e10 | 0.44 | 0.20 | 0.50 | 5.5e6 | ρ, E, ν: CRC Handbook (elastic constants of metals); e, μ: typical of a soft, plastically deforming metal (Goldsmith 1960); Y: pure lead, ASM Handbook vol. 2 |
//! | `aluminium` | 2700 | 7.0e10 | 0.33 | 0.70 | 0.40 | 2.76e8 | ρ, E, ν: CRC Handbook; e, μ: typical of aluminium alloys at ~1 m/s (Goldsmith 1960); Y: 6061-T6, ASM Handbook vol. 2 |
//! | `acrylic` | 1190 | 3.2e9 | 0.35 | 0.80 | 0.40 | 7.0e7 | ρ, E, ν, Y: PMMA, Ashby & Jones, *Engineering Materials 1* (tables of density, modulus, yield strength); e, μ: typical of a glassy polymer at ~1 m/s, first estimates |
//!
//! The linear-DEM paper (`../shared/seeds`, §3.1, Saeki's experiment) takes its grains' ρ, E,
//! ν and Y from handbooks as well (its Table 1 is not reproduced in the text we hold).

use serde::{Deserialize, Serialize};

use crate::error::SceneError;

/// A named grain material (`damper.material`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum MaterialPreset {
    /// Stainless steel, the thesis's grains.
    Steel,
    /// Soda-lime glass beads.
    Glass,
    /// Lead shot.
    Lead,
    /// Aluminium alloy.
    #[serde(alias = "aluminum")]
    Aluminium,
    /// SUS304 (AISI 304) austenitic stainless steel.
    Sus304,
    /// Acrylic (PMMA).
    Acrylic,
}

/// The values a preset gives (SI units: kg/m³, Pa, –).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MaterialValues {
    /// Density ρ (kg/m³).
    pub density: f64,
    /// Young's modulus E (Pa).
    pub youngs_modulus: f64,
    /// Poisson ratio ν (–).
    pub poisson: f64,
    /// Grain–grain coefficient of restitution e (–) at 1 m/s.
    pub restitution: f64,
    /// Grain–grain Coulomb friction μ (–).
    pub friction: f64,
    /// Yield strength Y (Pa) for the linear law; `None` for a brittle material.
    pub yield_strength: Option<f64>,
}

impl MaterialPreset {
    /// Every preset, in the order of the table above.
    pub const ALL: [MaterialPreset; 6] = [
        MaterialPreset::Steel,
        MaterialPreset::Sus304,
        MaterialPreset::Glass,
        MaterialPreset::Lead,
        MaterialPreset::Aluminium,
        MaterialPreset::Acrylic,
    ];

    /// The preset's name as written in a scene.
    pub fn name(self) -> &'static str {
        match self {
            MaterialPreset::Steel => "steel",
            MaterialPreset::Glass => "glass",
            MaterialPreset::Lead => "lead",
            MaterialPreset::Aluminium => "aluminium",
            MaterialPreset::Sus304 => "sus304",
            MaterialPreset::Acrylic => "acrylic",
        }
    }

    /// The preset of a name (`aluminum` accepted too).
    pub fn from_name(name: &str) -> Option<MaterialPreset> {
        match name {
            "aluminum" => Some(MaterialPreset::Aluminium),
            _ => Self::ALL.into_iter().find(|m| m.name() == name),
        }
    }

    /// The values of the preset (see the module table for their sources).
    pub fn values(self) -> MaterialValues {
        let (density, youngs_modulus, poisson, restitution, friction, yield_strength) = match self {
            MaterialPreset::Steel => (8030.0, 2.03e11, 0.28, 0.90, 0.30, Some(2.35e8)),
            MaterialPreset::Sus304 => (7930.0, 1.93e11, 0.29, 0.90, 0.30, Some(2.05e8)),
            MaterialPreset::Glass => (2500.0, 6.3e10, 0.23, 0.97, 0.092, None),
            MaterialPreset::Lead => (11340.0, 1.6e10, 0.44, 0.20, 0.50, Some(5.5e6)),
            MaterialPreset::Aluminium => (2700.0, 7.0e10, 0.33, 0.70, 0.40, Some(2.76e8)),
            MaterialPreset::Acrylic => (1190.0, 3.2e9, 0.35, 0.80, 0.40, Some(7.0e7)),
        };
        MaterialValues {
            density,
            youngs_modulus,
            poisson,
            restitution,
            friction,
            yield_strength,
        }
    }
}

/// Fills the keys a DEM damper table leaves out from its `material` preset (module docs).
/// A table without `material`, or of another damper kind, is left as it is (serde then
/// refuses `material` as an unknown key of the other kinds).
///
/// # Errors
/// `damper.material` that is not a string naming a preset.
pub(crate) fn fill_from_preset(damper: &mut toml::Table) -> Result<(), SceneError> {
    if damper.get("kind").and_then(toml::Value::as_str) != Some("dem") {
        return Ok(());
    }
    let Some(value) = damper.get("material") else {
        return Ok(());
    };
    let names = MaterialPreset::ALL.map(MaterialPreset::name).join(", ");
    let preset = value
        .as_str()
        .and_then(MaterialPreset::from_name)
        .ok_or_else(|| {
            SceneError::invalid(
                "damper.material",
                value.to_string(),
                format!("unknown material: use one of {names}, or give density, youngs_modulus, poisson and friction yourself"),
            )
        })?;
    let v = preset.values();
    let mut fill = |key: &str, x: f64| {
        damper
            .entry(key.to_string())
            .or_insert(toml::Value::Float(x));
    };
    fill("density", v.density);
    fill("youngs_modulus", v.youngs_modulus);
    fill("poisson", v.poisson);
    fill("friction", v.friction);
    if !damper.contains_key("gamma_n") {
        damper
            .entry("restitution".to_string())
            .or_insert(toml::Value::Float(v.restitution));
    }
    let linear = damper.get("contact").and_then(toml::Value::as_str) == Some("linear");
    if let (true, Some(y)) = (linear, v.yield_strength) {
        damper
            .entry("yield_strength".to_string())
            .or_insert(toml::Value::Float(y));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(text: &str) -> toml::Table {
        text.parse().unwrap()
    }

    #[test]
    fn fills_only_what_is_missing() {
        let mut d = table("kind = \"dem\"\nmaterial = \"glass\"\nfriction = 0.2\n");
        fill_from_preset(&mut d).unwrap();
        assert_eq!(d["density"].as_float(), Some(2500.0));
        assert_eq!(d["youngs_modulus"].as_float(), Some(6.3e10));
        assert_eq!(d["poisson"].as_float(), Some(0.23));
        assert_eq!(d["restitution"].as_float(), Some(0.97));
        assert_eq!(
            d["friction"].as_float(),
            Some(0.2),
            "the scene's own value wins"
        );
    }

    #[test]
    fn an_explicit_gamma_n_keeps_restitution_out() {
        let mut d = table("kind = \"dem\"\nmaterial = \"steel\"\ngamma_n = 3660.0\n");
        fill_from_preset(&mut d).unwrap();
        assert!(!d.contains_key("restitution"));
    }

    #[test]
    fn unknown_names_are_refused_with_the_list() {
        let mut d = table("kind = \"dem\"\nmaterial = \"granite\"\n");
        let e = fill_from_preset(&mut d).unwrap_err().to_string();
        assert!(
            e.contains("damper.material") && e.contains("aluminium"),
            "{e}"
        );
    }

    #[test]
    fn names_round_trip() {
        for m in MaterialPreset::ALL {
            assert_eq!(MaterialPreset::from_name(m.name()), Some(m));
        }
        assert_eq!(
            MaterialPreset::from_name("aluminum"),
            Some(MaterialPreset::Aluminium)
        );
    }
}
