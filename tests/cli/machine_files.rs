//! `import`, `draw`, `deps` and `liveness`: machine files read, written and drawn.

use super::{assert_one_problem_shape, check, stderr, stdout, temp_file};
use crate::proclaim;
use std::process::Command;

#[test]
fn draw_writes_dot_and_renders_through_graphviz() {
    let t = temp_file("TDoor.txt", b"0\topen\t1\n1\t~open\t0\n");
    temp_file(
        "ADoor.txt",
        b"1\tOpen|OnEntry Light: On;/\n0\tShut|OnEntry /\n",
    );
    let o = proclaim(&["draw", t.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        stdout(&o).starts_with("digraph \"Door\" {"),
        "{}",
        stdout(&o)
    );
    assert!(stdout(&o).contains("s0 -> s1 [label=\"1: open\"];"));
    let svg = t.with_file_name("door.svg");
    let o = proclaim(&["draw", t.to_str().unwrap(), "-o", svg.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let graphviz = std::process::Command::new("dot").arg("-V").output().is_ok();
    if graphviz {
        let text = std::fs::read_to_string(&svg).unwrap();
        assert!(text.contains("<svg") && text.contains("Open (1)"), "{text}");
    } else {
        assert!(
            stderr(&o).contains("Render it with `dot -Tsvg"),
            "{}",
            stderr(&o)
        );
        assert!(svg.with_extension("dot").exists());
    }
    let o = proclaim(&["draw", "tweety"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("is not a machine file"),
        "{}",
        stderr(&o)
    );
}

/// A reader that went away (`proclaim draw m | head -c1`) ends proclaim quietly, as the
/// SIGPIPE default would, though proclaim ignores SIGPIPE so a child's exit cannot kill it.
#[test]
fn output_whose_reader_left_ends_quietly() {
    let t = temp_file(
        "Quiet.machine",
        b"machine Quiet\ninitial A\nstate A {\n    when after(1s) -> A\n}\n",
    );
    let mut child = Command::new(env!("CARGO_BIN_EXE_proclaim"))
        .args(["draw", t.to_str().unwrap()])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(141), "{}", stderr(&out));
    assert_eq!(stderr(&out), "");
}

/// An SCXML document imports as a native file that nests states, which `check` reads and
/// imports again unchanged; a document that does not map is refused at its element's line.
#[test]
fn import_maps_an_scxml_document_onto_nested_states_or_says_where_it_cannot() {
    let doc = temp_file(
        "lamp.scxml",
        br#"<scxml xmlns="http://www.w3.org/2005/07/scxml" initial="off" name="Lamp">
  <state id="off"><transition event="press" target="on"/></state>
  <state id="on" initial="dim">
    <onexit><raise event="clicked"/></onexit>
    <transition event="press" target="off"/>
    <state id="dim"><transition event="turn" target="bright"/></state>
    <state id="bright"/>
  </state>
</scxml>
"#,
    );
    let out = doc.with_file_name("lamp-imported");
    import_ok(&doc, &out);
    let file = out.join("Lamp.machine");
    let text = std::fs::read_to_string(&file).unwrap();
    assert!(
        text.contains("state on { // SCXML line 3\n    exit {\n        post(\"clicked\", TRUE);"),
        "{text}"
    );
    check(
        &["check", file.to_str().unwrap()],
        0,
        &format!(
            "{}: ok (1 machine, 3 states, 4 transitions, 0 warnings)\n",
            file.display()
        ),
    );
    let again = doc.with_file_name("lamp-again");
    import_ok(&file, &again);
    assert_eq!(
        std::fs::read_to_string(again.join("Lamp.machine")).unwrap(),
        text
    );

    // Exported as SCXML, it reads back as the same chart.
    let exported = doc.with_file_name("lamp-exported.scxml");
    let o = proclaim(&[
        "export",
        file.to_str().unwrap(),
        "-o",
        exported.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let scxml = std::fs::read_to_string(&exported).unwrap();
    assert!(
        scxml.contains("<state id=\"on\" initial=\"dim\">"),
        "{scxml}"
    );
    check(
        &["check", exported.to_str().unwrap()],
        0,
        &format!(
            "{}: ok (1 machine, 3 states, 4 transitions, 0 warnings)\n",
            exported.display()
        ),
    );
    let o = proclaim(&["export", doc.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));

    let parallel = temp_file(
        "both.scxml",
        b"<scxml xmlns=\"http://www.w3.org/2005/07/scxml\">\n  <parallel id=\"p\"/>\n</scxml>\n",
    );
    let o = proclaim(&[
        "import",
        parallel.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains(
            "both.scxml:2: error: <parallel> holding no states: it has no regions to run"
        ),
        "{}",
        stderr(&o)
    );
}

#[test]
fn import_writes_native_files_that_check_and_import_again_unchanged() {
    let t = temp_file(
        "TBlink.txt",
        b"1\tTRUE\t2\n2\tstop\t1\n2\ttimeout(500000)\t1\n",
    );
    temp_file(
        "ABlink.txt",
        b"2\tOn|OnEntry LEDS: Chest On;/ OnExit LEDS: Chest Off;/\n1\tOff|OnEntry C++: msleep(100);/\n",
    );
    let out = t.with_file_name("imported");
    import_ok(&t, &out);
    let file = out.join("Blink.machine");
    let first = std::fs::read_to_string(&file).unwrap();
    assert!(
        first.contains("initial Off\n")
            && first.contains("when timeout(500000) -> Off\n    when stop -> Off"),
        "{first}"
    );
    check(
        &["check", file.to_str().unwrap()],
        0,
        &format!(
            "{}: ok (1 machine, 2 states, 3 transitions, 0 warnings)\n",
            file.display()
        ),
    );
    // Importing the native file again writes the same machine.
    let again = t.with_file_name("again");
    import_ok(&file, &again);
    let second = std::fs::read_to_string(again.join("Blink.machine")).unwrap();
    let body = |text: &str| text.lines().skip(1).collect::<Vec<_>>().join("\n");
    assert_eq!(body(&second), body(&first));

    let bad = temp_file("bad.machine", b"machine M\nstate A {\n  when -> A\n}\n");
    let o = proclaim(&[
        "import",
        bad.to_str().unwrap(),
        "-o",
        again.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("bad.machine:3: error: a transition needs a label"),
        "{}",
        stderr(&o)
    );
    let o = proclaim(&["import", "offside", "-o", again.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("offside is not a machine file"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn check_draw_deps_and_liveness_on_behaviours() {
    let repo = env!("CARGO_MANIFEST_DIR");
    let gc = format!("{repo}/machines/game_controller");
    check(
        &["check", &gc],
        0,
        &format!("{gc}: ok (2 machines, 0 theories, 2 sensors; 0 errors, 0 warnings)\n"),
    );
    // Built-in behaviours are found by name too.
    let o = proclaim(&["deps", "game_controller", "--module", "GameController"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        stdout(&o).contains(
            "\"gamecontroller\" -> \"GameController\" [color=green4, label=\"readyReceived\"];"
        ),
        "{}",
        stdout(&o)
    );
    let o = proclaim(&["deps", "game_controller", "--module", "Nobody"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains(
            "no module `Nobody`; the behaviour has GameController, Placer, gamecontroller"
        ),
        "{}",
        stderr(&o)
    );

    let svg = temp_file("gc.svg", b"");
    let o = proclaim(&["draw", "game_controller", "-o", svg.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let has_graphviz = Command::new("dot").arg("-V").output().is_ok();
    if has_graphviz {
        let text = std::fs::read_to_string(&svg).unwrap();
        assert!(text.contains("<svg") && text.contains("Placer"), "{text}");
    } else {
        let dot = std::fs::read_to_string(svg.with_extension("dot")).unwrap();
        assert!(dot.contains("subgraph cluster_1"), "{dot}");
    }

    let formulas = temp_file(
        "test.liveness",
        b"TestBehavior = (Play | NoPlay)+\nPlay = SitDownAndStare | StandUpAndScan\n",
    );
    let out = formulas.with_file_name("skeleton");
    let o = proclaim(&[
        "liveness",
        formulas.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let o = proclaim(&["check", out.to_str().unwrap(), "--json"]);
    assert_eq!(o.status.code(), Some(1), "open labels are errors");
    let report: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_one_problem_shape(&report);
    let messages: Vec<&str> = report
        .as_array()
        .unwrap()
        .iter()
        .map(|d| d["message"].as_str().unwrap())
        .collect();
    assert_eq!(messages.len(), 8, "{messages:#?}");
    assert!(
        messages.contains(&"label `againPlay` is answered by no expert and posted by no module")
    );

    let bad = temp_file("bad.liveness", b"A = (B | C\n");
    let o = proclaim(&[
        "liveness",
        bad.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("bad.liveness:1: error: in the formula of `A`: missing `)`"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn import_writes_a_label_it_cannot_read_as_a_comment_and_fails() {
    let fsm = temp_file(
        "Kicker.fsm",
        br#"<qfsmproject><machine name="FSM" initialstate="0">
<state code="0" description="OnEntry { int n; n = n + 1; postv(&quot;walk&quot;, n, -n); }">Start</state>
<state code="1" description="">End</state>
<transition><from>0</from><to>1</to><inputs>ball &amp;&amp; </inputs></transition>
<transition><from>0</from><to>-1</to><inputs>x</inputs></transition>
<transition><from>0</from><to>1</to><inputs>n &gt; 2</inputs></transition>
</machine></qfsmproject>"#,
    );
    let out_dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("proclaim-import-bad-{}", std::process::id()));
    let o = proclaim(&[
        "import",
        fsm.to_str().unwrap(),
        "-o",
        out_dir.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains("Kicker.fsm:4: error: label `ball &&`"),
        "{err}"
    );
    assert!(
        err.contains("Kicker.fsm:5: warning: a transition without `<from>` or `<to>`"),
        "{err}"
    );
    // Named after its file, not its `name="FSM"`; the unread label kept as a comment.
    let text = std::fs::read_to_string(out_dir.join("Kicker.machine")).unwrap();
    assert!(
        text.contains("machine Kicker\ndescription \"FSM\"\n"),
        "{text}"
    );
    assert!(
        text.contains("    // not read (line 4: expected a name, a number, a string, `(`, `!` or `-`, found the end (at column 9)): when ball && -> End\n"),
        "{text}"
    );
    assert!(
        text.contains("        n = n + 1;\n        postv(\"walk\", n, -n);\n"),
        "{text}"
    );
    assert!(text.contains("    when n > 2 -> End\n"), "{text}");
}

#[test]
fn deps_launch_writes_a_manifest_that_runs_from_where_it_is_written() {
    let elsewhere = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("proclaim-launch-{}", std::process::id()));
    std::fs::create_dir_all(&elsewhere).unwrap();
    let manifest = elsewhere.join("placer.toml");
    let o = proclaim(&[
        "deps",
        "machines/game_controller",
        "--launch",
        "Placer",
        "-o",
        manifest.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let o = proclaim(&["run", manifest.to_str().unwrap(), "--for", "5s"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        stdout(&o).contains("Placer  finished in IN_POSITION"),
        "{}",
        stdout(&o)
    );
}

/// `proclaim import FILE -o DIR`, which must succeed.
#[track_caller]
fn import_ok(file: &std::path::Path, dir: &std::path::Path) {
    let o = proclaim(&[
        "import",
        file.to_str().unwrap(),
        "-o",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
}
