//! What cannot be compiled is refused with a reason, never guessed.

use proclaim_cdl::{load, Language, SearchLimits};
use proclaim_compile::{compile, CompileError, Domain};

#[test]
fn an_answer_undecided_within_the_budget_is_refused_naming_its_row() {
    // The crossed ladder's attack cycle needs more than a thousand search steps.
    let text = format!(
        "{}\ninput{{gate}}.\nGated: gate => t0.\noutput{{beta t0}}.\n",
        proclaim_gen::crossed_ladder()
    );
    let theory = load(&text, Language::Dl).unwrap();
    let tight = SearchLimits {
        steps: 1000,
        ..Default::default()
    };
    let error = compile(&theory, tight, Domain::Boolean).unwrap_err();
    let CompileError::Undecided { output, row, .. } = &error else {
        panic!("not refused as undecided: {error}");
    };
    assert_eq!(output, "t0");
    assert_eq!(row, &["gate=false"]);
    assert!(
        error.to_string().contains("never guesses"),
        "the message says why: {error}"
    );
    // With the default budget the same theory compiles.
    let compiled = compile(&theory, SearchLimits::default(), Domain::Boolean).unwrap();
    assert_eq!(compiled.outputs, ["t0"]);
}

#[test]
fn too_many_inputs_are_refused() {
    let inputs: String = (0..21).map(|i| format!("input{{i{i}}}.\n")).collect();
    let theory = load(&format!("{inputs}R: i0 => c.\n"), Language::Dl).unwrap();
    assert_eq!(
        compile(&theory, SearchLimits::default(), Domain::Boolean).unwrap_err(),
        CompileError::TooManyInputs {
            variables: 21,
            limit: 20
        }
    );
    let theory = load("input{a}. input{b}. input{c}. input{d}. input{e}. input{f}. input{g}. input{h}. input{i}. input{j}. input{k}. R: a => z.", Language::Dl).unwrap();
    assert!(matches!(
        compile(&theory, SearchLimits::default(), Domain::Ternary),
        Err(CompileError::TooManyInputs { variables: 22, .. })
    ));
}

#[test]
fn clause_facts_are_refused_where_a_behaviour_would_run_them_and_groups_compile() {
    let grouped = load("input{a, b}. R: a => c.", Language::Dl).unwrap();
    let compiled = compile(&grouped, SearchLimits::default(), Domain::Ternary).unwrap();
    // Variables (a known, a true, b known, b true): both true is no state a run reaches, since
    // setting one true makes the other false; one true and the other unknown or false is.
    assert!(!compiled.valid(&[true, true, true, true]));
    assert!(compiled.valid(&[true, true, false, false]));
    assert!(compiled.valid(&[true, true, true, false]));
    assert!(compiled.answer(0, &[true, true, true, false]), "c from a");
    assert!(
        !compiled.answer(0, &[true, false, true, true]),
        "b alone proves nothing"
    );
    let axiom = load("input{a}. input{b}. \\/{~a, b}. R: a => c.", Language::Dl).unwrap();
    let error = compile(&axiom, SearchLimits::default(), Domain::Ternary).unwrap_err();
    assert!(error.to_string().contains("clause fact"), "{error}");
    // Over the truth table's rows both compile.
    assert!(compile(&grouped, SearchLimits::default(), Domain::Boolean).is_ok());
    assert!(compile(&axiom, SearchLimits::default(), Domain::Boolean).is_ok());
}
