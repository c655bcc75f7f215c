//! The contact laws of a [`DemWorld`](super::DemWorld) flattened for its loops ([`Laws`]),
//! and the coefficients every grain shares when all grains are alike ([`Uniform`]).

use crate::contact::material::Material;
use crate::contact::response::ContactCoefficients;
use crate::contact::{ContactModel, TangentialLaw};
use crate::dem::bag::Film;

/// Contact laws (grain–grain and grain–wall) of the [`DemModel`](crate::dem::DemModel),
/// flattened for the loops: the contact model, the grains' material and whether torques are
/// computed.
#[derive(Debug, Clone)]
pub(super) struct Laws {
    pub(super) contact: ContactModel,
    pub(super) grain: Material,
    pub(super) rotations: bool,
    /// The bean bag's film (its nodes' material and yield strength), if there is a bag.
    pub(super) film: Option<Film>,
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
    /// ([`ContactModel::coefficients_between`]) between bodies `(radius m, mass kg, is a
    /// film node)`: grains of the grains' material, nodes of the film's (a contact with a
    /// node yields at the film's strength).
    pub(super) fn coefficients(
        &self,
        (r_i, m_i, node_i): (f64, f64, bool),
        (r_j, m_j, node_j): (f64, f64, bool),
        wall: bool,
    ) -> ContactCoefficients {
        let film = self.film.filter(|_| node_i || (node_j && !wall));
        let mat = |node: bool| match (node, &self.film) {
            (true, Some(f)) => f.material,
            _ => self.grain,
        };
        // the film's body first: its Poisson ratio gives the yield coefficient
        let (a, b) = if node_j && !node_i && !wall {
            ((mat(true), r_j, m_j), (mat(false), r_i, m_i))
        } else {
            ((mat(node_i), r_i, m_i), (mat(node_j), r_j, m_j))
        };
        self.contact.coefficients_between(
            (&a.0, a.1, a.2),
            (&b.0, b.1, b.2),
            film.map(|f| f.yield_strength_pa),
            wall,
        )
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
        let alike =
            laws.film.is_none() && radius.iter().all(|&x| x == r) && mass.iter().all(|&x| x == m);
        alike.then(|| Uniform {
            radius: r,
            pair: laws.coefficients((r, m, false), (r, m, false), false),
            wall: laws.coefficients((r, m, false), (f64::INFINITY, f64::INFINITY, false), true),
        })
    }
}
