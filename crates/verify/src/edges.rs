//! The explicit search's successor lists, compressed into a byte stream as they are made. States
//! are numbered in the order they are found, so an edge to a state found by that very edge
//! needs no number (it is the next one) and takes a byte; an edge to a state found before is
//! the distance between the two numbers, as a varint. The breadth-first tree is then the edges
//! that found their state, so a state's parent is read from here rather than kept. Lists are
//! read in order; a list in the middle is found from the nearest block start (a byte offset
//! and the next new state's number every [`BLOCK`] lists).

use crate::chunked::Chunked;

/// Lists between two block starts.
const BLOCK: usize = 64;

/// The bit of an edge's varint that ends its list.
const LAST: u64 = 1;

/// One edge of a list: the state it leads to and whether a transition fired on the step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Edge {
    pub target: u32,
    pub fired: bool,
}

#[derive(Debug, Default)]
pub struct Edges {
    bytes: Chunked<u8>,
    /// Per block: where its first list starts in `bytes`.
    block_at: Vec<usize>,
    /// Per block: the number the first state found by its lists gets.
    block_found: Vec<u32>,
    lists: usize,
    edges: usize,
    /// The number the next state found gets.
    found: u32,
}

impl Edges {
    /// No lists yet; the first state found by an edge gets number `initial` (the initial states
    /// come before).
    pub fn new(initial: u32) -> Edges {
        Edges {
            found: initial,
            ..Edges::default()
        }
    }

    /// Lists held: states `0..lists()` had their successors made.
    pub fn lists(&self) -> usize {
        self.lists
    }

    pub fn len(&self) -> usize {
        self.edges
    }

    /// Bytes allocated, and at most what they would be after one more list of `edges` edges.
    pub fn bytes_after(&self, edges: usize) -> usize {
        let blocks = self.block_at.capacity() * 8 + self.block_found.capacity() * 4;
        self.bytes.bytes_after(5 + 6 * edges) + blocks + 12
    }

    /// Appends the successor list of state `lists()`; `new` says of each edge whether it found
    /// its state (which then has the next number). Each edge is one varint: its code (0 for an
    /// empty list, 1 for a state found by the edge, else 2 and the zigzagged distance from the
    /// list's state), whether a transition fired, and whether it is the list's last.
    pub fn push(&mut self, list: impl ExactSizeIterator<Item = (Edge, bool)>) {
        let source = self.lists as u32;
        if self.lists % BLOCK == 0 {
            self.block_at.push(self.bytes.len());
            self.block_found.push(self.found);
        }
        let last = list.len();
        if last == 0 {
            self.varint(LAST);
        }
        for (i, (edge, new)) in list.enumerate() {
            let code = if new {
                debug_assert_eq!(edge.target, self.found);
                self.found += 1;
                1
            } else {
                2 + zigzag(i64::from(edge.target) - i64::from(source))
            };
            let end = if i + 1 == last { LAST } else { 0 };
            self.varint(code << 2 | u64::from(edge.fired) << 1 | end);
            self.edges += 1;
        }
        self.lists += 1;
    }

    fn varint(&mut self, mut v: u64) {
        while v >= 0x80 {
            self.bytes.push(v as u8 | 0x80);
            v >>= 7;
        }
        self.bytes.push(v as u8);
    }

    /// Every list from state `first` on, in order: each state's number and its edges.
    pub fn from(&self, first: usize) -> Reader<'_> {
        let block = first / BLOCK;
        let mut reader = Reader {
            edges: self,
            at: self.block_at.get(block).copied().unwrap_or(0),
            source: (block * BLOCK) as u32,
            found: self.block_found.get(block).copied().unwrap_or(self.found),
        };
        while (reader.source as usize) < first.min(self.lists) {
            reader.skip_list();
        }
        reader
    }

    /// The state whose list found state `id` (`None` for one found by no list: an initial
    /// state).
    pub fn finder(&self, id: u32) -> Option<u32> {
        let block = self
            .block_found
            .partition_point(|&f| f <= id)
            .checked_sub(1)?;
        let mut reader = self.from(block * BLOCK);
        while let Some((source, list)) = reader.next_list() {
            for (edge, new) in list {
                if new && edge.target == id {
                    return Some(source);
                }
            }
            if reader.found > id {
                return None;
            }
        }
        None
    }
}

fn zigzag(v: i64) -> u64 {
    ((v << 1) ^ (v >> 63)) as u64
}

fn unzigzag(v: u64) -> i64 {
    (v >> 1) as i64 ^ -((v & 1) as i64)
}

/// Reads lists in order.
pub struct Reader<'a> {
    edges: &'a Edges,
    at: usize,
    source: u32,
    found: u32,
}

impl Reader<'_> {
    fn varint(&mut self) -> u64 {
        let mut v = 0u64;
        let mut shift = 0;
        loop {
            let b = self.edges.bytes.get(self.at);
            self.at += 1;
            v |= u64::from(b & 0x7f) << shift;
            if b & 0x80 == 0 {
                return v;
            }
            shift += 7;
        }
    }

    /// The next edge of the list being read, whether it found its state, and whether it ends
    /// the list; `None` for an empty list.
    fn edge(&mut self) -> Option<(Edge, bool, bool)> {
        let v = self.varint();
        let last = v & LAST != 0;
        let fired = v & 2 != 0;
        match v >> 2 {
            0 => None,
            1 => {
                self.found += 1;
                let target = self.found - 1;
                Some((Edge { target, fired }, true, last))
            }
            code => {
                let target = (i64::from(self.source) + unzigzag(code - 2)) as u32;
                Some((Edge { target, fired }, false, last))
            }
        }
    }

    /// Hands each edge of the next list, with whether it found its state, to `each`.
    fn list(&mut self, mut each: impl FnMut(Edge, bool)) {
        while let Some((edge, new, last)) = self.edge() {
            each(edge, new);
            if last {
                break;
            }
        }
        self.source += 1;
    }

    fn skip_list(&mut self) {
        self.list(|_, _| {});
    }

    /// The next state's number and its edges (with whether each found its state), or `None`
    /// after the last list.
    pub fn next_list(&mut self) -> Option<(u32, Vec<(Edge, bool)>)> {
        if self.source as usize >= self.edges.lists {
            return None;
        }
        let source = self.source;
        let mut list = Vec::new();
        self.list(|edge, new| list.push((edge, new)));
        Some((source, list))
    }

    /// Hands every edge of the next list to `each`, with the list's state; `false` after the
    /// last list.
    pub fn each_of_next(&mut self, mut each: impl FnMut(u32, Edge)) -> bool {
        if self.source as usize >= self.edges.lists {
            return false;
        }
        let source = self.source;
        self.list(|edge, _| each(source, edge));
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_read_back_and_finders_are_the_edges_that_found() {
        // A breadth-first graph over 1000 states from 1 initial state: state s finds the next
        // two states while there are any, and points back at s / 2 and forward at s + 300.
        let states = 1000u32;
        let mut edges = Edges::new(1);
        let mut found = 1u32;
        let mut expected = Vec::new();
        for s in 0..states {
            let mut list = Vec::new();
            for _ in 0..2 {
                if found < states {
                    list.push((
                        Edge {
                            target: found,
                            fired: s % 3 == 0,
                        },
                        true,
                    ));
                    found += 1;
                }
            }
            list.push((
                Edge {
                    target: s / 2,
                    fired: false,
                },
                false,
            ));
            if s + 300 < found {
                list.push((
                    Edge {
                        target: s + 300,
                        fired: true,
                    },
                    false,
                ));
            }
            expected.push(list.clone());
            edges.push(list.into_iter());
        }
        assert_eq!(edges.lists(), states as usize);
        let mut reader = edges.from(0);
        for (s, list) in expected.iter().enumerate() {
            assert_eq!(reader.next_list(), Some((s as u32, list.clone())));
        }
        assert_eq!(reader.next_list(), None);
        assert_eq!(
            edges.from(130).next_list(),
            Some((130, expected[130].clone()))
        );
        assert_eq!(edges.finder(0), None);
        for id in 1..states {
            assert_eq!(edges.finder(id), Some((id - 1) / 2), "state {id}");
        }
    }
}
