//! `pdamp plot` (to be written by the issue that owns it).

/// Arguments of `pdamp plot`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Run `pdamp plot`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`plot` is not available yet")
}
