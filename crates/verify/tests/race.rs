//! The automatic engine choice races the two engines on one model: whichever decides first
//! answers, the verdict is the one either engine gives alone, and a search the explicit engine
//! cannot hold in `--max-memory` is still decided when the symbolic engine can.

use crate::common;

use proclaim_behaviour::{load, Behaviour, Folder};
use proclaim_verify::{
    verify, Options, PropertyKind, PropertySource, Report, SearchEngine, Stop, Verdict,
};
use std::path::Path;
use std::sync::Arc;

fn family(name: &str, write: impl FnOnce(&Path)) -> Behaviour {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("proclaim-race-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    write(&dir);
    load(name, Arc::new(Folder::new(&dir))).expect("the family loads")
}

fn property(kind: PropertyKind, expression: &str) -> PropertySource {
    PropertySource {
        name: expression.into(),
        kind,
        expression: expression.into(),
        fair: Vec::new(),
    }
}

fn check(behaviour: &Behaviour, p: &PropertySource, engine: SearchEngine, memory: usize) -> Report {
    let options = Options {
        engine,
        max_memory: memory,
        ..Options::default()
    };
    verify(behaviour, std::slice::from_ref(p), options).expect("it verifies")
}

/// The press's liveness property is past the explicit search's first states, so both engines
/// run; whichever answers, the verdict and a lasso are there, as each engine gives alone.
#[test]
fn auto_answers_with_the_verdict_each_engine_gives_alone() {
    let press = family("press", common::families::write_press);
    let p = property(PropertyKind::AlwaysEventually, "Controller.Open");
    let budget = Options::default().max_memory;
    for engine in [
        SearchEngine::Explicit,
        SearchEngine::Symbolic,
        SearchEngine::Auto,
    ] {
        let report = check(&press, &p, engine, budget);
        let outcome = &report.properties[0];
        assert_eq!(outcome.verdict, Verdict::Fails, "{engine:?}");
        assert!(outcome.cycle.is_some(), "{engine:?}: a lasso");
        assert!(report.stats.complete, "{engine:?}");
    }
}

/// Twenty sensors are about a million explicit states, more than 4 MB hold; their decision
/// diagrams are small. Alone, the explicit search is undecided; auto answers, through the
/// symbolic engine, within the same budget.
#[test]
fn what_the_explicit_search_cannot_hold_the_symbolic_engine_decides_in_the_same_budget() {
    let sensors = family("sensors", |dir| common::families::write_sensors(dir, 20));
    let p = property(PropertyKind::Always, "alarm == 0 || alarm == 1");
    let budget = 4 << 20;
    let alone = check(&sensors, &p, SearchEngine::Explicit, budget);
    assert_eq!(alone.stats.stopped, Stop::MemoryBudget);
    assert_eq!(alone.properties[0].verdict, Verdict::Incomplete);
    let auto = check(&sensors, &p, SearchEngine::Auto, budget);
    assert_eq!(auto.properties[0].verdict, Verdict::Holds);
    assert_eq!(auto.stats.engine, SearchEngine::Symbolic.word());
    assert!(auto.stats.bytes <= budget, "{} bytes", auto.stats.bytes);
}
