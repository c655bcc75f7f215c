//! What [`super::kantz`] takes and gives: its options (the definition of S(Δn), the
//! dimensions, radii and steps) and its curves S(Δn) per (m, ε).

/// Largest embedding dimension supported by [`kantz`](super::kantz).
pub const MAX_DIMENSION: usize = 16;

/// Which average over the neighbourhood enters the logarithm of S(Δn).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum KantzDefinition {
    /// pdamp's default, (4.1.7) literally: `ln( mean over U_n of ‖y_{n+Δn} − y_{n'+Δn}‖ )`,
    /// the mean of the Euclidean distances of the full m-dimensional delay vectors.
    #[default]
    MeanDistance,
    /// TISEAN `lyap_k`: `ln( sqrt( mean over U_n of ‖y_{n+Δn} − y_{n'+Δn}‖² ) )`, the log of the
    /// root-mean-square distance (SPEC §8).
    TiseanRms,
}

/// Options of [`kantz`](super::kantz). `Default` gives pdamp's defaults; [`KantzOptions::tisean`] TISEAN's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KantzOptions {
    /// Smallest embedding dimension (TISEAN `-m`, which raises values below 2 to 2). Default 2.
    pub m_min: usize,
    /// Largest embedding dimension, ≤ 16 (TISEAN `-M`). Default 2 (TISEAN) — raise it.
    pub m_max: usize,
    /// Delay τ in samples (TISEAN `-d`). Default 1.
    pub tau: usize,
    /// Smallest neighbourhood radius ε in data units (TISEAN `-r`); `None` = range/1000.
    pub eps_min: Option<f64>,
    /// Largest radius in data units (TISEAN `-R`); `None` = range/100.
    pub eps_max: Option<f64>,
    /// Number of radii, log-spaced from `eps_min` to `eps_max` (TISEAN `-#`). Default 5.
    pub eps_count: usize,
    /// Number of reference points: the first n admissible indices (TISEAN `-n`); `None` = all.
    pub references: Option<usize>,
    /// Largest Δn in samples (TISEAN `-s`). Default 50.
    pub steps: usize,
    /// Theiler window w in samples: neighbours need `|n − n'| > w` (TISEAN `-t`). pdamp
    /// default `None` = one lag τ; TISEAN's default is 0.
    pub theiler: Option<usize>,
    /// Average inside the logarithm. Default [`KantzDefinition::MeanDistance`].
    pub definition: KantzDefinition,
}

impl Default for KantzOptions {
    fn default() -> Self {
        Self {
            m_min: 2,
            m_max: 2,
            tau: 1,
            eps_min: None,
            eps_max: None,
            eps_count: 5,
            references: None,
            steps: 50,
            theiler: None,
            definition: KantzDefinition::MeanDistance,
        }
    }
}

impl KantzOptions {
    /// TISEAN `lyap_k`'s defaults: `-m2 -M2 -d1 -#5 -s50 -t0`, all references, RMS definition.
    pub fn tisean() -> Self {
        Self {
            theiler: Some(0),
            definition: KantzDefinition::TiseanRms,
            ..Self::default()
        }
    }

    /// The Theiler window in effect (`theiler`, or τ when `None`).
    pub fn theiler_window(&self) -> usize {
        self.theiler.unwrap_or(self.tau)
    }
}

/// One curve S(Δn) for a given dimension and radius.
#[derive(Debug, Clone, PartialEq)]
pub struct KantzCurve {
    /// Embedding dimension m.
    pub m: usize,
    /// Neighbourhood radius ε in data units.
    pub eps: f64,
    /// `s[Δn]` = S(Δn) in rescaled units (add `ln(range)` for data units), Δn = 0..=steps;
    /// `None` where no reference point had a neighbour.
    pub s: Vec<Option<f64>>,
    /// Number of reference points that contributed at each Δn (TISEAN's third column).
    pub count: Vec<u64>,
}

/// All curves of one [`kantz`](super::kantz) call.
#[derive(Debug, Clone, PartialEq)]
pub struct KantzResult {
    /// Curves ordered by ε (outer) then m (inner), as TISEAN prints them.
    pub curves: Vec<KantzCurve>,
    /// `max − min` of the series (data units): S in data units is `S + ln(range)`.
    pub range: f64,
    /// Definition used.
    pub definition: KantzDefinition,
}
