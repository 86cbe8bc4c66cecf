//! States explored per second on a scalable family: `odometer N K`, N machines each holding
//! one digit (a global) of a base-K counter in its Internal activity, each digit stepping when
//! the one before it is 0, so all K^N readings are reached; the first machine also fires on a
//! free button, so every step has two environment choices and the graph has about
//! 2·N·K^N states. `cargo bench -p proclaim-verify`.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use proclaim_behaviour::{load, Behaviour, Folder};
use proclaim_verify::{verify, Options, PropertyKind, PropertySource};
use std::sync::Arc;

#[path = "../tests/common/odometer.rs"]
mod odometer_family;

/// The behaviour `odometer N K`, written to a temporary folder and loaded.
fn odometer(n: usize, k: usize) -> Behaviour {
    let dir = std::env::temp_dir().join(format!("proclaim-verify-bench-{n}-{k}"));
    odometer_family::write_odometer(&dir, n, k);
    load("odometer", Arc::new(Folder::new(dir))).expect("loads")
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("verify");
    group.sample_size(10);
    for (n, k) in [(2, 30), (3, 20), (4, 12)] {
        let behaviour = odometer(n, k);
        let property = [PropertySource {
            name: "bounded".into(),
            kind: PropertyKind::Never,
            expression: format!("g0 >= {k}"),
            fair: Vec::new(),
        }];
        let report = verify(&behaviour, &property, Options::default()).expect("verifies");
        let s = &report.stats;
        eprintln!(
            "odometer {n} {k}: {} states, {} steps, {:.1} bytes/state ({:.1} packed)",
            s.states, s.transitions, s.bytes_per_state, s.packed_bytes_per_state
        );
        group.throughput(Throughput::Elements(s.states as u64));
        group.bench_function(format!("odometer {n} {k}"), |b| {
            b.iter(|| verify(&behaviour, &property, Options::default()).expect("verifies"))
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
