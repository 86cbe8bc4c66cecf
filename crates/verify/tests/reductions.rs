//! The exact reductions change nothing a user reads: on every example behaviour and on the
//! families of real shapes, each combination of reductions gives every property the verdict
//! and the counterexample length of the plain search, and the same findings where both
//! searches finish.

use crate::common;

use proclaim_behaviour::{load, Behaviour, Folder};
use proclaim_verify::{
    manifest_properties, verify, Finding, Options, PropertyKind, PropertySource, Reductions,
    Report, SearchEngine, Stop, VerifyError,
};
use std::path::{Path, PathBuf};
use std::sync::Arc;

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("proclaim-reductions-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// The manifest's properties, and for every state of every machine whether it is reachable
/// (a witness) and a claim that it never is (a counterexample where it is).
fn properties(behaviour: &Behaviour, extra: &[(PropertyKind, &str)]) -> Vec<PropertySource> {
    let mut all = manifest_properties(behaviour);
    for m in &behaviour.machines {
        for s in &m.machine.states {
            // A state of regions is one of each region's (§3.2).
            let paths = m.machine.atomic_paths(s).into_iter();
            let each: Vec<String> = paths.map(|p| format!("{}.{p}", m.machine.name)).collect();
            for kind in [PropertyKind::Reachable, PropertyKind::Never] {
                let expression = each.join(" && ");
                all.push(PropertySource {
                    name: format!("{} {expression}", kind.word()),
                    kind,
                    expression,
                    fair: Vec::new(),
                });
            }
        }
    }
    for (kind, expression) in extra {
        all.push(PropertySource {
            name: format!("{} {expression}", kind.word()),
            kind: *kind,
            expression: expression.to_string(),
            fair: Vec::new(),
        });
    }
    all
}

/// A property beside those every case gets.
type Extra<'a> = (PropertyKind, &'a str);

/// Every combination of the three reductions.
fn combinations() -> Vec<Reductions> {
    (0..8)
        .map(|bits| Reductions {
            chosen_when_read: bits & 1 != 0,
            cone_of_influence: bits & 2 != 0,
            stop_when_decided: bits & 4 != 0,
        })
        .collect()
}

/// What must not change: each property's verdict and the length of its trace.
fn verdicts(report: &Report) -> Vec<String> {
    report
        .properties
        .iter()
        .map(|p| {
            let steps = p.trace.as_ref().map(|t| t.steps.len());
            format!("{}: {:?} {:?}", p.name, p.verdict, steps)
        })
        .collect()
}

fn findings(report: &Report) -> Vec<String> {
    report
        .findings
        .iter()
        .map(|f| match f {
            Finding::Deadlock { waiting, trace } => {
                format!("deadlock {waiting:?} after {} steps", trace.steps.len())
            }
            other => format!("{other:?}"),
        })
        .collect()
}

/// The symbolic engine, where it takes the behaviour, gives the explicit search's verdicts,
/// counterexample lengths, and states never entered and transitions that never fire.
fn check_symbolic(
    case: &str,
    behaviour: &Behaviour,
    properties: &[PropertySource],
    plain: &Report,
) {
    let options = Options {
        engine: SearchEngine::Symbolic,
        ..Options::default()
    };
    let symbolic = match verify(behaviour, properties, options) {
        Ok(report) => report,
        Err(VerifyError::SymbolicDeclined(why)) => {
            eprintln!("{case}: the symbolic engine declines: {why}");
            return;
        }
        Err(e) => panic!("{case}: {e}"),
    };
    assert_eq!(verdicts(&symbolic), verdicts(plain), "{case}, symbolic");
    if symbolic.stats.stopped == Stop::Explored {
        // Of the nearest deadlocks the engines may name different ones, at the same depth.
        let nearest = |r: &Report| {
            findings(r)
                .into_iter()
                .map(|f| match f.split_once(" after ") {
                    Some((_, depth)) if f.starts_with("deadlock") => {
                        format!("deadlock after {depth}")
                    }
                    _ => f,
                })
                .collect::<Vec<_>>()
        };
        assert_eq!(nearest(&symbolic), nearest(plain), "{case}, symbolic");
    }
}

/// Checks every other combination of reductions that includes those of `baseline` against it
/// (the baseline's own search is the one compared with).
fn check_case(
    case: &str,
    behaviour: &Behaviour,
    extra: &[(PropertyKind, &str)],
    baseline: Reductions,
) {
    let properties = properties(behaviour, extra);
    let options = |reductions| Options {
        max_states: 300_000,
        reductions,
        engine: SearchEngine::Explicit,
        ..Options::default()
    };
    let plain =
        verify(behaviour, &properties, options(baseline)).unwrap_or_else(|e| panic!("{case}: {e}"));
    assert_eq!(
        plain.stats.stopped,
        Stop::Explored,
        "{case}: too large a case"
    );
    let includes = |r: &Reductions| {
        *r != baseline
            && (r.chosen_when_read || !baseline.chosen_when_read)
            && (r.cone_of_influence || !baseline.cone_of_influence)
    };
    check_symbolic(case, behaviour, &properties, &plain);
    for reductions in combinations().into_iter().filter(includes) {
        let reduced = verify(behaviour, &properties, options(reductions)).expect("verifies");
        assert_eq!(
            verdicts(&reduced),
            verdicts(&plain),
            "{case} with {reductions:?}"
        );
        if reduced.stats.stopped == Stop::Explored {
            assert_eq!(
                findings(&reduced),
                findings(&plain),
                "{case} with {reductions:?}"
            );
        }
        assert!(
            reduced.stats.states <= plain.stats.states,
            "{case} with {reductions:?}: {} states, {} without",
            reduced.stats.states,
            plain.stats.states
        );
    }
}

#[test]
fn every_example_behaviour_keeps_its_verdicts() {
    let mut checked = 0;
    for entry in std::fs::read_dir(repo().join("machines")).expect("machines/") {
        let dir = entry.expect("entry").path();
        if !dir.join("behaviour.toml").exists() {
            continue;
        }
        let case = dir.file_name().unwrap().to_string_lossy().to_string();
        let Ok(behaviour) = load(&case, Arc::new(Folder::new(&dir))) else {
            continue;
        };
        // A behaviour the checker refuses (suppression, widths) is refused either way.
        if verify(&behaviour, &[], Options::default()).is_err() {
            continue;
        }
        // Where the plain search is long (the GameController's free inputs stored in every
        // state: hundreds of successors each), the examples are checked against the search
        // that chooses them when read, as the press of the families is.
        let plain = Options {
            max_states: 5_000,
            reductions: Reductions::NONE,
            engine: SearchEngine::Explicit,
            ..Options::default()
        };
        let small = verify(&behaviour, &[], plain).is_ok_and(|r| r.stats.complete);
        let baseline = if small {
            Reductions::NONE
        } else {
            Reductions {
                chosen_when_read: true,
                ..Reductions::NONE
            }
        };
        check_case(&case, &behaviour, &[], baseline);
        checked += 1;
    }
    assert!(checked >= 4, "only {checked} example behaviours checked");
}

// The real shapes, one test each so that nextest runs them side by side.

#[test]
fn the_sensors_shape_keeps_its_verdicts() {
    let sensors = scratch("sensors");
    common::families::write_sensors(&sensors, 3);
    let behaviour = load("sensors", Arc::new(Folder::new(&sensors))).expect("loads");
    // A free input a property names is stored, the others chosen when read.
    let extra: &[Extra] = &[
        (PropertyKind::Reachable, "in0 && Controller.Alarm"),
        (PropertyKind::Always, "alarm == 0 || s1 == 1"),
    ];
    check_case("sensors", &behaviour, extra, Reductions::NONE);
}

#[test]
fn the_press_shape_keeps_its_verdicts() {
    let press = scratch("press");
    common::families::write_press(&press);
    let behaviour = load("press", Arc::new(Folder::new(&press))).expect("loads");
    // Five free inputs stored in every state are more than a test should explore: the press
    // is checked against the search that chooses them when read and reduces nothing else.
    let chosen = Reductions {
        chosen_when_read: true,
        ..Reductions::NONE
    };
    let extra: &[Extra] = &[(
        PropertyKind::Never,
        "Controller.PressClosed && Controller.Open",
    )];
    check_case("press", &behaviour, extra, chosen);
}

#[test]
fn the_minepump_shape_keeps_its_verdicts() {
    let minepump = scratch("minepump");
    common::families::write_minepump(&minepump);
    let behaviour = load("minepump", Arc::new(Folder::new(&minepump))).expect("loads");
    let extra: &[Extra] = &[(PropertyKind::Never, "pumping == 1 && methane == 1")];
    check_case("minepump", &behaviour, extra, Reductions::NONE);
}

#[test]
fn the_odometer_shape_keeps_its_verdicts() {
    let odometer = scratch("odometer");
    common::odometer::write_odometer(&odometer, 2, 4);
    let behaviour = load("odometer", Arc::new(Folder::new(&odometer))).expect("loads");
    let extra: &[Extra] = &[(PropertyKind::Never, "g0 >= 4")];
    check_case("odometer", &behaviour, extra, Reductions::NONE);
}
