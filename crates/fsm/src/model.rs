//! The machine model: states with three activities, transitions in priority order, labels.

use crate::code::Statement;
use crate::interface::Interface;
use crate::label::Label;

/// A state's identifier as written in its file (T/A ids, Qfsm codes). Names may repeat; ids do
/// not.
pub type StateId = i64;

#[derive(Clone, Debug, Default, PartialEq)]
pub struct Machine {
    pub name: String,
    /// What the file said of the machine beyond its name (a Qfsm `name` attribute that is not
    /// the file's name); empty when nothing.
    pub description: String,
    pub states: Vec<State>,
    /// Every transition; those of one source state are in priority order (first = tried first).
    pub transitions: Vec<Transition>,
    pub initial: StateId,
    /// Transitions of the original file whose label could not be read: not run, but kept so
    /// that an import can write them down (as comments) instead of losing them.
    pub unread: Vec<UnreadTransition>,
    /// The composite states of a machine written with nested states, outermost first. Its
    /// `states` are then the flat states it lowers to (`native/chart.rs`), each named by its
    /// path (`PLAY.SEARCH`); empty for a flat machine.
    pub composites: Vec<Composite>,
    /// The parameters a start gives it and the outcomes its final states announce (§3.3),
    /// as declared; its own code already reads and sets them as the globals they become.
    pub interface: Interface,
}

/// A state that holds states (`docs/spec/behaviour.md` §3.2), kept after lowering for what
/// shows the nesting (`draw`'s clusters) and for naming a transition written on it.
#[derive(Clone, Debug, PartialEq)]
pub struct Composite {
    /// Its path, as the names of the states inside it begin (`PLAY`, `PLAY.DIVE`).
    pub name: String,
    /// The composite it is in, an index into `Machine::composites`.
    pub parent: Option<usize>,
    pub line: usize,
    /// Its own activities, as written: lowering runs them as part of the flat states'.
    pub on_entry: Vec<Action>,
    pub on_exit: Vec<Action>,
    pub internal: Vec<Action>,
    /// An atomic state of a region, kept as written and for its clock (the other regions'
    /// moves do not restart it): it holds no states, and draws as a state.
    pub atomic: bool,
    /// A parallel state: the states directly in it are regions.
    pub parallel: bool,
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnreadTransition {
    pub source: StateId,
    pub target: StateId,
    /// The label as written.
    pub label: String,
    /// Why it could not be read.
    pub reason: String,
    pub line: usize,
}

impl Machine {
    /// The clocks an arrival into flat state `state` started (indices into
    /// [`Machine::composites`], outermost first): exact for every clock a time test reads,
    /// since lowering keeps apart the arrivals that start one (`native/flatten.rs`).
    pub fn arrival_enters(&self, state: &State) -> Vec<usize> {
        state.arrival_clocks.clone()
    }

    /// The paths of the atomic states flat state `state` is: its name, or in a chart one for
    /// each region of a parallel state (`PLAY.HEAD.LEFT, PLAY.BODY.SEARCH`, §3.2).
    pub fn atomic_paths<'s>(&self, state: &'s State) -> Vec<&'s str> {
        match self.composites.is_empty() {
            true => vec![state.name.as_str()],
            false => state.name.split(", ").collect(),
        }
    }

    /// Whether the machine in flat state `state` is in the state `path` names: one of its
    /// atomic states, or in a chart a state around one.
    pub fn state_is_in(&self, state: &State, path: &str) -> bool {
        state.name == path
            || self.atomic_paths(state).into_iter().any(|p| {
                p == path
                    || p.strip_prefix(path)
                        .is_some_and(|rest| rest.starts_with('.'))
            })
    }

    /// Every action that can run, in file order: every state's, then what transitions run
    /// as they fire that their states do not (a transition's own actions; a nested state's
    /// composites' OnExits), which the lowered transitions carry; an action may come twice.
    pub fn actions(&self) -> impl Iterator<Item = &Action> + '_ {
        self.states
            .iter()
            .flat_map(|s| s.on_entry.iter().chain(&s.on_exit).chain(&s.internal))
            .chain(
                self.transitions
                    .iter()
                    .flat_map(|t| t.leaving.iter().flatten()),
            )
    }

    /// Every statement that can run ([`Machine::actions`]), nested ones included, outermost
    /// first.
    pub fn statements(&self) -> Vec<&Statement> {
        let mut out = Vec::new();
        for action in self.actions() {
            if let Action::Statement(s) = action {
                s.visit(&mut |inner| out.push(inner));
            }
        }
        out
    }

    pub fn state(&self, id: StateId) -> Option<&State> {
        self.states.iter().find(|s| s.id == id)
    }

    /// The transitions leaving `id`, highest priority first.
    pub fn outgoing(&self, id: StateId) -> impl Iterator<Item = &Transition> + '_ {
        self.transitions.iter().filter(move |t| t.source == id)
    }

    /// The composite directly holding the flat state `state` (an index into `composites`).
    pub fn composite_of(&self, state: &State) -> Option<usize> {
        let (outer, _) = state.name.rsplit_once('.')?;
        self.composites.iter().position(|c| c.name == outer)
    }

    /// The composite that wrote `action`, which the flat state `state` runs in the activity
    /// `section` picks (a composite's OnEntry for an arrival): the innermost around it whose
    /// activity holds it as written; `None` when the state's own text did. A state of regions
    /// is looked for in each region's state (each kept as a composite) and around it.
    pub fn composite_writing(
        &self,
        state: &State,
        action: &Action,
        section: ActivityOf,
    ) -> Option<&Composite> {
        self.atomic_paths(state).into_iter().find_map(|path| {
            let named = |name: &str| self.composites.iter().position(|c| c.name == name);
            let mut around =
                named(path).or_else(|| path.rsplit_once('.').and_then(|(outer, _)| named(outer)));
            while let Some(c) = around.and_then(|c| self.composites.get(c)) {
                if section(c).contains(action) {
                    return Some(c);
                }
                around = c.parent;
            }
            None
        })
    }

    /// The line that wrote `action`, which the flat state `state` runs in one of its
    /// activities.
    pub fn line_of(&self, state: &State, action: &Action) -> usize {
        let sections: [ActivityOf; 3] = [|c| &c.on_entry, |c| &c.on_exit, |c| &c.internal];
        let mut written = sections
            .iter()
            .filter_map(|&section| self.composite_writing(state, action, section));
        written.next().map_or(state.line, |c| c.line)
    }

    /// Where `transition` was written: its source state, or the composite holding it.
    pub fn written_on(&self, transition: &Transition) -> Option<&str> {
        match transition.composite {
            Some(c) => self.composites.get(c).map(|c| c.name.as_str()),
            None => self.state(transition.source).map(|s| s.name.as_str()),
        }
    }
}

/// One of a composite's activities: its OnEntry, OnExit or Internal.
pub type ActivityOf = fn(&Composite) -> &[Action];

#[derive(Clone, Debug, PartialEq)]
pub struct State {
    pub id: StateId,
    pub name: String,
    pub on_entry: Vec<Action>,
    pub on_exit: Vec<Action>,
    pub internal: Vec<Action>,
    /// Where it was written (1-based), for diagnostics.
    pub line: usize,
    /// How many of the composite states around it a move into this flat state enters too
    /// (§3.2): its OnEntry runs theirs, outermost first, before its own. 0 in a flat machine.
    pub arrives_through: usize,
    /// The clocks (indices into [`Machine::composites`]) an arrival into it starts: the
    /// composites it entered whose entry matters, and a region's atomic states that test the
    /// time. Empty in a flat machine.
    pub arrival_clocks: Vec<usize>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Transition {
    pub source: StateId,
    pub target: StateId,
    pub label: Label,
    pub line: usize,
    /// What runs as it fires when that is not its source's OnExit: leaving a nested state by
    /// a transition to outside its composite runs the composites' OnExits too (§3.2).
    pub leaving: Option<Vec<Action>>,
    /// The composite it was written on (an index into `Machine::composites`), when it was
    /// not written on its source: lowering copies a composite's transitions to every state
    /// inside it.
    pub composite: Option<usize>,
    /// The composites this move enters (indices into `Machine::composites`, outermost first):
    /// a time test on a composite's transition counts from the composite's entry, which the
    /// moves between the states inside it do not restart (§3.2). Empty for a flat machine.
    pub enters: Vec<usize>,
    /// The label as its file wrote it, when lowering changed it (a chart's `when done`, a
    /// history's arms, a parameter or an outcome read as its global): what traces, drawings
    /// and findings show, so a user reads what they wrote. `label` is what every back end runs.
    pub written: Option<Label>,
    /// The other transitions as written whose labels this one joins to its own, in a state of
    /// a parallel state's regions (§3.2): each one's composite (as `composite`), its line, and
    /// whether this arm fires it (a later region's move out of the parallel state is
    /// preempted). Empty elsewhere: then the whole label is the transition's on `line`.
    pub joined: Vec<(Option<usize>, usize, bool)>,
    /// It fires without moving (SCXML's transition without a target): `leaving` (its own
    /// actions, no OnExit) runs, and the machine stays in its state, which is `target`: no
    /// OnEntry runs after it and no clock starts again (§3.2).
    pub stays: bool,
    /// Its targets as written by path, where it names several (`-> P.A.X, P.B.Y`): `target` is
    /// the configuration they enter together, and a drawing shows each. Empty for one target.
    pub targets: Vec<String>,
}

impl Transition {
    /// The label to show: as written.
    pub fn shown(&self) -> &Label {
        self.written.as_ref().unwrap_or(&self.label)
    }

    /// Renames the names its label reads, keeping what was written first; a label renamed
    /// back to how it was written (the native writer's parameters) has nothing else to show.
    pub(crate) fn rename_label(&mut self, to: &mut impl FnMut(&str) -> Option<String>) {
        let before = self.label.clone();
        self.label.rename(to);
        if self.label != before && self.written.is_none() {
            self.written = Some(before);
        }
        if self.written.as_ref() == Some(&self.label) {
            self.written = None;
        }
    }
}

/// One thing an activity does.
#[derive(Clone, Debug, PartialEq)]
pub enum Action {
    /// `Type: content`: a whiteboard posting. Sub-machine control is a posting to the machine's
    /// name (`SMPlayer: On`, and gufsm's `suspend("M")` becomes `M: suspend`).
    Post { ty: String, content: String },
    /// `C++: f`, `C++: f(12)`, `msleep(100)`: a host function registered by name.
    Call {
        function: String,
        argument: Option<Argument>,
    },
    /// A statement of the activity language: a declaration, an assignment, a computed posting
    /// (`post("T", x + 1)`), a call, a block or a `for` loop.
    Statement(Statement),
    /// Text that could not be read as a statement, kept as written so nothing is lost; the
    /// reader reports it as an error and it does nothing when run.
    Code(String),
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Argument {
    Int(i64),
    Str(String),
    /// An identifier or anything else, as written.
    Word(String),
}

impl Machine {
    /// Replaces every name its code reads or assigns (`Statement::rename`), wherever the code
    /// runs: its states', its composites' (as written, for what draws them) and its
    /// transitions' (labels and what they run as they fire).
    pub(crate) fn rename(&mut self, to: &mut impl FnMut(&str) -> Option<String>) {
        let mut lists: Vec<&mut Vec<Action>> = Vec::new();
        for s in &mut self.states {
            lists.extend([&mut s.on_entry, &mut s.on_exit, &mut s.internal]);
        }
        for c in &mut self.composites {
            lists.extend([&mut c.on_entry, &mut c.on_exit, &mut c.internal]);
        }
        for t in &mut self.transitions {
            t.rename_label(to);
            lists.extend(t.leaving.as_mut());
        }
        for action in lists.into_iter().flatten() {
            if let Action::Statement(s) = action {
                s.rename(to);
            }
        }
    }
}
