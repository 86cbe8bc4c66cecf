//! The shipped theories: each truth table checked against what the theory is meant to say.

use proclaim_cdl::{load, truth_table, Engine, Language, Table};
use std::sync::Arc;

fn table(path: &str) -> Table {
    let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("theories")
        .join(path);
    let text = std::fs::read_to_string(&file).unwrap();
    let theory = load(&text, Language::Dl).unwrap_or_else(|e| panic!("{path}: {e:?}"));
    truth_table(Arc::new(Engine::new(theory))).unwrap()
}

/// Checks every row: `expect(inputs)` gives the outputs, columns in declaration order.
fn check(path: &str, expect: impl Fn(&[bool]) -> Vec<bool>) {
    let table = table(path);
    assert!(!table.rows.is_empty());
    for row in &table.rows {
        let outputs = row.outputs.as_ref().expect("consistent inputs");
        assert_eq!(
            outputs,
            &expect(&row.inputs),
            "{path}: inputs {:?} ({:?})",
            row.inputs,
            table.inputs
        );
    }
}

#[test]
fn offside() {
    let table = table("offside.dl");
    assert_eq!(
        table.inputs,
        [
            "fewerThanTwoOpponentsBetween",
            "inOwnHalf",
            "behindBall",
            "fromThrowIn"
        ]
    );
    assert_eq!(table.rows.len(), 16);
    check("offside.dl", |i| vec![i[0] && !i[1] && !i[2] && !i[3]]);
}

#[test]
fn microwave() {
    assert_eq!(table("microwave.dl").inputs, ["doorOpen", "timeLeft"]);
    check("microwave.dl", |i| {
        let (door, time) = (i[0], i[1]);
        let cook = !door && time;
        vec![cook, door || cook]
    });
}

#[test]
fn kickoff() {
    assert_eq!(
        table("kickoff.dl").inputs,
        [
            "ready",
            "set",
            "playing",
            "weKickOff",
            "ballMoved",
            "tenSecondsPassed",
            "holdingLong"
        ]
    );
    check("kickoff.dl", |i| {
        let (playing, we, moved, late, holding) = (i[2], i[3], i[4], i[5], i[6]);
        let may_play = playing && (we || moved || late);
        vec![may_play, may_play && !holding]
    });
}

#[test]
fn tweety() {
    // Columns: beta fly, beta ~fly, pi fly, mu fly; input: penguin.
    check("classics/tweety.dl", |i| {
        let penguin = i[0];
        vec![!penguin, penguin, !penguin, false]
    });
}

#[test]
fn nixon() {
    check("classics/nixon.dl", |_| vec![false, false, false]);
}

#[test]
fn team_defeat() {
    check("classics/team-defeat.dl", |_| vec![true, true, false]);
}

#[test]
fn blocking() {
    // mu pi beta alpha delta of e
    check("classics/blocking.dl", |_| {
        vec![false, false, true, false, true]
    });
}

#[test]
fn defeater() {
    check("classics/defeater.dl", |_| vec![false; 4]);
}

#[test]
fn loops() {
    check("classics/loops.dl", |_| vec![true, true, false, false]);
}

#[test]
fn exclusive_inputs_and_row_filters() {
    let theory = load(
        "input{red, green, blue}. input{night}. ignore{night, green}. assert{red, night}.\n\
         R1: red => stop. R2: night => ~stop. R2 > R1.\noutput{beta stop}.",
        Language::Dl,
    )
    .unwrap();
    let table = truth_table(Arc::new(Engine::new(theory))).unwrap();
    let rows: Vec<(Vec<bool>, Vec<bool>)> = table
        .rows
        .iter()
        .map(|r| (r.inputs.clone(), r.outputs.clone().unwrap()))
        .collect();
    // Exactly one colour; green at night ignored; only rows with red or night kept.
    assert_eq!(
        rows,
        vec![
            (vec![true, false, false, false], vec![true]),
            (vec![true, false, false, true], vec![false]),
            (vec![false, false, true, true], vec![false]),
        ]
    );
}

#[test]
fn rows_whose_inputs_contradict_the_axioms_are_marked() {
    let theory = load("input{a}. input{b}. \\/{~a, ~b}. R1: a => c.", Language::Dl).unwrap();
    let table = truth_table(Arc::new(Engine::new(theory))).unwrap();
    let outputs: Vec<_> = table
        .rows
        .iter()
        .map(|r| (r.inputs.clone(), r.outputs.is_some()))
        .collect();
    assert_eq!(
        outputs,
        [
            (vec![false, false], true),
            (vec![false, true], true),
            (vec![true, false], true),
            (vec![true, true], false)
        ]
    );
}
