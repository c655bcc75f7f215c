//! The contact laws of a [`DemWorld`](super::DemWorld) flattened for its loops ([`Laws`]),
//! and the coefficients every grain shares when all grains are alike ([`Uniform`]).

use crate::contact::material::Material;
use crate::contact::response::ContactCoefficients;
use crate::contact::{ContactModel, TangentialLaw};

/// Contact laws (grain–grain and grain–wall) of the [`DemModel`](crate::dem::DemModel),
/// flattened for the loops: the contact model, the grains' material and whether torques are
/// computed.
#[derive(Debug, Clone)]
pub(super) struct Laws {
    pub(super) contact: ContactModel,
    pub(super) grain: Material,
    pub(super) rotations: bool,
}

impl Laws {
    /// Coulomb friction coefficient μ (–) of grain–wall (`wall`) or grain–grain contacts.
    pub(super) fn friction(&self, wall: bool) -> f64 {
        if wall {
            self.contact.wall.tangential.friction()
        } else {
            self.contact.tangential.friction()
        }
    }

    /// The tangential law the loops run (the grain–grain one, or the wall's if grains have
    /// none; both come from the same scene key).
    pub(super) fn tangential_kind(&self) -> TangentialLaw {
        if self.contact.tangential != TangentialLaw::None {
            self.contact.tangential
        } else {
            self.contact.wall.tangential
        }
    }

    /// [`ContactCoefficients`] of a pair or grain–wall contact
    /// ([`ContactModel::coefficients`]).
    pub(super) fn coefficients(
        &self,
        r_i: f64,
        m_i: f64,
        r_j: f64,
        m_j: f64,
        wall: bool,
    ) -> ContactCoefficients {
        self.contact
            .coefficients(&self.grain, (r_i, m_i), (r_j, m_j), wall)
    }
}

/// What every grain shares when all grains are alike (one radius, one mass).
#[derive(Debug, Clone, Copy)]
pub(super) struct Uniform {
    pub(super) radius: f64,
    pub(super) pair: ContactCoefficients,
    pub(super) wall: ContactCoefficients,
}

impl Uniform {
    /// `Some` when every grain has the radius and mass of the first (a monodisperse bed):
    /// then every pair's and every wall contact's coefficients are the same numbers.
    pub(super) fn of(laws: &Laws, radius: &[f64], mass: &[f64]) -> Option<Self> {
        let (r, m) = (*radius.first()?, *mass.first()?);
        let alike = radius.iter().all(|&x| x == r) && mass.iter().all(|&x| x == m);
        alike.then(|| Uniform {
            radius: r,
            pair: laws.coefficients(r, m, r, m, false),
            wall: laws.coefficients(r, m, f64::INFINITY, f64::INFINITY, true),
        })
    }
}
