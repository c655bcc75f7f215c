//! `pdamp simulate` (to be written by the issue that owns it).

/// Arguments of `pdamp simulate`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Run `pdamp simulate`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`simulate` is not available yet")
}
