//! The CSV tables texrtl's commands read: a header line naming the columns, then one row per
//! line, fields separated by commas, white space around a field ignored, blank lines skipped.
//! Every error names the file, the line and the problem, with the offending value shortened.

use crate::shorten;
use std::path::Path;
use std::str::FromStr;

/// A table read from a file.
#[derive(Clone, Debug)]
pub struct Table {
    /// The file, as messages name it.
    pub file: String,
    /// The column names of the header.
    pub columns: Vec<String>,
    pub rows: Vec<Row>,
}

/// One row: its line number (from 1) and its fields.
#[derive(Clone, Debug)]
pub struct Row {
    pub line: usize,
    pub fields: Vec<String>,
}

/// Reads `path`, whose header must be one of `headers` (each a comma-separated list of
/// column names); every row must have as many fields as its header has columns.
pub fn read(path: &Path, headers: &[&str]) -> Result<Table, String> {
    let text = crate::read_text_bounded(path, crate::MAX_INPUT_BYTES)?;
    parse(&path.display().to_string(), &text, headers)
}

/// Parses `text` as [`read`] does; `file` names it in messages.
pub fn parse(file: &str, text: &str, headers: &[&str]) -> Result<Table, String> {
    let mut lines = text.lines().enumerate();
    let head = lines.next().map_or("", |(_, l)| l.trim());
    let columns: Vec<String> = head.split(',').map(|c| c.trim().to_string()).collect();
    let known = headers.iter().any(|h| {
        let want: Vec<&str> = h.split(',').collect();
        want == columns.iter().map(String::as_str).collect::<Vec<_>>()
    });
    if !known {
        let want: Vec<String> = headers.iter().map(|h| format!("'{h}'")).collect();
        return Err(format!(
            "{file}:1: header '{}' is not {}",
            shorten(head),
            want.join(" or ")
        ));
    }
    let mut rows = Vec::new();
    for (i, l) in lines {
        if l.trim().is_empty() {
            continue;
        }
        let fields: Vec<String> = l.split(',').map(|f| f.trim().to_string()).collect();
        if fields.len() != columns.len() {
            return Err(format!(
                "{file}:{}: {} fields, the header has {}",
                i + 1,
                fields.len(),
                columns.len()
            ));
        }
        rows.push(Row {
            line: i + 1,
            fields,
        });
    }
    Ok(Table {
        file: file.to_string(),
        columns,
        rows,
    })
}

impl Table {
    /// A message about `row`: `file:line: msg`.
    pub fn error(&self, row: &Row, msg: impl std::fmt::Display) -> String {
        format!("{}:{}: {msg}", self.file, row.line)
    }

    /// Field `col` of `row` parsed as `T` (`what` says what it should be, e.g. "a word
    /// address").
    pub fn parse<T: FromStr>(&self, row: &Row, col: usize, what: &str) -> Result<T, String> {
        let s = &row.fields[col];
        s.parse().map_err(|_| {
            self.error(
                row,
                format!("{} '{}' is not {what}", self.columns[col], shorten(s)),
            )
        })
    }

    /// Field `col` of `row` as a finite number.
    pub fn finite(&self, row: &Row, col: usize) -> Result<f64, String> {
        let x: f64 = self.parse(row, col, "a number")?;
        if x.is_finite() {
            Ok(x)
        } else {
            Err(self.error(
                row,
                format!(
                    "{} '{}' is not a finite number",
                    self.columns[col],
                    shorten(&row.fields[col])
                ),
            ))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn headers_fields_and_messages() {
        let t = parse("r.csv", "u, v\n1,2\n\n 3 ,4.5\n", &["u,v", "u,v,newline"]).unwrap();
        assert_eq!(t.rows.len(), 2);
        assert_eq!(t.rows[1].line, 4);
        assert_eq!(t.finite(&t.rows[1], 1).unwrap(), 4.5);
        let e = parse("r.csv", "x\n", &["u,v", "u,v,newline"]).unwrap_err();
        assert_eq!(e, "r.csv:1: header 'x' is not 'u,v' or 'u,v,newline'");
        let e = parse("r.csv", "u,v\n1\n", &["u,v"]).unwrap_err();
        assert_eq!(e, "r.csv:2: 1 fields, the header has 2");
        let long = "9".repeat(100_000);
        let t = parse("r.csv", &format!("u,v\n{long}x,1\n"), &["u,v"]).unwrap();
        let e = t.finite(&t.rows[0], 0).unwrap_err();
        assert!(e.len() < 100, "the value is shortened: {e}");
        let t = parse("r.csv", "u,v\ninf,1\n", &["u,v"]).unwrap();
        assert!(t
            .finite(&t.rows[0], 0)
            .unwrap_err()
            .contains("not a finite number"));
    }
}
