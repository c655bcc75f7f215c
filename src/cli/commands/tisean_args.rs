//! The TISEAN flags that several verbs share, declared once and flattened into each verb's
//! arguments (`#[command(flatten)]`): the delay `-d` (d2, lyap-k, lyap-r, fnn, cao, rqa), the
//! radius range `-r -R -#` (d2, lyap-k), the Theiler window `-t` (d2, lyap-k, lyap-r, fnn,
//! cao, rqa, surrogate-test, plot), the dimension range `-m -M` of TISEAN's `M` or
//! `components,M` (d2, fnn), the single embedding dimension `-m --dim` (lyap-r, rqa) and the
//! output file `-o` (mutual, fnn, lyap-k, lyap-r, d2, nrlazy, surrogates).
//!
//! A verb whose default for one of them differs in meaning (the largest radius of `d2` and
//! `lyap-k`) states it in its own help with `mut_arg`, so every verb's flags, defaults and help
//! read as before.
//!
//! The defaults and help of the groups' arguments are set in place ([`edit_arg`] in
//! `mut_args`): `mut_arg` would move the argument to the end of the command's list, which
//! orders the completion scripts and the man pages (the help keeps the declared order either
//! way). The older `mut_arg` calls on `-d` and `-r -R -#` stay, so those lists read as before.
//!
//! Left to their verbs, as they are other flags under the same letter: `-M` of lyap-k (a plain
//! number: TISEAN lyap_k has no `components,M`) and cao (no `-m`), `-m -M` of plot (`-M` reads
//! `min,max`), and `-m --dimension` of embed, nrlazy (`m` or `components,m`) and
//! surrogate-test.

/// TISEAN's output file `-o`: the verb's text goes to this file (written atomically: a
/// stopped run leaves no partial file) instead of stdout. The content is pdamp's (CSV with a
/// header, or one column), not TISEAN's file format, so the file must be named: TISEAN's bare
/// `-o` ("`'datafile'.ext`") is refused by clap's "a value is required".
#[derive(Debug, Clone, clap::Args)]
pub struct Output {
    /// Write to this file instead of stdout (TISEAN -o), atomically.
    #[arg(
        short = 'o',
        long = "output",
        value_name = "FILE",
        help_heading = "Output"
    )]
    pub path: Option<String>,
}

impl Output {
    /// Writes `text` to the `-o` file (atomically) or to stdout.
    ///
    /// # Errors
    /// The file cannot be written, or stdout is closed.
    pub fn write(&self, text: &[u8]) -> anyhow::Result<()> {
        use std::io::Write;
        match &self.path {
            Some(path) => pdamp::io::atomic_write(std::path::Path::new(path), text)
                .map_err(|e| anyhow::anyhow!("-o {path}: {e}")),
            None => {
                let mut out = std::io::stdout().lock();
                out.write_all(text)?;
                out.flush()?;
                Ok(())
            }
        }
    }
}

/// TISEAN's delay `-d` (default 1).
#[derive(Debug, Clone, Copy, clap::Args)]
pub struct Delay {
    /// Delay τ in samples (TISEAN -d).
    #[arg(
        short = 'd',
        long = "delay",
        default_value_t = 1,
        help_heading = "Estimator"
    )]
    pub tau: usize,
}

/// TISEAN's radius range `-r -R -#`. The verb gives the default of `-#` (`mut_arg("eps_count",
/// |a| a.default_value(…))`; not a const generic: clap keeps a derived default in one static
/// shared by every instance) and that of `-R` in its help.
#[derive(Debug, Clone, Copy, clap::Args)]
pub struct Radii {
    /// Smallest radius ε in data units (TISEAN -r). Default: (max − min)/1000.
    #[arg(short = 'r', long = "eps-min", help_heading = "Estimator")]
    pub eps_min: Option<f64>,
    /// Largest radius ε in data units (TISEAN -R).
    #[arg(short = 'R', long = "eps-max", help_heading = "Estimator")]
    pub eps_max: Option<f64>,
    /// Number of radii, log-spaced (TISEAN -#).
    #[arg(short = '#', long = "eps-count", help_heading = "Estimator")]
    eps_count: Option<usize>,
}

impl Radii {
    /// The number of radii (`-#`, or the verb's default).
    pub fn count(&self) -> usize {
        self.eps_count
            .expect("every verb that flattens `Radii` gives `-#` a default")
    }
}

/// For `Command::mut_args`: `f` applied to the argument `id` only, which stays in its place
/// among the command's arguments (`mut_arg` moves it to the end).
pub(crate) fn edit_arg(
    id: &'static str,
    mut f: impl FnMut(clap::Arg) -> clap::Arg,
) -> impl FnMut(clap::Arg) -> clap::Arg {
    move |a| if a.get_id() == id { f(a) } else { a }
}

/// TISEAN's Theiler window `-t`: pairs closer in time are not neighbours. A verb with a fixed
/// default gives it with `edit_arg("theiler", |a| a.default_value(…))` and reads
/// [`Theiler::window`]; one whose default depends on other flags (τ) reads [`Theiler::given`].
#[derive(Debug, Clone, Copy, clap::Args)]
pub struct Theiler {
    /// Theiler window in samples (TISEAN -t).
    #[arg(short = 't', long = "theiler", help_heading = "Estimator")]
    theiler: Option<usize>,
}

impl Theiler {
    /// The window given with `-t`, if any (no default declared).
    pub fn given(&self) -> Option<usize> {
        self.theiler
    }

    /// The window: `-t`, or the verb's default.
    pub fn window(&self) -> usize {
        self.theiler
            .expect("a verb that reads `Theiler::window` gives `-t` a default")
    }
}

/// TISEAN's dimension range `-m -M`, `-M` as `M` or TISEAN's `components,M` (one component).
/// The verb gives the defaults (`edit_arg("m_min" | "m_max", …)`) or reads them as absent.
#[derive(Debug, Clone, clap::Args)]
pub struct DimRange {
    /// Smallest embedding dimension (TISEAN -m).
    #[arg(short = 'm', long = "min-dim", help_heading = "Estimator")]
    m_min: Option<usize>,
    /// Largest embedding dimension: `M` or TISEAN's `components,M` (1 component).
    #[arg(short = 'M', long = "max-dim", help_heading = "Estimator")]
    m_max: Option<String>,
}

impl DimRange {
    /// The smallest dimension given with `-m` (or the verb's default), if any.
    pub fn min(&self) -> Option<usize> {
        self.m_min
    }

    /// The largest dimension given with `-M` (or the verb's default), if any; an error for
    /// more than one component or no number.
    pub fn max(&self) -> anyhow::Result<Option<usize>> {
        self.m_max.as_deref().map(parse_max_dim).transpose()
    }
}

/// `M` or TISEAN's `components,M`, one component only.
pub(crate) fn parse_max_dim(s: &str) -> anyhow::Result<usize> {
    let parts: Vec<&str> = s.split(',').collect();
    let (comp, m) = match parts.as_slice() {
        [m] => ("1", *m),
        [c, m] => (*c, *m),
        _ => anyhow::bail!("-M {s}: expected `M` or `components,M`"),
    };
    if comp.trim() != "1" {
        anyhow::bail!("-M {s}: only one component (univariate series) is supported");
    }
    anyhow::Context::with_context(m.trim().parse::<usize>(), || {
        format!("-M {s}: `{m}` is not a dimension")
    })
}

/// One embedding dimension `-m --dim` (TISEAN -m); the verb gives the default and help.
#[derive(Debug, Clone, Copy, clap::Args)]
pub struct Dim {
    /// Embedding dimension (TISEAN -m).
    #[arg(short = 'm', long = "dim", help_heading = "Estimator")]
    m: Option<usize>,
}

impl Dim {
    /// The dimension: `-m`, or the verb's default.
    pub fn get(&self) -> usize {
        self.m
            .expect("every verb that flattens `Dim` gives `-m` a default")
    }
}

#[cfg(test)]
mod tests {
    use clap::CommandFactory;

    use crate::cli::Cli;

    fn help_of(verb: &str, arg: &str) -> String {
        let cmd = Cli::command();
        let sub = cmd.find_subcommand(verb).expect("verb");
        let a = sub
            .get_arguments()
            .find(|a| a.get_id() == arg)
            .expect("argument");
        a.get_help().map(ToString::to_string).unwrap_or_default()
    }

    #[test]
    fn shared_flags_keep_each_verbs_help_and_defaults() {
        Cli::command().debug_assert();
        assert_eq!(
            help_of("d2", "eps_max"),
            "Largest ε in data units (TISEAN -R). Default: the data interval max − min"
        );
        assert_eq!(
            help_of("lyap-k", "eps_max"),
            "Largest radius ε in data units (TISEAN -R). Default: (max − min)/100"
        );
        assert_eq!(
            help_of("d2", "eps_min"),
            "Smallest ε in data units (TISEAN -r). Default: interval/1000"
        );
        for verb in ["d2", "lyap-k", "lyap-r"] {
            assert_eq!(help_of(verb, "tau"), "Delay τ in samples (TISEAN -d)");
        }
        assert_eq!(
            help_of("fnn", "tau"),
            "Delay τ in samples (TISEAN -d); use the first minimum of `pdamp mutual`"
        );
        assert_eq!(
            help_of("cao", "tau"),
            "Delay τ in samples; use the first minimum of `pdamp mutual`"
        );
        assert_eq!(help_of("rqa", "tau"), "Delay τ in samples");
        let default_count = |verb: &str| {
            let cmd = Cli::command();
            let sub = cmd.find_subcommand(verb).unwrap();
            let a = sub
                .get_arguments()
                .find(|a| a.get_id() == "eps_count")
                .unwrap();
            a.get_default_values()[0].to_string_lossy().into_owned()
        };
        assert_eq!(default_count("d2"), "100");
        assert_eq!(default_count("lyap-k"), "5");
    }
}
