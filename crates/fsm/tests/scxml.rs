//! SCXML documents read into the native format: each test a document and the native text it
//! maps to, or its refusals; and real documents written by others, each read or refused with a
//! reason, never a panic (`PROCLAIM_SCXML_CORPUS` names their folder; skipped without it).

use proclaim_fsm::{import_scxml, parse_machine, to_scxml, Machine};
use std::collections::BTreeMap;

/// `expect` is the native text, or each refusal as `line: message`.
#[track_caller]
fn check(scxml: &str, expect: &str) {
    let read = import_scxml("d.scxml", scxml, "d");
    let got = match &read.native {
        Some(native) => {
            assert!(
                !read.imported.has_errors(),
                "{:?}",
                read.imported.diagnostics
            );
            // What `proclaim import` writes reads back (its lines are its own, the machine's
            // the document's).
            let again = parse_machine("d.machine", native);
            assert!(!again.has_errors(), "{:?}", again.diagnostics);
            assert_eq!(
                again.machines[0].states.len(),
                read.imported.machines[0].states.len()
            );
            native.lines().skip(1).collect::<Vec<_>>().join("\n") + "\n"
        }
        None => read
            .imported
            .diagnostics
            .iter()
            .map(|d| format!("{}: {}\n", d.line.unwrap_or(0), d.message))
            .collect(),
    };
    assert_eq!(got, expect, "\n{got}");
}

#[test]
fn states_transitions_and_content_map_onto_the_native_format() {
    check(
        r#"<scxml xmlns="http://www.w3.org/2005/07/scxml" version="1.0" initial="closed" name="Door">
  <state id="closed">
    <onentry><raise event="door.shut"/></onentry>
    <transition event="open push" cond="force &gt;= 2" target="open">
      <log expr="'opening'"/>
    </transition>
  </state>
  <state id="open">
    <initial><transition target="swinging"/></initial>
    <onexit><send event="closing"/></onexit>
    <history id="back" type="deep"/>
    <transition event="close" target="closed"/>
    <state id="swinging"><transition event="stop" target="still"/></state>
    <state id="still"><transition event="nudge" target="back"/></state>
  </state>
  <final id="gone"/>
</scxml>"#,
        r#"machine Door
initial closed

state closed { // SCXML line 2
    entry {
        post("door_shut", TRUE);
    }
    when (open || push) && (force >= 2) -> open { // SCXML line 4
        print("opening");
    }
}

state open { // SCXML line 8
    exit {
        post("closing", TRUE);
    }
    initial swinging // SCXML line 9
    when close -> closed // SCXML line 12

    state swinging { // SCXML line 13
        when stop -> open.still // SCXML line 13
    }

    state still { // SCXML line 14
        when nudge -> open.deep_history // SCXML line 14
    }
}

state gone { // SCXML line 16
}
"#,
    );
}

#[test]
fn a_data_model_is_declared_by_a_first_state_that_moves_on_at_once() {
    check(
        r#"<scxml xmlns="http://www.w3.org/2005/07/scxml" initial="count" datamodel="ecmascript">
  <datamodel><data id="n" expr="0"/><data id="limit" expr="3" type="int32"/><data id="on" expr="true"/></datamodel>
  <state id="count">
    <transition cond="n &lt; limit" target="count"><assign location="n" expr="n + 1"/></transition>
  </state>
</scxml>"#,
        r#"machine d
initial DATAMODEL_START

state DATAMODEL_START {
    entry {
        int n;
        int limit = 3;
        bool on = TRUE;
    }
    when TRUE -> count
}

state count { // SCXML line 3
    when (n < limit) -> count { // SCXML line 4
        n = n + 1;
    }
}
"#,
    );
}

/// A transition without a target acts and stays: SCXML's and the native `when LABEL { … }`
/// (`docs/spec/behaviour.md` §3.2) are one, both ways.
#[test]
fn a_transition_without_a_target_reads_and_writes_as_one_that_stays() {
    check(
        r#"<scxml xmlns="http://www.w3.org/2005/07/scxml" initial="count" datamodel="ecmascript">
  <datamodel><data id="n" expr="0"/></datamodel>
  <state id="count">
    <transition cond="n &lt; 3"><assign location="n" expr="n + 1"/></transition>
    <transition event="tick" type="internal"/>
    <transition cond="n == 3" target="done"/>
  </state>
  <final id="done"/>
</scxml>"#,
        r#"machine d
initial DATAMODEL_START

state DATAMODEL_START {
    entry {
        int n;
    }
    when TRUE -> count
}

state count { // SCXML line 3
    when (n < 3) { // SCXML line 4
        n = n + 1;
    }
    when tick { // SCXML line 5
    }
    when (n == 3) -> done // SCXML line 6
}

state done { // SCXML line 8
}
"#,
    );
    let native = "machine M
initial DATAMODEL_START
state DATAMODEL_START {
    entry {
        int n;
    }
    when TRUE -> count
}
state count {
    when n < 3 {
        n = n + 1;
    }
    when tick { }
    when n == 3 -> done
}
state done {
}
";
    reads_back_the_same("M", native, "<transition cond=\"n &lt; 3\">");
    // SCXML raises a timer's event and a completion once; their labels here stay true.
    check(
        r#"<scxml xmlns="http://www.w3.org/2005/07/scxml" initial="p">
  <state id="p">
    <onentry><send event="t" delay="1s" id="i"/></onentry>
    <transition event="t"><log expr="1"/></transition>
    <transition event="done.state.p"/>
    <final id="a"/>
  </state>
</scxml>"#,
        "4: <transition event=\"t\"> without a target: SCXML raises it once, but its label here stays true in the state, so it would fire in every round
5: <transition event=\"done.state.p\"> without a target: SCXML raises it once, but its label here stays true in the state, so it would fire in every round
",
    );
}

/// A document of no states (Qt's parser tests have one) is refused where it starts, rather than
/// mapped to a machine that cannot be read.
#[test]
fn a_document_of_no_states_is_refused_at_its_root() {
    check(
        "<scxml>\n</scxml>",
        "1: <scxml> holds no state: a machine needs one to start in\n",
    );
}

#[test]
fn what_does_not_map_is_refused_with_its_element_and_line() {
    check(
        r#"<scxml xmlns="http://www.w3.org/2005/07/scxml" datamodel="xpath">
  <parallel id="both"/>
  <state id="a">
    <transition event="go.*" target="b"/>
    <transition event="go" target="a b"/>
    <transition event="go"><script>x = 1</script></transition>
    <transition event="go" cond="_event.data &gt; 1" target="b"/>
    <transition event="go" target="b"><send event="e" delay="1s"/><if cond="x"/></transition>
  </state>
  <state id="b"><invoke src="other.scxml"/></state>
</scxml>"#,
        "1: the `xpath` data model: only `null` and a small ECMAScript one (numbers, truths, operators) map
2: <parallel> holding no states: it has no regions to run
4: event `go.*`: a wildcard does not map: an event is one label atom
5: target \"a b\": `a` and `b` are not in different regions of a <parallel>, so they are no configuration
6: <script> in executable content: a script: only the small expression data model maps
7: `_event.data > 1`: an event's data (`_event`): events carry none here
8: <send event=\"e\"> with a delay: only a send on entering a state maps (it times that state)
8: <if> in executable content: control flow in executable content: the activity language has `for` but no `if` yet
10: <invoke> in a state: invoking another machine: use a sub-machine started by a posting
",
    );
    check(
        r#"<scxml xmlns="http://www.w3.org/2005/07/scxml">
  <state id="p" initial="deep">
    <state id="q"><state id="deep"/></state>
    <transition event="done.state.p" cond="x" target="p"/>
  </state>
  <state><transition target="p"/></state>
  <state id="r">
    <state id="idle"/>
    <transition event="done.state.r" target="p"/>
  </state>
  <state id="s"><transition cond="malfunction &gt; 0 &amp;&amp; x != 'it&quot;s'" target="s"/></state>
</scxml>"#,
        "4: `done.state.p` with a `cond`: `done` stands alone
6: <state> without an `id`: give it one (it names the state)
8: <state id=\"idle\"> has no transition, so it would be final here, which SCXML's is not, and `r` waits for its completion: write it as <final>
",
    );
    check(
        "<scxml",
        "1: malformed XML: syntax error: tag not closed: `>` not found before end of input\n",
    );
}

/// A history of a state holding a `<parallel>` maps: a shallow one resumes the parallel state
/// whole, a deep one the configuration it was left in (a state in each region).
#[test]
fn a_history_around_a_parallel_state_maps() {
    let document = |kind: &str| {
        format!(
            r#"<scxml xmlns="http://www.w3.org/2005/07/scxml">
  <state id="game">
    <history id="h" type="{kind}"/>
    <transition event="whistle" target="pause"/>
    <state id="ready"><transition event="go" target="play"/></state>
    <parallel id="play">
      <state id="head"/>
      <state id="body"/>
    </parallel>
  </state>
  <state id="pause"><transition event="resume" target="h"/></state>
</scxml>"#
        )
    };
    for (kind, word) in [("shallow", "history"), ("deep", "deep_history")] {
        let read = import_scxml("d.scxml", &document(kind), "d");
        assert!(
            !read.imported.has_errors(),
            "{:?}",
            read.imported.diagnostics
        );
        let native = read.native.unwrap_or_default();
        assert!(
            native.contains(&format!("when resume -> game.{word}")),
            "{native}"
        );
    }
}

/// A document nesting deeper than any chart is refused, not walked until the stack ends.
#[test]
fn elements_nesting_past_their_bound_are_refused() {
    let depth = 100_000;
    let mut text = String::from("<scxml xmlns=\"http://www.w3.org/2005/07/scxml\">\n");
    for i in 0..depth {
        text.push_str(&format!("<state id=\"s{i}\">\n"));
    }
    text.push_str(&"</state>\n".repeat(depth));
    text.push_str("</scxml>\n");
    check(&text, "257: elements nest deeper than 256\n");
}

/// A machine with every line number taken out: what two readings of one machine share.
fn without_lines(mut m: Machine) -> Machine {
    m.states.iter_mut().for_each(|s| s.line = 0);
    m.transitions.iter_mut().for_each(|t| {
        t.line = 0;
        t.joined.iter_mut().for_each(|j| j.1 = 0);
    });
    m.composites.iter_mut().for_each(|c| c.line = 0);
    m
}

/// native → SCXML → native is the same machine, nesting, histories, `done`, the data model
/// and transition content included.
#[test]
fn a_chart_written_as_scxml_reads_back_as_the_same_machine() {
    let native = r#"machine Keeper
initial DATAMODEL_START

state DATAMODEL_START {
    entry {
        int dives;
        int limit = 3;
        bool tired;
        float speed = 1.5;
    }
    when TRUE -> GUARD
}

state GUARD {
    when ballComing && dives < limit -> DIVE {
        dives = dives + 1;
    }
    when resume -> DIVE.history
}

state DIVE {
    entry {
        post("diving", TRUE);
    }
    exit {
        print("up " + dives);
        print("say \"hi\", it's\ttime");
    }
    initial AIM
    when penalized -> GUARD
    when after_ms(3000) -> GUARD
    when done -> GUARD
    when !(a || b) && !c -> DIVE.deep_history

    state AIM {
        when ballLeft -> LEFT
        when TRUE -> LIE
    }

    state LEFT {
        entry {
            print("left");
        }
        when x - (y - 1) > 2 -> LIE
        when after(2) -> LIE
        when after_ms(300) -> AIM
    }

    state LIE {
    }
}
"#;
    reads_back_the_same("Keeper", native, "<history");
}

#[test]
fn what_scxml_cannot_say_is_refused_at_its_line() {
    let native = "machine M\nstate A {\n    internal {\n        n = n + 1;\n    }\n    entry {\n        Say: hi\n    }\n    when after(2s) && p -> B\n    when p -> #2\n}\nstate B #2 { }\n";
    let refusals: Vec<String> = to_scxml("M.machine", native)
        .expect_err("refused")
        .iter()
        .map(|d| format!("{}: {}", d.line.unwrap_or(0), d.message))
        .collect();
    assert_eq!(
        refusals,
        [
            "3: state `A`: an internal activity (run each ringlet nothing fires) has no SCXML form",
            "7: the posting `Say: …`: its content has no SCXML form (an SCXML event carries none here); `post(\"Say\", TRUE);` raises it",
            "9: `after(2s) && p`: a time test has no SCXML condition (SCXML times a state with a delayed send, which a transition then waits on alone)",
            "10: `#2`: name the state; SCXML has no numbered states",
        ]
    );
    let stays = "machine M\nstate A {\n    when after(2s) {\n        n = 1;\n    }\n}\n";
    let refusals: Vec<String> = to_scxml("M.machine", stays)
        .expect_err("refused")
        .iter()
        .map(|d| format!("{}: {}", d.line.unwrap_or(0), d.message))
        .collect();
    assert_eq!(
        refusals,
        ["3: a transition that stays on a time test: SCXML raises its event once, where this label stays true in the state"]
    );
}

/// Real documents: every one read, or refused with at least one located reason.
#[test]
fn real_scxml_documents_are_read_or_refused_with_a_reason() {
    let Some(dir) = std::env::var_os("PROCLAIM_SCXML_CORPUS") else {
        eprintln!("skipped: PROCLAIM_SCXML_CORPUS names no folder of SCXML documents");
        return;
    };
    let Ok(entries) = std::fs::read_dir(&dir) else {
        eprintln!("skipped: {dir:?} is not a folder");
        return;
    };
    let (mut read, mut refused) = (0, 0);
    // Of the documents with a `<parallel>`: how many read, how many were refused.
    let (mut parallel_read, mut parallel_refused) = (0, 0);
    let mut reasons: BTreeMap<String, usize> = BTreeMap::new();
    for entry in entries.flatten() {
        let path = entry.path();
        let Ok(text) = std::fs::read_to_string(&path) else {
            continue;
        };
        let file = path.display().to_string();
        let imported = import_scxml(&file, &text, "d");
        let parallel = text.contains("<parallel");
        match &imported.native {
            Some(_) if !imported.imported.has_errors() => {
                assert_eq!(imported.imported.machines.len(), 1, "{file}");
                read += 1;
                parallel_read += usize::from(parallel);
            }
            Some(_) => panic!(
                "{file}: the native form of what mapped does not read: {:?}",
                imported.imported.diagnostics
            ),
            None => {
                refused += 1;
                parallel_refused += usize::from(parallel);
                let diagnostics = &imported.imported.diagnostics;
                assert!(!diagnostics.is_empty(), "{file}: refused without a reason");
                for d in diagnostics {
                    assert!(d.line.is_some(), "{file}: {d}");
                    let kind: String = d
                        .message
                        .split(':')
                        .next()
                        .unwrap_or_default()
                        .chars()
                        .take(60)
                        .collect();
                    *reasons.entry(kind).or_default() += 1;
                }
            }
        }
    }
    let mut by_count: Vec<_> = reasons.into_iter().collect();
    by_count.sort_by_key(|b| std::cmp::Reverse(b.1));
    eprintln!("{read} read, {refused} refused; the most frequent reasons:");
    eprintln!("  (with a <parallel>: {parallel_read} read, {parallel_refused} refused)");
    for (reason, n) in by_count.iter().take(15) {
        eprintln!("  {n:5}  {reason}");
    }
    assert!(read + refused > 0, "{dir:?} holds no documents");
    assert!(
        parallel_read + parallel_refused == 0 || parallel_read > 0,
        "no document with a <parallel> read"
    );
}

/// SCXML times a state with a delayed send on entering it and a transition on its event: that
/// is a time test. A delayed send that does more than that is refused, saying why.
#[test]
fn a_delayed_send_that_times_its_state_is_a_time_test() {
    check(
        r#"<scxml xmlns="http://www.w3.org/2005/07/scxml" version="1.0" initial="waiting" name="Kick">
  <state id="waiting">
    <onentry><send event="waited" delay="1.5s" id="t"/></onentry>
    <onexit><cancel sendid="t"/></onexit>
    <transition event="ball" target="kicking"/>
    <transition event="waited give_up" target="done"/>
  </state>
  <state id="kicking">
    <onentry><send event="kicked" delay="300ms"/></onentry>
    <transition event="kicked" target="done"/>
  </state>
  <final id="done"/>
</scxml>"#,
        r#"machine Kick
initial waiting

state waiting { // SCXML line 2
    when ball -> kicking // SCXML line 5
    when (after_ms(1500) || give_up) -> done // SCXML line 6
}

state kicking { // SCXML line 8
    when after_ms(300) -> done // SCXML line 10
}

state done { // SCXML line 12
}
"#,
    );
    check(
        r#"<scxml xmlns="http://www.w3.org/2005/07/scxml" initial="a">
  <state id="a">
    <onentry><send event="t" delay="2s"/><send event="u" delay="soon"/><send event="v" delay="1s"/></onentry>
    <transition event="t" cond="x &gt; 1" target="b"/>
    <transition event="u" target="b"/>
    <transition event="v" target="b"/>
  </state>
  <state id="b">
    <onentry><send event="w" delay="1s"/><raise event="w"/></onentry>
    <transition event="w" target="c"/>
    <transition event="v" target="a"/>
  </state>
  <state id="c">
    <onentry><send event="z" delay="1s"/></onentry>
    <transition event="z" target="a"/>
    <state id="c1"/>
  </state>
</scxml>"#,
        "3: <send event=\"t\"> with a delay: the transition on line 4 has a `cond`: SCXML drops the event if it is false then, while a time test stays true
3: <send event=\"u\"> with a delay: delay=\"soon\" is no duration (write `2s` or `500ms`, a whole number of milliseconds)
3: <send event=\"v\"> with a delay: `b` (line 11) waits on `v` too; only the state that sends it may
9: <send event=\"w\"> with a delay: `w` is also sent or raised at once; only an event the delay alone sends reads as a time test
",
    );
}

/// Native text of machine `name` written as SCXML (which must hold `shows`) and imported
/// again: the same machine, lines aside.
#[track_caller]
fn reads_back_the_same(name: &str, native: &str, shows: &str) {
    let written = parse_machine(&format!("{name}.machine"), native);
    assert!(!written.has_errors(), "{:?}", written.diagnostics);
    let scxml = to_scxml(&format!("{name}.machine"), native).unwrap_or_else(|e| panic!("{e:?}"));
    assert!(scxml.contains(shows), "{scxml}");
    let read = import_scxml(&format!("{name}.scxml"), &scxml, name);
    assert!(
        !read.imported.has_errors(),
        "{:?}\n{scxml}",
        read.imported.diagnostics
    );
    assert_eq!(
        without_lines(read.imported.machines[0].clone()),
        without_lines(written.machines[0].clone()),
        "\n{scxml}\n{}",
        read.native.unwrap_or_default()
    );
}

/// An `initial` naming a deeper state, or one in each region, is SCXML's `initial` both ways.
#[test]
fn deep_and_several_initials_read_back_as_the_same_machine() {
    let game = "machine Game
initial GAME

state GAME {
    initial PLAY.BODY.KICK
    state READY {
        when go -> PLAY
    }
    parallel PLAY {
        state HEAD {
            state LOOK {
                when seen -> TRACK
            }
            state TRACK {
                when lost -> READY
            }
        }
        state BODY {
            state WALK {
                when near -> KICK
            }
            state KICK {
                when far -> WALK
            }
        }
    }
}
";
    reads_back_the_same("Game", game, r#"<state id="GAME" initial="KICK">"#);
    let several = game
        .replace(
            "initial GAME\n",
            "initial GAME.PLAY.HEAD.TRACK, GAME.PLAY.BODY.KICK\n",
        )
        .replace("    initial PLAY.BODY.KICK\n", "");
    reads_back_the_same("Game", &several, r#"initial="TRACK KICK""#);
}

/// A parallel state is SCXML's `<parallel>` both ways (`docs/spec/behaviour.md` §3.2): its
/// regions, their own clocks and its `done` read back as the same machine.
#[test]
fn regions_written_as_scxml_read_back_as_the_same_machine() {
    let native = r#"machine Striker
initial PLAY

parallel PLAY {
    when gameOver -> STOP
    when done -> STOP

    state HEAD {
        state LEFT {
            when after_ms(400) -> RIGHT
        }
        state RIGHT {
            when after_ms(400) -> LEFT
        }
    }

    state LEGS {
        state WALK {
            entry {
                print("walk");
            }
            when ballNear -> KICKED
        }
        state KICKED {
        }
    }
}

state STOP {
}
"#;
    reads_back_the_same("Striker", native, "<parallel id=\"PLAY\">");
}

/// Several targets (`-> PLAY.HEAD.TRACK, PLAY.BODY.KICK`) are SCXML's `target="TRACK KICK"`
/// both ways, and read back as the same machine; targets that are no configuration, or a
/// history among several, are refused at the transition.
#[test]
fn several_targets_read_and_write_as_scxmls_target_list() {
    let native = "machine M
initial READY

state READY {
    when go -> PLAY.HEAD.TRACK, PLAY.BODY.KICK
}

parallel PLAY {
    state HEAD {
        state LOOK {
            when seen -> TRACK
        }
        state TRACK {
            when lost -> HEAD.LOOK, BODY.WALK
        }
    }

    state BODY {
        state WALK {
        }
        state KICK {
        }
    }
}
";
    reads_back_the_same("M", native, "target=\"TRACK KICK\"");
    check(
        r#"<scxml xmlns="http://www.w3.org/2005/07/scxml">
  <state id="ready">
    <transition event="a" target="look track"/>
    <transition event="b" target="look h"/>
    <transition event="c" target=" "/>
  </state>
  <parallel id="play">
    <state id="head"><history id="h"/><state id="look"/><state id="track"/></state>
    <state id="body"><state id="walk"/></state>
  </parallel>
</scxml>"#,
        "3: target \"look track\": `play.head.look` and `play.head.track` are not in different regions of a <parallel>, so they are no configuration
4: target \"look h\": a history among several targets does not map (a history resumes one state of its own)
5: an empty `target` (or `initial`): name a state, or leave the attribute out for a transition that stays
",
    );
    check(
        r#"<scxml xmlns="http://www.w3.org/2005/07/scxml" initial="look walk">
  <parallel id="play">
    <state id="head"><state id="look"/></state>
    <state id="body"><state id="walk"/></state>
  </parallel>
</scxml>"#,
        "machine d
initial play.head.look, play.body.walk

parallel play { // SCXML line 2

    state head { // SCXML line 3

        state look { // SCXML line 3
        }
    }

    state body { // SCXML line 4

        state walk { // SCXML line 4
        }
    }
}
",
    );
    // A state's `initial` naming a deeper state, and one in each region.
    check(
        r#"<scxml xmlns="http://www.w3.org/2005/07/scxml">
  <state id="game" initial="kick">
    <state id="ready"><transition event="go" target="play"/></state>
    <parallel id="play">
      <state id="head"><state id="look"/><state id="track"/></state>
      <state id="body"><state id="walk"/><state id="kick"/></state>
    </parallel>
  </state>
</scxml>"#,
        "machine d

state game { // SCXML line 2
    initial play.body.kick // SCXML line 2

    state ready { // SCXML line 3
        when go -> game.play // SCXML line 3
    }

    parallel play { // SCXML line 4

        state head { // SCXML line 5

            state look { // SCXML line 5
            }

            state track { // SCXML line 5
            }
        }

        state body { // SCXML line 6

            state walk { // SCXML line 6
            }

            state kick { // SCXML line 6
            }
        }
    }
}
",
    );
    check(
        r#"<scxml xmlns="http://www.w3.org/2005/07/scxml">
  <state id="other" initial="a b">
    <state id="a"/><state id="b"/>
    <transition event="h" target="other_h"/>
    <history id="other_h"/>
  </state>
  <state id="third" initial="third_h">
    <state id="c"/>
    <history id="third_h"/>
  </state>
</scxml>"#,
        "2: target \"a b\": `other.a` and `other.b` are not in different regions of a <parallel>, so they are no configuration
7: initial `third_h`: a history as an initial state does not map (name the state it would resume the first time)
",
    );
}

/// SCXML's `In('id')` is the native `in(STATE)` both ways: a region waiting on another's state
/// reads back as the same machine, and an id that names no state is refused at its line.
#[test]
fn in_reads_and_writes_as_the_native_in() {
    let native = "machine M
parallel P {
    state A {
        state a1 {
            when go -> a2
        }
        state a2 {
            when back -> a1
        }
    }
    state B {
        state b1 {
            when in(P.A.a2) -> b2
        }
        state b2 {
            when !in(P.A.a2) && tick -> b1
        }
    }
}
";
    reads_back_the_same("M", native, "cond=\"In(&quot;a2&quot;)\"");
    check(
        r#"<scxml xmlns="http://www.w3.org/2005/07/scxml" initial="a">
  <state id="a">
    <transition cond="In('b')" target="b"/>
    <transition cond="In('nowhere')" target="b"/>
  </state>
  <state id="b"/>
</scxml>"#,
        "4: `In('nowhere')`: `In(\"nowhere\")` names no state of the document (it takes one state's id, quoted)\n",
    );
}
