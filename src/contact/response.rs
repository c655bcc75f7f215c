//! One contact response for every contact the DEM computes: grain–grain pairs and grain–wall
//! contacts call the same [`contact_response`], which calls the per-law kernels of this module
//! ([`NormalKernel`], [`TangentialKernel`]) — the functions the tests check against the
//! references (tests/contact_*.rs) and the benchmarks measure (tests/benches/dem.rs).
//!
//! Every kernel is branch-free in the normal part (the laws are selected once per step by the
//! engine through the type parameters); the tangential springs branch only on slip.

use super::coulomb_viscous::coulomb_viscous_force;
use super::hertz_kuwabara_kono::{hertz_elastic_force, hertz_normal_force};
use super::lanes::{cross, dot, scale, select3, sub3, Real};
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
    fn eval<R: Real>(k: R, c: R, overlap_m: R, v_n: R) -> (R, R, R);
}

/// Hertz with the Kuwabara–Kono damping ([`hertz_normal_force`], (2.2.8)).
#[derive(Debug, Clone, Copy)]
pub struct HertzKernel;
impl NormalKernel for HertzKernel {
    #[inline(always)]
    fn eval<R: Real>(k: R, c: R, z: R, v_n: R) -> (R, R, R) {
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
    fn eval<R: Real>(k: R, c: R, z: R, v_n: R) -> (R, R, R) {
        (
            linear_normal_force(k, z, v_n, c),
            linear_elastic_force(k, z),
            R::splat(1.0),
        )
    }
}

/// Inputs of a tangential law for one contact (or one contact per lane).
#[derive(Debug, Clone, Copy)]
pub struct TangentialInput<R = f64> {
    /// Slip velocity of the contact point, i relative to j (m/s).
    pub v_s: [R; 3],
    /// Unit normal from j to i.
    pub normal: [R; 3],
    /// Overlap ζ (m).
    pub overlap_m: R,
    /// Factor of the tangential terms from the normal law (√ζ Hertz, 1 linear).
    pub factor: R,
    /// Total normal force after the attraction policy (N).
    pub f_n: R,
    /// Tangential damping coefficient `c_t` of [`ContactCoefficients`].
    pub c_t: R,
    /// Tangential stiffness factor `k_t` of [`ContactCoefficients`].
    pub k_t: R,
    /// Coulomb friction coefficient μ (–).
    pub friction: R,
    /// Time step (s): the spring's elongation grows by v_s dt per step.
    pub dt: R,
}

/// A tangential-force law; `history` is the contact's spring elongation ξ (m), unused by
/// history-free laws.
pub trait TangentialKernel {
    /// Whether the law has a tangential force at all.
    const ACTIVE: bool;
    /// Whether the law keeps a per-contact spring elongation.
    const HISTORY: bool;
    /// Tangential force on grain i (N) and the power −F_t·v_s booked as friction (W).
    fn eval<R: Real>(c: &TangentialInput<R>, history: &mut [R; 3]) -> ([R; 3], R);
}

/// Frictionless contacts.
#[derive(Debug, Clone, Copy)]
pub struct NoTangential;
impl TangentialKernel for NoTangential {
    const ACTIVE: bool = false;
    const HISTORY: bool = false;
    #[inline(always)]
    fn eval<R: Real>(_: &TangentialInput<R>, _: &mut [R; 3]) -> ([R; 3], R) {
        let z = R::splat(0.0);
        ([z; 3], z)
    }
}

/// The thesis's simplified Coulomb law ([`coulomb_viscous_force`], (2.2.12)), history-free.
#[derive(Debug, Clone, Copy)]
pub struct CoulombViscousKernel;
impl TangentialKernel for CoulombViscousKernel {
    const ACTIVE: bool = true;
    const HISTORY: bool = false;
    #[inline(always)]
    fn eval<R: Real>(c: &TangentialInput<R>, _: &mut [R; 3]) -> ([R; 3], R) {
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
    fn eval<R: Real>(c: &TangentialInput<R>, h: &mut [R; 3]) -> ([R; 3], R) {
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
    fn eval<R: Real>(c: &TangentialInput<R>, h: &mut [R; 3]) -> ([R; 3], R) {
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
/// Branch-free ([`Real`]): the rotation, the cap and the reset are lane selections.
///
/// # Units
/// `v_s` m/s, `normal` unit, `k_t` N/m, `c_t` kg/s, `cap` N, `dt` s, `history` m.
///
/// # References
/// P. A. Cundall & O. D. L. Strack, Géotechnique 29, 47 (1979); R. D. Mindlin &
/// H. Deresiewicz, J. Appl. Mech. 20, 327 (1953); A. Di Renzo & F. P. Di Maio, Chem. Eng.
/// Sci. 59, 525 (2004).
#[inline(always)]
pub fn tangential_spring_force<R: Real>(
    v_s: [R; 3],
    normal: [R; 3],
    k_t: R,
    c_t: R,
    cap: R,
    dt: R,
    history: &mut [R; 3],
) -> ([R; 3], R) {
    let zero = R::splat(0.0);
    let h = *history;
    let hn = dot(h, normal);
    let mut x = sub3(h, scale(hn, normal));
    // rotated: the length of h kept (where x has a length and it changed)
    let l0 = dot(h, h);
    let l1 = dot(x, x);
    let rotate = R::and(l1.gt(zero), l1.ne(l0));
    x = select3(rotate, scale((l0 / l1).sqrt(), x), x);
    for d in 0..3 {
        x[d] = x[d] + v_s[d] * dt;
    }
    let f = [
        -(k_t * x[0] + c_t * v_s[0]),
        -(k_t * x[1] + c_t * v_s[1]),
        -(k_t * x[2] + c_t * v_s[2]),
    ];
    // sliding: the force capped at μ|F_n|, the spring reset to give it
    let f2 = dot(f, f);
    let slide = f2.gt(cap * cap);
    let capped = scale(cap / f2.sqrt(), f);
    let reset = [
        -(capped[0] + c_t * v_s[0]) / k_t,
        -(capped[1] + c_t * v_s[1]) / k_t,
        -(capped[2] + c_t * v_s[2]) / k_t,
    ];
    *history = select3(R::and(slide, k_t.gt(zero)), reset, x);
    let f = select3(slide, capped, f);
    (f, -dot(f, v_s))
}

/// What one contact does to grain i (grain j, if any, gets the opposite force).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ContactResponse<R = f64> {
    /// Total contact force on grain i (N).
    pub force: [R; 3],
    /// n × F_t (N): the torque on grain i is −R_i (n × F_t), on grain j −R_j (n × F_t).
    pub torque_arm: [R; 3],
    /// Power dissipated by the normal damping (F_n − F_el) ζ' (W).
    pub p_collision: R,
    /// Power of the tangential force −F_t·v_s (W).
    pub p_friction: R,
}

/// Kinematics of one contact (or one contact per lane) as the engine sees it.
#[derive(Debug, Clone, Copy, Default)]
pub struct ContactKinematics<R = f64> {
    /// Overlap ζ > 0 (m).
    pub overlap_m: R,
    /// Unit normal from j (or the wall) to i.
    pub normal: [R; 3],
    /// Relative velocity v_i − v_j (m/s) (for a wall, v_i − v_wall).
    pub v_rel: [R; 3],
    /// R_i ω_i + R_j ω_j (m/s) (for a wall, R_i ω_i).
    pub spin: [R; 3],
}

/// The contact response of one grain–grain or grain–wall contact (2.2.8–2.2.15): normal force
/// of the law `N` with the attraction policy (`clamp`: total force ≥ 0), tangential force of
/// the law `T` on the slip velocity v_s = v_t − (R_i ω_i + R_j ω_j) × n (`rotations`: with the
/// spin term), the torque arm and the dissipated powers.
///
/// On `R = f64` one contact; on [`super::lanes::F64x8`] eight, each lane bitwise the `f64`
/// result of its contact (the engine's loops run it so).
#[inline(always)]
pub fn contact_response<N: NormalKernel, T: TangentialKernel, R: Real>(
    k: &ContactKinematics<R>,
    coef: &[R; 4],
    friction: f64,
    clamp: bool,
    rotations: bool,
    dt: f64,
    history: &mut [R; 3],
) -> ContactResponse<R> {
    let (n, vr) = (k.normal, k.v_rel);
    let vrn = dot(vr, n);
    let v_n = -vrn;
    let (raw, fel, ts) = N::eval(coef[0], coef[1], k.overlap_m, v_n);
    let f = if clamp { raw.max(R::splat(0.0)) } else { raw };
    let zero = R::splat(0.0);
    let mut out = ContactResponse {
        force: scale(f, n),
        torque_arm: [zero; 3],
        p_collision: (f - fel) * v_n,
        p_friction: zero,
    };
    if T::ACTIVE {
        let mut vs = sub3(vr, scale(vrn, n));
        if rotations {
            vs = sub3(vs, cross(k.spin, n));
        }
        let input = TangentialInput {
            v_s: vs,
            normal: n,
            overlap_m: k.overlap_m,
            factor: ts,
            f_n: f,
            c_t: coef[2],
            k_t: coef[3],
            friction: R::splat(friction),
            dt: R::splat(dt),
        };
        let (fs, p) = T::eval(&input, history);
        out.p_friction = p;
        out.force = [
            out.force[0] + fs[0],
            out.force[1] + fs[1],
            out.force[2] + fs[2],
        ];
        out.torque_arm = cross(n, fs);
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
