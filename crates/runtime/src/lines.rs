//! What the small line-based formats (mapping files, impersonator scripts, game scripts) share:
//! `#` comments, blank lines skipped, errors that name their line, and durations as they write
//! them.

use std::fmt;

/// A line of a line-based file that could not be read, and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LineError {
    pub line: usize,
    pub message: String,
}

impl fmt::Display for LineError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}: {}", self.line, self.message)
    }
}

impl std::error::Error for LineError {}

/// Every bad line of a file, an error in itself (one line each when shown), so `?` works on
/// `parse_script`, `parse_mapping` and `parse_game` in a function returning `Box<dyn Error>`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LineErrors(pub Vec<LineError>);

impl std::ops::Deref for LineErrors {
    type Target = [LineError];

    fn deref(&self) -> &[LineError] {
        &self.0
    }
}

impl IntoIterator for LineErrors {
    type Item = LineError;
    type IntoIter = std::vec::IntoIter<LineError>;

    fn into_iter(self) -> Self::IntoIter {
        self.0.into_iter()
    }
}

impl fmt::Display for LineErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, e) in self.0.iter().enumerate() {
            if i > 0 {
                f.write_str("\n")?;
            }
            write!(f, "{e}")?;
        }
        Ok(())
    }
}

impl std::error::Error for LineErrors {}

/// The non-blank lines with their comments removed, numbered from 1.
pub fn code_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    text.lines().enumerate().filter_map(|(i, raw)| {
        let code = raw.split('#').next().unwrap_or("").trim();
        (!code.is_empty()).then_some((i + 1, code))
    })
}

/// The longest duration a file or an option may write: about 31 years, beyond any run, and
/// far enough from `Duration`'s and the clocks' limits that adding it to a moment never
/// overflows.
pub const LONGEST_DURATION: std::time::Duration = std::time::Duration::from_secs(1_000_000_000);

/// Parses a duration written `250ms`, `2s`, `1.5s` or `3` (seconds), at most
/// [`LONGEST_DURATION`].
pub fn parse_duration(text: &str) -> Option<std::time::Duration> {
    let t = text.trim();
    let (number, scale) = if let Some(ms) = t.strip_suffix("ms") {
        (ms, 1e-3)
    } else if let Some(us) = t.strip_suffix("us") {
        (us, 1e-6)
    } else if let Some(s) = t.strip_suffix('s') {
        (s, 1.0)
    } else {
        (t, 1.0)
    };
    let value: f64 = number.trim().parse().ok()?;
    std::time::Duration::try_from_secs_f64(value * scale)
        .ok()
        .filter(|d| *d <= LONGEST_DURATION)
}
