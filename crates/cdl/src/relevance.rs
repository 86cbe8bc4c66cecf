//! Reads that cannot change a goal's value, dropped so that a component falls apart into
//! smaller ones. A goal's value under a history is a boolean function of what it reads under
//! the longer history; when that function ignores a read (a superior's team beats the attacker
//! the read would make applicable, say), the read is no dependency at all, and cdl.md §4's
//! component-by-component evaluation is exact on the graph without it. The priority ring of
//! `benchmarks.md` is one cycle of support with every attacker beaten or read only from outside
//! the cycle once such reads are gone.

use crate::cycle::{Component, Edge};
use crate::engine::Csr;

/// Members reading more members than this keep every read: the test tries every assignment.
const MOST_READS: usize = 4;

/// The component's parts once reads its members' conditions ignore are dropped, in the order
/// they can be evaluated (each reads only itself and earlier parts), as positions; `None` when
/// it stays one part.
pub(crate) fn independent_parts(component: &Component, edges: &[Edge]) -> Option<Vec<Vec<u32>>> {
    let n = component.members.len();
    // Components with aggregates (stand-ins for the implication graph's unwritten rules) stay
    // whole: on clause chains a truth table per member cost time and dropped nothing useful.
    if component.has_aggregate() {
        return None;
    }
    let mut kept: Vec<(u32, u32)> = Vec::with_capacity(edges.len());
    let mut dropped = false;
    let mut reads: Vec<u32> = Vec::new();
    let mut start = 0;
    while start < edges.len() {
        let reader = edges[start].0;
        let end = start + edges[start..].partition_point(|&(r, _, _)| r == reader);
        reads.clear();
        reads.extend(edges[start..end].iter().map(|&(_, to, _)| to));
        reads.dedup();
        start = end;
        if reads.len() > MOST_READS {
            kept.extend(reads.iter().map(|&to| (reader, to)));
            continue;
        }
        let relevant = relevant_reads(component, reader, &reads);
        for (bit, &to) in reads.iter().enumerate() {
            if relevant & 1 << bit != 0 {
                kept.push((reader, to));
            } else {
                dropped = true;
            }
        }
    }
    if !dropped {
        return None;
    }
    let parts = strongly_connected(&Csr::build(n, kept.iter().copied()), n);
    (parts.len() > 1).then_some(parts)
}

/// Which of `reads` (as bits) the reader's condition depends on, from its truth table over them.
fn relevant_reads(component: &Component, reader: u32, reads: &[u32]) -> u32 {
    let table: Vec<bool> = (0..1u32 << reads.len())
        .map(|assignment| {
            component.condition_with(reader, |x| {
                reads
                    .iter()
                    .position(|&r| r == x)
                    .is_some_and(|bit| assignment & 1 << bit != 0)
            })
        })
        .collect();
    let mut relevant = 0;
    for bit in 0..reads.len() {
        let flip = 1 << bit;
        if (0..table.len()).any(|a| a & flip == 0 && table[a] != table[a | flip]) {
            relevant |= flip as u32;
        }
    }
    relevant
}

/// Tarjan's strongly connected components (iterative), each emitted after every component it
/// reaches: the order in which they can be evaluated.
fn strongly_connected(successors: &Csr, n: usize) -> Vec<Vec<u32>> {
    const UNSEEN: u32 = u32::MAX;
    let mut index = vec![UNSEEN; n];
    let mut low = vec![0u32; n];
    let mut on_stack = vec![false; n];
    let mut stack: Vec<u32> = Vec::new();
    let mut parts = Vec::new();
    let mut next = 0u32;
    let mut frames: Vec<(u32, usize)> = Vec::new();
    for root in 0..n as u32 {
        if index[root as usize] != UNSEEN {
            continue;
        }
        frames.push((root, 0));
        index[root as usize] = next;
        low[root as usize] = next;
        next += 1;
        stack.push(root);
        on_stack[root as usize] = true;
        while let Some(&mut (v, ref mut cursor)) = frames.last_mut() {
            if let Some(&w) = successors.row(v as usize).get(*cursor) {
                *cursor += 1;
                if index[w as usize] == UNSEEN {
                    index[w as usize] = next;
                    low[w as usize] = next;
                    next += 1;
                    stack.push(w);
                    on_stack[w as usize] = true;
                    frames.push((w, 0));
                } else if on_stack[w as usize] {
                    low[v as usize] = low[v as usize].min(index[w as usize]);
                }
                continue;
            }
            frames.pop();
            if let Some(&(parent, _)) = frames.last() {
                low[parent as usize] = low[parent as usize].min(low[v as usize]);
            }
            if low[v as usize] == index[v as usize] {
                let mut part = Vec::new();
                while let Some(w) = stack.pop() {
                    on_stack[w as usize] = false;
                    part.push(w);
                    if w == v {
                        break;
                    }
                }
                parts.push(part);
            }
        }
    }
    parts
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parts_come_after_the_parts_they_read() {
        // 0 ⇄ 1 reads 2; 2 ⇄ 3; 4 reads itself and 0.
        let edges = [(0, 1), (1, 0), (1, 2), (2, 3), (3, 2), (4, 4), (4, 0)];
        let parts = strongly_connected(&Csr::build(5, edges.iter().copied()), 5);
        let sorted: Vec<Vec<u32>> = parts
            .iter()
            .map(|p| {
                let mut p = p.clone();
                p.sort();
                p
            })
            .collect();
        assert_eq!(sorted, vec![vec![2, 3], vec![0, 1], vec![4]]);
    }
}
