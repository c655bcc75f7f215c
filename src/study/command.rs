//! The `pdamp` command lines printed in `OUT/README.md`, built from the specifications that
//! ran (the sweep's scene, `--set` and `--vary`; the single run's scene and overrides; the
//! figure's input files), never written by hand. `tests/study_commands.rs` parses every
//! printed command with the CLI's parser and runs them.

use std::fmt;
use std::path::Path;

/// One `pdamp` command line: its arguments after `pdamp`, and the file its standard output
/// goes to, if any (`pdamp spectrum … > spectrum.csv`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Command {
    /// The arguments after `pdamp`, unquoted.
    pub args: Vec<String>,
    /// Where standard output is redirected (`> FILE`), if anywhere.
    pub stdout: Option<String>,
}

impl Command {
    /// `pdamp ARGS…`.
    pub fn new<I, S>(args: I) -> Command
    where
        I: IntoIterator<Item = S>,
        S: Into<String>,
    {
        Command {
            args: args.into_iter().map(Into::into).collect(),
            stdout: None,
        }
    }

    /// Appends one argument.
    pub fn arg(mut self, a: impl Into<String>) -> Command {
        self.args.push(a.into());
        self
    }

    /// Appends `--name value`.
    pub fn opt(mut self, name: &str, value: impl fmt::Display) -> Command {
        self.args.push(format!("--{name}"));
        self.args.push(value.to_string());
        self
    }

    /// Appends a path argument.
    pub fn path(self, p: &Path) -> Command {
        self.arg(p.display().to_string())
    }

    /// Redirects standard output to `p`.
    pub fn to_file(mut self, p: &Path) -> Command {
        self.stdout = Some(p.display().to_string());
        self
    }

    /// `pdamp sweep SCENE --set K=V … --vary K=RANGE … [--no-analysis] --out OUT`.
    pub fn sweep(
        scene: &str,
        set: &[(&str, String)],
        vary: &[(&str, String)],
        analyze: bool,
        out: &Path,
    ) -> Command {
        let mut c = Command::new(["sweep", scene]);
        for (k, v) in set {
            c = c.opt("set", format!("{k}={v}"));
        }
        for (k, v) in vary {
            c = c.opt("vary", format!("{k}={v}"));
        }
        if !analyze {
            c = c.arg("--no-analysis");
        }
        c.opt("out", out.display())
    }

    /// `pdamp plot KIND INPUT… -o OUT`.
    pub fn plot<P: AsRef<Path>>(kind: &str, inputs: &[P], out: &Path) -> Command {
        let mut c = Command::new(["plot", kind]);
        for p in inputs {
            c = c.path(p.as_ref());
        }
        c.arg("-o").path(out)
    }

    /// `pdamp reproduce MODE --out OUT --only NAME`: the figure `name` again, as it was made.
    pub fn reproduce(mode_flag: &str, out: &Path, name: &str) -> Command {
        Command::new(["reproduce", mode_flag])
            .opt("out", out.display())
            .opt("only", name)
    }

    /// `pdamp simulate SCENE --set K=V … --out OUT`.
    pub fn simulate(scene: &str, set: &[(&str, String)], out: &Path) -> Command {
        let mut c = Command::new(["simulate", scene]);
        for (k, v) in set {
            c = c.opt("set", format!("{k}={v}"));
        }
        c.opt("out", out.display())
    }
}

/// An argument as a POSIX shell reads it back: bare when it has no special character, else
/// in single quotes.
fn quote(a: &str) -> String {
    let plain = !a.is_empty()
        && a.chars().all(|c| {
            c.is_ascii_alphanumeric() || "-_./=:,+@%".contains(c) || (!c.is_ascii() && c != ' ')
        });
    if plain {
        a.to_string()
    } else {
        format!("'{}'", a.replace('\'', r"'\''"))
    }
}

impl fmt::Display for Command {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "pdamp")?;
        for a in &self.args {
            write!(f, " {}", quote(a))?;
        }
        if let Some(out) = &self.stdout {
            write!(f, " > {}", quote(out))?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quotes_what_the_shell_would_split() {
        let c = Command::new(["plot", "frf"])
            .opt("label", "e = 0")
            .opt("x", "damper.gap")
            .to_file(Path::new("a b.csv"));
        assert_eq!(
            c.to_string(),
            "pdamp plot frf --label 'e = 0' --x damper.gap > 'a b.csv'"
        );
        assert_eq!(quote("it's"), r"'it'\''s'");
    }
}
