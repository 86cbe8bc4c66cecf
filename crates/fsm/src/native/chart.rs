//! A chart read as written (`docs/spec/behaviour.md` §3.2): its states as a tree, each
//! transition's target and history found, names checked; and the walks over that tree that
//! lowering needs (what a move enters and leaves, which state is active, when `done` holds).
//! `flatten.rs` lowers it to the flat machine every back end already runs, so their traces
//! agree by construction.

use super::ast::{Initials, Ref, StateAst};
use super::flatten::Flattening;
use super::{Lowering, When};
use crate::code::Expr;
use crate::interface::global_of;
use crate::label::{Label, TIME_TESTS};
use crate::model::{Action, Composite, State, StateId, Transition};
use std::collections::{HashMap, HashSet};

/// `in(STATE)` in a label: whether the machine is in that state (SCXML's `In`), which the
/// flat state a transition is lowered in decides, so no back end reads it.
pub(super) const IN_STATE: &str = "in";

pub(super) fn in_state_usage() -> String {
    format!("`{IN_STATE}(…)` takes one state, by its name or path: `{IN_STATE}(PLAY.HEAD.TRACK)`")
}

/// What a chart lowers to.
pub(crate) struct Chart {
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
    initial: Option<Initials>,
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
        Some(written) => tree.initials(lowering, None, &written)?,
        None => vec![*tree.top.first()?],
    };
    let mut flat = Flattening::new(&tree);
    let first = flat.enter(&[], None, &start);
    flat.run();
    if let Some(at) = flat.too_many {
        lowering.error(
            at,
            format!(
                "its regions' transitions make more than {} combinations in one state: split it",
                super::flatten::MOST_ARMS
            ),
        );
        return None;
    }
    for (n, id) in flat.ids_not_kept() {
        let node = &tree.nodes[n];
        lowering.warn(
            node.at,
            format!(
                "`#{id}` names `{}` in this file only: a state inside a region runs as one of \
                 its combinations with the other regions' states, which are numbered afresh, \
                 so a trace will not show #{id}",
                node.path
            ),
        );
    }
    Some(flat.finish(first))
}

/// A state as written, composite or atomic.
pub(super) struct Node {
    pub name: String,
    /// `PLAY.SEARCH`: the flat states' names.
    pub path: String,
    pub parent: Option<usize>,
    pub children: Vec<usize>,
    pub id: Option<StateId>,
    pub at: usize,
    pub line: usize,
    pub entry: Vec<Action>,
    pub exit: Vec<Action>,
    pub internal: Vec<Action>,
    /// The states `initial` names, each where it is written.
    initial: Option<Initials>,
    whens: Vec<When>,
    /// `parallel`: the states it holds are regions, all active while it is.
    pub parallel: bool,
}

/// The most places a deep history may note: the configurations of the states inside its
/// composite (one atomic state in each region), as many as a state's arms may be.
pub(super) const MOST_CONFIGURATIONS: usize = super::flatten::MOST_ARMS;

/// A transition as written, its target found.
pub(super) struct Written {
    pub label: Label,
    /// `when done`: fires from the composite's final sub-states only.
    pub done: bool,
    pub target: usize,
    /// Further targets (`-> P.A.X, P.B.Y`): with `target`, a state in each of several regions,
    /// entered together (SCXML's `target="X Y"`).
    pub also: Vec<usize>,
    /// `-> P.history` or `-> P.deep_history`: `target` is P, entered where it was left.
    pub history: Option<History>,
    pub line: usize,
    /// Its own actions: they run as it fires, after the OnExits.
    pub actions: Vec<Action>,
    /// It has no target (`when p { … }`): it leaves and enters nothing, and `target` is the
    /// state it was written on.
    pub stays: bool,
}

impl Written {
    /// Every state it names as a target, the first first.
    pub fn targets(&self) -> Vec<usize> {
        std::iter::once(self.target)
            .chain(self.also.iter().copied())
            .collect()
    }
}

/// Which history a transition resumes (§3.2): the sub-state of the composite last active, or
/// the whole configuration inside it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum History {
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
pub(super) struct Tree {
    pub nodes: Vec<Node>,
    top: Vec<usize>,
    /// Each node's transitions, in priority order; those that could not be read are reported
    /// and left out.
    pub written: Vec<Vec<Written>>,
    /// The states each composite's `initial` names (else it enters its first): one of its
    /// own, a deeper one, or one in each of several regions.
    first: Vec<Option<Vec<usize>>>,
    /// The histories some transition resumes: only these are kept.
    pub histories: Vec<(usize, History)>,
    /// Each kept history's variable, told apart from every other name of the machine.
    variables: Vec<String>,
    /// Each kept deep history's places by their states, so that noting one on every way out
    /// does not list them all again.
    places: Vec<HashMap<Vec<usize>, usize>>,
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
        let parallel = s.parallel;
        let body = lowering.body(&s.name, s.members);
        if parallel && body.states.is_empty() {
            lowering.error(
                s.at,
                format!("parallel state `{path}` holds no regions: write a state in it for each"),
            );
        }
        if let (true, Some(initial)) = (parallel, &body.initial) {
            lowering.error(
                initial[0].1,
                format!(
                    "`{path}` is parallel: every region in it is entered, so it has no `initial`"
                ),
            );
        }
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
            initial: body.initial.filter(|_| !parallel),
            whens: body.whens,
            parallel,
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
        self.places = (self.histories.iter())
            .map(|&(composite, history)| match history {
                History::Shallow => HashMap::new(),
                History::Deep => (self.resumed(composite, history).into_iter())
                    .enumerate()
                    .map(|(k, states)| (states, k))
                    .collect(),
            })
            .collect();
    }

    /// Where leaving `composite` from the atomic states `atomics` leaves it, as its
    /// `history`'s variable numbers places (0: nowhere, none of them is inside it): the state
    /// of its own they are in (shallow), or the configuration of them inside it (deep).
    pub(super) fn place(&self, composite: usize, history: History, atomics: &[usize]) -> i64 {
        let inside: Vec<usize> = (atomics.iter().copied())
            .filter(|&a| self.chain(a).any(|n| n == composite))
            .collect();
        let place = match history {
            History::Shallow => inside.first().and_then(|&a| {
                let own = self
                    .chain(a)
                    .find(|&n| self.nodes[n].parent == Some(composite))?;
                self.nodes[composite]
                    .children
                    .iter()
                    .position(|&c| c == own)
            }),
            History::Deep => {
                let kept = self
                    .histories
                    .iter()
                    .position(|&h| h == (composite, history));
                match kept.and_then(|k| self.places.get(k)) {
                    Some(places) => places.get(&inside).copied(),
                    None => (self.resumed(composite, history).iter()).position(|c| *c == inside),
                }
            }
        };
        place.map_or(0, |k| k as i64 + 1)
    }

    /// The variable of `composite`'s `history`.
    pub(super) fn variable(&self, composite: usize, history: History) -> String {
        let at = self
            .histories
            .iter()
            .position(|&h| h == (composite, history));
        at.and_then(|k| self.variables.get(k))
            .cloned()
            .unwrap_or_else(|| history.variable(&self.nodes[composite].path))
    }

    fn initial_of(&self, lowering: &mut Lowering<'_>, n: usize) -> Option<Vec<usize>> {
        let written = self.nodes[n].initial.as_ref()?;
        self.initials(lowering, Some(n), written)
    }

    /// The states an `initial` of `owner` (the machine's, for `None`) names: each inside it,
    /// and several only one in each of several regions (SCXML's `initial="a b"`); `None` once
    /// why not is reported.
    pub(super) fn initials(
        &self,
        lowering: &mut Lowering<'_>,
        owner: Option<usize>,
        written: &[(Ref, usize)],
    ) -> Option<Vec<usize>> {
        let mut found: Vec<usize> = Vec::new();
        for (target, at) in written {
            let resolved = match (owner, target) {
                (Some(n), Ref::Name(path)) => self.down(Some(n), path),
                _ => self.resolve(owner, target),
            };
            let state = match resolved {
                Ok(state) => state,
                Err(message) => {
                    lowering.error(*at, message);
                    return None;
                }
            };
            if let Some(n) = owner.filter(|&n| !self.chain(state).skip(1).any(|c| c == n)) {
                let (path, other) = (&self.nodes[n].path, &self.nodes[state].path);
                lowering.error(
                    *at,
                    format!(
                        "the initial state of `{path}` must be a state inside it, not `{other}`"
                    ),
                );
                return None;
            }
            if let Some(&other) = found.iter().find(|&&o| !self.apart_in_regions(o, state)) {
                lowering.error(
                    *at,
                    format!(
                        "`{}` and `{}` are not in different regions of a parallel state: several initial states enter one state in each region",
                        self.nodes[other].path, self.nodes[state].path
                    ),
                );
                return None;
            }
            found.push(state);
        }
        Some(found)
    }

    /// Whether every `in(S)` of `label`, written on `n`, names a state as a target does (each
    /// flat state then decides it, `flatten.rs`); what does not is reported.
    fn in_states_named(
        &self,
        lowering: &mut Lowering<'_>,
        n: usize,
        when: &When,
        label: &Label,
    ) -> bool {
        let mut unresolved = None;
        label.clone().replace_calls(&mut |function, arguments| {
            if function != IN_STATE {
                return None;
            }
            let state = match arguments {
                [Expr::Name(path)] => self.resolve(Some(n), &Ref::Name(path.clone())),
                _ => Err(in_state_usage()),
            };
            if let Err(message) = state {
                let shown = arguments
                    .iter()
                    .map(ToString::to_string)
                    .collect::<Vec<_>>();
                unresolved.get_or_insert(format!("`{IN_STATE}({})`: {message}", shown.join(", ")));
            }
            Some(Expr::Bool(false))
        });
        match unresolved {
            Some(message) => {
                lowering.error(when.label_at, message);
                false
            }
            None => true,
        }
    }

    fn written(&self, lowering: &mut Lowering<'_>, n: usize, when: When) -> Option<Written> {
        let label = lowering.label(&when)?;
        if !self.in_states_named(lowering, n, &when, &label) {
            return None;
        }
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
            && !node.parallel
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
        if done && when.target.is_none() {
            lowering.error(
                when.label_at,
                "`when done` needs a target: `done` stays true in a final state, so one that stays would fire in every round".into(),
            );
            return None;
        }
        // No target: it stays, in the state it was written on.
        let (target, history) = match &when.target {
            Some(written) => self.target(lowering, n, written, when.target_at)?,
            None => (n, None),
        };
        let also = self.further_targets(lowering, n, &when, target)?;
        Some(Written {
            label,
            done,
            target,
            also,
            history,
            line: lowering.lines.line(when.at),
            actions: when.actions,
            stays: when.target.is_none(),
        })
    }

    /// The further targets of a transition written on `n` whose first is `first`: each a state
    /// in another region of a parallel state than every other target (SCXML: together they are
    /// a configuration), none a history as written (not even a parallel state's, which is
    /// entering it); `None` once why not is reported.
    fn further_targets(
        &self,
        lowering: &mut Lowering<'_>,
        n: usize,
        when: &When,
        first: usize,
    ) -> Option<Vec<usize>> {
        let names_history = |r: &Ref| {
            matches!(r, Ref::Name(path) if [History::Shallow, History::Deep]
                .iter()
                .any(|h| path.rsplit('.').next() == Some(h.word())))
        };
        let first_written = when.target.as_ref().filter(|_| !when.also.is_empty());
        if first_written.is_some_and(names_history) {
            let at = when.target_at;
            lowering.error(at, "a history is a target of its own: it resumes one state, and another target cannot join it".into());
            return None;
        }
        let mut all = vec![first];
        for (written, at) in &when.also {
            if names_history(written) {
                lowering.error(*at, "a history is a target of its own: it resumes one state, and another target cannot join it".into());
                return None;
            }
            let (target, _) = self.target(lowering, n, written, *at)?;
            if let Some(&other) = all.iter().find(|&&o| !self.apart_in_regions(o, target)) {
                lowering.error(
                    *at,
                    format!(
                        "`{}` and `{}` are not in different regions of a parallel state: several targets enter one state in each region",
                        self.nodes[other].path, self.nodes[target].path
                    ),
                );
                return None;
            }
            all.push(target);
        }
        Some(all.split_off(1))
    }

    /// Whether `a` and `b` may be active together as targets: neither holds the other, and the
    /// innermost state around both is parallel (they are in two of its regions).
    fn apart_in_regions(&self, a: usize, b: usize) -> bool {
        let around_a: HashSet<usize> = self.chain(a).collect();
        let common = self.chain(b).find(|n| around_a.contains(n));
        common.is_some_and(|c| c != a && c != b && self.nodes[c].parallel)
    }

    /// The state a transition written on `n` names as its target (at `at`), and the history it
    /// resumes there (`-> P.history`); `None` once why not is reported.
    fn target(
        &self,
        lowering: &mut Lowering<'_>,
        n: usize,
        written: &Ref,
        at: usize,
    ) -> Option<(usize, Option<History>)> {
        let (target, history) = match written {
            Ref::Name(path) => {
                let history = [History::Shallow, History::Deep]
                    .into_iter()
                    .find(|h| path.rsplit('.').next() == Some(h.word()));
                match (history, path.rsplit_once('.')) {
                    (Some(h), Some((composite, _))) => (Ref::Name(composite.to_string()), Some(h)),
                    _ => (written.clone(), None),
                }
            }
            Ref::Id(_) => (written.clone(), None),
        };
        match self.resolve(Some(n), &target) {
            Ok(target) if history.is_some() && self.nodes[target].children.is_empty() => {
                lowering.error(
                    at,
                    format!(
                        "`{}` holds no states, so it has no history to resume",
                        self.nodes[target].path
                    ),
                );
                None
            }
            // Every region of a parallel state is active while it is: resuming them all at
            // their initial (SCXML's shallow history) is entering it.
            Ok(target) if history == Some(History::Shallow) && self.nodes[target].parallel => {
                Some((target, None))
            }
            // A deep history around regions notes a configuration, one state in each: a
            // variable of a place each, bounded.
            Ok(target)
                if history == Some(History::Deep)
                    && self.resumed(target, History::Deep).len() > MOST_CONFIGURATIONS =>
            {
                lowering.error(
                    at,
                    format!(
                        "`{}` holds more than {MOST_CONFIGURATIONS} configurations of states for a deep history to resume: resume its own state (`{}.history`)",
                        self.nodes[target].path, self.nodes[target].path
                    ),
                );
                None
            }
            Ok(target) => Some((target, history)),
            Err(message) => {
                lowering.error(at, message);
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
    pub(super) fn resolve(&self, from: Option<usize>, target: &Ref) -> Result<usize, String> {
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

    /// The places a history of `composite` may resume, in the order its variable numbers them
    /// from 1, each the states entered together: its own states (shallow); every atomic state
    /// inside it (deep), or, where it holds regions, every configuration of them (one atomic
    /// state in each region), in file order.
    pub(super) fn resumed(&self, composite: usize, history: History) -> Vec<Vec<usize>> {
        match history {
            History::Shallow => (self.nodes[composite].children.iter())
                .map(|&c| vec![c])
                .collect(),
            History::Deep => {
                let mut configurations = self.configurations(composite);
                configurations.truncate(MOST_CONFIGURATIONS + 1);
                configurations
            }
        }
    }

    /// Every configuration of atomic states inside `node` (itself, when atomic), in file
    /// order; cut short once past [`MOST_CONFIGURATIONS`].
    fn configurations(&self, node: usize) -> Vec<Vec<usize>> {
        let n = &self.nodes[node];
        if n.children.is_empty() {
            return vec![vec![node]];
        }
        if !n.parallel {
            let each = n.children.iter().flat_map(|&c| self.configurations(c));
            return each.take(MOST_CONFIGURATIONS + 1).collect();
        }
        let mut out: Vec<Vec<usize>> = vec![Vec::new()];
        for &region in &n.children {
            let each = self.configurations(region);
            out = (out.iter())
                .flat_map(|prefix| each.iter().map(move |c| [prefix.as_slice(), c].concat()))
                .take(MOST_CONFIGURATIONS + 1)
                .collect();
        }
        out
    }

    /// `node` and the states around it, innermost first.
    pub(super) fn chain(&self, node: usize) -> impl Iterator<Item = usize> + '_ {
        std::iter::successors(Some(node), |&n| self.nodes[n].parent)
    }

    /// Whether a transition written on `node` tests the time: a composite's then counts from
    /// its entry, so the arrivals that enter it are told apart from those that do not.
    pub(super) fn timed(&self, node: usize) -> bool {
        self.written[node].iter().any(|w| {
            w.label
                .calls()
                .iter()
                .any(|(f, _)| TIME_TESTS.iter().any(|(t, _)| t == f))
        })
    }

    pub(super) fn outermost(&self, node: usize) -> usize {
        self.chain(node).last().unwrap_or(node)
    }

    /// The innermost state around `source` and every one of `targets` but none of them, and
    /// not parallel (`None`: the machine): what a transition between them leaves stays below
    /// it (§3.2). A parallel state is never one, so a move between its regions leaves it.
    pub(super) fn domain(&self, source: usize, targets: &[usize]) -> Option<usize> {
        let around: Vec<HashSet<usize>> = (targets.iter())
            .map(|&t| self.chain(t).skip(1).collect())
            .collect();
        self.chain(source)
            .skip(1)
            .find(|&n| around.iter().all(|a| a.contains(&n)) && !self.nodes[n].parallel)
    }

    /// Whether `node` is an atomic state in a region: a flat state is one of each region's,
    /// so it is kept as written (for drawing) with a clock of its own, which the other
    /// regions' moves do not restart.
    pub(super) fn in_region(&self, node: usize) -> bool {
        self.nodes[node].children.is_empty()
            && self.chain(node).skip(1).any(|n| self.nodes[n].parallel)
    }

    /// The states a move below `domain` to `targets` (one state, or one in each of several
    /// regions) enters, in file order: those around each target below `domain`, the other
    /// regions of each parallel state among them (those no target is in) at their initial, and
    /// each target and its initial states down.
    pub(super) fn entering(&self, domain: Option<usize>, targets: &[usize]) -> Vec<usize> {
        let mut path: Vec<usize> = (targets.iter())
            .flat_map(|&t| self.chain(t).take_while(move |&n| Some(n) != domain))
            .collect();
        path.sort_unstable();
        path.dedup();
        let mut out = path.clone();
        for &n in path.iter().filter(|n| !targets.contains(n)) {
            if self.nodes[n].parallel {
                for &region in &self.nodes[n].children {
                    if !path.contains(&region) {
                        out.push(region);
                        self.default_below(region, &mut out);
                    }
                }
            }
        }
        for &t in targets {
            self.default_below(t, &mut out);
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    /// What entering `node` enters below it: its initial state down, or every region.
    fn default_below(&self, node: usize, out: &mut Vec<usize>) {
        let n = &self.nodes[node];
        let named = self.first.get(node).and_then(Option::as_ref);
        let inner: Vec<usize> = match (n.parallel, n.children.first(), named) {
            (_, None, _) => return,
            (true, Some(_), _) => n.children.clone(),
            // Its `initial`: the states around each it names below it are entered too.
            (false, Some(_), Some(named)) => {
                out.extend(self.entering(Some(node), named));
                return;
            }
            (false, Some(&first), None) => vec![first],
        };
        for child in inner {
            out.push(child);
            self.default_below(child, out);
        }
    }

    /// The active states strictly inside `domain` (`None`: every active state) when the
    /// atomic states `atomics` are, in file order.
    pub(super) fn active_inside(&self, atomics: &[usize], domain: Option<usize>) -> Vec<usize> {
        let inside = |a: usize| domain.is_none_or(|d| self.chain(a).any(|n| n == d));
        let mut out: Vec<usize> = atomics
            .iter()
            .filter(|&&a| inside(a))
            .flat_map(|&a| self.chain(a).take_while(move |&n| Some(n) != domain))
            .collect();
        out.sort_unstable();
        out.dedup();
        out
    }

    /// The state directly in `node` that is active when `atomics` are.
    pub(super) fn active_child(&self, atomics: &[usize], node: usize) -> Option<usize> {
        let a = self.atomic_inside(atomics, node)?;
        self.chain(a).find(|&n| self.nodes[n].parent == Some(node))
    }

    /// The active atomic state inside `node` (the first, where it holds regions).
    pub(super) fn atomic_inside(&self, atomics: &[usize], node: usize) -> Option<usize> {
        atomics
            .iter()
            .copied()
            .find(|&a| self.chain(a).any(|n| n == node))
    }

    /// Whether `node`'s `when done` fires when `atomics` are active: its active state is final,
    /// or, for a parallel state, every region is (§3.2).
    pub(super) fn done_in(&self, atomics: &[usize], node: usize) -> bool {
        let n = &self.nodes[node];
        if n.children.is_empty() {
            return self.written[node].is_empty();
        }
        if n.parallel {
            return n.children.iter().all(|&r| self.done_in(atomics, r));
        }
        self.active_child(atomics, node)
            .is_some_and(|c| self.nodes[c].children.is_empty() && self.written[c].is_empty())
    }
}
