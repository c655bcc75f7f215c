//! `pdamp mutual` (to be written by the issue that owns it).

/// Arguments of `pdamp mutual`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Run `pdamp mutual`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`mutual` is not available yet")
}
