//! The primary system M z'' + C z' + K z = C u' + K u + F0 with u = U cos(Ω t) (2.1.2): exact
//! closed-form solution between events and the steady-state amplitude (2.1.21).

use crate::units::TWO_PI;

/// The primary system (SPEC §1): mass M on a spring K with a viscous damper C, mounted on a
/// moving base, M z'' + C z' + K z = C u' + K u + F (2.1.2). The one engine type of the
/// primary; `scene::Primary` is its TOML form (which also allows a damping ratio).
///
/// # Units
/// `mass_kg` kg, `stiffness_n_m` N/m, `damping_n_s_m` N s/m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrimarySystem {
    /// Primary mass M (kg).
    pub mass_kg: f64,
    /// Spring stiffness K (N/m).
    pub stiffness_n_m: f64,
    /// Viscous damping C (N s/m).
    pub damping_n_s_m: f64,
}

impl PrimarySystem {
    /// Steady-state amplitude Z(Ω) (m) of the primary under base motion U cos(Ω t).
    ///
    /// # Formula
    /// Z(Ω) = U sqrt( (K² + (CΩ)²) / ((K − MΩ²)² + (CΩ)²) )  (2.1.21), equivalently
    /// |Z/U| = sqrt(1 + (2ξr)²)/sqrt((1 − r²)² + (2ξr)²), r = Ω/Ω₀.
    ///
    /// # Units
    /// `base_amplitude_m` m, `omega_rad_s` rad/s → m.
    ///
    /// # Pitfalls
    /// Infinite for C = 0 at Ω = sqrt(K/M).
    ///
    /// # References
    /// Sánchez, M. (2012), doctoral thesis, eq. (2.1.21); any vibrations text (base excitation).
    ///
    /// # Example
    /// ```
    /// # use pdamp::model::PrimarySystem;
    /// let p = PrimarySystem { mass_kg: 1.0, stiffness_n_m: 100.0, damping_n_s_m: 0.2 };
    /// assert!((p.steady_amplitude_m(0.01, 1e-6) - 0.01).abs() < 1e-12); // Ω → 0: Z → U
    /// ```
    pub fn steady_amplitude_m(&self, base_amplitude_m: f64, omega_rad_s: f64) -> f64 {
        crate::analysis::frf_fit::base_excitation_amplitude(
            self.mass_kg,
            self.stiffness_n_m,
            self.damping_n_s_m,
            base_amplitude_m,
            omega_rad_s,
        )
    }

    /// Steady-state amplitude (m) of the primary under a force F0 sin(Ω t) on its mass.
    ///
    /// # Formula
    /// Z(Ω) = F0 / sqrt((K − MΩ²)² + (CΩ)²) (the receptance's modulus times F0).
    ///
    /// # Units
    /// `force_n` N, `omega_rad_s` rad/s → m.
    pub fn force_amplitude_m(&self, force_n: f64, omega_rad_s: f64) -> f64 {
        let det = self.stiffness_n_m - self.mass_kg * omega_rad_s * omega_rad_s;
        force_n / det.hypot(self.damping_n_s_m * omega_rad_s)
    }

    /// [`PrimarySystem::steady_amplitude_m`] at forcing frequency `frequency_hz` (Hz), (2.1.21).
    pub fn steady_amplitude_at_hz(&self, base_amplitude_m: f64, frequency_hz: f64) -> f64 {
        self.steady_amplitude_m(base_amplitude_m, TWO_PI * frequency_hz)
    }

    /// The same system with `extra_kg` (kg) added to the moving mass (e.g. a particle
    /// clamped to the box: M + m_p).
    pub fn with_added_mass(&self, extra_kg: f64) -> PrimarySystem {
        PrimarySystem {
            mass_kg: self.mass_kg + extra_kg,
            ..*self
        }
    }

    /// Damping ratio ξ = C / (2 sqrt(K M)) (dimensionless).
    pub fn damping_ratio(&self) -> f64 {
        self.damping_n_s_m / (2.0 * (self.stiffness_n_m * self.mass_kg).sqrt())
    }

    /// Natural frequency f0 = sqrt(K/M)/(2π) (Hz).
    pub fn natural_frequency_hz(&self) -> f64 {
        (self.stiffness_n_m / self.mass_kg).sqrt() / TWO_PI
    }
}

/// How the box moves: on a primary system driven through its base or by a force on its mass
/// (or released: free decay), or kinematically with the base (`primary = None`). Base motion
/// u(t) = U cos(Ωt), force F(t) = F0 sin(Ωt), Ω = 2πf, t = 0 when the drive starts; the box
/// moves along the unit vector `direction`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoxDrive {
    /// Primary system, or `None` for a box moved kinematically with the base.
    pub primary: Option<PrimarySystem>,
    /// Base amplitude U (m); 0 for a force drive or a free decay.
    pub amplitude_m: f64,
    /// Drive frequency f (Hz) (for a free decay: the clock of the periods and the section).
    pub frequency_hz: f64,
    /// Force amplitude F0 (N) on the primary mass, F(t) = F0 sin(Ωt); 0 for a base drive or a
    /// free decay.
    pub force_n: f64,
    /// Unit vector of the axis the primary and the box move along (`[0, 0, 1]`: vertical).
    pub direction: [f64; 3],
}

impl BoxDrive {
    /// A box at rest: no primary, no drive, the vertical axis (tests, and beds built at rest).
    pub const STILL: BoxDrive = BoxDrive {
        primary: None,
        amplitude_m: 0.0,
        frequency_hz: 0.0,
        force_n: 0.0,
        direction: [0.0, 0.0, 1.0],
    };

    /// Base displacement u(t) (m) and velocity u'(t) (m/s).
    #[inline]
    pub fn base(&self, t: f64) -> (f64, f64) {
        let (u, du, _) = base_motion(self.amplitude_m, self.omega_rad_s(), t);
        (u, du)
    }

    /// The drive force on the primary mass F(t) = F0 sin(Ωt) (N).
    #[inline]
    pub fn force(&self, t: f64) -> f64 {
        self.force_n * (self.omega_rad_s() * t).sin()
    }

    /// Angular forcing frequency Ω = 2π f (rad/s).
    pub fn omega_rad_s(&self) -> f64 {
        TWO_PI * self.frequency_hz
    }

    /// Forcing period T = 1/f (s).
    pub fn period_s(&self) -> f64 {
        1.0 / self.frequency_hz
    }

    /// Reference amplitude of the primary alone at this forcing (m): (2.1.21) with M for a
    /// base drive, F0/sqrt((K − MΩ²)² + (CΩ)²) for a force drive, 0 for a free decay; `None`
    /// for a kinematic box.
    pub fn reference_amplitude_m(&self) -> Option<f64> {
        let p = self.primary?;
        let w = self.omega_rad_s();
        Some(if self.force_n != 0.0 {
            p.force_amplitude_m(self.force_n, w)
        } else {
            p.steady_amplitude_m(self.amplitude_m, w)
        })
    }
}

/// Anchor of a closed-form segment: the homogeneous state at time `t0_s`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Anchor {
    /// Anchor time (s).
    pub t0_s: f64,
    /// Homogeneous displacement y0 = z(t0) − z_p(t0) (m).
    pub y0: f64,
    /// Homogeneous velocity y0' = z'(t0) − z_p'(t0) (m/s).
    pub w0: f64,
}

/// Linear SDOF m z'' + c z' + k z = c u' + k u + F0 sin(Ω t) + f0, u(t) = U cos(Ω t), solved
/// exactly (a base drive U or a force drive F0, see [`Sdof::with_force`]).
///
/// # Formula
/// z(t) = z_p(t) + y(t): particular part z_p = Re[H U e^{iΩt}] + f0/k with
/// H = (k + icΩ)/(k − mΩ² + icΩ) (so |z_p − f0/k| is (2.1.21)), or for the force drive
/// z_p = Re[−i G F0 e^{iΩt}] + f0/k with G = 1/(k − mΩ² + icΩ) (|z_p − f0/k| =
/// F0/sqrt((k − mΩ²)² + (cΩ)²)); homogeneous part, with
/// a = c/(2m), ω0² = k/m, q = ω0² − a², τ = t − t0:
/// y = e^{−aτ}[y0 C(τ) + (y0' + a y0) S(τ)], y' = e^{−aτ}[y0' C(τ) − (a y0' + ω0² y0) S(τ)],
/// C = cos(√q τ), S = sin(√q τ)/√q (underdamped), cosh/sinh (overdamped), and their Taylor
/// series in qτ² near critical damping (uniformly accurate as ξ → 1; ξ → 0 is the plain
/// underdamped branch).
///
/// # Units
/// SI: kg, N/m, N s/m, m, rad/s, N.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sdof {
    /// Moving mass m (kg).
    pub mass: f64,
    /// Stiffness k (N/m).
    pub stiffness: f64,
    /// Viscous damping c (N s/m).
    pub damping: f64,
    /// Base amplitude U (m).
    pub base_amplitude: f64,
    /// Forcing angular frequency Ω (rad/s).
    pub omega: f64,
    /// Constant force f0 (N), e.g. −m_p g for a particle resting on the floor.
    pub constant_force: f64,
    /// Amplitude F0 (N) of the harmonic force F0 sin(Ω t) on the mass (0: base drive).
    pub force_amplitude: f64,
    /// The particular part's amplitude factor: U (base drive) or F0 (force drive).
    resp: f64,
    a: f64,
    w0sq: f64,
    q: f64,
    hr: f64,
    hi: f64,
    zs: f64,
}

impl Sdof {
    /// Build the closed form for mass `m`, stiffness `k`, damping `c`, base amplitude `u_amp`,
    /// forcing `omega` and constant force `f0`. The caller guarantees m, k > 0, c ≥ 0 and no
    /// undamped exact resonance (the scene validation does).
    pub fn new(m: f64, k: f64, c: f64, u_amp: f64, omega: f64, f0: f64) -> Sdof {
        let a = c / (2.0 * m);
        let w0sq = k / m;
        let det = k - m * omega * omega;
        let co = c * omega;
        let den = det * det + co * co;
        // H = (k + i cΩ)(det − i cΩ)/den
        let hr = (k * det + co * co) / den;
        let hi = (co * det - k * co) / den;
        Sdof {
            mass: m,
            stiffness: k,
            damping: c,
            base_amplitude: u_amp,
            omega,
            constant_force: f0,
            force_amplitude: 0.0,
            resp: u_amp,
            a,
            w0sq,
            q: w0sq - a * a,
            hr,
            hi,
            zs: f0 / k,
        }
    }

    /// The same system driven by the force F0 sin(Ω t) on its mass (N) instead of its base
    /// (the base amplitude is set to 0). F0 = 0 gives the undriven system (free decay).
    pub fn with_force(self, force_amplitude: f64) -> Sdof {
        let (m, k, c, w) = (self.mass, self.stiffness, self.damping, self.omega);
        let det = k - m * w * w;
        let co = c * w;
        let den = det * det + co * co;
        // −i G = −i (det − i cΩ)/den
        Sdof {
            base_amplitude: 0.0,
            force_amplitude,
            resp: force_amplitude,
            hr: -co / den,
            hi: -det / den,
            ..self
        }
    }

    /// The drive force F0 sin(Ω t) and its rate F0 Ω cos(Ω t) from (sin Ωt, cos Ωt) (N, N/s).
    #[inline]
    fn drive_force(&self, sin_cos_wt: (f64, f64)) -> (f64, f64) {
        let f = self.force_amplitude;
        (f * sin_cos_wt.0, f * self.omega * sin_cos_wt.1)
    }

    /// Base motion (u, u', u'') at time t (m, m/s, m/s²).
    #[inline]
    pub fn base(&self, t: f64) -> (f64, f64, f64) {
        base_motion(self.base_amplitude, self.omega, t)
    }

    /// Particular (steady-state) solution (z_p, z_p') at time t.
    #[inline]
    pub fn particular(&self, t: f64) -> (f64, f64) {
        self.particular_parts((self.omega * t).sin_cos())
    }

    /// Steady-state amplitude of the particular solution (m): |H| U, = (2.1.21), or |G| F0.
    pub fn steady_amplitude(&self) -> f64 {
        self.resp * self.hr.hypot(self.hi)
    }

    /// [`Sdof::particular`] from (sin Ωt, cos Ωt).
    #[inline]
    pub fn particular_parts(&self, sin_cos_wt: (f64, f64)) -> (f64, f64) {
        let (s, c) = sin_cos_wt;
        let u = self.resp;
        let z = u * (self.hr * c - self.hi * s) + self.zs;
        let v = -u * self.omega * (self.hr * s + self.hi * c);
        (z, v)
    }

    /// Anchor a segment at time `t0` with state (z0, v0).
    #[inline]
    pub fn anchor(&self, t0: f64, z0: f64, v0: f64) -> Anchor {
        self.anchor_parts(t0, z0, v0, (self.omega * t0).sin_cos())
    }

    /// [`Sdof::anchor`] with (sin Ωt0, cos Ωt0) given (the same result; saves the caller who
    /// has them a `sin_cos`).
    #[inline]
    pub fn anchor_parts(&self, t0: f64, z0: f64, v0: f64, sin_cos_wt0: (f64, f64)) -> Anchor {
        let (zp, vp) = self.particular_parts(sin_cos_wt0);
        Anchor {
            t0_s: t0,
            y0: z0 - zp,
            w0: v0 - vp,
        }
    }

    /// State (z, z') at time t of the segment anchored at `an` (exact).
    #[inline]
    pub fn eval(&self, an: &Anchor, t: f64) -> (f64, f64) {
        let (ce, se) = self.homogeneous_basis(t - an.t0_s);
        let y = an.y0 * ce + (an.w0 + self.a * an.y0) * se;
        let w = an.w0 * ce - (self.a * an.w0 + self.w0sq * an.y0) * se;
        let (zp, vp) = self.particular(t);
        (zp + y, vp + w)
    }

    /// State (z, z') from precomputed pieces: `basis` = [`Sdof::homogeneous_basis`] at
    /// τ = t − t0 and (sin Ωt, cos Ωt). Same result as [`Sdof::eval`]; lets a caller reuse
    /// trigonometric values across equal-length segments.
    #[inline]
    pub fn eval_parts(&self, an: &Anchor, basis: (f64, f64), sin_cos_wt: (f64, f64)) -> (f64, f64) {
        let (ce, se) = basis;
        let (s, c) = sin_cos_wt;
        let y = an.y0 * ce + (an.w0 + self.a * an.y0) * se;
        let w = an.w0 * ce - (self.a * an.w0 + self.w0sq * an.y0) * se;
        let u = self.resp;
        let zp = u * (self.hr * c - self.hi * s) + self.zs;
        let vp = -u * self.omega * (self.hr * s + self.hi * c);
        (zp + y, vp + w)
    }

    /// e^{−aτ}·(C(τ), S(τ)): the homogeneous basis at τ (see the type's formula), robust for
    /// every damping ratio.
    #[inline]
    pub fn homogeneous_basis(&self, tau: f64) -> (f64, f64) {
        let q = self.q;
        let x = q * tau * tau;
        let decay = (-self.a * tau).exp();
        if x.abs() < 1e-3 {
            // Taylor series of cos(√q τ) and sin(√q τ)/√q in x = qτ² (error < x⁵/10! ≈ 3e-22).
            let c = 1.0 - x / 2.0 * (1.0 - x / 12.0 * (1.0 - x / 30.0 * (1.0 - x / 56.0)));
            let s = tau * (1.0 - x / 6.0 * (1.0 - x / 20.0 * (1.0 - x / 42.0 * (1.0 - x / 72.0))));
            (decay * c, decay * s)
        } else if q > 0.0 {
            let wd = q.sqrt();
            let (s, c) = (wd * tau).sin_cos();
            (decay * c, decay * s / wd)
        } else {
            let b = (-q).sqrt();
            let ep = ((b - self.a) * tau).exp();
            let em = (-(b + self.a) * tau).exp();
            (0.5 * (ep + em), 0.5 * (ep - em) / b)
        }
    }

    /// Acceleration z'' from the equation of motion at (t, z, z').
    #[inline]
    pub fn accel(&self, t: f64, z: f64, v: f64) -> f64 {
        let (u, du, _) = self.base(t);
        let mut f = self.stiffness * (u - z) + self.damping * (du - v) + self.constant_force;
        if self.force_amplitude != 0.0 {
            f += self.drive_force((self.omega * t).sin_cos()).0;
        }
        f / self.mass
    }

    /// [`Sdof::accel`] and [`Sdof::jerk`] from (sin Ωt, cos Ωt) at (z, z').
    #[inline]
    pub fn accel_jerk_parts(&self, sin_cos_wt: (f64, f64), z: f64, v: f64) -> (f64, f64) {
        let (s, c) = sin_cos_wt;
        let (u, du, ddu) = (
            self.base_amplitude * c,
            -self.base_amplitude * self.omega * s,
            -self.base_amplitude * self.omega * self.omega * c,
        );
        if self.force_amplitude != 0.0 {
            let (f, df) = self.drive_force(sin_cos_wt);
            let acc =
                (self.stiffness * (u - z) + self.damping * (du - v) + self.constant_force + f)
                    / self.mass;
            let jerk = (self.stiffness * (du - v) + self.damping * (ddu - acc) + df) / self.mass;
            return (acc, jerk);
        }
        let acc =
            (self.stiffness * (u - z) + self.damping * (du - v) + self.constant_force) / self.mass;
        let jerk = (self.stiffness * (du - v) + self.damping * (ddu - acc)) / self.mass;
        (acc, jerk)
    }

    /// Jerk z''' at (t, z, z', z'') (time derivative of the equation of motion).
    #[inline]
    pub fn jerk(&self, t: f64, v: f64, acc: f64) -> f64 {
        let (_, du, ddu) = self.base(t);
        let mut r = self.stiffness * (du - v) + self.damping * (ddu - acc);
        if self.force_amplitude != 0.0 {
            r += self.drive_force((self.omega * t).sin_cos()).1;
        }
        r / self.mass
    }

    /// Fastest time scale of the solution (s): the smallest of the forcing period, the natural
    /// period 2π/ω0 and 2π over the fastest decay rate (overdamped). Event search and quadrature
    /// steps are fractions of it.
    pub fn time_scale(&self) -> f64 {
        let fast_decay = self.a + (-self.q).max(0.0).sqrt();
        let mut ts = TWO_PI / self.omega;
        ts = ts.min(TWO_PI / self.w0sq.sqrt());
        if fast_decay > 0.0 {
            ts = ts.min(TWO_PI / fast_decay);
        }
        ts
    }
}

/// Base motion u = U cos(Ωt) and its first two derivatives at t.
#[inline]
pub fn base_motion(u_amp: f64, omega: f64, t: f64) -> (f64, f64, f64) {
    let (s, c) = (omega * t).sin_cos();
    (u_amp * c, -u_amp * omega * s, -u_amp * omega * omega * c)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed form satisfies the ODE: finite-difference acceleration matches `accel`.
    #[test]
    fn closed_form_satisfies_ode_all_damping_regimes() {
        for xi in [0.0, 0.01, 0.999_999, 1.0, 1.000_001, 3.0] {
            let (m, k): (f64, f64) = (2.0, 800.0);
            let c = 2.0 * xi * (k * m).sqrt();
            let sd = Sdof::new(m, k, c, 0.01, 13.0, -1.5);
            let an = sd.anchor(0.3, 0.002, -0.1);
            for t in [0.31, 0.5, 1.7] {
                let h = 1e-5;
                let (_, vp) = sd.eval(&an, t + h);
                let (_, vm) = sd.eval(&an, t - h);
                let (z, v) = sd.eval(&an, t);
                let fd = (vp - vm) / (2.0 * h);
                // central difference error ~ h² z'''' ≈ 1e-10 × 1e4 → 1e-6 relative is ample
                assert!(
                    (fd - sd.accel(t, z, v)).abs() < 1e-5 * (1.0 + fd.abs()),
                    "xi {xi} t {t}"
                );
            }
            // the anchor state is reproduced exactly
            let (z0, v0) = sd.eval(&an, 0.3);
            assert!((z0 - 0.002).abs() < 1e-15 && (v0 + 0.1).abs() < 1e-15);
        }
    }

    #[test]
    fn frf_static_limit_and_resonance() {
        // Ω → 0: Z → U; at resonance with ξ: |Z/U| = sqrt(1 + 4ξ²)/(2ξ)
        let p = |c| PrimarySystem {
            mass_kg: 1.0,
            stiffness_n_m: 100.0,
            damping_n_s_m: c,
        };
        assert!((p(0.2).steady_amplitude_m(0.01, 1e-6) - 0.01).abs() < 1e-12);
        let xi: f64 = 0.01;
        let z = p(2.0 * xi * 10.0).steady_amplitude_m(1.0, 10.0);
        assert!((z - (1.0 + 4.0 * xi * xi).sqrt() / (2.0 * xi)).abs() < 1e-9);
    }
}
