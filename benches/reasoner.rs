//! Criterion benchmarks: one query after one input change on the theories users meet first, and
//! parse-to-conclusions on the standard families. Figures, never asserts.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use proclaim_cdl::{load, Algorithm, Engine, Language, Session};
use std::hint::black_box;
use std::sync::Arc;

fn theory_text(path: &str) -> String {
    std::fs::read_to_string(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(path)).unwrap()
}

/// Flip one input, then ask one output: the reasoner expert's job on every sensor change.
fn query_after_input_change(c: &mut Criterion) {
    let mut group = c.benchmark_group("query after one input change");
    for (name, path, input, output) in [
        (
            "offside",
            "theories/offside.dl",
            "fewerThanTwoOpponentsBetween",
            "offside",
        ),
        ("microwave", "theories/microwave.dl", "doorOpen", "light"),
        (
            "microwave cook",
            "theories/microwave.dl",
            "timeLeft",
            "cook",
        ),
    ] {
        let theory = load(&theory_text(path), Language::Dl).unwrap();
        let atom = theory.atom(input).unwrap();
        let lit = theory.lit(output).unwrap();
        let mut session = Session::new(Engine::new(theory));
        for other in session.engine().clone().theory().input_atoms() {
            session.set_input(other, Some(false)).unwrap();
        }
        let mut value = false;
        group.bench_function(name, |b| {
            b.iter(|| {
                value = !value;
                session.set_input(atom, Some(value)).unwrap();
                black_box(session.prove(Algorithm::Beta, lit))
            })
        });
    }
    group.finish();
}

fn family_text(name: &str, sizes: &[u64]) -> String {
    let mut text = Vec::new();
    proclaim_gen::Family::parse(name, sizes)
        .unwrap()
        .write(&mut text, proclaim_gen::Format::Dl)
        .unwrap();
    String::from_utf8(text).unwrap()
}

/// Parse, check, compile and every β conclusion.
fn end_to_end(c: &mut Criterion) {
    let mut group = c.benchmark_group("parse to all beta conclusions");
    group.sample_size(10);
    for (name, sizes) in [
        ("chain", vec![10_000]),
        ("circle", vec![10_000]),
        ("dag", vec![3_333, 3]),
        ("levels-", vec![1_000]),
        ("teams", vec![6]),
        ("tree", vec![8, 3]),
    ] {
        let text = family_text(name, &sizes);
        let rules = proclaim_gen::Family::parse(name, &sizes)
            .unwrap()
            .rule_count();
        group.throughput(Throughput::Elements(rules as u64));
        group.bench_with_input(BenchmarkId::new(name, rules), &text, |b, text| {
            b.iter(|| {
                let theory = load(text, Language::Dl).unwrap();
                let mut session = Session::new(Engine::new(theory));
                black_box(session.count_conclusions(Algorithm::Beta))
            })
        });
    }
    group.finish();
}

/// Reasoning alone on a compiled theory (a fresh session each time).
fn reasoning_only(c: &mut Criterion) {
    let mut group = c.benchmark_group("all beta and pi conclusions");
    group.sample_size(10);
    for (name, sizes) in [
        ("chain", vec![100_000]),
        ("teams", vec![7]),
        ("levels", vec![1_000]),
    ] {
        let engine = Arc::new(Engine::new(
            load(&family_text(name, &sizes), Language::Dl).unwrap(),
        ));
        group.bench_function(name, |b| {
            b.iter(|| {
                let mut session = Session::new(engine.clone());
                black_box(
                    session.count_conclusions(Algorithm::Beta)
                        + session.count_conclusions(Algorithm::Pi),
                )
            })
        });
    }
    group.finish();
}

criterion_group!(
    benches,
    query_after_input_change,
    end_to_end,
    reasoning_only
);
criterion_main!(benches);
