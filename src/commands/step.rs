//! `proclaim run --step`: one ring at a time at a prompt, showing where every machine is (the
//! monitor's `Picture`, folded from the run's events) and what the whiteboard holds (a
//! snapshot).

use proclaim_behaviour::{Behaviour, Running, TraceView};
use proclaim_board::{Value, Whiteboard, QUERY_TYPE};
use proclaim_monitor::Picture;
use proclaim_runner::{running_type, Stepper};
use std::io::Write;
use std::time::Duration;
use tokio::io::AsyncBufReadExt;

const STEP_HELP: &str = "Enter: one ring of every running machine · ATOM=true|false: post an answer (labels no expert answers read it) · post TYPE VALUE · q: quit";

/// What one line at the prompt asks for.
enum Typed<'l> {
    Ring,
    Quit,
    Help,
    Post { ty: &'l str, value: &'l str },
    Unknown,
}

fn read_line(line: &str) -> Typed<'_> {
    let command = line.trim();
    match command {
        "" | "n" | "next" => Typed::Ring,
        "q" | "quit" | "exit" => Typed::Quit,
        "?" | "help" => Typed::Help,
        _ => {
            let posting = command
                .strip_prefix("post ")
                .and_then(|rest| rest.trim().split_once(char::is_whitespace))
                .or_else(|| command.split_once('='));
            match posting {
                Some((ty, value)) if !ty.trim().is_empty() => Typed::Post {
                    ty: ty.trim(),
                    value: value.trim(),
                },
                _ => Typed::Unknown,
            }
        }
    }
}

/// Runs the prompt until the behaviour is over, the input ends or the person quits; why.
pub async fn prompt(
    behaviour: &Behaviour,
    board: &Whiteboard,
    running: &mut Running,
    stepper: &Stepper,
    view: &mut TraceView,
) -> String {
    let mut picture =
        Picture::of_machines(behaviour.machines.iter().map(|m| (&m.machine, m.start)));
    let mut lines = tokio::io::BufReader::new(tokio::io::stdin()).lines();
    let limit = behaviour.answer_timeout * 4 + Duration::from_secs(1);
    wait_for_every_machine_to_say_whether_it_runs(behaviour, board).await;
    println!("{STEP_HELP}");
    let mut step = 0;
    loop {
        let over = show(board, running, view, &mut picture);
        if over {
            return "every machine that started is in a final state or halted".into();
        }
        print!("step {}> ", step + 1);
        let _ = std::io::stdout().flush();
        let Ok(Some(line)) = lines.next_line().await else {
            return "the input ended".into();
        };
        match read_line(&line) {
            Typed::Ring => {
                step = stepper.advance();
                ring(behaviour, board, stepper, step, limit).await;
            }
            Typed::Quit => return "quit at the prompt".into(),
            Typed::Help => println!("{STEP_HELP}"),
            Typed::Post { ty, value } => {
                board.post("you", ty, Value::parse(value));
            }
            Typed::Unknown => println!("  ? {STEP_HELP}"),
        }
    }
}

/// Bounded: a machine that never says is shown as starting.
async fn wait_for_every_machine_to_say_whether_it_runs(behaviour: &Behaviour, board: &Whiteboard) {
    for _ in 0..200 {
        if behaviour
            .machines
            .iter()
            .all(|m| board.truth(&running_type(&m.machine.name)).is_some())
        {
            return;
        }
        tokio::time::sleep(Duration::from_millis(5)).await;
    }
}

/// Prints what happened since the last prompt, then every machine and the whiteboard; whether
/// the behaviour is over.
fn show(
    board: &Whiteboard,
    running: &mut Running,
    view: &mut TraceView,
    picture: &mut Picture,
) -> bool {
    let mut over = false;
    while let Ok(event) = running.events.try_recv() {
        if let Some(line) = view.line(&event) {
            println!("{line}");
        }
        picture.observe(&event);
        over |= running.observe(&event);
    }
    let snapshot = board.snapshot();
    for (name, state) in picture.states() {
        let mode = match snapshot
            .newest(&running_type(name))
            .map(|m| m.value.truthy())
        {
            Some(true) => "running",
            Some(false) => "dormant",
            None => "starting",
        };
        println!("  {name}: {} ({mode})", state.unwrap_or("-"));
    }
    let board_line: Vec<String> = snapshot
        .rows()
        .iter()
        .filter(|row| row.ty != QUERY_TYPE)
        .map(|row| format!("{}={}", row.ty, row.newest.value))
        .collect();
    println!("  whiteboard: {}", board_line.join(", "));
    over
}

/// Lets every machine that runs (or is about to: a machine whose task has not begun has not
/// said) take ring `step`, and says which are still in theirs after `limit`.
async fn ring(
    behaviour: &Behaviour,
    board: &Whiteboard,
    stepper: &Stepper,
    step: u64,
    limit: Duration,
) {
    let active: Vec<String> = behaviour
        .machines
        .iter()
        .filter(|m| {
            board
                .truth(&running_type(&m.machine.name))
                .unwrap_or(m.start)
        })
        .map(|m| m.machine.name.clone())
        .collect();
    let busy = stepper.settled(&active, step, limit).await;
    if !busy.is_empty() {
        println!(
            "  still in their ring (waiting on an expert?): {}",
            busy.join(", ")
        );
    }
}
