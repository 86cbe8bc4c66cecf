//! A behaviour checked as a whole with one machine file as an editor holds it: what `proclaim
//! run` would refuse (a label no expert answers, a sub-machine that does not exist) is said
//! while the person edits, not after saving.

use crate::files::{EditedFolder, Files, Folder};
use proclaim_syntax::FileDiagnostic;
use std::path::Path;
use std::sync::Arc;

/// The problems `check` would find in the behaviour in `folder` that concern the file
/// `relative` (as the manifest names it), were its text `text`. Problems of the other files
/// are theirs to show; a behaviour that does not load says so about this file only when the
/// reason is in it.
pub fn check_edited(folder: &Path, relative: &str, text: &str) -> Vec<FileDiagnostic> {
    let files = EditedFolder {
        folder: Folder::new(folder),
        relative: relative.to_string(),
        text: text.to_string(),
    };
    let shown = files.show(relative);
    let name = folder
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or("behaviour")
        .to_string();
    let found = match crate::load::load(&name, Arc::new(files)) {
        Ok(behaviour) => {
            let mut found = behaviour.warnings.clone();
            found.extend(crate::analysis::check_behaviour(&behaviour));
            found
        }
        Err(problems) => problems,
    };
    found.into_iter().filter(|d| d.file == shown).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_label_no_expert_answers_is_found_in_the_text_being_edited() {
        let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../machines/microwave");
        let saved = std::fs::read_to_string(folder.join("Microwave.machine")).unwrap();
        assert!(check_edited(&folder, "Microwave.machine", &saved)
            .iter()
            .all(|d| !d.is_error()));
        let typo = saved.replace("when cook -> COOKING", "when cokk -> COOKING");
        let found = check_edited(&folder, "Microwave.machine", &typo);
        let error = found
            .iter()
            .find(|d| d.is_error())
            .unwrap_or_else(|| panic!("{found:?}"));
        assert!(error.message.contains("cokk"), "{error}");
        assert!(error.line.is_some(), "{error}");
    }
}
