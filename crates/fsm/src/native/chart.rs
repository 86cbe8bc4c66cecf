//! Nested states lowered to flat ones (`docs/spec/behaviour.md` §3.2): a flat state for each
//! atomic state and set of states a move into it enters, each composite's transitions copied to
//! every state inside it with what firing them leaves, so that every back end runs a chart as
//! the flat machine it already runs and their traces agree by construction.

use super::ast::{Ref, StateAst};
use super::{Lowering, When};
use crate::code::{BinOp, Expr, Statement, VarType};
use crate::interface::global_of;
use crate::label::{Label, TIME_TESTS};
use crate::model::{Action, Composite, State, StateId, Transition};
use std::collections::{HashMap, HashSet, VecDeque};

/// What a chart lowers to.
pub(super) struct Chart {
    pub states: Vec<State>,
    pub transitions: Vec<Transition>,
    pub initial: StateId,
    pub composites: Vec<Composite>,
}

/// Lowers the states of a file in which some state holds states; `None` when nothing could be
/// made of it (every reason is reported).
pub(super) fn lower_chart(
    lowering: &mut Lowering<'_>,
    parsed: Vec<StateAst>,
    initial: Option<(Ref, usize)>,
) -> Option<Chart> {
    let mut tree = Tree::default();
    let interface = &lowering.interface;
    let names = (interface.params.iter().map(|p| &p.name))
        .chain(interface.outcomes.iter().map(|o| &o.name));
    tree.reserved = names.map(|n| global_of(&lowering.machine, n)).collect();
    for s in parsed {
        let top = tree.add(lowering, s, None);
        tree.top.push(top);
    }
    tree.check_names(lowering);
    tree.resolve_all(lowering);
    let start = match initial {
        Some((target, at)) => match tree.resolve(None, &target) {
            Ok(node) => node,
            Err(message) => {
                lowering.error(at, message);
                return None;
            }
        },
        None => *tree.top.first()?,
    };
    let mut flat = Flattening::new(&tree);
    let outermost = tree.outermost(start);
    let first = flat.variant(tree.descend(start), outermost);
    flat.run();
    Some(flat.finish(first))
}

/// A state as written, composite or atomic.
struct Node {
    name: String,
    /// `PLAY.SEARCH`: the flat states' names.
    path: String,
    parent: Option<usize>,
    children: Vec<usize>,
    id: Option<StateId>,
    at: usize,
    line: usize,
    entry: Vec<Action>,
    exit: Vec<Action>,
    internal: Vec<Action>,
    initial: Option<(Ref, usize)>,
    whens: Vec<When>,
}

/// A transition as written, its target found.
struct Written {
    label: Label,
    /// `when done`: fires from the composite's final sub-states only.
    done: bool,
    target: usize,
    /// `-> P.history` or `-> P.deep_history`: `target` is P, entered where it was left.
    history: Option<History>,
    line: usize,
    /// Its own actions: they run as it fires, after the OnExits.
    actions: Vec<Action>,
}

/// Which history a transition resumes (§3.2): the sub-state of the composite last active, or
/// the whole configuration inside it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum History {
    Shallow,
    Deep,
}

impl History {
    /// The path segment that names it after its composite's path.
    fn word(self) -> &'static str {
        match self {
            History::Shallow => "history",
            History::Deep => "deep_history",
        }
    }

    /// The machine variable lowering keeps it in: named after the composite's path, so that a
    /// trace's assignments say which (letters, digits and `_`; see [`Tree::name_histories`]).
    fn variable(self, path: &str) -> String {
        let path: String = path
            .chars()
            .map(|c| if c.is_alphanumeric() { c } else { '_' })
            .collect();
        format!("{path}_{}", self.word())
    }
}

/// The states as written, in file order (a composite before the states it holds).
#[derive(Default)]
struct Tree {
    nodes: Vec<Node>,
    top: Vec<usize>,
    /// Each node's transitions, in priority order; those that could not be read are reported
    /// and left out.
    written: Vec<Vec<Written>>,
    /// Each composite's `initial`, found among its states (else its first).
    first: Vec<Option<usize>>,
    /// The histories some transition resumes: only these are kept.
    histories: Vec<(usize, History)>,
    /// Each kept history's variable, told apart from every other name of the machine.
    variables: Vec<String>,
    /// Names a history's variable must not take: the globals the machine's parameters and
    /// outcomes become (`Dive_history` for a parameter `history` of `Dive`).
    reserved: Vec<String>,
}

impl Tree {
    fn add(&mut self, lowering: &mut Lowering<'_>, s: StateAst, parent: Option<usize>) -> usize {
        if [History::Shallow, History::Deep]
            .iter()
            .any(|h| h.word() == s.name)
        {
            lowering.error(
                s.at,
                format!(
                    "`{}` names a composite's history where states nest (`-> PLAY.{}`): \
                     call the state something else",
                    s.name, s.name
                ),
            );
        }
        if s.name.contains('.') {
            lowering.error(
                s.at,
                format!(
                    "`{}`: a state's name cannot hold `.` where states nest, since `.` \
                     separates a path (`PLAY.SEARCH`)",
                    s.name
                ),
            );
        }
        let path = match parent {
            Some(p) => format!("{}.{}", self.nodes[p].path, s.name),
            None => s.name.clone(),
        };
        let line = lowering.lines.line(s.at);
        let body = lowering.body(&s.name, s.members);
        let index = self.nodes.len();
        self.nodes.push(Node {
            name: s.name,
            path,
            parent,
            children: Vec::new(),
            id: s.id,
            at: s.at,
            line,
            entry: body.entry,
            exit: body.exit,
            internal: body.internal,
            initial: body.initial,
            whens: body.whens,
        });
        for inner in body.states {
            let child = self.add(lowering, inner, Some(index));
            self.nodes[index].children.push(child);
        }
        index
    }

    /// Names must tell siblings apart, and ids every state.
    fn check_names(&self, lowering: &mut Lowering<'_>) {
        let mut ids = HashSet::new();
        for node in &self.nodes {
            if let Some(id) = node.id {
                if !ids.insert(id) {
                    lowering.error(node.at, format!("state id #{id} is used twice"));
                }
            }
        }
        let scopes = std::iter::once((None, &self.top))
            .chain((0..self.nodes.len()).map(|n| (Some(n), &self.nodes[n].children)));
        for (owner, scope) in scopes {
            let mut seen = HashSet::new();
            for &child in scope {
                let node = &self.nodes[child];
                if !seen.insert(node.name.as_str()) {
                    let place = owner.map_or("at the top of the machine".to_string(), |o| {
                        format!("in `{}`", self.nodes[o].path)
                    });
                    lowering.error(
                        node.at,
                        format!("two states are named `{}` {place}", node.name),
                    );
                }
            }
        }
    }

    /// Reads every transition and every composite's `initial`.
    fn resolve_all(&mut self, lowering: &mut Lowering<'_>) {
        for n in 0..self.nodes.len() {
            let first = self.initial_of(lowering, n);
            self.first.push(first);
            let whens = std::mem::take(&mut self.nodes[n].whens);
            let written: Vec<Written> = whens
                .into_iter()
                .filter_map(|when| self.written(lowering, n, when))
                .collect();
            for w in &written {
                if let Some(h) = w.history {
                    if !self.histories.contains(&(w.target, h)) {
                        self.histories.push((w.target, h));
                    }
                }
            }
            self.written.push(written);
        }
        self.name_histories();
    }

    /// A variable for each history: `PLAY_history`, with a number after it where two paths
    /// would give one name (`A.B` and `A_B`).
    fn name_histories(&mut self) {
        for &(composite, history) in &self.histories {
            let base = history.variable(&self.nodes[composite].path);
            let mut name = base.clone();
            let mut n = 1;
            while self.variables.contains(&name) || self.reserved.contains(&name) {
                n += 1;
                name = format!("{base}{n}");
            }
            self.variables.push(name);
        }
    }

    /// Where leaving `composite` from `atomic` leaves it, as its `history`'s variable numbers
    /// places (0: nowhere, `atomic` is not inside it).
    fn place(&self, composite: usize, history: History, atomic: usize) -> i64 {
        let inside = match history {
            // The state of `composite`'s own on the way out.
            History::Shallow => self
                .chain(atomic)
                .find(|&n| self.nodes[n].parent == Some(composite)),
            History::Deep => Some(atomic).filter(|_| self.chain(atomic).any(|n| n == composite)),
        };
        let Some(inside) = inside else {
            return 0;
        };
        match history {
            History::Shallow => self.nodes[composite]
                .children
                .iter()
                .position(|&c| c == inside)
                .map_or(0, |k| k as i64 + 1),
            // Atomic states in file order: those inside `composite` before this one, plus one.
            History::Deep => {
                1 + (composite..inside)
                    .filter(|&n| self.nodes[n].children.is_empty())
                    .count() as i64
            }
        }
    }

    /// The variable of `composite`'s `history`.
    fn variable(&self, composite: usize, history: History) -> String {
        let at = self
            .histories
            .iter()
            .position(|&h| h == (composite, history));
        at.and_then(|k| self.variables.get(k))
            .cloned()
            .unwrap_or_else(|| history.variable(&self.nodes[composite].path))
    }

    fn initial_of(&self, lowering: &mut Lowering<'_>, n: usize) -> Option<usize> {
        let node = &self.nodes[n];
        let (target, at) = node.initial.as_ref()?;
        let found = match target {
            Ref::Name(path) => self.down(Some(n), path),
            Ref::Id(_) => self.resolve(Some(n), target),
        };
        match found {
            Ok(child) if self.nodes[child].parent == Some(n) => Some(child),
            Ok(other) => {
                lowering.error(
                    *at,
                    format!(
                        "the initial state of `{}` must be one of its own states, not `{}`",
                        node.path, self.nodes[other].path
                    ),
                );
                None
            }
            Err(message) => {
                lowering.error(*at, message);
                None
            }
        }
    }

    fn written(&self, lowering: &mut Lowering<'_>, n: usize, when: When) -> Option<Written> {
        let label = lowering.label(&when)?;
        let node = &self.nodes[n];
        let done = label == Expr::Name("done".into());
        if done && node.children.is_empty() {
            lowering.error(
                when.label_at,
                format!(
                    "`when done` belongs to a state that holds states (it fires once the one \
                     it is in is final); `{}` holds none",
                    node.path
                ),
            );
            return None;
        }
        if done
            && !node
                .children
                .iter()
                .any(|&c| self.nodes[c].children.is_empty() && self.nodes[c].whens.is_empty())
        {
            lowering.warn(
                when.label_at,
                format!(
                    "`when done` on `{}` never fires: no state directly in it is final (has no transition of its own)",
                    node.path
                ),
            );
        }
        let (target, history) = match &when.target {
            Ref::Name(path) => {
                let history = [History::Shallow, History::Deep]
                    .into_iter()
                    .find(|h| path.rsplit('.').next() == Some(h.word()));
                match (history, path.rsplit_once('.')) {
                    (Some(h), Some((composite, _))) => (Ref::Name(composite.to_string()), Some(h)),
                    _ => (when.target.clone(), None),
                }
            }
            Ref::Id(_) => (when.target.clone(), None),
        };
        match self.resolve(Some(n), &target) {
            Ok(target) if history.is_some() && self.nodes[target].children.is_empty() => {
                lowering.error(
                    when.target_at,
                    format!(
                        "`{}` holds no states, so it has no history to resume",
                        self.nodes[target].path
                    ),
                );
                None
            }
            Ok(target) => Some(Written {
                label,
                done,
                target,
                history,
                line: lowering.lines.line(when.at),
                actions: when.actions,
            }),
            Err(message) => {
                lowering.error(when.target_at, message);
                None
            }
        }
    }

    /// The states directly in `owner` (`None`: the machine's own).
    fn scope(&self, owner: Option<usize>) -> &[usize] {
        match owner {
            Some(o) => &self.nodes[o].children,
            None => &self.top,
        }
    }

    /// The state `path` names from inside `owner`: its first part one of `owner`'s states.
    fn down(&self, owner: Option<usize>, path: &str) -> Result<usize, String> {
        let mut at = owner;
        for part in path.split('.') {
            let found = self
                .scope(at)
                .iter()
                .copied()
                .find(|&c| self.nodes[c].name == part);
            match found {
                Some(next) => at = Some(next),
                None => {
                    return Err(match at {
                        Some(o) => {
                            format!("`{}` holds no state named `{part}`", self.nodes[o].path)
                        }
                        None => self.unknown(part),
                    })
                }
            }
        }
        at.ok_or_else(|| self.unknown(path))
    }

    /// The state a transition of `from` (or the machine's `initial`, from `None`) names: a
    /// path whose first part is a sibling of `from`, else a state around it, outwards, else
    /// the one state anywhere whose path ends so.
    fn resolve(&self, from: Option<usize>, target: &Ref) -> Result<usize, String> {
        let path = match target {
            Ref::Id(id) => {
                return self
                    .nodes
                    .iter()
                    .position(|n| n.id == Some(*id))
                    .ok_or_else(|| format!("there is no state #{id}"))
            }
            Ref::Name(path) => path,
        };
        let first = path.split('.').next().unwrap_or_default();
        let mut owner = from.and_then(|f| self.nodes[f].parent);
        loop {
            if self
                .scope(owner)
                .iter()
                .any(|&c| self.nodes[c].name == first)
            {
                return self.down(owner, path);
            }
            match owner {
                Some(o) => owner = self.nodes[o].parent,
                None => break,
            }
        }
        // Deeper in: as SCXML's ids, a name that is one state's alone names it from anywhere.
        let named: Vec<usize> = (0..self.nodes.len())
            .filter(|&n| {
                self.nodes[n].path == *path || self.nodes[n].path.ends_with(&format!(".{path}"))
            })
            .collect();
        match named.as_slice() {
            [one] => Ok(*one),
            [] => Err(self.unknown(path)),
            many => Err(format!(
                "`{path}` could be {}: write the path of the one meant",
                many.iter()
                    .map(|&n| format!("`{}`", self.nodes[n].path))
                    .collect::<Vec<_>>()
                    .join(" or ")
            )),
        }
    }

    fn unknown(&self, name: &str) -> String {
        match proclaim_syntax::nearest(self.nodes.iter().map(|n| n.path.as_str()), name) {
            Some(near) => format!("there is no state named `{name}`; did you mean `{near}`?"),
            None => format!("there is no state named `{name}`"),
        }
    }

    /// The atomic state entering `node` ends in: down through each composite's initial.
    fn descend(&self, mut node: usize) -> usize {
        while let Some(&child) = self.nodes[node].children.first() {
            node = self.first[node].unwrap_or(child);
        }
        node
    }

    /// The states a history of `composite` may resume, in the order its variable numbers
    /// them from 1: its own states (shallow), or every atomic state inside it (deep).
    fn resumed(&self, composite: usize, history: History) -> Vec<usize> {
        match history {
            History::Shallow => self.nodes[composite].children.clone(),
            History::Deep => (composite..self.nodes.len())
                .filter(|&n| self.nodes[n].children.is_empty())
                .filter(|&n| self.chain(n).any(|a| a == composite))
                .collect(),
        }
    }

    /// `node` and the states around it, innermost first.
    fn chain(&self, node: usize) -> impl Iterator<Item = usize> + '_ {
        std::iter::successors(Some(node), |&n| self.nodes[n].parent)
    }

    /// The composites a move below `domain` into `atomic` enters, outermost first.
    fn entered(&self, atomic: usize, domain: Option<usize>) -> Vec<usize> {
        let mut entered: Vec<usize> = self
            .chain(atomic)
            .take_while(|&n| Some(n) != domain)
            .filter(|&n| !self.nodes[n].children.is_empty())
            .collect();
        entered.reverse();
        entered
    }

    /// Whether a transition written on `node` tests the time: a composite's then counts from
    /// its entry, so the arrivals that enter it are told apart from those that do not.
    fn timed(&self, node: usize) -> bool {
        self.written[node].iter().any(|w| {
            w.label
                .calls()
                .iter()
                .any(|(f, _)| TIME_TESTS.iter().any(|(t, _)| t == f))
        })
    }

    fn outermost(&self, node: usize) -> usize {
        self.chain(node).last().unwrap_or(node)
    }

    /// The innermost state around both `source` and `target` but neither of them (`None`:
    /// the machine): what a transition between them leaves stays below it (§3.2).
    fn domain(&self, source: usize, target: usize) -> Option<usize> {
        let around: HashSet<usize> = self.chain(target).skip(1).collect();
        self.chain(source).skip(1).find(|n| around.contains(n))
    }
}

/// One flat state: an atomic state entered from `top` down.
struct Flat {
    atomic: usize,
    top: usize,
    id: StateId,
    arms: Vec<FlatArm>,
}

struct FlatArm {
    label: Label,
    /// The label as written, when the arm's is not (`done`, a history's place).
    written: Option<Label>,
    /// The flat state it enters (an index into `Flattening::flats`).
    target: usize,
    line: usize,
    leaving: Option<Vec<Action>>,
    /// The composite it was written on, when not on the atomic state itself.
    written_on: Option<usize>,
    /// The composites it enters, outermost first.
    enters: Vec<usize>,
}

/// Flat states made as transitions reach them, from the initial one.
struct Flattening<'t> {
    tree: &'t Tree,
    flats: Vec<Flat>,
    variants: HashMap<(usize, usize), usize>,
    queue: VecDeque<usize>,
    /// Each atomic state's id: as written, else numbered; a further flat state of the same
    /// atomic state takes a fresh one.
    ids: Vec<Option<StateId>>,
    /// Whether each atomic state has a flat state yet.
    made: Vec<bool>,
    taken: HashSet<StateId>,
    next: StateId,
}

impl<'t> Flattening<'t> {
    fn new(tree: &'t Tree) -> Flattening<'t> {
        let taken: HashSet<StateId> = tree.nodes.iter().filter_map(|n| n.id).collect();
        let mut flattening = Flattening {
            tree,
            flats: Vec::new(),
            variants: HashMap::new(),
            queue: VecDeque::new(),
            ids: Vec::new(),
            made: vec![false; tree.nodes.len()],
            taken,
            next: 1,
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

    /// The flat state of `atomic` entered from `top` down. Entries that run nothing and
    /// start no composite's time are not told apart, so a chart whose composites have no
    /// OnEntry and test no time gets one flat state per atomic state.
    fn variant(&mut self, atomic: usize, top: usize) -> usize {
        let tree = self.tree;
        let entered: Vec<usize> = tree.chain(atomic).take_while(|&n| n != top).collect();
        let top = std::iter::once(top)
            .chain(entered.into_iter().rev())
            .find(|&n| n == atomic || !tree.nodes[n].entry.is_empty() || tree.timed(n))
            .unwrap_or(atomic);
        if let Some(&flat) = self.variants.get(&(atomic, top)) {
            return flat;
        }
        // The first flat state of an atomic state takes its id; the others fresh ones.
        let id = match self.ids[atomic].take() {
            Some(id) => id,
            None => self.fresh(),
        };
        self.made[atomic] = true;
        self.flats.push(Flat {
            atomic,
            top,
            id,
            arms: Vec::new(),
        });
        let flat = self.flats.len() - 1;
        self.variants.insert((atomic, top), flat);
        self.queue.push_back(flat);
        flat
    }

    /// Makes every flat state a transition reaches, then one for each atomic state none
    /// reached (so that `check` and `verify` can say it is never entered).
    fn run(&mut self) {
        let tree = self.tree;
        let mut from = 0;
        loop {
            while let Some(flat) = self.queue.pop_front() {
                let arms = self.arms(self.flats[flat].atomic);
                self.flats[flat].arms = arms;
            }
            let missed = (from..tree.nodes.len())
                .find(|&n| tree.nodes[n].children.is_empty() && !self.made[n]);
            match missed {
                Some(n) => {
                    from = n + 1;
                    self.variant(n, tree.outermost(n));
                }
                None => return,
            }
        }
    }

    /// The transitions tried in `atomic`: its own, then those of each state around it,
    /// outwards (the more deeply nested source wins, as in SCXML).
    fn arms(&mut self, atomic: usize) -> Vec<FlatArm> {
        let tree = self.tree;
        let final_state = tree.written[atomic].is_empty();
        let mut arms = Vec::new();
        for source in tree.chain(atomic) {
            for w in &tree.written[source] {
                if w.done && !(final_state && tree.nodes[atomic].parent == Some(source)) {
                    continue;
                }
                let domain = tree.domain(source, w.target);
                let left: Vec<usize> = tree
                    .chain(atomic)
                    .take_while(|&n| Some(n) != domain)
                    .collect();
                let mut leaving = self.leaving(atomic, &left);
                if !w.actions.is_empty() {
                    let exits = leaving.unwrap_or_else(|| tree.nodes[atomic].exit.clone());
                    leaving = Some(exits.into_iter().chain(w.actions.iter().cloned()).collect());
                }
                let written_on = (source != atomic).then_some(source);
                for (label, target) in self.targets(atomic, w, domain, &left) {
                    let enters = tree.entered(self.flats[target].atomic, domain);
                    arms.push(FlatArm {
                        written: (label != w.label).then(|| w.label.clone()),
                        label,
                        target,
                        line: w.line,
                        leaving: leaving.clone(),
                        written_on,
                        enters,
                    });
                }
            }
        }
        arms
    }

    /// The label and flat target of each arm a transition written as `w` lowers to, tried in
    /// this order, when it fires from `atomic`, leaving the states in `left` and entering below
    /// `domain`.
    fn targets(
        &mut self,
        atomic: usize,
        w: &Written,
        domain: Option<usize>,
        left: &[usize],
    ) -> Vec<(Label, usize)> {
        let tree = self.tree;
        let top = tree
            .chain(w.target)
            .find(|&n| tree.nodes[n].parent == domain)
            .unwrap_or(w.target);
        let label = if w.done { Label::TRUE } else { w.label.clone() };
        let mut arms = Vec::new();
        match w.history {
            // Leaving the composite notes where this very move leaves it: it comes back there.
            Some(history) if left.contains(&w.target) => {
                let place = tree.place(w.target, history, atomic);
                let resumed = tree.resumed(w.target, history);
                let back = usize::try_from(place - 1).map_or(w.target, |k| resumed[k]);
                arms.push((label, self.variant(tree.descend(back), top)));
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
                    arms.push((label, self.variant(tree.descend(resumed), top)));
                }
            }
            None => {}
        }
        arms.push((label, self.variant(tree.descend(w.target), top)));
        arms
    }

    /// What leaving `atomic` and the states around it in `left` (innermost first) runs: where
    /// each composite with a history was left is noted first (SCXML notes it before any exit
    /// runs), then their OnExits, innermost first. `None` when that is `atomic`'s own OnExit.
    fn leaving(&self, atomic: usize, left: &[usize]) -> Option<Vec<Action>> {
        let tree = self.tree;
        let mut noted = Vec::new();
        for &(composite, history) in &tree.histories {
            if !left.contains(&composite) {
                continue;
            }
            let at = tree.place(composite, history, atomic);
            noted.push(Action::Statement(Statement::Assign {
                name: tree.variable(composite, history),
                value: Expr::Int(at),
            }));
        }
        let more = left[1..].iter().any(|&n| !tree.nodes[n].exit.is_empty());
        if noted.is_empty() && !more {
            return None;
        }
        noted.extend(
            left.iter()
                .flat_map(|&n| tree.nodes[n].exit.iter().cloned()),
        );
        Some(noted)
    }

    fn finish(mut self, initial: usize) -> Chart {
        let tree = self.tree;
        let composites_of: Vec<Option<usize>> = {
            let mut next = 0;
            tree.nodes
                .iter()
                .map(|n| {
                    (!n.children.is_empty()).then(|| {
                        next += 1;
                        next - 1
                    })
                })
                .collect()
        };
        let composites = tree
            .nodes
            .iter()
            .filter(|n| !n.children.is_empty())
            .map(|n| Composite {
                name: n.path.clone(),
                parent: n.parent.and_then(|p| composites_of[p]),
                line: n.line,
                on_entry: n.entry.clone(),
                on_exit: n.exit.clone(),
                internal: n.internal.clone(),
            })
            .collect();
        let mut order: Vec<usize> = (0..self.flats.len()).collect();
        order.sort_by_key(|&f| self.flats[f].atomic);
        let ids: Vec<StateId> = self.flats.iter().map(|f| f.id).collect();
        let mut states = Vec::new();
        let mut transitions = Vec::new();
        for &f in &order {
            let flat = &mut self.flats[f];
            states.push(flat_state(tree, flat));
            for mut arm in std::mem::take(&mut flat.arms) {
                // A time test counts from the entry of the state its transition was written
                // on: a composite's, else its flat state's arrival.
                let written_on = arm.written_on.and_then(|n| composites_of[n]);
                arm.label.set_time_clocks(written_on);
                transitions.push(Transition {
                    source: flat.id,
                    target: ids[arm.target],
                    label: arm.label,
                    line: arm.line,
                    leaving: arm.leaving,
                    composite: written_on,
                    enters: arm
                        .enters
                        .iter()
                        .filter_map(|&n| composites_of[n])
                        .collect(),
                    written: arm.written,
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

/// The flat state: arriving runs the OnEntry of each state entered, outermost first; staying
/// runs the Internal of each state the machine is in, outermost first; its own OnExit is the
/// atomic state's (transitions that leave more carry their own).
fn flat_state(tree: &Tree, flat: &Flat) -> State {
    let node = &tree.nodes[flat.atomic];
    let mut around: Vec<usize> = tree.chain(flat.atomic).collect();
    around.reverse();
    let entered: Vec<usize> = around
        .iter()
        .copied()
        .skip_while(|&n| n != flat.top)
        .collect();
    State {
        id: flat.id,
        name: node.path.clone(),
        on_entry: entered
            .iter()
            .flat_map(|&n| tree.nodes[n].entry.iter().cloned())
            .collect(),
        on_exit: node.exit.clone(),
        internal: around
            .iter()
            .flat_map(|&n| tree.nodes[n].internal.iter().cloned())
            .collect(),
        line: node.line,
        arrives_through: entered.len().saturating_sub(1),
    }
}
