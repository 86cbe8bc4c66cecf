//! Experts that are other programs, loaded from the manifest's `[[prolog]]` and `[[expert]]`
//! sections: each checked at load (a knowledge base is loaded by SWI-Prolog once, so its syntax
//! errors are warnings at their lines in `check` and `run`; a command that is not there is a
//! warning), declared like any expert (so `check` and `deps` know the labels they answer), and
//! started as a supervised [`ProgramExpert`].

use crate::files::Files;
use crate::manifest::Manifest;
use crate::program_entries::{ProgramEntry, PrologEntry};
use proclaim_board::ModuleDecl;
use proclaim_experts::{
    check_knowledge_base, find_program, parse_duration, prolog_expert, KnowledgeBase, ProgramExpert,
};
use proclaim_syntax::FileDiagnostic;
use std::path::Path;

/// A program expert ready to start.
#[derive(Clone, Debug)]
pub struct LoadedProgram {
    pub name: String,
    pub answers: Vec<String>,
    pub inputs: Vec<String>,
    pub kind: ProgramKind,
}

#[derive(Clone, Debug)]
pub enum ProgramKind {
    /// `[[prolog]]`: the file as the manifest names it, and its text.
    Prolog { file: String, kb: KnowledgeBase },
    /// `[[expert]]`, and the folder it runs in as the manifest names it.
    Command {
        command: Vec<String>,
        folder: Option<String>,
    },
}

impl LoadedProgram {
    /// What it reads, posts and answers.
    pub fn declaration(&self) -> ModuleDecl {
        ModuleDecl::new(&self.name)
            .reads(
                self.inputs
                    .iter()
                    .cloned()
                    .chain([proclaim_board::QUERY_TYPE.to_string()]),
            )
            .posts(self.answers.clone())
            .answers(self.answers.clone())
    }

    /// The expert, its process run in the behaviour's `folder` when it has one on disk (or in
    /// the entry's `folder`, from there).
    pub fn expert(&self, folder: Option<&Path>) -> ProgramExpert {
        let expert = match &self.kind {
            // Loading checked the knowledge base and reported its warnings.
            ProgramKind::Prolog { kb, .. } => {
                prolog_expert(&self.name, kb, self.answers.clone(), self.inputs.clone())
                    .warnings_reported()
            }
            ProgramKind::Command { command, .. } => ProgramExpert::new(
                &self.name,
                command.clone(),
                self.answers.clone(),
                self.inputs.clone(),
            ),
        };
        match self.run_in(folder) {
            Some(folder) => expert.in_folder(folder),
            None => expert,
        }
    }

    /// Where its process runs: the entry's `folder` from the behaviour's, or the behaviour's.
    fn run_in(&self, behaviour_folder: Option<&Path>) -> Option<std::path::PathBuf> {
        let own = match &self.kind {
            ProgramKind::Command { folder, .. } => folder.as_deref(),
            ProgramKind::Prolog { .. } => None,
        };
        match (behaviour_folder, own) {
            (Some(b), Some(own)) => Some(b.join(own)),
            (Some(b), None) => Some(b.to_path_buf()),
            (None, own) => own.map(std::path::PathBuf::from),
        }
    }
}

/// The manifest's program experts, each checked; problems (errors and warnings, placed) into
/// `problems`.
pub(crate) fn load_programs(
    files: &dyn Files,
    manifest: &Manifest,
    manifest_file: &str,
    problems: &mut Vec<FileDiagnostic>,
) -> Vec<LoadedProgram> {
    let mut loaded = Vec::new();
    for entry in &manifest.prolog {
        if let Some(p) = load_prolog(files, entry, manifest_file, problems) {
            loaded.push(p);
        }
    }
    for entry in &manifest.programs {
        if let Some(p) = load_command(files, entry, manifest_file, problems) {
            loaded.push(p);
        }
    }
    loaded
}

fn load_prolog(
    files: &dyn Files,
    entry: &PrologEntry,
    manifest_file: &str,
    problems: &mut Vec<FileDiagnostic>,
) -> Option<LoadedProgram> {
    let text = files.read(&entry.file).map_err(|e| problems.push(e)).ok()?;
    let shown = files.show(&entry.file);
    if entry.answers.is_empty() {
        problems.push(FileDiagnostic::in_file(
            manifest_file,
            format!(
                "[[prolog]] `{}` answers no label (write `answers = [\"…\"]`)",
                entry.file
            ),
        ));
        return None;
    }
    let time_limit = match &entry.time_limit {
        None => KnowledgeBase::TIME_LIMIT,
        Some(text) => match parse_duration(text).filter(|d| !d.is_zero()) {
            Some(d) => d,
            None => {
                problems.push(FileDiagnostic::in_file(
                    manifest_file,
                    format!("[[prolog]] `{}`: time_limit = \"{text}\" is not a duration (write 200ms or 1s)", entry.file),
                ));
                return None;
            }
        },
    };
    let kb = KnowledgeBase {
        file: shown.clone(),
        text,
        time_limit,
    };
    match check_knowledge_base(&kb, &entry.answers) {
        Ok(warnings) => problems.extend(warnings.into_iter().map(|w| {
            let d = FileDiagnostic::warning(w.file.as_deref().unwrap_or(&shown), w.line, w.message);
            // The line is quoted from the knowledge base itself; a file it loads is not read.
            let source = if w.file.is_none() {
                kb.text.as_str()
            } else {
                ""
            };
            if w.column > 0 {
                d.at_column(w.column, source)
            } else {
                d
            }
        })),
        Err(e) => problems.push(FileDiagnostic::warning(&shown, 1, e.to_string())),
    }
    Some(LoadedProgram {
        name: entry.name.clone().unwrap_or_else(|| stem(&entry.file)),
        answers: entry.answers.clone(),
        inputs: entry.inputs.clone(),
        kind: ProgramKind::Prolog {
            file: entry.file.clone(),
            kb,
        },
    })
}

fn load_command(
    files: &dyn Files,
    entry: &ProgramEntry,
    manifest_file: &str,
    problems: &mut Vec<FileDiagnostic>,
) -> Option<LoadedProgram> {
    let Some(program) = entry.command.first() else {
        problems.push(FileDiagnostic::in_file(
            manifest_file,
            "an [[expert]] has `command = []` (write the program and its arguments, as [\"python3\", \"ball.py\"])",
        ));
        return None;
    };
    if entry.answers.is_empty() {
        problems.push(FileDiagnostic::in_file(
            manifest_file,
            format!(
                "[[expert]] `{}` answers no label (write `answers = [\"…\"]`)",
                entry.command.join(" ")
            ),
        ));
        return None;
    }
    let loaded = LoadedProgram {
        name: entry
            .name
            .clone()
            .unwrap_or_else(|| stem(entry.command.last().unwrap_or(program))),
        answers: entry.answers.clone(),
        inputs: entry.inputs.clone(),
        kind: ProgramKind::Command {
            command: entry.command.clone(),
            folder: entry.folder.clone(),
        },
    };
    let runs_in = loaded.run_in(files.folder());
    if let Some(folder) = runs_in.as_ref().filter(|f| !f.is_dir()) {
        problems.push(FileDiagnostic::in_file(
            manifest_file,
            format!(
                "[[expert]] `{}`: it runs in {}, which is not a folder",
                entry.command.join(" "),
                folder.display()
            ),
        ));
        return None;
    }
    // A program named by a path is found from the folder it runs in.
    let found = match &runs_in {
        Some(folder) if Path::new(program).components().count() > 1 => {
            folder.join(program).is_file()
        }
        _ => find_program(program).is_some(),
    };
    if !found {
        problems.push(FileDiagnostic::warning(
            manifest_file,
            1,
            format!("[[expert]] `{}`: `{program}` is not found, so the expert will not start and its labels will time out", entry.command.join(" ")),
        ));
    }
    Some(loaded)
}

/// The manifest entries of the program experts `needed` names, with each file written as
/// `place` says: what `deps --launch` keeps.
pub(crate) fn needed_entries(
    manifest: &Manifest,
    programs: &[LoadedProgram],
    needed: &dyn Fn(&str) -> bool,
    place: &dyn Fn(&str) -> String,
) -> (Vec<PrologEntry>, Vec<ProgramEntry>) {
    let named = |name: &str| programs.iter().any(|p| p.name == name) && needed(name);
    let prolog = manifest
        .prolog
        .iter()
        .filter(|e| named(&e.name.clone().unwrap_or_else(|| stem(&e.file))))
        .map(|e| PrologEntry {
            file: place(&e.file),
            ..e.clone()
        })
        .collect();
    let commands = manifest
        .programs
        .iter()
        .filter(|e| {
            let name = e
                .name
                .clone()
                .or_else(|| e.command.last().map(|l| stem(l)))
                .unwrap_or_default();
            named(&name)
        })
        .map(|e| {
            // It runs where it ran: its folder as seen from the new manifest.
            let from_manifest = e.folder.clone().unwrap_or_else(|| ".".into());
            let placed = place(&from_manifest);
            ProgramEntry {
                folder: (placed != from_manifest)
                    .then_some(placed)
                    .or_else(|| e.folder.clone()),
                ..e.clone()
            }
        })
        .collect();
    (prolog, commands)
}

fn stem(file: &str) -> String {
    Path::new(file)
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or(file)
        .to_string()
}
