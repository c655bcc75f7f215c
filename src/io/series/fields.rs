//! The fields of one line: the layout fixed by the first non-comment line (delimiter, field
//! count, header), delimiter detection, numbers (with or without decimal commas) and the
//! messages for a row that does not match.

use super::types::{Delimiter, SeriesReadOptions};

/// How to convert a decimal-comma file, for error messages.
pub(super) const DECIMAL_COMMA_FIX: &str =
    "this looks like decimal commas (e.g. `-4,408e0` for -4.408): \
    pass --decimal-comma (library: SeriesReadOptions::decimal_comma), or convert the file, \
    e.g. `sed 's/;/ /g; s/,/./g' in.csv > out.txt`; if the commas really separate integer \
    columns, pass --delimiter comma";

/// The layout fixed by the first non-comment line.
#[derive(Clone)]
pub(super) struct Layout {
    pub(super) delimiter: Delimiter,
    pub(super) fields: usize,
    pub(super) header: Option<Vec<String>>,
    /// Line of the first row (for messages).
    pub(super) line: usize,
}

/// Recognises the first non-comment line: delimiter, field count, header.
pub(super) fn first_row(
    line: &str,
    lineno: usize,
    opts: &SeriesReadOptions,
) -> Result<Layout, String> {
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
pub(super) fn detect_delimiter(line: &str, decimal_comma: bool) -> Delimiter {
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
pub(super) fn looks_decimal_comma(fields: &[String]) -> bool {
    if fields.len() < 2 || fields.iter().any(|f| f.contains('.')) {
        return false;
    }
    fields[1..].iter().any(|f| {
        let digits = f.trim_start_matches(['+', '-']);
        f.contains(['e', 'E']) || (digits.len() > 1 && digits.starts_with('0'))
    })
}

/// Splits `line` into trimmed fields by `d` (into `out`, reused across lines).
pub(super) fn split_into(line: &str, d: Delimiter, out: &mut Vec<String>) {
    out.clear();
    match d {
        Delimiter::Whitespace => out.extend(line.split_whitespace().map(str::to_string)),
        Delimiter::Comma => out.extend(line.split(',').map(|f| f.trim().to_string())),
        Delimiter::Semicolon => out.extend(line.split(';').map(|f| f.trim().to_string())),
        Delimiter::Tab => out.extend(line.split('\t').map(|f| f.trim().to_string())),
    }
}

/// The byte ranges in `line` of the fields [`split_into`] would give.
pub(super) fn field_ranges(line: &str, d: Delimiter, out: &mut Vec<(usize, usize)>) {
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
pub(super) fn number(field: &str, decimal_comma: bool) -> Option<f64> {
    if decimal_comma && field.contains(',') {
        field.replacen(',', ".", 1).parse().ok()
    } else {
        field.parse().ok()
    }
}

/// A data field as a finite number, or the message saying why not.
pub(super) fn parse_field(field: &str, k: usize, opts: &SeriesReadOptions) -> Result<f64, String> {
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
pub(super) fn field_count_message(
    got: usize,
    lay: &Layout,
    opts: &SeriesReadOptions,
    line: &str,
) -> String {
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
