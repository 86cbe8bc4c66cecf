//! `verify`: a seeded fault found, its counterexample written as a script that replays it.

use super::{stderr, stdout};
use crate::proclaim;

#[test]
fn verify_finds_the_seeded_interlock_fault_and_its_script_replays_it() {
    let machine = std::fs::read_to_string("machines/microwave/Microwave.machine").unwrap();
    // The fault: COOKING no longer leaves when the theory stops the magnetron.
    let faulty: String = machine
        .lines()
        .filter(|l| !l.contains("when ~cook"))
        .map(|l| format!("{l}\n"))
        .collect();
    assert_ne!(faulty, machine);
    let manifest = std::fs::read_to_string("machines/microwave/behaviour.toml")
        .unwrap()
        .replace("../../theories/", "");
    let dir = crate::behaviour_folder(
        "verify-fault",
        &[
            ("behaviour.toml", &manifest),
            ("Microwave.machine", &faulty),
            (
                "microwave.dl",
                &std::fs::read_to_string("theories/microwave.dl").unwrap(),
            ),
            (
                "kitchen.script",
                &std::fs::read_to_string("machines/microwave/kitchen.script").unwrap(),
            ),
        ],
    );
    let d = dir.to_str().unwrap();

    // The original holds; the fault fails (exit 1) with its counterexample by rounds.
    let o = proclaim(&["verify", "microwave"]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    assert!(
        stdout(&o).contains("door interlock: holds"),
        "{}",
        stdout(&o)
    );
    let script = dir.join("counterexample.script");
    let o = proclaim(&["verify", d, "--counterexample", script.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}{}", stdout(&o), stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("door interlock: FAILS"), "{out}");
    assert!(
        out.contains("Microwave: IDLE -> COOKING (when cook)"),
        "{out}"
    );
    assert!(
        out.contains("round 2\n    Microwave: COOKING stays; reads doorOpen = true"),
        "{out}"
    );

    // JSON, a budget too small (exit 3), a bad property (exit 2, located).
    let o = proclaim(&["verify", d, "--json"]);
    let json: serde_json::Value = serde_json::from_str(&stdout(&o)).expect("JSON");
    assert_eq!(json["report"]["properties"][0]["verdict"], "fails");
    let o = proclaim(&["verify", "microwave", "--max-states", "5"]);
    assert_eq!(o.status.code(), Some(3), "{}", stdout(&o));
    let o = proclaim(&["verify", "microwave", "--never", "Microwave.BAKING"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("column 1"), "{}", stderr(&o));

    // The script replays the counterexample: the door opens while the magnetron stays on.
    // (One machine: the runner's schedule, racing tasks or rounds, makes no difference here.)
    let o = proclaim(&[
        "run",
        d,
        "--script",
        script.to_str().unwrap(),
        "--virtual-clock",
        "--for",
        "2s",
    ]);
    let run = stdout(&o);
    let opened = run.find("posts doorOpen: true").expect("the door opens");
    let on = run
        .rfind("posts Magnetron: on")
        .expect("the magnetron goes on");
    assert!(on < opened, "{run}");
    assert!(!run[opened..].contains("Magnetron: off"), "{run}");

    // Beside the script, that run's trace for `replay --monitor`: the same story.
    let traced = std::fs::read_to_string(script.with_extension("jsonl")).unwrap();
    let opened = traced
        .find(r#""type":"doorOpen","content":"true""#)
        .expect("the door opens in the trace");
    assert!(traced[..opened].contains(r#""type":"Magnetron","content":"on""#));
    assert!(!traced[opened..].contains(r#""type":"Magnetron","content":"off""#));
    let o = proclaim(&["replay", script.with_extension("jsonl").to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
}
