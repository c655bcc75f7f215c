//! `pdamp fit_frf` (to be written by the issue that owns it).

/// Arguments of `pdamp fit_frf`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Run `pdamp fit_frf`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`fit_frf` is not available yet")
}
