//! The bean bag's film (issue 41, part 4, `[damper.bag]`): what a bag must do. It holds its
//! grains when shaken (no grain outside the shell of its nodes), its bonds carry the grains'
//! push at rest (the film in tension, the push on every side node balanced by its bonds), and
//! the energy ledger closes with the bonds' dissipation booked.
//!
//! References: Newton's law at rest (the radial push of the grains on the side nodes equals
//! the bonds' inward pull, to the residual of the settled bed) and the energy balance
//! E − E₀ = W_base − D (the bonds' stored and dissipated energies in it).

use pdamp::dem::run::{initial_world, settle};
use pdamp::dem::{BoxDrive, DemModel, DemWorld};
use pdamp::scene::Scene;

/// A small bag (D = 20 mm, L = 24 mm, nodes of 1.5 mm) of 14 balls of 4 mm in a wide box,
/// the linear law with a soft yield strength (larger steps).
fn model() -> DemModel {
    let text = "[excitation]\namplitude = 0.001\nfrequency = 27.0\n\
         [damper]\nkind = \"dem\"\nbox = [0.04, 0.04, 0.04]\ncount = 14\nradius = 0.002\n\
         material = \"steel\"\ncontact = \"linear\"\nrestitution = 0.75\nfriction = 0.2\n\
         yield_strength = 2.0e8\n\
         [damper.bag]\ndiameter = 0.02\nlength = 0.024\nfilm_thickness = 1e-4\n\
         node_radius = 0.0015\n[run]\nperiods = 10\n";
    let scene = Scene::from_toml(text).unwrap();
    let pdamp::scene::Damper::Dem(p) = &scene.damper else {
        panic!()
    };
    pdamp::setup::dem_model(p).unwrap()
}

fn dt(model: &DemModel, drive: &BoxDrive) -> f64 {
    pdamp::dem::stability::choose_dt(model, drive, None, 0.02)
        .unwrap()
        .0
}

/// The settled bag in its box, held still.
fn settled(model: &DemModel, drive: BoxDrive) -> DemWorld {
    let mut w = initial_world(model, drive, dt(model, &drive), 0.0).unwrap();
    settle(&mut w, 0.4);
    w
}

/// Grain count and the bag's axis (x, y) in the box frame.
fn layout(model: &DemModel) -> (usize, [f64; 2]) {
    let bag = model.bag.as_ref().unwrap();
    (model.grains.len(), bag.geometry.centre_m)
}

#[test]
fn the_bag_holds_its_grains_when_shaken_and_the_ledger_closes() {
    let model = model();
    // Γ = A ω²/g = 1 mm × (2π 27 Hz)² / g ≈ 2.9: the grains fly inside the bag
    let drive = BoxDrive {
        amplitude_m: 0.001,
        frequency_hz: 27.0,
        ..BoxDrive::STILL
    };
    let mut w = settled(&model, drive);
    let (n, c) = layout(&model);
    w.start_drive();
    let start = w.energy_state();
    let steps = (10.0 / 27.0 / w.dt) as usize;
    let mut worst_out: f64 = f64::NEG_INFINITY;
    for k in 0..steps {
        w.step();
        if k % 200 == 0 {
            let o = w.box_origin();
            // the shell of the nodes now: its radius about the axis and its z extent
            let nodes = &w.pos[n..];
            let rho =
                |p: &[f64; 3]| ((p[0] - o[0] - c[0]).powi(2) + (p[1] - o[1] - c[1]).powi(2)).sqrt();
            let shell = nodes.iter().map(rho).fold(0.0, f64::max);
            let (zlo, zhi) = nodes
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |a, p| {
                    (a.0.min(p[2]), a.1.max(p[2]))
                });
            for p in &w.pos[..n] {
                worst_out = worst_out
                    .max(rho(p) - shell)
                    .max(zlo - p[2])
                    .max(p[2] - zhi);
            }
        }
    }
    let (residual, rel) = pdamp::dem::energy::balance(&w.energy_state(), &start, &w.ledger);
    eprintln!(
        "worst grain beyond the shell {worst_out:.3e} m; ledger {rel:.2e} (residual {residual:.2e} J); \
         bag {:.3e} J, collisions {:.3e} J, friction {:.3e} J, base work {:.3e} J",
        w.ledger.bag_j, w.ledger.collision_j, w.ledger.friction_j, w.ledger.base_work_j
    );
    // a grain's centre stays inside the shell of node centres (by at least most of a node
    // radius: it cannot pass between nodes 3 mm apart)
    assert!(
        worst_out < 0.0,
        "a grain left the bag: {worst_out} m beyond its nodes"
    );
    assert!(w.ledger.bag_j > 0.0, "the bonds dissipated nothing");
    assert!(rel < 2e-3, "energy ledger {rel}");
}

#[test]
fn at_rest_the_films_bonds_carry_the_grains_push() {
    let model = model();
    let mut w = settled(&model, BoxDrive::STILL);
    w.settle_drag = 0.0;
    w.refresh();
    let (n, c) = layout(&model);
    let mean_v = w
        .vel
        .iter()
        .map(|v| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt())
        .sum::<f64>()
        / w.len() as f64;
    let bag = w.bag().unwrap();
    let rho_side = bag.bag.geometry.node_circle_m();
    let bonds = bag.forces();
    let (mut push, mut pull) = (0.0, 0.0);
    for ((p, f), b) in w.pos.iter().zip(&w.force).zip(bonds).skip(n) {
        let (dx, dy) = (p[0] - c[0], p[1] - c[1]);
        let r = (dx * dx + dy * dy).sqrt();
        // the side's nodes (not the caps' inner rings)
        if r < 0.9 * rho_side {
            continue;
        }
        let out = |f: [f64; 3]| (f[0] * dx + f[1] * dy) / r;
        let others = [f[0] - b[0], f[1] - b[1], f[2] - b[2]];
        let b = *b;
        push += out(others);
        pull -= out(b);
    }
    let tensions = bag.tensions(&w.pos);
    let stretched = tensions.iter().filter(|&&t| t > 0.0).count();
    let strain = bag
        .bag
        .bonds
        .iter()
        .zip(&tensions)
        .map(|(b, t)| t / b.stiffness_n_m / b.rest_m)
        .fold(0.0, f64::max);
    eprintln!(
        "mean speed {mean_v:.2e} m/s; grains' outward push on the side {push:.4e} N, bonds' pull \
         {pull:.4e} N; {stretched} of {} bonds stretched, largest strain {strain:.2e}",
        tensions.len()
    );
    assert!(mean_v < 1e-3, "not at rest: {mean_v} m/s");
    // the grains press the side outwards (the bed's weight turned sideways) and the film's
    // tension holds them: no walls are near (box 40 mm, bag 20 mm)
    assert!(push > 1e-3, "no outward push: {push} N");
    assert!(
        (pull - push).abs() < 0.05 * push,
        "push {push} N against pull {pull} N"
    );
    // a film in tension, barely stretched (E t = 2e4 N/m against mN loads)
    assert!(
        stretched > 0 && strain < 0.05,
        "{stretched} stretched, strain {strain}"
    );
}

#[test]
fn a_bag_that_cannot_be_built_is_refused_by_its_key() {
    // (bag lines, the key the error must name, a word of the fix)
    let cases = [
        (
            "diameter = 0.05\nlength = 0.024\nfilm_thickness = 1e-4",
            "damper.bag.diameter",
            "fit",
        ),
        (
            "diameter = 0.02\nlength = 0.024\nfilm_thickness = -1e-4",
            "damper.bag.film_thickness",
            "> 0",
        ),
        (
            "diameter = 0.02\nlength = 0.024\nfilm_thickness = 1e-4\nnode_radius = 0.003",
            "damper.bag.node_radius",
            "between",
        ),
        (
            "diameter = 0.02\nlength = 0.024\nfilm_thickness = 1e-4\nfilm_poisson = 0.7",
            "damper.bag.film_poisson",
            "[0, 0.5)",
        ),
        (
            "diameter = 0.02\nlength = 0.024\nfilm_thickness = 1e-4\nfilm_loss_factor = nan",
            "damper.bag.film_loss_factor",
            "η",
        ),
        (
            "diameter = 0.02\nlength = 0.024\nfilm_thickness = 1e-4\ncolour = \"red\"",
            "colour",
            "unknown",
        ),
    ];
    for (bag, key, fix) in cases {
        let text = format!(
            "[excitation]\namplitude = 0.001\nfrequency = 27.0\n\
             [damper]\nkind = \"dem\"\nbox = [0.04, 0.04, 0.04]\ncount = 14\nradius = 0.002\n\
             material = \"steel\"\n[damper.bag]\n{bag}\n[run]\nperiods = 10\n"
        );
        let e = Scene::from_toml(&text).map(|_| ()).unwrap_err().to_string();
        assert!(e.contains(key) && e.contains(fix), "{bag}: {e}");
    }
    // more balls than the bag holds: named by the bag, with the fix
    let text = "[excitation]\namplitude = 0.001\nfrequency = 27.0\n\
         [damper]\nkind = \"dem\"\nbox = [0.04, 0.04, 0.04]\ncount = 80\nradius = 0.002\n\
         material = \"steel\"\n[damper.bag]\ndiameter = 0.02\nlength = 0.024\n\
         film_thickness = 1e-4\nnode_radius = 0.0015\n[run]\nperiods = 10\n";
    let scene = Scene::from_toml(text).unwrap();
    let pdamp::scene::Damper::Dem(p) = &scene.damper else {
        panic!()
    };
    let model = pdamp::setup::dem_model(p).unwrap();
    let e = pdamp::dem::initial_positions(&model)
        .map_err(pdamp::setup::scene_error)
        .map(|_| ())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("damper.bag") && e.contains("do not fit inside the bag"),
        "{e}"
    );
}
