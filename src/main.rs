//! `pdamp` binary: the command line (clap, anyhow, indicatif) over the `pdamp` library.
//!
//! The CLI is part of the binary, not of the library (`src/cli/`, cargo feature `cli`).

mod cli;

fn main() -> std::process::ExitCode {
    match cli::run() {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(err) => {
            eprintln!("error: {err:#}");
            std::process::ExitCode::from(2)
        }
    }
}
