//! Breadth-first exploration of the model's states: every state packed once into a table of
//! fixed-width bit-packed records (`world.rs`, `chunked.rs`), found again by an index of state
//! numbers (`state_table.rs`), so the first state found that a property looks for has the
//! shortest path. Successor lists are kept compressed (`edges.rs`, a byte or two an edge) for
//! the deadlock and liveness checks, which need to know which states reach which; a state's
//! parent is the state whose list found it, read from them rather than kept. The environment's
//! choice on each step of a path is found again when the path is asked for, by making the
//! parent's successors once more, rather than stored with every state.

use crate::chunked::Records;
use crate::edges::{Edge, Edges};
use crate::found_memo::FoundMemo;
use crate::outcome::Stop;
use crate::property::Property;
use crate::ringlet::{initial_worlds, Choice, StepGenerator, Successor};
use crate::search::Search;
use crate::state_table::{self, StateTable, MAX_STATES};
use crate::step_memo::{Step, StepMemo};
use crate::world::{Layout, Status, SystemState, TooNarrow};
use proclaim_behaviour::PropertyKind;
use std::cell::OnceCell;

/// Every state explored, in breadth-first order.
pub struct Graph {
    layout: Layout,
    /// State i's packed record.
    states: Records,
    table: StateTable,
    /// How many initial states there are: states `0..initial`.
    initial: u32,
    /// Successors of the states expanded.
    edges: Edges,
    /// The successor lists unpacked, made when a liveness check first asks.
    adjacency: OnceCell<Adjacency>,
    /// A liveness check will follow the search: the budget keeps room for what it builds.
    liveness_follows: bool,
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
    /// The search stopped because a racing engine answered first (`race.rs`).
    pub overtaken: bool,
    /// How many times the layout was widened (records packed before are packed no more).
    generation: usize,
}

/// What a liveness check builds over a graph of `states` and `edges`, at most: the successor
/// lists unpacked (4 bytes an edge, 4 a state) and, per state, Tarjan's index, low link and
/// stack entry and frame (`components.rs`), its component and the marks of what is inside
/// (`acceptance.rs`, `liveness.rs`).
pub(crate) fn liveness_bytes(states: usize, edges: usize) -> usize {
    const PER_STATE: usize = 4 + 4 + 4 + 4 + 24 + 4 + 1 + 1;
    states * PER_STATE + edges * 4
}

/// Successor lists with an index, for checks that walk edges in any order: the successors of
/// state i are `targets[start[i]..start[i + 1]]`.
struct Adjacency {
    start: Vec<u32>,
    targets: Vec<u32>,
}

impl Graph {
    pub fn len(&self) -> usize {
        self.states.len()
    }

    pub fn edge_count(&self) -> usize {
        self.edges.len()
    }

    pub fn world(&self, id: u32) -> SystemState {
        self.layout.unpack(self.bytes_of(id))
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
        self.bytes_after(0, 0)
    }

    /// Bytes the tables would hold, at most, after `states` more states and `edges` more edges
    /// in one more list.
    fn bytes_after(&self, states: usize, edges: usize) -> usize {
        let adjacency = match self.adjacency.get() {
            Some(a) => 4 * (a.start.capacity() + a.targets.capacity()),
            // Before it is made: the room the liveness check will take, when one follows.
            None if self.liveness_follows => {
                liveness_bytes(self.len() + states, self.edges.len() + edges)
            }
            None => 0,
        };
        self.states.bytes_after(states)
            + self.table.bytes_after(states)
            + self.edges.bytes_after(edges)
            + adjacency
    }

    /// The state whose successors first found `id` (its parent in the breadth-first tree).
    fn parent(&self, id: u32) -> Option<u32> {
        if id < self.initial {
            return None;
        }
        self.edges.finder(id)
    }

    /// The path to `id`: the index of its initial world and the choices after it. Each step's
    /// choice is found by making its parent's successors again.
    pub fn path(&self, model: &Search, id: u32) -> (usize, Vec<(u32, Choice)>) {
        let mut states = vec![id];
        while let Some(parent) = states.last().and_then(|&at| self.parent(at)) {
            states.push(parent);
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
    pub fn deadlock(&self, model: &Search) -> Option<u32> {
        let n = self.len();
        // Reverse edges, counting-sorted.
        let mut start = vec![0u32; n + 1];
        let mut reader = self.edges.from(0);
        while reader.each_of_next(|_, e| start[e.target as usize + 1] += 1) {}
        for i in 0..n {
            start[i + 1] += start[i];
        }
        let mut fill = start.clone();
        let mut reverse = vec![0u32; self.edges.len()];
        let mut live = vec![false; n];
        let mut work = Vec::new();
        let mut reader = self.edges.from(0);
        while reader.each_of_next(|s, e| {
            let t = e.target as usize;
            reverse[fill[t] as usize] = s;
            fill[t] += 1;
            if e.fired && !live[s as usize] {
                live[s as usize] = true;
                work.push(s as usize);
            }
        }) {}
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
pub fn waiting(model: &Search, world: &SystemState) -> Vec<usize> {
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
    /// Once this many states are stored undecided, a racing symbolic engine may start
    /// (`race.rs`).
    pub rival_after: usize,
    /// Make successors through the step memo (`step_memo.rs`) where records fit it; off only
    /// to check that it changes nothing.
    pub memo: bool,
}

/// How often (in states expanded) the search asks whether a racing engine has answered, and
/// says what it holds.
const RACE_EVERY: usize = 1024;

/// Whether a search can stop once every property is decided: every property is a safety one
/// (a liveness property needs the whole graph).
fn all_decidable(properties: &[Property]) -> bool {
    !properties.is_empty()
        && properties.iter().all(|p| {
            matches!(
                p.source.kind,
                PropertyKind::Never | PropertyKind::Always | PropertyKind::Reachable
            )
        })
}

/// Stores the initial worlds, or says which budget they do not fit.
fn store_initial(
    graph: &mut Graph,
    store: &mut StateInserter,
    model: &Search,
    properties: &[Property],
    limits: Limits,
) -> Result<(), Stop> {
    for w in initial_worlds(model) {
        if graph.is_full(limits.max_states) {
            return Err(Stop::StateBudget);
        }
        if graph.bytes_after(1, 0) + model.values.borrow().bytes() > limits.max_memory {
            return Err(Stop::MemoryBudget);
        }
        store.insert(graph, &w, model, properties);
        graph.initial = graph.len() as u32;
    }
    Ok(())
}

/// Explores from the initial states until every reachable state is seen or a limit stops it;
/// checks `properties` on every state as it is found.
/// `progress` hears how far it got every [`PROGRESS_EVERY`] states expanded.
pub fn explore(
    model: &Search,
    properties: &[Property],
    limits: Limits,
    progress: &mut dyn FnMut(Progress),
) -> Graph {
    let mut graph = Graph::empty(model, properties.len());
    graph.liveness_follows = properties.iter().any(|p| p.source.kind.is_liveness());
    let mut store = StateInserter::default();
    let decidable = limits.stop_when_decided && all_decidable(properties);
    let stop = |graph: &mut Graph, reason: Stop| {
        graph.complete = false;
        graph.stopped = reason;
    };
    if let Err(reason) = store_initial(&mut graph, &mut store, model, properties, limits) {
        stop(&mut graph, reason);
        return graph;
    }
    graph.edges = Edges::new(graph.initial);
    let mut expansion = Expansion::new(model, properties, &graph, store);
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
        if graph.len() >= limits.rival_after {
            model.call_rival();
        }
        if next % RACE_EVERY == 0 {
            if model.overtaken() {
                graph.overtaken = true;
                stop(&mut graph, Stop::StateBudget);
                break;
            }
            model.hold(graph.bytes() + expansion.memos_bytes());
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
        if let Err(reason) = expansion.expand(&mut graph, &limits, next) {
            stop(&mut graph, reason);
            break;
        }
        next += 1;
    }
    graph
}

/// What expanding states needs besides the graph: the step generator and its memos, the
/// batch of successors made ahead, and buffers reused state after state.
struct Expansion<'m> {
    model: &'m Search<'m>,
    properties: &'m [Property],
    stepper: StepGenerator<'m>,
    memo: StepMemo<'m>,
    found: FoundMemo<'m>,
    /// The layout `found` knows ([`Graph::generation`]).
    found_generation: usize,
    batch: Batch,
    store: StateInserter,
    successors: Vec<Successor>,
    list: Vec<(Edge, bool)>,
    world: SystemState,
}

impl<'m> Expansion<'m> {
    fn new(
        model: &'m Search<'m>,
        properties: &'m [Property],
        graph: &Graph,
        store: StateInserter,
    ) -> Expansion<'m> {
        Expansion {
            model,
            properties,
            stepper: StepGenerator::new(model),
            memo: StepMemo::new(model, &graph.layout),
            found: FoundMemo::new(model, properties, &graph.layout),
            found_generation: graph.generation,
            batch: Batch::default(),
            store,
            successors: Vec::new(),
            list: Vec::new(),
            world: SystemState {
                turn: 0,
                machines: Vec::new(),
                values: Vec::new(),
                saw: Vec::new(),
            },
        }
    }

    /// Makes state `id`'s successors, stores the new ones and its successor list; or says
    /// that the memory budget does not hold them.
    fn expand(&mut self, graph: &mut Graph, limits: &Limits, id: usize) -> Result<(), Stop> {
        self.list.clear();
        if limits.memo
            && (self.batch.has(id, graph.generation)
                || self.batch.fill(graph, &mut self.memo, &self.stepper, id))
        {
            self.store_packed(graph, limits, id)?;
        } else {
            self.store_unpacked(graph, limits, id)?;
        }
        // The successors made before the choice budget ran out are stored, and a property may
        // have found one of them: their edges are kept so that its path has its parent (it
        // was once told as an initial state, with an empty counterexample).
        graph.edges.push(self.list.iter().copied());
        if self.stepper.overflowed() {
            return Err(Stop::ChoiceBudget);
        }
        Ok(())
    }

    /// Bytes the memos and the values met hold, besides the graph's tables.
    fn memos_bytes(&self) -> usize {
        self.memo.bytes() + self.found.bytes() + self.model.values.borrow().bytes()
    }

    /// Whether the tables, grown by `made` successors as if every one were new, stay within
    /// the memory budget (less what a rival engine holds); says what they hold now.
    fn within_budget(&self, graph: &Graph, limits: &Limits, made: usize) -> Result<(), Stop> {
        let held = self.memos_bytes();
        if graph.bytes_after(made, made) + held > self.model.memory_budget(limits.max_memory) {
            return Err(Stop::MemoryBudget);
        }
        Ok(())
    }

    /// State `id`'s successors from the batch, stored as they are packed.
    fn store_packed(&mut self, graph: &mut Graph, limits: &Limits, id: usize) -> Result<(), Stop> {
        if self.found_generation != graph.generation {
            self.found.relayout(&graph.layout);
            self.found_generation = graph.generation;
        }
        let range = self.batch.range(id);
        // What the tables would grow to must stay within the memory budget: as if every
        // successor were new.
        self.within_budget(graph, limits, range.len())?;
        let bytes = graph.layout.bytes();
        let steps = self.batch.steps[range.clone()].iter();
        for (step, &hash) in steps.zip(&self.batch.hashes[range]) {
            let record = step.record.to_le_bytes();
            let (target, new) = graph.insert_record(&record[..bytes], hash);
            if new {
                self.found.check(
                    &graph.layout,
                    step.record,
                    &mut self.world,
                    &mut graph.entered,
                    &mut graph.targets,
                    target,
                );
            }
            let fired = graph.mark_fired(self.model, step.machine, step.from, step.fired);
            self.list.push((Edge { target, fired }, new));
        }
        Ok(())
    }

    /// State `id`'s successors made on its unpacked world, each packed as it is stored.
    fn store_unpacked(
        &mut self,
        graph: &mut Graph,
        limits: &Limits,
        id: usize,
    ) -> Result<(), Stop> {
        graph
            .layout
            .unpack_into(graph.bytes_of(id as u32), &mut self.world);
        self.successors.clear();
        self.stepper
            .successors(&self.world, false, &mut self.successors);
        let made = self.successors.len();
        self.within_budget(graph, limits, made)?;
        for s in &self.successors {
            let (target, new) = self
                .store
                .insert(graph, &s.world, self.model, self.properties);
            let fired = graph.mark_fired(self.model, s.machine, s.from, s.fired);
            self.list.push((Edge { target, fired }, new));
        }
        Ok(())
    }
}

/// How many states' successors are made ahead of storing them, so that the table entries
/// they will probe are read from memory together rather than one after another.
const BATCH: usize = 64;

/// The successors of a run of states, packed, made through the step memo ahead of storing.
#[derive(Default)]
struct Batch {
    /// The first state of the run.
    first: usize,
    /// Per state of the run: where its successors end in `steps`.
    ends: Vec<usize>,
    steps: Vec<Step>,
    /// Each step's record's hash.
    hashes: Vec<u64>,
    /// The layout the records were packed with ([`Graph::generation`]).
    generation: usize,
    scratch: Vec<Step>,
}

impl Batch {
    /// Whether state `id`'s successors are here, packed with the layout of `generation`.
    fn has(&self, id: usize, generation: usize) -> bool {
        self.generation == generation && (self.first..self.first + self.ends.len()).contains(&id)
    }

    /// Where state `id`'s successors are in `steps`.
    fn range(&self, id: usize) -> std::ops::Range<usize> {
        let i = id - self.first;
        let start = if i == 0 { 0 } else { self.ends[i - 1] };
        start..self.ends[i]
    }

    /// Makes the successors of the states from `first` on (at most [`BATCH`] of them) and reads
    /// the table entries their records will probe; false (and nothing made) when the records
    /// are too wide for the step memo. A successor too wide for its field widens it: the memo
    /// starts afresh and so does the run.
    fn fill(
        &mut self,
        graph: &mut Graph,
        memo: &mut StepMemo,
        stepper: &StepGenerator,
        first: usize,
    ) -> bool {
        self.first = first;
        self.ends.clear();
        self.steps.clear();
        self.generation = graph.generation;
        let mut id = first;
        while id < graph.len() && id < first + BATCH {
            if !graph.layout.fits_register() {
                self.ends.clear();
                return false;
            }
            let mut record = [0u8; 16];
            let bytes = graph.bytes_of(id as u32);
            record[..bytes.len()].copy_from_slice(bytes);
            self.scratch.clear();
            let made = memo.successors(
                &graph.layout,
                stepper,
                u128::from_le_bytes(record),
                &mut self.scratch,
            );
            if let Err(narrow) = made {
                graph.widen(narrow);
                memo.relayout(&graph.layout);
                self.ends.clear();
                self.steps.clear();
                self.generation = graph.generation;
                id = first;
                continue;
            }
            self.steps.extend_from_slice(&self.scratch);
            self.ends.push(self.steps.len());
            id += 1;
        }
        let bytes = graph.layout.bytes();
        self.hashes.clear();
        self.hashes.extend(
            self.steps
                .iter()
                .map(|s| state_table::hash(&s.record.to_le_bytes()[..bytes])),
        );
        for &hash in &self.hashes {
            graph.table.touch(hash);
        }
        true
    }
}

impl Graph {
    /// Marks the transition a step fired (machine `machine`'s, from state `from`, by its
    /// position in priority order) as fired; whether one did.
    fn mark_fired(
        &mut self,
        model: &Search,
        machine: usize,
        from: usize,
        fired: Option<usize>,
    ) -> bool {
        if let Some(t) = fired {
            let index = model.machines[machine].states[from].transitions[t].index;
            self.fired[machine][index] = true;
        }
        fired.is_some()
    }

    /// No states yet, and nothing entered, fired or found.
    fn empty(model: &Search, properties: usize) -> Graph {
        let layout = Layout::new(model);
        Graph {
            states: Records::new(layout.bytes()),
            layout,
            table: StateTable::default(),
            initial: 0,
            edges: Edges::default(),
            adjacency: OnceCell::new(),
            liveness_follows: false,
            complete: true,
            stopped: Stop::Explored,
            entered: model.per_state(),
            fired: model.per_transition(),
            targets: vec![None; properties],
            depth: 0,
            overtaken: false,
            generation: 0,
        }
    }

    /// Whether another state would pass `max_states`, or what the index and the edge numbers
    /// can hold.
    fn is_full(&self, max_states: usize) -> bool {
        self.len() >= max_states
            || self.len() >= MAX_STATES
            || self.edges.len() >= (u32::MAX as usize - (1 << 20))
    }

    /// State `id`'s record.
    fn bytes_of(&self, id: u32) -> &[u8] {
        self.states.get(id as usize)
    }

    /// Every record packed again with `narrow`'s field widened, and the index made anew (the
    /// state numbers stay).
    fn widen(&mut self, narrow: TooNarrow) {
        let wider = self.layout.widened(narrow);
        let mut states = Records::new(wider.bytes());
        let mut table = StateTable::default();
        let mut record = Vec::new();
        for id in 0..self.len() as u32 {
            record.clear();
            let fits = wider.pack(&self.world(id), &mut record);
            // Every field is at least as wide as the one the record was packed with.
            debug_assert!(fits.is_ok());
            let stored = &states;
            table.find_or_insert(
                state_table::hash(&record),
                id,
                |_| false,
                |i| state_table::hash(stored.get(i as usize)),
            );
            states.push(&record);
        }
        self.layout = wider;
        self.states = states;
        self.table = table;
        self.generation += 1;
    }

    /// The id of the state packed as `record` (whose hash is `hash`) and whether it is new; a
    /// new one is stored.
    fn insert_record(&mut self, record: &[u8], hash: u64) -> (u32, bool) {
        let id = self.len() as u32;
        let states = &self.states;
        if let Some(found) = self.table.find_or_insert(
            hash,
            id,
            |id| state_table::same(states.get(id as usize), record),
            |id| state_table::hash(states.get(id as usize)),
        ) {
            return (found, false);
        }
        self.states.push(record);
        (id, true)
    }
}

/// Packs states and inserts them into the graph, checking each new one: what that needs
/// besides the graph, its packing buffer.
#[derive(Default)]
struct StateInserter {
    scratch: Vec<u8>,
}

impl StateInserter {
    /// The id of `world` and whether it is new; a new state is stored, checked against the
    /// properties and marks the states it is in as entered.
    fn insert(
        &mut self,
        graph: &mut Graph,
        world: &SystemState,
        model: &Search,
        properties: &[Property],
    ) -> (u32, bool) {
        loop {
            self.scratch.clear();
            match graph.layout.pack(world, &mut self.scratch) {
                Ok(()) => break,
                Err(narrow) => graph.widen(narrow),
            }
        }
        let (id, new) = graph.insert_record(&self.scratch, state_table::hash(&self.scratch));
        if new {
            self.note_new(graph, id, world, model, properties);
        }
        (id, new)
    }

    /// A new state `id`, `world`: it is checked against the properties and marks the states
    /// it is in as entered.
    fn note_new(
        &mut self,
        graph: &mut Graph,
        id: u32,
        world: &SystemState,
        model: &Search,
        properties: &[Property],
    ) {
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
    }
}

/// Read-only views of the explored graph for the checks made after exploration
/// ([`crate::liveness`], [`crate::components`], [`crate::lasso`]): which states were expanded,
/// their successors, and how a step is recognised when it is replayed.
impl Graph {
    /// How many states had all their successors made: states `0..expanded()` (breadth-first
    /// order); the others were stored but the budget ran out before their turn.
    pub fn expanded(&self) -> usize {
        self.edges.lists()
    }

    /// Whether state `id` is one of the initial states.
    pub fn is_initial(&self, id: u32) -> bool {
        id < self.initial
    }

    /// Where state `id`'s successors are in the edge list (`id` expanded; empty when no
    /// machine can ring there).
    pub fn edge_range(&self, id: u32) -> std::ops::Range<usize> {
        let a = self.adjacency();
        let i = id as usize;
        a.start[i] as usize..a.start[i + 1] as usize
    }

    /// The state edge `e` leads to.
    pub fn edge_target(&self, e: usize) -> u32 {
        self.adjacency().targets[e]
    }

    /// The successors of an expanded state `id`, as state ids (a state may repeat).
    pub fn successors_of(&self, id: u32) -> impl Iterator<Item = u32> + '_ {
        self.edge_range(id).map(|e| self.edge_target(e))
    }

    /// Whether `world` is stored as state `id` (a successor made again, when a step of a
    /// lasso is replayed, is recognised by its packed bytes).
    pub fn stores_as(&self, world: &SystemState, id: u32) -> bool {
        let mut bytes = Vec::new();
        self.layout.pack(world, &mut bytes).is_ok() && self.bytes_of(id) == bytes
    }

    /// The successor lists unpacked (made on the first call).
    fn adjacency(&self) -> &Adjacency {
        self.adjacency.get_or_init(|| {
            let mut start = Vec::with_capacity(self.expanded() + 1);
            let mut targets = Vec::with_capacity(self.edges.len());
            start.push(0);
            let mut reader = self.edges.from(0);
            while reader.each_of_next(|_, e| targets.push(e.target)) {
                start.push(targets.len() as u32);
            }
            Adjacency { start, targets }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::property::PropertySource;
    use crate::random_behaviour;
    use crate::reduce::{self, Reductions};
    use proclaim_behaviour::{load, Files};
    use proclaim_fsm::FileDiagnostic;
    use std::sync::Arc;

    /// Properties that read each machine's states and every global.
    fn properties(model: &crate::model::Model) -> Vec<PropertySource> {
        let mut out = Vec::new();
        let mut add = |kind: PropertyKind, expression: String| {
            out.push(PropertySource {
                name: expression.clone(),
                kind,
                expression,
                fair: Vec::new(),
            })
        };
        for m in &model.machines {
            // A state of regions is one of each region's (§3.2).
            for s in &m.machine.states {
                let paths = m.machine.atomic_paths(s).into_iter();
                let each: Vec<String> = paths.map(|p| format!("{}.{p}", m.name)).collect();
                add(PropertyKind::Reachable, each.join(" && "));
            }
        }
        for slot in &model.slots {
            if slot.kind == crate::model::SlotKind::Global {
                add(PropertyKind::Never, format!("{} == 1", slot.name));
            }
        }
        out
    }

    /// The whole graph as data: every record, successor list and mark, in order.
    fn picture(model: &Search, graph: &Graph) -> String {
        // The worlds, not their packing: a search with the memo makes a batch of successors
        // ahead and may widen a field for a state it then never stores.
        let records: Vec<SystemState> = (0..graph.len() as u32).map(|id| graph.world(id)).collect();
        let lists: Vec<Vec<u32>> = (0..graph.expanded() as u32)
            .map(|id| graph.successors_of(id).collect())
            .collect();
        format!(
            "{records:?}\n{lists:?}\n{:?} {:?} {:?} {} {} {:?} {}",
            graph.entered,
            graph.fired,
            graph.targets,
            graph.depth,
            graph.complete,
            graph.deadlock(model),
            graph.overtaken,
        )
    }

    /// A generated behaviour's files, read where they are held.
    struct Generated(Vec<(String, String)>);

    impl Files for Generated {
        fn read(&self, relative: &str) -> Result<String, FileDiagnostic> {
            self.0
                .iter()
                .find(|(name, _)| name == relative)
                .map(|(_, text)| text.clone())
                .ok_or_else(|| FileDiagnostic::in_file(relative, "no such file generated"))
        }

        fn show(&self, relative: &str) -> String {
            format!("<generated>/{relative}")
        }
    }

    /// A search whose rival has already answered stops at once: the explicit one saying it
    /// was overtaken, the symbolic one declining; the same searches in a race still undecided
    /// go on to their end.
    #[test]
    fn a_search_overtaken_by_its_rival_stops_and_says_so() {
        use crate::race::{Race, Side};
        // The first random behaviour the symbolic engine takes whose search goes past its
        // first layers (a smaller one ends before it looks at the race).
        let (model, compiled) = (0..50)
            .find_map(|seed| {
                let generated = random_behaviour::generate(seed);
                let files = Generated(generated.files.clone());
                let behaviour = load("random", Arc::new(files)).expect("it loads");
                let (mut model, compiled) =
                    crate::prepare(&behaviour, &[], true).expect("it models");
                model.storage = reduce::storage(&model, &compiled, Reductions::default());
                let taken = crate::symbolic::check(&Search::new(&model), &compiled, 1 << 30);
                taken
                    .is_ok_and(|o| o.steps > 2)
                    .then_some((model, compiled))
            })
            .expect("a random behaviour the symbolic engine takes");
        let limits = Limits {
            max_states: 100_000,
            max_memory: 1 << 30,
            stop_when_decided: true,
            rival_after: usize::MAX,
            memo: true,
        };
        let race = Race::new(1 << 30);
        let whole = explore(
            &Search::racing(&model, &race, Side::Explicit),
            &compiled,
            limits,
            &mut |_| {},
        );
        assert!(whole.complete && !whole.overtaken);
        race.finish(Side::Symbolic, true);
        let cut = explore(
            &Search::racing(&model, &race, Side::Explicit),
            &compiled,
            limits,
            &mut |_| {},
        );
        assert!(cut.overtaken && !cut.complete);
        assert!(cut.len() < whole.len(), "{} of {}", cut.len(), whole.len());
        let search = Search::racing(&model, &race, Side::Symbolic);
        let declined = crate::symbolic::check(&search, &compiled, 1 << 30).err();
        assert_eq!(
            declined.map(|d| d.0),
            Some("the explicit search answered first".to_string())
        );
    }

    /// The step memo and the found-state memo change nothing the search finds, on the random
    /// behaviours of the conformance test, every reduction on and off.
    #[test]
    fn the_memos_change_nothing_on_random_behaviours() {
        let mut replayed = 0;
        for seed in 0..20 {
            let generated = random_behaviour::generate(seed);
            let files = Generated(generated.files.clone());
            let behaviour = load("random", Arc::new(files)).expect("it loads");
            let (plain, _) = crate::prepare(&behaviour, &[], true).expect("it models");
            let asked = properties(&plain);
            for reductions in [Reductions::default(), Reductions::NONE] {
                // Each search numbers the values it meets.
                let picture_of = |memo| {
                    let (mut model, compiled) =
                        crate::prepare(&behaviour, &asked, true).expect("it models");
                    model.storage = reduce::storage(&model, &compiled, reductions);
                    let limits = Limits {
                        max_states: 5_000,
                        max_memory: 1 << 30,
                        stop_when_decided: reductions.stop_when_decided,
                        rival_after: usize::MAX,
                        memo,
                    };
                    let search = Search::new(&model);
                    let graph = explore(&search, &compiled, limits, &mut |_| {});
                    (picture(&search, &graph), graph.len())
                };
                let (with, states) = picture_of(true);
                let (without, _) = picture_of(false);
                assert!(
                    with == without,
                    "seed {seed}, {reductions:?}: the searches differ\n{}",
                    generated.show()
                );
                replayed += states;
            }
        }
        assert!(
            replayed > 5_000,
            "the behaviours explored only {replayed} states"
        );
    }
}
