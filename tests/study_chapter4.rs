//! The chapter-4 DEM study on a reduced grid (two frequencies, 12 forcing periods): every figure
//! and table is written, the run-length check pairs every frequency, and the bed's collective
//! impacts show the physics — at 14.5 Hz (Γ ≈ 3.8 with the primary's amplification) the bed
//! hits the floor and the ceiling once each per period (the source's "two impacts per period"),
//! at 5.5 Hz (box acceleration below g) it never leaves the floor.

mod scratch;

use pdamp::plot::table::Table;
use pdamp::plot::FigureOptions;
use pdamp::study::chapter4;
use pdamp::study::pipeline::Ctx;
use pdamp::study::settings::{Chapter4Settings, CH4_QUICK_DT_FRACTION, CH4_SLOWER_DT_FRACTION};
use pdamp::study::{Mode, Settings};

#[test]
fn reduced_chapter4_study_writes_every_figure_and_counts_two_impacts_at_14_5_hz() {
    let dir = scratch::tempdir().unwrap();
    let ctx = Ctx {
        out: dir.path().to_path_buf(),
        figure: FigureOptions {
            width: 640,
            height: 480,
            title: None,
        },
        progress: &|_| {},
        points: Default::default(),
    };
    let s = Settings::for_mode(Mode::Quick);
    let d = s.dem.clone().unwrap();
    let c = Chapter4Settings {
        frequencies_hz: vec![5.5, 14.5],
        periods: 12.0,
        duration_s: None,
        panel_freqs_hz: vec![14.5],
        doubling_freqs_hz: vec![5.5, 14.5],
        check_freqs_hz: vec![5.5, 14.5],
        ensemble_seeds: vec![2],
        recipe_freqs_hz: vec![5.5, 14.5],
        dt_fraction: CH4_QUICK_DT_FRACTION,
        slower_dt_fraction: Some(CH4_SLOWER_DT_FRACTION),
    };
    let figures = chapter4::all(&ctx, &s, &d, &c, &|_| true).unwrap().figures;
    let names: Vec<&str> = figures.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "ch4_regime_frf",
            "ch4_ensemble",
            "ch4_bifurcation",
            "ch4_impacts",
            "ch4_run_length",
            "ch4_checks",
            "ch4_time_step",
            "ch4_panel_f14.5",
            "ch4_reconstruction"
        ]
    );
    for n in &names {
        let png = dir.path().join(format!("{n}.png"));
        assert!(
            std::fs::metadata(&png).unwrap().len() > 5000,
            "{n}.png too small"
        );
    }
    let impacts = Table::read(&dir.path().join("ch4_impacts.csv")).unwrap();
    let f = impacts.f64_column("frequency_hz").unwrap();
    let floor = impacts.f64_column("floor_impacts_per_cycle").unwrap();
    let ceiling = impacts.f64_column("ceiling_impacts_per_cycle").unwrap();
    assert_eq!(f, [5.5, 14.5]);
    assert_eq!((floor[0], ceiling[0]), (0.0, 0.0), "5.5 Hz: the bed rests");
    assert!(
        (floor[1] - 1.0).abs() <= 0.15 && (ceiling[1] - 1.0).abs() <= 0.15,
        "14.5 Hz: one floor and one ceiling impact per period, got {} and {}",
        floor[1],
        ceiling[1]
    );
    let runs = Table::read(&dir.path().join("ch4_run_length.csv")).unwrap();
    assert_eq!(runs.rows.len(), 2);
    let change = runs.f64_column("amplitude_change_pct").unwrap();
    assert!(change.iter().all(|c| c.is_finite()), "{change:?}");
    // two starts per frequency; each frequency's ensemble words name the count of starts
    let ens = Table::read(&dir.path().join("ch4_ensemble.csv")).unwrap();
    assert_eq!(ens.rows.len(), 4);
    let words = ens.str_column("ensemble").unwrap();
    assert!(
        words
            .iter()
            .all(|w| w.ends_with("in all 2 starts") || w.starts_with("split: ")),
        "{words:?}"
    );
    // the checks: one row per frequency, every comparison filled
    let checks = Table::read(&dir.path().join("ch4_checks.csv")).unwrap();
    assert_eq!(checks.f64_column("frequency_hz").unwrap(), [5.5, 14.5]);
    for col in [
        "ensemble",
        "same_doubled",
        "same_soft_scene",
        "verdict_soft_scene",
    ] {
        let v = checks.str_column(col).unwrap();
        assert!(v.iter().all(|w| !w.is_empty()), "{col}: {v:?}");
    }
    let runs = checks.str_column("run_length").unwrap();
    assert!(
        runs.iter()
            .all(|w| w.starts_with("settled over 12 periods and 24 periods")
                || w.starts_with("unsettled: ")),
        "{runs:?}"
    );
    let same = checks.str_column("same_soft_scene").unwrap();
    assert!(
        same.iter().all(|w| *w == "true" || *w == "false"),
        "{same:?}"
    );
    assert!(dir
        .path()
        .join("data/dem_soft_p12_dt20/sweep.json")
        .is_file());
    // the time-step check: the same frequencies at t_s/50 (the scene file's step, its own
    // folder) against the study's t_s/20, with the starts' spread beside the change; each
    // step is snapped down to a divisor of the analysis sample clock, so the ratio is 2.5
    // within one step of that division
    let steps = Table::read(&dir.path().join("ch4_time_step.csv")).unwrap();
    assert_eq!(steps.f64_column("frequency_hz").unwrap(), [5.5, 14.5]);
    let spread = steps.f64_column("amplitude_spread_starts_pct").unwrap();
    assert!(
        spread.iter().all(|s| s.is_finite() && *s >= 0.0),
        "{spread:?}"
    );
    // the mean over the study's starts is the mean of the ensemble table's amplitudes, and the
    // slower step ran its own starts (its mean and change filled)
    let mean = steps.f64_column("amplitude_mean_starts_m").unwrap();
    let ens_f = ens.f64_column("frequency_hz").unwrap();
    let ens_z = ens.f64_column("amplitude_m").unwrap();
    for (f, m) in [5.5, 14.5].iter().zip(&mean) {
        let z: Vec<f64> = ens_f
            .iter()
            .zip(&ens_z)
            .filter(|(g, _)| *g == f)
            .map(|(_, z)| *z)
            .collect();
        let expect = z.iter().sum::<f64>() / z.len() as f64;
        assert_eq!(z.len(), 2);
        assert!(
            (m / expect - 1.0).abs() < 1e-12,
            "{f} Hz: mean {m} against {expect}"
        );
    }
    let change = steps.f64_column("amplitude_mean_change_pct").unwrap();
    assert!(change.iter().all(|c| c.is_finite()), "{change:?}");
    assert!(dir
        .path()
        .join("data/dem_ch4_p12_seeds/sweep.json")
        .is_file());
    let dt = |dir_name: &str| {
        let t = Table::read(&dir.path().join(format!("data/{dir_name}/sweep.csv"))).unwrap();
        t.f64_column("dt_s").unwrap()
    };
    let (fast, slow) = (dt("dem_ch4_p12_dt20"), dt("dem_ch4_p12"));
    for (a, b) in fast.iter().zip(&slow) {
        assert!(
            (2.2..=2.6).contains(&(a / b)),
            "dt {a} against {b}: not 2.5×"
        );
    }
    // the regime table carries the qualifiers and the replica outcome (12 periods: too short
    // for a verdict, but the columns are there)
    let frf = Table::read(&dir.path().join("ch4_regime_frf.csv")).unwrap();
    for col in [
        "verdict",
        "phase_locked",
        "section_scatter",
        "replica",
        "ensemble",
    ] {
        assert!(frf.has(col), "ch4_regime_frf.csv lacks {col}");
    }
    let section = Table::read(&dir.path().join("ch4_panel_f14.5_section.csv")).unwrap();
    // 60 % of 12 periods analysed: the strobe points at t = 5T … 12T
    assert!(
        (7..=8).contains(&section.rows.len()),
        "{} section points",
        section.rows.len()
    );
}
