//! Strongly connected components of a graph given by its successor rows (Tarjan's algorithm,
//! iterative so that a chain of a million literals does not overflow the stack).

/// Which nodes start a depth-first search.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Roots {
    /// Every node: each node ends up in exactly one component.
    All,
    /// Only nodes with successors: a node no edge touches is in no component, so a graph of a
    /// few edges among a million nodes costs a few steps.
    WithSuccessors,
}

/// The strongly connected components of the nodes `0..n`, each emitted after every component it
/// reaches: the order in which they can be evaluated. A component's last node is the one the
/// search entered it by.
pub(crate) fn strongly_connected<'g>(
    n: usize,
    successors: impl Fn(usize) -> &'g [u32],
    roots: Roots,
) -> Vec<Vec<u32>> {
    let mut search = Search {
        index: vec![UNSEEN; n],
        low: vec![0; n],
        on_stack: vec![false; n],
        stack: Vec::new(),
        frames: Vec::new(),
        next: 0,
    };
    let mut components = Vec::new();
    for root in 0..n {
        if search.index[root] != UNSEEN
            || (roots == Roots::WithSuccessors && successors(root).is_empty())
        {
            continue;
        }
        search.enter(root as u32);
        while let Some(&mut (v, ref mut cursor)) = search.frames.last_mut() {
            if let Some(&w) = successors(v as usize).get(*cursor) {
                *cursor += 1;
                if search.index[w as usize] == UNSEEN {
                    search.enter(w);
                } else if search.on_stack[w as usize] {
                    search.low[v as usize] = search.low[v as usize].min(search.index[w as usize]);
                }
                continue;
            }
            search.frames.pop();
            if let Some(&(parent, _)) = search.frames.last() {
                search.low[parent as usize] =
                    search.low[parent as usize].min(search.low[v as usize]);
            }
            if search.low[v as usize] == search.index[v as usize] {
                let mut component = Vec::new();
                while let Some(w) = search.stack.pop() {
                    search.on_stack[w as usize] = false;
                    component.push(w);
                    if w == v {
                        break;
                    }
                }
                components.push(component);
            }
        }
    }
    components
}

const UNSEEN: u32 = u32::MAX;

/// Tarjan's bookkeeping: each node's visit number and lowest reachable visit number.
struct Search {
    index: Vec<u32>,
    low: Vec<u32>,
    on_stack: Vec<bool>,
    stack: Vec<u32>,
    /// The depth-first path: each node and how many of its successors have been looked at.
    frames: Vec<(u32, usize)>,
    next: u32,
}

impl Search {
    fn enter(&mut self, v: u32) {
        self.index[v as usize] = self.next;
        self.low[v as usize] = self.next;
        self.next += 1;
        self.stack.push(v);
        self.on_stack[v as usize] = true;
        self.frames.push((v, 0));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rows(n: usize, edges: &[(u32, u32)]) -> Vec<Vec<u32>> {
        let mut rows = vec![Vec::new(); n];
        for &(from, to) in edges {
            rows[from as usize].push(to);
        }
        rows
    }

    fn check(n: usize, edges: &[(u32, u32)], roots: Roots, expect: &[&[u32]]) {
        let rows = rows(n, edges);
        let components: Vec<Vec<u32>> = strongly_connected(n, |v| &rows[v], roots)
            .into_iter()
            .map(|mut c| {
                c.sort();
                c
            })
            .collect();
        let expect: Vec<Vec<u32>> = expect.iter().map(|c| c.to_vec()).collect();
        assert_eq!(components, expect);
    }

    #[test]
    fn components_come_after_the_components_they_reach() {
        // 0 ⇄ 1 reads 2; 2 ⇄ 3; 4 reads itself and 0.
        let edges = [(0, 1), (1, 0), (1, 2), (2, 3), (3, 2), (4, 4), (4, 0)];
        check(5, &edges, Roots::All, &[&[2, 3], &[0, 1], &[4]]);
    }

    #[test]
    fn a_node_no_edge_touches_is_a_component_only_when_every_node_is_a_root() {
        let edges = [(0, 1), (1, 0)];
        check(3, &edges, Roots::All, &[&[0, 1], &[2]]);
        check(3, &edges, Roots::WithSuccessors, &[&[0, 1]]);
    }

    #[test]
    fn a_node_reached_but_without_successors_is_still_a_component() {
        check(2, &[(0, 1)], Roots::WithSuccessors, &[&[1], &[0]]);
    }

    #[test]
    fn a_long_chain_does_not_overflow_the_stack() {
        let n = 1_000_000;
        let edges: Vec<(u32, u32)> = (0..n as u32 - 1).map(|v| (v, v + 1)).collect();
        let rows = rows(n, &edges);
        let components = strongly_connected(n, |v| &rows[v], Roots::WithSuccessors);
        assert_eq!(components.len(), n);
        assert_eq!(components[0], vec![n as u32 - 1]);
    }
}
