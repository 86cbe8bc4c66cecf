//! A native machine written as SCXML, from its states as written (nesting, histories and
//! transition content kept), the inverse of `scxml/`'s mapping: what that mapping reads back
//! is the same machine. A state's time test alone on a transition is SCXML's way to time it: a
//! delayed send on entering, cancelled on leaving, and a transition on its event. What SCXML
//! cannot say is refused at its line.

use super::ast::{ActionAst, FileAst, Member, Ref, Section, StateAst, TopItem};
use super::{LineIndex, MachineLexer};
use crate::code::{parse_statements, Expr, Statement};
use crate::model::Action;
use proclaim_syntax::FileDiagnostic;
use std::collections::{HashMap, HashSet};
use std::fmt::Write;

/// A transition as written: its label (or the event standing for it) and its targets, each
/// where it is written.
struct Arrow<'a> {
    label: &'a str,
    label_at: usize,
    target: &'a Option<Ref>,
    target_at: usize,
    also: &'a [(Ref, usize)],
}

/// The SCXML document of the native machine `text`, or why it cannot be written.
pub fn to_scxml(file: &str, text: &str) -> Result<String, Vec<FileDiagnostic>> {
    let read = super::parse_machine(file, text);
    if read.has_errors() {
        return Err(read.diagnostics);
    }
    let lines = LineIndex::new(text);
    let ast = super::grammar::FileParser::new()
        .parse(MachineLexer::new(text))
        .map_err(|_| vec![FileDiagnostic::error(file, 1, "the file does not read")])?;
    let mut writer = Writer {
        file,
        lines: &lines,
        refusals: Vec::new(),
        histories: HashSet::new(),
        data: Vec::new(),
    };
    let out = writer.document(ast);
    if writer.refusals.is_empty() {
        Ok(out)
    } else {
        Err(writer.refusals)
    }
}

struct Writer<'a> {
    file: &'a str,
    lines: &'a LineIndex<'a>,
    refusals: Vec<FileDiagnostic>,
    /// The composites some transition resumes, with `deep`.
    histories: HashSet<(String, bool)>,
    /// `<data>` items: (name, type, first value).
    data: Vec<(String, &'static str, String)>,
}

impl Writer<'_> {
    fn refuse(&mut self, at: usize, message: String) {
        let line = self.lines.line(at);
        self.refusals
            .push(FileDiagnostic::error(self.file, line, message));
    }

    fn document(&mut self, ast: FileAst) -> String {
        let mut initial = None;
        let mut states = Vec::new();
        for item in ast.items {
            match item {
                TopItem::Initial(targets) => initial = self.ids(&targets),
                TopItem::Description(..) => {}
                TopItem::Param(text, at) => self.refuse(at, format!("`param {text}`: a machine's parameters (given by whoever starts it) are not written to SCXML yet")),
                TopItem::Outcome(text, at) => self.refuse(at, format!("`outcome {text}`: a machine's outcomes are not written to SCXML yet")),
                TopItem::State(s) => states.push(s),
            }
        }
        // A first state that only declares the data and moves on at once is the data model
        // (what reading SCXML writes).
        if let Some(first) = states.first() {
            if first.name == "DATAMODEL_START" {
                let start = states.remove(0);
                initial = self.data_start(start);
            }
        }
        let mut names = HashMap::new();
        for s in &states {
            self.name_all(s, &mut names);
        }
        self.note_histories(&states);
        let mut body = String::new();
        for s in states {
            self.state(s, &mut body, 1);
        }
        let mut out = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
        let _ = write!(
            out,
            "<scxml xmlns=\"http://www.w3.org/2005/07/scxml\" version=\"1.0\" datamodel=\"ecmascript\" name=\"{}\"",
            attr(&ast.name)
        );
        if let Some(initial) = initial {
            let _ = write!(out, " initial=\"{}\"", attr(&initial));
        }
        out.push_str(">\n");
        if !self.data.is_empty() {
            out.push_str("  <datamodel>\n");
            for (name, ty, value) in &self.data {
                let _ = writeln!(
                    out,
                    "    <data id=\"{}\" type=\"{ty}\" expr=\"{}\"/>",
                    attr(name),
                    attr(value)
                );
            }
            out.push_str("  </datamodel>\n");
        }
        out.push_str(&body);
        out.push_str("</scxml>\n");
        out
    }

    /// SCXML's ids are the document's: every state's name must be its own.
    fn name_all(&mut self, s: &StateAst, seen: &mut HashMap<String, usize>) {
        if seen.insert(s.name.clone(), s.at).is_some() {
            self.refuse(
                s.at,
                format!(
                    "a second state named `{}`: SCXML's ids are unique in a document",
                    s.name
                ),
            );
        }
        for m in &s.members {
            if let Member::State(inner) = m {
                self.name_all(inner, seen);
            }
        }
    }

    fn note_histories(&mut self, states: &[StateAst]) {
        for s in states {
            for m in &s.members {
                match m {
                    Member::When {
                        target: Some(Ref::Name(path)),
                        ..
                    } => {
                        if let Some((composite, word)) = path.rsplit_once('.') {
                            let composite = composite.rsplit('.').next().unwrap_or(composite);
                            match word {
                                "history" => self.histories.insert((composite.into(), false)),
                                "deep_history" => self.histories.insert((composite.into(), true)),
                                _ => false,
                            };
                        }
                    }
                    Member::State(inner) => self.note_histories(std::slice::from_ref(inner)),
                    _ => {}
                }
            }
        }
    }

    fn data_start(&mut self, start: StateAst) -> Option<String> {
        let mut next = None;
        for m in start.members {
            match m {
                Member::Activity {
                    section: Section::Entry,
                    actions,
                    ..
                } => {
                    for (action, at) in actions {
                        let ActionAst::Statement(text) = action else {
                            self.refuse(at, "the data model's first state may only declare".into());
                            continue;
                        };
                        for s in parse_statements(&text).unwrap_or_default() {
                            match s {
                                Statement::Declare { name, value, ty } => {
                                    let value = value.map_or("0".to_string(), |v| script(&v));
                                    self.declare(name, &ty, value, at);
                                }
                                _ => self.refuse(
                                    at,
                                    "the data model's first state may only declare".into(),
                                ),
                            }
                        }
                    }
                }
                Member::When {
                    target: Some(target),
                    target_at,
                    also,
                    ..
                } if also.is_empty() => next = self.id(&target, target_at),
                _ => self.refuse(
                    start.at,
                    "the data model's first state may only declare and move on".into(),
                ),
            }
        }
        next
    }

    /// A `<data>` item: a number or a truth.
    fn declare(&mut self, name: String, ty: &crate::code::VarType, value: String, at: usize) {
        use crate::code::VarType;
        let ty = match ty {
            VarType::Int | VarType::Char => "int32",
            VarType::Bool => "bool",
            VarType::Float | VarType::Double => "float64",
            VarType::Named(other) => {
                self.refuse(
                    at,
                    format!("`{other} {name}`: SCXML data here is a number or a truth"),
                );
                return;
            }
        };
        self.data.push((name, ty, value));
    }

    fn state(&mut self, s: StateAst, out: &mut String, depth: usize) {
        let pad = "  ".repeat(depth);
        let holds = s.members.iter().any(|m| matches!(m, Member::State(_)));
        let moves = s.members.iter().any(|m| matches!(m, Member::When { .. }));
        let element = match (s.parallel, holds || moves) {
            (true, _) => "parallel",
            (false, true) => "state",
            (false, false) => "final",
        };
        let _ = write!(out, "{pad}<{element} id=\"{}\"", attr(&s.name));
        let timed = Timed::of(&s, timers(&s), &pad);
        let mut inner = timed.before.clone();
        for m in s.members {
            match m {
                Member::Initial(targets) => {
                    if let Some(id) = self.ids(&targets) {
                        let _ = write!(out, " initial=\"{}\"", attr(&id));
                    }
                }
                Member::Activity {
                    section: Section::Internal,
                    at,
                    ..
                } => self.refuse(at, format!("state `{}`: an internal activity (run each ringlet nothing fires) has no SCXML form", s.name)),
                Member::Activity {
                    section, actions, ..
                } => {
                    let content = self.content(actions, depth + 2);
                    inner.push_str(&timed.activity(section, &content, &pad));
                }
                Member::When {
                    label,
                    label_at,
                    target,
                    target_at,
                    also,
                    actions,
                    ..
                } => {
                    let done = holds.then_some(s.name.as_str());
                    let event = timed.event(&label);
                    let when = Arrow {
                        label: event.unwrap_or(&label),
                        label_at,
                        target: &target,
                        target_at,
                        also: &also,
                    };
                    let timer = event.is_some();
                    self.transition(when, (done, timer), actions, &mut inner, depth + 1);
                }
                Member::State(child) => self.state(child, &mut inner, depth + 1),
                Member::Outcome(text, at) => self.refuse(at, format!("state `{}`: `outcome {text}` is not written to SCXML yet", s.name)),
            }
        }
        inner.push_str(&self.histories_of(&s.name, &pad));
        if inner.is_empty() {
            out.push_str("/>\n");
        } else {
            let _ = write!(out, ">\n{inner}{pad}</{element}>\n");
        }
    }

    /// The `<history>` elements of the state `name` that some transition resumes.
    fn histories_of(&self, name: &str, pad: &str) -> String {
        let mut out = String::new();
        for deep in [false, true] {
            if self.histories.contains(&(name.to_string(), deep)) {
                let kind = if deep { "deep" } else { "shallow" };
                let _ = writeln!(
                    out,
                    "{pad}  <history id=\"{}_{}\" type=\"{kind}\"/>",
                    attr(name),
                    if deep { "deep_history" } else { "history" }
                );
            }
        }
        out
    }

    /// `when LABEL -> TARGET { … }` as a `<transition>` (`-> A, B` as `target="A B"`), and `when LABEL { … }` (it stays) as one without a target:
    /// the label a `cond`, or the completion event of the composite `done` names when the label
    /// is `done`.
    fn transition(
        &mut self,
        Arrow {
            label,
            label_at,
            target,
            target_at,
            also,
        }: Arrow<'_>,
        (done, event): (Option<&str>, bool),
        actions: Vec<(ActionAst, usize)>,
        out: &mut String,
        depth: usize,
    ) {
        let pad = "  ".repeat(depth);
        // Its label stays true while it stays; the event SCXML would wait on comes once.
        let once = event || (label.trim() == "done" && done.is_some());
        if target.is_none() && once {
            self.refuse(
                label_at,
                format!(
                    "a transition that stays on {}: SCXML raises its event once, where this label stays true in the state",
                    if event { "a time test" } else { "`done`" }
                ),
            );
            return;
        }
        // A transition that stays is SCXML's without a target.
        let target = match target {
            Some(target) => {
                let mut ids = vec![self.id(target, target_at)];
                ids.extend(also.iter().map(|(r, at)| self.id(r, *at)));
                let Some(ids) = ids.into_iter().collect::<Option<Vec<String>>>() else {
                    return;
                };
                format!(" target=\"{}\"", attr(&ids.join(" ")))
            }
            None => String::new(),
        };
        let condition = match (label.trim(), done) {
            (timer, _) if event => format!(" event=\"{}\"", attr(timer)),
            ("done", Some(state)) => format!(" event=\"done.state.{}\"", attr(state)),
            ("TRUE" | "true" | "", _) => String::new(),
            (text, _) => match self.condition(text, label_at) {
                Some(c) => format!(" cond=\"{}\"", attr(&c)),
                None => return,
            },
        };
        let content = self.content(actions, depth + 1);
        let open = format!("{pad}<transition{condition}{target}");
        if content.is_empty() {
            let _ = writeln!(out, "{open}/>");
        } else {
            let _ = write!(out, "{open}>\n{content}{pad}</transition>\n");
        }
    }

    /// A target's SCXML id: the last part of its path, or a history's own id.
    /// Several states' ids, as `initial="a b"` names a configuration.
    fn ids(&mut self, targets: &[(Ref, usize)]) -> Option<String> {
        let ids: Option<Vec<String>> = (targets.iter())
            .map(|(target, at)| self.id(target, *at))
            .collect();
        Some(ids?.join(" "))
    }

    fn id(&mut self, target: &Ref, at: usize) -> Option<String> {
        match target {
            Ref::Id(id) => {
                self.refuse(
                    at,
                    format!("`#{id}`: name the state; SCXML has no numbered states"),
                );
                None
            }
            Ref::Name(path) => {
                let mut parts: Vec<&str> = path.split('.').collect();
                let last = parts.pop().unwrap_or_default();
                Some(match (last, parts.last()) {
                    ("history" | "deep_history", Some(composite)) => format!("{composite}_{last}"),
                    _ => last.to_string(),
                })
            }
        }
    }

    fn condition(&mut self, label: &str, at: usize) -> Option<String> {
        match crate::label::parse_label(label) {
            Ok(e) => {
                let timed = e
                    .calls()
                    .iter()
                    .any(|(f, _)| crate::label::TIME_TESTS.iter().any(|(t, _)| t == f));
                if timed {
                    self.refuse(at, format!("`{label}`: a time test has no SCXML condition (SCXML times a state with a delayed send, which a transition then waits on alone)"));
                    return None;
                }
                // `in(PATH)` is SCXML's `In('id')`; a state's id is its name here.
                let mut e = e;
                e.replace_calls(&mut |function, arguments| match (function, arguments) {
                    (super::chart::IN_STATE, [Expr::Name(path)]) => Some(Expr::Call {
                        function: "In".into(),
                        arguments: vec![Expr::Str(path.rsplit('.').next().unwrap_or(path).into())],
                        clock: None,
                    }),
                    _ => None,
                });
                Some(script(&e))
            }
            Err(e) => {
                self.refuse(at, format!("`{label}`: {}", e.message));
                None
            }
        }
    }

    /// Activity items as executable content, one element a line.
    fn content(&mut self, actions: Vec<(ActionAst, usize)>, depth: usize) -> String {
        let pad = "  ".repeat(depth);
        let mut out = String::new();
        for (action, at) in actions {
            let text = match action {
                ActionAst::Statement(text) => text,
                ActionAst::Done(Action::Post { ty, .. }) => {
                    self.refuse(at, format!("the posting `{ty}: …`: its content has no SCXML form (an SCXML event carries none here); `post(\"{ty}\", TRUE);` raises it"));
                    continue;
                }
                ActionAst::Done(_) => {
                    self.refuse(at, "a host call or kept code has no SCXML form".into());
                    continue;
                }
            };
            for s in parse_statements(&text).unwrap_or_default() {
                if let Statement::Declare {
                    name,
                    value: None,
                    ty,
                } = &s
                {
                    self.declare(name.clone(), ty, "0".into(), at);
                    continue;
                }
                match self.element(&s) {
                    Some(element) => {
                        let _ = writeln!(out, "{pad}{element}");
                    }
                    None => self.refuse(at, format!("`{s}`: only assignments, `post(\"event\", TRUE)` and `print(…)` have SCXML forms")),
                }
            }
        }
        out
    }

    fn element(&self, s: &Statement) -> Option<String> {
        match s {
            Statement::Assign { name, value } => Some(format!(
                "<assign location=\"{}\" expr=\"{}\"/>",
                attr(name),
                attr(&script(value))
            )),
            Statement::Expr(Expr::Call {
                function,
                arguments,
                ..
            }) => match (function.as_str(), arguments.as_slice()) {
                ("post", [Expr::Str(event), Expr::Bool(true)]) => {
                    Some(format!("<raise event=\"{}\"/>", attr(event)))
                }
                ("print", [e]) => Some(format!("<log expr=\"{}\"/>", attr(&script(e)))),
                _ => None,
            },
            _ => None,
        }
    }
}

/// An expression as ECMAScript: `!` for not, `'…'` strings.
/// What a state's timers add to its SCXML: a send each on entering, a cancel each on
/// leaving, in the state's own `<onentry>` and `<onexit>` or in ones of their own.
struct Timed {
    /// (the label as written, its event, its delay) of each timer.
    timers: Vec<(String, String, String)>,
    sends: String,
    cancels: String,
    /// What goes first inside the state: the timers' own `<onentry>` (and `<onexit>`) when
    /// the state has no entry activity.
    before: String,
    /// The timers' own `<onexit>`, after the state's entry, when it has no exit activity.
    fresh_exit: String,
}

impl Timed {
    fn of(s: &StateAst, timers: Vec<(String, String, String)>, pad: &str) -> Timed {
        let (sends, cancels): (String, String) = timers
            .iter()
            .map(|(_, event, delay)| {
                let e = attr(event);
                (
                    format!("{pad}    <send event=\"{e}\" delay=\"{delay}\" id=\"{e}\"/>\n"),
                    format!("{pad}    <cancel sendid=\"{e}\"/>\n"),
                )
            })
            .unzip();
        let has = |wanted: Section| {
            s.members
                .iter()
                .any(|m| matches!(m, Member::Activity { section, .. } if *section == wanted))
        };
        let fresh_exit = if has(Section::Exit) || cancels.is_empty() {
            String::new()
        } else {
            format!("{pad}  <onexit>\n{cancels}{pad}  </onexit>\n")
        };
        let before = if has(Section::Entry) || sends.is_empty() {
            String::new()
        } else {
            format!("{pad}  <onentry>\n{sends}{pad}  </onentry>\n{fresh_exit}")
        };
        Timed {
            timers,
            sends,
            cancels,
            before,
            fresh_exit,
        }
    }

    /// The event a transition labelled `label` waits on, when its label is a timer's.
    fn event(&self, label: &str) -> Option<&str> {
        let timer = self.timers.iter().find(|(l, _, _)| l == label.trim());
        timer.map(|(_, event, _)| event.as_str())
    }

    /// The state's own entry or exit activity (`content`), the timers' sends or cancels
    /// first; after the entry, the timers' own `<onexit>` when the state has none.
    fn activity(&self, section: Section, content: &str, pad: &str) -> String {
        let (tag, first) = match section {
            Section::Entry => ("onentry", &self.sends),
            _ => ("onexit", &self.cancels),
        };
        let mut out = format!("{pad}  <{tag}>\n{first}{content}{pad}  </{tag}>\n");
        if section == Section::Entry {
            out.push_str(&self.fresh_exit);
        }
        out
    }
}

/// The transitions of the atomic state `s` whose label is a time test alone, with a constant
/// duration in whole milliseconds: (the label as written, the event its delayed send raises,
/// the delay as SCXML writes it: `2s`, `1500ms`).
fn timers(s: &StateAst) -> Vec<(String, String, String)> {
    let mut out: Vec<(String, String, String)> = Vec::new();
    for m in &s.members {
        let Member::When { label, .. } = m else {
            continue;
        };
        let Ok(Expr::Call {
            function,
            arguments,
            ..
        }) = crate::label::parse_label(label)
        else {
            continue;
        };
        let Some((_, unit)) = crate::label::TIME_TESTS
            .iter()
            .find(|(f, _)| *f == function)
        else {
            continue;
        };
        // Written back as it reads again: `after(2)` as `2s`, `after_ms(300)` as `300ms`.
        let delay = match (function.as_str(), arguments.as_slice()) {
            ("after", [Expr::Int(n)]) if *n >= 0 => format!("{n}s"),
            ("after_ms", [Expr::Int(n)]) if *n >= 0 => format!("{n}ms"),
            (_, [Expr::Duration(us)]) if us % 1000 == 0 => format!("{}ms", us / 1000),
            (_, [Expr::Int(n)]) if *n >= 0 && (*n as u64 * *unit as u64) % 1000 == 0 => {
                format!("{}ms", *n as u64 * *unit as u64 / 1000)
            }
            _ => continue,
        };
        if out.iter().any(|(l, _, _)| l == label.trim()) {
            continue;
        }
        let event = format!("{}.after_{delay}", s.name);
        out.push((label.trim().to_string(), event, delay));
    }
    out
}

fn script(e: &Expr) -> String {
    match e {
        Expr::Unary {
            op: crate::code::UnOp::Not,
            operand,
        } => format!("!{}", wrapped(operand)),
        Expr::Binary { op, left, right } => {
            // The right side binds as tightly as its operator only in brackets: `a - (b - c)`.
            let side = |x: &Expr, right: bool| match x {
                Expr::Binary { op: inner, .. }
                    if inner.precedence() < op.precedence()
                        || (right && inner.precedence() == op.precedence()) =>
                {
                    format!("({})", script(x))
                }
                _ => script(x),
            };
            format!(
                "{} {} {}",
                side(left, false),
                op.symbol(),
                side(right, true)
            )
        }
        Expr::Str(s) => format!("{s:?}"),
        Expr::Bool(b) => b.to_string(),
        other => other.to_string(),
    }
}

fn wrapped(e: &Expr) -> String {
    match e {
        Expr::Binary { .. } => format!("({})", script(e)),
        _ => script(e),
    }
}

/// Text as an XML attribute's value (tabs and line breaks as references, which attribute
/// normalisation keeps).
fn attr(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
        .replace('\t', "&#9;")
        .replace('\n', "&#10;")
        .replace('\r', "&#13;")
}
