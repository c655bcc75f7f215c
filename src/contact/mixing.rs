//! The coefficients of one contact from the two bodies and the laws (as LAMMPS's pair styles
//! mix their per-type coefficients in `init_one`): [`ContactModel::coefficients`], the
//! [`ContactCoefficients`] `[k_n, c_n, c_t, k_t]` a contact's kernels read.
//!
//! # Formulas
//! With E*, G*, R*, m* of the pair ([`PairProperties`], (2.2.9); a wall has R_j, m_j → ∞):
//! - Hertz–Kuwabara–Kono normal law (2.2.8–2.2.9): k_n = (4/3) E* √R* (N m^-3/2),
//!   c_n = γ_n (kg s⁻¹ m^-1/2) from the scene;
//! - linear spring–dashpot: k_n (N/m), c_n (kg/s), k_s (N/m) and c_s (kg/s) of
//!   [`LinearContactParams::select`] (seed paper eqs. 11–17);
//! - tangential laws: c_t = γ_s (kg s⁻¹ m^-1/2) for the Coulomb-viscous (2.2.12) and Mindlin
//!   laws, c_s (kg/s) for the linear ones; k_t = 8 G* √R* (N m^-3/2, Mindlin: the spring is
//!   k_t √ζ), k_s (N/m) for the linear spring, 0 for history-free laws.

use super::hertz_kuwabara_kono::hertz_stiffness;
use super::linear_spring_dashpot::LinearContactParams;
use super::material::{Material, PairProperties};
use super::response::ContactCoefficients;
use super::{ContactModel, NormalLaw, TangentialLaw};

impl ContactModel {
    /// [`ContactCoefficients`] `[k_n, c_n, c_t, k_t]` of a contact between a grain of
    /// material `grain` with radius and mass `(r_i, m_i)` (m, kg) and a grain `(r_j, m_j)` of
    /// the same material, or the wall (`wall`; pass `f64::INFINITY` for its radius and mass),
    /// under this model's grain–grain or grain–wall laws (formulas in the module's doc).
    ///
    /// # Panics
    /// For a linear law whose yield strength or restitution [`LinearContactParams::select`]
    /// rejects (the scene's resolve step has validated them).
    pub fn coefficients(
        &self,
        grain: &Material,
        (r_i, m_i): (f64, f64),
        (r_j, m_j): (f64, f64),
        wall: bool,
    ) -> ContactCoefficients {
        self.coefficients_between((grain, r_i, m_i), (grain, r_j, m_j), None, wall)
    }

    /// [`ContactModel::coefficients`] between bodies of two materials: `(material, radius,
    /// mass)` of each (the second's material is ignored for a wall, whose own is the
    /// model's), with the linear law's yield strength replaced by `yield_strength` when given
    /// (a contact of the bean bag's film yields at the film's strength) and its yield
    /// coefficient c_e taken from the first body's Poisson ratio.
    ///
    /// # Panics
    /// As [`ContactModel::coefficients`].
    pub fn coefficients_between(
        &self,
        (mat_i, r_i, m_i): (&Material, f64, f64),
        (mat_j, r_j, m_j): (&Material, f64, f64),
        yield_strength: Option<f64>,
        wall: bool,
    ) -> ContactCoefficients {
        let (mat_j, normal, tangential) = if wall {
            (&self.wall.material, self.wall.normal, self.wall.tangential)
        } else {
            (mat_j, self.normal, self.tangential)
        };
        let p = PairProperties::new(r_i, m_i, mat_i, r_j, m_j, mat_j);
        let (k, c, c_lin_s, k_lin_s) = match normal {
            NormalLaw::HertzKuwabaraKono { gamma_n } => {
                (hertz_stiffness(p.e_star, p.r_star), gamma_n, 0.0, 0.0)
            }
            NormalLaw::LinearSpringDashpot {
                restitution,
                yield_strength: y,
            } => {
                let y = yield_strength.unwrap_or(y);
                let l = LinearContactParams::select(&p, mat_i, y, restitution)
                    .expect("validated linear parameters");
                (l.k_n, l.c_n, l.c_s, l.k_s)
            }
        };
        let (cs, kt) = match tangential {
            TangentialLaw::None => (0.0, 0.0),
            TangentialLaw::CoulombViscous { gamma_s, .. } => (gamma_s, 0.0),
            TangentialLaw::LinearDashpotCoulomb { .. } => (c_lin_s, 0.0),
            TangentialLaw::MindlinSpring { gamma_s, .. } => {
                (gamma_s, 8.0 * p.g_star * p.r_star.sqrt())
            }
            TangentialLaw::LinearSpring { .. } => (c_lin_s, k_lin_s),
        };
        [k, c, cs, kt]
    }
}
