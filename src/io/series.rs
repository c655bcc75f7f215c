//! Reading one- or many-column series files as TISEAN users expect — and refusing what cannot
//! be read unambiguously.
//!
//! Accepted format: one sample per line; blank lines and lines starting with `#` are skipped;
//! an optional header row (the first non-comment line, if any field is not a number) names the
//! columns. Columns are selected by 1-based number as TISEAN's `-c`, or by header name. `-`
//! reads standard input.
//!
//! What the reader checks, so that nothing is misread silently:
//! - **One delimiter per file**: comma, semicolon, tab or whitespace, detected from the first
//!   non-comment line (header or first data row) or given ([`SeriesReadOptions::delimiter`]).
//! - **Every row has the field count of the first row**; a row with more or fewer fields is an
//!   error naming the line.
//! - **Decimal commas** (`-4,408e0`, `0,25`) are refused with the way to convert them, unless
//!   [`SeriesReadOptions::decimal_comma`] says the file uses them (then the delimiter is a
//!   semicolon, tab or whitespace).
//! - **A time column**: a first column named `t`, `time` or `time_s` (any case) that increases
//!   uniformly is taken as time ([`SeriesTable::time`], with its inferred step `dt`); with no
//!   column selected, the data column is then the next one. A time-named first column that
//!   is not uniformly increasing is an error unless columns are selected explicitly.

use std::io::{BufRead, BufReader};

use crate::error::DataError;

/// One column to read: 1-based index (TISEAN `-c 2`) or header name (`-c grain_z_m`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Column {
    /// 1-based column number.
    Index(usize),
    /// Name in the header row.
    Name(String),
}

impl std::str::FromStr for Column {
    type Err = String;
    /// A positive integer is an index, anything else a header name.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let s = s.trim();
        match s.parse::<usize>() {
            Ok(0) => Err("column numbers start at 1 (as TISEAN's -c)".into()),
            Ok(i) => Ok(Column::Index(i)),
            Err(_) if s.is_empty() => Err("empty column name".into()),
            Err(_) => Ok(Column::Name(s.to_string())),
        }
    }
}

impl std::fmt::Display for Column {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Column::Index(i) => write!(f, "{i}"),
            Column::Name(n) => write!(f, "`{n}`"),
        }
    }
}

/// The field delimiter of a series file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Delimiter {
    /// `,`
    Comma,
    /// `;`
    Semicolon,
    /// One tab.
    Tab,
    /// Runs of spaces and tabs.
    Whitespace,
}

impl Delimiter {
    /// The name used on the command line (`--delimiter`).
    pub fn name(self) -> &'static str {
        match self {
            Delimiter::Comma => "comma",
            Delimiter::Semicolon => "semicolon",
            Delimiter::Tab => "tab",
            Delimiter::Whitespace => "whitespace",
        }
    }
}

impl std::str::FromStr for Delimiter {
    type Err = String;
    /// `comma` / `,`, `semicolon` / `;`, `tab`, `whitespace` / `space`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "comma" | "," => Ok(Delimiter::Comma),
            "semicolon" | ";" => Ok(Delimiter::Semicolon),
            "tab" | "\\t" | "\t" => Ok(Delimiter::Tab),
            "whitespace" | "space" | " " => Ok(Delimiter::Whitespace),
            other => Err(format!(
                "unknown delimiter `{other}`: use comma, semicolon, tab or whitespace"
            )),
        }
    }
}

/// Options of [`read_table`], mirroring TISEAN's `-c`, `-x`, `-l`.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct SeriesReadOptions {
    /// Columns to read. Empty (the default): one column chosen automatically — the first, or
    /// the second when the first is a time column.
    pub columns: Vec<Column>,
    /// Number of lines to skip at the start of the file (TISEAN `-x`), counted before
    /// comments and the header are recognised. Default 0.
    pub skip_lines: usize,
    /// Keep at most this many data rows (TISEAN `-l`). Default: all.
    pub max_rows: Option<usize>,
    /// The field delimiter; `None` (default): detected from the first non-comment line.
    pub delimiter: Option<Delimiter>,
    /// The file writes decimals with a comma (`-4,408e0`); default `false`, and a file that
    /// looks like it is refused.
    pub decimal_comma: bool,
}

/// The time column of a file: its header name and the uniform step between its values.
#[derive(Debug, Clone, PartialEq)]
pub struct TimeAxis {
    /// Header name of the time column (column 1).
    pub name: String,
    /// Mean step between consecutive rows (in the column's unit; seconds for `time_s`).
    pub dt: f64,
}

/// What [`read_table`] read: the selected columns and how they were found.
#[derive(Debug, Clone, PartialEq)]
pub struct SeriesTable {
    /// One `Vec` per selected column, in the order selected.
    pub columns: Vec<Vec<f64>>,
    /// 1-based numbers of the selected columns.
    pub indices: Vec<usize>,
    /// Header names of the selected columns (`None` without a header row).
    pub names: Vec<Option<String>>,
    /// The delimiter used.
    pub delimiter: Delimiter,
    /// The time column, if column 1 is one (see the module documentation).
    pub time: Option<TimeAxis>,
    /// The column was chosen automatically (no column selected).
    pub automatic: bool,
}

impl SeriesTable {
    /// One line saying which column was read and why, e.g.
    /// ``column 2 `base_u_m` (column 1 `time_s` is time, dt = 0.0001)``.
    pub fn describe_choice(&self) -> String {
        let col = |k: usize| match &self.names[k] {
            Some(n) => format!("column {} `{n}`", self.indices[k]),
            None => format!("column {}", self.indices[k]),
        };
        let cols: Vec<String> = (0..self.indices.len()).map(col).collect();
        let time = self.time.as_ref().map_or(String::new(), |t| {
            format!(" (column 1 `{}` is time, dt = {})", t.name, t.dt)
        });
        format!("{}{time}", cols.join(", "))
    }
}

/// Reads the selected columns of a series file (`-` = standard input): one `Vec` per column.
///
/// # Errors
/// As [`read_table`].
pub fn read_columns(path: &str, opts: &SeriesReadOptions) -> Result<Vec<Vec<f64>>, DataError> {
    Ok(read_table(path, opts)?.columns)
}

/// Reads a series file (`-` = standard input) with the checks of the module documentation.
///
/// # Errors
/// [`DataError::Io`] if the file cannot be read; [`DataError::Incomplete`] if it lies in a
/// run directory that is still being written or was interrupted
/// ([`crate::io::run_dir::check_complete`]);
/// [`DataError::Malformed`] naming `file:line` for a non-numeric or non-finite value, a row
/// whose field count differs from the first row's, decimal commas, a missing column, an
/// unknown column name, a time column that is not uniform, or a file without data rows.
pub fn read_table(path: &str, opts: &SeriesReadOptions) -> Result<SeriesTable, DataError> {
    let io_err = |source| DataError::Io {
        path: path.to_string(),
        source,
    };
    if path == "-" {
        let stdin = std::io::stdin();
        parse_table(stdin.lock(), "<stdin>", opts)
    } else {
        crate::io::run_dir::check_complete(std::path::Path::new(path))?;
        let file = std::fs::File::open(path).map_err(io_err)?;
        parse_table(BufReader::new(file), path, opts)
    }
}

/// Reads one column (the first of `opts.columns`, or the automatic choice) of a series file.
///
/// # Errors
/// Those of [`read_table`].
pub fn read_series(path: &str, opts: &SeriesReadOptions) -> Result<Vec<f64>, DataError> {
    let mut one = opts.clone();
    one.columns.truncate(1);
    Ok(read_columns(path, &one)?.remove(0))
}

/// Parses series text from any buffered reader; `name` is used in error messages.
///
/// # Errors
/// Those of [`read_table`].
pub fn parse_columns(
    reader: impl BufRead,
    name: &str,
    opts: &SeriesReadOptions,
) -> Result<Vec<Vec<f64>>, DataError> {
    Ok(parse_table(reader, name, opts)?.columns)
}

/// Parses series text held in memory (e.g. in tests); `name` is used in error messages.
///
/// # Errors
/// Those of [`read_table`].
pub fn parse_str(
    text: &str,
    name: &str,
    opts: &SeriesReadOptions,
) -> Result<Vec<Vec<f64>>, DataError> {
    parse_columns(text.as_bytes(), name, opts)
}

/// [`parse_table`] of text held in memory.
///
/// # Errors
/// Those of [`read_table`].
pub fn parse_table_str(
    text: &str,
    name: &str,
    opts: &SeriesReadOptions,
) -> Result<SeriesTable, DataError> {
    parse_table(text.as_bytes(), name, opts)
}

/// How to convert a decimal-comma file, for error messages.
const DECIMAL_COMMA_FIX: &str = "this looks like decimal commas (e.g. `-4,408e0` for -4.408): \
    pass --decimal-comma (library: SeriesReadOptions::decimal_comma), or convert the file, \
    e.g. `sed 's/;/ /g; s/,/./g' in.csv > out.txt`; if the commas really separate integer \
    columns, pass --delimiter comma";

/// The layout fixed by the first non-comment line.
struct Layout {
    delimiter: Delimiter,
    fields: usize,
    header: Option<Vec<String>>,
    /// Line of the first row (for messages).
    line: usize,
}

/// Parses series text from any buffered reader into a [`SeriesTable`]; `name` is used in
/// error messages.
///
/// # Errors
/// Those of [`read_table`].
pub fn parse_table(
    mut reader: impl BufRead,
    name: &str,
    opts: &SeriesReadOptions,
) -> Result<SeriesTable, DataError> {
    let malformed = |line: usize, message: String| DataError::Malformed {
        path: name.to_string(),
        line,
        message,
    };
    if opts.decimal_comma && opts.delimiter == Some(Delimiter::Comma) {
        return Err(malformed(
            0,
            "--decimal-comma with --delimiter comma: a comma cannot be both; the delimiter of \
             a decimal-comma file is a semicolon, tab or whitespace"
                .into(),
        ));
    }
    let mut layout: Option<Layout> = None;
    // kept columns (selected, time candidates) by 0-based index; the rest are only counted
    let mut raw: Vec<Option<Vec<f64>>> = Vec::new();
    let mut rows = 0usize;
    let mut line = String::new();
    let mut lineno = 0usize;
    // byte ranges of the fields of the current line (no allocation per line)
    let mut fields: Vec<(usize, usize)> = Vec::new();
    loop {
        line.clear();
        let read = reader
            .read_line(&mut line)
            .map_err(|source| DataError::Io {
                path: name.to_string(),
                source,
            })?;
        if read == 0 {
            break;
        }
        lineno += 1;
        if lineno <= opts.skip_lines {
            continue;
        }
        let trimmed = line.trim();
        if trimmed.is_empty() || trimmed.starts_with('#') {
            continue;
        }
        if opts.max_rows.is_some_and(|m| rows >= m) {
            break;
        }
        let lay = match &layout {
            Some(l) => l,
            None => {
                let l = first_row(trimmed, lineno, opts).map_err(|m| malformed(lineno, m))?;
                raw = kept_columns(&l, opts).map_err(|m| malformed(lineno, m))?;
                let is_header = l.header.is_some();
                layout = Some(l);
                if is_header {
                    continue;
                }
                layout.as_ref().expect("set above")
            }
        };
        field_ranges(trimmed, lay.delimiter, &mut fields);
        if fields.len() != lay.fields {
            return Err(malformed(
                lineno,
                field_count_message(fields.len(), lay, opts, trimmed),
            ));
        }
        for (k, column) in raw.iter_mut().enumerate() {
            if let Some(column) = column {
                let field = &trimmed[fields[k].0..fields[k].1];
                column.push(parse_field(field, k, opts).map_err(|m| malformed(lineno, m))?);
            }
        }
        rows += 1;
    }
    let Some(layout) = layout else {
        return Err(malformed(0, "no data rows found".into()));
    };
    if rows == 0 {
        return Err(malformed(0, "no data rows found".into()));
    }
    select(raw, &layout, opts).map_err(|m| malformed(layout.line, m))
}

/// The columns to keep (`Some` = kept) once the first row is known: the selected ones, or
/// with none selected columns 1 and 2 (the automatic choice); column 1 when named like time.
fn kept_columns(lay: &Layout, opts: &SeriesReadOptions) -> Result<Vec<Option<Vec<f64>>>, String> {
    let header = lay.header.as_deref();
    let mut keep = vec![false; lay.fields];
    keep[0] = opts.columns.is_empty() || header.is_some_and(|h| is_time_name(&h[0]));
    if opts.columns.is_empty() && lay.fields > 1 {
        keep[1] = true;
    }
    for c in &opts.columns {
        keep[resolve_column(c, header, lay.fields)?] = true;
    }
    Ok(keep.into_iter().map(|k| k.then(Vec::new)).collect())
}

/// Recognises the first non-comment line: delimiter, field count, header.
fn first_row(line: &str, lineno: usize, opts: &SeriesReadOptions) -> Result<Layout, String> {
    let delimiter = opts
        .delimiter
        .unwrap_or_else(|| detect_delimiter(line, opts.decimal_comma));
    let mut fields = Vec::new();
    split_into(line, delimiter, &mut fields);
    if fields.iter().any(String::is_empty) {
        return Err(format!(
            "empty field in the first row (delimiter: {}); every field needs a value",
            delimiter.name()
        ));
    }
    let numeric = |f: &str| number(f, opts.decimal_comma).is_some();
    let is_header = fields.iter().any(|f| !numeric(f));
    if !is_header
        && delimiter == Delimiter::Comma
        && opts.delimiter.is_none()
        && looks_decimal_comma(&fields)
    {
        return Err(DECIMAL_COMMA_FIX.into());
    }
    Ok(Layout {
        delimiter,
        fields: fields.len(),
        header: is_header.then_some(fields),
        line: lineno,
    })
}

/// The delimiter of a first row: a semicolon if there is one, else a tab between
/// non-blank fields, else a comma unless every comma sits inside a whitespace-separated number
/// (`1,5 2,5`: decimal commas), else whitespace. With `decimal_comma` a comma never delimits.
fn detect_delimiter(line: &str, decimal_comma: bool) -> Delimiter {
    if line.contains(';') {
        return Delimiter::Semicolon;
    }
    let words: Vec<&str> = line.split_whitespace().collect();
    if line.contains(',') && !decimal_comma {
        let inside_numbers = words.len() > 1
            && words
                .iter()
                .all(|w| !w.starts_with(',') && !w.ends_with(',') && w.matches(',').count() <= 1);
        if !inside_numbers {
            return Delimiter::Comma;
        }
    }
    Delimiter::Whitespace
}

/// A comma-delimited numeric first row that is more likely one decimal-comma number per
/// field pair: no `.` anywhere, and a field with an exponent (`408e0`) or a leading zero
/// (`0123`) after the first.
fn looks_decimal_comma(fields: &[String]) -> bool {
    if fields.len() < 2 || fields.iter().any(|f| f.contains('.')) {
        return false;
    }
    fields[1..].iter().any(|f| {
        let digits = f.trim_start_matches(['+', '-']);
        f.contains(['e', 'E']) || (digits.len() > 1 && digits.starts_with('0'))
    })
}

/// Splits `line` into trimmed fields by `d` (into `out`, reused across lines).
fn split_into(line: &str, d: Delimiter, out: &mut Vec<String>) {
    out.clear();
    match d {
        Delimiter::Whitespace => out.extend(line.split_whitespace().map(str::to_string)),
        Delimiter::Comma => out.extend(line.split(',').map(|f| f.trim().to_string())),
        Delimiter::Semicolon => out.extend(line.split(';').map(|f| f.trim().to_string())),
        Delimiter::Tab => out.extend(line.split('\t').map(|f| f.trim().to_string())),
    }
}

/// The byte ranges in `line` of the fields [`split_into`] would give.
fn field_ranges(line: &str, d: Delimiter, out: &mut Vec<(usize, usize)>) {
    out.clear();
    let base = line.as_ptr() as usize;
    let range = |f: &str| {
        let at = f.as_ptr() as usize - base;
        (at, at + f.len())
    };
    match d {
        Delimiter::Whitespace => out.extend(line.split_whitespace().map(range)),
        Delimiter::Comma => out.extend(line.split(',').map(|f| range(f.trim()))),
        Delimiter::Semicolon => out.extend(line.split(';').map(|f| range(f.trim()))),
        Delimiter::Tab => out.extend(line.split('\t').map(|f| range(f.trim()))),
    }
}

/// A field as a number (`,` read as the decimal point with `decimal_comma`).
fn number(field: &str, decimal_comma: bool) -> Option<f64> {
    if decimal_comma && field.contains(',') {
        field.replacen(',', ".", 1).parse().ok()
    } else {
        field.parse().ok()
    }
}

/// A data field as a finite number, or the message saying why not.
fn parse_field(field: &str, k: usize, opts: &SeriesReadOptions) -> Result<f64, String> {
    let Some(v) = number(field, opts.decimal_comma) else {
        if !opts.decimal_comma && number(field, true).is_some() {
            return Err(format!("column {}: `{field}`: {DECIMAL_COMMA_FIX}", k + 1));
        }
        return Err(format!("column {}: `{field}` is not a number", k + 1));
    };
    if !v.is_finite() {
        return Err(format!(
            "column {}: non-finite value `{field}`; remove or interpolate it",
            k + 1
        ));
    }
    Ok(v)
}

/// Why a row's field count differs from the first row's.
fn field_count_message(got: usize, lay: &Layout, opts: &SeriesReadOptions, line: &str) -> String {
    let mut m = format!(
        "{got} fields, but the first row (line {}) has {} ({} delimited); every row needs \
         the same number of fields",
        lay.line,
        lay.fields,
        lay.delimiter.name()
    );
    // a digit, a comma, a digit: the row may hold decimal commas (a row without a comma, or
    // with a point, is just short or long)
    let comma_between_digits = line
        .as_bytes()
        .windows(3)
        .any(|w| w[0].is_ascii_digit() && w[1] == b',' && w[2].is_ascii_digit());
    if !opts.decimal_comma
        && lay.delimiter == Delimiter::Comma
        && !line.contains('.')
        && comma_between_digits
    {
        m.push_str("; ");
        m.push_str(DECIMAL_COMMA_FIX);
    }
    m
}

/// Whether a header name denotes time (`t`, `time`, `time_s`, any case).
fn is_time_name(name: &str) -> bool {
    matches!(name.to_ascii_lowercase().as_str(), "t" | "time" | "time_s")
}

/// The uniform step of a time column, or why it is not one.
fn uniform_step(t: &[f64]) -> Result<f64, String> {
    if t.len() < 2 {
        return Err("a single row gives no time step".into());
    }
    let dt = (t[t.len() - 1] - t[0]) / (t.len() - 1) as f64;
    if !(dt > 0.0 && dt.is_finite()) {
        return Err("it does not increase".into());
    }
    // 1 % of dt: far above rounding in printed times, far below any real sampling change
    match t
        .windows(2)
        .position(|w| ((w[1] - w[0]) - dt).abs() > 0.01 * dt)
    {
        None => Ok(dt),
        Some(i) => Err(format!(
            "its step {} between data rows {} and {} differs from the mean step {dt} by more \
             than 1 %",
            t[i + 1] - t[i],
            i + 1,
            i + 2
        )),
    }
}

/// The selected columns (see [`SeriesReadOptions::columns`]) out of all columns read.
fn select(
    raw: Vec<Option<Vec<f64>>>,
    lay: &Layout,
    opts: &SeriesReadOptions,
) -> Result<SeriesTable, String> {
    let header = lay.header.as_deref();
    let time_named = header.is_some_and(|h| is_time_name(&h[0]));
    let time = if time_named && lay.fields > 1 {
        match uniform_step(raw[0].as_deref().unwrap_or_default()) {
            Ok(dt) => Some(TimeAxis {
                name: header.expect("time_named")[0].clone(),
                dt,
            }),
            Err(why) if opts.columns.is_empty() => {
                return Err(format!(
                    "column 1 `{}` is named like time but is not a uniform time axis: {why}; \
                     select the data column with -c (e.g. -c 2)",
                    header.expect("time_named")[0]
                ))
            }
            Err(_) => None,
        }
    } else {
        None
    };
    let automatic = opts.columns.is_empty();
    let indices: Vec<usize> = if automatic {
        vec![if time.is_some() { 1 } else { 0 }]
    } else {
        opts.columns
            .iter()
            .map(|c| resolve_column(c, header, lay.fields))
            .collect::<Result<_, _>>()?
    };
    let names = indices
        .iter()
        .map(|&i| header.map(|h| h[i].clone()))
        .collect();
    let columns = indices
        .iter()
        .map(|&i| raw[i].clone().expect("selected columns are kept"))
        .collect();
    Ok(SeriesTable {
        columns,
        indices: indices.iter().map(|i| i + 1).collect(),
        names,
        delimiter: lay.delimiter,
        time,
        automatic,
    })
}

/// The 0-based index of a selected column.
fn resolve_column(c: &Column, header: Option<&[String]>, fields: usize) -> Result<usize, String> {
    match c {
        Column::Index(0) => Err("column numbers start at 1 (as TISEAN's -c)".into()),
        Column::Index(i) if *i > fields => Err(format!(
            "column {i} missing: the file has {fields} column{}",
            if fields == 1 { "" } else { "s" }
        )),
        Column::Index(i) => Ok(i - 1),
        Column::Name(n) => match header {
            Some(h) => h
                .iter()
                .position(|f| f == n)
                .ok_or_else(|| format!("no column named `{n}` in the header ({})", h.join(", "))),
            None => Err(format!(
                "column `{n}` selected by name but the file has no header row"
            )),
        },
    }
}

#[cfg(test)]
mod tests {
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
}
