//! `pdamp reproduce` (to be written by the issue that owns it).

/// Arguments of `pdamp reproduce`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Run `pdamp reproduce`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`reproduce` is not available yet")
}
