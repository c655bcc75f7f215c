//! What [`DemParams::validate`] checks, each constraint once with the offending key named in
//! the error, and the radius keys resolved to a distribution
//! ([`DemParams::radius_distribution`]).

use crate::error::SceneError;
use crate::packing::RadiusDistribution;

use super::{ContactKind, DemParams, PackingKind, RadiusDistributionKind, TangentialKind};

fn positive(field: &str, v: f64, unit: &str) -> Result<(), SceneError> {
    if v > 0.0 && v.is_finite() {
        Ok(())
    } else {
        Err(SceneError::invalid(
            field,
            v,
            format!("must be > 0 ({unit})"),
        ))
    }
}

fn non_negative(field: &str, v: f64, unit: &str) -> Result<(), SceneError> {
    if v >= 0.0 && v.is_finite() {
        Ok(())
    } else {
        Err(SceneError::invalid(
            field,
            v,
            format!("must be ≥ 0 ({unit})"),
        ))
    }
}

fn poisson_ok(field: &str, v: f64) -> Result<(), SceneError> {
    if (0.0..0.5).contains(&v) {
        Ok(())
    } else {
        Err(SceneError::invalid(
            field,
            v,
            "must be in [0, 0.5) (Poisson ratio)",
        ))
    }
}

impl DemParams {
    /// The resolved radius distribution.
    ///
    /// # Errors
    /// Names the missing or inconsistent radius key.
    pub fn radius_distribution(&self) -> Result<RadiusDistribution, SceneError> {
        let kind = match self.radius_distribution {
            Some(k) => k,
            None => match (self.radius, self.radius_min, self.radius_max) {
                (Some(_), None, None) => RadiusDistributionKind::Fixed,
                (None, Some(_), Some(_)) => RadiusDistributionKind::Uniform,
                (None, None, None) if self.radius_table.is_some() => {
                    RadiusDistributionKind::Discrete
                }
                _ => {
                    return Err(SceneError::Missing {
                        field: "damper.radius".into(),
                        hint: "give `radius` (m), or `radius_min` and `radius_max` (m), or \
                               `radius_distribution` with its keys"
                            .into(),
                    })
                }
            },
        };
        let need = |v: Option<f64>, f: &str| -> Result<f64, SceneError> {
            let x = v.ok_or_else(|| SceneError::Missing {
                field: format!("damper.{f}"),
                hint: format!("required by radius_distribution = {kind:?} (metres)"),
            })?;
            positive(&format!("damper.{f}"), x, "metres")?;
            Ok(x)
        };
        let d = match kind {
            RadiusDistributionKind::Fixed => {
                RadiusDistribution::Fixed(need(self.radius, "radius")?)
            }
            RadiusDistributionKind::Uniform => {
                let (min, max) = (
                    need(self.radius_min, "radius_min")?,
                    need(self.radius_max, "radius_max")?,
                );
                if max < min {
                    return Err(SceneError::invalid(
                        "damper.radius_max",
                        max,
                        "must be ≥ radius_min",
                    ));
                }
                RadiusDistribution::Uniform { min, max }
            }
            RadiusDistributionKind::Normal => {
                let mean = need(self.radius, "radius")?;
                let std = self.radius_std.ok_or_else(|| SceneError::Missing {
                    field: "damper.radius_std".into(),
                    hint: "standard deviation of the normal radius distribution (m)".into(),
                })?;
                non_negative("damper.radius_std", std, "metres")?;
                let min = self
                    .radius_min
                    .unwrap_or((mean - 3.0 * std).max(0.05 * mean));
                let max = self.radius_max.unwrap_or(mean + 3.0 * std);
                positive("damper.radius_min", min, "metres")?;
                if max < min {
                    return Err(SceneError::invalid(
                        "damper.radius_max",
                        max,
                        "must be ≥ radius_min",
                    ));
                }
                RadiusDistribution::Normal {
                    mean,
                    std,
                    min,
                    max,
                }
            }
            RadiusDistributionKind::Discrete | RadiusDistributionKind::Empirical => {
                let t = self.radius_table.as_ref().filter(|t| !t.is_empty()).ok_or_else(|| {
                    SceneError::Missing {
                        field: "damper.radius_table".into(),
                        hint: "rows [radius_m, weight] (discrete) or [radius_m, cumulative] (empirical)".into(),
                    }
                })?;
                for row in t {
                    positive("damper.radius_table", row[0], "radius, metres")?;
                    non_negative(
                        "damper.radius_table",
                        row[1],
                        "weight or cumulative fraction",
                    )?;
                }
                let radii: Vec<f64> = t.iter().map(|r| r[0]).collect();
                let w: Vec<f64> = t.iter().map(|r| r[1]).collect();
                if kind == RadiusDistributionKind::Discrete {
                    if w.iter().sum::<f64>() <= 0.0 {
                        return Err(SceneError::invalid(
                            "damper.radius_table",
                            "weights",
                            "weights must not all be 0",
                        ));
                    }
                    RadiusDistribution::Discrete {
                        values: radii,
                        weights: w,
                    }
                } else {
                    let ok = t.len() >= 2
                        && radii.windows(2).all(|p| p[1] > p[0])
                        && w.windows(2).all(|p| p[1] >= p[0])
                        && w[0] == 0.0
                        && (w[w.len() - 1] - 1.0).abs() < 1e-9;
                    if !ok {
                        return Err(SceneError::invalid(
                            "damper.radius_table",
                            "curve",
                            "empirical curve needs ≥ 2 rows, radii increasing, cumulative fraction \
                             non-decreasing from 0 to 1",
                        ));
                    }
                    RadiusDistribution::Empirical { radii, cdf: w }
                }
            }
        };
        Ok(d)
    }

    /// `hertz-kk` with a restitution: e ∈ (0, 1] and not together with the γ_n it replaces.
    fn validate_hertz_restitution(&self) -> Result<(), SceneError> {
        for (k, e, gamma) in [
            ("damper.restitution", self.restitution, self.gamma_n > 0.0),
            (
                "damper.wall_restitution",
                self.wall_restitution,
                self.wall_gamma_n.is_some(),
            ),
        ] {
            let Some(e) = e else { continue };
            if !(e > 0.0 && e <= 1.0) {
                return Err(SceneError::invalid(
                    k,
                    e,
                    "must be in (0, 1] (coefficient of restitution)",
                ));
            }
            if gamma {
                return Err(SceneError::invalid(
                    k,
                    e,
                    format!(
                        "give either {k} or the damping {} for contact = \"hertz-kk\", not both (the restitution sets the damping)",
                        k.replace("restitution", "gamma_n")
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Checks every constraint once; the error names the key, the value and the fix.
    ///
    /// # Errors
    /// Non-positive box, count, radii, density or moduli; ν ∉ [0, 0.5); negative friction or
    /// damping; missing `restitution`/`yield_strength` for `linear`; grains that cannot fit
    /// (largest diameter above the smallest box side, or solid volume above 58 % of the box,
    /// about a random close packing).
    pub fn validate(&self) -> Result<(), SceneError> {
        for (k, v) in [
            "damper.box[0] (Lx)",
            "damper.box[1] (Ly)",
            "damper.box[2] (Lz)",
        ]
        .iter()
        .zip(self.r#box)
        {
            positive(k, v, "metres")?;
        }
        self.validate_container()?;
        if self.count == 0 {
            return Err(SceneError::invalid("damper.count", 0, "must be ≥ 1 grain"));
        }
        positive("damper.density", self.density, "kg/m³")?;
        positive("damper.youngs_modulus", self.youngs_modulus, "Pa")?;
        poisson_ok("damper.poisson", self.poisson)?;
        non_negative("damper.friction", self.friction, "–")?;
        non_negative("damper.gamma_n", self.gamma_n, "kg s⁻¹ m^-1/2")?;
        non_negative("damper.gamma_s", self.gamma_s, "kg s⁻¹ m^-1/2")?;
        if let Some(v) = self.wall_youngs_modulus {
            positive("damper.wall_youngs_modulus", v, "Pa")?;
        }
        if let Some(v) = self.wall_poisson {
            poisson_ok("damper.wall_poisson", v)?;
        }
        for (k, v) in [
            ("damper.wall_friction", self.wall_friction),
            ("damper.wall_gamma_n", self.wall_gamma_n),
            ("damper.wall_gamma_s", self.wall_gamma_s),
        ] {
            if let Some(v) = v {
                non_negative(k, v, "see the key's documentation")?;
            }
        }
        if let Some(v) = self.restitution_speed {
            positive("damper.restitution_speed", v, "m/s")?;
        }
        match (self.contact, self.tangential) {
            (ContactKind::Linear, TangentialKind::Mindlin) => {
                return Err(SceneError::invalid(
                    "damper.tangential",
                    "mindlin",
                    "the Mindlin spring goes with contact = \"hertz-kk\"; with \"linear\" use \"linear-spring\"",
                ))
            }
            (ContactKind::HertzKk, TangentialKind::LinearSpring) => {
                return Err(SceneError::invalid(
                    "damper.tangential",
                    "linear-spring",
                    "the linear spring goes with contact = \"linear\"; with \"hertz-kk\" use \"mindlin\"",
                ))
            }
            _ => {}
        }
        if self.contact == ContactKind::HertzKk {
            self.validate_hertz_restitution()?;
        }
        if self.contact == ContactKind::Linear {
            let e = self.restitution.ok_or_else(|| SceneError::Missing {
                field: "damper.restitution".into(),
                hint: "contact = \"linear\" needs the coefficient of restitution e in (0, 1]"
                    .into(),
            })?;
            for (k, e) in [
                ("damper.restitution", Some(e)),
                ("damper.wall_restitution", self.wall_restitution),
            ] {
                if let Some(e) = e {
                    if !(e > 0.0 && e <= 1.0) {
                        return Err(SceneError::invalid(
                            k,
                            e,
                            "must be in (0, 1] (coefficient of restitution)",
                        ));
                    }
                }
            }
            let y = self.yield_strength.ok_or_else(|| SceneError::Missing {
                field: "damper.yield_strength".into(),
                hint: "contact = \"linear\" needs the grains' yield strength (Pa), e.g. 1.0e9 for steel".into(),
            })?;
            positive("damper.yield_strength", y, "Pa")?;
        }
        if let Some(s) = self.snapshot_interval {
            positive("damper.snapshot_interval", s, "seconds")?;
        }
        if let Some(s) = self.neighbor_skin {
            positive("damper.neighbor_skin", s, "metres")?;
        }
        if let Some(s) = self.settle_time {
            non_negative("damper.settle_time", s, "seconds")?;
        }
        let dist = self.radius_distribution()?;
        let rmax = dist.r_max();
        let side = self.r#box.iter().cloned().fold(f64::INFINITY, f64::min);
        if 2.0 * rmax >= side {
            return Err(SceneError::invalid(
                "damper.radius",
                rmax,
                format!(
                    "largest diameter {:.4e} m does not fit the smallest box side {side:.4e} m",
                    2.0 * rmax
                ),
            ));
        }
        let v_grains = self.count as f64 * 4.0 / 3.0 * std::f64::consts::PI * rmax.powi(3);
        let shape = self.container_shape();
        let v_box = shape.volume_m3(self.r#box);
        if v_grains > 0.58 * v_box {
            return Err(SceneError::invalid(
                "damper.count",
                self.count,
                format!(
                    "{} grains up to R = {rmax:.3e} m fill {:.0} % of the {}; a random packing holds \
                     at most ~58 %: lower count or radius, or enlarge the container",
                    self.count,
                    100.0 * v_grains / v_box,
                    shape.name()
                ),
            ));
        }
        if let Some(bag) = &self.bag {
            self.validate_bag(bag, dist.r_min())?;
        }
        Ok(())
    }

    /// A bag holds grains of one size in a box, packed on the lattice.
    fn validate_bag(&self, bag: &super::bag::BagParams, r_min: f64) -> Result<(), SceneError> {
        if !self.container.is_box() || self.packing != PackingKind::Lattice {
            return Err(SceneError::invalid(
                "damper.bag",
                "(given)",
                "a bag stands in a box (damper.container = \"box\") and its grains are placed on \
                 the lattice (damper.packing = \"lattice\")",
            ));
        }
        bag.validate(self.r#box, r_min)
    }
}
