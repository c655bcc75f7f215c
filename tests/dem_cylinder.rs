//! A cylindrical cavity (issue 41, `damper.container = "cylinder"`): its curved wall is a wall
//! like the box's (the same contact law along the radial normal), its grains stay inside, the
//! lattice fills only the cylinder, its keys are checked by name, and ParaView gets its shape.
//!
//! References: a ball thrown radially at the curved wall meets it head-on, a one-dimensional
//! collision that must give the restitution of the same ball thrown at a flat box wall (the law
//! is the flat wall's: the curvature is left out of the equivalent radius, module doc of
//! `model::container`), and must come back along its own line; geometry (every grain inside
//! ρ ≤ R_c − r up to the contact overlap).

use pdamp::dem::run::initial_world;
use pdamp::dem::{BoxDrive, DemWorld};
use pdamp::model::{Container, Cylinder};
use pdamp::scene::Scene;

/// One 4 mm steel ball (E ÷ 100) in a container of the scene's `damper` lines, no gravity.
fn one_ball(damper: &str, pos: [f64; 3], vel: [f64; 3]) -> DemWorld {
    let text = format!(
        "[excitation]\namplitude = 0.0\nfrequency = 1.0\n\
         [damper]\nkind = \"dem\"\n{damper}\ncount = 1\nradius = 0.002\nmaterial = \"steel\"\n\
         youngs_modulus = 2.0e9\nrestitution = 0.8\nfriction = 0.3\n[run]\nduration = 0.1\n"
    );
    let scene = Scene::from_toml(&text).unwrap();
    let pdamp::scene::Damper::Dem(p) = &scene.damper else {
        panic!()
    };
    let model = pdamp::setup::dem_model(p).unwrap();
    let mut w = DemWorld::new(&model, BoxDrive::STILL, 2e-8, vec![0.002], vec![pos]).unwrap();
    w.gravity = [0.0; 3];
    w.set_velocities(&[vel], &[[0.0; 3]]);
    w.refresh();
    w
}

/// Runs until the ball has left the wall it hit (no overlap after a contact); returns its
/// velocity then.
fn bounce(w: &mut DemWorld) -> [f64; 3] {
    let mut touched = false;
    for _ in 0..2_000_000 {
        w.step();
        let on = w.wall_overlaps(0).iter().any(|&z| z > 0.0);
        if on {
            touched = true;
        } else if touched {
            return w.vel[0];
        }
    }
    panic!("no bounce");
}

fn norm(a: [f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

#[test]
fn a_ball_thrown_at_the_curved_wall_bounces_as_off_a_flat_one() {
    let v = 0.5;
    // the cylinder along z, D = 12.5 mm: thrown from its axis at angle θ across it
    let theta: f64 = 0.7;
    let (s, c) = theta.sin_cos();
    let cyl = "container = \"cylinder\"\ndiameter = 0.0125\nlength = 0.037";
    let mut w = one_ball(cyl, [0.00625, 0.00625, 0.0185], [v * c, v * s, 0.0]);
    let after = bounce(&mut w);
    let e_curved = norm(after) / v;
    // back along its own line: the velocity antiparallel to the throw
    let along = (after[0] * c + after[1] * s) / norm(after);
    // the same ball thrown at the box's x+ wall
    let boxed = "box = [0.0125, 0.0125, 0.037]";
    let mut b = one_ball(boxed, [0.00625, 0.00625, 0.0185], [v, 0.0, 0.0]);
    let e_flat = norm(bounce(&mut b)) / v;
    eprintln!("e curved {e_curved:.9}, flat {e_flat:.9}, cos to the reversed throw {along:.12}");
    assert!(e_curved > 0.5 && e_curved < 1.0, "{e_curved}");
    assert!((e_curved - e_flat).abs() < 1e-6, "{e_curved} vs {e_flat}");
    assert!(along < -1.0 + 1e-9, "{along}");
}

#[test]
fn a_shaken_bed_stays_inside_the_cylinder_and_closes_its_ledger() {
    // 40 balls, E ÷ 1000, shaken at Γ = Aω²/g ≈ 7 along z in a vertical and a horizontal
    // cylinder; the run's own escape check (a grain more than r beyond a wall) and the ledger
    for axis in ["z", "x"] {
        let text = format!(
            "[excitation]\namplitude = 0.002\nfrequency = 30.0\n\
             [damper]\nkind = \"dem\"\ncontainer = \"cylinder\"\ndiameter = 0.02\nlength = 0.04\n\
             axis = \"{axis}\"\ncount = 40\nradius = 0.002\nmaterial = \"steel\"\n\
             youngs_modulus = 2.0e8\nsettle_time = 0.2\n\
             [run]\nperiods = 15\n"
        );
        let scene = Scene::from_toml(&text).unwrap();
        let s = pdamp::sweep::run_scene(
            &scene,
            &mut pdamp::observe::NullObserver,
            &pdamp::model::RunOptions::summary_only(),
        )
        .unwrap_or_else(|e| panic!("axis {axis}: {e}"));
        let e = s.energy_balance_relative_error.unwrap();
        eprintln!("axis {axis}: ledger {e:e}");
        assert!(e.abs() < 1e-2, "axis {axis}: balance {e}");
        // the bed after the run, geometry by hand: the same scene's world stepped directly
        let pdamp::scene::Damper::Dem(p) = &scene.damper else {
            panic!()
        };
        let model = pdamp::setup::dem_model(p).unwrap();
        let drive = BoxDrive {
            amplitude_m: 0.002,
            frequency_hz: 30.0,
            ..BoxDrive::STILL
        };
        // the box held at u(0) while the bed falls, as a run does
        let mut w = initial_world(&model, drive, 2e-6, drive.base(0.0).0).unwrap();
        w.drive_on = true;
        let Container::Cylinder(c) = model.container else {
            panic!()
        };
        let (u, v) = c.across();
        let mut worst: f64 = 0.0;
        for k in 0..150_000 {
            w.step();
            if k % 100 == 0 {
                let o = w.box_origin();
                for (i, p) in w.pos.iter().enumerate() {
                    let (du, dv) = (p[u] - o[u] - c.radius_m, p[v] - o[v] - c.radius_m);
                    let beyond = (du * du + dv * dv).sqrt() - (c.radius_m - w.radius[i]);
                    worst = worst.max(beyond / w.radius[i]);
                }
            }
        }
        eprintln!("axis {axis}: deepest into the curved wall {worst:.4} r");
        assert!(
            worst > 0.0,
            "axis {axis}: the bed never touched the curved wall"
        );
        // a single ball meeting a wall at 1 m/s overlaps it by 0.04 r at E ÷ 1000 (Hertz); the
        // bed landing on it adds its weight: a tenth of a radius is a wall that holds, a grain
        // passing it would go to r and beyond
        assert!(worst < 0.1, "axis {axis}: {worst} r into the curved wall");
    }
}

#[test]
fn the_bed_of_a_cylinder_is_packed_inside_it() {
    // Els's bore takes its 26 balls (an FCC lattice held 24) and no more than 40
    let c = Cylinder::new(2, 0.0125, 0.037);
    let b = c.bounding_box();
    let p = pdamp::packing::cylinder_rings(&c, 26, 0.002, 0.05, 1).unwrap();
    assert_eq!(p.len(), 26);
    for q in &p {
        assert!(Container::Cylinder(c).holds(b, *q, 0.002), "{q:?}");
    }
    let e = pdamp::packing::cylinder_rings(&c, 41, 0.002, 0.05, 1).unwrap_err();
    assert!(e.hint.contains("cylinder"), "{e}");
}

#[test]
fn cylinder_keys_are_checked_by_name() {
    let base = "[run]\nduration = 0.1\n[excitation]\namplitude = 0.001\nfrequency = 10.0\n\
                [damper]\nkind = \"dem\"\nradius = 0.002\nmaterial = \"steel\"\n";
    let with = |lines: &str| {
        let count = if lines.contains("count") {
            ""
        } else {
            "count = 5\n"
        };
        Scene::from_toml(&format!("{base}{count}{lines}\n"))
    };
    let ok =
        with("container = \"cylinder\"\ndiameter = 0.0125\nlength = 0.037\naxis = \"y\"").unwrap();
    let pdamp::scene::Damper::Dem(p) = &ok.damper else {
        panic!()
    };
    assert_eq!(p.r#box, [0.0125, 0.037, 0.0125]);
    // a saved scene reads back the same (its box the bounding box)
    let again = Scene::from_toml(&ok.to_toml().unwrap()).unwrap();
    assert_eq!(again, ok);
    for (lines, key) in [
        ("container = \"cylinder\"\nlength = 0.037", "damper.diameter"),
        (
            "container = \"cylinder\"\ndiameter = -0.01\nlength = 0.037",
            "damper.diameter",
        ),
        ("container = \"cylinder\"\ndiameter = 0.0125", "damper.length"),
        (
            "container = \"cylinder\"\ndiameter = 0.0125\nlength = 0.037\naxis = \"w\"",
            "damper.axis",
        ),
        (
            "container = \"cylinder\"\ndiameter = 0.0125\nlength = 0.037\nbox = [0.02, 0.02, 0.04]",
            "damper.box",
        ),
        ("box = [0.02, 0.02, 0.04]\ndiameter = 0.0125", "damper.diameter"),
        ("container = \"sphere\"\nbox = [0.02, 0.02, 0.04]", "damper.container"),
        (
            "container = \"cylinder\"\ndiameter = 0.0125\nlength = 0.037\npacking = \"advancing-front\"",
            "damper.packing",
        ),
        // grains wider than the bore
        (
            "container = \"cylinder\"\ndiameter = 0.0035\nlength = 0.037",
            "damper.radius",
        ),
        // more grains than a random packing holds in π R² L (1227 mm³; 60 × 33.5 mm³)
        (
            "container = \"cylinder\"\ndiameter = 0.0125\nlength = 0.01\ncount = 60",
            "damper.count",
        ),
    ] {
        let e = with(lines).unwrap_err().to_string();
        assert!(e.contains(key), "{lines}: {e}");
    }
}

#[test]
fn paraview_gets_the_cylinder() {
    let cyl = "container = \"cylinder\"\ndiameter = 0.0125\nlength = 0.037\naxis = \"x\"";
    let mut w = one_ball(cyl, [0.0185, 0.00625, 0.00625], [0.0; 3]);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("box.vtp");
    pdamp::observe::vtk_xml::write_box_vtp(&w.grain_state(), &path).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("NumberOfPoints=\"96\""), "{text}");
    assert!(text.contains("NumberOfPolys=\"50\""));
    // every point on the bore, R_c from the axis (y = z = 6.25 mm), at x = 0 or L
    let pts: Vec<f64> = text
        .split("format=\"ascii\">")
        .nth(1)
        .unwrap()
        .split("</DataArray>")
        .next()
        .unwrap()
        .split_whitespace()
        .map(|x| x.parse().unwrap())
        .collect();
    assert_eq!(pts.len(), 96 * 3);
    for q in pts.chunks(3) {
        let rho = ((q[1] - 0.00625).powi(2) + (q[2] - 0.00625).powi(2)).sqrt();
        assert!((rho - 0.00625).abs() < 1e-12, "{q:?}");
        assert!(q[0] == 0.0 || (q[0] - 0.037).abs() < 1e-15, "{q:?}");
    }
}
