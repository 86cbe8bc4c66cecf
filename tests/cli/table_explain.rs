//! `table` and `explain`: a theory's answers for every input, and why an answer is what it is.

use super::{check, record_run, stderr, stdout, temp_file};
use crate::proclaim;

#[test]
fn table_formats() {
    check(
        &["table", "microwave", "--format", "csv"],
        0,
        "doorOpen,timeLeft,beta cook,beta light\nfalse,false,false,false\nfalse,true,true,true\ntrue,false,false,true\ntrue,true,false,true\n",
    );
    let o = proclaim(&["table", "microwave", "--format", "json"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["rows"][1]["outputs"]["beta cook"], true);
    let o = proclaim(&["table", "offside"]);
    assert!(
        stdout(&o).starts_with("fewerThanTwoOpponentsBetween  inOwnHalf"),
        "{}",
        stdout(&o)
    );
}

#[test]
fn explain_tree() {
    let o = proclaim(&["explain", "blocking", "e", "--alg", "pi", "--depth", "0"]);
    assert_eq!(o.status.code(), Some(0));
    assert_eq!(
        stdout(&o),
        "-pi e\n  supported by R4: a => e\n  attacker R7 stands: its antecedent is supported and no applicable rule for e beats it\n"
    );
}

#[test]
fn explain_json_names_goals_rules_and_their_roles() {
    let o = proclaim(&[
        "explain",
        "offside",
        "offside",
        "--set",
        "fewerThanTwoOpponentsBetween=true",
        "--set",
        "behindBall=true",
        "--json",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let json: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let root = &json[0];
    assert_eq!(
        root["goal"],
        serde_json::json!({"algorithm": "beta", "literal": "offside", "proved": false})
    );
    let roles: Vec<(String, String)> = root["because"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|n| {
            Some((
                n["rule"].as_str()?.to_string(),
                n["role"].as_str()?.to_string(),
            ))
        })
        .collect();
    assert_eq!(
        roles,
        [
            ("Exposed".to_string(), "supports".to_string()),
            ("Usually".to_string(), "beaten".to_string()),
            ("OwnHalf".to_string(), "discounted".to_string()),
            ("Behind".to_string(), "stands".to_string()),
            ("ThrowIn".to_string(), "discounted".to_string()),
        ]
    );
    assert_eq!(root["because"][1]["beaten_by"], "Exposed");
}

/// A recorded run's every answer of a theory, replayed from the recording's messages into the
/// behaviour's theories, is the answer the run gave (the microwave on its kitchen script to the
/// end, and the keeper whose theory reads an input group); `explain --recording` explains one
/// from the inputs the reasoner held then, and says where a label was asked when it was not.
#[test]
fn explain_from_a_recording_gives_the_runs_answer_and_why() {
    let keeper = crate::behaviour_folder("why-keeper", KEEPER);
    let keeper_script = temp_file("keeper.script", KEEPER_SCRIPT);
    let runs = [
        ("microwave".to_string(), None, "70s"),
        (
            keeper.to_str().unwrap().to_string(),
            Some(keeper_script),
            "2s",
        ),
    ];
    for (n, (behaviour, script, run_for)) in runs.iter().enumerate() {
        let recording = temp_file(&format!("why-{n}.jsonl"), b"");
        let script = script.as_ref().map(|s| s.to_str().unwrap());
        let extra: Vec<&str> = script.into_iter().flat_map(|s| ["--script", s]).collect();
        record_run(behaviour, run_for, &recording, &extra);
        let folder = match behaviour.as_str() {
            "microwave" => "machines/microwave",
            other => other,
        };
        let files = std::sync::Arc::new(proclaim_behaviour::Folder::new(folder));
        let loaded = proclaim_behaviour::load(folder, files).unwrap();
        let text = std::fs::read_to_string(&recording).unwrap();
        let read = proclaim_behaviour::read_recording(&text).unwrap();
        let asked = proclaim_behaviour::theory_answers(&loaded, &read);
        assert!(asked.iter().any(|a| a.replayed) && asked.iter().any(|a| !a.replayed));
        for a in &asked {
            assert_eq!(a.recorded, Some(a.replayed), "{behaviour}: {a:?}");
        }
        let first_true = asked.iter().find(|a| a.replayed).unwrap();
        let round = first_true.round.to_string();
        let o = explain_recorded(behaviour, &first_true.label, &recording, &round);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        let said = stdout(&o);
        let head = format!(
            "round {round}: {} asked `{}`; the theory `{}` answered true, its inputs then: ",
            first_true.machine, first_true.label, first_true.theory
        );
        assert!(said.starts_with(&head), "{said}");
        assert!(
            said.contains(&format!("\n+beta {}\n", first_true.label)),
            "{said}"
        );
        let recorded = recording.to_str().unwrap();
        let args = [
            "explain",
            behaviour,
            &first_true.label,
            "--recording",
            recorded,
        ];
        let o = proclaim(&[&args[..], &["--round", &round, "--json"]].concat());
        let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        assert_eq!(json["answer"], true, "{json}");
        assert_eq!(json["explanation"]["goal"]["proved"], true, "{json}");
        assert!(
            json["inputs"].as_array().is_some_and(|i| !i.is_empty()),
            "{json}"
        );
    }
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("proclaim-cli-{}", std::process::id()));
    // A machine named instead of a label: which transition fired in the round and why the
    // others did not (the microwave's kitchen run, the round it first cooks).
    let microwave = dir.join("why-0.jsonl");
    let text = std::fs::read_to_string(&microwave).unwrap();
    let fired = text
        .lines()
        .find(|l| l.contains("\"event\":\"fired\"") && l.contains("\"label\":\"cook\""))
        .unwrap();
    let round: serde_json::Value = serde_json::from_str(fired).unwrap();
    let round = round["round"].to_string();
    let o = explain_recorded("microwave", "Microwave", &microwave, &round);
    let said = stdout(&o);
    assert_eq!(o.status.code(), Some(0), "{said}{}", stderr(&o));
    assert!(
        said.starts_with(&format!("round {round}: Microwave rang in ")),
        "{said}"
    );
    assert!(
        said.contains("  its labels read: cook = true (microwave)"),
        "{said}"
    );
    assert!(
        said.contains("-> COOKING when cook: fired (cook = true)\n"),
        "{said}"
    );
    let recording = dir.join("why-1.jsonl");
    let o = explain_recorded(keeper.to_str().unwrap(), "diveRight", &recording, "1");
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("`diveRight` was not asked in round 1; it was in rounds"),
        "{}",
        stderr(&o)
    );
    let o = explain_recorded(keeper.to_str().unwrap(), "stay", &recording, "1");
    assert!(
        stderr(&o).contains("`stay` is no output of the behaviour's theories (keeper)"),
        "{}",
        stderr(&o)
    );
}

/// A goalkeeper whose theory reads an input group, and a script that plays a ball to each side.
const KEEPER: &[(&str, &str)] = &[
    ("behaviour.toml", "[[machine]]\nfile = \"Keeper.machine\"\n[[theory]]\nfile = \"keeper.dl\"\n"),
    ("Keeper.machine", "machine Keeper\ninitial Wait\nstate Wait {\n    when diveLeft -> Left\n}\nstate Left {\n    when diveRight && notLeft -> Right\n}\nstate Right {\n}\n"),
    ("keeper.dl", "input{ballLeft, ballCentre, ballRight}.\nL: ballLeft => diveLeft.\nR: ballRight => diveRight.\nN: ~ballLeft => notLeft.\noutput{diveLeft, diveRight, notLeft}.\n"),
];
const KEEPER_SCRIPT: &[u8] = b"at 300ms ballLeft = true\nat 700ms ballRight = true\n";

/// A run's trace explains its answers as its recording does: every theory answer of the
/// microwave's kitchen run and of the keeper's replays from the trace as the run gave it, in
/// the same rounds, and `explain --trace` prints what `explain --recording` prints.
#[test]
fn explain_from_a_trace_gives_what_the_recording_gives() {
    let keeper = crate::behaviour_folder("why-trace-keeper", KEEPER);
    let keeper_script = temp_file("trace-keeper.script", KEEPER_SCRIPT);
    let keeper_script = keeper_script.to_str().unwrap();
    let runs = [
        ("microwave", "machines/microwave", "70s", vec![]),
        (
            keeper.to_str().unwrap(),
            keeper.to_str().unwrap(),
            "2s",
            vec!["--script", keeper_script],
        ),
    ];
    for (n, (behaviour, folder, run_for, script)) in runs.iter().enumerate() {
        let recording = temp_file(&format!("why-trace-{n}.recording.jsonl"), b"");
        let trace = temp_file(&format!("why-trace-{n}.jsonl"), b"");
        let mut extra = script.clone();
        extra.extend(["--trace", trace.to_str().unwrap()]);
        record_run(behaviour, run_for, &recording, &extra);
        let files = std::sync::Arc::new(proclaim_behaviour::Folder::new(folder));
        let loaded = proclaim_behaviour::load(folder, files).unwrap();
        let machines: Vec<&str> = loaded
            .machines
            .iter()
            .map(|m| m.machine.name.as_str())
            .collect();
        let read =
            proclaim_behaviour::read_recording(&std::fs::read_to_string(&recording).unwrap())
                .unwrap();
        let events =
            proclaim_behaviour::read_trace(&std::fs::read_to_string(&trace).unwrap()).unwrap();
        let traced = proclaim_behaviour::Recording::from_trace(events, &machines);
        let from_recording = proclaim_behaviour::theory_answers(&loaded, &read);
        let from_trace = proclaim_behaviour::theory_answers(&loaded, &traced);
        assert!(!from_trace.is_empty(), "{behaviour}");
        assert_eq!(from_trace, from_recording, "{behaviour}");
        for a in &from_trace {
            assert_eq!(a.recorded, Some(a.replayed), "{behaviour}: {a:?}");
        }
        let first_true = from_trace.iter().find(|a| a.replayed).unwrap();
        let round = first_true.round.to_string();
        let recorded = explain_recorded(behaviour, &first_true.label, &recording, &round);
        let args = ["explain", behaviour, &first_true.label, "--round", &round];
        let traced = proclaim(&[&args[..], &["--trace", trace.to_str().unwrap()]].concat());
        assert_eq!(traced.status.code(), Some(0), "{}", stderr(&traced));
        assert_eq!(stdout(&traced), stdout(&recorded));
    }
    // `--round` explains a run: it needs one.
    let o = proclaim(&["explain", "microwave", "cook", "--round", "3"]);
    assert_eq!(o.status.code(), Some(2), "{}", stdout(&o));
}

/// Why a transition over variables did not fire: the machine view says what the variable and
/// the whiteboard value its label compares held then (a copied sighting, as a Griffith player
/// kept one).
#[test]
fn explain_a_machine_says_what_the_variables_its_labels_compare_held() {
    let player = crate::behaviour_folder(
        "why-variables",
        &[
            ("behaviour.toml", "[[machine]]\nfile = \"A.machine\"\n"),
            (
                "A.machine",
                "machine A\ninitial S\nstate S {\n    internal { extern ballRR; rr = ballRR; }\n    when rr > 3 -> LEFT\n    when rr < 0 && ballRR < -1 -> RIGHT\n}\nstate LEFT { }\nstate RIGHT { }\n",
            ),
        ],
    );
    let script = temp_file(
        "why-variables.script",
        b"at 0ms ballRR = 2.5\nat 250ms ballRR = -3\n",
    );
    let recording = temp_file("why-variables.jsonl", b"");
    let player = player.to_str().unwrap();
    record_run(
        player,
        "1s",
        &recording,
        &["--script", script.to_str().unwrap()],
    );
    let text = std::fs::read_to_string(&recording).unwrap();
    let fired = text
        .lines()
        .find(|l| l.contains("\"event\":\"fired\""))
        .expect("A fires");
    let fired: serde_json::Value = serde_json::from_str(fired).unwrap();
    let round = fired["round"].as_u64().unwrap();
    let o = explain_recorded(player, "A", &recording, &round.to_string());
    let said = stdout(&o);
    assert!(
        said.contains("1. -> LEFT when rr > 3: did not hold (rr = -3)\n"),
        "{said}"
    );
    assert!(
        said.contains("2. -> RIGHT when rr < 0 && ballRR < -1: fired (rr = -3, ballRR = -3)\n"),
        "{said}"
    );
    // A round before the ball went right: neither label held, on 2.5.
    let o = explain_recorded(player, "A", &recording, "2");
    let said = stdout(&o);
    assert!(
        said.contains("1. -> LEFT when rr > 3: did not hold (rr = 2.5)\n"),
        "{said}"
    );
    assert!(
        said.contains(
            "2. -> RIGHT when rr < 0 && ballRR < -1: did not hold (rr = 2.5, ballRR = 2.5)\n"
        ),
        "{said}"
    );
}

/// `proclaim explain BEHAVIOUR QUERY --recording RECORDING --round ROUND`.
fn explain_recorded(
    behaviour: &str,
    query: &str,
    recording: &std::path::Path,
    round: &str,
) -> std::process::Output {
    let recording = recording.to_str().unwrap();
    proclaim(&[
        "explain",
        behaviour,
        query,
        "--recording",
        recording,
        "--round",
        round,
    ])
}
