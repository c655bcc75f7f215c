//! Writes `figures/resonance_restitution*.png` (+ the CSV of the plotted data next to each): resonance amplitude Z_res versus the effective restitution e for several gaps (the impact model's counterpart of Z_res versus γ_n).
//!
//! SPEC §7: "Z_res versus γ_n, γ_s for several N". Scene B (Sánchez 2012 §3.2). Runs the same pipeline as
//! `pdamp reproduce --quick --only zres_vs_restitution` (sweeps cached under `figures/data/`, so a rerun is
//! fast); pass `--smoke` for a seconds-long run, `--full` for the source's parameters.
//!
//! Run: `cargo run --release --example fig_resonance_restitution [-- --smoke]`

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
    opts.only = vec!["zres_vs_restitution".into()];
    let report = reproduce(&opts, &|msg| eprintln!("{msg}"))?;
    for f in &report.figures {
        println!("wrote figures/{}.png and figures/{}.csv", f.name, f.name);
    }
    Ok(())
}
