//! Where a behaviour's files come from: a folder on disk, or texts built into the program.

use proclaim_syntax::FileDiagnostic;
use std::path::{Path, PathBuf};

/// Reads a behaviour's files by their path relative to the behaviour (as the manifest names
/// them).
pub trait Files: Send + Sync {
    /// The file's text, or why it cannot be had (about the file as a whole).
    fn read(&self, relative: &str) -> Result<String, FileDiagnostic>;

    /// How to name the file to a person (`machines/microwave/Microwave.machine`).
    fn show(&self, relative: &str) -> String;

    /// The folder on disk, when there is one (to watch it).
    fn folder(&self) -> Option<&Path> {
        None
    }
}

/// A folder on disk.
pub struct Folder {
    root: PathBuf,
}

impl Folder {
    pub fn new(root: impl Into<PathBuf>) -> Folder {
        Folder { root: root.into() }
    }
}

impl Files for Folder {
    fn read(&self, relative: &str) -> Result<String, FileDiagnostic> {
        proclaim_syntax::read_source(self.root.join(relative)).map_err(|e| {
            FileDiagnostic::in_file(&self.show(relative), format!("cannot read it: {e}"))
        })
    }

    fn show(&self, relative: &str) -> String {
        self.root.join(relative).display().to_string()
    }

    fn folder(&self) -> Option<&Path> {
        Some(&self.root)
    }
}

/// Texts built into the program: `(relative path, text)`.
pub struct Embedded {
    pub name: &'static str,
    pub files: &'static [(&'static str, &'static str)],
}

impl Files for Embedded {
    fn read(&self, relative: &str) -> Result<String, FileDiagnostic> {
        self.files
            .iter()
            .find(|(path, _)| *path == relative)
            .map(|(_, text)| text.to_string())
            .ok_or_else(|| {
                FileDiagnostic::in_file(
                    &self.show(relative),
                    format!("the built-in behaviour `{}` has no such file", self.name),
                )
            })
    }

    fn show(&self, relative: &str) -> String {
        format!("<embedded>/{}/{relative}", self.name)
    }
}

/// A folder on disk with one file's text as an editor holds it, not as saved: the behaviour
/// checked as it would be once that file is saved.
pub(crate) struct EditedFolder {
    pub folder: Folder,
    /// The file's path as the manifest names it.
    pub relative: String,
    pub text: String,
}

impl Files for EditedFolder {
    fn read(&self, relative: &str) -> Result<String, FileDiagnostic> {
        if relative == self.relative {
            return Ok(self.text.clone());
        }
        self.folder.read(relative)
    }

    fn show(&self, relative: &str) -> String {
        self.folder.show(relative)
    }

    fn folder(&self) -> Option<&Path> {
        self.folder.folder()
    }
}
