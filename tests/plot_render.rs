//! Every figure kind renders headless (bundled font, no display) to a PNG of the requested
//! size that is not blank and shows its data colour; bad data gives errors naming the field.

mod scratch;

use std::path::Path;

use pdamp::analysis::regime::Regime;
use pdamp::error::PlotError;
use pdamp::plot::bed_motion::BedMotionFigure;
use pdamp::plot::bifurcation::BifurcationFigure;
use pdamp::plot::common::{fmt_axis_tick, fmt_tick};
use pdamp::plot::effective::EffectiveFigure;
use pdamp::plot::energy::energy_figure;
use pdamp::plot::frf::{FrfFigure, FrfReference};
use pdamp::plot::poincare::PoincareFigure;
use pdamp::plot::reconstruction::ReconstructionFigure;
use pdamp::plot::regime_frf::{Exponents, RegimeFrfFigure};
use pdamp::plot::regime_map::RegimeMapFigure;
use pdamp::plot::resonance::{resonance_amplitudes, resonance_figure};
use pdamp::plot::spectrum::SpectrumFigure;
use pdamp::plot::{render, render_rgb, Figure, FigureOptions, Series};

mod common;
use common::sdof_amplitude;

const W: u32 = 720;
const H: u32 = 540;
/// Okabe–Ito blue, the first series colour.
const BLUE: [u8; 3] = [0, 114, 178];

fn opts() -> FigureOptions {
    FigureOptions {
        width: W,
        height: H,
        title: None,
    }
}

/// Width and height from the PNG IHDR chunk (bytes 16..24, big-endian), and the decoded RGB.
fn read_png(path: &Path) -> (u32, u32, image::RgbImage) {
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "not a PNG");
    assert_eq!(&bytes[12..16], b"IHDR");
    let w = u32::from_be_bytes(bytes[16..20].try_into().unwrap());
    let h = u32::from_be_bytes(bytes[20..24].try_into().unwrap());
    let img = image::load_from_memory(&bytes).unwrap().to_rgb8();
    (w, h, img)
}

/// Renders to PNG and checks size, non-blankness, that the data colour (or `data_color`)
/// appears, and that text was drawn in the caption strip (font works headless).
fn check_renders<F: Figure>(fig: &F, name: &str, data_color: [u8; 3], min_data_px: usize) {
    let dir = scratch::tempdir().unwrap();
    let path = dir.path().join(format!("{name}.png"));
    render(fig, &path, &opts()).unwrap_or_else(|e| panic!("{name}: {e}"));
    let (w, h, img) = read_png(&path);
    assert_eq!((w, h), (W, H), "{name}: size from IHDR");
    assert_eq!(img.dimensions(), (W, H));
    let non_white = img.pixels().filter(|p| p.0 != [255, 255, 255]).count();
    // axes, ticks and data cover well over 1 % of a real figure; a blank image has 0
    assert!(
        non_white > (W * H / 100) as usize,
        "{name}: only {non_white} non-white pixels"
    );
    let close = |p: &image::Rgb<u8>| {
        p.0.iter()
            .zip(data_color)
            .all(|(a, b)| (*a as i32 - b as i32).abs() <= 12)
    };
    let data_px = img.pixels().filter(|p| close(p)).count();
    assert!(
        data_px >= min_data_px,
        "{name}: {data_px} pixels of the data colour {data_color:?}, want ≥ {min_data_px}"
    );
    // the caption strip (top 6 %) holds dark text pixels: the bundled font rendered
    let caption_dark = (0..W)
        .flat_map(|x| (0..H * 6 / 100).map(move |y| (x, y)))
        .filter(|&(x, y)| img.get_pixel(x, y).0.iter().all(|&c| c < 100))
        .count();
    assert!(
        caption_dark > 50,
        "{name}: no caption text ({caption_dark})"
    );
}

fn frf_data() -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let f: Vec<f64> = (1..=60).map(|i| 0.5 * i as f64).collect();
    let z: Vec<f64> = f
        .iter()
        .map(|&f| sdof_amplitude(f, 2.37 + 0.15, 20.0, 21500.0, 4.5e-3))
        .collect();
    let z1: Vec<f64> = f
        .iter()
        .map(|&f| sdof_amplitude(f, 2.5, 14.0, 21500.0, 4.5e-3))
        .collect();
    (f, z, z1)
}

#[test]
fn frf_with_reference_curves() {
    let (f, z, z1) = frf_data();
    let fig = FrfFigure {
        series: vec![
            Series {
                label: "granular (DEM)",
                x: &f,
                y: &z,
            },
            Series {
                label: "one particle (impact)",
                x: &f,
                y: &z1,
            },
        ],
        reference: Some(FrfReference {
            primary: common::scene_b_primary(),
            particle_mass_kg: Some(common::SCENE_B_PARTICLE_MASS_KG),
            base_amplitude_m: common::SCENE_B_AMPLITUDE_M,
        }),
        fitted: vec![pdamp::plot::frf::FrfFitted {
            series: 0,
            system: pdamp::model::PrimarySystem {
                mass_kg: 2.5,
                stiffness_n_m: 21500.0,
                damping_n_s_m: 14.0,
            },
            base_amplitude_m: 4.5e-3,
        }],
    };
    check_renders(&fig, "frf", BLUE, 200);
}

#[test]
fn bed_motion_with_band_and_force() {
    let t: Vec<f64> = (0..4000).map(|i| i as f64 * 1e-4).collect();
    let w = std::f64::consts::TAU * 15.0;
    let floor: Vec<f64> = t.iter().map(|t| 5e-3 * (w * t).cos()).collect();
    let ceil: Vec<f64> = floor.iter().map(|z| z + 0.06).collect();
    let zcm: Vec<f64> = t
        .iter()
        .map(|t| 0.02 + 8e-3 * (w * t - 0.5).cos())
        .collect();
    let lo: Vec<f64> = zcm.iter().map(|z| z - 0.012).collect();
    let hi: Vec<f64> = zcm.iter().map(|z| z + 0.012).collect();
    let force: Vec<f64> = t
        .iter()
        .map(|t| 20.0 + 30.0 * (w * t).sin().max(0.0))
        .collect();
    let fig = BedMotionFigure {
        time_s: &t,
        floor_z_m: &floor,
        ceiling_z_m: &ceil,
        grain_z_m: &zcm,
        grain_band: Some((&lo, &hi)),
        grain_force_n: Some(&force),
    };
    check_renders(&fig, "bed_motion", BLUE, 200);
}

#[test]
fn poincare_section() {
    // quasi-periodic torus section: a closed curve
    let x: Vec<f64> = (0..500).map(|k| (k as f64 * 0.7548).cos()).collect();
    let y: Vec<f64> = (0..500).map(|k| (k as f64 * 0.7548).sin()).collect();
    let fig = PoincareFigure {
        x: &x,
        y: &y,
        x_label: "z(t_k) (m)".into(),
        y_label: "v(t_k) (m/s)".into(),
    };
    check_renders(&fig, "poincare", BLUE, 300);
}

#[test]
fn spectrum_log_power() {
    let f: Vec<f64> = (0..2000).map(|i| i as f64 * 0.05).collect();
    let p: Vec<f64> = f
        .iter()
        .map(|&f| {
            1e-10 + (-((f - 15.0) / 0.1).powi(2)).exp() + 1e-3 * (-((f - 30.0) / 0.1).powi(2)).exp()
        })
        .collect();
    let fig = SpectrumFigure {
        frequency_hz: &f,
        power: &p,
        forcing_hz: Some(15.0),
        power_label: "power (m²/Hz)".into(),
    };
    check_renders(&fig, "spectrum", BLUE, 200);
}

#[test]
fn delay_reconstruction() {
    let s: Vec<f64> = (0..3000)
        .map(|i| (i as f64 * 0.05).sin() + 0.3 * (i as f64 * 0.131).sin())
        .collect();
    let fig = ReconstructionFigure {
        series: &s,
        lag: 30,
        dt_s: Some(1e-3),
        value_label: "z_cm (m)".into(),
    };
    // the curve is drawn with 60 % alpha on white: blue blended, so test the blend colour
    check_renders(&fig, "reconstruction", [102, 170, 209], 200);
}

#[test]
fn bifurcation_diagram() {
    // logistic map as a stand-in for strobed positions: a period-doubling cascade
    let (mut x, mut z) = (vec![], vec![]);
    for i in 0..300 {
        let r = 2.8 + 1.2 * i as f64 / 300.0;
        let mut v = 0.5;
        for k in 0..400 {
            v = r * v * (1.0 - v);
            if k >= 350 {
                x.push(r);
                z.push(0.01 * v);
            }
        }
    }
    let fig = BifurcationFigure {
        x: &x,
        z_m: &z,
        x_label: "parameter r".into(),
    };
    // black at 60 % alpha on white → grey 102
    check_renders(&fig, "bifurcation", [102, 102, 102], 500);
}

fn regime_of(f: f64) -> Option<Regime> {
    Some(if f < 12.0 {
        Regime::Periodic
    } else if f < 18.0 {
        Regime::QuasiPeriodic
    } else if f < 22.0 {
        Regime::Chaotic
    } else {
        Regime::Periodic
    })
}

/// Vermillion, the data exponent's colour in `regime_frf`.
const VERMILLION: [u8; 3] = [213, 94, 0];

fn count_color(img: &[u8], c: [u8; 3]) -> usize {
    img.chunks(3)
        .filter(|p| {
            p.iter()
                .zip(c)
                .all(|(a, b)| (*a as i32 - b as i32).abs() <= 12)
        })
        .count()
}

#[test]
fn regime_frf_two_panels_with_error_bars() {
    let (f, z, _) = frf_data();
    let regime: Vec<Option<Regime>> = f.iter().map(|&f| regime_of(f)).collect();
    let period: Vec<Option<u32>> = f
        .iter()
        .map(|&f| {
            if f < 12.0 {
                Some(if f > 9.0 { 2 } else { 1 })
            } else {
                None
            }
        })
        .collect();
    let model: Vec<Option<f64>> = f
        .iter()
        .map(|&f| Some(if (18.0..22.0).contains(&f) { 3.0 } else { -0.5 }))
        .collect();
    let model_se = vec![Some(0.2); f.len()];
    // the data exponent only where chaotic, with large error bars
    let data: Vec<Option<f64>> = f
        .iter()
        .map(|&f| (18.0..22.0).contains(&f).then_some(2.5))
        .collect();
    let data_se = vec![Some(1.0); f.len()];
    let fig = RegimeFrfFigure {
        frequency_hz: &f,
        amplitude_m: &z,
        regime: &regime,
        period: Some(&period),
        data: Some(Exponents {
            per_s: &data,
            stderr_per_s: Some(&data_se),
        }),
        model: Some(Exponents {
            per_s: &model,
            stderr_per_s: Some(&model_se),
        }),
        phase_locked: None,
        replica: None,
    };
    // PNG of the requested size, amplitude in blue, data exponent in vermillion
    check_renders(&fig, "regime_frf", BLUE, 200);
    check_renders(&fig, "regime_frf", VERMILLION, 60);
    let img = render_rgb(&fig, &opts()).unwrap();
    assert_eq!(img.len(), (W * H * 3) as usize);
    // two panels: the amplitude (blue) in the upper half, the exponents (vermillion) in the
    // lower half only
    let half = (W * H / 2 * 3) as usize;
    let (upper, lower) = img.split_at(half);
    assert!(
        count_color(upper, BLUE) > 200,
        "amplitude in the upper panel"
    );
    // the legend panel (right, ≥ 200 px) is left out
    let legend_x = W as usize * 7 / 10;
    let in_plot = |part: &[u8]| -> usize {
        part.chunks(3)
            .enumerate()
            .filter(|(i, _)| (i % W as usize) < legend_x)
            .filter(|(_, p)| {
                p.iter()
                    .zip(VERMILLION)
                    .all(|(a, b)| (*a as i32 - b as i32).abs() <= 12)
            })
            .count()
    };
    assert!(in_plot(lower) > 40, "data exponent in the lower panel");
    assert_eq!(in_plot(upper), 0, "no exponent drawn over the FRF");
    // error bars add pixels of the data colour
    let bare = RegimeFrfFigure {
        data: Some(Exponents {
            per_s: &data,
            stderr_per_s: None,
        }),
        ..fig.clone()
    };
    let with_bars = count_color(&img, VERMILLION);
    let without = count_color(&render_rgb(&bare, &opts()).unwrap(), VERMILLION);
    assert!(
        with_bars > without + 50,
        "error bars: {with_bars} vs {without} vermillion pixels"
    );
    // points without an exponent are omitted, not drawn as 0: no data estimate at all leaves
    // no vermillion pixel (and no legend row)
    let none = vec![None; f.len()];
    let empty = RegimeFrfFigure {
        data: Some(Exponents {
            per_s: &none,
            stderr_per_s: Some(&data_se),
        }),
        ..fig.clone()
    };
    assert_eq!(
        count_color(&render_rgb(&empty, &opts()).unwrap(), VERMILLION),
        0
    );
    // without any exponent the figure is the FRF alone (one panel)
    let frf_only = RegimeFrfFigure {
        data: None,
        model: None,
        period: None,
        ..fig.clone()
    };
    check_renders(&frf_only, "regime_frf_only", BLUE, 200);
    // a column of the wrong length is refused, naming it
    let short = vec![Some(1.0); 3];
    let bad = RegimeFrfFigure {
        model: Some(Exponents {
            per_s: &short,
            stderr_per_s: None,
        }),
        ..fig
    };
    let err = render_rgb(&bad, &opts()).unwrap_err().to_string();
    assert!(err.contains("model_mle_per_s"), "{err}");
}

#[test]
fn axis_ticks_print_an_exact_zero() {
    // the tick at zero of a −0.1 … 0.3 axis arrives as 3.5e-18 from floating point
    assert_eq!(fmt_axis_tick(3.5e-18, -0.1, 0.3), "0");
    assert_eq!(fmt_axis_tick(-1.4e-17, -0.2, 0.2), "0");
    assert_eq!(fmt_axis_tick(-2e-7, -500.0, 400.0), "0");
    assert_eq!(fmt_axis_tick(0.0, -1.0, 1.0), "0");
    // a value above span × 1e-9 keeps its value
    assert_eq!(fmt_axis_tick(0.1, -0.1, 0.3), "0.1");
    assert_eq!(fmt_axis_tick(-0.05, -0.1, 0.3), "-0.05");
    assert_eq!(fmt_axis_tick(1e-6, -1e-4, 1e-4), "1.0e-6");
    // an axis not through zero (a log axis of powers) is never snapped
    assert_eq!(fmt_axis_tick(1e-15, 1e-16, 1e-5), "1.0e-15");
    assert_eq!(fmt_axis_tick(2.0e-18, 1e-18, 1e-3), "2.0e-18");
    // reversed limits behave alike; plain values are unchanged
    assert_eq!(fmt_axis_tick(3.5e-18, 0.3, -0.1), "0");
    assert_eq!(fmt_tick(3.5e-18), "3.5e-18");
    assert_eq!(fmt_tick(12.5), "12.5");
    assert_eq!(fmt_tick(0.0), "0");
}

#[test]
fn effective_mass_and_damping() {
    let lz: Vec<f64> = (0..10).map(|i| 0.05 + 0.02 * i as f64).collect();
    let m: Vec<f64> = lz.iter().map(|l| 2.6 - 2.0 * (l - 0.05)).collect();
    let ms = vec![0.01; lz.len()];
    let c: Vec<f64> = lz
        .iter()
        .map(|l| 7.6 + 20.0 * (-((l - 0.12) / 0.06f64).powi(2)).exp())
        .collect();
    let cs = vec![0.8; lz.len()];
    let fig = EffectiveFigure {
        x: &lz,
        x_label: "container height Lz (m)".into(),
        mass_ef_kg: &m,
        mass_ef_stderr_kg: &ms,
        damping_ef_n_s_m: &c,
        damping_ef_stderr_n_s_m: &cs,
        mass_kg: Some(2.37),
        damping_n_s_m: Some(7.6),
    };
    check_renders(&fig, "effective", BLUE, 100);
}

#[test]
fn energy_per_cycle() {
    let f: Vec<f64> = (1..=30).map(|i| i as f64).collect();
    let coll: Vec<f64> = f
        .iter()
        .map(|f| 0.01 * (-((f - 15.0) / 4.0f64).powi(2)).exp())
        .collect();
    let fric: Vec<f64> = coll.iter().map(|c| 0.3 * c).collect();
    let fig = energy_figure(
        &f,
        "frequency f (Hz)",
        &[("collision", &coll), ("friction", &fric)],
    );
    check_renders(&fig, "energy", BLUE, 100);
}

#[test]
fn resonance_amplitude_versus_parameter() {
    // two-key sweep flattened: γ_n × f; Z_res = max over f per γ_n
    let (mut g, mut z) = (vec![], vec![]);
    for gi in 0..6 {
        for fi in 0..20 {
            let gamma = 2000.0 * gi as f64;
            g.push(gamma);
            z.push(sdof_amplitude(
                10.0 + fi as f64 * 0.5,
                2.6,
                5.0 + gamma * 1e-3,
                21500.0,
                4.5e-3,
            ));
        }
    }
    let (x, zr) = resonance_amplitudes(&g, &z);
    assert_eq!(x.len(), 6);
    // Z_res of the first group is the max of its 20 rows
    assert_eq!(zr[0], z[..20].iter().cloned().fold(f64::MIN, f64::max));
    let zr2: Vec<f64> = zr.iter().map(|v| 0.8 * v).collect();
    let fig = resonance_figure(
        vec![
            Series {
                label: "N = 250",
                x: &x,
                y: &zr,
            },
            Series {
                label: "N = 1000",
                x: &x,
                y: &zr2,
            },
        ],
        "normal damping γ_n (kg s⁻¹ m^-1/2)",
    );
    check_renders(&fig, "resonance", BLUE, 100);
}

#[test]
fn regime_map_cells_and_legend() {
    let (mut x, mut y, mut reg, mut mle, mut per) = (vec![], vec![], vec![], vec![], vec![]);
    for i in 0..12 {
        for j in 0..8 {
            let f = 5.0 + 2.0 * i as f64;
            let lz = 0.05 + 0.02 * j as f64;
            x.push(f);
            y.push(lz);
            let chaotic = (f - 15.0).abs() < 4.0 && lz > 0.1;
            reg.push(Some(if chaotic {
                Regime::Chaotic
            } else if f > 20.0 {
                Regime::QuasiPeriodic
            } else {
                Regime::Periodic
            }));
            mle.push(Some(if chaotic { 2.5 } else { -0.4 }));
            per.push((!chaotic && f <= 20.0).then_some(if f < 8.0 { 3 } else { 1 }));
        }
    }
    let fig = RegimeMapFigure {
        x: &x,
        y: &y,
        regime: &reg,
        period: Some(&per),
        mle_per_s: Some(&mle),
        mle_label: "λ (1/s)".into(),
        x_label: "frequency f (Hz)".into(),
        y_label: "container height Lz (m)".into(),
    };
    // chaotic cells at the largest exponent: the darkest chaotic shade
    check_renders(&fig, "regime_map", [150, 15, 20], 2000);
    // periodic cells of period ≥ 2: darker green, numbered
    check_renders(&fig, "regime_map", [25, 120, 55], 2000);
    // a figure without exponents and periods still renders (regime colours only)
    let plain = RegimeMapFigure {
        period: None,
        mle_per_s: None,
        ..fig
    };
    // periodic green (60, 175, 90) at 80 % on white
    check_renders(&plain, "regime_map_plain", [99, 191, 123], 2000);
}

#[test]
fn regime_map_uneven_rows_are_equal() {
    // gaps 0.003 … 0.333 m: on a proportional axis the 0.003 m row would be ~2 % of the
    // height; one equal row per value gives it a third
    let gaps = [0.003, 0.013, 0.333];
    let (mut x, mut y, mut reg) = (vec![], vec![], vec![]);
    for &g in &gaps {
        for i in 0..10 {
            x.push(2.0 + i as f64);
            y.push(g);
            reg.push(Some(if g == 0.003 {
                Regime::Chaotic
            } else {
                Regime::Periodic
            }));
        }
    }
    let fig = RegimeMapFigure {
        x: &x,
        y: &y,
        regime: &reg,
        period: None,
        mle_per_s: None,
        mle_label: String::new(),
        x_label: "frequency f (Hz)".into(),
        y_label: "gap (m)".into(),
    };
    let img = render_rgb(&fig, &opts()).unwrap();
    // a chaotic cell without an exponent takes the middle shade
    let mid = [199, 108, 105];
    let n = count_color(&img, mid);
    assert!(
        n > (W * H / 10) as usize,
        "{n} pixels of the 0.003 m row, want over a tenth of the image"
    );
}

#[test]
fn render_rgb_has_requested_size_and_custom_title() {
    let (f, z, _) = frf_data();
    let fig = FrfFigure {
        series: vec![Series {
            label: "run",
            x: &f,
            y: &z,
        }],
        reference: None,
        fitted: Vec::new(),
    };
    let o = FigureOptions {
        width: 400,
        height: 300,
        title: Some("custom".into()),
    };
    let buf = render_rgb(&fig, &o).unwrap();
    assert_eq!(buf.len(), 400 * 300 * 3);
    assert!(buf.iter().any(|&b| b != 255));
}

// ---------- negative controls: bad data never gives a silent figure ----------

#[test]
fn nan_in_data_is_an_error_naming_the_field() {
    let f = [1.0, 2.0, 3.0];
    let z = [1e-3, f64::NAN, 2e-3];
    let fig = FrfFigure {
        series: vec![Series {
            label: "run",
            x: &f,
            y: &z,
        }],
        reference: None,
        fitted: Vec::new(),
    };
    let dir = scratch::tempdir().unwrap();
    let path = dir.path().join("bad.png");
    let e = render(&fig, &path, &opts()).unwrap_err();
    assert!(matches!(e, PlotError::BadData { .. }));
    assert!(
        e.to_string().contains("run (y)") && e.to_string().contains("row 1"),
        "{e}"
    );
    assert!(!path.exists(), "no file may be written for bad data");
}

#[test]
fn mismatched_lengths_empty_data_and_bad_extension_are_errors() {
    let t = [0.0, 1.0, 2.0];
    let short = [0.0, 1.0];
    let fig = BedMotionFigure {
        time_s: &t,
        floor_z_m: &t,
        ceiling_z_m: &short,
        grain_z_m: &t,
        grain_band: None,
        grain_force_n: None,
    };
    let e = render_rgb(&fig, &opts()).unwrap_err();
    assert!(e.to_string().contains("ceiling_z_m"), "{e}");
    let empty = PoincareFigure {
        x: &[],
        y: &[],
        x_label: "x".into(),
        y_label: "y".into(),
    };
    assert!(render_rgb(&empty, &opts()).is_err());
    let s = [1.0, 2.0, 3.0, 4.0];
    let rec = ReconstructionFigure {
        series: &s,
        lag: 10,
        dt_s: None,
        value_label: "s".into(),
    };
    assert!(render_rgb(&rec, &opts())
        .unwrap_err()
        .to_string()
        .contains("lag"));
    let ok = PoincareFigure {
        x: &s,
        y: &s,
        x_label: "x".into(),
        y_label: "y".into(),
    };
    let e = render(&ok, Path::new("/tmp/x.jpg"), &opts()).unwrap_err();
    assert!(matches!(e, PlotError::Format { .. }), "{e}");
    let zero = SpectrumFigure {
        frequency_hz: &s,
        power: &[0.0; 4],
        forcing_hz: None,
        power_label: "p".into(),
    };
    assert!(render_rgb(&zero, &opts())
        .unwrap_err()
        .to_string()
        .contains("power"));
}

#[test]
fn recurrence_plot_downsampled() {
    use pdamp::analysis::recurrence::{recurrence_grid, RecurrenceOptions, RecurrenceThreshold};
    use pdamp::plot::recurrence::RecurrenceFigure;
    // a sine's recurrence plot is diagonal stripes: many fully recurrent (black) cells, far
    // more than the axes and text contribute
    let x: Vec<f64> = (0..1200).map(|i| (i as f64 * 0.1).sin()).collect();
    let o = RecurrenceOptions {
        m: 2,
        tau: 16,
        threshold: RecurrenceThreshold::Fixed(0.2),
        ..Default::default()
    };
    let grid = recurrence_grid(&x, &o, 400).unwrap();
    assert_eq!(grid.block, 3, "1184 vectors in ≤ 400 cells per side");
    let fig = RecurrenceFigure {
        grid: &grid,
        embedding: (2, 16),
    };
    assert!(fig.default_title().contains("RR"));
    check_renders(&fig, "recurrence", [0, 0, 0], 3000);
}

#[test]
fn d2_local_slopes_with_plateau() {
    use pdamp::analysis::correlation_dimension::{correlation_dimension, D2Options};
    let x = pdamp::systems::henon::henon_x(3000);
    let o = D2Options {
        m_min: 1,
        m_max: 3,
        eps_max: Some(0.5),
        eps_count: 30,
        ..D2Options::default()
    };
    let (sums, est) = correlation_dimension(&x, &o, &Default::default()).unwrap();
    let fig = pdamp::plot::correlation_dimension::D2Figure {
        sums: &sums,
        estimate: Some(&est),
    };
    assert!(fig.default_title().contains("D2 ="));
    // the m = 1 curve is drawn in the first palette colour
    check_renders(&fig, "d2", BLUE, 200);
}

#[test]
fn svg_output_is_the_same_drawing_as_vectors() {
    // `-o x.svg` draws the figure with plotters' SVG backend: a standalone <svg> document of
    // the requested size, the caption as text, the data as vector primitives; written through a
    // temporary sibling, so nothing else is left in the directory.
    let dir = std::env::temp_dir().join(format!("pdamp_svg_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let x: Vec<f64> = (0..50).map(|i| (i as f64 * 0.3).sin()).collect();
    let y: Vec<f64> = (0..50).map(|i| (i as f64 * 0.3).cos()).collect();
    let fig = PoincareFigure {
        x: &x,
        y: &y,
        x_label: "z (m)".into(),
        y_label: "v (m/s)".into(),
    };
    let path = dir.join("section.SVG");
    let o = FigureOptions {
        title: Some("An SVG section".into()),
        ..opts()
    };
    render(&fig, &path, &o).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.starts_with("<svg"), "{}", &text[..text.len().min(80)]);
    assert!(text.trim_end().ends_with("</svg>"));
    assert!(text.contains(&format!("width=\"{}\"", o.width)), "size");
    assert!(text.contains("An SVG section"), "caption as text");
    assert!(text.contains("z (m)"), "axis label as text");
    // 50 points drawn as vector marks (circles or paths), not a raster image
    assert!(!text.contains("<image"), "no embedded raster");
    let marks = text.matches("<circle").count() + text.matches("<path").count();
    assert!(marks >= 50, "{marks} vector marks");
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left.len(), 1, "only the figure remains: {left:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}
