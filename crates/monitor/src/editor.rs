//! The editor page of `proclaim edit`: a behaviour's machines drawn as the monitor draws them,
//! changed by edits the server makes as text patches (`proclaim_fsm::edit`), checked as the
//! person types, undone and redone, and saved only when the machine has no errors.
//!
//! The server holds each machine's text; the page holds nothing it could lose. Undo and redo
//! are server-side stacks of whole texts (a machine file is small), so what the page shows is
//! always exactly what Save would write.

use crate::access::Access;
use crate::diagram::{node, Chart};
use crate::server::refusal;
use axum::extract::State;
use axum::http::{header, HeaderMap, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::{Json, Router};
use parking_lot::{Mutex, RwLock};
use proclaim_fsm::edit::{
    check_native, edit_native, editable, view_native, ActivityView, Edit, Section,
};
use proclaim_fsm::{parse_machine, FileDiagnostic};
use serde::{Deserialize, Serialize};
use std::net::SocketAddr;
use std::path::{Path, PathBuf};
use std::sync::Arc;

const EDITOR_HTML: &str = include_str!("../assets/editor.html");
const EDITOR_JS: &str = include_str!("../assets/editor.js");
const MONITOR_CSS: &str = include_str!("../assets/monitor.css");

/// How many edits of one machine can be undone.
const UNDO_DEPTH: usize = 500;

/// The behaviour-level check of one machine file's text as the editor holds it (its path,
/// its text): what `proclaim run` would refuse, such as a label no expert answers. Given by
/// whoever knows the behaviour (`proclaim edit`); the editor alone knows only the machine.
pub type BehaviourCheck = Arc<dyn Fn(&Path, &str) -> Vec<FileDiagnostic> + Send + Sync>;

/// A machine file the editor opens.
pub struct EditorFile {
    /// Where it is on disk; Save writes here.
    pub path: PathBuf,
    /// Started with the behaviour (drawn as the monitor draws it).
    pub start: bool,
}

/// A behaviour's machines being edited. Clones share it.
#[derive(Clone)]
pub struct Editor {
    shared: Arc<Shared>,
}

struct Shared {
    name: String,
    machines: Vec<Mutex<Open>>,
    access: RwLock<Access>,
}

/// One machine file as the editor holds it.
struct Open {
    path: PathBuf,
    start: bool,
    /// Why it cannot be edited (a Qfsm or T/A file, unreadable), shown instead of controls.
    refusal: Option<String>,
    text: String,
    /// The text on disk as last read or written: Save refuses to overwrite another's change.
    on_disk: String,
    undo: Vec<String>,
    redo: Vec<String>,
    /// The last drawing of a text that read as a machine.
    chart: Option<Chart>,
    drawn_text: String,
    check: Option<BehaviourCheck>,
    /// A text Save refused once for what the behaviour-level check found: a second Save of it
    /// saves it anyway.
    warned: Option<String>,
}

impl Editor {
    /// Opens every file (reading it now); a file that cannot be read is shown with why.
    pub fn open(name: impl Into<String>, files: Vec<EditorFile>) -> Editor {
        let machines = files
            .into_iter()
            .map(|f| {
                let (text, mut refusal) = match proclaim_syntax::read_source(&f.path) {
                    Ok(text) => (text, None),
                    Err(e) => (String::new(), Some(format!("cannot read it: {e}"))),
                };
                if let Err(e) = editable(&f.path) {
                    refusal = Some(e.to_string());
                }
                let mut open = Open {
                    path: f.path,
                    start: f.start,
                    refusal,
                    on_disk: text.clone(),
                    text,
                    undo: Vec::new(),
                    redo: Vec::new(),
                    chart: None,
                    drawn_text: String::new(),
                    check: None,
                    warned: None,
                };
                open.draw();
                Mutex::new(open)
            })
            .collect();
        Editor {
            shared: Arc::new(Shared {
                name: name.into(),
                machines,
                access: Default::default(),
            }),
        }
    }

    /// Checks each machine in its behaviour as it is edited, from now on: what it finds is
    /// shown with the machine's own diagnostics, and Save warns of its errors once.
    pub fn set_check(&self, check: BehaviourCheck) {
        for open in &self.shared.machines {
            open.lock().check = Some(check.clone());
        }
    }

    /// Who may edit from the page from now on (read-only: the page draws and edits nothing).
    pub fn set_access(&self, access: Access) {
        *self.shared.access.write() = access;
    }

    /// Serves the page on `addr` (port 0: any free port) until the runtime ends.
    pub async fn serve(&self, addr: SocketAddr) -> std::io::Result<SocketAddr> {
        crate::server::serve_router(self.router(), addr, "editor").await
    }

    pub fn router(&self) -> Router {
        let asset = |content_type: &'static str, body: &'static str| {
            move || async move { ([(header::CONTENT_TYPE, content_type)], body).into_response() }
        };
        Router::new()
            .route("/", get(asset("text/html; charset=utf-8", EDITOR_HTML)))
            .route(
                "/editor.js",
                get(asset("text/javascript; charset=utf-8", EDITOR_JS)),
            )
            .route(
                "/monitor.css",
                get(asset("text/css; charset=utf-8", MONITOR_CSS)),
            )
            .route("/api/edit/model", get(model))
            .route("/api/edit/change", post(change))
            .route("/api/edit/try", post(try_edit))
            .route("/api/edit/undo", post(undo))
            .route("/api/edit/redo", post(redo))
            .route("/api/edit/save", post(save))
            .with_state(self.shared.clone())
    }
}

impl Open {
    fn file_name(&self) -> String {
        self.path.display().to_string()
    }

    fn diagnostics(&self) -> Vec<FileDiagnostic> {
        if self.refusal.is_some() {
            return Vec::new();
        }
        let mut found = check_native(&self.file_name(), &self.text);
        found.extend(self.behaviour_diagnostics(&self.text, &found));
        found
    }

    /// What the behaviour-level check finds in `text` beyond `found` (the machine's own); it
    /// is not asked while the machine itself has errors.
    fn behaviour_diagnostics(&self, text: &str, found: &[FileDiagnostic]) -> Vec<FileDiagnostic> {
        let Some(check) = &self.check else {
            return Vec::new();
        };
        if found.iter().any(FileDiagnostic::is_error) {
            return Vec::new();
        }
        check(&self.path, text)
            .into_iter()
            .filter(|d| {
                !found
                    .iter()
                    .any(|f| f.line == d.line && f.message == d.message)
            })
            .collect()
    }

    /// Draws the text when it reads as a machine and changed since the last drawing; a text
    /// that does not read keeps the last drawing.
    fn draw(&mut self) {
        if self.chart.is_some() && self.drawn_text == self.text {
            return;
        }
        let machine = match &self.refusal {
            None => parse_machine(&self.file_name(), &self.text)
                .machines
                .into_iter()
                .next(),
            Some(_) => proclaim_fsm::machine_format(&self.path).and_then(|_| {
                // Not editable, still drawn: read by the importer its format needs.
                read_any(&self.path)
            }),
        };
        if let Some(machine) = machine {
            self.chart = Some(Chart::of_machine(&machine, self.start));
            self.drawn_text = self.text.clone();
        }
    }

    fn change(&mut self, edit: &Edit) -> Result<(), String> {
        if let Some(why) = &self.refusal {
            return Err(why.clone());
        }
        let edited = edit_native(&self.file_name(), &self.text, edit).map_err(|e| e.to_string())?;
        if edited.text != self.text {
            self.undo
                .push(std::mem::replace(&mut self.text, edited.text));
            if self.undo.len() > UNDO_DEPTH {
                self.undo.remove(0);
            }
            self.redo.clear();
            self.draw();
        }
        Ok(())
    }

    fn save(&mut self) -> Result<String, String> {
        if let Some(why) = &self.refusal {
            return Err(why.clone());
        }
        let errors: Vec<FileDiagnostic> = check_native(&self.file_name(), &self.text)
            .into_iter()
            .filter(FileDiagnostic::is_error)
            .collect();
        if let Some(first) = errors.first() {
            return Err(format!(
                "not saved: the machine has {} error{} ({}{}); the file keeps its last good text and the edit stays here",
                errors.len(),
                if errors.len() == 1 { "" } else { "s" },
                first.line.map(|l| format!("line {l}: ")).unwrap_or_default(),
                first.message
            ));
        }
        // Only what this edit brings: a behaviour that was already refused as saved (run with
        // `--force`, say) is not refused again for it.
        let before: Vec<String> = self
            .behaviour_diagnostics(&self.on_disk, &[])
            .into_iter()
            .map(|d| d.message)
            .collect();
        let refused: Vec<FileDiagnostic> = self
            .behaviour_diagnostics(&self.text, &[])
            .into_iter()
            .filter(|d| d.is_error() && !before.contains(&d.message))
            .collect();
        if let Some(first) = refused.first() {
            if self.warned.as_deref() != Some(self.text.as_str()) {
                self.warned = Some(self.text.clone());
                return Err(format!(
                    "not saved: `proclaim run` would refuse the behaviour with this machine: {} error{} ({}{}); Save again to save it anyway",
                    refused.len(),
                    if refused.len() == 1 { "" } else { "s" },
                    first.line.map(|l| format!("line {l}: ")).unwrap_or_default(),
                    first.message
                ));
            }
        }
        let now =
            proclaim_syntax::read_source(&self.path).map_err(|e| format!("not saved: {e}"))?;
        if now != self.on_disk {
            return Err(format!(
                "not saved: {} changed on disk since the editor read it; reopen the editor to edit the new text",
                self.file_name()
            ));
        }
        if self.text == now {
            return Ok(format!("{} is unchanged", self.file_name()));
        }
        // Written beside it and renamed over it: a reader (`run --watch`) never sees half a file.
        let mut partial = self.path.clone().into_os_string();
        partial.push(".saving");
        let partial = PathBuf::from(partial);
        std::fs::write(&partial, &self.text)
            .and_then(|()| std::fs::rename(&partial, &self.path))
            .map_err(|e| format!("not saved: {e}"))?;
        self.on_disk = self.text.clone();
        Ok(format!("saved {}", self.file_name()))
    }

    fn view(&self) -> MachineView {
        let diagnostics = self.diagnostics();
        let states = match (&self.refusal, view_native(&self.text)) {
            (None, Ok((states, initial))) => Some((states, initial)),
            _ => None,
        };
        let (states, initial, unreadable) = match states {
            Some((states, initial)) => (
                states
                    .into_iter()
                    .map(|s| StateJson {
                        node: node(s.id),
                        entry: activity(&s.activities, Section::Entry),
                        exit: activity(&s.activities, Section::Exit),
                        internal: activity(&s.activities, Section::Internal),
                        transitions: s
                            .transitions
                            .into_iter()
                            .map(|t| TransitionJson {
                                line: t.line,
                                label: t.label,
                                target: t.target,
                                target_as_written: t.target_as_written,
                            })
                            .collect(),
                        name: s.name,
                        id: s.id,
                    })
                    .collect(),
                initial,
                None,
            ),
            None => (
                Vec::new(),
                None,
                match (&self.refusal, view_native(&self.text)) {
                    (None, Err(e)) => Some(e.to_string()),
                    _ => None,
                },
            ),
        };
        let chart = self.chart.as_ref();
        MachineView {
            name: chart.map_or_else(
                || {
                    self.path
                        .file_stem()
                        .map_or_else(String::new, |s| s.to_string_lossy().into_owned())
                },
                |c| c.name.clone(),
            ),
            file: self.file_name(),
            refusal: self.refusal.clone().or(unreadable),
            text: self.text.clone(),
            saved: self.text == self.on_disk,
            can_undo: !self.undo.is_empty(),
            can_redo: !self.redo.is_empty(),
            states,
            initial,
            diagnostics: diagnostics.iter().map(DiagnosticJson::of).collect(),
            svg: chart.map_or_else(String::new, |c| c.svg.clone()),
            drawn_now: self.drawn_text == self.text,
        }
    }
}

/// A machine file of another format, read for drawing only.
fn read_any(path: &std::path::Path) -> Option<proclaim_fsm::Machine> {
    let file = path.display().to_string();
    match proclaim_fsm::machine_format(path)? {
        proclaim_fsm::MachineFormat::Native => None,
        proclaim_fsm::MachineFormat::Qfsm { stem } => {
            let text = proclaim_syntax::read_source(path).ok()?;
            proclaim_fsm::import_qfsm(&file, &text, &stem)
                .machines
                .into_iter()
                .next()
        }
        proclaim_fsm::MachineFormat::Scxml { stem } => {
            let text = proclaim_syntax::read_source(path).ok()?;
            proclaim_fsm::import_scxml(&file, &text, &stem)
                .imported
                .machines
                .into_iter()
                .next()
        }
        proclaim_fsm::MachineFormat::TablePair { t, a, name } => {
            let t_text = proclaim_syntax::read_source(&t).ok()?;
            let a_text = proclaim_syntax::read_source(&a).ok()?;
            proclaim_fsm::import_ta(
                &name,
                &t.display().to_string(),
                &t_text,
                &a.display().to_string(),
                &a_text,
            )
            .machines
            .into_iter()
            .next()
        }
    }
}

fn activity(activities: &[ActivityView], section: Section) -> Option<ActivityJson> {
    activities
        .iter()
        .find(|a| a.section == section)
        .map(|a| ActivityJson {
            text: a.text.clone(),
            first_line: *a.lines.start(),
            last_line: *a.lines.end(),
        })
}

#[derive(Serialize)]
struct ActivityJson {
    text: String,
    first_line: usize,
    last_line: usize,
}

#[derive(Serialize)]
struct ModelJson {
    name: String,
    read_only: bool,
    machines: Vec<MachineView>,
}

#[derive(Serialize)]
struct MachineView {
    name: String,
    file: String,
    /// Why it cannot be edited, when it cannot.
    refusal: Option<String>,
    text: String,
    /// Whether the text is the file's.
    saved: bool,
    can_undo: bool,
    can_redo: bool,
    states: Vec<StateJson>,
    initial: Option<usize>,
    diagnostics: Vec<DiagnosticJson>,
    svg: String,
    /// Whether the drawing is of the current text (not when it does not read as a machine).
    drawn_now: bool,
}

#[derive(Serialize)]
struct StateJson {
    name: String,
    id: i64,
    node: String,
    entry: Option<ActivityJson>,
    exit: Option<ActivityJson>,
    internal: Option<ActivityJson>,
    transitions: Vec<TransitionJson>,
}

#[derive(Serialize)]
struct TransitionJson {
    line: usize,
    label: String,
    target: Option<usize>,
    target_as_written: String,
}

#[derive(Serialize)]
struct DiagnosticJson {
    line: Option<usize>,
    column: Option<usize>,
    severity: &'static str,
    message: String,
    /// Where it falls in what a tried edit wrote (`/api/edit/try`), in characters.
    #[serde(skip_serializing_if = "Option::is_none")]
    in_box: Option<usize>,
}

impl DiagnosticJson {
    fn of(d: &FileDiagnostic) -> DiagnosticJson {
        DiagnosticJson {
            line: d.line,
            column: d.column,
            severity: if d.is_error() { "error" } else { "warning" },
            message: d.message.clone(),
            in_box: None,
        }
    }
}

/// An edit as the page sends it.
#[derive(Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
enum EditJson {
    AddState {
        name: String,
    },
    RenameState {
        state: usize,
        to: String,
    },
    DeleteState {
        state: usize,
    },
    SetInitial {
        state: usize,
    },
    MakeFinal {
        state: usize,
    },
    AddTransition {
        state: usize,
        label: String,
        target: usize,
    },
    DeleteTransition {
        state: usize,
        transition: usize,
    },
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
    SetActivity {
        state: usize,
        section: SectionJson,
        text: String,
    },
}

#[derive(Deserialize, Clone, Copy)]
#[serde(rename_all = "snake_case")]
enum SectionJson {
    Entry,
    Exit,
    Internal,
}

impl From<EditJson> for Edit {
    fn from(e: EditJson) -> Edit {
        match e {
            EditJson::AddState { name } => Edit::AddState { name },
            EditJson::RenameState { state, to } => Edit::RenameState { state, to },
            EditJson::DeleteState { state } => Edit::DeleteState { state },
            EditJson::SetInitial { state } => Edit::SetInitial { state },
            EditJson::MakeFinal { state } => Edit::MakeFinal { state },
            EditJson::AddTransition {
                state,
                label,
                target,
            } => Edit::AddTransition {
                state,
                label,
                target,
            },
            EditJson::DeleteTransition { state, transition } => {
                Edit::DeleteTransition { state, transition }
            }
            EditJson::MoveTransition { state, from, to } => {
                Edit::MoveTransition { state, from, to }
            }
            EditJson::SetLabel {
                state,
                transition,
                label,
            } => Edit::SetLabel {
                state,
                transition,
                label,
            },
            EditJson::SetTarget {
                state,
                transition,
                target,
            } => Edit::SetTarget {
                state,
                transition,
                target,
            },
            EditJson::SetActivity {
                state,
                section,
                text,
            } => Edit::SetActivity {
                state,
                section: match section {
                    SectionJson::Entry => Section::Entry,
                    SectionJson::Exit => Section::Exit,
                    SectionJson::Internal => Section::Internal,
                },
                text,
            },
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Change {
    machine: usize,
    edit: EditJson,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Which {
    machine: usize,
}

impl Shared {
    fn model(&self) -> ModelJson {
        ModelJson {
            name: self.name.clone(),
            read_only: *self.access.read() == Access::ReadOnly,
            machines: self.machines.iter().map(|m| m.lock().view()).collect(),
        }
    }

    /// Why there is no machine `index`.
    fn missing(&self, index: usize) -> Response {
        (
            StatusCode::NOT_FOUND,
            format!(
                "there is no machine number {index} (the behaviour has {})",
                self.machines.len()
            ),
        )
            .into_response()
    }

    fn refused(&self, headers: &HeaderMap) -> Option<Response> {
        refusal(
            &self.access.read(),
            headers,
            "this editor is read-only (--read-only): it draws the machines and changes nothing",
            "this editor edits only with the token it was given (open the address with ?token=… that proclaim printed)",
        )
    }
}

async fn model(State(shared): State<Arc<Shared>>) -> Response {
    let model = tokio::task::spawn_blocking(move || shared.model()).await;
    match model {
        Ok(model) => Json(model).into_response(),
        Err(e) => (StatusCode::INTERNAL_SERVER_ERROR, e.to_string()).into_response(),
    }
}

/// Runs `work` on the machine off the async threads (drawing runs Graphviz), then answers
/// with the model; a refusal is answered with its reason and the model unchanged.
async fn on_machine(
    shared: Arc<Shared>,
    headers: HeaderMap,
    index: usize,
    work: impl FnOnce(&mut Open) -> Result<Option<String>, String> + Send + 'static,
) -> Response {
    if let Some(refused) = shared.refused(&headers) {
        return refused;
    }
    if index >= shared.machines.len() {
        return shared.missing(index);
    }
    let done = tokio::task::spawn_blocking(move || {
        let result = work(&mut shared.machines[index].lock());
        (result, shared.model())
    })
    .await;
    match done {
        Ok((Ok(message), model)) => Json(Answer {
            ok: true,
            message,
            model,
        })
        .into_response(),
        Ok((Err(message), model)) => (
            StatusCode::CONFLICT,
            Json(Answer {
                ok: false,
                message: Some(message),
                model,
            }),
        )
            .into_response(),
        Err(e) => (StatusCode::INTERNAL_SERVER_ERROR, e.to_string()).into_response(),
    }
}

#[derive(Serialize)]
struct Answer {
    ok: bool,
    message: Option<String>,
    model: ModelJson,
}

async fn change(
    State(shared): State<Arc<Shared>>,
    headers: HeaderMap,
    Json(change): Json<Change>,
) -> Response {
    let edit = Edit::from(change.edit);
    on_machine(shared, headers, change.machine, move |open| {
        open.change(&edit).map(|()| None)
    })
    .await
}

async fn undo(
    State(shared): State<Arc<Shared>>,
    headers: HeaderMap,
    Json(which): Json<Which>,
) -> Response {
    on_machine(shared, headers, which.machine, |open| {
        let before = open.undo.pop().ok_or("nothing to undo")?;
        open.redo.push(std::mem::replace(&mut open.text, before));
        open.draw();
        Ok(None)
    })
    .await
}

async fn redo(
    State(shared): State<Arc<Shared>>,
    headers: HeaderMap,
    Json(which): Json<Which>,
) -> Response {
    on_machine(shared, headers, which.machine, |open| {
        let after = open.redo.pop().ok_or("nothing to redo")?;
        open.undo.push(std::mem::replace(&mut open.text, after));
        open.draw();
        Ok(None)
    })
    .await
}

async fn save(
    State(shared): State<Arc<Shared>>,
    headers: HeaderMap,
    Json(which): Json<Which>,
) -> Response {
    on_machine(shared, headers, which.machine, |open| open.save().map(Some)).await
}

/// What an edit would give, not made: the diagnostics as the person types, each placed in the
/// box when it falls in what the edit wrote.
async fn try_edit(
    State(shared): State<Arc<Shared>>,
    headers: HeaderMap,
    Json(change): Json<Change>,
) -> Response {
    if let Some(refused) = shared.refused(&headers) {
        return refused;
    }
    let Some(open) = shared.machines.get(change.machine) else {
        return shared.missing(change.machine);
    };
    let (file, text) = {
        let open = open.lock();
        if let Some(why) = &open.refusal {
            return (StatusCode::CONFLICT, why.clone()).into_response();
        }
        (open.file_name(), open.text.clone())
    };
    match edit_native(&file, &text, &Edit::from(change.edit)) {
        Ok(edited) => {
            let written = &edited.text[edited.written.clone()];
            let placed = edited.in_written();
            let mut diagnostics: Vec<DiagnosticJson> = edited
                .diagnostics
                .iter()
                .map(|d| DiagnosticJson {
                    in_box: placed
                        .iter()
                        .find(|(_, p)| *p == d)
                        .map(|(at, _)| written[..(*at).min(written.len())].chars().count()),
                    ..DiagnosticJson::of(d)
                })
                .collect();
            // What the behaviour would refuse, in the box when it is on a line the edit wrote.
            let first_line = edited.text[..edited.written.start].matches('\n').count() + 1;
            let lines = first_line..=first_line + written.matches('\n').count();
            let more = open
                .lock()
                .behaviour_diagnostics(&edited.text, &edited.diagnostics);
            diagnostics.extend(more.iter().map(|d| DiagnosticJson {
                in_box: d.line.filter(|l| lines.contains(l)).map(|_| 0),
                ..DiagnosticJson::of(d)
            }));
            Json(diagnostics).into_response()
        }
        Err(e) => (StatusCode::CONFLICT, e.to_string()).into_response(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn opened(tag: &str, text: &str) -> (Editor, PathBuf) {
        let dir =
            std::env::temp_dir().join(format!("proclaim-editor-{}-{tag}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("M.machine");
        std::fs::write(&path, text).unwrap();
        let editor = Editor::open(
            "test",
            vec![EditorFile {
                path: path.clone(),
                start: true,
            }],
        );
        (editor, path)
    }

    const M: &str = "machine M // kept\nstate A {\n    when go -> A\n}\n";

    #[test]
    fn save_writes_only_a_good_text_over_the_file_it_read() {
        let (editor, path) = opened("save", M);
        let mut open = editor.shared.machines[0].lock();
        open.change(&Edit::AddState { name: "B".into() }).unwrap();
        assert_eq!(open.save(), Ok(format!("saved {}", path.display())));
        assert_eq!(
            std::fs::read_to_string(&path).unwrap(),
            format!("{M}\nstate B {{\n}}\n")
        );
        // An error in the text: refused, the file as it was, the edit kept.
        open.change(&Edit::SetLabel {
            state: 0,
            transition: 0,
            label: "go &&".into(),
        })
        .unwrap();
        let refused = open.save().unwrap_err();
        assert!(
            refused.starts_with("not saved: the machine has 1 error (line 3: bad label"),
            "{refused}"
        );
        assert!(open.text.contains("go && -> A"));
        // Undone, then the file changed by someone else: not overwritten.
        let undone = open.undo.pop().unwrap();
        open.text = undone;
        std::fs::write(&path, "machine M\nstate Z {\n}\n").unwrap();
        open.change(&Edit::RenameState {
            state: 1,
            to: "C".into(),
        })
        .unwrap();
        let refused = open.save().unwrap_err();
        assert!(refused.contains("changed on disk"), "{refused}");
        assert_eq!(
            std::fs::read_to_string(&path).unwrap(),
            "machine M\nstate Z {\n}\n"
        );
        let _ = std::fs::remove_dir_all(path.parent().unwrap());
    }

    #[test]
    fn qfsm_and_t_a_files_are_drawn_not_edited() {
        let dir = std::env::temp_dir().join(format!("proclaim-editor-{}-qfsm", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("Door.fsm");
        std::fs::write(&path, "<qfsmproject></qfsmproject>").unwrap();
        let editor = Editor::open(
            "test",
            vec![EditorFile {
                path: path.clone(),
                start: true,
            }],
        );
        let mut open = editor.shared.machines[0].lock();
        let refused = open
            .change(&Edit::AddState { name: "B".into() })
            .unwrap_err();
        assert!(
            refused.starts_with("Qfsm machines are not edited in place"),
            "{refused}"
        );
        assert!(open.save().is_err());
        assert_eq!(
            std::fs::read_to_string(&path).unwrap(),
            "<qfsmproject></qfsmproject>"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }
}
