//! `pdamp fnn` (to be written by the issue that owns it).

/// Arguments of `pdamp fnn`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Run `pdamp fnn`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`fnn` is not available yet")
}
