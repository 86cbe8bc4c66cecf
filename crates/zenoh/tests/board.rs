//! The whiteboard across processes, each process here a Zenoh session of its own in one test
//! process on loopback: joining and its errors, the low-latency transport's limit, a late joiner
//! catching up, a process that goes leaving its types stale, a signal passing to the next claimant.
//! (The root's `network` suite runs `proclaim` processes over Zenoh; its `whiteboard` suite checks
//! every whiteboard semantic over Zenoh too.)

use proclaim_board::{Kind, Value};
use proclaim_zenoh::{whiteboard, Role, Settings};
use std::time::Duration;

/// An endpoint on loopback no one listens on yet.
fn free_endpoint() -> String {
    let port = std::net::TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port();
    format!("tcp/127.0.0.1:{port}")
}

/// Why joining `board` at `endpoint` with default settings fails (it must).
async fn join_error(endpoint: &str, board: &str) -> String {
    whiteboard(&Role::Connect(endpoint.into()), board, &Settings::default())
        .await
        .err()
        .expect("joining fails")
        .to_string()
}

/// How long a test waits for what must come: generous, for a loaded two-core CI machine where
/// Zenoh's links and gossip can take seconds; what never comes still fails.
const PATIENCE: Duration = Duration::from_secs(60);

/// Waits (at most [`PATIENCE`]) until `done` holds.
async fn until(what: &str, done: impl Fn() -> bool) {
    let deadline = std::time::Instant::now() + PATIENCE;
    while !done() {
        assert!(
            std::time::Instant::now() < deadline,
            "not within {PATIENCE:?}: {what}"
        );
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn joining_a_board_nobody_holds_says_so() {
    let endpoint = free_endpoint();
    let error = join_error(&endpoint, "test").await;
    assert!(error.contains(&endpoint), "{error}");
    let error = whiteboard(
        &Role::Listen("127.0.0.1:7447".into()),
        "test",
        &Settings::default(),
    )
    .await
    .err()
    .unwrap();
    assert!(
        matches!(&error, proclaim_zenoh::NetworkError::Endpoint(e) if e == "127.0.0.1:7447"),
        "{error}"
    );
    assert!(error.to_string().contains("write it as tcp/HOST:PORT"));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_low_latency_transport_refuses_what_it_cannot_carry_and_says_why() {
    let endpoint = free_endpoint();
    let settings = Settings {
        config_file: None,
        low_latency: true,
        ..Settings::default()
    };
    let holder = whiteboard(&Role::Listen(endpoint.clone()), "big", &settings)
        .await
        .unwrap();
    let replica = whiteboard(&Role::Connect(endpoint.clone()), "big", &settings)
        .await
        .unwrap();
    // A posting over the limit is not sent (the log says so); the link stays up for the rest.
    replica.post("camera", "image", Value::Bytes(vec![7; 100 * 1024]));
    replica.post("camera", "seen", true);
    let seen = holder.wait_for("seen", 0, PATIENCE).await;
    assert!(seen.is_some(), "the link survived");
    assert!(holder.latest("image").is_none());
    // A late joiner catches up one posting at a time, so a board larger than the limit is
    // joined whole.
    holder.declare("odometry", Kind::Data);
    for i in 0..100 {
        holder.post("walk", "odometry", format!("{i:01000}"));
    }
    let joiner = whiteboard(&Role::Connect(endpoint.clone()), "big", &settings)
        .await
        .expect("joins");
    let oldest = joiner
        .nearest_not_older("odometry", Duration::ZERO)
        .unwrap();
    assert_eq!(oldest.value, Value::from(format!("{:01000}", 0)));
    assert_eq!(
        joiner.latest("odometry").unwrap().value,
        Value::from(format!("{:01000}", 99))
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_late_joiner_gets_the_current_values_from_their_posters() {
    let endpoint = free_endpoint();
    let settings = Settings::default();
    let a = whiteboard(&Role::Listen(endpoint.clone()), "late", &settings)
        .await
        .unwrap();
    let b = whiteboard(&Role::Connect(endpoint.clone()), "late", &settings)
        .await
        .unwrap();
    a.post("vision", "ballSeen", true);
    b.declare("ballDistance", Kind::Data);
    for d in [90i64, 80] {
        b.post("vision", "ballDistance", d);
    }
    b.post("coach", "role", "keeper");
    until("a hears b", || {
        a.latest("role").map(|m| m.value) == Some(Value::from("keeper"))
    })
    .await;
    // The current value of `role` is a's now, so a alone answers for it.
    a.post("coach", "role", "striker");
    until("b hears a", || {
        b.latest("role").map(|m| m.value) == Some(Value::from("striker"))
    })
    .await;
    let mut stale = a.subscribe("*Stale");
    let c = whiteboard(&Role::Connect(endpoint), "late", &settings)
        .await
        .unwrap();
    assert_eq!(c.latest("ballSeen").unwrap().value, Value::Bool(true));
    assert_eq!(c.latest("ballSeen").unwrap().module.as_ref(), "vision");
    assert_eq!(c.kind("ballDistance"), Kind::Data);
    let history: Vec<Value> = [Duration::ZERO, Duration::MAX]
        .into_iter()
        .filter_map(|t| c.nearest("ballDistance", t))
        .map(|m| m.value)
        .collect();
    assert_eq!(history, [Value::Int(90), Value::Int(80)]);
    assert_eq!(c.latest("role").unwrap().value, Value::from("striker"));
    assert_eq!(
        c.snapshot()
            .rows()
            .iter()
            .filter(|r| r.ty == "role")
            .count(),
        1
    );
    // The joiner's arrival turned nothing stale.
    assert!(stale.try_next().is_none());
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_process_that_goes_leaves_its_types_stale_and_nothing_else_stops() {
    let endpoint = free_endpoint();
    let settings = Settings::default();
    let a = whiteboard(&Role::Listen(endpoint.clone()), "stale", &settings)
        .await
        .unwrap();
    let b = whiteboard(&Role::Connect(endpoint.clone()), "stale", &settings)
        .await
        .unwrap();
    let c = whiteboard(&Role::Connect(endpoint), "stale", &settings)
        .await
        .unwrap();
    b.post("vision", "ballSeen", true);
    c.post("gc", "gameState", "playing");
    until("a hears both", || {
        a.latest("ballSeen").is_some() && a.latest("gameState").is_some()
    })
    .await;
    let mut stale = a.subscribe("*Stale");
    drop(b);
    let gone = tokio::time::timeout(PATIENCE, stale.next())
        .await
        .expect("b's going is noticed")
        .unwrap();
    assert_eq!(
        (gone.ty.as_ref(), gone.value.clone()),
        ("ballSeenStale", Value::Bool(true))
    );
    assert!(gone.module.starts_with("gone "), "{gone:?}");
    // The value stays, marked; the types of the living are not stale.
    assert_eq!(a.latest("ballSeen").unwrap().value, Value::Bool(true));
    assert!(a.latest("gameStateStale").is_none());
    // Nothing else stops, and a posting from the living makes the type fresh again.
    c.post("gc", "gameState", "ready");
    c.post("vision2", "ballSeen", false);
    let fresh = tokio::time::timeout(PATIENCE, stale.next())
        .await
        .expect("fresh again")
        .unwrap();
    assert_eq!(
        (fresh.ty.as_ref(), fresh.value.clone()),
        ("ballSeenStale", Value::Bool(false))
    );
    assert_eq!(a.latest("gameState").unwrap().value, Value::from("ready"));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_signal_passes_to_the_next_claimant_when_its_consumer_dies_mid_consume() {
    let endpoint = free_endpoint();
    let settings = Settings::default();
    let ops = whiteboard(&Role::Listen(endpoint.clone()), "signals", &settings)
        .await
        .unwrap();
    let first = whiteboard(&Role::Connect(endpoint.clone()), "signals", &settings)
        .await
        .unwrap();
    let second = whiteboard(&Role::Connect(endpoint), "signals", &settings)
        .await
        .unwrap();
    first.declare("reload", Kind::Signal);
    until("the others know reload is a signal", || {
        ops.kind("reload") == Kind::Signal && second.kind("reload") == Kind::Signal
    })
    .await;
    second.declare("reload", Kind::Signal);
    first.post("first", "alive", true);
    until("the first's heartbeat is heard", || {
        ops.latest("alive").is_some() && second.latest("alive").is_some()
    })
    .await;
    // The earliest claim consumes; the later claimant observes.
    let mut observed = second.subscribe("reload");
    ops.post("ops", "reload", 1i64);
    let got = first.wait_for("reload", 0, PATIENCE).await;
    assert_eq!(got.map(|m| m.value), Some(Value::Int(1)));
    let seen = tokio::time::timeout(PATIENCE, observed.next())
        .await
        .unwrap()
        .unwrap();
    assert_eq!(seen.value, Value::Int(1));
    assert!(
        second.latest("reload").is_none(),
        "observed, not consumable"
    );
    // The consumer dies with a signal it had not read yet: that one goes with it (at most once).
    ops.post("ops", "reload", 2i64);
    tokio::time::timeout(PATIENCE, observed.next())
        .await
        .unwrap()
        .unwrap();
    let mut stale = ops.subscribe("aliveStale");
    let mut second_stale = second.subscribe("aliveStale");
    drop(first);
    for s in [&mut stale, &mut second_stale] {
        tokio::time::timeout(PATIENCE, s.next())
            .await
            .expect("the consumer's going is noticed")
            .unwrap();
    }
    // The next claimant consumes from then on, each signal once.
    ops.post("ops", "reload", 3i64);
    let got = second.wait_for("reload", 0, PATIENCE).await;
    assert_eq!(got.map(|m| m.value), Some(Value::Int(3)));
    assert!(second
        .wait_for("reload", 0, Duration::from_millis(200))
        .await
        .is_none());
    assert!(ops.latest("reload").is_none());
}
