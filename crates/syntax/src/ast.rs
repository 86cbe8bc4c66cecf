//! The syntax tree of a theory file: statements as written, names kept as spans into the source.

use crate::span::Span;

/// A literal as written in the source, `a` or `~a`, its atom a span (cdl checks it into a `Lit`). The atom's name is `atom.text(source)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SourceLiteral {
    pub negated: bool,
    pub atom: Span,
    /// The whole literal, `~` included.
    pub span: Span,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Arrow {
    /// `->`
    Strict,
    /// `=>`
    Defeasible,
    /// `~>`, a warning (defeater).
    Warning,
}

/// The five proof algorithms' names as written in `output{}` tags and on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Algorithm {
    Mu,
    Pi,
    Beta,
    Alpha,
    Delta,
}

impl Algorithm {
    pub const ALL: [Algorithm; 5] = [
        Algorithm::Mu,
        Algorithm::Pi,
        Algorithm::Beta,
        Algorithm::Alpha,
        Algorithm::Delta,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Algorithm::Mu => "mu",
            Algorithm::Pi => "pi",
            Algorithm::Beta => "beta",
            Algorithm::Alpha => "alpha",
            Algorithm::Delta => "delta",
        }
    }

    pub fn from_name(name: &str) -> Option<Algorithm> {
        Algorithm::ALL.into_iter().find(|a| a.name() == name)
    }
}

impl std::fmt::Display for Algorithm {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RuleItem {
    pub label: Option<Span>,
    pub body: Vec<SourceLiteral>,
    pub arrow: Arrow,
    pub head: SourceLiteral,
    pub span: Span,
}

/// One member of `output{…}`: a literal with its algorithm, or the description string.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum OutputPart {
    Lit {
        algorithm: Option<(Algorithm, Span)>,
        lit: SourceLiteral,
    },
    Description(String),
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Item {
    /// `a.`, `~a.` or `\/{a, ~b}.`: an axiom clause.
    Fact {
        clause: Vec<SourceLiteral>,
        span: Span,
    },
    Rule(RuleItem),
    /// `R1 > R2.` (or a chain `R1 > R2 > R3.`, meaning each beats the next).
    Priority {
        labels: Vec<Span>,
        span: Span,
    },
    /// `name{N}.`
    Name {
        name: Span,
        span: Span,
    },
    /// `input{a}.` one binary input; `input{a, b, c}.` mutually exclusive, exactly one true.
    Input {
        atoms: Vec<SourceLiteral>,
        span: Span,
    },
    /// `ignore{a, ~b}.` (all of them) or `ignore K of {…}.` (at least K of them): input
    /// combinations the truth table leaves out.
    Ignore {
        at_least: Option<u32>,
        lits: Vec<SourceLiteral>,
        span: Span,
    },
    /// `assert{a, ~b}.`: the truth table keeps only input combinations where one of these holds.
    Assert {
        lits: Vec<SourceLiteral>,
        span: Span,
    },
    /// `output{beta offside, "description"}.`
    Output {
        parts: Vec<OutputPart>,
        span: Span,
    },
}

impl Item {
    pub fn span(&self) -> Span {
        match self {
            Item::Rule(rule) => rule.span,
            Item::Fact { span, .. }
            | Item::Priority { span, .. }
            | Item::Name { span, .. }
            | Item::Input { span, .. }
            | Item::Ignore { span, .. }
            | Item::Assert { span, .. }
            | Item::Output { span, .. } => *span,
        }
    }
}

/// A query: a literal, a clause `\/{…}` or a conjunction `/\{…}` of clauses.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Query {
    Lit(SourceLiteral),
    Clause(Vec<SourceLiteral>),
    Conjunction(Vec<Vec<SourceLiteral>>),
}
