//! Whiteboard latency and throughput, in-process: post → subscriber woken, a label query answered
//! by the reasoner expert and by the Prolog expert (SWI-Prolog in a child process, when
//! installed) (percentiles from individual samples), and messages a second fanned out to 10
//! subscribers. Figures, never asserts. `cargo bench --bench board`.

use proclaim_board::Whiteboard;
use proclaim_experts::ReasonerExpert;
mod common;

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
    common::round_trips(&common::oven().await, samples).await
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

/// A two-state machine whose labels the reasoner expert answers: A --cook--> B --light--> A. Each
/// transition is one query answered and one firing; the samples are the times between firings.
async fn query_to_fire(samples: usize, schedule: Schedule) -> Vec<Duration> {
    let board = Whiteboard::local();
    tokio::spawn(
        ReasonerExpert::new("oven", common::microwave(), &Default::default()).run(board.clone()),
    );
    ping_pong(board, samples, schedule).await
}

/// The same machine, its labels answered by the microwave in Prolog (`theories/microwave.pl`)
/// through the Prolog expert: a query is a line to SWI-Prolog and a line back.
async fn prolog_query_to_fire(samples: usize, schedule: Schedule) -> Vec<Duration> {
    let board = Whiteboard::local();
    let kb = proclaim_experts::KnowledgeBase {
        file: "theories/microwave.pl".into(),
        text: include_str!("../theories/microwave.pl").into(),
        time_limit: proclaim_experts::KnowledgeBase::TIME_LIMIT,
    };
    let labels = vec!["cook".to_string(), "light".to_string()];
    let inputs = vec!["doorOpen".to_string(), "timeLeft".to_string()];
    let expert = proclaim_experts::prolog_expert("oven", &kb, labels, inputs);
    // Aborting the task drops the process, which is then killed.
    let task = tokio::spawn(expert.run(board.clone()));
    let out = ping_pong(board, samples, schedule).await;
    task.abort();
    out
}

/// A two-state machine whose labels `cook` and `light` the expert on `board` answers, once the
/// door is shut and there is time left: A --cook--> B --light--> A.
async fn ping_pong(board: Whiteboard, samples: usize, schedule: Schedule) -> Vec<Duration> {
    while board.registry().answerers("cook").is_empty() {
        tokio::task::yield_now().await;
    }
    board.post("sensors", "doorOpen", false);
    board.post("sensors", "timeLeft", true);
    // A process expert answers once it has started: wait for its first answer.
    while !matches!(
        board.query("bench", "cook", Duration::from_secs(5)).await,
        proclaim_board::QueryOutcome::Answered { value: true, .. }
    ) {}
    let machine = proclaim_fsm::import_ta(
        "PingPong",
        "T",
        "0\tcook\t1\n1\tlight\t0\n",
        "A",
        "1\tB|OnEntry /OnExit /\n0\tA|OnEntry /OnExit /\n",
    )
    .machines
    .remove(0);
    firing_intervals(machine, &board, samples, schedule).await
}

/// Runs `machine` on `board` until it has fired `samples + 1` times; the times between its
/// firings, by the machine's own timestamps (events are read in bursts, long after they happen).
async fn firing_intervals(
    machine: proclaim_fsm::Machine,
    board: &Whiteboard,
    samples: usize,
    schedule: Schedule,
) -> Vec<Duration> {
    use proclaim_runner::{Event, Hosts, MachineRunner, Rounds, RunOptions};
    let mut runner = MachineRunner::new(machine, Hosts::default(), RunOptions::default());
    let mut events = runner.events();
    let task = match schedule {
        Schedule::Concurrent => tokio::spawn(runner.run(board.clone())),
        Schedule::Rounds => {
            let rounds = Rounds::new(vec![runner]).run(board.clone());
            tokio::spawn(async move {
                rounds.await;
            })
        }
    };
    let mut last: Option<Duration> = None;
    let mut out = Vec::with_capacity(samples);
    while out.len() < samples {
        if let Some(Event::Fired { at, .. }) = events.recv().await {
            if let Some(before) = last {
                out.push(at - before);
            }
            last = Some(at);
        }
    }
    task.abort();
    out
}

/// 1,000 machines each ringing at 100 Hz (a `timeout(10000)` self-loop, so every ring fires and
/// re-enters).
fn thousand_ringers() -> Vec<proclaim_fsm::Machine> {
    (0..1000)
        .map(|i| {
            proclaim_fsm::import_ta(
                &format!("M{i}"),
                "T",
                "0\ttimeout(10000)\t0\n",
                "A",
                "0\tTick|OnEntry /OnExit /\n",
            )
            .machines
            .remove(0)
        })
        .collect()
}

/// A machine whose labels read only its own variable (`n > 0`): every ring fires, and nothing
/// goes to the whiteboard but the machine's own events. The samples are the times between
/// firings, as for `query_to_fire`; also the queries the board saw (none, if the label is
/// decided on the spot).
async fn variable_to_fire(samples: usize, schedule: Schedule) -> (Vec<Duration>, u64) {
    let machine = proclaim_fsm::parse_machine(
        "v.machine",
        "machine Flip\nstate A {\n entry { int n; n = n + 1; }\n when n > 0 && n % 1 == 0 -> B\n}\nstate B {\n entry { n = n + 1; }\n when n > 0 -> A\n}\n",
    )
    .machines
    .remove(0);
    let board = Whiteboard::local();
    let out = firing_intervals(machine, &board, samples, schedule).await;
    (out, board.stats().queries)
}

/// How the machines of a bench share time.
#[derive(Clone, Copy, PartialEq)]
enum Schedule {
    Rounds,
    Concurrent,
}

impl Schedule {
    fn name(self) -> &'static str {
        match self {
            Schedule::Rounds => "rounds",
            Schedule::Concurrent => "concurrent",
        }
    }
}

/// CPU seconds per wall second while `machines` run for `seconds` (after one to settle).
async fn cores_busy(
    machines: Vec<proclaim_fsm::Machine>,
    seconds: u64,
    schedule: Schedule,
) -> Option<f64> {
    use proclaim_runner::{Hosts, MachineRunner, Rounds, RunOptions, Shared};
    let board = Whiteboard::local();
    let shared = Shared::for_machines(&machines);
    let mut tasks = Vec::new();
    let mut runners = Vec::new();
    for machine in machines {
        let options = RunOptions {
            shared: Some(shared.clone()),
            ..RunOptions::default()
        };
        runners.push(MachineRunner::new(machine, Hosts::default(), options));
    }
    match schedule {
        Schedule::Concurrent => {
            for runner in runners {
                tasks.push(tokio::spawn(runner.run(board.clone())));
            }
        }
        Schedule::Rounds => {
            let rounds = Rounds::new(runners).run(board.clone());
            tasks.push(tokio::spawn(async move {
                rounds.await;
            }));
        }
    }
    tokio::time::sleep(Duration::from_secs(1)).await;
    let cpu = || -> Option<f64> {
        let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
        let fields: Vec<&str> = stat.rsplit(')').next()?.split_whitespace().collect();
        let ticks: f64 =
            fields.get(11)?.parse::<f64>().ok()? + fields.get(12)?.parse::<f64>().ok()?;
        Some(ticks / 100.0)
    };
    let (cpu0, wall0) = (cpu()?, Instant::now());
    tokio::time::sleep(Duration::from_secs(seconds)).await;
    let used = (cpu()? - cpu0) / wall0.elapsed().as_secs_f64();
    for t in tasks {
        t.abort();
    }
    Some(used)
}

/// 1,000 machines each counting in a variable of its own and posting the count at 100 Hz.
fn thousand_counters() -> Vec<proclaim_fsm::Machine> {
    (0..1000)
        .map(|i| {
            let text = format!(
                "machine C{i}\nstate Tick {{\n entry {{ int count; count = count + 1; post(\"Count{i}\", count); }}\n when timeout(10000) -> Tick\n}}\n"
            );
            proclaim_fsm::parse_machine("c.machine", &text)
                .machines
                .remove(0)
        })
        .collect()
}

fn main() {
    let runtime = common::runtime();
    let quick = common::quick();
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
        // The machine-side figures under both schedules, side by side in this one run.
        for schedule in [Schedule::Rounds, Schedule::Concurrent] {
            let name = schedule.name();
            let _ = query_to_fire(200, schedule).await;
            percentiles(
                &format!("label query -> expert -> fire ({name})"),
                query_to_fire(if quick { 500 } else { 20_000 }, schedule).await,
            );
            if proclaim_experts::find_swipl().is_some() {
                let _ = prolog_query_to_fire(200, schedule).await;
                percentiles(
                    &format!("label query -> Prolog -> fire ({name})"),
                    prolog_query_to_fire(if quick { 500 } else { 20_000 }, schedule).await,
                );
            } else {
                println!(
                    "label query -> Prolog expert: skipped, SWI-Prolog (swipl) is not installed"
                );
            }
            let seconds = if quick { 1 } else { 5 };
            if let Some(cores) = cores_busy(thousand_ringers(), seconds, schedule).await {
                println!(
                    "{:<44} {cores:.2} cores busy (CPU seconds per wall second)",
                    format!("1,000 machines ringing at 100 Hz ({name})")
                );
            }
            let _ = variable_to_fire(1_000, schedule).await;
            let (samples, queries) =
                variable_to_fire(if quick { 1_000 } else { 100_000 }, schedule).await;
            percentiles(&format!("label over variables -> fire ({name})"), samples);
            println!("{:<44} {queries} queries to the whiteboard", "");
            if let Some(cores) = cores_busy(thousand_counters(), seconds, schedule).await {
                println!(
                    "{:<44} {cores:.2} cores busy (CPU seconds per wall second)",
                    format!("1,000 counting, posting at 100 Hz ({name})")
                );
            }
        }
    });
}
