//! Parameters and outcomes: what a machine's file declares and its own lowering
//! (`native/interface.rs`), then what linking the machines of a behaviour makes of starts and
//! of labels reading outcomes (`link.rs`), each as `check(input, expect)`.

use proclaim_fsm::{link, parse_machine, to_native, Expr, Launch, Machine};

const DIVE: &str = "machine Dive\nparam side: int\noutcome saved, conceded\ninitial AIM\n\nstate AIM {\n    when side < 0 -> LEFT\n    when TRUE -> RIGHT\n}\n\nstate LEFT {\n    entry {\n        post(\"Motion\", side);\n    }\n    when held -> SAVED\n    when TRUE -> GONE\n}\n\nstate RIGHT {\n}\n\nstate SAVED {\n    outcome saved\n}\n\nstate GONE {\n    entry {\n        Say: goal\n    }\n    outcome conceded\n}\n";

/// Reads one machine file: `expect` is its errors, one a line (else its warnings), or (none)
/// the lowered machine's states: each state's OnEntry and labels as they run.
fn check(input: &str, expect: &str) {
    let read = parse_machine("m.machine", input);
    let errors = read
        .diagnostics
        .iter()
        .any(|d| d.severity == proclaim_fsm::Severity::Error);
    let got = if read.diagnostics.is_empty() {
        lowered(&read.machines[0])
    } else {
        read.diagnostics
            .iter()
            .filter(|d| !errors || d.severity == proclaim_fsm::Severity::Error)
            .map(|d| d.to_string() + "\n")
            .collect()
    };
    assert_eq!(got, expect, "input:\n{input}");
}

fn lowered(m: &Machine) -> String {
    let mut out = String::new();
    for s in &m.states {
        let entry: Vec<String> = s.on_entry.iter().map(action).collect();
        out += &format!("{}: [{}]", s.name, entry.join(" "));
        for t in m.outgoing(s.id) {
            out += &format!(
                " {} ->{}",
                t.label,
                m.state(t.target).map_or("?", |t| &t.name)
            );
        }
        out.push('\n');
    }
    out
}

fn action(a: &proclaim_fsm::Action) -> String {
    match a {
        proclaim_fsm::Action::Post { ty, content } => format!("{ty}: {content};"),
        proclaim_fsm::Action::Statement(s) => s.to_string(),
        other => format!("{other:?}"),
    }
}

#[test]
fn a_machine_reads_its_parameters_and_announces_its_outcomes_as_globals() {
    check(
        DIVE,
        "AIM: [] Dive_side < 0 ->LEFT TRUE ->RIGHT\n\
         LEFT: [post(\"Motion\", Dive_side);] held ->SAVED TRUE ->GONE\n\
         RIGHT: []\n\
         SAVED: [Dive_saved = 1;]\n\
         GONE: [Say: goal; Dive_conceded = 1;]\n",
    );
}

#[test]
fn what_a_file_cannot_declare_is_refused_where_it_is_written() {
    let m = |top: &str, body: &str| format!("machine Dive\n{top}\nstate A {{\n{body}\n}}\n");
    check(
        &m("param side", ""),
        "m.machine:2: error: `param side`: a parameter is `param NAME: TYPE`, as in `param side: int`\n",
    );
    check(
        &m("param side: vector", ""),
        "m.machine:2: error: `vector` is no type a parameter can have: int, bool, char, float or double\n",
    );
    check(
        &m("param side: int\nparam side: int", ""),
        "m.machine:3: error: `side` is declared twice (a parameter and an outcome become one global, `Dive_side`)\n",
    );
    check(
        &m("outcome saved, 2x", ""),
        "m.machine:2: error: `2x` cannot name an outcome: letters, digits and `_`, not first a digit (`outcome saved, missed`)\n",
    );
    check(
        &m("outcome saved", "    outcome savd"),
        "m.machine:4: error: `savd` is not an outcome of this machine; did you mean `saved`?\n",
    );
    check(
        &m("outcome saved", "    when TRUE -> A\n    outcome saved"),
        "m.machine:5: error: state `A` announces outcome `saved`, so it is final: it can have no transitions and hold no states\n",
    );
    check(
        &m("param side: int", "    entry {\n        side = 2;\n    }"),
        "m.machine:5: error: `side` is a parameter of `Dive`: whoever starts it sets it, so the machine cannot set or declare it (copy it to a variable of its own: `int s; s = side;`)\n",
    );
    check(
        &m("param side: int\noutcome up", "    entry {\n        Dive_side = 2;\n        Dive_up = 1;\n    }"),
        "m.machine:6: error: `Dive_side` is what parameter `side` becomes: whoever starts `Dive` sets it\n\
         m.machine:7: error: `Dive_up` is outcome `up`: a final state announces it (`outcome up`), nothing sets it\n",
    );
    // A declaration ends at a comment or at its state's `}`; a posting that only looks like a
    // start is a posting.
    check(
        "machine Dive\nparam side: int // which way\noutcome down // lying\nstate A { outcome down }\n",
        "A: [Dive_down = 1;]\n",
    );
    check(
        "machine M\nstate A {\n    entry {\n        LEDS: On(red)\n    }\n}\n",
        "A: [LEDS: On(red);]\n",
    );
    check(
        "machine Dive\noutcome up, down\nstate A { outcome up }\n",
        "m.machine:2: warning: outcome `down` is announced by no state (a final state says `outcome down`), so whoever waits on it waits for ever\n",
    );
    check(
        &m("param true: bool\noutcome", ""),
        "m.machine:2: error: `true` cannot name a parameter: letters, digits and `_`, not first a digit, and no truth value\n\
         m.machine:3: error: `outcome` names the outcomes a final state can announce: `outcome saved, missed`\n",
    );
    check(
        &m("outcome up, down", "    outcome up, down"),
        "m.machine:4: error: state `A` announces one outcome, by its name (`outcome landed`)\n",
    );
    check(
        &m("param side: int", "    entry {\n        extern side;\n    }"),
        "m.machine:5: error: `side` is a parameter of `Dive`: whoever starts it sets it, so the machine cannot set or declare it (copy it to a variable of its own: `int s; s = side;`)\n",
    );
    // `outcome` and `param` are names where a name is wanted.
    check(
        "machine M\ninitial outcome\nstate outcome {\n    when param -> param\n}\nstate param {\n}\n",
        "outcome: [] param ->param\nparam: []\n",
    );
}

#[test]
fn a_machine_with_parameters_and_outcomes_is_written_as_it_was_read() {
    let read = parse_machine("m.machine", DIVE);
    assert!(read.diagnostics.is_empty(), "{:?}", read.diagnostics);
    let text = to_native(&read.machines[0]);
    assert_eq!(text, DIVE);
}

/// A machine's text, whether it starts with the behaviour, and the manifest's parameters.
type Entry<'a> = (&'a str, bool, &'a [(&'a str, i64)]);

/// Links `machines`: the problems, one a line, then each machine's states as they run.
fn linked(machines: &[Entry<'_>], expect: &str) {
    let mut read: Vec<Machine> = machines
        .iter()
        .map(|(text, _, _)| {
            let r = parse_machine("m.machine", text);
            assert!(r.diagnostics.is_empty(), "{:?}", r.diagnostics);
            r.machines[0].clone()
        })
        .collect();
    let launches: Vec<Launch> = machines
        .iter()
        .map(|(_, start, params)| Launch {
            start: *start,
            params: params
                .iter()
                .map(|(n, v)| (n.to_string(), Expr::Int(*v)))
                .collect(),
        })
        .collect();
    let problems = link(&mut read, &launches);
    let mut got: String = problems
        .iter()
        .map(|p| {
            format!(
                "{} line {:?}: {}\n",
                read[p.machine].name, p.line, p.message
            )
        })
        .collect();
    for m in &read {
        got += &format!("-- {}\n{}", m.name, lowered(m));
    }
    assert_eq!(got, expect);
}

const KEEPER: &str = "machine Keeper\nstate GUARD {\n    entry {\n        Dive: restart(side = -1)\n    }\n    when Dive.saved -> CHEER\n}\nstate CHEER {\n}\n";

#[test]
fn a_start_gives_the_parameters_and_clears_the_outcomes_and_a_label_reads_one() {
    let dive = DIVE;
    linked(
        &[(KEEPER, true, &[]), (dive, false, &[])],
        "-- Keeper\n\
         GUARD: [Dive_side = -1; Dive_saved = 0; Dive_conceded = 0; Dive: restart;] Dive_saved ->CHEER\n\
         CHEER: []\n\
         -- Dive\n\
         AIM: [Dive_saved = 0; Dive_conceded = 0;] Dive_side < 0 ->LEFT TRUE ->RIGHT\n\
         LEFT: [post(\"Motion\", Dive_side);] held ->SAVED TRUE ->GONE\n\
         RIGHT: []\n\
         SAVED: [Dive_saved = 1;]\n\
         GONE: [Say: goal; Dive_conceded = 1;]\n",
    );
}

#[test]
fn what_does_not_fit_between_machines_is_said_where() {
    let only = |keeper: &str, dive_starts: bool, params: &[(&str, i64)]| {
        let mut read = vec![
            parse_machine("k", keeper).machines[0].clone(),
            parse_machine("d", DIVE).machines[0].clone(),
        ];
        let launches = [
            Launch {
                start: true,
                params: Vec::new(),
            },
            Launch {
                start: dive_starts,
                params: params
                    .iter()
                    .map(|(n, v)| (n.to_string(), Expr::Int(*v)))
                    .collect(),
            },
        ];
        link(&mut read, &launches)
            .into_iter()
            .map(|p| format!("{:?}: {}", p.line, p.message))
            .collect::<Vec<_>>()
    };
    let keeper = |entry: &str, label: &str| -> String {
        format!("machine Keeper\nstate GUARD {{\n    entry {{\n        {entry}\n    }}\n    when {label} -> GUARD\n}}\n")
    };
    let on = "`Dive` takes parameters or announces outcomes: start it with `Dive: restart(…)` (`On` does nothing to a machine already running, which would then run with other arguments, or keep an outcome its caller waits on)";
    assert_eq!(
        only(&keeper("Dive: On(side = 1)", "TRUE"), false, &[]),
        [format!("Some(2): {on}")]
    );
    assert_eq!(
        only(&keeper("Dive: restart", "Dive.saved"), false, &[]),
        ["Some(2): `Dive` takes side: start it with `Dive: restart(side = …)`"]
    );
    assert_eq!(
        only(&keeper("Dive: restart(sde = 1)", "Dive.savd"), false, &[]),
        [
            "Some(2): `Dive` has no parameter `sde`; did you mean `side`?",
            "Some(2): `Dive` takes side: start it with `Dive: restart(side = …)`",
            "Some(6): `Dive.savd`: `Dive` has no outcome `savd`; did you mean `Dive.saved`?",
        ]
    );
    assert_eq!(
        only(
            &keeper("Dive: restart(side = \"left\")", "TRUE"),
            false,
            &[]
        ),
        ["Some(2): `Dive`'s `side` is int, which `\"left\"` is not"]
    );
    assert_eq!(
        only(&keeper("Dive: restart(side = 1", "TRUE"), false, &[]),
        ["Some(2): `Dive: …`: `restart(side = 1`: the arguments of `restart` end with `)`"]
    );
    assert_eq!(
        only(&keeper("Dive: suspend(side = 1)", "TRUE"), false, &[]),
        ["Some(2): `Dive: suspend(side = 1)`: only `restart` gives a machine its parameters"]
    );
    assert_eq!(
        only(&keeper("restart(\"Dive\");", "TRUE"), false, &[]),
        ["Some(2): `Dive` takes parameters, which a statement cannot give: restart it on a line of its own, `Dive: restart(…)`"]
    );
    assert_eq!(
        only(&keeper("post(\"Dive\", \"restart(side = 1)\");", "TRUE"), false, &[]),
        ["Some(2): `Dive`: arguments are given on a line of its own, `Dive: restart(…)`, not by a statement"]
    );
    assert_eq!(
        only(&keeper("start(\"Dive\");", "TRUE"), false, &[]),
        ["Some(2): `Dive` takes parameters or announces outcomes: start it with `Dive: restart(…)` (`On` does nothing to a machine already running)"]
    );
    assert_eq!(
        only(&keeper("Keeper: restart(x = 1)", "TRUE"), false, &[]),
        ["Some(2): `Keeper: restart(x = 1)`: `Keeper` takes no parameters"]
    );
    assert_eq!(
        only(&keeper("Dive_side = 3;", "TRUE"), false, &[]),
        ["Some(2): `Keeper` sets `Dive_side`, the global that `Dive`'s `side` becomes: call the variable something else"]
    );
    assert_eq!(
        only(&keeper("x = 1;", "TRUE"), true, &[]),
        ["None: `Dive` starts with the behaviour and takes side: give them in its `[[machine]]` entry (`params = { side = … }`), or start it from a machine with `start = false`"]
    );
    assert_eq!(
        only(&keeper("Dive: restart(side = 1)", "TRUE"), true, &[("side", 2)]),
        ["None: `Dive` is given its parameters by the manifest and by `Keeper`, which starts it: give them in one place"]
    );
    assert_eq!(
        only(&keeper("x = 1;", "TRUE"), false, &[("side", 2), ("power", 1)]),
        [
            "None: the manifest gives `Dive` a parameter `power` it does not declare",
            "None: the manifest gives `Dive` parameters but starts it with `start = false`: whoever starts it gives them (`Dive: restart(…)`)",
        ]
    );
}

/// An argument reads the starting machine's own parameters and outcomes as the globals they
/// are: a machine that restarts itself with what it was given passes it on.
#[test]
fn an_argument_reads_the_callers_parameters_as_its_code_does() {
    let relay = "machine Relay\nparam k: int\noutcome up\nstate A {\n    entry {\n        Relay: restart(k = k + 1)\n    }\n    when Relay.up -> B\n}\nstate B {\n    outcome up\n}\n";
    linked(
        &[(relay, false, &[])],
        "-- Relay\n\
         A: [Relay_up = 0; Relay_k = Relay_k + 1; Relay_up = 0; Relay: restart;] Relay_up ->B\n\
         B: [Relay_up = 1;]\n",
    );
}

#[test]
fn the_manifests_parameters_are_set_first_as_a_launched_machine_starts() {
    linked(
        &[(DIVE, true, &[("side", 1)])],
        "-- Dive\n\
         AIM: [Dive_side = 1; Dive_saved = 0; Dive_conceded = 0;] Dive_side < 0 ->LEFT TRUE ->RIGHT\n\
         LEFT: [post(\"Motion\", Dive_side);] held ->SAVED TRUE ->GONE\n\
         RIGHT: []\n\
         SAVED: [Dive_saved = 1;]\n\
         GONE: [Say: goal; Dive_conceded = 1;]\n",
    );
}

#[test]
fn a_machine_with_outcomes_only_restarted_by_a_statement_has_them_cleared_first() {
    let flag = "machine Flag\noutcome up\nstate RAISE {\n    outcome up\n}\n";
    let caller = "machine Caller\nstate GO {\n    entry {\n        restart(\"Flag\");\n    }\n    when Flag.up -> GO\n}\n";
    linked(
        &[(caller, true, &[]), (flag, false, &[])],
        "-- Caller\n\
         GO: [Flag_up = 0; restart(\"Flag\");] Flag_up ->GO\n\
         -- Flag\n\
         RAISE: [Flag_up = 0; Flag_up = 1;]\n",
    );
}

/// In a chart, the manifest's parameters are set before the composites' OnEntry (which may read
/// them), and the outcomes cleared after it, before the initial state's own.
#[test]
fn a_launched_charts_parameters_come_before_its_composites_entry() {
    let a = "machine A\nparam k: int\noutcome up\ninitial P\nstate P {\n    entry {\n        B: restart(n = k)\n    }\n    when B.fine -> Q\n    state X {\n        entry {\n            Log: in X\n        }\n        when TRUE -> Y\n    }\n    state Y {\n        outcome up\n    }\n}\nstate Q {\n}\n";
    let b = "machine B\nparam n: int\noutcome fine\nstate S {\n    when n > 0 -> T\n}\nstate T {\n    outcome fine\n}\n";
    linked(
        &[(a, true, &[("k", 2)]), (b, false, &[])],
        "-- A\n\
         P.X: [A_k = 2; B_n = A_k; B_fine = 0; B: restart; A_up = 0; Log: in X;] TRUE ->P.Y B_fine ->Q\n\
         P.Y: [A_up = 1;] B_fine ->Q\n\
         Q: []\n\
         -- B\n\
         S: [B_fine = 0;] B_n > 0 ->T\n\
         T: [B_fine = 1;]\n",
    );
}

/// What the first review's second round found: an outcome set by hand (through its dotted name,
/// or its global in a transition's own actions), two parameters lowered to one global, and a
/// machine restarting itself with arguments that read what an earlier one set.
#[test]
fn outcomes_are_only_announced_and_globals_are_each_ones_own() {
    let problems = |texts: &[&str]| -> Vec<String> {
        let mut read: Vec<Machine> = texts
            .iter()
            .map(|t| {
                let r = parse_machine("m", t);
                assert!(!r.has_errors(), "{:?}", r.diagnostics);
                r.machines[0].clone()
            })
            .collect();
        let launches = vec![
            Launch {
                start: true,
                params: Vec::new()
            };
            read.len()
        ];
        link(&mut read, &launches)
            .into_iter()
            .map(|p| format!("{} {:?}: {}", read[p.machine].name, p.line, p.message))
            .collect()
    };
    let flag = "machine Flag\noutcome up\nstate A {\n    outcome up\n}\n";
    assert_eq!(
        problems(&[flag, "machine C\nstate S {\n    entry {\n        Flag.up = 1;\n    }\n}\n"]),
        ["C Some(2): `Flag.up = …`: `Flag`'s outcome `up` is announced by its final states (`outcome up`), never set"]
    );
    assert_eq!(
        problems(&[flag, "machine C\nstate S {\n    when go -> S {\n        Flag_up = 1;\n    }\n}\n"]),
        ["C Some(3): `C` sets `Flag_up`, the global that `Flag`'s `up` becomes: call the variable something else"]
    );
    assert_eq!(
        problems(&[
            "machine Dive\nparam left_side: int\nstate A {\n}\n",
            "machine Dive_left\nparam side: int\nstate A {\n}\n",
        ]),
        [
            "Dive None: `Dive` starts with the behaviour and takes left_side: give them in its `[[machine]]` entry (`params = { left_side = … }`), or start it from a machine with `start = false`",
            "Dive_left None: `Dive_left` starts with the behaviour and takes side: give them in its `[[machine]]` entry (`params = { side = … }`), or start it from a machine with `start = false`",
            "Dive_left Some(2): `Dive_left`'s `side` and `Dive`'s `left_side` both become the global `Dive_left_side`: rename one",
        ]
    );
    let swap = "machine S\nparam a: int\nparam b: int\nstate A {\n    entry {\n        S: restart(a = b, b = a)\n    }\n}\n";
    let found = problems(&[swap]);
    assert!(
        found.contains(&"S Some(4): `S: restart(…)`: the argument for `b` reads `S_a`, which an argument before it has already set: copy them to variables of the machine's own first".to_string()),
        "{found:?}"
    );
}

/// Every way into a chart's initial state clears its outcomes (a flat state for each set of
/// composites a move enters): back at A from M beside it, which enters no composite, as from
/// outside G, which enters G again.
#[test]
fn every_arrival_in_the_initial_state_clears_the_outcomes() {
    let dive = "machine Dive\noutcome landed\ninitial G\nstate G {\n    entry {\n        int n = 0;\n    }\n    initial A\n    when again -> B\n    state A {\n        when go -> L\n        when turn -> M\n    }\n    state M {\n        when back -> A\n    }\n    state L {\n        outcome landed\n    }\n}\nstate B {\n    when back -> A\n}\n";
    let mut read = vec![parse_machine("m", dive).machines[0].clone()];
    assert!(link(
        &mut read,
        &[Launch {
            start: true,
            params: Vec::new()
        }]
    )
    .is_empty());
    let arrivals: Vec<String> = read[0]
        .states
        .iter()
        .filter(|s| s.name == "G.A")
        .map(|s| s.on_entry.iter().map(action).collect::<Vec<_>>().join(" "))
        .collect();
    assert_eq!(
        arrivals,
        ["int n = 0; Dive_landed = 0;", "Dive_landed = 0;"]
    );
}

/// The editor edits a machine with parameters and outcomes, and refuses to give a state that
/// announces an outcome a transition, saying why.
#[test]
fn the_editor_keeps_a_final_state_that_announces_an_outcome_final() {
    use proclaim_fsm::edit::{edit_native, view_native, Edit};
    let (states, _) = view_native(DIVE).expect("the dive is edited");
    let saved = states.iter().position(|s| s.name == "SAVED").unwrap();
    let refused = edit_native(
        "Dive.machine",
        DIVE,
        &Edit::AddTransition {
            state: saved,
            label: "again".into(),
            target: 0,
        },
    )
    .unwrap_err();
    assert_eq!(
        refused.to_string(),
        "state SAVED announces outcome `saved`, so it is final: take `outcome saved` out of it before giving it a transition"
    );
}

/// A composite's activity runs in every flat state inside it (and its OnExit in every
/// transition leaving it): what is wrong in it is said once, at the composite; the same text
/// in a state's own activity of another kind is the state's.
#[test]
fn what_is_wrong_in_a_composites_activity_is_said_once_where_it_is_written() {
    let keeper = "machine Keeper
initial PLAY
state PLAY {
    entry {
        Dive: restart(power = 2)
    }
    exit {
        Dive: suspend(side = 1)
    }
    when stop -> OUT
    state A { when a -> B }
    state B {
        entry {
            Dive: suspend(side = 1)
        }
        when b -> A
    }
}
state OUT {
    when go -> PLAY.B
}
";
    let mut read = vec![
        parse_machine("k", keeper).machines[0].clone(),
        parse_machine("d", DIVE).machines[0].clone(),
    ];
    let launches = [true, false].map(|start| Launch {
        start,
        params: Vec::new(),
    });
    let problems: Vec<String> = link(&mut read, &launches)
        .into_iter()
        .map(|p| format!("{:?}: {}", p.line, p.message))
        .collect();
    assert_eq!(
        problems,
        [
            "Some(3): `Dive: suspend(side = 1)`: only `restart` gives a machine its parameters",
            "Some(3): `Dive` has no parameter `power`",
            "Some(3): `Dive` takes side: start it with `Dive: restart(side = …)`",
            // B's own entry says what PLAY's exit says: it is B's, said at B.
            "Some(12): `Dive: suspend(side = 1)`: only `restart` gives a machine its parameters",
        ]
    );
}
