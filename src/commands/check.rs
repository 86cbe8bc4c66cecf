//! `proclaim check`: every problem in every theory, machine file and behaviour, exit 1 when any
//! is an error (or, with `--deny-warnings`, a warning). Each summary line counts what was
//! printed above it.

use crate::behaviours::{is_behaviour, try_load_behaviour};
use crate::failure::Failure;
use crate::load::{self, color, ProblemJson};
use crate::machines::machine_file;
use proclaim_cdl::check_source;
use proclaim_fsm::{lint, FileDiagnostic, Imported, Severity};
use proclaim_syntax::render;
use std::process::ExitCode;

/// Problems found: errors and warnings.
#[derive(Clone, Copy, Default)]
struct Found {
    errors: usize,
    warnings: usize,
}

impl std::ops::AddAssign for Found {
    fn add_assign(&mut self, other: Found) {
        self.errors += other.errors;
        self.warnings += other.warnings;
    }
}

pub fn run(theories: &[String], json: bool, deny_warnings: bool) -> Result<ExitCode, Failure> {
    let mut found = Found::default();
    let mut report = Vec::new();
    for name in theories {
        if is_behaviour(name) {
            found += behaviour(name, json, &mut report)?;
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
            found += machines(name, &imported, json, &mut report);
            continue;
        }
        found += theory(name, json, &mut report)?;
    }
    let denied = if deny_warnings { found.warnings } else { 0 };
    if json {
        println!("{}", serde_json::Value::Array(report));
    } else if found.errors > 0 {
        eprintln!("error: {} found", count(found.errors, "error"));
    }
    if denied > 0 && !json {
        eprintln!(
            "error: {} denied (--deny-warnings)",
            count(denied, "warning")
        );
    }
    Ok(if found.errors + denied > 0 {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}

/// Reports a theory; what it found.
fn theory(name: &str, json: bool, report: &mut Vec<serde_json::Value>) -> Result<Found, Failure> {
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
    let errors = checked.diagnostics.iter().filter(|d| d.is_error()).count();
    let warnings = checked.diagnostics.len() - errors;
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
                "{}: ok ({}, {}, {}, {}, {}; {})",
                source.name,
                count(theory.atom_count(), "atom"),
                count(theory.rule_count(), "rule"),
                count(theory.priorities().len(), "priority"),
                count(theory.input_atoms().count(), "input"),
                count(theory.outputs().len(), "output"),
                count(warnings, "warning")
            );
        }
    }
    Ok(Found { errors, warnings })
}

/// Checks a behaviour as a whole; what it found. A behaviour whose files have errors reports
/// those (it cannot be checked further).
fn behaviour(
    name: &str,
    json: bool,
    report: &mut Vec<serde_json::Value>,
) -> Result<Found, Failure> {
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
            let errors = problems.iter().filter(|d| d.is_error()).count();
            return Ok(Found {
                errors: errors.max(1),
                warnings: problems.len() - errors,
            });
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
    // The files' own warnings were printed above too.
    let warnings = findings.len() - errors + loaded.warnings.len();
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
            count(warnings, "warning")
        );
    }
    Ok(Found { errors, warnings })
}

/// Reports an imported machine file; what it found.
fn machines(
    name: &str,
    imported: &Imported,
    json: bool,
    report: &mut Vec<serde_json::Value>,
) -> Found {
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
    Found {
        errors,
        warnings: imported.diagnostics.len() - errors,
    }
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
