//! Single collisions (two spheres, sphere–wall) against closed forms (SPEC §9):
//! - viscoelastic Hertz (Kuwabara–Kono) restitution e(v) vs Müller & Pöschel (2011);
//! - elastic Hertz contact duration vs 2.868 (m*²/(R* E*² v))^{1/5};
//! - the linear law returns the restitution it was built from, at every speed.
//!
//! Real steel stiffness (scene B); each collision is resolved with ~2000 steps, so the whole
//! file runs in well under a second in release mode.

use pdamp::contact::material::{Material, PairProperties};
use pdamp::contact::restitution::{
    hertz_contact_time, kuwabara_kono_gamma_n, kuwabara_kono_restitution,
    kuwabara_kono_restitution_exact, linear_restitution,
};
use pdamp::contact::{hertz_stiffness, LinearContactParams};
use pdamp::dem::{BoxDrive, DemWorld};
use pdamp::scene::dem::{ContactKind, DemParams};

fn params(gamma_n: f64) -> DemParams {
    let mut p = DemParams::thesis_b();
    p.r#box = [0.1, 0.1, 0.1];
    p.count = 2;
    p.gamma_n = gamma_n;
    p.friction = 0.0;
    p.gamma_s = 0.0;
    p
}

/// Collides two spheres head-on at relative speed v; returns (restitution, contact time).
fn two_sphere(p: &DemParams, v: f64, dt: f64) -> (f64, f64) {
    let r = 0.003;
    let pos = vec![[0.05 - r - 1e-6, 0.05, 0.05], [0.05 + r + 1e-6, 0.05, 0.05]];
    let mut w = DemWorld::new(
        &pdamp::setup::dem_model(p).unwrap(),
        BoxDrive::STILL,
        dt,
        vec![r, r],
        pos,
    )
    .unwrap();
    w.gravity = [0.0; 3];
    w.set_velocities(&[[0.5 * v, 0.0, 0.0], [-0.5 * v, 0.0, 0.0]], &[[0.0; 3]; 2]);
    w.refresh();
    let mut in_contact = 0u64;
    for _ in 0..2_000_000 {
        w.step();
        let d = w.pos[1][0] - w.pos[0][0];
        if d < 2.0 * r {
            in_contact += 1;
        } else if w.vel[1][0] > w.vel[0][0] {
            break;
        }
    }
    ((w.vel[1][0] - w.vel[0][0]) / v, in_contact as f64 * dt)
}

/// Drops one sphere on the floor at speed v (no gravity); returns (restitution, contact time).
fn sphere_wall(p: &DemParams, v: f64, dt: f64) -> (f64, f64) {
    let r = 0.003;
    let mut q = p.clone();
    q.count = 1;
    let mut w = DemWorld::new(
        &pdamp::setup::dem_model(&q).unwrap(),
        BoxDrive::STILL,
        dt,
        vec![r],
        vec![[0.05, 0.05, r + 1e-6]],
    )
    .unwrap();
    w.gravity = [0.0; 3];
    w.set_velocities(&[[0.0, 0.0, -v]], &[[0.0; 3]]);
    w.refresh();
    let mut in_contact = 0u64;
    for _ in 0..2_000_000 {
        w.step();
        if w.pos[0][2] < r {
            in_contact += 1;
        } else if w.vel[0][2] > 0.0 {
            break;
        }
    }
    (w.vel[0][2] / v, in_contact as f64 * dt)
}

fn steel() -> Material {
    Material {
        youngs_modulus: 2.03e11,
        poisson: 0.28,
    }
}

fn mass() -> f64 {
    8030.0 * 4.0 / 3.0 * std::f64::consts::PI * 0.003f64.powi(3)
}

#[test]
fn kuwabara_kono_restitution_matches_mueller_poeschel() {
    let m = mass();
    let pair = PairProperties::new(0.003, m, &steel(), 0.003, m, &steel());
    let wall = PairProperties::new(0.003, m, &steel(), f64::INFINITY, f64::INFINITY, &steel());
    let kp = hertz_stiffness(pair.e_star, pair.r_star);
    let kw = hertz_stiffness(wall.e_star, wall.r_star);
    // γ_n = 3660 (scene B, e ≈ 0.86–0.95) and 20000 (e ≈ 0.54–0.77): inside the formula's
    // accurate range (< 0.1 % for e ≳ 0.75, ~1 % near e ≈ 0.4; Müller & Pöschel 2011).
    for gamma_n in [3660.0, 20000.0] {
        let p = params(gamma_n);
        for v in [0.01, 0.1, 0.5, 1.0, 3.0] {
            let dt = hertz_contact_time(pair.m_star, pair.r_star, pair.e_star, v) / 2000.0;
            let (e, _) = two_sphere(&p, v, dt);
            let want = kuwabara_kono_restitution(kp, gamma_n, pair.m_star, v);
            eprintln!(
                "pair gamma_n={gamma_n} v={v}: e={e:.5} closed form {want:.5} ({:+.3} %)",
                100.0 * (e / want - 1.0)
            );
            // 1 % (issue's tolerance; formula error ≤ ~0.5 % at e ≥ 0.5, time-step error ~1e-4)
            assert!(
                (e / want - 1.0).abs() < 0.01,
                "pair γ_n={gamma_n} v={v}: e={e} want {want}"
            );
            let dtw = hertz_contact_time(wall.m_star, wall.r_star, wall.e_star, v) / 2000.0;
            let (ew, _) = sphere_wall(&p, v, dtw);
            let want_w = kuwabara_kono_restitution(kw, gamma_n, wall.m_star, v);
            eprintln!(
                "wall gamma_n={gamma_n} v={v}: e={ew:.5} closed form {want_w:.5} ({:+.3} %)",
                100.0 * (ew / want_w - 1.0)
            );
            assert!(
                (ew / want_w - 1.0).abs() < 0.01,
                "wall γ_n={gamma_n} v={v}: e={ew} want {want_w}"
            );
        }
    }
    // negative control: restitution falls with speed (a constant e would be the linear law)
    let p = params(20000.0);
    let (e_slow, _) = two_sphere(&p, 0.01, 1e-8);
    let (e_fast, _) = two_sphere(&p, 1.0, 1e-8);
    assert!(e_slow - e_fast > 0.1, "{e_slow} {e_fast}");
}

#[test]
fn elastic_hertz_contact_time() {
    let p = params(0.0);
    let m = mass();
    let pair = PairProperties::new(0.003, m, &steel(), 0.003, m, &steel());
    let wall = PairProperties::new(0.003, m, &steel(), f64::INFINITY, f64::INFINITY, &steel());
    for v in [0.05, 0.5, 2.0] {
        // SPEC §9: t_c = 2.868 (m*²/(R* E*² v))^{1/5}
        let want =
            2.868 * (pair.m_star.powi(2) / (pair.r_star * pair.e_star.powi(2) * v)).powf(0.2);
        let (e, tc) = two_sphere(&p, v, want / 4000.0);
        eprintln!(
            "v={v}: t_c={tc:.5e} Hertz {want:.5e} ({:+.3} %)",
            100.0 * (tc / want - 1.0)
        );
        // 0.2 %: constant 2.868 vs exact 2.86827 (0.01 %) + step counting (1/4000)
        assert!(
            (tc / want - 1.0).abs() < 2e-3,
            "v={v}: t_c={tc} want {want}"
        );
        assert!((e - 1.0).abs() < 1e-6, "elastic: e = {e}");
        let want_w =
            2.868 * (wall.m_star.powi(2) / (wall.r_star * wall.e_star.powi(2) * v)).powf(0.2);
        let (_, tw) = sphere_wall(&p, v, want_w / 4000.0);
        assert!(
            (tw / want_w - 1.0).abs() < 2e-3,
            "wall v={v}: t_c={tw} want {want_w}"
        );
    }
}

#[test]
fn linear_law_returns_its_restitution() {
    let mut p = params(0.0);
    p.contact = ContactKind::Linear;
    p.restitution = Some(0.6);
    p.wall_restitution = Some(0.8);
    p.yield_strength = Some(1.0e9);
    // restitution built for the overlap criterion (SPEC §9): attraction allowed
    p.attractive_normal_force = true;
    let m = mass();
    let pair = PairProperties::new(0.003, m, &steel(), 0.003, m, &steel());
    let lp = LinearContactParams::select(&pair, &steel(), 1.0e9, 0.6).unwrap();
    let tc = std::f64::consts::PI / (lp.k_n / pair.m_star).sqrt();
    for v in [0.01, 0.3, 2.0] {
        let (e, _) = two_sphere(&p, v, tc / 2000.0);
        eprintln!("linear v={v}: e={e:.5} (built for 0.6)");
        // e = 0.6 independent of v: exact for the linear ODE, time-step error ~1e-3
        assert!((e - 0.6).abs() < 3e-3, "v={v}: e={e}");
        let (ew, _) = sphere_wall(&p, v, tc / 2000.0);
        assert!((ew - 0.8).abs() < 3e-3, "wall v={v}: e={ew}");
    }
    assert!((linear_restitution(lp.k_n, lp.c_n, pair.m_star) - 0.6).abs() < 1e-12);
    // with the force clamped at 0 the grains separate earlier and e is higher (documented)
    p.attractive_normal_force = false;
    let (e_clamped, _) = two_sphere(&p, 0.3, tc / 2000.0);
    assert!(e_clamped > 0.62, "{e_clamped}");
}

#[test]
fn kuwabara_kono_damping_from_a_restitution_round_trips() {
    // inverse of the exact forward map: γ_n → e(v) → γ_n to 1e-9 (e > 0.01)
    let m = mass();
    let pair = PairProperties::new(0.003, m, &steel(), 0.003, m, &steel());
    let k = hertz_stiffness(pair.e_star, pair.r_star);
    for gamma_n in [10.0, 3660.0, 20000.0, 1e5] {
        for v in [0.01, 1.0, 5.0] {
            let e = kuwabara_kono_restitution_exact(k, gamma_n, pair.m_star, v);
            if e < 0.01 {
                continue;
            }
            let g = kuwabara_kono_gamma_n(k, pair.m_star, v, e).unwrap();
            assert!((g / gamma_n - 1.0).abs() < 1e-9, "γ_n {gamma_n} v {v}: {g}");
        }
    }
    assert_eq!(kuwabara_kono_gamma_n(k, pair.m_star, 1.0, 1.0), Some(0.0));
    for bad in [0.0, -0.1, 1.01, f64::NAN] {
        assert_eq!(
            kuwabara_kono_gamma_n(k, pair.m_star, 1.0, bad),
            None,
            "{bad}"
        );
    }
}

#[test]
fn a_scene_restitution_is_what_the_simulated_collision_gives() {
    // `restitution = 0.9` at `restitution_speed = 0.5` m/s with hertz-kk: the DEM's own
    // collision at 0.5 m/s rebounds with e = 0.9 within 1 % (grain–grain and grain–wall; the
    // wall from the same e through its own E*, R*, m*); at 0.05 m/s the grains bounce more
    // (viscoelastic e(v)), so the derived damping is not a constant-e law.
    let mut p = params(0.0);
    p.restitution = Some(0.9);
    p.restitution_speed = Some(0.5);
    p.validate().unwrap();
    let m = mass();
    let pair = PairProperties::new(0.003, m, &steel(), 0.003, m, &steel());
    let wall = PairProperties::new(0.003, m, &steel(), f64::INFINITY, f64::INFINITY, &steel());
    let dt = hertz_contact_time(pair.m_star, pair.r_star, pair.e_star, 0.5) / 2000.0;
    let (e, _) = two_sphere(&p, 0.5, dt);
    assert!((e / 0.9 - 1.0).abs() < 0.01, "pair e = {e}");
    let dtw = hertz_contact_time(wall.m_star, wall.r_star, wall.e_star, 0.5) / 2000.0;
    let (ew, _) = sphere_wall(&p, 0.5, dtw);
    assert!((ew / 0.9 - 1.0).abs() < 0.01, "wall e = {ew}");
    let (e_slow, _) = two_sphere(&p, 0.05, dt);
    assert!(e_slow > e + 0.02, "{e_slow} vs {e}");
    // a restitution and the damping it replaces together are refused, naming both keys
    let mut both = p.clone();
    both.gamma_n = 3660.0;
    let err = both.validate().unwrap_err().to_string();
    assert!(
        err.contains("damper.restitution") && err.contains("gamma_n"),
        "{err}"
    );
}
