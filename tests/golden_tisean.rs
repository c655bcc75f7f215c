//! `pdamp mutual`, `pdamp fnn --tisean`, `pdamp lyap-k --tisean`, `pdamp nrlazy --tisean`,
//! `pdamp d2` and `pdamp lyap-r` (and the statistics of `pdamp surrogates`) against the
//! outputs of the real TISEAN 3.0.1 (`tests/golden/tisean/`, provenance in
//! `tests/golden/README.md`): every row, to TISEAN's print precision (`%e`: 7 significant digits), with the same options.
//!
//! A value `g` printed by TISEAN stands for the interval `g ± ½·10^(e−6)` (e its decimal
//! exponent); pdamp's value must lie inside it (plus 1e-12 relative for rounding in either
//! program). Integer columns (m, Δn, counts) must be equal. The worst difference of each file
//! is printed in units of TISEAN's last digit (`cargo test --release --test golden_tisean --
//! --nocapture`).

use std::path::PathBuf;
use std::process::Command;

fn golden(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/golden/tisean")
        .join(name)
}

fn pdamp(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_pdamp"))
        .args(args)
        .output()
        .expect("run pdamp");
    assert!(
        out.status.success(),
        "pdamp {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("utf-8")
}

/// Data rows of a pdamp CSV (header dropped), split at commas.
fn csv_rows(text: &str) -> Vec<Vec<String>> {
    text.lines()
        .skip(1)
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

/// Rows of a TISEAN output (comment and blank lines dropped), split at whitespace.
fn tisean_rows(text: &str) -> Vec<Vec<String>> {
    text.lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with('#'))
        .map(|l| l.split_whitespace().map(str::to_string).collect())
        .collect()
}

/// Half a unit in the last place of a value printed with `%e` (7 significant digits).
fn half_ulp(printed: &str) -> f64 {
    let exp: i32 = printed
        .split(['e', 'E'])
        .nth(1)
        .and_then(|e| e.parse().ok())
        .unwrap_or_else(|| panic!("{printed} is not in %e format"));
    0.5 * 10f64.powi(exp - 6)
}

/// Whether pdamp's value printed as TISEAN prints it (`%e`) is TISEAN's string.
fn same_print(ours: f64, printed: &str) -> bool {
    let mine = format!("{ours:.6e}");
    let (m1, e1) = mine.split_once('e').unwrap();
    let (m2, e2) = printed.split_once('e').unwrap();
    m1 == m2 && e1.parse::<i32>().ok() == e2.parse::<i32>().ok()
}

/// Worst difference (units of TISEAN's last digit), values compared, values printing the same.
#[derive(Default)]
struct Score(f64, usize, usize);

impl Score {
    fn add(&mut self, what: &str, ours: f64, printed: &str) {
        self.0 = self.0.max(check(what, ours, printed));
        self.1 += 1;
        self.2 += usize::from(same_print(ours, printed));
    }
    fn report(&self, file: &str) {
        eprintln!(
            "{file}: {} values, worst difference {:.3} of TISEAN's last digit, {} print identically",
            self.1, self.0, self.2
        );
    }
}

/// Compares pdamp's value with TISEAN's printed one; returns the difference in units of
/// TISEAN's last printed digit (≤ 0.5 when equal to print precision).
fn check(what: &str, ours: f64, printed: &str) -> f64 {
    let g: f64 = printed.parse().expect("number");
    let h = half_ulp(printed);
    let diff = (ours - g).abs();
    assert!(
        diff <= h + 1e-12 * g.abs(),
        "{what}: pdamp {ours:.10e}, TISEAN {printed} (differs by {:.2} of its last digit)",
        diff / (2.0 * h)
    );
    diff / (2.0 * h)
}

fn mutual_file(series: &str, mut_file: &str) -> f64 {
    let path = golden(series);
    let out = pdamp(&["mutual", path.to_str().unwrap(), "-D100"]);
    let ours = csv_rows(&out);
    let want = tisean_rows(&std::fs::read_to_string(golden(mut_file)).unwrap());
    assert_eq!(ours.len(), want.len(), "{mut_file}: number of lags");
    let mut score = Score::default();
    for (o, w) in ours.iter().zip(&want) {
        assert_eq!(o[0], w[0], "{mut_file}: lag");
        let v: f64 = o[1].parse().unwrap();
        score.add(&format!("{mut_file} τ = {}", w[0]), v, &w[1]);
    }
    score.report(mut_file);
    score.0
}

#[test]
fn mutual_equals_tisean() {
    for s in ["lorenz_x_n10000", "henon_x_n20000", "noisy_sine_n8000"] {
        let series = if s.starts_with("lorenz") {
            format!("{s}.dat")
        } else {
            format!("{s}.txt")
        };
        mutual_file(&series, &format!("{s}.mut"));
    }
}

fn fnn_file(series: &str, opts: &[&str], fnn_file: &str) -> f64 {
    let path = golden(series);
    let mut args = vec!["fnn", path.to_str().unwrap(), "--tisean"];
    args.extend_from_slice(opts);
    let ours = csv_rows(&pdamp(&args));
    let want = tisean_rows(&std::fs::read_to_string(golden(fnn_file)).unwrap());
    assert_eq!(ours.len(), want.len(), "{fnn_file}: number of dimensions");
    let mut score = Score::default();
    // pdamp: m,false_fraction,accepted,false_count,mean_distance,rms_distance;
    // TISEAN: m, fraction, mean distance, RMS distance
    for (o, w) in ours.iter().zip(&want) {
        assert_eq!(o[0], w[0], "{fnn_file}: m");
        let at = |c: usize| -> f64 { o[c].parse().unwrap() };
        for (col, (ours, printed)) in [(at(1), &w[1]), (at(4), &w[2]), (at(5), &w[3])]
            .into_iter()
            .enumerate()
        {
            let what = format!("{fnn_file} m = {} column {}", w[0], col + 2);
            score.add(&what, ours, printed);
        }
    }
    score.report(fnn_file);
    score.0
}

#[test]
fn fnn_lorenz_delay_17_equals_tisean() {
    fnn_file(
        "lorenz_x_n10000.dat",
        &["-m1", "-M1,8", "-d17", "-f10", "-t100"],
        "lorenz_x_n10000.d17_f10_t100.fnn",
    );
    fnn_file(
        "lorenz_x_n10000.dat",
        &["-m1", "-M1,8", "-d17", "-f2", "-t0"],
        "lorenz_x_n10000.d17_f2_t0.fnn",
    );
}

#[test]
fn fnn_henon_equals_tisean() {
    fnn_file(
        "henon_x_n20000.txt",
        &["-m1", "-M1,6", "-d1", "-f10", "-t0"],
        "henon_x_n20000.d1_f10_t0.fnn",
    );
}

#[test]
fn fnn_noisy_sine_equals_tisean() {
    fnn_file(
        "noisy_sine_n8000.txt",
        &["-m1", "-M1,6", "-d9", "-f10", "-t20"],
        "noisy_sine_n8000.d9_f10_t20.fnn",
    );
}

/// TISEAN `lyap_k` output: (ε, m, rows (Δn, S, count)) per block.
type LyapBlock = (String, usize, Vec<(usize, String, u64)>);

fn parse_lyap(text: &str) -> Vec<LyapBlock> {
    let mut blocks: Vec<LyapBlock> = Vec::new();
    for line in text.lines() {
        if let Some(rest) = line.strip_prefix("#epsilon=") {
            let mut it = rest.split_whitespace();
            let eps = it.next().unwrap().to_string();
            assert_eq!(it.next(), Some("dim="));
            let m = it.next().unwrap().parse().unwrap();
            blocks.push((eps, m, Vec::new()));
        } else if !line.trim().is_empty() {
            let f: Vec<&str> = line.split_whitespace().collect();
            let block = blocks.last_mut().expect("row before a block header");
            block.2.push((
                f[0].parse().unwrap(),
                f[1].to_string(),
                f[2].parse().unwrap(),
            ));
        }
    }
    blocks
}

fn lyap_file(series: &str, opts: &[&str], lyap_file: &str) -> f64 {
    let path = golden(series);
    let mut args = vec!["lyap-k", path.to_str().unwrap(), "--tisean"];
    args.extend_from_slice(opts);
    // pdamp: eps,m,dn_samples,s,count, blocks in TISEAN's order (ε outer, m inner)
    let ours = csv_rows(&pdamp(&args));
    let want = parse_lyap(&std::fs::read_to_string(golden(lyap_file)).unwrap());
    let n_rows: usize = want.iter().map(|b| b.2.len()).sum();
    assert_eq!(ours.len(), n_rows, "{lyap_file}: number of rows");
    let mut score = Score::default();
    let mut o = ours.iter();
    for (eps, m, rows) in &want {
        for (dn, s, count) in rows {
            let r = o.next().unwrap();
            let what = format!("{lyap_file} ε = {eps} m = {m} Δn = {dn}");
            score.add(&what, r[0].parse().unwrap(), eps);
            assert_eq!(r[1].parse::<usize>().unwrap(), *m, "{what}: m");
            assert_eq!(r[2].parse::<usize>().unwrap(), *dn, "{what}: Δn");
            assert_eq!(r[4].parse::<u64>().unwrap(), *count, "{what}: count");
            score.add(&what, r[3].parse().unwrap(), s);
        }
    }
    eprintln!("{lyap_file}: {n_rows} rows (ε and S compared)");
    score.report(lyap_file);
    score.0
}

#[test]
fn lyap_k_lorenz_equals_tisean() {
    lyap_file(
        "lorenz_x_n10000.dat",
        &[
            "-m2", "-M6", "-d17", "-r0.05", "-R0.5", "-#4", "-s300", "-t100",
        ],
        "lorenz_x_n10000.lyap",
    );
}

#[test]
fn lyap_k_henon_equals_tisean() {
    lyap_file(
        "henon_x_n20000.txt",
        &[
            "-m2", "-M4", "-d1", "-r0.001", "-R0.01", "-#3", "-s30", "-t0",
        ],
        "henon_x_n20000.lyap",
    );
}

fn nrlazy_file(series: &str, opts: &[&str], laz_file: &str) -> f64 {
    let path = golden(series);
    let mut args = vec!["nrlazy", path.to_str().unwrap(), "--tisean"];
    args.extend_from_slice(opts);
    let ours: Vec<f64> = pdamp(&args)
        .lines()
        .map(|l| l.trim().parse().unwrap())
        .collect();
    let want = tisean_rows(&std::fs::read_to_string(golden(laz_file)).unwrap());
    assert_eq!(ours.len(), want.len(), "{laz_file}: number of samples");
    let mut score = Score::default();
    for (i, (o, w)) in ours.iter().zip(&want).enumerate() {
        score.add(&format!("{laz_file} sample {i}"), *o, &w[0]);
    }
    score.report(laz_file);
    score.0
}

#[test]
fn nrlazy_lorenz_equals_tisean() {
    // TISEAN: nrlazy lorenz_x_n10000.dat -m1,7 -v0.2 -i1 (and -i3)
    nrlazy_file(
        "lorenz_x_n10000.dat",
        &["-m1,7", "--radius-sd", "0.2", "-i1"],
        "lorenz_x_n10000.m7_v0.2_i1.laz",
    );
    nrlazy_file(
        "lorenz_x_n10000.dat",
        &["-m1,7", "--radius-sd", "0.2", "-i3"],
        "lorenz_x_n10000.m7_v0.2_i3.laz",
    );
}

#[test]
fn nrlazy_henon_and_sine_equal_tisean() {
    nrlazy_file(
        "henon_x_n20000.txt",
        &["-m1,5", "-r0.05", "-i2"],
        "henon_x_n20000.m5_r0.05_i2.laz",
    );
    nrlazy_file(
        "noisy_sine_n8000.txt",
        &["-m1,3", "-d9", "--radius-sd", "0.3", "-i2"],
        "noisy_sine_n8000.m3_d9_v0.3_i2.laz",
    );
}

/// The comparison can fail: pdamp's default (middle coordinate, ends unchanged) is not
/// TISEAN's nrlazy and must be told apart from it on the first sample.
#[test]
fn nrlazy_default_is_not_tisean() {
    let path = golden("lorenz_x_n10000.dat");
    let out = pdamp(&[
        "nrlazy",
        path.to_str().unwrap(),
        "-m7",
        "--radius-sd",
        "0.2",
    ]);
    let first: f64 = out.lines().next().unwrap().parse().unwrap();
    let want =
        tisean_rows(&std::fs::read_to_string(golden("lorenz_x_n10000.m7_v0.2_i1.laz")).unwrap());
    let g: f64 = want[0][0].parse().unwrap();
    assert!((first - g).abs() > 0.2, "pdamp {first}, TISEAN {g}");
    // TISEAN's -v (radius in standard deviations) and -V are refused, not misread
    for flag in ["-v0.2", "-V0"] {
        let o = Command::new(env!("CARGO_BIN_EXE_pdamp"))
            .args(["nrlazy", path.to_str().unwrap(), "-m1,7", flag])
            .output()
            .unwrap();
        assert!(!o.status.success(), "{flag} accepted");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(flag), "{flag}: {err}");
    }
}

/// TISEAN `d2`'s `.c2` file: (m, ε printed, C printed) rows.
fn parse_c2(text: &str) -> Vec<(usize, String, String)> {
    let mut m = 0;
    let mut rows = Vec::new();
    for line in text.lines() {
        if let Some(rest) = line.strip_prefix("#dim=") {
            m = rest.trim().parse().unwrap();
        } else if !line.starts_with('#') && !line.trim().is_empty() {
            let f: Vec<&str> = line.split_whitespace().collect();
            rows.push((m, f[0].to_string(), f[1].to_string()));
        }
    }
    rows
}

/// Compares two values both printed with `%e` (7 significant digits): equal true values print
/// at most one unit of the last digit apart (each rounded once); returns that difference.
fn check_both_printed(what: &str, ours: &str, printed: &str) -> f64 {
    let (o, g): (f64, f64) = (ours.parse().unwrap(), printed.parse().unwrap());
    let h = half_ulp(printed);
    let diff = (o - g).abs();
    assert!(
        diff <= 2.0 * h * (1.0 + 1e-9),
        "{what}: pdamp {ours}, TISEAN {printed} (differs by {:.2} of its last digit)",
        diff / (2.0 * h)
    );
    diff / (2.0 * h)
}

fn d2_file(series: &str, opts: &[&str], c2_file: &str) -> f64 {
    let path = golden(series);
    let mut args = vec!["d2", path.to_str().unwrap()];
    args.extend_from_slice(opts);
    // pdamp: m,eps,c,pairs,slope (ε ascending); TISEAN .c2: blocks per m, ε descending,
    // rows with C = 0 left out
    let ours = csv_rows(&pdamp(&args));
    let want = parse_c2(&std::fs::read_to_string(golden(c2_file)).unwrap());
    let nonzero: Vec<&Vec<String>> = ours
        .iter()
        .filter(|r| r[2].parse::<f64>().unwrap() > 0.0)
        .collect();
    assert_eq!(nonzero.len(), want.len(), "{c2_file}: number of rows");
    let (mut worst, mut same) = (0.0f64, 0);
    for (m, eps, c) in &want {
        let what = format!("{c2_file} m = {m} ε = {eps}");
        let e: f64 = eps.parse().unwrap();
        let row = nonzero
            .iter()
            .find(|r| {
                r[0].parse::<usize>().unwrap() == *m
                    && (r[1].parse::<f64>().unwrap() - e).abs() <= 2.0 * half_ulp(eps)
            })
            .unwrap_or_else(|| panic!("{what}: no such row in pdamp's output"));
        worst = worst.max(check_both_printed(&what, &row[1], eps));
        worst = worst.max(check_both_printed(&what, &row[2], c));
        same += usize::from(row[2].parse::<f64>().unwrap() == c.parse::<f64>().unwrap());
    }
    eprintln!(
        "{c2_file}: {} rows (ε and C), worst difference {worst:.3} of TISEAN's last digit, \
         {same} C print identically",
        want.len()
    );
    worst
}

#[test]
fn d2_lorenz_equals_tisean() {
    // TISEAN: d2 lorenz_x_n10000.dat -M1,6 -d10 -t100 -r0.05 -R8 -#50 -N0
    d2_file(
        "lorenz_x_n10000.dat",
        &["-M1,6", "-d10", "-t100", "-r0.05", "-R8", "-#50"],
        "lorenz_x_n10000.M6_d10_t100.c2",
    );
}

#[test]
fn d2_henon_and_sine_equal_tisean() {
    d2_file(
        "henon_x_n20000.txt",
        &["-M1,4", "-d1", "-t0", "-r0.001", "-R2", "-#30"],
        "henon_x_n20000.M4_d1_t0.c2",
    );
    d2_file(
        "noisy_sine_n8000.txt",
        &["-M1,5", "-d9", "-t20", "-r0.01", "-R2", "-#25"],
        "noisy_sine_n8000.M5_d9_t20.c2",
    );
}

#[test]
fn d2_rescaled_equals_tisean_e() {
    // TISEAN: d2 lorenz_x_n10000.dat -M1,6 -d10 -t100 -r0.002 -R0.3 -#40 -N0 -E (radii and
    // printed ε in units of the data interval)
    d2_file(
        "lorenz_x_n10000.dat",
        &[
            "-M1,6", "-d10", "-t100", "-r0.002", "-R0.3", "-#40", "-N0", "-E",
        ],
        "lorenz_x_n10000.E_M6_d10_t100.c2",
    );
}

fn lyap_r_file(series: &str, opts: &[&str], ros_file: &str) -> f64 {
    let path = golden(series);
    let mut args = vec!["lyap-r", path.to_str().unwrap()];
    args.extend_from_slice(opts);
    // pdamp: dn_samples,s,count; TISEAN .ros: Δn, S
    let ours = csv_rows(&pdamp(&args));
    let want = tisean_rows(&std::fs::read_to_string(golden(ros_file)).unwrap());
    assert_eq!(ours.len(), want.len(), "{ros_file}: number of rows");
    let mut score = Score::default();
    for (o, w) in ours.iter().zip(&want) {
        assert_eq!(o[0], w[0], "{ros_file}: Δn");
        score.add(
            &format!("{ros_file} Δn = {}", w[0]),
            o[1].parse().unwrap(),
            &w[1],
        );
    }
    score.report(ros_file);
    score.0
}

#[test]
fn lyap_r_equals_tisean() {
    lyap_r_file(
        "lorenz_x_n10000.dat",
        &["-m5", "-d10", "-t100", "-s150"],
        "lorenz_x_n10000.m5_d10_t100_s150.ros",
    );
    lyap_r_file(
        "henon_x_n20000.txt",
        &["-m2", "-d1", "-t0", "-s20"],
        "henon_x_n20000.m2_d1_t0_s20.ros",
    );
    lyap_r_file(
        "noisy_sine_n8000.txt",
        &["-m3", "-d9", "-t20", "-r0.01", "-s60"],
        "noisy_sine_n8000.m3_d9_t20_r0.01_s60.ros",
    );
}

/// Log band powers of the periodogram |Σ x_n e^{−2πikn/N}|², k = 1..N/2, in half-octave bands
/// (mean removed first).
fn band_log_power(x: &[f64]) -> Vec<f64> {
    let n = x.len();
    let mean = x.iter().sum::<f64>() / n as f64;
    let (cos, sin): (Vec<f64>, Vec<f64>) = (0..n)
        .map(|j| {
            let a = 2.0 * std::f64::consts::PI * j as f64 / n as f64;
            (a.cos(), a.sin())
        })
        .unzip();
    let p: Vec<f64> = (1..=n / 2)
        .map(|k| {
            let (mut re, mut im) = (0.0, 0.0);
            for (j, v) in x.iter().enumerate() {
                let t = (k * j) % n;
                re += (v - mean) * cos[t];
                im -= (v - mean) * sin[t];
            }
            re * re + im * im
        })
        .collect();
    let mut bands = Vec::new();
    let mut lo = 1.0f64;
    while (lo as usize) <= n / 2 {
        let hi = lo * std::f64::consts::SQRT_2;
        let (a, b) = (lo.ceil() as usize, (hi.ceil() as usize).min(n / 2 + 1));
        if b > a {
            bands.push(p[a - 1..b - 1].iter().sum::<f64>().ln());
        }
        lo = hi;
    }
    bands
}

/// TISEAN `surrogates` output on stdout: surrogates one after the other, blank lines between.
fn parse_surr(text: &str) -> Vec<Vec<f64>> {
    let mut out: Vec<Vec<f64>> = vec![Vec::new()];
    for line in text.lines() {
        if line.trim().is_empty() {
            if !out.last().unwrap().is_empty() {
                out.push(Vec::new());
            }
        } else {
            out.last_mut().unwrap().push(line.trim().parse().unwrap());
        }
    }
    out.retain(|s| !s.is_empty());
    out
}

/// pdamp `surrogates` output: one column per surrogate.
fn parse_columns(text: &str) -> Vec<Vec<f64>> {
    let rows: Vec<Vec<f64>> = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| l.split_whitespace().map(|v| v.parse().unwrap()).collect())
        .collect();
    (0..rows[0].len())
        .map(|c| rows.iter().map(|r| r[c]).collect())
        .collect()
}

fn sorted(x: &[f64]) -> Vec<f64> {
    let mut s = x.to_vec();
    s.sort_by(f64::total_cmp);
    s
}

/// Largest |ln P_b(pdamp mean) − ln P_b(TISEAN mean)| over bands, in units of TISEAN's own
/// scatter (standard deviation across its surrogates) — the statistic the test bounds.
fn spectrum_distance(ours: &[Vec<f64>], tisean: &[Vec<f64>]) -> f64 {
    let stats = |set: &[Vec<f64>]| -> Vec<(f64, f64)> {
        let b: Vec<Vec<f64>> = set.iter().map(|s| band_log_power(s)).collect();
        (0..b[0].len())
            .map(|k| {
                let v: Vec<f64> = b.iter().map(|r| r[k]).collect();
                let m = v.iter().sum::<f64>() / v.len() as f64;
                let var = v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (v.len() - 1) as f64;
                (m, var)
            })
            .collect()
    };
    let (o, t) = (stats(ours), stats(tisean));
    o.iter()
        .zip(&t)
        .map(|(&(mo, _), &(mt, vt))| (mo - mt).abs() / vt.sqrt())
        .fold(0.0, f64::max)
}

/// Surrogates are random: TISEAN's (Fortran `surrogates`, IAAFT to convergence, `-I1`) and
/// pdamp's (other generator) cannot be compared value by value. Compared instead: the
/// amplitude distribution (every surrogate a permutation of the data) and the periodogram in
/// half-octave bands, whose mean over 10 pdamp surrogates must lie within 3 standard
/// deviations of TISEAN's 10 (the standard deviation of a mean of 10 is 0.32 of one
/// surrogate's). Shuffled surrogates (white spectrum) must fail the same bound.
#[test]
fn surrogates_statistics_match_tisean() {
    let data: Vec<f64> = std::fs::read_to_string(golden("lorenz_x_n10000.dat"))
        .unwrap()
        .lines()
        .take(2048)
        .map(|l| l.trim().parse().unwrap())
        .collect();
    let tisean =
        parse_surr(&std::fs::read_to_string(golden("lorenz_x_n2048.I1_n10.surr")).unwrap());
    assert_eq!(tisean.len(), 10);
    // the judge itself: TISEAN's surrogates are the data reordered (single precision, 7
    // significant digits printed)
    let want = sorted(&data);
    for s in &tisean {
        assert_eq!(s.len(), 2048);
        for (a, b) in sorted(s).iter().zip(&want) {
            assert!(
                (a - b).abs() <= 5e-7 * b.abs().max(1e-3),
                "TISEAN {a} vs data {b}"
            );
        }
    }
    let path = golden("lorenz_x_n10000.dat");
    let run = |method: &str| {
        parse_columns(&pdamp(&[
            "surrogates",
            path.to_str().unwrap(),
            "-l",
            "2048",
            "-n",
            "10",
            "-I",
            "7",
            "--method",
            method,
        ]))
    };
    let ours = run("iaaft");
    assert_eq!(ours.len(), 10);
    for s in &ours {
        assert_eq!(s.len(), 2048);
        for (a, b) in sorted(s).iter().zip(&want) {
            assert!((a - b).abs() <= 1e-10 * b.abs(), "pdamp {a} vs data {b}");
        }
    }
    let d = spectrum_distance(&ours, &tisean);
    let d_shuffle = spectrum_distance(&run("shuffle"), &tisean);
    let d_data = spectrum_distance(&[data.clone(), data.clone()], &tisean);
    eprintln!(
        "surrogates: band periodogram of pdamp's IAAFT mean within {d:.2} of TISEAN's standard \
         deviations (shuffled: {d_shuffle:.1}, the data: {d_data:.2})"
    );
    assert!(d <= 3.0, "pdamp's IAAFT periodogram {d:.2} σ from TISEAN's");
    assert!(
        d_shuffle > 3.0,
        "shuffled surrogates pass the bound: the test cannot fail"
    );
}

#[test]
fn outputs_do_not_depend_on_thread_count() {
    let lorenz = golden("lorenz_x_n10000.dat");
    let lorenz = lorenz.to_str().unwrap();
    let runs: [&[&str]; 6] = [
        &[
            "fnn", lorenz, "--tisean", "-m1", "-M1,8", "-d17", "-f10", "-t100",
        ],
        &[
            "lyap-k", lorenz, "--tisean", "-m2", "-M6", "-d17", "-r0.05", "-R0.5", "-#4", "-s300",
            "-t100",
        ],
        &[
            "nrlazy",
            lorenz,
            "--tisean",
            "-m1,7",
            "--radius-sd",
            "0.2",
            "-i2",
        ],
        &[
            "d2", lorenz, "-M1,6", "-d10", "-t100", "-r0.05", "-R8", "-#50",
        ],
        &["lyap-r", lorenz, "-m5", "-d10", "-t100", "-s150"],
        &["surrogates", lorenz, "-l", "2048", "-n", "4", "-I", "7"],
    ];
    for args in runs {
        let out = |threads: &str| {
            let o = Command::new(env!("CARGO_BIN_EXE_pdamp"))
                .args(args)
                .env("RAYON_NUM_THREADS", threads)
                .output()
                .expect("run pdamp");
            assert!(o.status.success());
            o.stdout
        };
        assert!(out("1") == out("3"), "{args:?}: 1 and 3 threads differ");
    }
}
