//! The TISEAN flags that several verbs share, declared once and flattened into each verb's
//! arguments (`#[command(flatten)]`): the delay `-d` (d2, lyap-k, lyap-r, fnn, cao, rqa) and
//! the radius range `-r -R -#` (d2, lyap-k).
//!
//! A verb whose default for one of them differs in meaning (the largest radius of `d2` and
//! `lyap-k`) states it in its own help with `mut_arg`, so every verb's flags, defaults and help
//! read as before.

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
