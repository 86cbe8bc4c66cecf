//! What the monitor page costs a running behaviour: the label round trip with and without a
//! page open, the page under 10,000 postings a second (frames it gets, postings that still go
//! through), and memory over a long run with a page that reads and one that has stalled.
//! Figures, never asserts. `cargo bench --bench monitor` (`PROCLAIM_SOAK_SECS=3600` for an
//! hour's soak; 60 s by default).

mod common;

use proclaim_board::Whiteboard;
use proclaim_monitor::{Chart, Monitor};
use proclaim_runner::{Answerer, Event};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};
use tokio::io::{AsyncReadExt, AsyncWriteExt};

fn percentile_line(name: &str, mut samples: Vec<Duration>) -> f64 {
    samples.sort_unstable();
    let at = |q: f64| samples[((samples.len() - 1) as f64 * q) as usize].as_secs_f64() * 1e6;
    println!(
        "{name:<52} n={:<7} p50 {:>7.2} µs   p90 {:>7.2} µs   p99 {:>8.2} µs",
        samples.len(),
        at(0.5),
        at(0.9),
        at(0.99)
    );
    at(0.5)
}

fn machine() -> Vec<Chart> {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/machines/microwave/Microwave.machine"
    ))
    .unwrap();
    proclaim_fsm::parse_machine("Microwave.machine", &text)
        .machines
        .iter()
        .map(|m| Chart::of_machine(m, true))
        .collect()
}

/// A page reading `/api/frames`: counts frames and bytes until `stop`. `stalled`: reads the
/// response head, then nothing (a browser tab in the background, a page frozen).
fn open_page(
    addr: std::net::SocketAddr,
    stalled: bool,
    frames: Arc<AtomicU64>,
    bytes: Arc<AtomicU64>,
) -> tokio::task::JoinHandle<()> {
    tokio::spawn(async move {
        let mut stream = tokio::net::TcpStream::connect(addr).await.unwrap();
        stream
            .write_all(
                b"GET /api/frames HTTP/1.1\r\nHost: bench\r\nAccept: text/event-stream\r\n\r\n",
            )
            .await
            .unwrap();
        let mut buffer = vec![0u8; 1 << 16];
        let mut tail = Vec::new();
        loop {
            let Ok(n) = stream.read(&mut buffer).await else {
                return;
            };
            if n == 0 {
                return;
            }
            if stalled {
                std::future::pending::<()>().await;
            }
            bytes.fetch_add(n as u64, Ordering::Relaxed);
            tail.extend_from_slice(&buffer[..n]);
            let text = String::from_utf8_lossy(&tail).into_owned();
            frames.fetch_add(
                text.matches("event: frame").count() as u64,
                Ordering::Relaxed,
            );
            // Keep what may be the start of the next marker.
            let keep = tail.len().saturating_sub(16);
            tail.drain(..keep);
            let kept = String::from_utf8_lossy(&tail).into_owned();
            frames.fetch_sub(
                kept.matches("event: frame").count() as u64,
                Ordering::Relaxed,
            );
        }
    })
}

/// Calls `act` with 0, 1, 2, … `rate` times a second until `stop`; how many calls.
fn at_rate(
    rate: u64,
    stop: Arc<AtomicU64>,
    mut act: impl FnMut(u64, Duration) + Send + 'static,
) -> tokio::task::JoinHandle<u64> {
    tokio::spawn(async move {
        let start = Instant::now();
        let mut done = 0u64;
        while stop.load(Ordering::Relaxed) == 0 {
            let due = (start.elapsed().as_secs_f64() * rate as f64) as u64;
            while done < due {
                act(done, start.elapsed());
                done += 1;
            }
            tokio::time::sleep(Duration::from_millis(1)).await;
        }
        done
    })
}

/// Events as a run folds them in, `rate` a second, until `stop` (the answers of a machine's
/// labels, as the run's event loop hands them to the page).
fn fold_events(monitor: Monitor, rate: u64, stop: Arc<AtomicU64>) -> tokio::task::JoinHandle<u64> {
    at_rate(rate, stop, move |n, at| {
        monitor.observe(&Event::Answered {
            round: 0,
            machine: "Microwave".into(),
            atom: format!("label{}", n % 50),
            value: n % 7 == 0,
            by: Answerer::Expert("oven".into()),
            at,
        })
    })
}

/// Posts `rate` messages a second over 100 types until `stop`.
fn post_load(board: Whiteboard, rate: u64, stop: Arc<AtomicU64>) -> tokio::task::JoinHandle<u64> {
    at_rate(rate, stop, move |n, _| {
        board.post("sensor", &format!("Reading{}", n % 100), n as i64);
    })
}

fn resident_mib() -> Option<f64> {
    let statm = std::fs::read_to_string("/proc/self/statm").ok()?;
    let pages: f64 = statm.split_whitespace().nth(1)?.parse().ok()?;
    Some(pages * 4096.0 / (1024.0 * 1024.0))
}

fn main() {
    let runtime = common::runtime();
    let quick = common::quick();
    let n = if quick { 1_000 } else { 50_000 };
    let load_secs = if quick { 1 } else { 10 };
    let soak_secs: u64 = if quick {
        2
    } else {
        std::env::var("PROCLAIM_SOAK_SECS")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(60)
    };
    runtime.block_on(async {
        // The round trip, no page, then with two pages open (one reading, one stalled) and
        // 10,000 events a second folded into the picture.
        let board = common::oven().await;
        let _ = common::round_trips(&board, 1_000).await;
        let bare = percentile_line("label round trip, no monitor", common::round_trips(&board, n).await);
        let monitor = Monitor::live("microwave", machine(), board.clone(), None);
        let addr = monitor.serve("127.0.0.1:0".parse().unwrap()).await.unwrap();
        let (frames, bytes) = (Arc::new(AtomicU64::new(0)), Arc::new(AtomicU64::new(0)));
        let reader = open_page(addr, false, frames.clone(), bytes.clone());
        let stalled = open_page(addr, true, Arc::default(), Arc::default());
        let stop = Arc::new(AtomicU64::new(0));
        let folding = fold_events(monitor.clone(), 10_000, stop.clone());
        let _ = common::round_trips(&board, 1_000).await;
        let with = percentile_line(
            "label round trip, 2 pages open, 10k events/s folded",
            common::round_trips(&board, n).await,
        );
        println!("{:<52} {:.2}x the round trip without (p50)", "", with / bare);
        stop.store(1, Ordering::Relaxed);
        let _ = folding.await;

        // 10,000 postings a second for a while: what the page gets.
        let stop = Arc::new(AtomicU64::new(0));
        let (frames0, bytes0) = (frames.load(Ordering::Relaxed), bytes.load(Ordering::Relaxed));
        let poster = post_load(board.clone(), 10_000, stop.clone());
        let folding = fold_events(monitor.clone(), 10_000, stop.clone());
        let start = Instant::now();
        tokio::time::sleep(Duration::from_secs(load_secs)).await;
        stop.store(1, Ordering::Relaxed);
        let posted = poster.await.unwrap();
        let folded = folding.await.unwrap();
        let secs = start.elapsed().as_secs_f64();
        println!(
            "{:<52} {:.0} postings/s and {:.0} events/s went through; the page got {:.1} frames/s ({:.0} KiB/s)",
            "10,000 postings/s with a page open",
            posted as f64 / secs,
            folded as f64 / secs,
            (frames.load(Ordering::Relaxed) - frames0) as f64 / secs,
            (bytes.load(Ordering::Relaxed) - bytes0) as f64 / secs / 1024.0,
        );

        // Memory over a long run: postings and events at 10,000 a second each, both pages open.
        let stop = Arc::new(AtomicU64::new(0));
        let poster = post_load(board.clone(), 10_000, stop.clone());
        let folding = fold_events(monitor.clone(), 10_000, stop.clone());
        let start_mib = resident_mib();
        let mut samples = Vec::new();
        for tenth in 1..=10 {
            tokio::time::sleep(Duration::from_secs_f64(soak_secs as f64 / 10.0)).await;
            samples.push((tenth, resident_mib()));
        }
        stop.store(1, Ordering::Relaxed);
        let posted = poster.await.unwrap();
        let folded = folding.await.unwrap();
        let shown: Vec<String> = samples
            .iter()
            .map(|(t, m)| format!("{}%: {:.1}", t * 10, m.unwrap_or(f64::NAN)))
            .collect();
        println!(
            "{:<52} {posted} postings and {folded} events over {soak_secs} s; resident MiB at start {:.1}, then {}",
            "memory with 2 pages open (one stalled)",
            start_mib.unwrap_or(f64::NAN),
            shown.join(", ")
        );
        reader.abort();
        stalled.abort();
    });
}
