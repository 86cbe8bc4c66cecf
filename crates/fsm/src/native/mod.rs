//! The native machine format: one machine a file, readable and diffable, comments allowed,
//! transitions listed in priority order (first = tried first).
//!
//! ```text
//! // The seed paper's Figure 1, cut down.
//! machine GameController
//! initial INITIAL
//!
//! state INITIAL {
//!     entry {
//!         LEDS: ChestBoard Off
//!         call sayTeam
//!     }
//!     when readyReceived -> READY
//! }
//!
//! state READY {
//!     entry {
//!         Placer: On
//!     }
//!     exit {
//!         Placer: Off
//!     }
//!     when setReceived && !penaltyReceived -> SET
//!     when timeout(5000000) -> INITIAL
//! }
//! ```
//!
//! A posting is `Type: content` (the content is the rest of the line), a host call is
//! `call f`, `call f(12)`, `call f("text")`; anything else in an activity is a statement of the
//! activity language ending in `;` (`count = count + 1;`, `post("Say", count);`, `int n;`), and
//! `code …` keeps text that an importer could not read, as written. States may carry their original id (`state GetUp #14`); where names repeat,
//! a transition names its target by id (`-> #14`).

mod ast;
mod chart;
mod edit;
mod edit_error;
mod flatten;
mod interface;
mod lexer;
mod outline;
mod to_scxml;
mod write;

use crate::code::{parse_statements, Expr};
use crate::label::parse_label;
use crate::label::Label;
use crate::model::{Action, Machine, State, StateId, Transition};
use crate::Imported;
use ast::{ActionAst, FileAst, Initials, Member, Ref, StateAst, TopItem};
use lalrpop_util::ParseError;
use lexer::{LexError, MachineLexer, MachineToken};
use proclaim_syntax::FileDiagnostic;

pub use ast::Section;
pub use edit::{
    check_native, edit_native, editable, view_native, ActivityView, Edit, Edited, StateView,
    TransitionView,
};
pub use edit_error::EditError;
pub use to_scxml::to_scxml;
pub use write::{to_native, KEYWORDS};

lalrpop_util::lalrpop_mod!(
    #[allow(clippy::all, clippy::pedantic, unused)]
    grammar,
    "/native/grammar.rs"
);

/// The file extension of native machine files.
pub const EXTENSION: &str = "machine";

/// Reads one machine in the native format. Never fails: a file that does not parse yields no
/// machine and a diagnostic naming the line; names that resolve to no state are reported too.
pub fn parse_machine(file: &str, text: &str) -> Imported {
    let lines = LineIndex::new(text);
    let parsed = grammar::FileParser::new().parse(MachineLexer::new(text));
    match parsed {
        Ok(ast) => lower(file, &lines, ast),
        Err(error) => {
            let (at, message) = describe(error, text.len());
            Imported {
                machines: Vec::new(),
                diagnostics: vec![lines.error(file, at, message)],
            }
        }
    }
}

fn describe(error: ParseError<usize, MachineToken<'_>, LexError>, end: usize) -> (usize, String) {
    let expected = |expected: &[String]| {
        let names: Vec<String> = expected.iter().map(|e| friendly(e)).collect();
        match names.as_slice() {
            [] => String::new(),
            [one] => format!("; expected {one}"),
            many => format!("; expected one of {}", many.join(", ")),
        }
    };
    match error {
        ParseError::InvalidToken { location } => (location, "unreadable text".into()),
        ParseError::UnrecognizedEof { expected: e, .. } => {
            (end, format!("the file ends too early{}", expected(&e)))
        }
        ParseError::UnrecognizedToken {
            token: (at, tok, _),
            expected: e,
        } => (at, format!("unexpected {tok}{}", expected(&e))),
        ParseError::ExtraToken {
            token: (at, tok, _),
        } => (at, format!("unexpected {tok}")),
        ParseError::User { error } => (error.at, error.message),
    }
}

/// lalrpop names terminals as they are written in the grammar; say what they are instead.
fn friendly(terminal: &str) -> String {
    match terminal {
        "Word" => "a name".into(),
        "Str" => "a quoted string".into(),
        "Int" => "a whole number".into(),
        "Text" => "`:` and the posting's content".into(),
        "LabelText" => "a label".into(),
        "Statement" => "a statement".into(),
        quoted => format!("`{}`", quoted.trim_matches('"')),
    }
}

pub(crate) struct LineIndex<'t> {
    text: &'t str,
    starts: Vec<usize>,
}

impl LineIndex<'_> {
    pub(crate) fn new(text: &str) -> LineIndex<'_> {
        let mut starts = vec![0];
        starts.extend(text.match_indices('\n').map(|(i, _)| i + 1));
        LineIndex { text, starts }
    }

    /// 1-based.
    pub(crate) fn line(&self, offset: usize) -> usize {
        self.starts.partition_point(|&s| s <= offset)
    }

    /// The byte offset of a 1-based line and column (in characters), when the text has them.
    fn offset(&self, line: usize, column: usize) -> Option<usize> {
        let start = *self.starts.get(line.checked_sub(1)?)?;
        let rest = &self.text[start..];
        let within = rest
            .char_indices()
            .map(|(i, _)| i)
            .chain(std::iter::once(rest.len()))
            .nth(column.checked_sub(1)?)?;
        Some(start + within)
    }

    /// An error at a byte offset, with its line and column.
    fn error(&self, file: &str, offset: usize, message: String) -> FileDiagnostic {
        let line = self.line(offset);
        let start = self.starts[line - 1];
        let column = self
            .text
            .get(start..offset.min(self.text.len()))
            .map_or(1, |before| before.chars().count() + 1);
        let end = self
            .starts
            .get(line)
            .map_or(self.text.len(), |next| next - 1);
        let text = self.text.get(start..end).unwrap_or_default();
        let text = text.strip_suffix('\r').unwrap_or(text);
        FileDiagnostic::error(file, line, message).at_column_of(column, text)
    }
}

fn lower(file: &str, lines: &LineIndex<'_>, ast: FileAst) -> Imported {
    let mut lowering = Lowering {
        file,
        lines,
        diagnostics: Vec::new(),
        machine: ast.name.clone(),
        interface: Default::default(),
        announced: Vec::new(),
    };
    let (description, initial_ref, parsed) = lowering.header(ast.items);
    let nested = parsed
        .iter()
        .any(|s| s.parallel || s.members.iter().any(|m| matches!(m, Member::State(_))));
    if nested {
        let machines = chart::lower_chart(&mut lowering, parsed, initial_ref)
            .map(|chart| {
                let mut machine = Machine {
                    name: ast.name,
                    description,
                    states: chart.states,
                    transitions: chart.transitions,
                    initial: chart.initial,
                    unread: Vec::new(),
                    composites: chart.composites,
                    interface: Default::default(),
                };
                lowering.lower_params(&mut machine);
                machine
            })
            .into_iter()
            .collect();
        return Imported {
            machines,
            diagnostics: lowering.diagnostics,
        };
    }
    let ids = lowering.number(&parsed);
    let names = StateNames::new(
        &ids,
        parsed.iter().zip(&ids).map(|(s, &id)| (s.name.clone(), id)),
    );
    let mut states = Vec::new();
    let mut transitions = Vec::new();
    for (s, &id) in parsed.into_iter().zip(&ids) {
        states.push(lowering.state(s, id, &names, &mut transitions));
    }
    let initial = match initial_ref {
        Some(written) => lowering.flat_initial(written, &names),
        None => states.first().map(|s| s.id),
    };
    let machines = match initial {
        Some(initial) => {
            let mut machine = Machine {
                name: ast.name,
                description,
                states,
                transitions,
                initial,
                unread: Vec::new(),
                composites: Vec::new(),
                interface: Default::default(),
            };
            lowering.lower_params(&mut machine);
            vec![machine]
        }
        None if states.is_empty() => {
            lowering.error(ast.name_at, format!("machine `{}` has no states", ast.name));
            Vec::new()
        }
        None => Vec::new(),
    };
    Imported {
        machines,
        diagnostics: lowering.diagnostics,
    }
}

/// The syntax tree of one file becoming its machine, with every problem found on the way.
struct Lowering<'a> {
    file: &'a str,
    lines: &'a LineIndex<'a>,
    diagnostics: Vec<FileDiagnostic>,
    /// The machine's name: the globals its parameters and outcomes become are named after it.
    machine: String,
    /// Its parameters and outcomes, read from the top of the file before its states.
    interface: crate::interface::Interface,
    /// The outcomes some state announces.
    announced: Vec<String>,
}

/// The states' ids, and their names, for resolving `-> NAME` and `-> #id`.
/// States by id and by name, looked up in constant time: a machine of thousands of states
/// (generated, or a mutant) resolves its transitions in time linear in its size.
struct StateNames {
    ids: std::collections::HashSet<StateId>,
    by_name: std::collections::HashMap<String, Vec<StateId>>,
    /// In file order, for the nearest name to one that is not there.
    names: Vec<String>,
}

/// How many of the states one name names an error lists.
const LISTED: usize = 5;

impl StateNames {
    fn new(ids: &[StateId], names: impl Iterator<Item = (String, StateId)>) -> StateNames {
        let mut by_name: std::collections::HashMap<String, Vec<StateId>> = Default::default();
        let mut in_order = Vec::new();
        for (name, id) in names {
            in_order.push(name.clone());
            by_name.entry(name).or_default().push(id);
        }
        StateNames {
            ids: ids.iter().copied().collect(),
            by_name,
            names: in_order,
        }
    }

    fn resolve(&self, target: &Ref) -> Result<StateId, String> {
        match target {
            Ref::Id(id) if self.ids.contains(id) => Ok(*id),
            Ref::Id(id) => Err(format!("there is no state #{id}")),
            Ref::Name(name) => {
                let found = self.by_name.get(name).map_or(&[][..], Vec::as_slice);
                match found {
                    [id] => Ok(*id),
                    [] => Err(match proclaim_syntax::nearest(self.names.iter().map(String::as_str), name) {
                        Some(near) => format!("there is no state named `{name}`; did you mean `{near}`?"),
                        None => format!("there is no state named `{name}`"),
                    }),
                    many => Err(format!(
                        "`{name}` names {} states ({}); name the one meant by its id, as in `-> #{}`",
                        many.len(),
                        many.iter()
                            .take(LISTED)
                            .map(|id| format!("#{id}"))
                            .chain((many.len() > LISTED).then(|| "…".to_string()))
                            .collect::<Vec<_>>()
                            .join(", "),
                        many[0]
                    )),
                }
            }
        }
    }
}

impl Lowering<'_> {
    /// The state a flat machine's `initial` names: one (several are a configuration of
    /// regions, which it has none of).
    fn flat_initial(&mut self, written: Initials, names: &StateNames) -> Option<StateId> {
        if let Some((_, at)) = written.get(1) {
            self.error(*at, "several initial states enter a state in each region of a parallel state, and this machine has none: name one".into());
        }
        let (target, at) = written.into_iter().next()?;
        match names.resolve(&target) {
            Ok(id) => Some(id),
            Err(message) => {
                self.error(at, message);
                None
            }
        }
    }

    fn error(&mut self, at: usize, message: String) {
        self.diagnostics
            .push(self.lines.error(self.file, at, message));
    }

    fn warn(&mut self, at: usize, message: String) {
        let mut d = self.lines.error(self.file, at, message);
        d.severity = proclaim_syntax::Severity::Warning;
        self.diagnostics.push(d);
    }

    /// The description, the initial state as written, and the states, each said once.
    fn header(&mut self, items: Vec<TopItem>) -> (String, Option<Initials>, Vec<StateAst>) {
        let mut initial_ref = None;
        let mut description = String::new();
        let mut parsed = Vec::new();
        for item in items {
            match item {
                TopItem::Description(text, at) => {
                    if !description.is_empty() {
                        self.error(at, "the description is given twice".into());
                    }
                    description = text;
                }
                TopItem::Initial(targets) => {
                    if initial_ref.is_some() {
                        self.error(targets[0].1, "the initial state is given twice".into());
                    } else {
                        initial_ref = Some(targets);
                    }
                }
                TopItem::Param(text, at) => self.param(&text, at),
                TopItem::Outcome(text, at) => self.outcomes(&text, at),
                TopItem::State(s) => parsed.push(s),
            }
        }
        (description, initial_ref, parsed)
    }

    /// Ids as written; the others numbered from 1, skipping those taken.
    fn number(&mut self, parsed: &[StateAst]) -> Vec<StateId> {
        let mut taken: std::collections::HashSet<StateId> = Default::default();
        for s in parsed {
            if let Some(id) = s.id {
                if !taken.insert(id) {
                    self.error(s.at, format!("state id #{id} is used twice"));
                }
            }
        }
        let mut next = 1;
        parsed
            .iter()
            .map(|s| {
                s.id.unwrap_or_else(|| {
                    while taken.contains(&next) {
                        next += 1;
                    }
                    taken.insert(next);
                    next
                })
            })
            .collect()
    }

    /// One state of a flat machine, its transitions added to `transitions`.
    fn state(
        &mut self,
        s: StateAst,
        id: StateId,
        names: &StateNames,
        transitions: &mut Vec<Transition>,
    ) -> State {
        let line = self.lines.line(s.at);
        let body = self.body(&s.name, s.members);
        for when in body.whens {
            if let Some(mut t) = self.transition(id, &when, names) {
                if t.stays {
                    // It leaves nothing: its own actions are all it runs.
                    t.leaving = Some(when.actions.clone());
                } else if !when.actions.is_empty() {
                    t.leaving = Some(body.exit.iter().chain(&when.actions).cloned().collect());
                }
                transitions.push(t);
            }
        }
        State {
            id,
            name: s.name,
            on_entry: body.entry,
            on_exit: body.exit,
            internal: body.internal,
            line,
            arrives_through: 0,
            arrival_clocks: Vec::new(),
        }
    }

    /// What a state's block holds, each activity once.
    fn body(&mut self, name: &str, members: Vec<Member>) -> Body {
        let mut body = Body::default();
        let mut seen: Vec<Section> = Vec::new();
        let mut outcome: Option<(String, usize)> = None;
        for member in members {
            match member {
                Member::Activity {
                    section,
                    actions,
                    at,
                } => {
                    if seen.contains(&section) {
                        self.error(
                            at,
                            format!(
                                "state `{name}` has two {} blocks; put their items in one",
                                section_name(section)
                            ),
                        );
                    }
                    seen.push(section);
                    let list = match section {
                        Section::Entry => &mut body.entry,
                        Section::Exit => &mut body.exit,
                        Section::Internal => &mut body.internal,
                    };
                    self.actions(actions, list);
                }
                Member::When {
                    label,
                    label_at,
                    target,
                    target_at,
                    also,
                    at,
                    actions,
                } => {
                    let mut own = Vec::new();
                    self.actions(actions, &mut own);
                    body.whens.push(When {
                        label,
                        label_at,
                        target,
                        target_at,
                        also,
                        at,
                        actions: own,
                    });
                }
                Member::Initial(targets) => {
                    if body.initial.is_some() {
                        let at = targets[0].1;
                        self.error(at, format!("state `{name}` names its initial state twice"));
                    } else {
                        body.initial = Some(targets);
                    }
                }
                Member::State(inner) => body.states.push(inner),
                Member::Outcome(text, at) => {
                    if outcome.is_some() {
                        self.error(at, format!("state `{name}` announces two outcomes"));
                    } else {
                        outcome = Some((text, at));
                    }
                }
            }
        }
        if let Some(outcome) = outcome {
            self.announce(name, outcome, &mut body);
        }
        if let (Some(initial), true) = (&body.initial, body.states.is_empty()) {
            self.error(
                initial[0].1,
                format!("state `{name}` holds no states, so it has no initial state to name"),
            );
        }
        body
    }

    fn actions(&mut self, actions: Vec<(ActionAst, usize)>, list: &mut Vec<Action>) {
        for (action, at) in actions {
            match action {
                ActionAst::Done(action) => list.push(action),
                ActionAst::Statement(text) => match parse_statements(&text) {
                    Ok(statements) => {
                        self.check_sets(&statements, at);
                        self.no_in_state(&statements, at);
                        list.extend(statements.into_iter().map(Action::Statement));
                    }
                    Err(e) => self.error(at + e.offset, format!("bad statement: {}", e.message)),
                },
            }
        }
    }

    /// `in(S)` is decided where a label is lowered; an activity runs in whatever flat state
    /// arrives or leaves, so it has no one answer there.
    fn no_in_state(&mut self, statements: &[crate::code::Statement], at: usize) {
        let mut found = false;
        for statement in statements {
            statement.visit(&mut |s| {
                let calls = s.expressions().into_iter().flat_map(Expr::calls);
                found |= calls.into_iter().any(|(f, _)| f == chart::IN_STATE);
            });
        }
        if found {
            self.error(
                at,
                format!("`{}(…)` asks which state the machine is in, in a label only (`when {}(HEAD.TRACK) -> …`); an activity cannot", chart::IN_STATE, chart::IN_STATE),
            );
        }
    }

    fn transition(
        &mut self,
        source: StateId,
        when: &When,
        names: &StateNames,
    ) -> Option<Transition> {
        let written = self.label(when)?;
        // `in(S)` in a flat machine: whether S is this very state.
        let mut unresolved = None;
        let mut label = written.clone();
        label.replace_calls(&mut |function, arguments| {
            if function != chart::IN_STATE {
                return None;
            }
            let state = match arguments {
                [Expr::Name(name)] => names.resolve(&Ref::Name(name.clone())),
                _ => Err(chart::in_state_usage()),
            };
            match state {
                Ok(state) => Some(Expr::Bool(state == source)),
                Err(message) => {
                    let shown = arguments
                        .iter()
                        .map(ToString::to_string)
                        .collect::<Vec<_>>();
                    unresolved.get_or_insert(format!(
                        "`{}({})`: {message}",
                        chart::IN_STATE,
                        shown.join(", ")
                    ));
                    Some(Expr::Bool(false))
                }
            }
        });
        if let Some(message) = unresolved {
            self.error(when.label_at, message);
            return None;
        }
        if let Some((_, at)) = when.also.first() {
            self.error(
                *at,
                "several targets enter a state in each region of a parallel state, and this machine has none: name one target".into(),
            );
            return None;
        }
        let changed = label != written;
        let resolved = match &when.target {
            Some(target) => names.resolve(target),
            None => Ok(source),
        };
        match resolved {
            Ok(target) => Some(Transition {
                source,
                target,
                label: if changed {
                    label.folded_truths()
                } else {
                    label
                },
                line: self.lines.line(when.at),
                leaving: None,
                composite: None,
                enters: Vec::new(),
                written: changed.then_some(written),
                joined: Vec::new(),
                stays: when.target.is_none(),
                targets: Vec::new(),
            }),
            Err(message) => {
                self.error(when.target_at, message);
                None
            }
        }
    }

    /// A transition's label, or `None` once the reason it cannot be read is reported.
    fn label(&mut self, when: &When) -> Option<Label> {
        if when.label.is_empty() {
            self.error(
                when.at,
                "a transition needs a label; write `when TRUE -> …` for one that always fires"
                    .into(),
            );
            return None;
        }
        match parse_label(&when.label) {
            Ok(l) => Some(l),
            Err(e) => {
                self.error(
                    when.label_at + e.offset,
                    format!("bad label: {}", e.message),
                );
                None
            }
        }
    }
}

/// A state's block as read: its activities, transitions, and for a composite its states.
#[derive(Default)]
struct Body {
    entry: Vec<Action>,
    exit: Vec<Action>,
    internal: Vec<Action>,
    whens: Vec<When>,
    /// The states `initial` names, each where it is written.
    initial: Option<Initials>,
    states: Vec<StateAst>,
}

/// A `when LABEL -> TARGET` (or `when LABEL { … }`, which stays) as parsed, with where each
/// part was written.
struct When {
    label: String,
    label_at: usize,
    target: Option<Ref>,
    target_at: usize,
    /// Further targets (`-> P.A.X, P.B.Y`), each where it is written.
    also: Vec<(Ref, usize)>,
    at: usize,
    /// Its own actions: they run as it fires, after its source's OnExit.
    actions: Vec<Action>,
}

fn section_name(section: Section) -> &'static str {
    match section {
        Section::Entry => "entry",
        Section::Exit => "exit",
        Section::Internal => "internal",
    }
}
