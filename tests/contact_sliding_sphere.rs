//! A sphere launched sliding (ω = 0) on the floor decelerates at μg and starts rolling at
//! 5/7 of its initial speed (classical rigid-body result: friction −μmg decelerates the
//! centre and spins the sphere up at 5μg/(2R) until v = ωR, i.e. v = 5/7 v₀).
//!
//! Fails if the frictional torque has the wrong sign or arm (rolling speed ≠ 5/7 v₀), if the
//! slip velocity omits the rotation (never stops sliding), or if I ≠ 2/5 m R².
//! Real steel (scene B), one grain, dt = 2e-7 s: ~0.6 million cheap steps.

use pdamp::dem::{BoxDrive, DemWorld};
use pdamp::scene::dem::DemParams;
use pdamp::units::G;

#[test]
fn sliding_sphere_decelerates_at_mu_g_and_rolls_at_five_sevenths() {
    let mut p = DemParams::thesis_b();
    p.r#box = [2.0, 0.1, 0.1];
    p.count = 1;
    let r = 0.003;
    let still = BoxDrive::STILL;
    let dt = 2e-7;
    let mut w = DemWorld::new(
        &pdamp::setup::dem_model(&p).unwrap(),
        still,
        dt,
        vec![r],
        vec![[0.05, 0.05, r]],
    )
    .unwrap();
    // rest on the floor first (static overlap (mg/k)^{2/3} ≈ 7 nm), damped by γ_n
    for _ in 0..50_000 {
        w.step();
    }
    let v0 = 1.0;
    w.set_velocities(&[[v0, 0.0, 0.0]], &[[0.0; 3]]);
    w.refresh();
    let mu = p.friction;
    // sample v(t) during the sliding phase (ends at t* = (2/7) v0/(μg) ≈ 0.097 s)
    let t_star = 2.0 / 7.0 * v0 / (mu * G);
    let n_slide = (0.8 * t_star / dt) as usize;
    let (mut st, mut sv, mut stt, mut stv, mut n) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for k in 0..n_slide {
        w.step();
        if k % 100 == 0 {
            let t = (k + 1) as f64 * dt;
            let v = w.vel[0][0];
            st += t;
            sv += v;
            stt += t * t;
            stv += t * v;
            n += 1.0;
        }
    }
    let slope = (n * stv - st * sv) / (n * stt - st * st);
    // deceleration μg = 2.94 m/s²: 0.5 % (Coulomb branch exactly μF_n; F_n fluctuates by the
    // vertical contact oscillation only)
    assert!(
        (-slope / (mu * G) - 1.0).abs() < 5e-3,
        "deceleration {} vs μg {}",
        -slope,
        mu * G
    );
    for _ in 0..(0.5 * t_star / dt) as usize {
        w.step();
    }
    let v = w.vel[0][0];
    let wr = w.omega[0][1] * r; // rolling in +x: contact point v − R ω_y = 0
                                // rolling speed 5/7 v0 = 0.714286 m/s: 0.5 % (viscous tail of the slip ~1e-3 m/s)
    assert!(
        (v / (5.0 / 7.0 * v0) - 1.0).abs() < 5e-3,
        "rolling speed {v}"
    );
    assert!(
        (v - wr).abs() < 1e-3 * v0,
        "not rolling without slip: v = {v}, ωR = {wr}"
    );
    // negative control: without friction the sphere keeps sliding at v0
    let mut p0 = p.clone();
    p0.friction = 0.0;
    let mut w0 = DemWorld::new(
        &pdamp::setup::dem_model(&p0).unwrap(),
        still,
        dt,
        vec![r],
        vec![[0.05, 0.05, r]],
    )
    .unwrap();
    for _ in 0..50_000 {
        w0.step();
    }
    w0.set_velocities(&[[v0, 0.0, 0.0]], &[[0.0; 3]]);
    w0.refresh();
    for _ in 0..100_000 {
        w0.step();
    }
    assert!((w0.vel[0][0] - v0).abs() < 1e-9);
}
