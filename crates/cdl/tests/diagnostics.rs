//! A theory's diagnostics once checked: what the checker finds beyond the parser (labels,
//! priorities, declarations, inconsistent facts, unused inputs), how parse errors and checks
//! meet, and large files checked in a pipeline. One `check(input, expect)` per case; the
//! parser's own diagnostics are tested in crates/syntax.

use proclaim_cdl::{check as check_theory, load, Language};
use proclaim_syntax::{parse, render};

/// Every diagnostic of `input` in the short form `line:column: severity: message`, one a line.
fn diagnostics(input: &str, language: Language) -> String {
    let checked = check_theory(parse(input, language), input);
    checked
        .diagnostics
        .iter()
        .map(|d| d.short("t", input).trim_start_matches("t:").to_string() + "\n")
        .collect()
}

fn check(input: &str, expect: &str) {
    assert_eq!(
        diagnostics(input, Language::Dl),
        expect,
        "for input:\n{input}"
    );
}

fn check_dfl(input: &str, expect: &str) {
    assert_eq!(
        diagnostics(input, Language::Dfl),
        expect,
        "for input:\n{input}"
    );
}

#[test]
fn the_whole_language_parses() {
    check(
        "% a comment\n/* a block\ncomment */\nname{demo}.\ninput{a}. input{b, c, d}.\n\
         ignore{a, ~b}. ignore 2 of {b, c, d}. assert{a, b}.\n\
         Off: a => Offside. R2: {a, b} -> x. {} => y. => z. w ~> ~z. R4: a, b => {Offside}.\n\
         f. ~g. \\/{h, ~i}.\nOff > R2 > R4.\n\
         output{beta Offside, \"is off-side\"}. output{mu x}. output{y}.\n",
        // What a declared theory shows of itself: inputs nobody reads, a condition nothing
        // concludes.
        "5:20: warning: input `c` is read by no rule\n\
         5:23: warning: input `d` is read by no rule\n\
         7:52: warning: `w` is concluded by no rule and is no input or fact\n\
         9:1: warning: `Off > R2` changes nothing: they conclude `Offside` and `x`, which do not conflict\n\
         9:1: warning: `R2 > R4` changes nothing: they conclude `x` and `Offside`, which do not conflict\n",
    );
}

#[test]
fn every_problem_is_reported_at_once() {
    check(
        "a => b\nc => d.\nR1: a b => c.\nR2: x => y.\nR2: z => w.\nR1 > R9.\ne -> .\n",
        "2:1: error: unexpected `c`\n\
         3:7: error: unexpected `b`\n\
         5:1: error: rule label `R2` is used twice\n\
         6:6: error: no rule is labelled `R9`\n\
         7:6: error: unexpected `.`\n",
    );
}

#[test]
fn priority_cycles_name_their_rules() {
    check(
        "R1: => a. R2: => ~a. R3: => b.\nR1 > R2. R2 > R3. R3 > R1.\n",
        "1:1: error: priorities form a cycle among rules R1, R2, R3\n\
         2:10: warning: `R2 > R3` changes nothing: they conclude `~a` and `b`, which do not conflict\n\
         2:19: warning: `R3 > R1` changes nothing: they conclude `b` and `a`, which do not conflict\n",
    );
    check(
        "R1: => a. R1 > R1.",
        "1:11: error: rule `R1` is given priority over itself\n",
    );
}

#[test]
fn inconsistent_facts() {
    check(
        "a.\nb.\n~a.\n",
        "1:1: error: the facts are inconsistent: they prove both `a` and `~a`\n",
    );
    check(
        "\\/{a, b}.\n~a.\n~b.\n",
        "2:1: error: the facts are inconsistent: they prove both `~a` and `a`\n",
    );
}

#[test]
fn declarations_are_checked() {
    check("input{~a}. input{b}. input{b}.", "1:7: error: inputs are atoms, not negated literals\n1:28: error: `b` is declared as an input twice\n");
    check(
        "output{beta zz}. a.",
        "1:13: warning: output `zz` appears in no rule, fact or input\n",
    );
    check(
        "input{a}. ignore 3 of {a}.",
        "1:11: error: `ignore 3 of` names only 1 literals\n",
    );
    check(
        "name{a}. name{b}.",
        "1:10: error: the theory is named twice\n",
    );
    check(
        "\\/{a, ~a}.",
        "1:1: warning: this clause holds a literal and its complement, so it says nothing\n",
    );
}

#[test]
fn rendered_errors_show_the_line_a_caret_and_a_hint() {
    let source = "R1: => a.\nR1 > R9.\n";
    let checked = check_theory(parse(source, Language::Dl), source);
    let text = render(&checked.diagnostics, "demo.dl", source, false);
    assert!(text.contains("error: no rule is labelled `R9`"), "{text}");
    assert!(text.contains("demo.dl:2:6"), "{text}");
    assert!(text.contains("R1 > R9."), "{text}");
    assert!(text.contains("^^ undefined label"), "{text}");
    assert!(text.contains("hint:"), "{text}");
}

#[test]
fn a_label_used_twice_points_at_both_uses() {
    // Comments and indentation before either use, in both languages: the first use is found
    // through its rule, whose statement begins at the label.
    for (source, language) in [
        (
            "% first\n  R1: a => b.\nc.\n /* again */ R1: b => c.\n",
            Language::Dl,
        ),
        ("# first\n  R1: a => b\n>> c\n R1: b => c\n", Language::Dfl),
    ] {
        let checked = check_theory(parse(source, language), source);
        let places: Vec<(u32, Vec<u32>)> = checked
            .diagnostics
            .iter()
            .map(|d| {
                (
                    d.span.start,
                    d.related.iter().map(|(s, _)| s.start).collect(),
                )
            })
            .collect();
        let second = source.rfind("R1").unwrap() as u32;
        let first = source.find("R1").unwrap() as u32;
        assert_eq!(places, [(second, vec![first])], "{source:?}");
    }
}

#[test]
fn spindle_dfl() {
    check_dfl(
        "# a SPINdle theory\n>> bird\n>> -penguin, quaker\nr1: bird => fly\nr2: penguin -> -fly\nr3: p(x, y) ~> fly\nr2 > r1\n",
        "",
    );
    let theory = load(
        ">> bird\nr2: bird => fly\nr3: penguin => -fly\nr3 > r2\n",
        Language::Dfl,
    )
    .unwrap();
    assert_eq!(theory.rule_count(), 3);
    assert_eq!(theory.priorities().len(), 1);
}

/// A priority may come before the rules it names; priorities keep their file order whether they
/// are resolved as they are read (after their rules) or at the end (before them).
#[test]
fn priorities_before_and_after_their_rules() {
    let text = "r1 > r2\nr1: a => b\nr2: c => -b\nr3: d => -b\nr1 > r3\nr4: e => b\nr4 > r2\n";
    let theory = load(text, Language::Dfl).unwrap();
    let label = |id| theory.rule(id).label.unwrap();
    let pairs: Vec<(&str, &str)> = theory
        .priorities()
        .iter()
        .map(|&(w, l)| (label(w), label(l)))
        .collect();
    assert_eq!(pairs, [("r1", "r2"), ("r1", "r3"), ("r4", "r2")]);
    let resolved_at_once = load(&text[8..], Language::Dfl).unwrap();
    assert_eq!(resolved_at_once.priorities().len(), 2);
    check_dfl(
        "r1: a => b\nr2: c => -b\nr1 > r2\nr1 > r9\nr2 > r1 > r2\n",
        "1:1: error: priorities form a cycle among rules r1, r2\n4:6: error: no rule is labelled `r9`\n",
    );
}

#[test]
fn dl_and_dfl_of_a_benchmark_are_the_same_theory() {
    let family = proclaim_gen::Family::parse("levels", &[5]).unwrap();
    let mut dl = Vec::new();
    let mut dfl = Vec::new();
    family.write(&mut dl, proclaim_gen::Format::Dl).unwrap();
    family.write(&mut dfl, proclaim_gen::Format::Dfl).unwrap();
    let a = load(std::str::from_utf8(&dl).unwrap(), Language::Dl).unwrap();
    let b = load(std::str::from_utf8(&dfl).unwrap(), Language::Dfl).unwrap();
    let show = |t: &proclaim_cdl::Theory| {
        (0..t.rule_count() as u32)
            .map(|r| t.show_rule(r))
            .collect::<Vec<_>>()
    };
    assert_eq!(show(&a), show(&b));
    assert_eq!(a.priorities(), b.priorities());
}

#[test]
fn large_files_checked_in_a_pipeline_match_the_sequential_check() {
    // Over 1 MiB, so `check_source` parses on a second thread while it checks.
    let mut text = Vec::new();
    proclaim_gen::Family::parse("levels", &[60_000])
        .unwrap()
        .write(&mut text, proclaim_gen::Format::Dl)
        .unwrap();
    let mut text = String::from_utf8(text).unwrap();
    assert!(text.len() > 1 << 20);
    // Every statement that writes atoms, a third of the way in (the parser thread interns the
    // atoms in a pipeline, so each kind must hand over the atoms it writes).
    let third = text[..text.len() / 3].rfind('\n').unwrap() + 1;
    text.insert_str(
        third,
        "input{x1, x2}. input{y}. output{beta x1, \"d\"}. \\/{~x1, late}. ignore{x1}.\n\
         assert{y, ~x2}. fresh. r: fresh, x1 => ~late2.\n",
    );
    let sequential = |t: &str| check_theory(parse(t, Language::Dl), t);
    let good = proclaim_cdl::check_source(&text, Language::Dl);
    let expected = sequential(&text);
    assert_eq!(good.diagnostics, expected.diagnostics);
    let (a, b) = (good.theory.unwrap(), expected.theory.unwrap());
    assert_eq!(a.rule_count(), b.rule_count());
    assert_eq!(a.priorities(), b.priorities());
    assert_eq!(a.atom_count(), b.atom_count());
    for atom in (0..a.atom_count() as u32).map(proclaim_cdl::Atom) {
        assert_eq!(a.atom_name(atom), b.atom_name(atom));
    }
    for rule in (0..a.rule_count() as u32).step_by(997) {
        assert_eq!(a.show_rule(rule), b.show_rule(rule));
    }
    assert_eq!(format!("{:?}", a.inputs()), format!("{:?}", b.inputs()));
    assert_eq!(format!("{:?}", a.outputs()), format!("{:?}", b.outputs()));
    // Errors anywhere (a broken labelled rule, a priority naming it, an undefined label) are
    // reported the same way.
    text.insert_str(
        text.len() / 2,
        "Broken: a b => c.\nBroken > r1.\nr1 > Nowhere.\n",
    );
    let pipelined = proclaim_cdl::check_source(&text, Language::Dl);
    let expected = sequential(&text);
    assert!(pipelined.theory.is_none());
    assert_eq!(pipelined.diagnostics, expected.diagnostics);
    assert_eq!(
        pipelined.diagnostics.len(),
        2,
        "{:?}",
        pipelined.diagnostics
    );
}

#[test]
fn large_dfl_files_checked_in_a_pipeline_match_the_sequential_check() {
    // SPINdle's format goes through the same pipeline past 1 MiB.
    let mut text = Vec::new();
    proclaim_gen::Family::parse("tree", &[10, 3])
        .unwrap()
        .write(&mut text, proclaim_gen::Format::Dfl)
        .unwrap();
    let mut text = String::from_utf8(text).unwrap();
    assert!(text.len() > 1 << 20);
    let sequential = |t: &str| check_theory(parse(t, Language::Dfl), t);
    let good = proclaim_cdl::check_source(&text, Language::Dfl);
    let expected = sequential(&text);
    assert_eq!(good.diagnostics, expected.diagnostics);
    let (a, b) = (good.theory.unwrap(), expected.theory.unwrap());
    assert_eq!(a.rule_count(), b.rule_count());
    assert_eq!(a.atom_count(), b.atom_count());
    for rule in (0..a.rule_count() as u32).step_by(997) {
        assert_eq!(a.show_rule(rule), b.show_rule(rule));
    }
    let middle = text[..text.len() / 2].rfind('\n').unwrap() + 1;
    text.insert_str(middle, "Broken: a b => c\nBroken > r1\nr1 > Nowhere\n");
    let pipelined = proclaim_cdl::check_source(&text, Language::Dfl);
    let expected = sequential(&text);
    assert!(pipelined.theory.is_none());
    assert_eq!(pipelined.diagnostics, expected.diagnostics);
    assert!(!pipelined.diagnostics.is_empty());
}

#[test]
fn a_missing_dot_is_one_error_not_a_cascade() {
    // Before, the priority below also said "no rule is labelled `Doubt`".
    check(
        "Sure: a => b\nDoubt: c => ~b.\nDoubt > Sure.\n",
        "2:1: error: unexpected `Doubt`\n",
    );
}

#[test]
fn a_label_inside_a_statement_with_bad_characters_is_not_reported_again() {
    // The bad characters stop the whole statement, `Doubt`'s rule with it: one error.
    check(
        "Sure: a => b $ Doubt: c => ~b.\nDoubt > Sure.\n",
        "1:14: error: unexpected characters\n",
    );
}
