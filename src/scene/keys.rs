//! Scene keys that code sets or varies by name (`--set`, `--vary`, the study's sweeps), as
//! checked constants: a test parses a scene with each of them, so a renamed field breaks the
//! build's tests instead of a sweep at run time.

/// `excitation.frequency`: forcing frequency f (Hz).
pub const EXCITATION_FREQUENCY: &str = "excitation.frequency";
/// `excitation.amplitude`: base amplitude U (m).
pub const EXCITATION_AMPLITUDE: &str = "excitation.amplitude";
/// `damper.gap`: the impact particle's free travel (m).
pub const DAMPER_GAP: &str = "damper.gap";
/// `damper.restitution`: the impact particle's effective restitution e.
pub const DAMPER_RESTITUTION: &str = "damper.restitution";
/// `damper.count`: number of DEM grains.
pub const DAMPER_COUNT: &str = "damper.count";
/// `damper.radius`: DEM grain radius (m).
pub const DAMPER_RADIUS: &str = "damper.radius";
/// `damper.box`: DEM container size `[x, y, z]` (m).
pub const DAMPER_BOX: &str = "damper.box";
/// `damper.seed`: seed of the DEM bed's radii, packing and lattice jitter (its initial state).
pub const DAMPER_SEED: &str = "damper.seed";
/// `damper.gamma_n`: DEM normal damping γ_n (kg s⁻¹ m^-1/2).
pub const DAMPER_GAMMA_N: &str = "damper.gamma_n";
/// `damper.gamma_s`: DEM tangential damping γ_s.
pub const DAMPER_GAMMA_S: &str = "damper.gamma_s";
/// `damper.youngs_modulus`: DEM grains' Young's modulus E (Pa).
pub const DAMPER_YOUNGS_MODULUS: &str = "damper.youngs_modulus";
/// `run.duration`: simulated time (s); replaces `run.periods`.
pub const RUN_DURATION: &str = "run.duration";
/// `run.periods`: simulated forcing periods; replaces `run.duration`.
pub const RUN_PERIODS: &str = "run.periods";
/// `run.analysis_max_samples`: most samples of the analysed series (their interval is the
/// coarser of `run.sample_interval` and the analysis window over this count).
pub const RUN_ANALYSIS_MAX_SAMPLES: &str = "run.analysis_max_samples";
/// `run.analysis_fraction`: last fraction of the run that is analysed (section and series).
pub const RUN_ANALYSIS_FRACTION: &str = "run.analysis_fraction";
/// `run.sample_interval`: output sampling of `series.csv` (s).
pub const RUN_SAMPLE_INTERVAL: &str = "run.sample_interval";
/// `run.dt_fraction`: DEM time step as a fraction of the contact time.
pub const RUN_DT_FRACTION: &str = "run.dt_fraction";
/// `run.energy_ledger`: book the DEM energy ledger (default true).
pub const RUN_ENERGY_LEDGER: &str = "run.energy_ledger";
