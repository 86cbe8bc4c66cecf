//! Running machines one ring at a time (model simulation): each machine waits before each ring
//! until the stepper's count passes the last ring it took, and reports when the ring is done.
//! A stepper may also let the machines run freely and be paused later (the monitor's controls).

use parking_lot::Mutex;
use std::sync::Arc;
use tokio::sync::{watch, Notify};

/// The count of steps, and whether machines ring freely meanwhile.
#[derive(Clone, Copy, Debug, Default)]
struct Clock {
    step: u64,
    free: bool,
}

/// A machine and when its state's next time test comes due (none: it waits on none).
type Due = (String, Option<tokio::time::Instant>);

/// Shared by every machine of a behaviour and by whoever steps them. Clones share the count.
#[derive(Clone)]
pub struct Stepper {
    step: Arc<watch::Sender<Clock>>,
    /// Machine → the last step whose ring it finished.
    done: Arc<Mutex<Vec<(String, u64)>>>,
    finished: Arc<Notify>,
    /// Machine → when its state's next time test comes due, as its last ring left it.
    dues: Arc<Mutex<Vec<Due>>>,
}

impl std::fmt::Debug for Stepper {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let clock = *self.step.borrow();
        write!(f, "Stepper(step {}, free {})", clock.step, clock.free)
    }
}

/// Paused: nothing rings until [`Stepper::advance`].
impl Default for Stepper {
    fn default() -> Stepper {
        Stepper {
            step: Arc::new(watch::channel(Clock::default()).0),
            done: Arc::default(),
            finished: Arc::default(),
            dues: Arc::default(),
        }
    }
}

impl Stepper {
    /// Machines ring freely until [`Stepper::pause`].
    pub fn free() -> Stepper {
        let stepper = Stepper::default();
        stepper.resume();
        stepper
    }

    /// Lets every running machine take one ring; returns the new step number. Pauses first if
    /// the machines ran freely.
    pub fn advance(&self) -> u64 {
        let mut next = 0;
        self.step.send_modify(|c| {
            c.free = false;
            c.step += 1;
            next = c.step;
        });
        next
    }

    /// Each machine stops before its next ring.
    pub fn pause(&self) {
        self.step
            .send_if_modified(|c| std::mem::replace(&mut c.free, false));
    }

    /// Every machine rings freely again.
    pub fn resume(&self) {
        self.step
            .send_if_modified(|c| !std::mem::replace(&mut c.free, true));
    }

    pub fn is_paused(&self) -> bool {
        !self.step.borrow().free
    }

    /// The last step given.
    pub fn step(&self) -> u64 {
        self.step.borrow().step
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
                let done = self.done.lock();
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

    /// Before a ring: waits for a step after `last`, or for free running; returns the step.
    pub(crate) async fn wait(&self, last: u64) -> u64 {
        let clock = *self.step.borrow();
        if clock.free {
            return clock.step.max(last);
        }
        let mut rx = self.step.subscribe();
        let reached = rx
            .wait_for(|c| c.free || c.step > last)
            .await
            .map(|c| c.step.max(last));
        match reached {
            Ok(s) => s,
            // The stepper is gone: nobody will step again.
            Err(_) => std::future::pending().await,
        }
    }

    /// Whether a machine whose last ring was of step `last` may ring now, without waiting: the
    /// step to ring in, or none while paused (for a host that rings machines itself, as a
    /// compiled behaviour's does).
    pub fn may_ring(&self, last: u64) -> Option<u64> {
        let clock = *self.step.borrow();
        (clock.free || clock.step > last).then(|| clock.step.max(last))
    }

    /// When `machine`'s next time test comes due (none: it waits on none, or has moved and
    /// not yet arrived, so it rings next round anyway), as its last ring left it: what a host
    /// that moves a virtual clock itself moves it to.
    pub fn note_due(&self, machine: &str, due: Option<tokio::time::Instant>) {
        let mut dues = self.dues.lock();
        match dues.iter_mut().find(|(n, _)| n == machine) {
            Some(entry) => entry.1 = due,
            None => dues.push((machine.to_string(), due)),
        }
    }

    /// The soonest time test of any machine still to come due ([`Stepper::note_due`]).
    pub fn soonest_due(&self) -> Option<tokio::time::Instant> {
        self.dues.lock().iter().filter_map(|(_, due)| *due).min()
    }

    /// `machine` finished its ring of `step` (what the page's step waits for).
    pub fn ring_done(&self, machine: &str, step: u64) {
        {
            let mut done = self.done.lock();
            match done.iter_mut().find(|(n, _)| n == machine) {
                Some(entry) => entry.1 = step,
                None => done.push((machine.to_string(), step)),
            }
        }
        self.finished.notify_waiters();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    /// Whether `wait(last)` returns within a moment, and with what step.
    async fn rings(stepper: &Stepper, last: u64) -> Option<u64> {
        tokio::time::timeout(Duration::from_millis(50), stepper.wait(last))
            .await
            .ok()
    }

    #[tokio::test]
    async fn a_free_stepper_lets_machines_ring_until_paused_and_steps_one_ring_at_a_time() {
        let stepper = Stepper::free();
        assert!(!stepper.is_paused());
        assert_eq!(rings(&stepper, 0).await, Some(0), "free: no waiting");
        stepper.pause();
        assert!(stepper.is_paused());
        assert_eq!(rings(&stepper, 0).await, None, "paused: the machine waits");
        assert_eq!(stepper.advance(), 1);
        assert_eq!(rings(&stepper, 0).await, Some(1), "one ring");
        assert_eq!(rings(&stepper, 1).await, None, "and no more");
        stepper.resume();
        assert_eq!(rings(&stepper, 1).await, Some(1));
        // A step while running freely pauses first.
        assert_eq!(stepper.advance(), 2);
        assert!(stepper.is_paused());
        assert_eq!(rings(&stepper, 2).await, None);
    }

    #[test]
    fn may_ring_says_without_waiting_what_wait_would_return() {
        let stepper = Stepper::free();
        assert_eq!(stepper.may_ring(0), Some(0));
        stepper.pause();
        assert_eq!(stepper.may_ring(0), None);
        assert_eq!(stepper.advance(), 1);
        assert_eq!(stepper.may_ring(0), Some(1));
        assert_eq!(stepper.may_ring(1), None);
        stepper.resume();
        assert_eq!(stepper.may_ring(5), Some(5));
    }
}
