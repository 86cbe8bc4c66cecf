//! The round schedule gives a behaviour one meaning: `machines/press` (gufsm's IndustrialPress
//! race, where the sensor's write must land after the controller's) ends the same way in every
//! real-time run, and its trace is the same to the byte on the virtual clock.

use proclaim_behaviour::{launch, load, Folder, LaunchOptions};
use proclaim_board::Whiteboard;
use proclaim_runner::Event;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;

fn press() -> proclaim_behaviour::Behaviour {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../machines/press");
    load("press", Arc::new(Folder::new(&dir))).expect("machines/press loads")
}

/// Runs the behaviour until every machine is in a final state (or `limit` passes); every event.
async fn run_to_the_end(behaviour: &proclaim_behaviour::Behaviour, limit: Duration) -> Vec<Event> {
    let board = Whiteboard::local();
    let mut running = launch(behaviour, &board, LaunchOptions::default())
        .await
        .expect("launches");
    let (events, _) = running.follow(limit).await;
    running.stop().await;
    events
}

/// Each machine's states, in order, as `Machine State` lines.
fn states(events: &[Event]) -> Vec<String> {
    events
        .iter()
        .filter_map(|e| match e {
            Event::Entered { machine, state, .. } => Some(format!("{machine} {state}")),
            _ => None,
        })
        .collect()
}

#[test]
fn the_press_ends_the_same_way_in_a_hundred_real_time_runs() {
    let behaviour = press();
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .unwrap();
    let first = states(&runtime.block_on(run_to_the_end(&behaviour, Duration::from_secs(10))));
    assert!(
        first.iter().any(|s| s == "Controller Done") && !first.iter().any(|s| s.contains("Stuck")),
        "the sensor's write lands after the controller's, so the press reopens: {first:?}"
    );
    for run in 1..100 {
        let again = states(&runtime.block_on(run_to_the_end(&behaviour, Duration::from_secs(10))));
        assert_eq!(again, first, "run {run} went another way");
    }
}

#[test]
fn on_the_virtual_clock_the_trace_is_the_same_to_the_byte() {
    let behaviour = press();
    let trace = || {
        let runtime = tokio::runtime::Builder::new_current_thread()
            .enable_all()
            .start_paused(true)
            .build()
            .unwrap();
        let events = runtime.block_on(run_to_the_end(&behaviour, Duration::from_secs(10)));
        events
            .iter()
            .map(|e| serde_json::to_string(e).unwrap() + "\n")
            .collect::<String>()
    };
    let first = trace();
    assert!(first.contains("\"round\":"), "every event says its round");
    for _ in 0..5 {
        assert_eq!(trace(), first);
    }
}

/// Round by round, as §3.1 says: the controller's write on entry comes first and the sensor's
/// after it in the same round; a machine's first ringlet after a posting that starts it is in
/// the next round.
#[test]
fn rounds_run_machines_in_manifest_order_one_ringlet_each() {
    let behaviour = press();
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .start_paused(true)
        .build()
        .unwrap();
    let events = runtime.block_on(run_to_the_end(&behaviour, Duration::from_secs(10)));
    let round_of = |machine: &str, state: &str, nth: usize| {
        events
            .iter()
            .filter_map(|e| match e {
                Event::Entered {
                    machine: m,
                    state: s,
                    round,
                    ..
                } if m == machine && s == state => Some(*round),
                _ => None,
            })
            .nth(nth)
            .unwrap_or_else(|| panic!("{machine} never entered {state} ({nth})"))
    };
    // Round 1: the controller enters Closing; the sensor sees the motor on and fires, so it
    // enters Clear (and writes `low = 0`) in round 2; the controller sees that in round 3.
    assert_eq!(round_of("Controller", "Closing", 0), 1);
    assert_eq!(round_of("Sensor", "Clear", 0), 2);
    assert_eq!(round_of("Controller", "Reopening", 0), 4);
    let lows: Vec<(String, String, u64)> = events
        .iter()
        .filter_map(|e| match e {
            Event::Assigned {
                machine,
                variable,
                value,
                round,
                ..
            } if variable == "low" => Some((machine.clone(), value.clone(), *round)),
            _ => None,
        })
        .take(2)
        .collect();
    assert_eq!(
        lows,
        [
            ("Controller".to_string(), "1".to_string(), 1),
            ("Sensor".to_string(), "0".to_string(), 2)
        ]
    );
}

/// The Rust test API: a behaviour stepped one round at a time, its states and variables read
/// between rounds.
#[test]
fn a_test_steps_the_press_round_by_round() {
    use proclaim_behaviour::testing::RoundByRound;
    use proclaim_board::Value;
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../machines/press");
    let mut press = RoundByRound::start(&dir, "").unwrap();
    press.round();
    assert_eq!(press.rounds(), 1);
    assert_eq!(press.state_of("Controller"), Some("Closing"));
    assert_eq!(press.state_of("Sensor"), Some("Waiting"));
    // The controller's write on entry, then the sensor's a round later.
    assert_eq!(press.variable("Controller", "low"), Some(Value::Int(1)));
    assert_eq!(press.variable("Plate", "pos"), Some(Value::Int(1)));
    press.round();
    assert_eq!(press.state_of("Sensor"), Some("Clear"));
    assert_eq!(press.variable("Controller", "low"), Some(Value::Int(0)));
    assert_eq!(
        press.variable("Controller", "waited"),
        Some(Value::Int(2)),
        "its own, counted in Internal"
    );
    press.round();
    press.round();
    assert_eq!(press.state_of("Controller"), Some("Reopening"));
    assert_eq!(press.variable("Controller", "motor"), Some(Value::Int(-1)));
}

/// A command posted in a ringlet is obeyed when that ringlet ends: the machine it stops does
/// not ring later in the round, the machine it starts rings from the next round; a machine in a
/// final state whose OnEntry has run rings no more after that ringlet.
#[test]
fn commands_take_effect_after_the_ringlet_and_final_states_stop_ringing() {
    use proclaim_behaviour::testing::RoundByRound;
    use proclaim_board::Value;
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("proclaim-rounds-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let files = [
        (
            "behaviour.toml",
            "[[machine]]\nfile = \"Boss.machine\"\n[[machine]]\nfile = \"Worker.machine\"\n[[machine]]\nfile = \"Helper.machine\"\nstart = false\n",
        ),
        (
            "Boss.machine",
            "machine Boss\nstate Go {\n  entry {\n    Worker: Off\n    Helper: On\n  }\n  when TRUE -> End\n}\nstate End {\n  internal { ends = ends + 1; }\n}\n",
        ),
        (
            "Worker.machine",
            "machine Worker\nstate W {\n  internal { worked = worked + 1; }\n  when worked > 100 -> X\n}\nstate X {\n}\n",
        ),
        (
            "Helper.machine",
            "machine Helper\nstate H {\n  entry { helped = helped + 1; }\n  when helped > 100 -> Y\n}\nstate Y {\n}\n",
        ),
    ];
    for (name, text) in files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    let mut run = RoundByRound::start(&dir, "").unwrap();
    run.round();
    assert_eq!(run.state_of("Boss"), Some("Go"));
    assert_eq!(
        run.state_of("Worker"),
        None,
        "stopped before its turn in round 1"
    );
    assert_eq!(
        run.state_of("Helper"),
        None,
        "started in round 1, rings from round 2"
    );
    assert_eq!(run.variable("Worker", "worked"), Some(Value::Int(0)));
    run.round();
    assert_eq!(run.state_of("Boss"), Some("End"));
    assert_eq!(run.state_of("Helper"), Some("H"));
    for _ in 0..5 {
        run.round();
    }
    // The ringlet that enters End runs its Internal once, as any ringlet where nothing fires;
    // after that the machine's run is over.
    assert_eq!(
        run.variable("Boss", "ends"),
        Some(Value::Int(1)),
        "a final state rings no more"
    );
    assert_eq!(run.variable("Worker", "worked"), Some(Value::Int(0)));
}

/// An embedding program's function expert replaces the theory (its note says so), the machines
/// ring freely for a virtual minute in `run_for`, and the host functions are called.
#[test]
fn an_embedding_programs_expert_answers_in_place_of_the_theory_through_a_virtual_minute() {
    use proclaim_behaviour::testing::{RoundByRound, Stepping};
    use proclaim_experts::FunctionExpert;
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../machines/microwave");
    let asked = Arc::new(std::sync::atomic::AtomicUsize::new(0));
    let counted = asked.clone();
    let expert = FunctionExpert::new("oven", ["cook", "light"], move |_, _| {
        counted.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        Some(true)
    });
    let mut run = RoundByRound::start_with(
        &dir,
        Stepping {
            experts: vec![expert],
            ..Stepping::default()
        },
    )
    .unwrap();
    assert!(
        run.notes()
            .iter()
            .any(|n| n == "left out microwave: the embedding program answers cook, light"),
        "{:?}",
        run.notes()
    );
    run.round();
    assert_eq!(run.states(), [("Microwave", Some("IDLE"))]);
    run.round();
    assert_eq!(run.states(), [("Microwave", Some("COOKING"))]);
    assert!(!run.is_over());
    run.run_for(Duration::from_secs(59));
    assert_eq!(run.state_of("Microwave"), Some("COOKING"));
    run.run_for(Duration::from_secs(2));
    assert_eq!(run.state_of("Microwave"), Some("DONE"));
    assert!(run.is_over());
    assert!(asked.load(std::sync::atomic::Ordering::Relaxed) > 0);
}

/// An embedding program's expert for one label of a theory replaces exactly that label: the
/// theory keeps answering its other outputs (it once was silently left out whole, so nothing
/// it answered reached the machines).
#[test]
fn an_expert_for_one_label_leaves_the_theory_answering_the_rest() {
    use proclaim_behaviour::testing::{RoundByRound, Stepping};
    use proclaim_experts::FunctionExpert;
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../machines/microwave");
    // The light never comes on, whatever the door does; `cook` is still the theory's.
    let dark = FunctionExpert::new("lamp test", ["light"], |_, _| Some(false));
    let mut run = RoundByRound::start_with(
        &dir,
        Stepping {
            experts: vec![dark],
            ..Stepping::default()
        },
    )
    .unwrap();
    assert!(
        run.notes().iter().any(|n| n
            == "microwave answers the rest of its labels: the embedding program answers light"),
        "{:?}",
        run.notes()
    );
    // The kitchen script opens the door at 1 s (no light: the machine stays IDLE), shuts it at
    // 3 s and sets the minute at 4 s: the theory's `cook` starts the magnetron.
    run.run_for(Duration::from_millis(3500));
    assert_eq!(run.state_of("Microwave"), Some("IDLE"));
    run.run_for(Duration::from_secs(1));
    assert_eq!(run.state_of("Microwave"), Some("COOKING"));
}

#[test]
fn a_press_stepped_and_taken_up_from_a_checkpoint_reads_and_goes_on_as_it_was() {
    use proclaim_behaviour::testing::{RoundByRound, Stepping};
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../machines/press");
    let asked = Stepping {
        script: Some(String::new()),
        checkpoint_at: Some(3),
        ..Stepping::default()
    };
    let mut first = RoundByRound::start_with(&dir, asked).unwrap();
    first.round();
    first.round();
    let before: Vec<(String, Option<String>)> = first
        .states()
        .into_iter()
        .map(|(m, s)| (m.to_string(), s.map(str::to_string)))
        .collect();
    let low = first.variable("Controller", "low");
    first.round();
    let checkpoint = first.checkpoint().expect("taken at the start of round 3");
    assert_eq!(checkpoint.round, 3);
    let resumed = Stepping {
        script: Some(String::new()),
        resume: Some(checkpoint),
        ..Stepping::default()
    };
    let mut second = RoundByRound::start_with(&dir, resumed).unwrap();
    let taken_up: Vec<(String, Option<String>)> = second
        .states()
        .into_iter()
        .map(|(m, s)| (m.to_string(), s.map(str::to_string)))
        .collect();
    assert_eq!(taken_up, before, "where each machine was at the checkpoint");
    assert_eq!(second.variable("Controller", "low"), low);
    let went_on = second.round().to_vec();
    let first_round_three: Vec<Event> = first
        .events
        .iter()
        .filter(|e| e.round() == 3)
        .cloned()
        .collect();
    assert_eq!(went_on, first_round_three);
}

#[test]
fn the_microwave_taken_up_and_let_run_free_goes_on_as_it_did() {
    use proclaim_behaviour::testing::{RoundByRound, Stepping};
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../machines/microwave");
    let asked = Stepping {
        checkpoint_at: Some(6),
        ..Stepping::default()
    };
    let mut first = RoundByRound::start_with(&dir, asked).unwrap();
    first.round();
    first.wait(Duration::from_secs(3));
    let mut checkpoint = None;
    while checkpoint.is_none() && first.rounds() < 100 {
        first.round();
        checkpoint = first.checkpoint();
    }
    let checkpoint = checkpoint.expect("taken within a hundred rounds");
    first.run_for(Duration::from_secs(70));
    let lines = |events: &[Event]| -> Vec<String> {
        events
            .iter()
            .map(|e| serde_json::to_string(e).unwrap())
            .collect()
    };
    let whole = lines(&first.events);
    let resumed = Stepping {
        resume: Some(checkpoint),
        ..Stepping::default()
    };
    let mut second = RoundByRound::start_with(&dir, resumed).unwrap();
    second.round();
    second.run_for(Duration::from_secs(70));
    let rest = lines(&second.events);
    assert!(second.is_over(), "the minute cooked to its end");
    let split = whole.len() - rest.len();
    assert_eq!(whole[split..], rest[..]);
}

/// A stepped run says when its next time test comes due, as the runner counts it: in B, which
/// waits 2 s, the composite PLAY's 500 ms (counted from PLAY's entry at 0, not B's at 300 ms)
/// come first. What a host moving its own virtual clock (the Python package's) moves it to.
#[test]
fn a_stepped_run_says_when_a_composites_time_test_comes_due() {
    let dir = std::env::temp_dir().join(format!("proclaim-next-due-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let machine = "machine M\ninitial PLAY\nstate PLAY {\n    when after_ms(500) -> OUT\n    \
                   state A { when after_ms(300) -> B }\n    state B { when after(2s) -> A }\n}\n\
                   state OUT { }\n";
    std::fs::write(dir.join("M.machine"), machine).unwrap();
    std::fs::write(
        dir.join("behaviour.toml"),
        "[[machine]]\nfile = \"M.machine\"\n",
    )
    .unwrap();
    let mut run = proclaim_behaviour::testing::RoundByRound::start(&dir, "").expect("it starts");
    assert_eq!(run.next_time_test(), None, "nothing rang yet");
    run.round();
    assert_eq!(run.state_of("M"), Some("PLAY.A"));
    assert_eq!(run.next_time_test(), Some(Duration::from_millis(300)));
    run.wait(Duration::from_millis(300));
    run.round();
    assert_eq!(
        run.next_time_test(),
        None,
        "A's 300 ms fired: it moves, and rings next round anyway"
    );
    run.round();
    assert_eq!(run.state_of("M"), Some("PLAY.B"));
    assert_eq!(run.next_time_test(), Some(Duration::from_millis(500)));
    run.wait(Duration::from_millis(200));
    run.round();
    run.round();
    assert_eq!(run.state_of("M"), Some("OUT"));
    assert_eq!(run.next_time_test(), None, "over");
    let _ = std::fs::remove_dir_all(&dir);
}
