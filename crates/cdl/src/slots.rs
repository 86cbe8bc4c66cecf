//! A hash table of ids whose names the caller keeps (atoms in their arena, labels in the
//! theory's label text), with lookups that can be started early.
//!
//! Our own open-addressing table rather than a `hashbrown` one because a checker that takes in a
//! million rules waits on memory at almost every probe (the slots are spread over megabytes), and
//! only a table whose slot addresses we know can be prefetched: the checker asks for the slots of
//! a few dozen names ahead ([`Slots::prefetch`]) and then looks them up while those lines arrive
//! together, which interns the atoms of a large theory in well under half the time a plain
//! hash table takes.

use std::hash::Hasher;

/// The hash every name table shares.
pub(crate) fn hash(name: &str) -> u64 {
    hash_bytes(name.as_bytes())
}

/// [`hash`] of a name's bytes.
#[inline]
pub(crate) fn hash_bytes(name: &[u8]) -> u64 {
    let mut hasher = rustc_hash::FxHasher::default();
    hasher.write(name);
    hasher.finish()
}

/// Linear probing over a power-of-two number of slots, at most half full. A slot is 0 when empty,
/// else the name's hash's high half (its low bit set, so never 0) above the id plus one: a probe
/// asks the caller to compare names only when those 32 bits of the hash agree.
#[derive(Clone, Debug, Default)]
pub(crate) struct Slots {
    slots: Vec<u64>,
    len: usize,
}

fn tag(hash: u64) -> u64 {
    (hash >> 32) | 1
}

fn pack(hash: u64, id: u32) -> u64 {
    (tag(hash) << 32) | (id as u64 + 1)
}

/// Where a probe for this hash begins in a table of `slots` slots (a power of two).
fn home(hash: u64, slots: usize) -> usize {
    hash as usize & (slots - 1)
}

impl Slots {
    /// Room for `more` ids beyond those held without growing; `hash_of` gives the hash of an id
    /// already held, for rehashing.
    pub(crate) fn reserve(&mut self, more: usize, hash_of: impl Fn(u32) -> u64) {
        let wanted = ((self.len + more).max(8) * 2).next_power_of_two();
        if wanted <= self.slots.len() {
            return;
        }
        let mut slots = vec![0u64; wanted];
        for &slot in self.slots.iter().filter(|&&s| s != 0) {
            let id = (slot as u32) - 1;
            let mut i = home(hash_of(id), wanted);
            while slots[i] != 0 {
                i = (i + 1) & (wanted - 1);
            }
            slots[i] = slot;
        }
        self.slots = slots;
    }

    /// Starts bringing the slot a name of this hash is looked for in into the cache, so that the
    /// lookup a little later does not wait for memory. Only a hint: nothing changes.
    #[inline]
    pub(crate) fn prefetch(&self, hash: u64) {
        if self.slots.is_empty() {
            return;
        }
        #[cfg(target_arch = "x86_64")]
        {
            let slot = self.slots[home(hash, self.slots.len())..].as_ptr();
            // Safe on every x86_64 (SSE is part of the architecture); a prefetch reads nothing
            // the program sees and cannot fault. `unsafe` for toolchains before 1.87, where the
            // intrinsic was not yet a safe function.
            #[allow(unused_unsafe)]
            unsafe {
                core::arch::x86_64::_mm_prefetch::<{ core::arch::x86_64::_MM_HINT_T0 }>(
                    slot.cast::<i8>(),
                );
            }
        }
    }

    /// The id held for a name of this hash that `is_name` accepts, if any.
    pub(crate) fn find(&self, hash: u64, is_name: impl Fn(u32) -> bool) -> Option<u32> {
        self.probe(hash, is_name).ok()
    }

    /// The id held for this name, or `new` added for it. `Err(new)` when it was added; the
    /// table grows first when it must (`hash_of` as for [`Slots::reserve`]).
    pub(crate) fn find_or_insert(
        &mut self,
        hash: u64,
        new: u32,
        is_name: impl Fn(u32) -> bool,
        hash_of: impl Fn(u32) -> u64,
    ) -> Result<u32, u32> {
        if (self.len + 1) * 2 > self.slots.len() {
            self.reserve(1, hash_of);
        }
        match self.probe(hash, is_name) {
            Ok(id) => Ok(id),
            Err(empty) => {
                self.slots[empty] = pack(hash, new);
                self.len += 1;
                Err(new)
            }
        }
    }

    /// The id found, or the empty slot where the probe ended. A table with no slots yet has no
    /// slot to give: only `find` meets one (`find_or_insert` grows the table first).
    fn probe(&self, hash: u64, is_name: impl Fn(u32) -> bool) -> Result<u32, usize> {
        if self.slots.is_empty() {
            return Err(usize::MAX);
        }
        let mask = self.slots.len() - 1;
        let tag = tag(hash);
        let mut i = home(hash, self.slots.len());
        loop {
            let slot = self.slots[i];
            if slot == 0 {
                return Err(i);
            }
            if slot >> 32 == tag && is_name((slot as u32) - 1) {
                return Ok((slot as u32) - 1);
            }
            i = (i + 1) & mask;
        }
    }

    /// The ids held, in no particular order.
    pub(crate) fn ids(&self) -> impl Iterator<Item = u32> + '_ {
        self.slots
            .iter()
            .filter(|&&s| s != 0)
            .map(|&s| (s as u32) - 1)
    }
}

#[cfg(test)]
mod tests {
    use super::{hash, Slots};

    #[test]
    fn every_name_is_held_once_and_found_again_across_growth() {
        let names: Vec<String> = (0..5000).map(|i| format!("a{i}")).collect();
        let mut slots = Slots::default();
        for (i, name) in names.iter().enumerate() {
            slots.prefetch(hash(name));
            let got = slots.find_or_insert(
                hash(name),
                i as u32,
                |id| names[id as usize] == *name,
                |id| hash(&names[id as usize]),
            );
            assert_eq!(got, Err(i as u32));
        }
        for (i, name) in names.iter().enumerate() {
            let again = slots.find_or_insert(
                hash(name),
                u32::MAX,
                |id| names[id as usize] == *name,
                |id| hash(&names[id as usize]),
            );
            assert_eq!(again, Ok(i as u32), "{name} again");
        }
        assert_eq!(slots.len, names.len());
        assert_eq!(slots.ids().count(), names.len());
        assert_eq!(slots.find(hash("b0"), |_| false), None);
        assert_eq!(Slots::default().find(hash("a0"), |_| true), None);
    }

    #[test]
    fn a_reserved_table_holds_what_it_reserved_without_growing() {
        let mut slots = Slots::default();
        slots.reserve(1000, |_| unreachable!("nothing to rehash"));
        let size = slots.slots.len();
        for i in 0..1000u32 {
            let h = hash(&i.to_string());
            let added = slots.find_or_insert(h, i, |_| false, |_| unreachable!("no growth"));
            assert_eq!(added, Err(i));
        }
        assert_eq!(slots.slots.len(), size);
    }
}
