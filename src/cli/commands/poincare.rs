//! `pdamp poincare` (to be written by the issue that owns it).

/// Arguments of `pdamp poincare`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Run `pdamp poincare`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`poincare` is not available yet")
}
