//! Dominators of a flow graph (Lengauer and Tarjan's algorithm) and the numbering that
//! makes "is an ancestor in the dominator tree" two comparisons: used where a component's
//! structure is read off which goals every path passes through.

use crate::engine::Csr;

/// The dominator tree of the nodes `root` reaches, by Lengauer and Tarjan's algorithm with
/// path compression (O(m log n); the simpler iteration of Cooper, Harvey and Kennedy is
/// quadratic on long cycles, which the rings of `ring.rs` are). Returns those nodes in
/// depth-first preorder (a dominator comes before what it dominates) and each node's immediate
/// dominator (`u32::MAX` for nodes the root does not reach; the root is its own).
pub(crate) fn dominator_tree(
    successors: &Csr,
    predecessors: &Csr,
    root: u32,
    nodes: usize,
) -> (Vec<u32>, Vec<u32>) {
    let (order, number, parent) = depth_first(successors, root, nodes);
    const NONE: u32 = u32::MAX;
    // Semidominators, by DFS number; a forest linked in reverse preorder, evaluated with path
    // compression (`label` holds the node of least semidominator on the compressed path).
    let mut semi: Vec<u32> = (0..nodes).map(|v| number[v]).collect();
    let mut ancestor = vec![NONE; nodes];
    let mut label: Vec<u32> = (0..nodes as u32).collect();
    let mut idom = vec![NONE; nodes];
    let mut bucket_head = vec![NONE; nodes];
    let mut bucket_next = vec![NONE; nodes];
    let mut path: Vec<u32> = Vec::new();
    let mut eval = |v: u32, ancestor: &mut [u32], label: &mut [u32], semi: &[u32]| -> u32 {
        if ancestor[v as usize] == NONE {
            return v;
        }
        path.clear();
        let mut x = v;
        while ancestor[ancestor[x as usize] as usize] != NONE {
            path.push(x);
            x = ancestor[x as usize];
        }
        while let Some(x) = path.pop() {
            let a = ancestor[x as usize];
            if semi[label[a as usize] as usize] < semi[label[x as usize] as usize] {
                label[x as usize] = label[a as usize];
            }
            ancestor[x as usize] = ancestor[a as usize];
        }
        label[v as usize]
    };
    for &w in order.iter().skip(1).rev() {
        for &v in predecessors.row(w as usize) {
            if number[v as usize] == NONE {
                continue;
            }
            let u = eval(v, &mut ancestor, &mut label, &semi);
            if semi[u as usize] < semi[w as usize] {
                semi[w as usize] = semi[u as usize];
            }
        }
        let s = order[semi[w as usize] as usize];
        bucket_next[w as usize] = bucket_head[s as usize];
        bucket_head[s as usize] = w;
        let p = parent[w as usize];
        ancestor[w as usize] = p;
        let mut v = std::mem::replace(&mut bucket_head[p as usize], NONE);
        while v != NONE {
            let u = eval(v, &mut ancestor, &mut label, &semi);
            idom[v as usize] = if semi[u as usize] < semi[v as usize] {
                u
            } else {
                p
            };
            v = bucket_next[v as usize];
        }
    }
    for &w in order.iter().skip(1) {
        if idom[w as usize] != order[semi[w as usize] as usize] {
            idom[w as usize] = idom[idom[w as usize] as usize];
        }
    }
    idom[root as usize] = root;
    (order, idom)
}

/// The nodes `root` reaches in depth-first preorder, each node's place in it (`u32::MAX` for
/// the others) and its parent in the depth-first tree (iterative: the graphs are long).
fn depth_first(successors: &Csr, root: u32, nodes: usize) -> (Vec<u32>, Vec<u32>, Vec<u32>) {
    const NONE: u32 = u32::MAX;
    let mut number = vec![NONE; nodes];
    let mut parent = vec![NONE; nodes];
    let mut order: Vec<u32> = Vec::new();
    let mut stack: Vec<(u32, u32)> = vec![(root, 0)];
    number[root as usize] = 0;
    order.push(root);
    while let Some(&mut (v, ref mut next)) = stack.last_mut() {
        if let Some(&w) = successors.row(v as usize).get(*next as usize) {
            *next += 1;
            if number[w as usize] == NONE {
                number[w as usize] = order.len() as u32;
                order.push(w);
                parent[w as usize] = v;
                stack.push((w, 0));
            }
        } else {
            stack.pop();
        }
    }
    (order, number, parent)
}

/// Each node's interval in a depth-first numbering of the tree (`u32::MAX` on entry for nodes
/// outside it), so that "`g` is an ancestor of `x`" is two comparisons.
pub(crate) fn intervals(children: &Csr, root: u32, nodes: usize) -> (Vec<u32>, Vec<u32>) {
    let mut enter = vec![u32::MAX; nodes];
    let mut leave = vec![0u32; nodes];
    let mut clock = 0u32;
    let mut stack: Vec<(u32, u32)> = vec![(root, 0)];
    enter[root as usize] = clock;
    while let Some(&mut (v, ref mut next)) = stack.last_mut() {
        if let Some(&w) = children.row(v as usize).get(*next as usize) {
            *next += 1;
            clock += 1;
            enter[w as usize] = clock;
            stack.push((w, 0));
        } else {
            leave[v as usize] = clock;
            stack.pop();
        }
    }
    (enter, leave)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whether `target` is reachable from `root` with `removed` taken out of the graph.
    fn reaches(edges: &[(u32, u32)], root: u32, target: u32, removed: u32, nodes: usize) -> bool {
        let mut seen = vec![false; nodes];
        let mut stack = vec![root];
        seen[root as usize] = true;
        while let Some(v) = stack.pop() {
            if v == target {
                return true;
            }
            for &(a, b) in edges {
                if a == v && b != removed && !std::mem::replace(&mut seen[b as usize], true) {
                    stack.push(b);
                }
            }
        }
        false
    }

    #[test]
    fn immediate_dominators_agree_with_their_definition_on_random_graphs() {
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        let mut next = |bound: u64| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state % bound
        };
        for _ in 0..2000 {
            let nodes = 1 + next(9) as usize;
            let edges: Vec<(u32, u32)> = (0..next(3 * nodes as u64 + 1))
                .map(|_| (next(nodes as u64) as u32, next(nodes as u64) as u32))
                .collect();
            let successors = Csr::build(nodes, edges.iter().copied());
            let predecessors = Csr::build(nodes, edges.iter().map(|&(a, b)| (b, a)));
            let (order, idom) = dominator_tree(&successors, &predecessors, 0, nodes);
            for v in 1..nodes as u32 {
                if !reaches(&edges, 0, v, u32::MAX, nodes) {
                    assert_eq!(idom[v as usize], u32::MAX, "{edges:?}");
                    assert!(!order.contains(&v));
                    continue;
                }
                // The strict dominators of v, and the immediate one: dominated by all others.
                let strict: Vec<u32> = (0..nodes as u32)
                    .filter(|&d| d != v && (d == 0 || !reaches(&edges, 0, v, d, nodes)))
                    .collect();
                let expected = strict
                    .iter()
                    .copied()
                    .find(|&d| {
                        strict
                            .iter()
                            .all(|&e| e == d || e == 0 || !reaches(&edges, 0, d, e, nodes))
                    })
                    .unwrap();
                assert_eq!(idom[v as usize], expected, "{v} in {edges:?}");
            }
        }
    }
}
