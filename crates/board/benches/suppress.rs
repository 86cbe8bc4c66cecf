//! What subsumption costs a posting: a plain post on the in-process board, against the same
//! post after the behaviour's `Suppressor` judged it (a type not declared, as most are; a
//! suppressed type shown; one suppressed, which is not posted at all), and a `release` with
//! nothing due, which the round schedule asks before every ringlet. `cargo bench -p
//! proclaim-board --bench suppress`.

use criterion::{criterion_group, criterion_main, Criterion};
use proclaim_board::{LocalBoard, Suppressor, Transport, Value, Visibility};
use std::hint::black_box;
use std::time::Duration;

fn bench(c: &mut Criterion) {
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_time()
        .build()
        .expect("a runtime");
    let _guard = runtime.enter();
    let board = LocalBoard::new();
    let value = Value::Str("forward".into());
    let mut group = c.benchmark_group("suppress");
    group.bench_function("post, no suppressor", |b| {
        b.iter(|| board.post_ranked("Walk", "walk", black_box(value.clone()), 0))
    });
    let judged = |suppressor: &mut Suppressor<Value>, ty: &str, priority: u32, now: Duration| {
        match suppressor.offer("Walk", ty, &value, priority, now) {
            Visibility::Shown => Some(board.post_ranked("Walk", ty, value.clone(), priority)),
            Visibility::Suppressed { .. } => None,
        }
    };
    let mut suppressor = Suppressor::new([("walk", Duration::from_millis(500))]);
    group.bench_function("post, type not declared", |b| {
        b.iter(|| judged(&mut suppressor, black_box("say"), 0, Duration::ZERO))
    });
    let mut now = Duration::ZERO;
    group.bench_function("post, suppressed type shown", |b| {
        b.iter(|| {
            now += Duration::from_millis(1);
            judged(&mut suppressor, black_box("walk"), 0, now)
        })
    });
    let mut suppressor = Suppressor::new([("walk", Duration::from_secs(3600))]);
    suppressor.offer("Reflex", "walk", &value, 2, Duration::ZERO);
    group.bench_function("post, suppressed", |b| {
        b.iter(|| {
            judged(
                &mut suppressor,
                black_box("walk"),
                0,
                Duration::from_secs(1),
            )
        })
    });
    group.bench_function("release, nothing due", |b| {
        b.iter(|| suppressor.release(black_box(Duration::from_secs(2))))
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
