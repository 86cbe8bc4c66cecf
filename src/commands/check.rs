//! `proclaim check`: every problem in every theory, exit 1 when any is an error.

use crate::failure::Failure;
use crate::load::{self, color, diagnostic_json};
use proclaim_cdl::check_source;
use proclaim_syntax::render;
use std::process::ExitCode;

pub fn run(theories: &[String], json: bool) -> Result<ExitCode, Failure> {
    let mut errors = 0;
    let mut report = Vec::new();
    for name in theories {
        let source = load::read(name)?;
        let checked = check_source(&source.text, source.language);
        errors += checked.diagnostics.iter().filter(|d| d.is_error()).count();
        if json {
            report.extend(
                checked
                    .diagnostics
                    .iter()
                    .map(|d| diagnostic_json(d, &source.name, &source.text)),
            );
        } else {
            eprint!(
                "{}",
                render(&checked.diagnostics, &source.name, &source.text, color())
            );
            if let Some(theory) = &checked.theory {
                println!(
                    "{}: ok ({} atoms, {} rules, {} priorities, {} inputs, {} outputs)",
                    source.name,
                    theory.atom_count(),
                    theory.rule_count(),
                    theory.priorities().len(),
                    theory.input_atoms().count(),
                    theory.outputs().len()
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
