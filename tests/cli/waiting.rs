//! Waiting on a running `proclaim` for what it says, with a generous deadline, instead of
//! sleeping a fixed time that a loaded machine can outrun.

use std::io::{BufRead, BufReader, Read};
use std::sync::mpsc::{channel, Receiver};
use std::time::{Duration, Instant};

/// Long enough for a busy two-core CI machine; a test that waits this long has failed.
pub const PATIENCE: Duration = Duration::from_secs(60);

/// The lines of a child's pipe, read on a thread as they come, and every line read so far.
pub struct Lines {
    incoming: Receiver<String>,
    pub read: Vec<String>,
}

impl Lines {
    pub fn of(pipe: impl Read + Send + 'static) -> Lines {
        let (tx, incoming) = channel();
        std::thread::spawn(move || {
            for line in BufReader::new(pipe).lines().map_while(Result::ok) {
                if tx.send(line).is_err() {
                    return;
                }
            }
        });
        Lines {
            incoming,
            read: Vec::new(),
        }
    }

    /// Waits (at most [`PATIENCE`]) for a line containing `text`; a failure shows what was read.
    pub fn wait_for(&mut self, text: &str) {
        let deadline = Instant::now() + PATIENCE;
        if self.read.iter().any(|l| l.contains(text)) {
            return;
        }
        while let Some(left) = deadline.checked_duration_since(Instant::now()) {
            match self.incoming.recv_timeout(left) {
                Ok(line) => {
                    let found = line.contains(text);
                    self.read.push(line);
                    if found {
                        return;
                    }
                }
                Err(_) => break,
            }
        }
        panic!(
            "no line with `{text}` within {PATIENCE:?}; read:\n{}",
            self.read.join("\n")
        );
    }

    /// Every line, once the child has closed its pipe (it has exited), each ending in a newline.
    pub fn all(mut self) -> String {
        self.read.extend(self.incoming.iter());
        self.read.iter().map(|l| format!("{l}\n")).collect()
    }
}

/// A child process, killed when dropped: a test that fails while waiting leaves none behind.
pub struct Running(pub std::process::Child);

impl Drop for Running {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}
