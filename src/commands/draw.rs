//! `proclaim draw`: a machine, or a behaviour's machines, as a diagram. DOT is written directly; SVG, PNG and PDF go
//! through Graphviz's `dot`, and without it the DOT is written with a note on how to render it.

use crate::behaviours::{is_behaviour, load_behaviour};
use crate::failure::Failure;
use crate::machines::machine_file;
use proclaim_behaviour::behaviour_to_dot;
use proclaim_fsm::{to_dot, Machine, Severity};
use std::io::Write;
use std::path::Path;
use std::process::{Command, ExitCode, Stdio};

pub fn run(file: &str, output: Option<&Path>, name: Option<&str>) -> Result<ExitCode, Failure> {
    let dot = if is_behaviour(file) {
        let behaviour = load_behaviour(file)?;
        let machines: Vec<(&Machine, bool)> = behaviour
            .machines
            .iter()
            .map(|m| (&m.machine, m.start))
            .collect();
        behaviour_to_dot(&behaviour.name, &machines)
    } else {
        machine_dot(file, name)?
    };
    write_diagram(&dot, output)
}

/// A machine file's diagram (`name` chooses one when the file holds several).
fn machine_dot(file: &str, name: Option<&str>) -> Result<String, Failure> {
    let Some(imported) = machine_file(file)? else {
        return Err(Failure::Argument(format!(
            "{file} is not a machine file (a native .machine file, a Qfsm .fsm file, or TName.txt / AName.txt of a T/A pair)"
        )));
    };
    for d in &imported.diagnostics {
        eprintln!("{d}");
    }
    if imported
        .diagnostics
        .iter()
        .any(|d| d.severity == Severity::Error)
        && imported.machines.is_empty()
    {
        return Err(Failure::Argument(format!(
            "{file} holds no machine that could be read"
        )));
    }
    let names: Vec<&str> = imported.machines.iter().map(|m| m.name.as_str()).collect();
    let machine = match (name, imported.machines.as_slice()) {
        (None, [only]) => only,
        (Some(n), machines) => machines.iter().find(|m| m.name == n).ok_or_else(|| {
            Failure::Argument(format!(
                "{file} has no machine `{n}`; it has {}",
                names.join(", ")
            ))
        })?,
        (None, _) => {
            return Err(Failure::Argument(format!(
                "{file} holds several machines ({}); choose one with --machine NAME",
                names.join(", ")
            )))
        }
    };
    Ok(to_dot(machine))
}

/// Writes DOT to stdout or a .dot file, or renders it through Graphviz.
pub fn write_diagram(dot: &str, output: Option<&Path>) -> Result<ExitCode, Failure> {
    let Some(output) = output else {
        print!("{dot}");
        return Ok(ExitCode::SUCCESS);
    };
    let format = output
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("dot")
        .to_ascii_lowercase();
    let write = |path: &Path, bytes: &[u8]| {
        std::fs::write(path, bytes).map_err(|error| Failure::Write {
            path: path.to_path_buf(),
            error,
        })
    };
    if format == "dot" || format == "gv" {
        write(output, dot.as_bytes())?;
        return Ok(ExitCode::SUCCESS);
    }
    if !matches!(format.as_str(), "svg" | "png" | "pdf") {
        return Err(Failure::Argument(format!(
            "-o {}: write .dot, .svg, .png or .pdf",
            output.display()
        )));
    }
    match render(dot, &format, output) {
        Ok(()) => Ok(ExitCode::SUCCESS),
        Err(why) => {
            let dot_path = output.with_extension("dot");
            write(&dot_path, dot.as_bytes())?;
            eprintln!(
                "note: {why}; wrote {} instead. Render it with `dot -T{format} {} -o {}` (Debian: apt-get install graphviz)",
                dot_path.display(),
                dot_path.display(),
                output.display()
            );
            Ok(ExitCode::SUCCESS)
        }
    }
}

/// Runs Graphviz; the error says why it could not.
fn render(dot: &str, format: &str, output: &Path) -> Result<(), String> {
    let mut child = Command::new("dot")
        .arg(format!("-T{format}"))
        .arg("-o")
        .arg(output)
        .stdin(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("Graphviz's `dot` could not be started ({e})"))?;
    // Graphviz may stop reading early (a label over its 16,384-character limit); what it said
    // on stderr is then the reason, not our broken pipe.
    let taken = child
        .stdin
        .take()
        .map(|mut stdin| stdin.write_all(dot.as_bytes()));
    let result = child
        .wait_with_output()
        .map_err(|e| format!("Graphviz failed ({e})"))?;
    let said = String::from_utf8_lossy(&result.stderr);
    match taken {
        _ if !result.status.success() => Err(format!("Graphviz failed: {}", said.trim())),
        Some(Err(e)) => Err(format!("Graphviz did not take the diagram ({e})")),
        _ => Ok(()),
    }
}
