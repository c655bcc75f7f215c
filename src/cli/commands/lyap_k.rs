//! `pdamp lyap_k` (to be written by the issue that owns it).

/// Arguments of `pdamp lyap_k`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Run `pdamp lyap_k`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`lyap_k` is not available yet")
}
