//! Nested states as the flat machine they lower to (`docs/spec/behaviour.md` §3.2): each test
//! a chart and the flat states, arrivals, arms and leavings written out.

use proclaim_fsm::{parse_machine, to_native, Action, Machine};

/// Posts only, so that what runs reads as the order it runs in.
fn said(actions: &[Action]) -> String {
    let words: Vec<String> = actions
        .iter()
        .map(|a| match a {
            Action::Post { ty, content } if content.is_empty() => ty.clone(),
            Action::Post { ty, content } => format!("{ty}:{content}"),
            other => format!("{other:?}"),
        })
        .collect();
    words.join(" ")
}

fn written(machine: &Machine) -> String {
    let name = |id| {
        machine
            .state(id)
            .map_or("?".to_string(), |s| format!("{}#{id}", s.name))
    };
    let mut out = format!("initial {}\n", name(machine.initial));
    for s in &machine.states {
        out += &format!(
            "{}#{} entry[{}] exit[{}] internal[{}]\n",
            s.name,
            s.id,
            said(&s.on_entry),
            said(&s.on_exit),
            said(&s.internal)
        );
        for t in machine.outgoing(s.id) {
            let leaving = t
                .leaving
                .as_deref()
                .map_or(String::new(), |l| format!(" leaving[{}]", said(l)));
            let on = t.composite.map_or(String::new(), |c| {
                format!(" of {}", machine.composites[c].name)
            });
            let stays = if t.stays { " stays" } else { "" };
            out += &format!("  {} -> {}{leaving}{on}{stays}\n", t.label, name(t.target));
        }
    }
    out
}

fn check(text: &str, expect: &str) {
    let read = parse_machine("M.machine", text);
    let got = if read.has_errors() {
        let errors: Vec<String> = read
            .diagnostics
            .iter()
            .map(|d| format!("{}: {}", d.line.unwrap_or(0), d.message))
            .collect();
        errors.join("\n") + "\n"
    } else {
        written(&read.machines[0])
    };
    assert_eq!(got, expect, "\n{got}");
}

#[test]
fn a_composite_transition_is_tried_after_its_states_own_and_leaves_them_innermost_first() {
    check(
        "machine M
state PLAY {
    exit {
        PlayOff:
    }
    when gameOver -> FINISHED
    state SEARCH {
        exit {
            SearchOff:
        }
        when seen -> KICK
    }
    state KICK { when kicked -> SEARCH }
}
state FINISHED { }
",
        "initial PLAY.SEARCH#1
PLAY.SEARCH#1 entry[] exit[SearchOff] internal[]
  seen -> PLAY.KICK#2
  gameOver -> FINISHED#3 leaving[SearchOff PlayOff] of PLAY
PLAY.KICK#2 entry[] exit[] internal[]
  kicked -> PLAY.SEARCH#1
  gameOver -> FINISHED#3 leaving[PlayOff] of PLAY
FINISHED#3 entry[] exit[] internal[]
",
    );
}

#[test]
fn a_move_inside_a_composite_does_not_enter_it_again_but_one_from_outside_does() {
    check(
        "machine M
initial IDLE
state IDLE { when go -> PLAY }
state PLAY {
    entry {
        PlayOn:
    }
    internal {
        Playing:
    }
    initial KICK
    when stop -> IDLE
    state SEARCH {
        entry {
            Search:
        }
        internal {
            Looking:
        }
        when seen -> KICK
    }
    state KICK {
        entry {
            Kick:
        }
        when kicked -> SEARCH
        when again -> PLAY
    }
}
",
        "initial IDLE#1
IDLE#1 entry[] exit[] internal[]
  go -> PLAY.KICK#3
PLAY.SEARCH#2 entry[Search] exit[] internal[Playing Looking]
  seen -> PLAY.KICK#4
  stop -> IDLE#1 of PLAY
PLAY.KICK#3 entry[PlayOn Kick] exit[] internal[Playing]
  kicked -> PLAY.SEARCH#2
  again -> PLAY.KICK#3
  stop -> IDLE#1 of PLAY
PLAY.KICK#4 entry[Kick] exit[] internal[Playing]
  kicked -> PLAY.SEARCH#2
  again -> PLAY.KICK#3
  stop -> IDLE#1 of PLAY
",
    );
}

#[test]
fn done_fires_from_a_final_state_of_its_composite_only() {
    check(
        "machine M
state DIVE {
    exit {
        Up:
    }
    when done -> GUARD
    when hurt -> GUARD
    state FALL { when landed -> LIE }
    state LIE { }
}
state GUARD { when ball -> DIVE }
",
        "initial DIVE.FALL#1
DIVE.FALL#1 entry[] exit[] internal[]
  landed -> DIVE.LIE#2
  hurt -> GUARD#3 leaving[Up] of DIVE
DIVE.LIE#2 entry[] exit[] internal[]
  TRUE -> GUARD#3 leaving[Up] of DIVE
  hurt -> GUARD#3 leaving[Up] of DIVE
GUARD#3 entry[] exit[] internal[]
  ball -> DIVE.FALL#1
",
    );
}

#[test]
fn targets_are_found_beside_the_source_then_outwards_or_by_path() {
    check(
        "machine M
state A {
    state X { when p -> Y }
    state Y { when q -> B.X }
}
state B {
    state X { when r -> A }
    state Z { when s -> Y }
}
",
        "initial A.X#1
A.X#1 entry[] exit[] internal[]
  p -> A.Y#2
A.Y#2 entry[] exit[] internal[]
  q -> B.X#3
B.X#3 entry[] exit[] internal[]
  r -> A.X#1
B.Z#4 entry[] exit[] internal[]
  s -> A.Y#2
",
    );
}

#[test]
fn a_history_resumes_where_its_composite_was_left() {
    check(
        "machine M
state PLAY {
    exit {
        PlayOff:
    }
    when whistle -> PAUSE
    state SEARCH { when seen -> KICK }
    state KICK { when again -> PLAY.history }
}
state PAUSE {
    when resume -> PLAY.history
    when restart -> PLAY
}
",
        "initial PLAY.SEARCH#1
PLAY.SEARCH#1 entry[Statement(Declare { ty: Int, name: \"PLAY_history\", value: None })] exit[] internal[]
  seen -> PLAY.KICK#2
  whistle -> PAUSE#3 leaving[Statement(Assign { name: \"PLAY_history\", value: Int(1) }) PlayOff] of PLAY
PLAY.KICK#2 entry[] exit[] internal[]
  again -> PLAY.KICK#2 leaving[Statement(Assign { name: \"PLAY_history\", value: Int(2) }) PlayOff]
  whistle -> PAUSE#3 leaving[Statement(Assign { name: \"PLAY_history\", value: Int(2) }) PlayOff] of PLAY
PAUSE#3 entry[] exit[] internal[]
  PLAY_history == 1 && resume -> PLAY.SEARCH#1
  PLAY_history == 2 && resume -> PLAY.KICK#2
  resume -> PLAY.SEARCH#1
  restart -> PLAY.SEARCH#1
",
    );
}

/// A shallow history of a state that holds a parallel state resumes its own state: left from
/// inside the parallel state, it comes back to it with every region at its initial (SCXML's
/// shallow history); the history of the parallel state itself is entering it.
#[test]
fn a_shallow_history_around_regions_resumes_the_parallel_state_whole() {
    check(
        "machine M
state GAME {
    when whistle -> PAUSE
    state READY { when go -> PLAY }
    parallel PLAY {
        state HEAD {
            state LOOK { when seen -> TRACK }
            state TRACK { }
        }
        state BODY {
            state WALK { when near -> KICK }
            state KICK { }
        }
    }
}
state PAUSE {
    when resume -> GAME.history
    when again -> GAME.PLAY.history
}
",
        "initial GAME.READY#1
GAME.READY#1 entry[Statement(Declare { ty: Int, name: \"GAME_history\", value: None })] exit[] internal[]
  go -> GAME.PLAY.HEAD.LOOK, GAME.PLAY.BODY.WALK#7
  whistle -> PAUSE#6 leaving[Statement(Assign { name: \"GAME_history\", value: Int(1) })] of GAME
GAME.PLAY.HEAD.LOOK, GAME.PLAY.BODY.WALK#7 entry[] exit[] internal[]
  seen && near -> GAME.PLAY.HEAD.TRACK, GAME.PLAY.BODY.KICK#8 leaving[] of GAME.PLAY.HEAD.LOOK
  seen -> GAME.PLAY.HEAD.TRACK, GAME.PLAY.BODY.WALK#9 leaving[] of GAME.PLAY.HEAD.LOOK
  near -> GAME.PLAY.HEAD.LOOK, GAME.PLAY.BODY.KICK#10 leaving[] of GAME.PLAY.BODY.WALK
  whistle -> PAUSE#6 leaving[Statement(Assign { name: \"GAME_history\", value: Int(2) })] of GAME
GAME.PLAY.HEAD.LOOK, GAME.PLAY.BODY.KICK#10 entry[] exit[] internal[]
  seen -> GAME.PLAY.HEAD.TRACK, GAME.PLAY.BODY.KICK#8 leaving[] of GAME.PLAY.HEAD.LOOK
  whistle -> PAUSE#6 leaving[Statement(Assign { name: \"GAME_history\", value: Int(2) })] of GAME
GAME.PLAY.HEAD.TRACK, GAME.PLAY.BODY.WALK#9 entry[] exit[] internal[]
  near -> GAME.PLAY.HEAD.TRACK, GAME.PLAY.BODY.KICK#8 leaving[] of GAME.PLAY.BODY.WALK
  whistle -> PAUSE#6 leaving[Statement(Assign { name: \"GAME_history\", value: Int(2) })] of GAME
GAME.PLAY.HEAD.TRACK, GAME.PLAY.BODY.KICK#8 entry[] exit[] internal[]
  whistle -> PAUSE#6 leaving[Statement(Assign { name: \"GAME_history\", value: Int(2) })] of GAME
PAUSE#6 entry[] exit[] internal[]
  GAME_history == 1 && resume -> GAME.READY#1
  GAME_history == 2 && resume -> GAME.PLAY.HEAD.LOOK, GAME.PLAY.BODY.WALK#7
  resume -> GAME.READY#1
  again -> GAME.PLAY.HEAD.LOOK, GAME.PLAY.BODY.WALK#7
",
    );
}

/// A deep history around regions notes the configuration it was left in, one atomic state in
/// each region (in file order: READY, then each combination of HEAD's and BODY's), and
/// resumes it whole, as several targets do; one past 4,096 configurations is refused.
#[test]
fn a_deep_history_around_regions_resumes_the_configuration_it_left() {
    check(
        "machine M
state GAME {
    when whistle -> PAUSE
    state READY { when go -> PLAY }
    parallel PLAY {
        state HEAD {
            state LOOK { when seen -> TRACK }
            state TRACK { }
        }
        state BODY {
            state WALK { when near -> KICK }
            state KICK { }
        }
    }
}
state PAUSE { when resume -> GAME.deep_history }
",
        "initial GAME.READY#1
GAME.READY#1 entry[Statement(Declare { ty: Int, name: \"GAME_deep_history\", value: None })] exit[] internal[]
  go -> GAME.PLAY.HEAD.LOOK, GAME.PLAY.BODY.WALK#7
  whistle -> PAUSE#6 leaving[Statement(Assign { name: \"GAME_deep_history\", value: Int(1) })] of GAME
GAME.PLAY.HEAD.LOOK, GAME.PLAY.BODY.WALK#7 entry[] exit[] internal[]
  seen && near -> GAME.PLAY.HEAD.TRACK, GAME.PLAY.BODY.KICK#8 leaving[] of GAME.PLAY.HEAD.LOOK
  seen -> GAME.PLAY.HEAD.TRACK, GAME.PLAY.BODY.WALK#9 leaving[] of GAME.PLAY.HEAD.LOOK
  near -> GAME.PLAY.HEAD.LOOK, GAME.PLAY.BODY.KICK#10 leaving[] of GAME.PLAY.BODY.WALK
  whistle -> PAUSE#6 leaving[Statement(Assign { name: \"GAME_deep_history\", value: Int(2) })] of GAME
GAME.PLAY.HEAD.LOOK, GAME.PLAY.BODY.KICK#10 entry[] exit[] internal[]
  seen -> GAME.PLAY.HEAD.TRACK, GAME.PLAY.BODY.KICK#8 leaving[] of GAME.PLAY.HEAD.LOOK
  whistle -> PAUSE#6 leaving[Statement(Assign { name: \"GAME_deep_history\", value: Int(3) })] of GAME
GAME.PLAY.HEAD.TRACK, GAME.PLAY.BODY.WALK#9 entry[] exit[] internal[]
  near -> GAME.PLAY.HEAD.TRACK, GAME.PLAY.BODY.KICK#8 leaving[] of GAME.PLAY.BODY.WALK
  whistle -> PAUSE#6 leaving[Statement(Assign { name: \"GAME_deep_history\", value: Int(4) })] of GAME
GAME.PLAY.HEAD.TRACK, GAME.PLAY.BODY.KICK#8 entry[] exit[] internal[]
  whistle -> PAUSE#6 leaving[Statement(Assign { name: \"GAME_deep_history\", value: Int(5) })] of GAME
PAUSE#6 entry[] exit[] internal[]
  GAME_deep_history == 1 && resume -> GAME.READY#1
  GAME_deep_history == 2 && resume -> GAME.PLAY.HEAD.LOOK, GAME.PLAY.BODY.WALK#7
  GAME_deep_history == 3 && resume -> GAME.PLAY.HEAD.LOOK, GAME.PLAY.BODY.KICK#10
  GAME_deep_history == 4 && resume -> GAME.PLAY.HEAD.TRACK, GAME.PLAY.BODY.WALK#9
  GAME_deep_history == 5 && resume -> GAME.PLAY.HEAD.TRACK, GAME.PLAY.BODY.KICK#8
  resume -> GAME.READY#1
",
    );
    let regions: String = (0..13)
        .map(|r| format!("        state R{r} {{ state X{r} {{ }} state Y{r} {{ }} }}\n"))
        .collect();
    check(
        &format!(
            "machine M\nstate GAME {{\n    when whistle -> PAUSE\n    parallel PLAY {{\n{regions}    }}\n}}\nstate PAUSE {{ when resume -> GAME.deep_history }}\n"
        ),
        "20: `GAME` holds more than 4096 configurations of states for a deep history to resume: resume its own state (`GAME.history`)\n",
    );
}

/// Several targets (SCXML's `target="a b"`) enter a state in each of several regions at once:
/// the regions they name at those states, any other region at its initial. A move from inside
/// the parallel state to states of two of its regions leaves it and enters it again. Targets
/// that could not be active together, or a history among them, are refused where written.
#[test]
fn several_targets_enter_a_state_in_each_region() {
    check(
        "machine M
state READY {
    when go -> PLAY.HEAD.TRACK, PLAY.BODY.KICK
    when half -> PLAY.BODY.KICK
}
parallel PLAY {
    exit {
        PlayOff:
    }
    when whistle -> READY
    state HEAD {
        state LOOK { when seen -> TRACK }
        state TRACK { when lost -> HEAD.LOOK, BODY.WALK }
    }
    state BODY {
        state WALK { when near -> KICK }
        state KICK { }
    }
}
",
        "initial READY#1
READY#1 entry[] exit[] internal[]
  go -> PLAY.HEAD.TRACK, PLAY.BODY.KICK#6
  half -> PLAY.HEAD.LOOK, PLAY.BODY.KICK#7
PLAY.HEAD.LOOK, PLAY.BODY.WALK#8 entry[] exit[] internal[]
  seen && near -> PLAY.HEAD.TRACK, PLAY.BODY.KICK#6 leaving[] of PLAY.HEAD.LOOK
  seen -> PLAY.HEAD.TRACK, PLAY.BODY.WALK#9 leaving[] of PLAY.HEAD.LOOK
  near -> PLAY.HEAD.LOOK, PLAY.BODY.KICK#7 leaving[] of PLAY.BODY.WALK
  whistle -> READY#1 leaving[PlayOff] of PLAY
PLAY.HEAD.LOOK, PLAY.BODY.KICK#7 entry[] exit[] internal[]
  seen -> PLAY.HEAD.TRACK, PLAY.BODY.KICK#6 leaving[] of PLAY.HEAD.LOOK
  whistle -> READY#1 leaving[PlayOff] of PLAY
PLAY.HEAD.TRACK, PLAY.BODY.WALK#9 entry[] exit[] internal[]
  lost -> PLAY.HEAD.LOOK, PLAY.BODY.WALK#8 leaving[PlayOff] of PLAY.HEAD.TRACK
  near -> PLAY.HEAD.TRACK, PLAY.BODY.KICK#6 leaving[] of PLAY.BODY.WALK
  whistle -> READY#1 leaving[PlayOff] of PLAY
PLAY.HEAD.TRACK, PLAY.BODY.KICK#6 entry[] exit[] internal[]
  lost -> PLAY.HEAD.LOOK, PLAY.BODY.WALK#8 leaving[PlayOff] of PLAY.HEAD.TRACK
  whistle -> READY#1 leaving[PlayOff] of PLAY
",
    );
    check(
        "machine M
state READY {
    when a -> PLAY.HEAD.LOOK, PLAY.HEAD.TRACK
    when b -> PLAY.HEAD, PLAY.HEAD.LOOK
    when c -> PLAY.HEAD.LOOK, PLAY.BODY.history
    when d -> PLAY.HEAD.LOOK, NOWHERE
    when e -> PLAY.history, PLAY.HEAD.LOOK
}
parallel PLAY {
    state HEAD {
        state LOOK { }
        state TRACK { }
    }
    state BODY {
        state WALK { }
    }
}
",
        "3: `PLAY.HEAD.LOOK` and `PLAY.HEAD.TRACK` are not in different regions of a parallel state: several targets enter one state in each region
4: `PLAY.HEAD` and `PLAY.HEAD.LOOK` are not in different regions of a parallel state: several targets enter one state in each region
5: a history is a target of its own: it resumes one state, and another target cannot join it
6: there is no state named `NOWHERE`
7: a history is a target of its own: it resumes one state, and another target cannot join it
",
    );
    check(
        "machine M\nstate A { when go -> B, C }\nstate B { }\nstate C { }\n",
        "2: several targets enter a state in each region of a parallel state, and this machine has none: name one target\n",
    );
}

#[test]
fn a_transitions_own_actions_run_after_what_it_leaves() {
    check(
        "machine M
state A {
    exit {
        AOff:
    }
    when p -> B {
        Moved: 1
    }
    when q -> B
}
state B { }
",
        "initial A#1
A#1 entry[] exit[AOff] internal[]
  p -> B#2 leaving[AOff Moved:1]
  q -> B#2
B#2 entry[] exit[] internal[]
",
    );
    check(
        "machine M
state P {
    exit {
        POff:
    }
    when stop -> Q {
        Stopped:
    }
    state A {
        exit {
            AOff:
        }
        when p -> B {
            Moved:
        }
    }
    state B { }
}
state Q { }
",
        "initial P.A#1
P.A#1 entry[] exit[AOff] internal[]
  p -> P.B#2 leaving[AOff Moved]
  stop -> Q#3 leaving[AOff POff Stopped] of P
P.B#2 entry[] exit[] internal[]
  stop -> Q#3 leaving[POff Stopped] of P
Q#3 entry[] exit[] internal[]
",
    );
}

/// A transition without a target acts and stays (§3.2): its own actions run, no OnExit and,
/// after it, no OnEntry. Written on a composite, it stays in whichever state inside fired it;
/// in a region, it fires beside another region's move, which alone enters anything; when all
/// that fires stays, the machine stays in its very flat state.
#[test]
fn a_transition_without_a_target_runs_its_own_actions_and_stays() {
    check(
        "machine M
state A {
    exit {
        AOff:
    }
    when p {
        Counted:
    }
    when q { }
    when r -> B
}
state B { }
",
        "initial A#1
A#1 entry[] exit[AOff] internal[]
  p -> A#1 leaving[Counted] stays
  q -> A#1 leaving[] stays
  r -> B#2
B#2 entry[] exit[] internal[]
",
    );
    check(
        "machine M
state P {
    exit {
        POff:
    }
    when tick {
        Ticked:
    }
    state A {
        when p -> B
    }
    state B { }
}
",
        "initial P.A#1
P.A#1 entry[] exit[] internal[]
  p -> P.B#2
  tick -> P.A#1 leaving[Ticked] of P stays
P.B#2 entry[] exit[] internal[]
  tick -> P.B#2 leaving[Ticked] of P stays
",
    );
    check(
        "machine M
parallel P {
    state L {
        state L0 {
            entry {
                L0On:
            }
            when a {
                Counted:
            }
        }
    }
    state R {
        state R0 {
            when b -> R1
        }
        state R1 {
            entry {
                R1On:
            }
        }
    }
}
",
        "initial P.L.L0, P.R.R0#4
P.L.L0, P.R.R0#4 entry[L0On] exit[] internal[]
  a && b -> P.L.L0, P.R.R1#5 leaving[Counted] of P.L.L0
  a -> P.L.L0, P.R.R0#4 leaving[Counted] of P.L.L0 stays
  b -> P.L.L0, P.R.R1#5 leaving[] of P.R.R0
P.L.L0, P.R.R1#5 entry[R1On] exit[] internal[]
  a -> P.L.L0, P.R.R1#5 leaving[Counted] of P.L.L0 stays
",
    );
    // SCXML's conflict rule: one that stays leaves nothing, so it conflicts with no move and
    // fires beside another region's move out of the parallel state, before it or after it.
    let beside = |first: &str, second: &str| {
        format!("machine M\nparallel P {{\n    state L {{\n        state L0 {{\n            {first}\n        }}\n    }}\n    state R {{\n        state R0 {{\n            {second}\n        }}\n    }}\n}}\nstate Q {{ }}\n")
    };
    check(
        &beside(
            "when a {\n                Counted:\n            }",
            "when b -> Q",
        ),
        "initial P.L.L0, P.R.R0#4
P.L.L0, P.R.R0#4 entry[] exit[] internal[]
  a && b -> Q#3 leaving[Counted] of P.L.L0
  a -> P.L.L0, P.R.R0#4 leaving[Counted] of P.L.L0 stays
  b -> Q#3 leaving[] of P.R.R0
Q#3 entry[] exit[] internal[]
",
    );
    check(
        &beside(
            "when b -> Q",
            "when a {\n                Counted:\n            }",
        ),
        "initial P.L.L0, P.R.R0#4
P.L.L0, P.R.R0#4 entry[] exit[] internal[]
  b && a -> Q#3 leaving[Counted] of P.L.L0
  b -> Q#3 leaving[] of P.L.L0
  a -> P.L.L0, P.R.R0#4 leaving[Counted] of P.R.R0 stays
Q#3 entry[] exit[] internal[]
",
    );
}

/// A transition that stays is written back as it was written, with its block.
#[test]
fn a_transition_that_stays_is_written_back() {
    let text = "machine M\nstate A {\n    exit {\n        Off: now\n    }\n    when p {\n        n = n + 1;\n    }\n    when q { }\n    when r -> A\n}\n";
    let read = parse_machine("M.machine", text);
    assert!(!read.has_errors(), "{:?}", read.diagnostics);
    let written = to_native(&read.machines[0]);
    assert!(
        written
            .contains("    when p {\n        n = n + 1;\n    }\n    when q { }\n    when r -> A\n"),
        "{written}"
    );
    let again = parse_machine("M.machine", &written);
    let what = |m: &Machine| -> Vec<_> {
        (m.transitions.iter())
            .map(|t| (t.target, t.stays, t.leaving.clone()))
            .collect()
    };
    assert_eq!(what(&again.machines[0]), what(&read.machines[0]));
    assert_eq!(to_native(&again.machines[0]), written);
}

/// A flat machine's transition actions survive being written again (`proclaim import` of a
/// native file).
#[test]
fn a_transitions_own_actions_are_written_back() {
    let text = "machine M\nstate A {\n    exit {\n        Off: now\n    }\n    when p -> B {\n        n = n + 1;\n    }\n}\nstate B {\n}\n";
    let read = parse_machine("M.machine", text);
    assert!(!read.has_errors(), "{:?}", read.diagnostics);
    let written = to_native(&read.machines[0]);
    assert!(
        written.contains("when p -> B {\n        n = n + 1;\n    }"),
        "{written}"
    );
    let again = parse_machine("M.machine", &written);
    let leaving = |m: &Machine| m.transitions[0].leaving.clone();
    assert_eq!(leaving(&again.machines[0]), leaving(&read.machines[0]));
    assert_eq!(to_native(&again.machines[0]), written);
}

#[test]
fn what_cannot_be_lowered_is_refused_at_its_place() {
    check(
        "machine M
state A {
    when done -> B
    when p -> B
    initial Z
    state X { when done -> B }
    state X { when p -> SEARCH }
}
state B { state SEARCH { } state S.T { } state history { } }
state C { state SEARCH { } when p -> B.SEARCH.history }
state D { when done -> C  state E { when p -> E } }
",
        "9: `S.T`: a state's name cannot hold `.` where states nest, since `.` separates a path (`PLAY.SEARCH`)
9: `history` names a composite's history where states nest (`-> PLAY.history`): call the state something else
7: two states are named `X` in `A`
5: `A` holds no state named `Z`
3: `when done` on `A` never fires: no state directly in it is final (has no transition of its own)
6: `when done` belongs to a state that holds states (it fires once the one it is in is final); `A.X` holds none
7: `SEARCH` could be `B.SEARCH` or `C.SEARCH`: write the path of the one meant
10: `B.SEARCH` holds no states, so it has no history to resume
11: `when done` on `D` never fires: no state directly in it is final (has no transition of its own)
",
    );
}

#[test]
fn a_flat_file_reads_as_it_always_did() {
    check(
        "machine M
state A {
    exit {
        Off:
    }
    when p -> B
}
state B { }
",
        "initial A#1
A#1 entry[] exit[Off] internal[]
  p -> B#2
B#2 entry[] exit[] internal[]
",
    );
}

/// A file nesting deeper than any chart is refused at the place, not read until the stack ends.
#[test]
fn nesting_past_its_bound_is_refused_at_its_line() {
    let depth = 100_000;
    let mut text = String::from("machine M\n");
    for i in 0..depth {
        text.push_str(&format!("state S{i} {{\n"));
    }
    text.push_str(&"}\n".repeat(depth));
    let read = parse_machine("M.machine", &text);
    assert!(read.machines.is_empty());
    let said: Vec<String> = read
        .diagnostics
        .iter()
        .map(|d| format!("{}: {}", d.line.unwrap_or(0), d.message))
        .collect();
    assert_eq!(said, ["258: blocks nest deeper than 256"]);
}

#[test]
fn a_historys_variable_never_takes_the_name_a_parameter_becomes() {
    // `Dive`'s parameter `history` is the global `Dive_history`; so would be the history of its
    // composite `Dive`, which must be told apart from it.
    let text = "machine Dive
param history: int
state Dive {
    when stop -> REST
    state LOW { when h > history -> HIGH }
    state HIGH { }
}
state REST {
    when resume -> Dive.history
}
";
    let read = parse_machine("Dive.machine", text);
    assert!(!read.has_errors(), "{:?}", read.diagnostics);
    let got = written(&read.machines[0]);
    assert!(got.contains("\"Dive_history2\""), "{got}");
    assert!(
        got.contains("h > Dive_history"),
        "the parameter is still read: {got}"
    );
}

#[test]
fn a_label_lowering_changed_is_shown_as_written() {
    let text = "machine Dive
param side: int
outcome landed
state FALL {
    when done -> REST
    when stop -> REST
    state LOW { when side < 0 -> OUT }
    state OUT { }
}
state REST {
    when resume -> FALL.history
}
";
    let read = parse_machine("Dive.machine", text);
    assert!(!read.has_errors(), "{:?}", read.diagnostics);
    let shown: Vec<(String, String)> = read.machines[0]
        .transitions
        .iter()
        .map(|t| (t.label.to_string(), t.shown().to_string()))
        .collect();
    let has = |run: &str, seen: &str| shown.iter().any(|(l, s)| l == run && s == seen);
    assert!(has("Dive_side < 0", "side < 0"), "{shown:?}");
    assert!(has("TRUE", "done"), "{shown:?}");
    assert!(has("FALL_history == 1 && resume", "resume"), "{shown:?}");
    // What lowering left alone has nothing else to show.
    assert!(read.machines[0]
        .transitions
        .iter()
        .any(|t| t.written.is_none() && t.label.to_string() == "stop"));
}

/// A composite's transition back into itself is drawn out of its cluster's edge to a point
/// and in again, not as an edge between two states inside it (which Graphviz would draw, and
/// warn of, since the head is inside the tail's cluster).
#[test]
fn a_composite_entered_again_by_its_own_transition_is_drawn_leaving_it() {
    let text = "machine M
initial PLAY
state PLAY {
    when again -> PLAY
    state A { when a -> B }
    state B { when b -> A }
}
";
    let read = parse_machine("M.machine", text);
    assert!(!read.has_errors(), "{:?}", read.diagnostics);
    let dot = proclaim_fsm::to_dot(&read.machines[0]);
    let edges: Vec<&str> = dot
        .lines()
        .map(str::trim)
        .filter(|l| l.contains("->"))
        .collect();
    assert!(
        edges.contains(
            &"s2 -> cluster_c0_back4 [label=\"1: again\", ltail=\"cluster_c0\", arrowhead=none];"
        ),
        "{dot}"
    );
    assert!(edges.contains(&"cluster_c0_back4 -> s1;"), "{dot}");
    assert!(
        dot.contains("cluster_c0_back4 [shape=point, width=0.05];"),
        "{dot}"
    );
}

/// An `initial` may name a state deeper inside its composite, or one in each of several
/// regions (SCXML's `initial="a b"`): entering the composite enters the states around each,
/// and the regions none is in at their initial.
#[test]
fn an_initial_names_a_deeper_state_or_one_in_each_region() {
    check(
        "machine M
initial PLAY.HEAD.TRACK, PLAY.BODY.KICK
parallel PLAY {
    state HEAD {
        state LOOK { when seen -> TRACK }
        state TRACK { }
    }
    state BODY {
        state WALK { }
        state KICK { when far -> WALK }
    }
}
",
        "initial PLAY.HEAD.TRACK, PLAY.BODY.KICK#5
PLAY.HEAD.LOOK, PLAY.BODY.WALK#7 entry[] exit[] internal[]
  seen -> PLAY.HEAD.TRACK, PLAY.BODY.WALK#6 leaving[] of PLAY.HEAD.LOOK
PLAY.HEAD.TRACK, PLAY.BODY.WALK#6 entry[] exit[] internal[]
PLAY.HEAD.TRACK, PLAY.BODY.KICK#5 entry[] exit[] internal[]
  far -> PLAY.HEAD.TRACK, PLAY.BODY.WALK#6 leaving[] of PLAY.BODY.KICK
",
    );
    check(
        "machine M
state GAME {
    initial PLAY.BODY.KICK
    when whistle -> GAME
    state READY { when go -> PLAY }
    parallel PLAY {
        state HEAD {
            state LOOK { when seen -> TRACK }
            state TRACK { }
        }
        state BODY {
            state WALK { }
            state KICK { when far -> WALK }
        }
    }
}
",
        "initial GAME.PLAY.HEAD.LOOK, GAME.PLAY.BODY.KICK#6
GAME.READY#1 entry[] exit[] internal[]
  go -> GAME.PLAY.HEAD.LOOK, GAME.PLAY.BODY.WALK#9
  whistle -> GAME.PLAY.HEAD.LOOK, GAME.PLAY.BODY.KICK#6 of GAME
GAME.PLAY.HEAD.LOOK, GAME.PLAY.BODY.WALK#9 entry[] exit[] internal[]
  seen -> GAME.PLAY.HEAD.TRACK, GAME.PLAY.BODY.WALK#7 leaving[] of GAME.PLAY.HEAD.LOOK
  whistle -> GAME.PLAY.HEAD.LOOK, GAME.PLAY.BODY.KICK#6 leaving[] of GAME
GAME.PLAY.HEAD.LOOK, GAME.PLAY.BODY.KICK#6 entry[] exit[] internal[]
  seen && far -> GAME.PLAY.HEAD.TRACK, GAME.PLAY.BODY.WALK#7 leaving[] of GAME.PLAY.HEAD.LOOK
  seen -> GAME.PLAY.HEAD.TRACK, GAME.PLAY.BODY.KICK#8 leaving[] of GAME.PLAY.HEAD.LOOK
  far -> GAME.PLAY.HEAD.LOOK, GAME.PLAY.BODY.WALK#9 leaving[] of GAME.PLAY.BODY.KICK
  whistle -> GAME.PLAY.HEAD.LOOK, GAME.PLAY.BODY.KICK#6 leaving[] of GAME
GAME.PLAY.HEAD.TRACK, GAME.PLAY.BODY.WALK#7 entry[] exit[] internal[]
  whistle -> GAME.PLAY.HEAD.LOOK, GAME.PLAY.BODY.KICK#6 leaving[] of GAME
GAME.PLAY.HEAD.TRACK, GAME.PLAY.BODY.KICK#8 entry[] exit[] internal[]
  far -> GAME.PLAY.HEAD.TRACK, GAME.PLAY.BODY.WALK#7 leaving[] of GAME.PLAY.BODY.KICK
  whistle -> GAME.PLAY.HEAD.LOOK, GAME.PLAY.BODY.KICK#6 leaving[] of GAME
",
    );
    check(
        "machine M
initial PLAY.HEAD.TRACK, PLAY.HEAD.LOOK
state READY {
    initial #40
    state SET { }
}
parallel PLAY {
    state HEAD {
        state LOOK #40 { }
        state TRACK { }
    }
}
",
        "4: the initial state of `READY` must be a state inside it, not `PLAY.HEAD.LOOK`
2: `PLAY.HEAD.TRACK` and `PLAY.HEAD.LOOK` are not in different regions of a parallel state: several initial states enter one state in each region
",
    );
    check(
        "machine M\ninitial A, B\nstate A { }\nstate B { }\n",
        "2: several initial states enter a state in each region of a parallel state, and this machine has none: name one\n",
    );
}

/// A transition with several targets is drawn to a fork and from it into each target (it was
/// drawn into one of them alone).
#[test]
fn several_targets_are_drawn_forking_into_each() {
    let text = "machine M
state READY {
    when go -> PLAY.HEAD.TRACK, PLAY.BODY.KICK
}
parallel PLAY {
    when whistle -> READY
    state HEAD {
        state LOOK { when seen -> TRACK }
        state TRACK { when lost -> HEAD.LOOK, BODY.WALK }
    }
    state BODY {
        state WALK { when near -> KICK }
        state KICK { }
    }
}
";
    let read = parse_machine("M.machine", text);
    assert!(!read.has_errors(), "{:?}", read.diagnostics);
    let machine = &read.machines[0];
    let dot = proclaim_fsm::to_dot(machine);
    let node = |path: &str| {
        let c = (machine.composites.iter())
            .position(|c| c.atomic && c.name == path)
            .unwrap_or_else(|| panic!("{path} is a region's state"));
        format!("a{c}")
    };
    let forks: Vec<&str> = dot
        .lines()
        .map(str::trim)
        .filter(|l| l.contains("_fork"))
        .collect();
    let (track, kick) = (node("PLAY.HEAD.TRACK"), node("PLAY.BODY.KICK"));
    let (look, walk) = (node("PLAY.HEAD.LOOK"), node("PLAY.BODY.WALK"));
    assert_eq!(
        forks,
        [
            "s1_fork3 [shape=point, width=0.05];".to_string(),
            "s1 -> s1_fork3 [label=\"1: go\", arrowhead=none];".to_string(),
            format!("s1_fork3 -> {track};"),
            format!("s1_fork3 -> {kick};"),
            format!("{track}_fork9 [shape=point, width=0.05];"),
            format!("{track} -> {track}_fork9 [label=\"1: lost\", arrowhead=none];"),
            format!("{track}_fork9 -> {look};"),
            format!("{track}_fork9 -> {walk};"),
        ],
        "{dot}"
    );
}

/// Each flat state with what its arrival entered, and each arm with the composites it enters.
fn clocks(machine: &Machine) -> String {
    let composites = |list: &[usize]| {
        let names: Vec<&str> = list
            .iter()
            .map(|&c| machine.composites[c].name.as_str())
            .collect();
        names.join(" ")
    };
    let mut out = String::new();
    for s in &machine.states {
        out += &format!(
            "{}#{} arrived into [{}]\n",
            s.name,
            s.id,
            composites(&machine.arrival_enters(s))
        );
        for t in machine.outgoing(s.id) {
            let target = machine.state(t.target).map_or("?", |s| s.name.as_str());
            // Each time test's clock, as lowering gave it: a composite's entry, or the state's.
            let since: Vec<&str> = (t.label.time_tests().iter())
                .map(|&(_, _, clock)| clock.map_or("state", |c| &machine.composites[c].name))
                .collect();
            let since = match since.is_empty() {
                true => String::new(),
                false => format!(" since {}", since.join(" ")),
            };
            out += &format!(
                "  {}{since} -> {target}#{} enters [{}]\n",
                t.label,
                t.target,
                composites(&t.enters)
            );
        }
    }
    out
}

#[test]
fn a_composites_time_test_counts_from_its_entry_which_moves_inside_it_keep() {
    let read = parse_machine(
        "M.machine",
        "machine M
initial PLAY
state PLAY {
    when after(5s) -> REST
    when p -> PLAY
    state A { when after_ms(100) -> B }
    state B {
        when after_ms(100) -> A
        when q -> PLAY.history
    }
}
state REST { when p -> PLAY.B }
",
    );
    assert!(!read.has_errors(), "{:?}", read.diagnostics);
    // The arrivals that enter PLAY are kept apart from those that move inside it: only they
    // start its time. B's move to PLAY's history leaves PLAY and enters it again, back at B.
    let expect = "PLAY.A#1 arrived into [PLAY]
  after_ms(100) since state -> PLAY.B#2 enters []
  after(5s) since PLAY -> REST#3 enters []
  p -> PLAY.A#1 enters [PLAY]
PLAY.A#4 arrived into []
  after_ms(100) since state -> PLAY.B#2 enters []
  after(5s) since PLAY -> REST#3 enters []
  p -> PLAY.A#1 enters [PLAY]
PLAY.B#2 arrived into []
  after_ms(100) since state -> PLAY.A#4 enters []
  q -> PLAY.B#5 enters [PLAY]
  after(5s) since PLAY -> REST#3 enters []
  p -> PLAY.A#1 enters [PLAY]
PLAY.B#5 arrived into [PLAY]
  after_ms(100) since state -> PLAY.A#4 enters []
  q -> PLAY.B#5 enters [PLAY]
  after(5s) since PLAY -> REST#3 enters []
  p -> PLAY.A#1 enters [PLAY]
REST#3 arrived into []
  p -> PLAY.B#5 enters [PLAY]
";
    let got = clocks(&read.machines[0]);
    assert_eq!(got, expect, "\n{got}");
}

/// A striker whose head turns beside a body that searches and kicks: two regions.
const STRIKER: &str = "machine Striker
initial PLAY
parallel PLAY {
    when gameOver -> DONE
    state HEAD {
        state LEFT { when after_ms(400) -> RIGHT }
        state RIGHT { when after_ms(400) -> LEFT }
    }
    state BODY {
        state SEARCH { when ballSeen -> KICK }
        state KICK { when kicked -> DONE }
    }
}
state DONE { }
";

/// A parallel state's regions run side by side (`docs/spec/behaviour.md` §3.2): a flat state
/// for each pair of their states, whose arms are the combinations of what each region selects,
/// the first region's first; a transition that leaves the parallel state fires alone and is
/// preempted by an earlier region's move; each turn of the head keeps its own clock, which the
/// body's moves do not restart.
#[test]
fn regions_lower_to_the_combinations_of_their_choices() {
    let read = parse_machine("Striker.machine", STRIKER);
    assert!(!read.has_errors(), "{:?}", read.diagnostics);
    let got = clocks(&read.machines[0]);
    let expect = "PLAY.HEAD.LEFT, PLAY.BODY.SEARCH#6 arrived into [PLAY.HEAD.LEFT]
  after_ms(400) && ballSeen since PLAY.HEAD.LEFT -> PLAY.HEAD.RIGHT, PLAY.BODY.KICK#7 enters [PLAY.HEAD.RIGHT PLAY.BODY.KICK]
  after_ms(400) since PLAY.HEAD.LEFT -> PLAY.HEAD.RIGHT, PLAY.BODY.SEARCH#8 enters [PLAY.HEAD.RIGHT]
  ballSeen -> PLAY.HEAD.LEFT, PLAY.BODY.KICK#9 enters [PLAY.BODY.KICK]
  gameOver -> DONE#5 enters []
PLAY.HEAD.LEFT, PLAY.BODY.KICK#9 arrived into []
  after_ms(400) && kicked since PLAY.HEAD.LEFT -> PLAY.HEAD.RIGHT, PLAY.BODY.KICK#7 enters [PLAY.HEAD.RIGHT]
  after_ms(400) since PLAY.HEAD.LEFT -> PLAY.HEAD.RIGHT, PLAY.BODY.KICK#7 enters [PLAY.HEAD.RIGHT]
  kicked -> DONE#5 enters []
  gameOver -> DONE#5 enters []
PLAY.HEAD.LEFT, PLAY.BODY.KICK#10 arrived into [PLAY.HEAD.LEFT]
  after_ms(400) && kicked since PLAY.HEAD.LEFT -> PLAY.HEAD.RIGHT, PLAY.BODY.KICK#7 enters [PLAY.HEAD.RIGHT]
  after_ms(400) since PLAY.HEAD.LEFT -> PLAY.HEAD.RIGHT, PLAY.BODY.KICK#7 enters [PLAY.HEAD.RIGHT]
  kicked -> DONE#5 enters []
  gameOver -> DONE#5 enters []
PLAY.HEAD.RIGHT, PLAY.BODY.SEARCH#8 arrived into [PLAY.HEAD.RIGHT]
  after_ms(400) && ballSeen since PLAY.HEAD.RIGHT -> PLAY.HEAD.LEFT, PLAY.BODY.KICK#10 enters [PLAY.HEAD.LEFT PLAY.BODY.KICK]
  after_ms(400) since PLAY.HEAD.RIGHT -> PLAY.HEAD.LEFT, PLAY.BODY.SEARCH#6 enters [PLAY.HEAD.LEFT]
  ballSeen -> PLAY.HEAD.RIGHT, PLAY.BODY.KICK#11 enters [PLAY.BODY.KICK]
  gameOver -> DONE#5 enters []
PLAY.HEAD.RIGHT, PLAY.BODY.KICK#7 arrived into [PLAY.HEAD.RIGHT]
  after_ms(400) && kicked since PLAY.HEAD.RIGHT -> PLAY.HEAD.LEFT, PLAY.BODY.KICK#10 enters [PLAY.HEAD.LEFT]
  after_ms(400) since PLAY.HEAD.RIGHT -> PLAY.HEAD.LEFT, PLAY.BODY.KICK#10 enters [PLAY.HEAD.LEFT]
  kicked -> DONE#5 enters []
  gameOver -> DONE#5 enters []
PLAY.HEAD.RIGHT, PLAY.BODY.KICK#11 arrived into []
  after_ms(400) && kicked since PLAY.HEAD.RIGHT -> PLAY.HEAD.LEFT, PLAY.BODY.KICK#10 enters [PLAY.HEAD.LEFT]
  after_ms(400) since PLAY.HEAD.RIGHT -> PLAY.HEAD.LEFT, PLAY.BODY.KICK#10 enters [PLAY.HEAD.LEFT]
  kicked -> DONE#5 enters []
  gameOver -> DONE#5 enters []
DONE#5 arrived into []
";
    assert_eq!(got, expect, "\n{got}");
}

/// Regions are drawn as written (§3.2): each a dashed cluster holding its states, each state
/// once, a region's transition between its own states, the parallel state's from its cluster;
/// a state of every region lights together (`drawn_nodes`).
#[test]
fn regions_are_drawn_as_dashed_clusters_of_their_states() {
    let read = parse_machine("Striker.machine", STRIKER);
    assert!(!read.has_errors(), "{:?}", read.diagnostics);
    let machine = &read.machines[0];
    let dot = proclaim_fsm::to_dot(machine);
    for expected in [
        "label=\"HEAD\\l\"; labeljust=l; style=\"rounded,dashed\"",
        "a2 [label=\"LEFT\\n\", peripheries=2];",
        "a5 [label=\"SEARCH\\n\", peripheries=2];",
        "a2 -> a3 [label=\"1: after_ms(400)\"];",
        "a3 -> a2 [label=\"1: after_ms(400)\"];",
        "a5 -> a6 [label=\"1: ballSeen\"];",
        "ltail=\"cluster_c0\"",
    ] {
        assert!(dot.contains(expected), "{expected}\n{dot}");
    }
    // Each written state once, and no flat state of the product drawn as a node of its own.
    assert_eq!(dot.matches("[label=\"LEFT").count(), 1, "{dot}");
    assert!(!dot.contains("SEARCH ("), "{dot}");
    let nodes = proclaim_fsm::drawn_nodes(machine);
    let initial = nodes.iter().find(|(id, _)| *id == machine.initial).unwrap();
    assert_eq!(initial.1, ["a2", "a5"]);
}

/// What a review of regions found: a move to its own region's history leaves the parallel
/// state, so it fires alone (never two states of one region); a region's move back into its
/// own state is drawn back to it; a state whose regions' combinations pass 4,096 is refused.
#[test]
fn a_regions_history_leaves_alone_a_loop_is_drawn_home_and_too_many_arms_are_refused() {
    let read = parse_machine(
        "M.machine",
        "machine M
parallel P {
    state R {
        state r1 { when x -> R.history }
        state r2 { when z -> r1 }
    }
    state S {
        state s1 {
            when y -> s2
            when tick -> s1
        }
        state s2 { when w -> s1 }
    }
}
",
    );
    assert!(!read.has_errors(), "{:?}", read.diagnostics);
    let machine = &read.machines[0];
    for s in &machine.states {
        let in_s = machine
            .atomic_paths(s)
            .iter()
            .filter(|p| p.starts_with("P.S."))
            .count();
        assert!(in_s <= 1, "{} is two states of one region", s.name);
    }
    let dot = proclaim_fsm::to_dot(machine);
    assert!(dot.contains("a5 -> a5 [label=\"2: tick\"];"), "{dot}");

    let many: String = (0..17).map(|i| format!("when x{i} -> X2\n")).collect();
    let region = |r: &str| format!("state {r} {{ state X1 {{ {many} }} state X2 {{ }} }}\n");
    let text = format!(
        "machine M\nparallel P {{\n{}{}{}}}\n",
        region("A"),
        region("B"),
        region("C")
    );
    let read = parse_machine("M.machine", &text);
    let refused: Vec<String> = read.diagnostics.iter().map(|d| d.message.clone()).collect();
    assert!(
        refused
            .iter()
            .any(|m| m.contains("more than 4096 combinations in one state")),
        "{refused:?}"
    );
}

/// A state inside a region keeps no id of its own at run time (it runs as combinations with
/// the other regions' states), so an id written on it is said to name it in the file only;
/// the reference `-> #5` still reaches it.
#[test]
fn an_id_written_inside_a_region_is_said_to_name_it_in_the_file_only() {
    let read = parse_machine(
        "M.machine",
        "machine M
parallel P {
    state R {
        state r1 #5 { when x -> r2 }
        state r2 { when y -> #5 }
    }
    state S { state s1 { } }
}
",
    );
    assert!(!read.has_errors(), "{:?}", read.diagnostics);
    let said: Vec<String> = (read.diagnostics.iter())
        .map(|d| format!("{}: {}", d.line.unwrap_or(0), d.message))
        .collect();
    assert_eq!(
        said,
        [
            "4: `#5` names `P.R.r1` in this file only: a state inside a region runs as one of its \
          combinations with the other regions' states, which are numbered afresh, so a trace \
          will not show #5"
        ]
    );
    let machine = &read.machines[0];
    let back = machine
        .transitions
        .iter()
        .find(|t| t.label.to_string() == "y");
    let target = back
        .and_then(|t| machine.state(t.target))
        .expect("the move back");
    assert_eq!(machine.atomic_paths(target), ["P.R.r1", "P.S.s1"]);
}

/// A composite inside a region is drawn leaving from a node inside its own cluster, and a
/// sub-machine a region's state starts is drawn started from that state, not from whichever
/// region's state comes first in the combination.
#[test]
fn a_composite_in_a_region_leaves_its_own_cluster_and_a_regions_start_is_drawn_from_it() {
    let read = parse_machine(
        "M.machine",
        "machine M
parallel P {
    state H {
        state look { when seen -> track }
        state track { }
    }
    state B {
        state guard { when coming -> DIVE }
        state DIVE {
            when done -> guard
            state aim { when go -> fall }
            state fall {
                entry {
                    Dive: restart
                }
            }
        }
    }
}
",
    );
    assert!(!read.has_errors(), "{:?}", read.diagnostics);
    let machine = &read.machines[0];
    let mut dot = String::new();
    let started = proclaim_fsm::dot::body(&mut dot, machine, "", "");
    let node = |name: &str| {
        let line = dot
            .lines()
            .find(|l| l.contains(&format!("[label=\"{name}\\n")));
        line.and_then(|l| l.split_whitespace().next())
            .expect(name)
            .to_string()
    };
    let done = format!("{} -> {} [label=\"1: done\"", node("fall"), node("guard"));
    assert!(dot.contains(&done), "{done}\n{dot}");
    assert_eq!(started, [(node("fall"), "Dive".to_string())], "{dot}");
}

/// `in(STATE)` asks whether the machine is in a state (SCXML's `In`): each flat state decides
/// it, so a region can wait on another's state and no back end reads the call. A name is
/// looked up as a target is; one that names no state is refused at the label.
#[test]
fn in_state_is_decided_by_each_flat_state() {
    check(
        "machine M
parallel P {
    state A {
        state a1 { when go -> a2 }
        state a2 { when back -> a1 }
    }
    state B {
        state b1 { when in(a2) -> b2 }
        state b2 { when !in(P.A.a2) && tick -> b1 }
    }
}
",
        "initial P.A.a1, P.B.b1#5
P.A.a1, P.B.b1#5 entry[] exit[] internal[]
  go && FALSE -> P.A.a2, P.B.b2#6 leaving[] of P.A.a1
  go -> P.A.a2, P.B.b1#7 leaving[] of P.A.a1
  FALSE -> P.A.a1, P.B.b2#8 leaving[] of P.B.b1
P.A.a1, P.B.b2#8 entry[] exit[] internal[]
  go && tick -> P.A.a2, P.B.b1#7 leaving[] of P.A.a1
  go -> P.A.a2, P.B.b2#6 leaving[] of P.A.a1
  tick -> P.A.a1, P.B.b1#5 leaving[] of P.B.b2
P.A.a2, P.B.b1#7 entry[] exit[] internal[]
  back && TRUE -> P.A.a1, P.B.b2#8 leaving[] of P.A.a2
  back -> P.A.a1, P.B.b1#5 leaving[] of P.A.a2
  TRUE -> P.A.a2, P.B.b2#6 leaving[] of P.B.b1
P.A.a2, P.B.b2#6 entry[] exit[] internal[]
  back && FALSE -> P.A.a1, P.B.b1#5 leaving[] of P.A.a2
  back -> P.A.a1, P.B.b2#8 leaving[] of P.A.a2
  FALSE -> P.A.a2, P.B.b1#7 leaving[] of P.B.b2
",
    );
    // In a flat machine `in(S)` is whether S is the very state; `||` and `!` fold too.
    check(
        "machine M\nstate X {\n    when in(X) || go -> Y\n}\nstate Y {\n    when !in(X) && in(Y) -> X\n    when in(X) || go -> X\n}\n",
        "initial X#1
X#1 entry[] exit[] internal[]
  TRUE -> Y#2
Y#2 entry[] exit[] internal[]
  TRUE -> X#1
  go -> X#1
",
    );
    check(
        "machine M\nstate X {\n    when in(Z) -> X\n    when in(X, X) -> X\n}\n",
        "3: `in(Z)`: there is no state named `Z`
4: `in(X, X)`: `in(…)` takes one state, by its name or path: `in(PLAY.HEAD.TRACK)`
",
    );
}

/// What `in(S)` lowers to is said as written: an `in` of the state itself shadows what is below
/// it, and one of another state never fires there.
#[test]
fn check_says_what_in_decided_as_written() {
    let read = parse_machine(
        "F.machine",
        "machine F\nstate X {\n    when in(X) -> Y\n    when go -> Y\n}\nstate Y {\n    when in(X) -> X\n    when back -> X\n}\n",
    );
    assert!(!read.has_errors(), "{:?}", read.diagnostics);
    let said: Vec<String> = proclaim_fsm::lint(&read.machines[0], "F.machine")
        .iter()
        .map(|d| format!("{}: {}", d.line.unwrap_or(0), d.message))
        .collect();
    assert_eq!(
        said,
        [
            "4: `go` is never tried: `in(X)` above it (line 3) always fires first",
            "7: `in(X)` never fires: it is false in this state",
        ]
    );
}
