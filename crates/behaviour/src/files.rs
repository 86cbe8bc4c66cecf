//! Where a behaviour's files come from: a folder on disk, or texts built into the program.

use std::path::{Path, PathBuf};

/// Reads a behaviour's files by their path relative to the behaviour (as the manifest names
/// them).
pub trait Files: Send + Sync {
    fn read(&self, relative: &str) -> Result<String, String>;

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
    fn read(&self, relative: &str) -> Result<String, String> {
        let path = self.root.join(relative);
        std::fs::read_to_string(&path).map_err(|e| format!("cannot read {}: {e}", path.display()))
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
    fn read(&self, relative: &str) -> Result<String, String> {
        self.files
            .iter()
            .find(|(path, _)| *path == relative)
            .map(|(_, text)| text.to_string())
            .ok_or_else(|| {
                format!(
                    "the built-in behaviour `{}` has no file {relative}",
                    self.name
                )
            })
    }

    fn show(&self, relative: &str) -> String {
        format!("<embedded>/{}/{relative}", self.name)
    }
}
