//! The whiteboard across processes (needs `--features zenoh`), on loopback: a posting's way to a
//! reader in another process beside a bare Zenoh put to a subscriber in another process, in the
//! same run; a label query answered by a reasoner expert in another process, beside the bare
//! Zenoh request/reply round trip; a late joiner's catch-up with a board of 10,000 types; and
//! messages per second from one process to another. Both on Zenoh's default transport and on
//! its low-latency one (`--low-latency`). The bench binary is also its own other process
//! (`PROCLAIM_BENCH_ROLE`).
//!
//! `cargo bench --features zenoh --bench network`

use proclaim_board::Whiteboard;
use proclaim_zenoh::{whiteboard, Role, Settings};
use std::io::{BufRead, BufReader, Write};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const THEORY: &str = include_str!("../theories/microwave.dl");
const MESSAGES: u64 = 50_000;
const SAMPLES: usize = 3000;
/// The types of the board a late joiner catches up with.
const TYPES: usize = 10_000;

fn main() {
    // What `proclaim` runs with (before any thread exists).
    proclaim_zenoh::prefer_few_threads();
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .unwrap();
    match std::env::var("PROCLAIM_BENCH_ROLE") {
        Ok(role) => runtime.block_on(child(&role)),
        Err(_) => {
            for low_latency in [false, true] {
                runtime.block_on(parent(low_latency));
            }
        }
    }
}

/// The transport a child uses: the parent's, passed down in `PROCLAIM_BENCH_LOW_LATENCY`.
fn settings() -> Settings {
    Settings {
        config_file: None,
        low_latency: std::env::var_os("PROCLAIM_BENCH_LOW_LATENCY").is_some(),
        ..Settings::default()
    }
}

async fn join(endpoint: &str) -> Whiteboard {
    whiteboard(&Role::Connect(endpoint.to_string()), "bench", &settings())
        .await
        .expect("joins the bench board")
}

/// The other process: an expert, a sink that counts `tick`s, or a pinger.
async fn child(role: &str) {
    let (what, endpoint) = role.split_once(' ').expect("ROLE ENDPOINT");
    match what {
        "reader" | "bare" => {
            let ready = || println!("ready");
            let samples = if what == "bare" {
                proclaim_zenoh::bare_receive(endpoint, "bench", &settings(), SAMPLES, ready)
                    .await
                    .expect("the bare sender puts")
            } else {
                read_postings(join(endpoint).await, ready).await
            };
            let name = if what == "bare" {
                "bare Zenoh put -> subscriber in another process"
            } else {
                "posting -> reader in another process"
            };
            percentiles(name, samples);
            return;
        }
        "joiner" => {
            let started = Instant::now();
            let board = join(endpoint).await;
            let elapsed = started.elapsed();
            let types = board.snapshot().len();
            println!(
                "{:<48} {types} types in {:.0} ms (the mesh's settling included)",
                "a late joiner's catch-up",
                elapsed.as_secs_f64() * 1e3
            );
            return;
        }
        _ => {}
    }
    if what == "ping" {
        let samples = proclaim_zenoh::ping(endpoint, "bench", &settings(), SAMPLES)
            .await
            .expect("the board's processes answer pings");
        percentiles("bare Zenoh round trip (request, reply)", samples);
        return;
    }
    let board = join(endpoint).await;
    match what {
        "expert" => {
            let theory = proclaim_cdl::check_source(THEORY, proclaim_cdl::Language::Dl)
                .theory
                .expect("the microwave theory checks");
            proclaim_experts::ReasonerExpert::new("microwave", theory, &Default::default())
                .run(board)
                .await
        }
        _ => {
            // Counts what reached this process's replica: the last tick's number is how many
            // were posted, and the sink reports how many of them it saw.
            let mut ticks = board.subscribe("tick");
            println!("ready");
            let mut n = 0u64;
            let patience = Duration::from_secs(10);
            while let Ok(Some(tick)) = tokio::time::timeout(patience, ticks.next()).await {
                n += 1;
                if tick.value == proclaim_board::Value::Int(MESSAGES as i64 - 1) {
                    break;
                }
            }
            println!("received {n}");
            println!("dropped {}", board.stats().drops);
        }
    }
}

/// How long each of `SAMPLES` postings of `latency` took to reach this process (the poster's
/// clock and this one are the same machine's).
async fn read_postings(board: Whiteboard, ready: impl FnOnce()) -> Vec<Duration> {
    let mut postings = board.subscribe("latency");
    ready();
    let mut samples = Vec::with_capacity(SAMPLES);
    while samples.len() < SAMPLES {
        let posting = tokio::time::timeout(Duration::from_secs(10), postings.next())
            .await
            .expect("the postings keep coming")
            .expect("the board lives");
        samples.push(board.now().saturating_sub(posting.time));
    }
    samples
}

fn spawn(role: &str, low_latency: bool) -> std::process::Child {
    let mut command = Command::new(std::env::current_exe().unwrap());
    if low_latency {
        command.env("PROCLAIM_BENCH_LOW_LATENCY", "1");
    }
    command
        .env("PROCLAIM_BENCH_ROLE", role)
        .stdout(Stdio::piped())
        .spawn()
        .expect("the bench runs itself")
}

fn percentiles(name: &str, mut samples: Vec<Duration>) -> f64 {
    samples.sort();
    let at = |q: f64| samples[((samples.len() as f64 - 1.0) * q) as usize].as_secs_f64() * 1e6;
    println!(
        "{name:<48} n={:<6} p50 {:>8.1} µs   p90 {:>8.1} µs   p99 {:>8.1} µs",
        samples.len(),
        at(0.5),
        at(0.9),
        at(0.99)
    );
    at(0.5)
}

/// The p50 figure of a line `percentiles` printed.
fn p50_of(line: &str) -> f64 {
    line.split("p50")
        .nth(1)
        .and_then(|rest| rest.split_whitespace().next())
        .and_then(|n| n.parse().ok())
        .expect("a p50 figure")
}

fn free_endpoint() -> String {
    let port = std::net::TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port();
    format!("tcp/127.0.0.1:{port}")
}

async fn parent(low_latency: bool) {
    println!(
        "-- {} transport",
        if low_latency {
            "low-latency"
        } else {
            "default"
        }
    );
    let endpoint = free_endpoint();
    let settings = Settings {
        config_file: None,
        low_latency,
        ..Settings::default()
    };
    let board = whiteboard(&Role::Listen(endpoint.clone()), "bench", &settings)
        .await
        .expect("listens");

    // A posting to a reader in another process, then a bare Zenoh put the same way.
    let mut reader = spawn(&format!("reader {endpoint}"), low_latency);
    let mut out = BufReader::new(reader.stdout.take().unwrap()).lines();
    assert_eq!(out.next().unwrap().unwrap(), "ready");
    tokio::time::sleep(Duration::from_millis(300)).await;
    for i in 0..SAMPLES {
        board.post("bench", "latency", i as i64);
        tokio::time::sleep(Duration::from_micros(500)).await;
    }
    let line = out.next().unwrap().unwrap();
    println!("{line}");
    let posting_p50 = p50_of(&line);
    let _ = reader.wait();
    let bare_endpoint = free_endpoint();
    let bare = proclaim_zenoh::BareSender::listen(&bare_endpoint, "bench", &settings)
        .await
        .expect("listens");
    let mut receiver = spawn(&format!("bare {bare_endpoint}"), low_latency);
    let mut out = BufReader::new(receiver.stdout.take().unwrap()).lines();
    assert_eq!(out.next().unwrap().unwrap(), "ready");
    let deadline = Instant::now() + Duration::from_secs(10);
    while !bare.heard().await {
        assert!(
            Instant::now() < deadline,
            "the bare receiver did not subscribe"
        );
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
    tokio::time::sleep(Duration::from_millis(300)).await;
    for _ in 0..SAMPLES {
        bare.send_now();
        tokio::time::sleep(Duration::from_micros(500)).await;
    }
    let line = out.next().unwrap().unwrap();
    println!("{line}");
    println!(
        "{:<48} {:.2}x the bare put (p50)",
        "posting / bare Zenoh",
        posting_p50 / p50_of(&line)
    );
    let _ = receiver.wait();
    drop(bare);

    let mut expert = spawn(&format!("expert {endpoint}"), low_latency);
    let deadline = Instant::now() + Duration::from_secs(20);
    while !board.registry().answers("cook") {
        assert!(Instant::now() < deadline, "the expert process did not join");
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    board.post("sensors", "doorOpen", false);
    board.post("sensors", "timeLeft", true);
    tokio::time::sleep(Duration::from_millis(200)).await;
    let mut samples = Vec::new();
    for _ in 0..SAMPLES {
        let t = Instant::now();
        let answer = board.query("bench", "cook", Duration::from_secs(1)).await;
        samples.push(t.elapsed());
        assert!(answer.truth(), "{answer:?}");
    }
    let query_p50 = percentiles("query -> reasoner expert in another process", samples);
    let _ = expert.kill();
    let _ = expert.wait();

    let mut pinger = spawn(&format!("ping {endpoint}"), low_latency);
    let line = BufReader::new(pinger.stdout.take().expect("piped"))
        .lines()
        .next()
        .expect("the pinger reports")
        .unwrap();
    println!("{line}");
    let ping_p50 = p50_of(&line);
    println!(
        "{:<48} {:.2}x the bare round trip (p50)",
        "query / bare Zenoh",
        query_p50 / ping_p50
    );
    let _ = pinger.wait();

    // A late joiner catches up with a board of TYPES types.
    for i in 0..TYPES {
        board.post("bench", &format!("type{i}"), i as i64);
    }
    tokio::time::sleep(Duration::from_millis(300)).await;
    let mut joiner = spawn(&format!("joiner {endpoint}"), low_latency);
    let line = BufReader::new(joiner.stdout.take().unwrap())
        .lines()
        .next()
        .expect("the joiner reports")
        .unwrap();
    println!("{line}");
    let _ = joiner.wait();

    let mut sink = spawn(&format!("sink {endpoint}"), low_latency);
    let mut out = BufReader::new(sink.stdout.take().unwrap()).lines();
    assert_eq!(out.next().unwrap().unwrap(), "ready");
    tokio::time::sleep(Duration::from_millis(300)).await;
    let t = Instant::now();
    for i in 0..MESSAGES {
        board.post("bench", "tick", i as i64);
        if i % 1000 == 0 {
            tokio::task::yield_now().await;
        }
    }
    let received = out.next().unwrap().unwrap();
    let elapsed = t.elapsed();
    let dropped = out.next().unwrap().unwrap();
    println!(
        "{:<48} {:.0} messages/s ({received}, {dropped} by its full queue)",
        "one process -> another",
        MESSAGES as f64 / elapsed.as_secs_f64()
    );
    let _ = std::io::stdout().flush();
    let _ = sink.wait();
}
