//! `pdamp check_scene` (to be written by the issue that owns it).

/// Arguments of `pdamp check_scene`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Run `pdamp check_scene`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`check_scene` is not available yet")
}
