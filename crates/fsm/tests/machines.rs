//! Machines: label expressions as data, the T/A and Qfsm importers on the seed paper's
//! GameController, and every file of the Griffith team's corpus.

use proclaim_fsm::{
    import_qfsm, import_ta, parse_label, parse_machine, partner_of, to_native, Action, Argument,
    Machine, Severity,
};

/// `expect` is the canonical form, or `error: …` with the message.
fn check(label: &str, expect: &str) {
    let got = match parse_label(label) {
        Ok(l) => {
            let again = parse_label(&l.to_string()).expect("the canonical form parses");
            assert_eq!(
                again, l,
                "canonical form of `{label}` reads back differently"
            );
            l.to_string()
        }
        Err(e) => format!("error: {e}"),
    };
    assert_eq!(got, expect, "label `{label}`");
}

#[test]
fn labels() {
    check("TRUE", "TRUE");
    check("", "TRUE");
    check("1", "1");
    check("0", "0");
    check("true", "TRUE");
    check("readyReceived", "readyReceived");
    check("~fallen", "~fallen");
    check("!NaoMotionPlayerIsRunning", "~NaoMotionPlayerIsRunning");
    check("a && b || c", "a && b || c");
    check("a && (b || c)", "a && (b || c)");
    check("!(a || b)", "~(a || b)");
    check("timeout(500000)", "timeout(500000)");
    check("timeout(period)", "timeout(period)");
    check("x==0", "x == 0");
    check("((rot>-1) && (rot<180))", "rot > -1 && rot < 180");
    check(
        "(GoalIsVisible && (GoalDistance>250) && UseGoal)",
        "GoalIsVisible && GoalDistance > 250 && UseGoal",
    );
    check("rot==fwdAngle", "rot == fwdAngle");
    check("a !=b", "a != b");
    check(
        "a &&",
        "error: expected a name, a number, a string, `(`, `!` or `-`, found the end (at column 5)",
    );
    check(
        "(a",
        "error: expected `)` or an operator, found the end (at column 3)",
    );
    // A number is true when it is not zero, as in gufsm.
    check("abs(x)", "abs(x)");
    check("abs(ballX)>4", "abs(ballX) > 4");
    check(
        "timeout(",
        "error: expected a name, a number, a string, `(`, `!` or `-`, found the end (at column 9)",
    );
    check("timeout(delay*1000)", "timeout(delay * 1000)");
    check("a + b * (c - 1) > 2", "a + b * (c - 1) > 2");
    // What the team's machines hold (issue 11): unary minus, nested parentheses, arithmetic on
    // both sides, computed timeouts, clfsm's `after` and `after_ms`.
    check("HeadYaw<-boundaryLeftRight", "HeadYaw < -boundaryLeftRight");
    check(
        "loopCounter==2*(loopCounter/2)",
        "loopCounter == 2 * (loopCounter / 2)",
    );
    check("!(x<(-y))", "~(x < -y)");
    check("timeout((a*b)/2)", "timeout(a * b / 2)");
    check(
        "after(2) || after_ms(a + 10)",
        "after(2) || after_ms(a + 10)",
    );
    check(
        "x = 1",
        "error: expected an operator or the end of the expression, found `=`; `=` assigns: compare with `==` (at column 3)",
    );
    check("x - y - 1 < 0", "x - y - 1 < 0");
    check(
        "a b",
        "error: expected an operator or the end of the expression, found `b` (at column 3)",
    );
}

fn statement(text: &str) -> proclaim_fsm::Statement {
    let mut parsed = proclaim_fsm::code::parse_statements(text).expect("a statement");
    assert_eq!(parsed.len(), 1, "{text}");
    parsed.remove(0)
}

/// Every diagnostic of an import, as `file:line: severity: message`.
fn messages(imported: &proclaim_fsm::Imported) -> Vec<String> {
    imported
        .diagnostics
        .iter()
        .map(ToString::to_string)
        .collect()
}

/// Written as a native file and read back, a machine is the same (but for the lines it was
/// found on), and writing it again gives the same text.
fn round_trip(machine: &Machine, from: &str) {
    let text = to_native(machine);
    let back = parse_machine("exported.machine", &text);
    assert_eq!(messages(&back), Vec::<String>::new(), "{from}:\n{text}");
    let mut again = back.machines[0].clone();
    let mut original = machine.clone();
    for m in [&mut again, &mut original] {
        m.states.iter_mut().for_each(|s| s.line = 0);
        m.transitions.iter_mut().for_each(|t| t.line = 0);
        // Only the order among one state's transitions means anything.
        m.transitions.sort_by_key(|t| t.source);
    }
    assert_eq!(again, original, "{from} reads back differently:\n{text}");
    assert_eq!(to_native(&again), text, "{from}: a second export differs");
}

/// The native reader: `expect` is the machine written back, or its diagnostics one a line.
fn native(input: &str, expect: &str) {
    let imported = parse_machine("m.machine", input);
    let got = if imported.diagnostics.is_empty() {
        to_native(&imported.machines[0])
    } else {
        messages(&imported).join("\n") + "\n"
    };
    assert_eq!(got, expect, "input:\n{input}");
}

#[test]
fn the_native_format() {
    native(
        "// a comment\nmachine Blink\n\nstate Off {\n  entry {\n    LEDS: ChestBoard Off // kept\n    call msleep(100)\n  }\n  when TRUE -> On\n}\nstate On { when timeout(500000) && !stop -> Off\n when stop -> \"On\" }\n",
        "machine Blink\ninitial Off\n\nstate Off {\n    entry {\n        LEDS: ChestBoard Off // kept\n        call msleep(100)\n    }\n    when TRUE -> On\n}\n\nstate On {\n    when timeout(500000) && ~stop -> Off\n    when stop -> On\n}\n",
    );
    // Ids kept where they are not 1, 2, 3…; repeated names are referred to by id.
    native(
        "machine M\ninitial #7\nstate GetUp #7 { when a -> #9 }\nstate GetUp #9 {\n exit { Say: up\n }\n internal { call f(\"x y\") code int i = 0;\n }\n when TRUE -> #7 }\n",
        "machine M\ninitial #7\n\nstate GetUp #7 {\n    when a -> #9\n}\n\nstate GetUp #9 {\n    exit {\n        Say: up\n    }\n    internal {\n        call f(\"x y\")\n        code int i = 0;\n    }\n    when TRUE -> #7\n}\n",
    );
    native(
        "machine M\nstate A { when a -> B }\nstate A { when a ->A }\n",
        "m.machine:2: error: there is no state named `B`\nm.machine:3: error: `A` names 2 states (#1, #2); name the one meant by its id, as in `-> #1`\n",
    );
    // Statements of the activity language beside postings and calls, one a line when written.
    native(
        "machine Counter\ndescription \"counts \\\"beeps\\\"\"\nstate A {\n  entry {\n    int n = 0;\n    Say: hello\n    n = n + 1; post(\"Count\", n);\n    for (i = 0; i < 3; i = i + 1) {\n      postv(\"Beep\", i, n * 2); // a comment\n    }\n    call blink(3)\n    kickOffTeam = !kickOffTeam\n  }\n  when n >= 3 && !stop -> A\n}\n",
        "machine Counter\ndescription \"counts \\\"beeps\\\"\"\ninitial A\n\nstate A {\n    entry {\n        int n = 0;\n        Say: hello\n        n = n + 1;\n        post(\"Count\", n);\n        for (i = 0; i < 3; i = i + 1) { postv(\"Beep\", i, n * 2); }\n        call blink(3)\n        kickOffTeam = !kickOffTeam;\n    }\n    when n >= 3 && ~stop -> A\n}\n",
    );
    // An expression standing alone that starts with a string keeps its parentheses: written
    // bare, it would read back as a posting (found by the `machines` fuzz target).
    native(
        "machine M\nstate A {\n  entry {\n    (\"stuck\");\n    (\"a\" + 1);\n  }\n}\n",
        "machine M\ninitial A\n\nstate A {\n    entry {\n        (\"stuck\");\n        (\"a\" + 1);\n    }\n}\n",
    );
    native(
        "machine M\nstate A {\n  entry {\n    Say: hi\n    x = = 1;\n  }\n}\n",
        "m.machine:5: error: bad statement: expected a name, a number, a string, `(`, `!` or `-`, found `=`\n",
    );
    native(
        "machine M\nstate A {\n  when a && -> A\n}\n",
        "m.machine:3: error: bad label: expected a name, a number, a string, `(`, `!` or `-`, found the end\n",
    );
    native(
        "machine M\nstate A {\n  when a -> A\n",
        "m.machine:4: error: the file ends too early; expected one of `initial`, `state`, `parallel`, `entry`, `exit`, `internal`, `when`, `outcome`, `{`, `}`, `,`\n",
    );
    native(
        "machine M\nstate A {\n  entry { call }\n}\n",
        "m.machine:3: error: unexpected `}`; expected one of a name, a quoted string\n",
    );
    native(
        "machine M\nstate A {\n  when a\n}\n",
        "m.machine:4: error: unexpected `}`; expected one of `{`, `->`\n",
    );
    native(
        "machine M\nstate A #2 {}\nstate B #2 {}\n",
        "m.machine:3: error: state id #2 is used twice\n",
    );
    native(
        "machine M\n",
        "m.machine:1: error: machine `M` has no states\n",
    );
    native(
        "machine M\nstate A { entry { Say: \"a posting's content needs no quotes\n} }\nstate B { when x -> \"B }\n",
        "m.machine:4: error: string has no closing `\"` on its line\n",
    );
}

/// Where a transition's label ends: at its `->` or at the `{` of one that stays, whichever
/// comes first outside quoted text, and a block that stays may open on the next line.
#[test]
fn a_label_ends_at_its_arrow_or_at_the_block_of_one_that_stays() {
    native(
        "machine M\nstate A {\n  when s == \"a->b\" -> B\n  when p { s = \"x -> y\"; }\n  when q\n  {\n    n = n + 1;\n  }\n  when s == \"{\" -> B\n}\nstate B { }\n",
        "machine M\ninitial A\n\nstate A {\n    when s == \"a->b\" -> B\n    when p {\n        s = \"x -> y\";\n    }\n    when q {\n        n = n + 1;\n    }\n    when s == \"{\" -> B\n}\n\nstate B {\n}\n",
    );
}

#[test]
fn what_does_nothing_is_said() {
    let imported = parse_machine(
        "m.machine",
        "machine M\nstate A {\n  entry {\n    code x := 1\n  }\n}\n",
    );
    let lints: Vec<String> = proclaim_fsm::lint(&imported.machines[0], "m.machine")
        .iter()
        .map(ToString::to_string)
        .collect();
    assert_eq!(
        lints,
        ["m.machine:2: warning: state A: `x := 1` is kept as code and does nothing"]
    );
}

fn lints(text: &str) -> Vec<String> {
    let imported = parse_machine("m.machine", text);
    proclaim_fsm::lint(&imported.machines[0], "m.machine")
        .iter()
        .map(ToString::to_string)
        .collect()
}

/// A transition that stays on a label nothing can turn false while it stays (time alone, a
/// constant, `in` of its own state) fires in every round at one moment once it fires; one that
/// reads a name may turn false. `when done` without a target is refused.
#[test]
fn a_transition_that_stays_on_time_alone_is_said_to_fire_for_ever() {
    assert_eq!(
        lints("machine M\nstate A {\n  when p -> A\n  when after(2s) {\n    n = n + 1;\n  }\n  when go && after(1s) { }\n  when TRUE { }\n}\n"),
        [
            "m.machine:4: warning: `when after(2s) { … }` stays and reads nothing that changes while it stays: once it fires it fires in every round, at one moment, so time cannot pass (a run halts the machine); give it a target or a label that turns false",
            "m.machine:8: warning: `when TRUE { … }` stays and reads nothing that changes while it stays: once it fires it fires in every round, at one moment, so time cannot pass (a run halts the machine); give it a target or a label that turns false",
        ]
    );
    native(
        "machine M\nstate P {\n  when done { }\n  state A { }\n}\n",
        "m.machine:3: error: `when done` needs a target: `done` stays true in a final state, so one that stays would fire in every round\n",
    );
}

#[test]
fn a_cycle_that_takes_no_time_is_said_once() {
    assert_eq!(
        lints("machine M\ninitial S\nstate S {\n  when TRUE -> A\n}\nstate A {\n  when TRUE -> B\n}\nstate B {\n  when TRUE -> A\n}\n"),
        ["m.machine:7: warning: A -> B -> A goes round at one moment for ever: each state's first transition is `TRUE`, so time cannot pass (a run halts the machine)"]
    );
    assert_eq!(
        lints("machine M\ninitial A\nstate A {\n  when TRUE -> A\n}\n"),
        ["m.machine:4: warning: A -> A goes round at one moment for ever: each state's first transition is `TRUE`, so time cannot pass (a run halts the machine)"]
    );
    // Something tried first, or a time test, lets time pass.
    assert!(lints("machine M\ninitial A\nstate A {\n  when after(1s) -> B\n}\nstate B {\n  when TRUE -> A\n}\n").is_empty());
    assert!(lints("machine M\ninitial A\nstate A {\n  when x -> B\n  when TRUE -> B\n}\nstate B {\n  when TRUE -> A\n}\n").is_empty());
}

fn corpus() -> Option<std::path::PathBuf> {
    Some(corpus_dir()?.join("mipal"))
}

#[test]
fn the_seed_papers_game_controller_from_its_t_a_pair() {
    let Some(dir) = corpus() else {
        eprintln!("skipped: ../shared/corpus is absent");
        return;
    };
    let t = dir.join("testfiles/TGameController.txt");
    assert_eq!(
        partner_of(&t).unwrap(),
        dir.join("testfiles/AGameController.txt")
    );
    let read = |p: &std::path::Path| std::fs::read_to_string(p).unwrap();
    let a = partner_of(&t).unwrap();
    let imported = import_ta(
        "GameController",
        "TGameController.txt",
        &read(&t),
        "AGameController.txt",
        &read(&a),
    );
    assert!(
        imported.diagnostics.is_empty(),
        "{:?}",
        imported.diagnostics
    );
    let m = &imported.machines[0];
    assert_eq!(m.states.len(), 21);
    assert_eq!(
        m.state(m.initial).unwrap().name,
        "INITIAL",
        "the last A line is the initial state"
    );
    // State 2 (PLAYING): the last T line of a state is tried first.
    let labels: Vec<String> = m.outgoing(2).map(|t| t.label.to_string()).collect();
    assert_eq!(
        labels,
        [
            "finishedReceived",
            "readyReceived",
            "shortChestButtonPressed",
            "fallen",
            "penaltyReceived",
            "ReadyTheirGoal",
            "ReadyOurGoal"
        ]
    );
    let playing = m.state(2).unwrap();
    assert_eq!(
        playing.on_entry[0],
        Action::Post {
            ty: "NaoWalk".into(),
            content: "walk 0 0 0".into()
        }
    );
    assert!(playing.on_entry.contains(&Action::Call {
        function: "postTeamI_AmPlaying".into(),
        argument: None
    }));
    assert_eq!(
        playing.on_exit,
        [
            Action::Post {
                ty: "SMHeadBallTracker".into(),
                content: "Off".into()
            },
            Action::Post {
                ty: "SMPlayer".into(),
                content: "Off".into()
            }
        ]
    );
    assert!(playing.internal.contains(&Action::Call {
        function: "msleep".into(),
        argument: Some(Argument::Int(1000))
    }));
    assert_eq!(m.state(7).unwrap().on_exit, [], "no OnExit section");
}

#[test]
fn every_t_a_pair_of_the_corpus_imports() {
    let Some(dir) = corpus() else {
        eprintln!("skipped: ../shared/corpus is absent");
        return;
    };
    let mut pairs = 0;
    let mut broken = Vec::new();
    for entry in std::fs::read_dir(dir.join("testfiles")).unwrap() {
        let t = entry.unwrap().path();
        let name = t.file_name().unwrap().to_str().unwrap().to_string();
        let Some(machine) = name.strip_prefix('T').and_then(|n| n.strip_suffix(".txt")) else {
            continue;
        };
        let a = partner_of(&t).unwrap();
        let a_name = a.file_name().unwrap().to_str().unwrap().to_string();
        let imported = import_ta(
            machine,
            &name,
            &std::fs::read_to_string(&t).unwrap(),
            &a_name,
            &std::fs::read_to_string(&a).unwrap(),
        );
        broken.extend(
            imported
                .diagnostics
                .iter()
                .filter(|d| d.severity == Severity::Error)
                .map(ToString::to_string),
        );
        let m = &imported.machines[0];
        assert!(m.state(m.initial).is_some(), "{name}");
        round_trip(m, &name);
        pairs += 1;
    }
    broken.sort();
    // The truly broken lines of the corpus: both misspell OnEntry.
    assert_eq!(
        broken,
        [
            "APhysicalTester.txt:7: error: `OnEnrtry` is not a section keyword (OnEntry or OnExit); its items are read as Internal",
            "ASensorsTester.txt:12: error: `OnEnrtry` is not a section keyword (OnEntry or OnExit); its items are read as Internal",
        ]
    );
    assert_eq!(pairs, 55);
}

#[test]
fn every_qfsm_file_of_the_corpus_imports_or_says_why_not() {
    let Some(dir) = corpus() else {
        eprintln!("skipped: ../shared/corpus is absent");
        return;
    };
    let (mut machines, mut links, mut statements) = (0, 0, 0);
    for entry in std::fs::read_dir(dir.join("machines")).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_str().unwrap().to_string();
        let imported = import_qfsm(
            &name,
            &std::fs::read_to_string(&path).unwrap(),
            name.trim_end_matches(".fsm"),
        );
        let errors: Vec<_> = imported
            .diagnostics
            .iter()
            .filter(|d| d.severity == Severity::Error)
            .collect();
        if imported.machines.is_empty() {
            // The only files that do not import are links saved as text; they say so on line 1.
            assert_eq!(errors.len(), 1, "{name}: {errors:?}");
            assert_eq!(errors[0].line, Some(1));
            assert!(
                errors[0].message.contains("only names another file"),
                "{name}: {}",
                errors[0]
            );
            links += 1;
            continue;
        }
        assert!(errors.is_empty(), "{name}: {errors:?}");
        for m in &imported.machines {
            assert!(m.state(m.initial).is_some(), "{name}");
            round_trip(m, &name);
            machines += 1;
        }
        // Named after their files, as qfsm2gu and gufsm named them.
        if let [only] = imported.machines.as_slice() {
            assert_eq!(only.name, name.trim_end_matches(".fsm"));
        }
        statements += imported
            .machines
            .iter()
            .map(|m| m.statements().len())
            .sum::<usize>();
        let code: Vec<_> = imported
            .machines
            .iter()
            .flat_map(|m| m.actions())
            .filter(|a| matches!(a, Action::Code(_)))
            .collect();
        assert!(code.is_empty(), "{name}: statements kept as code: {code:?}");
    }
    assert_eq!((machines, links), (43, 35));
    // Every activity statement of the corpus is read (448 were kept as code before).
    assert!(statements > 448, "{statements} statements read");
}

#[test]
fn qfsm_traps() {
    let two = r#"<?xml version='1.0'?>
<qfsmproject>
  <machine name="A" initialstate="0">
    <state code="0" description="OnEntry { post(&quot;Say&quot;, &quot;hi&quot;); suspend(&quot;B&quot;); msleep(10); x = y + 1; postv(&quot;walk&quot;, 0, -35, 100); }&#xa;OnExit { }&#xa;{ }">Start</state>
    <state code="1" description="">End</state>
    <transition><from>0</from><to>1</to><inputs default="0" any="0" invert="0">a &amp;&amp; b</inputs><outputs>1</outputs></transition>
    <transition><from>0</from><to>1</to><inputs default="0" any="0" invert="1">c</inputs><outputs>2</outputs></transition>
    <transition><from>0</from><inputs>d</inputs><outputs>3</outputs></transition>
    <transition><from>1</from><to>0</to><inputs></inputs><outputs></outputs></transition>
  </machine>
  <machine name="B" initialstate="4"><state code="4" description="">Only</state></machine>
</qfsmproject>"#;
    let imported = import_qfsm("two.fsm", two, "two");
    assert_eq!(imported.machines.len(), 2);
    let a = &imported.machines[0];
    let labels: Vec<String> = a.outgoing(0).map(|t| t.label.to_string()).collect();
    assert_eq!(
        labels,
        ["~c", "a && b"],
        "larger <outputs> first; the unattached transition skipped"
    );
    assert_eq!(a.outgoing(1).next().unwrap().label.to_string(), "TRUE");
    let start = a.state(0).unwrap();
    assert_eq!(
        start.on_entry,
        [
            Action::Post {
                ty: "Say".into(),
                content: "hi".into()
            },
            Action::Post {
                ty: "B".into(),
                content: "suspend".into()
            },
            Action::Call {
                function: "msleep".into(),
                argument: Some(Argument::Int(10))
            },
            Action::Statement(statement("x = y + 1;")),
            Action::Statement(statement("postv(\"walk\", 0, -35, 100);")),
        ]
    );
    let messages = messages(&imported);
    assert_eq!(
        messages,
        [
            "two.fsm:8: warning: a transition without `<from>` or `<to>` (drawn but not attached) is skipped",
        ]
    );
    assert_eq!(
        (a.name.as_str(), imported.machines[1].name.as_str()),
        ("A", "B"),
        "several machines in a file keep their own names"
    );
    let broken = import_qfsm("bad.fsm", "<qfsmproject><machine name=\"M\" initialstate=\"9\"><state code=\"1\">S</state></machine></qfsmproject>", "bad");
    assert_eq!(
        broken.diagnostics[0].to_string(),
        "bad.fsm:1: error: initial state 9 of `M` is not one of its states"
    );
    let truncated = import_qfsm(
        "cut.fsm",
        "<qfsmproject>\n<machine name=\"M\" initialstate=\"1\">\n<state code=\"1\">S</sta",
        "cut",
    );
    assert!(truncated.has_errors());
    let link = import_qfsm("l.fsm", "../DefaultMachines/SMGetUp.fsm\n", "l");
    assert!(link.diagnostics[0]
        .message
        .contains("`../DefaultMachines/SMGetUp.fsm`"));
}

/// The later gufsm editors' sectioned descriptions: `$variables$` declared, `$includes$` kept as
/// a note, `$Layout.plist$` (the editor's drawing, in JSON) and the version never read as code.
#[test]
fn qfsm_sectioned_descriptions() {
    let text = r#"<?xml version='1.0'?>
<qfsmproject version="0.53" author="MiCASE">
  <machine name="Counter" initialstate="0" description="Version$&#x0a;1.3&#x0a;$includes$&#x0a;#include &lt;cmath&gt;&#x0a;$variables$&#x0a;int&#x09;total;&#x09;///&lt; pings so far&#x0a;$Layout.plist$&#x0a;{&#x0a;  &quot;States&quot; : { &quot;Ping&quot; : { &quot;x&quot; : 221 } }&#x0a;}&#x0a;">
    <state code="0" description="Version$&#x0a;1.3&#x0a;$includes$&#x0a;&#x0a;$OnEntry$&#x0a;total = total + 1;&#x0a;post(&quot;Say&quot;, &quot;ping &quot; + total);&#x0a;$OnExit$&#x0a;&#x0a;$Internal$&#x0a;&#x0a;$variables$&#x0a;int&#x09;beats;&#x09;///&lt; in this state&#x0a;const char *&#x09;stateName;&#x0a;$Layout.plist$&#x0a;{&#x0a;  &quot;x&quot; : 221,&#x0a;  &quot;Transitions&quot; : [ { &quot;srcPoint&quot; : [ 415, 181 ] } ]&#x0a;}&#x0a;">Ping</state>
    <state code="1" description="$OnEntry$&#x0a;beats = 2;&#x0a;">Done</state>
    <transition><from>0</from><to>1</to><inputs>total &gt;= 3</inputs><outputs>0</outputs></transition>
    <transition><from>0</from><to>0</to><inputs>after_ms(10)</inputs><outputs>0</outputs></transition>
  </machine>
</qfsmproject>
"#;
    let imported = import_qfsm("Counter.fsm", text, "Counter");
    assert_eq!(
        messages(&imported),
        ["Counter.fsm:4: warning: state `Ping`: `const char *\tstateName;` in `$variables$` is not a declaration proclaim knows (int, bool, char, float, double); the variable is not declared"]
    );
    let counter = &imported.machines[0];
    assert_eq!(
        counter.state(0).unwrap().on_entry,
        [
            Action::Statement(statement("int total;")),
            Action::Statement(statement("int beats;")),
            Action::Statement(statement("total = total + 1;")),
            Action::Statement(statement("post(\"Say\", \"ping \" + total);")),
        ],
        "the machine's variables, then the state's, then its OnEntry"
    );
    assert_eq!(
        counter.state(1).unwrap().on_entry,
        [Action::Statement(statement("beats = 2;"))]
    );
    assert_eq!(counter.description, "includes: #include <cmath>");
    round_trip(counter, "Counter.fsm");
}

/// The team's own files mix the two forms: sections whose first marker lacks its `$`, each
/// holding a braced block; they read as the braced form does.
#[test]
fn qfsm_sections_holding_braced_blocks() {
    let d = proclaim_fsm::parse_description(
        "OnEntry$\n{  light=0; post(\"LEDS\",\"Face Off\");}\n$OnExit$\n{light=1;}\n$Internal$\n{}\n",
    );
    assert!(d.problems.is_empty(), "{:?}", d.problems);
    assert_eq!(
        d.activities[0],
        [
            Action::Statement(statement("light = 0;")),
            Action::Post {
                ty: "LEDS".into(),
                content: "Face Off".into()
            },
        ]
    );
    assert_eq!(
        d.activities[1],
        [Action::Statement(statement("light = 1;"))]
    );
    assert!(d.activities[2].is_empty());
}

#[test]
fn t_a_errors_name_file_and_line() {
    let imported = import_ta(
        "M",
        "TM.txt",
        "1\tgo\t2\n1\ta &&\t1\n3\tgo\t1\nbad line\n",
        "AM.txt",
        "2\tB|OnEntry Say: hi; count = count + 1; post(\"Count\", count);/\n1\tA|OnEntry nonsense; C++: f(1);/ OnExit /\n",
    );
    let messages = messages(&imported);
    assert_eq!(
        messages,
        [
            "AM.txt:2: error: `nonsense` is not `Type: content`",
            "TM.txt:4: error: expected `source<TAB>label<TAB>target`",
            "TM.txt:3: error: state 3 is not in AM.txt",
            "TM.txt:2: error: label `a &&`: expected a name, a number, a string, `(`, `!` or `-`, found the end (at column 5)",
        ]
    );
    let m = &imported.machines[0];
    assert_eq!(m.initial, 1);
    assert_eq!(m.outgoing(1).count(), 1);
    // Statements of the activity language stand among T/A items too.
    assert_eq!(
        m.state(2).unwrap().on_entry[1..],
        [
            Action::Statement(statement("count = count + 1;")),
            Action::Statement(statement("post(\"Count\", count);")),
        ]
    );
    // The unreadable transition is kept for the import to write down, not lost.
    assert_eq!(m.unread.len(), 1);
    assert_eq!((m.unread[0].label.as_str(), m.unread[0].line), ("a &&", 2));
    assert!(to_native(m).contains(
        "// not read (line 2: expected a name, a number, a string, `(`, `!` or `-`, found the end (at column 5)): when a && -> A"
    ));
}

#[test]
#[ignore = "prints the corpus warnings for a person to read"]
fn print_corpus_warnings() {
    let dir = corpus().unwrap();
    for entry in std::fs::read_dir(dir.join("machines")).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_str().unwrap().to_string();
        for d in import_qfsm(&name, &std::fs::read_to_string(&path).unwrap(), "x").diagnostics {
            println!("{d}");
        }
    }
}

#[test]
fn a_machine_as_dot() {
    let imported = import_ta(
        "Door",
        "T",
        "0\topen\t1\n0\ttimeout(5000000)\t0\n1\t~open\t0\n",
        "A",
        "1\tOpen|OnEntry Light: On; Alarm: On;/ OnExit C++: beep(2);/\n0\tShut \"quiet\"|OnEntry /\n",
    );
    assert_eq!(
        proclaim_fsm::to_dot(&imported.machines[0]),
        r#"digraph "Door" {
  rankdir=LR;
  node [shape=box, style=rounded, fontname="Helvetica", fontsize=10];
  edge [fontname="Helvetica", fontsize=9];
  start [shape=point, width=0.15];
  start -> s0;
  s1 [label="Open (1)\nentry: Light: On\lentry: Alarm: On\lexit: beep(2)\l"];
  s0 [label="Shut \"quiet\" (0)\n", peripheries=2];
  s1 -> s0 [label="1: ~open"];
  s0 -> s0 [label="1: timeout(5000000)"];
  s0 -> s1 [label="2: open"];
  "Light" [shape=component, style=dashed];
  s1 -> "Light" [style=dashed, arrowhead=odot, label="starts"];
  "Alarm" [shape=component, style=dashed];
  s1 -> "Alarm" [style=dashed, arrowhead=odot, label="starts"];
}
"#
    );
}

/// A start written as a statement, alone or in a loop, is drawn as a start (it once was drawn
/// only when written `Dive: restart`).
#[test]
fn a_start_written_as_a_statement_is_drawn() {
    let text = "machine M\ninitial A\nstate A {\n  entry { restart(\"Dive\"); int i; for (i = 0; i < 2; i = i + 1) { post(\"Kick\", \"On\"); post(\"Light\", \"on\"); } }\n}\n";
    let read = parse_machine("M.machine", text);
    assert!(read.diagnostics.is_empty(), "{:?}", read.diagnostics);
    let dot = proclaim_fsm::to_dot(&read.machines[0]);
    let starts: Vec<&str> = dot.lines().filter(|l| l.contains("\"starts\"")).collect();
    assert_eq!(
        starts,
        [
            r#"  s1 -> "Dive" [style=dashed, arrowhead=odot, label="starts"];"#,
            r#"  s1 -> "Kick" [style=dashed, arrowhead=odot, label="starts"];"#,
        ],
        "{dot}"
    );
}

/// The shared corpus (`../shared/corpus` from the repository's root), when present beside it.
fn corpus_dir() -> Option<std::path::PathBuf> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus");
    dir.is_dir().then_some(dir)
}

/// A word where a name is due is a name, keyword or not: SCXML documents call states `initial`
/// and `entry`, and a quoted name or an id ends the wait for one.
#[test]
fn a_keyword_where_a_name_is_due_is_a_name() {
    let text = "machine M
initial initial
state initial {
    when go -> entry
}
state entry {
    when TRUE -> state
    when back -> \"B C\"
    when stop -> \"entry\" {
        print(\"x\");
    }
}
state \"state\" #7 {
    entry {
        Say: hi
    }
}
state \"B C\" { }
";
    let read = proclaim_fsm::parse_machine("M.machine", text);
    assert!(!read.has_errors(), "{:?}", read.diagnostics);
    let m = &read.machines[0];
    let names: Vec<&str> = m.states.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["initial", "entry", "state", "B C"]);
    assert_eq!(m.state(m.initial).map(|s| s.name.as_str()), Some("initial"));
    assert_eq!(
        m.states[2].on_entry.len(),
        1,
        "the quoted name's body still reads"
    );
    assert_eq!(m.transitions[1].target, 7);
    let actions = m.transitions[3].leaving.as_ref().map(Vec::len);
    assert_eq!(actions, Some(1), "a quoted target's actions read");
    // What the writer makes of it (keywords and spaces quoted) reads back the same.
    let again = proclaim_fsm::parse_machine("M.machine", &proclaim_fsm::to_native(m));
    assert!(!again.has_errors(), "{:?}", again.diagnostics);
    assert_eq!(again.machines[0].states.len(), 4);
}
