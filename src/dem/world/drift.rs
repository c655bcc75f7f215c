//! The first half kick and drift of a step (2.2.4–2.2.5), grain range by grain range: the
//! arrays and constants they read and write ([`Drift`]).

use std::ops::Range;

use crate::dem::team::Parts;
use crate::integrate::{half_kick_predict, kick_drift};
use crate::simd::WritePrefetch;

/// The grain arrays and constants of the step's first half kick and drift (2.2.4–2.2.5),
/// applied grain range by grain range.
pub(super) struct Drift<'a> {
    pub(super) pos: Parts<'a, [f64; 3]>,
    pub(super) vel: Parts<'a, [f64; 3]>,
    pub(super) vel_pred: Parts<'a, [f64; 3]>,
    pub(super) omega: Parts<'a, [f64; 3]>,
    pub(super) omega_pred: Parts<'a, [f64; 3]>,
    pub(super) inv_mass: &'a [f64],
    pub(super) inv_inertia: &'a [f64],
    /// Centres at the last neighbour build (m); empty when not tracked.
    pub(super) reference: &'a [[f64; 3]],
    /// Half step and step (s).
    pub(super) h: f64,
    pub(super) dt: f64,
    pub(super) rotations: bool,
    /// The box's displacement since the last neighbour build (m).
    pub(super) shift: [f64; 3],
    /// Write prefetches of the stored lines ([`WritePrefetch`]).
    pub(super) prefetch: Option<WritePrefetch>,
}

impl<'a> Drift<'a> {
    /// The drift of the grains whose centres, velocities, predicted velocities, spins and
    /// predicted spins are `kin` (handed out in pieces from here on), with their inverse
    /// masses and inertias `inv`, the centres at the last neighbour build `reference` (not
    /// tracked unless one per grain), the time step and rotation flag `(dt, rotations)`.
    pub(super) fn new(
        kin: [&'a mut [[f64; 3]]; 5],
        (inv_mass, inv_inertia): (&'a [f64], &'a [f64]),
        reference: &'a [[f64; 3]],
        (dt, rotations): (f64, bool),
        (shift, prefetch): ([f64; 3], Option<WritePrefetch>),
    ) -> Self {
        let n = kin[0].len();
        let [pos, vel, vel_pred, omega, omega_pred] = kin.map(Parts::new);
        Drift {
            pos,
            vel,
            vel_pred,
            omega,
            omega_pred,
            inv_mass,
            inv_inertia,
            reference: if reference.len() == n { reference } else { &[] },
            h: 0.5 * dt,
            dt,
            rotations,
            shift,
            prefetch,
        }
    }

    /// Half kick (v and ω, with their predicted full-step values) and drift of grains `r`,
    /// whose force and torque are `force` and `torque` (N, N m); returns the largest squared
    /// displacement since the last neighbour build relative to the box (m²; ∞ untracked).
    ///
    /// # Safety
    /// No other unit touches grains `r` of the drifted arrays meanwhile.
    pub(super) unsafe fn grains(
        &self,
        r: Range<usize>,
        force: &[[f64; 3]],
        torque: &[[f64; 3]],
    ) -> f64 {
        // SAFETY: the caller's promise.
        unsafe {
            if self.rotations {
                half_kick_predict(
                    self.omega.get(r.clone()),
                    self.omega_pred.get(r.clone()),
                    torque,
                    &self.inv_inertia[r.clone()],
                    self.h,
                    self.prefetch,
                );
            }
            let refs = match self.reference {
                [] => &[],
                all => &all[r.clone()],
            };
            kick_drift(
                self.pos.get(r.clone()),
                self.vel.get(r.clone()),
                self.vel_pred.get(r.clone()),
                force,
                &self.inv_mass[r],
                (self.h, self.dt),
                refs,
                self.shift,
                self.prefetch,
            )
        }
    }
}
