//! Options and result of the false-nearest-neighbour test: [`FnnOptions`] (pdamp's and
//! TISEAN's defaults, ratio R_t, Theiler window in samples), the vector construction
//! ([`FnnVectors`]) and one dimension's result ([`FnnPoint`]; distances in data units).

/// Largest embedding dimension supported (distances are unrolled for a compile-time dimension).
pub const MAX_DIMENSION: usize = 12;

/// Options of [`false_nearest_neighbors`](super::false_nearest_neighbors).
///
/// `Default` gives pdamp's defaults (Kennel's ratio 10, Theiler window = lag). TISEAN's
/// `false_nearest` defaults are [`FnnOptions::tisean`] (ratio 2, no Theiler window, `M = 5`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FnnOptions {
    /// Smallest embedding dimension tested, `m_min ≥ 1` (TISEAN `-m`). Default 1.
    pub m_min: usize,
    /// Largest embedding dimension tested, `m_max ≤ 12` (TISEAN `-M 1,m_max`). Default 6.
    pub m_max: usize,
    /// Delay τ in samples (TISEAN `-d`). Default 1 (use the MI lag).
    pub tau: usize,
    /// Escape ratio `R_t` (TISEAN `-f`). pdamp default 10 (Kennel et al. eq. 4's threshold);
    /// TISEAN's default is 2.
    pub ratio: f64,
    /// Theiler window `w` in samples: neighbours need `|n − j| > w` (TISEAN `-t`).
    /// pdamp default `None` = one lag τ; TISEAN's default is 0.
    pub theiler: Option<usize>,
    /// Which coordinates make up the vectors. Default [`FnnVectors::Delay`] (Kennel et al.);
    /// [`FnnOptions::tisean`] uses [`FnnVectors::TiseanUnivariate`].
    pub vectors: FnnVectors,
}

/// The coordinates of the vectors compared by [`false_nearest_neighbors`](super::false_nearest_neighbors).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FnnVectors {
    /// Delay vectors `(s_n, s_{n+τ}, …, s_{n+(m−1)τ})`, escape coordinate `s_{n+mτ}` (Kennel
    /// et al. 1992, SPEC (4.1.4)). pdamp's default.
    #[default]
    Delay,
    /// TISEAN 3.0.1 `false_nearest` on a univariate series: the vectors are *consecutive*
    /// samples `(s_n, s_{n+1}, …, s_{n+m−1})` and the escape coordinate is `s_{n+m}`, whatever
    /// the delay τ — its code sets the offsets `vemb[i] = i` for one component (and
    /// `(i/comp)·delay` only for several). τ still sets the index ranges: references
    /// `n < N − M·τ`, candidates `j < N − (M+1)·τ`. With τ = 1 both choices are the same.
    TiseanUnivariate,
}

impl Default for FnnOptions {
    fn default() -> Self {
        Self {
            m_min: 1,
            m_max: 6,
            tau: 1,
            ratio: 10.0,
            theiler: None,
            vectors: FnnVectors::Delay,
        }
    }
}

impl FnnOptions {
    /// TISEAN `false_nearest`'s defaults and definition: `-m1 -M1,5 -d1 -f2 -t0`, and
    /// [`FnnVectors::TiseanUnivariate`] (TISEAN ignores `-d` inside the vectors).
    pub fn tisean() -> Self {
        Self {
            m_min: 1,
            m_max: 5,
            tau: 1,
            ratio: 2.0,
            theiler: Some(0),
            vectors: FnnVectors::TiseanUnivariate,
        }
    }

    /// Spacing in samples of the vectors' coordinates: τ, or 1 for TISEAN's univariate vectors.
    pub fn stride(&self) -> usize {
        match self.vectors {
            FnnVectors::Delay => self.tau,
            FnnVectors::TiseanUnivariate => 1,
        }
    }

    /// The Theiler window in effect (`theiler`, or τ when `None`).
    pub fn theiler_window(&self) -> usize {
        self.theiler.unwrap_or(self.tau)
    }
}

/// Result of the false-nearest-neighbour test in one dimension (one line of TISEAN's output).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FnnPoint {
    /// Embedding dimension m.
    pub m: usize,
    /// Fraction of false neighbours among the points with an accepted neighbour; `None` when
    /// no point had one (all nearest neighbours farther than σ/R_t).
    pub fraction: Option<f64>,
    /// Number of points with an accepted nearest neighbour (the denominator).
    pub accepted: usize,
    /// Number of false neighbours (the numerator).
    pub false_count: usize,
    /// Mean nearest-neighbour distance of the accepted points, data units (TISEAN column 3).
    pub mean_distance: f64,
    /// Root mean square of those distances, data units (TISEAN column 4).
    pub rms_distance: f64,
}
