//! Branches of a recording from the command line (`docs/spec/behaviour.md` §3.5): `run
//! --branch REC --at ROUND` reads the recording it goes back into, and the replay page of a
//! recording (`replay REC --monitor --behaviour B`) starts each branch asked of it as a `run
//! --branch` process of its own, with a page of its own and a recording of its own.

use crate::cli::RunArgs;
use crate::failure::Failure;
use proclaim_behaviour::{read_recording, Behaviour, Branch, Recording};
use proclaim_monitor::{Branched, Brancher};
use std::io::{BufRead, BufReader, Read};
use std::net::SocketAddr;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::{Arc, Mutex};

/// The recording in `path`, or why it is none.
pub fn read(path: &Path) -> Result<Recording, Failure> {
    let text = crate::bounded::read_text(path, "a recording")?;
    read_recording(&text)
        .map_err(|e| Failure::Argument(format!("{}: not a recording: {e}", path.display())))
}

/// The branch `--branch` and `--at` ask for.
pub fn asked(args: &RunArgs) -> Result<Option<Branch>, Failure> {
    let (Some(path), Some(round)) = (&args.branch, args.at) else {
        return Ok(None);
    };
    if !args.network.is_local() {
        return Err(Failure::Argument(
            "--branch replays a recording onto a board of its own; it cannot share one".into(),
        ));
    }
    // Named whole, so the branch's parent is found from wherever the branch is read.
    let parent = std::fs::canonicalize(path).unwrap_or_else(|_| path.clone());
    let parent = parent.display().to_string();
    Branch::new(read(path)?, parent, round)
        .map(Some)
        .map_err(|why| Failure::Argument(format!("--branch {}: {why}", path.display())))
}

/// Says so when the behaviour, changed since the recording was made, does not replay it up to
/// the branch's round: the branch starts from where the behaviour is, not where the recording
/// was (a page that started the branch shows the note).
pub fn say_if_replayed_differently(behaviour: &Behaviour, args: &RunArgs) -> Result<(), Failure> {
    let Some(branch) = asked(args)? else {
        return Ok(());
    };
    if let Some(d) = branch
        .replayed_differently(behaviour)
        .map_err(Failure::Runtime)?
    {
        println!("{NOTE}the behaviour no longer does what the recording did before round {}: {d}; the branch starts where the behaviour is now", branch.of.round);
    }
    Ok(())
}

/// How a branch's run starts a note a page that started it shows.
const NOTE: &str = "note: ";

/// The branches started from a replay page, stopped with it.
#[derive(Clone, Default)]
pub struct Started(Arc<Mutex<Vec<Child>>>);

impl Started {
    /// Ends every branch still running as Ctrl-C would, so each writes its recording out;
    /// one that has not ended within a few seconds is killed.
    pub fn stop_all(&self) {
        let children = match self.0.lock() {
            Ok(mut children) => std::mem::take(&mut *children),
            Err(_) => return,
        };
        for child in &children {
            interrupt(child);
        }
        let deadline = std::time::Instant::now() + std::time::Duration::from_secs(5);
        for mut child in children {
            while std::time::Instant::now() < deadline && matches!(child.try_wait(), Ok(None)) {
                std::thread::sleep(std::time::Duration::from_millis(20));
            }
            let _ = child.kill();
            let _ = child.wait();
        }
    }
}

/// Ctrl-C to a branch's run.
#[cfg(unix)]
fn interrupt(child: &Child) {
    if let Ok(pid) = libc::pid_t::try_from(child.id()) {
        // SAFETY: kill(2) touches no memory of ours; the pid is a child we started and have not
        // waited for, so it names no other process.
        unsafe {
            libc::kill(pid, libc::SIGINT);
        }
    }
}

#[cfg(not(unix))]
fn interrupt(_child: &Child) {}

/// Starts branches of the recording at `record` of the behaviour `named`, each a `proclaim run
/// --branch` with its page on the replay page's host and its recording beside the parent.
pub fn brancher(named: &str, record: &Path, page: SocketAddr, started: Started) -> Brancher {
    let (named, record) = (named.to_string(), record.to_path_buf());
    Arc::new(move |round| {
        // One branch starts at a time: each gets a file of its own, and the ended are let go.
        let mut children = started
            .0
            .lock()
            .map_err(|_| "the branches' list is unusable")?;
        children.retain_mut(|c| matches!(c.try_wait(), Ok(None)));
        let file = free_name(&record, round);
        let program = std::env::current_exe().map_err(|e| format!("no program to run: {e}"))?;
        let mut child = Command::new(program)
            .args(["run", &named, "--branch"])
            .arg(&record)
            .args(["--at", &round.to_string(), "--monitor"])
            .arg(SocketAddr::new(page.ip(), 0).to_string())
            .arg("--record")
            .arg(&file)
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|e| format!("the branch did not start: {e}"))?;
        let (url, notes) = page_of(&mut child)?;
        children.push(child);
        Ok(Branched {
            url,
            file: file.display().to_string(),
            notes,
        })
    })
}

/// The branch's page, from the line its run prints, and the notes it printed before it; what
/// it said on error when it ended before printing one. The rest of its output is read (and dropped) so it never blocks.
fn page_of(child: &mut Child) -> Result<(String, Vec<String>), String> {
    let stdout = child.stdout.take().ok_or("the branch has no output")?;
    let mut lines = BufReader::new(stdout).lines();
    let mut notes = Vec::new();
    let url = lines.by_ref().map_while(Result::ok).find_map(|line| {
        if let Some(note) = line.strip_prefix(NOTE) {
            notes.push(note.to_string());
        }
        line.trim().strip_prefix("monitor: ").map(str::to_string)
    });
    let stderr = child.stderr.take();
    let Some(url) = url else {
        let mut said = String::new();
        if let Some(mut stderr) = stderr {
            let _ = stderr.read_to_string(&mut said);
        }
        let _ = child.wait();
        return Err(said.trim().to_string());
    };
    std::thread::spawn(move || lines.for_each(drop));
    if let Some(stderr) = stderr {
        std::thread::spawn(move || BufReader::new(stderr).lines().for_each(drop));
    }
    Ok((url, notes))
}

/// `kitchen.branch-r40.jsonl` beside `kitchen.jsonl`, or `…-r40-2.jsonl` and on when taken.
fn free_name(record: &Path, round: u64) -> PathBuf {
    let stem = record
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "recording".into());
    let named = |n: u32| {
        let tail = if n < 2 {
            String::new()
        } else {
            format!("-{n}")
        };
        record.with_file_name(format!("{stem}.branch-r{round}{tail}.jsonl"))
    };
    (1..)
        .map(named)
        .find(|path| !path.exists())
        .unwrap_or_else(|| named(1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_branch_is_recorded_beside_its_parent_under_a_name_not_taken() {
        let dir =
            std::env::temp_dir().join(format!("proclaim-branch-names-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let record = dir.join("kitchen.jsonl");
        let first = free_name(&record, 40);
        assert_eq!(first, dir.join("kitchen.branch-r40.jsonl"));
        std::fs::write(&first, "").unwrap();
        assert_eq!(
            free_name(&record, 40),
            dir.join("kitchen.branch-r40-2.jsonl")
        );
        let _ = std::fs::remove_dir_all(&dir);
    }
}
