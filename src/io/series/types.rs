//! The types of the series reader: a column selected by number or name ([`Column`]), the
//! delimiter ([`Delimiter`]), the reading options ([`SeriesReadOptions`]) and the table read
//! ([`SeriesTable`], with its time axis: step `dt` in the time column's units).

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

/// Options of [`read_table`](super::read_table), mirroring TISEAN's `-c`, `-x`, `-l`.
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

/// What [`read_table`](super::read_table) read: the selected columns and how they were found.
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
