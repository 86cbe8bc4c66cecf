//! The atom table: every atom name once, in one text arena, found by a hash table of atom ids.
//! One map and no allocation per atom, which matters at millions of atoms.

use crate::literal::Atom;
use hashbrown::hash_table::Entry;
use hashbrown::HashTable;
use std::hash::Hasher;

#[derive(Clone, Debug, Default)]
pub(crate) struct AtomTable {
    text: String,
    ends: Vec<u32>,
    index: HashTable<u32>,
}

/// The hash the atom and label tables share.
pub(crate) fn hash(name: &str) -> u64 {
    let mut hasher = rustc_hash::FxHasher::default();
    hasher.write(name.as_bytes());
    hasher.finish()
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
            .reserve(atoms, |&id| hash(name_of(text, ends, id)));
        self.ends.reserve(atoms);
    }

    pub(crate) fn get(&self, name: &str) -> Option<Atom> {
        self.index
            .find(hash(name), |&id| {
                name_of(&self.text, &self.ends, id) == name
            })
            .map(|&id| Atom(id))
    }

    /// The atom of this name, added when new (one probe of the table either way).
    pub(crate) fn intern(&mut self, name: &str) -> Atom {
        let (text, ends) = (&self.text, &self.ends);
        match self.index.entry(
            hash(name),
            |&id| name_of(text, ends, id) == name,
            |&id| hash(name_of(text, ends, id)),
        ) {
            Entry::Occupied(found) => Atom(*found.get()),
            Entry::Vacant(slot) => {
                let id = self.ends.len() as u32;
                slot.insert(id);
                self.text.push_str(name);
                self.ends.push(self.text.len() as u32);
                Atom(id)
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
