//! `damper.container`: the DEM damper's cavity, a box (`box = [Lx, Ly, Lz]`, the default) or a
//! circular cylinder:
//!
//! ```toml
//! [damper]
//! kind = "dem"
//! container = "cylinder"
//! diameter = 0.0125   # m, inner
//! length = 0.037      # m, between the end caps
//! axis = "z"          # "x", "y" or "z" (default "z")
//! ```
//!
//! A cylinder's `box` is its bounding box (the length along the axis, the diameter across),
//! filled in before the scene is read, so that everything sized by the box (the neighbour
//! grid, the rotating frame's centre, the packing's lattice) sees the cylinder's extent.

use crate::error::SceneError;
use crate::model::{Container, Cylinder};

use super::{AxisName, ContainerKind, DemParams};

/// Fills a cylinder's `box` (its bounding box) in a raw `[damper]` table (`kind = "dem"`,
/// `container = "cylinder"`). Returns whether the table changed.
///
/// # Errors
/// [`SceneError`] naming the key: an unknown `container`, a cylinder without `diameter` or
/// `length` (or with values that are not positive numbers), an unknown `axis`. A `box` beside
/// a cylinder's keys, and a cylinder's keys in a box, are [`DemParams::validate`]'s to refuse.
pub(crate) fn box_from_cylinder(d: &mut toml::Table) -> Result<bool, SceneError> {
    if d.get("kind").and_then(toml::Value::as_str) != Some("dem") {
        return Ok(false);
    }
    let cylinder = match d.get("container") {
        None => false,
        Some(v) => match v.as_str() {
            Some("box") => false,
            Some("cylinder") => true,
            _ => {
                return Err(SceneError::invalid(
                    "damper.container",
                    v,
                    "must be \"box\" (with damper.box) or \"cylinder\" (with damper.diameter, \
                     damper.length, damper.axis)",
                ))
            }
        },
    };
    // a box (cylinder keys in it are refused by `validate_container`)
    if !cylinder {
        return Ok(false);
    }
    let num = |key: &str| -> Result<f64, SceneError> {
        let v = d.get(key).ok_or_else(|| {
            SceneError::invalid(
                format!("damper.{key}"),
                "(missing)",
                "a cylinder needs damper.diameter and damper.length (m, inner)",
            )
        })?;
        v.as_float()
            .or_else(|| v.as_integer().map(|i| i as f64))
            .filter(|x| x.is_finite() && *x > 0.0)
            .ok_or_else(|| {
                SceneError::invalid(format!("damper.{key}"), v, "must be a number > 0 (m)")
            })
    };
    let (diameter, length) = (num("diameter")?, num("length")?);
    let axis = match d.get("axis") {
        None => AxisName::Z,
        Some(v) => match v.as_str() {
            Some("x") => AxisName::X,
            Some("y") => AxisName::Y,
            Some("z") => AxisName::Z,
            _ => {
                return Err(SceneError::invalid(
                    "damper.axis",
                    v,
                    "must be \"x\", \"y\" or \"z\" (the cylinder's axis)",
                ))
            }
        },
    };
    // a box given (a saved scene's) is checked against the bounding box by
    // `validate_container`
    if d.contains_key("box") {
        return Ok(false);
    }
    let b = Cylinder::new(axis.index(), diameter, length).bounding_box();
    d.insert(
        "box".into(),
        toml::Value::Array(b.iter().map(|&l| toml::Value::Float(l)).collect()),
    );
    Ok(true)
}

impl DemParams {
    /// The cavity's shape in the engine's terms (after [`DemParams::validate`]).
    pub fn container_shape(&self) -> Container {
        match (self.container, self.diameter, self.length) {
            (ContainerKind::Cylinder, Some(d), Some(l)) => Container::Cylinder(Cylinder::new(
                self.axis.unwrap_or(AxisName::Z).index(),
                d,
                l,
            )),
            _ => Container::Box,
        }
    }

    /// The container's keys agree: a cylinder has a diameter and a length whose bounding box
    /// is `box`; a box has none of the cylinder's keys.
    ///
    /// # Errors
    /// [`SceneError`] naming the key.
    pub(super) fn validate_container(&self) -> Result<(), SceneError> {
        if self.container.is_box() {
            let given = [
                ("damper.diameter", self.diameter.is_some()),
                ("damper.length", self.length.is_some()),
                ("damper.axis", self.axis.is_some()),
            ];
            if let Some((k, _)) = given.iter().find(|(_, g)| *g) {
                return Err(SceneError::invalid(
                    *k,
                    "(given)",
                    "is a cylinder's key: set damper.container = \"cylinder\" (or leave it out and \
                     give the box's size as damper.box = [Lx, Ly, Lz])",
                ));
            }
            return Ok(());
        }
        if self.packing == super::PackingKind::AdvancingFront {
            return Err(SceneError::invalid(
                "damper.packing",
                "advancing-front",
                "the advancing-front packing fills boxes only: use \"lattice\" in a cylinder",
            ));
        }
        for (k, v) in [
            ("damper.diameter", self.diameter),
            ("damper.length", self.length),
        ] {
            match v {
                Some(x) if x.is_finite() && x > 0.0 => {}
                _ => {
                    return Err(SceneError::invalid(
                        k,
                        format!("{v:?}"),
                        "a cylinder needs a diameter and a length > 0 (m)",
                    ))
                }
            }
        }
        let b = match self.container_shape() {
            Container::Cylinder(c) => c.bounding_box(),
            Container::Box => self.r#box,
        };
        if self
            .r#box
            .iter()
            .zip(b)
            .any(|(x, l)| (x - l).abs() > 1e-12 * l)
        {
            return Err(SceneError::invalid(
                "damper.box",
                format!("{:?}", self.r#box),
                format!(
                    "a cylinder's box is its bounding box {b:?} m (from damper.diameter and \
                     damper.length): leave damper.box out"
                ),
            ));
        }
        Ok(())
    }
}
