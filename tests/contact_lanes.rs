//! The contact kernels on eight lanes ([`F64x8`], what the DEM loops run) against the same
//! kernels on `f64` (what tests/contact_*.rs check against the references): every lane must be
//! bitwise the scalar result of its contact, for every normal × tangential law, with and
//! without the clamp and rotations, on contacts that stick, slide, have no slip, carry a
//! spring history with a normal component, or are being pulled apart (raw force < 0).

use pdamp::contact::lanes::{F64x8, Lanes};
use pdamp::contact::response::{
    contact_response, ContactKinematics, ContactResponse, CoulombViscousKernel, HertzKernel,
    LinearKernel, LinearSpringKernel, MindlinSpringKernel, NoTangential, NormalKernel,
    TangentialKernel,
};
use proptest::prelude::*;

/// One contact: kinematics, coefficients [k_n, c_n, c_t, k_t] and spring history.
type Contact = (ContactKinematics, [f64; 4], [f64; 3]);

fn unit(v: [f64; 3]) -> [f64; 3] {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|x| x / n)
}

fn contact() -> impl Strategy<Value = Contact> {
    let v3 = |s: f64| prop::array::uniform3(-s..s);
    (
        1e-9f64..1e-4,
        v3(1.0),
        v3(2.0),
        v3(1e-2),
        prop::array::uniform4(0.0f64..1e10),
        v3(1e-5),
        0usize..4,
    )
        .prop_filter("a direction", |c| c.1.iter().any(|x| x.abs() > 1e-3))
        .prop_map(|(z, n, v, w, coef, h, case)| {
            let n = unit(n);
            let mut k = ContactKinematics {
                overlap_m: z,
                normal: n,
                v_rel: v,
                spin: w,
            };
            let mut h = h;
            match case {
                // no slip at all
                0 => {
                    k.v_rel = [0.0; 3];
                    k.spin = [0.0; 3];
                }
                // purely normal motion (no tangential slip), spring at rest
                1 => {
                    k.v_rel = n.map(|x| 0.3 * x);
                    k.spin = [0.0; 3];
                    h = [0.0; 3];
                }
                _ => {}
            }
            (k, coef, h)
        })
}

fn lanes(cs: &[Contact]) -> (ContactKinematics<F64x8>, [F64x8; 4], [F64x8; 3]) {
    let mut k = ContactKinematics::<F64x8>::default();
    let mut coef = [F64x8::default(); 4];
    let mut h = [F64x8::default(); 3];
    for (l, (c, cf, hc)) in cs.iter().enumerate() {
        k.overlap_m.set(l, c.overlap_m);
        for d in 0..3 {
            k.normal[d].set(l, c.normal[d]);
            k.v_rel[d].set(l, c.v_rel[d]);
            k.spin[d].set(l, c.spin[d]);
            h[d].set(l, hc[d]);
        }
        for d in 0..4 {
            coef[d].set(l, cf[d]);
        }
    }
    (k, coef, h)
}

/// Bitwise equal (a NaN matches any NaN: none of these contacts should give one).
fn same(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

fn check<N: NormalKernel, T: TangentialKernel>(cs: &[Contact], clamp: bool, rotations: bool) {
    let (mu, dt) = (0.3, 2.8e-6);
    let (k8, c8, mut h8) = lanes(cs);
    let r8: ContactResponse<F64x8> =
        contact_response::<N, T, F64x8>(&k8, &c8, mu, clamp, rotations, dt, &mut h8);
    for (l, (k, cf, h0)) in cs.iter().enumerate() {
        let mut h = *h0;
        let r = contact_response::<N, T, f64>(k, cf, mu, clamp, rotations, dt, &mut h);
        for d in 0..3 {
            assert!(same(r.force[d], r8.force[d].get(l)), "force lane {l}");
            assert!(
                same(r.torque_arm[d], r8.torque_arm[d].get(l)),
                "torque lane {l}"
            );
            assert!(same(h[d], h8[d].get(l)), "history lane {l}");
        }
        assert!(
            same(r.p_collision, r8.p_collision.get(l)),
            "collision power lane {l}"
        );
        assert!(
            same(r.p_friction, r8.p_friction.get(l)),
            "friction power lane {l}"
        );
    }
}

fn all_laws(cs: &[Contact], clamp: bool, rotations: bool) {
    check::<HertzKernel, NoTangential>(cs, clamp, rotations);
    check::<HertzKernel, CoulombViscousKernel>(cs, clamp, rotations);
    check::<HertzKernel, MindlinSpringKernel>(cs, clamp, rotations);
    check::<HertzKernel, LinearSpringKernel>(cs, clamp, rotations);
    check::<LinearKernel, NoTangential>(cs, clamp, rotations);
    check::<LinearKernel, CoulombViscousKernel>(cs, clamp, rotations);
    check::<LinearKernel, MindlinSpringKernel>(cs, clamp, rotations);
    check::<LinearKernel, LinearSpringKernel>(cs, clamp, rotations);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]
    #[test]
    fn every_lane_is_the_scalar_kernel(
        cs in prop::collection::vec(contact(), 8),
        clamp in any::<bool>(),
        rotations in any::<bool>(),
    ) {
        all_laws(&cs, clamp, rotations);
    }
}

/// The branches of the laws, each hit on purpose in some lane: a sticking spring, a sliding
/// one (Coulomb cap and reset), no slip (Coulomb's 0/0 guard), a history with a normal
/// component (rotated into the tangent plane), a contact pulled apart (clamp), k_t = 0.
#[test]
fn each_branch_in_some_lane() {
    let n = unit([0.0, 0.6, 0.8]);
    let k = |v: [f64; 3]| ContactKinematics {
        overlap_m: 1e-6,
        normal: n,
        v_rel: v,
        spin: [0.0, 1e-3, 0.0],
    };
    let coef = [5.7e9, 3660.0, 10980.0, 2.0e9];
    let cs: Vec<Contact> = vec![
        (k([1e-4, 0.0, 0.0]), coef, [0.0; 3]),
        (k([3.0, 0.0, 0.0]), coef, [0.0; 3]),
        (
            ContactKinematics {
                spin: [0.0; 3],
                ..k([0.0; 3])
            },
            coef,
            [0.0; 3],
        ),
        (k([1e-3, 0.0, 0.0]), coef, [1e-7, 2e-7, 3e-7]),
        (k(n.map(|x| -50.0 * x)), coef, [0.0; 3]),
        (
            k([1e-3, 0.0, 0.0]),
            [5.7e9, 3660.0, 10980.0, 0.0],
            [1e-7, 0.0, 0.0],
        ),
        (k([0.2, -0.1, 0.05]), coef, [0.0, 1e-6, -1e-6]),
        (k([-0.02, 0.3, 0.0]), coef, [0.0; 3]),
    ];
    for clamp in [false, true] {
        for rotations in [false, true] {
            all_laws(&cs, clamp, rotations);
        }
    }
}
