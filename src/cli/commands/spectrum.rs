//! `pdamp spectrum` (to be written by the issue that owns it).

/// Arguments of `pdamp spectrum`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Run `pdamp spectrum`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`spectrum` is not available yet")
}
