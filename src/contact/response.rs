//! One contact response for every contact the DEM computes: grain–grain pairs and grain–wall
//! contacts call the same [`contact_response`], which calls the per-law kernels of this module
//! ([`NormalKernel`], [`TangentialKernel`]) — the functions the tests check against the
//! references (tests/contact_*.rs) and the benchmarks measure (tests/benches/dem.rs).
//!
//! Every kernel is branch-free in the normal part (the laws are selected once per step by the
//! engine through the type parameters); the tangential springs branch only on slip.

use super::coulomb_viscous::coulomb_viscous_force;
use super::hertz_kuwabara_kono::{hertz_elastic_force, hertz_normal_force};
use super::linear_spring_dashpot::{linear_elastic_force, linear_normal_force};

/// Per-contact coefficients the engine precomputes once per pair at each neighbour rebuild
/// (never in the step): `[k_n, c_n, c_t, k_t]`.
///
/// - `k_n`: normal stiffness (Hertz N m^-3/2, linear N/m);
/// - `c_n`: normal damping (Hertz γ_n kg s⁻¹ m^-1/2, linear c_n kg/s);
/// - `c_t`: tangential damping (γ_s kg s⁻¹ m^-1/2 for the Hertz family, c_s kg/s linear);
/// - `k_t`: tangential stiffness factor (Mindlin 8 G* √R* in N m^-3/2, so k_t = 8 G* √(R* ζ);
///   linear k_s in N/m; 0 for history-free laws).
pub type ContactCoefficients = [f64; 4];

/// A normal-force law: (raw total force, elastic part, factor of the tangential terms).
pub trait NormalKernel {
    /// Returns (raw total force F_n, elastic force F_el, √ζ for Hertz or 1 for linear) for
    /// stiffness `k`, damping `c`, overlap `overlap_m` ζ > 0 (m) and approach speed `v_n` ζ'
    /// (m/s, > 0 approaching).
    fn eval(k: f64, c: f64, overlap_m: f64, v_n: f64) -> (f64, f64, f64);
}

/// Hertz with the Kuwabara–Kono damping ([`hertz_normal_force`], (2.2.8)).
#[derive(Debug, Clone, Copy)]
pub struct HertzKernel;
impl NormalKernel for HertzKernel {
    #[inline(always)]
    fn eval(k: f64, c: f64, z: f64, v_n: f64) -> (f64, f64, f64) {
        (
            hertz_normal_force(k, z, v_n, c),
            hertz_elastic_force(k, z),
            z.sqrt(),
        )
    }
}

/// Linear spring–dashpot ([`linear_normal_force`]).
#[derive(Debug, Clone, Copy)]
pub struct LinearKernel;
impl NormalKernel for LinearKernel {
    #[inline(always)]
    fn eval(k: f64, c: f64, z: f64, v_n: f64) -> (f64, f64, f64) {
        (
            linear_normal_force(k, z, v_n, c),
            linear_elastic_force(k, z),
            1.0,
        )
    }
}

/// Inputs of a tangential law for one contact.
#[derive(Debug, Clone, Copy)]
pub struct TangentialInput {
    /// Slip velocity of the contact point, i relative to j (m/s).
    pub v_s: [f64; 3],
    /// Unit normal from j to i.
    pub normal: [f64; 3],
    /// Overlap ζ (m).
    pub overlap_m: f64,
    /// Factor of the tangential terms from the normal law (√ζ Hertz, 1 linear).
    pub factor: f64,
    /// Total normal force after the attraction policy (N).
    pub f_n: f64,
    /// Tangential damping coefficient `c_t` of [`ContactCoefficients`].
    pub c_t: f64,
    /// Tangential stiffness factor `k_t` of [`ContactCoefficients`].
    pub k_t: f64,
    /// Coulomb friction coefficient μ (–).
    pub friction: f64,
    /// Time step (s): the spring's elongation grows by v_s dt per step.
    pub dt: f64,
}

/// A tangential-force law; `history` is the contact's spring elongation ξ (m), unused by
/// history-free laws.
pub trait TangentialKernel {
    /// Whether the law has a tangential force at all.
    const ACTIVE: bool;
    /// Whether the law keeps a per-contact spring elongation.
    const HISTORY: bool;
    /// Tangential force on grain i (N) and the power −F_t·v_s booked as friction (W).
    fn eval(c: &TangentialInput, history: &mut [f64; 3]) -> ([f64; 3], f64);
}

/// Frictionless contacts.
#[derive(Debug, Clone, Copy)]
pub struct NoTangential;
impl TangentialKernel for NoTangential {
    const ACTIVE: bool = false;
    const HISTORY: bool = false;
    #[inline(always)]
    fn eval(_: &TangentialInput, _: &mut [f64; 3]) -> ([f64; 3], f64) {
        ([0.0; 3], 0.0)
    }
}

/// The thesis's simplified Coulomb law ([`coulomb_viscous_force`], (2.2.12)), history-free.
#[derive(Debug, Clone, Copy)]
pub struct CoulombViscousKernel;
impl TangentialKernel for CoulombViscousKernel {
    const ACTIVE: bool = true;
    const HISTORY: bool = false;
    #[inline(always)]
    fn eval(c: &TangentialInput, _: &mut [f64; 3]) -> ([f64; 3], f64) {
        coulomb_viscous_force(c.v_s, c.factor, c.f_n, c.c_t, c.friction)
    }
}

/// Mindlin (Hertz) tangential spring with history: k_t = 8 G* √(R* ζ)
/// ([`tangential_spring_force`]).
#[derive(Debug, Clone, Copy)]
pub struct MindlinSpringKernel;
impl TangentialKernel for MindlinSpringKernel {
    const ACTIVE: bool = true;
    const HISTORY: bool = true;
    #[inline(always)]
    fn eval(c: &TangentialInput, h: &mut [f64; 3]) -> ([f64; 3], f64) {
        let k_t = c.k_t * c.overlap_m.sqrt();
        tangential_spring_force(
            c.v_s,
            c.normal,
            k_t,
            c.c_t * c.factor,
            c.friction * c.f_n.abs(),
            c.dt,
            h,
        )
    }
}

/// Linear tangential spring with history: constant k_t = k_s ([`tangential_spring_force`]).
#[derive(Debug, Clone, Copy)]
pub struct LinearSpringKernel;
impl TangentialKernel for LinearSpringKernel {
    const ACTIVE: bool = true;
    const HISTORY: bool = true;
    #[inline(always)]
    fn eval(c: &TangentialInput, h: &mut [f64; 3]) -> ([f64; 3], f64) {
        tangential_spring_force(
            c.v_s,
            c.normal,
            c.k_t,
            c.c_t * c.factor,
            c.friction * c.f_n.abs(),
            c.dt,
            h,
        )
    }
}

/// Tangential spring–dashpot with per-contact history and a Coulomb cap (N, W).
///
/// # Formula
/// The elongation ξ is first rotated into the current tangent plane (its normal component
/// removed, its length kept), then ξ ← ξ + v_s dt and F_t = −k_t ξ − c_t v_s. If
/// |F_t| > μ|F_n| the contact slides: F_t ← μ|F_n| F_t/|F_t| and the spring is reset to the
/// elongation that gives that force, ξ = −(F_t + c_t v_s)/k_t (Cundall & Strack 1979;
/// LAMMPS/LIGGGHTS `tangential history`). Returns F_t on grain i and −F_t·v_s (the power of
/// the tangential force, booked as friction; the spring's stored part ½ k_t |ξ|² is the
/// elastic entry of the ledger).
///
/// # Units
/// `v_s` m/s, `normal` unit, `k_t` N/m, `c_t` kg/s, `cap` N, `dt` s, `history` m.
///
/// # References
/// P. A. Cundall & O. D. L. Strack, Géotechnique 29, 47 (1979); R. D. Mindlin &
/// H. Deresiewicz, J. Appl. Mech. 20, 327 (1953); A. Di Renzo & F. P. Di Maio, Chem. Eng.
/// Sci. 59, 525 (2004).
#[inline(always)]
pub fn tangential_spring_force(
    v_s: [f64; 3],
    normal: [f64; 3],
    k_t: f64,
    c_t: f64,
    cap: f64,
    dt: f64,
    history: &mut [f64; 3],
) -> ([f64; 3], f64) {
    let h = *history;
    let hn = h[0] * normal[0] + h[1] * normal[1] + h[2] * normal[2];
    let mut x = [
        h[0] - hn * normal[0],
        h[1] - hn * normal[1],
        h[2] - hn * normal[2],
    ];
    let l0 = h[0] * h[0] + h[1] * h[1] + h[2] * h[2];
    let l1 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
    if l1 > 0.0 && l1 != l0 {
        let s = (l0 / l1).sqrt();
        x = [x[0] * s, x[1] * s, x[2] * s];
    }
    for d in 0..3 {
        x[d] += v_s[d] * dt;
    }
    let mut f = [
        -(k_t * x[0] + c_t * v_s[0]),
        -(k_t * x[1] + c_t * v_s[1]),
        -(k_t * x[2] + c_t * v_s[2]),
    ];
    let f2 = f[0] * f[0] + f[1] * f[1] + f[2] * f[2];
    if f2 > cap * cap {
        let s = cap / f2.sqrt();
        f = [f[0] * s, f[1] * s, f[2] * s];
        if k_t > 0.0 {
            x = [
                -(f[0] + c_t * v_s[0]) / k_t,
                -(f[1] + c_t * v_s[1]) / k_t,
                -(f[2] + c_t * v_s[2]) / k_t,
            ];
        }
    }
    *history = x;
    (f, -(f[0] * v_s[0] + f[1] * v_s[1] + f[2] * v_s[2]))
}

/// What one contact does to grain i (grain j, if any, gets the opposite force).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ContactResponse {
    /// Total contact force on grain i (N).
    pub force: [f64; 3],
    /// n × F_t (N): the torque on grain i is −R_i (n × F_t), on grain j −R_j (n × F_t).
    pub torque_arm: [f64; 3],
    /// Power dissipated by the normal damping (F_n − F_el) ζ' (W).
    pub p_collision: f64,
    /// Power of the tangential force −F_t·v_s (W).
    pub p_friction: f64,
}

/// Kinematics of one contact as the engine sees it.
#[derive(Debug, Clone, Copy, Default)]
pub struct ContactKinematics {
    /// Overlap ζ > 0 (m).
    pub overlap_m: f64,
    /// Unit normal from j (or the wall) to i.
    pub normal: [f64; 3],
    /// Relative velocity v_i − v_j (m/s) (for a wall, v_i − v_wall).
    pub v_rel: [f64; 3],
    /// R_i ω_i + R_j ω_j (m/s) (for a wall, R_i ω_i).
    pub spin: [f64; 3],
}

/// The contact response of one grain–grain or grain–wall contact (2.2.8–2.2.15): normal force
/// of the law `N` with the attraction policy (`clamp`: total force ≥ 0), tangential force of
/// the law `T` on the slip velocity v_s = v_t − (R_i ω_i + R_j ω_j) × n (`rotations`: with the
/// spin term), the torque arm and the dissipated powers.
#[inline(always)]
pub fn contact_response<N: NormalKernel, T: TangentialKernel>(
    k: &ContactKinematics,
    coef: &ContactCoefficients,
    friction: f64,
    clamp: bool,
    rotations: bool,
    dt: f64,
    history: &mut [f64; 3],
) -> ContactResponse {
    let (n, vr) = (k.normal, k.v_rel);
    let vrn = vr[0] * n[0] + vr[1] * n[1] + vr[2] * n[2];
    let v_n = -vrn;
    let (raw, fel, ts) = N::eval(coef[0], coef[1], k.overlap_m, v_n);
    let f = if clamp { raw.max(0.0) } else { raw };
    let mut out = ContactResponse {
        force: [f * n[0], f * n[1], f * n[2]],
        torque_arm: [0.0; 3],
        p_collision: (f - fel) * v_n,
        p_friction: 0.0,
    };
    if T::ACTIVE {
        let mut vs = [vr[0] - vrn * n[0], vr[1] - vrn * n[1], vr[2] - vrn * n[2]];
        if rotations {
            let w = k.spin;
            let wn = [
                w[1] * n[2] - w[2] * n[1],
                w[2] * n[0] - w[0] * n[2],
                w[0] * n[1] - w[1] * n[0],
            ];
            vs = [vs[0] - wn[0], vs[1] - wn[1], vs[2] - wn[2]];
        }
        let input = TangentialInput {
            v_s: vs,
            normal: n,
            overlap_m: k.overlap_m,
            factor: ts,
            f_n: f,
            c_t: coef[2],
            k_t: coef[3],
            friction,
            dt,
        };
        let (fs, p) = T::eval(&input, history);
        out.p_friction = p;
        out.force = [
            out.force[0] + fs[0],
            out.force[1] + fs[1],
            out.force[2] + fs[2],
        ];
        out.torque_arm = [
            n[1] * fs[2] - n[2] * fs[1],
            n[2] * fs[0] - n[0] * fs[2],
            n[0] * fs[1] - n[1] * fs[0],
        ];
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spring_sticks_below_and_slides_at_the_coulomb_limit() {
        let n = [0.0, 0.0, 1.0];
        let mut h = [0.0; 3];
        // sticking: F = −k ξ after one step of v dt
        let (f, _) = tangential_spring_force([1e-3, 0.0, 0.0], n, 1e4, 0.0, 10.0, 1e-3, &mut h);
        assert!((h[0] - 1e-6).abs() < 1e-18 && (f[0] + 1e-2).abs() < 1e-15);
        // sliding: capped at μ F_n = 1e-3 N and the spring reset to F/k
        let mut h = [0.0; 3];
        let (f, p) = tangential_spring_force([1.0, 0.0, 0.0], n, 1e4, 0.0, 1e-3, 1e-3, &mut h);
        assert!((f[0] + 1e-3).abs() < 1e-15 && (h[0] - 1e-7).abs() < 1e-18 && p > 0.0);
        // a history with a normal component is rotated into the tangent plane, length kept
        let mut h = [3e-7, 0.0, 4e-7];
        tangential_spring_force([0.0; 3], n, 1.0, 0.0, 1.0, 1e-3, &mut h);
        assert!((h[0] - 5e-7).abs() < 1e-20 && h[2].abs() < 1e-22);
    }
}
