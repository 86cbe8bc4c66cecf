//! Behaviours verified end to end: written to a folder, loaded as `proclaim` loads them, their
//! properties checked; and the microwave of `machines/microwave` with seeded faults.

use proclaim_behaviour::{load, Behaviour, Folder};
use proclaim_verify::{
    render, to_script, verify, Finding, Options, PropertyKind, PropertySource, Report,
    SearchEngine, Verdict, VerifyError,
};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A fresh folder holding `files` (name, text).
fn folder(files: &[(&str, &str)]) -> PathBuf {
    static NEXT: AtomicUsize = AtomicUsize::new(0);
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!(
        "proclaim-verify-{}-{}",
        std::process::id(),
        NEXT.fetch_add(1, Ordering::Relaxed)
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    for (name, text) in files {
        std::fs::write(dir.join(name), text).expect("write");
    }
    dir
}

fn load_dir(dir: &Path) -> Behaviour {
    load("test", Arc::new(Folder::new(dir))).unwrap_or_else(|e| panic!("loads: {e:#?}"))
}

fn property(kind: PropertyKind, expression: &str) -> PropertySource {
    PropertySource {
        name: format!("{} {expression}", kind.word()),
        kind,
        expression: expression.into(),
        fair: Vec::new(),
    }
}

fn never(e: &str) -> PropertySource {
    property(PropertyKind::Never, e)
}

fn always(e: &str) -> PropertySource {
    property(PropertyKind::Always, e)
}

fn reachable(e: &str) -> PropertySource {
    property(PropertyKind::Reachable, e)
}

fn run(dir: &Path, properties: &[PropertySource]) -> Report {
    verify(&load_dir(dir), properties, Options::default()).expect("verifies")
}

/// The verdicts, then each trace as rendered, then the findings, as one text.
fn summary(report: &Report) -> String {
    let mut out = String::new();
    for p in &report.properties {
        out.push_str(&format!("{:?}: {} {}\n", p.verdict, p.kind, p.expression));
        if let Some(t) = &p.trace {
            out.push_str(&render(t));
        }
    }
    for f in &report.findings {
        match f {
            Finding::NeverEntered { machine, state } => {
                out.push_str(&format!("never entered: {machine}.{state}\n"))
            }
            Finding::NeverFires {
                machine, from, to, ..
            } => out.push_str(&format!("never fires: {machine}.{from} -> {to}\n")),
            Finding::Deadlock { waiting, trace } => {
                out.push_str(&format!("deadlock: {}\n", waiting.join(", ")));
                out.push_str(&render(trace));
            }
        }
    }
    out
}

/// A behaviour of the machines given (`start = false` for names ending in `*`) checked
/// against `properties`; `expect` is the [`summary`].
fn check(machines: &[(&str, &str)], properties: &[PropertySource], expect: &str) {
    let mut manifest = String::new();
    let mut files = Vec::new();
    for (name, text) in machines {
        let (name, start) = match name.strip_suffix('*') {
            Some(n) => (n, false),
            None => (*name, true),
        };
        manifest.push_str(&format!(
            "[[machine]]\nfile = \"{name}.machine\"\nstart = {start}\n"
        ));
        files.push((format!("{name}.machine"), text.to_string()));
    }
    files.push(("behaviour.toml".into(), manifest));
    let refs: Vec<(&str, &str)> = files
        .iter()
        .map(|(a, b)| (a.as_str(), b.as_str()))
        .collect();
    let dir = folder(&refs);
    let got = summary(&run(&dir, properties));
    assert_eq!(got.trim(), expect.trim(), "\n--- got ---\n{got}");
    // The symbolic engine, where it takes the behaviour, says the same.
    let symbolic = Options {
        engine: SearchEngine::Symbolic,
        ..Options::default()
    };
    match verify(&load_dir(&dir), properties, symbolic) {
        Ok(report) => {
            let got = summary(&report);
            assert_eq!(got.trim(), expect.trim(), "\n--- symbolic ---\n{got}");
        }
        Err(VerifyError::SymbolicDeclined(_)) => {}
        Err(e) => panic!("symbolic: {e}"),
    }
}

#[test]
fn machines_ring_in_manifest_order_and_see_variables_at_once() {
    // gufsm's IndustrialPress: the controller's `low = 1` is overwritten by the sensor's
    // `low = 0` because the sensor rings after it in every round.
    let controller =
        "machine Controller\nstate A { entry { low = 1; } when TRUE -> B }\nstate B { }";
    let sensor = "machine Sensor\nstate S { entry { low = 0; } when TRUE -> T }\nstate T { }";
    check(
        &[("Controller", controller), ("Sensor", sensor)],
        &[
            always("!(Controller.B && Sensor.T) || low == 0"),
            reachable("low == 1"),
        ],
        "Holds: always !(Controller.B && Sensor.T) || low == 0\n\
         Holds: reachable low == 1\n  round 1\n    Controller: A -> B (when TRUE)",
    );
}

#[test]
fn a_machine_started_in_a_round_rings_from_the_next() {
    // Main starts Sub during round 1; Sub stands after it in the manifest but must not ring
    // before round 2, so `count` is still 0 when Main's second ringlet reads it.
    let main = "machine Main\nstate GO { entry {\n Sub: On\n } when TRUE -> LOOK }\n\
                state LOOK { when count == 0 -> EARLY\n when count == 1 -> LATE }\n\
                state EARLY { }\nstate LATE { }";
    let sub = "machine Sub\nstate COUNT { entry { count = count + 1; } when FALSE -> COUNT }";
    check(
        &[("Main", main), ("Sub*", sub)],
        &[never("Main.LATE"), reachable("Main.EARLY")],
        "Holds: never Main.LATE\n\
         Holds: reachable Main.EARLY\n  round 1\n    Main: GO -> LOOK (when TRUE)\n  round 2\n    \
         Main: LOOK -> EARLY (when count == 0)\n\
         never entered: Main.LATE\n\
         never fires: Main.LOOK -> LATE\n\
         never fires: Sub.COUNT -> COUNT\n\
         deadlock: Sub.COUNT\n  round 1\n    Main: GO -> LOOK (when TRUE)\n  round 2\n    \
         Main: LOOK -> EARLY (when count == 0)",
    );
}

#[test]
fn the_environment_is_free_and_time_only_passes() {
    // `button` is nobody's: the world sets it at will. The timeout may come due at any
    // snapshot after the one of the ringlet that arrived (no time has passed in WAIT then), so
    // WAIT can end either way; a priority shadows the second `button` label.
    let m = "machine M\nstate WAIT { when button -> PRESSED\n when timeout(2s) -> LATE\n \
             when button && timeout(1s) -> NEVER }\nstate PRESSED { }\nstate LATE { }\nstate NEVER { }";
    check(
        &[("M", m)],
        &[reachable("M.LATE"), never("M.NEVER")],
        "Holds: reachable M.LATE\n  round 1\n    M: WAIT stays\n  \
         round 2\n    M: WAIT -> LATE (when timeout(2s)); due: timeout(1s), timeout(2s)\n\
         Holds: never M.NEVER\n\
         never entered: M.NEVER\n\
         never fires: M.WAIT -> NEVER",
    );
}

#[test]
fn suspend_and_resume_keep_the_state_and_enter_it_again() {
    // W rings first: its OnEntry counts; Boss suspends it, then resumes it, which runs the
    // OnEntry of the state it was in once more, from the round after.
    let worker = "machine W\nstate X { entry { n = n + 1; } when n > 5 -> Y }\nstate Y { }";
    let boss = "machine Boss\nstate A { entry { suspend(\"W\"); } when TRUE -> B }\n\
                state B { entry { resume(\"W\"); } when TRUE -> C }\nstate C { }";
    check(
        &[("W", worker), ("Boss", boss)],
        &[
            reachable("n == 2"),
            never("n == 3"),
            never("n == 2 && !Boss.C"),
        ],
        "Holds: reachable n == 2\n  round 1\n    W: X stays\n    Boss: A -> B (when TRUE)\n  \
         round 2\n    Boss: B -> C (when TRUE)\n  round 3\n    W: X stays\n\
         Holds: never n == 3\n\
         Holds: never n == 2 && !Boss.C\n\
         never entered: W.Y\n\
         never fires: W.X -> Y\n\
         deadlock: W.X\n  round 1\n    W: X stays\n    Boss: A -> B (when TRUE)\n  \
         round 2\n    Boss: B -> C (when TRUE)",
    );
}

#[test]
fn a_state_no_label_can_leave_is_a_deadlock_to_both_engines() {
    // Two free inputs: the symbolic engine takes this behaviour, so `check` holds both engines
    // to the same nearest deadlock.
    let m = "machine M\nstate WAIT { when a && b -> HELD }\nstate HELD { when FALSE -> WAIT }";
    // A property that holds, so the search is complete and deadlocks are looked for.
    let property = always("M.WAIT || M.HELD");
    let expect = "Holds: always M.WAIT || M.HELD\n\
                  never fires: M.HELD -> WAIT\n\
                  deadlock: M.HELD\n  round 1\n    \
                  M: WAIT -> HELD (when a && b); reads a = true, b = true";
    check(&[("M", m)], std::slice::from_ref(&property), expect);
    let dir = folder(&[
        ("M.machine", m),
        ("behaviour.toml", "[[machine]]\nfile = \"M.machine\"\n"),
    ]);
    let symbolic = Options {
        engine: SearchEngine::Symbolic,
        ..Options::default()
    };
    let report = verify(&load_dir(&dir), &[property], symbolic)
        .expect("the symbolic engine takes two free inputs");
    assert!(
        matches!(report.findings.last(), Some(Finding::Deadlock { .. })),
        "{:?}",
        report.findings
    );
}

fn microwave(machine: &str, properties: &[&str]) -> PathBuf {
    let manifest = std::fs::read_to_string(repo().join("machines/microwave/behaviour.toml"))
        .expect("manifest")
        .replace("../../theories/", "");
    let theory = std::fs::read_to_string(repo().join("theories/microwave.dl")).expect("theory");
    let script =
        std::fs::read_to_string(repo().join("machines/microwave/kitchen.script")).expect("script");
    // Only the machine text under test; the manifest's own properties are replaced.
    let manifest: String = manifest
        .split("[[property]]")
        .next()
        .unwrap_or_default()
        .to_string()
        + &properties.concat();
    folder(&[
        ("behaviour.toml", &manifest),
        ("microwave.dl", &theory),
        ("kitchen.script", &script),
        ("Microwave.machine", machine),
    ])
}

fn original_microwave() -> String {
    std::fs::read_to_string(repo().join("machines/microwave/Microwave.machine")).expect("machine")
}

const INTERLOCK: &str = "Magnetron == \"on\" && saw(Microwave, doorOpen)";

#[test]
fn the_microwave_interlock_holds_and_its_manifest_says_so() {
    let dir = repo().join("machines/microwave");
    let behaviour = load_dir(&dir);
    let declared = proclaim_verify::manifest_properties(&behaviour);
    assert!(
        declared.iter().any(|p| p.kind == PropertyKind::Never),
        "the manifest declares the interlock: {declared:?}"
    );
    let report = verify(&behaviour, &declared, Options::default()).expect("verifies");
    assert!(report.stats.complete);
    for p in &report.properties {
        assert_eq!(
            p.verdict,
            Verdict::Holds,
            "{}: {}",
            p.name,
            summary(&report)
        );
    }
    assert_eq!(report.findings, vec![], "{}", summary(&report));
    // The theory is consulted, not guessed: the magnetron is never on with the door seen
    // open, but the door can be open while the machine waits for its next ringlet (§6).
    let report = verify(
        &behaviour,
        &[never("Microwave.COOKING && doorOpen"), reachable("cook")],
        Options::default(),
    )
    .expect("verifies");
    assert_eq!(report.properties[0].verdict, Verdict::Fails);
    assert_eq!(report.properties[1].verdict, Verdict::Holds);
}

#[test]
fn seeded_faults_in_the_microwave_fail_with_a_counterexample() {
    let original = original_microwave();
    let faults = [
        // The transitions that leave COOKING when the theory stops the magnetron are gone.
        (
            "missing transition",
            original
                .replace("    when ~cook && light -> OPEN\n", "")
                .replace("    when ~cook -> IDLE\n", ""),
        ),
        // Leaving for OPEN only when the light is off: with the door open it is on.
        (
            "wrong label",
            original
                .replace(
                    "when ~cook && light -> OPEN",
                    "when ~cook && ~light -> OPEN",
                )
                .replace("    when ~cook -> IDLE\n", ""),
        ),
        // The magnetron is switched off on entering IDLE, a ringlet too late.
        (
            "missing exit",
            original.replace("    exit {\n        Magnetron: off\n    }\n", ""),
        ),
    ];
    for (fault, machine) in faults {
        assert_ne!(machine, original, "{fault}: the fault is seeded");
        let dir = microwave(&machine, &[]);
        let report = run(&dir, &[never(INTERLOCK)]);
        let outcome = &report.properties[0];
        assert_eq!(
            outcome.verdict,
            Verdict::Fails,
            "{fault}: {}",
            summary(&report)
        );
        let trace = outcome.trace.as_ref().expect("a counterexample");
        let last = trace.steps.last().expect("at least one step");
        assert_eq!(last.machine, "Microwave", "{fault}");
        assert_eq!(last.from, "COOKING", "{fault}: {}", render(trace));
        // The script that replays it sets the door and the timer, and parses.
        let (script, _) = to_script(trace, std::time::Duration::from_millis(100), fault);
        let parsed = proclaim_experts::parse_script(&script).expect("the script parses");
        assert!(
            parsed
                .steps
                .iter()
                .any(|s| s.atom == "doorOpen" && s.value.as_truth() == Some(true)),
            "{fault}: the door opens in\n{script}"
        );
    }
}

#[test]
fn the_shortest_counterexample_of_a_missing_transition() {
    let machine = original_microwave()
        .replace("    when ~cook && light -> OPEN\n", "")
        .replace("    when ~cook -> IDLE\n", "");
    let dir = microwave(&machine, &[]);
    let report = run(&dir, &[never(INTERLOCK)]);
    let trace = report.properties[0]
        .trace
        .as_ref()
        .expect("a counterexample");
    // Cook with the timer set (the door not yet reported), then see the door open and stay
    // in COOKING.
    let expect = "  round 1\n    \
                  Microwave: IDLE -> COOKING (when cook); reads timeLeft = true\n  \
                  round 2\n    Microwave: COOKING stays; reads doorOpen = true\n";
    assert_eq!(render(trace), expect);
}

#[test]
fn bad_properties_are_located_errors() {
    let dir = repo().join("machines/microwave");
    let behaviour = load_dir(&dir);
    let cases = [
        ("Oven.COOKING", 1, "`Oven` is no machine"),
        (
            "doorOpen && Microwave.BAKING",
            13,
            "no state or variable `BAKING`",
        ),
        ("Magnetron == 3", 1, "compares text with a number"),
        ("cook || timeout(3s)", 9, "properties cannot use it"),
        (
            "saw(Microwave, nothing)",
            16,
            "`nothing` is nothing machine Microwave can read",
        ),
        ("cook && && light", 9, "expected"),
        ("Microwave", 1, "is a machine"),
    ];
    for (expression, column, message) in cases {
        let err = verify(&behaviour, &[never(expression)], Options::default())
            .err()
            .unwrap_or_else(|| panic!("{expression} is refused"));
        let proclaim_verify::VerifyError::Properties(errors) = err else {
            panic!("{expression}: {err}");
        };
        assert_eq!(errors.len(), 1, "{expression}");
        assert_eq!(errors[0].column, column, "{expression}: {}", errors[0]);
        assert!(
            errors[0].message.contains(message),
            "{expression}: {}",
            errors[0]
        );
    }
}

#[test]
fn an_unbounded_counter_is_incomplete_not_a_hang() {
    let m = "machine Count\nstate UP { entry { int n; } internal { n = n + 1; } when FALSE -> UP }";
    let dir = folder(&[
        ("behaviour.toml", "[[machine]]\nfile = \"Count.machine\"\n"),
        ("Count.machine", m),
    ]);
    let report = verify(
        &load_dir(&dir),
        &[never("Count.n < 0"), reachable("Count.n == 50")],
        Options {
            max_states: 1000,
            ..Options::default()
        },
    )
    .expect("verifies");
    assert!(!report.stats.complete);
    assert_eq!(report.properties[0].verdict, Verdict::Incomplete);
    assert_eq!(report.properties[1].verdict, Verdict::Holds);
    assert_eq!(report.exit_code(), 3);
    assert!(report.findings.is_empty(), "no finding from half a graph");
}

#[test]
fn manifest_properties_need_exactly_one_kind() {
    let base = "[[machine]]\nfile = \"M.machine\"\n";
    for (property, ok) in [
        ("[[property]]\nname = \"p\"\nnever = \"x\"\n", true),
        ("[[property]]\nname = \"p\"\n", false),
        (
            "[[property]]\nname = \"p\"\nnever = \"x\"\nalways = \"y\"\n",
            false,
        ),
        ("[[property]]\nname = \"p\"\nsometimes = \"x\"\n", false),
    ] {
        let text = format!("{base}{property}");
        let parsed = proclaim_behaviour::parse_manifest("behaviour.toml", &text);
        assert_eq!(parsed.is_ok(), ok, "{property}: {parsed:?}");
        if let Err(e) = parsed {
            assert!(e.line >= Some(3), "{property}: located at {e}");
        }
    }
}
