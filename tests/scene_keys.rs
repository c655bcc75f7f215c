//! Every scene-key constant of `pdamp::scene::keys` is a key the scene parser accepts: set on
//! the scene file it belongs to (the impact or the DEM scene B) with a valid value, the scene
//! parses and the value arrives; a misspelt key is rejected (so the check has teeth).

use pdamp::scene::keys::*;
use pdamp::scene::{parse_assignment, SceneSource};

const IMPACT: &str = include_str!("../data/scenes/thesis_b_impact.toml");
const DEM: &str = include_str!("../data/scenes/thesis_b_soft.toml");

fn accepts(scene: &str, key: &str, value: &str) -> Result<(), String> {
    let src = SceneSource::parse(scene).map_err(|e| e.to_string())?;
    let ov = parse_assignment(&format!("{key}={value}")).map_err(|e| e.to_string())?;
    src.scene(&[ov]).map(|_| ()).map_err(|e| e.to_string())
}

#[test]
fn every_key_constant_is_accepted_by_the_scene_parser() {
    let cases: [(&str, &str, &str); 15] = [
        (IMPACT, EXCITATION_FREQUENCY, "12.5"),
        (IMPACT, EXCITATION_AMPLITUDE, "0.003"),
        (IMPACT, DAMPER_GAP, "0.05"),
        (IMPACT, DAMPER_RESTITUTION, "0.8"),
        (IMPACT, RUN_DURATION, "2.0"),
        (IMPACT, RUN_PERIODS, "100"),
        (IMPACT, RUN_SAMPLE_INTERVAL, "0.001"),
        (DEM, DAMPER_COUNT, "20"),
        (DEM, DAMPER_RADIUS, "0.003"),
        (DEM, DAMPER_BOX, "[0.03675,0.03675,0.1225]"),
        (DEM, DAMPER_GAMMA_N, "100.0"),
        (DEM, DAMPER_SEED, "3"),
        (DEM, DAMPER_GAMMA_S, "300.0"),
        (DEM, DAMPER_YOUNGS_MODULUS, "2.03e8"),
        (DEM, RUN_DT_FRACTION, "0.02"),
    ];
    for (scene, key, value) in cases {
        accepts(scene, key, value).unwrap_or_else(|e| panic!("{key}={value}: {e}"));
    }
    // the parser does check names: a misspelt key of each table is rejected
    for key in ["excitation.frequenzy", "damper.gapp", "run.duratoin"] {
        assert!(accepts(IMPACT, key, "1.0").is_err(), "{key} was accepted");
    }
    assert!(accepts(DEM, "damper.gama_n", "1.0").is_err());
}
