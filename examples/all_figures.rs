//! Regenerates every figure of SPEC §7 into `figures/` (PNG + CSV each) and
//! `figures/README.md` (figure → command → reductions): the library call behind
//! `pdamp reproduce`. The individual `fig_*` examples run parts of it.
//!
//! Run: `cargo run --release --example all_figures [-- --smoke | --full]`
//! (`--quick` is the default: minutes on 2 cores; `--full`: the source's parameters, hours).

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
    let opts = ReproduceOptions::new(mode, "figures");
    let started = std::time::Instant::now();
    let report = reproduce(&opts, &|msg| {
        eprintln!("[{:7.1} s] {msg}", started.elapsed().as_secs_f64())
    })?;
    for f in &report.figures {
        println!("figures/{}.png", f.name);
    }
    for s in &report.skipped {
        println!("skipped: {s}");
    }
    println!(
        "{} figures in {:.1} s; see figures/README.md",
        report.figures.len(),
        report.elapsed_s
    );
    Ok(())
}
