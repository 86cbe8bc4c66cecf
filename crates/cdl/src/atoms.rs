//! The atom table: every atom name once, in one text arena, found by a hash table of atom ids.
//! One map and no allocation per atom, which matters at millions of atoms.

use crate::literal::Atom;
use crate::slots::{hash, Slots};

#[derive(Clone, Debug, Default)]
pub(crate) struct AtomTable {
    text: String,
    ends: Vec<u32>,
    index: Slots,
}

fn name_of<'t>(text: &'t str, ends: &[u32], id: u32) -> &'t str {
    let end = ends[id as usize] as usize;
    let start = if id == 0 {
        0
    } else {
        ends[id as usize - 1] as usize
    };
    &text[start..end]
}

impl AtomTable {
    pub(crate) fn len(&self) -> usize {
        self.ends.len()
    }

    pub(crate) fn reserve(&mut self, atoms: usize) {
        let (text, ends) = (&self.text, &self.ends);
        self.index
            .reserve(atoms, |id| hash(name_of(text, ends, id)));
        self.ends.reserve(atoms);
    }

    /// Starts bringing the slot a name of this [`hash`] is looked for in into the cache (see
    /// [`Slots`]).
    #[inline]
    pub(crate) fn prefetch_hashed(&self, name_hash: u64) {
        self.index.prefetch(name_hash);
    }

    pub(crate) fn get(&self, name: &str) -> Option<Atom> {
        self.index
            .find(hash(name), |id| name_of(&self.text, &self.ends, id) == name)
            .map(Atom)
    }

    /// The atom of this name, added when new (one probe of the table either way).
    pub(crate) fn intern(&mut self, name: &str) -> Atom {
        self.intern_hashed(name, hash(name))
    }

    /// [`AtomTable::intern`] for a name whose [`hash`] is known already.
    pub(crate) fn intern_hashed(&mut self, name: &str, name_hash: u64) -> Atom {
        let (text, ends) = (&self.text, &self.ends);
        let found = self.index.find_or_insert(
            name_hash,
            ends.len() as u32,
            |id| name_of(text, ends, id) == name,
            |id| hash(name_of(text, ends, id)),
        );
        match found {
            Ok(id) => Atom(id),
            Err(new) => {
                self.text.push_str(name);
                self.ends.push(self.text.len() as u32);
                Atom(new)
            }
        }
    }

    pub(crate) fn name(&self, atom: Atom) -> &str {
        name_of(&self.text, &self.ends, atom.0)
    }

    pub(crate) fn names(&self) -> impl Iterator<Item = &str> + '_ {
        (0..self.ends.len() as u32).map(|id| name_of(&self.text, &self.ends, id))
    }
}
