//! Within one ringlet an atom reads one value (`docs/spec/behaviour.md` §3.1): a reasoner that
//! re-proves its output while the ringlet waits on another query (the answer to that query is
//! the theory's input, posted for the first time) does not change what the ringlet already
//! read of the output. The shape of the conformance test's seed 4715, with the real reasoner
//! and impersonator on a paused clock.

use proclaim_board::Whiteboard;
use proclaim_cdl::{load, Language};
use proclaim_experts::{parse_script, Impersonator, ReasonerExpert};
use proclaim_runner::{Answerer, Event, Hosts, MachineRunner, RunOptions};
use std::time::Duration;

/// `o0` holds when `in0` is known to be false; while `in0` was never posted it does not.
const THEORY: &str = "name{th}.
input{in0}.
D: => ~o0.
R: ~in0 => o0.
R > D.
output{beta o0, \"o0\"}.
";

/// The first label reads `o0` (false); the second waits for `in0`, which the script sets only
/// later, so the clock moves while it waits and the theory re-proves `o0` meanwhile.
const MACHINE: &str = "machine M
state Start {
    when o0 -> Yes
    when in0 || ~o0 -> No
}
state Yes {
}
state No {
}
";

#[tokio::test(start_paused = true)]
async fn an_answer_the_expert_changes_mid_ringlet_reads_as_it_did_first() {
    let board = Whiteboard::local();
    let theory = load(THEORY, Language::Dl).expect("the theory loads");
    tokio::spawn(ReasonerExpert::new("th", theory, &Default::default()).run(board.clone()));
    let script = parse_script("at 300ms in0 = false\n").expect("the script parses");
    tokio::spawn(Impersonator::new("impersonator", ["in0"], script).run(board.clone()));
    tokio::task::yield_now().await;
    let imported = proclaim_fsm::parse_machine("M.machine", MACHINE);
    assert!(
        imported.diagnostics.is_empty(),
        "{:?}",
        imported.diagnostics
    );
    let machine = imported.machines.into_iter().next().expect("one machine");
    let mut runner = MachineRunner::new(machine, Hosts::default(), RunOptions::default());
    let mut events = runner.events();
    tokio::spawn(runner.run(board.clone()));
    tokio::time::sleep(Duration::from_secs(2)).await;

    let mut entered = Vec::new();
    let mut reads = Vec::new();
    while let Ok(event) = events.try_recv() {
        match event {
            Event::Entered { state, .. } => entered.push(state),
            Event::Answered {
                atom,
                value,
                by,
                at,
                ..
            } if entered.len() == 1 => {
                if atom == "in0" {
                    // Answered only when the script set it: the ringlet waited that long.
                    assert_eq!(at, Duration::from_millis(300));
                }
                reads.push((atom, value, by))
            }
            _ => {}
        }
    }
    // The theory did change its answer while the ringlet waited for `in0`...
    assert_eq!(board.truth("o0"), Some(true));
    // ...and the ringlet read `o0` as it first had, so `~o0` held and it moved to No.
    let th = || Answerer::Expert("th".into());
    assert_eq!(
        reads,
        [
            ("o0".to_string(), false, th()),
            (
                "in0".to_string(),
                false,
                Answerer::Expert("impersonator".into())
            ),
            ("o0".to_string(), false, th()),
        ]
    );
    assert_eq!(entered, ["Start", "No"]);
}

/// A condition on a type no expert answers reads its posted value's truth; a value read of
/// that type later in the ringlet is still the value as posted, not that truth.
#[tokio::test(start_paused = true)]
async fn a_posted_number_read_as_a_condition_stays_a_number() {
    let board = Whiteboard::local();
    board.post("sensor", "T0", 2i64);
    let imported = proclaim_fsm::parse_machine(
        "M.machine",
        "machine M\nstate Start {\n    when ~T0 -> Yes\n    when T0 == 2 -> No\n}\nstate Yes {\n}\nstate No {\n}\n",
    );
    assert!(
        imported.diagnostics.is_empty(),
        "{:?}",
        imported.diagnostics
    );
    let machine = imported.machines.into_iter().next().expect("one machine");
    let mut runner = MachineRunner::new(machine, Hosts::default(), RunOptions::default());
    let mut events = runner.events();
    tokio::spawn(runner.run(board.clone()));
    tokio::time::sleep(Duration::from_secs(1)).await;
    let entered: Vec<String> = std::iter::from_fn(|| events.try_recv().ok())
        .filter_map(|e| match e {
            Event::Entered { state, .. } => Some(state),
            _ => None,
        })
        .collect();
    assert_eq!(entered, ["Start", "No"]);
}
