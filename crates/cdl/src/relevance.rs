//! Reads that cannot change a goal's value, dropped so that a component falls apart into
//! smaller ones. A goal's value under a history is a boolean function of what it reads under
//! the longer history; when that function ignores a read (a superior's team beats the attacker
//! the read would make applicable, say), the read is no dependency at all, and cdl.md §4's
//! component-by-component evaluation is exact on the graph without it. The priority ring of
//! `benchmarks.md` is one cycle of support with every attacker beaten or read only from outside
//! the cycle once such reads are gone.

use crate::component::{Component, Edge};
use crate::engine::Csr;
use crate::scc::{strongly_connected, Roots};

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
    let reads = Csr::build(n, kept.iter().copied());
    let parts = strongly_connected(n, |v| reads.row(v), Roots::All);
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
