//! `proclaim check`: every problem in every theory, machine file and behaviour, exit 1 when any
//! is an error.

use crate::behaviours::{is_behaviour, try_load_behaviour};
use crate::failure::Failure;
use crate::load::{self, color, ProblemJson};
use crate::machines::machine_file;
use proclaim_cdl::check_source;
use proclaim_fsm::{lint, FileDiagnostic, Imported, Severity};
use proclaim_syntax::render;
use std::process::ExitCode;

pub fn run(theories: &[String], json: bool) -> Result<ExitCode, Failure> {
    let mut errors = 0;
    let mut report = Vec::new();
    for name in theories {
        if is_behaviour(name) {
            errors += behaviour(name, json, &mut report)?;
            continue;
        }
        if let Some(mut imported) = machine_file(name)? {
            let file = imported
                .diagnostics
                .first()
                .map_or_else(|| name.clone(), |d| d.file.clone());
            let lints: Vec<FileDiagnostic> = imported
                .machines
                .iter()
                .flat_map(|m| lint(m, &file))
                .collect();
            imported.diagnostics.extend(lints);
            errors += machines(name, &imported, json, &mut report);
            continue;
        }
        let source = load::read(name)?;
        let mut checked = check_source(&source.text, source.language);
        if let Some(theory) = checked.theory.take() {
            let theory = std::sync::Arc::new(theory);
            checked
                .diagnostics
                .extend(proclaim_cdl::attack_cycle_warnings(
                    &theory,
                    proclaim_cdl::SearchLimits::default(),
                ));
            checked
                .diagnostics
                .sort_by_key(|d| (d.span.start, d.span.end));
            checked.theory = Some(std::sync::Arc::unwrap_or_clone(theory));
        }
        errors += checked.diagnostics.iter().filter(|d| d.is_error()).count();
        if json {
            report.extend(
                checked
                    .diagnostics
                    .iter()
                    .map(|d| ProblemJson::of_theory(d, &source.name, &source.text).value()),
            );
        } else {
            eprint!(
                "{}",
                render(&checked.diagnostics, &source.name, &source.text, color())
            );
            if let Some(theory) = &checked.theory {
                println!(
                    "{}: ok ({}, {}, {}, {}, {})",
                    source.name,
                    count(theory.atom_count(), "atom"),
                    count(theory.rule_count(), "rule"),
                    count(theory.priorities().len(), "priority"),
                    count(theory.input_atoms().count(), "input"),
                    count(theory.outputs().len(), "output")
                );
            }
        }
    }
    if json {
        println!("{}", serde_json::Value::Array(report));
    } else if errors > 0 {
        eprintln!(
            "error: {errors} error{} found",
            if errors == 1 { "" } else { "s" }
        );
    }
    Ok(if errors > 0 {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}

/// Checks a behaviour as a whole; returns its error count. A behaviour whose files have errors
/// reports those (it cannot be checked further).
fn behaviour(
    name: &str,
    json: bool,
    report: &mut Vec<serde_json::Value>,
) -> Result<usize, Failure> {
    let loaded = match try_load_behaviour(name)? {
        Ok(b) => b,
        Err(problems) => {
            if json {
                report.extend(problems.iter().map(|d| ProblemJson::of_file(d).value()));
            } else {
                for d in &problems {
                    eprint!("{}", d.render(color()));
                }
            }
            return Ok(problems.iter().filter(|d| d.is_error()).count().max(1));
        }
    };
    for w in &loaded.warnings {
        if json {
            report.push(ProblemJson::of_file(w).value());
        } else {
            eprint!("{}", w.render(color()));
        }
    }
    let findings = proclaim_behaviour::check_behaviour(&loaded);
    let errors = findings
        .iter()
        .filter(|d| d.severity == Severity::Error)
        .count();
    if json {
        report.extend(findings.iter().map(|d| ProblemJson::of_file(d).value()));
    } else {
        for d in &findings {
            eprintln!("{d}");
        }
        // Only behaviours that have them say so: the line stays as it was for the others.
        let programs = match loaded.programs.len() {
            0 => String::new(),
            n => format!(", {}", count(n, "program expert")),
        };
        println!(
            "{name}: {} ({}, {}{programs}, {}; {}, {})",
            if errors == 0 { "ok" } else { "has errors" },
            count(loaded.machines.len(), "machine"),
            count(loaded.theories.len(), "theory"),
            count(loaded.sensors.len(), "sensor"),
            count(errors, "error"),
            count(findings.len() - errors, "warning")
        );
    }
    Ok(errors)
}

/// Reports an imported machine file; returns its error count.
fn machines(
    name: &str,
    imported: &Imported,
    json: bool,
    report: &mut Vec<serde_json::Value>,
) -> usize {
    let errors = imported
        .diagnostics
        .iter()
        .filter(|d| d.severity == Severity::Error)
        .count();
    if json {
        report.extend(
            imported
                .diagnostics
                .iter()
                .map(|d| ProblemJson::of_file(d).value()),
        );
    } else {
        for d in &imported.diagnostics {
            eprint!("{}", d.render(color()));
        }
        let states: usize = imported.machines.iter().map(|m| m.states.len()).sum();
        let transitions: usize = imported.machines.iter().map(|m| m.transitions.len()).sum();
        if !imported.machines.is_empty() {
            println!(
                "{name}: {} ({}, {}, {}, {})",
                if errors == 0 { "ok" } else { "has errors" },
                count(imported.machines.len(), "machine"),
                count(states, "state"),
                count(transitions, "transition"),
                count(imported.diagnostics.len() - errors, "warning")
            );
        }
    }
    errors
}

/// `1 rule`, `2 rules`, `1 priority`, `2 priorities`.
fn count(n: usize, one: &str) -> String {
    let many = match one {
        "priority" => "priorities".to_string(),
        "theory" => "theories".to_string(),
        other => format!("{other}s"),
    };
    format!("{n} {}", if n == 1 { one } else { &many })
}
