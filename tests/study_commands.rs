//! Every command printed in `OUT/README.md` (issue 11, step 3) is a command the `pdamp` binary
//! accepts: the smoke reproduction's README is read back, each command is parsed by the CLI's
//! own clap parser (`Cli::try_parse_from`, the CLI's module included from `src/cli/`, after its
//! TISEAN-flag check, as `pdamp` parses), and then every one of them is run
//! end to end in order (the smoke sizes make them cheap: the sweeps resume from the finished
//! points, which also checks that a printed sweep is the very sweep that ran).

mod scratch;

// The binary's command line (it is not part of the library), for its parser only.
#[allow(dead_code)]
#[path = "../src/cli/mod.rs"]
mod cli;

use std::path::Path;
use std::process::{Command, Stdio};

use pdamp::study::{reproduce, Mode, ReproduceOptions};

/// Words of a command line as a POSIX shell splits them (bare words and single quotes, as
/// `pdamp::study::command::Command` writes them), and the `> FILE` redirection.
fn shell_words(line: &str) -> (Vec<String>, Option<String>) {
    let mut words = Vec::new();
    let mut cur: Option<String> = None;
    let mut chars = line.chars();
    while let Some(c) = chars.next() {
        match c {
            ' ' => {
                if let Some(w) = cur.take() {
                    words.push(w);
                }
            }
            '\'' => {
                let w = cur.get_or_insert_with(String::new);
                for q in chars.by_ref() {
                    if q == '\'' {
                        break;
                    }
                    w.push(q);
                }
            }
            '"' | '\\' | '&' | '|' | ';' | '$' | '`' | '*' | '?' => {
                panic!("`{line}`: unquoted shell character {c:?}")
            }
            c => cur.get_or_insert_with(String::new).push(c),
        }
    }
    words.extend(cur);
    match words.iter().position(|w| w == ">") {
        Some(i) => {
            assert_eq!(
                i + 2,
                words.len(),
                "`{line}`: `>` must be followed by one file"
            );
            let file = words.pop();
            words.pop();
            (words, file)
        }
        None => (words, None),
    }
}

fn readme_commands(readme: &str) -> Vec<String> {
    readme
        .lines()
        .filter_map(|l| l.strip_prefix("  - `"))
        .filter_map(|l| l.strip_suffix('`'))
        .filter(|l| l.starts_with("pdamp "))
        .map(String::from)
        .collect()
}

/// Whether `pdamp ARGS` parses, as the binary parses it (its TISEAN-flag check, then clap),
/// with the parser's message when not.
fn parses(args: &[String]) -> (bool, String) {
    let mut argv = vec!["pdamp".to_string()];
    argv.extend(args.iter().cloned());
    let parsed = cli::commands::tisean_flags::check(&argv)
        .map_err(|e| e.to_string())
        .and_then(|()| {
            <cli::Cli as clap::Parser>::try_parse_from(&argv)
                .map(|_| ())
                .map_err(|e| e.to_string())
        });
    match parsed {
        Ok(()) => (true, String::new()),
        Err(e) => (false, e),
    }
}

fn pdamp(args: &[String], stdout: Option<&str>) -> (bool, String) {
    let mut c = Command::new(env!("CARGO_BIN_EXE_pdamp"));
    c.args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stderr(Stdio::piped());
    match stdout {
        Some(f) => c.stdout(std::fs::File::create(f).unwrap()),
        None => c.stdout(Stdio::null()),
    };
    let out = c.output().unwrap();
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn every_readme_command_parses_and_runs() {
    let dir = scratch::tempdir().unwrap();
    let opts = ReproduceOptions::new(Mode::Smoke, dir.path());
    let report = reproduce(&opts, &|_| {}).unwrap();
    let readme = std::fs::read_to_string(dir.path().join("README.md")).unwrap();
    let commands = readme_commands(&readme);
    let per_figure: usize = report.figures.iter().map(|f| f.commands.len()).sum();
    assert_eq!(
        commands.len(),
        per_figure,
        "README commands:\n{}",
        commands.join("\n")
    );
    assert!(commands.iter().any(|c| c.starts_with("pdamp sweep ")));
    assert!(commands.iter().any(|c| c.starts_with("pdamp simulate ")));
    assert!(commands.iter().any(|c| c.starts_with("pdamp plot ")));

    // every command parses
    let mut bad = Vec::new();
    for line in &commands {
        let (words, _) = shell_words(line);
        assert_eq!(words[0], "pdamp");
        let (ok, err) = parses(&words[1..]);
        if !ok {
            bad.push(format!("{line}\n  {err}"));
        }
    }
    assert!(
        bad.is_empty(),
        "commands the CLI rejects:\n{}",
        bad.join("\n")
    );

    // and runs (in the order printed: a run directory before the figures drawn from it)
    for line in &commands {
        let (words, stdout) = shell_words(line);
        if let Some(f) = &stdout {
            assert!(Path::new(f).is_absolute(), "`{line}`: relative output");
        }
        let (ok, err) = pdamp(&words[1..], stdout.as_deref());
        assert!(ok, "`{line}` failed:\n{err}");
    }
}

#[test]
fn shell_words_read_back_what_the_study_writes() {
    let c = pdamp::study::command::Command::new(["plot", "frf"])
        .opt("label", "e = 0.8")
        .opt("set", "damper.box=[1,2,3]")
        .to_file(Path::new("/tmp/a b.csv"));
    let (w, f) = shell_words(&c.to_string());
    assert_eq!(
        w,
        [
            "pdamp",
            "plot",
            "frf",
            "--label",
            "e = 0.8",
            "--set",
            "damper.box=[1,2,3]"
        ]
    );
    assert_eq!(f.as_deref(), Some("/tmp/a b.csv"));
}

/// The chapter-4 family's commands (DEM sweeps, the panel runs and their figures) parse too,
/// on a reduced study (one frequency, 12 periods; the DEM runs are not rerun here).
#[test]
fn chapter4_commands_parse() {
    use pdamp::study::settings::Chapter4Settings;
    let dir = scratch::tempdir().unwrap();
    let ctx = pdamp::study::pipeline::Ctx {
        out: dir.path().to_path_buf(),
        figure: pdamp::plot::FigureOptions {
            width: 640,
            height: 480,
            title: None,
        },
        progress: &|_| {},
        points: Default::default(),
    };
    let s = pdamp::study::Settings::for_mode(Mode::Quick);
    let d = s.dem.clone().unwrap();
    let c = Chapter4Settings {
        frequencies_hz: vec![14.5],
        periods: 12.0,
        duration_s: None,
        panel_freqs_hz: vec![14.5],
        doubling_freqs_hz: vec![],
        check_freqs_hz: vec![],
        ensemble_seeds: vec![],
        recipe_freqs_hz: vec![],
        dt_fraction: pdamp::study::settings::CH4_QUICK_DT_FRACTION,
        slower_dt_fraction: Some(pdamp::study::settings::CH4_SLOWER_DT_FRACTION),
    };
    let figures = pdamp::study::chapter4::all(&ctx, &s, &d, &c, &|_| true)
        .unwrap()
        .figures;
    assert!(figures.iter().any(|f| f.name == "ch4_panel_f14.5"));
    let mut n = 0;
    for f in &figures {
        assert!(!f.commands.is_empty(), "{}: no commands", f.name);
        for cmd in &f.commands {
            let line = cmd.to_string();
            let (words, _) = shell_words(&line);
            let (ok, err) = parses(&words[1..]);
            assert!(ok, "{}: `{line}` rejected:\n{err}", f.name);
            n += 1;
        }
    }
    assert!(n >= 8, "{n} commands");
}
