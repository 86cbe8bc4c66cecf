//! The verifier's engines and SPIN side by side, in one run, on the families of behaviours the
//! checker is measured on (`sensors N`, the 8-machine `press`, `minepump`, `odometer N K`, and
//! the 8-machine `gamecontroller` and `infusion` of `tests/controllers`):
//! for each behaviour and engine, the verdicts, the states it stored, the time and the memory
//! it held, under the default budget. SPIN is run on `--emit promela`'s text (`spin -a`,
//! `gcc -O2 -DSAFETY`, one `pan -N` per property, its search time apart from its build time)
//! within a time limit; once SPIN or the explicit engine does not finish a family at one size,
//! the larger sizes skip it.
//! `cargo bench -p proclaim-verify --bench families` (`-- sensors` or `-- press` etc. to run
//! only the families named; SPIN is left out when `spin` or `gcc` is not on PATH).

#[path = "../tests/common/families.rs"]
mod families;
#[path = "../tests/common/odometer.rs"]
mod odometer;

use proclaim_behaviour::{load, Behaviour, Folder};
use proclaim_verify::{
    to_promela, verify, Options, PropertyKind, PropertySource, Report, SearchEngine, Stop, Verdict,
};
use std::collections::BTreeSet;
use std::path::PathBuf;
use std::process::Command;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// How long one SPIN search (one `pan` run) may take before the family's larger sizes skip SPIN.
const SPIN_LIMIT: Duration = Duration::from_secs(60);
/// The memory `pan` may use, in megabytes.
const SPIN_MEMORY_MB: usize = 4096;
/// `pan`'s depth limit (its stack is allocated for this depth up front, so no larger).
const SPIN_DEPTH: &str = "-m20000000";

/// One behaviour of a family and the properties asked of it.
struct Case {
    family: &'static str,
    size: String,
    dir: PathBuf,
    properties: Vec<PropertySource>,
}

fn property(kind: PropertyKind, expression: &str) -> PropertySource {
    PropertySource {
        name: format!("{} {expression}", kind.word()),
        kind,
        expression: expression.into(),
        fair: Vec::new(),
    }
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("proclaim-families-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    dir
}

fn cases(wanted: &BTreeSet<String>) -> Vec<Case> {
    let wants = |family: &str| wanted.is_empty() || wanted.contains(family);
    let mut cases = Vec::new();
    if wants("press") {
        let dir = scratch("press");
        families::write_press(&dir);
        cases.push(Case {
            family: "press",
            size: "8 machines".into(),
            dir,
            properties: vec![
                property(PropertyKind::Reachable, "Controller.Closing"),
                property(PropertyKind::Never, "Controller.Closing"),
                property(
                    PropertyKind::Never,
                    "Controller.PressClosed && Controller.Open",
                ),
                property(PropertyKind::Never, "Plunger.Extended && Motor.Down"),
            ],
        });
    }
    if wants("minepump") {
        let dir = scratch("minepump");
        families::write_minepump(&dir);
        cases.push(Case {
            family: "minepump",
            size: "4 machines".into(),
            dir,
            properties: vec![
                property(PropertyKind::Never, "pumping == 1 && methane == 1"),
                property(PropertyKind::Always, "Controller.Off || Controller.On"),
                property(PropertyKind::Reachable, "Pump.Pumping"),
            ],
        });
    }
    if wants("sensors") {
        for n in [3, 5, 6, 8, 12, 16, 24] {
            let dir = scratch(&format!("sensors-{n}"));
            families::write_sensors(&dir, n);
            cases.push(Case {
                family: "sensors",
                size: format!("n = {n}"),
                dir,
                properties: vec![
                    property(PropertyKind::Reachable, "Controller.Alarm"),
                    property(PropertyKind::Always, "Controller.Idle || Controller.Alarm"),
                ],
            });
        }
    }
    if wants("odometer") {
        for (n, k) in [(3, 20), (4, 12), (5, 10)] {
            let dir = scratch(&format!("odometer-{n}-{k}"));
            odometer::write_odometer(&dir, n, k);
            cases.push(Case {
                family: "odometer",
                size: format!("{n} digits base {k}"),
                dir,
                properties: vec![property(PropertyKind::Never, &format!("g0 >= {k}"))],
            });
        }
    }
    // A copy: each case's folder is the bench's to write in and remove.
    let controller = |name: &str| {
        let from = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("tests/controllers")
            .join(name);
        let dir = scratch(name);
        for file in std::fs::read_dir(&from).expect("the controller's folder") {
            let file = file.expect("a file").path();
            std::fs::copy(&file, dir.join(file.file_name().expect("a name"))).expect("copied");
        }
        dir
    };
    if wants("gamecontroller") {
        cases.push(Case {
            family: "gamecontroller",
            size: "8 machines".into(),
            dir: controller("gamecontroller"),
            properties: vec![
                property(PropertyKind::Reachable, "GameController.PLAYING"),
                property(
                    PropertyKind::Never,
                    "GameController.PLAYING && LeftFootControlIsRunning",
                ),
                property(
                    PropertyKind::Never,
                    "GameController.INITIAL && RobotPositionIsRunning",
                ),
                property(
                    PropertyKind::Never,
                    "GameController.FINISHED && fallen == 1",
                ),
            ],
        });
    }
    if wants("infusion") {
        cases.push(Case {
            family: "infusion",
            size: "8 machines".into(),
            dir: controller("infusion"),
            properties: vec![
                property(PropertyKind::Reachable, "Pump.DONE"),
                property(PropertyKind::Never, "timeLeft < 0"),
                property(PropertyKind::Never, "Pump.RUNNING && dose > 8"),
            ],
        });
    }
    cases
}

/// One engine's result on one case, as a table row's cells.
struct Row {
    verdicts: String,
    states: String,
    seconds: f64,
    /// Time spent before the search (SPIN: emitting, `spin -a`, `gcc`).
    preparing: Option<f64>,
    memory: String,
    finished: bool,
}

fn verdict_words(verdicts: impl Iterator<Item = Verdict>) -> String {
    verdicts
        .map(|v| match v {
            Verdict::Holds => "holds",
            Verdict::Fails => "FAILS",
            Verdict::Incomplete => "undecided",
        })
        .collect::<Vec<_>>()
        .join(", ")
}

fn checker(behaviour: &Behaviour, case: &Case, engine: SearchEngine) -> (Row, Option<Report>) {
    let options = Options {
        engine,
        ..Options::default()
    };
    let start = Instant::now();
    let outcome = verify(behaviour, &case.properties, options);
    let seconds = start.elapsed().as_secs_f64();
    match outcome {
        Ok(report) => {
            let s = &report.stats;
            let finished = matches!(s.stopped, Stop::Explored | Stop::Decided);
            let row = Row {
                verdicts: verdict_words(report.properties.iter().map(|p| p.verdict)),
                states: if finished {
                    format!("{} ({})", s.states, s.engine)
                } else {
                    format!("{} ({}, {})", s.states, s.engine, s.stopped.describe())
                },
                seconds,
                preparing: None,
                memory: if s.bytes > 0 {
                    format!("{:.1} MB", s.bytes as f64 / 1e6)
                } else {
                    "-".into()
                },
                finished,
            };
            (row, Some(report))
        }
        Err(error) => (
            Row {
                verdicts: format!("refused: {error}"),
                states: "-".into(),
                seconds,
                preparing: None,
                memory: "-".into(),
                finished: false,
            },
            None,
        ),
    }
}

fn tools_present() -> bool {
    let runs = |tool: &str, flag: &str| {
        Command::new(tool)
            .arg(flag)
            .output()
            .is_ok_and(|o| o.status.success())
    };
    runs("spin", "-V") && runs("gcc", "--version") && runs("timeout", "--version")
}

/// SPIN on the case: the emitted Promela compiled once, one `pan` per property within
/// [`SPIN_LIMIT`]; the time counts emitting, `spin -a`, `gcc` and every `pan` run.
fn spin(behaviour: &Behaviour, case: &Case) -> Row {
    let start = Instant::now();
    let failed = |why: String, start: Instant| Row {
        verdicts: why,
        states: "-".into(),
        seconds: start.elapsed().as_secs_f64(),
        preparing: None,
        memory: "-".into(),
        finished: false,
    };
    let promela = match to_promela(behaviour, &case.properties, Options::default()) {
        Ok(p) => p,
        Err(error) => return failed(format!("emit refused: {error}"), start),
    };
    let work = case.dir.join("spin");
    std::fs::create_dir_all(&work).expect("a folder for SPIN");
    std::fs::write(work.join("model.pml"), &promela.text).expect("write the model");
    let memlim = format!("-DMEMLIM={SPIN_MEMORY_MB}");
    for (program, args) in [
        ("spin", vec!["-a", "model.pml"]),
        (
            "gcc",
            vec!["-O2", "-DSAFETY", memlim.as_str(), "-o", "pan", "pan.c"],
        ),
    ] {
        let out = Command::new(program)
            .args(&args)
            .current_dir(&work)
            .output();
        if !out.as_ref().is_ok_and(|o| o.status.success()) {
            return failed(format!("{program} failed"), start);
        }
    }
    let preparing = start.elapsed().as_secs_f64();
    let searching = Instant::now();
    let mut verdicts = Vec::new();
    let mut stored = 0u64;
    let mut memory = 0.0f64;
    let mut finished = true;
    for claim in &promela.claims {
        let out = Command::new("timeout")
            .arg(SPIN_LIMIT.as_secs().to_string())
            .args(["./pan", "-N", &claim.name, SPIN_DEPTH])
            .current_dir(&work)
            .output()
            .expect("pan runs");
        let text = String::from_utf8_lossy(&out.stdout).to_string();
        if out.status.code() == Some(124) {
            finished = false;
            verdicts.push(format!("timed out ({} s)", SPIN_LIMIT.as_secs()));
            break;
        }
        let number_after = |marker: &str| -> Option<f64> {
            text.lines()
                .find(|l| l.contains(marker))
                .and_then(|l| l.split_whitespace().next())
                .and_then(|n| n.parse().ok())
        };
        let Some(states) = number_after("states, stored").filter(|&n| n > 0.0) else {
            finished = false;
            verdicts.push("pan did not search".into());
            break;
        };
        stored = stored.max(states as u64);
        memory = memory.max(number_after("total actual memory usage").unwrap_or(0.0));
        let complete =
            !text.contains("max search depth too small") && !text.contains("out of memory");
        finished &= complete;
        let violated = text.contains("assertion violated");
        verdicts.push(
            match claim.verdict(violated, complete) {
                Verdict::Holds => "holds",
                Verdict::Fails => "FAILS",
                Verdict::Incomplete => "undecided",
            }
            .to_string(),
        );
    }
    let mut note = String::new();
    if !promela.values_complete {
        note.push_str(" (values numbered by an incomplete search)");
    }
    Row {
        verdicts: verdicts.join(", ") + &note,
        states: format!("{stored} (most stored by one pan)"),
        seconds: searching.elapsed().as_secs_f64(),
        preparing: Some(preparing),
        memory: format!("{memory:.0} MB"),
        finished,
    }
}

fn main() {
    // `cargo bench` passes `--bench`; the other words name families.
    let wanted: BTreeSet<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-'))
        .collect();
    let spin_here = tools_present();
    if !spin_here {
        eprintln!("spin, gcc or timeout is not on PATH: SPIN's column is left out");
    }
    println!("| family | size | engine | verdicts | states | time | memory |");
    println!("|---|---|---|---|---|---|---|");
    let mut gave_up: BTreeSet<(&str, &str)> = BTreeSet::new();
    for case in cases(&wanted) {
        let behaviour = load(case.family, Arc::new(Folder::new(&case.dir))).expect("loads");
        let mut reference: Option<Vec<Verdict>> = None;
        for (name, engine) in [
            ("auto", Some(SearchEngine::Auto)),
            ("explicit", Some(SearchEngine::Explicit)),
            ("symbolic", Some(SearchEngine::Symbolic)),
            ("SPIN", None),
        ] {
            if gave_up.contains(&(case.family, name)) {
                println!(
                    "| {} | {} | {name} | skipped: did not finish a smaller size | | | |",
                    case.family, case.size
                );
                continue;
            }
            let row = match engine {
                Some(engine) => {
                    let (row, report) = checker(&behaviour, &case, engine);
                    if let Some(report) = report.filter(|_| row.finished) {
                        let verdicts: Vec<Verdict> =
                            report.properties.iter().map(|p| p.verdict).collect();
                        match &reference {
                            None => reference = Some(verdicts),
                            Some(first) => assert_eq!(
                                first, &verdicts,
                                "{} {}: {name} disagrees with the engine before it",
                                case.family, case.size
                            ),
                        }
                    }
                    row
                }
                None if spin_here => spin(&behaviour, &case),
                None => continue,
            };
            if !row.finished && name != "auto" {
                gave_up.insert((case.family, name));
            }
            let time = match row.preparing {
                Some(before) => format!("{:.2} s (+ {before:.1} s to build)", row.seconds),
                None => format!("{:.2} s", row.seconds),
            };
            println!(
                "| {} | {} | {name} | {} | {} | {time} | {} |",
                case.family, case.size, row.verdicts, row.states, row.memory
            );
        }
        let _ = std::fs::remove_dir_all(&case.dir);
    }
}
