//! The explicit search's index from a state's packed record to its number: open addressing
//! with linear probing over 4-byte entries (a state number and a few bits of its record's hash,
//! so most probes that cannot match are passed without reading a record), grown by half its
//! size when it is four-fifths full rather than doubled, so it holds little over what it
//! indexes.

/// Bits of an entry that hold the state number (plus one: 0 is an empty entry).
const ID_BITS: u32 = 27;
const ID_MASK: u32 = (1 << ID_BITS) - 1;

/// The most states the table can index.
pub const MAX_STATES: usize = ID_MASK as usize - 1;

/// The fewest entries a table has once it holds anything.
const SMALLEST: usize = 64;

#[derive(Debug, Default)]
pub struct StateTable {
    entries: Vec<u32>,
    len: usize,
}

/// The hash of a packed record: 8 bytes at a time, each folded in by a full 64-by-64-bit
/// multiply, so both the high bits (where an entry goes) and the low ones (the tag an entry
/// keeps) depend on every byte.
pub fn hash(record: &[u8]) -> u64 {
    let mut h: u64 = 0x243f_6a88_85a3_08d3;
    let mut words = record.chunks_exact(8);
    for word in &mut words {
        let mut w = [0u8; 8];
        w.copy_from_slice(word);
        h = fold(h ^ u64::from_le_bytes(w), 0x9e37_79b9_7f4a_7c15);
    }
    // The last few bytes a byte at a time: a copy of a length unknown here is a call.
    let rest = words
        .remainder()
        .iter()
        .rev()
        .fold(0u64, |w, &b| w << 8 | u64::from(b));
    fold(h ^ rest, 0xbf58_476d_1ce4_e5b9)
}

/// Whether two packed records are the same: those of a few bytes (most) compared as one
/// number, since comparing them as slices is a call.
pub fn same(a: &[u8], b: &[u8]) -> bool {
    if a.len() != b.len() {
        return false;
    }
    if a.len() > 16 {
        return a == b;
    }
    let number = |r: &[u8]| {
        r.iter()
            .rev()
            .fold(0u128, |n, &byte| n << 8 | u128::from(byte))
    };
    number(a) == number(b)
}

fn fold(a: u64, b: u64) -> u64 {
    let product = u128::from(a) * u128::from(b);
    (product as u64) ^ ((product >> 64) as u64)
}

impl StateTable {
    #[cfg(test)]
    pub fn len(&self) -> usize {
        self.len
    }

    /// Bytes allocated.
    pub fn bytes(&self) -> usize {
        self.entries.len() * 4
    }

    /// Bytes allocated at the peak of holding `more` more states: while the table grows, both
    /// the old entries and the new.
    pub fn bytes_after(&self, more: usize) -> usize {
        if self.len + more > self.limit() {
            self.bytes() + grown(self.entries.len(), self.len + more) * 4
        } else {
            self.bytes()
        }
    }

    /// The state whose record has `hash` and for which `same` says yes; else `id` is entered
    /// for it. `hash_of` gives a stored state's hash, for when the table grows (every state
    /// `0..len()` is in the table, and `id` is `len()`).
    pub fn find_or_insert(
        &mut self,
        hash: u64,
        id: u32,
        same: impl Fn(u32) -> bool,
        hash_of: impl Fn(u32) -> u64,
    ) -> Option<u32> {
        if self.len + 1 > self.limit() {
            self.grow(hash_of);
        }
        let tag = tag_of(hash);
        let mask = self.entries.len();
        let mut at = home(hash, mask);
        loop {
            let entry = self.entries[at];
            if entry == 0 {
                self.entries[at] = tag | (id + 1);
                self.len += 1;
                return None;
            }
            if entry & !ID_MASK == tag && same((entry & ID_MASK) - 1) {
                return Some((entry & ID_MASK) - 1);
            }
            at += 1;
            if at == mask {
                at = 0;
            }
        }
    }

    /// Reads the entry a record of `hash` is looked for first, so that it is in the cache when
    /// it is looked for.
    pub fn touch(&self, hash: u64) {
        if !self.entries.is_empty() {
            std::hint::black_box(self.entries[home(hash, self.entries.len())]);
        }
    }

    /// How many states the table holds before it grows: four-fifths of its entries.
    fn limit(&self) -> usize {
        self.entries.len() / 5 * 4
    }

    /// Enters every state again in a larger table. The old entries are taken in the order they
    /// lie, which is (but for the few displaced past the end) the order of their hashes, so
    /// the new entries are written in order too rather than scattered.
    fn grow(&mut self, hash_of: impl Fn(u32) -> u64) {
        let size = grown(self.entries.len(), self.len + 1);
        let mut entries = vec![0u32; size];
        for &entry in self.entries.iter().filter(|&&e| e != 0) {
            let hash = hash_of((entry & ID_MASK) - 1);
            let mut at = home(hash, size);
            while entries[at] != 0 {
                at = if at + 1 == size { 0 } else { at + 1 };
            }
            entries[at] = entry;
        }
        self.entries = entries;
    }
}

/// The size a table of `size` entries grows to so that it holds `states`.
fn grown(size: usize, states: usize) -> usize {
    let mut size = size.max(SMALLEST / 2);
    while size / 5 * 4 < states {
        size += size / 2;
    }
    size
}

/// Where an entry of `hash` goes first in a table of `size` entries: its high bits scaled.
fn home(hash: u64, size: usize) -> usize {
    ((u128::from(hash) * size as u128) >> 64) as usize
}

/// The hash bits an entry keeps beside the state number.
fn tag_of(hash: u64) -> u32 {
    (hash as u32) & !ID_MASK
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_record_is_found_again_across_growth() {
        let records: Vec<[u8; 3]> = (0..50_000u32)
            .map(|i| [(i % 251) as u8, (i / 251) as u8, 7])
            .collect();
        let mut table = StateTable::default();
        for (i, r) in records.iter().enumerate() {
            let found = table.find_or_insert(
                hash(r),
                i as u32,
                |id| records[id as usize] == *r,
                |id| hash(&records[id as usize]),
            );
            assert_eq!(found, None, "record {i} is new");
        }
        assert_eq!(table.len(), records.len());
        for (i, r) in records.iter().enumerate() {
            let found = table.find_or_insert(
                hash(r),
                u32::MAX,
                |id| records[id as usize] == *r,
                |id| hash(&records[id as usize]),
            );
            assert_eq!(found, Some(i as u32));
        }
        assert!(same(&records[3], &[3, 0, 7]) && !same(&records[3], &records[4]));
        assert!(
            !same(&[1, 2], &[1, 2, 0]),
            "a longer record is another record"
        );
        assert!(
            table.bytes() < records.len() * 4 * 2,
            "{} bytes",
            table.bytes()
        );
    }
}
