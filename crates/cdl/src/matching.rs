//! Maximum matchings in general graphs (Edmonds' blossom search) and the vertices some maximum
//! matching leaves uncovered, which decide undirected vertex geography (Fraenkel, Scheinerman and
//! Ullman 1993): the player to move from `v` wins iff every maximum matching covers `v`.

const NONE: u32 = u32::MAX;

/// For each vertex of the undirected graph `adjacency` (symmetric lists), whether some maximum
/// matching leaves it uncovered (the set `D` of the Gallai–Edmonds decomposition).
pub(crate) fn uncovered_by_some_maximum_matching(adjacency: &[Vec<u32>]) -> Vec<bool> {
    let mut search = Search::new(adjacency);
    search.greedy();
    for root in 0..adjacency.len() as u32 {
        if search.mate[root as usize] == NONE {
            if let Some(end) = search.alternating_tree(root) {
                search.augment(end);
            }
        }
    }
    // With the matching maximum, `D` is every vertex an even alternating path reaches from an
    // uncovered vertex: the outer vertices of the alternating trees grown from them.
    let mut uncovered = vec![false; adjacency.len()];
    for root in 0..adjacency.len() as u32 {
        if search.mate[root as usize] == NONE {
            let end = search.alternating_tree(root);
            debug_assert!(end.is_none(), "the matching is maximum");
            for (v, &outer) in search.outer.iter().enumerate() {
                uncovered[v] |= outer;
            }
        }
    }
    uncovered
}

struct Search<'a> {
    adjacency: &'a [Vec<u32>],
    mate: Vec<u32>,
    /// The tree parent of an inner vertex.
    parent: Vec<u32>,
    /// The base of the blossom each vertex lies in.
    base: Vec<u32>,
    outer: Vec<bool>,
    in_blossom: Vec<bool>,
    on_path: Vec<bool>,
    queue: Vec<u32>,
}

impl<'a> Search<'a> {
    fn new(adjacency: &'a [Vec<u32>]) -> Search<'a> {
        let n = adjacency.len();
        Search {
            adjacency,
            mate: vec![NONE; n],
            parent: vec![NONE; n],
            base: (0..n as u32).collect(),
            outer: vec![false; n],
            in_blossom: vec![false; n],
            on_path: vec![false; n],
            queue: Vec::new(),
        }
    }

    /// A maximal matching to start from: fewer augmenting searches.
    fn greedy(&mut self) {
        for v in 0..self.adjacency.len() {
            if self.mate[v] != NONE {
                continue;
            }
            if let Some(&u) = self.adjacency[v]
                .iter()
                .find(|&&u| u as usize != v && self.mate[u as usize] == NONE)
            {
                self.mate[v] = u;
                self.mate[u as usize] = v as u32;
            }
        }
    }

    /// Grows the alternating tree from the uncovered `root`, contracting blossoms; returns the
    /// uncovered end of an augmenting path when there is one.
    fn alternating_tree(&mut self, root: u32) -> Option<u32> {
        let n = self.adjacency.len();
        self.parent.iter_mut().for_each(|p| *p = NONE);
        self.outer.iter_mut().for_each(|o| *o = false);
        for (i, b) in self.base.iter_mut().enumerate() {
            *b = i as u32;
        }
        self.queue.clear();
        self.outer[root as usize] = true;
        self.queue.push(root);
        let mut head = 0;
        while head < self.queue.len() {
            let v = self.queue[head];
            head += 1;
            for &to in &self.adjacency[v as usize] {
                if self.base[v as usize] == self.base[to as usize] || self.mate[v as usize] == to {
                    continue;
                }
                let to_is_outer = to == root
                    || (self.mate[to as usize] != NONE
                        && self.parent[self.mate[to as usize] as usize] != NONE);
                if to_is_outer {
                    let base = self.common_base(v, to);
                    self.in_blossom.iter_mut().for_each(|b| *b = false);
                    self.mark_path(v, base, to);
                    self.mark_path(to, base, v);
                    for i in 0..n {
                        if self.in_blossom[self.base[i] as usize] {
                            self.base[i] = base;
                            if !self.outer[i] {
                                self.outer[i] = true;
                                self.queue.push(i as u32);
                            }
                        }
                    }
                } else if self.parent[to as usize] == NONE {
                    self.parent[to as usize] = v;
                    let next = self.mate[to as usize];
                    if next == NONE {
                        return Some(to);
                    }
                    self.outer[next as usize] = true;
                    self.queue.push(next);
                }
            }
        }
        None
    }

    /// The base of the smallest blossom holding the outer vertices `a` and `b`.
    fn common_base(&mut self, mut a: u32, mut b: u32) -> u32 {
        self.on_path.iter_mut().for_each(|p| *p = false);
        loop {
            a = self.base[a as usize];
            self.on_path[a as usize] = true;
            if self.mate[a as usize] == NONE {
                break;
            }
            a = self.parent[self.mate[a as usize] as usize];
        }
        loop {
            b = self.base[b as usize];
            if self.on_path[b as usize] {
                return b;
            }
            b = self.parent[self.mate[b as usize] as usize];
        }
    }

    fn mark_path(&mut self, mut v: u32, base: u32, mut child: u32) {
        while self.base[v as usize] != base {
            let m = self.mate[v as usize];
            self.in_blossom[self.base[v as usize] as usize] = true;
            self.in_blossom[self.base[m as usize] as usize] = true;
            self.parent[v as usize] = child;
            child = m;
            v = self.parent[m as usize];
        }
    }

    fn augment(&mut self, mut v: u32) {
        while v != NONE {
            let p = self.parent[v as usize];
            let next = self.mate[p as usize];
            self.mate[v as usize] = p;
            self.mate[p as usize] = v;
            v = next;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::uncovered_by_some_maximum_matching;

    fn graph(n: usize, edges: &[(u32, u32)]) -> Vec<Vec<u32>> {
        let mut adjacency = vec![Vec::new(); n];
        for &(a, b) in edges {
            adjacency[a as usize].push(b);
            adjacency[b as usize].push(a);
        }
        adjacency
    }

    /// The definition, by brute force: every matching of largest size, and who it leaves out.
    fn brute_force(n: usize, edges: &[(u32, u32)]) -> Vec<bool> {
        let mut best = 0;
        let mut uncovered = vec![false; n];
        for subset in 0u32..1 << edges.len() {
            let mut covered = vec![false; n];
            let mut ok = true;
            let mut size = 0;
            for (i, &(a, b)) in edges.iter().enumerate() {
                if subset & 1 << i != 0 {
                    if covered[a as usize] || covered[b as usize] {
                        ok = false;
                        break;
                    }
                    covered[a as usize] = true;
                    covered[b as usize] = true;
                    size += 1;
                }
            }
            if !ok {
                continue;
            }
            if size > best {
                best = size;
                uncovered = vec![false; n];
            }
            if size == best {
                for v in 0..n {
                    uncovered[v] |= !covered[v];
                }
            }
        }
        uncovered
    }

    #[test]
    fn agrees_with_brute_force_on_small_graphs() {
        // Every graph on up to 6 vertices whose edges a small generator picks, blossoms included.
        let mut state: u64 = 0x9E3779B97F4A7C15;
        for _ in 0..3000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let n = 1 + (state % 7) as usize;
            let mut edges = Vec::new();
            for a in 0..n as u32 {
                for b in a + 1..n as u32 {
                    state ^= state << 13;
                    state ^= state >> 7;
                    state ^= state << 17;
                    if state % 3 == 0 && edges.len() < 14 {
                        edges.push((a, b));
                    }
                }
            }
            assert_eq!(
                uncovered_by_some_maximum_matching(&graph(n, &edges)),
                brute_force(n, &edges),
                "{n} vertices, edges {edges:?}"
            );
        }
    }

    #[test]
    fn odd_cliques_leave_anyone_out_and_even_ones_nobody() {
        for n in 1..9u32 {
            let edges: Vec<(u32, u32)> = (0..n)
                .flat_map(|a| (a + 1..n).map(move |b| (a, b)))
                .collect();
            let d = uncovered_by_some_maximum_matching(&graph(n as usize, &edges));
            assert!(d.iter().all(|&x| x == (n % 2 == 1)), "clique of {n}");
        }
    }
}
