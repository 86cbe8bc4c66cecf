//! Which reader a machine file needs, decided from its name alone, in one place for the command
//! line and the behaviour loader.

use std::path::{Path, PathBuf};

/// The kinds of machine file proclaim reads.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum MachineFormat {
    /// A native `.machine` file.
    Native,
    /// A Qfsm `.fsm` file; its machine is named after the file (`stem`).
    Qfsm { stem: String },
    /// An SCXML document (`.scxml`); its machine is named by its `name`, else after the file.
    Scxml { stem: String },
    /// Either file of a T/A pair (`TName.txt`, `AName.txt`): both paths and the machine's name.
    TablePair {
        t: PathBuf,
        a: PathBuf,
        name: String,
    },
}

/// The format of the file at `path`, or `None` when its name is not a machine file's.
pub fn machine_format(path: &Path) -> Option<MachineFormat> {
    let file_name = path.file_name()?.to_str()?;
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or_default()
        .to_ascii_lowercase();
    if extension == crate::EXTENSION {
        return Some(MachineFormat::Native);
    }
    if extension == "fsm" {
        let stem = path.file_stem()?.to_str()?.to_string();
        return Some(MachineFormat::Qfsm { stem });
    }
    if extension == "scxml" {
        let stem = path.file_stem()?.to_str()?.to_string();
        return Some(MachineFormat::Scxml { stem });
    }
    if extension != "txt" {
        return None;
    }
    let partner = crate::partner_of(path)?;
    let name = file_name[1..].trim_end_matches(".txt").to_string();
    let (t, a) = if file_name.starts_with('T') {
        (path.to_path_buf(), partner)
    } else {
        (partner, path.to_path_buf())
    };
    Some(MachineFormat::TablePair { t, a, name })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(path: &str, expect: Option<MachineFormat>) {
        assert_eq!(machine_format(Path::new(path)), expect, "{path}");
    }

    #[test]
    fn formats_follow_the_file_names() {
        check("m/Microwave.machine", Some(MachineFormat::Native));
        check(
            "SMGetUp.FSM",
            Some(MachineFormat::Qfsm {
                stem: "SMGetUp".into(),
            }),
        );
        let pair = || MachineFormat::TablePair {
            t: "d/TGame.txt".into(),
            a: "d/AGame.txt".into(),
            name: "Game".into(),
        };
        check("d/TGame.txt", Some(pair()));
        check("d/AGame.txt", Some(pair()));
        check("d/Game.txt", None);
        check("theory.dl", None);
        check("", None);
    }
}
