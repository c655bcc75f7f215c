//! `pdamp tradeoff` (to be written by the issue that owns it).

/// Arguments of `pdamp tradeoff`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Run `pdamp tradeoff`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`tradeoff` is not available yet")
}
