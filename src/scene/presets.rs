//! Named scenes with their provenance (SPEC §6). The files under `data/scenes/` are the same
//! presets in TOML; `tests/scene_presets.rs`-style checks keep them in sync.

use super::{Damper, Excitation, ImpactParams, Primary, Run, Scene};

impl Scene {
    /// One-particle equivalent of the thesis's scene B (Sánchez 2012 §3.2, chapters 4–5):
    /// M = 2.37 kg, K = 21500 N/m, C = 7.6 N s/m (f0 = 15.16 Hz), U = 4.5 mm, the 250 steel
    /// spheres replaced by one particle of m_p = 0.227 kg with gap 0.0835 m and e = 0,
    /// 13.12 s per frequency, f = 15 Hz.
    pub fn thesis_b_impact() -> Scene {
        Scene {
            gravity: crate::units::G,
            primary: Some(Primary::new(2.37, 21500.0, 7.6)),
            excitation: Excitation::base(0.0045, 15.0),
            damper: Damper::Impact(ImpactParams {
                mass: 0.227,
                gap: 0.0835,
                restitution: 0.0,
                initial_height: 0.0,
                initial_velocity: 0.0,
            }),
            run: Run::with_duration(13.12),
            outputs: Default::default(),
            environment: Default::default(),
        }
    }

    /// The primary of scene B alone (no damper): the reference system of SPEC §1.
    pub fn primary_only() -> Scene {
        Scene {
            damper: Damper::None,
            ..Scene::thesis_b_impact()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scene_files_match_the_presets() {
        let b = Scene::from_toml(include_str!("../../data/scenes/thesis_b_impact.toml")).unwrap();
        assert_eq!(b, Scene::thesis_b_impact());
        let p = Scene::from_toml(include_str!("../../data/scenes/primary_only.toml")).unwrap();
        assert_eq!(p, Scene::primary_only());
        let bb = Scene::from_toml(include_str!("../../data/scenes/bouncing_ball.toml")).unwrap();
        assert!(bb.primary.is_none());
        // Γ = U (2π f)²/g = 1.50 as the file says
        let gamma = bb.excitation.amplitude * bb.excitation.omega_rad_s().powi(2) / bb.gravity;
        assert!((gamma - 1.5).abs() < 1e-3, "{gamma}");
    }

    #[test]
    fn thesis_b_natural_frequency() {
        // SPEC §6: f0 = 15.16 Hz for M = 2.37 kg, K = 21500 N/m
        let f0 = Scene::thesis_b_impact()
            .primary
            .unwrap()
            .natural_frequency_hz();
        assert!((f0 - 15.16).abs() < 0.005);
    }
}
