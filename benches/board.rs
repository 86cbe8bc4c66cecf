//! Whiteboard latency and throughput, in-process: post → subscriber woken, a label query answered
//! by the reasoner expert (percentiles from individual samples), and messages a second fanned
//! out to 10 subscribers. Figures, never asserts. `cargo bench --bench board`.

use proclaim_board::Whiteboard;
use proclaim_cdl::{load, Language};
use proclaim_experts::ReasonerExpert;
use std::sync::Arc;
use std::time::{Duration, Instant};
use tokio::sync::Notify;

fn percentiles(name: &str, mut samples: Vec<Duration>) {
    samples.sort_unstable();
    let at = |q: f64| samples[((samples.len() - 1) as f64 * q) as usize];
    println!(
        "{name:<44} n={:<7} p50 {:>8.2} µs   p90 {:>8.2} µs   p99 {:>8.2} µs   max {:>9.2} µs",
        samples.len(),
        at(0.5).as_secs_f64() * 1e6,
        at(0.9).as_secs_f64() * 1e6,
        at(0.99).as_secs_f64() * 1e6,
        at(1.0).as_secs_f64() * 1e6,
    );
}

/// From just before `post` to the subscribing task running with the message.
async fn post_to_wake(samples: usize) -> Vec<Duration> {
    let board = Whiteboard::local();
    let mut sub = board.subscribe("ping");
    let base = Instant::now();
    let done = Arc::new(Notify::new());
    let (tx, mut rx) = tokio::sync::mpsc::unbounded_channel();
    let notify = done.clone();
    tokio::spawn(async move {
        while let Some(m) = sub.next().await {
            let woke = base.elapsed();
            if let proclaim_board::Value::Int(sent) = m.value {
                let _ = tx.send(woke - Duration::from_nanos(sent as u64));
            }
            notify.notify_one();
        }
    });
    for _ in 0..samples {
        let sent = base.elapsed().as_nanos() as i64;
        board.post("bench", "ping", sent);
        done.notified().await;
    }
    let mut out = Vec::with_capacity(samples);
    while let Ok(d) = rx.try_recv() {
        out.push(d);
    }
    out
}

async fn query_latency(samples: usize) -> Vec<Duration> {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/theories/microwave.dl"
    ))
    .unwrap();
    let theory = load(&text, Language::Dl).unwrap();
    let board = Whiteboard::local();
    tokio::spawn(ReasonerExpert::new("oven", theory, &Default::default()).run(board.clone()));
    while board.registry().answerers("cook").is_empty() {
        tokio::task::yield_now().await;
    }
    board.post("sensors", "timeLeft", true);
    let mut out = Vec::with_capacity(samples);
    for i in 0..samples {
        if i % 100 == 0 {
            // An input change now and then, so answers are re-proved, not only cached.
            board.post("sensors", "doorOpen", i % 200 == 0);
        }
        let start = Instant::now();
        let answer = board.query("machine", "cook", Duration::from_secs(1)).await;
        out.push(start.elapsed());
        assert!(matches!(
            answer,
            proclaim_board::QueryOutcome::Answered { .. }
        ));
    }
    out
}

async fn fan_out(messages: usize, subscribers: usize) -> (f64, u64) {
    let board = Whiteboard::new(Arc::new(proclaim_board::LocalBoard::with_retention(
        proclaim_board::Retention {
            subscriber_queue: 1 << 16,
            ..Default::default()
        },
    )));
    let mut handles = Vec::new();
    for _ in 0..subscribers {
        let mut sub = board.subscribe("tick");
        handles.push(tokio::spawn(async move {
            let mut n = 0usize;
            while let Some(m) = sub.next().await {
                n += 1;
                if m.value == proclaim_board::Value::Int(-1) {
                    break;
                }
            }
            n
        }));
    }
    let start = Instant::now();
    for i in 0..messages {
        board.post("bench", "tick", i as i64);
        if i % 4096 == 0 {
            tokio::task::yield_now().await;
        }
    }
    board.post("bench", "tick", -1i64);
    for h in handles {
        h.await.unwrap();
    }
    (
        messages as f64 / start.elapsed().as_secs_f64(),
        board.stats().drops,
    )
}

fn main() {
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .unwrap();
    // Short runs when invoked by `cargo test --benches` / `cargo bench --no-run` smoke checks.
    let quick = std::env::args().any(|a| a == "--test");
    let n = if quick { 1_000 } else { 100_000 };
    runtime.block_on(async {
        let _ = post_to_wake(1_000).await; // warm up
        percentiles(
            "post -> subscriber woken (other task)",
            post_to_wake(n).await,
        );
        let _ = query_latency(1_000).await;
        percentiles(
            "query -> reasoner expert answer -> waiter",
            query_latency(n / 2).await,
        );
        let (rate, drops) = fan_out(if quick { 10_000 } else { 1_000_000 }, 10).await;
        println!(
            "{:<44} {:>10.0} messages/s posted, each to 10 subscribers ({drops} dropped)",
            "fan-out to 10 subscribers", rate
        );
    });
}
