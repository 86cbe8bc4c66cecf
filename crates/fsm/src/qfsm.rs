//! Qfsm `.fsm` XML, as the team drew its machines: `<state code=… description=ACTIVITIES>NAME`,
//! `<transition><from/><to/><inputs>LABEL</inputs><outputs>PRIORITY</outputs>`, larger priority
//! tried first. Traps handled: link files (a path instead of XML), missing `<from>`/`<to>`,
//! several machines in one file, no DTD, escaped labels (`&amp;&amp;`).

use crate::activity::{parse_description, Description};
use crate::code::Expr;
use crate::label::parse_label;
use crate::model::{Machine, State, StateId, Transition, UnreadTransition};
use crate::sections::is_sectioned;
use crate::Imported;
use proclaim_syntax::{FileDiagnostic, Severity};
use quick_xml::events::{BytesStart, Event};
use quick_xml::{Reader, XmlVersion};
use std::collections::HashSet;

#[derive(Default)]
struct TransitionDraft {
    from: Option<String>,
    to: Option<String>,
    inputs: String,
    invert: bool,
    any: bool,
    outputs: String,
    line: usize,
}

struct MachineDraft {
    /// The `name` attribute, which qfsm2gu and gufsm ignored (it is often `FSM`, or copied
    /// from another machine): the file's name names the machine.
    attribute_name: String,
    initial: Option<String>,
    states: Vec<State>,
    /// The codes of `states`, so that each state and transition is placed in constant time.
    codes: HashSet<StateId>,
    transitions: Vec<(i64, usize, Transition)>,
    unread: Vec<UnreadTransition>,
    /// The machine's own description, in the later editors' sectioned form where it has one
    /// (its `$variables$` are the machine's, its `$includes$` a note).
    description: String,
    /// What the descriptions said that is kept but not run: C++ includes.
    notes: Vec<String>,
    line: usize,
}

/// Imports every machine of a Qfsm file. A file's one machine is named `file_name` (the file's
/// name without `.fsm`, as qfsm2gu and gufsm named it); its `name` attribute, when it differs,
/// becomes the description. Several machines in one file keep their `name` attributes.
pub fn import_qfsm(file: &str, text: &str, file_name: &str) -> Imported {
    let mut drafts = Drafts::new(file, file_name);
    if !text.trim().starts_with('<') {
        drafts.out.diagnostics.push(not_xml(file, text));
        return drafts.out;
    }
    let mut lines = LineCounter::default();
    let mut line_of = |offset: u64| lines.line_of(text, offset as usize);
    let mut reader = Reader::from_str(text);
    loop {
        let position = reader.buffer_position();
        let event = match reader.read_event() {
            Ok(e) => e,
            Err(e) => {
                drafts.out.diagnostics.push(FileDiagnostic::error(
                    file,
                    line_of(reader.error_position()),
                    format!("malformed XML: {e}"),
                ));
                break;
            }
        };
        let line = line_of(position);
        match event {
            Event::Start(e) => drafts.start(&e, line),
            Event::Empty(e) if e.local_name().as_ref() == "machine" => drafts.start(&e, line),
            Event::Text(t) => drafts.text(&t.xml10_content()),
            Event::CData(t) => drafts.text(&t),
            Event::GeneralRef(r) => drafts.text(&entity(&r.xml10_content())),
            Event::End(e) => drafts.end(e.local_name().as_ref()),
            Event::Eof => break,
            _ => {}
        }
    }
    end_of_file(drafts.machine, file, file_name, &mut drafts.out);
    drafts.out
}

/// The line of each offset the reader reaches, counted on from the last one asked (offsets
/// grow as the file is read), so numbering every element takes one pass over the text, not
/// one a element.
#[derive(Default)]
struct LineCounter {
    offset: usize,
    line: usize,
}

impl LineCounter {
    fn line_of(&mut self, text: &str, offset: usize) -> usize {
        let offset = offset.min(text.len());
        if offset < self.offset {
            *self = LineCounter::default();
        }
        self.line += text.as_bytes()[self.offset..offset]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        self.offset = offset;
        self.line + 1
    }
}

/// What a Qfsm file has said so far: the machines finished, and the machine, state and
/// transition being read, each element's end its own step (`end_state`, `end_transition`,
/// `finish`).
struct Drafts<'f> {
    file: &'f str,
    file_name: &'f str,
    out: Imported,
    machine: Option<MachineDraft>,
    state: Option<StateDraft>,
    transition: Option<TransitionDraft>,
    /// The element whose text is being read.
    field: Option<&'static str>,
    /// How many transitions were read: their order in the file.
    order: usize,
}

impl<'f> Drafts<'f> {
    fn new(file: &'f str, file_name: &'f str) -> Drafts<'f> {
        Drafts {
            file,
            file_name,
            out: Imported::default(),
            machine: None,
            state: None,
            transition: None,
            field: None,
            order: 0,
        }
    }

    fn start(&mut self, e: &BytesStart<'_>, line: usize) {
        match e.local_name().as_ref() {
            "machine" => {
                self.machine = Some(MachineDraft {
                    attribute_name: attribute(e, "name").unwrap_or_default(),
                    initial: attribute(e, "initialstate"),
                    states: Vec::new(),
                    codes: HashSet::new(),
                    transitions: Vec::new(),
                    unread: Vec::new(),
                    description: attribute(e, "description").unwrap_or_default(),
                    notes: Vec::new(),
                    line,
                });
            }
            "state" => {
                self.state = Some(StateDraft {
                    code: attribute(e, "code"),
                    description: attribute(e, "description").unwrap_or_default(),
                    name: String::new(),
                    line,
                });
                self.field = Some("state");
            }
            "transition" => {
                self.transition = Some(TransitionDraft {
                    line,
                    ..Default::default()
                });
            }
            _ => {
                if let Some(t) = self.transition.as_mut() {
                    self.field = transition_field(e, t);
                }
            }
        }
    }

    fn text(&mut self, text: &str) {
        append(&mut self.state, &mut self.transition, self.field, text);
    }

    fn end(&mut self, name: &str) {
        match name {
            "state" => {
                self.field = None;
                if let (Some(draft), Some(m)) = (self.state.take(), self.machine.as_mut()) {
                    end_state(draft, m, self.file, &mut self.out.diagnostics);
                }
            }
            "from" | "to" | "inputs" | "outputs" => self.field = None,
            "transition" => {
                if let (Some(t), Some(m)) = (self.transition.take(), self.machine.as_mut()) {
                    self.order += 1;
                    end_transition(t, self.order, m, self.file, &mut self.out.diagnostics);
                }
            }
            "machine" => {
                if let Some(m) = self.machine.take() {
                    finish(m, self.file, self.file_name, &mut self.out);
                }
            }
            _ => {}
        }
    }
}

/// Which part of a `<transition>` an element starts (`<inputs>` also says whether the label
/// is inverted or the default).
fn transition_field(e: &BytesStart<'_>, t: &mut TransitionDraft) -> Option<&'static str> {
    match e.local_name().as_ref() {
        "from" => Some("from"),
        "to" => Some("to"),
        "inputs" => {
            t.invert = attribute(e, "invert").as_deref() == Some("1");
            t.any = attribute(e, "any").as_deref() == Some("1")
                || attribute(e, "default").as_deref() == Some("1");
            Some("inputs")
        }
        "outputs" => Some("outputs"),
        _ => None,
    }
}

/// A machine left open is still read (with an error); a file's one machine is named after the
/// file, as qfsm2gu did; a file with none says so.
fn end_of_file(machine: Option<MachineDraft>, file: &str, file_name: &str, out: &mut Imported) {
    if let Some(m) = machine {
        out.diagnostics.push(FileDiagnostic::error(
            file,
            m.line,
            format!("machine `{}` is not closed", m.attribute_name),
        ));
        finish(m, file, file_name, out);
    }
    if let [only] = out.machines.as_mut_slice() {
        if only.name != file_name {
            let attribute_name = std::mem::replace(&mut only.name, file_name.to_string());
            only.description = if only.description.is_empty() {
                attribute_name
            } else {
                format!("{attribute_name}\n{}", only.description)
            };
        }
    }
    if out.machines.is_empty() && !out.has_errors() {
        out.diagnostics
            .push(FileDiagnostic::error(file, 1, "no <machine> in this file"));
    }
}

/// Why a file that does not start with XML is not read.
fn not_xml(file: &str, text: &str) -> FileDiagnostic {
    let first = text.trim().lines().next().unwrap_or("");
    let message = if first.ends_with(".fsm") && !first.contains(char::is_whitespace) {
        format!("this file only names another file, `{first}` (a link saved as text); import that file instead")
    } else {
        "not a Qfsm file: it does not start with XML".to_string()
    };
    FileDiagnostic::error(file, 1, message)
}

/// A `<state>` as read, until its end.
struct StateDraft {
    code: Option<String>,
    description: String,
    name: String,
    line: usize,
}

/// A state read whole: its code checked, its activities parsed, added to the machine.
fn end_state(
    draft: StateDraft,
    m: &mut MachineDraft,
    file: &str,
    diagnostics: &mut Vec<FileDiagnostic>,
) {
    let StateDraft {
        code,
        description,
        name,
        line: at,
    } = draft;
    let Some(id) = code
        .as_deref()
        .and_then(|c| c.trim().parse::<StateId>().ok())
    else {
        diagnostics.push(FileDiagnostic::error(
            file,
            at,
            format!("state `{}` has no numeric code", name.trim()),
        ));
        return;
    };
    let Description {
        activities: [on_entry, on_exit, internal],
        notes,
        problems,
    } = parse_description(&description);
    m.notes.extend(
        notes
            .into_iter()
            .map(|note| format!("state {}: {note}", name.trim())),
    );
    diagnostics.extend(problems.into_iter().map(|(severity, problem)| {
        problem_at(
            severity,
            file,
            at,
            format!("state `{}`: {problem}", name.trim()),
        )
    }));
    if !m.codes.insert(id) {
        diagnostics.push(FileDiagnostic::error(
            file,
            at,
            format!("state code {id} is used twice"),
        ));
        return;
    }
    m.states.push(State {
        id,
        name: name.trim().to_string(),
        on_entry,
        on_exit,
        internal,
        line: at,
        arrives_through: 0,
        arrival_clocks: Vec::new(),
    });
}

/// A transition read whole: its ends attached, its label parsed (kept unread when it does not
/// parse), its priority read; added to the machine as the `order`th.
fn end_transition(
    t: TransitionDraft,
    order: usize,
    m: &mut MachineDraft,
    file: &str,
    diagnostics: &mut Vec<FileDiagnostic>,
) {
    // Qfsm writes `-1` for an end it could not attach, or leaves the end out.
    fn attached(end: Option<&str>) -> Option<&str> {
        end.map(str::trim).filter(|e| *e != "-1")
    }
    let (Some(from), Some(to)) = (attached(t.from.as_deref()), attached(t.to.as_deref())) else {
        diagnostics.push(FileDiagnostic::warning(
            file,
            t.line,
            "a transition without `<from>` or `<to>` (drawn but not attached) is skipped",
        ));
        return;
    };
    let (Ok(source), Ok(target)) = (from.parse::<StateId>(), to.parse::<StateId>()) else {
        diagnostics.push(FileDiagnostic::error(
            file,
            t.line,
            format!("`{from}` → `{to}` are not state codes"),
        ));
        return;
    };
    let label = if t.any {
        Ok(Expr::TRUE)
    } else {
        parse_label(&t.inputs).map(|l| if t.invert { Expr::negation(l) } else { l })
    };
    let label = match label {
        Ok(l) => l,
        Err(e) => {
            diagnostics.push(FileDiagnostic::error(
                file,
                t.line,
                format!("label `{}`: {e}", t.inputs.trim()),
            ));
            m.unread.push(UnreadTransition {
                source,
                target,
                label: t.inputs.trim().to_string(),
                reason: e.to_string(),
                line: t.line,
            });
            return;
        }
    };
    let priority = priority(&t, file, diagnostics);
    m.transitions.push((
        priority,
        order,
        Transition {
            source,
            target,
            label,
            line: t.line,
            leaving: None,
            composite: None,
            enters: Vec::new(),
            written: None,
            joined: Vec::new(),
            stays: false,
            targets: Vec::new(),
        },
    ));
}

/// A transition's priority, Qfsm's `<outputs>`: 0 when empty, or (with a warning) when not
/// a number.
fn priority(t: &TransitionDraft, file: &str, diagnostics: &mut Vec<FileDiagnostic>) -> i64 {
    match t.outputs.trim() {
        "" => 0,
        written => written.parse::<i64>().unwrap_or_else(|_| {
            diagnostics.push(FileDiagnostic::warning(
                file,
                t.line,
                format!("priority `{written}` is not a number; 0 is used"),
            ));
            0
        }),
    }
}

fn finish(mut m: MachineDraft, file: &str, file_name: &str, out: &mut Imported) {
    let initial = match m
        .initial
        .as_deref()
        .map(str::trim)
        .and_then(|c| c.parse::<StateId>().ok())
    {
        Some(code) if m.codes.contains(&code) => code,
        Some(code) => {
            out.diagnostics.push(FileDiagnostic::error(
                file,
                m.line,
                format!(
                    "initial state {code} of `{}` is not one of its states",
                    m.attribute_name
                ),
            ));
            return;
        }
        None => {
            out.diagnostics.push(FileDiagnostic::error(
                file,
                m.line,
                format!("machine `{}` names no initial state", m.attribute_name),
            ));
            return;
        }
    };
    let known = |id: StateId| m.codes.contains(&id);
    let mut transitions = Vec::new();
    for (priority, order, t) in std::mem::take(&mut m.transitions) {
        if known(t.source) && known(t.target) {
            transitions.push((priority, order, t));
        } else {
            out.diagnostics.push(FileDiagnostic::error(
                file,
                t.line,
                format!(
                    "transition {} → {} names a state that does not exist",
                    t.source, t.target
                ),
            ));
        }
    }
    // Per source state: larger <outputs> first; equal priorities keep the file's order.
    transitions.sort_by(|a, b| {
        a.2.source
            .cmp(&b.2.source)
            .then(b.0.cmp(&a.0))
            .then(a.1.cmp(&b.1))
    });
    let notes = machine_description(&mut m, initial, file, out);
    let name = if m.attribute_name.trim().is_empty() {
        format!("{file_name}_{}", out.machines.len() + 1)
    } else {
        m.attribute_name.trim().to_string()
    };
    out.machines.push(Machine {
        name,
        states: m.states,
        transitions: transitions.into_iter().map(|(_, _, t)| t).collect(),
        initial,
        unread: m.unread,
        composites: Vec::new(),
        interface: Default::default(),
        description: notes.join("\n"),
    });
}

/// The machine's own description, in the later editors' sectioned form: its problems reported,
/// its `$variables$` declared where the machine starts; returns what to keep as notes (its
/// `$includes$`, then the states'). An older machine description is prose, and says nothing.
fn machine_description(
    m: &mut MachineDraft,
    initial: StateId,
    file: &str,
    out: &mut Imported,
) -> Vec<String> {
    let machine_level = if is_sectioned(&m.description) {
        parse_description(&m.description)
    } else {
        Description::default()
    };
    out.diagnostics.extend(
        machine_level
            .problems
            .into_iter()
            .map(|(severity, problem)| {
                problem_at(
                    severity,
                    file,
                    m.line,
                    format!("machine description: {problem}"),
                )
            }),
    );
    let [declarations, ..] = machine_level.activities;
    if let Some(start) = m.states.iter_mut().find(|s| s.id == initial) {
        start.on_entry.splice(0..0, declarations);
    }
    let mut notes = machine_level.notes;
    notes.append(&mut m.notes);
    notes
}

/// A description's problem, placed at the line of the element it came from.
fn problem_at(severity: Severity, file: &str, line: usize, message: String) -> FileDiagnostic {
    match severity {
        Severity::Error => FileDiagnostic::error(file, line, message),
        Severity::Warning => FileDiagnostic::warning(file, line, message),
    }
}

fn attribute(e: &BytesStart<'_>, name: &str) -> Option<String> {
    e.attributes()
        .flatten()
        .find(|a| a.key.local_name().as_ref() == name)
        .map(|a| {
            a.normalized_value(XmlVersion::Implicit1_0)
                .map(|v| v.into_owned())
                .unwrap_or_else(|_| a.value.to_string())
        })
}

/// The text of an entity reference (`amp`, `#xa`, `#10`).
fn entity(name: &str) -> String {
    match name {
        "amp" => "&".into(),
        "lt" => "<".into(),
        "gt" => ">".into(),
        "quot" => "\"".into(),
        "apos" => "'".into(),
        _ => {
            let code = name
                .strip_prefix("#x")
                .and_then(|h| u32::from_str_radix(h, 16).ok())
                .or_else(|| name.strip_prefix('#').and_then(|d| d.parse().ok()));
            code.and_then(char::from_u32)
                .map_or_else(|| format!("&{name};"), String::from)
        }
    }
}

fn append(
    state: &mut Option<StateDraft>,
    transition: &mut Option<TransitionDraft>,
    field: Option<&'static str>,
    text: &str,
) {
    match (field, state.as_mut(), transition.as_mut()) {
        (Some("state"), Some(s), _) => s.name.push_str(text),
        (Some("from"), _, Some(t)) => t.from.get_or_insert_with(String::new).push_str(text),
        (Some("to"), _, Some(t)) => t.to.get_or_insert_with(String::new).push_str(text),
        (Some("inputs"), _, Some(t)) => t.inputs.push_str(text),
        (Some("outputs"), _, Some(t)) => t.outputs.push_str(text),
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::LineCounter;

    #[test]
    fn lines_are_counted_on_from_the_last_offset_and_anew_after_a_step_back() {
        let text = "a\nbb\n\nccc\nd";
        let naive = |o: usize| text[..o.min(text.len())].matches('\n').count() + 1;
        let mut lines = LineCounter::default();
        for offset in [0, 1, 2, 4, 5, 6, 9, 10, 11, 3, 7, 100] {
            assert_eq!(
                lines.line_of(text, offset),
                naive(offset),
                "offset {offset}"
            );
        }
    }
}
