//! `table` and `explain`: a theory's answers for every input, and why an answer is what it is.

use super::{check, stderr, stdout};
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
