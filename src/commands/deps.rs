//! `proclaim deps`: who a module depends on and who depends on it (the seed paper's Figure 4),
//! or the smallest behaviour that runs one machine (`--launch`).

use crate::behaviours::load_behaviour;
use crate::cli::DepsArgs;
use crate::commands::draw::write_diagram;
use crate::failure::Failure;
use proclaim_behaviour::{launch_manifest, module_diagram, modules, overall_diagram};
use std::path::Path;
use std::process::ExitCode;

/// `proclaim deps`.
pub fn command(args: DepsArgs) -> Result<ExitCode, Failure> {
    run(
        &args.behaviour,
        args.module.as_deref(),
        args.launch.as_deref(),
        args.output.as_deref(),
    )
}

pub fn run(
    behaviour: &str,
    module: Option<&str>,
    launch: Option<&str>,
    output: Option<&Path>,
) -> Result<ExitCode, Failure> {
    let loaded = load_behaviour(behaviour)?;
    let all = modules(&loaded);
    if let Some(machine) = launch {
        let place = |file: &str| placed(loaded.files.folder(), output, file);
        let text = launch_manifest(&loaded, &all, machine, &place)
            .map_err(|e| Failure::Argument(e.to_string()))?;
        return match output {
            None => {
                print!("{text}");
                Ok(ExitCode::SUCCESS)
            }
            Some(path) => {
                std::fs::write(path, text).map_err(|error| Failure::Write {
                    path: path.to_path_buf(),
                    error,
                })?;
                println!(
                    "wrote {}: run it with `proclaim run {}`",
                    path.display(),
                    path.display()
                );
                Ok(ExitCode::SUCCESS)
            }
        };
    }
    let dot = match module {
        Some(m) => module_diagram(&all, m).map_err(|e| Failure::Argument(e.to_string()))?,
        None => overall_diagram(&all, &loaded.name),
    };
    write_diagram(&dot, output)
}

/// A file of the behaviour as the manifest written to `output` must name it: as it is when
/// the manifest goes into the behaviour's folder (or to standard output), else by its full
/// path, which works from anywhere.
fn placed(folder: Option<&Path>, output: Option<&Path>, file: &str) -> String {
    let (Some(folder), Some(output)) = (folder, output) else {
        return file.to_string();
    };
    let out_dir = match output.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => Path::new(".").to_path_buf(),
    };
    let same = match (folder.canonicalize(), out_dir.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    };
    if same {
        return file.to_string();
    }
    let full = folder.join(file);
    full.canonicalize()
        .unwrap_or(full)
        .to_string_lossy()
        .into_owned()
}
