//! A component that is a ring of small blocks, each entered at one goal and leaving only for
//! the next block's entry (the pairs ring of `benchmarks.md`; a simple cycle is the ring of
//! one-goal blocks): decided without a search of the whole ring by composing each block's
//! transfer function round it, as cdl.md §4 ("Cost") asks for simple cycles.
//!
//! Why it is exact: a path of the top-down proof that leaves block `j` for the next entry can
//! only come back to `j` through its own entry, after passing every other block once, and no
//! other block reads `j`'s goals. So, seen from `j`, the rest of the ring is one boolean
//! function of the value its entry takes when the path comes round: each other block is a
//! function of one boolean (its entry's value given the next entry's), and they compose.

use crate::component::{Component, Edge};
use crate::dominators;
use crate::engine::Csr;
use crate::goal::{condition, Goal};
use crate::session::{PENDING, TRUE};
use rustc_hash::FxHashMap;

/// Blocks larger than this are left to the search: a block is searched under every history of
/// its own goals, so its cost doubles with each goal.
const BLOCK_LIMIT: usize = 12;

/// A function of one boolean as (value at false, value at true).
pub(crate) type Function = (bool, bool);

pub(crate) fn apply(f: Function, x: bool) -> bool {
    if x {
        f.1
    } else {
        f.0
    }
}

/// `(f ∘ g)(x) = f(g(x))`
pub(crate) fn compose(f: Function, g: Function) -> Function {
    (apply(f, g.0), apply(f, g.1))
}

pub(crate) const IDENTITY: Function = (false, true);

/// For each function of a ring, the composition of all the others from the next one round:
/// `around[i] = f(i+1) ∘ … ∘ f(n-1) ∘ f0 ∘ … ∘ f(i-1)`, by prefix and suffix compositions
/// (linear).
pub(crate) fn around(functions: &[Function]) -> Vec<Function> {
    let n = functions.len();
    // prefix[i] = f0 ∘ … ∘ f(i-1); suffix[i] = fi ∘ … ∘ f(n-1).
    let mut prefix = vec![IDENTITY; n + 1];
    for i in 0..n {
        prefix[i + 1] = compose(prefix[i], functions[i]);
    }
    let mut suffix = vec![IDENTITY; n + 1];
    for i in (0..n).rev() {
        suffix[i] = compose(functions[i], suffix[i + 1]);
    }
    (0..n).map(|i| compose(suffix[i + 1], prefix[i])).collect()
}

/// The blocks in ring order: block `j`'s goals (by position in the component) read only each
/// other and the entry of block `j + 1` (mod the number of blocks).
pub(crate) struct BlockRing {
    /// Each member's block.
    block: Vec<u32>,
    /// Each member's place inside its block (its bit in a block's history).
    place: Vec<u8>,
    /// Each block's members; the first is its entry.
    members: Vec<Vec<u32>>,
}

impl BlockRing {
    /// The ring the component's reads form, if they form one of at least two blocks, none
    /// larger than [`BLOCK_LIMIT`]. Found from the dominator tree of one member: its longest
    /// chain of dominators passes through every block's entry, and a block boundary is a place
    /// on that chain that only the reads closing the ring cross backwards.
    pub(crate) fn find(component: &Component, edges: &[Edge]) -> Option<BlockRing> {
        let n = component.members.len();
        if n < 3 || component.has_aggregate() {
            return None;
        }
        let successors = Csr::build(n, edges.iter().map(|&(from, to, _)| (from, to)));
        let predecessors = Csr::build(n, edges.iter().map(|&(from, to, _)| (to, from)));
        let (order, idom) = dominators::dominator_tree(&successors, &predecessors, 0, n);
        if order.len() != n {
            return None;
        }
        let (spine, anchor) = spine(&order, &idom, n);
        let k = spine.len();
        if k < 3 {
            return None;
        }
        // A read into a later place on the spine enters at the next place (its dominator);
        // a read back is what the boundaries must not cut, but for the reads closing the ring.
        let mut back: Vec<(u32, u32)> = Vec::new();
        for &(from, to, _) in edges {
            let (df, dt) = (anchor[from as usize], anchor[to as usize]);
            if dt < df {
                back.push((dt, df));
            }
        }
        let boundaries = boundaries(&back, k)?;
        if boundaries.len() < 2 {
            return None;
        }
        let ring = BlockRing::from_boundaries(&boundaries, &spine, &anchor)?;
        ring.holds(edges).then_some(ring)
    }

    /// The blocks the boundaries cut the spine into, each member in the block of its anchor;
    /// `None` when a block is larger than [`BLOCK_LIMIT`]. Block 0 is the root's part of the
    /// spine with the part from the last boundary on: one block of the ring, entered at the last
    /// boundary's place.
    fn from_boundaries(boundaries: &[u32], spine: &[u32], anchor: &[u32]) -> Option<BlockRing> {
        let mut block_of_place = vec![0u32; spine.len()];
        for (b, pair) in boundaries.windows(2).enumerate() {
            for slot in &mut block_of_place[pair[0] as usize..pair[1] as usize] {
                *slot = b as u32 + 1;
            }
        }
        let blocks = boundaries.len();
        let mut entries: Vec<u32> = boundaries[..blocks - 1]
            .iter()
            .map(|&b| spine[b as usize])
            .collect();
        entries.insert(0, spine[*boundaries.last()? as usize]);
        let n = anchor.len();
        let mut members: Vec<Vec<u32>> = entries.iter().map(|&e| vec![e]).collect();
        let mut block = vec![0u32; n];
        for m in 0..n as u32 {
            let b = block_of_place[anchor[m as usize] as usize];
            block[m as usize] = b;
            if m != entries[b as usize] {
                let list = &mut members[b as usize];
                if list.len() >= BLOCK_LIMIT {
                    return None;
                }
                list.push(m);
            }
        }
        let mut place = vec![0u8; n];
        for list in &members {
            for (i, &m) in list.iter().enumerate() {
                place[m as usize] = i as u8;
            }
        }
        Some(BlockRing {
            block,
            place,
            members,
        })
    }

    /// Every read stays in its block or enters the next block at its entry.
    fn holds(&self, edges: &[Edge]) -> bool {
        let blocks = self.members.len() as u32;
        edges.iter().all(|&(from, to, _)| {
            let b = self.block[from as usize];
            self.block[to as usize] == b || to == self.members[((b + 1) % blocks) as usize][0]
        })
    }

    /// Every member's value from the empty history, or `None` when the blocks' searches would
    /// pass `steps` goals.
    pub(crate) fn decide(&self, component: &Component, steps: u64) -> Option<(Vec<bool>, u64)> {
        let blocks = self.members.len();
        let mut search = BlockSearch {
            component,
            ring: self,
            memo: FxHashMap::default(),
            steps: 0,
            step_limit: steps,
        };
        // Each block's entry as a function of the next entry's value.
        let mut transfer = Vec::with_capacity(blocks);
        for b in 0..blocks {
            let entry = self.members[b][0];
            search.forget();
            let at_false = search.value(entry, 0, Exit::Constant(false))?;
            let at_true = search.value(entry, 0, Exit::Constant(true))?;
            transfer.push((at_false, at_true));
        }
        let around = around(&transfer);
        let mut values = vec![false; component.members.len()];
        for (b, &around) in around.iter().enumerate() {
            search.forget();
            for &m in &self.members[b] {
                values[m as usize] = search.value(m, 0, Exit::Around(around))?;
            }
        }
        Some((values, search.steps))
    }
}

/// The chain of dominators from member 0 that always follows the largest subtree, and each
/// member's anchor: the place on that chain of its nearest dominator on it.
fn spine(order: &[u32], idom: &[u32], n: usize) -> (Vec<u32>, Vec<u32>) {
    let mut size = vec![1u32; n];
    for &v in order.iter().skip(1).rev() {
        size[idom[v as usize] as usize] += size[v as usize];
    }
    // The largest child of each member.
    let mut largest = vec![u32::MAX; n];
    for &v in order.iter().skip(1) {
        let parent = idom[v as usize] as usize;
        if largest[parent] == u32::MAX || size[largest[parent] as usize] < size[v as usize] {
            largest[parent] = v;
        }
    }
    let mut spine = vec![order[0]];
    let mut anchor = vec![u32::MAX; n];
    anchor[order[0] as usize] = 0;
    let mut at = order[0];
    while largest[at as usize] != u32::MAX {
        at = largest[at as usize];
        anchor[at as usize] = spine.len() as u32;
        spine.push(at);
    }
    // Preorder meets a dominator before what it dominates.
    for &v in order.iter().skip(1) {
        if anchor[v as usize] == u32::MAX {
            anchor[v as usize] = anchor[idom[v as usize] as usize];
        }
    }
    (spine, anchor)
}

/// The places on the spine where blocks begin, the first being where block 0 (the root's)
/// ends. A place `k` is cut by a backward read `(to, from)` when `to < k ≤ from`; a boundary is
/// cut only by the reads that close the ring, which cut every boundary. For each place, the
/// cutting reads' latest target and earliest source; the pair most places share is the ring's.
fn boundaries(back: &[(u32, u32)], k: usize) -> Option<Vec<u32>> {
    let mut by_target: Vec<(u32, u32)> = back.to_vec();
    by_target.sort_unstable();
    // Max-heap of cutting reads by target, min-heap by source; a read stops cutting once the
    // place passes its source, and is dropped when it comes to the top.
    let mut latest_target = std::collections::BinaryHeap::new();
    let mut earliest_source = std::collections::BinaryHeap::new();
    let mut next = 0;
    let mut signature = vec![(u32::MAX, u32::MAX); k];
    for place in 1..k as u32 {
        while next < by_target.len() && by_target[next].0 < place {
            let (to, from) = by_target[next];
            latest_target.push((to, from));
            earliest_source.push(std::cmp::Reverse(from));
            next += 1;
        }
        while latest_target.peek().is_some_and(|&(_, from)| from < place) {
            latest_target.pop();
        }
        while earliest_source
            .peek()
            .is_some_and(|&std::cmp::Reverse(from)| from < place)
        {
            earliest_source.pop();
        }
        if let (Some(&(to, _)), Some(&std::cmp::Reverse(from))) =
            (latest_target.peek(), earliest_source.peek())
        {
            signature[place as usize] = (to, from);
        }
    }
    let mut counts: FxHashMap<(u32, u32), u32> = FxHashMap::default();
    for &s in &signature[1..] {
        *counts.entry(s).or_default() += 1;
    }
    let (&(to, from), _) = counts
        .iter()
        .filter(|&(&s, _)| s != (u32::MAX, u32::MAX))
        .max_by_key(|&(&s, &count)| (count, std::cmp::Reverse(s)))?;
    let chosen: Vec<u32> = (to + 1..=from.min(k as u32 - 1))
        .filter(|&place| {
            let (t, f) = signature[place as usize];
            t <= to && f >= from
        })
        .collect();
    Some(chosen)
}

/// What reading the next block's entry gives, from inside a block.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
enum Exit {
    /// The same whatever the block's history: the next entry's value, given.
    Constant(bool),
    /// The path goes round the ring and back to this block's entry: `around` of the entry's
    /// value under the block's history at the moment of leaving.
    Around(Function),
}

/// The top-down proof of cdl.md §4 inside one block, the history being the block's own goals
/// (a bit each).
struct BlockSearch<'a> {
    component: &'a Component<'a>,
    ring: &'a BlockRing,
    memo: FxHashMap<(u32, u16, Exit), bool>,
    steps: u64,
    step_limit: u64,
}

impl BlockSearch<'_> {
    /// Forgets the answers of the block searched before (histories are per block).
    fn forget(&mut self) {
        self.memo.clear();
    }

    /// Member `m`'s value under the block history `history`, `None` past the step budget.
    fn value(&mut self, m: u32, history: u16, exit: Exit) -> Option<bool> {
        let bit = 1u16 << self.ring.place[m as usize];
        if history & bit != 0 {
            return Some(false);
        }
        let key = (m, history, exit);
        if let Some(&v) = self.memo.get(&key) {
            return Some(v);
        }
        self.steps += 1;
        if self.steps > self.step_limit {
            return None;
        }
        let c = self.component;
        let block = self.ring.block[m as usize];
        let inner = history | bit;
        let mut over_budget = false;
        let mut read = |s: Goal, _| match c.values[s as usize] {
            PENDING => {
                let p = c.position[s as usize];
                let v = if self.ring.block[p as usize] == block {
                    self.value(p, inner, exit)
                } else {
                    self.leave(block, inner, exit)
                };
                v.unwrap_or_else(|| {
                    over_budget = true;
                    false
                })
            }
            v => v == TRUE,
        };
        let v = condition(c.engine, c.mu, c.members[m as usize], &mut read);
        if over_budget {
            return None;
        }
        self.memo.insert(key, v);
        Some(v)
    }

    /// The next entry's value, read from block `block` with history `history`.
    fn leave(&mut self, block: u32, history: u16, exit: Exit) -> Option<bool> {
        match exit {
            Exit::Constant(v) => Some(v),
            Exit::Around(around) => {
                // Round the ring the path meets this block's entry: it fails if the block's
                // history holds it, else it is searched with the history so far, and leaving
                // again meets the next entry, already on the path.
                let entry = self.ring.members[block as usize][0];
                let back = self.value(entry, history, Exit::Constant(false))?;
                Some(apply(around, back))
            }
        }
    }
}
