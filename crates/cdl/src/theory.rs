//! The checked theory: interned atoms, rules in flat arrays, priorities, axioms and their
//! resolution closure, and the declared inputs and outputs. Immutable once built by `check`.

use crate::atoms::AtomTable;
use crate::literal::{Atom, Lit, RuleId};
use proclaim_syntax::{Algorithm, Span};
use std::fmt;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RuleKind {
    /// `->`
    Strict,
    /// `=>`
    Defeasible,
    /// `~>`: never supports, only attacks.
    Warning,
}

impl RuleKind {
    /// Whether a rule of this kind can support its consequent (strict and defeasible rules can).
    pub fn supports(self) -> bool {
        self != RuleKind::Warning
    }

    pub fn arrow(self) -> &'static str {
        match self {
            RuleKind::Strict => "->",
            RuleKind::Defeasible => "=>",
            RuleKind::Warning => "~>",
        }
    }
}

/// Where a rule comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Origin {
    /// Written in the theory file at this place.
    Written(Span),
    /// Generated from clause number `n` of the resolution closure of the axioms (cdl.md §2).
    Clause(u32),
}

/// One declared input: a single binary atom, or a group of mutually exclusive atoms of which
/// exactly one is true.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct InputGroup {
    pub atoms: Vec<Atom>,
    pub span: Span,
}

/// One declared output: a literal answered with an algorithm.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Output {
    pub lit: Lit,
    pub algorithm: Algorithm,
    pub description: Option<String>,
    pub span: Span,
}

/// A constraint on the input combinations a truth table enumerates.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum RowFilter {
    /// `ignore{…}` / `ignore K of {…}`: leave out rows where at least `at_least` of `lits` hold.
    Ignore { at_least: usize, lits: Vec<Lit> },
    /// `assert{…}`: keep only rows where at least one of `lits` holds.
    Assert { lits: Vec<Lit> },
}

/// A clause of the axioms, with where it was written (closure members derived by resolution have
/// none).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Clause {
    pub lits: Vec<Lit>,
    pub span: Option<Span>,
}

impl AsRef<[Lit]> for Clause {
    fn as_ref(&self) -> &[Lit] {
        &self.lits
    }
}

/// A rule as the engine and the reference prover read it.
#[derive(Clone, Copy, Debug)]
pub struct RuleRef<'t> {
    pub id: RuleId,
    pub label: Option<&'t str>,
    pub kind: RuleKind,
    pub body: &'t [Lit],
    pub head: Lit,
    pub origin: Origin,
}

/// A theory that passed checking. Rules written in the file come first (in file order), then the
/// strict rules generated from the clause closure.
#[derive(Clone, Debug, Default)]
pub struct Theory {
    pub(crate) name: Option<String>,
    pub(crate) atoms: AtomTable,
    pub(crate) heads: Vec<Lit>,
    pub(crate) kinds: Vec<RuleKind>,
    pub(crate) body_start: Vec<u32>,
    pub(crate) bodies: Vec<Lit>,
    /// Each rule's label as a range of `label_text`; empty for none (labels are never empty).
    pub(crate) labels: Vec<(u32, u32)>,
    pub(crate) label_text: String,
    pub(crate) origins: Vec<Origin>,
    pub(crate) written_rules: usize,
    pub(crate) priorities: Vec<(RuleId, RuleId)>,
    pub(crate) axioms: Vec<Clause>,
    /// Empty when `closure_is_axioms`: a theory's facts alone are stored once.
    pub(crate) closure: Vec<Clause>,
    pub(crate) closure_is_axioms: bool,
    pub(crate) inputs: Vec<InputGroup>,
    pub(crate) outputs: Vec<Output>,
    pub(crate) filters: Vec<RowFilter>,
}

impl Theory {
    /// The theory's `name{…}`, if it declared one.
    pub fn name(&self) -> Option<&str> {
        self.name.as_deref()
    }

    pub fn atom_count(&self) -> usize {
        self.atoms.len()
    }

    pub fn atom(&self, name: &str) -> Option<Atom> {
        self.atoms.get(name)
    }

    pub fn atom_name(&self, atom: Atom) -> &str {
        self.atoms.name(atom)
    }

    pub(crate) fn label(&self, id: RuleId) -> Option<&str> {
        let (start, end) = self.labels[id as usize];
        (start < end).then(|| &self.label_text[start as usize..end as usize])
    }

    /// A literal of this theory by its written form, `a` or `~a`.
    pub fn lit(&self, text: &str) -> Option<Lit> {
        let text = text.trim();
        match text.strip_prefix('~') {
            Some(rest) => self.atom(rest.trim()).map(|a| Lit::new(a, true)),
            None => self.atom(text).map(Lit::positive),
        }
    }

    /// Prints a literal as written: `a` or `~a`.
    pub fn show(&self, lit: Lit) -> LitDisplay<'_> {
        LitDisplay { theory: self, lit }
    }

    pub fn rule_count(&self) -> usize {
        self.heads.len()
    }

    /// How many rules were written in the file (the rest come from clause axioms).
    pub fn written_rule_count(&self) -> usize {
        self.written_rules
    }

    pub fn rule(&self, id: RuleId) -> RuleRef<'_> {
        let i = id as usize;
        RuleRef {
            id,
            label: self.label(id),
            kind: self.kinds[i],
            body: &self.bodies[self.body_start[i] as usize..self.body_start[i + 1] as usize],
            head: self.heads[i],
            origin: self.origins[i],
        }
    }

    pub fn rules(&self) -> impl Iterator<Item = RuleRef<'_>> + '_ {
        (0..self.rule_count() as RuleId).map(|r| self.rule(r))
    }

    /// `(winner, loser)` pairs: `winner > loser`.
    pub fn priorities(&self) -> &[(RuleId, RuleId)] {
        &self.priorities
    }

    /// The clause axioms as written (facts are unit clauses).
    pub fn axioms(&self) -> &[Clause] {
        &self.axioms
    }

    /// The closure of the axioms under resolution, tautologies dropped.
    pub fn closure(&self) -> &[Clause] {
        if self.closure_is_axioms {
            &self.axioms
        } else {
            &self.closure
        }
    }

    pub fn inputs(&self) -> &[InputGroup] {
        &self.inputs
    }

    /// Every declared input atom, in declaration order.
    pub fn input_atoms(&self) -> impl Iterator<Item = Atom> + '_ {
        self.inputs.iter().flat_map(|g| g.atoms.iter().copied())
    }

    pub fn outputs(&self) -> &[Output] {
        &self.outputs
    }

    pub fn row_filters(&self) -> &[RowFilter] {
        &self.filters
    }

    /// A rule printed as it would be written: `R1: a, ~b => c`.
    pub fn show_rule(&self, id: RuleId) -> String {
        let rule = self.rule(id);
        let body: Vec<String> = rule
            .body
            .iter()
            .map(|&l| self.show(l).to_string())
            .collect();
        let text = format!(
            "{} {} {}",
            body.join(", "),
            rule.kind.arrow(),
            self.show(rule.head)
        );
        let text = text.trim_start();
        match rule.label {
            Some(label) => format!("{label}: {text}"),
            None => text.to_string(),
        }
    }

    /// How a rule is named in explanations: its label, or its text when it has none.
    pub fn rule_name(&self, id: RuleId) -> String {
        match self.rule(id).label {
            Some(label) => label.to_string(),
            None => format!("`{}`", self.show_rule(id)),
        }
    }
}

pub struct LitDisplay<'t> {
    theory: &'t Theory,
    lit: Lit,
}

impl fmt::Display for LitDisplay<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.lit.is_negated() {
            f.write_str("~")?;
        }
        f.write_str(self.theory.atom_name(self.lit.atom()))
    }
}
