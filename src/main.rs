//! `pdamp` binary: the command line (clap, anyhow, indicatif) over the `pdamp` library.
//!
//! The CLI is part of the binary, not of the library (`src/cli/`, cargo feature `cli`).
//! The exit status tells failure kinds apart ([`cli::exit`]); a closed standard output
//! (`pdamp embed … | head -1`) ends the program quietly.

mod cli;

fn main() -> std::process::ExitCode {
    cli::exit::quiet_on_broken_pipe();
    match cli::run() {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(err) if cli::exit::is_broken_pipe(&err) => std::process::ExitCode::SUCCESS,
        Err(err) => {
            eprintln!("error: {}", cli::exit::message(&err));
            std::process::ExitCode::from(cli::exit::code(&err) as u8)
        }
    }
}
