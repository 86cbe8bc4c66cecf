//! A chart's configurations lowered to flat states (`docs/spec/behaviour.md` §3.2): a flat state
//! for each set of atomic states the machine can be in (one for each region of an active
//! parallel state) and set of states a move into it enters, its arms every combination of what
//! its regions select, in the order the schedule tries them.

use super::ast::Ref;
use super::chart::{Chart, Tree, Written, IN_STATE};
use crate::code::{BinOp, Expr, Statement, VarType};
use crate::label::Label;
use crate::model::{Action, Composite, State, StateId, Transition};
use std::collections::{HashMap, HashSet, VecDeque};

/// The most arms one flat state may have: the combinations of its regions' choices.
pub(super) const MOST_ARMS: usize = 4096;

/// One flat state: the atomic state active in each region (file order), entered by an arrival
/// that entered `entered` (those of its states whose entry runs something or starts a clock).
struct Flat {
    atomics: Vec<usize>,
    entered: Vec<usize>,
    id: StateId,
    arms: Vec<FlatArm>,
}

struct FlatArm {
    label: Label,
    /// The label as written, when the arm's is not (`done`, a history's place, regions joined).
    written: Option<Label>,
    /// The flat state it enters (an index into `Flattening::flats`).
    target: usize,
    line: usize,
    leaving: Option<Vec<Action>>,
    /// The composite the first transition it fires was written on, when not on its atomic
    /// state.
    written_on: Option<usize>,
    /// The clock holders it enters, outermost first.
    enters: Vec<usize>,
    /// The other transitions whose labels it joins: where each was written, its line, and
    /// whether it fires (a later region's move out of the parallel state is preempted).
    joined: Vec<(Option<usize>, usize, bool)>,
    /// Every transition it fires stays (has no target): it does not move, and `target` is the
    /// flat state it fires in.
    stays: bool,
    /// The first transition's targets as written, by path, where it names several.
    targets: Vec<String>,
}

/// One transition a state selects: written on `source`, to `targets` (the states entered
/// together: its written targets, or where a history arm resumes).
#[derive(Clone)]
struct Fire<'t> {
    source: usize,
    written: &'t Written,
    targets: Vec<usize>,
}

/// One condition of an arm: its label as lowered (each time test on its clock), and as written.
#[derive(Clone)]
struct Condition {
    label: Label,
    unclocked: Label,
    written: Label,
    /// The state the transition was written on, and its line.
    source: usize,
    line: usize,
}

/// What the active states select when the labels of its conditions hold, and what fires.
#[derive(Clone)]
struct Choice<'t> {
    conditions: Vec<Condition>,
    fires: Vec<Fire<'t>>,
}

/// Flat states made as transitions reach them, from the initial one.
pub(super) struct Flattening<'t> {
    tree: &'t Tree,
    flats: Vec<Flat>,
    variants: HashMap<(Vec<usize>, Vec<usize>), usize>,
    queue: VecDeque<usize>,
    /// Each atomic state's id: as written, else numbered; a further flat state of the same
    /// atomic state (or one of several regions) takes a fresh one.
    ids: Vec<Option<StateId>>,
    /// Whether each atomic state is in a flat state yet.
    made: Vec<bool>,
    taken: HashSet<StateId>,
    next: StateId,
    /// The states whose time a clock keeps: composites, and the atomic states of regions.
    /// Their place is their index in `Chart::composites`.
    clocks: Vec<Option<usize>>,
    /// A state whose combinations pass [`MOST_ARMS`]: its line.
    pub too_many: Option<usize>,
}

impl<'t> Flattening<'t> {
    pub(super) fn new(tree: &'t Tree) -> Flattening<'t> {
        let taken: HashSet<StateId> = tree.nodes.iter().filter_map(|n| n.id).collect();
        let mut clocks = Vec::new();
        let mut next_clock = 0;
        for n in 0..tree.nodes.len() {
            let holds = !tree.nodes[n].children.is_empty() || tree.in_region(n);
            clocks.push(holds.then(|| {
                next_clock += 1;
                next_clock - 1
            }));
        }
        let mut flattening = Flattening {
            tree,
            flats: Vec::new(),
            variants: HashMap::new(),
            queue: VecDeque::new(),
            ids: Vec::new(),
            made: vec![false; tree.nodes.len()],
            taken,
            next: 1,
            clocks,
            too_many: None,
        };
        for n in 0..tree.nodes.len() {
            let node = &tree.nodes[n];
            let id = match (node.id, node.children.is_empty()) {
                (Some(id), _) => Some(id),
                (None, true) => Some(flattening.fresh()),
                (None, false) => None,
            };
            flattening.ids.push(id);
        }
        flattening
    }

    fn fresh(&mut self) -> StateId {
        while self.taken.contains(&self.next) {
            self.next += 1;
        }
        self.taken.insert(self.next);
        self.next
    }

    /// The flat state entering `target` from `domain` leads to, the atomic states in `kept`
    /// staying as they are.
    pub(super) fn enter(
        &mut self,
        kept: &[usize],
        domain: Option<usize>,
        targets: &[usize],
    ) -> usize {
        let entered = self.tree.entering(domain, targets);
        let mut atomics: Vec<usize> = kept.to_vec();
        atomics.extend(
            entered
                .iter()
                .copied()
                .filter(|&n| self.tree.nodes[n].children.is_empty()),
        );
        atomics.sort_unstable();
        atomics.dedup();
        self.variant(atomics, &entered)
    }

    /// The flat state of `atomics` arrived at by entering `entered`. Entries that run nothing
    /// and start no clock are not told apart, so a chart whose composites have no OnEntry and
    /// test no time gets one flat state per configuration.
    fn variant(&mut self, atomics: Vec<usize>, entered: &[usize]) -> usize {
        let tree = self.tree;
        let entered: Vec<usize> = entered
            .iter()
            .copied()
            .filter(|&n| {
                !tree.nodes[n].entry.is_empty()
                    || tree.timed(n)
                    || (atomics.len() == 1 && atomics[0] == n)
            })
            .collect();
        let key = (atomics, entered);
        if let Some(&flat) = self.variants.get(&key) {
            return flat;
        }
        let (atomics, entered) = key.clone();
        // The first flat state of an atomic state takes its id; the others fresh ones.
        let id = match atomics.as_slice() {
            [one] => self.ids[*one].take(),
            _ => None,
        };
        let id = id.unwrap_or_else(|| self.fresh());
        for &a in &atomics {
            self.made[a] = true;
        }
        self.flats.push(Flat {
            atomics,
            entered,
            id,
            arms: Vec::new(),
        });
        let flat = self.flats.len() - 1;
        self.variants.insert(key, flat);
        self.queue.push_back(flat);
        flat
    }

    /// Makes every flat state a transition reaches, then one for each atomic state none
    /// reached (so that `check` and `verify` can say it is never entered).
    pub(super) fn run(&mut self) {
        let tree = self.tree;
        let mut from = 0;
        loop {
            while let Some(flat) = self.queue.pop_front() {
                let atomics = self.flats[flat].atomics.clone();
                let arms = self.arms(flat, &atomics);
                self.flats[flat].arms = arms;
            }
            let missed = (from..tree.nodes.len())
                .find(|&n| tree.nodes[n].children.is_empty() && !self.made[n]);
            match missed {
                Some(n) => {
                    from = n + 1;
                    self.enter(&[], None, &[n]);
                }
                None => return,
            }
        }
    }

    /// The arms of the flat state of `atomics`: every combination of what its states select,
    /// in the order they are tried (§3.2).
    fn arms(&mut self, flat: usize, atomics: &[usize]) -> Vec<FlatArm> {
        let tree = self.tree;
        let Some(&first) = atomics.first() else {
            return Vec::new();
        };
        let top = tree.outermost(first);
        let choices = self.choices(atomics, top);
        let mut arms = Vec::new();
        for choice in choices {
            arms.push(self.arm(flat, atomics, choice));
        }
        arms
    }

    /// What active state `node` selects, in the order tried: what the states inside it select
    /// (its one active state's, or its regions' combined), then its own transitions.
    fn choices(&mut self, atomics: &[usize], node: usize) -> Vec<Choice<'t>> {
        let tree = self.tree;
        let mut out = if tree.nodes[node].parallel {
            self.combined(atomics, node)
        } else {
            match tree.active_child(atomics, node) {
                Some(child) => self.choices(atomics, child),
                None => Vec::new(),
            }
        };
        for w in &tree.written[node] {
            if w.done && !tree.done_in(atomics, node) {
                continue;
            }
            for (label, targets) in self.targets(atomics, node, w) {
                let mut clocked = label.clone();
                clocked.set_time_clocks(self.clocks_of(node));
                out.push(Choice {
                    conditions: vec![Condition {
                        label: clocked,
                        unclocked: label,
                        written: w.label.clone(),
                        source: node,
                        line: w.line,
                    }],
                    fires: vec![Fire {
                        source: node,
                        written: w,
                        targets,
                    }],
                });
            }
        }
        out
    }

    /// The regions of `parallel` combined: the first region whose choice holds fires it; each
    /// later region's fires with it as SCXML's conflict rule says in document order
    /// ([`Flattening::firing`]). A move out of `parallel` fires alone when no later region has
    /// a transition that stays, since nothing else could fire beside it.
    fn combined(&mut self, atomics: &[usize], parallel: usize) -> Vec<Choice<'t>> {
        let tree = self.tree;
        let regions = tree.nodes[parallel].children.clone();
        let per_region: Vec<Vec<Choice<'t>>> =
            regions.iter().map(|&r| self.choices(atomics, r)).collect();
        let stays = |choices: &[Choice<'_>]| {
            (choices.iter().flat_map(|c| &c.fires)).any(|f| f.written.stays)
        };
        let mut out = Vec::new();
        for (a, choices) in per_region.iter().enumerate() {
            let rest = &per_region[a + 1..];
            for x in choices {
                if self.leaves(x, parallel) && !rest.iter().any(|r| stays(r)) {
                    out.push(x.clone());
                    continue;
                }
                let mut combos = vec![x.clone()];
                for later in rest {
                    // Bounded before the combinations are made, not after.
                    if combos.len() * (later.len() + 1) + out.len() > MOST_ARMS {
                        self.too_many.get_or_insert(tree.nodes[parallel].at);
                        return out;
                    }
                    let mut next = Vec::new();
                    for combo in &combos {
                        // Past a move out of `parallel`, only what stays can fire.
                        if self.leaves(combo, parallel) && !stays(later) {
                            next.push(combo.clone());
                            continue;
                        }
                        for y in later {
                            let mut joined = combo.clone();
                            joined.conditions.extend(y.conditions.iter().cloned());
                            joined.fires.extend(self.firing(combo, y, parallel));
                            next.push(joined);
                        }
                        // None of this region's holds: the order says so, no label needed.
                        next.push(combo.clone());
                    }
                    combos = next;
                }
                out.extend(combos);
                if out.len() > MOST_ARMS {
                    self.too_many.get_or_insert(tree.nodes[parallel].at);
                    return out;
                }
            }
        }
        out
    }

    /// What of `y`, a later region's choice, fires beside what `combo` fires (SCXML's rule:
    /// two conflict when both leave a state, and the earlier wins): what stays always (it
    /// leaves nothing); a move out of `parallel` when nothing moved before it; a move inside
    /// its region unless a move out of `parallel` fired before it.
    fn firing(&self, combo: &Choice<'t>, y: &Choice<'t>, parallel: usize) -> Vec<Fire<'t>> {
        let left = self.leaves(combo, parallel);
        let moved = combo.fires.iter().any(|f| !f.written.stays);
        (y.fires.iter())
            .filter(|f| {
                f.written.stays
                    || match self.fire_leaves(f, parallel) {
                        true => !moved,
                        false => !left,
                    }
            })
            .cloned()
            .collect()
    }

    /// Whether what `choice` fires leaves `parallel` (its domain is around it).
    fn leaves(&self, choice: &Choice<'_>, parallel: usize) -> bool {
        choice.fires.iter().any(|f| self.fire_leaves(f, parallel))
    }

    /// Whether `fire` leaves `parallel`: it moves, and its domain is around `parallel`.
    fn fire_leaves(&self, fire: &Fire<'_>, parallel: usize) -> bool {
        // The domain of the transition as written: a move to a history resumes a state inside
        // its target, but leaves what the written target's domain says.
        let domain = self.tree.domain(fire.source, &fire.written.targets());
        !fire.written.stays
            && !domain.is_some_and(|d| self.tree.chain(d).any(|n| n == parallel) && d != parallel)
    }

    /// The flat arm of `choice` fired in `flat`, the flat state of `atomics`.
    fn arm(&mut self, flat: usize, atomics: &[usize], choice: Choice<'t>) -> FlatArm {
        let tree = self.tree;
        let mut left: Vec<usize> = Vec::new();
        let mut kept: Vec<usize> = atomics.to_vec();
        let mut entered: Vec<usize> = Vec::new();
        // A transition that stays leaves and enters nothing; when all it fires stay, the
        // machine stays in this very flat state, not arriving again.
        let stays = choice.fires.iter().all(|f| f.written.stays);
        for f in choice.fires.iter().filter(|f| !f.written.stays) {
            let domain = tree.domain(f.source, &f.written.targets());
            let active = tree.active_inside(atomics, domain);
            left.extend(active.iter().copied());
            kept.retain(|a| !active.contains(a));
            entered.extend(tree.entering(domain, &f.targets));
        }
        left.sort_unstable();
        left.dedup();
        entered.sort_unstable();
        entered.dedup();
        let mut next: Vec<usize> = kept;
        next.extend(
            entered
                .iter()
                .copied()
                .filter(|&n| tree.nodes[n].children.is_empty()),
        );
        next.sort_unstable();
        next.dedup();
        let target = if stays {
            flat
        } else {
            self.variant(next, &entered)
        };
        let leaving = self.leaving(atomics, &left, &choice.fires);
        // `None` would run the state's OnExit, which a transition that stays does not leave.
        let leaving = if stays {
            Some(leaving.unwrap_or_default())
        } else {
            leaving
        };
        let unclocked = join(choice.conditions.iter().map(|c| c.unclocked.clone()));
        let written = join(choice.conditions.iter().map(|c| c.written.clone()));
        let first = choice.fires.first();
        FlatArm {
            written: (written != unclocked).then_some(written),
            label: join(choice.conditions.iter().map(|c| c.label.clone())),
            target,
            line: first.map_or(0, |f| f.written.line),
            leaving,
            written_on: first
                .map(|f| f.source)
                .filter(|&s| !(atomics.len() == 1 && atomics[0] == s)),
            enters: entered
                .iter()
                .copied()
                .filter(|&n| self.clocks[n].is_some())
                .collect(),
            joined: (choice.conditions.iter().skip(1))
                .map(|c| {
                    let fires = (choice.fires.iter())
                        .any(|f| f.source == c.source && f.written.line == c.line);
                    (Some(c.source), c.line, fires)
                })
                .collect(),
            stays,
            targets: first
                .filter(|f| !f.written.also.is_empty())
                .map_or_else(Vec::new, |f| {
                    (f.written.targets().into_iter())
                        .map(|n| tree.nodes[n].path.clone())
                        .collect()
                }),
        }
    }

    /// The clock a time test written on `node` reads: its own when it keeps one (a composite,
    /// a region's atomic state), else the flat state's arrival.
    fn clocks_of(&self, node: usize) -> Option<usize> {
        self.clocks[node]
    }

    /// The label and targets of each arm a transition written as `w` on `source` lowers to,
    /// tried in this order, in the flat state of `atomics`.
    fn targets(&self, atomics: &[usize], source: usize, w: &Written) -> Vec<(Label, Vec<usize>)> {
        let tree = self.tree;
        let label = if w.done { Label::TRUE } else { w.label.clone() };
        let label = in_states(tree, atomics, source, label);
        let domain = tree.domain(source, &w.targets());
        let left = tree.active_inside(atomics, domain);
        let mut arms = Vec::new();
        match w.history {
            // Leaving the composite notes where this very move leaves it: it comes back there.
            Some(history) if left.iter().any(|&n| tree.chain(n).any(|c| c == w.target)) => {
                let place = tree.place(w.target, history, atomics);
                let resumed = tree.resumed(w.target, history);
                let back = usize::try_from(place - 1)
                    .map_or_else(|_| vec![w.target], |k| resumed[k].clone());
                arms.push((label, back));
                return arms;
            }
            // An arm for each place it may have been left at, tested first; then the written
            // one, to the initial, for never.
            Some(history) => {
                let variable = tree.variable(w.target, history);
                for (k, resumed) in tree.resumed(w.target, history).into_iter().enumerate() {
                    let was = Expr::Binary {
                        op: BinOp::Eq,
                        left: Box::new(Expr::Name(variable.clone())),
                        right: Box::new(Expr::Int(k as i64 + 1)),
                    };
                    let label = Expr::Binary {
                        op: BinOp::And,
                        left: Box::new(was),
                        right: Box::new(label.clone()),
                    };
                    arms.push((label, resumed));
                }
            }
            None => {}
        }
        arms.push((label, w.targets()));
        arms
    }

    /// What firing `fires` from the flat state of `atomics` runs as it leaves the states in
    /// `left`: where each composite with a history was left is noted first (SCXML notes it
    /// before any exit runs), then their OnExits in reverse file order (innermost first, later
    /// regions first), then each transition's own actions. `None` when that is the one atomic
    /// state's own OnExit.
    fn leaving(
        &self,
        atomics: &[usize],
        left: &[usize],
        fires: &[Fire<'_>],
    ) -> Option<Vec<Action>> {
        let tree = self.tree;
        let mut noted = Vec::new();
        for &(composite, history) in &tree.histories {
            if !left.contains(&composite) {
                continue;
            }
            noted.push(Action::Statement(Statement::Assign {
                name: tree.variable(composite, history),
                value: Expr::Int(tree.place(composite, history, atomics)),
            }));
        }
        let own: Vec<Action> = fires
            .iter()
            .flat_map(|f| f.written.actions.iter().cloned())
            .collect();
        let single = atomics.len() == 1;
        let more = left
            .iter()
            .any(|&n| (!single || n != atomics[0]) && !tree.nodes[n].exit.is_empty());
        if noted.is_empty() && own.is_empty() && single && !more {
            return None;
        }
        noted.extend(
            left.iter()
                .rev()
                .flat_map(|&n| tree.nodes[n].exit.iter().cloned()),
        );
        noted.extend(own);
        Some(noted)
    }

    /// The atomic states whose written id no flat state took: those inside regions, whose flat
    /// states are each a combination of one state from every region.
    pub(super) fn ids_not_kept(&self) -> Vec<(usize, StateId)> {
        (0..self.tree.nodes.len())
            .filter(|&n| self.tree.nodes[n].children.is_empty())
            .filter_map(|n| Some((n, self.tree.nodes[n].id.filter(|_| self.ids[n].is_some())?)))
            .collect()
    }

    pub(super) fn finish(mut self, initial: usize) -> Chart {
        let tree = self.tree;
        let composites: Vec<Composite> = (0..tree.nodes.len())
            .filter(|&n| self.clocks[n].is_some())
            .map(|n| {
                let node = &tree.nodes[n];
                Composite {
                    name: node.path.clone(),
                    parent: node.parent.and_then(|p| self.clocks[p]),
                    line: node.line,
                    on_entry: node.entry.clone(),
                    on_exit: node.exit.clone(),
                    internal: node.internal.clone(),
                    atomic: node.children.is_empty(),
                    parallel: node.parallel,
                }
            })
            .collect();
        let mut order: Vec<usize> = (0..self.flats.len()).collect();
        order.sort_by_key(|&f| self.flats[f].atomics.clone());
        let ids: Vec<StateId> = self.flats.iter().map(|f| f.id).collect();
        let mut states = Vec::new();
        let mut transitions = Vec::new();
        for &f in &order {
            let flat = &mut self.flats[f];
            states.push(flat_state(tree, flat, &self.clocks));
            for arm in std::mem::take(&mut flat.arms) {
                transitions.push(Transition {
                    source: flat.id,
                    target: ids[arm.target],
                    label: arm.label,
                    line: arm.line,
                    leaving: arm.leaving,
                    composite: arm.written_on.and_then(|n| self.clocks[n]),
                    enters: arm.enters.iter().filter_map(|&n| self.clocks[n]).collect(),
                    written: arm.written,
                    joined: (arm.joined.iter())
                        .map(|&(n, line, fires)| (n.and_then(|n| self.clocks[n]), line, fires))
                        .collect(),
                    stays: arm.stays,
                    targets: arm.targets,
                });
            }
        }
        // Each history's variable is the machine's own, declared where it starts (a
        // declaration runs nothing: the variable is there, 0, from the first ringlet).
        if let Some(first) = states.iter_mut().find(|s| s.id == ids[initial]) {
            first.on_entry.extend(tree.histories.iter().map(|&(c, h)| {
                Action::Statement(Statement::Declare {
                    ty: VarType::Int,
                    name: tree.variable(c, h),
                    value: None,
                })
            }));
        }
        Chart {
            states,
            transitions,
            initial: ids[initial],
            composites,
        }
    }
}

/// `label`, written on `source`, with each `in(S)` the truth it has in the flat state of
/// `atomics`: whether one of them is the state `S` names (as a target from `source` would) or
/// inside it. `chart.rs` refused every `in` that names no state.
fn in_states(tree: &Tree, atomics: &[usize], source: usize, mut label: Label) -> Label {
    let mut folded = false;
    label.replace_calls(&mut |function, arguments| {
        let [Expr::Name(path)] = arguments else {
            return None;
        };
        if function != IN_STATE {
            return None;
        }
        let state = tree.resolve(Some(source), &Ref::Name(path.clone())).ok()?;
        folded = true;
        let active = atomics.iter().any(|&a| tree.chain(a).any(|c| c == state));
        Some(Expr::Bool(active))
    });
    if folded {
        label.folded_truths()
    } else {
        label
    }
}

/// `a && b && …`; `TRUE` for none.
fn join(labels: impl Iterator<Item = Label>) -> Label {
    labels
        .reduce(|a, b| Expr::Binary {
            op: BinOp::And,
            left: Box::new(a),
            right: Box::new(b),
        })
        .unwrap_or(Label::TRUE)
}

/// The flat state: arriving runs the OnEntry of each state entered, in file order (outermost
/// first, then each region's); staying runs the Internal of each active state in file order;
/// its own OnExit is its one atomic state's (its transitions that leave more carry their own).
fn flat_state(tree: &Tree, flat: &Flat, clocks: &[Option<usize>]) -> State {
    let active = tree.active_inside(&flat.atomics, None);
    let names: Vec<&str> = flat
        .atomics
        .iter()
        .map(|&a| tree.nodes[a].path.as_str())
        .collect();
    let first = flat.atomics.first().copied().unwrap_or(0);
    // How many states around its one atomic state an arrival enters (§3.2).
    let arrives_through = match (flat.atomics.as_slice(), flat.entered.first()) {
        ([one], Some(&top)) => tree.chain(*one).position(|n| n == top).unwrap_or(0),
        _ => 0,
    };
    State {
        id: flat.id,
        name: names.join(", "),
        on_entry: flat
            .entered
            .iter()
            .flat_map(|&n| tree.nodes[n].entry.iter().cloned())
            .collect(),
        on_exit: match flat.atomics.as_slice() {
            [one] => tree.nodes[*one].exit.clone(),
            _ => Vec::new(),
        },
        internal: active
            .iter()
            .flat_map(|&n| tree.nodes[n].internal.iter().cloned())
            .collect(),
        line: tree.nodes[first].line,
        arrives_through,
        arrival_clocks: flat.entered.iter().filter_map(|&n| clocks[n]).collect(),
    }
}
