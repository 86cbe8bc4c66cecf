//! The run's whiteboard with its page: what the compiled program's host posts, asks and
//! observes goes through it, and it holds the rounds while the page has the run paused.

use crate::hear::hear;
use crate::place::whiteboard;
use proclaim_board::{QueryOutcome, Value, Whiteboard};
use proclaim_monitor::{Access, Chart, Monitor};
use proclaim_runner::Stepper;
use proclaim_runtime::host::{Heard, HostBoard, Place, MONITOR_ADDR};
use proclaim_runtime::world::Elsewhere;
use proclaim_runtime::Event;
use std::cell::RefCell;
use std::collections::VecDeque;
use std::sync::mpsc;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// The run's whiteboard, its page, and what is heard there.
pub struct LiveBoard {
    runtime: tokio::runtime::Runtime,
    board: Whiteboard,
    monitor: Option<Monitor>,
    /// Where the page listens, when there is one.
    page: Option<std::net::SocketAddr>,
    /// The page's pause and step, which hold the rounds.
    stepper: Option<Stepper>,
    heard: mpsc::Receiver<Heard>,
    /// What was heard while the run was held, taken before anything newer.
    held: RefCell<VecDeque<Heard>>,
    /// The names of the experts that answered a query, kept for the life of the run (the
    /// trace's reports name them).
    experts: RefCell<Vec<&'static str>>,
}

impl LiveBoard {
    /// The whiteboard `place` says, with the monitor's page when it asks for one (served
    /// before this returns, its address on standard error: standard output may be the trace).
    pub fn open(
        place: &Place,
        name: &'static str,
        ours: Vec<&'static str>,
        charts: impl FnOnce() -> Vec<Chart>,
    ) -> Result<LiveBoard, String> {
        let runtime = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(1)
            .enable_all()
            .build()
            .map_err(|e| format!("no runtime for the whiteboard ({e})"))?;
        let board = runtime.block_on(whiteboard(place))?;
        let stop = Arc::new(tokio::sync::Notify::new());
        let heard = hear(&runtime, &board, ours, stop.clone());
        let stepper = place.monitor.as_ref().map(|_| Stepper::free());
        let (monitor, page) = match &place.monitor {
            Some(asked) => {
                let monitor = Monitor::live(name, charts(), board.clone(), stepper.clone());
                if !place.read_only {
                    monitor.set_stopper(stop);
                }
                let read_only = place.read_only;
                let (bound, shown) =
                    runtime.block_on(monitor.serve_asked(asked, MONITOR_ADDR, |wanted| {
                        Access::for_address(wanted, read_only)
                    }))?;
                eprintln!("  monitor: {shown}");
                (Some(monitor), Some(bound))
            }
            None => (None, None),
        };
        Ok(LiveBoard {
            runtime,
            board,
            monitor,
            page,
            stepper,
            heard,
            held: RefCell::default(),
            experts: RefCell::default(),
        })
    }

    /// The whiteboard itself, for a program that posts or listens beside its machines.
    pub fn whiteboard(&self) -> &Whiteboard {
        &self.board
    }

    /// Where the page listens, when there is one.
    pub fn page(&self) -> Option<std::net::SocketAddr> {
        self.page
    }

    /// An expert's name for as long as the run lasts: few experts answer, each named once.
    fn expert(&self, name: &str) -> &'static str {
        let mut experts = self.experts.borrow_mut();
        if let Some(known) = experts.iter().find(|e| **e == name) {
            return known;
        }
        let kept: &'static str = Box::leak(name.to_string().into_boxed_str());
        experts.push(kept);
        kept
    }
}

impl HostBoard for LiveBoard {
    /// Posts one of the run's messages.
    fn post(&self, module: &str, ty: &str, value: &serde_json::Value) {
        let _on_the_runtime = self.runtime.enter();
        self.board.post(module, ty, Value::from_json(value));
    }

    /// Asks `atom` of whoever answers it on the whiteboard, waiting at most `timeout_ms`, as
    /// the runner asks it.
    fn query(&self, machine: &str, atom: &str, timeout_ms: u64) -> Elsewhere {
        let timeout = Duration::from_millis(timeout_ms);
        match self
            .runtime
            .block_on(self.board.query(machine, atom, timeout))
        {
            QueryOutcome::Answered { value, by, .. } => {
                Elsewhere::Answered(value, self.expert(&by))
            }
            QueryOutcome::TimedOut => Elsewhere::TimedOut,
            QueryOutcome::NoExpert => Elsewhere::NoExpert,
        }
    }

    /// Shows one of the trace's events on the page.
    fn observe(&self, event: &Event) {
        if let Some(monitor) = &self.monitor {
            monitor.observe(event);
        }
    }

    /// Waits until `deadline` (none: for as long as it takes) for another module's posting or
    /// Ctrl-C; none when the deadline came first.
    fn wait(&self, deadline: Option<Instant>) -> Option<Heard> {
        if let Some(held) = self.held.borrow_mut().pop_front() {
            return Some(held);
        }
        match deadline {
            Some(at) => self
                .heard
                .recv_timeout(at.saturating_duration_since(Instant::now()))
                .ok(),
            None => Some(self.heard.recv().unwrap_or(Heard::Interrupted)),
        }
    }

    /// What was heard and not yet taken, without waiting.
    fn heard_now(&self) -> Option<Heard> {
        let held = self.held.borrow_mut().pop_front();
        held.or_else(|| self.heard.try_recv().ok())
    }

    /// Before a round: while the page has the run paused, waits for its step (what is heard
    /// meanwhile is kept for later); the step the round rings in, after the last round's
    /// `last`. None at Ctrl-C.
    fn hold(&self, last: u64) -> Option<u64> {
        let Some(stepper) = &self.stepper else {
            return Some(last);
        };
        loop {
            if let Some(step) = stepper.may_ring(last) {
                return Some(step);
            }
            match self.heard.recv_timeout(Duration::from_millis(20)) {
                Ok(Heard::Interrupted) | Err(mpsc::RecvTimeoutError::Disconnected) => return None,
                Ok(posting) => self.held.borrow_mut().push_back(posting),
                Err(mpsc::RecvTimeoutError::Timeout) => {}
            }
        }
    }

    /// After a round rung in `step`: every machine's ring is done, as the page's step waits
    /// to hear.
    fn rung(&self, step: u64, machines: &[&str]) {
        if let Some(stepper) = &self.stepper {
            for machine in machines {
                stepper.ring_done(machine, step);
            }
        }
    }

    /// After the run: the page shows where everything ended until Ctrl-C.
    fn linger(&self) {
        if self.monitor.is_none() {
            return;
        }
        eprintln!("  the monitor page stays open; Ctrl-C to close it");
        while let Ok(heard) = self.heard.recv() {
            if let Heard::Interrupted = heard {
                return;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::{Read, Write};

    fn local(monitor: Option<&str>) -> LiveBoard {
        let place = Place {
            monitor: monitor.map(str::to_string),
            ..Place::default()
        };
        LiveBoard::open(&place, "test", vec!["Ours"], Vec::new).expect("opens")
    }

    #[test]
    fn another_modules_posting_is_heard_and_the_runs_own_are_not() {
        let board = local(None);
        board.post("Ours", "door", &serde_json::json!(true));
        {
            let _on_the_runtime = board.runtime.enter();
            board.whiteboard().post("Button", "pressed", Value::Int(3));
        }
        let soon = Some(Instant::now() + Duration::from_secs(5));
        match board.wait(soon) {
            Some(Heard::Posting(module, ty, text, json)) => {
                assert_eq!(
                    (module.as_str(), ty.as_str(), text.as_str()),
                    ("Button", "pressed", "3")
                );
                assert_eq!(json, serde_json::json!(3));
            }
            _ => panic!("the button's posting is heard"),
        }
        assert!(
            board.heard_now().is_none(),
            "the run's own posting is not heard back"
        );
    }

    #[test]
    fn a_question_nobody_answers_says_so() {
        let board = local(None);
        assert!(matches!(
            board.query("M", "lonely", 50),
            Elsewhere::NoExpert
        ));
    }

    #[test]
    fn the_page_is_served_where_asked_and_a_bad_address_is_refused() {
        let board = local(Some("127.0.0.1:0"));
        let page = board.page().expect("a page");
        let mut stream = std::net::TcpStream::connect(page).expect("the page listens");
        stream
            .write_all(b"GET / HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n")
            .unwrap();
        let mut reply = String::new();
        stream.read_to_string(&mut reply).unwrap();
        assert!(reply.starts_with("HTTP/1.1 200"), "{reply}");

        let place = Place {
            monitor: Some("not an address".into()),
            ..Place::default()
        };
        let error = LiveBoard::open(&place, "test", vec![], Vec::new)
            .err()
            .expect("refused");
        assert!(error.contains("--monitor not an address"), "{error}");
    }
}
