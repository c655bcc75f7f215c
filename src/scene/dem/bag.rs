//! `[damper.bag]`: the bean-bag damper's bag (the linear-DEM paper's §3.2), a closed
//! cylindrical film standing on the cavity's floor along z, centred in the box, holding the
//! grains (model in [`crate::dem::bag`]).
//!
//! ```toml
//! [damper.bag]
//! diameter = 0.030        # m, outer diameter of the film
//! length = 0.038          # m, outer length between the end caps
//! film_thickness = 1e-4   # m
//! film = "polyethylene"   # the film's ρ, E, ν, Y and loss factor (or give them)
//! node_radius = 0.001     # m, the film's nodes (spacing 2 × radius)
//! ```
//!
//! The `polyethylene` film is low-density polyethylene: ρ = 920 kg/m³, E = 0.2 GPa,
//! ν = 0.46, tensile yield 10 MPa (Ashby & Jones, *Engineering Materials 1*, tables of
//! density, modulus and yield strength of polymers), loss factor η = 0.1 near room
//! temperature at 1–100 Hz (typical of LDPE, Ashby, *Materials Selection in Mechanical Design*,
//! loss-coefficient chart).

use serde::{Deserialize, Serialize};

use crate::contact::material::Material;
use crate::dem::bag::{BagGeometry, Film};
use crate::error::SceneError;
use crate::scene::checks::positive;

/// Film presets (`damper.bag.film`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FilmPreset {
    /// Low-density polyethylene (the paper's "polyethylene plastic" bag).
    Polyethylene,
}

/// The bag of a bean-bag damper.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BagParams {
    /// Outer diameter of the film (m).
    pub diameter: f64,
    /// Outer length between the end caps (m).
    pub length: f64,
    /// Film thickness t (m).
    pub film_thickness: f64,
    /// Film preset filling the keys below that are left out (default `polyethylene`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub film: Option<FilmPreset>,
    /// Film density (kg/m³).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub film_density: Option<f64>,
    /// Film Young's modulus (Pa).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub film_youngs_modulus: Option<f64>,
    /// Film Poisson ratio (–).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub film_poisson: Option<f64>,
    /// Film yield strength (Pa): the linear law's stiffness of the nodes' contacts.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub film_yield_strength: Option<f64>,
    /// Film loss factor η (–): the bonds' damping ratio is η/2.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub film_loss_factor: Option<f64>,
    /// Radius of the film's nodes (m); default half the grains' radius.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub node_radius: Option<f64>,
}

/// LDPE (module doc): ρ, E, ν, Y, η.
const POLYETHYLENE: [f64; 5] = [920.0, 2.0e8, 0.46, 1.0e7, 0.1];

fn check(key: &str, v: f64, ok: bool, fix: &str) -> Result<(), SceneError> {
    if ok && v.is_finite() {
        Ok(())
    } else {
        Err(SceneError::invalid(format!("damper.bag.{key}"), v, fix))
    }
}

impl BagParams {
    /// The film: the preset's values where the keys are left out.
    pub fn film_model(&self) -> Film {
        let [rho, e, nu, y, eta] = match self.film.unwrap_or(FilmPreset::Polyethylene) {
            FilmPreset::Polyethylene => POLYETHYLENE,
        };
        Film {
            material: Material {
                youngs_modulus: self.film_youngs_modulus.unwrap_or(e),
                poisson: self.film_poisson.unwrap_or(nu),
            },
            yield_strength_pa: self.film_yield_strength.unwrap_or(y),
            thickness_m: self.film_thickness,
            density_kg_m3: self.film_density.unwrap_or(rho),
            loss_factor: self.film_loss_factor.unwrap_or(eta),
        }
    }

    /// The bag standing on the floor of a box of inner size `box_m`, centred across it, with
    /// nodes of `node_radius` (default half `grain_radius`, m).
    pub fn geometry(&self, box_m: [f64; 3], grain_radius: f64) -> BagGeometry {
        BagGeometry {
            diameter_m: self.diameter,
            length_m: self.length,
            centre_m: [0.5 * box_m[0], 0.5 * box_m[1]],
            spacing_m: 2.0 * self.node_radius.unwrap_or(0.5 * grain_radius),
        }
    }

    /// Every key in range and the bag inside the box `box_m` (m).
    ///
    /// # Errors
    /// [`SceneError`] naming `damper.bag.<key>` and the fix.
    pub fn validate(&self, box_m: [f64; 3], grain_radius: f64) -> Result<(), SceneError> {
        let f = self.film_model();
        positive("damper.bag.diameter", self.diameter, "m")?;
        positive("damper.bag.length", self.length, "m")?;
        check(
            "film_thickness",
            self.film_thickness,
            self.film_thickness > 0.0 && self.film_thickness < 0.1 * self.diameter,
            "must be > 0 and thin next to the bag (m; e.g. 1e-4 for a 0.1 mm film)",
        )?;
        let m = f.material;
        positive("damper.bag.film_density", f.density_kg_m3, "kg/m³")?;
        positive("damper.bag.film_youngs_modulus", m.youngs_modulus, "Pa")?;
        check(
            "film_poisson",
            m.poisson,
            (0.0..0.5).contains(&m.poisson),
            "must be in [0, 0.5)",
        )?;
        positive("damper.bag.film_yield_strength", f.yield_strength_pa, "Pa")?;
        check(
            "film_loss_factor",
            f.loss_factor,
            (0.0..=2.0).contains(&f.loss_factor),
            "must be in [0, 2] (a film's η is ~0.01–0.3)",
        )?;
        let g = self.geometry(box_m, grain_radius);
        check(
            "node_radius",
            0.5 * g.spacing_m,
            g.spacing_m > 0.0 && g.spacing_m <= 2.0 * grain_radius,
            "must be > 0 and at most the grains' radius, so that no grain passes between the \
             film's nodes (m)",
        )?;
        if self.diameter > box_m[0].min(box_m[1]) + 1e-12 || self.length > box_m[2] + 1e-12 {
            return Err(SceneError::invalid(
                "damper.bag.diameter",
                self.diameter,
                format!(
                    "a bag of {} × {} m does not fit the box {:?} m (diameter across x and y, \
                     length along z): shrink the bag or widen damper.box",
                    self.diameter, self.length, box_m
                ),
            ));
        }
        Ok(())
    }
}
