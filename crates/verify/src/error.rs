//! Why a behaviour or a property cannot be checked: data with a place, never a panic.

use std::fmt;

/// A property that cannot be read or makes no sense against the behaviour.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PropertyError {
    /// The property's name (`--never` and friends are named after their option).
    pub property: String,
    /// 1-based, in characters, into the property's expression.
    pub column: usize,
    pub message: String,
}

impl fmt::Display for PropertyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "property `{}`, column {}: {}",
            self.property, self.column, self.message
        )
    }
}

impl std::error::Error for PropertyError {}

/// Why a behaviour cannot be verified at all.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum VerifyError {
    /// One or more properties are wrong; every one is reported.
    Properties(Vec<PropertyError>),
    /// The packed state has fixed-width fields (states of a machine, machines, time tests of
    /// a state); a behaviour beyond them is refused rather than silently mis-encoded.
    TooLarge(String),
    /// The behaviour declares types under subsumption (`[suppress]`), which the model does not
    /// have yet (holds, suppressed postings, takeovers): refused rather than answered wrongly.
    Suppression(Vec<String>),
    /// `--engine symbolic` was asked for a behaviour the symbolic engine does not take.
    SymbolicDeclined(String),
}

impl fmt::Display for VerifyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            VerifyError::Properties(errors) => {
                for (i, e) in errors.iter().enumerate() {
                    if i > 0 {
                        f.write_str("\n")?;
                    }
                    write!(f, "{e}")?;
                }
                Ok(())
            }
            VerifyError::TooLarge(what) => write!(f, "too large to verify: {what}"),
            VerifyError::SymbolicDeclined(why) => write!(
                f,
                "the symbolic engine does not take this behaviour: {why} (the explicit engine does: --engine explicit)"
            ),
            VerifyError::Suppression(types) => write!(
                f,
                "the behaviour declares [suppress] for {}: verify does not model subsumption yet (holds, suppressed postings, takeovers), so it would answer wrongly; test it with `proclaim test` on a recorded run instead",
                types
                    .iter()
                    .map(|t| format!("`{t}`"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        }
    }
}

impl std::error::Error for VerifyError {}
