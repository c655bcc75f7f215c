//! Writes `figures/poincare*.png` (+ the CSV of the plotted data next to each): stroboscopic Poincaré sections (z, ż) of the particle at a few forcing frequencies (the same runs also give the spectrum and reconstruction figures).
//!
//! SPEC §7: "per frequency: stroboscopic Poincaré section". Scene B (Sánchez 2012 §3.2). Runs the same pipeline as
//! `pdamp reproduce --quick --only poincare` (sweeps cached under `figures/data/`, so a rerun is
//! fast); pass `--smoke` for a seconds-long run, `--full` for the source's parameters.
//!
//! Run: `cargo run --release --example fig_poincare [-- --smoke]`

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
    opts.only = vec!["poincare".into()];
    let report = reproduce(&opts, &|msg| eprintln!("{msg}"))?;
    for f in &report.figures {
        println!("wrote figures/{}.png and figures/{}.csv", f.name, f.name);
    }
    Ok(())
}
