//! The activity language at run time: machines that talk through variables (gufsm's scoping:
//! own, extern, global), computed postings, `for` loops, labels over variables decided with no
//! query, and gufsm's sub-machine control. Each case is machines (native text) plus what the
//! outside world posts, and the exact events expected; all on a paused clock.

use proclaim_board::{Value, Whiteboard};
use proclaim_fsm::{parse_machine, Machine};
use proclaim_runner::{Event, Hosts, MachineRunner, RunOptions, Shared};
use std::time::Duration;

fn machine(text: &str) -> Machine {
    let imported = parse_machine("m.machine", text);
    assert!(
        imported.diagnostics.is_empty(),
        "{:?}",
        imported.diagnostics
    );
    imported.machines.into_iter().next().unwrap()
}

/// Runs `machines` (the first `running` of them from the start, the rest dormant) sharing
/// their variables, while `world` posts `(when, type, value)`; returns every event but the
/// answers as `ms machine what`, in time order, and the board.
async fn run(
    machines: &[&str],
    running: usize,
    world: &[(u64, &str, Value)],
    limit: Duration,
) -> (Vec<String>, Whiteboard) {
    let machines: Vec<Machine> = machines.iter().map(|m| machine(m)).collect();
    let shared = Shared::for_machines(&machines);
    let board = Whiteboard::local();
    let (tx, mut events) = tokio::sync::mpsc::unbounded_channel();
    let epoch = tokio::time::Instant::now();
    for (i, m) in machines.into_iter().enumerate() {
        let mut runner = MachineRunner::new(
            m,
            Hosts::default(),
            RunOptions {
                start_running: i < running,
                shared: Some(shared.clone()),
                epoch: Some(epoch),
                ..RunOptions::default()
            },
        );
        runner.events_into(tx.clone());
        tokio::spawn(runner.run(board.clone()));
    }
    for (at, ty, value) in world {
        tokio::time::sleep_until(epoch + Duration::from_millis(*at)).await;
        board.post("world", ty, value.clone());
    }
    tokio::time::sleep_until(epoch + limit).await;
    let lines = std::iter::from_fn(|| events.try_recv().ok())
        .filter_map(|e| {
            let at = e.at().map_or(0, |d| d.as_millis());
            let what = match &e {
                Event::Entered { state, .. } => format!("enter {state}"),
                Event::Posted { ty, content, .. } => format!("post {ty}: {content}"),
                Event::Control { command, .. } => format!("control {command}"),
                Event::Finished { state, .. } => format!("finished in {state}"),
                Event::Printed { text, .. } => format!("print {text}"),
                Event::Warned { message, .. } => format!("warning: {message}"),
                Event::Answered { atom, .. } => format!("asked {atom}"),
                _ => return None,
            };
            Some(format!("{at}ms {} {what}", e.machine()))
        })
        .collect();
    (lines, board)
}

#[tokio::test(start_paused = true)]
async fn machines_talk_through_globals_and_keep_their_own_variables() {
    // The industrial-press pattern: one machine sets a variable, another's label reads it.
    let counter = "machine Counter
        state Count {
            entry {
                int n;
                n = n + 1;
                count = count + 10;
            }
            when timeout(1000000) && n < 3 -> Count
        }";
    let watcher = "machine Watcher
        state Wait {
            entry { int n = 7; }
            when count >= 30 -> Seen
        }
        state Seen {
            entry {
                post(\"Seen\", count);
                post(\"Own\", n);
                print_state_name();
            }
        }";
    let (trace, board) = run(&[counter, watcher], 2, &[], Duration::from_secs(5)).await;
    assert_eq!(
        trace,
        [
            "0ms Counter enter Count",
            "0ms Watcher enter Wait",
            "1000ms Counter enter Count",
            "2000ms Counter enter Count",
            "2000ms Watcher enter Seen",
            "2000ms Watcher post Seen: 30",
            "2000ms Watcher post Own: 7",
            "2000ms Watcher print Seen",
            "2000ms Watcher finished in Seen",
        ],
        "no `asked` line: every label here is over variables, so no expert is queried"
    );
    assert_eq!(board.latest("Own").unwrap().value, Value::Int(7));
    assert_eq!(board.stats().queries, 0);
}

#[tokio::test(start_paused = true)]
async fn an_extern_reads_the_whiteboard_and_assigning_it_posts() {
    let kicker = "machine Kicker
        state Approach {
            entry { extern ballDistance; extern kickStrength; }
            when ballDistance > 0 && ballDistance < 20 -> Kick
        }
        state Kick {
            entry { kickStrength = 100 - ballDistance * 2; }
        }";
    let (trace, board) = run(
        &[kicker],
        1,
        &[
            (500, "ballDistance", Value::Int(45)),
            (1000, "ballDistance", Value::Float(12.5)),
        ],
        Duration::from_secs(2),
    )
    .await;
    assert_eq!(
        trace,
        [
            "0ms Kicker enter Approach",
            "1000ms Kicker enter Kick",
            "1000ms Kicker post kickStrength: 75",
            "1000ms Kicker finished in Kick",
        ]
    );
    assert_eq!(
        board.latest("kickStrength").unwrap().value,
        Value::Float(75.0)
    );
}

#[tokio::test(start_paused = true)]
async fn computed_postings_lists_and_loops() {
    let beeper = "machine Beeper
        state Beep {
            entry {
                for (i = 0; i < 3; i = i + 1) {
                    postv(\"Tone\", i, i * i, 0.5);
                }
                post(\"Say\", \"\", \"three beeps\");
                say(\"done \" + i);
                post_int(\"Rounded\", 7 / 2.0);
                suspend(\"Other\");
            }
        }";
    let (trace, board) = run(&[beeper], 1, &[], Duration::from_millis(10)).await;
    assert_eq!(
        trace,
        [
            "0ms Beeper enter Beep",
            "0ms Beeper post Tone: 0 0 0.5",
            "0ms Beeper post Tone: 1 1 0.5",
            "0ms Beeper post Tone: 2 4 0.5",
            "0ms Beeper post Say: three beeps",
            "0ms Beeper post Say: done 3",
            "0ms Beeper post Rounded: 3",
            "0ms Beeper post Other: suspend",
            "0ms Beeper finished in Beep",
        ]
    );
    assert_eq!(
        board.latest("Tone").unwrap().value,
        Value::List(vec![Value::Int(2), Value::Int(4), Value::Float(0.5)])
    );
}

#[tokio::test(start_paused = true)]
async fn a_runaway_loop_is_stopped_with_a_warning() {
    let spinner = "machine Spinner
        state Spin {
            entry { for (;;) { x = x + 1; } post(\"X\", x); }
        }";
    let (trace, _) = run(&[spinner], 1, &[], Duration::from_millis(10)).await;
    assert_eq!(
        trace,
        [
            "0ms Spinner enter Spin",
            "0ms Spinner warning: a `for` loop in state Spin stopped after 100000 rounds",
            "0ms Spinner post X: 100000",
            "0ms Spinner finished in Spin",
        ]
    );
}

#[tokio::test(start_paused = true)]
async fn sub_machines_are_gufsm_suspensible_machines() {
    // The paper's AGameController posts `SMPlayer: On` on every ring: it must not restart a
    // running player. `suspend` parks the player; `resume` enters its state again.
    let coach = "machine Coach
        state Play {
            entry {
                Player: On
            }
            internal {
                Player: On
            }
            when timeout(2500000) -> Pause
        }
        state Pause {
            entry {
                Player: suspend
            }
            when timeout(1000000) -> Back
        }
        state Back {
            entry {
                Player: resume
            }
        }";
    let player = "machine Player
        state Warm {
            entry { warmups = warmups + 1; }
            when timeout(2000000) -> Go
        }
        state Go {
            entry { goes = goes + 1; }
        }";
    let (trace, _) = run(&[coach, player], 1, &[], Duration::from_secs(6)).await;
    let player_lines: Vec<&str> = trace
        .iter()
        .map(String::as_str)
        .filter(|l| l.contains(" Player enter") || l.contains("Player control"))
        .filter(|l| !l.contains("control On") || l.starts_with("0ms"))
        .collect();
    assert_eq!(
        player_lines,
        [
            "0ms Player control On",
            "0ms Player enter Warm",
            // On after On: nothing. Warm runs its full two seconds.
            "2000ms Player enter Go",
            "2500ms Player control suspend",
            "3500ms Player control resume",
            "3500ms Player enter Go",
        ],
        "{trace:#?}"
    );
}
