//! Behaviours named on the command line: a folder with a `behaviour.toml`, the manifest itself,
//! `machines/NAME` under the current folder, or one built into the binary.

use crate::embedded;
use crate::failure::Failure;
use crate::load::color;
use proclaim_behaviour::{load_manifest, Behaviour, Embedded, Files, Folder, MANIFEST};
use proclaim_syntax::FileDiagnostic;
use std::path::Path;
use std::sync::Arc;

/// A behaviour named on the command line: a folder holding `behaviour.toml`, a manifest file
/// (`launch-Placer.toml`), `machines/NAME` under the current folder, or one built into the binary.
/// A behaviour found: its name, its files, and its manifest's file name.
pub struct Found {
    pub label: String,
    pub files: Arc<dyn Files>,
    pub manifest: String,
}

pub fn resolve(name: &str) -> Result<Found, Failure> {
    let path = Path::new(name);
    let is_manifest = path.is_file() && path.extension().is_some_and(|e| e == "toml");
    let (folder, manifest) = if path.is_dir() {
        (Some(path.to_path_buf()), MANIFEST.to_string())
    } else if is_manifest {
        let file = path
            .file_name()
            .map_or_else(String::new, |f| f.to_string_lossy().into_owned());
        (
            Some(path.parent().unwrap_or(Path::new(".")).to_path_buf()),
            file,
        )
    } else {
        let local = Path::new("machines").join(name);
        (
            local.join(MANIFEST).is_file().then_some(local),
            MANIFEST.to_string(),
        )
    };
    if let Some(folder) = folder {
        if !folder.join(&manifest).is_file() {
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
        return Ok(Found {
            label,
            files: Arc::new(Folder::new(folder)),
            manifest,
        });
    }
    match embedded::behaviour(name) {
        Some(files) => {
            let name: &'static str = embedded::BEHAVIOURS
                .iter()
                .find(|(n, _)| *n == name)
                .map(|(n, _)| *n)
                .unwrap_or("behaviour");
            Ok(Found {
                label: name.to_string(),
                files: Arc::new(Embedded { name, files }),
                manifest: MANIFEST.to_string(),
            })
        }
        None => {
            // A path is looked for as itself only.
            let shipped = if name.contains(['/', '\\']) {
                String::new()
            } else {
                format!(" not machines/{name},")
            };
            Err(Failure::Argument(format!(
                "no behaviour `{name}`: not a folder with a {MANIFEST},{shipped} and not a built-in one ({})",
                embedded::behaviour_names()
            )))
        }
    }
}

pub fn load_behaviour(name: &str) -> Result<Behaviour, Failure> {
    let behaviour = try_load_behaviour(name)?.map_err(|problems| Failure::Invalid {
        what: "the behaviour",
        errors: problems.iter().filter(|d| d.is_error()).count().max(1),
        rendered: problems.iter().map(|p| p.render(color())).collect(),
    })?;
    for w in &behaviour.warnings {
        eprint!("{}", w.render(color()));
    }
    Ok(behaviour)
}

/// The behaviour `name`, or every problem its files have (`Err` inside); `Err` outside when
/// there is no such behaviour.
pub fn try_load_behaviour(name: &str) -> Result<Result<Behaviour, Vec<FileDiagnostic>>, Failure> {
    let found = resolve(name)?;
    Ok(load_manifest(&found.label, found.files, &found.manifest))
}

/// Whether `name` names a behaviour rather than a file (for commands that take either).
pub fn is_behaviour(name: &str) -> bool {
    let path = Path::new(name);
    path.is_dir()
        || path.is_file() && path.extension().is_some_and(|e| e == "toml")
        || !path.exists()
            && embedded::find(name).is_none()
            && (Path::new("machines").join(name).join(MANIFEST).is_file()
                || embedded::behaviour(name).is_some())
}
