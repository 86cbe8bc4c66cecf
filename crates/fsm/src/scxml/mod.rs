//! SCXML (the W3C statechart format Qt, Apache Commons SCXML and AS2FM read) mapped onto the
//! native format, nested states and histories included (`docs/spec/behaviour.md` §4): what
//! maps is written as a `.machine` text, what does not is refused with its element and line.
//! An event is a label atom (the proposition that it happened) and a `cond` is conjoined to
//! it; `<raise>` and `<send>` post the event, true, to the whiteboard, but a delayed send that
//! times the state sending it is that state's time test (`delayed.rs`).

mod delayed;
mod tree;

use crate::code::{parse_expression, parse_statements, Expr};
use crate::Imported;
use proclaim_syntax::FileDiagnostic;
use std::collections::HashMap;
use std::fmt::Write;
use tree::Element;

/// What reading an SCXML document gave: the machine and every refusal, and the native text it
/// was read through (what `proclaim import` writes), when the document mapped.
#[derive(Debug, Default)]
pub struct ImportedScxml {
    pub imported: Imported,
    pub native: Option<String>,
}

/// Reads an SCXML document; its machine is named by its `name` attribute, else `stem`.
pub fn import_scxml(file: &str, text: &str, stem: &str) -> ImportedScxml {
    let root = match tree::read(text) {
        Ok(root) => root,
        Err((line, message)) => return refused(vec![FileDiagnostic::error(file, line, message)]),
    };
    if root.name == "ascxml" {
        let message = "<ascxml>: AS2FM's abstract SCXML, whose ROS interfaces do not map; convert it to plain SCXML first".to_string();
        return refused(vec![FileDiagnostic::error(file, root.line, message)]);
    }
    if root.name != "scxml" {
        let message = format!("the root element is <{}>, not <scxml>", root.name);
        return refused(vec![FileDiagnostic::error(file, root.line, message)]);
    }
    let mut mapping = Mapping {
        file,
        refusals: Vec::new(),
        names: HashMap::new(),
        histories: HashMap::new(),
        parallels: Default::default(),
        data: Vec::new(),
        timers: HashMap::new(),
    };
    mapping.name_states(&root, "");
    let (timers, refusals) = delayed::timers(&root);
    mapping.timers = timers;
    for (line, why) in refusals {
        mapping.refuse(line, why);
    }
    let native = mapping.document(&root, stem);
    if !mapping.refusals.is_empty() {
        mapping.refusals.sort_by_key(|d| d.line);
        return refused(mapping.refusals);
    }
    let mut imported = crate::parse_machine(file, &native);
    for machine in &mut imported.machines {
        lines_of_the_document(machine, &native);
    }
    // The native text is this importer's own: a problem in it is reported at the document.
    for d in &mut imported.diagnostics {
        d.message = format!("{} (in the native form the SCXML maps to)", d.message);
        d.line = Some(1);
        d.column = None;
    }
    ImportedScxml {
        imported,
        native: Some(native),
    }
}

fn refused(diagnostics: Vec<FileDiagnostic>) -> ImportedScxml {
    ImportedScxml {
        imported: Imported {
            machines: Vec::new(),
            diagnostics,
        },
        native: None,
    }
}

struct Mapping<'a> {
    file: &'a str,
    refusals: Vec<FileDiagnostic>,
    /// Each state's id and the path it has in the native text.
    names: HashMap<String, String>,
    /// Each `<history>`'s id and the target that resumes it (`PLAY.history`).
    histories: HashMap<String, String>,
    /// The paths of the `<parallel>` states.
    parallels: std::collections::HashSet<String>,
    /// The data model: (name, type, first value written), in document order.
    data: Vec<(String, &'static str, String)>,
    /// The delayed sends that time their state, by event.
    timers: HashMap<String, delayed::Timer>,
}

const STATES: [&str; 3] = ["state", "final", "parallel"];

impl Mapping<'_> {
    fn refuse(&mut self, line: usize, message: String) {
        self.refusals
            .push(FileDiagnostic::error(self.file, line, message));
    }

    /// A native name for an SCXML id: letters, digits and `_` (the rest become `_`).
    fn word(id: &str) -> String {
        let mut word: String = id
            .chars()
            .map(|c| {
                if c.is_alphanumeric() || c == '_' {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        if !word.starts_with(|c: char| c.is_alphabetic() || c == '_') {
            word.insert_str(0, "s_");
        }
        if word == "history" || word == "deep_history" {
            word.push('_');
        }
        word
    }

    /// Every state's path and every history's target, before anything refers to them.
    fn name_states(&mut self, parent: &Element, path: &str) {
        for (n, child) in parent.children.iter().enumerate() {
            if child.name == "history" {
                let deep = child.attribute("type") == Some("deep");
                let id = child.attribute("id").unwrap_or_default().to_string();
                let word = if deep { "deep_history" } else { "history" };
                self.histories.insert(id, format!("{path}.{word}"));
                continue;
            }
            if !STATES.contains(&child.name.as_str()) {
                continue;
            }
            let id = child
                .attribute("id")
                .map_or_else(|| format!("{}_{n}", child.name), str::to_string);
            let word = Self::word(&id);
            let own = if path.is_empty() {
                word
            } else {
                format!("{path}.{word}")
            };
            if self.names.insert(id.clone(), own.clone()).is_some() {
                self.refuse(child.line, format!("two states have the id `{id}`"));
            }
            if child.name == "parallel" {
                self.parallels.insert(own.clone());
            }
            self.name_states(child, &own);
        }
    }

    fn document(&mut self, root: &Element, stem: &str) -> String {
        if let Some(model) = root.attribute("datamodel") {
            if !matches!(model, "null" | "ecmascript") {
                self.refuse(
                    root.line,
                    format!("the `{model}` data model: only `null` and a small ECMAScript one (numbers, truths, operators) map"),
                );
            }
        }
        let name = Self::word(root.attribute("name").unwrap_or(stem));
        let mut body = String::new();
        for child in &root.children {
            match child.name.as_str() {
                "datamodel" => self.datamodel(child),
                "state" | "final" | "parallel" => self.state(child, &mut body, 0),
                other => self.unmapped(child, other, "the document"),
            }
        }
        let holds_state = (root.children.iter())
            .any(|c| matches!(c.name.as_str(), "state" | "final" | "parallel"));
        if !holds_state {
            self.refuse(
                root.line,
                "<scxml> holds no state: a machine needs one to start in".to_string(),
            );
        }
        let initial = match root.attribute("initial") {
            Some(ids) => self.initial_target(ids, root.line),
            None => None,
        };
        let mut out = format!(
            "// Read from {}, an SCXML document (`proclaim import` maps it; docs/spec/behaviour.md §4).\nmachine {name}\n",
            self.file
        );
        if self.data.is_empty() {
            if let Some(initial) = initial {
                let _ = writeln!(out, "initial {initial}");
            }
        } else {
            // The data model is declared, and its first values set, by a state that moves on
            // at once: the document's `initial` is the one it moves to.
            let first = initial.or_else(|| self.first_state(root));
            out.push_str("initial DATAMODEL_START\n\nstate DATAMODEL_START {\n    entry {\n");
            for (name, ty, value) in &self.data {
                let _ = writeln!(out, "        {ty} {name}{value};");
            }
            let _ = writeln!(
                out,
                "    }}\n    when TRUE -> {}\n}}",
                first.unwrap_or_default()
            );
        }
        out.push_str(&body);
        out
    }

    fn first_state(&self, root: &Element) -> Option<String> {
        let first = root
            .children
            .iter()
            .find(|c| STATES.contains(&c.name.as_str()))?;
        let id = first.attribute("id")?;
        self.names.get(id).cloned()
    }

    fn datamodel(&mut self, model: &Element) {
        for data in &model.children {
            if data.name != "data" {
                self.unmapped(data, &data.name, "a data model");
                continue;
            }
            let id = data.attribute("id").unwrap_or_default();
            if data.attribute("src").is_some() || !data.text.is_empty() {
                self.refuse(data.line, format!("data `{id}`: a value from `src` or written inside the element does not map; give it as `expr`"));
                continue;
            }
            let expr = data.attribute("expr").unwrap_or("").trim();
            let ty = match (data.attribute("type").unwrap_or(""), expr) {
                (t, _) if t.starts_with("bool") => "bool",
                (t, _) if t.starts_with("float") || t.starts_with("double") => "float",
                (t, _) if t.starts_with("int") || t.starts_with("uint") => "int",
                ("", "true" | "false") => "bool",
                ("", e) if e.contains('.') => "float",
                ("", _) => "int",
                (other, _) => {
                    self.refuse(
                        data.line,
                        format!(
                            "data `{id}`: the type `{other}` does not map (numbers and truths do)"
                        ),
                    );
                    continue;
                }
            };
            let value = match expr {
                "" | "0" | "0.0" | "false" => String::new(),
                e => match self.expression(e, data.line, false) {
                    Some(e) => format!(" = {e}"),
                    None => continue,
                },
            };
            self.data.push((Self::word(id), ty, value));
        }
    }

    /// A state (or final state) and everything in it, written at `depth`.
    fn state(&mut self, element: &Element, out: &mut String, depth: usize) {
        let regions = element
            .children
            .iter()
            .filter(|c| STATES.contains(&c.name.as_str()));
        if element.name == "parallel" && regions.count() == 0 {
            self.refuse(
                element.line,
                "<parallel> holding no states: it has no regions to run".into(),
            );
            return;
        }
        let pad = "    ".repeat(depth);
        let Some(id) = element.attribute("id") else {
            let what = &element.name;
            self.refuse(
                element.line,
                format!("<{what}> without an `id`: give it one (it names the state)"),
            );
            return;
        };
        let path = self.names.get(id).cloned().unwrap_or_default();
        let name = path.rsplit('.').next().unwrap_or(&path).to_string();
        // A `<parallel>`'s children are its regions (§3.2).
        let keyword = if element.name == "parallel" {
            "parallel"
        } else {
            "state"
        };
        let _ = writeln!(out, "\n{pad}{keyword} {name} {{ {}", at(element.line));
        let mut inner = String::new();
        let mut whens = String::new();
        for child in &element.children {
            match child.name.as_str() {
                "onentry" | "onexit" => {
                    let section = if child.name == "onentry" {
                        "entry"
                    } else {
                        "exit"
                    };
                    let actions = self.content(child, depth + 2);
                    if !actions.is_empty() {
                        let _ = write!(out, "{pad}    {section} {{\n{actions}{pad}    }}\n");
                    }
                }
                "transition" => self.transition(child, id, &mut whens, depth + 1),
                "initial" => self.initial(child, &path, &mut whens, depth + 1),
                "state" | "final" | "parallel" => self.state(child, &mut inner, depth + 1),
                "history" => self.history(child, element),
                "datamodel" => self.datamodel(child),
                "donedata" => self.refuse(
                    child.line,
                    "<donedata>: a final state's data does not map".into(),
                ),
                other => self.unmapped(child, other, "a state"),
            }
        }
        if let Some(first) = element.attribute("initial") {
            if let Some(target) = self.own_state(first, &path, element.line) {
                let _ = writeln!(out, "{pad}    initial {target} {}", at(element.line));
            }
        }
        self.never_final(element, id);
        out.push_str(&whens);
        out.push_str(&inner);
        let _ = writeln!(out, "{pad}}}");
    }

    fn initial(&mut self, element: &Element, path: &str, out: &mut String, depth: usize) {
        let pad = "    ".repeat(depth);
        let transition = element.children.iter().find(|c| c.name == "transition");
        match transition.and_then(|t| t.attribute("target").map(|ids| (t, ids))) {
            Some((t, ids)) if t.children.is_empty() => {
                if let Some(target) = self.own_state(ids, path, t.line) {
                    let _ = writeln!(out, "{pad}initial {target} {}", at(t.line));
                }
            }
            _ => self.refuse(
                element.line,
                "<initial>: only a transition with a target and no content maps".into(),
            ),
        }
    }

    fn history(&mut self, element: &Element, composite: &Element) {
        let default = element
            .children
            .iter()
            .find(|c| c.name == "transition")
            .and_then(|t| t.attribute("target"));
        let first = composite.attribute("initial").or_else(|| {
            composite
                .children
                .iter()
                .find(|c| c.name == "initial")
                .and_then(|i| i.children.first())
                .and_then(|t| t.attribute("target"))
        });
        if default.is_some() && default != first {
            self.refuse(element.line, "<history>: a default other than its state's initial does not map (a history resumes at the initial the first time)".into());
        }
    }

    /// `when LABEL -> TARGET { actions }`.
    fn transition(&mut self, element: &Element, owner: &str, out: &mut String, depth: usize) {
        let pad = "    ".repeat(depth);
        let line = element.line;
        let ids = element.attribute("target");
        // Without a target, internal and external are one: it acts and stays.
        if element.attribute("type") == Some("internal") && ids.is_some() {
            self.refuse(line, "<transition type=\"internal\"> with a target: only external transitions map (a transition leaves and enters its states)".into());
            return;
        }
        // `-> TARGET`, or nothing for one that stays (`when p { … }`).
        let arrow = match ids {
            Some(ids) => match self.target(ids, line) {
                Some(target) => format!(" -> {target}"),
                None => return,
            },
            None => String::new(),
        };
        let mut label = Vec::new();
        let completion = format!("done.state.{owner}");
        // SCXML raises these once; their labels here stay true while the machine stays.
        let once = (element.attribute("event").into_iter())
            .flat_map(str::split_whitespace)
            .find(|e| *e == completion || self.timers.contains_key(*e));
        if let (Some(once), true) = (once, arrow.is_empty()) {
            self.refuse(line, format!("<transition event=\"{once}\"> without a target: SCXML raises it once, but its label here stays true in the state, so it would fire in every round"));
            return;
        }
        if element.attribute("event") == Some(completion.as_str()) {
            // The state's own completion: its sub-state is final (§3.2's `done`).
            if element.attribute("cond").is_some() {
                self.refuse(
                    line,
                    format!("`{completion}` with a `cond`: `done` stands alone"),
                );
                return;
            }
            label.push("done".to_string());
        } else if let Some(events) = element.attribute("event") {
            let names: Vec<String> = events
                .split_whitespace()
                .map(|e| {
                    self.timers
                        .get(e)
                        .map_or_else(|| event(e), |t| t.label.clone())
                })
                .collect();
            if events.contains('*') {
                self.refuse(
                    line,
                    format!(
                        "event `{events}`: a wildcard does not map: an event is one label atom"
                    ),
                );
                return;
            }
            match names.as_slice() {
                [] => {}
                [one] => label.push(one.clone()),
                many => label.push(format!("({})", many.join(" || "))),
            }
        }
        if let Some(cond) = element.attribute("cond") {
            let Some(cond) = self.expression(cond, line, true) else {
                return;
            };
            label.push(format!("({cond})"));
        }
        let label = if label.is_empty() {
            "TRUE".to_string()
        } else {
            label.join(" && ")
        };
        let actions = self.content(element, depth + 1);
        let at = at(line);
        if actions.is_empty() && !arrow.is_empty() {
            let _ = writeln!(out, "{pad}when {label}{arrow} {at}");
        } else {
            let _ = write!(out, "{pad}when {label}{arrow} {{ {at}\n{actions}{pad}}}\n");
        }
    }

    /// Executable content, one native action a line.
    fn content(&mut self, block: &Element, depth: usize) -> String {
        let pad = "    ".repeat(depth);
        let mut out = String::new();
        for e in &block.children {
            let line = match e.name.as_str() {
                "assign" => self.assign(e),
                "raise" | "send" => self.send(e),
                // Cancelling a timer on leaving its state: the time test ends with the state.
                "cancel" if self.cancels_a_timer(e) => None,
                "log" => match e.attribute("expr") {
                    Some(expr) => self
                        .expression(expr, e.line, false)
                        .map(|x| format!("print({x});")),
                    None => continue,
                },
                other => {
                    self.unmapped(e, other, "executable content");
                    None
                }
            };
            if let Some(line) = line {
                let _ = writeln!(out, "{pad}{line}");
            }
        }
        out
    }

    fn assign(&mut self, e: &Element) -> Option<String> {
        let location = e.attribute("location").unwrap_or_default();
        if !location.chars().all(|c| c.is_alphanumeric() || c == '_') || location.is_empty() {
            self.refuse(
                e.line,
                format!("<assign location=\"{location}\">: only a plain variable maps"),
            );
            return None;
        }
        let Some(expr) = e.attribute("expr") else {
            self.refuse(
                e.line,
                "<assign> without `expr`: a value written inside it does not map".into(),
            );
            return None;
        };
        let expr = self.expression(expr, e.line, false)?;
        let statement = format!("{} = {expr};", Self::word(location));
        match parse_statements(&statement) {
            Ok(_) => Some(statement),
            Err(err) => {
                self.refuse(
                    e.line,
                    format!("<assign>: `{statement}` does not read: {}", err.message),
                );
                None
            }
        }
    }

    fn send(&mut self, e: &Element) -> Option<String> {
        // A delayed send is its state's time test, or refused already (`delayed.rs`).
        if e.attribute("delay").is_some() {
            return None;
        }
        let what = format!("<{}>", e.name);
        if !e.children.is_empty() {
            self.refuse(e.line, format!("{what} with parameters or content: an event carries no data here (it is a proposition)"));
            return None;
        }
        if let Some((unmapped, value)) = unmapped_send(e) {
            self.refuse(e.line, format!("{what} {unmapped}=\"{value}\": only an event posted to the behaviour's whiteboard maps"));
            return None;
        }
        match e.attribute("event") {
            Some(name) => Some(format!("post(\"{}\", TRUE);", event(name))),
            None => {
                self.refuse(e.line, format!("{what} without `event`"));
                None
            }
        }
    }

    /// A native expression for an ECMAScript one of the small subset that maps; `In(…)` maps
    /// in a `cond` only (a label's `in`).
    fn expression(&mut self, text: &str, line: usize, cond: bool) -> Option<String> {
        if !cond && mentions(text, "In") {
            self.refuse(
                line,
                format!("`{text}`: `In(…)` maps in a transition's `cond` only"),
            );
            return None;
        }
        for (what, why) in [
            (
                "_event",
                "an event's data (`_event`): events carry none here",
            ),
            ("function", "a function"),
        ] {
            if mentions(text, what) {
                self.refuse(line, format!("`{text}`: {why}"));
                return None;
            }
        }
        let mapped = double_quoted(&text.replace("===", "==").replace("!==", "!="));
        match parse_expression(&mapped) {
            Ok(mut e) => {
                // `In('s')`: the native `in(PATH)` of the state that id names.
                let mut unknown = Vec::new();
                e.replace_calls(&mut |function, arguments| {
                    if function != "In" {
                        return None;
                    }
                    let path = match arguments {
                        [Expr::Str(id)] => self.names.get(id).cloned(),
                        _ => None,
                    };
                    if path.is_none() {
                        unknown.push(
                            arguments
                                .iter()
                                .map(ToString::to_string)
                                .collect::<Vec<_>>()
                                .join(", "),
                        );
                    }
                    Some(Expr::Call {
                        function: "in".into(),
                        arguments: vec![Expr::Name(path.unwrap_or_default())],
                        clock: None,
                    })
                });
                if let Some(which) = unknown.first() {
                    self.refuse(line, format!("`{text}`: `In({which})` names no state of the document (it takes one state's id, quoted)"));
                    return None;
                }
                Some(e.to_string())
            }
            Err(err) => {
                self.refuse(
                    line,
                    format!("`{text}` does not read as an expression: {}", err.message),
                );
                None
            }
        }
    }

    /// An `initial`'s states, written from inside `path`: each a state inside it (a deeper one
    /// too), several one in each of several regions; a history has no native form here.
    fn own_state(&mut self, ids: &str, path: &str, line: usize) -> Option<String> {
        let targets = self.initial_target(ids, line)?;
        let mut own = Vec::new();
        for target in targets.split(", ") {
            let inside = relative(target, path);
            let history = ["history", "deep_history"]
                .iter()
                .any(|h| inside.rsplit('.').next() == Some(h));
            if inside == target || history {
                self.refuse(line, format!("initial `{ids}`: only states inside `{path}` map (not a history, or a state outside it)"));
                return None;
            }
            own.push(inside);
        }
        Some(own.join(", "))
    }

    /// A `<state>` with no transition is final here (§3.2), which SCXML's is not: that differs
    /// only where its composite `id` waits for its completion, which is refused.
    fn never_final(&mut self, element: &Element, id: &str) {
        let completion = format!("done.state.{id}");
        let waits = element
            .children
            .iter()
            .any(|t| t.name == "transition" && t.attribute("event") == Some(completion.as_str()));
        if !waits {
            return;
        }
        let moves = |c: &Element| {
            c.children.iter().any(|t| {
                matches!(
                    t.name.as_str(),
                    "transition" | "state" | "parallel" | "final"
                )
            })
        };
        for c in &element.children {
            if c.name == "state" && !moves(c) {
                let which = c.attribute("id").unwrap_or_default().to_string();
                self.refuse(c.line, format!("<state id=\"{which}\"> has no transition, so it would be final here, which SCXML's is not, and `{id}` waits for its completion: write it as <final>"));
            }
        }
    }

    /// The native target of a `target` attribute: a state's path or a history's; several
    /// states (`target="a b"`, one in each of several regions) as `a, b`.
    fn target(&mut self, ids: &str, line: usize) -> Option<String> {
        let ids: Vec<&str> = ids.split_whitespace().collect();
        if ids.is_empty() {
            self.refuse(line, "an empty `target` (or `initial`): name a state, or leave the attribute out for a transition that stays".into());
            return None;
        }
        if let [id] = ids.as_slice() {
            if let Some(history) = self.histories.get(*id) {
                return Some(history.clone());
            }
        }
        let mut paths: Vec<String> = Vec::new();
        for id in &ids {
            if self.histories.contains_key(*id) {
                self.refuse(line, format!("target \"{}\": a history among several targets does not map (a history resumes one state of its own)", ids.join(" ")));
                return None;
            }
            let Some(path) = self.names.get(*id).cloned() else {
                self.refuse(line, format!("no state has the id `{id}`"));
                return None;
            };
            if let Some(other) = paths.iter().find(|o| !self.apart_in_regions(o, &path)) {
                self.refuse(line, format!("target \"{}\": `{other}` and `{path}` are not in different regions of a <parallel>, so they are no configuration", ids.join(" ")));
                return None;
            }
            paths.push(path);
        }
        Some(paths.join(", "))
    }

    /// The states an `initial` names: one, or one in each of several regions (`a, b`); not a
    /// history.
    fn initial_target(&mut self, ids: &str, line: usize) -> Option<String> {
        let targets = self.target(ids, line)?;
        if self.histories.values().any(|h| *h == targets) {
            self.refuse(line, format!("initial `{ids}`: a history as an initial state does not map (name the state it would resume the first time)"));
            return None;
        }
        Some(targets)
    }

    /// Whether the states at paths `a` and `b` lie in different regions of a `<parallel>`:
    /// neither holds the other, and the innermost state around both is parallel.
    fn apart_in_regions(&self, a: &str, b: &str) -> bool {
        let (a, b): (Vec<&str>, Vec<&str>) = (a.split('.').collect(), b.split('.').collect());
        let common = a.iter().zip(&b).take_while(|(x, y)| x == y).count();
        common < a.len().min(b.len()) && self.parallels.contains(&a[..common].join("."))
    }

    fn cancels_a_timer(&self, e: &Element) -> bool {
        let id = e.attribute("sendid");
        id.is_some() && self.timers.values().any(|t| t.id.as_deref() == id)
    }

    fn unmapped(&mut self, e: &Element, name: &str, inside: &str) {
        if e.foreign {
            return;
        }
        let why = match name {
            "script" => "a script: only the small expression data model maps",
            "invoke" => "invoking another machine: use a sub-machine started by a posting",
            "if" | "elseif" | "else" | "foreach" => "control flow in executable content: the activity language has `for` but no `if` yet",
            "cancel" => "cancelling a send other than the delayed one that times a state (name it by `sendid`)",
            _ => "not an SCXML element proclaim maps",
        };
        self.refuse(e.line, format!("<{name}> in {inside}: {why}"));
    }
}

/// The comment that ties a native line to the document's: `check`, `verify` and traces then
/// say the document's line ([`lines_of_the_document`]).
fn at(line: usize) -> String {
    format!("{MARK}{line}")
}

const MARK: &str = "// SCXML line ";

/// The machine's lines made the document's, from the native text's marks.
fn lines_of_the_document(machine: &mut crate::Machine, native: &str) {
    let mut last = 1;
    let document: Vec<usize> = native
        .lines()
        .map(|l| {
            if let Some(n) = l.rsplit_once(MARK).and_then(|(_, n)| n.trim().parse().ok()) {
                last = n;
            }
            last
        })
        .collect();
    let of = |line: usize| document.get(line.wrapping_sub(1)).copied().unwrap_or(line);
    for s in &mut machine.states {
        s.line = of(s.line);
    }
    for t in &mut machine.transitions {
        t.line = of(t.line);
    }
    for c in &mut machine.composites {
        c.line = of(c.line);
    }
}

/// Whether `text` names `word` as a whole identifier (`In(` but not `Index(`, `_event` but not
/// `my_event`).
fn mentions(text: &str, word: &str) -> bool {
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    text.match_indices(word).any(|(at, _)| {
        let before = text[..at].chars().next_back();
        let after = text[at + word.len()..].chars().next();
        !before.is_some_and(ident) && !after.is_some_and(ident)
    })
}

/// ECMAScript's single-quoted strings as the activity language's double-quoted ones.
fn double_quoted(text: &str) -> String {
    let mut out = String::new();
    let mut quote: Option<char> = None;
    let mut chars = text.chars();
    while let Some(c) = chars.next() {
        match (quote, c) {
            (None, '\'' | '"') => {
                quote = Some(c);
                out.push('"');
            }
            (Some(q), c) if c == q => {
                quote = None;
                out.push('"');
            }
            (Some(_), '\\') => {
                out.push('\\');
                out.extend(chars.next());
            }
            (Some('\''), '"') => out.push_str("\\\""),
            (_, c) => out.push(c),
        }
    }
    out
}

/// The first attribute of a `<send>` that says more than "post this event here" (a target
/// other than the document itself, a type, an event or delay computed at run time), with its
/// value.
fn unmapped_send(e: &Element) -> Option<(&'static str, &str)> {
    let unmapped = [
        "target",
        "targetexpr",
        "type",
        "delayexpr",
        "eventexpr",
        "namelist",
        "idlocation",
    ];
    unmapped.into_iter().find_map(|name| {
        let value = e.attribute(name)?;
        (!(name == "target" && value == "#_internal")).then_some((name, value))
    })
}

/// An event name as a label atom: `a.b-c` is `a_b_c`.
fn event(name: &str) -> String {
    Mapping::word(name)
}

/// A path written from inside `within` when it lies inside it (`initial` names a state of its
/// own composite).
fn relative(path: &str, within: &str) -> String {
    path.strip_prefix(&format!("{within}."))
        .unwrap_or(path)
        .to_string()
}
