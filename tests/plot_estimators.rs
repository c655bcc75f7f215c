//! `pdamp plot kantz | mutual | fnn` on the Lorenz x series: each writes a PNG of the requested
//! size that is not blank, shows its data colour and a caption; a constant series is a clear
//! error (no panic), and the figures reject unusable data naming the field.

mod scratch;

use std::io::Write;
use std::path::Path;
use std::process::Command;

use pdamp::analysis::kantz::{KantzDefinition, KantzResult, ScalingOptions};
use pdamp::plot::fnn::FnnFigure;
use pdamp::plot::kantz::KantzFigure;
use pdamp::plot::mutual::MutualFigure;
use pdamp::plot::{render_rgb, FigureOptions};

const LORENZ: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/data/series/lorenz_x_dt0.01_n10000.txt"
);
const W: u32 = 800;
const H: u32 = 600;
/// Okabe–Ito blue (m = 2 of kantz, the curve of mutual and fnn).
const BLUE: [u8; 3] = [0, 114, 178];
/// Okabe–Ito vermillion (the marked minimum / suggested dimension).
const RED: [u8; 3] = [213, 94, 0];

fn pdamp(args: &[&str]) -> (String, bool) {
    let out = Command::new(env!("CARGO_BIN_EXE_pdamp"))
        .args(args)
        .output()
        .unwrap();
    (String::from_utf8(out.stderr).unwrap(), out.status.success())
}

fn count_color(img: &image::RgbImage, c: [u8; 3]) -> usize {
    img.pixels()
        .filter(|p| {
            p.0.iter()
                .zip(c)
                .all(|(a, b)| (*a as i32 - b as i32).abs() <= 12)
        })
        .count()
}

/// Runs `pdamp plot KIND LORENZ ARGS -o FILE` and checks the PNG: size from IHDR, non-blank,
/// the given colours present, dark caption text in the top strip.
fn check_plot(kind: &str, extra: &[&str], colors: &[[u8; 3]]) -> String {
    let dir = scratch::tempdir().unwrap();
    let png = dir.path().join(format!("{kind}.png"));
    let (w, h) = (W.to_string(), H.to_string());
    let mut args = vec!["plot", kind, LORENZ, "-o", png.to_str().unwrap()];
    args.extend_from_slice(&["--width", &w, "--height", &h]);
    args.extend_from_slice(extra);
    let (err, ok) = pdamp(&args);
    assert!(ok, "{kind}: {err}");
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "{kind}: not a PNG");
    assert_eq!(&bytes[12..16], b"IHDR");
    let iw = u32::from_be_bytes(bytes[16..20].try_into().unwrap());
    let ih = u32::from_be_bytes(bytes[20..24].try_into().unwrap());
    assert_eq!((iw, ih), (W, H), "{kind}: size");
    let img = image::load_from_memory(&bytes).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (W, H));
    let non_white = img.pixels().filter(|p| p.0 != [255, 255, 255]).count();
    assert!(
        non_white > (W * H / 50) as usize,
        "{kind}: only {non_white} non-white pixels"
    );
    for &c in colors {
        let n = count_color(&img, c);
        assert!(n >= 200, "{kind}: {n} pixels of colour {c:?}");
    }
    let caption_dark = (0..W)
        .flat_map(|x| (0..H * 6 / 100).map(move |y| (x, y)))
        .filter(|&(x, y)| img.get_pixel(x, y).0.iter().all(|&c| c < 100))
        .count();
    assert!(caption_dark > 50, "{kind}: no caption ({caption_dark})");
    // keep the image for a look when PDAMP_KEEP_PLOTS names a directory
    if let Ok(keep) = std::env::var("PDAMP_KEEP_PLOTS") {
        std::fs::copy(&png, Path::new(&keep).join(format!("{kind}.png"))).unwrap();
    }
    err
}

fn constant_series(dir: &tempfile::TempDir) -> String {
    let path = dir.path().join("constant.txt");
    let mut f = std::fs::File::create(&path).unwrap();
    for _ in 0..2000 {
        writeln!(f, "1.5").unwrap();
    }
    path.to_str().unwrap().to_string()
}

/// A constant series fails with a message saying so, exit status ≠ 0, no panic, no file.
fn check_constant_fails(kind: &str) {
    let dir = scratch::tempdir().unwrap();
    let file = constant_series(&dir);
    let png = dir.path().join("c.png");
    let (err, ok) = pdamp(&["plot", kind, &file, "-o", png.to_str().unwrap()]);
    assert!(!ok, "{kind}: constant series accepted");
    assert!(err.contains("constant"), "{kind}: unclear error: {err}");
    assert!(!err.contains("panicked"), "{kind}: {err}");
    assert!(!png.exists(), "{kind}: wrote a figure of nothing");
}

#[test]
fn kantz_curves_with_fits_and_median_slope() {
    let err = check_plot(
        "kantz",
        &[
            "-m", "2", "-M", "4", "-d", "17", "-s", "200", "--dt", "0.01",
        ],
        &[BLUE],
    );
    // the Lorenz maximal exponent is ≈ 0.906 per time unit = 0.00906 per sample
    let slope: f64 = err
        .split("curves): ")
        .nth(1)
        .and_then(|s| s.split_whitespace().next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("no slope in {err}"));
    assert!((slope - 0.00906).abs() < 0.002, "slope {slope}");
}

#[test]
fn mutual_information_with_first_minimum() {
    let err = check_plot("mutual", &["-D", "50", "--dt", "0.01"], &[BLUE, RED]);
    assert!(err.contains("tau = 17 "), "{err}");
}

#[test]
fn fnn_with_suggested_dimension() {
    let err = check_plot("fnn", &["-M", "1,7", "-d", "17"], &[BLUE, RED]);
    assert!(err.contains("m = 3"), "{err}");
}

#[test]
fn constant_series_is_a_clear_error() {
    for kind in ["kantz", "mutual", "fnn"] {
        check_constant_fails(kind);
    }
}

#[test]
fn figures_reject_unusable_data() {
    let o = FigureOptions {
        width: 400,
        height: 300,
        title: None,
    };
    let empty = KantzResult {
        curves: vec![],
        range: 1.0,
        definition: KantzDefinition::MeanDistance,
    };
    let k = KantzFigure {
        result: &empty,
        scaling: ScalingOptions::default(),
        dt_s: None,
    };
    assert!(render_rgb(&k, &o)
        .unwrap_err()
        .to_string()
        .contains("kantz"));
    let m = MutualFigure {
        values: &[1.0, f64::NAN, 0.5],
        first_minimum: None,
        bins: 16,
        dt_s: None,
    };
    assert!(render_rgb(&m, &o).unwrap_err().to_string().contains("I(τ)"));
    let f = FnnFigure {
        points: &[],
        threshold: 0.01,
        ratio: 10.0,
    };
    assert!(render_rgb(&f, &o).unwrap_err().to_string().contains("fnn"));
}

#[test]
fn pareto_from_a_tradeoff_settings_table() {
    // a settings table as `pdamp tradeoff` writes it (the columns the figure reads)
    let dir = scratch::tempdir().unwrap();
    let table = dir.path().join("tradeoff_settings.csv");
    std::fs::write(
        &table,
        "# pdamp tradeoff\n\
         setting,axis,label,core_seconds_per_point,dissipation_max_rel_error\n\
         reference,reference,reference,480,0\n\
         dt-50,dt-fraction,dt = t_s/50,240,0.004\n\
         dt-20,dt-fraction,dt = t_s/20,96,0.02\n\
         soften-1000,softening,E / 1000,30,0.05\n\
         soften-10000,softening,E / 10000,12,0.3\n",
    )
    .unwrap();
    let settings = table.to_str().unwrap();
    let png = dir.path().join("pareto.png");
    let p = png.to_str().unwrap();
    let (err, ok) = pdamp(&[
        "plot",
        "pareto",
        settings,
        "--y",
        "dissipation_max_rel_error",
        "-o",
        p,
    ]);
    assert!(ok, "{err}");
    let img = image::open(&png).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (1024, 768));
    // the first knob (dt-fraction) in Okabe–Ito blue, the second (softening) in vermillion
    assert!(count_color(&img, BLUE) > 20 && count_color(&img, RED) > 20);
    // an unknown error column is refused naming the option and the choices
    let (err, ok) = pdamp(&["plot", "pareto", settings, "--y", "nope", "-o", p]);
    assert!(!ok);
    assert!(
        err.contains("y: `nope`") && err.contains("resonance_frequency_rel_error"),
        "{err}"
    );
}

#[test]
fn decay_from_a_run_folder_and_from_its_decay_csv() {
    // a run folder whose series.csv is a free decay of the primary (ζ = 0.03, offset −0.2 mm)
    let dir = scratch::tempdir().unwrap();
    let mut series = String::from("time_s,base_u_m,box_z_m\n");
    let (omega0, zeta) = (2.0 * std::f64::consts::PI * 5.0, 0.03_f64);
    let omega_d = omega0 * (1.0 - zeta * zeta).sqrt();
    for i in 0..4000 {
        let t = i as f64 * 1e-3;
        let z = -2e-4 + 1e-3 * (-zeta * omega0 * t).exp() * (omega_d * t).cos();
        series += &format!("{t},0,{z}\n");
    }
    std::fs::write(dir.path().join("series.csv"), series).unwrap();
    let png = dir.path().join("zeta.png");
    let run = dir.path().to_str().unwrap();
    let (err, ok) = pdamp(&["plot", "decay", run, "-o", png.to_str().unwrap()]);
    assert!(ok, "{err}");
    let img = image::open(&png).unwrap().to_rgb8();
    assert!(count_color(&img, BLUE) > 200);
    // the plotted data beside the figure: one row per cycle, ζ of the oscillator
    let data = std::fs::read_to_string(dir.path().join("zeta.csv")).unwrap();
    let mut lines = data.lines();
    assert_eq!(lines.next(), Some("cycle,amplitude_m,damping_ratio"));
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
        .collect();
    assert!(rows.len() >= 15, "{} cycles", rows.len());
    assert!(
        rows.iter().all(|r| (r[2] / zeta - 1.0).abs() < 1e-3),
        "{data}"
    );
    // the same figure from a decay.csv
    let decay_csv = dir.path().join("decay.csv");
    std::fs::write(
        &decay_csv,
        format!(
            "cycle,time_s,amplitude_m,period_s,log_decrement,damping_ratio\n{}",
            rows.iter()
                .map(|r| format!("{},0,{},0.2,0,{}\n", r[0], r[1], r[2]))
                .collect::<String>()
        ),
    )
    .unwrap();
    let png2 = dir.path().join("from_csv.svg");
    let (err, ok) = pdamp(&[
        "plot",
        "decay",
        decay_csv.to_str().unwrap(),
        "-o",
        png2.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    assert!(std::fs::read_to_string(&png2).unwrap().contains("<svg"));
    // too short a series: a clear error, no figure
    let short = dir.path().join("short.csv");
    std::fs::write(
        &short,
        "time_s,box_z_m\n0,1\n0.1,0\n0.2,-1\n0.3,0\n0.4,1\n0.5,0\n0.6,-0.9\n0.7,0\n",
    )
    .unwrap();
    let bad = dir.path().join("bad.png");
    let (err, ok) = pdamp(&[
        "plot",
        "decay",
        short.to_str().unwrap(),
        "-o",
        bad.to_str().unwrap(),
    ]);
    assert!(
        !ok && err.contains("2 full cycles") && !err.contains("panicked"),
        "{err}"
    );
    assert!(!bad.exists());
    // the example in --help
    let out = Command::new(env!("CARGO_BIN_EXE_pdamp"))
        .args(["plot", "--help"])
        .output()
        .unwrap();
    assert!(String::from_utf8(out.stdout)
        .unwrap()
        .contains("pdamp plot decay run/"));
}
