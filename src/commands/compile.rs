//! `proclaim compile`: a theory's outputs as decision functions in freestanding C99.

use crate::cli::CompileArgs;
use crate::cli::CompileTarget;
use crate::failure::Failure;
use crate::load;
use proclaim_cdl::SearchLimits;
use proclaim_compile::{c_identifier, compile, Domain, Form};
use std::path::Path;
use std::process::ExitCode;

/// `proclaim compile`.
pub fn command(args: CompileArgs) -> Result<ExitCode, Failure> {
    if names_behaviour(&args.theory, args.target) {
        return behaviour(&args.theory, args.target, args.whiteboard, &args.out);
    }
    if args.whiteboard {
        return Err(Failure::Argument(
            "--whiteboard is said of a behaviour compiled with --target rust".into(),
        ));
    }
    run(
        &args.theory,
        args.target,
        &args.out,
        args.unknown_inputs,
        args.budget,
    )
}

pub fn run(
    theory_name: &str,
    target: CompileTarget,
    out: &Path,
    unknown_inputs: bool,
    budget: Option<u64>,
) -> Result<ExitCode, Failure> {
    if names_behaviour(theory_name, target) {
        return behaviour(theory_name, target, false, out);
    }
    if target == CompileTarget::Rust {
        return Err(Failure::Argument(
            "--target rust compiles a behaviour (a folder); a theory compiles to C (--target c)"
                .into(),
        ));
    }
    let (source, theory) = load::theory(theory_name)?;
    let defaults = SearchLimits::default();
    let limits = SearchLimits {
        steps: budget.unwrap_or(defaults.steps),
        ..defaults
    };
    let domain = if unknown_inputs {
        Domain::Ternary
    } else {
        Domain::Boolean
    };
    let compiled = compile(&theory, limits, domain)
        .map_err(|e| Failure::Argument(format!("{}: {e}", source.name)))?;
    let stem = Path::new(&source.name)
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned());
    let prefix = c_identifier(
        theory
            .name()
            .map(str::to_string)
            .or(stem)
            .as_deref()
            .unwrap_or("theory"),
    );
    let c = compiled.to_c(&prefix);
    std::fs::create_dir_all(out).map_err(|error| Failure::Write {
        path: out.to_path_buf(),
        error,
    })?;
    for (file, text) in [
        (out.join(format!("{prefix}.h")), &c.header),
        (out.join(format!("{prefix}.c")), &c.source),
    ] {
        std::fs::write(&file, text).map_err(|error| Failure::Write { path: file, error })?;
    }
    let (kept, other) = match compiled.form {
        Form::Diagram => (
            format!(
                "a decision diagram of {} nodes, {}",
                compiled.diagram.nodes.len(),
                bytes(compiled.diagram_bytes())
            ),
            format!("a table would take {}", bytes(compiled.table_bytes())),
        ),
        Form::Table => (
            format!("a table of {}", bytes(compiled.table_bytes())),
            format!(
                "a decision diagram would take {} nodes, {}",
                compiled.diagram.nodes.len(),
                bytes(compiled.diagram_bytes())
            ),
        ),
    };
    println!(
        "{prefix}: {} input{}, {} output{}, {} rule{}: {kept} ({other}); wrote {}",
        compiled.inputs.len(),
        if compiled.inputs.len() == 1 { "" } else { "s" },
        compiled.outputs.len(),
        if compiled.outputs.len() == 1 { "" } else { "s" },
        compiled.rules,
        if compiled.rules == 1 { "" } else { "s" },
        out.join(format!("{prefix}.c")).display()
    );
    Ok(ExitCode::SUCCESS)
}

fn bytes(n: usize) -> String {
    format!("{n} byte{}", if n == 1 { "" } else { "s" })
}

/// A behaviour: its machines and theories as freestanding C with the host harness `main.c`, or
/// as a Cargo project.
/// Whether `name` is a behaviour's: a folder, a manifest's; or, for `--target rust` (a theory
/// compiles to C only), any name but a file's, so `microwave` is the built-in behaviour there
/// and the built-in theory for C.
fn names_behaviour(name: &str, target: CompileTarget) -> bool {
    let path = Path::new(name);
    path.is_dir()
        || path.join("behaviour.toml").exists()
        || target == CompileTarget::Rust && !path.is_file()
}

fn behaviour(
    name: &str,
    target: CompileTarget,
    whiteboard: bool,
    out: &Path,
) -> Result<ExitCode, Failure> {
    let behaviour = crate::behaviours::load_behaviour(name)?;
    let refused = |refusal: proclaim_compile::Refusal| Failure::Argument(refusal.to_string());
    let (files, what) = match target {
        CompileTarget::C if whiteboard => {
            return Err(Failure::Argument(
                "--whiteboard is said of --target rust: a behaviour compiled to C runs on its host's own board".into(),
            ))
        }
        CompileTarget::C => (
            proclaim_compile::compile_behaviour(&behaviour)
                .map_err(refused)?
                .files,
            "core: behaviour.c, which includes proclaim_runtime.h, and the theories; host harness: main.c",
        ),
        CompileTarget::Rust => {
            let repository = match whiteboard {
                false => None,
                true => Some(proclaim_compile::source_repository().ok_or_else(|| {
                    Failure::Argument(
                        "--whiteboard: the project depends on proclaim's board, monitor and runner by path, and the source tree this proclaim was built from is not here".into(),
                    )
                })?),
            };
            (
                proclaim_compile::compile_behaviour_rust(&behaviour, repository.as_deref())
                    .map_err(refused)?
                    .files,
                if whiteboard {
                    "a Cargo project: `cargo run --release -- --script FILE --virtual-clock --trace FILE`, on a whiteboard with `--monitor` (`--features network` for `--listen`, `--connect`)"
                } else {
                    "a Cargo project of crates.io crates alone: `cargo run --release -- --script FILE --virtual-clock --trace FILE`"
                },
            )
        }
    };
    warn_what_run_would_refuse(&behaviour);
    for (file, text) in &files {
        let path = out.join(file);
        if let Some(folder) = path.parent() {
            std::fs::create_dir_all(folder).map_err(|error| Failure::Write {
                path: folder.to_path_buf(),
                error,
            })?;
        }
        std::fs::write(&path, text).map_err(|error| Failure::Write { path, error })?;
    }
    println!(
        "{}: wrote {} files to {} ({what})",
        behaviour.name,
        files.len(),
        out.display()
    );
    Ok(ExitCode::SUCCESS)
}

/// What `check` finds stops `proclaim run` unless `--force`; a compiled program has no such
/// stop and runs as `run --force` does (an atom nobody answers reads false), so each finding is
/// shown as a warning.
fn warn_what_run_would_refuse(behaviour: &proclaim_behaviour::Behaviour) {
    let errors: Vec<String> = proclaim_behaviour::check_behaviour_with(behaviour, None, &[])
        .iter()
        .filter(|d| d.severity == proclaim_fsm::Severity::Error)
        .map(|d| d.to_string().replacen(": error: ", ": warning: ", 1))
        .collect();
    if errors.is_empty() {
        return;
    }
    for e in &errors {
        eprintln!("{e}");
    }
    eprintln!(
        "warning: `proclaim run` refuses this behaviour without --force; the compiled program runs it as `run --force` does"
    );
}
