//! Atoms and literals as dense integers: the currency of the checked theory and the engine.

/// An atom of a theory, numbered densely from 0 in order of first appearance.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Atom(pub u32);

/// A literal: an atom or its negation, packed as `atom * 2 + negated` so that complement is one
/// bit flip and literals index arrays directly.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Lit(pub u32);

impl Lit {
    pub fn new(atom: Atom, negated: bool) -> Lit {
        Lit(atom.0 << 1 | negated as u32)
    }

    pub fn positive(atom: Atom) -> Lit {
        Lit::new(atom, false)
    }

    pub fn atom(self) -> Atom {
        Atom(self.0 >> 1)
    }

    pub fn is_negated(self) -> bool {
        self.0 & 1 == 1
    }

    pub fn complement(self) -> Lit {
        Lit(self.0 ^ 1)
    }

    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// Index of a rule in its theory.
pub type RuleId = u32;
