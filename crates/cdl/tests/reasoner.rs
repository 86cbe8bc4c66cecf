//! The worked cases of cdl.md §6, answered by the fast engine and the reference prover alike.

use proclaim_cdl::{
    load, Algorithm, Engine, Formula, Language, ProofOutcome, ReferenceProver, Session,
};

/// `expect` gives μ π β α δ in order, `+` proved, `-` not.
fn check(theory: &str, query: &str, expect: &str) {
    let theory = load(theory, Language::Dl).unwrap_or_else(|d| panic!("{theory}: {d:?}"));
    let formula = Formula::parse(query, &theory).unwrap();
    let reference = ReferenceProver::new(&theory, &[]).unwrap();
    let mut session = Session::new(Engine::new(theory));
    let mut got = String::new();
    let mut oracle = String::new();
    for alg in [
        Algorithm::Mu,
        Algorithm::Pi,
        Algorithm::Beta,
        Algorithm::Alpha,
        Algorithm::Delta,
    ] {
        got.push(if session.prove_formula(alg, &formula) {
            '+'
        } else {
            '-'
        });
        if let Formula::Lit(l) = formula {
            oracle.push(if reference.prove(alg, l) { '+' } else { '-' });
        }
    }
    assert_eq!(got, expect, "engine on `{query}` (mu pi beta alpha delta)");
    if !oracle.is_empty() {
        assert_eq!(oracle, expect, "reference prover on `{query}`");
    }
}

const TWEETY: &str = "R1: penguin -> bird. R2: bird => fly. R3: penguin => ~fly. R3 > R2.";

#[test]
fn tweety_a_bird() {
    check(&format!("bird. {TWEETY}"), "fly", "-++++");
}

#[test]
fn tweety_a_penguin() {
    let theory = format!("penguin. {TWEETY}");
    check(&theory, "~fly", "-++++");
    check(&theory, "fly", "-----");
}

const NIXON: &str = "quaker. republican. R1: quaker => pacifist. R2: republican => ~pacifist.";

#[test]
fn nixon() {
    check(NIXON, "pacifist", "-----");
    check(NIXON, "~pacifist", "-----");
}

#[test]
fn nixon_ranked() {
    check(&format!("{NIXON} R1 > R2."), "pacifist", "-++++");
}

#[test]
fn team_defeat() {
    check(
        "p1. p2. q1. q2. R1: p1 => p. R2: q1 => ~p. R3: p2 => p. R4: q2 => ~p. R1 > R2. R3 > R4.",
        "p",
        "-++++",
    );
}

#[test]
fn blocking_versus_propagating() {
    check(
        "R1: => a. R2: => b. R3: => c. R4: a => e. R5: b => d. R6: c => ~d. R7: d => ~e.",
        "e",
        "--+-+",
    );
}

#[test]
fn defeater() {
    let theory = "gap. p -> b. gap -> p. R3: b => f. R4: p => ~f. R5: gap ~> f. R5 > R4. R4 > R3.";
    check(theory, "f", "-----");
    check(theory, "~f", "-----");
}

#[test]
fn positive_loop() {
    check("R1: a => b. R2: b => a.", "a", "-----");
}

#[test]
fn loop_under_attack() {
    check(
        "R0: => p. R1: a => ~p. R2: b => a. R3: a => b.",
        "p",
        "-++++",
    );
}

#[test]
fn clause_axioms() {
    check("\\/{a, b}. ~a.", "b", "+++++");
    check("\\/{a, b}. ~a.", "a", "-----");
}

#[test]
fn contraposition() {
    let theory = "\\/{~p, q}. R3: => p. R4: => ~q.";
    for query in ["p", "~p", "q", "~q"] {
        check(theory, query, "-----");
    }
}

#[test]
fn strict_rules_are_not_contraposed() {
    check("p -> q. ~q.", "~p", "-----");
}

#[test]
fn clause_queries() {
    // A clause follows from the axioms even when neither member does.
    check("\\/{a, b}.", "\\/{a, b}", "+++++");
    check("\\/{a, b}.", "a", "-----");
    check("R1: => a. R2: c => d.", "\\/{a, c}", "-++++");
    check("x. R2: c => d.", "\\/{c, ~c}", "+++++");
    check("x. R1: => a.", "/\\{x, a}", "-++++");
}

#[test]
fn warnings_attack_but_never_support() {
    check("R1: => a. R2: ~> ~a.", "a", "-----");
    check("R1: ~> a.", "a", "-----");
    check("R1: => a. R2: ~> ~a. R1 > R2.", "a", "-++++");
}

#[test]
fn attack_inside_a_loop() {
    // a is supported outright; b needs a; b attacks a. Under β the attack on a is met again on
    // its own path and fails, so a and b hold; under π b is supported, so the attack stands.
    check("R1: => a. R2: b => ~a. R3: a => b.", "a", "--+-+");
    check("R1: => a. R2: b => ~a. R3: a => b.", "b", "--+-+");
}

#[test]
fn inputs_re_prove_only_what_depends_on_them() {
    let theory = load(
        "input{doorOpen}. input{timeLeft}. input{other}. \
         C1: timeLeft => cook. C2: doorOpen => ~cook. C2 > C1. \
         L1: doorOpen => light. L2: cook => light. L3: => ~light. L1 > L3. L2 > L3. \
         O1: other => busy.",
        Language::Dl,
    )
    .unwrap();
    let atom = |n| theory.atom(n).unwrap();
    let (door, time, other) = (atom("doorOpen"), atom("timeLeft"), atom("other"));
    let cook = theory.lit("cook").unwrap();
    let light = theory.lit("light").unwrap();
    let busy = theory.lit("busy").unwrap();
    let mut s = Session::new(Engine::new(theory));
    s.set_input(time, Some(true)).unwrap();
    s.set_input(door, Some(false)).unwrap();
    assert!(s.prove(Algorithm::Beta, cook));
    assert!(s.prove(Algorithm::Beta, light));
    s.set_input(other, Some(true)).unwrap();
    assert!(s.prove(Algorithm::Beta, busy));
    let before = s.evaluations();
    s.set_input(door, Some(true)).unwrap();
    assert!(!s.prove(Algorithm::Beta, cook));
    assert!(s.prove(Algorithm::Beta, light));
    assert!(s.prove(Algorithm::Beta, busy), "untouched by the door");
    let after_door = s.evaluations() - before;
    assert!(
        after_door > 0 && after_door < 12,
        "re-proved {after_door} goals"
    );
    s.set_input(time, None).unwrap();
    s.set_input(door, Some(false)).unwrap();
    assert!(
        !s.prove(Algorithm::Beta, cook),
        "unknown time left is not time left"
    );
    assert!(!s.prove(Algorithm::Beta, light));
    assert!(s.prove(Algorithm::Beta, light.complement()));
}

#[test]
fn an_input_that_contradicts_the_axioms_is_refused_and_nothing_changes() {
    let theory = load("input{a}. input{b}. \\/{~a, ~b}. R1: => c.", Language::Dl).unwrap();
    let (a, b) = (theory.atom("a").unwrap(), theory.atom("b").unwrap());
    let not_b = theory.lit("~b").unwrap();
    let mut s = Session::new(Engine::new(theory));
    s.set_input(a, Some(true)).unwrap();
    assert!(s.prove(Algorithm::Mu, not_b));
    let err = s.set_input(b, Some(true)).unwrap_err();
    assert_eq!(err.input, "b");
    assert_eq!(err.clause, "\\/{~a, ~b}");
    assert_eq!(s.input(b), None);
    assert!(s.prove(Algorithm::Mu, not_b));
}

#[test]
fn one_of_an_input_group_true_makes_the_others_false_or_changes_nothing() {
    let theory = load("input{a, b, c}. input{e}. \\/{b, e}.", Language::Dl).unwrap();
    let [a, b, c, e] = ["a", "b", "c", "e"].map(|n| theory.atom(n).unwrap());
    let mut s = Session::new(Engine::new(theory));
    s.set_input(b, Some(true)).unwrap();
    s.set_input(c, Some(true)).unwrap();
    assert_eq!((s.input(b), s.input(c)), (Some(false), Some(true)));
    s.set_input(e, Some(false)).unwrap_err(); // `\/{b, e}` with b false
    s.set_input(b, Some(true)).unwrap();
    s.set_input(e, Some(false)).unwrap();
    // a true would make b false, which the axiom forbids with e false: all or nothing.
    s.set_input(a, Some(true)).unwrap_err();
    assert_eq!(
        (s.input(a), s.input(b), s.input(c)),
        (Some(false), Some(true), Some(false))
    );
}

#[test]
fn explanations_name_supporters_and_attackers() {
    let theory = load(&format!("bird. penguin. {TWEETY}"), Language::Dl).unwrap();
    let fly = theory.lit("~fly").unwrap();
    let mut s = Session::new(Engine::new(theory));
    let text = s.explain(Algorithm::Beta, fly, 1).to_string();
    assert_eq!(
        text,
        "+beta ~fly\n  supported by R3: penguin => ~fly\n    +beta penguin\n      +mu penguin: definitely proved\n  attacker R2 is beaten by R3\n"
    );
    let text = s.explain(Algorithm::Beta, fly.complement(), 0).to_string();
    assert!(text.contains("attacker R3 stands"), "{text}");
}

#[test]
fn consistency_fails_on_a_self_attacking_loop() {
    // Found by the property test. Read literally, cdl.md §4 proves both a2 and ~a2 by β:
    // r4's attack on ~a2 needs ~a2, which is met again on its own proof path and fails, while
    // a2's proof needs ~a2 from a fresh history. This pins the normative reading (engine and
    // reference agree) until the spec decides otherwise; §5.3 holds off dependency cycles.
    let theory = "r3: => ~a2. r4: ~a2 => a2. r4 > r3.";
    check(theory, "a2", "--+-+");
    check(theory, "~a2", "--+-+");
}

#[test]
fn a_long_loop_with_an_attack_inside_is_settled_without_search() {
    // A 20,000-goal cycle with a default and an exception inside it: exact answers, in linear
    // time (top-down search alone is quadratic here), and no stack overflow.
    let mut text = String::from("rd: => a0. rx: a5 => ~a0.\n");
    for i in 0..20_000 {
        text += &format!("r{i}: a{i} => a{}.\n", (i + 1) % 20_000);
    }
    let theory = load(&text, Language::Dl).unwrap();
    let lits: Vec<_> = ["a0", "a7", "a19999", "~a0"]
        .iter()
        .map(|l| theory.lit(l).unwrap())
        .collect();
    let mut s = Session::new(Engine::new(theory));
    let answers: Vec<bool> = lits.iter().map(|&l| s.prove(Algorithm::Beta, l)).collect();
    assert_eq!(answers, [true, true, true, false]);
}

fn family(name: &str, size: u64) -> proclaim_cdl::Theory {
    let mut text = Vec::new();
    proclaim_gen::Family::parse(name, &[size])
        .unwrap()
        .write(&mut text, proclaim_gen::Format::Dl)
        .unwrap();
    load(std::str::from_utf8(&text).unwrap(), Language::Dl).unwrap()
}

#[test]
fn a_search_past_its_budget_is_undecided_and_says_where() {
    let theory = load(&proclaim_gen::crossed_ladder(), Language::Dl).unwrap();
    let t0 = theory.lit("t0").unwrap();
    let not_t0 = theory.lit("~t0").unwrap();
    let tight = proclaim_cdl::SearchLimits {
        steps: 1000,
        ..Default::default()
    };
    let mut s = Session::with_limits(Engine::new(theory), tight);
    let undecided = s.decide(Algorithm::Beta, t0).unwrap_err();
    assert_eq!(
        undecided.to_string(),
        "`beta t0` is undecided: its component of 24 goals, where rules attack each other in a \
         cycle, was not decided within the search budget of 1000 steps"
    );
    // Not proved, for whoever asks for a boolean; decided answers outside the cycle stay exact;
    // α is undecided with it, δ too (π does not prove t0 either).
    assert!(!s.prove(Algorithm::Beta, t0));
    assert_eq!(s.decide(Algorithm::Beta, not_t0), Ok(false));
    assert!(
        s.decide(Algorithm::Alpha, t0).is_ok(),
        "π refutes t0, so α is decided"
    );
    assert!(s.decide(Algorithm::Delta, t0).is_err());
    assert!(s
        .searched()
        .iter()
        .any(|c| c.undecided && c.goals.len() == 24));
    // A larger budget decides it, as the reference prover does.
    s.set_limits(proclaim_cdl::SearchLimits::default());
    assert_eq!(s.decide(Algorithm::Beta, t0), Ok(true));
}

#[test]
fn cliques_and_rings_are_decided_by_their_structure_without_search() {
    for (name, size, proved) in [
        ("clique", 41, true),
        ("clique", 40, false),
        ("attack-ring", 10_001, true),
        ("attack-ring", 10_000, false),
    ] {
        let theory = family(name, size);
        let a0 = theory.lit("a0").unwrap();
        let mut s = Session::new(Engine::new(theory));
        assert_eq!(s.decide(Algorithm::Beta, a0), Ok(proved), "{name}({size})");
        s.conclusions(Algorithm::Beta);
        assert_eq!(s.searched(), [], "{name}({size}) needed no search");
    }
    // Almost a clique: one attack taken away makes the graph asymmetric, and the search decides.
    let theory = load(
        "=> a0. => a1. => a2. a1 => ~a0. a2 => ~a0. a0 => ~a1. a2 => ~a1. a0 => ~a2.",
        Language::Dl,
    )
    .unwrap();
    let reference = ReferenceProver::new(&theory, &[]).unwrap();
    let mut s = Session::new(Engine::new(theory.clone()));
    for l in (0..theory.atom_count() as u32 * 2).map(proclaim_cdl::Lit) {
        assert_eq!(
            s.prove(Algorithm::Beta, l),
            reference.prove(Algorithm::Beta, l),
            "{}",
            theory.show(l)
        );
    }
}

/// Every literal's answer at once (`Session::answers`, what `prove` with no query prints) is
/// each literal's answer asked alone in a fresh session, on generated theories of several
/// families under every algorithm, and on a cycle the search leaves undecided.
#[test]
fn every_answer_at_once_equals_each_asked_alone() {
    let verdict = |answer: Result<bool, proclaim_cdl::Undecided>| match answer {
        Ok(true) => ProofOutcome::Proved,
        Ok(false) => ProofOutcome::NotProved,
        Err(_) => ProofOutcome::Undecided,
    };
    let tight = proclaim_cdl::SearchLimits {
        steps: 1000,
        ..Default::default()
    };
    let mut cases: Vec<(String, proclaim_cdl::Theory, proclaim_cdl::SearchLimits)> = [
        ("chain", vec![30]),
        ("circle", vec![30]),
        ("teams", vec![3]),
        ("tree", vec![4, 3]),
        ("dag", vec![10, 3]),
        ("levels-", vec![10]),
        ("mix", vec![3, 2, 4]),
        ("attack-ring", vec![31]),
        ("pairs-ring", vec![12]),
        ("clique", vec![9]),
        ("ladder", vec![4]),
        ("clause-chain", vec![20]),
    ]
    .into_iter()
    .map(|(name, sizes)| {
        let mut text = Vec::new();
        proclaim_gen::Family::parse(name, &sizes)
            .unwrap()
            .write(&mut text, proclaim_gen::Format::Dl)
            .unwrap();
        let theory = load(std::str::from_utf8(&text).unwrap(), Language::Dl).unwrap();
        (name.to_string(), theory, Default::default())
    })
    .collect();
    let ladder = load(&proclaim_gen::crossed_ladder(), Language::Dl).unwrap();
    cases.push(("crossed ladder, tight budget".into(), ladder, tight));
    for (name, theory, limits) in cases {
        let engine = std::sync::Arc::new(Engine::new(theory));
        let lits = (0..engine.theory().atom_count() as u32 * 2).map(proclaim_cdl::Lit);
        for alg in Algorithm::ALL {
            let at_once = Session::with_limits(engine.clone(), limits).answers(alg);
            let alone: Vec<ProofOutcome> = lits
                .clone()
                .map(|l| verdict(Session::with_limits(engine.clone(), limits).decide(alg, l)))
                .collect();
            assert_eq!(at_once, alone, "{name}, {alg}");
        }
        let undecided = Session::with_limits(engine.clone(), limits)
            .answers(Algorithm::Beta)
            .contains(&ProofOutcome::Undecided);
        assert_eq!(undecided, name.contains("tight"), "{name}");
    }
}
