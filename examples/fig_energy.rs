//! Writes `figures/energy*.png` (+ the CSV of the plotted data next to each): energy dissipated per forcing cycle by each mechanism versus frequency (impact model: impacts and viscous; DEM: collision, friction, viscous).
//!
//! SPEC §7: "collision vs friction energy per cycle versus f". Scene B (Sánchez 2012 §3.2). Runs the same pipeline as
//! `pdamp reproduce --quick --only energy_vs_frequency` (sweeps cached under `figures/data/`, so a rerun is
//! fast); pass `--smoke` for a seconds-long run, `--full` for the source's parameters.
//!
//! Run: `cargo run --release --example fig_energy [-- --smoke]`

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
    opts.only = vec!["energy_vs_frequency".into()];
    let report = reproduce(&opts, &|msg| eprintln!("{msg}"))?;
    for f in &report.figures {
        println!("wrote figures/{}.png and figures/{}.csv", f.name, f.name);
    }
    Ok(())
}
