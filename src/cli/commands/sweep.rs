//! `pdamp sweep` (to be written by the issue that owns it).

/// Arguments of `pdamp sweep`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Run `pdamp sweep`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`sweep` is not available yet")
}
