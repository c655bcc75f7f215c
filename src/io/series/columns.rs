//! Choosing the columns of a table: the time column (a uniformly increasing first column
//! named `t`, `time` or `time_s`, with its step), the automatic data column and columns
//! selected by number or header name.

use super::fields::Layout;
use super::types::{Column, SeriesReadOptions, SeriesTable, TimeAxis};

/// Whether a header name denotes time (`t`, `time`, `time_s`, any case).
pub(super) fn is_time_name(name: &str) -> bool {
    matches!(name.to_ascii_lowercase().as_str(), "t" | "time" | "time_s")
}

/// The uniform step of a time column, or why it is not one.
pub(super) fn uniform_step(t: &[f64]) -> Result<f64, String> {
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
pub(super) fn select(
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
pub(super) fn resolve_column(
    c: &Column,
    header: Option<&[String]>,
    fields: usize,
) -> Result<usize, String> {
    match c {
        Column::Index(0) => Err("column numbers start at 1 (as TISEAN's -c)".into()),
        Column::Index(i) if *i > fields => Err(format!(
            "column {i} missing: the file has {fields} column{}",
            if fields == 1 { "" } else { "s" }
        )),
        Column::Index(i) => Ok(i - 1),
        Column::Name(n) if is_tisean_column_list(n) && header.is_none_or(|h| !h.contains(n)) => {
            Err(format!(
                "-c {n}: TISEAN's list of columns (several components of a multivariate \
                 series); this reads one column: give one number, e.g. -c {}",
                n.split(',').next().unwrap_or("1")
            ))
        }
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

/// `1,2` or `1,2,3`: TISEAN's `-c` list of several columns.
fn is_tisean_column_list(n: &str) -> bool {
    n.contains(',') && n.split(',').all(|p| p.trim().parse::<usize>().is_ok())
}
