//! `pdamp embed` (to be written by the issue that owns it).

/// Arguments of `pdamp embed`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Run `pdamp embed`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`embed` is not available yet")
}
