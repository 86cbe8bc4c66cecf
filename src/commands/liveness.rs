//! `proclaim liveness`: liveness formulas (Gaia operators) written as a skeleton behaviour in
//! the native format, for `proclaim check` to list what is left open.

use crate::failure::Failure;
use proclaim_behaviour::{liveness_machines, parse_liveness, MachineEntry, Manifest};
use proclaim_fsm::{Severity, EXTENSION};
use std::path::Path;
use std::process::ExitCode;

pub fn run(file: &Path, dir: &Path) -> Result<ExitCode, Failure> {
    let text = proclaim_syntax::read_source(file).map_err(|error| Failure::Read {
        path: file.to_path_buf(),
        error,
    })?;
    let shown = file.display().to_string();
    let (defs, mut diagnostics) = parse_liveness(&shown, &text);
    let errors = diagnostics
        .iter()
        .filter(|d| d.severity == Severity::Error)
        .count();
    if errors > 0 || defs.is_empty() {
        if defs.is_empty() && errors == 0 {
            diagnostics.push(proclaim_fsm::FileDiagnostic::error(
                &shown,
                1,
                "no formula: write `Behaviour = A . B`",
            ));
        }
        return Err(Failure::Invalid {
            what: "the liveness formulas",
            errors: errors.max(1),
            rendered: diagnostics.iter().map(|d| format!("{d}\n")).collect(),
        });
    }
    let (machines, warnings) = liveness_machines(&shown, &defs);
    for w in &warnings {
        eprintln!("{w}");
    }
    std::fs::create_dir_all(dir).map_err(|error| Failure::Write {
        path: dir.to_path_buf(),
        error,
    })?;
    let write = |path: &Path, text: &str| {
        std::fs::write(path, text).map_err(|error| Failure::Write {
            path: path.to_path_buf(),
            error,
        })
    };
    let mut manifest = Manifest {
        description: Some(format!("{} (from liveness formulas)", defs[0].name)),
        ..Manifest::default()
    };
    for machine in &machines {
        let path = dir.join(format!("{}.{EXTENSION}", machine.name));
        let text = format!(
            "// Generated from {shown} by `proclaim liveness`. Each basic activity's state calls a\n\
             // host function of its name; each open label says when to move on.\n{}",
            machine.text
        );
        write(&path, &text)?;
        println!("{}", path.display());
        manifest.machines.push(MachineEntry {
            file: format!("{}.{EXTENSION}", machine.name),
            start: machine.start,
            name: None,
            priority: 0,
            params: Default::default(),
        });
    }
    let manifest = manifest.to_toml(&format!(
        "Generated from {shown} by `proclaim liveness`: a skeleton to fill in.\n\
         `proclaim check` lists the labels still open; basic activities call host functions."
    ));
    let path = dir.join("behaviour.toml");
    write(&path, &manifest)?;
    println!("{}", path.display());
    Ok(ExitCode::SUCCESS)
}
