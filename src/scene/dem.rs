//! `[damper] kind = "dem"`: parameters of the granular (DEM) damper (SPEC §2, §5).
//!
//! This is the contract between the scene format and the DEM simulator. Every key keeps the
//! name of the issue and documents its unit; [`DemParams::validate`] checks every constraint
//! once and names the offending key in its error.
//!
//! ```toml
//! [damper]
//! kind = "dem"
//! box = [0.03675, 0.03675, 0.1225]  # m: Lx, Ly, Lz
//! count = 250
//! radius = 0.003                    # m (or radius_min / radius_max, or radius_distribution)
//! density = 8030.0                  # kg/m³
//! youngs_modulus = 2.03e11          # Pa
//! poisson = 0.28
//! friction = 0.3
//! gamma_n = 3660.0                  # kg s⁻¹ m^-1/2 (Kuwabara–Kono normal damping)
//! gamma_s = 10980.0                 # kg s⁻¹ m^-1/2 (tangential damping)
//! contact = "hertz-kk"              # or "linear" (needs restitution, yield_strength)
//! tangential = "coulomb-viscous"    # or "mindlin" (hertz-kk) / "linear-spring" (linear)
//! ```

use serde::{Deserialize, Serialize};

use crate::contact::material::Material;

pub mod bag;
pub(crate) mod container;
mod validate;

/// Contact law family of the scene (`damper.contact`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum ContactKind {
    /// Hertz + Kuwabara–Kono normal force, Coulomb–viscous tangential force (2.2.8–2.2.15).
    #[default]
    #[serde(rename = "hertz-kk", alias = "hertz_kuwabara_kono")]
    HertzKk,
    /// Linear spring–dashpot with the seed paper's parameter selection.
    #[serde(rename = "linear", alias = "linear_spring_dashpot")]
    Linear,
}

/// Tangential contact law (`damper.tangential`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum TangentialKind {
    /// The thesis's simplified Coulomb law, history-free: −min(γ_s |v_s| √ζ, μ|F_n|) v̂_s
    /// (`hertz-kk`), or −min(c_s |v_s|, μ|F_n|) v̂_s (`linear`).
    #[default]
    #[serde(rename = "coulomb-viscous", alias = "coulomb_viscous")]
    CoulombViscous,
    /// Mindlin (Hertz) tangential spring k_t = 8 G* √(R* ζ) with per-contact history, damping
    /// γ_s √ζ, Coulomb cap μ|F_n| with the spring reset while sliding (`hertz-kk` only).
    #[serde(rename = "mindlin")]
    Mindlin,
    /// Linear tangential spring k_s = γ k_n with history, the linear law's c_s, Coulomb cap
    /// (`linear` only).
    #[serde(rename = "linear-spring", alias = "linear_spring")]
    LinearSpring,
}

/// Shape of the cavity (`damper.container`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ContainerKind {
    /// A rectangular box of inner size `box`.
    #[default]
    Box,
    /// A circular cylinder of inner `diameter` and `length` along `axis`.
    Cylinder,
}

impl ContainerKind {
    /// True for the default (left out of saved scenes).
    pub fn is_box(&self) -> bool {
        *self == ContainerKind::Box
    }
}

/// A coordinate axis (`damper.axis`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum AxisName {
    /// x
    X,
    /// y
    Y,
    /// z
    Z,
}

impl AxisName {
    /// 0, 1 or 2.
    pub fn index(self) -> usize {
        match self {
            AxisName::X => 0,
            AxisName::Y => 1,
            AxisName::Z => 2,
        }
    }
}

/// How the initial bed is built (`damper.packing`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum PackingKind {
    /// Grains dropped from an FCC lattice and left to settle.
    #[default]
    #[serde(rename = "lattice")]
    Lattice,
    /// Advancing-front packing (SPEC §5) on the floor, then settled.
    #[serde(rename = "advancing-front", alias = "advancing_front")]
    AdvancingFront,
}

/// Shape of the radius distribution (`damper.radius_distribution`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum RadiusDistributionKind {
    /// All radii = `radius`.
    Fixed,
    /// Uniform on [`radius_min`, `radius_max`].
    Uniform,
    /// Normal(`radius`, `radius_std`) truncated to [`radius_min`, `radius_max`].
    Normal,
    /// `radius_table` rows `[radius_m, weight]` (by number).
    Discrete,
    /// `radius_table` rows `[radius_m, cumulative_fraction]`, a size curve by number.
    Empirical,
}

/// Format of particle snapshots (`damper.snapshot_format`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SnapshotFormat {
    /// `snapshots/grains_NNNNNN.csv`.
    Csv,
    /// VTK XML for ParaView: `grains_NNNNNN.vtp`, `box_NNNNNN.vtp` and the time series
    /// `grains.pvd`, `box.pvd`.
    Vtk,
    /// Both.
    #[default]
    Both,
}

/// Parameters of a box of spheres simulated with the discrete element method.
///
/// Every field gives its unit. Defaults are the thesis's scene B (Sánchez 2012 §3.2) where a
/// default makes sense.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DemParams {
    /// Inner box size [Lx, Ly, Lz] (m). The floor is at the box position z, the ceiling Lz above.
    pub r#box: [f64; 3],
    /// Shape of the cavity: `"box"` (default, of size `box`) or `"cylinder"` (`diameter`,
    /// `length`, `axis`; `box` is then its bounding box, filled in).
    #[serde(default, skip_serializing_if = "ContainerKind::is_box")]
    pub container: ContainerKind,
    /// A cylinder's inner diameter D (m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub diameter: Option<f64>,
    /// A cylinder's inner length L between its end caps (m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub length: Option<f64>,
    /// A cylinder's axis: `"x"`, `"y"` or `"z"` (default `"z"`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axis: Option<AxisName>,
    /// Number of spheres. May be left out when `mass` is given.
    pub count: usize,
    /// Total grain mass (kg), instead of `count`: the bed holds round(mass / m_grain) grains of
    /// the single `radius` (m_grain = ρ 4/3 π R³), so that a scene keeps its mass ratio when
    /// `material` changes (the linear-DEM paper's §3.1 compares materials at one mass ratio).
    /// Given with `count`, the two must agree to half a grain.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mass: Option<f64>,
    /// Sphere radius (m) when all grains are equal; the mean of `normal`.
    #[serde(default)]
    pub radius: Option<f64>,
    /// Smallest radius (m) of a uniform range (or truncation of `normal`).
    #[serde(default)]
    pub radius_min: Option<f64>,
    /// Largest radius (m) of a uniform range (or truncation of `normal`).
    #[serde(default)]
    pub radius_max: Option<f64>,
    /// Radius distribution; default: `fixed` if `radius` alone, `uniform` if min/max given.
    #[serde(default)]
    pub radius_distribution: Option<RadiusDistributionKind>,
    /// Standard deviation of the `normal` radius distribution (m).
    #[serde(default)]
    pub radius_std: Option<f64>,
    /// Table for `discrete` ([radius_m, weight]) or `empirical` ([radius_m, cumulative]) radii.
    #[serde(default)]
    pub radius_table: Option<Vec<[f64; 2]>>,
    /// Grain material preset (`"steel"`, `"sus304"`, `"glass"`, `"lead"`, `"aluminium"`,
    /// `"acrylic"`): fills `density`, `youngs_modulus`, `poisson`, `friction`, `restitution`
    /// and (linear law) `yield_strength` where the scene leaves them out
    /// ([`crate::scene::material`], sources cited there).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<crate::scene::material::MaterialPreset>,
    /// Grain density (kg/m³).
    pub density: f64,
    /// Grain Young's modulus E (Pa).
    pub youngs_modulus: f64,
    /// Grain Poisson ratio ν (–), 0 ≤ ν < 0.5.
    pub poisson: f64,
    /// Grain–grain Coulomb friction coefficient μ (–).
    pub friction: f64,
    /// Kuwabara–Kono normal damping γ_n (kg s⁻¹ m^-1/2), (2.2.8). Unused by `linear`.
    #[serde(default)]
    pub gamma_n: f64,
    /// Tangential damping γ_s (kg s⁻¹ m^-1/2), (2.2.12). Unused by `linear`. A `hertz-kk`
    /// scene that gives `restitution` instead of `gamma_n` and no `gamma_s` gets 3 γ_n, the
    /// ratio of the thesis's parameter sets.
    #[serde(default)]
    pub gamma_s: f64,
    /// Contact law: `"hertz-kk"` (Hertz + Kuwabara–Kono, default) or `"linear"`.
    #[serde(default)]
    pub contact: ContactKind,
    /// Tangential law: `"coulomb-viscous"` (the thesis's, default), `"mindlin"` (Hertz spring
    /// with history, `hertz-kk`) or `"linear-spring"` (with history, `linear`).
    #[serde(default)]
    pub tangential: TangentialKind,
    /// Coefficient of restitution e (–), grain–grain. `linear`: the law's constant e
    /// (required). `hertz-kk`: instead of `gamma_n`, the e that collisions at
    /// `restitution_speed` have; γ_n is derived from it (Müller–Pöschel's e(v) inverted at the
    /// grains' middle radius) and printed by `check-scene`.
    #[serde(default)]
    pub restitution: Option<f64>,
    /// Impact speed (m/s) at which `restitution` holds for `hertz-kk` (default 1 m/s):
    /// viscoelastic grains bounce more at lower speeds.
    #[serde(default)]
    pub restitution_speed: Option<f64>,
    /// Yield strength Y (Pa) for `contact = "linear"` (fixes k_n via the yield overlap).
    #[serde(default)]
    pub yield_strength: Option<f64>,
    /// Let the total normal force turn attractive while grains separate (default `false`:
    /// clamped to ≥ 0, the collision ends when the force vanishes — Müller & Pöschel).
    #[serde(default)]
    pub attractive_normal_force: bool,
    /// Wall Young's modulus E_b (Pa); default: the grains' E.
    #[serde(default)]
    pub wall_youngs_modulus: Option<f64>,
    /// Wall Poisson ratio ν_b (–); default: the grains' ν.
    #[serde(default)]
    pub wall_poisson: Option<f64>,
    /// Grain–wall friction coefficient (–); default: `friction`.
    #[serde(default)]
    pub wall_friction: Option<f64>,
    /// Grain–wall γ_n (kg s⁻¹ m^-1/2); default: `gamma_n`.
    #[serde(default)]
    pub wall_gamma_n: Option<f64>,
    /// Grain–wall γ_s (kg s⁻¹ m^-1/2); default: `gamma_s`.
    #[serde(default)]
    pub wall_gamma_s: Option<f64>,
    /// Grain–wall restitution (–); default: `restitution`. For `hertz-kk` it gives the wall's
    /// γ_n unless `wall_gamma_n` is set.
    #[serde(default)]
    pub wall_restitution: Option<f64>,
    /// Initial bed: `"lattice"` (FCC drop and settle, default) or `"advancing-front"`.
    #[serde(default)]
    pub packing: PackingKind,
    /// Seed of every random draw (radii, packing, lattice jitter).
    #[serde(default = "default_seed")]
    pub seed: u64,
    /// Integrate angular velocities and frictional torques (default `true`).
    #[serde(default = "default_true")]
    pub rotations: bool,
    /// Track orientations as unit quaternions (default `false`: spheres do not need them).
    #[serde(default)]
    pub orientations: bool,
    /// Interval between particle snapshots (s); none when absent.
    #[serde(default)]
    pub snapshot_interval: Option<f64>,
    /// Directory of the snapshots (default `snapshots`); a relative path is under the run's
    /// output directory (`pdamp simulate --out DIR`: `DIR/snapshots`; a sweep point `i`:
    /// `OUT/points/i/snapshots`); an absolute one is used as given by `simulate` and gets the
    /// point's number appended in a sweep (`/abs/dir/i`).
    #[serde(default)]
    pub snapshot_dir: Option<String>,
    /// Snapshot files: `"csv"`, `"vtk"` or `"both"` (default).
    #[serde(default)]
    pub snapshot_format: SnapshotFormat,
    /// Verlet-list skin (m); default 0.2 × the largest radius (the LIGGGHTS decks' 0.6 mm
    /// for R = 3 mm).
    #[serde(default)]
    pub neighbor_skin: Option<f64>,
    /// Longest settling time before the base starts (s); default 1.0. Settling stops earlier
    /// once the grains' mean speed is below 1 mm/s.
    #[serde(default)]
    pub settle_time: Option<f64>,
    /// A bag of film holding the grains (the bean-bag damper, `[damper.bag]`,
    /// [`bag::BagParams`]); none by default.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bag: Option<bag::BagParams>,
}

/// Factor of the damping coefficients γ_n, γ_s when Young's modulus is divided by `factor`:
/// factor^{-3/5} (keeps e(v) of Kuwabara–Kono, β ∝ γ_n k_n^{-3/5}, SPEC §9).
pub fn softening_damping_scale(factor: f64) -> f64 {
    factor.powf(-0.6)
}

fn default_seed() -> u64 {
    1
}
fn default_true() -> bool {
    true
}

impl DemParams {
    /// Scene B of the thesis (Sánchez 2012 §3.2): 250 steel spheres, R = 3 mm, in a
    /// 36.75 × 36.75 mm box, Lz = 0.1225 m (one of the thesis's heights).
    pub fn thesis_b() -> Self {
        DemParams {
            r#box: [0.03675, 0.03675, 0.1225],
            container: ContainerKind::Box,
            diameter: None,
            length: None,
            axis: None,
            count: 250,
            mass: None,
            radius: Some(0.003),
            radius_min: None,
            radius_max: None,
            radius_distribution: None,
            radius_std: None,
            radius_table: None,
            material: None,
            density: 8030.0,
            youngs_modulus: 2.03e11,
            poisson: 0.28,
            friction: 0.3,
            gamma_n: 3660.0,
            gamma_s: 10980.0,
            contact: ContactKind::HertzKk,
            tangential: TangentialKind::CoulombViscous,
            restitution: None,
            restitution_speed: None,
            yield_strength: None,
            attractive_normal_force: false,
            wall_youngs_modulus: None,
            wall_poisson: None,
            wall_friction: None,
            wall_gamma_n: None,
            wall_gamma_s: None,
            wall_restitution: None,
            packing: PackingKind::Lattice,
            seed: 1,
            rotations: true,
            orientations: false,
            snapshot_interval: None,
            snapshot_dir: None,
            snapshot_format: SnapshotFormat::Both,
            neighbor_skin: None,
            settle_time: None,
            bag: None,
        }
    }

    /// Scene B softened by `factor` ([`DemParams::softened`]). Used by tests and benchmarks
    /// to take ~factor^{2/5} larger time steps.
    pub fn thesis_b_softened(factor: f64) -> Self {
        Self::thesis_b().softened(factor)
    }

    /// The softening rule, the one place it is written: every Young's modulus (grains and
    /// walls) divided by `factor`, every γ_n, γ_s multiplied by [`softening_damping_scale`]
    /// = factor^{-3/5}, so that the Kuwabara–Kono restitution curve e(v) is unchanged
    /// (β ∝ γ_n k_n^{-3/5}, SPEC §9, k_n ∝ E); a linear law's yield strength is divided by
    /// `factor` too (same yield overlap, k_n ∝ E).
    pub fn softened(&self, factor: f64) -> DemParams {
        let mut q = self.clone();
        let s = softening_damping_scale(factor);
        q.youngs_modulus /= factor;
        q.wall_youngs_modulus = q.wall_youngs_modulus.map(|e| e / factor);
        q.gamma_n *= s;
        q.gamma_s *= s;
        q.wall_gamma_n = q.wall_gamma_n.map(|g| g * s);
        q.wall_gamma_s = q.wall_gamma_s.map(|g| g * s);
        q.yield_strength = q.yield_strength.map(|y| y / factor);
        q
    }

    /// Grain material.
    pub fn grain_material(&self) -> Material {
        Material {
            youngs_modulus: self.youngs_modulus,
            poisson: self.poisson,
        }
    }

    /// Wall material (defaults to the grains').
    pub fn wall_material(&self) -> Material {
        Material {
            youngs_modulus: self.wall_youngs_modulus.unwrap_or(self.youngs_modulus),
            poisson: self.wall_poisson.unwrap_or(self.poisson),
        }
    }
}

/// The grain count of a raw `[damper]` table (`kind = "dem"`) that gives `mass` instead of
/// `count`: round(mass / (ρ 4/3 π R³)), at least 1 (after the material preset filled ρ).
/// With both keys, they must agree to half a grain. Returns whether the table changed.
///
/// # Errors
/// [`SceneError`] naming `damper.mass` (not a positive number, no single `radius` or
/// `density` to divide by, or disagreeing with `count`).
pub(crate) fn count_from_mass(d: &mut toml::Table) -> Result<bool, crate::error::SceneError> {
    use crate::error::SceneError;
    if d.get("kind").and_then(toml::Value::as_str) != Some("dem") {
        return Ok(false);
    }
    let Some(value) = d.get("mass") else {
        return Ok(false);
    };
    let num = |v: &toml::Value| v.as_float().or_else(|| v.as_integer().map(|i| i as f64));
    let mass = num(value)
        .filter(|m| m.is_finite() && *m > 0.0)
        .ok_or_else(|| {
            SceneError::invalid("damper.mass", value, "must be a finite number > 0 (kg)")
        })?;
    let (Some(r), Some(rho)) = (
        d.get("radius").and_then(num),
        d.get("density").and_then(num),
    ) else {
        return Err(SceneError::invalid(
            "damper.mass",
            mass,
            "needs a single grain radius (damper.radius, m) and a density (damper.density, \
             kg/m³, or a material) to give the grain count; or write damper.count",
        ));
    };
    let grain = rho * 4.0 / 3.0 * std::f64::consts::PI * r * r * r;
    let count = (mass / grain).round().max(1.0);
    if !(count.is_finite() && count <= 1e9) {
        return Err(SceneError::invalid(
            "damper.mass",
            mass,
            format!("gives {count:e} grains of {grain:e} kg: check damper.mass (kg), radius (m) and density (kg/m³)"),
        ));
    }
    match d.get("count").and_then(toml::Value::as_integer) {
        Some(n) if ((n as f64) * grain - mass).abs() > 0.5 * grain => Err(SceneError::invalid(
            "damper.mass",
            mass,
            format!(
                "disagrees with damper.count = {n} ({:e} kg of grains of {grain:e} kg): give one of them",
                n as f64 * grain
            ),
        )),
        Some(_) => Ok(false),
        None => {
            d.insert("count".into(), toml::Value::Integer(count as i64));
            Ok(true)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thesis_b_is_valid_and_errors_name_the_key() {
        DemParams::thesis_b().validate().unwrap();
        let mut p = DemParams::thesis_b();
        p.radius = Some(-0.003);
        let e = p.validate().unwrap_err().to_string();
        assert!(e.contains("damper.radius") && e.contains("> 0"), "{e}");
        let mut p = DemParams::thesis_b();
        p.poisson = 0.5;
        assert!(p
            .validate()
            .unwrap_err()
            .to_string()
            .contains("damper.poisson"));
        let mut p = DemParams::thesis_b();
        p.count = 2000;
        assert!(p
            .validate()
            .unwrap_err()
            .to_string()
            .contains("damper.count"));
        let mut p = DemParams::thesis_b();
        p.contact = ContactKind::Linear;
        assert!(p
            .validate()
            .unwrap_err()
            .to_string()
            .contains("damper.restitution"));
    }

    #[test]
    fn parses_from_toml() {
        let t = r#"
            box = [0.03675, 0.03675, 0.1225]
            count = 250
            radius = 0.003
            density = 8030.0
            youngs_modulus = 2.03e11
            poisson = 0.28
            friction = 0.3
            gamma_n = 3660.0
            gamma_s = 10980.0
            contact = "hertz-kk"
        "#;
        let p: DemParams = toml::from_str(t).unwrap();
        assert_eq!(p, DemParams::thesis_b());
    }
}
