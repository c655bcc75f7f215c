//! `pdamp scene --template impact|dem|primary [-o FILE]`: write a commented starting scene, every
//! key with its unit, to edit for one's own damper.

use anyhow::Context;
use std::path::PathBuf;

/// The scenes a user can start from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Template {
    /// The primary system alone (mass, spring, viscous damper under base excitation).
    Primary,
    /// The impact damper: one effective particle with a restitution coefficient (event-driven).
    Impact,
    /// A box of spheres (DEM), scene B with softened steel for a fast first run.
    Dem,
}

impl Template {
    /// The commented TOML of the template: the repository's own scene files, which the test
    /// suite loads and runs (`tests/dem_scene_files.rs`, `tests/scene_errors.rs`).
    pub fn text(self) -> &'static str {
        match self {
            Template::Primary => include_str!("../../../data/scenes/primary_only.toml"),
            Template::Impact => include_str!("../../../data/scenes/thesis_b_impact.toml"),
            Template::Dem => include_str!("../../../data/scenes/thesis_b_soft.toml"),
        }
    }
}

/// Arguments of `pdamp scene`.
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Examples:\n  pdamp scene --template impact -o my_damper.toml\n  \
    pdamp scene --template dem > beads.toml && pdamp check-scene beads.toml"
)]
pub struct Args {
    /// Which starting scene to write.
    #[arg(long, value_enum)]
    pub template: Template,
    /// Output file (default: standard output). An existing file is not overwritten.
    #[arg(short, long, value_name = "FILE.toml")]
    pub output: Option<PathBuf>,
}

/// Run `pdamp scene`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let text = args.template.text();
    match &args.output {
        None => {
            print!("{text}");
            Ok(())
        }
        Some(path) => {
            if path.exists() {
                anyhow::bail!(
                    "{}: exists; choose another name or remove it first (a scene is never overwritten)",
                    path.display()
                );
            }
            pdamp::io::atomic_write(path, text.as_bytes())
                .with_context(|| format!("writing {}", path.display()))?;
            tracing::info!(
                "wrote {} — check it with: pdamp check-scene {}",
                path.display(),
                path.display()
            );
            Ok(())
        }
    }
}
