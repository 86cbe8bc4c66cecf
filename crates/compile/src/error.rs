//! Why a theory could not be compiled.

use std::fmt;

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum CompileError {
    /// The reasoner could not decide an answer within its budget: a compiled function must not
    /// guess it.
    Undecided {
        output: String,
        /// The inputs of the row, `name=true|false|unknown`.
        row: Vec<String>,
        why: String,
    },
    /// More input variables than a table may be built over.
    TooManyInputs { variables: usize, limit: usize },
    /// The domain asked for cannot express something the theory declares.
    Unsupported { what: String },
}

impl fmt::Display for CompileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CompileError::Undecided { output, row, why } => write!(
                f,
                "output `{output}` is undecided within the search budget for the inputs {{{}}} ({why}); a compiled theory never guesses an answer: raise the budget or break the attack cycle",
                row.join(", ")
            ),
            CompileError::TooManyInputs { variables, limit } => write!(
                f,
                "the inputs need {variables} decision variables, more than the {limit} a compiled theory may tabulate"
            ),
            CompileError::Unsupported { what } => write!(f, "{what} cannot be compiled yet"),
        }
    }
}

impl std::error::Error for CompileError {}
