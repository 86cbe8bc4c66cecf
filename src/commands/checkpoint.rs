//! `proclaim run --checkpoint-at / --checkpoint-every / --resume`: checkpoint files, written
//! whole or not at all (a file next to the one asked for, renamed over it) and read back with
//! what is wrong with one said.

use crate::cli::RunArgs;
use crate::failure::Failure;
use proclaim_behaviour::{Checkpoint, CheckpointPlan};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Where a run's checkpoints go: the file asked for when one is asked, else that name with
/// each checkpoint's round before its extension (`press.r200.json`).
pub struct CheckpointFiles {
    path: PathBuf,
    one: bool,
    written: usize,
}

/// What `args` ask: the plan and where its checkpoints go, if any are asked.
pub fn plan(args: &RunArgs) -> Option<(CheckpointPlan, CheckpointFiles)> {
    if args.checkpoint_at.is_empty() && args.checkpoint_every.is_none() {
        return None;
    }
    let plan = CheckpointPlan {
        at: args.checkpoint_at.clone(),
        every: args.checkpoint_every,
    };
    let files = CheckpointFiles {
        path: args
            .checkpoint_file
            .clone()
            .unwrap_or_else(|| PathBuf::from("checkpoint.json")),
        one: args.checkpoint_at.len() == 1 && args.checkpoint_every.is_none(),
        written: 0,
    };
    Some((plan, files))
}

impl CheckpointFiles {
    /// How many were written.
    pub fn written(&self) -> usize {
        self.written
    }

    /// Writes `checkpoint`; the file it went to and its size in bytes.
    pub fn write(&mut self, checkpoint: &Checkpoint) -> Result<(PathBuf, usize), Failure> {
        let path = if self.one {
            self.path.clone()
        } else {
            let stem = self.path.file_stem().unwrap_or_default().to_string_lossy();
            let name = match self.path.extension() {
                Some(ext) => format!("{stem}.r{}.{}", checkpoint.round, ext.to_string_lossy()),
                None => format!("{stem}.r{}", checkpoint.round),
            };
            self.path.with_file_name(name)
        };
        let partial = path.with_extension("partial");
        let failed = |error| Failure::Write {
            path: path.clone(),
            error,
        };
        let text = checkpoint.to_text();
        std::fs::write(&partial, &text).map_err(failed)?;
        std::fs::rename(&partial, &path).map_err(failed)?;
        self.written += 1;
        Ok((path, text.len()))
    }
}

/// The checkpoint a run takes up (`--resume FILE`).
pub fn read(path: &Path) -> Result<Arc<Checkpoint>, Failure> {
    let text = std::fs::read_to_string(path).map_err(|error| Failure::Read {
        path: path.to_path_buf(),
        error,
    })?;
    Checkpoint::read(&text)
        .map(Arc::new)
        .map_err(|why| Failure::Argument(format!("--resume {}: {why}", path.display())))
}
