//! Machines running on the whiteboard: the seed paper's GameController (its real T/A pair)
//! played through a game by the impersonator, sub-machine control, `timeout()` and comparison
//! labels. All on a paused clock, so the traces are deterministic.

use proclaim_board::Whiteboard;
use proclaim_experts::{parse_script, Impersonator};
use proclaim_fsm::{import_ta, Machine};
use proclaim_runner::{Event, Hosts, MachineRunner, RunOptions};
use std::time::Duration;

fn ta(name: &str, t: &str, a: &str) -> Machine {
    let imported = import_ta(name, "T", t, "A", a);
    assert!(!imported.has_errors(), "{:?}", imported.diagnostics);
    imported.machines.into_iter().next().unwrap()
}

/// The states entered, in order, until `stop` is entered or `limit` passes.
async fn entered(
    events: &mut tokio::sync::mpsc::UnboundedReceiver<Event>,
    stop: &str,
    limit: Duration,
) -> Vec<(String, u64)> {
    let mut seen = Vec::new();
    let deadline = tokio::time::Instant::now() + limit;
    while let Ok(Some(event)) = tokio::time::timeout_at(deadline, events.recv()).await {
        if let Event::Entered { state, at, .. } = event {
            seen.push((state.clone(), at.as_secs()));
            if state == stop {
                break;
            }
        }
    }
    seen
}

#[tokio::test(start_paused = true)]
async fn the_seed_papers_game_controller_plays_a_game() {
    let Some(dir) = corpus_dir() else {
        eprintln!("skipped: ../shared/corpus is absent");
        return;
    };
    let read = |f: &str| std::fs::read_to_string(dir.join("mipal/testfiles").join(f)).unwrap();
    let machine = ta(
        "GameController",
        &read("TGameController.txt"),
        &read("AGameController.txt"),
    );
    let board = Whiteboard::local();
    let mut runner = MachineRunner::new(machine, Hosts::default(), RunOptions::default());
    let atoms = runner.declaration().waits_on;
    let mut events = runner.events();
    let script = parse_script(
        "at 1s readyReceived = true\n\
         at 2s readyReceived = false\nat 2s setReceived = true\n\
         at 3s setReceived = false\nat 3s playingReceived = true\n\
         at 4s playingReceived = false\nat 4s penaltyReceived = true\n\
         at 5s penaltyReceived = false\nat 5s playingReceived = true\n\
         at 25s finishedReceived = true\n",
    )
    .unwrap();
    let imp = Impersonator::new("testcdl", atoms.clone(), script);
    for atom in &atoms {
        imp.set(atom, false);
    }
    tokio::spawn(imp.run(board.clone()));
    tokio::task::yield_now().await;
    tokio::spawn(runner.run(board.clone()));
    let trace = entered(&mut events, "FINISHED", Duration::from_secs(120)).await;
    let states: Vec<&str> = trace.iter().map(|(s, _)| s.as_str()).collect();
    assert_eq!(
        states,
        [
            "INITIAL",
            "READY",
            "SET",
            "PLAYING",
            "PENALIZED",
            "PLAYING",
            "FINISHED"
        ],
        "{trace:?}"
    );
    // Leaving PENALIZED runs its OnExit, which walks for 14 s (C++: msleep(14000)).
    assert!(trace[5].1 >= 19, "{trace:?}");
    assert_eq!(
        board.latest("Say").unwrap().value.to_string(),
        "\"Game over\"",
        "FINISHED's OnEntry ran"
    );
    assert_eq!(
        board.latest("LEDS").unwrap().value.to_string(),
        "\"Face Green\"",
        "to its last posting"
    );
    assert_eq!(
        board.latest("SMPlayer").unwrap().value.to_string(),
        "\"Off\"",
        "PLAYING's OnExit stopped the player"
    );
}

#[tokio::test(start_paused = true)]
async fn sub_machines_are_started_and_stopped_by_messages() {
    let parent = ta(
        "Parent",
        "0\ttimeout(2000000)\t1\n",
        "1\tDone|OnEntry Child: Off;/ OnExit /\n0\tStart|OnEntry Child: On;/ OnExit /\n",
    );
    let child = ta(
        "Child",
        "",
        "0\tTick|OnEntry /OnExit / tick: 1; C++: msleep(100);\n",
    );
    let board = Whiteboard::local();
    let mut child_runner = MachineRunner::new(
        child,
        Hosts::default(),
        RunOptions {
            start_running: false,
            ..Default::default()
        },
    );
    let mut child_events = child_runner.events();
    tokio::spawn(child_runner.run(board.clone()));
    tokio::task::yield_now().await;
    assert_eq!(
        board.truth("ChildIsRunning"),
        Some(false),
        "dormant until told"
    );
    let mut parent_runner = MachineRunner::new(parent, Hosts::default(), RunOptions::default());
    let mut parent_events = parent_runner.events();
    tokio::spawn(parent_runner.run(board.clone()));
    tokio::time::sleep(Duration::from_secs(1)).await;
    assert_eq!(board.truth("ChildIsRunning"), Some(true));
    assert_eq!(board.truth("tick"), Some(true), "the child's Internal runs");
    let trace = entered(&mut parent_events, "Done", Duration::from_secs(5)).await;
    assert_eq!(
        trace,
        [("Start".to_string(), 0), ("Done".to_string(), 2)],
        "timeout(2000000) is two seconds in the state"
    );
    tokio::time::sleep(Duration::from_millis(500)).await;
    assert_eq!(board.truth("ChildIsRunning"), Some(false));
    let mut commands = Vec::new();
    while let Ok(e) = child_events.try_recv() {
        if let Event::Control { command, .. } = e {
            commands.push(command);
        }
    }
    assert_eq!(commands, ["On", "Off"]);
}

#[tokio::test(start_paused = true)]
async fn a_comparison_label_wakes_on_the_value_it_reads() {
    let m = ta(
        "Watcher",
        "0\tdistance<300 && ~stop\t1\n",
        "1\tClose|OnEntry Say: close;/\n0\tFar|OnEntry /\n",
    );
    let board = Whiteboard::local();
    let mut hosts = Hosts::default();
    hosts.register("unused", |_| {});
    let mut runner = MachineRunner::new(
        m,
        hosts,
        RunOptions {
            ring_period: Duration::from_secs(60),
            answer_timeout: Duration::from_millis(50),
            ..Default::default()
        },
    );
    let mut events = runner.events();
    let imp = Impersonator::new("testcdl", ["stop"], Default::default());
    imp.set("stop", false);
    tokio::spawn(imp.run(board.clone()));
    tokio::task::yield_now().await;
    tokio::spawn(runner.run(board.clone()));
    tokio::time::sleep(Duration::from_secs(1)).await;
    board.post("vision", "distance", 500i64);
    tokio::time::sleep(Duration::from_secs(1)).await;
    board.post("vision", "distance", 250i64);
    let trace = entered(&mut events, "Close", Duration::from_secs(5)).await;
    // Woken by the posting of `distance`, not by the 60 s ring period.
    assert_eq!(trace, [("Far".to_string(), 0), ("Close".to_string(), 2)]);
    assert_eq!(board.latest("Say").unwrap().value.to_string(), "\"close\"");
}

#[tokio::test(start_paused = true)]
async fn suspend_keeps_the_state_resume_enters_it_again_and_unknown_hosts_are_reported() {
    let m = ta(
        "Stepper",
        "0\ttimeout(1000000)\t1\n1\ttimeout(1000000)\t2\n",
        "2\tThird|OnEntry /\n1\tSecond|OnEntry C++: blink(3);/\n0\tFirst|OnEntry /\n",
    );
    let board = Whiteboard::local();
    let mut hosts = Hosts::default();
    let calls = std::sync::Arc::new(std::sync::Mutex::new(Vec::new()));
    let seen = calls.clone();
    hosts.register("blink", move |arg| {
        seen.lock().unwrap().push(format!("{arg:?}"))
    });
    let mut runner = MachineRunner::new(m.clone(), hosts, RunOptions::default());
    let mut events = runner.events();
    tokio::spawn(runner.run(board.clone()));
    tokio::time::sleep(Duration::from_millis(1500)).await; // in Second since 1 s
    board.post("ops", "Stepper", "suspend");
    tokio::time::sleep(Duration::from_secs(5)).await;
    assert_eq!(board.truth("StepperIsRunning"), Some(false));
    board.post("ops", "Stepper", "resume");
    let trace = entered(&mut events, "Third", Duration::from_secs(5)).await;
    let states: Vec<&str> = trace.iter().map(|(s, _)| s.as_str()).collect();
    assert_eq!(
        states,
        ["First", "Second", "Second", "Third"],
        "resumed by entering Second again (gufsm's SuspensibleMachine), not restarted"
    );
    assert_eq!(
        *calls.lock().unwrap(),
        ["Some(Int(3))", "Some(Int(3))"],
        "registered host function called with its argument, on each entry"
    );
    // The same machine without the host function: reported once, as an event.
    let mut runner = MachineRunner::new(m, Hosts::default(), RunOptions::default());
    let mut events = runner.events();
    let board = Whiteboard::local();
    tokio::spawn(runner.run(board.clone()));
    tokio::time::sleep(Duration::from_secs(3)).await;
    let unknown: Vec<String> = std::iter::from_fn(|| events.try_recv().ok())
        .filter_map(|e| match e {
            Event::UnknownFunction { function, .. } => Some(function),
            _ => None,
        })
        .collect();
    assert_eq!(unknown, ["blink"]);
}

fn native(text: &str) -> Machine {
    let imported = proclaim_fsm::parse_machine("m.machine", text);
    assert!(
        imported.diagnostics.is_empty(),
        "{:?}",
        imported.diagnostics
    );
    imported.machines.into_iter().next().unwrap()
}

/// Every event but the answers, as `at machine what`, compact for exact comparison.
fn compact(events: &mut tokio::sync::mpsc::UnboundedReceiver<Event>) -> Vec<String> {
    std::iter::from_fn(|| events.try_recv().ok())
        .filter_map(|e| {
            let at = e.at().map_or(0, |d| d.as_millis());
            let what = match e {
                Event::Entered { state, .. } => format!("enter {state}"),
                Event::Control { command, .. } => format!("control {command}"),
                Event::Reloaded { state, .. } => format!("reloaded in {state}"),
                Event::ReloadFailed { error, .. } => format!("reload failed: {error}"),
                Event::Halted { reason, .. } => format!("halted: {reason}"),
                Event::Posted { ty, content, .. } => format!("post {ty}: {content}"),
                _ => return None,
            };
            Some(format!("{at}ms {what}"))
        })
        .collect()
}

#[tokio::test(start_paused = true)]
async fn reload_and_reread_replace_a_running_machine_and_a_bad_file_changes_nothing() {
    let v1 = "machine M\nstate A {\n when timeout(1000000) -> B\n}\nstate B {\n entry {\n  Say: v1\n }\n}\n";
    let v2 = "machine M\nstate Z {\n}\nstate B {\n entry {\n  Say: v2\n }\n when timeout(1000000) -> Z\n}\n";
    let file: std::sync::Arc<std::sync::Mutex<String>> =
        std::sync::Arc::new(std::sync::Mutex::new(v1.to_string()));
    let source = file.clone();
    let loader: proclaim_runner::Loader = std::sync::Arc::new(move || {
        let imported = proclaim_fsm::parse_machine("m.machine", &source.lock().unwrap());
        match imported.machines.into_iter().next() {
            Some(m) if imported.diagnostics.is_empty() => Ok(m),
            _ => Err(imported.diagnostics),
        }
    });
    let board = Whiteboard::local();
    let mut runner =
        MachineRunner::new(native(v1), Hosts::default(), RunOptions::default()).with_loader(loader);
    let mut events = runner.events();
    tokio::spawn(runner.run(board.clone()));
    tokio::time::sleep(Duration::from_millis(1500)).await; // in B
    *file.lock().unwrap() = "machine M\nstate A {\n when -> B\n}\n".to_string();
    board.post("ops", "M", "reread");
    tokio::time::sleep(Duration::from_millis(500)).await;
    *file.lock().unwrap() = v2.to_string();
    board.post("ops", "M", "reread");
    tokio::time::sleep(Duration::from_millis(1500)).await;
    board.post("ops", "M", "reload");
    tokio::time::sleep(Duration::from_millis(100)).await;
    assert_eq!(
        compact(&mut events),
        [
            "0ms enter A",
            "1000ms enter B",
            "1000ms post Say: v1",
            "1500ms control reread",
            "1500ms reload failed: m.machine:3: error: a transition needs a label; write `when TRUE -> …` for one that always fires",
            "2000ms control reread",
            "2000ms reloaded in B",
            // B kept its time in state: its new `timeout(1000000)` was already due.
            "2000ms enter Z",
            "3500ms control reload",
            "3500ms reloaded in Z",
            "3500ms enter Z",
        ]
    );
}

/// A composite's time counts from its entry, and a reread that keeps the machine's state keeps
/// that entry (by the composite's path): the play ends 2 s after it began, whatever the turns
/// inside it and the reread at 1.2 s did.
#[tokio::test(start_paused = true)]
async fn a_reread_keeps_when_a_composite_was_entered() {
    let version = |said: &str| {
        format!(
            "machine M\ninitial PLAY\nstate PLAY {{\n when after(2s) -> OUT\n \
             state A {{ when after_ms(300) -> B }}\n state B {{ when after_ms(300) -> A }}\n}}\n\
             state OUT {{\n entry {{\n  Say: {said}\n }}\n}}\n"
        )
    };
    let file = std::sync::Arc::new(std::sync::Mutex::new(version("v1")));
    let source = file.clone();
    let loader: proclaim_runner::Loader = std::sync::Arc::new(move || {
        let imported = proclaim_fsm::parse_machine("m.machine", &source.lock().unwrap());
        match imported.machines.into_iter().next() {
            Some(m) if imported.diagnostics.is_empty() => Ok(m),
            _ => Err(imported.diagnostics),
        }
    });
    let board = Whiteboard::local();
    let mut runner = MachineRunner::new(
        native(&version("v1")),
        Hosts::default(),
        RunOptions::default(),
    )
    .with_loader(loader);
    let mut events = runner.events();
    tokio::spawn(runner.run(board.clone()));
    tokio::time::sleep(Duration::from_millis(1200)).await;
    *file.lock().unwrap() = version("v2");
    board.post("ops", "M", "reread");
    tokio::time::sleep(Duration::from_millis(1500)).await;
    let got = compact(&mut events);
    let out: Vec<&String> = got
        .iter()
        .filter(|e| e.contains("OUT") || e.contains("Say"))
        .collect();
    assert_eq!(out, ["2000ms enter OUT", "2000ms post Say: v2"], "{got:#?}");
    assert!(
        got.contains(&"1200ms reloaded in PLAY.B".to_string()),
        "{got:#?}"
    );
}

#[tokio::test(start_paused = true)]
async fn halt_on_timeout_stops_the_machine_and_says_why() {
    let board = Whiteboard::local();
    // An expert that claims `ready` and never answers.
    board.register(proclaim_board::ModuleDecl::new("mute").answers(["ready"]));
    let mut runner = MachineRunner::new(
        native("machine M\nstate A {\n when ready -> B\n}\nstate B {\n}\n"),
        Hosts::default(),
        RunOptions {
            halt_on_timeout: true,
            ..Default::default()
        },
    );
    let mut events = runner.events();
    let task = tokio::spawn(runner.run(board.clone()));
    tokio::time::sleep(Duration::from_secs(3)).await;
    assert!(task.is_finished());
    assert_eq!(
        compact(&mut events),
        [
            "0ms enter A",
            "1000ms halted: no expert answered `ready` within 1s (in state A)"
        ]
    );
    assert_eq!(board.truth("MIsRunning"), Some(false));
}

/// The shared corpus (`../shared/corpus` from the repository's root), when present beside it.
fn corpus_dir() -> Option<std::path::PathBuf> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus");
    dir.is_dir().then_some(dir)
}

/// A posting due just as a round is (on the ring period's beat, of a type no label reads) is on
/// the board before that round's ringlet begins, whether the poster's timer or the schedule's
/// was set first.
#[tokio::test(start_paused = true)]
async fn a_posting_due_at_a_rounds_moment_is_on_the_board_before_that_round_begins() {
    for (poster_first, timer_set_at) in [(true, 0), (false, 0), (true, 250), (false, 250)] {
        let board = Whiteboard::local();
        let machine =
            native("machine M\ninitial A\nstate A {\n    when timeout(5s) -> B\n}\nstate B {\n}\n");
        let runner = MachineRunner::new(machine, Hosts::default(), RunOptions::default());
        let mut rounds = proclaim_runner::Rounds::new(vec![runner]);
        let mut ringlets = rounds.ringlets();
        let outside = board.clone();
        let start = tokio::time::Instant::now();
        let poster = async move {
            tokio::time::sleep_until(start + Duration::from_millis(timer_set_at)).await;
            tokio::time::sleep_until(start + Duration::from_millis(300)).await;
            outside.post("outside", "crowd", true);
        };
        if poster_first {
            tokio::spawn(poster);
            tokio::spawn(rounds.run(board.clone()));
        } else {
            tokio::spawn(rounds.run(board.clone()));
            tokio::spawn(poster);
        }
        tokio::time::sleep(Duration::from_secs(1)).await;
        let posted = board.snapshot().newest("crowd").map(|m| m.seq).unwrap();
        let at_its_moment = std::iter::from_fn(|| ringlets.try_recv().ok())
            .find(|r| r.at == Duration::from_millis(300))
            .expect("a round at 300 ms");
        assert!(
            at_its_moment.seq >= posted,
            "poster first: {poster_first}, its timer set at {timer_set_at} ms: the ringlet at 300 ms began at {} before the posting {posted}",
            at_its_moment.seq
        );
    }
}

/// A run stopped inside a ringlet (Ctrl-C, the page's Stop) drops the schedule there: the
/// ringlet under way is recorded all the same, so a recording holding that round's events
/// holds the round, and its replay plays it (it once ended a round short).
#[tokio::test(start_paused = true)]
async fn a_ringlet_the_run_stops_inside_is_recorded() {
    let machine = native(
        "machine M\ninitial A\nstate A {\n    when TRUE -> B\n}\nstate B {\n    entry { msleep(10000); }\n}\n",
    );
    let mut runner = MachineRunner::new(machine, Hosts::default(), RunOptions::default());
    let mut events = runner.events();
    let mut rounds = proclaim_runner::Rounds::new(vec![runner]);
    let mut ringlets = rounds.ringlets();
    let schedule = tokio::spawn(rounds.run(Whiteboard::local()));
    // Round 2's ringlet enters B and sleeps in its OnEntry; the run stops there.
    tokio::time::sleep(Duration::from_secs(1)).await;
    schedule.abort();
    let _ = schedule.await;
    let entered: Vec<u64> = std::iter::from_fn(|| events.try_recv().ok())
        .filter_map(|e| match e {
            Event::Entered { state, round, .. } if state == "B" => Some(round),
            _ => None,
        })
        .collect();
    assert_eq!(entered, [2]);
    let recorded: Vec<u64> = std::iter::from_fn(|| ringlets.try_recv().ok())
        .map(|r| r.round)
        .collect();
    assert_eq!(recorded, [1, 2]);
}

/// The ringlets of `machines` in one round schedule on a paused clock, watched by a task of
/// their thread until `last` holds of one (that one included) or a hundred thousand have begun;
/// `None` when the watching task got no turn within 30 s of real time (the schedule left every
/// other task none).
fn ringlets_until(
    machines: &'static [&'static str],
    last: impl Fn(&proclaim_runner::Ringlet) -> bool + Send + 'static,
) -> Option<Vec<proclaim_runner::Ringlet>> {
    let (send, receive) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let runtime = tokio::runtime::Builder::new_current_thread()
            .enable_all()
            .start_paused(true)
            .build()
            .expect("a runtime");
        runtime.block_on(async {
            let runners = machines
                .iter()
                .map(|m| MachineRunner::new(native(m), Hosts::default(), RunOptions::default()));
            let mut rounds = proclaim_runner::Rounds::new(runners.collect());
            let mut ringlets = rounds.ringlets();
            tokio::spawn(rounds.run(Whiteboard::local()));
            let mut seen = Vec::new();
            while let Some(r) = ringlets.recv().await {
                seen.push(r);
                if last(&r) || seen.len() >= 100_000 {
                    break;
                }
            }
            let _ = send.send(seen);
        });
    });
    receive.recv_timeout(Duration::from_secs(30)).ok()
}

/// A control command that changes nothing (`resume` to a machine in a final state whose last
/// ringlet read the board), posted in every ringlet of another machine, is no news: rounds keep
/// the ring period instead of following one another at one moment forever, which left the
/// clock, the trace and every other task no turn.
#[test]
fn a_command_that_changes_nothing_starts_no_round_of_its_own() {
    const DONE: &str =
        "machine Done\ninitial D\nstate D {\n    internal {\n        x = level;\n    }\n}\n";
    const NAGGER: &str = "machine Nagger\ninitial N\nstate N {\n    internal {\n        Done: resume\n    }\n    when timeout(5s) -> E\n}\nstate E {\n}\n";
    let second = Duration::from_secs(1);
    let ringlets = ringlets_until(&[DONE, NAGGER], move |r| r.at >= second)
        .expect("a second of virtual time passes: the rounds leave the clock a turn");
    // The nagger rings once a period, the finished machine once: about a dozen ringlets.
    assert!(
        ringlets.len() <= 15,
        "{} ringlets in a second: {ringlets:?}",
        ringlets.len()
    );
}

/// Two machines that keep posting values of a type the other reads are news to each other
/// round after round at one moment, none firing: the schedule still gives every other task a
/// turn (the trace's writer, an expert, a stop request), which it did not.
#[test]
fn machines_that_keep_telling_each_other_news_leave_other_tasks_a_turn() {
    const ZERO: &str = "machine Zero\ninitial S\nstate S {\n    internal {\n        x: 0\n    }\n    when x == 5 -> T\n}\nstate T {\n}\n";
    const ONE: &str = "machine One\ninitial S\nstate S {\n    internal {\n        x: 1\n    }\n    when x == 7 -> T\n}\nstate T {\n}\n";
    let ringlets = ringlets_until(&[ZERO, ONE], |r| r.round >= 1000)
        .expect("the test's own task gets a turn while the machines tell each other news");
    assert!(
        ringlets.iter().all(|r| r.at.is_zero()),
        "news, not time, starts these rounds"
    );
}
