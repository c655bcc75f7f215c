//! How much work each reproduction mode does: [`Mode`] → [`Settings`].
//!
//! `Full` keeps the source's parameters (Sánchez 2012 §3.2, SPEC §6): 13.12 s per frequency,
//! 196.83 s for the nonlinear analysis, f from 0.5 to 30 Hz, Lz from 0.042 to 0.372 m, real
//! steel contacts. `Quick` and `Smoke` reduce them; every reduction is listed next to the figure
//! it affects (see [`Settings::reductions`]).

/// Reproduction mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// A few seconds: the smallest runs that still exercise every figure (tests, CI smoke).
    Smoke,
    /// Minutes on 2 cores: shorter runs, fewer points, softened DEM contacts.
    Quick,
    /// The source's parameters unchanged (hours to days).
    Full,
}

impl Mode {
    /// Lower-case name (`smoke`, `quick`, `full`).
    pub fn as_str(self) -> &'static str {
        match self {
            Mode::Smoke => "smoke",
            Mode::Quick => "quick",
            Mode::Full => "full",
        }
    }

    /// The CLI flag selecting this mode.
    pub fn flag(self) -> &'static str {
        match self {
            Mode::Smoke => "--smoke",
            Mode::Quick => "--quick",
            Mode::Full => "--full",
        }
    }
}

/// A frequency range `start:stop:step` (Hz), as given to `pdamp sweep --vary`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreqRange {
    /// First frequency (Hz).
    pub start_hz: f64,
    /// Last frequency (Hz), included when on the grid.
    pub stop_hz: f64,
    /// Step (Hz).
    pub step_hz: f64,
}

impl FreqRange {
    const fn new(start_hz: f64, stop_hz: f64, step_hz: f64) -> Self {
        FreqRange {
            start_hz,
            stop_hz,
            step_hz,
        }
    }

    /// The `--vary` range text `START:STOP:STEP`.
    pub fn vary(&self) -> String {
        format!("{}:{}:{}", self.start_hz, self.stop_hz, self.step_hz)
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        ((self.stop_hz - self.start_hz) / self.step_hz + 1e-9).floor() as usize + 1
    }

    /// Always false (a range has at least its start).
    pub fn is_empty(&self) -> bool {
        false
    }
}

/// Settings of the DEM part of the figure set (scene B, SPEC §6).
#[derive(Debug, Clone, PartialEq)]
pub struct DemSettings {
    /// Young's modulus divisor (1 = real steel; 1000 = `thesis_b_soft.toml`: contacts 16×
    /// longer, restitution curve e(v) unchanged).
    pub soften: f64,
    /// Time step as a fraction of the Hertz contact time (`run.dt_fraction`).
    pub dt_fraction: f64,
    /// Seconds of drive per frequency point.
    pub duration_s: f64,
    /// Frequency range of the FRF and energy sweeps.
    pub freq: FreqRange,
    /// Frequencies of the Lz / N / γ_n sweeps (around the resonance).
    pub res_freq: FreqRange,
    /// Container heights Lz (m) of the effective-mass and Z_res-versus-Lz figures.
    pub heights_m: Vec<f64>,
    /// Grain numbers N (at fixed total grain mass) of the "several N" figures.
    pub counts: Vec<usize>,
    /// γ_n values (kg s⁻¹ m^-1/2, before softening) of the Z_res-versus-γ_n figure.
    pub gamma_n: Vec<f64>,
    /// Seconds of drive of the bed-motion run (at 15 Hz).
    pub bed_duration_s: f64,
    /// The source's chapter-4 study (regimes along f at Lz = 0.1225 m); `None` skips it.
    pub chapter4: Option<Chapter4Settings>,
}

/// The chapter-4 study's time step in the quick mode, t_s/20: at every one of its 26
/// frequencies the verdict of t_s/50 (the step `data/scenes/thesis_b_ch4.toml` is written
/// with) where that run's three initial packings agree, and the amplitude averaged over three
/// starts within 1.7 % of t_s/50's (`ch4_time_step`, `--ch4-checks`); 2.5× fewer steps.
pub const CH4_QUICK_DT_FRACTION: f64 = 0.05;

/// The shorter step the time-step check compares the chapter-4 study with (t_s/50).
pub const CH4_SLOWER_DT_FRACTION: f64 = 0.02;

/// Settings of the chapter-4 study (`study::chapter4`): scene B's DEM bed at Lz = 0.1225 m
/// (`data/scenes/thesis_b_ch4.toml`) analysed for its regime at every frequency.
#[derive(Debug, Clone, PartialEq)]
pub struct Chapter4Settings {
    /// Forcing frequencies of the regime sweep (Hz); the panel frequencies among them.
    pub frequencies_hz: Vec<f64>,
    /// Forcing periods per run (the scene file's `run.periods`) when `duration_s` is `None`.
    pub periods: f64,
    /// Seconds per run instead of a number of periods (the source's 196.83 s).
    pub duration_s: Option<f64>,
    /// Time step of the study's runs as a fraction of the Hertz contact time
    /// (`run.dt_fraction`).
    pub dt_fraction: f64,
    /// The time-step check (`ch4_time_step`): every frequency again at this shorter step
    /// (`run.dt_fraction`), verdict by verdict and amplitude by amplitude; `None` skips it.
    pub slower_dt_fraction: Option<f64>,
    /// Frequencies of the per-frequency panels and reconstructions (Hz; Figs. 4.2–4.7).
    pub panel_freqs_hz: Vec<f64>,
    /// Frequencies (Hz, a subset of `frequencies_hz`) repeated with runs twice as long
    /// (`ch4_run_length`); empty skips the check.
    pub doubling_freqs_hz: Vec<f64>,
    /// Frequencies (Hz, a subset of `frequencies_hz`) repeated from the `ensemble_seeds`
    /// packings (`ch4_ensemble`); empty skips the check.
    pub check_freqs_hz: Vec<f64>,
    /// Packing seeds (`damper.seed`) of further initial states at the check frequencies,
    /// beside the scene's own (seed 1): the ensemble check; empty skips it.
    pub ensemble_seeds: Vec<u64>,
    /// Frequencies (Hz, a subset of `frequencies_hz`) run with the other shipped softened
    /// scene (`thesis_b_soft.toml`, the same bed with other analysis windows) for `ch4_checks`;
    /// empty skips it.
    pub recipe_freqs_hz: Vec<f64>,
}

impl Chapter4Settings {
    /// With the checks of the verdicts (`pdamp reproduce --ch4-checks`), at every frequency of
    /// the sweep: two more initial packings (seeds 2 and 3), runs twice as long, the other
    /// shipped softened scene (`thesis_b_soft.toml`) and, where the study's step is longer than
    /// t_s/50, the same runs at t_s/50 ([`CH4_SLOWER_DT_FRACTION`]).
    pub fn with_checks(mut self) -> Chapter4Settings {
        self.check_freqs_hz = self.frequencies_hz.clone();
        self.doubling_freqs_hz = self.frequencies_hz.clone();
        self.recipe_freqs_hz = self.frequencies_hz.clone();
        self.ensemble_seeds = vec![2, 3];
        self.slower_dt_fraction =
            (self.dt_fraction > CH4_SLOWER_DT_FRACTION).then_some(CH4_SLOWER_DT_FRACTION);
        self
    }

    /// Whether these settings run the checks of [`Chapter4Settings::with_checks`] (the
    /// further initial packings; `--ch4-checks` on the command line that reproduces them).
    pub fn has_checks(&self) -> bool {
        !self.ensemble_seeds.is_empty()
    }
}

/// The source's per-frequency panels of chapter 4 (Hz).
pub const CH4_PANEL_HZ: [f64; 9] = [5.5, 7.5, 8.0, 10.0, 10.5, 11.0, 13.0, 14.5, 21.0];

/// Everything a reproduction run does, for one [`Mode`].
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// The mode these settings belong to.
    pub mode: Mode,
    /// Frequencies of the impact-model FRFs (Hz).
    pub freq: FreqRange,
    /// Seconds per frequency point of the impact-model sweeps.
    pub duration_s: f64,
    /// Gaps (m) of the impact-model effective-mass and Z_res figures; the first is 0
    /// (clamped particle) and the last "huge".
    pub gaps_m: Vec<f64>,
    /// Frequencies of the gap × frequency grid (Hz).
    pub grid_freq: FreqRange,
    /// Restitutions of the Z_res-versus-e figure.
    pub restitutions: Vec<f64>,
    /// Gaps (m) of the Z_res-versus-e figure (one curve each).
    pub restitution_gaps_m: Vec<f64>,
    /// Frequencies of the regime / bifurcation sweep (with nonlinear analysis).
    pub regime_freq: FreqRange,
    /// Seconds per point of the analysed sweeps.
    pub regime_duration_s: f64,
    /// Gaps (m) of the regime map.
    pub map_gaps_m: Vec<f64>,
    /// Frequencies of the regime map (Hz).
    pub map_freq: FreqRange,
    /// Forcing frequencies (Hz) of the per-frequency Poincaré / spectrum / reconstruction
    /// figures.
    pub series_freqs_hz: Vec<f64>,
    /// Forcing periods simulated for each per-frequency series (the steady state is the
    /// last half).
    pub series_periods: u32,
    /// DEM figures; `None` skips them.
    pub dem: Option<DemSettings>,
}

/// Gap (m) of the impact stand-in for scene B's Lz = 0.1225 m: Lz minus the bed at rest
/// (≈ 0.039 m, SPEC §6).
pub const SCENE_B_GAP_M: f64 = 0.0835;
/// Height of scene B's bed at rest (m), SPEC §6: the impact model's gap is Lz minus this.
pub const SCENE_B_BED_M: f64 = 0.039;

impl Settings {
    /// The settings of `mode`.
    pub fn for_mode(mode: Mode) -> Settings {
        match mode {
            Mode::Full => Settings {
                mode,
                freq: FreqRange::new(0.5, 30.0, 0.1),
                duration_s: 13.12,
                gaps_m: vec![
                    0.0, 0.003, 0.013, 0.028, 0.046, 0.056, 0.071, 0.081, 0.091, 0.111, 0.128,
                    0.226, 0.333, 1.0,
                ],
                grid_freq: FreqRange::new(0.5, 30.0, 0.1),
                restitutions: (0..=20).map(|i| i as f64 * 0.05).collect(),
                restitution_gaps_m: vec![0.013, SCENE_B_GAP_M, 0.333],
                regime_freq: FreqRange::new(0.5, 30.0, 0.1),
                regime_duration_s: 196.83,
                map_gaps_m: vec![
                    0.003, 0.013, 0.028, 0.046, 0.071, 0.091, 0.128, 0.226, 0.333,
                ],
                map_freq: FreqRange::new(0.5, 30.0, 0.1),
                series_freqs_hz: vec![10.0, 14.5, 20.0],
                series_periods: 4000,
                dem: Some(DemSettings {
                    soften: 1.0,
                    dt_fraction: 0.01,
                    duration_s: 13.12,
                    freq: FreqRange::new(0.5, 30.0, 0.5),
                    res_freq: FreqRange::new(10.0, 20.0, 0.5),
                    heights_m: vec![
                        0.042, 0.052, 0.067, 0.085, 0.095, 0.11, 0.12, 0.13, 0.15, 0.167, 0.265,
                        0.372,
                    ],
                    counts: vec![250, 500, 1000],
                    gamma_n: vec![0.0, 100.0, 500.0, 1000.0, 3660.0, 10000.0],
                    bed_duration_s: 13.12,
                    chapter4: Some(Chapter4Settings {
                        frequencies_hz: (1..=60).map(|i| i as f64 * 0.5).collect(),
                        periods: 100.0,
                        duration_s: Some(196.83),
                        dt_fraction: 0.01,
                        slower_dt_fraction: None,
                        panel_freqs_hz: CH4_PANEL_HZ.to_vec(),
                        doubling_freqs_hz: Vec::new(),
                        check_freqs_hz: Vec::new(),
                        ensemble_seeds: Vec::new(),
                        recipe_freqs_hz: Vec::new(),
                    }),
                }),
            },
            Mode::Quick => Settings {
                mode,
                freq: FreqRange::new(0.5, 30.0, 0.25),
                duration_s: 13.12,
                gaps_m: vec![
                    0.0, 0.003, 0.013, 0.028, 0.046, 0.071, 0.091, 0.128, 0.226, 0.333, 1.0,
                ],
                grid_freq: FreqRange::new(2.0, 30.0, 0.25),
                restitutions: (0..=10).map(|i| i as f64 * 0.1).collect(),
                restitution_gaps_m: vec![0.013, SCENE_B_GAP_M, 0.333],
                regime_freq: FreqRange::new(2.0, 30.0, 0.25),
                regime_duration_s: 40.0,
                map_gaps_m: vec![0.003, 0.013, 0.028, 0.046, 0.071, 0.128, 0.226, 0.333],
                map_freq: FreqRange::new(2.0, 30.0, 1.0),
                series_freqs_hz: vec![10.0, 14.5, 20.0],
                series_periods: 1000,
                dem: Some(DemSettings {
                    soften: 1000.0,
                    dt_fraction: 0.02,
                    duration_s: 1.5,
                    freq: FreqRange::new(4.0, 28.0, 2.0),
                    res_freq: FreqRange::new(11.0, 17.0, 1.0),
                    heights_m: vec![0.052, 0.085, 0.12, 0.167, 0.265],
                    counts: vec![125, 250],
                    gamma_n: vec![0.0, 500.0, 3660.0, 10000.0],
                    bed_duration_s: 1.0,
                    chapter4: Some({
                        // 5–26 Hz step 1 and the panel frequencies between; `--ch4-checks`
                        // repeats every point with its run doubled and from two more initial
                        // packings (the run-length and ensemble checks of every verdict)
                        let frequencies_hz = vec![
                            5.0, 5.5, 6.0, 7.0, 7.5, 8.0, 9.0, 10.0, 10.5, 11.0, 12.0, 13.0, 14.0,
                            14.5, 15.0, 16.0, 17.0, 18.0, 19.0, 20.0, 21.0, 22.0, 23.0, 24.0, 25.0,
                            26.0,
                        ];
                        Chapter4Settings {
                            doubling_freqs_hz: Vec::new(),
                            check_freqs_hz: Vec::new(),
                            ensemble_seeds: Vec::new(),
                            recipe_freqs_hz: Vec::new(),
                            frequencies_hz,
                            periods: 200.0,
                            duration_s: None,
                            dt_fraction: CH4_QUICK_DT_FRACTION,
                            slower_dt_fraction: None,
                            panel_freqs_hz: CH4_PANEL_HZ.to_vec(),
                        }
                    }),
                }),
            },
            Mode::Smoke => Settings {
                mode,
                freq: FreqRange::new(4.0, 26.0, 1.0),
                duration_s: 4.0,
                gaps_m: vec![0.0, 0.013, 0.046, 0.128, 1.0],
                grid_freq: FreqRange::new(6.0, 24.0, 0.5),
                restitutions: vec![0.0, 0.5, 1.0],
                restitution_gaps_m: vec![0.013, SCENE_B_GAP_M],
                regime_freq: FreqRange::new(6.0, 24.0, 3.0),
                regime_duration_s: 6.0,
                map_gaps_m: vec![0.013, 0.128],
                map_freq: FreqRange::new(8.0, 24.0, 8.0),
                series_freqs_hz: vec![20.0],
                series_periods: 120,
                dem: None,
            },
        }
    }

    /// Human-readable differences from the source's parameters (`Full`), for the settings
    /// named in `keys` (`freq`, `duration`, `gaps`, `grid`, `restitutions`, `regime`, `map`,
    /// `series`, `dem`, `dem_material` (softening and time step only), `dem_lz`, `dem_n`, `dem_gamma`, `dem_bed`). Empty in `Full` mode.
    pub fn reductions(&self, keys: &[&str]) -> Vec<String> {
        let full = Settings::for_mode(Mode::Full);
        let mut out = Vec::new();
        let mut diff = |what: &str, ours: String, theirs: String| {
            if ours != theirs {
                out.push(format!("{what}: {ours} (source: {theirs})"));
            }
        };
        let fr = |r: &FreqRange| format!("{}–{} Hz step {} Hz", r.start_hz, r.stop_hz, r.step_hz);
        let list = |v: &[f64]| {
            format!(
                "{} values {}",
                v.len(),
                v.iter()
                    .map(|x| x.to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        };
        for key in keys {
            match *key {
                "freq" => diff("frequencies", fr(&self.freq), fr(&full.freq)),
                "duration" => diff(
                    "drive per frequency",
                    format!("{} s", self.duration_s),
                    format!("{} s", full.duration_s),
                ),
                "gaps" => diff("gaps (m)", list(&self.gaps_m), list(&full.gaps_m)),
                "grid" => diff("grid frequencies", fr(&self.grid_freq), fr(&full.grid_freq)),
                "restitutions" => diff(
                    "restitutions e",
                    list(&self.restitutions),
                    list(&full.restitutions),
                ),
                "regime" => {
                    diff(
                        "analysed frequencies",
                        fr(&self.regime_freq),
                        fr(&full.regime_freq),
                    );
                    diff(
                        "drive per analysed point",
                        format!("{} s", self.regime_duration_s),
                        format!("{} s", full.regime_duration_s),
                    );
                }
                "map" => {
                    diff(
                        "map gaps (m)",
                        list(&self.map_gaps_m),
                        list(&full.map_gaps_m),
                    );
                    diff("map frequencies", fr(&self.map_freq), fr(&full.map_freq));
                    diff(
                        "drive per analysed point",
                        format!("{} s", self.regime_duration_s),
                        format!("{} s", full.regime_duration_s),
                    );
                }
                "series" => diff(
                    "periods per series",
                    self.series_periods.to_string(),
                    full.series_periods.to_string(),
                ),
                k if k.starts_with("dem") => {
                    let (Some(d), Some(fd)) = (&self.dem, &full.dem) else {
                        continue;
                    };
                    match k {
                        "dem" | "dem_material" => {
                            diff(
                                "grain Young's modulus",
                                if d.soften == fd.soften {
                                    format!("E/{}", d.soften)
                                } else {
                                    format!(
                                        "E/{} with γ scaled by {}^-0.6 (same e(v))",
                                        d.soften, d.soften
                                    )
                                },
                                format!("E/{}", fd.soften),
                            );
                            // the chapter-4 study has its own step (`dem_ch4`)
                            if *key == "dem_material" {
                                continue;
                            }
                            diff(
                                "DEM time step",
                                format!("t_s × {}", d.dt_fraction),
                                format!("t_s × {}", fd.dt_fraction),
                            );
                            diff(
                                "DEM drive per point",
                                format!("{} s", d.duration_s),
                                format!("{} s", fd.duration_s),
                            );
                            diff("DEM frequencies", fr(&d.freq), fr(&fd.freq));
                        }
                        "dem_res" => {
                            diff(
                                "DEM frequencies around resonance",
                                fr(&d.res_freq),
                                fr(&fd.res_freq),
                            );
                        }
                        "dem_lz" => diff("Lz (m)", list(&d.heights_m), list(&fd.heights_m)),
                        "dem_n" => diff(
                            "grain numbers N",
                            format!("{:?}", d.counts),
                            format!("{:?}", fd.counts),
                        ),
                        "dem_gamma" => diff("γ_n", list(&d.gamma_n), list(&fd.gamma_n)),
                        "dem_ch4" => {
                            if let (Some(c), Some(fc)) = (&d.chapter4, &fd.chapter4) {
                                let len = |c: &Chapter4Settings| match c.duration_s {
                                    Some(s) => format!("{s} s"),
                                    None => format!("{} forcing periods", c.periods),
                                };
                                diff("chapter-4 run length", len(c), len(fc));
                                diff(
                                    "chapter-4 time step",
                                    format!("t_s × {}", c.dt_fraction),
                                    format!("t_s × {}", fc.dt_fraction),
                                );
                                diff(
                                    "chapter-4 frequencies",
                                    list(&c.frequencies_hz),
                                    list(&fc.frequencies_hz),
                                );
                            }
                        }
                        "dem_bed" => diff(
                            "bed-motion drive",
                            format!("{} s", d.bed_duration_s),
                            format!("{} s", fd.bed_duration_s),
                        ),
                        _ => {}
                    }
                }
                _ => {}
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn full_mode_has_no_reductions_and_quick_lists_them() {
        let keys = ["freq", "duration", "gaps", "regime", "dem", "dem_lz"];
        assert!(Settings::for_mode(Mode::Full).reductions(&keys).is_empty());
        let quick = Settings::for_mode(Mode::Quick).reductions(&keys);
        assert!(
            quick.iter().any(|r| r.starts_with("frequencies")),
            "{quick:?}"
        );
        assert!(quick.iter().any(|r| r.contains("Young")), "{quick:?}");
    }

    #[test]
    fn gaps_span_clamped_to_huge() {
        for m in [Mode::Smoke, Mode::Quick, Mode::Full] {
            let s = Settings::for_mode(m);
            assert_eq!(s.gaps_m[0], 0.0);
            assert!(*s.gaps_m.last().unwrap() >= 1.0);
        }
    }
}
