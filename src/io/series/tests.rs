//! Tests of the series reader.

#![cfg(test)]

use super::fields::{detect_delimiter, field_ranges, split_into};
use super::*;

#[test]
fn field_ranges_are_the_fields() {
    let cases = [
        ("1.5  -2e3\t7", Delimiter::Whitespace),
        ("1.5, -2e3 ,,7", Delimiter::Comma),
        (" a ;b;  c", Delimiter::Semicolon),
        ("1\t 2 \t3", Delimiter::Tab),
    ];
    for (line, d) in cases {
        let (mut want, mut got) = (Vec::new(), Vec::new());
        split_into(line, d, &mut want);
        field_ranges(line, d, &mut got);
        let got: Vec<&str> = got.iter().map(|&(a, b)| &line[a..b]).collect();
        assert_eq!(got, want, "{line:?}");
    }
}

fn opts(cols: &[&str]) -> SeriesReadOptions {
    SeriesReadOptions {
        columns: cols.iter().map(|c| c.parse().unwrap()).collect(),
        ..SeriesReadOptions::default()
    }
}

fn err(text: &str, o: &SeriesReadOptions) -> String {
    parse_str(text, "f", o).unwrap_err().to_string()
}

#[test]
fn reads_whitespace_csv_comments_and_header() {
    let text = "# a comment\nx_s,grain_z_m\n0.0, 1.5\n\n0.1,2.5\n# end\n";
    let cols = parse_str(text, "f.csv", &opts(&["grain_z_m", "1"])).unwrap();
    assert_eq!(cols, vec![vec![1.5, 2.5], vec![0.0, 0.1]]);
    let ws = parse_str("1 2\n3\t4\n", "f.dat", &opts(&["2"])).unwrap();
    assert_eq!(ws, vec![vec![2.0, 4.0]]);
}

#[test]
fn skip_and_length_like_tisean() {
    let text = "9\n1\n2\n3\n4\n";
    let o = SeriesReadOptions {
        skip_lines: 1,
        max_rows: Some(2),
        ..SeriesReadOptions::default()
    };
    assert_eq!(parse_str(text, "f", &o).unwrap(), vec![vec![1.0, 2.0]]);
}

#[test]
fn errors_name_file_and_line() {
    let e = parse_str("1\n2\nnan\n", "data.txt", &opts(&["1"])).unwrap_err();
    assert!(e.to_string().starts_with("data.txt:3:"), "{e}");
    let e = parse_str("1 2\n3\n", "d", &opts(&["2"])).unwrap_err();
    assert!(e.to_string().starts_with("d:2:"), "{e}");
    let e = parse_str("1,2\n2,x\n", "d", &opts(&["2"])).unwrap_err();
    assert!(e.to_string().contains("`x` is not a number"), "{e}");
    assert!("0".parse::<Column>().is_err());
}

#[test]
fn index_zero_from_the_library_is_an_error_not_a_panic() {
    let e = err(
        "1\n2\n",
        &SeriesReadOptions {
            columns: vec![Column::Index(0)],
            ..SeriesReadOptions::default()
        },
    );
    assert!(e.contains("start at 1"), "{e}");
    let e = err("1 2\n3 4\n", &opts(&["3"]));
    assert!(
        e.contains("column 3 missing: the file has 2 columns"),
        "{e}"
    );
    // TISEAN's list of columns is named as such, not read as a header name
    let e = err("1 2\n3 4\n", &opts(&["1,2"]));
    assert!(
        e.contains("TISEAN's list of columns") && e.contains("-c 1"),
        "{e}"
    );
    // …unless the header really has a column of that name
    let t = parse_str("a b 1,2\n1 2 3\n", "d", &opts(&["1,2"])).unwrap();
    assert_eq!(t, vec![vec![3.0]]);
}

#[test]
fn every_row_has_the_first_rows_field_count() {
    // a header of two names and a row of three fields: refused, naming the line
    let e = err("a,b\n1,2\n1,2,3\n", &opts(&["1"]));
    assert!(
        e.starts_with("f:3: 3 fields, but the first row (line 1) has 2"),
        "{e}"
    );
    let e = err("1 2\n3 4 5\n", &opts(&["1"]));
    assert!(e.starts_with("f:2:"), "{e}");
    // a short row without any comma is short, not a decimal-comma row
    let e = err("a,b\n1,2\n3\n", &opts(&["1"]));
    assert!(
        e.contains("1 fields") && !e.contains("decimal commas"),
        "{e}"
    );
    // a row of three integer-looking fields in a comma file may be decimal commas
    let e = err("a,b\n1,2\n1,5,3\n", &opts(&["1"]));
    assert!(e.contains("decimal commas"), "{e}");
}

#[test]
fn one_delimiter_per_file() {
    // the semicolon file: a comma inside a field is not a second delimiter
    let e = err("1;2\n3;4,5\n", &opts(&["2"]));
    assert!(e.contains("decimal commas"), "{e}");
    // a comma file whose second row uses spaces: one field there, refused
    let e = err("1,2\n3 4\n", &opts(&["1"]));
    assert!(e.contains("1 fields, but the first row"), "{e}");
    let o = SeriesReadOptions {
        delimiter: Some(Delimiter::Tab),
        ..opts(&["2"])
    };
    assert_eq!(
        parse_str("1\t2 \n3\t 4\n", "f", &o).unwrap(),
        vec![vec![2.0, 4.0]]
    );
}

#[test]
fn decimal_commas_are_refused_with_the_fix_or_read_when_declared() {
    // the cases: one decimal-comma column (read as -4 before), and a semicolon
    // file with decimal commas (wrong column before)
    let lorenz = "-4,408476157576e0\n-3,1e0\n";
    let e = err(lorenz, &SeriesReadOptions::default());
    assert!(e.contains("--decimal-comma") && e.contains("sed"), "{e}");
    let semi = "t;x\n0;-4,408e0\n0,1;2,5e-1\n";
    let e = err(semi, &opts(&["x"]));
    assert!(e.contains("decimal commas"), "{e}");
    let dc = SeriesReadOptions {
        decimal_comma: true,
        ..SeriesReadOptions::default()
    };
    assert_eq!(
        parse_str(lorenz, "f", &dc).unwrap(),
        vec![vec![-4.408476157576, -3.1]]
    );
    let t = parse_table_str(semi, "f", &dc).unwrap();
    assert_eq!(t.columns, vec![vec![-4.408, 0.25]]);
    assert_eq!(t.time.map(|t| t.dt), Some(0.1));
    // whitespace-delimited decimal commas: two columns, not four
    assert_eq!(
        parse_str(
            "1,5 2,5\n3,5 4,5\n",
            "f",
            &SeriesReadOptions {
                columns: vec![Column::Index(2)],
                ..dc.clone()
            }
        )
        .unwrap(),
        vec![vec![2.5, 4.5]]
    );
    // a header of one name over decimal-comma rows
    let e = err("x\n0,25\n", &SeriesReadOptions::default());
    assert!(
        e.starts_with("f:2: column 1: `0,25`") && e.contains("decimal commas"),
        "{e}"
    );
    // a comma header over decimal-comma rows: the field count says so
    let e = err("t,x\n0,1,5\n", &SeriesReadOptions::default());
    assert!(
        e.contains("3 fields") && e.contains("decimal commas"),
        "{e}"
    );
    // integer CSV stays readable: no exponent, no leading zero
    assert_eq!(
        parse_str("1,2\n3,4\n", "f", &opts(&["2"])).unwrap(),
        vec![vec![2.0, 4.0]]
    );
    // an explicit comma delimiter overrides the suspicion
    let o = SeriesReadOptions {
        delimiter: Some(Delimiter::Comma),
        ..opts(&["2"])
    };
    assert_eq!(
        parse_str("0,012\n1,013\n", "f", &o).unwrap(),
        vec![vec![12.0, 13.0]]
    );
    let e = err("0,012\n1,013\n", &opts(&["2"]));
    assert!(e.contains("decimal commas"), "{e}");
}

#[test]
fn a_time_column_is_recognised_and_skipped_by_default() {
    let text = "time_s,base_u_m,grain_z_m\n0,1,5\n0.5,2,6\n1.0,3,7\n";
    let t = parse_table_str(text, "s.csv", &SeriesReadOptions::default()).unwrap();
    assert_eq!(t.columns, vec![vec![1.0, 2.0, 3.0]]);
    assert_eq!(t.indices, vec![2]);
    assert_eq!(
        t.time,
        Some(TimeAxis {
            name: "time_s".into(),
            dt: 0.5
        })
    );
    assert!(t.automatic);
    assert_eq!(
        t.describe_choice(),
        "column 2 `base_u_m` (column 1 `time_s` is time, dt = 0.5)"
    );
    // explicit selection of the time column itself is honoured
    let t = parse_table_str(text, "s.csv", &opts(&["1"])).unwrap();
    assert_eq!(t.columns, vec![vec![0.0, 0.5, 1.0]]);
    // non-uniform time: refused when the choice would rely on it
    let e = err("t x\n0 1\n1 2\n3 3\n", &SeriesReadOptions::default());
    assert!(
        e.contains("not a uniform time axis") && e.contains("-c 2"),
        "{e}"
    );
    assert_eq!(
        parse_str("t x\n0 1\n1 2\n3 3\n", "f", &opts(&["x"])).unwrap(),
        vec![vec![1.0, 2.0, 3.0]]
    );
    // a first column not named like time is data
    let t = parse_table_str("a,b\n0,1\n1,2\n", "f", &SeriesReadOptions::default()).unwrap();
    assert_eq!((t.columns, t.time), (vec![vec![0.0, 1.0]], None));
}

#[test]
fn delimiter_detection() {
    assert_eq!(detect_delimiter("a;b", false), Delimiter::Semicolon);
    assert_eq!(detect_delimiter("0.0, 1.5", false), Delimiter::Comma);
    assert_eq!(detect_delimiter("1,5 2,5", false), Delimiter::Whitespace);
    assert_eq!(detect_delimiter("-4,4e0", true), Delimiter::Whitespace);
    assert_eq!(detect_delimiter("1\t2", false), Delimiter::Whitespace);
    assert_eq!("tab".parse::<Delimiter>(), Ok(Delimiter::Tab));
    assert!("pipe".parse::<Delimiter>().is_err());
}

#[test]
fn text_in_memory_reads_as_the_stream_in_parallel_pieces() {
    // > 2 pieces after the first row: the parallel path; comments, blank lines, CRLF and a
    // header; the table equals the line-by-line reader's, and an error deep in the file
    // names the same line.
    let mut text = String::from("# comment\n\ntime_s,x\n");
    for i in 0..60_000 {
        let t = i as f64 * 0.01;
        if i % 997 == 0 {
            text.push_str("# note\r\n\n");
        }
        text.push_str(&format!("{t:.2},{:.12e}\r\n", (t * 1.3).sin()));
    }
    assert!(text.len() > 4 * 128 * 1024);
    let o = SeriesReadOptions::default();
    let streamed = super::parse_table(text.as_bytes(), "f", &o).unwrap();
    let parallel = super::parse_table_str(&text, "f", &o).unwrap();
    assert!(streamed == parallel, "the two readers differ");
    assert_eq!(parallel.columns[0].len(), 60_000);
    let bad = text.replacen("\n300.00,", "\n300.0x,", 1);
    let e1 = super::parse_table(bad.as_bytes(), "f", &o)
        .unwrap_err()
        .to_string();
    let e2 = super::parse_table_str(&bad, "f", &o)
        .unwrap_err()
        .to_string();
    assert_eq!(e1, e2);
    let line = bad.lines().position(|l| l.contains("300.0x,")).unwrap() + 1;
    assert!(line > 20_000 && e2.contains(&format!("f:{line}:")), "{e2}");
    // skip and length are honoured on the in-memory path too
    let o = SeriesReadOptions {
        skip_lines: 5,
        max_rows: Some(40_000),
        ..SeriesReadOptions::default()
    };
    let (a, b) = (
        super::parse_table(text.as_bytes(), "f", &o).unwrap(),
        super::parse_table_str(&text, "f", &o).unwrap(),
    );
    assert!(
        a == b && a.columns[0].len() == 40_000,
        "skip and length differ"
    );
}

#[test]
fn a_piece_boundary_inside_a_multibyte_character_is_no_panic() {
    // the byte where the first piece would be cut is the second byte of `é` (a comment after
    // the first row); the pieces are cut after the next line end instead
    let piece = super::parallel::PIECE_BYTES;
    let mut text = format!("1.0\n# {}é\n", "x".repeat(piece - 3));
    assert!(!text.is_char_boundary(4 + piece));
    for i in 0..40_000 {
        text.push_str(&format!("{}.5 # µ°\n", i % 97));
    }
    let o = SeriesReadOptions::default();
    let e = super::parse_table_str(&text, "f", &o)
        .unwrap_err()
        .to_string();
    let s = super::parse_table(text.as_bytes(), "f", &o)
        .unwrap_err()
        .to_string();
    assert_eq!(e, s);
    text = text.replace(" # µ°", "");
    let (a, b) = (
        super::parse_table_str(&text, "f", &o).unwrap(),
        super::parse_table(text.as_bytes(), "f", &o).unwrap(),
    );
    assert!(a == b && a.columns[0].len() == 40_001);
}
