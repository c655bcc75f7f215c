//! `pdamp` binary: a thin wrapper over [`pdamp::cli::run`].

fn main() -> std::process::ExitCode {
    match pdamp::cli::run() {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(err) => {
            eprintln!("error: {err:#}");
            std::process::ExitCode::from(2)
        }
    }
}
