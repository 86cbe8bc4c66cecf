//! `proclaim import`: machines from T/A pairs, Qfsm files, SCXML documents (or native files)
//! written as native `.machine` files, one per machine.

use crate::failure::Failure;
use crate::machines::machine_file;
use proclaim_fsm::{import_scxml, machine_format, to_native, MachineFormat, Severity, EXTENSION};
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
                "{file} is not a machine file (a Qfsm .fsm file, an SCXML .scxml document, a native .machine file, or TName.txt / AName.txt of a T/A pair)"
            )));
        };
        for d in &imported.diagnostics {
            eprintln!("{d}");
            errors |= d.severity == Severity::Error;
        }
        // A chart (an SCXML document, a native file that nests states) is written as its
        // states were written, not as the flat states it lowers to.
        let written_as = as_written(file);
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
            let text = match &written_as {
                Some(text) if imported.machines.len() == 1 => text.clone(),
                _ if !machine.composites.is_empty() => {
                    eprintln!("error: {file}: machine `{}` nests states, which only its own file can say; not written", machine.name);
                    errors = true;
                    continue;
                }
                _ => format!(
                    "// Imported from {file} by `proclaim import`.\n{}",
                    to_native(machine)
                ),
            };
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

/// The native text of a file that says its machine as written: an SCXML document's mapping,
/// or a native file itself; `None` for the formats `to_native` writes.
fn as_written(file: &str) -> Option<String> {
    let path = Path::new(file);
    let text = proclaim_syntax::read_source(path).ok()?;
    match machine_format(path)? {
        MachineFormat::Scxml { stem } => import_scxml(file, &text, &stem).native,
        MachineFormat::Native => {
            let read = proclaim_fsm::parse_machine(file, &text);
            let chart = read.machines.iter().any(|m| !m.composites.is_empty());
            chart.then_some(text)
        }
        _ => None,
    }
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

/// `proclaim export`: a native machine file written as SCXML, to `output` or standard output;
/// what SCXML cannot say is reported at its line and nothing is written (exit 1).
pub fn export(file: &Path, output: Option<&Path>) -> Result<ExitCode, Failure> {
    let text = proclaim_syntax::read_source(file).map_err(|error| Failure::Read {
        path: file.to_path_buf(),
        error,
    })?;
    if machine_format(file) != Some(MachineFormat::Native) {
        return Err(Failure::Argument(format!(
            "{}: only a native .machine file is exported (`proclaim import` writes one from the other formats)",
            file.display()
        )));
    }
    match proclaim_fsm::to_scxml(&file.display().to_string(), &text) {
        Ok(scxml) => {
            match output {
                Some(path) => std::fs::write(path, scxml).map_err(|error| Failure::Write {
                    path: path.to_path_buf(),
                    error,
                })?,
                None => print!("{scxml}"),
            }
            Ok(ExitCode::SUCCESS)
        }
        Err(refusals) => {
            for d in refusals {
                eprintln!("{d}");
            }
            Ok(ExitCode::from(1))
        }
    }
}
