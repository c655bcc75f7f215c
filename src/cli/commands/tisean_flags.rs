//! TISEAN flags that clap would misread in the TISEAN-like verbs: refused before parsing, with
//! the pdamp equivalent named.
//!
//! TISEAN's `-V<n>` (verbosity) would print pdamp's version and exit; TISEAN `nrlazy`'s
//! `-v<f>` (radius in units of the standard deviation) would count as `--verbose`; TISEAN
//! `surrogates`' `-m<k>` (number of columns) is named for what it is rather than left to
//! clap's "unexpected argument".

/// The verbs whose options follow TISEAN's programs.
const TISEAN_VERBS: [&str; 7] = [
    "mutual",
    "fnn",
    "lyap-k",
    "lyap-r",
    "d2",
    "nrlazy",
    "surrogates",
];

fn is_number(s: &str) -> bool {
    !s.is_empty() && s.parse::<f64>().is_ok()
}

/// Refuses TISEAN flags that clap would silently read as something else. `args` as from
/// `std::env::args()`, the program name first.
pub fn check(args: &[String]) -> anyhow::Result<()> {
    let mut it = args.iter().skip(1).skip_while(|a| a.starts_with('-'));
    let Some(verb) = it.next() else {
        return Ok(());
    };
    if !TISEAN_VERBS.contains(&verb.as_str()) {
        return Ok(());
    }
    let rest: Vec<&String> = it.take_while(|a| *a != "--").collect();
    for (i, a) in rest.iter().enumerate() {
        let next_is_number = rest.get(i + 1).is_some_and(|n| is_number(n));
        let value = |flag: &str| -> Option<String> {
            let tail = a.strip_prefix(flag)?;
            if is_number(tail) {
                Some(tail.to_string())
            } else if tail.is_empty() && next_is_number {
                Some(rest[i + 1].to_string())
            } else {
                None
            }
        };
        if let Some(v) = value("-V") {
            anyhow::bail!(
                "-V{v}: TISEAN's verbosity level is not a pdamp option (-V prints pdamp's \
                 version); pdamp writes only results to stdout, notes to stderr (-q quietens them)"
            );
        }
        if verb == "surrogates" {
            if let Some(v) = value("-m") {
                anyhow::bail!(
                    "-m{v}: TISEAN surrogates' number of columns (multivariate surrogates that \
                     keep the cross-spectrum) is not an option of pdamp surrogates, which makes \
                     surrogates of one column (-c): drop -m{v} and give the column with -c"
                );
            }
        }
        if let Some(v) = value("-v") {
            if verb == "nrlazy" {
                anyhow::bail!(
                    "-v{v}: TISEAN nrlazy's radius in units of the standard deviation is \
                     --radius-sd {v} in pdamp (-v is --verbose)"
                );
            }
            anyhow::bail!(
                "-v{v}: not an option of pdamp {verb} (-v is --verbose and takes no value)"
            );
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::check;

    fn args(s: &str) -> Vec<String> {
        s.split_whitespace().map(str::to_string).collect()
    }

    #[test]
    fn refuses_tisean_v_and_capital_v() {
        let e = check(&args("pdamp nrlazy f.dat -m1,7 -v0.2")).unwrap_err();
        assert!(e.to_string().contains("--radius-sd 0.2"), "{e}");
        let e = check(&args("pdamp nrlazy f.dat -v 0.2")).unwrap_err();
        assert!(e.to_string().contains("--radius-sd 0.2"), "{e}");
        assert!(check(&args("pdamp d2 f.dat -V0")).is_err());
        assert!(check(&args("pdamp -v lyap-r f.dat -V 1")).is_err());
        // pdamp's own -v, -vv and -V stay
        assert!(check(&args("pdamp -vv nrlazy f.dat -v -r 0.5")).is_ok());
        assert!(check(&args("pdamp nrlazy -V")).is_ok());
        assert!(check(&args("pdamp simulate -V0")).is_ok());
        assert!(check(&args("pdamp nrlazy -- -v0.2")).is_ok());
        let e = check(&args("pdamp surrogates f.dat -n1 -m2")).unwrap_err();
        assert!(e.to_string().contains("one column (-c)"), "{e}");
        assert!(check(&args("pdamp nrlazy f.dat -m 7")).is_ok());
    }
}
