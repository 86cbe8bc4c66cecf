//! `proclaim import`: machines from T/A pairs, Qfsm files (or native files) written as native
//! `.machine` files, one per machine.

use crate::failure::Failure;
use crate::machines::machine_file;
use proclaim_fsm::{to_native, Severity, EXTENSION};
use std::path::Path;
use std::process::ExitCode;

/// Writes every machine the files hold into `dir`. Problems are reported with file and line;
/// what could be read is still written, and the exit status is 1 when a file had errors.
pub fn run(files: &[String], dir: &Path) -> Result<ExitCode, Failure> {
    std::fs::create_dir_all(dir).map_err(|error| Failure::Write {
        path: dir.to_path_buf(),
        error,
    })?;
    let mut written: Vec<(String, String)> = Vec::new();
    let mut errors = false;
    for file in files {
        let Some(imported) = machine_file(file)? else {
            return Err(Failure::Argument(format!(
                "{file} is not a machine file (a Qfsm .fsm file, a native .machine file, or TName.txt / AName.txt of a T/A pair)"
            )));
        };
        for d in &imported.diagnostics {
            eprintln!("{d}");
            errors |= d.severity == Severity::Error;
        }
        for machine in &imported.machines {
            let stem = file_stem(&machine.name);
            if let Some((_, first)) = written.iter().find(|(s, _)| *s == stem) {
                eprintln!(
                    "error: {file}: machine `{}` would overwrite the one imported from {first}; not written",
                    machine.name
                );
                errors = true;
                continue;
            }
            let path = dir.join(format!("{stem}.{EXTENSION}"));
            let text = format!(
                "// Imported from {file} by `proclaim import`.\n{}",
                to_native(machine)
            );
            std::fs::write(&path, text).map_err(|error| Failure::Write {
                path: path.clone(),
                error,
            })?;
            println!("{}", path.display());
            written.push((stem, file.clone()));
        }
    }
    Ok(if errors {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}

/// A machine's name as a file name: letters, digits, `_`, `-` and `.` kept, the rest `_`.
fn file_stem(name: &str) -> String {
    let stem: String = name
        .chars()
        .map(|c| {
            if c.is_alphanumeric() || "_-.".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect();
    if stem.is_empty() || stem.starts_with('.') {
        format!("machine{stem}")
    } else {
        stem
    }
}
