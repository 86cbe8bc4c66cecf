//! SPIN against the checker: each example behaviour's Promela (`proclaim_verify::to_promela`)
//! compiled and searched by SPIN, one `pan -N` run per property, and SPIN's verdict compared
//! with `verify`'s; liveness claims by `pan -a`'s acceptance-cycle search. Needs `spin` and `gcc` on PATH: skipped without them, failed without them
//! when `CI` is set.

use crate::common;

use proclaim_behaviour::{load, Folder};
use proclaim_verify::{
    to_promela, verify, Options, PropertyKind, PropertySource, SearchEngine, Stop, Verdict,
};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Arc;

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A fresh temporary folder for one case.
fn scratch(name: &str) -> PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("proclaim-spin-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

/// Whether `spin` and `gcc` run; without them the test is skipped, unless `CI` is set.
fn tools_present() -> bool {
    let runs = |tool: &str, flag: &str| {
        Command::new(tool)
            .arg(flag)
            .output()
            .is_ok_and(|o| o.status.success())
    };
    let present = runs("spin", "-V") && runs("gcc", "--version");
    if !present {
        assert!(
            std::env::var_os("CI").is_none(),
            "spin and gcc must be installed on CI (.ci/run installs Debian's spin)"
        );
        eprintln!("skipped: spin or gcc is not on PATH");
    }
    present
}

fn property(kind: PropertyKind, expression: &str) -> PropertySource {
    PropertySource {
        name: format!("{} {expression}", kind.word()),
        kind,
        expression: expression.into(),
        fair: Vec::new(),
    }
}

fn run(dir: &Path, program: &str, args: &[&str]) -> String {
    let out = Command::new(program)
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap_or_else(|e| panic!("{program}: {e}"));
    let text =
        String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "{program} {args:?} in {dir:?}:\n{text}"
    );
    text
}

/// Checks `properties` of the behaviour in `behaviour_dir` with both checkers, SPIN in
/// `work`; returns the verdicts (equal in both).
fn both(case: &str, behaviour_dir: &Path, properties: &[PropertySource]) -> Vec<Verdict> {
    both_with(case, behaviour_dir, properties, Options::default())
}

/// [`both`] with `options`.
fn both_with(
    case: &str,
    behaviour_dir: &Path,
    properties: &[PropertySource],
    options: Options,
) -> Vec<Verdict> {
    let behaviour = load(case, Arc::new(Folder::new(behaviour_dir)))
        .unwrap_or_else(|e| panic!("{case} loads: {e:#?}"));
    let report = verify(&behaviour, properties, options).expect("verifies");
    assert!(
        matches!(report.stats.stopped, Stop::Explored | Stop::Decided),
        "{case}: the checker decided every property"
    );
    let promela = to_promela(&behaviour, properties, options).expect("emits");
    assert!(promela.values_complete, "{case}");
    let work = scratch(case);
    std::fs::write(work.join("model.pml"), &promela.text).expect("write");
    run(&work, "spin", &["-a", "model.pml"]);
    // Unoptimised: these searches are short, and optimising pan.c was most of this test's time
    // (the verdicts are the same; the odometer's timing below builds with -O2).
    run(&work, "gcc", &["-O0", "-DSAFETY", "-o", "pan", "pan.c"]);
    // Liveness claims need the acceptance-cycle search, which -DSAFETY leaves out.
    let live = promela.claims.iter().any(|c| c.kind.is_liveness());
    if live {
        run(&work, "gcc", &["-O0", "-o", "pan-live", "pan.c"]);
    }
    let mut verdicts = Vec::new();
    for (claim, outcome) in promela.claims.iter().zip(&report.properties) {
        assert_eq!(claim.property, outcome.name);
        let (violated, out) = if claim.kind.is_liveness() {
            spin_liveness(case, &work, &claim.name)
        } else {
            spin_safety(case, &work, &claim.name)
        };
        let complete = !out.contains("max search depth too small");
        let spin = claim.verdict(violated, complete);
        assert_eq!(
            spin, outcome.verdict,
            "{case}, {}: SPIN says {spin:?}, the checker {:?}\n{out}",
            outcome.name, outcome.verdict
        );
        verdicts.push(spin);
    }
    let _ = std::fs::remove_dir_all(&work);
    verdicts
}

/// `pan`'s count of errors in its output `out`.
fn errors(case: &str, out: &str) -> usize {
    out.split("errors: ")
        .nth(1)
        .and_then(|rest| rest.split_whitespace().next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("{case}: pan's output has no error count:\n{out}"))
}

/// A safety claim searched by `pan` built with -DSAFETY: whether it is violated, and the output.
fn spin_safety(case: &str, work: &Path, claim: &str) -> (bool, String) {
    let out = run(work, "./pan", &["-N", claim, "-m1000000"]);
    // Under -DSAFETY the claim is checked as an assertion: `assertion violated !( !( !(hit0)))`;
    // any other assertion is the model's own (a value beyond those the checker numbered).
    let violation = out.lines().find(|l| l.contains("assertion violated"));
    let violated = match violation {
        Some(line) => {
            assert!(
                line.contains(&format!("(hit{})", &claim[1..])),
                "{case}: SPIN met a value the checker never numbered:\n{out}"
            );
            true
        }
        None => false,
    };
    assert_eq!(
        errors(case, &out) > 0,
        violated,
        "{case}: an error that is no violation:\n{out}"
    );
    (violated, out)
}

/// A liveness claim searched for acceptance cycles (`pan -a`): whether one was found, and the
/// output. An assertion is the model's own (a value beyond those the checker numbered).
fn spin_liveness(case: &str, work: &Path, claim: &str) -> (bool, String) {
    let out = run(work, "./pan-live", &["-a", "-N", claim, "-m1000000"]);
    assert!(
        !out.contains("assertion violated"),
        "{case}: SPIN met a value the checker never numbered:\n{out}"
    );
    let violated = out.contains("acceptance cycle") || out.contains("claim violated");
    assert_eq!(
        errors(case, &out) > 0,
        violated,
        "{case}: an error that is no violation:\n{out}"
    );
    (violated, out)
}

/// The microwave's folder with `machine` as its machine and the manifest's own property.
fn microwave(case: &str, machine: &str) -> PathBuf {
    let dir = scratch(&format!("{case}-behaviour"));
    let source = repo().join("machines/microwave");
    let manifest = std::fs::read_to_string(source.join("behaviour.toml"))
        .expect("manifest")
        .replace("../../theories/", "");
    std::fs::write(dir.join("behaviour.toml"), manifest).expect("write");
    std::fs::write(dir.join("Microwave.machine"), machine).expect("write");
    std::fs::copy(source.join("kitchen.script"), dir.join("kitchen.script")).expect("copy");
    std::fs::copy(
        repo().join("theories/microwave.dl"),
        dir.join("microwave.dl"),
    )
    .expect("copy");
    dir
}

/// The shipped microwave's machine and the properties its manifest declares (the door
/// interlock and that cooking stops).
fn shipped_microwave() -> (String, Vec<PropertySource>) {
    let original = std::fs::read_to_string(repo().join("machines/microwave/Microwave.machine"))
        .expect("machine");
    let microwave_dir = repo().join("machines/microwave");
    let behaviour = load("microwave", Arc::new(Folder::new(&microwave_dir))).expect("loads");
    let declared = proclaim_verify::manifest_properties(&behaviour);
    assert_eq!(
        declared.iter().map(|p| p.kind).collect::<Vec<_>>(),
        [PropertyKind::Never, PropertyKind::LeadsTo],
        "the manifest declares the door interlock and that cooking stops"
    );
    (original, declared)
}

// One test an example, so that nextest runs them side by side: each builds SPIN's checker with
// gcc, which is most of its time.

#[test]
fn spin_agrees_with_the_checker_on_the_shipped_microwave() {
    if !tools_present() {
        return;
    }
    let (_, declared) = shipped_microwave();
    let microwave_dir = repo().join("machines/microwave");
    assert_eq!(
        both("microwave", &microwave_dir, &declared),
        [Verdict::Holds, Verdict::Holds]
    );
}

#[test]
fn spin_agrees_with_the_checker_on_a_magnetron_switched_off_too_late() {
    if !tools_present() {
        return;
    }
    let (original, declared) = shipped_microwave();
    // The magnetron switched off on entering IDLE, a ringlet too late.
    let late = original.replace("    exit {\n        Magnetron: off\n    }\n", "");
    assert_ne!(late, original, "the fault is seeded");
    let dir = microwave("late-off", &late);
    assert_eq!(
        both("late-off", &dir, &declared),
        [Verdict::Fails, Verdict::Holds]
    );
}

#[test]
fn spin_agrees_with_the_checker_on_a_minute_that_never_ends() {
    if !tools_present() {
        return;
    }
    let (original, declared) = shipped_microwave();
    // Without its timeout the minute never ends: cooking need not stop. Under the assumption
    // that the door is opened again and again, it does.
    let endless = original.replace("when timeout(60000000) -> DONE", "when FALSE -> DONE");
    assert_ne!(endless, original, "the fault is seeded");
    let dir = microwave("endless", &endless);
    let mut door_opens = declared[1].clone();
    door_opens.name = "cooking stops if the door opens".into();
    door_opens.fair = vec!["doorOpen".into()];
    assert_eq!(
        both(
            "endless",
            &dir,
            &[
                declared[1].clone(),
                door_opens,
                property(PropertyKind::AlwaysEventually, "!Microwave.COOKING"),
                property(PropertyKind::Eventually, "Microwave.COOKING"),
            ]
        ),
        [
            Verdict::Fails,
            Verdict::Holds,
            Verdict::Fails,
            Verdict::Fails
        ]
    );
}

/// No time has passed in a state at the snapshot of the ringlet that arrived in it, so its
/// `after(1s)` cannot fire there: A's Internal has set `y` to 2 first. Safety properties alone,
/// so nothing but the step's own bits tells an arrival from a later ringlet in SPIN's states.
#[test]
fn spin_agrees_with_the_checker_that_no_time_passes_before_an_arrivals_snapshot() {
    if !tools_present() {
        return;
    }
    let dir = scratch("arrival-behaviour");
    let machine = "machine M\ninitial C\nstate C { when TRUE -> A }\n\
                   state A {\n    entry { y = 1; }\n    internal { y = 2; }\n    when after(1s) -> B\n}\n\
                   state B { }\n";
    std::fs::write(dir.join("M.machine"), machine).expect("write");
    std::fs::write(
        dir.join("behaviour.toml"),
        "[[machine]]\nfile = \"M.machine\"\n",
    )
    .expect("write");
    assert_eq!(
        both(
            "arrival",
            &dir,
            &[
                property(PropertyKind::Never, "M.B && y == 1"),
                property(PropertyKind::Reachable, "M.B && y == 2"),
            ]
        ),
        [Verdict::Holds, Verdict::Holds]
    );
}

/// The behaviour in `tests/agree/CASE`: both of the checker's engines give `expected` for
/// `properties` with the clocks of different machines ordered (`Options::clock_order`), and
/// unordered with the verdicts a run decided checked again ordered, and so does SPIN where it
/// is installed.
fn agree(case: &str, properties: &[PropertySource], expected: &[Verdict]) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/agree")
        .join(case);
    let behaviour = load(case, Arc::new(Folder::new(&dir))).expect("loads");
    for engine in [SearchEngine::Explicit, SearchEngine::Symbolic] {
        let options = Options {
            engine,
            clock_order: true,
            ..Options::default()
        };
        let report = verify(&behaviour, properties, options).expect("verifies");
        let verdicts: Vec<Verdict> = report.properties.iter().map(|p| p.verdict).collect();
        assert_eq!(verdicts, expected, "{case}: {engine:?}");
        // Unordered first, the verdicts a run decided checked again ordered: the same.
        let options = Options {
            engine,
            ..Options::default()
        };
        let report = verify(&behaviour, properties, options).expect("verifies");
        let verdicts: Vec<Verdict> = report.properties.iter().map(|p| p.verdict).collect();
        assert_eq!(verdicts, expected, "{case}: {engine:?}, checked again");
        assert!(report.unordered_clocks.is_empty(), "{case}: {engine:?}");
    }
    if !tools_present() {
        return;
    }
    let ordered = Options {
        clock_order: true,
        ..Options::default()
    };
    assert_eq!(
        both_with(case, &dir, properties, ordered),
        expected,
        "{case}: SPIN"
    );
}

/// A transition that stays (§3.2) runs its own actions only and keeps the state's clock: A is
/// entered once however often it fires (an entry flips `entries`), its OnExit has not run
/// while in A, its count stops at 2, and either may come first, two counts or the timeout.
/// SPIN and both of the checker's engines agree.
#[test]
fn spin_and_both_engines_agree_on_a_transition_that_stays() {
    let properties = [
        property(PropertyKind::Never, "M.B && M.entries != 1"),
        property(PropertyKind::Never, "M.A && y == 1"),
        property(PropertyKind::Never, "M.n > 2"),
        property(PropertyKind::Reachable, "M.B && M.n == 2"),
        property(PropertyKind::Reachable, "M.A && M.n == 2"),
        property(PropertyKind::Eventually, "M.B"),
    ];
    agree("stays", &properties, &[Verdict::Holds; 6]);
}

/// A composite is entered no later than the states inside it (§6, time): when P's 3 s are
/// up, so is the 1 s of the state P was entered with, and that state's move (tried first)
/// has fired by then. Only after B is P left for LATE; a model whose clocks were free of
/// each other would leave from A. SPIN and both of the checker's engines agree.
#[test]
fn spin_and_both_engines_agree_that_a_composite_is_no_younger_than_its_states() {
    let properties = [
        property(PropertyKind::Never, "M.LATE && M.passed != 1"),
        property(PropertyKind::Reachable, "M.LATE"),
        property(PropertyKind::Eventually, "M.LATE"),
    ];
    agree("older-composite", &properties, &[Verdict::Holds; 3]);
}

/// A move inside a composite keeps its due tests into a state whose labels test more of its
/// clocks (an `in()` folded away where the move came from): the tests those imply are due on
/// arrival too. In M, Q's 2 s imply P's 1 s; in N, Q's 2 s imply its own 1 s. Each inner move
/// is tried first and fires when its 2 s are up, so M ends in Y and N in X. A symbolic engine
/// that made steps only from the sets of due tests a snapshot may choose had none from
/// there, and called Y and X unreachable.
#[test]
fn spin_and_both_engines_agree_on_the_tests_a_kept_clock_implies() {
    let properties = [
        property(PropertyKind::Reachable, "M.Y"),
        property(PropertyKind::Never, "M.X"),
        property(PropertyKind::Reachable, "N.X"),
        property(PropertyKind::Never, "N.Y"),
    ];
    agree("implied-time", &properties, &[Verdict::Holds; 4]);
}

/// `reload` reads the machine's file again and starts it at its initial state (the file
/// checked is the one read again): M's second visit to A flips `visits` back, which a model
/// that took the command for nothing never reached.
#[test]
fn spin_and_both_engines_agree_that_a_reload_starts_the_machine_again() {
    let properties = [
        property(PropertyKind::Reachable, "M.B && M.visits == 0"),
        property(PropertyKind::AlwaysEventually, "M.A"),
    ];
    agree("reload", &properties, &[Verdict::Holds; 2]);
}

/// A shallow history of a state that holds a parallel state resumes the parallel state whole:
/// READY is never entered once the history says PLAY was left, the pause is reached with it
/// so, and after resuming both regions move on from their initial states; `again` (the
/// parallel state's own history) enters PLAY even when the history says READY.
#[test]
fn spin_and_both_engines_agree_on_a_shallow_history_around_regions() {
    let properties = [
        property(PropertyKind::Never, "M.GAME.READY && M.GAME_history == 2"),
        property(
            PropertyKind::Reachable,
            "M.GAME.PLAY.HEAD.TRACK && M.GAME_history == 1",
        ),
        property(PropertyKind::Reachable, "M.PAUSE && M.GAME_history == 2"),
        property(
            PropertyKind::Reachable,
            "M.GAME.PLAY.HEAD.TRACK && M.GAME.PLAY.BODY.KICK && M.GAME_history == 2",
        ),
    ];
    agree("history-around-regions", &properties, &[Verdict::Holds; 4]);
}

/// A deep history of a state that holds a parallel state resumes the configuration it was
/// left in: left at TRACK and WALK (place 4), it comes back to both, never to LOOK (no move
/// leads back there) nor to READY; left at READY, back to READY.
#[test]
fn spin_and_both_engines_agree_on_a_deep_history_around_regions() {
    let properties = [
        property(
            PropertyKind::Never,
            "M.GAME.READY && M.GAME_deep_history >= 2",
        ),
        property(
            PropertyKind::Never,
            "M.GAME.PLAY.HEAD.LOOK && M.GAME_deep_history == 4",
        ),
        property(
            PropertyKind::Reachable,
            "M.GAME.PLAY.HEAD.TRACK && M.GAME.PLAY.BODY.WALK && M.GAME_deep_history == 4",
        ),
        property(
            PropertyKind::Reachable,
            "M.GAME.READY && M.GAME_deep_history == 1",
        ),
    ];
    agree(
        "deep-history-around-regions",
        &properties,
        &[Verdict::Holds; 4],
    );
}

/// A machine started and reloaded in one round rings from the next, as one only started
/// does: B, started by A and reloaded by C before its turn, first rings after A's second
/// ringlet. (The symbolic engine once took the reload for a start of its own that cleared
/// "started this round", and let B ring at once.)
#[test]
fn spin_and_both_engines_agree_that_a_reload_does_not_start_a_machine_early() {
    let properties = [
        property(PropertyKind::Never, "B.rang == 1 && A.A1"),
        property(PropertyKind::Reachable, "B.rang == 1"),
    ];
    agree("started-and-reloaded", &properties, &[Verdict::Holds; 2]);
}

/// Time passes on every clock in a fair run, as the due tests at the end of each step say:
/// after a move inside Q, once Q's 5 s are up so are P's 1 s and 2 s (P is no younger), in
/// whichever of A and B the machine is. A run that never sees `stop` never reaches X, and it
/// is fair. (SPIN's model once kept only the moved tests, saw P's time never pass, found no
/// fair run, and said `eventually M.X` held.)
#[test]
fn spin_and_both_engines_agree_that_time_passes_on_a_clock_a_kept_one_implies() {
    let properties = [property(PropertyKind::Eventually, "M.X")];
    agree("implied-fairness", &properties, &[Verdict::Fails]);
}

/// The press's properties: never stuck, done reachable and eventually done.
fn press_properties() -> [PropertySource; 3] {
    [
        property(PropertyKind::Never, "Controller.Stuck"),
        property(PropertyKind::Reachable, "Controller.Done"),
        property(PropertyKind::Eventually, "Controller.Done"),
    ]
}

#[test]
fn spin_agrees_with_the_checker_on_the_shipped_press() {
    if !tools_present() {
        return;
    }
    let press_dir = repo().join("machines/press");
    assert_eq!(
        both("press", &press_dir, &press_properties()),
        [Verdict::Holds, Verdict::Holds, Verdict::Holds]
    );
}

#[test]
fn spin_agrees_with_the_checker_on_a_press_whose_sensor_jams() {
    if !tools_present() {
        return;
    }
    // A sensor that never corrects `low`: the press jams and is never done.
    let press_dir = repo().join("machines/press");
    let dir = scratch("jammed-behaviour");
    for file in ["behaviour.toml", "Controller.machine", "Plate.machine"] {
        std::fs::copy(press_dir.join(file), dir.join(file)).expect("copy");
    }
    let sensor = std::fs::read_to_string(press_dir.join("Sensor.machine")).expect("sensor");
    let broken = sensor.replace("low = 0;", "");
    assert_ne!(broken, sensor, "the fault is seeded");
    std::fs::write(dir.join("Sensor.machine"), broken).expect("write");
    assert_eq!(
        both("jammed", &dir, &press_properties()),
        [Verdict::Fails, Verdict::Fails, Verdict::Fails]
    );
}

/// The keeper's properties (`machines/keeper`): a penalty from any step of the nested dive
/// runs the dive's exit, every dive ends, and the dive sub-machine falls to the side the
/// keeper gave it as a parameter.
fn keeper_properties() -> [PropertySource; 3] {
    [
        property(
            PropertyKind::Never,
            "Keeper.PENALIZED && (NaoMotionPlayer == \"diveLeft\" || NaoMotionPlayer == \"diveRight\")",
        ),
        property(PropertyKind::LeadsTo, "Keeper.DIVE ~> !Keeper.DIVE"),
        property(PropertyKind::Never, "Keeper.DIVE.LEFT && Dive.RIGHT"),
    ]
}

/// Shipped behaviour `name` in a fresh folder for `case`, with its files `copied` as they are
/// and its machine file `machine` as `edit` writes it. Its dictionary (`../nao.toml`) says who
/// listens, which no verdict depends on, so the manifest is copied without it.
fn shipped_copy(
    case: &str,
    name: &str,
    copied: &[&str],
    machine: &str,
    edit: impl FnOnce(String) -> String,
) -> PathBuf {
    let source = repo().join("machines").join(name);
    let dir = scratch(&format!("{case}-behaviour"));
    for file in copied {
        std::fs::copy(source.join(file), dir.join(file)).expect("copy");
    }
    let manifest = std::fs::read_to_string(source.join("behaviour.toml")).expect("manifest");
    let manifest: String = manifest
        .lines()
        .filter(|l| !l.starts_with("dictionary"))
        .map(|l| format!("{l}\n"))
        .collect();
    std::fs::write(dir.join("behaviour.toml"), manifest).expect("write");
    let text = std::fs::read_to_string(source.join(machine)).expect("machine");
    std::fs::write(dir.join(machine), edit(text)).expect("write");
    dir
}

/// The keeper in a fresh folder, its dive's exit (stopping the dive sub-machine, getting up)
/// taken out when `getting_up` is false.
fn keeper(case: &str, getting_up: bool) -> PathBuf {
    let copied = ["match.script", "Dive.machine"];
    shipped_copy(case, "keeper", &copied, "Keeper.machine", |machine| {
        if getting_up {
            return machine;
        }
        let exit = "    exit {\n        Dive: Off\n        NaoMotionPlayer: getUp\n    }\n";
        assert!(machine.contains(exit), "the fault is seeded");
        machine.replace(exit, "")
    })
}

#[test]
fn spin_agrees_with_the_checker_on_the_keepers_nested_dive() {
    if !tools_present() {
        return;
    }
    assert_eq!(
        both("keeper", &keeper("keeper", true), &keeper_properties()),
        [Verdict::Holds, Verdict::Holds, Verdict::Holds]
    );
    assert_eq!(
        both(
            "keeper-lying",
            &keeper("keeper-lying", false),
            &keeper_properties()
        ),
        [Verdict::Fails, Verdict::Holds, Verdict::Fails]
    );
}

/// The search's properties (`machines/search`): a search that sees nothing gives up, every
/// search ends, and the kick comes after the walk.
fn search_properties() -> [PropertySource; 3] {
    [
        property(PropertyKind::Reachable, "Search.GIVE_UP"),
        property(PropertyKind::LeadsTo, "Search.LOOK ~> !Search.LOOK"),
        property(PropertyKind::Never, "Search.KICK && NaoWalk != \"forward\""),
    ]
}

/// The search in a fresh folder; with `per_turn`, its 3 s written on each turn of the head
/// instead of on the search, so that every turn starts them again.
fn search(case: &str, per_turn: bool) -> PathBuf {
    shipped_copy(
        case,
        "search",
        &["ball.script"],
        "Search.machine",
        |machine| {
            if !per_turn {
                return machine;
            }
            let on_search = "    when after(3s) -> GIVE_UP\n";
            assert!(machine.contains(on_search), "the fault is seeded");
            machine.replace(on_search, "").replace(
                "        when after_ms(400)",
                "        when after(3s) -> GIVE_UP\n        when after_ms(400)",
            )
        },
    )
}

/// A time test on a composite counts from its entry: the search gives up, and every search
/// ends. Written on the turns instead, the 3 s start again with each turn: a search may go on
/// for ever (it gives up only where a turn lasts 3 s, as a robot stalled that long would).
#[test]
fn spin_agrees_with_the_checker_on_a_search_timed_as_a_whole() {
    if !tools_present() {
        return;
    }
    assert_eq!(
        both("search", &search("search", false), &search_properties()),
        [Verdict::Holds, Verdict::Holds, Verdict::Holds]
    );
    assert_eq!(
        both(
            "search-per-turn",
            &search("search-per-turn", true),
            &search_properties()
        ),
        [Verdict::Holds, Verdict::Fails, Verdict::Holds]
    );
}

/// `odometer N K` (`tests/common/odometer.rs`, the bench's family too), in a fresh folder.
fn odometer(n: usize, k: usize) -> PathBuf {
    let dir = scratch(&format!("odometer-{n}-{k}-behaviour"));
    common::odometer::write_odometer(&dir, n, k);
    dir
}

/// States per second of `verify` and of SPIN on the same model, the odometer at three sizes:
/// `cargo test --release -p proclaim-verify --test tests -- --ignored --nocapture spin::`. SPIN's
/// figures: `spin -a` with gcc apart from `pan`'s search; its states include those between a
/// step's parts (see `promela.rs`), so they are more than the checker's.
#[test]
#[ignore = "a measurement: run it in release with --ignored --nocapture"]
fn odometer_states_per_second_of_verify_and_spin() {
    if !tools_present() {
        return;
    }
    // 10^3 to 10^6 checker states; PROCLAIM_ODOMETER_MAX=5 adds 10^7 (the odometer is one long
    // cycle, so SPIN's depth-first stack holds nearly every state: several GB there).
    let largest: usize = std::env::var("PROCLAIM_ODOMETER_MAX")
        .ok()
        .and_then(|n| n.parse().ok())
        .unwrap_or(4);
    let options = Options {
        max_states: 50_000_000,
        ..Options::default()
    };
    for (n, k) in [(2, 30), (3, 20), (4, 12), (4, 24), (5, 16)]
        .into_iter()
        .filter(|(n, _)| *n <= largest)
    {
        let dir = odometer(n, k);
        let case = format!("odometer {n} {k}");
        let behaviour = load(&case, Arc::new(Folder::new(&dir))).expect("loads");
        let property = [property(PropertyKind::Never, &format!("g0 >= {k}"))];
        let started = std::time::Instant::now();
        let report = verify(&behaviour, &property, options).expect("verifies");
        let verify_seconds = started.elapsed().as_secs_f64();
        let started = std::time::Instant::now();
        let promela = to_promela(&behaviour, &property, options).expect("emits");
        let emit_seconds = started.elapsed().as_secs_f64();
        let work = scratch(&format!("odometer-{n}-{k}"));
        std::fs::write(work.join("model.pml"), &promela.text).expect("write");
        let started = std::time::Instant::now();
        run(&work, "spin", &["-a", "model.pml"]);
        run(&work, "gcc", &["-O2", "-DSAFETY", "-o", "pan", "pan.c"]);
        let compile_seconds = started.elapsed().as_secs_f64();
        let started = std::time::Instant::now();
        // SPIN's hash table and depth sized to the model (it stores about seven states per
        // checker state): a fixed large size would be most of a small run's time.
        let spin_expected = report.stats.states * 10;
        let hash_bits = (usize::BITS - spin_expected.leading_zeros()).clamp(18, 30);
        // A depth-first path can hold most of SPIN's states, and on the odometer SPIN keeps
        // many more a checker state than the hash estimate above.
        let depth = format!("-m{}", (report.stats.states * 100).max(10_000));
        let bits = format!("-w{hash_bits}");
        let out = run(&work, "./pan", &[depth.as_str(), bits.as_str()]);
        let pan_seconds = started.elapsed().as_secs_f64();
        assert!(!out.contains("max search depth too small"), "{out}");
        assert!(!out.contains("assertion violated"), "{out}");
        let spin_states: f64 = out
            .lines()
            .find(|l| l.contains("states, stored"))
            .and_then(|l| l.split_whitespace().next())
            .and_then(|n| n.parse().ok())
            .unwrap_or_else(|| panic!("no state count:\n{out}"));
        // pan's own clock: its search without allocating the stack and the hash table.
        let pan_search: String = out
            .lines()
            .find_map(|l| l.strip_prefix("pan: elapsed time "))
            .unwrap_or("?")
            .to_string();
        assert_eq!(report.properties[0].verdict, Verdict::Holds);
        let states = report.stats.states as f64;
        println!(
            "{case}: verify {states} states in {verify_seconds:.3} s ({:.0} states/s); \
             SPIN: emit {emit_seconds:.3} s (includes the checker's numbering pass), \
             spin -a + gcc {compile_seconds:.2} s, pan {spin_states} states in {pan_seconds:.3} s \
             ({:.0} states/s, {:.0} checker states/s; pan's own clock: {pan_search})",
            states / verify_seconds,
            spin_states / pan_seconds,
            states / pan_seconds,
        );
        let _ = std::fs::remove_dir_all(&work);
        let _ = std::fs::remove_dir_all(&dir);
    }
}

/// Safety only: SPIN's acceptance-cycle search of this model, several clocks' acceptance sets
/// over every combination of the regions, is too long for the suite; the checker's liveness
/// verdict is tested in `verify_cli`.
fn tracker_properties() -> [PropertySource; 3] {
    [
        property(PropertyKind::Reachable, "Striker.CHEER"),
        property(
            PropertyKind::Never,
            "Striker.PLAY.LEGS.WALK && (Striker.PLAY.HEAD.SCAN_LEFT || Striker.PLAY.HEAD.SCAN_RIGHT)",
        ),
        property(PropertyKind::Reachable, "Striker.PLAY.LEGS.KICK"),
    ]
}

/// The tracker in a fresh folder; with `turn_first`, a scanning head tries its turn before the
/// ball, so it may turn away from a ball the legs walk to.
fn tracker(case: &str, turn_first: bool) -> PathBuf {
    shipped_copy(
        case,
        "tracker",
        &["ball.script"],
        "Striker.machine",
        |machine| {
            if !turn_first {
                return machine;
            }
            let seen = "            when ballSeen -> TRACK\n";
            let left = "            when after_ms(400) -> SCAN_RIGHT\n";
            assert!(
                machine.contains(&format!("{seen}{left}")),
                "the fault is seeded"
            );
            machine.replace(&format!("{seen}{left}"), &format!("{left}{seen}"))
        },
    )
}

/// Regions read one snapshot (§3.2): the legs walk only while the head tracks the ball, a
/// property over both regions that the checker and SPIN both find to hold, and both find broken
/// once a scanning head turns before it looks at the ball.
#[test]
fn spin_agrees_with_the_checker_on_a_head_and_legs_side_by_side() {
    if !tools_present() {
        return;
    }
    assert_eq!(
        both("tracker", &tracker("tracker", false), &tracker_properties()),
        [Verdict::Holds, Verdict::Holds, Verdict::Holds]
    );
    assert_eq!(
        both(
            "tracker-turn-first",
            &tracker("tracker-turn-first", true),
            &tracker_properties()
        ),
        [Verdict::Holds, Verdict::Fails, Verdict::Holds]
    );
}

/// The whole goalkeeper's properties (`machines/goalkeeper`): one over both regions (the head
/// braces while the body lies after a dive) and the keeper's three, from inside the body's
/// region.
fn goalkeeper_properties() -> [PropertySource; 4] {
    [
        property(
            PropertyKind::Never,
            "Goalkeeper.PLAY.BODY.DIVE.LIE && !Goalkeeper.PLAY.HEAD.BRACE",
        ),
        property(
            PropertyKind::Never,
            "Goalkeeper.PENALIZED && (NaoMotionPlayer == \"diveLeft\" || NaoMotionPlayer == \"diveRight\")",
        ),
        property(
            PropertyKind::LeadsTo,
            "Goalkeeper.PLAY.BODY.DIVE ~> !Goalkeeper.PLAY.BODY.DIVE",
        ),
        property(
            PropertyKind::Never,
            "Goalkeeper.PLAY.BODY.DIVE.LEFT && Dive.RIGHT",
        ),
    ]
}

/// The goalkeeper in a fresh folder with the keeper's dive beside it; with `blind`, a head
/// tracking the ball does not see the body dive, so it may look away while the keeper lies.
fn goalkeeper(case: &str, blind: bool) -> PathBuf {
    let dir = shipped_copy(
        case,
        "goalkeeper",
        &["match.script"],
        "Goalkeeper.machine",
        |machine| {
            if !blind {
                return machine;
            }
            let track = "                NaoHeadMoveTo: ball\n            }\n";
            let sees = "            when diving -> BRACE\n";
            assert!(
                machine.contains(&format!("{track}{sees}")),
                "the fault is seeded"
            );
            machine.replace(&format!("{track}{sees}"), track)
        },
    );
    let dive = repo().join("machines/keeper/Dive.machine");
    std::fs::copy(dive, dir.join("Dive.machine")).expect("copy");
    let manifest = std::fs::read_to_string(dir.join("behaviour.toml")).expect("manifest");
    let manifest = manifest.replace("../keeper/Dive.machine", "Dive.machine");
    std::fs::write(dir.join("behaviour.toml"), manifest).expect("write");
    dir
}

/// A nested dive (a sub-machine with a parameter and an outcome) in one region and a head in
/// the other: the checker and SPIN both find the property over both regions to hold, and both
/// find it broken once the tracking head stops looking at the dive.
#[test]
fn spin_agrees_with_the_checker_on_the_whole_goalkeeper() {
    if !tools_present() {
        return;
    }
    assert_eq!(
        both(
            "goalkeeper",
            &goalkeeper("goalkeeper", false),
            &goalkeeper_properties()
        ),
        [Verdict::Holds; 4]
    );
    assert_eq!(
        both(
            "goalkeeper-blind",
            &goalkeeper("goalkeeper-blind", true),
            &goalkeeper_properties()
        ),
        [
            Verdict::Fails,
            Verdict::Holds,
            Verdict::Holds,
            Verdict::Holds
        ]
    );
}

/// Clocks of different machines are ordered (§6, time): Quick's half second and Slow's three
/// start in the first round, so Slow's three are never up while Quick's half is not, and
/// Quick, listed first, has left A when Slow leaves S. Time still passes in fair runs (the
/// order leaves some): one that never sets `late` to 2 is a counterexample.
#[test]
fn spin_and_both_engines_agree_that_a_half_second_comes_before_three_of_another_machine() {
    let properties = [
        property(PropertyKind::Never, "Slow.LATE && Quick.A"),
        property(PropertyKind::Never, "late == 1 && Quick.A"),
        property(PropertyKind::Reachable, "Slow.LATE"),
        property(PropertyKind::Eventually, "Slow.LATE"),
        property(PropertyKind::Eventually, "late == 2"),
    ];
    let mut expected = [Verdict::Holds; 5];
    expected[4] = Verdict::Fails;
    agree("machine-clocks", &properties, &expected);
}

/// Slow listed first: in the round whose moment has Slow's three seconds up, Slow leaves S
/// before Quick rings, so a snapshot between the two ringlets sees Slow in LATE and Quick in
/// A (a real run does too). Quick leaves A in that round all the same (Slow kept what it left
/// with for the round), so Slow's entry into LATE, in the next round, never meets Quick in A.
#[test]
fn spin_and_both_engines_agree_on_machines_clocks_listed_the_other_way() {
    let properties = [
        property(PropertyKind::Never, "Slow.LATE && Quick.A"),
        property(PropertyKind::Never, "late == 1 && Quick.A"),
        property(PropertyKind::Eventually, "Slow.LATE"),
    ];
    let expected = [Verdict::Fails, Verdict::Holds, Verdict::Holds];
    agree("machine-clocks-reversed", &properties, &expected);
}

/// Two machines whose clocks are ordered, for ever: time passes on both in fair runs, so each
/// comes back to its second state. A fair run need never see Ping in A with Pong in D: Pong
/// arrives in C a round after Ping arrives in B, and its half second there is up only in the
/// round Ping leaves A (Pong's clock is the younger, so nothing forces it sooner).
#[test]
fn spin_and_both_engines_agree_on_a_ping_and_a_pong() {
    let properties = [
        property(PropertyKind::AlwaysEventually, "Ping.B"),
        property(PropertyKind::AlwaysEventually, "Pong.D"),
        property(PropertyKind::Eventually, "Ping.A && Pong.D"),
    ];
    let expected = [Verdict::Holds, Verdict::Holds, Verdict::Fails];
    agree("ping-pong", &properties, &expected);
}
