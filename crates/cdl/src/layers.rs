//! A component that is a ring of layers of at most two goals, each goal reading only goals of
//! the next layer (the ladder of `benchmarks.md`): decided by a dynamic program over the layers
//! instead of a search of every path, whose count doubles with each layer.
//!
//! Why it is exact (cdl.md §4: a goal met again on the current path fails). A path from `x` in
//! layer 0 takes one goal a layer on its first lap, `c0 = x, c1, …, c(L-1)`. Back at layer 0
//! it can go on only through `x`'s twin (`x` is on the history), and from there only through
//! each layer's other goal `c'j`, the one off the history, until layer 0, where both are on it.
//! So the second lap is a chain the first lap fixes: the twin's value is
//! `g0 ∘ g1 ∘ … ∘ g(L-2)` applied to the last goal's, where `gj` (the goal `c'j` as a function
//! of `c'(j+1)`, with `c(j+1)` on the history) depends only on `cj` and `c(j+1)`. A first-lap
//! goal's value therefore depends on the path before it only through which goal it is and the
//! composition so far, one of four functions of a boolean: eight states a layer, whatever the
//! length of the path.

use crate::component::{Component, Edge};
use crate::ring::{apply, compose, Function, IDENTITY};

/// Components are decided this way while (members × layers) stays under this: every member is
/// a start of its own pass over the layers.
const WORK_LIMIT: usize = 20_000_000;

/// The layers in ring order: each member reads only members of the next layer.
pub(crate) struct Layers {
    /// Each layer's members (one or two), by position in the component.
    layers: Vec<Vec<u32>>,
    /// Each member's layer and its place in it (0 or 1).
    layer_of: Vec<u32>,
    slot_of: Vec<u8>,
}

/// The four functions of a boolean, as an index into a row of states.
fn index(f: Function) -> usize {
    usize::from(f.0) | usize::from(f.1) << 1
}

const FUNCTIONS: [Function; 4] = [(false, false), (true, false), (false, true), (true, true)];

impl Layers {
    /// The layers the component's reads form, if every read goes from one layer to the next
    /// round a ring of at least two layers, none of more than two members, and some of two
    /// (a ring of single goals is a simple cycle, decided before).
    pub(crate) fn find(component: &Component, edges: &[Edge]) -> Option<Layers> {
        let n = component.members.len();
        if n < 3 || component.has_aggregate() {
            return None;
        }
        let depth = depths(n, edges)?;
        // The number of layers: every read must step one layer on, modulo it.
        let period = edges.iter().fold(0u64, |g, &(from, to, _)| {
            gcd(
                g,
                (depth[from as usize] + 1 - depth[to as usize]).unsigned_abs(),
            )
        });
        if period < 2 || period as usize > n {
            return None;
        }
        let mut layers = vec![Vec::new(); period as usize];
        let mut layer_of = vec![0; n];
        let mut slot_of = vec![0; n];
        for (m, &d) in depth.iter().enumerate() {
            let layer = d.rem_euclid(period as i64) as usize;
            if layers[layer].len() == 2 {
                return None;
            }
            layer_of[m] = layer as u32;
            slot_of[m] = layers[layer].len() as u8;
            layers[layer].push(m as u32);
        }
        if layers.iter().any(Vec::is_empty)
            || layers.iter().all(|l| l.len() < 2)
            || n.saturating_mul(layers.len()) > WORK_LIMIT
        {
            return None;
        }
        Some(Layers {
            layers,
            layer_of,
            slot_of,
        })
    }

    /// Every member's value from the empty history.
    pub(crate) fn decide(&self, component: &Component) -> Vec<bool> {
        let tables = self.tables(component);
        let count = self.layers.len();
        // On the second lap: the twin of place `c` in layer `l` as a function of the twin of
        // place `a` in the next layer (`a` itself on the history); and that twin's value when
        // both goals of the next layer are on the history (the lap's last goal).
        let twin_step: Vec<[[Function; 2]; 2]> = (0..count)
            .map(|l| {
                let mut step = [[(false, false); 2]; 2];
                for (c, row) in step.iter_mut().enumerate() {
                    for (a, f) in row.iter_mut().enumerate() {
                        if let Some(twin) = self.twin(l, c) {
                            let with = |v: bool| tables[twin as usize][bits(a, v)];
                            *f = (with(false), with(true));
                        }
                    }
                }
                step
            })
            .collect();
        let last_twin: Vec<[bool; 2]> = (0..count)
            .map(|l| [0, 1].map(|c| self.twin(l, c).is_some_and(|t| tables[t as usize][0])))
            .collect();
        (0..self.layer_of.len())
            .map(|x| self.from(x, &tables, &twin_step, &last_twin))
            .collect()
    }

    /// Member `x`'s value, by the states of its pass round the ring, from the last layer back.
    fn from(
        &self,
        x: usize,
        tables: &[[bool; 4]],
        twin_step: &[[[Function; 2]; 2]],
        last_twin: &[[bool; 2]],
    ) -> bool {
        let count = self.layers.len();
        let start = self.layer_of[x] as usize;
        let home = usize::from(self.slot_of[x]);
        let layer = |j: usize| (start + j) % count;
        // `next[a][f]`: the value of place `a` of the layer after, reached with the second
        // lap's composition so far `f`.
        let mut next = [[false; 4]; 2];
        let last = layer(count - 1);
        for (c, &m) in self.layers[last].iter().enumerate() {
            for f in FUNCTIONS {
                // Layer 0 again: `x` is on the history; its twin is the second lap.
                let twin = apply(f, last_twin[last][c]);
                next[c][index(f)] = tables[m as usize][bits(home, twin)];
            }
        }
        for j in (1..count - 1).rev() {
            let l = layer(j);
            let mut here = [[false; 4]; 2];
            for (c, &m) in self.layers[l].iter().enumerate() {
                for f in FUNCTIONS {
                    let read = |a: usize| next[a][index(compose(f, twin_step[l][c][a]))];
                    here[c][index(f)] =
                        tables[m as usize][usize::from(read(0)) | usize::from(read(1)) << 1];
                }
            }
            next = here;
        }
        // `x` itself, with nothing composed yet.
        let read = |a: usize| next[a][index(compose(IDENTITY, twin_step[start][home][a]))];
        tables[x][usize::from(read(0)) | usize::from(read(1)) << 1]
    }

    /// The member beside place `c` in layer `l`, if the layer has two.
    fn twin(&self, l: usize, c: usize) -> Option<u32> {
        self.layers[l].get(1 - c).copied()
    }

    /// Each member's condition as a table over the next layer's two places (bit 0 the first,
    /// bit 1 the second; an absent place reads false).
    fn tables(&self, component: &Component) -> Vec<[bool; 4]> {
        (0..self.layer_of.len())
            .map(|m| {
                let next = &self.layers[(self.layer_of[m] as usize + 1) % self.layers.len()];
                [0usize, 1, 2, 3].map(|b| {
                    component.condition_with(m as u32, |p| {
                        next.iter()
                            .position(|&q| q == p)
                            .is_some_and(|slot| b >> slot & 1 == 1)
                    })
                })
            })
            .collect()
    }
}

/// The table index with place `false_place` read false and the other place read `v`.
fn bits(false_place: usize, v: bool) -> usize {
    usize::from(v) << (1 - false_place)
}

/// Each member's distance from member 0 along reads (backwards through a read counts minus
/// one), if every member is reached.
fn depths(n: usize, edges: &[Edge]) -> Option<Vec<i64>> {
    let mut around: Vec<Vec<(u32, i64)>> = vec![Vec::new(); n];
    for &(from, to, _) in edges {
        around[from as usize].push((to, 1));
        around[to as usize].push((from, -1));
    }
    let mut depth = vec![None; n];
    depth[0] = Some(0i64);
    let mut stack = vec![0u32];
    while let Some(u) = stack.pop() {
        let d = depth[u as usize]?;
        for &(v, step) in &around[u as usize] {
            if depth[v as usize].is_none() {
                depth[v as usize] = Some(d + step);
                stack.push(v);
            }
        }
    }
    depth.into_iter().collect()
}

fn gcd(a: u64, b: u64) -> u64 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}
