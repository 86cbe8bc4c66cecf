//! `run --record`: every whiteboard message as one JSON line (`seq`, `at_us`, `module`, `type`,
//! `value`), written while the behaviour runs, with every ringlet as it started
//! (`{"ringlet": …}`) and the machines' events (`{"event": …}`) between them: read back by
//! `proclaim replay` (the messages) and `proclaim test` (all three).

use crate::failure::Failure;
use proclaim_board::{Message, Pattern, Whiteboard};
use std::io::Write;
use std::path::{Path, PathBuf};

/// A record being written.
pub struct Recorder {
    task: tokio::task::JoinHandle<u64>,
    /// Ringlet and event lines, written as they come.
    lines: tokio::sync::mpsc::UnboundedSender<String>,
    stop: tokio::sync::oneshot::Sender<()>,
    path: PathBuf,
}

/// Subscribes to everything on `board` and writes it to `path` until told to finish.
pub fn start(board: &Whiteboard, path: &Path) -> Result<Recorder, Failure> {
    let file = std::fs::File::create(path).map_err(|error| Failure::Write {
        path: path.to_path_buf(),
        error,
    })?;
    let mut out = std::io::BufWriter::new(file);
    let mut all = board.subscribe_pattern(Pattern::All);
    let (stop, mut stopped) = tokio::sync::oneshot::channel();
    let (lines, mut other) = tokio::sync::mpsc::unbounded_channel::<String>();
    let task = tokio::spawn(async move {
        let mut written = 0u64;
        let mut write = |text: &str, message: bool| {
            if writeln!(out, "{text}").is_ok() && message {
                written += 1;
            }
        };
        loop {
            tokio::select! {
                biased;
                message = all.next() => match message {
                    Some(m) => write(&line(&m), true),
                    None => break,
                },
                Some(text) = other.recv() => write(&text, false),
                _ = &mut stopped => {
                    // What is already queued belongs to the run too.
                    while let Some(m) = all.try_next() {
                        write(&line(&m), true);
                    }
                    while let Ok(text) = other.try_recv() {
                        write(&text, false);
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
        path: path.to_path_buf(),
    })
}

impl Recorder {
    /// Writes the ringlets as they end (with their snapshots), from now on.
    pub fn follow(
        &self,
        mut ringlets: tokio::sync::mpsc::UnboundedReceiver<proclaim_runner::Ringlet>,
    ) {
        let lines = self.lines.clone();
        tokio::spawn(async move {
            while let Some(ringlet) = ringlets.recv().await {
                if lines
                    .send(proclaim_behaviour::ringlet_line(&ringlet))
                    .is_err()
                {
                    return;
                }
            }
        });
    }

    /// Writes one of the machines' events.
    pub fn event(&self, event: &proclaim_runner::Event) {
        let _ = self
            .lines
            .send(serde_json::to_string(event).unwrap_or_default());
    }

    /// Stops recording; how many messages were written, and where.
    pub async fn finish(self) -> (u64, PathBuf) {
        let _ = self.stop.send(());
        (self.task.await.unwrap_or(0), self.path)
    }
}

/// One message as a JSON line.
pub fn line(m: &Message) -> String {
    let mut line = serde_json::json!({
        "seq": m.seq,
        "at_us": m.time.as_micros() as u64,
        "module": &*m.module,
        "type": &*m.ty,
        "value": m.value.to_json(),
    });
    // A subsumption layer's priority; absent at 0, so other recordings read as they did.
    if m.priority != 0 {
        line["priority"] = serde_json::json!(m.priority);
    }
    line.to_string()
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
