//! A damper on a rotating part (issue 41, `environment.rotation`): the DEM grains feel the
//! centrifugal and Coriolis accelerations of the turning frame. Checked on a free grain (no
//! wall within reach, no gravity) against the exact reference: in the inertial frame it moves
//! on a straight line X(t) = R0 + (v0 + Ω × R0) t, so in the turning frame
//! R(t) = Rot(−ωt) X(t); and its Jacobi energy ½ m v² − ½ m |Ω × R|² is conserved (the Coriolis
//! force does no work). A code without the Coriolis term, or with its sign flipped, misses the
//! line by centimetres.

use pdamp::dem::{BoxDrive, DemWorld};
use pdamp::model::FrameRotation;
use pdamp::scene::dem::DemParams;
use pdamp::scene::Scene;

const W: f64 = 10.0;

fn free_grain(rotation: FrameRotation, v0: [f64; 3]) -> DemWorld {
    let mut p = DemParams::thesis_b_softened(1000.0);
    p.r#box = [1.0, 1.0, 1.0];
    p.count = 1;
    let still = BoxDrive {
        primary: None,
        amplitude_m: 0.0,
        frequency_hz: 1.0,
        force_n: 0.0,
        direction: [0.0, 0.0, 1.0],
    };
    let mut w = DemWorld::new(
        &pdamp::setup::dem_model(&p).unwrap(),
        still,
        1e-5,
        vec![0.003],
        vec![[0.6, 0.5, 0.5]],
    )
    .unwrap();
    w.gravity = [0.0; 3];
    w.rotation = Some(rotation);
    w.set_velocities(&[v0], &[[0.0; 3]]);
    w.start_drive();
    w
}

#[test]
fn a_free_grain_follows_the_turned_straight_line() {
    let frame = FrameRotation {
        omega_rad_s: [0.0, 0.0, W],
        axis_point_m: [0.5, 0.5, 0.5],
    };
    let v0 = [0.0, 0.2, 0.1];
    let mut w = free_grain(frame, v0);
    let r0 = [0.1, 0.0, 0.0];
    // inertial velocity v0 + Ω × R0
    let vi = [v0[0] - W * r0[1], v0[1] + W * r0[0], v0[2]];
    let jacobi = |w: &DemWorld| {
        let e = w.energy_state();
        e.kinetic_j + e.potential_j
    };
    let e0 = jacobi(&w);
    let mut worst: f64 = 0.0;
    for k in 1..=5000 {
        w.step();
        if k % 500 == 0 {
            let t = w.t;
            let x = [0, 1, 2].map(|d| r0[d] + vi[d] * t);
            let (s, c) = (W * t).sin_cos();
            // Rot(−ωt) about z
            let want = [c * x[0] + s * x[1], -s * x[0] + c * x[1], x[2]];
            let got = [0, 1, 2].map(|d| w.pos[0][d] - 0.5);
            for d in 0..3 {
                worst = worst.max((got[d] - want[d]).abs());
            }
        }
    }
    // the turned line over 0.05 s (half a radian): Verlet with the Coriolis force at the
    // predicted velocity is second order, (ω dt)² ~ 1e-8 of the 0.1 m path; 1e-7 m leaves room
    // and a missing Coriolis term is off by ~ω v t² ≈ 5 mm
    assert!(worst < 1e-7, "worst {worst:e} m");
    let e1 = jacobi(&w);
    assert!(
        (e1 - e0).abs() < 1e-8 * e0.abs(),
        "Jacobi energy {e0} → {e1}"
    );
    eprintln!(
        "free grain in the turning frame: worst {worst:e} m, Jacobi drift {:e}",
        (e1 - e0) / e0
    );
}

#[test]
fn bad_rotations_are_refused_by_name() {
    let base = "[primary]\nmass = 1.0\nstiffness = 1000.0\ndamping = 1.0\n\
                [excitation]\namplitude = 0.001\nfrequency = 5.0\n\
                [damper]\nkind = \"dem\"\nbox = [0.02, 0.02, 0.04]\ncount = 5\nradius = 0.002\nmaterial = \"steel\"\n\
                [run]\nduration = 0.1\n";
    let with = |rot: &str| Scene::from_toml(&format!("{base}[environment]\nrotation = {rot}\n"));
    assert!(with("{ radius = 0.4, rpm = 138.0 }").is_ok());
    for (rot, key) in [
        ("{ radius = 0.4, rpm = -1.0 }", "environment.rotation.rpm"),
        (
            "{ radius = -0.4, rpm = 138.0 }",
            "environment.rotation.radius",
        ),
        // ω²r = (2π·1e5/60)² × 1 m ≈ 1.1e8 m/s² > 1e5 g
        ("{ radius = 1.0, rpm = 1e5 }", "environment.rotation.rpm"),
        (
            "{ radius = 0.4, rpm = 138.0, axis = [0.0, 0.0, 0.0] }",
            "environment.rotation.axis",
        ),
        (
            "{ radius = 0.4, rpm = 138.0, radial = [0.0, 0.0, 1.0] }",
            "environment.rotation.radial",
        ),
        (
            "{ radius = 0.4, rpm = 138.0, axis = [1.0, 0.0, 0.0], radial = [0.0, 1.0, 0.0] }",
            "excitation.direction",
        ),
        ("{ radius = 0.4, rpm = 138.0, speed = 3 }", "speed"),
    ] {
        let e = with(rot).unwrap_err().to_string();
        assert!(e.contains(key), "{rot}: {e}");
    }
    // the one-particle model does not take it
    let impact = base.replace(
        "kind = \"dem\"\nbox = [0.02, 0.02, 0.04]\ncount = 5\nradius = 0.002\nmaterial = \"steel\"",
        "kind = \"impact\"\nmass = 0.1\ngap = 0.01\nrestitution = 0.5",
    );
    let e = Scene::from_toml(&format!(
        "{impact}[environment]\nrotation = {{ radius = 0.4, rpm = 138.0 }}\n"
    ))
    .unwrap_err()
    .to_string();
    assert!(e.contains("environment.rotation"), "{e}");
}

#[test]
fn a_bed_in_a_turning_box_keeps_its_energy_ledger() {
    // 26 steel balls of 4 mm in a 12.5 × 12.5 × 37 mm box at 0.4 m from the axis, 138 rpm
    // (the linear-DEM paper's §3.3 values, in a box), free decay along the axis from −6.5 mm:
    // the ledger closes with the centrifugal potential booked
    let text = "[primary]\nmass = 0.2\nstiffness = 800.0\ndamping = 0.05\ninitial_displacement = -0.0065\n\
                [excitation]\nkind = \"free\"\n\
                [damper]\nkind = \"dem\"\nbox = [0.0125, 0.0125, 0.037]\ncount = 26\nradius = 0.002\n\
                material = \"steel\"\nyoungs_modulus = 2.03e8\nsettle_time = 0.1\n\
                [environment]\nrotation = { radius = 0.4, rpm = 138.0 }\n\
                [run]\nduration = 1.0\n";
    let scene = Scene::from_toml(text).unwrap();
    let s = pdamp::sweep::run_scene(
        &scene,
        &mut pdamp::observe::NullObserver,
        &pdamp::model::RunOptions::summary_only(),
    )
    .unwrap();
    let e = s.energy_balance_relative_error.unwrap();
    assert!(e.abs() < 1e-2, "balance {e}");
    assert!(s.decay.is_some());
}
