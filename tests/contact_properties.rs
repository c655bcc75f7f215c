//! Properties of the contact laws (proptest, STYLE §13), over random overlaps, velocities and
//! materials in physical ranges:
//! - the kernels of `src/contact/` that the DEM's loops call (`hertz_normal_force`,
//!   `linear_normal_force` and their elastic parts, `AttractionPolicy::apply`,
//!   `coulomb_viscous_force`): the damping part of the normal force never does positive work
//!   on the approach (dissipated power (F_n − F_el) ζ' ≥ 0, the ledger's collision term), the
//!   clamped normal force is never attractive, friction opposes the slip within the Coulomb
//!   limit and dissipates exactly −F_s·v_s ≥ 0;
//! - two grains and one grain at a wall assembled by `DemWorld` (the engine itself, Hertz or
//!   linear laws, rotations on): the pair forces are equal and opposite (normal and
//!   tangential), each torque is the lever arm to the contact point crossed with that grain's
//!   force, the power of all contact forces and torques equals the normal force's power minus
//!   the friction dissipation the ledger books, and both booked powers are ≥ 0.
//!
//! How wrong code fails: a flipped damping sign makes (F_n − F_el) ζ' < 0 on approach; a
//! missing clamp gives F_n < 0 while separating fast; friction along the slip, or a slip
//! velocity built with +ω × n instead of −ω × n, breaks −F_s·v_s ≥ 0 and the power identity;
//! a torque with the wrong sign or arm breaks the lever-arm check; a pair force applied
//! twice or to one grain only breaks F_i = −F_j.

use pdamp::contact::{
    coulomb_viscous_force, hertz_elastic_force, hertz_normal_force, linear_elastic_force,
    linear_normal_force, AttractionPolicy,
};
use pdamp::dem::{BoxDrive, DemWorld};
use pdamp::scene::dem::{ContactKind, DemParams};
use proptest::prelude::*;

type V3 = [f64; 3];

fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn norm(a: V3) -> f64 {
    dot(a, a).sqrt()
}
fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn scale(s: f64, a: V3) -> V3 {
    [s * a[0], s * a[1], s * a[2]]
}
fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// log-uniform on [10^lo, 10^hi]
fn log_uniform(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo..hi).prop_map(|e| 10f64.powf(e))
}

fn vec3(max: f64) -> impl Strategy<Value = V3> {
    [-max..max, -max..max, -max..max]
}

/// A unit vector, uniform enough for the purpose (a random direction, rejected near 0).
fn unit() -> impl Strategy<Value = V3> {
    vec3(1.0)
        .prop_filter("not too short", |v| norm(*v) > 0.1)
        .prop_map(|v| scale(1.0 / norm(v), v))
}

/// The raw total and the elastic normal force of one law, as the DEM's loops compute them.
fn normal_forces(hertz: bool, k_n: f64, z: f64, v_n: f64, damping: f64) -> (f64, f64) {
    if hertz {
        (
            hertz_normal_force(k_n, z, v_n, damping),
            hertz_elastic_force(k_n, z),
        )
    } else {
        (
            linear_normal_force(k_n, z, v_n, damping),
            linear_elastic_force(k_n, z),
        )
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    /// Hertz: k_n = (4/3) E* √R* from E* ∈ [1e6, 2e11] Pa, R* ∈ [0.25, 5] mm → 1e4–2e10
    /// N m^-3/2, γ_n ∈ [0, 1e5] (steel 3660); linear: k_n ∈ [1e3, 1e9] N/m, c_n ∈ [0, 100]
    /// kg/s. Overlaps 1 nm–0.1 mm, ζ' within ±10 m/s.
    #[test]
    fn normal_damping_dissipates_and_the_clamp_never_attracts(
        hertz in any::<bool>(),
        k_hertz in log_uniform(4.0, 10.3),
        k_linear in log_uniform(3.0, 9.0),
        gamma in 0.0..1e5f64,
        c_n in 0.0..100.0f64,
        z in log_uniform(-9.0, -4.0),
        v_n in -10.0..10.0f64,
    ) {
        let (k, damping) = if hertz { (k_hertz, gamma) } else { (k_linear, c_n) };
        let (raw, elastic) = normal_forces(hertz, k, z, v_n, damping);
        prop_assert!(elastic > 0.0);
        for policy in [AttractionPolicy::Clamp, AttractionPolicy::Allow] {
            let f = policy.apply(raw);
            // the collision ledger's term: power taken out of the contact's mechanical energy
            let dissipated = (f - elastic) * v_n;
            prop_assert!(dissipated >= 0.0, "{policy:?}: (F − F_el) ζ' = {dissipated:e}");
        }
        let clamped = AttractionPolicy::Clamp.apply(raw);
        prop_assert!(clamped >= 0.0, "clamped F_n = {clamped:e}");
        // the clamp changes nothing while the raw force is repulsive
        if raw >= 0.0 {
            prop_assert_eq!(clamped, raw);
        }
    }

    /// Slip velocities within ±5 m/s, √ζ from ζ ∈ [1 nm, 0.1 mm] (Hertz) or 1 (linear),
    /// F_n ∈ [0, 1e4] N, γ_s ∈ [0, 1e5], μ ∈ [0, 1].
    #[test]
    fn friction_opposes_slip_within_the_coulomb_limit(
        v_s in vec3(5.0),
        z in log_uniform(-9.0, -4.0),
        hertz in any::<bool>(),
        f_n in 0.0..1e4f64,
        gamma_s in 0.0..1e5f64,
        mu in 0.0..1.0f64,
    ) {
        let factor = if hertz { z.sqrt() } else { 1.0 };
        let (fs, p) = coulomb_viscous_force(v_s, factor, f_n, gamma_s, mu);
        let speed = norm(v_s);
        let mag = norm(fs);
        // friction dissipation ≥ 0 and equal to the work the force does against the slip
        prop_assert!(p >= 0.0, "P = {p:e}");
        let against = -dot(fs, v_s);
        prop_assert!((p - against).abs() <= 1e-12 * p.max(1e-300), "{p:e} vs {against:e}");
        // Coulomb limit and the viscous branch below it
        prop_assert!(mag <= mu * f_n * (1.0 + 1e-12), "|F_s| = {mag:e} > μ F_n = {:e}", mu * f_n);
        prop_assert!(mag <= gamma_s * speed * factor * (1.0 + 1e-12) + 1e-300);
        // antiparallel to the slip: |F_s × v_s| ≈ 0
        prop_assert!(norm(cross(fs, v_s)) <= 1e-12 * mag * speed + 1e-300);
        // seen from the other grain the slip is −v_s: equal and opposite force, same power
        let (fj, pj) = coulomb_viscous_force(scale(-1.0, v_s), factor, f_n, gamma_s, mu);
        prop_assert_eq!(fj, scale(-1.0, fs));
        prop_assert_eq!(pj, p);
    }
}

// ---------------------------------------------------------------------------------------
// The engine: contacts assembled by DemWorld

/// Material and laws of a random bed: E ∈ [1e7, 3e11] Pa, ν ∈ [0, 0.49], ρ ∈ [1000, 2e4]
/// kg/m³, μ ∈ {0} ∪ (0, 1], γ_n ∈ [0, 2e4], γ_s ∈ [0, 5e4] (Hertz), e ∈ [0.05, 1] and
/// Y ∈ [1e7, 2e9] Pa (linear), attraction allowed or clamped.
#[derive(Debug, Clone)]
struct Bed {
    youngs_modulus: f64,
    poisson: f64,
    density: f64,
    friction: f64,
    gamma_n: f64,
    gamma_s: f64,
    linear: bool,
    restitution: f64,
    yield_strength: f64,
    attractive: bool,
}

fn bed() -> impl Strategy<Value = Bed> {
    (
        (
            log_uniform(7.0, 11.5),
            0.0..0.49f64,
            1000.0..2.0e4f64,
            prop_oneof![1 => Just(0.0), 4 => 0.01..1.0f64],
        ),
        (0.0..2e4f64, 0.0..5e4f64),
        (any::<bool>(), 0.05..1.0f64, log_uniform(7.0, 9.3)),
        any::<bool>(),
    )
        .prop_map(
            |(
                (youngs_modulus, poisson, density, friction),
                (gamma_n, gamma_s),
                lin,
                attractive,
            )| {
                Bed {
                    youngs_modulus,
                    poisson,
                    density,
                    friction,
                    gamma_n,
                    gamma_s,
                    linear: lin.0,
                    restitution: lin.1,
                    yield_strength: lin.2,
                    attractive,
                }
            },
        )
}

const BOX: f64 = 0.06;

fn params(b: &Bed, count: usize) -> DemParams {
    let mut p = DemParams::thesis_b();
    p.count = count;
    p.r#box = [BOX; 3];
    p.youngs_modulus = b.youngs_modulus;
    p.poisson = b.poisson;
    p.density = b.density;
    p.friction = b.friction;
    p.gamma_n = b.gamma_n;
    p.gamma_s = b.gamma_s;
    if b.linear {
        p.contact = ContactKind::Linear;
        p.restitution = Some(b.restitution);
        p.yield_strength = Some(b.yield_strength);
    }
    p.attractive_normal_force = b.attractive;
    p.rotations = true;
    p
}

/// A world without gravity or drive holding grains of `radius` at `pos` with velocities
/// `vel` and angular velocities `omega`, the box floor at 0 moving at `box_v` (m/s).
fn world(
    b: &Bed,
    radius: Vec<f64>,
    pos: Vec<V3>,
    vel: &[V3],
    omega: &[V3],
    box_v: f64,
) -> DemWorld {
    let still = BoxDrive::STILL;
    let model = pdamp::setup::dem_model(&params(b, radius.len())).expect("valid bed");
    let mut w = DemWorld::new(&model, still, 1e-7, radius, pos).unwrap();
    w.gravity = [0.0; 3];
    w.box_v = box_v;
    w.set_velocities(vel, omega);
    w
}

/// |a − b| within `rel` of `scale` (plus the smallest normal number, for a zero scale).
fn close(a: V3, b: V3, rel: f64, scale: f64) -> bool {
    norm(sub(a, b)) <= rel * scale + f64::MIN_POSITIVE
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Two grains of R ∈ [0.5, 5] mm overlapping by 1e-6–2 % of R_i + R_j about the box
    /// centre (far from the walls), along a random normal; velocities within ±2 m/s,
    /// angular velocities within ±500 rad/s.
    #[test]
    fn pair_forces_are_antisymmetric_torques_consistent_and_dissipative(
        b in bed(),
        r in [0.0005..0.005f64, 0.0005..0.005f64],
        n in unit(),
        frac in log_uniform(-6.0, -1.7),
        vel in [vec3(2.0), vec3(2.0)],
        omega in [vec3(500.0), vec3(500.0)],
    ) {
        let c = [0.5 * BOX; 3];
        let dist = (r[0] + r[1]) * (1.0 - frac);
        let pos = vec![add(c, scale(0.5 * dist, n)), sub(c, scale(0.5 * dist, n))];
        let mut w = world(&b, r.to_vec(), pos, &vel, &omega, 0.0);
        let (p_coll, p_fric) = w.compute_forces();
        let (fi, fj) = (w.force[0], w.force[1]);
        let (ti, tj) = (w.torque[0], w.torque[1]);
        let f_mag = norm(fi);
        // Newton's third law, normal and tangential parts together (round-off only)
        prop_assert!(close(fi, scale(-1.0, fj), 1e-14, f_mag), "F_i {fi:?}, F_j {fj:?}");
        // normal part along n (from j to i): repulsive unless attraction is allowed
        let f_n = dot(fi, n);
        let v_n = -dot(sub(vel[0], vel[1]), n);
        if !b.attractive {
            prop_assert!(f_n >= -1e-12 * f_mag, "attractive F_n = {f_n:e} with the clamp");
        }
        // approaching grains always repel (this also proves the contact was evaluated)
        if v_n >= 0.0 {
            prop_assert!(f_n > 0.0, "approach at {v_n} m/s without a repulsive force: {fi:?}");
        }
        // torques: lever arm from each centre to the contact point × that grain's force
        let arm_i = scale(-r[0], n);
        let arm_j = scale(r[1], n);
        prop_assert!(close(ti, cross(arm_i, fi), 1e-10, r[0] * f_mag), "τ_i {ti:?}");
        prop_assert!(close(tj, cross(arm_j, fj), 1e-10, r[1] * f_mag), "τ_j {tj:?}");
        // the ledger's powers are dissipations
        prop_assert!(p_coll >= 0.0, "collision power {p_coll:e}");
        prop_assert!(p_fric >= 0.0, "friction power {p_fric:e}");
        // power of the contact forces and torques on the grains = the normal force's power on
        // the approach (−F_n ζ') minus the friction dissipation the ledger books
        let power = dot(fi, vel[0]) + dot(fj, vel[1]) + dot(ti, omega[0]) + dot(tj, omega[1]);
        let want = -f_n * v_n - p_fric;
        let size = f_mag * (norm(vel[0]) + norm(vel[1]))
            + norm(ti) * norm(omega[0])
            + norm(tj) * norm(omega[1]);
        prop_assert!(
            (power - want).abs() <= 1e-9 * size + f64::MIN_POSITIVE,
            "power {power:e} vs −F_n ζ' − P_fric = {want:e}"
        );
    }

    /// One grain (R ∈ [0.5, 5] mm) overlapping one of the six walls by 1e-6–2 % of R, the box
    /// moving vertically at ±1 m/s; velocities within ±2 m/s, ω within ±500 rad/s.
    #[test]
    fn wall_forces_push_into_the_box_and_dissipate(
        b in bed(),
        r in 0.0005..0.005f64,
        wall in 0usize..6,
        frac in log_uniform(-6.0, -1.7),
        vel in vec3(2.0),
        omega in vec3(500.0),
        box_v in -1.0..1.0f64,
    ) {
        // wall `wall`: axis wall/2, inward normal +e (low side) or −e (high side)
        let axis = wall / 2;
        let sign = if wall % 2 == 0 { 1.0 } else { -1.0 };
        let mut n = [0.0; 3];
        n[axis] = sign;
        let mut pos = [0.5 * BOX; 3];
        pos[axis] = if sign > 0.0 { r * (1.0 - frac) } else { BOX - r * (1.0 - frac) };
        let mut w = world(&b, vec![r], vec![pos], &[vel], &[omega], box_v);
        let (p_coll, p_fric) = w.compute_forces();
        let (f, t) = (w.force[0], w.torque[0]);
        let f_mag = norm(f);
        let f_n = dot(f, n);
        let v_rel = [vel[0], vel[1], vel[2] - box_v];
        let v_n = -dot(v_rel, n);
        if !b.attractive {
            prop_assert!(f_n >= -1e-12 * f_mag, "attractive wall force {f_n:e}");
        }
        if v_n >= 0.0 {
            prop_assert!(f_n > 0.0, "approach at {v_n} m/s without a repulsive force: {f:?}");
        }
        // the grains' force on the box is the reaction of the floor's and ceiling's forces
        if axis == 2 {
            prop_assert!((w.grain_force_n + f[2]).abs() <= 1e-14 * f_mag);
        }
        prop_assert!(close(t, cross(scale(-r, n), f), 1e-10, r * f_mag), "τ {t:?}");
        prop_assert!(p_coll >= 0.0, "collision power {p_coll:e}");
        prop_assert!(p_fric >= 0.0, "friction power {p_fric:e}");
        // relative to the box (which moves along z): power identity as for a pair
        let power = dot(f, v_rel) + dot(t, omega);
        let want = -f_n * v_n - p_fric;
        let size = f_mag * norm(v_rel) + norm(t) * norm(omega);
        prop_assert!(
            (power - want).abs() <= 1e-9 * size + f64::MIN_POSITIVE,
            "power {power:e} vs −F_n ζ' − P_fric = {want:e}"
        );
    }
}
