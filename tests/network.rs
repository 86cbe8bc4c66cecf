//! The whiteboard across processes over Zenoh (built with `--features zenoh`): the in-process
//! semantics hold between a holder and replicas on real loopback sockets, and a behaviour split
//! over processes runs, loses an expert that dies (its labels time out) and gets it back.
//! Everything is on 127.0.0.1, on free ports, bounded in count and time.

use proclaim_board::{Kind, ModuleDecl, QueryOutcome, Value, Whiteboard};
use proclaim_zenoh::{whiteboard, Role};
use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::time::Duration;

fn free_endpoint() -> String {
    let port = std::net::TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port();
    format!("tcp/127.0.0.1:{port}")
}

/// A holder and `n` replicas of one board.
async fn boards(n: usize) -> (Whiteboard, Vec<Whiteboard>) {
    let endpoint = free_endpoint();
    let holder = whiteboard(&Role::Listen(endpoint.clone()), "test", None)
        .await
        .expect("listens");
    let mut replicas = Vec::new();
    for _ in 0..n {
        replicas.push(
            whiteboard(&Role::Connect(endpoint.clone()), "test", None)
                .await
                .expect("connects"),
        );
    }
    (holder, replicas)
}

/// Polls `check` until it holds, for at most two seconds.
async fn eventually(what: &str, mut check: impl FnMut() -> bool) {
    for _ in 0..200 {
        if check() {
            return;
        }
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
    panic!("{what}: not within 2 s");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn states_data_sequence_numbers_and_the_registry_are_the_same_everywhere() {
    let (holder, replicas) = boards(2).await;
    let (a, b) = (&replicas[0], &replicas[1]);
    a.post("vision", "ballDistance", 250i64);
    let seen = b
        .wait_for("ballDistance", 0, Duration::from_secs(2))
        .await
        .expect("reaches the other replica");
    assert_eq!(seen.value, Value::Int(250));
    assert_eq!(seen.module.as_ref(), "vision");
    let at_holder = holder.latest("ballDistance").unwrap();
    assert_eq!(at_holder.seq, seen.seq, "one numbering for all");

    holder.declare("odometry", Kind::Data);
    for i in 0..3i64 {
        holder.post("walk", "odometry", i);
    }
    eventually("the data history reaches a replica", || {
        a.nearest("odometry", Duration::ZERO)
            .is_some_and(|m| m.value == Value::Int(0))
            && a.latest("odometry")
                .is_some_and(|m| m.value == Value::Int(2))
    })
    .await;

    b.register(ModuleDecl::new("oven").answers(["cook"]));
    eventually("the registry reaches everyone", || {
        holder.registry().answers("cook") && a.registry().answers("cook")
    })
    .await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_signal_is_consumed_once_across_all_processes() {
    let (holder, replicas) = boards(2).await;
    let (owner, other) = (&replicas[0], &replicas[1]);
    // A command posted before its machine declared its name a signal is kept for it.
    holder.post("GameController", "Placer", "On");
    owner.declare("Placer", Kind::Signal);
    eventually("the holder learns who consumes Placer", || {
        holder.kind("Placer") == Kind::Signal && other.kind("Placer") == Kind::Signal
    })
    .await;
    let mut observed = other.subscribe("Placer");
    other.post("GameController", "Placer", "Off");
    let first = owner.wait_for("Placer", 0, Duration::from_secs(2)).await;
    let second = owner.wait_for("Placer", 0, Duration::from_secs(2)).await;
    let got: Vec<Value> = [first, second]
        .into_iter()
        .flatten()
        .map(|m| m.value)
        .collect();
    assert_eq!(got, [Value::from("On"), Value::from("Off")]);
    assert!(owner.latest("Placer").is_none(), "each taken once");
    assert!(
        holder.latest("Placer").is_none(),
        "not here: the owner takes them"
    );
    assert!(other.latest("Placer").is_none(), "nor here");
    // Others still observe it.
    let seen = tokio::time::timeout(Duration::from_secs(2), observed.next())
        .await
        .unwrap()
        .unwrap();
    assert_eq!(seen.value, Value::from("Off"));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_query_is_answered_by_an_expert_in_another_process_or_times_out() {
    let (holder, replicas) = boards(1).await;
    let expert_side = &replicas[0];
    let script = proclaim_experts::parse_script("ready = true\n").unwrap();
    let imp = proclaim_experts::Impersonator::new("testcdl", ["ready"], script);
    tokio::spawn(imp.run(expert_side.clone()));
    eventually("the expert registers", || {
        holder.registry().answers("ready")
    })
    .await;
    match holder
        .query("machine", "ready", Duration::from_secs(2))
        .await
    {
        QueryOutcome::Answered { value, by, .. } => {
            assert!(value);
            assert_eq!(by.as_ref(), "testcdl");
        }
        other => panic!("{other:?}"),
    }
    // Asked from a replica too.
    assert!(expert_side
        .query("machine", "ready", Duration::from_secs(2))
        .await
        .truth());
    // A registered expert that says nothing: the label times out, counted.
    expert_side.register(ModuleDecl::new("mute").answers(["ghost"]));
    eventually("the mute expert registers", || {
        holder.registry().answers("ghost")
    })
    .await;
    assert_eq!(
        holder
            .query("machine", "ghost", Duration::from_millis(200))
            .await,
        QueryOutcome::TimedOut
    );
    assert_eq!(holder.stats().timeouts, 1);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn joining_a_board_nobody_holds_says_so() {
    let endpoint = free_endpoint();
    let error = whiteboard(&Role::Connect(endpoint.clone()), "test", None)
        .await
        .err()
        .expect("nobody listens there");
    assert!(error.contains(&endpoint), "{error}");
    let error = whiteboard(&Role::Listen("127.0.0.1:7447".into()), "test", None)
        .await
        .err()
        .unwrap();
    assert!(error.contains("write it as tcp/HOST:PORT"), "{error}");
}

/// A child process, killed when dropped.
struct Process(Child);

impl Drop for Process {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn proclaim(args: &[&str]) -> Process {
    Process(
        Command::new(env!("CARGO_BIN_EXE_proclaim"))
            .args(args)
            .env("NO_COLOR", "1")
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("the binary runs"),
    )
}

/// Lines of a child's output, read on a thread so the test can wait with a bound.
fn lines(child: &mut Process) -> std::sync::mpsc::Receiver<String> {
    let (tx, rx) = std::sync::mpsc::channel();
    let out = child.0.stdout.take().unwrap();
    std::thread::spawn(move || {
        for line in BufReader::new(out).lines().map_while(Result::ok) {
            if tx.send(line).is_err() {
                return;
            }
        }
    });
    rx
}

/// Waits (at most `limit`) for a line containing `text`; returns the lines read until then.
fn wait_line(rx: &std::sync::mpsc::Receiver<String>, text: &str, limit: Duration) -> Vec<String> {
    let deadline = std::time::Instant::now() + limit;
    let mut seen = Vec::new();
    while let Some(left) = deadline.checked_duration_since(std::time::Instant::now()) {
        match rx.recv_timeout(left) {
            Ok(line) => {
                let found = line.contains(text);
                seen.push(line);
                if found {
                    return seen;
                }
            }
            Err(_) => break,
        }
    }
    panic!(
        "no line with `{text}` within {limit:?}; read:\n{}",
        seen.join("\n")
    );
}

/// `proclaim run` of a one-machine behaviour (its manifest and the machine the manifest's
/// `file` names) holding the board on a free loopback port: the process, its output, the
/// endpoint.
fn listening(
    tag: &str,
    manifest: &str,
    machine: &str,
) -> (Process, std::sync::mpsc::Receiver<String>, String) {
    let file = manifest
        .split('"')
        .find(|p| p.ends_with(".machine"))
        .expect("the manifest names a .machine file");
    let dir = crate::behaviour_folder(tag, &[("behaviour.toml", manifest), (file, machine)]);
    let endpoint = free_endpoint();
    let mut run = proclaim(&[
        "run",
        dir.to_str().unwrap(),
        "--listen",
        &endpoint,
        "--for",
        "60s",
    ]);
    let trace = lines(&mut run);
    wait_line(&trace, "holding whiteboard", Duration::from_secs(10));
    (run, trace, endpoint)
}

#[test]
fn a_behaviour_split_over_processes_loses_a_dead_expert_and_gets_it_back() {
    let (_run, trace, endpoint) = listening(
        "net",
        "answer_timeout = \"300ms\"\n[[machine]]\nfile = \"Oven.machine\"\n",
        "machine Oven\nstate IDLE {\n  when cook -> COOKING\n}\nstate COOKING {\n  when ~cook -> IDLE\n}\n",
    );
    // Nobody answers `cook` yet.
    wait_line(
        &trace,
        "cook: no expert answers it",
        Duration::from_secs(10),
    );

    let expert = proclaim(&["expert", "microwave", "--connect", &endpoint]);
    let post = |ty: &str, value: &str| {
        let o = Command::new(env!("CARGO_BIN_EXE_proclaim"))
            .args(["post", ty, value, "--connect", &endpoint])
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    };
    wait_line(&trace, "cook = false  (microwave)", Duration::from_secs(10));
    post("doorOpen", "false");
    post("timeLeft", "true");
    wait_line(&trace, "Oven  → COOKING", Duration::from_secs(10));

    // The expert dies: its label times out and the machine goes on.
    drop(expert);
    wait_line(
        &trace,
        "cook: no answer in time, counted false",
        Duration::from_secs(10),
    );
    wait_line(&trace, "Oven  → IDLE", Duration::from_secs(10));
    // It comes back, and is answered again without restarting the machine.
    let _expert = proclaim(&["expert", "microwave", "--connect", &endpoint]);
    wait_line(&trace, "cook = true  (microwave)", Duration::from_secs(10));
    wait_line(&trace, "Oven  → COOKING", Duration::from_secs(10));
}

#[test]
fn post_and_watch_poke_at_a_live_whiteboard() {
    let (_run, trace, endpoint) = listening(
        "watch-net",
        "[[machine]]\nfile = \"M.machine\"\n",
        "machine M\nstate A {\n  when go -> B\n}\nstate B {\n}\n",
    );
    let mut watch = proclaim(&["watch", "go*", "--connect", &endpoint, "--for", "20s"]);
    let watched = lines(&mut watch);
    std::thread::sleep(Duration::from_millis(500));
    let o = Command::new(env!("CARGO_BIN_EXE_proclaim"))
        .args([
            "post",
            "go",
            "true",
            "--connect",
            &endpoint,
            "--module",
            "tester",
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stdout).starts_with("posted go = true (#"));
    let seen = wait_line(&watched, "go = true", Duration::from_secs(10));
    assert!(seen.last().unwrap().contains("tester"), "{seen:?}");
    wait_line(&trace, "M  → B", Duration::from_secs(10));
}
