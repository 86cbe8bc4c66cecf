//! Every shipped theory (theories/ and the shared corpus's, when it is there) compiled to C
//! agrees with the reasoner on every row of its truth table, and, where a behaviour could run
//! it, on every valuation with unknown inputs too.

use crate::common;

use proclaim_cdl::{load_named, Language, SearchLimits, Theory};
use proclaim_compile::{compile, CompileError, Domain};
use std::path::{Path, PathBuf};

fn shipped() -> Vec<(PathBuf, Theory)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut files = Vec::new();
    for dir in ["theories", "theories/classics", "../shared/corpus"] {
        collect(
            &root.join(dir),
            dir != "theories" && dir != "theories/classics",
            &mut files,
        );
    }
    files.sort();
    assert!(
        files.len() >= 9,
        "the shipped theories are found: {files:?}"
    );
    files
        .into_iter()
        .map(|path| {
            let text = std::fs::read_to_string(&path).unwrap();
            let theory = load_named(&path.display().to_string(), &text, Language::Dl)
                .unwrap_or_else(|e| panic!("{e}"));
            (path, theory)
        })
        .collect()
}

fn collect(dir: &Path, deep: bool, files: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() && deep {
            collect(&path, deep, files);
        } else if path.extension().is_some_and(|e| e == "dl") {
            files.push(path);
        }
    }
}

#[test]
fn every_shipped_theory_compiled_to_c_agrees_with_its_truth_table() {
    if common::gcc_missing() {
        return;
    }
    let theories = shipped();
    let compiled: Vec<_> = theories
        .iter()
        .map(|(path, t)| {
            compile(t, SearchLimits::default(), Domain::Boolean)
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        })
        .collect();
    let (theories, compiled) = common::in_both_forms(&theories, &compiled);
    let printed = common::run_in_c(&common::scratch("shipped"), &compiled);
    assert_eq!(printed.len(), compiled.len());
    for (((_, theory), c), got) in theories.iter().zip(&compiled).zip(&printed) {
        let expected = common::expected_boolean(theory, c);
        if let Some(difference) = common::first_difference(c, got, &expected) {
            panic!("{difference}");
        }
    }
}

#[test]
fn shipped_theories_a_behaviour_can_run_agree_with_unknown_inputs_too() {
    if common::gcc_missing() {
        return;
    }
    let mut theories = Vec::new();
    let mut compiled = Vec::new();
    for (path, theory) in shipped() {
        match compile(&theory, SearchLimits::default(), Domain::Ternary) {
            Ok(c) => {
                theories.push(theory);
                compiled.push(c);
            }
            Err(CompileError::Unsupported { .. }) => {
                assert!(
                    theory.inputs().iter().any(|g| g.atoms.len() > 1)
                        || !theory.axioms().is_empty(),
                    "{} refused without a group or an axiom",
                    path.display()
                );
            }
            Err(e) => panic!("{}: {e}", path.display()),
        }
    }
    assert!(
        compiled.iter().any(|c| c.name == "microwave"),
        "the microwave is among them"
    );
    let (theories, compiled) = common::in_both_forms(&theories, &compiled);
    let printed = common::run_in_c(&common::scratch("ternary"), &compiled);
    for ((theory, c), got) in theories.iter().zip(&compiled).zip(&printed) {
        let expected = common::expected_ternary(theory, c);
        if let Some(difference) = common::first_difference(c, got, &expected) {
            panic!("{difference}");
        }
    }
}

#[test]
fn the_microwave_is_a_small_diagram() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../theories/microwave.dl");
    let text = std::fs::read_to_string(root).unwrap();
    let theory = load_named("microwave.dl", &text, Language::Dl).unwrap();
    let c = compile(&theory, SearchLimits::default(), Domain::Boolean).unwrap();
    assert_eq!(c.outputs, ["cook", "light"]);
    // cook = timeLeft ∧ ¬doorOpen; light = doorOpen ∨ timeLeft.
    for row in 0..4usize {
        let (door, time) = (row & 2 != 0, row & 1 != 0);
        assert_eq!(c.answer(0, &[door, time]), time && !door, "cook at {row:b}");
        assert_eq!(c.answer(1, &[door, time]), door || time, "light at {row:b}");
        assert!(c.valid(&[door, time]));
    }
}
