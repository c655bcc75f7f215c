//! Impacts of the bed as a whole on the floor and the ceiling, counted from the bed's centre
//! of mass and the grains' force on the box.
//!
//! The one-particle model counts impacts of its particle; a DEM bed has thousands of grain–wall
//! contacts per period, but what a reader of the source means by "two impacts per period" is
//! the bed *as a whole* landing on the floor or hitting the ceiling. Its signature is the
//! centre of mass's velocity relative to the box, v_rel = ż_cm − ż_box (m/s), being stopped by
//! a wall: falling (v_rel < −v_th) and then brought to rest (v_rel > −v_th/4) while the floor
//! carries more than half the bed's weight W = m_bed g (F_gz < −W/2, F_gz the grains' vertical
//! force on the box, N); the ceiling is the mirror image (v_rel > +v_th, then < +v_th/4, with
//! F_gz > +W/2). The force condition keeps the apex of a hop, where side-wall friction alone
//! can push either way, from counting as a ceiling impact.
//!
//! The threshold is the velocity gained in free fall over a twentieth of the forcing period,
//! v_th = g T / 20 (m/s; 0.034 m/s at 14.5 Hz). A bed that rests on the floor (Γ < 1) keeps
//! v_rel ≈ 0 and counts nothing; grains that rain on the floor one at a time, or chatter inside
//! one landing, move the centre of mass too little to re-arm a counter: both are "no new
//! collective impact". A bed that lands, bounces off by more than v_th and lands again counts
//! two floor impacts, as the one-particle model would.

/// Counts collective floor and ceiling impacts from a stream of (v_rel, F_gz) values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BedImpacts {
    v_th: f64,
    half_weight_n: f64,
    floor_armed: bool,
    ceiling_armed: bool,
    /// Floor impacts counted so far.
    pub floor: u64,
    /// Ceiling impacts counted so far.
    pub ceiling: u64,
}

impl BedImpacts {
    /// A counter for a bed of mass `bed_mass_kg` (kg) forced at `frequency_hz` (Hz) under
    /// gravity `g` (m/s²): v_th = g / (20 f). A zero frequency or gravity gives v_th = +∞
    /// (nothing is ever counted).
    pub fn new(bed_mass_kg: f64, g: f64, frequency_hz: f64) -> Self {
        let v_th = if g > 0.0 && frequency_hz > 0.0 {
            g / (20.0 * frequency_hz)
        } else {
            f64::INFINITY
        };
        BedImpacts {
            v_th,
            half_weight_n: 0.5 * bed_mass_kg * g,
            floor_armed: false,
            ceiling_armed: false,
            floor: 0,
            ceiling: 0,
        }
    }

    /// The arming velocity v_th (m/s).
    pub fn threshold_m_s(&self) -> f64 {
        self.v_th
    }

    /// Feeds one time step: the bed's velocity relative to the box `v_rel` (m/s) and the
    /// grains' vertical force on the box `f_gz` (N; negative when the floor carries them).
    pub fn observe(&mut self, v_rel: f64, f_gz: f64) {
        let (v, w2) = (self.v_th, self.half_weight_n);
        if v_rel < -v {
            self.floor_armed = true;
        } else if self.floor_armed && v_rel > -0.25 * v && f_gz < -w2 {
            self.floor += 1;
            self.floor_armed = false;
        }
        if v_rel > v {
            self.ceiling_armed = true;
        } else if self.ceiling_armed && v_rel < 0.25 * v && f_gz > w2 {
            self.ceiling += 1;
            self.ceiling_armed = false;
        }
    }

    /// Floor plus ceiling impacts.
    pub fn total(&self) -> u64 {
        self.floor + self.ceiling
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const G: f64 = 9.81;

    #[test]
    fn a_bed_that_never_leaves_the_floor_counts_nothing() {
        // resting: v_rel = 0 (tiny elastic jitter), F_gz = −m (g + a sin ωt) < 0
        let mut c = BedImpacts::new(1.0, G, 10.0);
        for i in 0..10_000 {
            let s = (std::f64::consts::TAU * i as f64 / 1000.0).sin();
            c.observe(1e-4 * s, -G * (1.0 + 0.8 * s));
        }
        assert_eq!(c.total(), 0);
    }

    #[test]
    fn a_ball_bouncing_on_the_floor_counts_one_impact_per_bounce() {
        // an inelastic bouncing ball, e = 0.5, from 1 m/s, integrated on a fine grid; the
        // floor force is a short pulse at each reversal. Bounces above v_th = g/(20 f) count.
        let f = 10.0;
        let mut c = BedImpacts::new(1.0, G, f);
        let (dt, mut z, mut v) = (1e-5, 0.0, 1.0_f64);
        let mut expected = 0;
        for _ in 0..200_000 {
            v -= G * dt;
            z += v * dt;
            let mut force = 0.0;
            if z < 0.0 {
                z = 0.0;
                if -v > c.threshold_m_s() {
                    expected += 1;
                }
                v *= -0.5;
                force = -100.0;
            }
            c.observe(v, force);
        }
        assert!(expected >= 3, "{expected}");
        assert_eq!((c.floor, c.ceiling), (expected, 0));
    }

    #[test]
    fn chatter_inside_one_landing_is_one_impact_and_ceilings_are_told_apart() {
        let mut c = BedImpacts::new(1.0, G, 10.0);
        for _ in 0..7 {
            // rise fast, hit the ceiling (force up), stop
            c.observe(2.0, 0.0);
            c.observe(0.0, 50.0);
            c.observe(0.01, 0.0); // chatter below v_th/4 after the hit: no re-arm
            c.observe(0.0, 40.0);
            // fall, land with chattering force
            c.observe(-2.0, 0.0);
            for k in 0..10 {
                c.observe(-0.01, if k % 2 == 0 { -80.0 } else { 0.0 });
            }
        }
        assert_eq!((c.floor, c.ceiling), (7, 7));
    }

    #[test]
    fn the_apex_of_a_small_hop_is_not_a_ceiling_impact() {
        // up at 0.3 m/s, apex with side-wall friction pushing the box up by W/10, down, land
        let mut c = BedImpacts::new(1.0, G, 10.0);
        for _ in 0..5 {
            c.observe(0.3, 0.0);
            c.observe(0.0, 0.1 * G);
            c.observe(-0.3, 0.0);
            c.observe(0.0, -3.0 * G);
        }
        assert_eq!((c.floor, c.ceiling), (5, 0));
    }
}
