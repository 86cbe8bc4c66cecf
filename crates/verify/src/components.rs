//! Strongly connected components of a part of the explored graph (Tarjan's algorithm, with an
//! explicit stack: graphs have millions of states and a recursive search would overflow the
//! thread's stack). Each component is handed over as it completes, so a search can stop at the
//! first one it looks for.

use crate::explore::Graph;

const UNSEEN: u32 = u32::MAX;

/// A search of the states for which `inside` is true (and the edges between them).
pub struct Components<'g> {
    graph: &'g Graph,
    inside: &'g [bool],
    index: Vec<u32>,
    low: Vec<u32>,
    on_stack: Vec<bool>,
    stack: Vec<u32>,
    next_index: u32,
    components: u32,
}

/// A state being searched and the next of its edges to follow.
struct Frame {
    state: u32,
    edge: usize,
    end: usize,
}

impl<'g> Components<'g> {
    /// `inside` has one entry per stored state; only expanded states may be inside.
    pub fn new(graph: &'g Graph, inside: &'g [bool]) -> Components<'g> {
        let n = graph.len();
        Components {
            graph,
            inside,
            index: vec![UNSEEN; n],
            low: vec![0; n],
            on_stack: vec![false; n],
            stack: Vec::new(),
            next_index: 0,
            components: 0,
        }
    }

    /// Searches from `root` (nothing when it was already reached), handing each completed
    /// component's states to `found`; stops and returns the component's number as soon as
    /// `found` says yes (the search is then over: call no more). Components reachable from an
    /// earlier root are not handed over again.
    pub fn search_from(&mut self, root: u32, found: &mut dyn FnMut(&[u32]) -> bool) -> Option<u32> {
        if self.index[root as usize] != UNSEEN || !self.inside[root as usize] {
            return None;
        }
        let mut frames = vec![self.enter(root)];
        let mut members = Vec::new();
        while let Some(frame) = frames.last_mut() {
            let v = frame.state;
            if frame.edge < frame.end {
                let w = self.graph.edge_target(frame.edge);
                frame.edge += 1;
                if !self.inside[w as usize] {
                    continue;
                }
                if self.index[w as usize] == UNSEEN {
                    let next = self.enter(w);
                    frames.push(next);
                } else if self.on_stack[w as usize] {
                    self.low[v as usize] = self.low[v as usize].min(self.index[w as usize]);
                }
                continue;
            }
            frames.pop();
            if let Some(parent) = frames.last() {
                let p = parent.state as usize;
                self.low[p] = self.low[p].min(self.low[v as usize]);
            }
            if self.low[v as usize] == self.index[v as usize] {
                members.clear();
                loop {
                    let w = self.stack.pop().unwrap_or(v);
                    self.on_stack[w as usize] = false;
                    members.push(w);
                    if w == v {
                        break;
                    }
                }
                let number = self.components;
                self.components += 1;
                if found(&members) {
                    return Some(number);
                }
            }
        }
        None
    }

    fn enter(&mut self, state: u32) -> Frame {
        let i = state as usize;
        self.index[i] = self.next_index;
        self.low[i] = self.next_index;
        self.next_index += 1;
        self.stack.push(state);
        self.on_stack[i] = true;
        let edges = self.graph.edge_range(state);
        Frame {
            state,
            edge: edges.start,
            end: edges.end,
        }
    }
}
