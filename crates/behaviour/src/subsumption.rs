//! The manifest's `[suppress]` table checked against the behaviour's machines: each entry a type
//! some machine posts, with a hold time that is a duration, under the round schedule (whose
//! moments time the holds). Every problem is placed at its key or value in the manifest.

use crate::loaded::LoadedMachine;
use crate::manifest::{Manifest, Schedule};
use proclaim_experts::parse_duration;
use proclaim_syntax::{line_column, nearest, FileDiagnostic, Severity};
use std::time::Duration;
use toml::Spanned;

/// The suppressed types with their hold times; the problems go into `problems`.
pub(crate) fn check(
    manifest: &Manifest,
    manifest_file: &str,
    manifest_text: &str,
    machines: &[LoadedMachine],
    problems: &mut Vec<FileDiagnostic>,
) -> Vec<(String, Duration)> {
    let at = |spanned_start: usize, message: String| {
        let (line, column) = line_column(manifest_text, spanned_start.min(manifest_text.len()));
        FileDiagnostic::error(manifest_file, line, message).at_column(column, manifest_text)
    };
    let shared = proclaim_runner::Shared::for_machines(machines.iter().map(|m| &m.machine));
    let posted: Vec<String> = machines
        .iter()
        .flat_map(|m| proclaim_runner::declaration(&m.machine, &m.machine.name, &shared).posts)
        .collect();
    let mut holds = Vec::new();
    for (ty, entry) in &manifest.suppress {
        let name = ty.get_ref();
        if manifest.schedule == Schedule::Concurrent {
            problems.push(at(
                start(ty),
                format!(
                    "`suppress` needs the round schedule: under schedule = \"concurrent\" there is no round's moment to time `{name}`'s hold by"
                ),
            ));
        }
        if !posted.iter().any(|p| p == name) {
            let hint = nearest(posted.iter().map(String::as_str), name)
                .map(|n| format!("; did you mean `{n}`?"))
                .unwrap_or_default();
            problems.push(at(
                start(ty),
                format!("`suppress` names `{name}`, which no machine of the behaviour posts{hint}"),
            ));
        }
        let text = entry.hold.get_ref();
        match parse_duration(text).filter(|d| !d.is_zero()) {
            Some(hold) => holds.push((name.clone(), hold)),
            None => problems.push(at(
                start(&entry.hold),
                format!(
                    "hold = \"{text}\" for `{name}` is not a duration above zero (write 500ms, 2s or 1.5s)"
                ),
            )),
        }
    }
    for m in machines.iter().filter(|m| m.priority != 0) {
        let decl = proclaim_runner::declaration(&m.machine, &m.machine.name, &shared);
        if !manifest
            .suppress
            .keys()
            .any(|ty| decl.posts.contains(ty.get_ref()))
        {
            problems.push(FileDiagnostic {
                severity: Severity::Warning,
                ..FileDiagnostic::in_file(
                    manifest_file,
                    format!(
                        "machine `{}` has priority = {}, but posts no type of [suppress]: its priority changes nothing",
                        m.machine.name, m.priority
                    ),
                )
            });
        }
    }
    holds
}

fn start<T>(spanned: &Spanned<T>) -> usize {
    spanned.span().start
}
