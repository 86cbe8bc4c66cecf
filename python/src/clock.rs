//! The virtual clock of a stepped behaviour, moved so that a user cannot get it wrong: a step is
//! one round at one moment, and `run_until` waits for time too: when its round moves no machine
//! it lets the clock run to the next moment something is due (a `timeout`/`after` of a
//! machine's current state, or a timed line of the script) and runs the round that moment
//! wakes, so it reaches a state behind a timeout with no `wait`; `run(s)` ends with a round at
//! exactly `s`, so what falls due then happens within it. Host calls, which the runner does not
//! report, are put among the events here.

use proclaim_behaviour::testing::RoundByRound;
use proclaim_behaviour::Checkpoint;
use proclaim_experts::{Script, When};
use proclaim_fsm::Argument;
use proclaim_runner::Event;
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// A host function's call, as the Python callable got it.
#[derive(Clone, Debug)]
pub(crate) struct HostCall {
    pub(crate) function: String,
    pub(crate) argument: Option<Argument>,
}

/// Host calls made during a round, in order; taken after it.
pub(crate) type Calls = Arc<Mutex<Vec<HostCall>>>;

/// One entry of a behaviour's events: the runner's, or a host call (with the round it was in).
pub(crate) enum Logged<'a> {
    Runner(&'a Event),
    Called(&'a HostCall, u64),
}

/// What the clock knows of a behaviour besides the runner: the script's times and where the
/// host calls go.
pub(crate) struct Clock {
    /// Times (since the start) the script posts at, soonest first.
    script_times: Vec<Duration>,
    /// How far the virtual clock has moved since the start.
    now: Duration,
    /// How many of the runner's events have been read into `now`.
    seen: usize,
    calls: Calls,
    /// Whether the clock is virtual: on the wall clock a step does not wait for what is due.
    virtual_clock: bool,
    /// Each host call with how many runner events came before it, and its round.
    placed: Vec<(usize, HostCall, u64)>,
}

/// At most how many rounds `run` runs at its end while machines move: machines whose labels
/// are always true would move for ever at one moment.
const SETTLING_ROUNDS: usize = 100;

/// Whether an event is a machine moving: such a round needs no time to pass.
fn moved(event: &Event) -> bool {
    matches!(
        event,
        Event::Entered { .. }
            | Event::Fired { .. }
            | Event::Finished { .. }
            | Event::Halted { .. }
            | Event::Control { .. }
            | Event::Reloaded { .. }
    )
}

impl Clock {
    pub(crate) fn new(script: Option<&Script>, calls: Calls, virtual_clock: bool) -> Clock {
        let mut script_times: Vec<Duration> = script
            .map(|s| {
                s.steps
                    .iter()
                    .filter_map(|step| match step.when {
                        When::At(at) => Some(at),
                        _ => None,
                    })
                    .collect()
            })
            .unwrap_or_default();
        script_times.sort();
        Clock {
            script_times,
            now: Duration::ZERO,
            seen: 0,
            calls,
            virtual_clock,
            placed: Vec::new(),
        }
    }

    /// Where a run taken up from `checkpoint` left the clock: at its moment (the machines'
    /// entries, which their time tests count from, are the runner's).
    pub(crate) fn taken_up(&mut self, checkpoint: &Checkpoint) {
        self.now = Duration::from_nanos(checkpoint.at_ns);
    }

    /// Reads the runner's new events (time passed in a round) and places the host calls made meanwhile after them; whether a machine moved.
    fn observe(&mut self, running: &RoundByRound) -> bool {
        let mut any_moved = false;
        for event in &running.events[self.seen..] {
            any_moved |= moved(event);
            if let Some(at) = event.at() {
                self.now = self.now.max(at);
            }
        }
        self.seen = running.events.len();
        let calls = match self.calls.lock() {
            Ok(mut calls) => std::mem::take(&mut *calls),
            Err(_) => Vec::new(),
        };
        let round = running.rounds();
        self.placed
            .extend(calls.into_iter().map(|call| (self.seen, call, round)));
        any_moved
    }

    /// The next moment after now something is due: a time test of a machine's current state
    /// coming true (as the runner has it: a composite's counts from the composite's entry), or
    /// the script's next timed line.
    fn next_due(&self, running: &RoundByRound) -> Option<Duration> {
        let script = self.script_times.iter().copied().find(|t| *t > self.now);
        let machines = running.next_time_test().filter(|due| *due > self.now);
        script.into_iter().chain(machines).min()
    }

    /// One round at the moment the clock is at; with `waiting`, when it moved no machine and
    /// something is due, the clock moved to that moment and the round run there too.
    pub(crate) fn step(&mut self, running: &mut RoundByRound, waiting: bool) {
        running.round();
        if self.observe(running) || !waiting || running.is_over() || !self.virtual_clock {
            return;
        }
        if let Some(due) = self.next_due(running) {
            running.wait(due - self.now);
            self.now = due;
            running.round();
            self.observe(running);
        }
    }

    /// Lets the machines run freely for `time`, then runs rounds at its end for as long as
    /// they move a machine (as free running goes on at one moment after a firing), so that what
    /// is due at exactly `time` from now happens within the run, its new states entered.
    pub(crate) fn run(&mut self, running: &mut RoundByRound, time: Duration) {
        let until = self.now + time;
        running.run_for(time);
        self.observe(running);
        self.now = self.now.max(until);
        for _ in 0..SETTLING_ROUNDS {
            if running.is_over() {
                break;
            }
            running.round();
            if !self.observe(running) {
                break;
            }
        }
    }

    /// Lets `time` pass with no round run.
    pub(crate) fn wait(&mut self, running: &mut RoundByRound, time: Duration) {
        // Events the wait brought (a script's line posted meanwhile) are no later than its end:
        // the clock is where it was plus the wait, not the last of them plus the wait.
        let until = self.now + time;
        running.wait(time);
        self.observe(running);
        self.now = self.now.max(until);
    }

    /// How far the virtual clock has moved since the start.
    pub(crate) fn now(&self) -> Duration {
        self.now
    }

    /// How many events there are, host calls included.
    pub(crate) fn event_count(&self, running: &RoundByRound) -> usize {
        running.events.len() + self.placed.len()
    }

    /// The events from the `first`-th on (host calls included), oldest first.
    pub(crate) fn events_from<'a>(
        &'a self,
        running: &'a RoundByRound,
        first: usize,
    ) -> Vec<Logged<'a>> {
        let mut out = Vec::with_capacity(self.event_count(running).saturating_sub(first));
        let mut calls = self.placed.iter().peekable();
        let mut index = 0;
        for (position, event) in running.events.iter().enumerate() {
            while let Some((_, call, round)) = calls.next_if(|(after, _, _)| *after <= position) {
                if index >= first {
                    out.push(Logged::Called(call, *round));
                }
                index += 1;
            }
            if index >= first {
                out.push(Logged::Runner(event));
            }
            index += 1;
        }
        for (_, call, round) in calls {
            if index >= first {
                out.push(Logged::Called(call, *round));
            }
            index += 1;
        }
        out
    }
}
