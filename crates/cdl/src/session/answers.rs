//! Every literal's answer under one algorithm at once, for the commands that print them all
//! (`prove` with no query, SPINdle's format, the benchmarks): one pass over the literals, each
//! goal settled once by the same walk a single query takes, and no reason built for an answer
//! that is not undecided.

use super::*;

/// A literal's answer without its reasons: [`Session::decide`] gives those of an undecided one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProofOutcome {
    Proved,
    NotProved,
    /// Not decided within the search limits.
    Undecided,
}

impl From<Truth> for ProofOutcome {
    fn from(truth: Truth) -> ProofOutcome {
        match truth {
            Truth::True => ProofOutcome::Proved,
            Truth::False => ProofOutcome::NotProved,
            Truth::Undecided(_) => ProofOutcome::Undecided,
        }
    }
}

impl Session {
    /// Whether `alg` proves the literal, without the reasons [`Session::decide`] gives for an
    /// undecided answer.
    pub fn verdict(&mut self, alg: Algorithm, lit: Lit) -> ProofOutcome {
        ProofOutcome::from(self.truth(alg, lit))
    }

    /// The answer of `alg` for every literal of the theory, indexed by [`Lit::index`]: the same
    /// as [`Session::decide`] asked literal by literal.
    pub fn answers(&mut self, alg: Algorithm) -> Vec<ProofOutcome> {
        (0..self.engine.lit_count as u32)
            .map(|l| self.verdict(alg, Lit(l)))
            .collect()
    }

    /// Every literal `alg` proves, in literal order.
    pub fn conclusions(&mut self, alg: Algorithm) -> Vec<Lit> {
        self.answers(alg)
            .into_iter()
            .zip(0..)
            .filter(|(v, _)| *v == ProofOutcome::Proved)
            .map(|(_, l)| Lit(l))
            .collect()
    }

    /// How many literals `alg` proves.
    pub fn count_conclusions(&mut self, alg: Algorithm) -> usize {
        (0..self.engine.lit_count as u32)
            .filter(|&l| self.truth(alg, Lit(l)) == Truth::True)
            .count()
    }
}
