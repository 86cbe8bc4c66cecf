//! `run --record`: every whiteboard message as one JSON line (`seq`, `at_us`, `module`, `type`,
//! `value`), written while the behaviour runs, with every ringlet once it has run, or as the
//! run stopped inside it (`{"ringlet": …}`), and the machines' events (`{"event": …}`) between
//! them: read back by `proclaim replay` (the messages) and `proclaim test` (all three).

use crate::failure::Failure;
use proclaim_board::{Pattern, Whiteboard};
use std::io::Write;
use std::path::{Path, PathBuf};

/// A record being written.
pub struct Recorder {
    task: tokio::task::JoinHandle<u64>,
    /// Ringlet and event lines, written as they come.
    lines: tokio::sync::mpsc::UnboundedSender<String>,
    stop: tokio::sync::oneshot::Sender<()>,
    /// The task passing ringlets on to `lines`, and how to tell it the run is over.
    follower: Option<(
        tokio::task::JoinHandle<()>,
        tokio::sync::oneshot::Sender<()>,
    )>,
    path: PathBuf,
}

/// Subscribes to everything on `board` and writes it to `path` until told to finish.
/// A branch's record (`header`) starts with the line naming its parent and round.
pub fn start(board: &Whiteboard, path: &Path, header: Option<&str>) -> Result<Recorder, Failure> {
    let file = std::fs::File::create(path).map_err(|error| Failure::Write {
        path: path.to_path_buf(),
        error,
    })?;
    let mut out = std::io::BufWriter::new(file);
    if let Some(header) = header {
        writeln!(out, "{header}").map_err(|error| Failure::Write {
            path: path.to_path_buf(),
            error,
        })?;
    }
    let mut all = board.subscribe_pattern(Pattern::All);
    let (stop, mut stopped) = tokio::sync::oneshot::channel();
    let (lines, mut other) = tokio::sync::mpsc::unbounded_channel::<String>();
    let task = tokio::spawn(async move {
        let mut written = 0u64;
        let mut write = |out: &mut std::io::BufWriter<std::fs::File>, text: &str, message: bool| {
            if writeln!(out, "{text}").is_ok() && message {
                written += 1;
            }
        };
        // Taken without waiting, at most this many before the task writes out and waits like
        // any other (taking without waiting spends none of tokio's budget).
        const BATCH: usize = 256;
        let mut taken = 0;
        loop {
            // Messages before other lines, as they come; whenever nothing more is waiting,
            // what came is written out, so a process killed loses at most what it was writing,
            // not a buffer's worth of its last seconds.
            if taken < BATCH {
                taken += 1;
                if let Some(m) = all.try_next() {
                    write(&mut out, &proclaim_behaviour::message_line(&m), true);
                    continue;
                }
                if let Ok(text) = other.try_recv() {
                    write(&mut out, &text, false);
                    continue;
                }
            }
            taken = 0;
            let _ = out.flush();
            tokio::select! {
                biased;
                message = all.next() => match message {
                    Some(m) => write(&mut out, &proclaim_behaviour::message_line(&m), true),
                    None => break,
                },
                Some(text) = other.recv() => write(&mut out, &text, false),
                _ = &mut stopped => {
                    // What is already queued belongs to the run too.
                    while let Some(m) = all.try_next() {
                        write(&mut out, &proclaim_behaviour::message_line(&m), true);
                    }
                    while let Ok(text) = other.try_recv() {
                        write(&mut out, &text, false);
                    }
                    break;
                }
            }
        }
        let _ = out.flush();
        written
    });
    Ok(Recorder {
        task,
        lines,
        stop,
        follower: None,
        path: path.to_path_buf(),
    })
}

impl Recorder {
    /// Writes the ringlets as they end (with their snapshots), from now on.
    pub fn follow(
        &mut self,
        mut ringlets: tokio::sync::mpsc::UnboundedReceiver<proclaim_runner::Ringlet>,
    ) {
        let lines = self.lines.clone();
        let (over, mut run_over) = tokio::sync::oneshot::channel();
        let task = tokio::spawn(async move {
            let send = |ringlet: &proclaim_runner::Ringlet| {
                lines
                    .send(proclaim_behaviour::ringlet_line(ringlet))
                    .is_ok()
            };
            loop {
                tokio::select! {
                    biased;
                    ringlet = ringlets.recv() => match ringlet {
                        Some(ringlet) if send(&ringlet) => {}
                        _ => return,
                    },
                    _ = &mut run_over => {
                        // The last ringlets may still be queued: a record without its last
                        // round would not replay to its end.
                        while let Ok(ringlet) = ringlets.try_recv() {
                            send(&ringlet);
                        }
                        return;
                    }
                }
            }
        });
        self.follower = Some((task, over));
    }

    /// Writes one of the machines' events.
    pub fn event(&self, event: &proclaim_runtime::Event) {
        let _ = self
            .lines
            .send(serde_json::to_string(event).unwrap_or_default());
    }

    /// Stops recording; how many messages were written, and where.
    pub async fn finish(self) -> (u64, PathBuf) {
        if let Some((task, over)) = self.follower {
            let _ = over.send(());
            let _ = task.await;
        }
        let _ = self.stop.send(());
        (self.task.await.unwrap_or(0), self.path)
    }
}

/// A recorded message as `replay` prints it, or `None` when the line is not one.
pub fn shown(line: &serde_json::Value) -> Option<String> {
    let at = line.get("at_us")?.as_u64()?;
    let module = line.get("module")?.as_str()?;
    let ty = line.get("type")?.as_str()?;
    let value = line.get("value")?;
    let priority = match line.get("priority").and_then(serde_json::Value::as_u64) {
        Some(p) => format!(" @{p}"),
        None => String::new(),
    };
    Some(format!(
        "{:>8.3}s #{:<6} {module:<14} {ty} = {value}{priority}",
        at as f64 / 1e6,
        line.get("seq")?.as_u64()?
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proclaim_runner::Ringlet;
    use std::time::Duration;

    /// The run's last ringlets are sent just before it finishes; the task passing them on may
    /// not have run since (it did not on a loaded machine, and the replay ended a round short).
    #[tokio::test(flavor = "current_thread")]
    async fn the_ringlets_sent_just_before_the_finish_are_written() {
        let dir = std::env::temp_dir().join(format!("proclaim-record-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("last-round.jsonl");
        let board = Whiteboard::local();
        let Ok(mut recorder) = start(&board, &path, None) else {
            panic!("cannot write {}", path.display());
        };
        let (ringlets, heard) = tokio::sync::mpsc::unbounded_channel();
        recorder.follow(heard);
        for round in 1..=3 {
            let ringlet = Ringlet {
                round,
                machine: 0,
                seq: 0,
                at: Duration::from_millis(100 * round),
                snapshot: None,
            };
            ringlets.send(ringlet).unwrap();
        }
        recorder.finish().await;
        let text = std::fs::read_to_string(&path).unwrap();
        let rounds: Vec<u64> = text
            .lines()
            .filter_map(|l| serde_json::from_str::<serde_json::Value>(l).ok())
            .filter_map(|l| l["ringlet"]["round"].as_u64())
            .collect();
        assert_eq!(rounds, [1, 2, 3], "{text}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
