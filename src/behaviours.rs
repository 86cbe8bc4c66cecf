//! Behaviours named on the command line: a folder with a `behaviour.toml`, the manifest itself,
//! `machines/NAME` under the current folder, or one built into the binary.

use crate::embedded;
use crate::failure::Failure;
use proclaim_behaviour::{load, Behaviour, Embedded, Files, Folder, MANIFEST};
use std::path::Path;
use std::sync::Arc;

/// A behaviour named on the command line: a folder holding `behaviour.toml`, the manifest
/// itself, `machines/NAME` under the current folder, or a behaviour built into the binary.
pub fn resolve(name: &str) -> Result<(String, Arc<dyn Files>), Failure> {
    let path = Path::new(name);
    let folder = if path.is_dir() {
        Some(path.to_path_buf())
    } else if path.file_name().is_some_and(|f| f == MANIFEST) {
        Some(path.parent().unwrap_or(Path::new(".")).to_path_buf())
    } else {
        let local = Path::new("machines").join(name);
        local.join(MANIFEST).is_file().then_some(local)
    };
    if let Some(folder) = folder {
        if !folder.join(MANIFEST).is_file() {
            return Err(Failure::Argument(format!(
                "{} is not a behaviour: it has no {MANIFEST}",
                folder.display()
            )));
        }
        let label = folder
            .canonicalize()
            .ok()
            .and_then(|p| p.file_name().map(|f| f.to_string_lossy().into_owned()))
            .unwrap_or_else(|| name.to_string());
        return Ok((label, Arc::new(Folder::new(folder))));
    }
    match embedded::behaviour(name) {
        Some(files) => {
            let name: &'static str = embedded::BEHAVIOURS
                .iter()
                .find(|(n, _)| *n == name)
                .map(|(n, _)| *n)
                .unwrap_or("behaviour");
            Ok((name.to_string(), Arc::new(Embedded { name, files })))
        }
        None => Err(Failure::Argument(format!(
            "no behaviour `{name}`: not a folder with a {MANIFEST}, not machines/{name}, and not a built-in one ({})",
            embedded::behaviour_names()
        ))),
    }
}

pub fn load_behaviour(name: &str) -> Result<Behaviour, Failure> {
    let (label, files) = resolve(name)?;
    let behaviour = load(&label, files).map_err(|lines| Failure::Invalid {
        what: "the behaviour",
        errors: lines.iter().filter(|l| l.contains("error")).count().max(1),
        rendered: lines.join("\n") + "\n",
    })?;
    for w in &behaviour.warnings {
        eprintln!("{w}");
    }
    Ok(behaviour)
}

/// Whether `name` names a behaviour rather than a file (for commands that take either).
pub fn is_behaviour(name: &str) -> bool {
    let path = Path::new(name);
    path.is_dir()
        || path.file_name().is_some_and(|f| f == MANIFEST)
        || !path.exists()
            && embedded::find(name).is_none()
            && (Path::new("machines").join(name).join(MANIFEST).is_file()
                || embedded::behaviour(name).is_some())
}
