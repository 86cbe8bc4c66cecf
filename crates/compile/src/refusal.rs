//! Why a behaviour is not compiled (a [`Refusal`], at a file and line), and the languages whose
//! limits decide it.

/// Why a behaviour was not compiled: where, and what.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Refusal {
    pub file: String,
    pub line: usize,
    pub what: String,
}

impl std::fmt::Display for Refusal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}:{}: cannot be compiled: {}",
            self.file, self.line, self.what
        )
    }
}

impl std::error::Error for Refusal {}

/// The language a behaviour is compiled to: what each cannot have is refused in its own words.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Language {
    /// Freestanding C: no heap, no operating system, no processes, no network.
    C,
    /// A Cargo project: a native program, but without a whiteboard of its own.
    Rust,
}

pub(crate) fn refuse(file: &str, line: usize, what: String) -> Refusal {
    Refusal {
        file: file.to_string(),
        line,
        what,
    }
}
