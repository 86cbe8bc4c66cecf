//! The manifest's `[ranges]` table: the whole numbers a type takes from outside the machines
//! (`doseEntered = "0..100"`, both ends included). `verify` gives such a type every value of
//! its range instead of a few that stand for intervals, so arithmetic that feeds on itself
//! stays exact; a run says so where a posting from outside leaves the range. Every problem is
//! placed at its key or value in the manifest.

use crate::manifest::Manifest;
use proclaim_board::Value;
use proclaim_fsm::Machine;
use proclaim_syntax::{line_column, nearest, FileDiagnostic};
use toml::Spanned;

/// At most this many values in one range: `verify` chooses among every one of them wherever
/// the type is read.
pub const MAX_RANGE_VALUES: u64 = 4096;

/// A declared range of a type: the whole numbers from `low` to `high`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DeclaredRange {
    pub ty: String,
    pub low: i64,
    pub high: i64,
}

impl DeclaredRange {
    /// Whether `value` lies in the range (a truth counts as 0 or 1, as the runner's
    /// arithmetic takes it).
    pub fn contains(&self, value: &Value) -> bool {
        let whole = match value {
            Value::Int(i) => *i,
            Value::Bool(b) => i64::from(*b),
            _ => return false,
        };
        (self.low..=self.high).contains(&whole)
    }

    /// Every value of the range, lowest first.
    pub fn values(&self) -> impl Iterator<Item = Value> {
        (self.low..=self.high).map(Value::Int)
    }
}

impl std::fmt::Display for DeclaredRange {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}..{}", self.low, self.high)
    }
}

/// Reads `"LOW..HIGH"`: two whole numbers, the first not above the second.
pub fn parse_range(text: &str) -> Result<(i64, i64), String> {
    let bad = || {
        format!("\"{text}\" is not a range of whole numbers (write \"0..100\" or \"-1000..1000\")")
    };
    let (low, high) = text.split_once("..").ok_or_else(bad)?;
    let low: i64 = low.trim().parse().map_err(|_| bad())?;
    let high: i64 = high.trim().parse().map_err(|_| bad())?;
    if low > high {
        return Err(format!(
            "\"{text}\" is empty: its low end is above its high end"
        ));
    }
    if high.abs_diff(low) >= MAX_RANGE_VALUES {
        return Err(format!(
            "\"{text}\" holds more than {MAX_RANGE_VALUES} values, more than the checker can try one by one"
        ));
    }
    Ok((low, high))
}

/// The declared ranges; the problems go into `problems` (an error for a range that cannot be
/// read, a warning for a type no machine reads).
pub(crate) fn check(
    manifest: &Manifest,
    manifest_file: &str,
    manifest_text: &str,
    machines: &[&Machine],
    problems: &mut Vec<FileDiagnostic>,
) -> Vec<DeclaredRange> {
    let at = |spanned: &Spanned<String>| {
        let (line, column) =
            line_column(manifest_text, spanned.span().start.min(manifest_text.len()));
        (line, column)
    };
    let shared = proclaim_runner::Shared::for_machines(machines.iter().copied());
    let read: Vec<String> = machines
        .iter()
        .flat_map(|m| {
            let decl = proclaim_runner::declaration(m, &m.name, &shared);
            let externs: Vec<String> = proclaim_fsm::names::externs_of(m)
                .into_iter()
                .map(str::to_string)
                .collect();
            decl.reads.into_iter().chain(decl.waits_on).chain(externs)
        })
        .collect();
    let mut ranges = Vec::new();
    for (ty, text) in &manifest.ranges {
        let name = ty.get_ref();
        if !read.iter().any(|r| r == name) {
            let hint = nearest(read.iter().map(String::as_str), name)
                .map(|n| format!("; did you mean `{n}`?"))
                .unwrap_or_default();
            let (line, column) = at(ty);
            problems.push(
                FileDiagnostic::warning(
                    manifest_file,
                    line,
                    format!(
                        "`ranges` names `{name}`, which no machine of the behaviour reads or binds with `extern`{hint}"
                    ),
                )
                .at_column(column, manifest_text),
            );
        }
        match parse_range(text.get_ref()) {
            Ok((low, high)) => ranges.push(DeclaredRange {
                ty: name.clone(),
                low,
                high,
            }),
            Err(why) => {
                let (line, column) = at(text);
                problems.push(
                    FileDiagnostic::error(manifest_file, line, format!("range of `{name}`: {why}"))
                        .at_column(column, manifest_text),
                );
            }
        }
    }
    ranges
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(text: &str, expect: Result<(i64, i64), &str>) {
        match (parse_range(text), expect) {
            (Ok(got), Ok(want)) => assert_eq!(got, want, "{text}"),
            (Err(got), Err(want)) => assert!(got.contains(want), "{text}: {got}"),
            (got, want) => panic!("{text}: {got:?}, expected {want:?}"),
        }
    }

    #[test]
    fn a_range_is_two_whole_numbers_in_order_and_not_too_many() {
        check("0..100", Ok((0, 100)));
        check("-1000..1000", Ok((-1000, 1000)));
        check(" 5 .. 5 ", Ok((5, 5)));
        check("0..4095", Ok((0, 4095)));
        check("0..4096", Err("more than 4096 values"));
        check("10..1", Err("is empty"));
        check("0-100", Err("not a range of whole numbers"));
        check("0..1.5", Err("not a range of whole numbers"));
        check("..", Err("not a range of whole numbers"));
    }

    #[test]
    fn a_range_holds_whole_numbers_and_truths_within_it() {
        let r = DeclaredRange {
            ty: "dose".into(),
            low: 0,
            high: 10,
        };
        assert!(r.contains(&Value::Int(10)) && r.contains(&Value::Bool(true)));
        assert!(!r.contains(&Value::Int(11)) && !r.contains(&Value::Float(1.0)));
        assert_eq!(r.values().count(), 11);
        assert_eq!(r.to_string(), "0..10");
    }
}
