//! Grain radius distributions sampled by Monte Carlo with a seeded RNG (SPEC §5): fixed,
//! uniform, truncated normal, discrete (radii with weights) and empirical (a cumulative
//! size curve, inverted by linear interpolation).

use rand::RngExt;
use rand_distr::{Distribution, Normal};

/// A distribution of sphere radii (m).
#[derive(Debug, Clone, PartialEq)]
pub enum RadiusDistribution {
    /// Every grain has radius `0` (m).
    Fixed(f64),
    /// Uniform on [min, max] (m).
    Uniform {
        /// Smallest radius (m).
        min: f64,
        /// Largest radius (m).
        max: f64,
    },
    /// Normal(mean, std) truncated to [min, max] by rejection (m).
    Normal {
        /// Mean radius (m).
        mean: f64,
        /// Standard deviation (m).
        std: f64,
        /// Lower truncation (m).
        min: f64,
        /// Upper truncation (m).
        max: f64,
    },
    /// Radii `values` (m) drawn with probabilities ∝ `weights` (by number of grains).
    Discrete {
        /// Radii (m).
        values: Vec<f64>,
        /// Relative frequencies (–), ≥ 0, not all 0.
        weights: Vec<f64>,
    },
    /// Empirical cumulative curve F(r) by number: points (r_k, F_k) with r increasing and
    /// F from 0 to 1, inverted by linear interpolation (a granulometric curve).
    Empirical {
        /// Radii r_k (m), increasing.
        radii: Vec<f64>,
        /// Cumulative fractions F_k (–), non-decreasing, F_0 = 0, F_last = 1.
        cdf: Vec<f64>,
    },
}

impl RadiusDistribution {
    /// Smallest radius the distribution can return (m).
    pub fn r_min(&self) -> f64 {
        match self {
            Self::Fixed(r) => *r,
            Self::Uniform { min, .. } | Self::Normal { min, .. } => *min,
            Self::Discrete { values, .. } => values.iter().cloned().fold(f64::INFINITY, f64::min),
            Self::Empirical { radii, .. } => radii[0],
        }
    }

    /// Largest radius the distribution can return (m).
    pub fn r_max(&self) -> f64 {
        match self {
            Self::Fixed(r) => *r,
            Self::Uniform { max, .. } | Self::Normal { max, .. } => *max,
            Self::Discrete { values, .. } => values.iter().cloned().fold(0.0, f64::max),
            Self::Empirical { radii, .. } => radii[radii.len() - 1],
        }
    }

    /// Draws one radius (m).
    pub fn sample<R: rand::Rng + ?Sized>(&self, rng: &mut R) -> f64 {
        match self {
            Self::Fixed(r) => *r,
            Self::Uniform { min, max } => {
                if max > min {
                    rng.random_range(*min..=*max)
                } else {
                    *min
                }
            }
            Self::Normal {
                mean,
                std,
                min,
                max,
            } => {
                if *std <= 0.0 {
                    return mean.clamp(*min, *max);
                }
                let nd = Normal::new(*mean, *std).expect("validated std > 0");
                for _ in 0..10_000 {
                    let r = nd.sample(rng);
                    if r >= *min && r <= *max {
                        return r;
                    }
                }
                mean.clamp(*min, *max)
            }
            Self::Discrete { values, weights } => {
                let total: f64 = weights.iter().sum();
                let mut u = rng.random::<f64>() * total;
                for (v, w) in values.iter().zip(weights) {
                    if u < *w {
                        return *v;
                    }
                    u -= w;
                }
                values[values.len() - 1]
            }
            Self::Empirical { radii, cdf } => {
                let u: f64 = rng.random();
                for k in 1..radii.len() {
                    if u <= cdf[k] {
                        let df = cdf[k] - cdf[k - 1];
                        let t = if df > 0.0 { (u - cdf[k - 1]) / df } else { 1.0 };
                        return radii[k - 1] + t * (radii[k] - radii[k - 1]);
                    }
                }
                radii[radii.len() - 1]
            }
        }
    }

    /// Draws `n` radii with a ChaCha8 generator seeded by `seed` (reproducible).
    pub fn sample_n(&self, n: usize, seed: u64) -> Vec<f64> {
        use rand::SeedableRng;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        (0..n).map(|_| self.sample(&mut rng)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_stay_in_range_and_match_means() {
        let u = RadiusDistribution::Uniform { min: 1.0, max: 2.0 };
        let s = u.sample_n(20_000, 3);
        let m = s.iter().sum::<f64>() / s.len() as f64;
        // mean 1.5, standard error 0.29/√20000 = 0.002: 5σ band
        assert!((m - 1.5).abs() < 0.01);
        assert!(s.iter().all(|r| (1.0..=2.0).contains(r)));
        let d = RadiusDistribution::Discrete {
            values: vec![1.0, 3.0],
            weights: vec![3.0, 1.0],
        };
        let s = d.sample_n(20_000, 4);
        let frac = s.iter().filter(|&&r| r == 3.0).count() as f64 / 20_000.0;
        // p = 0.25, σ = 0.003: 5σ band
        assert!((frac - 0.25).abs() < 0.016);
        let e = RadiusDistribution::Empirical {
            radii: vec![1.0, 2.0, 4.0],
            cdf: vec![0.0, 0.5, 1.0],
        };
        let s = e.sample_n(20_000, 5);
        let below2 = s.iter().filter(|&&r| r <= 2.0).count() as f64 / 20_000.0;
        assert!((below2 - 0.5).abs() < 0.02);
        assert_eq!(u.sample_n(10, 9), u.sample_n(10, 9));
    }
}
