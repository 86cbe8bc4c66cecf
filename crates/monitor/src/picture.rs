//! Where every machine is and what it last did, folded from the runner's events; with a
//! whiteboard snapshot, it is one frame of the page. Bounded whatever the run's length.

use crate::diagram::Chart;
use proclaim_board::{undecided_type, Kind, Snapshot};
use proclaim_fsm::Machine;
use proclaim_runner::{Answerer, Command, Event};
use serde::Serialize;
use std::collections::VecDeque;
use std::time::Duration;

/// How many events a frame carries at most (the newest).
pub const RECENT: usize = 200;
/// How many labels' answers are kept (the behaviour's labels, unless atoms are made up as it
/// runs: then those asked longest ago give way).
pub const LABELS: usize = 2000;
/// How many whiteboard rows a frame carries at most (by name; the page says how many more).
pub const BOARD_ROWS: usize = 2000;

/// The page's model of a running (or replayed) behaviour, apart from the whiteboard.
#[derive(Clone, Debug)]
pub struct Picture {
    machines: Vec<MachineView>,
    /// The last answer of each (machine, label).
    answers: VecDeque<AnswerView>,
    /// The newest events, an answer only when it differs from that label's last one (a
    /// machine asks its labels at every ring).
    events: VecDeque<Event>,
    /// Events folded in so far.
    pub count: u64,
    /// Events listed so far (the repeated answers are not).
    listed: u64,
}

#[derive(Clone, Debug, Serialize)]
pub struct MachineView {
    pub name: String,
    /// The state it is in (or going to: its OnEntry runs at its next ring).
    pub state: Option<i64>,
    pub state_name: Option<String>,
    /// The transition that moved it last.
    pub fired: Option<Fired>,
    /// Its last control command (`suspend`, `Off`, …), which tells suspended from dormant.
    pub control: Option<String>,
    pub finished: bool,
    pub halted: Option<String>,
    #[serde(skip)]
    start: bool,
    #[serde(skip)]
    states: Vec<(i64, String)>,
}

#[derive(Clone, Debug, Serialize)]
pub struct Fired {
    pub from: i64,
    pub to: i64,
    pub label: String,
    pub at_us: u64,
}

#[derive(Clone, Debug, Serialize)]
pub struct AnswerView {
    pub machine: String,
    pub atom: String,
    pub value: bool,
    /// The expert's or poster's name; empty for `timed out` and `no expert`.
    pub by: String,
    /// `expert`, `posted`, `timed_out` or `no_expert`.
    pub how: &'static str,
    /// When it was last asked.
    pub at_us: u64,
    /// When its value or who answered last changed.
    pub changed_us: u64,
    /// How often it was asked.
    pub asked: u64,
}

/// One frame as the page receives it.
#[derive(Debug, Serialize)]
pub struct Frame<'p> {
    pub machines: Vec<MachineFrame<'p>>,
    pub answers: Vec<AnswerFrame<'p>>,
    pub events: &'p VecDeque<Event>,
    /// How many events were listed since the start (the first of `events` is number
    /// `events_listed - events.len() + 1`).
    pub events_listed: u64,
    pub board: Vec<BoardRowFrame>,
    /// Types left out beyond [`BOARD_ROWS`].
    pub board_more: usize,
    pub board_seq: u64,
    pub time_us: u64,
}

#[derive(Debug, Serialize)]
pub struct AnswerFrame<'p> {
    #[serde(flatten)]
    pub view: &'p AnswerView,
    /// Its expert could not decide it within its search limits and answered false
    /// (`NameUndecided` on the board).
    pub undecided: bool,
}

#[derive(Debug, Serialize)]
pub struct MachineFrame<'p> {
    #[serde(flatten)]
    pub view: &'p MachineView,
    /// `running`, `suspended`, `dormant`, `finished` or `halted`.
    pub mode: &'static str,
}

/// One row of the board as the page shows it (the board crate's `BoardRow` in text).
#[derive(Debug, Serialize)]
pub struct BoardRowFrame {
    #[serde(rename = "type")]
    pub ty: String,
    pub kind: &'static str,
    pub value: String,
    pub by: String,
    pub seq: u64,
    pub at_us: u64,
    pub posts: u64,
}

impl Picture {
    /// The machines as the page draws them, each in its initial state.
    pub fn new(charts: &[Chart]) -> Picture {
        Picture::of(charts.iter().map(|chart| {
            let states = chart
                .states
                .iter()
                .map(|s| (s.id, s.name.clone()))
                .collect();
            (chart.name.clone(), chart.start, chart.initial, states)
        }))
    }

    /// Machines with whether each starts with the behaviour, without drawing them (`run
    /// --step` prints where each one is).
    pub fn of_machines<'m>(machines: impl IntoIterator<Item = (&'m Machine, bool)>) -> Picture {
        Picture::of(machines.into_iter().map(|(m, start)| {
            let states = m.states.iter().map(|s| (s.id, s.name.clone())).collect();
            (m.name.clone(), start, m.initial, states)
        }))
    }

    /// (name, starts, initial state, states) of each machine.
    fn of(machines: impl Iterator<Item = (String, bool, i64, Vec<(i64, String)>)>) -> Picture {
        Picture {
            machines: machines
                .map(|(name, start, initial, states)| {
                    let first = states.iter().find(|(id, _)| *id == initial);
                    MachineView {
                        name,
                        state: first.map(|(id, _)| *id),
                        state_name: first.map(|(_, n)| n.clone()),
                        fired: None,
                        control: None,
                        finished: false,
                        halted: None,
                        start,
                        states,
                    }
                })
                .collect(),
            answers: VecDeque::new(),
            events: VecDeque::new(),
            count: 0,
            listed: 0,
        }
    }

    /// A machine read again: its states are the new chart's, and where it is is found again by
    /// the state's name.
    pub fn redraw(&mut self, chart: &Chart) {
        let Some(view) = self.machines.iter_mut().find(|m| m.name == chart.name) else {
            return;
        };
        view.states = chart
            .states
            .iter()
            .map(|s| (s.id, s.name.clone()))
            .collect();
        view.state = view.state_name.as_deref().and_then(|n| view.id_of(n));
        // The transition that fired may be gone from the new machine.
        view.fired = None;
    }

    /// Each machine's name and the name of the state it is in (or going to).
    pub fn states(&self) -> impl Iterator<Item = (&str, Option<&str>)> {
        self.machines
            .iter()
            .map(|m| (m.name.as_str(), m.state_name.as_deref()))
    }

    /// Folds one event in: O(machines) at worst, and bounded memory.
    pub fn observe(&mut self, event: &Event) {
        self.count += 1;
        if let Event::Answered {
            machine,
            atom,
            value,
            by,
            at,
            ..
        } = event
        {
            if !self.answer(machine, atom, *value, by, *at) {
                return;
            }
        }
        self.listed += 1;
        push_bounded(&mut self.events, event.clone());
        if let Some(view) = self.machines.iter_mut().find(|m| m.name == event.machine()) {
            view.follow(event);
        }
    }

    /// Keeps a label's answer; whether it is news (a new label, value or answerer).
    fn answer(
        &mut self,
        machine: &str,
        atom: &str,
        value: bool,
        by: &Answerer,
        at: Duration,
    ) -> bool {
        let (how, by) = match by {
            Answerer::Expert(e) => ("expert", e.as_str()),
            Answerer::Posted(p) => ("posted", p.as_str()),
            Answerer::TimedOut => ("timed_out", ""),
            Answerer::NoExpert => ("no_expert", ""),
        };
        let at_us = micros(at);
        if let Some(row) = self
            .answers
            .iter_mut()
            .find(|a| a.machine == machine && a.atom == atom)
        {
            row.asked += 1;
            row.at_us = at_us;
            if row.value == value && row.how == how && row.by == by {
                return false;
            }
            row.value = value;
            row.how = how;
            row.by = by.to_string();
            row.changed_us = at_us;
            return true;
        }
        if self.answers.len() == LABELS {
            // The label asked longest ago.
            if let Some(oldest) = (0..self.answers.len()).min_by_key(|&i| self.answers[i].at_us) {
                self.answers.remove(oldest);
            }
        }
        self.answers.push_back(AnswerView {
            machine: machine.to_string(),
            atom: atom.to_string(),
            value,
            by: by.to_string(),
            how,
            at_us,
            changed_us: at_us,
            asked: 1,
        });
        true
    }

    /// The frame of this picture over `board`. `running` says, for a machine, whether its
    /// `NameIsRunning` reads true on the board (`None`: not said yet).
    pub fn frame<'p>(&'p self, board: &Snapshot) -> Frame<'p> {
        let machines = self
            .machines
            .iter()
            .map(|view| MachineFrame {
                view,
                mode: mode(view, board),
            })
            .collect();
        let rows = board.rows();
        let board_more = rows.len().saturating_sub(BOARD_ROWS);
        let board_rows = rows
            .into_iter()
            .filter(|r| r.ty != proclaim_board::QUERY_TYPE)
            .take(BOARD_ROWS)
            .map(|r| BoardRowFrame {
                ty: r.ty.to_string(),
                kind: match r.kind {
                    Kind::State => "state",
                    Kind::Signal => "signal",
                    Kind::Data => "data",
                },
                value: r.newest.value.to_string(),
                // A subsumption layer's postings say their priority (who holds the type).
                by: match r.newest.priority {
                    0 => r.newest.module.to_string(),
                    p => format!("{} @{p}", r.newest.module),
                },
                seq: r.newest.seq,
                at_us: micros(r.newest.time),
                posts: r.posts,
            })
            .collect();
        let answers = self
            .answers
            .iter()
            .map(|view| AnswerFrame {
                view,
                undecided: view.how == "expert"
                    && !view.value
                    && board
                        .newest(&undecided_type(&view.atom))
                        .is_some_and(|m| m.value.truthy()),
            })
            .collect();
        Frame {
            machines,
            answers,
            events: &self.events,
            events_listed: self.listed,
            board: board_rows,
            board_more,
            board_seq: board.seq,
            time_us: micros(board.time),
        }
    }
}

impl MachineView {
    /// Where an event of this machine leaves it.
    fn follow(&mut self, event: &Event) {
        match event {
            Event::Entered { state, id, .. } => {
                self.state = Some(*id);
                self.state_name = Some(state.clone());
                self.finished = false;
            }
            Event::Reloaded { state, .. } => {
                self.state = self.id_of(state);
                self.state_name = Some(state.clone());
                self.finished = false;
            }
            Event::Fired {
                from,
                to,
                label,
                at,
                ..
            } => {
                self.state = Some(*to);
                self.state_name = self.name_of(*to);
                self.fired = Some(Fired {
                    from: *from,
                    to: *to,
                    label: label.clone(),
                    at_us: micros(*at),
                });
            }
            Event::Control { command, .. } => {
                self.control = Some(command.clone());
                if matches!(
                    Command::parse(command),
                    Some(Command::On | Command::Restart)
                ) {
                    self.finished = false;
                    self.halted = None;
                }
            }
            Event::Finished { .. } => self.finished = true,
            Event::Halted { reason, .. } => self.halted = Some(reason.clone()),
            _ => {}
        }
    }

    fn id_of(&self, name: &str) -> Option<i64> {
        self.states
            .iter()
            .find(|(_, n)| n == name)
            .map(|(id, _)| *id)
    }

    fn name_of(&self, id: i64) -> Option<String> {
        self.states
            .iter()
            .find(|(s, _)| *s == id)
            .map(|(_, n)| n.clone())
    }
}

fn mode(view: &MachineView, board: &Snapshot) -> &'static str {
    if view.halted.is_some() {
        return "halted";
    }
    let running = board
        .newest(&proclaim_runner::running_type(&view.name))
        .map(|m| m.value.truthy())
        .unwrap_or(view.start);
    match (running, view.control.as_deref().and_then(Command::parse)) {
        (true, _) if view.finished => "finished",
        (true, _) => "running",
        (false, Some(Command::Suspend)) => "suspended",
        (false, _) => "dormant",
    }
}

fn push_bounded<T>(queue: &mut VecDeque<T>, item: T) {
    if queue.len() == RECENT {
        queue.pop_front();
    }
    queue.push_back(item);
}

fn micros(d: Duration) -> u64 {
    u64::try_from(d.as_micros()).unwrap_or(u64::MAX)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagram::{node, ChartState};
    use proclaim_board::{LocalBoard, Transport};

    fn chart(name: &str, start: bool) -> Chart {
        Chart {
            name: name.into(),
            start,
            initial: 0,
            states: ["A", "B"]
                .iter()
                .enumerate()
                .map(|(i, n)| ChartState {
                    id: i as i64,
                    name: n.to_string(),
                    node: node(i as i64),
                    also: Vec::new(),
                })
                .collect(),
            transitions: Vec::new(),
            svg: String::new(),
            drawn_by: "built-in",
        }
    }

    fn answered(atom: &str, value: bool, by: Answerer, ms: u64) -> Event {
        Event::Answered {
            round: 0,
            machine: "M".into(),
            atom: atom.into(),
            value,
            by,
            at: Duration::from_millis(ms),
        }
    }

    #[test]
    fn answers_are_one_row_per_label_and_undecided_ones_are_marked() {
        let mut picture = Picture::new(&[chart("M", true)]);
        let oven = || Answerer::Expert("oven".into());
        picture.observe(&answered("cook", false, oven(), 1));
        picture.observe(&answered("cook", false, oven(), 2));
        picture.observe(&answered("ready", false, Answerer::TimedOut, 3));
        picture.observe(&answered("cook", true, oven(), 4));
        picture.observe(&answered("t0", false, oven(), 5));
        let board = LocalBoard::new();
        board.post("oven", &undecided_type("t0"), true.into());
        let frame = picture.frame(&board.snapshot());
        let rows: Vec<(&str, bool, &str, u64, u64, bool)> = frame
            .answers
            .iter()
            .map(|a| {
                let v = a.view;
                (
                    v.atom.as_str(),
                    v.value,
                    v.how,
                    v.asked,
                    v.changed_us,
                    a.undecided,
                )
            })
            .collect();
        assert_eq!(
            rows,
            [
                ("cook", true, "expert", 3, 4000, false),
                ("ready", false, "timed_out", 1, 3000, false),
                ("t0", false, "expert", 1, 5000, true),
            ]
        );
        // The repeated answer is not listed again.
        assert_eq!(frame.events.len(), 4);
    }

    #[test]
    fn a_machine_shows_where_it_is_and_whether_it_runs() {
        let mut picture = Picture::new(&[chart("M", true), chart("Sub", false)]);
        let board = LocalBoard::new();
        let mode = |p: &Picture, b: &LocalBoard| -> Vec<(Option<String>, &'static str)> {
            p.frame(&b.snapshot())
                .machines
                .iter()
                .map(|m| (m.view.state_name.clone(), m.mode))
                .collect()
        };
        assert_eq!(
            mode(&picture, &board),
            [(Some("A".into()), "running"), (Some("A".into()), "dormant")]
        );
        picture.observe(&Event::Fired {
            round: 0,
            machine: "M".into(),
            from: 0,
            to: 1,
            label: "go".into(),
            at: Duration::ZERO,
        });
        board.post("Sub", "SubIsRunning", true.into());
        picture.observe(&Event::Control {
            round: 0,
            machine: "Sub".into(),
            command: "suspend".into(),
            at: Duration::ZERO,
        });
        board.post("Sub", "SubIsRunning", false.into());
        assert_eq!(
            mode(&picture, &board),
            [
                (Some("B".into()), "running"),
                (Some("A".into()), "suspended")
            ]
        );
        picture.observe(&Event::Halted {
            round: 0,
            machine: "M".into(),
            reason: "no answer".into(),
            at: Duration::ZERO,
        });
        assert_eq!(mode(&picture, &board)[0].1, "halted");
    }

    /// A suppressed posting is listed with the events (the page strikes it through), and the
    /// board says which layer holds a suppressed type.
    #[test]
    fn a_suppressed_posting_is_listed_and_the_holder_shows_its_priority() {
        let mut picture = Picture::new(&[chart("Walk", true)]);
        let suppressed = Event::Suppressed {
            round: 3,
            machine: "Walk".into(),
            ty: "walk".into(),
            content: "slow".into(),
            priority: 0,
            by: "Reflex".into(),
            by_priority: 2,
            until: Duration::from_millis(3000),
            at: Duration::from_millis(2500),
        };
        picture.observe(&suppressed);
        let board = LocalBoard::new();
        board.post_ranked("Reflex", "walk", "back".into(), 2);
        board.post("Walk", "kick", "right".into());
        let frame = picture.frame(&board.snapshot());
        assert_eq!(frame.events.back(), Some(&suppressed));
        let json = serde_json::to_value(&frame).unwrap();
        let listed = &json["events"][0];
        assert_eq!(
            (&listed["event"], &listed["by"], &listed["until_us"]),
            (&"suppressed".into(), &"Reflex".into(), &3_000_000.into())
        );
        let by: Vec<(&str, &str)> = frame
            .board
            .iter()
            .map(|r| (r.ty.as_str(), r.by.as_str()))
            .collect();
        assert_eq!(by, [("kick", "Walk"), ("walk", "Reflex @2")]);
    }
}
