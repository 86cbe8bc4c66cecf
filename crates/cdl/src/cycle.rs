//! Evaluating one strongly connected component of the goal graph that holds a cycle: a least
//! fixpoint when only support runs through it; with attacks inside, the structure cdl.md §4
//! ("Cost") names (a simple cycle in closed form, mutual attacks as undirected vertex geography
//! through maximum matchings, a ring of small blocks by composition in `ring.rs`, a ring of
//! layers of two by the dynamic program of `layers.rs`), or its
//! falling apart once reads that change nothing are dropped (`relevance.rs`), then bounds, then
//! a top-down search under a budget.

use crate::component::{Component, Edge, Evaluated, Method, Outcome, SearchLimits};
use crate::dominators;
use crate::goal::{condition, successors, Goal, Read, ATTACK, ATTACK_READ};
use crate::layers::Layers;
use crate::matching::uncovered_by_some_maximum_matching;
use crate::relevance::independent_parts;
use crate::ring::{apply, around, BlockRing, Function};
use crate::session::{FALSE, PENDING, TRUE, UNDECIDED};
use rustc_hash::FxHashMap;

/// Components larger than this are not tried as geography (the blossom search is cubic).
const GEOGRAPHY_LIMIT: usize = 2048;

/// Bounds the work of refining the lower bound: attacking goals times component size.
const REFINE_LIMIT: usize = 50_000_000;

/// Every (read member, reader) pair of the edges, sorted, without repeats. The edges come in
/// ascending order of reader, so a counting sort on the read member keeps each member's readers
/// in order: linear, where sorting by comparison was a visible share of deciding a component of
/// a million members.
fn readers_by_read_member(edges: &[Edge], members: usize) -> Vec<(u32, u32)> {
    debug_assert!(edges.windows(2).all(|w| w[0].0 <= w[1].0));
    let mut next = vec![0u32; members + 1];
    for &(_, read, _) in edges {
        next[read as usize + 1] += 1;
    }
    for i in 1..next.len() {
        next[i] += next[i - 1];
    }
    let mut readers = vec![(0, 0); edges.len()];
    for &(reader, read, _) in edges {
        let slot = &mut next[read as usize];
        readers[*slot as usize] = (read, reader);
        *slot += 1;
    }
    readers.dedup();
    readers
}

impl Component<'_> {
    /// Decides every member, or (when `may_fall_apart`) says which parts it is made of.
    pub fn evaluate(&self, limits: &SearchLimits, may_fall_apart: bool) -> Outcome {
        let mut edges = self.edges();
        let decided = |values: Vec<bool>, method| Evaluated {
            values: values
                .into_iter()
                .map(|v| if v { TRUE } else { FALSE })
                .collect(),
            method,
            steps: 0,
        };
        let readers = readers_by_read_member(&edges, self.members.len());
        let fixpoint = Fixpoint {
            component: self,
            readers: &readers,
        };
        if edges.iter().all(|&(_, _, attack)| !attack) {
            return Outcome::Evaluated(decided(
                fixpoint.least(|_, _| false, None),
                Method::Fixpoint,
            ));
        }
        // Sorted by reader, without repeats: what the structural tests look edges up in. They
        // come grouped by reader already, so only each reader's few edges need sorting.
        edges
            .chunk_by_mut(|a, b| a.0 == b.0)
            .for_each(|reads| reads.sort_unstable());
        edges.dedup();
        if let Some(values) = self.simple_cycle(&edges) {
            return Outcome::Evaluated(decided(values, Method::SimpleCycle));
        }
        if let Some(values) = self.geography(&edges) {
            return Outcome::Evaluated(decided(values, Method::Geography));
        }
        if let Some((values, steps)) =
            BlockRing::find(self, &edges).and_then(|ring| ring.decide(self, limits.steps))
        {
            return Outcome::Evaluated(Evaluated {
                steps,
                ..decided(values, Method::Ring)
            });
        }
        if let Some(layers) = Layers::find(self, &edges) {
            return Outcome::Evaluated(decided(layers.decide(self), Method::Layers));
        }
        if let Some(parts) = may_fall_apart
            .then(|| independent_parts(self, &edges))
            .flatten()
        {
            return Outcome::Parts(parts);
        }
        Outcome::Evaluated(self.search(&edges, &fixpoint, limits))
    }

    /// Every internal read, in member order (repeats possible).
    fn edges(&self) -> Vec<Edge> {
        let mut edges = Vec::new();
        let mut buffer = Vec::new();
        for (from, &g) in self.members.iter().enumerate() {
            buffer.clear();
            successors(self.engine, self.mu, g, &mut buffer, |s| {
                self.values[s as usize] == PENDING
            });
            for &s in &buffer {
                let to = self.position[(s & !ATTACK) as usize];
                edges.push((from as u32, to, s & ATTACK != 0));
            }
        }
        edges
    }

    /// Whether a member is an aggregate: it never enters the history, so a path may meet it
    /// twice, which the structural methods (each a claim about paths) do not allow for.
    pub(crate) fn has_aggregate(&self) -> bool {
        self.members.iter().any(|&g| self.engine.is_aggregate(g))
    }

    /// A member's condition with the members `is_true` accepts (by position) read as true and
    /// the other members as false.
    pub(crate) fn condition_with(&self, member: u32, is_true: impl Fn(u32) -> bool) -> bool {
        let mut read = |s: Goal, _: Read| match self.values[s as usize] {
            PENDING => is_true(self.position[s as usize]),
            v => v == TRUE,
        };
        condition(
            self.engine,
            self.mu,
            self.members[member as usize],
            &mut read,
        )
    }

    /// A component in which every member reads exactly one other member is one cycle: from any
    /// member the search walks it once round and meets the start, which fails. Each member is a
    /// function of its one read; the value of member `i` is the composition of the functions
    /// from `i` round to `i - 1`, applied to false.
    fn simple_cycle(&self, edges: &[Edge]) -> Option<Vec<bool>> {
        let n = self.members.len();
        if self.has_aggregate() {
            return None;
        }
        let mut next = vec![u32::MAX; n];
        for &(from, to, _) in edges {
            let slot = &mut next[from as usize];
            if *slot != u32::MAX && *slot != to {
                return None;
            }
            *slot = to;
        }
        // Strongly connected with one successor each: a single cycle through every member.
        let mut order = Vec::with_capacity(n);
        let mut seen = vec![false; n];
        let mut at = 0u32;
        for _ in 0..n {
            if at == u32::MAX || seen[at as usize] {
                return None;
            }
            seen[at as usize] = true;
            order.push(at);
            at = next[at as usize];
        }
        if at != 0 {
            return None;
        }
        let functions: Vec<Function> = order
            .iter()
            .map(|&m| {
                let read = next[m as usize];
                (
                    self.condition_with(m, |_| false),
                    self.condition_with(m, |x| x == read),
                )
            })
            .collect();
        let mut values = vec![false; n];
        for ((&m, &f), rest) in order.iter().zip(&functions).zip(around(&functions)) {
            values[m as usize] = apply(f, apply(rest, false));
        }
        Some(values)
    }

    /// Members that read each other only through attackers, symmetrically, and each hold exactly
    /// when no member it reads does: `beta(v, H)` is then the undirected vertex geography game on
    /// the attack graph, and holds from the empty history iff some maximum matching leaves `v`
    /// uncovered.
    fn geography(&self, edges: &[Edge]) -> Option<Vec<bool>> {
        let n = self.members.len();
        if n > GEOGRAPHY_LIMIT
            || edges.iter().any(|&(_, _, attack)| !attack)
            || self.has_aggregate()
        {
            return None;
        }
        let mut adjacency = vec![Vec::new(); n];
        for &(from, to, _) in edges {
            if from == to || edges.binary_search(&(to, from, true)).is_err() {
                return None;
            }
            adjacency[from as usize].push(to);
        }
        // The condition must be "no member I read holds": true with none, false with any one.
        for (m, read) in adjacency.iter().enumerate() {
            let m = m as u32;
            if !self.condition_with(m, |_| false)
                || read.iter().any(|&r| self.condition_with(m, |x| x == r))
            {
                return None;
            }
        }
        Some(uncovered_by_some_maximum_matching(&adjacency))
    }

    /// Least fixpoints bound the answers exactly: `up` reads every internal attack as failing,
    /// so a goal outside it fails under any history. `low` reads an internal attack on `x` by
    /// goal `g` as `x`'s upper bound computed with `g` removed (`g` is on the history whenever it
    /// reads `x`), so a goal inside `low` holds from the empty history: its minimal derivation
    /// never meets a goal twice on a path. Only goals between the bounds are proved top-down, as
    /// cdl.md §4 reads, with the history restricted to the component, until the budget is spent.
    fn search(&self, edges: &[Edge], fixpoint: &Fixpoint, limits: &SearchLimits) -> Evaluated {
        let members = self.members;
        let up = fixpoint.least(|_, _| false, None);
        let attacks: Vec<(u32, u32)> = edges
            .iter()
            .filter(|&&(_, _, attack)| attack)
            .map(|&(from, to, _)| (from, to))
            .collect();
        // First the cheap lower bound (an internal attack holds wherever its target can): when
        // it meets the upper bound, nothing is left to refine or search.
        let coarse = fixpoint.least(|_, x| up[x as usize], None);
        if coarse == up {
            return Evaluated {
                values: up.iter().map(|&v| if v { TRUE } else { FALSE }).collect(),
                method: Method::Search,
                steps: 0,
            };
        }
        // When every member's support reads at most one member per way (a graph of ORs), "`x`
        // without `g`" is "`g` does not dominate `x`" from the settled support: one dominator
        // tree instead of a fixpoint per attacker.
        if let Some(tree) = SupportDominators::new(self, &up) {
            let low = fixpoint.least(
                |reader, x| up[x as usize] && !tree.dominates(reader, x),
                None,
            );
            return self.top_down(&up, &low, limits);
        }
        let mut distinct: Vec<u32> = attacks
            .iter()
            .map(|&(g, _)| g)
            .filter(|&g| up[g as usize])
            .collect();
        distinct.dedup();
        let refine = distinct.len().saturating_mul(members.len()) <= REFINE_LIMIT;
        let mut holds: FxHashMap<(u32, u32), bool> = FxHashMap::default();
        if refine {
            for &g in &distinct {
                let without = fixpoint.least(|_, _| false, Some(g));
                let start = attacks.partition_point(|&(r, _)| r < g);
                for &(_, x) in attacks[start..].iter().take_while(|&&(r, _)| r == g) {
                    holds.insert((g, x), without[x as usize]);
                }
            }
        }
        let low = if refine {
            fixpoint.least(
                |reader, x| holds.get(&(reader, x)).copied().unwrap_or(false),
                None,
            )
        } else {
            coarse
        };
        self.top_down(&up, &low, limits)
    }

    /// Proves the members between the bounds top-down, until the budget is spent.
    fn top_down(&self, up: &[bool], low: &[bool], limits: &SearchLimits) -> Evaluated {
        let members = self.members;
        let mut top_down = TopDown::new(self, up, limits);
        let values = members
            .iter()
            .enumerate()
            .map(|(i, &g)| {
                if low[i] {
                    TRUE
                } else if !up[i] {
                    FALSE
                } else {
                    let v = top_down.prove(g);
                    top_down.forget_histories();
                    if top_down.exhausted {
                        UNDECIDED
                    } else if v {
                        TRUE
                    } else {
                        FALSE
                    }
                }
            })
            .collect();
        Evaluated {
            values,
            method: Method::Search,
            steps: top_down.steps,
        }
    }
}

/// Dominators of the upper bound's support graph, when it is a graph of ORs: a root stands for
/// everything settled, a member hangs from each member one of its ways to be supported reads
/// alone. `g` dominates `x` when every derivation of `x` passes through `g`.
struct SupportDominators {
    /// Each member's interval in a depth-first numbering of the dominator tree; none for
    /// members the root does not reach.
    enter: Vec<u32>,
    leave: Vec<u32>,
}

impl SupportDominators {
    fn new(c: &Component, up: &[bool]) -> Option<SupportDominators> {
        let root = c.members.len() as u32;
        let edges = support_graph(c, up, root)?;
        let nodes = c.members.len() + 1;
        let successors = crate::engine::Csr::build(nodes, edges.iter().copied());
        let predecessors = crate::engine::Csr::build(nodes, edges.iter().map(|&(a, b)| (b, a)));
        let (order, idom) = dominators::dominator_tree(&successors, &predecessors, root, nodes);
        let children =
            crate::engine::Csr::build(nodes, order.iter().skip(1).map(|&v| (idom[v as usize], v)));
        let (enter, leave) = dominators::intervals(&children, root, nodes);
        Some(SupportDominators { enter, leave })
    }

    /// Whether every derivation of member `x` in the upper bound passes through member `g` (so
    /// that `x` fails while `g` is on the history).
    fn dominates(&self, g: u32, x: u32) -> bool {
        let (g, x) = (g as usize, x as usize);
        self.enter[x] == u32::MAX
            || (self.enter[g] != u32::MAX
                && self.enter[g] <= self.enter[x]
                && self.leave[x] <= self.leave[g])
    }
}

/// The upper bound's support as edges `(p, x)`: some way of supporting `x` reads member `p`
/// alone (`root` for the ways that read no member). `None` when some way reads two members, or
/// a team of superiors reads one: not a graph of ORs.
fn support_graph(c: &Component, up: &[bool], root: u32) -> Option<Vec<(u32, u32)>> {
    let mut edges: Vec<(u32, u32)> = Vec::new();
    let mut or_graph = true;
    for (x, &g) in c.members.iter().enumerate() {
        if !up[x] {
            continue;
        }
        let settled = |s: Goal| match c.values[s as usize] {
            PENDING => None,
            v => Some(v == TRUE),
        };
        let structure = crate::goal::supporters(c.engine, c.mu, g, &settled, &mut |reads| {
            let mut internal = None;
            let mut holds = true;
            for s in reads {
                match c.values[s as usize] {
                    PENDING => {
                        let p = c.position[s as usize];
                        if internal.is_some_and(|q| q != p) {
                            or_graph = false;
                        }
                        internal = Some(p);
                    }
                    v => holds &= v == TRUE,
                }
            }
            match internal {
                _ if !holds => {}
                None => edges.push((root, x as u32)),
                Some(p) if up[p as usize] => edges.push((p, x as u32)),
                Some(_) => {}
            }
        });
        if structure.is_err() || !or_graph {
            return None;
        }
    }
    Some(edges)
}

/// Least fixpoints over the members of one component.
struct Fixpoint<'a> {
    component: &'a Component<'a>,
    /// (read member, reading member), sorted: a member that turns true wakes only its readers.
    readers: &'a [(u32, u32)],
}

impl Fixpoint<'_> {
    /// Support reads of members take the current approximation; an attack read of member `x` by
    /// member `r` takes `attack(r, x)`; `excluded` is held false; settled goals are read as they
    /// are.
    fn least(&self, attack: impl Fn(u32, u32) -> bool, excluded: Option<u32>) -> Vec<bool> {
        let c = self.component;
        let mut current = vec![false; c.members.len()];
        let mut work: Vec<u32> = (0..c.members.len() as u32)
            .filter(|&i| Some(i) != excluded)
            .collect();
        while let Some(i) = work.pop() {
            if current[i as usize] || Some(i) == excluded {
                continue;
            }
            let mut read = |s: Goal, how: Read| match c.values[s as usize] {
                PENDING => {
                    let p = c.position[s as usize];
                    if how == ATTACK_READ {
                        attack(i, p)
                    } else {
                        current[p as usize]
                    }
                }
                v => v == TRUE,
            };
            if condition(c.engine, c.mu, c.members[i as usize], &mut read) {
                current[i as usize] = true;
                let start = self.readers.partition_point(|&(to, _)| to < i);
                work.extend(
                    self.readers[start..]
                        .iter()
                        .take_while(|&&(to, _)| to == i)
                        .map(|&(_, from)| from),
                );
            }
        }
        current
    }
}

/// Bytes one memo entry may cost: 48 for the key and value as stored, with room for the
/// table's control bytes, its load factor and the doubling when it grows (a cap counted at 48
/// bytes an entry let the process peak at more than twice the cap).
const MEMO_ENTRY_BYTES: usize = 112;

/// Top-down proof inside one component, with the history of cdl.md §4 (a goal met again on the
/// current path fails). Goals outside the component are settled and read from `values`.
struct TopDown<'a> {
    component: &'a Component<'a>,
    /// Members outside the upper bound fail under every history.
    up: &'a [bool],
    in_history: Vec<bool>,
    /// The history as a key: the set itself for components of up to 128 members, else a 128-bit
    /// Zobrist hash of it.
    history: u128,
    zobrist: Vec<u128>,
    memo: FxHashMap<(u32, u128), bool>,
    memo_capacity: usize,
    steps: u64,
    step_limit: u64,
    /// The budget ran out: every answer from here on is meaningless.
    exhausted: bool,
}

impl<'a> TopDown<'a> {
    fn new(component: &'a Component<'a>, up: &'a [bool], limits: &SearchLimits) -> TopDown<'a> {
        let n = component.members.len();
        let zobrist = if n <= 128 {
            (0..n).map(|p| 1u128 << p).collect()
        } else {
            let mut state = 0x243F_6A88_85A3_08D3u64;
            let mut next = move || {
                // splitmix64: fixed seed, so runs are reproducible.
                state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
                let mut z = state;
                z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
                z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
                z ^ (z >> 31)
            };
            (0..n)
                .map(|_| (next() as u128) << 64 | next() as u128)
                .collect()
        };
        TopDown {
            component,
            up,
            in_history: vec![false; n],
            history: 0,
            zobrist,
            memo: FxHashMap::default(),
            memo_capacity: limits.memo_bytes / MEMO_ENTRY_BYTES,
            steps: 0,
            step_limit: limits.steps,
            exhausted: false,
        }
    }

    /// Forgets what was remembered under histories, once a member has been proved from the
    /// empty one. Every history below a member holds that member, so a later member's search
    /// meets an old key only where it visits the same set of goals in another order; a memo
    /// kept small stays in cache, which pays more than those meetings (on the ladder family it
    /// halves the time and cuts the memory tenfold). A memo one hard member grew
    /// large is dropped rather than cleared, which costs its whole capacity at every member.
    fn forget_histories(&mut self) {
        if self.memo.capacity() > 4 * self.memo.len().max(1024) {
            self.memo = FxHashMap::default();
        } else {
            self.memo.clear();
        }
    }

    fn prove(&mut self, g: Goal) -> bool {
        let c = self.component;
        match c.values[g as usize] {
            TRUE => return true,
            PENDING => {}
            _ => return false,
        }
        let p = c.position[g as usize];
        if self.exhausted || self.in_history[p as usize] || !self.up[p as usize] {
            return false;
        }
        // Aggregates stand for many rules at once and are no goals of cdl.md §4: they never
        // enter the history (their own reads are acyclic, so this ends).
        let transparent = c.engine.is_aggregate(g);
        let key = (p, self.history);
        if let Some(&v) = self.memo.get(&key) {
            return v;
        }
        self.steps += 1;
        if self.steps > self.step_limit {
            self.exhausted = true;
            return false;
        }
        if !transparent {
            self.in_history[p as usize] = true;
            self.history ^= self.zobrist[p as usize];
        }
        // The path can be as long as the component: grow the stack on the heap rather than
        // overflow it.
        let v = stacker::maybe_grow(64 * 1024, 4 * 1024 * 1024, || {
            condition(c.engine, c.mu, g, &mut |s, _| self.prove(s))
        });
        if !transparent {
            self.in_history[p as usize] = false;
            self.history ^= self.zobrist[p as usize];
        }
        if !self.exhausted && self.memo.len() < self.memo_capacity {
            self.memo.insert(key, v);
        }
        v
    }
}

#[cfg(test)]
mod tests {
    use super::{readers_by_read_member, Edge};

    /// The counting sort gives what sorting the reversed pairs by comparison gives.
    fn check(members: usize, edges: &[Edge]) {
        let mut expect: Vec<(u32, u32)> = edges.iter().map(|&(r, m, _)| (m, r)).collect();
        expect.sort_unstable();
        expect.dedup();
        assert_eq!(readers_by_read_member(edges, members), expect, "{edges:?}");
    }

    #[test]
    fn readers_come_sorted_and_once() {
        check(1, &[]);
        check(1, &[(0, 0, false)]);
        // A ring, read through support and attack alike, and a member read twice by one reader.
        check(3, &[(0, 1, false), (1, 2, true), (2, 0, false)]);
        check(
            4,
            &[
                (0, 3, false),
                (0, 1, true),
                (0, 3, true),
                (1, 0, false),
                (2, 3, false),
                (3, 0, true),
                (3, 2, false),
            ],
        );
    }
}
