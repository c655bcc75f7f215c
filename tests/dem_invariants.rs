//! Invariants of the DEM step without gravity, walls or drive (rapier-style):
//! - conservative contacts (γ_n = 0, μ = 0): linear momentum exact to round-off, energy
//!   (kinetic + Hertz elastic) conserved to 1e-3 (velocity Verlet, dt = t_s/50);
//! - dissipative contacts with friction: linear momentum to round-off and total angular
//!   momentum Σ m r×v + I ω to O(ζ/R) (fails if torques had the wrong sign or arm, or if the pair force
//!   were not applied once with Newton's third law), and the ledger closes:
//!   T₀ = T + U_el + D_collision + D_friction within 0.5 %;
//! - orientations (unit quaternions) keep norm 1 to 1e-12.
//!
//! 216 grains collapsing onto each other; stiffness softened 1000× (γ rescaled to keep e(v)),
//! which the invariants do not depend on. ~2 s in release mode.

use pdamp::dem::{BoxDrive, DemWorld};
use pdamp::scene::dem::DemParams;
use rand::{RngExt, SeedableRng};

fn cluster(p: &DemParams) -> DemWorld {
    let r = 0.003;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    let c = 0.15;
    let mut pos = vec![];
    let mut vel = vec![];
    for i in 0..6 {
        for j in 0..6 {
            for k in 0..6 {
                let q = [i, j, k]
                    .map(|a| c + (a as f64 - 2.5) * 2.4 * r + rng.random_range(-0.1 * r..0.1 * r));
                vel.push([0, 1, 2].map(|d| -8.0 * (q[d] - c) + rng.random_range(-0.2..0.2)));
                pos.push(q);
            }
        }
    }
    let n = pos.len();
    let still = BoxDrive::STILL;
    let mut w = DemWorld::new(
        &pdamp::setup::dem_model(p).unwrap(),
        still,
        1e-6,
        vec![r; n],
        pos,
    )
    .unwrap();
    w.gravity = [0.0; 3];
    let omega: Vec<[f64; 3]> = (0..n)
        .map(|_| [0, 1, 2].map(|_| rng.random_range(-50.0..50.0)))
        .collect();
    w.set_velocities(&vel, &omega);
    w.refresh();
    w
}

fn params() -> DemParams {
    let mut p = DemParams::thesis_b_softened(1000.0);
    p.r#box = [0.3, 0.3, 0.3];
    p.count = 216;
    p
}

fn angular_momentum(w: &DemWorld) -> [f64; 3] {
    let mut l = [0.0; 3];
    for i in 0..w.len() {
        let (r, v, m) = (w.pos[i], w.vel[i], w.mass[i]);
        let ii = 0.4 * m * w.radius[i] * w.radius[i];
        let rxv = [
            r[1] * v[2] - r[2] * v[1],
            r[2] * v[0] - r[0] * v[2],
            r[0] * v[1] - r[1] * v[0],
        ];
        for d in 0..3 {
            l[d] += m * rxv[d] + ii * w.omega[i][d];
        }
    }
    l
}

fn norm(a: [f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

#[test]
fn conservative_contacts_conserve_momentum_and_energy() {
    let mut p = params();
    p.gamma_n = 0.0;
    p.gamma_s = 0.0;
    p.friction = 0.0;
    let mut w = cluster(&p);
    let p0 = w.momentum();
    let scale: f64 = w.vel.iter().zip(&w.mass).map(|(v, m)| m * norm(*v)).sum();
    let e0 = w.energy_state();
    let mut max_err: f64 = 0.0;
    let mut contacts_seen = false;
    for k in 0..20_000 {
        w.step();
        if k % 500 == 0 {
            let e = w.energy_state();
            contacts_seen |= e.elastic_j > 1e-3 * e0.kinetic_j;
            max_err = max_err.max(
                ((e.kinetic_j + e.rotational_j + e.elastic_j) / (e0.kinetic_j + e0.rotational_j)
                    - 1.0)
                    .abs(),
            );
        }
    }
    assert!(contacts_seen, "the cluster must actually collide");
    let p1 = w.momentum();
    // momentum: exact pairwise cancellation, only round-off (1e-12 of Σ m|v|)
    assert!(norm([p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]]) < 1e-12 * scale);
    // energy: velocity Verlet with dt ≈ t_s/50 keeps the shadow energy; 1e-3 band
    assert!(max_err < 1e-3, "energy drift {max_err}");
}

#[test]
fn friction_and_damping_conserve_momenta_and_close_the_ledger() {
    let mut p = params();
    p.orientations = true;
    let mut w = cluster(&p);
    let p0 = w.momentum();
    let l0 = angular_momentum(&w);
    let scale_p: f64 = w.vel.iter().zip(&w.mass).map(|(v, m)| m * norm(*v)).sum();
    let scale_l: f64 = (0..w.len())
        .map(|i| w.mass[i] * norm(w.pos[i]) * norm(w.vel[i]))
        .sum();
    let e0 = w.energy_state();
    for _ in 0..20_000 {
        w.step();
    }
    let e = w.energy_state();
    let p1 = w.momentum();
    let l1 = angular_momentum(&w);
    assert!(norm([p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]]) < 1e-12 * scale_p);
    // angular momentum: torques −R n × F_s on both spheres balance the moment of F_s up to
    // −ζ n × F_s, because the arms are the radii R_i (2.2.13–2.2.15), not R_i − ζ/2; with
    // ζ/R ~ 1e-3 (softened) the drift measured is ~1e-6 of Σ m|r||v|: 1e-5 band. A sign error
    // of one torque component changes L by ~1e-4 of the scale (checked), 10× the band.
    let dl = norm([l1[0] - l0[0], l1[1] - l0[1], l1[2] - l0[2]]);
    assert!(
        dl < 1e-5 * scale_l,
        "angular momentum changed by {dl:e} (scale {scale_l:e})"
    );
    let d = w.ledger.collision_j + w.ledger.friction_j;
    let t0 = e0.kinetic_j + e0.rotational_j;
    let t1 = e.kinetic_j + e.rotational_j + e.elastic_j;
    assert!(
        w.ledger.friction_j > 0.01 * d && w.ledger.collision_j > 0.01 * d,
        "both losses must act"
    );
    // ledger: T₀ = T + U_el + D within 0.5 % of T₀ (dissipation sampled at half-step velocities)
    assert!(
        ((t1 + d) / t0 - 1.0).abs() < 5e-3,
        "T0 = {t0:e}, T + U + D = {:e}",
        t1 + d
    );
    for q in w.orientation.as_ref().unwrap() {
        assert!((q.quaternion().norm() - 1.0).abs() < 1e-12);
    }
    // spinning grains actually rotated
    assert!(w
        .orientation
        .as_ref()
        .unwrap()
        .iter()
        .any(|q| q.angle() > 0.1));
}

#[test]
fn too_large_time_step_is_reported_as_unstable() {
    // negative control of the stability check: dt = 2 t_s (100× the automatic step) lets two
    // steel spheres overlap deeply in one step; the stiff repulsion then creates energy.
    let mut p = DemParams::thesis_b();
    p.r#box = [0.1, 0.1, 0.1];
    p.count = 2;
    p.gamma_n = 0.0;
    let r = 0.003;
    let still = BoxDrive::STILL;
    let pos = vec![[0.05 - r - 1e-5, 0.05, 0.05], [0.05 + r + 1e-5, 0.05, 0.05]];
    let mut w = DemWorld::new(
        &pdamp::setup::dem_model(&p).unwrap(),
        still,
        4e-5,
        vec![r; 2],
        pos,
    )
    .unwrap();
    w.gravity = [0.0; 3];
    w.set_velocities(&[[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]], &[[0.0; 3]; 2]);
    w.refresh();
    let e0 = w.energy_state().total_j();
    let mut verdict = Ok(());
    for _ in 0..50 {
        w.step();
        let e = w.energy_state().total_j();
        verdict = pdamp::dem::stability::check(&w, e - e0, (e - e0).abs() / e0);
        if verdict.is_err() {
            break;
        }
    }
    let msg = verdict
        .expect_err("a blown-up collision must be reported")
        .to_string();
    assert!(msg.contains("time step"), "{msg}");
    // the same collision with the automatic step is stable and conserves energy to 1e-4
    let mut w = DemWorld::new(
        &pdamp::setup::dem_model(&p).unwrap(),
        still,
        2e-7,
        vec![r; 2],
        vec![[0.05 - r - 1e-5, 0.05, 0.05], [0.05 + r + 1e-5, 0.05, 0.05]],
    )
    .unwrap();
    w.gravity = [0.0; 3];
    w.set_velocities(&[[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]], &[[0.0; 3]; 2]);
    w.refresh();
    for _ in 0..2000 {
        w.step();
    }
    let e = w.energy_state().total_j();
    assert!(pdamp::dem::stability::check(&w, e - e0, (e - e0).abs() / e0).is_ok());
    assert!(((e - e0) / e0).abs() < 1e-4);
}
