//! The contact model of a DEM scene: the laws selected by `damper.contact` and
//! `damper.tangential`, and the Hertz–Kuwabara–Kono damping γ_n, γ_s (kg s⁻¹ m^-1/2) given
//! directly or from a coefficient of restitution.

use crate::contact::{AttractionPolicy, ContactModel, NormalLaw, TangentialLaw, WallContact};
use crate::error::SceneError;
use crate::scene::dem::{ContactKind, DemParams, TangentialKind};

/// Default impact speed (m/s) at which a `hertz-kk` scene's `restitution` holds.
pub const DEFAULT_RESTITUTION_SPEED: f64 = 1.0;

/// γ_n of the Hertz–Kuwabara–Kono law for grain–grain (`wall = false`) or grain–wall
/// contacts (kg s⁻¹ m^-1/2): the scene's `gamma_n` / `wall_gamma_n`, or, when the scene gives
/// a restitution instead, the damping that gives it at `restitution_speed`
/// ([`crate::contact::restitution::kuwabara_kono_gamma_n`]) for two grains of the
/// distribution's middle radius (r_min + r_max)/2, or such a grain and the wall.
///
/// # Errors
/// A bad radius distribution, or a restitution the inversion cannot reach.
pub fn hertz_kk_gamma_n(params: &DemParams, wall: bool) -> Result<f64, SceneError> {
    use crate::contact::material::{Material, PairProperties};
    let (explicit, e, key) = if wall {
        (
            params.wall_gamma_n,
            params.wall_restitution.or(params.restitution),
            "damper.wall_restitution",
        )
    } else {
        (None, params.restitution, "damper.restitution")
    };
    if let Some(g) = explicit {
        return Ok(g);
    }
    let Some(e) = e else {
        return Ok(params.gamma_n);
    };
    let dist = params.radius_distribution()?;
    let r = 0.5 * (dist.r_min() + dist.r_max());
    let m = params.density * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
    let grain = Material {
        youngs_modulus: params.youngs_modulus,
        poisson: params.poisson,
    };
    let pair = if wall {
        let w = Material {
            youngs_modulus: params.wall_youngs_modulus.unwrap_or(params.youngs_modulus),
            poisson: params.wall_poisson.unwrap_or(params.poisson),
        };
        PairProperties::new(r, m, &grain, f64::INFINITY, f64::INFINITY, &w)
    } else {
        PairProperties::new(r, m, &grain, r, m, &grain)
    };
    let k_n = crate::contact::hertz_stiffness(pair.e_star, pair.r_star);
    let v = params
        .restitution_speed
        .unwrap_or(DEFAULT_RESTITUTION_SPEED);
    crate::contact::restitution::kuwabara_kono_gamma_n(k_n, pair.m_star, v, e).ok_or_else(|| {
        SceneError::invalid(
            key,
            e,
            "no Kuwabara–Kono damping gives this restitution: use 0 < e ≤ 1",
        )
    })
}

/// Ratio γ_s/γ_n of the thesis's parameter sets (10980/3660 and 59.76/19.99, SPEC §6): the
/// tangential damping of a `hertz-kk` scene that gives a restitution and no `gamma_s`.
pub const GAMMA_S_PER_GAMMA_N: f64 = 3.0;

/// γ_s of the Hertz–Kuwabara–Kono law's Coulomb–viscous tangential force for grain–grain
/// (`wall = false`) or grain–wall contacts (kg s⁻¹ m^-1/2): the scene's `gamma_s` /
/// `wall_gamma_s` when given (> 0); for a scene whose γ_n comes from a restitution
/// ([`hertz_kk_gamma_n`]), [`GAMMA_S_PER_GAMMA_N`] × γ_n, so that its friction acts;
/// otherwise 0 (no tangential force).
///
/// # Errors
/// Those of [`hertz_kk_gamma_n`].
pub fn hertz_kk_gamma_s(params: &DemParams, wall: bool) -> Result<f64, SceneError> {
    let explicit = if wall {
        params.wall_gamma_s.unwrap_or(params.gamma_s)
    } else {
        params.gamma_s
    };
    let from_restitution = if wall {
        params.wall_gamma_n.is_none()
            && (params.wall_restitution.is_some() || params.restitution.is_some())
    } else {
        params.restitution.is_some()
    };
    if explicit > 0.0 || !from_restitution || params.contact != ContactKind::HertzKk {
        return Ok(explicit);
    }
    Ok(GAMMA_S_PER_GAMMA_N * hertz_kk_gamma_n(params, wall)?)
}

/// The contact model of `params` ([`DemParams::validate`] passed): grain–grain and
/// grain–wall laws selected by `damper.contact`, wall values defaulting to the grains'.
///
/// # Errors
/// `damper.restitution` / `damper.yield_strength` missing for `contact = "linear"`.
pub fn contact_model(params: &DemParams) -> Result<ContactModel, SceneError> {
    let normal = |wall: bool| -> Result<NormalLaw, SceneError> {
        Ok(match params.contact {
            ContactKind::HertzKk => NormalLaw::HertzKuwabaraKono {
                gamma_n: hertz_kk_gamma_n(params, wall)?,
            },
            ContactKind::Linear => {
                let e = params.restitution.ok_or_else(|| SceneError::Missing {
                    field: "damper.restitution".into(),
                    hint: "contact = \"linear\" needs the coefficient of restitution e in (0, 1]"
                        .into(),
                })?;
                NormalLaw::LinearSpringDashpot {
                    restitution: if wall {
                        params.wall_restitution.unwrap_or(e)
                    } else {
                        e
                    },
                    yield_strength: params.yield_strength.ok_or_else(|| SceneError::Missing {
                        field: "damper.yield_strength".into(),
                        hint: "contact = \"linear\" needs the grains' yield strength (Pa)".into(),
                    })?,
                }
            }
        })
    };
    let gamma_s = [
        hertz_kk_gamma_s(params, false)?,
        hertz_kk_gamma_s(params, true)?,
    ];
    let tangential = |wall: bool| -> TangentialLaw {
        let mu = if wall {
            params.wall_friction.unwrap_or(params.friction)
        } else {
            params.friction
        };
        if mu <= 0.0 {
            return TangentialLaw::None;
        }
        let gamma_s = gamma_s[usize::from(wall)];
        match (params.contact, params.tangential) {
            (_, TangentialKind::Mindlin) => TangentialLaw::MindlinSpring {
                gamma_s,
                friction: mu,
            },
            (_, TangentialKind::LinearSpring) => TangentialLaw::LinearSpring { friction: mu },
            (ContactKind::HertzKk, _) => {
                if gamma_s > 0.0 {
                    TangentialLaw::CoulombViscous {
                        gamma_s,
                        friction: mu,
                    }
                } else {
                    TangentialLaw::None
                }
            }
            (ContactKind::Linear, _) => TangentialLaw::LinearDashpotCoulomb { friction: mu },
        }
    };
    Ok(ContactModel {
        normal: normal(false)?,
        tangential: tangential(false),
        wall: WallContact {
            material: params.wall_material(),
            normal: normal(true)?,
            tangential: tangential(true),
        },
        attraction: if params.attractive_normal_force {
            AttractionPolicy::Allow
        } else {
            AttractionPolicy::Clamp
        },
    })
}
