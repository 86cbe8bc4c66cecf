//! Formulas a session can prove: a literal, a clause (disjunction) or a conjunction of clauses.

use crate::literal::Lit;
use crate::theory::Theory;
use proclaim_syntax::{parse_query, Diagnostic, Query};

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Formula {
    Lit(Lit),
    /// `\/{…}`: proved when one member is (or the clause follows from the axioms).
    Clause(Vec<Lit>),
    /// `/\{…}`: proved when every member clause is.
    Conjunction(Vec<Vec<Lit>>),
}

impl Formula {
    /// Parses a formula written as on the command line (`a`, `~a`, `\/{a, b}`,
    /// `/\{a, \/{b, c}}`) against a theory. An atom the theory does not know is an error that
    /// names it, with a suggestion when one is close.
    pub fn parse(text: &str, theory: &Theory) -> Result<Formula, Vec<Diagnostic>> {
        let query = parse_query(text)?;
        let mut errors = Vec::new();
        let mut lower = |lit: &proclaim_syntax::SourceLiteral| -> Lit {
            let name = lit.atom.text(text);
            match theory.atom(name) {
                Some(atom) => Lit::new(atom, lit.negated),
                None => {
                    let mut d =
                        Diagnostic::error(lit.atom, format!("the theory has no atom `{name}`"))
                            .with_label("unknown atom");
                    if let Some(close) = closest_atom(theory, name) {
                        d = d.with_hint(format!("did you mean `{close}`?"));
                    }
                    errors.push(d);
                    Lit(0)
                }
            }
        };
        let formula = match &query {
            Query::Lit(l) => Formula::Lit(lower(l)),
            Query::Clause(ls) => Formula::Clause(ls.iter().map(&mut lower).collect()),
            Query::Conjunction(cs) => Formula::Conjunction(
                cs.iter()
                    .map(|c| c.iter().map(&mut lower).collect())
                    .collect(),
            ),
        };
        if errors.is_empty() {
            Ok(formula)
        } else {
            Err(errors)
        }
    }

    /// Prints the formula as it would be written.
    pub fn show(&self, theory: &Theory) -> String {
        let clause = |c: &[Lit]| match c {
            [l] => theory.show(*l).to_string(),
            _ => {
                let parts: Vec<String> = c.iter().map(|&l| theory.show(l).to_string()).collect();
                format!("\\/{{{}}}", parts.join(", "))
            }
        };
        match self {
            Formula::Lit(l) => theory.show(*l).to_string(),
            Formula::Clause(c) if c.len() == 1 => theory.show(c[0]).to_string(),
            Formula::Clause(c) => {
                let parts: Vec<String> = c.iter().map(|&l| theory.show(l).to_string()).collect();
                format!("\\/{{{}}}", parts.join(", "))
            }
            Formula::Conjunction(cs) => {
                let parts: Vec<String> = cs.iter().map(|c| clause(c)).collect();
                format!("/\\{{{}}}", parts.join(", "))
            }
        }
    }
}

/// The atom whose name is nearest to `name` (case-insensitive equality, or one edit away).
pub(crate) fn closest_atom<'t>(theory: &'t Theory, name: &str) -> Option<&'t str> {
    if theory.atom_count() > 100_000 {
        return None;
    }
    proclaim_syntax::nearest(theory.atoms.names(), name)
}
