//! The `pdamp` command line: clap argument structs and one file per subcommand.
//!
//! The CLI turns arguments into validated library requests and calls the library; the
//! library never imports clap. Errors are reported through `anyhow`.

pub mod commands;
pub mod exit;
pub mod log;
pub mod progress;
pub mod runtime;

use clap::{Parser, Subcommand};

/// pdamp — particle vibration dampers: simulate, sweep, analyse and plot.
///
/// Simulation: `simulate`, `sweep`, `merge`, `slurm`, `check-scene`, `scene`, `tradeoff`.
/// Series analysis (TISEAN-like, reads plain text/CSV columns): `mutual`, `fnn`, `embed`,
/// `spectrum`, `poincare`, `lyap-k`, `lyap-r`, `d2`, `cao`, `rqa`, `analyze`, `surrogates`,
/// `surrogate-test`, `nrlazy`.
/// Studies and figures: `fit-frf`, `plot`, `reproduce`.
#[derive(Debug, Parser)]
#[command(name = "pdamp", version, about, long_about = None, propagate_version = true)]
pub struct Cli {
    /// Say more on standard error: -v adds the library's debug events, -vv trace events.
    #[arg(short, long, action = clap::ArgAction::Count, global = true)]
    pub verbose: u8,
    /// Say less on standard error: -q keeps warnings and errors only (no notes, no progress
    /// bars), -qq errors only.
    #[arg(short, long, action = clap::ArgAction::Count, global = true)]
    pub quiet: u8,
    /// The subcommand to run.
    #[command(subcommand)]
    pub command: Command,
}

/// All subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// [simulation] Run one scene and write series.csv and summary.json.
    Simulate(commands::simulate::Args),
    /// [simulation] Run a parameter sweep in parallel (resumable) and write sweep.csv, strobe.csv.
    Sweep(commands::sweep::Args),
    /// [simulation] Merge the shards of a sweep (`sweep --shard K/N`) into sweep.csv, strobe.csv.
    Merge(commands::merge::Args),
    /// [simulation] Write a Slurm job-array submission of a sweep (shards + dependent merge).
    Slurm(commands::slurm::Args),
    /// [simulation] Validate a scene file without running it.
    CheckScene(commands::check_scene::Args),
    /// [simulation] Write a commented starting scene (--template primary|impact|dem).
    Scene(commands::scene::Args),
    /// [simulation] Measure speed against accuracy for a scene's cheaper settings.
    Tradeoff(commands::tradeoff::Args),
    /// [analysis] Time-delayed mutual information I(τ) and its first minimum (TISEAN `mutual`).
    Mutual(commands::mutual::Args),
    /// [analysis] False nearest neighbours (Kennel et al. 1992; TISEAN `false_nearest`).
    Fnn(commands::fnn::Args),
    /// [analysis] Write delay vectors (m, τ).
    Embed(commands::embed::Args),
    /// [analysis] Power spectrum with window and detected spectral lines.
    Spectrum(commands::spectrum::Args),
    /// [analysis] Stroboscopic Poincaré section.
    Poincare(commands::poincare::Args),
    /// [analysis] Kantz's maximal Lyapunov exponent (TISEAN `lyap_k`).
    #[command(name = "lyap-k")]
    LyapK(commands::lyap_k::Args),
    /// [analysis] Surrogate series: IAAFT, phase-randomised or shuffled (TISEAN `surrogates`).
    Surrogates(commands::surrogates::Args),
    /// [analysis] Surrogate test of nonlinearity by rank (prediction error, time reversal).
    #[command(name = "surrogate-test")]
    SurrogateTest(commands::surrogate_test::Args),
    /// [analysis] Simple nonlinear noise reduction (Schreiber 1993; TISEAN `lazy`/`nrlazy`).
    Nrlazy(commands::nrlazy::Args),
    /// [analysis] Rosenstein's maximal Lyapunov exponent (TISEAN `lyap_r`).
    #[command(name = "lyap-r")]
    LyapR(commands::lyap_r::Args),
    /// [analysis] Correlation sum and dimension D2 (Grassberger–Procaccia; TISEAN `d2`).
    D2(commands::d2::Args),
    /// [analysis] Cao's minimum embedding dimension E1(m), E2(m) (Cao 1997).
    Cao(commands::cao::Args),
    /// [analysis] Recurrence quantification analysis: RR, DET, LAM, L, L_max, entropy.
    Rqa(commands::rqa::Args),
    /// [analysis] Whole analysis chain with automatic choices and a regime verdict.
    Analyze(commands::analyze::Args),
    /// [studies] Fit effective mass and damping to a frequency response (2.1.21).
    FitFrf(commands::fit_frf::Args),
    /// [figures] Draw one figure kind to PNG.
    Plot(commands::plot::Args),
    /// [figures] Regenerate the whole figure set for the source's scenes.
    Reproduce(commands::reproduce::Args),
    /// [shell] Print a completion script for bash, zsh, fish, elvish or PowerShell.
    Completions(commands::shell::CompletionArgs),
    /// [shell] Write man pages (pdamp.1 and one per subcommand) into a directory.
    Man(commands::shell::ManArgs),
}

/// Parse the command line and run the chosen subcommand.
pub fn run() -> anyhow::Result<()> {
    commands::tisean_flags::check(
        &std::env::args_os()
            .map(|a| a.to_string_lossy().into_owned())
            .collect::<Vec<_>>(),
    )?;
    let cli = Cli::parse();
    log::init(log::level(cli.verbose, cli.quiet));
    match cli.command {
        Command::Simulate(a) => commands::simulate::run(a),
        Command::Sweep(a) => commands::sweep::run(a),
        Command::Merge(a) => commands::merge::run(a),
        Command::Slurm(a) => commands::slurm::run(a),
        Command::CheckScene(a) => commands::check_scene::run(a),
        Command::Scene(a) => commands::scene::run(a),
        Command::Tradeoff(a) => commands::tradeoff::run(a),
        Command::Mutual(a) => commands::mutual::run(a),
        Command::Fnn(a) => commands::fnn::run(a),
        Command::Embed(a) => commands::embed::run(a),
        Command::Spectrum(a) => commands::spectrum::run(a),
        Command::Poincare(a) => commands::poincare::run(a),
        Command::LyapK(a) => commands::lyap_k::run(a),
        Command::Surrogates(a) => commands::surrogates::run(a),
        Command::SurrogateTest(a) => commands::surrogate_test::run(a),
        Command::Nrlazy(a) => commands::nrlazy::run(a),
        Command::LyapR(a) => commands::lyap_r::run(a),
        Command::D2(a) => commands::d2::run(a),
        Command::Cao(a) => commands::cao::run(a),
        Command::Rqa(a) => commands::rqa::run(a),
        Command::Analyze(a) => commands::analyze::run(a),
        Command::FitFrf(a) => commands::fit_frf::run(a),
        Command::Plot(a) => commands::plot::run(a),
        Command::Reproduce(a) => commands::reproduce::run(a),
        Command::Completions(a) => commands::shell::completions(a),
        Command::Man(a) => commands::shell::man(a),
    }
}
