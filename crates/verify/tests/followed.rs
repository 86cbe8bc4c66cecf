//! A run found with the clocks of different machines unordered and followed through the ordered
//! model (`confirm.rs`) decides as the whole ordered search does: random behaviours whose
//! machines' clocks are ordered, each state's `never`, `always`, `reachable`, `eventually` and
//! `always_eventually` checked first by the symbolic engine and then by an ordered search cut
//! short, and every verdict a followed run decided compared with that of the complete ordered
//! search, its lasso's loop closing where it starts.

use crate::common::random_behaviour::generate;
use proclaim_behaviour::{load, Folder, PropertyKind};
use proclaim_verify::{verify, Options, PropertyOutcome, PropertySource, SearchEngine, Verdict};
use std::path::Path;
use std::sync::Arc;

/// What the seeds gave: behaviours that order clocks, properties the cut search left to a
/// run (followed or not), and those decided by one.
#[derive(Debug, Default)]
struct Tally {
    seeds_ordered: usize,
    left_to_a_run: usize,
    /// Counterexamples and witnesses followed, and lassos.
    ways: usize,
    lassos: usize,
}

fn properties(behaviour: &proclaim_behaviour::Behaviour) -> Vec<PropertySource> {
    let mut out = Vec::new();
    for m in &behaviour.machines {
        for s in (m.machine.states.iter()).filter(|s| !s.name.contains('.')) {
            let at = format!("{}.{}", m.machine.name, s.name);
            for kind in [
                PropertyKind::Never,
                PropertyKind::Always,
                PropertyKind::Reachable,
                PropertyKind::Eventually,
                PropertyKind::AlwaysEventually,
            ] {
                out.push(PropertySource {
                    name: format!("{} {at}", kind.word()),
                    kind,
                    expression: at.clone(),
                    fair: Vec::new(),
                });
            }
        }
    }
    out
}

fn one(seed: u64, tally: &mut Tally) {
    let random = generate(seed);
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("followed-{}-{seed}", std::process::id()));
    random.write(&dir);
    let behaviour = load("random", Arc::new(Folder::new(&dir)))
        .unwrap_or_else(|e| panic!("seed {seed}: does not load: {e:#?}"));
    let _ = std::fs::remove_dir_all(&dir);
    let properties = properties(&behaviour);
    // The ordered search cut short, so that the runs the symbolic engine found decide: at 50
    // states it leaves lassos, at 12 a few counterexamples and witnesses too (a run's worlds
    // are bounded by the same budget).
    let mut exact = None;
    for states in [50, 12] {
        let cut = Options {
            engine: SearchEngine::Symbolic,
            max_states: states,
            ..Options::default()
        };
        let Ok(report) = verify(&behaviour, &properties, cut) else {
            return;
        };
        let Some(ordered) = &report.clocks_ordered else {
            return;
        };
        if states == 50 {
            tally.seeds_ordered += 1;
        }
        if ordered.stats.complete || !report.properties.iter().any(|p| p.followed) {
            continue;
        }
        let whole = Options {
            clock_order: true,
            engine: SearchEngine::Explicit,
            max_states: 200_000,
            ..Options::default()
        };
        let exact = exact.get_or_insert_with(|| verify(&behaviour, &properties, whole));
        let Ok(exact) = exact else { return };
        if !exact.stats.complete || !exact.inexact.is_empty() {
            return;
        }
        compare(
            seed,
            &random.show(),
            &report.properties,
            &exact.properties,
            tally,
        );
    }
}

/// Every verdict cut short is undecided or the whole search's, those a run decided above all.
fn compare(
    seed: u64,
    shown: &str,
    cut: &[PropertyOutcome],
    whole: &[PropertyOutcome],
    tally: &mut Tally,
) {
    for (p, e) in cut.iter().zip(whole) {
        if p.followed || p.unconfirmed {
            tally.left_to_a_run += 1;
        }
        if p.followed {
            match &p.cycle {
                Some(cycle) => {
                    assert!(
                        cycle.run.closes(),
                        "seed {seed}: {}'s loop does not close\n{shown}",
                        p.name
                    );
                    tally.lassos += 1;
                }
                None => tally.ways += 1,
            }
            assert_eq!(
                p.verdict, e.verdict,
                "seed {seed}: {} decided by its run as {:?}, by the whole ordered search as {:?}\n{shown}",
                p.name, p.verdict, e.verdict,
            );
        }
        assert!(
            p.verdict == Verdict::Incomplete || p.verdict == e.verdict,
            "seed {seed}: {} is {:?} cut short and {:?} whole\n{shown}",
            p.name,
            p.verdict,
            e.verdict,
        );
    }
}

fn tally(seeds: std::ops::Range<u64>) -> Tally {
    let mut tally = Tally::default();
    for seed in seeds {
        one(seed, &mut tally);
    }
    eprintln!("{tally:?}");
    tally
}

#[test]
fn runs_followed_through_the_ordered_model_decide_as_its_whole_search() {
    let tally = tally(0..150);
    assert!(tally.lassos >= 10, "too few lassos followed: {tally:?}");
    assert!(
        tally.ways >= 1,
        "no counterexample or witness followed: {tally:?}"
    );
    assert!(
        tally.seeds_ordered >= 20,
        "too few behaviours order clocks: {tally:?}"
    );
}

#[test]
#[ignore]
fn two_thousand_behaviours_decide_by_their_followed_runs_as_by_the_whole_ordered_search() {
    tally(0..2_000);
}
