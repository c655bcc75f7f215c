//! `pdamp completions SHELL` and `pdamp man [-o DIR]`: shell completion scripts
//! (clap_complete) and man pages (clap_mangen) generated from the same argument structs
//! the parser uses, so they never fall behind the options.

use std::path::PathBuf;

use anyhow::Context;
use clap::CommandFactory;

/// Arguments of `pdamp completions`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:\n  \
    pdamp completions bash > ~/.local/share/bash-completion/completions/pdamp\n  \
    pdamp completions zsh > ~/.zfunc/_pdamp    # with fpath+=(~/.zfunc) in ~/.zshrc\n  \
    pdamp completions fish > ~/.config/fish/completions/pdamp.fish")]
pub struct CompletionArgs {
    /// The shell to complete in.
    #[arg(value_enum)]
    pub shell: clap_complete::Shell,
}

/// Arguments of `pdamp man`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:\n  \
    pdamp man -o ~/.local/share/man/man1 && man pdamp-simulate\n  \
    pdamp man -o man && man -l man/pdamp.1")]
pub struct ManArgs {
    /// Directory the pages are written into (created if missing).
    #[arg(short, long, default_value = "man")]
    pub out: PathBuf,
}

/// Prints the completion script on standard output.
pub fn completions(args: CompletionArgs) -> anyhow::Result<()> {
    use std::io::Write;
    let mut cmd = super::super::Cli::command();
    // into a buffer first: clap_complete panics on a failed write (`… | head`), an
    // io::Error from here is a quiet broken pipe
    let mut buf = Vec::new();
    clap_complete::generate(args.shell, &mut cmd, "pdamp", &mut buf);
    std::io::stdout().write_all(&buf)?;
    Ok(())
}

/// Writes `pdamp.1` and `pdamp-<subcommand>.1` for every subcommand (atomically each).
pub fn man(args: ManArgs) -> anyhow::Result<()> {
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create {}", args.out.display()))?;
    let cmd = super::super::Cli::command();
    let mut pages = vec![("pdamp".to_string(), cmd.clone())];
    for sub in cmd.get_subcommands() {
        let name = format!("pdamp-{}", sub.get_name());
        pages.push((name.clone(), sub.clone().name(name)));
    }
    for (name, page) in &pages {
        let mut buf = Vec::new();
        clap_mangen::Man::new(page.clone()).render(&mut buf)?;
        let path = args.out.join(format!("{name}.1"));
        pdamp::io::atomic_write(&path, &buf)
            .with_context(|| format!("cannot write {}", path.display()))?;
    }
    tracing::info!(
        "wrote {} man pages into {} (man -l {}/pdamp.1)",
        pages.len(),
        args.out.display(),
        args.out.display()
    );
    Ok(())
}
