//! cdl.md §5 over random theories: the fast engine agrees with the reference prover on every
//! literal and algorithm; the hierarchy and consistency hold; parsing never panics.

use proclaim_cdl::{load, Algorithm, Engine, Language, Lit, ReferenceProver, Session};
use proptest::prelude::*;

const ATOMS: usize = 5;

fn lit_over(atoms: usize) -> impl Strategy<Value = String> {
    (0..atoms, any::<bool>()).prop_map(|(a, neg)| format!("{}a{a}", if neg { "~" } else { "" }))
}

/// A random theory as text: rules of every kind (with loops, since any atom may lead to any),
/// facts, clause facts and acyclic priorities, plus random input values.
fn theory() -> impl Strategy<Value = (String, Vec<(usize, Option<bool>)>)> {
    theory_over(ATOMS, 9)
}

/// Denser theories: more atoms and rules, so components with attacks inside grow larger.
fn dense_theory() -> impl Strategy<Value = (String, Vec<(usize, Option<bool>)>)> {
    theory_over(8, 15)
}

fn theory_over(
    atoms: usize,
    rules: usize,
) -> impl Strategy<Value = (String, Vec<(usize, Option<bool>)>)> {
    let lit = move || lit_over(atoms);
    let rule = (
        prop::collection::vec(lit(), 0..3),
        prop_oneof![3 => Just("=>"), 1 => Just("->"), 1 => Just("~>")],
        lit(),
    );
    (
        prop::collection::vec(rule, 1..rules),
        prop::collection::vec(lit(), 0..3),
        prop::collection::vec(prop::collection::vec(lit(), 2..4), 0..2),
        prop::collection::vec((0..rules, 0..rules), 0..rules),
        prop::collection::vec((0..atoms, prop::option::of(any::<bool>())), 0..3),
    )
        .prop_map(|(rules, facts, clauses, priorities, inputs)| {
            let mut text = String::new();
            for (i, (body, arrow, head)) in rules.iter().enumerate() {
                text += &format!("r{i}: {} {arrow} {head}.\n", body.join(", "));
            }
            for f in facts {
                text += &format!("{f}.\n");
            }
            for c in clauses {
                text += &format!("\\/{{{}}}.\n", c.join(", "));
            }
            for (a, b) in priorities {
                // Higher index beats lower: always acyclic.
                let (w, l) = (a.max(b), a.min(b));
                if w != l && w < rules.len() {
                    text += &format!("r{w} > r{l}.\n");
                }
            }
            (text, inputs)
        })
}

/// Theories shaped like the attack-cycle families (benchmarks.md): every atom has a default,
/// and atoms attack each other, often both ways (cliques, pairs), around a ring (one attack
/// each) or through a chain of support, with defeaters and priorities mixed in, so that the
/// structural shortcuts are taken, and refused when the shape is almost but not quite theirs.
fn attack_shaped_theory() -> impl Strategy<Value = (String, Vec<(usize, Option<bool>)>)> {
    let atoms = 2..7usize;
    atoms
        .prop_flat_map(|n| {
            let edge = (0..n, 0..n, 0..8u8);
            (
                Just(n),
                prop::collection::vec(edge, 1..3 * n),
                prop::collection::vec(any::<bool>(), n),
                prop::collection::vec((0..4 * n, 0..4 * n), 0..3),
                prop::collection::vec((0..n, prop::option::of(any::<bool>())), 0..2),
            )
        })
        .prop_map(|(n, edges, defaults, priorities, inputs)| {
            let mut text = String::new();
            let mut label = 0;
            let mut rule = |text: &mut String, body: &str, arrow: &str, head: String| {
                *text += &format!("r{label}: {body} {arrow} {head}.\n");
                label += 1;
            };
            for (i, &default) in defaults.iter().enumerate() {
                if default || i == 0 {
                    rule(&mut text, "", "=>", format!("a{i}"));
                }
            }
            for (from, to, shape) in edges {
                let (a, b) = (format!("a{from}"), format!("a{to}"));
                match shape {
                    // A mutual attack, the clique's and the pair's edge.
                    0..=2 => {
                        rule(&mut text, &a, "=>", format!("~{b}"));
                        rule(&mut text, &b, "=>", format!("~{a}"));
                    }
                    // One attack, as around a ring.
                    3 | 4 => rule(&mut text, &a, "=>", format!("~{b}")),
                    5 => rule(&mut text, &a, "~>", format!("~{b}")),
                    6 => rule(&mut text, &a, "=>", b),
                    _ => rule(
                        &mut text,
                        &format!("{a}, a{}", (to + 1) % n),
                        "=>",
                        format!("~{b}"),
                    ),
                }
            }
            for (x, y) in priorities {
                let (w, l) = (x.max(y), x.min(y));
                if w != l && w < label {
                    text += &format!("r{w} > r{l}.\n");
                }
            }
            (text, inputs)
        })
}

/// Theories heavy in two-literal clauses (chains, cycles and contradictions of implications,
/// whose resolvents the engine leaves implicit and the reference prover writes out), with a few
/// rules attacking and supporting their literals, some longer clauses and unit facts.
fn clause_heavy_theory() -> impl Strategy<Value = (String, Vec<(usize, Option<bool>)>)> {
    // Four atoms: the reference prover writes every resolvent out and searches them with a
    // history, which is exponential; six atoms pass too (5,000 cases checked by hand) but some
    // theories then take seconds each.
    let atoms = 4;
    let lit = move || lit_over(atoms);
    (
        prop::collection::vec((lit(), lit()), 1..9),
        prop::collection::vec(
            (
                prop::collection::vec(lit(), 0..2),
                prop_oneof![3 => Just("=>"), 1 => Just("->"), 1 => Just("~>")],
                lit(),
            ),
            0..5,
        ),
        prop::collection::vec(prop::collection::vec(lit(), 3..4), 0..2),
        prop::collection::vec(lit(), 0..2),
        prop::collection::vec((0..atoms, prop::option::of(any::<bool>())), 0..3),
    )
        .prop_map(|(binaries, rules, longer, facts, inputs)| {
            let mut text = String::new();
            for (a, b) in binaries {
                text += &format!("\\/{{{a}, {b}}}.\n");
            }
            for (i, (body, arrow, head)) in rules.iter().enumerate() {
                text += &format!("r{i}: {} {arrow} {head}.\n", body.join(", "));
            }
            for c in longer {
                text += &format!("\\/{{{}}}.\n", c.join(", "));
            }
            for f in facts {
                text += &format!("{f}.\n");
            }
            if rules.len() > 1 {
                text += &format!("r{} > r0.\n", rules.len() - 1);
            }
            (text, inputs)
        })
}

/// Rings of small random blocks (the pairs ring's shape, and rings almost of that shape): block
/// `j`'s atoms `bj_0…` have defaults and attack or support each other at random, and some of
/// them read block `j + 1`'s first atom (its entry), which the ring's composition relies on;
/// now and then a read skips to another atom of the next block, which is no ring.
fn block_ring_theory() -> impl Strategy<Value = (String, Vec<(usize, Option<bool>)>)> {
    (2..4usize, 1..3usize)
        .prop_flat_map(|(blocks, size)| {
            let inner = (0..size, 0..size, 0..4u8);
            let outer = (0..size, 0..size, 0..4u8, prop::bool::weighted(0.9));
            (
                Just((blocks, size)),
                prop::collection::vec(prop::collection::vec(inner, 0..2 * size), blocks),
                prop::collection::vec(prop::collection::vec(outer, 1..3), blocks),
            )
        })
        .prop_map(|((blocks, size), inner, outer)| {
            let mut text = String::new();
            let mut label = 0;
            let mut rule = |text: &mut String, body: String, shape: u8, head: String| {
                let (arrow, neg) = match shape {
                    0 | 1 => ("=>", "~"),
                    2 => ("~>", "~"),
                    _ => ("=>", ""),
                };
                *text += &format!("r{label}: {body} {arrow} {neg}{head}.\n");
                label += 1;
            };
            for j in 0..blocks {
                for a in 0..size {
                    text += &format!("=> b{j}_{a}.\n");
                }
                for &(from, to, shape) in &inner[j] {
                    rule(
                        &mut text,
                        format!("b{j}_{from}"),
                        shape,
                        format!("b{j}_{to}"),
                    );
                }
                let next = (j + 1) % blocks;
                for &(reader, other, shape, at_entry) in &outer[j] {
                    let read = if at_entry { 0 } else { other };
                    rule(
                        &mut text,
                        format!("b{next}_{read}"),
                        shape,
                        format!("b{j}_{reader}"),
                    );
                }
            }
            (text, vec![])
        })
}

/// Rings of layers of one or two atoms (the ladder's shape, with other conditions): every rule
/// for an atom of layer `j` reads only atoms of layer `j + 1`, with one or two antecedents, as
/// support, attack or defeater, now and then beaten by a priority.
fn layer_ring_theory() -> impl Strategy<Value = (String, Vec<(usize, Option<bool>)>)> {
    (2..5usize)
        .prop_flat_map(|layers| {
            let rule = (0..2usize, 0..2usize, any::<bool>(), 0..4u8);
            (
                prop::collection::vec(1..3usize, layers),
                prop::collection::vec(
                    (any::<bool>(), prop::collection::vec(rule, 1..3)),
                    2 * layers,
                ),
                prop::bool::weighted(0.3),
            )
        })
        .prop_map(|(mut sizes, atoms, priority)| {
            sizes[0] = 2;
            let layers = sizes.len();
            let mut text = String::new();
            let mut label = 0;
            for (j, &size) in sizes.iter().enumerate() {
                let next = (j + 1) % layers;
                let read = |a: usize| format!("l{next}_{}", a % sizes[next]);
                for a in 0..size {
                    let (default, rules) = &atoms[2 * j + a];
                    if *default {
                        text += &format!("=> l{j}_{a}.\n");
                    }
                    for &(x, y, two, shape) in rules {
                        let body = if two && x % sizes[next] != y % sizes[next] {
                            format!("{}, {}", read(x), read(y))
                        } else {
                            read(x)
                        };
                        let (arrow, neg) = match shape {
                            0 | 1 => ("=>", "~"),
                            2 => ("~>", "~"),
                            _ => ("=>", ""),
                        };
                        text += &format!("r{label}: {body} {arrow} {neg}l{j}_{a}.\n");
                        label += 1;
                    }
                }
            }
            if priority && label > 1 {
                text += &format!("r0 > r{}.\n", label - 1);
            }
            (text, vec![])
        })
}

/// The attack-cycle families at sizes the reference prover can still enumerate.
#[test]
fn attack_families_agree_with_the_reference_prover() {
    for (family, sizes) in [
        ("attack-ring", 3..=9),
        ("pairs-ring", 3..=5),
        ("priority-ring", 3..=5),
        ("defeater-ring", 3..=7),
        ("clique", 1..=7),
        ("ladder", 1..=3),
        ("clause-chain", 1..=6),
    ] {
        for size in sizes {
            let f = proclaim_gen::Family::parse(family, &[size]).unwrap();
            let mut text = Vec::new();
            f.write(&mut text, proclaim_gen::Format::Dl).unwrap();
            let text = String::from_utf8(text).unwrap();
            agree(&text, &[]).unwrap_or_else(|e| panic!("{f}: {e}"));
            let theory = load(&text, Language::Dl).unwrap();
            let mut session = Session::new(Engine::new(theory.clone()));
            for e in f.expected() {
                let alg = Algorithm::from_name(e.algorithm).unwrap();
                let lit = theory.lit(&e.literal).unwrap();
                assert_eq!(session.prove(alg, lit), e.proved, "{f}: {e}");
            }
        }
    }
}

/// The rings are decided at sizes where a search goal by goal is quadratic and runs out of its
/// default budget: by composition when their blocks are small (the pairs ring; the attack
/// ring's blocks are single goals), by bounds once the reads nothing depends on are dropped
/// (the priority ring: each `a(i+1)`'s attacker is beaten by its own supporter); the ladder,
/// whose paths double with every layer, by one pass over its layers per goal.
#[test]
fn rings_are_decided_within_the_default_budget() {
    for (family, size, searched) in [
        ("pairs-ring", 3000, false),
        ("attack-ring", 3001, false),
        ("priority-ring", 5000, true),
        ("ladder", 16, false),
    ] {
        let f = proclaim_gen::Family::parse(family, &[size]).unwrap();
        let mut text = Vec::new();
        f.write(&mut text, proclaim_gen::Format::Dl).unwrap();
        let theory = load(&String::from_utf8(text).unwrap(), Language::Dl).unwrap();
        let mut session = Session::new(Engine::new(theory.clone()));
        for lit in (0..2 * theory.atom_count() as u32).map(Lit) {
            session
                .decide(Algorithm::Beta, lit)
                .unwrap_or_else(|u| panic!("{f}: {u}"));
        }
        if !searched {
            assert_eq!(session.searched(), vec![], "{f}");
        }
        for e in f.expected() {
            let lit = theory.lit(&e.literal).unwrap();
            assert_eq!(session.prove(Algorithm::Beta, lit), e.proved, "{f}: {e}");
        }
    }
}

fn agree(text: &str, inputs: &[(usize, Option<bool>)]) -> Result<(), TestCaseError> {
    let Ok(theory) = load(text, Language::Dl) else {
        return Ok(()); // inconsistent facts: a load error, nothing to prove
    };
    let mut session = Session::new(Engine::new(theory.clone()));
    let mut facts = Vec::new();
    for &(a, value) in inputs {
        let Some(atom) = theory.atom(&format!("a{a}")) else {
            continue;
        };
        if session.set_input(atom, value).is_err() {
            continue;
        }
    }
    for atom in 0..theory.atom_count() as u32 {
        if let Some(v) = session.input(proclaim_cdl::Atom(atom)) {
            facts.push(Lit::new(proclaim_cdl::Atom(atom), !v));
        }
    }
    let reference = ReferenceProver::new(&theory, &facts).expect("session accepted these inputs");
    let lits = theory.atom_count() as u32 * 2;
    for alg in Algorithm::ALL {
        for l in (0..lits).map(Lit) {
            let fast = session.prove(alg, l);
            let slow = reference.prove(alg, l);
            prop_assert_eq!(fast, slow, "{} {} on\n{}", alg, theory.show(l), text);
        }
    }
    // Hierarchy: +μ ⇒ +α ⇒ (+π ∧ +β), (+π ∨ +β) ⇒ +δ.
    let strict_consistent = (0..lits / 2).all(|a| {
        !(session.prove(Algorithm::Mu, Lit(2 * a)) && session.prove(Algorithm::Mu, Lit(2 * a + 1)))
    });
    for l in (0..lits).map(Lit) {
        let [mu, pi, beta, alpha, delta] = Algorithm::ALL.map(|a| session.prove(a, l));
        prop_assert!(
            !mu || alpha,
            "mu without alpha: {}\n{}",
            theory.show(l),
            text
        );
        prop_assert!(!alpha || (pi && beta));
        prop_assert!(!(pi || beta) || delta);
        // cdl.md §5.3 as stated fails for atoms on a dependency cycle under the literal reading of
        // §4 (see `consistency_fails_on_a_self_attacking_loop` in reasoner.rs); it is checked for
        // the atoms no cycle passes through, where standard defeasible logic guarantees it.
        if strict_consistent && !on_cycle(&theory, l.atom()) {
            for alg in [
                Algorithm::Mu,
                Algorithm::Pi,
                Algorithm::Beta,
                Algorithm::Alpha,
            ] {
                let both = session.prove(alg, l) && session.prove(alg, l.complement());
                prop_assert!(
                    !both,
                    "{} proves {} and its complement\n{}",
                    alg,
                    theory.show(l),
                    text
                );
            }
        }
    }
    Ok(())
}

/// `explain` gives the reasons `prove` decides by: for β and π off any cycle (where the local
/// proof condition is the whole story), a goal is proved exactly when the explanation names a
/// supporting rule (or an implicit resolvent) and no attacker that stands; α and δ are proved
/// exactly when both (either) of the explained π and β parts are.
fn explanations_agree(text: &str, inputs: &[(usize, Option<bool>)]) -> Result<(), TestCaseError> {
    use proclaim_cdl::About;
    let Ok(theory) = load(text, Language::Dl) else {
        return Ok(());
    };
    let mut session = Session::new(Engine::new(theory.clone()));
    for &(a, value) in inputs {
        if let Some(atom) = theory.atom(&format!("a{a}")) {
            let _ = session.set_input(atom, value);
        }
    }
    let proved_goal = |e: &proclaim_cdl::Explanation| match e.about {
        About::Goal { proved, .. } => Some(proved),
        _ => None,
    };
    for l in (0..theory.atom_count() as u32 * 2).map(Lit) {
        for alg in Algorithm::ALL {
            let proved = session.prove(alg, l);
            let e = session.explain(alg, l, 1);
            prop_assert_eq!(
                proved_goal(&e),
                Some(proved),
                "{} {}\n{}",
                alg,
                theory.show(l),
                text
            );
            let decided_by_mu = e.children.iter().any(|c| c.text.starts_with("+mu"));
            match alg {
                Algorithm::Alpha | Algorithm::Delta => {
                    let parts: Vec<bool> = e.children.iter().filter_map(proved_goal).collect();
                    let want = if alg == Algorithm::Alpha {
                        parts.iter().all(|&p| p)
                    } else {
                        parts.iter().any(|&p| p)
                    };
                    prop_assert_eq!(parts.len(), 2);
                    prop_assert_eq!(proved, want, "{} {}\n{}\n{}", alg, theory.show(l), e, text);
                }
                Algorithm::Beta | Algorithm::Pi
                    if !decided_by_mu && !on_cycle(&theory, l.atom()) =>
                {
                    let supported = e.children.iter().any(|c| {
                        matches!(
                            c.about,
                            About::Rule {
                                role: "supports",
                                ..
                            }
                        ) || c.text.starts_with("supported by")
                    });
                    let standing = e.children.iter().any(|c| {
                        matches!(c.about, About::Rule { role: "stands", .. })
                            || (c.text.starts_with("attacker") && c.text.contains(" stands"))
                    });
                    prop_assert_eq!(
                        proved,
                        supported && !standing,
                        "{} {}\n{}\n{}",
                        alg,
                        theory.show(l),
                        e,
                        text
                    );
                }
                _ => {}
            }
        }
    }
    Ok(())
}

/// Whether an atom lies on a cycle of the atom dependency graph (an atom depends on the atoms
/// of the antecedents of every rule for it or its complement).
fn on_cycle(theory: &proclaim_cdl::Theory, start: proclaim_cdl::Atom) -> bool {
    let deps = |a: proclaim_cdl::Atom| -> Vec<proclaim_cdl::Atom> {
        theory
            .rules()
            .filter(|r| r.head.atom() == a)
            .flat_map(|r| r.body.iter().map(|l| l.atom()))
            .collect()
    };
    let mut seen = std::collections::HashSet::new();
    let mut work = deps(start);
    while let Some(a) = work.pop() {
        if a == start {
            return true;
        }
        if seen.insert(a) {
            work.extend(deps(a));
        }
    }
    false
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1500))]

    #[test]
    fn engine_agrees_with_the_reference_prover((text, inputs) in theory()) {
        agree(&text, &inputs)?;
    }

    #[test]
    fn engine_agrees_with_the_reference_prover_on_dense_theories((text, inputs) in dense_theory()) {
        agree(&text, &inputs)?;
    }

    #[test]
    fn engine_agrees_with_the_reference_prover_on_attack_cycles((text, inputs) in attack_shaped_theory()) {
        agree(&text, &inputs)?;
    }

    #[test]
    fn engine_agrees_with_the_reference_prover_on_rings_of_blocks((text, inputs) in block_ring_theory()) {
        agree(&text, &inputs)?;
    }

    #[test]
    fn engine_agrees_with_the_reference_prover_on_rings_of_layers((text, inputs) in layer_ring_theory()) {
        agree(&text, &inputs)?;
    }

    #[test]
    fn engine_agrees_with_the_reference_prover_on_clause_heavy_theories((text, inputs) in clause_heavy_theory()) {
        agree(&text, &inputs)?;
    }

    #[test]
    fn input_changes_agree_with_a_fresh_session(
        (text, first) in theory(),
        second in prop::collection::vec((0..ATOMS, prop::option::of(any::<bool>())), 1..4),
    ) {
        let Ok(theory) = load(&text, Language::Dl) else { return Ok(()) };
        let engine = std::sync::Arc::new(Engine::new(theory.clone()));
        let mut incremental = Session::new(engine.clone());
        let set = |s: &mut Session, values: &[(usize, Option<bool>)]| {
            for &(a, v) in values {
                if let Some(atom) = theory.atom(&format!("a{a}")) {
                    let _ = s.set_input(atom, v);
                }
            }
        };
        set(&mut incremental, &first);
        let lits = theory.atom_count() as u32 * 2;
        for alg in Algorithm::ALL {
            for l in (0..lits).map(Lit) {
                incremental.prove(alg, l);
            }
        }
        set(&mut incremental, &second);
        let mut fresh = Session::new(engine);
        for atom in 0..theory.atom_count() as u32 {
            let atom = proclaim_cdl::Atom(atom);
            fresh.set_input(atom, incremental.input(atom)).unwrap();
        }
        for alg in Algorithm::ALL {
            for l in (0..lits).map(Lit) {
                prop_assert_eq!(incremental.prove(alg, l), fresh.prove(alg, l), "{} {}\n{}", alg, theory.show(l), text);
            }
        }
    }

    #[test]
    fn explanations_give_the_reasons_prove_decides_by((text, inputs) in theory()) {
        explanations_agree(&text, &inputs)?;
    }

    #[test]
    fn parsing_random_bytes_never_panics(bytes in prop::collection::vec(any::<u8>(), 0..400)) {
        let text = String::from_utf8_lossy(&bytes);
        let parsed = proclaim_syntax::parse_dl(&text);
        let _ = proclaim_cdl::check(parsed, &text);
        let _ = proclaim_syntax::parse_dfl(&text);
        let _ = proclaim_syntax::parse_query(&text);
    }

    #[test]
    fn parsing_random_token_soup_never_panics(
        parts in prop::collection::vec(prop::sample::select(vec![
            "a", "~", "b", ".", ",", ":", "{", "}", "\\/", "/\\", "=>", "->", "~>", ">", "R1", "input",
            "output", "ignore", "assert", "name", "2", "of", "\"d\"", "beta", " ", "\n", "%c\n", "/*", "*/",
        ]), 0..60)
    ) {
        let text: String = parts.concat();
        let parsed = proclaim_syntax::parse_dl(&text);
        let checked = proclaim_cdl::check(parsed, &text);
        let rendered = proclaim_syntax::render(&checked.diagnostics, "soup.dl", &text, false);
        prop_assert!(checked.theory.is_some() || !rendered.is_empty());
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    /// The machine readers (labels, statements, native files, Qfsm XML, T/A pairs) never panic,
    /// and what they print reads back the same.
    #[test]
    fn machine_readers_never_panic(
        parts in prop::collection::vec(prop::sample::select(vec![
            "machine", "M", "state", "S", "T", "{", "}", "entry", "exit", "internal", "when", "->",
            "call", "code", "#", "7", "-", "x", "=", "==", "<", "(", ")", "&&", "||", "!", "~", ";",
            ",", "\"s\"", ":", " ", "\n", "\t", "int", "extern", "for", "post", "1.5", "/", "*",
            "<state code=\"1\">", "</state>", "<machine initialstate=\"1\">", "<transition>",
            "<from>1</from>", "<to>-1</to>", "<inputs>", "</inputs>", "&amp;", "|", "OnEntry",
        ]), 0..50)
    ) {
        let text: String = parts.concat();
        if let Ok(label) = proclaim_fsm::parse_label(&text) {
            prop_assert_eq!(proclaim_fsm::parse_label(&label.to_string()), Ok(label));
        }
        if let Ok(statements) = proclaim_fsm::code::parse_statements(&text) {
            let printed: Vec<String> = statements.iter().map(ToString::to_string).collect();
            prop_assert_eq!(proclaim_fsm::code::parse_statements(&printed.join(" ")), Ok(statements));
        }
        for m in proclaim_fsm::parse_machine("p.machine", &text).machines {
            let again = proclaim_fsm::parse_machine("p.machine", &proclaim_fsm::to_native(&m));
            prop_assert!(again.diagnostics.is_empty(), "{:?}", again.diagnostics);
        }
        let _ = proclaim_fsm::import_qfsm("p.fsm", &format!("<qfsmproject>{text}</qfsmproject>"), "p");
        let _ = proclaim_fsm::import_ta("p", "T", &text, "A", &text);
    }
}
