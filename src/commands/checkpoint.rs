//! `proclaim run --checkpoint-at / --checkpoint-every / --resume`: checkpoint files, written
//! whole or not at all (a file next to the one asked for, renamed over it) and read back with
//! what is wrong with one said.

use crate::cli::RunArgs;
use crate::failure::Failure;
use proclaim_behaviour::{Checkpoint, CheckpointPlan};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Where a run's checkpoints go: the file asked for when one is asked, else that name with
/// each checkpoint's round before its extension (`press.r200.json`).
pub struct CheckpointFiles {
    path: PathBuf,
    one: bool,
    taken: usize,
}

/// Whether `args` ask for checkpoints in a way that can be kept: a file says where they go,
/// not that one is taken.
pub fn refuse_unasked(args: &RunArgs) -> Result<(), Failure> {
    let asked = !args.checkpoint_at.is_empty() || args.checkpoint_every.is_some();
    if args.checkpoint_file.is_some() && !asked {
        return Err(Failure::Argument(
            "--checkpoint-file says where checkpoints go; ask for one with --checkpoint-at ROUND or --checkpoint-every N".into(),
        ));
    }
    Ok(())
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
        taken: 0,
    };
    Some((plan, files))
}

impl CheckpointFiles {
    /// How many the run took (each written, or warned of when it could not be).
    pub fn taken(&self) -> usize {
        self.taken
    }

    /// Writes `checkpoint`; the file it went to and its size in bytes.
    pub fn write(&mut self, checkpoint: &Checkpoint) -> Result<(PathBuf, usize), Failure> {
        self.taken += 1;
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
        // Written beside it under a name of its own and renamed over it once whole and on disk,
        // so a crash leaves the last checkpoint or this one, never half of one.
        let mut partial = path.clone().into_os_string();
        partial.push(".partial");
        let partial = PathBuf::from(partial);
        let failed = |error| Failure::Write {
            path: partial.clone(),
            error,
        };
        let text = checkpoint
            .to_text()
            .map_err(|e| failed(std::io::Error::other(e)))?;
        let mut file = std::fs::File::create(&partial).map_err(failed)?;
        file.write_all(text.as_bytes()).map_err(failed)?;
        file.sync_all().map_err(failed)?;
        std::fs::rename(&partial, &path).map_err(|error| Failure::Write {
            path: path.clone(),
            error,
        })?;
        Ok((path, text.len()))
    }
}

/// The checkpoint a run takes up (`--resume FILE`).
pub fn read(path: &Path) -> Result<Arc<Checkpoint>, Failure> {
    let text = crate::bounded::read_text(path, "a checkpoint")?;
    Checkpoint::read(&text)
        .map(Arc::new)
        .map_err(|why| Failure::Argument(format!("--resume {}: {why}", path.display())))
}
