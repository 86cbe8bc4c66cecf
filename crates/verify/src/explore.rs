//! Breadth-first exploration of the model's states: every state packed once into a table of
//! fixed-width records (`chunked.rs`), found again by a hash table of state numbers (FxHash of
//! the packed bytes), each with its parent, so the first state found that a property looks for
//! has the shortest path. The environment's choice on each step of that path is found again
//! when the path is asked for, by making the parent's successors once more, rather than stored
//! with every state. Successor lists are kept (4 bytes an edge) for the deadlock check, which
//! needs to know which states can still reach a firing.

use crate::chunked::{Chunked, Records};
use crate::model::Model;
use crate::outcome::Stop;
use crate::property::Property;
use crate::ringlet::{initial_worlds, Choice, StepGenerator, Successor};
use crate::world::{Layout, Status, World};
use hashbrown::HashTable;
use proclaim_behaviour::PropertyKind;
use rustc_hash::FxBuildHasher;
use std::hash::BuildHasher;

/// No parent: an initial state.
const ROOT: u32 = u32::MAX;

/// Every state explored, in breadth-first order.
pub struct Graph {
    layout: Layout,
    /// State i's packed bytes, padded to the widest state's.
    states: Records,
    /// State i's parent in the breadth-first tree, or [`ROOT`].
    parents: Chunked<u32>,
    table: HashTable<u32>,
    /// Successors of state i: `edges[edge_start[i]..edge_start[i + 1]]`; the high bit marks a
    /// step in which a transition fired.
    edge_start: Chunked<u32>,
    edges: Chunked<u32>,
    pub complete: bool,
    /// Why the search ended.
    pub stopped: Stop,
    /// Per machine, per state: ever current.
    pub entered: Vec<Vec<bool>>,
    /// Per machine, per transition (index in the machine's list): ever fired.
    pub fired: Vec<Vec<bool>>,
    /// Per property: the first state it looks for.
    pub targets: Vec<Option<u32>>,
    /// Breadth-first layers reached: the states at the greatest distance from an initial one
    /// are this many steps away.
    pub depth: usize,
    saw: usize,
}

const FIRED: u32 = 1 << 31;

impl Graph {
    pub fn len(&self) -> usize {
        self.parents.len()
    }

    pub fn edge_count(&self) -> usize {
        self.edges.len()
    }

    pub fn world(&self, id: u32) -> World {
        self.layout.unpack(self.bytes_of(id), self.saw)
    }

    /// The bytes a state's record takes.
    pub fn packed_bytes_per_state(&self) -> usize {
        self.states.stride()
    }

    /// Bytes held per state, all structures counted.
    pub fn bytes_per_state(&self) -> f64 {
        self.bytes() as f64 / self.len().max(1) as f64
    }

    /// Bytes the graph's tables hold.
    pub fn bytes(&self) -> usize {
        self.bytes_after(0, 0, 0)
    }

    /// Bytes the tables would hold after `states` more states of at most `width` bytes each
    /// and `edges` more edges (the hash table doubles when it grows).
    fn bytes_after(&self, states: usize, width: usize, edges: usize) -> usize {
        let table = if self.table.len() + states > self.table.capacity() {
            2 * self.table.allocation_size().max(64)
        } else {
            self.table.allocation_size()
        };
        self.states.bytes_after(states, width)
            + self.parents.bytes_after(states)
            + table
            + self.edge_start.bytes_after(1)
            + self.edges.bytes_after(edges)
    }

    /// The path to `id`: the index of its initial world and the choices after it. Each step's
    /// choice is found by making its parent's successors again.
    pub fn path(&self, model: &Model, id: u32) -> (usize, Vec<(u32, Choice)>) {
        let mut states = vec![id];
        while let Some(&at) = states.last() {
            match self.parents.get(at as usize) {
                ROOT => break,
                parent => states.push(parent),
            }
        }
        states.reverse();
        let root = states[0];
        let initial = initial_worlds(model)
            .position(|w| self.stores_as(&w, root))
            .unwrap_or(0);
        let stepper = StepGenerator::new(model);
        let steps = states
            .windows(2)
            .map_while(|pair| Some((pair[0], self.choice_between(&stepper, pair[0], pair[1])?)))
            .collect();
        (initial, steps)
    }

    /// The choice that leads from state `from` to state `to` in one step, if one does.
    pub fn choice_between(&self, stepper: &StepGenerator, from: u32, to: u32) -> Option<Choice> {
        let mut successors = Vec::new();
        stepper.successors(&self.world(from), false, &mut successors);
        successors
            .iter()
            .find(|s| self.stores_as(&s.world, to))
            .map(|s| s.choice)
    }

    /// The first state (so the nearest) from which no transition can ever fire again while a
    /// running machine is not in a final state; only meaningful when the graph is complete.
    pub fn deadlock(&self, model: &Model) -> Option<u32> {
        let n = self.len();
        // Reverse edges, counting-sorted.
        let mut start = vec![0u32; n + 1];
        for e in self.edges.iter() {
            start[(e & !FIRED) as usize + 1] += 1;
        }
        for i in 0..n {
            start[i + 1] += start[i];
        }
        let mut fill = start.clone();
        let mut reverse = vec![0u32; self.edges.len()];
        let mut bounds = self.edge_start.iter();
        let mut from = bounds.next().unwrap_or(0);
        let mut live = vec![false; n];
        let mut work = Vec::new();
        for (s, to) in bounds.enumerate() {
            for e in (from..to).map(|e| self.edges.get(e as usize)) {
                let t = (e & !FIRED) as usize;
                reverse[fill[t] as usize] = s as u32;
                fill[t] += 1;
                if e & FIRED != 0 && !live[s] {
                    live[s] = true;
                    work.push(s);
                }
            }
            from = to;
        }
        while let Some(t) = work.pop() {
            for &s in &reverse[start[t] as usize..start[t + 1] as usize] {
                if !live[s as usize] {
                    live[s as usize] = true;
                    work.push(s as usize);
                }
            }
        }
        (0..n as u32).find(|&id| !live[id as usize] && !waiting(model, &self.world(id)).is_empty())
    }
}

/// The running machines of `world` that are not in a final state (one just entered will
/// finish without firing anything).
pub fn waiting(model: &Model, world: &World) -> Vec<usize> {
    world
        .machines
        .iter()
        .enumerate()
        .filter(|(k, c)| {
            c.status == Status::Running
                && !model.machines[*k].states[usize::from(c.state)].is_final()
        })
        .map(|(k, _)| k)
        .collect()
}

/// How often a long search says how far it got.
pub const PROGRESS_EVERY: usize = 1 << 16;

/// How far a search got: states whose successors were made, and states found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Progress {
    pub expanded: usize,
    pub stored: usize,
}

/// Where a search stops before it has seen every reachable state.
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    pub max_states: usize,
    /// Bytes the graph's tables may hold.
    pub max_memory: usize,
    /// Stop once every property has found what it looks for.
    pub stop_when_decided: bool,
}

/// Explores from the initial states until every reachable state is seen or a limit stops it;
/// checks `properties` on every state as it is found.
/// `progress` hears how far it got every [`PROGRESS_EVERY`] states expanded.
pub fn explore(
    model: &Model,
    properties: &[Property],
    limits: Limits,
    progress: &mut dyn FnMut(Progress),
) -> Graph {
    let mut graph = Graph::empty(model, properties.len());
    let mut store = Store::default();
    let decidable = limits.stop_when_decided
        && !properties.is_empty()
        && properties.iter().all(|p| {
            matches!(
                p.source.kind,
                PropertyKind::Never | PropertyKind::Always | PropertyKind::Reachable
            )
        });
    let stop = |graph: &mut Graph, reason: Stop| {
        graph.complete = false;
        graph.stopped = reason;
    };
    for w in initial_worlds(model) {
        if graph.is_full(limits.max_states) {
            stop(&mut graph, Stop::StateBudget);
            return graph;
        }
        if graph.bytes_after(1, 64, 0) > limits.max_memory {
            stop(&mut graph, Stop::MemoryBudget);
            return graph;
        }
        store.insert(&mut graph, &w, ROOT, model, properties);
    }
    let stepper = StepGenerator::new(model);
    let mut successors: Vec<Successor> = Vec::new();
    let mut next = 0usize;
    // States from here on are one step further from the initial ones than those before.
    let mut layer_end = graph.len();
    while next < graph.len() {
        if next == layer_end {
            graph.depth += 1;
            layer_end = graph.len();
        }
        if decidable && graph.targets.iter().all(Option::is_some) {
            stop(&mut graph, Stop::Decided);
            break;
        }
        if graph.is_full(limits.max_states) {
            stop(&mut graph, Stop::StateBudget);
            break;
        }
        if next % PROGRESS_EVERY == 0 && next > 0 {
            progress(Progress {
                expanded: next,
                stored: graph.len(),
            });
        }
        let world = graph.world(next as u32);
        successors.clear();
        stepper.successors(&world, false, &mut successors);
        // What the tables would grow to must stay within the memory budget: as if every successor were new and a little wider than the state it came from.
        let width = graph.states.stride() + 8;
        if graph.bytes_after(successors.len(), width, successors.len()) > limits.max_memory {
            stop(&mut graph, Stop::MemoryBudget);
            break;
        }
        for s in &successors {
            let mut edge = store.insert(&mut graph, &s.world, next as u32, model, properties);
            if let Some(t) = s.fired {
                edge |= FIRED;
                let index = model.machines[s.machine].states[s.from].transitions[t].index;
                graph.fired[s.machine][index] = true;
            }
            graph.edges.push(edge);
        }
        graph.edge_start.push(graph.edges.len() as u32);
        next += 1;
    }
    graph
}

impl Graph {
    /// No states yet, and nothing entered, fired or found.
    fn empty(model: &Model, properties: usize) -> Graph {
        Graph {
            layout: Layout::new(model),
            states: Records::default(),
            parents: Chunked::default(),
            table: HashTable::new(),
            edge_start: {
                let mut start = Chunked::default();
                start.push(0);
                start
            },
            edges: Chunked::default(),
            complete: true,
            stopped: Stop::Explored,
            entered: model.per_state(),
            fired: model.per_transition(),
            targets: vec![None; properties],
            depth: 0,
            saw: model.saw.len(),
        }
    }

    /// Whether another state would pass `max_states`, or what the ids can hold (ids leave the
    /// top bit to the "fired" mark).
    fn is_full(&self, max_states: usize) -> bool {
        self.len() >= max_states
            || self.len() >= (FIRED - 1) as usize
            || self.edges.len() >= (u32::MAX as usize - (1 << 20))
    }

    /// State `id`'s record (padded with zero bytes to the stride).
    fn bytes_of(&self, id: u32) -> &[u8] {
        self.states.get(id as usize)
    }
}

/// What storing a state needs besides the graph: its packing buffer and the hasher.
#[derive(Default)]
struct Store {
    scratch: Vec<u8>,
    hasher: FxBuildHasher,
}

impl Store {
    /// The id of `world`, stored with `parent` if it is new; a new state is checked against
    /// the properties and marks the states it is in as entered.
    fn insert(
        &mut self,
        graph: &mut Graph,
        world: &World,
        parent: u32,
        model: &Model,
        properties: &[Property],
    ) -> u32 {
        self.scratch.clear();
        graph.layout.pack(world, &mut self.scratch);
        let hash = self.hasher.hash_one(unpadded(&self.scratch));
        if let Some(&id) = graph.table.find(hash, |&id| {
            unpadded(graph.bytes_of(id)) == unpadded(&self.scratch)
        }) {
            return id;
        }
        let id = graph.parents.len() as u32;
        graph.states.push(&self.scratch);
        graph.parents.push(parent);
        let (states, hasher) = (&graph.states, &self.hasher);
        graph.table.insert_unique(hash, id, |&id| {
            hasher.hash_one(unpadded(states.get(id as usize)))
        });
        for (k, c) in world.machines.iter().enumerate() {
            if c.status != Status::Dormant {
                graph.entered[k][usize::from(c.state)] = true;
            }
        }
        for (p, property) in properties.iter().enumerate() {
            if graph.targets[p].is_none() && property.is_target(model, world) {
                graph.targets[p] = Some(id);
            }
        }
        id
    }
}

/// Read-only views of the explored graph for the checks made after exploration
/// ([`crate::liveness`], [`crate::components`], [`crate::lasso`]): which states were expanded,
/// their successors, and how a step is recognised when it is replayed.
impl Graph {
    /// How many states had all their successors made: states `0..expanded()` (breadth-first
    /// order); the others were stored but the budget ran out before their turn.
    pub fn expanded(&self) -> usize {
        self.edge_start.len() - 1
    }

    /// Whether state `id` is one of the initial states.
    pub fn is_initial(&self, id: u32) -> bool {
        self.parents.get(id as usize) == ROOT
    }

    /// Where state `id`'s successors are in the edge list (`id` expanded; empty when no
    /// machine can ring there).
    pub fn edge_range(&self, id: u32) -> std::ops::Range<usize> {
        let i = id as usize;
        self.edge_start.get(i) as usize..self.edge_start.get(i + 1) as usize
    }

    /// The state edge `e` leads to.
    pub fn edge_target(&self, e: usize) -> u32 {
        self.edges.get(e) & !FIRED
    }

    /// The successors of an expanded state `id`, as state ids (a state may repeat).
    pub fn successors_of(&self, id: u32) -> impl Iterator<Item = u32> + '_ {
        self.edge_range(id).map(|e| self.edge_target(e))
    }

    /// Whether `world` is stored as state `id` (a successor made again, when a step of a
    /// lasso is replayed, is recognised by its packed bytes).
    pub fn stores_as(&self, world: &World, id: u32) -> bool {
        let mut bytes = Vec::new();
        self.layout.pack(world, &mut bytes);
        unpadded(self.bytes_of(id)) == unpadded(&bytes)
    }
}

/// A packed state without the zero bytes that pad it to its record's width. Two states' packed
/// forms never differ by trailing zeros alone (the layout says how many fields a state has and
/// each field's width follows from its first bytes), so this is what hashes and compares.
fn unpadded(bytes: &[u8]) -> &[u8] {
    let end = bytes.iter().rposition(|&b| b != 0).map_or(0, |i| i + 1);
    &bytes[..end]
}
