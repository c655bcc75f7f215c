//! Simplified Coulomb tangential force with viscous regularisation (2.2.12–2.2.15).

use super::lanes::{dot, scale, select3, Real};

/// Tangential force on grain i, opposing the slip velocity v_s of its contact point (N).
///
/// Returns the force vector and the dissipated power −F_s·v_s ≥ 0 (W).
///
/// # Formula
/// F_s = − min(γ_s |v_s| √ζ, μ |F_n|) · v_s/|v_s|  (2.2.12), with
/// v_s = v_t − (R_i ω_i + R_j ω_j) × n, v_t = v_rel − (v_rel·n) n (2.2.13–2.2.15) for n
/// pointing from j to i (the thesis writes n from i to j, hence its + sign).
/// The torque on each sphere is τ = −R n × F_s (same sign for i and j, see `dem`).
///
/// # Units
/// `v_s` m/s, `sqrt_overlap` m^1/2, `f_n` N, `gamma_s` kg s⁻¹ m^-1/2, `friction` μ (–).
///
/// # Parameters
/// Scene B: γ_s = 10980 kg s⁻¹ m^-1/2, μ = 0.3.
///
/// Branch-free ([`Real`]): the no-slip case is a lane selection.
///
/// # Pitfalls
/// No tangential spring: a grain on an incline creeps at the speed where γ_s|v_s|√ζ balances
/// the load, instead of sticking. It is history-free, so no per-contact state is needed.
///
/// # References
/// J. Schäfer, S. Dippel & D. E. Wolf, J. Phys. I France 6, 5 (1996); Sánchez (2012) §2.2.
#[inline(always)]
pub fn coulomb_viscous_force<R: Real>(
    v_s: [R; 3],
    sqrt_overlap: R,
    f_n: R,
    gamma_s: R,
    friction: R,
) -> ([R; 3], R) {
    let vs2 = dot(v_s, v_s);
    let vs = vs2.sqrt();
    let mag = (gamma_s * vs * sqrt_overlap).min(friction * f_n.abs());
    let s = -mag / vs;
    // no slip (|v_s| = 0): no force, and no 0/0
    let slip = vs2.gt(R::splat(0.0));
    let zero = R::splat(0.0);
    (
        select3(slip, scale(s, v_s), [zero; 3]),
        R::select(slip, mag * vs, zero),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn viscous_below_and_coulomb_above_the_limit() {
        // slow slip: viscous branch γ_s |v| √ζ = 10 · 0.01 · 0.1 = 0.01 N < μ F_n = 0.3 N
        let (f, p) = coulomb_viscous_force([0.01, 0.0, 0.0], 0.1, 1.0, 10.0, 0.3);
        assert!((f[0] + 0.01).abs() < 1e-15 && f[1] == 0.0);
        assert!((p - 1e-4).abs() < 1e-15);
        // fast slip: capped at μ F_n = 0.3 N, opposite to v_s
        let (f, _) = coulomb_viscous_force([0.0, 10.0, 0.0], 0.1, 1.0, 10.0, 0.3);
        assert!((f[1] + 0.3).abs() < 1e-12);
        // no slip: no force (no NaN from 0/0)
        let (f, p) = coulomb_viscous_force([0.0; 3], 0.1, 1.0, 10.0, 0.3);
        assert_eq!((f, p), ([0.0; 3], 0.0));
    }
}
