//! Writes `figures/reconstruction*.png` (+ the CSV of the plotted data next to each): 2-D delay reconstructions (z_n, z_{n+τ}) at a few forcing frequencies, τ from the first minimum of the mutual information (4.1.5).
//!
//! SPEC §7: "per frequency: 2-D projection of the delay reconstruction". Scene B (Sánchez 2012 §3.2). Runs the same pipeline as
//! `pdamp reproduce --quick --only reconstruction` (sweeps cached under `figures/data/`, so a rerun is
//! fast); pass `--smoke` for a seconds-long run, `--full` for the source's parameters.
//!
//! Run: `cargo run --release --example fig_reconstruction [-- --smoke]`

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
    opts.only = vec!["reconstruction".into()];
    let report = reproduce(&opts, &|msg| eprintln!("{msg}"))?;
    for f in &report.figures {
        println!("wrote figures/{}.png and figures/{}.csv", f.name, f.name);
    }
    Ok(())
}
