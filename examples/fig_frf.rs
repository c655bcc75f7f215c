//! Writes `figures/frf*.png` (+ the CSV of the plotted data next to each): the primary's frequency response Z(f) with the one-particle impact model (e = 0 and 0.8) and, when the DEM model is available, the granular bed, against the reference curves (2.1.21) for M and M + m_p.
//!
//! SPEC §7: "Frequency response Z(f) with the reference curves for M and M + m_p; the one-particle model's FRF against the granular one". Scene B (Sánchez 2012 §3.2). Runs the same pipeline as
//! `pdamp reproduce --quick --only frf` (sweeps cached under `figures/data/`, so a rerun is
//! fast); pass `--smoke` for a seconds-long run, `--full` for the source's parameters.
//!
//! Run: `cargo run --release --example fig_frf [-- --smoke]`

use pdamp::study::{reproduce, Mode, ReproduceOptions};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let mode = if args.iter().any(|a| a == "--smoke") {
        Mode::Smoke
    } else if args.iter().any(|a| a == "--full") {
        Mode::Full
    } else {
        Mode::Quick
    };
    let mut opts = ReproduceOptions::new(mode, "figures");
    opts.only = vec!["frf".into()];
    let report = reproduce(&opts, &|msg| eprintln!("{msg}"))?;
    for f in &report.figures {
        println!("wrote figures/{}.png and figures/{}.csv", f.name, f.name);
    }
    Ok(())
}
