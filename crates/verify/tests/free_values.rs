//! Free values that flow through variables and arithmetic into labels (spec §6, "Free
//! values"): controllers of the kinds the Griffith team wrote, in `tests/controllers/`, each
//! property's verdict checked by hand, and every counterexample or witness replayed in the
//! real runner on the virtual clock.

use proclaim_behaviour::testing::run_scripted;
use proclaim_behaviour::{load, Folder};
use proclaim_verify::{
    to_script, verify, Options, PropertyKind, PropertySource, Report, SearchEngine, Stop, Verdict,
};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;

fn controller(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/controllers")
        .join(name)
}

fn check(name: &str, kind: PropertyKind, expression: &str) -> Report {
    check_within(name, kind, expression, Options::default())
}

fn check_within(name: &str, kind: PropertyKind, expression: &str, options: Options) -> Report {
    let behaviour = load(name, Arc::new(Folder::new(controller(name))))
        .unwrap_or_else(|e| panic!("{name} loads: {e:#?}"));
    let property = PropertySource {
        name: expression.into(),
        kind,
        expression: expression.into(),
        fair: Vec::new(),
    };
    verify(&behaviour, &[property], options).expect("verifies")
}

/// The property's run written as a script and played by the runner: the states it enters.
fn replay(name: &str, report: &Report) -> Vec<String> {
    let trace = report.properties[0].trace.as_ref().expect("a run");
    let (script, notes) = to_script(trace, Duration::from_millis(100), name);
    assert!(
        notes.is_empty(),
        "{name}: the script reproduces it all:\n{script}"
    );
    let run = run_scripted(controller(name), &script, Duration::from_secs(5))
        .unwrap_or_else(|e| panic!("{name}: the script runs: {e}\n{script}"));
    run.visits
        .iter()
        .map(|v| format!("{}.{}", v.machine, v.state))
        .collect()
}

/// A free value the machine posts on entering T and reads again at T's snapshot: the run
/// needs the knob to turn it back inside that one ringlet, which no script can say, and the
/// script's notes say so (its read was once dropped as unchanged, silently).
#[test]
fn a_value_changed_after_the_machines_own_posting_in_one_ringlet_is_noted() {
    for engine in [SearchEngine::Explicit, SearchEngine::Symbolic] {
        let options = Options {
            engine,
            ..Options::default()
        };
        let report = check_within(
            "overwritten-on-entry",
            PropertyKind::Never,
            "A.BAD",
            options,
        );
        let p = &report.properties[0];
        assert_eq!(p.verdict, Verdict::Fails, "{report:#?}");
        let trace = p.trace.as_ref().expect("a counterexample");
        let (script, notes) = to_script(trace, Duration::from_millis(100), "t");
        assert_eq!(
            notes,
            ["`level` = 1 between A's OnEntry and its snapshot in round 2: set after that round"],
            "{engine:?}\n{script}"
        );
    }
}

/// A search the choice budget stops keeps the paths to what it stored before: the
/// counterexample it found says how (it was once empty, as if the initial state broke the
/// property, which no run shows: the differential test's replay found it).
#[test]
fn a_search_stopped_by_the_choice_budget_shows_the_run_it_found() {
    let options = Options {
        engine: SearchEngine::Explicit,
        ..Options::default()
    };
    let report = check_within("overflowing", PropertyKind::Never, "v1 == 10", options);
    assert_eq!(
        report.stats.stopped,
        Stop::ChoiceBudget,
        "{:?}",
        report.stats
    );
    let p = &report.properties[0];
    assert_eq!(p.verdict, Verdict::Fails, "{report:#?}");
    let steps = &p.trace.as_ref().expect("a counterexample").steps;
    assert_eq!(steps.len(), 1, "{steps:#?}");
    assert_eq!((steps[0].machine.as_str(), steps[0].round), ("N0", 1));
    assert!(
        // OnEntry read `in0` unposted (`v1 = in0`), and the snapshot as -7: a change inside
        // the ringlet, told as one.
        steps[0]
            .at_snapshot
            .iter()
            .any(|a| a.name == "in0" && a.value == "-7"),
        "{steps:#?}"
    );
}

/// A free value read, overwritten by the machine's own posting, and read again as it was: the
/// second read is the world's change and is told, so the script sets it again and replays.
#[test]
fn a_value_read_again_after_the_machine_overwrote_it_is_told() {
    for engine in [SearchEngine::Explicit, SearchEngine::Symbolic] {
        let options = Options {
            engine,
            ..Options::default()
        };
        let report = check_within("overwritten", PropertyKind::Never, "A.BAD", options);
        let p = &report.properties[0];
        assert_eq!(p.verdict, Verdict::Fails, "{report:#?}");
        let reads: Vec<Vec<String>> = (p.trace.as_ref().expect("a counterexample").steps)
            .iter()
            .map(|s| {
                s.read
                    .iter()
                    .map(|a| format!("{} = {}", a.name, a.value))
                    .collect()
            })
            .collect();
        assert_eq!(reads, [vec!["level = 1"], vec!["level = 1"]], "{engine:?}");
        assert!(replay("overwritten", &report).contains(&"A.BAD".to_string()));
    }
}

#[test]
fn a_copied_sighting_keeps_its_sign() {
    let report = check("cutdown", PropertyKind::Never, "A.RIGHT");
    let p = &report.properties[0];
    assert_eq!(p.verdict, Verdict::Fails, "{report:#?}");
    let trace = p.trace.as_ref().expect("a counterexample");
    let (script, _) = to_script(trace, Duration::from_millis(100), "cutdown");
    assert!(
        script.contains("ballRR = -"),
        "a negative sighting:\n{script}"
    );
    assert!(report.inexact.is_empty(), "{:?}", report.inexact);
    assert!(replay("cutdown", &report).contains(&"A.RIGHT".to_string()));
    // `ballRR` is only copied, so nothing says it is a truth: a property may compare it with a
    // number, and its reason names the property.
    let report = check("cutdown", PropertyKind::Never, "A.RIGHT && ballRR < rr + 1");
    assert!(
        report
            .inexact
            .iter()
            .any(|i| i.place == "the property `A.RIGHT && ballRR < rr + 1`"),
        "{:?}",
        report.inexact
    );
}

#[test]
fn a_scaled_battery_charge_reaches_the_warning() {
    let report = check(
        "battery",
        PropertyKind::Reachable,
        "BatteryMonitor.VerbalWarning",
    );
    assert_eq!(report.properties[0].verdict, Verdict::Holds, "{report:#?}");
    assert!(report.inexact.is_empty(), "{:?}", report.inexact);
    let visits = replay("battery", &report);
    assert!(
        visits.contains(&"BatteryMonitor.VerbalWarning".to_string()),
        "{visits:?}"
    );
    // By hand: LOW is entered only below 10 %, but its own ringlet recomputes the charge,
    // which may have risen since.
    let report = check(
        "battery",
        PropertyKind::Never,
        "BatteryMonitor.LOW && percent >= 10",
    );
    assert_eq!(report.properties[0].verdict, Verdict::Fails);
    // Exact: nothing the charge can be takes OK straight to the warning.
    let report = check(
        "battery",
        PropertyKind::Never,
        "BatteryMonitor.VerbalWarning && percent >= 5",
    );
    assert_eq!(report.properties[0].verdict, Verdict::Holds, "{report:#?}");
}

#[test]
fn sightings_compared_with_each_other_take_every_order() {
    let report = check("kicker", PropertyKind::Reachable, "Kicker.KICK_LEFT");
    assert_eq!(report.properties[0].verdict, Verdict::Holds);
    assert!(replay("kicker", &report).contains(&"Kicker.KICK_LEFT".to_string()));
    // By hand: the copies are made in WATCH alone and KICK_RIGHT is final, so they stay as
    // the label saw them.
    let report = check(
        "kicker",
        PropertyKind::Never,
        "Kicker.KICK_RIGHT && rl >= rr",
    );
    assert_eq!(report.properties[0].verdict, Verdict::Holds, "{report:#?}");
    let report = check(
        "kicker",
        PropertyKind::Never,
        "Kicker.KICK_RIGHT && rr <= 100",
    );
    assert_eq!(report.properties[0].verdict, Verdict::Holds, "{report:#?}");
}

#[test]
fn free_values_added_together_are_undecided_with_the_reason() {
    // `total > 1000` is reached by adding; a search that finds no way there must not say
    // "holds". Here it does find one (a step of `true`, 1, a thousand times), a real run.
    let report = check("accumulator", PropertyKind::Never, "Sum.FULL");
    assert_eq!(report.properties[0].verdict, Verdict::Fails);
    let why = &report.inexact;
    assert!(
        why.iter()
            .any(|i| i.value == "step" && i.why.contains("another free value")),
        "{why:?}"
    );
    assert!(
        report.findings.is_empty(),
        "no \"never\" findings: {:?}",
        report.findings
    );
    // What the search cannot reach under its budget is undecided, not "holds".
    let options = Options {
        max_states: 5_000,
        ..Options::default()
    };
    let report = check_within(
        "accumulator",
        PropertyKind::Never,
        "Sum.FULL && total <= 1000",
        options,
    );
    assert_eq!(
        report.properties[0].verdict,
        Verdict::Incomplete,
        "{report:#?}"
    );
}

#[test]
fn a_dose_read_twice_can_count_below_zero() {
    let report = check("pump", PropertyKind::Never, "timeLeft < 0");
    assert_eq!(report.properties[0].verdict, Verdict::Fails, "{report:#?}");
    let trace = report.properties[0]
        .trace
        .as_ref()
        .expect("a counterexample");
    let (script, _) = to_script(trace, Duration::from_millis(100), "pump");
    // A dose of -1 read on entering RUNNING, after a positive one started it.
    assert!(script.contains("doseRequested = -"), "{script}");
}

/// Eight machines of a 2012 NAO game controller's kind (`controllers/gamecontroller`): the
/// league's state and penalty, three buttons, the chest LED, team and kick-off by the feet in
/// INITIAL, a fall watch while the robot may move.
#[test]
fn a_game_controller_of_eight_machines_is_decided() {
    let name = "gamecontroller";
    let report = check(name, PropertyKind::Reachable, "GameController.PLAYING");
    assert_eq!(report.properties[0].verdict, Verdict::Holds, "{report:#?}");
    assert!(report.inexact.is_empty(), "{:?}", report.inexact);
    assert!(replay(name, &report).contains(&"GameController.PLAYING".to_string()));
    // By hand: PLAYING tries `gcState == 4` before `fallen == 1`, and FINISHED stops the fall
    // watch, so a robot lying down when the game ends keeps `fallen` set. (The run needs the
    // fall watch's 500 ms to pass within a round, which a script on the clock cannot say.)
    let report = check(
        name,
        PropertyKind::Never,
        "GameController.FINISHED && fallen == 1",
    );
    assert_eq!(report.properties[0].verdict, Verdict::Fails, "{report:#?}");
    // The LED follows the phase a ringlet later: it is still green after PLAYING is left.
    let report = check(
        name,
        PropertyKind::Never,
        "ChestLed.GREEN && !GameController.PLAYING",
    );
    assert_eq!(report.properties[0].verdict, Verdict::Fails, "{report:#?}");
    // By hand: INITIAL's OnExit suspends the foot controls, obeyed as its ringlet ends, before
    // any state that follows. Tens of millions of states: the symbolic engine decides it.
    let report = check(
        name,
        PropertyKind::Never,
        "GameController.PLAYING && LeftFootControlIsRunning",
    );
    assert_eq!(report.properties[0].verdict, Verdict::Holds, "{report:#?}");
}

/// Eight machines of an infusion pump's kind (`controllers/infusion`): keypad, dose entry,
/// the pump counting the accepted dose down, two sensors, a battery, an alarm, a display.
#[test]
fn an_infusion_pump_of_eight_machines_is_decided_with_its_declared_range() {
    let name = "infusion";
    let report = check(name, PropertyKind::Reachable, "Pump.DONE");
    assert_eq!(report.properties[0].verdict, Verdict::Holds, "{report:#?}");
    assert!(replay(name, &report).contains(&"Pump.DONE".to_string()));
    // The display lights a ringlet after the pump starts and darkens a ringlet after it stops.
    let report = check(name, PropertyKind::Never, "Display.LIT && Pump.IDLE");
    assert_eq!(report.properties[0].verdict, Verdict::Fails, "{report:#?}");
    // By hand: a dose is accepted only from 1 to 8 and copied once, and the count stops at
    // zero. The manifest declares the dose field's range (0..9), so every dose is in the model
    // and the count, which feeds on itself, is followed exactly.
    for never in ["timeLeft < 0", "Pump.RUNNING && dose > 8"] {
        let report = check(name, PropertyKind::Never, never);
        assert_eq!(report.properties[0].verdict, Verdict::Holds, "{report:#?}");
        assert!(report.inexact.is_empty(), "{:?}", report.inexact);
    }
    // Without the range no finite domain follows the count: not "holds", but the value, the
    // reason and the place.
    let mut behaviour = load(name, Arc::new(Folder::new(controller(name)))).expect("loads");
    behaviour.ranges.clear();
    let property = PropertySource {
        name: "timeLeft < 0".into(),
        kind: PropertyKind::Never,
        expression: "timeLeft < 0".into(),
        fair: Vec::new(),
    };
    let report = verify(&behaviour, &[property], Options::default()).expect("verifies");
    assert_ne!(report.properties[0].verdict, Verdict::Holds, "{report:#?}");
    assert!(
        report.inexact.iter().any(|i| i.value == "doseEntered"
            && i.why.contains("without bound")
            && i.place.starts_with("Pump.machine:16")),
        "{:?}",
        report.inexact
    );
}
