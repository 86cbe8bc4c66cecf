//! Liveness end to end: `eventually`, `leads_to` and `always_eventually` on small behaviours
//! written to a folder, each holding and failing; time passing; `fair` assumptions; the shape
//! of a lasso and its script; the microwave's own "cooking stops"; and (ignored, a
//! measurement) what the liveness check adds to an exploration.

use crate::common;

use proclaim_behaviour::{load, Behaviour, Folder};
use proclaim_verify::{
    lasso_script, render, verify, Options, PropertyKind, PropertySource, Report, SearchEngine,
    Verdict, VerifyError, LOOP_REPEATS,
};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

/// A behaviour of `machines` (name, text), all started, in a fresh folder.
fn behaviour(machines: &[(&str, &str)]) -> Behaviour {
    static NEXT: AtomicUsize = AtomicUsize::new(0);
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!(
        "proclaim-liveness-{}-{}",
        std::process::id(),
        NEXT.fetch_add(1, Ordering::Relaxed)
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    let mut manifest = String::new();
    for (name, text) in machines {
        manifest.push_str(&format!("[[machine]]\nfile = \"{name}.machine\"\n"));
        std::fs::write(dir.join(format!("{name}.machine")), text).expect("write");
    }
    std::fs::write(dir.join("behaviour.toml"), manifest).expect("write");
    load("test", Arc::new(Folder::new(&dir))).unwrap_or_else(|e| panic!("loads: {e:#?}"))
}

fn property(kind: PropertyKind, expression: &str, fair: &[&str]) -> PropertySource {
    PropertySource {
        name: format!("{} {expression}", kind.word()),
        kind,
        expression: expression.into(),
        fair: fair.iter().map(|f| f.to_string()).collect(),
    }
}

/// Each verdict, then a failing property's lasso as rendered, as one text.
fn summary(report: &Report) -> String {
    let mut out = String::new();
    for p in &report.properties {
        out.push_str(&format!("{:?}: {} {}\n", p.verdict, p.kind, p.expression));
        if let Some(cycle) = &p.cycle {
            out.push_str(&render(p.trace.as_ref().expect("a way in")));
            out.push_str("  loop:\n");
            out.push_str(&render(cycle));
        }
    }
    out
}

/// The behaviour of `machines` checked against `properties`; `expect` is the [`summary`].
fn check(machines: &[(&str, &str)], properties: &[PropertySource], expect: &str) {
    let behaviour = behaviour(machines);
    let report = verify(&behaviour, properties, Options::default()).expect("verifies");
    assert!(report.stats.complete);
    let got = summary(&report);
    assert_eq!(got.trim(), expect.trim(), "\n--- got ---\n{got}");
    // The symbolic engine, where it takes the behaviour, gives the same verdicts, and a lasso
    // (perhaps another) wherever one fails.
    let symbolic = Options {
        engine: SearchEngine::Symbolic,
        ..Options::default()
    };
    match verify(&behaviour, properties, symbolic) {
        Ok(symbolic) => {
            assert!(symbolic.stats.complete);
            let verdicts = |r: &Report| -> Vec<(Verdict, bool)> {
                r.properties
                    .iter()
                    .map(|p| (p.verdict, p.trace.is_some() && p.cycle.is_some()))
                    .collect()
            };
            assert_eq!(
                verdicts(&symbolic),
                verdicts(&report),
                "\n--- symbolic ---\n{}",
                summary(&symbolic)
            );
        }
        Err(VerifyError::SymbolicDeclined(_)) => {}
        Err(e) => panic!("symbolic: {e}"),
    }
}

/// Waits for a free `go`, then toggles between two states for ever.
const WAITER: &str = "machine M\nstate WAIT { when go -> ON }\nstate ON { when TRUE -> OFF }\n\
                      state OFF { when TRUE -> ON }";

#[test]
fn eventually_holds_where_every_run_gets_there_and_fails_with_a_lasso_where_one_need_not() {
    use PropertyKind::Eventually;
    check(
        &[("M", WAITER)],
        &[
            property(Eventually, "M.ON || M.WAIT", &[]),
            property(Eventually, "M.ON", &[]),
        ],
        "Holds: eventually M.ON || M.WAIT\n\
         Fails: eventually M.ON\n  round 1\n    M: WAIT stays; reads go = false\n  \
         loop:\n  round 2\n    M: WAIT stays",
    );
}

#[test]
fn a_timeout_comes_due_because_time_passes() {
    // Nothing but time moves the machine on: the model lets the timeout come due at any
    // snapshot, and a run where it never does is not a run (time passes).
    let m = "machine M\nstate WAIT { when timeout(1s) -> DONE }\nstate DONE { }";
    check(
        &[("M", m)],
        &[
            property(PropertyKind::Eventually, "M.DONE", &[]),
            property(PropertyKind::AlwaysEventually, "M.DONE", &[]),
        ],
        "Holds: eventually M.DONE\nHolds: always_eventually M.DONE",
    );
    // With `go` never set the machine waits for ever, but only a run where the timeout has
    // come due counts: the lasso lets it come due before it loops, and not in the ringlet
    // that arrived (no time has passed in the state then).
    let m = "machine M\nstate WAIT { when go && timeout(1s) -> DONE }\nstate DONE { }";
    check(
        &[("M", m)],
        &[property(PropertyKind::Eventually, "M.DONE", &[])],
        "Fails: eventually M.DONE\n  round 1\n    M: WAIT stays\n  \
         round 2\n    M: WAIT stays; due: timeout(1s); reads go = false\n  \
         loop:\n  round 3\n    M: WAIT stays",
    );
}

#[test]
fn fairness_of_the_environment_is_assumed_only_when_asked() {
    use PropertyKind::{AlwaysEventually, LeadsTo};
    check(
        &[("M", WAITER)],
        &[
            property(LeadsTo, "M.WAIT ~> M.ON", &[]),
            property(LeadsTo, "M.WAIT ~> M.ON", &["go"]),
            property(LeadsTo, "M.ON ~> M.OFF", &[]),
            property(AlwaysEventually, "M.OFF", &["go"]),
            property(AlwaysEventually, "M.WAIT", &["go"]),
        ],
        // `go` is stored (a property names it): the world sets it between ringlets.
        "Fails: leads_to M.WAIT ~> M.ON\n  round 1\n    M: WAIT stays; then the world sets go = false\n  \
         loop:\n  round 2\n    M: WAIT stays\n\
         Holds: leads_to M.WAIT ~> M.ON\n\
         Holds: leads_to M.ON ~> M.OFF\n\
         Holds: always_eventually M.OFF\n\
         Fails: always_eventually M.WAIT\n  initially: go = true\n  round 1\n    M: WAIT -> ON (when go)\n  loop:\n  \
         round 2\n    M: ON -> OFF (when TRUE)\n  round 3\n    M: OFF -> ON (when TRUE)",
    );
}

#[test]
fn a_run_that_ends_stays_where_it_ends() {
    // After DONE no machine can ring: the run stays there for ever, and `M.START` never
    // comes again, whatever the fairness assumed.
    let m = "machine M\nstate START { when TRUE -> DONE }\nstate DONE { }";
    check(
        &[("M", m)],
        &[property(
            PropertyKind::AlwaysEventually,
            "M.START",
            &["M.START"],
        )],
        "Fails: always_eventually M.START\n  round 1\n    M: START -> DONE (when TRUE)\n  \
         round 2\n    M: DONE stays\n  loop:",
    );
}

#[test]
fn a_leads_to_whose_p_the_symbolic_engine_cannot_encode_is_declined_not_held() {
    // Seven machines each leave A on a free input of their own and come back; none reaches C.
    // `P` reads all seven machines at once (more values than the symbolic engine encodes a
    // set of), so that engine must decline and leave the verdict to the explicit one: it once
    // took the seeds it could not build for none and answered "fails" with no run to show.
    let texts: Vec<(String, String)> = (0..7)
        .map(|i| {
            let text = format!(
                "machine M{i}\nstate A {{ when go{i} -> B }}\nstate B {{ when TRUE -> A }}\nstate C {{ }}"
            );
            (format!("M{i}"), text)
        })
        .collect();
    let machines: Vec<(&str, &str)> = texts
        .iter()
        .map(|(n, t)| (n.as_str(), t.as_str()))
        .collect();
    let all_in_a = (0..7)
        .map(|i| format!("M{i}.A"))
        .collect::<Vec<_>>()
        .join(" && ");
    let properties = [property(
        PropertyKind::LeadsTo,
        &format!("{all_in_a} ~> M0.C"),
        &[],
    )];
    let b = behaviour(&machines);
    let symbolic = Options {
        engine: SearchEngine::Symbolic,
        ..Options::default()
    };
    match verify(&b, &properties, symbolic) {
        Err(VerifyError::SymbolicDeclined(why)) => {
            assert!(why.contains("reads too many values at once"), "{why}")
        }
        Ok(report) => panic!("the symbolic engine answered:\n{}", summary(&report)),
        Err(e) => panic!("symbolic: {e}"),
    }
    let report = verify(&b, &properties, Options::default()).expect("verifies");
    assert_eq!(report.properties[0].verdict, Verdict::Fails);
    assert!(report.properties[0].cycle.is_some());
}

#[test]
fn the_lasso_runs_through_every_machine_and_its_script_plays_the_loop_again_and_again() {
    // Two machines: the loop must let both ring (one round at least) and let P's machine's
    // time pass; the script names the loop and repeats it.
    let stuck = "machine S\nstate A { when go -> B }\nstate B { }";
    let other = "machine T\nstate X { when TRUE -> Y }\nstate Y { when TRUE -> X }";
    let report = verify(
        &behaviour(&[("S", stuck), ("T", other)]),
        &[property(PropertyKind::Eventually, "S.B", &[])],
        Options::default(),
    )
    .expect("verifies");
    let outcome = &report.properties[0];
    assert_eq!(outcome.verdict, Verdict::Fails);
    let (prefix, cycle) = (
        outcome.trace.as_ref().unwrap(),
        outcome.cycle.as_ref().unwrap(),
    );
    let machines: Vec<&str> = cycle.steps.iter().map(|s| s.machine.as_str()).collect();
    assert!(
        machines.contains(&"S") && machines.contains(&"T"),
        "{machines:?}"
    );
    assert!(cycle
        .steps
        .iter()
        .all(|s| s.from != "B" && s.to.as_deref() != Some("B")));
    // The loop comes back where it started, whole rounds of S then T.
    assert_eq!(cycle.steps.len() % 2, 0, "{}", render(cycle));
    assert_ne!(
        cycle.steps[0].machine,
        cycle.steps[cycle.steps.len() - 1].machine
    );
    let (script, _) = lasso_script(prefix, cycle, std::time::Duration::from_millis(100), "t");
    assert!(
        script.contains(&format!("played {LOOP_REPEATS} times")),
        "{script}"
    );
    proclaim_experts::parse_script(&script).expect("the script parses");
}

#[test]
fn the_microwave_stops_cooking() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../machines/microwave");
    let behaviour = load("microwave", Arc::new(Folder::new(&dir))).expect("loads");
    let declared = proclaim_verify::manifest_properties(&behaviour);
    let stops = declared
        .iter()
        .find(|p| p.kind == PropertyKind::LeadsTo)
        .expect("the manifest declares that cooking stops");
    assert_eq!(stops.expression, "Microwave.COOKING ~> !Microwave.COOKING");
    let report = verify(&behaviour, &declared, Options::default()).expect("verifies");
    for p in &report.properties {
        assert_eq!(p.verdict, Verdict::Holds, "{}", summary(&report));
    }
    // Without its timeout the minute never ends: the door shut, the button never let go.
    let machine = std::fs::read_to_string(dir.join("Microwave.machine")).expect("machine");
    let endless = machine.replace("when timeout(60000000) -> DONE", "when FALSE -> DONE");
    assert_ne!(endless, machine, "the fault is seeded");
    let faulty = dir_with(&dir, &endless);
    let behaviour = load("endless", Arc::new(Folder::new(&faulty))).expect("loads");
    let report = verify(&behaviour, &declared, Options::default()).expect("verifies");
    let stops = &report.properties[1];
    assert_eq!(stops.verdict, Verdict::Fails, "{}", summary(&report));
    let cycle = stops.cycle.as_ref().expect("a loop");
    assert!(
        cycle.steps.iter().all(|s| s.from == "COOKING"),
        "{}",
        render(cycle)
    );
}

/// A copy of the microwave's folder `dir` with `machine` as its machine.
fn dir_with(dir: &Path, machine: &str) -> PathBuf {
    let copy = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!(
        "proclaim-liveness-microwave-{}",
        std::process::id()
    ));
    std::fs::create_dir_all(&copy).expect("temp dir");
    let manifest = std::fs::read_to_string(dir.join("behaviour.toml"))
        .expect("manifest")
        .replace("../../theories/", "");
    std::fs::write(copy.join("behaviour.toml"), manifest).expect("write");
    std::fs::write(copy.join("Microwave.machine"), machine).expect("write");
    for (from, to) in [
        (dir.join("kitchen.script"), "kitchen.script"),
        (dir.join("../../theories/microwave.dl"), "microwave.dl"),
    ] {
        std::fs::copy(from, copy.join(to)).expect("copy");
    }
    copy
}

#[test]
fn liveness_needs_a_whole_exploration_to_hold_but_a_lasso_in_part_of_it_fails() {
    // An unbounded counter: the budget runs out. A run that stops in DONE is found all the
    // same, and is a real run.
    let counter =
        "machine C\nstate UP { entry { int n; } internal { n = n + 1; } when go -> DONE }\n\
                   state DONE { }";
    let report = verify(
        &behaviour(&[("C", counter)]),
        &[
            property(PropertyKind::Eventually, "C.DONE || C.n > 1000", &[]),
            property(PropertyKind::AlwaysEventually, "C.UP", &[]),
        ],
        Options {
            max_states: 50,
            ..Options::default()
        },
    )
    .expect("verifies");
    assert!(!report.stats.complete);
    assert_eq!(report.properties[0].verdict, Verdict::Incomplete);
    assert_eq!(report.properties[1].verdict, Verdict::Fails);
    assert_eq!(
        report.properties[1].cycle.as_ref().map(|c| c.steps.len()),
        Some(0)
    );
}

#[test]
fn bad_liveness_properties_are_located_errors() {
    let m = "machine M\nstate A { }";
    let b = behaviour(&[("M", m)]);
    let errors = |p: PropertySource| {
        verify(&b, &[p], Options::default())
            .unwrap_err()
            .to_string()
    };
    let e = errors(property(PropertyKind::LeadsTo, "M.A", &[]));
    assert!(e.contains("`P ~> Q`"), "{e}");
    let e = errors(property(PropertyKind::LeadsTo, "M.A ~> M.B", &[]));
    assert!(e.contains("column 8"), "{e}");
    let e = errors(property(PropertyKind::Eventually, "M.A", &["nope &&"]));
    assert!(e.contains("in `fair nope &&`"), "{e}");
    let e = errors(property(PropertyKind::Never, "M.A", &["M.A"]));
    assert!(e.contains("liveness"), "{e}");
}

#[test]
fn manifests_declare_liveness_with_its_fairness() {
    let base = "[[machine]]\nfile = \"M.machine\"\n[[property]]\nname = \"p\"\n";
    for (property, ok) in [
        ("eventually = \"x\"\n", true),
        ("always_eventually = \"x\"\nfair = \"y\"\n", true),
        ("leads_to = [\"a\", \"b\"]\nfair = \"y\"\n", true),
        ("leads_to = [\"a\"]\n", false),
        ("leads_to = \"a ~> b\"\n", false),
        ("never = \"x\"\nfair = \"y\"\n", false),
        ("eventually = \"x\"\nleads_to = [\"a\", \"b\"]\n", false),
    ] {
        let text = format!("{base}{property}");
        let parsed = proclaim_behaviour::parse_manifest("behaviour.toml", &text);
        assert_eq!(parsed.is_ok(), ok, "{property}: {parsed:?}");
        match parsed {
            Err(e) => assert!(e.line >= Some(3), "{property}: located at {e}"),
            Ok(manifest) => {
                // Written back as it was read.
                let again = manifest.to_toml("");
                let reread = proclaim_behaviour::parse_manifest("again", &again).expect("rereads");
                assert_eq!(reread.properties, manifest.properties, "{again}");
            }
        }
    }
    let text = format!("{base}leads_to = [\"Pump.ON\", 'x == \"a ~> b\"']\nfair = \"y\"\n");
    let manifest = proclaim_behaviour::parse_manifest("behaviour.toml", &text).expect("parses");
    let p = &manifest.properties[0];
    assert_eq!(p.expression, "Pump.ON ~> x == \"a ~> b\"");
    assert_eq!(p.fair.as_deref(), Some("y"));
    assert_eq!(
        proclaim_behaviour::split_leads_to("a ~> \"~>\" ~> c"),
        Some(((0, "a"), (5, "\"~>\" ~> c")))
    );
}

/// The time and states of `verify` with a safety property and with each liveness kind on the
/// odometer family (`tests/common/odometer.rs`): what the check after the exploration adds.
/// `cargo test --release -p proclaim-verify --test tests -- --ignored --nocapture liveness::`.
#[test]
#[ignore = "a measurement: run it in release with --ignored --nocapture"]
fn liveness_costs_little_beside_the_exploration() {
    for (n, k) in [(4, 16), (4, 24)] {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!(
            "proclaim-liveness-odometer-{n}-{k}-{}",
            std::process::id()
        ));
        common::odometer::write_odometer(&dir, n, k);
        let behaviour = load("odometer", Arc::new(Folder::new(&dir))).expect("loads");
        let last = n - 1;
        for p in [
            property(PropertyKind::Never, &format!("g0 >= {k}"), &[]),
            property(
                PropertyKind::AlwaysEventually,
                &format!("g{last} == 0"),
                &[],
            ),
            property(
                PropertyKind::LeadsTo,
                &format!("g0 == 1 ~> g{last} == 5"),
                &[],
            ),
            property(PropertyKind::Eventually, &format!("g{last} == {k}"), &[]),
        ] {
            let started = std::time::Instant::now();
            let report = verify(
                &behaviour,
                std::slice::from_ref(&p),
                Options {
                    max_states: 10_000_000,
                    ..Options::default()
                },
            )
            .expect("verifies");
            let seconds = started.elapsed().as_secs_f64();
            let outcome = &report.properties[0];
            println!(
                "odometer {n} {k}, {} {}: {:?} in {seconds:.2} s, {} states ({:.0} states/s){}",
                p.kind.word(),
                p.expression,
                outcome.verdict,
                report.stats.states,
                report.stats.states as f64 / seconds,
                outcome.cycle.as_ref().map_or(String::new(), |c| format!(
                    ", a loop of {} ringlets",
                    c.steps.len()
                )),
            );
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}

/// `--max-memory` bounds what the search holds, the liveness check after it and a counter's
/// values included: the heap, counted by the test's allocator, grows no further than the budget
/// (and the model and report beside it, a few kilobytes here) where the whole search would need
/// four times as much; the property is then undecided. With room for all of it, it holds.
#[test]
fn the_memory_budget_holds_the_search_its_values_and_the_liveness_check() {
    let counter = "machine C\nstate S { entry { int n; } internal { n = (n + 1) % 40000; } \
                   when FALSE -> S }";
    let behaviour = behaviour(&[("C", counter)]);
    let explicit = |max_memory| Options {
        engine: SearchEngine::Explicit,
        max_memory,
        ..Options::default()
    };
    let live = [property(PropertyKind::AlwaysEventually, "C.n == 0", &[])];
    let (roomy, needed) = common::allocated::peak_growth(|| {
        verify(&behaviour, &live, explicit(1 << 30)).expect("verifies")
    });
    assert_eq!(roomy.properties[0].verdict, Verdict::Holds);
    let budget = needed / 4;
    let (tight, grown) = common::allocated::peak_growth(|| {
        verify(&behaviour, &live, explicit(budget)).expect("verifies")
    });
    assert!(!tight.stats.complete);
    assert_eq!(tight.properties[0].verdict, Verdict::Incomplete);
    assert!(
        grown <= budget + (64 << 10),
        "the heap grew by {grown} bytes under a budget of {budget}"
    );
}
