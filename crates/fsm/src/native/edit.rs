//! Edits of a native machine file applied as text patches at the reader's spans, so that what
//! an edit does not touch (comments, order, spacing, ids) stays byte for byte as written.
//!
//! States are named by their position in the file and transitions by their position among
//! their state's `when`s (their priority), because names may repeat where ids tell them apart.

use super::ast::{Ref, Section};
use super::outline::{Outline, StateAt};
use super::write::name;
use super::{parse_machine, EditError, LineIndex};
use crate::format::{machine_format, MachineFormat};
use crate::lint::lint;
use proclaim_syntax::FileDiagnostic;
use std::ops::Range;
use std::path::Path;

/// One change a person makes to a machine.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Edit {
    /// A new state with no activities and no transitions, after the last.
    AddState {
        name: String,
    },
    /// The state and every transition and `initial` that names it.
    RenameState {
        state: usize,
        to: String,
    },
    /// Refused while another state's transition leads to it, or while it is the initial state;
    /// its own transitions go with it.
    DeleteState {
        state: usize,
    },
    SetInitial {
        state: usize,
    },
    /// A final state is one with no way out: its transitions are deleted.
    MakeFinal {
        state: usize,
    },
    /// A transition of the lowest priority (last) of its state.
    AddTransition {
        state: usize,
        label: String,
        target: usize,
    },
    DeleteTransition {
        state: usize,
        transition: usize,
    },
    /// The transition moved to priority `to` (0 = tried first), the others shifting.
    MoveTransition {
        state: usize,
        from: usize,
        to: usize,
    },
    SetLabel {
        state: usize,
        transition: usize,
        label: String,
    },
    SetTarget {
        state: usize,
        transition: usize,
        target: usize,
    },
    /// The activity's text as a person writes it inside its braces; empty deletes the block.
    SetActivity {
        state: usize,
        section: Section,
        text: String,
    },
}

/// An edit's result: the new text, what `check` says of it, and where the edit wrote.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Edited {
    pub text: String,
    /// The reader's and the linter's diagnostics of the new text, as `proclaim check` gives them.
    pub diagnostics: Vec<FileDiagnostic>,
    /// The bytes of the new text the edit wrote (empty where it only deleted).
    pub written: Range<usize>,
}

impl Edited {
    /// The diagnostics placed inside what the edit wrote (a label's or an activity's box), each
    /// with its byte offset from the start of the written text.
    pub fn in_written(&self) -> Vec<(usize, &FileDiagnostic)> {
        let lines = LineIndex::new(&self.text);
        self.diagnostics
            .iter()
            .filter_map(|d| {
                let at = lines.offset(d.line?, d.column.unwrap_or(1))?;
                let inside = self.written.contains(&at)
                    || (at == self.written.end && !self.written.is_empty());
                inside.then(|| (at - self.written.start, d))
            })
            .collect()
    }
}

/// What `proclaim check MACHINE` says of a native machine's text: the reader's problems and,
/// when it reads, the linter's warnings.
pub fn check_native(file: &str, text: &str) -> Vec<FileDiagnostic> {
    let mut imported = parse_machine(file, text);
    let lints: Vec<FileDiagnostic> = imported
        .machines
        .iter()
        .flat_map(|m| lint(m, file))
        .collect();
    imported.diagnostics.extend(lints);
    imported.diagnostics
}

/// Whether the machine file at `path` can be edited in place: native files only. Qfsm and T/A
/// machines are refused with a way out (`proclaim import`), never converted behind the person's
/// back nor written in a format that would lose their layout.
pub fn editable(path: &Path) -> Result<(), EditError> {
    match machine_format(path) {
        Some(MachineFormat::Native) => Ok(()),
        Some(MachineFormat::Qfsm { .. }) => Err(EditError::NotNative {
            format: "Qfsm".into(),
        }),
        Some(MachineFormat::Scxml { .. }) => Err(EditError::NotNative {
            format: "SCXML".into(),
        }),
        Some(MachineFormat::TablePair { .. }) => Err(EditError::NotNative {
            format: "T/A table".into(),
        }),
        None => Err(EditError::NotNative {
            format: "unknown (not .machine, .fsm or a T/A pair)".into(),
        }),
    }
}

/// The machine in `text` with `edit` made, or why it cannot be made.
pub fn edit_native(file: &str, text: &str, edit: &Edit) -> Result<Edited, EditError> {
    let outline = read(text)?;
    let patches = Patcher {
        text,
        outline: &outline,
    }
    .patches(edit)?;
    let (new_text, written) = apply(text, patches);
    Ok(Edited {
        diagnostics: check_native(file, &new_text),
        text: new_text,
        written,
    })
}

/// A state of a machine file as the editor shows it: everything as written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StateView {
    pub name: String,
    pub id: i64,
    /// Each written activity's text, dedented, in file order.
    pub activities: Vec<ActivityView>,
    pub transitions: Vec<TransitionView>,
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ActivityView {
    pub section: Section,
    pub text: String,
    /// The lines of its block, braces included (1-based), where its diagnostics fall.
    pub lines: std::ops::RangeInclusive<usize>,
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TransitionView {
    /// Its line (1-based), where its label's diagnostics fall.
    pub line: usize,
    pub label: String,
    /// The target's position, `None` when the reference resolves to no single state.
    pub target: Option<usize>,
    pub target_as_written: String,
}

/// The states of `text` as written, for an editor to show, with the initial state's position.
pub fn view_native(text: &str) -> Result<(Vec<StateView>, Option<usize>), EditError> {
    let outline = read(text)?;
    let ids = outline.ids();
    let lines = LineIndex::new(text);
    let states = outline
        .states
        .iter()
        .zip(ids)
        .map(|(s, id)| StateView {
            name: s.name.clone(),
            id,
            activities: s
                .activities
                .iter()
                .map(|a| ActivityView {
                    section: a.section,
                    text: dedent(&text[a.open + 1..a.close]),
                    lines: lines.line(a.start)..=lines.line(a.close),
                })
                .collect(),
            transitions: s
                .whens
                .iter()
                .map(|w| TransitionView {
                    line: lines.line(w.start),
                    label: text[w.label.clone()].to_string(),
                    target: outline.resolve(&w.target.reference),
                    target_as_written: text[w.target.span.clone()].to_string(),
                })
                .collect(),
        })
        .collect();
    let initial = match &outline.initial {
        Some(r) => outline.resolve(&r.reference),
        None if !outline.states.is_empty() => Some(0),
        None => None,
    };
    Ok((states, initial))
}

fn read(text: &str) -> Result<Outline, EditError> {
    Outline::read(text).map_err(|e| {
        let line = LineIndex::new(text).line(e.at);
        let read = super::parse_machine("", text);
        match read.machines.first().filter(|_| !read.has_errors()) {
            Some(m) if !m.composites.is_empty() => EditError::Unsupported {
                line: m.composites[0].line,
                what: "nests states",
            },
            Some(m) if m.transitions.iter().any(|t| t.stays) => EditError::Unsupported {
                line: (m.transitions.iter().find(|t| t.stays)).map_or(line, |t| t.line),
                what: "has a transition that stays (no target)",
            },
            Some(_) => EditError::Unsupported {
                line,
                what: "gives a transition actions of its own",
            },
            None => EditError::DoesNotParse {
                line,
                message: e.message,
            },
        }
    })
}

/// One replacement of a byte range; `primary` marks the one whose new text is the edit's box.
struct Patch {
    range: Range<usize>,
    with: String,
    primary: bool,
}

fn patch(range: Range<usize>, with: impl Into<String>) -> Patch {
    Patch {
        range,
        with: with.into(),
        primary: false,
    }
}

fn primary(range: Range<usize>, with: impl Into<String>) -> Patch {
    Patch {
        primary: true,
        ..patch(range, with)
    }
}

/// The patches applied (they never overlap), and where the primary one's text landed.
fn apply(text: &str, mut patches: Vec<Patch>) -> (String, Range<usize>) {
    patches.sort_by_key(|p| (p.range.start, p.range.end));
    let mut out = String::with_capacity(text.len() + 64);
    let mut copied = 0;
    let mut written = 0..0;
    for p in patches {
        out.push_str(&text[copied..p.range.start]);
        let start = out.len();
        out.push_str(&p.with);
        if p.primary {
            written = start..out.len();
        }
        copied = p.range.end;
    }
    out.push_str(&text[copied..]);
    (out, written)
}

struct Patcher<'a> {
    text: &'a str,
    outline: &'a Outline,
}

impl Patcher<'_> {
    fn patches(&self, edit: &Edit) -> Result<Vec<Patch>, EditError> {
        match edit {
            Edit::AddState { name } => self.add_state(name),
            Edit::RenameState { state, to } => self.rename(*state, to),
            Edit::DeleteState { state } => self.delete_state(*state),
            Edit::SetInitial { state } => self.set_initial(*state),
            Edit::MakeFinal { state } => {
                let s = self.state(*state)?;
                Ok(s.whens
                    .iter()
                    .map(|w| patch(self.item_lines(w.start, w.target.span.end), ""))
                    .collect())
            }
            Edit::AddTransition {
                state,
                label,
                target,
            } => {
                let s = self.state(*state)?;
                if let Some(outcome) = &s.outcome {
                    return Err(EditError::Announces {
                        state: s.name.clone(),
                        outcome: outcome.clone(),
                    });
                }
                self.add_transition(*state, label, *target)
            }
            Edit::DeleteTransition { state, transition } => {
                let w = self.when(*state, *transition)?;
                Ok(vec![primary(
                    self.item_lines(w.start, w.target.span.end),
                    "",
                )])
            }
            Edit::MoveTransition { state, from, to } => self.move_transition(*state, *from, *to),
            Edit::SetLabel {
                state,
                transition,
                label,
            } => {
                let w = self.when(*state, *transition)?;
                Ok(vec![primary(w.label.clone(), check_label(label)?)])
            }
            Edit::SetTarget {
                state,
                transition,
                target,
            } => {
                let w = self.when(*state, *transition)?;
                Ok(vec![primary(
                    w.target.span.clone(),
                    self.reference(*target)?,
                )])
            }
            Edit::SetActivity {
                state,
                section,
                text,
            } => self.set_activity(*state, *section, text),
        }
    }

    fn state(&self, state: usize) -> Result<&StateAt, EditError> {
        self.outline
            .states
            .get(state)
            .ok_or(EditError::NoSuchState {
                state,
                count: self.outline.states.len(),
            })
    }

    fn when(&self, state: usize, transition: usize) -> Result<&super::outline::WhenAt, EditError> {
        let s = self.state(state)?;
        s.whens
            .get(transition)
            .ok_or_else(|| EditError::NoSuchTransition {
                state: s.name.clone(),
                transition,
                count: s.whens.len(),
            })
    }

    /// How a transition names the state: by name when it is the only one so named, else by id.
    fn reference(&self, state: usize) -> Result<String, EditError> {
        let s = self.state(state)?;
        if self
            .outline
            .states
            .iter()
            .filter(|o| o.name == s.name)
            .count()
            == 1
        {
            Ok(name(&s.name))
        } else {
            Ok(format!("#{}", self.outline.ids()[state]))
        }
    }

    fn line_of(&self, at: usize) -> usize {
        LineIndex::new(self.text).line(at)
    }

    /// The whole lines from `start` to `end` with their line break, when nothing else is on
    /// them but space and a trailing comment; else just the bytes.
    fn item_lines(&self, start: usize, end: usize) -> Range<usize> {
        let from = line_start(self.text, start);
        let to = line_end(self.text, end);
        let after = self.text[end..to].trim();
        if self.text[from..start].trim().is_empty() && (after.is_empty() || after.starts_with("//"))
        {
            from..(to + 1).min(self.text.len())
        } else {
            start..end
        }
    }

    fn new_name(&self, to: &str, except: Option<usize>) -> Result<String, EditError> {
        let bad = |why| {
            Err(EditError::BadName {
                name: to.to_string(),
                why,
            })
        };
        if to.trim().is_empty() {
            return bad("it is empty");
        }
        if to.contains(['\n', '\r']) {
            return bad("it holds a line break");
        }
        let taken = self
            .outline
            .states
            .iter()
            .enumerate()
            .any(|(i, s)| s.name == to && Some(i) != except);
        if taken {
            return Err(EditError::NameTaken {
                name: to.to_string(),
            });
        }
        Ok(name(to))
    }

    fn add_state(&self, to: &str) -> Result<Vec<Patch>, EditError> {
        let written = self.new_name(to, None)?;
        let end = self.text.len();
        let lead = if self.text.ends_with('\n') {
            "\n"
        } else {
            "\n\n"
        };
        let block = format!("state {written} {{\n}}\n");
        Ok(vec![patch(end..end, lead), primary(end..end, block)])
    }

    fn rename(&self, state: usize, to: &str) -> Result<Vec<Patch>, EditError> {
        let s = self.state(state)?;
        if s.name == to {
            return Ok(vec![primary(
                s.name_span.clone(),
                &self.text[s.name_span.clone()],
            )]);
        }
        let written = self.new_name(to, Some(state))?;
        let mut patches = vec![primary(s.name_span.clone(), written.clone())];
        let by_name = |r: &Ref| matches!(r, Ref::Name(n) if *n == s.name);
        let unique = self.outline.resolve(&Ref::Name(s.name.clone())) == Some(state);
        if unique {
            let refs = self
                .outline
                .states
                .iter()
                .flat_map(|o| o.whens.iter().map(|w| &w.target))
                .chain(&self.outline.initial);
            for r in refs.filter(|r| by_name(&r.reference)) {
                patches.push(patch(r.span.clone(), written.clone()));
            }
            for (span, named, _) in self.in_references() {
                if named == s.name {
                    patches.push(patch(span, written.clone()));
                }
            }
        }
        Ok(patches)
    }

    /// Each `in(NAME)` in a label: the name's span, the name, and where its `when` starts.
    fn in_references(&self) -> Vec<(Range<usize>, String, usize)> {
        let mut out = Vec::new();
        for w in self.outline.states.iter().flat_map(|o| &o.whens) {
            let label = &self.text[w.label.clone()];
            for (at, _) in label.match_indices("in") {
                let word_before = label[..at]
                    .chars()
                    .next_back()
                    .is_some_and(|c| c.is_alphanumeric() || c == '_' || c == '.');
                let rest = &label[at + 2..];
                let Some(inside) = rest.trim_start().strip_prefix('(') else {
                    continue;
                };
                let Some(close) = inside.find(')') else {
                    continue;
                };
                let named = inside[..close].trim();
                if word_before || named.is_empty() {
                    continue;
                }
                let start = w.label.start
                    + at
                    + 2
                    + (rest.len() - inside.len())
                    + (inside.len() - inside.trim_start().len());
                out.push((start..start + named.len(), named.to_string(), w.start));
            }
        }
        out
    }

    fn delete_state(&self, state: usize) -> Result<Vec<Patch>, EditError> {
        let s = self.state(state)?;
        let initial = match &self.outline.initial {
            Some(r) => self.outline.resolve(&r.reference),
            None => Some(0),
        };
        if initial == Some(state) {
            return Err(EditError::Initial {
                state: s.name.clone(),
            });
        }
        let by: Vec<(String, usize)> = self
            .outline
            .states
            .iter()
            .enumerate()
            .filter(|(i, _)| *i != state)
            .flat_map(|(_, o)| o.whens.iter().map(move |w| (o, w)))
            .filter(|(_, w)| self.outline.resolve(&w.target.reference) == Some(state))
            .map(|(o, w)| (o.name.clone(), self.line_of(w.start)))
            .collect();
        // A label that asks `in(S)` of it needs it as much as a transition to it does.
        let asked: Vec<(String, usize)> = (self.in_references().into_iter())
            .filter(|(_, named, _)| self.outline.resolve(&Ref::Name(named.clone())) == Some(state))
            .filter_map(|(_, _, at)| {
                let o = self
                    .outline
                    .states
                    .iter()
                    .find(|o| o.whens.iter().any(|w| w.start == at))?;
                Some((o.name.clone(), self.line_of(at)))
            })
            .collect();
        let by: Vec<(String, usize)> = by.into_iter().chain(asked).collect();
        if !by.is_empty() {
            return Err(EditError::Targeted {
                state: s.name.clone(),
                by,
            });
        }
        // The block, the comment lines right above it, and one blank line before those.
        let lines = self.item_lines(s.start, s.close + 1);
        let mut from = lines.start;
        if lines.start == line_start(self.text, s.start) {
            while from > 0 {
                let above = line_start(self.text, from - 1);
                if self.text[above..from].trim_start().starts_with("//") {
                    from = above;
                } else {
                    break;
                }
            }
            if from > 0 {
                let above = line_start(self.text, from - 1);
                if self.text[above..from].trim().is_empty() {
                    from = above;
                }
            }
        }
        Ok(vec![primary(from..lines.end, "")])
    }

    fn set_initial(&self, state: usize) -> Result<Vec<Patch>, EditError> {
        let written = self.reference(state)?;
        match &self.outline.initial {
            Some(r) => Ok(vec![primary(r.span.clone(), written)]),
            None => {
                let at = line_end(self.text, self.outline.header_end);
                Ok(vec![primary(at..at, format!("\ninitial {written}"))])
            }
        }
    }

    fn member_indent(&self, s: &StateAt) -> String {
        let first = s
            .activities
            .iter()
            .map(|a| a.start)
            .chain(s.whens.iter().map(|w| w.start))
            .min();
        match first {
            Some(at) if self.text[line_start(self.text, at)..at].trim().is_empty() => {
                self.text[line_start(self.text, at)..at].to_string()
            }
            _ => format!("{}    ", indent_of(self.text, s.start)),
        }
    }

    /// Inserts `item` (without indent or line break) as a line of the state just before
    /// `before` (a member's start), or at the end of the state's block.
    fn insert_line(&self, s: &StateAt, before: Option<usize>, item: &str) -> Vec<Patch> {
        let indent = self.member_indent(s);
        let at = before.unwrap_or(s.close);
        let start = line_start(self.text, at);
        if self.text[start..at].trim().is_empty() {
            let line = format!("{indent}{}\n", indent_lines(item, &indent));
            vec![primary(start..start, line)]
        } else {
            let closing = indent_of(self.text, s.start);
            let with = format!("\n{indent}{}\n{closing}", indent_lines(item, &indent));
            vec![primary(at..at, with)]
        }
    }

    fn add_transition(
        &self,
        state: usize,
        label: &str,
        target: usize,
    ) -> Result<Vec<Patch>, EditError> {
        let s = self.state(state)?;
        let label = check_label(label)?;
        let item = format!("when {label} -> {}", self.reference(target)?);
        match s.whens.last() {
            Some(last) => {
                let end = line_end(self.text, last.target.span.end);
                let lines = self.item_lines(last.start, last.target.span.end);
                if lines.start == line_start(self.text, last.start) && end < self.text.len() {
                    let indent = &self.text[lines.start..last.start];
                    let at = end + 1;
                    Ok(vec![primary(at..at, format!("{indent}{item}\n"))])
                } else {
                    Ok(self.insert_line(s, None, &item))
                }
            }
            None => Ok(self.insert_line(s, None, &item)),
        }
    }

    fn move_transition(
        &self,
        state: usize,
        from: usize,
        to: usize,
    ) -> Result<Vec<Patch>, EditError> {
        let moving = self.when(state, from)?;
        let place = self.when(state, to)?;
        if from == to {
            return Ok(Vec::new());
        }
        let moved = self.item_lines(moving.start, moving.target.span.end);
        let whole_lines = moved.start == line_start(self.text, moving.start);
        let text = &self.text[moved.clone()];
        let at = if to < from {
            if whole_lines {
                line_start(self.text, place.start)
            } else {
                place.start
            }
        } else if whole_lines {
            (line_end(self.text, place.target.span.end) + 1).min(self.text.len())
        } else {
            place.target.span.end
        };
        let with = if whole_lines {
            if text.ends_with('\n') {
                text.to_string()
            } else {
                format!("{text}\n")
            }
        } else if to < from {
            format!("{text} ")
        } else {
            format!(" {text}")
        };
        Ok(vec![patch(moved, ""), primary(at..at, with)])
    }

    fn set_activity(
        &self,
        state: usize,
        section: Section,
        new: &str,
    ) -> Result<Vec<Patch>, EditError> {
        let s = self.state(state)?;
        let new = new.trim_end();
        let keyword = section_keyword(section);
        match s.activities.iter().find(|a| a.section == section) {
            Some(a) => {
                let old = dedent(&self.text[a.open + 1..a.close]);
                if old == new {
                    let inner = a.open + 1..a.close;
                    return Ok(vec![primary(inner.clone(), &self.text[inner])]);
                }
                if new.trim().is_empty() {
                    return Ok(vec![primary(self.item_lines(a.start, a.close + 1), "")]);
                }
                let block_indent = match self.text[line_start(self.text, a.start)..a.start].trim() {
                    "" => self.text[line_start(self.text, a.start)..a.start].to_string(),
                    _ => self.member_indent(s),
                };
                let inner_indent = format!("{block_indent}    ");
                let body = indent_lines(new, &inner_indent);
                let close_line = line_start(self.text, a.close);
                if self.text[close_line..a.close].trim().is_empty() && close_line > a.open {
                    let with = format!("\n{inner_indent}{body}\n");
                    Ok(vec![primary(a.open + 1..close_line, with)])
                } else {
                    let with = format!("\n{inner_indent}{body}\n{block_indent}");
                    Ok(vec![primary(a.open + 1..a.close, with)])
                }
            }
            None if new.trim().is_empty() => Ok(Vec::new()),
            None => {
                let order = |x: Section| match x {
                    Section::Entry => 0,
                    Section::Exit => 1,
                    Section::Internal => 2,
                };
                let before = s
                    .activities
                    .iter()
                    .filter(|a| order(a.section) > order(section))
                    .map(|a| a.start)
                    .chain(s.whens.iter().map(|w| w.start))
                    .min();
                // Indented relative to the block; `insert_line` indents the whole item.
                let item = format!("{keyword} {{\n    {}\n}}", indent_lines(new, "    "));
                Ok(self.insert_line(s, before, &item))
            }
        }
    }
}

fn check_label(label: &str) -> Result<&str, EditError> {
    let label = label.trim();
    let bad = |why: &str| {
        Err(EditError::BadText {
            what: "label",
            why: why.to_string(),
        })
    };
    if label.is_empty() {
        bad("it is empty; write `TRUE` for a transition that always fires")
    } else if label.contains(['\n', '\r']) {
        bad("a label is one line")
    } else if label.contains("->") {
        bad("`->` ends a label; write the comparison another way")
    } else if label.contains("//") {
        bad("`//` would start a comment")
    } else {
        Ok(label)
    }
}

fn section_keyword(section: Section) -> &'static str {
    match section {
        Section::Entry => "entry",
        Section::Exit => "exit",
        Section::Internal => "internal",
    }
}

fn line_start(text: &str, at: usize) -> usize {
    text[..at].rfind('\n').map_or(0, |i| i + 1)
}

/// The position of the line break ending the line of `at`, or the end of the text.
fn line_end(text: &str, at: usize) -> usize {
    text[at..].find('\n').map_or(text.len(), |i| at + i)
}

fn indent_of(text: &str, at: usize) -> &str {
    let start = line_start(text, at);
    let line = &text[start..];
    &line[..line.len() - line.trim_start_matches([' ', '\t']).len()]
}

/// Every line after the first indented by `indent` (the first follows text already indented);
/// empty lines stay empty.
fn indent_lines(text: &str, indent: &str) -> String {
    let mut out = String::new();
    for (i, line) in text.lines().enumerate() {
        if i > 0 {
            out.push('\n');
            if !line.trim().is_empty() {
                out.push_str(indent);
            }
        }
        out.push_str(if line.trim().is_empty() { "" } else { line });
    }
    out
}

/// The text inside an activity's braces as a person would type it in a box: the first line
/// break and the closing line's indent dropped, the common indent taken off every line.
pub(super) fn dedent(inner: &str) -> String {
    let lines: Vec<&str> = inner.lines().collect();
    let common = lines
        .iter()
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.len() - l.trim_start_matches([' ', '\t']).len())
        .min()
        .unwrap_or(0);
    let body: Vec<&str> = lines
        .iter()
        .map(|l| {
            if l.trim().is_empty() {
                ""
            } else {
                &l[common..]
            }
        })
        .collect();
    let first = body
        .iter()
        .position(|l| !l.is_empty())
        .unwrap_or(body.len());
    let last = body
        .iter()
        .rposition(|l| !l.is_empty())
        .map_or(first, |i| i + 1);
    body[first..last.max(first)]
        .join("\n")
        .trim_end()
        .to_string()
}
