//! Running machines one ring at a time (model simulation): each machine waits before each ring
//! until the stepper's count passes the last ring it took, and reports when the ring is done.

use std::sync::{Arc, Mutex};
use tokio::sync::{watch, Notify};

/// Shared by every machine of a behaviour and by whoever steps them. Clones share the count.
#[derive(Clone)]
pub struct Stepper {
    step: Arc<watch::Sender<u64>>,
    /// Machine → the last step whose ring it finished.
    done: Arc<Mutex<Vec<(String, u64)>>>,
    finished: Arc<Notify>,
}

impl std::fmt::Debug for Stepper {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Stepper(step {})", *self.step.borrow())
    }
}

impl Default for Stepper {
    fn default() -> Stepper {
        Stepper {
            step: Arc::new(watch::channel(0).0),
            done: Arc::default(),
            finished: Arc::default(),
        }
    }
}

impl Stepper {
    /// Lets every running machine take one ring; returns the new step number.
    pub fn advance(&self) -> u64 {
        let mut next = 0;
        self.step.send_modify(|s| {
            *s += 1;
            next = *s;
        });
        next
    }

    /// Waits until each of `machines` finished its ring of `step`, or `limit` passes (a ring
    /// waiting on a slow expert). Returns the machines still busy.
    pub async fn settled(
        &self,
        machines: &[String],
        step: u64,
        limit: std::time::Duration,
    ) -> Vec<String> {
        let deadline = tokio::time::Instant::now() + limit;
        loop {
            let notified = self.finished.notified();
            let busy: Vec<String> = {
                let done = self.done.lock().unwrap_or_else(|e| e.into_inner());
                machines
                    .iter()
                    .filter(|m| !done.iter().any(|(n, s)| n == *m && *s >= step))
                    .cloned()
                    .collect()
            };
            if busy.is_empty() || tokio::time::timeout_at(deadline, notified).await.is_err() {
                return busy;
            }
        }
    }

    /// Before a ring: waits for a step after `last`; returns it.
    pub(crate) async fn wait(&self, last: u64) -> u64 {
        let mut rx = self.step.subscribe();
        let reached = rx.wait_for(|s| *s > last).await.map(|s| *s);
        match reached {
            Ok(s) => s,
            // The stepper is gone: nobody will step again.
            Err(_) => std::future::pending().await,
        }
    }

    pub(crate) fn ring_done(&self, machine: &str, step: u64) {
        {
            let mut done = self.done.lock().unwrap_or_else(|e| e.into_inner());
            match done.iter_mut().find(|(n, _)| n == machine) {
                Some(entry) => entry.1 = step,
                None => done.push((machine.to_string(), step)),
            }
        }
        self.finished.notify_waiters();
    }
}
