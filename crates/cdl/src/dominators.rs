//! Dominators of a flow graph (Cooper, Harvey and Kennedy's iteration) and the numbering that
//! makes "is an ancestor in the dominator tree" two comparisons: used where a component's
//! structure is read off which goals every path passes through.

use crate::engine::Csr;

/// The nodes `root` reaches, in reverse postorder of a depth-first walk (iterative).
pub(crate) fn reverse_postorder(successors: &Csr, root: u32, nodes: usize) -> Vec<u32> {
    let mut order = Vec::new();
    let mut seen = vec![false; nodes];
    let mut stack: Vec<(u32, u32)> = vec![(root, 0)];
    seen[root as usize] = true;
    while let Some(&mut (v, ref mut next)) = stack.last_mut() {
        if let Some(&w) = successors.row(v as usize).get(*next as usize) {
            *next += 1;
            if !std::mem::replace(&mut seen[w as usize], true) {
                stack.push((w, 0));
            }
        } else {
            order.push(v);
            stack.pop();
        }
    }
    order.reverse();
    order
}

/// Cooper, Harvey and Kennedy's iteration: each node's immediate dominator, by intersecting its
/// predecessors' dominator chains in reverse postorder until nothing changes (`u32::MAX` for
/// nodes the root does not reach).
pub(crate) fn immediate_dominators(predecessors: &Csr, order: &[u32], nodes: usize) -> Vec<u32> {
    const UNDEFINED: u32 = u32::MAX;
    let mut rank = vec![u32::MAX; nodes];
    for (i, &v) in order.iter().enumerate() {
        rank[v as usize] = i as u32;
    }
    let mut idom = vec![UNDEFINED; nodes];
    idom[order[0] as usize] = order[0];
    let mut changed = true;
    while changed {
        changed = false;
        for &v in order.iter().skip(1) {
            let mut new = UNDEFINED;
            for &p in predecessors.row(v as usize) {
                if idom[p as usize] == UNDEFINED {
                    continue;
                }
                new = if new == UNDEFINED {
                    p
                } else {
                    let (mut a, mut b) = (p, new);
                    while a != b {
                        while rank[a as usize] > rank[b as usize] {
                            a = idom[a as usize];
                        }
                        while rank[b as usize] > rank[a as usize] {
                            b = idom[b as usize];
                        }
                    }
                    a
                };
            }
            if new != idom[v as usize] {
                idom[v as usize] = new;
                changed = true;
            }
        }
    }
    idom
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
