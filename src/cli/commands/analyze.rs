//! `pdamp analyze` (to be written by the issue that owns it).

/// Arguments of `pdamp analyze`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Run `pdamp analyze`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`analyze` is not available yet")
}
